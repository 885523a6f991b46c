//! Dense univariate polynomials over Q, exact: arithmetic, gcd, square-free decomposition, Sturm
//! sequences and real root isolation.
//!
//! Coefficients are `BigRational`, lowest degree first, without trailing zeros (the zero polynomial
//! has no coefficients). Everything here is exact; no float is ever formed. Written by hand: the
//! MIT/Apache polynomial crates either use floats for roots or (polyfactor/polycore) rebuild the
//! Sturm chain on every query and bring their own polynomial type; this module is small and is
//! shared by [`crate::algebra::factor`] (factorisation), [`crate::algebra::algebraic`] and [`crate::analysis::ratio`].

use num_bigint::{BigInt, Sign};
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
use std::fmt;
use std::ops::{Add, Mul, Neg, Sub};

/// A polynomial with rational coefficients, lowest degree first.
#[derive(Clone, Debug, PartialEq, Eq, Hash, Default)]
pub struct Poly {
    c: Vec<BigRational>,
}

impl Poly {
    /// The zero polynomial.
    pub fn zero() -> Self {
        Poly { c: Vec::new() }
    }

    /// The constant `q`.
    pub fn constant(q: BigRational) -> Self {
        Poly::new(vec![q])
    }

    /// The polynomial `x`.
    pub fn x() -> Self {
        Poly::from_ints(&[0, 1])
    }

    /// The polynomial with coefficients `c` (lowest degree first); trailing zeros are dropped.
    pub fn new(mut c: Vec<BigRational>) -> Self {
        while c.last().is_some_and(Zero::is_zero) {
            c.pop();
        }
        Poly { c }
    }

    /// The polynomial with small integer coefficients `c` (lowest degree first).
    pub fn from_ints(c: &[i64]) -> Self {
        Poly::new(
            c.iter()
                .map(|&a| BigRational::from_integer(a.into()))
                .collect(),
        )
    }

    /// The polynomial with integer coefficients `c` (lowest degree first).
    pub fn from_bigints(c: &[BigInt]) -> Self {
        Poly::new(
            c.iter()
                .map(|a| BigRational::from_integer(a.clone()))
                .collect(),
        )
    }

    /// The coefficients, lowest degree first (empty for zero).
    pub fn coeffs(&self) -> &[BigRational] {
        &self.c
    }

    /// The coefficient of `x^i` (zero beyond the degree).
    pub fn coeff(&self, i: usize) -> BigRational {
        self.c.get(i).cloned().unwrap_or_else(BigRational::zero)
    }

    /// Whether this is the zero polynomial.
    pub fn is_zero(&self) -> bool {
        self.c.is_empty()
    }

    /// The degree; 0 for constants and for zero (check [`Poly::is_zero`]).
    pub fn deg(&self) -> usize {
        self.c.len().saturating_sub(1)
    }

    /// The leading coefficient (zero for the zero polynomial).
    pub fn lc(&self) -> BigRational {
        self.c.last().cloned().unwrap_or_else(BigRational::zero)
    }

    /// `self * q`.
    pub fn scale(&self, q: &BigRational) -> Poly {
        Poly::new(
            self.c
                .iter()
                .map(|a| crate::algebra::intgcd::mul(a, q))
                .collect(),
        )
    }

    /// `self` divided by its leading coefficient (zero stays zero).
    pub fn monic(&self) -> Poly {
        if self.is_zero() {
            return Poly::zero();
        }
        // Already monic: no rational product (and no gcd) per coefficient.
        if self.c.last().is_some_and(One::is_one) {
            return self.clone();
        }
        self.scale(&self.lc().recip())
    }

    /// `x^k * self`.
    pub fn shift(&self, k: usize) -> Poly {
        if self.is_zero() {
            return Poly::zero();
        }
        let mut c = vec![BigRational::zero(); k];
        c.extend(self.c.iter().cloned());
        Poly { c }
    }

