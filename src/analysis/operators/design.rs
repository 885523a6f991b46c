//! Inverse design (THEORY §8): an operator `T = V·D·V⁻¹` built exactly over Q from chosen
//! eigenvalues and eigenvectors, and checked against the constraints of an automaton.
//!
//! A designer picks λ0 = 1 with the fixed point, λ1 with the tangent v1 and λ2 with v2 — the
//! curvature class follows from |λ2| against λ1² — and gets either a barycentric operator or the
//! precise reason why not ([`DesignError`]). [`check_design`] plugs the operator into an
//! automaton: every constraint whose words involve only it and known operators is evaluated
//! exactly, and the whole system is re-solved with the operator fixed.

use crate::algebra::matrix::Matrix;
use crate::analysis::operators::operator::op_error;
use crate::constraint::automaton::{solve_automaton, Automaton, Factor};
use crate::error::{Error, Result};
use num_rational::BigRational;
use num_traits::{One, Zero};
use serde::Serialize;

/// Why a design is not a valid operator.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum DesignError {
    /// Not one eigenvector per eigenvalue, or vectors of the wrong length (E0906).
    #[error("{what}")]
    Shape {
        /// What does not match.
        what: String,
    },
    /// 1 is not among the eigenvalues: no fixed point (E0907).
    #[error("1 is not among the eigenvalues: the operator would have no fixed point")]
    NoEigenvalueOne,
    /// An eigenvector of an eigenvalue λ ≠ 1 does not have coordinate sum 0, so `T` would not
    /// be barycentric (1ᵀ·T = 1ᵀ forces 1ᵀ·v = 0 when T·v = λ·v, λ ≠ 1) (E0908).
    #[error("eigenvector {index} (eigenvalue {eigenvalue}) has coordinate sum {sum}: it must be 0 for a barycentric operator (a direction, not a point)")]
    NotBarycentric {
        /// Index of the eigenvector (0-based, in the order given).
        index: usize,
        /// Its eigenvalue.
        eigenvalue: String,
        /// Its coordinate sum.
        sum: String,
    },
    /// The eigenvectors are linearly dependent: V is singular (E0909).
    #[error("V is singular: eigenvector {index} is a linear combination of the ones before it")]
    Singular {
        /// The first dependent eigenvector (0-based).
        index: usize,
    },
    /// The operator to check is not in the automaton, or has another shape (E0910).
    #[error("{what}")]
    Operator {
        /// What is wrong.
        what: String,
    },
}

impl DesignError {
    /// The stable error code.
    pub fn code(&self) -> &'static str {
        match self {
            DesignError::Shape { .. } => "E0906",
            DesignError::NoEigenvalueOne => "E0907",
            DesignError::NotBarycentric { .. } => "E0908",
            DesignError::Singular { .. } => "E0909",
            DesignError::Operator { .. } => "E0910",
        }
    }
}

impl From<DesignError> for Error {
    fn from(e: DesignError) -> Self {
        op_error(e.code(), e.to_string())
    }
}

/// The first vector (index) that is a combination of the previous ones, by elimination over Q.
fn first_dependent(vectors: &[Vec<BigRational>]) -> Option<usize> {
    let mut basis: Vec<(usize, Vec<BigRational>)> = Vec::new();
    for (idx, v) in vectors.iter().enumerate() {
        let mut w = v.clone();
        for (p, b) in &basis {
            if !w[*p].is_zero() {
                let f = w[*p].clone() / &b[*p];
                for (x, y) in w.iter_mut().zip(b) {
                    *x -= &f * y;
                }
            }
        }
        match w.iter().position(|x| !x.is_zero()) {
            Some(p) => basis.push((p, w)),
            None => return Some(idx),
        }
    }
    None
}

