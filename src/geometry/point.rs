//! Planar geometry in floating point: polygons, Bézier evaluation, a coverage raster, connected
//! components and box counting (THEORY §7).
//!
//! This is the only layer of lacuna that computes with `f64`. Nothing here decides a verdict on
//! its own: the one comparison that can fail a verification (observed holes and components against
//! the exact counts, in [`crate::measure::measurement`]) compares integers counted on a raster with integers
//! counted exactly on the topology.

use num_bigint::BigInt;
use num_rational::BigRational as Q;
use num_traits::Zero;

/// A point with exact coordinates.
pub(crate) type QPoint = [Q; 2];

/// `x` rounded to the nearest multiple of `2^-bits` (0 when not finite).
pub(crate) fn dyadic(x: f64, bits: u32) -> Q {
    let scaled = (x * 2f64.powi(bits as i32)).round();
    let num = if scaled.is_finite() {
        BigInt::from(scaled as i128)
    } else {
        BigInt::zero()
    };
    Q::new(num, BigInt::from(1u8) << bits)
}

/// A point of the plane.
pub type Point = [f64; 2];

/// Signed area of a closed polygon (shoelace formula; positive when counter-clockwise).
pub fn signed_area(poly: &[Point]) -> f64 {
    let n = poly.len();
    let mut s = 0.0;
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        s += a[0] * b[1] - a[1] * b[0];
    }
    s / 2.0
}

/// Euclidean distance of two points.
pub fn distance(a: Point, b: Point) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// Length of an open polyline.
pub fn polyline_length(points: &[Point]) -> f64 {
    points.windows(2).map(|w| distance(w[0], w[1])).sum()
}

/// The point of a Bézier curve with control points `ctrl` at parameter `t` (de Casteljau).
pub fn bezier_point(ctrl: &[Point], t: f64) -> Point {
    let mut buf: Vec<Point> = ctrl.to_vec();
    let n = buf.len();
    for level in 1..n {
        for i in 0..n - level {
            buf[i] = [
                (1.0 - t) * buf[i][0] + t * buf[i + 1][0],
                (1.0 - t) * buf[i][1] + t * buf[i + 1][1],
            ];
        }
    }
    buf[0]
}

/// An axis-aligned bounding box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BBox {
    /// Lower-left corner.
    pub min: Point,
    /// Upper-right corner.
    pub max: Point,
}

impl BBox {
    /// The empty box (grows with [`BBox::add`]).
    pub fn empty() -> Self {
        BBox {
            min: [f64::INFINITY; 2],
            max: [f64::NEG_INFINITY; 2],
        }
    }

    /// Grows the box to contain `p`.
    pub fn add(&mut self, p: Point) {
        for (k, &v) in p.iter().enumerate() {
            self.min[k] = self.min[k].min(v);
            self.max[k] = self.max[k].max(v);
        }
    }

    /// The larger side.
    pub fn size(&self) -> f64 {
        (self.max[0] - self.min[0]).max(self.max[1] - self.min[1])
    }
}

/// A square grid of `size × size` pixels over a square window of the plane, counting how many
/// polygons cover each pixel centre (saturating at 255). Row 0 is the top of the picture.
#[derive(Clone, Debug)]
pub struct Raster {
    /// Pixels per side.
    pub size: usize,
    /// Coverage counts, row-major.
    pub counts: Vec<u8>,
    /// Plane coordinates of the window's lower-left corner.
    pub origin: Point,
    /// Pixels per unit length.
    pub scale: f64,
}

/// A fraction of a pixel added to the window placement so that straight edges of rational
/// coordinates never run exactly through pixel centres (a centre on a shared edge could be missed
/// by both neighbours through rounding, and show as a false one-pixel hole).
const JITTER: f64 = 0.293_847_561;

impl Raster {
    /// A raster of `size` pixels per side whose window contains `bbox` with a margin of `margin`
    /// pixels on every side.
    pub fn fitting(bbox: BBox, size: usize, margin: usize) -> Raster {
        let inner = (size.saturating_sub(2 * margin)).max(1) as f64;
        let extent = bbox.size().max(1e-300);
        let scale = inner / extent;
        let cx = (bbox.min[0] + bbox.max[0]) / 2.0;
        let cy = (bbox.min[1] + bbox.max[1]) / 2.0;
        let half = size as f64 / 2.0 / scale;
        Raster {
            size,
            counts: vec![0; size * size],
            origin: [cx - half + JITTER / scale, cy - half + JITTER / scale],
            scale,
        }
    }

