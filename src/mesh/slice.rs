//! Layers of a closed solid as a printer slices it (GEOMETRY §5): the cross-section of the
//! surface with a horizontal plane, and the smallest hole and thinnest ligament of the material
//! in each of a number of layers ([`layer_features`]), measured as the planar structures of faces
//! are ([`super::feature`]).
//!
//! **The cross-section.** Every triangle is read counter-clockwise from outside. A vertex at the
//! height of the plane counts as above it (a symbolic perturbation of the plane downwards), so a
//! triangle is cut when its vertices are on both sides, and then exactly two of its edges cross
//! the plane. The segment runs from the crossing of the edge that goes down to the crossing of
//! the edge that goes up: with the outward normal `n`, that is the direction `z × n`, which has
//! the material on its left. A crossing is computed from its edge taken from the lower-numbered
//! vertex, so the two triangles of an edge get the same point, and segments are chained by the
//! edge they cross (a closed manifold gives closed loops). The loops are normalised by
//! `i_overlay` (non-zero winding), as the outline of a face's cells is.
//!
//! **The figures.** A layer's smallest hole is the bracketed width of [`smallest_hole`], its
//! thinnest ligament the erosion estimate of [`thinnest_ligament`]; the solid's figures are the
//! least over the layers sliced, one in each of `layers` equal bands of the height, in the middle
//! of the gap between vertex heights there ([`layer_heights`]). Layers
//! between are not seen, so both are estimates for the solid even where a layer's figure is a
//! bracket. Floating point, for a warning; never a verdict.

use super::feature::{betti, erode, smallest_hole, thinnest_ligament_below, Shapes, P2};
use super::solid::Part;
use i_overlay::core::fill_rule::FillRule;
use i_overlay::float::simplify::SimplifyShape;
use serde::Serialize;
use std::collections::HashMap;

/// The layers sliced by default.
pub const DEFAULT_LAYERS: usize = 20;

/// The most layers `--layers` accepts.
pub const MAX_LAYERS: usize = 10_000;

/// The least figures over the layers of a solid, with the height where each was found.
#[derive(Clone, Debug, Default, Serialize)]
pub struct LayerFeatures {
    /// The layers sliced (fewer than asked where bands share a gap between vertex heights).
    pub layers: usize,
    /// The smallest hole of any layer (the low end of its bracket), mm, and its layer's height.
    pub smallest_hole: Option<(f64, f64)>,
    /// The thinnest ligament of any layer, mm, and its layer's height.
    pub thinnest_ligament: Option<(f64, f64)>,
    /// The layers with a hole below the resolution.
    pub holes_below: usize,
    /// The layers with a ligament below the resolution.
    pub ligaments_below: usize,
}

impl LayerFeatures {
    /// The figures below `resolution` (mm), in words: how many layers and the least.
    pub fn below(&self, resolution: f64) -> Vec<String> {
        [
            ("smallest hole", self.smallest_hole, self.holes_below),
            ("thinnest ligament", self.thinnest_ligament, self.ligaments_below),
        ]
        .into_iter()
        .filter_map(|(what, f, n)| {
            let (x, z) = f.filter(|&(x, _)| x < resolution)?;
            Some(format!(
                "the {what} is below the resolution {resolution} mm in {n} of {} layers (the least {x:.3} mm, at z = {z:.2} mm)",
                self.layers
            ))
        })
        .collect()
    }
}

