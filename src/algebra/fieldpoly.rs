//! Polynomials and linear algebra over a real number field K = Q(λ), for the exact eigen
//! analysis of operators ([`crate::analysis::operator`]): Euclid, the Schur–Cohn test "every root in the
//! open unit disk", the position of roots relative to the unit circle, null spaces.
//!
//! K is a [`NumberField`] (degree 1 for Q); signs are exact ([`NumberField::sign`]). Written by
//! hand: [`crate::algebra::poly`] works over Q only, and these few routines are all the analysis needs.

use crate::algebra::algebraic::{FieldElement, NumberField, RealAlgebraic};
use crate::algebra::kmatrix::KMatrix;
use crate::algebra::matrix::Matrix;
use crate::algebra::poly::Poly;
use num_rational::BigRational;
use num_traits::{One, Zero};
use std::cmp::Ordering;

/// A polynomial over K, lowest degree first, without trailing zeros.
pub(crate) type KPoly = Vec<FieldElement>;

fn q(n: i64) -> BigRational {
    BigRational::from_integer(n.into())
}

pub(crate) fn trim(mut p: KPoly) -> KPoly {
    while p.last().is_some_and(FieldElement::is_zero) {
        p.pop();
    }
    p
}

pub(crate) fn to_k(k: &NumberField, p: &Poly) -> KPoly {
    trim(p.coeffs().iter().map(|c| k.rational(c.clone())).collect())
}

pub(crate) fn k_eval(k: &NumberField, p: &[FieldElement], x: &FieldElement) -> FieldElement {
    p.iter()
        .rev()
        .fold(k.rational(BigRational::zero()), |acc, c| {
            k.add(&k.mul(&acc, x), c)
        })
}

pub(crate) fn k_monic(k: &NumberField, p: KPoly) -> KPoly {
    let p = trim(p);
    match p.last() {
        None => p,
        Some(lc) => {
            let inv = k.inv(lc).expect("non-zero leading coefficient");
            p.iter().map(|c| k.mul(c, &inv)).collect()
        }
    }
}

/// `(quotient, remainder)` of `a / b`, `b ≠ 0`.
pub(crate) fn k_divrem(k: &NumberField, a: &[FieldElement], b: &[FieldElement]) -> (KPoly, KPoly) {
    let b = trim(b.to_vec());
    let mut r = trim(a.to_vec());
    let db = b.len() - 1;
    let inv = k.inv(&b[db]).expect("non-zero divisor");
    let mut quo = vec![k.rational(BigRational::zero()); r.len().saturating_sub(db).max(1)];
    while r.len() > db && !r.is_empty() {
        let s = r.len() - 1 - db;
        let c = k.mul(&r[r.len() - 1], &inv);
        for (i, bi) in b.iter().enumerate() {
            r[s + i] = k.sub(&r[s + i], &k.mul(&c, bi));
        }
        quo[s] = c;
        r.pop();
        r = trim(r);
    }
    (trim(quo), r)
}

pub(crate) fn k_gcd(k: &NumberField, a: &[FieldElement], b: &[FieldElement]) -> KPoly {
    let (mut a, mut b) = (trim(a.to_vec()), trim(b.to_vec()));
    while !b.is_empty() {
        let (_, r) = k_divrem(k, &a, &b);
        a = b;
        b = r;
    }
    k_monic(k, a)
}

/// `p(c·x)`.
pub(crate) fn k_scale_var(k: &NumberField, p: &[FieldElement], c: &FieldElement) -> KPoly {
    let mut pow = k.rational(BigRational::one());
    let mut out = Vec::with_capacity(p.len());
    for a in p {
        out.push(k.mul(a, &pow));
        pow = k.mul(&pow, c);
    }
    trim(out)
}

