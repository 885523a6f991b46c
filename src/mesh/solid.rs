//! The solid: the outline triangulated and extruded, one [`Part`] per component, checked against
//! the exact topology before it is handed to a writer.
//!
//! **Top and bottom.** The boundary points go into one constrained Delaunay triangulation
//! (`spade`, bulk loaded) with every boundary segment as a constraint. Two boundary points at the
//! same position (the boundary touching itself, or two components touching) and two boundary
//! segments that cross are refused (E1041). Every triangle then gets the winding number of the
//! boundary around it, by walking from the outer face across the triangulation: crossing a
//! boundary segment that has the triangle on its left adds 1, on its right subtracts 1. Triangles
//! of winding 1 are the material; any other value than 0 or 1 means overlapping cells (E1041).
//! With `crate::mesh::outline`'s check that every cell is simple and counter-clockwise, this is
//! a proof that no two cells overlap.
//!
//! **Extrusion.** Each boundary point gives a bottom vertex (z = 0) and a top vertex (z = the
//! thickness); a material triangle gives a top triangle (counter-clockwise seen from above) and
//! a bottom one (reversed); each boundary segment `a → b` (material on its left) gives a wall of
//! two triangles facing outwards. Nothing else: shared cell edges leave no wall.

use super::below::{population, Instance};
use super::check::{check_part, PartCheck};
use super::expect::{expected, Expected};
use super::outline::{outline, Outline};
use super::{MeshError, Size};
use num_bigint::BigUint;
use num_traits::Zero;
use spade::{ConstrainedDelaunayTriangulation, Point2, Triangulation};
use std::collections::{HashMap, HashSet, VecDeque};

/// One connected component of a solid: an indexed triangle mesh in millimetres.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Part {
    /// Vertex positions.
    pub vertices: Vec<[f32; 3]>,
    /// Triangles, counter-clockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
    /// The holes the exact topology gives this component (when known per component).
    pub holes: Option<u64>,
}

/// A checked solid: its parts and what was checked.
#[derive(Clone, Debug)]
pub struct Solid {
    /// The structure's name.
    pub name: String,
    /// The level.
    pub level: u32,
    /// The sizes in mm.
    pub size: Size,
    /// One part per component.
    pub parts: Vec<Part>,
    /// The check of each part.
    pub checks: Vec<PartCheck>,
    /// The exact expectations it was checked against.
    pub expected: Expected,
    /// The number of level-n cells.
    pub cells: u64,
}

impl Solid {
    /// The extent of all parts in mm (x, y, z), from the written (`f32`) coordinates.
    pub fn extent(&self) -> [f64; 3] {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for v in self.parts.iter().flat_map(|p| &p.vertices) {
            for k in 0..3 {
                lo[k] = lo[k].min(f64::from(v[k]));
                hi[k] = hi[k].max(f64::from(v[k]));
            }
        }
        std::array::from_fn(|k| if hi[k] >= lo[k] { hi[k] - lo[k] } else { 0.0 })
    }

    /// Whether the solid fits a printer's build volume `bed` (mm): a warning when it does not
    /// (with the largest uniform scale that would fit, as a `--width`), or when it fills the bed
    /// to within 1 mm in some direction, where a brim, a skirt or the bed's margin no longer fit.
    /// `width` is the `--width` the solid was made with. Orientation is not changed: the extent
    /// is the solid's as written.
    pub fn bed_advice(&self, bed: [f64; 3], width: f64) -> Option<String> {
        let e = self.extent();
        let shown = |x: [f64; 3]| format!("{:.1} × {:.1} × {:.1} mm", x[0], x[1], x[2]);
        let scale = (0..3)
            .filter(|&k| e[k] > 0.0)
            .map(|k| bed[k] / e[k])
            .fold(f64::INFINITY, f64::min);
        if scale < 1.0 {
            return Some(format!(
                "warning: the object is {}, larger than the bed {} (--bed): it fits scaled by \
                 {:.4} or less, --width {:.2} mm",
                shown(e),
                shown(bed),
                scale,
                (width * scale * 1e2).floor() / 1e2
            ));
        }
        let tight: Vec<&str> = (0..3)
            .filter(|&k| bed[k] - e[k] < 1.0)
            .map(|k| ["x", "y", "z"][k])
            .collect();
        (!tight.is_empty()).then(|| {
            format!(
                "warning: the object is {}, within 1 mm of the bed {} in {} (--bed): no room \
                 for a brim or the bed's margin",
                shown(e),
                shown(bed),
                tight.join(", ")
            )
        })
    }

