// Geometry (issue #6): instantiation is exact, level-1 cells tile the face without overlap, the
// observed holes and components match the exact counts, exports are well formed, box counting
// recovers known dimensions. Also writes the pictures of docs/images/ (made by the code).

mod common;
use common::inst;
use lacuna::{
    export::write_json, export::write_obj, export::write_png, export::write_svg,
    geometry::box_dimension, geometry::instantiate, geometry::BBox, geometry::InstantiateOptions,
    geometry::Raster, input::load_input, measure::check_cells, measure::exact_topology,
    measure::measure, measure::MeasureOptions, topology::counts,
};

const BUILT_IN: [&str; 5] = [
    "F0",
    "square-B2",
    "triangle-C2",
    "two-quads",
    "cycle-sqrt17",
];

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
    for name in face_fixtures() {
        let i = inst(name);
        let bb = lacuna::geometry::bounds(&i, 4);
        // The face itself finely flattened: the level-1 cells' flattened Bézier pieces are chords
        // of the curve, inside it (a digon's bulging edge is most of its boundary).
        let mut whole = Raster::fitting(bb, 1024, 8);
        i.walk(0, false, |c| {
            whole.fill_polygon(&i.cell_polygon(c.ty, c.points, 64))
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

/// Every built-in fixture made of faces (`lacuna library` lists them; automata are skipped).
fn face_fixtures() -> Vec<&'static str> {
    lacuna::input::library()
        .iter()
        .map(|(n, _)| *n)
        .filter(|n| load_input(n).is_ok())
        .collect()
}

#[test]
fn observed_holes_and_components_match_the_exact_counts_at_levels_1_to_4() {
    let names = face_fixtures();
    // The seven face fixtures of the library at the time of writing; a new one is measured too.
    assert!(names.len() >= 7, "{names:?}");
    for name in names {
        let i = inst(name);
        // Raster 256 is only the smallest: each level gets the raster its smallest hole needs.
        let r = measure(
            &i,
            &MeasureOptions {
                level: 4,
                raster: 256,
                density_grid: 0,
                ..MeasureOptions::default()
            },
        )
        .unwrap();
        assert!(r.verified, "{name}: {:?}", r.failures);
        // Independent derivation of the components: union-find over the cells.
        let by_cells = lacuna::topology::components_by_cells(&i.types, &i.glue, 4, 1_000_000)
            .expect("under the cell limit")
            .expect("no edge held by three cells");
        for l in &r.levels {
            assert_eq!(
                l.components as u64, l.exact.components,
                "{name} level {}",
                l.level
            );
            assert_eq!(l.exact.components, by_cells[l.level as usize] as u64);
            assert_eq!(
                l.holes.to_string(),
                l.exact.holes.to_string(),
                "{name} level {}",
                l.level
            );
            if l.level >= 1 {
                let px = l.smallest_hole_pixels.expect("a hole from level 1 on");
                assert!(
                    px >= lacuna::measure::MIN_HOLE_WIDTH,
                    "{name} level {}: {px}",
                    l.level
                );
            }
        }
        // Area decreases with the level.
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
fn two_faces_without_a_shared_edge_are_two_components() {
    // Two F0 faces, nothing glued: by hand, 2 components at every level (the default placement
    // puts the second face 2.5 to the right, 0.5 apart), and twice F0's holes (1, 13).
    let text =
        "face 0: C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A1\nface 1: C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A1\n";
    let f0 = load_input("F0").unwrap();
    let input = lacuna::input::Input {
        name: "two-apart".into(),
        assembly: lacuna::input::parse_text(&lacuna::Source {
            name: "two-apart".into(),
            text: text.into(),
        })
        .unwrap(),
    };
    assert_eq!(input.faces()[0], f0.faces()[0], "the face is F0's");
    let i = instantiate(&input, &InstantiateOptions::default()).unwrap();
    let t = exact_topology(&i, 2).unwrap();
    assert!(t.iter().all(|l| l.components == 2));
    assert_eq!(
        t.iter().map(|l| l.holes.to_string()).collect::<Vec<_>>(),
        ["0", "2", "26"]
    );
    let r = measure(
        &i,
        &MeasureOptions {
            level: 2,
            raster: 256,
            density_grid: 0,
            ..MeasureOptions::default()
        },
    )
    .unwrap();
    assert!(r.verified, "{:?}", r.failures);
    assert!(r.levels.iter().all(|l| l.components == 2));
}

#[test]
fn a_mismatch_is_a_failure_with_a_code() {
    // Capping the raster below what level 3 of F0 needs: the measure says so (E1011) instead of
    // reporting a silently different count.
    let r = measure(
        &inst("F0"),
        &MeasureOptions {
            level: 3,
            raster: 64,
            max_raster: 64,
            density_grid: 0,
            ..MeasureOptions::default()
        },
    )
    .unwrap();
    assert!(!r.verified);
    assert!(
        r.failures.iter().any(|f| f.starts_with("E1011 level 3")),
        "{:?}",
        r.failures
    );
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
    write_png(&lacuna::export::render_raster(&i, 2, 64, 2), &mut png).unwrap();
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
    // The middle-third Cantor set × [0, 1] → 1 + ln 2 / ln 3 ≈ 1.631. Level 8 (intervals of
    // 3^-8 < 1/4096) on a 4096 raster; a pixel column is covered when the interval meets it (box
    // counting counts boxes that meet the set). Dyadic boxes against triadic gaps make ln N(k)
    // wobble around the line, hence the tolerance of 0.05.
    let n = 4096usize;
    let mut cantor = Raster::unit(n);
    let mut intervals = vec![(0.0f64, 1.0f64)];
    for _ in 0..8 {
        intervals = intervals
            .iter()
            .flat_map(|&(a, b)| {
                let t = (b - a) / 3.0;
                [(a, a + t), (b - t, b)]
            })
            .collect();
    }
    for (a, b) in intervals {
        let (c0, c1) = (
            (a * n as f64) as usize,
            ((b * n as f64).ceil() as usize).min(n),
        );
        for row in 0..n {
            for c in c0..c1 {
                cantor.counts[row * n + c] = 1;
            }
        }
    }
    let f = box_dimension(&cantor, 4);
    let expected = 1.0 + 2f64.ln() / 3f64.ln();
    assert!(
        (f.slope - expected).abs() < 0.05,
        "Cantor × interval {} (residual {})",
        f.slope,
        f.residual
    );
    let _ = BBox::empty();
}

#[test]
fn f0_area_and_perimeter_factors_are_stable_across_levels() {
    // Only areas and perimeters matter here: a small raster keeps the test fast (the holes of
    // level 5 are then below the resolution, which the report says and this test ignores).
    let r = measure(
        &inst("F0"),
        &MeasureOptions {
            level: 5,
            raster: 64,
            max_raster: 64,
            density_grid: 0,
            ..MeasureOptions::default()
        },
    )
    .unwrap();
    let ratios = |v: Vec<f64>| v.windows(2).map(|w| w[1] / w[0]).collect::<Vec<f64>>();
    let area = ratios(r.levels.iter().map(|l| l.area).collect());
    let perim = ratios(r.levels.iter().map(|l| l.perimeter).collect());
    // The area ratio is stable: A_{i+1}/A_i for i = 0..4 all within 1% of the last one (each
    // subdivision removes about the same fraction of every cell). The perimeter ratio is not
    // stable at low levels: P_i counts the boundaries of all holes opened so far, so P_{i+1}/P_i
    // converges to its limit geometrically (measured: 1.41, 1.85, 2.11, 2.21, 2.24). The test
    // states that: the changes of the perimeter ratio shrink by a factor of at most 0.7 per
    // level, and the last one is under 2%.
    let last = area[area.len() - 1];
    for (i, x) in area.iter().enumerate() {
        assert!(
            (x / last - 1.0).abs() < 0.01,
            "F0 area ratio at level {}: {x} against {last} ({area:?})",
            i + 1
        );
    }
    let steps: Vec<f64> = perim.windows(2).map(|w| w[1] - w[0]).collect();
    for w in steps.windows(2) {
        assert!(
            w[1] > 0.0 && w[1] <= 0.7 * w[0],
            "F0 perimeter ratios do not converge geometrically: {perim:?}"
        );
    }
    let (p4, p5) = (perim[perim.len() - 2], perim[perim.len() - 1]);
    assert!((p5 / p4 - 1.0).abs() < 0.02, "{perim:?}");
    // F_A is exp(slope) of ln(A_i/A_0) against i: with stable ratios, the slope matches the mean
    // log ratio within 0.01 (for the perimeter, whose ratios still grow, within 0.15).
    for (what, factor, v, tol) in [
        ("area", r.area_factor, &area, 0.01),
        ("perimeter", r.perimeter_factor, &perim, 0.15),
    ] {
        let logs: Vec<f64> = v.iter().map(|x| x.ln()).collect();
        let mean = logs.iter().sum::<f64>() / logs.len() as f64;
        assert!(
            (factor.ln() - mean).abs() < tol,
            "F0 {what} factor {factor} against mean ratio {}",
            mean.exp()
        );
    }
    // The area shrinks and the perimeter grows (THEORY §7: lacunas remove area, add boundary).
    assert!(r.area_factor < 1.0 && r.perimeter_factor > 1.0);
}

/// A decoder for the PNGs lacuna writes (written for the test: signature, chunk CRCs, IHDR, one
/// zlib stream of stored deflate blocks with its Adler-32): returns (width, height, bit depth,
/// the filtered scanlines).
fn decode_png(png: &[u8]) -> (u32, u32, u8, Vec<u8>) {
    fn crc(data: &[u8]) -> u32 {
        let mut c = 0xFFFF_FFFFu32;
        for &b in data {
            c ^= u32::from(b);
            for _ in 0..8 {
                c = if c & 1 == 1 {
                    (c >> 1) ^ 0xEDB8_8320
                } else {
                    c >> 1
                };
            }
        }
        !c
    }
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n", "signature");
    let mut pos = 8;
    let (mut ihdr, mut idat, mut end) = (Vec::new(), Vec::new(), false);
    while pos < png.len() {
        let len = u32::from_be_bytes(png[pos..pos + 4].try_into().unwrap()) as usize;
        let kind = &png[pos + 4..pos + 8];
        let data = &png[pos + 8..pos + 8 + len];
        let stored = u32::from_be_bytes(png[pos + 8 + len..pos + 12 + len].try_into().unwrap());
        assert_eq!(stored, crc(&png[pos + 4..pos + 8 + len]), "CRC of {kind:?}");
        match kind {
            b"IHDR" => ihdr = data.to_vec(),
            b"IDAT" => idat.extend_from_slice(data),
            b"IEND" => end = true,
            _ => panic!("unexpected chunk {kind:?}"),
        }
        pos += 12 + len;
    }
    assert!(end && ihdr.len() == 13);
    let w = u32::from_be_bytes(ihdr[0..4].try_into().unwrap());
    let h = u32::from_be_bytes(ihdr[4..8].try_into().unwrap());
    assert_eq!(
        &ihdr[9..],
        &[0, 0, 0, 0],
        "grayscale, deflate, filter 0, no interlace"
    );
    assert_eq!((idat[0], idat[1]), (0x78, 0x01));
    assert_eq!(
        (u16::from(idat[0]) << 8 | u16::from(idat[1])) % 31,
        0,
        "zlib header check"
    );
    let (mut i, mut raw) = (2, Vec::new());
    loop {
        let last = idat[i] & 1 == 1;
        assert_eq!(idat[i] >> 1, 0, "stored block");
        let len = u16::from_le_bytes([idat[i + 1], idat[i + 2]]);
        let nlen = u16::from_le_bytes([idat[i + 3], idat[i + 4]]);
        assert_eq!(len, !nlen);
        raw.extend_from_slice(&idat[i + 5..i + 5 + len as usize]);
        i += 5 + len as usize;
        if last {
            break;
        }
    }
    let (mut a, mut b) = (1u32, 0u32);
    for &x in &raw {
        a = (a + u32::from(x)) % 65_521;
        b = (b + a) % 65_521;
    }
    assert_eq!(&idat[i..], &((b << 16) | a).to_be_bytes(), "Adler-32");
    (w, h, ihdr[8], raw)
}

#[test]
fn density_maps_are_right_and_decode() {
    // A filled square covering the whole window: uniform 1 (unit test in density.rs); here a
    // structure: the mean density of F0 at level 2 equals A_2 / s² within the raster error.
    let i = inst("F0");
    let r = measure(
        &i,
        &MeasureOptions {
            level: 2,
            raster: 256,
            density_grid: 32,
            ..MeasureOptions::default()
        },
    )
    .unwrap();
    let d = r.density.clone().expect("a density summary");
    let side = lacuna::geometry::bounds(&i, 4).size();
    let fraction = r.area / (side * side);
    assert_eq!(d.area_fraction, Some(fraction));
    // 512² samples: the boundary pixels of the cells are about 4·P·512/s of 512², well under 1%.
    assert!(
        (d.mean - fraction).abs() < 0.01,
        "{} against {fraction}",
        d.mean
    );
    assert!(d.min == 0.0 && d.max <= 1.0 && d.max > 0.9, "{d:?}");
    // The PNG: 32 × 32 8-bit gray, one pixel per block, 255·(1 − density).
    let map = lacuna::measure::density_map(&i, 2, 32, 4);
    let mut png = Vec::new();
    lacuna::export::write_density_png(&map, &mut png).unwrap();
    let (w, h, depth, raw) = decode_png(&png);
    assert_eq!((w, h, depth), (32, 32, 8));
    assert_eq!(raw.len(), 32 * 33);
    for (row, line) in raw.chunks(33).enumerate() {
        assert_eq!(line[0], 0, "filter type");
        for (col, &g) in line[1..].iter().enumerate() {
            let v = map.values[row * 32 + col];
            assert_eq!(g, (255.0 * (1.0 - v)).round() as u8);
        }
    }
    // The 1-bit picture decodes too: F0 level 0 is a filled face, its centre pixel black.
    let mut png1 = Vec::new();
    write_png(&lacuna::export::render_raster(&i, 0, 64, 4), &mut png1).unwrap();
    let (w, h, depth, raw) = decode_png(&png1);
    assert_eq!((w, h, depth, raw.len()), (64, 64, 1, 64 * 9));
    assert_eq!(raw[32 * 9 + 1 + 4] & 0x80, 0, "centre covered (black)");
    assert_eq!(raw[1], 0xFF, "corner white");
}

/// Writes docs/images/<name>.svg (level 3) for every built-in face, colour PNGs of three inputs and
/// a density map: the pictures of GEOMETRY.md.
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
    // Colour PNG pictures (with their legends) and a density map.
    for (name, level, width) in [
        ("F0", 4, 640),
        ("triangle-C2", 3, 640),
        ("delayed-B2-C2", 3, 640),
    ] {
        let i = inst(name);
        let opts = lacuna::export::PictureOptions {
            width,
            ..Default::default()
        };
        let mut png = Vec::new();
        lacuna::export::write_png_picture(&i, level, &opts, &mut png).unwrap();
        std::fs::write(dir.join(format!("{name}-level{level}.png")), png).unwrap();
    }
    // The digon of Bézier edges under A1 (issue #36): its two-sided lacuna is a lens.
    for level in [1, 3] {
        let i = inst("B2 B2 | B2 B2 B2 | A1");
        let opts = lacuna::export::PictureOptions {
            width: 480,
            ..Default::default()
        };
        let mut png = Vec::new();
        lacuna::export::write_png_picture(&i, level, &opts, &mut png).unwrap();
        std::fs::write(dir.join(format!("digon-B2-A1-level{level}.png")), png).unwrap();
    }
    let i = inst("F0");
    let map = lacuna::measure::density_map(&i, 4, 64, 4);
    let pic = lacuna::export::DensityPicture {
        size: 448,
        level: 4,
        window: lacuna::geometry::bounds(&i, 4).size(),
        outside: lacuna::measure::density_map(&i, 0, 64, 4)
            .values
            .iter()
            .map(|&v| v == 0.0)
            .collect(),
    };
    let mut png = Vec::new();
    lacuna::export::write_density_picture(&map, &pic, &mut png).unwrap();
    std::fs::write(dir.join("F0-density-level4.png"), png).unwrap();
}

#[test]
fn triangulation_covers_a_non_convex_polygon() {
    // An L shape (area 3) has a reflex corner: the ear clipping must not use it as an ear.
    let l: Vec<lacuna::geometry::Point> = vec![
        [0.0, 0.0],
        [2.0, 0.0],
        [2.0, 1.0],
        [1.0, 1.0],
        [1.0, 2.0],
        [0.0, 2.0],
    ];
    let tris = lacuna::export::triangulate(&l);
    assert_eq!(tris.len(), 4);
    let area: f64 = tris
        .iter()
        .map(|t| lacuna::geometry::signed_area(&[l[t[0]], l[t[1]], l[t[2]]]))
        .sum();
    assert!((area - 3.0).abs() < 1e-12, "{area}");
    assert!(tris
        .iter()
        .all(|t| lacuna::geometry::signed_area(&[l[t[0]], l[t[1]], l[t[2]]]) > 0.0));
}

#[test]
fn stl_prisms_are_closed_surfaces() {
    // A union of closed oriented surfaces: every directed edge a→b is matched by as many b→a.
    let input = lacuna::input::load_input("F0").unwrap();
    let inst =
        lacuna::geometry::instantiate(&input, &lacuna::geometry::InstantiateOptions::default())
            .unwrap();
    let mut buf = Vec::new();
    lacuna::export::write_stl(&inst, 1, 4, 0.1, &mut buf).unwrap();
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
    let dir = common::scratch("report");
    let path = dir.join("f0.html");
    let (code, _, err) = common::lacuna(&[
        "report",
        "F0",
        "--level",
        "2",
        "--raster",
        "256",
        "--out",
        path.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
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

/// Issue #36: every two-edge face of the edge kinds B2, C2, B3, C3 (E = B2 B2 B2) under A1 and A3,
/// with its outline derived by hand. A digon's corners are (−1, 1/4) and (1, 1/4). Every Bézier
/// edge, `B2` or `B3` alike (n counts its pieces; the curve's degree is `--degree`, 2 by default),
/// has one inner control point, at the chord's middle pushed outwards by ½·4·½·½ = ½ of the chord
/// (length 2), so 1 off the chord; the curve's middle (P0 + 2P1 + P2)/4 is ½ off, its farthest
/// point. A Cantor edge stays on the chord. So the outline spans x ∈ [−1, 1] and, across the
/// chord, the sum of both edges' offsets: height/width = (off(e0) + off(e1))/2, with off = ½ for
/// a Bézier edge and 0 for a Cantor edge. Two Cantor edges make a flat face: a forced collapse
/// (E1013), refused by `render`, stated by `verify`. Every other face draws at levels 1 and 2
/// (every level checked, E1041 otherwise) and measures its exact holes and components at level 2.
#[test]
fn two_edge_faces_have_their_hand_derived_outline_or_are_a_forced_collapse() {
    let off = |e: &str| match e.starts_with('B') {
        true => 1.0 / 2.0,
        false => 0.0,
    };
    let dir = common::scratch("two-edge");
    for algorithm in ["A1", "A3"] {
        for e0 in ["B2", "C2", "B3", "C3"] {
            for e1 in ["B2", "C2", "B3", "C3"] {
                let face = format!("{e0} {e1} | B2 B2 B2 | {algorithm}");
                let input = load_input(&face).unwrap();
                let got = instantiate(&input, &InstantiateOptions::default());
                if e0.starts_with('C') && e1.starts_with('C') {
                    let e = got.err().unwrap_or_else(|| panic!("{face}: drawn flat"));
                    assert_eq!(e.code(), "E1013", "{face}: {e}");
                    continue;
                }
                let i = got.unwrap_or_else(|e| panic!("{face}: {e}"));
                let b = lacuna::geometry::bounds(&i, 256);
                let (w, h) = (b.max[0] - b.min[0], b.max[1] - b.min[1]);
                let want = (off(e0) + off(e1)) / 2.0;
                assert!((h / w - want).abs() < 1e-3, "{face}: {h}/{w}, want {want}");
                let png = dir.join(format!("{}.png", face.replace([' ', '|'], "")));
                let (code, _, err) = common::lacuna(&[
                    "render",
                    &face,
                    "--level",
                    "2",
                    "--png",
                    png.to_str().unwrap(),
                    "--size",
                    "200",
                ]);
                assert_eq!(code, 0, "{face}: {err}");
                let (code, out, err) =
                    common::lacuna(&["measure", &face, "--level", "2", "--raster", "512"]);
                assert_eq!(code, 0, "{face}: {err}");
                assert!(out.contains("verdict: VERIFIED"), "{face}: {out}");
            }
        }
    }
}
