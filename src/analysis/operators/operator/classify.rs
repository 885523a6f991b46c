//! The §8 case analysis at the fixed point, exact: which eigenvalue dominates after 1 (a real λ1,
//! a negative one, a complex pair), and in the tangent case the class of α = log|λ2| / log λ1 by
//! comparing the other moduli with λ1², equalities recognised exactly in Q(λ1).

use super::{eigenvector_in, q, Behaviour, ComplexFactor, CurvatureClass, RealRoot, TangentData};
use crate::algebra::algebraic::{NumberField, RealAlgebraic};
use crate::algebra::fieldpoly::{
    circle_position, inside_unit_disk, k_divrem, k_eval, k_scale_var, to_k, AdjugateChains,
    Position,
};
use crate::algebra::matrix::Matrix;
use crate::algebra::poly::Poly;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
use std::cmp::Ordering;

/// An enclosure `[lo, hi]` of `|r|`, refined to width `w` (`lo ≥ 0`).
fn abs_enclosure(r: &mut RealAlgebraic, w: &BigRational) -> (BigRational, BigRational) {
    r.refine_to(w);
    let (lo, hi) = r.interval();
    let (lo, hi) = if lo.is_negative() && hi.is_positive() {
        (BigRational::zero(), lo.abs().max(hi.abs()))
    } else if hi.is_positive() || hi.is_zero() && lo.is_zero() {
        (lo.clone(), hi.clone())
    } else {
        (hi.abs(), lo.abs())
    };
    (lo.max(BigRational::zero()), hi)
}

/// Exact comparison of `|mu|` with `lambda1²` (λ1 > 0): interval refinement separates distinct
/// numbers; equality is recognised exactly — `g(±λ1²) = 0` in Q(λ1) for the minimal polynomial
/// g of μ, and the enclosure of ±λ1² inside μ's isolating interval (g has one root there).
/// Returns the ordering and, on equality, the sign of μ.
pub(crate) fn cmp_abs_with_square(
    mu: &RealAlgebraic,
    lambda1: &RealAlgebraic,
    k: &NumberField,
) -> Ordering {
    let mu_neg = mu.cmp_exact(&RealAlgebraic::rational(BigRational::zero())) == Ordering::Less;
    if let Some(l) = lambda1.as_rational() {
        let sq = l * l;
        let target = RealAlgebraic::rational(if mu_neg { -sq } else { sq });
        let c = mu.cmp_exact(&target);
        return if mu_neg { c.reverse() } else { c };
    }
    let (mut m, mut l) = (mu.clone(), lambda1.clone());
    let mut w = BigRational::new(1.into(), (1u64 << 40).into());
    let mut equal_checked = false;
    for round in 0.. {
        let (mlo, mhi) = abs_enclosure(&mut m, &w);
        l.refine_to(&w);
        let (llo, lhi) = l.interval();
        let (slo, shi) = (llo.max(&BigRational::zero()).clone(), lhi.clone());
        let (slo, shi) = (&slo * &slo, &shi * &shi);
        if mhi < slo {
            return Ordering::Less;
        }
        if mlo > shi {
            return Ordering::Greater;
        }
        if round >= 2 && !equal_checked {
            equal_checked = true;
            let s = if mu_neg { q(-1) } else { q(1) };
            let g = k_eval(
                k,
                &to_k(k, mu.min_poly()),
                &k.scale(&k.mul(&k.generator_element(), &k.generator_element()), &s),
            );
            if g.is_zero() && mu.degree() == 1 {
                return Ordering::Equal;
            }
            if g.is_zero() {
                // ±λ1² is a root of g: it is μ iff its enclosure falls in μ's isolating interval.
                loop {
                    let (ilo, ihi) = m.interval();
                    let (ilo, ihi) = (ilo.clone(), ihi.clone());
                    l.refine_to(&w);
                    let (llo, lhi) = l.interval();
                    let (a, b) = (llo * llo * &s, lhi * lhi * &s);
                    let (a, b) = if a <= b { (a, b) } else { (b, a) };
                    if ilo < a && b < ihi {
                        return Ordering::Equal;
                    }
                    if b < ilo || ihi < a {
                        break;
                    }
                    w = &w / q(1 << 20);
                }
            }
        }
        w = &w / q(1 << 20);
    }
    unreachable!("the loop returns")
}

