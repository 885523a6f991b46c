//! No two triangles cross. Two non-degenerate triangles may meet only in what they share: nothing,
//! one vertex, or one edge. The test, for every pair whose closed bounding boxes meet (found
//! through a uniform grid), with exact predicates ([`super::exact`]):
//!
//! - **no shared vertex**: the closed triangles must be disjoint. Two closed triangles meet iff a
//!   side of one meets the other (if they meet, an end point of their intersection lies on a
//!   side of one of them), so the six side–triangle tests decide it, touching included;
//! - **one shared vertex `v`** (`v a b` and `v c d`): they must meet only in `v`. If they meet
//!   in another point `x`, the segment `v x` lies in both, and the point where the ray from `v`
//!   through `x` leaves the smaller of them lies on its side opposite `v` and in the other
//!   triangle; so the test is: side `a b` against `v c d`, and side `c d` against `v a b`
//!   (this covers the coplanar case, overlapping fans);
//! - **one shared edge `u v`** (third corners `p` and `q`): when `p`, `q`, `u`, `v` are not
//!   coplanar the planes meet in the line `u v` and the triangles meet in the edge only; when
//!   they are coplanar the triangles overlap unless `p` and `q` lie on opposite sides of the
//!   line `u v` (a fold flat onto itself is a crossing);
//! - **three shared vertices**: the same triangle twice, which always overlaps.
//!
//! Degenerate triangles are reported by their own check and left out of this one. The grid only
//! chooses which pairs are compared: a triangle is put in every cell its box meets, cell indices
//! come from a monotone function of the coordinates (so boxes that meet always share a cell,
//! whatever the rounding of that function), and each pair is compared once, in the first cell
//! both boxes meet; whether two boxes meet is then decided by comparing coordinates, which is
//! exact.

use super::exact::{exactly, normal_axis, orient2d, orient3d, segment_meets_triangle, Point};
use super::incidence::finding;
use super::input::Mesh;
use super::report::Tally;

/// The most cells along one axis of the grid.
const MAX_CELLS_PER_AXIS: f64 = (1u64 << 21) as f64 - 1.0;

/// Closed bounding box.
#[derive(Clone, Copy)]
struct Box3 {
    lo: Point,
    hi: Point,
}

impl Box3 {
    fn of(p: [Point; 3]) -> Box3 {
        let lo = [0, 1, 2].map(|k| p[0][k].min(p[1][k]).min(p[2][k]));
        let hi = [0, 1, 2].map(|k| p[0][k].max(p[1][k]).max(p[2][k]));
        Box3 { lo, hi }
    }

    fn meets(&self, o: &Box3) -> bool {
        (0..3).all(|k| self.lo[k] <= o.hi[k] && o.lo[k] <= self.hi[k])
    }
}

/// A uniform grid: cell size and origin.
struct Grid {
    origin: Point,
    size: f64,
}

impl Grid {
    /// The cell of a coordinate along an axis: monotone in `x`.
    fn cell(&self, x: f64, k: usize) -> u64 {
        (((x - self.origin[k]) / self.size).floor()).clamp(0.0, MAX_CELLS_PER_AXIS) as u64
    }

    fn cells(&self, b: &Box3) -> ([u64; 3], [u64; 3]) {
        let lo = [0, 1, 2].map(|k| self.cell(b.lo[k], k));
        let hi = [0, 1, 2].map(|k| self.cell(b.hi[k], k));
        (lo, hi)
    }

    fn insertions(&self, boxes: &[(usize, Box3)]) -> u64 {
        boxes
            .iter()
            .map(|(_, b)| {
                let (lo, hi) = self.cells(b);
                (0..3).map(|k| hi[k] - lo[k] + 1).product::<u64>()
            })
            .sum()
    }
}

fn key(c: [u64; 3]) -> u64 {
    c[0] | (c[1] << 21) | (c[2] << 42)
}