/// The cross-section of the parts' closed surfaces with the plane at height `z` (mm): the
/// material as shapes (an outer contour counter-clockwise, its holes clockwise).
pub fn slice(parts: &[Part], z: f64) -> Shapes {
    let mut loops: Vec<Vec<P2>> = Vec::new();
    for part in parts {
        let v = |i: u32| part.vertices[i as usize].map(f64::from);
        let above = |i: u32| v(i)[2] >= z;
        // The crossing of the edge {a, b}, computed from its lower-numbered end.
        let crossing = |a: u32, b: u32| -> P2 {
            let (p, q) = (v(a.min(b)), v(a.max(b)));
            let t = (z - p[2]) / (q[2] - p[2]);
            [p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])]
        };
        // Segments keyed by the edge they start on: (start edge, end edge).
        let mut next: HashMap<(u32, u32), (u32, u32)> = HashMap::new();
        let key = |a: u32, b: u32| (a.min(b), a.max(b));
        for t in &part.triangles {
            let (mut down, mut up) = (None, None);
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                match (above(a), above(b)) {
                    (true, false) => down = Some(key(a, b)),
                    (false, true) => up = Some(key(a, b)),
                    _ => {}
                }
            }
            if let (Some(d), Some(u)) = (down, up) {
                next.insert(d, u);
            }
        }
        while let Some((&start, _)) = next.iter().next() {
            let mut ring = Vec::new();
            let mut at = start;
            while let Some(to) = next.remove(&at) {
                ring.push(crossing(at.0, at.1));
                at = to;
            }
            if ring.len() >= 3 {
                loops.push(ring);
            }
        }
    }
    if loops.is_empty() {
        return Vec::new();
    }
    loops.simplify_shape(FillRule::NonZero)
}

/// The heights of the layers sliced: in each of `layers` equal bands of the parts' height, the
/// middle of the widest interval of the band without a vertex height. A plane through vertices
/// (or close to them) cuts a horizontal ridge or a flat face (almost) exactly: its section has
/// necks and slivers of width (almost) zero that the layers of a printer, a layer height apart,
/// do not show; as far from every vertex height as the band allows, the section is generic.
pub fn layer_heights(parts: &[Part], layers: usize) -> Vec<f64> {
    let mut zs: Vec<f64> = parts
        .iter()
        .flat_map(|p| p.vertices.iter().map(|v| f64::from(v[2])))
        .collect();
    zs.sort_by(f64::total_cmp);
    zs.dedup();
    let (Some(&lo), Some(&hi)) = (zs.first(), zs.last()) else {
        return Vec::new();
    };
    if zs.len() < 2 || layers == 0 {
        return Vec::new();
    }
    let h = (hi - lo) / layers as f64;
    (0..layers)
        .map(|i| {
            let (b0, b1) = (lo + i as f64 * h, lo + (i + 1) as f64 * h);
            // The gaps (zs[k − 1], zs[k]) that meet the band, clipped to it.
            let first = zs.partition_point(|&z| z <= b0).clamp(1, zs.len() - 1);
            let last = zs.partition_point(|&z| z < b1).clamp(first, zs.len() - 1);
            let (a, b) = (first..=last)
                .map(|k| (zs[k - 1].max(b0), zs[k].min(b1)))
                .max_by(|x, y| (x.1 - x.0).total_cmp(&(y.1 - y.0)))
                .unwrap_or((b0, b1));
            (a + b) / 2.0
        })
        .collect()
}

/// The least smallest hole and thinnest ligament over `layers` slices of the parts, and the
/// layers where each is below `resolution` (mm).
pub fn layer_features(parts: &[Part], layers: usize, resolution: f64) -> LayerFeatures {
    let heights = layer_heights(parts, layers);
    let mut f = LayerFeatures {
        layers: heights.len(),
        ..Default::default()
    };
    // The layers are independent until their ligaments: sliced and measured on every core, a
    // batch at a time (a batch's slices are held in memory), then gathered in height order, so
    // the figures do not depend on the number of threads.
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    for batch in heights.chunks(4 * threads) {
        for layer in in_parallel(batch, threads, |z| Layer::of(parts, z, resolution)) {
            if let Some((lo, _)) = layer.hole {
                if lo < resolution {
                    f.holes_below += 1;
                }
                if f.smallest_hole.is_none_or(|(a, _)| lo < a) {
                    f.smallest_hole = Some((lo, layer.z));
                }
            }
            if layer.ligament_below {
                f.ligaments_below += 1;
            }
            if !layer.material {
                continue;
            }
            // Only a layer thinner than the least so far is bisected (one erosion decides the
            // others): in height order, one layer after the other.
            let best = f.thinnest_ligament.map_or(f64::INFINITY, |l| l.0);
            if let Some((_, hi)) = thinnest_ligament_below(&layer.shapes, best) {
                if hi < best {
                    f.thinnest_ligament = Some((hi, layer.z));
                }
            }
        }
    }
    f
}

