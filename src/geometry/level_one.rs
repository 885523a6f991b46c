//! The exact level-1 check of a chosen point of the solution space (THEORY §7, issue #36), and
//! the area goal that moves a degenerate choice off its collapse.
//!
//! **The check.** In each type's default template (its control points rounded to dyadic
//! rationals, the *frame*), every sub-face's control polygon — its control points in boundary
//! order, placed by the chosen operator — and the central lacuna's (the sub-faces' lacuna sides,
//! reversed) must have positive signed area. The areas are computed exactly over Q.
//!
//! **The area goal.** Twice a cell's signed area is a quadratic function of the unknowns: each
//! control point is `Σ_r x_r·F_r` (F the frame), and the shoelace sum multiplies two of them. The
//! goal "every cell's area ≥ its margin" is met by sequential linearisation: at the current point
//! each area is replaced by its tangent plane (exact gradient over Q), the linear program of
//! [`crate::geometry::lp::meet_goals`] finds the point L1-closest to the current one whose tangent
//! planes clear the margins (together with any linear goals), and the exact areas are evaluated
//! again there. The tangent planes aim 1/8 above each margin; quadratic terms they ignore can
//! still leave a cell short, and then the next round linearises at the new point. The result is
//! accepted only when every exact area clears its margin, and the level-1 check itself (positive
//! area) runs again afterwards — the linearisation decides which point is tried, never whether
//! it is accepted.

use crate::constraint::{Generated, Linearized, Parametrization};
use crate::geometry::lp::{meet_goals, Goal, GoalFailure, Inequality};
use crate::geometry::options::{GeometryError, InstantiateOptions};
use crate::geometry::point::{dyadic, QPoint};
use crate::topology::{Origin, TypeSet};
use num_rational::BigRational as Q;
use num_traits::{Signed, Zero};
use std::collections::BTreeMap;

/// What the exact level-1 check found: every cell's control polygon has positive area.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct LevelOne {
    /// Sub-faces checked, over all types.
    pub cells: usize,
    /// Central lacunas checked.
    pub lacunas: usize,
    /// The smallest signed area of a sub-face's control polygon, in its type's template,
    /// exactly.
    #[serde(serialize_with = "rational_str")]
    pub smallest_area: Option<Q>,
    /// Each type's frame, the control points in which its cells were measured (what a
    /// certificate's `level-one` step carries).
    #[serde(skip)]
    pub frames: Vec<Vec<QPoint>>,
}

impl LevelOne {
    /// The line `render` and `measure` print.
    pub fn describe(&self) -> String {
        format!(
            "level-1 cells: {} {} and {} {} over all types, every control polygon of positive area (exact, in each type's template)",
            self.cells,
            if self.cells == 1 { "sub-face" } else { "sub-faces" },
            self.lacunas,
            if self.lacunas == 1 { "lacuna" } else { "lacunas" }
        )
    }
}

fn rational_str<S: serde::Serializer>(x: &Option<Q>, s: S) -> Result<S::Ok, S::Error> {
    match x {
        Some(v) => s.serialize_str(&v.to_string()),
        None => s.serialize_none(),
    }
}

/// One cell of level 1 inside its parent type `ty`: a sub-face or the central lacuna, as the
/// list of its polygon's vertices, each given by its unknowns (one per control point of `ty`:
/// the vertex is `Σ_r x[vertices[i][r]]·F_ty[r]`).
#[derive(Clone, Debug)]
pub(crate) struct CellPolygon {
    /// The parent type.
    pub(crate) ty: usize,
    /// `sub-face k of Tt (face)` or `the lacuna of Tt (face)`.
    pub(crate) label: String,
    /// Whether it is a lacuna (else a sub-face).
    pub(crate) lacuna: bool,
    /// The constraints force its collapse (THEORY §6: Cantor sides on one chord).
    pub(crate) forced: bool,
    /// Its vertices.
    pub(crate) vertices: Vec<Vec<usize>>,
}

