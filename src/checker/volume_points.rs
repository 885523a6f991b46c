//! The points of the volume types of a `volume-solution-space` step: each volume type's points
//! (the face points of its surface, glued edges merged) in the step's frames, its level-1
//! complex, and the placement of a derived sub-volume onto its listed type proved as an
//! isomorphism through the gluing. Used by `volume_system.rs`.

use super::closure::least_rotation;
use super::volume::{face_key, pieces, Level1, Prov, Side};
use crate::certificate::{ClosureStep, Edge, Face, Kind, Origin, SubVolumePlacement, Volume};
use std::collections::HashMap;

/// The control points of an edge: q + 1 for `Bn`, 2 for `Cn`.
fn dim(q: usize, e: &Edge) -> usize {
    match e.kind {
        Kind::B => q + 1,
        Kind::C => 2,
    }
}

/// The face-state point of position `c` of edge `k` of a face type.
fn point(offsets: &[usize], m: usize, k: usize, c: usize) -> usize {
    (offsets[k] + c) % m
}

fn find(parent: &mut [usize], mut x: usize) -> usize {
    while parent[x] != x {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    x
}

/// The points of one volume type: `ids[base[f] + p]` is the volume point of point `p` (in its
/// face type's order) of face `f`; `m` of them.
pub(super) struct Points {
    pub(super) base: Vec<usize>,
    pub(super) ids: Vec<usize>,
    pub(super) m: usize,
}

/// The face types' data the volume part needs.
pub(super) struct Faces<'a> {
    pub(super) c: &'a ClosureStep,
    pub(super) q: usize,
    pub(super) dims: Vec<usize>,
    pub(super) offsets: Vec<Vec<usize>>,
    pub(super) base: Vec<Vec<usize>>,
}

impl Faces<'_> {
    pub(super) fn face(&self, t: usize) -> Result<&Face, String> {
        self.c
            .types
            .get(t)
            .map(|r| &r.face)
            .ok_or_else(|| format!("face type {t} is not listed"))
    }

    /// `row_of[p]` for the turn `R` of type `u` by `rot`: built point (edge `k + rot`, `c`) is
    /// point (edge `k`, `c`) of the frame.
    pub(super) fn turn(&self, u: usize, rot: usize) -> Vec<usize> {
        let f = &self.c.types[u].face;
        let (n, m) = (f.boundary.len(), self.dims[u]);
        let mut row_of = vec![0usize; m];
        for (k, e) in f.boundary.iter().enumerate() {
            for c in 0..dim(self.q, e) {
                row_of[point(&self.offsets[u], m, (k + rot) % n, c)] =
                    point(&self.offsets[u], m, k, c);
            }
        }
        row_of
    }

    /// One face read from both sides as types `t1` and `t2`, edge `i` of `t2` on edge `x − i`
    /// of `t1` run backwards: point `p` of `t2` is point `row_of[p]` of `t1`.
    pub(super) fn reversed(&self, t1: usize, t2: usize, x: usize) -> Result<Vec<usize>, String> {
        let (f1, f2) = (self.face(t1)?, self.face(t2)?);
        let n = f1.boundary.len();
        if f2.boundary.len() != n || self.dims[t1] != self.dims[t2] {
            return Err(format!(
                "face types {t1} and {t2} are not one face read both ways"
            ));
        }
        let mut row_of = vec![0usize; self.dims[t2]];
        for (i2, e) in f2.boundary.iter().enumerate() {
            let i1 = (x + n - i2 % n) % n;
            if f1.boundary[i1] != *e {
                return Err(format!(
                    "face types {t1} and {t2}: edge {i1} of one is not edge {i2} of the other"
                ));
            }
            let d = dim(self.q, e);
            for c in 0..d {
                row_of[point(&self.offsets[t2], self.dims[t2], i2, c)] =
                    point(&self.offsets[t1], self.dims[t1], i1, d - 1 - c);
            }
        }
        Ok(row_of)
    }
}

