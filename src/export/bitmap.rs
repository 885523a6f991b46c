//! Colour PNG pictures: the cells of a level, anti-aliased and filled by face type with the SVG's
//! palette, with a legend; and density maps at a chosen size with the viridis colour map, a
//! colour bar and the grid and mask stated.
//!
//! Shapes are rasterised by `zeno` (exact-area anti-aliasing, non-zero fill, strokes with round
//! joins); text is drawn from the pre-rasterised glyphs of Noto Sans Mono (`noto-sans-mono-bitmap`,
//! no font file to load); the image is encoded by `png`. The canvas is premultiplied RGBA, 8 bits
//! per channel; source-over compositing.

use crate::export::palette::{darker, density_colour, outline_colour, type_colour, Rgb, OUTSIDE};
use crate::export::picture::{
    legend_entries, legend_grid, outline, stroke_width, Background, Frame, PictureOptions,
};
use crate::geometry::instantiate::Instance;
use crate::geometry::point::Point;
use crate::geometry::raster::cell_count;
use crate::measure::DensityMap;
use crate::progress::Progress;
use noto_sans_mono_bitmap::{get_raster, get_raster_width, FontWeight, RasterHeight};
use std::io::{self, Write};
use zeno::{Command, Join, Mask, PathBuilder, Scratch, Stroke};

/// A premultiplied RGBA canvas.
pub(crate) struct Canvas {
    width: u32,
    height: u32,
    data: Vec<u8>,
}

impl Canvas {
    fn new(width: u32, height: u32, background: Background) -> Canvas {
        let fill = match background {
            Background::White => 255,
            Background::Transparent => 0,
        };
        Canvas {
            width,
            height,
            data: vec![fill; width as usize * height as usize * 4],
        }
    }

    /// Source-over of an opaque colour with coverage `cov` (0–255) at pixel (x, y).
    fn blend(&mut self, x: i64, y: i64, c: Rgb, cov: u8) {
        if cov == 0 || x < 0 || y < 0 || x >= i64::from(self.width) || y >= i64::from(self.height) {
            return;
        }
        let i = (y as usize * self.width as usize + x as usize) * 4;
        let a = u32::from(cov);
        for (d, &v) in self.data[i..i + 3].iter_mut().zip(&c) {
            *d = ((u32::from(v) * a + u32::from(*d) * (255 - a) + 127) / 255) as u8;
        }
        let d = u32::from(self.data[i + 3]);
        self.data[i + 3] = ((255 * a + d * (255 - a) + 127) / 255) as u8;
    }

    /// Composites a coverage mask placed at (left, top).
    fn mask(&mut self, mask: &[u8], p: zeno::Placement, c: Rgb) {
        for row in 0..p.height as usize {
            for col in 0..p.width as usize {
                let cov = mask[row * p.width as usize + col];
                self.blend(
                    i64::from(p.left) + col as i64,
                    i64::from(p.top) + row as i64,
                    c,
                    cov,
                );
            }
        }
    }

    /// Fills (and optionally outlines) a closed polygon given in pixel coordinates. The coverage
    /// mask covers only the polygon's pixel box (clipped to the canvas) and reuses `buf`.
    fn polygon(
        &mut self,
        scratch: &mut Scratch,
        buf: &mut Vec<u8>,
        poly: &[[f64; 2]],
        fill: Option<Rgb>,
        line: Option<(Rgb, f64)>,
    ) {
        if poly.len() < 2 {
            return;
        }
        let Some((mut path, place)) = self.local_path(poly, line.map_or(0.0, |l| l.1) + 1.0) else {
            return;
        };
        path.close();
        let (w, h) = (place.width, place.height);
        let n = w as usize * h as usize;
        if let Some(c) = fill {
            buf.clear();
            buf.resize(n, 0);
            Mask::with_scratch(&path, scratch)
                .size(w, h)
                .render_into(buf, None);
            self.mask(buf, place, c);
        }
        if let Some((c, lw)) = line {
            let mut stroke = Stroke::new(lw as f32);
            stroke.join(Join::Round);
            buf.clear();
            buf.resize(n, 0);
            Mask::with_scratch(&path, scratch)
                .style(stroke)
                .size(w, h)
                .render_into(buf, None);
            self.mask(buf, place, c);
        }
    }

