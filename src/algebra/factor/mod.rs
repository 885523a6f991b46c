//! Work modulo word-size primes: characteristic polynomials of integer matrices (Hessenberg
//! reduction modulo primes + Chinese remaindering under a Hadamard bound) and factorisation of
//! integer polynomials over Q (Cantor–Zassenhaus modulo a prime, linear Hensel lifting past the
//! Mignotte bound, Zassenhaus recombination by trial division).
//!
//! Written by hand: polyfactor 0.1.6 (MIT) silently returns a polynomial as irreducible when it
//! has more than 20 factors modulo its prime, which would make a reported minimal polynomial
//! wrong; the other factorisers are LGPL. Here a factorisation either completes or reports that
//! the recombination budget ran out ([`FactorError`]), never a wrong answer.
//!
//! Primes are below 2^31, so a product of two residues fits in a `u64`.

use crate::algebra::poly::Poly;
use num_bigint::{BigInt, BigUint};
use num_integer::Integer;
use num_traits::{One, Signed, Zero};

mod hensel;
mod irreducible;
mod scaled;
mod split;
mod subsets;
use hensel::hensel;
pub(crate) use irreducible::irreducibility_prime;
use split::edf;
use subsets::subsets_in_order;

/// Factorisation gave up: too many factors modulo every prime tried.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("factorisation of a degree-{degree} polynomial needs more than {budget} recombination trials ({modular} factors modulo {prime})")]
pub struct FactorError {
    /// Degree of the square-free polynomial being factored.
    pub degree: usize,
    /// Number of its factors modulo the best prime.
    pub modular: usize,
    /// That prime.
    pub prime: u64,
    /// The number of subset trials allowed.
    pub budget: u64,
}

/// Subset trials allowed in the recombination.
const BUDGET: u64 = 1 << 22;

/// Deterministic Miller–Rabin for `n < 3 215 031 751` (bases 2, 3, 5, 7).
fn is_prime(n: u64) -> bool {
    if n < 2 {
        return false;
    }
    for p in [2, 3, 5, 7] {
        if n % p == 0 {
            return n == p;
        }
    }
    let (mut d, mut s) = (n - 1, 0);
    while d % 2 == 0 {
        d /= 2;
        s += 1;
    }
    'base: for a in [2u64, 3, 5, 7] {
        let mut x = pow_mod(a, d, n);
        if x == 1 || x == n - 1 {
            continue;
        }
        for _ in 1..s {
            x = x * x % n;
            if x == n - 1 {
                continue 'base;
            }
        }
        return false;
    }
    true
}

fn pow_mod(mut a: u64, mut e: u64, p: u64) -> u64 {
    let mut r = 1 % p;
    a %= p;
    while e > 0 {
        if e & 1 == 1 {
            r = r * a % p;
        }
        a = a * a % p;
        e >>= 1;
    }
    r
}

fn inv_mod(a: u64, p: u64) -> u64 {
    pow_mod(a, p - 2, p)
}

/// Primes below 2^31, descending.
pub(crate) fn primes() -> impl Iterator<Item = u64> {
    (1u64 << 20..1u64 << 31)
        .rev()
        .filter(|&n| n % 2 == 1 && is_prime(n))
}

/// `a mod p` in `[0, p)` for a prime `p < 2^31` (as [`Integer::mod_floor`]): Horner on the 32-bit
/// digits of |a|, most significant first, in u64 — no big division and no allocation.
fn residue(a: &BigInt, p: u64) -> u64 {
    debug_assert!(p < 1 << 31);
    let r = a
        .magnitude()
        .iter_u32_digits()
        .rev()
        .fold(0u64, |r, d| ((r << 32) | u64::from(d)) % p);
    if a.sign() == num_bigint::Sign::Minus && r != 0 {
        p - r
    } else {
        r
    }
}

/// `x mod m` in `(−m/2, m/2]`.
fn symmetric(x: &BigInt, m: &BigInt) -> BigInt {
    let r = x.mod_floor(m);
    if &r * 2 > *m {
        r - m
    } else {
        r
    }
}

