//! The BC-IFS automaton of a closed set of volume types (THEORY §10): the automaton of every face
//! type on the volumes' surfaces (as for faces, THEORY §6) and one state per volume type.
//!
//! * A volume state's control points are the control points of the faces of its surface, with the
//!   points of glued edges merged (edge `i` of one face runs against edge `j` of the other, so its
//!   point `c` is the other's point `d − 1 − c`); `B_f` selects face `f`'s points in the order of
//!   its face state.
//! * The sub-volume operators `T_k` are the unknowns, with barycentric columns.
//! * Incidence: sub-face `j` of face `f` (a face of type `t`) lies on sub-volume `k` as its face
//!   `l`: `B_f · T_j^t = T_k · B_l · R`, where `R` turns the points from the frame in which the
//!   sub-volume's surface reads the face to the frame of the face type's subdivision.
//! * Adjacency: two sub-volumes share the side face over a spoke edge, read in opposite
//!   orientations: `T_a · B_s · P = T_b · B_s'`, where `P` pairs the points of the two readings
//!   (edge `e` of one reading is edge `−e` of the other, run backwards).
//! * Shared faces of an assembly: a face read by two start volumes in opposite directions is one
//!   face, so its sub-faces from either side must be the same polygons, at every level. For the
//!   two face types `t₁`, `t₂` of the readings, with edge `i` of `t₁` on edge `x − i` of `t₂`:
//!   `P · T₂ₖ' = T₁ₖ · Q` for every sub-face `k` of `t₁` and its mirror `k'` of `t₂` (the one with
//!   the same boundary pieces), where `P` reads `t₁`'s points in `t₂`'s frame and `Q` the
//!   sub-face's points in the mirror's frame; then the same for every pair of sub-face types.

use crate::algebra::matrix::Matrix;
use crate::constraint::automaton::{Constraint, ConstraintKind, Factor, OpKind};
use crate::constraint::generate::{automaton_of, GenOptions, Generated};
use crate::error::{Error, Result};
use crate::topology::closure::{close_or_error, TypeSet};
use crate::topology::component::Dsu;
use crate::topology::edge::{EdgeKind, EdgeType};
use crate::topology::face::Face;
use crate::topology::limits::Limits;
use crate::topology::subdivision::Origin;
use crate::topology::volume::{Placed, Surface, VolumeTypeSet};
use std::collections::HashMap;

/// The automaton of a volume closure with the indices of its volume states.
#[derive(Clone, Debug)]
pub struct GeneratedVolumes {
    /// The face part (every face type on the surfaces) and the whole automaton.
    pub generated: Generated,
    /// The face types.
    pub faces: TypeSet,
    /// The state of each volume type.
    pub volume_state: Vec<usize>,
}

fn dim(e: &EdgeType, q: usize) -> usize {
    match e.kind {
        EdgeKind::B => q + 1,
        EdgeKind::C => 2,
    }
}

/// The face-state point of edge `k`, position `c`, of a face type with these edge offsets.
fn point(offsets: &[usize], m: usize, k: usize, c: usize) -> usize {
    (offsets[k] + c) % m
}

/// The permutation matrix with a 1 at `(row_of(col), col)` for every column.
fn permutation(m: usize, row_of: impl Fn(usize) -> usize) -> Matrix {
    let mut rows = vec![vec![num_rational::BigRational::from_integer(0.into()); m]; m];
    for (c, row) in (0..m).map(|c| (c, row_of(c))) {
        rows[row][c] = num_rational::BigRational::from_integer(1.into());
    }
    Matrix::from_rows(rows)
}

/// A face shared by two volumes of an assembly: each volume's reading of it (counter-clockwise
/// from its own outside) and the edge of each reading that lies on the other's.
#[derive(Clone, Debug)]
pub struct SharedReading {
    /// The face as the first volume reads it.
    pub a: Face,
    /// Its edge lying on `b_edge` of the other reading.
    pub a_edge: usize,
    /// The face as the second volume reads it.
    pub b: Face,
    /// Its edge lying on `a_edge`.
    pub b_edge: usize,
}

/// The shared faces of an assembly as its volumes read them.
pub fn shared_readings(a: &crate::topology::volume::VolumeAssembly) -> Vec<SharedReading> {
    a.shared
        .iter()
        .map(|s| SharedReading {
            a: a.volumes[s.a.0].surface.faces[s.a.1].clone(),
            a_edge: s.a.2,
            b: a.volumes[s.b.0].surface.faces[s.b.1].clone(),
            b_edge: s.b.2,
        })
        .collect()
}

