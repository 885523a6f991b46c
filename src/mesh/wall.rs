//! A lower bound on the wall thickness of a closed triangle mesh (GEOMETRY §5, "Wall thickness").
//!
//! **The bound.** The least distance between two triangles of one part that share no vertex and
//! face each other (outward normals with `n1·n2 < 0`).
//!
//! **Why it is a bound on every ray-sampled thickness.** A ray-sampled thickness is the distance
//! from a point `x` of a triangle `T1` along its inward normal `d = −n1/|n1|` to the first
//! triangle `T2` the ray meets. On a closed, oriented surface that does not cross itself, the ray
//! starts into the material, so the first triangle it meets is left from the inside: `d·n2 ≥ 0`,
//! i.e. `n1·n2 ≤ 0` (equality only for a ray that grazes `T2`). The hit point `y` lies on `T2`,
//! so `|x − y| ≥ dist(T1, T2)`. Hence, whenever `T2` shares no vertex with `T1`, the sampled
//! thickness is at least the least distance over the facing pairs, whatever the sample points.
//! Pairs with a shared vertex are left out because their distance is 0 (a sharp edge of the solid
//! is not a thin wall); a ray whose first hit is such a neighbour is not bounded by this figure.
//! Perpendicular pairs are left out too (at a re-entrant edge two perpendicular walls come close
//! without being a wall): the test is `n1·n2 < −FACING·|n1|·|n2|`, with [`FACING`] = 1e-9, so the
//! sign is never one that rounding of the normals (computed in `f64` from the `f32` coordinates,
//! relative error below 1e-12) could have flipped. The rays left uncovered are those that meet
//! their first triangle within 1e-9 rad of grazing it; a ray exactly along a face never leaves it
//! through that face.
//!
//! **Material between, not air.** Two walls can face each other across a gap of air too (the
//! inner sides of a U). Such a pair is left out when one triangle lies wholly on the outer side of
//! the other's plane: a ray hit gives points `x ∈ T1`, `y ∈ T2` with `(y − x)·n1 < 0` and
//! `(x − y)·n2 < 0`, so some vertex of `T2` is strictly behind `T1`'s plane and some vertex of `T1`
//! behind `T2`'s (a convex combination of the vertices is), and the pairs kept still include
//! every ray hit. The test keeps a pair when a vertex is less than 1e-7 mm in front of the plane,
//! far above the rounding of the signed distances.
//!
//! **Error.** The distance of two triangles is the least of the 6 vertex–triangle and 9
//! edge–edge distances (Ericson, *Real-Time Collision Detection*, 5.1.5 and 5.1.9) when they do
//! not meet; when they do, the exact predicates of the self-intersection test see it and the
//! distance is 0. Each candidate distance is the distance between two points of the triangles
//! computed in `f64` from the `f32` coordinates written, so it exceeds the true least distance by
//! rounding only: a few ulps of the coordinates, under 1e-12 mm for coordinates below 10⁴ mm.
//! The reported bound is the computed least distance minus [`MARGIN`] mm, which covers that.
//!
//! **Cost.** A [`Bvh`] over the triangles: each triangle visits only the boxes nearer than the
//! least distance found so far.

use super::bvh::{Aabb, Bvh};
use super::solid::Part;

/// The least cosine of the angle between the outward normals' opposites for a pair to count as
/// facing: `n1·n2 < −FACING·|n1|·|n2|` (see the module doc: rays meeting their first triangle within
/// this of grazing are the only ones the bound does not cover).
pub const FACING: f64 = 1e-9;

/// Millimetres subtracted from the computed least distance to cover its rounding.
pub const MARGIN: f64 = 1e-6;

type V = [f64; 3];

