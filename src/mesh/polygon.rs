//! Polygons in the plane: ear clipping, for the cells of the 2D prisms and for the boundary faces
//! of volumes that are not star-shaped from their centre.

/// Triangulates a simple counter-clockwise polygon by ear clipping (O(n²); cells have few
/// vertices). Returns index triples, counter-clockwise. Written by hand: a dozen lines, where a
/// triangulation crate would bring far more than a cell needs.
pub fn triangulate(poly: &[[f64; 2]]) -> Vec<[usize; 3]> {
    let cross = |a: [f64; 2], b: [f64; 2], c: [f64; 2]| {
        (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    };
    let mut idx: Vec<usize> = (0..poly.len()).collect();
    let mut out = Vec::with_capacity(poly.len().saturating_sub(2));
    while idx.len() > 3 {
        let n = idx.len();
        let ear = (0..n).find(|&k| {
            let (a, b, c) = (
                poly[idx[(k + n - 1) % n]],
                poly[idx[k]],
                poly[idx[(k + 1) % n]],
            );
            if cross(a, b, c) <= 0.0 {
                return false; // reflex or degenerate corner
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
        // A degenerate polygon (collinear rest) has no strict ear: clip any corner.
        let k = ear.unwrap_or(0);
        out.push([idx[(k + n - 1) % n], idx[k], idx[(k + 1) % n]]);
        idx.remove(k);
    }
    if idx.len() == 3 {
        out.push([idx[0], idx[1], idx[2]]);
    }
    out
}
