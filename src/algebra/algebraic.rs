//! Exact real algebraic numbers and arithmetic in a real number field Q(α).
//!
//! A [`RealAlgebraic`] is a rational, or the unique root of a monic irreducible polynomial over Q
//! in an open interval with rational end points (the polynomial changes sign across it).
//! Comparisons are exact: distinct minimal polynomials mean distinct numbers, so intervals are
//! refined until they separate; with the same minimal polynomial, the hull of the two intervals
//! holding a single root (Sturm) means equality. [`NumberField`] does arithmetic in Q(α) on the
//! power basis `1, α, …, α^(d−1)`, inverses by the extended Euclid algorithm modulo the minimal
//! polynomial. Decimals are certified: interval enclosures are refined until every printed digit
//! is decided. Written by hand (the crates that do this are LGPL: `algebraics`).

use crate::algebra::poly::{descartes_bound, largest_root_interval, sign_at_int, Poly};
use crate::algebra::square_part::square_split;
use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
use std::cmp::Ordering;
use std::fmt;
mod mirror;

/// The number of digits after the point printed by default.
pub const DEFAULT_DIGITS: usize = 30;

/// A real algebraic number, exact.
#[derive(Clone, Debug)]
pub struct RealAlgebraic {
    /// Monic irreducible over Q.
    min_poly: Poly,
    /// For degree 1, `lo = hi` = the number; otherwise the number is the only root of `min_poly`
    /// in the open interval `(lo, hi)`.
    lo: BigRational,
    hi: BigRational,
}

fn two() -> BigRational {
    BigRational::from_integer(2.into())
}

impl RealAlgebraic {
    /// The rational `q`.
    pub fn rational(q: BigRational) -> Self {
        RealAlgebraic {
            min_poly: Poly::new(vec![-q.clone(), BigRational::one()]),
            lo: q.clone(),
            hi: q,
        }
    }

    /// The largest real root of the irreducible polynomial `f` (`None` without real root).
    /// The caller guarantees irreducibility (from [`crate::algebra::factor::factor`]).
    pub fn largest_root(f: &Poly) -> Option<Self> {
        let f = f.monic();
        if f.deg() == 1 {
            return Some(RealAlgebraic::rational(-f.coeff(0)));
        }
        let (lo, hi) = largest_root_interval(&f)?;
        Some(RealAlgebraic {
            min_poly: f,
            lo,
            hi,
        })
    }

    /// Every real root of the irreducible polynomial `f`, increasing (empty when it has none).
    /// Bisection with Descartes' bound inside the Cauchy bound, as for [`Self::largest_root`];
    /// the caller guarantees irreducibility (from [`crate::algebra::factor::factor`]).
    pub fn real_roots(f: &Poly) -> Vec<Self> {
        let f = f.monic();
        if f.deg() == 1 {
            return vec![RealAlgebraic::rational(-f.coeff(0))];
        }
        let ints = f.primitive_int();
        let lc = ints.last().map(Signed::abs).unwrap_or_else(BigInt::one);
        let max = ints
            .iter()
            .map(Signed::abs)
            .max()
            .unwrap_or_else(BigInt::one);
        let bound = BigRational::from_integer(max.div_ceil(&lc) + 1);
        let mut out = Vec::new();
        let mut stack = vec![(-bound.clone(), bound)];
        while let Some((lo, hi)) = stack.pop() {
            match descartes_bound(&ints, &lo, &hi) {
                0 => {}
                1 => out.push(RealAlgebraic {
                    min_poly: f.clone(),
                    lo,
                    hi,
                }),
                _ => {
                    // Irreducible of degree ≥ 2: no rational root, so `mid` is never a root.
                    let mid = (&lo + &hi) / two();
                    stack.push((lo, mid.clone()));
                    stack.push((mid, hi));
                }
            }
        }
        out.sort_by(|a, b| a.lo.cmp(&b.lo));
        out
    }

    /// The only root of `f` in the closed interval `[lo, hi]` (`lo < hi` rationals), with its
    /// minimal polynomial (the irreducible factor of `f` vanishing there). `None` when `f` has no
    /// root or more than one distinct root in `[lo, hi]`, or cannot be factored.
    pub fn root_in(f: &Poly, lo: &BigRational, hi: &BigRational) -> Option<Self> {
        if f.is_zero() || lo >= hi {
            return None;
        }
        let factors = crate::algebra::factor::factor(&f.square_free_part()).ok()?;
        let mut found = Vec::new();
        for (g, _) in factors {
            for mut r in RealAlgebraic::real_roots(&g) {
                if let Some(q) = r.as_rational() {
                    if q >= lo && q <= hi {
                        found.push(r.clone());
                    }
                    continue;
                }
                // No rational root: refine until the isolating interval is inside or outside.
                loop {
                    if &r.lo >= lo && &r.hi <= hi {
                        found.push(r.clone());
                        break;
                    }
                    if &r.hi <= lo || &r.lo >= hi {
                        break;
                    }
                    r.refine();
                }
            }
        }
        (found.len() == 1).then(|| found.pop().expect("one root"))
    }