/// Incremental Chinese remaindering: `(x mod m, r mod p)` ↦ `x mod m·p`.
fn crt_step(x: &BigInt, m: &BigInt, r: u64, p: u64) -> BigInt {
    let xm = residue(x, p);
    let t = (r + p - xm) % p * inv_mod(residue(m, p), p) % p;
    x + m * BigInt::from(t)
}

/// `det(x·I − a) mod p` (lowest degree first) by reduction to Hessenberg form (Cohen, Alg. 2.2.9).
fn charpoly_mod(a: &[Vec<BigInt>], p: u64) -> Vec<u64> {
    let n = a.len();
    let mut h: Vec<Vec<u64>> = a
        .iter()
        .map(|r| r.iter().map(|x| residue(x, p)).collect())
        .collect();
    for j in 0..n.saturating_sub(2) {
        let Some(i) = (j + 1..n).find(|&i| h[i][j] != 0) else {
            continue;
        };
        if i != j + 1 {
            h.swap(i, j + 1);
            for row in h.iter_mut() {
                row.swap(i, j + 1);
            }
        }
        let inv = inv_mod(h[j + 1][j], p);
        for k in j + 2..n {
            if h[k][j] == 0 {
                continue;
            }
            let u = h[k][j] * inv % p;
            let pivot_row = h[j + 1].clone();
            for (x, &y) in h[k].iter_mut().zip(&pivot_row) {
                *x = (*x + p - u * y % p) % p;
            }
            for row in h.iter_mut() {
                row[j + 1] = (row[j + 1] + u * row[k]) % p;
            }
        }
    }
    // p_m = (x − h_mm) p_{m−1} − Σ_{i<m} h_im (h_{m,m−1} ⋯ h_{i+1,i}) p_{i−1}   (1-based)
    let mut ps: Vec<Vec<u64>> = vec![vec![1]];
    for m in 1..=n {
        let prev = &ps[m - 1];
        let mut next = vec![0u64; m + 1];
        for (k, &c) in prev.iter().enumerate() {
            next[k + 1] = (next[k + 1] + c) % p;
            next[k] = (next[k] + p - h[m - 1][m - 1] * c % p) % p;
        }
        let mut t = 1u64;
        for i in (1..m).rev() {
            t = t * h[i][i - 1] % p;
            let coef = h[i - 1][m - 1] * t % p;
            if coef == 0 {
                continue;
            }
            for (k, &c) in ps[i - 1].iter().enumerate() {
                next[k] = (next[k] + p - coef * c % p) % p;
            }
        }
        ps.push(next);
    }
    ps.pop().expect("n + 1 polynomials")
}

/// The characteristic polynomial `det(x·I − a)` of a square integer matrix, exact.
///
/// Every coefficient is a signed sum of principal minors, each bounded by Hadamard's product of
/// row norms, so `|c_k| ≤ Π (1 + ⌈‖row_i‖₂⌉)`; primes are used until their product exceeds
/// twice that bound, and the symmetric residues are the coefficients.
pub fn charpoly(a: &[Vec<BigInt>]) -> Poly {
    let bound = a.iter().fold(BigInt::one(), |acc, row| {
        let sq: BigInt = row.iter().map(|x| x * x).sum();
        let mut r = sq.sqrt();
        if &r * &r < sq {
            r += 1;
        }
        acc * (r + 1)
    });
    let mut m = BigInt::one();
    let mut coeffs: Vec<BigInt> = vec![BigInt::zero(); a.len() + 1];
    for p in primes() {
        let c = charpoly_mod(a, p);
        for (x, &r) in coeffs.iter_mut().zip(&c) {
            *x = crt_step(x, &m, r, p);
        }
        m *= p;
        if m > &bound * 2 {
            break;
        }
    }
    Poly::from_bigints(&coeffs.iter().map(|x| symmetric(x, &m)).collect::<Vec<_>>())
}

// ---- polynomials over GF(p): Vec<u64>, lowest degree first, no trailing zeros ----

type Fp = Vec<u64>;

fn trim(mut a: Fp) -> Fp {
    while a.last() == Some(&0) {
        a.pop();
    }
    a
}