    /// Strokes an open polyline given in pixel coordinates, `lw` pixels wide, round joins.
    fn polyline(
        &mut self,
        scratch: &mut Scratch,
        buf: &mut Vec<u8>,
        pts: &[[f64; 2]],
        c: Rgb,
        lw: f64,
    ) {
        if pts.len() < 2 {
            return;
        }
        let Some((path, place)) = self.local_path(pts, lw + 1.0) else {
            return;
        };
        let (w, h) = (place.width, place.height);
        let mut stroke = Stroke::new(lw as f32);
        stroke.join(Join::Round);
        stroke.cap(zeno::Cap::Round);
        buf.clear();
        buf.resize(w as usize * h as usize, 0);
        Mask::with_scratch(&path, scratch)
            .style(stroke)
            .size(w, h)
            .render_into(buf, None);
        self.mask(buf, place, c);
    }

    /// The open path through `pts` (pixel coordinates) in the frame of their pixel box grown by
    /// `pad` and clipped to the canvas, with that box; `None` when the box misses the canvas.
    fn local_path(&self, pts: &[[f64; 2]], pad: f64) -> Option<(Vec<Command>, zeno::Placement)> {
        let (mut x0, mut y0, mut x1, mut y1) = (f64::MAX, f64::MAX, f64::MIN, f64::MIN);
        for p in pts {
            x0 = x0.min(p[0]);
            y0 = y0.min(p[1]);
            x1 = x1.max(p[0]);
            y1 = y1.max(p[1]);
        }
        let x0 = ((x0 - pad).floor()).max(0.0);
        let y0 = ((y0 - pad).floor()).max(0.0);
        let x1 = ((x1 + pad).ceil()).min(f64::from(self.width));
        let y1 = ((y1 + pad).ceil()).min(f64::from(self.height));
        if !(x1 > x0 && y1 > y0) {
            return None;
        }
        let mut path: Vec<Command> = Vec::with_capacity(pts.len() + 2);
        path.move_to([(pts[0][0] - x0) as f32, (pts[0][1] - y0) as f32]);
        for p in &pts[1..] {
            path.line_to([(p[0] - x0) as f32, (p[1] - y0) as f32]);
        }
        let place = zeno::Placement {
            left: x0 as i32,
            top: y0 as i32,
            width: (x1 - x0) as u32,
            height: (y1 - y0) as u32,
        };
        Some((path, place))
    }

    /// A legend's swatch: an `s`-pixel square of colour `c` with a darker rim.
    fn swatch(&mut self, x: i64, y: i64, s: i64, c: Rgb) {
        self.rect(x, y, s, s, darker(c));
        self.rect(x + 1, y + 1, s - 2, s - 2, c);
    }

    fn rect(&mut self, x: i64, y: i64, w: i64, h: i64, c: Rgb) {
        for yy in y..y + h {
            for xx in x..x + w {
                self.blend(xx, yy, c, 255);
            }
        }
    }

    /// Draws `text` with its top-left corner at (x, y); characters the font lacks are drawn as `?`.
    /// Returns the width drawn.
    fn text(&mut self, x: i64, y: i64, text: &str, size: RasterHeight, c: Rgb) -> i64 {
        let cw = get_raster_width(FontWeight::Regular, size) as i64;
        let mut cx = x;
        for ch in text.chars() {
            let g = get_raster(ch, FontWeight::Regular, size)
                .or_else(|| get_raster('?', FontWeight::Regular, size));
            if let Some(g) = g {
                for (r, row) in g.rows().enumerate() {
                    for (k, &v) in row.iter().enumerate() {
                        self.blend(cx + k as i64, y + r as i64, c, v);
                    }
                }
            }
            cx += cw;
        }
        cx - x
    }

    /// Encodes the canvas as an 8-bit RGBA PNG (straight alpha).
    fn write_png<W: Write>(&self, out: W) -> io::Result<()> {
        let mut straight = self.data.clone();
        for px in straight.chunks_mut(4) {
            let a = u32::from(px[3]);
            if a != 0 && a != 255 {
                for v in &mut px[..3] {
                    *v = ((u32::from(*v) * 255 + a / 2) / a).min(255) as u8;
                }
            }
        }
        let mut enc = png::Encoder::new(out, self.width, self.height);
        enc.set_color(png::ColorType::Rgba);
        enc.set_depth(png::BitDepth::Eight);
        let mut w = enc.write_header().map_err(io::Error::other)?;
        w.write_image_data(&straight).map_err(io::Error::other)?;
        w.finish().map_err(io::Error::other)
    }
}

