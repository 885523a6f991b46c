//! The `lacuna` binary on fixtures: exit codes, JSON fields scripts rely on, and snapshots of
//! what users see (checked by eye against the hand derivations in tests/fixtures.rs).

mod common;
use common::lacuna;

fn json(args: &[&str]) -> serde_json::Value {
    let (code, out, err) = lacuna(args);
    assert_eq!(code, 0, "{args:?}: {err}");
    serde_json::from_str(&out).unwrap_or_else(|e| panic!("{args:?}: not JSON ({e}): {out}"))
}

#[test]
fn verify_without_argument_reports_f0() {
    let (code, out, _) = lacuna(&["verify"]);
    assert_eq!(code, 0);
    insta::assert_snapshot!("verify_f0", out);
}

#[test]
fn closure_json_has_the_documented_fields() {
    let v = json(&["closure", "C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A1", "--json"]);
    let types = v["types"].as_array().unwrap();
    assert_eq!(types.len(), 1);
    assert_eq!(types[0]["contribution"], "5/2");
    assert_eq!(types[0]["subfaces"].as_array().unwrap().len(), 6);
    assert_eq!(types[0]["face"], types[0]["subfaces"][0]);
}

#[test]
fn counts_json_matches_the_spec_table() {
    let v = json(&[
        "counts",
        "C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A1",
        "--levels",
        "5",
        "--json",
    ]);
    assert_eq!(v["types"], 1);
    let levels = v["levels"].as_array().unwrap();
    let lac: Vec<&str> = levels
        .iter()
        .map(|l| l["lacunas"].as_str().unwrap())
        .collect();
    assert_eq!(lac, ["0", "5/2", "35/2", "215/2", "1295/2", "7775/2"]);
    assert_eq!(levels[5]["faces"], "7776");
    assert_eq!(levels[0]["level"], 0);
}

#[test]
fn counts_of_an_assembly_report_each_face() {
    let v = json(&[
        "counts",
        "fixtures/two-quads.txt",
        "--levels",
        "1",
        "--json",
    ]);
    assert_eq!(v["levels"][1]["faces"], "8");
    assert_eq!(v["per_face"].as_array().unwrap().len(), 2);
    assert_eq!(v["per_face"][0]["levels"][1]["lacunas"], "2");
}

#[test]
fn level_200_counts() {
    let v = json(&["counts", "F0", "--levels", "200", "--json"]);
    let f = v["levels"][200]["faces"].as_str().unwrap();
    // 6^200 has 156 digits (200·log10 6 = 155.6).
    assert_eq!(f.len(), 156);
}

#[test]
fn runaway_exits_one_with_a_witness() {
    let (code, out, _) = lacuna(&[
        "verify",
        "B2 C3 | B2 B2 C3 | {joint}",
        "--max-boundary",
        "30",
    ]);
    assert_eq!(code, 1);
    assert!(out.contains("RUNAWAY"), "{out}");
    assert!(out.contains("witness chain"), "{out}");
}

#[test]
fn parse_error_snapshot() {
    let (code, out, err) = lacuna(&["verify", "C2 B2 X2 B2 | C2 B2 B2 | A1"]);
    assert_eq!(code, 2);
    assert!(out.is_empty());
    insta::assert_snapshot!("error_unknown_edge", err);
}

