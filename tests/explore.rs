//! `lacuna explore` (issue #23, THEORY §14): it finds the runaway of the spoke rule `{gap}` and the
//! forced collapse of `C2 | B2 B2 B2 | A1`, shrinks every failure to them, and sharded runs merge
//! to the unsharded result.

mod common;
use common::lacuna;
use serde_json::Value;

/// Runs `lacuna explore … --json`: (exit code, boundary lines, summary).
fn explore(args: &[&str]) -> (i32, Vec<Value>, Value) {
    let mut all = vec!["explore", "--json"];
    all.extend_from_slice(args);
    let (code, out, err) = lacuna(&all);
    let mut lines: Vec<Value> = out
        .lines()
        .map(|l| serde_json::from_str(l).unwrap_or_else(|_| panic!("not JSON: {l}\n{err}")))
        .collect();
    let summary = lines.pop().expect("a summary line")["summary"].clone();
    assert!(summary.is_object(), "the last line is the summary: {out}");
    (code, lines, summary)
}

fn failures(lines: &[Value]) -> Vec<&Value> {
    lines
        .iter()
        .flat_map(|l| l["failures"].as_array().unwrap())
        .collect()
}

/// The minimal runaway of `{gap}` (spokes only at gaps), derived by hand.
///
/// `C2 | B2 B2 B2 | {gap}`: the one gap of C2 is the only spoke (the corner is not one), so the
/// single sub-face is the run of both pieces of C2 closed by Ec, Ea El Ea, Ec:
/// `C2 C2 B2 B2 B2 B2 B2` (7 edges). That face has two spokes, the gaps of its two C2; the run
/// from the second gap to the first crosses all 5 B2 edges (10 pieces, joints are not spokes), so
/// its sub-face has 1 + 10 + 1 + 5 = 17 edges with 15 B2, and so on: the B2 stretch at least
/// doubles at every level and the boundary grows without bound. It is minimal: a boundary of one
/// edge is the shortest; an all-B boundary has no gap, hence no spoke (refused, not a runaway);
/// C2 is the least Cantor edge (n = 2, no delay); and E = B2 B2 B2 is the least E (B before C,
/// n = 2, no delay).
#[test]
fn finds_and_shrinks_the_runaway_of_gap() {
    let (code, lines, summary) = explore(&[
        "--edges",
        "B2,C2",
        "--max-length",
        "3",
        "--params",
        "B2,C2",
        "--algorithm",
        "{gap}",
        "--properties",
        "closes",
        "--max-boundary",
        "48",
    ]);
    assert_eq!(code, 1, "a failure is a negative verdict");
    let f = failures(&lines);
    assert!(!f.is_empty());
    for x in &f {
        assert_eq!(x["property"], "closes");
        assert_eq!(x["witness"]["kind"], "runaway chain");
    }
    // Every failure whose E can shrink to B2 B2 B2 does; the witness chain of the minimal face
    // starts as derived above and grows.
    let minimal: Vec<&&Value> = f
        .iter()
        .filter(|x| x["shrunk"]["face"] == "C2 | B2 B2 B2 | {gap}")
        .collect();
    assert!(minimal.len() >= 6, "{f:?}");
    assert!(minimal
        .iter()
        .any(|x| x["shrunk"]["steps"].as_u64().unwrap() >= 2));
    let chain = minimal[0]["shrunk"]["witness"]["detail"]
        .as_array()
        .unwrap();
    assert_eq!(chain[1], "C2 | B2 B2 B2 | {gap}");
    assert_eq!(chain[2], "B2 B2 B2 B2 B2 C2 C2 | B2 B2 B2 | {gap}");
    assert_eq!(minimal[0]["shrunk"]["minimal"], true);
    let lens: Vec<usize> = chain[1..]
        .iter()
        .map(|c| {
            c.as_str()
                .unwrap()
                .split('|')
                .next()
                .unwrap()
                .split_whitespace()
                .count()
        })
        .collect();
    assert_eq!(&lens[..3], &[1, 7, 17]);
    assert!(lens.windows(2).all(|w| w[0] < w[1]), "{lens:?}");
    // All-B boundaries are refused (no spoke), not failures.
    assert!(summary["refused"].as_u64().unwrap() > 0);
    let cx = summary["counterexamples"].as_array().unwrap();
    assert!(cx.contains(&serde_json::json!(["C2 | B2 B2 B2 | {gap}", "closes"])));
}