/// The inverse of an invertible square matrix over Q (Gauss–Jordan).
fn inverse(m: &Matrix) -> Option<Matrix> {
    let n = m.rows;
    let mut a: Vec<Vec<BigRational>> = (0..n)
        .map(|i| {
            (0..n)
                .map(|j| m.get(i, j).clone())
                .chain((0..n).map(|j| {
                    if i == j {
                        BigRational::one()
                    } else {
                        BigRational::zero()
                    }
                }))
                .collect()
        })
        .collect();
    for c in 0..n {
        let p = (c..n).find(|&i| !a[i][c].is_zero())?;
        a.swap(c, p);
        let inv = BigRational::one() / &a[c][c];
        a[c] = a[c].iter().map(|x| x * &inv).collect();
        for i in 0..n {
            if i != c && !a[i][c].is_zero() {
                let f = a[i][c].clone();
                let row = a[c].clone();
                for (x, y) in a[i].iter_mut().zip(&row) {
                    *x -= &f * y;
                }
            }
        }
    }
    Some(Matrix::from_rows(
        a.into_iter().map(|r| r[n..].to_vec()).collect(),
    ))
}

/// `T = V·D·V⁻¹` with `D = diag(eigenvalues)` and the columns of V the given eigenvectors (one
/// per eigenvalue, in order), exactly over Q. Requires 1 among the eigenvalues, every other
/// eigenvector with coordinate sum 0 (so that T is barycentric) and independent eigenvectors.
pub fn design_operator(
    eigenvalues: &[BigRational],
    eigenvectors: &[Vec<BigRational>],
) -> std::result::Result<Matrix, DesignError> {
    let n = eigenvalues.len();
    if n == 0 || eigenvectors.len() != n {
        return Err(DesignError::Shape {
            what: format!(
                "{n} eigenvalues but {} eigenvectors (one per eigenvalue, at least one)",
                eigenvectors.len()
            ),
        });
    }
    if let Some((i, v)) = eigenvectors.iter().enumerate().find(|(_, v)| v.len() != n) {
        return Err(DesignError::Shape {
            what: format!(
                "eigenvector {i} has {} coordinates; {n} eigenvalues need {n}",
                v.len()
            ),
        });
    }
    if !eigenvalues.iter().any(One::is_one) {
        return Err(DesignError::NoEigenvalueOne);
    }
    for (i, (l, v)) in eigenvalues.iter().zip(eigenvectors).enumerate() {
        let s: BigRational = v.iter().sum();
        if !l.is_one() && !s.is_zero() {
            return Err(DesignError::NotBarycentric {
                index: i,
                eigenvalue: l.to_string(),
                sum: s.to_string(),
            });
        }
    }
    if let Some(index) = first_dependent(eigenvectors) {
        return Err(DesignError::Singular { index });
    }
    let v = Matrix::from_rows(
        (0..n)
            .map(|r| (0..n).map(|c| eigenvectors[c][r].clone()).collect())
            .collect(),
    );
    let inv = inverse(&v).ok_or(DesignError::Singular { index: n - 1 })?;
    let mut vd = v.clone();
    for (c, l) in eigenvalues.iter().enumerate() {
        for r in 0..n {
            let x = v.get(r, c) * l;
            vd.set(r, c, x);
        }
    }
    Ok(vd.mul(&inv).expect("square"))
}

/// One constraint evaluated with the designed operator.
#[derive(Clone, Debug, Serialize)]
pub struct ConstraintCheck {
    /// Constraint index in the automaton.
    pub index: usize,
    /// Its label (file line, or origin).
    pub label: String,
    /// The constraint as text.
    pub text: String,
    /// Both sides are equal.
    pub holds: bool,
    /// The first differing entry `(r, c): lhs ≠ rhs`, when it does not hold.
    pub difference: Option<String>,
}

/// The result of plugging a designed operator into an automaton. A violated constraint is a
/// result, not an error.
#[derive(Clone, Debug, Serialize)]
pub struct DesignCheck {
    /// The operator replaced.
    pub operator: String,
    /// `Some(false)` when the operator must be barycentric and is not.
    pub barycentric: Option<bool>,
    /// Every constraint whose words involve the operator and otherwise only known operators.
    pub constraints: Vec<ConstraintCheck>,
    /// The whole system, re-solved with the operator fixed, is consistent.
    pub consistent: bool,
    /// Degrees of freedom left for the other unknown operators.
    pub remaining_dof: usize,
    /// When inconsistent: the conflicting constraints reported by the solver, with multipliers.
    pub conflict: Vec<String>,
}

impl DesignCheck {
    /// The design satisfies every constraint.
    pub fn ok(&self) -> bool {
        self.barycentric != Some(false)
            && self.constraints.iter().all(|c| c.holds)
            && self.consistent
    }

