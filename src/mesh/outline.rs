//! The outline of the union of the level-n cells: its boundary points, identified exactly, and its
//! directed boundary segments (material on the left), with the component of each point.
//!
//! **How shared points are identified.** Every cell edge gets an exact *key*, the identity it
//! shares with the cell across it (the scheme of `crate::component::components_by_cells`, here
//! computed while streaming the depth-first walk): an edge of a start face has its own key, or the
//! key of the edge the assembly glues it to (the second side reversed); a spoke `Ea` gets a key
//! per (parent cell, spoke), traversed `inward` or not; piece `j` of a parent edge gets the key
//! (parent key, `j` read in the key's reference direction), so the children of both neighbours
//! agree; `El` and `Ec` edges have keys of their own (they border holes). A key held by two cells
//! is traversed in opposite directions (checked). The two end points of a key are union-find
//! nodes; the end of a cell's edge `i` is its corner with edge `i + 1`, so uniting them over all
//! cells identifies every corner of the level-n complex with exactly the corners it is equal to by
//! the topology — the points of the same vertex computed from different cells are never compared
//! or welded by position. The inner points of a flattened Bézier edge are named by (key, index in
//! the reference direction). Each identified point takes one position: the first computed.
//!
//! **What is checked here.** Every cell of level n, on the identified positions, is a simple
//! polygon, counter-clockwise (exact orientation predicates on the `f32` coordinates); a key is
//! held by at most two cells, in opposite directions, and by one exactly when the topology says
//! the edge is free. Together with the winding numbers of `crate::mesh::solid` this proves the
//! cells do not overlap: the sum of the cells' winding numbers is the winding number of the
//! boundary (shared edges cancel), each cell's is 0 or 1, so where the boundary's is at most 1
//! no two cells overlap.

use super::below::{bezier_point, bounds, distance, Cell, Instance, Point};
use super::{MeshError, Size};
use crate::topology::Origin;
use std::collections::HashMap;

/// An exact edge key: its identity and whether the cell traverses it against the reference
/// direction.
#[derive(Clone, Copy, Debug)]
struct Key {
    id: u32,
    reversed: bool,
}

const NONE: u32 = u32::MAX;

/// The boundary of the union of the level-n cells.
#[derive(Clone, Debug, Default)]
pub struct Outline {
    /// Boundary points, in millimetres (values of `f32`).
    pub points: Vec<[f64; 2]>,
    /// The cell component of each boundary point.
    pub component: Vec<u32>,
    /// Directed boundary segments (indices into `points`), material on the left.
    pub segments: Vec<[u32; 2]>,
    /// The number of cell components (cells joined by shared edges).
    pub components: usize,
    /// The start face of the first cell of each component.
    pub component_start: Vec<usize>,
    /// The number of level-n cells.
    pub cells: u64,
    /// With [`outline_with_cells`]: every cell as a polygon over [`Outline::cell_points`] (its
    /// type, its component and its points counter-clockwise); empty otherwise.
    pub cell_polygons: Vec<CellPolygon>,
    /// With [`outline_with_cells`]: every identified point of the level-n complex (corners and
    /// the inner points of flattened Bézier edges), one position each.
    pub cell_points: Vec<[f64; 2]>,
    /// With [`outline_with_cells`]: the cell point of each boundary point.
    pub boundary_cell_point: Vec<u32>,
    /// With [`outline_with_cells`]: the type of the cell on the left of each boundary segment.
    pub segment_type: Vec<u32>,
}

/// A level-n cell as a polygon over the identified points.
#[derive(Clone, Debug, Default)]
pub struct CellPolygon {
    /// The cell's face type.
    pub ty: u32,
    /// Its component.
    pub component: u32,
    /// Its points, counter-clockwise (indices into [`Outline::cell_points`]).
    pub points: Vec<u32>,
}

/// The next fresh key identity.
struct Ids(u32);

impl Ids {
    /// `n` consecutive fresh identities; returns the first.
    fn take(&mut self, n: u32) -> u32 {
        self.0 += n;
        self.0 - n
    }
}

/// A parent cell on the walk's stack.
struct Frame {
    ty: usize,
    keys: Vec<Key>,
    spoke_base: u32,
    next_child: usize,
}

