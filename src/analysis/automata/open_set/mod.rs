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
//!   3. the neighbour maps ([`crate::analysis::automata::neighbour_maps`], Bandt–Graf, exact in
//!      K): the worklist of maps `f_u⁻¹ ∘ f_v` whose pieces may meet closes without the identity.
//! - **Fails** when two operators out of one state into the same state are equal, or when the
//!   neighbour maps meet the identity: two pieces coincide, and the dimension is smaller than s.
//! - **Undecided** otherwise (infinitely many neighbour maps, operators that are no contracting
//!   similitudes in the coordinates, states of other sizes, 3D): s is then reported as an upper
//!   bound, never as the dimension.
//!
//! **Files.** This file holds the verdict, the witness types and [`part_verdict`];
//! `hulls.rs` the chart maps and the convex hulls in the charts (the hull witness), and
//! `neighbours.rs` the coordinates the neighbour-map search runs in (attractor centres, the
//! rescaling that balances them).

mod hulls;
mod neighbours;

use self::hulls::{attractor_hulls, chart_map, feasible, q0, Edge, Pt};
use self::neighbours::{attractor_centres, balance, neighbour_edges};
use crate::algebra::algebraic::FieldElement;
use crate::algebra::kmatrix::KMatrix;
use crate::analysis::automata::contraction::control_graph;
use crate::analysis::automata::neighbour_maps::{search, KEdge, Search};
use crate::input::automaton_model::AutomatonModel;
use num_rational::BigRational;
use num_traits::One;
use serde::Serialize;

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

/// The witness of a verdict decided by neighbour maps
/// ([`crate::analysis::automata::neighbour_maps`]).
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
    let raw = part_operators(m, &g, part);
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
    let why = match neighbour_system(m, ops, frames, part) {
        Err(why) => why,
        Ok(NeighbourSystem {
            coordinates,
            centres,
            edges: kedges,
            scales,
            ..
        }) => {
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

/// The coordinates of the part's neighbour-map search, exactly as [`part_verdict`] builds them
/// (the same states' coordinates, centres and rescaling, so the same search). The boundary
/// graph ([`crate::analysis::automata::boundary`]) runs the search on them.
pub(crate) struct NeighbourSystem {
    /// The kind of coordinates.
    pub coordinates: Coordinates,
    /// One centre per state of the part, in part order.
    pub centres: Vec<Vec<FieldElement>>,
    /// The part's operators as similitudes between the states' coordinates.
    pub edges: Vec<KEdge>,
    /// The operator index of each edge.
    pub operators: Vec<usize>,
    /// The scale of each state's coordinates, when rescaled ([`balance`]).
    pub scales: Option<Vec<BigRational>>,
}

/// The part's [`NeighbourSystem`], or why there is none.
pub(crate) fn neighbour_system(
    m: &AutomatonModel,
    ops: &[KMatrix],
    frames: &[Option<KMatrix>],
    part: &[usize],
) -> Result<NeighbourSystem, String> {
    let a = &m.automaton;
    let k = &m.field;
    let g = control_graph(m);
    let raw = part_operators(m, &g, part);
    if raw.len() > MAX_EDGES {
        return Err(format!("more than {MAX_EDGES} operators in the part"));
    }
    let dims: Vec<usize> = part.iter().map(|&s| a.states[s].dim).collect();
    let d = match (dims.iter().all(|&x| x == dims[0]), dims[0], m.space) {
        (true, 2, _) => 1,
        (true, 3, 2) => 2,
        _ => {
            return Err(
                "the neighbour maps work on states of 2 points, or of 3 points in the plane".into(),
            )
        }
    };
    let edges: Vec<Edge> = raw
        .iter()
        .map(|&(q, w, o)| (q, w, chart_map(k, &ops[o], d), o))
        .collect();
    let (coordinates, centres, kedges) = neighbour_edges(k, part, &edges, frames, d)?;
    let centres = attractor_centres(k, &centres, &kedges);
    let (centres, edges, scales) = match balance(k, &centres, &kedges) {
        Some((c, e, x)) => (c, e, Some(x)),
        None => (centres, kedges, None),
    };
    Ok(NeighbourSystem {
        coordinates,
        centres,
        edges,
        operators: raw.iter().map(|x| x.2).collect(),
        scales,
    })
}

/// The operators `o: q ← w` with both ends in the strongly connected part `part` (sorted), as
/// `(q, w, o)`: the system the open-set search and the boundary graph work on.
fn part_operators(
    m: &AutomatonModel,
    g: &[Vec<usize>],
    part: &[usize],
) -> Vec<(usize, usize, usize)> {
    let mut raw = Vec::new();
    for &q in part {
        for &o in &g[q] {
            let w = m.automaton.operators[o].from;
            if part.binary_search(&w).is_ok() {
                raw.push((q, w, o));
            }
        }
    }
    raw
}
