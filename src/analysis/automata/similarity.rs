//! The exact similarity dimension of an automaton's attractor (Mauldin–Williams), when the
//! operators of each strongly connected part of the control graph act as similitudes in the
//! chosen geometry.
//!
//! Each state reachable from the start gets a frame: the start state's control points, and for a
//! state first reached through `T: q ← w` the points `F_q · T`. An operator `T: q ← w` is a
//! similitude of ratio r when its images of the frame's differences have Gram matrix `r²` times
//! theirs: with `D_w = F_w·Δ` (the differences `P_j − P_0`, of full rank), `(F_q·T·Δ)ᵀ(F_q·T·Δ) =
//! r²·D_wᵀD_w` exactly in the field. When every squared ratio of a part is a power `σ^k` of the
//! smallest one σ < 1 (k ≤ 16), the matrix `M(s)_(q,w) = Σ r_T^s` is `Σ u^k` with `u = σ^(s/2)`,
//! and its spectral radius is 1 at the smallest root `u*` in (0, 1] of `det(I − M(u))` (M is
//! irreducible and increasing in u), so `s = 2·ln u*/ln σ`. Decimals are certified by
//! [`crate::algebra::reallog`]: enclosures of u* and σ, logarithms by series with rigorous tails,
//! refined until every printed digit is decided.

use crate::algebra::algebraic::{decide_digits, FieldElement, NumberField, RealAlgebraic};
use crate::algebra::kmatrix::KMatrix;
use crate::algebra::poly::Poly;
use crate::algebra::reallog::{log_ratio_bounds, round_out};
use crate::analysis::automata::contraction::{control_graph, reachable};
use crate::analysis::automata::open_set::NeighbourWitness;
use crate::input::automaton_model::AutomatonModel;
use crate::topology::class::strong_components;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
use serde::Serialize;
use std::cmp::Ordering;

/// The similarity dimension, exact and certified.
#[derive(Clone, Debug, Serialize)]
pub struct SimilarityDimension {
    /// The exact value: `log 3 / log 2`, `2`, or `2·log(u)/log(σ) where …`.
    pub exact: String,
    /// Certified digits after the point, truncated.
    pub decimal: String,
    /// The strongly connected parts (their states) and each part's exact value.
    pub parts: Vec<(Vec<String>, String)>,
    /// True unless the open-set condition is proved for every part
    /// ([`crate::analysis::automata::open_set`]): the value is then only an upper bound of the
    /// Hausdorff dimension, never the dimension.
    pub upper_bound: bool,
    /// What the open-set check found (the criterion that decided, or why none did).
    pub open_set: String,
    /// Each part's exact data, for the certificate: its states, σ, the exponent of every
    /// operator inside it, u* and the rational value when there is one.
    #[serde(skip)]
    pub witness: Vec<PartWitness>,
}

impl SimilarityDimension {
    /// Whether every part's open-set condition was proved with a witness the certificate
    /// carries: convex sets, or a closed set of neighbour maps.
    pub fn open_set_witnessed(&self) -> bool {
        !self.witness.is_empty()
            && self.witness.iter().all(|p| {
                p.open_set.is_some()
                    || matches!(p.neighbour_maps, Some(NeighbourWitness::Holds { .. }))
            })
    }

    /// Whether some part's open-set condition was proved by neighbour maps (the others by
    /// convex sets).
    pub fn open_set_by_neighbour_maps(&self) -> bool {
        self.witness
            .iter()
            .any(|p| matches!(p.neighbour_maps, Some(NeighbourWitness::Holds { .. })))
    }

    /// Whether some part's open-set condition was refuted with a witness the certificate
    /// carries: two words with different first operators and the same map.
    pub fn open_set_refuted(&self) -> bool {
        self.witness
            .iter()
            .any(|p| matches!(p.neighbour_maps, Some(NeighbourWitness::Fails { .. })))
    }
}

/// One cyclic part's exact data (the certificate's `similarity-dimension` witness).
#[derive(Clone, Debug)]
pub struct PartWitness {
    /// The part's states, increasing.
    pub states: Vec<usize>,
    /// σ: every squared ratio inside the part is `σ^k`.
    pub sigma: FieldElement,
    /// `(operator, k)` for every operator inside the part, by operator index.
    pub exponents: Vec<(usize, u32)>,
    /// u*, the smallest root of `det(I − M(u))` in (0, 1].
    pub u: RealAlgebraic,
    /// The dimension when it is rational.
    pub rational: Option<BigRational>,
    /// The open-set condition's witness, when convex sets decided it: per state of the part,
    /// the vertices of a convex polygon (an interval in one dimension) in the state's chart.
    pub open_set: Option<Vec<Vec<Vec<FieldElement>>>>,
    /// The witness when the neighbour maps decided the condition (holds or fails).
    pub neighbour_maps: Option<NeighbourWitness>,
}

