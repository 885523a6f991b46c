//! Pictures and files of an automaton's attractor: SVG, colour PNG, JSON and OBJ of the shapes of
//! level n ([`crate::geometry::Evaluator`]), and the HTML report of an automaton. In space 3 the
//! SVG and PNG show an axonometric view; OBJ keeps the coordinates.

use crate::analysis::CurveCurvature;
use crate::export::html::esc;
use crate::export::plot::{plot_svg, signed, tick_label, ticks, Plot};
use crate::geometry::point::{fit_line, Raster};
use crate::geometry::{Evaluator, Shape, ShapeKind};
use crate::measure::AutomatonMeasure;
use std::fmt::Write as _;
use std::io::{self, Write};

/// The plane picture of a point: itself in space 2, an axonometric view in space 3.
fn view(space: usize, p: &[f64; 3]) -> (f64, f64) {
    if space == 3 {
        let (c, s) = (0.866_025_403_784_438_6, 0.5);
        ((p[0] - p[1]) * c, p[2] + (p[0] + p[1]) * s)
    } else {
        (p[0], p[1])
    }
}

fn bounds2(space: usize, shapes: &[Shape]) -> (f64, f64, f64, f64) {
    let (mut x0, mut y0, mut x1, mut y1) = (f64::MAX, f64::MAX, f64::MIN, f64::MIN);
    for s in shapes {
        for p in &s.points {
            let (x, y) = view(space, p);
            x0 = x0.min(x);
            y0 = y0.min(y);
            x1 = x1.max(x);
            y1 = y1.max(y);
        }
    }
    if x0 > x1 {
        return (0.0, 0.0, 1.0, 1.0);
    }
    let pad = ((x1 - x0).max(y1 - y0) * 0.03).max(1e-9);
    // A drawing on a line (a Cantor set) gets a band a quarter as high as it is wide, its
    // pieces drawn as bars across it ([`crate::export::bitmap::bar_width`]).
    let grow = ((x1 - x0) / 8.0 - (y1 - y0) / 2.0 - pad).max(0.0);
    (x0 - pad, y0 - pad - grow, x1 + pad, y1 + pad + grow)
}

/// The SVG text of shapes (y upwards), `width` pixels wide.
pub fn automaton_svg(space: usize, shapes: &[Shape], width: f64) -> String {
    let (x0, y0, x1, y1) = bounds2(space, shapes);
    let scale = width / (x1 - x0);
    let h = (y1 - y0) * scale;
    let flat = shapes
        .iter()
        .flat_map(|sh| &sh.points)
        .map(|p| view(space, p).1)
        .fold((f64::MAX, f64::MIN), |(a, b), y| (a.min(y), b.max(y)));
    let stroke = crate::export::bitmap::bar_width(x1 - x0, (flat.1 - flat.0).max(0.0), width, 1.0);
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width:.0}\" height=\"{h:.0}\" viewBox=\"0 0 {width:.3} {h:.3}\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    );
    let pt = |p: &[f64; 3]| {
        let (x, y) = view(space, p);
        ((x - x0) * scale, (y1 - y) * scale)
    };
    let colours = [
        "#1f5fa8", "#c0392b", "#27864a", "#8e44ad", "#d35400", "#2c3e50",
    ];
    for sh in shapes {
        let col = colours[sh.state % colours.len()];
        let pts: Vec<String> = sh
            .points
            .iter()
            .map(|p| {
                let (x, y) = pt(p);
                format!("{x:.3},{y:.3}")
            })
            .collect();
        match sh.kind {
            ShapeKind::Point => {
                let (x, y) = pt(&sh.points[0]);
                let _ = writeln!(
                    s,
                    "<circle cx=\"{x:.3}\" cy=\"{y:.3}\" r=\"1.2\" fill=\"{col}\"/>"
                );
            }
            ShapeKind::Polyline => {
                let _ = writeln!(s, "<polyline points=\"{}\" fill=\"none\" stroke=\"{col}\" stroke-width=\"{stroke:.2}\" stroke-linejoin=\"round\"/>", pts.join(" "));
            }
            ShapeKind::Polygon => {
                let _ = writeln!(s, "<polygon points=\"{}\" fill=\"{col}\" fill-opacity=\"0.35\" stroke=\"{col}\" stroke-width=\"0.5\"/>", pts.join(" "));
            }
        }
    }
    s += "</svg>\n";
    s
}

