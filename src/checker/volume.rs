//! The volume-closure step (THEORY §10): the checker's own oriented maps (sphere check, canonical
//! code) and its own one-step subdivision of a volume, re-derived from the listed types with the
//! face subdivision of `closure.rs` (see `docs/CERTIFICATES.md`).
//!
//! A surface is a list of faces read counter-clockwise from outside and a gluing
//! `glue[f][i] = (g, j)`: edge `i` of face `f` runs against edge `j` of face `g`. Types are
//! compared by a canonical code: the least, over every root (a face and one of its edges), of
//! the breadth-first traversal that reads each face from its root edge and records, for every
//! edge, the discovery index of the face across it and the offset of that edge from its root.

use super::closure::{breadth_first_order, contribution, subdivide, Substitution};
use crate::certificate::{
    Edge, Face, Origin, SpokeItem, Volume, VolumeClosureStep, VolumeRule, VolumesClaim,
};
use num_bigint::BigUint;
use num_rational::BigRational;
use num_traits::Zero;
use std::collections::{BTreeMap, HashMap, VecDeque};

/// The most sides (sub-face edges) the level-1 surface of one listed type may have: a hostile
/// certificate must not make the checker build a surface of billions of sub-faces.
const MAX_SIDES: u128 = 2_000_000;

/// The most sides (face edges) a listed or derived surface may have: its canonical code costs
/// up to quadratic time in them.
const MAX_SURFACE_SIDES: usize = 20_000;

/// A face as compared: boundary as read from a root, E, the spoke items as a set, delay.
pub(super) type FaceKey = (Vec<Edge>, [Edge; 3], Vec<SpokeItem>, u32);

/// One item of a traversal code.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub(super) enum Tok {
    Face(FaceKey),
    Glue(usize, usize),
}

/// What identifies a volume type: the surface's code, G, E, A, rule and delay.
pub(super) type TypeKey = (Vec<Tok>, Edge, Edge, FaceKey, VolumeRule, u32);

/// A side of the level-1 surface: (face of S, sub-face, position).
pub(super) type Side = (usize, usize, usize);

/// A sub-volume with where each of its faces comes from.
pub(super) type Traced = (Volume, Vec<Prov>);

/// Where a face of a sub-volume comes from ([`step_traced`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Prov {
    /// Sub-face `k` of face `f` of the level-1 surface, with the same boundary positions.
    Sub(usize, usize),
    /// The side face over a rim side of the patch (edge 0 against it).
    Side(Side),
    /// A face created inside that no other sub-volume reads: the inner face of a patch, or the
    /// cap over a hole of a delayed volume.
    Inner,
}

/// A closed surface: faces and gluing.
struct Map {
    faces: Vec<Face>,
    glue: Vec<Vec<(usize, usize)>>,
}

fn items(a: &[SpokeItem]) -> Vec<SpokeItem> {
    let mut v = a.to_vec();
    v.sort();
    v.dedup();
    v
}

pub(super) fn face_key(f: &Face, root: usize) -> FaceKey {
    let mut b = f.boundary.clone();
    if !b.is_empty() {
        let r = root % b.len();
        b.rotate_left(r);
    }
    let p = f.params;
    (b, [p.ea, p.el, p.ec], items(&f.algorithm), f.delay)
}

fn edge_ok(e: &Edge) -> bool {
    e.n >= 2 && e.delay >= 1
}

/// Sub-edges of an edge: 1 when delayed, else n.
pub(super) fn pieces(e: &Edge) -> usize {
    match e.delay >= 2 {
        true => 1,
        false => e.n as usize,
    }
}

