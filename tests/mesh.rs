// Printable solids (issue #13, THEORY §11): the written STL (binary and ASCII) and 3MF are read back
// with readers that are not the writers (the `stl_io` crate; the `zip` crate and a minimal XML
// scan, in tests/common/mesh_files.rs) and checked here, independently of `lacuna::mesh::check`: one part per
// component, every edge in exactly two triangles with opposite orientations, no facet wound
// against its normal, outward orientation, and the Euler characteristic 2 − 2·holes with the
// holes derived by hand below.

mod common;
use common::inst;
use common::mesh_files::{
    attr, attribute, binary_stl_triangles, model_xml, read_closed_stl, Read3,
};
use lacuna::mesh::{build, Size, Solid};
use lacuna::{geometry::instantiate, geometry::Instance, geometry::InstantiateOptions};
use std::collections::HashMap;
use std::io::Cursor;

fn solid(i: &Instance, level: u32) -> Solid {
    build(i, level, 4, Size::default())
        .unwrap_or_else(|e| panic!("{} level {level}: {} {e}", i.name, e.code()))
}

/// Per connected piece: (V, E, F). Panics unless every directed edge occurs once and its reverse
/// once (each edge in exactly two triangles, oppositely oriented) and every piece encloses a
/// positive volume (outward orientation).
fn pieces(m: &Read3, what: &str) -> Vec<(usize, usize, usize)> {
    let mut directed: HashMap<(usize, usize), usize> = HashMap::new();
    for t in &m.triangles {
        for k in 0..3 {
            *directed.entry((t[k], t[(k + 1) % 3])).or_default() += 1;
        }
    }
    for (&(a, b), &n) in &directed {
        assert_eq!(
            n, 1,
            "{what}: edge {a}-{b} traversed {n} times the same way"
        );
        assert_eq!(
            directed.get(&(b, a)),
            Some(&1),
            "{what}: edge {a}-{b} is not in exactly two opposite triangles"
        );
    }
    let mut parent: Vec<usize> = (0..m.vertices.len()).collect();
    fn find(p: &mut [usize], mut x: usize) -> usize {
        while p[x] != x {
            p[x] = p[p[x]];
            x = p[x];
        }
        x
    }
    for t in &m.triangles {
        for k in 1..3 {
            let (a, b) = (find(&mut parent, t[0]), find(&mut parent, t[k]));
            parent[a] = b;
        }
    }
    let mut by_root: HashMap<usize, (std::collections::HashSet<usize>, usize, usize, f64)> =
        HashMap::new();
    for t in &m.triangles {
        let r = find(&mut parent, t[0]);
        let e = by_root.entry(r).or_default();
        e.0.extend(t.iter().copied());
        e.1 += 3; // directed edges: two per edge
        e.2 += 1;
        let [a, b, c] = t.map(|v| m.vertices[v].map(f64::from));
        e.3 += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
            + a[2] * (b[0] * c[1] - b[1] * c[0]);
    }
    let mut out: Vec<(usize, usize, usize)> = by_root
        .into_values()
        .map(|(v, d, f, vol)| {
            assert!(vol > 0.0, "{what}: a piece encloses volume {vol} (inward)");
            (v.len(), d / 2, f)
        })
        .collect();
    out.sort();
    out
}

fn euler((v, e, f): (usize, usize, usize)) -> i64 {
    v as i64 - e as i64 + f as i64
}

/// Reads a 3MF package with the `zip` crate and scans its model: the unit and, per object, its
/// mesh.
fn read_3mf(bytes: &[u8]) -> (String, Vec<Read3>) {
    let xml = model_xml(bytes);
    let model = &xml[xml.find("<model").unwrap()..];
    let unit = attr(&model[..model.find('>').unwrap()], "unit").to_string();
    let mut objects = Vec::new();
    for obj in xml.split("<object ").skip(1) {
        let obj = &obj[..obj.find("</object>").expect("closed object")];
        let els = |tag: &str| -> Vec<String> {
            obj.split(&format!("<{tag} "))
                .skip(1)
                .map(|s| format!(" {}", &s[..s.find("/>").unwrap()]))
                .collect()
        };
        let vertices = els("vertex")
            .iter()
            .map(|e| ["x", "y", "z"].map(|k| attr(e, k).parse::<f32>().unwrap()))
            .collect();
        let triangles = els("triangle")
            .iter()
            .map(|e| ["v1", "v2", "v3"].map(|k| attr(e, k).parse::<usize>().unwrap()))
            .collect();
        objects.push(Read3 {
            vertices,
            triangles,
        });
    }
    (unit, objects)
}

/// Writes the solid in binary STL, ASCII STL and 3MF, reads each back and checks it has the
/// components and Euler characteristics `expected` (sorted).
fn check_written(s: &Solid, expected_euler: &[i64], what: &str) {
    let mut bin = Vec::new();
    lacuna::mesh::stl::write_binary(s, &mut bin).unwrap();
    assert_ne!(
        &bin[..5],
        b"solid",
        "{what}: a binary STL must not start with `solid`"
    );
    let mut ascii = Vec::new();
    lacuna::mesh::stl::write_ascii(s, &mut ascii).unwrap();
    for (bytes, kind) in [(&bin, "binary STL"), (&ascii, "ASCII STL")] {
        let m = read_closed_stl(bytes, &format!("{what} {kind}"));
        let p = pieces(&m, &format!("{what} {kind}"));
        let mut eu: Vec<i64> = p.iter().map(|&x| euler(x)).collect();
        eu.sort();
        assert_eq!(eu, expected_euler, "{what} {kind}: Euler characteristics");
    }
    let mut mf = Cursor::new(Vec::new());
    lacuna::mesh::threemf::write(s, &mut mf).unwrap();
    let (unit, objects) = read_3mf(mf.get_ref());
    assert_eq!(unit, "millimeter", "{what} 3MF unit");
    assert_eq!(
        objects.len(),
        expected_euler.len(),
        "{what}: one 3MF object per component"
    );
    let mut eu: Vec<i64> = objects
        .iter()
        .map(|o| {
            let p = pieces(o, &format!("{what} 3MF"));
            assert_eq!(p.len(), 1, "{what}: a 3MF object is one piece");
            euler(p[0])
        })
        .collect();
    eu.sort();
    assert_eq!(eu, expected_euler, "{what} 3MF: Euler characteristics");
}