/// Tests every pair of non-degenerate triangles whose boxes meet; returns the pairs tested.
pub(super) fn crossings(mesh: &Mesh, degenerate: &[bool], tally: &mut Tally) -> u64 {
    let corners = |t: usize| mesh.triangles[t].map(|v| mesh.vertices[v as usize]);
    let boxes: Vec<(usize, Box3)> = (0..mesh.triangles.len())
        .filter(|&t| !degenerate[t])
        .map(|t| (t, Box3::of(corners(t))))
        .collect();
    if boxes.len() < 2 {
        return 0;
    }
    let mut lo = boxes[0].1.lo;
    let mut hi = boxes[0].1.hi;
    let mut extent = 0.0;
    for (_, b) in &boxes {
        for k in 0..3 {
            lo[k] = lo[k].min(b.lo[k]);
            hi[k] = hi[k].max(b.hi[k]);
        }
        extent += (0..3).map(|k| b.hi[k] - b.lo[k]).fold(0.0, f64::max);
    }
    let span = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
    let mut grid = Grid {
        origin: lo,
        size: (extent / boxes.len() as f64)
            .max(span / MAX_CELLS_PER_AXIS)
            .max(f64::MIN_POSITIVE),
    };
    // Long thin triangles would fill many cells: coarsen until the grid holds a few cells per
    // triangle.
    let budget = 16 * boxes.len() as u64 + 1024;
    while grid.insertions(&boxes) > budget && grid.size < span {
        grid.size *= 2.0;
    }
    let mut first_cell: Vec<[u64; 3]> = vec![[0; 3]; mesh.triangles.len()];
    let mut entries: Vec<(u64, u32)> = Vec::with_capacity(budget as usize);
    for (t, b) in &boxes {
        let (l, h) = grid.cells(b);
        first_cell[*t] = l;
        for x in l[0]..=h[0] {
            for y in l[1]..=h[1] {
                for z in l[2]..=h[2] {
                    entries.push((key([x, y, z]), *t as u32));
                }
            }
        }
    }
    entries.sort_unstable();
    let bx: Vec<Option<Box3>> = {
        let mut v = vec![None; mesh.triangles.len()];
        for (t, b) in &boxes {
            v[*t] = Some(*b);
        }
        v
    };
    let mut pairs = 0u64;
    for g in entries.chunk_by(|a, b| a.0 == b.0) {
        let k = g[0].0;
        let here = [k & 0x1f_ffff, (k >> 21) & 0x1f_ffff, k >> 42];
        for i in 0..g.len() {
            let s = g[i].1 as usize;
            for e in &g[i + 1..] {
                let t = e.1 as usize;
                let (fs, ft) = (first_cell[s], first_cell[t]);
                if (0..3).any(|a| fs[a].max(ft[a]) != here[a]) {
                    continue;
                }
                let (Some(bs), Some(bt)) = (bx[s], bx[t]) else {
                    continue;
                };
                if !bs.meets(&bt) {
                    continue;
                }
                pairs += 1;
                if let Some(how) = crossing(mesh, s.min(t), s.max(t)) {
                    let (s, t) = (s.min(t), s.max(t));
                    tally.add("crossing triangles", || {
                        let mut vs = mesh.triangles[s].to_vec();
                        vs.extend(mesh.triangles[t]);
                        let name = |t: usize| {
                            let c: Vec<String> = mesh.triangles[t]
                                .iter()
                                .map(|&v| {
                                    let p = mesh.vertices[v as usize];
                                    format!("({}, {}, {})", p[0], p[1], p[2])
                                })
                                .collect();
                            format!("{} [{}]", mesh.triangle_name(t), c.join(" "))
                        };
                        finding(
                            mesh,
                            "crossing triangles",
                            vec![s, t],
                            vs,
                            format!("{} and {} {how}", name(s), name(t)),
                        )
                    });
                }
            }
        }
    }
    pairs
}

/// How two non-degenerate triangles cross, or `None` when they meet only in what they share.
fn crossing(mesh: &Mesh, s: usize, t: usize) -> Option<String> {
    let (ts, tt) = (mesh.triangles[s], mesh.triangles[t]);
    let at = |v: u32| mesh.vertices[v as usize];
    let shared: Vec<u32> = ts.iter().copied().filter(|v| tt.contains(v)).collect();
    // Rotate a triangle so that its corners in `shared` come first, in its own order.
    let rotate = |tri: [u32; 3]| -> [u32; 3] {
        (0..3)
            .map(|r| [tri[r], tri[(r + 1) % 3], tri[(r + 2) % 3]])
            .find(|x| {
                (0..shared.len()).all(|i| shared.contains(&x[i]))
                    && !(shared.len()..3).any(|i| shared.contains(&x[i]))
            })
            .expect("a rotation puts the shared corners first")
    };
    let side_meets = |p: u32, q: u32, tri: [u32; 3]| {
        let pts = [at(p), at(q), at(tri[0]), at(tri[1]), at(tri[2])];
        exactly!(pts, |x| segment_meets_triangle(
            &x[0], &x[1], &x[2], &x[3], &x[4]
        ))
    };
    match shared.len() {
        0 => {
            let hit = (0..3).any(|i| side_meets(ts[i], ts[(i + 1) % 3], tt))
                || (0..3).any(|i| side_meets(tt[i], tt[(i + 1) % 3], ts));
            hit.then(|| "share no vertex and meet".to_string())
        }
        1 => {
            let (a, b) = (rotate(ts), rotate(tt));
            let hit = side_meets(a[1], a[2], b) || side_meets(b[1], b[2], a);
            hit.then(|| {
                format!(
                    "share the vertex {} and meet elsewhere too",
                    mesh.vertex_name(shared[0])
                )
            })
        }
        2 => {
            let (a, b) = (rotate(ts), rotate(tt));
            let (u, v, p, q) = (a[0], a[1], a[2], b[2]);
            let pts = [at(u), at(v), at(p), at(q)];
            let folded = exactly!(pts, |x| {
                if orient3d(&x[0], &x[1], &x[2], &x[3]) != 0 {
                    false
                } else {
                    match normal_axis(&x[0], &x[1], &x[2]) {
                        Some(k) => {
                            orient2d(k, &x[0], &x[1], &x[2]) == orient2d(k, &x[0], &x[1], &x[3])
                        }
                        None => false,
                    }
                }
            });
            folded.then(|| {
                format!(
                    "share the edge {} – {} and lie on the same side of it in one plane: they overlap",
                    mesh.vertex_name(u),
                    mesh.vertex_name(v)
                )
            })
        }
        _ => Some("have the same three corners: they coincide".to_string()),
    }
}