/// The cells of level 1 of every type, in the order the check visits them (per type: its
/// sub-faces, then its lacuna).
pub(crate) fn cells(types: &TypeSet, generated: &Generated, lin: &Linearized) -> Vec<CellPolygon> {
    let a = &generated.automaton;
    let dim = |t: usize| a.states[generated.face_state[t]].dim;
    let (flat_faces, flat_lacunas) = types.flat_cells();
    let mut out = Vec::new();
    for (t, ty) in types.types.iter().enumerate() {
        let m_t = dim(t);
        let column = |k: usize, c: usize| -> Vec<usize> {
            let m_w = dim(ty.children[k]);
            let base =
                lin.offsets[generated.sub_ops[t][k]].expect("face sub-operators are unknown");
            (0..m_t).map(|r| base + r * m_w + c).collect()
        };
        let mut lacuna: Vec<(usize, Vec<Vec<usize>>)> = Vec::new();
        for (k, &w) in ty.children.iter().enumerate() {
            let m_w = dim(w);
            let forced = flat_faces.contains(&t) || flat_faces.contains(&w);
            out.push(CellPolygon {
                ty: t,
                label: format!("sub-face {k} of T{t} ({})", types.types[w].face),
                lacuna: false,
                forced,
                vertices: (0..m_w).map(|c| column(k, c)).collect(),
            });
            let offsets = &generated.edge_offsets[w];
            for (e, o) in ty.subdivision.subfaces[k].origins.iter().enumerate() {
                if let Origin::Lacuna { side } = *o {
                    // The side's control points, from its first to the next edge's first.
                    let (from, to) = (offsets[e], offsets.get(e + 1).copied().unwrap_or(m_w));
                    let mut pts: Vec<Vec<usize>> =
                        (from..=to).map(|c| column(k, c % m_w)).collect();
                    pts.reverse();
                    lacuna.push((side, pts));
                }
            }
        }
        if !lacuna.is_empty() {
            lacuna.sort_by_key(|(side, _)| *side);
            out.push(CellPolygon {
                ty: t,
                label: format!("the lacuna of T{t} ({})", ty.face),
                lacuna: true,
                forced: flat_lacunas.contains(&t) || flat_faces.contains(&t),
                vertices: lacuna.into_iter().flat_map(|(_, p)| p).collect(),
            });
        }
    }
    out
}

/// Each type's default template under `opt`, its control points rounded to multiples of 2^-40:
/// the frames in which the level-1 cells are measured.
pub(crate) fn frames(types: &TypeSet, q: usize, opt: &InstantiateOptions) -> Vec<Vec<QPoint>> {
    types
        .types
        .iter()
        .map(|ty| {
            crate::geometry::template::template(ty, types, q, opt)
                .points
                .iter()
                .map(|p| [dyadic(p[0], 40), dyadic(p[1], 40)])
                .collect()
        })
        .collect()
}

fn vertex(frame: &[QPoint], unknowns: &[usize], x: &[Q]) -> QPoint {
    let mut p = [Q::zero(), Q::zero()];
    for (u, f) in unknowns.iter().zip(frame) {
        p[0] += &x[*u] * &f[0];
        p[1] += &x[*u] * &f[1];
    }
    p
}

fn cross(a: &QPoint, b: &QPoint) -> Q {
    &a[0] * &b[1] - &a[1] * &b[0]
}

/// Twice the signed area of a polygon (shoelace), exactly.
fn shoelace(pts: &[QPoint]) -> Q {
    let n = pts.len();
    (0..n).fold(Q::zero(), |s, i| s + cross(&pts[i], &pts[(i + 1) % n]))
}

/// The vertices of `cell` in its frame at the unknowns `x`.
fn points(cell: &CellPolygon, frames: &[Vec<QPoint>], x: &[Q]) -> Vec<QPoint> {
    let frame = &frames[cell.ty];
    cell.vertices.iter().map(|v| vertex(frame, v, x)).collect()
}

/// Twice the signed area of `cell` at the unknowns `x`, exactly.
pub(crate) fn area2(cell: &CellPolygon, frames: &[Vec<QPoint>], x: &[Q]) -> Q {
    shoelace(&points(cell, frames, x))
}

