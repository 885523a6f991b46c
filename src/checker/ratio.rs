//! The limit-ratio step, in every case (shared radii, periodic classes, ρ = 1).
//!
//! 1. The classes reached from the start and their periods are recomputed (mutual reachability,
//!    BFS levels) and compared with the certificate.
//! 2. ρ is isolated (Sturm) and shown ≥ 1. Each class is transient, or *dominant* (a positive
//!    left eigenvector of its block for ρ: by Perron–Frobenius its radius is ρ, and its
//!    eigenvalues of modulus ρ are `ρ·ω`, `ω^p = 1`, p its period), or *below* (Collatz–Wielandt:
//!    radius < lo ≤ ρ). `P` = lcm of the dominant periods.
//! 3. The augmented matrix `A = [[M, c], [0, 1]]` on the reached types has its eigenvalues in the
//!    class blocks and 1, so every eigenvalue of `A^P` of modulus ≥ ρ^P equals `y₀ = ρ^P` (ρ ≥ 1).
//!    `q = det(y·I − A^P)` (per class block by Faddeev–LeVerrier, then Newton's identities)
//!    annihilates `A^P`
//!    (Cayley–Hamilton), so for each residue `r` the counts `x_n = X_(P·n + r)` have the generating
//!    function `N(w)/Q(w)`, `Q(w) = w^d·q(1/w)`, `N = Q·Σ x_n w^n mod w^d`, from the first `d`
//!    terms, computed here by iterating the substitution.
//! 4. With `y = 1/w`: `Σ x_n w^n = y·Ñ(y)/q(y)`, `Ñ(y) = y^(d−1)·N(1/y)`. The pole at `w₀ = 1/y₀`
//!    (the only one on its circle) has order `m − j`, `m` the multiplicity of `y₀` in `q`, `j` that
//!    in `Ñ`, decided by exact zero tests of derivatives at `y₀` in Q[x]/(p). Then
//!    `x_n ~ C·n^(m−j−1)·ρ^(P·n)` with `C` proportional to `Ñ^(j)(y₀)`, the factor being common to
//!    faces and lacunas: `R_r` is 1, 0, or `a_L / (a_L + 2·a_C)` (lacunas counted in halves).

use super::closure::Substitution;
use super::field::{add, scale, Root, P};
use super::series::{charpoly, counts, power_charpoly, residue, Residue};
use super::{rat, Q};
use crate::certificate::{ClassClaim, PointClaim, RadiusWitness, RatioStep};
use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{One, Signed, Zero};
use std::collections::{BTreeMap, VecDeque};

/// The most levels of counts (`P·d`) the checker computes: the counts grow like `ρ^(P·d)`, so
/// a hostile period must not make it hang. Closures met in practice need `P·d` below a few
/// hundred.
const MAX_LEVELS: usize = 20_000;

/// The largest class whose characteristic polynomial the checker computes (Faddeev–LeVerrier
/// costs about `size²·arcs` big-integer operations).
const MAX_CLASS: usize = 1_000;

/// The product of two integer polynomials (ascending coefficients).
fn times(a: &[BigInt], b: &[BigInt]) -> Vec<BigInt> {
    let mut c = vec![BigInt::zero(); a.len() + b.len() - 1];
    for (i, x) in a.iter().enumerate() {
        for (j, y) in b.iter().enumerate() {
            c[i + j] += x * y;
        }
    }
    c
}

/// A recomputed class: members ascending and period (`None` for a transient type).
type Class = (Vec<usize>, Option<u64>);

