//! The exact sparse linear system of the BC-IFS constraints (SPEC §6): solve over Q, report rank,
//! degrees of freedom, a particular solution and a basis of directions, or a small conflicting
//! set of equations with the rational combination that proves `0 = c ≠ 0`.
//!
//! # Method
//! 1. **Presolve** (`crate::presolve`): rows that after substitution read `0 = c`, `a·x = c` or
//!    `a·x + b·y = c` become facts (fixed values, affine union-find links), repeated to a fixed
//!    point. The BC-IFS systems (column sums, `x = c` incidences, `x = y` adjacencies) are mostly
//!    solved here in near-linear time.
//! 2. **Core**: the remaining rows, over the remaining roots, are cleared to integers and
//!    eliminated fraction-free (`row ← (a/g)·row − (b/g)·pivot row`, then divided by the row's
//!    content), choosing pivots Markowitz-style (shortest active row, then the column with the
//!    fewest active rows, preferring unit coefficients), then back-substituted to reduced form.
//! 3. **Conflict**: the derivation of `0 = c ≠ 0` is replayed backwards into a combination of
//!    original rows: through the fact forest (`crate::presolve`), and for a contradiction found
//!    in the core by re-running the (deterministic) elimination while tracking each row's
//!    combination of core rows. Its support is the conflicting row plus pivot rows, so at most
//!    `rank + 1` rows. When it has at most [`MINIMIZE_LIMIT`] rows it is then made minimal: on
//!    those rows `R` the transposed system `yᵀ[A_R | b_R] = (0,…,0,1)` is solved; its particular
//!    solution (free parameters 0) is basic, so its support is a minimal inconsistent subsystem
//!    (independent in `[A|b]`, exactly one dependency in `A`: dropping any row leaves a
//!    consistent system). Above the limit the transposed solve can fill in quadratically (long
//!    chains of `x = y` make every certificate long), so the derivation is returned as is.
//!
//! Rank witness: each fact and each core pivot is a pair (row, unknown). The pivot rows, taken in
//! the order their facts were made, only use facts from earlier pivot rows, so with the free roots
//! set to 0 the homogeneous subsystem on the pivot rows forces every pivot unknown to 0: the minor
//! is nonsingular. With the basis vectors (unit on their free unknown) this makes
//! `rank = |pivots|` and `span(basis) = kernel` checkable ([`SolutionSpace::check`]).
//!
//! Written by hand: crates.io has sparse solvers over `f64` only (rsparse, russell_sparse,
//! sparsela), none exact, rank-revealing or certifying.

use crate::presolve::{integer_row, Presolve, RowFate, Q, Z};
use num_rational::BigRational;
use num_traits::{One, Zero};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::io::{self, Write};

/// A linear system `Σ coef·x[var] = rhs` over Q in `unknowns` unknowns.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct LinearSystem {
    /// Number of unknowns; every variable index is below it.
    pub unknowns: usize,
    /// The equations.
    pub rows: Vec<Equation>,
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

/// Outcome of [`solve`]: inconsistency is a result with its certificate, not an error.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Solution {
    /// The system has solutions: `particular + span(basis)`.
    Consistent(SolutionSpace),
    /// No solution; the conflict proves it.
    Inconsistent(Conflict),
}

/// All solutions of a consistent system: `particular + Σ t_k·basis[k]`, `t_k ∈ Q`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SolutionSpace {
    /// Rank of the coefficient matrix.
    pub rank: usize,
    /// One solution, with every free parameter 0.
    #[serde(with = "rat_vec")]
    pub particular: Vec<BigRational>,
    /// The unknown serving as free parameter of each direction, increasing.
    pub free: Vec<usize>,
    /// Sparse direction vectors sorted by unknown; `basis[k]` is 1 at `free[k]` and 0 at the other
    /// free unknowns.
    #[serde(with = "rat_basis")]
    pub basis: Vec<Vec<(usize, BigRational)>>,
    /// Rank witness: `(equation, unknown)` pairs whose square minor is nonsingular, in
    /// elimination order (each pivot row only needs earlier ones to isolate its unknown; the
    /// checker eliminates in this order).
    pub pivots: Vec<(usize, usize)>,
}

/// A certificate of inconsistency: `Σ m_i·row_i` has every coefficient 0 and right-hand side
/// `constant ≠ 0`. Multipliers are coprime integers; the rows form a minimal conflicting set.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Conflict {
    /// `(equation index, multiplier)`, by increasing equation index.
    #[serde(with = "rat_terms")]
    pub multipliers: Vec<(usize, BigRational)>,
    /// `Σ m_i·rhs_i`.
    #[serde(with = "rat")]
    pub constant: BigRational,
}

/// Solves the system exactly (see the module documentation for the method).
///
/// # Panics
/// If a term names an unknown `≥ sys.unknowns`, or `sys.unknowns ≥ 2^32 − 1`.
pub fn solve(sys: &LinearSystem) -> Solution {
    let rows = sys.rows.iter().map(|e| {
        let mut t: Vec<(u32, Q)> = e
            .terms
            .iter()
            .map(|(v, c)| {
                assert!(*v < sys.unknowns, "unknown {v} out of range");
                (*v as u32, Q::from_big(c))
            })
            .collect();
        (merge_terms(&mut t), Q::from_big(&e.rhs))
    });
    assert!(
        sys.unknowns < u32::MAX as usize,
        "at most 2^32 − 2 unknowns"
    );
    match run(sys.unknowns, rows, true) {
        Ok(space) => Solution::Consistent(space),
        Err(failure) => {
            let (ps, seeds) = *failure;
            Solution::Inconsistent(certificate(&ps, seeds))
        }
    }
}

fn merge_terms(t: &mut Vec<(u32, Q)>) -> Vec<(u32, Q)> {
    t.sort_by_key(|x| x.0);
    let mut out: Vec<(u32, Q)> = Vec::with_capacity(t.len());
    for (v, q) in t.drain(..) {
        match out.last_mut() {
            Some((lv, lq)) if *lv == v => *lq = lq.add(&q),
            _ => out.push((v, q)),
        }
    }
    out.retain(|x| !x.1.is_zero());
    out
}

/// A core row in integer form, columns sorted (local core column ids).
#[derive(Clone, Debug)]
struct CRow {
    cols: Vec<u32>,
    vals: Vec<Z>,
    rhs: Z,
}

impl CRow {
    fn coef(&self, c: u32) -> Option<&Z> {
        self.cols.binary_search(&c).ok().map(|k| &self.vals[k])
    }
    /// `(a/g)·self − (b/g)·o` with `g = gcd(a, b)`, then divided by its content.
    fn combine(&self, a: &Z, o: &CRow, b: &Z) -> CRow {
        self.combine_with_factors(a, o, b).0
    }