/// Schur–Cohn: every root of the real polynomial `p ≠ 0` lies in the open unit disk. With
/// `p*(x) = x^n p(1/x)`, this holds iff `|a_0| < |a_n|` and `(a_n·p − a_0·p*)/x` (degree n − 1)
/// passes the same test (Rouché on the unit circle).
pub(crate) fn inside_unit_disk(k: &NumberField, p: &[FieldElement]) -> bool {
    let mut p = k_monic(k, p.to_vec());
    while p.len() > 1 {
        let n = p.len() - 1;
        let (a0, an) = (&p[0], &p[n]);
        let d = k.sub(&k.mul(an, an), &k.mul(a0, a0));
        if k.sign(&d) != Ordering::Greater {
            return false;
        }
        let next: KPoly = (0..n)
            .map(|i| k.sub(&k.mul(an, &p[i + 1]), &k.mul(a0, &p[n - 1 - i])))
            .collect();
        p = k_monic(k, next);
    }
    true
}

/// Where the roots of a real polynomial lie relative to the unit circle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Position {
    /// Every root strictly inside.
    Inside,
    /// None outside, at least one on the circle.
    OnCircle,
    /// At least one strictly outside.
    Outside,
    /// Not decided by the exact tests implemented.
    Undecided,
}

/// Exact position of the roots of `g` relative to the unit circle. Roots on the circle are roots
/// of `c = gcd(g, g*)` (for real g, |z| = 1 ⇔ 1/z = z̄ is a root); the rest of g is tested by
/// Schur–Cohn; c itself is split into `x ∓ 1` factors and inverse pairs {z, 1/z}, decided by
/// the discriminant when one pair is left (real pair: one root outside; complex: on the circle).
pub(crate) fn circle_position(k: &NumberField, g: &[FieldElement]) -> Position {
    let g = trim(g.to_vec());
    if g.len() <= 1 {
        return Position::Inside;
    }
    let rev: KPoly = g.iter().rev().cloned().collect();
    let c = k_gcd(k, &g, &rev);
    if c.len() <= 1 {
        return if inside_unit_disk(k, &g) {
            Position::Inside
        } else {
            Position::Outside
        };
    }
    let mut rest = g;
    loop {
        let (quo, r) = k_divrem(k, &rest, &c);
        if !r.is_empty() {
            break;
        }
        rest = quo;
    }
    loop {
        let common = k_gcd(k, &rest, &c);
        if common.len() <= 1 {
            break;
        }
        rest = k_divrem(k, &rest, &common).0;
    }
    if !inside_unit_disk(k, &rest) {
        return Position::Outside;
    }
    // Strip x − 1 and x + 1 from c (simple roots of the square-free gcd).
    let mut c = c;
    for s in [1i64, -1] {
        let root = k.rational(q(s));
        if k_eval(k, &c, &root).is_zero() {
            c = k_divrem(k, &c, &[k.rational(q(-s)), k.rational(q(1))]).0;
        }
    }
    match c.len() {
        0 | 1 => Position::OnCircle,
        3 => {
            // x² + b·x + 1 (roots z, 1/z): on the circle iff b² − 4 < 0.
            let c = k_monic(k, c);
            let disc = k.sub(&k.mul(&c[1], &c[1]), &k.rational(q(4)));
            if k.sign(&disc) == Ordering::Less {
                Position::OnCircle
            } else {
                Position::Outside
            }
        }
        _ => Position::Undecided,
    }
}

/// A basis of the null space of the `n × n` matrix `a` over K, each vector scaled so that its last
/// non-zero coordinate is 1.
pub(crate) fn null_space(k: &NumberField, mut a: Vec<Vec<FieldElement>>) -> Vec<Vec<FieldElement>> {
    let rows = a.len();
    let cols = a.first().map_or(0, Vec::len);
    let mut pivots = Vec::new();
    let mut r = 0;
    for c in 0..cols {
        let Some(p) = (r..rows).find(|&i| !a[i][c].is_zero()) else {
            continue;
        };
        a.swap(r, p);
        let inv = k.inv(&a[r][c]).expect("pivot");
        a[r] = a[r].iter().map(|x| k.mul(x, &inv)).collect();
        for i in 0..rows {
            if i != r && !a[i][c].is_zero() {
                let f = a[i][c].clone();
                let row_r = a[r].clone();
                for (x, y) in a[i].iter_mut().zip(&row_r) {
                    *x = k.sub(x, &k.mul(&f, y));
                }
            }
        }
        pivots.push(c);
        r += 1;
        if r == rows {
            break;
        }
    }
    let free: Vec<usize> = (0..cols).filter(|c| !pivots.contains(c)).collect();
    free.iter()
        .map(|&f| {
            let mut v = vec![k.rational(BigRational::zero()); cols];
            v[f] = k.rational(BigRational::one());
            for (i, &pc) in pivots.iter().enumerate() {
                v[pc] = k.sub(&v[pc], &a[i][f]);
            }
            let last = v.iter().rev().find(|x| !x.is_zero()).cloned();
            let inv = k
                .inv(&last.expect("non-zero basis vector"))
                .expect("non-zero");
            v.iter().map(|x| k.mul(x, &inv)).collect()
        })
        .collect()
}

