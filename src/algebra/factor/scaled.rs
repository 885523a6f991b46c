//! One square-free part of [`super::factor`]: a monic rational `g` of degree n is factored as the
//! monic integer polynomial `G(y) = a^n g(y / a)`. Any `a` making `G` integral gives the same
//! factors of `g`; the lcm of the denominators of `g` (the scale this module was first written
//! with) can make `G`'s coefficients hundreds of bits longer than needed, and the Hensel lift
//! runs as many more steps. [`factor_part`] factors at a smaller scale and gives the factors in
//! the order the lcm scale gives them.

use super::{
    factor_monic, fp_rem, modular_factors, residue, subsets_in_order, trim, FactorError, Fp, BUDGET,
};
use crate::algebra::poly::Poly;
use num_bigint::BigInt;
use num_traits::{One, Zero};

/// The lcm of the denominators of `g`'s coefficients.
pub(super) fn lcm_scale(g: &Poly) -> BigInt {
    g.coeffs().iter().fold(BigInt::one(), |acc, c| {
        crate::algebra::intgcd::lcm(&acc, c.denom())
    })
}

/// A scale `a` making `a^n g(y / a)` integral, at most [`lcm_scale`]: for the primes 2, 3, 5
/// and 7 the least exponent `e` with `q^(e·(n−i))` divisible by the `q`-part of every
/// denominator `d_i`, times the lcm of the denominators' other parts.
pub(super) fn small_scale(g: &Poly) -> BigInt {
    let n = g.deg();
    let mut exps = [0u32; 4];
    let mut rest = BigInt::one();
    for (i, c) in g.coeffs().iter().enumerate().take(n) {
        if c.is_zero() {
            continue;
        }
        let mut d = c.denom().clone();
        let e = (n - i) as u32;
        for (k, q) in [2u32, 3, 5, 7].into_iter().enumerate() {
            let mut v = 0u32;
            while (&d % q).is_zero() {
                d /= q;
                v += 1;
            }
            exps[k] = exps[k].max(v.div_ceil(e));
        }
        rest = crate::algebra::intgcd::lcm(&rest, &d);
    }
    [2u32, 3, 5, 7]
        .into_iter()
        .zip(exps)
        .fold(rest, |acc, (q, e)| acc * BigInt::from(q).pow(e))
}

/// `a^n g(y / a)`'s integer coefficients (constant first), `None` when one is not an integer.
fn scaled_ints(g: &Poly, a: &BigInt) -> Option<Vec<BigInt>> {
    let n = g.deg();
    let mut big: Vec<BigInt> = Vec::with_capacity(n + 1);
    let mut apow = BigInt::one();
    for i in (0..=n).rev() {
        // c·a^i must be an integer: a remainder test, no rational product.
        let c = g.coeff(i);
        let (q, r) = num_integer::Integer::div_rem(&(c.numer() * &apow), c.denom());
        if !r.is_zero() {
            return None;
        }
        big.push(q);
        apow *= a;
    }
    big.reverse();
    Some(big)
}

/// The monic irreducible factors of `g` (monic, square-free, degree ≥ 1) found at scale `a`, in
/// the order of [`factor_monic`] on `a^n g(y / a)`, the factor `x` last when `g(0) = 0`.
pub(super) fn factor_scaled(g: &Poly, a: &BigInt) -> Result<Vec<Poly>, FactorError> {
    let mut big = scaled_ints(g, a).expect("the scale makes g integral");
    let zero_root = big[0].is_zero();
    if zero_root {
        big.remove(0);
    }
    let mut parts = if big.len() > 1 {
        factor_monic(&big)?
    } else {
        Vec::new()
    };
    if zero_root {
        parts.push(vec![BigInt::zero(), BigInt::one()]);
    }
    Ok(parts
        .into_iter()
        .map(|h| {
            // back: h(a x), made monic
            let mut apow = BigInt::one();
            let mut c = Vec::with_capacity(h.len());
            for x in &h {
                c.push(x * &apow);
                apow *= a;
            }
            Poly::from_bigints(&c).monic()
        })
        .collect())
}