/// Why there is no similarity dimension.
pub type NotApplicable = String;

fn q(n: i64) -> BigRational {
    BigRational::from_integer(n.into())
}

/// The default control points of a start state with m points: the zigzag `(j, j mod 2)` (`z = 0`
/// in space 3), exact.
pub fn default_points(m: usize, space: usize, k: &NumberField) -> Vec<Vec<FieldElement>> {
    (0..m)
        .map(|j| {
            let mut p = vec![k.rational(q(j as i64)), k.rational(q((j % 2) as i64))];
            if space == 3 {
                p.push(k.rational(q(0)));
            }
            p
        })
        .collect()
}

/// The frame of every reachable state as a `space × m` matrix over K (columns are points).
pub fn frames(m: &AutomatonModel, ops: &[KMatrix]) -> Vec<Option<KMatrix>> {
    let a = &m.automaton;
    let k = &m.field;
    let pts = m
        .points
        .clone()
        .unwrap_or_else(|| default_points(a.states[m.start].dim, m.space, k));
    let cols = pts.len();
    let mut data = Vec::with_capacity(m.space * cols);
    for d in 0..m.space {
        for p in &pts {
            data.push(p[d].clone());
        }
    }
    let mut frames: Vec<Option<KMatrix>> = vec![None; a.states.len()];
    frames[m.start] = Some(KMatrix {
        rows: m.space,
        cols,
        data,
    });
    let g = control_graph(m);
    let mut queue = std::collections::VecDeque::from([m.start]);
    while let Some(s) = queue.pop_front() {
        for &o in &g[s] {
            let w = a.operators[o].from;
            if frames[w].is_none() {
                let f = frames[s]
                    .as_ref()
                    .expect("visited")
                    .mul(k, &ops[o])
                    .expect("shapes chain");
                frames[w] = Some(f);
                queue.push_back(w);
            }
        }
    }
    frames
}

/// The determinant over K by elimination.
fn kdet(k: &NumberField, mut m: KMatrix) -> FieldElement {
    let n = m.rows;
    let mut det = k.rational(q(1));
    for c in 0..n {
        let Some(p) = (c..n).find(|&r| !m.get(r, c).is_zero()) else {
            return k.rational(q(0));
        };
        if p != c {
            for j in 0..n {
                m.data.swap(p * n + j, c * n + j);
            }
            det = k.sub(&k.rational(q(0)), &det);
        }
        let piv = m.get(c, c).clone();
        det = k.mul(&det, &piv);
        let inv = k.inv(&piv).expect("non-zero pivot");
        for r in c + 1..n {
            let f = k.mul(m.get(r, c), &inv);
            if f.is_zero() {
                continue;
            }
            for j in c..n {
                let v = k.sub(m.get(r, j), &k.mul(&f, m.get(c, j)));
                m.data[r * n + j] = v;
            }
        }
    }
    det
}

/// The squared ratio of `T: q ← w` as a similitude from the frame of w into the frame of q, or
/// `None` when it is not a similitude (or w's frame is degenerate).
fn squared_ratio(k: &NumberField, fq: &KMatrix, fw: &KMatrix, t: &KMatrix) -> Option<FieldElement> {
    let m = fw.cols;
    if m < 2 {
        return None;
    }
    // Δ: m × (m − 1), column j = e_(j+1) − e_0.
    let mut delta = KMatrix::zeros(k, m, m - 1);
    for j in 0..m - 1 {
        delta.data[j] = k.rational(q(-1));
        delta.data[(j + 1) * (m - 1) + j] = k.rational(q(1));
    }
    let d = fw.mul(k, &delta)?;
    let g = d.transpose().mul(k, &d)?;
    if kdet(k, g.clone()).is_zero() {
        return None;
    }
    let img = fq.mul(k, t)?.mul(k, &delta)?;
    let h = img.transpose().mul(k, &img)?;
    let r2 = k.div(h.get(0, 0), g.get(0, 0))?;
    let scaled: Vec<FieldElement> = g.data.iter().map(|x| k.mul(x, &r2)).collect();
    (scaled == h.data && k.sign(&r2) == Ordering::Greater).then_some(r2)
}

