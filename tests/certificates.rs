//! Certificates and the independent checker (issue #5): the checker's isolation, the committed
//! `proofs/`, round trips, mutations that must be rejected (each naming its step), and random
//! faces.
//!
//! `proofs/*.json` are regenerated and compared byte for byte; after an intended change rewrite
//! them with `LACUNA_BLESS=1 cargo test --test certificates`.

use lacuna::certificate::{Certificate, RadiusWitness, RatioStep, Step};
use lacuna::certify::{
    certificate_for, certificate_for_automaton, certificate_for_system, ratio_step,
};
use lacuna::checker::{check, check_json, Outcome};
use lacuna::{Algorithm, EdgeKind, EdgeType, Face, GenOptions, Limits, Params};
use num_rational::BigRational;
use proptest::prelude::*;

const FACE_FIXTURES: [&str; 8] = [
    "F0",
    "cycle-sqrt17",
    "shared-radius-pentagons",
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

/// The checker's files: `src/checker/mod.rs` and every submodule beside it.
fn checker_files(dir: &str) -> Vec<String> {
    let mut files: Vec<String> = std::fs::read_dir(format!("{dir}/src/checker"))
        .expect("src/checker/ exists")
        .map(|e| {
            format!(
                "src/checker/{}",
                e.expect("readable").file_name().to_string_lossy()
            )
        })
        .filter(|f| f.ends_with(".rs"))
        .collect();
    files.sort();
    assert!(files.len() >= 2 && files.contains(&"src/checker/mod.rs".to_string()));
    files
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
    // Submodules may reach their siblings through `super::` (which is `crate::checker`); the
    // module root may not (its `super` is lacuna).
    let with_super: Vec<&str> = allowed_roots.iter().copied().chain(["super::"]).collect();
    // The module root reaches its submodules through `self::`.
    let with_self: Vec<&str> = allowed_roots.iter().copied().chain(["self::"]).collect();
    let files = checker_files(dir);
    let mut all: Vec<(&str, &[&str])> = files
        .iter()
        .map(|f| {
            let roots = match f.ends_with("/mod.rs") {
                true => &with_self[..],
                false => &with_super[..],
            };
            (f.as_str(), roots)
        })
        .collect();
    all.push(("src/certificate.rs", &["std", "serde", "serde_json"][..]));
    for (file, roots) in all {
        let text = std::fs::read_to_string(format!("{dir}/{file}")).expect("readable");
        let mut bad_paths = vec![
            "lacuna::",
            "::lacuna",
            "extern crate",
            "#[path",
            "super::super",
        ];
        if !roots.contains(&"super::") {
            bad_paths.push("super::");
        }
        for (i, line) in text.lines().enumerate() {
            let code = line.split("//").next().unwrap_or("");
            for bad in &bad_paths {
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
    // SPEC §5: one type, 6 copies, contribution 5/2: R = (5/2)/(5/2 + 5) = 1/3.
    assert!(r.exists);
    assert_eq!(r.points.len(), 1);
    assert_eq!(r.points[0].value, ["1/3"]);
    assert_eq!(r.points[0].real.poly, ["-1", "3"]);
    assert_eq!(r.rho.poly, ["-6", "1"]);
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

/// Asserts that the solution-space step fails because its system is not the closure's.
fn assert_not_the_closures(what: &str, cert: &Certificate) {
    assert_rejected(what, cert, "solution-space");
    let report = check(cert);
    let step = report
        .step("solution-space")
        .expect("a solution-space step");
    assert!(
        step.message
            .contains("the system does not match the closure"),
        "{what}: {}",
        step.message
    );
}

fn solution_of(cert: &mut Certificate) -> &mut lacuna::certificate::SolutionStep {
    let found = cert.steps.iter_mut().find_map(|s| match s {
        Step::SolutionSpace(s) => Some(s),
        _ => None,
    });
    found.expect("a solution-space step")
}

/// The certificate's system as lacuna's `LinearSystem`.
fn linear_system(s: &lacuna::certificate::System) -> lacuna::LinearSystem {
    let q = |x: &str| x.parse::<BigRational>().expect("rational");
    lacuna::LinearSystem {
        unknowns: s.unknowns,
        rows: s
            .rows
            .iter()
            .map(|r| lacuna::Equation {
                terms: r.terms.iter().map(|(v, c)| (*v, q(c))).collect(),
                rhs: q(&r.rhs),
            })
            .collect(),
    }
}

#[test]
fn systems_that_are_not_the_closures_are_rejected() {
    let base = face_certificate("F0");
    let edit = |f: &dyn Fn(&mut lacuna::certificate::SolutionStep)| {
        let mut cert = base.clone();
        f(solution_of(&mut cert));
        cert
    };
    let one = BigRational::from_integer(1.into());
    // One coefficient changed (the first row with a term).
    let c = edit(&|s| {
        let row = s.system.rows.iter_mut().find(|r| !r.terms.is_empty());
        let term = &mut row.expect("a row with a term").terms[0].1;
        *term = (term.parse::<BigRational>().unwrap() + &one).to_string();
    });
    assert_not_the_closures("change one coefficient", &c);
    // One row dropped: the last one that is not a pivot row, so the rest of the step (particular,
    // basis, rank witness) stays valid for the smaller system and only the tie can object.
    let c = edit(&|s| {
        let pivot_rows: Vec<usize> = s.pivots.iter().map(|p| p.0).collect();
        let last = (0..s.system.rows.len())
            .rev()
            .find(|i| !pivot_rows.contains(i))
            .expect("a non-pivot row");
        s.system.rows.remove(last);
    });
    assert_not_the_closures("drop a row", &c);
    // One row added that is implied (the sum of rows 0 and 1): the old checks all hold.
    let c = edit(&|s| {
        let (a, b) = (s.system.rows[0].clone(), s.system.rows[1].clone());
        let q = |x: &str| x.parse::<BigRational>().unwrap();
        s.system.rows.push(lacuna::certificate::Row {
            terms: a.terms.into_iter().chain(b.terms).collect(),
            rhs: (q(&a.rhs) + q(&b.rhs)).to_string(),
        });
    });
    assert_not_the_closures("add an implied row", &c);
    // One row added that is not implied (the first free unknown is 0), with the solution space
    // recomputed so that the step is consistent on its own: without the closure it is proved
    // ("system as given"), with it it is rejected.
    let mut c = base.clone();
    let s = solution_of(&mut c);
    let mut sys = linear_system(&s.system);
    sys.rows.push(lacuna::Equation {
        terms: vec![(s.free[0], one.clone())],
        rhs: BigRational::from_integer(0.into()),
    });
    let solution = lacuna::solve(&sys);
    let Step::SolutionSpace(mut forged) = lacuna::certify::solution_step("forged", &sys, &solution)
    else {
        panic!("the forged system is consistent");
    };
    assert_eq!(forged.dof + 1, s.dof, "the added row is not implied");
    forged.system.recipe = s.system.recipe.clone();
    *s = forged;
    assert_not_the_closures("add a row that is not implied", &c);
    let mut alone = c.clone();
    alone.steps.retain(|s| s.name() == "solution-space");
    solution_of(&mut alone).system.recipe = None;
    let report = check(&alone);
    assert!(report.all_proved(), "{}", report.to_text());
    assert!(report.to_text().contains("system as given"));
    // A wrong recipe: another Bézier degree, another Cantor ratio, permuted unknown names.
    let c = edit(&|s| s.system.recipe.as_mut().expect("a recipe").degree = 3);
    assert_not_the_closures("degree 3", &c);
    let c = edit(&|s| {
        s.system
            .recipe
            .as_mut()
            .expect("a recipe")
            .unknowns
            .swap(0, 1)
    });
    assert_not_the_closures("two unknown names swapped", &c);
    let c = edit(&|s| {
        s.system
            .recipe
            .as_mut()
            .expect("a recipe")
            .unknowns
            .reverse()
    });
    assert_not_the_closures("unknown names reversed", &c);
    let mut c = face_certificate("triangle-C2");
    solution_of(&mut c)
        .system
        .recipe
        .as_mut()
        .expect("a recipe")
        .cantor_gap = "1/2".into();
    assert_not_the_closures("Cantor gap 1/2 instead of 1", &c);
    // A face certificate whose system has no recipe is not tied to its closure: rejected.
    let c = edit(&|s| s.system.recipe = None);
    assert_rejected("no recipe after a closure", &c, "solution-space");
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
fn golden() -> RatioStep {
    let m = vec![
        vec![(1, 1)],
        vec![(1, 1), (2, 1)],
        vec![(1, 1), (3, 1)],
        vec![(3, 1)],
    ];
    ratio_step(&m, &[2, 1, 3, 0], &[(0, 1)]).expect("analyses")
}

fn ratio_certificate(step: RatioStep) -> Certificate {
    let mut cert = Certificate::new("matrix");
    cert.steps.push(Step::LimitRatio(step));
    cert
}

/// The ratio step of `matrix` (rows `(sub-face type, count)`), contributions in halves, one
/// start face of type 0; asserts that it checks.
fn proved_step(what: &str, matrix: &[Vec<(usize, u64)>], halves: &[u64]) -> RatioStep {
    let step = ratio_step(matrix, halves, &[(0, 1)]).expect("analyses");
    assert_proved(what, &ratio_certificate(step.clone()));
    step
}

fn values(step: &RatioStep) -> Vec<String> {
    step.points.iter().map(|p| p.value.join(" ")).collect()
}

fn bump(s: &mut String) {
    *s = (s.parse::<BigRational>().unwrap() + BigRational::new(1.into(), 7.into())).to_string();
}

#[test]
fn irrational_perron_roots_are_certified() {
    let step = golden();
    assert_eq!(step.rho.poly, ["-1", "-1", "1"]);
    assert_eq!(step.points[0].value.len(), 2, "R is irrational here");
    assert_eq!(step.points[0].real.poly.len(), 3, "R is quadratic");
    let cert = ratio_certificate(step.clone());
    assert_proved("golden", &cert);
    // Nudge the interval past ρ ≈ 1.618: it no longer isolates the root.
    let nudge = |lo: &str, hi: &str| {
        let mut s = step.clone();
        (s.rho.lo, s.rho.hi) = (lo.into(), hi.into());
        ratio_certificate(s)
    };
    assert_rejected("interval beyond ρ", &nudge("13/8", "2"), "limit-ratio");
    assert_rejected(
        "interval holding both roots",
        &nudge("-1", "2"),
        "limit-ratio",
    );
    let mut s = step.clone();
    s.points[0].value[1] = format!(
        "{}",
        s.points[0].value[1].parse::<BigRational>().unwrap() * BigRational::from_integer(2.into())
    );
    assert_rejected("wrong limit", &ratio_certificate(s), "limit-ratio");
    let mut s = step.clone();
    if let RadiusWitness::Perron(y) = &mut s.classes[1].radius {
        y[1][0] = "7".into();
    }
    assert_rejected("wrong eigenvector", &ratio_certificate(s), "limit-ratio");
    // R's own interval: moved off R (it still isolates a root of nothing there).
    let mut s = step.clone();
    s.points[0].real.lo = s.points[0].real.hi.clone();
    bump(&mut s.points[0].real.hi);
    assert_rejected("interval of R moved", &ratio_certificate(s), "limit-ratio");
    let mut s = step.clone();
    s.points[0].real.poly[0] = "5".into();
    assert_rejected(
        "wrong polynomial of R",
        &ratio_certificate(s),
        "limit-ratio",
    );
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
fn equal_radii_in_a_chain_are_certified() {
    // a → {a, a, b}, b → {b, b}: M = [[2, 1], [0, 2]], two classes of radius 2 in a chain. From
    // one a: a_i = 2^i, b_i = i·2^(i−1), N^C_i = 2^(i−1)(i + 2),
    // N^L_i = c_a(2^i − 1) + c_b((i − 2)·2^(i−1) + 1). Both grow like i·2^i when c_b > 0 (pole
    // orders 2 and 2) and R = c_b/(c_b + 1); with c = (1/2, 1): R = 1/2.
    let m = vec![vec![(0, 2), (1, 1)], vec![(1, 2)]];
    let step = proved_step("chain, c_b = 1", &m, &[1, 2]);
    assert!(step.exists && step.period == 1);
    assert!(step
        .classes
        .iter()
        .all(|c| matches!(c.radius, RadiusWitness::Perron(_))));
    assert_eq!(values(&step), ["1/2"]);
    // c = (3, 0): N^L_i = 3(2^i − 1) is of lower order than N^C_i: R = 0.
    assert_eq!(values(&proved_step("chain, c_b = 0", &m, &[6, 0])), ["0"]);
    // Three classes of radius 2 in a chain a → b → c (pole order 3): N^C_i ~ i²·2^i/8,
    // lacunas only at c: N^L_i ~ c_c·Σ_(j<i) j²·2^j/8 ~ c_c·i²·2^i/8: R = c_c/(c_c + 1) = 1/3
    // with c_c = 1/2.
    let m = vec![vec![(0, 2), (1, 1)], vec![(1, 2), (2, 1)], vec![(2, 2)]];
    assert_eq!(
        values(&proved_step("chain of three", &m, &[0, 0, 1])),
        ["1/3"]
    );
}

#[test]
fn shared_radius_fixture_is_certified() {
    // fixtures/shared-radius-pentagons.txt: two one-type classes P → 5P, P' → 5P', contribution 1
    // each, one start face of each: N^C_i = 2·5^i, N^L_i = 2(5^i − 1)/4, R = (1/2)/(1/2 + 2) = 1/5.
    let cert = face_certificate("shared-radius-pentagons");
    let Some(Step::LimitRatio(r)) = cert.steps.last() else {
        panic!("no ratio step")
    };
    assert_eq!(r.classes.len(), 2);
    assert!(r
        .classes
        .iter()
        .all(|c| matches!(c.radius, RadiusWitness::Perron(_))));
    assert_eq!(values(r), ["1/5"]);
    assert!(check(&cert).all_proved());
}

#[test]
fn periodic_dominant_classes_are_certified() {
    // a → 2b, b → 8a: ρ = 4, period 2. Level 2j: 16^j faces a; level 2j+1: 2·16^j faces b.
    // N^L_(2j) = (16^j − 1)/15·S, S = c_a + 2c_b: R_(2j) → S/(S + 15);
    // N^L_(2j+1) = N^L_(2j) + 16^j·c_a: R_(2j+1) → T/(T + 30), T = 16c_a + 2c_b.
    let m = vec![vec![(1, 2)], vec![(0, 8)]];
    // c = (1, 0): S = 1, T = 16: no limit, limit points 1/16 and 16/46 = 8/23.
    let step = proved_step("periodic, oscillating", &m, &[2, 0]);
    assert!(!step.exists);
    assert_eq!(step.period, 2);
    assert_eq!(values(&step), ["1/16", "8/23"]);
    assert_eq!(step.points[0].decimal, "0.062500000000000000000000000000");
    // c = (1/2, 7/2): S = 15/2, T = 15: both residues give 1/3, the limit exists.
    let step = proved_step("periodic, converging", &m, &[1, 7]);
    assert!(step.exists);
    assert_eq!(values(&step), ["1/3", "1/3"]);
}

#[test]
fn radius_one_is_certified() {
    // a → a: N^C_i = 1, N^L_i = i·c: R = 1 if c > 0, else 0.
    assert_eq!(
        values(&proved_step("a → a, c = 1", &[vec![(0, 1)]], &[2])),
        ["1"]
    );
    assert_eq!(
        values(&proved_step("a → a, c = 0", &[vec![(0, 1)]], &[0])),
        ["0"]
    );
    // a → b → a, c = (1, 0): period 2 at radius 1; N^C = 1, N^L_i = ⌈i/2⌉: R = 1 on both residues.
    let step = proved_step("a ⇄ b", &[vec![(1, 1)], vec![(0, 1)]], &[2, 0]);
    assert!(step.exists && step.period == 2);
    assert_eq!(values(&step), ["1", "1"]);
    // a → {a, b}, b → b, c = (1, 0): N^C_i = i + 1, N^L_i = i: R = 1/2 (two radius-1 classes
    // in a chain and the lacuna type: pole orders 2 and 2).
    let m = vec![vec![(0, 1), (1, 1)], vec![(1, 1)]];
    assert_eq!(values(&proved_step("radius-1 chain", &m, &[2, 0])), ["1/2"]);
    // a → {a, b}, b → 2b, c = (7, 1/2): a (radius 1) feeds b (radius 2); only b matters:
    // R = (1/2)/(1/2 + 2 − 1) = 1/3, a's linear lacunas are negligible.
    let m = vec![vec![(0, 1), (1, 1)], vec![(1, 2)]];
    let step = proved_step("radius 1 feeding 2", &m, &[14, 1]);
    assert_eq!(values(&step), ["1/3"]);
    assert!(matches!(step.classes[0].radius, RadiusWitness::Below(_)));
}

#[test]
fn mutated_limit_claims_are_rejected() {
    let m = vec![vec![(1, 2)], vec![(0, 8)]];
    let oscillating = ratio_step(&m, &[2, 0], &[(0, 1)]).expect("analyses");
    let converging = ratio_step(&m, &[1, 7], &[(0, 1)]).expect("analyses");
    let rejected = |what: &str, step: &RatioStep, edit: &dyn Fn(&mut RatioStep)| {
        let mut s = step.clone();
        edit(&mut s);
        assert_ne!(&s, step, "{what}: the mutation changed nothing");
        assert_rejected(what, &ratio_certificate(s), "limit-ratio");
    };
    rejected("claim a limit that does not exist", &oscillating, &|s| {
        s.exists = true
    });
    rejected("deny a limit that exists", &converging, &|s| {
        s.exists = false
    });
    rejected("nudge a limit point", &oscillating, &|s| {
        bump(&mut s.points[1].value[0])
    });
    rejected("swap the limit points", &oscillating, &|s| {
        s.points.swap(0, 1)
    });
    rejected("claim period 1", &oscillating, &|s| {
        s.period = 1;
        s.points.truncate(1);
    });
    rejected("claim period 4", &converging, &|s| {
        s.period = 4;
        s.points.extend(s.points.clone());
    });
    rejected("claim a class period", &oscillating, &|s| {
        s.classes[0].period = Some(1)
    });
    rejected("nudge the interval of R", &oscillating, &|s| {
        bump(&mut s.points[0].real.lo);
        s.points[0].real.hi = s.points[0].real.lo.clone();
    });
    rejected("wrong decimals", &oscillating, &|s| {
        s.points[0].decimal = "0.062600000000000000000000000000".into()
    });
    rejected("nudge ρ", &oscillating, &|s| {
        s.rho.poly = vec!["-5".into(), "1".into()];
        (s.rho.lo, s.rho.hi) = ("5".into(), "5".into());
    });
    rejected(
        "a dominant class passed off as smaller",
        &converging,
        &|s| s.classes[0].radius = RadiusWitness::Below(vec!["1".into(), "1".into()]),
    );
    // A smaller class's bound is not a Perron vector, nor the other way round.
    let feeding =
        ratio_step(&[vec![(0, 1), (1, 1)], vec![(1, 2)]], &[14, 1], &[(0, 1)]).expect("analyses");
    rejected("a smaller class passed off as dominant", &feeding, &|s| {
        s.classes[0].radius = RadiusWitness::Perron(vec![vec!["1".into()]])
    });
    rejected(
        "a Collatz–Wielandt vector that is not positive",
        &feeding,
        &|s| s.classes[0].radius = RadiusWitness::Below(vec!["0".into()]),
    );
    rejected(
        "the dominant class's witness moved to the other class",
        &feeding,
        &|s| s.classes.swap(0, 1),
    );
}

#[test]
fn wrong_versions_are_rejected() {
    let mut cert = face_certificate("F0");
    cert.version = 99;
    assert_rejected("version 99", &cert, "header");
    assert!(check_json("{").failed());
    // Files of versions 1 and 2 (other step forms: version 2 had no recipe) are refused by their
    // version, not by a parse error.
    for old in ["1", "2"] {
        let json = face_certificate("F0").to_json().replacen(
            "\"version\":3",
            &format!("\"version\":{old}"),
            1,
        );
        let report = check_json(&json);
        assert!(report.failed(), "{}", report.to_text());
        assert!(
            report.steps[0]
                .message
                .contains(&format!("unknown certificate version {old}")),
            "{}",
            report.to_text()
        );
    }
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
        prop_assert!(report.all_proved(), "{f}:\n{}", report.to_text());
        let mut bad = cert;
        let step = mutate(&mut bad, which);
        if step != "none" {
            let report = check(&bad);
            let rejected = report.steps.iter().any(|s| s.step == step && s.outcome == Outcome::Failed);
            prop_assert!(rejected, "{f}: mutation of {step} not caught:\n{}", report.to_text());
        }
    }
}
