//! The linear-system steps: a solution space (particular solution, kernel basis, a pivot minor
//! shown nonsingular modulo a prime) and an inconsistency (a combination giving `0 = c ≠ 0`).

use super::system::{tie, Tie};
use super::{rat, Checked, Equation, Q};
use crate::certificate::{ConflictStep, Row, SolutionStep};
use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{One, ToPrimitive, Zero};
use std::collections::{BTreeMap, BTreeSet};

pub(super) fn parse_rows(rows: &[Row], unknowns: usize) -> Result<Vec<Equation>, String> {
    rows.iter()
        .enumerate()
        .map(|(i, r)| {
            let terms = r
                .terms
                .iter()
                .map(|(v, c)| match *v < unknowns {
                    true => Ok((*v, rat(c)?)),
                    false => Err(format!("row {i}: unknown {v} out of range")),
                })
                .collect::<Result<Vec<_>, String>>()?;
            Ok((terms, rat(&r.rhs)?))
        })
        .collect()
}

/// A sparse vector with strictly increasing, in-range indices, as a map.
fn sparse(v: &[(usize, String)], n: usize, what: &str) -> Result<BTreeMap<usize, Q>, String> {
    if v.windows(2).any(|w| w[0].0 >= w[1].0) || v.last().is_some_and(|x| x.0 >= n) {
        return Err(format!("{what}: indices not increasing or out of range"));
    }
    v.iter().map(|(i, s)| Ok((*i, rat(s)?))).collect()
}

fn dot(terms: &[(usize, Q)], x: &BTreeMap<usize, Q>) -> Q {
    terms
        .iter()
        .filter_map(|(v, c)| x.get(v).map(|y| c * y))
        .sum()
}

/// A solution space of the system tied to the claim (rebuilt from the closure or the automaton,
/// or the claim's own system).
pub(super) fn check_solution(s: &SolutionStep, to: Tie) -> Checked {
    let n = s.system.unknowns;
    // rank + dof = unknowns with rank = |pivots| and dof = |free|, first: `n` then bounds the
    // allocations below by the certificate's own size.
    let dof = s.free.len();
    if s.rank != s.pivots.len() || s.dof != dof || s.rank.checked_add(dof) != Some(n) {
        return Err(format!(
            "rank {} (|pivots| = {}) + dof {} (|free| = {dof}) ≠ {n} unknowns",
            s.rank,
            s.pivots.len(),
            s.dof
        ));
    }
    let rows = parse_rows(&s.system.rows, n)?;
    let system = tie(&s.system, &rows, to)?;
    satisfies(&rows, n, &s.particular, &s.free, &s.basis)?;
    let p = nonsingular_minor(&rows, &s.pivots, n)?;
    Ok((
        format!(
            "{system}; rank {} (pivot minor nonsingular mod {p}), {dof} degrees of freedom; the \
             solution set is exactly particular + span(basis)",
            s.rank
        ),
        format!(
            "constraint system: consistent, rank {}, {dof} degrees of freedom",
            s.rank
        ),
    ))
}

/// Checks a solution space's witness against `rows` over `n` unknowns: the particular solution
/// (sparse, other unknowns 0) satisfies every row; the free unknowns are increasing and in
/// range; each basis vector is 1 at its own free unknown, 0 at the other free ones, and
/// satisfies every homogeneous row it touches (so the vectors are independent solutions of the
/// homogeneous system: the nullity is at least their number).
pub(super) fn satisfies(
    rows: &[Equation],
    n: usize,
    particular: &[(usize, String)],
    free: &[usize],
    basis: &[Vec<(usize, String)>],
) -> Result<(), String> {
    let part = sparse(particular, n, "particular solution")?;
    if let Some(i) = rows.iter().position(|(t, rhs)| dot(t, &part) != *rhs) {
        return Err(format!("the particular solution fails row {i}"));
    }
    if free.windows(2).any(|w| w[0] >= w[1]) || free.last().is_some_and(|&f| f >= n) {
        return Err("free unknowns not increasing or out of range".into());
    }
    if basis.len() != free.len() {
        return Err(format!(
            "{} basis vectors for {} free unknowns",
            basis.len(),
            free.len()
        ));
    }
    let mut rows_of: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (i, (t, _)) in rows.iter().enumerate() {
        t.iter().for_each(|(v, _)| rows_of[*v].push(i));
    }
    // Which unknown is free, and the index of its basis vector: one pass over each vector's
    // own entries instead of a scan of every free unknown per vector.
    let mut free_at: Vec<Option<usize>> = vec![None; n];
    free.iter()
        .enumerate()
        .for_each(|(j, &f)| free_at[f] = Some(j));
    for (k, b) in basis.iter().enumerate() {
        let b = sparse(b, n, &format!("basis vector {k}"))?;
        if b.get(&free[k]).is_none_or(|x| !x.is_one()) {
            return Err(format!(
                "basis vector {k} is not 1 at free unknown {}",
                free[k]
            ));
        }
        if let Some((f, _)) = b
            .iter()
            .find(|(v, x)| free_at[**v].is_some_and(|j| j != k) && !x.is_zero())
        {
            return Err(format!("basis vector {k} is not 0 at free unknown {f}"));
        }
        let touched: BTreeSet<usize> = b.keys().flat_map(|v| rows_of[*v].iter().copied()).collect();
        if let Some(i) = touched
            .into_iter()
            .find(|&i| !dot(&rows[i].0, &b).is_zero())
        {
            return Err(format!("basis vector {k} fails homogeneous row {i}"));
        }
    }
    Ok(())
}

