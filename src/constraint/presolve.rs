//! Exact numbers with a machine-word fast path, and the presolve of [`crate::constraint::linsys`]: the
//! equations `x = c` and `a·x + b·y = c` are turned into facts about unknowns (fixed values and
//! affine links kept in a union-find forest) before any elimination.
//!
//! Written by hand: no crate offers exact sparse presolve; `Z`/`Q` exist because the BC-IFS
//! systems are millions of tiny numbers, where an allocation per `BigInt` operation dominates.
//!
//! # Facts and their provenance
//! Every unknown starts as a root. A row that, after substituting the current facts, has one
//! unknown fixes that root; with two unknowns it links the root of the smaller class below the
//! other (`child = f·parent + g`). Each fact stores the row that created it, an event time, the
//! coefficient of its unknown in the substituted row and (links) the original `f`. Links are never
//! rewritten in `orig_parent`; path compression only touches `parent/f/g`. So the derivation of
//! any substituted row can be replayed backwards, latest fact first, as a combination of original
//! rows ([`Presolve::combination`]): this is how conflict certificates are obtained. Only a
//! certificate reads the rows, coefficients and original parents and factors, so they are kept
//! only by a presolve made to track them; the solver makes one when a system proves inconsistent,
//! by replaying the same presolve.

use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::ToPrimitive;
use std::borrow::Cow;
use std::collections::BTreeMap;

/// An integer: `S` while it fits an `i64`, else boxed big (never `B` for a value that fits).
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum Z {
    S(i64),
    B(Box<BigInt>),
}

/// `gcd(a, b)` of two words, hardware 64-bit remainders (`gcd(0, b) = b`).
fn gcd_u64(mut a: u64, mut b: u64) -> u64 {
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a
}

fn gcd_u128(mut a: u128, mut b: u128) -> u128 {
    while b != 0 {
        if a <= u64::MAX as u128 && b <= u64::MAX as u128 {
            // Hardware 64-bit remainders are much cheaper than the 128-bit library routine.
            return gcd_u64(a as u64, b as u64) as u128;
        }
        (a, b) = (b, a % b);
    }
    a
}

impl Z {
    pub(crate) fn zero() -> Z {
        Z::S(0)
    }
    pub(crate) fn one() -> Z {
        Z::S(1)
    }
    pub(crate) fn from_i128(v: i128) -> Z {
        match i64::try_from(v) {
            Ok(s) => Z::S(s),
            Err(_) => Z::B(Box::new(BigInt::from(v))),
        }
    }
    pub(crate) fn from_big(b: BigInt) -> Z {
        match b.to_i64() {
            Some(s) => Z::S(s),
            None => Z::B(Box::new(b)),
        }
    }
    pub(crate) fn big(&self) -> BigInt {
        match self {
            Z::S(s) => BigInt::from(*s),
            Z::B(b) => (**b).clone(),
        }
    }
    pub(crate) fn is_zero(&self) -> bool {
        matches!(self, Z::S(0))
    }
    pub(crate) fn is_unit(&self) -> bool {
        matches!(self, Z::S(1) | Z::S(-1))
    }
    pub(crate) fn neg(&self) -> Z {
        match self {
            Z::S(s) => Z::from_i128(-(*s as i128)),
            Z::B(b) => Z::from_big(-(**b).clone()),
        }
    }
    pub(crate) fn mul(&self, o: &Z) -> Z {
        match (self, o) {
            (Z::S(a), Z::S(b)) => Z::from_i128(*a as i128 * *b as i128),
            _ => Z::from_big(self.big() * o.big()),
        }
    }
    /// `a·x − b·y`, the fraction-free elimination step.
    pub(crate) fn lin(a: &Z, x: &Z, b: &Z, y: &Z) -> Z {
        if let (Z::S(a), Z::S(x), Z::S(b), Z::S(y)) = (a, x, b, y) {
            // Each product is below 2^126 in magnitude, so the difference fits an i128.
            return Z::from_i128(*a as i128 * *x as i128 - *b as i128 * *y as i128);
        }
        Z::from_big(a.big() * x.big() - b.big() * y.big())
    }
    /// Non-negative gcd (`gcd(0, 0) = 0`).
    pub(crate) fn gcd(&self, o: &Z) -> Z {
        match (self, o) {
            (Z::S(a), Z::S(b)) => {
                Z::from_i128(gcd_u128(a.unsigned_abs() as u128, b.unsigned_abs() as u128) as i128)
            }
            _ => Z::from_big(self.big().gcd(&o.big())),
        }
    }
    /// Exact quotient (the caller guarantees divisibility).
    pub(crate) fn div_exact(&self, o: &Z) -> Z {
        match (self, o) {
            (Z::S(a), Z::S(b)) => Z::from_i128(*a as i128 / *b as i128),
            _ => Z::from_big(self.big() / o.big()),
        }
    }
}

/// A reduced rational, 16 bytes (an `Option<Q>` too): `S(n, d)` is `n/d` with `d > 0`, for
/// every value whose numerator fits an `i64` and denominator a `u32`; every other value is `B`
/// (never `B` for a value that fits, so the derived equality is value equality). The fast path
/// computes in `i128`: with 32-bit denominators no product of two words overflows it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum Q {
    S(i64, u32),
    B(Box<BigRational>),
}

