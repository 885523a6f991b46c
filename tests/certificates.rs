//! Certificates and the independent checker (issue #5): the checker's isolation, the committed
//! `proofs/`, round trips, mutations that must be rejected (each naming its step), and random
//! faces.
//!
//! `proofs/*.json` are regenerated and compared byte for byte; after an intended change rewrite
//! them with `LACUNA_BLESS=1 cargo test --test certificates`.

use lacuna::certificate::{certificate_for, certificate_for_system};
use lacuna::certificate::{Certificate, Claim, Step};
use lacuna::checker::{check, check_json, Outcome};
use lacuna::{
    constraint::GenOptions, topology::EdgeKind, topology::EdgeType, topology::Face,
    topology::Limits,
};
use num_rational::BigRational;
use proptest::prelude::*;

mod common;
use common::{
    assert_proved, assert_rejected, automaton_certificate, face_certificate, steps_named,
    volume_certificate_with_system,
};

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
const AUTOMATON_FIXTURES: [&str; 32] = [
    "de-casteljau-edge",
    "chaikin-known",
    "spec-edge",
    "spec-edge-incidence",
    "half-tangent-edge",
    "bspline-quadratic",
    "quad-patch",
    "de-casteljau-cubic",
    "bspline-quadratic-4",
    "bspline-cubic",
    "quad-patch-3d",
    "sierpinski-triangle",
    "cantor-set",
    "kite-dart",
    "penrose-robinson",
    // Seed 002: the Sierpinski carpet and the gasket family (issue #37).
    "sierpinski-carpet",
    "lemniscate-fractal",
    "rose-fractal",
    "gasket-3",
    "gasket-4",
    "gasket-5",
    "gasket-6",
    "gasket-7",
    "gasket-8",
    // Production rules (issue #17), compiled to automata.
    "quadric-koch",
    "koch",
    "sierpinski-arrowhead",
    "heighway-dragon",
    "pythagoras-tree",
    "self-seeding-square",
    "vegetation",
    "random-tree",
];

/// Volumes and assemblies of volumes (THEORY §10): the closure of volume types and the counts to
/// level 3.
const VOLUME_FIXTURES: &[&str] = &[
    "cube-B2",
    "tetrahedron-B2",
    "cube-C2",
    "truncated-tetrahedron",
    "two-cubes",
];

#[test]
fn every_library_entry_has_a_proof() {
    for (name, text) in lacuna::input::library() {
        if VOLUME_FIXTURES.contains(name) {
            assert!(
                lacuna::input::is_volume_text(text),
                "{name} is not a volume"
            );
            continue;
        }
        assert!(
            FACE_FIXTURES.contains(name) || AUTOMATON_FIXTURES.contains(name),
            "library entry {name} has no certificate in proofs/: add it to the lists above and bless"
        );
    }
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
    all.push((
        "src/certificate/format.rs",
        &["std", "serde", "serde_json"][..],
    ));
    // The format's parts, beside it in format/: plain data too, reaching each other through
    // `super::` (the format module) only.
    let parts: Vec<String> = std::fs::read_dir(format!("{dir}/src/certificate/format"))
        .map(|d| {
            d.map(|e| {
                format!(
                    "src/certificate/format/{}",
                    e.expect("readable").file_name().to_string_lossy()
                )
            })
            .filter(|f| f.ends_with(".rs"))
            .collect()
        })
        .unwrap_or_default();
    for f in &parts {
        all.push((f.as_str(), &["std", "serde", "serde_json", "super::"][..]));
    }
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
        )
        .chain(
            VOLUME_FIXTURES
                .iter()
                .map(|n| (*n, volume_certificate_with_system(n))),
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
        // Every entry, one face or an assembly with its gluing: its complex's cells, components
        // and holes too.
        let expected = [
            "closure",
            "solution-space",
            "degeneracy",
            "limit-ratio",
            "face-homology",
        ];
        assert_eq!(names, expected, "{name}");
        assert_proved(name, &cert);
    }
    for name in AUTOMATON_FIXTURES {
        assert_proved(name, &automaton_certificate(name));
    }
}

