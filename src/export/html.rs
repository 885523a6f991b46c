//! `lacuna report`: one self-contained HTML page with the verdicts and the pictures — the pictures
//! of levels 0–k, the type graph, the counts table, R and how it was decided, the solver's verdict,
//! and the plots of ln A and ln P against the level and of the box-counting fit. Everything is
//! computed elsewhere; this module only lays it out (inline SVG, no script, no external file).

use crate::export::report::VerifyReport;
use crate::export::writer::write_svg;
use crate::geometry::instantiate::Instance;
use crate::geometry::point::Fit;
use crate::measure::measurement::MeasureReport;
use std::fmt::Write as _;

/// Escapes text for HTML.
fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// A small inline SVG scatter plot of `points` with the fitted line `fit` (if any).
fn plot(
    title: &str,
    xlabel: &str,
    ylabel: &str,
    points: &[(f64, f64)],
    fit: Option<&Fit>,
) -> String {
    let (w, h, m) = (360.0, 240.0, 40.0);
    let finite: Vec<(f64, f64)> = points
        .iter()
        .copied()
        .filter(|(x, y)| x.is_finite() && y.is_finite())
        .collect();
    if finite.is_empty() {
        return format!("<p>{}: no data</p>", esc(title));
    }
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for &(x, y) in &finite {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    if (x1 - x0).abs() < 1e-12 {
        x1 = x0 + 1.0;
    }
    if (y1 - y0).abs() < 1e-12 {
        y1 = y0 + 1.0;
    }
    let px = |x: f64| m + (x - x0) / (x1 - x0) * (w - 2.0 * m);
    let py = |y: f64| h - m - (y - y0) / (y1 - y0) * (h - 2.0 * m);
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" font-size=\"11\"><rect width=\"{w}\" height=\"{h}\" fill=\"white\" stroke=\"#ccc\"/>\
         <text x=\"{}\" y=\"14\" text-anchor=\"middle\">{}</text>\
         <text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>\
         <text x=\"12\" y=\"{}\" transform=\"rotate(-90 12 {})\" text-anchor=\"middle\">{}</text>",
        w / 2.0,
        esc(title),
        w / 2.0,
        h - 8.0,
        esc(xlabel),
        h / 2.0,
        h / 2.0,
        esc(ylabel)
    );
    let _ = write!(
        s,
        "<line x1=\"{m}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"#999\"/><line x1=\"{m}\" y1=\"{m}\" x2=\"{m}\" y2=\"{}\" stroke=\"#999\"/>",
        h - m,
        w - m,
        h - m,
        h - m
    );
    if let Some(f) = fit {
        let _ = write!(
            s,
            "<line x1=\"{:.1}\" y1=\"{:.1}\" x2=\"{:.1}\" y2=\"{:.1}\" stroke=\"#c33\" stroke-dasharray=\"4,3\"/>",
            px(x0),
            py(f.intercept + f.slope * x0),
            px(x1),
            py(f.intercept + f.slope * x1)
        );
    }
    for (x, y) in finite {
        let _ = write!(
            s,
            "<circle cx=\"{:.1}\" cy=\"{:.1}\" r=\"3\" fill=\"#236\"/>",
            px(x),
            py(y)
        );
    }
    s + "</svg>"
}