/// `f(−x)`.
fn reflect(f: &Poly) -> Poly {
    Poly::new(
        f.coeffs()
            .iter()
            .enumerate()
            .map(|(i, c)| if i % 2 == 1 { -c } else { c.clone() })
            .collect(),
    )
}

/// The §8 case analysis, exact. Returns the behaviour and, in the tangent case, λ1 and v1.
///
/// Moduli are compared first by enclosures — isolating intervals of the real eigenvalues and the
/// certified disks of the complex ones — which decide every strict inequality; equalities of
/// real eigenvalues (λ2 = ±λ1²) are recognised exactly in Q(λ1). Only when a complex disk cannot
/// be separated from the circle in question does the analysis fall back to the exact tests over
/// Q(ρ) (Schur–Cohn, gcd with the reciprocal polynomial).
pub(super) fn classify(
    t: &Matrix,
    chi: &Poly,
    chains: &AdjugateChains,
    mult_one: usize,
    reals: &[RealRoot],
    complex: &[ComplexFactor],
) -> (Behaviour, Option<TangentData>) {
    let degenerate = |detail: String| (Behaviour::Degenerate { detail }, None);
    if mult_one == 0 {
        return degenerate("1 is not an eigenvalue".into());
    }
    if mult_one > 1 {
        return degenerate(format!("1 is an eigenvalue of multiplicity {mult_one}"));
    }
    if t.rows == 1 {
        return degenerate("a 1×1 operator: its attractor is a point".into());
    }
    let zero = RealAlgebraic::rational(BigRational::zero());
    let one = RealAlgebraic::rational(BigRational::one());
    // Largest positive root, and the largest |r| over negative roots, with multiplicities.
    let mut pos: Option<(RealAlgebraic, usize)> = None;
    let mut neg: Option<(RealAlgebraic, usize)> = None;
    for r in reals {
        if r.value.cmp_exact(&one) == Ordering::Equal {
            continue;
        }
        match r.value.cmp_exact(&zero) {
            Ordering::Greater => {
                if pos
                    .as_ref()
                    .is_none_or(|(p, _)| r.value.cmp_exact(p) == Ordering::Greater)
                {
                    pos = Some((r.value.clone(), r.mult));
                }
            }
            Ordering::Less => {
                // `reals` hold the roots exactly as isolated (see `RealRoot`): mirror them.
                let a = r.value.negated_isolated();
                if neg
                    .as_ref()
                    .is_none_or(|(p, _)| a.cmp_exact(p) == Ordering::Greater)
                {
                    neg = Some((a, r.mult));
                }
            }
            Ordering::Equal => {}
        }
    }
    let (rho, rho_pos, rho_neg) = match (&pos, &neg) {
        (None, None) => {
            return if complex.is_empty() {
                degenerate(
                    "every eigenvalue but 1 is 0: the operator collapses onto its fixed point"
                        .into(),
                )
            } else {
                (
                    Behaviour::Spiralling {
                        detail: "every eigenvalue but 1 and 0 is complex".into(),
                    },
                    None,
                )
            };
        }
        (Some((p, _)), None) => (p.clone(), true, false),
        (None, Some((n, _))) => (n.clone(), false, true),
        (Some((p, _)), Some((n, _))) => match p.cmp_exact(n) {
            Ordering::Greater => (p.clone(), true, false),
            Ordering::Less => (n.clone(), false, true),
            Ordering::Equal => (p.clone(), true, true),
        },
    };
    let k = NumberField::new(rho.clone());
    let rho_k = k.generator_element();
    // Does a complex pair reach modulus ρ? Disks first; else Schur–Cohn on f(ρ·x) over Q(ρ)
    // with its roots ±1 removed.
    for c in complex {
        let fast = c.upper.as_ref().and_then(|d| {
            let mut r = rho.clone();
            let mut reach = false;
            for x in d {
                let mut decided = None;
                for digits in [40u32, 80, 160] {
                    r.refine_to(&BigRational::new(1.into(), BigInt::from(2).pow(digits)));
                    let (lo, hi) = r.interval();
                    if let Some(o) = x.cmp_modulus(lo, hi) {
                        decided = Some(o);
                        break;
                    }
                }
                match decided? {
                    Ordering::Less => {}
                    _ => reach = true,
                }
            }
            Some(reach)
        });
        let reach = fast.unwrap_or_else(|| {
            let mut g = k_scale_var(&k, &to_k(&k, &c.poly), &rho_k);
            for s in [1i64, -1] {
                if k_eval(&k, &g, &k.rational(q(s))).is_zero() {
                    g = k_divrem(&k, &g, &[k.rational(q(-s)), k.rational(q(1))]).0;
                }
            }
            !inside_unit_disk(&k, &g)
        });
        if reach {
            return (
                Behaviour::Spiralling {
                    detail: format!(
                        "a complex pair (roots of {}) has modulus at least {}, the largest real modulus",
                        short_poly(&c.poly),
                        short_number(&rho)
                    ),
                },
                None,
            );
        }
    }
    if rho_neg {
        let rho = short_number(&rho);
        let detail = if rho_pos {
            format!("both {rho} and -({rho}) are eigenvalues of largest modulus")
        } else {
            format!("the largest other modulus belongs to the negative eigenvalue -({rho})")
        };
        return (Behaviour::Oscillating { detail }, None);
    }
    let mult = pos.as_ref().map_or(1, |(_, m)| *m);
    if mult > 1 {
        return degenerate(format!("λ1 = {rho} is repeated (multiplicity {mult})"));
    }
    if rho.cmp_exact(&one) != Ordering::Less {
        return degenerate(format!("λ1 = {rho} is not below 1: not contractive"));
    }
    // Tangent case: λ1 = ρ simple and strictly dominant. v1 over Q(λ1).
    let v1 = eigenvector_in(&k, t, chains, &rho_k).expect("a simple eigenvalue has an eigenvector");
    let r2 = k.mul(&rho_k, &rho_k);
    // The other eigenvalues against the circle of radius λ1².
    let mut outside = false;
    let mut on_circle = false;
    let mut which: Vec<&str> = Vec::new();
    let mut others = 0usize;
    for r in reals {
        if r.value.cmp_exact(&one) == Ordering::Equal || r.value.cmp_exact(&rho) == Ordering::Equal
        {
            continue;
        }
        others += 1;
        match cmp_abs_with_square(&r.value, &rho, &k) {
            Ordering::Greater => outside = true,
            Ordering::Equal => {
                on_circle = true;
                let neg = r.value.cmp_exact(&zero) == Ordering::Less;
                let w = if neg { "-λ1²" } else { "λ1²" };
                if !which.contains(&w) {
                    which.push(w);
                }
            }
            Ordering::Less => {}
        }
    }
    let mut fallback = false;
    let mut complex_on_circle = false;
    if !complex.is_empty() {
        others += 1;
        let mut sq = rho.clone();
        for c in complex {
            let Some(d) = &c.upper else {
                fallback = true;
                break;
            };
            for x in d {
                let mut decided = None;
                for digits in [40u32, 80, 160] {
                    sq.refine_to(&BigRational::new(1.into(), BigInt::from(2).pow(digits)));
                    let (lo, hi) = sq.interval();
                    let lo = lo.max(&BigRational::zero()).clone();
                    let (lo, hi) = (&lo * &lo, hi * hi);
                    if let Some(o) = x.cmp_modulus(&lo, &hi) {
                        decided = Some(o);
                        break;
                    }
                }
                match decided {
                    Some(Ordering::Greater) => outside = true,
                    Some(_) => {}
                    None => fallback = true,
                }
            }
        }
    }
    let class = if outside {
        CurvatureClass::Sharp
    } else if fallback {
        // A complex pair too close to the circle |z| = λ1² for the disks: the exact test on
        // g(x) = h2(λ1²·x), h2 = χ / ((x − 1)(x − λ1)), over Q(λ1).
        let h = chi
            .exact_div(&Poly::from_ints(&[-1, 1]))
            .expect("1 is a root");
        let (h2, _) = k_divrem(
            &k,
            &to_k(&k, &h),
            &[
                k.sub(&k.rational(BigRational::zero()), &rho_k),
                k.rational(q(1)),
            ],
        );
        let g = k_scale_var(&k, &h2, &r2);
        match circle_position(&k, &g) {
            Position::Inside => CurvatureClass::Flat,
            Position::OnCircle => {
                complex_on_circle = !on_circle;
                CurvatureClass::Finite
            }
            Position::Outside => CurvatureClass::Sharp,
            Position::Undecided => CurvatureClass::Undecided,
        }
    } else if on_circle {
        CurvatureClass::Finite
    } else {
        CurvatureClass::Flat
    };
    // λ2 = ±λ1² real: keep it and its eigenvector for dyadic points and curvature.
    let mut second = None;
    for w in &which {
        let s = if *w == "λ1²" { q(1) } else { q(-1) };
        let l2 = k.scale(&r2, &s);
        let multiple = reals
            .iter()
            .any(|r| r.mult > 1 && cmp_abs_with_square(&r.value, &rho, &k) == Ordering::Equal);
        if second.is_none() && !multiple {
            if let Some(v) = eigenvector_in(&k, t, chains, &l2) {
                second = Some((l2, v));
            }
        }
    }
    let detail = if others == 0 {
        "no eigenvalue besides 1 and λ1: the curve is straight at its fixed point".to_string()
    } else {
        match class {
            CurvatureClass::Flat => "every other eigenvalue has modulus < λ1² (α > 2)".to_string(),
            CurvatureClass::Sharp => "an eigenvalue has modulus > λ1² (α < 2)".to_string(),
            CurvatureClass::Finite if which.is_empty() || complex_on_circle && which.is_empty() => {
                "a complex pair has modulus exactly λ1² and none exceeds it (α = 2)".to_string()
            }
            CurvatureClass::Finite => format!(
                "λ2 = {} and no eigenvalue exceeds λ1² in modulus (α = 2)",
                which.join(" and ")
            ),
            CurvatureClass::Undecided => {
                "several eigenvalues of modulus λ1² related by inversion: not decided".to_string()
            }
        }
    };
    (
        Behaviour::Tangent { class, detail },
        Some(TangentData {
            field: k,
            lambda1: rho,
            v1,
            second,
        }),
    )
}

/// The polynomial, or `a factor of degree d` when it is long.
fn short_poly(p: &Poly) -> String {
    let s = p.to_string();
    if s.chars().count() <= 60 {
        s
    } else {
        format!("an irreducible factor of degree {}", p.deg())
    }
}

/// The exact form, or `≈ decimal (degree d)` when it is long.
fn short_number(r: &RealAlgebraic) -> String {
    let s = r.to_string();
    if s.chars().count() <= 60 {
        s
    } else {
        format!("≈ {} (degree {})", r.decimal(12), r.degree())
    }
}

/// `−r`: the root of `f(−x)` (f the minimal polynomial of r) mirroring r — real roots come in
/// opposite order.
pub(crate) fn negate(r: &RealAlgebraic) -> RealAlgebraic {
    let f = r.min_poly();
    let roots = RealAlgebraic::real_roots(f);
    let i = roots
        .iter()
        .position(|x| x.cmp_exact(r) == Ordering::Equal)
        .expect("r is a root of its minimal polynomial");
    let mut mirrored = RealAlgebraic::real_roots(&reflect(f));
    mirrored.swap_remove(roots.len() - 1 - i)
}
