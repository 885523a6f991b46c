//! 3D assemblies: several volumes glued face to face (THEORY §10).
//!
//! A shared face is one face of the solid seen from two volumes: each reads it counter-clockwise
//! from its own outside, so the two readings run in opposite directions. Edge `a` of the face of
//! the first volume lies on edge `b` of the face of the second; then edge `a + k` lies on edge
//! `b − k`, and corner `a + k` is corner `b + 1 − k`. Both readings must be the same face type
//! (equal E, A and delay, and the boundary of one is the other's reversed), and both volumes must
//! subdivide it the same way: every junction a spoke from one side is a spoke from the other,
//! for the face and every face type its subdivision reaches (its sub-faces are shared too).
//!
//! The level-0 complex of an assembly counts each shared face once and identifies the edges and
//! corners the shared faces identify; from there the level-n solid follows by birth
//! ([`crate::topology::volume::complex`]).

use crate::error::Result;
use crate::topology::component::Dsu;
use crate::topology::edge::EdgeType;
use crate::topology::face::Face;
use crate::topology::limits::Limits;
use crate::topology::subdivision::subdivide;
use crate::topology::volume::Volume;
use std::collections::{HashMap, HashSet, VecDeque};

/// Two volumes sharing a face: edge `a.2` of face `a.1` of volume `a.0` lies on edge `b.2` of
/// face `b.1` of volume `b.0`, traversed in the opposite direction.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SharedFace {
    /// (volume, face, edge) on one side.
    pub a: (usize, usize, usize),
    /// (volume, face, edge) on the other side.
    pub b: (usize, usize, usize),
}

/// Volumes with shared faces (a single volume is an assembly of one).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct VolumeAssembly {
    /// The volumes.
    pub volumes: Vec<Volume>,
    /// The shared faces.
    pub shared: Vec<SharedFace>,
}

/// The cells of the level-0 complex of an assembly: each face, edge and corner once.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StartCells {
    /// The faces (a shared face once, as the first volume reads it).
    pub faces: Vec<Face>,
    /// The edges.
    pub edges: Vec<EdgeType>,
    /// The number of corners.
    pub corners: u64,
    /// Connected components: volumes joined by shared faces.
    pub components: u64,
}

/// The cells of the level-0 complex of an assembly as the volumes read them.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StartMap {
    /// `corner[v][f][i]`: the corner of the complex that corner `i` of face `f` of volume `v` is.
    pub corner: Vec<Vec<Vec<usize>>>,
    /// `side[v][f][i]`: the edge of the complex that side `i` of face `f` of volume `v` lies on.
    pub side: Vec<Vec<Vec<usize>>>,
    /// `face[v][f]`: the face of the complex that face `f` of volume `v` is.
    pub face: Vec<Vec<usize>>,
    /// Each face of the complex as its first reader holds it: (volume, face).
    pub faces: Vec<(usize, usize)>,
}

impl StartMap {
    /// The number of corners of the complex.
    pub fn corner_count(&self) -> usize {
        self.corner
            .iter()
            .flatten()
            .flatten()
            .max()
            .map_or(0, |m| m + 1)
    }

    /// The number of edges of the complex.
    pub fn edge_count(&self) -> usize {
        self.side
            .iter()
            .flatten()
            .flatten()
            .max()
            .map_or(0, |m| m + 1)
    }
}

/// The face read from the other side, with edge `k` the edge `−k` of `f`.
pub fn reversed(f: &Face) -> Face {
    let n = f.boundary.len();
    Face {
        boundary: (0..n).map(|k| f.boundary[(n - k) % n]).collect(),
        ..f.clone()
    }
}

