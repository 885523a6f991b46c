//! Measures of an instantiated structure per level (SPEC §7): area, perimeter of the union, their
//! factors, the box-counting dimension, and the observed holes and components compared with the
//! exact topology.
//!
//! **Exact topology.** A level-i cell edge is *shared* (it separates two cells of level i) or
//! *free* (on the boundary of the union: the outer boundary, a lacuna or a notch). Flags propagate
//! exactly: the edges of the start faces are free unless the assembly glues them; a sub-face's
//! piece of a parent edge inherits the parent edge's flag; its `Ea` edges are shared (with the
//! neighbouring sub-face); its `El` and `Ec` edges are free. Subdividing a level-i cell opens its
//! central lacuna (one hole, if the cell is not delayed) and `n − 1` gaps on each non-delayed `Cn`
//! edge. A gap on a shared edge is seen from both cells: the two halves make one hole. A gap on a
//! free edge opens into the outside or into an existing hole: it is a notch, not a hole. So
//! `holes_i = Σ central lacunas + (interior gap halves)/2`, and since SPEC §5 counts every gap as
//! a half from each side, `N^L_i = holes_i + (free gaps)/2` — both are computed with big integers
//! over the multiset of (type, flags) and checked against each other. The union stays connected:
//! components must be 1.

use crate::geometry::{box_dimension, distance, signed_area, BBox, Fit, Raster};
use crate::instantiate::{GeometryError, Instance};
use lacuna::{counts, EdgeKind};
use num_bigint::BigUint;
use num_rational::BigRational;
use num_traits::{ToPrimitive, Zero};
use serde::Serialize;
use std::collections::BTreeMap;

/// Serialises an exact number as a JSON string.
fn ser_display<T: std::fmt::Display, S: serde::Serializer>(v: &T, s: S) -> Result<S::Ok, S::Error> {
    s.collect_str(v)
}

/// The exact topology at one level.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct ExactTopology {
    /// The level i.
    pub level: u32,
    /// N^C_i.
    #[serde(serialize_with = "ser_display")]
    pub faces: BigUint,
    /// N^L_i of SPEC §5.
    #[serde(serialize_with = "ser_display")]
    pub lacunas: BigRational,
    /// Holes of the union of the level-i cells (bounded components of its complement).
    #[serde(serialize_with = "ser_display")]
    pub holes: BigUint,
    /// Gaps opened on free edges up to level i (notches: each is half a lacuna in N^L).
    #[serde(serialize_with = "ser_display")]
    pub notches: BigUint,
    /// Components of the union: 1.
    pub components: u32,
}

/// The exact topology for levels 0 to `levels`; also checks `N^L_i = holes_i + notches_i / 2`
/// against [`lacuna::counts`] (the `Err` names the first level where it fails).
pub fn exact_topology(inst: &Instance, levels: u32) -> Result<Vec<ExactTopology>, String> {
    let ts = &inst.types;
    let mut states: BTreeMap<(usize, Vec<bool>), BigUint> = BTreeMap::new();
    for s in &inst.start {
        *states.entry((s.ty, s.free.clone())).or_default() += 1u32;
    }
    let reference = counts(ts, levels as u64);
    let (mut centre, mut interior_halves, mut notches) =
        (BigUint::zero(), BigUint::zero(), BigUint::zero());
    let mut out = Vec::new();
    for level in 0..=levels {
        let holes = &centre + &interior_halves / 2u32;
        let lc = &reference[level as usize];
        let lacunas = BigRational::from_integer(holes.clone().into())
            + BigRational::new(notches.clone().into(), 2.into());
        if lacunas != lc.lacunas || &interior_halves % 2u32 != BigUint::zero() {
            return Err(format!(
                "level {level}: holes {holes} + notches {notches}/2 ≠ N^L = {}",
                lc.lacunas
            ));
        }
        out.push(ExactTopology {
            level,
            faces: lc.faces.clone(),
            lacunas,
            holes,
            notches: notches.clone(),
            components: 1,
        });
        if level == levels {
            break;
        }
        let mut next: BTreeMap<(usize, Vec<bool>), BigUint> = BTreeMap::new();
        for ((t, free), c) in &states {
            let face = &ts.types[*t].face;
            if face.delay == 1 {
                centre += c;
            }
            for (i, e) in face.boundary.iter().enumerate() {
                if e.kind == EdgeKind::C && !e.is_delayed() {
                    let gaps = c * (e.n - 1);
                    if free[i] {
                        notches += gaps;
                    } else {
                        interior_halves += gaps;
                    }
                }
            }
            for (k, &w) in ts.types[*t].children.iter().enumerate() {
                *next.entry((w, inst.child_free(*t, k, free))).or_default() += c;
            }
        }
        states = next;
    }
    Ok(out)
}

