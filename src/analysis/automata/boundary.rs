//! The dimension of the boundary of each state's attractor as seen by the pieces that touch it
//! (what IFStile computes for tiles), from the graph of neighbour maps, exact in the automaton's
//! real number field K.
//!
//! **The sets.** For a neighbour map `h = g_u⁻¹ ∘ g_v: chart r → chart q`
//! ([`crate::analysis::automata::neighbour_maps`]) let `B_h = A_q ∩ h(A_r)`: the points where the
//! piece `g_u(A_q)` meets the piece `g_v(A_r)`, seen in q's chart. The balanced refinement of the
//! search splits it: when `ratio(h) ≤ 1`, `B_h = ⋃_{e: q ← w} g_e(B_{g_e⁻¹ ∘ h})` (an edge of
//! the operator's ratio), else `B_h = ⋃_{e: r ← w} B_{h ∘ g_e}` (an edge of ratio 1). A child
//! whose map fails the ball test has `B = ∅`, so the children kept by the search are all that
//! count, and when the open-set search closes (finite type) its kept maps and these edges form a
//! finite graph ([`crate::analysis::automata::neighbour_maps::map_graph`]), whose nodes start at
//! the maps `g_a⁻¹ ∘ g_b` of two different operators out of one state.
//!
//! **The value.** For every strongly connected component C with a cycle, s_C solves
//! "spectral radius of `M_C(s) = (Σ_edges ratio^s)` is 1", the Mauldin–Williams equation of the
//! similarity dimension ([`crate::analysis::automata::similarity`]): every squared ratio is a
//! power `σ^k` of the part's σ (k = 0 on the edges of ratio 1), `M_C(u)` has entries `Σ u^k`
//! with `u = σ^(s/2)`, and u* is the smallest root in (0, 1] of `det(I − M_C(u))`. The value of
//! a state q is the largest s_C over the components reachable from a node with q on either side
//! (`B_h ⊂ A_q`, and `h⁻¹(B_h) ⊂ A_r` has the same dimension); nodes that lead to no cycle hold
//! finite or empty sets and count 0. Computed in the neighbour search's coordinates (conjugated
//! by rational scales), the edges take the operators' own ratios: a cycle's product of ratios,
//! hence the spectral radius, does not depend on the conjugation. No cycle has only edges of
//! ratio 1 (checked: a cycle `h → … → h` refines the left side by a closed walk of the control
//! graph, which contracts), so the covering argument applies.
//!
//! **What it is, exactly.** The value is an **upper bound** of the Hausdorff (and upper box)
//! dimension of `⋃ B_h`, the set where pieces touch, by the covering argument alone: it needs
//! neither the open-set condition for the B sets nor that any B_h be non-empty. It is the
//! dimension when every node of the dominant component has a non-empty B_h and the
//! graph-directed system of that component satisfies the open-set condition (Bandt–Mesing's
//! finite-type setting); neither is proved here, and the ball test keeps every map whose pieces
//! come within the margin μ, so a kept node may have `B_h = ∅`: [`BoundaryDimension`] always
//! says upper bound. When the attractors are tiles (the closure of their interior, pieces with
//! disjoint interiors), `B_h ⊂ ∂A_q`; points of `∂A_q` that no neighbouring piece touches (the
//! outer boundary of a tile that touches nothing of its own system there) are not counted.
//!
//! **When it applies.** Only to tiles: a value is computed for the states of a cyclic part whose
//! similarity dimension is exactly 2 (`u* = σ`, found exactly) in the plane and whose open-set
//! condition is proved with a witness ([`part_tiling`]). Under the open-set condition a strongly
//! connected graph-directed system of similarity dimension s has `0 < H^s(A_q) < ∞` for every
//! state (Mauldin–Williams 1988); with s = 2, H² is a multiple of Lebesgue measure, so every
//! `A_q` has positive area. That it then has interior and is the closure of it is Schief's
//! theorem (1994) for one state; for several states we rely on its graph-directed analogue (as
//! used for self-affine multi-tiles, Lagarias–Wang), not re-proved here. When the similarity
//! dimension is < 2 (with or without the open-set condition, since it bounds the Hausdorff
//! dimension) the attractor has area 0, no interior, and is its own boundary: no value is given
//! ([`not_a_tile`] says why), because the dimension of the contact set (0 for the Sierpinski
//! triangle, 1 for the carpet) is not that of the boundary. Above 2, or at 2 without a proved
//! open-set condition, the attractor is not known to be a tile and no value is given either.
//!
//! **Not decided** (an error, never a verdict) when the open-set search does not close within
//! its limits ([`crate::analysis::automata::neighbour_maps::MAX_NEIGHBOUR_MAPS`],
//! [`crate::analysis::automata::neighbour_maps::MAX_NEIGHBOUR_TESTS`]) or finds the identity, or
//! when the similarity dimension does not apply. The open-set search is not rerun when the
//! similarity dimension's witness already holds its closed set of maps.

