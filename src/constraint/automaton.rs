//! The BC-IFS automaton and its constraint system (THEORY §6).
//!
//! States carry a barycentric space of dimension m; operators (subdivision `T`, embedding `B`,
//! permutation `J`, or any other) are given exact matrices or are unknown; constraints are
//! equalities of words (products of operators and literal matrices). With at most one unknown
//! factor per word every constraint is linear in the unknown entries, and the system is handed to
//! the exact sparse solver ([`crate::constraint::linsys`]).

use crate::algebra::matrix::Matrix;
use crate::constraint::linsys::{self, LinearSystem, Solution};
use crate::constraint::presolve::{Q, Z};
use crate::error::{Error, Result, Span};
use num_rational::BigRational;
use num_traits::{One, Zero};
use serde::Serialize;
use std::collections::BTreeMap;

/// What an operator is, for reports and defaults (barycentric constraints apply to `Sub` and
/// `Embed`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum OpKind {
    /// A subdivision operator `T_k^q`.
    Sub,
    /// An embedding operator `B_i^q`.
    Embed,
    /// A permutation `J`.
    Perm,
    /// Anything else.
    Other,
}

/// A state (cell) with its barycentric dimension.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct State {
    /// Name.
    pub name: String,
    /// Number of control points m.
    pub dim: usize,
}

/// An operator from state `from` (columns) into state `to` (rows).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Operator {
    /// Name.
    pub name: String,
    /// Kind.
    pub kind: OpKind,
    /// Row state q.
    pub to: usize,
    /// Column state w.
    pub from: usize,
    /// The exact matrix, or `None` when unknown.
    pub value: Option<Matrix>,
}

/// A factor of a word.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Factor {
    /// An operator, by index.
    Op(usize),
    /// A literal matrix (a vector is a one-column matrix).
    Literal(Matrix),
}

/// The kinds of constraints, for reports.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum ConstraintKind {
    /// `B_i^q · T_j^w = T_k^q · B_l^(w_k)`.
    Incidence,
    /// `T_a^q · B_l · J = T_b^q · B_m`.
    Adjacency,
    /// Any other equality of words (hand-written files).
    Word,
}

/// An equality of two words.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Constraint {
    /// Where it comes from (a file line, or a face-type incidence), for reports.
    pub label: String,
    /// Its span in a source file, if any.
    pub span: Option<Span>,
    /// Kind.
    pub kind: ConstraintKind,
    /// Left word.
    pub lhs: Vec<Factor>,
    /// Right word.
    pub rhs: Vec<Factor>,
}

/// A BC-IFS automaton with its constraints.
#[derive(Clone, Debug, Default)]
pub struct Automaton {
    /// States.
    pub states: Vec<State>,
    /// Operators.
    pub operators: Vec<Operator>,
    /// Constraints.
    pub constraints: Vec<Constraint>,
    /// Operators whose columns must each sum to 1.
    pub barycentric: Vec<usize>,
}

/// Where a row of the linear system comes from.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub enum RowOrigin {
    /// Entry (r, c) of constraint `constraint`.
    Entry {
        /// Constraint index.
        constraint: usize,
        /// Row of the word's matrix.
        r: usize,
        /// Column of the word's matrix.
        c: usize,
    },
    /// Column `c` of operator `op` sums to 1.
    Barycentric {
        /// Operator index.
        op: usize,
        /// Column.
        c: usize,
    },
}

/// The linear system of an automaton with the provenance of each row and unknown.
#[derive(Clone, Debug)]
pub struct Linearized {
    /// The system.
    pub system: LinearSystem,
    /// Provenance of each row.
    pub origins: Vec<RowOrigin>,
    /// For each unknown: (operator index, row, column).
    pub unknown_entries: Vec<(usize, usize, usize)>,
    /// First unknown index of each operator (unknown operators only).
    pub offsets: Vec<Option<usize>>,
}

/// A linear form: terms over unknowns plus a constant.
type Form = (Vec<(usize, Q)>, BigRational);