/// Walks the level-`level` cells depth first with the exact key of each of their edges and the
/// index of their start face. Deterministic: two walks give the same keys.
fn walk_keyed(inst: &Instance, level: u32, mut visit: impl FnMut(&Cell, &[Key], usize)) {
    let mut ids = Ids(0);
    let fresh = |ids: &mut Ids| ids.take(1);
    let mut glued: HashMap<(usize, usize), Key> = HashMap::new();
    for [a, b] in &inst.glue {
        let id = fresh(&mut ids);
        glued.insert(
            *a,
            Key {
                id,
                reversed: false,
            },
        );
        glued.insert(*b, Key { id, reversed: true });
    }
    let start_keys: Vec<Vec<Key>> = inst
        .start
        .iter()
        .enumerate()
        .map(|(f, s)| {
            (0..s.free.len())
                .map(|e| {
                    glued.get(&(f, e)).copied().unwrap_or_else(|| Key {
                        id: fresh(&mut ids),
                        reversed: false,
                    })
                })
                .collect()
        })
        .collect();
    let mut pieces: HashMap<(u32, u32), u32> = HashMap::new();
    let mut frames: Vec<Option<Frame>> = (0..=level).map(|_| None).collect();
    let (mut start, mut starts_seen) = (0usize, 0usize);
    inst.walk(level, true, |c| {
        let d = c.depth as usize;
        let keys: Vec<Key> = if d == 0 {
            start = starts_seen;
            starts_seen += 1;
            start_keys[start].clone()
        } else {
            let p = frames[d - 1]
                .as_mut()
                .expect("a parent before its children");
            let k = p.next_child;
            p.next_child += 1;
            let ty = &inst.types.types[p.ty];
            ty.subdivision.subfaces[k]
                .origins
                .iter()
                .map(|o| match *o {
                    Origin::Piece { edge, piece } => {
                        let pk = p.keys[edge];
                        let np = ty.face.boundary[edge].piece_count();
                        let j = if pk.reversed {
                            np - 1 - piece as u32
                        } else {
                            piece as u32
                        };
                        let id = match pieces.remove(&(pk.id, j)) {
                            // The neighbour's child took it first: both sides now hold it.
                            Some(id) => id,
                            None => {
                                let id = fresh(&mut ids);
                                pieces.insert((pk.id, j), id);
                                id
                            }
                        };
                        Key {
                            id,
                            reversed: pk.reversed,
                        }
                    }
                    Origin::Spoke { spoke, inward } => Key {
                        id: p.spoke_base + spoke as u32,
                        reversed: inward,
                    },
                    Origin::Lacuna { .. } | Origin::GapSide { .. } => Key {
                        id: fresh(&mut ids),
                        reversed: false,
                    },
                })
                .collect()
        };
        if d < level as usize {
            let spokes = inst.types.types[c.ty].subdivision.spokes.len() as u32;
            let base = ids.take(spokes);
            frames[d] = Some(Frame {
                ty: c.ty,
                keys,
                spoke_base: base,
                next_child: 0,
            });
        } else {
            visit(c, &keys, start);
        }
    });
}

/// Union-find with path halving over growable nodes.
#[derive(Default)]
struct Dsu(Vec<u32>);

impl Dsu {
    fn grow(&mut self, n: usize) {
        while self.0.len() < n {
            let k = self.0.len() as u32;
            self.0.push(k);
        }
    }
    fn find(&mut self, mut x: u32) -> u32 {
        while self.0[x as usize] != x {
            let p = self.0[self.0[x as usize] as usize];
            self.0[x as usize] = p;
            x = p;
        }
        x
    }
    fn union(&mut self, a: u32, b: u32) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            let (lo, hi) = (ra.min(rb), ra.max(rb));
            self.0[hi as usize] = lo;
        }
    }
}

/// Grows `v` with `fill` to hold index `i`.
fn slot<T: Clone>(v: &mut Vec<T>, i: usize, fill: T) -> &mut T {
    if v.len() <= i {
        v.resize(i + 1, fill);
    }
    &mut v[i]
}

/// Which cells hold a key: the first holder, its direction and how many.
#[derive(Clone, Copy)]
struct Holder {
    cell: u32,
    reversed: bool,
    count: u8,
}

/// Computes the outline of the level-`level` cells in millimetres: the level-0 faces' x extent
/// is scaled to `size.width`, their lower-left corner moved to the origin.
pub fn outline(
    inst: &Instance,
    level: u32,
    segments: usize,
    size: Size,
) -> Result<Outline, MeshError> {
    outline_of(inst, level, segments, size, false)
}

/// [`outline`] that also keeps every cell as a polygon over the identified points (for a mesh
/// whose top and bottom are triangulated cell by cell, each triangle in one cell).
pub fn outline_with_cells(
    inst: &Instance,
    level: u32,
    segments: usize,
    size: Size,
) -> Result<Outline, MeshError> {
    outline_of(inst, level, segments, size, true)
}