/// Builds the automaton of a closed set of volumes; `shared` are the faces shared between the
/// start volumes of an assembly (empty for one volume).
pub fn volume_automaton(
    set: &VolumeTypeSet,
    shared: &[SharedReading],
    opts: GenOptions,
    limits: &Limits,
) -> Result<GeneratedVolumes> {
    let q = opts.degree.max(1);
    let surface_faces: Vec<Face> = set
        .types
        .iter()
        .flat_map(|t| t.volume.surface.faces.iter().map(|f| f.canonical().0))
        .collect();
    let faces = close_or_error(&surface_faces, limits)?;
    let index: HashMap<&Face, usize> = faces
        .types
        .iter()
        .enumerate()
        .map(|(i, t)| (&t.face, i))
        .collect();
    let mut g = automaton_of(&faces, opts);
    let dims = g_dims(&faces, q);
    let face_dim = |t: usize| dims[t];
    let type_of = |f: &Face| -> Result<(usize, usize)> {
        let (c, r) = f.canonical();
        index
            .get(&c)
            .map(|&t| (t, r))
            .ok_or_else(|| Error::Usage(format!("face {c} of a volume is not in the face closure")))
    };
    // Points of each volume type: union-find over (face, face-state point).
    let mut volume_state = Vec::new();
    let mut embeds: Vec<Vec<usize>> = Vec::new();
    let mut frames: Vec<Vec<(usize, usize)>> = Vec::new();
    for (v, ty) in set.types.iter().enumerate() {
        let s: &Surface = &ty.volume.surface;
        let fr: Vec<(usize, usize)> = s.faces.iter().map(type_of).collect::<Result<_>>()?;
        let base: Vec<usize> = fr
            .iter()
            .scan(0, |acc, &(t, _)| {
                let b = *acc;
                *acc += face_dim(t);
                Some(b)
            })
            .collect();
        let total: usize = fr.iter().map(|&(t, _)| face_dim(t)).sum();
        let mut uf = Dsu::new(total);
        // Point `c` of surface edge `i` of face `f`, in the face state's numbering.
        let edge_point = |f: usize, i: usize, c: usize| {
            let (t, r) = fr[f];
            let n = s.faces[f].boundary.len();
            let k = (i + n - r) % n;
            base[f] + point(&g.edge_offsets[t], face_dim(t), k, c)
        };
        for (f, row) in s.glue.iter().enumerate() {
            for (i, &(h, j)) in row.iter().enumerate() {
                let d = dim(&s.faces[f].boundary[i], q);
                for c in 0..d {
                    uf.union(edge_point(f, i, c), edge_point(h, j, d - 1 - c));
                }
            }
        }
        let mut class: HashMap<usize, usize> = HashMap::new();
        let ids: Vec<usize> = (0..total)
            .map(|x| {
                let r = uf.find(x);
                let next = class.len();
                *class.entry(r).or_insert(next)
            })
            .collect();
        let m = class.len();
        let state = g.automaton.add_state(format!("V{v}"), m);
        volume_state.push(state);
        let mut bs = Vec::new();
        for (f, &(t, _)) in fr.iter().enumerate() {
            let pick: Vec<usize> = (0..face_dim(t)).map(|p| ids[base[f] + p]).collect();
            bs.push(g.automaton.add_op(
                format!("V{v}.B{f}"),
                OpKind::Embed,
                state,
                g.face_state[t],
                Some(Matrix::selection(m, &pick)),
            ));
        }
        embeds.push(bs);
        frames.push(fr);
    }
    // The unknowns are known now, from the state dimensions alone: a system above the limit is
    // refused before its constraints are built (they cost seconds on a prism of 64 sides).
    let state_dim = |v: usize| g.automaton.states[volume_state[v]].dim;
    let sub_unknowns: usize = set
        .types
        .iter()
        .enumerate()
        .flat_map(|(v, ty)| ty.children.iter().map(move |&w| (v, w)))
        .map(|(v, w)| state_dim(v).saturating_mul(state_dim(w)))
        .fold(0, usize::saturating_add);
    limits.check_unknowns(g.automaton.unknown_count().saturating_add(sub_unknowns))?;
    // Sub-volume operators and their constraints.
    for (v, ty) in set.types.iter().enumerate() {
        let ops: Vec<usize> = ty
            .children
            .iter()
            .enumerate()
            .map(|(k, &w)| {
                let op = g.automaton.add_op(
                    format!("V{v}.T{k}"),
                    OpKind::Sub,
                    volume_state[v],
                    volume_state[w],
                    None,
                );
                g.automaton.barycentric.push(op);
                op
            })
            .collect();
        // The rotation R from a face's frame on a sub-volume to its frame as built.
        let turn = |t: usize, rotation: usize| -> Matrix {
            let m = face_dim(t);
            let n = faces.types[t].face.boundary.len();
            let offs = &g.edge_offsets[t];
            let dims: Vec<usize> = faces.types[t]
                .face
                .boundary
                .iter()
                .map(|e| dim(e, q))
                .collect();
            // Built point (edge (k + rotation), c) is point (edge k, c) of the sub-volume's frame.
            let mut row_of = vec![0usize; m];
            for k in 0..n {
                for c in 0..dims[k] {
                    row_of[point(offs, m, (k + rotation) % n, c)] = point(offs, m, k, c);
                }
            }
            permutation(m, |c| row_of[c])
        };
        let mut side_of: HashMap<(usize, usize, usize), (usize, Placed)> = HashMap::new();
        for (k, sub) in ty.subdivision.subvolumes.iter().enumerate() {
            let w = ty.children[k];
            for &((f, j), placed) in &sub.subfaces {
                let (t, _) = frames[v][f];
                let wt = frames[w][placed.face].0;
                let sub_op = g.sub_ops[t][j];
                g.automaton.constraints.push(Constraint {
                    label: format!(
                        "V{v} incidence: sub-face {j} of face {f} is face {} of sub-volume {k}",
                        placed.face
                    ),
                    span: None,
                    kind: ConstraintKind::Incidence,
                    lhs: vec![Factor::Op(embeds[v][f]), Factor::Op(sub_op)],
                    rhs: vec![
                        Factor::Op(ops[k]),
                        Factor::Op(embeds[w][placed.face]),
                        Factor::Literal(turn(wt, placed.rotation)),
                    ],
                });
            }
            for &(side, placed) in &sub.sides {
                side_of.insert(side, (k, placed));
            }
        }
        // Spoke faces: a rim side whose partner side is a rim side of another sub-volume.
        for (a_side, b_side) in &ty.subdivision.spoke_pairs {
            let (Some(&(ka, pa)), Some(&(kb, pb))) = (side_of.get(a_side), side_of.get(b_side))
            else {
                return Err(Error::Usage(format!(
                    "V{v}: a spoke edge is not on the rim of two sub-volumes"
                )));
            };
            let (wa, wb) = (ty.children[ka], ty.children[kb]);
            let t = frames[wa][pa.face].0;
            let n = faces.types[t].face.boundary.len();
            // Frame edge k of b's reading is built edge (k + rb) of b; built edge e of b is built
            // edge (n − e) of a run backwards; built edge e of a is frame edge (e − ra) of a: frame
            // edge k of b lies on frame edge (−ra − rb − k) of a.
            let x = (2 * n - pa.rotation % n - pb.rotation % n) % n;
            let row_of = reversed_reading(&g, &faces, &dims, q, t, t, x)?;
            g.automaton.constraints.push(Constraint {
                label: format!(
                    "V{v} adjacency: face {} of sub-volume {ka} = face {} of sub-volume {kb} reversed",
                    pa.face, pb.face
                ),
                span: None,
                kind: ConstraintKind::Adjacency,
                lhs: vec![
                    Factor::Op(ops[ka]),
                    Factor::Op(embeds[wa][pa.face]),
                    Factor::Literal(permutation(face_dim(t), |c| row_of[c])),
                ],
                rhs: vec![Factor::Op(ops[kb]), Factor::Op(embeds[wb][pb.face])],
            });
        }
    }
    let mut start = Vec::with_capacity(shared.len());
    for sh in shared {
        let (ta, ra) = type_of(&sh.a)?;
        let (tb, rb) = type_of(&sh.b)?;
        let n = sh.a.boundary.len();
        // Edge i of type ta is edge i + ra of a's reading, which lies on edge
        // b_edge − (i + ra − a_edge) of b's reading, which is edge (that − rb) of type tb.
        let x = (sh.a_edge + sh.b_edge + 2 * n - ra % n - rb % n) % n;
        start.push((ta, tb, x));
    }
    mirror_constraints(&mut g, &faces, q, start)?;
    Ok(GeneratedVolumes {
        generated: g,
        faces,
        volume_state,
    })
}

