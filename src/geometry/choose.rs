//! Choosing the free parameters t of the exact solution space `x = particular + B·t` (THEORY §7):
//! the default least-squares fit to the template in floating point (rounded to dyadic
//! rationals), and the **exact** least-squares projection of a template with rational positions.
//!
//! Both minimise, over the free parameters not fixed by name, `Σ |P·c − y|² + δ·Σ |c − r|²`
//! where `c` runs over the barycentric columns of the sub-face operators (a column is one level-1
//! control point), `P` holds the control points of the parent type's template, `y` the target of
//! the control point and `r` a reference column (its mean value coordinates in the template
//! polygon). The exact projection forms the normal equations over Q and solves them with
//! lacuna's exact solver ([`crate::constraint::solve`]). When δ = 0 they are singular as soon as a type has
//! more than three control points (many columns give the same point); the minimiser picked is then
//! the one closest to the reference columns (a second exact least-squares problem over the
//! minimisers), and if that is still not unique, the one whose remaining free parameters are 0.

use crate::geometry::point::Point;
use crate::geometry::point::{dyadic, QPoint};
use crate::geometry::template::{mean_value, Template};
use crate::{
    constraint::solve, constraint::Equation, constraint::Generated, constraint::LinearSystem,
    constraint::Linearized, constraint::Parametrization, constraint::Solution,
};
use num_rational::BigRational as Q;
use num_traits::{Signed, ToPrimitive, Zero};
use std::collections::BTreeMap;

/// One level-1 control point: control point `point` of sub-face `sub` of type `ty`, whose
/// position is `Σ_r x[unknowns[r]]·P_ty[r]`.
#[derive(Clone, Debug)]
pub(crate) struct Column {
    pub(crate) ty: usize,
    pub(crate) sub: usize,
    pub(crate) point: usize,
    pub(crate) unknowns: Vec<usize>,
}

/// The columns of every sub-face operator, by type, sub-face and control point.
pub(crate) fn columns(
    generated: &Generated,
    lin: &Linearized,
    children: &[&[usize]],
) -> Vec<Column> {
    let a = &generated.automaton;
    let mut out = Vec::new();
    for (t, kids) in children.iter().enumerate() {
        let m_t = a.states[generated.face_state[t]].dim;
        for (k, &w) in kids.iter().enumerate() {
            let base =
                lin.offsets[generated.sub_ops[t][k]].expect("face sub-operators are unknown");
            let m_w = a.states[generated.face_state[w]].dim;
            for c in 0..m_w {
                out.push(Column {
                    ty: t,
                    sub: k,
                    point: c,
                    unknowns: (0..m_t).map(|r| base + r * m_w + c).collect(),
                });
            }
        }
    }
    out
}

fn to_f64(r: &Q) -> f64 {
    r.to_f64().unwrap_or(f64::NAN)
}

