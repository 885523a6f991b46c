//! The field K of a hand-written automaton and its constraints: K's arithmetic and matrices,
//! the claim's shape, every operator's value (the claim's or the instance's), and the steps
//! `constraints-hold` and `constraint-fails`, each re-derived from the claim. The attractor's
//! contraction is in `contraction.rs`, its similarity dimension in `similarity.rs`.
//!
//! K = Q(α) is the claim's field (Q when it has none: α = 0 as the root of `x`). Elements are
//! polynomials in α reduced modulo α's polynomial; equalities are exact zero tests and signs are
//! decided by [`Root::sign`] (Sturm isolation, interval bisection), so every comparison is
//! exact.

use super::field::{self, Root, P};
use super::{rat, Q};
use crate::certificate::{AutomatonClaim, FieldCoords, WordFactor};
use num_traits::One;
use std::collections::BTreeMap;

/// What a proved step says: (message, verdict).
pub(super) type Checked = Result<(String, String), String>;

/// The most control points of a state, states and operators the checker works with here (the
/// library's automata have at most a few dozen of each).
const MAX_DIM: usize = 256;

const MAX_STATES: usize = 4096;

const MAX_OPERATORS: usize = 1 << 16;

/// A matrix over K, row-major.
#[derive(Clone)]
pub(super) struct KMat {
    pub(super) rows: usize,
    pub(super) cols: usize,
    pub(super) data: Vec<P>,
}

/// K with its arithmetic.
pub(super) struct Field {
    root: Root,
}

impl Field {
    pub(super) fn of(a: &AutomatonClaim) -> Result<Field, String> {
        let root = match &a.field {
            Some(k) => Root::isolate(&k.poly, &k.lo, &k.hi, "the field's generator α")?,
            None => Root::isolate(&["0".into(), "1".into()], "0", "0", "α")?,
        };
        Ok(Field { root })
    }

    pub(super) fn element(&self, c: &FieldCoords) -> Result<P, String> {
        self.root.element(c)
    }

    /// `p` reduced modulo α's polynomial.
    pub(super) fn reduce(&self, p: &[Q]) -> P {
        self.root.reduce(p)
    }

    pub(super) fn mul(&self, a: &[Q], b: &[Q]) -> P {
        self.root.mul(a, b)
    }

    pub(super) fn sub(&self, a: &[Q], b: &[Q]) -> P {
        field::add(a, &field::scale(b, &-Q::one()))
    }

    pub(super) fn is_zero(&self, a: &[Q]) -> bool {
        self.root.is_zero(a)
    }

    /// Whether `p` (coefficients over Q, in the generator's variable) vanishes at α.
    pub(super) fn vanishes(&self, p: &[Q]) -> bool {
        self.root.is_zero(&self.root.reduce(p))
    }

    /// α's isolating interval.
    pub(super) fn interval(&self) -> (Q, Q) {
        (self.root.lo.clone(), self.root.hi.clone())
    }

    /// The sign of `a`, or an error when the bisection gives up.
    pub(super) fn sign(&self, a: &[Q]) -> Result<i32, String> {
        self.root
            .sign(a)
            .ok_or_else(|| "a sign in K was not decided within 4000 bisections".to_string())
    }

    pub(super) fn abs(&self, a: &[Q]) -> Result<P, String> {
        Ok(match self.sign(a)? < 0 {
            true => field::scale(a, &-Q::one()),
            false => a.to_vec(),
        })
    }

    pub(super) fn rational(q: Q) -> P {
        field::trim(vec![q])
    }

    /// `1/a` in K, or an error when `a` is no unit of `Q[x]/(p)` (zero at α, or sharing a factor
    /// with a reducible p).
    pub(super) fn inv(&self, a: &[Q]) -> Result<P, String> {
        self.root
            .inverse(a)
            .ok_or_else(|| "an element of K could not be inverted".to_string())
    }

