//! Adaptive flattening of Bézier edges for pictures: a curve is split in halves (de Casteljau)
//! until every piece's control polygon lies within a tolerance of its chord, so a picture's
//! polyline is never farther than the tolerance from the true curve, however the cell is scaled.
//!
//! The measures keep their fixed number of segments per edge (`segments`), which is part of what
//! they report; only the pictures use this.

use crate::geometry::point::Point;

/// Deepest halving: 2^16 pieces per edge at most, whatever the tolerance.
const MAX_DEPTH: u32 = 16;

/// Distance from `p` to the line through `a` and `b` (to `a` when they coincide).
fn distance_to_line(p: Point, a: Point, b: Point) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len = dx.hypot(dy);
    if len == 0.0 {
        return (p[0] - a[0]).hypot(p[1] - a[1]);
    }
    ((p[0] - a[0]) * dy - (p[1] - a[1]) * dx).abs() / len
}

/// Splits a Bézier curve at t = 1/2 into its two halves (de Casteljau).
fn halves(ctrl: &[Point]) -> (Vec<Point>, Vec<Point>) {
    let n = ctrl.len();
    let mut left = Vec::with_capacity(n);
    let mut right = Vec::with_capacity(n);
    let mut buf = ctrl.to_vec();
    left.push(buf[0]);
    right.push(buf[n - 1]);
    for level in 1..n {
        for i in 0..n - level {
            buf[i] = [
                0.5 * (buf[i][0] + buf[i + 1][0]),
                0.5 * (buf[i][1] + buf[i + 1][1]),
            ];
        }
        left.push(buf[0]);
        right.push(buf[n - 1 - level]);
    }
    right.reverse();
    (left, right)
}

/// Appends to `out` the points of the Bézier curve `ctrl` after its first point, ending with its
/// last: a polyline within `tolerance` of the curve (the curve lies in the convex hull of each
/// piece's control points, and every inner control point is within `tolerance` of the chord).
/// A curve of one or two control points is its chord.
pub fn flatten_bezier(ctrl: &[Point], tolerance: f64, out: &mut Vec<Point>) {
    fn rec(ctrl: &[Point], tol: f64, depth: u32, out: &mut Vec<Point>) {
        let (a, b) = (ctrl[0], ctrl[ctrl.len() - 1]);
        let flat = ctrl[1..ctrl.len() - 1]
            .iter()
            .all(|&p| distance_to_line(p, a, b) <= tol);
        // A chord of length zero with inner points off it (a loop) is not flat.
        if (flat && (a != b || ctrl.iter().all(|&p| p == a))) || depth >= MAX_DEPTH {
            out.push(b);
            return;
        }
        let (l, r) = halves(ctrl);
        rec(&l, tol, depth + 1, out);
        rec(&r, tol, depth + 1, out);
    }
    match ctrl.len() {
        0 => {}
        1 | 2 => out.push(ctrl[ctrl.len() - 1]),
        _ => rec(ctrl, tolerance.max(1e-12), 0, out),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::point::bezier_point;

    #[test]
    fn a_quarter_circle_like_arc_is_within_the_tolerance_and_tighter_means_more_points() {
        let ctrl = [[1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        let mut coarse = vec![ctrl[0]];
        flatten_bezier(&ctrl, 0.01, &mut coarse);
        let mut fine = vec![ctrl[0]];
        flatten_bezier(&ctrl, 0.0001, &mut fine);
        assert!(fine.len() > coarse.len(), "{} {}", fine.len(), coarse.len());
        assert_eq!(*coarse.last().unwrap(), ctrl[2]);
        // Every curve point is within the tolerance of the polyline.
        for k in 0..=200 {
            let p = bezier_point(&ctrl, k as f64 / 200.0);
            let d = coarse
                .windows(2)
                .map(|w| {
                    let (a, b) = (w[0], w[1]);
                    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
                    let t = (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (dx * dx + dy * dy))
                        .clamp(0.0, 1.0);
                    (p[0] - a[0] - t * dx).hypot(p[1] - a[1] - t * dy)
                })
                .fold(f64::INFINITY, f64::min);
            assert!(d <= 0.01, "point {k} is {d} from the polyline");
        }
    }

    #[test]
    fn a_straight_curve_is_one_segment_and_a_loop_is_split() {
        let mut out = Vec::new();
        flatten_bezier(&[[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]], 0.1, &mut out);
        assert_eq!(out, vec![[2.0, 0.0]]);
        let mut out = Vec::new();
        flatten_bezier(&[[0.0, 0.0], [1.0, 1.0], [0.0, 0.0]], 0.1, &mut out);
        // The curve goes out to (1/2, 1/2) at t = 1/2 and back: not its zero-length chord.
        assert_eq!(out, vec![[0.5, 0.5], [0.0, 0.0]]);
    }
}
