//! `lacuna report`: one self-contained HTML page with the verdicts and the pictures — the pictures
//! of levels 0–k with the legend of the types, the type graph, the counts table, R and how it was
//! decided, the solver's verdict, the measures with the raster and level of each, and the plots of
//! ln A and ln P against the level and of the box-counting fit (axes, ticks, the fitted line's
//! equation). Everything is computed elsewhere; this module only lays it out (inline SVG, no
//! script, no external file).

use crate::export::graph::type_graph;
use crate::export::palette::hex;
use crate::export::picture::{legend_entries, write_svg_picture, PictureOptions};
use crate::export::plot::{plot_svg, signed, Plot};
use crate::export::report::VerifyReport;
use crate::geometry::instantiate::Instance;
use crate::measure::measurement::{LevelMeasure, MeasureReport};
use std::fmt::Write as _;

/// Escapes text for HTML.
pub(crate) fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// The solver's verdict for a web page: the counts and the degeneracy check as text, and the
/// particular solution (every unknown operator's exact matrix) in a collapsed section.
fn solver_section(s: &crate::constraint::automaton::SolveReport, input: &str) -> String {
    let mut text = String::new();
    let mut skipping = false;
    for line in s.to_text(false).lines() {
        if line.starts_with("particular solution") {
            skipping = true;
            continue;
        }
        if skipping && line.starts_with("  ") {
            continue;
        }
        skipping = false;
        text += line;
        text.push('\n');
    }
    let mut h = format!("<pre>{}</pre>", esc(&text));
    if s.consistent && !s.particular.is_empty() {
        let _ = write!(
            h,
            "<details class=\"particular\"><summary>A particular solution: the exact matrices of the {} unknown operators ({} unknowns; <code>lacuna solve {} --json</code> prints them as JSON)</summary><div class=\"matrices\">",
            s.particular.len(),
            s.unknowns,
            esc(input)
        );
        for (name, m) in &s.particular {
            let _ = write!(h, "<div><code>{} = {}</code></div>", esc(name), esc(m));
        }
        h += "</div></details>";
    }
    h
}

/// The head of a face's page and its title.
fn page_head(v: &VerifyReport) -> String {
    page_start(&v.input)
}

/// The start of every report page — faces, volumes and automata share one layout: the head with
/// one style, the title `lacuna report: NAME` as the heading, then ([`verdict_line`]) the verdict,
/// then the pictures, then the details.
pub(crate) fn page_start(name: &str) -> String {
    format!(
        "<!DOCTYPE html><html lang=\"en\"><head><meta charset=\"utf-8\">\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\"><title>lacuna report: {0}</title>\
         <style>body{{font-family:sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;line-height:1.4}}\
         table{{border-collapse:collapse}}td,th{{border:1px solid #ccc;padding:2px 8px;text-align:right}}\
         .pics figure{{display:inline-block;margin:4px}}.pics figure>svg{{width:250px;height:250px;border:1px solid #eee}}\
         pre{{background:#f6f6f6;padding:8px;white-space:pre-wrap;overflow-wrap:anywhere}}\
         ul.legend{{list-style:none;padding:0;margin:4px 0 0 4px;columns:2 300px}}\
         ul.legend li{{margin:2px 0}}.swatch{{display:inline-block;width:12px;height:12px;border:1px solid #333;margin-right:6px;vertical-align:-1px}}\
         .plots svg{{margin:4px;border:1px solid #ddd}}\
         details.particular{{margin:8px 0}}details .matrices{{max-height:24em;overflow:auto;font-size:90%;background:#f6f6f6;padding:8px}}\
         .note{{color:#555;font-size:92%}}\
         .ok{{color:#063}}.bad{{color:#a00}}</style></head><body><h1>lacuna report: {0}</h1>",
        esc(name)
    )
}

