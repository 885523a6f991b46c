//! Tests of the exact projection on the THEORY §6 edge, where every answer is derived by hand.
//!
//! The edge automaton (fixtures/spec-edge.aut): state `e` of 3 control points, sub-operators
//! `e.T0`, `e.T1` (3 × 3, barycentric columns), incidences `T0·B0 = B0` (column 0 of T0 is
//! (1, 0, 0)), `T1·B1 = B1` (column 2 of T1 is (0, 0, 1)) and adjacency `T0·B1 = T1·B0` (column 2
//! of T0 = column 0 of T1). 6 degrees of freedom: columns 1 of T0 and T1 are free barycentric
//! columns (2 each), the shared column is one more free barycentric column (2).
//! Template: P0 = (0, 0), P1 = (1, 2), P2 = (2, 0), not collinear, so a point has unique
//! barycentric coordinates and the projection is unique.

use super::*;
use crate::{
    constraint::solve, constraint::Solution, constraint::SolutionSpace, input::parse_automaton,
};
use proptest::prelude::*;

fn q(a: i64, b: i64) -> Q {
    Q::new(a.into(), b.into())
}

struct Edge {
    space: SolutionSpace,
    /// First unknown of e.T0 and of e.T1.
    base: [usize; 2],
    unknowns: usize,
}

fn edge() -> Edge {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/fixtures/spec-edge.aut"
    ))
    .unwrap();
    let a = parse_automaton(&crate::Source {
        name: "spec-edge.aut".into(),
        text,
    })
    .unwrap();
    let lin = a.linearize().unwrap();
    let Solution::Consistent(space) = solve(&lin.system) else {
        panic!("spec-edge is consistent");
    };
    let op = |n: &str| a.operators.iter().position(|o| o.name == n).unwrap();
    Edge {
        base: [
            lin.offsets[op("e.T0")].unwrap(),
            lin.offsets[op("e.T1")].unwrap(),
        ],
        unknowns: lin.system.unknowns,
        space,
    }
}

fn template_points() -> Vec<QPoint> {
    vec![[q(0, 1), q(0, 1)], [q(1, 1), q(2, 1)], [q(2, 1), q(0, 1)]]
}

/// The six columns (T0 col 0, 1, 2, T1 col 0, 1, 2) with the given targets.
fn columns_with(e: &Edge, targets: &[QPoint]) -> Vec<ExactColumn> {
    let mut out = Vec::new();
    for (o, base) in e.base.iter().enumerate() {
        for c in 0..3 {
            out.push(ExactColumn {
                unknowns: (0..3).map(|r| base + r * 3 + c).collect(),
                points: template_points(),
                target: targets[o * 3 + c].clone(),
                reference: vec![q(1, 3); 3],
            });
        }
    }
    out
}

fn pt(x: (i64, i64), y: (i64, i64)) -> QPoint {
    [q(x.0, x.1), q(y.0, y.1)]
}

/// De Casteljau at 1/2 on P0, P1, P2: T0 puts P0, (P0 + P1)/2, (P0 + 2P1 + P2)/4; T1 puts
/// (P0 + 2P1 + P2)/4, (P1 + P2)/2, P2.
fn de_casteljau_targets() -> Vec<QPoint> {
    vec![
        pt((0, 1), (0, 1)),
        pt((1, 2), (1, 1)),
        pt((1, 1), (1, 1)),
        pt((1, 1), (1, 1)),
        pt((3, 2), (1, 1)),
        pt((2, 1), (0, 1)),
    ]
}

fn column_values(x: &[Q], col: &ExactColumn) -> Vec<Q> {
    col.unknowns.iter().map(|u| x[*u].clone()).collect()
}

#[test]
fn de_casteljau_targets_project_to_the_de_casteljau_operators() {
    let e = edge();
    let p = e.space.parametrize();
    let cols = columns_with(&e, &de_casteljau_targets());
    let fixed = vec![None; e.space.dof()];
    let proj = project_exact(&p, &fixed, &cols, &Q::zero());
    assert!(
        proj.unique,
        "a triangle template: unique barycentric coordinates"
    );
    assert_eq!(proj.residual, Q::zero());
    let x = unknowns_at(&p, e.unknowns, &proj.t);
    // T0 = [1 1/2 1/4; 0 1/2 1/2; 0 0 1/4] (fixtures/de-casteljau-edge.aut), by columns.
    assert_eq!(column_values(&x, &cols[0]), vec![q(1, 1), q(0, 1), q(0, 1)]);
    assert_eq!(column_values(&x, &cols[1]), vec![q(1, 2), q(1, 2), q(0, 1)]);
    assert_eq!(column_values(&x, &cols[2]), vec![q(1, 4), q(1, 2), q(1, 4)]);
    assert_eq!(column_values(&x, &cols[4]), vec![q(0, 1), q(1, 2), q(1, 2)]);
}