/// The integer data of [`adjugate_eigenvector`] for one matrix `T`, shared by all its
/// eigenvalues: `A = d·T` (d the lcm of the denominators), the monic integer characteristic
/// polynomial `p(x) = d^n·χ(x/d)` of A and, per column j, the chain `w_{n−1} = e_j`,
/// `w_{i−1} = A·w_i + p_i·e_j` (computed on first use). None of it depends on the eigenvalue.
pub(crate) struct AdjugateChains {
    d: num_bigint::BigInt,
    a: Vec<Vec<num_bigint::BigInt>>,
    p: Vec<num_bigint::BigInt>,
    /// Per column, `ws[i] = w_i`.
    chains: Vec<std::cell::OnceCell<Vec<Vec<num_bigint::BigInt>>>>,
}

impl AdjugateChains {
    /// The data of the square matrix `t` with characteristic polynomial `chi`.
    pub(crate) fn new(t: &Matrix, chi: &Poly) -> Self {
        use num_bigint::BigInt;
        let n = t.rows;
        let chi = chi.monic();
        // Over Z: A = d·T has the eigenvalue μ = d·λ; adj(μI − A) = d^(n−1)·adj(λI − T).
        let d = t.data.iter().fold(BigInt::one(), |acc, x| {
            if x.denom().is_one() {
                acc
            } else {
                crate::algebra::intgcd::lcm(&acc, x.denom())
            }
        });
        let scaled = |x: &BigRational| {
            if x.denom().is_one() {
                x.numer() * &d
            } else {
                x.numer() * (&d / x.denom())
            }
        };
        let a: Vec<Vec<BigInt>> = (0..n)
            .map(|i| (0..n).map(|j| scaled(t.get(i, j))).collect())
            .collect();
        // p_i = c_i·d^(n−i), an integer: one exact integer division each.
        let mut dpow = BigInt::one();
        let mut p: Vec<BigInt> = (0..=n)
            .rev()
            .map(|i| {
                let c = chi.coeff(i);
                let x = c.numer() * &dpow / c.denom();
                dpow *= &d;
                x
            })
            .collect();
        p.reverse();
        AdjugateChains {
            d,
            a,
            p,
            chains: (0..n).map(|_| std::cell::OnceCell::new()).collect(),
        }
    }

    /// `ws[i] = w_i` for column `col`.
    fn column(&self, col: usize) -> &[Vec<num_bigint::BigInt>] {
        use num_bigint::BigInt;
        self.chains[col].get_or_init(|| {
            let n = self.a.len();
            let mut w = vec![BigInt::zero(); n];
            w[col] = BigInt::one();
            let mut ws = vec![w.clone()];
            for i in (1..n).rev() {
                let mut next: Vec<BigInt> = self
                    .a
                    .iter()
                    .map(|row| {
                        row.iter()
                            .zip(&w)
                            .filter(|(x, y)| !x.is_zero() && !y.is_zero())
                            .map(|(x, y)| x * y)
                            .sum()
                    })
                    .collect();
                next[col] += &self.p[i];
                ws.push(next.clone());
                w = next;
            }
            ws.reverse();
            ws
        })
    }
}

