//! Certificates and the independent checker (issue #5): the checker's isolation, the committed
//! `proofs/`, round trips, mutations that must be rejected (each naming its step), and random
//! faces.
//!
//! `proofs/*.json` are regenerated and compared byte for byte; after an intended change rewrite
//! them with `LACUNA_BLESS=1 cargo test --test certificates`.

use lacuna::certificate::{Certificate, RatioClaim, Step};
use lacuna::certify::{
    certificate_for, certificate_for_automaton, certificate_for_system, ratio_step,
};
use lacuna::checker::{check, check_json, Outcome};
use lacuna::{Algorithm, EdgeKind, EdgeType, Face, GenOptions, Limits, Params};
use num_rational::BigRational;
use proptest::prelude::*;

const FACE_FIXTURES: [&str; 7] = [
    "F0",
    "cycle-sqrt17",
    "square-B2",
    "triangle-C2",
    "delayed-B2-C2",
    "two-quads",
    "autofrac-two-quads",
];
const AUTOMATON_FIXTURES: [&str; 7] = [
    "de-casteljau-edge",
    "chaikin-known",
    "spec-edge",
    "spec-edge-incidence",
    "half-tangent-edge",
    "bspline-quadratic",
    "quad-patch",
];

#[test]
fn every_library_entry_has_a_proof() {
    for (name, _) in lacuna::library() {
        assert!(
            FACE_FIXTURES.contains(name) || AUTOMATON_FIXTURES.contains(name),
            "library entry {name} has no certificate in proofs/: add it to the lists above and bless"
        );
    }
}

fn face_certificate(name: &str) -> Certificate {
    let input = lacuna::load_input(name).unwrap_or_else(|e| panic!("{name}: {}", e.render()));
    let ts = lacuna::close_or_error(&input.faces(), &Limits::default()).expect("closes");
    certificate_for(name, &ts, GenOptions::default()).expect("certifiable")
}

fn automaton_certificate(name: &str) -> Certificate {
    match lacuna::load_any(name).expect("loads") {
        lacuna::Loaded::Automaton { automaton, .. } => {
            certificate_for_automaton(name, &automaton).expect("certifiable")
        }
        lacuna::Loaded::Faces(_) => panic!("{name} is not an automaton"),
    }
}

/// Emits, round-trips and checks a certificate (STYLE rule 5): every step must be proved.
fn assert_proved(name: &str, cert: &Certificate) {
    let json = cert.to_json();
    assert_eq!(
        json,
        cert.to_json(),
        "{name}: serialisation is not deterministic"
    );
    let back = Certificate::from_json(&json).expect("parses back");
    assert_eq!(
        &back, cert,
        "{name}: JSON round trip changed the certificate"
    );
    let report = check_json(&json);
    assert!(report.all_proved(), "{name}:\n{}", report.to_text());
}

/// Asserts that the checker rejects `cert` at the step called `step`, with a message naming it.
fn assert_rejected(what: &str, cert: &Certificate, step: &str) {
    let report = check(cert);
    let failed: Vec<_> = report
        .steps
        .iter()
        .filter(|s| s.outcome == Outcome::Failed)
        .collect();
    assert!(
        failed
            .iter()
            .any(|s| s.step == step && s.message.contains(step)),
        "{what}: expected step `{step}` to fail, got:\n{}",
        report.to_text()
    );
    assert!(!report.all_proved());
}

fn steps_named<'a>(cert: &'a mut Certificate, name: &str) -> Vec<&'a mut Step> {
    cert.steps.iter_mut().filter(|s| s.name() == name).collect()
}

#[test]
fn checker_imports_only_the_certificate_module() {
    let dir = env!("CARGO_MANIFEST_DIR");
    let allowed_roots = [
        "std",
        "crate::certificate",
        "num_bigint",
        "num_rational",
        "num_traits",
        "num_integer",
        "serde_json",
    ];
    for (file, roots) in [
        ("src/checker.rs", &allowed_roots[..]),
        ("src/certificate.rs", &["std", "serde", "serde_json"][..]),
    ] {
        let text = std::fs::read_to_string(format!("{dir}/{file}")).expect("readable");
        for (i, line) in text.lines().enumerate() {
            let code = line.split("//").next().unwrap_or("");
            for bad in ["lacuna::", "super::", "::lacuna", "extern crate", "#[path"] {
                assert!(!code.contains(bad), "{file}:{}: `{bad}` in `{line}`", i + 1);
            }
            let mut rest = code;
            while let Some(at) = rest.find("crate::") {
                let after = &rest[at + "crate::".len()..];
                assert!(
                    roots.contains(&"crate::certificate") && after.starts_with("certificate"),
                    "{file}:{}: path into lacuna other than crate::certificate: `{line}`",
                    i + 1
                );
                rest = after;
            }
            if let Some(path) = code.trim_start().strip_prefix("use ") {
                assert!(
                    roots.iter().any(|r| path.starts_with(r)),
                    "{file}:{}: `use {path}` is not allowed here",
                    i + 1
                );
            }
        }
    }
}

