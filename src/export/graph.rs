//! The type graph of the HTML report: which type's cells contain which, and how many times.
//!
//! Up to [`MAX_DRAWN`] types it is drawn as SVG: the types on a circle (filled with their picture
//! colour), one arrow per (parent, child) pair. An arrow ends on the child's circle with its head
//! outside it, so direction is always visible; when two types point at each other, the two arrows
//! bend apart; a self-loop leaves the node away from the centre. The multiplicity is written beside
//! the middle of its arrow as `×k`, on a white halo, when k > 1 (an arrow without a label has
//! multiplicity 1, which keeps graphs of many types legible). Beyond [`MAX_DRAWN`] types, a table (a drawing
//! would be unreadable).
//!
//! Classes for the browser tests: `node` (a type's circle, `r` its radius), `edge`, `loop`,
//! `arrowhead` (a triangle `M tip L base L base Z`), `multiplicity`.

use crate::export::palette::{hex, lightness, type_colour};
use crate::export::picture::xml_escape as esc;
use crate::export::report::VerifyReport;
use std::f64::consts::{FRAC_PI_2, TAU};
use std::fmt::Write as _;

/// The most types drawn as a graph.
pub(crate) const MAX_DRAWN: usize = 30;

/// Node radius in pixels.
const NODE: f64 = 15.0;
/// Arrowhead length and half width.
const HEAD: (f64, f64) = (10.0, 4.5);
/// Gap between an arrow's tip and the node's circle.
const GAP: f64 = 2.0;

/// (parent, child, multiplicity) for every distinct pair, in order.
pub(crate) fn edges(v: &VerifyReport) -> Vec<(usize, usize, usize)> {
    let mut out = Vec::new();
    for (t, row) in v.types.iter().enumerate() {
        let mut seen: Vec<(usize, usize)> = Vec::new();
        for c in &row.children {
            let c: usize = c.trim_start_matches('T').parse().unwrap_or(0);
            match seen.iter_mut().find(|(x, _)| *x == c) {
                Some(e) => e.1 += 1,
                None => seen.push((c, 1)),
            }
        }
        out.extend(seen.into_iter().map(|(c, k)| (t, c, k)));
    }
    out
}

type P = (f64, f64);

fn add(a: P, b: P) -> P {
    (a.0 + b.0, a.1 + b.1)
}
fn sub(a: P, b: P) -> P {
    (a.0 - b.0, a.1 - b.1)
}
fn mul(a: P, k: f64) -> P {
    (a.0 * k, a.1 * k)
}
fn unit(a: P) -> P {
    let l = a.0.hypot(a.1).max(1e-12);
    (a.0 / l, a.1 / l)
}

/// The arrowhead with its tip at `tip`, pointing along the unit vector `dir`; returns the path
/// and the middle of its base (where the arrow's line stops).
fn arrowhead(tip: P, dir: P) -> (String, P) {
    let base = sub(tip, mul(dir, HEAD.0));
    let n = (-dir.1, dir.0);
    let (a, b) = (add(base, mul(n, HEAD.1)), sub(base, mul(n, HEAD.1)));
    (
        format!(
            "<path class=\"arrowhead\" d=\"M{:.1},{:.1} L{:.1},{:.1} L{:.1},{:.1} Z\" fill=\"#444\"/>",
            tip.0, tip.1, a.0, a.1, b.0, b.1
        ),
        base,
    )
}

fn label(at: P, k: usize) -> String {
    format!(
        "<text class=\"multiplicity\" x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"middle\" dominant-baseline=\"central\" stroke=\"white\" stroke-width=\"3\" paint-order=\"stroke\" fill=\"#222\">×{k}</text>",
        at.0, at.1
    )
}