impl Map {
    /// Checks the gluing and that the surface is a sphere: every edge glued to one other edge
    /// (not itself) of the same type, glued back, connected, V − E + F = 2.
    fn sphere(&self) -> Result<(), String> {
        if self.faces.is_empty() || self.glue.len() != self.faces.len() {
            return Err("no face, or a gluing row missing".into());
        }
        for (f, face) in self.faces.iter().enumerate() {
            let p = face.params;
            let valid = [p.ea, p.el, p.ec].iter().chain(&face.boundary).all(edge_ok);
            if face.boundary.is_empty() || face.delay < 1 || face.algorithm.is_empty() || !valid {
                return Err(format!(
                    "face {f}: empty boundary or algorithm, n < 2 or a delay 0"
                ));
            }
            if self.glue[f].len() != face.boundary.len() {
                return Err(format!("face {f}: one gluing per edge is needed"));
            }
            for (i, &(g, j)) in self.glue[f].iter().enumerate() {
                let back = self.glue.get(g).and_then(|r| r.get(j));
                if back != Some(&(f, i)) || (g, j) == (f, i) {
                    return Err(format!(
                        "face {f} edge {i}: glued to face {g} edge {j}, which is not glued back"
                    ));
                }
                if self.faces[g].boundary.get(j) != Some(&face.boundary[i]) {
                    return Err(format!(
                        "face {f} edge {i}: glued to an edge of another type"
                    ));
                }
            }
        }
        let n = self.faces.len();
        let mut seen = vec![false; n];
        seen[0] = true;
        let mut queue = VecDeque::from([0usize]);
        while let Some(f) = queue.pop_front() {
            for &(g, _) in &self.glue[f] {
                if !std::mem::replace(&mut seen[g], true) {
                    queue.push_back(g);
                }
            }
        }
        if seen.iter().any(|s| !s) {
            return Err("the surface is not connected".into());
        }
        // Points: orbits of the corners under "the next corner around the same point", which is
        // the end of the edge before the corner, seen from the face across it.
        let mut done: Vec<Vec<bool>> = self
            .faces
            .iter()
            .map(|f| vec![false; f.boundary.len()])
            .collect();
        let mut points = 0i128;
        for f in 0..n {
            for i in 0..done[f].len() {
                if done[f][i] {
                    continue;
                }
                points += 1;
                let (mut g, mut j) = (f, i);
                while !done[g][j] {
                    done[g][j] = true;
                    let len = self.faces[g].boundary.len();
                    (g, j) = self.glue[g][(j + len - 1) % len];
                }
            }
        }
        let sides: i128 = self.faces.iter().map(|f| f.boundary.len() as i128).sum();
        let chi = points - sides / 2 + n as i128;
        match chi {
            2 => Ok(()),
            _ => Err(format!("V − E + F = {chi}, not 2: not a sphere")),
        }
    }

    /// The code of the traversal rooted at edge `i0` of face `f0`.
    fn code(&self, f0: usize, i0: usize) -> Vec<Tok> {
        let n = self.faces.len();
        let mut order = vec![usize::MAX; n];
        let mut root = vec![0usize; n];
        let mut seq = vec![f0];
        order[f0] = 0;
        root[f0] = i0;
        let mut out = Vec::new();
        let mut head = 0;
        while head < seq.len() {
            let f = seq[head];
            head += 1;
            let len = self.faces[f].boundary.len();
            out.push(Tok::Face(face_key(&self.faces[f], root[f])));
            for k in 0..len {
                let (g, j) = self.glue[f][(root[f] + k) % len];
                if order[g] == usize::MAX {
                    order[g] = seq.len();
                    root[g] = j;
                    seq.push(g);
                }
                let lg = self.faces[g].boundary.len();
                out.push(Tok::Glue(order[g], (j + lg - root[g]) % lg));
            }
        }
        out
    }

    /// The least code over every root whose face reading is least (only those can start the
    /// least code). The surface must have passed [`Map::sphere`].
    fn canonical_code(&self) -> Vec<Tok> {
        let roots: Vec<(usize, usize)> = (0..self.faces.len())
            .flat_map(|f| (0..self.faces[f].boundary.len()).map(move |i| (f, i)))
            .collect();
        let least = roots
            .iter()
            .map(|&(f, i)| face_key(&self.faces[f], i))
            .min();
        roots
            .iter()
            .filter(|&&(f, i)| Some(face_key(&self.faces[f], i)) == least)
            .map(|&(f, i)| self.code(f, i))
            .min()
            .unwrap_or_default()
    }
}

fn map_of(v: &Volume) -> Map {
    Map {
        faces: v.faces.clone(),
        glue: v.glue.clone(),
    }
}

/// The faces a volume creates inside it have its E and A and delay 1.
fn inside_face(v: &Volume, boundary: Vec<Edge>) -> Face {
    Face {
        boundary,
        params: v.params,
        algorithm: v.algorithm.clone(),
        delay: 1,
    }
}

fn type_key(v: &Volume, code: Vec<Tok>) -> TypeKey {
    let inside = face_key(&inside_face(v, Vec::new()), 0);
    (code, v.radial, v.inner, inside, v.rule, v.delay)
}

