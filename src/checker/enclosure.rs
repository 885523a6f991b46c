//! Rational enclosures of numbers of K and of roots by bisection on exact sign tests, and of
//! logarithms by series with rigorous tail bounds (`ln_bounds`), needed only for the digits of
//! a dimension and of a contraction bound.

use super::field::Root;
use super::ifs::Field;
use super::{field, Q};
use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{One, Signed, Zero};

/// Rational bounds `lo ≤ x ≤ hi` of an element of K with `hi − lo ≤ 2^−bits`, by bisection on
/// exact sign tests.
pub(super) fn enclose(k: &Field, x: &[Q], bits: u64) -> Result<(Q, Q), String> {
    if x.len() <= 1 {
        let v = x.first().cloned().unwrap_or_else(Q::zero);
        return Ok((v.clone(), v));
    }
    // A first bound: |x| ≤ 2^e by doubling.
    let mut e = Q::one();
    while k.sign(&k.sub(&field::scale(x, &Q::one()), &[e.clone()]))? > 0
        || k.sign(&field::add(x, &[e.clone()]))? < 0
    {
        e *= Q::from_integer(2.into());
        super::within_work("an enclosure in K", 64)?;
    }
    let (mut lo, mut hi) = (-e.clone(), e);
    let width = Q::new(BigInt::one(), BigInt::one() << bits);
    while &hi - &lo > width {
        super::within_work("an enclosure in K", 64)?;
        let mid = (&lo + &hi) / Q::from_integer(2.into());
        match k.sign(&k.sub(x, std::slice::from_ref(&mid)))? {
            0 => return Ok((mid.clone(), mid)),
            s if s > 0 => lo = mid,
            _ => hi = mid,
        }
    }
    Ok((lo, hi))
}

/// Rational bounds of the root `u` with width at most `2^−bits`, by bisection (Sturm).
pub(super) fn enclose_root(u: &Root, bits: u64) -> Result<(Q, Q), String> {
    let (mut lo, mut hi) = (u.lo.clone(), u.hi.clone());
    let width = Q::new(BigInt::one(), BigInt::one() << bits);
    while &hi - &lo > width {
        super::within_work("an enclosure of u*", 64)?;
        let mid = (&lo + &hi) / Q::from_integer(2.into());
        match u.cmp_rational(&mid) {
            std::cmp::Ordering::Equal => return Ok((mid.clone(), mid)),
            std::cmp::Ordering::Greater => lo = mid,
            std::cmp::Ordering::Less => hi = mid,
        }
    }
    Ok((lo, hi))
}

/// `(lo, hi)` integers with `lo·2^−b ≤ atanh(p/q) ≤ hi·2^−b`, for `|p/q| ≤ 1/2`. atanh is odd,
/// so the series `Σ a^(2n+1)/(2n+1)` is summed for `a = |p/q|` in fixed point with `b + 8`
/// bits, every number kept to that width: `a` between `A/2^B` and `(A + 1)/2^B`, every term
/// positive and increasing in `a`; the lower sum truncates the series with powers and terms
/// rounded down, the upper sum rounds them up and adds the tail after the first term below one
/// unit, at most `term/(1 − a²) ≤ 4/3` units.
fn atanh_bounds(p: &BigInt, q: &BigInt, b: u64) -> (BigInt, BigInt) {
    let guard = b + 8;
    let a_lo = (p.abs() << guard).div_floor(q);
    let a_hi = &a_lo + 1;
    let sum = |a: &BigInt, up: bool| -> BigInt {
        let a2 = a * a;
        let mut power = a.clone();
        let mut total = BigInt::zero();
        let mut m = 1u64;
        loop {
            let d = BigInt::from(m);
            let term = match up {
                true => -((-&power).div_floor(&d)),
                false => power.div_floor(&d),
            };
            if term.is_zero() || (up && term <= BigInt::one()) {
                total += match up {
                    true => BigInt::from(2),
                    false => BigInt::zero(),
                };
                break;
            }
            total += term;
            let next = &power * &a2;
            power = match up {
                true => -((-next) >> (2 * guard)),
                false => next >> (2 * guard),
            };
            m += 2;
        }
        total
    };
    let (lo, hi) = (sum(&a_lo, false), sum(&a_hi, true));
    // Back from b + 8 bits to b, outward.
    let (lo, hi) = (lo >> 8u32, -((-hi) >> 8u32));
    match p.is_negative() {
        true => (-hi, -lo),
        false => (lo, hi),
    }
}

/// Bounds of `ln x` for a rational `x > 0`, as `(lo, hi)` rationals with width about
/// `2^−(b−8)`: `x = 2^e·x'`, `x' ∈ [1/2, 2)`… `ln x = e·ln 2 + 2·atanh((x' − 1)/(x' + 1))`,
/// `ln 2 = 2·atanh(1/3)`.
pub(super) fn ln_bounds(x: &Q, b: u64) -> (Q, Q) {
    let e = x.numer().bits() as i64 - x.denom().bits() as i64;
    let xr = match e >= 0 {
        true => x / Q::from_integer(BigInt::one() << e as u64),
        false => x * Q::from_integer(BigInt::one() << (-e) as u64),
    };
    let y = (&xr - Q::one()) / (&xr + Q::one());
    let (alo, ahi) = atanh_bounds(y.numer(), y.denom(), b);
    let (llo, lhi) = atanh_bounds(&BigInt::one(), &BigInt::from(3), b);
    let scale = Q::from_integer(BigInt::one() << b);
    let two = Q::from_integer(2.into());
    let ee = Q::from_integer(e.into());
    let (l2lo, l2hi) = (
        &two * Q::from_integer(llo) / &scale,
        &two * Q::from_integer(lhi) / &scale,
    );
    let (elo, ehi) = match e >= 0 {
        true => (&ee * &l2lo, &ee * &l2hi),
        false => (&ee * &l2hi, &ee * &l2lo),
    };
    (
        elo + &two * Q::from_integer(alo) / &scale,
        ehi + &two * Q::from_integer(ahi) / &scale,
    )
}

pub(super) fn decimal(x: &Q, digits: usize) -> String {
    let ten = num_traits::pow(BigInt::from(10), digits);
    let v = (x * Q::from_integer(ten)).floor().to_integer();
    let s = v.abs().to_string();
    let s = format!("{s:0>width$}", width = digits + 1);
    let (i, f) = s.split_at(s.len() - digits);
    format!("{}{i}.{f}", if v.is_negative() { "-" } else { "" })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn logarithms_are_enclosed() {
        // ln 2 = 0.693147180559945309417…, ln(1/27) = −3·ln 3 = −3.295836866004329074185…
        // (published constants): the enclosures lie inside these 18-digit brackets.
        let q = |n: i64, d: i64| Q::new(n.into(), d.into());
        let e18 = 1_000_000_000_000_000_000i64;
        let (lo, hi) = ln_bounds(&Q::from_integer(2.into()), 80);
        assert!(q(693_147_180_559_945_309, e18) <= lo && hi <= q(693_147_180_559_945_310, e18));
        assert!(&hi - &lo < Q::new(1.into(), (1i64 << 60).into()));
        let (lo, hi) = ln_bounds(&q(1, 27), 80);
        let e17 = 100_000_000_000_000_000i64;
        assert!(q(-329_583_686_600_432_908, e17) <= lo && hi <= q(-329_583_686_600_432_907, e17));
        // x = 1 exactly: ln 1 = 0 lies in the enclosure.
        let (lo, hi) = ln_bounds(&Q::one(), 80);
        assert!(lo <= Q::zero() && Q::zero() <= hi);
    }
}
