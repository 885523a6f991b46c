//! One subdivision step of a face, with its full incidence map (THEORY §3).
//!
//! Every edge of every sub-face records where it comes from ([`Origin`]): a piece of a boundary
//! edge of the parent, one side of an adjacency edge (spoke), a side of the central lacuna, or one
//! side of a gap. Adjacencies pair the two Ea edges of consecutive sub-faces. The constraint
//! generator (THEORY §6) reads incidence and adjacency constraints off this map.

use crate::error::{Error, Result};
use crate::topology::edge::{EdgeType, JunctionKind};
use crate::topology::face::{least_rotation, Face};
use crate::topology::rule::Junction;
use serde::Serialize;
use std::collections::HashSet;
use std::sync::Arc;

/// Where an edge of a sub-face comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
pub enum Origin {
    /// Piece `piece` (0-based, counter-clockwise) of boundary edge `edge` of the parent.
    Piece {
        /// Index of the parent's boundary edge.
        edge: usize,
        /// Index of the sub-edge within it.
        piece: usize,
    },
    /// The adjacency edge Ea on spoke `spoke`; `inward` when traversed from the boundary towards
    /// the central lacuna.
    Spoke {
        /// Index of the spoke (in the order of [`Subdivision::spokes`]).
        spoke: usize,
        /// Direction of traversal.
        inward: bool,
    },
    /// The lacuna edge El bordering the central lacuna; sub-face `side` owns side `side`.
    Lacuna {
        /// Index of the side (equal to the sub-face's index).
        side: usize,
    },
    /// A gap-closing edge Ec at gap `gap` (between pieces `gap` and `gap + 1`) of boundary edge
    /// `edge`; `after` for the side attached to the later piece.
    GapSide {
        /// Index of the parent's boundary edge.
        edge: usize,
        /// Index of the gap within it.
        gap: usize,
        /// Which side of the gap.
        after: bool,
    },
}

/// A sub-face: its canonical face type and, aligned with its boundary, where each edge comes from.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SubFace {
    /// The sub-face, in canonical form. Interned: the sub-faces of one step that are the same
    /// type share one face (a wide edge gives hundreds of equal sub-faces).
    pub face: Arc<Face>,
    /// `origins[k]` is the origin of `face.boundary[k]`.
    pub origins: Vec<Origin>,
}

/// Two sub-faces sharing an edge, traversed in opposite directions.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct Adjacency {
    /// (sub-face, boundary position) of one side.
    pub first: (usize, usize),
    /// (sub-face, boundary position) of the other side.
    pub second: (usize, usize),
}

/// The result of one subdivision step.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Subdivision {
    /// The junctions of the subdivided boundary; junction `m` follows sub-edge `m`.
    pub junctions: Vec<Junction>,
    /// Indices of the junctions chosen as spokes (empty for a delayed face).
    pub spokes: Vec<usize>,
    /// The sub-faces; sub-face `k` runs from spoke `k` to spoke `k + 1`.
    pub subfaces: Vec<SubFace>,
    /// Adjacencies along shared Ea edges.
    pub adjacencies: Vec<Adjacency>,
}

/// The level-1 complex of one subdivision step (THEORY §9).
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Complex {
    /// Distinct points (corners of sub-faces after identification).
    pub vertices: usize,
    /// Distinct edges (a shared Ea counts once).
    pub edges: usize,
    /// Sub-faces.
    pub faces: usize,
    /// Holes it must have: 1 (the central lacuna) for a non-delayed face, else 0.
    pub holes: usize,
    /// Number of vertices per valence (edges meeting at the vertex).
    pub valences: std::collections::BTreeMap<usize, usize>,
}

impl Complex {
    /// V − E + F.
    pub fn euler(&self) -> i64 {
        self.vertices as i64 - self.edges as i64 + self.faces as i64
    }

    /// Whether V − E + F = 1 − holes (a disk with `holes` holes).
    pub fn euler_matches(&self) -> bool {
        self.euler() == 1 - self.holes as i64
    }
}