/// The sides the level-1 surface of `v` may have: at most 4·n per edge side (n pieces, gap
/// sides, spokes and lacuna sides), saturating.
pub(super) fn level1_sides(v: &Volume) -> u128 {
    v.faces
        .iter()
        .flat_map(|f| &f.boundary)
        .map(|e| u128::from(e.n).saturating_mul(4))
        .fold(0, u128::saturating_add)
}

/// A list of `n` items must have one per level from 0 to `levels`.
pub(super) fn one_per_level(n: usize, levels: u64, what: &str) -> Result<(), String> {
    match n as u128 == u128::from(levels) + 1 {
        true => Ok(()),
        false => Err(format!(
            "{n} {what} for levels 0 to {levels} ({} needed)",
            u128::from(levels) + 1
        )),
    }
}

/// Checks a volume's own fields and its surface; returns its type key.
pub(super) fn checked_key(v: &Volume) -> Result<TypeKey, String> {
    let p = v.params;
    let fields_ok = [v.radial, v.inner, p.ea, p.el, p.ec].iter().all(edge_ok);
    if !fields_ok || v.delay < 1 || v.algorithm.is_empty() {
        return Err("G or E with n < 2 or a delay 0, no algorithm, or delay 0".into());
    }
    let surface: usize = v.faces.iter().map(|f| f.boundary.len()).sum();
    if surface > MAX_SURFACE_SIDES {
        return Err(format!(
            "its surface has {surface} sides, above the checker's limit of {MAX_SURFACE_SIDES}"
        ));
    }
    let sides = level1_sides(v);
    if sides > MAX_SIDES {
        return Err(format!(
            "its level-1 surface may have {sides} sides, above the checker's limit of {MAX_SIDES}"
        ));
    }
    let map = map_of(v);
    map.sphere()?;
    // The canonical code reads the surface once from every root: quadratic in its sides.
    super::within_work("the canonical codes of surfaces", (surface as u128).pow(2))?;
    Ok(type_key(v, map.canonical_code()))
}

/// The level-1 surface: every face subdivided (as it lies on the surface), and the pairing of
/// sides: the two sides of a spoke edge inside a face, and piece `j` of an edge of `n` pieces
/// with piece `n − 1 − j` of the edge glued to it.
pub(super) struct Level1 {
    /// `subs[f][k]`: sub-face `k` of face `f`, as the volume reads it, with its origins.
    pub(super) subs: Vec<Vec<(Face, Vec<Origin>)>>,
    /// The side glued to each side (none for the sides of lacunas and gaps).
    pub(super) partner: HashMap<Side, Side>,
}

impl Level1 {
    fn of(v: &Volume) -> Result<Level1, String> {
        let mut subs = Vec::with_capacity(v.faces.len());
        let mut partner = HashMap::new();
        let mut piece_at: HashMap<(usize, usize, usize), (usize, usize)> = HashMap::new();
        for (f, face) in v.faces.iter().enumerate() {
            let (derived, adj) = subdivide(face).map_err(|e| format!("face {f}: {e}"))?;
            for a in adj {
                let (x, y) = ((f, a.first.0, a.first.1), (f, a.second.0, a.second.1));
                partner.insert(x, y);
                partner.insert(y, x);
            }
            let mut list = Vec::with_capacity(derived.len());
            for (k, (boundary, origins, delay)) in derived.into_iter().enumerate() {
                for (p, o) in origins.iter().enumerate() {
                    if let Origin::Piece { edge, piece } = *o {
                        piece_at.insert((f, edge, piece), (k, p));
                    }
                }
                let sub = Face {
                    boundary,
                    delay,
                    ..face.clone()
                };
                list.push((sub, origins));
            }
            subs.push(list);
        }
        for (f, list) in subs.iter().enumerate() {
            for (k, (_, origins)) in list.iter().enumerate() {
                for (p, o) in origins.iter().enumerate() {
                    let Origin::Piece { edge, piece } = *o else {
                        continue;
                    };
                    let (g, j) = v.glue[f][edge];
                    let n = pieces(&v.faces[f].boundary[edge]);
                    let Some(&(k2, p2)) = piece_at.get(&(g, j, n - 1 - piece)) else {
                        return Err(format!("face {f} edge {edge} piece {piece}: no partner"));
                    };
                    partner.insert((f, k, p), (g, k2, p2));
                }
            }
        }
        Ok(Level1 { subs, partner })
    }

