//! Certified complex root disks of a square-free polynomial over Q: floating-point approximations
//! (Durand–Kerner) made rigorous by exact rational evaluation.
//!
//! For any z, some root of f lies within `n·|f(z)/f'(z)|` of z (since `f'/f = Σ 1/(z − ζ_k)`).
//! When the n disks of these radii around n approximations are pairwise disjoint, each holds at
//! least one root and there are n roots, so each holds exactly one. The radius is evaluated
//! exactly at the rational (dyadic) point z and rounded upwards; the disjointness test is exact.
//! A float only proposes the centres; every statement made from a disk is a theorem.
//! When the approximations are too poor to separate, [`root_disks`] returns `None` and the caller
//! uses its exact (slower) method instead.

use crate::algebra::poly::Poly;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{FromPrimitive, One, Signed, ToPrimitive, Zero};
use std::cmp::Ordering;

/// A closed disk `|w − (re + i·im)| ≤ r` holding exactly one root.
#[derive(Clone, Debug)]
pub struct Disk {
    /// Real part of the centre.
    pub re: BigRational,
    /// Imaginary part of the centre.
    pub im: BigRational,
    /// Radius (a rational upper bound).
    pub r: BigRational,
}

fn cx_mul(a: (f64, f64), b: (f64, f64)) -> (f64, f64) {
    (a.0 * b.0 - a.1 * b.1, a.0 * b.1 + a.1 * b.0)
}

fn cx_div(a: (f64, f64), b: (f64, f64)) -> (f64, f64) {
    let d = b.0 * b.0 + b.1 * b.1;
    ((a.0 * b.0 + a.1 * b.1) / d, (a.1 * b.0 - a.0 * b.1) / d)
}

/// Float approximations of every root of `f` (Durand–Kerner, then Newton polishing).
pub fn approx_roots(f: &Poly) -> Vec<(f64, f64)> {
    let f = f.monic();
    let c: Vec<f64> = f
        .coeffs()
        .iter()
        .map(|x| x.to_f64().unwrap_or(0.0))
        .collect();
    let n = f.deg();
    let eval = |z: (f64, f64)| {
        c.iter().rev().fold((0.0, 0.0), |acc, &a| {
            let m = cx_mul(acc, z);
            (m.0 + a, m.1)
        })
    };
    let dc: Vec<f64> = (1..c.len()).map(|i| c[i] * i as f64).collect();
    let deval = |z: (f64, f64)| {
        dc.iter().rev().fold((0.0, 0.0), |acc, &a| {
            let m = cx_mul(acc, z);
            (m.0 + a, m.1)
        })
    };
    // Start on a circle of the size of the roots (Fujiwara-like bound).
    let scale = (0..n)
        .map(|i| c[i].abs().powf(1.0 / (n - i) as f64))
        .fold(0.0f64, f64::max)
        .clamp(1e-12, 1e12);
    let w = (0.4f64, 0.9f64);
    let wn = w.0.hypot(w.1);
    let mut z: Vec<(f64, f64)> = (0..n)
        .map(|i| {
            let p = (0..i).fold((1.0, 0.0), |acc, _| cx_mul(acc, (w.0 / wn, w.1 / wn)));
            (p.0 * scale, p.1 * scale)
        })
        .collect();
    dk_sweeps(&mut z, eval, true);
    for zi in z.iter_mut() {
        for _ in 0..3 {
            let d = deval(*zi);
            if d.0 == 0.0 && d.1 == 0.0 {
                break;
            }
            let s = cx_div(eval(*zi), d);
            *zi = (zi.0 - s.0, zi.1 - s.1);
        }
    }
    z
}

/// Durand–Kerner sweeps over `z` (in place, in order), at most 500, until the largest relative
/// step is below 1e-17. With `stop_when_still`, also after a sweep that left every `z[i]` bit for
/// bit unchanged: every later sweep would repeat that one exactly (the same inputs in the same
/// order), so stopping there gives the same result as running on.
fn dk_sweeps(z: &mut [(f64, f64)], eval: impl Fn((f64, f64)) -> (f64, f64), stop_when_still: bool) {
    let n = z.len();
    let bits = |w: (f64, f64)| (w.0.to_bits(), w.1.to_bits());
    for _ in 0..500 {
        let mut moved = 0.0f64;
        let mut still = true;
        for i in 0..n {
            let num = eval(z[i]);
            let mut den = (1.0, 0.0);
            for j in 0..n {
                if i != j {
                    den = cx_mul(den, (z[i].0 - z[j].0, z[i].1 - z[j].1));
                }
            }
            if den.0 * den.0 + den.1 * den.1 > 0.0 {
                let quo = cx_div(num, den);
                let next = (z[i].0 - quo.0, z[i].1 - quo.1);
                still &= bits(next) == bits(z[i]);
                z[i] = next;
                moved = moved.max(quo.0.hypot(quo.1) / z[i].0.hypot(z[i].1).max(1e-300));
            }
        }
        if moved < 1e-17 || stop_when_still && still {
            break;
        }
    }
}

