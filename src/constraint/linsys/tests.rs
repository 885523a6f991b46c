use super::*;
use num_bigint::BigInt;
use num_traits::{One, Signed};
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
    let mut y = s.particular.to_vec();
    for (k, b) in s.basis.iter().enumerate() {
        let t = &x[s.free[k]];
        b.iter().for_each(|(v, c)| y[v] += t * c);
    }
    y == x
}

/// THEORY §6 worked example: unknown `T_k[row][col]` is `k*9 + row*3 + col`.
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
    LinearSystem::from_equations(18, rows)
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
    // An unknown beyond the 18 of the system takes no part (it is 0 in every direction).
    assert!(forced_equal(&s, &[(5, r(1, 1)), (40, r(3, 1))], &u(12)));
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
fn equations_read_back_as_given() {
    // Terms keep their order, repeats and zero coefficients; a coefficient too big for the two
    // words of the compact form (2^100/3) and one whose denominator is too big (1/2^40) come
    // back exactly.
    let big = BigRational::new(BigInt::from(1) << 100, BigInt::from(3));
    let tiny = BigRational::new(BigInt::from(1), BigInt::from(1) << 40);
    let rows = vec![
        eq(
            &[(2, r(1, 1)), (0, r(1, 2)), (2, r(-1, 1)), (1, r(0, 1))],
            r(1, 3),
        ),
        eq(&[], r(0, 1)),
        eq(&[(4, big.clone()), (3, tiny.clone())], big.clone() + &tiny),
    ];
    let sys = LinearSystem::from_equations(6, rows.clone());
    assert_eq!(
        (sys.len(), sys.term_count(), sys.variable_bound()),
        (3, 6, 5)
    );
    assert_eq!(sys.equations().collect::<Vec<_>>(), rows);
    assert_eq!(sys.get(3), None);
    assert_eq!(LinearSystem::new(4).variable_bound(), 0);
}

#[test]
fn systems_serialise_as_lists_of_equations() {
    // The shape of the serialised system is that of a plain list of equations, written here by
    // hand, so that files written before the compact storage still read.
    let sys = LinearSystem::from_equations(
        3,
        [
            eq(&[(2, r(1, 1)), (0, r(1, 2))], r(1, 3)),
            eq(&[(1, r(2, 1)), (1, r(-2, 1))], r(0, 1)),
        ],
    );
    let json = serde_json::to_string(&sys).expect("serialize");
    let want = concat!(
        r#"{"unknowns":3,"rows":[{"terms":[[2,"1"],[0,"1/2"]],"rhs":"1/3"},"#,
        r#"{"terms":[[1,"2"],[1,"-2"]],"rhs":"0"}]}"#
    );
    assert_eq!(json, want);
    let back: LinearSystem = serde_json::from_str(&json).expect("deserialize");
    assert_eq!(back, sys);
    // A variable beyond the solver's 2^32 − 2 is an error, not a panic.
    let far = r#"{"unknowns":3,"rows":[{"terms":[[4294967295,"1"]],"rhs":"0"}]}"#;
    let err = serde_json::from_str::<LinearSystem>(far).expect_err("out of range");
    assert!(err.to_string().contains("4294967295"), "{err}");
}

#[test]
fn empty_and_repeated_terms() {
    // x0 + x0 − 2·x0 = 0 is 0 = 0; 0 = 3 is a one-row conflict with constant 3.
    let mut sys = LinearSystem::from_equations(
        2,
        vec![
            eq(&[(0, r(1, 1)), (0, r(1, 1)), (0, r(-2, 1))], r(0, 1)),
            eq(&[], r(0, 1)),
        ],
    );
    let s = space(&sys);
    assert_eq!((s.rank, s.dof()), (0, 2));
    sys.push(&eq(&[], r(3, 1)));
    let c = conflict(&sys);
    assert_eq!(c.multipliers, vec![(2, r(1, 1))]);
    assert_eq!(c.constant, r(3, 1));
}

#[test]
fn exporter_formats() {
    // x0/2 + x2 = 1/3 and x1 = 0 (written with a repeat: 2·x1 − 2·x1 + x1).
    let sys = LinearSystem::from_equations(
        3,
        vec![
            eq(&[(2, r(1, 1)), (0, r(1, 2))], r(1, 3)),
            eq(&[(1, r(2, 1)), (1, r(-2, 1)), (1, r(1, 1))], r(0, 1)),
        ],
    );
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
    let rows: Vec<Equation> = (0..m)
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
    (LinearSystem::from_equations(n, rows), x0)
}