/// The verdict line under a report's title: `Verdict: VERIFIED` (green) or the failure (red),
/// with what it covers.
pub(crate) fn verdict_line(ok: bool, verdict: &str, covers: &str) -> String {
    format!(
        "<p class=\"{}\"><b>Verdict: {}</b>{}</p>\n",
        if ok { "ok" } else { "bad" },
        esc(verdict),
        match covers {
            "" => String::new(),
            c => format!(" ({})", esc(c)),
        }
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
/// `segments` is the flattening of the measures (the pictures draw the curves themselves).
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
    let opts = PictureOptions {
        width: 250,
        legend: false,
        ..Default::default()
    };
    for level in 0..=pictures_up_to {
        let mut buf = Vec::new();
        if write_svg_picture(inst, level, &opts, &mut buf).is_ok() {
            let svg = String::from_utf8_lossy(&buf);
            let cells = m
                .levels
                .iter()
                .find(|l| l.level == level)
                .map(|l| match l.cells {
                    1 => ": 1 cell".to_string(),
                    n => format!(": {n} cells"),
                })
                .unwrap_or_default();
            let _ = write!(
                h,
                "<figure>{svg}<figcaption>level {level}{cells}</figcaption></figure>"
            );
        }
    }
    h += "<ul class=\"legend\">";
    for (id, colour, face) in legend_entries(inst) {
        let _ = write!(
            h,
            "<li class=\"legend-entry\"><span class=\"swatch\" style=\"background:{}\"></span><b>{}</b> {}</li>",
            hex(colour),
            esc(&id),
            esc(&face)
        );
    }
    h += "</ul></div><h2>Type graph</h2>";
    h += "<p class=\"note\">An arrow from a type to each type of its sub-faces, labelled ×k when it has k &gt; 1 sub-faces of that type (no label: one).</p>";
    h += &type_graph(v);
    h += "<h2>Face types</h2><table class=\"types\"><tr><th>type</th><th>face</th><th>sub-faces</th><th>contribution (exact)</th></tr>";
    for (k, t) in v.types.iter().enumerate() {
        let _ = write!(
            h,
            "<tr><td><span class=\"swatch\" style=\"background:{}\"></span>{}</td><td style=\"text-align:left\">{}</td><td>{}</td><td>{}</td></tr>",
            hex(crate::export::palette::type_colour(k)),
            esc(&t.id),
            esc(&t.face),
            t.children.len(),
            esc(&t.contribution)
        );
    }
    h += "</table><h2>Counts (exact)</h2><table><tr><th>level</th><th>faces N<sup>C</sup></th><th>lacunas N<sup>L</sup></th><th>R<sub>i</sub></th></tr>";
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
            "<h2>Limit ratio R (exact)</h2><pre>{}</pre>",
            esc(&crate::export::report::ratio_text(r))
        );
    }
    if let Some(s) = &v.solver {
        h += "<h2>Constraint solver (exact)</h2>";
        h += &solver_section(s, &v.input);
    }
    h += "<h2>Measures (floating point; holes and components compared with the exact counts)</h2>";
    let _ = write!(
        h,
        "<p class=\"note\">Area and perimeter from the cells' polygons (Bézier edges flattened to {segments} segments); holes and components counted on the raster of each level, given in pixels per side (a level's raster is fine enough for its smallest hole).</p>"
    );
    h += "<table><tr><th>level</th><th>cells</th><th>area A<sub>i</sub></th><th>perimeter P<sub>i</sub></th><th>raster</th><th>holes (exact)</th><th>components (exact)</th><th>match</th></tr>";
    for l in &m.levels {
        let _ = write!(
            h,
            "<tr><td>{}</td><td>{}</td><td>{:.6}</td><td>{:.6}</td><td>{}²</td><td>{} ({})</td><td>{} ({})</td><td class=\"{}\">{}</td></tr>",
            l.level,
            l.cells,
            l.area,
            l.perimeter,
            l.raster,
            l.holes,
            l.exact.holes,
            l.components,
            l.exact.components,
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
    let lnrel = |f: &dyn Fn(&LevelMeasure) -> f64| -> Vec<(f64, f64)> {
        let base = m.levels.first().map(f).unwrap_or(1.0);
        m.levels
            .iter()
            .map(|l| (f64::from(l.level), (f(l) / base).ln()))
            .collect()
    };
    let (kmin, kmax) = (
        m.box_counts.first().map_or(0, |c| c.0),
        m.box_counts.last().map_or(0, |c| c.0),
    );
    let levels = format!("levels 0–{}", m.level);
    let box_where = format!(
        "level {}, raster {}², boxes of side 2⁻ᵏ of the window, k = {kmin}…{kmax}",
        m.level, m.raster
    );
    let _ = write!(
        h,
        "<p>F<sub>A</sub> = {:.6}, F<sub>P</sub> = {:.6} (slopes of the fits over {levels}); box-counting dimension {:.4} (fit residual {:.4}; {box_where})</p><div class=\"plots\">{}{}{}</div>",
        m.area_factor,
        m.perimeter_factor,
        m.box_dimension,
        m.box_fit.residual,
        plot_svg(&Plot {
            title: "ln(Aᵢ/A₀) against the level i",
            subtitle: &format!("area of the cells, {levels}"),
            xlabel: "level i",
            ylabel: "ln(Aᵢ/A₀)",
            points: &lnrel(&|l| l.area),
            fit: Some((
                &m.area_fit,
                format!(
                    "ln(Aᵢ/A₀) ≈ {}·i {};  F_A = e^slope = {:.4}",
                    signed(m.area_fit.slope, 4),
                    signed_term(m.area_fit.intercept),
                    m.area_factor
                )
            )),
        }),
        plot_svg(&Plot {
            title: "ln(Pᵢ/P₀) against the level i",
            subtitle: &format!("perimeter of the union, {levels}"),
            xlabel: "level i",
            ylabel: "ln(Pᵢ/P₀)",
            points: &lnrel(&|l| l.perimeter),
            fit: Some((
                &m.perimeter_fit,
                format!(
                    "ln(Pᵢ/P₀) ≈ {}·i {};  F_P = e^slope = {:.4}",
                    signed(m.perimeter_fit.slope, 4),
                    signed_term(m.perimeter_fit.intercept),
                    m.perimeter_factor
                )
            )),
        }),
        plot_svg(&Plot {
            title: "box counting: ln N(ε) against ln(1/ε)",
            subtitle: &box_where,
            xlabel: "ln(1/ε)",
            ylabel: "ln N(ε)",
            points: &m
                .box_counts
                .iter()
                .map(|&(k, n)| (f64::from(k) * std::f64::consts::LN_2, (n as f64).ln()))
                .collect::<Vec<_>>(),
            fit: Some((
                &m.box_fit,
                format!(
                    "ln N ≈ {}·ln(1/ε) {};  dimension {:.4}",
                    signed(m.box_fit.slope, 4),
                    signed_term(m.box_fit.intercept),
                    m.box_dimension
                )
            )),
        })
    );
    for f in &m.failures {
        let _ = write!(h, "<p class=\"bad\">{}</p>", esc(f));
    }
    h += "</body></html>\n";
    h
}

/// `+ 0.1234` or `− 0.1234`.
fn signed_term(x: f64) -> String {
    if x < 0.0 {
        format!("− {:.4}", -x)
    } else {
        format!("+ {x:.4}")
    }
}