    pub(super) fn matmul(&self, a: &KMat, b: &KMat) -> Result<KMat, String> {
        if a.cols != b.rows {
            return Err(format!(
                "a product of a {}×{} and a {}×{} matrix",
                a.rows, a.cols, b.rows, b.cols
            ));
        }
        super::within_work(
            "the products of operators in K",
            (a.rows * a.cols * b.cols) as u128 * 8,
        )?;
        let mut data = vec![P::new(); a.rows * b.cols];
        for r in 0..a.rows {
            for c in 0..b.cols {
                let mut acc = P::new();
                for j in 0..a.cols {
                    let (x, y) = (&a.data[r * a.cols + j], &b.data[j * b.cols + c]);
                    if !x.is_empty() && !y.is_empty() {
                        acc = field::add(&acc, &self.mul(x, y));
                    }
                }
                data[r * b.cols + c] = acc;
            }
        }
        Ok(KMat {
            rows: a.rows,
            cols: b.cols,
            data,
        })
    }

    pub(super) fn identity(n: usize) -> KMat {
        let mut data = vec![P::new(); n * n];
        for i in 0..n {
            data[i * n + i] = Self::rational(Q::one());
        }
        KMat {
            rows: n,
            cols: n,
            data,
        }
    }

    pub(super) fn equal(&self, a: &KMat, b: &KMat) -> bool {
        a.rows == b.rows
            && a.cols == b.cols
            && a.data
                .iter()
                .zip(&b.data)
                .all(|(x, y)| self.is_zero(&self.sub(x, y)))
    }
}

/// A nonempty rectangular matrix, each entry read by `entry`.
fn parse_matrix<T>(
    m: &[Vec<T>],
    what: &str,
    entry: impl Fn(&T) -> Result<P, String>,
) -> Result<KMat, String> {
    let cols = m.first().map_or(0, Vec::len);
    if m.is_empty() || cols == 0 || m.iter().any(|r| r.len() != cols) {
        return Err(format!("{what}: not a nonempty rectangular matrix"));
    }
    let data = m.iter().flatten().map(entry).collect::<Result<_, _>>()?;
    Ok(KMat {
        rows: m.len(),
        cols,
        data,
    })
}

pub(super) fn parse_rational_matrix(m: &[Vec<String>], what: &str) -> Result<KMat, String> {
    parse_matrix(m, what, |x| Ok(Field::rational(rat(x)?)))
}

pub(super) fn parse_field_matrix(
    k: &Field,
    m: &[Vec<FieldCoords>],
    what: &str,
) -> Result<KMat, String> {
    parse_matrix(m, what, |x| k.element(x))
}

/// Sizes read before anything is built.
fn check_sizes(a: &AutomatonClaim) -> Result<(), String> {
    if a.states.len() > MAX_STATES || a.operators.len() > MAX_OPERATORS {
        return Err(format!(
            "{} states and {} operators: the checker handles at most {MAX_STATES} and {MAX_OPERATORS}",
            a.states.len(),
            a.operators.len()
        ));
    }
    if let Some(s) = a.states.iter().find(|s| s.dim == 0 || s.dim > MAX_DIM) {
        return Err(format!(
            "state {} has {} control points, not in 1..={MAX_DIM}",
            s.name, s.dim
        ));
    }
    for o in &a.operators {
        if o.to >= a.states.len() || o.from >= a.states.len() {
            return Err(format!("operator {}: a state out of range", o.name));
        }
    }
    Ok(())
}

/// The claim's field isolates a root; every operator joins existing states; every given operator
/// (rational or in K, not both) has its states' shape and parses; the attractor's start state
/// exists, has as many points as its dimension, all of 2 or all of 3 coordinates, in K;
/// its subdivision operators exist, increasing.
pub(super) fn well_formed(a: &AutomatonClaim) -> Result<(), String> {
    for o in &a.operators {
        if o.to >= a.states.len() || o.from >= a.states.len() {
            return Err(format!("operator {}: a state out of range", o.name));
        }
    }
    let k = Field::of(a)?;
    for o in &a.operators {
        let shape = (a.states[o.to].dim, a.states[o.from].dim);
        let m = match (&o.value, &o.field_value) {
            (Some(_), Some(_)) => {
                return Err(format!(
                    "operator {} is given twice (in Q and in K)",
                    o.name
                ))
            }
            (Some(v), None) => parse_rational_matrix(v, &o.name)?,
            (None, Some(v)) => parse_field_matrix(&k, v, &o.name)?,
            (None, None) => continue,
        };
        if (m.rows, m.cols) != shape {
            return Err(format!(
                "operator {} is {}×{}, its states need {}×{}",
                o.name, m.rows, m.cols, shape.0, shape.1
            ));
        }
    }
    if let Some(at) = &a.attractor {
        let dim = a
            .states
            .get(at.start)
            .ok_or_else(|| format!("the start state {} is out of range", at.start))?
            .dim;
        let space = at.points.first().map_or(0, Vec::len);
        if at.points.len() != dim
            || !(2..=3).contains(&space)
            || at.points.iter().any(|p| p.len() != space)
        {
            return Err(format!(
                "the attractor needs {dim} points, all in the plane or all in space"
            ));
        }
        for p in &at.points {
            for x in p {
                k.element(x)?;
            }
        }
        if at.subdivision.windows(2).any(|w| w[0] >= w[1])
            || at.subdivision.iter().any(|&o| o >= a.operators.len())
        {
            return Err("the subdivision operators are not increasing indices of operators".into());
        }
    }
    Ok(())
}