    /// The monic minimal polynomial over Q.
    pub fn min_poly(&self) -> &Poly {
        &self.min_poly
    }

    /// The degree over Q.
    pub fn degree(&self) -> usize {
        self.min_poly.deg()
    }

    /// The current isolating interval (a point for rationals).
    pub fn interval(&self) -> (&BigRational, &BigRational) {
        (&self.lo, &self.hi)
    }

    /// The value when it is rational.
    pub fn as_rational(&self) -> Option<&BigRational> {
        (self.degree() == 1).then_some(&self.lo)
    }

    /// Halves the isolating interval (no-op for rationals).
    pub fn refine(&mut self) {
        if self.degree() == 1 {
            return;
        }
        let ints = self.min_poly.primitive_int();
        let s_lo = sign_at_int(&ints, &self.lo);
        self.bisect(&ints, s_lo);
    }

    /// One bisection step; `s_lo` is the sign of the minimal polynomial at `lo`.
    fn bisect(&mut self, ints: &[BigInt], s_lo: i32) {
        // (lo + hi)/2 with one gcd (num-rational's sum and quotient reduce twice).
        let (lo, hi) = (&self.lo, &self.hi);
        let mid = crate::algebra::intgcd::ratio(
            lo.numer() * hi.denom() + hi.numer() * lo.denom(),
            (lo.denom() * hi.denom()) << 1u32,
        );
        // No rational root: the sign at `mid` is never zero.
        if sign_at_int(ints, &mid) == s_lo {
            self.lo = mid;
        } else {
            self.hi = mid;
        }
    }

    /// Refines until the interval is no wider than `width`. Newton's iteration in fixed point
    /// with doubling precision reaches the width in O(log) steps of growing size; the result is
    /// certified, not trusted: the minimal polynomial must change sign across the new interval,
    /// which must lie inside the old one (whose only root is this number). When that fails (the
    /// start point is not yet in Newton's basin) a few bisection steps shrink the interval and
    /// Newton is tried again, so the refinement always ends. Bisection alone costs a full
    /// polynomial evaluation on ever longer rationals per bit: cubic in the number of digits.
    pub fn refine_to(&mut self, width: &BigRational) {
        if self.degree() == 1 || !wider(&self.lo, &self.hi, width) {
            return;
        }
        let ints = self.min_poly.primitive_int();
        let s_lo = sign_at_int(&ints, &self.lo);
        // 2^-k ≤ width/2, so an interval x ± 2^-k is no wider than `width`.
        let k = (width.denom().bits() + 2)
            .saturating_sub(width.numer().bits())
            .max(1);
        loop {
            if !wider(&self.lo, &self.hi, width) {
                return;
            }
            let current = &self.hi - &self.lo;
            let have = current
                .denom()
                .bits()
                .saturating_sub(current.numer().bits());
            // Close to the goal, bisection is as cheap as Newton.
            if k.saturating_sub(have) > 16 {
                if let Some((lo, hi)) = newton_interval(&ints, &self.lo, &self.hi, have, k) {
                    self.lo = lo;
                    self.hi = hi;
                    return;
                }
            }
            for _ in 0..16 {
                if !wider(&self.lo, &self.hi, width) {
                    return;
                }
                self.bisect(&ints, s_lo);
            }
        }
    }

    /// Exact comparison.
    pub fn cmp_exact(&self, other: &Self) -> Ordering {
        let (mut a, mut b) = (self.clone(), other.clone());
        loop {
            if a.hi < b.lo || (a.hi == b.lo && (a.degree() > 1 || b.degree() > 1)) {
                return Ordering::Less;
            }
            if b.hi < a.lo || (b.hi == a.lo && (a.degree() > 1 || b.degree() > 1)) {
                return Ordering::Greater;
            }
            if a.degree() == 1 && b.degree() == 1 {
                return a.lo.cmp(&b.lo);
            }
            if a.min_poly == b.min_poly {
                let lo = a.lo.clone().min(b.lo.clone());
                let hi = a.hi.clone().max(b.hi.clone());
                if descartes_bound(&a.min_poly.primitive_int(), &lo, &hi) == 1 {
                    return Ordering::Equal;
                }
            }
            a.refine();
            b.refine();
        }
    }

