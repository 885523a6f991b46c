//! The level-n solid of a volume in 3D (THEORY §10), for pictures and printable meshes.
//!
//! **What this is.** A default placement, not a solution of the BC-IFS constraint system: the
//! start volume is a regular solid (its corners on known coordinates), and every step places
//! the new points by simple rules on the points already placed. Floats live here only; every
//! cell, incidence and count comes from the exact step ([`subdivide_volume`] and
//! [`crate::topology::subdivision::subdivide`]), so the geometry cannot have other cells than the
//! topology: the cells built here are counted and compared with
//! [`crate::topology::volume::solid_topology`] by the mesh layer.
//!
//! **Cells.** Points, edges (straight segments between two points), faces (a loop of edges, with
//! a centre point used to place their inner points and to triangulate them) and volumes (a
//! canonical [`Volume`] with, for every face of its surface, the global face it reads and how).
//! A face shared by two volumes is one global face, subdivided once: the points and edges born
//! inside a face are keyed by what identifies them on either side (the junction point of a
//! spoke, the boundary pieces of a sub-face, the end point of a gap), so the second reader finds
//! what the first made. A reader that would make a different cell is refused.
//!
//! **Placement rules.**
//! - An edge's pieces split its segment evenly; a `Cn` edge has n pieces and n − 1 gaps of equal
//!   length.
//! - Inside a face with centre `c`: the lacuna corner of the spoke at junction point `j` is
//!   `c + λ(j − c)` (λ = [`LACUNA`]), the point of a gap with ends `a`, `b` is
//!   `m + μ(c − m)` with `m = (a + b)/2` (μ = [`NOTCH`]).
//! - Inside a volume with centre `o` (the mean of the corners of its faces, a corner counted once
//!   for every face that holds it): the inner corner at the end of the radial edge from a rim
//!   point `p` is `p + σ(o − p)` (σ = [`SHRINK`]). The side face over a rim edge then lies in the
//!   cone from `o` over that edge, and the inner face is the rim loop shrunk towards `o`. (An
//!   earlier rule pushed `p` along the summed outward normals of its faces by one depth per
//!   volume; on the non-convex pieces of level 2 and beyond the pushed copies crossed.) Side faces
//!   join a rim edge to its inner copy; the inner face is the loop of inner corners.
//! - A face's centre is the mean of its corners; a cap of a delayed volume is pushed into its
//!   volume by [`PUSH`] of the way to the volume's centre, so that two caps over one hole part.
//! - [`InnerFan::Radial`], the third way the mesh layer tries when the first two fold (issue
//!   #31), changes four of these rules: the volume's centre sees its level-1 surface, an inner
//!   face is fanned around a point from which the centre sees every fan triangle, the shrink is
//!   lowered where the inner face would reach its patch (`reach`), and a face whose mean lies
//!   outside its kernel is centred at a kernel point.

use crate::error::{Diagnostic, Error, Result};
use crate::input::Corners;
use crate::topology::edge::{EdgeType, JunctionKind};
use crate::topology::face::Face;
use crate::topology::subdivision::{subdivide, Origin, Subdivision};
use crate::topology::volume::{subdivide_volume, Solid, Volume, VolumeAssembly, VolumeSubdivision};
use std::collections::HashMap;
use std::rc::Rc;

/// A point in space.
pub type P3 = [f64; 3];

/// λ: where a lacuna corner lies between the face centre and its spoke's junction point.
pub const LACUNA: f64 = 0.5;
/// μ: how far a gap's point lies from the gap towards the face centre.
pub const NOTCH: f64 = 0.25;
/// κ: how far the centre of a cap of a delayed volume is pushed towards the volume's centre.
pub const PUSH: f64 = 0.2;
/// σ: the fraction of the way from a rim point to its volume's centre at which its inner corner
/// (the end of its radial edge) is placed.
pub const SHRINK: f64 = 0.5;

/// An edge: a straight segment from point `a` to point `b`.
#[derive(Clone, Debug)]
pub struct GeoEdge {
    /// Start point.
    pub a: usize,
    /// End point.
    pub b: usize,
    /// Its type.
    pub ty: EdgeType,
}

/// A face: a loop of edges as its first reader reads it.
#[derive(Clone, Debug)]
pub struct GeoFace {
    /// Its type as read by its first reader.
    pub face: Face,
    /// Corner `i` is where side `i` starts.
    pub corners: Vec<usize>,
    /// The centre: inner points are placed towards it, and the face is triangulated as a fan
    /// around it.
    pub center: P3,
}

/// One face of a volume's surface as the volume reads it (counter-clockwise from outside).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Reading {
    /// The global face.
    pub face: usize,
    /// Corner `i`: the start of side `i`.
    pub corners: Vec<usize>,
    /// The edge of side `i`.
    pub edges: Vec<usize>,
    /// Whether side `i` runs along its edge (from `a` to `b`).
    pub forward: Vec<bool>,
}

/// A volume of the evaluated solid.
#[derive(Clone, Debug)]
pub struct GeoVolume {
    /// The volume (its surface in the form the step gives it).
    pub volume: Volume,
    /// `faces[k]` reads face `k` of `volume.surface`.
    pub faces: Vec<Reading>,
}

/// The solid of one level: every cell with its geometry.
#[derive(Clone, Debug)]
pub struct SolidGeometry {
    /// The level.
    pub level: u32,
    /// Every point made so far (cells of this level and of the levels before).
    pub points: Vec<P3>,
    /// Every edge made so far.
    pub edges: Vec<GeoEdge>,
    /// Every face made so far.
    pub faces: Vec<GeoFace>,
    /// The volumes of this level.
    pub volumes: Vec<GeoVolume>,
    /// The holes the last step opened, as loops of points: the lacuna of every face it
    /// subdivided (its lacuna corners) and every gap of a `Cn` edge (its two ends).
    pub holes: Vec<Vec<usize>>,
}

impl SolidGeometry {
    /// The cells of this level: (volumes, faces, edges, corners), each counted once.
    pub fn cell_counts(&self) -> (usize, usize, usize, usize) {
        let mut faces = std::collections::HashSet::new();
        let mut edges = std::collections::HashSet::new();
        let mut corners = std::collections::HashSet::new();
        for v in &self.volumes {
            for r in &v.faces {
                faces.insert(r.face);
                edges.extend(r.edges.iter().copied());
                corners.extend(r.corners.iter().copied());
            }
        }
        (self.volumes.len(), faces.len(), edges.len(), corners.len())
    }

    /// For every face of this level, the volumes that hold it, with the reading of each.
    pub fn face_readers(&self) -> HashMap<usize, Vec<(usize, usize)>> {
        let mut out: HashMap<usize, Vec<(usize, usize)>> = HashMap::new();
        for (vi, v) in self.volumes.iter().enumerate() {
            for (k, r) in v.faces.iter().enumerate() {
                out.entry(r.face).or_default().push((vi, k));
            }
        }
        out
    }
}

fn geometry_error(code: &'static str, message: String) -> Error {
    Error::Syntax(Box::new(Diagnostic {
        code,
        message,
        span: None,
        source: None,
    }))
}

fn add(a: P3, b: P3) -> P3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn sub(a: P3, b: P3) -> P3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn scale(a: P3, s: f64) -> P3 {
    [a[0] * s, a[1] * s, a[2] * s]
}
fn lerp(a: P3, b: P3, t: f64) -> P3 {
    add(a, scale(sub(b, a), t))
}
fn dot(a: P3, b: P3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: P3, b: P3) -> P3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn norm(a: P3) -> f64 {
    dot(a, a).sqrt()
}
fn mean(points: impl Iterator<Item = P3>) -> P3 {
    let (mut s, mut n) = ([0.0; 3], 0.0f64);
    for p in points {
        s = add(s, p);
        n += 1.0;
    }
    scale(s, 1.0 / n.max(1.0))
}

/// The corners of a solid, indexed as [`Solid::polygons`] numbers them: regular solids with
/// their centre at the origin and edges of comparable length.
pub fn solid_corners(solid: Solid) -> Vec<P3> {
    match solid {
        Solid::Cube => (0..8)
            .map(|i| {
                let b = |k: usize| if i >> k & 1 == 1 { 1.0 } else { -1.0 };
                [b(0), b(1), b(2)]
            })
            .collect(),
        Solid::Tetrahedron => vec![
            [1.0, 1.0, 1.0],
            [1.0, -1.0, -1.0],
            [-1.0, 1.0, -1.0],
            [-1.0, -1.0, 1.0],
        ],
        Solid::Octahedron => vec![
            [1.5, 0.0, 0.0],
            [-1.5, 0.0, 0.0],
            [0.0, 1.5, 0.0],
            [0.0, -1.5, 0.0],
            [0.0, 0.0, 1.5],
            [0.0, 0.0, -1.5],
        ],
        Solid::Prism(n) => {
            let h = (std::f64::consts::PI / n as f64).sin();
            let ring = |z: f64| {
                (0..n).map(move |i| {
                    let a = 2.0 * std::f64::consts::PI * i as f64 / n as f64;
                    [a.cos(), a.sin(), z]
                })
            };
            ring(-h).chain(ring(h)).collect()
        }
        Solid::TruncatedTetrahedron => {
            let t = solid_corners(Solid::Tetrahedron);
            (0..16)
                .map(|id| {
                    let (v, w) = (id / 4, id % 4);
                    if v == w {
                        [0.0; 3]
                    } else {
                        lerp(t[v], t[w], 1.0 / 3.0)
                    }
                })
                .collect()
        }
    }
}

