// Geometry (issue #6): instantiation is exact, level-1 cells tile the face without overlap, the
// observed holes and components match the exact counts, exports are well formed, box counting
// recovers known dimensions. Also writes the pictures of docs/images/ (made by the code).

use lacuna::{
    box_dimension, check_cells, counts, exact_topology, instantiate, load_input, measure,
    write_json, write_obj, write_png, write_svg, BBox, Instance, InstantiateOptions,
    MeasureOptions, Raster,
};

const BUILT_IN: [&str; 5] = [
    "F0",
    "square-B2",
    "triangle-C2",
    "two-quads",
    "cycle-sqrt17",
];

fn inst(name: &str) -> Instance {
    let input = load_input(name).unwrap_or_else(|e| panic!("{name}: {e}"));
    instantiate(&input, &InstantiateOptions::default()).unwrap_or_else(|e| panic!("{name}: {e}"))
}

#[test]
fn instantiated_faces_satisfy_every_equation_exactly() {
    for name in BUILT_IN {
        let i = inst(name);
        i.check_exact().unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(
            i.fit_residual < 0.05,
            "{name}: template residual {}",
            i.fit_residual
        );
    }
}

#[test]
fn user_values_are_kept_exactly() {
    let input = load_input("F0").unwrap();
    let first = inst("F0").parameters[0].clone();
    let v = num_rational::BigRational::new(1.into(), 7.into());
    let opts = InstantiateOptions {
        values: vec![(first.0.clone(), v.clone())],
        ..InstantiateOptions::default()
    };
    let i = instantiate(&input, &opts).unwrap();
    assert_eq!(i.parameters[0], (first.0, v.clone()));
    i.check_exact().unwrap();
    let bad = InstantiateOptions {
        values: vec![("T0.T9[0][0]".into(), v.clone())],
        ..InstantiateOptions::default()
    };
    assert_eq!(instantiate(&input, &bad).unwrap_err().code(), "E1002");
}

#[test]
fn level_one_cells_tile_the_face_without_overlap() {
    for name in BUILT_IN {
        let i = inst(name);
        let bb = lacuna::bounds(&i, 4);
        let mut whole = Raster::fitting(bb, 1024, 8);
        i.walk(0, false, |c| {
            whole.fill_polygon(&i.cell_polygon(c.ty, c.points, 4))
        });
        let mut cells = Raster::fitting(bb, 1024, 8);
        i.walk(1, false, |c| {
            cells.fill_polygon(&i.cell_polygon(c.ty, c.points, 4))
        });
        let px = cells.pixel_area();
        let overlap = cells.overlap_count() as f64 * px;
        let area = whole.covered_count() as f64 * px;
        assert!(
            overlap < 1e-4 * area,
            "{name}: level-1 cells overlap on {overlap}"
        );
        // Inside the level-0 face: no covered pixel outside it (a pixel of slack at the border).
        let outside = (0..cells.size * cells.size)
            .filter(|&p| cells.counts[p] > 0 && whole.counts[p] == 0)
            .count();
        assert!(
            outside as f64 <= 2e-3 * whole.covered_count() as f64,
            "{name}: {outside} pixels outside"
        );
    }
}

#[test]
fn observed_holes_and_components_match_the_exact_counts() {
    for name in ["F0", "square-B2"] {
        let i = inst(name);
        let r = measure(
            &i,
            &MeasureOptions {
                level: 3,
                raster: 2048,
                ..MeasureOptions::default()
            },
        )
        .unwrap();
        assert!(r.verified, "{name}: {:?}", r.failures);
        for l in &r.levels {
            assert_eq!(l.components, 1, "{name} level {}", l.level);
            assert_eq!(
                l.holes.to_string(),
                l.exact.holes.to_string(),
                "{name} level {}",
                l.level
            );
        }
        // Area decreases with the level; the exact counts were compared level by level.
        for w in r.levels.windows(2) {
            assert!(
                w[1].area < w[0].area,
                "{name}: area grows at level {}",
                w[1].level
            );
        }
    }
}