/// The default fit in floating point: the minimiser of the template objective over the
/// non-fixed parameters (normal equations, Gaussian elimination), each rounded to `2^-bits`.
pub(crate) fn fit_float(
    param: &Parametrization,
    fixed: &[Option<Q>],
    templates: &[Template],
    cols: &[Column],
    delta: f64,
    bits: u32,
) -> Vec<Q> {
    let dof = fixed.len();
    let mut h = vec![vec![0.0; dof]; dof];
    let mut g = vec![0.0; dof];
    for col in cols {
        let p = &templates[col.ty].points;
        let y = templates[col.ty].targets[col.sub][col.point];
        let m_t = p.len();
        let reference = mean_value(p, y);
        // x_c = e + E·t, with the fixed parameters folded into e.
        let mut e = vec![0.0; m_t];
        let mut rows: Vec<Vec<(usize, f64)>> = vec![Vec::new(); m_t];
        for (r, &u) in col.unknowns.iter().enumerate() {
            let (cst, terms) = param.expression(u);
            e[r] = to_f64(cst);
            for (kk, coef) in terms {
                match &fixed[*kk] {
                    Some(v) => e[r] += to_f64(coef) * to_f64(v),
                    None => rows[r].push((*kk, to_f64(coef))),
                }
            }
        }
        // A = PᵀP + δI, b = Pᵀy + δ·ref; gradient term Eᵀ(b − A e); Hessian EᵀAE.
        let amat = |r: usize, s: usize| {
            p[r][0] * p[s][0] + p[r][1] * p[s][1] + if r == s { delta } else { 0.0 }
        };
        for r in 0..m_t {
            let b = p[r][0] * y[0] + p[r][1] * y[1] + delta * reference[r];
            let ae: f64 = (0..m_t).map(|s| amat(r, s) * e[s]).sum();
            for &(kk, cf) in &rows[r] {
                g[kk] += cf * (b - ae);
                for (s, row_s) in rows.iter().enumerate() {
                    let ars = amat(r, s);
                    if ars != 0.0 {
                        for &(kj, cj) in row_s {
                            h[kk][kj] += cf * ars * cj;
                        }
                    }
                }
            }
        }
    }
    for (k, f) in fixed.iter().enumerate() {
        if let Some(v) = f {
            h[k].iter_mut().for_each(|x| *x = 0.0);
            h[k][k] = 1.0;
            g[k] = to_f64(v);
        }
    }
    let tf = solve_dense(h, g);
    tf.iter()
        .zip(fixed)
        .map(|(x, f)| f.clone().unwrap_or_else(|| dyadic(*x, bits)))
        .collect()
}

/// Solves the dense symmetric system `h·t = g` (Gaussian elimination with partial pivoting).
fn solve_dense(mut h: Vec<Vec<f64>>, mut g: Vec<f64>) -> Vec<f64> {
    let n = g.len();
    for col in 0..n {
        let p = (col..n)
            .max_by(|&a, &b| h[a][col].abs().total_cmp(&h[b][col].abs()))
            .unwrap_or(col);
        h.swap(col, p);
        g.swap(col, p);
        let d = h[col][col];
        if d.abs() < 1e-300 {
            continue;
        }
        for r in col + 1..n {
            let f = h[r][col] / d;
            if f != 0.0 {
                let (top, bottom) = h.split_at_mut(r);
                for (x, y) in bottom[0][col..].iter_mut().zip(&top[col][col..]) {
                    *x -= f * y;
                }
                g[r] -= f * g[col];
            }
        }
    }
    let mut t = vec![0.0; n];
    for r in (0..n).rev() {
        let s: f64 = (r + 1..n).map(|c| h[r][c] * t[c]).sum();
        t[r] = if h[r][r].abs() < 1e-300 {
            0.0
        } else {
            (g[r] - s) / h[r][r]
        };
    }
    t
}

/// A level-1 control point for the exact projection: its unknowns, the exact template points of
/// its parent type, its exact target and its reference column.
#[derive(Clone, Debug)]
pub struct ExactColumn {
    /// The unknowns of the column, one per control point of the parent.
    pub unknowns: Vec<usize>,
    /// The parent's template control points (as many as unknowns).
    pub points: Vec<QPoint>,
    /// Where the control point should go.
    pub target: QPoint,
    /// The reference column (for δ and for picking a minimiser).
    pub reference: Vec<Q>,
}

/// An affine function `Σ coef·s_j + constant` of some variables.
#[derive(Clone, Debug, Default)]
struct Affine {
    terms: BTreeMap<usize, Q>,
    constant: Q,
}

impl Affine {
    fn add_scaled(&mut self, other: &Affine, f: &Q) {
        if f.is_zero() {
            return;
        }
        self.constant += &other.constant * f;
        for (j, c) in &other.terms {
            let e = self.terms.entry(*j).or_insert_with(Q::zero);
            *e += c * f;
            if e.is_zero() {
                self.terms.remove(j);
            }
        }
    }
    fn at(&self, s: &[Q]) -> Q {
        self.terms
            .iter()
            .fold(self.constant.clone(), |acc, (j, c)| acc + c * &s[*j])
    }
}