fn fp_sub(a: &[u64], b: &[u64], p: u64) -> Fp {
    let n = a.len().max(b.len());
    trim(
        (0..n)
            .map(|i| (a.get(i).unwrap_or(&0) + p - b.get(i).unwrap_or(&0)) % p)
            .collect(),
    )
}

/// `⌊(2^64 − 1)/p⌋`, the constant of [`reduce`].
fn barrett(p: u64) -> u64 {
    u64::MAX / p
}

/// `x mod p` for `2 ≤ p < 2^31` with `m = barrett(p)`, without a division: the estimate
/// `⌊x·m / 2^64⌋` lies in `(x/p − 3, x/p]`, so `x − q·p` is in `[0, 3p)` and two conditional
/// subtractions finish it.
#[inline]
fn reduce(x: u64, p: u64, m: u64) -> u64 {
    let q = ((u128::from(x) * u128::from(m)) >> 64) as u64;
    let mut r = x - q * p;
    if r >= p {
        r -= p;
    }
    if r >= p {
        r -= p;
    }
    r
}

fn fp_mul(a: &[u64], b: &[u64], p: u64) -> Fp {
    debug_assert!(p < 1 << 31);
    if a.is_empty() || b.is_empty() {
        return Vec::new();
    }
    // p < 2^31: products are below p² < 2^62, and sums are kept below p² by subtracting it
    // (no division in the inner loop); one reduction per coefficient at the end.
    let pp = p * p;
    let mut c = vec![0u64; a.len() + b.len() - 1];
    for (i, &x) in a.iter().enumerate() {
        if x == 0 {
            continue;
        }
        for (ci, &y) in c[i..].iter_mut().zip(b) {
            *ci += x * y;
            if *ci >= pp {
                *ci -= pp;
            }
        }
    }
    let m = barrett(p);
    trim(c.into_iter().map(|x| reduce(x, p, m)).collect())
}

fn fp_divrem(a: &[u64], b: &[u64], p: u64) -> (Fp, Fp) {
    let db = b.len() - 1;
    if a.len() < b.len() {
        return (Vec::new(), a.to_vec());
    }
    let inv = inv_mod(b[db], p);
    // Residues of −b: the update adds t·(p − b_j). As in fp_mul, the entries of r stay below
    // p² (p < 2^31) and are reduced mod p only when read as a leading coefficient, and at the end.
    let neg: Vec<u64> = b.iter().map(|&x| (p - x % p) % p).collect();
    let (pp, m) = (p * p, barrett(p));
    let mut r = a.to_vec();
    let mut q = vec![0u64; a.len() - db];
    for i in (0..q.len()).rev() {
        let lead = reduce(r[i + db], p, m);
        // Monic divisors (the usual case) need no second product.
        let t = if inv == 1 {
            lead
        } else {
            reduce(lead * inv, p, m)
        };
        q[i] = t;
        if t == 0 {
            continue;
        }
        for (ri, &nb) in r[i..i + db].iter_mut().zip(&neg) {
            *ri += t * nb;
            if *ri >= pp {
                *ri -= pp;
            }
        }
    }
    r.truncate(db);
    (
        trim(q),
        trim(r.into_iter().map(|x| reduce(x, p, m)).collect()),
    )
}

fn fp_rem(a: &[u64], b: &[u64], p: u64) -> Fp {
    fp_divrem(a, b, p).1
}

fn fp_monic(a: &[u64], p: u64) -> Fp {
    let inv = inv_mod(*a.last().expect("nonzero"), p);
    a.iter().map(|x| x * inv % p).collect()
}

fn fp_gcd(a: &[u64], b: &[u64], p: u64) -> Fp {
    let (mut a, mut b) = (a.to_vec(), b.to_vec());
    while !b.is_empty() {
        let r = fp_rem(&a, &b, p);
        a = b;
        b = r;
    }
    if a.is_empty() {
        a
    } else {
        fp_monic(&a, p)
    }
}

