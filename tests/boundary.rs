//! The boundary dimension of `lacuna measure --json` (`boundary_dimension`), against values
//! derived by hand and published (`src/analysis/automata/boundary.rs`, THEORY §12), and its
//! certificate step `boundary-dimension`: proved for the library's tiles, every forgery
//! rejected.

mod common;
use common::{assert_proved, assert_rejected, automaton_certificate, lacuna};
use lacuna::certificate::{BoundaryStep, Certificate, NeighbourMaps, Step};

/// `measure NAME --json`'s `boundary_dimension`, each state's `(name, exact, decimal)`, after
/// checking that the value is labelled an upper bound.
fn boundary(name: &str) -> Vec<(String, String, String)> {
    let (code, out, err) = lacuna(&["measure", name, "--level", "1", "--json"]);
    assert_eq!(code, 0, "{name}: {err}");
    let v: serde_json::Value = serde_json::from_str(&out).expect("JSON");
    let b = &v["boundary_dimension"];
    assert_eq!(b["upper_bound"].as_bool(), Some(true), "{name}: {b}");
    assert!(
        b["note"]
            .as_str()
            .is_some_and(|n| n.contains("upper bound")),
        "{name}: {b}"
    );
    b["states"]
        .as_array()
        .unwrap_or_else(|| panic!("{name}: no states in {b}"))
        .iter()
        .map(|s| {
            let f = |k: &str| s[k].as_str().expect("a string").to_string();
            (f("state"), f("exact"), f("decimal"))
        })
        .collect()
}

#[test]
fn heighway_dragon_boundary_is_two_log2_of_the_root_of_x3_minus_x2_minus_2() {
    // The dragon's boundary (Chang–Zhang; Duvall–Keesling): dimension 2·log₂ λ with λ the real
    // root of λ³ − λ² − 2 = 0, λ = 1.69562076955986…, so 2·log₂ λ = 1.52362708620249…
    // Both maps have ratio 1/√2: σ = 1/2 and u = σ^(s/2) = 2^(−s/2) = 1/λ, and λ³ = λ² + 2
    // reads 1 = u + 2u³: u* is the root of 2u³ + u − 1 (printed monic: x³ + x/2 − 1/2).
    let got = boundary("heighway-dragon");
    assert_eq!(got.len(), 2, "{got:?}");
    for (state, exact, decimal) in &got {
        assert!(
            exact.contains("u = root of x^3 + 1/2*x - 1/2") && exact.contains("σ = 1/2"),
            "heighway-dragon {state}: {exact}"
        );
        assert!(decimal.starts_with("1.5236270862"), "{state}: {decimal}");
    }
}

#[test]
fn robinson_triangles_have_straight_boundaries_of_dimension_one() {
    // penrose-robinson: straight-edged half kite and half dart. Two triangles touch along
    // segments, and a segment is divided by the maps into pieces of ratios whose Mauldin–Williams
    // equation has the root s = 1: exactly 1 for every state.
    let got = boundary("penrose-robinson");
    assert!(!got.is_empty());
    for (state, exact, decimal) in &got {
        assert_eq!(exact, "1", "penrose-robinson {state}");
        assert!(decimal.starts_with("1.000000"), "{state}: {decimal}");
    }
}

#[test]
fn the_fractal_kite_and_dart_have_boundaries_above_one() {
    // Bandt–Gummelt's fractal kite and dart: tiles with fractal boundaries, dimension strictly
    // between 1 and 2 (their area is positive and the similarity dimension is 2).
    let got = boundary("kite-dart");
    assert_eq!(got.len(), 2, "{got:?}");
    for (state, _, decimal) in &got {
        let d: f64 = decimal.parse().expect("a decimal");
        assert!(d > 1.0 && d < 2.0, "kite-dart {state}: {decimal}");
        assert!(
            !decimal.starts_with("1.000"),
            "kite-dart {state}: {decimal}"
        );
    }
}

#[test]
fn the_text_report_has_a_boundary_line() {
    let (code, out, err) = lacuna(&["measure", "heighway-dragon", "--level", "1"]);
    assert_eq!(code, 0, "{err}");
    let line = boundary_line(&out);
    assert!(
        line.contains("left ≤ ") && line.contains("1.5236270862"),
        "{line}"
    );
    assert!(line.contains("upper bound"), "{line}");
}

/// `measure NAME --json`'s `boundary_dimension` when there is no value: only a note.
fn no_boundary(name: &str) -> String {
    let (code, out, err) = lacuna(&["measure", name, "--level", "1", "--json"]);
    assert_eq!(code, 0, "{name}: {err}");
    let v: serde_json::Value = serde_json::from_str(&out).expect("JSON");
    let b = &v["boundary_dimension"];
    assert!(b.get("states").is_none(), "{name}: {b}");
    assert_eq!(
        b.as_object().map(|o| o.len()),
        Some(1),
        "{name}: only a note in {b}"
    );
    b["note"]
        .as_str()
        .unwrap_or_else(|| panic!("{name}: no note in {b}"))
        .to_string()
}

