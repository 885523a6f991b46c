//! Soundness, round two (issue #28): a certificate proves its claim and nothing else, its
//! printed claim cannot be forged by the names it carries, and `check` answers every small
//! certificate within a bounded cost. Each defect of the issue is a named regression here.

mod common;
use common::{assert_proved, lacuna, volume_certificate};
use lacuna::certificate::{certificate_for, certificate_for_volumes, Certificate, Claim, Step};
use lacuna::checker::{check, Outcome};
use lacuna::topology::volume::VolumeClosure;
use lacuna::{constraint::GenOptions, topology::Limits};
use proptest::prelude::*;

/// The closed type set of the given start faces (notation or library names), in the canonical
/// breadth-first order.
fn closed(starts: &[&str]) -> lacuna::topology::TypeSet {
    let faces: Vec<_> = starts
        .iter()
        .flat_map(|s| lacuna::input::load_input(s).expect("loads").faces())
        .collect();
    lacuna::topology::close_or_error(&faces, &Limits::default()).expect("closes")
}

/// The honest certificate of `family` (F0 then the square's closed family), with the claim cut
/// back to the first `keep` start faces: the closure and system steps still list the union.
fn union_with_claim_of_first(family: &[&str], keep: usize) -> Certificate {
    let ts = closed(family);
    let mut cert = certificate_for("forged", &ts, GenOptions::default()).expect("certifiable");
    if let Claim::Faces(f) = &mut cert.claim {
        f.faces.truncate(keep);
    }
    cert
}

fn step_failed_with(cert: &Certificate, step: &str, needle: &str) {
    let report = check(cert);
    let s = report.step(step).expect("the step is reported");
    assert_eq!(s.outcome, Outcome::Failed, "{}", report.to_text());
    assert!(s.message.contains(needle), "{}", report.to_text());
    assert!(!report.all_proved());
}

#[test]
fn types_never_reached_from_the_claim_are_refused() {
    // The forgery of the issue: F0 closes on its one type; square-B2's two types are closed
    // under subdivision but never reached from F0. The union is honest for the claim
    // [F0, square-B2]: proved as it stands.
    let honest = union_with_claim_of_first(&["F0", "square-B2"], 2);
    assert_proved("F0 and square-B2", &honest);
    let Some(Step::Closure(c)) = honest.steps.first() else {
        panic!("a closure first")
    };
    assert_eq!(c.types.len(), 3, "F0's type and the square's two");
    // The same steps for the claim F0 alone: types 1 and 2 are not reached.
    let forged = union_with_claim_of_first(&["F0", "square-B2"], 1);
    step_failed_with(
        &forged,
        "closure",
        "not reached from the claim's start faces",
    );
    // No verdict about F0 comes out of it: no proved rank, no proved ratio.
    let report = check(&forged);
    assert!(report
        .steps
        .iter()
        .all(|s| s.outcome == Outcome::Failed || s.step != "closure"));
    assert!(report.claims().iter().all(|c| !c.contains("3 face types")));
}

#[test]
fn types_numbered_out_of_breadth_first_order_are_refused() {
    // F0 then the square: swap the square's two types (1 ↔ 2) and renumber every reference.
    // Every type is still reached and every subdivision still holds; only the numbering differs
    // from the canonical breadth-first closure, which fixes it so that two certificates of one
    // claim print the same verdicts.
    let mut cert = union_with_claim_of_first(&["F0", "square-B2"], 2);
    let Some(Step::Closure(c)) = cert.steps.first_mut() else {
        panic!("a closure first")
    };
    c.types.swap(1, 2);
    for t in &mut c.types {
        for s in &mut t.subfaces {
            s.type_index = match s.type_index {
                1 => 2,
                2 => 1,
                x => x,
            };
        }
    }
    step_failed_with(&cert, "closure", "start faces must be types 0, 1");
}

/// The closed volume types of `names`, certified with counts to level 2.
fn volume_union(names: &[&str], keep: usize) -> Certificate {
    let volumes: Vec<_> = names
        .iter()
        .flat_map(|n| {
            let (_, v) = lacuna::input::load_volumes(n)
                .expect("loads")
                .expect("volume");
            v.volume_list()
        })
        .collect();
    let VolumeClosure::Closed(set) = VolumeClosure::of(&volumes, &Limits::default()).expect("ok")
    else {
        panic!("closes")
    };
    let assembly = lacuna::topology::volume::VolumeAssembly {
        volumes: volumes.clone(),
        shared: Vec::new(),
    };
    let mut cert = certificate_for_volumes("forged", &set, 2, &assembly).expect("certifiable");
    if let Claim::Volumes(v) = &mut cert.claim {
        v.volumes.truncate(keep);
    }
    cert
}

