//! Links and one step of them: the items of a link, its canonical form, the fans of glued
//! polygons, and what one step of a face type creates (the sectors at its corners, the vertices
//! and edges born inside it) and what it makes of an edge (its pieces, the points born inside it).

use crate::topology::closure::TypeSet;
use crate::topology::edge::JunctionKind;
use crate::topology::face::least_rotation;
use crate::topology::subdivision::Origin;
use std::collections::HashMap;

/// An item of a link.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Item {
    /// Corner `corner` of a face of type `ty`.
    Sector {
        /// The face type.
        ty: usize,
        /// The corner (the start of boundary side `corner`).
        corner: usize,
    },
    /// A lacuna, a gap or the outside.
    Hole,
}

/// What lies on the other side of an edge.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub(super) enum Other {
    /// Side `side` of a face of type `ty`.
    Face(usize, usize),
    /// A lacuna or a gap: a hole inside the structure.
    Hole,
    /// The outside of the structure.
    Outside,
}

/// An edge of the complex: one face side and what is across it (canonical: the smaller first
/// when both are faces).
pub(super) type EdgeCell = ((usize, usize), Other);

pub(super) fn edge_cell(a: (usize, usize), b: Other) -> EdgeCell {
    match b {
        Other::Face(t, s) if (t, s) < a => ((t, s), Other::Face(a.0, a.1)),
        _ => (a, b),
    }
}

/// The canonical link: adjacent holes merged, least rotation.
pub(super) fn canonical(mut link: Vec<Item>) -> Vec<Item> {
    let mut out: Vec<Item> = Vec::with_capacity(link.len());
    for it in link.drain(..) {
        if it == Item::Hole && out.last() == Some(&Item::Hole) {
            continue;
        }
        out.push(it);
    }
    while out.len() > 1 && out.first() == Some(&Item::Hole) && out.last() == Some(&Item::Hole) {
        out.pop();
    }
    let r = least_rotation(&out);
    out.rotate_left(r);
    out
}

/// Fans of a set of polygons with paired sides: maximal chains of corners, counter-clockwise,
/// each with whether it closes on itself. `lens[k]` is polygon k's side count.
pub(super) fn fans(
    lens: &[usize],
    partner: &HashMap<(usize, usize), (usize, usize)>,
) -> Vec<(Vec<(usize, usize)>, bool)> {
    let succ = |(k, p): (usize, usize)| partner.get(&(k, (p + lens[k] - 1) % lens[k])).copied();
    let pred = |(k, p): (usize, usize)| {
        partner
            .get(&(k, p))
            .map(|&(k2, p2)| (k2, (p2 + 1) % lens[k2]))
    };
    let mut seen = std::collections::HashSet::new();
    let mut out = Vec::new();
    for (k, &len) in lens.iter().enumerate() {
        for p in 0..len {
            if seen.contains(&(k, p)) {
                continue;
            }
            let mut first = (k, p);
            let mut cyclic = false;
            while let Some(q) = pred(first) {
                first = q;
                if first == (k, p) {
                    cyclic = true;
                    break;
                }
            }
            let mut fan = vec![first];
            seen.insert(first);
            let mut c = first;
            while let Some(d) = succ(c) {
                if d == first {
                    break;
                }
                fan.push(d);
                seen.insert(d);
                c = d;
            }
            out.push((fan, cyclic));
        }
    }
    out
}

/// Where a fan of one face's level-1 complex touches the face's boundary.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum Point {
    /// The start of piece `piece` of boundary edge `edge` (a corner when `piece` is 0).
    Start(usize, usize),
    /// The end of piece `piece` of edge `edge`, before a gap.
    End(usize, usize),
}

/// What one step of a face type creates and how its corners turn.
pub(super) struct Local {
    /// For each corner: the sectors at it after the step.
    pub(super) corner_fan: Vec<Vec<Item>>,
    /// Links of the vertices born inside the face.
    pub(super) births: Vec<Vec<Item>>,
    /// Edges born inside the face.
    pub(super) edges: Vec<EdgeCell>,
    /// Fans at the points of the boundary, from the face's side.
    at: HashMap<Point, Vec<Item>>,
    /// For each edge and piece: the (sub-face type, side) holding it.
    pub(super) pieces: Vec<Vec<(usize, usize)>>,
}