proptest! {
    /// Any equations, with small, repeated, zero and big coefficients, read back exactly as
    /// they were given; pushed one at a time they make the same system; and what the solver
    /// proves about them passes the independent check.
    #[test]
    fn compact_storage_reads_back_every_equation(
        rows in proptest::collection::vec(
            (proptest::collection::vec((0usize..6, -3i64..4, 1i64..4, any::<bool>()), 0..6),
             -3i64..4), 0..8),
    ) {
        let coef = |(n, d, big): (i64, i64, bool)| {
            let v = r(n, d);
            if big { v * BigRational::from_integer(BigInt::from(1) << 70) } else { v }
        };
        let eqs: Vec<Equation> = rows
            .iter()
            .map(|(t, c)| Equation {
                terms: t.iter().map(|&(v, n, d, b)| (v, coef((n, d, b)))).collect(),
                rhs: r(*c, 1),
            })
            .collect();
        let sys = LinearSystem::from_equations(6, eqs.clone());
        prop_assert_eq!(sys.equations().collect::<Vec<_>>(), eqs.clone());
        let mut one_by_one = LinearSystem::new(6);
        eqs.iter().for_each(|e| one_by_one.push(e));
        prop_assert_eq!(&one_by_one, &sys);
        match solve(&sys) {
            Solution::Consistent(s) => prop_assert_eq!(s.check(&sys), Ok(())),
            Solution::Inconsistent(c) => prop_assert_eq!(c.check(&sys), Ok(())),
        }
    }
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
        for e in sys.equations() {
            let c = r(g.int(-2, 2), 1);
            row.terms.extend(e.terms.iter().map(|(v, a)| (*v, a * &c)));
            row.rhs += &e.rhs * &c;
        }
        row.rhs += r(delta, 1);
        sys.push(&row);
        let c = conflict(&sys);
        let rank = rank.min(m).min(n);
        prop_assert!(c.multipliers.len() <= rank + 1);
        prop_assert!(c.multipliers.iter().any(|(i, _)| *i == m), "the shifted row is needed");
        // Minimal: dropping any one of its rows leaves a consistent system.
        for (drop, _) in &c.multipliers {
            let rows = c.multipliers.iter().filter(|(i, _)| i != drop).map(|(i, _)| sys.equation(*i));
            let sub = LinearSystem::from_equations(n, rows);
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
        LinearSystem::from_equations(n, rows),
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
        sys.set_rhs(changed, &(sys.rhs(changed) + r(delta, 3)));
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
    let sys = LinearSystem::from_equations(n + 1, order.iter().map(|&k| rows[k].clone()));
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
    let last = (0..sys.len())
        .rev()
        .find(|&i| {
            let terms = sys.equation(i).terms;
            terms.len() >= m && terms[0].0 == (cells - 1) * m * m + 1
        })
        .expect("column sum of the last cell's column 1");
    sys.set_rhs(last, &r(2, 1));
    let c = conflict(&sys);
    let s = space(&structured(cells, m, 1).0);
    assert!(c.multipliers.len() <= s.rank + 1);
    assert!(c.multipliers.iter().any(|t| t.0 == last));
}

/// Structured systems of growing size: the solution space has the expected dimension and passes
/// its independent check. (Timing lives in `benches/solver.rs`.)
#[test]
fn structured_systems_of_growing_size() {
    for cells in [100, 2_000] {
        let (sys, dof, _, _) = structured(cells, 5, 2);
        let s = match solve(&sys) {
            Solution::Consistent(s) => s,
            Solution::Inconsistent(_) => panic!("structured system is consistent"),
        };
        assert_eq!(s.dof(), dof, "{cells} cells");
        s.check(&sys).expect("check");
    }
}

proptest! {
    /// The arena lists hold, per column, exactly what a vector per column would, newest first;
    /// taking a column empties it and leaves the others.
    #[test]
    fn arena_lists_match_a_vector_per_column(
        pushes in proptest::collection::vec((0u32..6, any::<u32>()), 0..60),
        taken in 0u32..6,
    ) {
        let mut lists: Lists<u32> = Lists::new(6, 0);
        let mut want: Vec<Vec<u32>> = vec![vec![]; 6];
        for &(c, t) in &pushes {
            lists.push(c, t);
            want[c as usize].insert(0, t);
        }
        for c in 0..6u32 {
            prop_assert_eq!(lists.iter(c).collect::<Vec<_>>(), want[c as usize].clone());
        }
        // A column beyond the lists (a free root outside the core) is empty.
        prop_assert_eq!(lists.iter(u32::MAX).count(), 0);
        let mut out = vec![7];
        lists.take(taken, &mut out);
        prop_assert_eq!(&out, &want[taken as usize]);
        prop_assert_eq!(lists.iter(taken).count(), 0);
        lists.push(taken, 9);
        prop_assert_eq!(lists.iter(taken).collect::<Vec<_>>(), vec![9]);
        for c in (0..6u32).filter(|&c| c != taken) {
            prop_assert_eq!(lists.iter(c).collect::<Vec<_>>(), want[c as usize].clone());
        }
    }
}
