//! The solid-homology step (THEORY §10): the checker builds the level-n solid of the claim's
//! volumes cell by cell and computes its cells, χ and Betti numbers (see `docs/CERTIFICATES.md`).
//!
//! **Cells by birth.** Every cell of level n + 1 is born inside one cell of level n, and is built
//! once there: the pieces of an edge (in the edge's own direction), the sub-faces of a face and
//! the spokes, lacuna sides and gap sides inside it (in the face's own orientation, the one of
//! the first volume that read it), the sub-volumes of a volume with the side faces, inner faces
//! and radial and inner edges inside it. A volume derives the sub-faces of each face of its
//! surface as it reads the face (from outside, so a face shared by two volumes is read the two
//! ways); each such sub-face is matched, through the pieces of the face's edges it runs along,
//! with the one sub-face of the face's own subdivision that has them at the same places in the
//! same directions, or the step fails: the two sides of a shared face must subdivide it alike.
//! The edges created inside a volume are the classes of the sides of its side and inner faces
//! under the gluing of the sub-volumes' surfaces and the pairing of the side faces two
//! sub-volumes share (a union–find that keeps each side's direction); a class holding a side
//! glued to the level-1 surface is that surface's edge. Corners are the classes of edge ends,
//! the end of each side of a face joined to the start of the next.
//!
//! **Ranks over F2.** b0 is the number of classes of corners joined by edges. The boundary
//! matrices ∂2 (faces → edges) and ∂3 (volumes → faces) are reduced over F2 (an incidence
//! counted modulo 2: a cell's boundary meeting a cell twice cancels, as in its integer boundary
//! reduced modulo 2). For an integer matrix the rank over F2 is at most the rank over Q, so the
//! F2 Betti numbers b_k = n_k − r_k − r_(k+1) bound the rational ones from above, and
//! Σ (−1)^k b_k = χ over every field. With b3 = b2 = 0 over F2, both are 0 over Q, and then
//! b1 over Q = b0 + b2 − χ = b1 over F2: the step certifies b0, b1, b2 over Q. A row whose F2
//! b2 or b3 is not 0 is refused (the step proves no cavity it cannot rule out).

use super::closure::{piece_type, subdivide};
use super::ranks::betti;
use super::volume::{checked_key, step_traced, Prov};
use crate::certificate::{Edge, Face, Origin, SolidHomologyStep, SolidRow, Volume, VolumesClaim};
use std::collections::HashMap;

#[cfg(test)]
use super::ranks::rank_f2;
#[cfg(test)]
use super::volume::tests as volume_tests;

/// A union–find over sides that keeps, for each, whether it runs against its class's root.
pub(super) struct Parity {
    parent: Vec<usize>,
    flip: Vec<bool>,
}

impl Parity {
    pub(super) fn new(n: usize) -> Parity {
        Parity {
            parent: (0..n).collect(),
            flip: vec![false; n],
        }
    }

    /// The root of `x` and whether `x` runs against it.
    pub(super) fn find(&mut self, x: usize) -> (usize, bool) {
        let mut path = Vec::new();
        let mut r = x;
        while self.parent[r] != r {
            path.push(r);
            r = self.parent[r];
        }
        let mut p = false;
        for &n in path.iter().rev() {
            p ^= self.flip[n];
            self.flip[n] = p;
            self.parent[n] = r;
        }
        (r, if x == r { false } else { self.flip[x] })
    }

    /// Joins `a` and `b`: the same edge, run the other way when `opposite`.
    pub(super) fn union(&mut self, a: usize, b: usize, opposite: bool) -> Result<(), String> {
        let (ra, pa) = self.find(a);
        let (rb, pb) = self.find(b);
        if ra == rb {
            return match pa ^ pb == opposite {
                true => Ok(()),
                false => Err("the gluing makes an edge run against itself".into()),
            };
        }
        self.parent[ra] = rb;
        self.flip[ra] = pa ^ pb ^ opposite;
        Ok(())
    }
}

/// A side: an edge of the complex and whether it is run in the edge's own direction.
pub(super) type Run = (usize, bool);

