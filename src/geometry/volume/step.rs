//! The builder of a volume's solid: one step of every face and volume, the points, edges and
//! faces born inside them keyed so that a shared face is subdivided once, and the inner-face
//! rules (shrink, side faces, fans); the readings of faces rotated and checked against the gluing.

use super::cells::{
    cross, dot, geometry_error, lerp, mean, norm, scale, sub, GeoEdge, GeoFace, GeoVolume,
    InnerFan, Reading, LACUNA, NOTCH, P3, PUSH, SHRINK,
};
use super::centres::{face_centre, kernel_point, radial_centre, reach};
use crate::error::Result;
use crate::topology::edge::{EdgeType, JunctionKind};
use crate::topology::face::Face;
use crate::topology::subdivision::{subdivide, Origin, Subdivision};
use crate::topology::volume::{subdivide_volume, Volume, VolumeSubdivision};
use std::collections::HashMap;
use std::rc::Rc;

/// The pieces of an edge, in its direction: (start point, end point, piece edge).
type Pieces = Vec<(usize, usize, usize)>;

/// One face of a volume as the step reads it: its sub-faces in the form the step builds them.
struct SubReadings {
    /// `subs[k]`: sub-face `k` of the canonical subdivision, read from its canonical start.
    subs: Vec<Reading>,
}

/// Builds the solid level by level.
pub(super) struct Builder {
    pub(super) fan: InnerFan,
    pub(super) points: Vec<P3>,
    pub(super) edges: Vec<GeoEdge>,
    pub(super) faces: Vec<GeoFace>,
    pub(super) pieces: HashMap<usize, Pieces>,
    pub(super) gap_point: HashMap<(usize, usize), usize>,
    pub(super) spoke: HashMap<(usize, usize), (usize, usize)>,
    pub(super) lacuna: HashMap<(usize, usize), usize>,
    pub(super) gap_side: HashMap<(usize, usize), usize>,
    pub(super) subface: HashMap<(usize, usize), usize>,
    pub(super) side: HashMap<(usize, usize), usize>,
    pub(super) inner_edge: HashMap<usize, usize>,
    pub(super) steps: HashMap<Volume, Rc<VolumeSubdivision>>,
    pub(super) face_steps: HashMap<Face, Rc<Subdivision>>,
    pub(super) holes: Vec<Vec<usize>>,
}

impl Builder {
    pub(super) fn point(&mut self, p: P3) -> usize {
        self.points.push(p);
        self.points.len() - 1
    }

    pub(super) fn edge(&mut self, a: usize, b: usize, ty: EdgeType) -> usize {
        self.edges.push(GeoEdge { a, b, ty });
        self.edges.len() - 1
    }

