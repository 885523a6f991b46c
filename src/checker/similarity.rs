//! The step `similarity-dimension` (Mauldin–Williams): the frames of the states, every operator
//! inside a cyclic part a similitude of squared ratio σ^k on them, u* the smallest root of
//! det(I − M(u)), the digits of the largest dimension, and what the parts' open-set witnesses
//! make of it.

use super::control_graph::{cyclic_parts, graph, Graph};
use super::convex_open_set::check_open_set;
use super::enclosure::{decimal, enclose, enclose_root, ln_bounds};
use super::field::{self, Root, P};
use super::ifs::{constraints_hold, gram, instance, Field, KMat};
use super::neighbour::{self, Decided, Refinements};
use super::{rat, Q};
use crate::certificate::{AutomatonClaim, SimilarityPart, SimilarityStep};
use num_bigint::BigInt;
use num_traits::{One, Signed, Zero};
use std::collections::{BTreeSet, VecDeque};

/// The most bits of working precision for the digits of a dimension.
const MAX_BITS: u64 = 1 << 14;

/// The frames: the start state's points (a `space × m` matrix, columns are points), then
/// `F_w = F_q·T` along the first subdivision operator reaching w breadth first (operators of a
/// state in index order).
pub(super) fn frames(
    k: &Field,
    a: &AutomatonClaim,
    g: &Graph,
    ops: &[KMat],
) -> Result<Vec<Option<KMat>>, String> {
    let at = a.attractor.as_ref().ok_or("the claim has no attractor")?;
    let m = at.points.len();
    let space = at.points.first().map_or(0, Vec::len);
    if m != a.states[g.start].dim
        || !(1..=3).contains(&space)
        || at.points.iter().any(|p| p.len() != space)
    {
        return Err(format!(
            "the attractor's points: {m} points of the start state's {} in a space of dimension 1 to 3, all of one dimension",
            a.states[g.start].dim
        ));
    }
    let mut data = vec![P::new(); space * m];
    for (j, p) in at.points.iter().enumerate() {
        for (d, x) in p.iter().enumerate() {
            data[d * m + j] = k.element(x)?;
        }
    }
    let mut frames = vec![None; a.states.len()];
    frames[g.start] = Some(KMat {
        rows: space,
        cols: m,
        data,
    });
    let mut queue = VecDeque::from([g.start]);
    while let Some(q) = queue.pop_front() {
        for &o in &g.out[q] {
            let w = a.operators[o].from;
            if frames[w].is_none() {
                let f = k.matmul(frames[q].as_ref().expect("visited"), &ops[o])?;
                frames[w] = Some(f);
                queue.push_back(w);
            }
        }
    }
    Ok(frames)
}

pub(super) fn power(k: &Field, x: &[Q], e: u32) -> P {
    let mut acc = Field::rational(Q::one());
    for _ in 0..e {
        acc = k.mul(&acc, x);
    }
    acc
}

/// `det(I − M(u))` for `M(u)_(i,j) = Σ u^k` over the exponents of the operators from member i
/// to member j, by interpolation at `u = 0, 1, …, n·max k` (Newton's divided differences).
pub(super) fn part_polynomial(n: usize, entries: &[Vec<Vec<u32>>]) -> Result<P, String> {
    let top = entries
        .iter()
        .flatten()
        .flatten()
        .copied()
        .max()
        .unwrap_or(0) as usize;
    let deg = n * top;
    super::within_work(
        "the determinant polynomial of a part",
        ((deg + 1) * n * n * n) as u128 * 16,
    )?;
    let xs: Vec<Q> = (0..=deg).map(|i| Q::from_integer(i.into())).collect();
    let ys: Vec<Q> = xs
        .iter()
        .map(|u| {
            let mut m = vec![vec![Q::zero(); n]; n];
            for i in 0..n {
                for j in 0..n {
                    let s: Q = entries[i][j]
                        .iter()
                        .map(|&e| num_traits::pow(u.clone(), e as usize))
                        .sum();
                    m[i][j] = if i == j { Q::one() - s } else { -s };
                }
            }
            det(m)
        })
        .collect();
    let mut coef = ys;
    for j in 1..xs.len() {
        for i in (j..xs.len()).rev() {
            coef[i] = (&coef[i] - &coef[i - 1]) / (&xs[i] - &xs[i - j]);
        }
    }
    let mut p = vec![coef[xs.len() - 1].clone()];
    for i in (0..xs.len() - 1).rev() {
        p = field::add(
            &field::mul(&p, &[-xs[i].clone(), Q::one()]),
            &[coef[i].clone()],
        );
    }
    Ok(field::trim(p))
}

