//! The template of a face type (see [`crate::geometry::instantiate`]): its control points on a regular
//! polygon and the target position of every level-1 control point, plus mean value coordinates.

use crate::geometry::options::InstantiateOptions;
use crate::geometry::point::Point;
use crate::{
    topology::EdgeKind, topology::EdgeType, topology::Face, topology::FaceType,
    topology::JunctionKind, topology::Origin, topology::TypeSet,
};
use num_traits::ToPrimitive;
use std::f64::consts::PI;

fn to_f64(r: &num_rational::BigRational) -> f64 {
    r.to_f64().unwrap_or(f64::NAN)
}

pub(crate) fn dim_of(e: &EdgeType, q: usize) -> usize {
    match e.kind {
        EdgeKind::B => q + 1,
        EdgeKind::C => 2,
    }
}

pub(crate) fn lerp(a: Point, b: Point, t: f64) -> Point {
    [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]
}

/// The control points of a face whose corners are `corners` (edge i from corner i to i + 1),
/// every edge straight with its inner points evenly spaced — except in a face of two edges (a
/// digon, flat if both were straight), whose Bézier inner points are pushed outwards (to the right
/// of the edge) by [`DIGON_BULGE`] times the chord, so that the face has an area.
pub fn control_points(face: &Face, corners: &[Point], q: usize) -> Vec<Point> {
    let n = corners.len();
    let mut pts = Vec::new();
    for (i, e) in face.boundary.iter().enumerate() {
        let d = dim_of(e, q);
        let (a, b) = (corners[i], corners[(i + 1) % n]);
        for c in 0..d - 1 {
            let t = c as f64 / (d - 1) as f64;
            let mut p = lerp(a, b, t);
            if n == 2 && c > 0 {
                // Outward normal of a counter-clockwise face: the edge direction turned right.
                let h = DIGON_BULGE * 4.0 * t * (1.0 - t);
                p[0] += h * (b[1] - a[1]);
                p[1] -= h * (b[0] - a[0]);
            }
            pts.push(p);
        }
    }
    pts
}

/// How far the Bézier inner points of a digon's edges are pushed out, relative to the chord (at
/// the middle of the edge; less towards its ends).
pub const DIGON_BULGE: f64 = 0.5;

/// How far the inner points of the two sides of a two-sided lacuna are pushed apart, relative to
/// the chord: less than a digon face's bulge, so that the lens's tips, where the spokes meet it,
/// are not so sharp that the cells around them fold a few levels down.
pub const LENS_BULGE: f64 = 0.25;

/// The corners of a regular n-gon of circumradius 1 centred at the origin, edge 0 at the bottom.
/// For n = 2 (a digon, see [`control_points`]) the chord is raised by a quarter so that the origin
/// lies inside the face once its Bézier edge bulges downwards.
pub fn regular_polygon(n: usize) -> Vec<Point> {
    if n == 2 {
        return vec![[-1.0, 0.25], [1.0, 0.25]];
    }
    (0..n)
        .map(|i| {
            let a = -PI / 2.0 - PI / n as f64 + 2.0 * PI * i as f64 / n as f64;
            [a.cos(), a.sin()]
        })
        .collect()
}

/// The parameter range of piece `k` of an edge (in [0, 1] along the edge).
/// The parameter range of piece `k` of an edge (in [0, 1] along the edge); `g` is the Cantor gap
/// ratio.
fn piece_range(e: &EdgeType, k: usize, g: f64) -> (f64, f64) {
    if e.is_delayed() {
        return (0.0, 1.0);
    }
    let n = e.n as f64;
    match e.kind {
        EdgeKind::B => (k as f64 / n, (k + 1) as f64 / n),
        EdgeKind::C => {
            let p = 1.0 / (n + (n - 1.0) * g);
            let lo = k as f64 * (p + g * p);
            (lo, lo + p)
        }
    }
}

