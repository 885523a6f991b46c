//! The animated SVG of a morph (THEORY §13): every frame's cells in one picture with a common
//! window, shown one after the other by SMIL `<animate>` of `visibility` (discrete key times,
//! repeated for ever), which browsers play. A viewer without animation shows frame 0. Each frame
//! carries its label (t and its verdict); a frame that failed is outlined in red with the reason.

use crate::error::Error;
use crate::export::palette::{hex, outline_colour, type_colour};
use crate::export::picture::xml_escape;
use crate::geometry::{Evaluator, GeometryError, Instance, InstantiateOptions, Point, ShapeKind};
use crate::input::{AutomatonModel, Input};
use crate::measure::{MeasureOptions, MorphFrame, MorphReport};
use crate::topology::Limits;
use std::io::{self, Write};

/// The cells of one frame: face type (or automaton state), points in the plane, and whether the
/// points close a polygon (filled) or form an open polyline (stroked only).
pub type FrameCells = Vec<(usize, Vec<Point>, bool)>;

/// Writes the animated SVG of `frames` (cells and verdict per frame), `width` pixels wide,
/// `seconds` per frame.
pub fn write_morph_svg<W: Write>(
    name: &str,
    frames: &[(FrameCells, MorphFrame)],
    width: u32,
    seconds: f64,
    mut out: W,
) -> io::Result<()> {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for (cells, _) in frames {
        for (_, poly, _) in cells {
            for p in poly {
                for i in 0..2 {
                    lo[i] = lo[i].min(p[i]);
                    hi[i] = hi[i].max(p[i]);
                }
            }
        }
    }
    if !lo[0].is_finite() {
        (lo, hi) = ([0.0, 0.0], [1.0, 1.0]);
    }
    let span = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(1e-9);
    let margin = span * 0.04;
    let scale = f64::from(width) / (span + 2.0 * margin);
    let height = ((hi[1] - lo[1] + 2.0 * margin) * scale).ceil() as u32 + 28;
    let px = |p: &Point| {
        (
            (p[0] - lo[0] + margin) * scale,
            (hi[1] - p[1] + margin) * scale,
        )
    };
    let n = frames.len().max(1);
    let total = seconds * n as f64;
    writeln!(
        out,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 {width} {height}\" width=\"{width}\" height=\"{height}\">"
    )?;
    writeln!(
        out,
        "<title>{} morph, {n} frames</title>\n<rect width=\"{width}\" height=\"{height}\" fill=\"#fff\"/>",
        xml_escape(name)
    )?;
    for (k, (cells, frame)) in frames.iter().enumerate() {
        let (values, times) = key_times(k, n);
        writeln!(
            out,
            "<g class=\"frame\" id=\"frame-{k}\" visibility=\"{}\">",
            if k == 0 { "visible" } else { "hidden" }
        )?;
        writeln!(
            out,
            "<animate attributeName=\"visibility\" values=\"{values}\" keyTimes=\"{times}\" calcMode=\"discrete\" dur=\"{total}s\" repeatCount=\"indefinite\"/>"
        )?;
        for (ty, poly, closed) in cells {
            // A point (an automaton's `point` primitive) is a dot: a path of one point draws
            // nothing.
            if let [p] = poly.as_slice() {
                let (x, y) = px(p);
                let colour = match frame.verified {
                    true => hex(outline_colour(*ty)),
                    false => "#d00".to_string(),
                };
                writeln!(
                    out,
                    "<circle cx=\"{x:.2}\" cy=\"{y:.2}\" r=\"1.6\" fill=\"{colour}\"/>"
                )?;
                continue;
            }
            let mut d = String::new();
            for (i, p) in poly.iter().enumerate() {
                let (x, y) = px(p);
                d.push_str(&format!("{}{x:.2} {y:.2}", if i == 0 { "M" } else { " L" }));
            }
            let stroke = if frame.verified {
                hex(outline_colour(*ty))
            } else {
                "#d00".to_string()
            };
            let fill = if *closed {
                d.push_str(" Z");
                hex(type_colour(*ty))
            } else {
                "none".to_string()
            };
            writeln!(
                out,
                "<path d=\"{d}\" fill=\"{fill}\" stroke=\"{stroke}\" stroke-width=\"{}\" stroke-linejoin=\"round\"/>",
                if *closed { 0.8 } else { 1.5 }
            )?;
        }
        let mut label = if frame.verified {
            format!("frame {k}, t = {}: verified", frame.t)
        } else {
            format!(
                "frame {k}, t = {}: FAILED — {}",
                frame.t,
                frame.failures.first().map_or("", String::as_str)
            )
        };
        // About 7 pixels a character at 13 pixels: cut what would not fit.
        let fit = (width.saturating_sub(16) / 7).max(8) as usize;
        if label.chars().count() > fit {
            label = label.chars().take(fit - 1).collect::<String>() + "…";
        }
        writeln!(
            out,
            "<text x=\"8\" y=\"{}\" font-family=\"sans-serif\" font-size=\"13\" fill=\"{}\">{}</text>\n</g>",
            height - 9,
            if frame.verified { "#222" } else { "#d00" },
            xml_escape(&label)
        )?;
    }
    writeln!(out, "</svg>")
}