/// One face read from both sides as types `t1` and `t2`, edge `i` of `t1` lying on edge `x − i`
/// of `t2` run backwards: point `p` of `t2`'s frame is point `row_of[p]` of `t1`'s frame (for
/// [`permutation`]). An error when the two types are not one face read both ways.
fn reversed_reading(
    g: &Generated,
    faces: &TypeSet,
    dims: &[usize],
    q: usize,
    t1: usize,
    t2: usize,
    x: usize,
) -> Result<Vec<usize>> {
    let (f1, f2) = (&faces.types[t1].face, &faces.types[t2].face);
    let n = f1.boundary.len();
    let m = dims[t1];
    if f2.boundary.len() != n || dims[t2] != m {
        return Err(Error::Usage(format!(
            "a face read from both sides as {f1} and {f2}: not one face"
        )));
    }
    let mut row_of = vec![0usize; m];
    for i2 in 0..n {
        let i1 = (x + n - i2 % n) % n;
        let e = f2.boundary[i2];
        if f1.boundary[i1] != e {
            return Err(Error::Usage(format!(
                "a face read from both sides as {f1} and {f2}: edge {i1} of one is not edge {i2} of the other"
            )));
        }
        let d = dim(&e, q);
        for c in 0..d {
            row_of[point(&g.edge_offsets[t2], m, i2, c)] =
                point(&g.edge_offsets[t1], m, i1, d - 1 - c);
        }
    }
    Ok(row_of)
}

