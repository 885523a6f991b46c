//! The size of the smallest hole at each level, computed from the cells, so that the raster that
//! counts holes can be chosen fine enough to see every one of them (THEORY §7).
//!
//! A hole opened by subdividing a level-i cell is its central lacuna, bounded by the `El` edges of
//! its sub-faces, or a gap of a shared `Cn` edge, made of two halves, each bounded by the two `Ec`
//! edges of the sub-faces on one side and the gap's segment of the parent edge. The *size* of a
//! polygon is `2·area / perimeter` (its inradius when it is a triangle or a regular polygon, and for
//! convex shapes between half the inradius and the inradius); a gap's two halves (from the two
//! parents sharing the edge) are paired by the midpoint of their common chord, and a half left
//! unpaired counts alone (a lower bound for the whole gap). Holes never shrink with the level (subdividing
//! only removes material from cells, and notches open into holes), so the smallest hole at level i
//! is the smallest opened at a level ≤ i. Floating point: this only chooses a resolution; the
//! verdict is still the integer comparison of observed and exact counts.

use crate::geometry::instantiate::Instance;
use crate::geometry::point::{distance, signed_area, Point};
use crate::topology::Origin;
use std::collections::BTreeMap;

/// The children seen so far of one parent cell, with the pieces of its holes.
struct Parent {
    ty: usize,
    free: Vec<bool>,
    next_child: usize,
    /// The `El` polylines of the children, in child order.
    lacuna: Vec<Vec<Point>>,
    /// Gap halves on shared edges: (edge, gap) → (side before, side after).
    gaps: BTreeMap<(usize, usize), (Vec<Point>, Vec<Point>)>,
}

/// `2·area / perimeter` of a closed polygon (0 when degenerate).
pub fn polygon_size(poly: &[Point]) -> f64 {
    let n = poly.len();
    if n < 3 {
        return 0.0;
    }
    let per: f64 = (0..n).map(|i| distance(poly[i], poly[(i + 1) % n])).sum();
    if per > 0.0 {
        2.0 * signed_area(poly).abs() / per
    } else {
        0.0
    }
}

/// One half of a gap on a shared edge: its area, the length of its two `Ec` sides, and the
/// midpoint of its chord (the gap's segment of the parent edge), where the other half meets it.
struct Half {
    area: f64,
    sides: f64,
    chord: f64,
    mid: Point,
}

impl Parent {
    /// The size of the central lacuna and the halves of the gaps this parent's subdivision opened.
    fn holes(self) -> (Option<f64>, Vec<Half>) {
        // Sub-face k's side runs from the lacuna vertex of spoke k + 1 to that of spoke k, so the
        // sides in reverse order make the lacuna's boundary (each end point once).
        let mut ring: Vec<Point> = Vec::new();
        for side in self.lacuna.iter().rev() {
            ring.extend_from_slice(&side[..side.len().saturating_sub(1)]);
        }
        let centre = (ring.len() >= 3).then(|| polygon_size(&ring));
        let halves = self
            .gaps
            .into_values()
            .filter(|(b, a)| !b.is_empty() && !a.is_empty())
            .map(|(mut poly, after)| {
                poly.extend(after);
                let (first, last) = (poly[0], poly[poly.len() - 1]);
                Half {
                    area: signed_area(&poly).abs(),
                    sides: poly.windows(2).map(|w| distance(w[0], w[1])).sum(),
                    chord: distance(first, last),
                    mid: [(first[0] + last[0]) / 2.0, (first[1] + last[1]) / 2.0],
                }
            })
            .collect();
        (centre, halves)
    }
}