/// [`factor_scaled`] at [`lcm_scale`] — the same factors in the same order — computed at
/// [`small_scale`]. When two factors have the same degree their order is the lcm scale's:
/// each factor, brought to that scale, is matched with the modular factors it reduces to there,
/// and the recombination's order over those is replayed (without lifting). Whenever anything
/// does not match, the lcm scale is used as it is.
pub(super) fn factor_part(g: &Poly) -> Result<Vec<Poly>, FactorError> {
    let a_old = lcm_scale(g);
    let a = small_scale(g);
    if a >= a_old {
        return factor_scaled(g, &a_old);
    }
    let Ok(found) = factor_scaled(g, &a) else {
        return factor_scaled(g, &a_old);
    };
    let mut degrees: Vec<usize> = found.iter().map(Poly::deg).collect();
    degrees.sort_unstable();
    if degrees.windows(2).all(|w| w[0] != w[1]) {
        // Distinct degrees: `factor` sorts them by degree, whatever their order here.
        return Ok(found);
    }
    match order_at_scale(g, &a_old, found) {
        Some(r) => r,
        None => factor_scaled(g, &a_old),
    }
}

/// The factors `found` of `g` in [`factor_scaled`]'s order at scale `a`, or its error; `None`
/// when the factors do not match that scale's modular factors one to one.
fn order_at_scale(
    g: &Poly,
    a: &BigInt,
    found: Vec<Poly>,
) -> Option<Result<Vec<Poly>, FactorError>> {
    let mut big = scaled_ints(g, a)?;
    let zero_root = big[0].is_zero();
    if zero_root {
        big.remove(0);
    }
    let (mut rest, mut x): (Vec<Poly>, Vec<Poly>) = found
        .into_iter()
        .partition(|h| !(zero_root && h.deg() == 1 && h.coeff(0).is_zero()));
    if x.len() != usize::from(zero_root) {
        return None;
    }
    if big.len() <= 1 {
        return rest.is_empty().then_some(Ok(x));
    }
    let Some((p, gs)) = modular_factors(&big) else {
        // Irreducible there: a single factor.
        return (rest.len() == 1).then(|| {
            rest.append(&mut x);
            Ok(rest)
        });
    };
    // The modular factors each factor reduces to (its subset of `gs`).
    let mut owner = vec![usize::MAX; gs.len()];
    for (j, h) in rest.iter().enumerate() {
        let hp: Fp = trim(scaled_ints(h, a)?.iter().map(|c| residue(c, p)).collect());
        for (t, gt) in gs.iter().enumerate() {
            if fp_rem(&hp, gt, p).is_empty() {
                if owner[t] != usize::MAX {
                    return None;
                }
                owner[t] = j;
            }
        }
    }
    if owner.contains(&usize::MAX) {
        return None;
    }
    let (degree, modular) = (big.len() - 1, gs.len());
    let order = match replay_recombination(owner)? {
        Some(order) => order,
        None => {
            return Some(Err(FactorError {
                degree,
                modular,
                prime: p,
                budget: BUDGET,
            }))
        }
    };
    let mut slots: Vec<Option<Poly>> = rest.into_iter().map(Some).collect();
    let mut out: Vec<Poly> = order
        .into_iter()
        .map(|j| slots[j].take())
        .collect::<Option<_>>()?;
    if slots.iter().any(Option::is_some) {
        return None;
    }
    out.append(&mut x);
    Some(Ok(out))
}

/// The order in which [`super::recombine`] finds the factors when the modular factor `t`
/// belongs to the true factor `owner[t]`: subsets by increasing size, lexicographically over the
/// pool left; a subset divides `f` exactly when it is one factor's whole set (a union of two or
/// more is larger than each of them, and these were found at their own size). `Some(None)` when
/// the recombination would exceed its trial budget, `None` when what is left at the end is not
/// one factor (which the argument rules out).
pub(super) fn replay_recombination(pool: Vec<usize>) -> Option<Option<Vec<usize>>> {
    let mut out = Vec::new();
    let whole_factor = |pool: &[usize], subset: &[usize]| {
        let j = pool[subset[0]];
        let found = subset.iter().all(|&i| pool[i] == j)
            && pool.iter().filter(|&&o| o == j).count() == subset.len();
        if found {
            out.push(j);
        }
        found
    };
    let Some(pool) = subsets_in_order(pool, whole_factor) else {
        return Some(None);
    };
    if let Some(&j) = pool.first() {
        if pool.iter().any(|&o| o != j) {
            return None;
        }
        out.push(j);
    }
    Some(Some(out))
}