/// What to measure.
#[derive(Clone, Debug)]
pub struct MeasureOptions {
    /// The deepest level.
    pub level: u32,
    /// Raster size for holes, components and box counting (a power of two).
    pub raster: usize,
    /// Smallest box-counting level k (boxes of side 2^-k of the window).
    pub box_min: u32,
    /// Segments per Bézier edge when flattening.
    pub segments: usize,
}

impl Default for MeasureOptions {
    fn default() -> Self {
        MeasureOptions {
            level: 3,
            raster: 2048,
            box_min: 4,
            segments: 4,
        }
    }
}

/// The measures of one level.
#[derive(Clone, Debug, Serialize)]
pub struct LevelMeasure {
    /// The level i.
    pub level: u32,
    /// Number of cells visited (must be N^C_i).
    pub cells: u64,
    /// A_i: the sum of the cell areas (cells do not overlap).
    pub area: f64,
    /// P_i: the length of the free edges (the perimeter of the union; shared edges cancel).
    pub perimeter: f64,
    /// Holes counted on the raster.
    pub holes: usize,
    /// Components counted on the raster.
    pub components: usize,
    /// The exact topology it is compared with.
    pub exact: ExactTopology,
    /// Whether holes and components match the exact counts.
    pub matches: bool,
}

/// The measures of an instance (`lacuna measure --json`).
#[derive(Clone, Debug, Serialize)]
pub struct MeasureReport {
    /// The input.
    pub name: String,
    /// The deepest level.
    pub level: u32,
    /// A at the deepest level.
    pub area: f64,
    /// P at the deepest level.
    pub perimeter: f64,
    /// Observed holes at the deepest level.
    pub holes: usize,
    /// Observed components at the deepest level.
    pub components: usize,
    /// Box-counting dimension of the deepest level (least-squares slope).
    pub box_dimension: f64,
    /// The fit of log N against log 2^k (slope, intercept, RMS residual).
    pub box_fit: Fit,
    /// (k, N(k)) for boxes of side 2^-k of the window.
    pub box_counts: Vec<(u32, u64)>,
    /// F_A = exp(slope of ln(A_i/A_0) against i).
    pub area_factor: f64,
    /// F_P = exp(slope of ln(P_i/P_0) against i).
    pub perimeter_factor: f64,
    /// The fit of ln(A_i/A_0) against i.
    pub area_fit: Fit,
    /// The fit of ln(P_i/P_0) against i.
    pub perimeter_fit: Fit,
    /// Per level.
    pub levels: Vec<LevelMeasure>,
    /// Raster size used.
    pub raster: usize,
    /// RMS distance of the chosen control points to the template (instantiation quality).
    pub template_residual: f64,
    /// Every level's holes and components match the exact counts.
    pub verified: bool,
    /// One line per mismatch.
    pub failures: Vec<String>,
}

/// The bounding box of the level-0 faces (every cell lies inside them).
pub fn bounds(inst: &Instance, segments: usize) -> BBox {
    let mut bb = BBox::empty();
    inst.walk(0, false, |c| {
        for p in inst.cell_polygon(c.ty, c.points, segments) {
            bb.add(p);
        }
    });
    bb
}

