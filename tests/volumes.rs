//! Volumes (THEORY §10) through the command line: closure, counts, ratio, verify, errors.

mod common;
use common::lacuna;

#[test]
fn the_cube_closes_with_three_volume_types() {
    let (code, out, _) = lacuna(&["closure", "cube-B2"]);
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("closed, 3 volume types"), "{out}");
    // The worked example: the cube's 8 children of one type with 13 faces, 19 corners, 30 edges.
    assert!(out.contains("13 faces, 19 corners, 30 edges"), "{out}");
    assert!(out.contains("→ 8×V1"), "{out}");
}

#[test]
fn counts_of_the_tetrahedron_by_hand() {
    // Each of the 4 corners of the tetrahedron (degree 3) raises one corner-type volume W3 with
    // 19 corners (16 of degree 3, 3 of degree 4), and W4 has 25 (20 and 5): 1, 4, 4·19 = 76,
    // 4·(16·19 + 3·25) = 1516 cells.
    let (code, out, err) = lacuna(&["counts", "tetrahedron-B2", "--levels", "3", "--json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let cells: Vec<&str> = v["counts"]
        .as_array()
        .unwrap()
        .iter()
        .map(|l| l["cells"].as_str().unwrap())
        .collect();
    assert_eq!(cells, ["1", "4", "76", "1516"]);
    // Lacunas: the tetrahedron contributes 1 + 4/2 = 3.
    assert_eq!(v["counts"][1]["lacunas"], "3");
}

#[test]
fn the_limit_ratio_of_the_cube_by_hand() {
    // The dominant class {W3, W4} has M = [[16, 3], [20, 5]], ρ = 20 (λ² − 21λ + 20 = 0), left
    // eigenvector u = (5, 1). Cells grow as 20^i·(5 + 1); lacunas add u·c = 5·15/2 + 19/2 = 47
    // per unit, summed over the levels below: 47/19. R = (47/19) / (47/19 + 6) = 47/161.
    let (code, out, err) = lacuna(&["ratio", "cube-B2", "--json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["exact"], "47/161", "{out}");
    assert_eq!(v["exists"], true);
}

#[test]
fn verify_a_volume_in_notation() {
    let (code, out, err) = lacuna(&["verify", "octahedron B2 | B2 B2 B2 | A1 | B2 B2 | V2"]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("every sub-volume's boundary is a sphere"),
        "{out}"
    );
    assert!(out.contains("verdict: VERIFIED"), "{out}");
}

#[test]
fn bad_volume_notation_is_a_coded_error() {
    let (code, _, err) = lacuna(&["closure", "cube B2 | B2 B2 B2 | A1 | B2 B2 | V9"]);
    assert_eq!(code, 2);
    assert!(err.contains("E1205"), "{err}");
    assert!(err.contains("V1 or V2"), "{err}");
    // A volume where only faces are read is refused by name.
    let (code, _, err) = lacuna(&["measure", "cube-B2", "--level", "1"]);
    assert_eq!(code, 2);
    assert!(err.contains("this is a volume"), "{err}");
}

#[test]
fn solve_a_volume() {
    let (code, out, err) = lacuna(&["solve", "tetrahedron-B2", "--degree", "1", "--json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["consistent"], true);
    assert_eq!(v["degeneracy_checked"], true);
    assert_eq!(v["degenerate"].as_array().unwrap().len(), 0);
    // A state per volume type (the tetrahedron, W3 and W4), beside the face states.
    let states = v["dof_by_state"].as_object().unwrap();
    assert!(
        ["V0", "V1", "V2"].iter().all(|s| states.contains_key(*s)),
        "{states:?}"
    );
}