/// Strongly connected parts of the reachable control graph that hold a cycle, each sorted,
/// ordered by smallest state.
pub(crate) fn cyclic_parts(m: &AutomatonModel) -> Vec<Vec<usize>> {
    let a = &m.automaton;
    let g = control_graph(m);
    let reach = reachable(m);
    let succ: Vec<Vec<usize>> = g
        .iter()
        .map(|ops| ops.iter().map(|&o| a.operators[o].from).collect())
        .collect();
    let (comp, count) = strong_components(&succ);
    let mut parts = vec![Vec::new(); count];
    for (v, &c) in comp.iter().enumerate() {
        parts[c].push(v);
    }
    // A part is reached whole or not at all: reachability follows the same arcs.
    let mut out: Vec<Vec<usize>> = parts
        .into_iter()
        .filter(|c| reach[c[0]] && (c.len() > 1 || succ[c[0]].contains(&c[0])))
        .collect();
    out.sort();
    out
}

/// `det(I − M(u))` for the part's matrix of `Σ u^k` (`entries[i][j]` the exponents k of the
/// edges from i to j), as a polynomial (by interpolation at `u = 0, 1, …, deg`).
pub(crate) fn part_polynomial(n: usize, entries: &[Vec<Vec<usize>>]) -> Poly {
    let deg = n * entries
        .iter()
        .flatten()
        .flatten()
        .copied()
        .max()
        .unwrap_or(0);
    let xs: Vec<BigRational> = (0..=deg).map(|i| q(i as i64)).collect();
    let ys: Vec<BigRational> = xs
        .iter()
        .map(|u| {
            let mut m = vec![vec![BigRational::zero(); n]; n];
            for i in 0..n {
                for j in 0..n {
                    let s: BigRational = entries[i][j]
                        .iter()
                        .map(|&e| num_traits::pow(u.clone(), e))
                        .sum();
                    m[i][j] = if i == j { q(1) - s } else { -s };
                }
            }
            rat_det(m)
        })
        .collect();
    // Newton's divided differences, then expansion.
    let mut coef = ys.clone();
    for j in 1..xs.len() {
        for i in (j..xs.len()).rev() {
            coef[i] = (&coef[i] - &coef[i - 1]) / (&xs[i] - &xs[i - j]);
        }
    }
    let mut p = Poly::constant(coef[xs.len() - 1].clone());
    for i in (0..xs.len() - 1).rev() {
        p = &(&p * &Poly::new(vec![-xs[i].clone(), q(1)])) + &Poly::constant(coef[i].clone());
    }
    p
}

/// The smallest root u* in (0, 1] of `det(I − M(u))` (exact, from its factors over Q).
pub(crate) fn smallest_root(p: &Poly) -> Result<RealAlgebraic, NotApplicable> {
    let factors = crate::algebra::factor::factor(&p.square_free_part())
        .map_err(|_| "the part's polynomial could not be factored".to_string())?;
    let zero = RealAlgebraic::rational(q(0));
    let onea = RealAlgebraic::rational(q(1));
    let mut best: Option<RealAlgebraic> = None;
    for (f, _) in factors {
        for r in RealAlgebraic::real_roots(&f) {
            if r.cmp_exact(&zero) == Ordering::Greater
                && r.cmp_exact(&onea) != Ordering::Greater
                && best
                    .as_ref()
                    .is_none_or(|b| r.cmp_exact(b) == Ordering::Less)
            {
                best = Some(r);
            }
        }
    }
    best.ok_or_else(|| "no root of det(I − M(u)) in (0, 1]".to_string())
}

fn rat_det(mut m: Vec<Vec<BigRational>>) -> BigRational {
    let n = m.len();
    let mut det = q(1);
    for c in 0..n {
        let Some(p) = (c..n).find(|&r| !m[r][c].is_zero()) else {
            return q(0);
        };
        if p != c {
            m.swap(p, c);
            det = -det;
        }
        let piv = m[c][c].clone();
        det *= &piv;
        let pivot_row = m[c].clone();
        for row in m.iter_mut().skip(c + 1) {
            let f = &row[c] / &piv;
            if f.is_zero() {
                continue;
            }
            for (x, p) in row.iter_mut().zip(&pivot_row).skip(c) {
                *x -= &f * p;
            }
        }
    }
    det
}