/// Union-find: the root of `x`, with path compression.
fn find(uf: &mut [usize], x: usize) -> usize {
    let mut r = x;
    while uf[r] != r {
        r = uf[r];
    }
    let mut y = x;
    while uf[y] != r {
        let next = uf[y];
        uf[y] = r;
        y = next;
    }
    r
}

fn union(uf: &mut [usize], x: usize, y: usize) {
    let (rx, ry) = (find(uf, x), find(uf, y));
    if rx != ry {
        uf[rx] = ry;
    }
}

/// One sub-edge of the subdivided boundary.
#[derive(Clone, Copy, Debug)]
struct Piece {
    edge: usize,
    piece: usize,
    ty: EdgeType,
}

/// Subdivides a face (THEORY §3). The face should be canonical: edge indices in the origins refer
/// to its boundary as given.
pub fn subdivide(face: &Face) -> Result<Subdivision> {
    // One piece and one junction per sub-edge: sized once, so that the junctions the step keeps
    // carry no spare capacity.
    let total: usize = face.boundary.iter().map(|e| e.piece_count() as usize).sum();
    let mut pieces: Vec<Piece> = Vec::with_capacity(total);
    let mut junctions: Vec<Junction> = Vec::with_capacity(total);
    let len = face.boundary.len();
    for (i, e) in face.boundary.iter().enumerate() {
        let count = e.piece_count() as usize;
        for k in 0..count {
            pieces.push(Piece {
                edge: i,
                piece: k,
                ty: e.piece(),
            });
            junctions.push(if k + 1 < count {
                Junction {
                    kind: e
                        .inner_junction()
                        .expect("a subdivided edge has inner junctions"),
                    before: *e,
                    after: *e,
                }
            } else {
                Junction {
                    kind: JunctionKind::Corner,
                    before: *e,
                    after: face.boundary[(i + 1) % len],
                }
            });
        }
    }
    let ec = face.params.ec;
    let gap_sides = |m: usize| -> [(EdgeType, Origin); 2] {
        let p = pieces[m];
        [
            (
                ec,
                Origin::GapSide {
                    edge: p.edge,
                    gap: p.piece,
                    after: false,
                },
            ),
            (
                ec,
                Origin::GapSide {
                    edge: p.edge,
                    gap: p.piece,
                    after: true,
                },
            ),
        ]
    };
    let piece_edge = |m: usize| {
        let p = pieces[m];
        (
            p.ty,
            Origin::Piece {
                edge: p.edge,
                piece: p.piece,
            },
        )
    };
    let n = pieces.len();
    if face.delay >= 2 {
        let mut raw = Vec::new();
        for (m, j) in junctions.iter().enumerate() {
            raw.push(piece_edge(m));
            if j.kind == JunctionKind::Gap {
                raw.extend(gap_sides(m));
            }
        }
        let sub = make_subface(face, face.delay - 1, raw, &mut HashSet::new());
        return Ok(Subdivision {
            junctions,
            spokes: Vec::new(),
            subfaces: vec![sub],
            adjacencies: Vec::new(),
        });
    }
    let flags = face.algorithm.spokes(&junctions);
    let spokes: Vec<usize> = (0..n)
        .filter(|&m| flags.get(m).copied().unwrap_or(false))
        .collect();
    if spokes.is_empty() {
        return Err(Error::NoSpoke {
            face: face.to_string(),
            algorithm: face.algorithm.to_string(),
        });
    }
    let s = spokes.len();
    let p = face.params;
    let mut subfaces = Vec::with_capacity(s);
    let mut interned = HashSet::new();
    for k in 0..s {
        let start = spokes[k];
        let end = spokes[(k + 1) % s];
        let run_len = if s == 1 { n } else { (end + n - start) % n };
        let mut raw = Vec::new();
        for step in 1..=run_len {
            let m = (start + step) % n;
            raw.push(piece_edge(m));
            if step < run_len && junctions[m].kind == JunctionKind::Gap {
                raw.extend(gap_sides(m));
            }
        }
        if junctions[end].kind == JunctionKind::Gap {
            raw.push(gap_sides(end)[0]);
        }
        raw.push((
            p.ea,
            Origin::Spoke {
                spoke: (k + 1) % s,
                inward: true,
            },
        ));
        raw.push((p.el, Origin::Lacuna { side: k }));
        raw.push((
            p.ea,
            Origin::Spoke {
                spoke: k,
                inward: false,
            },
        ));
        if junctions[start].kind == JunctionKind::Gap {
            raw.push(gap_sides(start)[1]);
        }
        subfaces.push(make_subface(face, 1, raw, &mut interned));
    }
    let position = |sub: &SubFace, o: Origin| {
        sub.origins
            .iter()
            .position(|x| *x == o)
            .expect("spoke edge present")
    };
    let adjacencies = (0..s)
        .map(|k| {
            let next = (k + 1) % s;
            let a = position(
                &subfaces[k],
                Origin::Spoke {
                    spoke: next,
                    inward: true,
                },
            );
            let b = position(
                &subfaces[next],
                Origin::Spoke {
                    spoke: next,
                    inward: false,
                },
            );
            Adjacency {
                first: (k, a),
                second: (next, b),
            }
        })
        .collect();
    Ok(Subdivision {
        junctions,
        spokes,
        subfaces,
        adjacencies,
    })
}