    /// The number of triangles of all parts.
    pub fn triangle_count(&self) -> usize {
        self.parts.iter().map(|p| p.triangles.len()).sum()
    }

    /// A few lines saying what was built and checked.
    pub fn summary(&self) -> String {
        let v: usize = self.parts.iter().map(|p| p.vertices.len()).sum();
        let euler: Vec<String> = self.checks.iter().map(|c| c.euler.to_string()).collect();
        format!(
            "mesh: {} level {}, {}, width {} mm, thickness {} mm: {}, {v} vertices, {} triangles; closed oriented manifold, Euler characteristic {} (exact: {}, {})\n",
            self.name,
            self.level,
            super::counted(self.cells, "cell", "cells"),
            self.size.width,
            self.size.thickness,
            super::counted(self.parts.len(), "part", "parts"),
            self.triangle_count(),
            euler.join(", "),
            super::counted(self.expected.components, "component", "components"),
            super::counted(&self.expected.holes, "hole", "holes")
        )
    }
}

/// The material triangles of an outline by component (indices into the outline's points).
fn material(o: &Outline, level: u32) -> Result<Vec<Vec<[u32; 3]>>, MeshError> {
    let overlap = |reason: String| MeshError::Overlap { level, reason };
    // Distinct positions: a boundary touching itself is not a manifold.
    let mut seen: HashMap<(u64, u64), u32> = HashMap::with_capacity(o.points.len());
    for (i, p) in o.points.iter().enumerate() {
        if let Some(j) = seen.insert((p[0].to_bits(), p[1].to_bits()), i as u32) {
            return Err(overlap(format!(
                "the boundary touches itself at ({}, {}) mm (boundary points {j} and {i}{})",
                p[0],
                p[1],
                if o.component[j as usize] != o.component[i] {
                    ", of two components"
                } else {
                    ""
                }
            )));
        }
    }
    drop(seen);
    // Every boundary point starts one segment and ends one.
    let mut degree = vec![[0u8; 2]; o.points.len()];
    for s in &o.segments {
        degree[s[0] as usize][0] += 1;
        degree[s[1] as usize][1] += 1;
    }
    if let Some(i) = degree.iter().position(|d| *d != [1, 1]) {
        let p = o.points[i];
        return Err(overlap(format!(
            "the boundary passes {} times through ({}, {}) mm",
            degree[i][0].max(degree[i][1]),
            p[0],
            p[1]
        )));
    }
    let pts: Vec<Point2<f64>> = o.points.iter().map(|p| Point2::new(p[0], p[1])).collect();
    let edges: Vec<[usize; 2]> = o
        .segments
        .iter()
        .map(|s| [s[0] as usize, s[1] as usize])
        .collect();
    let mut conflict: Option<[usize; 2]> = None;
    let cdt = ConstrainedDelaunayTriangulation::<Point2<f64>>::try_bulk_load_cdt(
        pts,
        edges.clone(),
        |e| {
            conflict.get_or_insert(e);
        },
    )
    .map_err(|e| overlap(format!("the boundary cannot be triangulated: {e:?}")))?;
    if let Some(e) = conflict {
        let p = o.points[e[0]];
        return Err(overlap(format!(
            "the boundary crosses itself near ({}, {}) mm",
            p[0], p[1]
        )));
    }
    if cdt.num_vertices() != o.points.len() {
        return Err(overlap("boundary points were merged".into()));
    }
    // Winding numbers from the outer face.
    let directed: HashSet<(u32, u32)> = o.segments.iter().map(|s| (s[0], s[1])).collect();
    let faces = cdt.num_all_faces();
    // Per face: the face across each edge, the winding step, and the edge's midpoint (the place
    // named when the windings disagree).
    let mut adj: Vec<Vec<(usize, i32, [f64; 2])>> = vec![Vec::new(); faces];
    for e in cdt.directed_edges() {
        let (a, b) = (e.from().fix().index() as u32, e.to().fix().index() as u32);
        let (f, g) = (e.face().fix().index(), e.rev().face().fix().index());
        // Crossing from g into f (f lies on the left of a → b).
        let step = if directed.contains(&(a, b)) {
            1
        } else if directed.contains(&(b, a)) {
            -1
        } else {
            0
        };
        let (p, q) = (e.from().position(), e.to().position());
        adj[g].push((f, step, [(p.x + q.x) / 2.0, (p.y + q.y) / 2.0]));
    }
    let outer = cdt.outer_face().fix().index();
    let mut winding: Vec<Option<i32>> = vec![None; faces];
    winding[outer] = Some(0);
    let mut queue = VecDeque::from([outer]);
    while let Some(g) = queue.pop_front() {
        let w = winding[g].expect("set when queued");
        for &(f, step, at) in &adj[g] {
            match winding[f] {
                None => {
                    winding[f] = Some(w + step);
                    queue.push_back(f);
                }
                Some(x) if x != w + step => {
                    return Err(overlap(format!(
                        "the boundary is not a set of closed curves near ({:.4}, {:.4}) mm (two \
                         boundary segments on top of each other, or a cell of zero area)",
                        at[0], at[1]
                    )));
                }
                Some(_) => {}
            }
        }
    }
    let mut parts: Vec<Vec<[u32; 3]>> = vec![Vec::new(); o.components];
    for f in cdt.inner_faces() {
        let w = winding[f.fix().index()].unwrap_or(0);
        match w {
            0 => {}
            1 => {
                let v = f.vertices().map(|v| v.fix().index() as u32);
                let c = o.component[v[0] as usize];
                if v.iter().any(|&x| o.component[x as usize] != c) {
                    return Err(overlap(format!(
                        "components {} and {} overlap",
                        c,
                        v.iter()
                            .map(|&x| o.component[x as usize])
                            .find(|&x| x != c)
                            .unwrap_or(c)
                    )));
                }
                parts[c as usize].push(v);
            }
            _ => {
                let p = f.center();
                return Err(overlap(format!(
                    "{w} layers of cells cover ({:.4}, {:.4}) mm: cells overlap",
                    p.x, p.y
                )));
            }
        }
    }
    Ok(parts)
}

