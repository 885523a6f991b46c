//! Seed 002's gasket family and the Sierpinski carpet (issue #37), and `docs/GALLERY.md` kept
//! true: every entry's ratio derived by hand and checked against the drawn pieces, its certified
//! dimension against `ln n / ln(1/r)` computed here in f64, the open-set verdict, the count of
//! pieces per level, the certificate checked by `lacuna check`; then every command of the gallery
//! run again and compared with the numbers and pictures the page shows.

mod common;
use common::lacuna;
use std::f64::consts::PI;

/// A library entry of the family: name, number of maps, and its ratio written by hand.
struct Entry {
    name: &'static str,
    maps: usize,
    /// The ratio's closed form, evaluated in f64.
    ratio: f64,
}

/// The hand values (fixtures/gasket-N.aut derive them): the copies at neighbouring corners touch
/// when r = L/(L + W), W the polygon's width along a side; n = 3, 4: W = L; n = 5: W = φ·L (a
/// diagonal); n = 6: W = 2L; n = 7: W = (1 + 2cos 2π/7)·L; n = 8: W = (1 + √2)·L (across flats).
/// The carpet keeps eight ninths of the square.
fn entries() -> Vec<Entry> {
    let sqrt5 = 5f64.sqrt();
    let e = |name, maps, ratio| Entry { name, maps, ratio };
    vec![
        e("gasket-3", 3, 0.5),
        e("gasket-4", 4, 0.5),
        e("gasket-5", 5, (3.0 - sqrt5) / 2.0),
        e("gasket-6", 6, 1.0 / 3.0),
        e("gasket-7", 7, 1.0 / (2.0 + 2.0 * (2.0 * PI / 7.0).cos())),
        e("gasket-8", 8, 1.0 - 2f64.sqrt() / 2.0),
        e("sierpinski-carpet", 8, 1.0 / 3.0),
    ]
}

/// The family's formula, `1 / (2 + 2 Σ_(k=1..⌊n/4⌋) cos(2πk/n))`.
fn formula(n: usize) -> f64 {
    let sum: f64 = (1..=n / 4)
        .map(|k| (2.0 * PI * k as f64 / n as f64).cos())
        .sum();
    1.0 / (2.0 + 2.0 * sum)
}