    /// [`CRow::combine`], also returning `(a/g, b/g, content)`.
    fn combine_with_factors(&self, a: &Z, o: &CRow, b: &Z) -> (CRow, Z, Z, Z) {
        let g = a.gcd(b);
        let (a, b) = (a.div_exact(&g), b.div_exact(&g));
        let mut out = CRow {
            cols: vec![],
            vals: vec![],
            rhs: Z::lin(&a, &self.rhs, &b, &o.rhs),
        };
        let (mut i, mut j) = (0, 0);
        let zero = Z::zero();
        while i < self.cols.len() || j < o.cols.len() {
            let ci = self.cols.get(i).copied().unwrap_or(u32::MAX);
            let cj = o.cols.get(j).copied().unwrap_or(u32::MAX);
            let c = ci.min(cj);
            let x = if ci == c {
                i += 1;
                &self.vals[i - 1]
            } else {
                &zero
            };
            let y = if cj == c {
                j += 1;
                &o.vals[j - 1]
            } else {
                &zero
            };
            let v = Z::lin(&a, x, &b, y);
            if !v.is_zero() {
                out.cols.push(c);
                out.vals.push(v);
            }
        }
        let mut g = out.rhs.clone();
        for v in &out.vals {
            if g.is_unit() {
                break;
            }
            g = g.gcd(v);
        }
        if !g.is_zero() && !g.is_unit() {
            out.vals.iter_mut().for_each(|v| *v = v.div_exact(&g));
            out.rhs = out.rhs.div_exact(&g);
        } else {
            g = Z::one();
        }
        (out, a, b, g)
    }
}

/// A combination of core rows, sorted by row.
type Combo = Vec<(u32, Q)>;
/// `(row, pivot column, reduced row)` per pivot, in elimination order.
type Reduced = Vec<(usize, u32, CRow)>;

/// Fraction-free sparse elimination with Markowitz-style pivots, then back substitution.
/// `Err` holds the row that became `0 = c ≠ 0` and, when `track`, its combination of input rows.
fn eliminate(mut rows: Vec<CRow>, ncols: usize, track: bool) -> Result<Reduced, (usize, Combo)> {
    let mut combos: Vec<Combo> = match track {
        true => (0..rows.len() as u32)
            .map(|i| vec![(i, Q::int(Z::one()))])
            .collect(),
        false => vec![],
    };
    // Column lists are lazy (entries may be stale or repeated; validated when used); the counts of
    // active rows per column are exact and drive the pivot choice.
    let mut col_rows: Vec<Vec<u32>> = vec![vec![]; ncols];
    let mut col_count: Vec<u32> = vec![0; ncols];
    let mut buckets: Vec<Vec<u32>> = vec![];
    let mut active = vec![true; rows.len()];
    for (i, r) in rows.iter().enumerate() {
        for &c in &r.cols {
            col_rows[c as usize].push(i as u32);
            col_count[c as usize] += 1;
        }
        if buckets.len() <= r.cols.len() {
            buckets.resize(r.cols.len() + 1, vec![]);
        }
        buckets[r.cols.len()].push(i as u32);
    }
    let mut pivots: Vec<(usize, u32)> = vec![];
    let mut low = 1;
    'outer: loop {
        // Shortest active row (lazy buckets: stale entries are skipped).
        let i = loop {
            while low < buckets.len() && buckets[low].is_empty() {
                low += 1;
            }
            if low >= buckets.len() {
                break 'outer;
            }
            let i = buckets[low].pop().expect("nonempty") as usize;
            if active[i] && rows[i].cols.len() == low {
                break i;
            }
        };
        let piv = &rows[i];
        let k = (0..piv.cols.len())
            .min_by_key(|&k| (col_count[piv.cols[k] as usize], !piv.vals[k].is_unit()))
            .expect("active rows are nonempty");
        let (p, a) = (piv.cols[k], piv.vals[k].clone());
        active[i] = false;
        piv.cols.iter().for_each(|&c| col_count[c as usize] -= 1);
        let mut others = std::mem::take(&mut col_rows[p as usize]);
        others.sort_unstable();
        others.dedup();
        others.retain(|&j| active[j as usize] && rows[j as usize].coef(p).is_some());
        for j in others.into_iter().map(|j| j as usize) {
            let b = rows[j].coef(p).expect("validated").clone();
            let (new, fa, fb, content) = rows[j].combine_with_factors(&a, &rows[i], &b);
            if track {
                combos[j] = lin_combo(&fa, &combos[j], &fb, &combos[i], &content);
            }
            let old = std::mem::replace(&mut rows[j], new);
            // Exact counts: merge the old and new column sets; new columns join the lists.
            let (oc, nc) = (&old.cols, &rows[j].cols);
            let (mut x, mut y) = (0, 0);
            while x < oc.len() || y < nc.len() {
                let (co, cn) = (
                    oc.get(x).copied().unwrap_or(u32::MAX),
                    nc.get(y).copied().unwrap_or(u32::MAX),
                );
                if co == cn {
                    x += 1;
                    y += 1;
                } else if co < cn {
                    col_count[co as usize] -= 1;
                    x += 1;
                } else {
                    col_count[cn as usize] += 1;
                    col_rows[cn as usize].push(j as u32);
                    y += 1;
                }
            }
            let len = rows[j].cols.len();
            if len == 0 {
                if !rows[j].rhs.is_zero() {
                    return Err((j, combos.get(j).cloned().unwrap_or_default()));
                }
                active[j] = false;
            } else {
                // Fill-in can make a row longer than every row was at the start.
                if len >= buckets.len() {
                    buckets.resize(len + 1, Vec::new());
                }
                buckets[len].push(j as u32);
                low = low.min(len);
            }
        }
        pivots.push((i, p));
    }
    // Back substitution, last pivot first: each reduced row holds its pivot and free columns.
    let mut pivot_of: Vec<Option<usize>> = vec![None; ncols];
    let mut reduced: Vec<Option<CRow>> = vec![None; pivots.len()];
    for (k, &(i, p)) in pivots.iter().enumerate().rev() {
        let mut row = std::mem::replace(
            &mut rows[i],
            CRow {
                cols: vec![],
                vals: vec![],
                rhs: Z::zero(),
            },
        );
        let later: Vec<(u32, usize)> = row
            .cols
            .iter()
            .filter(|&&c| c != p)
            .filter_map(|&c| pivot_of[c as usize].map(|k2| (c, k2)))
            .collect();
        for (c, k2) in later {
            let red = reduced[k2].as_ref().expect("later pivots are reduced");
            let b = row.coef(c).expect("column present").clone();
            row = row.combine(red.coef(c).expect("pivot present"), red, &b);
        }
        pivot_of[p as usize] = Some(k);
        reduced[k] = Some(row);
    }
    Ok(pivots
        .into_iter()
        .zip(reduced)
        .map(|((i, p), r)| (i, p, r.expect("reduced")))
        .collect())
}

/// `(fa·x − fb·y) / content` on sparse combinations sorted by row.
fn lin_combo(fa: &Z, x: &Combo, fb: &Z, y: &Combo, content: &Z) -> Combo {
    let (fa, fb, c) = (
        Q::int(fa.clone()),
        Q::int(fb.clone()),
        Q::int(content.clone()),
    );
    let mut out = Vec::with_capacity(x.len() + y.len());
    let (mut i, mut j) = (0, 0);
    while i < x.len() || j < y.len() {
        let (ri, rj) = (
            x.get(i).map_or(u32::MAX, |t| t.0),
            y.get(j).map_or(u32::MAX, |t| t.0),
        );
        let r = ri.min(rj);
        let mut v = Q::zero();
        if ri == r {
            v = v.add(&fa.mul(&x[i].1));
            i += 1;
        }
        if rj == r {
            v = v.sub(&fb.mul(&y[j].1));
            j += 1;
        }
        if !v.is_zero() {
            out.push((r, v.div(&c)));
        }
    }
    out
}

