//! A witness that an integer polynomial is irreducible over Q: a prime modulo which it stays
//! irreducible of the same degree (any factorisation over Q would reduce to one modulo that
//! prime). Certificates give it to the checker, which re-proves it with its own test.

use super::{ddf, fp_gcd, fp_monic, is_prime, residue, trim};
use num_bigint::BigInt;

/// The first odd prime below 10⁴ that does not divide the leading coefficient of `p`
/// (integer coefficients, constant term first) and modulo which `p` is irreducible; `None`
/// when there is none (p reducible, or its Galois group has no element of order deg p), or for
/// a constant.
pub(crate) fn irreducibility_prime(p: &[BigInt]) -> Option<u64> {
    let d = p.len().checked_sub(1).filter(|&d| d >= 1)?;
    (3..10_000u64).filter(|&q| is_prime(q)).find(|&q| {
        let f = trim(p.iter().map(|c| residue(c, q)).collect());
        if f.len() != d + 1 {
            return false; // q divides the leading coefficient
        }
        let f = fp_monic(&f, q);
        let derivative: Vec<u64> = (1..f.len()).map(|i| f[i] * (i as u64 % q) % q).collect();
        if fp_gcd(&f, &trim(derivative), q).len() > 1 {
            return false; // a repeated factor modulo q
        }
        let parts = ddf(&f, q);
        parts.len() == 1 && parts[0].1 == d
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn poly(c: &[i64]) -> Vec<BigInt> {
        c.iter().map(|&x| BigInt::from(x)).collect()
    }

    #[test]
    fn witnesses_by_hand() {
        // x² − 2: 2 is a square neither mod 3 nor mod 5 (squares mod 3: 0, 1): the first is 3.
        assert_eq!(irreducibility_prime(&poly(&[-2, 0, 1])), Some(3));
        // x² − 3: 3 divides it mod 3 (x², repeated); mod 5, 3 is no square (1, 4): 5.
        assert_eq!(irreducibility_prime(&poly(&[-3, 0, 1])), Some(5));
        // (x − 1)(x + 1) splits modulo every prime.
        assert_eq!(irreducibility_prime(&poly(&[-1, 0, 1])), None);
        // x⁴ + 1 is irreducible over Q but reducible modulo every prime.
        assert_eq!(irreducibility_prime(&poly(&[1, 0, 0, 0, 1])), None);
        // A linear polynomial is irreducible modulo any prime not dividing its leading term.
        assert_eq!(irreducibility_prime(&poly(&[5, 3])), Some(5));
    }
}