    /// The raster of the unit square `[0,1]²` with `size` pixels per side (box counting of shapes
    /// given in that square).
    pub fn unit(size: usize) -> Raster {
        Raster {
            size,
            counts: vec![0; size * size],
            origin: [0.0, 0.0],
            scale: size as f64,
        }
    }

    /// Pixel coordinates (column, row from the bottom) of a plane point.
    fn to_pixel(&self, p: Point) -> Point {
        [
            (p[0] - self.origin[0]) * self.scale,
            (p[1] - self.origin[1]) * self.scale,
        ]
    }

    /// Counts one more polygon on every pixel whose centre it contains (even–odd rule, centres on
    /// a left edge inside, on a right edge outside, so polygons sharing an edge do not overlap).
    pub fn fill_polygon(&mut self, poly: &[Point]) {
        let n = poly.len();
        if n < 3 {
            return;
        }
        let pts: Vec<Point> = poly.iter().map(|&p| self.to_pixel(p)).collect();
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for p in &pts {
            lo = lo.min(p[1]);
            hi = hi.max(p[1]);
        }
        let size = self.size as i64;
        let r0 = ((lo - 0.5).ceil() as i64).max(0);
        let r1 = ((hi - 0.5).floor() as i64).min(size - 1);
        let mut xs: Vec<f64> = Vec::with_capacity(8);
        for r in r0..=r1 {
            let y = r as f64 + 0.5;
            xs.clear();
            for i in 0..n {
                let (a, b) = (pts[i], pts[(i + 1) % n]);
                if (a[1] <= y) != (b[1] <= y) {
                    xs.push(a[0] + (y - a[1]) / (b[1] - a[1]) * (b[0] - a[0]));
                }
            }
            xs.sort_by(f64::total_cmp);
            let row = (self.size - 1 - r as usize) * self.size;
            for pair in xs.chunks_exact(2) {
                let c0 = ((pair[0] - 0.5).ceil() as i64).max(0);
                let c1 = ((pair[1] - 0.5).ceil() as i64).min(size);
                for c in c0..c1 {
                    let v = &mut self.counts[row + c as usize];
                    *v = v.saturating_add(1);
                }
            }
        }
    }

    /// Marks every pixel a segment passes through (for shapes without area, such as a segment in
    /// the box-counting tests): samples at a quarter-pixel step.
    pub fn draw_segment(&mut self, a: Point, b: Point) {
        let (pa, pb) = (self.to_pixel(a), self.to_pixel(b));
        let steps = ((distance(pa, pb) * 4.0).ceil() as usize).max(1);
        for s in 0..=steps {
            let t = s as f64 / steps as f64;
            let (x, y) = (pa[0] + t * (pb[0] - pa[0]), pa[1] + t * (pb[1] - pa[1]));
            if x >= 0.0 && y >= 0.0 && (x as usize) < self.size && (y as usize) < self.size {
                let idx = (self.size - 1 - y as usize) * self.size + x as usize;
                self.counts[idx] = self.counts[idx].max(1);
            }
        }
    }

    /// Whether a pixel is covered.
    pub fn covered(&self, col: usize, row: usize) -> bool {
        self.counts[row * self.size + col] > 0
    }

    /// The number of covered pixels.
    pub fn covered_count(&self) -> usize {
        self.counts.iter().filter(|&&c| c > 0).count()
    }

    /// The number of pixels covered more than once (overlaps of cells).
    pub fn overlap_count(&self) -> usize {
        self.counts.iter().filter(|&&c| c > 1).count()
    }

    /// The area of one pixel in plane units.
    pub fn pixel_area(&self) -> f64 {
        1.0 / (self.scale * self.scale)
    }

