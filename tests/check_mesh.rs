//! `lacuna check-mesh` on the meshes `lacuna render` writes (issue #29): the independent checker
//! agrees with the parts and Euler characteristics `render` prints and with the claims file it
//! writes; a truncated file is bad input (exit 2), a flipped triangle a failed check (exit 1)
//! naming its edge.

mod common;
use common::{lacuna, number_after, number_before, s};

fn check_json(args: &[&str]) -> (i32, serde_json::Value) {
    let mut all = vec!["check-mesh"];
    all.extend_from_slice(args);
    all.push("--json");
    let (code, out, err) = lacuna(&all);
    let v = serde_json::from_str(&out).unwrap_or_else(|e| panic!("{all:?}: {e}: {out}{err}"));
    (code, v)
}

#[test]
fn a_face_mesh_checks_with_its_claims() {
    let d = common::scratch("check-mesh-face");
    let (stl, claims) = (d.join("f0.stl"), d.join("f0.json"));
    let (code, out, err) = lacuna(&[
        "render",
        "F0",
        "--level",
        "2",
        "--stl",
        &s(&stl),
        "--claims",
        &s(&claims),
    ]);
    assert_eq!(code, 0, "{out}{err}");
    // render: "… 1 part, … Euler characteristic -24 (exact: 1 component, 13 holes)".
    let euler = number_after(&out, "Euler characteristic");
    let components = number_after(&out, "(exact:");
    let (code, v) = check_json(&[&s(&stl), "--claims", &s(&claims)]);
    assert_eq!(code, 0, "{v:#}");
    assert_eq!(v["passed"], true);
    assert_eq!(v["format"], "stl-binary");
    assert_eq!(v["euler"], euler);
    assert_eq!(v["parts"].as_array().unwrap().len() as i64, components);
    assert_eq!(v["genus"], (2 * components - euler) / 2);
    assert_eq!(v["expectations"].as_array().unwrap().len(), 5, "{v:#}");
    assert!(v["parts"][0]["outward"] == true);
    // The text names each check and the verdict.
    let (code, out, _) = lacuna(&["check-mesh", &s(&stl), "--expect-euler", "-24"]);
    assert_eq!(code, 0);
    assert!(out.contains("closed: every edge has exactly two triangles, opposite directions"));
    assert!(out.contains("manifold: every vertex link is one cycle"));
    assert!(out.contains("candidate pairs tested exactly"));
    assert!(out.contains("verdict: ONE CLOSED ORIENTED MANIFOLD WITHOUT CROSSINGS"));
    // An expectation that differs is a failure (exit 1) that says which.
    let (code, out, _) = lacuna(&["check-mesh", &s(&stl), "--expect-parts", "2"]);
    assert_eq!(code, 1);
    assert!(
        out.contains("expected parts (--expect-parts): 2, found 1 — DIFFERS"),
        "{out}"
    );
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_volume_mesh_checks_as_stl_and_3mf() {
    let d = common::scratch("check-mesh-volume");
    let (stl, mf, claims) = (d.join("c.stl"), d.join("c.3mf"), d.join("c.json"));
    let (code, out, err) = lacuna(&[
        "render",
        "cube-B2",
        "--level",
        "1",
        "--stl",
        &s(&stl),
        "--3mf",
        &s(&mf),
        "--claims",
        &s(&claims),
    ]);
    assert_eq!(code, 0, "{out}{err}");
    // render: "… surface Euler characteristic -8 = 2χ …, 1 surface piece, genus 5".
    let euler = number_after(&out, "surface Euler characteristic");
    let pieces = number_before(&out, "surface piece");
    let genus = number_after(&out, "surface piece, genus");
    for (file, format) in [(&stl, "stl-binary"), (&mf, "3mf")] {
        let (code, v) = check_json(&[&s(file), "--claims", &s(&claims)]);
        assert_eq!(code, 0, "{v:#}");
        assert_eq!(v["format"], format);
        assert_eq!(v["euler"], euler);
        assert_eq!(v["genus"], genus);
        assert_eq!(v["parts"].as_array().unwrap().len() as i64, pieces);
        assert!(v["notes"].as_array().unwrap().is_empty(), "{v:#}");
    }
    // A claim the mesh does not meet: exit 1, naming it.
    let text = std::fs::read_to_string(&claims).unwrap();
    let wrong = text.replace(&format!("\"genus\": {genus}"), "\"genus\": 4");
    assert_ne!(wrong, text);
    let bad = d.join("wrong.json");
    std::fs::write(&bad, wrong).unwrap();
    let (code, out, _) = lacuna(&["check-mesh", &s(&stl), "--claims", &s(&bad)]);
    assert_eq!(code, 1, "{out}");
    assert!(
        out.contains("expected genus (claims): 4, found 5 — DIFFERS"),
        "{out}"
    );
    assert!(
        out.contains("verdict: EXPECTATION FAILED (genus (claims))"),
        "{out}"
    );
    // Not a claims file: bad input.
    let (code, _, err) = lacuna(&["check-mesh", &s(&stl), "--claims", &s(&stl)]);
    assert_eq!(code, 2);
    assert!(
        err.contains("error[E0602]") || err.contains("error[E1504]"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_truncated_stl_is_bad_input_and_a_flipped_triangle_fails_naming_its_edge() {
    let d = common::scratch("check-mesh-broken");
    let stl = d.join("f0.stl");
    let (code, _, err) = lacuna(&["render", "F0", "--level", "1", "--stl", &s(&stl)]);
    assert_eq!(code, 0, "{err}");
    let bytes = std::fs::read(&stl).unwrap();
    // Truncated: exit 2, E1501, never a panic.
    let cut = d.join("cut.stl");
    std::fs::write(&cut, &bytes[..bytes.len() - 7]).unwrap();
    let (code, out, err) = lacuna(&["check-mesh", &s(&cut)]);
    assert_eq!(code, 2, "{out}{err}");
    assert!(err.starts_with("error[E1501]:"), "{err}");
    assert!(err.contains("truncated"), "{err}");
    // Triangle 0 with its corners 1 and 2 swapped: its three edges run the same way as in
    // their other triangles.
    let mut flipped = bytes.clone();
    let (c1, c2) = (84 + 24, 84 + 36);
    let corner1: Vec<u8> = flipped[c1..c1 + 12].to_vec();
    flipped.copy_within(c2..c2 + 12, c1);
    flipped[c2..c2 + 12].copy_from_slice(&corner1);
    let bad = d.join("flipped.stl");
    std::fs::write(&bad, &flipped).unwrap();
    let (code, out, _) = lacuna(&["check-mesh", &s(&bad)]);
    assert_eq!(code, 1, "{out}");
    assert!(
        out.contains("closed: FAILED — 3 × edge run one way twice"),
        "{out}"
    );
    assert!(
        out.contains("is run in the same direction by triangle 0 and"),
        "{out}"
    );
    assert!(out.contains("verdict: FAILED (not closed or not consistently oriented)"));
    let (code, v) = check_json(&[&s(&bad)]);
    assert_eq!(code, 1);
    let closed = &v["checks"]["closed"];
    assert_eq!(closed["count"]["edge run one way twice"], 3);
    let first = &closed["examples"][0];
    assert_eq!(first["vertices"].as_array().unwrap().len(), 2);
    assert_eq!(first["coordinates"].as_array().unwrap().len(), 2);
    assert!(first["triangles"].as_array().unwrap().contains(&0.into()));
    // A file that is not there, and a limit: exit 2.
    let (code, _, err) = lacuna(&["check-mesh", &s(&d.join("none.stl"))]);
    assert_eq!((code, err.starts_with("error[E0601]")), (2, true), "{err}");
    let (code, _, err) = lacuna(&["check-mesh", &s(&stl), "--max-triangles", "10"]);
    assert_eq!(code, 2);
    assert!(
        err.contains("not a verdict") && err.contains("--max-triangles"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn claims_need_a_mesh() {
    let d = common::scratch("check-mesh-claims");
    let c = d.join("c.json");
    let (code, _, err) = lacuna(&[
        "render",
        "F0",
        "--level",
        "1",
        "--svg",
        "-",
        "--claims",
        &s(&c),
    ]);
    assert_eq!(code, 2);
    assert!(err.starts_with("error[E0504]"), "{err}");
    assert!(!c.exists());
    // An automaton's mesh has no exact topology to claim yet.
    let stl = d.join("t.stl");
    let (code, _, err) = lacuna(&[
        "render",
        "sierpinski-triangle",
        "--level",
        "2",
        "--stl",
        &s(&stl),
        "--claims",
        &s(&c),
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("--claims"), "{err}");
    let _ = std::fs::remove_dir_all(&d);
}
