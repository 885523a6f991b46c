// Pictures (issue #22): the colour PNG is read back and its pixels checked — each type's colour
// inside its cells, the background in a hole, the legend below the picture; the density picture
// shows the colour of each block; the SVG draws the curves themselves and has one legend entry per
// type; outlines scale with the cells of the level.

mod common;
use common::inst;
use lacuna::export::{
    density_colour, outline, stroke_width, type_colour, write_density_picture, write_png_picture,
    write_svg_picture, Background, DensityPicture, Frame, PictureOptions,
};
use lacuna::geometry::{signed_area, Instance, Point};

/// Decodes an 8-bit RGBA PNG: (width, height, pixels).
fn decode(bytes: &[u8]) -> (u32, u32, Vec<[u8; 4]>) {
    let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgba);
    assert_eq!(info.bit_depth, png::BitDepth::Eight);
    let px = buf[..info.buffer_size()]
        .chunks(4)
        .map(|p| [p[0], p[1], p[2], p[3]])
        .collect();
    (info.width, info.height, px)
}

fn centroid(poly: &[Point]) -> Point {
    let a = signed_area(poly);
    let (mut cx, mut cy) = (0.0, 0.0);
    for k in 0..poly.len() {
        let (p, q) = (poly[k], poly[(k + 1) % poly.len()]);
        let w = p[0] * q[1] - q[0] * p[1];
        cx += (p[0] + q[0]) * w;
        cy += (p[1] + q[1]) * w;
    }
    [cx / (6.0 * a), cy / (6.0 * a)]
}

/// Distance from `p` to the polygon's boundary, and whether `p` is inside (even-odd).
fn inside_by(poly: &[Point], p: Point) -> (bool, f64) {
    let mut inside = false;
    let mut d = f64::INFINITY;
    for k in 0..poly.len() {
        let (a, b) = (poly[k], poly[(k + 1) % poly.len()]);
        if (a[1] > p[1]) != (b[1] > p[1])
            && p[0] < a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0])
        {
            inside = !inside;
        }
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let t = (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (dx * dx + dy * dy)).clamp(0.0, 1.0);
        d = d.min((p[0] - a[0] - t * dx).hypot(p[1] - a[1] - t * dy));
    }
    (inside, d)
}

/// Samples every cell of `level` well inside (at its centroid, when that lies at least 3 pixels
/// plus the outline inside the cell) and checks the pixel has the type's colour exactly; returns
/// the types seen.
fn check_cell_colours(i: &Instance, level: u32, width: u32) -> Vec<usize> {
    let opts = PictureOptions {
        width,
        ..Default::default()
    };
    let mut bytes = Vec::new();
    write_png_picture(i, level, &opts, &mut bytes).unwrap();
    let (w, h, px) = decode(&bytes);
    let f = Frame::of(i, width);
    assert_eq!(w, width);
    assert!(h > f.height, "the legend is below the picture");
    let stroke = stroke_width(i, level, f.scale) * f.scale;
    let mut seen = Vec::new();
    let mut sampled = 0;
    i.walk(level, false, |c| {
        let poly = outline(i, c.ty, c.points, 0.01 / f.scale);
        let p = centroid(&poly);
        let (inside, d) = inside_by(&poly, p);
        if !inside || d * f.scale < 3.0 + stroke {
            return;
        }
        let [x, y] = f.to_pixel(p);
        let got = px[y as usize * w as usize + x as usize];
        let want = type_colour(c.ty);
        assert_eq!(
            got,
            [want[0], want[1], want[2], 255],
            "{} level {level}: a T{} cell at pixel ({x:.0}, {y:.0})",
            i.name,
            c.ty
        );
        sampled += 1;
        if !seen.contains(&c.ty) {
            seen.push(c.ty);
        }
    });
    assert!(sampled > 0, "{}: no cell sampled", i.name);
    seen.sort();
    seen
}

#[test]
fn png_cells_have_their_types_colour() {
    // triangle-C2 at level 2 has cells of T1, T2 and T3; F0 at level 2 only T0.
    let t = inst("triangle-C2");
    assert_eq!(check_cell_colours(&t, 2, 600), vec![1, 2, 3]);
    assert_eq!(check_cell_colours(&inst("F0"), 2, 400), vec![0]);
}

