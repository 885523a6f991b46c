// Meshes of 3D automata (issue #14, brief autofin): `render X.aut --stl/--3mf` writes the open
// surface of the polygon leaves, and with `--thickness T` a closed shell. The written files are
// read back with readers that are not the writers (`stl_io`; `zip` and a minimal XML scan, in
// tests/common/mesh_files.rs) and their combinatorics counted here, independently of
// `lacuna::mesh::check`.
//
// Hand counts for fixtures/quad-patch-3d.aut at level 3: 4³ = 64 quad leaves on an 8 × 8 grid of
// the parameter square, so 9 × 9 = 81 distinct corners, 2 · 64 = 128 triangles (a fan of two per
// quad) and 4 · 8 = 32 boundary edges. The open surface is a disc: E = (3 · 128 + 32)/2 = 208,
// χ = 81 − 208 + 128 = 1. The shell doubles the sheet (162 vertices, 256 triangles) and adds two
// wall triangles per boundary edge (64): F = 320, E = 3 · 320 / 2 = 480, χ = 162 − 480 + 320 = 2,
// a sphere.

mod common;
use common::lacuna;
use common::mesh_files::{cross, model_xml, Read3};
use std::collections::HashMap;

/// Reads back the STL at `path` (which need not be closed).
fn read_stl(path: &std::path::Path) -> Read3 {
    let bytes = std::fs::read(path).expect("the STL was written");
    common::mesh_files::read_stl(&bytes, &path.display().to_string())
}

/// Directed edge counts: (edges in one triangle, edges in two with opposite directions, edges
/// traversed twice the same way or in more than two triangles).
fn edges(m: &Read3) -> (usize, usize, usize) {
    let mut dir: HashMap<(usize, usize), usize> = HashMap::new();
    for t in &m.triangles {
        for k in 0..3 {
            *dir.entry((t[k], t[(k + 1) % 3])).or_default() += 1;
        }
    }
    let mut und: HashMap<(usize, usize), (usize, usize)> = HashMap::new();
    for (&(a, b), &n) in &dir {
        let e = und.entry((a.min(b), a.max(b))).or_default();
        if a < b {
            e.0 += n;
        } else {
            e.1 += n;
        }
    }
    let (mut one, mut two, mut bad) = (0, 0, 0);
    for &(f, r) in und.values() {
        match (f, r) {
            (1, 0) | (0, 1) => one += 1,
            (1, 1) => two += 1,
            _ => bad += 1,
        }
    }
    (one, two, bad)
}

fn signed_volume(m: &Read3) -> f64 {
    m.triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|v| m.vertices[v].map(f64::from));
            a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                + a[2] * (b[0] * c[1] - b[1] * c[0])
        })
        .sum::<f64>()
        / 6.0
}

