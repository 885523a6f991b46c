//! What the SVG and PNG pictures of a level share: the frame (window and scale), the outline of a
//! cell (Bézier edges flattened adaptively to a tolerance in pixels), the stroke width relative to
//! the cells of the level, the legend's entries; and the SVG picture itself.
//!
//! The window fits the level-0 faces with a 2% margin; y points up in the plane and down in the
//! picture. Cells are filled by face type ([`crate::export::palette`]) and outlined in a darker
//! shade of their fill, with a width of 3% of the level's typical cell size (the square root of the
//! mean cell area), at most 2.5 pixels, and no outline below 0.2 pixels: neighbouring cells of one
//! type stay apart at level 1, and the outlines do not wash out deep levels.

use crate::export::palette::{hex, outline_colour, type_colour};
use crate::geometry::flatten::flatten_bezier;
use crate::geometry::instantiate::Instance;
use crate::geometry::point::{signed_area, BBox, Point};
use std::fmt::Write as _;
use std::io::{self, Write};

/// The background of a picture.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Background {
    /// Opaque white.
    #[default]
    White,
    /// Transparent (PNG alpha 0; SVG draws no background).
    Transparent,
}

/// How to draw a picture of one level.
#[derive(Clone, Debug, PartialEq)]
pub struct PictureOptions {
    /// Width in pixels (the PNG's width; the SVG's nominal width). The height follows the window's
    /// aspect ratio, plus the legend.
    pub width: u32,
    /// White or transparent.
    pub background: Background,
    /// Draw the legend (type → colour, with each type's notation) below the picture.
    pub legend: bool,
    /// Largest distance, in pixels, of a flattened curve from the true Bézier edge.
    pub tolerance: f64,
}

impl Default for PictureOptions {
    fn default() -> Self {
        PictureOptions {
            width: 512,
            background: Background::White,
            legend: true,
            tolerance: 0.1,
        }
    }
}

/// Outline width relative to the typical cell size of the level.
const STROKE_FRACTION: f64 = 0.03;
/// Widest outline, in pixels.
const STROKE_MAX_PX: f64 = 2.5;
/// Narrowest outline drawn, in pixels (below it, none).
const STROKE_MIN_PX: f64 = 0.2;

/// The window of a picture and its scale.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// The left edge of the window (plane coordinates).
    pub left: f64,
    /// The top edge of the window (plane coordinates; y up).
    pub top: f64,
    /// Pixels per unit of the plane.
    pub scale: f64,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels of the picture (without the legend).
    pub height: u32,
}

impl Frame {
    /// The frame of a picture `width` pixels wide that fits the level-0 faces (the true curves,
    /// not a fixed flattening) with a 2% margin.
    pub fn of(inst: &Instance, width: u32) -> Frame {
        let mut hull = BBox::empty();
        inst.walk(0, false, |c| c.points.iter().for_each(|&p| hull.add(p)));
        let tol = hull.size().max(1e-300) * 1e-5;
        let mut bb = BBox::empty();
        inst.walk(0, false, |c| {
            for p in outline(inst, c.ty, c.points, tol) {
                bb.add(p);
            }
        });
        if bb.min[0] > bb.max[0] {
            bb = BBox {
                min: [0.0, 0.0],
                max: [1.0, 1.0],
            };
        }
        let m = 0.02 * bb.size().max(1e-300);
        let (w, h) = (
            bb.max[0] - bb.min[0] + 2.0 * m,
            bb.max[1] - bb.min[1] + 2.0 * m,
        );
        let width = width.max(1);
        let scale = f64::from(width) / w;
        Frame {
            left: bb.min[0] - m,
            top: bb.max[1] + m,
            scale,
            width,
            height: ((h * scale).round() as u32).max(1),
        }
    }

    /// The pixel position of a point of the plane (x right, y down; pixel centres at half
    /// integers).
    pub fn to_pixel(&self, p: Point) -> [f64; 2] {
        [
            (p[0] - self.left) * self.scale,
            (self.top - p[1]) * self.scale,
        ]
    }
}