/// A face as a volume reads it: the face of the complex (and whether it is read against its
/// own orientation) and the runs of its sides.
type Reading = ((usize, bool), Vec<Run>);

/// A face of the complex in its own orientation.
#[derive(Clone)]
pub(super) struct CFace {
    pub(super) ty: Face,
    pub(super) bnd: Vec<Run>,
}

/// A volume of the complex as it reads its surface: `faces[f]` is the face of the complex that
/// its face `f` is (and whether it reads it against its own orientation), `sides[f][i]` the
/// edge its side `i` of face `f` runs along.
pub(super) struct CVol {
    v: Volume,
    pub(super) faces: Vec<(usize, bool)>,
    sides: Vec<Vec<Run>>,
}

/// The cell complex of the solid at one level (corners are derived by [`Complex::corners`]).
pub(super) struct Complex {
    pub(super) edges: Vec<Edge>,
    pub(super) faces: Vec<CFace>,
    pub(super) vols: Vec<CVol>,
}

impl Complex {
    /// The complex without its volumes: the surfaces alone.
    pub(super) fn surface(&self) -> Complex {
        Complex {
            edges: self.edges.clone(),
            faces: self.faces.clone(),
            vols: Vec::new(),
        }
    }

    fn cells(&self) -> usize {
        self.edges.len() + self.faces.len() + self.vols.len()
    }

    /// Adds a face read by a volume as `sides`: a new face of the complex in that orientation.
    pub(super) fn new_face(&mut self, ty: Face, bnd: Vec<Run>) -> Result<usize, String> {
        check_types(&ty, &bnd, &self.edges)?;
        self.faces.push(CFace { ty, bnd });
        Ok(self.faces.len() - 1)
    }

    /// The corner of every edge end (`2e` its start, `2e + 1` its end) and the number of corners.
    pub(super) fn corners(&self) -> (Vec<usize>, usize) {
        let mut dsu = Parity::new(2 * self.edges.len());
        let end = |(e, fwd): Run| 2 * e + usize::from(fwd);
        let start = |(e, fwd): Run| 2 * e + usize::from(!fwd);
        for f in &self.faces {
            let n = f.bnd.len();
            for i in 0..n {
                // Both ends are corners, never sides: their directions play no part.
                let _ = dsu.union(end(f.bnd[i]), start(f.bnd[(i + 1) % n]), false);
            }
        }
        let mut id = HashMap::new();
        let corner: Vec<usize> = (0..2 * self.edges.len())
            .map(|x| {
                let r = dsu.find(x).0;
                let k = id.len();
                *id.entry(r).or_insert(k)
            })
            .collect();
        (corner, id.len())
    }
}

/// Every side of a face must run along an edge of the face's type there.
fn check_types(ty: &Face, bnd: &[Run], edges: &[Edge]) -> Result<(), String> {
    if ty.boundary.len() != bnd.len() {
        return Err("a face's sides and boundary differ in length".into());
    }
    for (i, &(e, _)) in bnd.iter().enumerate() {
        if edges[e] != ty.boundary[i] {
            return Err(format!(
                "side {i} of a face of type {:?} runs along an edge of another type",
                ty.boundary
            ));
        }
    }
    Ok(())
}