    /// Quotient and remainder of the division by `d` (panics when `d` is zero).
    pub fn div_rem(&self, d: &Poly) -> (Poly, Poly) {
        assert!(!d.is_zero(), "polynomial division by zero");
        if self.c.len() < d.c.len() {
            return (Poly::zero(), self.clone());
        }
        let dn = d.deg();
        let inv = d.lc().recip();
        let mut r = self.c.clone();
        let mut q = vec![BigRational::zero(); r.len() - dn];
        for i in (0..q.len()).rev() {
            let t = &r[i + dn] * &inv;
            if t.is_zero() {
                continue;
            }
            for (j, dj) in d.c.iter().enumerate().take(dn) {
                if !dj.is_zero() {
                    r[i + j] -= &t * dj;
                }
            }
            r[i + dn] = BigRational::zero();
            q[i] = t;
        }
        r.truncate(dn);
        (Poly::new(q), Poly::new(r))
    }

    /// The remainder of the division by `d`.
    pub fn rem(&self, d: &Poly) -> Poly {
        self.div_rem(d).1
    }

    /// `Some(self / d)` when `d` divides `self` exactly.
    pub fn exact_div(&self, d: &Poly) -> Option<Poly> {
        let (q, r) = self.div_rem(d);
        r.is_zero().then_some(q)
    }

    /// The formal derivative.
    pub fn derivative(&self) -> Poly {
        Poly::new(
            self.c
                .iter()
                .enumerate()
                .skip(1)
                .map(|(i, a)| a * BigRational::from_integer(i.into()))
                .collect(),
        )
    }

    /// `self^e`.
    pub fn pow(&self, e: usize) -> Poly {
        let mut acc = Poly::constant(BigRational::one());
        for _ in 0..e {
            acc = &acc * self;
        }
        acc
    }

    /// The value at `x` (Horner).
    pub fn eval(&self, x: &BigRational) -> BigRational {
        self.c
            .iter()
            .rev()
            .fold(BigRational::zero(), |acc, a| acc * x + a)
    }

    /// The sign (−1, 0, 1) of the value at `x`.
    pub fn sign_at(&self, x: &BigRational) -> i32 {
        sign_at_int(&self.primitive_int(), x)
    }

    /// The positive multiple of `self` with coprime integer coefficients (empty for zero).
    pub fn primitive_int(&self) -> Vec<BigInt> {
        let den = self.c.iter().fold(BigInt::one(), |acc, a| {
            crate::algebra::intgcd::lcm(&acc, a.denom())
        });
        let ints: Vec<BigInt> = self
            .c
            .iter()
            .map(|a| a.numer() * (&den / a.denom()))
            .collect();
        let g = ints.iter().fold(BigInt::zero(), |acc, a| {
            crate::algebra::intgcd::gcd(&acc, a)
        });
        if g.is_zero() {
            return Vec::new();
        }
        ints.into_iter().map(|a| a / &g).collect()
    }

    /// The positive rational multiple of `self` with coprime integer coefficients.
    pub fn primitive(&self) -> Poly {
        Poly::from_bigints(&self.primitive_int())
    }

    /// The monic gcd (zero when both are zero). Euclid over Q, each remainder made primitive to
    /// keep the coefficients small.
    pub fn gcd(&self, other: &Poly) -> Poly {
        let (mut a, mut b) = (self.primitive(), other.primitive());
        while !b.is_zero() {
            let r = a.rem(&b).primitive();
            a = b;
            b = r;
        }
        a.monic()
    }

    /// `(g, s, t)` with `g = s·self + t·other` the monic gcd.
    pub fn ext_gcd(&self, other: &Poly) -> (Poly, Poly, Poly) {
        let one = Poly::constant(BigRational::one());
        let (mut r0, mut r1) = (self.clone(), other.clone());
        let (mut s0, mut s1) = (one.clone(), Poly::zero());
        let (mut t0, mut t1) = (Poly::zero(), one);
        while !r1.is_zero() {
            let (q, r) = r0.div_rem(&r1);
            let s = &s0 - &(&q * &s1);
            let t = &t0 - &(&q * &t1);
            (r0, r1, s0, s1, t0, t1) = (r1, r, s1, s, t1, t);
        }
        if r0.is_zero() {
            return (r0, s0, t0);
        }
        let inv = r0.lc().recip();
        (r0.scale(&inv), s0.scale(&inv), t0.scale(&inv))
    }