    /// At least `digits` correct digits after the point, truncated (not rounded).
    pub fn decimal(&self, digits: usize) -> String {
        let mut a = self.clone();
        let mut width = BigRational::new(BigInt::one(), BigInt::from(10).pow(digits as u32 + 1));
        loop {
            if let Some(s) = decide_digits(&a.lo, &a.hi, digits, a.degree() == 1) {
                return s;
            }
            a.refine_to(&width);
            width = &width / BigRational::from_integer(256.into());
        }
    }

    /// `(a + b*sqrt(d))/c` for a quadratic number, `None` otherwise.
    pub fn closed_form(&self) -> Option<String> {
        if self.degree() != 2 {
            return None;
        }
        let field = NumberField::new(self.clone());
        Some(field.render(&field.generator_element()))
    }
}

impl fmt::Display for RealAlgebraic {
    /// `1/3` for a rational, `(1 + sqrt(5))/2` for a quadratic, `root of x^3 - x - 1 in [1, 2]`
    /// otherwise (the unique root of the minimal polynomial in that interval).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(q) = self.as_rational() {
            return write!(f, "{q}");
        }
        if let Some(s) = self.closed_form() {
            return f.write_str(&s);
        }
        write!(f, "root of {} in [{}, {}]", self.min_poly, self.lo, self.hi)
    }
}

/// Exact comparison of two rationals by cross-multiplication (denominators are positive).
/// `num_rational`'s own `Ord` expands continued fractions recursively, which on numbers of
/// thousands of digits is far slower than two products.
fn cmp_rat(x: &BigRational, y: &BigRational) -> Ordering {
    (x.numer() * y.denom()).cmp(&(y.numer() * x.denom()))
}

/// True when the interval `[lo, hi]` is wider than `width`.
fn wider(lo: &BigRational, hi: &BigRational, width: &BigRational) -> bool {
    // hi − lo > width ⟺ (hi·dl − lo·dh)·dw > nw·dl·dh, all denominators positive.
    let (dl, dh, dw) = (lo.denom(), hi.denom(), width.denom());
    let diff = hi.numer() * dl - lo.numer() * dh;
    diff * dw > width.numer() * dl * dh
}

/// `2^(p·deg)·f(m/2^p)` and `2^(p·(deg−1))·f'(m/2^p)` for integer coefficients `f` (low degree
/// first): the polynomial and its derivative at a fixed-point number, in integers.
fn eval_fixed(f: &[BigInt], m: &BigInt, p: u64) -> (BigInt, BigInt) {
    let d = f.len() - 1;
    let (mut v, mut dv) = (BigInt::zero(), BigInt::zero());
    for (i, a) in f.iter().enumerate().rev() {
        // v = Σ a_i m^i 2^(p(d−i)); dv = Σ i a_i m^(i−1) 2^(p(d−i)).
        let scaled = a << (p * (d - i) as u64);
        if i >= 1 {
            dv = dv * m + &scaled * BigInt::from(i);
        }
        v = v * m + scaled;
    }
    // dv was accumulated with one factor m fewer per term but the same powers of two: its
    // terms carry 2^(p(d−i)) = 2^(p(d−1−(i−1))), which is the derivative's scaling.
    (v, dv)
}

/// Newton's iteration for the root of `f` in `(lo, hi)` (width about `2^-have`), to an interval
/// `x ± 2^-k` certified by a sign change of `f` inside `(lo, hi)`; `None` when it does not certify.
fn newton_interval(
    f: &[BigInt],
    lo: &BigRational,
    hi: &BigRational,
    have: u64,
    k: u64,
) -> Option<(BigRational, BigRational)> {
    let target = k + 8;
    let mut p = (have + 8).clamp(32, target);
    let mid = (lo + hi) / two();
    let mut m = floor_scaled(&mid, p);
    let mut last = false;
    loop {
        let (v, dv) = eval_fixed(f, &m, p);
        if dv.is_zero() {
            return None;
        }
        // x − f(x)/f'(x), in units of 2^-p: m − v/dv (rounded).
        let (q, r) = v.div_mod_floor(&dv);
        let round_up = (&r << 1u32).abs() >= dv.abs();
        m -= if round_up { q + 1 } else { q };
        if last {
            break;
        }
        if p == target {
            last = true;
        } else {
            let next = (2 * p).min(target);
            m <<= next - p;
            p = next;
        }
    }
    // The candidate interval m/2^p ± 2^-k, checked exactly.
    let delta = BigInt::one() << (p - k);
    let (a, b) = (&m - &delta, &m + &delta);
    let sa = eval_fixed(f, &a, p).0.sign();
    let sb = eval_fixed(f, &b, p).0.sign();
    let scale = BigInt::one() << p;
    let (a, b) = (
        crate::algebra::intgcd::ratio(a, scale.clone()),
        crate::algebra::intgcd::ratio(b, scale),
    );
    let inside = cmp_rat(&a, lo) != Ordering::Less && cmp_rat(&b, hi) != Ordering::Greater;
    let opposite = sa != sb && sa != num_bigint::Sign::NoSign && sb != num_bigint::Sign::NoSign;
    (inside && opposite).then_some((a, b))
}