/// Every operator's value: the claim's (rational or in K), else the instance's. Shapes are
/// checked against the states.
pub(super) fn instance(
    k: &Field,
    a: &AutomatonClaim,
    given: &[(usize, Vec<Vec<FieldCoords>>)],
) -> Result<Vec<KMat>, String> {
    check_sizes(a)?;
    let mut extra: BTreeMap<usize, &Vec<Vec<FieldCoords>>> = BTreeMap::new();
    for (o, m) in given {
        let op = a
            .operators
            .get(*o)
            .ok_or_else(|| format!("the instance names operator {o}, out of range"))?;
        if op.value.is_some() || op.field_value.is_some() {
            return Err(format!(
                "the instance gives operator {}, which the claim already gives",
                op.name
            ));
        }
        if extra.insert(*o, m).is_some() {
            return Err(format!("the instance gives operator {} twice", op.name));
        }
    }
    let mut out = Vec::with_capacity(a.operators.len());
    for (i, op) in a.operators.iter().enumerate() {
        let m = match (&op.value, &op.field_value, extra.get(&i)) {
            (Some(v), _, _) => parse_rational_matrix(v, &op.name)?,
            (None, Some(v), _) => parse_field_matrix(k, v, &op.name)?,
            (None, None, Some(v)) => parse_field_matrix(k, v, &op.name)?,
            (None, None, None) => {
                return Err(format!(
                    "operator {} has no value: neither the claim nor the instance gives it",
                    op.name
                ))
            }
        };
        let (r, c) = (a.states[op.to].dim, a.states[op.from].dim);
        if (m.rows, m.cols) != (r, c) {
            return Err(format!(
                "operator {} is {}×{}, its states need {r}×{c}",
                op.name, m.rows, m.cols
            ));
        }
        out.push(m);
    }
    Ok(out)
}

/// A word's product in K (an error when an operator is out of range or the shapes do not
/// chain).
fn word(k: &Field, ops: &[KMat], w: &[WordFactor], which: &str, n: usize) -> Result<KMat, String> {
    let mut acc: Option<KMat> = None;
    for f in w {
        let m = match f {
            WordFactor::Op(o) => ops
                .get(*o)
                .cloned()
                .ok_or_else(|| format!("constraint {n}: operator {o} out of range"))?,
            WordFactor::Literal(m) => parse_rational_matrix(m, "a literal")?,
        };
        acc = Some(match acc {
            None => m,
            Some(p) => k
                .matmul(&p, &m)
                .map_err(|e| format!("constraint {n}, {which} side: {e}"))?,
        });
    }
    acc.ok_or_else(|| format!("constraint {n}: the {which} side is an empty word"))
}

/// Whether constraint n's two words are equal in K (an error when they are malformed or of
/// different shapes).
fn constraint_holds(k: &Field, a: &AutomatonClaim, ops: &[KMat], n: usize) -> Result<bool, String> {
    let c = a
        .constraints
        .get(n)
        .ok_or_else(|| format!("constraint {n} is out of range"))?;
    let (l, r) = (
        word(k, ops, &c.lhs, "left", n)?,
        word(k, ops, &c.rhs, "right", n)?,
    );
    if (l.rows, l.cols) != (r.rows, r.cols) {
        return Err(format!(
            "constraint {n}: its two words have different shapes"
        ));
    }
    Ok(k.equal(&l, &r))
}

