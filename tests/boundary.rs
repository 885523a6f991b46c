//! The boundary dimension of `lacuna measure --json` (`boundary_dimension`), against values
//! derived by hand and published (`src/analysis/automata/boundary.rs`, THEORY §12).

mod common;
use common::lacuna;

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
