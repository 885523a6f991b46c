//! The open-set condition, decided exactly where a sufficient or a refuting criterion applies.
//!
//! The similarity dimension s of a strongly connected part of the control graph is the
//! Hausdorff dimension of the part's attractor when the part satisfies the open-set condition
//! (Mauldin–Williams): open sets `V_q`, one per state, with `T(V_w) ⊆ V_q` for every operator
//! `T: q ← w` of the part and the images of the operators out of one state pairwise disjoint.
//! Without it s is only an upper bound. The test works in each state's own affine chart (the
//! barycentric coordinates of its control points: two for a state of 3 points in the plane, one
//! for a state of 2 points), where the operators are affine maps; disjointness and inclusion do
//! not depend on the chart, so a feasible family found there is one in the drawing.
//!
//! - **Holds** when one of two candidate families is feasible, checked in exact arithmetic:
//!   1. the convex hulls of the part's attractors, computed by iterating
//!      `H_q ← hull(H_q ∪ ⋃ T(H_w))` from fixed points of the part's cycles (points of the
//!      attractors) until the hulls stop changing (at most [`MAX_ROUNDS`] rounds). A family
//!      that stops changing is invariant, so its interiors satisfy the inclusions; the pieces
//!      must then have pairwise disjoint interiors (a separating edge line, convex polygons) and
//!      non-empty interior;
//!   2. one fixed polygon for every state: the square whose diagonal is the state's first two
//!      points (for rules: the square on the segment), or the segment itself for 2-point states.
//!   3. the neighbour maps ([`crate::analysis::neighbour_maps`], Bandt–Graf, exact in K): the
//!      worklist of maps `f_u⁻¹ ∘ f_v` whose pieces may meet closes without the identity.
//! - **Fails** when two operators out of one state into the same state are equal, or when the
//!   neighbour maps meet the identity: two pieces coincide, and the dimension is smaller than s.
//! - **Undecided** otherwise (infinitely many neighbour maps, operators that are no contracting
//!   similitudes in the coordinates, states of other sizes, 3D): s is then reported as an upper
//!   bound, never as the dimension.

use crate::algebra::algebraic::{FieldElement, NumberField};
use crate::algebra::kmatrix::KMatrix;
use crate::analysis::contraction::control_graph;
use crate::analysis::neighbour_maps::{search, KAffine, KEdge, Search};
use crate::input::automaton_model::AutomatonModel;
use num_rational::BigRational;
use num_traits::{One, Zero};
use serde::Serialize;
use std::cmp::Ordering;

/// The most rounds of the hull iteration.
pub const MAX_ROUNDS: usize = 6;
/// The most vertices of one hull (beyond it the hull criterion gives up).
const MAX_VERTICES: usize = 48;
/// The most operators of a part for any criterion (the checks are quadratic in their number).
const MAX_EDGES: usize = 256;
/// The most states of a part for the hull criterion.
const MAX_PART: usize = 64;

/// The verdict on the open-set condition.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct OpenSetVerdict {
    /// `Some(true)`: holds (proved); `Some(false)`: fails (proved); `None`: undecided.
    pub holds: Option<bool>,
    /// The criterion that decided, or why none did.
    pub reason: String,
    /// When a family of convex sets decided it (the hulls or the squares): one per state of
    /// the part, in part order, its vertices counter-clockwise in the state's chart (the
    /// certificate's witness).
    #[serde(skip)]
    pub witness: Option<Vec<Vec<Vec<FieldElement>>>>,
    /// When the neighbour maps decided it: the certificate's witness (the closed set of maps,
    /// or the two words with the same map).
    #[serde(skip)]
    pub neighbour: Option<NeighbourWitness>,
}

/// The coordinates of each state in which the neighbour maps are computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Coordinates {
    /// The state's chart (the barycentric coordinates of its control points).
    Charts,
    /// The drawing, through the state's frame `E_q(y) = P_0 + (P_1 − P_0, P_2 − P_0)·y`.
    Drawing,
}

/// One kept neighbour map `h: x ↦ A·x + b` from the chart of the part's state `r` to that of
/// `q` (positions in the part), `A` row-major.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct NeighbourMap {
    /// The position in the part of the state whose coordinates h maps into.
    pub q: usize,
    /// The position in the part of the state whose coordinates h maps from.
    pub r: usize,
    /// The linear part, `d × d` row-major.
    pub a: Vec<FieldElement>,
    /// The translation.
    pub b: Vec<FieldElement>,
}