/// The gradient of twice the area of `cell` with respect to the unknowns, at the cell's
/// vertices `pts` (from [`points`]), exactly: vertex `i` enters the terms `p_i × p_{i+1}` and
/// `p_{i−1} × p_i`, and `∂p_i/∂x_{v_i[r]} = F_r`.
fn area2_gradient(
    cell: &CellPolygon,
    frames: &[Vec<QPoint>],
    pts: &[QPoint],
) -> BTreeMap<usize, Q> {
    let frame = &frames[cell.ty];
    let n = pts.len();
    let mut g: BTreeMap<usize, Q> = BTreeMap::new();
    for (i, v) in cell.vertices.iter().enumerate() {
        let (prev, next) = (&pts[(i + n - 1) % n], &pts[(i + 1) % n]);
        for (u, f) in v.iter().zip(frame) {
            *g.entry(*u).or_insert_with(Q::zero) += cross(f, next) + cross(prev, f);
        }
    }
    g.retain(|_, c| !c.is_zero());
    g
}

/// The exact level-1 check of the unknowns `x` (module documentation): the first cell of zero
/// or negative area is a degenerate choice (E1012), or a forced collapse (E1013).
pub(crate) fn check(
    cells: &[CellPolygon],
    frames: &[Vec<QPoint>],
    x: &[Q],
) -> Result<LevelOne, GeometryError> {
    let mut out = LevelOne {
        frames: frames.to_vec(),
        ..Default::default()
    };
    let two = Q::from_integer(2.into());
    for cell in cells {
        let a = area2(cell, frames, x) / &two;
        match cell.lacuna {
            true => out.lacunas += 1,
            false => out.cells += 1,
        }
        if !a.is_positive() {
            let advice = match cell.forced {
                true => {
                    "a forced collapse: no choice of parameters gives it area (THEORY §6; \
                         `lacuna verify` states it)"
                }
                false => "choose other parameters: --template, --goal or --param",
            };
            return Err(GeometryError::Degenerate {
                cell: cell.label.clone(),
                area: a.to_string(),
                advice: advice.into(),
                forced: cell.forced,
            });
        }
        if !cell.lacuna {
            out.smallest_area = Some(match out.smallest_area.take() {
                Some(s) if s <= a => s,
                _ => a,
            });
        }
    }
    Ok(out)
}

/// The margin of the automatic area goal for the cells of type `ty`: 1/64 of the type's frame
/// area shared among its cells (its sub-faces and its lacuna). A default-template cell is
/// usually several times larger, so the goal lifts a collapsed cell to a visible size without
/// pulling its neighbours far from their template.
pub(crate) fn automatic_margins(cells: &[CellPolygon], frames: &[Vec<QPoint>]) -> Vec<Q> {
    let mut count = vec![0i64; frames.len()];
    for c in cells {
        count[c.ty] += 1;
    }
    let frame_area: Vec<Q> = frames
        .iter()
        .map(|f| (shoelace(f) / Q::from_integer(2.into())).abs())
        .collect();
    cells
        .iter()
        .map(|c| &frame_area[c.ty] / Q::from_integer((64 * count[c.ty].max(1)).into()))
        .collect()
}

/// The most linearisation rounds of [`lift`].
const ROUNDS: usize = 12;

/// The largest trust region of a round (how far one weight may move).
const RHO_MAX: i64 = 4;

/// What [`lift`] works on: the solution space, the cells and the LP's objective.
pub(crate) struct Lift<'a> {
    pub(crate) param: &'a Parametrization,
    pub(crate) fixed: &'a [Option<Q>],
    pub(crate) cells: &'a [CellPolygon],
    pub(crate) frames: &'a [Vec<QPoint>],
    /// The unknowns whose L1 distance to the current point the LP minimises.
    pub(crate) objective: &'a [usize],
    pub(crate) bits: u32,
}

