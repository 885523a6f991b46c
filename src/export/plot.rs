//! Scatter plots for the HTML report, written as SVG: axes with ticks at round numbers (1, 2 or 5
//! times a power of ten) and their labels, light grid lines, axis labels, the points, the fitted
//! line and its equation. Text is Unicode (subscripts, ε, the minus sign).
//!
//! Classes for the browser tests: `axis x`, `axis y` (the axis groups), `tick` (a tick label),
//! `fit` (the fitted line), `equation`, `point`.

use crate::export::picture::xml_escape as esc;
use crate::geometry::point::Fit;
use std::fmt::Write as _;

/// A plot to draw.
pub(crate) struct Plot<'a> {
    /// The title (first line).
    pub title: &'a str,
    /// Under the title: what was measured where (level, raster).
    pub subtitle: &'a str,
    /// The label of the x axis.
    pub xlabel: &'a str,
    /// The label of the y axis.
    pub ylabel: &'a str,
    /// The points.
    pub points: &'a [(f64, f64)],
    /// The fitted line and its equation as text.
    pub fit: Option<(&'a Fit, String)>,
}

/// Round tick positions covering [lo, hi]: about `target` steps of 1, 2 or 5 times a power of ten;
/// returns the step and the ticks (the first at or below `lo`, the last at or above `hi`).
pub(crate) fn ticks(lo: f64, hi: f64, target: usize) -> (f64, Vec<f64>) {
    let (lo, hi) = if hi - lo < 1e-12 {
        (lo - 0.5, hi + 0.5)
    } else {
        (lo, hi)
    };
    let raw = (hi - lo) / target.max(1) as f64;
    let mag = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .find(|s| *s >= raw * 0.999)
        .unwrap_or(10.0 * mag);
    let first = (lo / step).floor() as i64;
    let last = (hi / step).ceil() as i64;
    let t = (first..=last).map(|k| k as f64 * step).collect();
    (step, t)
}

/// A number for a tick label: as many decimals as the step needs, and a true minus sign.
pub(crate) fn tick_label(x: f64, step: f64) -> String {
    let decimals = (-(step.log10().floor())).max(0.0) as usize;
    let s = format!("{:.*}", decimals, x);
    let s = if s
        .trim_start_matches('-')
        .chars()
        .all(|c| c == '0' || c == '.')
    {
        s.trim_start_matches('-').to_string()
    } else {
        s
    };
    s.replace('-', "−")
}

/// A signed number with a true minus sign.
pub(crate) fn signed(x: f64, decimals: usize) -> String {
    format!("{:.*}", decimals, x).replace('-', "−")
}

