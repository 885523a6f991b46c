//! What the mesh must be, from the exact topology alone (no coordinates): the number of
//! components and the number of holes of each, hence the Euler characteristic `2 − 2·holes` of
//! each component's surface (THEORY §11).
//!
//! The holes are counted as in `crate::measure::exact_topology` — a central lacuna per
//! non-delayed cell subdivided, a hole per two halves of a gap on a shared `Cn` edge, a gap on a
//! free edge being a notch — but separately for the start faces of each component of the start
//! assembly. When the sub-faces of every type are connected through their spokes, the components
//! of every level are in bijection with those of the assembly (`crate::component`), and this
//! gives the holes of each component. Otherwise only the totals are known exactly (`per_start` is
//! `None`) and the mesh is checked against them.

use super::below::{components_by_induction, exact_topology, start_components, Instance};
use crate::topology::EdgeKind;
use num_bigint::BigUint;
use num_traits::{ToPrimitive, Zero};
use std::collections::BTreeMap;

/// The exact expectations at one level.
#[derive(Clone, Debug)]
pub struct Expected {
    /// Components of the union of the level-n cells.
    pub components: u64,
    /// Holes of the union.
    pub holes: BigUint,
    /// When the components are those of the start assembly: for each start face, its component
    /// (numbered in order of first start face) and the holes of each such component.
    pub per_start: Option<(Vec<usize>, Vec<BigUint>)>,
}

impl Expected {
    /// The Euler characteristic the surface of a component with `holes` holes must have.
    pub fn euler(holes: &BigUint) -> Option<i64> {
        holes
            .to_i64()
            .and_then(|h| 2i64.checked_sub(h.checked_mul(2)?))
    }
}

/// The start components of the assembly, numbered in order of their first start face.
fn start_component_of(inst: &Instance) -> Vec<usize> {
    let n = inst.start.len();
    let mut parent: Vec<usize> = (0..n).collect();
    fn find(p: &mut [usize], mut x: usize) -> usize {
        while p[x] != x {
            p[x] = p[p[x]];
            x = p[x];
        }
        x
    }
    for [a, b] in &inst.glue {
        let (ra, rb) = (find(&mut parent, a.0), find(&mut parent, b.0));
        parent[ra] = rb;
    }
    let mut number: BTreeMap<usize, usize> = BTreeMap::new();
    (0..n)
        .map(|f| {
            let r = find(&mut parent, f);
            let next = number.len();
            *number.entry(r).or_insert(next)
        })
        .collect()
}

/// The holes at `level` of the union of the cells descending from the start faces `faces`.
fn holes_of(inst: &Instance, faces: &[usize], level: u32) -> BigUint {
    let ts = &inst.types;
    let mut states: BTreeMap<(usize, Vec<bool>), BigUint> = BTreeMap::new();
    for &f in faces {
        let s = &inst.start[f];
        *states.entry((s.ty, s.free.clone())).or_default() += 1u32;
    }
    let (mut centre, mut interior_halves) = (BigUint::zero(), BigUint::zero());
    for _ in 0..level {
        let mut next: BTreeMap<(usize, Vec<bool>), BigUint> = BTreeMap::new();
        for ((t, free), c) in &states {
            let face = &ts.types[*t].face;
            if face.delay == 1 {
                centre += c;
            }
            for (i, e) in face.boundary.iter().enumerate() {
                if e.kind == EdgeKind::C && !e.is_delayed() && !free[i] {
                    interior_halves += c * (e.n - 1);
                }
            }
            for (k, &w) in ts.types[*t].children.iter().enumerate() {
                *next.entry((w, inst.child_free(*t, k, free))).or_default() += c;
            }
        }
        states = next;
    }
    centre + interior_halves / 2u32
}

/// The exact components and holes at `level`, per start component when the induction of
/// `crate::component` holds. The per-component holes are checked to add up to the holes of
/// [`exact_topology`].
pub fn expected(inst: &Instance, level: u32) -> Result<Expected, String> {
    let topo = exact_topology(inst, level)?;
    let top = &topo[level as usize];
    let per_start = match components_by_induction(&inst.types, &inst.glue) {
        Ok(c) => {
            let of = start_component_of(inst);
            debug_assert_eq!(c, start_components(inst.start.len(), &inst.glue));
            let n = of.iter().max().map_or(0, |m| m + 1);
            let holes: Vec<BigUint> = (0..n)
                .map(|k| {
                    let faces: Vec<usize> = (0..of.len()).filter(|&f| of[f] == k).collect();
                    holes_of(inst, &faces, level)
                })
                .collect();
            let sum: BigUint = holes.iter().sum();
            if sum != top.holes || n as u64 != top.components {
                return Err(format!(
                    "level {level}: the holes of the components add up to {sum} and there are {n} of them, the exact topology says {} holes and {} components",
                    top.holes, top.components
                ));
            }
            Some((of, holes))
        }
        Err(_) => None,
    };
    Ok(Expected {
        components: top.components,
        holes: top.holes.clone(),
        per_start,
    })
}