/// Evaluates every constraint and barycentric condition on the operators, exactly in K.
pub(super) fn constraints_hold(k: &Field, a: &AutomatonClaim, ops: &[KMat]) -> Result<(), String> {
    for n in 0..a.constraints.len() {
        if !constraint_holds(k, a, ops, n)? {
            return Err(format!(
                "constraint {n} does not hold: its two words differ in K"
            ));
        }
    }
    for &o in &a.barycentric {
        let m = ops
            .get(o)
            .ok_or_else(|| format!("barycentric operator {o} out of range"))?;
        if !barycentric(k, m) {
            return Err(format!(
                "operator {} is listed barycentric but a column does not sum to 1",
                a.operators[o].name
            ));
        }
    }
    Ok(())
}

pub(super) fn barycentric(k: &Field, m: &KMat) -> bool {
    (0..m.cols).all(|c| {
        let s = (0..m.rows).fold(P::new(), |acc, r| field::add(&acc, &m.data[r * m.cols + c]));
        k.is_zero(&k.sub(&s, &Field::rational(Q::one())))
    })
}

/// The step `constraints-hold`.
pub(super) fn check_constraints_hold(a: &AutomatonClaim, claimed: usize) -> Checked {
    let k = Field::of(a)?;
    if claimed != a.constraints.len() {
        return Err(format!(
            "the step counts {claimed} constraints, the claim has {}",
            a.constraints.len()
        ));
    }
    let ops = instance(&k, a, &[])?;
    constraints_hold(&k, a, &ops)?;
    Ok((
        format!(
            "every operator is given; {} and {} evaluated exactly in {}: every one holds",
            super::counted(a.constraints.len(), "constraint", "constraints"),
            super::counted(
                a.barycentric.len(),
                "barycentric operator",
                "barycentric operators"
            ),
            match a.field {
                Some(_) => "K",
                None => "Q",
            }
        ),
        "consistent: every constraint holds".into(),
    ))
}

/// The step `constraint-fails`.
pub(super) fn check_constraint_fails(
    a: &AutomatonClaim,
    s: &crate::certificate::ConstraintFailsStep,
) -> Checked {
    let k = Field::of(a)?;
    let ops = instance(&k, a, &[])?;
    let (what, failed) = match (s.constraint, s.barycentric) {
        (Some(n), None) => (
            format!("constraint {n}"),
            !constraint_holds(&k, a, &ops, n)?,
        ),
        (None, Some(o)) => {
            if !a.barycentric.contains(&o) {
                return Err(format!("operator {o} is not listed barycentric"));
            }
            let m = ops
                .get(o)
                .ok_or_else(|| format!("operator {o} out of range"))?;
            (
                format!("the column sums of {}", a.operators[o].name),
                !barycentric(&k, m),
            )
        }
        _ => return Err("exactly one of `constraint` and `barycentric` must be given".into()),
    };
    match failed {
        true => Ok((
            format!("{what} evaluated exactly in K: it does not hold"),
            format!("INCONSISTENT: {what} fails"),
        )),
        false => Err(format!("{what} holds: it is no counterexample")),
    }
}

/// The Gram matrix of the differences `P_j − P_0` of a frame's points after `t` (or of the
/// frame itself).
pub(super) fn gram(k: &Field, f: &KMat) -> KMat {
    let m = f.cols;
    let d = |r: usize, j: usize| k.sub(&f.data[r * m + j + 1], &f.data[r * m]);
    let diffs: Vec<Vec<P>> = (0..m - 1)
        .map(|j| (0..f.rows).map(|r| d(r, j)).collect())
        .collect();
    let mut data = Vec::with_capacity((m - 1) * (m - 1));
    for x in &diffs {
        for y in &diffs {
            let s = x
                .iter()
                .zip(y)
                .fold(P::new(), |acc, (a, b)| field::add(&acc, &k.mul(a, b)));
            data.push(s);
        }
    }
    KMat {
        rows: m - 1,
        cols: m - 1,
        data,
    }
}