fn sub(a: V, b: V) -> V {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn add(a: V, b: V) -> V {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn scale(a: V, s: f64) -> V {
    [a[0] * s, a[1] * s, a[2] * s]
}

fn dot(a: V, b: V) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: V, b: V) -> V {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn norm(a: V) -> f64 {
    dot(a, a).sqrt()
}

/// The point of triangle `abc` nearest to `p` (Ericson 5.1.5, by Voronoi regions).
pub fn closest_on_triangle(p: V, a: V, b: V, c: V) -> V {
    let (ab, ac, ap) = (sub(b, a), sub(c, a), sub(p, a));
    let (d1, d2) = (dot(ab, ap), dot(ac, ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = sub(p, b);
    let (d3, d4) = (dot(ab, bp), dot(ac, bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = d1 / (d1 - d3);
        return add(a, scale(ab, v));
    }
    let cp = sub(p, c);
    let (d5, d6) = (dot(ab, cp), dot(ac, cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = d2 / (d2 - d6);
        return add(a, scale(ac, w));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return add(b, scale(sub(c, b), w));
    }
    let denom = va + vb + vc;
    if denom == 0.0 || !denom.is_finite() {
        // A degenerate triangle: the nearest of its edges' points.
        let cands = [
            closest_on_segment(p, a, b),
            closest_on_segment(p, b, c),
            closest_on_segment(p, c, a),
        ];
        return cands
            .into_iter()
            .min_by(|x, y| norm(sub(p, *x)).total_cmp(&norm(sub(p, *y))))
            .unwrap_or(a);
    }
    let (v, w) = (vb / denom, vc / denom);
    add(a, add(scale(ab, v), scale(ac, w)))
}

fn closest_on_segment(p: V, a: V, b: V) -> V {
    let ab = sub(b, a);
    let l = dot(ab, ab);
    if l == 0.0 {
        return a;
    }
    let t = (dot(sub(p, a), ab) / l).clamp(0.0, 1.0);
    add(a, scale(ab, t))
}

/// The distance between the segments `p1 q1` and `p2 q2` (Ericson 5.1.9), as the distance of two
/// points of the segments.
pub fn segment_distance(p1: V, q1: V, p2: V, q2: V) -> f64 {
    let (d1, d2, r) = (sub(q1, p1), sub(q2, p2), sub(p1, p2));
    let (a, e, f) = (dot(d1, d1), dot(d2, d2), dot(d2, r));
    let (s, t);
    if a == 0.0 && e == 0.0 {
        return norm(r);
    }
    if a == 0.0 {
        s = 0.0;
        t = (f / e).clamp(0.0, 1.0);
    } else {
        let c = dot(d1, r);
        if e == 0.0 {
            t = 0.0;
            s = (-c / a).clamp(0.0, 1.0);
        } else {
            let b = dot(d1, d2);
            let denom = a * e - b * b;
            let s0 = if denom > 0.0 {
                ((b * f - c * e) / denom).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let t0 = (b * s0 + f) / e;
            if t0 < 0.0 {
                t = 0.0;
                s = (-c / a).clamp(0.0, 1.0);
            } else if t0 > 1.0 {
                t = 1.0;
                s = ((b - c) / a).clamp(0.0, 1.0);
            } else {
                t = t0;
                s = s0;
            }
        }
    }
    norm(sub(add(p1, scale(d1, s)), add(p2, scale(d2, t))))
}

/// The distance between two triangles that do not meet: the least of the vertex–triangle and
/// edge–edge distances (for triangles that do not meet, the nearest pair of points has one of
/// them at a vertex or both on edges).
pub fn triangle_distance(s: &[V; 3], t: &[V; 3]) -> f64 {
    let mut best = f64::INFINITY;
    for p in s {
        best = best.min(norm(sub(*p, closest_on_triangle(*p, t[0], t[1], t[2]))));
    }
    for p in t {
        best = best.min(norm(sub(*p, closest_on_triangle(*p, s[0], s[1], s[2]))));
    }
    for i in 0..3 {
        for j in 0..3 {
            best = best.min(segment_distance(s[i], s[(i + 1) % 3], t[j], t[(j + 1) % 3]));
        }
    }
    best
}

/// Whether a vertex of `t` is behind (or within 1e-7 of) the plane through `a` with outward
/// normal `n` of length `len`.
fn behind(t: &[V; 3], a: V, n: V, len: f64) -> bool {
    t.iter().any(|v| dot(sub(*v, a), n) < 1e-7 * len)
}

/// The wall bound of the parts and the pair of triangles that attains it ((part, triangle),
/// (part, triangle)); none when no part has two facing triangles that share no vertex.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WallBound {
    /// Every ray-sampled wall thickness is at least this, in the mesh's units (mm), after the
    /// rounding margin.
    pub thickness: f64,
    /// The part and the two triangles at the least distance.
    pub pair: (usize, usize, usize),
}

/// The least distance between two triangles of one part that share no vertex and face each other
/// (see the module doc), minus [`MARGIN`], with the pair attaining it.
pub fn wall_bound(parts: &[Part]) -> Option<WallBound> {
    let mut best: Option<(f64, (usize, usize, usize))> = None;
    for (pi, p) in parts.iter().enumerate() {
        let tris: Vec<[V; 3]> = p
            .triangles
            .iter()
            .map(|t| t.map(|v| p.vertices[v as usize].map(f64::from)))
            .collect();
        let normals: Vec<V> = tris
            .iter()
            .map(|t| cross(sub(t[1], t[0]), sub(t[2], t[0])))
            .collect();
        let bvh = Bvh::new(tris.iter().map(Aabb::of).collect());
        let least = std::cell::Cell::new(best.map_or(f64::INFINITY, |b| b.0));
        for i in 0..tris.len() {
            let ni = normals[i];
            let li = norm(ni);
            if li == 0.0 {
                continue;
            }
            let ti = p.triangles[i];
            bvh.near(
                bvh.item_box(i),
                || least.get(),
                |j| {
                    // Each pair once: when `j < i` the pair was seen from `j` under a limit no
                    // lower than now, so it was measured then or is pruned now anyway.
                    if j <= i || p.triangles[j].iter().any(|v| ti.contains(v)) {
                        return;
                    }
                    let nj = normals[j];
                    if dot(ni, nj) >= -FACING * li * norm(nj) {
                        return;
                    }
                    if !behind(&tris[j], tris[i][0], ni, li)
                        || !behind(&tris[i], tris[j][0], nj, norm(nj))
                    {
                        return;
                    }
                    let mut d = triangle_distance(&tris[i], &tris[j]);
                    if d < least.get() && super::volume::triangles_meet(&tris[i], &tris[j]) {
                        d = 0.0;
                    }
                    if d < least.get() {
                        least.set(d);
                        best = Some((d, (pi, i, j)));
                    }
                },
            );
        }
    }
    best.map(|(d, pair)| WallBound {
        thickness: (d - MARGIN).max(0.0),
        pair,
    })
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// The closed surface of a union of cells of a grid with lines at `xs`, `ys`, `zs`
    /// (`filled(i, j, k)` for the cell between lines i, i + 1 …): a quad, two triangles, on every
    /// cell side between a filled cell and an empty one, counter-clockwise seen from outside.
    /// Vertices are the grid points, so cells sharing a side share its vertices.
    pub(crate) fn voxels(lines: [&[f64]; 3], filled: impl Fn([usize; 3]) -> bool) -> Part {
        let n = lines.map(|l| l.len());
        let id = |p: [usize; 3]| (p[0] * n[1] * n[2] + p[1] * n[2] + p[2]) as u32;
        let mut vertices = Vec::new();
        for i in 0..n[0] {
            for j in 0..n[1] {
                for k in 0..n[2] {
                    vertices.push([lines[0][i] as f32, lines[1][j] as f32, lines[2][k] as f32]);
                }
            }
        }
        let full = |c: [isize; 3]| {
            (0..3).all(|a| c[a] >= 0 && (c[a] as usize) + 1 < n[a]) && filled(c.map(|x| x as usize))
        };
        let mut triangles = Vec::new();
        for a in 0..3 {
            let (b, c) = ((a + 1) % 3, (a + 2) % 3);
            // The side at plane index p across axis a, cell (u, v) in axes (b, c).
            for p in 0..n[a] {
                for u in 0..n[b] - 1 {
                    for v in 0..n[c] - 1 {
                        let mut below = [0isize; 3];
                        below[a] = p as isize - 1;
                        below[b] = u as isize;
                        below[c] = v as isize;
                        let mut above = below;
                        above[a] = p as isize;
                        let (lo, hi) = (full(below), full(above));
                        if lo == hi {
                            continue;
                        }
                        let corner = |du: usize, dv: usize| {
                            let mut q = [0usize; 3];
                            q[a] = p;
                            q[b] = u + du;
                            q[c] = v + dv;
                            id(q)
                        };
                        // e_b × e_c = e_a: counter-clockwise in (b, c) faces +a.
                        let mut quad = [corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)];
                        if hi {
                            quad.reverse();
                        }
                        triangles.push([quad[0], quad[1], quad[2]]);
                        triangles.push([quad[0], quad[2], quad[3]]);
                    }
                }
            }
        }
        Part {
            vertices,
            triangles,
            holes: None,
        }
    }

    #[test]
    fn triangle_distances_by_hand() {
        let t = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        // A parallel copy 0.5 above: distance 0.5.
        let up = t.map(|p| [p[0], p[1], 0.5]);
        assert_eq!(triangle_distance(&t, &up), 0.5);
        // A triangle whose lowest edge runs above the origin at height 2, across the first: the
        // nearest points are the origin and the middle of that edge, 2 apart.
        let e = [[-1.0, 1.0, 2.0], [1.0, -1.0, 2.0], [0.0, 0.0, 3.0]];
        assert!((triangle_distance(&t, &e) - 2.0).abs() < 1e-15);
        // Two crossing segments, one 1 above the other.
        assert_eq!(
            segment_distance([0.0; 3], [1.0, 0.0, 0.0], [0.5, 1.0, 1.0], [0.5, -1.0, 1.0]),
            1.0
        );
    }

    #[test]
    fn a_slab_of_thickness_h_has_wall_bound_h() {
        // A closed box 10 × 10 × h: its facing pairs that share no vertex are across the slab
        // (top against bottom, h apart) or across the box (10 apart), so the bound is h.
        for h in [0.25, 1.5] {
            let part = voxels([&[0.0, 10.0], &[0.0, 10.0], &[0.0, h]], |_| true);
            crate::mesh::check_part(&part).unwrap();
            let b = wall_bound(&[part]).unwrap();
            assert!(
                (b.thickness - h).abs() <= MARGIN + 1e-6,
                "h = {h}: {}",
                b.thickness
            );
        }
    }

    #[test]
    fn two_cubes_joined_by_a_thin_neck_have_the_neck_as_wall() {
        // Two 4 mm cubes, x in [0, 4] and [10, 14], joined by a bar x in [4, 10], y in [1, 3],
        // z in [1.85, 2.15]: one closed surface of genus 0. Facing pairs that share no vertex:
        // the bar's top and bottom (0.3 apart), its two sides (2 apart), a cube's opposite
        // sides (4), the cubes' facing sides (6), the bar's top or bottom against a cube's
        // bottom or top (at least 1.85). Perpendicular walls at the re-entrant edges where the
        // bar meets a cube are not facing. So the bound is the neck's thickness, 0.3 mm.
        let neck = 0.3;
        let z = [0.0, 1.85, 1.85 + neck, 4.0];
        let part = voxels([&[0.0, 4.0, 10.0, 14.0], &[0.0, 1.0, 3.0, 4.0], &z], |c| {
            c[0] != 1 || (c[1] == 1 && c[2] == 1)
        });
        let check = crate::mesh::check_part(&part).unwrap();
        assert_eq!((check.components, check.euler), (1, 2));
        let b = wall_bound(std::slice::from_ref(&part)).unwrap();
        assert!(
            (b.thickness - neck).abs() <= 1e-6 + MARGIN,
            "{}",
            b.thickness
        );
        // Thickening the neck to 1 mm moves the bound to 1 mm.
        let z = [0.0, 1.5, 2.5, 4.0];
        let part = voxels([&[0.0, 4.0, 10.0, 14.0], &[0.0, 1.0, 3.0, 4.0], &z], |c| {
            c[0] != 1 || (c[1] == 1 && c[2] == 1)
        });
        let b = wall_bound(&[part]).unwrap();
        assert!(
            (b.thickness - 1.0).abs() <= 1e-6 + MARGIN,
            "{}",
            b.thickness
        );
    }
}
