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
    /// The plate's extent: x, y (the level's cells at the scale) and z (the thickness), mm.
    pub extent_mm: [f64; 3],
    /// The area of the material (the union of the level's cells), mm²: what rests on the bed.
    pub material_mm2: Option<f64>,
}

/// How far a figure of [`PrintReport`] can be trusted.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum FigureKind {
    /// Exact by construction (the plate's thickness, a flat plate's overhang).
    Exact,
    /// Within a stated bracket of the true value on the flattened polygons.
    Bracket,
    /// A proved lower bound (the wall thickness of a volume).
    LowerBound,
    /// An estimate (erosion by bisection, the least over sampled layers).
    Estimate,
}

/// The printability of a printed object in one shape for faces and volumes (`measure --json`,
/// `printability`): every figure in mm with what kind of figure it is, the extent against the
/// build volume, the overhang as built, and the features below the resolution.
#[derive(Clone, Debug, Serialize)]
pub struct PrintReport {
    /// The level.
    pub level: u32,
    /// The printer resolution compared with, mm.
    pub resolution_mm: f64,
    /// The smallest hole's width, mm.
    pub smallest_hole_mm: Option<f64>,
    /// The thinnest ligament, mm.
    pub thinnest_ligament_mm: Option<f64>,
    /// The wall thickness, mm.
    pub wall_thickness_mm: Option<f64>,
    /// What kind of figure each of the three is, and how close (`smallest_hole`,
    /// `thinnest_ligament`, `wall_thickness`).
    pub kinds: std::collections::BTreeMap<&'static str, (FigureKind, String)>,
    /// The extent along x, y, z as written (z up), mm.
    pub extent_mm: [f64; 3],
    /// The build volume compared with (`--bed`), mm.
    pub bed_mm: [f64; 3],
    /// Whether the extent fits the build volume.
    pub fits_bed: bool,
    /// The overhang beyond 45° as built (z up), mm² ([`crate::mesh::orient`]).
    pub overhang_mm2: Option<f64>,
    /// The area resting on the bed as built, mm².
    pub bed_contact_mm2: Option<f64>,
    /// The largest bridge as built, mm ([`crate::mesh::orient::largest_bridge`], an estimate);
    /// none when nothing overhangs.
    pub largest_bridge_mm: Option<f64>,
    /// The features below the resolution, in words.
    pub below_resolution: Vec<String>,
    /// Why the features were not measured, if so.
    pub not_measured: Option<String>,
}

impl PrintReport {
    /// The report of a flat plate (a face structure extruded to its thickness).
    pub fn of_plate(p: &Printability, bed: [f64; 3]) -> PrintReport {
        let mut kinds = std::collections::BTreeMap::new();
        kinds.insert(
            "smallest_hole",
            (
                FigureKind::Bracket,
                format!(
                    "twice the largest inscribed radius, within {} mm",
                    2.0 * HOLE_TOLERANCE
                ),
            ),
        );
        kinds.insert(
            "thinnest_ligament",
            (
                FigureKind::Estimate,
                format!("erosion by bisection, ±{} mm", 2.0 * LIGAMENT_TOLERANCE),
            ),
        );
        kinds.insert(
            "wall_thickness",
            (
                FigureKind::Exact,
                "the plate's thickness (its widths in the plane are the ligaments)".into(),
            ),
        );
        PrintReport {
            level: p.level,
            resolution_mm: p.resolution_mm,
            smallest_hole_mm: p.smallest_hole_mm,
            thinnest_ligament_mm: p.thinnest_ligament_mm,
            wall_thickness_mm: Some(p.extent_mm[2]),
            kinds,
            extent_mm: p.extent_mm,
            bed_mm: bed,
            fits_bed: (0..3).all(|k| p.extent_mm[k] <= bed[k]),
            // Vertical walls and a flat bottom on the bed: nothing overhangs, the material rests.
            overhang_mm2: p.material_mm2.map(|_| 0.0),
            bed_contact_mm2: p.material_mm2,
            largest_bridge_mm: None,
            below_resolution: p.below(),
            not_measured: p.not_measured.clone(),
        }
    }
}

