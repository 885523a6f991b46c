//! The linear system of a hand-written automaton (THEORY §6), rebuilt by the checker from the
//! claim's states, operators and words, so that a solution-space or inconsistency step is about
//! the claimed automaton and not about some other system.
//!
//! Unknowns are the entries of the unknown operators, operator by operator, row by row. Rows:
//! every entry `(r, c)` of every constraint `lhs = rhs` (a word has at most one unknown factor
//! `X`, so an entry of `K₁·X·K₂` is `Σ_(i,j) K₁[r][i]·K₂[j][c]·X[i][j]`; constants move to the
//! right), then every column of every barycentric operator (`Σ column = 1`).
//!
//! Cost: sizes are checked before anything is built (dimensions, the number of unknowns against
//! the step's, the number of rows against the certificate's), matrices are sparse, and the terms
//! produced are counted against the certificate's own terms, so the work stays proportional to
//! the certificate's size.

use super::{rat, Equation, Q};
use crate::certificate::{AutomatonClaim, WordFactor};
use num_traits::{One, Zero};
use std::collections::BTreeMap;

/// The largest state dimension the checker accepts (lacuna's automata use a few dozen).
const MAX_DIM: usize = 1 << 16;

/// The most multiplications spent on products of known factors.
const MAX_PRODUCT_WORK: u128 = 50_000_000;

/// A sparse matrix: `rows × cols`, the nonzero entries of each row.
#[derive(Clone)]
struct Sparse {
    rows: usize,
    cols: usize,
    data: Vec<Vec<(usize, Q)>>,
}

impl Sparse {
    fn identity(n: usize) -> Sparse {
        Sparse {
            rows: n,
            cols: n,
            data: (0..n).map(|i| vec![(i, Q::one())]).collect(),
        }
    }

    /// A matrix given as rows of rationals; every row has the same length.
    fn parse(m: &[Vec<String>], what: &str) -> Result<Sparse, String> {
        let cols = m.first().map_or(0, Vec::len);
        if m.is_empty() || cols == 0 || m.iter().any(|r| r.len() != cols) {
            return Err(format!("{what}: not a nonempty rectangular matrix"));
        }
        let data = m
            .iter()
            .map(|r| {
                let mut out = Vec::new();
                for (j, x) in r.iter().enumerate() {
                    let x = rat(x)?;
                    if !x.is_zero() {
                        out.push((j, x));
                    }
                }
                Ok(out)
            })
            .collect::<Result<_, String>>()?;
        Ok(Sparse {
            rows: m.len(),
            cols,
            data,
        })
    }

    fn mul(&self, b: &Sparse, work: &mut u128) -> Result<Sparse, String> {
        let mut data = Vec::with_capacity(self.rows);
        for row in &self.data {
            let mut acc: BTreeMap<usize, Q> = BTreeMap::new();
            for (k, a) in row {
                *work += b.data[*k].len() as u128;
                if *work > MAX_PRODUCT_WORK {
                    return Err(super::over(
                        "the products of known factors (multiplications of rationals)",
                        *work,
                        MAX_PRODUCT_WORK,
                        "max-work",
                    ));
                }
                // A product of rationals costs a few word operations and gcds: charged as 16.
                super::within_work(
                    "the products of known factors",
                    16 * b.data[*k].len() as u128,
                )?;
                for (c, x) in &b.data[*k] {
                    *acc.entry(*c).or_insert_with(Q::zero) += a * x;
                }
            }
            data.push(acc.into_iter().filter(|(_, x)| !x.is_zero()).collect());
        }
        Ok(Sparse {
            rows: self.rows,
            cols: b.cols,
            data,
        })
    }

    fn get(&self, r: usize, c: usize) -> Q {
        let row = &self.data[r];
        match row.binary_search_by_key(&c, |(j, _)| *j) {
            Ok(at) => row[at].1.clone(),
            Err(_) => Q::zero(),
        }
    }

    /// The nonzero entries of each column.
    fn columns(&self) -> Vec<Vec<(usize, Q)>> {
        let mut cols = vec![Vec::new(); self.cols];
        for (r, row) in self.data.iter().enumerate() {
            for (c, x) in row {
                cols[*c].push((r, x.clone()));
            }
        }
        cols
    }
}

/// The parsed automaton: state dimensions, known operator values, unknown offsets.
struct Parsed {
    shape: Vec<(usize, usize)>,
    value: Vec<Option<Sparse>>,
    offset: Vec<Option<usize>>,
}

