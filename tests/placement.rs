// Control points from the user and placement by all shared edges (issue #6): the coordinates
// syntax and its coded errors, AutoFrac2D's `p` section, shared edges drawn once, cycles of faces,
// and the affine invariance of the level-1 cells.

mod common;
use common::lacuna;
use lacuna::{
    geometry::instantiate, geometry::regular_polygon, geometry::Instance,
    geometry::InstantiateOptions, geometry::Point, input::load_input, input::parse_text,
    input::set_corners, input::Assembly, input::CoordKind, input::Input, Source,
};
use num_rational::BigRational;
use proptest::prelude::*;

fn src(text: &str) -> Source {
    Source {
        name: "test.txt".into(),
        text: text.into(),
    }
}

fn input(text: &str) -> Input {
    Input {
        name: "test".into(),
        assembly: parse_text(&src(text)).unwrap_or_else(|e| panic!("{}", e.render())),
    }
}

fn inst(input: &Input) -> Instance {
    instantiate(input, &InstantiateOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

fn q(n: i64, d: i64) -> BigRational {
    BigRational::new(n.into(), d.into())
}

/// The control points of written edge `e` of start face `f` (both ends), from the instance.
fn edge_points(i: &Instance, asm: &Assembly, f: usize, e: usize) -> Vec<Point> {
    let face = &asm.faces[f].1;
    let n = face.boundary.len();
    let r = face.canonical().1;
    let s = &i.start[f];
    i.edge_controls(s.ty, (e + n - r) % n, &s.points)
}

/// Twice the signed area of a polygon.
fn area2(p: &[Point]) -> f64 {
    (0..p.len())
        .map(|k| {
            let (a, b) = (p[k], p[(k + 1) % p.len()]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum()
}

const QUAD: &str = "C2 B2 C2 B2 | C2 B2 B2 | A1";

#[test]
fn coordinate_lines_have_coded_errors_with_columns() {
    let two = format!("face 0: {QUAD}\nface 1: {QUAD}\nface 0 edge 3 ~ face 1 edge 1\n");
    // (text, code, line, column), columns counted by hand in the lines below.
    let cases = [
        // `x` is the 24th character of `corners 0: 0 0, 1 0, 1 x, 0 1`.
        (format!("face 0: {QUAD}\ncorners 0: 0 0, 1 0, 1 x, 0 1"), "E0209", 2, 24),
        // An empty point: the third piece starts at column 21.
        (format!("face 0: {QUAD}\ncorners 0: 0 0, 1 0,, 0 1"), "E0209", 2, 21),
        // 10^16 is above the magnitude bound; it starts at column 14.
        (format!("face 0: {QUAD}\ncorners 0: 0 10000000000000000, 1 0, 1 1, 0 1"), "E0209", 2, 14),
        // Three corners for four edges: the point list starts at column 12.
        (format!("face 0: {QUAD}\ncorners 0: 0 0, 1 0, 1 1"), "E0210", 2, 12),
        // `points` for C2 B2 C2 B2 needs 6 (degree 2) or 8 (degree 3): 5 is neither.
        (format!("face 0: {QUAD}\npoints 0: 0 0, 1 0, 2 0, 1 1, 0 1"), "E0210", 2, 11),
        (format!("face 0: {QUAD}\ncorners 9: 0 0, 1 0, 1 1, 0 1"), "E0203", 2, 9),
        (
            format!("face 0: {QUAD}\ncorners 0: 0 0, 1 0, 1 1, 0 1\ncorners 0: 0 0, 1 0, 1 1, 0 1"),
            "E0213",
            3,
            9,
        ),
        // Clockwise square: the error points at the first point (column 12).
        (format!("face 0: {QUAD}\ncorners 0: 0 0, 0 1, 1 1, 1 0"), "E0212", 2, 12),
        // A bow tie: edges 1 and 3 cross; the error points at corner 3 (column 27).
        (format!("face 0: {QUAD}\ncorners 0: 0 0, 2 0, 0 1, 3 1"), "E0212", 2, 27),
        // Shared edge 0.3 ~ 1.1: face 0 corner 0 is (0, 10) but face 1 corner 1 is (0, 11),
        // written at column 19 of line 5.
        (
            format!("{two}corners 0: 0 10, -10 10, -10 0, 0 0\ncorners 1: 10 10, 0 11, 0 0, 10 0"),
            "E0211",
            5,
            19,
        ),
        // Both faces give their inner points; face 1's inner point of edge 1, (1, 5) written
        // third at column 24, is not face 0's inner point of edge 3, (-1, 5).
        (
            format!(
                "{two}points 0: 0 10, -10 10, -11 5, -10 0, 0 0, -1 5\npoints 1: 10 10, 0 10, 1 5, 0 0, 10 0, 11 5"
            ),
            "E0211",
            5,
            24,
        ),
        // Degree 2 on face 0 and degree 3 on face 1 (8 points): one degree for all faces.
        (
            format!(
                "face 0: {QUAD}\nface 1: {QUAD}\npoints 0: 0 0, 1 0, 2 0, 2 1, 1 1, 0 1\npoints 1: 5 0, 6 0, 7 0, 7 1, 7 2, 6 2, 5 2, 5 1"
            ),
            "E0214",
            4,
            11,
        ),
    ];
    for (text, code, line, col) in cases {
        let e = parse_text(&src(&text)).unwrap_err();
        let span = e.span().cloned();
        assert_eq!(
            (e.code(), span.as_ref().map(|s| (s.line, s.col))),
            (code, Some((line, col))),
            "{text}\n{}",
            e.render()
        );
    }
}

#[test]
fn corners_and_points_are_read_exactly() {
    let a = input(&format!(
        "face 0: {QUAD}\nface 1: {QUAD}\ncorners 0: 0 0, 1/3 0, 0.5 1, -2 1\npoints 1: 5 0, 6 0, 7 0, 7 1, 6 1.5, 5 1"
    ))
    .assembly;
    let c0 = a.coords.of(0).unwrap();
    assert_eq!(c0.kind, CoordKind::Corners);
    assert_eq!(c0.points[1], [q(1, 3), q(0, 1)]);
    assert_eq!(c0.points[2], [q(1, 2), q(1, 1)]);
    let c1 = a.coords.of(1).unwrap();
    assert_eq!(c1.kind, CoordKind::Controls { degree: 2 });
    // Corners of C2 B2 C2 B2 at degree 2: points 0, 1, 3, 4 (edges 1 and 3 have an inner point).
    assert_eq!(c1.corners(&a.faces[1].1)[2], [q(7, 1), q(1, 1)]);
    assert_eq!(a.coords.degree(), Some(2));
}

#[test]
fn two_quads_with_user_corners_share_their_edge_exactly() {
    // The README example of AutoFrac2D in lacuna's format: face 0 is [-10, 0] × [0, 10], face 1
    // is [0, 10] × [0, 10]; edge 3 of face 0 runs (0, 0) → (0, 10), edge 1 of face 1 back.
    let text = format!(
        "face 0: {QUAD}\nface 1: {QUAD}\nface 0 edge 3 ~ face 1 edge 1\ncorners 0: 0 10, -10 10, -10 0, 0 0\ncorners 1: 10 10, 0 10, 0 0, 10 0\n"
    );
    let input = input(&text);
    let i = inst(&input);
    let a = edge_points(&i, &input.assembly, 0, 3);
    let mut b = edge_points(&i, &input.assembly, 1, 1);
    b.reverse();
    // B2 at degree 2: ends and the midpoint, by hand.
    assert_eq!(a, vec![[0.0, 0.0], [0.0, 5.0], [0.0, 10.0]]);
    assert_eq!(a, b, "both sides of the shared edge hold identical points");
    // The level-1 cells stay inside the union of the two squares.
    i.walk(1, false, |c| {
        for p in c.points {
            assert!(
                (-10.0 - 1e-9..=10.0 + 1e-9).contains(&p[0])
                    && (-1e-9..=10.0 + 1e-9).contains(&p[1]),
                "{p:?}"
            );
        }
    });
    // The same file in AutoFrac2D's format gives the same start faces.
    let af = load_input("autofrac-two-quads").unwrap();
    let j = inst(&af);
    for f in 0..2 {
        assert_eq!(i.start[f].points, j.start[f].points, "face {f}");
    }
}

#[test]
fn three_quads_around_a_vertex_close_with_every_shared_edge() {
    // Three quads with corner 0 at the common vertex V: edge 0 leaves V, edge 3 enters it, and
    // each face's edge 0 is the next face's edge 3. Regular squares leave a 90° gap, so the
    // breadth-first placement does not close and the least-squares placement is used. The
    // problem is symmetric under the rotation by 120° about V and its objective is invariant
    // under similarities, so its minimiser gives each face an angle of 120° at V.
    let sq = "B2 B2 B2 B2 | B2 B2 B2 | A1";
    let text = format!(
        "face a: {sq}\nface b: {sq}\nface c: {sq}\nface a edge 0 ~ face b edge 3\nface b edge 0 ~ face c edge 3\nface c edge 0 ~ face a edge 3\n"
    );
    let input = input(&text);
    let i = inst(&input);
    let asm = &input.assembly;
    for s in &asm.shared {
        let a = edge_points(&i, asm, s.a.0, s.a.1);
        let mut b = edge_points(&i, asm, s.b.0, s.b.1);
        b.reverse();
        assert_eq!(a, b, "shared edge {s:?}");
    }
    for f in 0..3 {
        let c: Vec<Point> = (0..4).map(|e| edge_points(&i, asm, f, e)[0]).collect();
        assert!(area2(&c) > 0.1, "face {f} is counter-clockwise: {c:?}");
        let (v, next, prev) = (c[0], c[1], c[3]);
        let ang = |p: Point| (p[1] - v[1]).atan2(p[0] - v[0]);
        // The interior angle of a counter-clockwise polygon: from the next corner round to the
        // previous one.
        let mut angle = ang(prev) - ang(next);
        angle = angle.rem_euclid(2.0 * std::f64::consts::PI);
        assert!(
            (angle - 2.0 * std::f64::consts::PI / 3.0).abs() < 1e-6,
            "face {f}: angle {angle} at V"
        );
    }
}

#[test]
fn faces_that_cannot_be_drawn_are_refused() {
    let sq = "B2 B2 B2 B2 | B2 B2 B2 | A1";
    // Glued to itself: corners 0 and 3 become one point.
    let selfglued = input(&format!("face 0: {sq}\nface 0 edge 0 ~ face 0 edge 2\n"));
    let e = instantiate(&selfglued, &InstantiateOptions::default()).unwrap_err();
    assert_eq!(e.code(), "E1008", "{e}");
    // Two quads glued along two opposite edges (an annulus): both would need the same four
    // vertices in opposite orders, so one of them is clockwise or flat.
    let annulus = input(&format!(
        "face 0: {sq}\nface 1: {sq}\nface 0 edge 0 ~ face 1 edge 2\nface 0 edge 2 ~ face 1 edge 0\n"
    ));
    let e = instantiate(&annulus, &InstantiateOptions::default()).unwrap_err();
    assert_eq!(e.code(), "E1008", "{e}");
}

/// Two triangles C2 B2 B2 splitting the square [0, 2]² along its diagonal: face 0 is (0,0),
/// (2,0), (2,2); face 1 is (0,2), (0,0), (2,2); face 0 edge 2 (2,2) → (0,0) is face 1 edge 1.
const TRIANGLES: &str = "f\nC_2_0 - B_2_0 - B_2_0 / C_2_0 - B_2_0 - B_2_0 / 0 / 1\nC_2_0 - B_2_0 - B_2_0 / C_2_0 - B_2_0 - B_2_0 / 0 / 1\nc\n0.2 / 1.1\np\n";

#[test]
fn autofrac_point_sections_are_read_three_ways() {
    let pts = |p: &[(i64, i64, i64)]| -> Vec<[BigRational; 2]> {
        p.iter().map(|&(x, y, d)| [q(x, d), q(y, d)]).collect()
    };
    // 6 = Σ n_f points: the corners face after face.
    let a = input(&format!("{TRIANGLES}0 0\n2 0\n2 2\n0 2\n0 0\n2 2\n")).assembly;
    assert_eq!(a.coords.of(1).unwrap().kind, CoordKind::Corners);
    assert_eq!(
        a.coords.of(1).unwrap().points,
        pts(&[(0, 2, 1), (0, 0, 1), (2, 2, 1)])
    );
    // 4 = V points: the distinct vertices in order of first appearance: face 0 gives (0,0),
    // (2,0), (2,2); face 1's corner 0 is new, its corners 1 and 2 are face 0's corners 0 and 2.
    let b = input(&format!("{TRIANGLES}0 0\n2 0\n2 2\n0 2\n")).assembly;
    assert_eq!(
        b.coords.faces,
        a.coords
            .faces
            .iter()
            .map(|f| {
                let mut g = f.clone();
                g.spans = b.coords.of(f.face).unwrap().spans.clone();
                g
            })
            .collect::<Vec<_>>()
    );
    // 10 = K_2 points (1 for C2, 2 for each B2, per face): every control point at degree 2; the
    // shared diagonal is bent through (3/2, 1/2) on both sides.
    let text = format!("{TRIANGLES}0 0\n2 0\n2 1\n2 2\n1.5 0.5\n0 2\n0 0\n1.5 0.5\n2 2\n1 2\n");
    let c = input(&text);
    assert_eq!(
        c.assembly.coords.of(0).unwrap().kind,
        CoordKind::Controls { degree: 2 }
    );
    let i = inst(&c);
    assert_eq!(
        edge_points(&i, &c.assembly, 0, 2),
        vec![[2.0, 2.0], [1.5, 0.5], [0.0, 0.0]]
    );
    assert_eq!(
        edge_points(&i, &c.assembly, 1, 1),
        vec![[0.0, 0.0], [1.5, 0.5], [2.0, 2.0]]
    );
    // 5 points fit no reading (6, 10 or 14, or 4): the topology still reads the file, the
    // placement refuses with E0304 at the `p` line (line 6).
    let d = input(&format!("{TRIANGLES}0 0\n2 0\n2 2\n0 2\n0 0\n"));
    assert_eq!(d.faces().len(), 2);
    let e = instantiate(&d, &InstantiateOptions::default()).unwrap_err();
    assert_eq!(e.code(), "E0304");
    let lacuna::geometry::GeometryError::Lacuna(le) = e else {
        panic!("a lacuna error")
    };
    assert_eq!(le.span().map(|s| s.line), Some(6));
    assert!(le.to_string().contains("6 (the corners"), "{le}");
    // Corners that do not match across the shared edge: kept as E0211 for the placement.
    let m = input(&format!("{TRIANGLES}0 0\n2 0\n2 2\n0 2\n0 0\n2 3\n"));
    let e = instantiate(&m, &InstantiateOptions::default()).unwrap_err();
    assert_eq!(e.code(), "E0211");
}

#[test]
fn the_fixture_p_section_is_read_as_corners() {
    let a = load_input("autofrac-two-quads").unwrap().assembly;
    // The file's points 5–8: face 1 is (10,10), (0,10), (0,0), (10,0).
    assert_eq!(a.coords.of(1).unwrap().kind, CoordKind::Corners);
    assert_eq!(a.coords.of(1).unwrap().points[3], [q(10, 1), q(0, 1)]);
}

#[test]
fn corners_on_the_command_line() {
    let dir = std::env::temp_dir().join(format!("lacuna-place-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("q.json");
    let (code, _, err) = lacuna(&[
        "render",
        QUAD,
        "--corners",
        "0 0, 2 0, 2 1, 0 1",
        "--level",
        "0",
        "--json-out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    let poly = v["cells"][0]["polygon"].as_array().unwrap();
    let pts: Vec<(f64, f64)> = poly
        .iter()
        .map(|p| (p[0].as_f64().unwrap(), p[1].as_f64().unwrap()))
        .collect();
    // Level 0 of the rectangle, from its canonical edge (B2 first: written edge 1), each B2
    // flattened to 4 segments: (2,0) … (2,1), then (2,1) → (0,1) (C2), then (0,1) … (0,0).
    for corner in [
        (0.0, 0.0),
        (2.0, 0.0),
        (2.0, 1.0),
        (0.0, 1.0),
        (2.0, 0.5),
        (0.0, 0.5),
    ] {
        assert!(pts.contains(&corner), "{corner:?} in {pts:?}");
    }
    assert!(pts
        .iter()
        .all(|p| (0.0..=2.0).contains(&p.0) && (0.0..=1.0).contains(&p.1)));
    let (code, _, err) = lacuna(&[
        "render",
        QUAD,
        "--corners",
        "0 0, 2 0, 2 1",
        "--json-out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 2);
    assert!(err.starts_with("error[E0210]"), "{err}");
    let (code, _, err) = lacuna(&["measure", "two-quads", "--corners", "0 0, 2 0, 2 1, 0 1"]);
    assert_eq!(code, 2);
    assert!(err.starts_with("error[E0215]"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

fn affine(m: &[f64; 6], p: Point) -> Point {
    [
        m[0] * p[0] + m[1] * p[1] + m[4],
        m[2] * p[0] + m[3] * p[1] + m[5],
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    /// Affine invariance of the BC-IFS: the sub-face operators are barycentric (every column
    /// sums to 1) and do not depend on where the start face is, so giving the corners A(c) of the
    /// default corners c maps every level-1 control point p to A(p).
    #[test]
    fn affine_images_of_the_corners_give_affine_images_of_the_cells(
        which in 0usize..3,
        m in proptest::array::uniform6(-2.0f64..2.0),
    ) {
        let det = m[0] * m[3] - m[1] * m[2];
        prop_assume!(det > 0.2);
        let name = ["F0", "square-B2", "triangle-C2"][which];
        let base = load_input(name).unwrap();
        let n = base.assembly.faces[0].1.boundary.len();
        let corners: Vec<String> = regular_polygon(n)
            .into_iter()
            .map(|p| {
                let a = affine(&m, p);
                format!("{} {}", a[0], a[1])
            })
            .collect();
        let mut moved = base.clone();
        set_corners(&mut moved.assembly, &corners.join(", ")).unwrap();
        let (i, j) = (inst(&base), inst(&moved));
        let mut cells = Vec::new();
        i.walk(1, false, |c| cells.push(c.points.to_vec()));
        let mut k = 0;
        j.walk(1, false, |c| {
            for (p, r) in c.points.iter().zip(&cells[k]) {
                let want = affine(&m, *r);
                assert!(
                    (p[0] - want[0]).abs() < 1e-9 && (p[1] - want[1]).abs() < 1e-9,
                    "{name}: cell {k}: {p:?} != {want:?}"
                );
            }
            k += 1;
        });
        prop_assert_eq!(k, cells.len());
    }
}
