//! The linear system itself: how its equations are stored, read, serialised and written as text.
//!
//! The BC-IFS systems have millions of terms whose coefficients are nearly all `±1` or small
//! fractions. A `(usize, BigRational)` term is about 136 bytes, with its numerator and its
//! denominator on the heap, and reading one costs two cache misses; on the 1.18M-unknown system
//! of `benches/solver.rs` the solver spent a twelfth of its time only reading its input (issue
//! #34). So a [`LinearSystem`] keeps its equations in one compressed sparse row array of 20-byte
//! terms (a `u32` unknown and a rational in two words while it fits, boxed when it does not), and
//! the solver reads that array in place. [`Equation`] remains the plain form in which equations
//! are given and read back.

use super::check::difference;
use crate::constraint::presolve::{Rows, Q};
use num_rational::BigRational;
use serde::{ser::SerializeStruct, Deserialize, Deserializer, Serialize, Serializer};
use std::io::{self, Write};

/// A linear system `Σ coef·x[var] = rhs` over Q in `unknowns` unknowns.
///
/// Equations keep their terms as given: in any order, a variable may repeat (the coefficients
/// add up) and a coefficient may be zero. Serialises as `{"unknowns": n, "rows": [equation,
/// …]}`, each equation as [`Equation`] does.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LinearSystem {
    /// Number of unknowns; every variable index is below it.
    pub unknowns: usize,
    rows: Rows,
    /// One more than the largest variable named by a term (0 without terms).
    bound: usize,
}

/// One equation `Σ coef·x[var] = rhs`; a variable may repeat (coefficients add up), `terms` may
/// be empty.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Equation {
    /// `(variable, coefficient)` pairs.
    #[serde(with = "rat_terms")]
    pub terms: Vec<(usize, BigRational)>,
    /// Right-hand side.
    #[serde(with = "rat")]
    pub rhs: BigRational,
}

impl LinearSystem {
    /// A system of no equations in `unknowns` unknowns.
    pub fn new(unknowns: usize) -> LinearSystem {
        LinearSystem {
            unknowns,
            ..LinearSystem::default()
        }
    }

    /// The system of the given equations in `unknowns` unknowns.
    ///
    /// # Panics
    /// As [`LinearSystem::push`].
    pub fn from_equations(
        unknowns: usize,
        equations: impl IntoIterator<Item = Equation>,
    ) -> LinearSystem {
        let mut sys = LinearSystem::new(unknowns);
        equations.into_iter().for_each(|e| sys.push(&e));
        sys
    }

    /// Appends an equation.
    ///
    /// # Panics
    /// If a term names the variable `2^32 − 1` or a larger one (the solver's limit, far above
    /// what memory allows).
    pub fn push(&mut self, e: &Equation) {
        let terms = e.terms.iter().map(|(v, c)| (*v, Q::from_big(c)));
        self.push_q(terms, Q::from_big(&e.rhs));
    }

    /// Appends the equation `Σ q·x[v] = rhs` in the solver's numbers.
    ///
    /// # Panics
    /// As [`LinearSystem::push`].
    pub(crate) fn push_q(&mut self, terms: impl IntoIterator<Item = (usize, Q)>, rhs: Q) {
        let from = self.rows.vars.len();
        self.rows
            .push(terms.into_iter().map(|(v, q)| (var(v), q)), rhs);
        if let Some(&top) = self.rows.vars[from..].iter().max() {
            self.bound = self.bound.max(top as usize + 1);
        }
    }

    /// Number of equations.
    pub fn len(&self) -> usize {
        self.rows.len()
    }

    /// Whether there are no equations.
    pub fn is_empty(&self) -> bool {
        self.rows.len() == 0
    }

    /// Number of terms over all equations.
    pub fn term_count(&self) -> usize {
        self.rows.vars.len()
    }

    /// One more than the largest variable any term names (0 when there are no terms): the
    /// system is well formed when this is at most [`LinearSystem::unknowns`].
    pub fn variable_bound(&self) -> usize {
        self.bound
    }

    /// Equation `i`.
    ///
    /// # Panics
    /// If `i ≥ self.len()`.
    pub fn equation(&self, i: usize) -> Equation {
        Equation {
            terms: self.terms(i).collect(),
            rhs: self.rhs(i),
        }
    }

    /// Equation `i`, or `None` when there is no such equation.
    pub fn get(&self, i: usize) -> Option<Equation> {
        (i < self.len()).then(|| self.equation(i))
    }

    /// The equations in order.
    pub fn equations(&self) -> impl ExactSizeIterator<Item = Equation> + '_ {
        (0..self.len()).map(|i| self.equation(i))
    }

    /// The `(variable, coefficient)` terms of equation `i`, as given.
    ///
    /// # Panics
    /// If `i ≥ self.len()`.
    pub fn terms(&self, i: usize) -> impl ExactSizeIterator<Item = (usize, BigRational)> + '_ {
        let (vars, coefs) = self.rows.row(i);
        vars.iter().zip(coefs).map(|(v, c)| (*v as usize, c.big()))
    }

    /// The right-hand side of equation `i`.
    ///
    /// # Panics
    /// If `i ≥ self.len()`.
    pub fn rhs(&self, i: usize) -> BigRational {
        self.rows.rhs[i].big()
    }

    /// Replaces the right-hand side of equation `i`.
    ///
    /// # Panics
    /// If `i ≥ self.len()`.
    pub fn set_rhs(&mut self, i: usize, rhs: &BigRational) {
        self.rows.rhs[i] = Q::from_big(rhs);
    }

    /// The equations in the solver's form, read in place.
    pub(crate) fn rows(&self) -> &Rows {
        &self.rows
    }
}

