//! Small dense matrices over Q, for the known operators of an automaton (selection matrices,
//! de Casteljau operators, permutations). Written by hand: the matrices are tiny and only need
//! exact products, so a general linear-algebra crate would add weight without helping.

use num_rational::BigRational;
use num_traits::{One, Zero};
use std::fmt;

/// A dense `rows × cols` matrix of rationals, row-major.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Matrix {
    /// Number of rows.
    pub rows: usize,
    /// Number of columns.
    pub cols: usize,
    /// Entries, row-major.
    pub data: Vec<BigRational>,
}

impl Matrix {
    /// The zero matrix.
    pub fn zeros(rows: usize, cols: usize) -> Self {
        Matrix {
            rows,
            cols,
            data: vec![BigRational::zero(); rows * cols],
        }
    }

    /// The identity.
    pub fn identity(n: usize) -> Self {
        let mut m = Self::zeros(n, n);
        for i in 0..n {
            m.set(i, i, BigRational::one());
        }
        m
    }

    /// The reversal permutation `J` (anti-identity).
    pub fn reversal(n: usize) -> Self {
        let mut m = Self::zeros(n, n);
        for i in 0..n {
            m.set(i, n - 1 - i, BigRational::one());
        }
        m
    }

    /// A `rows × k` selection matrix whose column c is the unit vector `e_{pick[c]}`.
    pub fn selection(rows: usize, pick: &[usize]) -> Self {
        let mut m = Self::zeros(rows, pick.len());
        for (c, &r) in pick.iter().enumerate() {
            m.set(r, c, BigRational::one());
        }
        m
    }

    /// Builds a matrix from rows.
    pub fn from_rows(rows: Vec<Vec<BigRational>>) -> Self {
        let r = rows.len();
        let c = rows.first().map_or(0, Vec::len);
        Matrix {
            rows: r,
            cols: c,
            data: rows.into_iter().flatten().collect(),
        }
    }

    /// Entry (r, c).
    pub fn get(&self, r: usize, c: usize) -> &BigRational {
        &self.data[r * self.cols + c]
    }

    /// Sets entry (r, c).
    pub fn set(&mut self, r: usize, c: usize, v: BigRational) {
        self.data[r * self.cols + c] = v;
    }

    /// The product `self · other`; `None` when the shapes do not match.
    pub fn mul(&self, other: &Matrix) -> Option<Matrix> {
        if self.cols != other.rows {
            return None;
        }
        let mut out = Matrix::zeros(self.rows, other.cols);
        for i in 0..self.rows {
            for k in 0..self.cols {
                let a = self.get(i, k);
                if a.is_zero() {
                    continue;
                }
                for j in 0..other.cols {
                    let b = other.get(k, j);
                    if !b.is_zero() {
                        let v = out.get(i, j) + a * b;
                        out.set(i, j, v);
                    }
                }
            }
        }
        Some(out)
    }

    /// True when every column sums to 1 (the matrix maps points to points).
    pub fn is_barycentric(&self) -> bool {
        (0..self.cols).all(|c| {
            (0..self.rows)
                .map(|r| self.get(r, c))
                .fold(BigRational::zero(), |acc, x| {
                    crate::algebra::intgcd::add(&acc, x)
                })
                .is_one()
        })
    }
}

impl fmt::Display for Matrix {
    /// `[a b; c d]` with exact entries.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("[")?;
        for r in 0..self.rows {
            if r > 0 {
                f.write_str("; ")?;
            }
            let row: Vec<String> = (0..self.cols).map(|c| self.get(r, c).to_string()).collect();
            f.write_str(&row.join(" "))?;
        }
        f.write_str("]")
    }
}

/// The degree-q Bernstein (de Casteljau) operator restricting a Bézier curve to `[a, b]`:
/// column i holds the barycentric coordinates of the i-th control point of the restricted curve
/// in the parent's control points (its blossom at a^(q−i) b^i).
pub fn bezier_restriction(q: usize, a: &BigRational, b: &BigRational) -> Matrix {
    let m = q + 1;
    let mut out = Matrix::zeros(m, m);
    for i in 0..m {
        // de Casteljau on unit vectors with parameters a (q−i times) then b (i times).
        let mut pts: Vec<Vec<BigRational>> = (0..m)
            .map(|j| {
                (0..m)
                    .map(|k| {
                        if j == k {
                            BigRational::one()
                        } else {
                            BigRational::zero()
                        }
                    })
                    .collect()
            })
            .collect();
        for step in 0..q {
            let u = if step < q - i { a } else { b };
            let one_minus = BigRational::one() - u;
            pts = (0..pts.len() - 1)
                .map(|j| {
                    (0..m)
                        .map(|k| &one_minus * &pts[j][k] + u * &pts[j + 1][k])
                        .collect()
                })
                .collect();
        }
        for (k, v) in pts[0].iter().enumerate() {
            out.set(k, i, v.clone());
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(n: i64, d: i64) -> BigRational {
        BigRational::new(n.into(), d.into())
    }

    #[test]
    fn de_casteljau_halves_match_the_spec() {
        // THEORY §6: T_0 = [[1,1/2,1/4],[0,1/2,1/2],[0,0,1/4]], T_1 = [[1/4,0,0],[1/2,1/2,0],[1/4,1/2,1]].
        let t0 = bezier_restriction(2, &q(0, 1), &q(1, 2));
        let t1 = bezier_restriction(2, &q(1, 2), &q(1, 1));
        assert_eq!(t0.to_string(), "[1 1/2 1/4; 0 1/2 1/2; 0 0 1/4]");
        assert_eq!(t1.to_string(), "[1/4 0 0; 1/2 1/2 0; 1/4 1/2 1]");
        assert!(t0.is_barycentric() && t1.is_barycentric());
        // Restricting to [0,1] is the identity.
        assert_eq!(
            bezier_restriction(3, &q(0, 1), &q(1, 1)),
            Matrix::identity(4)
        );
    }

    #[test]
    fn products_and_shapes() {
        let j = Matrix::reversal(3);
        assert_eq!(j.mul(&j).unwrap(), Matrix::identity(3));
        assert!(j.mul(&Matrix::identity(2)).is_none());
        let s = Matrix::selection(3, &[2]);
        assert_eq!(j.mul(&s).unwrap(), Matrix::selection(3, &[0]));
    }
}
