//! The exact sparse linear system of the BC-IFS constraints (THEORY §6): solve over Q, report rank,
//! degrees of freedom, a particular solution and a basis of directions, or a small conflicting
//! set of equations with the rational combination that proves `0 = c ≠ 0`.
//!
//! # Method
//! 1. **Presolve** (`crate::constraint::presolve`): rows that after substitution read `0 = c`, `a·x = c` or
//!    `a·x + b·y = c` become facts (fixed values, affine union-find links), repeated to a fixed
//!    point. The BC-IFS systems (column sums, `x = c` incidences, `x = y` adjacencies) are mostly
//!    solved here in near-linear time.
//! 2. **Core**: the remaining rows, over the remaining roots, are cleared to integers and
//!    eliminated fraction-free (`row ← (a/g)·row − (b/g)·pivot row`, then divided by the row's
//!    content), choosing pivots Markowitz-style (shortest active row, then the column with the
//!    fewest active rows, preferring unit coefficients), then back-substituted to reduced form.
//! 3. **Conflict**: the derivation of `0 = c ≠ 0` is replayed backwards into a combination of
//!    original rows: through the fact forest (`crate::constraint::presolve`), and for a contradiction found
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

use crate::constraint::presolve::{integer_row, Presolve, RowFate, Rows, Q, Z};
pub use compact::{Direction, Directions, Rationals};
use num_rational::BigRational;
use num_traits::Zero;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use system::{rat, rat_terms};
pub use system::{write_text, Equation, LinearSystem, TextLayout};

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
    pub particular: Rationals,
    /// The unknown serving as free parameter of each direction, increasing.
    pub free: Vec<usize>,
    /// Sparse direction vectors sorted by unknown; direction `k` is 1 at `free[k]` and 0 at the
    /// other free unknowns.
    pub basis: Directions,
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
    assert!(
        sys.unknowns < u32::MAX as usize,
        "at most 2^32 − 2 unknowns"
    );
    assert!(
        sys.variable_bound() <= sys.unknowns,
        "unknown {} out of range",
        sys.variable_bound() - 1
    );
    match run(sys.unknowns, sys.rows(), true, true) {
        Ok(space) => Solution::Consistent(space),
        Err(failure) => {
            let (ps, seeds) = *failure.expect("certified");
            Solution::Inconsistent(certificate(&ps, seeds))
        }
    }
}

/// The presolve state and the substituted rows (with weights) whose sum reads `0 = c ≠ 0`.
type Failure<'a> = Box<(Presolve<'a>, Vec<(usize, Q)>)>;

/// Presolve + core over `rows` in `n` unknowns (every variable of `rows` below `n`); the
/// presolve runs a second time only when the system is inconsistent and `certify`. On
/// inconsistency returns, with `certify`, the presolve state that can replay its facts and the
/// conflicting combination.
fn run(
    n: usize,
    rows: &Rows,
    want_basis: bool,
    certify: bool,
) -> Result<SolutionSpace, Option<Failure<'_>>> {
    let mut ps = Presolve::new(n, rows, false);
    if ps.run().is_none() {
        let pending = pending(&ps);
        let Core {
            rows, roots, local, ..
        } = build_core(&mut ps, &pending);
        ps.release_run();
        if let Ok(core) = eliminate(rows, roots.len(), false) {
            return Ok(assemble(
                &mut ps,
                &pending,
                (&roots, &local),
                core,
                want_basis,
            ));
        }
    }
    if !certify {
        return Err(None);
    }
    // Inconsistent. The presolve and the elimination are deterministic, so both are replayed:
    // the presolve now keeping the rows and factors of its facts, the elimination now tracking
    // the combination of rows that each of its rows is.
    drop(ps);
    let mut ps = Presolve::new(n, rows, true);
    if let Some(bad) = ps.run() {
        return Err(Some(Box::new((ps, vec![(bad, Q::int(Z::one()))]))));
    }
    let pending = pending(&ps);
    let Core {
        rows,
        roots,
        scales,
        ..
    } = build_core(&mut ps, &pending);
    let (_, combo) = eliminate(rows, roots.len(), true).expect_err("same elimination");
    let seeds = combo
        .into_iter()
        .map(|(k, w)| (pending[k as usize], w.mul(&scales[k as usize])));
    Err(Some(Box::new((ps, seeds.collect()))))
}