/// `(Re, Im)` of `D^n·p((a + b·i)/D)` for the integer polynomial `p` of degree n (lowest
/// degree first): homogeneous Horner over Z, exact.
fn eval_homogeneous(p: &[BigInt], a: &BigInt, b: &BigInt, d: &BigInt) -> (BigInt, BigInt) {
    let n = p.len() - 1;
    let (mut re, mut im) = (p[n].clone(), BigInt::zero());
    let mut dpow = d.clone();
    for c in p[..n].iter().rev() {
        let nre = &re * a - &im * b + c * &dpow;
        let nim = &re * b + &im * a;
        re = nre;
        im = nim;
        dpow *= d;
    }
    (re, im)
}

/// A rational `s ≥ √x` (x ≥ 0), close to it.
pub fn sqrt_up(x: &BigRational) -> BigRational {
    if x.is_zero() {
        return BigRational::zero();
    }
    let two = BigRational::from_integer(2.into());
    let mut up = x
        .to_f64()
        .and_then(|v| BigRational::from_f64(v.sqrt() * (1.0 + 1e-12) + f64::MIN_POSITIVE))
        .unwrap_or_else(|| x + BigRational::from_integer(1.into()));
    // up² < x by cross-multiplication (positive denominators): no gcd for a comparison.
    while up.numer() * up.numer() * x.denom() < x.numer() * up.denom() * up.denom() {
        up = crate::algebra::intgcd::mul(&up, &two);
    }
    up
}

/// The certified disks of the roots of the square-free `f`, one per root, or `None` when the
/// float approximations do not separate them.
pub fn root_disks(f: &Poly) -> Option<Vec<Disk>> {
    let n = f.deg();
    if n == 0 {
        return Some(Vec::new());
    }
    let fi = f.primitive_int();
    let dfi: Vec<BigInt> = (1..fi.len()).map(|i| &fi[i] * BigInt::from(i)).collect();
    let nn = BigInt::from(n);
    let mut disks = Vec::with_capacity(n);
    for (x, y) in approx_roots(f) {
        if !x.is_finite() || !y.is_finite() {
            return None;
        }
        // Centre (a + b·i)/2^e with |a|, |b| < 2^62.
        let m = x.abs().max(y.abs()).max(f64::MIN_POSITIVE);
        let e = (62 - m.log2().ceil() as i64).clamp(0, 2000) as u32;
        let scale = 2f64.powi(e.min(1000) as i32) * 2f64.powi(e.saturating_sub(1000) as i32);
        let a = BigInt::from((x * scale).round() as i64);
        let b = BigInt::from((y * scale).round() as i64);
        let d = BigInt::one() << e;
        let (fa, fb) = eval_homogeneous(&fi, &a, &b, &d);
        let (da, db) = eval_homogeneous(&dfi, &a, &b, &d);
        let den = &da * &da + &db * &db;
        if den.is_zero() {
            return None;
        }
        // f(z) = F/D^n, f'(z) = F'/D^(n−1): |f/f'|² = |F|² / (|F'|²·D²).
        // Left unreduced (a gcd of two large integers saved): sqrt_up only compares and
        // converts it, and both work on its value.
        let r2 = BigRational::new_raw(&nn * &nn * (&fa * &fa + &fb * &fb), den * &d * &d);
        disks.push(Disk {
            re: crate::algebra::intgcd::ratio(a, d.clone()),
            im: crate::algebra::intgcd::ratio(b, d),
            r: sqrt_up(&r2),
        });
    }
    let approx: Vec<[f64; 3]> = disks
        .iter()
        .map(|d| [&d.re, &d.im, &d.r].map(|x| x.to_f64().unwrap_or(f64::NAN)))
        .collect();
    for i in 0..n {
        for j in i + 1..n {
            if apart_f64(&approx[i], &approx[j]) {
                continue;
            }
            let (a, b) = (&disks[i], &disks[j]);
            let dre = &a.re - &b.re;
            let dim = &a.im - &b.im;
            let s = &a.r + &b.r;
            if (&dre * &dre + &dim * &dim).cmp(&(&s * &s)) != Ordering::Greater {
                return None;
            }
        }
    }
    Some(disks)
}

/// Whether the disks `[re, im, r]` (each number within a few units in the last place of the
/// rational it approximates) are certainly disjoint: the distance of the centres, bounded below
/// with every rounding error, exceeds the sum of the radii bounded above. `false` means "not
/// decided in floats" (the caller then compares exactly), never "they meet".
fn apart_f64(a: &[f64; 3], b: &[f64; 3]) -> bool {
    // A relative error far above the few ulps of the conversions and operations, and floors that
    // keep every square a normal float.
    const E: f64 = 1e-9;
    const FLOOR: f64 = 1e-140;
    if !a.iter().chain(b).all(|x| x.is_finite()) {
        return false;
    }
    let lower = |x: f64, y: f64| ((x - y).abs() * (1.0 - E) - E * (x.abs() + y.abs())).max(0.0);
    let (dre, dim) = (lower(a[0], b[0]), lower(a[1], b[1]));
    let dist2 = (dre * dre + dim * dim) * (1.0 - E);
    let s = ((a[2].abs() + b[2].abs()) * (1.0 + E)).max(FLOOR);
    let s2 = s * s * (1.0 + E);
    dist2.is_finite() && s2.is_finite() && dist2 > FLOOR && dist2 > s2
}