/// The witness of a verdict decided by neighbour maps ([`crate::analysis::neighbour_maps`]).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum NeighbourWitness {
    /// The condition holds: the coordinates, one centre per state of the part (in part order),
    /// the common radius R and margin μ of the ball test, and the closed set of maps.
    Holds {
        /// The coordinates of the states.
        coordinates: Coordinates,
        /// The centres `c_q`.
        centres: Vec<Vec<FieldElement>>,
        /// The radius R.
        radius: BigRational,
        /// The margin μ.
        margin: BigRational,
        /// The kept maps.
        maps: Vec<NeighbourMap>,
        /// The scale `c_q` of each state's coordinates (in part order), when rescaled so that
        /// every operator contracts ([`balance`]); `None`: all 1.
        scales: Option<Vec<BigRational>>,
    },
    /// The condition fails: two words of operators (operator indices) from one state, with
    /// different first operators and one end state, whose maps are equal.
    Fails {
        /// The first word.
        u: Vec<usize>,
        /// The second word.
        v: Vec<usize>,
    },
}

/// A point of a chart (1 or 2 coordinates).
type Pt = Vec<FieldElement>;

/// An operator as an affine map between charts: `x ↦ A·x + b`, `A` row-major `d × d`.
#[derive(Clone, Debug, PartialEq)]
struct Map {
    a: Vec<FieldElement>,
    b: Vec<FieldElement>,
}

fn q0(k: &NumberField) -> FieldElement {
    k.rational(BigRational::zero())
}

/// The chart map of `T: q ← w` (both states of `d + 1` points): the child's chart point x has
/// barycentric coordinates `(1 − Σx, x)`, its image `T·(1 − Σx, x)` read in the parent's chart.
fn chart_map(k: &NumberField, t: &KMatrix, d: usize) -> Map {
    // Image of x = Σ_j x_j e_j: T·(e_0 + Σ x_j (e_j − e_0)); chart rows 1..=d.
    let mut a = Vec::with_capacity(d * d);
    let mut b = Vec::with_capacity(d);
    for r in 1..=d {
        for j in 1..=d {
            a.push(k.sub(t.get(r, j), t.get(r, 0)));
        }
        b.push(t.get(r, 0).clone());
    }
    Map { a, b }
}

impl Map {
    fn apply(&self, k: &NumberField, x: &Pt) -> Pt {
        let d = x.len();
        (0..d)
            .map(|r| {
                let mut acc = self.b[r].clone();
                for (j, xj) in x.iter().enumerate() {
                    acc = k.add(&acc, &k.mul(&self.a[r * d + j], xj));
                }
                acc
            })
            .collect()
    }

    /// `self ∘ other`.
    fn then(&self, k: &NumberField, o: &Map) -> Map {
        let d = self.b.len();
        let mut a = vec![q0(k); d * d];
        for r in 0..d {
            for c in 0..d {
                let mut acc = q0(k);
                for j in 0..d {
                    acc = k.add(&acc, &k.mul(&self.a[r * d + j], &o.a[j * d + c]));
                }
                a[r * d + c] = acc;
            }
        }
        Map {
            a,
            b: self.apply(k, &o.b),
        }
    }

    /// The fixed point, when `I − A` is invertible (d = 1 or 2).
    fn fixed_point(&self, k: &NumberField) -> Option<Pt> {
        let one = k.rational(BigRational::one());
        match self.b.len() {
            1 => {
                let den = k.sub(&one, &self.a[0]);
                Some(vec![k.div(&self.b[0], &den)?])
            }
            2 => {
                // (I − A) x = b by Cramer's rule.
                let (m00, m01) = (k.sub(&one, &self.a[0]), k.sub(&q0(k), &self.a[1]));
                let (m10, m11) = (k.sub(&q0(k), &self.a[2]), k.sub(&one, &self.a[3]));
                let det = k.sub(&k.mul(&m00, &m11), &k.mul(&m01, &m10));
                let x = k.sub(&k.mul(&self.b[0], &m11), &k.mul(&m01, &self.b[1]));
                let y = k.sub(&k.mul(&m00, &self.b[1]), &k.mul(&m10, &self.b[0]));
                Some(vec![k.div(&x, &det)?, k.div(&y, &det)?])
            }
            _ => None,
        }
    }
}