/// Parameters near `t0` at which every cell's area is at least its margin, exactly (and every
/// linear inequality of `linear` holds), by sequential linearisation (module documentation).
/// `goals` names the goals for messages; `goals[area_goal]` is the area goal, whose index the
/// area inequalities carry.
pub(crate) fn lift(
    lx: &Lift,
    t0: &[Q],
    margins: &[Q],
    linear: &[Inequality],
    (goals, area_goal): (&[Goal], usize),
) -> Result<Vec<Q>, GoalFailure> {
    let two = Q::from_integer(2.into());
    let mut t = t0.to_vec();
    for _ in 0..ROUNDS {
        let x = lx.param.at(&t);
        let pts: Vec<Vec<QPoint>> = lx.cells.iter().map(|c| points(c, lx.frames, &x)).collect();
        let areas: Vec<Q> = pts.iter().map(|p| shoelace(p)).collect();
        // Twice the area against twice the margin: met exactly, or another round.
        if areas.iter().zip(margins).all(|(a2, m)| *a2 >= &two * m) && linear_hold(linear, &x) {
            return Ok(t);
        }
        let mut ineqs = linear.to_vec();
        for (((cell, p), a2), m) in lx.cells.iter().zip(&pts).zip(&areas).zip(margins) {
            // The tangent plane aims 1/8 above the margin, room for the quadratic terms it
            // ignores: area2(x) + g·(y − x) ≥ 2m·9/8, i.e. g·y ≥ 9m/4 − area2(x) + g·x.
            let g = area2_gradient(cell, lx.frames, p);
            let gx = g.iter().fold(Q::zero(), |s, (u, c)| s + c * &x[*u]);
            ineqs.push(Inequality {
                goal: area_goal,
                what: format!("the area of {}", cell.label),
                terms: g.into_iter().collect(),
                rhs: m * Q::new(9.into(), 4.into()) - a2 + gx,
            });
        }
        // A trust region: each weight moves at most ρ this round, so the tangent planes stay
        // close to the areas and the change spreads over many weights instead of one (an L1
        // objective alone moves a single weight as far as it takes). ρ doubles while the
        // tangent problem is infeasible. An infeasible tangent problem at the largest ρ proves
        // nothing about the areas themselves: E1034, not a verdict.
        let mut rho = Q::new(1.into(), 16.into());
        t = loop {
            let mut bounded = ineqs.clone();
            for &u in lx.objective {
                for sign in [1i64, -1] {
                    let s = Q::from_integer(sign.into());
                    bounded.push(Inequality {
                        goal: area_goal,
                        what: format!("the trust region of unknown {u}"),
                        terms: vec![(u, s.clone())],
                        rhs: &s * &x[u] - &rho,
                    });
                }
            }
            match meet_goals(
                lx.param,
                lx.fixed,
                &t,
                lx.objective,
                &bounded,
                goals,
                lx.bits,
            ) {
                Ok(next) => break next,
                Err(GoalFailure::Infeasible(_)) if rho < Q::from_integer(RHO_MAX.into()) => {
                    rho = &rho * &two;
                }
                Err(GoalFailure::Infeasible(m)) => {
                    return Err(GoalFailure::Unmet(format!(
                        "goal `{}` was not reached: at a linearisation, {m}",
                        goals[area_goal]
                    )))
                }
                Err(e) => return Err(e),
            }
        };
    }
    let x = lx.param.at(&t);
    match lx
        .cells
        .iter()
        .zip(margins)
        .find(|(c, m)| area2(c, lx.frames, &x) < &two * *m)
    {
        Some((c, _)) => Err(GoalFailure::Unmet(format!(
            "goal `{}` was not reached: {} stays below its margin after {ROUNDS} rounds of \
             linearisation",
            goals[area_goal], c.label
        ))),
        None => Ok(t),
    }
}