/// Truncated decimal of a number known to lie in `[lo, hi]`, when the interval decides every
/// digit (`exact`: `lo = hi` is the number itself).
pub(crate) fn decide_digits(
    lo: &BigRational,
    hi: &BigRational,
    digits: usize,
    exact: bool,
) -> Option<String> {
    let neg = if exact {
        lo.is_negative()
    } else if lo.is_positive() {
        false
    } else if hi.is_negative() {
        true
    } else {
        return None;
    };
    let ten = BigInt::from(10).pow(digits as u32);
    let (a, b) = if neg {
        (-hi, -lo)
    } else {
        (lo.clone(), hi.clone())
    };
    // floor(x·10^digits) in integers: a rational product would reduce by a gcd of numbers of
    // thousands of digits.
    let floor_scaled10 = |x: &BigRational| (x.numer() * &ten).div_floor(x.denom());
    let fa = floor_scaled10(&a);
    let fb = floor_scaled10(&b);
    if fa != fb {
        return None;
    }
    let (int, frac) = fa.div_rem(&ten);
    let sign = if neg { "-" } else { "" };
    if digits == 0 {
        // No digit after the point: the fraction is 0 and there is nothing to pad.
        return Some(format!("{sign}{int}"));
    }
    let frac = frac.to_string();
    let pad = "0".repeat(digits.saturating_sub(frac.len()));
    Some(format!("{sign}{int}.{pad}{frac}"))
}

fn floor_scaled(x: &BigRational, prec: u64) -> BigInt {
    (x.numer() << prec).div_floor(x.denom())
}

fn ceil_scaled(x: &BigRational, prec: u64) -> BigInt {
    -((-x.numer() << prec).div_floor(x.denom()))
}

/// Interval Horner evaluation of the polynomial `c` on `[glo, ghi]` in fixed point: integers
/// `(lo, hi)` with the value in `[lo, hi]·2^(−prec)`, every rounding outwards. Fixed point keeps
/// the numbers at `prec` bits where exact rationals would grow at every step.
fn enclose_fixed(
    c: &[BigRational],
    glo: &BigRational,
    ghi: &BigRational,
    prec: u64,
) -> (BigInt, BigInt) {
    let (xl, xh) = (floor_scaled(glo, prec), ceil_scaled(ghi, prec));
    let unit = BigInt::one() << prec;
    let (mut lo, mut hi) = (BigInt::zero(), BigInt::zero());
    for a in c.iter().rev() {
        let p = [&lo * &xl, &lo * &xh, &hi * &xl, &hi * &xh];
        let min = p.iter().min().expect("four");
        let max = p.iter().max().expect("four");
        lo = min.div_floor(&unit) + floor_scaled(a, prec);
        hi = -((-max).div_floor(&unit)) + ceil_scaled(a, prec);
    }
    (lo, hi)
}

/// `(ints, den)` with `c_i = ints_i / den`, den the lcm of the denominators.
fn integral(c: &[BigRational]) -> (Vec<BigInt>, BigInt) {
    let den = c.iter().fold(BigInt::one(), |acc, x| {
        if x.denom().is_one() {
            acc
        } else {
            crate::algebra::intgcd::lcm(&acc, x.denom())
        }
    });
    let ints = c
        .iter()
        .map(|x| {
            if x.denom() == &den {
                x.numer().clone()
            } else {
                x.numer() * (&den / x.denom())
            }
        })
        .collect();
    (ints, den)
}

/// An element of a [`NumberField`]: a polynomial in the generator of degree below the field's.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct FieldElement(Poly);

impl FieldElement {
    /// Coordinates on the power basis `1, α, …` (trailing zeros omitted).
    pub fn coords(&self) -> &[BigRational] {
        self.0.coeffs()
    }

    /// The polynomial in the generator representing this element.
    pub fn poly(&self) -> &Poly {
        &self.0
    }