/// The rows presolve left pending, which make the core.
fn pending(ps: &Presolve) -> Vec<usize> {
    (0..ps.row_count())
        .filter(|&i| ps.fate[i] == RowFate::Pending)
        .collect()
}

/// The rows presolve left, ready for elimination.
struct Core {
    /// The pending rows substituted and cleared to integers, over local column ids.
    rows: Vec<CRow>,
    /// The root of each local column.
    roots: Vec<u32>,
    /// The local column of each root in the core (`u32::MAX` for the other unknowns).
    local: Vec<u32>,
    /// The integer scale of each row.
    scales: Vec<Q>,
}

/// The core of the pending rows.
fn build_core(ps: &mut Presolve, pending: &[usize]) -> Core {
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
    Core {
        rows: crows,
        roots,
        local,
        scales,
    }
}

/// Builds the public solution space from the facts and the reduced core.
fn assemble(
    ps: &mut Presolve,
    pending: &[usize],
    (roots, local): (&[u32], &[u32]),
    core: Vec<(usize, u32, CRow)>,
    want_basis: bool,
) -> SolutionSpace {
    let n = ps.n;
    // The pivot of each local core column (`u32::MAX` for a free one).
    let mut pivot_of: Vec<u32> = vec![u32::MAX; roots.len()];
    let mut pivots: Vec<(usize, usize)> = Vec::with_capacity(ps.facts.len() + core.len());
    pivots.extend(ps.facts.iter().map(|&(i, c)| (i as usize, c as usize)));
    for (k, (i, p, _)) in core.iter().enumerate() {
        pivot_of[*p as usize] = k as u32;
        pivots.push((pending[*i], roots[*p as usize] as usize));
    }
    // The core pivot whose root is `r`, if any.
    let pivot_of = &pivot_of;
    let core_pivot = |r: u32| {
        let c = local[r as usize];
        pivot_of
            .get(c as usize)
            .filter(|&&k| k != u32::MAX)
            .map(|&k| k as usize)
    };
    // The coefficient of each core row's pivot.
    let pivot_coef: Vec<Q> = core
        .iter()
        .map(|(_, p, row)| Q::int(row.coef(*p).expect("pivot").clone()))
        .collect();
    let root_val = |ps: &Presolve, r: u32| -> Q {
        if let Some(v) = ps.root_value(r) {
            return v;
        }
        match core_pivot(r) {
            Some(k) => Q::int(core[k].2.rhs.clone()).div(&pivot_coef[k]),
            None => Q::zero(),
        }
    };
    let mut particular = Rationals::with_capacity(n);
    let mut free = vec![];
    // For the basis: each unknown's root (`u32::MAX` in a fixed class, which no direction
    // moves), and the size of each other class counted into `start[r]`.
    let mut root_of: Vec<u32> = Vec::with_capacity(if want_basis { n } else { 0 });
    let mut start = vec![0u32; if want_basis { n + 1 } else { 0 }];
    let mut moving = 0;
    // One pass over the unknowns compresses each path and reads the relation it leaves: the
    // union-find nodes of a million unknowns are far out of cache, so they are read once here.
    for x in 0..n as u32 {
        let (r, f, g) = ps.find(x);
        let fixed = ps.root_fixed(r);
        if want_basis {
            if fixed {
                root_of.push(u32::MAX);
            } else {
                root_of.push(r);
                start[r as usize] += 1;
                moving += 1;
            }
        }
        let v = if r == x {
            if !fixed && core_pivot(x).is_none() {
                free.push(x as usize);
            }
            root_val(ps, x)
        } else {
            f.mul(&root_val(ps, r)).add(&g)
        };
        push_q(&mut particular, &v);
    }
    let ps = &*ps;
    let mut basis = Directions::default();
    if want_basis {
        // dirs[local core column of a free root]: (pivot k, position of the column in its row);
        // the parameter's coefficient in pivot root k is −row[position]/row[pivot].
        let entries = core.iter().map(|(_, _, row)| row.cols.len() - 1).sum();
        let mut dirs: Lists<(u32, u32)> = Lists::new(roots.len(), entries);
        for (k, (_, p, row)) in core.iter().enumerate() {
            for (j, c) in row.cols.iter().enumerate() {
                if c != p {
                    dirs.push(*c, (k as u32, j as u32));
                }
            }
        }
        // The members of each class that is not fixed, with their factors `F` (`x = F·root +
        // G`), CSR by root: the counts in `start[r]` are summed so that `start[r]` ends class
        // `r`, then the members are filled from the last unknown down, which moves each
        // `start[r]` back to where class `r` begins and leaves each class increasing. Reading
        // the factors here, in order, spares the directions a read of a union-find node, far
        // out of cache, for each of their entries.
        (1..=n).for_each(|i| start[i] += start[i - 1]);
        let mut members = vec![0u32; moving];
        let mut factors = vec![Q::zero(); moving];
        for x in (0..n as u32).rev() {
            let r = root_of[x as usize];
            if r != u32::MAX {
                let k = &mut start[r as usize];
                *k -= 1;
                members[*k as usize] = x;
                factors[*k as usize] = ps.relation(x).1;
            }
        }
        drop(root_of);
        let class = |r: u32| start[r as usize] as usize..start[r as usize + 1] as usize;
        let coef = |(k, j): (u32, u32)| {
            let (_, p, row) = &core[k as usize];
            let c = Q::int(row.vals[j as usize].neg()).div(&pivot_coef[k as usize]);
            (roots[*p as usize], c)
        };
        // The exact size of the basis, so that its arrays are allocated once.
        let entries = free.iter().map(|&f| {
            let d = dirs
                .iter(local[f])
                .map(|(k, _)| class(roots[core[k as usize].1 as usize]).len());
            class(f as u32).len() + d.sum::<usize>()
        });
        basis = Directions::with_capacity(free.len(), entries.sum());
        let one = Q::int(Z::one());
        // One scratch vector for every direction: the directions share their storage.
        let mut v: Vec<(u32, Q)> = vec![];
        for &f in &free {
            v.clear();
            let d = dirs.iter(local[f]).map(coef);
            for (root, c) in std::iter::once((f as u32, one.clone())).chain(d) {
                let k = class(root);
                v.extend(
                    members[k.clone()]
                        .iter()
                        .zip(&factors[k])
                        .map(|(&x, f)| (x, f.mul(&c))),
                );
            }
            v.sort_unstable_by_key(|t| t.0);
            for (x, q) in &v {
                push_q(basis.entry(*x as usize), q);
            }
            basis.close();
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

/// Appends a presolve value to the compact store, without building a `BigRational` when it is
/// small.
fn push_q(out: &mut Rationals, q: &Q) {
    match q.small() {
        Some((a, b)) => out.push_small(a, b as u64),
        None => out.push(&q.big()),
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
        let constant = multipliers.iter().fold(BigRational::zero(), |s, (i, m)| {
            s + m * ps.rows.rhs[*i].big()
        });
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
        let (vars, coefs) = ps.rows.row(i);
        for (&v, q) in vars.iter().zip(coefs) {
            by_col.entry(v).or_default().push((k as u32, q.clone()));
        }
    }
    let rhs = &ps.rows.rhs;
    let rhs_row: Vec<(u32, Q)> = rows
        .iter()
        .enumerate()
        .filter(|(_, &i)| !rhs[i].is_zero())
        .map(|(k, &i)| (k as u32, rhs[i].clone()))
        .collect();
    let terms = by_col.values().map(Vec::len).sum::<usize>() + rhs_row.len();
    let mut transposed = Rows::with_capacity(by_col.len() + 1, terms);
    by_col
        .into_values()
        .for_each(|t| transposed.push(t, Q::zero()));
    transposed.push(rhs_row, Q::int(Z::one()));
    let space = run(rows.len(), &transposed, false, false).ok()?;
    let m: Vec<(usize, Q)> = (0..space.particular.len())
        .filter(|&k| !space.particular.is_zero_at(k))
        .map(|k| (rows[k], Q::from_big(&space.particular.get(k))))
        .collect();
    Some(m)
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
            b.iter().for_each(|(x, c)| params[x].push((k, c)));
        }
        Parametrization {
            constant: self.particular.to_vec(),
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

    /// The value of every unknown at the free parameters `t` (one per parameter), exactly.
    pub fn at(&self, t: &[BigRational]) -> Vec<BigRational> {
        self.constant
            .iter()
            .zip(&self.params)
            .map(|(c, terms)| terms.iter().fold(c.clone(), |acc, (k, v)| acc + v * &t[*k]))
            .collect()
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

mod check;
mod compact;
mod elimination;
mod system;
#[cfg(test)]
mod tests;

use check::difference;
pub use check::forced_equal;
use elimination::{eliminate, CRow, Lists};