/// One part's dimension `s = 2·ln u*/ln σ`: `(u*, σ)`.
#[derive(Clone)]
pub(crate) struct PartValue {
    /// u*, the smallest root in (0, 1] of `det(I − M(u))`.
    pub u: RealAlgebraic,
    /// σ, the base of the squared ratios.
    pub sigma: FieldElement,
    /// The exact text ([`exact_text`]).
    pub exact: String,
    /// The dimension when it is rational (found exactly).
    pub rational: Option<BigRational>,
}

/// The similarity dimension of the attractor of the start state, or why it does not apply.
pub fn similarity_dimension(
    m: &AutomatonModel,
    ops: &[KMatrix],
    digits: usize,
) -> Result<SimilarityDimension, NotApplicable> {
    let a = &m.automaton;
    let k = &m.field;
    if a.states.len() > 4096 {
        return Err("more than 4096 states".into());
    }
    let frames = frames(m, ops);
    let parts = cyclic_parts(m);
    if parts.is_empty() {
        return Err("the control graph has no cycle".into());
    }
    let g = control_graph(m);
    let mut values = Vec::new();
    let mut exponent_lists = Vec::new();
    for part in &parts {
        let names: Vec<String> = part.iter().map(|&s| a.states[s].name.clone()).collect();
        // Squared ratios of the operators inside the part.
        let mut inside = Vec::new();
        for &s in part {
            for &o in &g[s] {
                let w = a.operators[o].from;
                if let Ok(j) = part.binary_search(&w) {
                    let (fq, fw) = (
                        frames[s].as_ref().expect("reachable"),
                        frames[w].as_ref().expect("reachable"),
                    );
                    let r2 = squared_ratio(k, fq, fw, &ops[o]).ok_or_else(|| {
                        format!("operator `{}` is not a similitude on the frame of state `{}` (or that frame's points are affinely dependent)", a.operators[o].name, a.states[w].name)
                    })?;
                    inside.push((part.binary_search(&s).expect("in part"), j, r2, o));
                }
            }
        }
        let one = k.rational(q(1));
        let mut sigma: Option<FieldElement> = None;
        for (_, _, r2, _) in &inside {
            if k.sign(&k.sub(r2, &one)) == Ordering::Less
                && sigma
                    .as_ref()
                    .is_none_or(|s| k.sign(&k.sub(r2, s)) == Ordering::Less)
            {
                sigma = Some(r2.clone());
            }
        }
        let sigma = sigma
            .ok_or_else(|| format!("no operator of the part {{{}}} contracts", names.join(", ")))?;
        let n = part.len();
        // Exponents of every squared ratio over a common base: σ itself, or else (σ rational) a
        // rational root τ = σ^(1/d), d ≤ 6, so that ratios 1/3 and 1/(3√3) (σ = 1/27) share
        // τ = 1/3 with exponents 2 and 3.
        let exponents = |base: &FieldElement, max: usize| -> Option<Vec<usize>> {
            inside
                .iter()
                .map(|(_, _, r2, _)| {
                    let mut pow = one.clone();
                    for kk in 0..=max {
                        if &pow == r2 {
                            return Some(kk);
                        }
                        pow = k.mul(&pow, base);
                    }
                    None
                })
                .collect()
        };
        let mut found = exponents(&sigma, 16).map(|e| (sigma.clone(), e));
        if found.is_none() {
            if let Some(sr) = sigma.as_rational() {
                for d in 2..=6u32 {
                    if let Some(t) = rational_root(&sr, d) {
                        let tau = k.rational(t);
                        if let Some(e) = exponents(&tau, 16 * d as usize) {
                            found = Some((tau, e));
                            break;
                        }
                    }
                }
            }
        }
        let Some((sigma, exps)) = found else {
            let o = inside
                .iter()
                .find(|(_, _, r2, _)| {
                    let mut pow = one.clone();
                    !(0..=16).any(|_| {
                        let hit = &pow == r2;
                        pow = k.mul(&pow, &sigma);
                        hit
                    })
                })
                .map_or(0, |x| x.3);
            return Err(format!("the squared ratio of `{}` is not a power σ^k (k ≤ 16) of the smallest one σ = {}, nor of a rational root of it", a.operators[o].name, k.render(&sigma)));
        };
        let mut entries = vec![vec![Vec::new(); n]; n];
        let mut exponents: Vec<(usize, u32)> = Vec::new();
        for ((i, j, _, o), e) in inside.iter().zip(exps) {
            entries[*i][*j].push(e);
            exponents.push((*o, e as u32));
        }
        exponents.sort_unstable();
        let p = part_polynomial(n, &entries);
        let u = smallest_root(&p)?;
        let (exact, rational) = exact_text(k, &u, &sigma);
        values.push((
            names,
            PartValue {
                u,
                sigma,
                exact,
                rational,
            },
        ));
        exponent_lists.push(exponents);
    }
    // The largest part's value (certified comparison of enclosures).
    let mut best = 0;
    for i in 1..values.len() {
        if compare(k, &values[i].1, &values[best].1) == Ordering::Greater {
            best = i;
        }
    }
    let decimal = certified_decimal(k, &values[best].1, digits);
    let verdicts: Vec<_> = parts
        .iter()
        .map(|p| crate::analysis::automata::open_set::part_verdict(m, ops, &frames, p))
        .collect();
    let upper_bound = verdicts.iter().any(|v| v.holds != Some(true));
    let open_set = if verdicts.len() == 1 {
        verdicts[0].reason.clone()
    } else {
        verdicts
            .iter()
            .zip(&values)
            .map(|(v, (n, _))| format!("part {{{}}}: {}", n.join(", "), v.reason))
            .collect::<Vec<_>>()
            .join("; ")
    };
    let witness = parts
        .iter()
        .zip(&values)
        .zip(exponent_lists)
        .zip(&verdicts)
        .map(|(((states, (_, v)), exponents), verdict)| {
            let mut u = v.u.clone();
            u.refine_to(&BigRational::new(BigInt::one(), BigInt::one() << 64));
            PartWitness {
                states: states.clone(),
                sigma: v.sigma.clone(),
                exponents,
                u,
                rational: v.rational.clone(),
                open_set: verdict.witness.clone(),
                neighbour_maps: verdict.neighbour.clone(),
            }
        })
        .collect();
    Ok(SimilarityDimension {
        witness,
        upper_bound,
        open_set,
        exact: values[best].1.exact.clone(),
        decimal,
        parts: values
            .iter()
            .map(|(n, v)| (n.clone(), v.exact.clone()))
            .collect(),
    })
}