fn cmp(k: &NumberField, a: &FieldElement, b: &FieldElement) -> Ordering {
    k.sign(&k.sub(a, b))
}

/// The sign of the cross product `(b − a) × (c − a)`.
fn turn(k: &NumberField, a: &Pt, b: &Pt, c: &Pt) -> Ordering {
    let l = k.mul(&k.sub(&b[0], &a[0]), &k.sub(&c[1], &a[1]));
    let r = k.mul(&k.sub(&b[1], &a[1]), &k.sub(&c[0], &a[0]));
    cmp(k, &l, &r)
}

/// The convex hull, counter-clockwise, without collinear points (monotone chain, exact). In one
/// dimension: the two ends.
fn hull(k: &NumberField, mut pts: Vec<Pt>) -> Vec<Pt> {
    pts.sort_by(|a, b| {
        a.iter()
            .zip(b)
            .map(|(x, y)| cmp(k, x, y))
            .find(|o| *o != Ordering::Equal)
            .unwrap_or(Ordering::Equal)
    });
    pts.dedup();
    if pts.len() <= 2 || pts[0].len() == 1 {
        if pts.len() >= 2 {
            let last = pts.len() - 1;
            return vec![pts[0].clone(), pts[last].clone()];
        }
        return pts;
    }
    let mut lower: Vec<Pt> = Vec::new();
    for p in &pts {
        while lower.len() >= 2
            && turn(k, &lower[lower.len() - 2], &lower[lower.len() - 1], p) != Ordering::Greater
        {
            lower.pop();
        }
        lower.push(p.clone());
    }
    let mut upper: Vec<Pt> = Vec::new();
    for p in pts.iter().rev() {
        while upper.len() >= 2
            && turn(k, &upper[upper.len() - 2], &upper[upper.len() - 1], p) != Ordering::Greater
        {
            upper.pop();
        }
        upper.push(p.clone());
    }
    lower.pop();
    upper.pop();
    lower.extend(upper);
    lower
}

/// True when the polygon (or interval) has a non-empty interior.
fn solid(p: &[Pt]) -> bool {
    match p.first().map(Vec::len) {
        Some(1) => p.len() == 2 && p[0] != p[1],
        Some(2) => p.len() >= 3,
        _ => false,
    }
}

/// True when the interiors of two convex polygons (or intervals) do not meet: an edge line of
/// one leaves the other on its closed outer side.
fn interiors_disjoint(k: &NumberField, a: &[Pt], b: &[Pt]) -> bool {
    if a[0].len() == 1 {
        // Intervals [lo, hi], sorted ends.
        return cmp(k, &a[1][0], &b[0][0]) != Ordering::Greater
            || cmp(k, &b[1][0], &a[0][0]) != Ordering::Greater;
    }
    let separates = |p: &[Pt], other: &[Pt]| {
        (0..p.len()).any(|i| {
            let (s, e) = (&p[i], &p[(i + 1) % p.len()]);
            other.iter().all(|v| turn(k, s, e, v) != Ordering::Greater)
        })
    };
    separates(a, b) || separates(b, a)
}

/// True when every vertex of `inner` lies in the closed convex polygon (interval) `outer`.
fn contains(k: &NumberField, outer: &[Pt], inner: &[Pt]) -> bool {
    if outer[0].len() == 1 {
        return inner.iter().all(|v| {
            cmp(k, &outer[0][0], &v[0]) != Ordering::Greater
                && cmp(k, &v[0], &outer[1][0]) != Ordering::Greater
        });
    }
    inner.iter().all(|v| {
        (0..outer.len())
            .all(|i| turn(k, &outer[i], &outer[(i + 1) % outer.len()], v) != Ordering::Less)
    })
}

/// The part's operators as chart maps: (source state q, target state w, map, operator).
type Edge = (usize, usize, Map, usize);