/// The sub-face of `parent` with the edges and origins of `raw`, rotated to canonical form; its
/// face is the one of `interned` when an earlier sub-face of the step has the same type.
fn make_subface(
    parent: &Face,
    delay: u32,
    raw: Vec<(EdgeType, Origin)>,
    interned: &mut HashSet<Arc<Face>>,
) -> SubFace {
    let (mut boundary, mut origins): (Vec<EdgeType>, Vec<Origin>) = raw.into_iter().unzip();
    let r = least_rotation(&boundary);
    boundary.rotate_left(r);
    origins.rotate_left(r);
    let face = Face {
        boundary,
        params: parent.params,
        algorithm: parent.algorithm.clone(),
        delay,
    };
    let face = match interned.get(&face) {
        Some(f) => Arc::clone(f),
        None => {
            let f = Arc::new(face);
            interned.insert(Arc::clone(&f));
            f
        }
    };
    SubFace { face, origins }
}

/// A dense numbering of the origins a step of `parent` with `spokes` spokes can have: the pieces
/// of each edge, the two sides of each gap of a Cantor edge, the two directions of each spoke and
/// the lacuna sides (one per spoke). [`Subdivision::verify`] counts the uses of each in a vector
/// instead of a hash map (a wide face's step has 10⁵ origins).
struct OriginSlots {
    /// Per edge: the slot of its piece 0 and its piece count.
    pieces: Vec<(usize, usize)>,
    /// Per edge: the slot of its gap 0's first side and its gap count (0 without gaps).
    gaps: Vec<(usize, usize)>,
    /// The slot of spoke 0 inward; spoke `j` takes `2j` (inward) and `2j + 1`.
    spoke: usize,
    /// The slot of lacuna side 0.
    lacuna: usize,
    /// The number of spokes.
    spokes: usize,
    /// The number of slots.
    total: usize,
}

impl OriginSlots {
    fn of(parent: &Face, spokes: usize) -> Self {
        let mut total = 0;
        let mut pieces = Vec::with_capacity(parent.boundary.len());
        let mut gaps = Vec::with_capacity(parent.boundary.len());
        for e in &parent.boundary {
            let n = e.piece_count() as usize;
            pieces.push((total, n));
            total += n;
            let g = if e.inner_junction() == Some(JunctionKind::Gap) {
                (e.n as usize).saturating_sub(1)
            } else {
                0
            };
            gaps.push((total, g));
            total += 2 * g;
        }
        let spoke = total;
        let lacuna = spoke + 2 * spokes;
        OriginSlots {
            pieces,
            gaps,
            spoke,
            lacuna,
            spokes,
            total: lacuna + spokes,
        }
    }

