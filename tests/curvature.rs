//! The differential characteristic function and pseudo-curvature (issue #16; Janbein, Gentil,
//! Roudet, Poull, GRAPP 2024). Every expected value is derived by hand in the test that checks it.

mod common;

use lacuna::{
    algebra::{bezier_restriction, Matrix},
    analysis::{
        analyse_matrix, curve_curvature, operator_dcf, parse_matrix_arg, CurvatureClass,
        CurveCurvature,
    },
};
use num_rational::BigRational;

fn m(text: &str) -> Matrix {
    parse_matrix_arg(text).unwrap_or_else(|e| panic!("matrix {text}: {}", e.render()))
}

fn q(n: i64, d: i64) -> BigRational {
    BigRational::new(n.into(), d.into())
}

fn names(n: usize) -> Vec<String> {
    (0..n).map(|i| format!("T{i}")).collect()
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-9 * b.abs().max(1.0)
}

/// The κ range `[inf, sup]` on one side of the point with parameter `t`.
fn range(c: &CurveCurvature, t: &str, left: bool) -> [f64; 2] {
    let p = c.points.iter().find(|p| p.t == t).expect("point");
    let s = if left { &p.left } else { &p.right };
    let s = s.as_ref().expect("side");
    [s.kappa_inf.0, s.kappa_sup.0]
}

const PARABOLA: [[f64; 2]; 3] = [[0.0, 0.0], [1.0, 1.0], [2.0, 0.0]];

fn de_casteljau(q_deg: usize) -> Vec<Matrix> {
    vec![
        bezier_restriction(q_deg, &q(0, 1), &q(1, 2)),
        bezier_restriction(q_deg, &q(1, 2), &q(1, 1)),
    ]
}

#[test]
fn quadratic_bezier_curvature_at_the_start_and_the_joint() {
    // B(t) = (1−t)²·(0,0) + 2t(1−t)·(1,1) + t²·(2,0) = (2t, 2t − 2t²):
    // B' = (2, 2 − 4t), B'' = (0, −4), κ = |B' × B''| / |B'|³ = 8 / |B'|³.
    // t = 0: |B'| = √8, κ = 8 / (8·√8) = 1/(2√2) ≈ 0.353553.
    // t = 1/2: B' = (2, 0), κ = 8 / 8 = 1 (from both sides: the curve is a polynomial).
    // t = 3/8: B' = (2, 1/2), |B'|² = 17/4, κ = 8 / (17/4)^(3/2) ≈ 0.913014.
    let pts: Vec<Vec<f64>> = PARABOLA.iter().map(|p| p.to_vec()).collect();
    let c = curve_curvature(&names(2), &de_casteljau(2), &pts, &[q(3, 8)], 8).unwrap();
    let start = 1.0 / (2.0 * 2f64.sqrt());
    let [lo, hi] = range(&c, "0", false);
    assert!(close(lo, start) && close(hi, start), "{}", c.to_text(true));
    for left in [true, false] {
        let [lo, hi] = range(&c, "1/2", left);
        assert!(close(lo, 1.0) && close(hi, 1.0), "{}", c.to_text(true));
        let k = 8.0 / (17f64 / 4.0).powf(1.5);
        let [lo, hi] = range(&c, "3/8", left);
        assert!(close(lo, k) && close(hi, k), "{lo} {hi} {k}");
    }
    let [lo, hi] = range(&c, "1", true);
    assert!(close(lo, start) && close(hi, start));
    // The DCF of T0 at c0 = (1, 0, 0): v1 = (−1, 1, 0) (λ1 = 1/2), v2 = (1, −2, 1) (λ2 = 1/4).
    // From q0 = c1 = (0, 0, 1): q0 − c0 = (−1, 0, 1) = 2·v1 + 1·v2, so x1 = 2, x2 = 1,
    // β = x2/x1² = 1/4, and κ = 2β·|V1 × V2|/|V1|³ with V1 = (1, 1), V2 = (0, −2):
    // 2·(1/4)·2 / (2√2) = 1/(2√2), the value above.
    let d = c.dcfs[0].as_ref().unwrap();
    assert_eq!((d.alpha.as_str(), d.alpha_exact), ("2", true));
    assert_eq!(d.v1, ["-1", "1", "0"]);
    assert_eq!(d.v2, ["1", "-2", "1"]);
    let s = &d.starts[0];
    assert_eq!((s.x1.as_str(), s.x2.as_str()), ("2", "1"));
    assert_eq!(s.beta.as_deref(), Some("1/4"));
    // The same curve in 3D, tilted out of the plane z = 0 by a rotation about the x axis
    // (an isometry): the same curvatures.
    let (cs, sn) = (0.6, 0.8);
    let pts3: Vec<Vec<f64>> = PARABOLA
        .iter()
        .map(|p| vec![p[0], p[1] * cs, p[1] * sn])
        .collect();
    let c3 = curve_curvature(&names(2), &de_casteljau(2), &pts3, &[], 8).unwrap();
    let [lo, hi] = range(&c3, "1/2", true);
    assert!(close(lo, 1.0) && close(hi, 1.0));
    let [lo, _] = range(&c3, "0", false);
    assert!(close(lo, start));
    // Pictures: a plane curve is drawn with its osculating circles (κinf and κsup on each side
    // of the points t = 0, 1/2, 1, 3/8: 1 + 2 + 1 + 2 sides, two circles each, plus a dot at
    // each point); a space curve is not drawn.
    let svg = c.to_svg().unwrap();
    assert!(svg.contains("<polyline"));
    assert_eq!(svg.matches("<circle").count(), 2 * 6 + 4);
    assert!(c3.to_svg().is_none());
}

