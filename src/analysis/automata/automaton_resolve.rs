//! The operators of an automaton model made concrete, exactly: values in the declared field for the
//! operators given in the file, and for the unknown ones the solver's particular solution once the
//! `param` lines and `--param` values are added as equations (free parameters left at 0, as
//! `lacuna solve` prints them). With entries outside Q every operator must be given, and every
//! constraint and barycentric condition is checked exactly in the field.

use crate::algebra::algebraic::NumberField;
use crate::algebra::kmatrix::KMatrix;
use crate::algebra::matrix::Matrix;
use crate::constraint::automaton::{Automaton, Factor};
use crate::constraint::linsys::{self, Equation, Solution};
use crate::error::{Diagnostic, Error, Result};
use crate::input::automaton_model::AutomatonModel;
use num_rational::BigRational;
use num_traits::One;
use serde::Serialize;

/// The solver's verdict on the model's constraints, as far as evaluation needs it.
#[derive(Clone, Debug, Serialize)]
pub struct ResolveVerdict {
    /// Whether every constraint (and barycentric condition) holds with the chosen values.
    pub consistent: bool,
    /// The field the check ran in (`Q` or the declaration).
    pub field: String,
    /// The free parameters left (set to 0), named after the entries they control.
    pub free_left: Vec<String>,
    /// The parameter values applied (file `param` lines, then `--param`).
    pub applied: Vec<String>,
    /// The constraints that fail (known operators only).
    pub failed: Vec<String>,
}

/// Every operator with an exact value, and the verdict.
#[derive(Clone, Debug)]
pub struct Resolved {
    /// The value of each operator (unknown ones from the particular solution).
    pub ops: Vec<KMatrix>,
    /// The verdict.
    pub verdict: ResolveVerdict,
}

/// A coded error without a source span.
pub(crate) fn coded(code: &'static str, message: String) -> Error {
    Error::Syntax(Box::new(Diagnostic {
        code,
        message,
        span: None,
        source: None,
    }))
}

/// Parses `OP[r][c]` into (operator, row, column).
fn parse_entry(m: &AutomatonModel, name: &str) -> Option<(usize, usize, usize)> {
    let (op, rest) = name.split_once('[')?;
    let (r, rest) = rest.split_once("][")?;
    let c = rest.strip_suffix(']')?;
    let o = m
        .automaton
        .operators
        .iter()
        .position(|x| x.name == op.trim())?;
    Some((o, r.trim().parse().ok()?, c.trim().parse().ok()?))
}