/// The solids whose surface a volume may have been written with.
fn candidates() -> impl Iterator<Item = Solid> {
    [
        Solid::Cube,
        Solid::Tetrahedron,
        Solid::Octahedron,
        Solid::TruncatedTetrahedron,
    ]
    .into_iter()
    .chain((3..=64).map(Solid::Prism))
}

/// The default placement of a volume's surface: the solid it was written as (its gluing is that
/// solid's), with the solid's corners. `None` when the surface is no shorthand solid.
pub fn default_placement(v: &Volume) -> Option<(Solid, Vec<Vec<P3>>)> {
    let first = v.surface.faces.first()?;
    for s in candidates() {
        let polys = s.polygons();
        if polys.len() != v.surface.faces.len() {
            continue;
        }
        if s.surface_with(|_| first.boundary[0], first).glue != v.surface.glue {
            continue;
        }
        let mut corners = solid_corners(s);
        // Counter-clockwise from outside: the enclosed volume is positive; mirror otherwise.
        let vol: f64 = polys
            .iter()
            .map(|p| {
                (1..p.len() - 1)
                    .map(|i| dot(corners[p[0]], cross(corners[p[i]], corners[p[i + 1]])))
                    .sum::<f64>()
            })
            .sum();
        if vol < 0.0 {
            for c in &mut corners {
                c[0] = -c[0];
            }
        }
        let placed = polys
            .iter()
            .map(|p| p.iter().map(|&i| corners[i]).collect())
            .collect();
        return Some((s, placed));
    }
    None
}

/// How the inner face of a sub-volume (its rim shrunk towards the volume's centre, see
/// [`SHRINK`]) is drawn: a fan of triangles around one centre point. Two rules, because each
/// folds where the other does not (`docs/volume-sweep.sh`); the mesh layer tries them in order
/// and keeps the first whose solid embeds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InnerFan {
    /// Around the mean of the inner face's corners.
    RimMean,
    /// Around the same shrink of a point M of the patch (a corner of the patch inside it, the
    /// middle of an edge between two of its sub-faces, or a sub-face's centre: the one with the
    /// least sum of squared distances to the rim's corners), so that the fan is the shrunk image
    /// of a fan on the patch. Around the rim's mean, the fan of a strongly bent rim (two faces
    /// meeting in a valley seen from the centre) can cut through the patch.
    PatchPoint,
    /// Around the same shrink of a point from which every triangle of the rim's fan is seen from
    /// the volume's centre (counter-clockwise from outside), with the step's shrink lowered below
    /// [`SHRINK`] where an inner face would otherwise reach its patch; the volume's centre is
    /// then chosen to see the sub-faces of its level-1 surface, on which the sub-volumes stand
    /// (issue #31: at level 3, the inner face of a sub-volume over a patch bent around a corner of
    /// the cavity cut through that patch under both rules above).
    Radial,
}

impl InnerFan {
    /// Every rule, in the order the mesh layer tries them.
    pub const ALL: [InnerFan; 3] = [InnerFan::RimMean, InnerFan::PatchPoint, InnerFan::Radial];

    /// A few words for reports.
    pub fn describe(self) -> &'static str {
        match self {
            InnerFan::RimMean => "inner faces fanned around their mean",
            InnerFan::PatchPoint => {
                "inner faces fanned around the shrink of a point of their patch"
            }
            InnerFan::Radial => {
                "inner faces fanned around a point seen from their volume's centre, and shrunk to stay inside their patch's cone"
            }
        }
    }
}

/// The pieces of an edge, in its direction: (start point, end point, piece edge).
type Pieces = Vec<(usize, usize, usize)>;

/// One face of a volume as the step reads it: its sub-faces in the form the step builds them.
struct SubReadings {
    /// `subs[k]`: sub-face `k` of the canonical subdivision, read from its canonical start.
    subs: Vec<Reading>,
}

/// Builds the solid level by level.
struct Builder {
    fan: InnerFan,
    points: Vec<P3>,
    edges: Vec<GeoEdge>,
    faces: Vec<GeoFace>,
    pieces: HashMap<usize, Pieces>,
    gap_point: HashMap<(usize, usize), usize>,
    spoke: HashMap<(usize, usize), (usize, usize)>,
    lacuna: HashMap<(usize, usize), usize>,
    gap_side: HashMap<(usize, usize), usize>,
    subface: HashMap<(usize, usize), usize>,
    side: HashMap<(usize, usize), usize>,
    inner_edge: HashMap<usize, usize>,
    steps: HashMap<Volume, Rc<VolumeSubdivision>>,
    face_steps: HashMap<Face, Rc<Subdivision>>,
    holes: Vec<Vec<usize>>,
}

impl Builder {
    fn point(&mut self, p: P3) -> usize {
        self.points.push(p);
        self.points.len() - 1
    }

    fn edge(&mut self, a: usize, b: usize, ty: EdgeType) -> usize {
        self.edges.push(GeoEdge { a, b, ty });
        self.edges.len() - 1
    }

    fn face(&mut self, face: Face, corners: Vec<usize>, center: Option<P3>) -> usize {
        let center = center.unwrap_or_else(|| {
            let pts: Vec<P3> = corners.iter().map(|&c| self.points[c]).collect();
            match self.fan {
                InnerFan::Radial => face_centre(&pts),
                _ => mean(pts.iter().copied()),
            }
        });
        self.faces.push(GeoFace {
            face,
            corners,
            center,
        });
        self.faces.len() - 1
    }

    /// The pieces of edge `e` in its direction.
    fn pieces(&mut self, e: usize) -> Pieces {
        if let Some(p) = self.pieces.get(&e) {
            return p.clone();
        }
        let GeoEdge { a, b, ty } = self.edges[e].clone();
        let n = ty.piece_count() as usize;
        let (pa, pb) = (self.points[a], self.points[b]);
        let mut out = Vec::with_capacity(n);
        match ty.inner_junction() {
            Some(JunctionKind::Gap) => {
                // n pieces and n − 1 gaps of equal length.
                let len = (2 * n - 1) as f64;
                let mut start = a;
                for q in 0..n {
                    let end = if q + 1 == n {
                        b
                    } else {
                        self.point(lerp(pa, pb, (2 * q + 1) as f64 / len))
                    };
                    let id = self.edge(start, end, ty.piece());
                    out.push((start, end, id));
                    if q + 1 < n {
                        start = self.point(lerp(pa, pb, (2 * q + 2) as f64 / len));
                        self.holes.push(vec![end, start]);
                    }
                }
            }
            _ => {
                let mut start = a;
                for q in 0..n {
                    let end = if q + 1 == n {
                        b
                    } else {
                        self.point(lerp(pa, pb, (q + 1) as f64 / n as f64))
                    };
                    let id = self.edge(start, end, ty.piece());
                    out.push((start, end, id));
                    start = end;
                }
            }
        }
        self.pieces.insert(e, out.clone());
        out
    }

    fn face_step(&mut self, f: &Face) -> Result<Rc<Subdivision>> {
        if let Some(s) = self.face_steps.get(f) {
            return Ok(s.clone());
        }
        let s = Rc::new(subdivide(f)?);
        self.face_steps.insert(f.clone(), s.clone());
        Ok(s)
    }