#[test]
fn de_casteljau_operators_have_alpha_two_everywhere() {
    // The restriction to [0, 1/2] of a degree-q Bézier curve is triangular with diagonal
    // 1, 1/2, 1/4, …, (1/2)^q: λ1 = 1/2, λ2 = 1/4 = λ1², so α = 2 (exactly) at both fixed
    // points, hence at every dyadic point (the images keep the class).
    for deg in 2..=4 {
        let ops = de_casteljau(deg);
        let pts: Vec<Vec<f64>> = (0..=deg)
            .map(|i| vec![i as f64, (i * i) as f64 / 3.0])
            .collect();
        let c = curve_curvature(&names(2), &ops, &pts, &[q(1, 4), q(5, 8)], 6).unwrap();
        for d in &c.dcfs {
            let d = d.as_ref().unwrap();
            assert_eq!(
                (d.alpha.as_str(), d.class.as_str()),
                ("2", "finite"),
                "degree {deg}"
            );
        }
        for p in &c.points {
            for s in [&p.left, &p.right].into_iter().flatten() {
                assert_eq!(s.class, "finite", "degree {deg}, t = {}", p.t);
                assert!(s.kappa_sup.0.is_finite());
            }
        }
    }
}

#[test]
fn lambda2_near_lambda1_squared_changes_class_exactly_at_epsilon_zero() {
    // T(ε) = [1 1/2 1 − μ; 0 1/2 0; 0 0 μ], μ = (1/4)(1 + ε): triangular, eigenvalues 1, 1/2, μ,
    // columns sum to 1. λ1 = 1/2, λ2 = μ: α = log μ / log(1/2) is > 2 for ε < 0 (flat), = 2 at
    // ε = 0 (finite), < 2 for ε > 0 (sharp) — decided exactly, even for |ε| = 10^−40.
    let eps = [
        "-1/1000",
        "-1/10000000000000000000000000000000000000000",
        "0",
        "1/10000000000000000000000000000000000000000",
        "1/1000",
    ];
    let expect = [
        CurvatureClass::Flat,
        CurvatureClass::Flat,
        CurvatureClass::Finite,
        CurvatureClass::Sharp,
        CurvatureClass::Sharp,
    ];
    for (e, want) in eps.iter().zip(expect) {
        let e = lacuna::input::parse_rational(e).unwrap();
        let mu = q(1, 4) * (q(1, 1) + e);
        let t = m(&format!("[1 1/2 {}; 0 1/2 0; 0 0 {mu}]", q(1, 1) - &mu));
        let rep = analyse_matrix(&t).unwrap();
        assert_eq!(
            rep.behaviour.class(),
            Some(want),
            "μ = {mu}: {}",
            rep.summary()
        );
    }
}