    /// Yun's square-free decomposition: monic `(g_i, i)` with `self = lc · Π g_i^i`, the `g_i`
    /// square-free and pairwise coprime; constant parts are omitted.
    pub fn square_free(&self) -> Vec<(Poly, usize)> {
        let mut out = Vec::new();
        if self.deg() == 0 {
            return out;
        }
        let f = self.monic();
        let d = f.derivative();
        let a0 = f.gcd(&d);
        let mut b = f.exact_div(&a0).expect("gcd divides");
        let mut c = d.exact_div(&a0).expect("gcd divides");
        let mut i = 1;
        loop {
            let dd = &c - &b.derivative();
            if dd.is_zero() {
                if b.deg() > 0 {
                    out.push((b.monic(), i));
                }
                break;
            }
            let a = b.gcd(&dd);
            if a.deg() > 0 {
                out.push((a.clone(), i));
            }
            b = b.exact_div(&a).expect("gcd divides");
            c = dd.exact_div(&a).expect("gcd divides");
            i += 1;
            if b.deg() == 0 {
                break;
            }
        }
        out
    }

    /// The square-free part (monic): the product of the distinct irreducible factors.
    pub fn square_free_part(&self) -> Poly {
        if self.deg() == 0 {
            return Poly::constant(BigRational::one());
        }
        self.exact_div(&self.gcd(&self.derivative()))
            .expect("gcd divides")
            .monic()
    }

    /// Renders with variable `var`, highest degree first, e.g. `x^2 - 3/2*x + 1`.
    pub fn render(&self, var: &str) -> String {
        if self.is_zero() {
            return "0".into();
        }
        let mut s = String::new();
        for (i, a) in self.c.iter().enumerate().rev() {
            if a.is_zero() {
                continue;
            }
            let neg = a.is_negative();
            let abs = a.abs();
            if s.is_empty() {
                if neg {
                    s.push('-');
                }
            } else {
                s.push_str(if neg { " - " } else { " + " });
            }
            // Written in place: `abs`, `abs*x^i` or `x^i` (no string per monomial).
            if i == 0 || !abs.is_one() {
                crate::algebra::intgcd::push_ratio(&mut s, &abs);
                if i > 0 {
                    s.push('*');
                }
            }
            if i >= 1 {
                s.push_str(var);
            }
            if i >= 2 {
                s.push('^');
                s.push_str(&i.to_string());
            }
        }
        s
    }
}

impl fmt::Display for Poly {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.render("x"))
    }
}

impl Add for &Poly {
    type Output = Poly;
    fn add(self, o: &Poly) -> Poly {
        let n = self.c.len().max(o.c.len());
        Poly::new(
            (0..n)
                .map(|i| crate::algebra::intgcd::add(&self.coeff(i), &o.coeff(i)))
                .collect(),
        )
    }
}

impl Sub for &Poly {
    type Output = Poly;
    fn sub(self, o: &Poly) -> Poly {
        let n = self.c.len().max(o.c.len());
        Poly::new(
            (0..n)
                .map(|i| crate::algebra::intgcd::sub(&self.coeff(i), &o.coeff(i)))
                .collect(),
        )
    }
}

impl Neg for &Poly {
    type Output = Poly;
    fn neg(self) -> Poly {
        Poly::new(self.c.iter().map(|a| -a).collect())
    }
}

