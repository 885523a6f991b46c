//! The degeneracy step (THEORY §6): which corners of the level-1 complexes the constraints force
//! to coincide, and which cells the combinatorics makes flat.
//!
//! **Corners.** The checker builds the level-1 complex of every listed face type with its own
//! subdivision (`solid.rs`, the cells of `face-homology`): corner `i` of sub-face `k` is the
//! class of the start of its side `i`. In the placement of the type's control points, that
//! corner is column `o_w(i) mod m_w` of the sub-face operator `T_k` (`o_w(i)` the first point of
//! boundary edge `i` of the sub-face's type `w`): `m_t` unknowns of the proved system. On the
//! proved solution set `particular + span(basis)` every unknown `x` is the affine function
//! `x = particular[x] + Σ_j t_j·basis_j[x]` of the free parameters, and the basis vectors are
//! independent (each is 1 at its own free unknown, 0 at the others), so two unknowns are equal
//! on every solution exactly when these expressions are equal term by term. Two corners
//! coincide on every solution, whatever the parent's control points, exactly when their
//! columns are equal on every solution. The classes of corners with equal expressions must be
//! exactly the classes the step's pairs join: a missing pair is a forced collapse left out, an
//! extra pair one that does not exist.
//!
//! **Flat cells.** A Cantor edge has two control points and every control point of its pieces
//! is a barycentric combination of them, so its attractor lies on its chord; a face of two
//! Cantor edges, and a lacuna of two sides that are Cantor edges, enclose no area on any
//! solution. The checker lists them from the closure's types and requires the step's lists.

use super::closure::subdivide;
use super::face_homology::level_one_corners;
use super::system::{layout, solution_layout, Layout};
use super::{rat, within_work, Checked, Q};
use crate::certificate::{
    ClosureStep, DegeneracyStep, Kind, Origin, SolutionStep, VolumeSystemStep,
};
use std::collections::{BTreeSet, HashMap};

/// An unknown's affine expression on the solution set: the particular value and the nonzero
/// coefficients of the free parameters, by basis index.
type Expr = (Q, Vec<(usize, Q)>);

/// The affine expression of every unknown the certificate's basis or particular solution
/// touches (the others are 0 on every solution).
fn expressions(
    particular: &[(usize, String)],
    basis: &[Vec<(usize, String)>],
) -> Result<HashMap<usize, Expr>, String> {
    let entries = particular.len() + basis.iter().map(Vec::len).sum::<usize>();
    within_work("the degeneracy step's expressions", 64 * entries as u128)?;
    let mut out: HashMap<usize, Expr> = HashMap::new();
    for (x, v) in particular {
        let v = rat(v)?;
        let e = out.entry(*x).or_default();
        e.0 += v;
    }
    for (j, b) in basis.iter().enumerate() {
        for (x, v) in b {
            out.entry(*x).or_default().1.push((j, rat(v)?));
        }
    }
    for e in out.values_mut() {
        // Coefficients of one parameter listed twice add up; zeros are dropped.
        let mut merged: Vec<(usize, Q)> = Vec::with_capacity(e.1.len());
        for (j, v) in std::mem::take(&mut e.1) {
            match merged.last_mut() {
                Some((k, w)) if *k == j => *w += v,
                _ => merged.push((j, v)),
            }
        }
        merged.retain(|(_, v)| *v != Q::default());
        e.1 = merged;
    }
    Ok(out)
}

/// The smallest member of each element's class, for classes given by equal keys.
fn classes_by_key<K: std::hash::Hash + Eq>(keys: Vec<K>) -> Vec<usize> {
    let mut first: HashMap<K, usize> = HashMap::new();
    keys.into_iter()
        .enumerate()
        .map(|(i, k)| *first.entry(k).or_insert(i))
        .collect()
}

/// The smallest member of each element's class, for classes joined by `pairs`.
fn classes_by_pairs(n: usize, pairs: &[(usize, usize)]) -> Vec<usize> {
    let mut parent: Vec<usize> = (0..n).collect();
    fn find(p: &mut [usize], mut x: usize) -> usize {
        while p[x] != x {
            p[x] = p[p[x]];
            x = p[x];
        }
        x
    }
    for &(a, b) in pairs {
        let (ra, rb) = (find(&mut parent, a), find(&mut parent, b));
        // The smaller root stays: every class ends at its smallest member.
        parent[ra.max(rb)] = ra.min(rb);
    }
    (0..n).map(|x| find(&mut parent, x)).collect()
}