/// An exact text for `s = 2·ln u/ln σ`, and its value when it is rational (`u^(2b) = σ^a`
/// for small a, b when u and σ are rational; `u = σ^j` otherwise).
pub(crate) fn exact_text(
    k: &NumberField,
    u: &RealAlgebraic,
    sigma: &FieldElement,
) -> (String, Option<BigRational>) {
    if u.as_rational().is_some_and(|x| x.is_one()) {
        return ("0".into(), Some(q(0)));
    }
    // s = 2j: u = σ^j.
    let mut pow = sigma.clone();
    for j in 1..=16i64 {
        if equals(k, u, &pow) {
            return ((2 * j).to_string(), Some(q(2 * j)));
        }
        pow = k.mul(&pow, sigma);
    }
    if let (Some(ur), Some(sr)) = (u.as_rational(), sigma.as_rational()) {
        // s = a/b exactly when u^(2b) = σ^a.
        for b in 1..=12u32 {
            let lhs = num_traits::pow(ur.clone(), 2 * b as usize);
            for a in 1..=48 * b {
                let rhs = num_traits::pow(sr.clone(), a as usize);
                if rhs < lhs {
                    break;
                }
                if rhs == lhs {
                    let v = BigRational::new(a.into(), b.into());
                    return (v.to_string(), Some(v));
                }
            }
        }
        // σ = r0² with r0 rational: s = ln(1/u)/ln(1/r0).
        if let Some(r0) = rational_sqrt(&sr) {
            return (format!("log {} / log {}", ur.recip(), r0.recip()), None);
        }
        return (format!("2·log {} / log {}", ur.recip(), sr.recip()), None);
    }
    (
        format!(
            "2·log(u)/log(σ) where u = {} and σ = {}",
            u,
            k.render(sigma)
        ),
        None,
    )
}

/// The rational d-th root of a positive rational, when it exists.
fn rational_root(x: &BigRational, d: u32) -> Option<BigRational> {
    let (n, m) = (x.numer().nth_root(d), x.denom().nth_root(d));
    (num_traits::pow(n.clone(), d as usize) == *x.numer()
        && num_traits::pow(m.clone(), d as usize) == *x.denom())
    .then(|| BigRational::new(n, m))
}