#[test]
fn png_hole_shows_the_background_white_or_transparent() {
    // F0 level 1: the central lacuna contains the centre of the start face.
    let i = inst("F0");
    let mut centre = [0.0, 0.0];
    i.walk(0, false, |c| {
        centre = centroid(&outline(&i, c.ty, c.points, 1e-4))
    });
    for (background, want) in [
        (Background::White, [255, 255, 255, 255]),
        (Background::Transparent, [0, 0, 0, 0]),
    ] {
        let opts = PictureOptions {
            width: 300,
            background,
            legend: false,
            ..Default::default()
        };
        let mut bytes = Vec::new();
        write_png_picture(&i, 1, &opts, &mut bytes).unwrap();
        let (w, h, px) = decode(&bytes);
        let f = Frame::of(&i, 300);
        assert_eq!(h, f.height, "no legend");
        let [x, y] = f.to_pixel(centre);
        assert_eq!(
            px[y as usize * w as usize + x as usize],
            want,
            "{background:?}"
        );
        // A corner of the picture is background too; some pixel is covered.
        assert_eq!(px[0], want);
        assert!(px.iter().any(|p| p[3] == 255 && p[..3] == type_colour(0)));
    }
}

#[test]
fn density_picture_colours_each_block_and_has_a_colour_bar() {
    let i = inst("F0");
    let map = lacuna::measure::density_map(&i, 2, 16, 4);
    let pic = DensityPicture {
        size: 320,
        level: 2,
        window: lacuna::geometry::bounds(&i, 4).size(),
        outside: Vec::new(),
    };
    let mut bytes = Vec::new();
    write_density_picture(&map, &pic, &mut bytes).unwrap();
    let (w, h, px) = decode(&bytes);
    assert!(w > 320 && h > 320, "{w}×{h}");
    // Blocks are 20 × 20 pixels; the map starts at the margin m = 8 (half the 16-pixel text).
    let m = 8;
    for (row, col) in [(0, 0), (8, 8), (5, 11), (15, 15)] {
        let (x, y) = (m + col * 20 + 10, m + row * 20 + 10);
        let c = density_colour(map.values[row * 16 + col]);
        assert_eq!(
            px[y * w as usize + x],
            [c[0], c[1], c[2], 255],
            "block {row},{col}"
        );
    }
    // The colour bar: yellow (1) at its top, dark violet (0) at its bottom.
    let bx = m + 320 + m + 4;
    let near = |p: [u8; 4], c: [u8; 3]| (0..3).all(|k| p[k].abs_diff(c[k]) <= 4);
    assert!(near(px[(m + 1) * w as usize + bx], density_colour(1.0)));
    assert!(near(px[(m + 318) * w as usize + bx], density_colour(0.0)));
    // With the level-0 face's own map, the blocks outside the hexagon are pale grey, off the
    // colour map, and an empty block inside (a hole) keeps the map's dark violet: the two are
    // told apart (issue #32: one blue for both).
    let face = lacuna::measure::density_map(&i, 0, 16, 4);
    let pic = DensityPicture {
        outside: face.values.iter().map(|&v| v == 0.0).collect(),
        ..pic
    };
    let mut bytes = Vec::new();
    write_density_picture(&map, &pic, &mut bytes).unwrap();
    let (w, _, px) = decode(&bytes);
    let at = |row: usize, col: usize| px[(m + row * 20 + 10) * w as usize + m + col * 20 + 10];
    // F0's hexagon has corners (±1, 0) in a square window: the top left block is outside it.
    assert_eq!(face.values[0], 0.0);
    let o = lacuna::export::OUTSIDE;
    assert_eq!(at(0, 0), [o[0], o[1], o[2], 255]);
    let mut holes = 0;
    for row in 0..16 {
        for col in 0..16 {
            let k = row * 16 + col;
            if face.values[k] == 1.0 && map.values[k] < 0.1 {
                holes += 1;
                let c = at(row, col);
                assert!(
                    lacuna::export::lightness([c[0], c[1], c[2]]) < 35.0,
                    "{c:?}"
                );
            }
        }
    }
    assert!(
        holes > 0,
        "F0 level 2 has blocks inside the face that are nearly empty"
    );
}

#[test]
fn svg_has_curves_a_legend_per_type_and_outlines_relative_to_the_cells() {
    let i = inst("triangle-C2");
    let mut svg = Vec::new();
    write_svg_picture(&i, 2, &PictureOptions::default(), &mut svg).unwrap();
    let svg = String::from_utf8(svg).unwrap();
    assert_eq!(
        svg.matches("class=\"legend-entry\"").count(),
        i.types.types.len()
    );
    for (t, ty) in i.types.types.iter().enumerate() {
        assert!(svg.contains(&format!(
            "<tspan font-weight=\"bold\">T{t}</tspan> {}",
            ty.face
        )));
    }
    // B2 edges are quadratic Bézier curves, drawn as such.
    assert!(svg.contains(" Q"), "no quadratic curve");
    // Outlines: thinner at deeper levels, none when the cells are a few pixels wide.
    let f = Frame::of(&i, 512);
    let (w1, w3) = (stroke_width(&i, 1, f.scale), stroke_width(&i, 3, f.scale));
    assert!(w1 > 2.0 * w3 && w3 > 0.0, "{w1} {w3}");
    assert_eq!(stroke_width(&i, 7, f.scale), 0.0);
}