/// Makes every operator concrete. `cli` values override the file's `param` lines of the same
/// name. `max_unknowns` bounds the unknown entries before the solver runs.
pub fn resolve(
    m: &AutomatonModel,
    cli: &[(String, BigRational)],
    max_unknowns: usize,
) -> Result<Resolved> {
    let a = &m.automaton;
    let k = &m.field;
    let field = m
        .field_decl
        .as_ref()
        .map_or("Q".to_string(), |(_, d)| d.clone());
    let mut params: Vec<(String, BigRational)> = m
        .params
        .iter()
        .map(|(n, v, _)| (n.clone(), v.clone()))
        .collect();
    for (n, v) in cli {
        params.retain(|(x, _)| x != n);
        params.push((n.clone(), v.clone()));
    }
    if !m.field_ops.is_empty() {
        if let Some(o) = (0..a.operators.len()).find(|&o| m.kvalues[o].is_none()) {
            return Err(coded("E0713", format!(
                "operator `{}` is unknown, but entries outside Q are given: with a `field`, give every operator's matrix (solve the rational part first)",
                a.operators[o].name
            )));
        }
        if let Some((n, _)) = params.first() {
            return Err(coded(
                "E0717",
                format!("parameter `{n}`: every operator of this file is known"),
            ));
        }
        let ops: Vec<KMatrix> = m
            .kvalues
            .iter()
            .map(|v| v.clone().expect("all known"))
            .collect();
        let failed = check_in_field(m, k, &ops)?;
        return Ok(Resolved {
            ops,
            verdict: ResolveVerdict {
                consistent: failed.is_empty(),
                field,
                free_left: Vec::new(),
                applied: Vec::new(),
                failed,
            },
        });
    }
    let unknowns = a.unknown_count();
    if unknowns > max_unknowns {
        return Err(Error::limit(
            "the unknown operator entries",
            unknowns,
            max_unknowns,
            "--max-unknowns",
        ));
    }
    let mut lin = a.linearize()?;
    let mut applied = Vec::new();
    for (n, v) in &params {
        let Some((o, r, c)) = parse_entry(m, n) else {
            return Err(coded("E0717", format!("parameter `{n}`: expected OPERATOR[ROW][COL] naming an operator of the automaton")));
        };
        let op = &a.operators[o];
        let (rows, cols) = (a.states[op.to].dim, a.states[op.from].dim);
        let Some(base) = lin.offsets[o] else {
            return Err(coded(
                "E0717",
                format!(
                    "parameter `{n}`: `{}` is known in the file, not a free operator",
                    op.name
                ),
            ));
        };
        if r >= rows || c >= cols {
            return Err(coded(
                "E0717",
                format!("parameter `{n}`: `{}` is {rows}×{cols}", op.name),
            ));
        }
        lin.system.push(&Equation {
            terms: vec![(base + r * cols + c, BigRational::one())],
            rhs: v.clone(),
        });
        applied.push(format!("{n} = {v}"));
    }
    let solution = linsys::solve(&lin.system);
    match solution {
        Solution::Consistent(space) => {
            let mut ops = Vec::with_capacity(a.operators.len());
            for (o, op) in a.operators.iter().enumerate() {
                let (r, c) = (a.states[op.to].dim, a.states[op.from].dim);
                let mat = match (&op.value, lin.offsets[o]) {
                    (Some(v), _) => v.clone(),
                    (None, Some(base)) => Matrix {
                        rows: r,
                        cols: c,
                        data: space.particular.range(base..base + r * c),
                    },
                    (None, None) => unreachable!("unknown operators have offsets"),
                };
                ops.push(KMatrix::from_rational(k, &mat));
            }
            let free_left = space
                .free
                .iter()
                .map(|&f| a.entry_name(lin.unknown_entries[f]))
                .collect();
            Ok(Resolved {
                ops,
                verdict: ResolveVerdict {
                    consistent: true,
                    field,
                    free_left,
                    applied,
                    failed: Vec::new(),
                },
            })
        }
        Solution::Inconsistent(conflict) => {
            let failed: Vec<String> = conflict
                .multipliers
                .iter()
                .map(|(row, mult)| match lin.origins.get(*row) {
                    Some(o) => format!("× {mult}  {}", a.origin_text(o)),
                    None => format!("× {mult}  a parameter value"),
                })
                .collect();
            if unknowns > 0 {
                return Err(coded("E0714", format!(
                    "the constraints have no solution with these parameter values (these rows sum to 0 = {}): {}",
                    conflict.constant,
                    failed.join("; ")
                )));
            }
            let ops = a
                .operators
                .iter()
                .map(|op| KMatrix::from_rational(k, op.value.as_ref().expect("known")))
                .collect();
            Ok(Resolved {
                ops,
                verdict: ResolveVerdict {
                    consistent: false,
                    field,
                    free_left: Vec::new(),
                    applied,
                    failed,
                },
            })
        }
    }
}

/// The constraints and barycentric conditions that fail, evaluated exactly in the field.
/// The constraints of `m` that fail with the operator values `ops` (exact, in `m`'s field): one
/// message per failing constraint (a morph's frame between two automata, THEORY §13).
pub fn constraints_failing(m: &AutomatonModel, ops: &[KMatrix]) -> Result<Vec<String>> {
    check_in_field(m, &m.field, ops)
}

fn check_in_field(m: &AutomatonModel, k: &NumberField, ops: &[KMatrix]) -> Result<Vec<String>> {
    let a = &m.automaton;
    Ok(failures(a, k, ops)?
        .into_iter()
        .map(|f| match f {
            Failing::Constraint(i) => {
                format!("{}: {}", a.constraints[i].label, a.constraint_text(i))
            }
            Failing::Barycentric(o) => format!(
                "barycentric: a column of {} does not sum to 1",
                a.operators[o].name
            ),
        })
        .collect())
}