/// The cells of one type gathered into one path, filled at once with the non-zero rule: every
/// cell is oriented the same way, so an edge shared by two cells of the type is crossed once in
/// each direction and cancels, and no seam of background shows between them (filling cells one by
/// one would blend each shared pixel twice with partial coverage). Flushed every
/// [`Batch::LIMIT`] commands to bound memory.
struct Batch {
    path: Vec<Command>,
    bbox: [f64; 4],
}

impl Batch {
    const LIMIT: usize = 1 << 18;

    fn new() -> Batch {
        Batch {
            path: Vec::new(),
            bbox: [f64::MAX, f64::MAX, f64::MIN, f64::MIN],
        }
    }

    /// Adds a closed polygon (pixel coordinates), counter-clockwise on the screen.
    fn add(&mut self, poly: &[[f64; 2]]) {
        if poly.len() < 3 {
            return;
        }
        let area: f64 = (0..poly.len())
            .map(|k| {
                let (a, b) = (poly[k], poly[(k + 1) % poly.len()]);
                a[0] * b[1] - b[0] * a[1]
            })
            .sum();
        let mut pts: Vec<[f64; 2]> = poly.to_vec();
        if area < 0.0 {
            pts.reverse();
        }
        self.path.move_to([pts[0][0] as f32, pts[0][1] as f32]);
        for p in &pts[1..] {
            self.path.line_to([p[0] as f32, p[1] as f32]);
        }
        self.path.close();
        for p in &pts {
            self.bbox[0] = self.bbox[0].min(p[0]);
            self.bbox[1] = self.bbox[1].min(p[1]);
            self.bbox[2] = self.bbox[2].max(p[0]);
            self.bbox[3] = self.bbox[3].max(p[1]);
        }
    }

    /// Fills the gathered path in colour `c` and empties the batch.
    fn flush(&mut self, canvas: &mut Canvas, scratch: &mut Scratch, buf: &mut Vec<u8>, c: Rgb) {
        if self.path.is_empty() {
            return;
        }
        let x0 = (self.bbox[0] - 1.0).floor().max(0.0);
        let y0 = (self.bbox[1] - 1.0).floor().max(0.0);
        let x1 = (self.bbox[2] + 1.0).ceil().min(f64::from(canvas.width));
        let y1 = (self.bbox[3] + 1.0).ceil().min(f64::from(canvas.height));
        if x1 > x0 && y1 > y0 {
            let (w, h) = ((x1 - x0) as u32, (y1 - y0) as u32);
            buf.clear();
            buf.resize(w as usize * h as usize, 0);
            Mask::with_scratch(&self.path, scratch)
                .size(w, h)
                .offset(zeno::Vector::new(-x0 as f32, -y0 as f32))
                .render_into(buf, None);
            let place = zeno::Placement {
                left: x0 as i32,
                top: y0 as i32,
                width: w,
                height: h,
            };
            canvas.mask(buf, place, c);
        }
        *self = Batch::new();
    }
}

/// The text size for a picture of this width.
fn text_size(width: u32) -> RasterHeight {
    if width >= 1400 {
        RasterHeight::Size24
    } else {
        RasterHeight::Size16
    }
}