/// The box of the pixels of a picture that are not white, over its first `rows` rows (the
/// picture above the legend): (x0, y0, x1, y1), and how many there are.
fn ink(w: u32, px: &[[u8; 4]], rows: u32) -> ([u32; 4], usize) {
    let mut b = [u32::MAX, u32::MAX, 0, 0];
    let mut n = 0;
    for y in 0..rows {
        for x in 0..w {
            let p = px[(y * w + x) as usize];
            if p[..3] != [255, 255, 255] {
                n += 1;
                b = [b[0].min(x), b[1].min(y), b[2].max(x), b[3].max(y)];
            }
        }
    }
    (b, n)
}

/// An automaton's PNG (issue #32): colour, anti-aliased, the shapes centred with a margin, every
/// state in its colour, the pieces visible at every level. The Heighway dragon is a polyline
/// drawn in its states' colours; the Cantor set at level 5 is 32 segments of 1/243 on one line,
/// centred in a picture a quarter as tall as wide; the fractal kite fills the middle of its
/// picture (the frame triangle of every leaf contains its piece).
#[test]
fn automaton_pictures_are_coloured_centred_and_visible() {
    let dir = common::scratch("apng");
    let render = |name: &str, level: &str| {
        let path = dir.join(format!("{name}.png"));
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_lacuna"))
            .args(["render", name, "--level", level, "--png"])
            .arg(&path)
            .args(["--size", "400", "--no-legend"])
            .output()
            .unwrap();
        assert!(out.status.success(), "{name}");
        decode(&std::fs::read(&path).unwrap())
    };
    // The dragon: many colours (anti-aliasing and two states), ink centred within 2 % both ways
    // and a margin on every side.
    let (w, h, px) = render("heighway-dragon", "10");
    let colours: std::collections::HashSet<[u8; 4]> = px.iter().copied().collect();
    assert!(colours.len() > 16, "{} colours", colours.len());
    let (b, _) = ink(w, &px, h);
    let (mx, my) = (f64::from(b[0] + b[2]) / 2.0, f64::from(b[1] + b[3]) / 2.0);
    assert!(
        (mx - f64::from(w) / 2.0).abs() < 0.02 * f64::from(w),
        "{b:?} in {w}×{h}"
    );
    assert!(
        (my - f64::from(h) / 2.0).abs() < 0.02 * f64::from(h),
        "{b:?} in {w}×{h}"
    );
    assert!(
        b[0] > 4 && b[1] > 4 && b[2] < w - 5 && b[3] < h - 5,
        "{b:?}"
    );
    // The Cantor set: a picture 100 pixels tall, its 32 pieces drawn as bars a fortieth of the
    // width (10 px) tall across the middle row, spread over the width less the margins (16 px
    // each side), with a gap in the middle third.
    let (w, h, px) = render("cantor-set", "5");
    assert_eq!((w, h), (400, 100));
    let (b, n) = ink(w, &px, h);
    assert!(n >= 32 * 10, "{n} pixels");
    assert!(b[1] >= 44 && b[3] <= 55 && b[3] - b[1] >= 8, "{b:?}");
    assert!(b[0] <= 17 && b[2] >= 382, "{b:?}");
    let row = (b[1] + b[3]) / 2;
    let middle = (180..220).all(|x| px[(row * w + x) as usize][..3] == [255, 255, 255]);
    assert!(middle, "the middle third is empty");
    // A surface in space 3 is shaded: the quad patch's pieces face the light at many angles, so
    // its ink has many colours (a flat fill would have its state's colour and anti-aliased
    // edges only).
    let (w, h, px) = render("quad-patch-3d", "4");
    let shades: std::collections::HashSet<[u8; 4]> = px[..(w * h) as usize]
        .iter()
        .filter(|p| p[3] == 255 && p[..3] != [255, 255, 255])
        .copied()
        .collect();
    assert!(shades.len() > 40, "{} colours", shades.len());
    // The kite: its middle is filled.
    let (w, h, px) = render("kite-dart", "12");
    let (b, n) = ink(w, &px, h);
    let c = px[(((b[1] + b[3]) / 2) * w + (b[0] + b[2]) / 2) as usize];
    assert_ne!(c[..3], [255, 255, 255], "the kite's middle");
    assert!(n as f64 > 0.3 * f64::from(w * h), "{n} of {} pixels", w * h);
    std::fs::remove_dir_all(&dir).ok();
}