/// The level-0 complex: the claim's volumes, each face once (a shared face as its first
/// reader reads it), edges the classes of sides under the surfaces' gluing and the shared faces.
pub(super) fn start(claim: &VolumesClaim) -> Result<Complex, String> {
    for (i, v) in claim.volumes.iter().enumerate() {
        checked_key(v).map_err(|e| format!("start volume {i}: {e}"))?;
    }
    let vols = &claim.volumes;
    let mut base = Vec::with_capacity(vols.len());
    let mut n = 0usize;
    for v in vols {
        let mut per = Vec::with_capacity(v.faces.len());
        for f in &v.faces {
            per.push(n);
            n += f.boundary.len();
        }
        base.push(per);
    }
    let slot = |v: usize, f: usize, i: usize| base[v][f] + i;
    let mut dsu = Parity::new(n);
    for (a, v) in vols.iter().enumerate() {
        for (f, row) in v.glue.iter().enumerate() {
            for (i, &(g, j)) in row.iter().enumerate() {
                dsu.union(slot(a, f, i), slot(a, g, j), true)?;
            }
        }
    }
    // Faces read by a second volume: (volume, face) → (face of its first reader, reversed).
    let mut second: HashMap<(usize, usize), (usize, usize)> = HashMap::new();
    let mut used: HashMap<(usize, usize), usize> = HashMap::new();
    for (k, s) in claim.shared.iter().enumerate() {
        let ([va, fa, ea], [vb, fb, eb]) = (s.a, s.b);
        let face = |v: usize, f: usize| vols.get(v).and_then(|x| x.faces.get(f));
        let (Some(x), Some(y)) = (face(va, fa), face(vb, fb)) else {
            return Err(format!("shared face {k}: no such volume or face"));
        };
        let m = x.boundary.len();
        if va == vb || y.boundary.len() != m || ea >= m || eb >= m {
            return Err(format!(
                "shared face {k}: a volume with itself, or faces of different lengths or edges \
                 out of range"
            ));
        }
        let same = x.params == y.params && x.algorithm == y.algorithm && x.delay == y.delay;
        if !same || (0..m).any(|t| x.boundary[(ea + t) % m] != y.boundary[(eb + m - t) % m]) {
            return Err(format!(
                "shared face {k}: the two readings are not one face read both ways"
            ));
        }
        for key in [(va, fa), (vb, fb)] {
            if let Some(j) = used.insert(key, k) {
                return Err(format!(
                    "volume {} face {} is shared twice (shared faces {j} and {k})",
                    key.0, key.1
                ));
            }
        }
        for t in 0..m {
            dsu.union(
                slot(va, fa, (ea + t) % m),
                slot(vb, fb, (eb + m - t) % m),
                true,
            )?;
        }
        second.insert((vb, fb), (va, fa));
    }
    let mut edge_id: HashMap<usize, usize> = HashMap::new();
    let mut edges: Vec<Edge> = Vec::new();
    let mut sides: Vec<Vec<Vec<Run>>> = Vec::with_capacity(vols.len());
    for (a, v) in vols.iter().enumerate() {
        let mut per = Vec::with_capacity(v.faces.len());
        for (f, face) in v.faces.iter().enumerate() {
            let mut row = Vec::with_capacity(face.boundary.len());
            for (i, ty) in face.boundary.iter().enumerate() {
                let (r, p) = dsu.find(slot(a, f, i));
                let e = *edge_id.entry(r).or_insert_with(|| {
                    edges.push(*ty);
                    edges.len() - 1
                });
                if edges[e] != *ty {
                    return Err("two sides glued together are of different edge types".into());
                }
                row.push((e, !p));
            }
            per.push(row);
        }
        sides.push(per);
    }
    let mut c = Complex {
        edges,
        faces: Vec::new(),
        vols: Vec::new(),
    };
    let mut face_id: HashMap<(usize, usize), usize> = HashMap::new();
    for (a, v) in vols.iter().enumerate() {
        for (f, face) in v.faces.iter().enumerate() {
            if !second.contains_key(&(a, f)) {
                let id = c.new_face(face.clone(), sides[a][f].clone())?;
                face_id.insert((a, f), id);
            }
        }
    }
    for (a, v) in vols.iter().enumerate() {
        let faces = (0..v.faces.len())
            .map(|f| match second.get(&(a, f)) {
                Some(first) => (face_id[first], true),
                None => (face_id[&(a, f)], false),
            })
            .collect();
        c.vols.push(CVol {
            v: v.clone(),
            faces,
            sides: std::mem::take(&mut sides[a]),
        });
    }
    Ok(c)
}

/// A side created inside a face, by its origin there.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
enum Inside {
    Spoke(usize),
    Lacuna(usize),
    Gap(usize, usize, bool),
}

