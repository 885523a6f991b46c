//! Measures of an automaton's attractor, drawn to level n: the total length (polylines and polygon
//! boundaries) and area (polygons) per level, and a box-counting dimension estimate, with the exact
//! similarity dimension where it applies ([`crate::analysis::similarity_dimension`]) and the
//! boundary dimension of each state from the graph of neighbour maps
//! ([`crate::analysis::boundary_dimension`], an upper bound). Floats measure; they decide nothing.

use crate::analysis::{BoundaryDimension, ContractionReport, ResolveVerdict, SimilarityDimension};
use crate::geometry::{fit_line, Evaluator, Shape, ShapeKind};
use serde::Serialize;
use std::collections::HashSet;

/// Length and area of one level.
#[derive(Clone, Debug, Serialize)]
pub struct AutomatonLevel {
    /// The level.
    pub level: u32,
    /// Pieces drawn.
    pub pieces: u128,
    /// Total length of polylines and polygon boundaries.
    pub length: f64,
    /// Total area of polygons (each counted once, overlaps included).
    pub area: f64,
}

/// A box-counting estimate: the least-squares slope of `log N(ε)` against `log 1/ε`.
#[derive(Clone, Debug, Serialize)]
pub struct BoxDimension {
    /// The slope, `None` when too few scales are finer than the bounding box and coarser than
    /// the pieces.
    pub value: Option<f64>,
    /// The level whose pieces were counted.
    pub level: u32,
    /// The box sizes `ε = L/2^k` used (k) and the boxes met at each.
    pub counts: Vec<(u32, u64)>,
}

/// Everything `measure` reports for an automaton.
#[derive(Clone, Debug, Serialize)]
pub struct AutomatonMeasure {
    /// The input's name.
    pub input: String,
    /// The modelling space's dimension.
    pub space: usize,
    /// The level asked for.
    pub level: u32,
    /// The solver's verdict with the values chosen.
    pub solver: ResolveVerdict,
    /// The elementary cycles checked for contraction.
    pub contraction: ContractionReport,
    /// Per level, 0 to n.
    pub levels: Vec<AutomatonLevel>,
    /// The box-counting estimate.
    pub box_dimension: BoxDimension,
    /// The exact similarity dimension, where the operators act as similitudes.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub similarity_dimension: Option<SimilarityDimension>,
    /// Why there is no similarity dimension.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub similarity_note: Option<String>,
    /// The boundary dimension of each state (an upper bound), or why it is not decided.
    pub boundary_dimension: BoundaryReport,
    /// The state measured when it is not the start (`measure --state`): the automaton restarted
    /// there, from its frame.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub state: Option<String>,
}

/// The boundary dimension as `measure` reports it: the values, or why there are none.
#[derive(Clone, Debug, Serialize)]
#[serde(untagged)]
pub enum BoundaryReport {
    /// The exact values per state.
    Decided(BoundaryDimension),
    /// The attractors are not tiles, or not known to be (similarity dimension < 2 in the
    /// plane, or the open-set condition not proved): the boundary of a set without interior is
    /// the set itself, and the contact set is not reported.
    NotATile {
        /// Why.
        note: String,
    },
    /// A tile, but no value (limits reached, no neighbour maps, …): never a verdict.
    NotDecided {
        /// The reason.
        note: String,
    },
}

