//! The face-homology step: the checker builds the level-n complex of the claim's start faces
//! (one face, or an assembly glued along the claim's sides) with the cells of `solid.rs` and
//! compares cells, χ, components and holes with the rows (see `docs/CERTIFICATES.md`). Split
//! from `solid.rs`, whose complex, subdivision and ranks it uses: that file builds solids, this
//! one the faces' complexes and the level-1 corners other steps read.

use super::ranks::betti;
use super::solid::{admissible, grow, next, Complex, Parity};
use crate::certificate::{Face, FaceHomologyStep, FaceRow, FacesClaim};
use std::collections::HashMap;

#[cfg(test)]
use super::ranks::Betti;
#[cfg(test)]
use super::volume::tests as volume_tests;

/// The level-0 complex of one face: its sides are distinct edges, run forwards.
pub(super) fn start_face(face: &Face) -> Result<Complex, String> {
    let mut c = Complex {
        edges: face.boundary.clone(),
        faces: Vec::new(),
        vols: Vec::new(),
    };
    let bnd = (0..face.boundary.len()).map(|e| (e, true)).collect();
    c.new_face(face.clone(), bnd)?;
    Ok(c)
}

/// The level-0 complex of the claim's start faces, each side glued to its partner in the claim
/// (one edge, read in opposite directions by the two sides); the other sides are distinct edges,
/// each face in its own orientation. A side glued twice, to itself, or to a side of another edge
/// type is refused.
pub(super) fn start_faces(claim: &FacesClaim) -> Result<Complex, String> {
    let faces = &claim.faces;
    if faces.is_empty() {
        return Err("the claim has no start face".into());
    }
    let mut base = Vec::with_capacity(faces.len());
    let mut n = 0usize;
    for (k, f) in faces.iter().enumerate() {
        if f.boundary.is_empty() || f.boundary.iter().any(|e| e.n < 2 || e.delay < 1) {
            return Err(format!(
                "start face {k} has no side, or an edge with n < 2 or delay 0"
            ));
        }
        base.push(n);
        n += f.boundary.len();
    }
    let slot = |[f, i]: [usize; 2]| -> Option<usize> {
        (i < faces.get(f)?.boundary.len()).then(|| base[f] + i)
    };
    let mut dsu = Parity::new(n);
    let mut glued = vec![false; n];
    for (k, g) in claim.glue.iter().enumerate() {
        let (Some(a), Some(b)) = (slot(g.a), slot(g.b)) else {
            return Err(format!("glued sides {k}: no such face or side"));
        };
        if a == b || glued[a] || glued[b] {
            return Err(format!(
                "glued sides {k}: a side glued to itself, or a side glued twice"
            ));
        }
        if faces[g.a[0]].boundary[g.a[1]] != faces[g.b[0]].boundary[g.b[1]] {
            return Err(format!(
                "glued sides {k}: the two sides are of different edge types"
            ));
        }
        glued[a] = true;
        glued[b] = true;
        dsu.union(a, b, true)?;
    }
    let mut edge_id: HashMap<usize, usize> = HashMap::new();
    let mut c = Complex {
        edges: Vec::new(),
        faces: Vec::new(),
        vols: Vec::new(),
    };
    for (k, f) in faces.iter().enumerate() {
        let mut bnd = Vec::with_capacity(f.boundary.len());
        for (i, ty) in f.boundary.iter().enumerate() {
            let (r, p) = dsu.find(base[k] + i);
            let e = *edge_id.entry(r).or_insert_with(|| {
                c.edges.push(*ty);
                c.edges.len() - 1
            });
            bnd.push((e, !p));
        }
        c.new_face(f.clone(), bnd)?;
    }
    Ok(c)
}

/// The corners of the level-1 complex of one face: `[k][i]` is the corner at the start of side
/// `i` of sub-face `k` (sub-faces in the order of the checker's subdivision), and the number of
/// corners.
pub(super) fn level_one_corners(face: &Face) -> Result<(Vec<Vec<usize>>, usize), String> {
    let c = next(&start_face(face)?)?;
    let (corner, n) = c.corners();
    let at = c
        .faces
        .iter()
        .map(|f| {
            f.bnd
                .iter()
                .map(|&(e, fwd)| corner[2 * e + usize::from(!fwd)])
                .collect()
        })
        .collect();
    Ok((at, n))
}