/// Checks that the level-`level` cells of a face embed, as the solid would (the outline and
/// the winding numbers of its constrained triangulation, no mesh built): no two cells overlap,
/// and the boundary of their union neither touches nor crosses itself. Fails with E1041 and the
/// place. `render` runs it before drawing a face's level in any format, so that a degenerate
/// point of the solution space (two spoke curves on top of each other, a lacuna of zero width)
/// is never drawn as a picture without a word.
pub fn embedded(inst: &Instance, level: u32, segments: usize, size: Size) -> Result<(), MeshError> {
    let o = outline(inst, level, segments, size)?;
    material(&o, level).map(|_| ())
}

/// Builds the solid of the level-`level` cells and checks it (see the module documentation and
/// `crate::mesh::check`). Fails with E1041 when cells overlap, E1040 when the mesh is not a
/// closed oriented manifold with the exact topology.
pub fn build(inst: &Instance, level: u32, segments: usize, size: Size) -> Result<Solid, MeshError> {
    let (expected, o, tops) = checked_outline(inst, level, segments, size, false)?;
    // Local vertex numbers per component.
    let mut local = vec![u32::MAX; o.points.len()];
    let mut members: Vec<Vec<u32>> = vec![Vec::new(); o.components];
    for (i, &c) in o.component.iter().enumerate() {
        local[i] = members[c as usize].len() as u32;
        members[c as usize].push(i as u32);
    }
    let mut walls: Vec<Vec<[u32; 2]>> = vec![Vec::new(); o.components];
    for s in &o.segments {
        walls[o.component[s[0] as usize] as usize]
            .push([local[s[0] as usize], local[s[1] as usize]]);
    }
    let z = size.thickness as f32;
    let mut parts = Vec::with_capacity(o.components);
    for (c, top) in tops.into_iter().enumerate() {
        let n = members[c].len() as u32;
        let mut triangles = Vec::with_capacity(2 * top.len() + 2 * walls[c].len());
        for t in &top {
            push_caps(&mut triangles, t.map(|i| local[i as usize]), n);
        }
        for &w in &walls[c] {
            push_wall(&mut triangles, w, n);
        }
        parts.push(Part {
            vertices: layers(&o.points, &members[c], z),
            triangles,
            holes: None,
        });
    }
    checked_solid(inst, level, size, parts, expected, &o)
}