    /// The value when it is rational (a constant on the power basis).
    pub fn as_rational(&self) -> Option<BigRational> {
        (self.0.deg() == 0).then(|| self.0.coeff(0))
    }

    /// Whether this is zero.
    pub fn is_zero(&self) -> bool {
        self.0.is_zero()
    }
}

/// The real number field Q(α) for a real algebraic α.
#[derive(Clone, Debug)]
pub struct NumberField {
    gen: RealAlgebraic,
    /// The minimal polynomial as primitive integers (lowest degree first), for reductions.
    f_int: Vec<BigInt>,
}

impl NumberField {
    /// The field generated by `gen`.
    pub fn new(gen: RealAlgebraic) -> Self {
        let f_int = gen.min_poly().primitive_int();
        NumberField { gen, f_int }
    }

    /// The generator α.
    pub fn generator(&self) -> &RealAlgebraic {
        &self.gen
    }

    /// The degree over Q.
    pub fn degree(&self) -> usize {
        self.gen.degree()
    }

    /// The element `p(α)`.
    pub fn element(&self, p: &Poly) -> FieldElement {
        if p.deg() < self.degree() {
            return FieldElement(p.clone());
        }
        let (ints, den) = integral(p.coeffs());
        FieldElement(self.reduce(ints, den))
    }

    /// `(Σ ints_i x^i / den) mod f` over Q, by a pseudo-remainder over Z: integer arithmetic
    /// throughout, one gcd per coefficient of the result at the end (instead of one per
    /// rational operation).
    fn reduce(&self, r: Vec<BigInt>, den: BigInt) -> Poly {
        let (r, den) = self.reduce_ints(r, den);
        Poly::new(
            r.into_iter()
                .map(|x| crate::algebra::intgcd::ratio(x, den.clone()))
                .collect(),
        )
    }

    /// `(Σ ints_i x^i / den) mod f` as `(integers, denominator)`, unreduced: the pseudo-remainder
    /// of [`NumberField::reduce`] without its final gcds (the denominator is `den` times a power
    /// of the leading coefficient of the primitive minimal polynomial, so it stays positive when
    /// `den` is).
    pub(crate) fn reduce_ints(&self, mut r: Vec<BigInt>, mut den: BigInt) -> (Vec<BigInt>, BigInt) {
        let f = &self.f_int;
        let d = f.len() - 1;
        let lc = &f[d];
        while r.len() > d {
            let top = r.pop().expect("non-empty");
            if top.is_zero() {
                continue;
            }
            let s = r.len() - d;
            if !lc.is_one() {
                for x in r.iter_mut() {
                    *x *= lc;
                }
                den *= lc;
            }
            for (i, fi) in f.iter().enumerate().take(d) {
                if !fi.is_zero() {
                    r[s + i] -= &top * fi;
                }
            }
        }
        (r, den)
    }

    /// The element α.
    pub fn generator_element(&self) -> FieldElement {
        self.element(&Poly::x())
    }

    /// The rational `q` as an element.
    pub fn rational(&self, q: BigRational) -> FieldElement {
        FieldElement(Poly::constant(q))
    }

    /// `a + b`.
    pub fn add(&self, a: &FieldElement, b: &FieldElement) -> FieldElement {
        FieldElement(&a.0 + &b.0)
    }

    /// `a − b`.
    pub fn sub(&self, a: &FieldElement, b: &FieldElement) -> FieldElement {
        FieldElement(&a.0 - &b.0)
    }

    /// `q · a` for a rational q.
    pub fn scale(&self, a: &FieldElement, q: &BigRational) -> FieldElement {
        FieldElement(a.0.scale(q))
    }

    /// `a · b`.
    pub fn mul(&self, a: &FieldElement, b: &FieldElement) -> FieldElement {
        if a.is_zero() || b.is_zero() {
            return FieldElement(Poly::zero());
        }
        if self.degree() == 1 {
            return FieldElement(Poly::constant(a.0.coeff(0) * b.0.coeff(0)));
        }
        // Integer product of the two numerators, one common denominator, reduced over Z.
        let (ai, ad) = integral(a.0.coeffs());
        let (bi, bd) = integral(b.0.coeffs());
        let mut c = vec![BigInt::zero(); ai.len() + bi.len() - 1];
        for (i, x) in ai.iter().enumerate() {
            if x.is_zero() {
                continue;
            }
            for (j, y) in bi.iter().enumerate() {
                if !y.is_zero() {
                    c[i + j] += x * y;
                }
            }
        }
        FieldElement(self.reduce(c, ad * bd))
    }