    /// The sub-faces of a face as a volume reads it (`face` its type in that reading).
    fn subdivide_reading(&mut self, face: &Face, r: &Reading) -> Result<SubReadings> {
        let g = r.face;
        let (canon, rot) = face.canonical();
        let sub = self.face_step(&canon)?;
        let n = face.boundary.len();
        // Piece q of canonical edge e, in the reading's direction: (start, end, edge, forward).
        let mut piece_of: HashMap<(usize, usize), (usize, usize, usize, bool)> = HashMap::new();
        for e in 0..n {
            let side = (e + rot) % n;
            let edge = r.edges[side];
            let list = self.pieces(edge);
            let count = list.len();
            for q in 0..count {
                let item = if r.forward[side] {
                    let (s, t, id) = list[q];
                    (s, t, id, true)
                } else {
                    let (s, t, id) = list[count - 1 - q];
                    (t, s, id, false)
                };
                piece_of.insert((e, q), item);
            }
        }
        // The flattened pieces with their junctions.
        let mut flat: Vec<(usize, usize)> = Vec::new();
        for (e, ty) in canon.boundary.iter().enumerate() {
            for q in 0..ty.piece_count() as usize {
                flat.push((e, q));
            }
        }
        let center = self.faces[g].center;
        // The point of the gap after flattened piece m (kept by the gap's first end).
        let gap_point = |me: &mut Builder, m: usize| -> usize {
            let (_, end, _, _) = piece_of[&flat[m]];
            let (start, _, _, _) = piece_of[&flat[(m + 1) % flat.len()]];
            let key = (g, end.min(start));
            if let Some(&p) = me.gap_point.get(&key) {
                return p;
            }
            let mid = lerp(me.points[end], me.points[start], 0.5);
            let p = me.point(lerp(mid, center, NOTCH));
            me.gap_point.insert(key, p);
            p
        };
        let junction_point = |me: &mut Builder, m: usize| -> usize {
            match sub.junctions[m].kind {
                JunctionKind::Gap => gap_point(me, m),
                _ => piece_of[&flat[m]].1,
            }
        };
        // Spokes: (edge from the junction point to the lacuna corner, lacuna corner).
        let mut spokes = Vec::with_capacity(sub.spokes.len());
        for &m in &sub.spokes {
            let j = junction_point(self, m);
            let key = (g, j);
            let s = match self.spoke.get(&key) {
                Some(&s) => s,
                None => {
                    let l = self.point(lerp(center, self.points[j], LACUNA));
                    let e = self.edge(j, l, canon.params.ea);
                    self.spoke.insert(key, (e, l));
                    (e, l)
                }
            };
            spokes.push((j, s.0, s.1));
        }
        if spokes.len() > 1 && !self.spoke.contains_key(&(g, usize::MAX)) {
            // Once per face: its lacuna (the mark is a key no point has).
            self.spoke.insert((g, usize::MAX), (0, 0));
            self.holes.push(spokes.iter().map(|s| s.2).collect());
        }
        let mut subs = Vec::with_capacity(sub.subfaces.len());
        for s in &sub.subfaces {
            // The sub-face's key: its least piece edge.
            let subkey = s
                .origins
                .iter()
                .filter_map(|o| match *o {
                    Origin::Piece { edge, piece } => Some(piece_of[&(edge, piece)].2),
                    _ => None,
                })
                .min()
                .ok_or_else(|| {
                    geometry_error(
                        "E1211",
                        format!("a sub-face of `{canon}` has no piece of the face's boundary"),
                    )
                })?;
            let len = s.origins.len();
            let mut corners = Vec::with_capacity(len);
            let mut edges = Vec::with_capacity(len);
            let mut forward = Vec::with_capacity(len);
            for (p, o) in s.origins.iter().enumerate() {
                let (start, edge, fwd) = match *o {
                    Origin::Piece { edge, piece } => {
                        let (a, _, id, f) = piece_of[&(edge, piece)];
                        (a, id, f)
                    }
                    Origin::Spoke { spoke, inward } => {
                        let (j, e, l) = spokes[spoke];
                        if inward {
                            (j, e, true)
                        } else {
                            (l, e, false)
                        }
                    }
                    Origin::Lacuna { side } => {
                        let from = spokes[(side + 1) % spokes.len()].2;
                        let to = spokes[side].2;
                        match self.lacuna.get(&(g, subkey)) {
                            Some(&e) => (from, e, false),
                            None => {
                                let e = self.edge(from, to, canon.params.el);
                                self.lacuna.insert((g, subkey), e);
                                (from, e, true)
                            }
                        }
                    }
                    Origin::GapSide { edge, gap, after } => {
                        // Flattened index of piece `gap` of canonical edge `edge`.
                        let m = flat
                            .iter()
                            .position(|&x| x == (edge, gap))
                            .expect("the gap's piece is on the boundary");
                        let gp = gap_point(self, m);
                        let end = if after {
                            piece_of[&flat[(m + 1) % flat.len()]].0
                        } else {
                            piece_of[&flat[m]].1
                        };
                        let e = match self.gap_side.get(&(g, end)) {
                            Some(&e) => e,
                            None => {
                                let e = self.edge(end, gp, canon.params.ec);
                                self.gap_side.insert((g, end), e);
                                e
                            }
                        };
                        if after {
                            (gp, e, false)
                        } else {
                            (end, e, true)
                        }
                    }
                };
                corners.push(start);
                edges.push(edge);
                forward.push(fwd);
                let _ = p;
            }
            // The sides must chain: each ends where the next starts.
            for p in 0..len {
                let e = &self.edges[edges[p]];
                let end = if forward[p] { e.b } else { e.a };
                if end != corners[(p + 1) % len] {
                    return Err(geometry_error(
                        "E1211",
                        format!("the sub-faces of `{canon}` do not close as read from this side"),
                    ));
                }
            }
            let id = match self.subface.get(&(g, subkey)) {
                Some(&id) => {
                    let mut mine = corners.clone();
                    let mut theirs = self.faces[id].corners.clone();
                    mine.sort_unstable();
                    theirs.sort_unstable();
                    if mine != theirs {
                        return Err(geometry_error(
                            "E1211",
                            format!(
                                "face `{canon}` is subdivided differently from its two sides: the geometry needs one subdivision of a shared face"
                            ),
                        ));
                    }
                    id
                }
                None => {
                    let id = self.face(s.face.clone(), corners.clone(), None);
                    self.subface.insert((g, subkey), id);
                    id
                }
            };
            subs.push(Reading {
                face: id,
                corners,
                edges,
                forward,
            });
        }
        Ok(SubReadings { subs })
    }

    /// The point the sub-volumes of `gv` shrink towards: the mean of the corners of its faces (a
    /// corner counted once per face that holds it) when the whole surface is seen from there
    /// from inside — every fan triangle of every face with the point strictly on its inner side
    /// (the point lies in the surface's *kernel*) — else the point of the kernel nearest to that
    /// mean with a margin of half the kernel's inradius, found by two linear programs; the mean
    /// when the kernel is empty (the volume is not star-shaped; the placement may then fold, and
    /// the mesh check says so).
    ///
    /// Shrinking towards a kernel point keeps the side faces of two sub-volumes in disjoint
    /// cones; towards the mean of a non-convex volume (the bent pieces next to a Cantor gap) some
    /// faces are seen from behind and the sub-volumes over them fold.
    ///
    /// `seen`: the faces whose fan triangles the point must see (the volume's own faces when
    /// empty).
    fn star_centre(&self, gv: &GeoVolume, seen: &[&Reading]) -> P3 {
        let m = mean(
            gv.faces
                .iter()
                .flat_map(|r| r.corners.iter())
                .map(|&c| self.points[c]),
        );
        // Outward unit normals and a point of every fan triangle.
        let mut planes: Vec<(P3, P3)> = Vec::new();
        let mut size = 0.0f64;
        let own: Vec<&Reading> = gv.faces.iter().collect();
        let seen = if seen.is_empty() { &own[..] } else { seen };
        for r in seen.iter().copied() {
            let c = self.faces[r.face].center;
            let n = r.corners.len();
            for i in 0..n {
                let a = self.points[r.corners[i]];
                let b = self.points[r.corners[(i + 1) % n]];
                size = size.max(norm(sub(a, m)));
                let nn = cross(sub(a, c), sub(b, c));
                let l = norm(nn);
                if l > 0.0 {
                    planes.push((scale(nn, 1.0 / l), c));
                }
            }
        }
        let margin = |x: P3| {
            planes
                .iter()
                .map(|(n, c)| -dot(*n, sub(x, *c)))
                .fold(f64::INFINITY, f64::min)
        };
        if margin(m) > 1e-9 * size {
            return m;
        }
        kernel_point(&planes, m, size).unwrap_or(m)
    }

    fn volume_step(&mut self, v: &Volume) -> Result<Rc<VolumeSubdivision>> {
        if let Some(s) = self.steps.get(v) {
            return Ok(s.clone());
        }
        let s = Rc::new(subdivide_volume(v)?);
        self.steps.insert(v.clone(), s.clone());
        Ok(s)
    }