fn outline_of(
    inst: &Instance,
    level: u32,
    segments: usize,
    size: Size,
    keep_cells: bool,
) -> Result<Outline, MeshError> {
    let bb = bounds(inst, segments);
    let extent = bb.max[0] - bb.min[0];
    let scale = size.width / if extent > 0.0 { extent } else { 1.0 };
    let to_mm = |p: Point| -> [f64; 2] {
        [
            ((p[0] - bb.min[0]) * scale) as f32 as f64,
            ((p[1] - bb.min[1]) * scale) as f32 as f64,
        ]
    };
    let overlap = |reason: String| MeshError::Overlap { level, reason };

    // Pass 1: keys, corner identities, positions, cell adjacency.
    let mut corners = Dsu::default();
    let mut corner_pos: Vec<[f64; 2]> = Vec::new();
    // Per key: (first, count) of its inner points in `samples`, in the reference direction.
    let mut sample_at: Vec<(u32, u32)> = Vec::new();
    let mut samples: Vec<[f64; 2]> = Vec::new();
    let mut holders: Vec<Option<Holder>> = Vec::new();
    let mut cells = Dsu::default();
    let mut cell_start: Vec<u32> = Vec::new();
    let mut error: Option<MeshError> = None;
    walk_keyed(inst, level, |c, keys, start| {
        if error.is_some() {
            return;
        }
        let me = cell_start.len() as u32;
        cell_start.push(start as u32);
        cells.grow(me as usize + 1);
        let n = keys.len();
        for (e, k) in keys.iter().enumerate() {
            let ctrl = inst.edge_controls(c.ty, e, c.points);
            let (s, t) = (2 * k.id + k.reversed as u32, 2 * k.id + !k.reversed as u32);
            corners.grow(2 * k.id as usize + 2);
            let p = slot(&mut corner_pos, s as usize, [f64::NAN; 2]);
            if p[0].is_nan() {
                *p = to_mm(ctrl[0]);
            }
            let q = slot(&mut corner_pos, t as usize, [f64::NAN; 2]);
            if q[0].is_nan() {
                *q = to_mm(ctrl[ctrl.len() - 1]);
            }
            let next = keys[(e + 1) % n];
            let next_start = 2 * next.id + next.reversed as u32;
            corners.grow(2 * next.id as usize + 2);
            corners.union(t, next_start);
            if inst.slots[c.ty][e].bezier
                && slot(&mut sample_at, k.id as usize, (NONE, 0)).0 == NONE
            {
                // The first cell to meet the key flattens it, for both sides.
                let pl = flatten(&ctrl, segments, FLATTENING_TOLERANCE_MM / scale);
                let inner = &pl[1..pl.len() - 1];
                sample_at[k.id as usize] = (samples.len() as u32, inner.len() as u32);
                if k.reversed {
                    samples.extend(inner.iter().rev().map(|&p| to_mm(p)));
                } else {
                    samples.extend(inner.iter().map(|&p| to_mm(p)));
                }
            }
            let h = slot(&mut holders, k.id as usize, None);
            match h {
                None => {
                    *h = Some(Holder {
                        cell: me,
                        reversed: k.reversed,
                        count: 1,
                    })
                }
                Some(hd) if hd.count == 1 && hd.reversed != k.reversed => {
                    hd.count = 2;
                    let other = hd.cell;
                    cells.union(other, me);
                }
                Some(_) => {
                    error = Some(MeshError::Check {
                        level,
                        reason: format!(
                            "an edge of cell {me} is held by a third cell, or twice in one direction (the topology is not a surface)"
                        ),
                    });
                }
            }
        }
    });
    if let Some(e) = error {
        return Err(e);
    }
    // Every class of corners takes the position of its smallest node that has one.
    let mut class_pos: Vec<[f64; 2]> = vec![[f64::NAN; 2]; corner_pos.len()];
    for node in 0..corner_pos.len() as u32 {
        if corner_pos[node as usize][0].is_nan() {
            continue;
        }
        let r = corners.find(node) as usize;
        if class_pos[r][0].is_nan() {
            class_pos[r] = corner_pos[node as usize];
        }
    }
    drop(corner_pos);
    // Components of cells, numbered in walk order.
    let ncells = cell_start.len();
    let mut comp_of_root: Vec<u32> = vec![NONE; ncells];
    let mut component_start = Vec::new();
    let mut cell_comp: Vec<u32> = Vec::with_capacity(ncells);
    for c in 0..ncells as u32 {
        let r = cells.find(c) as usize;
        if comp_of_root[r] == NONE {
            comp_of_root[r] = component_start.len() as u32;
            component_start.push(cell_start[c as usize] as usize);
        }
        cell_comp.push(comp_of_root[r]);
    }

    // Pass 2: the polygon of every cell on the identified positions; the free edges.
    let mut out = Outline {
        components: component_start.len(),
        component_start,
        cells: ncells as u64,
        ..Outline::default()
    };
    let mut boundary_of_class: Vec<u32> = Vec::new();
    let mut cell = 0usize;
    let mut poly: Vec<[f64; 2]> = Vec::new();
    // With `keep_cells`: the cell point of each corner class and of each sample, and the cell
    // point of each entry of `poly`.
    let mut cell_of_class: Vec<u32> = Vec::new();
    let mut cell_of_sample: Vec<u32> = Vec::new();
    let mut poly_ids: Vec<u32> = Vec::new();
    walk_keyed(inst, level, |c, keys, _| {
        if error.is_some() {
            return;
        }
        let me = cell;
        cell += 1;
        poly.clear();
        poly_ids.clear();
        let comp = cell_comp[me];
        let mut first_of_edge: Vec<usize> = Vec::with_capacity(keys.len());
        for (e, k) in keys.iter().enumerate() {
            let h = holders[k.id as usize].expect("held");
            if c.free[e] != (h.count == 1) {
                error = Some(MeshError::Check {
                    level,
                    reason: format!(
                        "edge {e} of cell {me} is {} by the flags but held by {}",
                        if c.free[e] { "free" } else { "shared" },
                        crate::error::counted(h.count, "cell", "cells")
                    ),
                });
                return;
            }
            first_of_edge.push(poly.len());
            let s = corners.find(2 * k.id + k.reversed as u32);
            poly.push(class_pos[s as usize]);
            if keep_cells {
                let id = slot(&mut cell_of_class, s as usize, NONE);
                if *id == NONE {
                    *id = out.cell_points.len() as u32;
                    out.cell_points.push(class_pos[s as usize]);
                }
                poly_ids.push(*id);
            }
            let (at, m) = sample_at.get(k.id as usize).copied().unwrap_or((NONE, 0));
            if at != NONE {
                let inner = &samples[at as usize..(at + m) as usize];
                if k.reversed {
                    poly.extend(inner.iter().rev());
                } else {
                    poly.extend(inner.iter());
                }
                if keep_cells {
                    let mut ids: Vec<u32> = (at..at + m)
                        .map(|j| {
                            let id = slot(&mut cell_of_sample, j as usize, NONE);
                            if *id == NONE {
                                *id = out.cell_points.len() as u32;
                                out.cell_points.push(samples[j as usize]);
                            }
                            *id
                        })
                        .collect();
                    if k.reversed {
                        ids.reverse();
                    }
                    poly_ids.extend(ids);
                }
            }
        }
        if let Err(why) = simple_ccw(&poly) {
            error = Some(overlap(format!("cell {me} (type T{}) {why}", c.ty)));
            return;
        }
        if keep_cells {
            out.cell_polygons.push(CellPolygon {
                ty: c.ty as u32,
                component: comp,
                points: poly_ids.clone(),
            });
        }
        // Free edges: boundary points and directed segments.
        let n = poly.len();
        for (e, k) in keys.iter().enumerate() {
            if !c.free[e] {
                continue;
            }
            let (from, to) = (
                first_of_edge[e],
                first_of_edge.get(e + 1).copied().unwrap_or(n),
            );
            let mut ids: Vec<u32> = Vec::with_capacity(to - from + 1);
            let mut corner_id = |node: u32, out: &mut Outline, map: &mut Vec<u32>| {
                let r = corners.find(node) as usize;
                let b = slot(map, r, NONE);
                if *b == NONE {
                    *b = out.points.len() as u32;
                    out.points.push(class_pos[r]);
                    out.component.push(comp);
                    if keep_cells {
                        out.boundary_cell_point.push(cell_of_class[r]);
                    }
                }
                *b
            };
            ids.push(corner_id(
                2 * k.id + k.reversed as u32,
                &mut out,
                &mut boundary_of_class,
            ));
            for (j, p) in poly.iter().enumerate().take(to).skip(from + 1) {
                ids.push(out.points.len() as u32);
                out.points.push(*p);
                out.component.push(comp);
                if keep_cells {
                    out.boundary_cell_point.push(poly_ids[j]);
                }
            }
            ids.push(corner_id(
                2 * k.id + !k.reversed as u32,
                &mut out,
                &mut boundary_of_class,
            ));
            out.segments.extend(ids.windows(2).map(|w| [w[0], w[1]]));
            if keep_cells {
                out.segment_type
                    .extend(std::iter::repeat_n(c.ty as u32, ids.len() - 1));
            }
        }
    });
    if let Some(e) = error {
        return Err(e);
    }
    Ok(out)
}