/// The type graph as SVG (up to [`MAX_DRAWN`] types) or as an HTML table.
pub(crate) fn type_graph(v: &VerifyReport) -> String {
    let n = v.types.len();
    let pairs = edges(v);
    if n > MAX_DRAWN {
        let mut s = String::from(
            "<p>Too many types to draw readably: the graph as a table (parent → children with their multiplicities).</p><table class=\"type-graph\"><tr><th>type</th><th>children</th></tr>",
        );
        for t in 0..n {
            let kids: Vec<String> = pairs
                .iter()
                .filter(|e| e.0 == t)
                .map(|&(_, c, k)| format!("T{c} ×{k}"))
                .collect();
            let _ = write!(
                s,
                "<tr><td>T{t}</td><td style=\"text-align:left\">{}</td></tr>",
                kids.join(", ")
            );
        }
        return s + "</table>";
    }
    // Nodes on a circle whose circumference gives every node about 100 px (at most 440 px of
    // radius, which the page's width holds); a single type alone.
    let r = if n <= 1 {
        0.0
    } else {
        (100.0 * n as f64 / TAU).clamp(70.0, 440.0)
    };
    // Room for the self-loops and their labels around the nodes (a lone node needs less).
    let margin = if n <= 1 { NODE + 42.0 } else { NODE + 62.0 };
    let c = (r + margin, r + margin);
    let size = 2.0 * (r + margin);
    let pos = |k: usize| {
        let a = TAU * k as f64 / n.max(1) as f64 - FRAC_PI_2;
        (c.0 + r * a.cos(), c.1 + r * a.sin())
    };
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"type-graph\" width=\"{size:.0}\" height=\"{size:.0}\" viewBox=\"0 0 {size:.0} {size:.0}\" font-family=\"sans-serif\" font-size=\"12\">"
    );
    let mut labels = String::new();
    for &(t, ch, k) in &pairs {
        let (a, b) = (pos(t), pos(ch));
        if t == ch {
            // Outward direction (straight up for a lone node).
            let out = if n <= 1 { (0.0, -1.0) } else { unit(sub(a, c)) };
            let ang = out.1.atan2(out.0);
            let spread = 0.45;
            let d0 = (f64::cos(ang - spread), f64::sin(ang - spread));
            let d1 = (f64::cos(ang + spread), f64::sin(ang + spread));
            let start = add(a, mul(d0, NODE));
            let tip = add(a, mul(d1, NODE + GAP));
            let c0 = add(a, mul(d0, NODE * 3.6));
            let c1 = add(a, mul(d1, NODE * 3.6));
            // The tangent at the end of the cubic is (tip − c1).
            let dir = unit(sub(tip, c1));
            let (head, base) = arrowhead(tip, dir);
            let _ = write!(
                s,
                "<path class=\"loop\" d=\"M{:.1},{:.1} C{:.1},{:.1} {:.1},{:.1} {:.1},{:.1}\" fill=\"none\" stroke=\"#444\" stroke-width=\"1.3\"/>{head}",
                start.0, start.1, c0.0, c0.1, c1.0, c1.1, base.0, base.1
            );
            if k > 1 {
                labels += &label(add(a, mul(out, NODE * 3.6)), k);
            }
        } else {
            let both = pairs.iter().any(|&(x, y, _)| x == ch && y == t);
            let d = sub(b, a);
            let len = d.0.hypot(d.1);
            let nrm = unit((-d.1, d.0));
            // Bend to the right of the direction when the reverse arrow exists.
            let bend = if both { 0.16 * len } else { 0.0 };
            let ctrl = add(add(a, mul(d, 0.5)), mul(nrm, bend));
            let start = add(a, mul(unit(sub(ctrl, a)), NODE));
            let end_dir = unit(sub(b, ctrl));
            let tip = sub(b, mul(end_dir, NODE + GAP));
            let (head, base) = arrowhead(tip, end_dir);
            let _ = write!(
                s,
                "<path class=\"edge\" d=\"M{:.1},{:.1} Q{:.1},{:.1} {:.1},{:.1}\" fill=\"none\" stroke=\"#444\" stroke-width=\"1.3\"/>{head}",
                start.0, start.1, ctrl.0, ctrl.1, base.0, base.1
            );
            // The middle of the curve, pushed a little to its side.
            let mid = add(mul(add(a, b), 0.25), mul(ctrl, 0.5));
            if k > 1 {
                labels += &label(add(mid, mul(nrm, if both { 9.0 } else { 0.0 })), k);
            }
        }
    }
    s += &labels;
    for (t, row) in v.types.iter().enumerate() {
        let (x, y) = pos(t);
        let fill = type_colour(t);
        let text = if lightness(fill) < 55.0 {
            "#fff"
        } else {
            "#000"
        };
        let _ = write!(
            s,
            "<circle class=\"node\" cx=\"{x:.1}\" cy=\"{y:.1}\" r=\"{NODE}\" fill=\"{}\" stroke=\"#222\"><title>{} {}</title></circle><text x=\"{x:.1}\" y=\"{y:.1}\" text-anchor=\"middle\" dominant-baseline=\"central\" fill=\"{text}\" font-weight=\"bold\">{}</text>",
            hex(fill),
            esc(&row.id),
            esc(&row.face),
            esc(&row.id)
        );
    }
    s + "</svg>"
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::export::report::verify_report;
    use crate::topology::{Closure, Limits};

    fn f0_report() -> VerifyReport {
        let input = crate::input::load_input("F0").unwrap();
        let limits = Limits::default();
        let closure = Closure::of(&input.faces(), &limits).unwrap();
        verify_report(&input, &closure, 3, &limits).unwrap()
    }

    #[test]
    fn one_type_has_a_self_loop_with_its_multiplicity_and_the_head_outside_the_node() {
        let svg = type_graph(&f0_report());
        assert_eq!(svg.matches("class=\"node\"").count(), 1);
        assert_eq!(svg.matches("class=\"loop\"").count(), 1);
        assert_eq!(svg.matches("class=\"arrowhead\"").count(), 1);
        assert!(svg.contains(">×6</text>"), "{svg}");
    }

    #[test]
    fn past_thirty_types_the_graph_is_a_table_and_multiplicities_are_counted() {
        let mut v = f0_report();
        let row = v.types[0].clone();
        v.types = (0..=MAX_DRAWN)
            .map(|k| {
                let mut r = row.clone();
                r.id = format!("T{k}");
                r.children = vec![format!("T{}", (k + 1) % (MAX_DRAWN + 1)); 2];
                r
            })
            .collect();
        let pairs = edges(&v);
        assert_eq!(pairs.len(), MAX_DRAWN + 1);
        assert!(pairs
            .iter()
            .all(|&(t, c, k)| c == (t + 1) % (MAX_DRAWN + 1) && k == 2));
        let html = type_graph(&v);
        assert!(!html.contains("<svg"));
        assert_eq!(html.matches("<tr>").count(), MAX_DRAWN + 2);
        assert!(html.contains("<td>T30</td><td style=\"text-align:left\">T0 ×2</td>"));
    }
}