    /// The sub-volumes of one volume (number `vid` of its level, for keys).
    fn step(&mut self, vid: usize, gv: &GeoVolume) -> Result<Vec<GeoVolume>> {
        let v = &gv.volume;
        let step = self.volume_step(v)?;
        let mut subs = Vec::with_capacity(gv.faces.len());
        for (k, r) in gv.faces.iter().enumerate() {
            subs.push(self.subdivide_reading(&v.surface.faces[k], r)?);
        }
        let radial = self.fan == InnerFan::Radial && v.delay < 2;
        let vcenter = if radial {
            // The sub-volumes stand on the level-1 surface: the centre must see its sub-faces.
            let level_one: Vec<&Reading> = subs.iter().flat_map(|s| s.subs.iter()).collect();
            self.star_centre(gv, &level_one)
        } else {
            self.star_centre(gv, &[])
        };
        let (shrink, radial_centres) = if radial {
            self.radial_fans(&step, &subs, vcenter)
        } else {
            (SHRINK, Vec::new())
        };
        // Every rim point goes [`SHRINK`] of the way to the volume's centre: the side face over a
        // rim edge lies in the cone from the centre over that edge, so the side faces of two rim
        // edges meet only along the radial edge they share, and the inner face is the rim loop
        // shrunk towards the centre (no offset along summed normals, which folds where the
        // volume is not convex).
        let inner_of = |me: &mut Builder, p: usize| -> P3 { lerp(me.points[p], vcenter, shrink) };
        let mut out = Vec::with_capacity(step.subvolumes.len());
        if v.delay >= 2 {
            let s = &step.subvolumes[0];
            let mut faces: Vec<Option<Reading>> = vec![None; s.volume.surface.faces.len()];
            for &((f, k), placed) in &s.subfaces {
                faces[placed.face] = Some(rotated(
                    &subs[f].subs[k],
                    surface_rotation(&s.volume, placed),
                ));
            }
            let faces = self.fill(&s.volume, faces, Some(vcenter), None)?;
            out.push(GeoVolume {
                volume: s.volume.clone(),
                faces,
            });
            return Ok(out);
        }
        // Radial slots: slot (s, i) is the radial edge at the start of rim side i of sub-volume
        // s; the sub-volumes of a fan share it through their spoke faces.
        let offsets: Vec<usize> = step
            .subvolumes
            .iter()
            .scan(0usize, |acc, s| {
                let o = *acc;
                *acc += s.sides.len();
                Some(o)
            })
            .collect();
        let slots =
            offsets.last().map_or(0, |&o| o) + step.subvolumes.last().map_or(0, |s| s.sides.len());
        let mut dsu = crate::topology::component::Dsu::new(slots);
        let rim = |s: usize, i: usize| -> (usize, bool, usize, usize) {
            let ((f, k, p), _) = step.subvolumes[s].sides[i];
            let r = &subs[f].subs[k];
            let e = r.edges[p];
            (
                e,
                r.forward[p],
                r.corners[p],
                r.corners[(p + 1) % r.corners.len()],
            )
        };
        let mut over: HashMap<usize, (usize, usize)> = HashMap::new();
        for (s, sv) in step.subvolumes.iter().enumerate() {
            let m = sv.sides.len();
            for i in 0..m {
                let (e, _, _, _) = rim(s, i);
                if let Some(&(s2, i2)) = over.get(&e) {
                    let m2 = step.subvolumes[s2].sides.len();
                    dsu.union(offsets[s] + i, offsets[s2] + (i2 + 1) % m2);
                    dsu.union(offsets[s] + (i + 1) % m, offsets[s2] + i2);
                } else {
                    over.insert(e, (s, i));
                }
            }
        }
        let mut radial: HashMap<usize, (usize, usize)> = HashMap::new();
        let mut slot_edge = |me: &mut Builder, s: usize, i: usize| -> (usize, usize) {
            let root = dsu.find(offsets[s] + i);
            if let Some(&x) = radial.get(&root) {
                return x;
            }
            let (_, _, a, _) = rim(s, i);
            let inner = inner_of(me, a);
            let ia = me.point(inner);
            let e = me.edge(a, ia, v.radial);
            radial.insert(root, (e, ia));
            (e, ia)
        };
        for (s, sv) in step.subvolumes.iter().enumerate() {
            let mut faces: Vec<Option<Reading>> = vec![None; sv.volume.surface.faces.len()];
            for &((f, k), placed) in &sv.subfaces {
                faces[placed.face] = Some(rotated(
                    &subs[f].subs[k],
                    surface_rotation(&sv.volume, placed),
                ));
            }
            let m = sv.sides.len();
            for (i, &(_, placed)) in sv.sides.iter().enumerate() {
                let (e, fwd, a, b) = rim(s, i);
                let (ra, ia) = slot_edge(self, s, i);
                let (rb, ib) = slot_edge(self, s, (i + 1) % m);
                let x = self.edges[e].ty;
                let (id, created) = match self.side.get(&(vid, e)) {
                    Some(&id) => (id, false),
                    None => {
                        let face = v.inner_face(vec![x, v.radial, v.inner, v.radial]);
                        let id = self.face(face, vec![b, a, ia, ib], None);
                        self.side.insert((vid, e), id);
                        (id, true)
                    }
                };
                let ei = match self.inner_edge.get(&id) {
                    Some(&ei) => ei,
                    None => {
                        let ei = self.edge(ia, ib, v.inner);
                        self.inner_edge.insert(id, ei);
                        ei
                    }
                };
                let built = Reading {
                    face: id,
                    corners: vec![b, a, ia, ib],
                    edges: vec![e, ra, ei, rb],
                    forward: vec![!fwd, true, created, false],
                };
                faces[placed.face] = Some(rotated(&built, surface_rotation(&sv.volume, placed)));
            }
            // The inner face is the rim shrunk towards the centre, drawn as a fan (see
            // [`InnerFan`]).
            let centre = match self.fan {
                InnerFan::RimMean => None,
                InnerFan::Radial => radial_centres
                    .get(s)
                    .copied()
                    .flatten()
                    .map(|c| lerp(c, vcenter, shrink)),
                InnerFan::PatchPoint => {
                    let rim_of = |i: usize| {
                        let (e, _, a, _) = rim(s, i);
                        (e, a)
                    };
                    self.patch_point(sv, &subs, (0..m).map(rim_of).collect())
                        .map(|p| lerp(p, vcenter, shrink))
                }
            };
            let faces = self.fill(&sv.volume, faces, None, centre)?;
            out.push(GeoVolume {
                volume: sv.volume.clone(),
                faces,
            });
        }
        Ok(out)
    }

    /// The inner faces of [`InnerFan::Radial`]: the fraction of the way from a rim point to `o`
    /// at which the step places inner corners, and for every sub-volume the point its inner
    /// face is fanned around before that shrink (`None` where no fan of its rim is seen from
    /// `o`; the mean of its rim is used then).
    ///
    /// The fan centre of a sub-volume is the mean of its rim when every fan triangle around it
    /// is seen from `o` counter-clockwise from outside, else a point of the cone of such centres
    /// ([`radial_centre`]). The fraction is [`SHRINK`] times the least [`reach`] of the fans over
    /// their patches (at most 1): the inner face then lies, on every ray from `o`, at most half of
    /// the way from `o` to the patch, so it cannot meet the patch, and it stays in the cone over
    /// the patch, which the other sub-volumes do not enter.
    fn radial_fans(
        &self,
        step: &VolumeSubdivision,
        subs: &[SubReadings],
        o: P3,
    ) -> (f64, Vec<Option<P3>>) {
        let mut least = 1.0f64;
        let mut centres = Vec::with_capacity(step.subvolumes.len());
        for sv in &step.subvolumes {
            let pts: Vec<P3> = sv
                .sides
                .iter()
                .map(|&((f, k, p), _)| self.points[subs[f].subs[k].corners[p]])
                .collect();
            let Some(c) = radial_centre(o, &pts) else {
                centres.push(None);
                continue;
            };
            centres.push(Some(c));
            let m = pts.len();
            let fan: Vec<[P3; 3]> = (0..m).map(|i| [c, pts[i], pts[(i + 1) % m]]).collect();
            let mut patch: Vec<[P3; 3]> = Vec::new();
            for &((f, k), _) in &sv.subfaces {
                let r = &subs[f].subs[k];
                let cc = self.faces[r.face].center;
                let n = r.corners.len();
                for i in 0..n {
                    let (a, b) = (r.corners[i], r.corners[(i + 1) % n]);
                    patch.push([cc, self.points[a], self.points[b]]);
                }
            }
            if let Some(t) = reach(o, &fan, &patch) {
                least = least.min(t);
            }
        }
        (1.0 - (1.0 - SHRINK) * least.min(1.0), centres)
    }

    /// The point M of [`InnerFan::PatchPoint`] for sub-volume `sv`, whose rim is `rim` ((edge,
    /// start point) of every side): among the patch's corners inside it, the middles of the edges
    /// between two of its sub-faces and its sub-faces' centres, the one with the least sum of
    /// squared distances to the rim's points.
    fn patch_point(
        &self,
        sv: &crate::topology::volume::SubVolume,
        subs: &[SubReadings],
        rim: Vec<(usize, usize)>,
    ) -> Option<P3> {
        let rim_ids: std::collections::HashSet<usize> = rim.iter().map(|r| r.1).collect();
        let rim_edges: std::collections::HashSet<usize> = rim.iter().map(|r| r.0).collect();
        let mut candidates: Vec<P3> = Vec::new();
        for &((f, k), _) in &sv.subfaces {
            let r = &subs[f].subs[k];
            candidates.push(self.faces[r.face].center);
            for (j, &c) in r.corners.iter().enumerate() {
                if !rim_ids.contains(&c) {
                    candidates.push(self.points[c]);
                }
                let e = r.edges[j];
                if !rim_edges.contains(&e) {
                    let GeoEdge { a, b, .. } = self.edges[e];
                    candidates.push(lerp(self.points[a], self.points[b], 0.5));
                }
            }
        }
        let spread = |x: P3| {
            rim.iter()
                .map(|r| sub(self.points[r.1], x))
                .map(|d| dot(d, d))
                .sum::<f64>()
        };
        candidates
            .into_iter()
            .min_by(|a, b| spread(*a).total_cmp(&spread(*b)))
    }

    /// Completes the readings of a sub-volume: every face not placed (the inner face, or the caps
    /// of a delayed volume) runs against the placed faces it is glued to. A cap's centre is
    /// pushed towards `push_to`.
    fn fill(
        &mut self,
        v: &Volume,
        mut faces: Vec<Option<Reading>>,
        push_to: Option<P3>,
        centre: Option<P3>,
    ) -> Result<Vec<Reading>> {
        let surface = &v.surface;
        for u in 0..faces.len() {
            if faces[u].is_some() {
                continue;
            }
            let len = surface.faces[u].boundary.len();
            let mut corners = Vec::with_capacity(len);
            let mut edges = Vec::with_capacity(len);
            let mut forward = Vec::with_capacity(len);
            for i in 0..len {
                let (h, j) = surface.glue[u][i];
                let Some(other) = faces[h].as_ref() else {
                    return Err(geometry_error(
                        "E1211",
                        "a face made inside a volume is glued to another such face".into(),
                    ));
                };
                let lh = other.corners.len();
                corners.push(other.corners[(j + 1) % lh]);
                edges.push(other.edges[j]);
                forward.push(!other.forward[j]);
            }
            let center = push_to
                .map(|c| {
                    let m = mean(corners.iter().map(|&p| self.points[p]));
                    lerp(m, c, PUSH)
                })
                .or(centre);
            let id = self.face(surface.faces[u].clone(), corners.clone(), center);
            faces[u] = Some(Reading {
                face: id,
                corners,
                edges,
                forward,
            });
        }
        let faces: Vec<Reading> = faces.into_iter().map(|f| f.expect("filled")).collect();
        check_glue(v, &faces, &self.edges)?;
        Ok(faces)
    }
}

