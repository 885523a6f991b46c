//! Small dense matrices over a real number field K = Q(α) ([`NumberField`]): the operators of an
//! automaton whose entries are declared in a field (`field s = root of … in […]`), their products,
//! and their characteristic polynomials (Faddeev–LeVerrier, exact in characteristic 0).

use crate::algebra::algebraic::{FieldElement, NumberField};
use crate::algebra::matrix::Matrix;
use num_rational::BigRational;
use num_traits::{One, Zero};

/// A dense `rows × cols` matrix of field elements, row-major.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct KMatrix {
    /// Number of rows.
    pub rows: usize,
    /// Number of columns.
    pub cols: usize,
    /// Entries, row-major.
    pub data: Vec<FieldElement>,
}

impl KMatrix {
    /// The zero matrix.
    pub fn zeros(k: &NumberField, rows: usize, cols: usize) -> Self {
        KMatrix {
            rows,
            cols,
            data: vec![k.rational(BigRational::zero()); rows * cols],
        }
    }

    /// The identity.
    pub fn identity(k: &NumberField, n: usize) -> Self {
        let mut m = Self::zeros(k, n, n);
        for i in 0..n {
            m.data[i * n + i] = k.rational(BigRational::one());
        }
        m
    }

    /// A rational matrix as a matrix over K.
    pub fn from_rational(k: &NumberField, m: &Matrix) -> Self {
        KMatrix {
            rows: m.rows,
            cols: m.cols,
            data: m.data.iter().map(|v| k.rational(v.clone())).collect(),
        }
    }

    /// Entry (r, c).
    pub fn get(&self, r: usize, c: usize) -> &FieldElement {
        &self.data[r * self.cols + c]
    }

    /// The product `self · other`, `None` when the shapes do not chain.
    pub fn mul(&self, k: &NumberField, other: &KMatrix) -> Option<KMatrix> {
        if self.cols != other.rows {
            return None;
        }
        let mut out = KMatrix::zeros(k, self.rows, other.cols);
        for r in 0..self.rows {
            for i in 0..self.cols {
                let a = self.get(r, i);
                if a.is_zero() {
                    continue;
                }
                for c in 0..other.cols {
                    let b = other.get(i, c);
                    if b.is_zero() {
                        continue;
                    }
                    let idx = r * other.cols + c;
                    out.data[idx] = k.add(&out.data[idx], &k.mul(a, b));
                }
            }
        }
        Some(out)
    }

    /// The transpose.
    pub fn transpose(&self) -> KMatrix {
        let mut data = Vec::with_capacity(self.data.len());
        for c in 0..self.cols {
            for r in 0..self.rows {
                data.push(self.get(r, c).clone());
            }
        }
        KMatrix {
            rows: self.cols,
            cols: self.rows,
            data,
        }
    }

    /// Whether every column sums to 1.
    pub fn is_barycentric(&self, k: &NumberField) -> bool {
        (0..self.cols).all(|c| {
            let s = (0..self.rows).fold(k.rational(BigRational::zero()), |acc, r| {
                k.add(&acc, self.get(r, c))
            });
            s == k.rational(BigRational::one())
        })
    }

    /// The characteristic polynomial `det(x·I − A)` of a square matrix, lowest degree first
    /// (monic of degree n), by Faddeev–LeVerrier: `M_0 = 0`, `M_k = A·M_(k−1) + c_(n−k+1)·I`,
    /// `c_(n−k) = −tr(A·M_k)/k`.
    pub fn charpoly(&self, k: &NumberField) -> Vec<FieldElement> {
        let n = self.rows;
        let mut c = vec![k.rational(BigRational::zero()); n + 1];
        c[n] = k.rational(BigRational::one());
        let mut m = KMatrix::zeros(k, n, n);
        for step in 1..=n {
            let am = self.mul(k, &m).expect("square");
            let mut mk = am;
            for i in 0..n {
                let idx = i * n + i;
                mk.data[idx] = k.add(&mk.data[idx], &c[n - step + 1]);
            }
            let amk = self.mul(k, &mk).expect("square");
            let tr = (0..n).fold(k.rational(BigRational::zero()), |acc, i| {
                k.add(&acc, amk.get(i, i))
            });
            let f = k.rational(BigRational::new((-1).into(), (step as i64).into()));
            c[n - step] = k.mul(&tr, &f);
            m = mk;
        }
        c
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::algebraic::RealAlgebraic;

    fn q(n: i64, d: i64) -> BigRational {
        BigRational::new(n.into(), d.into())
    }

    #[test]
    fn charpoly_of_chaikin() {
        // T_0 = [3/4 1/4 0; 1/4 3/4 3/4; 0 0 1/4]: eigenvalues 1, 1/2, 1/4, so the characteristic
        // polynomial is (x − 1)(x − 1/2)(x − 1/4) = x³ − 7/4 x² + 7/8 x − 1/8.
        let k = NumberField::new(RealAlgebraic::rational(q(0, 1)));
        let m = Matrix::from_rows(vec![
            vec![q(3, 4), q(1, 4), q(0, 1)],
            vec![q(1, 4), q(3, 4), q(3, 4)],
            vec![q(0, 1), q(0, 1), q(1, 4)],
        ]);
        let p = KMatrix::from_rational(&k, &m).charpoly(&k);
        let want = [q(-1, 8), q(7, 8), q(-7, 4), q(1, 1)];
        for (a, b) in p.iter().zip(want) {
            assert_eq!(a.as_rational().unwrap(), b);
        }
    }
}