    /// Connected components of the covered pixels (8-connectivity) and holes: components of the
    /// uncovered pixels (4-connectivity, the dual of 8) that do not touch the border of the raster.
    /// A component of uncovered pixels counts as a hole only when it holds a 2×2 block of
    /// uncovered pixels. Pixel centres that happen to fall in a sliver narrower than one pixel —
    /// the tip of an acute notch or hole, such as the fans of thin cells at the corners of a face
    /// with corner spokes — form specks that 4-connectivity separates from the region they belong
    /// to; a 2×2 block of pixel centres is at least one pixel wide in every direction, so no such
    /// speck holds one. A real hole does: a hole whose inscribed disk has a radius above √2 pixels
    /// contains the 2×2 block around the pixel centre nearest to the disk's centre
    /// ([`crate::measure::MIN_HOLE_WIDTH`] chooses rasters that make it so).
    pub fn components_and_holes(&self) -> (usize, usize) {
        let n = self.size;
        let mut seen = vec![false; n * n];
        let mut stack: Vec<usize> = Vec::new();
        let (mut components, mut holes) = (0, 0);
        for start in 0..n * n {
            if seen[start] {
                continue;
            }
            let filled = self.counts[start] > 0;
            seen[start] = true;
            stack.push(start);
            let mut touches_border = false;
            let mut block = false;
            while let Some(i) = stack.pop() {
                let (r, c) = (i / n, i % n);
                if !filled && !block && r + 1 < n && c + 1 < n {
                    let free = |j: usize| self.counts[j] == 0;
                    // The 2×2 block with this pixel at its top left: a block's four pixels are
                    // 4-connected, so the component holding a block visits its top-left pixel.
                    block = free(i + 1) && free(i + n) && free(i + n + 1);
                }
                if r == 0 || c == 0 || r == n - 1 || c == n - 1 {
                    touches_border = true;
                }
                for dr in -1i64..=1 {
                    for dc in -1i64..=1 {
                        if (dr == 0 && dc == 0) || (!filled && dr != 0 && dc != 0) {
                            continue;
                        }
                        let (rr, cc) = (r as i64 + dr, c as i64 + dc);
                        if rr < 0 || cc < 0 || rr >= n as i64 || cc >= n as i64 {
                            continue;
                        }
                        let j = rr as usize * n + cc as usize;
                        if !seen[j] && (self.counts[j] > 0) == filled {
                            seen[j] = true;
                            stack.push(j);
                        }
                    }
                }
            }
            if filled {
                components += 1;
            } else if !touches_border && block {
                holes += 1;
            }
        }
        (components, holes)
    }

    /// Box counts of the covered set: for each k with `k_min ≤ k` and `2^k ≤ size`, the number of
    /// cells of the `2^k × 2^k` grid over the raster that contain a covered pixel. The raster size
    /// must be a power of two.
    pub fn box_counts(&self, k_min: u32) -> Vec<(u32, u64)> {
        let n = self.size;
        assert!(
            n.is_power_of_two(),
            "box counting needs a power-of-two raster"
        );
        let k_max = n.trailing_zeros();
        // Occupancy at the finest level, then halve the resolution k_max − k_min times.
        let mut occ: Vec<bool> = self.counts.iter().map(|&c| c > 0).collect();
        let mut side = n;
        let mut out = Vec::new();
        for k in (k_min..=k_max).rev() {
            out.push((k, occ.iter().filter(|&&b| b).count() as u64));
            if k == k_min {
                break;
            }
            let half = side / 2;
            let mut next = vec![false; half * half];
            for r in 0..side {
                for c in 0..side {
                    if occ[r * side + c] {
                        next[(r / 2) * half + c / 2] = true;
                    }
                }
            }
            occ = next;
            side = half;
        }
        out.reverse();
        out
    }
}

/// A least-squares line `y = slope·x + intercept` with the root-mean-square residual.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Fit {
    /// Slope.
    pub slope: f64,
    /// Intercept.
    pub intercept: f64,
    /// Root-mean-square residual of the fit.
    pub residual: f64,
}