fn linear_hold(ineqs: &[Inequality], x: &[Q]) -> bool {
    crate::geometry::lp::min_slack(ineqs, x).is_none_or(|s| !s.is_negative())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(n: i64) -> Q {
        Q::from_integer(n.into())
    }

    /// A triangle in the frame F = (0,0), (1,0), (0,1): vertex i is
    /// x[3i]·F0 + x[3i+1]·F1 + x[3i+2]·F2 = (x[3i+1], x[3i+2]).
    fn triangle(lacuna: bool) -> (Vec<Vec<QPoint>>, CellPolygon) {
        let frames = vec![vec![[q(0), q(0)], [q(1), q(0)], [q(0), q(1)]]];
        let cell = CellPolygon {
            ty: 0,
            label: "the triangle".into(),
            lacuna,
            forced: false,
            vertices: (0..3).map(|i| vec![3 * i, 3 * i + 1, 3 * i + 2]).collect(),
        };
        (frames, cell)
    }

    #[test]
    fn the_gradient_is_the_derivative_of_the_shoelace_sum() {
        let (frames, cell) = triangle(false);
        // Vertices (0,0), (2,0), (0,3): twice the area is 2·3 = 6.
        let x: Vec<Q> = [1, 0, 0, 0, 2, 0, 0, 0, 3].iter().map(|&v| q(v)).collect();
        assert_eq!(area2(&cell, &frames, &x), q(6));
        // The area is quadratic: the tangent plane is exact up to second order, so a central
        // difference of step 1 in one unknown equals the derivative (the x² term cancels).
        let g = area2_gradient(&cell, &frames, &points(&cell, &frames, &x));
        for u in 0..9 {
            let (mut up, mut down) = (x.clone(), x.clone());
            up[u] += q(1);
            down[u] -= q(1);
            let diff = (area2(&cell, &frames, &up) - area2(&cell, &frames, &down)) / q(2);
            assert_eq!(
                g.get(&u).cloned().unwrap_or_else(Q::zero),
                diff,
                "unknown {u}"
            );
        }
        // By hand: with vertex 0 at the origin, 2A = x4·x8 − x5·x7, so ∂/∂x4 = x8 = 3 and
        // ∂/∂x8 = x4 = 2.
        assert_eq!(g[&4], q(3));
        assert_eq!(g[&8], q(2));
    }

    #[test]
    fn the_lift_opens_a_flat_triangle_to_its_margin_exactly() {
        // Nine free unknowns (no equation), the triangle of the test above, flattened onto the
        // x axis: (0,0), (1,0), (2,0), not a point, so its tangent plane is not flat. Margin 1:
        // the result must have area ≥ 1, checked here by the shoelace formula by hand.
        use crate::constraint::{solve, LinearSystem, Solution};
        let Solution::Consistent(space) = solve(&LinearSystem::new(9)) else {
            panic!("an empty system is consistent")
        };
        let param = space.parametrize();
        let (frames, cell) = triangle(false);
        let fixed = vec![None; 9];
        // The free parameters are the unknowns themselves, in some order: set them through
        // the parametrisation's pivots.
        let want: Vec<Q> = [1, 0, 0, 0, 1, 0, 0, 2, 0].iter().map(|&v| q(v)).collect();
        let t0: Vec<Q> = space.free.iter().map(|&u| want[u].clone()).collect();
        assert_eq!(param.at(&t0), want);
        let objective: Vec<usize> = (0..9).collect();
        let cells = [cell];
        let lx = Lift {
            param: &param,
            fixed: &fixed,
            cells: &cells,
            frames: &frames,
            objective: &objective,
            bits: 20,
        };
        let goals = [Goal::MinArea];
        let t = lift(&lx, &t0, &[q(1)], &[], (&goals, 0)).expect("met");
        let x = param.at(&t);
        let p: Vec<(Q, Q)> = (0..3)
            .map(|i| (x[3 * i + 1].clone(), x[3 * i + 2].clone()))
            .collect();
        let twice =
            (&p[1].0 - &p[0].0) * (&p[2].1 - &p[0].1) - (&p[2].0 - &p[0].0) * (&p[1].1 - &p[0].1);
        assert!(twice >= q(2), "area {}", twice / q(2));
    }

    #[test]
    fn a_flat_cell_is_degenerate_and_a_forced_one_says_so() {
        let (frames, mut cell) = triangle(true);
        // Three points on the x axis: (0,0), (1,0), (2,0).
        let x: Vec<Q> = [1, 0, 0, 0, 1, 0, 0, 2, 0].iter().map(|&v| q(v)).collect();
        let e = check(std::slice::from_ref(&cell), &frames, &x).unwrap_err();
        assert_eq!(e.code(), "E1012");
        cell.forced = true;
        let e = check(&[cell], &frames, &x).unwrap_err();
        assert_eq!(e.code(), "E1013");
    }
}