/// `(g, s)` with `s·a ≡ g (mod b)`, `g` the monic gcd.
fn fp_inverse_mod(a: &[u64], b: &[u64], p: u64) -> Fp {
    let (mut r0, mut r1) = (b.to_vec(), fp_rem(a, b, p));
    let (mut s0, mut s1): (Fp, Fp) = (Vec::new(), vec![1]);
    while !r1.is_empty() {
        let (q, r) = fp_divrem(&r0, &r1, p);
        let s = fp_sub(&s0, &fp_mul(&q, &s1, p), p);
        (r0, r1, s0, s1) = (r1, r, s1, s);
    }
    assert_eq!(r0.len(), 1, "coprime modular factors");
    let inv = inv_mod(r0[0], p);
    fp_rem(&s0.iter().map(|x| x * inv % p).collect::<Vec<_>>(), b, p)
}

fn fp_powmod(a: &[u64], e: &BigUint, f: &[u64], p: u64) -> Fp {
    let red = Reducer::new(f, p);
    let mut r: Fp = vec![1];
    let base = fp_rem(a, f, p);
    for i in (0..e.bits()).rev() {
        r = red.rem(fp_mul(&r, &r, p));
        if e.bit(i) {
            r = red.rem(fp_mul(&r, &base, p));
        }
    }
    r
}

/// [`fp_rem`] by one divisor `f` many times: the residues of `−f`, the inverse of its leading
/// coefficient and Barrett's constant are found once, the remainder is formed in the dividend's
/// own vector and no quotient is kept — the same steps as [`fp_divrem`], so the same remainder.
struct Reducer {
    neg: Vec<u64>,
    inv: u64,
    p: u64,
    m: u64,
}

impl Reducer {
    fn new(f: &[u64], p: u64) -> Self {
        let db = f.len() - 1;
        Reducer {
            neg: f[..db].iter().map(|&x| (p - x % p) % p).collect(),
            inv: inv_mod(f[db], p),
            p,
            m: barrett(p),
        }
    }

    /// `a mod f` for `a` with entries below `p` and no trailing zeros.
    fn rem(&self, mut r: Fp) -> Fp {
        let (p, m, db) = (self.p, self.m, self.neg.len());
        if r.len() <= db {
            return r;
        }
        let pp = p * p;
        for i in (0..r.len() - db).rev() {
            let lead = reduce(r[i + db], p, m);
            let t = if self.inv == 1 {
                lead
            } else {
                reduce(lead * self.inv, p, m)
            };
            if t == 0 {
                continue;
            }
            for (ri, &nb) in r[i..i + db].iter_mut().zip(&self.neg) {
                *ri += t * nb;
                if *ri >= pp {
                    *ri -= pp;
                }
            }
        }
        r.truncate(db);
        for x in &mut r {
            *x = reduce(*x, p, m);
        }
        trim(r)
    }
}

/// `a · b⁻¹ mod (f, p)`, `None` when `b` is not invertible there or `p` divides `lc(f)`.
fn quotient_mod_p(a: &[BigInt], b: &[BigInt], f: &[BigInt], p: u64) -> Option<Fp> {
    let fp = trim(f.iter().map(|x| residue(x, p)).collect());
    if fp.len() != f.len() {
        return None;
    }
    let bp = trim(b.iter().map(|x| residue(x, p)).collect());
    let ap = trim(a.iter().map(|x| residue(x, p)).collect());
    let (mut r0, mut r1) = (fp.clone(), fp_rem(&bp, &fp, p));
    let (mut s0, mut s1): (Fp, Fp) = (Vec::new(), vec![1]);
    while !r1.is_empty() {
        let (q, r) = fp_divrem(&r0, &r1, p);
        let s = fp_sub(&s0, &fp_mul(&q, &s1, p), p);
        (r0, r1, s0, s1) = (r1, r, s1, s);
    }
    if r0.len() != 1 {
        return None;
    }
    let inv = inv_mod(r0[0], p);
    let binv: Fp = s0.iter().map(|x| x * inv % p).collect();
    Some(fp_rem(&fp_mul(&ap, &binv, p), &fp, p))
}