/// An eigenvector of the rational matrix `t` (whose [`AdjugateChains`] are `chains`, computed
/// once for all its eigenvalues) for an eigenvalue `lambda` ∈ K of geometric
/// multiplicity 1, from a non-zero column of the adjugate `adj(λ·I − T) = Σ_i λ^i·Q_i` with
/// `Q_{n−1} = I`, `Q_{i−1} = T·Q_i + c_i·I` (`χ = Σ c_i x^i` monic; `(x·I − T)·Σ x^i Q_i = χ(x)·I`
/// by Cayley–Hamilton). Column j needs only n rational matrix–vector products; the field enters at
/// the end, in one combination per coordinate. No elimination over K, so no coefficient growth
/// beyond the size of the answer. `None` when every column vanishes (eigenspace of dimension > 1)
/// — the caller then uses [`null_space`]. Scaled so that the last non-zero coordinate is 1 when
/// K has degree ≤ 2; in a field of degree ≥ 3, to coprime integer coordinates on the power basis
/// (normalising would need an inversion in K and make the coordinates much larger).
pub(crate) fn adjugate_eigenvector(
    chains: &AdjugateChains,
    k: &NumberField,
    lambda: &FieldElement,
) -> Option<Vec<FieldElement>> {
    use num_bigint::BigInt;
    let n = chains.a.len();
    let d = &chains.d;
    let dq = BigRational::from_integer(d.clone());
    // Powers 1, μ, …, μ^(n−1) of μ = d·λ in K, for the general case only.
    let pows = std::cell::OnceCell::new();
    let pows = || {
        pows.get_or_init(|| {
            let mu = k.scale(lambda, &dq);
            let mut pows = vec![k.rational(BigRational::one())];
            for i in 1..n {
                pows.push(k.mul(&pows[i - 1], &mu));
            }
            pows
        })
    };
    let gen = is_generator(k, lambda);
    for col in 0..n {
        let ws = chains.column(col);
        if gen && k.degree() >= 3 {
            // Integers only: Σ (w_i)_r·d^i·x^i reduced over Z, then the primitive vector.
            if let Some(v) = primitive_generator_column(k, ws, d) {
                return Some(v);
            }
            continue;
        }
        if let Some(q) = lambda.as_rational() {
            if let Some(v) = rational_column(k, ws, &(q * &dq)) {
                return Some(v);
            }
            continue;
        }
        let v: Vec<FieldElement> = (0..n)
            .map(|r| {
                if gen {
                    // λ the generator: Σ (w_i)_r·d^i·λ^i, reduced modulo the minimal polynomial.
                    let mut dp = BigInt::one();
                    let c: Vec<BigRational> = ws
                        .iter()
                        .map(|x| {
                            let c = BigRational::from_integer(&x[r] * &dp);
                            dp *= d;
                            c
                        })
                        .collect();
                    return k.element(&Poly::new(c));
                }
                ws.iter().zip(pows()).filter(|(x, _)| !x[r].is_zero()).fold(
                    k.rational(BigRational::zero()),
                    |acc, (x, p)| {
                        k.add(&acc, &k.scale(p, &BigRational::from_integer(x[r].clone())))
                    },
                )
            })
            .collect();
        if let Some(last) = v.iter().rev().find(|x| !x.is_zero()) {
            if k.degree() <= 2 {
                let inv = k.inv(last)?;
                return Some(v.iter().map(|x| k.mul(x, &inv)).collect());
            }
            return Some(primitive_vector(k, v));
        }
    }
    None
}

/// The column `Σ_i μ^i·w_i` for a rational `μ = a/b` (b > 0), as the integers
/// `V_r = Σ_i (w_i)_r·a^i·b^(n−1−i)` (a positive multiple), normalised like
/// [`adjugate_eigenvector`]: last non-zero coordinate 1 when K has degree ≤ 2, else coprime
/// integers. One gcd per coordinate instead of one per rational operation. `None` when the column
/// vanishes.
fn rational_column(
    k: &NumberField,
    ws: &[Vec<num_bigint::BigInt>],
    mu: &BigRational,
) -> Option<Vec<FieldElement>> {
    use num_bigint::BigInt;
    let n = ws.len();
    let (a, b) = (mu.numer(), mu.denom());
    let v: Vec<BigInt> = (0..n)
        .map(|r| {
            // Horner on the homogeneous form: ((w_{n−1}·a + w_{n−2}·b)·a + w_{n−3}·b²)…
            let mut acc = BigInt::zero();
            let mut bp = BigInt::one();
            for w in ws.iter().rev() {
                acc = acc * a + &w[r] * &bp;
                bp *= b;
            }
            acc
        })
        .collect();
    let last = v.iter().rev().find(|x| !x.is_zero())?.clone();
    if k.degree() <= 2 {
        return Some(
            v.into_iter()
                .map(|x| k.rational(crate::algebra::intgcd::ratio(x, last.clone())))
                .collect(),
        );
    }
    let g = v.iter().fold(BigInt::zero(), |acc, x| {
        crate::algebra::intgcd::gcd(&acc, x)
    });
    Some(
        v.into_iter()
            .map(|x| k.rational(BigRational::from_integer(x / &g)))
            .collect(),
    )
}