#[test]
fn assembly_error_snapshot() {
    let dir = std::env::temp_dir().join(format!("lacuna-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("mismatch.txt");
    std::fs::write(&path, "face 0: C2 B2 C2 B2 | C2 B2 B2 | A1\nface 1: C2 B2 C2 B2 | C2 B2 B2 | A1\nface 0 edge 0 ~ face 1 edge 1\n").unwrap();
    let (code, _, err) = lacuna(&["verify", path.to_str().unwrap()]);
    assert_eq!(code, 2);
    let err = err.replace(path.to_str().unwrap(), "mismatch.txt");
    insta::assert_snapshot!("error_shared_edge_mismatch", err);
}

#[test]
fn errors_in_json_mode_are_json_too() {
    let (code, out, _) = lacuna(&["counts", "C2 B2 | C2 B2 B2 | A9", "--levels", "1", "--json"]);
    assert_eq!(code, 2);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["error"]["code"], "E0108");
    assert_eq!(v["error"]["span"]["col"], 20);
}

#[test]
fn limits_are_enforced_with_their_flag_named() {
    let (code, _, err) = lacuna(&["counts", "F0", "--levels", "20", "--max-level", "10"]);
    assert_eq!(code, 2);
    assert!(
        err.contains("E0501") && err.contains("--max-level"),
        "{err}"
    );
    let (code, _, err) = lacuna(&["verify", "C99 B2 | C2 B2 B2 | A1"]);
    assert_eq!(code, 2);
    assert!(err.contains("--max-subedges"), "{err}");
}

#[test]
fn no_spoke_is_bad_input() {
    let (code, _, err) = lacuna(&["verify", "B2^2 C2^3 | C2 B2 B2 | A1"]);
    assert_eq!(code, 2);
    assert!(err.contains("E0401"), "{err}");
}

#[test]
fn census_runs_a_small_family() {
    let v = json(&[
        "census",
        "--max-length",
        "2",
        "--edges",
        "B2,C2",
        "--params",
        "B2",
        "--algorithms",
        "A1",
        "--json",
    ]);
    // Necklaces of length ≤ 2 over two letters: B2, C2, B2B2, B2C2, C2C2.
    assert_eq!(v["faces"], 5);
    assert_eq!(v["runaway"], 0);
}

#[test]
fn measure_prints_a_table_with_the_exact_counts() {
    // F0's holes per level are 0, 1, 13 (derived by hand in tests/geometry.rs: at level 2 the
    // level-1 lacuna, the 6 cells' own lacunas and the 6 gaps closed between them, 1 + 6 + 6).
    let (code, out, err) = lacuna(&["measure", "F0", "--level", "2", "--raster", "512"]);
    assert_eq!(code, 0, "{err}");
    let rows: Vec<&str> = out
        .lines()
        .filter(|l| l.trim_start().starts_with(|c: char| c.is_ascii_digit()))
        .collect();
    assert_eq!(rows.len(), 3, "{out}");
    for (row, (cells, holes)) in rows.iter().zip([(1, 0), (6, 1), (36, 13)]) {
        let words: Vec<&str> = row.split_whitespace().collect();
        assert_eq!(words[1], cells.to_string(), "{row}");
        assert_eq!(
            words[4..6],
            [holes.to_string(), format!("({holes})")],
            "{row}"
        );
        assert_eq!(words.last(), Some(&"yes"), "{row}");
    }
    assert!(out.contains("verdict: VERIFIED"), "{out}");
}

#[test]
fn measure_writes_a_certificate_of_its_exact_lines() {
    let dir = std::env::temp_dir().join(format!("lacuna-cli-measure-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let cert = dir.join("F0-measure.json");
    let c = cert.to_str().unwrap();
    let (code, out, err) = lacuna(&["measure", "F0", "--level", "1", "--certificate", c]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("the level-1 line by the level-one step"),
        "{out}"
    );
    assert!(
        out.contains(&format!("certificate written to {c}")),
        "{out}"
    );
    let (code, out, err) = lacuna(&["check", c]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(
        out.contains("every level-1 control polygon has positive area"),
        "{out}"
    );
    // Volumes and automata: verify certifies their exact figures; measure says so (bad input).
    for input in ["cube-B2", "koch"] {
        let (code, _, err) = lacuna(&["measure", input, "--level", "1", "--certificate", c]);
        assert_eq!(code, 2, "{input}: {err}");
        assert!(err.contains("lacuna verify"), "{input}: {err}");
    }
    std::fs::remove_dir_all(&dir).ok();
}