/// Wang's rational reconstruction: `n/d ≡ u (mod m)` with `|n|, d ≤ √(m/2)`, if any.
fn rational_reconstruction(u: &BigInt, m: &BigInt) -> Option<num_rational::BigRational> {
    let bound = (m / 2u32).sqrt();
    let (mut r0, mut r1) = (m.clone(), u.mod_floor(m));
    let (mut t0, mut t1) = (BigInt::zero(), BigInt::one());
    while r1 > bound {
        let q = &r0 / &r1;
        let r = &r0 - &q * &r1;
        let t = &t0 - &q * &t1;
        (r0, r1, t0, t1) = (r1, r, t1, t);
    }
    if t1.is_zero() || t1.abs() > bound {
        return None;
    }
    Some(num_rational::BigRational::new(r1, t1))
}

/// Whether the rational coefficients `c` reduce, modulo a prime not dividing `m`, to the image
/// of `a/b` there.
fn agrees_mod_fresh_prime(
    c: &[num_rational::BigRational],
    a: &[BigInt],
    b: &[BigInt],
    f: &[BigInt],
    m: &BigInt,
) -> bool {
    for p in (1u64 << 19..1u64 << 20)
        .rev()
        .filter(|&n| n % 2 == 1 && is_prime(n))
    {
        if (m % p).is_zero() || c.iter().any(|x| (x.denom() % p).is_zero()) {
            continue;
        }
        let Some(img) = quotient_mod_p(a, b, f, p) else {
            continue;
        };
        let cp = trim(
            c.iter()
                .map(|x| residue(x.numer(), p) * inv_mod(residue(x.denom(), p), p) % p)
                .collect(),
        );
        return cp == img;
    }
    true
}

/// Candidates for `a/b` in `Q[x]/(f)` (integer polynomials, `f` of degree `d`, `b` invertible):
/// images modulo more and more primes, Chinese remaindering and rational reconstruction at every
/// doubling of the prime count. `accept` verifies a candidate exactly; the first accepted one is
/// returned. Reconstruction is used because the quotient is usually far smaller than the inputs.
pub(crate) fn modular_quotient(
    a: &[BigInt],
    b: &[BigInt],
    f: &[BigInt],
    mut accept: impl FnMut(&[num_rational::BigRational]) -> bool,
) -> Vec<num_rational::BigRational> {
    let d = f.len() - 1;
    let mut acc = vec![BigInt::zero(); d];
    let mut m = BigInt::one();
    let mut used = 0usize;
    let mut next_try = 1usize;
    for p in primes() {
        let Some(img) = quotient_mod_p(a, b, f, p) else {
            continue;
        };
        for (i, x) in acc.iter_mut().enumerate() {
            *x = crt_step(x, &m, img.get(i).copied().unwrap_or(0), p);
        }
        m *= p;
        used += 1;
        if used == next_try {
            next_try *= 2;
            let cand: Option<Vec<_>> = acc.iter().map(|x| rational_reconstruction(x, &m)).collect();
            // A cheap filter before the exact check: the candidate must agree with the
            // image modulo a prime not used yet.
            if let Some(c) = cand.filter(|c| agrees_mod_fresh_prime(c, a, b, f, &m)) {
                if accept(&c) {
                    return c;
                }
            }
        }
    }
    unreachable!("there are enough primes below 2^31")
}

/// `Σ c_i·rows[i]` over GF(p) (`c` no longer than `rows`).
fn fp_combine(c: &[u64], rows: &[Fp], p: u64) -> Fp {
    let width = rows.iter().map(Vec::len).max().unwrap_or(0);
    let (pp, m) = (p * p, barrett(p));
    let mut acc = vec![0u64; width];
    for (&ci, row) in c.iter().zip(rows) {
        for (a, &r) in acc.iter_mut().zip(row) {
            *a += ci * r;
            if *a >= pp {
                *a -= pp;
            }
        }
    }
    trim(acc.into_iter().map(|x| reduce(x, p, m)).collect())
}