#[test]
fn a_hand_derived_projection_with_residual() {
    // Targets: T0 column 0 at (0, 1) although it is forced to P0 = (0, 0): contributes 1.
    // T0 column 2 at (1, 1) and T1 column 0 at (1, 0): one shared point z minimising
    // |z − (1, 1)|² + |z − (1, 0)|², z = (1, 1/2), contributing 1/4 + 1/4. The free columns
    // reach their targets. Residual 3/2; z = (3/8)P0 + (1/4)P1 + (3/8)P2 (2b = 1/2, b + 2c = 1).
    let e = edge();
    let p = e.space.parametrize();
    let mut targets = de_casteljau_targets();
    targets[0] = pt((0, 1), (1, 1));
    targets[2] = pt((1, 1), (1, 1));
    targets[3] = pt((1, 1), (0, 1));
    let cols = columns_with(&e, &targets);
    let proj = project_exact(&p, &vec![None; e.space.dof()], &cols, &Q::zero());
    assert_eq!(proj.residual, q(3, 2));
    let x = unknowns_at(&p, e.unknowns, &proj.t);
    assert_eq!(column_values(&x, &cols[2]), vec![q(3, 8), q(1, 4), q(3, 8)]);
    assert_eq!(column_values(&x, &cols[3]), vec![q(3, 8), q(1, 4), q(3, 8)]);
    let total: Q = cols.iter().map(|c| squared_distance(c, &x)).sum();
    assert_eq!(total, q(3, 2));
}

#[test]
fn a_fixed_parameter_keeps_its_value() {
    let e = edge();
    let p = e.space.parametrize();
    let cols = columns_with(&e, &de_casteljau_targets());
    let mut fixed = vec![None; e.space.dof()];
    fixed[0] = Some(q(7, 3));
    let proj = project_exact(&p, &fixed, &cols, &Q::zero());
    assert_eq!(proj.t[0], q(7, 3));
    assert!(
        proj.residual > Q::zero(),
        "the de Casteljau value of t0 is not 7/3"
    );
}

/// The gradient of Σ|P·c − y|² with respect to every free parameter, exactly.
fn gradient(
    p: &crate::constraint::Parametrization,
    cols: &[ExactColumn],
    x: &[Q],
    dof: usize,
) -> Vec<Q> {
    let mut g = vec![Q::zero(); dof];
    for col in cols {
        let mut pos = [Q::zero(), Q::zero()];
        for (u, pt) in col.unknowns.iter().zip(&col.points) {
            pos[0] += &x[*u] * &pt[0];
            pos[1] += &x[*u] * &pt[1];
        }
        for (u, pt) in col.unknowns.iter().zip(&col.points) {
            for (k, c) in p.expression(*u).1 {
                for d in 0..2 {
                    g[*k] += Q::from_integer(2.into()) * c * &pt[d] * (&pos[d] - &col.target[d]);
                }
            }
        }
    }
    g
}

fn small() -> impl Strategy<Value = Q> {
    (-12i64..=12, 1i64..=4).prop_map(|(a, b)| q(a, b))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    /// Optimality: the residual of the projection is at most that of any exact point of the
    /// space, and the gradient of the residual in the parameters is exactly 0.
    #[test]
    fn projection_is_optimal(
        ys in proptest::collection::vec((small(), small()), 6),
        others in proptest::collection::vec(proptest::collection::vec(small(), 6), 4),
    ) {
        let e = edge();
        let p = e.space.parametrize();
        let targets: Vec<QPoint> = ys.into_iter().map(|(a, b)| [a, b]).collect();
        let cols = columns_with(&e, &targets);
        let proj = project_exact(&p, &vec![None; e.space.dof()], &cols, &Q::zero());
        let x = unknowns_at(&p, e.unknowns, &proj.t);
        prop_assert!(gradient(&p, &cols, &x, e.space.dof()).iter().all(|g| g.is_zero()));
        let residual = |x: &[Q]| cols.iter().map(|c| squared_distance(c, x)).sum::<Q>();
        prop_assert_eq!(residual(&x), proj.residual.clone());
        for t in others {
            let y = unknowns_at(&p, e.unknowns, &t);
            prop_assert!(residual(&y) >= proj.residual);
        }
    }

    /// A template generated from exact parameters is reproduced exactly: residual 0 and the
    /// same parameters (the positions identify the parameters on a triangle template).
    #[test]
    fn templates_in_the_space_are_reproduced(t in proptest::collection::vec(small(), 6)) {
        let e = edge();
        let p = e.space.parametrize();
        let x = unknowns_at(&p, e.unknowns, &t);
        let mut cols = columns_with(&e, &vec![pt((0, 1), (0, 1)); 6]);
        for c in cols.iter_mut() {
            let mut pos = [Q::zero(), Q::zero()];
            for (u, pt) in c.unknowns.iter().zip(&c.points) {
                pos[0] += &x[*u] * &pt[0];
                pos[1] += &x[*u] * &pt[1];
            }
            c.target = pos;
        }
        let proj = project_exact(&p, &vec![None; e.space.dof()], &cols, &Q::zero());
        prop_assert_eq!(proj.residual, Q::zero());
        prop_assert_eq!(proj.t, t);
    }
}

#[test]
fn dyadic_rounding() {
    assert_eq!(dyadic(0.3, 2), q(1, 4));
    assert_eq!(dyadic(-0.375, 3), q(-3, 8));
    assert_eq!(dyadic(f64::NAN, 4), Q::zero());
}
