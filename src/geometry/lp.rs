//! Inequality goals on the free parameters through a linear program (THEORY §7): `good_lp` with
//! the pure-Rust simplex `microlp` (f64), its answer snapped to dyadic rationals and re-checked
//! exactly over Q.
//!
//! **Goals** (each a set of linear inequalities on the unknowns `x = particular + B·t`):
//! - `nonnegative[=M]`: every barycentric weight of the sub-face operators that is not a constant
//!   of the solution space is ≥ M (default 0); the constant ones (fixed by the topology, e.g. the
//!   pieces of the boundary) must be ≥ 0.
//! - `min-lacuna=S`: every lacuna vertex (the ends of the `El` edges of the sub-faces: level-1
//!   control points) lies at least S from the centre `o` of its parent's template polygon (the
//!   mean of its corners), measured along its template direction: `(v − o)·d ≥ S`, where `d` is
//!   the unit vector from `o` towards the vertex's template target, rounded to multiples of 2⁻²⁰
//!   (a rational vector, so the inequality is exact). Lengths are in template units (the default
//!   polygons have circumradius 1).
//!
//! The automatic cell-area goal (`crate::geometry::level_one`) is quadratic: it linearises the
//! areas round by round and calls [`meet_goals`] with the tangent planes beside the linear goals.
//!
//! **Objective**: stay close to the reference solution `x0` (the template fit, or the exact
//! template projection with `--template`): minimise the L1 distance `Σ_u |x_u − x0_u|` over the
//! sub-face weights, with one auxiliary variable per weight. When `x0` already satisfies every
//! goal exactly it is returned as is (distance 0) without running the LP.
//!
//! **Exactness**: the LP runs in f64; its parameters are rounded to multiples of `2^-bits`, the
//! unknowns formed exactly and every inequality re-checked over Q (the equations hold by
//! construction and are re-checked by `Instance::check_exact`). If rounding broke an inequality,
//! the LP is solved again with every non-constant inequality tightened by
//! `‖a‖₁·2^-bits·4^k + 10⁻⁹` (k = 0, 1, 2), which covers the rounding error.

use crate::constraint::Parametrization;
use crate::geometry::point::QPoint;
use good_lp::{microlp, variable, variables, Expression, ResolutionError, Solution, SolverModel};
use num_rational::BigRational as Q;
use num_traits::{Signed, ToPrimitive, Zero};
use std::collections::BTreeMap;

/// An inequality goal on the free parameters (`--goal`).
#[derive(Clone, Debug, PartialEq)]
pub enum Goal {
    /// Every non-constant barycentric weight of the sub-face operators ≥ `margin`.
    NonNegative {
        /// The smallest weight allowed.
        margin: Q,
    },
    /// Every lacuna vertex at least `size` from its template centre along its template direction.
    MinLacuna {
        /// The smallest distance (template units).
        size: Q,
    },
    /// Every level-1 cell (sub-face and central lacuna) has a control polygon of area at least
    /// a margin in its type's template: the automatic goal that moves a fitted point off a
    /// collapse the constraints do not force (`crate::geometry::level_one`). Quadratic, met by
    /// sequential linearisation; not given on the command line.
    MinArea,
}

impl std::fmt::Display for Goal {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Goal::NonNegative { margin } if margin.is_zero() => write!(f, "nonnegative"),
            Goal::NonNegative { margin } => write!(f, "nonnegative={margin}"),
            Goal::MinLacuna { size } => write!(f, "min-lacuna={size}"),
            Goal::MinArea => write!(f, "automatic cell area"),
        }
    }
}

/// Parses `nonnegative`, `nonnegative=M` or `min-lacuna=S` (exact numbers, M, S ≥ 0).
pub fn parse_goal(text: &str) -> Option<Goal> {
    let (name, value) = match text.split_once('=') {
        Some((n, v)) => (n.trim(), Some(crate::input::parse_rational(v.trim())?)),
        None => (text.trim(), None),
    };
    if value.as_ref().is_some_and(|v| v.is_negative()) {
        return None;
    }
    match (name, value) {
        ("nonnegative", v) => Some(Goal::NonNegative {
            margin: v.unwrap_or_else(Q::zero),
        }),
        ("min-lacuna", Some(size)) => Some(Goal::MinLacuna { size }),
        _ => None,
    }
}

/// One inequality `Σ coef·x_u ≥ rhs`, from goal `goal`.
#[derive(Clone, Debug)]
pub(crate) struct Inequality {
    pub(crate) goal: usize,
    pub(crate) what: String,
    pub(crate) terms: Vec<(usize, Q)>,
    pub(crate) rhs: Q,
}