impl Automaton {
    /// Adds a state; returns its index.
    pub fn add_state(&mut self, name: impl Into<String>, dim: usize) -> usize {
        self.states.push(State {
            name: name.into(),
            dim,
        });
        self.states.len() - 1
    }

    /// Adds an operator; returns its index.
    pub fn add_op(
        &mut self,
        name: impl Into<String>,
        kind: OpKind,
        to: usize,
        from: usize,
        value: Option<Matrix>,
    ) -> usize {
        self.operators.push(Operator {
            name: name.into(),
            kind,
            to,
            from,
            value,
        });
        self.operators.len() - 1
    }

    /// The number of unknown entries (of the unknown operators), known before linearising.
    pub fn unknown_count(&self) -> usize {
        self.operators
            .iter()
            .filter(|o| o.value.is_none())
            .map(|o| self.states[o.to].dim * self.states[o.from].dim)
            .sum()
    }

    /// Checks the solve of this automaton's system against `limits` before it is built: its
    /// unknowns against `--max-unknowns` and its [estimated memory](Self::solve_memory_estimate)
    /// against `--max-memory`. Every command that solves calls this one check.
    pub fn check_solve_limits(&self, limits: &crate::topology::Limits) -> Result<()> {
        limits.check_unknowns(self.unknown_count())?;
        limits.check_memory(self.solve_memory_estimate())
    }

    /// The memory a solve of this automaton takes, in bytes, estimated from its shapes alone
    /// (before the system is built): about 1,100 bytes per unknown (its entry, its value in the
    /// particular solution, its basis direction and report line when free — measured on
    /// `state e N` with one unknown `N×N` operator when the system stored `BigRational`s: 104 MB
    /// for N = 300, 403 MB for N = 600), 100 per equation row and 64 per term, with a word
    /// `A·X·B` counted as `p·q` terms per entry for an unknown `X` of shape `p×q` (fewer when `A`
    /// or `B` is absent). Fill-in during elimination comes on top, while the term count is an
    /// upper bound. Since the compact system of issue #34 the estimate runs above the whole
    /// `lacuna solve` process's peak: 95 against 73 MiB and 378 against 272 MiB on `state e`
    /// 300 and 600; 2,140 against 952 MiB on `B4 C4 B3^3 C4 B4 C3 B2^2 | C3 B2 C3 | A3 | 3`
    /// (1.18 M unknowns); 3,275 against 1,536 MiB on the closure of
    /// `B3 B2 C2 C4 B2 C4 C4 | B2 B2 C3 | A1 | 3` (1.76 M unknowns). It is left on that side on
    /// purpose (it refuses some solves that would fit, which `--max-memory` lets through); it is
    /// an estimate, not a proved bound.
    pub fn solve_memory_estimate(&self) -> u128 {
        let unknowns = self.unknown_count() as u128;
        let (mut rows, mut terms) = (0u128, 0u128);
        for c in &self.constraints {
            let (r, k) = match (c.lhs.first(), c.lhs.last()) {
                (Some(first), Some(last)) => (self.shape(first).0, self.shape(last).1),
                _ => (0, 0),
            };
            let entries = (r as u128) * (k as u128);
            rows += entries;
            for word in [&c.lhs, &c.rhs] {
                terms += entries * self.terms_per_entry(word);
            }
        }
        for &o in &self.barycentric {
            let op = &self.operators[o];
            let (r, k) = (
                self.states[op.to].dim as u128,
                self.states[op.from].dim as u128,
            );
            rows += k;
            if op.value.is_none() {
                terms += r * k;
            }
        }
        1100 * unknowns + 100 * rows + 64 * terms
    }

    /// At most how many unknowns one entry of `word` involves (its one unknown factor `X`, `p×q`:
    /// `p` when a factor stands left of it, times `q` when one stands right of it).
    fn terms_per_entry(&self, word: &[Factor]) -> u128 {
        let unknown = word.iter().position(|f| match f {
            Factor::Op(o) => self.operators[*o].value.is_none(),
            Factor::Literal(_) => false,
        });
        let Some(i) = unknown else { return 0 };
        let (p, q) = self.shape(&word[i]);
        let left = if i > 0 { p as u128 } else { 1 };
        let right = if i + 1 < word.len() { q as u128 } else { 1 };
        left * right
    }

