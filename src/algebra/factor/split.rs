//! Equal-degree splitting (Cantor–Zassenhaus) for [`super::modular_factors`]: a product of
//! irreducibles of one degree `d` modulo `p` split by gcds with `a^((p^d − 1)/2) − 1` for
//! pseudo-random `a`, the power formed through the Frobenius rows.

use super::{fp_combine, fp_divrem, fp_gcd, fp_mul, fp_powmod, fp_rem, fp_sub, trim, Fp};
use num_bigint::BigUint;

/// Equal-degree splitting (Cantor–Zassenhaus) of `f`, a product of irreducibles of degree `d`.
pub(super) fn edf(f: &[u64], d: usize, p: u64, seed: &mut u64, out: &mut Vec<Fp>) {
    let rows = if d > 1 && f.len() - 1 > d {
        frobenius_rows(f, p)
    } else {
        Vec::new()
    };
    edf_with(f, d, p, seed, out, &rows);
}

/// The rows `x^(i·p) mod f`, `i < deg f`, of the Frobenius map `h ↦ h^p = h(x^p)` mod `f`.
pub(super) fn frobenius_rows(f: &[u64], p: u64) -> Vec<Fp> {
    let xp = fp_powmod(&[0, 1], &BigUint::from(p), f, p);
    let mut rows: Vec<Fp> = vec![vec![1]];
    for i in 1..f.len() - 1 {
        let next = fp_rem(&fp_mul(&rows[i - 1], &xp, p), f, p);
        rows.push(next);
    }
    rows
}

/// `a^((p^d − 1)/2) mod f`, as [`fp_powmod`] gives it: the exponent is `(p − 1)/2` times
/// `1 + p + … + p^(d−1)`, so the power is `(Π_{i<d} a^(p^i))^((p−1)/2)` with each `a^(p^i)` one
/// step of the Frobenius rows (`rows`, those of `f`, needed when `d > 1`) instead of a power.
pub(super) fn fp_pow_half(a: &[u64], d: usize, f: &[u64], p: u64, rows: &[Fp]) -> Fp {
    let half = BigUint::from((p - 1) / 2);
    let mut conj = fp_rem(a, f, p);
    let mut norm = conj.clone();
    for _ in 1..d {
        conj = fp_rem(&fp_combine(&conj, rows, p), f, p);
        norm = fp_rem(&fp_mul(&norm, &conj, p), f, p);
    }
    fp_powmod(&norm, &half, f, p)
}

fn edf_with(f: &[u64], d: usize, p: u64, seed: &mut u64, out: &mut Vec<Fp>, rows: &[Fp]) {
    let n = f.len() - 1;
    if n == d {
        out.push(f.to_vec());
        return;
    }
    loop {
        let a: Fp = trim(
            (0..n)
                .map(|_| {
                    *seed ^= *seed << 13;
                    *seed ^= *seed >> 7;
                    *seed ^= *seed << 17;
                    *seed % p
                })
                .collect(),
        );
        if a.len() < 2 {
            continue;
        }
        let b = fp_sub(&fp_pow_half(&a, d, f, p, rows), &[1], p);
        let g = fp_gcd(f, &b, p);
        if g.len() > 1 && g.len() < f.len() {
            let other = fp_divrem(f, &g, p).0;
            // The rows of a divisor are those of f reduced modulo it.
            let reduced = |h: &[u64]| -> Vec<Fp> {
                rows.iter()
                    .take(h.len() - 1)
                    .map(|r| fp_rem(r, h, p))
                    .collect()
            };
            edf_with(&g, d, p, seed, out, &reduced(&g));
            edf_with(&other, d, p, seed, out, &reduced(&other));
            return;
        }
    }
}