impl Mul for &Poly {
    type Output = Poly;
    fn mul(self, o: &Poly) -> Poly {
        if self.is_zero() || o.is_zero() {
            return Poly::zero();
        }
        let mut c = vec![BigRational::zero(); self.c.len() + o.c.len() - 1];
        for (i, a) in self.c.iter().enumerate() {
            if a.is_zero() {
                continue;
            }
            for (j, b) in o.c.iter().enumerate() {
                if !b.is_zero() {
                    let ab = crate::algebra::intgcd::mul(a, b);
                    c[i + j] = crate::algebra::intgcd::add(&c[i + j], &ab);
                }
            }
        }
        Poly::new(c)
    }
}

/// The sign (−1, 0, 1) of the integer polynomial `p` (lowest degree first) at the rational `x`, evaluated
/// homogeneously over the integers: `Σ p_i·num^i·den^(n−i)` has the sign of `p(x)` as `den > 0`.
pub fn sign_at_int(p: &[BigInt], x: &BigRational) -> i32 {
    let (num, den) = (x.numer(), x.denom());
    let mut acc = BigInt::zero();
    let mut den_pow = BigInt::one();
    for a in p.iter().rev() {
        acc = acc * num + a * &den_pow;
        den_pow *= den;
    }
    // acc = Σ p_i num^i den^(n-i) up to the positive factor den^k; sign is what matters.
    match acc.sign() {
        Sign::Minus => -1,
        Sign::NoSign => 0,
        Sign::Plus => 1,
    }
}

/// (Tests only: an independent root counter to cross-check the isolation.)
/// A Sturm chain of a square-free polynomial, kept with primitive integer coefficients (each
/// member is a positive multiple of the classical one, which keeps the sign variations).
#[derive(Clone, Debug)]
#[cfg(test)]
pub struct Sturm {
    chain: Vec<Vec<BigInt>>,
}

#[cfg(test)]
impl Sturm {
    /// Builds the chain of `p`; `p` should be square-free (else it counts distinct roots of
    /// `p / gcd(p, p')` only where that gcd has no sign change — callers pass square-free input).
    pub fn new(p: &Poly) -> Self {
        let mut polys = vec![p.primitive(), p.derivative().primitive()];
        while !polys[polys.len() - 1].is_zero() {
            let n = polys.len();
            let r = polys[n - 2].rem(&polys[n - 1]);
            polys.push((-&r).primitive());
        }
        polys.pop();
        Sturm {
            chain: polys.iter().map(Poly::primitive_int).collect(),
        }
    }

    fn variations(signs: impl Iterator<Item = i32>) -> usize {
        let mut last = 0;
        let mut v = 0;
        for s in signs.filter(|&s| s != 0) {
            if last != 0 && s != last {
                v += 1;
            }
            last = s;
        }
        v
    }

    fn var_at(&self, x: &BigRational) -> usize {
        Sturm::variations(self.chain.iter().map(|p| sign_at_int(p, x)))
    }

    fn var_at_infinity(&self, positive: bool) -> usize {
        Sturm::variations(self.chain.iter().map(|p| {
            let s = if p.last().is_some_and(Signed::is_positive) {
                1
            } else {
                -1
            };
            if positive || (p.len() - 1) % 2 == 0 {
                s
            } else {
                -s
            }
        }))
    }

    /// The number of distinct real roots in `(a, b]`, `a < b`.
    pub fn count(&self, a: &BigRational, b: &BigRational) -> usize {
        self.var_at(a).saturating_sub(self.var_at(b))
    }

    /// The number of distinct real roots greater than `a`.
    pub fn count_above(&self, a: &BigRational) -> usize {
        self.var_at(a).saturating_sub(self.var_at_infinity(true))
    }

    /// The number of distinct real roots.
    pub fn count_all(&self) -> usize {
        self.var_at_infinity(false)
            .saturating_sub(self.var_at_infinity(true))
    }
}

/// Taylor shift in place: `c(x) ↦ c(x + a)` (lowest degree first).
fn taylor_shift(c: &mut [BigInt], a: &BigInt) {
    let n = c.len();
    for i in 0..n.saturating_sub(1) {
        for j in (i..n - 1).rev() {
            let t = &c[j + 1] * a;
            c[j] += t;
        }
    }
}