/// Least-squares fit of a line through `(x, y)` pairs (at least two distinct x).
pub fn fit_line(data: &[(f64, f64)]) -> Fit {
    let n = data.len() as f64;
    let mx = data.iter().map(|d| d.0).sum::<f64>() / n;
    let my = data.iter().map(|d| d.1).sum::<f64>() / n;
    let sxx: f64 = data.iter().map(|d| (d.0 - mx) * (d.0 - mx)).sum();
    let sxy: f64 = data.iter().map(|d| (d.0 - mx) * (d.1 - my)).sum();
    let slope = if sxx > 0.0 { sxy / sxx } else { 0.0 };
    let intercept = my - slope * mx;
    let rss: f64 = data
        .iter()
        .map(|d| (d.1 - slope * d.0 - intercept).powi(2))
        .sum();
    Fit {
        slope,
        intercept,
        residual: (rss / n).sqrt(),
    }
}

/// The box-counting dimension of a raster's covered set: the least-squares slope of
/// `log N(k)` against `log 2^k` over `k_min ≤ k ≤ log2(size)`.
pub fn box_dimension(raster: &Raster, k_min: u32) -> Fit {
    let data: Vec<(f64, f64)> = raster
        .box_counts(k_min)
        .into_iter()
        .filter(|&(_, n)| n > 0)
        .map(|(k, n)| (k as f64 * std::f64::consts::LN_2, (n as f64).ln()))
        .collect();
    fit_line(&data)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shoelace_and_fill_agree_on_a_square() {
        let sq = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        assert_eq!(signed_area(&sq), 1.0);
        let mut bb = BBox::empty();
        sq.iter().for_each(|&p| bb.add(p));
        let mut r = Raster::fitting(bb, 256, 8);
        r.fill_polygon(&sq);
        let area = r.covered_count() as f64 * r.pixel_area();
        assert!((area - 1.0).abs() < 0.02, "{area}");
        assert_eq!(r.components_and_holes(), (1, 0));
    }

    /// Issue #20 item 4: a speck of uncovered pixels one pixel wide (pixel centres in a sliver
    /// narrower than a pixel) is not a hole; a 2×2 block is.
    #[test]
    fn hardening_04_specks_in_slivers_are_not_holes() {
        let mut r = Raster::unit(10);
        r.counts.fill(1);
        // A horizontal speck of 4 pixels (row 2, columns 1–4) and a diagonal one of 3.
        for c in 1..5 {
            r.counts[2 * 10 + c] = 0;
        }
        for k in 1..4 {
            r.counts[(4 + k) * 10 + k] = 0;
        }
        assert_eq!(r.components_and_holes(), (1, 0));
        // A 2×2 block (rows 6–7, columns 6–7) is one hole; joined to the horizontal speck through
        // a column of pixels, speck and block are one hole.
        for (row, col) in [(6, 6), (6, 7), (7, 6), (7, 7)] {
            r.counts[row * 10 + col] = 0;
        }
        assert_eq!(r.components_and_holes(), (1, 1));
        for row in 2..6 {
            r.counts[row * 10 + 6] = 0;
        }
        r.counts[2 * 10 + 5] = 0;
        assert_eq!(r.components_and_holes(), (1, 1));
    }

    #[test]
    fn shared_edges_do_not_overlap_and_a_ring_has_one_hole() {
        // A 3×3 block of unit squares without its middle one.
        let mut r = Raster::fitting(
            BBox {
                min: [0.0, 0.0],
                max: [3.0, 3.0],
            },
            128,
            4,
        );
        for i in 0..3 {
            for j in 0..3 {
                if (i, j) != (1, 1) {
                    let (x, y) = (i as f64, j as f64);
                    r.fill_polygon(&[[x, y], [x + 1.0, y], [x + 1.0, y + 1.0], [x, y + 1.0]]);
                }
            }
        }
        assert_eq!(r.overlap_count(), 0);
        assert_eq!(r.components_and_holes(), (1, 1));
    }

    #[test]
    fn line_fit_is_exact_on_a_line() {
        let f = fit_line(&[(0.0, 1.0), (1.0, 3.0), (2.0, 5.0)]);
        assert!((f.slope - 2.0).abs() < 1e-12 && f.residual < 1e-12);
    }

    #[test]
    fn bezier_ends_and_middle() {
        let c = [[0.0, 0.0], [1.0, 2.0], [2.0, 0.0]];
        assert_eq!(bezier_point(&c, 0.0), [0.0, 0.0]);
        assert_eq!(bezier_point(&c, 1.0), [2.0, 0.0]);
        assert_eq!(bezier_point(&c, 0.5), [1.0, 1.0]);
    }
}