/// The presolve state and the substituted rows (with weights) whose sum reads `0 = c ≠ 0`.
type Failure = Box<(Presolve, Vec<(usize, Q)>)>;

/// Presolve + core. On inconsistency returns the presolve state and the conflicting combination.
fn run(
    n: usize,
    rows: impl Iterator<Item = (Vec<(u32, Q)>, Q)>,
    want_basis: bool,
) -> Result<SolutionSpace, Failure> {
    let mut ps = Presolve::new(n, rows);
    if let Some(bad) = ps.run() {
        return Err(Box::new((ps, vec![(bad, Q::int(Z::one()))])));
    }
    // Core: pending rows over the remaining roots.
    let pending: Vec<usize> = (0..ps.rows())
        .filter(|&i| ps.fate[i] == RowFate::Pending)
        .collect();
    let (crows, roots, _) = build_core(&mut ps, &pending);
    let core = match eliminate(crows, roots.len(), false) {
        Ok(core) => core,
        Err(_) => {
            // Replay the deterministic elimination, now tracking combinations.
            let (crows, roots, scales) = build_core(&mut ps, &pending);
            let (_, combo) = eliminate(crows, roots.len(), true).expect_err("same elimination");
            let seeds = combo
                .into_iter()
                .map(|(k, w)| (pending[k as usize], w.mul(&scales[k as usize])));
            let seeds = seeds.collect();
            return Err(Box::new((ps, seeds)));
        }
    };
    Ok(assemble(&mut ps, &pending, &roots, core, want_basis))
}

/// The pending rows substituted and cleared to integers over local column ids; the roots of the
/// local columns; the integer scale of each row.
fn build_core(ps: &mut Presolve, pending: &[usize]) -> (Vec<CRow>, Vec<u32>, Vec<Q>) {
    let mut local: Vec<u32> = vec![u32::MAX; ps.n];
    let (mut roots, mut crows, mut scales) = (vec![], Vec::with_capacity(pending.len()), vec![]);
    for &i in pending {
        let (terms, rhs) = ps.substitute(i);
        let (row, r, scale) = integer_row(&terms, &rhs);
        let mut t: Vec<(u32, Z)> = row
            .into_iter()
            .map(|(root, z)| {
                if local[root as usize] == u32::MAX {
                    local[root as usize] = roots.len() as u32;
                    roots.push(root);
                }
                (local[root as usize], z)
            })
            .collect();
        t.sort_unstable_by_key(|x| x.0);
        let (cols, vals) = t.into_iter().unzip();
        crows.push(CRow { cols, vals, rhs: r });
        scales.push(scale);
    }
    (crows, roots, scales)
}

/// Builds the public solution space from the facts and the reduced core.
fn assemble(
    ps: &mut Presolve,
    pending: &[usize],
    roots: &[u32],
    core: Vec<(usize, u32, CRow)>,
    want_basis: bool,
) -> SolutionSpace {
    let n = ps.n;
    // Value (free parameters 0) of each pivot root, and its dependence on free roots.
    let mut core_of: Vec<u32> = vec![u32::MAX; n];
    let mut pivots: Vec<(usize, usize)> = vec![];
    let mut facts: Vec<(u32, usize, usize)> = vec![];
    for (i, fate) in ps.fate.iter().enumerate() {
        if let RowFate::Pivot(c) = fate {
            facts.push((ps.fact_time(*c), i, *c as usize));
        }
    }
    facts.sort_unstable();
    pivots.extend(facts.into_iter().map(|(_, i, c)| (i, c)));
    for (k, (i, p, _)) in core.iter().enumerate() {
        core_of[roots[*p as usize] as usize] = k as u32;
        pivots.push((pending[*i], roots[*p as usize] as usize));
    }
    ps.compress_all();
    let ps = &*ps;
    let root_val = |r: u32| -> Q {
        if let Some(v) = ps.root_value(r) {
            return v.clone();
        }
        match core.get(core_of[r as usize] as usize) {
            Some((_, p, row)) => {
                Q::int(row.rhs.clone()).div(&Q::int(row.coef(*p).expect("pivot").clone()))
            }
            None => Q::zero(),
        }
    };
    let mut particular = Vec::with_capacity(n);
    let mut free = vec![];
    for x in 0..n as u32 {
        let (r, f, g) = ps.relation(x);
        if r == x {
            let v = root_val(x);
            if ps.root_value(x).is_none() && core_of[x as usize] == u32::MAX {
                free.push(x as usize);
            }
            particular.push(v.big());
        } else if let Some(v) = ps.root_value(r).filter(|_| r < x) {
            // Common case (fixed class): no need to revisit the root.
            particular.push(f.mul(v).add(g).big());
        } else {
            particular.push(f.mul(&root_val(r)).add(g).big());
        }
    }
    let mut basis = vec![];
    if want_basis {
        // dirs[local core column of a free root]: (pivot root, coefficient of that parameter)
        let mut dirs: Vec<Vec<(u32, Q)>> = vec![vec![]; roots.len()];
        for (_, p, row) in &core {
            let d = Q::int(row.coef(*p).expect("pivot").clone());
            for (c, v) in row.cols.iter().zip(&row.vals) {
                if c != p {
                    dirs[*c as usize].push((roots[*p as usize], Q::int(v.neg()).div(&d)));
                }
            }
        }
        let mut local: Vec<u32> = vec![u32::MAX; n];
        roots
            .iter()
            .enumerate()
            .for_each(|(k, r)| local[*r as usize] = k as u32);
        // members of each class (CSR by root)
        let mut start = vec![0u32; n + 1];
        (0..n as u32).for_each(|x| start[ps.relation(x).0 as usize + 1] += 1);
        (0..n).for_each(|i| start[i + 1] += start[i]);
        let mut fill = start.clone();
        let mut members = vec![0u32; n];
        for x in 0..n as u32 {
            let r = ps.relation(x).0 as usize;
            members[fill[r] as usize] = x;
            fill[r] += 1;
        }
        drop(fill);
        let one = Q::int(Z::one());
        let none: Vec<(u32, Q)> = vec![];
        for &f in &free {
            let mut v: Vec<(usize, BigRational)> = vec![];
            let d = dirs.get(local[f] as usize).unwrap_or(&none);
            for (root, c) in std::iter::once((f as u32, &one)).chain(d.iter().map(|(r, c)| (*r, c)))
            {
                for &x in &members[start[root as usize] as usize..start[root as usize + 1] as usize]
                {
                    v.push((x as usize, ps.relation(x).1.mul(c).big()));
                }
            }
            v.sort_unstable_by_key(|t| t.0);
            basis.push(v);
        }
    }
    debug_assert_eq!(pivots.len() + free.len(), n);
    SolutionSpace {
        rank: pivots.len(),
        particular,
        free,
        basis,
        pivots,
    }
}