/// Writes the cells of `level` as a colour PNG `opts.width` pixels wide: anti-aliased, filled by
/// face type with the SVG's palette, outlined in a darker shade ([`stroke_width`]), on a white or
/// transparent background, with the legend below when `opts.legend`. The picture's frame is
/// [`Frame::of`] (a test maps points of the plane to pixels with it).
pub fn write_png_picture<W: Write>(
    inst: &Instance,
    level: u32,
    opts: &PictureOptions,
    out: W,
) -> io::Result<()> {
    let f = Frame::of(inst, opts.width);
    let size = text_size(f.width);
    let (cw, ch) = (
        get_raster_width(FontWeight::Regular, size) as f64,
        size.val() as f64,
    );
    let entries = legend_entries(inst);
    let swatch = ch * 0.75;
    let (_, rows, column) = legend_grid(&entries, f.width, cw, swatch);
    let row_h = (ch * 1.25).round();
    let legend_h = if opts.legend {
        (rows as f64 * row_h + ch * 0.75).round() as u32
    } else {
        0
    };
    let mut canvas = Canvas::new(f.width, f.height + legend_h, opts.background);
    let tol = opts.tolerance.max(1e-6) / f.scale;
    let stroke = stroke_width(inst, level, f.scale) * f.scale;
    let mut scratch = Scratch::new();
    let mut buf = Vec::new();
    let to_px =
        |poly: Vec<Point>| -> Vec<[f64; 2]> { poly.into_iter().map(|p| f.to_pixel(p)).collect() };
    // Fills first, one batch per type; then the outlines, cell by cell.
    let mut bar = Progress::new(
        "picture",
        cell_count(inst, level) * if stroke > 0.0 { 2 } else { 1 },
    );
    let mut batches: Vec<Batch> = (0..inst.types.types.len()).map(|_| Batch::new()).collect();
    inst.walk(level, false, |c| {
        bar.tick();
        let b = &mut batches[c.ty];
        b.add(&to_px(outline(inst, c.ty, c.points, tol)));
        if b.path.len() >= Batch::LIMIT {
            b.flush(&mut canvas, &mut scratch, &mut buf, type_colour(c.ty));
        }
    });
    for (t, b) in batches.iter_mut().enumerate() {
        b.flush(&mut canvas, &mut scratch, &mut buf, type_colour(t));
    }
    if stroke > 0.0 {
        inst.walk(level, false, |c| {
            bar.tick();
            let poly = to_px(outline(inst, c.ty, c.points, tol));
            canvas.polygon(
                &mut scratch,
                &mut buf,
                &poly,
                None,
                Some((outline_colour(c.ty), stroke)),
            );
        });
    }
    if opts.legend {
        for (k, (id, colour, face)) in entries.iter().enumerate() {
            let (col, r) = (k / rows, k % rows);
            let x = (ch * 0.4 + col as f64 * column).round() as i64;
            let y = (f64::from(f.height) + ch * 0.4 + r as f64 * row_h).round() as i64;
            let s = swatch.round() as i64;
            let sy = y + ((ch - swatch) / 2.0).round() as i64;
            canvas.swatch(x, sy, s, *colour);
            let tx = x + (swatch * 1.6).round() as i64;
            let used = canvas.text(tx, y, id, size, [0, 0, 0]);
            canvas.text(tx + used + cw as i64, y, face, size, [0x33, 0x33, 0x33]);
        }
    }
    canvas.write_png(out)
}

/// The stroke of polylines, in pixels of a picture `width` wide: 1, or for a drawing that lies
/// on a line (x-extent `dx`, y-extent `dy`) bars a fortieth of the width thick, so that a Cantor
/// set reads as bars rather than a hairline.
pub(crate) fn bar_width(dx: f64, dy: f64, width: f64, line: f64) -> f64 {
    match dy <= dx * 1e-9 {
        true => (width / 40.0).max(line),
        false => line,
    }
}

