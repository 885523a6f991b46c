//! Integer gcd and reduced rationals for the hot paths of the exact kernel (issue #34).
//!
//! Why not `num_integer::Integer::gcd`: num-bigint's `BigUint::gcd` is Stein's binary gcd, whose
//! every step shifts, compares and subtracts whole `BigUint`s for about one bit of progress (its
//! `biguint_shr2` was 14 % of the operator kernel's samples). Here two integers that fit in a machine word take a word-sized binary
//! gcd, and larger ones Lehmer's gcd (Knuth, TAOCP vol. 2, §4.5.2, Algorithm L): Euclid's
//! quotients simulated on the leading 63 bits, applied to the big integers once per batch. The gcd
//! is unique, so every result equals num-bigint's (the property tests below compare the two).
//!
//! [`lcm`], [`ratio`], [`mul`], [`add`] and [`sub`] build on it; the rationals they return are
//! reduced with a positive denominator exactly as [`BigRational::new`] reduces them.

use num_bigint::{BigInt, BigUint};
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};

/// A binary gcd (Stein's algorithm) on one unsigned primitive width; `gcd(0, 0) = 0`. One body
/// for the word and the double word, which are both hot.
macro_rules! binary_gcd {
    ($name:ident, $t:ty, $doc:literal) => {
        #[doc = $doc]
        fn $name(mut a: $t, mut b: $t) -> $t {
            if a == 0 {
                return b;
            }
            if b == 0 {
                return a;
            }
            let shift = (a | b).trailing_zeros();
            a >>= a.trailing_zeros();
            loop {
                b >>= b.trailing_zeros();
                if a > b {
                    std::mem::swap(&mut a, &mut b);
                }
                b -= a;
                if b == 0 {
                    return a << shift;
                }
            }
        }
    };
}

binary_gcd!(gcd_u64, u64, "Binary gcd of two machine words.");
binary_gcd!(gcd_u128, u128, "Binary gcd of two double words.");

/// `n/d` reduced, positive denominator, for double words (`d ≠ 0`, both above `i128::MIN`).
fn ratio_small(n: i128, d: i128) -> BigRational {
    let g = gcd_u128(n.unsigned_abs(), d.unsigned_abs()) as i128;
    let (n, d) = (n / g, d / g);
    if d < 0 {
        BigRational::new_raw(BigInt::from(-n), BigInt::from(-d))
    } else {
        BigRational::new_raw(BigInt::from(n), BigInt::from(d))
    }
}

/// Numerator and denominator as machine words, when both fit.
fn small(x: &BigRational) -> Option<(i64, i64)> {
    Some((x.numer().to_i64()?, x.denom().to_i64()?))
}

/// The leading 62 bits of `x`, shifted right by `shift` bits.
fn top_bits(x: &BigUint, shift: u64) -> i64 {
    (x >> shift).to_i64().expect("62 bits")
}

/// `Some(k)` when `x = 2^k`.
fn power_of_two(x: &BigUint) -> Option<u64> {
    let k = x.trailing_zeros()?;
    (x.bits() == k + 1).then_some(k)
}

/// `p·u + q·v` for cofactors of opposite signs (or zero) whose result is known to be ≥ 0
/// (Lehmer's cofactors keep the remainders non-negative).
fn combine(p: i64, u: &BigUint, q: i64, v: &BigUint) -> BigUint {
    let (pu, qv) = (u * p.unsigned_abs(), v * q.unsigned_abs());
    if p >= 0 && q >= 0 {
        pu + qv
    } else if p >= 0 {
        pu - qv
    } else {
        qv - pu
    }
}