/// Largest derivation certificate that is shrunk to a minimal one (see the module docs).
pub const MINIMIZE_LIMIT: usize = 2000;

/// The certificate: the replayed derivation, minimised when small.
fn certificate(ps: &Presolve, seeds: Vec<(usize, Q)>) -> Conflict {
    let derived = ps.combination(&seeds);
    let support: Vec<usize> = derived.keys().copied().collect();
    let conflict = |m: Vec<(usize, Q)>| {
        // Scale to coprime integers.
        let terms: Vec<(u32, Q)> = m
            .iter()
            .enumerate()
            .map(|(k, (_, q))| (k as u32, q.clone()))
            .collect();
        let (ints, _, _) = integer_row(&terms, &Q::zero());
        let multipliers: Vec<(usize, BigRational)> = ints
            .into_iter()
            .map(|(k, z)| (m[k as usize].0, BigRational::from_integer(z.big())))
            .collect();
        let constant = multipliers
            .iter()
            .fold(BigRational::zero(), |s, (i, m)| s + m * ps.rhs[*i].big());
        Conflict {
            multipliers,
            constant,
        }
    };
    if support.len() <= MINIMIZE_LIMIT {
        if let Some(m) = minimal(ps, &support) {
            return conflict(m);
        }
    }
    conflict(derived.into_iter().collect())
}

/// The basic solution of `yᵀ[A_R | b_R] = (0,…,0,1)` on the inconsistent rows `R`.
fn minimal(ps: &Presolve, rows: &[usize]) -> Option<Vec<(usize, Q)>> {
    // Column j of A_R becomes the equation Σ_k A[r_k][j]·y_k = 0; the last one Σ b·y = 1.
    let mut by_col: BTreeMap<u32, Vec<(u32, Q)>> = BTreeMap::new();
    for (k, &i) in rows.iter().enumerate() {
        for t in ps.start[i]..ps.start[i + 1] {
            by_col
                .entry(ps.cols[t])
                .or_default()
                .push((k as u32, ps.coefs[t].clone()));
        }
    }
    let rhs_row: Vec<(u32, Q)> = rows
        .iter()
        .enumerate()
        .filter(|(_, &i)| !ps.rhs[i].is_zero())
        .map(|(k, &i)| (k as u32, ps.rhs[i].clone()))
        .collect();
    let eqs = by_col.into_values().map(|t| (t, Q::zero()));
    let space = run(
        rows.len(),
        eqs.chain(std::iter::once((rhs_row, Q::int(Z::one())))),
        false,
    )
    .ok()?;
    let m: Vec<(usize, Q)> = space
        .particular
        .iter()
        .enumerate()
        .filter(|(_, y)| !y.is_zero())
        .map(|(k, y)| (rows[k], Q::from_big(y)))
        .collect();
    Some(m)
}

mod rat {
    use num_rational::BigRational;
    use serde::{de::Error, Deserialize, Deserializer, Serializer};
    pub fn serialize<S: Serializer>(r: &BigRational, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(r)
    }
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<BigRational, D::Error> {
        String::deserialize(d)?.parse().map_err(D::Error::custom)
    }
}
mod rat_vec {
    use num_rational::BigRational;
    use serde::{de::Error, Deserialize, Deserializer, Serializer};
    pub fn serialize<S: Serializer>(v: &[BigRational], s: S) -> Result<S::Ok, S::Error> {
        s.collect_seq(v.iter().map(|r| r.to_string()))
    }
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<BigRational>, D::Error> {
        Vec::<String>::deserialize(d)?
            .iter()
            .map(|s| s.parse().map_err(D::Error::custom))
            .collect()
    }
}
mod rat_terms {
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
mod rat_basis {
    use num_rational::BigRational;
    use serde::{de::Error, Deserialize, Deserializer, Serializer};
    type Basis = Vec<Vec<(usize, BigRational)>>;
    pub fn serialize<S: Serializer>(v: &Basis, s: S) -> Result<S::Ok, S::Error> {
        s.collect_seq(v.iter().map(|b| {
            b.iter()
                .map(|(i, r)| (*i, r.to_string()))
                .collect::<Vec<_>>()
        }))
    }
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Basis, D::Error> {
        let raw = Vec::<Vec<(usize, String)>>::deserialize(d)?;
        raw.into_iter()
            .map(|b| {
                b.into_iter()
                    .map(|(i, s)| Ok((i, s.parse().map_err(D::Error::custom)?)))
                    .collect()
            })
            .collect()
    }
}

// ---------------------------------------------------------------------------------------------
// Independent checkers: plain `BigRational` (and modular) arithmetic, nothing from the solver.
// ---------------------------------------------------------------------------------------------

fn row_value(e: &Equation, x: &dyn Fn(usize) -> BigRational) -> BigRational {
    e.terms
        .iter()
        .fold(BigRational::zero(), |s, (v, c)| s + c * x(*v))
}

impl SolutionSpace {
    /// Degrees of freedom: the dimension of the solution space.
    pub fn dof(&self) -> usize {
        self.free.len()
    }

