//! Every library fixture against the structure derived by hand in its header (and repeated
//! here, with the derivation). Assertion messages name the fixture.

mod common;
use lacuna::{
    input::load_input, topology::close_or_error, topology::counts, topology::Face,
    topology::Limits, topology::TypeSet,
};

fn closed(name: &str) -> TypeSet {
    let input = load_input(name).unwrap_or_else(|e| panic!("fixture {name}: {}", e.render()));
    let ts = close_or_error(&input.faces(), &Limits::default())
        .unwrap_or_else(|e| panic!("fixture {name}: {}", e.render()));
    ts.verify()
        .unwrap_or_else(|e| panic!("fixture {name}: {e}"));
    common::assert_certified(name, &ts);
    ts
}

/// The type index of a face given in notation (any rotation).
fn id(ts: &TypeSet, notation: &str) -> usize {
    let f = Face::parse(notation).unwrap().canonical().0;
    ts.types
        .iter()
        .position(|t| t.face == f)
        .unwrap_or_else(|| panic!("`{notation}` is not a type of the closure"))
}

/// Asserts that type `from` has exactly the given sub-face multiset.
fn rule(ts: &TypeSet, fixture: &str, from: &str, to: &[(&str, usize)]) {
    let t = id(ts, from);
    let mut got: Vec<usize> = ts.types[t].children.clone();
    got.sort_unstable();
    let mut want: Vec<usize> = to
        .iter()
        .flat_map(|(n, k)| std::iter::repeat_n(id(ts, n), *k))
        .collect();
    want.sort_unstable();
    assert_eq!(got, want, "fixture {fixture}: sub-faces of `{from}`");
}

fn strings(v: impl IntoIterator<Item = impl ToString>) -> Vec<String> {
    v.into_iter().map(|x| x.to_string()).collect()
}

#[test]
fn f0_spec_worked_example() {
    let ts = closed("F0");
    assert_eq!(ts.types.len(), 1, "fixture F0");
    rule(
        &ts,
        "F0",
        "C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A1",
        &[("C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A1", 6)],
    );
    let c = counts(&ts, 5);
    assert_eq!(
        strings(c.iter().map(|l| &l.lacunas)),
        ["0", "5/2", "35/2", "215/2", "1295/2", "7775/2"],
        "fixture F0 (THEORY §5)"
    );
    assert_eq!(
        strings(c.iter().map(|l| &l.faces)),
        ["1", "6", "36", "216", "1296", "7776"],
        "fixture F0 (THEORY §5)"
    );
    assert_eq!(
        c[1].ratio.to_string(),
        "5/17",
        "fixture F0: R_1 (THEORY §5)"
    );
}

#[test]
fn square_b2() {
    // Derivation in fixtures/square-B2.txt: square → 4 pentagons, pentagon → 5 pentagons.
    let ts = closed("square-B2");
    assert_eq!(ts.types.len(), 2, "fixture square-B2");
    let p5 = "B2 B2 B2 B2 B2 | B2 B2 B2 | A1";
    rule(&ts, "square-B2", "B2 B2 B2 B2 | B2 B2 B2 | A1", &[(p5, 4)]);
    rule(&ts, "square-B2", p5, &[(p5, 5)]);
    // N^C = 1, 4, 20; N^L = 0, 1, 1 + 4 = 5 (one central lacuna per face and step).
    let c = counts(&ts, 2);
    assert_eq!(strings(c.iter().map(|l| &l.faces)), ["1", "4", "20"]);
    assert_eq!(strings(c.iter().map(|l| &l.lacunas)), ["0", "1", "5"]);
}

#[test]
fn triangle_c2() {
    // A run between two gaps of consecutive C2 edges: `C2 C2 | Ec | Ea El Ea | Ec` = H.
    // H = C2 C2 B2 B2 B2 B2 B2 has 7 spokes: runs (C2,C2) → H, (C2,B2) and (B2,C2) → Q6,
    // four (B2,B2) → P5. Q6 = C2 B2 B2 B2 B2 B2: (C2,B2), (B2,C2) → Q6, four (B2,B2) → P5.
    let ts = closed("triangle-C2");
    let (t, h, q6, p5) = (
        "C2 C2 C2 | B2 B2 B2 | A1",
        "C2 C2 B2 B2 B2 B2 B2 | B2 B2 B2 | A1",
        "C2 B2 B2 B2 B2 B2 | B2 B2 B2 | A1",
        "B2 B2 B2 B2 B2 | B2 B2 B2 | A1",
    );
    assert_eq!(ts.types.len(), 4, "fixture triangle-C2");
    rule(&ts, "triangle-C2", t, &[(h, 3)]);
    rule(&ts, "triangle-C2", h, &[(p5, 4), (q6, 2), (h, 1)]);
    rule(&ts, "triangle-C2", q6, &[(p5, 4), (q6, 2)]);
    rule(&ts, "triangle-C2", p5, &[(p5, 5)]);
    // Contributions 5/2, 2, 3/2, 1 (in halves 5, 4, 3, 2).
    let halves: Vec<u64> = [t, h, q6, p5]
        .iter()
        .map(|f| ts.types[id(&ts, f)].contribution_halves())
        .collect();
    assert_eq!(halves, [5, 4, 3, 2]);
    // Level 2: 12 P5 + 6 Q6 + 3 H = 21 faces; N^L_2 = 5/2 + 3·2 = 17/2.
    // Level 3: 12·5 + 6·6 + 3·7 = 117 faces; N^L_3 = 17/2 + 12·1 + 6·3/2 + 3·2 = 71/2.
    let c = counts(&ts, 3);
    assert_eq!(strings(c.iter().map(|l| &l.faces)), ["1", "3", "21", "117"]);
    assert_eq!(
        strings(c.iter().map(|l| &l.lacunas)),
        ["0", "5/2", "17/2", "71/2"]
    );
    // Classes: {T} and {Q6} transient/self-looping chain ending in {P5}.
    let cl = ts.classes();
    assert_eq!(cl.classes.len(), 4);
    assert_eq!(cl.classes[0].period, None, "the triangle is transient");
}