use crate::algebra::algebraic::RealAlgebraic;
use crate::algebra::kmatrix::KMatrix;
use crate::algebra::poly::Poly;
use crate::analysis::automata::neighbour_maps::{
    map_graph, search, Closed, KAffine, MapEdge, Search,
};
use crate::analysis::automata::open_set::{neighbour_system, NeighbourMap, NeighbourWitness};
use crate::analysis::automata::similarity::{
    certified_decimal, compare, equals, exact_text, frames, part_polynomial, smallest_root,
    NotApplicable, PartValue, PartWitness, SimilarityDimension,
};
use crate::input::automaton_model::AutomatonModel;
use crate::topology::class::strong_components;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed};
use serde::Serialize;
use std::cmp::Ordering;

/// The most classes of nodes (after lumping) of one strongly connected component whose
/// polynomial is computed (the interpolated determinant costs about `n⁴` in their number):
/// beyond it the value is not decided.
pub const MAX_COMPONENT: usize = 48;

/// The boundary dimension of every state of the automaton's cyclic parts.
#[derive(Clone, Debug, Serialize)]
pub struct BoundaryDimension {
    /// One entry per state of a cyclic part, in part order.
    pub states: Vec<StateBoundary>,
    /// Always true: the value is an upper bound of the dimension of the set where pieces touch
    /// (see the module doc); it is the dimension when the dominant component's sets are
    /// non-empty and satisfy the open-set condition, which is not proved.
    pub upper_bound: bool,
    /// What the value bounds, and the graph's size.
    pub note: String,
    /// The graph of every cyclic part, for tests and the certificate.
    #[serde(skip)]
    pub graphs: Vec<BoundaryGraph>,
}

/// One state's boundary dimension.
#[derive(Clone, Debug, Serialize)]
pub struct StateBoundary {
    /// The state's name.
    pub state: String,
    /// The exact value (`2·log(u)/log(σ) where …`, or a rational).
    pub exact: String,
    /// Certified digits after the point, truncated.
    pub decimal: String,
}

/// The neighbour-map graph of one tile part: what the certificate step carries.
#[derive(Clone, Debug)]
pub struct BoundaryGraph {
    /// The part's index among the similarity dimension's parts.
    pub part: usize,
    /// The part's states.
    pub states: Vec<usize>,
    /// The kept maps and their coordinates, when the search ran here (the part's open-set
    /// condition was proved by convex sets); `None`: the similarity dimension's own neighbour
    /// maps, in their order.
    pub witness: Option<NeighbourWitness>,
    /// The maps the open-set search kept (the graph's nodes).
    pub nodes: usize,
    /// The nodes on or leading to a cycle.
    pub kept: usize,
    /// The cyclic strongly connected components, ordered by smallest node.
    pub components: Vec<BoundaryComponent>,
    /// For every state of the part, in order: the component of largest value reachable from a
    /// node with the state on either side (`None`: no cycle is reachable, value 0).
    pub dominant: Vec<Option<usize>>,
}

/// One cyclic strongly connected component of the boundary graph.
#[derive(Clone, Debug)]
pub struct BoundaryComponent {
    /// Its nodes (indices of kept maps), increasing.
    pub nodes: Vec<usize>,
    /// The class of every node in an equitable partition (classes numbered by first
    /// appearance).
    pub classes: Vec<usize>,
    /// `det(I − Q(u))` of the lumped matrix.
    pub poly: Poly,
    /// Its smallest root u* in (0, 1].
    pub u: RealAlgebraic,
    /// The value when it is rational.
    pub rational: Option<BigRational>,
    /// The exact value.
    pub exact: String,
}