/// What [`PrintReport::of_solid`] reads of a checked 3D solid (a volume's, or an automaton's
/// thickened shell).
pub struct SolidFigures<'a> {
    /// The level.
    pub level: u32,
    /// The printer resolution compared with, mm.
    pub resolution: f64,
    /// The build volume, mm.
    pub bed: [f64; 3],
    /// The extent along x, y, z as written, mm.
    pub extent_mm: [f64; 3],
    /// The wall-thickness lower bound ([`super::wall::wall_bound`]), mm.
    pub wall_bound_mm: Option<f64>,
    /// The horizontal layers measured ([`super::slice::layer_features`]).
    pub layers: &'a super::slice::LayerFeatures,
}

impl SolidFigures<'_> {
    /// The features below the resolution, in words: the layers' and the wall bound's.
    pub fn below(&self) -> Vec<String> {
        let resolution = self.resolution;
        let mut out = self.layers.below(resolution);
        if let Some(l) = self.wall_bound_mm.filter(|&l| l < resolution) {
            out.push(format!(
                "the wall thickness bound ({l:.3} mm: two facing walls that close) is below the resolution {resolution} mm"
            ));
        }
        out
    }
}

impl PrintReport {
    /// The report of a checked 3D solid: the smallest hole and the thinnest ligament of its
    /// horizontal layers (estimates), the wall thickness (a lower bound), the overhang and the
    /// largest bridge of `parts` as built (z up).
    pub fn of_solid(parts: &[super::solid::Part], f: SolidFigures) -> PrintReport {
        let mut kinds = std::collections::BTreeMap::new();
        let n = f.layers.layers;
        kinds.insert(
            "smallest_hole",
            (
                FigureKind::Estimate,
                format!(
                    "the narrowest hole of {n} horizontal layers (each twice its largest inscribed radius, within {} mm); the layers between are not seen",
                    2.0 * HOLE_TOLERANCE
                ),
            ),
        );
        kinds.insert(
            "thinnest_ligament",
            (
                FigureKind::Estimate,
                format!(
                    "the thinnest ligament of {n} horizontal layers (erosion by bisection, ±{} mm); the layers between are not seen",
                    2.0 * LIGAMENT_TOLERANCE
                ),
            ),
        );
        kinds.insert(
            "wall_thickness",
            (
                FigureKind::LowerBound,
                "the least distance of two facing triangles with material between them".into(),
            ),
        );
        let (o, _) = super::orient::overhangs(parts);
        PrintReport {
            level: f.level,
            resolution_mm: f.resolution,
            smallest_hole_mm: f.layers.smallest_hole.map(|h| h.0),
            thinnest_ligament_mm: f.layers.thinnest_ligament.map(|l| l.0),
            wall_thickness_mm: f.wall_bound_mm,
            kinds,
            extent_mm: f.extent_mm,
            bed_mm: f.bed,
            fits_bed: (0..3).all(|k| f.extent_mm[k] <= f.bed[k]),
            overhang_mm2: o.first().map(|x| x.overhang_mm2),
            bed_contact_mm2: o.first().map(|x| x.bed_contact_mm2),
            largest_bridge_mm: super::orient::largest_bridge(parts),
            below_resolution: f.below(),
            not_measured: None,
        }
    }
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
        extent_mm: [
            size.width,
            (bb.max[1] - bb.min[1]).max(0.0) * scale,
            size.thickness,
        ],
        material_mm2: None,
    };
    match super::outline::outline(inst, level, segments, size) {
        Ok(o) => {
            let m = material(&o);
            p.material_mm2 = Some(area(&m));
            p.smallest_hole_mm = smallest_hole(&m).map(|h| h.0);
            p.thinnest_ligament_mm = thinnest_ligament(&m).map(|l| l.1);
        }
        // The mesh build refuses such a level with the same error; the measure command still
        // reports the rest.
        Err(e) => p.not_measured = Some(e.to_string()),
    }
    Ok(p)
}

/// The area of shapes (an outer contour and its holes each), mm².
fn area(m: &super::feature::Shapes) -> f64 {
    let ring = |c: &Vec<super::feature::P2>| {
        let n = c.len();
        (0..n)
            .map(|i| c[i][0] * c[(i + 1) % n][1] - c[(i + 1) % n][0] * c[i][1])
            .sum::<f64>()
            .abs()
            / 2.0
    };
    m.iter()
        .map(|shape| match shape.split_first() {
            Some((outer, holes)) => ring(outer) - holes.iter().map(ring).sum::<f64>(),
            None => 0.0,
        })
        .sum()
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
    pub printability: &'a PrintReport,
}