/// The complex one level down.
pub(super) fn next(c: &Complex) -> Result<Complex, String> {
    let mut edges: Vec<Edge> = Vec::new();
    // Pieces of each edge, in its own direction.
    let mut first_piece = Vec::with_capacity(c.edges.len());
    for e in &c.edges {
        let (count, ty) = piece_type(e);
        first_piece.push((edges.len(), count));
        edges.extend(std::iter::repeat_n(ty, count));
    }
    let piece = |(e, fwd): Run, p: usize| -> Result<Run, String> {
        let (b, count) = first_piece[e];
        match (p < count, fwd) {
            (false, _) => Err(format!("piece {p} of an edge of {count} pieces")),
            (true, true) => Ok((b + p, true)),
            (true, false) => Ok((b + count - 1 - p, false)),
        }
    };
    let mut out = Complex {
        edges,
        faces: Vec::new(),
        vols: Vec::new(),
    };
    // Sub-faces of every face in its own orientation.
    let mut subs_of: Vec<Vec<usize>> = Vec::with_capacity(c.faces.len());
    for (g, face) in c.faces.iter().enumerate() {
        let (derived, _) = subdivide(&face.ty).map_err(|e| format!("face {g}: {e}"))?;
        let mut born: HashMap<Inside, usize> = HashMap::new();
        let mut ids = Vec::with_capacity(derived.len());
        for (boundary, origins, delay) in derived {
            let mut bnd = Vec::with_capacity(origins.len());
            for (q, o) in origins.iter().enumerate() {
                let (key, fwd) = match *o {
                    Origin::Piece { edge, piece: p } => {
                        let run = face.bnd.get(edge).ok_or("a piece of no edge")?;
                        bnd.push(piece(*run, p)?);
                        continue;
                    }
                    Origin::Spoke { spoke, inward } => (Inside::Spoke(spoke), inward),
                    Origin::Lacuna { side } => (Inside::Lacuna(side), true),
                    Origin::GapSide { edge, gap, after } => (Inside::Gap(edge, gap, after), true),
                };
                match born.get(&key) {
                    // A spoke is run inward on one side and outward on the other; a lacuna or
                    // gap side read a second time is read the other way.
                    Some(&e) => bnd.push((e, matches!(key, Inside::Spoke(_)) && fwd)),
                    None => {
                        out.edges.push(boundary[q]);
                        let e = out.edges.len() - 1;
                        born.insert(key, e);
                        bnd.push((e, fwd));
                    }
                }
            }
            let ty = Face {
                boundary,
                delay,
                ..face.ty.clone()
            };
            ids.push(out.new_face(ty, bnd)?);
        }
        subs_of.push(ids);
    }
    for (a, vol) in c.vols.iter().enumerate() {
        let (l1, subvolumes) = step_traced(&vol.v).map_err(|e| format!("volume {a}: {e}"))?;
        // Each sub-face the volume reads, matched with a sub-face of the face's subdivision.
        let mut read: HashMap<(usize, usize), Reading> = HashMap::new();
        for (f, list) in l1.subs.iter().enumerate() {
            let (g, _) = *vol
                .faces
                .get(f)
                .ok_or("a volume reads a face it does not have")?;
            for (k, (sub, origins)) in list.iter().enumerate() {
                let mut pieces = Vec::new();
                for (q, o) in origins.iter().enumerate() {
                    if let Origin::Piece { edge, piece: p } = *o {
                        let run = *vol.sides[f].get(edge).ok_or("a piece of no edge")?;
                        pieces.push((q, piece(run, p)?));
                    }
                }
                let matched = subs_of[g]
                    .iter()
                    .find_map(|&id| align(&out.faces[id], sub, &pieces).map(|m| (id, m)));
                let Some((id, (reversed, sides))) = matched else {
                    return Err(format!(
                        "volume {a} face {f}: its sub-face {k} as the volume reads it is no \
                         sub-face of the face's own subdivision (the face is not subdivided \
                         alike from both sides)"
                    ));
                };
                read.insert((f, k), ((id, reversed), sides));
            }
        }
        // Sides of the faces created inside: one slot each, joined by the gluing.
        let mut slot_base: Vec<Vec<usize>> = Vec::with_capacity(subvolumes.len());
        let mut n = 0usize;
        for (s, prov) in &subvolumes {
            let mut per = Vec::with_capacity(prov.len());
            for (x, p) in prov.iter().enumerate() {
                per.push(n);
                if !matches!(p, Prov::Sub(..)) {
                    n += s.faces[x].boundary.len();
                }
            }
            slot_base.push(per);
        }
        let mut dsu = Parity::new(n);
        let mut fixed: Vec<Option<Run>> = vec![None; n];
        let mut side_at: HashMap<super::volume::Side, (usize, usize)> = HashMap::new();
        for (j, (_, prov)) in subvolumes.iter().enumerate() {
            for (x, p) in prov.iter().enumerate() {
                if let Prov::Side(r) = p {
                    side_at.insert(*r, (j, x));
                }
            }
        }
        for (j, (s, prov)) in subvolumes.iter().enumerate() {
            for (x, p) in prov.iter().enumerate() {
                if matches!(p, Prov::Sub(..)) {
                    continue;
                }
                for (q, &(y, r)) in s.glue[x].iter().enumerate() {
                    let here = slot_base[j][x] + q;
                    match prov.get(y) {
                        Some(Prov::Sub(f, k)) => {
                            let (e, fwd) = read[&(*f, *k)].1[r];
                            fixed[here] = Some((e, !fwd));
                        }
                        Some(_) => dsu.union(here, slot_base[j][y] + r, true)?,
                        None => return Err("a sub-volume glued to no face".into()),
                    }
                }
                // A side face two sub-volumes share: read the other way by the other one.
                if let Prov::Side(r) = p {
                    let other = l1.partner.get(r).and_then(|t| side_at.get(t));
                    if let Some(&(j2, x2)) = other {
                        let m = s.faces[x].boundary.len();
                        if subvolumes[j2].0.faces[x2].boundary.len() != m {
                            return Err("two readings of a side face differ in length".into());
                        }
                        for q in 0..m {
                            let (mine, theirs) =
                                (slot_base[j][x] + q, slot_base[j2][x2] + (m - q) % m);
                            dsu.union(mine, theirs, true)?;
                        }
                    }
                }
            }
        }
        // Each class is an edge of the level-1 surface (a side glued to it) or a new edge.
        let mut class_edge: HashMap<usize, Run> = HashMap::new();
        for (i, f) in fixed.iter().enumerate() {
            if let Some((e, fwd)) = *f {
                let (r, p) = dsu.find(i);
                let root_run = (e, fwd ^ p);
                if let Some(old) = class_edge.insert(r, root_run) {
                    if old != root_run {
                        return Err("a class of sides runs along two edges".into());
                    }
                }
            }
        }
        let mut run_of = |dsu: &mut Parity, i: usize, ty: Edge, edges: &mut Vec<Edge>| {
            let (r, p) = dsu.find(i);
            let (e, fwd) = *class_edge.entry(r).or_insert_with(|| {
                edges.push(ty);
                (edges.len() - 1, true)
            });
            (e, fwd ^ p)
        };
        let mut shared_face: HashMap<(usize, usize), usize> = HashMap::new();
        for (j, (s, prov)) in subvolumes.iter().enumerate() {
            let mut faces = Vec::with_capacity(prov.len());
            let mut sides = Vec::with_capacity(prov.len());
            for (x, p) in prov.iter().enumerate() {
                if let Prov::Sub(f, k) = p {
                    let (face, runs) = &read[&(*f, *k)];
                    faces.push(*face);
                    sides.push(runs.clone());
                    continue;
                }
                let ty = &s.faces[x];
                let runs: Vec<Run> = (0..ty.boundary.len())
                    .map(|q| {
                        run_of(
                            &mut dsu,
                            slot_base[j][x] + q,
                            ty.boundary[q],
                            &mut out.edges,
                        )
                    })
                    .collect();
                let partner = match p {
                    Prov::Side(r) => l1.partner.get(r).and_then(|t| side_at.get(t)).copied(),
                    _ => None,
                };
                match partner.and_then(|o| shared_face.get(&o)) {
                    Some(&id) => faces.push((id, true)),
                    None => {
                        let id = out.new_face(ty.clone(), runs.clone())?;
                        shared_face.insert((j, x), id);
                        faces.push((id, false));
                    }
                }
                sides.push(runs);
            }
            out.vols.push(CVol {
                v: s.clone(),
                faces,
                sides,
            });
        }
    }
    Ok(out)
}

