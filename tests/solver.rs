//! The constraint solver on the hand-written automata of `fixtures/` and on generated face
//! automata. Every expected number is derived by hand in the test that checks it.

mod common;

use lacuna::{
    algebra::bezier_restriction, algebra::Matrix, constraint::solve_automaton,
    constraint::solve_closure, constraint::Automaton, constraint::GenOptions,
    constraint::Linearized, constraint::Solution, input::load_any, input::parse_rational,
    input::Loaded,
};
use num_rational::BigRational;
use num_traits::Zero;

fn automaton(name: &str) -> Automaton {
    match load_any(name).unwrap_or_else(|e| panic!("fixture {name}: {}", e.render())) {
        Loaded::Automaton { automaton, .. } => automaton,
        Loaded::Faces(_) => panic!("fixture {name} is not an automaton"),
    }
}

fn m(text: &str) -> Matrix {
    Matrix::from_rows(
        text.split(';')
            .map(|r| {
                r.split_whitespace()
                    .map(|t| parse_rational(t).unwrap())
                    .collect()
            })
            .collect(),
    )
}

/// True when assigning the given matrices to the unknown operators satisfies every equation
/// exactly (that is, the assignment lies in the solution space).
fn satisfies(a: &Automaton, lin: &Linearized, values: &[(&str, Matrix)]) -> bool {
    let mut x = vec![BigRational::zero(); lin.system.unknowns];
    for (k, &(o, r, c)) in lin.unknown_entries.iter().enumerate() {
        let name = &a.operators[o].name;
        let (_, mat) = values
            .iter()
            .find(|(n, _)| n == name)
            .unwrap_or_else(|| panic!("no value for {name}"));
        x[k] = mat.get(r, c).clone();
    }
    lin.system.equations().all(|row| {
        row.terms
            .iter()
            .map(|(v, a)| a * &x[*v])
            .sum::<BigRational>()
            == row.rhs
    })
}

fn space(a: &Automaton) -> (lacuna::constraint::SolveReport, Linearized, Solution) {
    let (report, lin, sol) = solve_automaton(a).unwrap();
    if let Solution::Consistent(s) = &sol {
        s.check(&lin.system)
            .expect("the solution space re-checks exactly");
    }
    (report, lin, sol)
}

#[test]
fn spec_edge_has_8_then_6_degrees_of_freedom() {
    // THEORY §6: barycentric + incidence leave 8; the adjacency leaves 6.
    let (r, _, _) = space(&automaton("spec-edge-incidence"));
    assert!(r.consistent);
    assert_eq!(r.dof, 8, "fixture spec-edge-incidence");
    let a = automaton("spec-edge");
    let (r, lin, _) = space(&a);
    assert_eq!(r.dof, 6, "fixture spec-edge");
    assert_eq!(r.dof_by_state["e"], 6);
    // The degree-2 de Casteljau pair is a solution.
    let t0 = m("1 1/2 1/4; 0 1/2 1/2; 0 0 1/4");
    let t1 = m("1/4 0 0; 1/2 1/2 0; 1/4 1/2 1");
    assert!(satisfies(
        &a,
        &lin,
        &[("e.T0", t0.clone()), ("e.T1", t1.clone())]
    ));
    // Swapping them is not (T_0 must fix the first control point).
    assert!(!satisfies(&a, &lin, &[("e.T0", t1), ("e.T1", t0)]));
}