impl Q {
    pub(crate) fn zero() -> Q {
        Q::S(0, 1)
    }
    pub(crate) fn int(n: Z) -> Q {
        match n {
            Z::S(s) => Q::S(s, 1),
            Z::B(b) => Q::B(Box::new(BigRational::from_integer(*b))),
        }
    }
    /// The integer `v`.
    fn int_i128(v: i128) -> Q {
        match i64::try_from(v) {
            Ok(s) => Q::S(s, 1),
            Err(_) => Q::B(Box::new(BigRational::from_integer(BigInt::from(v)))),
        }
    }
    /// `n/d` reduced, `d ≠ 0`.
    #[cfg(test)]
    fn from_i128(n: i128, d: i128) -> Q {
        Q::reduce((n < 0) != (d < 0), n.unsigned_abs(), d.unsigned_abs())
    }
    /// `±n/d` reduced (`neg` the sign, `d > 0`); in 64-bit words when both fit (hardware
    /// division instead of the 128-bit library routine).
    fn reduce(neg: bool, n: u128, d: u128) -> Q {
        if let (Ok(n), Ok(d)) = (u64::try_from(n), u64::try_from(d)) {
            if d == 1 {
                return Q::fit(neg, n, 1);
            }
            let g = gcd_u64(n, d);
            return Q::fit(neg, n / g, d / g);
        }
        let g = gcd_u128(n, d);
        let (n, d) = (n / g, d / g);
        if let (Ok(n), Ok(d)) = (u64::try_from(n), u64::try_from(d)) {
            return Q::fit(neg, n, d);
        }
        Q::boxed(neg, BigInt::from(n), BigInt::from(d))
    }
    /// `±n/d`, already reduced with `d > 0`: `S` when it fits.
    fn fit(neg: bool, n: u64, d: u64) -> Q {
        if let Ok(d) = u32::try_from(d) {
            if !neg && n <= i64::MAX as u64 {
                return Q::S(n as i64, d);
            }
            // −2^63 = i64::MIN is the one magnitude that fits negated only.
            if neg && n <= 1 << 63 {
                return Q::S((n as i64).wrapping_neg(), d);
            }
        }
        Q::boxed(neg, BigInt::from(n), BigInt::from(d))
    }
    fn boxed(neg: bool, n: BigInt, d: BigInt) -> Q {
        let n = if neg { -n } else { n };
        Q::B(Box::new(BigRational::new_raw(n, d)))
    }
    pub(crate) fn from_big(r: &BigRational) -> Q {
        match (r.numer().to_i64(), r.denom().to_u32()) {
            (Some(n), Some(d)) => Q::S(n, d),
            _ => Q::B(Box::new(r.clone())),
        }
    }
    /// [`Q::from_big`] without the copy; `r` must be reduced (BigRational arithmetic is).
    fn from_big_owned(r: BigRational) -> Q {
        match (r.numer().to_i64(), r.denom().to_u32()) {
            (Some(n), Some(d)) => Q::S(n, d),
            _ => Q::B(Box::new(r)),
        }
    }
    pub(crate) fn big(&self) -> BigRational {
        self.big_cow().into_owned()
    }
    fn big_cow(&self) -> Cow<'_, BigRational> {
        match self {
            Q::S(n, d) => Cow::Owned(BigRational::new_raw(BigInt::from(*n), BigInt::from(*d))),
            Q::B(r) => Cow::Borrowed(&**r),
        }
    }
    /// `self ∘ o` through BigRational arithmetic (the slow path).
    fn big_op(&self, o: &Q, op: fn(&BigRational, &BigRational) -> BigRational) -> Q {
        Q::from_big_owned(op(&self.big_cow(), &o.big_cow()))
    }
    /// The numerator (sign of the value).
    pub(crate) fn numer(&self) -> Z {
        match self {
            Q::S(n, _) => Z::S(*n),
            Q::B(r) => Z::from_big(r.numer().clone()),
        }
    }
    /// The denominator (positive).
    pub(crate) fn denom(&self) -> Z {
        match self {
            Q::S(_, d) => Z::S(*d as i64),
            Q::B(r) => Z::from_big(r.denom().clone()),
        }
    }
    /// `(numerator, denominator)` of a value in the small form.
    pub(crate) fn small(&self) -> Option<(i64, u32)> {
        match self {
            Q::S(n, d) => Some((*n, *d)),
            Q::B(_) => None,
        }
    }
    pub(crate) fn is_zero(&self) -> bool {
        matches!(self, Q::S(0, _))
    }
    pub(crate) fn neg(&self) -> Q {
        match self {
            Q::S(n, d) => match n.checked_neg() {
                Some(m) => Q::S(m, *d),
                None => Q::boxed(false, BigInt::from(n.unsigned_abs()), BigInt::from(*d)),
            },
            Q::B(r) => Q::from_big_owned(-(**r).clone()),
        }
    }
    pub(crate) fn add(&self, o: &Q) -> Q {
        if let (Some((a, b)), Some((c, d))) = (self.small(), o.small()) {
            if b == 1 && d == 1 {
                // Two integers: the sum is an integer, no gcd needed.
                return Q::int_i128(a as i128 + c as i128);
            }
            // |a·d + c·b| < 2^96 and b·d < 2^64.
            let (b, d) = (b as i128, d as i128);
            let n = a as i128 * d + c as i128 * b;
            return Q::reduce(n < 0, n.unsigned_abs(), (b * d) as u128);
        }
        self.big_op(o, |x, y| x + y)
    }
    pub(crate) fn sub(&self, o: &Q) -> Q {
        if let (Some((a, b)), Some((c, d))) = (self.small(), o.small()) {
            if b == 1 && d == 1 {
                return Q::int_i128(a as i128 - c as i128);
            }
            let (b, d) = (b as i128, d as i128);
            let n = a as i128 * d - c as i128 * b;
            return Q::reduce(n < 0, n.unsigned_abs(), (b * d) as u128);
        }
        self.big_op(o, |x, y| x - y)
    }
    pub(crate) fn mul(&self, o: &Q) -> Q {
        if let (Some((a, b)), Some((c, d))) = (self.small(), o.small()) {
            if b == 1 && d == 1 {
                return Q::int_i128(a as i128 * c as i128);
            }
            let n = a.unsigned_abs() as u128 * c.unsigned_abs() as u128;
            return Q::reduce((a < 0) != (c < 0), n, b as u128 * d as u128);
        }
        self.big_op(o, |x, y| x * y)
    }
    /// `self / o`, `o ≠ 0`.
    pub(crate) fn div(&self, o: &Q) -> Q {
        if let (Some((a, b)), Some((c, d))) = (self.small(), o.small()) {
            let n = a.unsigned_abs() as u128 * d as u128;
            return Q::reduce((a < 0) != (c < 0), n, b as u128 * c.unsigned_abs() as u128);
        }
        self.big_op(o, |x, y| x / y)
    }
}