/// The column `Σ_i λ^i·d^i·w_i` for λ the generator of K (degree ≥ 3), each coordinate reduced
/// modulo the minimal polynomial over Z ([`NumberField::reduce_ints`]) and the vector brought to
/// coprime integers on the power basis — the result of [`primitive_vector`], without the rational
/// arithmetic. `None` when the column vanishes.
fn primitive_generator_column(
    k: &NumberField,
    ws: &[Vec<num_bigint::BigInt>],
    d: &num_bigint::BigInt,
) -> Option<Vec<FieldElement>> {
    use num_bigint::BigInt;
    use num_traits::Signed;
    let n = ws.len();
    let rows: Vec<(Vec<BigInt>, BigInt)> = (0..n)
        .map(|r| {
            let mut dp = BigInt::one();
            let c: Vec<BigInt> = ws
                .iter()
                .map(|x| {
                    let c = &x[r] * &dp;
                    dp *= d;
                    c
                })
                .collect();
            let (mut ints, mut den) = k.reduce_ints(c, BigInt::one());
            if den.is_negative() {
                den = -den;
                ints.iter_mut().for_each(|x| *x = -&*x);
            }
            (ints, den)
        })
        .collect();
    if rows.iter().all(|(c, _)| c.iter().all(Zero::is_zero)) {
        return None;
    }
    let common = rows.iter().fold(BigInt::one(), |acc, (_, den)| {
        if &acc == den {
            acc
        } else {
            crate::algebra::intgcd::lcm(&acc, den)
        }
    });
    let mut ints: Vec<Vec<BigInt>> = rows
        .into_iter()
        .map(|(c, den)| {
            if den == common {
                c
            } else {
                let m = &common / &den;
                c.into_iter().map(|x| x * &m).collect()
            }
        })
        .collect();
    let mut g = BigInt::zero();
    for x in ints.iter().flatten() {
        if !x.is_zero() {
            g = crate::algebra::intgcd::gcd(&g, x);
            if g.is_one() {
                break;
            }
        }
    }
    if !g.is_one() {
        ints.iter_mut().flatten().for_each(|x| *x = &*x / &g);
    }
    Some(
        ints.into_iter()
            .map(|c| {
                k.element(&Poly::new(
                    c.into_iter().map(BigRational::from_integer).collect(),
                ))
            })
            .collect(),
    )
}

/// `v` scaled by a positive rational so that every coordinate on the power basis is an integer
/// and the integers have no common factor (an inversion in K would make the vector larger).
fn primitive_vector(k: &NumberField, v: Vec<FieldElement>) -> Vec<FieldElement> {
    let coeffs = v.iter().flat_map(|x| x.coords().iter());
    let den = coeffs.clone().fold(num_bigint::BigInt::one(), |acc, c| {
        crate::algebra::intgcd::lcm(&acc, c.denom())
    });
    let num = coeffs.fold(num_bigint::BigInt::zero(), |acc, c| {
        crate::algebra::intgcd::gcd(&acc, &(c.numer() * (&den / c.denom())))
    });
    if num.is_zero() {
        return v;
    }
    let s = crate::algebra::intgcd::ratio(den, num);
    v.iter().map(|x| k.scale(x, &s)).collect()
}

fn is_generator(k: &NumberField, a: &FieldElement) -> bool {
    k.degree() > 1 && *a == k.generator_element()
}

/// `T − λ·I` over K.
pub(crate) fn shifted(
    k: &NumberField,
    t: &Matrix,
    lambda: &FieldElement,
) -> Vec<Vec<FieldElement>> {
    shifted_entries(
        k,
        t.rows,
        t.cols,
        |i, j| k.rational(t.get(i, j).clone()),
        lambda,
    )
}