/// The unknowns as affine functions of the non-fixed parameters (compact indices).
struct Unknowns<'a> {
    param: &'a Parametrization,
    fixed: &'a [Option<Q>],
    compact: Vec<Option<usize>>,
}

impl Unknowns<'_> {
    fn of(&self, u: usize) -> Affine {
        let (cst, terms) = self.param.expression(u);
        let mut a = Affine {
            terms: BTreeMap::new(),
            constant: cst.clone(),
        };
        for (k, c) in terms {
            match (&self.fixed[*k], self.compact[*k]) {
                (Some(v), _) => a.constant += c * v,
                (None, Some(j)) => {
                    a.terms.insert(j, c.clone());
                }
                (None, None) => unreachable!("every non-fixed parameter has a compact index"),
            }
        }
        a
    }
}

/// The exact least-squares minimisers of `Σ w_i·f_i(s)²` over `n` variables: the solution space
/// of the normal equations `Σ w_i·∇f_i·f_i = 0` (always consistent).
fn least_squares(n: usize, rows: &[(Affine, Q)]) -> crate::constraint::SolutionSpace {
    let mut normal: Vec<BTreeMap<usize, Q>> = vec![BTreeMap::new(); n];
    let mut rhs = vec![Q::zero(); n];
    for (f, w) in rows {
        for (j, a) in &f.terms {
            let wa = w * a;
            rhs[*j] -= &wa * &f.constant;
            for (k, b) in &f.terms {
                *normal[*j].entry(*k).or_insert_with(Q::zero) += &wa * b;
            }
        }
    }
    let system = LinearSystem::from_equations(
        n,
        normal.into_iter().zip(rhs).map(|(r, rhs)| Equation {
            terms: r.into_iter().filter(|(_, c)| !c.is_zero()).collect(),
            rhs,
        }),
    );
    match solve(&system) {
        Solution::Consistent(space) => space,
        // Normal equations are consistent (their right-hand side lies in the column space of
        // AᵀA = the row space of A); the solver proves every conflict, so this cannot happen.
        Solution::Inconsistent(_) => unreachable!("normal equations are always consistent"),
    }
}

/// Substitutes `s = particular + K·z` (a solution space of the variables `s`) into `f`.
fn substitute(f: &Affine, p: &Parametrization) -> Affine {
    let mut out = Affine {
        terms: BTreeMap::new(),
        constant: f.constant.clone(),
    };
    for (j, c) in &f.terms {
        let (cst, terms) = p.expression(*j);
        out.constant += c * cst;
        for (m, k) in terms {
            let e = out.terms.entry(*m).or_insert_with(Q::zero);
            *e += c * k;
        }
    }
    out.terms.retain(|_, c| !c.is_zero());
    out
}

/// The result of the exact projection.
#[derive(Clone, Debug)]
pub struct Projection {
    /// The value of every free parameter (the fixed ones as given).
    pub t: Vec<Q>,
    /// `Σ |P·c − y|²` at the minimiser, exactly.
    pub residual: Q,
    /// Whether the minimiser of the template residual was unique (no second stage needed).
    pub unique: bool,
}

