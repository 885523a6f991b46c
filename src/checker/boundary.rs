//! The step `boundary-dimension`: an upper bound of the dimension of the set where the pieces of
//! each state's attractor touch, for the states of a tile part, re-derived from the claim's
//! operators, the proved `similarity-dimension` step and the neighbour maps.
//!
//! **The sets.** For a neighbour map `h: r → q` of the part (`h = g_u⁻¹ ∘ g_v`) let
//! `B_h = A_q ∩ h(A_r)`, the points where the pieces `g_u(A_q)` and `g_v(A_r)` meet, seen in q's
//! coordinates. Refining the side of the smaller map splits it: when `ρ(h) ≤ 1`,
//! `B_h = ⋃_{e: q ← w} g_e(B_{g_e⁻¹ ∘ h})`, else `B_h = ⋃_{e: r ← w} B_{h ∘ g_e}`. The attractors
//! lie in the balls of the witness, so a child that fails the ball test has `B = ∅`; the
//! children that pass are in the set (the neighbour check proves it). So every `B_h` is covered
//! by the images of its children's sets under maps of ratio `ρ_e` (left) or 1 (right): a
//! graph-directed covering, whose Mauldin–Williams value bounds the Hausdorff and upper box
//! dimension of `B_h` (the covering argument; neither the open-set condition for the B sets nor
//! their non-emptiness is needed for the bound).
//!
//! **The value.** The checker rebuilds that graph itself (while checking the neighbour maps,
//! [`super::neighbour::refinements`]),
//! gives an edge refined on the left the exponent k of its operator (`ρ² = σ^k` on the frames,
//! proved by [`super::similarity::part_value`]; in the neighbour coordinates the ratios differ
//! by a factor per state, which cancels along every cycle, so the spectral radius is the same)
//! and an edge on the right the exponent 0. Edges of exponent 0 must form no cycle. For every
//! cyclic strongly connected component C (recomputed, compared with the listed ones) the
//! step's equitable partition is checked (nodes of one class have, class by class, the same
//! exponents on their edges inside C), so the quotient `Q(u)` has the spectral radius of
//! `M_C(u)` (a positive eigenvector of Q lifts to one of M). `u*`, the smallest root of
//! `det(I − Q(u))` in (0, 1], is where `ρ(M_C(u)) = 1` (ρ grows with u from `ρ(M_C(0)) = 0` and
//! an irreducible integer matrix has `ρ(M_C(1)) ≥ 1`), and `s_C = 2·ln u*/ln σ`.
//!
//! **A state's bound.** The maps with state q on either side reach some components; the bound
//! is the largest `s_C` among them, the smallest u*: the claimed component's u* must be the only
//! root in `(0, u*]` of the product of their polynomials (Sturm counts, u*'s interval narrowed
//! until decided). With no reachable cycle every set is finite or empty and the bound is 0.
//!
//! **Tiles.** The step applies to parts whose similarity dimension is exactly 2 in the plane;
//! the neighbour maps prove the open-set condition, so the attractors have positive area
//! (Mauldin–Williams) and are the closure of their interiors (Schief; its graph-directed
//! analogue is relied on, not re-proved): the set where pieces touch is then in the boundary of
//! each piece. The verdict says "at most": it is the dimension when the dominant component's
//! sets are non-empty and satisfy the open-set condition, which is not checked.

use super::control_graph::{cyclic_components, cyclic_parts, graph};
use super::enclosure::enclose_root;
use super::field::{self, Root, P};
use super::ifs::{instance, Checked, Field};
use super::neighbour::{refinements, Refinements};
use super::similarity::{
    check_digits, frames, part_polynomial, part_value, rational_value, roots_in, states_label,
    PartValue,
};
use super::Q;
use crate::certificate::{AutomatonClaim, BoundaryComponent, NeighbourMaps, SimilarityStep};
use num_traits::{One, Signed, Zero};
use std::cmp::Ordering;
use std::collections::VecDeque;

/// The most classes of one component's equitable partition.
const MAX_CLASSES: usize = 64;