/// The largest distance in millimetres between a Bézier edge and its flattened polyline: far
/// below any printer's resolution, and it keeps the deep levels (cells of hundredths of a
/// millimetre) from carrying `--segments` points per edge that no printer can show.
pub const FLATTENING_TOLERANCE_MM: f64 = 0.005;

/// A Bézier edge flattened to at most `segments` segments (both ends included), as few as keep
/// the polyline within `tol` of the curve: a chord over a parameter interval h is within
/// h²/8 · max|B''| of the curve, and |B''| ≤ q(q − 1)·max|Δ²P| for degree q.
pub fn flatten(ctrl: &[Point], segments: usize, tol: f64) -> Vec<Point> {
    let q = ctrl.len().saturating_sub(1);
    let d2 = ctrl
        .windows(3)
        .map(|w| {
            distance(
                [w[0][0] - w[1][0], w[0][1] - w[1][1]],
                [w[1][0] - w[2][0], w[1][1] - w[2][1]],
            )
        })
        .fold(0.0f64, f64::max);
    let bound = (q * q.saturating_sub(1)) as f64 * d2;
    let needed = (bound / (8.0 * tol)).sqrt().ceil();
    let n = if needed.is_finite() {
        (needed as usize).clamp(1, segments.max(1))
    } else {
        segments.max(1)
    };
    (0..=n)
        .map(|i| bezier_point(ctrl, i as f64 / n as f64))
        .collect()
}

