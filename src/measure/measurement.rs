//! Measures of an instantiated structure per level (THEORY §7): area, perimeter of the union, their
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
//! `holes_i = Σ central lacunas + (interior gap halves)/2`, and since THEORY §5 counts every gap as
//! a half from each side, `N^L_i = holes_i + (free gaps)/2` — both are computed with big integers
//! over the multiset of (type, flags) and checked against each other. The number of components
//! is derived exactly in [`crate::topology::component`] (by induction on the levels, or by union-find over
//! the cells).
//!
//! **Resolution.** Each level is rasterised fine enough that its smallest hole (computed from the
//! cells, [`crate::measure::hole`]) is at least [`MIN_HOLE_WIDTH`] pixels wide, up to
//! [`MeasureOptions::max_raster`]; a level whose smallest hole stays below that is a failure
//! (E1011), never a silently different count. A mismatch of observed and exact counts is E1010.

use crate::geometry::point::{distance, fit_line, signed_area, Fit};
use crate::geometry::raster::{bounds, cell_count, rasterize};
use crate::geometry::{instantiate::Instance, options::GeometryError};
use crate::measure::density::{density_map, DensitySummary, DEFAULT_GRID};
use crate::measure::hole::smallest_holes;
use crate::progress::Progress;
use crate::topology::component::{components_by_cells, components_by_induction};
use crate::{topology::counts, topology::EdgeKind};
use num_bigint::BigUint;
use num_rational::BigRational;
use num_traits::{ToPrimitive, Zero};
use serde::Serialize;
use std::collections::BTreeMap;

/// The exact topology at one level.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct ExactTopology {
    /// The level i.
    pub level: u32,
    /// N^C_i.
    #[serde(serialize_with = "crate::topology::closure::ser_display")]
    pub faces: BigUint,
    /// N^L_i of THEORY §5.
    #[serde(serialize_with = "crate::topology::closure::ser_display")]
    pub lacunas: BigRational,
    /// Holes of the union of the level-i cells (bounded components of its complement).
    #[serde(serialize_with = "crate::topology::closure::ser_display")]
    pub holes: BigUint,
    /// Gaps opened on free edges up to level i (notches: each is half a lacuna in N^L).
    #[serde(serialize_with = "crate::topology::closure::ser_display")]
    pub notches: BigUint,
    /// Components of the union (cells joined by shared edges; [`crate::topology::component`]).
    pub components: u64,
}

/// Above this many cells the union-find fallback of [`exact_components`] is not run.
pub const UNION_FIND_CELLS: usize = 2_000_000;

/// The exact number of components at levels 0 to `levels` and how it was derived: by induction
/// when the sub-faces of every type are connected through their spokes (then it is the number of
/// components of the start assembly at every level), else by union-find over the cells of each
/// level (at most [`UNION_FIND_CELLS`]).
pub fn exact_components(inst: &Instance, levels: u32) -> Result<(Vec<u64>, &'static str), String> {
    let n = levels as usize + 1;
    match components_by_induction(&inst.types, &inst.glue) {
        Ok(c) => Ok((vec![c as u64; n], "induction")),
        Err(t) => match components_by_cells(&inst.types, &inst.glue, levels, UNION_FIND_CELLS) {
            Some(Ok(v)) => Ok((v.into_iter().map(|c| c as u64).collect(), "union-find")),
            Some(Err(l)) => Err(format!(
                "level {l}: an edge is shared by more than two cells"
            )),
            None => Err(format!(
                "the sub-faces of T{t} are not connected through spokes and a level up to {levels} has more than {UNION_FIND_CELLS} cells: the components cannot be derived"
            )),
        },
    }
}