/// Whether a family of polygons (one per state of the part, in part order) is feasible: every
/// piece inside its state's polygon, and the pieces out of one state with disjoint interiors.
fn feasible(
    k: &NumberField,
    part: &[usize],
    edges: &[Edge],
    sets: &[Vec<Pt>],
    check_inclusion: bool,
) -> bool {
    if !sets.iter().all(|s| solid(s)) {
        return false;
    }
    let pos = |s: usize| part.binary_search(&s).expect("in part");
    for (i, &q) in part.iter().enumerate() {
        let pieces: Vec<Vec<Pt>> = edges
            .iter()
            .filter(|e| e.0 == q)
            .map(|(_, w, m, _)| hull(k, sets[pos(*w)].iter().map(|p| m.apply(k, p)).collect()))
            .collect();
        if check_inclusion && !pieces.iter().all(|p| contains(k, &sets[i], p)) {
            return false;
        }
        for a in 0..pieces.len() {
            for b in a + 1..pieces.len() {
                if !solid(&pieces[a]) || !interiors_disjoint(k, &pieces[a], &pieces[b]) {
                    return false;
                }
            }
        }
    }
    true
}

/// The convex hulls of the part's attractors, when the iteration stops changing.
fn attractor_hulls(
    k: &NumberField,
    part: &[usize],
    edges: &[Edge],
) -> Option<(Vec<Vec<Pt>>, usize)> {
    let n = part.len();
    let pos = |s: usize| part.binary_search(&s).expect("in part");
    let mut sets: Vec<Vec<Pt>> = vec![Vec::new(); n];
    // Seeds: the fixed point of one cycle through each state (found breadth first).
    for (i, &q) in part.iter().enumerate() {
        let mut prev: Vec<Option<usize>> = vec![None; n];
        let mut queue = std::collections::VecDeque::from([i]);
        let mut found = None;
        'bfs: while let Some(v) = queue.pop_front() {
            for (e, (s, w, _, _)) in edges.iter().enumerate() {
                if pos(*s) != v {
                    continue;
                }
                let wi = pos(*w);
                if wi == i {
                    found = Some((v, e));
                    break 'bfs;
                }
                if prev[wi].is_none() {
                    prev[wi] = Some(e);
                    queue.push_back(wi);
                }
            }
        }
        let (mut v, e) = found?;
        // The cycle's edges from q: rebuild backwards.
        let mut path = vec![e];
        while v != i {
            let pe = prev[v].expect("reached");
            path.push(pe);
            v = pos(edges[pe].0);
        }
        path.reverse();
        let mut m = edges[path[0]].2.clone();
        for &pe in &path[1..] {
            m = m.then(k, &edges[pe].2);
        }
        sets[i].push(m.fixed_point(k)?);
        // And the fixed points of every cycle of one or two operators through q.
        for (s1, w1, m1, _) in edges.iter().filter(|e| e.0 == q) {
            if *w1 == q {
                sets[i].extend(m1.fixed_point(k));
                continue;
            }
            for (_, _, m2, _) in edges.iter().filter(|e| e.0 == *w1 && e.1 == *s1) {
                if edges.len() <= 512 {
                    sets[i].extend(m1.then(k, m2).fixed_point(k));
                }
            }
        }
    }
    for round in 1..=MAX_ROUNDS {
        let mut next = Vec::with_capacity(n);
        for (i, &q) in part.iter().enumerate() {
            let mut pts = sets[i].clone();
            for (_, w, m, _) in edges.iter().filter(|e| e.0 == q) {
                pts.extend(sets[pos(*w)].iter().map(|p| m.apply(k, p)));
            }
            let h = hull(k, pts);
            if h.len() > MAX_VERTICES {
                return None;
            }
            next.push(h);
        }
        if next == sets {
            return Some((sets, round));
        }
        sets = next;
    }
    None
}