/// Why the goals could not be met.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum GoalFailure {
    /// No parameter values meet the goals (the message names the goal).
    Infeasible(String),
    /// The LP answer could not be rounded to rationals that meet the goals exactly.
    Snap(String),
    /// The LP solver failed otherwise.
    Solver(String),
    /// A quadratic goal (`min-area`) was not reached by linearisation: not a proof that no
    /// point meets it.
    Unmet(String),
}

/// A lacuna vertex of type `ty`: its unknowns (one per control point of the type), its exact
/// template target, the type's exact control points and corners.
pub(crate) struct LacunaVertex<'a> {
    pub(crate) name: String,
    pub(crate) unknowns: &'a [usize],
    pub(crate) target: &'a QPoint,
    pub(crate) points: &'a [QPoint],
    pub(crate) corners: &'a [QPoint],
}

/// The inequalities of the goals.
pub(crate) fn inequalities(
    goals: &[Goal],
    weights: &[(usize, String)],
    constant: &dyn Fn(usize) -> bool,
    vertices: &[LacunaVertex],
    bits: u32,
) -> Vec<Inequality> {
    let mut out = Vec::new();
    for (g, goal) in goals.iter().enumerate() {
        match goal {
            Goal::NonNegative { margin } => {
                for (u, name) in weights {
                    out.push(Inequality {
                        goal: g,
                        what: format!("weight {name}"),
                        terms: vec![(*u, Q::from_integer(1.into()))],
                        rhs: if constant(*u) {
                            Q::zero()
                        } else {
                            margin.clone()
                        },
                    });
                }
            }
            // Quadratic: linearised round by round in `crate::geometry::level_one::lift`.
            Goal::MinArea => {}
            Goal::MinLacuna { size } => {
                for v in vertices {
                    let n = Q::from_integer((v.corners.len().max(1) as i64).into());
                    let centre: [Q; 2] =
                        [0, 1].map(|d| v.corners.iter().fold(Q::zero(), |a, c| a + &c[d]) / &n);
                    let dir = [0, 1].map(|d| (&v.target[d] - &centre[d]).to_f64().unwrap_or(0.0));
                    let len = dir[0].hypot(dir[1]);
                    if len.is_nan() || len <= 1e-9 {
                        continue;
                    }
                    let d = dir.map(|c| crate::geometry::point::dyadic(c / len, bits));
                    let terms = v
                        .unknowns
                        .iter()
                        .zip(v.points)
                        .map(|(u, p)| (*u, &p[0] * &d[0] + &p[1] * &d[1]))
                        .collect();
                    out.push(Inequality {
                        goal: g,
                        what: format!("lacuna vertex {}", v.name),
                        terms,
                        rhs: size + &centre[0] * &d[0] + &centre[1] * &d[1],
                    });
                }
            }
        }
    }
    out
}

/// `Σ coef·x_u − rhs` as an affine function of the non-fixed parameters: (terms, constant).
type Row = (BTreeMap<usize, Q>, Q);

fn affine(terms: &[(usize, Q)], rhs: &Q, param: &Parametrization, fixed: &[Option<Q>]) -> Row {
    let mut t: BTreeMap<usize, Q> = BTreeMap::new();
    let mut c = -rhs.clone();
    for (u, a) in terms {
        let (cst, ex) = param.expression(*u);
        c += a * cst;
        for (k, b) in ex {
            match &fixed[*k] {
                Some(v) => c += a * b * v,
                None => *t.entry(*k).or_insert_with(Q::zero) += a * b,
            }
        }
    }
    t.retain(|_, v| !v.is_zero());
    (t, c)
}

fn value(row: &Row, t: &[Q]) -> Q {
    row.0
        .iter()
        .fold(row.1.clone(), |acc, (k, a)| acc + a * &t[*k])
}

fn f(q: &Q) -> f64 {
    q.to_f64().unwrap_or(f64::NAN)
}