#[test]
fn half_tangent_edge_by_hand() {
    // Writing T_0 = [a0 a1 a2; b0 b1 b2; c0 c1 c2], T^d0 = [p q; r s]: the tangent incidence makes
    // the first two columns of T_0 equal to (p, r, 0), (q, s, 0); the vertex incidence makes the
    // first column (1, 0, 0), so p = 1, r = 0. Symmetrically T_1's last two columns are
    // (0, p', r'), (0, 0, 1). The adjacency makes T_1's first column (a, b, 1−a−b) = T_0's last.
    // The tangent adjacency −col1 + col2 of T_0 = −col0 + col1 of T_1 gives q = 2a,
    // p' = 2b − s, r' = 2(1−a−b), and then p' + r' = 1 holds by itself. Free: a, b.
    let a = automaton("half-tangent-edge");
    let (r, lin, _) = space(&a);
    assert!(r.consistent);
    assert_eq!(r.dof, 2, "fixture half-tangent-edge");
    // The closed form at two parameter points, among them de Casteljau's (a, b) = (1/4, 1/2).
    for (pa, pb) in [("1/4", "1/2"), ("1/10", "3/5")] {
        let (x, y) = (parse_rational(pa).unwrap(), parse_rational(pb).unwrap());
        let one = BigRational::from_integer(1.into());
        let two = BigRational::from_integer(2.into());
        let z = &one - &x - &y;
        let s = &one - &two * &x;
        let t0 = Matrix::from_rows(vec![
            vec![one.clone(), &two * &x, x.clone()],
            vec![BigRational::zero(), s.clone(), y.clone()],
            vec![BigRational::zero(), BigRational::zero(), z.clone()],
        ]);
        let pp = &two * &y - &s;
        let t1 = Matrix::from_rows(vec![
            vec![x.clone(), BigRational::zero(), BigRational::zero()],
            vec![y.clone(), pp.clone(), BigRational::zero()],
            vec![z.clone(), &two * &z, one.clone()],
        ]);
        let d0 = Matrix::from_rows(vec![
            vec![one.clone(), &two * &x],
            vec![BigRational::zero(), s.clone()],
        ]);
        let d1 = Matrix::from_rows(vec![
            vec![pp.clone(), BigRational::zero()],
            vec![&two * &z, one.clone()],
        ]);
        assert!(
            satisfies(
                &a,
                &lin,
                &[("e.T0", t0), ("e.T1", t1), ("d0.T", d0), ("d1.T", d1)]
            ),
            "closed form at a = {pa}, b = {pb}"
        );
    }
}

#[test]
fn quadratic_bspline_by_hand() {
    // Symmetry gives T_1 = J T_0 J; the shared control points give T_0 col1 = reverse(T_0 col2)
    // (the second condition is the same one). So T_0 = [u, rev(c), c] with u and c barycentric:
    // 2 + 2 = 4 degrees of freedom. Chaikin's operators are one solution.
    let a = automaton("bspline-quadratic");
    let (r, lin, _) = space(&a);
    assert_eq!(r.dof, 4, "fixture bspline-quadratic");
    let t0 = m("3/4 1/4 0; 1/4 3/4 3/4; 0 0 1/4");
    // T_1 = J T_0 J.
    let t1 = m("1/4 0 0; 3/4 3/4 1/4; 0 1/4 3/4");
    assert!(satisfies(&a, &lin, &[("e.T0", t0), ("e.T1", t1)]));
}

#[test]
fn quad_patch_by_hand() {
    // Columns fixed by incidence: every sub-patch point on the parent's boundary. Free columns,
    // each a barycentric 9-vector (8 dof): the parent's centre (shared by the four sub-patches),
    // the middle points of the four inner edges (each shared by two), and the four sub-patch
    // centres: 9 × 8 = 72.
    let a = automaton("quad-patch");
    let (r, lin, _) = space(&a);
    assert!(r.consistent);
    assert_eq!(r.dof, 72, "fixture quad-patch");
    // The bi-quadratic Bézier patch: S_xy[(k,l)][(i,j)] = T_x[k][i] · T_y[l][j], index 3j + i.
    let half = [
        bezier_restriction(2, &q("0"), &q("1/2")),
        bezier_restriction(2, &q("1/2"), &q("1")),
    ];
    let tensor = |x: usize, y: usize| {
        let mut s = Matrix::zeros(9, 9);
        for (k, l, i, j) in itertools4() {
            s.set(3 * l + k, 3 * j + i, half[x].get(k, i) * half[y].get(l, j));
        }
        s
    };
    let values = [
        ("p.S00", tensor(0, 0)),
        ("p.S10", tensor(1, 0)),
        ("p.S11", tensor(1, 1)),
        ("p.S01", tensor(0, 1)),
    ];
    assert!(satisfies(&a, &lin, &values));
}

