//! One subdivision step of a volume (THEORY §10).
//!
//! The level-1 surface is made of the sub-faces of every face of S. Its sides (half-edges) are
//! paired when two sub-faces share an edge: the two sides of a spoke edge Ea of one face, and the
//! pieces of an edge of S seen from its two faces (piece `j` of an edge with `n` pieces is piece
//! `n − 1 − j` from the other side). Lacuna edges El and gap sides Ec stay unpaired: they border
//! holes. Cutting along the rule's spoke edges leaves patches; each patch must be a disk (one rim
//! loop, V − E + F = 1), and becomes the outer boundary of one sub-volume, closed by a side face
//! `X Er Ei Er` on every rim edge and an inner face `Ei … Ei`. A delayed volume instead keeps the
//! whole level-1 surface and caps every hole with a face of the hole's edge types.

use crate::error::{Error, Result};
use crate::topology::component::Dsu;
use crate::topology::subdivision::{subdivide, Origin, Subdivision};
use crate::topology::volume::surface::Surface;
use crate::topology::volume::Volume;
use std::collections::HashMap;

/// A side of the level-1 surface: (face of S, sub-face, position in the sub-face's boundary).
pub type Side = (usize, usize, usize);

/// A patch: the sub-faces (face of S, sub-face) of one sub-volume's outer boundary.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Patch {
    /// The sub-faces, in the order of the sub-volume's faces.
    pub subfaces: Vec<(usize, usize)>,
    /// Rim edges that are spoke edges (shared with a neighbouring sub-volume).
    pub spoke_sides: usize,
    /// Rim edges that border a hole (wall faces).
    pub wall_sides: usize,
}

/// Where a face of the step lies on a sub-volume's canonical surface, and how its frame turns:
/// its boundary as built (a sub-face in the canonical form its face type gives it, a side face as
/// `X Er Ei Er`) rotated left by `rotation` is the canonical form of its type as the sub-volume's
/// surface reads it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Placed {
    /// The face's index on the sub-volume's canonical surface.
    pub face: usize,
    /// The rotation from the face as built to the canonical frame of the sub-volume's surface.
    pub rotation: usize,
}

/// One sub-volume with the patch it stands on (none for the single sub-volume of a delayed one).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SubVolume {
    /// The sub-volume, in canonical form.
    pub volume: Volume,
    /// Its patch.
    pub patch: Option<Patch>,
    /// The level-1 sub-faces `(face of S, sub-face)` on its surface.
    pub subfaces: Vec<((usize, usize), Placed)>,
    /// Its side faces: the rim side `(face of S, sub-face, position)` each stands on.
    pub sides: Vec<(Side, Placed)>,
}

/// Canonicalizes a built sub-volume and places the faces it was built from.
fn placed(sub: Volume) -> (Volume, impl Fn(usize) -> Placed) {
    let (surface, index, root) = sub.surface.canonical_map();
    let frames: Vec<usize> = surface
        .faces
        .iter()
        .map(|f| crate::topology::face::least_rotation(&f.boundary))
        .collect();
    let lens: Vec<usize> = sub.surface.faces.iter().map(|f| f.boundary.len()).collect();
    let place = move |old: usize| Placed {
        face: index[old],
        rotation: (root[old] + frames[index[old]]) % lens[old],
    };
    (Volume { surface, ..sub }, place)
}

/// The result of one step.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct VolumeSubdivision {
    /// The sub-volumes.
    pub subvolumes: Vec<SubVolume>,
    /// The two sides `(face of S, sub-face, position)` of every spoke edge, each pair once (the
    /// sub-volumes on either side share the side face over it).
    pub spoke_pairs: Vec<(Side, Side)>,
    /// The cells the step creates inside the volume, read off the same level-1 surface (the
    /// solid's counts use them: nothing is subdivided twice).
    pub interior: Interior,
}

/// The level-1 surface of a volume: every face subdivided, and the pairing of sides.
struct Level1 {
    subs: Vec<Subdivision>,
    partner: HashMap<Side, Side>,
}

