//! The `volume-solution-space` step (THEORY §10): the constraint system of a volume closure,
//! rebuilt by the checker, and a solution space checked against it (see `docs/CERTIFICATES.md`).
//!
//! The system has the face part of THEORY §6 for the face types of the surfaces (rebuilt by
//! `system.rs` from the step's own face closure, checked as a `closure` step), then one state per
//! volume type: its points are the face points of its surface with the points of glued edges
//! merged, numbered in the order in which they first occur (face by face, each face's points in
//! the order of its face type, read through the step's frame). The sub-volume operators
//! `V<v>.T<k>` are the unknowns. The checker derives the sub-volumes of every volume type with its
//! own code (`volume.rs`, the faces subdivided in the frames of their types), matches each with
//! the step's placement by the sub-faces it stands on, and proves the placement is an
//! isomorphism onto the listed type by propagating it through the gluing. Rows: the incidences
//! `B_f · T_j^t = T_k · B_g · R` of the sub-faces, the adjacency `T_a · B_g · P = T_b · B_h` of
//! the two side faces over every spoke edge, and the barycentric columns of every `V<v>.T<k>`.
//!
//! The witness: a particular solution and a basis (each 1 at its own free unknown, 0 at the
//! other free ones) satisfy the rebuilt rows exactly over Q, so the solution set contains
//! particular + span(basis) and the nullity is at least dof; the columns that are not free are
//! shown independent by elimination modulo a prime (a rank over F_p is at most the rank over Q),
//! so a kernel vector vanishing at the free unknowns vanishes: the nullity is at most dof.

use super::closure::{check_closure, least_rotation};
use super::system::rebuild_ordered;
use super::volume::{face_key, pieces, traced, Prov, Side};
use super::volume_points::{level1, placement, points, Faces, Points};
use super::{Checked, Equation, Q};
use crate::certificate::{Origin, VolumeClosureStep, VolumeSystemStep, VolumesClaim};
use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{One, ToPrimitive, Zero};
use std::collections::{BTreeMap, BTreeSet, HashMap};

/// The rebuilt rows, growing; unknowns as column indices.
struct Rows {
    rows: Vec<Equation>,
}

impl Rows {
    fn push(&mut self, terms: Vec<(usize, Q)>, rhs: Q) {
        self.rows.push((terms, rhs));
    }
}

