//! The valences of the limit complex, decided on the strongly connected classes of the sector
//! graph: bounded, with the value every born vertex settles at, or unbounded, with a sector that
//! comes back to itself with more sectors as witness.

use super::link::{canonical, Item, Local};
use crate::error::{Error, Result};
use crate::topology::class::strong_components;
use crate::topology::closure::TypeSet;
use num_bigint::BigUint;
use serde::Serialize;
use std::collections::{BTreeSet, HashMap};

/// A sector named for people: a face type in notation and one of its corners.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct SectorName {
    /// The face type, in canonical notation.
    pub face: String,
    /// The corner: the start of boundary side `corner` (0-based, canonical rotation).
    pub corner: usize,
}

/// Why the valence grows without bound: a sector that comes back to itself with more sectors.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct GrowthWitness {
    /// The sector that reproduces itself.
    pub sector: SectorName,
    /// The sectors it steps through, from it back to it (`period + 1` entries).
    pub cycle: Vec<SectorName>,
    /// The number of steps p of the cycle.
    pub period: usize,
    /// How many more sectors (hence edges at the vertex) it has become after p steps, ≥ 1.
    pub gained: String,
}

/// The valences of the limit complex (every level together: valences never decrease).
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum LimitValence {
    /// Every vertex's valence settles; the values every born vertex settles at.
    Bounded {
        /// The largest valence at any level and in the limit.
        max_valence: usize,
        /// The valences of the vertices of the limit, ascending.
        valences: Vec<usize>,
    },
    /// Some vertex's valence grows without bound.
    Unbounded {
        /// The sector that proves it.
        witness: GrowthWitness,
    },
}

impl std::fmt::Display for LimitValence {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            LimitValence::Bounded { max_valence, valences } => {
                let v: Vec<String> = valences.iter().map(|v| v.to_string()).collect();
                write!(f, "bounded: largest valence {max_valence} (limit valences {})", v.join(", "))
            }
            LimitValence::Unbounded { witness: w } => write!(
                f,
                "unbounded: corner {} of `{}` comes back to itself after {} step{} with {} more sector{}",
                w.sector.corner,
                w.sector.face,
                w.period,
                if w.period == 1 { "" } else { "s" },
                w.gained,
                if w.gained == "1" { "" } else { "s" }
            ),
        }
    }
}