/// Integer form of a rational row: multiply by the lcm of the denominators, divide by the content.
/// Returns the scaled `(coefficients, rhs)`.
/// The third component is the scale: integer row = scale · rational row.
pub(crate) fn integer_row(terms: &[(u32, Q)], rhs: &Q) -> (Vec<(u32, Z)>, Z, Q) {
    let mut l = rhs.denom();
    for (_, q) in terms {
        let d = q.denom();
        let g = l.gcd(&d);
        l = l.div_exact(&g).mul(&d);
    }
    let scale = |q: &Q| q.numer().mul(&l.div_exact(&q.denom()));
    let mut row: Vec<(u32, Z)> = terms.iter().map(|(c, q)| (*c, scale(q))).collect();
    let mut r = scale(rhs);
    let mut g = r.clone();
    for (_, z) in &row {
        g = g.gcd(z);
    }
    if !g.is_zero() && g != Z::one() {
        for (_, z) in row.iter_mut() {
            *z = z.div_exact(&g);
        }
        r = r.div_exact(&g);
    }
    let scale = if g.is_zero() {
        Q::int(l)
    } else {
        Q::int(l).div(&Q::int(g))
    };
    (row, r, scale)
}

/// Adds up the coefficients of equal columns in a row sorted by column, in place, and drops the
/// zeros (one pass, no second vector).
pub(crate) fn merge_sorted(terms: &mut Vec<(u32, Q)>) {
    let mut w = 0;
    for k in 0..terms.len() {
        if w > 0 && terms[w - 1].0 == terms[k].0 {
            let sum = terms[w - 1].1.add(&terms[k].1);
            terms[w - 1].1 = sum;
        } else {
            if w > 0 && terms[w - 1].1.is_zero() {
                w -= 1;
            }
            terms.swap(w, k);
            w += 1;
        }
    }
    if w > 0 && terms[w - 1].1.is_zero() {
        w -= 1;
    }
    terms.truncate(w);
}

const NONE: u32 = u32::MAX;

/// What a presolved row turned into.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum RowFate {
    /// Not yet decided (ends in the core if still pending after presolve).
    Pending,
    /// Reduced to `0 = 0`.
    Redundant,
    /// Created a fact (listed in [`Presolve::facts`]).
    Fact,
}

/// Equations in compressed sparse row form, as given: row `i` is `Σ coefs[k]·x[vars[k]] =
/// rhs[i]` over `k ∈ start[i]..start[i + 1]`; a variable may repeat (the coefficients add up) and
/// a coefficient may be zero. Twenty bytes a term, against about 136 for a `(usize,
/// BigRational)` with its digits on the heap; and the presolve reads them where they are, with
/// no copy of its own.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Rows {
    pub(crate) start: Vec<usize>,
    pub(crate) vars: Vec<u32>,
    pub(crate) coefs: Vec<Q>,
    pub(crate) rhs: Vec<Q>,
}

impl Default for Rows {
    fn default() -> Rows {
        Rows::with_capacity(0, 0)
    }
}

impl Rows {
    /// No rows, with room for `rows` rows of `terms` terms in all.
    pub(crate) fn with_capacity(rows: usize, terms: usize) -> Rows {
        let mut start = Vec::with_capacity(rows + 1);
        start.push(0);
        Rows {
            start,
            vars: Vec::with_capacity(terms),
            coefs: Vec::with_capacity(terms),
            rhs: Vec::with_capacity(rows),
        }
    }
    /// Appends the row `Σ q·x[v] = rhs`.
    pub(crate) fn push(&mut self, terms: impl IntoIterator<Item = (u32, Q)>, rhs: Q) {
        for (v, q) in terms {
            self.vars.push(v);
            self.coefs.push(q);
        }
        self.start.push(self.vars.len());
        self.rhs.push(rhs);
    }
    /// The number of rows.
    pub(crate) fn len(&self) -> usize {
        self.rhs.len()
    }
    /// The terms of row `i`: its variables and their coefficients.
    pub(crate) fn row(&self, i: usize) -> (&[u32], &[Q]) {
        let r = self.start[i]..self.start[i + 1];
        (&self.vars[r.clone()], &self.coefs[r])
    }
}

/// The presolve state over rows it borrows.
pub(crate) struct Presolve<'a> {
    pub(crate) n: usize,
    pub(crate) rows: &'a Rows,
    // union-find: x = node[x].f·node[x].parent + node[x].g, side by side in 24 bytes so that a
    // find touches one cache line per node (usually) and the array of a million unknowns stays
    // small
    node: Vec<Node>,
    /// The nodes' values that do not fit a word ([`W`]); a value rewritten by path compression
    /// is appended again, so this only grows, and it is empty on the BC-IFS systems, whose
    /// relations are small fractions.
    big: Vec<Q>,
    size: Vec<u32>,
    /// Whether the arrays below are kept: only a certificate of inconsistency reads them, so a
    /// solve first runs without them and replays the (deterministic) presolve with them when the
    /// system turns out inconsistent.
    track: bool,
    // The fact about each unknown, if any: a link (the unknown is a child, `orig_parent[x] ≠
    // x`) or a fixed value (the unknown is a root). One set of arrays serves both kinds, since
    // an unknown is linked or fixed at most once and never both.
    orig_parent: Vec<u32>,
    /// Row that made the fact, or `NONE`.
    fact_row: Vec<u32>,
    /// A link's original `f` (before path compression).
    link_f: Vec<Q>,
    /// Coefficient of the fact's unknown (child or fixed root) in its substituted row.
    fact_a: Vec<Q>,
    pub(crate) fate: Vec<RowFate>,
    /// `(row, unknown)` of each fact, in the order they were made: the rank witness, since each
    /// fact's row isolates its unknown given the earlier facts.
    pub(crate) facts: Vec<(u32, u32)>,
    pub(crate) time: u32,
    // registration lists (flat linked lists per root) and row bookkeeping
    head: Vec<u32>,
    ent_row: Vec<u32>,
    ent_epoch: Vec<u32>,
    ent_next: Vec<u32>,
    epoch: Vec<u32>,
    live: Vec<u32>,
    queued: Vec<bool>,
    /// Whether a root of the row was fixed or linked since the row was last examined: only
    /// such a row can read differently when substituted again.
    dirty: Vec<bool>,
    queue: Vec<u32>,
    /// Scratch for the substituted row of [`Presolve::process`].
    sub: Vec<(u32, Q)>,
}

/// A union-find node: `x = f·parent + g`. A root has `parent == x` and `f = 1`, and `g = 0`
/// unless it is fixed, when `g` is its value.
#[derive(Clone)]
struct Node {
    f: W,
    g: W,
    parent: u32,
    /// When the fact about `x` was made (facts are numbered 1, 2, … in order), 0 if none: in
    /// what would be padding, so that it costs no memory.
    at: u32,
}