#[test]
fn f0_levels_0_to_4_read_back_with_the_exact_topology() {
    // By hand: F0 = C2 B2 C2 B2 C2 B2 | Ea = C2, El = B2, Ec = B2 | A1 subdivides into six F0s, so
    // level k has 6^k cells. Holes: each subdivided cell opens its central lacuna, and each C2
    // edge shared by two cells opens one hole (its gap seen from both sides); a gap on a free edge
    // is a notch. Lacunas and gap sides are B2, so the only free C2 edges are the 3·2^j pieces of
    // the outer boundary, and of the 3·6^j C2 edge-sides at level j, (3·6^j − 3·2^j)/2 are shared:
    // h_k = Σ_{j<k} [6^j + (3·6^j − 3·2^j)/2] = 0, 1, 13, 97, 625. One component.
    let i = inst("F0");
    let mut h = 0i64;
    for k in 0..=4u32 {
        let s = solid(&i, k);
        assert_eq!(s.cells, 6u64.pow(k), "F0 level {k}: cells");
        assert_eq!(s.parts.len(), 1);
        check_written(&s, &[2 - 2 * h], &format!("F0 level {k}"));
        let j = k;
        h += 6i64.pow(j) + (3 * 6i64.pow(j) - 3 * 2i64.pow(j)) / 2;
    }
    assert_eq!(h, 3841, "the recurrence continued to level 5");
}

#[test]
fn triangle_delayed_and_two_quads_read_back_with_the_exact_topology() {
    // triangle-C2 (fixture header): T → 3 H; H → 4 P5 + 2 Q6 + H; Q6 → 4 P5 + 2 Q6; P5 → 5 P5;
    // N^C = 1, 3, 21. No type is delayed, and every C2 edge is a piece of the triangle's free
    // boundary (Ea, El, Ec are B2): every gap is a notch, so h_k = Σ_{j<k} N^C_j = 0, 1, 4, 25.
    // delayed-B2-C2: X = B2 C2^2 → 2 S4 + U (three sub-faces joined by three C2 spokes); S4 → 4
    // G6, U → 2 G6 + 2 V7. Level 1: X's lacuna, 1. Level 2: + 3 lacunas + 3 shared C2 spokes =
    // 7. Level 3: + 12 lacunas + shared C2 edges at level 2: of 10·3 (G6) + 2·4 (V7) = 38
    // C2 edge-sides, 2 are the pieces of the outer C2^2: (38 − 2)/2 = 18, so 37.
    // two-quads: two C2 B2 C2 B2 glued along a B2 edge, each → 4 F0s. Level 1: 2; level 2: + 8
    // lacunas + 8 shared spokes = 18; level 3: + 48 + (48·3 − 2·2·4)/2 = 64 → 130.
    for (name, holes) in [
        ("triangle-C2", [0i64, 1, 4, 25]),
        ("delayed-B2-C2", [0, 1, 7, 37]),
        ("two-quads", [0, 2, 18, 130]),
    ] {
        let i = inst(name);
        for (k, h) in holes.iter().enumerate() {
            let s = solid(&i, k as u32);
            check_written(&s, &[2 - 2 * h], &format!("{name} level {k}"));
        }
    }
}

#[test]
fn two_faces_apart_are_two_parts() {
    // Two F0 faces, nothing glued: two components, each with F0's holes (0, 1, 13).
    let text =
        "face 0: C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A1\nface 1: C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A1\n";
    let input = lacuna::input::Input {
        name: "two-apart".into(),
        assembly: lacuna::input::parse_text(&lacuna::Source {
            name: "two-apart".into(),
            text: text.into(),
        })
        .unwrap(),
    };
    let i = instantiate(&input, &InstantiateOptions::default()).unwrap();
    for (k, h) in [0i64, 1, 13].iter().enumerate() {
        let s = solid(&i, k as u32);
        assert_eq!(s.parts.len(), 2);
        assert!(s.parts.iter().all(|p| p.holes == Some(*h as u64)));
        check_written(&s, &[2 - 2 * h, 2 - 2 * h], &format!("two apart level {k}"));
    }
}

#[test]
fn obj_has_triangles_only_and_one_object_per_part() {
    let s = solid(&inst("two-quads"), 2);
    let mut buf = Vec::new();
    lacuna::mesh::obj::write(&s, &mut buf).unwrap();
    let text = String::from_utf8(buf).unwrap();
    let faces: Vec<&str> = text.lines().filter(|l| l.starts_with("f ")).collect();
    assert!(faces.iter().all(|f| f.split_whitespace().count() == 4));
    assert_eq!(faces.len(), s.triangle_count());
    assert_eq!(text.lines().filter(|l| l.starts_with("o ")).count(), 1);
    let v = text.lines().filter(|l| l.starts_with("v ")).count();
    let m = Read3 {
        vertices: text
            .lines()
            .filter(|l| l.starts_with("v "))
            .map(|l| {
                let x: Vec<f32> = l[2..].split(' ').map(|x| x.parse().unwrap()).collect();
                [x[0], x[1], x[2]]
            })
            .collect(),
        triangles: faces
            .iter()
            .map(|f| {
                let x: Vec<usize> = f[2..].split(' ').map(|x| x.parse().unwrap()).collect();
                [x[0] - 1, x[1] - 1, x[2] - 1]
            })
            .collect(),
    };
    assert_eq!(m.vertices.len(), v);
    assert_eq!(pieces(&m, "two-quads OBJ").len(), 1);
}

#[test]
fn sizes_are_millimetres() {
    let i = inst("F0");
    let s = build(
        &i,
        1,
        4,
        Size {
            width: 50.0,
            thickness: 3.0,
        },
    )
    .unwrap();
    let (mut lo, mut hi) = ([f32::MAX; 3], [f32::MIN; 3]);
    for v in &s.parts[0].vertices {
        for k in 0..3 {
            lo[k] = lo[k].min(v[k]);
            hi[k] = hi[k].max(v[k]);
        }
    }
    assert_eq!((lo[2], hi[2]), (0.0, 3.0));
    // The level-0 face spans x from 0 to 50 mm; level 1 keeps its corners.
    assert!(
        lo[0] >= 0.0 && hi[0] <= 50.0 && hi[0] > 49.0,
        "{lo:?} {hi:?}"
    );
}