    /// `a⁻¹`, `None` for zero.
    pub fn inv(&self, a: &FieldElement) -> Option<FieldElement> {
        self.div(&self.rational(BigRational::one()), a)
    }

    /// `a / b`, `None` when `b` is zero. Computed modulo primes with rational reconstruction
    /// (the quotient is often much smaller than `a` and `b`, e.g. a ratio of two large
    /// leading coefficients), each candidate verified exactly: `q·b ≡ a (mod f)`.
    pub fn div(&self, a: &FieldElement, b: &FieldElement) -> Option<FieldElement> {
        if b.is_zero() {
            return None;
        }
        if self.degree() == 1 {
            return Some(FieldElement(Poly::constant(a.0.coeff(0) / b.0.coeff(0))));
        }
        // Common positive scale: a/b is unchanged, and both become integral.
        let s =
            a.0.coeffs()
                .iter()
                .chain(b.0.coeffs())
                .fold(BigInt::one(), |acc, c| {
                    crate::algebra::intgcd::lcm(&acc, c.denom())
                });
        let s = BigRational::from_integer(s);
        let ints = |x: &FieldElement| -> Vec<BigInt> {
            x.0.coeffs().iter().map(|c| (c * &s).to_integer()).collect()
        };
        let (ai, bi) = (ints(a), ints(b));
        let f = self.gen.min_poly().primitive_int();
        let c = crate::algebra::factor::modular_quotient(&ai, &bi, &f, |c| {
            let q = Poly::new(c.to_vec());
            self.mul(&FieldElement(q), b) == *a
        });
        Some(FieldElement(Poly::new(c)))
    }

    /// A float approximation of `a` (the middle of an enclosure 2^-64 wide; exact rationals
    /// converted directly), for drawing and for choices a later exact step checks — never for a
    /// verdict. NaN when it does not fit an `f64`.
    pub fn approx(&self, a: &FieldElement) -> f64 {
        use num_traits::ToPrimitive;
        if let Some(q) = a.as_rational() {
            return q.to_f64().unwrap_or(f64::NAN);
        }
        let width = BigRational::new(1.into(), BigInt::from(1u8) << 64u32);
        let (lo, hi) = self.enclosure(a, &width);
        ((lo + hi) / BigRational::from_integer(2.into()))
            .to_f64()
            .unwrap_or(f64::NAN)
    }

    /// An interval `[lo, hi]` holding `a`, no wider than `width`.
    pub fn enclosure(&self, a: &FieldElement, width: &BigRational) -> (BigRational, BigRational) {
        self.refine_until(a, |lo, hi| {
            (hi - lo <= *width).then(|| (lo.clone(), hi.clone()))
        })
    }

    /// Encloses `a` at growing precision until `decide` accepts the interval.
    fn refine_until<T>(
        &self,
        a: &FieldElement,
        mut decide: impl FnMut(&BigRational, &BigRational) -> Option<T>,
    ) -> T {
        if let Some(q) = a.as_rational() {
            if let Some(t) = decide(&q, &q) {
                return t;
            }
        }
        let mut g = self.gen.clone();
        let mut prec = 64u64;
        loop {
            let width = BigRational::new(BigInt::one(), BigInt::one() << prec);
            g.refine_to(&width);
            let (lo, hi) = enclose_fixed(a.0.coeffs(), &g.lo, &g.hi, prec);
            let scale = BigInt::one() << prec;
            let (lo, hi) = (
                crate::algebra::intgcd::ratio(lo, scale.clone()),
                crate::algebra::intgcd::ratio(hi, scale),
            );
            if let Some(t) = decide(&lo, &hi) {
                return t;
            }
            prec += prec / 2;
        }
    }

    /// Exact comparison of `a` with zero.
    pub fn sign(&self, a: &FieldElement) -> Ordering {
        if let Some(q) = a.as_rational() {
            return q.cmp(&BigRational::zero());
        }
        self.refine_until(a, |lo, hi| {
            if lo.is_positive() {
                Some(Ordering::Greater)
            } else if hi.is_negative() {
                Some(Ordering::Less)
            } else {
                None
            }
        })
    }

    /// At least `digits` correct digits of `a` after the point, truncated.
    pub fn decimal(&self, a: &FieldElement, digits: usize) -> String {
        if let Some(q) = a.as_rational() {
            return RealAlgebraic::rational(q).decimal(digits);
        }
        self.refine_until(a, |lo, hi| decide_digits(lo, hi, digits, false))
    }

