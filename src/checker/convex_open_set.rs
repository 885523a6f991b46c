//! The open-set condition of a cyclic part from convex sets in the states' charts: the charts
//! (non-degenerate frames, barycentric operators), each set strictly convex, every operator's
//! chart map injective into its row state's set, and the pieces out of one state with disjoint
//! interiors.

use super::field::{self, P};
use super::ifs::{barycentric, gram, Field, KMat};
use crate::certificate::{AutomatonClaim, FieldCoords};

/// The dimension d of a part's charts: every state of the part has m = d + 1 points, 2 or 3.
fn chart_dimension(a: &AutomatonClaim, members: &[usize]) -> Result<usize, String> {
    let m = a.states[members[0]].dim;
    if !(2..=3).contains(&m) || members.iter().any(|&q| a.states[q].dim != m) {
        return Err("the charts need every state of the part with 2 or with 3 points".into());
    }
    Ok(m - 1)
}

/// Every state's frame is non-degenerate (its d + 1 points affinely independent: the Gram
/// determinant of its edge vectors is not 0), so its chart is an affine bijection onto the
/// affine hull of its points.
fn independent_frames(
    k: &Field,
    a: &AutomatonClaim,
    frames: &[Option<KMat>],
    members: &[usize],
    d: usize,
) -> Result<(), String> {
    for &q in members {
        let g = gram(k, frames[q].as_ref().expect("reachable"));
        let det = match d {
            1 => g.data[0].clone(),
            _ => k.sub(
                &k.mul(&g.data[0], &g.data[3]),
                &k.mul(&g.data[1], &g.data[2]),
            ),
        };
        if k.is_zero(&det) {
            return Err(format!(
                "the points of state {} are affinely dependent",
                a.states[q].name
            ));
        }
    }
    Ok(())
}

/// The part's frames are non-degenerate and its operators barycentric; returns d.
pub(super) fn charts(
    k: &Field,
    a: &AutomatonClaim,
    ops: &[KMat],
    frames: &[Option<KMat>],
    members: &[usize],
    inside: &[usize],
) -> Result<usize, String> {
    let d = chart_dimension(a, members)?;
    independent_frames(k, a, frames, members, d)?;
    if let Some(&o) = inside.iter().find(|&&o| !barycentric(k, &ops[o])) {
        return Err(format!(
            "operator {} is not barycentric (a column does not sum to 1): it has no chart map",
            a.operators[o].name
        ));
    }
    Ok(d)
}

/// The sign of `(b − a) × (c − a)` in K.
fn turn(k: &Field, a: &[P], b: &[P], c: &[P]) -> Result<i32, String> {
    let l = k.mul(&k.sub(&b[0], &a[0]), &k.sub(&c[1], &a[1]));
    let r = k.mul(&k.sub(&b[1], &a[1]), &k.sub(&c[0], &a[0]));
    k.sign(&k.sub(&l, &r))
}