fn parse(a: &AutomatonClaim, unknowns: usize) -> Result<Parsed, String> {
    if let Some(s) = a.states.iter().find(|s| s.dim == 0 || s.dim > MAX_DIM) {
        return Err(format!(
            "state {} has dimension {}, not in 1..={MAX_DIM}",
            s.name, s.dim
        ));
    }
    let dim = |s: usize, o: &str| {
        a.states
            .get(s)
            .map(|x| x.dim)
            .ok_or_else(|| format!("operator {o}: state {s} out of range"))
    };
    let (mut shape, mut value, mut offset) = (Vec::new(), Vec::new(), Vec::new());
    let mut count: usize = 0;
    for op in &a.operators {
        let (r, c) = (dim(op.to, &op.name)?, dim(op.from, &op.name)?);
        shape.push((r, c));
        match &op.value {
            Some(m) => {
                let m = Sparse::parse(m, &format!("operator {}", op.name))?;
                if (m.rows, m.cols) != (r, c) {
                    return Err(format!(
                        "operator {}: a {}×{} matrix between states of dimensions {r} and {c}",
                        op.name, m.rows, m.cols
                    ));
                }
                value.push(Some(m));
                offset.push(None);
            }
            None => {
                value.push(None);
                offset.push(Some(count));
                count = r
                    .checked_mul(c)
                    .and_then(|x| count.checked_add(x))
                    .ok_or("the number of unknowns overflows")?;
            }
        }
    }
    if count != unknowns {
        return Err(format!(
            "the automaton has {count} unknown entries, the system {unknowns}"
        ));
    }
    Ok(Parsed {
        shape,
        value,
        offset,
    })
}

/// The shape of a word and the position of its unknown factor; shapes must chain, at most one
/// factor may be unknown.
fn word_shape(
    p: &Parsed,
    w: &[WordFactor],
    literals: &[Option<Sparse>],
    k: usize,
) -> Result<((usize, usize), Option<usize>), String> {
    let shape = |i: usize| -> Result<(usize, usize), String> {
        match &w[i] {
            WordFactor::Op(o) => p
                .shape
                .get(*o)
                .copied()
                .ok_or_else(|| format!("constraint {k}: operator {o} out of range")),
            WordFactor::Literal(_) => {
                let m = literals[i].as_ref().expect("literals are parsed");
                Ok((m.rows, m.cols))
            }
        }
    };
    if w.is_empty() {
        return Err(format!("constraint {k}: an empty word"));
    }
    let shapes: Vec<(usize, usize)> = (0..w.len()).map(shape).collect::<Result<_, _>>()?;
    if shapes.windows(2).any(|s| s[0].1 != s[1].0) {
        return Err(format!("constraint {k}: the shapes of a word do not chain"));
    }
    let unknown: Vec<usize> = (0..w.len())
        .filter(|&i| matches!(w[i], WordFactor::Op(o) if p.value[o].is_none()))
        .collect();
    if unknown.len() > 1 {
        return Err(format!(
            "constraint {k}: a word with {} unknown factors is not linear",
            unknown.len()
        ));
    }
    let rows = shapes[0].0;
    let cols = shapes[shapes.len() - 1].1;
    Ok(((rows, cols), unknown.first().copied()))
}

/// The entries of a word as linear forms `(terms, constant)`, row-major.
fn word_forms(
    p: &Parsed,
    w: &[WordFactor],
    literals: &[Option<Sparse>],
    (rows, unknown): (usize, Option<usize>),
    budget: &mut (u128, u128),
) -> Result<Vec<Equation>, String> {
    let known = |i: usize| -> &Sparse {
        match &w[i] {
            WordFactor::Op(o) => p.value[*o].as_ref().expect("a known operator"),
            WordFactor::Literal(_) => literals[i].as_ref().expect("parsed"),
        }
    };
    let product = |from: usize, to: usize, n: usize, work: &mut u128| -> Result<Sparse, String> {
        match from < to {
            false => Ok(Sparse::identity(n)),
            true => (from + 1..to).try_fold(known(from).clone(), |acc, i| acc.mul(known(i), work)),
        }
    };
    match unknown {
        None => {
            let m = product(0, w.len(), rows, &mut budget.0)?;
            let mut out = Vec::with_capacity(m.rows * m.cols);
            for r in 0..m.rows {
                for c in 0..m.cols {
                    out.push((Vec::new(), m.get(r, c)));
                }
            }
            Ok(out)
        }
        Some(at) => {
            let WordFactor::Op(o) = w[at] else {
                unreachable!("unknown factors are operators")
            };
            let (xr, xc) = p.shape[o];
            let base = p.offset[o].expect("an unknown operator");
            let k1 = product(0, at, xr, &mut budget.0)?;
            let k2 = product(at + 1, w.len(), xc, &mut budget.0)?;
            let k2cols = k2.columns();
            let mut out = Vec::with_capacity(k1.rows * k2.cols);
            for r in 0..k1.rows {
                for col in &k2cols {
                    budget.1 = budget
                        .1
                        .checked_sub((k1.data[r].len() as u128) * (col.len() as u128))
                        .ok_or("the automaton's rows have more terms than the certificate's")?;
                    let mut terms = Vec::new();
                    for (i, a) in &k1.data[r] {
                        for (j, b) in col {
                            terms.push((base + i * xc + j, a * b));
                        }
                    }
                    out.push((terms, Q::zero()));
                }
            }
            Ok(out)
        }
    }
}