/// The template of a face type: its control points on the regular polygon and, per sub-face, the
/// target position of each control point of the sub-face.
pub(crate) fn template(
    ty: &FaceType,
    types: &TypeSet,
    q: usize,
    opt: &InstantiateOptions,
) -> Template {
    let face = &ty.face;
    let n = face.boundary.len();
    let corners = regular_polygon(n);
    let points = control_points(face, &corners, q);
    // Edge i's control points; a digon's bulging Bézier edges are followed along the curve (on a
    // straight edge with evenly spaced points the curve is the chord, so others use the chord).
    let mut edge_ctrl: Vec<Vec<Point>> = Vec::new();
    let mut off = 0;
    for e in &face.boundary {
        let d = dim_of(e, q);
        edge_ctrl.push((0..d).map(|c| points[(off + c) % points.len()]).collect());
        off += d - 1;
    }
    let at = |i: usize, s: f64| {
        if n == 2 {
            crate::geometry::point::bezier_point(&edge_ctrl[i], s)
        } else {
            lerp(corners[i], corners[(i + 1) % n], s)
        }
    };
    let g = to_f64(&opt.cantor_gap);
    let gap_point = |i: usize, k: usize| {
        let e = &face.boundary[i];
        let (a, b) = (piece_range(e, k, g).1, piece_range(e, k + 1, g).0);
        let mid = at(i, (a + b) / 2.0);
        [mid[0] * opt.gap_depth, mid[1] * opt.gap_depth]
    };
    // The pieces of the subdivided boundary, in order: junction m follows piece m.
    let mut pieces = Vec::new();
    for (i, e) in face.boundary.iter().enumerate() {
        for k in 0..e.piece_count() as usize {
            pieces.push((i, k));
        }
    }
    let sub = &ty.subdivision;
    let junction_point = |m: usize| -> Point {
        let (i, k) = pieces[m];
        match sub.junctions[m].kind {
            JunctionKind::Corner => corners[(i + 1) % n],
            JunctionKind::Joint => at(i, piece_range(&face.boundary[i], k, g).1),
            JunctionKind::Gap => gap_point(i, k),
        }
    };
    let lacuna: Vec<Point> = sub
        .spokes
        .iter()
        .map(|&m| {
            let p = junction_point(m);
            [p[0] * opt.lacuna_scale, p[1] * opt.lacuna_scale]
        })
        .collect();
    let s = lacuna.len().max(1);
    let mut targets = Vec::new();
    for (k, sf) in sub.subfaces.iter().enumerate() {
        let w = ty.children[k];
        let wface = &types.types[w].face;
        let mut pts = Vec::new();
        for (l, o) in sf.origins.iter().enumerate() {
            // A lacuna of two sides (two spokes) would be a slit between two straight sides on
            // one chord: its sides bulge away from each other, like a digon's edges, so that the
            // fitted point of the solution space has a lacuna of positive area (issue #36).
            let lens = s == 2 && matches!(o, Origin::Lacuna { .. });
            let (a, b) = match *o {
                Origin::Piece { edge, piece } => {
                    let (s0, s1) = piece_range(&face.boundary[edge], piece, g);
                    (at(edge, s0), at(edge, s1))
                }
                Origin::Spoke { spoke, inward } => {
                    let p = junction_point(sub.spokes[spoke]);
                    if inward {
                        (p, lacuna[spoke])
                    } else {
                        (lacuna[spoke], p)
                    }
                }
                Origin::Lacuna { side } => (lacuna[(side + 1) % s], lacuna[side]),
                Origin::GapSide { edge, gap, after } => {
                    let e = &face.boundary[edge];
                    let gp = gap_point(edge, gap);
                    if after {
                        (gp, at(edge, piece_range(e, gap + 1, g).0))
                    } else {
                        (at(edge, piece_range(e, gap, g).1), gp)
                    }
                }
            };
            let d = dim_of(&wface.boundary[l], q);
            for c in 0..d - 1 {
                let t = c as f64 / (d - 1) as f64;
                let mut p = lerp(a, b, t);
                if lens && c > 0 {
                    // The sub-face lies on the left of its lacuna side a → b, the lacuna on the
                    // right: the side's inner points move left, into the sub-face.
                    let h = LENS_BULGE * 4.0 * t * (1.0 - t);
                    p[0] -= h * (b[1] - a[1]);
                    p[1] += h * (b[0] - a[0]);
                }
                pts.push(p);
            }
        }
        targets.push(pts);
    }
    Template { points, targets }
}

pub(crate) struct Template {
    pub(crate) points: Vec<Point>,
    pub(crate) targets: Vec<Vec<Point>>,
}

/// Mean value coordinates of `x` in the polygon `poly` (linear interpolation on its edges).
pub(crate) fn mean_value(poly: &[Point], x: Point) -> Vec<f64> {
    let m = poly.len();
    let mut w = vec![0.0; m];
    if m < 3 {
        w.iter_mut().for_each(|v| *v = 1.0 / m as f64);
        return w;
    }
    for j in 0..m {
        let (a, b) = (poly[j], poly[(j + 1) % m]);
        let ab = [b[0] - a[0], b[1] - a[1]];
        let len2 = ab[0] * ab[0] + ab[1] * ab[1];
        if len2 == 0.0 {
            continue;
        }
        let t = ((x[0] - a[0]) * ab[0] + (x[1] - a[1]) * ab[1]) / len2;
        let foot = lerp(a, b, t);
        if (-1e-12..=1.0 + 1e-12).contains(&t) && crate::geometry::point::distance(foot, x) < 1e-9 {
            let t = t.clamp(0.0, 1.0);
            w[j] += 1.0 - t;
            w[(j + 1) % m] += t;
            return w;
        }
    }
    let s: Vec<Point> = poly.iter().map(|p| [p[0] - x[0], p[1] - x[1]]).collect();
    let r: Vec<f64> = s.iter().map(|v| v[0].hypot(v[1])).collect();
    let tan_half = |j: usize| {
        let (a, b) = (s[j], s[(j + 1) % m]);
        let cross = a[0] * b[1] - a[1] * b[0];
        let dot = a[0] * b[0] + a[1] * b[1];
        cross / (r[j] * r[(j + 1) % m] + dot)
    };
    for j in 0..m {
        w[j] = (tan_half((j + m - 1) % m) + tan_half(j)) / r[j];
    }
    let total: f64 = w.iter().sum();
    w.iter_mut().for_each(|v| *v /= total);
    w
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mean_value_coordinates_reproduce_points() {
        let poly = regular_polygon(6);
        for x in [[0.1, 0.2], [0.0, 0.0], [-0.3, 0.5]] {
            let w = mean_value(&poly, x);
            let p = w.iter().zip(&poly).fold([0.0, 0.0], |acc, (wi, pi)| {
                [acc[0] + wi * pi[0], acc[1] + wi * pi[1]]
            });
            assert!((p[0] - x[0]).abs() < 1e-12 && (p[1] - x[1]).abs() < 1e-12);
            assert!(w.iter().all(|&v| v > 0.0));
        }
        let mid = lerp(poly[1], poly[2], 0.25);
        let w = mean_value(&poly, mid);
        assert!((w[1] - 0.75).abs() < 1e-12 && (w[2] - 0.25).abs() < 1e-12);
    }
}