/// The verdict for one strongly connected part (sorted state indices).
pub(crate) fn part_verdict(
    m: &AutomatonModel,
    ops: &[KMatrix],
    frames: &[Option<KMatrix>],
    part: &[usize],
) -> OpenSetVerdict {
    let a = &m.automaton;
    let k = &m.field;
    let g = control_graph(m);
    let undecided = |r: String| OpenSetVerdict {
        holds: None,
        reason: r,
        witness: None,
        neighbour: None,
    };
    let mut raw = Vec::new();
    for &q in part {
        for &o in &g[q] {
            let w = a.operators[o].from;
            if part.binary_search(&w).is_ok() {
                raw.push((q, w, o));
            }
        }
    }
    if raw.len() > MAX_EDGES {
        return undecided(format!(
            "undecided: more than {MAX_EDGES} operators in the part (the exact check is not attempted)"
        ));
    }
    // Equal operators out of one state into one state: the same piece twice.
    for (i, x) in raw.iter().enumerate() {
        for y in &raw[i + 1..] {
            if x.0 == y.0 && x.1 == y.1 && ops[x.2] == ops[y.2] {
                return OpenSetVerdict {
                    witness: None,
                    neighbour: Some(NeighbourWitness::Fails {
                        u: vec![x.2],
                        v: vec![y.2],
                    }),
                    holds: Some(false),
                    reason: format!(
                        "fails: `{}` and `{}` are the same map, so their pieces coincide",
                        a.operators[x.2].name, a.operators[y.2].name
                    ),
                };
            }
        }
    }
    let dims: Vec<usize> = part.iter().map(|&s| a.states[s].dim).collect();
    let d =
        match (dims.iter().all(|&x| x == dims[0]), dims[0], m.space) {
            (true, 2, _) => 1,
            (true, 3, 2) => 2,
            _ => return undecided(
                "undecided: the criteria work on states of 2 points, or of 3 points in the plane"
                    .into(),
            ),
        };
    let edges: Vec<Edge> = raw
        .iter()
        .map(|&(q, w, o)| (q, w, chart_map(k, &ops[o], d), o))
        .collect();
    if part.len() <= MAX_PART {
        if let Some((sets, rounds)) = attractor_hulls(k, part, &edges) {
            if feasible(k, part, &edges, &sets, false) {
                return OpenSetVerdict {
                    holds: Some(true),
                    reason: format!("holds: the interiors of the convex hulls of the attractors (exact, {} vertices, found in {rounds} rounds) are a feasible open set", sets.iter().map(Vec::len).sum::<usize>()),
                    witness: Some(sets),
                    neighbour: None,
                };
            }
        }
    }
    let one = k.rational(BigRational::one());
    let half = k.rational(BigRational::new(1.into(), 2.into()));
    let cell: Vec<Pt> = if d == 1 {
        vec![vec![q0(k)], vec![one]]
    } else {
        let mhalf = k.rational(BigRational::new((-1).into(), 2.into()));
        vec![
            vec![q0(k), q0(k)],
            vec![half.clone(), mhalf],
            vec![one, q0(k)],
            vec![half.clone(), half],
        ]
    };
    let sets = vec![cell; part.len()];
    if feasible(k, part, &edges, &sets, true) {
        return OpenSetVerdict {
            witness: Some(sets),
            neighbour: None,
            holds: Some(true),
            reason: if d == 1 {
                "holds: the open segment between each state's two points is a feasible open set"
                    .into()
            } else {
                "holds: the open square whose diagonal joins each state's first two points (for a rule: the square on the segment) is a feasible open set".into()
            },
        };
    }
    let why = match neighbour_edges(k, part, &edges, frames, d) {
        Err(why) => why,
        Ok((coordinates, centres, kedges)) => {
            let centres = attractor_centres(k, &centres, &kedges);
            let (centres, kedges, scales) = match balance(k, &centres, &kedges) {
                Some((c, e, x)) => (c, e, Some(x)),
                None => (centres, kedges, None),
            };
            match search(k, &centres, &kedges) {
            Search::Closed(closed) => {
                return OpenSetVerdict {
                    witness: None,
                    holds: Some(true),
                    reason: format!("holds: the neighbour maps (Bandt–Graf, exact) form a finite set of {} maps without the identity", closed.maps.len()),
                    neighbour: Some(NeighbourWitness::Holds {
                        coordinates,
                        centres,
                        radius: closed.radius,
                        margin: closed.margin,
                        maps: closed
                            .maps
                            .into_iter()
                            .map(|(q, r, h)| NeighbourMap { q, r, a: h.a, b: h.b })
                            .collect(),
                        scales,
                    }),
                }
            }
            Search::Identity(u, v) => {
                let op = |e: &usize| edges[*e].3;
                return OpenSetVerdict {
                    witness: None,
                    holds: Some(false),
                    reason: format!(
                        "fails: the identity is a neighbour map (two words starting with `{}` and `{}` give the same map, so their pieces coincide)",
                        a.operators[op(&u[0])].name, a.operators[op(&v[0])].name
                    ),
                    neighbour: Some(NeighbourWitness::Fails {
                        u: u.iter().map(op).collect(),
                        v: v.iter().map(op).collect(),
                    }),
                }
            }
            Search::Undecided(why) => why,
            }
        }
    };
    undecided(format!("undecided: neither the convex hulls of the attractors nor the square on the segment is a feasible open set, and the neighbour maps decide nothing: {why} (the condition may still hold)"))
}