fn q(t: &str) -> BigRational {
    parse_rational(t).unwrap()
}

fn itertools4() -> impl Iterator<Item = (usize, usize, usize, usize)> {
    (0..3).flat_map(|k| {
        (0..3).flat_map(move |l| (0..3).flat_map(move |i| (0..3).map(move |j| (k, l, i, j))))
    })
}

#[test]
fn generated_f0_system_is_consistent_and_not_degenerate() {
    let input = lacuna::input::load_input("F0").unwrap();
    let ts = lacuna::topology::close_or_error(&input.faces(), &lacuna::topology::Limits::default())
        .unwrap();
    let r = solve_closure(
        &ts,
        GenOptions::default(),
        &lacuna::topology::Limits::default(),
    )
    .unwrap();
    assert!(r.consistent, "{}", r.to_text(false));
    assert!(r.degeneracy_checked);
    assert!(r.degenerate.is_empty(), "{:?}", r.degenerate);
    // F0 has 6 edges: 3 C2 (m=2) and 3 B2 (m=3): m = 3·1 + 3·2 = 9 control points; six 9×9
    // sub-operators: 486 unknowns.
    assert_eq!(r.unknowns, 486);
    // Free points of the level-1 complex (each a barycentric 9-vector: 8 dof): the six inner
    // lacuna vertices (each shared by two sub-faces), the three spoke points inside the gaps
    // (joint spokes are fixed on the boundary), the middles of the six El edges and of the six
    // Ec edges: 21 points, 168 degrees of freedom.
    assert_eq!(r.dof, 168);
}

#[test]
fn a_non_barycentric_fixed_operator_is_inconsistent_with_a_certificate() {
    // v.T0 = [2] does not map points to points; no choice of the unknowns repairs that.
    let mut a = automaton("spec-edge");
    let v = a.operators.iter().position(|o| o.name == "v.T0").unwrap();
    a.operators[v].value = Some(m("2"));
    let (r, lin, sol) = solve_automaton(&a).unwrap();
    assert!(!r.consistent);
    let Solution::Inconsistent(conflict) = sol else {
        panic!("expected a conflict")
    };
    conflict
        .check(&lin.system)
        .expect("the certificate verifies");
    assert!(!conflict.constant.is_zero());
}

mod properties {
    use super::*;
    use lacuna::{
        constraint::automaton_of, topology::close, topology::Closure, topology::Face,
        topology::Limits,
    };
    use proptest::prelude::*;

    fn face() -> impl Strategy<Value = Face> {
        common::strategies::face(
            common::strategies::edge(2..=3, 1u32..=2),
            2..=5,
            common::strategies::edge(2..=3, Just(1u32)),
            common::strategies::builtin_algorithm(),
            Just(1u32),
        )
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

        #[test]
        fn generated_systems_are_consistent_and_perturbations_are_caught(f in face(), pick in 0usize..1000, bump in 1i64..5) {
            let Ok(Closure::Closed(ts)) = close(&f, &Limits::default()) else { return Ok(()) };
            prop_assume!(ts.types.len() <= 12);
            let g = automaton_of(&ts, GenOptions::default());
            let (r, lin, sol) = solve_automaton(&g.automaton).unwrap();
            let Solution::Consistent(space) = sol else { panic!("generated system inconsistent: {}", r.to_text(false)) };
            // The particular solution and every direction satisfy every equation exactly.
            space.check(&lin.system).map_err(TestCaseError::fail)?;
            // Perturb one entry of one fixed barycentric operator: its column no longer sums to
            // 1, so the system must become inconsistent, with a certificate that checks.
            let fixed: Vec<usize> = g.automaton.barycentric.iter().copied().filter(|&o| g.automaton.operators[o].value.is_some()).collect();
            let o = fixed[pick % fixed.len()];
            let mut a = g.automaton.clone();
            let mat = a.operators[o].value.as_mut().unwrap();
            let (rr, cc) = (pick % mat.rows, (pick / 7) % mat.cols);
            let v = mat.get(rr, cc) + BigRational::new(bump.into(), 7.into());
            mat.set(rr, cc, v);
            let (r2, lin2, sol2) = solve_automaton(&a).unwrap();
            prop_assert!(!r2.consistent);
            let Solution::Inconsistent(c) = sol2 else { unreachable!() };
            c.check(&lin2.system).map_err(TestCaseError::fail)?;
        }
    }
}