    /// The slot of `o`, or `None` for an origin outside the step (an index out of range).
    fn slot(&self, o: Origin) -> Option<usize> {
        let within = |i: usize, n: usize| (i < n).then_some(i);
        match o {
            Origin::Piece { edge, piece } => {
                let &(base, n) = self.pieces.get(edge)?;
                Some(base + within(piece, n)?)
            }
            Origin::GapSide { edge, gap, after } => {
                let &(base, n) = self.gaps.get(edge)?;
                Some(base + 2 * within(gap, n)? + usize::from(after))
            }
            Origin::Spoke { spoke, inward } => {
                Some(self.spoke + 2 * within(spoke, self.spokes)? + usize::from(!inward))
            }
            Origin::Lacuna { side } => Some(self.lacuna + within(side, self.spokes)?),
        }
    }
}

impl Subdivision {
    /// Checks every structural identity of the step against the parent face: each sub-edge of each
    /// parent edge is used exactly once and with its type; each gap has both sides closed once; each
    /// spoke is traversed once inward and once outward, and the two sides are paired by an
    /// adjacency; the lacuna cycle has one side per sub-face; every edge has the type its origin
    /// demands. Returns the first violation found.
    pub fn verify(&self, parent: &Face) -> std::result::Result<(), String> {
        let slots = OriginSlots::of(parent, self.spokes.len());
        let mut seen = vec![0usize; slots.total];
        for (k, sub) in self.subfaces.iter().enumerate() {
            if sub.face.boundary.len() != sub.origins.len() {
                return Err(format!(
                    "sub-face {k}: boundary and origins differ in length"
                ));
            }
            if !sub.face.is_canonical() {
                return Err(format!("sub-face {k} is not in canonical form"));
            }
            let want_delay = if parent.delay >= 2 {
                parent.delay - 1
            } else {
                1
            };
            if sub.face.delay != want_delay
                || sub.face.params != parent.params
                || sub.face.algorithm != parent.algorithm
            {
                return Err(format!(
                    "sub-face {k} does not keep E, A and the right delay"
                ));
            }
            for (pos, (o, ty)) in sub.origins.iter().zip(&sub.face.boundary).enumerate() {
                let want = match *o {
                    Origin::Piece { edge, piece } => {
                        let e = parent
                            .boundary
                            .get(edge)
                            .ok_or(format!("sub-face {k}: edge {edge} out of range"))?;
                        if piece >= e.piece_count() as usize {
                            return Err(format!(
                                "sub-face {k}: piece {piece} of edge {edge} out of range"
                            ));
                        }
                        e.piece()
                    }
                    Origin::Spoke { .. } => parent.params.ea,
                    Origin::Lacuna { .. } => parent.params.el,
                    Origin::GapSide { .. } => parent.params.ec,
                };
                if want != *ty {
                    return Err(format!(
                        "sub-face {k} position {pos}: edge {ty} but its origin demands {want}"
                    ));
                }
                let slot = slots.slot(*o).ok_or_else(|| {
                    format!("sub-face {k} position {pos}: {o:?} is not a part of this step")
                })?;
                seen[slot] += 1;
            }
        }
        // Every slot once; the message is formatted only for a violation.
        let once = |o: Origin, what: &dyn Fn() -> String| match slots.slot(o).map_or(0, |i| seen[i])
        {
            1 => Ok(()),
            0 => Err(format!("{} is missing", what())),
            c => Err(format!("{} used {c} times", what())),
        };
        for (i, e) in parent.boundary.iter().enumerate() {
            for piece in 0..e.piece_count() as usize {
                once(Origin::Piece { edge: i, piece }, &|| {
                    format!("piece {piece} of edge {i}")
                })?;
            }
            if e.inner_junction() == Some(JunctionKind::Gap) {
                for gap in 0..(e.n - 1) as usize {
                    for after in [false, true] {
                        once(
                            Origin::GapSide {
                                edge: i,
                                gap,
                                after,
                            },
                            &|| format!("side {after} of gap {gap} of edge {i}"),
                        )?;
                    }
                }
            }
        }
        let s = self.spokes.len();
        if parent.delay == 1 {
            if s == 0 || self.subfaces.len() != s {
                return Err(format!("{} sub-faces for {s} spokes", self.subfaces.len()));
            }
            for j in 0..s {
                once(
                    Origin::Spoke {
                        spoke: j,
                        inward: true,
                    },
                    &|| format!("spoke {j} inward"),
                )?;
                once(
                    Origin::Spoke {
                        spoke: j,
                        inward: false,
                    },
                    &|| format!("spoke {j} outward"),
                )?;
                once(Origin::Lacuna { side: j }, &|| format!("lacuna side {j}"))?;
            }
            if self.adjacencies.len() != s {
                return Err(format!(
                    "{} adjacencies for {s} spokes",
                    self.adjacencies.len()
                ));
            }
            for a in &self.adjacencies {
                let get = |(f, p): (usize, usize)| {
                    self.subfaces.get(f).and_then(|x| x.origins.get(p)).copied()
                };
                match (get(a.first), get(a.second)) {
                    (
                        Some(Origin::Spoke {
                            spoke: x,
                            inward: true,
                        }),
                        Some(Origin::Spoke {
                            spoke: y,
                            inward: false,
                        }),
                    ) if x == y => {}
                    _ => {
                        return Err(format!(
                            "adjacency {a:?} does not pair the two sides of one spoke"
                        ))
                    }
                }
            }
        } else if self.subfaces.len() != 1 || s != 0 || !self.adjacencies.is_empty() {
            return Err("a delayed face has exactly one sub-face and no spoke".into());
        }
        Ok(())
    }