/// The rows of the claim's automaton, in the checker's own construction. `unknowns` is the
/// step's number of unknowns, `given` the certificate's rows (their number and their terms
/// bound the work before and while building).
pub(super) fn rebuild_automaton(
    a: &AutomatonClaim,
    unknowns: usize,
    given: &[Equation],
) -> Result<Vec<Equation>, String> {
    let p = parse(a, unknowns)?;
    // Literals parsed once, and every word's shape, before any row is built.
    let mut words = Vec::with_capacity(a.constraints.len());
    let mut expected: usize = 0;
    for (k, c) in a.constraints.iter().enumerate() {
        let mut sides = Vec::new();
        for w in [&c.lhs, &c.rhs] {
            let literals = w
                .iter()
                .map(|f| match f {
                    WordFactor::Literal(m) => {
                        Sparse::parse(m, &format!("constraint {k}: a literal")).map(Some)
                    }
                    WordFactor::Op(_) => Ok(None),
                })
                .collect::<Result<Vec<_>, String>>()?;
            let (shape, unknown) = word_shape(&p, w, &literals, k)?;
            sides.push((literals, shape, unknown));
        }
        if sides[0].1 != sides[1].1 {
            return Err(format!(
                "constraint {k}: the two sides have different shapes"
            ));
        }
        let (r, cols) = sides[0].1;
        expected = r
            .checked_mul(cols)
            .and_then(|x| expected.checked_add(x))
            .ok_or("the number of rows overflows")?;
        words.push(sides);
    }
    for &o in &a.barycentric {
        let (_, c) = *p
            .shape
            .get(o)
            .ok_or_else(|| format!("barycentric operator {o} out of range"))?;
        expected = expected
            .checked_add(c)
            .ok_or("the number of rows overflows")?;
    }
    if expected != given.len() {
        return Err(format!(
            "the automaton has {expected} rows, the certificate lists {}",
            given.len()
        ));
    }
    let given_terms: u128 = given.iter().map(|(t, _)| t.len() as u128).sum();
    let mut budget = (0u128, 2 * given_terms + 4096);
    let mut rows = Vec::with_capacity(expected);
    for (c, sides) in a.constraints.iter().zip(&words) {
        let [(ll, (lr, _), lu), (rl, _, ru)] = &sides[..] else {
            unreachable!("two sides")
        };
        let lf = word_forms(&p, &c.lhs, ll, (*lr, *lu), &mut budget)?;
        let rf = word_forms(&p, &c.rhs, rl, (*lr, *ru), &mut budget)?;
        for ((mut terms, lk), (rt, rk)) in lf.into_iter().zip(rf) {
            terms.extend(rt.into_iter().map(|(v, x)| (v, -x)));
            rows.push((terms, rk - lk));
        }
    }
    for &o in &a.barycentric {
        let (r, c) = p.shape[o];
        for j in 0..c {
            match (&p.value[o], p.offset[o]) {
                (Some(m), _) => {
                    let sum: Q = (0..r).map(|i| m.get(i, j)).sum();
                    rows.push((Vec::new(), Q::one() - sum));
                }
                (None, Some(base)) => {
                    budget.1 = budget
                        .1
                        .checked_sub(r as u128)
                        .ok_or("the automaton's rows have more terms than the certificate's")?;
                    let terms = (0..r).map(|i| (base + i * c + j, Q::one())).collect();
                    rows.push((terms, Q::one()));
                }
                (None, None) => unreachable!("unknown operators have offsets"),
            }
        }
    }
    Ok(rows)
}