/// The centre of a face with corners `pts`: their mean when the face is star-shaped from it
/// about its Newell normal n (every fan triangle (c, aᵢ, aᵢ₊₁) turns counter-clockwise about n,
/// strictly), else the point of that kernel nearest to the mean (with a margin, in the plane
/// through the mean normal to n; [`kernel_point`]), else the mean.
///
/// Inner points of a face are placed towards its centre (a lacuna corner half-way from the
/// centre to its junction point), and faces are fanned around it: a centre outside the kernel
/// (the mean of an arrow-shaped sub-face at level 3, issue #31) turns fan triangles over and
/// makes sub-faces that cross.
fn face_centre(pts: &[P3]) -> P3 {
    let m = mean(pts.iter().copied());
    let k = pts.len();
    if k < 4 {
        return m;
    }
    let mut n = [0.0; 3];
    for i in 0..k {
        n = add(n, cross(sub(pts[i], m), sub(pts[(i + 1) % k], m)));
    }
    let nl = norm(n);
    let size = pts.iter().map(|p| norm(sub(*p, m))).fold(0.0f64, f64::max);
    if nl <= 1e-12 * size * size {
        return m;
    }
    let n = scale(n, 1.0 / nl);
    // (c − aᵢ)·(eᵢ × n) < 0 for every side eᵢ = aᵢ₊₁ − aᵢ.
    let mut planes: Vec<(P3, P3)> = Vec::with_capacity(k + 2);
    for i in 0..k {
        let e = sub(pts[(i + 1) % k], pts[i]);
        let out = cross(e, n);
        let l = norm(out);
        if l > 0.0 {
            planes.push((scale(out, 1.0 / l), pts[i]));
        }
    }
    let inside = |c: P3| {
        planes
            .iter()
            .all(|(o, a)| dot(*o, sub(c, *a)) < -1e-9 * size)
    };
    if inside(m) {
        return m;
    }
    // A slab about the mean's plane bounds the prism of such points.
    planes.push((n, add(m, scale(n, size))));
    planes.push((scale(n, -1.0), sub(m, scale(n, size))));
    match kernel_point(&planes, m, size) {
        Some(c) => sub(c, scale(n, dot(sub(c, m), n))),
        None => m,
    }
}

/// A point `c` around which the loop `rim` is fanned with every triangle (c, rᵢ, rᵢ₊₁) seen from
/// `o` counter-clockwise from outside (strictly): the mean of the rim when it is one, else the
/// point nearest to it of the cone {c : (c − o)·((rᵢ − o) × (rᵢ₊₁ − o)) > 0 for all i} (each
/// condition is linear in c), cut off beyond the rim's mean and behind `o`, with a margin
/// ([`kernel_point`]). `None` when that cone is empty or thin.
fn radial_centre(o: P3, rim: &[P3]) -> Option<P3> {
    let m = rim.len();
    let normals: Vec<P3> = (0..m)
        .map(|i| cross(sub(rim[i], o), sub(rim[(i + 1) % m], o)))
        .collect();
    let c = mean(rim.iter().copied());
    let sees = |c: P3| normals.iter().all(|n| dot(*n, sub(c, o)) > 0.0);
    if sees(c) {
        return Some(c);
    }
    let size = rim.iter().map(|p| norm(sub(*p, o))).fold(0.0f64, f64::max);
    let g = sub(c, o);
    let gl = norm(g);
    if gl <= 1e-12 * size {
        return None;
    }
    let g = scale(g, 1.0 / gl);
    // Outward normals: −n̂ᵢ through o, and the cap ĝ through o + 2·(c − o).
    let mut planes: Vec<(P3, P3)> = normals
        .iter()
        .filter(|n| norm(**n) > 0.0)
        .map(|n| (scale(*n, -1.0 / norm(*n)), o))
        .collect();
    planes.push((g, add(o, scale(g, 2.0 * gl))));
    // …and on the rim's side of o (behind o a clockwise rim would be seen counter-clockwise).
    planes.push((scale(g, -1.0), o));
    kernel_point(&planes, c, size).filter(|x| sees(*x) && dot(g, sub(*x, o)) > 0.0)
}

/// How far the fan `fan` may be shrunk towards `o` and stay strictly between `o` and the
/// surface `patch`: the least, over the rays from `o` through both, of the patch's distance
/// from `o` over the fan's (ρ_P/ρ_F). The fan shrunk by any factor below it lies strictly
/// closer to `o` than the patch on every ray. `None` when a triangle of either is not seen
/// from `o` counter-clockwise from outside (strictly): the bound means nothing then.
///
/// On the cone over one fan triangle and one patch triangle, 1/ρ is linear in the direction
/// (1/ρ(ω) = n·ω / n·a for the plane through a with normal n), so ρ_P/ρ_F is a ratio of two
/// linear functions, positive on the cone, and its least value is at an edge ray of the
/// intersection of the two cones: the fan triangle's corners clipped by the three planes through
/// `o` and the patch triangle's edges.
fn reach(o: P3, fan: &[[P3; 3]], patch: &[[P3; 3]]) -> Option<f64> {
    let rel = |t: &[P3; 3]| t.map(|p| sub(p, o));
    let det = |t: &[P3; 3]| dot(t[0], cross(t[1], t[2]));
    let plane = |t: &[P3; 3]| {
        let n = cross(sub(t[1], t[0]), sub(t[2], t[0]));
        (n, dot(n, t[0]))
    };
    let patch: Vec<[P3; 3]> = patch.iter().map(rel).collect();
    if patch.iter().any(|t| det(t) <= 0.0) {
        return None;
    }
    let mut least = f64::INFINITY;
    for f in fan.iter().map(rel) {
        if det(&f) <= 0.0 {
            return None;
        }
        let (nf, df) = plane(&f);
        for p in &patch {
            let mut poly: Vec<P3> = f.to_vec();
            for k in 0..3 {
                let h = cross(p[k], p[(k + 1) % 3]);
                poly = clip(&poly, h);
                if poly.is_empty() {
                    break;
                }
            }
            let (np, dp) = plane(p);
            for w in poly {
                let (a, b) = (dot(nf, w) / df, dot(np, w) / dp);
                if b > 0.0 {
                    least = least.min(a / b);
                }
            }
        }
    }
    Some(least)
}

/// The polygon `poly` (corners as directions) clipped to the half-space `h·x ≥ 0`
/// (Sutherland–Hodgman).
fn clip(poly: &[P3], h: P3) -> Vec<P3> {
    let mut out = Vec::with_capacity(poly.len() + 1);
    for i in 0..poly.len() {
        let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
        let (sa, sb) = (dot(h, a), dot(h, b));
        if sa >= 0.0 {
            out.push(a);
        }
        if (sa >= 0.0) != (sb >= 0.0) {
            out.push(lerp(a, b, sa / (sa - sb)));
        }
    }
    out
}

/// A point of the kernel of a surface given by the outward unit normals and points of its fan
/// triangles (`n·(x − c) < 0` for all): the one nearest (in L1) to `near` among the points at
/// least half the kernel's inradius inside every plane. `None` when the kernel is empty or thin
/// (inradius ≤ 10⁻⁹·`size`) or the solver fails. Two linear programs with `good_lp`'s pure-Rust
/// simplex (`microlp`, f64): this is geometry, no verdict rests on it.
fn kernel_point(planes: &[(P3, P3)], near: P3, size: f64) -> Option<P3> {
    use good_lp::{microlp, variable, variables, Expression, Solution, SolverModel};
    let side = |x: &[good_lp::Variable; 3], n: P3, c: P3| -> Expression {
        // −n·(x − c): the distance inside the plane.
        let mut e = Expression::from(dot(n, c));
        for k in 0..3 {
            e.add_mul(-n[k], x[k]);
        }
        e
    };
    let bound = |k: usize| (near[k] - 2.0 * size, near[k] + 2.0 * size);
    // 1. The inradius: maximise t with every plane at least t away.
    let mut vars = variables!();
    let x: [good_lp::Variable; 3] = std::array::from_fn(|k| {
        let (lo, hi) = bound(k);
        vars.add(variable().min(lo).max(hi))
    });
    let t = vars.add(variable().min(0.0).max(size));
    let mut model = vars.maximise(t).using(microlp);
    for &(n, c) in planes {
        model.add_constraint(side(&x, n, c).geq(t));
    }
    let sol = model.solve().ok()?;
    let r = sol.value(t);
    if r <= 1e-9 * size {
        return None;
    }
    // 2. Nearest to `near` (L1) among the points at least r/2 inside.
    let mut vars = variables!();
    let x: [good_lp::Variable; 3] = std::array::from_fn(|k| {
        let (lo, hi) = bound(k);
        vars.add(variable().min(lo).max(hi))
    });
    let d: [good_lp::Variable; 3] = std::array::from_fn(|_| vars.add(variable().min(0.0)));
    let total: Expression = d.iter().copied().sum();
    let mut model = vars.minimise(total).using(microlp);
    for k in 0..3 {
        model.add_constraint((Expression::from(x[k]) - near[k]).leq(d[k]));
        model.add_constraint((Expression::from(near[k]) - x[k]).leq(d[k]));
    }
    for &(n, c) in planes {
        model.add_constraint(side(&x, n, c).geq(r / 2.0));
    }
    let sol = model.solve().ok()?;
    Some(std::array::from_fn(|k| sol.value(x[k])))
}

