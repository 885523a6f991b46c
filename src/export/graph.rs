//! The type graph of the HTML report: which type's cells contain which, and how many times.
//!
//! Up to [`MAX_DRAWN`] types it is drawn as SVG, layered by strongly connected class in the
//! order of the condensation (a class below every class that reaches it; classes of several
//! types, or of one type with a loop, in a dashed box), the types filled with their picture
//! colour, one arrow per (parent, child) pair. An arrow ends on the child's circle with its head
//! outside it, so direction is always visible; when two types point at each other, the two arrows
//! bend apart; arrows along a row bend around the nodes between; a self-loop sits on its node's
//! right. The multiplicity is written on the middle of its arrow as `×k`, on a white halo, when
//! k > 1 (an arrow without a label has multiplicity 1). Beyond [`MAX_DRAWN`] types, the
//! adjacency matrix with the multiplicities as numbers (a drawing would be unreadable).
//!
//! Classes for the browser tests: `node` (a type's circle, `r` its radius), `edge`, `loop`,
//! `arrowhead` (a triangle `M tip L base L base Z`), `multiplicity`.

use crate::export::palette::{hex, lightness, type_colour};
use crate::export::picture::xml_escape as esc;
use crate::export::report::VerifyReport;
use std::fmt::Write as _;

/// The most types drawn as a graph.
pub(crate) const MAX_DRAWN: usize = 20;

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

