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
//!    faces and lacunas: `R_r` is 1, 0, or `a_L / (a_L + 2·a_C)` (lacunas counted in halves; in
//!    quarters for volumes: `a_L / (a_L + 4·a_C)`).

use super::claim::parse_decimal;
use super::closure::Substitution;
use super::field::{add, scale, Root, P};
use super::series::{charpoly, counts, multiplicity, power_charpoly, residue, Powers, Residue};
use super::{budget, over, rat, within_work, Checked, Q};
use crate::certificate::{ClassClaim, PointClaim, RadiusWitness, RatioStep};
use num_bigint::{BigInt, BigUint};
use num_integer::Integer;
use num_traits::{One, Signed, ToPrimitive, Zero};
use std::collections::{BTreeMap, VecDeque};

/// The largest class whose characteristic polynomial the checker computes (its cost is also
/// estimated against the work budget; this only keeps the estimate's own arithmetic small).
const MAX_CLASS: usize = 100_000;

/// The lcm of the periods, exactly (a big integer: the lcm of 115 small periods can exceed
/// 2^64, and a wrapped value must never be compared with the claim).
pub(super) fn lcm_of(periods: impl IntoIterator<Item = u64>) -> BigUint {
    periods
        .into_iter()
        .fold(BigUint::one(), |acc, p| acc.lcm(&BigUint::from(p)))
}

/// The bits of a big integer (at least 1), as a u128 for work estimates.
fn bits(x: &BigUint) -> u128 {
    u128::from(x.bits().max(1))
}

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

/// The types reached from `start`, in a breadth-first order.
fn reached(m: &[BTreeMap<usize, BigUint>], start: &[usize]) -> Vec<bool> {
    let mut seen = vec![false; m.len()];
    let mut queue: VecDeque<usize> = start.iter().copied().collect();
    start.iter().for_each(|&s| seen[s] = true);
    while let Some(t) = queue.pop_front() {
        for &s in m[t].keys() {
            if !std::mem::replace(&mut seen[s], true) {
                queue.push_back(s);
            }
        }
    }
    seen
}

/// Classes reached from `start` (members ascending, ordered by smallest member) with periods,
/// in linear time: Kosaraju (an iterative depth-first search for the finishing order, then the
/// reversed graph), and per class the gcd of `level(u) + 1 − level(v)` over its arcs (BFS
/// levels, which are below the number of types).
fn classes(m: &[BTreeMap<usize, BigUint>], start: &[usize]) -> Vec<Class> {
    let n = m.len();
    let inside = reached(m, start);
    let mut order = Vec::new();
    let mut done = vec![false; n];
    for root in (0..n).filter(|&t| inside[t]) {
        if done[root] {
            continue;
        }
        done[root] = true;
        let mut stack: Vec<(usize, std::collections::btree_map::Keys<usize, BigUint>)> =
            vec![(root, m[root].keys())];
        while let Some((t, next)) = stack.last_mut() {
            match next.next() {
                Some(&s) if !done[s] => {
                    done[s] = true;
                    stack.push((s, m[s].keys()));
                }
                Some(_) => {}
                None => {
                    order.push(*t);
                    stack.pop();
                }
            }
        }
    }
    let mut back: Vec<Vec<usize>> = vec![Vec::new(); n];
    for t in (0..n).filter(|&t| inside[t]) {
        m[t].keys().for_each(|&s| back[s].push(t));
    }
    let mut class_of = vec![usize::MAX; n];
    let mut found: Vec<Vec<usize>> = Vec::new();
    for &root in order.iter().rev() {
        if class_of[root] != usize::MAX {
            continue;
        }
        let id = found.len();
        let mut members = vec![root];
        class_of[root] = id;
        let mut k = 0;
        while k < members.len() {
            let t = members[k];
            k += 1;
            for &s in &back[t] {
                if class_of[s] == usize::MAX {
                    class_of[s] = id;
                    members.push(s);
                }
            }
        }
        members.sort_unstable();
        found.push(members);
    }
    found.sort_unstable_by_key(|c| c[0]);
    found
        .into_iter()
        .map(|members| {
            let t = members[0];
            let id = class_of[t];
            let mut level: BTreeMap<usize, u64> = BTreeMap::from([(t, 0)]);
            let mut queue = VecDeque::from([t]);
            let mut g: u64 = 0;
            while let Some(u) = queue.pop_front() {
                let lu = level[&u];
                for v in m[u].keys().filter(|v| class_of[**v] == id) {
                    match level.get(v) {
                        // level(v) ≤ level(u) + 1 for a BFS arc, so this is ≥ 0.
                        Some(&lv) => g = g.gcd(&(lu + 1 - lv)),
                        None => {
                            level.insert(*v, lu + 1);
                            queue.push_back(*v);
                        }
                    }
                }
            }
            let cyclic = members.len() > 1 || m[t].contains_key(&t);
            (members, cyclic.then_some(g))
        })
        .collect()
}

