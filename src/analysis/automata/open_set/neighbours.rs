//! The coordinates of the neighbour-map search: the centres of a part's attractor pieces, their
//! rescaling to balance the edges, and the neighbour edges in those coordinates.

use super::hulls::{cmp, q0, Edge};
use super::Coordinates;
use crate::algebra::algebraic::{FieldElement, NumberField};
use crate::algebra::kmatrix::KMatrix;
use crate::analysis::automata::neighbour_maps::{KAffine, KEdge};
use num_rational::BigRational;
use num_traits::One;
use std::cmp::Ordering;

/// Centres of the balls of the neighbour-map search near the middle of each state's attractor:
/// the attractors are estimated in floating point (from `start`, twelve rounds of the operators,
/// at most 4096 points kept per state) and each centre is the middle of its state's bounding box,
/// rounded to a rational of denominator 1024. Any centres are sound — the search certifies its
/// radius exactly for the centres it is given — but balls around the attractors' middles are
/// smallest, and the fewer neighbour maps pass the ball test. `start` when the estimate is not
/// finite.
pub(super) fn attractor_centres(
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
pub(super) fn balance(
    k: &NumberField,
    centres: &[Vec<FieldElement>],
    edges: &[KEdge],
) -> Option<Rescaled> {
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
pub(super) fn neighbour_edges(
    k: &NumberField,
    part: &[usize],
    edges: &[Edge],
    frames: &[Option<KMatrix>],
    d: usize,
) -> Result<Neighbourhood, String> {
    let pos = |s: usize| part.binary_search(&s).expect("in part");
    let half = k.rational(BigRational::new(1.into(), 2.into()));
    let in_charts: Vec<KEdge> = edges
        .iter()
        .map(|(s, w, m, _)| (pos(*s), pos(*w), m.clone()))
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
            (i, j, embed[i].0.then(k, m).then(k, &embed[j].1))
        })
        .collect();
    Ok((Coordinates::Drawing, centres, q))
}
