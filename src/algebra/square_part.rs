//! The square part of an integer, for writing quadratic numbers in closed form (`a + b·sqrt(d)`)
//! with a small radicand.

use num_bigint::BigInt;
use num_traits::{One, Zero};

/// `(k, d)` with `n = k²·d`, `d` free of the square factors found by trial division up to 10⁴
/// (a larger square factor may stay in `d`; the form is still exact).
pub(crate) fn square_split(n: &BigInt) -> (BigInt, BigInt) {
    let mut k = BigInt::one();
    let mut d = n.clone();
    let mut i = BigInt::from(2);
    let limit = BigInt::from(10_000);
    while i <= limit && &i * &i <= d {
        let sq = &i * &i;
        while (&d % &sq).is_zero() {
            d /= &sq;
            k *= &i;
        }
        i += 1;
    }
    let r = d.sqrt();
    if &r * &r == d {
        k *= &r;
        d = BigInt::one();
    }
    (k, d)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn square_factors_come_out() {
        // 72 = 6²·2, 45 = 3²·5, 49 = 7²·1, 7 is square-free; 10007² · 3 has its square factor
        // above the trial bound 10⁴, so it stays in d.
        for (n, k, d) in [
            (72, 6, 2),
            (45, 3, 5),
            (49, 7, 1),
            (7, 1, 7),
            (300_420_147, 1, 300_420_147),
        ] {
            assert_eq!(square_split(&BigInt::from(n)), (k.into(), d.into()), "{n}");
        }
    }
}
