//! The printability report (THEORY §11): the smallest hole and the thinnest ligament at level n, in
//! millimetres, against a printer resolution (the smallest feature it prints).
//!
//! Both are measured on the material as a printer sees it, the union of the level-n cells
//! ([`super::feature`], GEOMETRY §5): the smallest hole is the least width `2r` such that dilating
//! the material by `r` closes a hole (twice the largest inscribed radius, within
//! [`super::feature::HOLE_TOLERANCE`] on the flattened polygons); the thinnest ligament is the
//! least `2r` such that eroding it by `r` changes its topology (an estimate: polygon offsets and a
//! bisection). Both are floating point and decide a warning, or with `--strict` a failure (E1042),
//! never a topological verdict.

use super::below::{bounds, Instance};
use super::feature::{
    material, smallest_hole, thinnest_ligament, HOLE_TOLERANCE, LIGAMENT_TOLERANCE,
};
use super::{MeshError, Size};
use serde::Serialize;

/// The smallest features of a level, in millimetres.
#[derive(Clone, Debug, Serialize)]
pub struct Printability {
    /// The level.
    pub level: u32,
    /// Millimetres per unit of the plane (`--width` over the x extent of the level-0 faces).
    pub scale: f64,
    /// The smallest hole's width: twice the largest inscribed radius of the narrowest hole, the
    /// low end of a bracket of width `2·HOLE_TOLERANCE` (none when there is no hole).
    pub smallest_hole_mm: Option<f64>,
    /// The thinnest ligament: the least `2r` seen to change the material's topology under
    /// erosion by `r` (an estimate, within `2·LIGAMENT_TOLERANCE` of the bisection; none when
    /// there is no material or the cells overlap).
    pub thinnest_ligament_mm: Option<f64>,
    /// Why the features were not measured (the cells of the level overlap), if so.
    pub not_measured: Option<String>,
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
    let mut p = Printability {
        level,
        scale,
        smallest_hole_mm: None,
        thinnest_ligament_mm: None,
        not_measured: None,
        resolution_mm: resolution,
    };
    match super::outline::outline(inst, level, segments, size) {
        Ok(o) => {
            let m = material(&o);
            p.smallest_hole_mm = smallest_hole(&m).map(|h| h.0);
            p.thinnest_ligament_mm = thinnest_ligament(&m).map(|l| l.1);
        }
        // The mesh build refuses such a level with the same error; the measure command still
        // reports the rest.
        Err(e) => p.not_measured = Some(e.to_string()),
    }
    Ok(p)
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
        if let Some(l) = self.thinnest_ligament_mm {
            if l < self.resolution_mm {
                v.push(format!(
                    "E1042 level {}: the thinnest ligament is {l:.3} mm, below the resolution {} mm",
                    self.level, self.resolution_mm
                ));
            }
        }
        v
    }

    /// The report: sizes, and a warning per feature below the resolution.
    pub fn text(&self) -> String {
        let mut s = match &self.not_measured {
            Some(why) => format!(
                "printability at level {} ({:.4} mm per unit): not measured ({why}), resolution {} mm\n",
                self.level, self.scale, self.resolution_mm
            ),
            None => format!(
                "printability at level {} ({:.4} mm per unit): smallest hole {} (inscribed disc, ±{} mm), thinnest ligament {} (estimate by erosion, ±{} mm), resolution {} mm\n",
                self.level,
                self.scale,
                self.smallest_hole_mm
                    .map_or("none".to_string(), |h| format!("{h:.3} mm")),
                2.0 * HOLE_TOLERANCE,
                self.thinnest_ligament_mm
                    .map_or("none".to_string(), |l| format!("{l:.3} mm")),
                2.0 * LIGAMENT_TOLERANCE,
                self.resolution_mm
            ),
        };
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