fn det(mut m: Vec<Vec<Q>>) -> Q {
    let n = m.len();
    let mut d = Q::one();
    for c in 0..n {
        let Some(p) = (c..n).find(|&r| !m[r][c].is_zero()) else {
            return Q::zero();
        };
        if p != c {
            m.swap(p, c);
            d = -d;
        }
        let piv = m[c][c].clone();
        d *= &piv;
        let row = m[c].clone();
        for r in m.iter_mut().skip(c + 1) {
            let f = &r[c] / &piv;
            if !f.is_zero() {
                for (x, y) in r.iter_mut().zip(&row).skip(c) {
                    *x -= &f * y;
                }
            }
        }
    }
    d
}

/// The number of distinct roots of `p` in `(a, b]` (Sturm, on the squarefree part).
pub(super) fn roots_in(p: &[Q], a: &Q, b: &Q) -> usize {
    let (squarefree, _) = field::divide(p, &field::gcd(p, &field::derivative(p)));
    if squarefree.len() < 2 {
        return 0;
    }
    // A squarefree polynomial always has its chain; an empty one counts no root.
    let chain = field::sturm_chain(&squarefree).unwrap_or_default();
    field::sign_changes(&chain, a).saturating_sub(field::sign_changes(&chain, b))
}

/// One part re-derived: its σ (in K), u* and the rational value when claimed.
pub(super) struct PartValue {
    pub(super) sigma: P,
    pub(super) u: Root,
    pub(super) rational: Option<Q>,
}