/// The corners of the regular n-gon of circumradius 1 with `v_0 = (1, 0)`.
fn corners(n: usize) -> Vec<[f64; 2]> {
    (0..n)
        .map(|k| {
            let t = 2.0 * PI * k as f64 / n as f64;
            [t.cos(), t.sin()]
        })
        .collect()
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

#[test]
fn the_hand_ratios_are_the_formula_and_neighbouring_copies_touch() {
    for e in entries().iter().filter(|e| e.name.starts_with("gasket-")) {
        let n = e.maps;
        assert!(
            close(formula(n), e.ratio, 1e-15),
            "{}: the formula gives {}, the hand value {}",
            e.name,
            formula(n),
            e.ratio
        );
        // The shadows on the side v_k v_(k+1), computed from the corners: the copy about v_k
        // reaches r·(max − p) past p = v_k·u, the copy about v_(k+1) starts r·(q − min) before
        // q = v_(k+1)·u. They meet: the gap is zero; with a ratio 1% smaller it is positive.
        let v = corners(n);
        for k in 0..n {
            let (a, b) = (v[k], v[(k + 1) % n]);
            let l = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
            let u = [(b[0] - a[0]) / l, (b[1] - a[1]) / l];
            let proj: Vec<f64> = v.iter().map(|c| c[0] * u[0] + c[1] * u[1]).collect();
            let (lo, hi) = proj
                .iter()
                .fold((f64::MAX, f64::MIN), |(lo, hi), &x| (lo.min(x), hi.max(x)));
            let (p, q) = (proj[k], proj[(k + 1) % n]);
            let gap = |r: f64| (q - r * (q - lo)) - (p + r * (hi - p));
            assert!(close(gap(e.ratio), 0.0, 1e-12), "{}: side {k}", e.name);
            assert!(gap(0.99 * e.ratio) > 1e-3, "{}: side {k}", e.name);
            // The width along a side is the formula's W = L·(1 + 2 Σ cos 2πk/n).
            let w = l * (1.0 / formula(n) - 1.0);
            assert!(close(hi - lo, w, 1e-12), "{}: width", e.name);
        }
    }
}

/// The level-1 pieces as `render --json-out` writes them: each piece's three points.
fn level_one(name: &str) -> Vec<Vec<[f64; 2]>> {
    pieces(name, "1")
}

/// The pieces of a level as `render --json-out` writes them, in the walk's order.
fn pieces(name: &str, level: &str) -> Vec<Vec<[f64; 2]>> {
    let (code, out, err) = lacuna(&["render", name, "--level", level, "--json-out", "-"]);
    assert_eq!(code, 0, "{name}: {err}");
    let v: serde_json::Value = serde_json::from_str(&out).expect("JSON");
    v["shapes"]
        .as_array()
        .expect("shapes")
        .iter()
        .map(|s| {
            s["points"]
                .as_array()
                .expect("points")
                .iter()
                .map(|p| [p[0].as_f64().unwrap(), p[1].as_f64().unwrap()])
                .collect()
        })
        .collect()
}

#[test]
fn the_drawn_pieces_are_homotheties_towards_the_corners() {
    // A gasket's frame is (O, v_0, v_1); piece k is f_k of it, f_k(x) = r·x + (1 − r)·v_k: its
    // first point is (1 − r)·v_k and its sides are r times the frame's (no rotation).
    for e in entries().iter().filter(|e| e.name.starts_with("gasket-")) {
        let (n, r) = (e.maps, e.ratio);
        let v = corners(n);
        let pieces = level_one(e.name);
        assert_eq!(pieces.len(), n, "{}", e.name);
        let near = |a: [f64; 2], b: [f64; 2]| close(a[0], b[0], 1e-12) && close(a[1], b[1], 1e-12);
        let scaled = |s: f64, a: [f64; 2]| [s * a[0], s * a[1]];
        let minus = |a: [f64; 2], b: [f64; 2]| [a[0] - b[0], a[1] - b[1]];
        for (k, p) in pieces.iter().enumerate() {
            assert!(near(p[0], scaled(1.0 - r, v[k])), "{}: T{k}", e.name);
            assert!(near(minus(p[1], p[0]), scaled(r, v[0])), "{}: T{k}", e.name);
            assert!(near(minus(p[2], p[0]), scaled(r, v[1])), "{}: T{k}", e.name);
        }
    }
    // The carpet's frame is (0, 0), (1, 0), (0, 1); piece k is x/3 + t_k, the t_k counter-clockwise
    // from the lower left corner, the middle ninth left out.
    let pieces = level_one("sierpinski-carpet");
    let t = [
        (0, 0),
        (1, 0),
        (2, 0),
        (2, 1),
        (2, 2),
        (1, 2),
        (0, 2),
        (0, 1),
    ];
    assert_eq!(pieces.len(), t.len());
    for (p, (a, b)) in pieces.iter().zip(t) {
        let o = [a as f64 / 3.0, b as f64 / 3.0];
        let want = [o, [o[0] + 1.0 / 3.0, o[1]], [o[0], o[1] + 1.0 / 3.0]];
        for (got, want) in p.iter().zip(want) {
            assert!(close(got[0], want[0], 1e-15) && close(got[1], want[1], 1e-15));
        }
    }
}

/// The similarity line of `lacuna verify NAME`.
fn similarity_line(name: &str) -> String {
    let (code, out, err) = lacuna(&["verify", name]);
    assert_eq!(code, 0, "{name}: {err}");
    assert!(out.contains("verdict: VERIFIED"), "{name}: {out}");
    out.lines()
        .find(|l| l.starts_with("similarity dimension = "))
        .unwrap_or_else(|| panic!("{name}: no similarity dimension in\n{out}"))
        .to_string()
}

/// The certified decimal of a similarity line: the digits before `…`.
fn certified_decimal(line: &str) -> &str {
    let end = line.find('…').expect("certified digits end with …");
    let start = line[..end].rfind("= ").expect("`= ` before the digits") + 2;
    &line[start..end]
}

#[test]
fn the_certified_dimension_is_log_n_over_log_one_over_r_and_the_open_set_condition_holds() {
    for e in entries() {
        let line = similarity_line(e.name);
        let decimal = certified_decimal(&line);
        assert!(decimal.len() >= 30, "{}: {decimal}", e.name);
        let got: f64 = decimal.parse().expect("a decimal");
        let want = (e.maps as f64).ln() / (1.0 / e.ratio).ln();
        assert!(
            close(got, want, 1e-12),
            "{}: verify says {decimal}, ln {} / ln(1/r) = {want}",
            e.name,
            e.maps
        );
        assert!(
            line.contains("(the Hausdorff dimension: holds: the interiors of the convex hulls"),
            "{}: {line}",
            e.name
        );
    }
    // The exact forms lacuna prints where the ratio is rational.
    for (name, exact) in [
        ("gasket-3", "log 3 / log 2"),
        ("gasket-4", "2"),
        ("gasket-6", "log 6 / log 3"),
        ("sierpinski-carpet", "log 8 / log 3"),
    ] {
        let line = similarity_line(name);
        assert!(
            line.starts_with(&format!("similarity dimension = {exact} = ")),
            "{name}: {line}"
        );
    }
}

#[test]
fn level_k_has_n_to_the_k_pieces() {
    for e in entries() {
        let (code, out, err) = lacuna(&["measure", e.name, "--level", "3", "--json"]);
        assert_eq!(code, 0, "{}: {err}", e.name);
        let v: serde_json::Value = serde_json::from_str(&out).expect("JSON");
        let levels = v["levels"].as_array().expect("levels");
        assert_eq!(levels.len(), 4, "{}", e.name);
        for (k, l) in levels.iter().enumerate() {
            assert_eq!(l["level"].as_u64(), Some(k as u64), "{}", e.name);
            assert_eq!(
                l["pieces"].as_u64(),
                Some(e.maps.pow(k as u32) as u64),
                "{}: level {k}",
                e.name
            );
        }
        let sd = &v["similarity_dimension"];
        assert_eq!(sd["upper_bound"].as_bool(), Some(false), "{}", e.name);
        assert!(
            sd["open_set"].as_str().unwrap_or("").starts_with("holds"),
            "{}",
            e.name
        );
    }
}

#[test]
fn every_certificate_is_checked_by_lacuna_check() {
    let dir = std::env::temp_dir().join(format!("lacuna-gallery-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for e in entries() {
        let c = dir.join(format!("{}.json", e.name));
        let c = c.to_str().unwrap();
        let (code, _, err) = lacuna(&["verify", e.name, "--certificate", c]);
        assert_eq!(code, 0, "{}: {err}", e.name);
        let (code, out, err) = lacuna(&["check", c]);
        assert_eq!(code, 0, "{}: {out}{err}", e.name);
        assert!(
            out.contains("the open-set condition holds"),
            "{}: {out}",
            e.name
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

// ---- Seed 002, Fig. 7: multiplicities ----

/// The level-1 points of Fig. 7's sets from the paper's curves, computed here: the lemniscate
/// `(sin θ, sin 2θ)` (eq. (24) at t = 1) and the rose `cos(3θ/2)·e^(jθ/2)`, both at θ = uπ/3,
/// u = 1…6; with the multiplicity of each distinct point (eq. (18)).
fn figure_7(rose: bool) -> (Vec<[f64; 2]>, Vec<usize>) {
    let points: Vec<[f64; 2]> = (1..=6)
        .map(|u| {
            let t = u as f64 * PI / 3.0;
            match rose {
                false => [t.sin(), (2.0 * t).sin()],
                true => {
                    let r = (1.5 * t).cos();
                    [r * (t / 2.0).cos(), r * (t / 2.0).sin()]
                }
            }
        })
        .collect();
    let mut distinct: Vec<([f64; 2], usize)> = Vec::new();
    for p in &points {
        match distinct
            .iter_mut()
            .find(|(q, _)| close(q[0], p[0], 1e-12) && close(q[1], p[1], 1e-12))
        {
            Some((_, n)) => *n += 1,
            None => distinct.push((*p, 1)),
        }
    }
    let mut mult: Vec<usize> = distinct.iter().map(|d| d.1).collect();
    mult.sort_unstable();
    (points, mult)
}

#[test]
fn figure_7_sets_sample_their_curves_and_classify_tells_them_apart() {
    for (name, rose, want) in [
        ("lemniscate-fractal", false, vec![1, 1, 1, 1, 2]),
        ("rose-fractal", true, vec![1, 1, 1, 3]),
    ] {
        let (points, mult) = figure_7(rose);
        assert_eq!(mult, want, "{name}: the curve's multiplicities");
        // Each level-1 piece draws its image of the origin: the sample of its map.
        let drawn = pieces(name, "1");
        assert_eq!(drawn.len(), 6, "{name}");
        for (k, (d, p)) in drawn.iter().zip(&points).enumerate() {
            assert!(
                close(d[0][0], p[0], 1e-12) && close(d[0][1], p[1], 1e-12),
                "{name}: T{k} draws {:?}, the curve's sample is {p:?}",
                d[0]
            );
        }
        // The coinciding maps make the open-set condition fail, and verify names two of them.
        let line = similarity_line(name);
        assert!(
            line.contains("an upper bound") && line.contains("are the same map"),
            "{line}"
        );
    }
    // classify compares seed 002's multiplicity (the default): the distinct maps of level 1
    // are the distinct points counted above (5 and 4); equal cardinality (6 pieces each) is not
    // enough. Each set's distinct maps satisfy the open-set condition, so no deeper level adds
    // a coincidence and two levels (one state each: 1 + 1) decide every level.
    let classify = |a: &str, b: &str| -> serde_json::Value {
        let (code, out, err) = lacuna(&["classify", a, b, "--levels", "2", "--json"]);
        assert!(code == 0 || code == 1, "{a} {b}: {err}");
        let v: serde_json::Value = serde_json::from_str(&out).expect("JSON");
        assert_eq!(v["every_level"], true, "{a} {b}: {v}");
        v
    };
    let v = classify("lemniscate-fractal", "rose-fractal");
    let (l, r) = (figure_7(false).1.len(), figure_7(true).1.len());
    assert_eq!(v["same_class"], false);
    assert_eq!(v["differs"]["group"], "multiplicity");
    assert_eq!(v["differs"]["invariant"], "distinct maps");
    assert_eq!(
        (v["differs"]["a"].clone(), v["differs"]["b"].clone()),
        (l.to_string().into(), r.to_string().into())
    );
    // The paper's classes: the octagonal gasket and the carpet share cardinality 8 and have no
    // multiplicity; the Sierpinski gasket has 3 points.
    assert_eq!(
        classify("gasket-8", "sierpinski-carpet")["same_class"],
        true
    );
    let v = classify("gasket-3", "sierpinski-carpet");
    assert_eq!(v["differs"]["group"], "cardinality");
    assert_eq!(
        (v["differs"]["a"].clone(), v["differs"]["b"].clone()),
        ("3".into(), "8".into())
    );
    // One set written two ways (on the triangle's corners; on its centre and two corners) is
    // one class, whatever corners the maps happen to fix.
    assert_eq!(
        classify("sierpinski-triangle", "gasket-3")["same_class"],
        true
    );
}

/// Fig. 8's samples by hand: the gasket's on the unit circle, `(sin uπ/4, cos uπ/4)`, and the
/// carpet's around the square in the same directions, for u = 1…8.
fn figure_8_samples() -> (Vec<[f64; 2]>, Vec<[f64; 2]>) {
    let gasket = (1..=8)
        .map(|u| {
            let t = u as f64 * PI / 4.0;
            [t.sin(), t.cos()]
        })
        .collect();
    let square = [
        [1.0, 1.0],
        [1.0, 0.0],
        [1.0, -1.0],
        [0.0, -1.0],
        [-1.0, -1.0],
        [-1.0, 0.0],
        [-1.0, 1.0],
        [0.0, 1.0],
    ];
    (gasket, square.to_vec())
}

/// Fig. 8: one product system drawn with two projections is the octagonal gasket (ratio
/// 1/(2 + √2)) and the carpet (ratio 1/3); `morph` between them moves the control points, so the
/// frame at t = 1/2 has the midpoints of the two ends' samples (eq. (21)).
#[test]
fn figure_8_is_a_morph_of_one_product_system_between_two_projections() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/fixtures/");
    let (gasket, carpet) = (
        format!("{dir}octagonal-gasket-product.aut"),
        format!("{dir}carpet-product.aut"),
    );
    let (f, g) = figure_8_samples();
    assert_samples(&gasket, &f, 1.0 / (2.0 + 2f64.sqrt()));
    assert_samples(&carpet, &g, 1.0 / 3.0);
    let svg = std::env::temp_dir().join(format!("lacuna-fig8-{}.svg", std::process::id()));
    let (code, out, err) = lacuna(&[
        "morph",
        &gasket,
        &carpet,
        "--frames",
        "3",
        "--level",
        "1",
        "--svg",
        svg.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("0 of 8 operators change, 4 of 5 control points move"),
        "{out}"
    );
    assert!(out.contains("VERIFIED: every frame"), "{out}");
    // The middle frame's dots against the midpoints (f_u + g_u)/2, up to the picture's
    // similarity (scale, translation, y downwards): every distance in the same ratio.
    let text = std::fs::read_to_string(&svg).unwrap();
    std::fs::remove_file(&svg).ok();
    let group = text
        .split("<g class=\"frame\" id=\"frame-1\"")
        .nth(1)
        .and_then(|g| g.split("</g>").next())
        .expect("frame 1");
    let attr = |c: &str, k: &str| -> f64 {
        let v = c.split(&format!("{k}=\"")).nth(1).unwrap();
        v[..v.find('"').unwrap()].parse().unwrap()
    };
    let dots: Vec<[f64; 2]> = group
        .split("<circle ")
        .skip(1)
        .map(|c| [attr(c, "cx"), -attr(c, "cy")])
        .collect();
    assert_eq!(dots.len(), 8);
    let mid: Vec<[f64; 2]> = f
        .iter()
        .zip(&g)
        .map(|(a, b)| [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0])
        .collect();
    let dist = |a: &[f64; 2], b: &[f64; 2]| ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt();
    let scale = dist(&dots[0], &dots[4]) / dist(&mid[0], &mid[4]);
    for i in 0..8 {
        for j in 0..8 {
            let (d, e) = (dist(&dots[i], &dots[j]), scale * dist(&mid[i], &mid[j]));
            assert!((d - e).abs() < 0.05, "dots {i}, {j}: {d} px, expected {e}");
        }
    }
}

/// The level-1 points of `file` (a leaf draws F_u(O) = f_u) are `samples`, in order, and level 2
/// begins with F_1(F_1(O)) = (1 + r)·f_1.
fn assert_samples(file: &str, samples: &[[f64; 2]], r: f64) {
    let one = pieces(file, "1");
    assert_eq!(one.len(), samples.len(), "{file}");
    for (d, p) in one.iter().zip(samples) {
        assert!(
            close(d[0][0], p[0], 1e-12) && close(d[0][1], p[1], 1e-12),
            "{file}: {d:?} {p:?}"
        );
    }
    let two = pieces(file, "2");
    assert_eq!(two.len(), samples.len().pow(2), "{file}");
    let want = [samples[0][0] * (1.0 + r), samples[0][1] * (1.0 + r)];
    assert!(
        close(two[0][0][0], want[0], 1e-12) && close(two[0][0][1], want[1], 1e-12),
        "{file}"
    );
}

/// How many times each distinct point occurs, largest first.
fn multiplicities(points: &[[f64; 2]]) -> Vec<usize> {
    let mut seen: Vec<([f64; 2], usize)> = Vec::new();
    for p in points {
        match seen
            .iter_mut()
            .find(|(q, _)| close(q[0], p[0], 1e-12) && close(q[1], p[1], 1e-12))
        {
            Some((_, n)) => *n += 1,
            None => seen.push((*p, 1)),
        }
    }
    let mut m: Vec<usize> = seen.into_iter().map(|(_, n)| n).collect();
    m.sort_unstable_by(|a, b| b.cmp(a));
    m
}

/// Fig. 11 and 12: the Sierpinski gasket written with six (eight) samples, each of its three
/// taken several times, and the hexagonal gasket (the carpet); the linear metamorphosis between
/// the two projections of one product system verifies every frame.
#[test]
fn figures_11_and_12_unfold_the_gasket_s_multiplicities() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/fixtures/");
    let at = |k: f64| [(k * PI / 3.0).cos(), (k * PI / 3.0).sin()];
    // Fig. 11: e^(j·u·2π/3) and e^(j·u·π/3), u = 1…6 (eq. (26) at T = 2π/3 and π/3).
    let gasket6: Vec<[f64; 2]> = (1..=6).map(|u| at(2.0 * u as f64)).collect();
    let hexagon: Vec<[f64; 2]> = (1..=6).map(|u| at(u as f64)).collect();
    assert_eq!(multiplicities(&gasket6), vec![2, 2, 2]);
    assert_eq!(multiplicities(&hexagon), vec![1; 6]);
    // Fig. 12: (sin θ, cos θ) at θ = −2uπ/3, u = 1…8 (eq. (28) at t = 0), and the square.
    let gasket8: Vec<[f64; 2]> = (1..=8)
        .map(|u| {
            let t = -2.0 * u as f64 * PI / 3.0;
            [t.sin(), t.cos()]
        })
        .collect();
    assert_eq!(multiplicities(&gasket8), vec![3, 3, 2]);
    let (_, square) = figure_8_samples();
    for (name, start, end) in [
        ("gasket-to-hexagonal", &gasket6, &hexagon),
        ("gasket-to-carpet", &gasket8, &square),
    ] {
        let (a, b) = (
            format!("{dir}{name}-start.aut"),
            format!("{dir}{name}-end.aut"),
        );
        assert_samples(&a, start, 0.5);
        assert_samples(&b, end, 1.0 / 3.0);
        let (code, out, err) = lacuna(&["morph", &a, &b, "--frames", "3", "--level", "2"]);
        assert_eq!(code, 0, "{name}: {err}");
        assert!(out.contains("4 of 5 control points move"), "{name}: {out}");
        assert!(out.contains("VERIFIED: every frame"), "{name}: {out}");
    }
}

/// Fig. 10: the hexagonal gasket's samples are the circle's, in the lemniscate's order, so that
/// `morph` between the two automata is eq. (24); every frame is verified.
#[test]
fn figure_10_is_a_morph_from_the_circle_samples_to_the_lemniscate() {
    let hex = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/fixtures/hexagonal-gasket-samples.aut"
    );
    let drawn = pieces(hex, "1");
    assert_eq!(drawn.len(), 6);
    for (k, d) in drawn.iter().enumerate() {
        let t = (k + 1) as f64 * PI / 3.0;
        assert!(
            close(d[0][0], t.cos(), 1e-12) && close(d[0][1], t.sin(), 1e-12),
            "T{k}: {:?}",
            d[0]
        );
    }
    let line = similarity_line(hex);
    assert!(line.contains("(the Hausdorff dimension: holds"), "{line}");
    let (code, out, err) = lacuna(&[
        "morph",
        hex,
        "lemniscate-fractal",
        "--frames",
        "3",
        "--level",
        "2",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("VERIFIED: every frame"), "{out}");
}

// ---- docs/GALLERY.md stays true ----

/// One figure of the gallery: the commands of its console block and the first row of the table
/// after them.
struct Figure {
    verify: Option<String>,
    /// The `lacuna render` commands of its pictures (the kite and dart have two).
    render: Vec<Vec<String>>,
    row: Vec<String>,
}

fn gallery_figures() -> Vec<Figure> {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/GALLERY.md"))
        .expect("docs/GALLERY.md");
    let mut figures = Vec::new();
    let mut current: Option<Figure> = None;
    let mut lines = text.lines().peekable();
    while let Some(line) = lines.next() {
        if let Some(rest) = line.strip_prefix("lacuna verify ") {
            figures.extend(current.take());
            current = Some(Figure {
                verify: Some(rest.trim().to_string()),
                render: Vec::new(),
                row: Vec::new(),
            });
        } else if line.starts_with("lacuna solve ") {
            // A figure of constraints (seed 004, §3), checked by its own test below.
            figures.extend(current.take());
        } else if let Some(rest) = line.strip_prefix("lacuna render ") {
            if let Some(f) = current.as_mut() {
                f.render
                    .push(rest.split_whitespace().map(String::from).collect());
            }
        } else if line.starts_with("|---") {
            // The figure's numbers: the first table whose row is not pictures side by side.
            let pictures = lines.peek().is_some_and(|r| r.starts_with("| !["));
            if let Some(f) = current.as_mut().filter(|f| f.row.is_empty() && !pictures) {
                let row = lines.next().expect("a row under the table's header");
                f.row = row
                    .trim_matches('|')
                    .split('|')
                    .map(|c| c.trim().to_string())
                    .collect();
            }
        }
    }
    figures.extend(current);
    figures
}

#[test]
fn the_gallery_lists_every_new_entry() {
    let names: Vec<String> = gallery_figures()
        .into_iter()
        .filter_map(|f| f.verify)
        .collect();
    for e in entries() {
        assert!(
            names.iter().any(|n| n == e.name),
            "{} is not in docs/GALLERY.md",
            e.name
        );
    }
}

#[test]
fn the_gallery_numbers_are_what_verify_prints_now() {
    for f in gallery_figures() {
        let name = f.verify.expect("a verify command");
        assert_eq!(
            f.row.len(),
            4,
            "{name}: maps | ratio | dimension | open set"
        );
        let line = similarity_line(&name);
        // The dimension cell ends with the certified digits, cut short: verify prints them.
        let cell = &f.row[2];
        let shown = certified_decimal(cell);
        assert!(shown.len() >= 12, "{name}: {cell}");
        assert!(
            certified_decimal(&line).starts_with(shown),
            "docs/GALLERY.md says {shown}… for {name}; verify prints: {line}"
        );
        // The open-set cell: holds exactly when verify says so.
        assert_eq!(
            f.row[3].starts_with("holds"),
            line.contains("(the Hausdorff dimension: holds"),
            "{name}: {} against {line}",
            f.row[3]
        );
        // The number of maps: the pieces of level 1.
        let (code, out, _) = lacuna(&["measure", &name, "--level", "1", "--json"]);
        assert_eq!(code, 0);
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        assert_eq!(
            v["levels"][1]["pieces"].as_u64().map(|p| p.to_string()),
            Some(f.row[0].clone()),
            "{name}: maps"
        );
    }
}

#[test]
fn the_gallery_pictures_are_what_render_draws_now() {
    let dir = std::env::temp_dir().join(format!("lacuna-gallery-png-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let figures = gallery_figures();
    assert!(
        figures.iter().any(|f| f.render.len() == 2),
        "the kite and dart"
    );
    for args in figures.iter().flat_map(|f| {
        assert!(!f.render.is_empty(), "{:?}: a render command", f.verify);
        &f.render
    }) {
        let png = args.iter().position(|a| a == "--png").expect("--png") + 1;
        let committed = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(&args[png]);
        let fresh = dir.join("fresh.png");
        let mut run: Vec<&str> = vec!["render"];
        run.extend(args.iter().map(String::as_str));
        run[png + 1] = fresh.to_str().unwrap();
        let (code, _, err) = lacuna(&run);
        assert_eq!(code, 0, "{run:?}: {err}");
        let want = std::fs::read(&committed)
            .unwrap_or_else(|_| panic!("{} is missing", committed.display()));
        assert!(
            std::fs::read(&fresh).unwrap() == want,
            "{} differs from `lacuna render {}`: run docs/make-automaton-images.sh",
            committed.display(),
            args.join(" ")
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

// ---- Seed 004: the kite and dart of Example 1 ----

/// A similitude of the plane `z ↦ w·z + t` (complex numbers as pairs).
#[derive(Clone, Copy)]
struct Sim {
    w: (f64, f64),
    t: (f64, f64),
}

impl Sim {
    fn apply(&self, z: (f64, f64)) -> (f64, f64) {
        (
            self.w.0 * z.0 - self.w.1 * z.1 + self.t.0,
            self.w.0 * z.1 + self.w.1 * z.0 + self.t.1,
        )
    }
}

/// The paper's four maps (seed 004, Example 1) with T0b's y-translation `1 + sign·φ cos(4π/5)`:
/// sign +1 as printed, −1 corrected. Returns (T0a, T1a, T0b, T1b).
fn paper_maps(sign: f64) -> [Sim; 4] {
    let phi = (1.0 + 5f64.sqrt()) / 2.0;
    let r = 1.0 / phi;
    let rot = |k: f64| (r * (k * PI / 5.0).cos(), r * (k * PI / 5.0).sin());
    [
        Sim {
            w: (1.0, 0.0),
            t: (0.0, 0.0),
        },
        Sim {
            w: rot(3.0),
            t: (0.0, 1.0),
        },
        Sim {
            w: rot(4.0),
            t: (
                phi * (4.0 * PI / 5.0).sin(),
                1.0 + sign * phi * (4.0 * PI / 5.0).cos(),
            ),
        },
        Sim {
            w: rot(7.0),
            t: (0.0, 1.0),
        },
    ]
}

/// The frame of both states in fixtures/kite-dart.aut.
const KITE_FRAME: [(f64, f64); 3] = [(-4.0, -0.5), (4.0, -0.5), (0.0, 5.0)];

#[test]
fn the_kite_and_dart_are_the_paper_s_maps_with_one_sign_corrected() {
    for (input, sign) in [
        ("kite-dart", -1.0),
        ("fixtures/kite-dart-as-printed.aut", 1.0),
    ] {
        let [_, t1a, t0b, t1b] = paper_maps(sign);
        // The level-2 leaves from a, in the walk's order: a.T0 b.T0, a.T0 b.T1, a.T1 a.T0,
        // a.T1 a.T1, each the image of the frame (T0a is the identity).
        let want: [Vec<(f64, f64)>; 4] = [
            KITE_FRAME.iter().map(|&p| t0b.apply(p)).collect(),
            KITE_FRAME.iter().map(|&p| t1b.apply(p)).collect(),
            KITE_FRAME.iter().map(|&p| t1a.apply(p)).collect(),
            KITE_FRAME
                .iter()
                .map(|&p| t1a.apply(t1a.apply(p)))
                .collect(),
        ];
        let got: Vec<Vec<(f64, f64)>> = pieces(input, "2")
            .into_iter()
            .map(|p| p.into_iter().map(|[x, y]| (x, y)).collect())
            .collect();
        assert_eq!(got.len(), 4, "{input}");
        for (g, w) in got.iter().zip(&want) {
            for (a, b) in g.iter().zip(w) {
                assert!(
                    (a.0 - b.0).abs() < 1e-9 && (a.1 - b.1).abs() < 1e-9,
                    "{input}: {g:?} against the paper's {w:?}"
                );
            }
        }
    }
    // As printed, two words of different first letters give one map (composed here from the
    // formulas alone): u = T0a T1b T0a T0b T0b T0b T1b T0a, v = T1a T1a T1a T1a T0a T0b. Corrected,
    // they differ.
    let word = |maps: &[Sim; 4], w: &[usize], z: (f64, f64)| {
        w.iter().rev().fold(z, |z, &i| maps[i].apply(z))
    };
    let (u, v) = ([0, 3, 0, 2, 2, 2, 3, 0], [1, 1, 1, 1, 0, 2]);
    for (sign, same) in [(1.0, true), (-1.0, false)] {
        let maps = paper_maps(sign);
        let apart = KITE_FRAME
            .iter()
            .map(|&p| {
                let (a, b) = (word(&maps, &u, p), word(&maps, &v, p));
                (a.0 - b.0).hypot(a.1 - b.1)
            })
            .fold(0.0, f64::max);
        assert_eq!(apart < 1e-12, same, "sign {sign}: {apart}");
    }
    // lacuna proves both verdicts, and its checker accepts both certificates.
    let dir = std::env::temp_dir().join(format!("lacuna-kite-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (input, verdict) in [
        (
            "kite-dart",
            "(the Hausdorff dimension: holds: the neighbour maps",
        ),
        (
            "fixtures/kite-dart-as-printed.aut",
            "fails: the identity is a neighbour map (two words starting with `a.T0` and `a.T1`",
        ),
    ] {
        let cert = dir.join("c.json");
        let (code, out, err) = lacuna(&["verify", input, "--certificate", cert.to_str().unwrap()]);
        assert_eq!(code, 0, "{input}: {err}");
        assert!(out.contains("similarity dimension = 2 = 2.000"), "{out}");
        assert!(out.contains(verdict), "{input}: {out}");
        let (code, out, _) = lacuna(&["check", cert.to_str().unwrap()]);
        assert_eq!(code, 0, "{input}: {out}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

// ---- Seed 004: Fig. 4 and the constraint figures of §3 ----

/// The degrees of freedom of the entries of seed 004's §3, derived by hand, against what `solve`
/// prints now and what docs/GALLERY.md says. Every column is barycentric (its entries sum to 1),
/// so a column of 3 entries with none fixed has 2 free entries, one of 9 has 8.
/// - `spec-edge-incidence`: incidence fixes T₀'s column 0 to B₀ = (1, 0, 0) and T₁'s column 2 to
///   (0, 0, 1); the other two columns of each are free: 2·2 + 2·2 = 8.
/// - `spec-edge`: adjacency `T₀ B₁ = T₁ B₀` also makes T₀'s column 2 equal T₁'s column 0: one
///   column of 2 free entries less, 8 − 2 = 6 (the paper's "6 degrees of freedom left").
/// - `quad-patch`: the patch has 9 control points (bi-quadratic), each sub-patch operator 9×9.
///   A corner sub-patch has 5 of its points on the parent's boundary edges, fixed by the edge's
///   operators through incidence. Free columns: each sub-patch's inner point (4 columns), the
///   middle point of each of the 4 inner edges shared by two sub-patches (adjacency makes it one
///   column for both), and the parent's centre, shared by all four (1 column): 9 columns of 8
///   free entries, 72.
/// - `half-tangent-edge`: 2 (the derivation in tests/solver.rs).
/// - `bspline-quadratic-4`: every operator is given: 0.
#[test]
fn seed_004_constraint_figures_have_their_hand_derived_degrees_of_freedom() {
    let by_hand = [
        ("bspline-quadratic-4", 0),
        ("spec-edge-incidence", 8),
        ("spec-edge", 6),
        ("quad-patch", 72),
        ("half-tangent-edge", 2),
    ];
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/GALLERY.md"))
        .expect("docs/GALLERY.md");
    let solved: Vec<&str> = text
        .lines()
        .filter_map(|l| l.strip_prefix("lacuna solve "))
        .map(str::trim)
        .collect();
    assert_eq!(
        solved,
        by_hand.iter().map(|(n, _)| *n).collect::<Vec<_>>(),
        "the solve commands of docs/GALLERY.md"
    );
    for (name, dof) in by_hand {
        let (code, out, err) = lacuna(&["solve", name, "--json"]);
        assert_eq!(code, 0, "{name}: {err}");
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        assert_eq!(v["consistent"], true, "{name}");
        assert_eq!(v["dof"].as_u64(), Some(dof), "{name}");
        // The table of Fig. 6–11 names the entry and starts its last cell with the number.
        if let Some(row) = text.lines().find(|l| l.contains(&format!("| `{name}` |"))) {
            let last = row.trim_end_matches('|').rsplit('|').next().unwrap().trim();
            assert!(
                last.starts_with(&dof.to_string()),
                "docs/GALLERY.md says {last} for {name}; by hand {dof}"
            );
        }
    }
    // The pictures of these sections are the ones the commands draw now (SVG, byte for byte).
    let dir = std::env::temp_dir().join(format!("lacuna-gallery-svg-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let section = &text[text
        .find("### Fig. 4 — the uniform quadratic B-spline")
        .unwrap()..];
    for line in section.lines().filter(|l| l.starts_with("lacuna render ")) {
        let mut args: Vec<String> = line.split_whitespace().skip(1).map(String::from).collect();
        let svg = args.iter().position(|a| a == "--svg").expect("--svg") + 1;
        let committed = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(&args[svg]);
        let fresh = dir.join("fresh.svg");
        args[svg] = fresh.to_str().unwrap().to_string();
        let run: Vec<&str> = args.iter().map(String::as_str).collect();
        let (code, _, err) = lacuna(&run);
        assert_eq!(code, 0, "{line}: {err}");
        assert!(
            std::fs::read(&fresh).unwrap() == std::fs::read(&committed).unwrap(),
            "{} differs from `{line}`: run docs/make-automaton-images.sh",
            committed.display()
        );
    }
    // The measure line of Fig. 4: the contraction is proved (T0a, T1a on no cycle).
    for line in section.lines().filter(|l| l.starts_with("lacuna measure ")) {
        let args: Vec<&str> = line.split_whitespace().skip(1).collect();
        let (code, out, err) = lacuna(&args);
        assert_eq!(code, 0, "{line}: {err}");
        assert!(out.contains("contraction: proven"), "{line}: {out}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

// ---- Seed 001: differential behaviour of BC-IFS curves ----

/// The seed-001 section of docs/GALLERY.md: every `$ lacuna …` line of its console blocks, with
/// the output lines shown under it (`…` marks lines left out).
fn seed_001_commands() -> Vec<(String, Vec<String>)> {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/GALLERY.md"))
        .expect("docs/GALLERY.md");
    let start = text.find("## Seed 001").expect("a seed 001 section");
    let end = text.find("## Seed 002").expect("a seed 002 section");
    let mut out: Vec<(String, Vec<String>)> = Vec::new();
    let mut inside = false;
    for line in text[start..end].lines() {
        if line.starts_with("```") {
            inside = line == "```console";
        } else if !inside {
        } else if let Some(cmd) = line.strip_prefix("$ lacuna ") {
            out.push((cmd.to_string(), Vec::new()));
        } else if let Some(last) = out.last_mut() {
            last.1.push(line.to_string());
        }
    }
    out
}

/// Splits a command line as the shell does for the gallery's commands: words, and `'…'` quoted.
fn shell_words(line: &str) -> Vec<String> {
    let (mut words, mut cur, mut quoted, mut any) = (Vec::new(), String::new(), false, false);
    for ch in line.chars() {
        match ch {
            '\'' => (quoted, any) = (!quoted, true),
            ' ' if !quoted => {
                if any {
                    words.push(std::mem::take(&mut cur));
                }
                any = false;
            }
            _ => (cur.push(ch), any = true).1,
        }
    }
    if any {
        words.push(cur);
    }
    words
}

/// Runs one gallery command, its picture written to a temporary file instead (compared byte for
/// byte with the committed one): the standard output, with the temporary path put back.
fn run_gallery_command(cmd: &str) -> String {
    let mut args = shell_words(cmd);
    let dir = std::env::temp_dir().join(format!("lacuna-gallery-cmd-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut picture = None;
    if let Some(i) = args.iter().position(|a| a == "--svg" || a == "--png") {
        let committed = args[i + 1].clone();
        let fresh = dir.join(committed.rsplit('/').next().unwrap());
        args[i + 1] = fresh.to_str().unwrap().to_string();
        picture = Some((committed, fresh));
    }
    let run: Vec<&str> = args.iter().map(String::as_str).collect();
    let (code, out, err) = lacuna(&run);
    assert_eq!(code, 0, "lacuna {cmd}: {err}");
    let mut out = out;
    if let Some((committed, fresh)) = picture {
        let want = std::fs::read(std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(&committed))
            .unwrap_or_else(|_| panic!("{committed} is missing"));
        assert!(
            std::fs::read(&fresh).unwrap() == want,
            "{committed} differs from `lacuna {cmd}`: run docs/make-automaton-images.sh"
        );
        out = out.replace(fresh.to_str().unwrap(), &committed);
    }
    std::fs::remove_dir_all(&dir).ok();
    out
}

/// A fraction n/d, written as lacuna writes it (`n/d`, or `n` when d = 1), with d > 0.
#[derive(Clone, Copy, PartialEq, Debug)]
struct Frac(i64, i64);

impl Frac {
    fn new(n: i64, d: i64) -> Frac {
        let g = gcd(n.abs(), d.abs());
        let s = if d < 0 { -1 } else { 1 };
        Frac(s * n / g, s * d / g)
    }
    fn text(self) -> String {
        match self.1 {
            1 => self.0.to_string(),
            d => format!("{}/{d}", self.0),
        }
    }
    fn f(self) -> f64 {
        self.0 as f64 / self.1 as f64
    }
    fn one_minus(self) -> Frac {
        Frac::new(self.1 - self.0, self.1)
    }
}

fn gcd(a: i64, b: i64) -> i64 {
    if b == 0 {
        a
    } else {
        gcd(b, a % b)
    }
}

/// The paper's class of an operator from its two leading eigenvalues (§4–§6): λ1 < 0 makes the
/// tangent oscillate; otherwise compare |λ2| with λ1² — α = log|λ2| / log λ1 is 2 exactly when
/// they are equal (finite range), above 2 when |λ2| is smaller (flat), below when larger (sharp).
/// Compared over the integers: |n2|/d2 against n1²/d1².
fn hand_class(l1: Frac, l2: Frac) -> &'static str {
    if l1.0 < 0 {
        return "oscillating";
    }
    let (lhs, rhs) = (
        (l2.0.abs() as i128) * (l1.1 as i128).pow(2),
        (l1.0 as i128).pow(2) * l2.1 as i128,
    );
    match lhs.cmp(&rhs) {
        std::cmp::Ordering::Equal => "finite",
        std::cmp::Ordering::Less => "flat",
        std::cmp::Ordering::Greater => "sharp",
    }
}

/// Takagi's function `Σ_n dist(2ⁿx, Z)/2ⁿ`; for a dyadic x of denominator 2^k the terms of
/// n ≥ k vanish, so 60 terms are exact up to rounding.
fn takagi(x: f64) -> f64 {
    (0..60)
        .map(|n| {
            let y = x * 2f64.powi(n);
            (y - y.round()).abs() / 2f64.powi(n)
        })
        .sum()
}

#[test]
fn seed_001_commands_print_what_the_gallery_shows_and_the_hand_derived_values() {
    let commands = seed_001_commands();
    let output = |prefix: &str| -> String {
        let (cmd, shown) = commands
            .iter()
            .find(|(c, _)| c == prefix)
            .or_else(|| commands.iter().find(|(c, _)| c.starts_with(prefix)))
            .unwrap_or_else(|| panic!("docs/GALLERY.md has no `lacuna {prefix}…`"));
        let out = run_gallery_command(cmd);
        // The lines shown are the command's, in its order (`…` stands for lines left out).
        let printed: Vec<&str> = out.lines().collect();
        let mut from = 0;
        for line in shown.iter().filter(|l| l.as_str() != "…") {
            let at = printed[from..]
                .iter()
                .position(|l| l == line)
                .unwrap_or_else(|| panic!("`lacuna {cmd}` no longer prints\n{line}\n{out}"));
            from += at + 1;
        }
        out
    };

    // Fig. 1. The Takagi maps w0(x, y) = (x/2, x/2 + y/2), w1(x, y) = ((x + 1)/2, (1 − x)/2 + y/2)
    // in the barycentric coordinates (1 − x − y/2, y, x − y/2) of P0 = (0, 0), P1 = (1/2, 1),
    // P2 = (1, 0): column j of T_i holds w_i(P_j). Both have eigenvalues 1, 1/2, 1/2: T0 keeps
    // e0, and its block on (e1, e2) is [3/4 1/2; −1/8 1/4], trace 1 = 1/2 + 1/2, determinant
    // 3/16 + 1/16 = 1/4 = (1/2)², but not I/2: one eigenvector (a Jordan block); T1 is T0 with
    // the coordinates reversed.
    let bary = |(x, y): (f64, f64)| [1.0 - x - y / 2.0, y, x - y / 2.0];
    let w0 = |(x, y): (f64, f64)| (x / 2.0, x / 2.0 + y / 2.0);
    let w1 = |(x, y): (f64, f64)| ((x + 1.0) / 2.0, (1.0 - x) / 2.0 + y / 2.0);
    let p = [(0.0, 0.0), (0.5, 1.0), (1.0, 0.0)];
    let fixture =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/fixtures/takagi.aut"))
            .unwrap();
    for (name, w) in [("c.T0", &w0 as &dyn Fn(_) -> _), ("c.T1", &w1)] {
        let line = fixture
            .lines()
            .find(|l| l.starts_with(&format!("sub {name} ")))
            .unwrap();
        let inner = &line[line.find('[').unwrap() + 1..line.find(']').unwrap()];
        let rows: Vec<Vec<f64>> = inner
            .split(';')
            .map(|r| {
                r.split_whitespace()
                    .map(|e| match e.split_once('/') {
                        Some((n, d)) => n.parse::<f64>().unwrap() / d.parse::<f64>().unwrap(),
                        None => e.parse().unwrap(),
                    })
                    .collect()
            })
            .collect();
        for (j, &pj) in p.iter().enumerate() {
            let col = bary(w(pj));
            for i in 0..3 {
                assert!(close(rows[i][j], col[i], 1e-15), "{name}[{i}][{j}]");
            }
        }
    }
    let out = output("operators fixtures/takagi.aut");
    let half = Frac::new(1, 2).text();
    assert_eq!(
        out.matches(&format!("eigenvalues: 1, {half} (×2)")).count(),
        2,
        "{out}"
    );
    assert_eq!(
        out.matches(&format!("degenerate — λ1 = {half} is repeated"))
            .count(),
        2
    );
    // The picture: every leaf of level 6 is the image of the control triangle; the images of P0
    // and P2 are points of the graph, whose y is T(x).
    for leaf in pieces("fixtures/takagi.aut", "6") {
        for q in [leaf[0], leaf[2]] {
            assert!(
                close(q[1], takagi(q[0]), 1e-12),
                "{q:?}: T = {}",
                takagi(q[0])
            );
        }
    }
    output("render fixtures/takagi.aut");

    // Fig. 2 and §3. The de Casteljau halves are triangular: eigenvalues their diagonals, 1, 1/2,
    // 1/4; λ2 = 1/4 = (1/2)² = λ1², α = 2. T0 fixes e0; (T0 − I/2)v = 0 gives v2 = 0 and
    // v0 + v1 = 0: v1 = (−1, 1, 0). T1 fixes e2; (T1 − I/2)v = 0 gives v0 = 0 and v1 + v2 = 0:
    // v1 = (0, −1, 1). They join at T0·e2 = T0's third column = (1/4, 1/2, 1/4) = T1's first
    // column = T1·e0.
    let (one, q2, q4) = (Frac::new(1, 1), Frac::new(1, 2), Frac::new(1, 4));
    let out = output("operators --matrix '[1 1/2 1/4;");
    assert_eq!(
        out.matches(&format!(
            "eigenvalues: {}, {}, {}",
            one.text(),
            q2.text(),
            q4.text()
        ))
        .count(),
        2
    );
    assert_eq!(hand_class(q2, q4), "finite");
    assert_eq!(out.matches("finite — λ2 = λ1²").count(), 2, "{out}");
    assert!(out.contains("fixed point: (1, 0, 0)") && out.contains("fixed point: (0, 0, 1)"));
    assert!(out.contains("tangent v1 = (-1, 1, 0)") && out.contains("tangent v1 = (0, -1, 1)"));
    let out = output("operators de-casteljau-edge");
    assert!(out.contains("joint e.T0|e.T1 at (1/4, 1/2, 1/4)"), "{out}");

    // The Bézier curve of (0, 0), (1, 1), (2, 0): B(t) = (2t, 2t − 2t²), B' = (2, 2 − 4t),
    // B'' = (0, −4), κ = |B' × B''|/|B'|³ = 8/|B'|³: 8/8^(3/2) = 1/(2√2) at t = 0 and 1, 8/2³ = 1
    // at t = 1/2. The DCF of T0 from c1 = e2: e2 − e0 = (−1, 0, 1) = 2·(−1, 1, 0) + 1·(1, −2, 1),
    // x1 = 2, x2 = 1, β = x2/x1² = 1/4; κ = 2β·|V1 × V2|/|V1|³ with V1 = (1, 1), V2 = (0, −2):
    // 2·(1/4)·2/(2√2) = 1/(2√2) again. One DCF: every range is a single value.
    let out = output("operators de-casteljau-edge --points");
    assert!(
        out.contains("from fix(e.T1): x1 = 2, x2 = 1, β = 1/4"),
        "{out}"
    );
    let end = 1.0 / (2.0 * 2f64.sqrt());
    let lines: Vec<&str> = out.lines().collect();
    let dyadic = lines
        .iter()
        .position(|l| l.starts_with("pseudo-curvature at dyadic points"))
        .unwrap();
    let mut seen = 0;
    let mut kappa = 0.0;
    for l in &lines[dyadic..] {
        let l = l.trim();
        if let Some(t) = l.strip_prefix("t = ") {
            kappa = match t.split(' ').next().unwrap() {
                "1/2" => 1.0,
                _ => end,
            };
        } else if l.starts_with("left [") || l.starts_with("right [") {
            let inner = &l[l.find('[').unwrap() + 1..l.find(']').unwrap()];
            let (lo, hi) = inner.split_once(", ").unwrap();
            for v in [lo, hi] {
                let v: f64 = v.parse().unwrap();
                assert!(close(v, kappa, 1e-6), "{l}: by hand {kappa}");
            }
            seen += 1;
        }
    }
    assert_eq!(seen, 4, "{out}");

    // Figs. 16–22: the eigenvalues each caption gives, read as fractions (signs from the text:
    // Fig. 16 has λ2 < 0, Fig. 19 λ1 < 0), in the matrix [1 1−λ1 1−λ2; 0 λ1 0; 0 0 λ2]:
    // barycentric (columns sum to 1), triangular, so its eigenvalues are 1, λ1, λ2.
    let f = Frac::new;
    let captions = [
        ("16", f(3, 5), f(-9, 25)),
        ("17", f(11, 20), f(121, 400)),
        ("18", f(7, 10), f(49, 100)),
        ("19", f(-7, 20), f(49, 400)),
        ("20", f(3, 5), f(9, 25)),
        ("21", f(13, 20), f(169, 400)),
        ("22 left", f(7, 10), f(343, 1000)),
        ("22 right T0", f(1, 2), f(221, 625)),
        ("22 right T1", f(11, 20), f(4079, 10000)),
    ];
    let mut matrices = Vec::new();
    for (fig, l1, l2) in captions {
        let m = format!(
            "[1 {} {}; 0 {} 0; 0 0 {}]",
            l1.one_minus().text(),
            l2.one_minus().text(),
            l1.text(),
            l2.text()
        );
        let want = hand_class(l1, l2);
        let (code, out, err) = lacuna(&["operators", "--matrix", &m]);
        assert_eq!(code, 0, "{m}: {err}");
        assert!(
            out.starts_with(&format!(
                "matrix (3×3, barycentric, contractive): {want} — "
            )),
            "Fig. {fig}: by hand {want}; lacuna: {out}"
        );
        match want {
            "flat" | "sharp" => {
                let alpha = l2.f().abs().ln() / l1.f().ln();
                let shown = out.split("α ≈ ").nth(1).unwrap().trim();
                assert!(close(shown.parse().unwrap(), alpha, 1e-6), "{fig}: {alpha}");
            }
            "finite" if l2.0 < 0 => assert!(out.contains("λ2 = -λ1²"), "{out}"),
            _ => {}
        }
        matrices.push(m);
    }
    // The page runs exactly these matrices, and its table states the classes derived above.
    let documented: Vec<String> = commands
        .iter()
        .filter(|(c, _)| c.starts_with("operators --matrix") && !c.contains("[1 1/2 1/4;"))
        .flat_map(|(c, _)| {
            shell_words(c)
                .into_iter()
                .filter(|w| w.starts_with('['))
                .collect::<Vec<_>>()
        })
        .collect();
    let mut a = documented.clone();
    let mut b = matrices.clone();
    a.sort();
    b.sort();
    assert_eq!(a, b, "the caption matrices of docs/GALLERY.md");

    // Figs. 20–21 in kind (fixtures/alpha-two-valley.aut): T0 = [1 2/5 9/25; 0 3/5 7/25; 0 0 9/25]
    // is triangular, eigenvalues 1, 3/5, 9/25 = (3/5)²: α = 2; T1 is T0 with the coordinates
    // reversed. The joint is T0's third column (9/25, 7/25, 9/25). Eigenvectors of T0:
    // (T0 − 3/5)v = 0 gives z = 0, x = −y: v1 = (−1, 1, 0); (T0 − 9/25)v = 0 gives y = −7z/6 and
    // 16x/25 = (7/15 − 9/25)z = 8z/75, x = z/6: v2 = (1/6, −7/6, 1). From c1 = e2:
    // e2 − e0 = (−1, 0, 1) = (7/6)·v1 + 1·v2, β = 1/(7/6)² = 36/49, and with P = (0, 0), (1, 3),
    // (2, 0) the curvature of that DCF is 2β·|V1 × V2|/|V1|³. By the symmetry (x ↦ 2 − x swaps
    // the control points P0 and P2 and the operators), the left and right ranges at the joint
    // are equal, as the paper says of its symmetric curves.
    let project = |v: [f64; 3], p: [[f64; 2]; 3]| {
        [
            v[0] * p[0][0] + v[1] * p[1][0] + v[2] * p[2][0],
            v[0] * p[0][1] + v[1] * p[1][1] + v[2] * p[2][1],
        ]
    };
    let dcf_kappa = |beta: f64, v1: [f64; 3], v2: [f64; 3], p: [[f64; 2]; 3]| {
        let (a, b) = (project(v1, p), project(v2, p));
        2.0 * beta * (a[0] * b[1] - a[1] * b[0]).abs() / (a[0] * a[0] + a[1] * a[1]).powf(1.5)
    };
    let ranges = |out: &str, prefix: &str| -> Vec<[f64; 2]> {
        out.lines()
            .filter(|l| l.trim_start().starts_with(prefix))
            .flat_map(|l| {
                l.split('[')
                    .skip(1)
                    .map(|r| {
                        let (lo, hi) = r[..r.find(']').unwrap()].split_once(", ").unwrap();
                        let num = |x: &str| {
                            if x == "+∞" {
                                f64::INFINITY
                            } else {
                                x.parse().unwrap()
                            }
                        };
                        [num(lo), num(hi)]
                    })
                    .collect::<Vec<[f64; 2]>>()
            })
            .collect()
    };
    let out = output("operators fixtures/alpha-two-valley.aut");
    assert!(
        out.contains("joint c.T0|c.T1 at (9/25, 7/25, 9/25)"),
        "{out}"
    );
    assert!(out.contains("c = (1, 0, 0), v1 = (-1, 1, 0), v2 = (1/6, -7/6, 1)"));
    assert!(out.contains("from fix(c.T1): x1 = 7/6, x2 = 1, β = 36/49"));
    let k = dcf_kappa(
        36.0 / 49.0,
        [-1.0, 1.0, 0.0],
        [1.0 / 6.0, -7.0 / 6.0, 1.0],
        [[0.0, 0.0], [1.0, 3.0], [2.0, 0.0]],
    );
    let start = ranges(&out, "right [")[0];
    assert!(close(start[1], k, 1e-6), "κ from c1 by hand {k}: {start:?}");
    assert!(
        start[0] < start[1] - 1e-3,
        "a range, not one value: {start:?}"
    );
    let (left, right) = (ranges(&out, "left ["), ranges(&out, "right ["));
    assert_eq!(left[0], right[1], "the joint: left and right ranges equal");
    assert_eq!(left[1], start, "the end mirrors the start");

    // Fig. 19 on a curve of our own (fixtures/negative-lambda1-curve.aut): T0 = [1 27/20 1/4;
    // 0 −7/20 251/400; 0 0 49/400], triangular, λ1 = −7/20, λ2 = 49/400 = λ1². (T0 + 7/20)v = 0
    // gives z = 0, x = −y: v1 = (−1, 1, 0). (T0 − 49/400)v = 0: −189y/400 + 251z/400 = 0, so
    // y = 251z/189, and 351x/400 = −(27/20·251/189 + 1/4)z = −(251/140 + 35/140)z, so
    // x = −440z/189: v2 = (−440/189, 251/189, 1). From c1 = e2: (−1, 0, 1) = x1·v1 + x2·v2 gives
    // x2 = 1, x1 = −251/189, β = x2/x1² = (189/251)² = 35721/63001; with P = (0, 0), (1, 1),
    // (2, 0) its curvature lies in the range on both sides. The range has no upper bound: the
    // sub-arc T0ⁿ(C) minus T0ⁿ⁺¹(C) joins points with x1 of both signs (T0ⁿ of the curve's end
    // has the sign of (−7/20)ⁿ), so it meets x1 = 0 near c, where β is infinite (THEORY §8). The
    // class is `oscillating`, κsup is +∞, and κinf (sampled) can only fall with the level.
    let curve = "operators fixtures/negative-lambda1-curve.aut --points '0 0; 1 1; 2 0'";
    let out = output(curve);
    assert!(out.starts_with("c.T0 (3×3, barycentric, contractive): oscillating"));
    assert!(
        out.contains("v1 = (-1, 1, 0), v2 = (-440/189, 251/189, 1)"),
        "{out}"
    );
    assert!(out.contains("from fix(c.T1): x1 = -251/189, x2 = 1, β = 35721/63001"));
    assert!(
        out.contains("c.T0: oscillating (α = 2), λ1 = -7/20"),
        "{out}"
    );
    let k = dcf_kappa(
        35721.0 / 63001.0,
        [-1.0, 1.0, 0.0],
        [-440.0 / 189.0, 251.0 / 189.0, 1.0],
        [[0.0, 0.0], [1.0, 1.0], [2.0, 0.0]],
    );
    let eight = ranges(&out, "c.T0: x1 > 0");
    assert_eq!(eight.len(), 2, "both sides of c0");
    assert_eq!(eight[0], eight[1], "both sub-sequences, one range");
    assert!(eight[0][0] <= k && k <= eight[0][1], "{k} in {eight:?}");
    assert_eq!(eight[0][1], f64::INFINITY, "{eight:?}");
    let twelve = ranges(&output(&format!("{curve} --level 12")), "c.T0: x1 > 0");
    assert!(
        twelve[0][1] == f64::INFINITY && twelve[0][0] <= eight[0][0],
        "level 8: {eight:?}, level 12: {twelve:?}"
    );

    // Every command of the section prints what the page shows (and draws what it shows).
    for (c, _) in &commands {
        output(c);
    }
    assert_eq!(
        commands.len(),
        14,
        "the seed 001 commands of docs/GALLERY.md"
    );
}

// ---- Seed 002, Fig. 3: the triangle's and the hexagon's levels in turn ----

/// Fig. 3's points of level k by eq. (10)–(11) directly: every sum `Σ_i h_i` where level i adds
/// `e^(jθ)/2^(i−1)` with θ in {2π/3, 4π/3, 2π} at odd i and `e^(jθ)/3^(i−1)` with θ = uπ/3 at
/// even i (a_f = a_g = 1, as the fixture takes them).
fn figure_3(level: u32) -> Vec<[f64; 2]> {
    let mut points = vec![[0.0, 0.0]];
    for i in 1..=level {
        let (angles, amp): (Vec<f64>, f64) = if i % 2 == 1 {
            (
                (1..=3).map(|u| 2.0 * PI * u as f64 / 3.0).collect(),
                0.5f64.powi(i as i32 - 1),
            )
        } else {
            (
                (1..=6).map(|u| PI * u as f64 / 3.0).collect(),
                (1.0f64 / 3.0).powi(i as i32 - 1),
            )
        };
        points = points
            .iter()
            .flat_map(|p| {
                angles
                    .iter()
                    .map(move |t| [p[0] + amp * t.cos(), p[1] + amp * t.sin()])
            })
            .collect();
    }
    points
}

#[test]
fn figure_3_alternates_the_triangle_s_levels_and_the_hexagon_s() {
    let file = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/fixtures/triangle-hexagon-alternating.aut"
    );
    for level in [1u32, 2, 3] {
        let mut drawn: Vec<[f64; 2]> = pieces(file, &level.to_string())
            .iter()
            .map(|s| s[0])
            .collect();
        let mut want = figure_3(level);
        // 3, 18, 54 pieces: three and six in turn.
        assert_eq!(drawn.len(), want.len(), "level {level}");
        let key = |p: &[f64; 2]| ((p[0] * 1e6).round() as i64, (p[1] * 1e6).round() as i64);
        drawn.sort_by_key(key);
        want.sort_by_key(key);
        for (d, w) in drawn.iter().zip(&want) {
            assert!(
                close(d[0], w[0], 1e-9) && close(d[1], w[1], 1e-9),
                "level {level}: drawn {d:?}, eq. (10) gives {w:?}"
            );
        }
    }
    // Its cardinality is neither gasket's: 18 pieces at level 2 against the triangle's 9.
    let (code, out, err) = lacuna(&["classify", file, "gasket-3", "--json"]);
    assert_eq!(code, 1, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["differs"]["group"], "cardinality");
    assert_eq!(v["differs"]["level"], 2);
    assert_eq!(
        (v["differs"]["a"].clone(), v["differs"]["b"].clone()),
        ("18".into(), "9".into())
    );
    // The gallery's picture is what render draws now.
    run_gallery_command(
        "render fixtures/triangle-hexagon-alternating.aut --level 6 --png docs/images/triangle-hexagon-alternating.png",
    );
}

#[test]
fn figure_9_lifts_the_lemniscate_to_a_space_curve_whose_views_are_the_two_sets() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/fixtures/");
    let circle = format!("{dir}twisted-circle-circle-view.aut");
    let lemniscate = format!("{dir}twisted-circle-lemniscate-view.aut");
    // The views' level-1 points: the samples θ = uπ/3 of (cos θ, sin θ) and (sin θ, sin 2θ).
    for (file, curve) in [
        (
            &circle,
            (|t: f64| [t.cos(), t.sin()]) as fn(f64) -> [f64; 2],
        ),
        (&lemniscate, |t: f64| [t.sin(), (2.0 * t).sin()]),
    ] {
        let drawn = pieces(file, "1");
        assert_eq!(drawn.len(), 6, "{file}");
        for (k, d) in drawn.iter().enumerate() {
            let p = curve((k + 1) as f64 * PI / 3.0);
            assert!(
                close(d[0][0], p[0], 1e-12) && close(d[0][1], p[1], 1e-12),
                "{file}: T{k} draws {:?}, the curve's sample is {p:?}",
                d[0]
            );
        }
    }
    // The two views are one automaton: the morph moves control points only.
    let (code, out, err) = lacuna(&[
        "morph",
        &circle,
        &lemniscate,
        "--frames",
        "3",
        "--level",
        "2",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("0 of 6 operators change") && out.contains("VERIFIED: every frame"),
        "{out}"
    );
    // In R^3 the six maps are distinct (the crossing is two points of the lift): six distinct
    // maps against the lemniscate fractal's five.
    let lift = format!("{dir}twisted-circle.aut");
    let (code, out, err) = lacuna(&["classify", &lift, "lemniscate-fractal", "--json"]);
    assert_eq!(code, 1, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["differs"]["invariant"], "distinct maps");
    assert_eq!(
        (v["differs"]["a"].clone(), v["differs"]["b"].clone()),
        ("6".into(), "5".into())
    );
    let (code, out, err) = lacuna(&["classify", &lift, "gasket-6", "--json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["same_class"], true);
    // The gallery's animation is what the morph draws now (relative paths, as the script
    // writes them: the SVG's title names the files; cargo runs tests from the package root).
    run_gallery_command(
        "morph fixtures/twisted-circle-circle-view.aut fixtures/twisted-circle-lemniscate-view.aut --frames 8 --level 3 --svg docs/images/twisted-circle-circle-to-lemniscate.svg",
    );
}