/// The constraints of faces read from both sides (see the module documentation): a work list of
/// (t₁, t₂, x), edge `i` of type `t₁` on edge `x − i` of type `t₂` run backwards.
fn mirror_constraints(
    g: &mut Generated,
    faces: &TypeSet,
    q: usize,
    start: Vec<(usize, usize, usize)>,
) -> Result<()> {
    let dims = g_dims(faces, q);
    let mut seen = std::collections::HashSet::new();
    let mut work = start;
    while let Some((t1, t2, x)) = work.pop() {
        if !seen.insert((t1.min(t2), t1.max(t2), x)) {
            continue;
        }
        let row_of = reversed_reading(g, faces, &dims, q, t1, t2, x)?;
        let p = permutation(dims[t1], |c| row_of[c]);
        let (y1, y2) = (&faces.types[t1], &faces.types[t2]);
        let n = y1.face.boundary.len();
        let pieces = |o: &[Origin]| -> Vec<(usize, usize, usize)> {
            o.iter()
                .enumerate()
                .filter_map(|(l, o)| match *o {
                    Origin::Piece { edge, piece } => Some((edge, piece, l)),
                    _ => None,
                })
                .collect()
        };
        for (k1, sub1) in y1.subdivision.subfaces.iter().enumerate() {
            let mine = pieces(&sub1.origins);
            // The mirror of piece (e, p): piece count − 1 − p of edge x − e.
            let mirror = |e: usize, p: usize| {
                let count = y1.face.boundary[e].piece_count() as usize;
                ((x + n - e % n) % n, count - 1 - p)
            };
            let mut want: Vec<(usize, usize)> =
                mine.iter().map(|&(e, p, _)| mirror(e, p)).collect();
            want.sort_unstable();
            let found = y2.subdivision.subfaces.iter().position(|s2| {
                let mut got: Vec<(usize, usize)> = pieces(&s2.origins)
                    .iter()
                    .map(|&(e, p, _)| (e, p))
                    .collect();
                got.sort_unstable();
                got == want
            });
            let (Some(k2), Some(&(e, pc, l1))) = (found, mine.first()) else {
                return Err(Error::Usage(format!(
                    "sub-face {k1} of {} has no mirror in {} read from the other side",
                    y1.face, y2.face
                )));
            };
            let sub2 = &y2.subdivision.subfaces[k2];
            let (me, mp) = mirror(e, pc);
            let l2 = pieces(&sub2.origins)
                .iter()
                .find(|&&(e2, p2, _)| (e2, p2) == (me, mp))
                .map(|&(_, _, l)| l)
                .expect("matched by pieces");
            let len = sub1.origins.len();
            let xk = (l1 + l2) % len.max(1);
            let (w1, w2) = (y1.children[k1], y2.children[k2]);
            let q_rows = reversed_reading(g, faces, &dims, q, w1, w2, xk)?;
            g.automaton.constraints.push(Constraint {
                label: format!(
                    "shared face: sub-face {k1} of T{t1} = sub-face {k2} of T{t2} read from the other side"
                ),
                span: None,
                kind: ConstraintKind::Adjacency,
                lhs: vec![Factor::Literal(p.clone()), Factor::Op(g.sub_ops[t2][k2])],
                rhs: vec![
                    Factor::Op(g.sub_ops[t1][k1]),
                    Factor::Literal(permutation(dims[w1], |c| q_rows[c])),
                ],
            });
            work.push((w1, w2, xk));
        }
    }
    Ok(())
}