impl Level1 {
    fn of(v: &Volume) -> Result<Level1> {
        // Every face is subdivided in its canonical form, so that sub-face k is sub-face k of its
        // face type (the constraint generator ties them to the face type's operators); edge e of
        // the canonical form is edge (e + rot) of the face as it lies on the surface.
        let mut subs = Vec::new();
        let mut rot = Vec::new();
        for f in &v.surface.faces {
            let (c, r) = f.canonical();
            subs.push(subdivide(&c)?);
            rot.push(r);
        }
        let mut partner = HashMap::new();
        // Where each piece of each face edge lies: (face, origin) -> (sub-face, position).
        let mut piece_at: HashMap<(usize, Origin), (usize, usize)> = HashMap::new();
        for (f, sub) in subs.iter().enumerate() {
            for (k, s) in sub.subfaces.iter().enumerate() {
                for (p, o) in s.origins.iter().enumerate() {
                    if let Origin::Piece { .. } = o {
                        piece_at.insert((f, *o), (k, p));
                    }
                }
            }
            for a in &sub.adjacencies {
                let x = (f, a.first.0, a.first.1);
                let y = (f, a.second.0, a.second.1);
                partner.insert(x, y);
                partner.insert(y, x);
            }
        }
        for (f, sub) in subs.iter().enumerate() {
            for (k, s) in sub.subfaces.iter().enumerate() {
                for (p, o) in s.origins.iter().enumerate() {
                    let Origin::Piece { edge, piece } = *o else {
                        continue;
                    };
                    let len_f = v.surface.faces[f].boundary.len();
                    let (g, j) = v.surface.glue[f][(edge + rot[f]) % len_f];
                    let len_g = v.surface.faces[g].boundary.len();
                    let n =
                        v.surface.faces[f].boundary[(edge + rot[f]) % len_f].piece_count() as usize;
                    let there = Origin::Piece {
                        edge: (j + len_g - rot[g]) % len_g,
                        piece: n - 1 - piece,
                    };
                    let Some(&(k2, p2)) = piece_at.get(&(g, there)) else {
                        return Err(Error::Usage(format!(
                            "volume: piece {piece} of edge {edge} of face {f} has no partner"
                        )));
                    };
                    partner.insert((f, k, p), (g, k2, p2));
                }
            }
        }
        Ok(Level1 { subs, partner })
    }

    fn len(&self, f: usize, k: usize) -> usize {
        self.subs[f].subfaces[k].face.boundary.len()
    }

    fn origin(&self, (f, k, p): Side) -> Origin {
        self.subs[f].subfaces[k].origins[p]
    }

    /// The sub-faces as (face of S, sub-face) pairs.
    fn subfaces(&self) -> Vec<(usize, usize)> {
        self.subs
            .iter()
            .enumerate()
            .flat_map(|(f, s)| (0..s.subfaces.len()).map(move |k| (f, k)))
            .collect()
    }

    /// The next rim side after `h`, where `interior(side)` tells the sides glued inside the
    /// region: from the end of `h`, turn around its end point across interior sides until a rim
    /// side starts there.
    fn next_rim(&self, h: Side, interior: &dyn Fn(Side) -> bool) -> Side {
        let (f, k, p) = h;
        let mut c = (f, k, (p + 1) % self.len(f, k));
        let mut guard = 0usize;
        while interior(c) {
            let (f2, k2, p2) = self.partner[&c];
            c = (f2, k2, (p2 + 1) % self.len(f2, k2));
            guard += 1;
            assert!(guard <= self.partner.len() + 1, "rim walk loops");
        }
        c
    }

    /// The rim loops of a region (its rim sides, each loop in walking order).
    fn loops(&self, rim: &[Side], interior: &dyn Fn(Side) -> bool) -> Vec<Vec<Side>> {
        let mut done: HashMap<Side, bool> = rim.iter().map(|&s| (s, false)).collect();
        let mut out = Vec::new();
        for &s in rim {
            if done[&s] {
                continue;
            }
            let mut cycle = Vec::new();
            let mut c = s;
            while !done[&c] {
                done.insert(c, true);
                cycle.push(c);
                c = self.next_rim(c, interior);
            }
            out.push(cycle);
        }
        out
    }
}