/// The closed outline of a cell, each edge's end once: Cantor edges as chords, Bézier edges
/// flattened to within `tolerance` (plane units).
pub fn outline(inst: &Instance, ty: usize, points: &[Point], tolerance: f64) -> Vec<Point> {
    let mut poly = Vec::new();
    for e in 0..inst.slots[ty].len() {
        let ctrl = inst.edge_controls(ty, e, points);
        poly.push(ctrl[0]);
        if inst.slots[ty][e].bezier {
            flatten_bezier(&ctrl, tolerance, &mut poly);
        } else {
            poly.push(ctrl[ctrl.len() - 1]);
        }
        poly.pop();
    }
    poly
}

/// The outline width of the cells of `level` in plane units (0: no outline), for a picture of
/// `scale` pixels per unit: [`STROKE_FRACTION`] of the square root of the mean cell area.
pub fn stroke_width(inst: &Instance, level: u32, scale: f64) -> f64 {
    let (mut area, mut count) = (0.0, 0u64);
    inst.walk(level, false, |c| {
        // The corners' polygon is enough for a size.
        area += signed_area(&inst.cell_polygon(c.ty, c.points, 1)).abs();
        count += 1;
    });
    if count == 0 {
        return 0.0;
    }
    let typical = (area / count as f64).sqrt();
    let px = (STROKE_FRACTION * typical * scale).min(STROKE_MAX_PX);
    if px.is_finite() && px >= STROKE_MIN_PX {
        px / scale
    } else {
        0.0
    }
}

/// The legend's entries: (type id, its colour, its notation), one per face type.
pub fn legend_entries(inst: &Instance) -> Vec<(String, [u8; 3], String)> {
    inst.types
        .types
        .iter()
        .enumerate()
        .map(|(t, ty)| (format!("T{t}"), type_colour(t), ty.face.to_string()))
        .collect()
}

/// Legend layout shared by the SVG and PNG pictures: entries in columns of equal width, as many
/// columns as fit; returns (columns, rows, column width) for text of `char_width` pixels per
/// character and a swatch of `swatch` pixels.
pub(crate) fn legend_grid(
    entries: &[(String, [u8; 3], String)],
    width: u32,
    char_width: f64,
    swatch: f64,
) -> (usize, usize, f64) {
    let longest = entries
        .iter()
        .map(|(id, _, face)| id.chars().count() + 2 + face.chars().count())
        .max()
        .unwrap_or(0);
    let column = swatch * 1.6 + char_width * (longest as f64 + 2.0);
    let columns = ((f64::from(width) / column).floor() as usize).clamp(1, entries.len().max(1));
    (columns, entries.len().div_ceil(columns), column)
}

fn fmt(x: f64) -> String {
    let s = format!("{x:.6}");
    if s == "-0.000000" {
        "0.000000".into()
    } else {
        s
    }
}

pub(crate) fn xml_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The SVG path data of a cell (y negated): quadratic and cubic Bézier edges as the curves
/// themselves, higher degrees flattened to within `tolerance` (plane units), Cantor edges as
/// lines.
fn svg_path(inst: &Instance, ty: usize, points: &[Point], tolerance: f64) -> String {
    let mut d = String::new();
    let pt = |d: &mut String, p: Point| {
        d.push_str(&fmt(p[0]));
        d.push(' ');
        d.push_str(&fmt(-p[1]));
    };
    for e in 0..inst.slots[ty].len() {
        let ctrl = inst.edge_controls(ty, e, points);
        if e == 0 {
            d.push('M');
            pt(&mut d, ctrl[0]);
        }
        let bezier = inst.slots[ty][e].bezier;
        match ctrl.len() {
            3 if bezier => {
                d.push_str(" Q");
                pt(&mut d, ctrl[1]);
                d.push(' ');
                pt(&mut d, ctrl[2]);
            }
            4 if bezier => {
                d.push_str(" C");
                pt(&mut d, ctrl[1]);
                d.push(' ');
                pt(&mut d, ctrl[2]);
                d.push(' ');
                pt(&mut d, ctrl[3]);
            }
            n if bezier && n > 4 => {
                let mut line = Vec::new();
                flatten_bezier(&ctrl, tolerance, &mut line);
                for p in line {
                    d.push_str(" L");
                    pt(&mut d, p);
                }
            }
            _ => {
                d.push_str(" L");
                pt(&mut d, ctrl[ctrl.len() - 1]);
            }
        }
    }
    d.push_str(" Z");
    d
}