/// Centres of the balls of the neighbour-map search near the middle of each state's attractor:
/// the attractors are estimated in floating point (from `start`, twelve rounds of the operators,
/// at most 4096 points kept per state) and each centre is the middle of its state's bounding box,
/// rounded to a rational of denominator 1024. Any centres are sound — the search certifies its
/// radius exactly for the centres it is given — but balls around the attractors' middles are
/// smallest, and the fewer neighbour maps pass the ball test. `start` when the estimate is not
/// finite.
fn attractor_centres(
    k: &NumberField,
    start: &[Vec<FieldElement>],
    edges: &[KEdge],
) -> Vec<Vec<FieldElement>> {
    let d = start.first().map_or(0, Vec::len);
    let maps: Vec<(usize, usize, Vec<f64>, Vec<f64>)> = edges
        .iter()
        .map(|(q, w, g)| {
            let a = g.a.iter().map(|x| k.approx(x)).collect();
            let b = g.b.iter().map(|x| k.approx(x)).collect();
            (*q, *w, a, b)
        })
        .collect();
    let mut pts: Vec<Vec<Vec<f64>>> = start
        .iter()
        .map(|c| vec![c.iter().map(|x| k.approx(x)).collect()])
        .collect();
    for _ in 0..12 {
        let mut next: Vec<Vec<Vec<f64>>> = vec![Vec::new(); start.len()];
        for (q, w, a, b) in &maps {
            for x in &pts[*w] {
                let y: Vec<f64> = (0..d)
                    .map(|r| b[r] + (0..d).map(|j| a[r * d + j] * x[j]).sum::<f64>())
                    .collect();
                next[*q].push(y);
            }
        }
        for (q, v) in next.iter_mut().enumerate() {
            if v.is_empty() {
                v.clone_from(&pts[q]);
            }
            if v.len() > 4096 {
                let step = v.len().div_ceil(4096);
                *v = v.iter().step_by(step).cloned().collect();
            }
        }
        pts = next;
    }
    pts.iter()
        .zip(start)
        .map(|(v, fallback)| {
            let centre: Option<Vec<FieldElement>> = (0..d)
                .map(|r| {
                    let lo = v.iter().map(|x| x[r]).fold(f64::INFINITY, f64::min);
                    let hi = v.iter().map(|x| x[r]).fold(f64::NEG_INFINITY, f64::max);
                    let m = ((lo + hi) / 2.0 * 1024.0).round();
                    (m.is_finite() && m.abs() < 1e15).then(|| {
                        k.rational(BigRational::new(
                            num_bigint::BigInt::from(m as i64),
                            1024.into(),
                        ))
                    })
                })
                .collect();
            centre.unwrap_or_else(|| fallback.clone())
        })
        .collect()
}

/// Centres, operators and the scales of the states' coordinates after [`balance`].
type Rescaled = (Vec<Vec<FieldElement>>, Vec<KEdge>, Vec<BigRational>);

