//! Independent checkers of a solution space and of a conflict: plain `BigRational` (and modular)
//! arithmetic, nothing from the solver.

use super::{Conflict, Equation, LinearSystem, SolutionSpace};
use num_rational::BigRational;
use num_traits::{One, Zero};
use std::collections::BTreeMap;

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
        // One pass over the equations: each is checked on the particular solution and indexed
        // by the unknowns it holds (the rows each basis vector must satisfy).
        let mut rows_of: Vec<Vec<u32>> = vec![vec![]; n];
        for (i, e) in sys.equations().enumerate() {
            if e.terms.iter().any(|(v, _)| *v >= n) {
                return Err(format!("equation {i}: unknown out of range"));
            }
            if row_value(&e, &|v| self.particular.get(v)) != e.rhs {
                return Err(format!("equation {i} fails on the particular solution"));
            }
            e.terms.iter().for_each(|(v, _)| rows_of[*v].push(i as u32));
        }
        let mut free_pos = vec![usize::MAX; n];
        for (k, &f) in self.free.iter().enumerate() {
            if f >= n || free_pos[f] != usize::MAX || !self.particular.is_zero_at(f) {
                return Err(format!(
                    "free unknown {f}: repeated, out of range or nonzero in particular"
                ));
            }
            free_pos[f] = k;
        }
        for (k, b) in self.basis.iter().enumerate() {
            let xs = b.unknowns();
            if xs.windows(2).any(|w| w[0] >= w[1]) || xs.last().is_some_and(|&x| x >= n) {
                return Err(format!("basis vector {k} not sorted by unknown"));
            }
            for (v, c) in b.iter() {
                let unit = free_pos[v] == k;
                if free_pos[v] != usize::MAX && (unit != c.is_one() || (!unit && !c.is_zero())) {
                    return Err(format!("basis vector {k} is not unit on the free unknowns"));
                }
            }
            if xs.binary_search(&self.free[k]).is_err() {
                return Err(format!("basis vector {k} misses its free unknown"));
            }
            let at = |v: usize| b.at(v);
            let mut touched: Vec<u32> = xs
                .iter()
                .flat_map(|&v| rows_of[v].iter().copied())
                .collect();
            touched.sort_unstable();
            touched.dedup();
            for i in touched {
                if !row_value(&sys.equation(i as usize), &at).is_zero() {
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
    let mut seen_row = vec![false; sys.len()];
    for (k, &(i, c)) in pivots.iter().enumerate() {
        if i >= sys.len() || c >= sys.unknowns || seen_row[i] || pos[c] != usize::MAX {
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
            for (v, c) in &sys.equation(i).terms {
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
            let e = sys.get(*i).ok_or(format!("equation {i} out of range"))?;
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

pub(super) fn difference(
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
    // Unknowns beyond the space count as 0, as when this walked the particular solution.
    let particular = d
        .iter()
        .filter(|(&x, _)| x < space.particular.len())
        .fold(BigRational::zero(), |s, (&x, w)| {
            s + w * space.particular.get(x)
        });
    particular.is_zero()
        && space.basis.iter().all(|bk| {
            bk.unknowns()
                .iter()
                .enumerate()
                .filter_map(|(j, x)| d.get(x).map(|w| w * bk.coef(j)))
                .fold(BigRational::zero(), |s, t| s + t)
                .is_zero()
        })
}
