//! Certified natural logarithms of positive rationals, and certified decimals of a quotient of
//! logarithms, in exact rational arithmetic (no float is formed).
//!
//! `ln x = k·ln 2 + ln y` with `y = x/2^k ∈ [1, 2)`; `ln y = 2·atanh(z)`, `z = (y − 1)/(y + 1) ∈
//! [0, 1/3)`, and `ln 2 = 2·atanh(1/3)`. The series `atanh z = Σ z^(2j+1)/(2j+1)` has positive terms,
//! so a partial sum is a lower bound and the tail after term J is at most
//! `z^(2J+3) / ((2J+3)(1 − z²))`, an upper bound. Written by hand: the certified-real crates pull
//! in heavy dependencies, and these few lines are all the similarity dimension needs.

use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};

fn rat(n: i64, d: i64) -> BigRational {
    BigRational::new(n.into(), d.into())
}

/// `[lo, hi] ∋ atanh(z)` for `0 ≤ z < 1`, of width about `2^-bits`, in fixed point with
/// `bits + 32` fractional bits: the lower bound rounds every product and quotient down from
/// `⌊z⌋`, the upper bound rounds up from `⌈z⌉` and adds the tail bound (rounded up), so both stay
/// bounds.
fn atanh_enclosure(z: &BigRational, bits: u32) -> (BigRational, BigRational) {
    if z.is_zero() {
        return (BigRational::zero(), BigRational::zero());
    }
    let p = bits + 32;
    let one = BigInt::one() << p;
    let ceil_div = |a: &BigInt, d: &BigInt| -> BigInt { (a + d - BigInt::one()).div_floor(d) };
    let zl = (z.numer() << p).div_floor(z.denom());
    let zh = ceil_div(&(z.numer() << p), z.denom());
    let z2l = (&zl * &zl) >> p;
    let z2h = ceil_div(&(&zh * &zh), &one);
    let (mut pl, mut ph) = (zl, zh);
    let (mut sl, mut sh) = (BigInt::zero(), BigInt::zero());
    let ulps = BigInt::one() << 32u32;
    let mut j: u64 = 0;
    loop {
        let d = BigInt::from(2 * j + 1);
        sl += pl.div_floor(&d);
        sh += ceil_div(&ph, &d);
        pl = (&pl * &z2l) >> p;
        ph = ceil_div(&(&ph * &z2h), &one);
        let den = BigInt::from(2 * j + 3) * (&one - &z2h);
        let tail = ceil_div(&(&ph * &one), &den);
        if tail <= ulps {
            return (
                BigRational::new(sl, one.clone()),
                BigRational::new(sh + tail, one),
            );
        }
        j += 1;
    }
}

/// `[lo, hi] ∋ ln x` for a rational `x > 0`, of width about `2^-bits` (times the binary
/// exponent of x). `None` for `x ≤ 0`.
pub fn ln_bounds(x: &BigRational, bits: u32) -> Option<(BigRational, BigRational)> {
    if !x.is_positive() {
        return None;
    }
    // x = 2^k · y, 1 ≤ y < 2.
    let mut k: i64 = x.numer().bits() as i64 - x.denom().bits() as i64;
    let two = BigRational::from_integer(2.into());
    let pow2 = |e: i64| -> BigRational {
        if e >= 0 {
            BigRational::from_integer(BigInt::one() << e as u64)
        } else {
            BigRational::new(BigInt::one(), BigInt::one() << (-e) as u64)
        }
    };
    let mut y = x / pow2(k);
    while y >= two {
        y /= &two;
        k += 1;
    }
    while y < BigRational::one() {
        y *= &two;
        k -= 1;
    }
    let extra = 64 - (k.unsigned_abs().max(1)).leading_zeros();
    let b = bits + extra + 2;
    let z = (&y - BigRational::one()) / (&y + BigRational::one());
    let (ylo, yhi) = atanh_enclosure(&z, b);
    let (l2lo, l2hi) = atanh_enclosure(&rat(1, 3), b);
    let kq = BigRational::from_integer(k.into());
    let (klo, khi) = if k >= 0 {
        (&kq * &l2lo, &kq * &l2hi)
    } else {
        (&kq * &l2hi, &kq * &l2lo)
    };
    Some((two.clone() * (klo + ylo), two * (khi + yhi)))
}

/// Rounds `[lo, hi]` outwards to dyadics of `bits` bits (keeps later arithmetic small).
pub fn round_out(lo: &BigRational, hi: &BigRational, bits: u32) -> (BigRational, BigRational) {
    let scale = BigInt::one() << bits;
    let l = (lo.numer() * &scale).div_floor(lo.denom());
    let h = -((-(hi.numer() * &scale)).div_floor(hi.denom()));
    (
        BigRational::new(l, scale.clone()),
        BigRational::new(h, scale),
    )
}

/// An enclosure `[lo, hi]` of `c · ln(a) / ln(b)` from enclosures of `a` and `b`, all positive,
/// `a, b < 1` on both ends (so both logarithms are negative), `c > 0`. `None` when an end is out
/// of range (the caller refines and asks again).
pub fn log_ratio_bounds(
    c: &BigRational,
    a: (&BigRational, &BigRational),
    b: (&BigRational, &BigRational),
    bits: u32,
) -> Option<(BigRational, BigRational)> {
    let one = BigRational::one();
    if !a.0.is_positive() || !b.0.is_positive() || *a.1 >= one || *b.1 >= one {
        return None;
    }
    // ln a ∈ [ln a.0, ln a.1] ⊂ (−∞, 0), ln b likewise; the ratio of negatives is positive:
    // smallest |ln a| over largest |ln b| and the converse.
    let (la_lo, _) = ln_bounds(a.0, bits)?;
    let (_, la_hi) = ln_bounds(a.1, bits)?;
    let (lb_lo, _) = ln_bounds(b.0, bits)?;
    let (_, lb_hi) = ln_bounds(b.1, bits)?;
    if !la_hi.is_negative() || !lb_hi.is_negative() {
        return None;
    }
    // |ln a| ∈ [−la_hi, −la_lo], |ln b| ∈ [−lb_hi, −lb_lo].
    let lo = c * (-&la_hi) / (-&lb_lo);
    let hi = c * (-&la_lo) / (-&lb_hi);
    Some((lo, hi))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ln2_is_enclosed() {
        // ln 2 = 0.693147180559945309417232121458…
        let (lo, hi) = ln_bounds(&rat(2, 1), 200).unwrap();
        let a = rat(693_147_180_559_945_309, 1_000_000_000_000_000_000);
        let b = rat(693_147_180_559_945_310, 1_000_000_000_000_000_000);
        assert!(a < lo && hi < b);
        let (lo, hi) = ln_bounds(&rat(1, 3), 100).unwrap();
        // ln(1/3) = −1.098612288668109691…
        assert!(rat(-1_098_612_288_668_109_692, 1_000_000_000_000_000_000) < lo);
        assert!(hi < rat(-1_098_612_288_668_109_691, 1_000_000_000_000_000_000));
    }
}