/// The value `s = 2·ln u/ln σ` when it is an integer j that [`exact_text`] does not see, with
/// u irrational and `u² = σ^j` (a segment's `s = 1` with `u = √σ`): u² is the root of
/// `f_e(y)² − y·f_o(y)²` (f = f_e(x²) + x·f_o(x²) u's minimal polynomial) in the square of u's
/// interval, compared exactly with the powers of σ in K.
fn odd_integer_value(
    k: &crate::algebra::algebraic::NumberField,
    u: &RealAlgebraic,
    sigma: &crate::algebra::algebraic::FieldElement,
) -> Option<i64> {
    if u.as_rational().is_some() {
        return None;
    }
    let c = u.min_poly().coeffs();
    let half = |start: usize| Poly::new(c.iter().skip(start).step_by(2).cloned().collect());
    let (fe, fo) = (half(0), half(1));
    let g = &(&fe * &fe) - &(&Poly::x() * &(&fo * &fo));
    let mut u = u.clone();
    let mut width = BigRational::new(1.into(), 1024.into());
    let v = loop {
        u.refine_to(&width);
        let (lo, hi) = u.interval();
        if lo.is_positive() {
            if let Some(v) = RealAlgebraic::root_in(&g, &(lo * lo), &(hi * hi)) {
                break v;
            }
        }
        width /= BigRational::from_integer(1024.into());
        if width < BigRational::new(1.into(), BigInt::one() << 200) {
            return None;
        }
    };
    let mut pow = sigma.clone();
    for j in 1..=32i64 {
        if equals(k, &v, &pow) {
            return Some(j);
        }
        pow = k.mul(&pow, sigma);
    }
    None
}

/// The coarsest equitable partition of a component (`nodes` increasing, `inside` its membership
/// test) and its quotient matrix: nodes are in one class when, class by class, their edges
/// inside the component carry the same multiset of exponents. Returns the number of classes,
/// `entries[X][Y]` (the exponents of the edges from any node of X into Y) and the class of
/// every node (numbered by first appearance).
///
/// The quotient Q(u) has the same spectral radius as the component's M(u) for every u > 0: a
/// positive eigenvector of Q (Perron, Q irreducible as a quotient of an irreducible M) lifts,
/// constant on classes, to a positive eigenvector of M with the same eigenvalue, which is then
/// M's Perron root. So the smallest root of `det(I − Q(u))` in (0, 1] is that of M, with a
/// polynomial of much smaller degree (the dragon's component collapses to a few classes).
fn lumped(
    succ: &[Vec<(usize, usize)>],
    nodes: &[usize],
    inside: impl Fn(usize) -> bool,
) -> (usize, Vec<Vec<Vec<usize>>>, Vec<usize>) {
    use std::collections::HashMap;
    let pos = |v: usize| nodes.binary_search(&v).expect("member");
    let mut class = vec![0usize; nodes.len()];
    let mut count = 1;
    let signature = |v: usize, class: &[usize]| {
        let mut sig: Vec<(usize, usize)> = succ[v]
            .iter()
            .filter(|(w, _)| inside(*w))
            .map(|&(w, e)| (class[pos(w)], e))
            .collect();
        sig.sort_unstable();
        (class[pos(v)], sig)
    };
    loop {
        let mut ids: HashMap<(usize, Vec<(usize, usize)>), usize> = HashMap::new();
        let next: Vec<usize> = nodes
            .iter()
            .map(|&v| {
                let sig = signature(v, &class);
                let n = ids.len();
                *ids.entry(sig).or_insert(n)
            })
            .collect();
        let refined = ids.len();
        class = next;
        if refined == count {
            break;
        }
        count = refined;
    }
    let mut entries = vec![vec![Vec::new(); count]; count];
    let mut done = vec![false; count];
    for (i, &v) in nodes.iter().enumerate() {
        if done[class[i]] {
            continue;
        }
        done[class[i]] = true;
        for &(w, e) in succ[v].iter().filter(|(w, _)| inside(*w)) {
            entries[class[i]][class[pos(w)]].push(e);
        }
    }
    (count, entries, class)
}