/// Classes reached from `start` (members ascending, ordered by smallest member) with periods.
fn classes(m: &[BTreeMap<usize, u64>], start: &[usize]) -> Vec<Class> {
    let n = m.len();
    let reach = |from: usize| {
        let mut seen = vec![false; n];
        let mut queue = VecDeque::from([from]);
        seen[from] = true;
        while let Some(t) = queue.pop_front() {
            for &s in m[t].keys() {
                if !std::mem::replace(&mut seen[s], true) {
                    queue.push_back(s);
                }
            }
        }
        seen
    };
    let mut reached = vec![false; n];
    start.iter().for_each(|&s| {
        reach(s)
            .iter()
            .enumerate()
            .for_each(|(t, &r)| reached[t] |= r)
    });
    let from: Vec<Vec<bool>> = (0..n)
        .map(|t| if reached[t] { reach(t) } else { vec![] })
        .collect();
    let mut out = Vec::new();
    let mut placed = vec![false; n];
    for t in (0..n).filter(|&t| reached[t]) {
        if placed[t] {
            continue;
        }
        let members: Vec<usize> = (t..n)
            .filter(|&s| reached[s] && from[t][s] && from[s][t])
            .collect();
        members.iter().for_each(|&s| placed[s] = true);
        // Period: gcd of level(u) + 1 − level(v) over arcs inside the class (BFS levels).
        let inside = |s: &usize| members.binary_search(s).is_ok();
        let mut level: BTreeMap<usize, i64> = BTreeMap::from([(t, 0)]);
        let mut queue = VecDeque::from([t]);
        let mut g: i64 = 0;
        while let Some(u) = queue.pop_front() {
            for v in m[u].keys().filter(|v| inside(v)) {
                let lu = level[&u];
                match level.get(v) {
                    Some(&lv) => g = g.gcd(&(lu + 1 - lv)),
                    None => {
                        level.insert(*v, lu + 1);
                        queue.push_back(*v);
                    }
                }
            }
        }
        let cyclic = members.len() > 1 || m[t].contains_key(&t);
        out.push((members, cyclic.then_some(g.unsigned_abs())));
    }
    out
}

fn int(k: u64) -> Q {
    Q::from_integer(k.into())
}

/// Checks the radius witness of one class; returns whether the class is dominant.
fn check_radius(
    m: &[BTreeMap<usize, u64>],
    root: &Root,
    (k, class): (usize, &ClassClaim),
) -> Result<bool, String> {
    let members = &class.members;
    let entry = |t: usize, s: usize| int(m[t].get(&s).copied().unwrap_or(0));
    match (&class.radius, class.period) {
        (RadiusWitness::Transient, None) => Ok(false),
        (RadiusWitness::Perron(y), Some(_)) => {
            let y: Vec<P> = y
                .iter()
                .map(|v| root.element(v))
                .collect::<Result<_, _>>()?;
            if y.len() != members.len() {
                return Err(format!("class {k}: the Perron vector has the wrong length"));
            }
            for (i, &s) in members.iter().enumerate() {
                let yb = members.iter().zip(&y).fold(P::new(), |acc, (&t, yt)| {
                    add(&acc, &scale(yt, &entry(t, s)))
                });
                if !root.is_zero(&add(
                    &yb,
                    &scale(&root.mul(&y[i], &[Q::zero(), Q::one()]), &-Q::one()),
                )) {
                    return Err(format!("class {k}: y·B ≠ ρ·y at type {s}"));
                }
            }
            match y.iter().position(|v| root.sign(v) != Some(1)) {
                Some(i) => Err(format!(
                    "class {k}: y at type {} is not shown > 0",
                    members[i]
                )),
                None => Ok(true),
            }
        }
        (RadiusWitness::Below(x), Some(_)) => {
            let x: Vec<Q> = x.iter().map(|s| rat(s)).collect::<Result<_, _>>()?;
            if x.len() != members.len() || x.iter().any(|v| !v.is_positive()) {
                return Err(format!(
                    "class {k}: the bound is not a positive vector on its members"
                ));
            }
            for (i, &t) in members.iter().enumerate() {
                let bx: Q = members.iter().zip(&x).map(|(&s, v)| v * entry(t, s)).sum();
                if bx >= &root.lo * &x[i] {
                    return Err(format!(
                        "class {k}: (B·x)_{t} ≥ lo·x_{t}, no Collatz–Wielandt bound"
                    ));
                }
            }
            Ok(false)
        }
        _ => Err(format!("class {k}: the witness does not fit its period")),
    }
}

/// The parsed substitution of a ratio step: matrix rows and start counts.
type Parsed = (Vec<BTreeMap<usize, u64>>, BTreeMap<usize, u64>);

fn parse(r: &RatioStep) -> Result<Parsed, String> {
    let n = r.matrix.len();
    if r.contribution_halves.len() != n {
        return Err(format!(
            "{} contributions for {n} types",
            r.contribution_halves.len()
        ));
    }
    let mut m: Vec<BTreeMap<usize, u64>> = vec![BTreeMap::new(); n];
    for (t, row) in r.matrix.iter().enumerate() {
        for &(s, k) in row {
            if s >= n {
                return Err(format!("matrix row {t}: type {s} out of range"));
            }
            if k > 0 {
                *m[t].entry(s).or_insert(0) += k;
            }
        }
    }
    let mut start: BTreeMap<usize, u64> = BTreeMap::new();
    for &(t, k) in &r.start {
        if t >= n || k == 0 {
            return Err(format!("start ({t}, {k}) is out of range or empty"));
        }
        *start.entry(t).or_insert(0) += k;
    }
    if start.is_empty() {
        return Err("no start type".into());
    }
    Ok((m, start))
}

