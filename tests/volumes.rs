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
    let cells: Vec<&str> = v["levels"]
        .as_array()
        .unwrap()
        .iter()
        .map(|l| l["cells"].as_str().unwrap())
        .collect();
    assert_eq!(cells, ["1", "4", "76", "1516"]);
    // Lacunas: the tetrahedron contributes 1 + 4/2 = 3.
    assert_eq!(v["levels"][1]["lacunas"], "3");
    // One JSON shape across kinds (issue #32): `levels` and `types` as for faces, the old
    // `counts` kept as an alias; a face's counts name their input as a volume's do.
    assert_eq!(v["counts"], v["levels"]);
    assert_eq!(
        (v["types"].clone(), v["input"].clone()),
        (3.into(), "tetrahedron-B2".into())
    );
    let (code, out, _) = lacuna(&["counts", "F0", "--levels", "1", "--json"]);
    assert_eq!(code, 0);
    let f: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(
        (f["types"].clone(), f["input"].clone()),
        (1.into(), "F0".into())
    );
    assert_eq!(f["levels"][1]["cells"], "6");
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
    // The reasons speak of volumes (issue #32: "3 volume types", then "3 face types reached").
    let (code, out, _) = lacuna(&["ratio", "cube-B2"]);
    assert_eq!(code, 0);
    assert!(out.contains("3 volume types reached in 2 classes"), "{out}");
    assert!(
        out.contains("sub-volumes 1") && !out.contains("face type"),
        "{out}"
    );
}