/// Checks the face-homology step against the claim's start faces, glued as the claim says.
pub(super) fn check_face(
    s: &FaceHomologyStep,
    claim: &FacesClaim,
) -> Result<(String, String), String> {
    let sizes: Vec<u64> = s
        .rows
        .iter()
        .map(|r| {
            [r.faces, r.edges, r.corners]
                .iter()
                .fold(0u64, |a, &x| a.saturating_add(x))
        })
        .collect();
    let levels: Vec<u64> = s.rows.iter().map(|r| r.level).collect();
    admissible(&levels, &sizes)?;
    let mut c = start_faces(claim)?;
    let mut lines = Vec::new();
    for (i, claimed) in s.rows.iter().enumerate() {
        if i > 0 {
            grow(&mut c, i)?;
        }
        let b = betti(&c, i as u64)?;
        let got = FaceRow {
            level: i as u64,
            faces: b.cells[1],
            edges: b.cells[2],
            corners: b.cells[3],
            euler: b.euler,
            components: b.b0,
            holes: b.b1,
        };
        if got != *claimed {
            return Err(format!(
                "level {i}: re-derived {} cells, {} edges, {} corners, χ = {}, b0 = {}, b1 = {}; \
                 the row says {}, {}, {}, χ = {}, b0 = {}, b1 = {}",
                got.faces,
                got.edges,
                got.corners,
                got.euler,
                got.components,
                got.holes,
                claimed.faces,
                claimed.edges,
                claimed.corners,
                claimed.euler,
                claimed.components,
                claimed.holes
            ));
        }
        lines.push(format!(
            "level {i}: {}, {}, {}, χ = {}, {}, {}",
            super::counted(got.faces, "cell", "cells"),
            super::counted(got.edges, "edge", "edges"),
            super::counted(got.corners, "corner", "corners"),
            got.euler,
            super::counted(got.components, "component", "components"),
            super::counted(got.holes, "hole", "holes")
        ));
    }
    let glued = match claim.glue.len() {
        0 => String::new(),
        g => format!(
            " ({} glued)",
            super::counted(g as u64, "pair of sides", "pairs of sides")
        ),
    };
    let what = match claim.faces.len() {
        1 => "face".to_string(),
        k => format!("{k} faces{glued}"),
    };
    let msg = format!(
        "the level-n complex of the claim's {what} built cell by cell at levels 0–{} (edges' \
         pieces, sub-faces, spokes, lacuna and gap sides, corners), cells counted, b0 from the \
         1-skeleton, the rank of ∂2 over F2: b2 = 0, so the rational Betti numbers equal the F2 \
         ones",
        s.rows.len() - 1
    );
    let whose = match claim.faces.len() {
        1 => "the face's".to_string(),
        k => format!("the {k} faces'"),
    };
    Ok((msg, format!("{whose} complex: {}", lines.join("; "))))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::certificate::Edge;

    #[test]
    fn the_b2_square_by_hand() {
        // A square of B2 edges under {joint gap}: level 1 is 4 pentagons round the lacuna
        // (spokes at the 4 joints): cells 4; edges 4·2 pieces + 4 spokes + 4 lacuna sides = 16;
        // corners 4 + 4 joints + 4 lacuna corners = 12; χ = 12 − 16 + 4 = 0, one component, so
        // one hole (the lacuna).
        let face = volume_tests::square();
        let mut c = start_face(&face).unwrap();
        let b = betti(&c, 0).unwrap();
        assert_eq!((b.cells, b.euler, b.b0, b.b1), ([0, 1, 4, 4], 1, 1, 0));
        c = next(&c).unwrap();
        let b = betti(&c, 1).unwrap();
        assert_eq!((b.cells, b.euler, b.b0, b.b1), ([0, 4, 16, 12], 0, 1, 1));
    }

    fn glued(faces: Vec<Face>, glue: &[([usize; 2], [usize; 2])]) -> FacesClaim {
        FacesClaim {
            faces,
            degree: 2,
            cantor_gap: "1".into(),
            glue: glue
                .iter()
                .map(|&(a, b)| crate::certificate::GluedSides { a, b })
                .collect(),
        }
    }

    fn levels_of(claim: &FacesClaim, to: usize) -> Vec<Betti> {
        let mut c = start_faces(claim).unwrap();
        let mut out = vec![betti(&c, 0).unwrap()];
        for i in 1..=to {
            c = next(&c).unwrap();
            out.push(betti(&c, i as u64).unwrap());
        }
        out
    }

    #[test]
    fn two_b2_squares_glued_by_hand() {
        // Level 0: 2 cells, 4 + 4 − 1 = 7 edges, 4 + 4 − 2 = 6 corners, χ = 1, no hole.
        // Level 1: twice the square's (4 cells, 16 edges, 12 corners) less the glued edge's
        // 2 pieces, its joint and its 2 end corners counted twice: 8 cells, 30 edges,
        // 21 corners, χ = −1, one component, so 2 holes (the two lacunas).
        let sq = volume_tests::square();
        let claim = glued(vec![sq.clone(), sq], &[([0, 0], [1, 2])]);
        let b = levels_of(&claim, 1);
        assert_eq!(
            (b[0].cells, b[0].euler, b[0].b0, b[0].b1),
            ([0, 2, 7, 6], 1, 1, 0)
        );
        assert_eq!(
            (b[1].cells, b[1].euler, b[1].b0, b[1].b1),
            ([0, 8, 30, 21], -1, 1, 2)
        );
    }

    #[test]
    fn a_glued_cantor_edge_closes_its_notches_into_holes() {
        // Mayer–Vietoris for A ∪ B along the glued edge E (b2 = 0, E a union of segments):
        // b1(A ∪ B) = b1(A) + b1(B) + b0(E) − 1 when A and B are connected. An undelayed C2
        // edge is 2^n pieces apart at level n: the two half-notches over each gap become one
        // hole, 2^n − 1 of them.
        let mut f = volume_tests::square();
        f.boundary[1] = Edge {
            kind: crate::certificate::Kind::C,
            n: 2,
            delay: 1,
        };
        let one = levels_of(&glued(vec![f.clone()], &[]), 3);
        let two = levels_of(&glued(vec![f.clone(), f], &[([0, 1], [1, 1])]), 3);
        for (n, (a, b)) in one.iter().zip(&two).enumerate() {
            assert_eq!(a.b0, 1, "level {n}");
            assert_eq!(b.b0, 1, "level {n}");
            assert_eq!(b.b1, 2 * a.b1 + (1 << n) - 1, "level {n}");
        }
    }

    #[test]
    fn a_malformed_gluing_is_refused() {
        let sq = volume_tests::square();
        let mut tri = sq.clone();
        tri.boundary.clear();
        let mut other = sq.clone();
        other.boundary[0].delay = 2;
        for (faces, glue, why) in [
            (
                vec![sq.clone(), sq.clone()],
                vec![([0, 0], [2, 0])],
                "no such face",
            ),
            (
                vec![sq.clone(), sq.clone()],
                vec![([0, 4], [1, 0])],
                "no such face",
            ),
            (vec![sq.clone()], vec![([0, 0], [0, 0])], "itself"),
            (
                vec![sq.clone(), sq.clone(), sq.clone()],
                vec![([0, 0], [1, 0]), ([2, 0], [1, 0])],
                "twice",
            ),
            (
                vec![sq.clone(), other],
                vec![([0, 0], [1, 0])],
                "different edge types",
            ),
            (vec![sq, tri], vec![([0, 0], [1, 0])], "no side"),
        ] {
            let e = start_faces(&glued(faces, &glue)).err().unwrap_or_default();
            assert!(e.contains(why), "{why}: {e}");
        }
    }
}