#[test]
fn proofs_are_fresh_and_check() {
    let dir = format!("{}/proofs", env!("CARGO_MANIFEST_DIR"));
    let bless = std::env::var_os("LACUNA_BLESS").is_some_and(|v| v == "1");
    let all = FACE_FIXTURES
        .iter()
        .map(|n| (*n, face_certificate(n)))
        .chain(
            AUTOMATON_FIXTURES
                .iter()
                .map(|n| (*n, automaton_certificate(n))),
        );
    for (name, cert) in all {
        let path = format!("{dir}/{name}.json");
        let json = cert.to_json();
        if bless {
            std::fs::write(&path, &json).expect("writable proofs/");
        }
        let on_disk = std::fs::read_to_string(&path).unwrap_or_default();
        assert!(
            on_disk == json,
            "proofs/{name}.json is stale or missing: regenerate with \
             `LACUNA_BLESS=1 cargo test --test certificates` and review the diff"
        );
        let report = check_json(&on_disk);
        assert!(
            report.all_proved(),
            "proofs/{name}.json:\n{}",
            report.to_text()
        );
    }
}

#[test]
fn every_fixture_round_trips_and_checks() {
    for name in FACE_FIXTURES {
        let cert = face_certificate(name);
        let names: Vec<&str> = cert.steps.iter().map(Step::name).collect();
        assert_eq!(
            names,
            ["closure", "solution-space", "limit-ratio"],
            "{name}"
        );
        assert_proved(name, &cert);
    }
    for name in AUTOMATON_FIXTURES {
        assert_proved(name, &automaton_certificate(name));
    }
}

#[test]
fn f0_ratio_is_one_third() {
    let cert = face_certificate("F0");
    let Some(Step::LimitRatio(r)) = cert.steps.last() else {
        panic!("no ratio step")
    };
    let RatioClaim::Limit(p) = &r.claim else {
        panic!("F0 is covered")
    };
    assert_eq!(p.ratio, ["1/3"]);
    assert_eq!(p.rho.poly, ["-6", "1"]);
}

#[test]
fn mutated_closures_are_rejected() {
    // Drop one type: a sub-face then refers to a type that is not listed.
    let mut cert = face_certificate("triangle-C2");
    if let [Step::Closure(c)] = &mut steps_named(&mut cert, "closure")[..] {
        c.types.pop();
    }
    assert_rejected("drop a type", &cert, "closure");
    // Change one origin.
    let mut cert = face_certificate("F0");
    if let [Step::Closure(c)] = &mut steps_named(&mut cert, "closure")[..] {
        c.types[0].subfaces[2].origins.swap(0, 1);
    }
    assert_rejected("swap two origins", &cert, "closure");
    let mut cert = face_certificate("delayed-B2-C2");
    if let [Step::Closure(c)] = &mut steps_named(&mut cert, "closure")[..] {
        c.types[0].contribution_halves += 1;
    }
    assert_rejected("change a contribution", &cert, "closure");
    let mut cert = face_certificate("square-B2");
    if let [Step::Closure(c)] = &mut steps_named(&mut cert, "closure")[..] {
        c.types[1].adjacencies.reverse();
        c.types[1].adjacencies.pop();
    }
    assert_rejected("drop an adjacency", &cert, "closure");
}

#[test]
fn mutated_solution_spaces_are_rejected() {
    let base = face_certificate("F0");
    let edit = |f: &dyn Fn(&mut lacuna::certificate::SolutionStep)| {
        let mut cert = base.clone();
        if let [Step::SolutionSpace(s)] = &mut steps_named(&mut cert, "solution-space")[..] {
            f(s);
        }
        cert
    };
    let bump = |s: &mut String| {
        *s = format!(
            "{}",
            s.parse::<BigRational>().unwrap() + BigRational::from_integer(1.into())
        )
    };
    let c = edit(&|s| bump(&mut s.basis[0][0].1));
    assert_rejected("change a basis entry", &c, "solution-space");
    let c = edit(&|s| {
        let last = s.basis[3].len() - 1;
        bump(&mut s.basis[3][last].1)
    });
    assert_rejected("change another basis entry", &c, "solution-space");
    let c = edit(&|s| bump(&mut s.particular[0].1));
    assert_rejected("change the particular solution", &c, "solution-space");
    let c = edit(&|s| bump(&mut s.system.rows[7].rhs));
    assert_rejected("change a right-hand side", &c, "solution-space");
    let c = edit(&|s| {
        s.pivots.pop();
        s.rank -= 1;
    });
    assert_rejected("drop a pivot", &c, "solution-space");
    let c = edit(&|s| {
        let (r, _) = s.pivots[0];
        let other = s.free[0];
        s.pivots[0] = (r, other);
    });
    assert_rejected("a free unknown as pivot", &c, "solution-space");
}

