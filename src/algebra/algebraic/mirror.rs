//! `−x` for a real root as [`RealAlgebraic::real_roots`] isolated it, without isolating the roots
//! of `f(−x)` again.
//!
//! `real_roots(f(−x))` mirrors `real_roots(f)` interval for interval: both start from the same
//! Cauchy bound (the same largest coefficient and leading coefficient up to sign), the midpoint
//! of `(−b, −a)` is minus that of `(a, b)`, and Descartes' bound of `f(−x)` on `(−b, −a)` counts
//! the sign variations of the reversed transform of `f` on `(a, b)` (substitute `x ↦ 1/x`), which
//! are the same. So the root `−r` gets exactly the interval `(−hi, −lo)` and the minimal
//! polynomial `f(−x)` made monic, as the isolation of `f(−x)` would give it.

use super::RealAlgebraic;
use crate::algebra::poly::Poly;

impl RealAlgebraic {
    /// `−self`, for a value exactly as [`RealAlgebraic::real_roots`] returned it (its interval
    /// not refined since): the same number, polynomial and interval as isolating the roots of
    /// `f(−x)` would produce (module documentation), at the cost of a copy.
    pub(crate) fn negated_isolated(&self) -> Self {
        let reflected = self
            .min_poly
            .coeffs()
            .iter()
            .enumerate()
            .map(|(i, c)| if i % 2 == 1 { -c } else { c.clone() })
            .collect();
        RealAlgebraic {
            min_poly: Poly::new(reflected).monic(),
            lo: -&self.hi,
            hi: -&self.lo,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::factor::factor;
    use proptest::prelude::*;

    /// The isolation of `f(−x)`, from scratch: the slow path the mirror replaces.
    fn isolated_again(r: &RealAlgebraic) -> RealAlgebraic {
        let f = r.min_poly();
        let roots = RealAlgebraic::real_roots(f);
        let i = roots
            .iter()
            .position(|x| x.interval() == r.interval())
            .expect("r as isolated");
        let reflected = Poly::new(
            f.coeffs()
                .iter()
                .enumerate()
                .map(|(i, c)| if i % 2 == 1 { -c } else { c.clone() })
                .collect(),
        );
        let mut mirrored = RealAlgebraic::real_roots(&reflected);
        mirrored.swap_remove(roots.len() - 1 - i)
    }

    fn same(a: &RealAlgebraic, b: &RealAlgebraic) -> bool {
        a.min_poly() == b.min_poly() && a.interval() == b.interval()
    }

    #[test]
    fn mirrors_a_known_isolation() {
        // x³ − 3x + 1: three real roots; x − 5/2: a rational one.
        for f in [Poly::from_ints(&[1, -3, 0, 1]), Poly::from_ints(&[-5, 2])] {
            for r in RealAlgebraic::real_roots(&f) {
                assert!(same(&r.negated_isolated(), &isolated_again(&r)));
            }
        }
    }

    proptest! {
        /// The mirrored interval is the one a fresh isolation of `f(−x)` gives, for every real
        /// root of every irreducible factor of random integer polynomials.
        #[test]
        fn mirror_is_the_fresh_isolation(c in prop::collection::vec(-30i64..=30, 2..=9)) {
            let p = Poly::from_ints(&c);
            prop_assume!(p.deg() >= 1);
            for (g, _) in factor(&p).expect("small") {
                for r in RealAlgebraic::real_roots(&g) {
                    prop_assert!(same(&r.negated_isolated(), &isolated_again(&r)));
                }
            }
        }
    }
}
