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

fn scratch(what: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("lacuna-volgeo-{what}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A thick spherical shell pierced by k holes (one per face of the solid, each face's central
/// lacuna opening the cavity) is a handlebody of genus k − 1; its surface has Euler
/// characteristic 2 − 2(k − 1). The cube has k = 6: genus 5, χ = −8 (THEORY §10).
#[test]
fn render_a_volume_writes_a_checked_mesh_and_pictures() {
    let d = scratch("render");
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
    // At level 2 the default placement of this tetrahedron with Cantor edges folds (two
    // triangles cross): a mesh would not be the verified structure, so nothing is written and
    // the verdict is negative.
    let d = scratch("fold");
    let stl = d.join("t2.stl");
    let (code, _, err) = lacuna(&[
        "render",
        "tetrahedron C2 | B2 B2 B2 | A1 | B2 B2 | V1",
        "--level",
        "2",
        "--stl",
        &stl.to_string_lossy(),
    ]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("E1041"), "{err}");
    assert!(!stl.exists());
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
    let d = scratch("report");
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