/// The gcd of two natural numbers (`gcd(0, 0) = 0`), equal to `BigUint::gcd`.
pub fn gcd_uint(a: &BigUint, b: &BigUint) -> BigUint {
    if let (Some(x), Some(y)) = (a.to_u64(), b.to_u64()) {
        return BigUint::from(gcd_u64(x, y));
    }
    // A power of two (the denominators of dyadic numbers): the gcd is the smaller power of two
    // dividing both.
    for (x, y) in [(a, b), (b, a)] {
        if let Some(k) = power_of_two(x) {
            let t = y.trailing_zeros().map_or(k, |t| t.min(k));
            return BigUint::one() << t;
        }
    }
    let (mut u, mut v) = if a >= b {
        (a.clone(), b.clone())
    } else {
        (b.clone(), a.clone())
    };
    // Invariant: u ≥ v.
    loop {
        if let Some(vs) = v.to_u64() {
            if vs == 0 {
                return u;
            }
            let us = u
                .to_u64()
                .unwrap_or_else(|| (&u % vs).to_u64().expect("< v"));
            return BigUint::from(gcd_u64(us, vs));
        }
        let bits = u.bits();
        if bits - v.bits() >= 32 {
            // Sizes far apart: one big division does what many simulated steps could not.
            let r = &u % &v;
            u = std::mem::replace(&mut v, r);
            continue;
        }
        // 62 bits: the simulated remainders and the cofactors stay below 2^62 in magnitude, so
        // every sum and product of the loop fits in an i64 (no double-word division).
        let shift = bits - 62;
        let (mut uh, mut vh) = (top_bits(&u, shift), top_bits(&v, shift));
        let (mut ca, mut cb, mut cc, mut cd) = (1i64, 0i64, 0i64, 1i64);
        loop {
            if vh + cc <= 0 || vh + cd <= 0 {
                break;
            }
            let q = (uh + ca) / (vh + cc);
            if q != (uh + cb) / (vh + cd) {
                break;
            }
            (ca, cc) = (cc, ca - q * cc);
            (cb, cd) = (cd, cb - q * cd);
            (uh, vh) = (vh, uh - q * vh);
        }
        if cb == 0 {
            let r = &u % &v;
            u = std::mem::replace(&mut v, r);
        } else {
            let nu = combine(ca, &u, cb, &v);
            let nv = combine(cc, &u, cd, &v);
            u = nu;
            v = nv;
        }
    }
}

/// The non-negative gcd of two integers, equal to `Integer::gcd` on `BigInt`.
pub fn gcd(a: &BigInt, b: &BigInt) -> BigInt {
    BigInt::from(gcd_uint(a.magnitude(), b.magnitude()))
}

/// `|x|`'s decimal digits appended to `out`, as `Display` writes them (`i64` formatting when the
/// value fits: num-bigint's `Display` builds a digit vector and a string per call).
pub fn push_int(out: &mut String, x: &BigInt) {
    use std::fmt::Write;
    match x.to_i64() {
        Some(v) => write!(out, "{v}"),
        None => write!(out, "{x}"),
    }
    .expect("writing to a String");
}

/// `q` appended to `out` as `Display` writes it (`n` or `n/d`), without the intermediate strings
/// of num-rational's `Display`.
pub fn push_ratio(out: &mut String, q: &BigRational) {
    push_int(out, q.numer());
    if !q.denom().is_one() {
        out.push('/');
        push_int(out, q.denom());
    }
}

/// The non-negative lcm of two integers, equal to `Integer::lcm` on `BigInt`.
pub fn lcm(a: &BigInt, b: &BigInt) -> BigInt {
    if a.is_zero() && b.is_zero() {
        return BigInt::zero();
    }
    let g = gcd(a, b);
    (a / &g * b).abs()
}

/// `n/d` reduced with a positive denominator, equal to `BigRational::new(n, d)` (`d ≠ 0`).
pub fn ratio(n: BigInt, d: BigInt) -> BigRational {
    assert!(!d.is_zero(), "denominator == 0");
    if let (Some(a), Some(b)) = (n.to_i64(), d.to_i64()) {
        return ratio_small(a.into(), b.into());
    }
    if n.is_zero() {
        return BigRational::new_raw(n, BigInt::one());
    }
    let g = gcd(&n, &d);
    let (n, d) = if g.is_one() { (n, d) } else { (n / &g, d / &g) };
    if d.is_negative() {
        BigRational::new_raw(-n, -d)
    } else {
        BigRational::new_raw(n, d)
    }
}