#[test]
fn exact_holes_of_f0_by_hand() {
    // F0 alone: every edge of the face is free. Level 1: the central lacuna only (its three
    // gaps are notches): 1 hole, N^L = 1 + 3/2 = 5/2.
    let i = inst("F0");
    let t = exact_topology(&i, 2).unwrap();
    assert_eq!(t[1].holes.to_string(), "1");
    assert_eq!(t[1].notches.to_string(), "3");
    assert_eq!(t[1].lacunas.to_string(), "5/2");
}

#[test]
fn svg_json_obj_png_are_well_formed() {
    let i = inst("F0");
    for level in 0..=2u32 {
        let n = counts(&i.types, level as u64)[level as usize]
            .faces
            .to_string();
        let mut svg = Vec::new();
        write_svg(&i, level, 4, &mut svg).unwrap();
        let svg = String::from_utf8(svg).unwrap();
        assert_eq!(svg.matches("<path ").count().to_string(), n);
        assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
        let mut json = Vec::new();
        write_json(&i, level, 4, &mut json).unwrap();
        let v: serde_json::Value = serde_json::from_slice(&json).unwrap();
        assert_eq!(v["cells"].as_array().unwrap().len().to_string(), n);
    }
    let mut a = Vec::new();
    let mut b = Vec::new();
    write_svg(&i, 2, 4, &mut a).unwrap();
    write_svg(&i, 2, 4, &mut b).unwrap();
    assert_eq!(a, b, "deterministic");
    let mut obj = Vec::new();
    write_obj(&i, 1, 2, 0.1, &mut obj).unwrap();
    let obj = String::from_utf8(obj).unwrap();
    // 6 prisms; a cell has 3 B2 edges (2 segments each) and 3 C2 edges: 9 corners.
    assert_eq!(
        obj.lines().filter(|l| l.starts_with("f ")).count(),
        6 * (2 + 9)
    );
    let mut png = Vec::new();
    write_png(&lacuna::render_raster(&i, 2, 64, 2), &mut png).unwrap();
    assert_eq!(&png[1..4], b"PNG");
}

#[test]
fn cell_limit_is_refused_before_rendering() {
    let i = inst("F0");
    assert!(check_cells(&i, 3, 216).is_ok());
    assert_eq!(check_cells(&i, 4, 1000).unwrap_err().code(), "E1003");
}

#[test]
fn box_counting_recovers_known_dimensions() {
    // A filled square → 2.
    let mut sq = Raster::unit(1024);
    sq.fill_polygon(&[[0.1, 0.1], [0.9, 0.1], [0.9, 0.9], [0.1, 0.9]]);
    let d = box_dimension(&sq, 4).slope;
    assert!((d - 2.0).abs() < 0.05, "square {d}");
    // A segment → 1.
    let mut seg = Raster::unit(1024);
    seg.draw_segment([0.1, 0.2], [0.9, 0.7]);
    let d = box_dimension(&seg, 4).slope;
    assert!((d - 1.0).abs() < 0.05, "segment {d}");
    // The Sierpinski triangle (level 10, rasterised at 1024) → ln 3 / ln 2 ≈ 1.585.
    let mut sier = Raster::unit(1024);
    let mut stack = vec![([0.0, 0.0], [1.0, 0.0], [0.5, 0.866_025_4], 0u32)];
    while let Some((a, b, c, d)) = stack.pop() {
        if d == 10 {
            sier.fill_polygon(&[a, b, c]);
            sier.draw_segment(a, b);
            sier.draw_segment(b, c);
            sier.draw_segment(c, a);
            continue;
        }
        let m = |p: [f64; 2], q: [f64; 2]| [(p[0] + q[0]) / 2.0, (p[1] + q[1]) / 2.0];
        let (ab, bc, ca) = (m(a, b), m(b, c), m(c, a));
        stack.push((a, ab, ca, d + 1));
        stack.push((ab, b, bc, d + 1));
        stack.push((ca, bc, c, d + 1));
    }
    let f = box_dimension(&sier, 4);
    let expected = 3f64.ln() / 2f64.ln();
    assert!(
        (f.slope - expected).abs() < 0.05,
        "Sierpinski {} (residual {})",
        f.slope,
        f.residual
    );
    let _ = BBox::empty();
}