/// The outline of the level's cells (with the cells' polygons when `keep_cells`), its
/// components compared with the exact topology, and the triangles of its material (the
/// winding numbers that show the cells do not overlap, [`material`]).
#[allow(clippy::type_complexity)]
fn checked_outline(
    inst: &Instance,
    level: u32,
    segments: usize,
    size: Size,
    keep_cells: bool,
) -> Result<(Expected, Outline, Vec<Vec<[u32; 3]>>), MeshError> {
    let expected = expected(inst, level).map_err(MeshError::Topology)?;
    let o = match keep_cells {
        false => outline(inst, level, segments, size)?,
        true => super::outline::outline_with_cells(inst, level, segments, size)?,
    };
    if o.components as u64 != expected.components {
        return Err(MeshError::Check {
            level,
            reason: format!(
                "{} components of cells, the exact topology says {}",
                o.components, expected.components
            ),
        });
    }
    let tops = material(&o, level)?;
    Ok((expected, o, tops))
}

/// The vertices of one component's prism: its points `members` (of `points`) at z = 0, then
/// the same at z = `z`.
fn layers(points: &[[f64; 2]], members: &[u32], z: f32) -> Vec<[f32; 3]> {
    let mut vertices = Vec::with_capacity(2 * members.len());
    for h in [0.0f32, z] {
        vertices.extend(members.iter().map(|&i| {
            let p = points[i as usize];
            [p[0] as f32, p[1] as f32, h]
        }));
    }
    vertices
}

/// A counter-clockwise triangle of the plane as the prism's top (its copy at `+ n`) and bottom
/// (reversed, so both face outwards).
fn push_caps(triangles: &mut Vec<[u32; 3]>, [a, b, d]: [u32; 3], n: u32) {
    triangles.push([a + n, b + n, d + n]);
    triangles.push([a, d, b]);
}

/// The wall on a boundary segment `a → b` (material on its left): two triangles facing right.
fn push_wall(triangles: &mut Vec<[u32; 3]>, [a, b]: [u32; 2], n: u32) {
    triangles.push([a, b, b + n]);
    triangles.push([a, b + n, a + n]);
}

/// The parts checked against the exact topology ([`verdict`]) as the level's solid.
fn checked_solid(
    inst: &Instance,
    level: u32,
    size: Size,
    mut parts: Vec<Part>,
    expected: Expected,
    o: &Outline,
) -> Result<Solid, MeshError> {
    let checks = verdict(level, &mut parts, &expected, &o.component_start)?;
    Ok(Solid {
        name: inst.name.clone(),
        level,
        size,
        parts,
        checks,
        expected,
        cells: o.cells,
    })
}

/// A solid whose triangles each lie in one level-n cell, with the cell's face type: for a
/// 3MF coloured by type (`render --3mf-colours`).
#[derive(Clone, Debug)]
pub struct TypedSolid {
    /// The solid, checked as [`build`]'s is.
    pub solid: Solid,
    /// Per part, the face type of each triangle (top and bottom: the cell's; a wall: the cell
    /// whose free edge it stands on).
    pub types: Vec<Vec<u32>>,
}