/// The open-set condition of a part, as its witness proves it.
enum OpenSet {
    /// No witness: not proved either way.
    Unproved,
    /// Holds: convex sets in the charts.
    Convex,
    /// Holds: a closed set of this many neighbour maps without the identity, in these
    /// coordinates, and the graph of their refinements.
    Neighbour(usize, &'static str, Refinements),
    /// Fails: the two words (named) with the same map.
    Fails(String, String),
}

/// The names of a part's states, comma-separated.
pub(super) fn states_label(a: &AutomatonClaim, members: &[usize]) -> String {
    members
        .iter()
        .map(|&q| a.states[q].name.as_str())
        .collect::<Vec<_>>()
        .join(", ")
}

/// A part checked with its open-set witness.
fn check_part(
    k: &Field,
    a: &AutomatonClaim,
    g: &Graph,
    ops: &[KMat],
    frames: &[Option<KMat>],
    members: &[usize],
    p: &SimilarityPart,
) -> Result<(PartValue, OpenSet), String> {
    let (value, inside) = part_value(k, a, g, ops, frames, members, p)?;
    let label = || states_label(a, members);
    let open_set = match (&p.open_set, &p.neighbour_maps) {
        (None, None) => OpenSet::Unproved,
        (Some(sets), None) => {
            check_open_set(k, a, ops, frames, members, &inside, sets)
                .map_err(|e| format!("part {{{}}}: the open-set witness: {e}", label()))?;
            OpenSet::Convex
        }
        (None, Some(w)) => {
            match neighbour::check_neighbour_maps(k, a, ops, frames, members, &inside, w)
                .map_err(|e| format!("part {{{}}}: the neighbour maps: {e}", label()))?
            {
                (Decided::Holds(n, coordinates), Some(r)) => OpenSet::Neighbour(n, coordinates, r),
                (Decided::Holds(..), None) => unreachable!("a holding witness has its graph"),
                (Decided::Fails(u, v), _) => OpenSet::Fails(u, v),
            }
        }
        (Some(_), Some(_)) => {
            return Err(format!(
                "part {{{}}}: two open-set witnesses (convex sets and neighbour maps): give one",
                label()
            ))
        }
    };
    Ok((value, open_set))
}

/// A part's σ, exponents, u* and rational value re-derived (not its open-set witness), and
/// the part's operators (increasing).
pub(super) fn part_value(
    k: &Field,
    a: &AutomatonClaim,
    g: &Graph,
    ops: &[KMat],
    frames: &[Option<KMat>],
    members: &[usize],
    p: &SimilarityPart,
) -> Result<(PartValue, Vec<usize>), String> {
    let label = || states_label(a, members);
    let sigma = k.element(&p.sigma)?;
    if k.sign(&sigma)? <= 0 || k.sign(&k.sub(&sigma, &Field::rational(Q::one())))? >= 0 {
        return Err(format!("part {{{}}}: σ is not in (0, 1)", label()));
    }
    // The operators inside the part, with their claimed exponents.
    let inside: Vec<usize> = members
        .iter()
        .flat_map(|&q| g.out[q].iter().copied())
        .filter(|&o| members.binary_search(&a.operators[o].from).is_ok())
        .collect::<BTreeSet<_>>()
        .into_iter()
        .collect();
    let listed: Vec<usize> = p.exponents.iter().map(|(o, _)| *o).collect();
    if listed != inside {
        return Err(format!(
            "part {{{}}}: the exponents must list exactly the part's operators, in increasing order",
            label()
        ));
    }
    let n = members.len();
    let mut entries = vec![vec![Vec::new(); n]; n];
    for &(o, e) in &p.exponents {
        if e > 128 {
            return Err(format!(
                "part {{{}}}: operator {}'s exponent {e} is above 128",
                label(),
                a.operators[o].name
            ));
        }
        let (q, w) = (a.operators[o].to, a.operators[o].from);
        let (fq, fw) = (
            frames[q].as_ref().expect("reachable"),
            frames[w].as_ref().expect("reachable"),
        );
        if fw.cols < 2 {
            return Err(format!(
                "part {{{}}}: state {} has one point",
                label(),
                a.states[w].name
            ));
        }
        let gw = gram(k, fw);
        if gw.data.iter().all(|x| k.is_zero(x)) {
            return Err(format!(
                "part {{{}}}: the points of state {}'s frame coincide",
                label(),
                a.states[w].name
            ));
        }
        let image = gram(k, &k.matmul(fq, &ops[o])?);
        let r2 = power(k, &sigma, e);
        let scaled = KMat {
            data: gw.data.iter().map(|x| k.mul(x, &r2)).collect(),
            ..gw
        };
        if !k.equal(&image, &scaled) {
            return Err(format!(
                "part {{{}}}: operator {} is not a similitude of squared ratio σ^{e} on the frames (the Gram matrices differ)",
                label(),
                a.operators[o].name
            ));
        }
        let (i, j) = (
            members.binary_search(&q).expect("member"),
            members.binary_search(&w).expect("member"),
        );
        entries[i][j].push(e);
    }
    // M(0) counts the operators of ratio 1 (the first operator reaching a state fixes that
    // state's frame, so it has ratio 1): they must form no cycle, i.e. M(0) is nilpotent and
    // ρ(M(0)) = 0, where the argument below starts.
    let m0: Vec<Vec<BigInt>> = entries
        .iter()
        .map(|r| {
            r.iter()
                .map(|es| BigInt::from(es.iter().filter(|&&e| e == 0).count()))
                .collect()
        })
        .collect();
    let mut pw = m0.clone();
    for _ in 1..n {
        pw = (0..n)
            .map(|i| {
                (0..n)
                    .map(|j| (0..n).map(|t| &pw[i][t] * &m0[t][j]).sum())
                    .collect()
            })
            .collect();
    }
    if pw.iter().flatten().any(|x| !x.is_zero()) {
        return Err(format!(
            "part {{{}}}: the operators of exponent 0 (ratio 1) form a cycle",
            label()
        ));
    }
    let d = part_polynomial(n, &entries)?;
    let u = Root::isolate(&p.u.poly, &p.u.lo, &p.u.hi, "u*")?;
    if !u.is_zero(&d) {
        return Err(format!(
            "part {{{}}}: u* is not a root of det(I − M(u))",
            label()
        ));
    }
    // u* as an element of K, when the step gives it: a root of u*'s polynomial inside its
    // isolating interval is u* itself.
    let u_field = match &p.u_field {
        None => None,
        Some(c) => {
            let y = k.element(c)?;
            let poly: Vec<Q> = p.u.poly.iter().map(|x| rat(x)).collect::<Result<_, _>>()?;
            let value = poly.iter().rev().fold(P::new(), |acc, c| {
                field::add(&k.mul(&acc, &y), &Field::rational(c.clone()))
            });
            let inside = k.sign(&k.sub(&y, &Field::rational(u.lo.clone())))? > 0
                && k.sign(&k.sub(&y, &Field::rational(u.hi.clone())))? < 0;
            if !k.is_zero(&value) || !inside {
                return Err(format!(
                    "part {{{}}}: the element of K given for u* is not u*",
                    label()
                ));
            }
            Some(y)
        }
    };
    if u.lo.is_negative() || u.cmp_rational(&Q::one()) == std::cmp::Ordering::Greater {
        return Err(format!("part {{{}}}: u* is not in (0, 1]", label()));
    }
    if roots_in(&d, &Q::zero(), &u.hi) != 1 {
        return Err(format!(
            "part {{{}}}: det(I − M(u)) has another root in (0, {}]: u* is not shown to be its smallest positive root",
            label(),
            u.hi
        ));
    }
    let rational = match &p.rational {
        None => None,
        Some(v) => Some(
            rational_value(k, &sigma, &u, u_field.as_ref(), v)
                .map_err(|e| format!("part {{{}}}: {e}", label()))?,
        ),
    };
    Ok((PartValue { sigma, u, rational }, inside))
}

/// Checks a claimed rational dimension `s = a/b` of `s = 2·ln u*/ln σ`: `u*^(2b) = σ^a`,
/// compared in K when u* is rational or given as an element of K (`u_field`), through u*'s
/// polynomial when σ^a is rational, and for an integer s with both irrational through
/// `y = u*²`: with u*'s polynomial `f(x) = f_e(x²) + x·f_o(x²)`, y is a root of
/// `f_e(y)² − y·f_o(y)²`; σ^s is y when it is a root too and lies in an interval that holds
/// exactly one root and y (the square of u*'s interval, narrowed until it does).
pub(super) fn rational_value(
    k: &Field,
    sigma: &P,
    u: &Root,
    u_field: Option<&P>,
    s: &str,
) -> Result<Q, String> {
    let v = rat(s)?;
    if v.is_negative() {
        return Err("a negative dimension".into());
    }
    let (num, den) = (v.numer().clone(), v.denom().clone());
    let (an, bn): (u32, u32) = match (u32::try_from(&num), u32::try_from(&den)) {
        (Ok(x), Ok(y)) if x <= 4096 && y <= 4096 => (x, y),
        _ => return Err(format!("the rational dimension {v} is too large")),
    };
    let sa = power(k, sigma, an);
    let holds = match (u.p.len() == 2, sa.len() <= 1) {
        _ if u_field.is_some() => {
            let ub = power(k, u_field.expect("given"), 2 * bn);
            k.is_zero(&k.sub(&ub, &sa))
        }
        (true, _) => {
            let ub = power(k, std::slice::from_ref(&u.lo), 2 * bn);
            k.is_zero(&k.sub(&ub, &sa))
        }
        (false, true) => {
            // u^(2b) − σ^a vanishes at u (σ^a rational).
            let mut z = vec![Q::zero(); 2 * bn as usize + 1];
            z[2 * bn as usize] = Q::one();
            z[0] = -sa.first().cloned().unwrap_or_else(Q::zero);
            u.is_zero(&z)
        }
        (false, false) if bn == 1 => square_is(k, u, &sa)?,
        (false, false) => {
            return Err(
                "a rational dimension that is no integer, with u* and σ both irrational, needs u* as an element of K (`u_field`)".into(),
            )
        }
    };
    match holds {
        true => Ok(v),
        false => Err(format!("the dimension is not {v} (u*^{} ≠ σ^{an})", 2 * bn)),
    }
}

/// Whether `u² = z` for the irrational root u > 0 and z in K (see [`rational_value`]).
fn square_is(k: &Field, u: &Root, z: &P) -> Result<bool, String> {
    let half = |start: usize| -> P { u.p.iter().skip(start).step_by(2).cloned().collect() };
    let (fe, fo) = (half(0), half(1));
    let g = field::add(
        &field::mul(&fe, &fe),
        &field::scale(
            &field::mul(&[Q::zero(), Q::one()], &field::mul(&fo, &fo)),
            &-Q::one(),
        ),
    );
    let g = field::trim(g);
    let value = g.iter().rev().fold(P::new(), |acc, c| {
        field::add(&k.mul(&acc, z), &Field::rational(c.clone()))
    });
    if !k.is_zero(&value) {
        return Ok(false);
    }
    let mut bits = 32;
    loop {
        let (lo, hi) = enclose_root(u, bits)?;
        if !lo.is_positive() {
            return Err("u* is not separated from 0".into());
        }
        let (lo2, hi2) = (&lo * &lo, &hi * &hi);
        if roots_in(&g, &lo2, &hi2) == 1 {
            // y = u² is the only root of g in (lo², hi²]; z is a root of g: it is y when it
            // lies there.
            let above = k.sign(&k.sub(z, &Field::rational(lo2)))? > 0;
            let below = k.sign(&k.sub(z, &Field::rational(hi2)))? <= 0;
            return Ok(above && below);
        }
        if bits >= MAX_BITS {
            return Err(format!("u*² was not isolated at {MAX_BITS} bits"));
        }
        bits *= 2;
    }
}

/// Bounds of a part's dimension `s = 2·ln u*/ln σ` at `bits` bits.
pub(super) fn dimension_bounds(k: &Field, v: &PartValue, bits: u64) -> Result<(Q, Q), String> {
    if let Some(r) = &v.rational {
        return Ok((r.clone(), r.clone()));
    }
    let (ulo, uhi) = enclose_root(&v.u, bits + 16)?;
    let (slo, shi) = enclose(k, &v.sigma, bits + 16)?;
    if !ulo.is_positive() || !slo.is_positive() || shi >= Q::one() {
        return Err("the enclosures of u* and σ are not inside (0, 1)".into());
    }
    super::within_work("logarithms", u128::from(bits) * u128::from(bits))?;
    // A = −ln u ∈ [−ln uhi, −ln ulo], B = −ln σ ∈ [−ln shi, −ln slo], s = 2A/B.
    let (a_lo, a_hi) = (-ln_bounds(&uhi, bits + 16).1, -ln_bounds(&ulo, bits + 16).0);
    let (b_lo, b_hi) = (-ln_bounds(&shi, bits + 16).1, -ln_bounds(&slo, bits + 16).0);
    if !b_lo.is_positive() {
        return Err("ln σ was not separated from 0".into());
    }
    let two = Q::from_integer(2.into());
    let a_lo = if a_lo.is_negative() { Q::zero() } else { a_lo };
    Ok((&two * a_lo / &b_hi, &two * a_hi / &b_lo))
}

/// Checks that `decimal` (with `digits` digits after the point) is the truncation of the
/// largest of the values' dimensions: `decimal ≤ s < decimal + 10^(−digits)`, from enclosures
/// refined up to [`MAX_BITS`] bits.
pub(super) fn check_digits(
    k: &Field,
    values: &[&PartValue],
    claimed: &str,
    digits: usize,
) -> Result<(), String> {
    if digits == 0 || digits > 1000 {
        return Err(format!("{digits} digits: not in 1..=1000"));
    }
    let n = super::parse_decimal(claimed, digits)?;
    let ten = Q::from_integer(num_traits::pow(BigInt::from(10), digits));
    let (low, high) = (
        Q::from_integer(n.clone()) / &ten,
        Q::from_integer(n + 1) / &ten,
    );
    let mut bits = 64u64.max(4 * digits as u64);
    loop {
        let mut lo_max = Q::zero();
        let mut hi_max = Q::zero();
        for v in values {
            let (l, h) = dimension_bounds(k, v, bits)?;
            lo_max = lo_max.max(l);
            hi_max = hi_max.max(h);
        }
        if hi_max < low || lo_max >= high {
            return Err(format!(
                "the dimension is not {claimed} (it lies in [{}, {}])",
                decimal(&lo_max, digits),
                decimal(&hi_max, digits)
            ));
        }
        if lo_max >= low && hi_max < high {
            return Ok(());
        }
        if bits >= MAX_BITS {
            return Err(format!(
                "the digits {claimed} were not decided at {MAX_BITS} bits (a dimension on a decimal boundary must be claimed rational)"
            ));
        }
        bits *= 2;
    }
}

/// The step `similarity-dimension`, and for every part whose neighbour maps hold, the graph of
/// their refinements (for the `boundary-dimension` step).
pub(super) fn check_similarity(
    a: &AutomatonClaim,
    s: &SimilarityStep,
) -> Result<(String, String, Vec<Option<Refinements>>), String> {
    let k = Field::of(a)?;
    let ops = instance(&k, a, &s.instance)?;
    constraints_hold(&k, a, &ops).map_err(|e| format!("the instance: {e}"))?;
    let g = graph(a)?;
    let parts = cyclic_parts(a, &g);
    let listed: Vec<&Vec<usize>> = s.parts.iter().map(|p| &p.states).collect();
    if parts.iter().collect::<Vec<_>>() != listed {
        return Err(format!(
            "the parts must be the {} of the reachable control graph, ordered by smallest state",
            super::counted(
                parts.len(),
                "cyclic strongly connected part",
                "cyclic strongly connected parts"
            )
        ));
    }
    if parts.is_empty() {
        return Err("the control graph has no cycle: there is no similarity dimension".into());
    }
    let frames = frames(&k, a, &g, &ops)?;
    let (values, open_sets): (Vec<PartValue>, Vec<OpenSet>) = parts
        .iter()
        .zip(&s.parts)
        .map(|(m, p)| check_part(&k, a, &g, &ops, &frames, m, p))
        .collect::<Result<Vec<_>, _>>()?
        .into_iter()
        .unzip();
    check_digits(&k, &values.iter().collect::<Vec<_>>(), &s.decimal, s.digits)?;
    let forms: Vec<String> = values
        .iter()
        .zip(&open_sets)
        .zip(&parts)
        .map(|((v, open_set), m)| {
            let states: Vec<&str> = m.iter().map(|&q| a.states[q].name.as_str()).collect();
            let value = match &v.rational {
                Some(r) => r.to_string(),
                None if v.u.p.len() == 2 => format!(
                    "2·ln u*/ln σ with u* = {}, σ = {}",
                    v.u.lo,
                    coords_line(&v.sigma)
                ),
                None => format!(
                    "2·ln u*/ln σ, u* the root of {} in [{}, {}], σ = {}",
                    poly_line(&v.u.p),
                    v.u.lo,
                    v.u.hi,
                    coords_line(&v.sigma)
                ),
            };
            let witness = match open_set {
                OpenSet::Neighbour(n, coordinates, _) => format!(
                    ", the open-set condition by {n} neighbour maps in the {coordinates} (a set closed under refinement, without the identity)"
                ),
                OpenSet::Fails(u, w) => format!(
                    ", the open-set condition fails: the words {u} and {w} have the same map"
                ),
                OpenSet::Convex | OpenSet::Unproved => String::new(),
            };
            format!("{{{}}}: s = {value}{witness}", states.join(", "))
        })
        .collect();
    let hausdorff = hausdorff(a, &parts, &open_sets, &s.decimal);
    Ok((
        format!(
            "{}; every operator inside a part is a similitude of squared ratio σ^k on the frames, exactly in {}; u* is the smallest root of det(I − M(u)) in (0, 1] (Sturm), so ρ(M(u*)) = 1; {}; the largest is {}… ({} digits re-derived)",
            super::counted(parts.len(), "cyclic part", "cyclic parts"),
            if a.field.is_some() { "K" } else { "Q" },
            forms.join("; "),
            s.decimal,
            s.digits
        ),
        format!(
            "similarity dimension = {}… (Mauldin–Williams{}): {hausdorff}",
            s.decimal,
            match s.instance.is_empty() {
                true => "",
                false => ", of the instance the step completes",
            }
        ),
        open_sets
            .into_iter()
            .map(|o| match o {
                OpenSet::Neighbour(_, _, r) => Some(r),
                _ => None,
            })
            .collect(),
    ))
}

/// What the parts' open-set witnesses make of the similarity dimension.
fn hausdorff(
    a: &AutomatonClaim,
    parts: &[Vec<usize>],
    open_sets: &[OpenSet],
    decimal: &str,
) -> String {
    let label = |m: &[usize]| states_label(a, m);
    let fails: Vec<String> = open_sets
        .iter()
        .zip(parts)
        .filter(|(v, _)| matches!(v, OpenSet::Fails(..)))
        .map(|(_, m)| format!("part {{{}}}", label(m)))
        .collect();
    if !fails.is_empty() {
        return format!(
            "an upper bound of the Hausdorff dimension; the open-set condition fails in {} (two words from one state with different first operators have the same map, so their pieces coincide; checked exactly)",
            fails.join(", ")
        );
    }
    let means: Vec<&str> = open_sets
        .iter()
        .map(|v| match v {
            OpenSet::Convex => Some("convex sets in the charts"),
            OpenSet::Neighbour(..) => Some(
                "neighbour maps, Bandt–Graf: a finite set closed under refinement, without the identity",
            ),
            _ => None,
        })
        .collect::<Option<Vec<_>>>()
        .unwrap_or_default();
    if means.is_empty() {
        return "an upper bound of the Hausdorff dimension; equal to it under the open-set condition, which this step does not prove".to_string();
    }
    let mut distinct = means.clone();
    distinct.sort_unstable();
    distinct.dedup();
    match parts.len() {
        1 => format!(
            "the open-set condition holds ({}, checked exactly), so the Hausdorff dimension of the attractor is {decimal}…",
            means[0]
        ),
        _ => format!(
            "the open-set condition holds in every part ({}, checked exactly): each part's attractor has Hausdorff dimension equal to its similarity dimension; the attractor's is at most the largest",
            match distinct.len() {
                1 => distinct[0].to_string(),
                _ => means
                    .iter()
                    .zip(parts)
                    .map(|(w, m)| format!("part {{{}}}: {w}", label(m)))
                    .collect::<Vec<_>>()
                    .join("; "),
            }
        ),
    }
}

fn poly_line(p: &[Q]) -> String {
    let c: Vec<String> = p.iter().map(Q::to_string).collect();
    super::claim::power_text(&c, "x", true)
}

fn coords_line(p: &[Q]) -> String {
    let c: Vec<String> = p.iter().map(Q::to_string).collect();
    super::claim::power_text(&c, "α", false)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_integer_dimension_with_irrational_u_and_sigma_is_checked_through_the_square() {
        // K = Q(√5): u = 1/φ = (√5 − 1)/2, the root of x² + x − 1 in (1/2, 1); σ = 1/φ² =
        // (3 − √5)/2. Then u² = σ: s = 1 holds; s = 2 (u² = σ²) and s = 3 do not.
        let a = AutomatonClaim {
            states: Vec::new(),
            operators: Vec::new(),
            constraints: Vec::new(),
            barycentric: Vec::new(),
            field: Some(crate::certificate::Algebraic {
                poly: vec!["-5".into(), "0".into(), "1".into()],
                lo: "2".into(),
                hi: "3".into(),
            }),
            attractor: None,
            rule: None,
        };
        let k = Field::of(&a).unwrap();
        let u = Root::isolate(&["-1".into(), "1".into(), "1".into()], "1/2", "1", "u").unwrap();
        let sigma = k.element(&vec!["3/2".into(), "-1/2".into()]).unwrap();
        assert_eq!(
            rational_value(&k, &sigma, &u, None, "1").ok(),
            Some(Q::one())
        );
        for wrong in ["2", "3", "0"] {
            assert!(
                rational_value(&k, &sigma, &u, None, wrong).is_err(),
                "{wrong}"
            );
        }
        // A non-integer needs u* in K.
        assert!(rational_value(&k, &sigma, &u, None, "1/2").is_err());
    }

    #[test]
    fn sturm_counts_distinct_roots() {
        // (x − 1/4)²·(x − 1/2) has two distinct roots in (0, 1], one in (0, 1/3].
        let q = |a: i64, b: i64| Q::new(a.into(), b.into());
        let p = field::mul(
            &field::mul(&[q(-1, 4), q(1, 1)], &[q(-1, 4), q(1, 1)]),
            &[q(-1, 2), q(1, 1)],
        );
        assert_eq!(roots_in(&p, &Q::zero(), &Q::one()), 2);
        assert_eq!(roots_in(&p, &Q::zero(), &q(1, 3)), 1);
    }
}