/// A volume's PNG (issue #32): the solid centred in the picture and filling it, and the three
/// sides of a cube in view in three shades, none of them dark (the darkest at least half as
/// bright as the brightest).
#[test]
fn volume_pictures_are_centred_and_every_side_in_view_is_lit() {
    let dir = common::scratch("vpng");
    let render = |name: &str, level: &str| {
        let path = dir.join("v.png");
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_lacuna"))
            .args(["render", name, "--level", level, "--png"])
            .arg(&path)
            .args(["--size", "300"])
            .output()
            .unwrap();
        assert!(out.status.success(), "{name}");
        decode(&std::fs::read(&path).unwrap())
    };
    for name in ["tetrahedron-B2", "two-cubes", "cube-B2"] {
        let (w, h, px) = render(name, "1");
        let (b, _) = ink(w, &px, h);
        let (mx, my) = (f64::from(b[0] + b[2]) / 2.0, f64::from(b[1] + b[3]) / 2.0);
        assert!(
            (mx - 150.0).abs() < 6.0 && (my - 150.0).abs() < 6.0,
            "{name}: {b:?}"
        );
        let side = (b[2] - b[0]).max(b[3] - b[1]);
        assert!(side > 250, "{name}: the solid spans {side} of 300 pixels");
    }
    // The plain cube (level 0): the three most common colours of the solid are its three sides.
    let (_, _, px) = render("cube-B2", "0");
    let mut count: std::collections::HashMap<[u8; 3], usize> = Default::default();
    for p in px
        .iter()
        .filter(|p| p[3] == 255 && p[..3] != [255, 255, 255])
    {
        *count.entry([p[0], p[1], p[2]]).or_default() += 1;
    }
    let mut by: Vec<([u8; 3], usize)> = count.into_iter().collect();
    by.sort_by_key(|c| std::cmp::Reverse(c.1));
    let ink: usize = by.iter().map(|c| c.1).sum();
    let sides = &by[..3];
    assert!(sides.iter().all(|c| c.1 * 10 > ink), "{sides:?} of {ink}");
    let lum =
        |c: [u8; 3]| 0.2126 * f64::from(c[0]) + 0.7152 * f64::from(c[1]) + 0.0722 * f64::from(c[2]);
    let (lo, hi) = sides.iter().fold((f64::MAX, 0.0f64), |(lo, hi), c| {
        (lo.min(lum(c.0)), hi.max(lum(c.0)))
    });
    assert!(lo >= 0.5 * hi, "a dark side: {sides:?}");
    std::fs::remove_dir_all(&dir).ok();
}

/// Issue #32: the three reports — a face, a volume, an automaton — share one layout: the title
/// `lacuna report: NAME`, the verdict line before any section, the pictures first, and text
/// blocks that wrap instead of scrolling (a long mesh line is never cut).
#[test]
fn every_kind_of_report_has_one_layout() {
    let dir = common::scratch("report-layout");
    for (name, level) in [("F0", "1"), ("cube-C2", "1"), ("sierpinski-triangle", "2")] {
        let out = dir.join(format!("{name}.html"));
        let (code, _, err) = common::lacuna(&[
            "report",
            name,
            "--level",
            level,
            "--out",
            out.to_str().unwrap(),
        ]);
        assert_eq!(code, 0, "{name}: {err}");
        let html = std::fs::read_to_string(&out).unwrap();
        assert!(
            html.contains(&format!("<title>lacuna report: {name}</title>"))
                && html.contains(&format!("<h1>lacuna report: {name}</h1>")),
            "{name}: the title"
        );
        let verdict = html
            .find("<b>Verdict: VERIFIED</b>")
            .expect("a verdict line");
        let first = html.find("<h2>").expect("sections");
        assert!(
            verdict < first,
            "{name}: the verdict comes before the sections"
        );
        assert!(
            html[first..].starts_with("<h2>Pictures</h2>"),
            "{name}: the pictures come first"
        );
        assert!(html.contains("white-space:pre-wrap") && !html.contains("overflow-x:auto"));
    }
    std::fs::remove_dir_all(&dir).ok();
}