/// Places a sub-face `sub` as a volume reads it on the sub-face `own` of the face's own
/// subdivision: `pieces` are its sides along the face's edges (position, run). Returns whether
/// the volume reads it against its own orientation, and the runs of all its sides.
fn align(own: &CFace, sub: &Face, pieces: &[(usize, Run)]) -> Option<(bool, Vec<Run>)> {
    let len = own.bnd.len();
    let &(q0, (e0, d0)) = pieces.first()?;
    if sub.boundary.len() != len || sub.delay != own.ty.delay {
        return None;
    }
    for t in (0..len).filter(|&t| own.bnd[t].0 == e0) {
        let reversed = own.bnd[t].1 != d0;
        let at = |q: usize| match reversed {
            false => (t + q + len - q0) % len,
            true => (t + q0 + len - q % len) % len,
        };
        let fits = pieces.iter().all(|&(q, (e, d))| {
            let (oe, od) = own.bnd[at(q)];
            oe == e && (od != d) == reversed
        }) && (0..len).all(|q| sub.boundary[q] == own.ty.boundary[at(q)]);
        if fits {
            let runs = (0..len)
                .map(|q| {
                    let (e, d) = own.bnd[at(q)];
                    (e, d ^ reversed)
                })
                .collect();
            return Some((reversed, runs));
        }
    }
    None
}