/// The open-set condition for one part, from convex sets given in the states' charts: each
/// state's frame is non-degenerate (its chart is an affine bijection onto the affine hull of its
/// points), every operator of the part is barycentric (only then is its action on control points
/// an affine map of the charts, read off rows 1..d), each set is a strictly convex polygon (an interval in one dimension), every
/// operator's chart map is injective and maps its column state's set into its row state's set
/// (closed, vertex by vertex: then the open interiors go into the open interiors), and the
/// images out of one state have disjoint interiors (a separating edge line).
pub(super) fn check_open_set(
    k: &Field,
    a: &AutomatonClaim,
    ops: &[KMat],
    frames: &[Option<KMat>],
    members: &[usize],
    inside: &[usize],
    sets: &[Vec<Vec<FieldCoords>>],
) -> Result<(), String> {
    let d = charts(k, a, ops, frames, members, inside)?;
    if sets.len() != members.len() {
        return Err(format!("{} sets for {} states", sets.len(), members.len()));
    }
    let mut polys: Vec<Vec<Vec<P>>> = Vec::with_capacity(sets.len());
    for (set, &q) in sets.iter().zip(members) {
        if set.len() > 4096 || set.iter().any(|v| v.len() != d) {
            return Err(format!(
                "the set of state {} is not a list of points of {d} coordinates",
                a.states[q].name
            ));
        }
        let pts: Vec<Vec<P>> = set
            .iter()
            .map(|v| v.iter().map(|x| k.element(x)).collect())
            .collect::<Result<_, _>>()?;
        let ok = match d {
            1 => pts.len() == 2 && k.sign(&k.sub(&pts[1][0], &pts[0][0]))? > 0,
            _ => {
                let n = pts.len();
                n >= 3
                    && (0..n).try_fold(true, |acc, i| {
                        Ok::<_, String>(
                            acc && turn(k, &pts[i], &pts[(i + 1) % n], &pts[(i + 2) % n])? > 0,
                        )
                    })?
            }
        };
        if !ok {
            return Err(format!(
                "the set of state {} is not {}",
                a.states[q].name,
                match d {
                    1 => "an interval with increasing ends",
                    _ => "a strictly convex polygon, counter-clockwise",
                }
            ));
        }
        polys.push(pts);
    }
    let pos = |q: usize| members.binary_search(&q).expect("member");
    // The image of the column state's set under each operator's chart map.
    let mut images: Vec<(usize, Vec<Vec<P>>)> = Vec::with_capacity(inside.len());
    for &o in inside {
        let (q, w) = (a.operators[o].to, a.operators[o].from);
        let t = &ops[o];
        let at = |r: usize, c: usize| &t.data[r * t.cols + c];
        // x ↦ A·x + b with A[r−1][j−1] = T[r][j] − T[r][0], b[r−1] = T[r][0].
        let amat: Vec<Vec<P>> = (1..=d)
            .map(|r| (1..=d).map(|j| k.sub(at(r, j), at(r, 0))).collect())
            .collect();
        let det = match d {
            1 => amat[0][0].clone(),
            _ => k.sub(
                &k.mul(&amat[0][0], &amat[1][1]),
                &k.mul(&amat[0][1], &amat[1][0]),
            ),
        };
        let sign = k.sign(&det)?;
        if sign == 0 {
            return Err(format!(
                "{}'s chart map is not injective",
                a.operators[o].name
            ));
        }
        let mut img: Vec<Vec<P>> = polys[pos(w)]
            .iter()
            .map(|x| {
                (0..d)
                    .map(|r| {
                        (0..d).fold(at(r + 1, 0).clone(), |acc, j| {
                            field::add(&acc, &k.mul(&amat[r][j], &x[j]))
                        })
                    })
                    .collect()
            })
            .collect();
        if sign < 0 {
            img.reverse();
        }
        // Inside the row state's closed set.
        let outer = &polys[pos(q)];
        for v in &img {
            let inside_outer = match d {
                1 => {
                    k.sign(&k.sub(&v[0], &outer[0][0]))? >= 0
                        && k.sign(&k.sub(&outer[1][0], &v[0]))? >= 0
                }
                _ => {
                    let n = outer.len();
                    (0..n).try_fold(true, |acc, i| {
                        Ok::<_, String>(acc && turn(k, &outer[i], &outer[(i + 1) % n], v)? >= 0)
                    })?
                }
            };
            if !inside_outer {
                return Err(format!(
                    "the image of state {}'s set under {} leaves state {}'s set",
                    a.states[w].name, a.operators[o].name, a.states[q].name
                ));
            }
        }
        images.push((q, img));
    }
    // Pieces out of one state: disjoint interiors.
    let separates = |p: &[Vec<P>], other: &[Vec<P>]| -> Result<bool, String> {
        let n = p.len();
        for i in 0..n {
            let mut all = true;
            for v in other {
                if turn(k, &p[i], &p[(i + 1) % n], v)? > 0 {
                    all = false;
                    break;
                }
            }
            if all {
                return Ok(true);
            }
        }
        Ok(false)
    };
    for (i, (q, x)) in images.iter().enumerate() {
        for (j, (r, y)) in images.iter().enumerate().skip(i + 1) {
            if q != r {
                continue;
            }
            let disjoint = match d {
                1 => {
                    k.sign(&k.sub(&y[0][0], &x[1][0]))? >= 0
                        || k.sign(&k.sub(&x[0][0], &y[1][0]))? >= 0
                }
                _ => separates(x, y)? || separates(y, x)?,
            };
            if !disjoint {
                return Err(format!(
                    "the pieces of {} and {} out of state {} overlap (no separating edge)",
                    a.operators[inside[i]].name, a.operators[inside[j]].name, a.states[*q].name
                ));
            }
        }
    }
    Ok(())
}