#[test]
fn verify_a_volume_in_notation() {
    let (code, out, err) = lacuna(&["verify", "octahedron B2 | B2 B2 B2 | A1 | B2 B2 | V2"]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.starts_with("lacuna verify: "),
        "the heading names the command: {out}"
    );
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
    let (code, _, err) = lacuna(&["operators", "cube-B2"]);
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

/// `counts --json` of a volume input: the cells and lacunas per level, and the solid's rows
/// (volumes, faces, edges, corners, χ, components, tunnels) per level.
fn counts_json(input: &str, levels: &str) -> (Vec<String>, Vec<String>, Vec<Vec<String>>) {
    let (code, out, err) = lacuna(&["counts", input, "--levels", levels, "--json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let text = |x: &serde_json::Value| match x {
        serde_json::Value::String(s) => s.clone(),
        other => other.to_string(),
    };
    let col = |k: &str| -> Vec<String> {
        v["levels"]
            .as_array()
            .unwrap()
            .iter()
            .map(|l| text(&l[k]))
            .collect()
    };
    let solid = v["solid"]
        .as_array()
        .unwrap()
        .iter()
        .map(|l| {
            [
                "volumes",
                "faces",
                "edges",
                "corners",
                "euler",
                "components",
                "tunnels",
            ]
            .iter()
            .map(|k| text(&l[*k]))
            .collect()
        })
        .collect();
    (col("cells"), col("lacunas"), solid)
}

fn row(x: [&str; 7]) -> Vec<String> {
    x.iter().map(|s| s.to_string()).collect()
}

#[test]
fn cube_c2_by_hand() {
    // Each square C2 C2 C2 C2 with A1 (spokes at the four gaps, none at a corner) splits into
    // four heptagons, one per corner; V1 joins the three at each cube corner: 8 cells. Every
    // later volume also has one child per corner (every face has spokes at its joints and gaps
    // only), and a level-1 cell has 31 corners (a patch of 3 heptagons: 16 points, 15 on the
    // rim, plus 15 inner copies): 8·31 = 248 at level 2.
    // Lacunas at level 1, in quarters: 4 (cavity) + 6 squares × (2 centre + 4 gaps·1) halves =
    // 40, i.e. 10.
    // The level-1 solid by birth (THEORY §10): level 0 has 1 volume, 6 faces, 12 C2 edges, 8
    // corners. Faces: 24 spoke faces (4 spokes per square), 72 wall faces (4 El + 8 Ec sides
    // per square), 8 inner faces, and the 24 heptagons: 128. Edges: one inner edge per side
    // face (96), per square 4 Ea + 4 El + 8 Ec (96), two pieces per cube edge (24), and one
    // radial edge per rim point of the level-1 surface: 24 lacuna corners, 24 gap points inside
    // the squares, 24 gap ends on the cube edges (72): 288. Corners: 8 + 2·12 gap ends + 8·6
    // (4 lacuna corners and 4 gap points per square) + 72 radial ends = 152.
    // χ = 152 − 288 + 128 − 8 = −16; connected, no void: 17 tunnels.
    let (cells, lacunas, solid) = counts_json("cube-C2", "2");
    assert_eq!(cells, ["1", "8", "248"]);
    assert_eq!(lacunas[1], "10");
    assert_eq!(solid[0], row(["1", "6", "12", "8", "1", "1", "0"]));
    assert_eq!(solid[1], row(["8", "128", "288", "152", "-16", "1", "17"]));
}

#[test]
fn truncated_tetrahedron_by_hand() {
    // 4 triangles and 4 hexagons, 12 corners of degree 3, 18 edges. With B2 edges and A1 every
    // face splits into pentagons, one per corner (3 per triangle, 6 per hexagon: 36), and V1
    // joins the three at each corner into the cube's corner type W3 (19 corners: 16 of degree 3,
    // 3 of degree 4; W4 has 20 and 5): cells 1, 12, 12·19 = 228, 12·(16·19 + 3·25) = 4548.
    // Lacunas at level 1: 4 + 8·2 quarters = 20, i.e. 5.
    // The level-1 solid: faces 36 spoke + 36 wall + 12 inner + 36 pentagons = 120; edges 72
    // inner, 54 radial (36 lacuna corners and 18 edge joints), 72 in the faces (36 Ea, 36 El),
    // 36 pieces = 234; corners 12 + 18 joints + 36 lacuna corners + 54 radial ends = 120.
    // χ = 120 − 234 + 120 − 12 = −6: the thickened graph of the solid, genus 18 − 12 + 1 = 7.
    let (cells, lacunas, solid) = counts_json("truncated-tetrahedron", "3");
    assert_eq!(cells, ["1", "12", "228", "4548"]);
    assert_eq!(lacunas[1], "5");
    assert_eq!(solid[0], row(["1", "8", "18", "12", "1", "1", "0"]));
    assert_eq!(solid[1], row(["12", "120", "234", "120", "-6", "1", "7"]));
}

#[test]
fn two_cubes_by_hand() {
    // Two cubes sharing a square: level 0 has 2 volumes, 6 + 6 − 1 = 11 faces, 12 + 12 − 4 = 20
    // edges, 8 + 8 − 4 = 12 corners: χ = 12 − 20 + 11 − 2 = 1. Counts are twice cube-B2's
    // (1, 8, 152, 3032 and 0, 4, 64, 1252).
    // Level 1 by birth, from cube-B2's level 1 (8 volumes, 80 faces, 156 edges, 80 corners):
    // a B2 square gives 4 pentagons, 8 edges (4 Ea, 4 El), 4 lacuna corners; a B2 edge 2
    // pieces and 1 joint; so a cube volume gives 80 − 24 = 56 faces, 156 − 48 − 24 = 84 edges,
    // 80 − 24 − 12 − 8 = 36 corners. Two cubes: faces 2·56 + 11·4 = 156, edges 2·84 + 11·8 +
    // 20·2 = 296, corners 2·36 + 11·4 + 20 + 12 = 148, χ = 148 − 296 + 156 − 16 = −8 =
    // (−4) + (−4) − 0 (glued along the annulus of the shared square): 9 tunnels.
    let (cells, lacunas, solid) = counts_json("two-cubes", "3");
    assert_eq!(cells, ["2", "16", "304", "6064"]);
    assert_eq!(lacunas, ["0", "8", "128", "2504"]);
    assert_eq!(solid[0], row(["2", "11", "20", "12", "1", "1", "0"]));
    assert_eq!(solid[1], row(["16", "156", "296", "148", "-8", "1", "9"]));
}

#[test]
fn an_assembly_file_verifies_and_certifies() {
    let dir = common::scratch("volasm");
    // A tetrahedron block (corners 0 1 2 3, faces counter-clockwise from outside) glued to a
    // shorthand tetrahedron along one triangle.
    let file = dir.join("pair.txt");
    std::fs::write(
        &file,
        "volume A {
  inside: B2 B2 | B2 B2 B2 | A1 | V1
  face a: B2 B2 B2 | B2 B2 B2 | A1   # 0 2 1
  face b: B2 B2 B2 | B2 B2 B2 | A1   # 0 1 3
  face c: B2 B2 B2 | B2 B2 B2 | A1   # 1 2 3
  face d: B2 B2 B2 | B2 B2 B2 | A1   # 0 3 2
  face a edge 0 ~ face d edge 2
  face a edge 1 ~ face c edge 0
  face a edge 2 ~ face b edge 0
  face b edge 1 ~ face c edge 2
  face b edge 2 ~ face d edge 0
  face c edge 1 ~ face d edge 1
}
volume B = tetrahedron B2 | B2 B2 B2 | A1 | B2 B2 | V1
volume A face c edge 0 ~ volume B face 0 edge 0
",
    )
    .unwrap();
    let cert = dir.join("pair.json");
    let (code, out, err) = lacuna(&[
        "verify",
        file.to_str().unwrap(),
        "--levels",
        "2",
        "--certificate",
        cert.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{out}{err}");
    // Two tetrahedra, each with one child per corner (4), of type W3 (19 children each).
    assert!(out.contains("verdict: VERIFIED"), "{out}");
    let (code, out, _) = lacuna(&["check", cert.to_str().unwrap()]);
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("proved  step 0 (volume-closure)"), "{out}");
    let (cells, _, solid) = counts_json(file.to_str().unwrap(), "2");
    assert_eq!(cells, ["2", "8", "152"]);
    // Level 0: 2 volumes, 4 + 4 − 1 = 7 faces, 6 + 6 − 3 = 9 edges, 4 + 4 − 3 = 5 corners.
    assert_eq!(solid[0], row(["2", "7", "9", "5", "1", "1", "0"]));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn face_counts_name_their_cells() {
    // F0: one type, six sub-faces per face: 1, 6, 36 faces, and `cells` says the same.
    let (code, out, err) = lacuna(&["counts", "F0", "--levels", "2", "--json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    for (i, want) in ["1", "6", "36"].iter().enumerate() {
        assert_eq!(v["levels"][i]["cells"], *want, "{out}");
        assert_eq!(v["levels"][i]["faces"], *want, "{out}");
    }
}

#[test]
fn a_bad_volume_file_is_exit_2_with_its_line_and_column() {
    let dir = common::scratch("volbad");
    let file = dir.join("open.txt");
    // A square with only two of its edges glued: edge 1 is not glued (E1225, at the face's
    // name on line 3, column 8).
    std::fs::write(
        &file,
        "volume X {\n  inside: B2 B2 | B2 B2 B2 | A1 | V1\n  face a: B2 B2 B2 B2 | B2 B2 B2 | A1\n  face a edge 0 ~ face a edge 2\n}\n",
    )
    .unwrap();
    let (code, _, err) = lacuna(&["counts", file.to_str().unwrap(), "--levels", "1"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("error[E1225]"), "{err}");
    assert!(err.contains("open.txt:3:8"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

/// A thick spherical shell pierced by k holes (one per face of the solid, each face's central
/// lacuna opening the cavity) is a handlebody of genus k − 1; its surface has Euler
/// characteristic 2 − 2(k − 1). The cube has k = 6: genus 5, χ = −8 (THEORY §10).
#[test]
fn render_a_volume_writes_a_checked_mesh_and_pictures() {
    let d = common::scratch("volgeo-render");
    let f = |n: &str| d.join(n).to_string_lossy().into_owned();
    let (code, out, err) = lacuna(&[
        "render",
        "cube-B2",
        "--level",
        "1",
        "--stl",
        &f("c.stl"),
        "--3mf",
        &f("c.3mf"),
        "--obj",
        &f("c.obj"),
        "--png",
        &f("c.png"),
        "--svg",
        &f("c.svg"),
        "--size",
        "200",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("surface Euler characteristic -8 = 2χ (exact χ = -4)"),
        "{out}"
    );
    assert!(out.contains("genus 5"), "{out}");
    assert!(out.contains("no two triangles cross"), "{out}");
    for n in ["c.stl", "c.3mf", "c.obj", "c.png", "c.svg"] {
        assert!(d.join(n).metadata().unwrap().len() > 100, "{n}");
    }
    // The PNG decodes at the asked size; the solid covers part of it, not all of it, and is
    // shaded (more than one colour).
    let dec = png::Decoder::new(std::io::BufReader::new(
        std::fs::File::open(d.join("c.png")).unwrap(),
    ));
    let mut r = dec.read_info().unwrap();
    let mut buf = vec![0; r.output_buffer_size().unwrap()];
    let info = r.next_frame(&mut buf).unwrap();
    assert_eq!((info.width, info.height), (200, 200));
    let px: Vec<&[u8]> = buf[..info.buffer_size()].chunks(4).collect();
    let white = px.iter().filter(|p| p[..3] == [255, 255, 255]).count();
    assert!(
        white > px.len() / 10 && white < px.len() * 9 / 10,
        "{white}"
    );
    let shades: std::collections::HashSet<&[u8]> = px.iter().map(|p| &p[..3]).collect();
    assert!(shades.len() > 3);
    let svg = std::fs::read_to_string(d.join("c.svg")).unwrap();
    assert!(svg.starts_with("<svg") && svg.contains("<polygon"));
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_solid_that_folds_is_not_written() {
    // The cube whose top is turned by 160° (fixtures/twisted-cube-160.txt) embeds at level 1,
    // but at level 2 its placement folds (two triangles cross) under all three fan rules: a mesh
    // would not be the verified structure, so nothing is written and the verdict is negative.
    // (This was tetrahedron C3 A1 V1 at level 3 until boundary faces were fanned around a point
    // of their own kernel, issue #31; tests/volume_sweep.rs runs that case.)
    let d = common::scratch("volgeo-fold");
    let stl = d.join("t3.stl");
    let (code, _, err) = lacuna(&[
        "render",
        "fixtures/twisted-cube-160.txt",
        "--level",
        "2",
        "--stl",
        &stl.to_string_lossy(),
    ]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("E1041"), "{err}");
    assert!(!stl.exists());
    // A cube whose top is turned by 150° (fixtures/twisted-cube.txt) folds at level 2 under the
    // first fan rule; the second (inner faces fanned around the shrink of a point of their
    // patch) embeds it, now that a boundary face that is not star-shaped from its centre is
    // fanned around a point it is star-shaped from (issue #31): the mesh is written.
    let stl = d.join("t2.stl");
    let (code, out, err) = lacuna(&[
        "render",
        "fixtures/twisted-cube.txt",
        "--level",
        "2",
        "--stl",
        &stl.to_string_lossy(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("no two triangles cross"), "{out}");
    assert!(stl.exists());
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn measure_and_report_a_volume() {
    let (code, out, err) = lacuna(&["measure", "tetrahedron-B2", "--level", "1", "--json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["verified"], true);
    // Four face holes: genus 3, surface χ = 2 − 2·3 = −4, solid χ = −2.
    assert_eq!(v["solid"]["euler"], "-2");
    assert_eq!(v["mesh"]["genus"], 3);
    assert_eq!(v["mesh"]["surface_euler"], -4);
    // Scaled to 100 mm wide: less material than the box around it, more than nothing.
    let vol = v["sizes"]["volume_mm3"].as_f64().unwrap();
    let e = &v["sizes"]["extent_mm"];
    let bx: f64 = (0..3).map(|k| e[k].as_f64().unwrap()).product();
    assert!(vol > 0.0 && vol < bx, "{vol} {bx}");
    assert!((e[0].as_f64().unwrap() - 100.0).abs() < 1e-3);
    // --strict with a resolution above the smallest hole fails.
    let (code, _, _) = lacuna(&[
        "measure",
        "tetrahedron-B2",
        "--level",
        "1",
        "--resolution",
        "1000",
        "--strict",
    ]);
    assert_eq!(code, 1);
    let d = common::scratch("volgeo-report");
    let page = d.join("t.html");
    let (code, _, err) = lacuna(&[
        "report",
        "tetrahedron-B2",
        "--level",
        "1",
        "--out",
        &page.to_string_lossy(),
    ]);
    assert_eq!(code, 0, "{err}");
    let html = std::fs::read_to_string(&page).unwrap();
    assert!(html.contains("<canvas id=\"solid3d\""));
    assert!(!html.contains("<script src"), "no external script");
    let _ = std::fs::remove_dir_all(&d);
}

/// The default placement's cases of issue #15 through the command line: `render` of each writes
/// a binary STL and exits 0; the STL reads back as 80 header bytes, a count and 50 bytes per
/// triangle, and the count agrees with the mesh line.
#[test]
fn render_writes_the_solids_that_folded_before() {
    let d = common::scratch("volgeo-unfold");
    for (i, (text, level)) in [
        ("cube C2 | B2 B2 B2 | A1 | B2 B2 | V1", "2"),
        ("cube B2 | B2 B2 B2 | A1 | B2 B2 | V2", "2"),
        ("cube-B2", "3"),
        // Folded until the inner faces could be fanned around a point of their patch
        // (`InnerFan::PatchPoint`), which the summary then names.
        ("cube C2 | B2 B2 B2 | A2 | B2 B2 | V1", "2"),
    ]
    .into_iter()
    .enumerate()
    {
        let stl = d.join(format!("s{i}.stl"));
        let (code, out, err) = lacuna(&[
            "render",
            text,
            "--level",
            level,
            "--stl",
            &stl.to_string_lossy(),
        ]);
        assert_eq!(code, 0, "{text} level {level}: {err}");
        assert!(out.contains("no two triangles cross"), "{out}");
        if text.contains("A2") {
            assert!(
                out.contains("around the shrink of a point of their patch"),
                "{out}"
            );
        }
        let bytes = std::fs::read(&stl).unwrap();
        let n = common::mesh_files::binary_stl_triangles(&bytes);
        assert_eq!(bytes.len(), 84 + 50 * n, "{text}");
        assert!(out.contains(&format!("{n} triangles")), "{text}: {n} {out}");
    }
    let _ = std::fs::remove_dir_all(&d);
}

/// A square pyramid is none of the shorthand solids: `fixtures/pyramid.txt` gives its corners.
/// Under V1 each of its 5 corners raises one piece, and the pieces meet pairwise along its 8
/// edges (as the cube's 8 pieces along its 12): a thickened graph with 5 vertices and 8 edges,
/// genus 8 − 5 + 1 = 4, surface Euler characteristic 2 − 2·4 = −6. The apex is at height 0.8 on
/// a unit base, so at 100 mm wide the extent is 100 × 100 × 80 mm.
#[test]
fn a_volume_on_user_coordinates() {
    let (code, out, err) = lacuna(&["measure", "fixtures/pyramid.txt", "--level", "1", "--json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["verified"], true);
    assert_eq!(v["solid"]["volumes"], "5");
    assert_eq!(v["mesh"]["genus"], 4);
    assert_eq!(v["mesh"]["surface_euler"], -6);
    let e = &v["sizes"]["extent_mm"];
    for (k, want) in [100.0, 100.0, 80.0].into_iter().enumerate() {
        assert!((e[k].as_f64().unwrap() - want).abs() < 1e-3, "{e}");
    }
    // The cube shorthand on corners of a 2 × 1 × 1 box: the cube's topology (genus 5), the
    // box's proportions.
    let (code, out, err) = lacuna(&[
        "measure",
        "fixtures/box-2x1x1.txt",
        "--level",
        "1",
        "--json",
    ]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["mesh"]["genus"], 5);
    let e = &v["sizes"]["extent_mm"];
    for (k, want) in [100.0, 50.0, 50.0].into_iter().enumerate() {
        assert!((e[k].as_f64().unwrap() - want).abs() < 1e-3, "{e}");
    }
}

/// Two cube-B2 volumes glued face to face. As a thickened graph: 8 + 8 pieces, 12 + 12 bridges
/// inside the cubes and 4 across the shared face (the pentagons at its corners), cycle rank
/// 28 − 16 + 1 = 13. But around each of the shared face's 4 edges the two bridges and the two
/// crossings meet along one spoke edge of the shared face (all four pieces hold it), so those 4
/// cycles bound no tunnel: genus 13 − 4 = 9, surface Euler characteristic 2 − 2·9 = −16.
/// The second cube is laid beside the first: 100 × 200 × 100 mm.
#[test]
fn an_assembly_is_drawn_as_one_solid() {
    let d = common::scratch("volgeo-assembly");
    let stl = d.join("two.stl");
    let (code, out, err) = lacuna(&[
        "render",
        "two-cubes",
        "--level",
        "1",
        "--stl",
        &stl.to_string_lossy(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("16 volumes"), "{out}");
    assert!(out.contains("surface Euler characteristic -16"), "{out}");
    assert!(out.contains("genus 9"), "{out}");
    assert!(out.contains("1 part,"), "{out}");
    assert!(stl.metadata().unwrap().len() > 84);
    let (code, out, err) = lacuna(&["measure", "two-cubes", "--level", "1", "--json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let e = &v["sizes"]["extent_mm"];
    let mut ext: Vec<f64> = (0..3).map(|k| e[k].as_f64().unwrap()).collect();
    ext.sort_by(f64::total_cmp);
    assert!(
        (ext[0] - 100.0).abs() < 1e-3 && (ext[2] - 200.0).abs() < 1e-3,
        "{e}"
    );
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn bad_coordinates_are_coded_errors_with_their_place() {
    let d = common::scratch("volgeo-coords");
    let pyramid = std::fs::read_to_string("fixtures/pyramid.txt").unwrap();
    let cases: [(&str, String, &str); 5] = [
        // s2 gives the base's corner (1 1 0) as (1 1 0.5).
        (
            "E1212",
            pyramid.replace("corners s2: 1 1 0,", "corners s2: 1 1 0.5,"),
            ":19:15",
        ),
        // Without s0 and s2 the apex has no coordinates.
        (
            "E1213",
            pyramid
                .lines()
                .filter(|l| !l.contains("corners s"))
                .collect::<Vec<_>>()
                .join("\n"),
            ":5:8",
        ),
        // Two points for a triangle.
        (
            "E1214",
            pyramid.replace(", 1 0 0, 0.5 0.5 0.8", ", 1 0 0"),
            ":18:",
        ),
        // The apex below the base: the faces wind clockwise seen from outside.
        ("E1215", pyramid.replace(" 0.8", " -0.8"), ""),
        // A box of 2 × 1 × 1 cannot take a unit cube on its 2 × 1 face.
        (
            "E1216",
            "volume A = cube B2 | B2 B2 B2 | A1 | B2 B2 | V1\nvolume B = cube B2 | B2 B2 B2 | A1 | B2 B2 | V1\nvolume A face 1 edge 0 ~ volume B face 0 edge 0\nvolume B corners: 0 0 0, 2 0 0, 0 1 0, 2 1 0, 0 0 1, 2 0 1, 0 1 1, 2 1 1\n".to_string(),
            "",
        ),
    ];
    for (code_want, text, place) in cases {
        let p = d.join(format!("{code_want}.txt"));
        std::fs::write(&p, text).unwrap();
        let (code, _, err) = lacuna(&["measure", &p.to_string_lossy(), "--level", "1"]);
        assert_eq!(code, 2, "{code_want}: {err}");
        assert!(err.contains(code_want), "{code_want}: {err}");
        assert!(err.contains(place), "{code_want}: {err}");
    }
    let _ = std::fs::remove_dir_all(&d);
}

/// A face shared by two volumes is one face: its sub-faces seen from either side must be the same
/// polygons, at every level (THEORY §10, constraint/volume.rs). `fixtures/two-boxes.txt` stacks
/// two copies of one block (edges along x are B3, the others B2), so the assembly has exactly the
/// volume types of one box and the same unknowns; the shared square `B3 B2 B3 B2` can only add
/// equations. They must leave the system consistent (two stacked boxes with their regular
/// subdivision are a solution) and collapse nothing. A reading of the square turned by one edge
/// would pair B3 with B2 and is refused, so the pairing of the two readings is checked too.
#[test]
fn an_assembly_solves_with_its_shared_face_read_from_both_sides() {
    let solve = |path: &str| -> serde_json::Value {
        let (code, out, err) = lacuna(&["solve", path, "--degree", "1", "--json"]);
        assert_eq!(code, 0, "{err}");
        serde_json::from_str(&out).unwrap()
    };
    let d = common::scratch("volgeo-solve-assembly");
    let both = std::fs::read_to_string("fixtures/two-boxes.txt").unwrap();
    // Box A alone: the lines up to the end of its block.
    let one: String = both
        .lines()
        .take_while(|l| !l.starts_with("volume B"))
        .map(|l| format!("{l}\n"))
        .collect();
    let alone = d.join("one-box.txt");
    std::fs::write(&alone, one).unwrap();
    let a = solve(&alone.to_string_lossy());
    let ab = solve("fixtures/two-boxes.txt");
    assert_eq!(ab["consistent"], true);
    assert_eq!(ab["degeneracy_checked"], true);
    assert_eq!(ab["degenerate"].as_array().unwrap().len(), 0);
    assert_eq!(a["unknowns"], ab["unknowns"]);
    let n = |v: &serde_json::Value, k: &str| v[k].as_u64().unwrap();
    assert!(
        n(&ab, "equations") > n(&a, "equations"),
        "{} {}",
        ab["equations"],
        a["equations"]
    );
    assert!(n(&ab, "dof") <= n(&a, "dof"));
    let _ = std::fs::remove_dir_all(&d);
}