    /// The shape (rows, cols) of a factor.
    fn shape(&self, f: &Factor) -> (usize, usize) {
        match f {
            Factor::Op(o) => {
                let op = &self.operators[*o];
                (self.states[op.to].dim, self.states[op.from].dim)
            }
            Factor::Literal(m) => (m.rows, m.cols),
        }
    }

    fn word_text(&self, w: &[Factor]) -> String {
        w.iter()
            .map(|f| match f {
                Factor::Op(o) => self.operators[*o].name.clone(),
                Factor::Literal(m) => m.to_string(),
            })
            .collect::<Vec<_>>()
            .join(" * ")
    }

    /// The text of constraint `k` (`lhs = rhs`).
    pub fn constraint_text(&self, k: usize) -> String {
        let c = &self.constraints[k];
        format!("{} = {}", self.word_text(&c.lhs), self.word_text(&c.rhs))
    }

    fn constraint_error(&self, k: usize, code: &'static str, msg: String) -> Error {
        let c = &self.constraints[k];
        match &c.span {
            Some(span) => Error::syntax(code, msg, span.clone(), None),
            None => Error::Syntax(Box::new(crate::error::Diagnostic {
                code,
                message: format!("{} ({})", msg, c.label),
                span: None,
                source: None,
            })),
        }
    }

    /// The entries of a word as linear forms: `forms[r * cols + c]`.
    fn word_forms(
        &self,
        k: usize,
        w: &[Factor],
        offsets: &[Option<usize>],
    ) -> Result<(usize, usize, Vec<Form>)> {
        if w.is_empty() {
            return Err(self.constraint_error(k, "E0703", "empty word".into()));
        }
        // Shapes must chain.
        for pair in w.windows(2) {
            let (a, b) = (self.shape(&pair[0]), self.shape(&pair[1]));
            if a.1 != b.0 {
                return Err(self.constraint_error(
                    k,
                    "E0703",
                    format!(
                        "shapes do not chain in `{}`: {}×{} times {}×{}",
                        self.word_text(w),
                        a.0,
                        a.1,
                        b.0,
                        b.1
                    ),
                ));
            }
        }
        let unknown_at: Vec<usize> = (0..w.len())
            .filter(|&i| matches!(&w[i], Factor::Op(o) if self.operators[*o].value.is_none()))
            .collect();
        if unknown_at.len() > 1 {
            let names: Vec<String> = unknown_at
                .iter()
                .map(|&i| self.word_text(&w[i..=i]))
                .collect();
            return Err(self.constraint_error(
                k,
                "E0704",
                format!(
                    "nonlinear word `{}`: {} unknown factors ({}); fix all but one (solve lower cells first)",
                    self.word_text(w),
                    names.len(),
                    names.join(", ")
                ),
            ));
        }
        let known = |f: &Factor| -> Matrix {
            match f {
                Factor::Op(o) => self.operators[*o].value.clone().expect("known"),
                Factor::Literal(m) => m.clone(),
            }
        };
        // The product of known factors; `None` for none (the identity, never built).
        let product = |fs: &[Factor]| -> Option<Matrix> {
            let (first, rest) = fs.split_first()?;
            Some(rest.iter().fold(known(first), |acc, f| {
                acc.mul(&known(f)).expect("shapes checked")
            }))
        };
        let rows = self.shape(&w[0]).0;
        let cols = self.shape(w.last().expect("non-empty")).1;
        match unknown_at.first() {
            None => {
                let m = product(w).expect("non-empty");
                Ok((
                    rows,
                    cols,
                    m.data.into_iter().map(|v| (Vec::new(), v)).collect(),
                ))
            }
            Some(&p) => {
                let (xr, xc) = self.shape(&w[p]);
                // K1·X·K2 entry (r, c) = Σ K1[r][i]·X[i][j]·K2[j][c] over the nonzero entries
                // only: K1's rows and K2's columns as sparse lists (an absent product is the
                // identity, one entry per row), in increasing i and j as a dense loop visits them.
                let one = || Q::int(Z::one());
                let k1 = product(&w[..p]);
                let k2 = product(&w[p + 1..]);
                let k1_rows: Vec<Vec<(usize, Q)>> = (0..rows)
                    .map(|r| match &k1 {
                        None => vec![(r, one())],
                        Some(m) => (0..xr)
                            .map(|i| (i, m.get(r, i)))
                            .filter(|(_, a)| !a.is_zero())
                            .map(|(i, a)| (i, Q::from_big(a)))
                            .collect(),
                    })
                    .collect();
                let k2_cols: Vec<Vec<(usize, Q)>> = (0..cols)
                    .map(|c| match &k2 {
                        None => vec![(c, one())],
                        Some(m) => (0..xc)
                            .map(|j| (j, m.get(j, c)))
                            .filter(|(_, b)| !b.is_zero())
                            .map(|(j, b)| (j, Q::from_big(b)))
                            .collect(),
                    })
                    .collect();
                let Factor::Op(o) = &w[p] else {
                    unreachable!("unknowns are operators")
                };
                let base = offsets[*o].expect("unknown operators have offsets");
                let mut forms = Vec::with_capacity(rows * cols);
                for row in &k1_rows {
                    for col in &k2_cols {
                        let mut terms = Vec::with_capacity(row.len() * col.len());
                        for (i, a) in row {
                            for (j, b) in col {
                                // Machine-word product with a checked fallback: the same
                                // reduced value as `a * b`, without BigInt gcds (issue #34).
                                terms.push((base + i * xc + j, a.mul(b)));
                            }
                        }
                        forms.push((terms, BigRational::zero()));
                    }
                }
                Ok((rows, cols, forms))
            }
        }
    }