/// The exact topology for levels 0 to `levels`; also checks `N^L_i = holes_i + notches_i / 2`
/// against [`crate::topology::counts`] (the `Err` names the first level where it fails).
pub fn exact_topology(inst: &Instance, levels: u32) -> Result<Vec<ExactTopology>, String> {
    let ts = &inst.types;
    let mut states: BTreeMap<(usize, Vec<bool>), BigUint> = BTreeMap::new();
    for s in &inst.start {
        *states.entry((s.ty, s.free.clone())).or_default() += 1u32;
    }
    let reference = counts(ts, levels as u64);
    let (components, _) = exact_components(inst, levels)?;
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
            components: components[level as usize],
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

/// A level's raster is chosen so that its smallest hole is at least this many pixels wide
/// (`2·area/perimeter`, see [`crate::measure::hole`]). For a convex hole that size is between
/// the radius r of its inscribed disk and 2r, so r ≥ 1.5 pixels > √2: the disk holds a 2×2 block
/// of pixel centres, and [`crate::geometry::Raster::components_and_holes`], which counts only
/// uncovered components holding such a block, cannot drop a real hole.
pub const MIN_HOLE_WIDTH: f64 = 3.0;

/// The finest raster `lacuna measure` accepts (`--max-raster`): 16384² pixels.
pub const LARGEST_RASTER: usize = 16_384;

/// What to measure.
#[derive(Clone, Debug)]
pub struct MeasureOptions {
    /// The deepest level.
    pub level: u32,
    /// Raster size for box counting, and the smallest raster for holes and components (a power
    /// of two).
    pub raster: usize,
    /// The largest raster a level may be given to resolve its smallest hole (a power of two).
    pub max_raster: usize,
    /// Smallest box-counting level k (boxes of side 2^-k of the window).
    pub box_min: u32,
    /// Segments per Bézier edge when flattening.
    pub segments: usize,
    /// Blocks per side of the relative-density map of the deepest level (0: none).
    pub density_grid: usize,
}

impl Default for MeasureOptions {
    fn default() -> Self {
        MeasureOptions {
            level: 3,
            raster: 2048,
            max_raster: 8192,
            box_min: 4,
            segments: 4,
            density_grid: DEFAULT_GRID,
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
    /// The raster size used for this level's holes and components.
    pub raster: usize,
    /// Width of the smallest hole in pixels of that raster (`2·area/perimeter`; none without
    /// holes).
    pub smallest_hole_pixels: Option<f64>,
    /// The exact topology it is compared with.
    pub exact: ExactTopology,
    /// Whether the raster was fine enough for the level's smallest hole (else the observed
    /// counts are not trusted: E1011, and no comparison).
    pub resolved: bool,
    /// Whether holes and components were resolved and match the exact counts.
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
    /// How the exact components were derived: `induction` or `union-find`.
    pub components_by: &'static str,
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
    /// The relative-density map of the deepest level (summary; `render --density` writes it).
    pub density: Option<DensitySummary>,
    /// Per level.
    pub levels: Vec<LevelMeasure>,
    /// Raster size for box counting (and the smallest raster of the levels).
    pub raster: usize,
    /// RMS distance of the chosen control points to the template (instantiation quality).
    pub template_residual: f64,
    /// The exact level-1 check of the chosen point: every cell's control polygon has positive
    /// area (issue #36).
    pub level_one: crate::geometry::LevelOne,
    /// Which certificate step proves the exact holes and components, when the caller asked
    /// ([`certification`]: `measure` leaves it, so that callers that only compare counts, such
    /// as `explore`'s holes property, do not build the certificate's rows).
    #[serde(skip_serializing_if = "Certification::not_asked")]
    pub certification: Certification,
    /// Every level's holes and components match the exact counts.
    pub verified: bool,
    /// One line per failure, starting with its code (E1010 mismatch, E1011 below resolution).
    pub failures: Vec<String>,
}

/// The raster size (a power of two, at least `min`) whose window, fitted to a box of side
/// `extent` as in [`crate::geometry::rasterize`], makes a hole of size `hole` at least [`MIN_HOLE_WIDTH`] pixels
/// wide.
pub fn raster_for_hole(extent: f64, hole: f64, min: usize) -> usize {
    let px = MIN_HOLE_WIDTH * extent / hole.max(1e-300);
    let size = (px * 64.0 / 62.0).max(px + 4.0).ceil();
    if !size.is_finite() || size > (1u64 << 40) as f64 {
        return usize::MAX;
    }
    (size as usize).next_power_of_two().max(min)
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
    let (_, components_by) = exact_components(inst, opts.level).map_err(GeometryError::Topology)?;
    let n = opts.level as usize + 1;
    let (mut area, mut perim, mut cells) = (vec![0.0; n], vec![0.0; n], vec![0u64; n]);
    let all: u64 = (0..=opts.level).map(|i| cell_count(inst, i)).sum();
    let mut bar = Progress::new("measure", all);
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
        bar.tick();
    });
    bar.finish();
    let extent = bounds(inst, opts.segments).size();
    let smallest = smallest_holes(inst, opts.level, opts.segments);
    let mut levels = Vec::new();
    let mut failures = Vec::new();
    let mut last = None;
    for i in 0..n {
        let wanted = smallest[i].map_or(opts.raster, |h| raster_for_hole(extent, h, opts.raster));
        let size = wanted.min(opts.max_raster.max(opts.raster));
        let r = rasterize(inst, i as u32, size, opts.segments);
        let hole_px = smallest[i].map(|h| h * r.scale);
        let resolved = wanted <= size;
        if !resolved {
            let needs = if wanted == usize::MAX {
                "more than 2^40".to_string()
            } else {
                wanted.to_string()
            };
            let advice = if wanted <= LARGEST_RASTER {
                format!("raise --max-raster to {wanted} or lower the level")
            } else {
                format!("above the finest raster accepted ({LARGEST_RASTER}): lower the level")
            };
            failures.push(format!(
                "E1011 level {i}: the smallest hole is {:.2} pixels wide at raster {size}, below the resolution of {MIN_HOLE_WIDTH} pixels (it needs a raster of {needs}): {advice}",
                hole_px.unwrap_or(0.0),
            ));
        }
        let (components, holes) = r.components_and_holes();
        let ex = exact[i].clone();
        let equal = BigUint::from(holes) == ex.holes && components as u64 == ex.components;
        // A level below the resolution is E1011 alone: its counts are not compared.
        if resolved && !equal {
            failures.push(format!(
                "E1010 level {i}: observed {holes} holes and {components} components at raster {size}, exact {} holes and {} components",
                ex.holes, ex.components
            ));
        }
        let matches = resolved && equal;
        if ex.faces.to_u64() != Some(cells[i]) {
            failures.push(format!(
                "E1010 level {i}: {} cells evaluated, N^C = {}",
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
            raster: size,
            smallest_hole_pixels: hole_px,
            exact: ex,
            resolved,
            matches,
        });
        last = Some(r);
    }
    let r = last.expect("at least level 0");
    // Box counting from 1/2^box_min down to 1/raster, whatever raster the level needed.
    let k_max = opts.raster.trailing_zeros();
    let box_counts: Vec<(u32, u64)> = r
        .box_counts(opts.box_min)
        .into_iter()
        .filter(|&(k, _)| k <= k_max)
        .collect();
    let box_fit = fit_line(
        &box_counts
            .iter()
            .filter(|&&(_, c)| c > 0)
            .map(|&(k, c)| (f64::from(k) * std::f64::consts::LN_2, (c as f64).ln()))
            .collect::<Vec<_>>(),
    );
    let log_fit = |v: &[f64]| {
        let data: Vec<(f64, f64)> = v
            .iter()
            .enumerate()
            .map(|(i, x)| (i as f64, (x / v[0]).ln()))
            .collect();
        fit_line(&data)
    };
    let (area_fit, perimeter_fit) = (log_fit(&area), log_fit(&perim));
    let top = &levels[n - 1];
    let density = (opts.density_grid > 0).then(|| {
        let mut s = density_map(inst, opts.level, opts.density_grid, opts.segments).summary();
        s.area_fraction = Some(top.area / (extent * extent));
        s
    });
    Ok(MeasureReport {
        name: inst.name.clone(),
        level: opts.level,
        area: top.area,
        perimeter: top.perimeter,
        holes: top.holes,
        components: top.components,
        components_by,
        box_dimension: box_fit.slope,
        box_fit,
        box_counts,
        area_factor: area_fit.slope.exp(),
        perimeter_factor: perimeter_fit.slope.exp(),
        area_fit,
        perimeter_fit,
        density,
        raster: opts.raster,
        template_residual: inst.fit_residual,
        level_one: inst.level_one.clone(),
        certification: Certification::NotAsked,
        verified: failures.is_empty(),
        failures,
        levels,
    })
}

/// Which step of the faces' certificate proves a measure's exact holes and components.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Certification {
    /// Not looked up (the caller did not ask for [`certification`]).
    #[default]
    NotAsked,
    /// The `face-homology` step, from level 0 to `to`.
    FaceHomology {
        /// Its last level.
        to: u64,
    },
    /// No step: a level 0 too large to build, or components lacuna cannot derive within the
    /// step's cell bound.
    NotInCertificate,
}

impl Certification {
    fn not_asked(&self) -> bool {
        *self == Certification::NotAsked
    }
}

/// Which step of `inst`'s certificate proves its exact holes and components: the levels of the
/// rows `certificate_for` puts in the `face-homology` step.
pub fn certification(inst: &Instance) -> Certification {
    match crate::certificate::face_rows(&inst.types, &inst.glue)
        .ok()
        .and_then(|rows| rows.last().map(|r| r.level))
    {
        Some(to) => Certification::FaceHomology { to },
        None => Certification::NotInCertificate,
    }
}

impl MeasureReport {
    /// The human-readable report of `lacuna measure` (without `--json`): a table per level with
    /// the observed and exact holes and components, the factors, the box-counting dimension, the
    /// density summary and the verdict.
    pub fn to_text(&self) -> String {
        use std::fmt::Write;
        let mut s = format!(
            "{} up to level {} (floating point; holes and components compared with the exact counts)\n\n",
            self.name, self.level
        );
        s += "level        cells          area     perimeter  holes (exact)  components (exact)  raster  match\n";
        for l in &self.levels {
            let _ = writeln!(
                s,
                "{:>5} {:>12} {:>13.6} {:>13.6} {:>14} {:>19} {:>7}  {}",
                l.level,
                l.cells,
                l.area,
                l.perimeter,
                format!("{} ({})", l.holes, l.exact.holes),
                format!("{} ({})", l.components, l.exact.components),
                l.raster,
                match (l.resolved, l.matches) {
                    (false, _) => "not resolved (E1011)",
                    (true, true) => "yes",
                    (true, false) => "NO",
                }
            );
        }
        let _ = writeln!(
            s,
            "\nF_A = {:.6} (estimate: fit residual {:.4}), F_P = {:.6} (estimate: fit residual {:.4})",
            self.area_factor,
            self.area_fit.residual,
            self.perimeter_factor,
            self.perimeter_fit.residual
        );
        let _ = writeln!(
            s,
            "box-counting dimension {:.4} (estimate: fit residual {:.4}, boxes 1/{} to 1/{})",
            self.box_dimension,
            self.box_fit.residual,
            self.box_counts.first().map_or(0, |b| 1u64 << b.0),
            self.box_counts.last().map_or(0, |b| 1u64 << b.0),
        );
        if let Some(d) = &self.density {
            let _ = writeln!(
                s,
                "relative density on a {0}×{0} grid: min {1:.4}, mean {2:.4}, max {3:.4}",
                d.grid, d.min, d.mean, d.max
            );
        }
        let _ = writeln!(s, "components derived by {}", self.components_by);
        let _ = writeln!(s, "{}", self.level_one.describe());
        let certified = match self.certification {
            Certification::NotAsked => None,
            Certification::FaceHomology { to } => Some(format!(
                "certified: the exact holes and components by the face-homology step at levels 0–{to}"
            )),
            Certification::NotInCertificate => Some(
                "the exact holes and components derived by lacuna, not in a certificate \
                 (level 0 is beyond the face-homology step's cell bound)"
                    .to_string(),
            ),
        };
        if let Some(c) = certified {
            let _ = writeln!(
                s,
                "{c}; the level-1 line by the level-one step (`--certificate OUT.json` writes them)"
            );
        }
        if self.verified {
            s += "verdict: VERIFIED (observed holes and components equal the exact counts)\n";
        } else {
            s += "verdict: NOT VERIFIED\n";
            for f in &self.failures {
                let _ = writeln!(s, "  {f}");
            }
        }
        s
    }
}