/// Writes level n as a colour PNG `width` pixels wide ([`crate::export::write_shapes_png`]):
/// polygons filled by state, polylines stroked, centred, with a legend of the states.
pub fn write_automaton_png<W: Write>(
    ev: &Evaluator,
    level: u32,
    width: u32,
    background: crate::export::Background,
    legend: bool,
    out: W,
) -> io::Result<()> {
    let space = ev.space;
    let to_plane = |p: &[f64; 3]| view(space, p);
    // The axonometric view's line of sight: screen x = (x − y)·cos 30°, screen y = z +
    // (x + y)/2, so points of larger x + y − z lie farther away.
    let depth = |p: &[f64; 3]| p[0] + p[1] - p[2];
    crate::export::write_shapes_png(
        &ev.shapes(level),
        crate::export::Projection {
            to_plane: &to_plane,
            depth: (space == 3).then_some(&depth as &crate::export::bitmap::Depth),
        },
        &ev.names,
        width,
        background,
        legend,
        out,
    )
}

/// Writes the SVG of level n.
pub fn write_automaton_svg<W: Write>(ev: &Evaluator, level: u32, mut out: W) -> io::Result<()> {
    out.write_all(automaton_svg(ev.space, &ev.shapes(level), 800.0).as_bytes())?;
    out.flush()
}

/// Writes the shapes of level n as JSON: `{"space", "level", "shapes": [{"state", "kind",
/// "points"}]}` (points with `space` coordinates).
pub fn write_automaton_json<W: Write>(ev: &Evaluator, level: u32, mut out: W) -> io::Result<()> {
    write!(
        out,
        "{{\"space\":{},\"level\":{level},\"shapes\":[",
        ev.space
    )?;
    let mut first = true;
    let mut res = Ok(());
    ev.walk(level, &mut |q, _, pts| {
        if res.is_err() {
            return;
        }
        if let Some(s) = ev.shape(q, pts) {
            let p: Vec<String> = s
                .points
                .iter()
                .map(|p| {
                    let c: Vec<String> = p[..ev.space].iter().map(|v| format!("{v}")).collect();
                    format!("[{}]", c.join(","))
                })
                .collect();
            let kind = match s.kind {
                ShapeKind::Point => "point",
                ShapeKind::Polyline => "polyline",
                ShapeKind::Polygon => "polygon",
            };
            res = write!(
                out,
                "{}{{\"state\":\"{}\",\"kind\":\"{kind}\",\"points\":[{}]}}",
                if first { "" } else { "," },
                ev.names[q],
                p.join(",")
            );
            first = false;
        }
    });
    res?;
    writeln!(out, "]}}")?;
    out.flush()
}

/// Writes level n as Wavefront OBJ: a vertex per point, `p` for points, `l` for polylines, `f`
/// for polygons.
pub fn write_automaton_obj<W: Write>(ev: &Evaluator, level: u32, mut out: W) -> io::Result<()> {
    writeln!(out, "# lacuna: automaton attractor, level {level}")?;
    let mut next = 1usize;
    let mut res = Ok(());
    ev.walk(level, &mut |q, _, pts| {
        if res.is_err() {
            return;
        }
        if let Some(s) = ev.shape(q, pts) {
            let mut text = String::new();
            for p in &s.points {
                let _ = writeln!(text, "v {} {} {}", p[0], p[1], p[2]);
            }
            let idx: Vec<String> = (next..next + s.points.len())
                .map(|i| i.to_string())
                .collect();
            next += s.points.len();
            let tag = match s.kind {
                ShapeKind::Point => "p",
                ShapeKind::Polyline => "l",
                ShapeKind::Polygon => "f",
            };
            let _ = writeln!(text, "{tag} {}", idx.join(" "));
            res = out.write_all(text.as_bytes());
        }
    });
    res?;
    out.flush()
}