    pub(super) fn face(&mut self, face: Face, corners: Vec<usize>, center: Option<P3>) -> usize {
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
            fan_fixed: false,
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
                    let id = self.face(s.face.as_ref().clone(), corners.clone(), None);
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
    /// empty). When no point sees all of them, the point of the kernel of the volume's own faces
    /// is taken instead, if it has one: at level 3 of the truncated tetrahedron with `C3` edges
    /// (A1, V1) 24 volumes have no point that sees every sub-face of their level-1 surface, and
    /// their means folded the solid where their own kernel points do not (issue #31).
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
        let given = !seen.is_empty();
        let seen = if given { seen } else { &own[..] };
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
        match kernel_point(&planes, m, size) {
            Some(k) => k,
            None if given => self.star_centre(gv, &[]),
            None => m,
        }
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
    pub(super) fn step(&mut self, vid: usize, gv: &GeoVolume) -> Result<Vec<GeoVolume>> {
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
        let (shrinks, radial_centres) = if radial {
            self.radial_fans(&step, &subs, vcenter)
        } else {
            (vec![SHRINK; step.subvolumes.len()], Vec::new())
        };
        // Every rim point goes [`SHRINK`] of the way to the volume's centre (under
        // [`InnerFan::Radial`], its slot's fraction, below): the side face over a rim edge lies
        // in the cone from the centre over that edge, so the side faces of two rim edges meet
        // only along the radial edge they share, and the inner face is the rim loop shrunk
        // towards the centre (no offset along summed normals, which folds where the volume is
        // not convex).
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
        // The shrink of a radial slot: the largest of its sub-volumes' (the point nearest the
        // centre), so that each inner face lies, on every ray from the centre, no further out
        // than its own sub-volume's shrink allows (see [`Builder::radial_fans`]).
        let mut slot_shrink: HashMap<usize, f64> = HashMap::new();
        for (s, sv) in step.subvolumes.iter().enumerate() {
            for i in 0..sv.sides.len() {
                let t = slot_shrink.entry(dsu.find(offsets[s] + i)).or_insert(0.0);
                *t = t.max(shrinks[s]);
            }
        }
        let mut radial: HashMap<usize, (usize, usize)> = HashMap::new();
        let mut slot_edge = |me: &mut Builder, s: usize, i: usize| -> (usize, usize) {
            let root = dsu.find(offsets[s] + i);
            if let Some(&x) = radial.get(&root) {
                return x;
            }
            let (_, _, a, _) = rim(s, i);
            let inner = lerp(me.points[a], vcenter, slot_shrink[&root]);
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
                    .map(|c| lerp(c, vcenter, shrinks[s])),
                InnerFan::PatchPoint => {
                    let rim_of = |i: usize| {
                        let (e, _, a, _) = rim(s, i);
                        (e, a)
                    };
                    self.patch_point(sv, &subs, (0..m).map(rim_of).collect())
                        .map(|p| lerp(p, vcenter, shrinks[s]))
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

    /// The inner faces of [`InnerFan::Radial`]: for every sub-volume, the fraction `t` of the way
    /// from a rim point to `o` at which its inner corners may lie, and the point its inner face
    /// is fanned around before that shrink (`None` where no fan of its rim is seen from `o`; the
    /// mean of its rim is used then).
    ///
    /// The fan centre of a sub-volume is the mean of its rim when every fan triangle around it
    /// is seen from `o` counter-clockwise from outside, else a point of the cone of such centres
    /// ([`radial_centre`]). With ρ its fan's [`reach`] over its patch (at most 1), `1 − t` is
    /// [`SHRINK`]·ρ: the fan scaled about `o` by `1 − t` lies, on every ray from `o`, at most
    /// half of the way from `o` to the patch. A radial slot shared by several sub-volumes takes
    /// the largest of their `t` (the step does), and the inner face's centre its own: a triangle
    /// whose corners lie on the rays of a triangle T, each at most a fraction α of the way out,
    /// lies on every ray through it at most α of the way to T (a point `Σλᵢvᵢ` of T is met at
    /// `1/Σ(λᵢ/αᵢ)` of it, and `Σλᵢ/αᵢ ≥ 1/α`). So each inner face stays below its patch and in
    /// the cone over it, which the other sub-volumes do not enter. One fraction for all, the
    /// least reach of the whole step, was used before: a single patch bent towards `o` (reach
    /// 0.09 at level 2 of prism-3 with `C3` edges, A2, V1) then drew every inner corner of the
    /// step within a twentieth of the way from `o`, where the gap faces of neighbouring
    /// sub-volumes were slivers that crossed (issue #31).
    fn radial_fans(
        &self,
        step: &VolumeSubdivision,
        subs: &[SubReadings],
        o: P3,
    ) -> (Vec<f64>, Vec<Option<P3>>) {
        let mut shrinks = vec![SHRINK; step.subvolumes.len()];
        let mut centres = Vec::with_capacity(step.subvolumes.len());
        for (s, sv) in step.subvolumes.iter().enumerate() {
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
                shrinks[s] = 1.0 - (1.0 - SHRINK) * t.min(1.0);
            }
        }
        (shrinks, centres)
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
            self.faces[id].fan_fixed =
                self.fan == InnerFan::Radial && push_to.is_none() && centre.is_some();
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
pub(super) fn check_glue(v: &Volume, faces: &[Reading], edges: &[GeoEdge]) -> Result<()> {
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