/// The most bits to which a u* is narrowed to compare it with the other components' roots.
const MAX_BITS: u64 = 1 << 12;

/// The step `boundary-dimension`, after the proved `similarity-dimension` step `sim`.
pub(super) fn check_boundary(
    a: &AutomatonClaim,
    sim: Option<&(&SimilarityStep, Vec<Option<Refinements>>)>,
    b: &crate::certificate::BoundaryStep,
) -> Checked {
    let (sim, graphs) = sim.ok_or("no proved similarity-dimension step to take the parts from")?;
    let k = Field::of(a)?;
    let ops = instance(&k, a, &sim.instance)?;
    let g = graph(a)?;
    let parts = cyclic_parts(a, &g);
    let frames = frames(&k, a, &g, &ops)?;
    if b.parts.is_empty() {
        return Err("the step lists no tile part".into());
    }
    if b.digits == 0 || b.digits > 1000 {
        return Err(format!("{} digits: not in 1..=1000", b.digits));
    }
    let mut messages = Vec::new();
    let mut bounds = Vec::new();
    let mut last: Option<usize> = None;
    for bp in &b.parts {
        if last.is_some_and(|l| bp.part <= l) || bp.part >= parts.len().min(sim.parts.len()) {
            return Err(format!(
                "part {}: the parts must be indices of the similarity-dimension step's parts, increasing",
                bp.part
            ));
        }
        last = Some(bp.part);
        let members = &parts[bp.part];
        let sp = &sim.parts[bp.part];
        let label = states_label(a, members);
        let fail = |e: String| format!("part {{{label}}}: {e}");
        let (value, inside) = part_value(&k, a, &g, &ops, &frames, members, sp)?;
        if value.rational != Some(Q::from_integer(2.into())) {
            return Err(fail(
                "its similarity dimension is not proved to be exactly 2: not a tile".into(),
            ));
        }
        if frames[members[0]].as_ref().map(|f| f.rows) != Some(2) {
            return Err(fail(
                "the boundary dimension is checked in the plane only".into(),
            ));
        }
        // The part's own neighbour maps were checked by the similarity step, which kept
        // their graph; the step's are checked here.
        let own;
        let r = match (&bp.maps, &sp.neighbour_maps, graphs.get(bp.part)) {
            (Some(h), None, _) => {
                own = refinements(&k, a, &ops, &frames, members, &inside, h)
                    .map_err(|e| fail(format!("the neighbour maps: {e}")))?;
                &own
            }
            (None, Some(NeighbourMaps::Holds(_)), Some(Some(r))) => r,
            (Some(_), Some(_), _) => {
                return Err(fail(
                    "the part has its own neighbour maps: the step must not give others".into(),
                ))
            }
            _ => return Err(fail("no neighbour maps that hold for the part".into())),
        };
        let exponent = |o: usize| {
            sp.exponents
                .iter()
                .find(|x| x.0 == o)
                .map(|x| x.1)
                .expect("part_value checked the part's operators")
        };
        let n = r.ends.len();
        let mut succ: Vec<Vec<(usize, u32)>> = vec![Vec::new(); n];
        for &(i, j, o, left) in &r.edges {
            succ[i].push((j, if left { exponent(o) } else { 0 }));
        }
        let plain = |keep: &dyn Fn(u32) -> bool| -> Vec<Vec<usize>> {
            succ.iter()
                .map(|v| v.iter().filter(|x| keep(x.1)).map(|x| x.0).collect())
                .collect()
        };
        if !cyclic_components(&plain(&|e| e == 0), |_| true).is_empty() {
            return Err(fail(
                "a cycle of the boundary graph has only edges of ratio 1".into(),
            ));
        }
        let components = cyclic_components(&plain(&|_| true), |_| true);
        let listed: Vec<&Vec<usize>> = bp.components.iter().map(|c| &c.nodes).collect();
        if components.iter().collect::<Vec<_>>() != listed {
            return Err(fail(format!(
                "the components must be the {} cyclic strongly connected components of the graph of refinements, ordered by smallest node",
                components.len()
            )));
        }
        let mut polys = Vec::with_capacity(components.len());
        let mut values: Vec<PartValue> = Vec::with_capacity(components.len());
        for (c, comp) in bp.components.iter().enumerate() {
            let (poly, u, rational) = component_value(&k, &value, &succ, comp)
                .map_err(|e| fail(format!("component {c}: {e}")))?;
            polys.push(poly);
            values.push(PartValue {
                sigma: value.sigma.clone(),
                u,
                rational,
            });
        }
        let mut component_of = vec![usize::MAX; n];
        for (c, comp) in components.iter().enumerate() {
            for &v in comp {
                component_of[v] = c;
            }
        }
        if bp.states.len() != members.len() {
            return Err(fail(format!(
                "{} states listed for {} states",
                bp.states.len(),
                members.len()
            )));
        }
        for (state, claim) in members.iter().zip(&bp.states) {
            let name = &a.states[*state].name;
            // The components reachable from the maps with the state on either side.
            let mut seen = vec![false; n];
            let mut queue: VecDeque<usize> = (0..n)
                .filter(|&v| r.ends[v].0 == *state || r.ends[v].1 == *state)
                .collect();
            for &v in &queue {
                seen[v] = true;
            }
            let mut reach = vec![false; components.len()];
            while let Some(v) = queue.pop_front() {
                if component_of[v] != usize::MAX {
                    reach[component_of[v]] = true;
                }
                for &(w, _) in &succ[v] {
                    if !seen[w] {
                        seen[w] = true;
                        queue.push_back(w);
                    }
                }
            }
            match claim.component {
                None if reach.iter().any(|&x| x) => {
                    return Err(fail(format!(
                        "state {name}: a cyclic component is reachable, the bound is not 0"
                    )))
                }
                None => {
                    if super::parse_decimal(&claim.decimal, b.digits)? != 0.into() {
                        return Err(fail(format!(
                            "state {name}: no cycle is reachable, the bound is 0, not {}",
                            claim.decimal
                        )));
                    }
                }
                Some(c) if c >= components.len() || !reach[c] => {
                    return Err(fail(format!(
                        "state {name}: component {c} is not reachable from its maps"
                    )))
                }
                Some(c) => {
                    let product = (0..components.len())
                        .filter(|&x| reach[x])
                        .fold(vec![Q::one()], |acc, x| field::mul(&acc, &polys[x]));
                    largest(&product, &values[c].u).map_err(|e| {
                        fail(format!(
                            "state {name}: component {c} has not the largest value: {e}"
                        ))
                    })?;
                    check_digits(&k, &[&values[c]], &claim.decimal, b.digits)
                        .map_err(|e| fail(format!("state {name}: {e}")))?;
                }
            }
            bounds.push(format!("{name} ≤ {}…", claim.decimal));
        }
        messages.push(format!(
            "part {{{label}}} (s = 2, a tile): {} neighbour maps closed under refinement without the identity, {} refinements passing the ball test, {} cyclic component{} ({}); every state's component is the largest reachable (Sturm counts)",
            n,
            r.edges.len(),
            components.len(),
            if components.len() == 1 { "" } else { "s" },
            bp.components
                .iter()
                .zip(&values)
                .map(|(c, v)| {
                    let classes = c.classes.iter().max().map_or(0, |m| m.saturating_add(1));
                    match &v.rational {
                        Some(s) => format!("{} nodes in {classes} classes, s = {s}", c.nodes.len()),
                        None => format!(
                            "{} nodes in {classes} classes, u* algebraic of degree {}",
                            c.nodes.len(),
                            v.u.p.len() - 1
                        ),
                    }
                })
                .collect::<Vec<_>>()
                .join("; ")
        ));
    }
    Ok((
        messages.join("; "),
        format!(
            "boundary dimension {} (upper bounds of the dimension of the set where each state's pieces touch, from the graph of neighbour maps; {} digits)",
            bounds.join(", "),
            b.digits
        ),
    ))
}