/// Rasterises level n into a `size × size` 1-bit raster (lines one pixel wide, polygons filled).
pub fn automaton_raster(ev: &Evaluator, level: u32, size: usize) -> Raster {
    let shapes = ev.shapes(level);
    let (x0, y0, x1, y1) = bounds2(ev.space, &shapes);
    let side = (x1 - x0).max(y1 - y0);
    let scale = (size as f64 - 1.0) / side;
    let mut counts = vec![0u8; size * size];
    let mut set = |x: f64, y: f64| {
        let (c, r) = (x.floor(), (size as f64 - 1.0 - y).floor());
        if c >= 0.0 && r >= 0.0 && (c as usize) < size && (r as usize) < size {
            counts[r as usize * size + c as usize] = 1;
        }
    };
    let px = |p: &[f64; 3]| {
        let (x, y) = view(ev.space, p);
        ((x - x0) * scale, (y - y0) * scale)
    };
    for s in &shapes {
        let p: Vec<(f64, f64)> = s.points.iter().map(px).collect();
        let mut line = |a: (f64, f64), b: (f64, f64)| {
            let n = ((b.0 - a.0).abs().max((b.1 - a.1).abs()) * 2.0)
                .ceil()
                .max(1.0) as usize;
            for i in 0..=n {
                let t = i as f64 / n as f64;
                set(a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1));
            }
        };
        match s.kind {
            ShapeKind::Point => line(p[0], p[0]),
            ShapeKind::Polyline => p.windows(2).for_each(|w| line(w[0], w[1])),
            ShapeKind::Polygon => {
                for i in 1..p.len().saturating_sub(1) {
                    // Fill the fan triangle (p0, pi, pi+1) by lines from p0.
                    let (a, b) = (p[i], p[i + 1]);
                    let n = ((b.0 - a.0).abs().max((b.1 - a.1).abs()) * 2.0)
                        .ceil()
                        .max(1.0) as usize;
                    for j in 0..=n {
                        let t = j as f64 / n as f64;
                        line(p[0], (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1)));
                    }
                }
                for w in p.windows(2) {
                    line(w[0], w[1]);
                }
            }
        }
    }
    Raster {
        size,
        counts,
        origin: [x0, y0],
        scale,
    }
}

/// One side's pseudo-curvature ranges along a curve: `(t, κinf, κsup)`.
type RangeSeries<'a> = (&'a str, &'a str, Vec<(f64, f64, f64)>);