/// `v` as the solver's `u32` variable index.
fn var(v: usize) -> u32 {
    match u32::try_from(v) {
        Ok(x) if x < u32::MAX => x,
        _ => panic!("variable {v} is beyond the solver's 2^32 − 2"),
    }
}

impl Serialize for LinearSystem {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        /// The equations, serialised one at a time (no copy of the system).
        struct Each<'a>(&'a LinearSystem);
        impl Serialize for Each<'_> {
            fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                s.collect_seq(self.0.equations())
            }
        }
        let mut st = s.serialize_struct("LinearSystem", 2)?;
        st.serialize_field("unknowns", &self.unknowns)?;
        st.serialize_field("rows", &Each(self))?;
        st.end()
    }
}

impl<'de> Deserialize<'de> for LinearSystem {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<LinearSystem, D::Error> {
        /// The serialised form.
        #[derive(Deserialize)]
        struct Plain {
            unknowns: usize,
            rows: Vec<Equation>,
        }
        let plain = Plain::deserialize(d)?;
        if let Some(v) = plain
            .rows
            .iter()
            .flat_map(|e| e.terms.iter().map(|t| t.0))
            .find(|&v| v >= u32::MAX as usize)
        {
            return Err(serde::de::Error::custom(format!(
                "variable {v} is beyond the solver's 2^32 − 2"
            )));
        }
        Ok(LinearSystem::from_equations(plain.unknowns, plain.rows))
    }
}

pub(super) mod rat {
    use num_rational::BigRational;
    use serde::{de::Error, Deserialize, Deserializer, Serializer};
    pub fn serialize<S: Serializer>(r: &BigRational, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(r)
    }
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<BigRational, D::Error> {
        String::deserialize(d)?.parse().map_err(D::Error::custom)
    }
}

pub(super) mod rat_terms {
    use num_rational::BigRational;
    use serde::{de::Error, Deserialize, Deserializer, Serializer};
    pub fn serialize<S: Serializer>(v: &[(usize, BigRational)], s: S) -> Result<S::Ok, S::Error> {
        s.collect_seq(v.iter().map(|(i, r)| (i, r.to_string())))
    }
    pub fn deserialize<'de, D: Deserializer<'de>>(
        d: D,
    ) -> Result<Vec<(usize, BigRational)>, D::Error> {
        let raw = Vec::<(usize, String)>::deserialize(d)?;
        raw.into_iter()
            .map(|(i, s)| Ok((i, s.parse().map_err(D::Error::custom)?)))
            .collect()
    }
}

/// Text layouts of [`write_text`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TextLayout {
    /// First line `rows cols`; then per equation `c_0 c_1 … c_{cols−1} | rhs`.
    Dense,
    /// First line `rows cols`; then per equation `rhs | col:coef col:coef …` (columns increasing,
    /// repeats summed, zeros omitted).
    Sparse,
}

/// Writes the system as text for an external comparison; rationals are `p/q` or `p`.
///
/// Reading it with python-flint (`fmpq_mat.rref()` returns `(rref, rank)`; consistency is
/// `rank(A) = rank([A|b])`):
/// ```text
/// from fractions import Fraction
/// import flint
/// def q(s):
///     f = Fraction(s)
///     return flint.fmpq(f.numerator, f.denominator)
/// def read(path, sparse):
///     with open(path) as f:
///         m, n = map(int, f.readline().split())
///         a, b = [[flint.fmpq(0)] * n for _ in range(m)], []
///         for i, line in enumerate(f):
///             left, right = line.split("|")
///             if sparse:  # rhs | col:coef ...
///                 b.append(q(left))
///                 for t in right.split():
///                     c, v = t.split(":")
///                     a[i][int(c)] = q(v)
///             else:       # c_0 ... c_{n-1} | rhs
///                 a[i] = [q(v) for v in left.split()]
///                 b.append(q(right))
///         return flint.fmpq_mat(m, n, [x for r in a for x in r]), flint.fmpq_mat(m, 1, b)
/// ```
pub fn write_text<W: Write>(sys: &LinearSystem, layout: TextLayout, mut out: W) -> io::Result<()> {
    writeln!(out, "{} {}", sys.len(), sys.unknowns)?;
    for i in 0..sys.len() {
        let d = difference(&sys.equation(i).terms, &[]);
        let rhs = sys.rhs(i);
        match layout {
            TextLayout::Dense => {
                for v in 0..sys.unknowns {
                    match d.get(&v) {
                        Some(c) => write!(out, "{c} ")?,
                        None => write!(out, "0 ")?,
                    }
                }
                writeln!(out, "| {rhs}")?;
            }
            TextLayout::Sparse => {
                write!(out, "{rhs} |")?;
                for (v, c) in d {
                    write!(out, " {v}:{c}")?;
                }
                writeln!(out)?;
            }
        }
    }
    Ok(())
}