/// Whether the graph restricted to `nodes` (a component, as a membership test) and to the edges
/// `keep` accepts has a cycle (depth-first search for a back edge).
fn has_cycle(
    succ: &[Vec<(usize, usize)>],
    inside: impl Fn(usize) -> bool,
    keep: impl Fn(usize) -> bool,
) -> bool {
    // 0 unvisited, 1 on the path, 2 done.
    let mut state = vec![0u8; succ.len()];
    for root in (0..succ.len()).filter(|&v| inside(v)) {
        if state[root] != 0 {
            continue;
        }
        state[root] = 1;
        let mut call = vec![(root, 0usize)];
        while let Some(&(v, i)) = call.last() {
            if i < succ[v].len() {
                call.last_mut().expect("non-empty").1 += 1;
                let (w, k) = succ[v][i];
                if !inside(w) || !keep(k) {
                    continue;
                }
                match state[w] {
                    0 => {
                        state[w] = 1;
                        call.push((w, 0));
                    }
                    1 => return true,
                    _ => {}
                }
            } else {
                state[v] = 2;
                call.pop();
            }
        }
    }
    false
}

/// Whether a cyclic part's attractors are tiles, or why not.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum Tiling {
    /// The part's similarity dimension is exactly 2 in the plane and the open-set condition
    /// holds for it (proved, with a witness): its attractors have positive Lebesgue measure and
    /// are the closure of their interior (module doc, "When it applies").
    Tile,
    /// The part's similarity dimension is < 2 (exact): its attractors have Lebesgue measure 0,
    /// no interior, and each is its own boundary.
    NoInterior,
    /// Not known to be a tile, and why: not in the plane, the similarity dimension is > 2 or
    /// not separated from 2, or the open-set condition is not proved.
    Unknown(String),
}

/// Whether the part's attractors are tiles ([`Tiling`]), decided exactly from its witness:
/// `s = 2` is `u* = σ` (found exactly, `rational == Some(2)`), `s < 2` by certified enclosures
/// of `s ≠ 2`.
pub(crate) fn part_tiling(m: &AutomatonModel, part: &PartWitness) -> Tiling {
    let two = BigRational::from_integer(2.into());
    let value = PartValue {
        u: part.u.clone(),
        sigma: part.sigma.clone(),
        exact: String::new(),
        rational: part.rational.clone(),
    };
    let against = PartValue {
        rational: Some(two.clone()),
        ..value.clone()
    };
    let order = match &part.rational {
        Some(r) => r.cmp(&two),
        None => compare(&m.field, &value, &against),
    };
    if order == Ordering::Less {
        return Tiling::NoInterior;
    }
    if m.space != 2 {
        return Tiling::Unknown("the boundary dimension is computed in the plane only".into());
    }
    if order == Ordering::Greater || part.rational.is_none() {
        return Tiling::Unknown(
            "the similarity dimension is above 2 (the pieces overlap) or not separated from 2"
                .into(),
        );
    }
    let osc = part.open_set.is_some()
        || matches!(part.neighbour_maps, Some(NeighbourWitness::Holds { .. }));
    if osc {
        Tiling::Tile
    } else {
        Tiling::Unknown(
            "the similarity dimension is 2 but the open-set condition is not proved".into(),
        )
    }
}

/// Why no cyclic part of the similarity dimension is a tile ([`part_tiling`]), or `None` when
/// some part is one (its states get a boundary dimension).
pub fn not_a_tile(m: &AutomatonModel, sim: &SimilarityDimension) -> Option<String> {
    let verdicts: Vec<Tiling> = sim.witness.iter().map(|p| part_tiling(m, p)).collect();
    if verdicts.contains(&Tiling::Tile) {
        return None;
    }
    if verdicts.iter().all(|t| *t == Tiling::NoInterior) {
        return Some(
            "not a tile: similarity dimension < 2, so the attractor has no interior and is its own boundary".into(),
        );
    }
    let why: Vec<String> = verdicts
        .into_iter()
        .filter_map(|t| match t {
            Tiling::Unknown(w) => Some(w),
            _ => None,
        })
        .collect();
    Some(format!("not known to be a tile: {}", why.join("; ")))
}

/// The kept maps of the part's open-set search when the neighbour maps proved the condition
/// (the same coordinates as [`neighbour_system`], so the same search): no need to run it again.
fn closed_of(part: &PartWitness) -> Option<Closed> {
    match &part.neighbour_maps {
        Some(NeighbourWitness::Holds {
            radius,
            margin,
            maps,
            ..
        }) => Some(Closed {
            radius: radius.clone(),
            margin: margin.clone(),
            maps: maps
                .iter()
                .map(|h| {
                    (
                        h.q,
                        h.r,
                        KAffine {
                            a: h.a.clone(),
                            b: h.b.clone(),
                        },
                    )
                })
                .collect(),
        }),
        _ => None,
    }
}