/// The exact projection (see the module documentation): minimises
/// `Σ |P·c − y|² + δ·Σ |c − r|²` over the parameters not in `fixed` exactly over Q.
pub fn project_exact(
    param: &Parametrization,
    fixed: &[Option<Q>],
    cols: &[ExactColumn],
    delta: &Q,
) -> Projection {
    let mut compact = vec![None; fixed.len()];
    let mut n = 0;
    for (k, f) in fixed.iter().enumerate() {
        if f.is_none() {
            compact[k] = Some(n);
            n += 1;
        }
    }
    let unk = Unknowns {
        param,
        fixed,
        compact,
    };
    let one = Q::from_integer(1.into());
    let mut fit_rows = Vec::new();
    let mut ref_rows = Vec::new();
    for col in cols {
        let xs: Vec<Affine> = col.unknowns.iter().map(|&u| unk.of(u)).collect();
        for d in 0..2 {
            let mut f = Affine {
                terms: BTreeMap::new(),
                constant: -col.target[d].clone(),
            };
            for (x, p) in xs.iter().zip(&col.points) {
                f.add_scaled(x, &p[d]);
            }
            fit_rows.push((f, one.clone()));
        }
        for (x, r) in xs.into_iter().zip(&col.reference) {
            let mut f = x;
            f.constant -= r;
            ref_rows.push(f);
        }
    }
    let rows: Vec<(Affine, Q)> = if delta.is_positive() {
        let reg = ref_rows.iter().map(|f| (f.clone(), delta.clone()));
        fit_rows.iter().cloned().chain(reg).collect()
    } else {
        fit_rows.clone()
    };
    let first = least_squares(n, &rows);
    let unique = first.dof() == 0;
    let s: Vec<Q> = if unique {
        first.particular.to_vec()
    } else {
        // Among the minimisers s = particular + K·z, the one closest to the reference columns.
        let p1 = first.parametrize();
        let rows2: Vec<(Affine, Q)> = ref_rows
            .iter()
            .map(|f| (substitute(f, &p1), one.clone()))
            .collect();
        let second = least_squares(first.dof(), &rows2);
        let z = second.particular.to_vec();
        (0..n)
            .map(|j| {
                let (cst, terms) = p1.expression(j);
                terms
                    .iter()
                    .fold(cst.clone(), |acc, (m, c)| acc + c * &z[*m])
            })
            .collect()
    };
    let residual = fit_rows
        .iter()
        .map(|(f, _)| {
            let v = f.at(&s);
            &v * &v
        })
        .fold(Q::zero(), |a, b| a + b);
    let t = fixed
        .iter()
        .zip(&unk.compact)
        .map(|(f, c)| match (f, c) {
            (Some(v), _) => v.clone(),
            (None, Some(j)) => s[*j].clone(),
            (None, None) => unreachable!("compact index"),
        })
        .collect();
    Projection {
        t,
        residual,
        unique,
    }
}

/// The exact value of every unknown at parameters `t`.
pub(crate) fn unknowns_at(param: &Parametrization, count: usize, t: &[Q]) -> Vec<Q> {
    let x = param.at(t);
    debug_assert_eq!(x.len(), count, "one value per unknown");
    x
}

/// The exact squared distance of a column's point to its target at the unknowns `x`.
pub(crate) fn squared_distance(col: &ExactColumn, x: &[Q]) -> Q {
    let mut pos = [Q::zero(), Q::zero()];
    for (u, p) in col.unknowns.iter().zip(&col.points) {
        pos[0] += &x[*u] * &p[0];
        pos[1] += &x[*u] * &p[1];
    }
    let (dx, dy) = (&pos[0] - &col.target[0], &pos[1] - &col.target[1]);
    &dx * &dx + &dy * &dy
}

/// The floating-point position of a level-1 control point.
pub(crate) fn position(p: &[Point], x: &[Q], unknowns: &[usize]) -> Point {
    let mut pos = [0.0, 0.0];
    for (r, &u) in unknowns.iter().enumerate() {
        let v = to_f64(&x[u]);
        pos[0] += v * p[r][0];
        pos[1] += v * p[r][1];
    }
    pos
}