/// Checks the degeneracy step against the proved closure (degree `q`) and solution space.
pub(super) fn check_degeneracy(
    d: &DegeneracyStep,
    c: &ClosureStep,
    q: usize,
    s: &SolutionStep,
) -> Checked {
    let (lay, column) = solution_layout(c, q, s)?;
    let expr = expressions(&s.particular, &s.basis)?;
    check_with(d, c, &lay, &column, &expr)
}

/// Checks a degeneracy step that follows a proved `volume-solution-space` step: the corners of
/// the level-1 complexes of the surfaces' face types, on the volume system's solution set (its
/// first unknowns are the face operators' entries, in the checker's layout order).
pub(super) fn check_volume_degeneracy(d: &DegeneracyStep, s: &VolumeSystemStep) -> Checked {
    let lay = layout(&s.faces, s.degree, None)?;
    let column: Vec<usize> = (0..lay.names.len()).collect();
    let expr = expressions(&s.particular, &s.basis)?;
    check_with(d, &s.faces, &lay, &column, &expr)
}

/// The check itself, the face operators' entries at `column` of the proved system.
fn check_with(
    d: &DegeneracyStep,
    c: &ClosureStep,
    lay: &Layout,
    column: &[usize],
    expr: &HashMap<usize, Expr>,
) -> Checked {
    let zero: Expr = Default::default();
    if let Some(i) = d.coincide.iter().position(|x| x[0] >= c.types.len()) {
        return Err(format!(
            "pair {i} names face type {}, which is not listed",
            d.coincide[i][0]
        ));
    }
    let mut corners_total = 0usize;
    let mut classes_total = 0usize;
    let mut first_witness: Option<String> = None;
    for (t, rule) in c.types.iter().enumerate() {
        let (at, n) = level_one_corners(&rule.face).map_err(|e| format!("type {t}: {e}"))?;
        corners_total += n;
        if at.len() != rule.subfaces.len() {
            return Err(format!(
                "type {t}: {} sub-faces in the level-1 complex, {} in the closure",
                at.len(),
                rule.subfaces.len()
            ));
        }
        within_work(
            "the degeneracy step's corners",
            (n as u128) * (lay.dims[t] as u128) * 64,
        )?;
        // One representative side start per corner: the first in sub-face order.
        let mut rep: Vec<Option<(usize, usize)>> = vec![None; n];
        for (k, sides) in at.iter().enumerate() {
            let w = rule.subfaces[k].type_index;
            if sides.len() != c.types[w].face.boundary.len() {
                return Err(format!(
                    "type {t}: sub-face {k} has {} sides in the complex, its type {w} has {}",
                    sides.len(),
                    c.types[w].face.boundary.len()
                ));
            }
            for (p, &x) in sides.iter().enumerate() {
                rep[x].get_or_insert((k, p));
            }
        }
        let key = |(k, p): (usize, usize)| -> Vec<&Expr> {
            let w = rule.subfaces[k].type_index;
            let col = lay.offsets[w][p] % lay.dims[w];
            (0..lay.dims[t])
                .map(|r| {
                    let x = column[lay.base[t][k] + r * lay.dims[w] + col];
                    expr.get(&x).unwrap_or(&zero)
                })
                .collect()
        };
        let keys: Vec<Vec<&Expr>> = rep
            .iter()
            .map(|r| r.map(key).ok_or("a corner of the complex starts no side"))
            .collect::<Result<_, _>>()?;
        let forced = classes_by_key(keys);
        let mut pairs = Vec::new();
        for &[_, k1, p1, k2, p2] in d.coincide.iter().filter(|x| x[0] == t) {
            let corner = |k: usize, p: usize| at.get(k).and_then(|s| s.get(p)).copied();
            let (Some(a), Some(b)) = (corner(k1, p1), corner(k2, p2)) else {
                return Err(format!(
                    "type {t}: the pair (sub-face {k1} corner {p1}, sub-face {k2} corner {p2}) \
                     names a corner the level-1 complex does not have"
                ));
            };
            if a == b {
                return Err(format!(
                    "type {t}: corner {p1} of sub-face {k1} and corner {p2} of sub-face {k2} are \
                     one corner of the complex, not two distinct ones"
                ));
            }
            pairs.push((a, b));
        }
        let claimed = classes_by_pairs(n, &pairs);
        if let Some(x) = (0..n).find(|&x| forced[x] != claimed[x]) {
            let (k, p) = rep[x].unwrap_or_default();
            let (y, listed) = match forced[x] != x {
                true => (forced[x], false),
                false => (claimed[x], true),
            };
            let (k2, p2) = rep[y].unwrap_or_default();
            return Err(match listed {
                true => format!(
                    "type {t}: corner {p} of sub-face {k} and corner {p2} of sub-face {k2} are \
                     listed as coinciding, but their coordinates differ on the solution set"
                ),
                false => format!(
                    "type {t}: corner {p2} of sub-face {k2} and corner {p} of sub-face {k} \
                     coincide on every solution, and the step does not list it"
                ),
            });
        }
        let joined = (0..n).filter(|&x| forced[x] != x).count();
        classes_total += joined;
        if let Some(x) = (0..n).find(|&x| forced[x] != x) {
            let ((k, p), (k2, p2)) = (
                rep[forced[x]].unwrap_or_default(),
                rep[x].unwrap_or_default(),
            );
            first_witness.get_or_insert(format!(
                "type {t}: corner {p} of sub-face {k} and corner {p2} of sub-face {k2}"
            ));
        }
    }
    // Flat cells, from the types alone.
    let flat_faces: BTreeSet<usize> = c
        .types
        .iter()
        .enumerate()
        .filter(|(_, r)| {
            r.face.boundary.len() == 2 && r.face.boundary.iter().all(|e| e.kind == Kind::C)
        })
        .map(|(t, _)| t)
        .collect();
    let mut flat_lacunas = BTreeSet::new();
    for (t, r) in c.types.iter().enumerate() {
        if r.face.params.el.kind != Kind::C || r.face.delay != 1 {
            continue;
        }
        let (derived, _) = subdivide(&r.face).map_err(|e| format!("type {t}: {e}"))?;
        let sides: BTreeSet<usize> = derived
            .iter()
            .flat_map(|(_, origins, _)| origins)
            .filter_map(|o| match o {
                Origin::Lacuna { side } => Some(*side),
                _ => None,
            })
            .collect();
        if sides.len() == 2 {
            flat_lacunas.insert(t);
        }
    }
    let same = |given: &[usize], derived: &BTreeSet<usize>| {
        given.len() == derived.len() && given.iter().copied().collect::<BTreeSet<_>>() == *derived
    };
    if !same(&d.flat_faces, &flat_faces) {
        return Err(format!(
            "the flat faces are types {flat_faces:?} (two Cantor edges), the step lists {:?}",
            d.flat_faces
        ));
    }
    if !same(&d.flat_lacunas, &flat_lacunas) {
        return Err(format!(
            "the flat lacunas are those of types {flat_lacunas:?} (two sides, Cantor edges), the \
             step lists {:?}",
            d.flat_lacunas
        ));
    }
    let message = format!(
        "the level-1 {} ({}) built by the checker; the corners' coordinates compared as \
         affine functions on the proved solution set: {} forced to coincide with another; flat \
         cells re-derived from the types: {}, {}",
        match c.types.len() {
            1 => "complex of 1 type".to_string(),
            n => format!("complexes of {n} types"),
        },
        super::counted(corners_total, "corner", "corners"),
        classes_total,
        super::counted(flat_faces.len(), "face", "faces"),
        super::counted(flat_lacunas.len(), "lacuna", "lacunas")
    );
    let verdict = match (
        first_witness,
        flat_faces.is_empty() && flat_lacunas.is_empty(),
    ) {
        (None, true) => "no forced collapse: no two distinct corners of a level-1 complex \
                         coincide on every solution, and no cell is forced flat"
            .to_string(),
        (w, _) => {
            let mut parts = Vec::new();
            if let Some(w) = w {
                parts.push(format!(
                    "{} on every solution with a distinct one ({w})",
                    match classes_total {
                        1 => "1 corner coincides".to_string(),
                        n => format!("{n} corners coincide"),
                    }
                ));
            }
            if let Some(t) = flat_faces.first() {
                parts.push(format!("face type T{t} has two Cantor edges: area 0"));
            }
            if let Some(t) = flat_lacunas.first() {
                parts.push(format!(
                    "the lacuna of type T{t} has two Cantor sides: area 0"
                ));
            }
            format!("FORCED COLLAPSE: {}", parts.join("; "))
        }
    };
    Ok((message, verdict))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn classes_end_at_their_smallest_member() {
        assert_eq!(classes_by_pairs(5, &[(3, 1), (4, 3)]), vec![0, 1, 2, 1, 1]);
        assert_eq!(
            classes_by_key(vec!["a", "b", "a", "c", "b"]),
            vec![0, 1, 0, 3, 1]
        );
    }
}