/// The row of one level of a solid.
fn row(c: &Complex, level: u64) -> Result<SolidRow, String> {
    let b = betti(c, level)?;
    Ok(SolidRow {
        level,
        volumes: b.cells[0],
        faces: b.cells[1],
        edges: b.cells[2],
        corners: b.cells[3],
        euler: b.euler,
        components: b.b0,
        voids: 0,
        tunnels: b.b1,
    })
}

/// The rows are levels 0, 1, … in order, none above the cells the step builds.
pub(super) fn admissible(levels: &[u64], sizes: &[u64]) -> Result<(), String> {
    if levels.is_empty() {
        return Err("no row".into());
    }
    for (i, (&l, &cells)) in levels.iter().zip(sizes).enumerate() {
        if l != i as u64 {
            return Err(format!("row {i} is for level {l}"));
        }
        if cells > MAX_CELLS {
            return Err(super::over(
                &format!("building the level-{i} complex (cells)"),
                cells.into(),
                MAX_CELLS.into(),
                "max-work",
            ));
        }
    }
    Ok(())
}

/// Builds the next level of `c` (level `i`), within the budget on its size: faces have at most
/// 4·n sides per edge side after one step (pieces, gap sides, spokes, lacuna sides), volumes
/// their level-1 surfaces.
pub(super) fn grow(c: &mut Complex, i: usize) -> Result<(), String> {
    let face_sides: u128 = c
        .faces
        .iter()
        .flat_map(|f| &f.ty.boundary)
        .map(|e| u128::from(e.n).saturating_mul(4))
        .fold(0, u128::saturating_add);
    let sides = c
        .vols
        .iter()
        .map(|v| super::volume::level1_sides(&v.v))
        .fold(face_sides, u128::saturating_add);
    if sides > 8 * u128::from(MAX_CELLS) {
        return Err(super::over(
            &format!("building the level-{i} complex (sides after one step)"),
            sides,
            8 * u128::from(MAX_CELLS),
            "max-work",
        ));
    }
    *c = next(c)?;
    Ok(())
}

/// The most cells of the solid the step builds at one level by default: the ranks cost about
/// the square of the faces of a level in the worst case; the work budget meters them.
const MAX_CELLS: u64 = 400_000;