/// The forced collapse of `C2 | B2 B2 B2 | A1`: the C2 edge has one gap and A1 puts no spoke at
/// the corner, so there is one spoke and one sub-face, glued to itself along its Ea edge
/// (traversed inwards and outwards): the adjacency constraint forces the two inner ends of the
/// spoke — the two ends of the lacuna edge El, distinct corners of the level-1 complex — onto one
/// point. It is minimal for the same reasons as above (one edge, C2, E = B2 B2 B2).
#[test]
fn finds_and_shrinks_the_forced_collapse() {
    let (code, lines, summary) = explore(&[
        "--edges",
        "C2,C3",
        "--max-length",
        "2",
        "--params",
        "B2,C2",
        "--properties",
        "no-collapse",
    ]);
    assert_eq!(code, 1);
    let f = failures(&lines);
    assert!(f.len() >= 4);
    for x in &f {
        assert_eq!(x["property"], "no-collapse");
        assert_eq!(x["shrunk"]["face"], "C2 | B2 B2 B2 | A1", "{x}");
        assert_eq!(x["shrunk"]["minimal"], true);
        assert_eq!(x["shrunk"]["witness"]["kind"], "collapsing pair");
    }
    // From C3 C3 with C2 in E: fewer edges, smaller n and a simpler E on the way.
    assert!(f
        .iter()
        .any(|x| x["shrunk"]["steps"].as_u64().unwrap() >= 3));
    assert_eq!(
        summary["counterexamples"],
        serde_json::json!([["C2 | B2 B2 B2 | A1", "no-collapse"]])
    );
}

#[test]
fn sharded_runs_merge_to_one_run() {
    let family = [
        "--edges",
        "B2,C2,C2^2",
        "--max-length",
        "3",
        "--params",
        "B2,C2",
        "--algorithm",
        "A3",
        "--properties",
        "closes,ratio",
    ];
    let (code, whole, summary) = explore(&family);
    assert_eq!(code, 0);
    assert_eq!(
        whole.len(),
        20 * 8,
        "necklaces over 3 letters up to length 3, × 8 E"
    );
    let mut merged = Vec::new();
    let mut total = 0;
    for i in 1..=3 {
        let shard = format!("{i}/3");
        let mut args = family.to_vec();
        args.extend(["--shard", &shard]);
        let (code, lines, s) = explore(&args);
        assert_eq!(code, 0);
        assert_eq!(s["shard"], shard);
        total += s["boundaries"].as_u64().unwrap();
        merged.extend(lines);
    }
    merged.sort_by_key(|l| l["index"].as_u64().unwrap());
    assert_eq!(merged, whole);
    assert_eq!(total, summary["boundaries"].as_u64().unwrap());
    // The thread count changes nothing either.
    for threads in ["1", "3"] {
        let mut args = family.to_vec();
        args.extend(["--threads", threads]);
        let (_, lines, s) = explore(&args);
        assert_eq!(lines, whole, "--threads {threads}");
        assert_eq!(s, summary, "--threads {threads}");
    }
    // A random family too: the sample depends on the seed only.
    let random = [
        "--random",
        "25",
        "--seed",
        "11",
        "--max-length",
        "5",
        "--properties",
        "closes",
    ];
    let (_, whole, _) = explore(&random);
    let mut merged = Vec::new();
    for i in 1..=2 {
        let shard = format!("{i}/2");
        let mut args = random.to_vec();
        args.extend(["--shard", &shard]);
        merged.extend(explore(&args).1);
    }
    merged.sort_by_key(|l| l["index"].as_u64().unwrap());
    assert_eq!(merged, whole);
}

#[test]
fn bad_options_are_coded() {
    for (args, code) in [
        (vec!["explore", "--shard", "4/3"], "E0114"),
        (vec!["explore", "--properties", "pretty"], "E0114"),
        (vec!["explore", "--edges", "B2,,C2"], "E0112"),
        (vec!["explore", "--algorithm", "A9"], "E0108"),
        (vec!["explore", "--max-length", "13"], "E0501"),
        (vec!["explore", "--max-length", "0"], "E0503"),
        (vec!["explore", "--random", "100000000"], "E0501"),
    ] {
        let (exit, _, err) = lacuna(&args);
        assert_eq!(exit, 2, "{args:?}");
        assert!(err.contains(code), "{args:?}: {err}");
    }
}