#[test]
fn negative_lambda1_gives_two_sub_sequences_with_the_same_range() {
    // T0 = [1 3/2 1/4; 0 −1/2 1/2; 0 0 1/4] (columns sum to 1), T1 the de Casteljau right half.
    // They join: T0·c1 = third column of T0 = (1/4, 1/2, 1/4) = first column of T1 = T1·c0.
    // T0 is triangular: λ1 = −1/2, λ2 = 1/4 = λ1², c0 = (1, 0, 0).
    // (T0 + I/2)v = 0: z = 0, x = −y → v1 = (−1, 1, 0).
    // (T0 − I/4)v = 0: −3y/4 + z/2 = 0, 3x/4 + 3y/2 + z/4 = 0 → v2 = (−5/3, 2/3, 1).
    // Left eigenvectors: u1 = (0, −3/2, 1) (u1·v1 = −3/2), u2 = (0, 0, 1) (u2·v2 = 1).
    // From q0 = c1 = (0, 0, 1): q0 − c0 = (−1, 0, 1), x1 = 1/(−3/2) = −2/3, x2 = 1:
    // indeed −2/3·(−1, 1, 0) + (−5/3, 2/3, 1) = (−1, 0, 1). β = x2/x1² = 9/4.
    // Even iterates: t = x1·(1/4)^m < 0, on c + t·v1 + β·t²·v2; odd ones t = x1·(−1/2)^(2m+1) > 0,
    // the other side, same β. With P = (0,0), (1,1), (2,0): V1 = (1, 1), V2 = (8/3, 2/3),
    // |V1 × V2| = |2/3 − 8/3| = 2, |V1|³ = 2√2, so κ = 2·β·2/(2√2) = √2·β = 9√2/4 ≈ 3.181981
    // for both sub-sequences: both sides of c0 carry the same range, which contains 9√2/4.
    let t0 = m("[1 3/2 1/4; 0 -1/2 1/2; 0 0 1/4]");
    let t1 = de_casteljau(2).remove(1);
    let pts: Vec<Vec<f64>> = PARABOLA.iter().map(|p| p.to_vec()).collect();
    let c = curve_curvature(&names(2), &[t0, t1], &pts, &[], 8).unwrap();
    let d = c.dcfs[0].as_ref().unwrap();
    assert_eq!(d.lambda1, "-1/2");
    assert_eq!(d.lambda2, "1/4");
    assert_eq!(d.v2, ["-5/3", "2/3", "1"]);
    assert!(d.case.starts_with("λ1 < 0"));
    let s = &d.starts[0];
    assert_eq!(
        (s.x1.as_str(), s.x2.as_str(), s.beta.as_deref()),
        ("-2/3", "1", Some("9/4"))
    );
    let k = 9.0 * 2f64.sqrt() / 4.0;
    let sides = &c.fixed_points[0];
    assert_eq!(sides.len(), 2);
    let (a, b) = (&sides[0], &sides[1]);
    assert_eq!((a.kappa_inf, a.kappa_sup), (b.kappa_inf, b.kappa_sup));
    assert!(
        a.kappa_inf.0 <= k + 1e-9 && k - 1e-9 <= a.kappa_sup.0,
        "{}",
        c.to_text(true)
    );
}

#[test]
fn bad_parameters_are_coded_errors() {
    let pts: Vec<Vec<f64>> = PARABOLA.iter().map(|p| p.to_vec()).collect();
    // 1/3 is not dyadic for two operators.
    let e = curve_curvature(&names(2), &de_casteljau(2), &pts, &[q(1, 3)], 4).unwrap_err();
    assert!(e.render().contains("E0911"), "{}", e.render());
    let e = curve_curvature(&names(2), &de_casteljau(2), &pts, &[q(3, 2)], 4).unwrap_err();
    assert!(e.render().contains("E0911"));
    // Two control points for 3×3 operators.
    let e = curve_curvature(&names(2), &de_casteljau(2), &pts[..2], &[], 4).unwrap_err();
    assert!(e.render().contains("E0905"));
    // Pieces that do not join: T0·c1 = B(1/2) but the restriction to [1/3, 1] maps c0 to B(1/3).
    let ops = vec![
        de_casteljau(2).remove(0),
        bezier_restriction(2, &q(1, 3), &q(1, 1)),
    ];
    let e = curve_curvature(&names(2), &ops, &pts, &[], 4).unwrap_err();
    assert!(e.render().contains("E0912"), "{}", e.render());
}