/// Shows the pivot minor nonsingular: eliminating its rows in the listed order modulo a prime
/// gives an upper-triangular matrix with nonzero diagonal. Returns the prime that worked.
fn nonsingular_minor(
    rows: &[Equation],
    pivots: &[(usize, usize)],
    n: usize,
) -> Result<u64, String> {
    let mut col_pos = vec![usize::MAX; n];
    let mut used = BTreeSet::new();
    for (k, &(r, c)) in pivots.iter().enumerate() {
        if r >= rows.len() || c >= n || !used.insert(r) || col_pos[c] != usize::MAX {
            return Err(format!("pivot {k} ({r}, {c}) is repeated or out of range"));
        }
        col_pos[c] = k;
    }
    let mut why = String::from("no prime tried");
    'prime: for p in [(1u64 << 61) - 1, 1_000_000_007, 998_244_353, 2_147_483_647] {
        let mul = |a: u64, b: u64| ((u128::from(a) * u128::from(b)) % u128::from(p)) as u64;
        let inv = |a: u64| {
            let (mut r, mut b, mut e) = (1u64, a, p - 2);
            while e > 0 {
                if e & 1 == 1 {
                    r = mul(r, b);
                }
                b = mul(b, b);
                e >>= 1;
            }
            r
        };
        let modp = |z: &BigInt| z.mod_floor(&BigInt::from(p)).to_u64().unwrap_or(0);
        let mut done: Vec<BTreeMap<usize, u64>> = Vec::with_capacity(pivots.len());
        for (k, &(r, _)) in pivots.iter().enumerate() {
            let mut row: BTreeMap<usize, u64> = BTreeMap::new();
            for (v, c) in &rows[r].0 {
                if col_pos[*v] == usize::MAX {
                    continue;
                }
                let d = modp(c.denom());
                if d == 0 {
                    why = format!("a denominator is divisible by {p}");
                    continue 'prime;
                }
                let e = row.entry(col_pos[*v]).or_insert(0);
                *e = (*e + mul(modp(c.numer()), inv(d))) % p;
            }
            row.retain(|_, x| *x != 0);
            while let Some((&j, &x)) = row.first_key_value() {
                if j >= k {
                    break;
                }
                // Fill-in cannot be foreseen from the sizes: the elimination is metered as it
                // goes (a modular multiply-add and a map update, charged as 4 word operations).
                super::within_work(
                    "the elimination of the pivot minor",
                    4 * done[j].len() as u128,
                )?;
                for (&l, &y) in &done[j] {
                    let e = row.entry(l).or_insert(0);
                    *e = (*e + p - mul(x, y)) % p;
                }
                row.retain(|_, x| *x != 0);
            }
            let Some(&d) = row.get(&k) else {
                why = format!("pivot {k} vanishes after elimination mod {p}");
                continue 'prime;
            };
            let di = inv(d);
            done.push(row.into_iter().map(|(l, x)| (l, mul(x, di))).collect());
        }
        return Ok(p);
    }
    Err(format!("the pivot minor is not shown nonsingular: {why}"))
}

/// An inconsistency of the system tied to the claim.
pub(super) fn check_conflict(c: &ConflictStep, to: Tie) -> Checked {
    let rows = parse_rows(&c.system.rows, c.system.unknowns)?;
    let system = tie(&c.system, &rows, to)?;
    let mut sum: BTreeMap<usize, Q> = BTreeMap::new();
    let mut rhs = Q::zero();
    let mut used = BTreeSet::new();
    for (i, m) in &c.multipliers {
        let m = rat(m)?;
        let Some((terms, b)) = rows.get(*i).filter(|_| used.insert(*i)) else {
            return Err(format!("multiplier for row {i}: repeated or out of range"));
        };
        for (v, a) in terms {
            *sum.entry(*v).or_insert_with(Q::zero) += &m * a;
        }
        rhs += &m * b;
    }
    if let Some((v, a)) = sum.iter().find(|(_, a)| !a.is_zero()) {
        return Err(format!("the combination leaves {a}·x{v}"));
    }
    if rhs != rat(&c.constant)? || rhs.is_zero() {
        return Err(format!(
            "the combination gives 0 = {rhs}, the certificate claims {}",
            c.constant
        ));
    }
    Ok((
        format!(
            "{system}; {} of them combine to 0 = {rhs}: no solution",
            c.multipliers.len()
        ),
        "constraint system: inconsistent (no solution)".into(),
    ))
}
