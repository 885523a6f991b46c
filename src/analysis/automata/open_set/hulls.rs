//! The open-set condition's hull witness: the operators' affine chart maps in the field, exact
//! convex hulls, disjoint interiors and containment, and the hulls of a part's attractor pieces
//! refined until they are feasible.

use super::{MAX_ROUNDS, MAX_VERTICES};
use crate::algebra::algebraic::{FieldElement, NumberField};
use crate::algebra::kmatrix::KMatrix;
use crate::analysis::automata::neighbour_maps::KAffine;
use num_rational::BigRational;
use num_traits::{One, Zero};
use std::cmp::Ordering;

/// A point of a chart (1 or 2 coordinates).
pub(super) type Pt = Vec<FieldElement>;

pub(super) fn q0(k: &NumberField) -> FieldElement {
    k.rational(BigRational::zero())
}

/// The chart map of `T: q ← w` (both states of `d + 1` points): the child's chart point x has
/// barycentric coordinates `(1 − Σx, x)`, its image `T·(1 − Σx, x)` read in the parent's chart.
pub(super) fn chart_map(k: &NumberField, t: &KMatrix, d: usize) -> KAffine {
    // Image of x = Σ_j x_j e_j: T·(e_0 + Σ x_j (e_j − e_0)); chart rows 1..=d.
    let mut a = Vec::with_capacity(d * d);
    let mut b = Vec::with_capacity(d);
    for r in 1..=d {
        for j in 1..=d {
            a.push(k.sub(t.get(r, j), t.get(r, 0)));
        }
        b.push(t.get(r, 0).clone());
    }
    KAffine { a, b }
}

/// The fixed point of `m`, when `I − A` is invertible (d = 1 or 2).
fn fixed_point(k: &NumberField, m: &KAffine) -> Option<Pt> {
    let one = k.rational(BigRational::one());
    match m.b.len() {
        1 => {
            let den = k.sub(&one, &m.a[0]);
            Some(vec![k.div(&m.b[0], &den)?])
        }
        2 => {
            // (I − A) x = b by Cramer's rule.
            let (m00, m01) = (k.sub(&one, &m.a[0]), k.sub(&q0(k), &m.a[1]));
            let (m10, m11) = (k.sub(&q0(k), &m.a[2]), k.sub(&one, &m.a[3]));
            let det = k.sub(&k.mul(&m00, &m11), &k.mul(&m01, &m10));
            let x = k.sub(&k.mul(&m.b[0], &m11), &k.mul(&m01, &m.b[1]));
            let y = k.sub(&k.mul(&m00, &m.b[1]), &k.mul(&m10, &m.b[0]));
            Some(vec![k.div(&x, &det)?, k.div(&y, &det)?])
        }
        _ => None,
    }
}

pub(super) fn cmp(k: &NumberField, a: &FieldElement, b: &FieldElement) -> Ordering {
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
pub(super) type Edge = (usize, usize, KAffine, usize);

/// Whether a family of polygons (one per state of the part, in part order) is feasible: every
/// piece inside its state's polygon, and the pieces out of one state with disjoint interiors.
pub(super) fn feasible(
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
pub(super) fn attractor_hulls(
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
        sets[i].push(fixed_point(k, &m)?);
        // And the fixed points of every cycle of one or two operators through q.
        for (s1, w1, m1, _) in edges.iter().filter(|e| e.0 == q) {
            if *w1 == q {
                sets[i].extend(fixed_point(k, m1));
                continue;
            }
            for (_, _, m2, _) in edges.iter().filter(|e| e.0 == *w1 && e.1 == *s1) {
                if edges.len() <= 512 {
                    sets[i].extend(fixed_point(k, &m1.then(k, m2)));
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
        let m = KAffine {
            a: vec![r(-1, 2), r(0, 1), r(0, 1), r(-1, 2)],
            b: vec![r(3, 2), r(3, 1)],
        };
        assert_eq!(fixed_point(&k, &m).unwrap(), p(&k, 1, 2, 1));
    }
}