/// `census --json` lists every face with its type count, exact R and verdict (issue #23).
#[test]
fn census_json_lists_every_face() {
    let (code, out, err) = lacuna(&[
        "census",
        "--max-length",
        "2",
        "--edges",
        "B2,C2",
        "--params",
        "B2",
        "--algorithms",
        "A1,{joint}",
        "--json",
    ]);
    assert_eq!(code, 0, "{err}");
    let v: Value = serde_json::from_str(&out).unwrap();
    let faces = v["per_face"].as_array().unwrap();
    assert_eq!(faces.len(), v["faces"].as_u64().unwrap() as usize);
    let find = |f: &str| faces.iter().find(|x| x["face"] == f).unwrap();
    // B2 | B2 B2 B2 | A1: one spoke (the joint), one sub-face `B2 B2 B2 B2 B2` (both pieces, then
    // Ea El Ea). That face has 5 joint spokes and 5 sub-faces, each the last piece of one edge,
    // the first of the next and Ea El Ea: itself again. So 2 types; a step adds the central
    // lacuna only (no Cn), l = 1, k = 5, and R = l / (l + k − 1) = 1/5 (THEORY §5).
    assert_eq!(find("B2 | B2 B2 B2 | A1")["types"], 2);
    assert_eq!(find("B2 | B2 B2 B2 | A1")["ratio"], "1/5");
    assert_eq!(find("B2 | B2 B2 B2 | A1")["verdict"], "closed");
    let refused = find("C2 | B2 B2 B2 | {joint}");
    assert_eq!(refused["verdict"], "refused");
    assert_eq!(refused["code"], "E0401");
    assert!(refused["ratio"].is_null());
}

/// The opt-in `holes` property instantiates the default geometry and compares the holes observed
/// per level with the exact count: a triangle of C2 edges has the central lacuna at level 1
/// (1 hole, observed), while one- and two-edge faces placed with straight edges have no area and
/// are skipped, not failed.
#[test]
fn holes_property_is_measured_on_the_geometry() {
    let (code, lines, _) = explore(&[
        "--edges",
        "C2",
        "--max-length",
        "3",
        "--params",
        "C2",
        "--properties",
        "holes",
        "--holes-level",
        "1",
    ]);
    assert_eq!(code, 0);
    let outcome = |k: usize| {
        lines[k]["properties"]["holes"]
            .as_str()
            .unwrap()
            .to_string()
    };
    assert_eq!(lines[2]["face"], "C2 C2 C2 | C2 C2 C2 | A1");
    assert_eq!(outcome(2), "pass");
    assert!(outcome(0).starts_with("skip"), "{}", outcome(0));
}

/// Issue #36: on the families where two-edge faces used to fail (edges B2, C2, boundaries of
/// length ≤ 3, every E of B2 and C2, under A1 and under A3), every face measures its exact holes
/// at levels 0 to 2 or is refused with a reason. The two-edge faces whose two spokes bound a
/// lacuna of Cantor sides are forced collapses (refused here, failed by `no-collapse`); those with
/// Bézier lacuna sides are placed with a lens-shaped lacuna and measured.
#[test]
fn two_edge_faces_measure_their_holes_or_are_refused_with_a_reason() {
    for algorithm in ["A1", "A3"] {
        let (code, lines, _) = explore(&[
            "--edges",
            "B2,C2",
            "--max-length",
            "3",
            "--algorithm",
            algorithm,
            "--properties",
            "holes",
            "--holes-level",
            "2",
        ]);
        assert_eq!(code, 0, "{algorithm}: {lines:?}");
        let faces: Vec<&Value> = lines.iter().filter(|l| l.get("face").is_some()).collect();
        assert_eq!(
            faces.len(),
            72,
            "{algorithm}: (2 + 3 + 4) boundaries × 2³ E"
        );
        let outcome = |l: &Value| l["properties"]["holes"].as_str().unwrap_or("").to_string();
        for l in &faces {
            let o = outcome(l);
            assert!(o == "pass" || o.starts_with("skip"), "{algorithm}: {l}");
        }
        // The digon of Bézier lacuna sides is measured, not skipped.
        let digon = faces
            .iter()
            .find(|l| l["face"] == format!("B2 B2 | B2 B2 B2 | {algorithm}"))
            .expect("the digon is in the family");
        assert_eq!(outcome(digon), "pass", "{digon}");
        // The one of Cantor lacuna sides is refused as a forced collapse.
        let flat = faces
            .iter()
            .find(|l| l["face"] == format!("B2 B2 | B2 C2 B2 | {algorithm}"))
            .expect("in the family");
        assert!(outcome(flat).contains("forced collapse"), "{flat}");
    }
}