/// `x·y`, equal to the `Mul` of [`BigRational`].
pub fn mul(x: &BigRational, y: &BigRational) -> BigRational {
    if x.is_zero() || y.is_zero() {
        return BigRational::zero();
    }
    if let (Some((a, b)), Some((c, d))) = (small(x), small(y)) {
        // Products of two words fit in a double word; one gcd of the result.
        return ratio_small(i128::from(a) * i128::from(c), i128::from(b) * i128::from(d));
    }
    // Cross gcds: the product of the reduced factors is then reduced already.
    let g1 = gcd(x.numer(), y.denom());
    let g2 = gcd(y.numer(), x.denom());
    let n = (x.numer() / &g1) * (y.numer() / &g2);
    let d = (x.denom() / &g2) * (y.denom() / &g1);
    BigRational::new_raw(n, d)
}

/// `x + y`, equal to the `Add` of [`BigRational`].
pub fn add(x: &BigRational, y: &BigRational) -> BigRational {
    if let (Some((a, b)), Some((c, d))) = (small(x), small(y)) {
        let (a, b, c, d) = (i128::from(a), i128::from(b), i128::from(c), i128::from(d));
        return ratio_small(a * d + c * b, b * d);
    }
    if x.denom() == y.denom() {
        return ratio(x.numer() + y.numer(), x.denom().clone());
    }
    ratio(
        x.numer() * y.denom() + y.numer() * x.denom(),
        x.denom() * y.denom(),
    )
}