#[test]
fn volume_types_never_reached_from_the_claim_are_refused() {
    // cube-B2 and tetrahedron-B2 share no volume type: the union is honest for both starts.
    let honest = volume_union(&["cube-B2", "tetrahedron-B2"], 2);
    assert_proved("cube and tetrahedron", &honest);
    // For the cube alone the tetrahedron's types are not reached (the counts listed are the
    // union's and would fail too; the closure is refused first, for the right reason).
    let forged = volume_union(&["cube-B2", "tetrahedron-B2"], 1);
    // Whether the first foreign type is met as a child numbered too far or as a type left over,
    // the closure is refused for not being the claim's breadth-first closure.
    step_failed_with(&forged, "volume-closure", "canonical breadth-first closure");
    // The honest certificate of the cube alone still checks.
    assert_proved("cube-B2", &volume_certificate("cube-B2"));
}

#[test]
fn hostile_names_are_printed_escaped() {
    // A state name that ends the claim line and prints a fake "proved" line, and one that
    // reverses the text after it (U+202E), in an otherwise honest automaton certificate.
    let mut cert = common::automaton_certificate("sierpinski-triangle");
    let fake = "t\n       proved  step 0 (solution-space): the forged verdict";
    if let Claim::Automaton(a) = &mut cert.claim {
        a.states[0].name = fake.into();
        a.operators[0].name = "ab\u{202e}lieF\u{200b}\u{7}".into();
    }
    let report = check(&cert);
    let text = report.to_text();
    // Every line of the report starts with its own tag: no line begins with a forged one.
    for line in text.lines() {
        let tag = line.trim_start().split("  ").next().unwrap_or("");
        assert!(
            ["claim", "proved", "verdict", "FAILED", "PARTIAL"].contains(&tag),
            "{text}"
        );
    }
    let proved = text
        .lines()
        .filter(|l| l.trim_start().starts_with("proved"))
        .count();
    assert!(!text.contains("the forged verdict\n"), "{text}");
    assert_eq!(proved, report.steps.len(), "{text}");
    // The hidden characters are shown as escapes, in the claim and the JSON alike.
    assert!(text.contains(r"t\u{a}       proved  step 0"), "{text}");
    assert!(text.contains(r"ab\u{202e}lieF\u{200b}\u{7}"), "{text}");
    for c in ['\u{202e}', '\u{200b}', '\u{7}'] {
        assert!(!text.contains(c), "{text}");
        assert!(!report.to_json().to_string().contains(c));
    }
    // A backslash is doubled, so an escape cannot be forged by spelling it out.
    assert_eq!(lacuna::checker::escape(r"a\u{a}"), r"a\\u{a}");
    assert_eq!(lacuna::checker::escape("plain – text ρ"), "plain – text ρ");
}

/// A chain of cycles: a cycle of each length in `lengths`, every arc of weight `w`, the first
/// type of each cycle feeding the first of the next; contributions 1/2, 1, 3/2 in turn. Every
/// cycle has radius `w` (its block is `w` times a cyclic permutation) and period its length, so
/// all are dominant and the period is the lcm of the lengths.
fn chain_of_cycles(w: u64, lengths: &[usize]) -> (Vec<Vec<(usize, u64)>>, Vec<u64>) {
    let (mut m, mut halves): (Vec<Vec<(usize, u64)>>, Vec<u64>) = (Vec::new(), Vec::new());
    let mut previous: Option<usize> = None;
    for &len in lengths {
        let first = m.len();
        if let Some(p) = previous {
            m[p].push((first, 1));
        }
        for i in 0..len {
            let next = if i + 1 == len { first } else { first + i + 1 };
            m.push(vec![(next, w)]);
            halves.push(i as u64 % 3 + 1);
        }
        previous = Some(first);
    }
    (m, halves)
}

/// The honest certificate of cycles of lengths 4, 5, 7 of weight 5 in a chain, made once for
/// the tests that use it (lacuna's producer takes seconds on it in a debug build).
fn cycles_4_5_7() -> Certificate {
    static CERT: std::sync::OnceLock<Certificate> = std::sync::OnceLock::new();
    CERT.get_or_init(|| {
        let (m, h) = chain_of_cycles(5, &[4, 5, 7]);
        lacuna::certificate::certificate_for_substitution("cycles", &m, &h, &[(0, 1)]).unwrap()
    })
    .clone()
}