/// The curvature-range plot: at every reported parameter t, a vertical bar from κinf to κsup,
/// left side (t − 0) and right side (t + 0) offset apart; +∞ (a sharp point) is a triangle above
/// the top of the axis, a range with no sample is left out. Classes for the browser tests:
/// `curvature-plot`, `kappa-left`, `kappa-right`, `kappa-inf-marker`.
pub(crate) fn curvature_range_svg(title: &str, subtitle: &str, series: &[RangeSeries]) -> String {
    let (w, h) = (520.0, 340.0);
    let (left, right, top, bottom) = (62.0, 18.0, 86.0, 46.0);
    let finite_max = series
        .iter()
        .flat_map(|(_, _, v)| v.iter())
        .flat_map(|&(_, lo, hi)| [lo, hi])
        .filter(|k| k.is_finite())
        .fold(0.0f64, f64::max);
    let (ys, yt) = ticks(0.0, if finite_max > 0.0 { finite_max } else { 1.0 }, 5);
    let (xs, xt) = ticks(0.0, 1.0, 8);
    let ay1 = yt[yt.len() - 1];
    let px = |x: f64| left + x * (w - left - right);
    let py = |y: f64| h - bottom - y / ay1 * (h - top - bottom);
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"plot curvature-plot\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\" font-family=\"sans-serif\" font-size=\"12\">\
         <rect width=\"{w}\" height=\"{h}\" fill=\"white\"/>\
         <text x=\"{}\" y=\"17\" text-anchor=\"middle\" font-weight=\"bold\" font-size=\"13\">{}</text>\
         <text x=\"{}\" y=\"33\" text-anchor=\"middle\" fill=\"#555\" font-size=\"11\">{}</text>",
        w / 2.0,
        esc(title),
        w / 2.0,
        esc(subtitle)
    );
    let _ = write!(s, "<g class=\"axis x\">");
    for &x in &xt {
        let _ = write!(
            s,
            "<line x1=\"{0:.1}\" y1=\"{top}\" x2=\"{0:.1}\" y2=\"{1}\" stroke=\"#eee\"/><text class=\"tick\" x=\"{0:.1}\" y=\"{2}\" text-anchor=\"middle\">{3}</text>",
            px(x),
            h - bottom,
            h - bottom + 18.0,
            tick_label(x, xs)
        );
    }
    let _ = write!(
        s,
        "<line x1=\"{left}\" y1=\"{0}\" x2=\"{1}\" y2=\"{0}\" stroke=\"#333\"/><text x=\"{2}\" y=\"{3}\" text-anchor=\"middle\">parameter t</text></g>",
        h - bottom,
        w - right,
        (left + w - right) / 2.0,
        h - 8.0
    );
    let _ = write!(s, "<g class=\"axis y\">");
    for &y in &yt {
        let _ = write!(
            s,
            "<line x1=\"{left}\" y1=\"{0:.1}\" x2=\"{1}\" y2=\"{0:.1}\" stroke=\"#eee\"/><text class=\"tick\" x=\"{2}\" y=\"{3:.1}\" text-anchor=\"end\">{4}</text>",
            py(y),
            w - right,
            left - 8.0,
            py(y) + 4.0,
            tick_label(y, ys)
        );
    }
    let mid = (top + h - bottom) / 2.0;
    let _ = write!(
        s,
        "<line x1=\"{left}\" y1=\"{top}\" x2=\"{left}\" y2=\"{}\" stroke=\"#333\"/><text x=\"14\" y=\"{mid}\" transform=\"rotate(-90 14 {mid})\" text-anchor=\"middle\">pseudo-curvature κ</text><text class=\"tick\" x=\"{}\" y=\"{}\" text-anchor=\"end\">+∞</text><line x1=\"{left}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"#ddd\" stroke-dasharray=\"3,3\"/></g>",
        h - bottom,
        left - 8.0,
        top - 12.0,
        top - 16.0,
        w - right,
        top - 16.0
    );
    for (i, (name, colour, v)) in series.iter().enumerate() {
        let off = if i == 0 { -3.0 } else { 3.0 };
        let _ = write!(
            s,
            "<g class=\"kappa-{name}\"><rect x=\"{}\" y=\"{}\" width=\"10\" height=\"10\" fill=\"{colour}\"/><text x=\"{}\" y=\"{}\" font-size=\"11\">{} side (t {} 0)</text>",
            left + 10.0 + 150.0 * i as f64,
            top - 44.0,
            left + 24.0 + 150.0 * i as f64,
            top - 35.0,
            name,
            if i == 0 { "−" } else { "+" }
        );
        for &(t, lo, hi) in v {
            let x = px(t) + off;
            if lo.is_infinite() {
                let _ = write!(
                    s,
                    "<path class=\"kappa-inf-marker\" d=\"M{:.1},{:.1} l-4,8 h8 z\" fill=\"{colour}\"><title>t = {t}: +∞ (sharp)</title></path>",
                    x,
                    top - 20.0
                );
                continue;
            }
            if !(lo.is_finite() && hi.is_finite()) {
                continue;
            }
            let (y0, y1) = (py(lo), py(hi));
            let _ = write!(
                s,
                "<line x1=\"{x:.1}\" y1=\"{y0:.1}\" x2=\"{x:.1}\" y2=\"{:.1}\" stroke=\"{colour}\" stroke-width=\"3\"><title>t = {t}: [{lo:.6}, {hi:.6}]</title></line><circle cx=\"{x:.1}\" cy=\"{y0:.1}\" r=\"2.5\" fill=\"{colour}\"/><circle cx=\"{x:.1}\" cy=\"{y1:.1}\" r=\"2.5\" fill=\"{colour}\"/>",
                y1.min(y0 - 0.5)
            );
        }
        s += "</g>";
    }
    s + "</svg>"
}