/// Whether a closed polygon is simple and counter-clockwise, by exact orientation predicates on
/// its coordinates (`Err` says why not).
pub fn simple_ccw(poly: &[[f64; 2]]) -> Result<(), String> {
    let n = poly.len();
    if n < 3 {
        return Err(format!("has {n} distinct points"));
    }
    let pt = |i: usize| robust::Coord {
        x: poly[i % n][0],
        y: poly[i % n][1],
    };
    for i in 0..n {
        if poly[i] == poly[(i + 1) % n] {
            return Err(format!("has a zero-length edge at {:?}", poly[i]));
        }
    }
    let area2: f64 = (0..n)
        .map(|i| {
            let (a, b) = (poly[i], poly[(i + 1) % n]);
            a[0] * b[1] - a[1] * b[0]
        })
        .sum();
    if area2.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return Err("is clockwise or flat".into());
    }
    // No two edges meet except consecutive ones at their common end.
    for i in 0..n {
        for j in i + 1..n {
            let adjacent = j == i + 1 || (i == 0 && j == n - 1);
            let (a, b, c, d) = (pt(i), pt(i + 1), pt(j), pt(j + 1));
            if adjacent {
                // Consecutive edges overlap only when they fold back on each other.
                let (p, q, r) = if j == i + 1 { (a, b, d) } else { (c, d, b) };
                if robust::orient2d(p, q, r) == 0.0 {
                    let dot = (p.x - q.x) * (r.x - q.x) + (p.y - q.y) * (r.y - q.y);
                    if dot > 0.0 {
                        return Err(format!("folds back on itself at {:?}", [q.x, q.y]));
                    }
                }
                continue;
            }
            if segments_meet(a, b, c, d) {
                return Err(format!("crosses itself near {:?}", [a.x, a.y]));
            }
        }
    }
    Ok(())
}

/// Whether closed segments `ab` and `cd` have a point in common (exact predicates).
pub fn segments_meet(
    a: robust::Coord<f64>,
    b: robust::Coord<f64>,
    c: robust::Coord<f64>,
    d: robust::Coord<f64>,
) -> bool {
    let sign = |x: f64| (x > 0.0) as i8 - (x < 0.0) as i8;
    let o1 = sign(robust::orient2d(a, b, c));
    let o2 = sign(robust::orient2d(a, b, d));
    let o3 = sign(robust::orient2d(c, d, a));
    let o4 = sign(robust::orient2d(c, d, b));
    if o1 * o2 < 0 && o3 * o4 < 0 {
        return true;
    }
    let within = |p: robust::Coord<f64>, q: robust::Coord<f64>, r: robust::Coord<f64>| {
        r.x >= p.x.min(q.x) && r.x <= p.x.max(q.x) && r.y >= p.y.min(q.y) && r.y <= p.y.max(q.y)
    };
    (o1 == 0 && within(a, b, c))
        || (o2 == 0 && within(a, b, d))
        || (o3 == 0 && within(c, d, a))
        || (o4 == 0 && within(c, d, b))
}
