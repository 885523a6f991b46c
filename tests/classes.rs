//! Topological classes and metamorphosis (issue #18, THEORY §13): the Euler characteristic of the
//! exact level-k complex against the lacuna count over random faces, `lacuna classify` on pairs
//! derived by hand, and `lacuna morph` between templates of F0, through a collapse too.

mod common;
use common::{lacuna, strategies};
use lacuna::topology::{close, components_by_cells, counts, multiplicity, Closure, Face, Limits};
use num_bigint::{BigInt, BigUint};
use num_rational::BigRational;
use proptest::prelude::*;

/// Faces of 2 to 6 edges (`B`/`C`, 2 or 3 sub-edges, delay ≤ 2), undelayed parameters, A1–A3
/// or a spoke set of at most two plain items, face delay 1 or 2.
fn face() -> impl Strategy<Value = Face> {
    strategies::face(
        strategies::edge(2..=3, 1..=2u32),
        2..=6,
        strategies::edge(2..=3, 1..=1u32),
        strategies::algorithm(strategies::plain_spoke_item(), 3),
        1u32..=2,
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// V − E + F of the exact level-k complex equals components − holes, where the holes are the
    /// lacunas N^L less the halves of the gaps opened on the border of a hole or of the outside
    /// (a notch, not a hole), and the components come from the independent union-find over the
    /// cells. The degree sum is twice the edges. A mismatch is a bug of the vertex types.
    #[test]
    fn euler_characteristic_matches_the_lacuna_count(f in face()) {
        let limits = Limits { max_types: 40, ..Limits::default() };
        let Ok(Closure::Closed(ts)) = close(&f, &limits) else { return Ok(()) };
        let levels = 3u64;
        let Ok(m) = multiplicity(&ts, &[], levels, 2_000) else { return Ok(()) };
        let Some(Ok(components)) = components_by_cells(&ts, &[], levels as u32, 20_000) else {
            return Ok(())
        };
        let c = counts(&ts, levels);
        for (l, lc) in m.levels.iter().zip(&c) {
            let chi = BigInt::from(l.vertices.clone()) - BigInt::from(l.edges.clone())
                + BigInt::from(l.faces.clone());
            let holes = &lc.lacunas
                - BigRational::new(BigInt::from(l.half_gaps.clone()), BigInt::from(2));
            let want = BigRational::from_integer(BigInt::from(components[l.level as usize])) - holes;
            prop_assert_eq!(BigRational::from_integer(chi), want, "{} level {}", f, l.level);
            prop_assert_eq!(&l.faces, &lc.faces);
            let degree_sum: BigUint = l
                .valences
                .iter()
                .map(|(v, k)| k.parse::<BigUint>().unwrap() * *v)
                .sum();
            prop_assert_eq!(degree_sum, &l.edges * 2u32, "{} level {}", f, l.level);
        }
    }

    /// With bounded valences the linear system of the complex (closed vertex types, edge cells,
    /// face types) stepped k times gives the valences of level k built level by level, and the
    /// limit shares lie in [0, 1], cover every valence of the system and sum to 1 (certified
    /// decimals, truncated: within 1e-9). With an unbounded valence the shares are not decided.
    #[test]
    fn limit_shares_are_a_distribution(f in face()) {
        let limits = Limits { max_types: 40, ..Limits::default() };
        let Ok(Closure::Closed(ts)) = close(&f, &limits) else { return Ok(()) };
        let Ok(m) = multiplicity(&ts, &[], 3, 2_000) else { return Ok(()) };
        let Ok(shares) = lacuna::analysis::limit_shares(&m) else { return Ok(()) };
        match (&m.system, &shares) {
            (None, lacuna::analysis::LimitShares::NotDecided { .. }) => {}
            (Some(sys), lacuna::analysis::LimitShares::Exact { shares }) => {
                for l in &m.levels {
                    let got: Vec<(usize, String)> = sys
                        .valences_at(l.level)
                        .into_iter()
                        .map(|(v, k)| (v, k.to_string()))
                        .collect();
                    let want: Vec<(usize, String)> =
                        l.valences.iter().map(|(v, k)| (*v, k.clone())).collect();
                    prop_assert_eq!(got, want, "{} level {}", f, l.level);
                }
                let mut sum = 0.0;
                for x in shares {
                    let d: f64 = x.decimal.parse().unwrap();
                    prop_assert!((0.0..=1.0).contains(&d), "{}: {:?}", f, x);
                    sum += d;
                }
                prop_assert!((sum - 1.0).abs() < 1e-9, "{}: sum {}", f, sum);
            }
            (Some(_), lacuna::analysis::LimitShares::NoLimit { residues, .. }) => {
                prop_assert!(residues.len() >= 2, "{}", f);
            }
            (sys, other) => prop_assert!(false, "{}: system {} with {:?}", f, sys.is_some(), other),
        }
    }
}

fn json(args: &[&str], want_code: i32) -> serde_json::Value {
    let (code, out, err) = lacuna(args);
    assert_eq!(code, want_code, "{args:?}: {out}{err}");
    serde_json::from_str(&out).unwrap_or_else(|e| panic!("{args:?}: not JSON ({e}): {out}"))
}

#[test]
fn classify_f0_with_itself_and_with_the_square() {
    let v = json(&["classify", "F0", "F0", "--json"], 0);
    assert_eq!(v["same_class"], true);
    assert_eq!(v["every_level"], true);
    // F0 splits into 6 (THEORY §5), the B2 square into 4 (count.rs): cardinality at level 1.
    let v = json(&["classify", "F0", "square-B2", "--json"], 1);
    assert_eq!(v["same_class"], false);
    assert_eq!(v["differs"]["group"], "cardinality");
    assert_eq!(v["differs"]["level"], 1);
    assert_eq!(
        (v["differs"]["a"].as_str(), v["differs"]["b"].as_str()),
        (Some("6"), Some("4"))
    );
    // F0's limit valence (hand derivation in topology/vertex.rs): bounded, largest 3.
    assert_eq!(v["limit_valence"]["a"]["max_valence"], 3);
    // Limit shares. F0: 6·2^k vertices of valence 2, 3·6^k − 3·2^k of valence 3 (THEORY §13),
    // so the shares tend to 0 and 1. The square: 4 corners of valence 2, (4/3)(5^k − 1) +
    // (8/3)(2^k − 1) of valence 3 and (5^k − 1)/3 − (4/3)(2^k − 1) of valence 4 (derivation in
    // analysis/invariants/shares.rs), so 0, 4/5 and 1/5.
    let shares = |side: &str| -> Vec<(u64, String, String)> {
        assert_eq!(v["limit_shares"][side]["status"], "exact");
        v["limit_shares"][side]["shares"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| {
                (
                    x["valence"].as_u64().unwrap(),
                    x["share"].as_str().unwrap().to_string(),
                    x["decimal"].as_str().unwrap()[..8].to_string(),
                )
            })
            .collect()
    };
    let row = |v: u64, s: &str, d: &str| (v, s.to_string(), d.to_string());
    assert_eq!(
        shares("a"),
        vec![row(2, "0", "0.000000"), row(3, "1", "1.000000")]
    );
    assert_eq!(
        shares("b"),
        vec![
            row(2, "0", "0.000000"),
            row(3, "4/5", "0.800000"),
            row(4, "1/5", "0.200000")
        ]
    );
}

#[test]
fn classify_tells_equal_counts_with_different_multiplicity_apart() {
    // Hand derivation (analysis/invariants/classes.rs): both have 5 sub-faces and 3/2 lacunas at
    // level 1; at level 1 P has 3 vertices of valence 2 (its C2 gap has no spoke: two ends and a
    // middle), Q has 2 (a spoke at its gap gives the middle valence 3).
    let v = json(
        &[
            "classify",
            "B2 B2 C2 | B2 B2 B2 | {joint corner}",
            "B2 B2^2 C2 | B2 B2 B2 | A2",
            "--json",
        ],
        1,
    );
    assert_eq!(v["same_class"], false);
    assert_eq!(v["differs"]["group"], "multiplicity");
    assert_eq!(v["differs"]["invariant"], "vertices of valence 2");
    assert_eq!(v["differs"]["level"], 1);
    assert_eq!(
        (v["differs"]["a"].as_str(), v["differs"]["b"].as_str()),
        (Some("3"), Some("2"))
    );
    // Both have spokes at corners: their valences grow without bound, with a witness, and the
    // limit shares are not decided.
    assert_eq!(v["limit_valence"]["a"]["kind"], "unbounded");
    assert_eq!(v["limit_shares"]["a"]["status"], "not_decided");
    assert_eq!(v["every_level"], false);
}

#[test]
fn classify_does_not_separate_faces_with_equal_invariants() {
    // Two different quads, each with 2 joints and 2 gaps under A1 (hand derivation in
    // analysis/invariants/classes.rs: 4 sub-faces, 2 lacunas, valences {2: 8, 3: 8} at level 1).
    let v = json(
        &[
            "classify",
            "B2 C2 B2 C2 | C2 B2 B2 | A1",
            "B2 B2 C2 C2 | C2 B2 B2 | A1",
            "--json",
        ],
        0,
    );
    assert_eq!(v["same_class"], true);
    assert_eq!(v["every_level"], true);
}

#[test]
fn classify_automata_and_volumes() {
    // Sierpinski: 3 pieces per piece; the Cantor set: 2 (their fixture comments).
    let v = json(
        &["classify", "sierpinski-triangle", "cantor-set", "--json"],
        1,
    );
    assert_eq!(v["differs"]["invariant"], "pieces");
    assert_eq!(
        (v["differs"]["a"].as_str(), v["differs"]["b"].as_str()),
        (Some("3"), Some("2"))
    );
    // A cube has 6 faces, a tetrahedron 4, at level 0.
    let v = json(&["classify", "cube-B2", "tetrahedron-B2", "--json"], 1);
    assert_eq!(v["differs"]["level"], 0);
    assert_eq!(
        (v["differs"]["a"].as_str(), v["differs"]["b"].as_str()),
        (Some("6"), Some("4"))
    );
    // Two cubes glued face to face (fixtures/two-cubes.txt) start from two volumes, one cube
    // from one: they differ in cells at level 0. Against itself the assembly is one class.
    let v = json(&["classify", "cube-B2", "two-cubes", "--json"], 1);
    assert_eq!(v["differs"]["invariant"], "cells");
    assert_eq!(v["differs"]["level"], 0);
    assert_eq!(
        (v["differs"]["a"].as_str(), v["differs"]["b"].as_str()),
        (Some("1"), Some("2"))
    );
    let v = json(&["classify", "two-cubes", "two-cubes", "--json"], 0);
    assert_eq!(v["same_class"], true);
}

#[test]
fn classify_volumes_by_the_valences_of_their_complexes() {
    // The hexagonal prism and the truncated tetrahedron (B2, A1, G = (B2, B2), V1) are different
    // solids with 12 corners of degree 3, 18 edges and 8 faces. By hand (geometry's
    // volume_valence tests) a solid with 3 faces at every corner has, at level 1, V + E corners
    // of valence 3, 4E of valence 4 and E of valence 5: equal here, and so are the counts. The
    // comparison covers the levels built (0 to 2 by default; the counts 0 to 4) and says that
    // the limit is not decided.
    let v = json(
        &[
            "classify",
            "truncated-tetrahedron",
            "prism-6 B2 | B2 B2 B2 | A1 | B2 B2 | V1",
            "--json",
        ],
        0,
    );
    assert_eq!(v["same_class"], true);
    assert_eq!(v["every_level"], false);
    assert_eq!(v["limit_shares"]["a"]["status"], "not_decided");
    let notes = v["notes"].to_string();
    assert!(
        notes.contains("volume valences: levels 0 to 2 only")
            && !notes.contains("not derived")
            && !notes.contains("not built"),
        "{notes}"
    );
    // The cells of the level-3 complex of cube-B2: 3032 + 29432 + 53520 + 25700 = 111684
    // (lacuna counts), above a limit of 1000: refused before the work, exit 2.
    let (code, _, err) = lacuna(&[
        "classify",
        "cube-B2",
        "cube-B2",
        "--levels",
        "3",
        "--volume-levels",
        "3",
        "--max-cells",
        "1000",
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--max-cells"), "{err}");
}

/// F0's default template with the points of every sub-face's lacuna side (its El edge: points
/// 6–8 of the even sub-faces, 3–5 of the odd ones, as the template's comments say) scaled by
/// `factor` about the centre.
fn lacuna_template(dir: &std::path::Path, name: &str, factor: f64) -> String {
    let base = dir.join("base.txt");
    if !base.exists() {
        let (code, _, err) = lacuna(&["render", "F0", "--write-template", base.to_str().unwrap()]);
        assert_eq!(code, 0, "{err}");
    }
    let text = std::fs::read_to_string(&base).unwrap();
    let mut out = String::new();
    for line in text.lines() {
        let Some(rest) = line.strip_prefix("sub ") else {
            out += line;
            out += "\n";
            continue;
        };
        let (k, pts) = rest.split_once(' ').unwrap();
        let k: usize = k.parse().unwrap();
        let lacuna = if k % 2 == 0 { 6..=8 } else { 3..=5 };
        let pts: Vec<String> = pts
            .split(';')
            .enumerate()
            .map(|(i, p)| {
                if !lacuna.contains(&i) {
                    return p.trim().to_string();
                }
                p.split_whitespace()
                    .map(|x| format!("{:.6}", x.parse::<f64>().unwrap() * factor))
                    .collect::<Vec<_>>()
                    .join(" ")
            })
            .collect();
        out += &format!("sub {k} {}\n", pts.join("; "));
    }
    let path = dir.join(name);
    std::fs::write(&path, out).unwrap();
    path.to_str().unwrap().to_string()
}

#[test]
fn morph_between_two_templates_of_f0_keeps_every_frame_verified() {
    let dir = common::scratch("classes-morph");
    let a = lacuna_template(&dir, "a.txt", 1.0);
    let b = lacuna_template(&dir, "b.txt", 0.5);
    let svg = dir.join("m.svg");
    let png = dir.join("f-{}.png");
    let v = json(
        &[
            "morph",
            &a,
            &b,
            "--on",
            "F0",
            "--frames",
            "4",
            "--level",
            "2",
            "--size",
            "128",
            "--svg",
            svg.to_str().unwrap(),
            "--png",
            png.to_str().unwrap(),
            "--json",
        ],
        0,
    );
    assert_eq!(v["verified"], true);
    let frames = v["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 4);
    let ts: Vec<&str> = frames.iter().map(|f| f["t"].as_str().unwrap()).collect();
    assert_eq!(ts, ["0", "1/3", "2/3", "1"]);
    // Exact holes of F0 at level 2 (topology/vertex.rs): (6^2 − 3·2^2 + 2)/2 = 13; one component.
    for f in frames {
        assert_eq!(f["verified"], true, "{f}");
        assert_eq!(
            (f["holes"].as_u64(), f["components"].as_u64()),
            (Some(13), Some(1))
        );
    }
    let text = std::fs::read_to_string(&svg).unwrap();
    assert_eq!(text.matches("<g class=\"frame\"").count(), 4);
    assert_eq!(
        text.matches("<animate attributeName=\"visibility\"")
            .count(),
        4
    );
    assert!(text.trim_end().ends_with("</svg>"));
    for k in 0..4 {
        let bytes = std::fs::read(dir.join(format!("f-{k:03}.png"))).unwrap();
        assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn morph_through_a_collapse_fails_at_the_frame_where_it_happens() {
    // B is A with every lacuna point reflected through the centre (factor −1), so the frame at
    // t = 1/2 targets every lacuna point at the centre: the exact projection is affine in the
    // targets, so that frame's lacunas have no width. Frames 0 and 1 (t = 1/4: lacunas at half
    // size) stay verified; frame 2 is the first to fail.
    let dir = common::scratch("classes-collapse");
    let a = lacuna_template(&dir, "a.txt", 1.0);
    let b = lacuna_template(&dir, "b.txt", -1.0);
    let (code, out, err) = lacuna(&[
        "morph", &a, &b, "--on", "F0", "--frames", "5", "--level", "1", "--size", "128", "--json",
    ]);
    assert_eq!(code, 1, "{out}{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["verified"], false);
    assert_eq!(v["first_failure"], 2);
    let frames = v["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 5, "a failing frame is reported, not skipped");
    assert_eq!(frames[0]["verified"], true);
    assert_eq!(frames[1]["verified"], true);
    assert_eq!(frames[2]["verified"], false);
    assert_eq!(frames[2]["t"], "1/2");
    assert!(!frames[2]["failures"].as_array().unwrap().is_empty());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn morph_refuses_bad_arguments_with_codes() {
    let (code, _, err) = lacuna(&[
        "morph", "default", "default", "--on", "F0", "--png", "x.png",
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("E1401"), "{err}");
    let (code, _, err) = lacuna(&["morph", "default", "default"]);
    assert_eq!(code, 2);
    assert!(err.contains("E1402"), "{err}");
    let (code, _, _) = lacuna(&["morph", "default", "default", "--on", "F0", "--frames", "1"]);
    assert_eq!(code, 2);
}

#[test]
fn morph_between_two_automata_of_one_shape() {
    // The degree-2 de Casteljau edge split at t = 1/2 (fixture) and at t = 1/3: T0 restricts the
    // parabola to [0, 1/3], columns P0, (2/3)P0 + (1/3)P1, B(1/3) = (4/9, 4/9, 1/9); T1 to
    // [1/3, 1], columns B(1/3), (2/3)P1 + (1/3)P2, P2. The constraints are linear in the
    // operators (T0·B1 = T1·B0 holds at both ends), so every frame satisfies them; each frame's
    // cycles are triangular with diagonals in (0, 1], so they contract.
    let dir = common::scratch("classes-automata");
    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/de-casteljau-edge.aut"),
    )
    .unwrap();
    let third: String = text
        .lines()
        .map(|l| {
            if l.starts_with("sub   e.T0") {
                "sub   e.T0 : e <- e = [1 2/3 4/9; 0 1/3 4/9; 0 0 1/9]".to_string()
            } else if l.starts_with("sub   e.T1") {
                "sub   e.T1 : e <- e = [4/9 0 0; 4/9 2/3 0; 1/9 1/3 1]".to_string()
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n");
    let b = dir.join("third.aut");
    std::fs::write(&b, third + "\n").unwrap();
    let svg = dir.join("a.svg");
    let v = json(
        &[
            "morph",
            "de-casteljau-edge",
            b.to_str().unwrap(),
            "--frames",
            "3",
            "--level",
            "3",
            "--svg",
            svg.to_str().unwrap(),
            "--json",
        ],
        0,
    );
    assert_eq!(v["verified"], true);
    assert_eq!(
        v["changing"], 2,
        "T0 and T1 change, the vertex operator and embeddings do not"
    );
    assert_eq!(v["frames"][1]["t"], "1/2");
    assert!(std::fs::read_to_string(&svg).unwrap().contains("<animate"));
    // Not one shape: refused with its code.
    let (code, _, err) = lacuna(&["morph", "de-casteljau-edge", "sierpinski-triangle"]);
    assert_eq!(code, 2);
    assert!(err.contains("E1403"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Valences of an assembly's complex: two cubes sharing a square. At level 0 the 4 corners of the
/// shared square hold the 3 edges of one cube and the edge of the other cube that leaves the
/// square (4 edges); the 8 other corners hold 3. Edges 12 + 12 − 4 = 20, and 4·4 + 8·3 = 2·20.
/// At level 1 the corners and edges agree with the exact counts of the assembly's solid.
#[test]
fn the_valences_of_two_cubes_glued_face_to_face() {
    let (_, file) = lacuna::input::load_volume_file("two-cubes")
        .unwrap()
        .unwrap();
    let placement =
        lacuna::geometry::place_assembly(&file.assembly, &file.corners, &file.names).unwrap();
    let c = lacuna::geometry::assembly_valences(&file.assembly, &placement, 0).unwrap();
    assert_eq!((c.corners, c.edges), (12, 20));
    assert_eq!(
        c.valences,
        std::collections::BTreeMap::from([(3, 8), (4, 4)])
    );
    let lacuna::topology::volume::VolumeClosure::Closed(set) =
        lacuna::topology::volume::VolumeClosure::of(&file.assembly.volumes, &Default::default())
            .unwrap()
    else {
        panic!("closes")
    };
    let exact =
        lacuna::topology::volume::solid_topology_of(&set, 1, &file.assembly.start_cells()).unwrap();
    let c = lacuna::geometry::assembly_valences(&file.assembly, &placement, 1).unwrap();
    assert_eq!(exact[1].corners, c.corners.into());
    assert_eq!(exact[1].edges, c.edges.into());
    let degree_sum: u64 = c.valences.iter().map(|(v, n)| *v as u64 * n).sum();
    assert_eq!(degree_sum, 2 * c.edges as u64);
}