impl Disk {
    /// True when the disk lies strictly above the real axis (its root is not real, and it is
    /// the one of its conjugate pair with positive imaginary part).
    pub fn above_axis(&self) -> bool {
        self.im > self.r
    }

    /// Compares the modulus of the root in this disk with a number known to lie in
    /// `[lo, hi]` (`0 ≤ lo ≤ hi`): `Some(Less)` / `Some(Greater)` when decided, `None` otherwise.
    pub fn cmp_modulus(&self, lo: &BigRational, hi: &BigRational) -> Option<Ordering> {
        // Exact comparisons in integers over positive denominators: no gcd (num-rational would
        // reduce every product and sum only for them to be compared).
        let (re, im, r) = (&self.re, &self.im, &self.r);
        let (rd2, id2) = (re.denom() * re.denom(), im.denom() * im.denom());
        // |z|² = mn / md.
        let mn = re.numer() * re.numer() * &id2 + im.numer() * im.numer() * &rd2;
        let md = rd2 * id2;
        // |w| ≤ |z| + r < lo  ⇐  |z| < lo − r, with lo − r = an / ad.
        let an = lo.numer() * r.denom() - r.numer() * lo.denom();
        if an.is_positive() {
            let ad = lo.denom() * r.denom();
            if &mn * &ad * &ad < &an * &an * &md {
                return Some(Ordering::Less);
            }
        }
        // |w| ≥ |z| − r > hi  ⇐  |z| > hi + r, with hi + r = bn / bd.
        let bn = hi.numer() * r.denom() + r.numer() * hi.denom();
        let bd = hi.denom() * r.denom();
        if &mn * &bd * &bd > &bn * &bn * &md {
            return Some(Ordering::Greater);
        }
        None
    }

    /// `(re, im)` of the centre as floats.
    pub fn approx(&self) -> (f64, f64) {
        (
            self.re.to_f64().unwrap_or(f64::NAN),
            self.im.to_f64().unwrap_or(f64::NAN),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// Stopping after a sweep that moved nothing gives, bit for bit, the approximations of
        /// all 500 sweeps (or of the relative-step test), from the same start as approx_roots.
        #[test]
        fn still_sweep_stop_is_exact(c in prop::collection::vec(-50i32..=50, 2..=10), s in 0.1f64..3.0) {
            let n = c.len() - 1;
            prop_assume!(c[n] != 0);
            let c: Vec<f64> = c.iter().map(|&x| f64::from(x) / f64::from(c[n])).collect();
            let eval = |z: (f64, f64)| {
                c.iter().rev().fold((0.0, 0.0), |acc, &a| {
                    let m = cx_mul(acc, z);
                    (m.0 + a, m.1)
                })
            };
            let (w, wn) = ((0.4f64, 0.9f64), 0.4f64.hypot(0.9));
            let start: Vec<(f64, f64)> = (0..n)
                .map(|i| {
                    let p = (0..i).fold((1.0, 0.0), |acc, _| cx_mul(acc, (w.0 / wn, w.1 / wn)));
                    (p.0 * s, p.1 * s)
                })
                .collect();
            let (mut fast, mut full) = (start.clone(), start);
            dk_sweeps(&mut fast, eval, true);
            dk_sweeps(&mut full, eval, false);
            let bits = |v: &[(f64, f64)]| v.iter().map(|z| (z.0.to_bits(), z.1.to_bits())).collect::<Vec<_>>();
            prop_assert_eq!(bits(&fast), bits(&full));
        }
    }

    #[test]
    fn disks_of_known_roots() {
        // x² + 1/4: ±i/2; x³ − 2: one real root 2^(1/3) ≈ 1.26 and a pair of modulus 2^(1/3).
        let d = root_disks(&Poly::new(vec![
            BigRational::new(1.into(), 4.into()),
            BigRational::zero(),
            BigRational::from_integer(1.into()),
        ]))
        .unwrap();
        assert_eq!(d.iter().filter(|x| x.above_axis()).count(), 1);
        let half = BigRational::new(1.into(), 2.into());
        let third = BigRational::new(1.into(), 3.into());
        assert_eq!(d[0].cmp_modulus(&third, &third), Some(Ordering::Greater));
        assert_eq!(d[0].cmp_modulus(&half, &half), None);
        let d = root_disks(&Poly::from_ints(&[-2, 0, 0, 1])).unwrap();
        assert_eq!(d.iter().filter(|x| x.above_axis()).count(), 1);
        assert!(d
            .iter()
            .all(|x| x.r < BigRational::new(1.into(), 1_000_000.into())));
    }
}