    /// Exact re-check against `sys`: `particular` satisfies every row; each basis vector is sorted,
    /// is 1 at its free unknown and 0 at the others, and satisfies the homogeneous rows;
    /// `|pivots| + dof = unknowns`; and the pivot minor is nonsingular, shown by eliminating it in
    /// the listed order modulo a large prime (a nonzero determinant mod p is nonzero over Q; an
    /// unlucky prime, dividing the determinant, is retried with others). Together: `rank` is the
    /// rank and `span(basis)` is the whole kernel.
    pub fn check(&self, sys: &LinearSystem) -> Result<(), String> {
        let n = sys.unknowns;
        if self.particular.len() != n || self.basis.len() != self.free.len() {
            return Err("sizes of particular/basis/free do not match the system".into());
        }
        if self.rank != self.pivots.len() || self.rank + self.dof() != n {
            return Err(format!(
                "rank {} + dof {} ≠ {n} unknowns",
                self.rank,
                self.dof()
            ));
        }
        for (i, e) in sys.rows.iter().enumerate() {
            if e.terms.iter().any(|(v, _)| *v >= n) {
                return Err(format!("equation {i}: unknown out of range"));
            }
            if row_value(e, &|v| self.particular[v].clone()) != e.rhs {
                return Err(format!("equation {i} fails on the particular solution"));
            }
        }
        let mut free_pos = vec![usize::MAX; n];
        for (k, &f) in self.free.iter().enumerate() {
            if f >= n || free_pos[f] != usize::MAX || !self.particular[f].is_zero() {
                return Err(format!(
                    "free unknown {f}: repeated, out of range or nonzero in particular"
                ));
            }
            free_pos[f] = k;
        }
        // rows of each unknown
        let mut rows_of: Vec<Vec<u32>> = vec![vec![]; n];
        for (i, e) in sys.rows.iter().enumerate() {
            e.terms.iter().for_each(|(v, _)| rows_of[*v].push(i as u32));
        }
        for (k, b) in self.basis.iter().enumerate() {
            if b.windows(2).any(|w| w[0].0 >= w[1].0) || b.last().is_some_and(|t| t.0 >= n) {
                return Err(format!("basis vector {k} not sorted by unknown"));
            }
            for (v, c) in b {
                let unit = free_pos[*v] == k;
                if free_pos[*v] != usize::MAX && (unit != c.is_one() || (!unit && !c.is_zero())) {
                    return Err(format!("basis vector {k} is not unit on the free unknowns"));
                }
            }
            if b.binary_search_by_key(&self.free[k], |t| t.0).is_err() {
                return Err(format!("basis vector {k} misses its free unknown"));
            }
            let at = |v: usize| {
                b.binary_search_by_key(&v, |t| t.0)
                    .map_or_else(|_| BigRational::zero(), |p| b[p].1.clone())
            };
            let mut touched: Vec<u32> = b
                .iter()
                .flat_map(|(v, _)| rows_of[*v].iter().copied())
                .collect();
            touched.sort_unstable();
            touched.dedup();
            for i in touched {
                if !row_value(&sys.rows[i as usize], &at).is_zero() {
                    return Err(format!("basis vector {k} fails homogeneous equation {i}"));
                }
            }
        }
        check_minor(sys, &self.pivots)
    }
}

/// Nonsingularity of the pivot minor by left-looking elimination modulo primes.
fn check_minor(sys: &LinearSystem, pivots: &[(usize, usize)]) -> Result<(), String> {
    const PRIMES: [u64; 4] = [(1 << 61) - 1, 1_000_000_007, 998_244_353, (1 << 31) - 1];
    let mut pos = vec![usize::MAX; sys.unknowns];
    let mut seen_row = vec![false; sys.rows.len()];
    for (k, &(i, c)) in pivots.iter().enumerate() {
        if i >= sys.rows.len() || c >= sys.unknowns || seen_row[i] || pos[c] != usize::MAX {
            return Err(format!("pivot {k} ({i}, {c}) repeated or out of range"));
        }
        seen_row[i] = true;
        pos[c] = k;
    }
    let mut last = String::new();
    'prime: for p in PRIMES {
        let mulm = |a: u64, b: u64| ((a as u128 * b as u128) % p as u128) as u64;
        let powm = |mut a: u64, mut e: u64| {
            let mut r = 1;
            while e > 0 {
                if e & 1 == 1 {
                    r = mulm(r, a);
                }
                a = mulm(a, a);
                e >>= 1;
            }
            r
        };
        let bp = num_bigint::BigInt::from(p);
        let modp = |z: &num_bigint::BigInt| -> u64 {
            let r = ((z % &bp) + &bp) % &bp;
            u64::try_from(r).expect("reduced mod p")
        };
        // u[k]: reduced pivot row k, normalised to 1 at position k, entries at positions > k.
        let mut u: Vec<Vec<(usize, u64)>> = Vec::with_capacity(pivots.len());
        for (k, &(i, _)) in pivots.iter().enumerate() {
            let mut row: BTreeMap<usize, u64> = BTreeMap::new();
            for (v, c) in &sys.rows[i].terms {
                if pos[*v] == usize::MAX {
                    continue;
                }
                let d = modp(c.denom());
                if d == 0 {
                    last = format!("denominator divisible by {p}");
                    continue 'prime;
                }
                let x = mulm(modp(c.numer()), powm(d, p - 2));
                let e = row.entry(pos[*v]).or_insert(0);
                *e = (*e + x) % p;
            }
            row.retain(|_, x| *x != 0);
            while let Some((&j, &x)) = row.first_key_value() {
                if j >= k {
                    break;
                }
                row.remove(&j);
                for &(l, y) in &u[j][1..] {
                    let e = row.entry(l).or_insert(0);
                    *e = (*e + p - mulm(x, y)) % p;
                    if *e == 0 {
                        row.remove(&l);
                    }
                }
            }
            let Some(&piv) = row.get(&k) else {
                last = format!("pivot {k} (equation {i}) vanishes mod {p}");
                continue 'prime;
            };
            let inv = powm(piv, p - 2);
            u.push(row.into_iter().map(|(l, x)| (l, mulm(x, inv))).collect());
        }
        return Ok(());
    }
    Err(format!("pivot minor not shown nonsingular: {last}"))
}

impl Conflict {
    /// Exact re-check: distinct equations, `Σ m_i·row_i` has every coefficient 0 and right-hand
    /// side equal to `constant ≠ 0`.
    pub fn check(&self, sys: &LinearSystem) -> Result<(), String> {
        let mut sum: BTreeMap<usize, BigRational> = BTreeMap::new();
        let mut rhs = BigRational::zero();
        let mut used = std::collections::BTreeSet::new();
        for (i, m) in &self.multipliers {
            let e = sys
                .rows
                .get(*i)
                .ok_or(format!("equation {i} out of range"))?;
            if !used.insert(*i) {
                return Err(format!("equation {i} repeated"));
            }
            for (v, c) in &e.terms {
                *sum.entry(*v).or_insert_with(BigRational::zero) += m * c;
            }
            rhs += m * &e.rhs;
        }
        if let Some((v, c)) = sum.iter().find(|(_, c)| !c.is_zero()) {
            return Err(format!("combination leaves {c}·x{v}"));
        }
        if rhs != self.constant || rhs.is_zero() {
            return Err(format!(
                "combination gives 0 = {rhs}, certificate claims {}",
                self.constant
            ));
        }
        Ok(())
    }
}

fn difference(
    a: &[(usize, BigRational)],
    b: &[(usize, BigRational)],
) -> BTreeMap<usize, BigRational> {
    let mut d: BTreeMap<usize, BigRational> = BTreeMap::new();
    for (v, c) in a {
        *d.entry(*v).or_insert_with(BigRational::zero) += c;
    }
    for (v, c) in b {
        *d.entry(*v).or_insert_with(BigRational::zero) -= c;
    }
    d.retain(|_, c| !c.is_zero());
    d
}

/// Whether `Σ a` and `Σ b` (affine combinations of unknowns, as `(unknown, coefficient)`) agree
/// on every solution: `(a−b)·particular = 0` and `(a−b)·basis_k = 0` for every `k`. Costs one
/// pass over the basis; for many queries use [`SolutionSpace::parametrize`].
pub fn forced_equal(
    space: &SolutionSpace,
    a: &[(usize, BigRational)],
    b: &[(usize, BigRational)],
) -> bool {
    let d = difference(a, b);
    let dot = |v: &mut dyn Iterator<Item = (usize, &BigRational)>| {
        v.filter_map(|(x, c)| d.get(&x).map(|w| w * c))
            .fold(BigRational::zero(), |s, t| s + t)
    };
    dot(&mut space.particular.iter().enumerate()).is_zero()
        && space
            .basis
            .iter()
            .all(|bk| dot(&mut bk.iter().map(|(x, c)| (*x, c))).is_zero())
}