/// A condition of an automaton that fails with given operator values.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Failing {
    /// The constraint of this index: its two words differ.
    Constraint(usize),
    /// The operator of this index, listed barycentric: a column does not sum to 1.
    Barycentric(usize),
}

/// The constraints (in order), then the barycentric operators, that fail with the operator
/// values `ops`, exactly in `k`; E0703 when a constraint's words do not multiply out to one
/// shape.
pub fn failures(a: &Automaton, k: &NumberField, ops: &[KMatrix]) -> Result<Vec<Failing>> {
    let mut failed = Vec::new();
    let word = |w: &[Factor]| -> Option<KMatrix> {
        let mut acc: Option<KMatrix> = None;
        for f in w {
            let x = match f {
                Factor::Op(o) => ops[*o].clone(),
                Factor::Literal(l) => KMatrix::from_rational(k, l),
            };
            acc = Some(match acc {
                None => x,
                Some(p) => p.mul(k, &x)?,
            });
        }
        acc
    };
    for (i, c) in a.constraints.iter().enumerate() {
        let (l, r) = (word(&c.lhs), word(&c.rhs));
        match (l, r) {
            (Some(l), Some(r)) if (l.rows, l.cols) == (r.rows, r.cols) => {
                if l != r {
                    failed.push(Failing::Constraint(i));
                }
            }
            _ => {
                return Err(coded(
                    "E0703",
                    format!(
                        "{}: the shapes of `{}` do not match",
                        c.label,
                        a.constraint_text(i)
                    ),
                ))
            }
        }
    }
    for &o in &a.barycentric {
        if !ops[o].is_barycentric(k) {
            failed.push(Failing::Barycentric(o));
        }
    }
    Ok(failed)
}

/// What `lacuna verify` decides about an automaton's attractor: the operators resolved (free
/// parameters 0), the contraction of that instance or the cycle that does not contract, the
/// similarity dimension (`digits` certified digits) or why there is none, and the boundary
/// dimension of its tiles.
#[derive(Clone, Debug)]
pub struct Attractor {
    /// The resolved operators and the verdict on the constraints.
    pub resolved: Resolved,
    /// The contraction proof, when every walk contracts.
    pub contraction: Option<crate::analysis::ContractionReport>,
    /// The refusal (E0715, E0716: a cycle that does not contract, an operator on a cycle that is
    /// not barycentric), coded, when contraction fails.
    pub contraction_fails: Option<String>,
    /// The similarity dimension, when it applies.
    pub similarity: Option<crate::analysis::SimilarityDimension>,
    /// Why there is no similarity dimension.
    pub similarity_note: Option<String>,
    /// The boundary dimension of the tile parts, when some part is a tile and it is decided.
    pub boundary: Option<crate::analysis::BoundaryDimension>,
}

/// Resolves `m`, proves contraction (within `max_products` products) and computes the
/// similarity dimension of a contracting instance. A cycle that does not contract is a result,
/// not an error; an undecided contraction (E0721) and every other failure are errors.
pub fn analyse_attractor(
    m: &AutomatonModel,
    max_unknowns: usize,
    max_products: usize,
    digits: usize,
) -> Result<Attractor> {
    let resolved = resolve(m, &[], max_unknowns)?;
    let (contraction, contraction_fails) =
        match crate::analysis::check_contraction_within(m, &resolved.ops, max_products) {
            Ok(c) => (Some(c), None),
            Err(Error::Syntax(d)) if d.code == "E0715" || d.code == "E0716" => {
                (None, Some(format!("{}: {}", d.code, d.message)))
            }
            Err(e) => return Err(e),
        };
    let (similarity, similarity_note) = match &contraction {
        Some(_) => match crate::analysis::similarity_dimension(m, &resolved.ops, digits) {
            Ok(s) => (Some(s), None),
            Err(n) => (None, Some(n)),
        },
        None => (
            None,
            Some("the attractor is not proven to exist".to_string()),
        ),
    };
    let boundary = similarity.as_ref().and_then(|sim| {
        crate::analysis::not_a_tile(m, sim)
            .is_none()
            .then(|| crate::analysis::boundary_dimension(m, &resolved.ops, sim, digits).ok())
            .flatten()
    });
    Ok(Attractor {
        resolved,
        contraction,
        contraction_fails,
        similarity,
        similarity_note,
        boundary,
    })
}