/// Writes the shapes of an automaton's level (`Evaluator::shapes`, drawn in the plane: space 3
/// through the SVG's axonometric view) as a colour PNG `width` pixels wide: the picture centred
/// with a margin (its height follows the shapes' aspect, at least a quarter and at most twice the
/// width), polygons filled by state with the face pictures' palette (one non-zero path per state,
/// so no seam shows where two pieces of a state meet), polylines stroked in their state's
/// colour, points as dots, and below, unless `legend` is false, each state's colour and name.
pub fn write_shapes_png<W: Write>(
    shapes: &[crate::geometry::Shape],
    projection: Projection<'_>,
    names: &[String],
    width: u32,
    background: Background,
    legend: bool,
    out: W,
) -> io::Result<()> {
    let view = projection.to_plane;
    let (mut x0, mut y0, mut x1, mut y1) = (f64::MAX, f64::MAX, f64::MIN, f64::MIN);
    for p in shapes.iter().flat_map(|s| &s.points) {
        let (x, y) = view(p);
        x0 = x0.min(x);
        y0 = y0.min(y);
        x1 = x1.max(x);
        y1 = y1.max(y);
    }
    if x0 > x1 {
        (x0, y0, x1, y1) = (0.0, 0.0, 1.0, 1.0);
    }
    let (dx, dy) = ((x1 - x0).max(1e-12), (y1 - y0).max(0.0));
    let w = f64::from(width.max(16));
    let height = (w * dy / dx).clamp(w / 4.0, 2.0 * w).round();
    let margin = (w * 0.04).max(2.0);
    let scale = ((w - 2.0 * margin) / dx).min(if dy > 0.0 {
        (height - 2.0 * margin) / dy
    } else {
        f64::INFINITY
    });
    // Centred both ways.
    let (cx, cy) = ((x0 + x1) / 2.0, (y0 + y1) / 2.0);
    let to_px = |p: &[f64; 3]| {
        let (x, y) = view(p);
        [w / 2.0 + (x - cx) * scale, height / 2.0 - (y - cy) * scale]
    };
    let size = text_size(width);
    let ch = size.val() as f64;
    let states: Vec<usize> = {
        let mut v: Vec<usize> = shapes.iter().map(|s| s.state).collect();
        v.sort_unstable();
        v.dedup();
        v
    };
    let legend_h = if legend && !states.is_empty() {
        (ch * 2.0).round() as u32
    } else {
        0
    };
    let mut canvas = Canvas::new(w as u32, height as u32 + legend_h, background);
    let mut scratch = Scratch::new();
    let mut buf = Vec::new();
    let line = (w / 700.0).max(1.0);
    let n = names.len().max(1);
    let mut fills: Vec<Batch> = (0..n).map(|_| Batch::new()).collect();
    // In space 3, polygons are shaded and painted far to near (below).
    let mut shaded: Vec<(f64, usize)> = Vec::new();
    for (k, s) in shapes.iter().enumerate() {
        let pts: Vec<[f64; 2]> = s.points.iter().map(to_px).collect();
        let colour = type_colour(s.state);
        match s.kind {
            crate::geometry::ShapeKind::Polygon if projection.depth.is_some() => {
                let depth = projection.depth.expect("checked");
                let d = s.points.iter().map(depth).sum::<f64>() / s.points.len().max(1) as f64;
                shaded.push((d, k));
            }
            crate::geometry::ShapeKind::Polygon => {
                let b = &mut fills[s.state % n];
                b.add(&pts);
                if b.path.len() >= Batch::LIMIT {
                    b.flush(&mut canvas, &mut scratch, &mut buf, colour);
                }
            }
            crate::geometry::ShapeKind::Polyline if !below_pixel(&pts) => {
                let stroke = bar_width(dx, dy, w, line * 1.5);
                if stroke > line * 1.5 {
                    // Bars with square ends, filled, so that the gaps between pieces stay exact.
                    let b = &mut fills[s.state % n];
                    for seg in pts.windows(2) {
                        let (a, c) = (seg[0], seg[1]);
                        let len = (c[0] - a[0]).hypot(c[1] - a[1]).max(1e-12);
                        let (nx, ny) = (
                            -(c[1] - a[1]) / len * stroke / 2.0,
                            (c[0] - a[0]) / len * stroke / 2.0,
                        );
                        b.add(&[
                            [a[0] + nx, a[1] + ny],
                            [c[0] + nx, c[1] + ny],
                            [c[0] - nx, c[1] - ny],
                            [a[0] - nx, a[1] - ny],
                        ]);
                    }
                } else {
                    canvas.polyline(&mut scratch, &mut buf, &pts, colour, stroke);
                }
            }
            // A point, or a polyline shorter than a pixel: a dot.
            _ => {
                let r = line * 1.5;
                let disc: Vec<[f64; 2]> = (0..12)
                    .map(|k| {
                        let t = std::f64::consts::TAU * f64::from(k) / 12.0;
                        [pts[0][0] + r * t.cos(), pts[0][1] + r * t.sin()]
                    })
                    .collect();
                canvas.polygon(&mut scratch, &mut buf, &disc, Some(colour), None);
            }
        }
    }
    for (q, b) in fills.iter_mut().enumerate() {
        b.flush(&mut canvas, &mut scratch, &mut buf, type_colour(q));
    }
    // Far to near, each polygon lightened by how squarely it faces a light over the viewer's
    // shoulder (two-sided: a surface has no outside), outlined in its own colour so that no
    // background shows between neighbours.
    shaded.sort_by(|a, b| b.0.total_cmp(&a.0));
    for &(_, k) in &shaded {
        let s = &shapes[k];
        let pts: Vec<[f64; 2]> = s.points.iter().map(to_px).collect();
        let c = lit(type_colour(s.state), facing(&s.points));
        canvas.polygon(&mut scratch, &mut buf, &pts, Some(c), Some((c, 0.6)));
    }
    if legend_h > 0 {
        let cw = get_raster_width(FontWeight::Regular, size) as f64;
        let swatch = (ch * 0.75).round() as i64;
        let y = (height + ch * 0.5).round() as i64;
        let mut x = (margin).round() as i64;
        for &q in &states {
            let colour = type_colour(q);
            let sy = y + ((ch - swatch as f64) / 2.0).round() as i64;
            canvas.swatch(x, sy, swatch, colour);
            let label = format!("state {}", names.get(q).map_or("?", String::as_str));
            let used = canvas.text(x + swatch + (cw * 0.6) as i64, y, &label, size, [0, 0, 0]);
            x += swatch + (cw * 0.6) as i64 + used + (cw * 2.0) as i64;
        }
    }
    canvas.write_png(out)
}