/// Checks the `volume-solution-space` step: the system rebuilt from the proved volume closure,
/// and the solution space against it.
pub(super) fn check_volume_system(
    s: &VolumeSystemStep,
    closure: Option<&VolumeClosureStep>,
    claim: &VolumesClaim,
) -> Checked {
    let Some(vc) = closure else {
        return Err("no proved volume-closure step to tie the system to".into());
    };
    let n = s.unknowns;
    if s.rank.checked_add(s.dof) != Some(n) || s.dof != s.free.len() || s.basis.len() != s.dof {
        return Err(format!(
            "rank {} + dof {} (|free| = {}, {} basis vectors) ≠ {n} unknowns",
            s.rank,
            s.dof,
            s.free.len(),
            s.basis.len()
        ));
    }
    let nv = vc.types.len();
    if s.frames.len() != nv || s.subvolumes.len() != nv {
        return Err(format!(
            "{} frame lists and {} placement lists for {nv} volume types",
            s.frames.len(),
            s.subvolumes.len()
        ));
    }
    // The face closure of the surfaces: its start faces are the surface faces' types, volume
    // by volume, face by face.
    let mut starts = Vec::new();
    for (v, fr) in s.frames.iter().enumerate() {
        for &(t, _) in fr {
            let rule = s
                .faces
                .types
                .get(t)
                .ok_or(format!("volume type {v}: face type {t} is not listed"))?;
            starts.push(rule.face.clone());
        }
    }
    let (closure_msg, _, _) =
        check_closure(&s.faces, &starts).map_err(|e| format!("the face closure: {e}"))?;
    let closure_msg = closure_msg.replace("the claim's ", "the surfaces' ");
    let (lay, mut face_rows) = rebuild_ordered(
        &s.faces,
        (s.degree, &s.cantor_gap),
        None,
        u128::from(u32::MAX),
    )
    .map_err(|e| format!("the face system: {e}"))?;
    let faces = Faces {
        c: &s.faces,
        q: s.degree,
        dims: lay.dims.clone(),
        offsets: lay.offsets.clone(),
        base: lay.base.clone(),
    };
    let face_unknowns = lay.names.len();
    drop(lay);
    let pts: Vec<Points> = vc
        .types
        .iter()
        .zip(&s.frames)
        .enumerate()
        .map(|(v, (ty, fr))| {
            points(&ty.volume, fr, &faces).map_err(|e| format!("volume type {v}: {e}"))
        })
        .collect::<Result<_, _>>()?;
    // The sub-volume operators' unknowns, counted before anything of their size is built.
    let mut op_base: Vec<Vec<usize>> = Vec::with_capacity(nv);
    let mut count = face_unknowns;
    for (v, list) in s.subvolumes.iter().enumerate() {
        let mut bs = Vec::with_capacity(list.len());
        for p in list {
            let w = pts.get(p.type_index).ok_or(format!(
                "volume type {v}: a sub-volume type is out of range"
            ))?;
            bs.push(count);
            count = pts[v]
                .m
                .checked_mul(w.m)
                .and_then(|x| count.checked_add(x))
                .ok_or("the number of unknowns overflows")?;
        }
        op_base.push(bs);
    }
    if count != n {
        return Err(format!(
            "the step names {n} unknowns, the rebuilt system has {count}"
        ));
    }
    super::within_work("the rows of the volume system", 4 * count as u128)?;
    let mut rows = Rows {
        rows: std::mem::take(&mut face_rows),
    };
    let face_rows_count = rows.rows.len();
    let mut placed = 0usize;
    for (v, ty) in vc.types.iter().enumerate() {
        let volume = &ty.volume;
        let l1 =
            level1(volume, &s.frames[v], &faces).map_err(|e| format!("volume type {v}: {e}"))?;
        let (l1, derived) = traced(volume, l1).map_err(|e| format!("volume type {v}: {e}"))?;
        let list = &s.subvolumes[v];
        if derived.len() != list.len() {
            return Err(format!(
                "volume type {v}: {} sub-volumes derived, {} placed",
                derived.len(),
                list.len()
            ));
        }
        let mut listed_children: Vec<usize> = list.iter().map(|p| p.type_index).collect();
        let mut children = ty.children.clone();
        listed_children.sort_unstable();
        children.sort_unstable();
        if listed_children != children {
            return Err(format!(
                "volume type {v}: the placed sub-volumes are not the closure's children"
            ));
        }
        // Each derived sub-volume is the placement standing on the same sub-faces.
        let key = |subs: &mut dyn Iterator<Item = (usize, usize)>| -> Vec<(usize, usize)> {
            let mut k: Vec<(usize, usize)> = subs.collect();
            k.sort_unstable();
            k
        };
        let by_subfaces: HashMap<Vec<(usize, usize)>, usize> = list
            .iter()
            .enumerate()
            .map(|(k, p)| (key(&mut p.subfaces.iter().map(|x| x.0)), k))
            .collect();
        let pv = &pts[v];
        // (sub-volume, its face) of the side face over each rim side.
        let mut side_face: HashMap<Side, (usize, usize)> = HashMap::new();
        let mut maps: Vec<Vec<(usize, usize)>> = vec![Vec::new(); list.len()];
        for (d, prov) in &derived {
            let mine = key(&mut prov.iter().filter_map(|p| match p {
                Prov::Sub(f, j) => Some((*f, *j)),
                _ => None,
            }));
            let &k = by_subfaces.get(&mine).ok_or(format!(
                "volume type {v}: a derived sub-volume has no placement"
            ))?;
            if !maps[k].is_empty() {
                return Err(format!(
                    "volume type {v}: placement {k} matches two sub-volumes"
                ));
            }
            let p = &list[k];
            let w = p.type_index;
            let map = placement(d, prov, p, &vc.types[w].volume, &s.frames[w], &faces)
                .map_err(|e| format!("volume type {v} sub-volume {k}: {e}"))?;
            let pw = &pts[w];
            for (i, pr) in prov.iter().enumerate() {
                let (g, rot) = map[i];
                match *pr {
                    Prov::Sub(f, j) => {
                        // B_f · T_j^t = T_k · B_g · R(rot), entry by entry.
                        let (t, _) = s.frames[v][f];
                        let u = s.faces.types[t].subfaces[j].type_index;
                        if s.frames[w][g].0 != u {
                            return Err(format!(
                                "volume type {v} sub-volume {k}: face {g} of type {w} is not of \
                                 the sub-face's type {u}"
                            ));
                        }
                        let (mt, mu) = (faces.dims[t], faces.dims[u]);
                        let row_of = faces.turn(u, rot);
                        let mut on: Vec<Vec<usize>> = vec![Vec::new(); pv.m];
                        (0..mt).for_each(|p| on[pv.ids[pv.base[f] + p]].push(p));
                        let fb = faces.base[t][j];
                        for (r, ps) in on.iter().enumerate() {
                            for (c, &rc) in row_of.iter().enumerate() {
                                let mut terms: Vec<(usize, Q)> =
                                    ps.iter().map(|&p| (fb + p * mu + c, Q::one())).collect();
                                let col = pw.ids[pw.base[g] + rc];
                                terms.push((op_base[v][k] + r * pw.m + col, -Q::one()));
                                rows.push(terms, Q::zero());
                            }
                        }
                    }
                    Prov::Side(side) => {
                        side_face.insert(side, (k, i));
                    }
                    Prov::Inner => {}
                }
            }
            maps[k] = map;
            placed += 1;
        }
        // The two side faces over every spoke edge are one face read both ways.
        let mut pairs: Vec<(Side, Side)> = side_face
            .keys()
            .filter_map(|s| l1.partner.get(s).map(|t| (*s, *t)))
            .filter(|(s, t)| s < t && side_face.contains_key(t))
            .collect();
        pairs.sort_unstable();
        for (sa, sb) in pairs {
            let ((ka, ia), (kb, ib)) = (side_face[&sa], side_face[&sb]);
            let ((ga, ra), (gb, rb)) = (maps[ka][ia], maps[kb][ib]);
            let (wa, wb) = (list[ka].type_index, list[kb].type_index);
            let (ta, tb) = (s.frames[wa][ga].0, s.frames[wb][gb].0);
            let nn = faces.face(ta)?.boundary.len();
            // Built edge e of one side face lies on built edge −e of the other, run backwards.
            let x = (2 * nn - ra % nn - rb % nn) % nn;
            let row_of = faces
                .reversed(ta, tb, x)
                .map_err(|e| format!("volume type {v}: a spoke face: {e}"))?;
            let (pa, pb) = (&pts[wa], &pts[wb]);
            for r in 0..pv.m {
                for (c, &rc) in row_of.iter().enumerate() {
                    let left = op_base[v][ka] + r * pa.m + pa.ids[pa.base[ga] + rc];
                    let right = op_base[v][kb] + r * pb.m + pb.ids[pb.base[gb] + c];
                    rows.push(vec![(left, Q::one()), (right, -Q::one())], Q::zero());
                }
            }
        }
        // Every column of every sub-volume operator sums to 1.
        for (k, p) in list.iter().enumerate() {
            let mw = pts[p.type_index].m;
            for c in 0..mw {
                let terms = (0..pv.m)
                    .map(|r| (op_base[v][k] + r * mw + c, Q::one()))
                    .collect();
                rows.push(terms, Q::one());
            }
        }
    }
    let before = rows.rows.len();
    shared_faces(claim, &faces, &mut rows)?;
    let mirrored = rows.rows.len() - before;
    let rows = rows.rows;
    let (rank_p, p) = witness(s, &rows)?;
    Ok((
        format!(
            "{closure_msg}; {} frames and {placed} sub-volume \
             placements proved (isomorphisms onto the listed types through the gluing); system \
             rebuilt from the closures: {} rows over {n} unknowns ({} of face operators, THEORY \
             §6, Bézier degree {}, Cantor gap/piece {}; {} rows of volume states{}, THEORY \
             §10); \
             the particular solution and the {} basis vectors satisfy every row; rank {rank_p} \
             (the unknowns that are not free independent mod {p}), {} degrees of freedom; the \
             solution set is exactly particular + span(basis)",
            s.frames.iter().map(Vec::len).sum::<usize>(),
            rows.len(),
            face_unknowns,
            s.degree,
            s.cantor_gap,
            rows.len() - face_rows_count - mirrored,
            match claim.shared.len() {
                0 => String::new(),
                k => format!(
                    " and {mirrored} of {} shared by the start volumes, read from both sides",
                    super::counted(k, "face", "faces")
                ),
            },
            s.basis.len(),
            s.dof
        ),
        format!(
            "volume constraints: consistent, {n} unknowns, rank {}, {} degrees of freedom",
            s.rank, s.dof
        ),
    ))
}