#[test]
fn f0_ratio_is_one_third() {
    let cert = face_certificate("F0");
    let Some(Step::LimitRatio(r)) = cert.steps.iter().find(|s| matches!(s, Step::LimitRatio(_)))
    else {
        panic!("no ratio step")
    };
    // THEORY §5: one type, 6 copies, contribution 5/2: R = (5/2)/(5/2 + 5) = 1/3.
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
fn linear_system(s: &lacuna::certificate::System) -> lacuna::constraint::LinearSystem {
    let q = |x: &str| x.parse::<BigRational>().expect("rational");
    lacuna::constraint::LinearSystem::from_equations(
        s.unknowns,
        s.rows.iter().map(|r| lacuna::constraint::Equation {
            terms: r.terms.iter().map(|(v, c)| (*v, q(c))).collect(),
            rhs: q(&r.rhs),
        }),
    )
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
    sys.push(&lacuna::constraint::Equation {
        terms: vec![(s.free[0], one.clone())],
        rhs: BigRational::from_integer(0.into()),
    });
    let solution = lacuna::constraint::solve(&sys);
    let Step::SolutionSpace(mut forged) =
        lacuna::certificate::solution_step("forged", &sys, &solution)
    else {
        panic!("the forged system is consistent");
    };
    assert_eq!(forged.dof + 1, s.dof, "the added row is not implied");
    forged.system.recipe = s.system.recipe.clone();
    *s = forged;
    assert_not_the_closures("add a row that is not implied", &c);
    // As the claim of its own certificate (a system claim), the forged system is proved.
    let mut forged = solution_of(&mut c).clone();
    forged.system.recipe = None;
    let mut alone = Certificate::new(
        "forged",
        lacuna::certificate::Claim::System(forged.system.clone()),
    );
    alone.steps.push(Step::SolutionSpace(forged));
    let report = check(&alone);
    assert!(report.all_proved(), "{}", report.to_text());
    assert!(report.to_text().contains("the claim's system"));
    // Another claim (Bézier degree, Cantor ratio) for the same system, or permuted unknown
    // names.
    let mut c = base.clone();
    if let lacuna::certificate::Claim::Faces(f) = &mut c.claim {
        f.degree = 3;
    }
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
    if let lacuna::certificate::Claim::Faces(f) = &mut c.claim {
        f.cantor_gap = "1/2".into();
    }
    assert_not_the_closures("Cantor gap 1/2 instead of 1", &c);
    // A face certificate whose system has no recipe is not tied to its closure: rejected.
    let c = edit(&|s| s.system.recipe = None);
    assert_rejected("no recipe after a closure", &c, "solution-space");
}

#[test]
fn inconsistent_systems_are_certified_and_mutations_rejected() {
    // x0 + x1 = 1, x1 + x2 = 1, x0 − x2 = 1 (the first minus the second gives x0 − x2 = 0), x3 = 5.
    let q = |n: i64| BigRational::from_integer(n.into());
    let row = |terms: &[(usize, i64)], rhs: i64| lacuna::constraint::Equation {
        terms: terms.iter().map(|&(v, c)| (v, q(c))).collect(),
        rhs: q(rhs),
    };
    let sys = lacuna::constraint::LinearSystem::from_equations(
        4,
        [
            row(&[(3, 1)], 5),
            row(&[(0, 1), (1, 1)], 1),
            row(&[(1, 1), (2, 1)], 1),
            row(&[(0, 1), (2, -1)], 1),
        ],
    );
    let solution = lacuna::constraint::solve(&sys);
    assert!(matches!(
        solution,
        lacuna::constraint::Solution::Inconsistent(_)
    ));
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

#[test]
fn wrong_versions_are_rejected() {
    let mut cert = face_certificate("F0");
    cert.version = 99;
    assert_rejected("version 99", &cert, "header");
    assert!(check_json("{").failed());
    // Files of versions 1 to 12 (other step forms: version 2 had no recipe, version 3 no claim,
    // version 4 no attractor steps, version 5 no solid-homology step nor shared faces, version
    // 6 no neighbour-map witnesses nor degeneracy step, version 7 no volume-solution-space
    // step, version 8 no solid-recurrence step, version 9 no level-one step, version 10 no
    // gluing of an assembly's faces, version 11 no boundary-dimension step, version 12 no
    // multiplicity step) are refused by their version, not by a parse error.
    let current = format!("\"version\":{}", lacuna::certificate::VERSION);
    for old in [
        "1", "2", "3", "4", "5", "6", "7", "8", "9", "10", "11", "12",
    ] {
        let json =
            face_certificate("F0")
                .to_json()
                .replacen(&current, &format!("\"version\":{old}"), 1);
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

fn face() -> impl Strategy<Value = Face> {
    common::strategies::face(
        common::strategies::edge(2..=3, prop_oneof![4 => Just(1u32), 1 => Just(2u32)]),
        1..=4,
        prop_oneof![Just(EdgeKind::B), Just(EdgeKind::C)].prop_map(|k| EdgeType::new(k, 2)),
        common::strategies::builtin_algorithm(),
        prop_oneof![3 => Just(1u32), 1 => Just(2u32)],
    )
}

/// One semantic change per kind; each one must be caught by the named step.
fn mutate(cert: &mut Certificate, which: usize) -> &'static str {
    // The closure, the system, the degeneracy step and the limit ratio (a face-homology step
    // may follow: not mutated here, see tests/volume_certificates.rs).
    let names = ["closure", "solution-space", "degeneracy", "limit-ratio"];
    let wanted = names[which % 4];
    let Some(step) = cert.steps.iter_mut().find(|s| s.name() == wanted) else {
        return "none";
    };
    match step {
        Step::Closure(c) if c.types[0].subfaces[0].origins.len() >= 2 => {
            c.types[0].subfaces[0].origins.rotate_left(1);
            "closure"
        }
        Step::SolutionSpace(s) if !s.system.rows.is_empty() => {
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
        // A flat face listed, or unlisted: either way the lists differ from the derived ones.
        Step::Degeneracy(d) => {
            match d.flat_faces.pop() {
                Some(_) => {}
                None => d.flat_faces.push(0),
            }
            "degeneracy"
        }
        Step::LimitRatio(r) => {
            r.exists = !r.exists;
            "limit-ratio"
        }
        _ => "none",
    }
}

/// A faces certificate of a notation, as `verify --certificate` writes it.
fn notation_certificate(text: &str) -> Certificate {
    let f = Face::parse(text).expect("a face");
    let ts = lacuna::topology::close_or_error(std::slice::from_ref(&f), &Limits::default())
        .expect("closes");
    certificate_for(text, &ts, GenOptions::default()).expect("certifiable")
}

fn degeneracy_of(cert: &mut Certificate) -> &mut lacuna::certificate::DegeneracyStep {
    cert.steps
        .iter_mut()
        .find_map(|s| match s {
            Step::Degeneracy(d) => Some(d),
            _ => None,
        })
        .expect("a degeneracy step")
}

#[test]
fn forced_collapses_are_certified_and_forgeries_rejected() {
    // `C2 | B2 B2 B2 | A1`: one Cantor edge from a corner back to itself. The face state has
    // m = Σ (m_e − 1) = 2 − 1 = 1 control point, so every column of every sub-face operator is
    // the single unknown that the barycentric row sets to 1: every corner of the level-1
    // complex is the same point. All of type 0's corners form one class, joined by pairs.
    let mut loop_ = notation_certificate("C2 | B2 B2 B2 | A1");
    assert_proved("C2 loop", &loop_);
    let d = degeneracy_of(&mut loop_).clone();
    assert!(!d.coincide.is_empty() && d.coincide.iter().all(|p| p[0] == 0));
    let report = check(&loop_);
    let v = report.step("degeneracy").unwrap().verdict.clone().unwrap();
    assert!(v.starts_with("FORCED COLLAPSE"), "{v}");
    // Drop a pair: that collapse would go unlisted.
    let mut bad = loop_.clone();
    degeneracy_of(&mut bad).coincide.pop();
    assert_rejected("a pair dropped", &bad, "degeneracy");
    // A pair naming one corner twice is not a pair of distinct corners.
    let mut bad = loop_.clone();
    let [t, k, p, _, _] = d.coincide[0];
    degeneracy_of(&mut bad).coincide.push([t, k, p, k, p]);
    assert_rejected("one corner twice", &bad, "degeneracy");
    // A corner that does not exist.
    let mut bad = loop_.clone();
    degeneracy_of(&mut bad).coincide.push([t, k, 999, k, p]);
    assert_rejected("no such corner", &bad, "degeneracy");

    // `B2 B2 | B2 B2 B2 | A1` (the digon of issue #36): the corners are free, nothing collapses;
    // claiming that two of its distinct corners coincide must fail.
    let mut digon = notation_certificate("B2 B2 | B2 B2 B2 | A1");
    assert_proved("digon", &digon);
    assert!(degeneracy_of(&mut digon).coincide.is_empty());
    let v = check(&digon)
        .step("degeneracy")
        .unwrap()
        .verdict
        .clone()
        .unwrap();
    assert!(v.starts_with("no forced collapse"), "{v}");
    let mut bad = digon.clone();
    degeneracy_of(&mut bad).coincide.push([0, 0, 0, 0, 1]);
    assert_rejected("an invented collapse", &bad, "degeneracy");

    // Flat cells: two Cantor edges enclose no area; a two-spoke lacuna with `El = C2` neither.
    let mut flat = notation_certificate("C2 C2 | B2 B2 B2 | A1");
    assert_proved("Cantor digon", &flat);
    assert_eq!(degeneracy_of(&mut flat).flat_faces, vec![0]);
    degeneracy_of(&mut flat).flat_faces.clear();
    assert_rejected("the flat face dropped", &flat, "degeneracy");
    let mut lens = notation_certificate("B2 B2 | B2 C2 B2 | A1");
    assert_proved("Cantor lacuna", &lens);
    assert_eq!(degeneracy_of(&mut lens).flat_lacunas, vec![0]);
    degeneracy_of(&mut lens).flat_lacunas.clear();
    assert_rejected("the flat lacuna dropped", &lens, "degeneracy");
    // Without the solution space the step has nothing to stand on.
    let mut alone = notation_certificate("B2 B2 | B2 B2 B2 | A1");
    alone.steps.retain(|s| s.name() != "solution-space");
    let report = check(&alone);
    assert!(!report.all_proved(), "{}", report.to_text());
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 32, ..ProptestConfig::default() })]

    #[test]
    fn random_faces_certify_and_mutations_fail(f in face(), which in 0usize..4) {
        let limits = Limits { max_types: 60, max_boundary: 12, ..Limits::default() };
        let Ok(ts) = lacuna::topology::close_or_error(std::slice::from_ref(&f), &limits) else {
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

fn level_one_of(cert: &mut Certificate) -> &mut lacuna::certificate::LevelOneStep {
    cert.steps
        .iter_mut()
        .find_map(|s| match s {
            Step::LevelOne(l) => Some(l),
            _ => None,
        })
        .expect("a level-one step")
}

/// The certificate `measure --certificate` writes for library entry `name` at the default
/// choice of parameters.
fn placement_certificate(name: &str) -> Certificate {
    let input = lacuna::input::load_input(name).expect("a library entry");
    let inst =
        lacuna::geometry::instantiate(&input, &lacuna::geometry::InstantiateOptions::default())
            .expect("instantiates");
    lacuna::measure::placement_certificate(&inst).expect("certifiable")
}

/// Each frame's coordinates mapped by `f`.
fn map_frames(cert: &mut Certificate, f: impl Fn(&BigRational, usize) -> BigRational) {
    for frame in &mut level_one_of(cert).frames {
        for p in frame.iter_mut() {
            for (i, c) in p.iter_mut().enumerate() {
                let v: BigRational = c.parse().unwrap();
                *c = f(&v, i).to_string();
            }
        }
    }
}

#[test]
fn the_chosen_point_is_certified_and_forgeries_rejected() {
    for name in ["F0", "two-quads", "delayed-B2-C2"] {
        let cert = placement_certificate(name);
        assert_proved(name, &cert);
    }
    let cert = placement_certificate("F0");
    let step = {
        let mut c = cert.clone();
        level_one_of(&mut c).clone()
    };
    // F0's one type has 6 sub-faces (every spoke of its 6 corners) and one central lacuna.
    assert_eq!((step.sub_faces, step.lacunas), (6, 1));
    let smallest: BigRational = step.smallest_area.parse().unwrap();
    let four = BigRational::from_integer(4.into());
    // By hand: every control point of a cell is Σ_r x_r·F_r with Σ_r x_r = 1 (each column of a
    // sub-face operator is barycentric), so translating every frame by (3/7, −5) translates
    // every cell, and the areas stay; doubling every frame doubles every control point, and the
    // areas are multiplied by 4.
    let mut moved = cert.clone();
    let shift = [
        BigRational::new(3.into(), 7.into()),
        BigRational::from_integer((-5).into()),
    ];
    map_frames(&mut moved, |v, i| v + &shift[i]);
    assert_proved("frames translated", &moved);
    let mut doubled = cert.clone();
    map_frames(&mut doubled, |v, _| v * BigRational::from_integer(2.into()));
    assert_rejected("frames doubled, area kept", &doubled, "level-one");
    level_one_of(&mut doubled).smallest_area = (&smallest * &four).to_string();
    assert_proved("frames doubled, area ×4", &doubled);
    // A mirrored frame turns clockwise: its own area is negative.
    let mut mirrored = cert.clone();
    map_frames(&mut mirrored, |v, i| if i == 0 { -v } else { v.clone() });
    assert_rejected("a mirrored frame", &mirrored, "level-one");
    // Counts, points and parameters that are not the closure's or the space's.
    let mut bad = cert.clone();
    level_one_of(&mut bad).sub_faces += 1;
    assert_rejected("a sub-face too many", &bad, "level-one");
    let mut bad = cert.clone();
    level_one_of(&mut bad).frames[0].pop();
    assert_rejected("a frame point missing", &bad, "level-one");
    let mut bad = cert.clone();
    level_one_of(&mut bad).parameters.pop();
    assert_rejected("a parameter missing", &bad, "level-one");
    // A smallest area that is not the smallest: half of it.
    let mut bad = cert.clone();
    level_one_of(&mut bad).smallest_area =
        (&smallest / BigRational::from_integer(2.into())).to_string();
    assert_rejected("half the smallest area", &bad, "level-one");
    // (Another point of the space is no forgery by itself: the claim may hold there too, e.g. with
    // parameter 0 of F0 set to 1000, whose sub-faces keep positive area and the same smallest.)
    // Without the solution space the step has nothing to stand on.
    let mut alone = cert.clone();
    alone.steps.retain(|s| s.name() != "solution-space");
    assert!(!check(&alone).all_proved());
}

fn face_homology_of(cert: &Certificate) -> Option<Vec<lacuna::certificate::FaceRow>> {
    cert.steps.iter().find_map(|s| match s {
        Step::FaceHomology(h) => Some(h.rows.clone()),
        _ => None,
    })
}

#[test]
fn an_assembly_certifies_its_glued_complex_and_forgeries_fail() {
    // The two quads of `two-quads` glued along one B2 edge. Level 0 by hand: 2 cells,
    // 4 + 4 − 1 = 7 edges, 4 + 4 − 2 = 6 corners, χ = 1, one component, no hole.
    let cert = face_certificate("two-quads");
    assert_proved("two-quads", &cert);
    let Claim::Faces(claim) = &cert.claim else {
        panic!("a faces claim")
    };
    assert_eq!(claim.glue.len(), 1);
    let rows = face_homology_of(&cert).expect("a face-homology step");
    let r0 = &rows[0];
    assert_eq!(
        (
            r0.faces,
            r0.edges,
            r0.corners,
            r0.euler,
            r0.components,
            r0.holes
        ),
        (2, 7, 6, 1, 1, 0)
    );
    // Every level against an independent derivation: measure's exact holes (centre lacunas and
    // half gaps, THEORY §5 accounting, no cell complex) and components.
    let input = lacuna::input::load_input("two-quads").expect("a library entry");
    let inst =
        lacuna::geometry::instantiate(&input, &lacuna::geometry::InstantiateOptions::default())
            .expect("instantiates");
    let exact = lacuna::measure::exact_topology(&inst, 4).expect("exact topology");
    for (row, ex) in rows.iter().zip(&exact) {
        assert_eq!(
            row.holes.to_string(),
            ex.holes.to_string(),
            "level {}",
            row.level
        );
        assert_eq!(row.components, ex.components, "level {}", row.level);
        assert_eq!(
            row.faces.to_string(),
            ex.faces.to_string(),
            "level {}",
            row.level
        );
    }

    // The gluing dropped: two components, the rows no longer hold.
    let mut apart = cert.clone();
    if let Claim::Faces(f) = &mut apart.claim {
        f.glue.clear();
    }
    assert_rejected("the gluing dropped", &apart, "face-homology");
    // A B2 side glued to a C2 side: refused as a whole, before any step.
    let mut wrong = cert.clone();
    if let Claim::Faces(f) = &mut wrong.claim {
        let face = &f.faces[f.glue[0].b[0]];
        let side = face
            .boundary
            .iter()
            .position(|e| e.kind == lacuna::certificate::Kind::C)
            .expect("a C2 side");
        f.glue[0].b[1] = side;
    }
    let report = check(&wrong);
    assert!(!report.all_proved(), "{}", report.to_text());
    assert!(
        report.to_text().contains("different edge types"),
        "{}",
        report.to_text()
    );
    // A side glued twice.
    let mut twice = cert.clone();
    if let Claim::Faces(f) = &mut twice.claim {
        let g = f.glue[0];
        f.glue.push(g);
    }
    assert!(check(&twice).to_text().contains("glued twice"));
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 16, ..ProptestConfig::default() })]

    /// A face glued to a copy of itself along an undelayed `Cn` side: by Mayer–Vietoris (b2 = 0,
    /// the glued edge a union of n^l segments at level l, both copies connected) the glued
    /// complex has 2·holes + n^l − 1 holes at level l: the half-notches over each gap close into
    /// one hole. The rows of the assembly's certificate (checked) must say so.
    #[test]
    fn random_faces_glued_along_a_cantor_side(f in face()) {
        let Some(side) = f.boundary.iter().position(|e| {
            e.kind == lacuna::topology::EdgeKind::C && !e.is_delayed()
        }) else {
            return Ok(());
        };
        let limits = Limits { max_types: 60, max_boundary: 12, ..Limits::default() };
        let Ok(one_ts) = lacuna::topology::close_or_error(std::slice::from_ref(&f), &limits) else {
            return Ok(());
        };
        let Ok(one) = certificate_for("one", &one_ts, GenOptions::default()) else {
            return Ok(());
        };
        let two_ts = lacuna::topology::close_or_error(&[f.clone(), f.clone()], &limits)
            .expect("closes as one face does");
        let (_, r) = f.canonical();
        let m = f.boundary.len();
        let canon = (side + m - r % m) % m;
        let two = lacuna::certificate::certificate_for_assembly(
            "two",
            &two_ts,
            &[[(0, canon), (1, canon)]],
            GenOptions::default(),
        )
        .expect("certifiable as one face is");
        let report = check(&two);
        prop_assert!(report.all_proved(), "{f}:\n{}", report.to_text());
        let n = u64::from(f.boundary[side].n);
        // Without a step (components not derived within the cell bound) there is nothing to
        // compare.
        let (Some(a), Some(b)) = (face_homology_of(&one), face_homology_of(&two)) else {
            return Ok(());
        };
        for (x, y) in a.iter().zip(&b) {
            if x.components != 1 {
                return Ok(());
            }
            let l = u32::try_from(x.level).expect("small");
            prop_assert_eq!(y.components, 1, "{} level {}", f, l);
            prop_assert_eq!(y.holes, 2 * x.holes + n.pow(l) - 1, "{} level {}", f, l);
        }
    }
}