#[test]
fn the_sierpinski_triangle_and_carpet_are_their_own_boundaries() {
    // Similarity dimensions log 3/log 2 and log 8/log 3, both < 2: Lebesgue measure 0, no
    // interior, so each set is its own boundary and no boundary dimension of a tile is reported
    // (the set where their pieces touch has dimension 0 and 1, which is not their boundary).
    for name in ["sierpinski-triangle", "sierpinski-carpet"] {
        let note = no_boundary(name);
        assert!(
            note.starts_with("not a tile: similarity dimension < 2")
                && note.contains("its own boundary"),
            "{name}: {note}"
        );
    }
    let (code, out, err) = lacuna(&["measure", "sierpinski-triangle", "--level", "1"]);
    assert_eq!(code, 0, "{err}");
    let line = boundary_line(&out);
    assert!(
        line.starts_with("boundary dimension: none (not a tile"),
        "{line}"
    );
}

#[test]
fn an_overlapping_system_below_dimension_two_is_not_a_tile() {
    // The lemniscate fractal's pieces coincide (the open-set condition fails), but its
    // similarity dimension, an upper bound of the Hausdorff dimension in any case, is < 2: no
    // interior, no value, and the note says so.
    let note = no_boundary("lemniscate-fractal");
    assert!(
        note.starts_with("not a tile: similarity dimension < 2"),
        "{note}"
    );
}

/// The `boundary dimension: …` line of a text report.
fn boundary_line(out: &str) -> &str {
    out.lines()
        .find(|l| l.starts_with("boundary dimension: "))
        .unwrap_or_else(|| panic!("no boundary line in {out}"))
}

fn boundary_step(cert: &mut Certificate) -> &mut BoundaryStep {
    cert.steps
        .iter_mut()
        .find_map(|s| match s {
            Step::BoundaryDimension(b) => Some(b),
            _ => None,
        })
        .expect("a boundary-dimension step")
}

#[test]
fn the_dragon_s_boundary_is_certified_and_forgeries_fail() {
    // The published value 2·log₂ λ = 1.52362708620249… (λ³ − λ² − 2 = 0), for both states.
    let base = automaton_certificate("heighway-dragon");
    assert_proved("heighway-dragon", &base);
    let names: Vec<&str> = base.steps.iter().map(Step::name).collect();
    assert_eq!(
        names,
        [
            "constraints-hold",
            "contraction",
            "similarity-dimension",
            "boundary-dimension",
            "multiplicity",
            "rule-compilation"
        ]
    );
    let mut c = base.clone();
    let b = boundary_step(&mut c).clone();
    assert_eq!(b.parts.len(), 1);
    let part = &b.parts[0];
    // The part's own neighbour maps are the graph's nodes: the step does not repeat them.
    assert!(part.maps.is_none());
    for s in &part.states {
        assert!(s.decimal.starts_with("1.5236270862"), "{s:?}");
    }
    let report = lacuna::checker::check(&base);
    assert!(
        report
            .claims()
            .iter()
            .any(|l| l.starts_with("boundary dimension left ≤ 1.5236270862")),
        "{}",
        report.to_text()
    );
    let dominant = part.states[0].component.expect("a cycle is reachable");
    // A component of value 0 (the pieces meet in single points there) is reachable too:
    // claiming it as the largest is a lie the product's Sturm count catches.
    let zero = part
        .components
        .iter()
        .position(|x| x.rational.as_deref() == Some("0"))
        .expect("a component of points");
    let mut c = base.clone();
    boundary_step(&mut c).parts[0].states[0] = lacuna::certificate::BoundaryState {
        component: Some(zero),
        decimal: format!("0.{}", "0".repeat(b.digits)),
    };
    assert_rejected("a smaller component claimed", &c, "boundary-dimension");
    let mut c = base.clone();
    boundary_step(&mut c).parts[0].states[0].component = None;
    boundary_step(&mut c).parts[0].states[0].decimal = format!("0.{}", "0".repeat(b.digits));
    assert_rejected("no cycle claimed", &c, "boundary-dimension");
    let mut c = base.clone();
    let d = &mut boundary_step(&mut c).parts[0].states[1].decimal;
    *d = d.replace("1.5236270862", "1.5236270863");
    assert_rejected("a wrong digit", &c, "boundary-dimension");
    let mut c = base.clone();
    let classes = &mut boundary_step(&mut c).parts[0].components[dominant].classes;
    classes.iter_mut().for_each(|x| *x = 0);
    assert_rejected("one class for all nodes", &c, "boundary-dimension");
    // Numbers near 2^64 (found by the certificate_forgery fuzz target): a class number past
    // the nodes, digits out of range — refused, never an overflow.
    let mut c = base.clone();
    boundary_step(&mut c).parts[0].components[dominant].classes[0] = usize::MAX;
    assert_rejected("a class number of 2^64 − 1", &c, "boundary-dimension");
    let mut c = base.clone();
    boundary_step(&mut c).digits = usize::MAX;
    assert_rejected("2^64 − 1 digits", &c, "boundary-dimension");
    let mut c = base.clone();
    boundary_step(&mut c).parts[0].components.remove(zero);
    assert_rejected("a component dropped", &c, "boundary-dimension");
    let mut c = base.clone();
    boundary_step(&mut c).parts[0].components[dominant]
        .nodes
        .pop();
    assert_rejected("a node dropped", &c, "boundary-dimension");
    // u* replaced by the other ends of its polynomial's sign change: 2u³ + u − 1 has its one
    // real root in (1/2, 3/5) (at 1/2: −1/4, at 3/5: 1/50); (3/5, 1) holds none.
    let mut c = base.clone();
    let u = &mut boundary_step(&mut c).parts[0].components[dominant].u;
    u.lo = "3/5".into();
    u.hi = "1".into();
    assert_rejected("an interval without u*", &c, "boundary-dimension");
    let mut c = base.clone();
    let maps = match &c.steps[2] {
        Step::SimilarityDimension(s) => match &s.parts[0].neighbour_maps {
            Some(NeighbourMaps::Holds(h)) => h.clone(),
            other => panic!("neighbour maps expected, got {other:?}"),
        },
        _ => unreachable!(),
    };
    boundary_step(&mut c).parts[0].maps = Some(maps);
    assert_rejected("maps given twice", &c, "boundary-dimension");
    let mut c = base.clone();
    c.steps.remove(2);
    assert_rejected("no similarity step", &c, "boundary-dimension");
}