/// Every frame of a morph: its cells and its verdict, as [`write_morph_svg`] draws them.
pub type MorphFrames = Vec<(FrameCells, MorphFrame)>;

/// The morph of faces between two parameter choices `a` and `b` of `input` (THEORY §13): the
/// cells of `level` counted exactly first (more than `max_cells` is refused), then `frames`
/// frames built and checked (holes and components counted on a raster of `size` pixels, rounded
/// up to a power of two), each frame's cells kept as polygons (8 segments per Bézier edge).
/// `each` sees every frame's instance as it is built (the command line writes PNG frames).
#[allow(clippy::too_many_arguments)]
pub fn morph_faces(
    input: &Input,
    a: &InstantiateOptions,
    b: &InstantiateOptions,
    frames: u32,
    level: u32,
    size: u32,
    max_cells: u64,
    limits: &Limits,
    mut each: impl FnMut(u32, &Instance) -> Result<(), GeometryError>,
) -> Result<(MorphReport, MorphFrames), GeometryError> {
    let ts = crate::topology::close_or_error(&input.faces(), limits)?;
    let counts = crate::topology::counts(&ts, u64::from(level));
    let cells = &counts[level as usize].faces;
    if cells > &num_bigint::BigUint::from(max_cells) {
        return Err(Error::limit("the cells of one frame", cells, max_cells, "--max-cells").into());
    }
    let mopts = MeasureOptions {
        level,
        raster: (size as usize).next_power_of_two(),
        density_grid: 0,
        ..Default::default()
    };
    let mut drawn: MorphFrames = Vec::new();
    let report = crate::measure::morph(input, a, b, frames, &mopts, |k, inst, frame| {
        let mut cells = Vec::new();
        inst.walk(level, false, |c| {
            cells.push((c.ty, inst.cell_polygon(c.ty, c.points, 8), true));
        });
        drawn.push((cells, frame.clone()));
        each(k, inst)
    })?;
    Ok((report, drawn))
}

/// The morph between two automata of one shape (THEORY §13): both resolved (free parameters 0),
/// the pieces of `level` counted first (more than 2 000 000 in one frame is refused), then
/// `frames` frames built and checked, each frame's pieces kept (polygons filled, polylines and
/// points open). `each` sees every frame's evaluator as it is built. The report is named `name`.
pub fn morph_automata(
    name: &str,
    a: &AutomatonModel,
    b: &AutomatonModel,
    frames: u32,
    level: u32,
    limits: &Limits,
    mut each: impl FnMut(u32, &Evaluator) -> Result<(), Error>,
) -> Result<(MorphReport, MorphFrames), Error> {
    let ra = crate::analysis::resolve(a, &[], limits.max_unknowns)?;
    let rb = crate::analysis::resolve(b, &[], limits.max_unknowns)?;
    // The pieces of the level are counted before any frame is drawn.
    let count = Evaluator::new(a, &ra).count(level);
    let max = 2_000_000u128;
    if count > max {
        return Err(Error::limit(
            "the pieces of one frame",
            count,
            max,
            "--level (lower it)",
        ));
    }
    let mut drawn: MorphFrames = Vec::new();
    let mut report =
        crate::measure::morph_automata(a, &ra, b, &rb, frames, level, |k, ev, frame| {
            let cells = ev
                .shapes(level)
                .into_iter()
                .map(|s| {
                    let closed = matches!(s.kind, ShapeKind::Polygon);
                    (
                        s.state,
                        s.points.iter().map(|p| [p[0], p[1]]).collect(),
                        closed,
                    )
                })
                .collect();
            drawn.push((cells, frame.clone()));
            each(k, ev)
        })?;
    report.name = name.to_string();
    Ok((report, drawn))
}