/// [`build`] with the top and bottom triangulated cell by cell (ear clipping of each cell's
/// polygon over the exactly identified points, so two cells meet along the same points) instead
/// of as the union's outline, so that every triangle lies in one cell and carries its type. The
/// cells are first shown not to overlap exactly as [`build`] does ([`embedded`]'s outline and
/// winding numbers); the mesh is then checked against the exact topology by the same
/// [`verdict`].
pub fn build_typed(
    inst: &Instance,
    level: u32,
    segments: usize,
    size: Size,
) -> Result<TypedSolid, MeshError> {
    let (expected, o, _) = checked_outline(inst, level, segments, size, true)?;
    // Local vertex numbers per component, over the cell points.
    let mut comp_of_point = vec![u32::MAX; o.cell_points.len()];
    for c in &o.cell_polygons {
        for &p in &c.points {
            comp_of_point[p as usize] = c.component;
        }
    }
    let mut local = vec![u32::MAX; o.cell_points.len()];
    let mut members: Vec<Vec<u32>> = vec![Vec::new(); o.components];
    for (i, &c) in comp_of_point.iter().enumerate() {
        if c != u32::MAX {
            local[i] = members[c as usize].len() as u32;
            members[c as usize].push(i as u32);
        }
    }
    let z = size.thickness as f32;
    let mut parts: Vec<Part> = members
        .iter()
        .map(|m| Part {
            vertices: layers(&o.cell_points, m, z),
            triangles: Vec::new(),
            holes: None,
        })
        .collect();
    let mut types: Vec<Vec<u32>> = vec![Vec::new(); o.components];
    for cell in &o.cell_polygons {
        let c = cell.component as usize;
        let n = members[c].len() as u32;
        let poly: Vec<[f64; 2]> = cell
            .points
            .iter()
            .map(|&p| o.cell_points[p as usize])
            .collect();
        for t in super::polygon::triangulate(&poly) {
            push_caps(
                &mut parts[c].triangles,
                t.map(|i| local[cell.points[i] as usize]),
                n,
            );
            types[c].extend([cell.ty, cell.ty]);
        }
    }
    for (s, &ty) in o.segments.iter().zip(&o.segment_type) {
        let c = o.component[s[0] as usize] as usize;
        let n = members[c].len() as u32;
        push_wall(
            &mut parts[c].triangles,
            s.map(|i| local[o.boundary_cell_point[i as usize] as usize]),
            n,
        );
        types[c].extend([ty, ty]);
    }
    Ok(TypedSolid {
        solid: checked_solid(inst, level, size, parts, expected, &o)?,
        types,
    })
}

/// The mesh of one type's cells (`render --3mf-parts`): every level-n cell of the type as a
/// closed shell of its own (its own vertices; cells that share an edge or a face touch along
/// it, and a slicer merges the touching shells of a part), checked to be as many spheres as the
/// exact count of the type's cells.
#[derive(Clone, Debug)]
pub struct TypePart {
    /// The type's index in its closure.
    pub ty: usize,
    /// The number of cells (closed shells).
    pub cells: u64,
    /// The shells, in millimetres.
    pub part: Part,
}

/// Checks that `part` is `cells` closed oriented spheres ([`check_part`]: every edge in two
/// triangles with opposite orientations, every vertex link one cycle; then as many connected
/// pieces as cells and Euler characteristic 2 per piece).
pub fn check_type_part(ty: usize, part: Part, cells: &BigUint) -> Result<TypePart, String> {
    let ck = check_part(&part).map_err(|e| format!("the cells of type {ty}: {e}"))?;
    let n = ck.components as u64;
    if BigUint::from(n) != *cells || ck.euler != 2 * ck.components as i64 {
        return Err(format!(
            "the cells of type {ty} give {} of Euler characteristic {} in all; the exact count is {}, each a sphere",
            crate::error::counted(ck.components, "closed surface", "closed surfaces"),
            ck.euler,
            crate::error::counted(cells, "cell", "cells")
        ));
    }
    Ok(TypePart { ty, cells: n, part })
}