/// Checks `frames[f] = (t, r)` for every face of `v` (face `f` rotated left by `r` is type `t`)
/// and numbers the volume's points.
pub(super) fn points(
    v: &Volume,
    frames: &[(usize, usize)],
    faces: &Faces,
) -> Result<Points, String> {
    if frames.len() != v.faces.len() {
        return Err(format!(
            "{} frames for {} faces",
            frames.len(),
            v.faces.len()
        ));
    }
    let mut base = Vec::with_capacity(frames.len());
    let mut total = 0usize;
    for (f, &(t, r)) in frames.iter().enumerate() {
        let face = &v.faces[f];
        if r >= face.boundary.len().max(1) || face_key(face, r) != face_key(faces.face(t)?, 0) {
            return Err(format!("face {f} rotated by {r} is not face type {t}"));
        }
        // The frame is the canonical rotation (the least, Booth's): on a symmetric face another
        // rotation would read the type's sub-faces onto other parts of the face, another system.
        if r != least_rotation(&face.boundary) {
            return Err(format!(
                "face {f}: frame rotation {r} is not its canonical rotation {}",
                least_rotation(&face.boundary)
            ));
        }
        base.push(total);
        total = total
            .checked_add(faces.dims[t])
            .ok_or("the points overflow")?;
    }
    super::within_work("the points of a volume type", total as u128)?;
    let mut parent: Vec<usize> = (0..total).collect();
    let at = |f: usize, i: usize, c: usize| {
        let (t, r) = frames[f];
        let n = v.faces[f].boundary.len();
        base[f] + point(&faces.offsets[t], faces.dims[t], (i + n - r) % n, c)
    };
    for (f, row) in v.glue.iter().enumerate() {
        for (i, &(h, j)) in row.iter().enumerate() {
            let d = dim(faces.q, &v.faces[f].boundary[i]);
            for c in 0..d {
                let (a, b) = (
                    find(&mut parent, at(f, i, c)),
                    find(&mut parent, at(h, j, d - 1 - c)),
                );
                parent[a.max(b)] = a.min(b);
            }
        }
    }
    let mut class: HashMap<usize, usize> = HashMap::new();
    let ids: Vec<usize> = (0..total)
        .map(|x| {
            let r = find(&mut parent, x);
            let next = class.len();
            *class.entry(r).or_insert(next)
        })
        .collect();
    Ok(Points {
        base,
        ids,
        m: class.len(),
    })
}

/// The level-1 surface of `v` with every face subdivided in the frame of its face type, as the
/// step's face closure lists the sub-faces (`(f, j, p)`: side `p` of sub-face `j` of face `f`,
/// numbered as its face type's subdivision numbers them).
pub(super) fn level1(
    v: &Volume,
    frames: &[(usize, usize)],
    faces: &Faces,
) -> Result<Level1, String> {
    let mut subs = Vec::with_capacity(v.faces.len());
    let mut partner = HashMap::new();
    let mut piece_at: HashMap<(usize, usize, usize), (usize, usize)> = HashMap::new();
    for (f, &(t, _)) in frames.iter().enumerate() {
        let rule = &faces.c.types[t];
        let mut list = Vec::with_capacity(rule.subfaces.len());
        for (j, sf) in rule.subfaces.iter().enumerate() {
            for (p, o) in sf.origins.iter().enumerate() {
                if let Origin::Piece { edge, piece } = *o {
                    piece_at.insert((f, edge, piece), (j, p));
                }
            }
            list.push((faces.face(sf.type_index)?.clone(), sf.origins.clone()));
        }
        for a in &rule.adjacencies {
            let (x, y) = ((f, a.first.0, a.first.1), (f, a.second.0, a.second.1));
            partner.insert(x, y);
            partner.insert(y, x);
        }
        subs.push(list);
    }
    for (f, list) in subs.iter().enumerate() {
        let (_, r) = frames[f];
        let n = v.faces[f].boundary.len();
        for (j, (_, origins)) in list.iter().enumerate() {
            for (p, o) in origins.iter().enumerate() {
                let Origin::Piece { edge, piece } = *o else {
                    continue;
                };
                let listed = (edge + r) % n;
                let (g, i) = v.glue[f][listed];
                let (_, rg) = frames[g];
                let ng = v.faces[g].boundary.len();
                let count = pieces(&v.faces[f].boundary[listed]);
                let there = ((i + ng - rg % ng) % ng, count - 1 - piece);
                let Some(&(j2, p2)) = piece_at.get(&(g, there.0, there.1)) else {
                    return Err(format!("face {f} edge {edge} piece {piece}: no partner"));
                };
                partner.insert((f, j, p), (g, j2, p2));
            }
        }
    }
    Ok(Level1 { subs, partner })
}

