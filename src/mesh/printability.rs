//! The printability report (THEORY §11): the smallest hole and the thinnest ligament at level n, in
//! millimetres, against a printer resolution (the smallest feature it prints).
//!
//! Both are sizes in the sense of `crate::hole::polygon_size`, `2·area / perimeter` (the inradius
//! of a triangle or a regular polygon, the width of a thin strip): the smallest hole is the one of
//! `crate::hole::smallest_holes` at the level; the thinnest ligament is the smallest size of a
//! level-n cell (every piece of material is made of cells, and a cell joined to its neighbours is
//! only wider). Both are floating-point estimates that decide a warning, or with `--strict` a
//! failure (E1042), never a topological verdict.

use super::below::{bounds, polygon_size, smallest_holes, Instance, Point};
use super::{MeshError, Size};
use serde::Serialize;

/// The smallest features of a level, in millimetres.
#[derive(Clone, Debug, Serialize)]
pub struct Printability {
    /// The level.
    pub level: u32,
    /// Millimetres per unit of the plane (`--width` over the x extent of the level-0 faces).
    pub scale: f64,
    /// The smallest hole (none before the first subdivision).
    pub smallest_hole_mm: Option<f64>,
    /// The thinnest ligament (the smallest cell).
    pub thinnest_ligament_mm: f64,
    /// The printer resolution compared with.
    pub resolution_mm: f64,
}

/// Measures the smallest hole and the thinnest ligament of `level` at the size `size.width`.
pub fn printability(
    inst: &Instance,
    level: u32,
    segments: usize,
    size: Size,
    resolution: f64,
) -> Result<Printability, MeshError> {
    super::check_size("--width", size.width)?;
    super::check_size("--resolution", resolution)?;
    let bb = bounds(inst, segments);
    let extent = bb.max[0] - bb.min[0];
    let scale = size.width / if extent > 0.0 { extent } else { 1.0 };
    let hole = smallest_holes(inst, level, segments)[level as usize];
    let mut thinnest = f64::INFINITY;
    inst.walk(level, false, |c| {
        let poly: Vec<Point> = inst.cell_polygon(c.ty, c.points, segments);
        thinnest = thinnest.min(polygon_size(&poly));
    });
    Ok(Printability {
        level,
        scale,
        smallest_hole_mm: hole.map(|h| h * scale),
        thinnest_ligament_mm: thinnest * scale,
        resolution_mm: resolution,
    })
}

impl Printability {
    /// The features below the resolution, one line each starting with E1042.
    pub fn below(&self) -> Vec<String> {
        let mut v = Vec::new();
        if let Some(h) = self.smallest_hole_mm {
            if h < self.resolution_mm {
                v.push(format!(
                    "E1042 level {}: the smallest hole is {h:.3} mm, below the resolution {} mm",
                    self.level, self.resolution_mm
                ));
            }
        }
        if self.thinnest_ligament_mm < self.resolution_mm {
            v.push(format!(
                "E1042 level {}: the thinnest ligament is {:.3} mm, below the resolution {} mm",
                self.level, self.thinnest_ligament_mm, self.resolution_mm
            ));
        }
        v
    }

    /// The report: sizes, and a warning per feature below the resolution.
    pub fn text(&self) -> String {
        let mut s = format!(
            "printability at level {} ({:.4} mm per unit): smallest hole {}, thinnest ligament {:.3} mm, resolution {} mm\n",
            self.level,
            self.scale,
            self.smallest_hole_mm
                .map_or("none".to_string(), |h| format!("{h:.3} mm")),
            self.thinnest_ligament_mm,
            self.resolution_mm
        );
        for b in self.below() {
            s += &format!("warning: {b}\n");
        }
        s
    }

    /// With `strict`, a failure when a feature is below the resolution.
    pub fn enforce(&self, strict: bool) -> Result<(), MeshError> {
        let below = self.below();
        if strict && !below.is_empty() {
            return Err(MeshError::Resolution(below.join("; ")));
        }
        Ok(())
    }
}

/// A report with the printability added as one more field (`measure --json`), keeping the
/// report's own fields first and in their order.
#[derive(Serialize)]
pub struct WithPrintability<'a, T: Serialize> {
    /// The report.
    #[serde(flatten)]
    pub report: &'a T,
    /// The printability at its level.
    pub printability: &'a Printability,
}