    /// The vertices of the level-1 complex: for each sub-face and each of its corners (corner p
    /// is where edge p starts), the index of the point it is, after the identifications the
    /// topology makes — the two ends of each shared Ea edge (opposite directions), and the points
    /// of the parent's boundary (the end of a piece is the start of the next piece at a joint, or
    /// of the next edge's first piece at a corner; a gap keeps them apart). Indices are 0..V.
    pub fn corner_classes(&self, parent: &Face) -> Vec<Vec<usize>> {
        let subs = &self.subfaces;
        let stride = subs.iter().map(|s| s.origins.len()).max().unwrap_or(0);
        let mut uf: Vec<usize> = (0..subs.len() * stride).collect();
        let id = |k: usize, p: usize| k * stride + p % subs[k].origins.len();
        for adj in &self.adjacencies {
            let ((sa, la), (sb, lb)) = (adj.first, adj.second);
            union(&mut uf, id(sa, la), id(sb, lb + 1));
            union(&mut uf, id(sa, la + 1), id(sb, lb));
        }
        // The first corner seen at each boundary point, by the point's key (edge, piece, end of
        // a gap's piece) numbered densely through the pieces' slots (the keys name pieces of the
        // parent, which have slots).
        let slots = OriginSlots::of(parent, 0);
        let mut at_point = vec![usize::MAX; 2 * slots.total];
        let point = |(edge, piece, end): (usize, usize, bool)| {
            let slot = slots.slot(Origin::Piece { edge, piece });
            2 * slot.expect("a piece of the parent") + usize::from(end)
        };
        for (k, s) in subs.iter().enumerate() {
            for (l, o) in s.origins.iter().enumerate() {
                let Origin::Piece { edge, piece } = *o else {
                    continue;
                };
                let e = parent.boundary[edge];
                for (end, corner) in [(false, l), (true, l + 1)] {
                    let key = if !end {
                        (edge, piece, false)
                    } else if piece + 1 < e.piece_count() as usize {
                        match e.inner_junction() {
                            Some(JunctionKind::Gap) => (edge, piece, true),
                            _ => (edge, piece + 1, false),
                        }
                    } else {
                        ((edge + 1) % parent.boundary.len(), 0, false)
                    };
                    let c = id(k, corner);
                    match at_point[point(key)] {
                        usize::MAX => at_point[point(key)] = c,
                        other => union(&mut uf, c, other),
                    }
                }
            }
        }
        // Classes numbered in order of first appearance, through a table indexed by the root.
        let mut number = vec![usize::MAX; uf.len()];
        let mut next = 0;
        subs.iter()
            .enumerate()
            .map(|(k, s)| {
                (0..s.origins.len())
                    .map(|p| {
                        let r = find(&mut uf, id(k, p));
                        if number[r] == usize::MAX {
                            number[r] = next;
                            next += 1;
                        }
                        number[r]
                    })
                    .collect()
            })
            .collect()
    }