/// Writes the cells of `level` as an SVG picture with the given options: one `<path>` per cell,
/// filled by face type and outlined in a darker shade; lacunas and notches stay open. With a
/// legend, the picture is an inner `<svg>` and the legend a `<g class="legend">` below it with one
/// `<g class="legend-entry">` per type.
pub fn write_svg_picture<W: Write>(
    inst: &Instance,
    level: u32,
    opts: &PictureOptions,
    mut out: W,
) -> io::Result<()> {
    let f = Frame::of(inst, opts.width);
    let tol = opts.tolerance.max(1e-6) / f.scale;
    let stroke = stroke_width(inst, level, f.scale);
    let (w, h) = (f64::from(f.width) / f.scale, f64::from(f.height) / f.scale);
    let view = format!("{} {} {} {}", fmt(f.left), fmt(-f.top), fmt(w), fmt(h));
    let entries = legend_entries(inst);
    let (font, row, swatch, char_width) = (13.0, 20.0, 12.0, 7.6);
    let (_, rows, column) = legend_grid(&entries, f.width, char_width, swatch);
    let legend_h = if opts.legend {
        rows as f64 * row + 12.0
    } else {
        0.0
    };
    let title = format!("<title>{} level {level}</title>", xml_escape(&inst.name));
    if opts.legend {
        let total = f64::from(f.height) + legend_h;
        writeln!(
            out,
            "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 {} {total}\" width=\"{}\" height=\"{total}\">\n{title}",
            f.width, f.width
        )?;
        if opts.background == Background::White {
            writeln!(
                out,
                "<rect width=\"{}\" height=\"{total}\" fill=\"#fff\"/>",
                f.width
            )?;
        }
        writeln!(
            out,
            "<svg class=\"cells\" x=\"0\" y=\"0\" width=\"{}\" height=\"{}\" viewBox=\"{view}\">",
            f.width, f.height
        )?;
    } else {
        writeln!(
            out,
            "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"cells\" viewBox=\"{view}\" width=\"{}\" height=\"{}\">\n{title}",
            f.width, f.height
        )?;
        if opts.background == Background::White {
            writeln!(
                out,
                "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"#fff\"/>",
                fmt(f.left),
                fmt(-f.top),
                fmt(w),
                fmt(h)
            )?;
        }
    }
    if stroke > 0.0 {
        writeln!(
            out,
            "<g stroke-width=\"{}\" stroke-linejoin=\"round\">",
            fmt(stroke)
        )?;
    } else {
        writeln!(out, "<g stroke=\"none\">")?;
    }
    let mut result = Ok(());
    inst.walk(level, false, |c| {
        if result.is_err() {
            return;
        }
        let d = svg_path(inst, c.ty, c.points, tol);
        result = if stroke > 0.0 {
            writeln!(
                out,
                "<path fill=\"{}\" stroke=\"{}\" d=\"{d}\"/>",
                hex(type_colour(c.ty)),
                hex(outline_colour(c.ty))
            )
        } else {
            writeln!(out, "<path fill=\"{}\" d=\"{d}\"/>", hex(type_colour(c.ty)))
        };
    });
    result?;
    writeln!(out, "</g>\n</svg>")?;
    if opts.legend {
        let mut s = format!(
            "<g class=\"legend\" font-family=\"DejaVu Sans Mono, monospace\" font-size=\"{font}\">\n"
        );
        for (k, (id, colour, face)) in entries.iter().enumerate() {
            let (col, r) = (k / rows, k % rows);
            let x = 6.0 + col as f64 * column;
            let y = f64::from(f.height) + 6.0 + r as f64 * row;
            let _ = writeln!(
                s,
                "<g class=\"legend-entry\"><rect x=\"{x}\" y=\"{}\" width=\"{swatch}\" height=\"{swatch}\" fill=\"{}\" stroke=\"{}\"/><text x=\"{}\" y=\"{}\"><tspan font-weight=\"bold\">{}</tspan> {}</text></g>",
                y + 3.0,
                hex(*colour),
                hex(crate::export::palette::darker(*colour)),
                x + swatch * 1.6,
                y + 3.0 + swatch - 1.0,
                xml_escape(id),
                xml_escape(face)
            );
        }
        s.push_str("</g>\n");
        out.write_all(s.as_bytes())?;
        writeln!(out, "</svg>")?;
    }
    Ok(())
}