    /// Builds the exact linear system: one row per entry of every constraint and one per column of
    /// every barycentric operator.
    pub fn linearize(&self) -> Result<Linearized> {
        let mut offsets = vec![None; self.operators.len()];
        let mut unknown_entries = Vec::new();
        for (o, op) in self.operators.iter().enumerate() {
            if op.value.is_none() {
                offsets[o] = Some(unknown_entries.len());
                let (r, c) = (self.states[op.to].dim, self.states[op.from].dim);
                for i in 0..r {
                    for j in 0..c {
                        unknown_entries.push((o, i, j));
                    }
                }
            }
        }
        let mut system = LinearSystem::new(unknown_entries.len());
        let mut origins = Vec::new();
        for (k, con) in self.constraints.iter().enumerate() {
            let (lr, lc, lf) = self.word_forms(k, &con.lhs, &offsets)?;
            let (rr, rc, rf) = self.word_forms(k, &con.rhs, &offsets)?;
            if (lr, lc) != (rr, rc) {
                return Err(self.constraint_error(
                    k,
                    "E0703",
                    format!("the two sides have different shapes: {lr}×{lc} and {rr}×{rc}"),
                ));
            }
            for (idx, ((lt, lk), (rt, rk))) in lf.into_iter().zip(rf).enumerate() {
                let terms = lt
                    .into_iter()
                    .chain(rt.into_iter().map(|(v, a)| (v, a.neg())));
                system.push_q(terms, Q::from_big(&(rk - lk)));
                origins.push(RowOrigin::Entry {
                    constraint: k,
                    r: idx / lc,
                    c: idx % lc,
                });
            }
        }
        for &o in &self.barycentric {
            let op = &self.operators[o];
            let (r, c) = (self.states[op.to].dim, self.states[op.from].dim);
            for j in 0..c {
                let (terms, known) = match (&op.value, offsets[o]) {
                    (Some(m), _) => (
                        Vec::new(),
                        (0..r).map(|i| m.get(i, j).clone()).sum::<BigRational>(),
                    ),
                    (None, Some(base)) => (
                        (0..r)
                            .map(|i| (base + i * c + j, Q::int(Z::one())))
                            .collect(),
                        BigRational::zero(),
                    ),
                    (None, None) => unreachable!("unknown operators have offsets"),
                };
                system.push_q(terms, Q::from_big(&(BigRational::one() - known)));
                origins.push(RowOrigin::Barycentric { op: o, c: j });
            }
        }
        Ok(Linearized {
            system,
            origins,
            unknown_entries,
            offsets,
        })
    }