/// The report's section on the curves of the automaton: the curvature-range plot of each.
fn curvature_section(h: &mut String, curves: &[(String, Result<CurveCurvature, String>)]) {
    if curves.is_empty() {
        return;
    }
    h.push_str("<h2 id=\"curvature\">Pseudo-curvature</h2>\n");
    for (state, c) in curves {
        match c {
            Err(e) => {
                let _ = writeln!(
                    h,
                    "<p>State {}: no pseudo-curvature ({}).</p>",
                    esc(state),
                    esc(e)
                );
            }
            Ok(c) => {
                let t_of = |t: &str| -> f64 {
                    match t.split_once('/') {
                        Some((a, b)) => {
                            a.trim().parse::<f64>().unwrap_or(f64::NAN)
                                / b.trim().parse::<f64>().unwrap_or(f64::NAN)
                        }
                        None => t.trim().parse().unwrap_or(f64::NAN),
                    }
                };
                let mut sides: [Vec<(f64, f64, f64)>; 2] = [Vec::new(), Vec::new()];
                let mut rows = String::new();
                let mut points: Vec<_> = c.points.iter().collect();
                points.sort_by(|a, b| t_of(&a.t).total_cmp(&t_of(&b.t)));
                for p in points {
                    let t = t_of(&p.t);
                    for (i, s) in [&p.left, &p.right].into_iter().enumerate() {
                        if let Some(s) = s {
                            sides[i].push((t, s.kappa_inf.0, s.kappa_sup.0));
                            let _ = write!(
                                rows,
                                "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
                                esc(&p.t),
                                if i == 0 { "left" } else { "right" },
                                esc(&s.class),
                                s.kappa_inf,
                                s.kappa_sup
                            );
                        }
                    }
                }
                let [l, r] = sides;
                let _ = writeln!(
                    h,
                    "<p>State {}: the range [κinf, κsup] of the pseudo-curvature on each side of the parameters t (start, joints, end and the points k/I³, I operators), from the differential characteristic functions: {}; level {}.</p>{}",
                    esc(state),
                    esc(&c.note),
                    c.level,
                    curvature_range_svg(
                        &format!("κinf and κsup against t, state {state}"),
                        "bars from κinf to κsup; ▲ on the +∞ row: a sharp side",
                        &[("left", "#1f5fa8", l), ("right", "#e07b00", r)],
                    )
                );
                let _ = writeln!(
                    h,
                    "<table class=\"kappa\"><tr><th>t</th><th>side</th><th>class</th><th>κinf</th><th>κsup</th></tr>{rows}</table>"
                );
            }
        }
    }
}

/// The box-counting plot: `ln N` against `k·ln 2 = ln(1/ε) + ln L` with its least-squares line.
fn box_section(h: &mut String, m: &AutomatonMeasure) {
    let pts = m.box_dimension.log_points();
    if pts.len() < 2 {
        return;
    }
    let f = fit_line(&pts);
    let _ = writeln!(
        h,
        "<div class=\"box-fit\">{}</div>",
        plot_svg(&Plot {
            title: "box counting: ln N(ε) against ln(1/ε)",
            subtitle: &format!(
                "level {} pieces, boxes of side ε = L/2ᵏ, k = {}…{}",
                m.box_dimension.level,
                m.box_dimension.counts[0].0,
                m.box_dimension.counts[m.box_dimension.counts.len() - 1].0
            ),
            xlabel: "ln(1/ε) + ln L = k·ln 2",
            ylabel: "ln N(ε)",
            points: &pts,
            fit: Some((
                &f,
                format!(
                    "ln N ≈ {}·k ln 2 {}  (residual {:.3})",
                    signed(f.slope, 4),
                    {
                        let c = signed(f.intercept.abs(), 3);
                        if f.intercept < 0.0 {
                            format!("− {c}")
                        } else {
                            format!("+ {c}")
                        }
                    },
                    f.residual
                )
            )),
        })
    );
}