/// Checks the solid-homology step against the claim's volumes.
pub(super) fn check_solid(
    s: &SolidHomologyStep,
    claim: &VolumesClaim,
) -> Result<(String, String), String> {
    let sizes: Vec<u64> = s
        .rows
        .iter()
        .map(|r| {
            [r.volumes, r.faces, r.edges, r.corners]
                .iter()
                .fold(0u64, |a, &x| a.saturating_add(x))
        })
        .collect();
    let levels: Vec<u64> = s.rows.iter().map(|r| r.level).collect();
    admissible(&levels, &sizes)?;
    let mut c = start(claim)?;
    let mut lines = Vec::new();
    for (i, claimed) in s.rows.iter().enumerate() {
        if i > 0 {
            // A level is built only from one that had the claimed cells.
            grow(&mut c, i)?;
        }
        let built = c.cells() as u64;
        let listed = claimed
            .volumes
            .saturating_add(claimed.faces)
            .saturating_add(claimed.edges);
        if built != listed {
            return Err(format!(
                "level {i}: the solid built has {} volumes, {} faces and {} edges; the row says \
                 {}, {} and {}",
                c.vols.len(),
                c.faces.len(),
                c.edges.len(),
                claimed.volumes,
                claimed.faces,
                claimed.edges
            ));
        }
        let got = row(&c, i as u64)?;
        if got != *claimed {
            return Err(format!(
                "level {i}: re-derived {} volumes, {} faces, {} edges, {} corners, χ = {}, b0 = \
                 {}, b2 = {}, b1 = {}; the row says {}, {}, {}, {}, χ = {}, b0 = {}, b2 = {}, \
                 b1 = {}",
                got.volumes,
                got.faces,
                got.edges,
                got.corners,
                got.euler,
                got.components,
                got.voids,
                got.tunnels,
                claimed.volumes,
                claimed.faces,
                claimed.edges,
                claimed.corners,
                claimed.euler,
                claimed.components,
                claimed.voids,
                claimed.tunnels
            ));
        }
        lines.push(format!(
            "level {i}: {}, {}, {}, {}, χ = {}, {}, {}, {}",
            super::counted(got.volumes, "volume", "volumes"),
            super::counted(got.faces, "face", "faces"),
            super::counted(got.edges, "edge", "edges"),
            super::counted(got.corners, "corner", "corners"),
            got.euler,
            super::counted(got.components, "component", "components"),
            super::counted(got.voids, "void", "voids"),
            super::counted(got.tunnels, "tunnel", "tunnels")
        ));
    }
    let last = s.rows.len() - 1;
    let msg = format!(
        "the level-n solid built cell by cell at levels 0–{last} from the claim's volumes{} \
         (every face subdivided once and matched from each volume reading it, sub-volumes, side \
         and inner faces, radial and inner edges, corners), cells counted, b0 from the \
         1-skeleton, the ranks of ∂2 and ∂3 over F2: b2 = b3 = 0, so the rational Betti numbers \
         equal the F2 ones",
        match claim.shared.len() {
            0 => String::new(),
            n => format!(
                " with their {}",
                super::counted(n, "shared face", "shared faces")
            ),
        }
    );
    Ok((msg, format!("the level-n solid: {}", lines.join("; "))))
}

#[cfg(test)]
mod tests {
    use super::volume_tests::{b2, cube};
    use super::*;
    use crate::certificate::SharedFaceClaim;

    fn claim(volumes: Vec<Volume>, shared: Vec<SharedFaceClaim>) -> VolumesClaim {
        VolumesClaim {
            volumes,
            levels: 1,
            shared,
        }
    }

    fn rows(c: &VolumesClaim, levels: usize) -> Vec<SolidRow> {
        let mut x = start(c).unwrap();
        let mut out = vec![row(&x, 0).unwrap()];
        for level in 1..=levels {
            x = next(&x).unwrap();
            out.push(row(&x, level as u64).unwrap());
        }
        out
    }

    fn r(v: u64, f: u64, e: u64, c: u64, euler: i64, b0: u64, b1: u64) -> SolidRow {
        SolidRow {
            level: 0,
            volumes: v,
            faces: f,
            edges: e,
            corners: c,
            euler,
            components: b0,
            voids: 0,
            tunnels: b1,
        }
    }