#[test]
fn inconsistent_systems_are_certified_and_mutations_rejected() {
    // x0 + x1 = 1, x1 + x2 = 1, x0 − x2 = 1 (the first minus the second gives x0 − x2 = 0), x3 = 5.
    let q = |n: i64| BigRational::from_integer(n.into());
    let row = |terms: &[(usize, i64)], rhs: i64| lacuna::Equation {
        terms: terms.iter().map(|&(v, c)| (v, q(c))).collect(),
        rhs: q(rhs),
    };
    let sys = lacuna::LinearSystem {
        unknowns: 4,
        rows: vec![
            row(&[(3, 1)], 5),
            row(&[(0, 1), (1, 1)], 1),
            row(&[(1, 1), (2, 1)], 1),
            row(&[(0, 1), (2, -1)], 1),
        ],
    };
    let solution = lacuna::solve(&sys);
    assert!(matches!(solution, lacuna::Solution::Inconsistent(_)));
    let cert = certificate_for_system("planted", "a planted inconsistent system", &sys, &solution);
    assert_proved("planted", &cert);
    let mut bad = cert.clone();
    if let [Step::Inconsistent(c)] = &mut steps_named(&mut bad, "inconsistent")[..] {
        let m = &mut c.multipliers[0].1;
        *m = format!("{}", m.parse::<BigRational>().unwrap() * q(2));
    }
    assert_rejected("change one multiplier", &bad, "inconsistent");
    let mut bad = cert;
    if let [Step::Inconsistent(c)] = &mut steps_named(&mut bad, "inconsistent")[..] {
        c.constant = "0".into();
    }
    assert_rejected("claim a zero constant", &bad, "inconsistent");
}

/// A golden-ratio substitution: a transient start type 0 → 1; the class {1, 2} with
/// 1 → 1 + 2, 2 → 1 (ρ = (1 + √5)/2); a downstream class {3} (3 → 3) reached from 2.
fn golden() -> lacuna::certificate::RatioStep {
    let m = vec![
        vec![(1, 1)],
        vec![(1, 1), (2, 1)],
        vec![(1, 1), (3, 1)],
        vec![(3, 1)],
    ];
    ratio_step(&m, &[2, 1, 3, 0], &[(0, 1)]).expect("analyses")
}

fn ratio_certificate(step: lacuna::certificate::RatioStep) -> Certificate {
    let mut cert = Certificate::new("matrix");
    cert.steps.push(Step::LimitRatio(step));
    cert
}

#[test]
fn irrational_perron_roots_are_certified() {
    let step = golden();
    let RatioClaim::Limit(p) = &step.claim else {
        panic!("covered: {:?}", step.claim)
    };
    assert_eq!(p.rho.poly, ["-1", "-1", "1"]);
    assert_eq!(p.ratio.len(), 2, "R is irrational here");
    let cert = ratio_certificate(step.clone());
    assert_proved("golden", &cert);
    // Nudge the interval past ρ ≈ 1.618: it no longer isolates the root.
    let nudge = |lo: &str, hi: &str| {
        let mut s = step.clone();
        if let RatioClaim::Limit(p) = &mut s.claim {
            (p.rho.lo, p.rho.hi) = (lo.into(), hi.into());
        }
        ratio_certificate(s)
    };
    assert_rejected("interval beyond ρ", &nudge("13/8", "2"), "limit-ratio");
    assert_rejected(
        "interval holding both roots",
        &nudge("-1", "2"),
        "limit-ratio",
    );
    let mut s = step.clone();
    if let RatioClaim::Limit(p) = &mut s.claim {
        p.ratio[1] = format!(
            "{}",
            p.ratio[1].parse::<BigRational>().unwrap() * BigRational::from_integer(2.into())
        );
    }
    assert_rejected("wrong limit", &ratio_certificate(s), "limit-ratio");
    let mut s = step.clone();
    if let RatioClaim::Limit(p) = &mut s.claim {
        p.left_vector[0].1[0] = "7".into();
    }
    assert_rejected("wrong eigenvector", &ratio_certificate(s), "limit-ratio");
    let mut s = step;
    s.matrix[2][0].1 = 2;
    assert_rejected("flip a matrix entry", &ratio_certificate(s), "limit-ratio");
}

#[test]
fn flipped_matrix_entries_are_rejected_against_the_closure() {
    let mut cert = face_certificate("triangle-C2");
    if let [Step::LimitRatio(r)] = &mut steps_named(&mut cert, "limit-ratio")[..] {
        r.matrix[1][0].1 += 1;
    }
    assert_rejected("flip a matrix entry", &cert, "limit-ratio");
}

