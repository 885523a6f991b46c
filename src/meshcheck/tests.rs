//! Hand-made meshes with hand-derived figures. Each mesh is written as binary STL (the format
//! the checker reads), so the readers are exercised too; a few go through ASCII STL and 3MF.

use super::*;
use std::io::Write;

type Tri = [usize; 3];

fn binary_stl(v: &[[f32; 3]], t: &[Tri]) -> Vec<u8> {
    let mut out = vec![b' '; 80];
    out.extend((t.len() as u32).to_le_bytes());
    for tri in t {
        out.extend([0u8; 12]);
        for &i in tri {
            for x in v[i] {
                out.extend(x.to_le_bytes());
            }
        }
        out.extend([0u8; 2]);
    }
    out
}

fn ascii_stl(v: &[[f32; 3]], t: &[Tri]) -> Vec<u8> {
    let mut s = String::from("solid test\n");
    for tri in t {
        s += "facet normal 0 0 0\n outer loop\n";
        for &i in tri {
            s += &format!("  vertex {} {} {}\n", v[i][0], v[i][1], v[i][2]);
        }
        s += " endloop\nendfacet\n";
    }
    (s + "endsolid test\n").into_bytes()
}

/// A 3MF package with one object per list of triangles (all over the same vertices).
fn threemf(v: &[[f32; 3]], objects: &[&[Tri]]) -> Vec<u8> {
    let mut z = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let o = zip::write::SimpleFileOptions::default();
    z.start_file("3D/3dmodel.model", o).unwrap();
    let mut m = String::from(
        r#"<?xml version="1.0"?><model unit="millimeter" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02"><resources>"#,
    );
    for (k, tris) in objects.iter().enumerate() {
        m += &format!(r#"<object id="{}" type="model"><mesh><vertices>"#, k + 1);
        for p in v {
            m += &format!(r#"<vertex x="{}" y="{}" z="{}"/>"#, p[0], p[1], p[2]);
        }
        m += "</vertices><triangles>";
        for t in tris.iter() {
            m += &format!(r#"<triangle v1="{}" v2="{}" v3="{}"/>"#, t[0], t[1], t[2]);
        }
        m += "</triangles></mesh></object>";
    }
    m += "</resources><build>";
    for k in 0..objects.len() {
        m += &format!(r#"<item objectid="{}"/>"#, k + 1);
    }
    m += "</build></model>";
    z.write_all(m.as_bytes()).unwrap();
    z.finish().unwrap().into_inner()
}

fn run(bytes: &[u8]) -> Report {
    check(bytes, "test", &Options::default()).unwrap()
}

/// The unit tetrahedron, counter-clockwise seen from outside: V 4, E 6, F 4, χ 2, volume 1/6.
const TETRA_V: [[f32; 3]; 4] = [[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]];
const TETRA_T: [Tri; 4] = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]];

fn shifted(v: &[[f32; 3]], d: [f32; 3]) -> Vec<[f32; 3]> {
    v.iter()
        .map(|p| [p[0] + d[0], p[1] + d[1], p[2] + d[2]])
        .collect()
}

/// Two meshes side by side (the second's vertex indices after the first's).
fn both(a: (&[[f32; 3]], &[Tri]), b: (&[[f32; 3]], &[Tri])) -> (Vec<[f32; 3]>, Vec<Tri>) {
    let mut v = a.0.to_vec();
    v.extend_from_slice(b.0);
    let mut t = a.1.to_vec();
    t.extend(b.1.iter().map(|x| x.map(|i| i + a.0.len())));
    (v, t)
}

fn figures(r: &Report) -> Vec<(u64, u64, u64, i64, Option<i64>)> {
    r.parts
        .iter()
        .map(|p| (p.vertices, p.edges, p.triangles, p.euler, p.genus))
        .collect()
}

#[test]
fn a_tetrahedron_is_a_sphere_of_volume_one_sixth() {
    let r = run(&binary_stl(&TETRA_V, &TETRA_T));
    assert!(r.passed(), "{}", r.to_text());
    assert_eq!(r.format, Format::BinaryStl);
    assert_eq!(figures(&r), vec![(4, 6, 4, 2, Some(0))]);
    assert_eq!(
        r.parts[0].volume.as_ref().unwrap().to_string(),
        "1/6",
        "det of the three unit vectors over 6"
    );
    // Every pair of its 4 triangles shares an edge, and their boxes meet: C(4, 2) = 6 pairs.
    assert_eq!(r.pairs_tested, 6);
    // The same from ASCII STL and from 3MF.
    for bytes in [
        ascii_stl(&TETRA_V, &TETRA_T),
        threemf(&TETRA_V, &[&TETRA_T]),
    ] {
        let s = run(&bytes);
        assert!(s.passed(), "{}", s.to_text());
        assert_eq!(figures(&s), figures(&r));
    }
}

#[test]
fn a_cube_of_side_ten_encloses_a_thousand() {
    // Corner i at (10·(i & 1), 10·(i >> 1 & 1), 10·(i >> 2)); two triangles per face, outward.
    let v: Vec<[f32; 3]> = (0..8)
        .map(|i| {
            [
                10. * (i & 1) as f32,
                10. * (i >> 1 & 1) as f32,
                10. * (i >> 2) as f32,
            ]
        })
        .collect();
    let quads = [
        [0, 2, 3, 1], // z = 0, seen from below
        [4, 5, 7, 6], // z = 10
        [0, 1, 5, 4], // y = 0
        [2, 6, 7, 3], // y = 10
        [0, 4, 6, 2], // x = 0
        [1, 3, 7, 5], // x = 10
    ];
    let t: Vec<Tri> = quads
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .collect();
    let r = run(&binary_stl(&v, &t));
    assert!(r.passed(), "{}", r.to_text());
    // V 8, E 12 cube edges + 6 diagonals = 18, F 12: χ 2.
    assert_eq!(figures(&r), vec![(8, 18, 12, 2, Some(0))]);
    assert_eq!(r.parts[0].volume.as_ref().unwrap().to_string(), "1000");
    assert!(r.to_text().contains("volume 1000 mm³ (outward)"));
    // Expectations: χ 2 holds, 3 parts does not (exit 1, naming it).
    let o = Options {
        expect_euler: Some(2),
        expect_parts: Some(3),
        ..Options::default()
    };
    let r = check(&binary_stl(&v, &t), "cube.stl", &o).unwrap();
    assert!(r.checks_pass() && !r.passed());
    assert!(r
        .verdict()
        .contains("EXPECTATION FAILED (parts (--expect-parts))"));
}

/// A torus from a 4 × 4 grid of quads: the centre line a square of "radius" 4, the cross-section
/// a square of radius 1 (cos and sin of multiples of 90° are exact).
fn torus() -> (Vec<[f32; 3]>, Vec<Tri>) {
    let (cs, sn) = ([1., 0., -1., 0.], [0., 1., 0., -1.]);
    let at = |i: usize, j: usize| i % 4 * 4 + j % 4;
    let mut v = Vec::new();
    for i in 0..4 {
        for j in 0..4 {
            let rad = 4.0 + cs[j];
            v.push([rad * cs[i], rad * sn[i], sn[j]]);
        }
    }
    let mut t = Vec::new();
    for i in 0..4 {
        for j in 0..4 {
            // (∂u, ∂v) is outward at u = v = 0: counter-clockwise seen from outside.
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            t.push([a, b, c]);
            t.push([a, c, d]);
        }
    }
    (v, t)
}

#[test]
fn a_torus_of_sixteen_quads_has_genus_one() {
    let (v, t) = torus();
    let r = run(&binary_stl(&v, &t));
    assert!(r.passed(), "{}", r.to_text());
    // V 16, E 16·3 = 48 (each quad adds two grid edges and a diagonal), F 32: χ 0, genus 1.
    assert_eq!(figures(&r), vec![(16, 48, 32, 0, Some(1))]);
    assert!(num_traits::Signed::is_positive(
        r.parts[0].volume.as_ref().unwrap()
    ));
}

#[test]
fn two_disjoint_tetrahedra_are_two_parts() {
    let far = shifted(&TETRA_V, [5., 0., 0.]);
    let (v, t) = both((&TETRA_V, &TETRA_T), (&far, &TETRA_T));
    let r = run(&binary_stl(&v, &t));
    assert!(r.passed(), "{}", r.to_text());
    assert_eq!(figures(&r), vec![(4, 6, 4, 2, Some(0)); 2]);
    assert_eq!(r.euler(), 4);
    assert_eq!(r.parts[1].first_triangle, 4);
    // The same as two 3MF objects.
    let mut v2 = TETRA_V.to_vec();
    v2.extend(&far);
    let second: Vec<Tri> = TETRA_T.iter().map(|x| x.map(|i| i + 4)).collect();
    let s = run(&threemf(&v2, &[&TETRA_T, &second]));
    assert!(s.passed(), "{}", s.to_text());
    assert_eq!(figures(&s), figures(&r));
}

#[test]
fn a_flipped_triangle_fails_orientation_naming_its_edges() {
    let mut t = TETRA_T;
    t[1] = [0, 3, 1];
    let r = run(&binary_stl(&TETRA_V, &t));
    assert!(!r.passed());
    // Its three edges are each run the same way by it and by a neighbour.
    assert_eq!(r.edges.count.get("edge run one way twice"), Some(&3));
    assert!(
        r.links.is_none(),
        "links are not checked on open or flipped edges"
    );
    let f = &r.edges.examples[0];
    assert!(f.triangles.contains(&1), "{f:?}");
    assert!(f.message.contains("triangle 1"), "{}", f.message);
    // Parts and χ are still counted; genus and volume are not defined.
    assert_eq!(figures(&r), vec![(4, 6, 4, 2, None)]);
    assert!(r
        .verdict()
        .contains("FAILED (not closed or not consistently oriented)"));
}

#[test]
fn a_missing_triangle_leaves_three_open_edges() {
    let r = run(&binary_stl(&TETRA_V, &TETRA_T[..3]));
    assert!(!r.passed());
    assert_eq!(r.edges.count.get("open edge"), Some(&3));
    // V 4, E 6, F 3: χ 1, a disc.
    assert_eq!(figures(&r), vec![(4, 6, 3, 1, None)]);
    assert!(r.parts[0].volume.is_none());
}

#[test]
fn two_tetrahedra_touching_at_a_vertex_pinch_it() {
    // The second is the first reflected through the origin (det −1: its triangles reversed).
    let mirror: Vec<[f32; 3]> = TETRA_V.iter().map(|p| p.map(|x| -x)).collect();
    let reversed: Vec<Tri> = TETRA_T.iter().map(|t| [t[0], t[2], t[1]]).collect();
    let (v, t) = both((&TETRA_V, &TETRA_T), (&mirror, &reversed));
    let r = run(&binary_stl(&v, &t));
    assert!(!r.passed());
    assert!(r.edges.passed(), "{}", r.to_text());
    let links = r.links.as_ref().unwrap();
    assert_eq!(links.count.get("pinched vertex"), Some(&1));
    assert_eq!(links.examples[0].coordinates, vec![[0.0, 0.0, 0.0]]);
    assert!(links.examples[0].message.contains("2 fans"));
    // They meet only at that vertex: no crossing. Two parts (by edges), 7 vertices in all.
    assert!(r.crossings.passed(), "{}", r.to_text());
    assert_eq!(r.vertices, 7);
    assert_eq!(figures(&r), vec![(4, 6, 4, 2, None); 2]);
}

#[test]
fn two_crossing_tetrahedra_fail_the_crossing_test() {
    // The second has a corner at (1/4, 1/4, 1/4), inside the first.
    let inside = shifted(&TETRA_V, [0.25, 0.25, 0.25]);
    let (v, t) = both((&TETRA_V, &TETRA_T), (&inside, &TETRA_T));
    let r = run(&binary_stl(&v, &t));
    assert!(r.edges.passed() && r.links.as_ref().unwrap().passed());
    assert!(!r.crossings.passed());
    assert!(!r.passed());
    let f = &r.crossings.examples[0];
    assert!(f.triangles[0] < 4 && f.triangles[1] >= 4, "{f:?}");
    assert!(r.verdict().contains("crossing triangles"));
}

#[test]
fn folds_coincidences_and_touches_are_crossings() {
    // A flat "pillow": one triangle and its reverse. Closed, oriented, χ 2 — and coincident.
    let v = [[0f32, 0., 0.], [1., 0., 0.], [0., 1., 0.]];
    let r = run(&binary_stl(&v, &[[0, 1, 2], [0, 2, 1]]));
    assert!(r.manifold(), "{}", r.to_text());
    assert!(r.crossings.examples[0].message.contains("coincide"));
    assert!(!r.orientation.passed(), "a flat part encloses no volume");
    // A tetrahedron touching another's face with a corner: they share no vertex and meet.
    // Its corner 0 at (1/4, 1/4, 1/2) is on the slanted face x + y + z = 1 of the first; its
    // other corners have x + y + z > 1.
    let lifted = shifted(&TETRA_V, [0.25, 0.25, 0.5]);
    let (v, t) = both((&TETRA_V, &TETRA_T), (&lifted, &TETRA_T));
    let r = run(&binary_stl(&v, &t));
    assert!(!r.crossings.passed(), "{}", r.to_text());
    assert!(r.crossings.examples[0].message.contains("share no vertex"));
    // Two triangles of one plane sharing the edge 0–1, both on its side y > 0: folded flat.
    let v = [[0f32, 0., 0.], [1., 0., 0.], [0., 1., 0.], [1., 1., 0.]];
    let r = run(&binary_stl(&v, &[[0, 1, 2], [1, 0, 3]]));
    assert!(
        r.crossings.examples[0].message.contains("same side"),
        "{}",
        r.to_text()
    );
    // On opposite sides (corner 3 at y = −1) they only share the edge.
    let v = [[0f32, 0., 0.], [1., 0., 0.], [0., 1., 0.], [1., -1., 0.]];
    assert!(run(&binary_stl(&v, &[[0, 1, 2], [1, 0, 3]]))
        .crossings
        .passed());
    // Two fans of one plane at the vertex 0 that overlap near it: the side 1–2 of the first,
    // on x + y = 2, passes through the second at (4/3, 2/3).
    let v = [
        [0f32, 0., 0.],
        [2., 0., 0.],
        [0., 2., 0.],
        [2., 1., 0.],
        [1., 2., 0.],
    ];
    let r = run(&binary_stl(&v, &[[0, 1, 2], [0, 3, 4]]));
    assert!(
        r.crossings.examples[0].message.contains("share the vertex"),
        "{}",
        r.to_text()
    );
    // Rotated away from the first (corners at y < 0) they share only the vertex.
    let v = [
        [0f32, 0., 0.],
        [2., 0., 0.],
        [0., 2., 0.],
        [2., -1., 0.],
        [1., -2., 0.],
    ];
    assert!(run(&binary_stl(&v, &[[0, 1, 2], [0, 3, 4]]))
        .crossings
        .passed());
}

#[test]
fn bad_input_is_an_error_not_a_verdict() {
    let good = binary_stl(&TETRA_V, &TETRA_T);
    let e = check(&good[..good.len() - 10], "t.stl", &Options::default()).unwrap_err();
    assert_eq!(e.code(), "E1501");
    assert!(e.to_string().contains("4 triangles"), "{e}");
    let e = check(&binary_stl(&TETRA_V, &[]), "t.stl", &Options::default()).unwrap_err();
    assert_eq!(e.code(), "E1501", "no triangle: nothing to check");
    let e = check(b"PK\x03\x04 nothing", "t.3mf", &Options::default()).unwrap_err();
    assert_eq!(e.code(), "E1503");
    let mut nan = good.clone();
    nan[84 + 12..84 + 16].copy_from_slice(&f32::NAN.to_le_bytes());
    assert_eq!(
        check(&nan, "t.stl", &Options::default())
            .unwrap_err()
            .code(),
        "E1502"
    );
    let limited = Options {
        max_triangles: 3,
        ..Options::default()
    };
    let e = check(&good, "t.stl", &limited).unwrap_err();
    assert_eq!(e.code(), "E0501");
    assert!(e.to_string().contains("not a verdict"), "{e}");
}

#[test]
fn claims_are_compared() {
    let claims = Claims {
        format: CLAIMS_FORMAT.into(),
        version: CLAIMS_VERSION,
        source: "a tetrahedron".into(),
        meshes: vec!["tetra.stl".into()],
        triangles: 4,
        parts: Some(1),
        euler: Some(2),
        genus: Some(0),
        per_part: Some(vec![PartClaim { euler: 2, genus: 0 }]),
    };
    let back = Claims::parse(&claims.to_json(), "c.json").unwrap();
    assert_eq!(back, claims);
    let o = Options {
        claims: Some(claims.clone()),
        ..Options::default()
    };
    let r = check(&binary_stl(&TETRA_V, &TETRA_T), "dir/tetra.stl", &o).unwrap();
    assert!(r.passed(), "{}", r.to_text());
    assert_eq!(r.expectations.len(), 5);
    assert!(r.notes.is_empty(), "{:?}", r.notes);
    let wrong = Claims {
        per_part: Some(vec![PartClaim { euler: 0, genus: 1 }]),
        ..claims
    };
    let o = Options {
        claims: Some(wrong),
        ..Options::default()
    };
    let r = check(&binary_stl(&TETRA_V, &TETRA_T), "other.stl", &o).unwrap();
    assert!(!r.passed());
    assert!(r.to_text().contains("DIFFERS"));
    assert_eq!(r.notes.len(), 1, "a renamed file is a note");
    let e = Claims::parse(r#"{"format": "x"}"#, "c.json").unwrap_err();
    assert_eq!(e.code(), "E1504");
}