#[test]
fn delayed_b2_c2() {
    // A3 spokes: the B2 joint and both corners next to C2^2. Runs: B2 (second half) → S4,
    // the C2 piece of C2^2 → U, B2 (first half) → S4. See fixtures/delayed-B2-C2.txt.
    let ts = closed("delayed-B2-C2");
    let (x, s4, u, g6, v7) = (
        "B2 C2^2 | C2 B2 B2 | A3",
        "B2 C2 B2 C2 | C2 B2 B2 | A3",
        "B2 C2 C2 C2 | C2 B2 B2 | A3",
        "B2 C2 B2 C2 B2 C2 | C2 B2 B2 | A3",
        "C2 C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A3",
    );
    assert_eq!(ts.types.len(), 5, "fixture delayed-B2-C2");
    rule(&ts, "delayed-B2-C2", x, &[(s4, 2), (u, 1)]);
    rule(&ts, "delayed-B2-C2", s4, &[(g6, 4)]);
    rule(&ts, "delayed-B2-C2", u, &[(g6, 2), (v7, 2)]);
    rule(&ts, "delayed-B2-C2", v7, &[(g6, 6), (v7, 1)]);
    rule(&ts, "delayed-B2-C2", g6, &[(g6, 6)]);
    // X contributes its central lacuna only: the delayed C2^2 opens no gap yet.
    assert_eq!(ts.types[id(&ts, x)].contribution_halves(), 2);
}

#[test]
fn two_quads_in_both_formats() {
    // Each quad C2 B2 C2 B2 → 4 F0-shaped faces; contribution 1 + 2·1/2 = 2 per quad.
    for name in ["two-quads", "autofrac-two-quads"] {
        let input = load_input(name).unwrap();
        assert_eq!(input.assembly.shared.len(), 1, "fixture {name}");
        let ts = closed(name);
        rule(
            &ts,
            name,
            "C2 B2 C2 B2 | C2 B2 B2 | A1",
            &[("C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A1", 4)],
        );
        let c = counts(&ts, 2);
        assert_eq!(
            strings(c.iter().map(|l| &l.faces)),
            ["2", "8", "48"],
            "fixture {name}"
        );
        // N^L_2 = 2·2 + 8·5/2 = 24.
        assert_eq!(
            strings(c.iter().map(|l| &l.lacunas)),
            ["0", "4", "24"],
            "fixture {name}"
        );
    }
}

#[test]
fn shared_radius_pentagons() {
    // Two pentagons B2^5 differing only in Ec (unused: no gap). A1: the five joints are the
    // spokes; each run `B2 B2` closes with `Ea El Ea = B2 B2 B2` to the same pentagon: each type
    // gives five copies of itself, contribution 1 (the centre). Two classes of radius 5.
    let name = "shared-radius-pentagons";
    let ts = closed(name);
    assert_eq!(ts.types.len(), 2, "fixture {name}");
    for p in [
        "B2 B2 B2 B2 B2 | B2 B2 B2 | A1",
        "B2 B2 B2 B2 B2 | B2 B2 C2 | A1",
    ] {
        rule(&ts, name, p, &[(p, 5)]);
        assert_eq!(
            ts.types[id(&ts, p)].contribution_halves(),
            2,
            "fixture {name}"
        );
    }
    // N^C_i = 2·5^i; N^L_(i+1) = N^L_i + N^C_i·1: 0, 2, 12, 62.
    let c = counts(&ts, 3);
    assert_eq!(
        strings(c.iter().map(|l| &l.faces)),
        ["2", "10", "50", "250"],
        "fixture {name}"
    );
    assert_eq!(
        strings(c.iter().map(|l| &l.lacunas)),
        ["0", "2", "12", "62"],
        "fixture {name}"
    );
}