/// The type graph as an SVG: the types on a circle, an arrow per distinct (parent, child) pair
/// labelled with its multiplicity.
fn type_graph(v: &VerifyReport) -> String {
    let n = v.types.len();
    // The types on a circle whose radius grows with their number (a single type sits alone); the
    // picture is cropped to the nodes plus a margin for self-loops and labels.
    let r = if n <= 1 {
        0.0
    } else {
        (24.0 * n as f64 / std::f64::consts::PI).clamp(60.0, 260.0)
    };
    let margin = 48.0;
    let (cx, cy) = (r + margin, r + margin);
    let (w, h) = (2.0 * (r + margin), 2.0 * (r + margin));
    let pos = |k: usize| {
        let a = std::f64::consts::TAU * k as f64 / n.max(1) as f64 - std::f64::consts::FRAC_PI_2;
        (cx + r * a.cos(), cy + r * a.sin())
    };
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w:.0}\" height=\"{h:.0}\" font-size=\"11\">\
         <defs><marker id=\"arrow\" viewBox=\"0 0 10 10\" refX=\"16\" refY=\"5\" markerWidth=\"6\" markerHeight=\"6\" orient=\"auto\"><path d=\"M0,0 L10,5 L0,10 z\" fill=\"#555\"/></marker></defs>"
    );
    for (t, row) in v.types.iter().enumerate() {
        let mut seen: Vec<(usize, usize)> = Vec::new();
        for c in &row.children {
            let c: usize = c.trim_start_matches('T').parse().unwrap_or(0);
            match seen.iter_mut().find(|(x, _)| *x == c) {
                Some(e) => e.1 += 1,
                None => seen.push((c, 1)),
            }
        }
        for (c, k) in seen {
            let ((x0, y0), (x1, y1)) = (pos(t), pos(c));
            if c == t {
                let _ = write!(
                    s,
                    "<circle cx=\"{:.1}\" cy=\"{:.1}\" r=\"18\" fill=\"none\" stroke=\"#555\"/><text x=\"{:.1}\" y=\"{:.1}\">{k}</text>",
                    x0,
                    y0 - 18.0,
                    x0 + 14.0,
                    y0 - 32.0
                );
            } else {
                let _ = write!(
                    s,
                    "<line x1=\"{x0:.1}\" y1=\"{y0:.1}\" x2=\"{x1:.1}\" y2=\"{y1:.1}\" stroke=\"#555\" marker-end=\"url(#arrow)\"/><text x=\"{:.1}\" y=\"{:.1}\">{k}</text>",
                    (x0 + 2.0 * x1) / 3.0,
                    (y0 + 2.0 * y1) / 3.0
                );
            }
        }
    }
    for (t, row) in v.types.iter().enumerate() {
        let (x, y) = pos(t);
        let _ = write!(
            s,
            "<circle cx=\"{x:.1}\" cy=\"{y:.1}\" r=\"12\" fill=\"#def\" stroke=\"#236\"><title>{}</title></circle><text x=\"{x:.1}\" y=\"{:.1}\" text-anchor=\"middle\">{}</text>",
            esc(&row.face),
            y + 4.0,
            esc(&row.id)
        );
    }
    s + "</svg>"
}

/// The head of the page and its title.
fn page_head(v: &VerifyReport) -> String {
    format!(
        "<!DOCTYPE html><html lang=\"en\"><head><meta charset=\"utf-8\"><title>lacuna report: {0}</title>\
         <style>body{{font-family:sans-serif;max-width:1100px;margin:2em auto;line-height:1.4}}\
         table{{border-collapse:collapse}}td,th{{border:1px solid #ccc;padding:2px 8px;text-align:right}}\
         .pics svg{{width:250px;height:250px;border:1px solid #eee;margin:4px}}pre{{background:#f6f6f6;padding:8px;overflow-x:auto}}\
         .ok{{color:#063}}.bad{{color:#a00}}</style></head><body><h1>lacuna report: {0}</h1>",
        esc(&v.input)
    )
}

/// The page of an input whose closure did not close: the verdict and the verification report
/// with its runaway witness, and no geometry (there is no finite automaton to instantiate).
pub fn report_html_unverified(v: &VerifyReport) -> String {
    let mut h = page_head(v);
    let _ = writeln!(
        h,
        "<p class=\"bad\"><b>Verdict: NOT VERIFIED</b> (the closure did not close: nothing to draw or measure)</p><h2>Verification</h2><pre>{}</pre></body></html>",
        esc(&v.to_text())
    );
    h
}