/// Rescales the states' coordinates so that every operator contracts, when one does not as
/// given (an identity from one state to another, as in the kite and dart of seed 004, THEORY §6):
/// state q's coordinates are multiplied by a rational `c_q > 0`, so that `g: w → q` of ratio ρ
/// becomes `x ↦ c_q·g(x/c_w)` of ratio `ρ·c_q/c_w`. The open-set condition does not depend on the
/// coordinates; the neighbour maps are conjugated, not changed in number.
///
/// Such scales exist exactly when every cycle of the part has a product of ratios below 1 (what
/// the contraction step proves): with `x_q = ln c_q` the conditions are the difference
/// constraints `x_q − x_w ≤ −ln ρ_e − ε`, feasible (no negative cycle, Bellman–Ford) for every ε
/// below the least mean of `−ln ρ` over the cycles. The scales are chosen in floating point at
/// nine tenths of the largest feasible ε found by bisection and rounded to rationals of
/// denominator 64; whether every scaled operator contracts is then decided exactly by the search
/// itself (and by the checker). `None` when every operator contracts already, when the ratios are
/// not those of similitudes, or when no scales are found.
fn balance(k: &NumberField, centres: &[Vec<FieldElement>], edges: &[KEdge]) -> Option<Rescaled> {
    let one = k.rational(BigRational::one());
    let mut log_ratio = Vec::with_capacity(edges.len());
    let mut all_contract = true;
    for (_, _, g) in edges {
        let r2 = g.similitude_ratio2(k)?;
        all_contract &= cmp(k, &r2, &one) == Ordering::Less;
        let r2 = k.approx(&r2);
        if !(r2.is_finite() && r2 > 0.0) {
            return None;
        }
        log_ratio.push(0.5 * r2.ln());
    }
    if all_contract {
        return None;
    }
    let n = centres.len();
    // Bellman–Ford from a virtual source joined to every state by 0: the least x with
    // x_q ≤ x_w + (−ln ρ_e − ε) for every edge, or None on a negative cycle.
    let potentials = |eps: f64| -> Option<Vec<f64>> {
        let mut x = vec![0.0f64; n];
        for round in 0..=n {
            let mut changed = false;
            for ((q, w, _), l) in edges.iter().zip(&log_ratio) {
                let via = x[*w] - l - eps;
                if via < x[*q] - 1e-12 {
                    x[*q] = via;
                    changed = true;
                }
            }
            if !changed {
                return Some(x);
            }
            if round == n {
                return None;
            }
        }
        None
    };
    let top = log_ratio.iter().map(|l| -l).fold(0.0f64, f64::max);
    potentials(0.0)?;
    let (mut lo, mut hi) = (0.0f64, top);
    for _ in 0..50 {
        let mid = 0.5 * (lo + hi);
        match potentials(mid) {
            Some(_) => lo = mid,
            None => hi = mid,
        }
    }
    if lo <= 0.0 {
        return None;
    }
    let x = potentials(0.9 * lo)?;
    let scales: Vec<BigRational> = x
        .iter()
        .map(|&v| {
            let c = (v.exp() * 64.0).round().max(1.0);
            BigRational::new(num_bigint::BigInt::from(c as i64), 64.into())
        })
        .collect();
    let scale = |q: usize| k.rational(scales[q].clone());
    let centres = centres
        .iter()
        .enumerate()
        .map(|(q, c)| c.iter().map(|v| k.mul(v, &scale(q))).collect())
        .collect();
    let edges = edges
        .iter()
        .map(|(q, w, g)| {
            let f = k.rational(&scales[*q] / &scales[*w]);
            let g = KAffine {
                a: g.a.iter().map(|v| k.mul(v, &f)).collect(),
                b: g.b.iter().map(|v| k.mul(v, &scale(*q))).collect(),
            };
            (*q, *w, g)
        })
        .collect();
    Some((centres, edges, scales))
}

/// The coordinates chosen, the centre of each state in them and the operators as maps in them.
type Neighbourhood = (Coordinates, Vec<Vec<FieldElement>>, Vec<KEdge>);