/// The paths of a morph's PNG frames: `pattern` with `{}` replaced by each frame number, three
/// digits from `000`. E1401, naming `flag` (the command line's `--png`, Python's `png`), when the
/// pattern has no `{}`.
pub fn morph_png_paths(
    pattern: &str,
    frames: u32,
    flag: &str,
) -> Result<Vec<std::path::PathBuf>, Error> {
    if !pattern.contains("{}") {
        return Err(Error::syntax(
            "E1401",
            format!("{flag} `{pattern}`: the pattern needs `{{}}`, replaced by the frame number"),
            crate::Span {
                line: 1,
                col: 1,
                len: pattern.chars().count().max(1),
            },
            Some(&crate::Source::command_line(pattern)),
        ));
    }
    Ok((0..frames)
        .map(|k| pattern.replace("{}", &format!("{k:03}")).into())
        .collect())
}

/// Writes one frame of a morph of faces as its PNG frame: the cells of `level`, `size` pixels
/// wide, without the legend.
pub fn write_morph_png<W: Write>(inst: &Instance, level: u32, size: u32, out: W) -> io::Result<()> {
    let picture = crate::export::picture::PictureOptions {
        width: size,
        legend: false,
        ..Default::default()
    };
    crate::export::bitmap::write_png_picture(inst, level, &picture, out)
}

/// Writes one frame of a morph of automata as its PNG frame: the pieces of `level` on a raster
/// of `size` × `size` pixels.
pub fn write_morph_automaton_png<W: Write>(
    ev: &Evaluator,
    level: u32,
    size: u32,
    out: W,
) -> io::Result<()> {
    let raster = crate::export::automaton_writer::automaton_raster(ev, level, size as usize);
    crate::export::writer::write_png(&raster, out)
}

/// The discrete `values` and `keyTimes` that show frame `k` of `n` during [k/n, (k+1)/n).
fn key_times(k: usize, n: usize) -> (String, String) {
    let t = |i: usize| format!("{}", i as f64 / n as f64);
    let mut values = Vec::new();
    let mut times = Vec::new();
    if k > 0 {
        values.push("hidden");
        times.push(t(0));
    }
    values.push("visible");
    times.push(t(k));
    if k + 1 < n {
        values.push("hidden");
        times.push(t(k + 1));
    }
    (values.join(";"), times.join(";"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_frame_is_shown_in_its_own_slot() {
        // 4 frames: frame 0 visible on [0, 1/4), frame 2 on [1/2, 3/4), frame 3 on [3/4, 1].
        assert_eq!(key_times(0, 4), ("visible;hidden".into(), "0;0.25".into()));
        assert_eq!(
            key_times(2, 4),
            ("hidden;visible;hidden".into(), "0;0.5;0.75".into())
        );
        assert_eq!(key_times(3, 4), ("hidden;visible".into(), "0;0.75".into()));
        assert_eq!(key_times(0, 1), ("visible".into(), "0".into()));
    }

    #[test]
    fn a_point_is_drawn_as_a_dot() {
        // Two points of an automaton's `point` primitive and one closed triangle: the points
        // are circles (a path of one point would draw nothing), the triangle a filled path.
        let frame = MorphFrame {
            index: 0,
            t: "0".into(),
            verified: true,
            failures: Vec::new(),
            holes: None,
            components: None,
        };
        let cells: FrameCells = vec![
            (0, vec![[0.0, 0.0]], false),
            (0, vec![[1.0, 1.0]], false),
            (1, vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]], true),
        ];
        let mut out = Vec::new();
        write_morph_svg("dots", &[(cells, frame)], 100, 0.5, &mut out).unwrap();
        let svg = String::from_utf8(out).unwrap();
        assert_eq!(svg.matches("<circle ").count(), 2, "{svg}");
        assert_eq!(svg.matches("<path ").count(), 1, "{svg}");
    }
}