    /// The level-1 complex of the step: its vertex, edge and face counts, the valence of each
    /// vertex, and the number of holes it must have (the central lacuna of a non-delayed face;
    /// gaps of the boundary are notches, not holes). Its Euler characteristic V − E + F must be
    /// 1 − holes (a disk with holes).
    pub fn level1_complex(&self, parent: &Face) -> Complex {
        let class = self.corner_classes(parent);
        let vertices = class.iter().flatten().copied().max().map_or(0, |m| m + 1);
        let slots: usize = self.subfaces.iter().map(|s| s.origins.len()).sum();
        // Each shared Ea is one edge seen from two sub-faces.
        let edges = slots - self.adjacencies.len();
        let mut valence = vec![0usize; vertices];
        // The second side of each adjacency, as a flag per (sub-face, position) slot.
        let mut start = Vec::with_capacity(self.subfaces.len());
        let mut total = 0;
        for s in &self.subfaces {
            start.push(total);
            total += s.origins.len();
        }
        let mut shared = vec![false; total];
        for a in &self.adjacencies {
            let (k, p) = a.second;
            if self.subfaces.get(k).is_some_and(|s| p < s.origins.len()) {
                shared[start[k] + p] = true;
            }
        }
        for (k, s) in self.subfaces.iter().enumerate() {
            let n = s.origins.len();
            for p in 0..n {
                if shared[start[k] + p] {
                    continue;
                }
                valence[class[k][p]] += 1;
                valence[class[k][(p + 1) % n]] += 1;
            }
        }
        let mut histogram = std::collections::BTreeMap::new();
        for v in valence {
            *histogram.entry(v).or_insert(0usize) += 1;
        }
        Complex {
            vertices,
            edges,
            faces: self.subfaces.len(),
            holes: usize::from(parent.delay == 1),
            valences: histogram,
        }
    }