/// Parameters meeting every inequality, L1-closest to `t0` in the weights `objective` (see the
/// module documentation). `t0` holds every parameter (the fixed ones as fixed).
pub(crate) fn meet_goals(
    param: &Parametrization,
    fixed: &[Option<Q>],
    t0: &[Q],
    objective: &[usize],
    ineqs: &[Inequality],
    goals: &[Goal],
    bits: u32,
) -> Result<Vec<Q>, GoalFailure> {
    let rows: Vec<Row> = ineqs
        .iter()
        .map(|i| affine(&i.terms, &i.rhs, param, fixed))
        .collect();
    // Constant inequalities are decided exactly, before any LP.
    for (row, ineq) in rows.iter().zip(ineqs) {
        if row.0.is_empty() && row.1.is_negative() {
            return Err(GoalFailure::Infeasible(format!(
                "goal `{}` cannot be met: {} is fixed at {} by the constraints (or by --param), below the bound {}",
                goals[ineq.goal],
                ineq.what,
                &row.1 + &ineq.rhs,
                ineq.rhs
            )));
        }
    }
    if rows.iter().all(|r| !value(r, t0).is_negative()) {
        return Ok(t0.to_vec());
    }
    let zero = Q::zero();
    let obj: Vec<Row> = objective
        .iter()
        .map(|&u| {
            let x0 = ineq_value(param, u, t0);
            affine(&[(u, Q::from_integer(1.into()))], &x0, param, fixed)
        })
        .filter(|r| !r.0.is_empty())
        .collect();
    let free: Vec<usize> = (0..fixed.len()).filter(|&k| fixed[k].is_none()).collect();
    let scale = 2f64.powi(-(bits as i32));
    let mut last = t0.to_vec();
    for attempt in 0..4 {
        let tighten = |row: &Row| {
            if attempt == 0 {
                0.0
            } else {
                let norm: f64 = row.0.values().map(|a| f(a).abs()).sum();
                norm * scale * 4f64.powi(attempt - 1) + 1e-9
            }
        };
        let mut vars = variables!();
        let tv: BTreeMap<usize, good_lp::Variable> =
            free.iter().map(|&k| (k, vars.add(variable()))).collect();
        let dv: Vec<good_lp::Variable> =
            obj.iter().map(|_| vars.add(variable().min(0.0))).collect();
        let expr = |row: &Row| {
            let mut e = Expression::from(f(&row.1));
            for (k, a) in &row.0 {
                e.add_mul(f(a), tv[k]);
            }
            e
        };
        let total: Expression = dv.iter().copied().sum();
        let mut model = vars.minimise(total).using(microlp);
        for (row, d) in obj.iter().zip(&dv) {
            model.add_constraint(expr(row).leq(*d));
            model.add_constraint(expr(row).geq(-*d));
        }
        for row in rows.iter().filter(|r| !r.0.is_empty()) {
            model.add_constraint(expr(row).geq(tighten(row)));
        }
        let sol = match model.solve() {
            Ok(s) => s,
            Err(ResolutionError::Infeasible) => {
                let names: Vec<String> = goals.iter().map(|g| format!("`{g}`")).collect();
                return Err(GoalFailure::Infeasible(format!(
                    "the goals {} cannot be met together: the linear program is infeasible{}",
                    names.join(", "),
                    if attempt > 0 {
                        " once tightened by the rounding margin"
                    } else {
                        ""
                    }
                )));
            }
            Err(e) => return Err(GoalFailure::Solver(e.to_string())),
        };
        let t: Vec<Q> = (0..fixed.len())
            .map(|k| match &fixed[k] {
                Some(v) => v.clone(),
                None => crate::geometry::point::dyadic(sol.value(tv[&k]), bits),
            })
            .collect();
        if rows.iter().all(|r| value(r, &t) >= zero) {
            return Ok(t);
        }
        last = t;
    }
    let broken = rows
        .iter()
        .zip(ineqs)
        .find(|(r, _)| value(r, &last).is_negative())
        .map(|(_, i)| format!("goal `{}` ({})", goals[i.goal], i.what))
        .unwrap_or_default();
    Err(GoalFailure::Snap(format!(
        "the LP answer rounded to multiples of 2^-{bits} still breaks {broken} after tightening three times"
    )))
}

fn ineq_value(param: &Parametrization, u: usize, t: &[Q]) -> Q {
    let (cst, ex) = param.expression(u);
    ex.iter().fold(cst.clone(), |acc, (k, a)| acc + a * &t[*k])
}

/// The smallest slack `Σ coef·x_u − rhs` of the inequalities at the unknowns `x`, exactly.
pub(crate) fn min_slack(ineqs: &[Inequality], x: &[Q]) -> Option<Q> {
    ineqs
        .iter()
        .map(|i| {
            i.terms
                .iter()
                .fold(-i.rhs.clone(), |acc, (u, a)| acc + a * &x[*u])
        })
        .min()
}
