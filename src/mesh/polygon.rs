//! Polygons in the plane: ear clipping, for the cells of the 2D prisms and for the boundary faces
//! of volumes that are not star-shaped from their centre.

/// Triangulates a simple counter-clockwise polygon by ear clipping (O(n²); cells have few
/// vertices). Returns index triples, counter-clockwise. Written by hand: a dozen lines, where a
/// triangulation crate would bring far more than a cell needs.
///
/// A corner is an ear when it turns left by more than a relative tolerance (`1e-10` of the
/// squared size of the polygon) and no other vertex lies in its triangle: three points in line
/// up to rounding (the pieces of a straight edge, issue #31) are never clipped as a triangle of
/// no area while a proper ear exists. When none does (a polygon degenerate beyond rounding), the
/// corner that turns left the most is clipped.
pub fn triangulate(poly: &[[f64; 2]]) -> Vec<[usize; 3]> {
    let cross = |a: [f64; 2], b: [f64; 2], c: [f64; 2]| {
        (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    };
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in poly {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let size = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(0.0);
    let tol = 1e-10 * size * size;
    let mut idx: Vec<usize> = (0..poly.len()).collect();
    let mut out = Vec::with_capacity(poly.len().saturating_sub(2));
    while idx.len() > 3 {
        let n = idx.len();
        let corner = |k: usize| {
            (
                poly[idx[(k + n - 1) % n]],
                poly[idx[k]],
                poly[idx[(k + 1) % n]],
            )
        };
        let ear = (0..n).find(|&k| {
            let (a, b, c) = corner(k);
            if cross(a, b, c) <= tol {
                return false; // reflex, or in line up to rounding
            }
            // No other vertex inside the triangle (a, b, c).
            idx.iter().all(|&j| {
                let p = poly[j];
                p == a
                    || p == b
                    || p == c
                    || cross(a, b, p) < 0.0
                    || cross(b, c, p) < 0.0
                    || cross(c, a, p) < 0.0
            })
        });
        let k = ear.unwrap_or_else(|| {
            (0..n)
                .max_by(|&x, &y| {
                    let (a, b, c) = corner(x);
                    let (d, e, f) = corner(y);
                    cross(a, b, c).total_cmp(&cross(d, e, f))
                })
                .unwrap_or(0)
        });
        out.push([idx[(k + n - 1) % n], idx[k], idx[(k + 1) % n]]);
        idx.remove(k);
    }
    if idx.len() == 3 {
        out.push([idx[0], idx[1], idx[2]]);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn area(poly: &[[f64; 2]], t: [usize; 3]) -> f64 {
        let [a, b, c] = t.map(|i| poly[i]);
        ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])) / 2.0
    }

    #[test]
    fn points_in_line_are_not_clipped_as_flat_triangles() {
        // A triangle whose bottom edge carries three more points, one of them off the line by
        // rounding only: 6 vertices, 4 triangles, each of positive area, summing to the whole
        // (base 4, height 2: area 4).
        let poly = [
            [0.0, 0.0],
            [1.0, 1e-17],
            [2.0, 0.0],
            [3.0, -1e-17],
            [4.0, 0.0],
            [2.0, 2.0],
        ];
        let t = triangulate(&poly);
        assert_eq!(t.len(), 4);
        assert!(t.iter().all(|&x| area(&poly, x) > 1e-6), "{t:?}");
        let total: f64 = t.iter().map(|&x| area(&poly, x)).sum();
        assert!((total - 4.0).abs() < 1e-12);
    }

    #[test]
    fn an_l_shape_is_cut_into_four_triangles_of_its_area() {
        // The L of issue #31's failing face: the unit square minus its upper-right quarter,
        // area 3/4, six corners, four triangles.
        let poly = [
            [0.0, 0.0],
            [1.0, 0.0],
            [1.0, 0.5],
            [0.5, 0.5],
            [0.5, 1.0],
            [0.0, 1.0],
        ];
        let t = triangulate(&poly);
        assert_eq!(t.len(), 4);
        assert!(t.iter().all(|&x| area(&poly, x) > 0.0));
        let total: f64 = t.iter().map(|&x| area(&poly, x)).sum();
        assert!((total - 0.75).abs() < 1e-12);
    }
}