/// The rows of the faces the claim's start volumes share (THEORY §10): a face read from both
/// sides is one face, so its sub-faces from either side are the same polygons at every level.
/// For the face types `t1`, `t2` of the two readings, edge `i` of `t2` on edge `x − i` of `t1`
/// run backwards: `P · T2_k' = T1_k · Q` for every sub-face `k` of `t1` and its mirror `k'`
/// (the sub-face of `t2` made of the mirrored pieces), `P` and `Q` reading the points of one
/// frame in the other; then the same for the pair of sub-face types, until no new pair appears.
fn shared_faces(claim: &VolumesClaim, faces: &Faces, rows: &mut Rows) -> Result<(), String> {
    if claim.shared.is_empty() {
        return Ok(());
    }
    let index: HashMap<_, usize> = faces
        .c
        .types
        .iter()
        .enumerate()
        .map(|(t, r)| (face_key(&r.face, 0), t))
        .collect();
    let reading = |[v, f, e]: [usize; 3]| -> Result<(usize, usize, usize, usize), String> {
        let face = claim
            .volumes
            .get(v)
            .and_then(|x| x.faces.get(f))
            .ok_or(format!("shared face ({v}, {f}) is not a face of the claim"))?;
        let n = face.boundary.len();
        let r = least_rotation(&face.boundary);
        let t = *index
            .get(&face_key(face, r))
            .ok_or(format!("shared face ({v}, {f}) is not a listed face type"))?;
        Ok((t, r, e, n))
    };
    let mut work = Vec::new();
    for sh in &claim.shared {
        let (ta, ra, ea, n) = reading(sh.a)?;
        let (tb, rb, eb, _) = reading(sh.b)?;
        // Edge i of type ta is edge i + ra of a's reading, which lies on edge eb − (i + ra − ea)
        // of b's reading, which is edge (that − rb) of type tb.
        work.push((ta, tb, (ea + eb + 2 * n - ra % n - rb % n) % n));
    }
    let mut seen = BTreeSet::new();
    while let Some((t1, t2, x)) = work.pop() {
        if !seen.insert((t1.min(t2), t1.max(t2), x)) {
            continue;
        }
        let row_of = faces.reversed(t1, t2, x)?;
        let mut inverse = vec![0usize; row_of.len()];
        row_of.iter().enumerate().for_each(|(j, &r)| inverse[r] = j);
        let (y1, y2) = (&faces.c.types[t1], &faces.c.types[t2]);
        let n = y1.face.boundary.len();
        let pieces_of = |o: &[Origin]| -> Vec<(usize, usize, usize)> {
            o.iter()
                .enumerate()
                .filter_map(|(l, o)| match *o {
                    Origin::Piece { edge, piece } => Some((edge, piece, l)),
                    _ => None,
                })
                .collect()
        };
        for (k1, sub1) in y1.subfaces.iter().enumerate() {
            let mine = pieces_of(&sub1.origins);
            let mirror = |e: usize, p: usize| {
                let count = pieces(&y1.face.boundary[e]);
                ((x + n - e % n) % n, count - 1 - p)
            };
            let mut want: Vec<(usize, usize)> =
                mine.iter().map(|&(e, p, _)| mirror(e, p)).collect();
            want.sort_unstable();
            let found = y2.subfaces.iter().position(|s2| {
                let mut got: Vec<(usize, usize)> = pieces_of(&s2.origins)
                    .iter()
                    .map(|&(e, p, _)| (e, p))
                    .collect();
                got.sort_unstable();
                got == want
            });
            let (Some(k2), Some(&(e, pc, l1))) = (found, mine.first()) else {
                return Err(format!(
                    "sub-face {k1} of face type {t1} has no mirror in face type {t2}"
                ));
            };
            let sub2 = &y2.subfaces[k2];
            let m = mirror(e, pc);
            let l2 = pieces_of(&sub2.origins)
                .iter()
                .find(|&&(e2, p2, _)| (e2, p2) == m)
                .map(|&(_, _, l)| l)
                .ok_or("a mirrored piece is missing")?;
            let xk = (l1 + l2) % sub1.origins.len().max(1);
            let (w1, w2) = (sub1.type_index, sub2.type_index);
            let q_rows = faces.reversed(w1, w2, xk)?;
            let (m1, mw1, mw2) = (faces.dims[t1], faces.dims[w1], faces.dims[w2]);
            let (b1, b2) = (faces.base[t1][k1], faces.base[t2][k2]);
            super::within_work("the rows of shared faces", (m1 * mw2) as u128)?;
            for (r, &j) in inverse.iter().enumerate() {
                for (c, &qc) in q_rows.iter().enumerate() {
                    rows.push(
                        vec![(b2 + j * mw2 + c, Q::one()), (b1 + r * mw1 + qc, -Q::one())],
                        Q::zero(),
                    );
                }
            }
            work.push((w1, w2, xk));
        }
    }
    Ok(())
}