/// Distinct-degree factorisation of a square-free monic `f`: `(product, degree)` pairs.
fn ddf(f: &[u64], p: u64) -> Vec<(Fp, usize)> {
    let mut out = Vec::new();
    let f0 = f;
    let mut f = f.to_vec();
    let x: Fp = vec![0, 1];
    let mut h = x.clone();
    let pe = BigUint::from(p);
    // Rows x^(i·p) mod f0 of the Frobenius map, built at the second step: then h^p = h(x^p)
    // (coefficients in GF(p)) is one combination of rows instead of a power, and reducing it
    // mod the current f (which divides f0) gives exactly h^p mod f.
    let mut frobenius: Vec<Fp> = Vec::new();
    let mut xp: Fp = Vec::new();
    let mut d = 0;
    while f.len() > 1 {
        d += 1;
        if f.len() - 1 < 2 * d {
            let deg = f.len() - 1;
            out.push((f, deg));
            break;
        }
        h = if d == 1 {
            // f = f0 and h = x here: x^p mod f0, kept for the Frobenius rows.
            xp = fp_powmod(&x, &pe, f0, p);
            xp.clone()
        } else {
            if frobenius.is_empty() {
                frobenius.push(vec![1]);
                for i in 1..f0.len() - 1 {
                    let next = fp_rem(&fp_mul(&frobenius[i - 1], &xp, p), f0, p);
                    frobenius.push(next);
                }
            }
            fp_rem(&fp_combine(&h, &frobenius, p), &f, p)
        };
        let g = fp_gcd(&f, &fp_sub(&h, &x, p), p);
        if g.len() > 1 {
            f = fp_divrem(&f, &g, p).0;
            h = fp_rem(&h, &f, p);
            out.push((g, d));
        }
    }
    out
}

/// The monic irreducible factors of a monic square-free integer polynomial `f` (lowest degree
/// first) of degree ≥ 1 with `f(0) ≠ 0`.
fn factor_monic(f: &[BigInt]) -> Result<Vec<Vec<BigInt>>, FactorError> {
    let Some((p, gs)) = modular_factors(f) else {
        return Ok(vec![f.to_vec()]);
    };
    let n = f.len() - 1;
    // Mignotte: a factor's coefficients are at most 2^n ‖f‖₂ ≤ 2^n ‖f‖₁.
    let norm1: BigInt = f.iter().map(Signed::abs).sum();
    let bound = (BigInt::one() << n) * norm1;
    let (lifted, m) = hensel(f, &gs, p, &bound);
    recombine(f, lifted, &m, p)
}

/// The prime [`factor_monic`] works modulo and its monic irreducible factors of `f` there, in
/// the order the recombination takes them; `None` when `f` is linear or stays irreducible
/// modulo that prime (then `f` is irreducible).
fn modular_factors(f: &[BigInt]) -> Option<(u64, Vec<Fp>)> {
    let n = f.len() - 1;
    if n == 1 {
        return None;
    }
    // The best of three suitable primes: fewest modular factors.
    type Choice = (u64, Vec<(Fp, usize)>, usize);
    let mut best: Option<Choice> = None;
    for p in primes()
        .filter(|&p| {
            let fp = trim(f.iter().map(|a| residue(a, p)).collect());
            let dfp = trim((1..fp.len()).map(|i| fp[i] * (i as u64 % p) % p).collect());
            fp_gcd(&fp, &dfp, p).len() == 1
        })
        .take(3)
    {
        let fp: Fp = f.iter().map(|a| residue(a, p)).collect();
        let parts = ddf(&fp, p);
        let count: usize = parts.iter().map(|(g, d)| (g.len() - 1) / d).sum();
        if best.as_ref().is_none_or(|b| count < b.2) {
            best = Some((p, parts, count));
        }
    }
    let (p, parts, count) = best.expect("some prime keeps f square-free");
    if count == 1 {
        return None;
    }
    let mut seed = 0x9E37_79B9_7F4A_7C15u64;
    let mut gs = Vec::new();
    for (g, d) in &parts {
        edf(g, *d, p, &mut seed, &mut gs);
    }
    Some((p, gs))
}

