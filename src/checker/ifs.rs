//! The attractor of a hand-written automaton: its constraints evaluated in the claim's field K,
//! the contraction of every infinite walk of its control graph, and its similarity dimension
//! (Mauldin–Williams), each re-derived from the claim and the step's witness.
//!
//! K = Q(α) is the claim's field (Q when it has none: α = 0 as the root of `x`). Elements are
//! polynomials in α reduced modulo α's polynomial; equalities are exact zero tests and signs are
//! decided by [`Root::sign`] (Sturm isolation, interval bisection), so every comparison is
//! exact. Logarithms, needed only for the digits of a dimension, are enclosed by series with
//! rigorous tail bounds (`ln_bounds`).

use super::field::{self, Root, P};
use super::neighbour::{self, Decided};
use super::{rat, Q};
use crate::certificate::{
    AutomatonClaim, ContractionStep, FieldCoords, SimilarityPart, SimilarityStep, WordFactor,
};
use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{One, Signed, Zero};
use std::collections::{BTreeMap, BTreeSet, VecDeque};

/// What a proved step says: (message, verdict).
type Checked = Result<(String, String), String>;

/// The most control points of a state, states and operators the checker works with here (the
/// library's automata have at most a few dozen of each).
const MAX_DIM: usize = 256;
const MAX_STATES: usize = 4096;
const MAX_OPERATORS: usize = 1 << 16;
/// The most walks of a contraction step, and the longest walk.
const MAX_WALKS: usize = 1 << 20;
const MAX_WALK_LEN: usize = 4096;
/// The most bits of working precision for the digits of a dimension.
const MAX_BITS: u64 = 1 << 14;

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

    fn abs(&self, a: &[Q]) -> Result<P, String> {
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

    fn matmul(&self, a: &KMat, b: &KMat) -> Result<KMat, String> {
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

    fn identity(n: usize) -> KMat {
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
fn instance(
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
fn constraints_hold(k: &Field, a: &AutomatonClaim, ops: &[KMat]) -> Result<(), String> {
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

/// The control graph: for each state, its subdivision operators `T: q ← w` (edges q → w).
struct Graph {
    out: Vec<Vec<usize>>,
    start: usize,
    reachable: Vec<bool>,
}

fn graph(a: &AutomatonClaim) -> Result<Graph, String> {
    let at = a
        .attractor
        .as_ref()
        .ok_or("the claim has no attractor (start state, points, subdivision operators)")?;
    if at.start >= a.states.len() {
        return Err(format!("the start state {} is out of range", at.start));
    }
    if at.subdivision.windows(2).any(|w| w[0] >= w[1]) {
        return Err("the subdivision operators are not listed in increasing order".into());
    }
    let mut out = vec![Vec::new(); a.states.len()];
    for &o in &at.subdivision {
        let op = a
            .operators
            .get(o)
            .ok_or_else(|| format!("subdivision operator {o} out of range"))?;
        out[op.to].push(o);
    }
    let mut reachable = vec![false; a.states.len()];
    reachable[at.start] = true;
    let mut stack = vec![at.start];
    while let Some(q) = stack.pop() {
        for &o in &out[q] {
            let w = a.operators[o].from;
            if !reachable[w] {
                reachable[w] = true;
                stack.push(w);
            }
        }
    }
    Ok(Graph {
        out,
        start: at.start,
        reachable,
    })
}

/// The restriction of a barycentric `T` (m_q × m_w) to the differences of points, in the
/// coordinates `d = Σ_(i<m−1) d_i (e_i − e_(m−1))`: `A[i][j] = T[i][j] − T[i][m_w − 1]`.
fn restriction(k: &Field, t: &KMat) -> KMat {
    let (r, c) = (t.rows - 1, t.cols - 1);
    let mut data = Vec::with_capacity(r * c);
    for i in 0..r {
        for j in 0..c {
            data.push(k.sub(&t.data[i * t.cols + j], &t.data[i * t.cols + t.cols - 1]));
        }
    }
    KMat {
        rows: r,
        cols: c,
        data,
    }
}

/// The induced norm of `a` (`inf`: max row sum, `1`: max column sum) compared with 1: the
/// largest sum, exactly, when it is below 1.
fn norm_below_one(k: &Field, a: &KMat, inf: bool) -> Result<Option<P>, String> {
    let (outer, inner) = match inf {
        true => (a.rows, a.cols),
        false => (a.cols, a.rows),
    };
    let one = Field::rational(Q::one());
    let mut largest = P::new();
    for o in 0..outer {
        let mut s = P::new();
        for i in 0..inner {
            let x = match inf {
                true => &a.data[o * a.cols + i],
                false => &a.data[i * a.cols + o],
            };
            s = field::add(&s, &k.abs(x)?);
        }
        if k.sign(&k.sub(&s, &one))? >= 0 {
            return Ok(None);
        }
        if k.sign(&k.sub(&s, &largest))? > 0 {
            largest = s;
        }
    }
    Ok(Some(largest))
}

/// The step `contraction`.
pub(super) fn check_contraction(a: &AutomatonClaim, s: &ContractionStep) -> Checked {
    let k = Field::of(a)?;
    let ops = instance(&k, a, &s.instance)?;
    constraints_hold(&k, a, &ops).map_err(|e| format!("the instance: {e}"))?;
    let g = graph(a)?;
    let inf = match s.norm.as_str() {
        "inf" => true,
        "1" => false,
        other => return Err(format!("unknown norm `{other}` (inf or 1)")),
    };
    if s.walks.len() > MAX_WALKS {
        return Err(format!(
            "{} walks: the checker reads at most {MAX_WALKS}",
            s.walks.len()
        ));
    }
    let subdivision: BTreeSet<usize> = g.out.iter().flatten().copied().collect();
    // The walks as paths, grouped by their first state.
    let mut leaves: BTreeSet<&[usize]> = BTreeSet::new();
    let mut inner: BTreeSet<(usize, &[usize])> = BTreeSet::new();
    for (n, w) in s.walks.iter().enumerate() {
        if w.is_empty() || w.len() > MAX_WALK_LEN {
            return Err(format!(
                "walk {n} has length {}, not in 1..={MAX_WALK_LEN}",
                w.len()
            ));
        }
        for (i, &o) in w.iter().enumerate() {
            if !subdivision.contains(&o) {
                return Err(format!(
                    "walk {n}: operator {o} is not a subdivision operator"
                ));
            }
            if i > 0 && a.operators[o].to != a.operators[w[i - 1]].from {
                return Err(format!(
                    "walk {n}: {} does not start where {} ends",
                    a.operators[o].name,
                    a.operators[w[i - 1]].name
                ));
            }
        }
        if !g.reachable[a.operators[w[0]].to] {
            return Err(format!(
                "walk {n} starts at a state the start does not reach"
            ));
        }
        if !leaves.insert(w.as_slice()) {
            return Err(format!("walk {n} is listed twice"));
        }
        for l in 0..w.len() {
            inner.insert((a.operators[w[0]].to, &w[..l]));
        }
    }
    // Prefix-free: no walk is a proper prefix of another.
    for &(_, p) in &inner {
        if !p.is_empty() && leaves.contains(p) {
            return Err(format!(
                "the walk {} is a prefix of another walk: the walks are not a prefix code",
                names(a, p)
            ));
        }
    }
    // Complete: from every reachable state, every node of the tree continues along every
    // subdivision operator out of the state it ends in, into a walk or into the tree.
    let reached: Vec<usize> = (0..a.states.len()).filter(|&q| g.reachable[q]).collect();
    for &q in &reached {
        if !g.out[q].is_empty() && !inner.contains(&(q, &[][..])) {
            return Err(format!(
                "no walk starts at state {}, which the start reaches and which has subdivision operators",
                a.states[q].name
            ));
        }
    }
    for &(q, p) in &inner {
        let end = p.last().map_or(q, |&o| a.operators[o].from);
        for &o in &g.out[end] {
            let mut next = p.to_vec();
            next.push(o);
            // A walk into a state without subdivision operators ends there: no infinite walk
            // continues it.
            let dead_end = g.out[a.operators[o].from].is_empty();
            if !dead_end
                && !leaves.contains(next.as_slice())
                && !inner.contains(&(q, next.as_slice()))
            {
                return Err(format!(
                    "the walks from state {} are not complete: the walk {} is neither listed nor extended",
                    a.states[q].name,
                    names(a, &next)
                ));
            }
        }
    }
    // Every operator on a walk is barycentric; every walk's product has norm below 1.
    let used: BTreeSet<usize> = s.walks.iter().flatten().copied().collect();
    let mut restricted = BTreeMap::new();
    for &o in &used {
        if !barycentric(&k, &ops[o]) {
            return Err(format!(
                "operator {} is not barycentric: it need not map differences of points to differences",
                a.operators[o].name
            ));
        }
        restricted.insert(o, restriction(&k, &ops[o]));
    }
    let mut worst = P::new();
    let mut depth = 0;
    for w in &s.walks {
        let first = a.operators[w[0]].to;
        let mut p = Field::identity(a.states[first].dim - 1);
        for o in w {
            p = k.matmul(&p, &restricted[o])?;
        }
        match norm_below_one(&k, &p, inf)? {
            Some(c) => {
                if k.sign(&k.sub(&c, &worst))? > 0 {
                    worst = c;
                }
            }
            None => {
                return Err(format!(
                "the product of the walk {} has {}-norm at least 1 on the differences of points",
                names(a, w),
                s.norm
            ))
            }
        }
        depth = depth.max(w.len());
    }
    let bound = match worst.len() <= 1 {
        true => worst.first().cloned().unwrap_or_else(Q::zero).to_string(),
        false => {
            // An upper bound of four decimals, rounded up (still below 1: the enclosure is
            // finer than the gap to 1 whenever the ceiling reaches 1, the exact test decided).
            let (_, hi) = enclose(&k, &worst, 20)?;
            let up = (hi * Q::from_integer(10_000.into())).ceil() / Q::from_integer(10_000.into());
            match up < Q::one() {
                true => format!("{} (rounded up)", decimal(&up, 4)),
                false => "a number below 1".into(),
            }
        }
    };
    Ok((
        format!(
            "{} of at most {} form a complete prefix code from each of the {}; every operator on them is barycentric and every walk's product on the differences of points has {}-norm ≤ {bound} < 1 (exact in {}), for the instance {}: every infinite walk contracts",
            super::counted(s.walks.len(), "walk", "walks"),
            super::counted(depth, "operator", "operators"),
            super::counted(reached.len(), "reachable state", "reachable states"),
            if inf { "∞" } else { "1" },
            if a.field.is_some() { "K" } else { "Q" },
            match s.instance.is_empty() {
                true => "the claim gives".to_string(),
                false => format!("completed by the step's values of {} (every constraint holds)", super::counted(s.instance.len(), "unknown operator", "unknown operators")),
            }
        ),
        match s.instance.is_empty() {
            true => "contraction: every infinite walk of the control graph contracts: the attractor is defined".to_string(),
            false => "contraction: every infinite walk of the control graph contracts for the instance the step completes (its unknown operators given, every constraint holding): that instance's attractor is defined".to_string(),
        },
    ))
}

fn names(a: &AutomatonClaim, w: &[usize]) -> String {
    w.iter()
        .map(|&o| a.operators.get(o).map_or("?", |x| x.name.as_str()))
        .collect::<Vec<_>>()
        .join(" · ")
}

/// The strongly connected parts of the reachable control graph that hold a cycle, each sorted,
/// ordered by smallest state (iterative Kosaraju).
fn cyclic_parts(a: &AutomatonClaim, g: &Graph) -> Vec<Vec<usize>> {
    let n = a.states.len();
    let succ: Vec<Vec<usize>> = (0..n)
        .map(|q| g.out[q].iter().map(|&o| a.operators[o].from).collect())
        .collect();
    let mut pred = vec![Vec::new(); n];
    for (q, s) in succ.iter().enumerate() {
        for &w in s {
            pred[w].push(q);
        }
    }
    // First pass: finishing order.
    let mut seen = vec![false; n];
    let mut order = Vec::new();
    for r in (0..n).filter(|&q| g.reachable[q]) {
        if seen[r] {
            continue;
        }
        seen[r] = true;
        let mut stack = vec![(r, 0usize)];
        while let Some((v, i)) = stack.pop() {
            if i < succ[v].len() {
                stack.push((v, i + 1));
                let w = succ[v][i];
                if !seen[w] {
                    seen[w] = true;
                    stack.push((w, 0));
                }
            } else {
                order.push(v);
            }
        }
    }
    // Second pass on the reversed graph.
    let mut part = vec![usize::MAX; n];
    let mut parts = Vec::new();
    for &r in order.iter().rev() {
        if part[r] != usize::MAX {
            continue;
        }
        let id = parts.len();
        let mut members = vec![r];
        part[r] = id;
        let mut stack = vec![r];
        while let Some(v) = stack.pop() {
            for &w in &pred[v] {
                if g.reachable[w] && part[w] == usize::MAX {
                    part[w] = id;
                    members.push(w);
                    stack.push(w);
                }
            }
        }
        members.sort_unstable();
        parts.push(members);
    }
    let mut out: Vec<Vec<usize>> = parts
        .into_iter()
        .filter(|c| c.len() > 1 || succ[c[0]].contains(&c[0]))
        .collect();
    out.sort();
    out
}

/// The frames: the start state's points (a `space × m` matrix, columns are points), then
/// `F_w = F_q·T` along the first subdivision operator reaching w breadth first (operators of a
/// state in index order).
fn frames(
    k: &Field,
    a: &AutomatonClaim,
    g: &Graph,
    ops: &[KMat],
) -> Result<Vec<Option<KMat>>, String> {
    let at = a.attractor.as_ref().ok_or("the claim has no attractor")?;
    let m = at.points.len();
    let space = at.points.first().map_or(0, Vec::len);
    if m != a.states[g.start].dim
        || !(1..=3).contains(&space)
        || at.points.iter().any(|p| p.len() != space)
    {
        return Err(format!(
            "the attractor's points: {m} points of the start state's {} in a space of dimension 1 to 3, all of one dimension",
            a.states[g.start].dim
        ));
    }
    let mut data = vec![P::new(); space * m];
    for (j, p) in at.points.iter().enumerate() {
        for (d, x) in p.iter().enumerate() {
            data[d * m + j] = k.element(x)?;
        }
    }
    let mut frames = vec![None; a.states.len()];
    frames[g.start] = Some(KMat {
        rows: space,
        cols: m,
        data,
    });
    let mut queue = VecDeque::from([g.start]);
    while let Some(q) = queue.pop_front() {
        for &o in &g.out[q] {
            let w = a.operators[o].from;
            if frames[w].is_none() {
                let f = k.matmul(frames[q].as_ref().expect("visited"), &ops[o])?;
                frames[w] = Some(f);
                queue.push_back(w);
            }
        }
    }
    Ok(frames)
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

fn power(k: &Field, x: &[Q], e: u32) -> P {
    let mut acc = Field::rational(Q::one());
    for _ in 0..e {
        acc = k.mul(&acc, x);
    }
    acc
}

/// `det(I − M(u))` for `M(u)_(i,j) = Σ u^k` over the exponents of the operators from member i
/// to member j, by interpolation at `u = 0, 1, …, n·max k` (Newton's divided differences).
fn part_polynomial(n: usize, entries: &[Vec<Vec<u32>>]) -> Result<P, String> {
    let top = entries
        .iter()
        .flatten()
        .flatten()
        .copied()
        .max()
        .unwrap_or(0) as usize;
    let deg = n * top;
    super::within_work(
        "the determinant polynomial of a part",
        ((deg + 1) * n * n * n) as u128 * 16,
    )?;
    let xs: Vec<Q> = (0..=deg).map(|i| Q::from_integer(i.into())).collect();
    let ys: Vec<Q> = xs
        .iter()
        .map(|u| {
            let mut m = vec![vec![Q::zero(); n]; n];
            for i in 0..n {
                for j in 0..n {
                    let s: Q = entries[i][j]
                        .iter()
                        .map(|&e| num_traits::pow(u.clone(), e as usize))
                        .sum();
                    m[i][j] = if i == j { Q::one() - s } else { -s };
                }
            }
            det(m)
        })
        .collect();
    let mut coef = ys;
    for j in 1..xs.len() {
        for i in (j..xs.len()).rev() {
            coef[i] = (&coef[i] - &coef[i - 1]) / (&xs[i] - &xs[i - j]);
        }
    }
    let mut p = vec![coef[xs.len() - 1].clone()];
    for i in (0..xs.len() - 1).rev() {
        p = field::add(
            &field::mul(&p, &[-xs[i].clone(), Q::one()]),
            &[coef[i].clone()],
        );
    }
    Ok(field::trim(p))
}

fn det(mut m: Vec<Vec<Q>>) -> Q {
    let n = m.len();
    let mut d = Q::one();
    for c in 0..n {
        let Some(p) = (c..n).find(|&r| !m[r][c].is_zero()) else {
            return Q::zero();
        };
        if p != c {
            m.swap(p, c);
            d = -d;
        }
        let piv = m[c][c].clone();
        d *= &piv;
        let row = m[c].clone();
        for r in m.iter_mut().skip(c + 1) {
            let f = &r[c] / &piv;
            if !f.is_zero() {
                for (x, y) in r.iter_mut().zip(&row).skip(c) {
                    *x -= &f * y;
                }
            }
        }
    }
    d
}

/// The number of distinct roots of `p` in `(a, b]` (Sturm, on the squarefree part).
fn roots_in(p: &[Q], a: &Q, b: &Q) -> usize {
    let (squarefree, _) = field::divide(p, &field::gcd(p, &field::derivative(p)));
    if squarefree.len() < 2 {
        return 0;
    }
    // A squarefree polynomial always has its chain; an empty one counts no root.
    let chain = field::sturm_chain(&squarefree).unwrap_or_default();
    field::sign_changes(&chain, a).saturating_sub(field::sign_changes(&chain, b))
}

/// Rational bounds `lo ≤ x ≤ hi` of an element of K with `hi − lo ≤ 2^−bits`, by bisection on
/// exact sign tests.
fn enclose(k: &Field, x: &[Q], bits: u64) -> Result<(Q, Q), String> {
    if x.len() <= 1 {
        let v = x.first().cloned().unwrap_or_else(Q::zero);
        return Ok((v.clone(), v));
    }
    // A first bound: |x| ≤ 2^e by doubling.
    let mut e = Q::one();
    while k.sign(&k.sub(&field::scale(x, &Q::one()), &[e.clone()]))? > 0
        || k.sign(&field::add(x, &[e.clone()]))? < 0
    {
        e *= Q::from_integer(2.into());
        super::within_work("an enclosure in K", 64)?;
    }
    let (mut lo, mut hi) = (-e.clone(), e);
    let width = Q::new(BigInt::one(), BigInt::one() << bits);
    while &hi - &lo > width {
        super::within_work("an enclosure in K", 64)?;
        let mid = (&lo + &hi) / Q::from_integer(2.into());
        match k.sign(&k.sub(x, std::slice::from_ref(&mid)))? {
            0 => return Ok((mid.clone(), mid)),
            s if s > 0 => lo = mid,
            _ => hi = mid,
        }
    }
    Ok((lo, hi))
}

/// Rational bounds of the root `u` with width at most `2^−bits`, by bisection (Sturm).
fn enclose_root(u: &Root, bits: u64) -> Result<(Q, Q), String> {
    let (mut lo, mut hi) = (u.lo.clone(), u.hi.clone());
    let width = Q::new(BigInt::one(), BigInt::one() << bits);
    while &hi - &lo > width {
        super::within_work("an enclosure of u*", 64)?;
        let mid = (&lo + &hi) / Q::from_integer(2.into());
        match u.cmp_rational(&mid) {
            std::cmp::Ordering::Equal => return Ok((mid.clone(), mid)),
            std::cmp::Ordering::Greater => lo = mid,
            std::cmp::Ordering::Less => hi = mid,
        }
    }
    Ok((lo, hi))
}

/// `(lo, hi)` integers with `lo·2^−b ≤ atanh(p/q) ≤ hi·2^−b`, for `|p/q| ≤ 1/2`. atanh is odd,
/// so the series `Σ a^(2n+1)/(2n+1)` is summed for `a = |p/q|` in fixed point with `b + 8`
/// bits, every number kept to that width: `a` between `A/2^B` and `(A + 1)/2^B`, every term
/// positive and increasing in `a`; the lower sum truncates the series with powers and terms
/// rounded down, the upper sum rounds them up and adds the tail after the first term below one
/// unit, at most `term/(1 − a²) ≤ 4/3` units.
fn atanh_bounds(p: &BigInt, q: &BigInt, b: u64) -> (BigInt, BigInt) {
    let guard = b + 8;
    let a_lo = (p.abs() << guard).div_floor(q);
    let a_hi = &a_lo + 1;
    let sum = |a: &BigInt, up: bool| -> BigInt {
        let a2 = a * a;
        let mut power = a.clone();
        let mut total = BigInt::zero();
        let mut m = 1u64;
        loop {
            let d = BigInt::from(m);
            let term = match up {
                true => -((-&power).div_floor(&d)),
                false => power.div_floor(&d),
            };
            if term.is_zero() || (up && term <= BigInt::one()) {
                total += match up {
                    true => BigInt::from(2),
                    false => BigInt::zero(),
                };
                break;
            }
            total += term;
            let next = &power * &a2;
            power = match up {
                true => -((-next) >> (2 * guard)),
                false => next >> (2 * guard),
            };
            m += 2;
        }
        total
    };
    let (lo, hi) = (sum(&a_lo, false), sum(&a_hi, true));
    // Back from b + 8 bits to b, outward.
    let (lo, hi) = (lo >> 8u32, -((-hi) >> 8u32));
    match p.is_negative() {
        true => (-hi, -lo),
        false => (lo, hi),
    }
}

/// Bounds of `ln x` for a rational `x > 0`, as `(lo, hi)` rationals with width about
/// `2^−(b−8)`: `x = 2^e·x'`, `x' ∈ [1/2, 2)`… `ln x = e·ln 2 + 2·atanh((x' − 1)/(x' + 1))`,
/// `ln 2 = 2·atanh(1/3)`.
fn ln_bounds(x: &Q, b: u64) -> (Q, Q) {
    let e = x.numer().bits() as i64 - x.denom().bits() as i64;
    let xr = match e >= 0 {
        true => x / Q::from_integer(BigInt::one() << e as u64),
        false => x * Q::from_integer(BigInt::one() << (-e) as u64),
    };
    let y = (&xr - Q::one()) / (&xr + Q::one());
    let (alo, ahi) = atanh_bounds(y.numer(), y.denom(), b);
    let (llo, lhi) = atanh_bounds(&BigInt::one(), &BigInt::from(3), b);
    let scale = Q::from_integer(BigInt::one() << b);
    let two = Q::from_integer(2.into());
    let ee = Q::from_integer(e.into());
    let (l2lo, l2hi) = (
        &two * Q::from_integer(llo) / &scale,
        &two * Q::from_integer(lhi) / &scale,
    );
    let (elo, ehi) = match e >= 0 {
        true => (&ee * &l2lo, &ee * &l2hi),
        false => (&ee * &l2hi, &ee * &l2lo),
    };
    (
        elo + &two * Q::from_integer(alo) / &scale,
        ehi + &two * Q::from_integer(ahi) / &scale,
    )
}

/// One part re-derived: its σ (in K), u* and the rational value when claimed.
struct PartValue {
    sigma: P,
    u: Root,
    rational: Option<Q>,
    /// What the step's open-set witness proves.
    open_set: OpenSet,
}

/// The open-set condition of a part, as its witness proves it.
enum OpenSet {
    /// No witness: not proved either way.
    Unproved,
    /// Holds: convex sets in the charts.
    Convex,
    /// Holds: a closed set of this many neighbour maps without the identity, in these
    /// coordinates.
    Neighbour(usize, &'static str),
    /// Fails: the two words (named) with the same map.
    Fails(String, String),
}

fn check_part(
    k: &Field,
    a: &AutomatonClaim,
    g: &Graph,
    ops: &[KMat],
    frames: &[Option<KMat>],
    members: &[usize],
    p: &SimilarityPart,
) -> Result<PartValue, String> {
    let label = || {
        members
            .iter()
            .map(|&q| a.states[q].name.as_str())
            .collect::<Vec<_>>()
            .join(", ")
    };
    let sigma = k.element(&p.sigma)?;
    if k.sign(&sigma)? <= 0 || k.sign(&k.sub(&sigma, &Field::rational(Q::one())))? >= 0 {
        return Err(format!("part {{{}}}: σ is not in (0, 1)", label()));
    }
    // The operators inside the part, with their claimed exponents.
    let inside: Vec<usize> = members
        .iter()
        .flat_map(|&q| g.out[q].iter().copied())
        .filter(|&o| members.binary_search(&a.operators[o].from).is_ok())
        .collect::<BTreeSet<_>>()
        .into_iter()
        .collect();
    let listed: Vec<usize> = p.exponents.iter().map(|(o, _)| *o).collect();
    if listed != inside {
        return Err(format!(
            "part {{{}}}: the exponents must list exactly the part's operators, in increasing order",
            label()
        ));
    }
    let n = members.len();
    let mut entries = vec![vec![Vec::new(); n]; n];
    for &(o, e) in &p.exponents {
        if e > 128 {
            return Err(format!(
                "part {{{}}}: operator {}'s exponent {e} is above 128",
                label(),
                a.operators[o].name
            ));
        }
        let (q, w) = (a.operators[o].to, a.operators[o].from);
        let (fq, fw) = (
            frames[q].as_ref().expect("reachable"),
            frames[w].as_ref().expect("reachable"),
        );
        if fw.cols < 2 {
            return Err(format!(
                "part {{{}}}: state {} has one point",
                label(),
                a.states[w].name
            ));
        }
        let gw = gram(k, fw);
        if gw.data.iter().all(|x| k.is_zero(x)) {
            return Err(format!(
                "part {{{}}}: the points of state {}'s frame coincide",
                label(),
                a.states[w].name
            ));
        }
        let image = gram(k, &k.matmul(fq, &ops[o])?);
        let r2 = power(k, &sigma, e);
        let scaled = KMat {
            data: gw.data.iter().map(|x| k.mul(x, &r2)).collect(),
            ..gw
        };
        if !k.equal(&image, &scaled) {
            return Err(format!(
                "part {{{}}}: operator {} is not a similitude of squared ratio σ^{e} on the frames (the Gram matrices differ)",
                label(),
                a.operators[o].name
            ));
        }
        let (i, j) = (
            members.binary_search(&q).expect("member"),
            members.binary_search(&w).expect("member"),
        );
        entries[i][j].push(e);
    }
    // M(0) counts the operators of ratio 1 (the first operator reaching a state fixes that
    // state's frame, so it has ratio 1): they must form no cycle, i.e. M(0) is nilpotent and
    // ρ(M(0)) = 0, where the argument below starts.
    let m0: Vec<Vec<BigInt>> = entries
        .iter()
        .map(|r| {
            r.iter()
                .map(|es| BigInt::from(es.iter().filter(|&&e| e == 0).count()))
                .collect()
        })
        .collect();
    let mut pw = m0.clone();
    for _ in 1..n {
        pw = (0..n)
            .map(|i| {
                (0..n)
                    .map(|j| (0..n).map(|t| &pw[i][t] * &m0[t][j]).sum())
                    .collect()
            })
            .collect();
    }
    if pw.iter().flatten().any(|x| !x.is_zero()) {
        return Err(format!(
            "part {{{}}}: the operators of exponent 0 (ratio 1) form a cycle",
            label()
        ));
    }
    let d = part_polynomial(n, &entries)?;
    let u = Root::isolate(&p.u.poly, &p.u.lo, &p.u.hi, "u*")?;
    if !u.is_zero(&d) {
        return Err(format!(
            "part {{{}}}: u* is not a root of det(I − M(u))",
            label()
        ));
    }
    // u* as an element of K, when the step gives it: a root of u*'s polynomial inside its
    // isolating interval is u* itself.
    let u_field = match &p.u_field {
        None => None,
        Some(c) => {
            let y = k.element(c)?;
            let poly: Vec<Q> = p.u.poly.iter().map(|x| rat(x)).collect::<Result<_, _>>()?;
            let value = poly.iter().rev().fold(P::new(), |acc, c| {
                field::add(&k.mul(&acc, &y), &Field::rational(c.clone()))
            });
            let inside = k.sign(&k.sub(&y, &Field::rational(u.lo.clone())))? > 0
                && k.sign(&k.sub(&y, &Field::rational(u.hi.clone())))? < 0;
            if !k.is_zero(&value) || !inside {
                return Err(format!(
                    "part {{{}}}: the element of K given for u* is not u*",
                    label()
                ));
            }
            Some(y)
        }
    };
    if u.lo.is_negative() || u.cmp_rational(&Q::one()) == std::cmp::Ordering::Greater {
        return Err(format!("part {{{}}}: u* is not in (0, 1]", label()));
    }
    if roots_in(&d, &Q::zero(), &u.hi) != 1 {
        return Err(format!(
            "part {{{}}}: det(I − M(u)) has another root in (0, {}]: u* is not shown to be its smallest positive root",
            label(),
            u.hi
        ));
    }
    let rational = match &p.rational {
        None => None,
        Some(s) => {
            let v = rat(s)?;
            if v.is_negative() {
                return Err(format!("part {{{}}}: a negative dimension", label()));
            }
            // s = a/b iff u^(2b) = σ^a.
            let (num, den) = (v.numer().clone(), v.denom().clone());
            let (an, bn): (u32, u32) = match (u32::try_from(&num), u32::try_from(&den)) {
                (Ok(x), Ok(y)) if x <= 4096 && y <= 4096 => (x, y),
                _ => {
                    return Err(format!(
                        "part {{{}}}: the rational dimension {v} is too large",
                        label()
                    ))
                }
            };
            let sa = power(k, &sigma, an);
            let holds = match (u.p.len() == 2, sa.len() <= 1) {
                _ if u_field.is_some() => {
                    let ub = power(k, u_field.as_ref().expect("given"), 2 * bn);
                    k.is_zero(&k.sub(&ub, &sa))
                }
                (true, _) => {
                    let ur = u.lo.clone();
                    let ub = power(k, &[ur], 2 * bn);
                    k.is_zero(&k.sub(&ub, &sa))
                }
                (false, true) => {
                    // u^(2b) − σ^a vanishes at u (σ^a rational).
                    let mut z = vec![Q::zero(); 2 * bn as usize + 1];
                    z[2 * bn as usize] = Q::one();
                    z[0] = -sa.first().cloned().unwrap_or_else(Q::zero);
                    u.is_zero(&z)
                }
                (false, false) => {
                    return Err(format!(
                        "part {{{}}}: a rational dimension with u* and σ both irrational needs u* as an element of K (`u_field`)",
                        label()
                    ))
                }
            };
            if !holds {
                return Err(format!(
                    "part {{{}}}: the dimension is not {v} (u*^{} ≠ σ^{an})",
                    label(),
                    2 * bn
                ));
            }
            Some(v)
        }
    };
    let open_set = match (&p.open_set, &p.neighbour_maps) {
        (None, None) => OpenSet::Unproved,
        (Some(sets), None) => {
            check_open_set(k, a, ops, frames, members, &inside, sets)
                .map_err(|e| format!("part {{{}}}: the open-set witness: {e}", label()))?;
            OpenSet::Convex
        }
        (None, Some(w)) => {
            match neighbour::check_neighbour_maps(k, a, ops, frames, members, &inside, w)
                .map_err(|e| format!("part {{{}}}: the neighbour maps: {e}", label()))?
            {
                Decided::Holds(n, coordinates) => OpenSet::Neighbour(n, coordinates),
                Decided::Fails(u, v) => OpenSet::Fails(u, v),
            }
        }
        (Some(_), Some(_)) => {
            return Err(format!(
                "part {{{}}}: two open-set witnesses (convex sets and neighbour maps): give one",
                label()
            ))
        }
    };
    Ok(PartValue {
        sigma,
        u,
        rational,
        open_set,
    })
}

/// The dimension d of a part's charts: every state of the part has m = d + 1 points, 2 or 3.
fn chart_dimension(a: &AutomatonClaim, members: &[usize]) -> Result<usize, String> {
    let m = a.states[members[0]].dim;
    if !(2..=3).contains(&m) || members.iter().any(|&q| a.states[q].dim != m) {
        return Err("the charts need every state of the part with 2 or with 3 points".into());
    }
    Ok(m - 1)
}

/// Every state's frame is non-degenerate (its d + 1 points affinely independent: the Gram
/// determinant of its edge vectors is not 0), so its chart is an affine bijection onto the
/// affine hull of its points.
fn independent_frames(
    k: &Field,
    a: &AutomatonClaim,
    frames: &[Option<KMat>],
    members: &[usize],
    d: usize,
) -> Result<(), String> {
    for &q in members {
        let g = gram(k, frames[q].as_ref().expect("reachable"));
        let det = match d {
            1 => g.data[0].clone(),
            _ => k.sub(
                &k.mul(&g.data[0], &g.data[3]),
                &k.mul(&g.data[1], &g.data[2]),
            ),
        };
        if k.is_zero(&det) {
            return Err(format!(
                "the points of state {} are affinely dependent",
                a.states[q].name
            ));
        }
    }
    Ok(())
}

/// The part's frames are non-degenerate and its operators barycentric; returns d.
pub(super) fn charts(
    k: &Field,
    a: &AutomatonClaim,
    ops: &[KMat],
    frames: &[Option<KMat>],
    members: &[usize],
    inside: &[usize],
) -> Result<usize, String> {
    let d = chart_dimension(a, members)?;
    independent_frames(k, a, frames, members, d)?;
    if let Some(&o) = inside.iter().find(|&&o| !barycentric(k, &ops[o])) {
        return Err(format!(
            "operator {} is not barycentric (a column does not sum to 1): it has no chart map",
            a.operators[o].name
        ));
    }
    Ok(d)
}

/// The sign of `(b − a) × (c − a)` in K.
fn turn(k: &Field, a: &[P], b: &[P], c: &[P]) -> Result<i32, String> {
    let l = k.mul(&k.sub(&b[0], &a[0]), &k.sub(&c[1], &a[1]));
    let r = k.mul(&k.sub(&b[1], &a[1]), &k.sub(&c[0], &a[0]));
    k.sign(&k.sub(&l, &r))
}

/// The open-set condition for one part, from convex sets given in the states' charts: each
/// state's frame is non-degenerate (its chart is an affine bijection onto the affine hull of its
/// points), every operator of the part is barycentric (only then is its action on control points
/// an affine map of the charts, read off rows 1..d), each set is a strictly convex polygon (an interval in one dimension), every
/// operator's chart map is injective and maps its column state's set into its row state's set
/// (closed, vertex by vertex: then the open interiors go into the open interiors), and the
/// images out of one state have disjoint interiors (a separating edge line).
fn check_open_set(
    k: &Field,
    a: &AutomatonClaim,
    ops: &[KMat],
    frames: &[Option<KMat>],
    members: &[usize],
    inside: &[usize],
    sets: &[Vec<Vec<FieldCoords>>],
) -> Result<(), String> {
    let d = charts(k, a, ops, frames, members, inside)?;
    if sets.len() != members.len() {
        return Err(format!("{} sets for {} states", sets.len(), members.len()));
    }
    let mut polys: Vec<Vec<Vec<P>>> = Vec::with_capacity(sets.len());
    for (set, &q) in sets.iter().zip(members) {
        if set.len() > 4096 || set.iter().any(|v| v.len() != d) {
            return Err(format!(
                "the set of state {} is not a list of points of {d} coordinates",
                a.states[q].name
            ));
        }
        let pts: Vec<Vec<P>> = set
            .iter()
            .map(|v| v.iter().map(|x| k.element(x)).collect())
            .collect::<Result<_, _>>()?;
        let ok = match d {
            1 => pts.len() == 2 && k.sign(&k.sub(&pts[1][0], &pts[0][0]))? > 0,
            _ => {
                let n = pts.len();
                n >= 3
                    && (0..n).try_fold(true, |acc, i| {
                        Ok::<_, String>(
                            acc && turn(k, &pts[i], &pts[(i + 1) % n], &pts[(i + 2) % n])? > 0,
                        )
                    })?
            }
        };
        if !ok {
            return Err(format!(
                "the set of state {} is not {}",
                a.states[q].name,
                match d {
                    1 => "an interval with increasing ends",
                    _ => "a strictly convex polygon, counter-clockwise",
                }
            ));
        }
        polys.push(pts);
    }
    let pos = |q: usize| members.binary_search(&q).expect("member");
    // The image of the column state's set under each operator's chart map.
    let mut images: Vec<(usize, Vec<Vec<P>>)> = Vec::with_capacity(inside.len());
    for &o in inside {
        let (q, w) = (a.operators[o].to, a.operators[o].from);
        let t = &ops[o];
        let at = |r: usize, c: usize| &t.data[r * t.cols + c];
        // x ↦ A·x + b with A[r−1][j−1] = T[r][j] − T[r][0], b[r−1] = T[r][0].
        let amat: Vec<Vec<P>> = (1..=d)
            .map(|r| (1..=d).map(|j| k.sub(at(r, j), at(r, 0))).collect())
            .collect();
        let det = match d {
            1 => amat[0][0].clone(),
            _ => k.sub(
                &k.mul(&amat[0][0], &amat[1][1]),
                &k.mul(&amat[0][1], &amat[1][0]),
            ),
        };
        let sign = k.sign(&det)?;
        if sign == 0 {
            return Err(format!(
                "{}'s chart map is not injective",
                a.operators[o].name
            ));
        }
        let mut img: Vec<Vec<P>> = polys[pos(w)]
            .iter()
            .map(|x| {
                (0..d)
                    .map(|r| {
                        (0..d).fold(at(r + 1, 0).clone(), |acc, j| {
                            field::add(&acc, &k.mul(&amat[r][j], &x[j]))
                        })
                    })
                    .collect()
            })
            .collect();
        if sign < 0 {
            img.reverse();
        }
        // Inside the row state's closed set.
        let outer = &polys[pos(q)];
        for v in &img {
            let inside_outer = match d {
                1 => {
                    k.sign(&k.sub(&v[0], &outer[0][0]))? >= 0
                        && k.sign(&k.sub(&outer[1][0], &v[0]))? >= 0
                }
                _ => {
                    let n = outer.len();
                    (0..n).try_fold(true, |acc, i| {
                        Ok::<_, String>(acc && turn(k, &outer[i], &outer[(i + 1) % n], v)? >= 0)
                    })?
                }
            };
            if !inside_outer {
                return Err(format!(
                    "the image of state {}'s set under {} leaves state {}'s set",
                    a.states[w].name, a.operators[o].name, a.states[q].name
                ));
            }
        }
        images.push((q, img));
    }
    // Pieces out of one state: disjoint interiors.
    let separates = |p: &[Vec<P>], other: &[Vec<P>]| -> Result<bool, String> {
        let n = p.len();
        for i in 0..n {
            let mut all = true;
            for v in other {
                if turn(k, &p[i], &p[(i + 1) % n], v)? > 0 {
                    all = false;
                    break;
                }
            }
            if all {
                return Ok(true);
            }
        }
        Ok(false)
    };
    for (i, (q, x)) in images.iter().enumerate() {
        for (j, (r, y)) in images.iter().enumerate().skip(i + 1) {
            if q != r {
                continue;
            }
            let disjoint = match d {
                1 => {
                    k.sign(&k.sub(&y[0][0], &x[1][0]))? >= 0
                        || k.sign(&k.sub(&x[0][0], &y[1][0]))? >= 0
                }
                _ => separates(x, y)? || separates(y, x)?,
            };
            if !disjoint {
                return Err(format!(
                    "the pieces of {} and {} out of state {} overlap (no separating edge)",
                    a.operators[inside[i]].name, a.operators[inside[j]].name, a.states[*q].name
                ));
            }
        }
    }
    Ok(())
}

/// Bounds of a part's dimension `s = 2·ln u*/ln σ` at `bits` bits.
fn dimension_bounds(k: &Field, v: &PartValue, bits: u64) -> Result<(Q, Q), String> {
    if let Some(r) = &v.rational {
        return Ok((r.clone(), r.clone()));
    }
    let (ulo, uhi) = enclose_root(&v.u, bits + 16)?;
    let (slo, shi) = enclose(k, &v.sigma, bits + 16)?;
    if !ulo.is_positive() || !slo.is_positive() || shi >= Q::one() {
        return Err("the enclosures of u* and σ are not inside (0, 1)".into());
    }
    super::within_work("logarithms", u128::from(bits) * u128::from(bits))?;
    // A = −ln u ∈ [−ln uhi, −ln ulo], B = −ln σ ∈ [−ln shi, −ln slo], s = 2A/B.
    let (a_lo, a_hi) = (-ln_bounds(&uhi, bits + 16).1, -ln_bounds(&ulo, bits + 16).0);
    let (b_lo, b_hi) = (-ln_bounds(&shi, bits + 16).1, -ln_bounds(&slo, bits + 16).0);
    if !b_lo.is_positive() {
        return Err("ln σ was not separated from 0".into());
    }
    let two = Q::from_integer(2.into());
    let a_lo = if a_lo.is_negative() { Q::zero() } else { a_lo };
    Ok((&two * a_lo / &b_hi, &two * a_hi / &b_lo))
}

/// The step `similarity-dimension`.
pub(super) fn check_similarity(a: &AutomatonClaim, s: &SimilarityStep) -> Checked {
    let k = Field::of(a)?;
    let ops = instance(&k, a, &s.instance)?;
    constraints_hold(&k, a, &ops).map_err(|e| format!("the instance: {e}"))?;
    let g = graph(a)?;
    let parts = cyclic_parts(a, &g);
    let listed: Vec<&Vec<usize>> = s.parts.iter().map(|p| &p.states).collect();
    if parts.iter().collect::<Vec<_>>() != listed {
        return Err(format!(
            "the parts must be the {} of the reachable control graph, ordered by smallest state",
            super::counted(
                parts.len(),
                "cyclic strongly connected part",
                "cyclic strongly connected parts"
            )
        ));
    }
    if parts.is_empty() {
        return Err("the control graph has no cycle: there is no similarity dimension".into());
    }
    let frames = frames(&k, a, &g, &ops)?;
    let values: Vec<PartValue> = parts
        .iter()
        .zip(&s.parts)
        .map(|(m, p)| check_part(&k, a, &g, &ops, &frames, m, p))
        .collect::<Result<_, _>>()?;
    // The digits of the largest value.
    if s.digits == 0 || s.digits > 1000 {
        return Err(format!("{} digits: not in 1..=1000", s.digits));
    }
    let claimed = super::parse_decimal(&s.decimal, s.digits)?;
    let ten = Q::from_integer(num_traits::pow(BigInt::from(10), s.digits));
    let (low, high) = (
        Q::from_integer(claimed.clone()) / &ten,
        Q::from_integer(claimed + 1) / &ten,
    );
    let mut bits = 64u64.max(4 * s.digits as u64);
    let decided = loop {
        let mut lo_max = Q::zero();
        let mut hi_max = Q::zero();
        for v in &values {
            let (l, h) = dimension_bounds(&k, v, bits)?;
            lo_max = lo_max.max(l);
            hi_max = hi_max.max(h);
        }
        if hi_max < low || lo_max >= high {
            return Err(format!(
                "the dimension is not {} (it lies in [{}, {}])",
                s.decimal,
                decimal(&lo_max, s.digits),
                decimal(&hi_max, s.digits)
            ));
        }
        if lo_max >= low && hi_max < high {
            break true;
        }
        if bits >= MAX_BITS {
            break false;
        }
        bits *= 2;
    };
    if !decided {
        return Err(format!(
            "the digits {} were not decided at {MAX_BITS} bits (a dimension on a decimal boundary must be claimed rational)",
            s.decimal
        ));
    }
    let forms: Vec<String> = values
        .iter()
        .zip(&parts)
        .map(|(v, m)| {
            let states: Vec<&str> = m.iter().map(|&q| a.states[q].name.as_str()).collect();
            let value = match &v.rational {
                Some(r) => r.to_string(),
                None if v.u.p.len() == 2 => format!(
                    "2·ln u*/ln σ with u* = {}, σ = {}",
                    v.u.lo,
                    coords_line(&v.sigma)
                ),
                None => format!(
                    "2·ln u*/ln σ, u* the root of {} in [{}, {}], σ = {}",
                    poly_line(&v.u.p),
                    v.u.lo,
                    v.u.hi,
                    coords_line(&v.sigma)
                ),
            };
            let witness = match &v.open_set {
                OpenSet::Neighbour(n, coordinates) => format!(
                    ", the open-set condition by {n} neighbour maps in the {coordinates} (a set closed under refinement, without the identity)"
                ),
                OpenSet::Fails(u, w) => format!(
                    ", the open-set condition fails: the words {u} and {w} have the same map"
                ),
                OpenSet::Convex | OpenSet::Unproved => String::new(),
            };
            format!("{{{}}}: s = {value}{witness}", states.join(", "))
        })
        .collect();
    let hausdorff = hausdorff(a, &parts, &values, &s.decimal);
    Ok((
        format!(
            "{}; every operator inside a part is a similitude of squared ratio σ^k on the frames, exactly in {}; u* is the smallest root of det(I − M(u)) in (0, 1] (Sturm), so ρ(M(u*)) = 1; {}; the largest is {}… ({} digits re-derived)",
            super::counted(parts.len(), "cyclic part", "cyclic parts"),
            if a.field.is_some() { "K" } else { "Q" },
            forms.join("; "),
            s.decimal,
            s.digits
        ),
        format!(
            "similarity dimension = {}… (Mauldin–Williams{}): {hausdorff}",
            s.decimal,
            match s.instance.is_empty() {
                true => "",
                false => ", of the instance the step completes",
            }
        ),
    ))
}

/// What the parts' open-set witnesses make of the similarity dimension.
fn hausdorff(
    a: &AutomatonClaim,
    parts: &[Vec<usize>],
    values: &[PartValue],
    decimal: &str,
) -> String {
    let label = |m: &[usize]| {
        m.iter()
            .map(|&q| a.states[q].name.as_str())
            .collect::<Vec<_>>()
            .join(", ")
    };
    let fails: Vec<String> = values
        .iter()
        .zip(parts)
        .filter(|(v, _)| matches!(v.open_set, OpenSet::Fails(..)))
        .map(|(_, m)| format!("part {{{}}}", label(m)))
        .collect();
    if !fails.is_empty() {
        return format!(
            "an upper bound of the Hausdorff dimension; the open-set condition fails in {} (two words from one state with different first operators have the same map, so their pieces coincide; checked exactly)",
            fails.join(", ")
        );
    }
    let means: Vec<&str> = values
        .iter()
        .map(|v| match v.open_set {
            OpenSet::Convex => Some("convex sets in the charts"),
            OpenSet::Neighbour(..) => Some(
                "neighbour maps, Bandt–Graf: a finite set closed under refinement, without the identity",
            ),
            _ => None,
        })
        .collect::<Option<Vec<_>>>()
        .unwrap_or_default();
    if means.is_empty() {
        return "an upper bound of the Hausdorff dimension; equal to it under the open-set condition, which this step does not prove".to_string();
    }
    let mut distinct = means.clone();
    distinct.sort_unstable();
    distinct.dedup();
    match parts.len() {
        1 => format!(
            "the open-set condition holds ({}, checked exactly), so the Hausdorff dimension of the attractor is {decimal}…",
            means[0]
        ),
        _ => format!(
            "the open-set condition holds in every part ({}, checked exactly): each part's attractor has Hausdorff dimension equal to its similarity dimension; the attractor's is at most the largest",
            match distinct.len() {
                1 => distinct[0].to_string(),
                _ => means
                    .iter()
                    .zip(parts)
                    .map(|(w, m)| format!("part {{{}}}: {w}", label(m)))
                    .collect::<Vec<_>>()
                    .join("; "),
            }
        ),
    }
}

fn decimal(x: &Q, digits: usize) -> String {
    let ten = num_traits::pow(BigInt::from(10), digits);
    let v = (x * Q::from_integer(ten)).floor().to_integer();
    let s = v.abs().to_string();
    let s = format!("{s:0>width$}", width = digits + 1);
    let (i, f) = s.split_at(s.len() - digits);
    format!("{}{i}.{f}", if v.is_negative() { "-" } else { "" })
}

fn poly_line(p: &[Q]) -> String {
    let c: Vec<String> = p.iter().map(Q::to_string).collect();
    super::claim::power_text(&c, "x", true)
}

fn coords_line(p: &[Q]) -> String {
    let c: Vec<String> = p.iter().map(Q::to_string).collect();
    super::claim::power_text(&c, "α", false)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn logarithms_are_enclosed() {
        // ln 2 = 0.693147180559945309417…, ln(1/27) = −3·ln 3 = −3.295836866004329074185…
        // (published constants): the enclosures lie inside these 18-digit brackets.
        let q = |n: i64, d: i64| Q::new(n.into(), d.into());
        let e18 = 1_000_000_000_000_000_000i64;
        let (lo, hi) = ln_bounds(&Q::from_integer(2.into()), 80);
        assert!(q(693_147_180_559_945_309, e18) <= lo && hi <= q(693_147_180_559_945_310, e18));
        assert!(&hi - &lo < Q::new(1.into(), (1i64 << 60).into()));
        let (lo, hi) = ln_bounds(&q(1, 27), 80);
        let e17 = 100_000_000_000_000_000i64;
        assert!(q(-329_583_686_600_432_908, e17) <= lo && hi <= q(-329_583_686_600_432_907, e17));
        // x = 1 exactly: ln 1 = 0 lies in the enclosure.
        let (lo, hi) = ln_bounds(&Q::one(), 80);
        assert!(lo <= Q::zero() && Q::zero() <= hi);
    }

    #[test]
    fn sturm_counts_distinct_roots() {
        // (x − 1/4)²·(x − 1/2) has two distinct roots in (0, 1], one in (0, 1/3].
        let q = |a: i64, b: i64| Q::new(a.into(), b.into());
        let p = field::mul(
            &field::mul(&[q(-1, 4), q(1, 1)], &[q(-1, 4), q(1, 1)]),
            &[q(-1, 2), q(1, 1)],
        );
        assert_eq!(roots_in(&p, &Q::zero(), &Q::one()), 2);
        assert_eq!(roots_in(&p, &Q::zero(), &q(1, 3)), 1);
    }
}