/// What one layer gives on its own.
struct Layer {
    /// Its height, mm.
    z: f64,
    /// Its material.
    shapes: Shapes,
    /// Its smallest hole's bracket, mm.
    hole: Option<(f64, f64)>,
    /// Whether it has material.
    material: bool,
    /// Whether eroding its material by half the resolution changes its components or holes.
    ligament_below: bool,
}

impl Layer {
    fn of(parts: &[Part], z: f64, resolution: f64) -> Layer {
        let shapes = slice(parts, z);
        let hole = smallest_hole(&shapes);
        let base = betti(&shapes);
        let material = base.0 > 0;
        let ligament_below = material && betti(&erode(&shapes, resolution / 2.0)) != base;
        Layer {
            z,
            shapes,
            hole,
            material,
            ligament_below,
        }
    }
}

/// `f` of every item on up to `threads` threads (item `i` on thread `i mod threads`), the
/// results in the items' order.
fn in_parallel<T: Send>(items: &[f64], threads: usize, f: impl Fn(f64) -> T + Sync) -> Vec<T> {
    let threads = threads.clamp(1, items.len().max(1));
    if threads == 1 {
        return items.iter().map(|&x| f(x)).collect();
    }
    let mut out: Vec<Option<T>> = items.iter().map(|_| None).collect();
    std::thread::scope(|sc| {
        let f = &f;
        let handles: Vec<_> = (0..threads)
            .map(|t| {
                sc.spawn(move || {
                    (t..items.len())
                        .step_by(threads)
                        .map(|i| (i, f(items[i])))
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        for h in handles {
            // A panic of a worker is a defect of the measuring code: passed on as it is.
            let done = h.join().unwrap_or_else(|e| std::panic::resume_unwind(e));
            for (i, r) in done {
                out[i] = Some(r);
            }
        }
    });
    out.into_iter().flatten().collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn in_parallel_keeps_the_order_of_the_items() {
        let items: Vec<f64> = (0..11).map(f64::from).collect();
        let square = |x: f64| x * x;
        let one: Vec<f64> = items.iter().map(|&x| square(x)).collect();
        for threads in [1, 2, 3, 16] {
            assert_eq!(
                in_parallel(&items, threads, square),
                one,
                "{threads} threads"
            );
        }
        assert!(in_parallel(&[], 4, square).is_empty());
    }

    /// An axis box `[x0, x1] × [y0, y1] × [z0, z1]` as a closed part, triangles counter-clockwise
    /// from outside.
    fn cuboid(lo: [f32; 3], hi: [f32; 3]) -> Part {
        let vertices: Vec<[f32; 3]> = (0..8)
            .map(|i| {
                [0, 1, 2].map(|k| match (i >> k) & 1 {
                    0 => lo[k],
                    _ => hi[k],
                })
            })
            .collect();
        // Corner i has bit k set when coordinate k is high.
        let quads = [
            [0, 2, 3, 1], // z low, seen from below
            [4, 5, 7, 6], // z high
            [0, 1, 5, 4], // y low
            [2, 6, 7, 3], // y high
            [0, 4, 6, 2], // x low
            [1, 3, 7, 5], // x high
        ];
        let triangles = quads
            .iter()
            .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
            .collect();
        Part {
            vertices,
            triangles,
            holes: Some(0),
        }
    }

    fn area(ring: &[P2]) -> f64 {
        let n = ring.len();
        (0..n)
            .map(|i| ring[i][0] * ring[(i + 1) % n][1] - ring[(i + 1) % n][0] * ring[i][1])
            .sum::<f64>()
            / 2.0
    }

    #[test]
    fn a_box_slices_to_its_rectangle_counter_clockwise() {
        let b = cuboid([0.0, 0.0, 0.0], [4.0, 3.0, 2.0]);
        let s = slice(std::slice::from_ref(&b), 1.0);
        assert_eq!(betti(&s), (1, 0));
        // 4 × 3 = 12, positive: counter-clockwise, the material on the left.
        assert!((area(&s[0][0]) - 12.0).abs() < 1e-9, "{s:?}");
        // The plane is perturbed downwards: at the top face's height it cuts just below it (the
        // whole rectangle), at the bottom face's height every vertex is above it (nothing).
        assert_eq!(betti(&slice(std::slice::from_ref(&b), 2.0)), (1, 0));
        assert!(slice(&[b], 0.0).is_empty());
    }

    #[test]
    fn a_frame_has_its_hole_and_walls_measured_in_every_layer() {
        // A 10 × 10 square frame with a 4 × 6 window (walls 3, 3 in x and 2, 2 in y), 5 tall, as
        // four boxes glued into one closed surface would be: here four separate boxes that
        // touch, whose union the normalisation makes one shape with one hole.
        let parts = [
            cuboid([0.0, 0.0, 0.0], [10.0, 2.0, 5.0]),
            cuboid([0.0, 8.0, 0.0], [10.0, 10.0, 5.0]),
            cuboid([0.0, 2.0, 0.0], [3.0, 8.0, 5.0]),
            cuboid([7.0, 2.0, 0.0], [10.0, 8.0, 5.0]),
        ];
        let s = slice(&parts, 2.5);
        assert_eq!(betti(&s), (1, 1), "{s:?}");
        let f = layer_features(&parts, 4, 0.4);
        assert_eq!(f.layers, 4);
        // By hand: the window is 4 wide (x) and 6 tall (y): its largest disc has diameter 4.
        let (hole, z) = f.smallest_hole.expect("a hole");
        assert!((hole - 4.0).abs() < 1e-3, "{hole}");
        // No vertex height inside the bands (0 to 5, bands of 1.25): the first band's middle.
        assert!((z - 0.625).abs() < 1e-9, "the first band's middle: {z}");
        // The thinnest wall is 2 (the y walls): eroding by 1 cuts them and opens the window.
        let (lig, _) = f.thinnest_ligament.expect("a ligament");
        assert!((lig - 2.0).abs() < 2e-3, "{lig}");
        assert_eq!((f.holes_below, f.ligaments_below), (0, 0));
        // Against a resolution of 3 mm: the hole (4) is wider, the walls (2) are not.
        let f = layer_features(&parts, 4, 3.0);
        assert_eq!((f.holes_below, f.ligaments_below), (0, 4), "every layer");
        let (lig, _) = f.thinnest_ligament.expect("a ligament");
        assert!((lig - 2.0).abs() < 2e-3, "{lig}");
    }

    #[test]
    fn heights_keep_away_from_vertex_heights() {
        // Vertex heights 1, 3 (a box) and 1, 1.5 (a slab). Bands of 0.5: [1, 1.5] has no vertex
        // height inside (its middle 1.25); [1.5, 2] begins at one (the gap (1.5, 3) clipped:
        // 1.75); [2, 2.5] and [2.5, 3] lie in that gap (2.25, 2.75). With 2 bands: [1, 2] holds
        // 1.5, its widest gap clipped is (1, 1.5) or (1.5, 2) — equal, the later kept by
        // `max_by` (1.75); [2, 3] is free (2.5).
        let parts = [
            cuboid([0.0, 0.0, 1.0], [1.0, 1.0, 3.0]),
            cuboid([2.0, 0.0, 1.0], [3.0, 1.0, 1.5]),
        ];
        assert_eq!(layer_heights(&parts, 4), vec![1.25, 1.75, 2.25, 2.75]);
        assert_eq!(layer_heights(&parts, 2), vec![1.75, 2.5]);
        // A vertex height at 1.2 makes [1, 1.5]'s widest free interval (1.2, 1.5).
        let with = [
            parts[0].clone(),
            parts[1].clone(),
            cuboid([5.0, 0.0, 1.2], [6.0, 1.0, 2.9]),
        ];
        let z = layer_heights(&with, 4)[0];
        assert!((z - 1.35).abs() < 1e-6, "{z}");
        assert!(layer_heights(&parts, 0).is_empty());
    }
}