/// How a picture of shapes maps space to the plane: `to_plane` gives the picture's coordinates (y
/// up); `depth`, for shapes in space 3, the distance along the line of sight (larger is farther),
/// with which polygons are shaded and painted far to near.
pub struct Projection<'a> {
    /// Space to picture plane.
    pub to_plane: &'a dyn Fn(&[f64; 3]) -> (f64, f64),
    /// Depth along the line of sight (space 3), or `None` (flat pictures).
    pub depth: Option<&'a Depth>,
}

/// The depth of a point of space along the line of sight.
pub type Depth = dyn Fn(&[f64; 3]) -> f64;

/// |cos| of the angle between a polygon's normal (Newell) and a light from the viewer's side,
/// above and to the left, in the axonometric view of space 3.
fn facing(points: &[[f64; 3]]) -> f64 {
    let mut n = [0.0f64; 3];
    for (k, p) in points.iter().enumerate() {
        let q = points[(k + 1) % points.len()];
        n[0] += (p[1] - q[1]) * (p[2] + q[2]);
        n[1] += (p[2] - q[2]) * (p[0] + q[0]);
        n[2] += (p[0] - q[0]) * (p[1] + q[1]);
    }
    let light = [-0.5f64, -1.1, 1.6];
    let (ln, nn) = (
        light.iter().map(|x| x * x).sum::<f64>().sqrt(),
        n.iter().map(|x| x * x).sum::<f64>().sqrt(),
    );
    if nn == 0.0 {
        return 0.0;
    }
    (n.iter().zip(light).map(|(a, b)| a * b).sum::<f64>() / (nn * ln)).abs()
}

/// A colour lightened towards white by up to 55 % as `t` goes from 0 to 1.
fn lit(c: Rgb, t: f64) -> Rgb {
    c.map(|x| (f64::from(x) + (255.0 - f64::from(x)) * 0.55 * t).round() as u8)
}

/// Whether the points span less than a pixel both ways (a piece too small to stroke).
fn below_pixel(pts: &[[f64; 2]]) -> bool {
    let span = |k: usize| {
        let (lo, hi) = pts.iter().fold((f64::MAX, f64::MIN), |(lo, hi), p| {
            (lo.min(p[k]), hi.max(p[k]))
        });
        hi - lo
    };
    span(0) < 1.0 && span(1) < 1.0
}