/// The HTML report of an automaton: the solver's verdict, the contraction proof, the operators'
/// classes (text given by the caller), the dimensions (with the box-counting fit), the
/// pseudo-curvature ranges of its curves (`curves`: per state, computed by the caller), lengths
/// and areas per level, and a picture of each level 0 to n.
pub fn automaton_report_html(
    ev: &Evaluator,
    m: &AutomatonMeasure,
    classes: &str,
    curves: &[(String, Result<CurveCurvature, String>)],
    source: &str,
) -> String {
    // The layout of every report (crate::export::html::page_start): title, verdict, pictures,
    // then the details.
    let mut h = crate::export::html::page_start(&m.input);
    h += &crate::export::html::verdict_line(
        m.solver.consistent,
        if m.solver.consistent {
            "VERIFIED"
        } else {
            "NOT VERIFIED"
        },
        if m.solver.consistent {
            "the constraints hold exactly and every infinite walk contracts"
        } else {
            "a constraint fails: see Solver"
        },
    );
    let _ = writeln!(
        h,
        "<p>Automaton in space {}, drawn to level {}.</p>",
        m.space, m.level
    );
    h += "<h2>Pictures</h2>\n<div class=\"pics\">\n";
    for l in 0..=m.level {
        let _ = writeln!(
            h,
            "<figure>{}<figcaption>level {l}</figcaption></figure>",
            automaton_svg(ev.space, &ev.shapes(l), 320.0)
        );
    }
    h += "</div>\n";
    let _ = writeln!(
        h,
        "<h2>Solver</h2><p>Field {}: {}.</p>",
        esc(&m.solver.field),
        if m.solver.consistent {
            "every constraint holds"
        } else {
            "<b>constraints fail</b>"
        }
    );
    if !m.solver.failed.is_empty() || !m.solver.applied.is_empty() || !m.solver.free_left.is_empty()
    {
        h += "<ul>";
        for f in &m.solver.failed {
            let _ = write!(h, "<li>fails: {}</li>", esc(f));
        }
        for p in &m.solver.applied {
            let _ = write!(h, "<li>parameter {}</li>", esc(p));
        }
        if !m.solver.free_left.is_empty() {
            let _ = write!(
                h,
                "<li>free parameters left at 0: {}</li>",
                esc(&m.solver.free_left.join(", "))
            );
        }
        h += "</ul>\n";
    }
    let _ = writeln!(h, "<h2>Contraction</h2><p>{}.</p><p>Every elementary cycle of the control graph contracts (its product's eigenvalues other than the barycentric 1 lie in the open unit disk, decided exactly):</p><ul>", esc(&m.contraction.text()));
    for c in &m.contraction.cycles {
        let _ = write!(h, "<li>{}</li>", esc(c));
    }
    h += "</ul>\n<h2>Operators</h2>\n<pre>";
    h += &esc(classes);
    h += "</pre>\n<h2>Dimension</h2>\n<ul>";
    match (&m.similarity_dimension, &m.similarity_note) {
        (Some(s), _) => {
            let _ = write!(
                h,
                "<li>similarity dimension (exact) = {} = {}…{}</li><li>open-set condition: {}</li>",
                esc(&s.exact),
                s.decimal,
                if s.upper_bound {
                    " — an upper bound of the Hausdorff dimension only"
                } else {
                    " — the Hausdorff dimension"
                },
                esc(&s.open_set)
            );
        }
        (None, Some(n)) => {
            let _ = write!(
                h,
                "<li>similarity dimension: not applicable ({})</li>",
                esc(n)
            );
        }
        _ => {}
    }
    match m.box_dimension.value {
        Some(v) => {
            let _ = write!(
                h,
                "<li>box-counting dimension ≈ {v:.4} (level {}; boxes: {})</li>",
                m.box_dimension.level,
                m.box_dimension
                    .counts
                    .iter()
                    .map(|(k, n)| format!("2^-{k}: {n}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            );
        }
        None => h += "<li>box-counting dimension: too few scales</li>",
    }
    h += "</ul>\n";
    box_section(&mut h, m);
    curvature_section(&mut h, curves);
    h += "<h2>Levels</h2>\n<table><tr><th>level</th><th>pieces</th><th>length</th><th>area</th></tr>\n";
    for l in &m.levels {
        let _ = writeln!(
            h,
            "<tr><td>{}</td><td>{}</td><td>{:.6}</td><td>{:.6}</td></tr>",
            l.level, l.pieces, l.length, l.area
        );
    }
    h += "</table>\n<h2>Input</h2>\n<pre>";
    h += &esc(source);
    h += "</pre>\n</body></html>\n";
    h
}