/// Checks the particular solution and the basis against `rows`, then that the columns that are
/// not free are independent modulo a prime. Returns the rank shown and the prime.
fn witness(s: &VolumeSystemStep, rows: &[Equation]) -> Result<(usize, u64), String> {
    let n = s.unknowns;
    super::linear::satisfies(rows, n, &s.particular, &s.free, &s.basis)?;
    let mut free_at: Vec<Option<usize>> = vec![None; n];
    s.free
        .iter()
        .enumerate()
        .for_each(|(j, &f)| free_at[f] = Some(j));
    let want = n - s.dof;
    let mut why = String::new();
    for p in [(1u64 << 61) - 1, 1_000_000_007, 998_244_353] {
        match independent(rows, &free_at, p)? {
            Some(r) if r == want => return Ok((r, p)),
            Some(r) => why = format!("rank {r} mod {p} for {want} unknowns that are not free"),
            None => why = format!("a denominator is divisible by {p}"),
        }
    }
    Err(format!(
        "the unknowns that are not free are not shown independent: {why}"
    ))
}

/// The rank modulo `p` of the rows restricted to the columns that are not free, by an echelon
/// basis keyed by each row's least column (metered as it goes); `None` when a denominator
/// vanishes modulo `p`.
fn independent(
    rows: &[Equation],
    free_at: &[Option<usize>],
    p: u64,
) -> Result<Option<usize>, String> {
    let mul = |a: u64, b: u64| ((u128::from(a) * u128::from(b)) % u128::from(p)) as u64;
    let inv = |a: u64| {
        let (mut r, mut b, mut e) = (1u64, a, p - 2);
        while e > 0 {
            if e & 1 == 1 {
                r = mul(r, b);
            }
            b = mul(b, b);
            e >>= 1;
        }
        r
    };
    let modp = |z: &BigInt| z.mod_floor(&BigInt::from(p)).to_u64().unwrap_or(0);
    // Pivot rows by leading column, normalised to 1 there.
    let mut pivot: HashMap<usize, Vec<(usize, u64)>> = HashMap::new();
    for (terms, _) in rows {
        let mut row: BTreeMap<usize, u64> = BTreeMap::new();
        for (v, c) in terms {
            if free_at[*v].is_some() {
                continue;
            }
            let d = modp(c.denom());
            if d == 0 {
                return Ok(None);
            }
            let e = row.entry(*v).or_insert(0);
            *e = (*e + mul(modp(c.numer()), inv(d))) % p;
        }
        row.retain(|_, x| *x != 0);
        while let Some((&lead, &x)) = row.first_key_value() {
            match pivot.get(&lead) {
                Some(prow) => {
                    super::within_work(
                        "the independence of the pivot columns",
                        4 * prow.len() as u128,
                    )?;
                    for &(l, y) in prow {
                        let e = row.entry(l).or_insert(0);
                        *e = (*e + p - mul(x, y)) % p;
                    }
                    row.retain(|_, x| *x != 0);
                }
                None => {
                    let xi = inv(x);
                    pivot.insert(lead, row.iter().map(|(&l, &y)| (l, mul(y, xi))).collect());
                    break;
                }
            }
        }
    }
    Ok(Some(pivot.len()))
}