/// What the density picture states besides the map.
#[derive(Clone, Debug, PartialEq)]
pub struct DensityPicture {
    /// Side of the map in pixels (each block is drawn as a square of `size / grid` pixels).
    pub size: u32,
    /// The level of the map.
    pub level: u32,
    /// Side of the window in plane units (the mask of a block is `window / grid` wide).
    pub window: f64,
    /// Per block (row-major, as the map's values), whether it lies wholly outside the structure
    /// (no point of its level-0 faces): drawn in [`OUTSIDE`], off the colour map, so that it is
    /// not read as a hole. Empty: every block is drawn on the map.
    pub outside: Vec<bool>,
}

/// Writes a density map as a colour PNG: the map `size × size` pixels (blocks as squares, dark
/// violet for empty to yellow for full, [`density_colour`]; blocks outside the structure pale
/// grey), a colour bar with ticks 0, 0.25, …, 1 to its right, and below it the level, the grid,
/// the mask (a block's side in plane units and its samples) and what the grey is.
pub fn write_density_picture<W: Write>(
    map: &DensityMap,
    pic: &DensityPicture,
    out: W,
) -> io::Result<()> {
    let s = pic.size.max(1);
    let size = text_size(s);
    let (cw, ch) = (
        get_raster_width(FontWeight::Regular, size) as u32,
        size.val() as u32,
    );
    let m = ch / 2;
    let bar_w = (s / 32).clamp(12, 48);
    let mut lines = vec![
        format!("relative density, level {}", pic.level),
        format!("grid {0} x {0} blocks", map.grid),
        format!(
            "mask: block of side {:.4} ({1} x {1} samples)",
            pic.window / map.grid.max(1) as f64,
            map.samples
        ),
    ];
    if pic.outside.iter().any(|&o| o) {
        lines.push("pale grey: outside the level-0 faces".to_string());
    }
    let text_w = lines
        .iter()
        .map(|l| l.chars().count() as u32)
        .max()
        .unwrap_or(0)
        * cw;
    let width = (m + s + m + bar_w + cw / 2 + 4 * cw + m).max(2 * m + text_w);
    let height = m + s + m / 2 + lines.len() as u32 * (ch + 2) + m;
    let mut canvas = Canvas::new(width, height, Background::White);
    let g = map.grid.max(1);
    for y in 0..s {
        let br = (y as usize * g) / s as usize;
        for x in 0..s {
            let bc = (x as usize * g) / s as usize;
            let d = map.values.get(br * g + bc).copied().unwrap_or(0.0);
            let colour = match pic.outside.get(br * g + bc) {
                Some(true) => OUTSIDE,
                _ => density_colour(d),
            };
            canvas.blend(i64::from(m + x), i64::from(m + y), colour, 255);
        }
    }
    // The colour bar: 1 at the top, 0 at the bottom, with a thin frame and five ticks.
    let bx = m + s + m;
    for y in 0..s {
        let d = 1.0 - f64::from(y) / f64::from((s - 1).max(1));
        canvas.rect(
            i64::from(bx),
            i64::from(m + y),
            i64::from(bar_w),
            1,
            density_colour(d),
        );
    }
    let grey = [0x44, 0x44, 0x44];
    canvas.rect(i64::from(bx), i64::from(m), i64::from(bar_w), 1, grey);
    canvas.rect(
        i64::from(bx),
        i64::from(m + s - 1),
        i64::from(bar_w),
        1,
        grey,
    );
    canvas.rect(i64::from(bx), i64::from(m), 1, i64::from(s), grey);
    canvas.rect(
        i64::from(bx + bar_w - 1),
        i64::from(m),
        1,
        i64::from(s),
        grey,
    );
    for (k, label) in ["1", "0.75", "0.5", "0.25", "0"].iter().enumerate() {
        let y = m + ((s - 1) * k as u32) / 4;
        canvas.rect(
            i64::from(bx + bar_w),
            i64::from(y),
            i64::from(cw / 2),
            1,
            grey,
        );
        let ty = i64::from(y) - i64::from(ch / 2);
        let ty = ty.clamp(0, i64::from(height - ch));
        canvas.text(
            i64::from(bx + bar_w + cw / 2 + 2),
            ty,
            label,
            size,
            [0, 0, 0],
        );
    }
    for (k, l) in lines.iter().enumerate() {
        let y = m + s + m / 2 + k as u32 * (ch + 2);
        canvas.text(i64::from(m), i64::from(y), l, size, [0, 0, 0]);
    }
    canvas.write_png(out)
}