/// Monic division over Z: `Some(a / b)` when exact.
fn int_div_exact(a: &[BigInt], b: &[BigInt]) -> Option<Vec<BigInt>> {
    let db = b.len() - 1;
    let mut r = a.to_vec();
    let mut q = vec![BigInt::zero(); a.len() - db];
    for i in (0..q.len()).rev() {
        let t = r[i + db].clone();
        for (j, bj) in b.iter().enumerate() {
            r[i + j] -= &t * bj;
        }
        q[i] = t;
    }
    r.iter().all(Zero::is_zero).then_some(q)
}

/// Zassenhaus recombination: products of lifted factors that divide `f`, by increasing size.
fn recombine(
    f: &[BigInt],
    pool: Vec<Vec<BigInt>>,
    m: &BigInt,
    p: u64,
) -> Result<Vec<Vec<BigInt>>, FactorError> {
    let (degree, modular) = (f.len() - 1, pool.len());
    let mut f = f.to_vec();
    let mut out = Vec::new();
    let divides = |pool: &[Vec<BigInt>], subset: &[usize]| {
        // The constant term of the product alone first: it is exactly the `h[0]` the full
        // product below gives (the constant term of each partial product is the symmetric
        // residue of the previous one times `g[0]`), and most subsets fail here.
        let h0 = subset
            .iter()
            .fold(BigInt::one(), |acc, &i| symmetric(&(acc * &pool[i][0]), m));
        if h0.is_zero() || !(&f[0] % &h0).is_zero() {
            return false;
        }
        let mut h = vec![BigInt::one()];
        for &i in subset {
            let g = &pool[i];
            let mut c = vec![BigInt::zero(); h.len() + g.len() - 1];
            for (a, x) in h.iter().enumerate() {
                for (b, y) in g.iter().enumerate() {
                    c[a + b] += x * y;
                }
            }
            h = c.iter().map(|x| symmetric(x, m)).collect();
        }
        match int_div_exact(&f, &h) {
            Some(q) => {
                f = q;
                out.push(h);
                true
            }
            None => false,
        }
    };
    if subsets_in_order(pool, divides).is_none() {
        return Err(FactorError {
            degree,
            modular,
            prime: p,
            budget: BUDGET,
        });
    }
    if f.len() > 1 {
        out.push(f);
    }
    Ok(out)
}

/// Whether `f` (nonconstant) is square-free modulo one of a few primes not dividing its leading
/// coefficient, which proves it square-free over Q (a repeated factor stays repeated mod p).
fn square_free_mod_some_prime(f: &Poly) -> bool {
    let ints = f.primitive_int();
    if ints.len() < 2 {
        return false;
    }
    primes().take(3).any(|p| {
        let fp = trim(ints.iter().map(|a| residue(a, p)).collect());
        if fp.len() != ints.len() {
            return false;
        }
        let dfp = trim((1..fp.len()).map(|i| fp[i] * (i as u64 % p) % p).collect());
        fp_gcd(&fp, &dfp, p).len() == 1
    })
}

/// The monic irreducible factors over Q of `f` with their multiplicities.
pub fn factor(f: &Poly) -> Result<Vec<(Poly, usize)>, FactorError> {
    factor_with(f, true)
}

/// [`factor`]; with `small_scale` each square-free part is factored at the smallest scale
/// [`scaled::factor_part`] finds, otherwise at the lcm of its denominators only (the result is
/// the same).
fn factor_with(f: &Poly, small_scale: bool) -> Result<Vec<(Poly, usize)>, FactorError> {
    let mut out = Vec::new();
    let parts = if square_free_mod_some_prime(f) {
        vec![(f.monic(), 1)]
    } else {
        f.square_free()
    };
    for (g, mult) in parts {
        let found = if small_scale {
            scaled::factor_part(&g)?
        } else {
            scaled::factor_scaled(&g, &scaled::lcm_scale(&g))?
        };
        out.extend(found.into_iter().map(|h| (h, mult)));
    }
    out.sort_by_key(|(g, m)| (g.deg(), *m));
    Ok(out)
}

#[cfg(test)]
mod tests;