/// The rotation from a face as built to the frame of the sub-volume's surface: [`Placed`] gives
/// the rotation to the canonical form of the face's type, which is the surface's frame turned by
/// the least rotation of the boundary the surface holds.
///
/// [`Placed`]: crate::topology::volume::Placed
fn surface_rotation(child: &Volume, placed: crate::topology::volume::Placed) -> usize {
    let b = &child.surface.faces[placed.face].boundary;
    let len = b.len();
    (placed.rotation + len - crate::topology::face::least_rotation(b) % len) % len
}

/// The reading of a face rotated left by `r` (side `i` of the result is side `i + r`).
fn rotated(r: &Reading, by: usize) -> Reading {
    let rot = |v: &[usize]| {
        let mut v = v.to_vec();
        let len = v.len().max(1);
        v.rotate_left(by % len);
        v
    };
    let mut forward = r.forward.clone();
    let len = forward.len().max(1);
    forward.rotate_left(by % len);
    Reading {
        face: r.face,
        corners: rot(&r.corners),
        edges: rot(&r.edges),
        forward,
    }
}

/// Checks that the readings of a volume's faces agree with its gluing: glued sides are one edge
/// run both ways, and every side runs along its edge as it says.
fn check_glue(v: &Volume, faces: &[Reading], edges: &[GeoEdge]) -> Result<()> {
    for (f, row) in v.surface.glue.iter().enumerate() {
        let r = &faces[f];
        let len = r.corners.len();
        for (i, &(g, j)) in row.iter().enumerate() {
            let o = &faces[g];
            let e = &edges[r.edges[i]];
            let (s, t) = if r.forward[i] { (e.a, e.b) } else { (e.b, e.a) };
            let ok = r.edges[i] == o.edges[j]
                && r.forward[i] != o.forward[j]
                && s == r.corners[i]
                && t == r.corners[(i + 1) % len]
                && e.ty == v.surface.faces[f].boundary[i];
            if !ok {
                return Err(geometry_error(
                    "E1211",
                    format!(
                        "the geometry of face {f} side {i} does not follow the volume's gluing"
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// The distance from `p` along the unit direction `d` to the first triangle it meets further
/// than a small tolerance (the surface's thickness there).
fn thickness(p: P3, d: P3, tris: &[[P3; 3]]) -> Option<f64> {
    let mut best: Option<f64> = None;
    let scale_of = tris
        .iter()
        .flat_map(|t| t.iter())
        .map(|q| norm(sub(*q, p)))
        .fold(0.0f64, f64::max);
    let eps = 1e-7 * scale_of.max(1e-30);
    for t in tris {
        // Möller–Trumbore.
        let e1 = sub(t[1], t[0]);
        let e2 = sub(t[2], t[0]);
        let h = cross(d, e2);
        let a = dot(e1, h);
        if a.abs() < 1e-14 * norm(e1) * norm(e2) {
            continue;
        }
        let f = 1.0 / a;
        let s = sub(p, t[0]);
        let u = f * dot(s, h);
        if !(-1e-9..=1.0 + 1e-9).contains(&u) {
            continue;
        }
        let q = cross(s, e1);
        let w = f * dot(d, q);
        if w < -1e-9 || u + w > 1.0 + 1e-9 {
            continue;
        }
        let dist = f * dot(e2, q);
        if dist > eps && best.is_none_or(|b| dist < b) {
            best = Some(dist);
        }
    }
    best
}

/// Where the corners of the volumes of an assembly lie: `[v][f][i]` is corner `i` (the start of
/// edge `i`) of face `f` of volume `v`.
pub type Placement = Vec<Vec<Vec<P3>>>;

/// The enclosed volume of a closed surface given as polygons (fans around their means): positive
/// when the polygons run counter-clockwise seen from outside.
fn enclosed(polys: &[Vec<P3>]) -> f64 {
    polys
        .iter()
        .map(|p| {
            let c = mean(p.iter().copied());
            (0..p.len())
                .map(|i| dot(c, cross(p[i], p[(i + 1) % p.len()])))
                .sum::<f64>()
        })
        .sum::<f64>()
        / 6.0
}

/// A similarity (rotation, uniform scale, translation; no reflection) taking the polygon `q` onto
/// `p` corner by corner, if there is one (up to rounding).
fn fit(q: &[P3], p: &[P3]) -> Option<impl Fn(P3) -> P3> {
    let frame = |pts: &[P3]| -> Option<(P3, [P3; 3], f64)> {
        let c = mean(pts.iter().copied());
        let mut n = [0.0; 3];
        for i in 0..pts.len() {
            n = add(n, cross(sub(pts[i], c), sub(pts[(i + 1) % pts.len()], c)));
        }
        let nl = norm(n);
        let r = (pts.iter().map(|x| dot(sub(*x, c), sub(*x, c))).sum::<f64>() / pts.len() as f64)
            .sqrt();
        if nl <= 1e-12 * r * r || r == 0.0 {
            return None;
        }
        let n = scale(n, 1.0 / nl);
        let d = sub(pts[0], c);
        let u = sub(d, scale(n, dot(d, n)));
        let ul = norm(u);
        if ul <= 1e-12 * r {
            return None;
        }
        let u = scale(u, 1.0 / ul);
        Some((c, [u, cross(n, u), n], r))
    };
    let (cq, bq, rq) = frame(q)?;
    let (cp, bp, rp) = frame(p)?;
    let s = rp / rq;
    let map = move |x: P3| {
        let d = sub(x, cq);
        let mut out = cp;
        for k in 0..3 {
            out = add(out, scale(bp[k], s * dot(d, bq[k])));
        }
        out
    };
    let worst = q
        .iter()
        .zip(p)
        .map(|(a, b)| norm(sub(map(*a), *b)))
        .fold(0.0f64, f64::max);
    (worst <= 1e-9 * rp).then_some(map)
}

/// Places the volumes of an assembly in 3D: a volume with user coordinates (`given`) where they
/// say; a shorthand solid glued to a placed volume by the similarity that lays its shared face on
/// the placed one (so the solid lands on the far side); the first shorthand of a group that
/// nothing places yet on its default placement ([`default_placement`]). Refused: a volume left
/// without a place (E1210), coordinates that wind a surface inside out (E1215), and two volumes
/// that put one corner of the level-0 complex at two places (E1216).
pub fn place_assembly(
    a: &VolumeAssembly,
    given: &[Option<Corners>],
    names: &[String],
) -> Result<Placement> {
    let n = a.volumes.len();
    let name = |v: usize| match names.get(v) {
        Some(x) => format!("volume `{x}`"),
        None if n == 1 => "the volume".to_string(),
        None => format!("volume {v}"),
    };
    let mut placed: Vec<Option<Corners>> =
        (0..n).map(|v| given.get(v).cloned().flatten()).collect();
    let default: Vec<Option<Corners>> = a
        .volumes
        .iter()
        .map(|v| default_placement(v).map(|(_, p)| p))
        .collect();
    let mut group = crate::topology::component::Dsu::new(n);
    for s in &a.shared {
        group.union(s.a.0, s.b.0);
    }
    loop {
        let mut progress = false;
        for s in &a.shared {
            for (here, there) in [(s.a, s.b), (s.b, s.a)] {
                let (vh, fh, eh) = here;
                let (vt, ft, et) = there;
                if placed[vh].is_none() || placed[vt].is_some() {
                    continue;
                }
                let Some(own) = &default[vt] else { continue };
                let len = own[ft].len();
                // Corner `eh + k` of the placed face is corner `et + 1 − k` of the other.
                let target: Vec<P3> = (0..len)
                    .map(|j| {
                        placed[vh].as_ref().expect("placed")[fh]
                            [(eh + et + 1 + len - j % len) % len]
                    })
                    .collect();
                let Some(map) = fit(&own[ft], &target) else {
                    return Err(geometry_error(
                        "E1216",
                        format!(
                            "{} cannot be laid on face {fh} of {}: its face {ft} has another shape (give its corners)",
                            name(vt),
                            name(vh)
                        ),
                    ));
                };
                placed[vt] = Some(
                    own.iter()
                        .map(|f| f.iter().map(|&x| map(x)).collect())
                        .collect(),
                );
                progress = true;
            }
        }
        if !progress {
            let next = (0..n).find(|&v| {
                placed[v].is_none()
                    && default[v].is_some()
                    && (0..n).all(|w| placed[w].is_none() || group.find(w) != group.find(v))
            });
            match next {
                Some(v) => placed[v] = default[v].clone(),
                None => break,
            }
        }
    }
    let mut out = Vec::with_capacity(n);
    for (v, p) in placed.into_iter().enumerate() {
        let Some(p) = p else {
            return Err(geometry_error(
                "E1210",
                format!("the surface of {} is none of the shorthand solids (cube, tetrahedron, octahedron, prism-N, truncated-tetrahedron) and nothing places it: give its corners (`corners FACE: X Y Z, …` lines in its block, docs/FORMATS.md)", name(v)),
            ));
        };
        if enclosed(&p).partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            return Err(geometry_error(
                "E1215",
                format!("the corners of {} do not enclose a positive volume with its faces counter-clockwise seen from outside (mirror them, or list every face's corners counter-clockwise from outside)", name(v)),
            ));
        }
        out.push(p);
    }
    // One corner of the level-0 complex, one place.
    let map = a.start_map();
    let size = out
        .iter()
        .flatten()
        .flatten()
        .map(|x| norm(*x))
        .fold(0.0f64, f64::max)
        .max(1e-300);
    let mut seen: HashMap<usize, (P3, usize)> = HashMap::new();
    for (v, faces) in out.iter().enumerate() {
        for (f, face) in faces.iter().enumerate() {
            for (i, &x) in face.iter().enumerate() {
                let c = map.corner[v][f][i];
                match seen.get(&c) {
                    Some(&(y, w)) if norm(sub(x, y)) > 1e-9 * size => {
                        return Err(geometry_error(
                            "E1216",
                            format!(
                                "corner {i} of face {f} of {} is at ({:.6} {:.6} {:.6}) but {} puts the same corner at ({:.6} {:.6} {:.6}): volumes sharing a face must agree on its corners",
                                name(v), x[0], x[1], x[2], name(w), y[0], y[1], y[2]
                            ),
                        ))
                    }
                    Some(_) => {}
                    None => {
                        seen.insert(c, (x, v));
                    }
                }
            }
        }
    }
    Ok(out)
}

/// The start of the evaluation: the level-0 complex of the assembly on its placement, one cell
/// per cell of [`VolumeAssembly::start_map`].
fn start(b: &mut Builder, a: &VolumeAssembly, placement: &Placement) -> Result<Vec<GeoVolume>> {
    let map = a.start_map();
    let mut ids: Vec<Option<usize>> = vec![None; map.corner_count()];
    for (v, faces) in map.corner.iter().enumerate() {
        for (f, row) in faces.iter().enumerate() {
            for (i, &c) in row.iter().enumerate() {
                if ids[c].is_none() {
                    ids[c] = Some(b.point(placement[v][f][i]));
                }
            }
        }
    }
    let ids: Vec<usize> = ids
        .into_iter()
        .map(|x| x.expect("every corner placed"))
        .collect();
    let mut edge_of: Vec<Option<usize>> = vec![None; map.edge_count()];
    let mut face_of: Vec<Option<usize>> = vec![None; map.faces.len()];
    let mut out = Vec::with_capacity(a.volumes.len());
    for (v, vol) in a.volumes.iter().enumerate() {
        let mut faces = Vec::with_capacity(vol.surface.faces.len());
        for (f, face) in vol.surface.faces.iter().enumerate() {
            let len = face.boundary.len();
            let corners: Vec<usize> = (0..len).map(|i| ids[map.corner[v][f][i]]).collect();
            let mut edges = Vec::with_capacity(len);
            let mut forward = Vec::with_capacity(len);
            for i in 0..len {
                let (s, t) = (corners[i], corners[(i + 1) % len]);
                let e = match edge_of[map.side[v][f][i]] {
                    Some(e) => e,
                    None => {
                        let e = b.edge(s, t, face.boundary[i]);
                        edge_of[map.side[v][f][i]] = Some(e);
                        e
                    }
                };
                edges.push(e);
                forward.push(b.edges[e].a == s && b.edges[e].b == t);
            }
            let g = map.face[v][f];
            let id = match face_of[g] {
                Some(id) => id,
                None => {
                    let id = b.face(face.clone(), corners.clone(), None);
                    face_of[g] = Some(id);
                    id
                }
            };
            faces.push(Reading {
                face: id,
                corners,
                edges,
                forward,
            });
        }
        check_glue(vol, &faces, &b.edges)?;
        out.push(GeoVolume {
            volume: vol.clone(),
            faces,
        });
    }
    Ok(out)
}

/// Evaluates the level-`level` solid of a volume on its default placement. The caller bounds
/// the work first (the exact number of level-n cells is known from the topology).
pub fn evaluate_volume(v: &Volume, level: u32) -> Result<SolidGeometry> {
    let a = VolumeAssembly::single(v.clone());
    let placement = place_assembly(&a, &[], &[])?;
    evaluate_assembly(&a, &placement, level, InnerFan::RimMean)
}

/// Evaluates the level-`level` solid of an assembly on a placement ([`place_assembly`]): one
/// complex, a face shared by two volumes subdivided once; inner faces fanned as `fan` says. The
/// caller bounds the work first.
pub fn evaluate_assembly(
    a: &VolumeAssembly,
    placement: &Placement,
    level: u32,
    fan: InnerFan,
) -> Result<SolidGeometry> {
    let mut b = Builder {
        fan,
        points: Vec::new(),
        edges: Vec::new(),
        faces: Vec::new(),
        pieces: HashMap::new(),
        gap_point: HashMap::new(),
        spoke: HashMap::new(),
        lacuna: HashMap::new(),
        gap_side: HashMap::new(),
        subface: HashMap::new(),
        side: HashMap::new(),
        inner_edge: HashMap::new(),
        steps: HashMap::new(),
        face_steps: HashMap::new(),
        holes: Vec::new(),
    };
    let mut volumes = start(&mut b, a, placement)?;
    for _ in 0..level {
        b.holes.clear();
        let mut next = Vec::new();
        for (vid, gv) in volumes.iter().enumerate() {
            next.extend(b.step(vid, gv)?);
        }
        volumes = next;
        // Keys of one level are not needed at the next (face and volume numbers are fresh).
        b.side.clear();
    }
    Ok(SolidGeometry {
        level,
        points: b.points,
        edges: b.edges,
        faces: b.faces,
        volumes,
        holes: b.holes,
    })
}

/// The least thickness of a volume of the solid: from every corner of its surface, along the
/// inward normal of every face there, the distance to its surface (an estimate: corners only).
pub fn least_thickness(g: &SolidGeometry, v: &GeoVolume) -> Option<f64> {
    let mut tris: Vec<[P3; 3]> = Vec::new();
    let mut rays: Vec<(usize, P3)> = Vec::new();
    for r in &v.faces {
        let c = g.faces[r.face].center;
        let mut n = [0.0; 3];
        for i in 0..r.corners.len() {
            let a = g.points[r.corners[i]];
            let b = g.points[r.corners[(i + 1) % r.corners.len()]];
            n = add(n, cross(sub(a, c), sub(b, c)));
            tris.push([c, a, b]);
        }
        let len = norm(n);
        if len > 0.0 {
            for &p in &r.corners {
                rays.push((p, scale(n, -1.0 / len)));
            }
        }
    }
    let mut least: Option<f64> = None;
    for (p, d) in rays {
        if let Some(h) = thickness(g.points[p], d, &tris) {
            least = Some(least.map_or(h, |l: f64| l.min(h)));
        }
    }
    least
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::topology::volume::parse_volume;

    #[test]
    fn the_kernel_point_of_a_cube_nearest_to_a_far_point() {
        // The unit cube [0, 1]³ by its six planes (outward normal, a point). Its kernel is the
        // cube, whose inradius is 1/2 (the centre). The points at least 1/4 inside every plane
        // form [1/4, 3/4]³, and the one nearest to (5, 5, 5) in L1 is its corner (3/4, 3/4, 3/4).
        // (`size` bounds the search to a box of ±2·size around the given point.)
        let planes: Vec<(P3, P3)> = (0..3)
            .flat_map(|k| {
                let mut n = [0.0; 3];
                n[k] = 1.0;
                [(n, [1.0; 3]), (scale(n, -1.0), [0.0; 3])]
            })
            .collect();
        let p = kernel_point(&planes, [5.0; 3], 10.0).unwrap();
        for x in p {
            assert!((x - 0.75).abs() < 1e-7, "{p:?}");
        }
        // Two parallel planes facing away from each other leave an empty kernel.
        let empty = [
            ([1.0, 0.0, 0.0], [0.0; 3]),
            ([-1.0, 0.0, 0.0], [1.0, 0.0, 0.0]),
        ];
        assert_eq!(kernel_point(&empty, [0.5; 3], 1.0), None);
    }

    #[test]
    fn the_reach_of_a_fan_is_the_least_ratio_of_distances_on_the_shared_cone() {
        // Seen from the origin, the patch is the triangle a = (1, 0, 1), b = (0, 1, 1),
        // c = (−½, −½, 1) in the plane z = 1 (det(a, b, c) = 2 > 0: counter-clockwise from
        // outside). A copy twice as far (the plane z = 2) is at twice the distance on every ray:
        // reach ½.
        let patch = [[[1.0, 0.0, 1.0], [0.0, 1.0, 1.0], [-0.5, -0.5, 1.0]]];
        let twice = [patch[0].map(|p| scale(p, 2.0))];
        let r = reach([0.0; 3], &twice, &patch).unwrap();
        assert!((r - 0.5).abs() < 1e-12, "{r}");
        // A fan triangle in the plane z − x/4 = 1 whose cone holds the patch's: its corners are
        // the rays (3, 0, 1), (−1, ±2, 1) met at t = 4 and t = 4/5. On a ray ω the patch is at
        // 1/ω_z and the fan at 1/(ω_z − ω_x/4), so ρ_P/ρ_F = 1 − ω_x/(4ω_z): least where x/z is
        // greatest inside the patch's cone, 1 at a, so 3/4. Over the fan's whole cone (x/z up to
        // 3) it would be 1/4: only the shared cone counts.
        let fan = [[[12.0, 0.0, 4.0], [-0.8, 1.6, 0.8], [-0.8, -1.6, 0.8]]];
        let r = reach([0.0; 3], &fan, &patch).unwrap();
        assert!((r - 0.75).abs() < 1e-12, "{r}");
        // Moving everything by the same vector changes nothing.
        let d = [0.3, -2.0, 5.0];
        let moved =
            |t: &[[P3; 3]]| -> Vec<[P3; 3]> { t.iter().map(|x| x.map(|p| add(p, d))).collect() };
        let r = reach(d, &moved(&fan), &moved(&patch)).unwrap();
        assert!((r - 0.75).abs() < 1e-12, "{r}");
        // A fan triangle seen from behind (clockwise) bounds nothing.
        let turned = [[fan[0][0], fan[0][2], fan[0][1]]];
        assert_eq!(reach([0.0; 3], &turned, &patch), None);
        // Nor does a patch seen from behind.
        let behind = [[patch[0][0], patch[0][2], patch[0][1]]];
        assert_eq!(reach([0.0; 3], &fan, &behind), None);
    }

    /// Whether every fan triangle (c, rᵢ, rᵢ₊₁) turns counter-clockwise seen from `o`.
    fn sees_all(o: P3, c: P3, rim: &[P3]) -> bool {
        let m = rim.len();
        (0..m).all(|i| dot(sub(c, o), cross(sub(rim[i], o), sub(rim[(i + 1) % m], o))) > 0.0)
    }

    /// A chevron, counter-clockwise in its plane: (0, 0), (4, 0), (4, 1), (1, 1), (1, 4),
    /// (0, 4), with the reflex corner at (1, 1). The mean of its six corners, (5/3, 5/3), lies
    /// beyond the reflex corner; its kernel is the open square (0, 1)².
    const CHEVRON: [[f64; 2]; 6] = [
        [0.0, 0.0],
        [4.0, 0.0],
        [4.0, 1.0],
        [1.0, 1.0],
        [1.0, 4.0],
        [0.0, 4.0],
    ];

    #[test]
    fn a_radial_centre_sees_every_fan_triangle_from_the_volume_centre() {
        // A square rim in the plane z = 1 around the z axis: its mean (0, 0, 1) sees it.
        let square: Vec<P3> = vec![
            [1.0, -1.0, 1.0],
            [1.0, 1.0, 1.0],
            [-1.0, 1.0, 1.0],
            [-1.0, -1.0, 1.0],
        ];
        assert_eq!(radial_centre([0.0; 3], &square), Some([0.0, 0.0, 1.0]));
        // A chevron in the plane z = 1, counter-clockwise seen from above: (0, 0), (4, 0),
        // (4, 1), (1, 1), (1, 4), (0, 4)… with the reflex corner at (1, 1), the mean of its six
        // corners is (5/3, 5/3), beyond the reflex corner: the triangle (mean, (4, 1), (1, 1))
        // turns clockwise. Its kernel is the open square (0, 1)².
        let chevron: Vec<P3> = CHEVRON.iter().map(|p| [p[0], p[1], 1.0]).collect();
        let o = [0.5, 0.5, -1.0];
        assert!(!sees_all(o, mean(chevron.iter().copied()), &chevron));
        let c = radial_centre(o, &chevron).unwrap();
        assert!(sees_all(o, c, &chevron), "{c:?}");
        // Clockwise, no point on its side of o sees it (behind o, the points over the kernel
        // would).
        let mut turned = chevron.clone();
        turned.reverse();
        assert_eq!(radial_centre(o, &turned), None);
    }

    #[test]
    fn a_face_centre_is_its_mean_unless_the_mean_is_outside_its_kernel() {
        // A square: its mean.
        let square: Vec<P3> = vec![
            [0.0, 0.0, 2.0],
            [2.0, 0.0, 2.0],
            [2.0, 2.0, 2.0],
            [0.0, 2.0, 2.0],
        ];
        assert_eq!(face_centre(&square), [1.0, 1.0, 2.0]);
        // The chevron above, tilted out of its plane by a rotation about the x axis: the mean
        // lies beyond the reflex corner, and the centre chosen instead lies in the face's plane
        // and sees every side counter-clockwise about the face's normal.
        let (cs, sn) = (0.6, 0.8);
        let chevron: Vec<P3> = CHEVRON
            .iter()
            .map(|p| [p[0], cs * p[1], sn * p[1] + 3.0])
            .collect();
        let n = [0.0, -sn, cs];
        let sees = |c: P3| {
            (0..6).all(|i| {
                let (a, b) = (chevron[i], chevron[(i + 1) % 6]);
                dot(n, cross(sub(a, c), sub(b, c))) > 0.0
            })
        };
        let m = mean(chevron.iter().copied());
        assert!(!sees(m));
        let c = face_centre(&chevron);
        assert!(sees(c), "{c:?}");
        assert!(
            dot(n, sub(c, chevron[0])).abs() < 1e-9,
            "{c:?} off the plane"
        );
    }

    #[test]
    fn a_surface_that_is_no_shorthand_solid_has_no_default_placement() {
        // The tetrahedron with its faces listed in another order is the same sphere, but its
        // gluing is not the one `Solid::Tetrahedron` writes: no placement is guessed (E1210).
        let mut v = parse_volume("tetrahedron B2 | B2 B2 B2 | A1 | B2 B2 | V1").unwrap();
        assert!(default_placement(&v).is_some());
        let order = [1usize, 0, 2, 3];
        let new_index = |f: usize| order.iter().position(|&o| o == f).unwrap();
        let faces = order.iter().map(|&f| v.surface.faces[f].clone()).collect();
        let glue = order
            .iter()
            .map(|&f| {
                v.surface.glue[f]
                    .iter()
                    .map(|&(g, j)| (new_index(g), j))
                    .collect()
            })
            .collect();
        v.surface = crate::topology::volume::Surface { faces, glue };
        assert_eq!(v.surface.check(), Ok(()));
        assert!(default_placement(&v).is_none());
        assert_eq!(evaluate_volume(&v, 1).unwrap_err().code(), "E1210");
    }

    #[test]
    fn the_solids_are_placed_counter_clockwise_from_outside() {
        for name in [
            "cube",
            "tetrahedron",
            "octahedron",
            "prism-5",
            "truncated-tetrahedron",
        ] {
            let v = parse_volume(&format!("{name} B2 | B2 B2 B2 | A1 | B2 B2 | V1")).unwrap();
            let (_, polys) = default_placement(&v).unwrap();
            // Every face is planar with its normal pointing away from the origin (the centre).
            for p in &polys {
                let c = mean(p.iter().copied());
                let mut n = [0.0; 3];
                for i in 0..p.len() {
                    n = add(n, cross(p[i], p[(i + 1) % p.len()]));
                }
                assert!(dot(n, c) > 0.0, "{name}: a face is wound inwards");
                for q in p {
                    assert!(
                        dot(sub(*q, c), n).abs() < 1e-9,
                        "{name}: a face is not flat"
                    );
                }
            }
        }
    }

    #[test]
    fn inner_corners_of_the_cube_are_its_rim_points_shrunk_towards_its_centre() {
        // By hand: the cube on [−1, 1]³ has its centre o at the origin (every corner is counted
        // three times, once per face, and the corners are symmetric). At level 1 its rim points
        // are the 12 edge midpoints and the 24 lacuna corners (c + ½(j − c) on each face), all
        // on the surface (max |coordinate| = 1); with the 8 cube corners that is 44 surface
        // points. Each rim point has one radial edge (its two sub-volumes share it through their
        // spoke face), ending at p + σ(o − p) = 0.65 p: 36 inner corners, max |coordinate| =
        // 0.65, each 0.65 times a rim point. 44 + 36 = 80 corners (docs/VOLUMES.md).
        let v = parse_volume("cube B2 | B2 B2 B2 | A1 | B2 B2 | V1").unwrap();
        let g = evaluate_volume(&v, 1).unwrap();
        let mut corners = std::collections::BTreeSet::new();
        for gv in &g.volumes {
            for r in &gv.faces {
                corners.extend(r.corners.iter().copied());
            }
        }
        let size = |p: P3| p.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let (outer, inner): (Vec<P3>, Vec<P3>) = corners
            .iter()
            .map(|&c| g.points[c])
            .partition(|&p| (size(p) - 1.0).abs() < 1e-12);
        assert_eq!((outer.len(), inner.len()), (44, 36));
        for q in &inner {
            assert!((size(*q) - (1.0 - SHRINK)).abs() < 1e-12, "{q:?}");
            assert!(
                outer
                    .iter()
                    .any(|p| norm(sub(scale(*p, 1.0 - SHRINK), *q)) < 1e-12),
                "{q:?} is no rim point shrunk towards the centre"
            );
        }
    }
}