/// Subdivides a volume: its sub-volumes, each in canonical form.
pub fn subdivide_volume(v: &Volume) -> Result<VolumeSubdivision> {
    let l1 = Level1::of(v)?;
    if v.delay >= 2 {
        let subvolumes = vec![delayed(v, &l1)];
        let interior = interior_cells(v, &l1, &subvolumes);
        return Ok(VolumeSubdivision {
            subvolumes,
            spoke_pairs: Vec::new(),
            interior,
        });
    }
    let all = l1.subfaces();
    let index: HashMap<(usize, usize), usize> =
        all.iter().enumerate().map(|(i, &s)| (s, i)).collect();
    // Patches: sub-faces joined across paired sides that are not spoke edges.
    let mut uf = Dsu::new(all.len());
    for (&a, &b) in &l1.partner {
        if !v.rule.is_spoke(&l1.origin(a)) {
            uf.union(index[&(a.0, a.1)], index[&(b.0, b.1)]);
        }
    }
    let mut groups: Vec<Vec<(usize, usize)>> = Vec::new();
    let mut group_of: HashMap<usize, usize> = HashMap::new();
    for (i, &s) in all.iter().enumerate() {
        let r = uf.find(i);
        let g = *group_of.entry(r).or_insert_with(|| {
            groups.push(Vec::new());
            groups.len() - 1
        });
        groups[g].push(s);
    }
    let subvolumes = groups
        .iter()
        .enumerate()
        .map(|(n, g)| raise(v, &l1, n, g))
        .collect::<Result<Vec<_>>>()?;
    let mut spoke_pairs: Vec<(Side, Side)> = l1
        .partner
        .iter()
        .filter(|(a, b)| a < b && v.rule.is_spoke(&l1.origin(**a)))
        .map(|(&a, &b)| (a, b))
        .collect();
    spoke_pairs.sort();
    let interior = interior_cells(v, &l1, &subvolumes);
    Ok(VolumeSubdivision {
        subvolumes,
        spoke_pairs,
        interior,
    })
}

/// The sub-volume over one patch.
fn raise(v: &Volume, l1: &Level1, n: usize, patch: &[(usize, usize)]) -> Result<SubVolume> {
    let member: HashMap<(usize, usize), usize> =
        patch.iter().enumerate().map(|(i, &s)| (s, i)).collect();
    let interior = |s: Side| -> bool {
        !v.rule.is_spoke(&l1.origin(s))
            && l1
                .partner
                .get(&s)
                .is_some_and(|t| member.contains_key(&(t.0, t.1)))
    };
    let sides: Vec<Side> = patch
        .iter()
        .flat_map(|&(f, k)| (0..l1.len(f, k)).map(move |p| (f, k, p)))
        .collect();
    let rim: Vec<Side> = sides.iter().copied().filter(|&s| !interior(s)).collect();
    let loops = l1.loops(&rim, &interior);
    // The patch's Euler characteristic: corners identified across interior sides.
    let corner: HashMap<Side, usize> = sides.iter().enumerate().map(|(i, &s)| (s, i)).collect();
    let mut uf = Dsu::new(sides.len());
    let mut interior_sides = 0usize;
    for &s in &sides {
        if interior(s) {
            interior_sides += 1;
            let t = l1.partner[&s];
            let after = (t.0, t.1, (t.2 + 1) % l1.len(t.0, t.1));
            uf.union(corner[&s], corner[&after]);
        }
    }
    let vertices = uf.classes();
    let edges = interior_sides / 2 + rim.len();
    let chi = vertices as i64 - edges as i64 + patch.len() as i64;
    if loops.len() != 1 || chi != 1 {
        let names: Vec<String> = patch
            .iter()
            .map(|&(f, k)| format!("face {f} sub-face {k}"))
            .collect();
        return Err(Error::Usage(format!(
            "volume rule {}: patch {n} ({}) is not a disk ({} rim loop{}, V − E + F = {chi}): the rule cannot raise a sub-volume over it",
            v.rule,
            names.join(", "),
            loops.len(),
            if loops.len() == 1 { "" } else { "s" }
        )));
    }
    let rim = &loops[0];
    // A spoke edge with the patch on both sides would make the sub-volume meet itself across
    // its spoke face: W(P) would not be a ball of the solid.
    if let Some(&(f, k, p)) = rim.iter().find(|&&s| {
        v.rule.is_spoke(&l1.origin(s))
            && l1
                .partner
                .get(&s)
                .is_some_and(|t| member.contains_key(&(t.0, t.1)))
    }) {
        return Err(Error::Usage(format!(
            "volume rule {}: patch {n} is not a disk in the solid: the spoke edge on side {p} of face {f} sub-face {k} has the patch on both sides, so its sub-volume would meet itself across the spoke face",
            v.rule
        )));
    }
    let m = rim.len();
    let mut faces = Vec::with_capacity(patch.len() + m + 1);
    let mut glue: Vec<Vec<(usize, usize)>> = Vec::new();
    for &(f, k) in patch {
        faces.push(l1.subs[f].subfaces[k].face.as_ref().clone());
        glue.push(vec![(usize::MAX, 0); l1.len(f, k)]);
    }
    for &s in &sides {
        if interior(s) {
            let t = l1.partner[&s];
            glue[member[&(s.0, s.1)]][s.2] = (member[&(t.0, t.1)], t.2);
        }
    }
    let side0 = patch.len();
    let inner_face = side0 + m;
    let mut spoke_sides = 0;
    for (i, &r) in rim.iter().enumerate() {
        let x = l1.subs[r.0].subfaces[r.1].face.boundary[r.2];
        if v.rule.is_spoke(&l1.origin(r)) {
            spoke_sides += 1;
        }
        faces.push(v.inner_face(vec![x, v.radial, v.inner, v.radial]));
        let prev = side0 + (i + m - 1) % m;
        let next = side0 + (i + 1) % m;
        glue[member[&(r.0, r.1)]][r.2] = (side0 + i, 0);
        glue.push(vec![
            (member[&(r.0, r.1)], r.2),
            (prev, 3),
            (inner_face, m - 1 - i),
            (next, 1),
        ]);
    }
    faces.push(v.inner_face(vec![v.inner; m]));
    glue.push((0..m).map(|k| (side0 + (m - 1 - k), 2)).collect());
    let sub = Volume {
        surface: Surface { faces, glue },
        delay: 1,
        ..v.clone()
    };
    debug_assert!(sub.surface.check().is_ok(), "{:?}", sub.surface.check());
    let (volume, place) = placed(sub);
    Ok(SubVolume {
        volume,
        patch: Some(Patch {
            subfaces: patch.to_vec(),
            spoke_sides,
            wall_sides: m - spoke_sides,
        }),
        subfaces: patch
            .iter()
            .enumerate()
            .map(|(i, &sf)| (sf, place(i)))
            .collect(),
        sides: rim
            .iter()
            .enumerate()
            .map(|(i, &r)| (r, place(side0 + i)))
            .collect(),
    })
}