fn sign_variations(c: &[BigInt]) -> usize {
    let mut last = Sign::NoSign;
    let mut v = 0;
    for s in c.iter().map(BigInt::sign).filter(|&s| s != Sign::NoSign) {
        if last != Sign::NoSign && s != last {
            v += 1;
        }
        last = s;
    }
    v
}

/// Descartes' bound for the roots of the integer polynomial `p` in the open interval `(a, b)`:
/// the sign variations of `(1 + x)^n · p((a + b·x)/(1 + x))`. It is at least the number of
/// roots and of the same parity, so 0 means none and 1 means exactly one.
pub fn descartes_bound(p: &[BigInt], a: &BigRational, b: &BigRational) -> usize {
    let d = crate::algebra::intgcd::lcm(a.denom(), b.denom());
    let (aa, bb) = (a.numer() * (&d / a.denom()), b.numer() * (&d / b.denom()));
    if let Some(v) = descartes_bound_i128(p, &aa, &bb, &d) {
        return v;
    }
    descartes_bound_big(p, &aa, &bb, &d)
}

/// [`descartes_bound`] on `(aa/d, bb/d)`, in big integers.
fn descartes_bound_big(p: &[BigInt], aa: &BigInt, bb: &BigInt, d: &BigInt) -> usize {
    let n = p.len().saturating_sub(1);
    // g(y) = d^n p(y / d), integral; then g(aa + (bb − aa) x), then reverse and shift by 1.
    let mut dpow = BigInt::one();
    let mut g: Vec<BigInt> = vec![BigInt::zero(); n + 1];
    for i in (0..=n).rev() {
        g[i] = &p[i] * &dpow;
        dpow *= d;
    }
    taylor_shift(&mut g, aa);
    let h = bb - aa;
    let mut hpow = BigInt::one();
    for x in g.iter_mut() {
        *x *= &hpow;
        hpow *= &h;
    }
    g.reverse();
    taylor_shift(&mut g, &BigInt::one());
    sign_variations(&g)
}

/// [`descartes_bound_big`] in `i128` with checked arithmetic: the same count whenever every
/// intermediate value fits, `None` as soon as one would overflow (never a wrapped value).
fn descartes_bound_i128(p: &[BigInt], aa: &BigInt, bb: &BigInt, d: &BigInt) -> Option<usize> {
    let small = |x: &BigInt| i128::try_from(x).ok();
    let (aa, bb, d) = (small(aa)?, small(bb)?, small(d)?);
    let shift = |c: &mut [i128], a: i128| -> Option<()> {
        let n = c.len();
        for i in 0..n.saturating_sub(1) {
            for j in (i..n - 1).rev() {
                c[j] = c[j].checked_add(c[j + 1].checked_mul(a)?)?;
            }
        }
        Some(())
    };
    let mut g = vec![0i128; p.len()];
    let mut dpow = 1i128;
    for (k, (gi, pi)) in g.iter_mut().zip(p).rev().enumerate() {
        if k > 0 {
            dpow = dpow.checked_mul(d)?;
        }
        *gi = small(pi)?.checked_mul(dpow)?;
    }
    shift(&mut g, aa)?;
    let h = bb.checked_sub(aa)?;
    let mut hpow = 1i128;
    for (k, x) in g.iter_mut().enumerate() {
        if k > 0 {
            hpow = hpow.checked_mul(h)?;
        }
        *x = x.checked_mul(hpow)?;
    }
    g.reverse();
    shift(&mut g, 1)?;
    let signs = g.iter().map(|x| x.signum()).filter(|&s| s != 0);
    let mut v = 0;
    let mut last = 0;
    for s in signs {
        v += usize::from(last != 0 && s != last);
        last = s;
    }
    Some(v)
}