/// Each unknown as `particular + Σ_k coef·t_k` (the transpose of the basis), for answering many
/// [`Parametrization::forced_equal`] queries.
#[derive(Clone, Debug)]
pub struct Parametrization {
    constant: Vec<BigRational>,
    params: Vec<Vec<(usize, BigRational)>>,
}

impl SolutionSpace {
    /// Transposes the basis: the affine form of every unknown in the free parameters.
    pub fn parametrize(&self) -> Parametrization {
        let mut params = vec![vec![]; self.particular.len()];
        for (k, b) in self.basis.iter().enumerate() {
            b.iter().for_each(|(x, c)| params[*x].push((k, c.clone())));
        }
        Parametrization {
            constant: self.particular.clone(),
            params,
        }
    }
}

impl Parametrization {
    /// Unknown `x` as an affine function of the free parameters: its constant and its
    /// `(parameter index, coefficient)` terms (sorted by parameter, no zeros). Two unknowns are
    /// equal on every solution exactly when these coincide.
    pub fn expression(&self, x: usize) -> (&BigRational, &[(usize, BigRational)]) {
        (&self.constant[x], &self.params[x])
    }

    /// Same answer as [`forced_equal`], in time proportional to the unknowns involved.
    pub fn forced_equal(&self, a: &[(usize, BigRational)], b: &[(usize, BigRational)]) -> bool {
        let mut sum: BTreeMap<usize, BigRational> = BTreeMap::new();
        let mut c = BigRational::zero();
        for (x, w) in difference(a, b) {
            c += &w * &self.constant[x];
            for (k, v) in &self.params[x] {
                *sum.entry(*k).or_insert_with(BigRational::zero) += &w * v;
            }
        }
        c.is_zero() && sum.values().all(|v| v.is_zero())
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
    writeln!(out, "{} {}", sys.rows.len(), sys.unknowns)?;
    for e in &sys.rows {
        let d = difference(&e.terms, &[]);
        match layout {
            TextLayout::Dense => {
                for v in 0..sys.unknowns {
                    match d.get(&v) {
                        Some(c) => write!(out, "{c} ")?,
                        None => write!(out, "0 ")?,
                    }
                }
                writeln!(out, "| {}", e.rhs)?;
            }
            TextLayout::Sparse => {
                write!(out, "{} |", e.rhs)?;
                for (v, c) in d {
                    write!(out, " {v}:{c}")?;
                }
                writeln!(out)?;
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_bigint::BigInt;
    use num_traits::Signed;
    use proptest::prelude::*;

    fn r(n: i64, d: i64) -> BigRational {
        BigRational::new(BigInt::from(n), BigInt::from(d))
    }
    fn eq(terms: &[(usize, BigRational)], rhs: BigRational) -> Equation {
        Equation {
            terms: terms.to_vec(),
            rhs,
        }
    }
    fn space(sys: &LinearSystem) -> SolutionSpace {
        match solve(sys) {
            Solution::Consistent(s) => {
                s.check(sys)
                    .unwrap_or_else(|e| panic!("solution space fails its check: {e}"));
                s
            }
            Solution::Inconsistent(c) => panic!("unexpected conflict {c:?}"),
        }
    }
    fn conflict(sys: &LinearSystem) -> Conflict {
        match solve(sys) {
            Solution::Inconsistent(c) => {
                c.check(sys)
                    .unwrap_or_else(|e| panic!("conflict fails its check: {e}"));
                c
            }
            Solution::Consistent(s) => panic!("unexpected solution, rank {}", s.rank),
        }
    }
    /// `x` lies in `particular + span(basis)`: take `t_k = x[free[k]]` and compare.
    fn contains(s: &SolutionSpace, x: &[BigRational]) -> bool {
        let mut y = s.particular.clone();
        for (k, b) in s.basis.iter().enumerate() {
            let t = &x[s.free[k]];
            b.iter().for_each(|(v, c)| y[*v] += t * c);
        }
        y == x
    }

    /// SPEC §6 worked example: unknown `T_k[row][col]` is `k*9 + row*3 + col`.
    fn spec_example(adjacency: bool) -> LinearSystem {
        let t = |k: usize, row: usize, col: usize| k * 9 + row * 3 + col;
        let mut rows = vec![];
        for k in 0..2 {
            for col in 0..3 {
                rows.push(eq(
                    &(0..3)
                        .map(|row| (t(k, row, col), r(1, 1)))
                        .collect::<Vec<_>>(),
                    r(1, 1),
                ));
            }
        }
        // B_0·[1] = T_0·B_0: first column of T_0 is (1,0,0); B_1·[1] = T_1·B_1: last of T_1 (0,0,1).
        for row in 0..3 {
            rows.push(eq(&[(t(0, row, 0), r(1, 1))], r((row == 0) as i64, 1)));
            rows.push(eq(&[(t(1, row, 2), r(1, 1))], r((row == 2) as i64, 1)));
        }
        if adjacency {
            // T_0·B_1 = T_1·B_0: last column of T_0 equals first column of T_1.
            for row in 0..3 {
                rows.push(eq(
                    &[(t(0, row, 2), r(1, 1)), (t(1, row, 0), r(-1, 1))],
                    r(0, 1),
                ));
            }
        }
        LinearSystem { unknowns: 18, rows }
    }

    #[test]
    fn spec_worked_example() {
        // Barycentric + incidence: 18 unknowns; 6 fixed entries; the 6 column sums, two of them
        // (T_0 col 0, T_1 col 2) implied by the fixed entries: rank 6 + 4 = 10, dof 8.
        let s = space(&spec_example(false));
        assert_eq!((s.rank, s.dof()), (10, 8));
        // Adjacency adds 3 links, one implied by the two column sums involved: rank 12, dof 6.
        let sys = spec_example(true);
        let s = space(&sys);
        assert_eq!((s.rank, s.dof()), (12, 6));
        let t0 = [
            [r(1, 1), r(1, 2), r(1, 4)],
            [r(0, 1), r(1, 2), r(1, 2)],
            [r(0, 1), r(0, 1), r(1, 4)],
        ];
        let t1 = [
            [r(1, 4), r(0, 1), r(0, 1)],
            [r(1, 2), r(1, 2), r(0, 1)],
            [r(1, 4), r(1, 2), r(1, 1)],
        ];
        let x: Vec<BigRational> = t0.iter().chain(&t1).flatten().cloned().collect();
        assert!(contains(&s, &x), "de Casteljau pair must be a solution");
        // Forced equalities: T_0[1][2] = T_1[1][0] always; T_0[1][1] = T_1[1][1] not forced.
        let u = |v: usize| vec![(v, r(1, 1))];
        assert!(forced_equal(&s, &u(5), &u(12)));
        assert!(!forced_equal(&s, &u(4), &u(13)));
        let pz = s.parametrize();
        assert!(pz.forced_equal(&u(5), &u(12)) && !pz.forced_equal(&u(4), &u(13)));
        // T_0[0][0] (fixed to 1) equals T_1[2][2] (fixed to 1).
        assert!(pz.forced_equal(&u(0), &u(17)));
    }

    #[test]
    fn serde_round_trip_uses_strings() {
        let s = space(&spec_example(true));
        let json = serde_json::to_string(&Solution::Consistent(s.clone())).expect("serialize");
        assert!(json.contains("\"1/2\"") || json.contains("\"1\""), "{json}");
        let back: Solution = serde_json::from_str(&json).expect("deserialize");
        assert_eq!(back, Solution::Consistent(s));
    }

    #[test]
    fn empty_and_repeated_terms() {
        // x0 + x0 − 2·x0 = 0 is 0 = 0; 0 = 3 is a one-row conflict with constant 3.
        let mut sys = LinearSystem {
            unknowns: 2,
            rows: vec![
                eq(&[(0, r(1, 1)), (0, r(1, 1)), (0, r(-2, 1))], r(0, 1)),
                eq(&[], r(0, 1)),
            ],
        };
        let s = space(&sys);
        assert_eq!((s.rank, s.dof()), (0, 2));
        sys.rows.push(eq(&[], r(3, 1)));
        let c = conflict(&sys);
        assert_eq!(c.multipliers, vec![(2, r(1, 1))]);
        assert_eq!(c.constant, r(3, 1));
    }

    #[test]
    fn exporter_formats() {
        // x0/2 + x2 = 1/3 and x1 = 0 (written with a repeat: 2·x1 − 2·x1 + x1).
        let sys = LinearSystem {
            unknowns: 3,
            rows: vec![
                eq(&[(2, r(1, 1)), (0, r(1, 2))], r(1, 3)),
                eq(&[(1, r(2, 1)), (1, r(-2, 1)), (1, r(1, 1))], r(0, 1)),
            ],
        };
        let mut dense = vec![];
        write_text(&sys, TextLayout::Dense, &mut dense).expect("write");
        assert_eq!(
            String::from_utf8(dense).expect("utf8"),
            "2 3\n1/2 0 1 | 1/3\n0 1 0 | 0\n"
        );
        let mut sparse = vec![];
        write_text(&sys, TextLayout::Sparse, &mut sparse).expect("write");
        assert_eq!(
            String::from_utf8(sparse).expect("utf8"),
            "2 3\n1/3 | 0:1/2 2:1\n0 | 1:1\n"
        );
    }

    /// Deterministic generator for the planted tests.
    struct Rng(u64);
    impl Rng {
        fn next(&mut self) -> u64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            self.0
        }
        fn int(&mut self, lo: i64, hi: i64) -> i64 {
            lo + (self.next() % (hi - lo + 1) as u64) as i64
        }
        fn perm(&mut self, n: usize) -> Vec<usize> {
            let mut p: Vec<usize> = (0..n).collect();
            for i in (1..n).rev() {
                p.swap(i, self.next() as usize % (i + 1));
            }
            p
        }
    }

    /// `A = L·U` with `L` (m×r) containing `I_r` on r chosen rows and `U` (r×n) containing `I_r`
    /// on r chosen columns: both have rank r, so rank A = r. Rows are then scaled by nonzero
    /// rationals (rank unchanged). Returns the system with `b = A·x0` and `x0`.
    fn planted(seed: u64, m: usize, n: usize, rank: usize) -> (LinearSystem, Vec<BigRational>) {
        let mut g = Rng(seed | 1);
        let rank = rank.min(m).min(n);
        let (pr, pc) = (g.perm(m), g.perm(n));
        let mut l = vec![vec![0i64; rank]; m];
        let mut u = vec![vec![0i64; n]; rank];
        for (i, &row) in pr.iter().enumerate() {
            for (k, e) in l[row].iter_mut().enumerate() {
                *e = if i < rank {
                    (i == k) as i64
                } else {
                    g.int(-3, 3)
                };
            }
        }
        for (k, uk) in u.iter_mut().enumerate() {
            for (j, &col) in pc.iter().enumerate() {
                uk[col] = if j < rank {
                    (j == k) as i64
                } else {
                    g.int(-3, 3)
                };
            }
        }
        let x0: Vec<BigRational> = (0..n).map(|_| r(g.int(-5, 5), g.int(1, 3))).collect();
        let rows = (0..m)
            .map(|i| {
                let s = r(
                    g.int(1, 4) * if g.next().is_multiple_of(2) { 1 } else { -1 },
                    g.int(1, 3),
                );
                let terms: Vec<(usize, BigRational)> = (0..n)
                    .map(|j| (j, (0..rank).map(|k| l[i][k] * u[k][j]).sum::<i64>()))
                    .filter(|(_, a)| *a != 0)
                    .map(|(j, a)| (j, &s * BigRational::from_integer(a.into())))
                    .collect();
                let rhs = terms
                    .iter()
                    .fold(BigRational::zero(), |acc, (j, a)| acc + a * &x0[*j]);
                Equation { terms, rhs }
            })
            .collect();
        (LinearSystem { unknowns: n, rows }, x0)
    }

    proptest! {
        #[test]
        fn planted_rank_and_solution(seed in any::<u64>(), m in 1usize..9, n in 1usize..9, rank in 0usize..9) {
            let (sys, x0) = planted(seed, m, n, rank);
            let s = space(&sys);
            let rank = rank.min(m).min(n);
            prop_assert_eq!(s.rank, rank);
            prop_assert_eq!(s.dof(), n - rank);
            prop_assert!(contains(&s, &x0));
        }

        #[test]
        fn planted_conflict_is_minimal(seed in any::<u64>(), m in 1usize..8, n in 1usize..8, rank in 1usize..8, delta in 1i64..5) {
            let (mut sys, _) = planted(seed, m, n, rank);
            // New row: a combination of existing rows with the right-hand side shifted by δ.
            let mut g = Rng(seed.rotate_left(17) | 1);
            let mut row = Equation::default();
            for e in &sys.rows {
                let c = r(g.int(-2, 2), 1);
                row.terms.extend(e.terms.iter().map(|(v, a)| (*v, a * &c)));
                row.rhs += &e.rhs * &c;
            }
            row.rhs += r(delta, 1);
            sys.rows.push(row);
            let c = conflict(&sys);
            let rank = rank.min(m).min(n);
            prop_assert!(c.multipliers.len() <= rank + 1);
            prop_assert!(c.multipliers.iter().any(|(i, _)| *i == m), "the shifted row is needed");
            // Minimal: dropping any one of its rows leaves a consistent system.
            for (drop, _) in &c.multipliers {
                let rows = c.multipliers.iter().filter(|(i, _)| i != drop).map(|(i, _)| sys.rows[*i].clone()).collect();
                let sub = LinearSystem { unknowns: n, rows };
                prop_assert!(matches!(solve(&sub), Solution::Consistent(_)));
            }
        }
    }

    /// BC-IFS-like system: `cells` independent edge-like states, each with `p` unknown m×m
    /// operators `T_k` (m ≥ 3), column sums 1, `T_0` column 0 = e_0 and `T_{p−1}` column m−1 =
    /// e_{m−1} (entry-wise `x = c`), adjacency `T_k` column m−1 = `T_{k+1}` column 0 (`x = y`),
    /// and cell c's `T_0` column 1 tied entry-wise to cell c+1's. Odd cells write their column
    /// sums with every term split in halves. Returns the system, the expected dof, the column
    /// sum row of cell 0's `T_0` column 0 and the rows fixing that column.
    ///
    /// Rank per cell: 2m fixed entries; p·m column sums, 2 implied by the fixed columns;
    /// (p−1)·m adjacency links, one per adjacent column pair implied by the two column sums:
    /// 2m + pm − 2 + (p−1)(m−1). Each tie adds m − 1 (again one link implied by column sums).
    fn structured(cells: usize, m: usize, p: usize) -> (LinearSystem, usize, usize, Vec<usize>) {
        let x = |c: usize, k: usize, row: usize, col: usize| ((c * p + k) * m + row) * m + col;
        let mut rows = vec![];
        let (mut colsum0, mut fixed0) = (0, vec![]);
        for c in 0..cells {
            for k in 0..p {
                for col in 0..m {
                    if (c, k, col) == (0, 0, 0) {
                        colsum0 = rows.len();
                    }
                    let terms: Vec<(usize, BigRational)> = if c % 2 == 1 {
                        (0..m)
                            .flat_map(|row| {
                                [(x(c, k, row, col), r(1, 2)), (x(c, k, row, col), r(1, 2))]
                            })
                            .collect()
                    } else {
                        (0..m).map(|row| (x(c, k, row, col), r(1, 1))).collect()
                    };
                    rows.push(eq(&terms, r(1, 1)));
                }
            }
            for row in 0..m {
                if c == 0 {
                    fixed0.push(rows.len());
                }
                rows.push(eq(&[(x(c, 0, row, 0), r(1, 1))], r((row == 0) as i64, 1)));
                rows.push(eq(
                    &[(x(c, p - 1, row, m - 1), r(1, 1))],
                    r((row == m - 1) as i64, 1),
                ));
                for k in 0..p - 1 {
                    rows.push(eq(
                        &[
                            (x(c, k, row, m - 1), r(1, 1)),
                            (x(c, k + 1, row, 0), r(-1, 1)),
                        ],
                        r(0, 1),
                    ));
                }
                if c + 1 < cells {
                    rows.push(eq(
                        &[(x(c, 0, row, 1), r(1, 1)), (x(c + 1, 0, row, 1), r(-1, 1))],
                        r(0, 1),
                    ));
                }
            }
        }
        let n = cells * p * m * m;
        let rank = cells * (2 * m + p * m - 2 + (p - 1) * (m - 1)) + (cells - 1) * (m - 1);
        (
            LinearSystem { unknowns: n, rows },
            n - rank,
            colsum0,
            fixed0,
        )
    }

    #[test]
    fn structured_dof_matches_count() {
        for (cells, m, p) in [(1, 3, 2), (4, 3, 2), (5, 4, 3), (7, 5, 1), (30, 6, 4)] {
            let (sys, dof, _, _) = structured(cells, m, p);
            let s = space(&sys);
            assert_eq!(s.dof(), dof, "cells {cells}, m {m}, p {p}");
        }
    }

    proptest! {
        #[test]
        fn perturbed_fixed_entry_conflicts(cells in 1usize..5, m in 3usize..6, p in 1usize..4, which in 0usize..6, delta in 1i64..7) {
            // Cell 0's T_0 column 0: the column sum and the m fixed entries are m + 1 rows with one
            // dependency (column sum − Σ fixed rows = 0 = 1 − 1). Shifting one fixed entry by δ/3
            // breaks it: the unique minimal conflict is exactly those m + 1 rows, constant ±δ/3.
            let (mut sys, _, colsum0, fixed0) = structured(cells, m, p);
            let changed = fixed0[which % m];
            sys.rows[changed].rhs += r(delta, 3);
            let c = conflict(&sys);
            let mut want: Vec<usize> = fixed0.clone();
            want.push(colsum0);
            want.sort_unstable();
            prop_assert_eq!(c.multipliers.iter().map(|t| t.0).collect::<Vec<_>>(), want);
            prop_assert!(c.multipliers.iter().all(|(_, k)| k.numer().magnitude() == &1u32.into()));
            prop_assert_eq!(c.constant.abs(), r(delta, 3));
        }
    }

    #[test]
    fn long_presolve_conflict_is_the_chain() {
        // x_0 = 0, x_i − x_{i+1} = 0 (i < N), x_N = 1, rows shuffled: the only dependency uses
        // every row, x_0 − Σ(x_i − x_{i+1}) − x_N = 0 with right-hand side −1, so the certificate
        // is all N + 2 rows with multipliers ±1 and constant ±1 (N + 2 > MINIMIZE_LIMIT: this is
        // the replayed derivation, not the transposed solve).
        let n = MINIMIZE_LIMIT + 100;
        let mut rows = vec![eq(&[(0, r(1, 1))], r(0, 1)), eq(&[(n, r(1, 1))], r(1, 1))];
        rows.extend((0..n).map(|i| eq(&[(i, r(1, 1)), (i + 1, r(-1, 1))], r(0, 1))));
        let order = Rng(7).perm(rows.len());
        let sys = LinearSystem {
            unknowns: n + 1,
            rows: order.iter().map(|&k| rows[k].clone()).collect(),
        };
        let c = conflict(&sys);
        assert_eq!(c.multipliers.len(), n + 2);
        assert!(c.multipliers.iter().all(|(_, m)| m.abs().is_one()));
        assert!(c.constant.abs().is_one());
    }

    #[test]
    fn long_core_conflict_replays_the_elimination() {
        // The tied T_0 column 1 sums of all cells are identical core rows; the last one is set
        // to 2. The certificate comes from the tracked core elimination and the fact forest.
        let (cells, m) = (700, 3);
        let (mut sys, _, _, _) = structured(cells, m, 1);
        let last = (0..sys.rows.len())
            .rev()
            .find(|&i| {
                sys.rows[i].terms.len() >= m && sys.rows[i].terms[0].0 == (cells - 1) * m * m + 1
            })
            .expect("column sum of the last cell's column 1");
        sys.rows[last].rhs = r(2, 1);
        let c = conflict(&sys);
        let s = space(&structured(cells, m, 1).0);
        assert!(c.multipliers.len() <= s.rank + 1);
        assert!(c.multipliers.iter().any(|t| t.0 == last));
    }

    /// Timing (release): `cargo test --release -- --ignored --nocapture scaling`.
    #[test]
    #[ignore]
    fn scaling_structured() {
        for cells in [100, 2_000, 20_000] {
            let (sys, dof, _, _) = structured(cells, 5, 2);
            let t = std::time::Instant::now();
            let s = match solve(&sys) {
                Solution::Consistent(s) => s,
                Solution::Inconsistent(_) => panic!("structured system is consistent"),
            };
            let solved = t.elapsed();
            assert_eq!(s.dof(), dof);
            let t = std::time::Instant::now();
            s.check(&sys).expect("check");
            println!(
                "{} unknowns, {} rows: solve {:?}, check {:?}",
                sys.unknowns,
                sys.rows.len(),
                solved,
                t.elapsed()
            );
        }
    }
}