/// How the parameters were chosen, with the exact residual when the template is exact.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct Choice {
    /// `least-squares fit` (floating point, rounded), `exact template projection`, and
    /// `+ LP goals` when goals were given.
    pub method: String,
    /// `Σ |P·c − y|²` over every level-1 control point, exactly (a rational), when the template
    /// is exact (`--template`, or the rounded default template under goals).
    pub residual: Option<String>,
    /// The same, as a decimal.
    pub residual_approx: Option<f64>,
    /// Per face type, the largest squared distance of a level-1 control point to its target,
    /// exactly.
    pub per_type_max: Vec<String>,
    /// Whether the minimiser of the template residual was unique (exact projection only).
    pub unique: Option<bool>,
    /// The goals met.
    pub goals: Vec<String>,
    /// The smallest slack of the goals' inequalities, exactly (≥ 0).
    pub min_slack: Option<String>,
    /// Whether the goals moved the parameters (false: the fit met them as it was).
    pub moved_by_goals: bool,
    /// When the fitted point made a level-1 cell degenerate and the automatic area goal moved
    /// it: the cell that had collapsed and its exact signed area at the fitted point.
    pub lifted: Option<String>,
    /// Root-mean-square distance of the level-1 control points to the floating-point template.
    pub rms: f64,
}

/// What [`choose`] needs to know about the instance.
pub(crate) struct Context<'a> {
    pub(crate) types: &'a crate::topology::TypeSet,
    pub(crate) generated: &'a Generated,
    pub(crate) lin: &'a Linearized,
    pub(crate) param: &'a Parametrization,
    pub(crate) fixed: &'a [Option<Q>],
    pub(crate) q: usize,
    /// Move a fitted point that makes a level-1 cell degenerate (not forced by the constraints)
    /// with the automatic area goal (`crate::geometry::level_one`); false for a caller that
    /// reports degenerate frames as findings (a morph).
    pub(crate) lift: bool,
}

/// What [`choose`] returns: the parameters, how they were chosen, and with `Context::lift` the
/// exact level-1 check of the chosen point (`crate::geometry::level_one`).
type Chosen = (
    Vec<Q>,
    Choice,
    Option<Result<crate::geometry::LevelOne, crate::geometry::options::GeometryError>>,
);

