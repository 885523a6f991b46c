//! Linear Hensel lifting of a factorisation modulo p to one modulo p^k, for
//! [`super::factor_monic`]: the error of each step in big integers, or in machine integers while
//! the modulus fits.

use super::{fp_divrem, fp_inverse_mod, fp_mul, fp_rem, residue, trim, Fp};
use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{One, Zero};

/// Lifts `f ≡ Π gs (mod p)` to `f ≡ Π lifted (mod m)` with `m = p^k > 2·bound`.
pub(super) fn hensel(
    f: &[BigInt],
    gs: &[Fp],
    p: u64,
    bound: &BigInt,
) -> (Vec<Vec<BigInt>>, BigInt) {
    let fp: Fp = f.iter().map(|a| residue(a, p)).collect();
    // a_i = (f / g_i)^{-1} mod g_i: then Σ a_i f/g_i ≡ 1, the partial-fraction identity.
    let inverses: Vec<Fp> = gs
        .iter()
        .map(|g| fp_inverse_mod(&fp_divrem(&fp, g, p).0, g, p))
        .collect();
    let mut lifted: Vec<Vec<BigInt>> = gs
        .iter()
        .map(|g| g.iter().map(|&x| BigInt::from(x)).collect())
        .collect();
    let mut m = BigInt::from(p);
    let pb = BigInt::from(p);
    while m <= bound * 2 {
        let mp = &m * &pb;
        let err = lift_error_u64(f, &lifted, &m, &mp, p)
            .unwrap_or_else(|| lift_error_big(f, &lifted, &m, &mp, p));
        for ((g, g0), a) in lifted.iter_mut().zip(gs).zip(&inverses) {
            let delta = fp_rem(&fp_mul(&err, a, p), g0, p);
            for (x, &d) in g.iter_mut().zip(&delta) {
                *x += &m * d;
            }
        }
        m = mp;
    }
    (lifted, m)
}

/// `(f − Π lifted) / m mod p` (exact: `f ≡ Π lifted mod m`), the product reduced mod `mp = m·p`.
pub(super) fn lift_error_big(
    f: &[BigInt],
    lifted: &[Vec<BigInt>],
    m: &BigInt,
    mp: &BigInt,
    p: u64,
) -> Fp {
    let mut prod = vec![BigInt::one()];
    for g in lifted {
        let mut c = vec![BigInt::zero(); prod.len() + g.len() - 1];
        for (i, x) in prod.iter().enumerate() {
            for (j, y) in g.iter().enumerate() {
                c[i + j] += x * y;
            }
        }
        prod = c.iter().map(|x| x.mod_floor(mp)).collect();
    }
    trim(
        f.iter()
            .zip(&prod)
            .map(|(a, b)| residue(&((a - b).mod_floor(mp) / m), p))
            .collect(),
    )
}

/// [`lift_error_big`] in machine integers while `m·p < 2^63` and the lifted coefficients are in
/// `[0, m)` (as lifting leaves them): products of residues mod `mp` fit a `u128`, and the same
/// residues give the same error. `None` otherwise.
pub(super) fn lift_error_u64(
    f: &[BigInt],
    lifted: &[Vec<BigInt>],
    m: &BigInt,
    mp: &BigInt,
    p: u64,
) -> Option<Fp> {
    let (m, mp) = (u64::try_from(m).ok()?, u64::try_from(mp).ok()?);
    if mp >= 1 << 63 {
        return None;
    }
    let modulus = u128::from(mp);
    let mut prod = vec![1u128];
    for g in lifted {
        let g: Vec<u128> = g
            .iter()
            .map(|x| u64::try_from(x).ok().filter(|&v| v < m).map(u128::from))
            .collect::<Option<_>>()?;
        let mut c = vec![0u128; prod.len() + g.len() - 1];
        for (i, &x) in prod.iter().enumerate() {
            for (j, &y) in g.iter().enumerate() {
                c[i + j] = (c[i + j] + x * y % modulus) % modulus;
            }
        }
        prod = c;
    }
    let err = f.iter().zip(&prod).map(|(a, &b)| {
        // a mod mp, digit by digit (mp < 2^63, so r·2^32 + digit fits a u128).
        let r = a
            .magnitude()
            .iter_u32_digits()
            .rev()
            .fold(0u128, |r, d| ((r << 32) | u128::from(d)) % modulus);
        let a = if a.sign() == num_bigint::Sign::Minus && r != 0 {
            modulus - r
        } else {
            r
        };
        let diff = (a + modulus - b) % modulus;
        (diff as u64 / m) % p
    });
    Some(trim(err.collect()))
}