/// The sizes of the gaps made of `halves` (paired by the midpoints of their chords: a rhombus of
/// two halves has size `2(A₁ + A₂)/(sides₁ + sides₂)`; a half left alone counts as a triangle).
fn gap_sizes(halves: Vec<Half>, extent: f64) -> Vec<f64> {
    let q = 1e-7 * extent.max(1e-300);
    let key = |p: Point| ((p[0] / q).round() as i64, (p[1] / q).round() as i64);
    let mut by_mid: BTreeMap<(i64, i64), Vec<Half>> = BTreeMap::new();
    for h in halves {
        by_mid.entry(key(h.mid)).or_default().push(h);
    }
    by_mid
        .into_values()
        .flat_map(|hs| {
            if hs.len() == 2 {
                vec![2.0 * (hs[0].area + hs[1].area) / (hs[0].sides + hs[1].sides)]
            } else {
                hs.iter()
                    .map(|h| 2.0 * h.area / (h.sides + h.chord))
                    .collect()
            }
        })
        .collect()
}

/// For each level 0..=level, the size of the smallest hole of the union of that level's cells
/// (`None` when there is no hole yet).
pub fn smallest_holes(inst: &Instance, level: u32, segments: usize) -> Vec<Option<f64>> {
    let n = level as usize + 1;
    let mut opened: Vec<Option<f64>> = vec![None; n];
    let mut halves: Vec<Vec<Half>> = (0..n).map(|_| Vec::new()).collect();
    let mut open: Vec<Option<Parent>> = (0..n).map(|_| None).collect();
    let record =
        |opened: &mut Vec<Option<f64>>, halves: &mut Vec<Vec<Half>>, d: usize, p: Parent| {
            let (centre, h) = p.holes();
            if let Some(s) = centre {
                let slot = &mut opened[d + 1];
                *slot = Some(slot.map_or(s, |m: f64| m.min(s)));
            }
            halves[d + 1].extend(h);
        };
    if level == 0 {
        return opened;
    }
    inst.walk(level, true, |c| {
        let d = c.depth as usize;
        if d >= 1 {
            if let Some(p) = open[d - 1].as_mut() {
                let k = p.next_child;
                p.next_child += 1;
                let sf = &inst.types.types[p.ty].subdivision.subfaces[k];
                for (e, o) in sf.origins.iter().enumerate() {
                    match *o {
                        Origin::Lacuna { .. } => {
                            p.lacuna
                                .push(inst.edge_polyline(c.ty, e, c.points, segments));
                        }
                        Origin::GapSide { edge, gap, after } if !p.free[edge] => {
                            let pl = inst.edge_polyline(c.ty, e, c.points, segments);
                            let entry = p.gaps.entry((edge, gap)).or_default();
                            if after {
                                entry.1 = pl;
                            } else {
                                entry.0 = pl;
                            }
                        }
                        _ => {}
                    }
                }
            }
        }
        if d < n - 1 {
            if let Some(prev) = open[d].take() {
                record(&mut opened, &mut halves, d, prev);
            }
            open[d] = Some(Parent {
                ty: c.ty,
                free: c.free.to_vec(),
                next_child: 0,
                lacuna: Vec::new(),
                gaps: BTreeMap::new(),
            });
        }
    });
    for (d, p) in open.into_iter().enumerate() {
        if let Some(p) = p {
            record(&mut opened, &mut halves, d, p);
        }
    }
    let extent = crate::geometry::raster::bounds(inst, segments).size();
    for (d, h) in halves.into_iter().enumerate() {
        for s in gap_sizes(h, extent) {
            let slot = &mut opened[d];
            *slot = Some(slot.map_or(s, |m: f64| m.min(s)));
        }
    }
    // Holes persist: the smallest at level i is the smallest opened at a level ≤ i.
    let mut best: Option<f64> = None;
    opened
        .into_iter()
        .map(|o| {
            if let Some(s) = o {
                best = Some(best.map_or(s, |b| b.min(s)));
            }
            best
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn size_of_simple_polygons() {
        // A unit square: 2·1/4 = 1/2, its inradius.
        let sq = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        assert!((polygon_size(&sq) - 0.5).abs() < 1e-12);
        // A 3-4-5 right triangle: inradius (3 + 4 − 5)/2 = 1 = 2·6/12.
        let t = [[0.0, 0.0], [4.0, 0.0], [0.0, 3.0]];
        assert!((polygon_size(&t) - 1.0).abs() < 1e-12);
        assert_eq!(polygon_size(&sq[..2]), 0.0);
    }
}