/// The claimed decimal `d` with `k` digits: `0 ≤ v − d < 10^(−k)`.
fn check_decimal(root: &Root, v: &[Q], text: &str) -> bool {
    let (int, frac) = text.split_once('.').unwrap_or((text, ""));
    if frac.len() > 10_000 {
        return false; // beyond any certified precision lacuna writes (and costly to check)
    }
    let digits = u32::try_from(frac.len()).unwrap_or(u32::MAX);
    let ulp = Q::new(BigInt::one(), BigInt::from(10).pow(digits));
    let Ok(d) = format!("{int}{frac}").parse::<BigInt>() else {
        return false;
    };
    let d = Q::from_integer(d) * &ulp;
    let minus = |x: &Q| add(v, &[-x]);
    int.chars().all(|c| c.is_ascii_digit())
        && root.sign(&minus(&d)).is_some_and(|s| s >= 0)
        && root.sign(&minus(&(d + ulp))) == Some(-1)
}

/// Checks one claimed limit point against the recomputed `R_r`.
fn check_point(root: &Root, r: usize, got: &Residue, claim: &PointClaim) -> Result<P, String> {
    let v = root.element(&claim.value)?;
    if !got.is(root, &v) {
        return Err(format!(
            "residue {r}: the claimed value is not R_{r} ({})",
            got.why
        ));
    }
    let what = format!("R_{r}");
    let real = Root::isolate(&claim.real.poly, &claim.real.lo, &claim.real.hi, &what)?;
    let ints: Vec<BigInt> = real.p.iter().map(|c| c.to_integer()).collect();
    let at_least = |x: &[Q], y: &Q| root.sign(&add(x, &[-y.clone()])).is_some_and(|s| s >= 0);
    let hi_minus_v = add(std::slice::from_ref(&real.hi), &scale(&v, &-Q::one()));
    if !root.is_zero(&root.eval_at(&ints, &v))
        || !at_least(&v, &real.lo)
        || !at_least(&hi_minus_v, &Q::zero())
    {
        return Err(format!(
            "residue {r}: the claimed polynomial and interval do not isolate R_{r}"
        ));
    }
    if !check_decimal(root, &v, &claim.decimal) {
        return Err(format!(
            "residue {r}: the decimal {} is not a truncation of R_{r}",
            claim.decimal
        ));
    }
    Ok(v)
}