/// `T − λ·I` for a matrix over K ([`shifted`] for a rational one).
pub(crate) fn shifted_k(
    k: &NumberField,
    t: &KMatrix,
    lambda: &FieldElement,
) -> Vec<Vec<FieldElement>> {
    shifted_entries(k, t.rows, t.cols, |i, j| t.get(i, j).clone(), lambda)
}

/// The rows of `T − λ·I` for the `rows × cols` matrix whose entry (i, j) is `entry(i, j)`.
fn shifted_entries(
    k: &NumberField,
    rows: usize,
    cols: usize,
    entry: impl Fn(usize, usize) -> FieldElement,
    lambda: &FieldElement,
) -> Vec<Vec<FieldElement>> {
    (0..rows)
        .map(|i| {
            (0..cols)
                .map(|j| {
                    let e = entry(i, j);
                    if i == j {
                        k.sub(&e, lambda)
                    } else {
                        e
                    }
                })
                .collect()
        })
        .collect()
}

/// `T · v` for a rational matrix and a vector over K.
pub(crate) fn apply(k: &NumberField, t: &Matrix, v: &[FieldElement]) -> Vec<FieldElement> {
    (0..t.rows)
        .map(|i| {
            v.iter()
                .enumerate()
                .fold(k.rational(BigRational::zero()), |acc, (j, x)| {
                    k.add(&acc, &k.mul(&k.rational(t.get(i, j).clone()), x))
                })
        })
        .collect()
}

/// The rational field Q as a [`NumberField`] of degree 1.
pub(crate) fn rationals() -> NumberField {
    NumberField::new(RealAlgebraic::rational(BigRational::zero()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn poly(c: &[i64], den: i64) -> Poly {
        Poly::new(
            c.iter()
                .map(|&x| BigRational::new(x.into(), den.into()))
                .collect(),
        )
    }

    #[test]
    fn schur_cohn_on_known_roots() {
        let k = rationals();
        let inside = |p: &Poly| inside_unit_disk(&k, &to_k(&k, p));
        assert!(inside(&poly(&[1, 0, 4], 4))); // x² + 1/4: ±i/2
        assert!(!inside(&poly(&[-1, 1], 1))); // x − 1: on the circle
        assert!(!inside(&poly(&[2, -9, 4], 4))); // (x − 2)(x − 1/4)
        assert!(inside(&poly(&[0, 0, 1], 1))); // x²: 0 twice
    }

    #[test]
    fn circle_positions() {
        let k = rationals();
        let pos = |p: &Poly| circle_position(&k, &to_k(&k, p));
        assert_eq!(pos(&poly(&[1, 0, 1], 1)), Position::OnCircle); // ±i
        assert_eq!(pos(&poly(&[3, -10, 3], 3)), Position::Outside); // 3 and 1/3
        assert_eq!(pos(&poly(&[1, 1], 1)), Position::OnCircle); // −1
        assert_eq!(pos(&poly(&[1, 4], 8)), Position::Inside); // −1/4
        assert_eq!(pos(&poly(&[-1, 0, 0, 1], 1)), Position::OnCircle); // cube roots of 1
    }

    #[test]
    fn all_real_roots_and_null_space() {
        // x³ − 3x + 1 has three real roots (2cos(2π/9), …), ≈ −1.879, 0.347, 1.532.
        let roots = RealAlgebraic::real_roots(&Poly::from_ints(&[1, -3, 0, 1]));
        let d: Vec<String> = roots.iter().map(|r| r.decimal(3)).collect();
        assert_eq!(d, ["-1.879", "0.347", "1.532"]);
        assert!(RealAlgebraic::real_roots(&Poly::from_ints(&[1, 0, 1])).is_empty());
        let k = rationals();
        let a = Matrix::from_rows(vec![
            vec![BigRational::one(), BigRational::one()],
            vec![BigRational::one(), BigRational::one()],
        ]);
        let zero = k.rational(BigRational::zero());
        let ns = null_space(&k, shifted(&k, &a, &zero));
        assert_eq!(ns.len(), 1);
        assert_eq!(ns[0][0].as_rational(), Some(-BigRational::one()));
    }
}