/// One component's `det(I − Q(u))`, u* and rational value, with its equitable partition
/// checked.
fn component_value(
    k: &Field,
    part: &PartValue,
    succ: &[Vec<(usize, u32)>],
    c: &BoundaryComponent,
) -> Result<(P, Root, Option<Q>), String> {
    if c.classes.len() != c.nodes.len() {
        return Err(format!(
            "{} classes for {} nodes",
            c.classes.len(),
            c.nodes.len()
        ));
    }
    if let Some(x) = c.classes.iter().find(|&&x| x >= c.nodes.len()) {
        return Err(format!(
            "class {x}: the classes of {} nodes are numbered below {}",
            c.nodes.len(),
            c.nodes.len()
        ));
    }
    let count = c.classes.iter().max().map_or(0, |m| m + 1);
    if count > MAX_CLASSES {
        return Err(format!(
            "{count} classes: the checker reads at most {MAX_CLASSES}"
        ));
    }
    let mut used = vec![false; count];
    for &x in &c.classes {
        used[x] = true;
    }
    if used.contains(&false) {
        return Err("the classes must be numbered 0, 1, … without a gap".into());
    }
    super::within_work(
        "the boundary component",
        (c.nodes.len() as u128 + 1) * (count as u128).pow(4) * 64,
    )?;
    let class = |w: usize| c.nodes.binary_search(&w).ok().map(|i| c.classes[i]);
    // Every node's edges inside the component, as sorted (class, exponent) pairs.
    let mut signature: Vec<Option<Vec<(usize, u32)>>> = vec![None; count];
    for (&v, &x) in c.nodes.iter().zip(&c.classes) {
        let mut sig: Vec<(usize, u32)> = succ[v]
            .iter()
            .filter_map(|&(w, e)| class(w).map(|y| (y, e)))
            .collect();
        sig.sort_unstable();
        match &signature[x] {
            None => signature[x] = Some(sig),
            Some(s) if *s == sig => {}
            Some(_) => {
                return Err(format!(
                    "the partition is not equitable: node {v} of class {x} has other edges than the first node of its class"
                ))
            }
        }
    }
    let mut entries = vec![vec![Vec::new(); count]; count];
    for (x, sig) in signature.iter().enumerate() {
        for &(y, e) in sig.as_ref().expect("every class is used") {
            entries[x][y].push(e);
        }
    }
    let d = part_polynomial(count, &entries)?;
    let u = Root::isolate(&c.u.poly, &c.u.lo, &c.u.hi, "u*")?;
    if !u.is_zero(&d) {
        return Err("u* is not a root of det(I − Q(u))".into());
    }
    if u.lo.is_negative() || u.cmp_rational(&Q::one()) == Ordering::Greater {
        return Err("u* is not in (0, 1]".into());
    }
    largest(&d, &u).map_err(|e| {
        format!("u* is not shown to be the smallest positive root of det(I − Q(u)): {e}")
    })?;
    let rational = match &c.rational {
        None => None,
        Some(s) => Some(rational_value(k, &part.sigma, &u, None, s)?),
    };
    Ok((d, u, rational))
}

/// Checks that the root u is the only root of `p` (which has it) in `(0, u]`: the smallest
/// positive root (of a component's polynomial; of the product over the components a state
/// reaches: the largest value). u's interval is narrowed until the Sturm counts decide.
fn largest(p: &[Q], u: &Root) -> Result<(), String> {
    let mut bits = 32u64;
    loop {
        let (lo, hi) = match u.p.len() == 2 {
            true => (u.lo.clone(), u.lo.clone()),
            false => enclose_root(u, bits)?,
        };
        if lo == hi {
            // A rational u: it is the one root in (0, u].
            return match roots_in(p, &Q::zero(), &lo) {
                1 => Ok(()),
                _ => Err("another root lies below u*".into()),
            };
        }
        if roots_in(p, &Q::zero(), &lo) > 0 {
            return Err(format!("another root lies in (0, {lo}], below u*"));
        }
        if roots_in(p, &Q::zero(), &hi) == 1 {
            return Ok(());
        }
        if bits >= MAX_BITS {
            return Err(format!(
                "not separated from the other roots at {MAX_BITS} bits"
            ));
        }
        bits *= 2;
    }
}