/// The classes of the graph as groups of types in layers: each class (strongly connected, from
/// the report's class structure; each type alone when there is none) goes one layer below the
/// lowest class that reaches it (longest path in the condensation), types reached by no class
/// last. Returns the layers, each a list of classes, each a list of types.
fn layers(v: &VerifyReport, pairs: &[(usize, usize, usize)]) -> Vec<Vec<Vec<usize>>> {
    let n = v.types.len();
    let mut groups: Vec<Vec<usize>> = match &v.classes {
        Some(cl) => cl.classes.iter().map(|c| c.members.clone()).collect(),
        None => Vec::new(),
    };
    let mut group_of = vec![usize::MAX; n];
    for (g, members) in groups.iter().enumerate() {
        for &t in members {
            if t < n {
                group_of[t] = g;
            }
        }
    }
    for (t, g) in group_of.iter_mut().enumerate() {
        if *g == usize::MAX {
            *g = groups.len();
            groups.push(vec![t]);
        }
    }
    // Longest path from the sources, relaxed until stable (the condensation is acyclic; at most
    // one round per group).
    let mut layer = vec![0usize; groups.len()];
    for _ in 0..groups.len() {
        let mut changed = false;
        for &(a, b, _) in pairs {
            let (ga, gb) = (group_of[a], group_of[b]);
            if ga != gb && layer[gb] < layer[ga] + 1 {
                layer[gb] = layer[ga] + 1;
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
    let depth = layer.iter().copied().max().unwrap_or(0) + 1;
    let mut out: Vec<Vec<Vec<usize>>> = vec![Vec::new(); depth];
    for (g, members) in groups.into_iter().enumerate() {
        out[layer[g]].push(members);
    }
    out.retain(|l| !l.is_empty());
    out
}

/// Types per row inside a class box.
const PER_ROW: usize = 6;
/// Horizontal and vertical distance between node centres, and the gap between class boxes.
const STEP: (f64, f64, f64) = (84.0, 124.0, 36.0);

/// The type graph as SVG (up to [`MAX_DRAWN`] types) or, beyond, as an adjacency matrix.
///
/// The drawing is layered by strongly connected class in the order of the condensation (a
/// class below every class that reaches it), each class in a dashed box named by its types;
/// arrows between classes run downwards, arrows inside a class bend, self-loops sit on their
/// node's right. Each arrowhead ends outside its child's circle, and arrows into one node come in along
/// their own curves, so heads do not pile up; a multiplicity above 1 is written on its arrow.
pub(crate) fn type_graph(v: &VerifyReport) -> String {
    let n = v.types.len();
    let pairs = edges(v);
    if n > MAX_DRAWN {
        return matrix(v, &pairs);
    }
    let layers = layers(v, &pairs);
    // Positions: each class a block of at most PER_ROW columns; classes of a layer side by side.
    let block = |members: &[usize]| {
        let cols = members.len().clamp(1, PER_ROW);
        let rows = members.len().div_ceil(PER_ROW).max(1);
        (cols as f64 * STEP.0, rows)
    };
    let layer_width = |l: &Vec<Vec<usize>>| {
        l.iter().map(|c| block(c).0).sum::<f64>() + STEP.2 * (l.len() as f64 - 1.0)
    };
    let width = layers.iter().map(layer_width).fold(0.0, f64::max) + 2.0 * STEP.2;
    let mut pos = vec![(0.0, 0.0); n];
    let mut boxes: Vec<(f64, f64, f64, f64, String)> = Vec::new();
    // Room above the first row for the class boxes.
    let mut y = NODE * 2.0 + 16.0;
    for l in &layers {
        let mut x = (width - layer_width(l)) / 2.0;
        let rows = l.iter().map(|c| block(c).1).max().unwrap_or(1);
        for c in l {
            let (w, r) = block(c);
            for (i, &t) in c.iter().enumerate() {
                let (row, col) = (i / PER_ROW, i % PER_ROW);
                pos[t] = (x + (col as f64 + 0.5) * STEP.0, y + row as f64 * STEP.1);
            }
            if c.len() > 1 || pairs.iter().any(|&(a, b, _)| a == c[0] && b == c[0]) {
                let names: Vec<String> = c.iter().map(|t| format!("T{t}")).collect();
                boxes.push((
                    x + 4.0,
                    y - NODE - 14.0,
                    w - 8.0,
                    (r as f64 - 1.0) * STEP.1 + 2.0 * NODE + 22.0,
                    names.join(" "),
                ));
            }
            x += w + STEP.2;
        }
        y += rows as f64 * STEP.1 + STEP.1 * 0.35;
    }
    let _ = y;
    // The vertical extent: every node and class box, and every curve (a quadratic Bézier strays
    // at most half-way to its control point).
    let mut top = pos.iter().map(|p| p.1 - NODE).fold(f64::MAX, f64::min);
    let mut bottom = pos.iter().map(|p| p.1 + NODE).fold(f64::MIN, f64::max);
    for (_, by, _, bh, _) in &boxes {
        top = top.min(*by);
        bottom = bottom.max(by + bh);
    }
    let mut s = String::new();
    for (x, y, w, h, name) in &boxes {
        let _ = write!(
            s,
            "<rect class=\"class-box\" x=\"{x:.1}\" y=\"{y:.1}\" width=\"{w:.1}\" height=\"{h:.1}\" rx=\"10\" fill=\"#f6f6f6\" stroke=\"#999\" stroke-dasharray=\"4 3\"><title>class {}</title></rect>",
            esc(name)
        );
    }
    let mut labels = String::new();
    for &(t, ch, k) in &pairs {
        let (a, b) = (pos[t], pos[ch]);
        if t == ch {
            // A loop on the node's right (arrows between layers come in from above and leave
            // below).
            let out: P = (1.0, 0.0);
            let ang = out.1.atan2(out.0);
            let spread = 0.45;
            let d0 = (f64::cos(ang - spread), f64::sin(ang - spread));
            let d1 = (f64::cos(ang + spread), f64::sin(ang + spread));
            let start = add(a, mul(d0, NODE));
            let tip = add(a, mul(d1, NODE + GAP));
            let c0 = add(a, mul(d0, NODE * 3.4));
            let c1 = add(a, mul(d1, NODE * 3.4));
            let dir = unit(sub(tip, c1));
            let (head, base) = arrowhead(tip, dir);
            let _ = write!(
                s,
                "<path class=\"loop\" d=\"M{:.1},{:.1} C{:.1},{:.1} {:.1},{:.1} {:.1},{:.1}\" fill=\"none\" stroke=\"#444\" stroke-width=\"1.3\"/>{head}",
                start.0, start.1, c0.0, c0.1, c1.0, c1.1, base.0, base.1
            );
            if k > 1 {
                labels += &label(add(a, mul(out, NODE * 3.4)), k);
            }
            continue;
        }
        let both = pairs.iter().any(|&(x, y, _)| x == ch && y == t);
        let d = sub(b, a);
        let len = d.0.hypot(d.1);
        let nrm = unit((-d.1, d.0));
        // Straight down between layers; bent when the two arrows of a pair would overlap, when
        // the arrow runs along a row (it would cross the nodes between), or when it rises.
        let along_row = d.1.abs() < 1.0;
        let bend = if along_row {
            0.22 * len + 12.0
        } else if both || d.1 < 0.0 {
            0.18 * len
        } else {
            0.0
        };
        let ctrl = add(add(a, mul(d, 0.5)), mul(nrm, bend));
        let mid = add(mul(add(a, b), 0.25), mul(ctrl, 0.5));
        top = top.min(mid.1 - 12.0);
        bottom = bottom.max(mid.1 + 12.0);
        let start = add(a, mul(unit(sub(ctrl, a)), NODE));
        let end_dir = unit(sub(b, ctrl));
        let tip = sub(b, mul(end_dir, NODE + GAP));
        let (head, base) = arrowhead(tip, end_dir);
        let _ = write!(
            s,
            "<path class=\"edge\" d=\"M{:.1},{:.1} Q{:.1},{:.1} {:.1},{:.1}\" fill=\"none\" stroke=\"#444\" stroke-width=\"1.3\"/>{head}",
            start.0, start.1, ctrl.0, ctrl.1, base.0, base.1
        );
        if k > 1 {
            // On the curve, at its middle.
            labels += &label(mid, k);
        }
    }
    s += &labels;
    for (t, row) in v.types.iter().enumerate() {
        let (x, y) = pos[t];
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
    let (y0, h) = (top - 12.0, bottom - top + 24.0);
    format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"type-graph\" width=\"{width:.0}\" height=\"{h:.0}\" viewBox=\"0 {y0:.0} {width:.0} {h:.0}\" font-family=\"sans-serif\" font-size=\"12\">{s}</svg>"
    )
}

/// Beyond [`MAX_DRAWN`] types: the adjacency matrix, a row per parent and a column per child,
/// each cell the multiplicity (empty for none).
fn matrix(v: &VerifyReport, pairs: &[(usize, usize, usize)]) -> String {
    let n = v.types.len();
    let mut s = String::from(
        "<p>Too many types to draw readably: the graph as its adjacency matrix (row: the parent type; column: the child type; the number of children of that type).</p><div style=\"overflow-x:auto\"><table class=\"type-graph\"><tr><th></th>",
    );
    for c in 0..n {
        let _ = write!(s, "<th>T{c}</th>");
    }
    s += "</tr>";
    for t in 0..n {
        let _ = write!(s, "<tr><th>T{t}</th>");
        for c in 0..n {
            match pairs.iter().find(|&&(a, b, _)| a == t && b == c) {
                Some(&(_, _, k)) => {
                    let _ = write!(s, "<td>{k}</td>");
                }
                None => s += "<td></td>",
            }
        }
        s += "</tr>";
    }
    s + "</table></div>"
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
    fn past_twenty_types_the_graph_is_an_adjacency_matrix_of_multiplicities() {
        // A ring of 21 types, each with two children of the next type: 21 pairs of multiplicity
        // 2, one non-empty cell per row, at column t + 1 (mod 21).
        let mut v = f0_report();
        let row = v.types[0].clone();
        let m = MAX_DRAWN + 1;
        v.types = (0..m)
            .map(|k| {
                let mut r = row.clone();
                r.id = format!("T{k}");
                r.children = vec![format!("T{}", (k + 1) % m); 2];
                r
            })
            .collect();
        v.classes = None;
        let pairs = edges(&v);
        assert_eq!(pairs.len(), m);
        assert!(pairs.iter().all(|&(t, c, k)| c == (t + 1) % m && k == 2));
        let html = type_graph(&v);
        assert!(!html.contains("<svg"));
        assert_eq!(html.matches("<tr>").count(), m + 1);
        assert_eq!(html.matches("<td>2</td>").count(), m);
        // Row T20: its only child is T0, the first column.
        let last = &html[html.find("<tr><th>T20</th>").unwrap()..];
        assert!(
            last.starts_with("<tr><th>T20</th><td>2</td><td></td>"),
            "{last}"
        );
    }

    #[test]
    fn classes_are_layered_in_the_condensation_order() {
        // delayed-B2-C2 (tests/fixtures.rs): X → 2 S4 + U, S4 → 4 G6, U → 2 G6 + 2 V7,
        // V7 → 6 G6 + V7, G6 → 6 G6. Five classes, each one type; longest paths from X: S4
        // and U one layer down, V7 two, G6 three.
        let input = crate::input::load_input("delayed-B2-C2").unwrap();
        let limits = Limits::default();
        let closure = Closure::of(&input.faces(), &limits).unwrap();
        let v = verify_report(&input, &closure, 2, &limits).unwrap();
        let pairs = edges(&v);
        let l = layers(&v, &pairs);
        let sizes: Vec<usize> = l.iter().map(|x| x.iter().map(Vec::len).sum()).collect();
        assert_eq!(sizes, [1, 2, 1, 1]);
        let svg = type_graph(&v);
        // Every node below the layers above it: the y of each node grows with its layer.
        let ys: Vec<f64> = svg
            .split("<circle class=\"node\" cx=\"")
            .skip(1)
            .map(|c| {
                let y = c.split("cy=\"").nth(1).unwrap();
                y[..y.find('"').unwrap()].parse().unwrap()
            })
            .collect();
        let layer_of = |t: usize| {
            l.iter()
                .position(|x| x.iter().any(|c| c.contains(&t)))
                .unwrap()
        };
        for a in 0..ys.len() {
            for b in 0..ys.len() {
                if layer_of(a) < layer_of(b) {
                    assert!(ys[a] < ys[b], "T{a} at {} above T{b} at {}", ys[a], ys[b]);
                }
            }
        }
        // Self-loops (V7 and G6) are boxed as classes.
        assert_eq!(svg.matches("class=\"class-box\"").count(), 2);
    }
}
