//! Operator eigen analysis and inverse design (THEORY §8, issue #7). Every expected value is derived
//! by hand in the test that checks it.

mod common;
use lacuna::{
    algebra::Matrix, analysis::analyse_automaton, analysis::analyse_matrix, analysis::check_design,
    analysis::design_operator, analysis::estimate_curvature, analysis::parse_matrix_arg,
    analysis::parse_rationals_arg, analysis::Behaviour, analysis::CurvatureClass,
    analysis::DesignError, constraint::Automaton, input::parse_automaton, input::parse_rational,
    Source,
};
use num_rational::BigRational;
use proptest::prelude::*;

fn m(text: &str) -> Matrix {
    parse_matrix_arg(text).unwrap_or_else(|e| panic!("matrix {text}: {}", e.render()))
}

fn r(t: &str) -> BigRational {
    parse_rational(t).unwrap()
}

fn fixture(name: &str) -> Automaton {
    let path = format!("{}/fixtures/{name}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap();
    parse_automaton(&Source { name: path, text })
        .unwrap_or_else(|e| panic!("fixture {name}: {}", e.render()))
}

fn exact_eigenvalues(t: &Matrix) -> Vec<String> {
    analyse_matrix(t)
        .unwrap()
        .eigenvalues
        .iter()
        .map(|e| e.exact.clone().unwrap())
        .collect()
}

const DE_CASTELJAU_T0: &str = "[1 1/2 1/4; 0 1/2 1/2; 0 0 1/4]";

#[test]
fn de_casteljau_t0_is_the_parabola() {
    // Upper triangular: eigenvalues are the diagonal 1, 1/2, 1/4; 1/4 = (1/2)² so α = 2.
    let rep = analyse_matrix(&m(DE_CASTELJAU_T0)).unwrap();
    assert_eq!(exact_eigenvalues(&m(DE_CASTELJAU_T0)), ["1", "1/2", "1/4"]);
    assert_eq!(rep.charpoly, "x^3 - 7/4*x^2 + 7/8*x - 1/8"); // (x−1)(x−1/2)(x−1/4)
    assert!(rep.barycentric && rep.contractive);
    // The first column is e_0: T_0 fixes the first control point.
    assert_eq!(
        rep.fixed_point.as_deref(),
        Some(&["1".to_string(), "0".into(), "0".into()][..])
    );
    assert_eq!(rep.behaviour.class(), Some(CurvatureClass::Finite));
    assert_eq!(rep.lambda1.as_deref(), Some("1/2"));
    // (T_0 − I/2)·v = 0 gives z = 0, x + y = 0: v1 = P1 − P0 = (−1, 1, 0).
    assert_eq!(rep.tangent.as_deref().unwrap(), ["-1", "1", "0"]);
    assert!((rep.alpha_approx.unwrap() - 2.0).abs() < 1e-12);
    // The eigenvector of 1/4 solves −y/4... : (1, −2, 1) = the second difference.
    let e = &rep.eigenvalues[2];
    assert_eq!(
        e.eigenvectors,
        vec![vec!["1".to_string(), "-2".into(), "1".into()]]
    );
    assert!(rep.to_text().contains("behaviour: finite"));
}

#[test]
fn designed_alpha_one_and_a_half_is_sharp_and_alpha_three_is_flat() {
    let vecs = [
        vec![r("1"), r("0"), r("0")],
        vec![r("-1"), r("1"), r("0")],
        vec![r("1"), r("-2"), r("1")],
    ];
    // λ1 = 1/4, λ2 = 1/8: |λ2| = 1/8 > 1/16 = λ1², α = ln 8 / ln 4 = 1.5.
    let sharp = design_operator(&[r("1"), r("1/4"), r("1/8")], &vecs).unwrap();
    let rep = analyse_matrix(&sharp).unwrap();
    assert_eq!(rep.behaviour.class(), Some(CurvatureClass::Sharp));
    assert!((rep.alpha_approx.unwrap() - 1.5).abs() < 1e-12);
    // λ1 = 1/2, λ2 = 1/8 < 1/4, α = 3.
    let flat = design_operator(&[r("1"), r("1/2"), r("1/8")], &vecs).unwrap();
    let rep = analyse_matrix(&flat).unwrap();
    assert_eq!(rep.behaviour.class(), Some(CurvatureClass::Flat));
    assert!((rep.alpha_approx.unwrap() - 3.0).abs() < 1e-12);
    // The de Casteljau eigenvectors with 1, 1/2, 1/4 give back T_0 exactly.
    let t0 = design_operator(&[r("1"), r("1/2"), r("1/4")], &vecs).unwrap();
    assert_eq!(t0, m(DE_CASTELJAU_T0));
}

/// The half-tangent edge (fixtures/half-tangent-edge.aut): T_0 = [1 2a a; 0 1−2a b; 0 0 1−a−b],
/// upper triangular, eigenvalues 1, λ1 = 1−2a, λ2 = 1−a−b. With a = 1/4, λ1 = 1/2 and the
/// boundary |λ2| = λ1² = 1/4 is b = 1/2 (λ2 = 1/4) or b = 1 (λ2 = −1/4).
fn half_tangent(a: &str, b: &str) -> Matrix {
    let (a, b) = (r(a), r(b));
    let one = r("1");
    let two = r("2");
    let z = r("0");
    Matrix::from_rows(vec![
        vec![one.clone(), &two * &a, a.clone()],
        vec![z.clone(), &one - &two * &a, b.clone()],
        vec![z.clone(), z, one - a - b],
    ])
}

#[test]
fn half_tangent_family_on_both_sides_of_the_boundary() {
    for (b, expected, l2) in [
        ("3/8", CurvatureClass::Sharp, "3/8"),  // λ2 = 3/8 > 1/4
        ("1/2", CurvatureClass::Finite, "1/4"), // λ2 = 1/4 = λ1²
        ("5/8", CurvatureClass::Flat, "1/8"),   // λ2 = 1/8 < 1/4
        ("1", CurvatureClass::Finite, "-1/4"),  // λ2 = −1/4, |λ2| = λ1²
        ("9/8", CurvatureClass::Sharp, "-3/8"), // |λ2| = 3/8 > 1/4
    ] {
        let t = half_tangent("1/4", b);
        assert!(t.is_barycentric());
        let rep = analyse_matrix(&t).unwrap();
        assert_eq!(
            rep.behaviour.class(),
            Some(expected),
            "b = {b}: {}",
            rep.to_text()
        );
        assert!(exact_eigenvalues(&t).contains(&l2.to_string()), "b = {b}");
        assert_eq!(rep.lambda1.as_deref(), Some("1/2"));
    }
    // b = 3/2: λ2 = −3/4, larger in modulus than λ1 = 1/2: oscillating, no tangent case.
    assert!(matches!(
        analyse_matrix(&half_tangent("1/4", "3/2"))
            .unwrap()
            .behaviour,
        Behaviour::Oscillating { .. }
    ));
    // a = 5/8: λ1 = 1 − 5/4 = −1/4 is negative and dominates λ2 = 1 − 5/8 − 1/4 = 1/8.
    assert!(matches!(
        analyse_matrix(&half_tangent("5/8", "1/4"))
            .unwrap()
            .behaviour,
        Behaviour::Oscillating { .. }
    ));
}

#[test]
fn irrational_and_complex_eigenvalues() {
    // B = [1/2 1/8; 1/8 1/4]: trace 3/4, det 7/64, eigenvalues (3 ± √2)/8 ≈ 0.552, 0.198;
    // λ1² = (11 + 6√2)/64 ≈ 0.305 > 0.198: flat. The top row makes every column sum to 1.
    let t = m("[1 3/8 5/8; 0 1/2 1/8; 0 1/8 1/4]");
    let rep = analyse_matrix(&t).unwrap();
    assert_eq!(rep.lambda1.as_deref(), Some("(3 + sqrt(2))/8"));
    assert_eq!(rep.behaviour.class(), Some(CurvatureClass::Flat));
    assert!(rep.contractive);
    assert_eq!(rep.eigenvalues[1].min_poly, "x^2 - 3/4*x + 7/64");
    // B = [1/2 −1/4; 1/4 1/2]: 1/2 ± i/4, modulus² 5/16 < 1: contractive and spiralling.
    let t = m("[1 1/4 3/4; 0 1/2 -1/4; 0 1/4 1/2]");
    let rep = analyse_matrix(&t).unwrap();
    assert!(rep.contractive);
    assert!(matches!(rep.behaviour, Behaviour::Spiralling { .. }));
    let pair = rep.eigenvalues.iter().find(|e| !e.real).unwrap();
    assert_eq!(pair.exact.as_deref(), Some("1/2 ± i*sqrt(1/16)"));
    assert!(pair.approx.starts_with("0.5"));
    // λ1 = 1/2 and the pair ±i/4 of modulus 1/4 = λ1² exactly: finite (α = 2), complex λ2.
    let t = m("[1 1/2 3/4 5/4; 0 1/2 0 0; 0 0 0 -1/4; 0 0 1/4 0]");
    let rep = analyse_matrix(&t).unwrap();
    assert_eq!(
        rep.behaviour.class(),
        Some(CurvatureClass::Finite),
        "{}",
        rep.to_text()
    );
    assert!(
        matches!(&rep.behaviour, Behaviour::Tangent { detail, .. } if detail.contains("complex"))
    );
    // Modulus exactly 1 (rotation by 90°): not contractive.
    let t = m("[1 1 0; 0 0 -1; 0 1 1]");
    let rep = analyse_matrix(&t).unwrap();
    assert!(!rep.contractive);
}

#[test]
fn degenerate_and_non_square() {
    let rep = analyse_matrix(&m("[1 0; 0 1]")).unwrap();
    assert!(matches!(rep.behaviour, Behaviour::Degenerate { .. }));
    assert!(!rep.contractive && rep.fixed_point.is_none());
    let rep = analyse_matrix(&m("[1/2 0; 0 1/3]")).unwrap();
    assert!(rep.fixed_point_note.unwrap().contains("not an eigenvalue"));
    // Every other eigenvalue 0: collapse.
    let rep = analyse_matrix(&m("[1 1; 0 0]")).unwrap();
    assert!(matches!(rep.behaviour, Behaviour::Degenerate { .. }));
    assert!(rep.contractive);
    let e = analyse_matrix(&m("[1 2 3]")).unwrap_err();
    assert_eq!(e.code(), "E0902");
}

#[test]
fn de_casteljau_curve_points() {
    let rep = analyse_automaton(&fixture("de-casteljau-edge.aut")).unwrap();
    // v.T0 (1×1) and e.T0, e.T1; none skipped.
    assert_eq!(rep.operators.len(), 3);
    assert!(rep.skipped.is_empty());
    let curve = rep.curves.iter().find(|c| c.state == "e").unwrap();
    assert!(curve.joined, "{}", rep.to_text());
    let labels: Vec<&str> = curve.points.iter().map(|p| p.label.as_str()).collect();
    assert_eq!(labels, ["start", "joint e.T0|e.T1", "end"]);
    // The joint is T_0·fix(T_1) = T_0·(0,0,1) = (1/4, 1/2, 1/4), the parabola's midpoint.
    let joint = &curve.points[1];
    assert_eq!(joint.point, ["1/4", "1/2", "1/4"]);
    // Left: T_0·v1(T_1) = T_0·(0,−1,1) = (−1/4, 0, 1/4); right: T_1·v1(T_0) = T_1·(−1,1,0),
    // the same vector: G1.
    let left = joint.left.as_ref().unwrap();
    let right = joint.right.as_ref().unwrap();
    assert_eq!(left.tangent.as_deref().unwrap(), ["-1/4", "0", "1/4"]);
    assert_eq!(right.tangent.as_deref().unwrap(), ["-1/4", "0", "1/4"]);
    assert_eq!(joint.tangent_continuous, Some(true));
    assert_eq!(left.class, Some(CurvatureClass::Finite));
    assert_eq!(curve.points[2].point, ["0", "0", "1"]);
    let text = rep.to_text();
    assert!(
        text.contains("joint e.T0|e.T1 at (1/4, 1/2, 1/4)"),
        "{text}"
    );
}

#[test]
fn chaikin_fixed_points_are_not_control_points() {
    let rep = analyse_automaton(&fixture("chaikin-known.aut")).unwrap();
    let t0 = &rep.operators[0];
    assert_eq!(t0.fixed_point.as_deref().unwrap(), ["1/2", "1/2", "0"]);
    assert_eq!(t0.behaviour.class(), Some(CurvatureClass::Finite));
    let curve = &rep.curves[0];
    assert!(curve.joined);
    assert_eq!(curve.points[1].point, ["1/8", "3/4", "1/8"]);
    assert_eq!(curve.points[1].tangent_continuous, Some(true));
}

#[test]
fn unknown_operators_are_skipped() {
    let rep = analyse_automaton(&fixture("spec-edge.aut")).unwrap();
    assert_eq!(rep.skipped.len(), 2);
    assert!(rep.curves[0].note.as_deref().unwrap().contains("unknown"));
}

#[test]
fn parabola_curvature_estimate() {
    // Control points (0,0), (1,1), (2,0): B(t) = (2t, 2t(1−t)), B'(0) = (2, 2),
    // B''(0) = (0, −4), curvature at P0 = (2·(−4) − 2·0)/|B'|³ = −8/8^1.5 = −1/(2√2).
    let ops = [m(DE_CASTELJAU_T0), m("[1/4 0 0; 1/2 1/2 0; 1/4 1/2 1]")];
    let est = estimate_curvature(&ops, 0, &[[0.0, 0.0], [1.0, 1.0], [2.0, 0.0]], 4).unwrap();
    let expected = -1.0 / (2.0 * 2f64.sqrt());
    let [lo, hi] = est.positive_side.or(est.negative_side).unwrap();
    assert!(
        (lo - expected).abs() < 1e-9 && (hi - expected).abs() < 1e-9,
        "{}",
        est.to_text()
    );
    assert!(est.samples > 0);
    // A sharp operator has no finite curvature range.
    let e = estimate_curvature(&[half_tangent("1/4", "3/8")], 0, &[[0.0, 0.0]; 3], 2).unwrap_err();
    assert_eq!(e.code(), "E0903");
}

#[test]
fn design_errors_name_the_reason() {
    let v = |s: &str| parse_rationals_arg(s).unwrap();
    let e = design_operator(&v("1/2 1/4"), &[v("1 0"), v("-1 1")]).unwrap_err();
    assert_eq!(e, DesignError::NoEigenvalueOne);
    let e = design_operator(&v("1 1/2"), &[v("1 0"), v("1 1")]).unwrap_err();
    assert!(matches!(e, DesignError::NotBarycentric { index: 1, .. }));
    assert_eq!(e.code(), "E0908");
    let e = design_operator(&v("1 1/2 1/4"), &[v("1 0 0"), v("-1 1 0"), v("2 -2 0")]).unwrap_err();
    assert_eq!(e, DesignError::Singular { index: 2 });
    let e = design_operator(&v("1 1/2"), &[v("1 0")]).unwrap_err();
    assert_eq!(e.code(), "E0906");
}

#[test]
fn design_checked_against_the_spec_edge() {
    let a = fixture("spec-edge.aut");
    let t0 = m(DE_CASTELJAU_T0);
    let check = check_design(&a, "e.T0", &t0).unwrap();
    assert!(check.ok(), "{}", check.to_text());
    // The incidence e.B0 * v.T0 = e.T0 * e.B0 involves only T_0 and known operators: evaluated.
    assert!(check.constraints.iter().any(|c| c.text.contains("e.T0")));
    // Fixed point (0,1,0) instead of (1,0,0): the incidence B_0·[1] = T_0·B_0 fails at (0,0).
    let bad = design_operator(
        &[r("1"), r("1/2"), r("1/4")],
        &[
            vec![r("0"), r("1"), r("0")],
            vec![r("-1"), r("1"), r("0")],
            vec![r("1"), r("-2"), r("1")],
        ],
    )
    .unwrap();
    let check = check_design(&a, "e.T0", &bad).unwrap();
    assert!(!check.ok());
    let failed: Vec<_> = check.constraints.iter().filter(|c| !c.holds).collect();
    assert_eq!(failed.len(), 1, "{}", check.to_text());
    assert!(failed[0]
        .difference
        .as_deref()
        .unwrap()
        .starts_with("entry (0, 0)"));
    assert!(!check.consistent);
    let e = check_design(&a, "e.T9", &t0).unwrap_err();
    assert_eq!(e.code(), "E0910");
}

#[test]
fn matrix_arguments() {
    assert_eq!(m("1 2; 3 4"), m("[1, 2; 3, 4]"));
    let e = parse_matrix_arg("[1 x; 0 1]").unwrap_err();
    assert_eq!(e.code(), "E0901");
    assert!(e.render().contains("<command line>:1:4"), "{}", e.render());
    assert_eq!(parse_matrix_arg("[1 2; 3]").unwrap_err().code(), "E0901");
    assert_eq!(
        parse_rationals_arg("1 1/2 0.25").unwrap(),
        vec![r("1"), r("1/2"), r("1/4")]
    );
}

#[test]
fn json_reports() {
    let rep = analyse_matrix(&m(DE_CASTELJAU_T0)).unwrap();
    let j = serde_json::to_value(&rep).unwrap();
    assert_eq!(j["behaviour"]["case"], "tangent");
    assert_eq!(j["behaviour"]["class"], "finite");
    assert_eq!(j["fixed_point"][0], "1");
}

fn arb_design() -> impl Strategy<Value = (Vec<BigRational>, Vec<Vec<BigRational>>)> {
    (2usize..=4).prop_flat_map(|n| {
        (
            prop::collection::btree_set((-20i64..20, 1i64..9), n - 1),
            prop::collection::vec(prop::collection::vec(-4i64..5, n), n),
        )
            .prop_map(move |(vals, raw)| {
                let mut ev = vec![BigRational::from_integer(1.into())];
                for (p, q) in vals {
                    let x = BigRational::new(p.into(), q.into());
                    if !ev.contains(&x) {
                        ev.push(x);
                    }
                }
                let n = ev.len();
                let mut vecs: Vec<Vec<BigRational>> = raw
                    .iter()
                    .take(n)
                    .map(|v| {
                        v.iter()
                            .take(n)
                            .map(|&x| BigRational::from_integer(x.into()))
                            .collect()
                    })
                    .collect();
                for v in vecs.iter_mut().skip(1) {
                    // Coordinate sum 0: the last coordinate balances the others.
                    let s: BigRational = v[..n - 1].iter().sum();
                    v[n - 1] = -s;
                }
                (ev, vecs)
            })
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    #[test]
    fn design_round_trips_eigenvalues_and_eigenvectors((ev, vecs) in arb_design()) {
        let n = ev.len();
        let sum0: BigRational = vecs[0].iter().sum();
        prop_assume!(sum0 != BigRational::from_integer(0.into()));
        let t = match design_operator(&ev, &vecs) {
            Ok(t) => t,
            Err(DesignError::Singular { .. }) => return Ok(()),
            Err(e) => panic!("unexpected {e}"),
        };
        prop_assert!(t.is_barycentric());
        let rep = analyse_matrix(&t).unwrap();
        prop_assert_eq!(rep.eigenvalues.len(), n);
        for (l, v) in ev.iter().zip(&vecs) {
            let e = rep.eigenvalues.iter().find(|e| e.exact.as_deref() == Some(&l.to_string()));
            let e = e.unwrap_or_else(|| panic!("eigenvalue {l} missing from {}", rep.to_text()));
            prop_assert_eq!(e.multiplicity, 1);
            prop_assert_eq!(e.eigenvectors.len(), 1);
            let w: Vec<BigRational> = e.eigenvectors[0].iter().map(|s| r(s)).collect();
            // Parallel: every 2×2 minor vanishes.
            for i in 0..n {
                for j in 0..n {
                    prop_assert_eq!(&v[i] * &w[j], &v[j] * &w[i]);
                }
            }
        }
        // The fixed point is the eigenvector of 1 scaled to sum 1.
        let fp: Vec<BigRational> = rep.fixed_point.unwrap().iter().map(|s| r(s)).collect();
        let expect: Vec<BigRational> = vecs[0].iter().map(|x| x / &sum0).collect();
        prop_assert_eq!(fp, expect);
    }
}

#[test]
fn cli_curvature_estimate_of_the_parabola() {
    // B(t) = (2t, 2t − 2t²) for the control points (0,0), (1,1), (2,0): at t = 0,
    // κ = (x'y'' − y'x'')/(x'² + y'²)^{3/2} = (2·(−4) − 0)/8^{3/2} = −1/(2√2).
    let (code, out, err) = common::lacuna(&[
        "operators",
        "de-casteljau-edge",
        "--curvature",
        "e.T0",
        "--points",
        "0 0; 1 1; 2 0",
        "--level",
        "6",
        "--json",
    ]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let side = &v["curvature"]["positive_side"];
    let want = -1.0 / (2.0 * 2f64.sqrt());
    for k in 0..2 {
        assert!((side[k].as_f64().unwrap() - want).abs() < 1e-9, "{side}");
    }
}

#[test]
fn koch_s_rotations_are_analysed_over_q_sqrt3() {
    // The Koch maps on [0, 1] as complex maps: f1(z) = e^(iπ/3)·z/3 + 1/3 and
    // f2(z) = e^(−iπ/3)·z/3 + 1/2 + i√3/6. Their linear parts are rotations by ±60° of ratio
    // 1/3: χ = (x − 1)(x² − x/3 + 1/9) over Q although the entries hold √3, so no real
    // eigenvalue but 1 — spiralling — and every other modulus 1/3 < 1 — contractive. Fixed
    // points by hand: f1: z = (1/3)/(1 − e^(iπ/3)/3) = (5 + i√3)/14; f2: z = (1/2 + i√3/6)/(1 −
    // e^(−iπ/3)/3) = (3 + i√3)/(5 + i√3) = (9 + i√3)/14. In barycentric coordinates of the frame
    // (0, 0), (1, 0), (0, 1): (1 − x − y, x, y).
    let (code, out, err) = common::lacuna(&["operators", "koch", "--json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let ops = v["automaton"]["operators"].as_array().unwrap();
    let op = |name: &str| {
        ops.iter()
            .find(|o| o["name"] == name)
            .unwrap_or_else(|| panic!("{name} is analysed: {v}"))
    };
    for (name, fixed) in [
        ("koch.T1", ["(9 - sqrt(3))/14", "5/14", "sqrt(3)/14"]),
        ("koch.T2", ["(5 - sqrt(3))/14", "9/14", "sqrt(3)/14"]),
    ] {
        let o = op(name);
        assert_eq!(o["behaviour"]["case"], "spiralling", "{o}");
        assert_eq!(o["contractive"], true, "{o}");
        assert_eq!(o["fixed_point"], serde_json::json!(fixed), "{name}");
        // Two complex eigenvalues of modulus 1/3: real part 1/6, imaginary √3/6.
        let pair = o["eigenvalues"]
            .as_array()
            .unwrap()
            .iter()
            .find(|e| e["real"] == false)
            .expect("a complex pair");
        assert_eq!(pair["min_poly"], "x^2 - 1/3*x + 1/9", "{pair}");
    }
    // Nothing of the curve's state is skipped for its field any more; the curve is not read.
    let skipped = v["automaton"]["skipped"].as_array().unwrap();
    assert!(
        skipped
            .iter()
            .all(|s| s.as_str().unwrap().starts_with("initiator.")),
        "{skipped:?}"
    );
    assert_eq!(v["automaton"]["curves"][0]["joined"], false);
}