pub(super) fn check_ratio(r: &RatioStep, closure: Option<&Substitution>) -> Result<String, String> {
    let (m, start) = parse(r)?;
    let tied = match closure {
        Some(c)
            if c.matrix == m && c.contributions == r.contribution_halves && c.start == start =>
        {
            "the closure's substitution"
        }
        Some(_) => {
            return Err("matrix, contributions or start differ from the closure step".into())
        }
        None => "the given substitution (no closure step to tie it to)",
    };
    let start_types: Vec<usize> = start.keys().copied().collect();
    let cls = classes(&m, &start_types);
    let claimed: Vec<Class> = r
        .classes
        .iter()
        .map(|c| (c.members.clone(), c.period))
        .collect();
    if cls != claimed {
        return Err(
            "the classes or periods differ from the checker's own (BFS, gcd of levels)".into(),
        );
    }
    let root = Root::isolate(&r.rho.poly, &r.rho.lo, &r.rho.hi, "ρ")?;
    if root.sign(&[-Q::one(), Q::one()]).is_none_or(|s| s < 0) {
        return Err("ρ ≥ 1 is not shown".into());
    }
    let mut period = 1u64;
    for (k, class) in r.classes.iter().enumerate() {
        if check_radius(&m, &root, (k, class))? {
            period = period.lcm(&class.period.expect("a Perron class has a cycle"));
        }
    }
    if !r
        .classes
        .iter()
        .any(|c| matches!(c.radius, RadiusWitness::Perron(_)))
    {
        return Err("no class has radius ρ (no Perron vector)".into());
    }
    if period != r.period || r.points.len() as u64 != period {
        return Err(format!(
            "the period is P = {period} (lcm of the dominant periods); the certificate claims {} with {} point(s)",
            r.period,
            r.points.len()
        ));
    }
    // det(x·I − A) for the augmented matrix A = [[M, c], [0, 1]] on the reached types: ordered
    // by the class DAG, A is block triangular, so it is the product of the class blocks'
    // characteristic polynomials and (x − 1) for the lacuna type.
    let d = cls.iter().map(|(ms, _)| ms.len()).sum::<usize>() + 1;
    let big_p = usize::try_from(period).map_err(|_| "the period is too large")?;
    if big_p.saturating_mul(d) > MAX_LEVELS {
        return Err(format!(
            "P·d = {period}·{d} levels of counts exceed the checker's limit of {MAX_LEVELS}"
        ));
    }
    let mut chi = vec![-BigInt::one(), BigInt::one()];
    for (members, _) in &cls {
        if members.len() > MAX_CLASS {
            return Err(format!(
                "a class of {} types exceeds the checker's limit of {MAX_CLASS}",
                members.len()
            ));
        }
        let at = |s: &usize| members.binary_search(s).ok();
        let block: Vec<Vec<(usize, BigInt)>> = members
            .iter()
            .map(|t| {
                let inside = m[*t]
                    .iter()
                    .filter_map(|(s, k)| Some((at(s)?, BigInt::from(*k))));
                inside.collect()
            })
            .collect();
        chi = times(&chi, &charpoly(&block)?);
    }
    let q = power_charpoly(&chi, big_p)?;
    let (faces, lacunas) = counts(&m, &r.contribution_halves, &start, big_p * d);
    let y0 = root.reduce(&[vec![Q::zero(); big_p], vec![Q::one()]].concat());
    // Q(w) = Σ b_i w^i with b_i = q_(d−i); N_j = Σ_(i ≤ j) b_i·x_(j−i); Ñ reverses N.
    let reflected = |seq: &[BigInt], res: usize| -> Vec<BigInt> {
        let mut n: Vec<BigInt> = (0..d)
            .map(|j| {
                (0..=j)
                    .map(|i| &q[d - i] * &seq[big_p * (j - i) + res])
                    .sum()
            })
            .collect();
        n.reverse();
        n
    };
    let mut values: Vec<P> = Vec::new();
    let mut whys = Vec::new();
    for (res, claim) in r.points.iter().enumerate() {
        let got = residue(
            &root,
            &q,
            &reflected(&lacunas, res),
            &reflected(&faces, res),
            &y0,
        )
        .map_err(|e| format!("residue {res}: {e}"))?;
        values.push(check_point(&root, res, &got, claim)?);
        whys.push(match period {
            1 => got.why,
            _ => format!("r = {res}: {}", got.why),
        });
    }
    let exists = values
        .iter()
        .all(|v| root.is_zero(&add(v, &scale(&values[0], &-Q::one()))));
    if exists != r.exists {
        return Err(format!(
            "the certificate claims the limit {}, but the residues give {}",
            ["does not exist", "exists"][usize::from(r.exists)],
            ["different limit points", "one value"][usize::from(exists)]
        ));
    }
    let rho = match root.p.len() {
        2 => format!("ρ = {}", root.lo),
        _ => format!("ρ isolated in ({}, {}) (Sturm)", root.lo, root.hi),
    };
    let dominant = r
        .classes
        .iter()
        .filter(|c| matches!(c.radius, RadiusWitness::Perron(_)))
        .count();
    let verdict = match exists {
        true => format!(
            "R exists and equals {} ({})",
            shown(&r.points[0].value),
            r.points[0].decimal
        ),
        false => format!(
            "R_i has no limit; limit points by residue mod {period}: {}",
            r.points
                .iter()
                .map(|p| format!("{} ({})", shown(&p.value), p.decimal))
                .collect::<Vec<_>>()
                .join(", ")
        ),
    };
    Ok(format!(
        "{} class(es) re-derived for {tied}; {rho}, {dominant} dominant class(es) (Perron vectors, \
         Collatz–Wielandt bounds), P = {period}; {}; {verdict}",
        cls.len(),
        whys.join("; ")
    ))
}

fn shown(v: &[String]) -> String {
    match v.len() {
        0 => "0".into(),
        1 => v[0].clone(),
        _ => format!("({}) on 1, ρ, …", v.join(", ")),
    }
}