/// The dimension of each face type's state.
fn g_dims(faces: &TypeSet, q: usize) -> Vec<usize> {
    faces
        .types
        .iter()
        .map(|t| {
            t.face
                .boundary
                .iter()
                .map(|e| dim(e, q) - 1)
                .sum::<usize>()
                .max(1)
        })
        .collect()
}

/// Generates and solves the automaton of a closed set of volumes, and runs the degeneracy check
/// of THEORY §6 on every face type of the surfaces: a volume constraint that identified the wrong
/// points of two faces would force distinct corners of a face's level-1 complex together.
pub fn solve_volumes(
    set: &VolumeTypeSet,
    shared: &[SharedReading],
    opts: GenOptions,
    limits: &Limits,
) -> Result<crate::constraint::automaton::SolveReport> {
    Ok(solve_volumes_with_system(set, shared, opts, limits)?.report)
}

/// A solved volume system: lacuna's report, and the automaton, its linearisation and the exact
/// solution the report was read from (what a certificate is made of).
#[derive(Clone, Debug)]
pub struct SolvedVolumes {
    /// The report.
    pub report: crate::constraint::automaton::SolveReport,
    /// The automaton.
    pub generated: GeneratedVolumes,
    /// Its linear system, with the operator entry of every unknown.
    pub linearized: crate::constraint::automaton::Linearized,
    /// The solution.
    pub solution: crate::constraint::linsys::Solution,
}

/// [`solve_volumes`], keeping the system and its solution.
pub fn solve_volumes_with_system(
    set: &VolumeTypeSet,
    shared: &[SharedReading],
    opts: GenOptions,
    limits: &Limits,
) -> Result<SolvedVolumes> {
    let gv = volume_automaton(set, shared, opts, limits)?;
    gv.generated.automaton.check_solve_limits(limits)?;
    let (mut report, lin, solution) =
        crate::constraint::automaton::solve_automaton(&gv.generated.automaton)?;
    if let crate::constraint::linsys::Solution::Consistent(space) = &solution {
        report.degenerate = crate::constraint::generate::degeneracies(
            &gv.faces,
            &gv.generated,
            &lin.offsets,
            space,
        );
        report.degeneracy_checked = true;
    }
    Ok(SolvedVolumes {
        report,
        generated: gv,
        linearized: lin,
        solution,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::topology::volume::{parse_volume, VolumeClosure};

    fn solved(text: &str) -> crate::constraint::automaton::SolveReport {
        let v = parse_volume(text).unwrap();
        let VolumeClosure::Closed(set) = VolumeClosure::of(&[v], &Limits::default()).unwrap()
        else {
            panic!("closes")
        };
        let opts = GenOptions {
            degree: 1,
            ..GenOptions::default()
        };
        solve_volumes(&set, &[], opts, &Limits::default()).unwrap()
    }

    #[test]
    fn volume_constraints_are_consistent_and_collapse_nothing() {
        // Wrong point frames in an incidence or an adjacency would identify distinct corners of
        // some face's level-1 complex (or contradict a barycentric row).
        for text in [
            "cube B2 | B2 B2 B2 | A1 | B2 B2 | V1",
            "tetrahedron B2 | B2 B2 B2 | A1 | B2 B2 | V1",
            "cube B2 | B2 B2 B2 | A1 | B2 B2 | V2",
            "prism-3 C2 | C2 B2 B2 | A1 | B2 B2 | V1",
            "cube B2 | B2 B2 B2 | A1 | B2 B2 | V1 | 2",
        ] {
            let r = solved(text);
            assert!(r.consistent, "{text}: {:?}", r.conflict);
            assert!(r.degeneracy_checked);
            assert!(r.degenerate.is_empty(), "{text}: {:?}", r.degenerate);
            assert!(r.dof > 0, "{text}");
        }
    }
}