fn rational_sqrt(x: &BigRational) -> Option<BigRational> {
    let (n, d) = (x.numer().sqrt(), x.denom().sqrt());
    (&n * &n == *x.numer() && &d * &d == *x.denom()).then(|| BigRational::new(n, d))
}

/// Whether the algebraic `u` equals the field element `x`.
pub(crate) fn equals(k: &NumberField, u: &RealAlgebraic, x: &FieldElement) -> bool {
    if let Some(ur) = u.as_rational() {
        return x.as_rational().as_ref() == Some(ur);
    }
    // x is a root of u's minimal polynomial and lies in u's isolating interval.
    let f = u.min_poly();
    let mut acc = k.rational(q(0));
    for c in f.coeffs().iter().rev() {
        acc = k.add(&k.mul(&acc, x), &k.rational(c.clone()));
    }
    if !acc.is_zero() {
        return false;
    }
    let (lo, hi) = u.interval();
    let lo_s = k.sign(&k.sub(x, &k.rational(lo.clone())));
    let hi_s = k.sign(&k.sub(x, &k.rational(hi.clone())));
    lo_s == Ordering::Greater && hi_s == Ordering::Less
}

/// An enclosure of a part's dimension at `bits` bits of working precision.
fn bounds(k: &NumberField, v: &PartValue, bits: u32) -> Option<(BigRational, BigRational)> {
    if let Some(r) = &v.rational {
        return Some((r.clone(), r.clone()));
    }
    let w = BigRational::new(BigInt::one(), BigInt::one() << (bits + 8));
    let mut u = v.u.clone();
    u.refine_to(&w);
    let (ulo, uhi) = match u.as_rational() {
        Some(x) => (x.clone(), x.clone()),
        None => {
            let (l, h) = u.interval();
            round_out(l, h, bits + 8)
        }
    };
    let (slo, shi) = k.enclosure(&v.sigma, &w);
    let (slo, shi) = round_out(&slo, &shi, bits + 8);
    if !ulo.is_positive() {
        return None;
    }
    log_ratio_bounds(&q(2), (&ulo, &uhi), (&slo, &shi), bits)
}

/// Compares two parts' dimensions by certified enclosures (equal when 4096 bits do not separate
/// them).
pub(crate) fn compare(k: &NumberField, a: &PartValue, b: &PartValue) -> Ordering {
    let mut bits = 64;
    while bits <= 4096 {
        if let (Some((alo, ahi)), Some((blo, bhi))) = (bounds(k, a, bits), bounds(k, b, bits)) {
            if alo > bhi {
                return Ordering::Greater;
            }
            if ahi < blo {
                return Ordering::Less;
            }
            if alo == ahi && blo == bhi && alo == blo {
                return Ordering::Equal;
            }
        }
        bits *= 2;
    }
    Ordering::Equal
}

/// Certified digits: enclosures refined until the truncated decimal is decided.
pub(crate) fn certified_decimal(k: &NumberField, v: &PartValue, digits: usize) -> String {
    let digits = digits.max(1);
    if let Some(r) = &v.rational {
        return decide_digits(r, r, digits, true).expect("exact");
    }
    let mut bits = u32::try_from(digits * 10 / 3 + 32).unwrap_or(u32::MAX / 4);
    loop {
        if let Some((lo, hi)) = bounds(k, v, bits) {
            if let Some(s) = decide_digits(&lo, &hi, digits, false) {
                return s;
            }
        }
        bits += bits / 2;
        if bits > 40_000 {
            // Digits that do not separate (a rational dimension not recognised, with a finite
            // decimal expansion): print only the digits that are decided.
            if let Some((lo, hi)) = bounds(k, v, bits) {
                for d in (1..digits).rev() {
                    if let Some(s) = decide_digits(&lo, &hi, d, false) {
                        return s;
                    }
                }
            }
            return "undecided".into();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rational_roots_exist_only_when_exact() {
        // (1/3)^3 = 1/27; (4/9)^2 = 16/81; 1/2 has no rational square root.
        assert_eq!(
            rational_root(&BigRational::new(1.into(), 27.into()), 3),
            Some(BigRational::new(1.into(), 3.into()))
        );
        assert_eq!(
            rational_root(&BigRational::new(16.into(), 81.into()), 2),
            Some(BigRational::new(4.into(), 9.into()))
        );
        assert_eq!(
            rational_root(&BigRational::new(1.into(), 2.into()), 2),
            None
        );
        assert_eq!(
            rational_root(&BigRational::new(1.into(), 27.into()), 2),
            None
        );
    }
}