#[test]
fn straight_edges_are_certified_to_touch_along_sets_of_dimension_one() {
    // Robinson triangles: σ = 1/φ² and u* = 1/φ, both irrational; s = 1 is certified through
    // u*² = σ. gasket-4 (a square cut in four): the step carries its own neighbour maps, since
    // the part's open-set condition is proved by convex sets.
    for name in ["penrose-robinson", "gasket-4"] {
        let base = automaton_certificate(name);
        assert_proved(name, &base);
        let mut c = base.clone();
        let b = boundary_step(&mut c).clone();
        for p in &b.parts {
            for s in &p.states {
                assert!(s.decimal.starts_with("1.000000"), "{name}: {s:?}");
            }
        }
        if name == "penrose-robinson" {
            // The forgeries below on the cheaper gasket (the Robinson check takes seconds).
            continue;
        }
        let one = b.parts[0].states[0].component.expect("reachable");
        for wrong in ["3/2", "2"] {
            let mut c = base.clone();
            boundary_step(&mut c).parts[0].components[one].rational = Some(wrong.into());
            assert_rejected(&format!("{name}: s = {wrong}"), &c, "boundary-dimension");
        }
        {
            assert!(b.parts[0].maps.is_some(), "{name}: the step's own maps");
            let mut c = base.clone();
            let maps = boundary_step(&mut c).parts[0].maps.as_mut().expect("maps");
            let last = maps.maps.pop().expect("a map");
            assert_rejected(&format!("{name}: a map dropped"), &c, "boundary-dimension");
            let mut c = base.clone();
            let maps = boundary_step(&mut c).parts[0].maps.as_mut().expect("maps");
            maps.maps.push(last);
            assert_rejected(
                &format!("{name}: a map listed twice"),
                &c,
                "boundary-dimension",
            );
        }
    }
}

#[test]
fn no_boundary_step_is_written_for_what_is_not_a_tile() {
    // log 3/log 2 < 2: no interior; and the step cannot be moved onto such a claim.
    let tri = automaton_certificate("sierpinski-triangle");
    assert!(tri.steps.iter().all(|s| s.name() != "boundary-dimension"));
    let mut dragon = automaton_certificate("heighway-dragon");
    let step = boundary_step(&mut dragon).clone();
    let mut c = tri.clone();
    c.steps.insert(3, Step::BoundaryDimension(step));
    assert_rejected("a tile's step on a triangle", &c, "boundary-dimension");
}

#[test]
fn verify_prints_and_certifies_the_boundary() {
    let dir = std::env::temp_dir().join(format!("lacuna-boundary-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join("kite-dart.json");
    let p = path.to_str().expect("utf-8");
    let (code, out, err) = lacuna(&["verify", "kite-dart", "--certificate", p]);
    assert_eq!(code, 0, "{err}");
    let line = out
        .lines()
        .find(|l| l.starts_with("boundary dimension (an upper bound, tiles): "))
        .unwrap_or_else(|| panic!("no boundary line in {out}"));
    assert!(line.contains("a ≤ ") && line.contains("b ≤ "), "{line}");
    let (code, out, err) = lacuna(&["check", p]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains("boundary dimension a ≤ 1.26"), "{out}");
    std::fs::remove_dir_all(&dir).ok();
}