#[test]
fn cli_summary_op_at_and_json() {
    // F0's eleven operators: a summary without long exact forms (the longest exact forms are
    // thousands of characters: eigenvectors over fields of degree 5).
    let (code, out, err) = common::lacuna(&["operators", "F0"]);
    assert_eq!(code, 0, "{err}");
    let longest = out.lines().map(|l| l.chars().count()).max().unwrap();
    assert!(longest <= 200, "a line of {longest} characters");
    assert!(
        out.contains("T0.T0 (9×9, barycentric, contractive): sharp"),
        "{out}"
    );
    // --op: one operator only.
    let (code, out, _) = common::lacuna(&["operators", "F0", "--op", "T0.T0"]);
    assert_eq!(code, 0);
    assert!(out.starts_with("T0.T0 ") && !out.contains("T0.T1"), "{out}");
    let (code, _, err) = common::lacuna(&["operators", "F0", "--op", "T9.T9"]);
    assert_eq!(code, 2);
    assert!(err.contains("E0910"), "{err}");
    // --at 1/3 is not dyadic for a curve of two operators.
    let args = [
        "operators",
        "de-casteljau-edge",
        "--points",
        "0 0; 1 1; 2 0",
        "--at",
    ];
    let (code, _, err) = common::lacuna(&[&args[..], &["1/3"]].concat());
    assert_eq!(code, 2);
    assert!(err.contains("E0911"), "{err}");
    // JSON: every point carries kappa_inf and kappa_sup per side; 1 at the joint (see above).
    let (code, out, err) = common::lacuna(&[&args[..], &["1/4", "--json"]].concat());
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let points = v["curves"][0]["curvature"]["points"].as_array().unwrap();
    let joint = points.iter().find(|p| p["t"] == "1/2").unwrap();
    for side in ["left", "right"] {
        for k in ["kappa_inf", "kappa_sup"] {
            assert!(
                (joint[side][k].as_f64().unwrap() - 1.0).abs() < 1e-9,
                "{joint}"
            );
        }
    }
    assert!(points.iter().any(|p| p["t"] == "1/4"));
}

#[test]
fn equal_moduli_are_described_as_the_paper_does() {
    // [1 1/2 1/2; 0 1/2 0; 0 0 1/2]: 1/2 twice (columns sum to 1): λ1 = λ2, straight lines.
    let e = operator_dcf("T", &m("[1 1/2 1/2; 0 1/2 0; 0 0 1/2]"), &[]).unwrap_err();
    assert!(e.starts_with("λ1 = λ2 = 1/2"), "{e}");
    // [1 3/2 1/2; 0 −1/2 0; 0 0 1/2]: λ1 = −1/2, λ2 = 1/2, α = 1, two lines.
    let e = operator_dcf("T", &m("[1 3/2 1/2; 0 -1/2 0; 0 0 1/2]"), &[]).unwrap_err();
    assert!(e.starts_with("λ1 = −λ2") && e.contains("α = 1"), "{e}");
    // [1 3/2 3/4; 0 −1/2 0; 0 0 1/4]: λ1 = −1/2, λ2 = 1/4 = λ1²: α = 2 exactly; from the
    // vertex e2 = (0, 0, 1): q − c = (−1, 0, 1); v1 = (−1, 1, 0), v2 = (−1, 0, 1) (row 2 forces
    // y = 0), so x1 = 0 — no DCF from e2; from e1 = (0, 1, 0): q − c = (−1, 1, 0) = v1: x1 = 1,
    // x2 = 0, β = 0 (the iterates run along the line c + t·v1, on both sides).
    let d = operator_dcf(
        "T",
        &m("[1 3/2 3/4; 0 -1/2 0; 0 0 1/4]"),
        &[
            ("e2".into(), vec![q(0, 1), q(0, 1), q(1, 1)]),
            ("e1".into(), vec![q(0, 1), q(1, 1), q(0, 1)]),
        ],
    )
    .unwrap();
    // λ1 < 0: the tangent flips side at every iterate, so the class is `oscillating` whatever
    // α (THEORY §8), though the even and odd iterates lie on DCFs of exponent 2.
    assert_eq!((d.alpha.as_str(), d.class.as_str()), ("2", "oscillating"));
    assert_eq!(d.v2, ["-1", "0", "1"]);
    assert_eq!(d.starts.len(), 1);
    let s = &d.starts[0];
    assert_eq!(
        (s.from.as_str(), s.x1.as_str(), s.x2.as_str()),
        ("e1", "1", "0")
    );
    assert_eq!(s.beta.as_deref(), Some("0"));
}