    /// Asserts [`Subdivision::verify`] (tests and fuzzing).
    #[cfg(any(test, fuzzing))]
    pub fn sanity_check(&self, parent: &Face) {
        if let Err(e) = self.verify(parent) {
            panic!("subdivision of `{parent}` broke an identity: {e}");
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn face(s: &str) -> Face {
        Face::parse(s).unwrap().canonical().0
    }

    #[test]
    fn verify_rejects_an_origin_outside_the_step() {
        // F0's step has 6 spokes; a sub-face that claims spoke 9 (an Ea edge, so its type is
        // right) or a piece past the end of its edge is caught, and so is a spoke used twice.
        let f0 = face("C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A1");
        let good = subdivide(&f0).unwrap();
        assert_eq!(good.verify(&f0), Ok(()));
        let (k, p) = good.adjacencies[0].first;
        let mut bad = good.clone();
        bad.subfaces[k].origins[p] = Origin::Spoke {
            spoke: 9,
            inward: true,
        };
        let e = bad.verify(&f0).unwrap_err();
        assert!(e.contains("is not a part of this step"), "{e}");
        let mut twice = good.clone();
        let (k2, p2) = good.adjacencies[1].first;
        twice.subfaces[k2].origins[p2] = good.subfaces[k].origins[p];
        let e = twice.verify(&f0).unwrap_err();
        assert!(e.contains("used 2 times") || e.contains("missing"), "{e}");
        let mut past = good.clone();
        let (k3, p3) = good
            .subfaces
            .iter()
            .enumerate()
            .find_map(|(k, s)| {
                s.origins
                    .iter()
                    .position(|o| matches!(o, Origin::Piece { .. }))
                    .map(|p| (k, p))
            })
            .unwrap();
        if let Origin::Piece { edge, .. } = past.subfaces[k3].origins[p3] {
            past.subfaces[k3].origins[p3] = Origin::Piece { edge, piece: 7 };
        }
        assert!(past.verify(&f0).unwrap_err().contains("out of range"));
    }

    #[test]
    fn f0_subdivides_into_six_copies_of_itself() {
        // THEORY §3 worked example.
        let f0 = face("C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A1");
        let sub = subdivide(&f0).unwrap();
        sub.sanity_check(&f0);
        assert_eq!(sub.junctions.len(), 12);
        let kinds = |k| sub.junctions.iter().filter(|j| j.kind == k).count();
        assert_eq!(kinds(JunctionKind::Corner), 6);
        assert_eq!(kinds(JunctionKind::Joint), 3);
        assert_eq!(kinds(JunctionKind::Gap), 3);
        assert_eq!(sub.spokes.len(), 6);
        assert_eq!(sub.subfaces.len(), 6);
        for s in &sub.subfaces {
            assert_eq!(*s.face, f0);
            // Equal sub-faces of one step share one interned face.
            assert!(Arc::ptr_eq(&s.face, &sub.subfaces[0].face));
        }
        // The level-1 complex by hand: points = 3 joints (valence 3: two pieces and a spoke),
        // 6 corners (2), 6 gap ends (2: a piece and an Ec), 3 spoke points inside the gaps (3: two
        // Ec and an Ea), 6 lacuna vertices (3: an Ea and two El) = 24; edges = 6 × 6 − 6 shared
        // Ea = 30; 6 faces: V − E + F = 0 = 1 − 1 hole.
        let cx = sub.level1_complex(&f0);
        assert_eq!((cx.vertices, cx.edges, cx.faces, cx.holes), (24, 30, 6, 1));
        assert_eq!(cx.valences, [(2, 12), (3, 12)].into());
        assert!(cx.euler_matches());
    }

    #[test]
    fn run_boundary_by_hand() {
        // `B2 C2 | C2 B2 B2 | A1` (Ea = C2, El = B2, Ec = B2). Junctions: B2 joint (spoke),
        // corner B2→C2, C2 gap (spoke), corner C2→B2. Run after the joint: B2, C2 then it ends at
        // the gap: `B2 C2 | Ec=B2 | C2 B2 C2` and starts at a joint. Run after the gap: C2, B2 then
        // ends at the joint: `C2 B2 | C2 B2 C2 | Ec=B2` (starts at the gap).
        let f = face("B2 C2 | C2 B2 B2 | A1");
        let sub = subdivide(&f).unwrap();
        sub.sanity_check(&f);
        let got: Vec<String> = sub.subfaces.iter().map(|s| s.face.to_string()).collect();
        let a = face("B2 C2 B2 C2 B2 C2 | C2 B2 B2 | A1").to_string();
        let b = face("C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A1").to_string();
        assert_eq!(got, vec![a, b]);
        // Gap inside a run with a custom rule (spokes at joints only): `Ec Ec` is inserted.
        let g = face("B2 C2 | C2 B2 B2 | {joint}");
        let sub = subdivide(&g).unwrap();
        sub.sanity_check(&g);
        assert_eq!(sub.subfaces.len(), 1);
        // Run: B2(second half) C2 [B2 B2] C2 B2(first half), then Ea El Ea.
        let want = face("B2 C2 B2 B2 C2 B2 C2 B2 C2 | C2 B2 B2 | {joint}");
        assert_eq!(*sub.subfaces[0].face, want);
    }

    #[test]
    fn delayed_face_has_one_subface_with_gap_closers() {
        let f = face("C3 B2^2 | B2 B2 B3 | A1 | 3");
        let sub = subdivide(&f).unwrap();
        sub.sanity_check(&f);
        assert_eq!(sub.subfaces.len(), 1);
        // C3 -> C3 [B3 B3] C3 [B3 B3] C3, B2^2 -> B2.
        assert_eq!(
            *sub.subfaces[0].face,
            face("C3 B3 B3 C3 B3 B3 C3 B2 | B2 B2 B3 | A1 | 2")
        );
    }

    #[test]
    fn no_spoke_is_an_error() {
        let f = face("B2^2 C2^3 | C2 B2 B2 | A1");
        assert_eq!(subdivide(&f).unwrap_err().code(), "E0401");
        // A3 puts spokes at corners next to delayed edges, so the same boundary subdivides.
        let f = face("B2^2 C2^3 | C2 B2 B2 | A3");
        let sub = subdivide(&f).unwrap();
        sub.sanity_check(&f);
        assert_eq!(sub.subfaces.len(), 2);
    }
}