/// The single sub-volume of a delayed volume: the level-1 surface with a cap over every hole.
fn delayed(v: &Volume, l1: &Level1) -> SubVolume {
    let all = l1.subfaces();
    let index: HashMap<(usize, usize), usize> =
        all.iter().enumerate().map(|(i, &s)| (s, i)).collect();
    let interior = |s: Side| l1.partner.contains_key(&s);
    let mut faces = Vec::new();
    let mut glue: Vec<Vec<(usize, usize)>> = Vec::new();
    let mut holes = Vec::new();
    for &(f, k) in &all {
        faces.push(l1.subs[f].subfaces[k].face.as_ref().clone());
        glue.push(
            (0..l1.len(f, k))
                .map(|p| match l1.partner.get(&(f, k, p)) {
                    Some(t) => (index[&(t.0, t.1)], t.2),
                    None => (usize::MAX, 0),
                })
                .collect(),
        );
        for p in 0..l1.len(f, k) {
            if !interior((f, k, p)) {
                holes.push((f, k, p));
            }
        }
    }
    for hole in l1.loops(&holes, &interior) {
        // The cap runs round the hole the other way: its edge c is the hole's side m − 1 − c.
        let m = hole.len();
        let cap = faces.len();
        let boundary = (0..m)
            .map(|c| {
                let (f, k, p) = hole[m - 1 - c];
                l1.subs[f].subfaces[k].face.boundary[p]
            })
            .collect();
        faces.push(v.inner_face(boundary));
        glue.push(
            (0..m)
                .map(|c| {
                    let (f, k, p) = hole[m - 1 - c];
                    (index[&(f, k)], p)
                })
                .collect(),
        );
        for (c, &(f, k, p)) in hole.iter().rev().enumerate() {
            glue[index[&(f, k)]][p] = (cap, c);
        }
    }
    let sub = Volume {
        surface: Surface { faces, glue },
        delay: v.delay - 1,
        ..v.clone()
    };
    debug_assert!(sub.surface.check().is_ok(), "{:?}", sub.surface.check());
    let (volume, place) = placed(sub);
    SubVolume {
        volume,
        patch: None,
        subfaces: all
            .iter()
            .enumerate()
            .map(|(i, &sf)| (sf, place(i)))
            .collect(),
        sides: Vec::new(),
    }
}

/// The cells a step creates in the relative interior of a volume (THEORY §10): they and the
/// cells born inside the faces, edges and corners of the previous level make up the level-n solid
/// without double counting, since every cell of the level-n complex is born inside exactly one
/// cell of the level before.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Interior {
    /// Faces created inside: one side face per spoke edge (shared by the two sub-volumes) and per
    /// wall edge, one inner face per sub-volume; for a delayed volume, its caps.
    pub faces: Vec<crate::topology::face::Face>,
    /// Radial edges Er: one per fan of sub-volumes around a rim point (sub-volumes joined by
    /// spoke faces share it); one inner corner at the end of each.
    pub radial_edges: usize,
    /// Inner edges Ei: one per side face.
    pub inner_edges: usize,
    /// Whether the level-1 surface has a hole (an unpaired side): the central cavity opens.
    pub opens: bool,
    /// Whether the sub-volumes are connected to each other (through shared surface points).
    pub children_connected: bool,
}