    /// The exact string of `a`: `1/3` when rational; `(a + b*sqrt(d))/c` in a quadratic field
    /// (integers, `c > 0`, `gcd(a, b, c) = 1`; the form shortens to `a + b*sqrt(d)` for `c = 1`
    /// and drops zero terms); otherwise `<polynomial in rho> where rho = root of <min poly> in
    /// [lo, hi]`, e.g. `2*rho^2 - 1/3 where rho = root of x^3 - x - 1 in [1, 2]`.
    pub fn render(&self, a: &FieldElement) -> String {
        if let Some(q) = a.as_rational() {
            return q.to_string();
        }
        if self.degree() == 2 {
            return self.quadratic_form(a);
        }
        format!("{}{}", a.0.render("rho"), self.where_rho())
    }

    /// [`NumberField::render`] of every element, the generator's description (` where rho = …`,
    /// the same for all) written once.
    pub fn render_many(&self, v: &[FieldElement]) -> Vec<String> {
        if self.degree() <= 2 {
            return v.iter().map(|a| self.render(a)).collect();
        }
        let suffix = self.where_rho();
        v.iter()
            .map(|a| match a.as_rational() {
                Some(q) => q.to_string(),
                None => a.0.render("rho") + &suffix,
            })
            .collect()
    }

    /// ` where rho = root of f in [lo, hi]`: the generator, for degree ≥ 3.
    fn where_rho(&self) -> String {
        format!(
            " where rho = root of {} in [{}, {}]",
            self.gen.min_poly, self.gen.lo, self.gen.hi
        )
    }