#[test]
fn uncovered_cases_are_said_plainly() {
    // Two classes of radius 2 below the start: not covered by v1.
    let shared = ratio_step(
        &[vec![(1, 1), (2, 1)], vec![(1, 2)], vec![(2, 2)]],
        &[2, 2, 2],
        &[(0, 1)],
    )
    .expect("analyses");
    // A periodic dominant class: 0 ⇄ 1 with two arcs each way.
    let periodic = ratio_step(&[vec![(1, 2)], vec![(0, 2)]], &[2, 0], &[(0, 1)]).expect("analyses");
    for (what, step) in [("shared radius", shared), ("periodic", periodic)] {
        assert!(
            matches!(step.claim, RatioClaim::NotCovered { .. }),
            "{what}"
        );
        let report = check(&ratio_certificate(step));
        let r = report.step("limit-ratio").expect("reported");
        assert_eq!(r.outcome, Outcome::NotCovered, "{what}: {}", r.message);
        assert!(r.message.contains("NOT certified"), "{what}: {}", r.message);
        assert!(!report.all_proved() && !report.failed(), "{what}");
    }
}

#[test]
fn wrong_versions_are_rejected() {
    let mut cert = face_certificate("F0");
    cert.version = 99;
    assert_rejected("version 99", &cert, "header");
    assert!(check_json("{").failed());
}

fn edge() -> impl Strategy<Value = EdgeType> {
    (
        prop_oneof![Just(EdgeKind::B), Just(EdgeKind::C)],
        2u32..=3,
        prop_oneof![4 => Just(1u32), 1 => Just(2u32)],
    )
        .prop_map(|(k, n, d)| EdgeType::new(k, n).delayed(d))
}

fn param() -> impl Strategy<Value = EdgeType> {
    prop_oneof![Just(EdgeKind::B), Just(EdgeKind::C)].prop_map(|k| EdgeType::new(k, 2))
}

fn face() -> impl Strategy<Value = Face> {
    (
        proptest::collection::vec(edge(), 1..=4),
        (param(), param(), param()),
        prop_oneof![
            Just(Algorithm::a1()),
            Just(Algorithm::a2()),
            Just(Algorithm::a3())
        ],
        prop_oneof![3 => Just(1u32), 1 => Just(2u32)],
    )
        .prop_map(|(boundary, (ea, el, ec), algorithm, delay)| Face {
            boundary,
            params: Params { ea, el, ec },
            algorithm,
            delay,
        })
}

/// One semantic change per kind; each one must be caught by the named step.
fn mutate(cert: &mut Certificate, which: usize) -> &'static str {
    let n_steps = cert.steps.len();
    match (which % 4, &mut cert.steps[(which % 4).min(n_steps - 1)]) {
        (0, Step::Closure(c)) if c.types[0].subfaces[0].origins.len() >= 2 => {
            c.types[0].subfaces[0].origins.rotate_left(1);
            "closure"
        }
        (1, Step::SolutionSpace(s)) if !s.system.rows.is_empty() => {
            let rhs = s.system.rows[0]
                .rhs
                .parse::<BigRational>()
                .expect("rational");
            s.system.rows[0].rhs = (rhs + BigRational::from_integer(1.into())).to_string();
            // Consistency may survive a new right-hand side only if the row is all zero.
            if s.system.rows[0].terms.is_empty() {
                return "none";
            }
            "solution-space"
        }
        (2 | 3, Step::LimitRatio(r)) => {
            r.contribution_halves[0] += 1;
            "limit-ratio"
        }
        _ => "none",
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 32, ..ProptestConfig::default() })]

    #[test]
    fn random_faces_certify_and_mutations_fail(f in face(), which in 0usize..4) {
        let limits = Limits { max_types: 60, max_boundary: 12, ..Limits::default() };
        let Ok(ts) = lacuna::close_or_error(std::slice::from_ref(&f), &limits) else {
            return Ok(()); // no spoke or a runaway: nothing to certify
        };
        let Ok(cert) = certificate_for(&f.to_string(), &ts, GenOptions::default()) else {
            return Ok(());
        };
        let report = check(&cert);
        prop_assert!(!report.failed(), "{f}:\n{}", report.to_text());
        for s in &report.steps {
            let covered = s.outcome == Outcome::Proved || s.step == "limit-ratio";
            prop_assert!(covered, "{f}: {}", s.message);
        }
        let mut bad = cert;
        let step = mutate(&mut bad, which);
        if step != "none" {
            let report = check(&bad);
            let rejected = report.steps.iter().any(|s| s.step == step && s.outcome == Outcome::Failed);
            prop_assert!(rejected, "{f}: mutation of {step} not caught:\n{}", report.to_text());
        }
    }
}