/// Chooses the parameters (module documentation, and `crate::geometry::lp` for goals).
pub(crate) fn choose(
    cx: &Context,
    opt: &crate::geometry::options::InstantiateOptions,
) -> Result<Chosen, crate::geometry::options::GeometryError> {
    use crate::geometry::lp::{inequalities, meet_goals, GoalFailure, LacunaVertex};
    use crate::geometry::template_file::{parse_template, ExactTemplate};
    let types = cx.types;
    let templates: Vec<Template> = types
        .types
        .iter()
        .map(|ty| crate::geometry::template::template(ty, types, cx.q, opt))
        .collect();
    let children: Vec<&[usize]> = types.types.iter().map(|t| t.children.as_slice()).collect();
    let cols = columns(cx.generated, cx.lin, &children);
    let exact = match &opt.template {
        Some(src) => {
            let default = ExactTemplate::rounded(types, &templates, cx.q);
            Some(parse_template(&src.text, &src.name, types, cx.q, &default)?)
        }
        None if !opt.goals.is_empty() => Some(ExactTemplate::rounded(types, &templates, cx.q)),
        None => None,
    };
    let exact_cols: Vec<ExactColumn> = match &exact {
        Some(ex) => cols
            .iter()
            .map(|c| {
                let tt = &ex.types[c.ty];
                let target = tt.targets[c.sub][c.point].clone();
                ExactColumn {
                    unknowns: c.unknowns.clone(),
                    points: tt.points.clone(),
                    reference: ex.reference(c.ty, &target, opt.bits),
                    target,
                }
            })
            .collect(),
        None => Vec::new(),
    };
    let default_fit = || {
        fit_float(
            cx.param,
            cx.fixed,
            &templates,
            &cols,
            opt.regularization,
            opt.bits,
        )
    };
    let mut choice = Choice::default();
    let mut t = match (&opt.template, &exact) {
        (Some(_), Some(ex)) => {
            let p = project_exact(cx.param, cx.fixed, &exact_cols, &ex.delta);
            choice.method = "exact template projection".into();
            choice.unique = Some(p.unique);
            p.t
        }
        _ => {
            choice.method = format!(
                "least-squares fit (floating point, rounded to 2^-{})",
                opt.bits
            );
            default_fit()
        }
    };
    let count = cx.lin.system.unknowns;
    // The sub-face weights (every unknown of a column, once, in order): the LPs' objective,
    // built only when goals or the area goal need it.
    let mut objective: Option<Vec<usize>> = None;
    let weights_of = || {
        let mut o: Vec<usize> = cols
            .iter()
            .flat_map(|c| c.unknowns.iter().copied())
            .collect();
        o.sort_unstable();
        o.dedup();
        o
    };
    let goal_error = |code: &'static str, message: String| {
        crate::geometry::options::GeometryError::Goal { code, message }
    };
    let goal_failure = |e: GoalFailure| match e {
        GoalFailure::Infeasible(m) => goal_error("E1031", m),
        GoalFailure::Snap(m) => goal_error("E1032", m),
        GoalFailure::Solver(m) => goal_error("E1033", format!("the LP solver failed: {m}")),
        GoalFailure::Unmet(m) => goal_error("E1031", m),
    };
    let mut ineqs = Vec::new();
    if !opt.goals.is_empty() {
        let ex = exact.as_ref().expect("an exact template under goals");
        let a = &cx.generated.automaton;
        let objective = objective.get_or_insert_with(weights_of);
        let weights: Vec<(usize, String)> = objective
            .iter()
            .map(|&u| (u, a.entry_name(cx.lin.unknown_entries[u])))
            .collect();
        let mut vertices = Vec::new();
        for (c, ec) in cols.iter().zip(&exact_cols) {
            let ty = &types.types[c.ty];
            let w = ty.children[c.sub];
            let wface = &types.types[w].face;
            let sf = &ty.subdivision.subfaces[c.sub];
            // Control points of the lacuna edges (`El`): both ends and the inner points.
            let m_w = cx.generated.automaton.states[cx.generated.face_state[w]].dim;
            let mut off = 0;
            let mut on_lacuna = false;
            for (l, e) in wface.boundary.iter().enumerate() {
                let d = crate::geometry::template::dim_of(e, cx.q);
                if matches!(sf.origins[l], crate::topology::Origin::Lacuna { .. }) {
                    on_lacuna |= (0..d).any(|i| (off + i) % m_w == c.point);
                }
                off += d - 1;
            }
            if on_lacuna {
                vertices.push(LacunaVertex {
                    name: format!("T{}.T{}[point {}]", c.ty, c.sub, c.point),
                    unknowns: &ec.unknowns,
                    target: &ec.target,
                    points: &ex.types[c.ty].points,
                    corners: &ex.types[c.ty].corners,
                });
            }
        }
        let constant = |u: usize| cx.param.expression(u).1.is_empty();
        ineqs = inequalities(&opt.goals, &weights, &constant, &vertices, opt.bits);
        let met = meet_goals(
            cx.param, cx.fixed, &t, objective, &ineqs, &opt.goals, opt.bits,
        )
        .map_err(goal_failure)?;
        choice.moved_by_goals = met != t;
        t = met;
        let x = unknowns_at(cx.param, count, &t);
        choice.min_slack = crate::geometry::lp::min_slack(&ineqs, &x).map(|s| s.to_string());
        choice.goals = opt.goals.iter().map(|g| g.to_string()).collect();
        choice.method += " + LP goals";
    }
    // The exact level-1 check of the chosen point, and before it the automatic area goal when
    // the point chosen so far makes a level-1 cell flat that the constraints do not force flat
    // (`crate::geometry::level_one`). The check's verdict goes back to the caller, which reports
    // it after the rest of the instance is built.
    let mut checked = None;
    if cx.lift {
        use crate::geometry::level_one as l1;
        let cells = l1::cells(types, cx.generated, cx.lin);
        let frames = l1::frames(types, cx.q, opt);
        let first = l1::check(&cells, &frames, &unknowns_at(cx.param, count, &t));
        // A positive check, or a collapse the constraints force, is the verdict as it is.
        if let Err(crate::geometry::options::GeometryError::Degenerate {
            forced: false,
            cell,
            area,
            ..
        }) = &first
        {
            let margins = l1::automatic_margins(&cells, &frames);
            // The area goal's index, for messages: after the user's goals (the linear
            // inequalities keep their indices).
            let mut goals = opt.goals.clone();
            goals.push(crate::geometry::lp::Goal::MinArea);
            let lx = l1::Lift {
                param: cx.param,
                fixed: cx.fixed,
                cells: &cells,
                frames: &frames,
                objective: objective.get_or_insert_with(weights_of),
                bits: opt.bits,
            };
            // At a cell shrunk to a point the area is stationary (its tangent plane is flat):
            // linearisation cannot start there. When the template or goals moved the point
            // away from the default fit and the default fit is not flat, start instead from the
            // first point on the segment towards it (a solution too: the space is affine) where
            // every cell has area, nearest the chosen point first.
            let start = match opt.template.is_some() || !opt.goals.is_empty() {
                true => {
                    let fit = default_fit();
                    let on = |lambda: &Q| -> Vec<Q> {
                        t.iter()
                            .zip(&fit)
                            .map(|(a, b)| a + (b - a) * lambda)
                            .collect()
                    };
                    (0..=4)
                        .rev()
                        .map(|k| on(&Q::new(1.into(), (1i64 << k).into())))
                        .find(|s| {
                            l1::check(&cells, &frames, &unknowns_at(cx.param, count, s)).is_ok()
                        })
                        .unwrap_or_else(|| t.clone())
                }
                false => t.clone(),
            };
            let area_goal = goals.len() - 1;
            let met =
                l1::lift(&lx, &start, &margins, &ineqs, (&goals, area_goal)).map_err(|e| {
                    // Failing, it leaves the fitted point degenerate: E1012, with what it tried.
                    let (GoalFailure::Infeasible(m)
                    | GoalFailure::Snap(m)
                    | GoalFailure::Solver(m)
                    | GoalFailure::Unmet(m)) = e;
                    crate::geometry::options::GeometryError::Degenerate {
                        cell: cell.clone(),
                        area: area.clone(),
                        advice: format!(
                        "the automatic area goal did not lift it ({m}); choose other parameters: \
                         --template, --goal or --param"
                    ),
                        forced: false,
                    }
                })?;
            choice.moved_by_goals |= met != t;
            choice.lifted = Some(format!("{cell} (signed area {area})"));
            choice.method += " + automatic area goal";
            t = met;
            checked = Some(l1::check(
                &cells,
                &frames,
                &unknowns_at(cx.param, count, &t),
            ));
        } else {
            checked = Some(first);
        }
    }
    let x = unknowns_at(cx.param, count, &t);
    if exact.is_some() {
        let mut total = Q::zero();
        let mut per_type = vec![Q::zero(); types.types.len()];
        for (c, ec) in cols.iter().zip(&exact_cols) {
            let d = squared_distance(ec, &x);
            if d > per_type[c.ty] {
                per_type[c.ty] = d.clone();
            }
            total += d;
        }
        choice.residual_approx = total.to_f64();
        choice.residual = Some(total.to_string());
        choice.per_type_max = per_type.iter().map(|q| q.to_string()).collect();
    }
    let sq: f64 = cols
        .iter()
        .map(|c| {
            let tp = &templates[c.ty];
            let pos = position(&tp.points, &x, &c.unknowns);
            let y = tp.targets[c.sub][c.point];
            (pos[0] - y[0]).powi(2) + (pos[1] - y[1]).powi(2)
        })
        .sum();
    choice.rms = (sq / cols.len().max(1) as f64).sqrt();
    Ok((t, choice, checked))
}

#[cfg(test)]
#[path = "choose_tests.rs"]
mod tests;