    /// The name of unknown entry (o, r, c): `T.sub0[1][2]`.
    pub fn entry_name(&self, (o, r, c): (usize, usize, usize)) -> String {
        format!("{}[{r}][{c}]", self.operators[o].name)
    }

    /// Describes a row's provenance for reports.
    pub fn origin_text(&self, o: &RowOrigin) -> String {
        match o {
            RowOrigin::Entry { constraint, r, c } => {
                let con = &self.constraints[*constraint];
                format!(
                    "{} entry ({r},{c}): {}",
                    con.label,
                    self.constraint_text(*constraint)
                )
            }
            RowOrigin::Barycentric { op, c } => format!(
                "barycentric: column {c} of {} sums to 1",
                self.operators[*op].name
            ),
        }
    }
}

/// One term of a conflict certificate, as reported.
#[derive(Clone, Debug, Serialize)]
pub struct ConflictRow {
    /// The constraint (or barycentric condition) and entry.
    pub constraint: String,
    /// The rational multiplier.
    pub multiplier: String,
}

/// The solver's verdict on an automaton.
#[derive(Clone, Debug, Serialize)]
pub struct SolveReport {
    /// Number of unknown entries.
    pub unknowns: usize,
    /// Number of scalar equations.
    pub equations: usize,
    /// Rank of the system (when consistent).
    pub rank: Option<usize>,
    /// Whether a solution exists.
    pub consistent: bool,
    /// Degrees of freedom in total.
    pub dof: usize,
    /// Free parameters per state (the state of the operator whose entry each parameter controls).
    pub dof_by_state: BTreeMap<String, usize>,
    /// Free parameters per operator.
    pub dof_by_operator: BTreeMap<String, usize>,
    /// The free parameters, named after the entry each controls.
    pub parameters: Vec<String>,
    /// A particular solution: each unknown operator's matrix.
    pub particular: BTreeMap<String, String>,
    /// The basis of directions: for each parameter, the entries it moves and by how much.
    pub basis: Vec<BTreeMap<String, String>>,
    /// When inconsistent: constraints with multipliers summing to `0 = constant`.
    pub conflict: Option<Vec<ConflictRow>>,
    /// The constant of the contradiction.
    pub conflict_constant: Option<String>,
    /// Forced collapses found by the degeneracy check.
    pub degenerate: Vec<String>,
    /// Whether the degeneracy check ran (it needs the face structure of a generated automaton).
    pub degeneracy_checked: bool,
}

impl SolveReport {
    /// Consistent and without forced collapse.
    pub fn ok(&self) -> bool {
        self.consistent && self.degenerate.is_empty()
    }
}

/// Solves the automaton's constraint system exactly, without the report: for the callers that
/// only read the solution (exports, certificates). Naming every free unknown and basis entry of
/// the report costs more than the solve on systems of thousands of unknowns.
pub fn solve_system(a: &Automaton) -> Result<(Linearized, Solution)> {
    let lin = a.linearize()?;
    let solution = linsys::solve(&lin.system);
    Ok((lin, solution))
}