/// A union-find value in one word: `n/d` when `d > 0` (a [`Q::S`] whose numerator fits an
/// `i32`); with `d == 0`, `n` (as `u32`) indexes [`Presolve`]'s side table of the values that
/// do not fit. One word instead of a 16-byte [`Q`] makes a node 24 bytes instead of 40: on the
/// 1.18M-unknown system of `benches/solver.rs` the node array falls from 47 to 28 MB, and its
/// presolve from about 100 to 78 ms (issue #34).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct W(i32, u32);

const W_ONE: W = W(1, 1);
const W_ZERO: W = W(0, 1);

/// A substituted row: distinct roots with nonzero coefficients, and the right-hand side.
pub(crate) type SubRow = (Vec<(u32, Q)>, Q);

impl<'a> Presolve<'a> {
    /// The presolve of `n` unknowns (every variable of `rows` below it) on `rows`.
    ///
    /// With `track`, it also keeps what [`Presolve::combination`] needs.
    pub(crate) fn new(n: usize, rows: &'a Rows, track: bool) -> Presolve<'a> {
        let m = rows.len();
        Presolve {
            n,
            rows,
            node: (0..n as u32)
                .map(|x| Node {
                    f: W_ONE,
                    g: W_ZERO,
                    parent: x,
                    at: 0,
                })
                .collect(),
            big: vec![],
            size: vec![1; n],
            track,
            orig_parent: if track {
                (0..n as u32).collect()
            } else {
                vec![]
            },
            fact_row: if track { vec![NONE; n] } else { vec![] },
            link_f: if track { vec![Q::zero(); n] } else { vec![] },
            fact_a: if track { vec![Q::zero(); n] } else { vec![] },
            fate: vec![RowFate::Pending; m],
            facts: Vec::with_capacity(m.min(n)),
            time: 0,
            head: vec![NONE; n],
            ent_row: vec![],
            ent_epoch: vec![],
            ent_next: vec![],
            epoch: vec![0; m],
            live: vec![0; m],
            queued: vec![false; m],
            dirty: vec![true; m],
            queue: vec![],
            sub: vec![],
        }
    }

    /// Frees what the run kept to find its facts (sizes, registrations, queues), leaving the
    /// facts and the rows' fates: once a consistent solve has built its core it reads nothing
    /// else, and what is freed here is then reused by the elimination and the solution space
    /// instead of new pages.
    pub(crate) fn release_run(&mut self) {
        self.size = vec![];
        self.head = vec![];
        self.ent_row = vec![];
        self.ent_epoch = vec![];
        self.ent_next = vec![];
        self.epoch = vec![];
        self.live = vec![];
        self.queued = vec![];
        self.dirty = vec![];
        self.queue = vec![];
        self.sub = vec![];
    }

    pub(crate) fn row_count(&self) -> usize {
        self.rows.len()
    }

    /// `(root, F, G)` with `x = F·root + G`, compressing the path.
    pub(crate) fn find(&mut self, x: u32) -> (u32, Q, Q) {
        let nx = &self.node[x as usize];
        let p = nx.parent;
        if p == x {
            return (x, Q::int(Z::one()), Q::zero());
        }
        if self.node[p as usize].parent == p {
            let (f, g) = (nx.f, nx.g);
            return (p, self.get(f), self.get(g));
        }
        let mut path = vec![];
        let mut r = x;
        while self.node[r as usize].parent != r {
            path.push(r);
            r = self.node[r as usize].parent;
        }
        // Walk back from the node nearest the root, composing relations.
        // The node nearest the root already points at it: its relation is the start, and it
        // is not rewritten (a rewrite would append a value that does not fit a word again).
        let last = *path.last().expect("x is not a root") as usize;
        let (mut cf, mut cg) = (self.get(self.node[last].f), self.get(self.node[last].g));
        for &y in path.iter().rev().skip(1) {
            let y = y as usize;
            // y = f_y·p + g_y and p = cf·r + cg  ⇒  y = (f_y·cf)·r + (f_y·cg + g_y)
            let (yf, yg) = (self.get(self.node[y].f), self.get(self.node[y].g));
            let nf = yf.mul(&cf);
            let ng = yf.mul(&cg).add(&yg);
            let (wf, wg) = (self.put(&nf), self.put(&ng));
            let ny = &mut self.node[y];
            ny.parent = r;
            ny.f = wf;
            ny.g = wg;
            (cf, cg) = (nf, ng);
        }
        (r, cf, cg)
    }

    /// `(root, F, G)` with `x = F·root + G`; only valid once [`Presolve::find`] has compressed
    /// the path of `x` and no fact was made since.
    #[inline]
    pub(crate) fn relation(&self, x: u32) -> (u32, Q, Q) {
        let nx = &self.node[x as usize];
        (nx.parent, self.get(nx.f), self.get(nx.g))
    }

    /// The value of a one-word rational.
    #[inline]
    fn get(&self, w: W) -> Q {
        if w.1 != 0 {
            Q::S(w.0 as i64, w.1)
        } else {
            self.big[w.0 as u32 as usize].clone()
        }
    }

    /// `q` in one word, kept in the side table when it does not fit.
    fn put(&mut self, q: &Q) -> W {
        if let Q::S(n, d) = q {
            if let Ok(n) = i32::try_from(*n) {
                return W(n, *d);
            }
        }
        let k = u32::try_from(self.big.len()).expect("fewer than 2^32 values aside");
        self.big.push(q.clone());
        W(k as i32, 0)
    }

    /// The fixed value of root `r`, if any (a root's only possible fact is a fixed value).
    #[inline]
    pub(crate) fn root_value(&self, r: u32) -> Option<Q> {
        self.root_fixed(r)
            .then(|| self.get(self.node[r as usize].g))
    }

    /// Whether root `r` is fixed: [`Presolve::root_value`] without building the value.
    #[inline]
    pub(crate) fn root_fixed(&self, r: u32) -> bool {
        let nr = &self.node[r as usize];
        debug_assert_eq!(nr.parent, r, "a root");
        nr.at != 0
    }

    /// Whether `x` was fixed (it is then a root of its own class); needs tracking.
    fn fixed(&self, x: usize) -> bool {
        self.orig_parent[x] as usize == x && self.node[x].at != 0
    }

    /// Row `i` after substituting all current facts, roots sorted.
    pub(crate) fn substitute(&mut self, i: usize) -> SubRow {
        let mut terms: Vec<(u32, Q)> = Vec::with_capacity(self.rows.row(i).0.len());
        let rhs = self.substitute_into(i, &mut terms);
        (terms, rhs)
    }

    /// [`Presolve::substitute`] into a vector the caller reuses (cleared first); returns the
    /// right-hand side.
    fn substitute_into(&mut self, i: usize, terms: &mut Vec<(u32, Q)>) -> Q {
        terms.clear();
        let rows = self.rows;
        let mut rhs = rows.rhs[i].clone();
        let (vars, coefs) = rows.row(i);
        for (&v, a) in vars.iter().zip(coefs) {
            let (r, f, g) = self.find(v);
            let shift = match self.root_value(r) {
                Some(val) => f.mul(&val).add(&g),
                None => {
                    terms.push((r, a.mul(&f)));
                    g
                }
            };
            if !shift.is_zero() {
                rhs = rhs.sub(&a.mul(&shift));
            }
        }
        terms.sort_unstable_by_key(|t| t.0);
        merge_sorted(terms);
        rhs
    }

    fn push(&mut self, i: u32) {
        if !self.queued[i as usize] && self.fate[i as usize] == RowFate::Pending {
            self.queued[i as usize] = true;
            self.queue.push(i);
        }
    }

    /// Walks the registrations of root `r` (consuming them); `on_valid` decides to requeue;
    /// `move_to` re-hangs still valid entries under another root.
    fn notify(&mut self, r: u32, threshold: u32, decrement: bool, move_to: Option<u32>) {
        let mut e = std::mem::replace(&mut self.head[r as usize], NONE);
        while e != NONE {
            let next = self.ent_next[e as usize];
            let row = self.ent_row[e as usize] as usize;
            if self.fate[row] == RowFate::Pending && self.ent_epoch[e as usize] == self.epoch[row] {
                self.dirty[row] = true;
                if decrement {
                    self.live[row] = self.live[row].saturating_sub(1);
                }
                if self.live[row] <= threshold {
                    self.push(row as u32);
                } else if let Some(b) = move_to {
                    self.ent_next[e as usize] = self.head[b as usize];
                    self.head[b as usize] = e;
                }
            }
            e = next;
        }
    }

    /// Runs the presolve to a fixed point. Returns the row found to read `0 = c ≠ 0`, if any.
    pub(crate) fn run(&mut self) -> Option<usize> {
        self.run_sweeping(false)
    }

    /// [`Presolve::run`]; with `always`, every sweep examines every pending row, even when
    /// [`Presolve::settled`] shows it would change nothing (the tests compare the two).
    fn run_sweeping(&mut self, always: bool) -> Option<usize> {
        self.queue = (0..self.row_count() as u32).rev().collect();
        self.queued.iter_mut().for_each(|q| *q = true);
        loop {
            while let Some(i) = self.queue.pop() {
                self.queued[i as usize] = false;
                if self.fate[i as usize] != RowFate::Pending {
                    continue;
                }
                if let Some(bad) = self.process(i as usize) {
                    return Some(bad);
                }
            }
            // Sweep: the registrations are a heuristic, so every pending row is examined once
            // more, in order; unless no row can have changed into a fact or a conflict.
            if !always && self.settled() {
                return None;
            }
            let before = self.time;
            for i in 0..self.row_count() {
                if self.fate[i] == RowFate::Pending {
                    if let Some(bad) = self.process(i) {
                        return Some(bad);
                    }
                }
            }
            if self.time == before && self.queue.is_empty() {
                return None;
            }
        }
    }

    /// Whether the sweep would make no fact and find no conflict, found by substituting only
    /// the pending rows marked dirty (in order, marking those that read `0 = 0` redundant, as
    /// the sweep would). A row that is not dirty reads as when it was last examined, when it
    /// stayed pending, so it cannot make a fact; the sweep would only register it again, and
    /// nothing reads the registrations after the run. So when this holds, skipping the sweep
    /// leaves the same facts, fates and relations; when it does not, the sweep runs as before
    /// and meets the same rows in the same state (it only re-substitutes).
    fn settled(&mut self) -> bool {
        let mut terms = std::mem::take(&mut self.sub);
        let mut settled = true;
        for i in 0..self.row_count() {
            if self.fate[i] != RowFate::Pending || !self.dirty[i] {
                continue;
            }
            let rhs = self.substitute_into(i, &mut terms);
            match terms.len() {
                0 if rhs.is_zero() => self.fate[i] = RowFate::Redundant,
                0..=2 => {
                    settled = false;
                    break;
                }
                _ => {}
            }
        }
        self.sub = terms;
        settled
    }

    fn process(&mut self, i: usize) -> Option<usize> {
        self.dirty[i] = false;
        // One substituted-row buffer for the whole presolve, not an allocation per row.
        let mut terms = std::mem::take(&mut self.sub);
        let rhs = self.substitute_into(i, &mut terms);
        let bad = self.decide(i, &terms, rhs);
        self.sub = terms;
        bad
    }

    /// What row `i`, substituted to `terms = rhs`, becomes: redundant, a fact, pending (with
    /// registrations), or the conflict (`Some(i)`).
    fn decide(&mut self, i: usize, terms: &[(u32, Q)], rhs: Q) -> Option<usize> {
        match terms.len() {
            0 => {
                if rhs.is_zero() {
                    self.fate[i] = RowFate::Redundant;
                    None
                } else {
                    Some(i)
                }
            }
            1 => {
                let (r, a) = &terms[0];
                self.time += 1;
                let g = self.put(&rhs.div(a));
                let nr = &mut self.node[*r as usize];
                nr.g = g;
                nr.at = self.time;
                if self.track {
                    self.fact_a[*r as usize] = a.clone();
                    self.fact_row[*r as usize] = i as u32;
                }
                self.fate[i] = RowFate::Fact;
                self.facts.push((i as u32, *r));
                self.notify(*r, 2, true, None);
                None
            }
            2 => {
                // Link the smaller class below the larger: child = −(b/a)·parent + c/a.
                let (mut x, mut y) = (terms[0].clone(), terms[1].clone());
                if self.size[x.0 as usize] > self.size[y.0 as usize] {
                    std::mem::swap(&mut x, &mut y);
                }
                let (c, p) = (x.0 as usize, y.0);
                self.time += 1;
                let f = y.1.div(&x.1).neg();
                let (wf, wg) = (self.put(&f), self.put(&rhs.div(&x.1)));
                let nc = &mut self.node[c];
                nc.parent = p;
                nc.f = wf;
                nc.g = wg;
                nc.at = self.time;
                if self.track {
                    self.orig_parent[c] = p;
                    self.link_f[c] = f;
                    self.fact_a[c] = x.1.clone();
                    self.fact_row[c] = i as u32;
                }
                self.size[p as usize] += self.size[c];
                self.fate[i] = RowFate::Fact;
                self.facts.push((i as u32, c as u32));
                self.notify(c as u32, 3, false, Some(p));
                None
            }
            len => {
                self.epoch[i] += 1;
                self.live[i] = len as u32;
                for &(r, _) in terms {
                    self.ent_row.push(i as u32);
                    self.ent_epoch.push(self.epoch[i]);
                    self.ent_next.push(self.head[r as usize]);
                    self.head[r as usize] = self.ent_row.len() as u32 - 1;
                }
                None
            }
        }
    }

    /// Replays derivations backwards. `seeds` are `(row, weight)` for rows substituted with all
    /// facts; returns `m` with `Σ m_r·row_r = Σ weight·(substituted row)`, as original rows.
    ///
    /// Substituting `α·x` for a child `x` subtracts `α·D_x`, with `D_x: x − f·p = g` the link
    /// normalised to coefficient 1 (for a fixed root, `D_y: y = v`); `D_x` itself is the
    /// substituted fact row divided by `fact_a[x]`, a combination of strictly older facts. So the
    /// weights on the facts are resolved latest first, each exactly once.
    ///
    /// Needs a presolve made with `track`.
    pub(crate) fn combination(&self, seeds: &[(usize, Q)]) -> BTreeMap<usize, Q> {
        assert!(self.track, "a combination needs the tracked facts");
        let mut m: BTreeMap<usize, Q> = BTreeMap::new();
        let mut w: BTreeMap<u32, (u32, Q)> = BTreeMap::new();
        for (r, q) in seeds {
            self.expand(*r, u32::MAX, q, &mut m, &mut w);
        }
        while let Some((t, (x, q))) = w.pop_last() {
            if q.is_zero() {
                continue;
            }
            let x = x as usize;
            let row = self.fact_row[x];
            self.expand(row as usize, t, &q.div(&self.fact_a[x]), &mut m, &mut w);
        }
        m.retain(|_, q| !q.is_zero());
        m
    }

    /// Adds `weight·row_i` and the (negated) weights of the facts older than `t` it substitutes.
    fn expand(
        &self,
        i: usize,
        t: u32,
        weight: &Q,
        m: &mut BTreeMap<usize, Q>,
        w: &mut BTreeMap<u32, (u32, Q)>,
    ) {
        let e = m.entry(i).or_insert_with(Q::zero);
        *e = e.add(weight);
        let mut sub = |time: u32, x: usize, alpha: &Q| {
            let e = w.entry(time).or_insert_with(|| (x as u32, Q::zero()));
            e.1 = e.1.sub(alpha);
        };
        let (vars, coefs) = self.rows.row(i);
        for (&v, a) in vars.iter().zip(coefs) {
            let mut alpha = weight.mul(a);
            let mut x = v as usize;
            while self.orig_parent[x] as usize != x && self.node[x].at < t {
                sub(self.node[x].at, x, &alpha);
                alpha = alpha.mul(&self.link_f[x]);
                x = self.orig_parent[x] as usize;
            }
            if self.fixed(x) && self.node[x].at < t {
                sub(self.node[x].at, x, &alpha);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn q(n: i64, d: i64) -> Q {
        Q::from_i128(n as i128, d as i128)
    }

    #[test]
    fn small_and_big_paths_agree() {
        let big = Q::from_big(&BigRational::new(BigInt::from(1) << 80, BigInt::from(3)));
        let a = q(i64::MAX, 7);
        // (2^63−1)/7 + 2^80/3, computed through the big path, checked against BigRational.
        let want = a.big() + big.big();
        assert_eq!(a.add(&big).big(), want);
        // Overflowing small·small falls back to big.
        let p = a.mul(&a);
        assert_eq!(p.big(), a.big() * a.big());
        assert!(matches!(p, Q::B(_)));
        // and back to small when it fits again
        assert_eq!(p.div(&a), a);
        assert_eq!(
            Z::lin(&Z::S(i64::MAX), &Z::S(2), &Z::S(i64::MAX), &Z::S(2)),
            Z::zero()
        );
        assert_eq!(q(2, -4), q(-1, 2));
        assert_eq!(q(1, 3).sub(&q(1, 3)), Q::zero());
    }

    /// Numbers around the edges of the word fast path: small, near `i64::MAX`/`i64::MIN`, zero.
    fn edge_i64() -> impl Strategy<Value = i64> {
        prop_oneof![
            -20i64..20,
            Just(i64::MIN),
            Just(i64::MAX),
            (i64::MIN..i64::MIN + 4),
            (i64::MAX - 4..=i64::MAX),
            any::<i64>(),
        ]
    }

    /// Denominators around the edges of the small form: 1, small, near `u32::MAX` and `2^32`,
    /// near `2^63` and around `2^100`.
    fn edge_denom() -> impl Strategy<Value = BigInt> {
        let near = |c: u128| (0u128..4).prop_map(move |k| BigInt::from(c - 2 + k));
        prop_oneof![
            (1u64..20).prop_map(BigInt::from),
            near(1 << 32),
            near(1 << 63),
            any::<u32>().prop_map(|v| BigInt::from(v) + 1),
            any::<u128>().prop_map(|v| BigInt::from(v >> 27) + 1),
        ]
    }

    /// Numerators: the word edges, `±2^31` (a node's word), `±2^63`, `±2^64`, zero and big values
    /// around `2^100`.
    fn edge_numer() -> impl Strategy<Value = BigInt> {
        prop_oneof![
            edge_i64().prop_map(BigInt::from),
            (-4i128..4).prop_map(|k| BigInt::from((1i128 << 31) + k)),
            (-4i128..4).prop_map(|k| BigInt::from(-(1i128 << 31) + k)),
            (-4i128..4).prop_map(|k| BigInt::from((1i128 << 63) + k)),
            (-4i128..4).prop_map(|k| BigInt::from(-(1i128 << 64) + k)),
            any::<i128>().prop_map(|v| BigInt::from(v >> 27)),
            Just(BigInt::from(0)),
        ]
    }

    /// A reduced rational from the edge numerators and denominators.
    fn edge_q() -> impl Strategy<Value = Q> {
        (edge_numer(), edge_denom()).prop_map(|(n, d)| Q::from_big(&BigRational::new(n, d)))
    }

    #[test]
    fn q_is_sixteen_bytes_and_a_node_twenty_four() {
        assert_eq!(std::mem::size_of::<Q>(), 16);
        assert_eq!(std::mem::size_of::<Option<Q>>(), 16);
        assert_eq!(std::mem::size_of::<Node>(), 24);
    }

    proptest! {
        /// A node's value reads back as it was written: in a word when the numerator fits an
        /// `i32`, from the side table otherwise (and a big value is kept whole).
        #[test]
        fn node_words_read_back_what_was_written(vals in proptest::collection::vec(edge_q(), 1..12)) {
            let rows = Rows::default();
            let mut p = Presolve::new(0, &rows, false);
            let words: Vec<W> = vals.iter().map(|v| p.put(v)).collect();
            for (v, w) in vals.iter().zip(&words) {
                prop_assert_eq!(&p.get(*w), v);
                let fits = matches!(v, Q::S(n, _) if i32::try_from(*n).is_ok());
                prop_assert_eq!(w.1 != 0, fits);
            }
        }
    }

    /// Runs both presolves (of the same number of unknowns; `b` sweeping every time with
    /// `always`) and compares their outcome, fates, facts and the relation and root value of
    /// every unknown.
    fn same_facts(a: &mut Presolve, b: &mut Presolve, always: bool) -> Result<(), TestCaseError> {
        prop_assert_eq!(a.run(), b.run_sweeping(always));
        prop_assert_eq!(&a.fate, &b.fate);
        prop_assert_eq!(&a.facts, &b.facts);
        for x in 0..a.n as u32 {
            let (fa, fb) = (a.find(x), b.find(x));
            prop_assert_eq!(a.root_value(fa.0), b.root_value(fb.0));
            prop_assert_eq!(fa, fb);
        }
        Ok(())
    }

    proptest! {
        /// The 64-bit reduction, the integer shortcuts of `add`/`mul` and the in-place merge agree
        /// with BigRational arithmetic (issue #34).
        #[test]
        fn word_fast_paths_match_big_rationals(
            a in edge_i64(), b in edge_i64(), c in edge_i64(), d in edge_i64(),
            ints in any::<bool>(),
        ) {
            let (b, d) = if ints { (1, 1) } else { (b, d) };
            prop_assume!(b != 0 && d != 0);
            let big = |n: i64, d: i64| BigRational::new(BigInt::from(n), BigInt::from(d));
            let (x, y) = (Q::from_i128(a as i128, b as i128), Q::from_i128(c as i128, d as i128));
            prop_assert_eq!(x.big(), big(a, b));
            prop_assert_eq!(x.add(&y).big(), big(a, b) + big(c, d));
            prop_assert_eq!(x.mul(&y).big(), big(a, b) * big(c, d));
            // Canonical: a value that fits is never boxed, the denominator is positive.
            for q in [x.add(&y), x.mul(&y)] {
                prop_assert_eq!(Q::from_big(&q.big()), q.clone());
                prop_assert!(q.big().denom() > &BigInt::from(0));
            }
        }

        /// The 16-byte representation around its edges (numerators near `i64::MIN`/`MAX`,
        /// denominators near `u32::MAX`, big values): every operation agrees with BigRational
        /// arithmetic and returns the canonical form (`S` exactly when the value fits).
        #[test]
        fn small_form_edges_match_big_rationals(x in edge_q(), y in edge_q()) {
            let (bx, by) = (x.big(), y.big());
            prop_assert_eq!(Q::from_big(&bx), x.clone());
            prop_assert_eq!(x.numer().big(), bx.numer().clone());
            prop_assert_eq!(x.denom().big(), bx.denom().clone());
            prop_assert_eq!(x.is_zero(), bx == BigRational::from_integer(BigInt::from(0)));
            let mut results = vec![
                (x.neg(), -bx.clone()),
                (x.add(&y), &bx + &by),
                (x.sub(&y), &bx - &by),
                (x.mul(&y), &bx * &by),
            ];
            if !y.is_zero() {
                results.push((x.div(&y), &bx / &by));
            }
            for (q, want) in results {
                prop_assert_eq!(q.big(), want.clone());
                prop_assert_eq!(Q::from_big(&q.big()), q.clone());
                let fits = want.numer().to_i64().is_some() && want.denom().to_u32().is_some();
                prop_assert_eq!(q.small().is_some(), fits);
                if let Some((n, d)) = q.small() {
                    prop_assert_eq!((Z::S(n), Z::S(d as i64)), (q.numer(), q.denom()));
                }
            }
        }

        /// A presolve that keeps nothing for certificates makes the same facts, in the same
        /// order, with the same fates and relations, as one that does: the solver relies on
        /// replaying the one with the other when a system turns out inconsistent.
        #[test]
        fn tracking_changes_no_fact(
            rows in proptest::collection::vec(
                (proptest::collection::vec((0u32..8, -2i64..3), 1..5), -2i64..3), 0..12),
        ) {
            let input: Vec<(Vec<(u32, Q)>, Q)> = rows
                .iter()
                .map(|(r, c)| (r.iter().map(|&(x, v)| (x, q(v, 1))).collect(), q(*c, 1)))
                .collect();
            let mut rows = Rows::default();
            input.into_iter().for_each(|(t, c)| rows.push(t, c));
            let mut plain = Presolve::new(8, &rows, false);
            let mut tracked = Presolve::new(8, &rows, true);
            same_facts(&mut plain, &mut tracked, false)?;
        }

        /// Rows as given, with repeated variables, zero coefficients and any order, make the
        /// same facts, fates and relations as the same rows sorted and merged: the presolve
        /// reads a system's rows where they are, without normalising a copy.
        #[test]
        fn repeats_and_zeros_change_no_fact(
            rows in proptest::collection::vec(
                (proptest::collection::vec((0u32..6, -2i64..3), 0..6), -2i64..3), 0..10),
        ) {
            let mut raw = Rows::default();
            let mut merged = Rows::default();
            for (terms, c) in &rows {
                let terms: Vec<(u32, Q)> = terms.iter().map(|&(x, v)| (x, q(v, 1))).collect();
                raw.push(terms.clone(), q(*c, 1));
                let mut clean = terms;
                clean.sort_by_key(|t| t.0);
                merge_sorted(&mut clean);
                merged.push(clean, q(*c, 1));
            }
            let mut a = Presolve::new(6, &raw, true);
            let mut b = Presolve::new(6, &merged, true);
            same_facts(&mut a, &mut b, false)?;
            let seeds: Vec<(usize, Q)> = (0..rows.len()).map(|i| (i, q(1, 1))).collect();
            prop_assert_eq!(a.combination(&seeds), b.combination(&seeds));
        }

        /// Skipping a sweep that [`Presolve::settled`] shows would change nothing leaves the
        /// same facts, fates, relations and conflict as sweeping every pending row each time.
        /// Rows of up to six terms over five unknowns, so that links often merge two roots of
        /// one row, which the registrations do not count (the case the sweep exists for).
        #[test]
        fn skipped_sweeps_change_no_fact(
            rows in proptest::collection::vec(
                (proptest::collection::vec((0u32..5, -2i64..3), 1..7), -2i64..3), 0..12),
        ) {
            let mut input = Rows::default();
            for (t, c) in &rows {
                input.push(t.iter().map(|&(x, v)| (x, q(v, 1))), q(*c, 1));
            }
            let mut skipping = Presolve::new(5, &input, true);
            let mut sweeping = Presolve::new(5, &input, true);
            same_facts(&mut skipping, &mut sweeping, true)?;
        }

        #[test]
        fn merge_sorted_matches_a_map(
            raw in proptest::collection::vec((0u32..6, -3i64..4), 0..12),
        ) {
            let mut terms: Vec<(u32, Q)> = raw.iter().map(|&(c, v)| (c, q(v, 1))).collect();
            terms.sort_by_key(|t| t.0);
            merge_sorted(&mut terms);
            let mut want: BTreeMap<u32, i64> = BTreeMap::new();
            raw.iter().for_each(|&(c, v)| *want.entry(c).or_default() += v);
            want.retain(|_, v| *v != 0);
            let want: Vec<(u32, Q)> = want.into_iter().map(|(c, v)| (c, q(v, 1))).collect();
            prop_assert_eq!(terms, want);
        }
    }

    #[test]
    fn integer_row_clears_denominators_and_content() {
        // (1/2)x + (1/3)y = 5/6  ⇒  3x + 2y = 5
        let (row, r, s) = integer_row(&[(0, q(1, 2)), (1, q(1, 3))], &q(5, 6));
        assert_eq!(row, vec![(0, Z::S(3)), (1, Z::S(2))]);
        assert_eq!((r, s), (Z::S(5), q(6, 1)));
        // 4x + 6y = 2  ⇒  2x + 3y = 1
        let (row, r, s) = integer_row(&[(0, q(4, 1)), (1, q(6, 1))], &q(2, 1));
        assert_eq!(row, vec![(0, Z::S(2)), (1, Z::S(3))]);
        assert_eq!((r, s), (Z::S(1), q(1, 2)));
    }

    #[test]
    fn compressing_a_path_keeps_aside_only_the_rewritten_nodes_values() {
        // x_i = c·x_(i+1) along a chain, with c = 2^40 (not a word): every relation is big.
        // The chain is linked as two halves first and joined last, so that one half's root
        // goes under the other's and its members end two steps from the root.
        let (len, c) = (12u32, 1i64 << 40);
        let mut rows = Rows::default();
        let link =
            |rows: &mut Rows, i: u32| rows.push([(i, q(1, 1)), (i + 1, q(-c, 1))], Q::zero());
        (0..len - 1)
            .filter(|&i| i != 4)
            .for_each(|i| link(&mut rows, i));
        link(&mut rows, 4);
        let mut p = Presolve::new(len as usize, &rows, false);
        assert_eq!(p.run(), None);
        // Only a node at depth two or more is rewritten by `find`.
        let deep = (0..len as usize)
            .filter(|&x| {
                let parent = p.node[x].parent as usize;
                p.node[parent].parent as usize != parent
            })
            .count();
        assert!(deep > 0, "the chain leaves a path to compress");
        let aside = p.big.len();
        let rel: Vec<(u32, Q, Q)> = (0..len).map(|x| p.find(x)).collect();
        // Each rewritten node gets one new big value, its factor (its offset 0 fits a word).
        assert_eq!(p.big.len() - aside, deep);
        // x_i = c^(j−i)·x_j: every relation is the last unknown's times a power of c.
        let last = &rel[len as usize - 1];
        for (i, (r, f, g)) in rel.iter().enumerate() {
            assert_eq!((r, g), (&last.0, &Q::zero()), "x{i}");
            let mut want = last.1.clone();
            (i..len as usize - 1).for_each(|_| want = want.mul(&q(c, 1)));
            assert_eq!(f, &want, "x{i}");
        }
    }

    #[test]
    fn chain_of_links_composes() {
        // x0 = 2·x1 (x0 − 2x1 = 0), x1 = x2 + 1, x2 = 3  ⇒  x1 = 4, x0 = 8
        let mut rows = Rows::default();
        rows.push([(0, q(1, 1)), (1, q(-2, 1))], Q::zero());
        rows.push([(1, q(1, 1)), (2, q(-1, 1))], q(1, 1));
        rows.push([(2, q(1, 1))], q(3, 1));
        let mut p = Presolve::new(3, &rows, true);
        assert_eq!(p.run(), None);
        for (x, want) in [(0, 8), (1, 4), (2, 3)] {
            let (r, f, g) = p.find(x);
            let v = p.root_value(r).expect("fixed");
            assert_eq!(f.mul(&v).add(&g), q(want, 1), "x{x}");
        }
    }
}