/// The part's operators as similitudes over K between per-state coordinates, for the
/// neighbour-map search: in one dimension the charts themselves (every affine map of the line is
/// a similitude); in the plane the charts when every operator is a contracting similitude there
/// (a rule's states: the charts are the generators' own Euclidean coordinates), else the
/// drawing's coordinates through each state's frame `E_q(y) = P_0 + (P_1 − P_0, P_2 − P_0)·y`,
/// where the operators are similitudes. The centres are the midpoints of each state's first two
/// points. Any choice of coordinates per state is sound: the condition does not depend on it.
fn neighbour_edges(
    k: &NumberField,
    part: &[usize],
    edges: &[Edge],
    frames: &[Option<KMatrix>],
    d: usize,
) -> Result<Neighbourhood, String> {
    let pos = |s: usize| part.binary_search(&s).expect("in part");
    let chart = |m: &Map| KAffine {
        a: m.a.clone(),
        b: m.b.clone(),
    };
    let half = k.rational(BigRational::new(1.into(), 2.into()));
    let in_charts: Vec<KEdge> = edges
        .iter()
        .map(|(s, w, m, _)| (pos(*s), pos(*w), chart(m)))
        .collect();
    let one = k.rational(BigRational::one());
    let contracting = |q: &[KEdge]| {
        q.iter().all(|(_, _, g)| {
            g.similitude_ratio2(k)
                .is_some_and(|r2| cmp(k, &r2, &one) == Ordering::Less)
        })
    };
    if d == 1 || contracting(&in_charts) {
        let centre = if d == 1 {
            vec![half]
        } else {
            vec![half, q0(k)]
        };
        return Ok((Coordinates::Charts, vec![centre; part.len()], in_charts));
    }
    let mut embed = Vec::with_capacity(part.len());
    let mut centres = Vec::with_capacity(part.len());
    for &s in part {
        let f = frames[s]
            .as_ref()
            .filter(|f| f.rows == 2 && f.cols == 3)
            .ok_or_else(|| "a state has no frame of three points in the plane".to_string())?;
        let p = |r: usize, c: usize| f.get(r, c);
        let (x0, y0) = (p(0, 0), p(1, 0));
        let e = KAffine {
            a: vec![
                k.sub(p(0, 1), x0),
                k.sub(p(0, 2), x0),
                k.sub(p(1, 1), y0),
                k.sub(p(1, 2), y0),
            ],
            b: vec![x0.clone(), y0.clone()],
        };
        let inv = e
            .inverse(k)
            .ok_or_else(|| "a state's frame is degenerate".to_string())?;
        centres.push(vec![
            k.mul(&k.add(x0, p(0, 1)), &half),
            k.mul(&k.add(y0, p(1, 1)), &half),
        ]);
        embed.push((e, inv));
    }
    let q = edges
        .iter()
        .map(|(s, w, m, _)| {
            let (i, j) = (pos(*s), pos(*w));
            (i, j, embed[i].0.then(k, &chart(m)).then(k, &embed[j].1))
        })
        .collect();
    Ok((Coordinates::Drawing, centres, q))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::algebraic::RealAlgebraic;

    fn qk() -> NumberField {
        NumberField::new(RealAlgebraic::rational(BigRational::zero()))
    }
    fn p(k: &NumberField, x: i64, y: i64, d: i64) -> Pt {
        vec![
            k.rational(BigRational::new(x.into(), d.into())),
            k.rational(BigRational::new(y.into(), d.into())),
        ]
    }

    #[test]
    fn hulls_drop_inner_and_collinear_points() {
        let k = qk();
        let h = hull(
            &k,
            vec![
                p(&k, 0, 0, 1),
                p(&k, 1, 0, 1),
                p(&k, 2, 0, 1),
                p(&k, 1, 1, 2),
                p(&k, 1, 2, 1),
            ],
        );
        // Triangle (0,0), (2,0), (1,2), counter-clockwise from the lowest-leftmost point.
        assert_eq!(h, vec![p(&k, 0, 0, 1), p(&k, 2, 0, 1), p(&k, 1, 2, 1)]);
    }

    #[test]
    fn touching_squares_have_disjoint_interiors_overlapping_ones_not() {
        let k = qk();
        let sq = |x: i64| {
            vec![
                p(&k, x, 0, 1),
                p(&k, x + 1, 0, 1),
                p(&k, x + 1, 1, 1),
                p(&k, x, 1, 1),
            ]
        };
        assert!(interiors_disjoint(&k, &sq(0), &sq(1)));
        let shifted = vec![
            p(&k, 1, 0, 2),
            p(&k, 3, 0, 2),
            p(&k, 3, 2, 2),
            p(&k, 1, 2, 2),
        ];
        assert!(!interiors_disjoint(&k, &sq(0), &shifted));
        assert!(contains(&k, &sq(0), &[p(&k, 1, 1, 2)]));
        assert!(!contains(&k, &sq(0), &[p(&k, 3, 1, 2)]));
    }

    #[test]
    fn fixed_point_of_a_half_turn_map() {
        // x ↦ −x/2 + (3/2, 3): fixed point x = (1, 2).
        let k = qk();
        let r = |n: i64, d: i64| k.rational(BigRational::new(n.into(), d.into()));
        let m = Map {
            a: vec![r(-1, 2), r(0, 1), r(0, 1), r(-1, 2)],
            b: vec![r(3, 2), r(3, 1)],
        };
        assert_eq!(m.fixed_point(&k).unwrap(), p(&k, 1, 2, 1));
    }
}