/// Solves the automaton's constraint system exactly, with the report of what was found.
pub fn solve_automaton(a: &Automaton) -> Result<(SolveReport, Linearized, Solution)> {
    let (lin, solution) = solve_system(a)?;
    let mut report = SolveReport {
        unknowns: lin.system.unknowns,
        equations: lin.system.len(),
        rank: None,
        consistent: false,
        dof: 0,
        dof_by_state: a.states.iter().map(|s| (s.name.clone(), 0)).collect(),
        dof_by_operator: BTreeMap::new(),
        parameters: Vec::new(),
        particular: BTreeMap::new(),
        basis: Vec::new(),
        conflict: None,
        conflict_constant: None,
        degenerate: Vec::new(),
        degeneracy_checked: false,
    };
    match &solution {
        Solution::Consistent(space) => {
            report.consistent = true;
            report.rank = Some(space.rank);
            report.dof = space.free.len();
            for &f in &space.free {
                let e = lin.unknown_entries[f];
                let op = &a.operators[e.0];
                *report
                    .dof_by_state
                    .entry(a.states[op.to].name.clone())
                    .or_default() += 1;
                *report.dof_by_operator.entry(op.name.clone()).or_default() += 1;
                report.parameters.push(a.entry_name(e));
            }
            for (o, op) in a.operators.iter().enumerate() {
                if let Some(base) = lin.offsets[o] {
                    let (r, c) = (a.states[op.to].dim, a.states[op.from].dim);
                    let m = Matrix {
                        rows: r,
                        cols: c,
                        data: space.particular.range(base..base + r * c),
                    };
                    report.particular.insert(op.name.clone(), m.to_string());
                }
            }
            report.basis = space
                .basis
                .iter()
                .map(|v| {
                    v.iter()
                        .map(|(i, x)| (a.entry_name(lin.unknown_entries[i]), x.to_string()))
                        .collect()
                })
                .collect();
        }
        Solution::Inconsistent(conflict) => {
            report.conflict = Some(
                conflict
                    .multipliers
                    .iter()
                    .map(|(row, m)| ConflictRow {
                        constraint: a.origin_text(&lin.origins[*row]),
                        multiplier: m.to_string(),
                    })
                    .collect(),
            );
            report.conflict_constant = Some(conflict.constant.to_string());
        }
    }
    Ok((report, lin, solution))
}

impl SolveReport {
    /// The human-readable report; `params` adds the basis directions.
    pub fn to_text(&self, params: bool) -> String {
        let mut o = format!(
            "unknowns {}, equations {}, rank {}\n",
            self.unknowns,
            self.equations,
            self.rank.map_or("-".into(), |r| r.to_string())
        );
        if !self.consistent {
            o +=
                "INCONSISTENT: no solution. These constraints, with these multipliers, sum to 0 = ";
            o += self.conflict_constant.as_deref().unwrap_or("?");
            o += ":\n";
            for c in self.conflict.iter().flatten() {
                o += &format!("  × {:>6}  {}\n", c.multiplier, c.constraint);
            }
            return o;
        }
        o += &format!(
            "consistent: {} degree{} of freedom\n",
            self.dof,
            if self.dof == 1 { "" } else { "s" }
        );
        for (s, d) in &self.dof_by_state {
            o += &format!("  state {s}: {d}\n");
        }
        if self.unknowns <= 120 {
            o += "particular solution:\n";
            for (name, m) in &self.particular {
                o += &format!("  {name} = {m}\n");
            }
        } else {
            o += "particular solution: in the JSON output (--json)\n";
        }
        if params {
            o += "free parameters and their directions:\n";
            for (p, dir) in self.parameters.iter().zip(&self.basis) {
                let moves: Vec<String> = dir.iter().map(|(e, v)| format!("{e} {v}")).collect();
                o += &format!("  {p}: {}\n", moves.join(", "));
            }
        }
        if !self.degeneracy_checked {
            o += "degeneracy: not checked (needs the face structure of a generated automaton)\n";
        } else if self.degenerate.is_empty() {
            o += "degeneracy: no two distinct corner points of a level-1 complex are forced to coincide\n";
        } else {
            o += "degeneracy: FORCED COLLAPSES\n";
            for d in &self.degenerate {
                o += &format!("  {d}\n");
            }
        }
        o
    }
}