#[test]
fn the_degeneracy_check_reports_a_forced_collapse() {
    // Add to F0's system a constraint that glues the lacuna vertex at the start of sub-face 0's
    // El edge to the one at the start of sub-face 2's: two combinatorially distinct corners are
    // then forced to coincide, and the check must say so (and say nothing without it).
    use lacuna::{
        constraint::automaton_of, constraint::degeneracies, constraint::Constraint,
        constraint::ConstraintKind, constraint::Factor, topology::Origin,
    };
    let input = lacuna::input::load_input("F0").unwrap();
    let ts = lacuna::topology::close_or_error(&input.faces(), &lacuna::topology::Limits::default())
        .unwrap();
    let mut g = automaton_of(&ts, GenOptions::default());
    let (_, lin, sol) = solve_automaton(&g.automaton).unwrap();
    let Solution::Consistent(space) = sol else {
        panic!()
    };
    assert!(degeneracies(&ts, &g, &lin.offsets, &space).is_empty());
    let corner = |k: usize| {
        let sub = &ts.types[0].subdivision.subfaces[k];
        let p = sub
            .origins
            .iter()
            .position(|o| matches!(o, Origin::Lacuna { .. }))
            .unwrap();
        let col = g.edge_offsets[ts.types[0].children[k]][p];
        Matrix::selection(9, &[col])
    };
    g.automaton.constraints.push(Constraint {
        label: "glue".into(),
        span: None,
        kind: ConstraintKind::Word,
        lhs: vec![Factor::Op(g.sub_ops[0][0]), Factor::Literal(corner(0))],
        rhs: vec![Factor::Op(g.sub_ops[0][2]), Factor::Literal(corner(2))],
    });
    let (r, lin, sol) = solve_automaton(&g.automaton).unwrap();
    assert!(r.consistent);
    let Solution::Consistent(space) = sol else {
        panic!()
    };
    let found = degeneracies(&ts, &g, &lin.offsets, &space);
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(
        found[0].contains("sub-face 0") && found[0].contains("sub-face 2"),
        "{found:?}"
    );
}

#[test]
fn cantor_layout_is_configurable() {
    // C2 with gap/piece ratio g: pieces of length p = 1/(2 + g), the second starting at p + g·p.
    // g = 1/2: p = 2/5, pieces [0, 2/5] and [3/5, 1]: T1 = [1 − 3/5, 0; 3/5, 1] = [2/5 0; 3/5 1].
    use lacuna::constraint::automaton_of;
    let input = lacuna::input::load_input("F0").unwrap();
    let ts = lacuna::topology::close_or_error(&input.faces(), &lacuna::topology::Limits::default())
        .unwrap();
    let opts = GenOptions {
        cantor_gap: parse_rational("1/2").unwrap(),
        ..GenOptions::default()
    };
    let g = automaton_of(&ts, opts);
    let t1 = g
        .automaton
        .operators
        .iter()
        .find(|o| o.name == "C2.T1")
        .unwrap();
    assert_eq!(t1.value.as_ref().unwrap().to_string(), "[2/5 0; 3/5 1]");
    let t0 = g
        .automaton
        .operators
        .iter()
        .find(|o| o.name == "C2.T0")
        .unwrap();
    assert_eq!(t0.value.as_ref().unwrap().to_string(), "[1 3/5; 0 2/5]");
    // The default leaves equal pieces and gaps: thirds.
    let g = automaton_of(&ts, GenOptions::default());
    let t1 = g
        .automaton
        .operators
        .iter()
        .find(|o| o.name == "C2.T1")
        .unwrap();
    assert_eq!(t1.value.as_ref().unwrap().to_string(), "[1/3 0; 2/3 1]");
}