#[test]
fn crossing_cells_are_refused_and_nothing_is_written() {
    // measure says NOT VERIFIED for min-lacuna=0.6 at level 3: render must not write the STL.
    let dir = common::scratch("mesh");
    let path = dir.join("crossing.stl");
    let p = path.to_str().unwrap();
    let (code, _, err) = common::lacuna(&[
        "render",
        "F0",
        "--level",
        "3",
        "--goal",
        "min-lacuna=0.6",
        "--stl",
        p,
    ]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("E1041"), "{err}");
    assert!(!path.exists(), "a file was written");
    // The same at 0.5 verifies and is written, with the printability report.
    let (code, out, err) = common::lacuna(&[
        "render",
        "F0",
        "--level",
        "3",
        "--goal",
        "min-lacuna=0.5",
        "--stl",
        p,
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("printability at level 3") && out.contains("wrote"),
        "{out}"
    );
    let bytes = std::fs::read(&path).unwrap();
    assert_eq!(
        pieces(&read_closed_stl(&bytes, "min-lacuna=0.5"), "min-lacuna=0.5").len(),
        1
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn strict_resolution_is_a_failure_and_bad_sizes_are_refused() {
    // F0 level 4 at 100 mm: its smallest holes are well under a millimetre.
    let (code, out, err) = common::lacuna(&[
        "measure",
        "F0",
        "--level",
        "2",
        "--resolution",
        "5",
        "--strict",
        "--raster",
        "256",
    ]);
    assert_eq!(code, 1, "{out}{err}");
    assert!(err.contains("E1042"), "{err}");
    let (code, out, _) = common::lacuna(&[
        "measure",
        "F0",
        "--level",
        "2",
        "--resolution",
        "5",
        "--raster",
        "256",
    ]);
    assert_eq!(code, 0);
    assert!(out.contains("warning: E1042"), "{out}");
    let (code, _, err) = common::lacuna(&[
        "render",
        "F0",
        "--level",
        "1",
        "--stl",
        "/dev/null",
        "--width",
        "0",
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("E1043"), "{err}");
    // --thickness is read as an exact positive number first (E0503, as every number flag).
    let (code, _, err) = common::lacuna(&[
        "render",
        "F0",
        "--level",
        "1",
        "--stl",
        "/dev/null",
        "--thickness",
        "0",
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("E0503"), "{err}");
}

mod random {
    use super::*;
    use lacuna::{topology::EdgeType, topology::Face};
    use proptest::prelude::*;

    fn edge() -> impl Strategy<Value = EdgeType> + Clone {
        common::strategies::edge(2..=3, Just(1u32))
    }

    fn face() -> impl Strategy<Value = Face> {
        common::strategies::face(
            edge(),
            3..=6,
            edge(),
            common::strategies::builtin_algorithm(),
            Just(1u32),
        )
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

        /// Whenever the default geometry realises a random face at level 1 or 2, its solid is one
        /// closed manifold with Euler characteristic 2 − 2·holes (holes from the exact counts);
        /// otherwise the refusal is geometric (E1041: cells overlap), never a combinatorial
        /// failure of the mesh (E1040).
        #[test]
        fn random_faces_give_closed_manifolds(f in face(), level in 1u32..=2) {
            let text = format!("face 0: {f}\n");
            let Ok(assembly) = lacuna::input::parse_text(&lacuna::Source { name: "random".into(), text }) else {
                return Ok(());
            };
            let input = lacuna::input::Input { name: "random".into(), assembly };
            let opts = InstantiateOptions {
                limits: lacuna::topology::Limits { max_types: 12, ..lacuna::topology::Limits::default() },
                ..InstantiateOptions::default()
            };
            let Ok(i) = instantiate(&input, &opts) else { return Ok(()); };
            if lacuna::geometry::cell_count(&i, level) > 5_000 {
                return Ok(());
            }
            let Ok(topo) = lacuna::measure::exact_topology(&i, level) else { return Ok(()); };
            let holes: i64 = topo[level as usize].holes.to_string().parse().unwrap();
            match build(&i, level, 4, Size::default()) {
                Ok(s) => {
                    let mut bin = Vec::new();
                    lacuna::mesh::stl::write_binary(&s, &mut bin).unwrap();
                    let p = pieces(&read_closed_stl(&bin, &f.to_string()), &f.to_string());
                    prop_assert_eq!(p.len(), 1);
                    prop_assert_eq!(euler(p[0]), 2 - 2 * holes, "{}", f);
                }
                Err(e) => prop_assert_eq!(e.code(), "E1041", "{}: {}", f, e),
            }
        }
    }
}

/// Debian's admesh, an independent STL checker, on written files: one part, nothing to repair
/// (no disconnected edge, degenerate facet, reversed facet, backwards edge or wrong normal).
/// Ignored by a plain `cargo test` (it needs admesh); `.ci/run` installs admesh and runs it.
#[test]
#[ignore]
fn admesh_finds_one_part_and_nothing_to_repair() {
    let dir = common::scratch("admesh");
    for (name, level, ascii) in [
        ("F0", 4u32, false),
        ("F0", 3, true),
        ("triangle-C2", 3, false),
        ("delayed-B2-C2", 3, false),
        ("two-quads", 3, false),
    ] {
        let s = solid(&inst(name), level);
        let path = dir.join(format!("{name}-{level}.stl"));
        let mut f = std::io::BufWriter::new(std::fs::File::create(&path).unwrap());
        if ascii {
            lacuna::mesh::stl::write_ascii(&s, &mut f).unwrap();
        } else {
            lacuna::mesh::stl::write_binary(&s, &mut f).unwrap();
        }
        drop(f);
        let what = format!("{name} level {level}{}", if ascii { " ASCII" } else { "" });
        let facets = common::admesh_finds_nothing_to_repair(&path, &what);
        assert_eq!(facets, s.triangle_count().to_string(), "{what}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The checked solid of a volume (THEORY §10) at a level.
fn volume(text: &str, level: u32) -> lacuna::mesh::VolumeSolid {
    let (name, v) = lacuna::input::load_volume(text).unwrap().expect("a volume");
    let lacuna::topology::volume::VolumeClosure::Closed(set) =
        lacuna::topology::volume::VolumeClosure::of(
            std::slice::from_ref(&v),
            &lacuna::topology::Limits::default(),
        )
        .unwrap()
    else {
        panic!("{text} closes")
    };
    lacuna::mesh::volume_solid(&name, &v, &set, level, 100.0)
        .unwrap_or_else(|e| panic!("{text} level {level}: {} {e}", e.code()))
}

/// Volumes at level 1, read back from STL and 3MF. By hand: when every face of the solid S keeps
/// its central lacuna, the level-1 solid is a thick shell around S's cavity pierced by one hole per
/// face; a shell pierced by k holes is a handlebody of genus k − 1, whose surface has Euler
/// characteristic 2 − 2(k − 1) = 4 − 2k: the cube (k = 6) −8 and genus 5 as in THEORY §10's worked
/// example, the tetrahedron (4) −4, the octahedron and the truncated tetrahedron (8) −12, with V1
/// or V2. A delayed volume caps its holes: one ball, χ = 2.
#[test]
fn volume_solids_read_back_with_the_hand_derived_euler_characteristic() {
    for (text, euler) in [
        ("cube-B2", -8),
        ("tetrahedron-B2", -4),
        ("octahedron B2 | B2 B2 B2 | A1 | B2 B2 | V2", -12),
        ("truncated-tetrahedron B2 | B2 B2 B2 | A1 | B2 B2 | V1", -12),
        ("cube B2 | B2 B2 B2 | A1 | B2 B2 | V2", -8),
        ("cube B2 | B2 B2 B2 | A1 | B2 B2 | V1 | 2", 2),
    ] {
        let s = volume(text, 1);
        s.embedded().unwrap_or_else(|e| panic!("{text}: {e}"));
        check_written(&s.solid, &[euler], text);
    }
    let cube = volume("cube-B2", 1);
    assert_eq!((cube.genus, cube.euler), (5, -8));
}

/// cube-B2 at level 2, by hand: each of the 8 corner blocks (13 faces) is at level 2 a shell
/// pierced by 13 holes, χ = 1 − 12 = −11; two blocks along a cube edge share two spoke faces,
/// each an annulus at level 2 (χ = 0), joined along their radial edge (χ = −1); no three blocks
/// share a point. χ = 8·(−11) − 12·(−1) = −76, connected with no void: genus 77, surface
/// χ = −152.
#[test]
fn the_cube_at_level_two_reads_back_with_genus_77() {
    let s = volume("cube-B2", 2);
    s.embedded().unwrap();
    assert_eq!((s.genus, s.euler), (77, -152));
    check_written(&s.solid, &[-152], "cube-B2 level 2");
}

/// Solids the default placement once folded (issue #15): with every rim point's inner corner
/// shrunk towards its volume's centre they embed. The surface's Euler characteristic read back
/// from the written STL and 3MF must be twice the solid's χ from the exact counting of
/// `solid_topology` (an independent computation: it never sees the geometry).
#[test]
fn solids_that_folded_before_now_embed_and_read_back() {
    for (text, level) in [
        ("cube C2 | B2 B2 B2 | A1 | B2 B2 | V1", 2),
        ("cube B2 | B2 B2 B2 | A1 | B2 B2 | V2", 2),
        ("tetrahedron C2 | B2 B2 B2 | A1 | B2 B2 | V1", 2),
        ("octahedron B2 | B2 B2 B2 | A1 | B2 B2 | V2", 2),
        ("cube-B2", 3),
    ] {
        let s = volume(text, level);
        s.embedded()
            .unwrap_or_else(|e| panic!("{text} level {level}: {e}"));
        let twice: i64 = (num_bigint::BigInt::from(2) * &s.exact.euler)
            .try_into()
            .unwrap();
        assert_eq!(s.euler, twice, "{text} level {level}");
        check_written(&s.solid, &[twice], &format!("{text} level {level}"));
    }
}

/// admesh on volume solids at level 1: one part, nothing to repair.
#[test]
#[ignore]
fn admesh_on_volume_solids() {
    let dir = common::scratch("admesh-vol");
    for name in ["cube-B2", "tetrahedron-B2"] {
        let s = volume(name, 1);
        let path = dir.join(format!("{name}.stl"));
        let mut f = std::io::BufWriter::new(std::fs::File::create(&path).unwrap());
        lacuna::mesh::stl::write_binary(&s.solid, &mut f).unwrap();
        drop(f);
        let facets = common::admesh_finds_nothing_to_repair(&path, name);
        assert_eq!(facets, s.solid.triangle_count().to_string(), "{name}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

mod random_volumes {
    //! Property test over random volumes (small solids with random B/C edges, random E and
    //! algorithms, both rules, delays 1 and 2): the mesh of levels 1 and 2 is a closed oriented
    //! manifold whose cells and Euler characteristic are the exact ones (checked inside
    //! `volume_solid`: cell counts, 2χ, components, voids, genus), and its surface read back has
    //! Euler characteristic 2χ with χ from the exact topology.
    use super::common;
    use lacuna::topology::volume::{solid_topology, Volume, VolumeClosure};
    use proptest::prelude::*;

    fn volume() -> impl Strategy<Value = Volume> {
        common::random_volume::volume(
            vec!["B2", "B3", "C2", "C3", "B2^2"],
            vec!["B2 B2 B2", "C2 B2 B2", "B2 B2 C2"],
            vec!["A1", "A2"],
        )
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(12))]
        #[test]
        fn the_mesh_has_the_exact_euler_characteristic(v in volume()) {
            let limits = lacuna::topology::Limits { max_types: 300, ..Default::default() };
            let set = match VolumeClosure::of(std::slice::from_ref(&v), &limits) {
                Ok(VolumeClosure::Closed(set)) => set,
                // Refused (a patch that is not a disk, no spoke) or not closing within the limits.
                _ => return Ok(()),
            };
            let exact = solid_topology(&set, 2).unwrap();
            for level in 1..=2u32 {
                if exact[level as usize].faces > 4000u32.into() {
                    break;
                }
                let s = lacuna::mesh::volume_solid("random", &v, &set, level, 100.0);
                let s = match s {
                    Ok(s) => s,
                    // The default placement draws edges straight: it refuses, by name, two
                    // edges between the same two points (faces with two spokes).
                    Err(e) if e.code() == "E1211" && e.to_string().contains("cannot draw") => break,
                    Err(e) => {
                        prop_assert!(false, "{} level {}: {} {}", v, level, e.code(), e);
                        unreachable!()
                    }
                };
                let chi: i64 = exact[level as usize].euler.to_string().parse().unwrap();
                prop_assert_eq!(s.euler, 2 * chi);
                // Read back by a reader that is not the writer.
                let mut bin = Vec::new();
                lacuna::mesh::stl::write_binary(&s.solid, &mut bin).unwrap();
                let m = super::read_closed_stl(&bin, "random volume");
                let total: i64 = super::pieces(&m, "random volume").into_iter().map(super::euler).sum();
                prop_assert_eq!(total, 2 * chi);
            }
        }
    }
}

/// Moving a volume's corners by a similarity (a rotation, a scale, a translation) changes
/// nothing but where the solid lies: the mesh check passes with the same Euler characteristic,
/// and the enclosed volume scales with the cube of the scale.
mod placed_anywhere {
    use lacuna::geometry::{default_placement, place_assembly};
    use lacuna::topology::volume::{parse_volume, VolumeAssembly, VolumeClosure};
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(8))]
        #[test]
        fn a_similar_placement_is_the_same_solid(
            q in proptest::array::uniform4(-1.0f64..1.0),
            s in 0.1f64..20.0,
            t in proptest::array::uniform3(-50.0f64..50.0),
            which in 0usize..3,
        ) {
            let text = ["cube-B2", "tetrahedron-B2", "prism-5 B2 | B2 B2 B2 | A1 | B2 B2 | V1"][which];
            let text = match text {
                "cube-B2" => "cube B2 | B2 B2 B2 | A1 | B2 B2 | V1",
                "tetrahedron-B2" => "tetrahedron B2 | B2 B2 B2 | A1 | B2 B2 | V1",
                x => x,
            };
            let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
            prop_assume!(n > 0.1);
            let [w, x, y, z] = q.map(|c| c / n);
            // The rotation matrix of the unit quaternion (w, x, y, z).
            let r = [
                [1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - w * z), 2.0 * (x * z + w * y)],
                [2.0 * (x * y + w * z), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - w * x)],
                [2.0 * (x * z - w * y), 2.0 * (y * z + w * x), 1.0 - 2.0 * (x * x + y * y)],
            ];
            let v = parse_volume(text).unwrap();
            let (_, base) = default_placement(&v).unwrap();
            let moved: Vec<Vec<[f64; 3]>> = base
                .iter()
                .map(|f| {
                    f.iter()
                        .map(|p| {
                            let mut o = [0.0; 3];
                            for i in 0..3 {
                                o[i] = t[i] + s * (0..3).map(|k| r[i][k] * p[k]).sum::<f64>();
                            }
                            o
                        })
                        .collect()
                })
                .collect();
            let a = VolumeAssembly::single(v.clone());
            let VolumeClosure::Closed(set) =
                VolumeClosure::of(&a.volumes, &Default::default()).unwrap()
            else {
                panic!("closes")
            };
            let at_home = lacuna::mesh::volume_solid("home", &v, &set, 1, 100.0).unwrap();
            let placement = place_assembly(&a, &[Some(moved)], &[]).unwrap();
            let away = lacuna::mesh::assembly_solid("away", &a, &placement, &set, 1, 100.0).unwrap();
            prop_assert!(away.crossing.is_none(), "{:?}", away.crossing);
            prop_assert_eq!(away.euler, at_home.euler);
            prop_assert_eq!(away.genus, at_home.genus);
            // In the geometry's own units the enclosed volume is s³ times the original's.
            let vol = |g: &lacuna::mesh::VolumeSolid| g.sizes(1, 0.4).volume_mm3 / g.transform.0.powi(3);
            let ratio = vol(&away) / vol(&at_home);
            prop_assert!((ratio / s.powi(3) - 1.0).abs() < 1e-4, "{} vs {}", ratio, s.powi(3));
        }
    }
}

/// Issue #30: the build volume. F0 at --width 250 is 250 mm wide (and 250·√3/2 ≈ 216.5 mm
/// deep): on the default 200 × 200 × 200 mm bed it fits scaled by min(200/250, 200/216.5) = 0.8,
/// i.e. --width 200. two-cubes is exactly 200 mm along y: it fits, with no room for a brim.
#[test]
fn a_solid_that_does_not_fit_the_bed_gets_a_warning_with_the_width_that_fits() {
    let dir = common::scratch("bed");
    let stl = dir.join("f0.stl").to_string_lossy().to_string();
    let (code, _, err) = common::lacuna(&[
        "render", "F0", "--level", "1", "--stl", &stl, "--width", "250",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("larger than the bed 200.0 × 200.0 × 200.0 mm")
            && err.contains("scaled by 0.8000")
            && err.contains("--width 200.00 mm"),
        "{err}"
    );
    let (code, _, err) = common::lacuna(&["render", "F0", "--level", "1", "--stl", &stl]);
    assert_eq!(code, 0, "{err}");
    assert!(!err.contains("bed"), "the default width fits: {err}");
    let stl = dir.join("two-cubes.stl").to_string_lossy().to_string();
    let (code, _, err) = common::lacuna(&["render", "two-cubes", "--level", "1", "--stl", &stl]);
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("within 1 mm of the bed") && err.contains("in y"),
        "{err}"
    );
    let (code, _, err) = common::lacuna(&[
        "render", "F0", "--level", "1", "--stl", &stl, "--bed", "100x100",
    ]);
    assert_eq!(code, 2, "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn feature_sizes_of_f0_and_delayed_b2_c2_are_the_printed_widths() {
    // Level 3 at the default width (100 mm), the default 4 segments per Bézier edge. Expected
    // widths come from an independent measure of the same union of cells (the `render
    // --json-out` polygons, unioned and buffered with shapely, round joins of 64 segments per
    // quarter circle) — not from lacuna's output:
    // - F0: its narrowest hole closes under dilation at 2r = 1.050 mm; under erosion the hole
    //   count first drops (97 → 91: walls between holes, or a hole and the outside, are cut)
    //   between 2r = 1.78 and 1.80 mm, and the first component splits between 2.24 and 2.26 mm.
    // - delayed-B2-C2: narrowest hole 0.44 mm wide (0.441 by the inscribed disc); holes first
    //   merge (37 → 35) between 2r = 0.535 and 0.54 mm.
    // Tolerances: the hole is bracketed within 2e-4 mm; the ligament is the bisection's upper
    // end, within 1e-3 mm of the change, plus the offset's chord error (1.3e-4·r): 0.01 mm is
    // ample and still separates the candidates (1.78 against 2.25).
    let size = Size::default();
    let f0 = lacuna::mesh::printability(&inst("F0"), 3, 4, size, 0.4).unwrap();
    let hole = f0.smallest_hole_mm.unwrap();
    assert!((hole - 1.05).abs() < 0.005, "F0 hole {hole}");
    let lig = f0.thinnest_ligament_mm.unwrap();
    assert!(
        (1.78 - 0.01..=1.80 + 0.01).contains(&lig),
        "F0 ligament {lig}"
    );
    assert!(f0.below().is_empty(), "{:?}", f0.below());

    let d = lacuna::mesh::printability(&inst("delayed-B2-C2"), 3, 4, size, 0.4).unwrap();
    let hole = d.smallest_hole_mm.unwrap();
    assert!((hole - 0.44).abs() < 0.005, "delayed-B2-C2 hole {hole}");
    let lig = d.thinnest_ligament_mm.unwrap();
    assert!(
        (0.535 - 0.01..=0.54 + 0.01).contains(&lig),
        "delayed-B2-C2 ligament {lig}"
    );
    // 0.441 mm is above the 0.4 mm nozzle: no false warning any more.
    assert!(d.below().is_empty(), "{:?}", d.below());
    // At a 0.45 mm nozzle the hole is below it.
    let d = lacuna::mesh::printability(&inst("delayed-B2-C2"), 3, 4, size, 0.45).unwrap();
    assert_eq!(d.below().len(), 1, "{:?}", d.below());
}

/// Debian's PrusaSlicer (the `prusa-slicer` command line, installed by `.ci/run`) slices every
/// library solid at level 2 without repair, as lacuna orients it with `--orient auto`; where
/// lacuna says that no face rests on the bed, with supports (`--support-material`), as it
/// advises. The thickened quad-patch shell is one of them: it slices only that way.
#[test]
#[ignore]
fn prusa_slicer_slices_every_library_solid_at_level_2() {
    let dir = common::scratch("prusa");
    let cases: &[(&str, &[&str])] = &[
        ("F0", &[]),
        ("square-B2", &[]),
        ("triangle-C2", &[]),
        ("delayed-B2-C2", &[]),
        ("two-quads", &[]),
        ("cube-B2", &[]),
        ("tetrahedron-B2", &[]),
        ("cube-C2", &[]),
        ("truncated-tetrahedron", &[]),
        ("two-cubes", &[]),
        ("quad-patch-3d", &["--thickness", "1"]),
    ];
    for (name, extra) in cases {
        let stl = dir.join(format!("{name}.stl"));
        let gcode = dir.join(format!("{name}.gcode"));
        let mut args = vec!["render", name, "--level", "2", "--orient", "auto", "--stl"];
        args.push(stl.to_str().unwrap());
        args.extend_from_slice(extra);
        let (code, out, err) = common::lacuna(&args);
        assert_eq!(code, 0, "{name}: {out}{err}");
        assert!(out.contains("orientation: "), "{name}: {out}");
        let supports = err.contains("no face rests on the bed");
        let (sliced, text) = common::prusa_slice(&stl, &gcode, supports);
        assert!(sliced, "{name} (supports: {supports}): {text}");
        assert!(
            !text.contains("no extrusions in the first layer"),
            "{name}: {text}"
        );
        let g = std::fs::read_to_string(&gcode).unwrap();
        assert!(g.contains("G1"), "{name}: no moves in the G-code");
    }
    // The shell needs the supports lacuna asked for: without them PrusaSlicer refuses it.
    let stl = dir.join("quad-patch-3d.stl");
    let (sliced, _) = common::prusa_slice(&stl, &dir.join("bare.gcode"), false);
    assert!(!sliced, "the shell sliced without supports");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue #31's Done-when: the level-3 solids of cube-C2 (C2 edges, A1, V1) and of the
/// tetrahedron with C2 edges under A1 and V1 embed, and PrusaSlicer slices them as lacuna orients
/// them (with supports where lacuna says no face rests on the bed). Ignored by a plain
/// `cargo test` (it needs prusa-slicer, and each slice takes a minute or more).
#[test]
#[ignore]
fn prusa_slicer_slices_cube_c2_and_tetrahedron_c2_at_level_3() {
    let dir = common::scratch("prusa3");
    for (k, name) in ["cube-C2", "tetrahedron C2 | B2 B2 B2 | A1 | B2 B2 | V1"]
        .iter()
        .enumerate()
    {
        let stl = dir.join(format!("{k}.stl"));
        let gcode = dir.join(format!("{k}.gcode"));
        let (code, out, err) = common::lacuna(&[
            "render",
            name,
            "--level",
            "3",
            "--orient",
            "auto",
            "--stl",
            stl.to_str().unwrap(),
        ]);
        assert_eq!(code, 0, "{name}: {out}{err}");
        assert!(out.contains("no two triangles cross"), "{name}: {out}");
        let supports = err.contains("no face rests on the bed");
        let (sliced, text) = common::prusa_slice(&stl, &gcode, supports);
        assert!(sliced, "{name} (supports: {supports}): {text}");
        let g = std::fs::read_to_string(&gcode).unwrap();
        assert!(g.contains("G1"), "{name}: no moves in the G-code");
        assert_eq!(
            common::admesh_finds_nothing_to_repair(&stl, name),
            // admesh counts facets; every triangle of the binary STL is one.
            binary_stl_triangles(&std::fs::read(&stl).unwrap()).to_string(),
            "{name}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The printability object of a plate and of a volume: the plate's area on the bed, from the
/// union of its cells' polygons, equals the area of the downward triangles on the bed of the
/// mesh built from them (two derivations); a plate has no overhang; a volume's figures say what
/// kind they are, and its overhang is the mesh's as built.
#[test]
fn the_printability_object_of_a_plate_and_of_a_volume() {
    let i = inst("F0");
    let size = Size::default();
    let p = lacuna::mesh::printability(&i, 2, 4, size, 0.4).unwrap();
    let r = lacuna::mesh::printability::PrintReport::of_plate(&p, lacuna::mesh::DEFAULT_BED);
    let s = solid(&i, 2);
    let (o, _) = lacuna::mesh::orient::overhangs(&s.parts);
    let from_mesh = o[0].bed_contact_mm2;
    let from_polygons = r.bed_contact_mm2.unwrap();
    assert!(
        (from_mesh - from_polygons).abs() < 1e-6 * from_mesh,
        "{from_mesh} against {from_polygons}"
    );
    assert_eq!((r.overhang_mm2, o[0].overhang_mm2), (Some(0.0), 0.0));
    // The plate: 100 mm wide, the hexagon's height √3/2 of it, 2 mm thick; it fits 200³.
    assert!(
        (r.extent_mm[1] - 50.0 * 3f64.sqrt()).abs() < 1e-9,
        "{:?}",
        r.extent_mm
    );
    assert_eq!((r.extent_mm[2], r.wall_thickness_mm), (2.0, Some(2.0)));
    assert!(r.fits_bed);
    let v = volume("cube-C2", 1);
    let sizes = v.sizes(8, 0.4);
    let vr = sizes.report(&v.solid.parts, 1, 0.4, [50.0, 200.0, 200.0]);
    // The hole and the ligament are the least over the 8 layers: recomputed here from the
    // slices, each measured as a face's plate is.
    let heights = lacuna::mesh::slice::layer_heights(&v.solid.parts, 8);
    assert_eq!(heights.len(), 8);
    let each: Vec<_> = heights
        .iter()
        .map(|&z| lacuna::mesh::slice::slice(&v.solid.parts, z))
        .collect();
    let least = |f: &dyn Fn(&lacuna::mesh::feature::Shapes) -> Option<f64>| {
        each.iter().filter_map(f).fold(f64::INFINITY, f64::min)
    };
    let hole = least(&|s| lacuna::mesh::feature::smallest_hole(s).map(|h| h.0));
    let lig = least(&|s| lacuna::mesh::feature::thinnest_ligament(s).map(|l| l.1));
    assert_eq!(vr.smallest_hole_mm, Some(hole));
    let got = vr.thinnest_ligament_mm.expect("a ligament");
    assert!(
        (got - lig).abs() <= 2.0 * lacuna::mesh::feature::LIGAMENT_TOLERANCE,
        "{got} {lig}"
    );
    for k in ["smallest_hole", "thinnest_ligament"] {
        assert_eq!(
            vr.kinds[k].0,
            lacuna::mesh::printability::FigureKind::Estimate
        );
    }
    // The slices themselves, against an independent figure: the areas of 400 slices at equal
    // heights, summed by the midpoint rule, give the enclosed volume that the divergence theorem
    // gives from the triangles (`sizes.volume_mm3`), to well under 1 %.
    let (lo, hi) = (0.0, sizes.extent_mm[2]);
    let n = 400;
    let h = (hi - lo) / f64::from(n);
    let area = |shapes: &lacuna::mesh::feature::Shapes| -> f64 {
        let ring = |r: &Vec<[f64; 2]>| {
            (0..r.len())
                .map(|i| {
                    let (a, b) = (r[i], r[(i + 1) % r.len()]);
                    a[0] * b[1] - b[0] * a[1]
                })
                .sum::<f64>()
                / 2.0
        };
        // Outer contours counter-clockwise, holes clockwise: the signed sum is the material.
        shapes.iter().flatten().map(ring).sum()
    };
    let z0 = v
        .solid
        .parts
        .iter()
        .flat_map(|p| p.vertices.iter().map(|x| f64::from(x[2])))
        .fold(f64::INFINITY, f64::min);
    let by_slices: f64 = (0..n)
        .map(|i| {
            area(&lacuna::mesh::slice::slice(
                &v.solid.parts,
                z0 + (f64::from(i) + 0.5) * h,
            )) * h
        })
        .sum();
    assert!(
        (by_slices - sizes.volume_mm3).abs() < 0.005 * sizes.volume_mm3,
        "slices {by_slices} against {}",
        sizes.volume_mm3
    );
    // cube-C2's level 1 overhangs (the undersides of its tunnels' roofs): a bridge to cross.
    assert!(vr.largest_bridge_mm.is_some_and(|b| b > 0.0 && b < 100.0));
    assert_eq!(
        vr.kinds["wall_thickness"].0,
        lacuna::mesh::printability::FigureKind::LowerBound
    );
    assert_eq!(vr.wall_thickness_mm, sizes.wall_bound_mm);
    // 100 mm wide: it does not fit a bed 50 mm wide.
    assert!(!vr.fits_bed);
    let (o, _) = lacuna::mesh::orient::overhangs(&v.solid.parts);
    assert_eq!(vr.overhang_mm2, Some(o[0].overhang_mm2));
}

/// `render --3mf-colours` (issue #30): the coloured 3MF is one closed manifold with the exact
/// topology (read back by `check-mesh`, which ignores materials), with a base material per face
/// type — delayed-B2-C2 closes with 5 types — and every triangle naming one of them; volumes and
/// automata have no face types to colour by and are refused (exit 2).
#[test]
fn the_coloured_3mf_names_a_material_per_type_on_every_triangle() {
    let dir = common::scratch("colours");
    let mf = dir.join("d.3mf");
    let path = mf.to_string_lossy().to_string();
    let (code, out, err) = common::lacuna(&[
        "render",
        "delayed-B2-C2",
        "--level",
        "3",
        "--3mf",
        &path,
        "--3mf-colours",
    ]);
    assert_eq!(code, 0, "{out}{err}");
    let (code, out, _) = common::lacuna(&["check-mesh", &path, "--expect-euler", "-72"]);
    assert_eq!(code, 0, "{out}");
    let xml = model_xml(&std::fs::read(&mf).unwrap());
    assert_eq!(xml.matches("<base ").count(), 5);
    let triangles = xml.matches("<triangle ").count();
    assert!(triangles > 0);
    let coloured = xml
        .match_indices("<triangle ")
        .filter(|(i, _)| {
            let t = &xml[*i..*i + xml[*i..].find("/>").unwrap()];
            let p1 = t.split("p1=\"").nth(1).and_then(|r| r.split('"').next());
            t.contains("pid=\"1\"")
                && p1
                    .and_then(|k| k.parse::<u32>().ok())
                    .is_some_and(|k| k < 5)
        })
        .count();
    assert_eq!(coloured, triangles);
    // A volume's triangles each lie on one sub-volume: cube-B2 closes with 3 volume types (the
    // cube, and the corner pieces W3 and W4 of THEORY §10), so 3 materials; at level 2 only the
    // corner pieces are left, so only materials 1 and 2 are named.
    let cube = dir.join("cube.3mf");
    let (code, out, err) = common::lacuna(&[
        "render",
        "cube-B2",
        "--level",
        "2",
        "--3mf",
        &cube.to_string_lossy(),
        "--3mf-colours",
    ]);
    assert_eq!(code, 0, "{out}{err}");
    let xml = model_xml(&std::fs::read(&cube).unwrap());
    assert_eq!(xml.matches("<base ").count(), 3);
    let used: std::collections::BTreeSet<&str> = xml
        .match_indices(" p1=\"")
        .map(|(i, _)| {
            let r = &xml[i + 5..];
            &r[..r.find('"').unwrap()]
        })
        .collect();
    assert_eq!(used, ["1", "2"].into_iter().collect());
    // An automaton's surface has no cells of types.
    let (code, _, err) = common::lacuna(&[
        "render",
        "quad-patch-3d",
        "--3mf",
        &dir.join("x.3mf").to_string_lossy(),
        "--3mf-colours",
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--3mf-colours"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Reads the mesh objects of a 3MF model on its own (no lacuna code): for each, its name,
/// material index and its closed shells — every directed edge of its triangles must occur once
/// and its reverse once (closed and oriented), the shells are the connected pieces, and each
/// must have V − E + F = 2 (a sphere). Returns (name, pindex, shells).
fn closed_shells(xml: &str) -> Vec<(String, Option<u32>, usize)> {
    let mut out = Vec::new();
    for chunk in xml.split("<object ").skip(1) {
        let head = &chunk[..chunk.find('>').unwrap()];
        let Some(body) = chunk.split("<mesh>").nth(1) else {
            continue;
        };
        let name = attribute(&format!(" {head}"), "name").unwrap().to_string();
        let pindex = attribute(&format!(" {head}"), "pindex").map(|p| p.parse().unwrap());
        let nv = body.matches("<vertex ").count();
        let tris: Vec<[usize; 3]> = body
            .split("<triangle ")
            .skip(1)
            .map(|t| {
                let t = format!(" {t}");
                ["v1", "v2", "v3"].map(|k| attribute(&t, k).unwrap().parse().unwrap())
            })
            .collect();
        let mut edges = std::collections::HashMap::new();
        for t in &tris {
            for i in 0..3 {
                *edges.entry((t[i], t[(i + 1) % 3])).or_insert(0u32) += 1;
            }
        }
        for (&(a, b), &n) in &edges {
            assert_eq!(n, 1, "{name}: edge {a}→{b} used {n} times");
            assert_eq!(
                edges.get(&(b, a)),
                Some(&1),
                "{name}: edge {a}→{b} has no twin"
            );
        }
        let mut parent: Vec<usize> = (0..nv).collect();
        fn find(p: &mut [usize], mut x: usize) -> usize {
            while p[x] != x {
                p[x] = p[p[x]];
                x = p[x];
            }
            x
        }
        for t in &tris {
            let a = find(&mut parent, t[0]);
            for &v in &t[1..] {
                let b = find(&mut parent, v);
                parent[b] = a;
            }
        }
        let mut shell: std::collections::HashMap<usize, (i64, i64, i64)> = Default::default();
        let used: std::collections::BTreeSet<usize> = tris.iter().flatten().copied().collect();
        for &v in &used {
            shell.entry(find(&mut parent, v)).or_default().0 += 1;
        }
        for &(a, _) in edges.keys() {
            shell.entry(find(&mut parent, a)).or_default().1 += 1;
        }
        for t in &tris {
            shell.entry(find(&mut parent, t[0])).or_default().2 += 1;
        }
        for (v, e2, f) in shell.values() {
            // Each edge was counted once per direction.
            assert_eq!(v - e2 / 2 + f, 2, "{name}: a shell is no sphere");
        }
        out.push((name, pindex, shell.len()));
    }
    out
}

/// `render --3mf-parts` (issue #30): one object per type, each of its own material, gathered as
/// the components of one object, every level-n cell a closed sphere of its own. Expected counts
/// by hand. delayed-B2-C2 (tests/fixtures.rs): X → 2 S4 + U, S4 → 4 G6, U → 2 G6 + 2 V7,
/// V7 → 6 G6 + V7, G6 → 6 G6; level 2 is 10 G6 + 2 V7, level 3 is 60 + 12 = 72 G6 (six edges)
/// and 2 V7 (seven). cube-B2 (THEORY §10): the cube's 8 corner pieces are W3 (13 faces), each
/// → 16 W3 + 3 W4, so level 2 is 128 W3 and 24 W4 (17 faces).
#[test]
fn the_3mf_parts_hold_each_type_s_cells_as_closed_shells() {
    let dir = common::scratch("parts");
    let faces = dir.join("d.3mf");
    let (code, out, err) = common::lacuna(&[
        "render",
        "delayed-B2-C2",
        "--level",
        "3",
        "--3mf",
        &faces.to_string_lossy(),
        "--3mf-parts",
    ]);
    assert_eq!(code, 0, "{out}{err}");
    let xml = model_xml(&std::fs::read(&faces).unwrap());
    let objects = closed_shells(&xml);
    let mut by_edges: Vec<(usize, usize)> = objects
        .iter()
        .map(|(name, _, shells)| {
            // "T3 B2 C2 … | C2 B2 B2 | A3": the edges before the first bar, less the name.
            let edges = name.split('|').next().unwrap().split_whitespace().count() - 1;
            (edges, *shells)
        })
        .collect();
    by_edges.sort();
    assert_eq!(by_edges, [(6, 72), (7, 2)], "{objects:?}");
    // Distinct materials, one per part, and one object made of the parts, built once.
    let materials: std::collections::BTreeSet<_> = objects.iter().map(|o| o.1.unwrap()).collect();
    assert_eq!(materials.len(), 2);
    assert_eq!(xml.matches("<base ").count(), 2);
    assert_eq!(xml.matches("<component ").count(), 2);
    assert_eq!(xml.matches("<item ").count(), 1);
    assert!(out.contains("3MF parts: 2 parts"), "{out}");

    let cube = dir.join("cube.3mf");
    let (code, out, err) = common::lacuna(&[
        "render",
        "cube-B2",
        "--level",
        "2",
        "--3mf",
        &cube.to_string_lossy(),
        "--3mf-parts",
        "--orient",
        "auto",
    ]);
    assert_eq!(code, 0, "{out}{err}");
    let (_, closure, _) = common::lacuna(&["closure", "cube-B2"]);
    let faces_of = |v: &str| -> usize {
        let line = closure
            .lines()
            .find(|l| l.trim_start().starts_with(&format!("{v} ")))
            .unwrap();
        line.split_whitespace().nth(1).unwrap().parse().unwrap()
    };
    let mut got: Vec<(usize, usize)> = closed_shells(&model_xml(&std::fs::read(&cube).unwrap()))
        .iter()
        .map(|(name, _, shells)| (faces_of(name), *shells))
        .collect();
    got.sort();
    assert_eq!(got, [(13, 128), (17, 24)]);
    // The parts are not one solid: --claims (which describes one) is refused with them.
    let (code, _, err) = common::lacuna(&[
        "render",
        "cube-B2",
        "--3mf",
        &cube.to_string_lossy(),
        "--3mf-parts",
        "--claims",
        &dir.join("c.json").to_string_lossy(),
    ]);
    assert_eq!(code, 2, "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// `render --json` (issue #30): one JSON object on standard output with the same printability
/// object for a face's plate, a volume and an automaton's thickened shell; the status lines go
/// to standard error. The extents are checked against the STL each command wrote, read back by
/// `stl_io` (the shell's `--width` is the printed object's x extent), and the figures' kinds
/// against what each kind of solid can prove: a plate's wall is its thickness (exact), a
/// solid's wall a lower bound, never above the shell's own thickness.
#[test]
fn render_json_gives_one_printability_object_for_every_kind() {
    let dir = common::scratch("render-json");
    let cases: [(&[&str], &str); 3] = [
        (&["F0", "--level", "1"], "exact"),
        (&["cube-C2", "--level", "1"], "lower-bound"),
        (
            &["quad-patch-3d", "--level", "2", "--thickness", "1"],
            "lower-bound",
        ),
    ];
    for (k, (args, wall_kind)) in cases.iter().enumerate() {
        let stl = dir.join(format!("{k}.stl"));
        let stl = stl.to_str().unwrap();
        let mut a = vec!["render"];
        a.extend_from_slice(args);
        a.extend_from_slice(&["--stl", stl, "--json"]);
        let (code, out, err) = common::lacuna(&a);
        assert_eq!(code, 0, "{args:?}: {err}");
        assert!(
            err.contains("wrote "),
            "{args:?}: status lines on stderr: {err}"
        );
        let j: serde_json::Value = serde_json::from_str(&out).expect("one JSON object");
        assert_eq!(j["input"], args[0]);
        assert_eq!(j["written"], serde_json::json!([stl]));
        let p = &j["printability"];
        for key in [
            "smallest_hole_mm",
            "thinnest_ligament_mm",
            "wall_thickness_mm",
            "extent_mm",
            "fits_bed",
            "overhang_mm2",
            "largest_bridge_mm",
            "resolution_mm",
            "kinds",
        ] {
            assert!(p.get(key).is_some(), "{args:?}: no {key} in {p}");
        }
        assert_eq!(p["kinds"]["wall_thickness"][0], *wall_kind, "{args:?}");
        let m = read_closed_stl(&std::fs::read(stl).unwrap(), stl);
        for d in 0..3 {
            let (lo, hi) = m.vertices.iter().fold((f64::MAX, f64::MIN), |(l, h), v| {
                (l.min(f64::from(v[d])), h.max(f64::from(v[d])))
            });
            let e = p["extent_mm"][d].as_f64().unwrap();
            // The file holds f32 coordinates: equal to ~1e-5 of 100 mm.
            assert!(
                (e - (hi - lo)).abs() < 1e-3,
                "{args:?}: extent {d}: {e} vs {}",
                hi - lo
            );
        }
        let x = p["extent_mm"][0].as_f64().unwrap();
        assert!((x - 100.0).abs() < 1e-3, "{args:?}: width {x}");
        if k == 2 {
            let w = p["wall_thickness_mm"].as_f64().expect("a wall bound");
            assert!(w > 0.0 && w <= 1.0 + 1e-6, "shell wall bound {w}");
        }
    }
    // Without a mesh there is nothing to print: null. With an output on standard output, the
    // JSON would share it: refused.
    let svg = dir.join("f.svg");
    let (code, out, _) = common::lacuna(&[
        "render",
        "F0",
        "--level",
        "1",
        "--svg",
        svg.to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(code, 0);
    let j: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert!(j["printability"].is_null());
    let (code, _, err) = common::lacuna(&["render", "F0", "--svg", "-", "--json"]);
    assert_eq!(code, 2, "{err}");
}