/// Whether the two readings of every face type reached from `f` subdivide it the same way: for
/// each type, the spoke junctions of the type and of its reversal correspond. `Err` names the
/// first type where they do not (or a closure past `limits`).
pub fn mirror_consistent(f: &Face, limits: &Limits) -> Result<std::result::Result<(), String>> {
    let mut seen: HashSet<Face> = HashSet::new();
    let mut queue = VecDeque::from([f.canonical().0]);
    while let Some(g) = queue.pop_front() {
        if !seen.insert(g.clone()) {
            continue;
        }
        if seen.len() > limits.max_types {
            return Err(crate::error::Error::Usage(format!(
                "the shared face reaches more than {} face types (--max-types)",
                limits.max_types
            )));
        }
        let here = subdivide(&g)?;
        let there = subdivide(&reversed(&g))?;
        // Sub-edge (i, p) of g is sub-edge (−i, c − 1 − p) of the reversal; the junction after
        // sub-edge m of g is the junction before its image, i.e. after the image's predecessor.
        let mut index: Vec<(usize, usize)> = Vec::new();
        for (i, e) in g.boundary.iter().enumerate() {
            index.extend((0..e.piece_count() as usize).map(|p| (i, p)));
        }
        let n = g.boundary.len();
        let mut at: HashMap<(usize, usize), usize> = HashMap::new();
        for (i, e) in reversed(&g).boundary.iter().enumerate() {
            for p in 0..e.piece_count() as usize {
                at.insert((i, p), at.len());
            }
        }
        let total = index.len();
        let image: HashSet<usize> = here
            .spokes
            .iter()
            .map(|&m| {
                let (i, p) = index[m];
                let c = g.boundary[i].piece_count() as usize;
                (at[&((n - i) % n, c - 1 - p)] + total - 1) % total
            })
            .collect();
        let theirs: HashSet<usize> = there.spokes.iter().copied().collect();
        if image != theirs {
            return Ok(Err(format!(
                "face type `{g}` has {} spokes read from one side and {} read from the other, at different junctions",
                here.spokes.len(),
                there.spokes.len()
            )));
        }
        for s in here.subfaces {
            if !seen.contains(&*s.face) {
                queue.push_back(std::sync::Arc::unwrap_or_clone(s.face));
            }
        }
    }
    Ok(Ok(()))
}

impl VolumeAssembly {
    /// One volume.
    pub fn single(v: Volume) -> VolumeAssembly {
        VolumeAssembly {
            volumes: vec![v],
            shared: Vec::new(),
        }
    }

    /// The volumes alone, in order.
    pub fn volume_list(&self) -> Vec<Volume> {
        self.volumes.clone()
    }

    /// Whether the two sides of a shared face read the same face type in opposite directions
    /// (`Err` says how they differ).
    pub fn same_face(&self, s: &SharedFace) -> std::result::Result<(), String> {
        let fa = &self.volumes[s.a.0].surface.faces[s.a.1];
        let fb = &self.volumes[s.b.0].surface.faces[s.b.1];
        let n = fa.boundary.len();
        if fb.boundary.len() != n {
            return Err(format!(
                "the faces have {n} and {} edges",
                fb.boundary.len()
            ));
        }
        if (fa.params, &fa.algorithm, fa.delay) != (fb.params, &fb.algorithm, fb.delay) {
            return Err("the faces differ in E, algorithm or delay".into());
        }
        for k in 0..n {
            let (x, y) = (
                fa.boundary[(s.a.2 + k) % n],
                fb.boundary[(s.b.2 + n - k % n) % n],
            );
            if x != y {
                return Err(format!(
                    "edge {} is {x} on one side but edge {} is {y} on the other: both sides must have the same type and delay",
                    (s.a.2 + k) % n,
                    (s.b.2 + n - k % n) % n
                ));
            }
        }
        Ok(())
    }