/// The boundary dimension of every state of the automaton's tiles: the states of the cyclic
/// parts of `sim` (the similarity dimension of the same automaton and operators) whose
/// attractors are tiles ([`part_tiling`]), with `digits` certified digits, or why it is not
/// decided (and [`not_a_tile`]'s reason when no part is a tile).
pub fn boundary_dimension(
    m: &AutomatonModel,
    ops: &[KMatrix],
    sim: &SimilarityDimension,
    digits: usize,
) -> Result<BoundaryDimension, NotApplicable> {
    if let Some(why) = not_a_tile(m, sim) {
        return Err(why);
    }
    let a = &m.automaton;
    let k = &m.field;
    let frames = frames(m, ops);
    let mut states = Vec::new();
    let mut graphs = Vec::new();
    let mut others = Vec::new();
    for (index, part) in sim.witness.iter().enumerate() {
        if part_tiling(m, part) != Tiling::Tile {
            others.extend(part.states.iter().map(|&s| a.states[s].name.clone()));
            continue;
        }
        let system = neighbour_system(m, ops, &frames, &part.states)
            .map_err(|why| format!("no neighbour maps: {why}"))?;
        let (closed, witness) = match closed_of(part) {
            Some(c) => (c, None),
            None => match search(k, &system.centres, &system.edges) {
                Search::Closed(c) => {
                    let witness = NeighbourWitness::Holds {
                        coordinates: system.coordinates,
                        centres: system.centres.clone(),
                        radius: c.radius.clone(),
                        margin: c.margin.clone(),
                        maps: c
                            .maps
                            .iter()
                            .map(|(q, r, h)| NeighbourMap {
                                q: *q,
                                r: *r,
                                a: h.a.clone(),
                                b: h.b.clone(),
                            })
                            .collect(),
                        scales: system.scales.clone(),
                    };
                    (c, Some(witness))
                }
                Search::Identity(..) => {
                    return Err("the identity is a neighbour map (two pieces coincide)".into())
                }
                Search::Undecided(why) => return Err(format!("not decided: {why}")),
            },
        };
        let graph = map_graph(k, &system.centres, &system.edges, &closed)
            .ok_or("the kept neighbour maps are not closed under refinement")?;
        let exponent = |e: &MapEdge| -> Result<usize, NotApplicable> {
            if !e.left {
                return Ok(0);
            }
            let o = system.operators[e.operator];
            part.exponents
                .iter()
                .find(|x| x.0 == o)
                .map(|x| x.1 as usize)
                .ok_or_else(|| format!("no exponent for operator {o}"))
        };
        let succ: Vec<Vec<(usize, usize)>> = graph
            .iter()
            .map(|kids| {
                kids.iter()
                    .map(|e| Ok((e.child, exponent(e)?)))
                    .collect::<Result<_, NotApplicable>>()
            })
            .collect::<Result<_, _>>()?;
        let plain: Vec<Vec<usize>> = succ
            .iter()
            .map(|v| v.iter().map(|x| x.0).collect())
            .collect();
        let (comp, count) = strong_components(&plain);
        if has_cycle(&succ, |_| true, |k| k == 0) {
            return Err("a cycle of the boundary graph has only edges of ratio 1".into());
        }
        // Members of every component (increasing), and the cyclic ones' values.
        let mut members = vec![Vec::new(); count];
        for (v, &c) in comp.iter().enumerate() {
            members[c].push(v);
        }
        let mut values: Vec<Option<BoundaryComponent>> = Vec::with_capacity(count);
        for (c, nodes) in members.iter().enumerate() {
            let cyclic = nodes.len() > 1 || succ[nodes[0]].iter().any(|x| x.0 == nodes[0]);
            if !cyclic {
                values.push(None);
                continue;
            }
            let (classes, entries, class) = lumped(&succ, nodes, |w| comp[w] == c);
            if classes > MAX_COMPONENT {
                return Err(format!(
                    "not decided: a component of the boundary graph has {classes} classes of nodes (limit {MAX_COMPONENT})"
                ));
            }
            let poly = part_polynomial(classes, &entries);
            let u = smallest_root(&poly)?;
            let (exact, rational) = match odd_integer_value(k, &u, &part.sigma) {
                Some(j) => (j.to_string(), Some(BigRational::from_integer(j.into()))),
                None => exact_text(k, &u, &part.sigma),
            };
            values.push(Some(BoundaryComponent {
                nodes: nodes.clone(),
                classes: class,
                poly,
                u,
                rational,
                exact,
            }));
        }
        let value = |c: &BoundaryComponent| PartValue {
            u: c.u.clone(),
            sigma: part.sigma.clone(),
            exact: c.exact.clone(),
            rational: c.rational.clone(),
        };
        // The cyclic components ranked by value once (certified comparisons), so that the best
        // one reachable is a maximum of ranks.
        let mut order: Vec<usize> = (0..count).filter(|&c| values[c].is_some()).collect();
        order.sort_by(|&i, &j| {
            compare(
                k,
                &value(values[i].as_ref().expect("cyclic")),
                &value(values[j].as_ref().expect("cyclic")),
            )
        });
        let mut rank = vec![0usize; count];
        for (r, &c) in order.iter().enumerate() {
            rank[c] = r;
        }
        let better = |x: Option<usize>, y: Option<usize>| match (x, y) {
            (Some(i), Some(j)) => Some(if rank[j] > rank[i] { j } else { i }),
            (x, None) => x,
            (None, y) => y,
        };
        // The best cyclic component reachable from each component (successors come first).
        let mut best: Vec<Option<usize>> = vec![None; count];
        for c in 0..count {
            let mut b = values[c].as_ref().map(|_| c);
            for &v in &members[c] {
                for &(w, _) in &succ[v] {
                    if comp[w] != c {
                        b = better(b, best[comp[w]]);
                    }
                }
            }
            best[c] = b;
        }
        let kept = (0..graph.len())
            .filter(|&v| best[comp[v]].is_some())
            .count();
        // The cyclic components in the certificate's order: by smallest node.
        let mut listed: Vec<usize> = (0..count).filter(|&c| values[c].is_some()).collect();
        listed.sort_by_key(|&c| members[c][0]);
        let mut dominant = Vec::with_capacity(part.states.len());
        for (i, &s) in part.states.iter().enumerate() {
            let mut b = None;
            for (v, (q, r, _)) in closed.maps.iter().enumerate() {
                if *q == i || *r == i {
                    b = better(b, best[comp[v]]);
                }
            }
            let (exact, decimal) = match b {
                Some(c) => {
                    let v = value(values[c].as_ref().expect("cyclic"));
                    (v.exact.clone(), certified_decimal(k, &v, digits))
                }
                None => ("0".into(), format!("0.{}", "0".repeat(digits.max(1)))),
            };
            dominant.push(b.map(|c| listed.iter().position(|&x| x == c).expect("cyclic")));
            states.push(StateBoundary {
                state: a.states[s].name.clone(),
                exact,
                decimal,
            });
        }
        graphs.push(BoundaryGraph {
            part: index,
            states: part.states.clone(),
            witness,
            nodes: graph.len(),
            kept,
            components: listed
                .iter()
                .map(|&c| values[c].take().expect("cyclic"))
                .collect(),
            dominant,
        });
    }
    let sizes: Vec<String> = graphs
        .iter()
        .map(|g| {
            format!(
                "{} neighbour maps, {} on or leading to a cycle, {} cyclic components",
                g.nodes,
                g.kept,
                g.components.len()
            )
        })
        .collect();
    let skipped = if others.is_empty() {
        String::new()
    } else {
        format!(
            "; states {} are not tiles and get no value",
            others.join(", ")
        )
    };
    Ok(BoundaryDimension {
        states,
        upper_bound: true,
        note: format!(
            "an upper bound of the dimension of the boundary of each tile as seen by its neighbour pieces (the set where pieces touch): exact Mauldin–Williams value of the graph of neighbour maps ({}); it is the dimension when the dominant component's sets are non-empty and satisfy the open-set condition, not proved here{skipped}",
            sizes.join("; ")
        ),
        graphs,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::input::library::{load_any, Loaded};

    /// A library automaton, its resolved operators and its similarity dimension (12 digits).
    fn analysed(name: &str) -> (AutomatonModel, Vec<KMatrix>, SimilarityDimension) {
        let Loaded::Automaton { model, .. } = load_any(name).expect("library input") else {
            panic!("{name} is an automaton");
        };
        let r = crate::analysis::automata::automaton_resolve::resolve(&model, &[], 64)
            .expect("resolves");
        let sim = crate::analysis::automata::similarity::similarity_dimension(&model, &r.ops, 12)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        (*model, r.ops, sim)
    }

    fn run(name: &str) -> BoundaryDimension {
        let (model, ops, sim) = analysed(name);
        boundary_dimension(&model, &ops, &sim, 12).unwrap_or_else(|e| panic!("{name}: {e}"))
    }

    #[test]
    fn the_dragon_s_polynomial_has_the_factor_2u3_plus_u_minus_1() {
        // Heighway's dragon: both maps of ratio 1/√2, σ = 1/2, u = 2^(−s/2). The published
        // boundary dimension (Chang–Zhang; Duvall–Keesling) is 2·log₂ λ with λ³ − λ² − 2 = 0;
        // with u = 1/λ that is 1 = u + 2u³, so the dominant component's det(I − Q(u)) must
        // have the factor 2u³ + u − 1 and u* is its root: s = 1.52362708620249…
        let b = run("heighway-dragon");
        let cubic = Poly::from_ints(&[-1, 1, 0, 2]);
        let g = &b.graphs[0];
        assert!(
            g.components
                .iter()
                .any(|c| c.poly.rem(&cubic).is_zero() && c.poly.deg() > 0),
            "{:?}",
            g.components
        );
        assert!(g.kept <= g.nodes && g.kept > 0);
        for s in &b.states {
            assert!(s.decimal.starts_with("1.523627086202"), "{s:?}");
            assert!(s.exact.contains("x^3 + 1/2*x - 1/2"), "{s:?}");
        }
    }

    #[test]
    fn robinson_triangles_touch_along_segments_of_dimension_exactly_one() {
        // Straight-edged triangles meet along segments: u* = √σ, recognised exactly as s = 1.
        let b = run("penrose-robinson");
        assert_eq!(b.states.len(), 2);
        for s in &b.states {
            assert_eq!(s.exact, "1", "{s:?}");
        }
    }

    fn tiling(name: &str) -> Vec<Tiling> {
        let (model, _, sim) = analysed(name);
        sim.witness.iter().map(|p| part_tiling(&model, p)).collect()
    }

    #[test]
    fn only_parts_of_similarity_dimension_two_with_the_open_set_condition_are_tiles() {
        // log 3/log 2 < 2: no interior. Robinson triangles and the dragon: s = 2, open set proved.
        assert_eq!(tiling("sierpinski-triangle"), vec![Tiling::NoInterior]);
        assert_eq!(tiling("sierpinski-carpet"), vec![Tiling::NoInterior]);
        assert_eq!(tiling("penrose-robinson"), vec![Tiling::Tile]);
        assert_eq!(tiling("heighway-dragon"), vec![Tiling::Tile]);
    }

    #[test]
    fn lumping_keeps_the_spectral_radius_equation() {
        // Two nodes 0 ⇄ 1 with exponent 1 each way and one self-loop of exponent 1 on each:
        // both nodes look alike, one class with entries [1, 1]: det = 1 − 2u, u* = 1/2
        // (the full matrix [[u, u], [u, u]] has det(I − M) = 1 − 2u too).
        let succ = vec![vec![(0, 1), (1, 1)], vec![(0, 1), (1, 1)]];
        let (n, e, class) = lumped(&succ, &[0, 1], |_| true);
        assert_eq!((n, &e, &class), (1, &vec![vec![vec![1, 1]]], &vec![0, 0]));
        assert_eq!(part_polynomial(n, &e), Poly::from_ints(&[1, -2]));
        // A cycle of exponent-0 edges only is found; one with a contracting edge is not counted.
        let zero_cycle = vec![vec![(1, 0)], vec![(0, 0)]];
        assert!(has_cycle(&zero_cycle, |_| true, |k| k == 0));
        let mixed = vec![vec![(1, 0)], vec![(0, 1)]];
        assert!(!has_cycle(&mixed, |_| true, |k| k == 0));
    }
}