/// The HTML page. `pictures_up_to` is the deepest level drawn (pictures of levels 0..=it).
pub fn report_html(
    v: &VerifyReport,
    inst: &Instance,
    m: &MeasureReport,
    pictures_up_to: u32,
    segments: usize,
) -> String {
    let mut h = page_head(v);
    let verdict = if v.verified && m.verified {
        ("ok", "VERIFIED")
    } else {
        ("bad", "NOT VERIFIED")
    };
    let _ = write!(
        h,
        "<p class=\"{}\"><b>Verdict: {}</b></p>",
        verdict.0, verdict.1
    );
    h += "<h2>Pictures</h2><div class=\"pics\">";
    for level in 0..=pictures_up_to {
        let mut buf = Vec::new();
        if write_svg(inst, level, segments, &mut buf).is_ok() {
            let svg = String::from_utf8_lossy(&buf);
            let body = svg.split_once("?>").map_or(svg.as_ref(), |(_, b)| b);
            let _ = write!(h, "<figure style=\"display:inline-block\">{body}<figcaption>level {level}</figcaption></figure>");
        }
    }
    h += "</div><h2>Type graph</h2>";
    h += &type_graph(v);
    h += "<h2>Face types</h2><table><tr><th>type</th><th>face</th><th>sub-faces</th><th>contribution</th></tr>";
    for t in &v.types {
        let _ = write!(
            h,
            "<tr><td>{}</td><td style=\"text-align:left\">{}</td><td>{}</td><td>{}</td></tr>",
            esc(&t.id),
            esc(&t.face),
            t.children.len(),
            esc(&t.contribution)
        );
    }
    h += "</table><h2>Counts</h2><table><tr><th>level</th><th>faces N<sup>C</sup></th><th>lacunas N<sup>L</sup></th><th>R<sub>i</sub></th></tr>";
    for l in &v.counts {
        let _ = write!(
            h,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
            l.level, l.faces, l.lacunas, l.ratio
        );
    }
    h += "</table>";
    if let Some(r) = &v.ratio {
        let _ = write!(
            h,
            "<h2>Limit ratio R</h2><pre>{}</pre>",
            esc(&crate::export::report::ratio_text(r))
        );
    }
    if let Some(s) = &v.solver {
        let _ = write!(
            h,
            "<h2>Constraint solver</h2><pre>{}</pre>",
            esc(&s.to_text(false))
        );
    }
    h += "<h2>Measures (floating point; holes and components compared with the exact counts)</h2>";
    h += "<table><tr><th>level</th><th>cells</th><th>area</th><th>perimeter</th><th>holes (exact)</th><th>components</th><th>match</th></tr>";
    for l in &m.levels {
        let _ = write!(
            h,
            "<tr><td>{}</td><td>{}</td><td>{:.6}</td><td>{:.6}</td><td>{} ({})</td><td>{}</td><td class=\"{}\">{}</td></tr>",
            l.level,
            l.cells,
            l.area,
            l.perimeter,
            l.holes,
            l.exact.holes,
            l.components,
            if l.matches { "ok" } else { "bad" },
            if l.matches { "yes" } else { "NO" }
        );
    }
    h += "</table>";
    let rasters: Vec<String> = m.levels.iter().map(|l| l.raster.to_string()).collect();
    let _ = write!(
        h,
        "<p>Rasters (pixels per side), levels 0–{}: {}; box counting with boxes 1/16 to 1/{}.</p>",
        m.level,
        rasters.join(", "),
        m.raster
    );
    let lnrel = |f: &dyn Fn(&crate::measure::measurement::LevelMeasure) -> f64| -> Vec<(f64, f64)> {
        let base = m.levels.first().map(f).unwrap_or(1.0);
        m.levels
            .iter()
            .map(|l| (f64::from(l.level), (f(l) / base).ln()))
            .collect()
    };
    let _ = write!(
        h,
        "<p>F<sub>A</sub> = {:.6}, F<sub>P</sub> = {:.6}, box-counting dimension {:.4} (fit residual {:.4})</p><div>{}{}{}</div>",
        m.area_factor,
        m.perimeter_factor,
        m.box_dimension,
        m.box_fit.residual,
        plot("ln(A_i / A_0)", "level i", "ln A", &lnrel(&|l| l.area), Some(&m.area_fit)),
        plot("ln(P_i / P_0)", "level i", "ln P", &lnrel(&|l| l.perimeter), Some(&m.perimeter_fit)),
        plot(
            "box counting",
            "ln(1/ε)",
            "ln N",
            &m.box_counts
                .iter()
                .map(|&(k, n)| (f64::from(k) * std::f64::consts::LN_2, (n as f64).ln()))
                .collect::<Vec<_>>(),
            Some(&m.box_fit)
        )
    );
    for f in &m.failures {
        let _ = write!(h, "<p class=\"bad\">{}</p>", esc(f));
    }
    h += "</body></html>\n";
    h
}