fn int(k: &BigUint) -> Q {
    Q::from_integer(BigInt::from(k.clone()))
}

/// Checks the radius witness of one class; returns whether the class is dominant. Linear in
/// the class's arcs (field operations).
fn check_radius(
    m: &[BTreeMap<usize, BigUint>],
    root: &Root,
    (k, class): (usize, &ClassClaim),
) -> Result<bool, String> {
    let members = &class.members;
    let at = |s: &usize| members.binary_search(s).ok();
    match (&class.radius, class.period) {
        (RadiusWitness::Transient, None) => Ok(false),
        (RadiusWitness::Perron(y), Some(_)) => {
            if y.len() != members.len() {
                return Err(format!("class {k}: the Perron vector has the wrong length"));
            }
            let y: Vec<P> = y
                .iter()
                .map(|v| root.element(v))
                .collect::<Result<_, _>>()?;
            // (y·B)_s = Σ_t y_t·B[t][s], over the arcs inside the class.
            let mut yb: Vec<P> = vec![P::new(); members.len()];
            for (i, t) in members.iter().enumerate() {
                for (s, e) in &m[*t] {
                    if let Some(j) = at(s) {
                        yb[j] = add(&yb[j], &scale(&y[i], &int(e)));
                    }
                }
            }
            for (i, &s) in members.iter().enumerate() {
                let rho_y = root.mul(&y[i], &[Q::zero(), Q::one()]);
                if !root.is_zero(&add(&yb[i], &scale(&rho_y, &-Q::one()))) {
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
            if x.len() != members.len() {
                return Err(format!("class {k}: the bound has the wrong length"));
            }
            let x: Vec<Q> = x.iter().map(|s| rat(s)).collect::<Result<_, _>>()?;
            if x.iter().any(|v| !v.is_positive()) {
                return Err(format!(
                    "class {k}: the bound is not a positive vector on its members"
                ));
            }
            for (i, &t) in members.iter().enumerate() {
                let bx: Q = m[t]
                    .iter()
                    .filter_map(|(s, e)| Some(&x[at(s)?] * int(e)))
                    .sum();
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

/// Checks one claimed limit point against the recomputed `R_r`. The decimal is compared
/// with `R_r` exactly through the point's own isolating polynomial (Sturm counts at the decimal
/// and one unit above it), with no bisection, so its cost does not depend on how close the
/// truncation is.
fn check_point(
    root: &Root,
    (r, digits): (usize, usize),
    got: &Residue,
    claim: &PointClaim,
) -> Result<P, String> {
    let v = root.element(&claim.value)?;
    if !got.is(root, &v) {
        return Err(format!(
            "residue {r}: the claimed value is not R_{r} ({})",
            got.why
        ));
    }
    let what = format!("R_{r}");
    if claim.real.poly.len() > root.p.len() {
        return Err(format!(
            "residue {r}: the polynomial of R_{r} has a higher degree than ρ's, which R_{r} \
             cannot need (R_{r} lies in Q(ρ))"
        ));
    }
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
    // R_r is now the only root of `real` in [lo, hi]: compare it with d and d + 10^(−k).
    let d = parse_decimal(&claim.decimal, digits).map_err(|e| format!("residue {r}: {e}"))?;
    let ulp = Q::new(BigInt::one(), BigInt::from(10u32).pow(digits as u32));
    let d = Q::from_integer(d) * &ulp;
    let above = &d + &ulp;
    if real.cmp_rational(&d) == std::cmp::Ordering::Less
        || real.cmp_rational(&above) != std::cmp::Ordering::Less
    {
        return Err(format!(
            "residue {r}: the decimal {} is not a truncation of R_{r}",
            super::claim::shorten(&claim.decimal)
        ));
    }
    Ok(v)
}

/// Checks a limit-ratio step about `sub` (`tied` says where the substitution comes from).
pub(super) fn check_ratio(r: &RatioStep, sub: &Substitution, tied: &str) -> Checked {
    let m = &sub.matrix;
    let start_types: Vec<usize> = sub.start.keys().copied().collect();
    let cls = classes(m, &start_types);
    if cls.len() != r.classes.len()
        || cls
            .iter()
            .zip(&r.classes)
            .any(|((ms, p), c)| *ms != c.members || *p != c.period)
    {
        return Err(
            "the classes or periods differ from the checker's own (Kosaraju, gcd of levels)".into(),
        );
    }
    // ρ is an eigenvalue of a cyclic class block, so a polynomial of higher degree than the
    // largest class is refused before any arithmetic on it.
    let largest = cls
        .iter()
        .filter(|(_, p)| p.is_some())
        .map(|(ms, _)| ms.len())
        .max()
        .unwrap_or(0);
    if r.rho.poly.len() > largest + 1 {
        return Err(format!(
            "ρ's polynomial has degree {}, more than the largest class ({largest} types) allows",
            r.rho.poly.len().saturating_sub(1)
        ));
    }
    // The period the witnesses claim (the lcm of the periods of the classes with a Perron
    // vector) and every cost, before any arithmetic: a wrong or costly claim is refused at once.
    let claimed_dominant: Vec<u64> = r
        .classes
        .iter()
        .filter(|c| matches!(c.radius, RadiusWitness::Perron(_)))
        .filter_map(|c| c.period)
        .collect();
    if claimed_dominant.is_empty() {
        return Err("no class has radius ρ (no Perron vector)".into());
    }
    let period = lcm_of(claimed_dominant);
    if period != BigUint::from(r.period) || BigUint::from(r.points.len()) != period {
        return Err(format!(
            "the period is P = {period} (lcm of the dominant periods); the certificate claims {} \
             with {}",
            r.period,
            super::counted(r.points.len(), "point", "points")
        ));
    }
    let d = cls.iter().map(|(ms, _)| ms.len()).sum::<usize>() + 1;
    let levels = &period * BigUint::from(d);
    let max_levels = budget().levels;
    if levels > BigUint::from(max_levels) {
        return Err(over(
            &format!("P·d = {period}·{d} levels of counts"),
            levels.to_u128().unwrap_or(u128::MAX),
            max_levels.into(),
            "max-levels",
        ));
    }
    let Some(big_p) = period.to_usize() else {
        return Err("the period does not fit in memory".into());
    };
    let levels = big_p * d;
    // The counts: levels · arcs products of numbers of up to levels·log₂(growth) bits.
    let arcs: usize = cls
        .iter()
        .flat_map(|(ms, _)| ms.iter())
        .map(|&t| m[t].len() + 1)
        .sum();
    let growth = cls
        .iter()
        .flat_map(|(ms, _)| ms.iter())
        .map(|&t| m[t].values().sum::<BigUint>() + &sub.contributions[t])
        .max()
        .unwrap_or_default();
    let start_bits = sub.start.values().map(bits).max().unwrap_or(1);
    let count_bits = (levels as u128) * bits(&growth) + start_bits;
    within_work(
        "iterating the substitution",
        (levels as u128) * (arcs as u128) * (count_bits.div_ceil(64) + 1),
    )?;
    let mut blocks = Vec::with_capacity(cls.len());
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
                    .filter_map(|(s, k)| Some((at(s)?, BigInt::from(k.clone()))));
                inside.collect()
            })
            .collect();
        // Faddeev–LeVerrier: size steps of (arcs × size) products with entries of about
        // size·(log₂(max entry) + log₂ size) bits.
        let size = members.len() as u128;
        let class_arcs: u128 = block.iter().map(|r| r.len() as u128).sum::<u128>() + 1;
        let entry_bits = block
            .iter()
            .flatten()
            .map(|(_, k)| u128::from(k.bits().max(1)))
            .max()
            .unwrap_or(1);
        within_work(
            "the characteristic polynomial of a class (Faddeev–LeVerrier)",
            size * size * class_arcs * ((size * (entry_bits + 10)).div_ceil(64) + 1),
        )?;
        blocks.push(block);
    }
    let root = Root::isolate(&r.rho.poly, &r.rho.lo, &r.rho.hi, "ρ")?;
    if root.sign(&[-Q::one(), Q::one()]).is_none_or(|s| s < 0) {
        return Err("ρ ≥ 1 is not shown".into());
    }
    for (k, class) in r.classes.iter().enumerate() {
        check_radius(m, &root, (k, class))?;
    }
    // det(x·I − A) for the augmented matrix A = [[M, c], [0, 1]] on the reached types: ordered
    // by the class DAG, A is block triangular, so it is the product of the class blocks'
    // characteristic polynomials and (x − 1) for the lacuna type.
    let mut chi = vec![-BigInt::one(), BigInt::one()];
    for block in &blocks {
        chi = times(&chi, &charpoly(block)?);
    }
    let q = power_charpoly(&chi, big_p)?;
    let (faces, lacunas) = counts(m, &sub.contributions, &sub.start, levels);
    let y0 = root.reduce(&[vec![Q::zero(); big_p], vec![Q::one()]].concat());
    // Q(w) = Σ b_i w^i with b_i = q_(d−i); N_j = Σ_(i ≤ j) b_i·x_(j−i); Ñ reverses N.
    let powers = Powers::of(&root, &y0, d);
    let reflected = |seq: &[BigInt], res: usize| -> Result<Vec<BigInt>, String> {
        let mut n = Vec::with_capacity(d);
        for j in 0..d {
            let mut sum = BigInt::zero();
            for i in 0..=j {
                let (a, b) = (&q[d - i], &seq[big_p * (j - i) + res]);
                powers.spend(a.bits(), b.bits())?;
                sum += a * b;
            }
            n.push(sum);
        }
        n.reverse();
        Ok(n)
    };
    let m = multiplicity(&root, &powers, &q)?;
    let mut values: Vec<P> = Vec::new();
    let mut whys = Vec::new();
    for (res, claim) in r.points.iter().enumerate() {
        let got = residue(
            &root,
            (&powers, m),
            (&reflected(&lacunas, res)?, sub.unit),
            &reflected(&faces, res)?,
        )
        .map_err(|e| format!("residue {res}: {e}"))?;
        values.push(check_point(&root, (res, r.digits), &got, claim)?);
        whys.push(match big_p {
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
    Ok((
        format!(
            "{} re-derived for {tied}; {rho}, {} (Perron vectors, Collatz–Wielandt bounds), P = \
             {period}; {}; {verdict}",
            super::counted(cls.len(), "class", "classes"),
            super::counted(dominant, "dominant class", "dominant classes"),
            whys.join("; ")
        ),
        format!("limit ratio: {verdict}"),
    ))
}

fn shown(v: &[String]) -> String {
    match v.len() {
        0 => "0".into(),
        1 => v[0].clone(),
        _ => format!("({}) on 1, ρ, …", v.join(", ")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_lcm_of_periods_does_not_wrap() {
        // 115 classes: the primes below 640 and 3 (for period 3). Their lcm, the product of the
        // primes, is far beyond 2^64; any u64 fold of it is wrong.
        let primes: Vec<u64> = (2u64..640)
            .filter(|p| (2..*p).take_while(|d| d * d <= *p).all(|d| p % d != 0))
            .take(115)
            .collect();
        assert_eq!(primes.len(), 115);
        let exact = lcm_of(primes.iter().copied());
        let product = primes.iter().fold(BigUint::one(), |a, &p| a * p);
        assert_eq!(exact, product);
        assert!(exact.bits() > 64);
        // Periods whose lcm is ≡ 1 mod 2^64: 3 and p = 3^(−1) mod 2^64 = (2^65 + 1)/3 (odd,
        // and coprime to 3 since 2^65 + 1 = 3·p is not divisible by 9: 2^65 ≡ 2^5 = 32 ≡ 5
        // mod 9, so 2^65 + 1 ≡ 6). A u64 fold multiplies them to 2^65 + 1 ≡ 1.
        let p = 12_297_829_382_473_034_411u64;
        assert_eq!(3u64.wrapping_mul(p), 1);
        assert_eq!(lcm_of([3, p]), (BigUint::one() << 65u32) + BigUint::one());
    }

    #[test]
    fn classes_and_periods_by_hand() {
        // 0 → 1, 1 → 2, 2 → 0 (a 3-cycle), 2 → 3, 3 → 3 (a loop), 4 unreached.
        let e = |pairs: &[usize]| -> BTreeMap<usize, BigUint> {
            pairs.iter().map(|&s| (s, BigUint::one())).collect()
        };
        let m = vec![e(&[1]), e(&[2]), e(&[0, 3]), e(&[3]), e(&[0])];
        assert_eq!(
            classes(&m, &[0]),
            vec![(vec![0, 1, 2], Some(3)), (vec![3], Some(1))]
        );
        // A transient type: 0 → 1 → 1.
        let m = vec![e(&[1]), e(&[1])];
        assert_eq!(classes(&m, &[0]), vec![(vec![0], None), (vec![1], Some(1))]);
    }
}