/// One part per face type of the level-n cells ([`TypePart`]): each cell's polygon (the points
/// [`build_typed`] identifies, triangulated the same way) extruded to the thickness, as a prism
/// with its own vertices. The cells are first shown not to overlap as for [`build`]; the number
/// of cells of each type is compared with the exact count (the start vector times the
/// substitution matrix). Types with no cell at the level give no part.
pub fn face_parts(
    inst: &Instance,
    level: u32,
    segments: usize,
    size: Size,
) -> Result<Vec<TypePart>, MeshError> {
    let (_, o, _) = checked_outline(inst, level, segments, size, true)?;
    let want = population(&inst.types, u64::from(level));
    let z = size.thickness as f32;
    let mut parts: Vec<Part> = vec![Part::default(); want.len()];
    for cell in &o.cell_polygons {
        let ty = cell.ty as usize;
        let part = parts.get_mut(ty).ok_or_else(|| MeshError::Check {
            level,
            reason: format!("a cell of type {ty}, which the closure does not have"),
        })?;
        let base = part.vertices.len() as u32;
        let n = cell.points.len() as u32;
        let own: Vec<u32> = (0..n).collect();
        let points: Vec<[f64; 2]> = cell
            .points
            .iter()
            .map(|&p| o.cell_points[p as usize])
            .collect();
        part.vertices.extend(layers(&points, &own, z));
        let mut tris = Vec::new();
        for t in super::polygon::triangulate(&points) {
            push_caps(&mut tris, t.map(|i| i as u32), n);
        }
        for i in 0..n {
            push_wall(&mut tris, [i, (i + 1) % n], n);
        }
        part.triangles
            .extend(tris.into_iter().map(|t| t.map(|v| v + base)));
    }
    let mut out = Vec::new();
    for (ty, (part, cells)) in parts.into_iter().zip(&want).enumerate() {
        if part.triangles.is_empty() && cells.is_zero() {
            continue;
        }
        out.push(
            check_type_part(ty, part, cells)
                .map_err(|reason| MeshError::Check { level, reason })?,
        );
    }
    Ok(out)
}

/// Checks every part ([`check_part`]) and compares it with the exact topology: one connected
/// surface per component, Euler characteristic `2 − 2·holes` per component when the holes of each
/// are known (`component_start[c]` is the start face of component `c`), and in any case
/// `Σ χ = 2·components − 2·holes`. Records each part's holes.
pub fn verdict(
    level: u32,
    parts: &mut [Part],
    expected: &Expected,
    component_start: &[usize],
) -> Result<Vec<PartCheck>, MeshError> {
    let failed = |reason: String| MeshError::Check { level, reason };
    let mut checks = Vec::with_capacity(parts.len());
    let mut euler_sum = 0i64;
    for (c, part) in parts.iter_mut().enumerate() {
        let ck = check_part(part).map_err(|e| failed(format!("component {c}: {e}")))?;
        if ck.components != 1 {
            return Err(failed(format!(
                "component {c} of cells gives {} connected surfaces",
                ck.components
            )));
        }
        if let Some((of, holes)) = &expected.per_start {
            let h = &holes[of[component_start[c]]];
            let want = Expected::euler(h)
                .ok_or_else(|| failed(format!("component {c}: {h} holes is too many")))?;
            if ck.euler != want {
                return Err(failed(format!(
                    "component {c}: Euler characteristic {}, the exact topology gives {h} holes: 2 − 2·{h} = {want}",
                    ck.euler
                )));
            }
            part.holes = h.try_into().ok();
        }
        euler_sum += ck.euler;
        checks.push(ck);
    }
    // Σ (2 − 2·h_c) = 2·components − 2·holes.
    let want = num_traits::ToPrimitive::to_i64(&expected.holes)
        .and_then(|h| (expected.components as i64).checked_sub(h)?.checked_mul(2));
    if want != Some(euler_sum) {
        return Err(failed(format!(
            "the Euler characteristics add up to {euler_sum}, the exact topology ({} components, {} holes) gives {}",
            expected.components,
            expected.holes,
            want.map_or("an overflow".to_string(), |w| w.to_string())
        )));
    }
    Ok(checks)
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use num_bigint::BigUint;

    /// A unit tetrahedron, wound outward (shared with the checker's tests).
    pub(in crate::mesh) fn tetra() -> Part {
        Part {
            vertices: vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            triangles: vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]],
            holes: None,
        }
    }

    fn expected(holes: u32, per_start: bool) -> Expected {
        Expected {
            components: 1,
            holes: BigUint::from(holes),
            per_start: per_start.then(|| (vec![0], vec![BigUint::from(holes)])),
        }
    }

    #[test]
    fn a_sphere_passes_for_no_hole_and_fails_for_one() {
        let mut parts = vec![tetra()];
        let c = verdict(0, &mut parts, &expected(0, true), &[0]).unwrap();
        assert_eq!(c[0].euler, 2);
        assert_eq!(parts[0].holes, Some(0));
        for per_start in [true, false] {
            let e = verdict(3, &mut parts, &expected(1, per_start), &[0]).unwrap_err();
            assert_eq!(e.code(), "E1040", "{e}");
            assert!(e.is_failure());
        }
    }
}