#[test]
fn an_honest_certificate_of_a_long_period_checks_within_the_default_budget() {
    // Cycles of lengths 4, 5, 7 of weight 5 in a chain: ρ = 5 on each, P = lcm(4, 5, 7) = 140,
    // d = 16 + 1. Before the residues were computed in integers this took 7.5 s in a release
    // build (the gcds of counts of 5^(140·17) ≈ 2^5500); it now takes 0.1 s there.
    let cert = cycles_4_5_7();
    let Some(Step::LimitRatio(r)) = cert.steps.first() else {
        panic!("a ratio step")
    };
    assert_eq!(r.period, 140, "lcm(4, 5, 7)");
    assert_eq!(r.points.len(), 140);
    assert_proved("cycles 4, 5, 7", &cert);
    // A forgery that is right for every residue but the last costs no more than the honest
    // certificate before it is rejected.
    let mut forged = cert.clone();
    if let Some(Step::LimitRatio(r)) = forged.steps.first_mut() {
        let last = r.points.last_mut().unwrap();
        last.value = vec!["1/7".into()];
    }
    let report = check(&forged);
    assert!(report.failed(), "{}", report.to_text());
    assert!(
        report.to_text().contains("residue 139"),
        "{}",
        report.to_text()
    );
}

#[test]
fn a_small_budget_refuses_for_cost_and_never_as_a_verdict() {
    // The same honest certificate with a budget of 10⁵ word operations: refused (E0501, the
    // flag named), neither proved nor failed; through the command line, exit 2.
    let cert = cycles_4_5_7();
    let budget = lacuna::checker::Budget {
        work: 100_000,
        ..Default::default()
    };
    let report = lacuna::checker::check_with(&cert, budget);
    assert!(report.refused() && !report.failed() && !report.all_proved());
    let text = report.to_text();
    assert!(text.contains("REFUSED") && text.contains("E0501"), "{text}");
    assert!(text.contains("--max-work"), "{text}");
    let dir = std::env::temp_dir().join(format!("lacuna-soundness-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("cycles.json");
    std::fs::write(&file, cert.to_json()).unwrap();
    let path = file.to_string_lossy().to_string();
    let (code, out, _) = lacuna(&["check", &path, "--max-work", "100000"]);
    assert_eq!(code, 2, "{out}");
    assert!(out.contains("REFUSED"), "{out}");
    let (code, out, _) = lacuna(&["check", &path]);
    assert_eq!(code, 0, "{out}");
    // P·d = 140·17 = 2380 levels of counts, refused by --max-levels 1000 before any count.
    let (code, out, _) = lacuna(&["check", &path, "--max-levels", "1000"]);
    assert_eq!(code, 2, "{out}");
    assert!(
        out.contains("2380") && out.contains("--max-levels"),
        "{out}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn oversized_volume_inputs_are_refused_before_the_work() {
    // The two inputs of the issue: the truncated tetrahedron with B64 edges under a delay of 64
    // (its delayed sub-volume has a face for every spoke of every face: 4·3·64 + 4·6·64 edges'
    // worth, far above --max-boundary 256), and a 64-prism of B64 edges under V1: its level-1
    // surface has (2·64 + 4·64)·64 = 24 576 sub-edges, above --max-boundary × --max-subedges =
    // 256·64 (and its system about 1.25·10⁸ unknowns, above --max-unknowns, were it built).
    // Both: E0501, exit 2, the flag named.
    let (code, _, err) = lacuna(&[
        "verify",
        "truncated-tetrahedron B64 | B64 B64 B64 | A1 | B64 B64 | V2 | 64",
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("E0501") && err.contains("--max-boundary"),
        "{err}"
    );
    let (code, _, err) = lacuna(&["verify", "prism-64 B64 | B2 B2 B2 | A1 | B2 B2 | V1"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("E0501") && err.contains("24576"), "{err}");
}

/// A library face or a random short face of B2/C2/B3 edges under A1 or A2.
fn family() -> impl Strategy<Value = String> {
    let edge = prop::sample::select(vec!["B2", "C2", "B3"]);
    let algorithm = prop::sample::select(vec!["A1", "A2"]);
    (prop::collection::vec(edge, 3..=5), algorithm)
        .prop_map(|(b, a)| format!("{} | B2 B2 B2 | {a}", b.join(" ")))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 12, ..ProptestConfig::default() })]

    /// An honest closure with another closed family appended (types renumbered after it, the
    /// system of the union): the claim still names only the first family, so the checker must
    /// reject it, whatever the families are.
    #[test]
    fn appended_closed_families_are_rejected(a in family(), b in family()) {
        let first = closed(&[&a]);
        let union = closed(&[&a, &b]);
        prop_assume!(union.types.len() > first.types.len());
        let mut cert = certificate_for("appended", &union, GenOptions::default()).unwrap();
        if let Claim::Faces(f) = &mut cert.claim {
            f.faces.truncate(1);
        }
        let report = check(&cert);
        prop_assert!(!report.all_proved(), "{}", report.to_text());
        let s = report.step("closure").unwrap();
        prop_assert_eq!(s.outcome, Outcome::Failed);
        prop_assert!(s.message.contains("canonical") || s.message.contains("breadth-first"),
            "{}", report.to_text());
    }
}

#[test]
fn an_explored_family_too_costly_to_measure_is_refused_before_the_work() {
    // Boundaries of length ≤ 2 over the default edges B2, C2: 2 + 3 = 5 necklaces (B2, C2,
    // B2 B2, B2 C2, C2 C2) times 2³ = 8 choices of E: 40 faces; at level 6 the holes property
    // would measure about 40·4⁶ = 163 840 cells (a minute of work): refused at once, naming the
    // flag; level 2 (40·16 = 640) is within the default.
    let (code, _, err) = lacuna(&[
        "explore",
        "--max-length",
        "2",
        "--properties",
        "holes",
        "--holes-level",
        "6",
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("E0501") && err.contains("163840") && err.contains("--max-holes-cells"),
        "{err}"
    );
}

#[test]
fn a_degenerate_face_is_not_drawn_without_a_word() {
    // `B2 B2 | B2 C2 B2 | A1` (issue #36): a two-edge face with two spokes whose lacuna sides
    // are Cantor edges C2, segments between the same two points — a lacuna of zero width on
    // every solution. `verify` states it as a forced collapse; `render` checks the chosen point
    // exactly at level 1 before any output (the lacuna's control polygon, its two chords, has
    // area 0) and refuses it as forced: E1013, exit 1, nothing written.
    let (code, out, _) = lacuna(&["verify", "B2 B2 | B2 C2 B2 | A1"]);
    assert_eq!(code, 1, "{out}");
    assert!(
        out.contains("FORCED COLLAPSE: T0: its lacuna has two sides"),
        "{out}"
    );
    let dir = std::env::temp_dir().join(format!("lacuna-digon-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for flag in ["--svg", "--png", "--json-out"] {
        let out = dir.join("flat.out");
        let path = out.to_string_lossy().to_string();
        let (code, _, err) = lacuna(&[
            "render",
            "B2 B2 | B2 C2 B2 | A1",
            "--level",
            "1",
            flag,
            &path,
        ]);
        assert_eq!(code, 1, "{flag}: {err}");
        assert!(err.contains("E1013"), "{flag}: {err}");
        assert!(!out.exists(), "{flag}: a picture was written");
    }
    // The digon of Bézier sides is not forced flat: its default placement bulges the two lacuna
    // sides into a lens, and every level to 3 is drawn, checked, and measured as verified.
    for level in ["1", "2", "3"] {
        let out = dir.join(format!("digon-{level}.svg"));
        let path = out.to_string_lossy().to_string();
        let (code, _, err) = lacuna(&[
            "render",
            "B2 B2 | B2 B2 B2 | A1",
            "--level",
            level,
            "--svg",
            &path,
        ]);
        assert_eq!(code, 0, "level {level}: {err}");
        assert!(out.exists());
    }
    let (code, out, err) = lacuna(&["measure", "B2 B2 | B2 B2 B2 | A1", "--level", "2"]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains("verdict: VERIFIED"), "{out}");
    std::fs::remove_dir_all(&dir).ok();
}

/// Every Cantor edge `{"kind": "C", "n": …}` of a JSON value set to `n`.
fn cantor_edges_to(v: &mut serde_json::Value, n: u64) {
    match v {
        serde_json::Value::Object(o) => {
            if o.get("kind").and_then(|k| k.as_str()) == Some("C") && o.contains_key("n") {
                o.insert("n".into(), n.into());
            }
            o.values_mut().for_each(|x| cantor_edges_to(x, n));
        }
        serde_json::Value::Array(a) => a.iter_mut().for_each(|x| cantor_edges_to(x, n)),
        _ => {}
    }
}

#[test]
fn a_small_volume_certificate_of_long_edges_is_refused_before_its_surface_is_built() {
    // cube-C2's certificate with every Cantor edge C20000: the cube's level-1 surface alone would
    // have 6 faces · 4 edges · 4·20 000 = 1 920 000 sides (a 4.7 KB certificate of this kind took
    // 23 s and 1.5 GB before it was rejected). Refused for cost by --max-sides (400 000) before
    // anything is subdivided.
    let cert = volume_certificate("cube-C2");
    let mut json: serde_json::Value = serde_json::from_str(&cert.to_json()).unwrap();
    cantor_edges_to(&mut json, 20_000);
    let text = json.to_string();
    assert!(text.len() < 100_000);
    let start = std::time::Instant::now();
    let report = lacuna::checker::check_json(&text);
    assert!(report.refused(), "{}", report.to_text());
    assert!(
        report.to_text().contains("--max-sides"),
        "{}",
        report.to_text()
    );
    // A guard against a runaway (the refusal comes before the work), not a speed measurement.
    assert!(start.elapsed() < std::time::Duration::from_secs(20));
}
