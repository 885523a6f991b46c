//! Operators with entries in a real number field K (Koch's and the arrowhead's rotations, in
//! Q(√3)): the §8 analysis when the characteristic polynomial over K has rational coefficients.
//!
//! **Why that suffices for the class.** The behaviour at the fixed point (sharp, finite, flat,
//! oscillating, spiralling, degenerate) and the contraction depend on the eigenvalues only, that
//! is on `χ_T`. When `χ_T ∈ Q[x]` — the rule for plane similitudes whose rotation has a rational
//! cosine, since a rotation by φ and ratio r gives `x² − 2r·cos φ·x + r²` — the eigenvalues are
//! those of the companion matrix C of `χ_T`, a rational matrix, and the exact analysis of C
//! (`analyse_matrix`) decides the class for T. Everything that depends on T itself is then
//! computed from T over K: the fixed point (the kernel of `T − I`) and the eigenvectors of the
//! rational eigenvalues (the kernel of `T − λI`). An eigenvector of an irrational eigenvalue lies
//! in K(λ), a field lacuna does not build: it is left out, and so are the tangent data that the
//! DCFs and curvature ranges need (a curve of such operators is not read).
//!
//! When `χ_T` has a coefficient outside Q, no analysis is made and the reason is returned.

use super::{analyse_matrix, render_vec, OperatorReport};
use crate::algebra::algebraic::{FieldElement, NumberField};
use crate::algebra::fieldpoly::{null_space, shifted_k};
use crate::algebra::kmatrix::KMatrix;
use crate::algebra::matrix::Matrix;
use crate::error::Result;
use num_rational::BigRational;
use num_traits::{One, Zero};

/// The companion matrix of the monic `x^n + c_(n−1)·x^(n−1) + … + c_0` (coefficients lowest
/// first, the leading 1 included): ones below the diagonal, `−c` in the last column.
fn companion(c: &[BigRational]) -> Matrix {
    let n = c.len() - 1;
    let rows = (0..n)
        .map(|i| {
            (0..n)
                .map(|j| {
                    if j == n - 1 {
                        -c[i].clone()
                    } else if i == j + 1 {
                        BigRational::one()
                    } else {
                        BigRational::zero()
                    }
                })
                .collect()
        })
        .collect();
    Matrix::from_rows(rows)
}

/// `[a b; c d]` with K's entries rendered.
fn render_matrix(k: &NumberField, t: &KMatrix) -> String {
    let rows: Vec<String> = t
        .data
        .chunks(t.cols)
        .map(|row| render_vec(k, row).join(" "))
        .collect();
    format!("[{}]", rows.join("; "))
}