/// An open interval `(a, b)` holding exactly one root of the square-free `p`, its largest real
/// root, with `p(a), p(b) ≠ 0`; `None` when `p` has no real root. Bisection with Descartes'
/// bound (Vincent–Collins–Akritas), upper halves first, inside the Cauchy bound.
pub fn largest_root_interval(p: &Poly) -> Option<(BigRational, BigRational)> {
    let ints = p.primitive_int();
    let lc = ints.last()?.abs();
    let max = ints.iter().map(Signed::abs).max().expect("nonempty");
    let bound = BigRational::from_integer(max.div_ceil(&lc) + 1);
    let mut stack = vec![(-bound.clone(), bound)];
    let two = BigRational::from_integer(2.into());
    while let Some((a, b)) = stack.pop() {
        match descartes_bound(&ints, &a, &b) {
            0 => continue,
            1 => return Some((a, b)),
            _ => {}
        }
        // Split off the roots so that no end point is ever a root.
        let mut mid = (&a + &b) / &two;
        let mut k = 3;
        while p.sign_at(&mid) == 0 {
            mid = &a + (&b - &a) * BigRational::new(1.into(), k.into());
            k += 1;
        }
        stack.push((a, mid.clone()));
        stack.push((mid, b));
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn q(a: i64, b: i64) -> BigRational {
        BigRational::new(a.into(), b.into())
    }

    fn arb_poly(max_deg: usize) -> impl Strategy<Value = Poly> {
        prop::collection::vec(-9i64..=9, 1..=max_deg + 1).prop_map(|c| Poly::from_ints(&c))
    }

    #[test]
    fn render_and_basic_ops() {
        let p = Poly::from_ints(&[1, -3, 0, 2]);
        assert_eq!(p.to_string(), "2*x^3 - 3*x + 1");
        assert_eq!(p.derivative().to_string(), "6*x^2 - 3");
        assert_eq!(
            Poly::new(vec![q(-1, 2), q(1, 1)]).render("rho"),
            "rho - 1/2"
        );
        assert_eq!(p.eval(&q(1, 2)), q(1, 4) - q(3, 2) + q(1, 1));
    }

    #[test]
    fn square_free_of_known_product() {
        // (x-1)^3 (x+2) (x^2+1)^2
        let a = Poly::from_ints(&[-1, 1]);
        let b = Poly::from_ints(&[2, 1]);
        let c = Poly::from_ints(&[1, 0, 1]);
        let p = &(&a.pow(3) * &b) * &c.pow(2);
        let sf = p.square_free();
        assert_eq!(sf, vec![(b.clone(), 1), (c.clone(), 2), (a.clone(), 3)]);
        assert_eq!(p.square_free_part(), &(&a * &b) * &c);
    }

    #[test]
    fn sturm_counts_known_roots() {
        // (x-1)(x-2)(x+3)(x^2+1): real roots -3, 1, 2.
        let p = &(&Poly::from_ints(&[2, -3, 1]) * &Poly::from_ints(&[3, 1]))
            * &Poly::from_ints(&[1, 0, 1]);
        let s = Sturm::new(&p);
        assert_eq!(s.count_all(), 3);
        assert_eq!(s.count(&q(0, 1), &q(2, 1)), 2); // (0, 2] holds 1 and 2
        assert_eq!(s.count(&q(1, 1), &q(3, 2)), 0); // 1 itself is excluded
        assert_eq!(s.count(&q(-4, 1), &q(0, 1)), 1);
        assert_eq!(s.count_above(&q(3, 2)), 1);
        let (lo, hi) = largest_root_interval(&p).unwrap();
        assert!(lo < q(2, 1) && q(2, 1) < hi);
        // Descartes on (0, 3): two roots (1, 2); on (3/2, 5/2): one.
        let ints = p.primitive_int();
        assert_eq!(descartes_bound(&ints, &q(3, 2), &q(5, 2)), 1);
        assert_eq!(descartes_bound(&ints, &q(5, 2), &q(9, 1)), 0);
        assert_eq!(largest_root_interval(&Poly::from_ints(&[1, 0, 1])), None);
    }

    #[test]
    fn descartes_fast_path_fits_small_and_refuses_huge() {
        let ints: Vec<BigInt> = [-2i64, 0, 1].iter().map(|&c| c.into()).collect();
        let (a, b, d) = (BigInt::from(1), BigInt::from(3), BigInt::from(2));
        assert_eq!(descartes_bound_i128(&ints, &a, &b, &d), Some(1));
        let huge = BigInt::from(1) << 100u32;
        assert_eq!(descartes_bound_i128(&ints, &a, &b, &huge), None);
        assert_eq!(descartes_bound_big(&ints, &a, &b, &huge), 0);
    }

    proptest! {
        /// The i128 fast path of Descartes' bound gives the big-integer count whenever it
        /// answers; the coefficient and end-point sizes reach both sides of the overflow line.
        #[test]
        fn descartes_fast_path_agrees(
            c in prop::collection::vec(-(1i64 << 40)..(1i64 << 40), 2..=10),
            shift in 0u32..40,
            a in -(1i64 << 40)..(1i64 << 40),
            w in 1i64..(1i64 << 30),
            k in 0u32..30,
        ) {
            let ints: Vec<BigInt> = c.iter().map(|&x| BigInt::from(x) >> shift).collect();
            prop_assume!(!ints.last().expect("nonempty").is_zero());
            let d = BigInt::from(1) << k;
            let aa = BigInt::from(a) >> shift;
            let bb = &aa + w;
            if let Some(v) = descartes_bound_i128(&ints, &aa, &bb, &d) {
                prop_assert_eq!(v, descartes_bound_big(&ints, &aa, &bb, &d));
            }
        }

        #[test]
        fn division_identity(a in arb_poly(6), b in arb_poly(4)) {
            prop_assume!(!b.is_zero());
            let (qq, r) = a.div_rem(&b);
            prop_assert_eq!(&(&qq * &b) + &r, a);
            prop_assert!(r.is_zero() || r.deg() < b.deg());
        }

        #[test]
        fn gcd_divides_and_is_maximal(a in arb_poly(3), b in arb_poly(3), c in arb_poly(3)) {
            prop_assume!(!c.is_zero() && !a.is_zero() && !b.is_zero());
            let (ac, bc) = (&a * &c, &b * &c);
            let g = ac.gcd(&bc);
            prop_assert!(ac.exact_div(&g).is_some());
            prop_assert!(bc.exact_div(&g).is_some());
            prop_assert!(g.exact_div(&c.monic()).is_some());
            let (g2, s, t) = ac.ext_gcd(&bc);
            prop_assert_eq!(&g2, &g);
            prop_assert_eq!(&(&s * &ac) + &(&t * &bc), g);
        }

        #[test]
        fn square_free_reassembles(a in arb_poly(3), b in arb_poly(2)) {
            prop_assume!(a.deg() > 0 && b.deg() > 0);
            let p = &(&a * &a) * &b;
            let mut back = Poly::constant(p.lc());
            for (g, i) in p.square_free() {
                prop_assert_eq!(g.gcd(&g.derivative()).deg(), 0);
                back = &back * &g.pow(i);
            }
            prop_assert_eq!(back, p);
        }

        #[test]
        fn sturm_counts_integer_roots(roots in prop::collection::btree_set(-20i64..20, 1..6)) {
            let p = roots.iter().fold(Poly::from_ints(&[1]), |acc, &r| &acc * &Poly::from_ints(&[-r, 1]));
            let p = &p * &Poly::from_ints(&[5, 0, 1]);
            let s = Sturm::new(&p);
            prop_assert_eq!(s.count_all(), roots.len());
            let inside = roots.iter().filter(|&&r| (-5..=7).contains(&r)).count();
            prop_assert_eq!(s.count(&q(-11, 2), &q(7, 1)), inside);
            let (lo, hi) = largest_root_interval(&p).unwrap();
            let max = q(*roots.iter().max().unwrap(), 1);
            prop_assert!(lo < max && max < hi);
            prop_assert_eq!(s.count(&lo, &hi), 1);
        }
    }
}