pub(super) fn local(ts: &TypeSet, t: usize) -> Local {
    let ty = &ts.types[t];
    let sub = &ty.subdivision;
    let lens: Vec<usize> = sub.subfaces.iter().map(|s| s.origins.len()).collect();
    let mut partner = HashMap::new();
    for a in &sub.adjacencies {
        partner.insert(a.first, a.second);
        partner.insert(a.second, a.first);
    }
    let origin = |k: usize, p: usize| sub.subfaces[k].origins[p % lens[k]];
    let sector = |(k, p): (usize, usize)| Item::Sector {
        ty: ty.children[k],
        corner: p,
    };
    let mut out = Local {
        corner_fan: vec![Vec::new(); ty.face.boundary.len()],
        births: Vec::new(),
        edges: Vec::new(),
        at: HashMap::new(),
        pieces: ty
            .face
            .boundary
            .iter()
            .map(|e| vec![(0, 0); e.piece_count() as usize])
            .collect(),
    };
    for (k, s) in sub.subfaces.iter().enumerate() {
        for (p, o) in s.origins.iter().enumerate() {
            let me = (ty.children[k], p);
            match (*o, partner.get(&(k, p))) {
                (Origin::Piece { edge, piece }, _) => out.pieces[edge][piece] = me,
                (_, Some(&(k2, p2))) => {
                    if (k, p) < (k2, p2) {
                        out.edges
                            .push(edge_cell(me, Other::Face(ty.children[k2], p2)));
                    }
                }
                (_, None) => out.edges.push(edge_cell(me, Other::Hole)),
            }
        }
    }
    for (fan, cyclic) in fans(&lens, &partner) {
        let sectors: Vec<Item> = fan.iter().map(|&c| sector(c)).collect();
        if cyclic {
            out.births.push(canonical(sectors));
            continue;
        }
        let (k0, p0) = fan[0];
        let (kr, pr) = *fan.last().expect("a fan has a corner");
        let out_side = origin(k0, p0);
        let in_side = origin(kr, pr + lens[kr] - 1);
        let mut items = Vec::new();
        if !matches!(out_side, Origin::Piece { .. }) {
            items.push(Item::Hole);
        }
        items.extend(sectors.iter().copied());
        if !matches!(in_side, Origin::Piece { .. }) {
            items.push(Item::Hole);
        }
        match (out_side, in_side) {
            (Origin::Piece { edge, piece }, _) => {
                if piece == 0 {
                    out.corner_fan[edge] = sectors;
                }
                out.at.insert(Point::Start(edge, piece), items);
            }
            (_, Origin::Piece { edge, piece }) => {
                out.at.insert(Point::End(edge, piece), items);
            }
            _ => out.births.push(canonical(items)),
        }
    }
    out
}

/// The edge count and whether the inner junctions are gaps, for side `s` of type `t`.
pub(super) fn pieces_of(ts: &TypeSet, t: usize, s: usize) -> (usize, bool) {
    let e = ts.types[t].face.boundary[s];
    (
        e.piece_count() as usize,
        e.inner_junction() == Some(JunctionKind::Gap),
    )
}

/// What lies across piece `m` of an edge of `n` pieces whose far side is `other`: the far side
/// runs the edge backwards, so its piece n − 1 − m.
pub(super) fn across(locals: &[Local], other: Other, n: usize, m: usize) -> Other {
    match other {
        Other::Face(t2, j) => {
            let (a, b) = locals[t2].pieces[j][n - 1 - m];
            Other::Face(a, b)
        }
        o => o,
    }
}

/// One step of a link: each sector becomes the sectors at that corner of its face.
pub(super) fn evolve(locals: &[Local], link: &[Item]) -> Vec<Item> {
    link.iter()
        .flat_map(|&it| match it {
            Item::Sector { ty, corner } => locals[ty].corner_fan[corner].clone(),
            Item::Hole => vec![Item::Hole],
        })
        .collect()
}

/// The links of the points born inside an edge cell of `n` pieces (joints, or both ends of every
/// gap): the fan of the face on one side, then the fan of the face on the other side (or a hole).
pub(super) fn edge_births(
    locals: &[Local],
    (t, i): (usize, usize),
    other: Other,
    n: usize,
    gap: bool,
) -> Vec<Vec<Item>> {
    let fan = |f: usize, p: Point| locals[f].at.get(&p).cloned().unwrap_or_default();
    let mut out = Vec::new();
    for m in 1..n {
        // The same point read from the other side, which runs the edge backwards: piece m is
        // its piece n − 1 − m.
        let pairs = match (gap, other) {
            (true, Other::Face(_, j)) => vec![
                (Point::Start(i, m), Some(Point::End(j, n - 1 - m))),
                (Point::End(i, m - 1), Some(Point::Start(j, n - m))),
            ],
            (true, _) => vec![(Point::Start(i, m), None), (Point::End(i, m - 1), None)],
            (false, Other::Face(_, j)) => vec![(Point::Start(i, m), Some(Point::Start(j, n - m)))],
            (false, _) => vec![(Point::Start(i, m), None)],
        };
        for (p, q) in pairs {
            let mut link = fan(t, p);
            match (other, q) {
                (Other::Face(t2, _), Some(q)) => link.extend(fan(t2, q)),
                _ => link.push(Item::Hole),
            }
            out.push(link);
        }
    }
    out
}