/// The valences of the limit complex.
///
/// A sector (face type, corner) steps to the sectors of the sub-faces at that corner, never to
/// none, so the sectors form a non-erasing substitution and the length of what a sector becomes
/// after k steps, L_k, never decreases in k (by induction: L_1 ≥ 1 = L_0, and L_{k+1}(a) =
/// Σ_{b in fan(a)} L_k(b) ≥ Σ L_{k−1}(b) = L_k(a)). Every corner of every reached type is a corner
/// of some vertex. Two cases, decided on the strongly connected classes of the sector graph:
/// - some class on a cycle holds a sector whose fan has two or more sectors: that sector comes back
///   to itself after p steps together with at least one more sector, so a vertex holding it gains
///   an edge at least every p levels — the valence is unbounded (the witness);
/// - otherwise every sector on a cycle has a fan of one sector, L_∞ = 1 on cycles and L_∞(a) =
///   Σ L_∞(fan(a)) elsewhere (finite: the graph of classes is acyclic), and a vertex born with link
///   ℓ ends with valence Σ_{x ∈ ℓ} L_∞(x) (a hole counts 1). Valences never decrease, so the
///   largest of these is the largest valence at every level and in the limit.
pub(super) fn limit_valence(
    ts: &TypeSet,
    locals: &[Local],
    born: &[Vec<Item>],
) -> Result<LimitValence> {
    let mut index: HashMap<(usize, usize), usize> = HashMap::new();
    let mut sectors: Vec<(usize, usize)> = Vec::new();
    for (t, l) in locals.iter().enumerate() {
        for c in 0..l.corner_fan.len() {
            index.insert((t, c), sectors.len());
            sectors.push((t, c));
        }
    }
    let fan_of = |i: usize| -> Vec<usize> {
        let (t, c) = sectors[i];
        locals[t].corner_fan[c]
            .iter()
            .filter_map(|it| match *it {
                Item::Sector { ty, corner } => Some(index[&(ty, corner)]),
                Item::Hole => None,
            })
            .collect()
    };
    // Sinks first: every class is numbered below the classes that reach it.
    let fans: Vec<Vec<usize>> = (0..sectors.len()).map(fan_of).collect();
    let (class_of, _) = strong_components(&fans);
    let on_cycle = |i: usize| fan_of(i).iter().any(|&j| class_of[j] == class_of[i]);
    if let Some(b) = (0..sectors.len()).find(|&b| on_cycle(b) && fan_of(b).len() >= 2) {
        return Ok(LimitValence::Unbounded {
            witness: growth_witness(ts, &sectors, &class_of, &fan_of, b),
        });
    }
    let mut lim = vec![0usize; sectors.len()];
    let mut order: Vec<usize> = (0..sectors.len()).collect();
    order.sort_by_key(|&i| class_of[i]);
    for i in order {
        lim[i] = if on_cycle(i) {
            1
        } else {
            fan_of(i)
                .iter()
                .try_fold(0usize, |acc, &j| acc.checked_add(lim[j]))
                .ok_or_else(|| Error::Analysis("a limit valence above 2^64".into()))?
        };
    }
    let mut valences: BTreeSet<usize> = BTreeSet::new();
    for link in born {
        let v = canonical(link.clone())
            .iter()
            .map(|it| match *it {
                Item::Sector { ty, corner } => lim[index[&(ty, corner)]],
                Item::Hole => 1,
            })
            .sum::<usize>();
        valences.insert(v);
    }
    Ok(LimitValence::Bounded {
        max_valence: valences.iter().next_back().copied().unwrap_or(0),
        valences: valences.into_iter().collect(),
    })
}

/// The witness of unbounded valence: sector `b` lies on a cycle and its fan has two or more
/// sectors. The shortest cycle from `b` back to itself gives the period p; after p steps `b`
/// has become itself and `gained` more sectors (counted exactly along the p steps).
fn growth_witness(
    ts: &TypeSet,
    sectors: &[(usize, usize)],
    class_of: &[usize],
    fan_of: &dyn Fn(usize) -> Vec<usize>,
    b: usize,
) -> GrowthWitness {
    // Breadth-first search inside b's class for the shortest path back to b.
    let mut prev: HashMap<usize, usize> = HashMap::new();
    let mut queue = std::collections::VecDeque::from([b]);
    let mut back = None;
    'search: while let Some(u) = queue.pop_front() {
        for v in fan_of(u) {
            if class_of[v] != class_of[b] {
                continue;
            }
            if v == b {
                back = Some(u);
                break 'search;
            }
            if let std::collections::hash_map::Entry::Vacant(e) = prev.entry(v) {
                e.insert(u);
                queue.push_back(v);
            }
        }
    }
    let mut cycle = vec![b];
    let mut u = back.expect("b lies on a cycle of its class");
    while u != b {
        cycle.push(u);
        u = prev[&u];
    }
    cycle.push(b);
    cycle[1..].reverse();
    // Exact length of what b becomes after p steps: counts per sector, step by step.
    let p = cycle.len() - 1;
    let mut count: HashMap<usize, BigUint> = HashMap::from([(b, BigUint::from(1u32))]);
    for _ in 0..p {
        let mut next: HashMap<usize, BigUint> = HashMap::new();
        for (&i, k) in &count {
            for j in fan_of(i) {
                *next.entry(j).or_default() += k;
            }
        }
        count = next;
    }
    let after: BigUint = count.values().sum();
    let name = |i: usize| {
        let (t, c) = sectors[i];
        SectorName {
            face: ts.types[t].face.to_string(),
            corner: c,
        }
    };
    GrowthWitness {
        sector: name(b),
        cycle: cycle.iter().map(|&i| name(i)).collect(),
        period: p,
        gained: (after - 1u32).to_string(),
    }
}