/// The §8 analysis of a square matrix over K (module doc): `Ok(Err(why))` when its
/// characteristic polynomial is not over Q, or the matrix is not square.
pub fn analyse_kmatrix(
    k: &NumberField,
    t: &KMatrix,
) -> Result<std::result::Result<OperatorReport, String>> {
    if t.rows != t.cols || t.rows == 0 {
        return Ok(Err(format!(
            "eigen analysis needs a non-empty square matrix, not {}×{}",
            t.rows, t.cols
        )));
    }
    let chi = t.charpoly(k);
    let Some(coeffs) = chi
        .iter()
        .map(FieldElement::as_rational)
        .collect::<Option<Vec<BigRational>>>()
    else {
        let shown = render_vec(k, &chi);
        return Ok(Err(format!(
            "its characteristic polynomial over the field has coefficients outside Q ({}, lowest degree first): the eigen analysis over a number field covers rational characteristic polynomials only",
            shown.join(", ")
        )));
    };
    let mut r = analyse_matrix(&companion(&coeffs))?;
    r.matrix = render_matrix(k, t);
    r.barycentric = t.is_barycentric(k);
    // Eigenvectors from T over K: rational eigenvalues only.
    for e in &mut r.eigenvalues {
        e.eigenvectors = match e.exact.as_deref().map(str::parse::<BigRational>) {
            Some(Ok(lam)) if e.real => null_space(k, shifted_k(k, t, &k.rational(lam)))
                .iter()
                .map(|v| render_vec(k, v))
                .collect(),
            _ => Vec::new(),
        };
    }
    // The fixed point: the kernel of T − I, scaled to coordinate sum 1.
    r.fixed = None;
    r.fixed_point = None;
    r.fixed_point_note = None;
    let ns = null_space(k, shifted_k(k, t, &k.rational(BigRational::one())));
    match ns.len() {
        0 => r.fixed_point_note = Some("1 is not an eigenvalue: no fixed point".into()),
        1 => {
            let s = ns[0]
                .iter()
                .fold(k.rational(BigRational::zero()), |acc, x| k.add(&acc, x));
            match k.inv(&s) {
                Some(inv) => {
                    let p: Vec<FieldElement> = ns[0].iter().map(|x| k.mul(x, &inv)).collect();
                    r.fixed = p
                        .iter()
                        .map(FieldElement::as_rational)
                        .collect::<Option<Vec<_>>>();
                    r.fixed_point = Some(render_vec(k, &p));
                }
                None => {
                    r.fixed_point_note = Some(
                        "the eigenvector of 1 has coordinate sum 0: it is a direction, not a point"
                            .into(),
                    )
                }
            }
        }
        d => {
            r.fixed_point_note = Some(format!(
                "the eigenspace of 1 has dimension {d}: the fixed point is not unique"
            ))
        }
    }
    // The tangent: v1 over K when λ1 is rational; the exact tangent data (Q(λ1)) is not built.
    r.tangent = match r.lambda1.as_deref().map(str::parse::<BigRational>) {
        Some(Ok(l1)) => null_space(k, shifted_k(k, t, &k.rational(l1)))
            .first()
            .map(|v| render_vec(k, v)),
        _ => None,
    };
    r.exact = None;
    Ok(Ok(r))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::algebraic::RealAlgebraic;
    use crate::algebra::poly::Poly;

    fn sqrt3() -> NumberField {
        // √3: the largest root of x² − 3.
        NumberField::new(RealAlgebraic::largest_root(&Poly::from_ints(&[-3, 0, 1])).unwrap())
    }

    #[test]
    fn a_rotation_by_sixty_degrees_spirals_and_fixes_its_centre() {
        // The Koch map z ↦ e^(iπ/3)·z/3 + 1/3 in barycentric coordinates of (0, 0), (1, 0),
        // (0, 1): its linear part has trace 2·(1/3)·cos(π/3) = 1/3 and determinant 1/9, so
        // χ = (x − 1)(x² − x/3 + 1/9), rational though the entries hold √3/6. The pair
        // (1 ± i√3)/6 has modulus 1/3 and no real eigenvalue but 1: spiralling. The fixed point
        // z = 1/3 / (1 − e^(iπ/3)/3) = (5 + √3·i)/14 by hand (multiply by the conjugate
        // 1 − e^(−iπ/3)/3: |1 − e^(iπ/3)/3|² = 1 − 1/3 + 1/9 = 7/9, and
        // (1/3)(1 − (1/2 − i√3/2)/3) = (1/3)(5/6 + i√3/6)), so (x, y) = (5/14, √3/14) and the
        // barycentric point (1 − x − y, x, y).
        let k = sqrt3();
        let s = k.generator_element();
        let q = |n: i64, d: i64| k.rational(BigRational::new(n.into(), d.into()));
        let s6 = k.mul(&s, &q(1, 6));
        // Columns: images of (0,0), (1,0), (0,1): f(0) = (1/3, 0); f(1) = (1/3 + 1/6, √3/6);
        // f(i) = (1/3 − √3/6, 1/6); each as (1 − x − y, x, y).
        let col = |x: FieldElement, y: FieldElement| {
            let one = q(1, 1);
            vec![k.sub(&k.sub(&one, &x), &y), x, y]
        };
        let c0 = col(q(1, 3), q(0, 1));
        let c1 = col(q(1, 2), s6.clone());
        let c2 = col(k.sub(&q(1, 3), &s6), q(1, 6));
        let mut t = KMatrix::zeros(&k, 3, 3);
        for (j, c) in [c0, c1, c2].into_iter().enumerate() {
            for (i, x) in c.into_iter().enumerate() {
                t.data[i * 3 + j] = x;
            }
        }
        let r = analyse_kmatrix(&k, &t).unwrap().unwrap();
        assert_eq!(r.behaviour.label(), "spiralling", "{r:?}");
        assert!(r.contractive && r.barycentric);
        let x = q(5, 14);
        let y = k.mul(&s, &q(1, 14));
        let want: Vec<String> = [k.sub(&k.sub(&q(1, 1), &x), &y), x, y]
            .iter()
            .map(|e| k.render(e))
            .collect();
        assert_eq!(r.fixed_point.as_ref(), Some(&want));
    }

    #[test]
    fn an_irrational_characteristic_polynomial_is_refused_with_its_reason() {
        // diag(1, √3/3, 1/2): χ has the coefficient −√3/3 − … outside Q.
        let k = sqrt3();
        let s = k.generator_element();
        let mut t = KMatrix::identity(&k, 3);
        t.data[4] = k.mul(&s, &k.rational(BigRational::new(1.into(), 3.into())));
        t.data[8] = k.rational(BigRational::new(1.into(), 2.into()));
        let why = analyse_kmatrix(&k, &t).unwrap().unwrap_err();
        assert!(why.contains("outside Q"), "{why}");
    }
}