/// Writes docs/images/<name>.svg (level 3) for every built-in face; the pictures of GEOMETRY.md.
#[test]
fn pictures_for_the_docs() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/images");
    let dir = if dir.exists() {
        dir
    } else {
        std::path::PathBuf::from("/work/main/docs/images")
    };
    for name in BUILT_IN {
        let i = inst(name);
        let mut svg = Vec::new();
        write_svg(&i, 3, 4, &mut svg).unwrap();
        std::fs::write(dir.join(format!("{name}.svg")), svg).unwrap();
    }
}

#[test]
fn triangulation_covers_a_non_convex_polygon() {
    // An L shape (area 3) has a reflex corner: the ear clipping must not use it as an ear.
    let l: Vec<lacuna::Point> = vec![
        [0.0, 0.0],
        [2.0, 0.0],
        [2.0, 1.0],
        [1.0, 1.0],
        [1.0, 2.0],
        [0.0, 2.0],
    ];
    let tris = lacuna::triangulate(&l);
    assert_eq!(tris.len(), 4);
    let area: f64 = tris
        .iter()
        .map(|t| lacuna::signed_area(&[l[t[0]], l[t[1]], l[t[2]]]))
        .sum();
    assert!((area - 3.0).abs() < 1e-12, "{area}");
    assert!(tris
        .iter()
        .all(|t| lacuna::signed_area(&[l[t[0]], l[t[1]], l[t[2]]]) > 0.0));
}

#[test]
fn stl_prisms_are_closed_surfaces() {
    // A union of closed oriented surfaces: every directed edge a→b is matched by as many b→a.
    let input = lacuna::load_input("F0").unwrap();
    let inst = lacuna::instantiate(&input, &lacuna::InstantiateOptions::default()).unwrap();
    let mut buf = Vec::new();
    lacuna::write_stl(&inst, 1, 4, 0.1, &mut buf).unwrap();
    let text = String::from_utf8(buf).unwrap();
    let mut verts: Vec<String> = Vec::new();
    let mut edges: std::collections::HashMap<(String, String), i64> = Default::default();
    let mut facets = 0;
    for line in text.lines() {
        if let Some(v) = line.trim().strip_prefix("vertex ") {
            verts.push(v.to_string());
            if verts.len() == 3 {
                facets += 1;
                for k in 0..3 {
                    let (a, b) = (verts[k].clone(), verts[(k + 1) % 3].clone());
                    *edges.entry((a.clone(), b.clone())).or_default() += 1;
                    *edges.entry((b, a)).or_default() -= 1;
                }
                verts.clear();
            }
        }
    }
    assert!(facets > 0);
    assert!(
        edges.values().all(|&c| c == 0),
        "an edge is not matched by its reverse"
    );
}

#[test]
fn html_report_is_self_contained_and_complete() {
    let dir = std::env::temp_dir().join(format!("lacuna-report-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("f0.html");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_lacuna"))
        .args([
            "report",
            "F0",
            "--level",
            "2",
            "--raster",
            "256",
            "--out",
            path.to_str().unwrap(),
        ])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let html = std::fs::read_to_string(&path).unwrap();
    // Pictures of levels 0, 1, 2, the type graph and three plots, all inline; no external file.
    assert_eq!(html.matches("<figure").count(), 3);
    assert_eq!(html.matches("<svg").count(), 3 + 1 + 3);
    assert!(!html.contains("<?xml") && !html.contains("src=\"") && !html.contains("<script"));
    for section in [
        "Type graph",
        "Counts",
        "Limit ratio R",
        "Constraint solver",
        "Measures",
    ] {
        assert!(
            html.contains(&format!("<h2>{section}")),
            "missing section {section}"
        );
    }
    // The counts table shows the spec's numbers and R = 1/3.
    assert!(html.contains("<td>35/2</td>") && html.contains("limit ratio R = 1/3"));
    assert!(html.contains("Verdict: VERIFIED"));
}