/// The interior cells of the step of `v` whose level-1 surface is `l1` and whose sub-volumes
/// are `subvolumes` (see [`Interior`]).
fn interior_cells(v: &Volume, l1: &Level1, subvolumes: &[SubVolume]) -> Interior {
    let all = l1.subfaces();
    let sides: Vec<Side> = all
        .iter()
        .flat_map(|&(f, k)| (0..l1.len(f, k)).map(move |p| (f, k, p)))
        .collect();
    let paired = |s: Side| l1.partner.contains_key(&s);
    let holes: Vec<Side> = sides.iter().copied().filter(|&s| !paired(s)).collect();
    let opens = !holes.is_empty();
    if v.delay >= 2 {
        // One cap over every hole, with the hole's edge types.
        let faces = l1
            .loops(&holes, &paired)
            .iter()
            .map(|hole| {
                let boundary = hole
                    .iter()
                    .rev()
                    .map(|&(f, k, p)| l1.subs[f].subfaces[k].face.boundary[p])
                    .collect();
                v.inner_face(boundary).canonical().0
            })
            .collect();
        return Interior {
            faces,
            radial_edges: 0,
            inner_edges: 0,
            opens,
            children_connected: true,
        };
    }
    // Side faces: a spoke edge once (from its smaller side), a wall edge once; then the inner
    // faces, one per sub-volume.
    let mut faces = Vec::new();
    let mut walls = Vec::new();
    for &s in &sides {
        let x = l1.subs[s.0].subfaces[s.1].face.boundary[s.2];
        let side_face = || {
            v.inner_face(vec![x, v.radial, v.inner, v.radial])
                .canonical()
                .0
        };
        match l1.partner.get(&s) {
            None => walls.push(side_face()),
            Some(t) if v.rule.is_spoke(&l1.origin(s)) && s < *t => faces.push(side_face()),
            Some(_) => {}
        }
    }
    faces.extend(walls);
    let inner_edges = faces.len();
    for s in subvolumes {
        let m = s.patch.as_ref().map_or(0, |p| p.spoke_sides + p.wall_sides);
        faces.push(v.inner_face(vec![v.inner; m]).canonical().0);
    }
    // Fans around the points of the level-1 surface: the corners (sectors) met turning across
    // paired sides, broken at holes. A fan ended by holes, or crossing a spoke side, has one
    // radial edge (the sub-volumes of the fan share it through their spoke faces); a full turn
    // across non-spoke sides only is a point inside one patch.
    let before = |c: Side| -> Option<Side> {
        let n = l1.len(c.0, c.1);
        l1.partner.get(&(c.0, c.1, (c.2 + n - 1) % n)).copied()
    };
    let after = |c: Side| -> Option<Side> {
        l1.partner
            .get(&c)
            .map(|t| (t.0, t.1, (t.2 + 1) % l1.len(t.0, t.1)))
    };
    let mut radial_edges = 0usize;
    let mut seen: std::collections::HashSet<Side> = std::collections::HashSet::new();
    for &c0 in &sides {
        if seen.contains(&c0) {
            continue;
        }
        let mut first = c0;
        let mut cyclic = false;
        while let Some(q) = before(first) {
            first = q;
            if first == c0 {
                cyclic = true;
                break;
            }
        }
        let mut radial = !cyclic;
        let mut c = first;
        loop {
            seen.insert(c);
            match after(c) {
                None => break,
                Some(d) => {
                    radial |= v.rule.is_spoke(&l1.origin(c));
                    if d == first {
                        break;
                    }
                    c = d;
                }
            }
        }
        radial_edges += usize::from(radial);
    }
    // The sub-volumes are joined when their patches share an edge of the level-1 surface (the
    // sub-volumes of one fan share its point, and a fan is joined across paired sides).
    let index: HashMap<(usize, usize), usize> = subvolumes
        .iter()
        .enumerate()
        .flat_map(|(i, s)| {
            s.patch
                .as_ref()
                .map(|p| {
                    p.subfaces
                        .iter()
                        .map(move |&sf| (sf, i))
                        .collect::<Vec<_>>()
                })
                .unwrap_or_default()
        })
        .collect();
    let mut uf = Dsu::new(subvolumes.len());
    for (&a, &b) in &l1.partner {
        uf.union(index[&(a.0, a.1)], index[&(b.0, b.1)]);
    }
    let children_connected = uf.classes() == 1;
    Interior {
        faces,
        radial_edges,
        inner_edges,
        opens,
        children_connected,
    }
}