    #[test]
    fn the_cube_at_level_one_by_hand() {
        let got = rows(&claim(vec![cube()], Vec::new()), 1);
        // Level 0: the cube, 1 volume, 6 faces, 12 edges, 8 corners, χ = 1, a ball.
        assert_eq!(got[0], r(1, 6, 12, 8, 1, 1, 0));
        // Level 1 (THEORY §10, B2 squares, spokes at the 4 joints of each face, V1):
        // faces: 6·4 pentagons on the surface, one side face per spoke (24, shared by the two
        // sub-volumes beside it), one per lacuna side (24 walls), one inner face per sub-volume
        // (8): 80. Edges: 12·2 pieces, per square 4 spokes and 4 lacuna sides (48), one radial
        // edge per rim point of the level-1 surface (24 lacuna corners and 12 joints: 36) and
        // one inner edge per side face (48): 156. Corners: 8 + 12 joints + 24 lacuna corners +
        // 36 inner ends of the radial edges = 80. χ = 80 − 156 + 80 − 8 = −4; one component,
        // no cavity (it opens through the six lacunas), so b1 = 1 + 0 − (−4) = 5: a hollow
        // cube with six windows.
        assert_eq!(
            got[1],
            SolidRow {
                level: 1,
                ..r(8, 80, 156, 80, -4, 1, 5)
            }
        );
    }

    #[test]
    fn two_cubes_glued_by_hand() {
        // Face 5 of the first cube (corners 1 3 7 5, x = 1) on face 4 of the second (corners
        // 0 4 6 2, x = 0 of the second): corner 1 of the first is corner 0 of the second, so
        // edge 0 (1 → 3) lies on the second's edge 3 (2 → 0).
        let shared = vec![SharedFaceClaim {
            a: [0, 5, 0],
            b: [1, 4, 3],
        }];
        let got = rows(&claim(vec![cube(), cube()], shared), 1);
        // Level 0: 2 volumes, 11 faces, 20 edges, 12 corners; χ = 12 − 20 + 11 − 2 = 1.
        assert_eq!(got[0], r(2, 11, 20, 12, 1, 1, 0));
        // Level 1: twice the cube's level-1 cells, less the shared face's copy of what lies
        // on it (4 pentagons; 4·2 pieces, 4 spokes and 4 lacuna sides: 16 edges; its 4 corners,
        // 4 joints and 4 lacuna corners: 12): 160 − 4 = 156 faces, 312 − 16 = 296 edges,
        // 160 − 12 = 148 corners; χ = 148 − 296 + 156 − 16 = −8, b1 = 9.
        assert_eq!(
            got[1],
            SolidRow {
                level: 1,
                ..r(16, 156, 296, 148, -8, 1, 9)
            }
        );
    }

    #[test]
    fn a_shared_face_read_alike_from_both_sides_is_required() {
        // The same face on both sides, but not read the other way round (edge 0 on edge 0
        // makes corners meet out of turn): refused, or the level-0 gluing fails.
        let mut other = cube();
        other.faces[4].boundary[0] = Edge { n: 3, ..b2() };
        let shared = vec![SharedFaceClaim {
            a: [0, 5, 0],
            b: [1, 4, 3],
        }];
        let e = start(&claim(vec![cube(), other], shared)).err();
        assert!(e.is_some(), "a face of another type was accepted as shared");
        let twice = vec![
            SharedFaceClaim {
                a: [0, 5, 0],
                b: [1, 4, 3],
            },
            SharedFaceClaim {
                a: [0, 5, 0],
                b: [1, 2, 0],
            },
        ];
        let e = start(&claim(vec![cube(), cube()], twice)).err().unwrap();
        assert!(e.contains("shared twice"), "{e}");
    }

    #[test]
    fn ranks_over_f2_cancel_pairs() {
        // A triangle's three edges as columns over its three corners: rank 2 (the sum of the
        // columns is 0 over F2); a column meeting a row twice is 0.
        assert_eq!(rank_f2(vec![vec![0, 1], vec![1, 2], vec![0, 2]]), Ok(2));
        assert_eq!(rank_f2(vec![vec![3, 3]]), Ok(0));
    }
}