    /// A human-readable rendering.
    pub fn to_text(&self) -> String {
        let mut out = format!("check of {} against the automaton:\n", self.operator);
        if let Some(b) = self.barycentric {
            out += &format!("  barycentric: {}\n", if b { "yes" } else { "NO" });
        }
        for c in &self.constraints {
            out += &format!(
                "  {} {}: {}{}\n",
                if c.holds { "ok  " } else { "FAIL" },
                c.label,
                c.text,
                c.difference
                    .as_ref()
                    .map_or(String::new(), |d| format!(" — {d}"))
            );
        }
        if self.consistent {
            out += &format!(
                "  re-solved with {} fixed: consistent, {} degrees of freedom left\n",
                self.operator, self.remaining_dof
            );
        } else {
            out += &format!("  re-solved with {} fixed: INCONSISTENT\n", self.operator);
            for c in &self.conflict {
                out += &format!("    {c}\n");
            }
        }
        out += if self.ok() {
            "  verdict: valid\n"
        } else {
            "  verdict: not valid\n"
        };
        out
    }
}

/// Plugs `m` in as the value of operator `op_name` of `a`: checks barycentricity when the file
/// asks for it, evaluates exactly every constraint that involves only `m` and known operators,
/// and re-solves the whole system with the operator fixed. Errors: E0910 (no such operator,
/// wrong shape), and the solver's own errors.
pub fn check_design(a: &Automaton, op_name: &str, m: &Matrix) -> Result<DesignCheck> {
    let Some(o) = a.operators.iter().position(|op| op.name == op_name) else {
        return Err(DesignError::Operator {
            what: format!("no operator `{op_name}` in the automaton"),
        }
        .into());
    };
    let op = &a.operators[o];
    let (rows, cols) = (a.states[op.to].dim, a.states[op.from].dim);
    if (m.rows, m.cols) != (rows, cols) {
        return Err(DesignError::Operator {
            what: format!(
                "operator `{op_name}` is {rows}×{cols} but the design is {}×{}",
                m.rows, m.cols
            ),
        }
        .into());
    }
    let mut b = a.clone();
    b.operators[o].value = Some(m.clone());
    let barycentric = b.barycentric.contains(&o).then(|| m.is_barycentric());
    let word = |w: &[Factor]| -> Option<Matrix> {
        let mut acc: Option<Matrix> = None;
        for f in w {
            let x = match f {
                Factor::Op(i) => b.operators[*i].value.clone()?,
                Factor::Literal(l) => l.clone(),
            };
            acc = Some(match acc {
                None => x,
                Some(p) => p.mul(&x)?,
            });
        }
        acc
    };
    let mut constraints = Vec::new();
    for (k, con) in b.constraints.iter().enumerate() {
        let involves = con
            .lhs
            .iter()
            .chain(&con.rhs)
            .any(|f| matches!(f, Factor::Op(i) if *i == o));
        if !involves {
            continue;
        }
        let (Some(l), Some(r)) = (word(&con.lhs), word(&con.rhs)) else {
            continue; // another unknown operator, or shapes the solver will report
        };
        let difference = if (l.rows, l.cols) != (r.rows, r.cols) {
            Some(format!(
                "shapes {}×{} and {}×{}",
                l.rows, l.cols, r.rows, r.cols
            ))
        } else {
            (0..l.rows * l.cols)
                .find(|&i| l.data[i] != r.data[i])
                .map(|i| {
                    format!(
                        "entry ({}, {}): {} ≠ {}",
                        i / l.cols,
                        i % l.cols,
                        l.data[i],
                        r.data[i]
                    )
                })
        };
        constraints.push(ConstraintCheck {
            index: k,
            label: con.label.clone(),
            text: b.constraint_text(k),
            holds: difference.is_none(),
            difference,
        });
    }
    let (report, _, _) = solve_automaton(&b)?;
    Ok(DesignCheck {
        operator: op_name.to_string(),
        barycentric,
        constraints,
        consistent: report.consistent,
        remaining_dof: report.dof,
        conflict: report
            .conflict
            .unwrap_or_default()
            .iter()
            .map(|c| format!("{} × {}", c.multiplier, c.constraint))
            .collect(),
    })
}