fn area(m: &Read3) -> f64 {
    m.triangles
        .iter()
        .map(|t| {
            let n = cross(t.map(|v| m.vertices[v].map(f64::from)));
            (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt() / 2.0
        })
        .sum()
}

#[test]
fn the_open_patch_is_a_disc_and_its_shell_a_sphere() {
    let d = common::scratch("autmesh-shell");
    let open = d.join("open.stl");
    let shell = d.join("shell.stl");
    let (code, _, err) = lacuna(&[
        "render",
        "quad-patch-3d",
        "--level",
        "3",
        "--stl",
        open.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("open"),
        "the open surface is said on stderr: {err}"
    );
    let (code, out, err) = lacuna(&[
        "render",
        "quad-patch-3d",
        "--level",
        "3",
        "--thickness",
        "2",
        "--stl",
        shell.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(!err.contains("open"), "{err}");
    assert!(out.contains("Euler characteristic 2"), "{out}");

    let o = read_stl(&open);
    assert_eq!((o.vertices.len(), o.triangles.len()), (81, 128));
    let (one, two, bad) = edges(&o);
    assert_eq!((one, two, bad), (32, 176, 0));
    assert_eq!(81 - (one + two) as i64 + 128, 1, "a disc");

    let s = read_stl(&shell);
    assert_eq!((s.vertices.len(), s.triangles.len()), (162, 320));
    let (one, two, bad) = edges(&s);
    assert_eq!(
        (one, two, bad),
        (0, 480, 0),
        "closed, consistently oriented"
    );
    assert_eq!(162 - 480 + 320, 2);
    // Outward, and the volume of a 2 mm shell is about 2 mm times its mid-surface's area (the
    // offset along normals changes it only by the curvature terms, small for a 100 mm patch).
    // The shell's two faces each have about that area; its rim is the patch's perimeter times
    // 2 mm (the perimeter taken on the open patch, whose scale differs from the mid-surface's by
    // the 2 % that --width leaves for the shell: a small error on a small term).
    let perimeter: f64 = {
        let mut count: HashMap<(usize, usize), usize> = HashMap::new();
        for t in &o.triangles {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                *count.entry((a.min(b), a.max(b))).or_default() += 1;
            }
        }
        count
            .iter()
            .filter(|(_, &n)| n == 1)
            .map(|(&(a, b), _)| {
                let (p, q) = (o.vertices[a], o.vertices[b]);
                (0..3)
                    .map(|d| (f64::from(p[d]) - f64::from(q[d])).powi(2))
                    .sum::<f64>()
                    .sqrt()
            })
            .sum()
    };
    let (v, a) = (signed_volume(&s), (area(&s) - 2.0 * perimeter) / 2.0);
    assert!(v > 0.0, "outward: {v}");
    assert!(
        (v / (2.0 * a) - 1.0).abs() < 0.02,
        "volume {v} against 2 × {a}"
    );
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn the_3mf_and_obj_shells_have_the_same_counts() {
    // Level 4: 16 × 16 quads, 17² = 289 corners, 512 triangles, 64 boundary edges; the shell has
    // 578 vertices and 2 · 512 + 2 · 64 = 1152 triangles.
    let d = common::scratch("autmesh-3mf");
    let mf = d.join("p.3mf");
    let obj = d.join("p.obj");
    let (code, _, err) = lacuna(&[
        "render",
        "quad-patch-3d",
        "--level",
        "4",
        "--thickness",
        "1/2",
        "--3mf",
        mf.to_str().unwrap(),
        "--obj",
        obj.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let model = model_xml(&std::fs::read(&mf).unwrap());
    assert!(model.contains(r#"unit="millimeter""#));
    assert_eq!(model.matches("<vertex ").count(), 578);
    assert_eq!(model.matches("<triangle ").count(), 1152);
    let text = std::fs::read_to_string(&obj).unwrap();
    assert_eq!(text.lines().filter(|l| l.starts_with("v ")).count(), 578);
    assert_eq!(text.lines().filter(|l| l.starts_with("f ")).count(), 1152);
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn an_automaton_without_polygons_has_no_mesh() {
    let (code, _, err) = lacuna(&["render", "cantor-set", "--stl", "-"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("E0720"), "{err}");
}

/// Debian's admesh, an independent STL checker, on the shell: one part, nothing to repair.
/// Ignored by a plain `cargo test` (it needs admesh).
#[test]
#[ignore]
fn admesh_finds_the_shell_closed() {
    let d = common::scratch("autmesh-admesh");
    let shell = d.join("shell.stl");
    let (code, _, err) = lacuna(&[
        "render",
        "quad-patch-3d",
        "--level",
        "4",
        "--thickness",
        "1",
        "--stl",
        shell.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(
        common::admesh_finds_nothing_to_repair(&shell, "quad-patch-3d shell"),
        "1152"
    );
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn exact_and_tolerance_identities_agree_on_the_patch() {
    // The two ways of identifying corners (exact coordinates in the field; floats within 10⁻⁹ of
    // the size) give the same surface at level 3: 81 vertices, 128 triangles (hand count above).
    let m = match lacuna::input::load_any("quad-patch-3d").unwrap() {
        lacuna::input::Loaded::Automaton { model, .. } => *model,
        lacuna::input::Loaded::Faces(_) => unreachable!(),
    };
    let r = lacuna::analysis::resolve(&m, &[], 10_000).unwrap();
    let ev = lacuna::geometry::Evaluator::new(&m, &r);
    let exact = lacuna::mesh::exact_automaton_surface(&m, &r, 3).expect("64 leaves");
    let floats = lacuna::mesh::automaton_surface(&ev, 3).expect("polygons");
    for s in [&exact, &floats] {
        assert_eq!((s.vertices.len(), s.triangles.len()), (81, 128));
        assert_eq!(s.boundary_edges().len(), 32);
    }
}

/// `render --claims` on a thickened automaton shell (issue #29): the claims are the figures of
/// lacuna's own check of the shell — the patch's shell is one sphere (a disc thickened: χ 2,
/// genus 0) — and `check-mesh`, which shares no code with the writer, re-derives them from the
/// file. The open surface is no solid: `--claims` without `--thickness` is refused (exit 2).
#[test]
fn a_shell_checks_with_the_claims_render_writes() {
    let d = common::scratch("autmesh-claims");
    let (stl, claims) = (d.join("patch.stl"), d.join("patch.json"));
    let p = |x: &std::path::Path| x.to_string_lossy().to_string();
    let (code, out, err) = lacuna(&[
        "render",
        "quad-patch-3d",
        "--level",
        "2",
        "--thickness",
        "1",
        "--stl",
        &p(&stl),
        "--claims",
        &p(&claims),
    ]);
    assert_eq!(code, 0, "{out}{err}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&claims).unwrap()).unwrap();
    assert_eq!(json["parts"], 1);
    assert_eq!(json["euler"], 2);
    assert_eq!(json["genus"], 0);
    let m = read_stl(&stl);
    assert_eq!(json["triangles"], m.triangles.len());
    let (code, out, err) = lacuna(&["check-mesh", &p(&stl), "--claims", &p(&claims)]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains("expected χ (claims): 2, found 2"), "{out}");
    // A forged claim (a handle the shell does not have) is caught.
    let forged = d.join("forged.json");
    std::fs::write(
        &forged,
        std::fs::read_to_string(&claims)
            .unwrap()
            .replace("\"genus\": 0,", "\"genus\": 1,"),
    )
    .unwrap();
    let (code, out, _) = lacuna(&["check-mesh", &p(&stl), "--claims", &p(&forged)]);
    assert_eq!(code, 1, "{out}");
    let (code, _, err) = lacuna(&[
        "render",
        "quad-patch-3d",
        "--stl",
        &p(&d.join("open.stl")),
        "--claims",
        &p(&d.join("open.json")),
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--thickness"), "{err}");
    let _ = std::fs::remove_dir_all(&d);
}

/// The thickened shell's walls against the printer (issue #30): its two sides are the surface
/// moved by ± T/2 along the normals, so facing triangles lie about T apart and the wall bound
/// is at most T; the patch bends gently, so it is not far below (above T/2). With T below the
/// resolution, `--strict` fails with E1042 (exit 1) and nothing is written.
#[test]
fn the_shells_wall_bound_is_its_thickness_and_strict_refuses_a_thin_one() {
    let d = common::scratch("autmesh-walls");
    let stl = d.join("patch.stl").to_string_lossy().to_string();
    let (code, out, err) = lacuna(&[
        "render",
        "quad-patch-3d",
        "--level",
        "3",
        "--thickness",
        "1",
        "--stl",
        &stl,
    ]);
    assert_eq!(code, 0, "{err}");
    let line = out
        .lines()
        .find(|l| l.starts_with("printability: wall thickness ≥ "))
        .unwrap_or_else(|| panic!("{out}"));
    let w: f64 = line["printability: wall thickness ≥ ".len()..]
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(w <= 1.0 && w > 0.5, "{line}");
    let _ = std::fs::remove_file(&stl);
    let (code, _, err) = lacuna(&[
        "render",
        "quad-patch-3d",
        "--level",
        "3",
        "--thickness",
        "0.3",
        "--stl",
        &stl,
        "--strict",
    ]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("E1042"), "{err}");
    assert!(!std::path::Path::new(&stl).exists());
    let _ = std::fs::remove_dir_all(&d);
}

/// `--width` sizes what is printed (issue #30): the x extent of the thickened shell, read back
/// from the STL, is the width asked for, as the open surface's is; the shell's mid-surface is
/// then narrower. A shell wider than the width is refused.
#[test]
fn the_width_is_the_printed_shell_s_extent() {
    let d = common::scratch("autmesh-width");
    let extent = |m: &Read3| {
        let xs = m.vertices.iter().map(|v| f64::from(v[0]));
        xs.clone().fold(f64::MIN, f64::max) - xs.fold(f64::MAX, f64::min)
    };
    for (thickness, width) in [(None, "80"), (Some("2"), "80"), (Some("5"), "60")] {
        let path = d.join("w.stl");
        let mut args = vec![
            "render",
            "quad-patch-3d",
            "--level",
            "3",
            "--width",
            width,
            "--stl",
            path.to_str().unwrap(),
        ];
        if let Some(t) = thickness {
            args.extend(["--thickness", t]);
        }
        let (code, _, err) = lacuna(&args);
        assert_eq!(code, 0, "{err}");
        let x = extent(&read_stl(&path));
        let want: f64 = width.parse().unwrap();
        assert!(
            (x - want).abs() < 1e-3,
            "{thickness:?}: x extent {x} for --width {want}"
        );
    }
    let (code, _, err) = lacuna(&[
        "render",
        "quad-patch-3d",
        "--level",
        "2",
        "--width",
        "1",
        "--thickness",
        "5",
        "--stl",
        d.join("x.stl").to_str().unwrap(),
    ]);
    assert_ne!(code, 0, "{err}");
    std::fs::remove_dir_all(&d).ok();
}