fn dist(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// The area of a polygon in space (half the norm of the sum of fan cross products).
fn polygon_area(p: &[[f64; 3]]) -> f64 {
    let mut s = [0.0; 3];
    for i in 1..p.len().saturating_sub(1) {
        let (u, v) = (
            [p[i][0] - p[0][0], p[i][1] - p[0][1], p[i][2] - p[0][2]],
            [
                p[i + 1][0] - p[0][0],
                p[i + 1][1] - p[0][1],
                p[i + 1][2] - p[0][2],
            ],
        );
        s[0] += u[1] * v[2] - u[2] * v[1];
        s[1] += u[2] * v[0] - u[0] * v[2];
        s[2] += u[0] * v[1] - u[1] * v[0];
    }
    0.5 * (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt()
}

/// Length and area of one shape.
pub fn shape_measure(s: &Shape) -> (f64, f64) {
    let p = &s.points;
    match s.kind {
        ShapeKind::Point => (0.0, 0.0),
        ShapeKind::Polyline => (p.windows(2).map(|w| dist(&w[0], &w[1])).sum(), 0.0),
        ShapeKind::Polygon => {
            let per: f64 = p.windows(2).map(|w| dist(&w[0], &w[1])).sum::<f64>()
                + if p.len() > 1 {
                    dist(&p[p.len() - 1], &p[0])
                } else {
                    0.0
                };
            (per, polygon_area(p))
        }
    }
}

/// Length and area of levels 0 to n.
pub fn level_measures(ev: &Evaluator, level: u32) -> Vec<AutomatonLevel> {
    (0..=level)
        .map(|l| {
            let (mut length, mut area) = (0.0, 0.0);
            ev.walk(l, &mut |q, _, pts| {
                if let Some(s) = ev.shape(q, pts) {
                    let (a, b) = shape_measure(&s);
                    length += a;
                    area += b;
                }
            });
            AutomatonLevel {
                level: l,
                pieces: ev.count(l),
                length,
                area,
            }
        })
        .collect()
}

/// The box-counting estimate from the pieces of level `level`: every piece sampled finer than the
/// finest box (polygons filled), boxes of size `L/2^k` counted for k from 2 up to the finest
/// scale still coarser than twice the largest piece still to be refined (terminal shapes, such as a
/// rule's infertile segments, are exact at every scale; at most 9 in the plane, 7 in space),
/// lowered while the samples of every piece would exceed about 4 million.
pub fn box_dimension(ev: &Evaluator, level: u32) -> BoxDimension {
    let shapes = ev.shapes(level);
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    let mut piece = 0.0f64;
    for s in &shapes {
        let (mut plo, mut phi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for p in &s.points {
            for d in 0..3 {
                lo[d] = lo[d].min(p[d]);
                hi[d] = hi[d].max(p[d]);
                plo[d] = plo[d].min(p[d]);
                phi[d] = phi[d].max(p[d]);
            }
        }
        // Shapes of terminal states are exact parts of the set at every scale: only the pieces
        // still to be refined bound the finest scale.
        if !ev.is_terminal(s.state) {
            piece = piece.max(dist(&plo, &phi));
        }
    }
    let side = (0..3).map(|d| hi[d] - lo[d]).fold(0.0, f64::max);
    let empty = BoxDimension {
        value: None,
        level,
        counts: Vec::new(),
    };
    if shapes.is_empty() || side <= 0.0 || !side.is_finite() {
        return empty;
    }
    let kcap = if ev.space == 3 { 7 } else { 9 };
    let mut kmax = 0u32;
    while kmax < kcap && side / f64::from(1u32 << (kmax + 1)) >= 2.0 * piece {
        kmax += 1;
    }
    // Lower the finest scale until the samples fit the budget (never drop pieces: a count over
    // part of them is no estimate).
    let estimate = |step: f64| -> f64 {
        shapes
            .iter()
            .map(|s| {
                let p = &s.points;
                let per: f64 = p.windows(2).map(|w| dist(&w[0], &w[1])).sum::<f64>()
                    + if s.kind == ShapeKind::Polygon && p.len() > 2 {
                        dist(&p[p.len() - 1], &p[0])
                    } else {
                        0.0
                    };
                let fill = if s.kind == ShapeKind::Polygon {
                    let diam = (1..p.len()).map(|i| dist(&p[0], &p[i])).fold(0.0, f64::max);
                    (p.len().saturating_sub(2)) as f64 * (diam / step + 2.0).powi(2)
                } else {
                    0.0
                };
                per / step + fill + p.len() as f64 + 2.0
            })
            .sum()
    };
    while kmax >= 4 && estimate(side / f64::from(1u32 << kmax) / 3.0) > 4.0e6 {
        kmax -= 1;
    }
    if kmax < 4 {
        return empty;
    }
    let step = side / f64::from(1u32 << kmax) / 3.0;
    // Sample points of every piece at spacing ≤ step.
    let mut samples: Vec<[f64; 3]> = Vec::new();
    let seg = |a: &[f64; 3], b: &[f64; 3], out: &mut Vec<[f64; 3]>| {
        let n = (dist(a, b) / step).ceil().max(1.0) as usize;
        for i in 0..=n {
            let t = i as f64 / n as f64;
            out.push([
                a[0] + t * (b[0] - a[0]),
                a[1] + t * (b[1] - a[1]),
                a[2] + t * (b[2] - a[2]),
            ]);
        }
    };
    for s in &shapes {
        let p = &s.points;
        match s.kind {
            ShapeKind::Point => samples.push(p[0]),
            ShapeKind::Polyline => {
                p.windows(2).for_each(|w| seg(&w[0], &w[1], &mut samples));
                if p.len() == 1 {
                    samples.push(p[0]);
                }
            }
            ShapeKind::Polygon => {
                // Fill: segments from the first point to points along each far edge.
                for i in 1..p.len().saturating_sub(1) {
                    let n = (dist(&p[i], &p[i + 1]) / step).ceil().max(1.0) as usize;
                    for j in 0..=n {
                        let t = j as f64 / n as f64;
                        let e = [
                            p[i][0] + t * (p[i + 1][0] - p[i][0]),
                            p[i][1] + t * (p[i + 1][1] - p[i][1]),
                            p[i][2] + t * (p[i + 1][2] - p[i][2]),
                        ];
                        seg(&p[0], &e, &mut samples);
                    }
                }
                p.windows(2).for_each(|w| seg(&w[0], &w[1], &mut samples));
                if p.len() == 1 {
                    samples.push(p[0]);
                }
            }
        }
    }
    let mut counts = Vec::new();
    for k in 2..=kmax {
        let eps = side / f64::from(1u32 << k);
        let mut set: HashSet<(i64, i64, i64)> = HashSet::new();
        for p in &samples {
            set.insert((
                ((p[0] - lo[0]) / eps).floor() as i64,
                ((p[1] - lo[1]) / eps).floor() as i64,
                ((p[2] - lo[2]) / eps).floor() as i64,
            ));
        }
        counts.push((k, set.len() as u64));
    }
    let mut b = BoxDimension {
        value: None,
        level,
        counts,
    };
    b.value = Some(fit_line(&b.log_points()).slope);
    b
}

impl BoxDimension {
    /// The points of the fit: `(k·ln 2, ln N)` for every count, `k·ln 2 = ln(1/ε) + ln L`.
    pub fn log_points(&self) -> Vec<(f64, f64)> {
        self.counts
            .iter()
            .map(|&(k, n)| (f64::from(k) * std::f64::consts::LN_2, (n as f64).ln()))
            .collect()
    }
}

/// What `verify` and `measure` add to an open-set verdict that lacuna decided without a witness
/// the certificate can carry.
pub const OPEN_SET_NOT_CERTIFIED: &str =
    "; decided by lacuna, not certified: the certificate states an upper bound";

impl AutomatonMeasure {
    /// The human-readable report.
    pub fn to_text(&self) -> String {
        let mut o = format!(
            "{}: automaton in space {}, level {}{}\n",
            self.input,
            self.space,
            self.level,
            match &self.state {
                Some(s) =>
                    format!(", the attractor of state {s} (restarted there, from its frame)"),
                None => String::new(),
            }
        );
        o += &format!(
            "solver ({}): {}\n",
            self.solver.field,
            if self.solver.consistent {
                "every constraint holds"
            } else {
                "CONSTRAINTS FAIL"
            }
        );
        for f in &self.solver.failed {
            o += &format!("  fails: {f}\n");
        }
        for p in &self.solver.applied {
            o += &format!("  parameter {p}\n");
        }
        if !self.solver.free_left.is_empty() {
            o += &format!(
                "  free parameters left at 0: {}\n",
                self.solver.free_left.join(", ")
            );
        }
        o += &self.contraction.text();
        o += "\n";
        o += "level  pieces        length           area\n";
        for l in &self.levels {
            o += &format!(
                "{:>5}  {:>6}  {:>12.6}  {:>13.6}\n",
                l.level, l.pieces, l.length, l.area
            );
        }
        match self.box_dimension.value {
            Some(v) => {
                o += &format!(
                    "box-counting dimension ≈ {v:.4} (level {}, {} scales)\n",
                    self.box_dimension.level,
                    self.box_dimension.counts.len()
                )
            }
            None => o += "box-counting dimension: too few scales (raise --level)\n",
        }
        match (&self.similarity_dimension, &self.similarity_note) {
            (Some(s), _) if s.upper_bound => {
                o += &format!(
                    "similarity dimension = {} = {}… — an upper bound of the dimension only; open-set condition {}\n",
                    s.exact, s.decimal, s.open_set
                )
            }
            (Some(s), _) => {
                o += &format!(
                    "similarity dimension = {} = {}… (the Hausdorff dimension: open-set condition {}{})\n",
                    s.exact,
                    s.decimal,
                    s.open_set,
                    match s.open_set_witnessed() {
                        true => "",
                        false => OPEN_SET_NOT_CERTIFIED,
                    }
                )
            }
            (None, Some(n)) => o += &format!("similarity dimension: not applicable ({n})\n"),
            _ => {}
        }
        match &self.boundary_dimension {
            BoundaryReport::Decided(b) => {
                let per: Vec<String> = b
                    .states
                    .iter()
                    .map(|s| format!("{} ≤ {} = {}…", s.state, s.exact, s.decimal))
                    .collect();
                o += &format!("boundary dimension: {} ({})\n", per.join("; "), b.note);
            }
            BoundaryReport::NotATile { note } => {
                o += &format!("boundary dimension: none ({note})\n")
            }
            BoundaryReport::NotDecided { note } => {
                o += &format!("boundary dimension: not decided ({note})\n")
            }
        }
        if let Some(state) = &self.state {
            o += &format!(
                "the exact figures above are computed for the automaton restarted at state {state}, as `lacuna verify` computes them; its certificate (`lacuna verify {} --certificate OUT.json`) covers the start state's, not this restart; lengths, areas and box counting are floating-point estimates\n",
                self.input
            );
            return o;
        }
        o += &format!(
            "the solver's verdict, the contraction{} are certified by the steps `lacuna verify {} --certificate OUT.json` writes; lengths, areas and box counting are floating-point estimates\n",
            match (&self.similarity_dimension, &self.boundary_dimension) {
                (Some(_), BoundaryReport::Decided(_)) => {
                    ", the similarity dimension and the boundary dimension"
                }
                (Some(_), _) => " and the similarity dimension",
                (None, _) => "",
            },
            self.input
        );
        o
    }
}

/// Everything `measure` reports for an automaton drawn by `ev` (its model resolved as
/// `resolved`, its cycles checked as `contraction`): lengths and areas per level 0 to `level`,
/// box counting at the deepest level with at most 100 000 pieces (and at least `level`), and the
/// exact similarity dimension with `digits` certified digits (the caller checks `digits`).
#[allow(clippy::too_many_arguments)]
pub fn automaton_measure(
    name: &str,
    model: &crate::input::AutomatonModel,
    resolved: &crate::analysis::Resolved,
    contraction: &ContractionReport,
    ev: &Evaluator,
    level: u32,
    digits: usize,
) -> AutomatonMeasure {
    let levels = level_measures(ev, level);
    // Box counting wants fine pieces: the deepest level with at most 100 000 of them.
    let mut box_level = level;
    while box_level < 40 && ev.count(box_level + 1) <= 100_000 {
        box_level += 1;
    }
    let box_dimension = box_dimension(ev, box_level);
    let (similarity_dimension, similarity_note) =
        match crate::analysis::similarity_dimension(model, &resolved.ops, digits) {
            Ok(s) => (Some(s), None),
            Err(n) => (None, Some(n)),
        };
    let boundary_dimension = match &similarity_dimension {
        None => BoundaryReport::NotATile {
            note: "not known to be a tile: the similarity dimension does not apply".into(),
        },
        Some(sim) => match crate::analysis::not_a_tile(model, sim) {
            Some(note) => BoundaryReport::NotATile { note },
            None => match crate::analysis::boundary_dimension(model, &resolved.ops, sim, digits) {
                Ok(b) => BoundaryReport::Decided(b),
                Err(note) => BoundaryReport::NotDecided { note },
            },
        },
    };
    AutomatonMeasure {
        boundary_dimension,
        input: name.to_string(),
        space: model.space,
        level,
        solver: resolved.verdict.clone(),
        contraction: contraction.clone(),
        levels,
        box_dimension,
        similarity_dimension,
        similarity_note,
        state: None,
    }
}