    fn len(&self, (f, k): (usize, usize)) -> usize {
        self.subs[f][k].0.boundary.len()
    }

    fn origin(&self, (f, k, p): Side) -> Origin {
        self.subs[f][k].1[p]
    }

    fn edge(&self, (f, k, p): Side) -> Edge {
        self.subs[f][k].0.boundary[p]
    }

    fn sides_of(&self, sf: (usize, usize)) -> impl Iterator<Item = Side> {
        (0..self.len(sf)).map(move |p| (sf.0, sf.1, p))
    }

    /// The loops formed by the `rim` sides: after a rim side, turn around its end point across
    /// the sides `inside` tells glued within the region until a rim side starts there.
    fn loops(&self, rim: &[Side], inside: &dyn Fn(Side) -> bool) -> Result<Vec<Vec<Side>>, String> {
        let mut done: HashMap<Side, bool> = rim.iter().map(|&s| (s, false)).collect();
        let mut out = Vec::new();
        for &s in rim {
            if done[&s] {
                continue;
            }
            let mut cycle = Vec::new();
            let mut c = s;
            while !done.get(&c).copied().unwrap_or(true) {
                done.insert(c, true);
                cycle.push(c);
                let mut d = (c.0, c.1, (c.2 + 1) % self.len((c.0, c.1)));
                let mut guard = 0usize;
                while inside(d) {
                    let t = self.partner[&d];
                    d = (t.0, t.1, (t.2 + 1) % self.len((t.0, t.1)));
                    guard += 1;
                    if guard > self.partner.len() + 1 {
                        return Err("a rim walk does not end".into());
                    }
                }
                c = d;
            }
            if c != s {
                return Err("a rim walk does not close".into());
            }
            out.push(cycle);
        }
        Ok(out)
    }
}

fn spoke(rule: VolumeRule, o: Origin) -> bool {
    match (rule, o) {
        (_, Origin::Spoke { .. }) => true,
        (VolumeRule::V2, Origin::Piece { .. }) => true,
        (VolumeRule::V1, Origin::Piece { .. }) => false,
        (_, Origin::Lacuna { .. } | Origin::GapSide { .. }) => false,
    }
}