/// `x − y`, equal to the `Sub` of [`BigRational`].
pub fn sub(x: &BigRational, y: &BigRational) -> BigRational {
    if let (Some((a, b)), Some((c, d))) = (small(x), small(y)) {
        let (a, b, c, d) = (i128::from(a), i128::from(b), i128::from(c), i128::from(d));
        return ratio_small(a * d - c * b, b * d);
    }
    if x.denom() == y.denom() {
        return ratio(x.numer() - y.numer(), x.denom().clone());
    }
    ratio(
        x.numer() * y.denom() - y.numer() * x.denom(),
        x.denom() * y.denom(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_bigint::Sign;
    use num_integer::Integer;
    use proptest::prelude::*;

    /// Big integers of many shapes: 0, 1, small, powers of two (times odd factors), and products
    /// of random words up to ~1300 bits, with shared factors to make the gcd non-trivial.
    fn arb_uint() -> impl Strategy<Value = BigUint> {
        prop_oneof![
            Just(BigUint::zero()),
            Just(BigUint::one()),
            any::<u64>().prop_map(BigUint::from),
            (0u32..1100, 1u64..1000).prop_map(|(e, o)| BigUint::from(o) << e),
            proptest::collection::vec(any::<u64>(), 1..22).prop_map(|w| {
                w.iter()
                    .fold(BigUint::zero(), |acc, &x| (acc << 64u32) + BigUint::from(x))
            }),
        ]
    }

    fn arb_int() -> impl Strategy<Value = BigInt> {
        (arb_uint(), any::<bool>()).prop_map(|(m, neg)| {
            BigInt::from_biguint(if neg { Sign::Minus } else { Sign::Plus }, m)
        })
    }

    fn arb_rat() -> impl Strategy<Value = BigRational> {
        (arb_int(), arb_uint(), arb_int()).prop_map(|(n, d, c)| {
            let d = BigInt::from(d) + 1;
            BigRational::new(n * &c, d * c.abs().max(BigInt::one()))
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]
        #[test]
        fn gcd_matches_num_bigint(a in arb_uint(), b in arb_uint(), c in arb_uint()) {
            prop_assert_eq!(gcd_uint(&a, &b), a.gcd(&b));
            prop_assert_eq!(gcd_uint(&a, &a), a.clone());
            // A shared factor c: the gcd is at least c.
            let (ac, bc) = (&a * &c, &b * &c);
            prop_assert_eq!(gcd_uint(&ac, &bc), ac.gcd(&bc));
            prop_assert_eq!(gcd_uint(&bc, &ac), ac.gcd(&bc));
        }

        #[test]
        fn int_gcd_lcm_match(a in arb_int(), b in arb_int()) {
            prop_assert_eq!(gcd(&a, &b), a.gcd(&b));
            prop_assert_eq!(lcm(&a, &b), a.lcm(&b));
        }

        #[test]
        fn rational_ops_match(x in arb_rat(), y in arb_rat(), n in arb_int(), d in arb_int()) {
            // Representations, not only values: numerators and denominators equal.
            let same = |r: BigRational, e: BigRational| r.into_raw() == e.into_raw();
            prop_assert!(same(mul(&x, &y), &x * &y));
            prop_assert!(same(add(&x, &y), &x + &y));
            prop_assert!(same(sub(&x, &y), &x - &y));
            prop_assert!(same(add(&x, &x), &x + &x));
            prop_assert!(same(sub(&x, &x), &x - &x));
            if !d.is_zero() {
                prop_assert!(same(ratio(n.clone(), d.clone()), BigRational::new(n, d)));
            }
        }
    }

    /// Rationals of one-word numerators and denominators, extremes included: the double-word
    /// fast paths.
    fn arb_small_rat() -> impl Strategy<Value = BigRational> {
        let word = prop_oneof![
            Just(i64::MIN),
            Just(i64::MAX),
            Just(0i64),
            Just(1i64),
            -100i64..100,
            any::<i64>()
        ];
        let den = prop_oneof![Just(i64::MAX), Just(1i64), 1i64..100, 1i64..];
        (word, den).prop_map(|(n, d)| BigRational::new(n.into(), d.into()))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(5000))]
        #[test]
        fn small_rational_ops_match(x in arb_small_rat(), y in arb_small_rat(), n in any::<i64>(), d in any::<i64>()) {
            let same = |r: BigRational, e: BigRational| r.into_raw() == e.into_raw();
            prop_assert!(same(mul(&x, &y), &x * &y));
            prop_assert!(same(add(&x, &y), &x + &y));
            prop_assert!(same(sub(&x, &y), &x - &y));
            if d != 0 {
                let (n, d) = (BigInt::from(n), BigInt::from(d));
                prop_assert!(same(ratio(n.clone(), d.clone()), BigRational::new(n, d)));
            }
        }
    }

    proptest! {
        #[test]
        fn push_ratio_matches_display(x in arb_rat(), n in any::<i64>(), d in 1i64..) {
            for q in [x, BigRational::new(n.into(), d.into()), BigRational::from_integer(n.into())] {
                let mut s = String::new();
                push_ratio(&mut s, &q);
                prop_assert_eq!(s, q.to_string());
            }
            for v in [i64::MIN, i64::MAX, 0, -1] {
                let mut s = String::new();
                push_int(&mut s, &BigInt::from(v));
                prop_assert_eq!(s, v.to_string());
            }
        }
    }

    #[test]
    fn edge_cases() {
        let p = BigUint::one() << 1000u32;
        let q = BigUint::one() << 700u32;
        assert_eq!(gcd_uint(&p, &q), q);
        assert_eq!(
            gcd_uint(&BigUint::zero(), &BigUint::zero()),
            BigUint::zero()
        );
        assert_eq!(gcd_uint(&p, &BigUint::zero()), p);
        assert_eq!(gcd_u64(0, 0), 0);
        assert_eq!(gcd_u64(12, 18), 6);
    }
}