    /// `u + v·α` with `α = (−p + s·√Δ)/2` for `α² + pα + q = 0`, `Δ = p² − 4q`.
    fn quadratic_form(&self, a: &FieldElement) -> String {
        let f = self.gen.min_poly();
        let (p, q) = (f.coeff(1), f.coeff(0));
        let (u, v) = (a.0.coeff(0), a.0.coeff(1));
        // s: which root — α above or below the midpoint −p/2 of the two roots.
        let mid = RealAlgebraic::rational(-&p / two());
        let s = if self.gen.cmp_exact(&mid) == Ordering::Greater {
            BigRational::one()
        } else {
            -BigRational::one()
        };
        let delta = &p * &p - q * BigRational::from_integer(4.into());
        // √Δ = √(num·den)/den = k·√d/den with num·den = k²·d.
        let (k, d) = square_split(&(delta.numer() * delta.denom()));
        let a_part = u - &v * &p / two();
        let b_part = v * s * BigRational::from_integer(k)
            / (BigRational::from_integer(delta.denom().clone()) * two());
        let c = crate::algebra::intgcd::lcm(a_part.denom(), b_part.denom());
        let ai = (&a_part * BigRational::from_integer(c.clone())).to_integer();
        let bi = (&b_part * BigRational::from_integer(c.clone())).to_integer();
        let g = crate::algebra::intgcd::gcd(&crate::algebra::intgcd::gcd(&ai, &bi), &c);
        let (ai, bi, c) = (ai / &g, bi / &g, c / &g);
        let root = if bi.abs().is_one() {
            format!("sqrt({d})")
        } else {
            format!("{}*sqrt({d})", bi.abs())
        };
        let inner = match (ai.is_zero(), bi.is_negative()) {
            (true, false) => root,
            (true, true) => format!("-{root}"),
            (false, false) => format!("{ai} + {root}"),
            (false, true) => format!("{ai} - {root}"),
        };
        if c.is_one() {
            inner
        } else if ai.is_zero() {
            format!("{inner}/{c}")
        } else {
            format!("({inner})/{c}")
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn q(a: i64, b: i64) -> BigRational {
        BigRational::new(a.into(), b.into())
    }

    fn sqrt2() -> RealAlgebraic {
        RealAlgebraic::largest_root(&Poly::from_ints(&[-2, 0, 1])).unwrap()
    }

    #[test]
    fn sqrt2_to_fifty_digits() {
        // √2 = 1.41421356237309504880168872420969807856967187537694… (known expansion)
        assert_eq!(
            sqrt2().decimal(50),
            "1.41421356237309504880168872420969807856967187537694"
        );
        assert_eq!(sqrt2().to_string(), "sqrt(2)");
    }

    #[test]
    fn zero_digits_and_long_expansions() {
        // Issue #20 item 1: no digit after the point is the integer part, not an underflow.
        assert_eq!(sqrt2().decimal(0), "1");
        assert_eq!(RealAlgebraic::rational(q(-7, 2)).decimal(0), "-3");
        // 2,000 digits of √2 against an independent integer square root, floor(√(2·10^4000)):
        // the Newton refinement must agree with it digit for digit.
        let ten = num_bigint::BigUint::from(10u32).pow(2000);
        let isqrt = (num_bigint::BigUint::from(2u32) * &ten * &ten).sqrt();
        let digits = isqrt.to_string();
        let want = format!("{}.{}", &digits[..1], &digits[1..]);
        assert_eq!(sqrt2().decimal(2000), want);
        // A refined interval is certified: the root stays inside, the width is met.
        let mut r = sqrt2();
        let width = q(1, 1) / BigRational::from_integer(BigInt::from(10).pow(500));
        r.refine_to(&width);
        let (lo, hi) = r.interval();
        assert!(hi - lo <= width);
        assert!(lo * lo < q(2, 1) && hi * hi > q(2, 1));
    }

    #[test]
    fn golden_ratio_forms() {
        let phi = RealAlgebraic::largest_root(&Poly::from_ints(&[-1, -1, 1])).unwrap();
        assert_eq!(phi.to_string(), "(1 + sqrt(5))/2");
        assert_eq!(phi.decimal(20), "1.61803398874989484820");
        let k = NumberField::new(phi);
        // 1/φ = φ − 1
        let inv = k.inv(&k.generator_element()).unwrap();
        assert_eq!(inv, k.element(&Poly::from_ints(&[-1, 1])));
        assert_eq!(k.render(&inv), "(-1 + sqrt(5))/2");
        // (5 − √5)/10 = 1/2 − (2φ − 1)/10 = 3/5 − φ/5
        let e = k.element(&Poly::new(vec![q(3, 5), q(-1, 5)]));
        assert_eq!(k.render(&e), "(5 - sqrt(5))/10");
    }

    #[test]
    fn cubic_render_and_compare() {
        let a = RealAlgebraic::largest_root(&Poly::from_ints(&[-1, -1, 0, 1])).unwrap();
        assert!(a.to_string().starts_with("root of x^3 - x - 1 in ["));
        // plastic number 1.3247179572447460259…
        assert_eq!(a.decimal(19), "1.3247179572447460259");
        assert_eq!(
            a.cmp_exact(&RealAlgebraic::rational(q(4, 3))),
            Ordering::Less
        );
        assert_eq!(a.cmp_exact(&sqrt2()), Ordering::Less);
        let mut b = a.clone();
        b.refine_to(&q(1, 1000));
        assert_eq!(a.cmp_exact(&b), Ordering::Equal);
        let k = NumberField::new(a);
        let e = k.element(&Poly::new(vec![q(-1, 3), q(0, 1), q(2, 1)]));
        assert!(k
            .render(&e)
            .starts_with("2*rho^2 - 1/3 where rho = root of x^3 - x - 1 in ["));
        assert_eq!(k.sign(&e), Ordering::Greater);
    }

    #[test]
    fn rational_decimals() {
        assert_eq!(RealAlgebraic::rational(q(1, 3)).decimal(5), "0.33333");
        assert_eq!(RealAlgebraic::rational(q(-1, 8)).decimal(5), "-0.12500");
        assert_eq!(RealAlgebraic::rational(q(7, 1)).decimal(2), "7.00");
    }

    proptest! {
        #[test]
        fn field_inverse(c in prop::collection::vec(-20i64..20, 1..3), poly in 0usize..3) {
            let f = [Poly::from_ints(&[-1, -1, 1]), Poly::from_ints(&[-2, 0, 0, 1]), Poly::from_ints(&[-1, -1, 0, 1])];
            let k = NumberField::new(RealAlgebraic::largest_root(&f[poly]).unwrap());
            let a = k.element(&Poly::from_ints(&c));
            prop_assume!(!a.is_zero());
            let inv = k.inv(&a).unwrap();
            prop_assert_eq!(k.mul(&a, &inv), k.rational(BigRational::one()));
        }

        #[test]
        fn quadratic_closed_form_matches_decimal(p in -9i64..9, qq in -9i64..9) {
            let f = Poly::from_ints(&[qq, p, 1]);
            prop_assume!(crate::algebra::factor::factor(&f).unwrap().len() == 1 && p * p - 4 * qq > 0);
            let a = RealAlgebraic::largest_root(&f).unwrap();
            // the larger root is (−p + √Δ)/2: a^2 + p a + q = 0 checked through the field
            let k = NumberField::new(a.clone());
            let g = k.generator_element();
            let val = k.add(&k.add(&k.mul(&g, &g), &k.mul(&k.rational(q(p, 1)), &g)), &k.rational(q(qq, 1)));
            prop_assert!(val.is_zero());
            prop_assert!(a.to_string().contains("sqrt("));
        }
    }
}