/// The SVG of a plot (420 × 300 pixels).
pub(crate) fn plot_svg(p: &Plot) -> String {
    let (w, h) = (420.0, 300.0);
    let (left, right, top, bottom) = (62.0, 18.0, 58.0, 46.0);
    let finite: Vec<(f64, f64)> = p
        .points
        .iter()
        .copied()
        .filter(|(x, y)| x.is_finite() && y.is_finite())
        .collect();
    if finite.is_empty() {
        return format!("<p>{}: no data</p>", esc(p.title));
    }
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for &(x, y) in &finite {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    let (xs, xt) = ticks(x0, x1, 6);
    let (ys, yt) = ticks(y0, y1, 5);
    let (ax0, ax1) = (xt[0], xt[xt.len() - 1]);
    let (ay0, ay1) = (yt[0], yt[yt.len() - 1]);
    let px = |x: f64| left + (x - ax0) / (ax1 - ax0) * (w - left - right);
    let py = |y: f64| h - bottom - (y - ay0) / (ay1 - ay0) * (h - top - bottom);
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"plot\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\" font-family=\"sans-serif\" font-size=\"12\">\
         <rect width=\"{w}\" height=\"{h}\" fill=\"white\"/>\
         <text x=\"{}\" y=\"17\" text-anchor=\"middle\" font-weight=\"bold\" font-size=\"13\">{}</text>\
         <text x=\"{}\" y=\"33\" text-anchor=\"middle\" fill=\"#555\" font-size=\"11\">{}</text>",
        w / 2.0,
        esc(p.title),
        w / 2.0,
        esc(p.subtitle),
    );
    // Grid, axes, ticks and their labels.
    let _ = write!(s, "<g class=\"axis x\">");
    for &x in &xt {
        let xp = px(x);
        let _ = write!(
            s,
            "<line x1=\"{xp:.1}\" y1=\"{top}\" x2=\"{xp:.1}\" y2=\"{}\" stroke=\"#eee\"/>\
             <line x1=\"{xp:.1}\" y1=\"{}\" x2=\"{xp:.1}\" y2=\"{}\" stroke=\"#333\"/>\
             <text class=\"tick\" x=\"{xp:.1}\" y=\"{}\" text-anchor=\"middle\">{}</text>",
            h - bottom,
            h - bottom,
            h - bottom + 5.0,
            h - bottom + 18.0,
            tick_label(x, xs)
        );
    }
    let _ = write!(
        s,
        "<line x1=\"{left}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"#333\"/>\
         <text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text></g>",
        h - bottom,
        w - right,
        h - bottom,
        (left + w - right) / 2.0,
        h - 8.0,
        esc(p.xlabel)
    );
    let _ = write!(s, "<g class=\"axis y\">");
    for &y in &yt {
        let yp = py(y);
        let _ = write!(
            s,
            "<line x1=\"{left}\" y1=\"{yp:.1}\" x2=\"{}\" y2=\"{yp:.1}\" stroke=\"#eee\"/>\
             <line x1=\"{}\" y1=\"{yp:.1}\" x2=\"{left}\" y2=\"{yp:.1}\" stroke=\"#333\"/>\
             <text class=\"tick\" x=\"{}\" y=\"{:.1}\" text-anchor=\"end\">{}</text>",
            w - right,
            left - 5.0,
            left - 8.0,
            yp + 4.0,
            tick_label(y, ys)
        );
    }
    let mid = (top + h - bottom) / 2.0;
    let _ = write!(
        s,
        "<line x1=\"{left}\" y1=\"{top}\" x2=\"{left}\" y2=\"{}\" stroke=\"#333\"/>\
         <text x=\"14\" y=\"{mid}\" transform=\"rotate(-90 14 {mid})\" text-anchor=\"middle\">{}</text></g>",
        h - bottom,
        esc(p.ylabel)
    );
    if let Some((f, eq)) = &p.fit {
        let _ = write!(
            s,
            "<line class=\"fit\" x1=\"{:.1}\" y1=\"{:.1}\" x2=\"{:.1}\" y2=\"{:.1}\" stroke=\"#c33\" stroke-width=\"1.5\" stroke-dasharray=\"5,3\"/>\
             <text class=\"equation\" x=\"{}\" y=\"{}\" fill=\"#b22\" font-size=\"11.5\">{}</text>",
            px(x0),
            py(f.intercept + f.slope * x0),
            px(x1),
            py(f.intercept + f.slope * x1),
            left + 6.0,
            top - 10.0,
            esc(eq)
        );
    }
    for (x, y) in finite {
        let _ = write!(
            s,
            "<circle class=\"point\" cx=\"{:.1}\" cy=\"{:.1}\" r=\"3.5\" fill=\"#236\"/>",
            px(x),
            py(y)
        );
    }
    s + "</svg>"
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_are_round_and_cover_the_range() {
        let (step, t) = ticks(0.0, 3.0, 6);
        assert_eq!(step, 0.5);
        assert_eq!(t.first(), Some(&0.0));
        assert_eq!(t.last(), Some(&3.0));
        let (step, t) = ticks(-0.83, -0.01, 5);
        assert_eq!(step, 0.2);
        assert!(t[0] <= -0.83 && *t.last().unwrap() >= -0.01);
        assert_eq!(tick_label(-0.4, 0.2), "−0.4");
        assert_eq!(tick_label(-0.0, 0.2), "0.0");
        assert_eq!(tick_label(2.0, 1.0), "2");
    }
}