fn find(parent: &mut [usize], mut x: usize) -> usize {
    while parent[x] != x {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    x
}

fn union(parent: &mut [usize], a: usize, b: usize) {
    let (ra, rb) = (find(parent, a), find(parent, b));
    parent[ra.max(rb)] = ra.min(rb);
}

/// The sub-volumes of one step of `v`, each as a volume.
fn step(v: &Volume) -> Result<Vec<Volume>, String> {
    Ok(step_traced(v)?.1.into_iter().map(|(s, _)| s).collect())
}

/// One step of `v`: its level-1 surface, and the sub-volumes, each with where every one of its
/// faces comes from.
pub(super) fn step_traced(v: &Volume) -> Result<(Level1, Vec<Traced>), String> {
    traced(v, Level1::of(v)?)
}

/// One step of `v` from its level-1 surface `l1` (as [`step_traced`], with the faces
/// subdivided in whatever frames `l1` holds them).
pub(super) fn traced(v: &Volume, l1: Level1) -> Result<(Level1, Vec<Traced>), String> {
    let all: Vec<(usize, usize)> = l1
        .subs
        .iter()
        .enumerate()
        .flat_map(|(f, s)| (0..s.len()).map(move |k| (f, k)))
        .collect();
    let index: HashMap<(usize, usize), usize> =
        all.iter().enumerate().map(|(i, &s)| (s, i)).collect();
    let child = |faces: Vec<Face>, glue: Vec<Vec<(usize, usize)>>, delay: u32| Volume {
        faces,
        glue,
        delay,
        ..v.clone()
    };
    if v.delay >= 2 {
        // One sub-volume: the whole level-1 surface with a cap over every hole.
        let paired = |s: Side| l1.partner.contains_key(&s);
        let mut faces: Vec<Face> = all.iter().map(|&(f, k)| l1.subs[f][k].0.clone()).collect();
        let mut glue: Vec<Vec<(usize, usize)>> = all
            .iter()
            .map(|&sf| {
                l1.sides_of(sf)
                    .map(|s| match l1.partner.get(&s) {
                        Some(t) => (index[&(t.0, t.1)], t.2),
                        None => (usize::MAX, 0),
                    })
                    .collect()
            })
            .collect();
        let holes: Vec<Side> = all
            .iter()
            .flat_map(|&sf| l1.sides_of(sf))
            .filter(|&s| !paired(s))
            .collect();
        let mut prov: Vec<Prov> = all.iter().map(|&(f, k)| Prov::Sub(f, k)).collect();
        for hole in l1.loops(&holes, &paired)? {
            prov.push(Prov::Inner);
            let m = hole.len();
            let cap = faces.len();
            // The cap runs round the hole the other way: its edge c lies on hole side m − 1 − c.
            let boundary = (0..m).map(|c| l1.edge(hole[m - 1 - c])).collect();
            faces.push(inside_face(v, boundary));
            glue.push(
                (0..m)
                    .map(|c| {
                        let s = hole[m - 1 - c];
                        (index[&(s.0, s.1)], s.2)
                    })
                    .collect(),
            );
            for c in 0..m {
                let s = hole[m - 1 - c];
                glue[index[&(s.0, s.1)]][s.2] = (cap, c);
            }
        }
        let one = vec![(child(faces, glue, v.delay - 1), prov)];
        return Ok((l1, one));
    }
    // Patches: sub-faces joined across paired sides that are not spoke edges.
    let mut parent: Vec<usize> = (0..all.len()).collect();
    for (&a, &b) in &l1.partner {
        if !spoke(v.rule, l1.origin(a)) {
            union(&mut parent, index[&(a.0, a.1)], index[&(b.0, b.1)]);
        }
    }
    let mut groups: Vec<Vec<(usize, usize)>> = Vec::new();
    let mut group_of: HashMap<usize, usize> = HashMap::new();
    for (i, &sf) in all.iter().enumerate() {
        let r = find(&mut parent, i);
        let g = *group_of.entry(r).or_insert(groups.len());
        if g == groups.len() {
            groups.push(Vec::new());
        }
        groups[g].push(sf);
    }
    let mut out = Vec::with_capacity(groups.len());
    for (n, patch) in groups.iter().enumerate() {
        let member: HashMap<(usize, usize), usize> =
            patch.iter().enumerate().map(|(i, &s)| (s, i)).collect();
        let inside = |s: Side| {
            !spoke(v.rule, l1.origin(s))
                && l1
                    .partner
                    .get(&s)
                    .is_some_and(|t| member.contains_key(&(t.0, t.1)))
        };
        let sides: Vec<Side> = patch.iter().flat_map(|&sf| l1.sides_of(sf)).collect();
        let rim: Vec<Side> = sides.iter().copied().filter(|&s| !inside(s)).collect();
        let loops = l1.loops(&rim, &inside)?;
        // V − E + F of the patch: corners identified across inner sides.
        let corner: HashMap<Side, usize> = sides.iter().enumerate().map(|(i, &s)| (s, i)).collect();
        let mut cp: Vec<usize> = (0..sides.len()).collect();
        let mut inner = 0usize;
        for &s in &sides {
            if inside(s) {
                inner += 1;
                let t = l1.partner[&s];
                let next = |x: Side| (x.0, x.1, (x.2 + 1) % l1.len((x.0, x.1)));
                union(&mut cp, corner[&s], corner[&next(t)]);
                union(&mut cp, corner[&next(s)], corner[&t]);
            }
        }
        let points = (0..sides.len()).filter(|&i| find(&mut cp, i) == i).count();
        let chi = points as i128 - (inner / 2 + rim.len()) as i128 + patch.len() as i128;
        if loops.len() != 1 || chi != 1 {
            return Err(format!(
                "patch {n} is not a disk ({} rim loops, V − E + F = {chi})",
                loops.len()
            ));
        }
        let rim = &loops[0];
        if rim.iter().any(|&s| {
            spoke(v.rule, l1.origin(s))
                && l1
                    .partner
                    .get(&s)
                    .is_some_and(|t| member.contains_key(&(t.0, t.1)))
        }) {
            return Err(format!(
                "patch {n} has a spoke edge with the patch on both sides: its sub-volume would meet itself"
            ));
        }
        let m = rim.len();
        let mut faces: Vec<Face> = patch
            .iter()
            .map(|&(f, k)| l1.subs[f][k].0.clone())
            .collect();
        let mut prov: Vec<Prov> = patch.iter().map(|&(f, k)| Prov::Sub(f, k)).collect();
        prov.extend(rim.iter().map(|&r| Prov::Side(r)));
        prov.push(Prov::Inner);
        let mut glue: Vec<Vec<(usize, usize)>> = patch
            .iter()
            .map(|&sf| vec![(usize::MAX, 0); l1.len(sf)])
            .collect();
        for &s in &sides {
            if inside(s) {
                let t = l1.partner[&s];
                glue[member[&(s.0, s.1)]][s.2] = (member[&(t.0, t.1)], t.2);
            }
        }
        // Side face i over rim side r_i: `X Er Ei Er`, edge 0 against r_i, edge 1 against the
        // previous side face's edge 3, edge 2 against the inner face, edge 3 against the next
        // side face's edge 1. The inner face's edge k lies on side face m − 1 − k.
        let first = patch.len();
        let centre = first + m;
        for (i, &r) in rim.iter().enumerate() {
            faces.push(inside_face(
                v,
                vec![l1.edge(r), v.radial, v.inner, v.radial],
            ));
            glue[member[&(r.0, r.1)]][r.2] = (first + i, 0);
            glue.push(vec![
                (member[&(r.0, r.1)], r.2),
                (first + (i + m - 1) % m, 3),
                (centre, m - 1 - i),
                (first + (i + 1) % m, 1),
            ]);
        }
        faces.push(inside_face(v, vec![v.inner; m]));
        glue.push((0..m).map(|k| (first + m - 1 - k, 2)).collect());
        out.push((child(faces, glue, 1), prov));
    }
    Ok((l1, out))
}

/// Lacunas of one step in quarters: 4 for the cavity plus the halves of every face's
/// contribution (THEORY §10); 0 when delayed.
fn quarters(v: &Volume) -> BigUint {
    match v.delay >= 2 {
        true => BigUint::zero(),
        false => v
            .faces
            .iter()
            .fold(BigUint::from(4u32), |acc, f| acc + contribution(f)),
    }
}

/// Checks the volume-closure step against the claim; returns the report, the verdict and the
/// substitution read off it (lacunas in quarters).
pub(super) fn check_volume_closure(
    c: &VolumeClosureStep,
    claim: &VolumesClaim,
) -> Result<(String, String, Substitution), String> {
    let nt = c.types.len();
    let total = c
        .types
        .iter()
        .map(|t| level1_sides(&t.volume))
        .fold(0u128, u128::saturating_add);
    let limit = super::budget().sides;
    if total > limit {
        return Err(super::over(
            "re-deriving the level-1 surfaces of the listed types (sides)",
            total,
            limit,
            "max-sides",
        ));
    }
    let mut index: HashMap<TypeKey, usize> = HashMap::with_capacity(nt);
    for (t, rule) in c.types.iter().enumerate() {
        let key = checked_key(&rule.volume).map_err(|e| format!("type {t}: {e}"))?;
        if let Some(u) = index.insert(key, t) {
            return Err(format!("types {u} and {t} are the same volume type"));
        }
    }
    if claim.volumes.is_empty() {
        return Err("the claim has no start volume".into());
    }
    let mut start = vec![BigUint::zero(); nt];
    let mut firsts = Vec::new();
    for (i, v) in claim.volumes.iter().enumerate() {
        let key = checked_key(v).map_err(|e| format!("start volume {i}: {e}"))?;
        match index.get(&key) {
            Some(&t) => {
                if start[t].is_zero() {
                    firsts.push(t);
                }
                start[t] += 1u32;
            }
            None => return Err(format!("start volume {i} is not a listed type")),
        }
    }
    let children: Vec<Vec<usize>> = c.types.iter().map(|r| r.children.clone()).collect();
    breadth_first_order(&firsts, &children, "volume")?;
    let mut subvolumes = 0usize;
    for (t, rule) in c.types.iter().enumerate() {
        let derived = step(&rule.volume).map_err(|e| format!("type {t}: {e}"))?;
        let mut got = Vec::with_capacity(derived.len());
        for (k, d) in derived.iter().enumerate() {
            let surface: usize = d.faces.iter().map(|f| f.boundary.len()).sum();
            if surface > MAX_SURFACE_SIDES {
                return Err(format!(
                    "type {t}: its sub-volume {k} has {surface} sides, above the checker's limit of \
                     {MAX_SURFACE_SIDES}"
                ));
            }
            let map = map_of(d);
            map.sphere()
                .map_err(|e| format!("type {t} sub-volume {k}: {e}"))?;
            super::within_work("the canonical codes of surfaces", (surface as u128).pow(2))?;
            match index.get(&type_key(d, map.canonical_code())) {
                Some(&u) => got.push(u),
                None => {
                    return Err(format!(
                        "type {t}: its derived sub-volume {k} ({} faces) is not a listed type",
                        d.faces.len()
                    ))
                }
            }
        }
        let mut listed = rule.children.clone();
        listed.sort_unstable();
        got.sort_unstable();
        if listed != got {
            return Err(format!(
                "type {t}: the listed children {listed:?} are not the derived sub-volumes {got:?} \
                 (as a multiset of types)"
            ));
        }
        if quarters(&rule.volume) != BigUint::from(rule.contribution_quarters) {
            return Err(format!(
                "type {t}: contribution {} quarters is not the one of THEORY §10 ({})",
                rule.contribution_quarters,
                quarters(&rule.volume)
            ));
        }
        subvolumes += derived.len();
    }
    // The counts, level by level, from the derived children.
    let max_levels = super::budget().levels;
    if claim.levels > max_levels {
        return Err(super::over(
            "recounting the claimed levels",
            claim.levels.into(),
            max_levels.into(),
            "max-levels",
        ));
    }
    one_per_level(c.counts.len(), claim.levels, "counts listed")?;
    let contributions: Vec<BigUint> = c
        .types
        .iter()
        .map(|r| BigUint::from(r.contribution_quarters))
        .collect();
    let substitution = Substitution {
        matrix: c
            .types
            .iter()
            .map(|t| {
                let mut row: BTreeMap<usize, BigUint> = BTreeMap::new();
                for &ch in &t.children {
                    *row.entry(ch).or_insert_with(BigUint::zero) += 1u32;
                }
                row
            })
            .collect(),
        contributions: contributions.clone(),
        start: start
            .iter()
            .enumerate()
            .filter(|(_, k)| !k.is_zero())
            .map(|(t, k)| (t, k.clone()))
            .collect(),
        unit: 4,
    };
    let mut v = start;
    let mut lacuna_quarters = BigUint::zero();
    let (mut cells_line, mut lacunas_line) = (Vec::new(), Vec::new());
    for (i, count) in c.counts.iter().enumerate() {
        let cells: BigUint = v.iter().sum();
        let lacunas = BigRational::new(lacuna_quarters.clone().into(), 4.into());
        let listed_cells = super::rat(&count.cells).map_err(|e| format!("level {i}: {e}"))?;
        let listed_lacunas = super::rat(&count.lacunas).map_err(|e| format!("level {i}: {e}"))?;
        if count.level != i as u64 {
            return Err(format!("count {i} is for level {}", count.level));
        }
        if listed_cells != BigRational::from_integer(cells.clone().into()) {
            return Err(format!(
                "level {i}: {} cells listed, {cells} recounted",
                count.cells
            ));
        }
        if listed_lacunas != lacunas {
            return Err(format!(
                "level {i}: {} lacunas listed, {lacunas} recounted",
                count.lacunas
            ));
        }
        cells_line.push(cells.to_string());
        lacunas_line.push(lacunas.to_string());
        let mut next = vec![BigUint::zero(); nt];
        for (t, k) in v.iter().enumerate() {
            if k.is_zero() {
                continue;
            }
            lacuna_quarters += k * &contributions[t];
            for &ch in &c.types[t].children {
                next[ch] += k;
            }
        }
        v = next;
    }
    let msg = format!(
        "{} closed under subdivision, the claim's {} among them: every surface a sphere, \
         {subvolumes} sub-volumes re-derived (THEORY §10) and identified by canonical code, every \
         contribution and the counts of levels 0–{} recounted",
        super::counted(nt, "volume type", "volume types"),
        super::counted(claim.volumes.len(), "start volume", "start volumes"),
        claim.levels
    );
    let verdict = format!(
        "volume closure: {}, closed under subdivision; N^C = {}; N^L = {}",
        super::counted(nt, "volume type", "volume types"),
        cells_line.join(", "),
        lacunas_line.join(", ")
    );
    Ok((msg, verdict, substitution))
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::certificate::{Kind, Params};

    pub fn b2() -> Edge {
        Edge {
            kind: Kind::B,
            n: 2,
            delay: 1,
        }
    }

    pub fn square() -> Face {
        Face {
            boundary: vec![b2(); 4],
            params: Params {
                ea: b2(),
                el: b2(),
                ec: b2(),
            },
            algorithm: vec![SpokeItem::Joint],
            delay: 1,
        }
    }

    /// The cube: faces as corner lists (corner x + 2y + 4z), counter-clockwise from outside,
    /// glued where one face runs a → b and another b → a.
    pub fn cube() -> Volume {
        let polys: [[usize; 4]; 6] = [
            [0, 2, 3, 1],
            [4, 5, 7, 6],
            [0, 1, 5, 4],
            [2, 6, 7, 3],
            [0, 4, 6, 2],
            [1, 3, 7, 5],
        ];
        let mut at = HashMap::new();
        for (f, p) in polys.iter().enumerate() {
            for i in 0..4 {
                at.insert((p[i], p[(i + 1) % 4]), (f, i));
            }
        }
        let glue = polys
            .iter()
            .map(|p| (0..4).map(|i| at[&(p[(i + 1) % 4], p[i])]).collect())
            .collect();
        Volume {
            faces: vec![square(); 6],
            glue,
            radial: b2(),
            inner: b2(),
            params: square().params,
            algorithm: vec![SpokeItem::Joint],
            rule: VolumeRule::V1,
            delay: 1,
        }
    }

    #[test]
    fn the_cube_is_a_sphere_and_splits_into_eight_corner_pieces() {
        let c = cube();
        assert_eq!(map_of(&c).sphere(), Ok(()));
        // THEORY §10: each B2 square splits into four pentagons, one per corner; V1 cuts along
        // the spokes only, so each patch is the three pentagons at one cube corner: 8 pieces,
        // each 3 pentagons + 9 side faces + one 9-gon = 13 faces, all of one type.
        let subs = step(&c).unwrap();
        assert_eq!(subs.len(), 8);
        let codes: Vec<Vec<Tok>> = subs.iter().map(|s| map_of(s).canonical_code()).collect();
        for (s, code) in subs.iter().zip(&codes) {
            assert_eq!(s.faces.len(), 13);
            assert_eq!(map_of(s).sphere(), Ok(()));
            assert_eq!(code, &codes[0]);
        }
        // 4 for the cavity, 2 halves per square (its centre): 4 + 6·2 = 16 quarters.
        assert_eq!(quarters(&c), BigUint::from(16u32));
    }

    #[test]
    fn the_code_sees_orientation_and_relabelling() {
        let c = cube();
        // Relabelling the faces (reverse order) keeps the type.
        let n = c.faces.len();
        let relabel = Map {
            faces: c.faces.iter().rev().cloned().collect(),
            glue: c
                .glue
                .iter()
                .rev()
                .map(|r| r.iter().map(|&(g, j)| (n - 1 - g, j)).collect())
                .collect(),
        };
        assert_eq!(relabel.canonical_code(), map_of(&c).canonical_code());
        // A broken gluing is refused.
        let mut bad = map_of(&c);
        bad.glue[0][0] = bad.glue[0][1];
        assert!(bad.sphere().is_err());
    }

    #[test]
    fn hostile_sizes_are_refused_before_the_work() {
        // Two digons glued into a sphere, with edges of a million pieces: 8 000 000 level-1
        // sides, above the per-type cap, refused before any subdivision.
        let big = Edge {
            kind: Kind::B,
            n: 1_000_000,
            delay: 1,
        };
        let digon = Face {
            boundary: vec![big; 2],
            ..square()
        };
        let v = Volume {
            faces: vec![digon.clone(), digon],
            glue: vec![vec![(1, 0), (1, 1)], vec![(0, 0), (0, 1)]],
            ..cube()
        };
        let e = checked_key(&v).unwrap_err();
        assert!(e.contains("above the checker's limit"), "{e}");
        // A surface of 25 000 sides is refused before its canonical code is computed.
        let mut many = cube();
        many.faces[0].boundary = vec![b2(); 25_000];
        let e = checked_key(&many).unwrap_err();
        // 25 000 + five squares of 4.
        assert!(e.contains("25020 sides"), "{e}");
    }
}