/// Proves the placement of a derived sub-volume `d` (faces traced by `prov`) onto the listed
/// type `w`: the seeds the step gives (its sub-faces and side faces), propagated through the
/// gluing, map every face of `d` to a face of `w` bijectively, each face rotated onto its image's
/// face type, every glued pair onto a glued pair. Returns `(g, rot)` per face of `d`.
pub(super) fn placement(
    d: &Volume,
    prov: &[Prov],
    p: &SubVolumePlacement,
    w: &Volume,
    frames_w: &[(usize, usize)],
    faces: &Faces,
) -> Result<Vec<(usize, usize)>, String> {
    let nf = d.faces.len();
    if w.faces.len() != nf {
        return Err(format!(
            "{} faces derived, type {} has {}",
            nf,
            p.type_index,
            w.faces.len()
        ));
    }
    let subs: HashMap<(usize, usize), (usize, usize)> = p.subfaces.iter().copied().collect();
    let sides: HashMap<Side, (usize, usize)> = p.sides.iter().copied().collect();
    let mut map: Vec<Option<(usize, usize)>> = vec![None; nf];
    let mut used = vec![false; nf];
    let mut work = Vec::new();
    let (mut n_subs, mut n_sides) = (0, 0);
    for (i, pr) in prov.iter().enumerate() {
        let seed = match pr {
            Prov::Sub(f, j) => {
                n_subs += 1;
                subs.get(&(*f, *j))
            }
            Prov::Side(s) => {
                n_sides += 1;
                sides.get(s)
            }
            Prov::Inner => continue,
        };
        let &(g, rot) = seed.ok_or(format!("derived face {i} ({pr:?}) has no placement"))?;
        if g >= nf || std::mem::replace(&mut used[g], true) {
            return Err(format!(
                "face {g} of the type is out of range or placed twice"
            ));
        }
        map[i] = Some((g, rot));
        work.push(i);
    }
    if n_subs != subs.len() || n_sides != sides.len() {
        return Err("the placement names faces the sub-volume does not have".into());
    }
    // Built edge e of derived face i is edge e − rot + r_g of face g of the type.
    let listed = |i: usize, (g, rot): (usize, usize), e: usize| {
        let n = d.faces[i].boundary.len();
        (e + 2 * n - rot % n + frames_w[g].1 % n) % n
    };
    while let Some(i) = work.pop() {
        let (g, rot) = map[i].expect("placed");
        let n = d.faces[i].boundary.len();
        let (t, _) = frames_w[g];
        if rot >= n.max(1) || face_key(&d.faces[i], rot) != face_key(faces.face(t)?, 0) {
            return Err(format!(
                "derived face {i} rotated by {rot} is not face {g}'s face type {t}"
            ));
        }
        for e in 0..n {
            let (i2, e2) = d.glue[i][e];
            let (g2, le2) = w.glue[g][listed(i, (g, rot), e)];
            let n2 = d.faces[i2].boundary.len();
            if w.faces[g2].boundary.len() != n2 {
                return Err(format!("derived face {i2} and face {g2} differ in length"));
            }
            let rot2 = (e2 + frames_w[g2].1 % n2 + n2 - le2 % n2) % n2;
            match map[i2] {
                Some(x) if x == (g2, rot2) => {}
                Some(_) => {
                    return Err(format!(
                        "the gluing does not carry derived face {i2} onto one face of the type"
                    ))
                }
                None => {
                    if std::mem::replace(&mut used[g2], true) {
                        return Err(format!("face {g2} of the type is placed twice"));
                    }
                    map[i2] = Some((g2, rot2));
                    work.push(i2);
                }
            }
        }
    }
    map.into_iter()
        .enumerate()
        .map(|(i, x)| {
            x.ok_or(format!(
                "derived face {i} is not reached from the placement"
            ))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_turn_by_a_quarter_moves_every_point_one_edge_on() {
        // A square of four B2 edges (q = 2): 8 points, edge k starts at point 2k. Turned by 1,
        // built edge k + 1 is frame edge k: built point 2(k+1) + c is frame point 2k + c.
        let b2 = Edge {
            kind: Kind::B,
            n: 2,
            delay: 1,
        };
        let sq = Face {
            boundary: vec![b2; 4],
            params: crate::certificate::Params {
                ea: b2,
                el: b2,
                ec: b2,
            },
            algorithm: vec![crate::certificate::SpokeItem::Joint],
            delay: 1,
        };
        let c = ClosureStep {
            types: vec![crate::certificate::TypeRule {
                face: sq,
                subfaces: Vec::new(),
                adjacencies: Vec::new(),
                contribution_halves: 0,
            }],
        };
        let faces = Faces {
            c: &c,
            q: 2,
            dims: vec![8],
            offsets: vec![vec![0, 2, 4, 6]],
            base: vec![Vec::new()],
        };
        assert_eq!(faces.turn(0, 1), vec![6, 7, 0, 1, 2, 3, 4, 5]);
        // Read from the other side with edge i on edge −i: point 2i + c of the second reading
        // is point 2(−i) + 2 − c of the first (mod 8).
        assert_eq!(
            faces.reversed(0, 0, 0).unwrap(),
            vec![2, 1, 0, 7, 6, 5, 4, 3]
        );
    }
}