/// Rasterises the cells of one level.
pub fn rasterize(inst: &Instance, level: u32, size: usize, segments: usize) -> Raster {
    let mut r = Raster::fitting(bounds(inst, segments), size, (size / 64).max(2));
    inst.walk(level, false, |c| {
        r.fill_polygon(&inst.cell_polygon(c.ty, c.points, segments));
    });
    r
}

/// Refuses a level whose exact number of cells N^C exceeds `limit`.
pub fn check_cells(inst: &Instance, level: u32, limit: u64) -> Result<(), GeometryError> {
    let c = counts(&inst.types, level as u64);
    let n = &c[level as usize].faces;
    if n > &BigUint::from(limit) {
        return Err(GeometryError::TooManyCells {
            level,
            cells: n.to_string(),
            limit,
        });
    }
    Ok(())
}

/// Measures an instance at every level up to `opts.level`.
pub fn measure(inst: &Instance, opts: &MeasureOptions) -> Result<MeasureReport, GeometryError> {
    let exact = exact_topology(inst, opts.level).map_err(GeometryError::Topology)?;
    let n = opts.level as usize + 1;
    let (mut area, mut perim, mut cells) = (vec![0.0; n], vec![0.0; n], vec![0u64; n]);
    inst.walk(opts.level, true, |c| {
        let d = c.depth as usize;
        cells[d] += 1;
        area[d] += signed_area(&inst.cell_polygon(c.ty, c.points, opts.segments)).abs();
        for (e, &free) in c.free.iter().enumerate() {
            if free {
                let pl = inst.edge_polyline(c.ty, e, c.points, opts.segments);
                perim[d] += pl.windows(2).map(|w| distance(w[0], w[1])).sum::<f64>();
            }
        }
    });
    let mut levels = Vec::new();
    let mut failures = Vec::new();
    let mut last = None;
    for i in 0..n {
        let r = rasterize(inst, i as u32, opts.raster, opts.segments);
        let (components, holes) = r.components_and_holes();
        let ex = exact[i].clone();
        let matches = BigUint::from(holes) == ex.holes && components == 1;
        if !matches {
            failures.push(format!(
                "level {i}: observed {holes} holes and {components} components, exact {} holes and 1 component",
                ex.holes
            ));
        }
        if ex.faces.to_u64() != Some(cells[i]) {
            failures.push(format!(
                "level {i}: {} cells evaluated, N^C = {}",
                cells[i], ex.faces
            ));
        }
        levels.push(LevelMeasure {
            level: i as u32,
            cells: cells[i],
            area: area[i],
            perimeter: perim[i],
            holes,
            components,
            exact: ex,
            matches,
        });
        last = Some(r);
    }
    let r = last.expect("at least level 0");
    let box_counts = r.box_counts(opts.box_min);
    let box_fit = box_dimension(&r, opts.box_min);
    let log_fit = |v: &[f64]| {
        let data: Vec<(f64, f64)> = v
            .iter()
            .enumerate()
            .map(|(i, x)| (i as f64, (x / v[0]).ln()))
            .collect();
        crate::geometry::fit_line(&data)
    };
    let (area_fit, perimeter_fit) = (log_fit(&area), log_fit(&perim));
    let top = &levels[n - 1];
    Ok(MeasureReport {
        name: inst.name.clone(),
        level: opts.level,
        area: top.area,
        perimeter: top.perimeter,
        holes: top.holes,
        components: top.components,
        box_dimension: box_fit.slope,
        box_fit,
        box_counts,
        area_factor: area_fit.slope.exp(),
        perimeter_factor: perimeter_fit.slope.exp(),
        area_fit,
        perimeter_fit,
        raster: opts.raster,
        template_residual: inst.fit_residual,
        verified: failures.is_empty(),
        failures,
        levels,
    })
}