    /// How the corners, sides and faces of the volumes' surfaces are the cells of the level-0
    /// complex (glued inside each volume and across the shared faces).
    pub fn start_map(&self) -> StartMap {
        // Sides and corners numbered volume by volume, face by face.
        let mut base: Vec<Vec<usize>> = Vec::new();
        let mut total = 0usize;
        for v in &self.volumes {
            base.push(
                v.surface
                    .faces
                    .iter()
                    .map(|f| {
                        let b = total;
                        total += f.boundary.len();
                        b
                    })
                    .collect(),
            );
        }
        let len = |v: usize, f: usize| self.volumes[v].surface.faces[f].boundary.len();
        let id = |v: usize, f: usize, i: usize| base[v][f] + i % len(v, f);
        let mut sides = Dsu::new(total);
        let mut corners = Dsu::new(total);
        for (v, vol) in self.volumes.iter().enumerate() {
            for (f, row) in vol.surface.glue.iter().enumerate() {
                for (i, &(g, j)) in row.iter().enumerate() {
                    sides.union(id(v, f, i), id(v, g, j));
                    corners.union(id(v, f, i), id(v, g, j + 1));
                    corners.union(id(v, f, i + 1), id(v, g, j));
                }
            }
        }
        let mut hidden: HashMap<(usize, usize), (usize, usize)> = HashMap::new();
        for s in &self.shared {
            let (va, fa, a) = s.a;
            let (vb, fb, b) = s.b;
            let n = len(va, fa);
            hidden.insert((vb, fb), (va, fa));
            for k in 0..n {
                let bk = (b + n - k % n) % n;
                sides.union(id(va, fa, a + k), id(vb, fb, bk));
                corners.union(id(va, fa, a + k), id(vb, fb, bk + 1));
            }
        }
        // Dense numbers in the order of first appearance.
        let dense = |d: &mut Dsu, next: &mut HashMap<usize, usize>, x: usize| {
            let root = d.find(x);
            let n = next.len();
            *next.entry(root).or_insert(n)
        };
        let (mut corner_no, mut side_no) = (HashMap::new(), HashMap::new());
        let mut map = StartMap {
            corner: Vec::new(),
            side: Vec::new(),
            face: Vec::new(),
            faces: Vec::new(),
        };
        for (v, vol) in self.volumes.iter().enumerate() {
            let mut cs = Vec::new();
            let mut ss = Vec::new();
            for (f, face) in vol.surface.faces.iter().enumerate() {
                let n = face.boundary.len();
                cs.push(
                    (0..n)
                        .map(|i| dense(&mut corners, &mut corner_no, id(v, f, i)))
                        .collect(),
                );
                ss.push(
                    (0..n)
                        .map(|i| dense(&mut sides, &mut side_no, id(v, f, i)))
                        .collect(),
                );
            }
            map.corner.push(cs);
            map.side.push(ss);
        }
        for (v, vol) in self.volumes.iter().enumerate() {
            let mut fs = Vec::new();
            for f in 0..vol.surface.faces.len() {
                if !hidden.contains_key(&(v, f)) {
                    map.faces.push((v, f));
                    fs.push(map.faces.len() - 1);
                } else {
                    fs.push(usize::MAX);
                }
            }
            map.face.push(fs);
        }
        for (&(v, f), &(va, fa)) in &hidden {
            map.face[v][f] = map.face[va][fa];
        }
        map
    }

    /// The cells of the level-0 complex.
    pub fn start_cells(&self) -> StartCells {
        let map = self.start_map();
        let mut edges: Vec<Option<EdgeType>> = vec![None; map.edge_count()];
        for (v, vol) in self.volumes.iter().enumerate() {
            for (f, face) in vol.surface.faces.iter().enumerate() {
                for (i, &e) in face.boundary.iter().enumerate() {
                    edges[map.side[v][f][i]].get_or_insert(e);
                }
            }
        }
        let mut parts = Dsu::new(self.volumes.len());
        for s in &self.shared {
            parts.union(s.a.0, s.b.0);
        }
        StartCells {
            faces: map
                .faces
                .iter()
                .map(|&(v, f)| self.volumes[v].surface.faces[f].clone())
                .collect(),
            edges: edges.into_iter().flatten().collect(),
            corners: map.corner_count() as u64,
            components: parts.classes() as u64,
        }
    }
}
