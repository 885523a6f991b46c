//! The solid-recurrence step (THEORY §10): the cells, χ and components of the level-n solid at
//! every claimed level, by the recurrence of cells by birth (see `docs/CERTIFICATES.md`).
//!
//! **Cells by birth.** The complex of `solid.rs` is built one level from the next, and every
//! cell it creates is created inside one cell of the level before: the pieces of an edge and
//! the corners between them inside the edge; the sub-faces, the spokes, lacuna and gap sides
//! and the lacuna corners and gap points inside a face; the sub-volumes, side and inner faces,
//! radial and inner edges and inner corners inside a volume. What a cell creates depends only
//! on its type: an edge on its own type, a face on its type up to rotation (the subdivision is
//! read around its cycle), a volume on its volume type (the closure step identifies sub-volumes
//! by type on the same ground). The counts of each type at level n + 1 are therefore a linear
//! function of those at level n.
//!
//! **The birth table, derived here.** The checker does not read a birth table: it builds one
//! step of small complexes with the code of `solid-homology` and reads what is new in them.
//! - A volume type: its own level-0 complex K (the volume and its surface) and the same
//!   without the volume, S. One step of S is a prefix of one step of K (the same edges' pieces
//!   and the same faces' subdivisions, in the same order), so the faces and edges of step(K)
//!   past that prefix are born in the volume, and so are the corners of step(K) that hold no end
//!   of a prefix edge. The corners of step(S) must be exactly the classes those prefix ends
//!   fall in (the inside glues no two of them). The sub-volumes are the proved closure's
//!   children.
//! - A face type (at its least rotation): its own complex, its sides distinct edges. One step
//!   gives its sub-faces and, past its sides' pieces, the edges born inside it. A corner class
//!   holding an outer end of a side's pieces is one of the face's own corners; one holding an
//!   inner end of one side's pieces (and no outer end) is born in that side's edge; the rest are
//!   born in the face.
//! - An edge type: its pieces (`piece_type`) and the corners born in it, read in every face that
//!   has it as a side; all readings must agree.
//!
//! **Components.** When every volume type's level-1 complex is connected (one class of corners
//! under its edges), every level has the components of level 0: the children of a volume fill
//! a connected set, and two cells of level n that meet still meet at level n + 1 through the
//! subdivision of a cell they share (a corner stays a corner, an edge keeps its ends).

use super::closure::{least_rotation, piece_type};
use super::face_homology::start_face;
use super::ranks::{betti, rank_f2};
use super::solid::{next, start, Complex, Parity};
use super::volume::{checked_key, face_key, one_per_level, FaceKey, TypeKey};
use crate::certificate::{
    Edge, Face, SolidRecurrenceStep, Volume, VolumeClosureStep, VolumesClaim,
};
use num_bigint::{BigInt, BigUint};
use num_traits::Zero;
use std::collections::HashMap;

#[cfg(test)]
use super::volume::tests as volume_tests;

/// What one cell of a type creates inside itself: faces and edges by index into the
/// registries, and a number of corners.
#[derive(Clone, Default)]
struct Birth {
    faces: Vec<usize>,
    edges: Vec<usize>,
    corners: u64,
}

/// The face and edge types met, with what each creates.
#[derive(Default)]
struct Table {
    faces: Vec<Face>,
    face_index: HashMap<FaceKey, usize>,
    face_birth: Vec<Option<Birth>>,
    edges: Vec<Edge>,
    edge_index: HashMap<Edge, usize>,
    /// Pieces of each edge type, and the corners born in it once a face has shown them.
    edge_birth: Vec<(Vec<usize>, Option<u64>)>,
    /// Whether some face type has a set of sub-faces whose boundary lies on its sides only (a
    /// 2-cycle of the subdivided faces may then exist: no voids derived).
    sealed: bool,
}

/// Most face and edge types the recurrence may meet.
const MAX_TYPES: usize = 100_000;

impl Table {
    fn edge(&mut self, e: Edge) -> Result<usize, String> {
        if let Some(&i) = self.edge_index.get(&e) {
            return Ok(i);
        }
        if self.edges.len() >= MAX_TYPES {
            return Err(format!("more than {MAX_TYPES} edge types"));
        }
        let i = self.edges.len();
        self.edges.push(e);
        self.edge_index.insert(e, i);
        self.edge_birth.push((Vec::new(), None));
        let (count, ty) = piece_type(&e);
        let piece = self.edge(ty)?;
        self.edge_birth[i].0 = vec![piece; count];
        Ok(i)
    }

    /// The index of a face's type (its least rotation), registered when new.
    fn face(&mut self, f: &Face) -> Result<usize, String> {
        let r = least_rotation(&f.boundary);
        let key = face_key(f, r);
        if let Some(&i) = self.face_index.get(&key) {
            return Ok(i);
        }
        if self.faces.len() >= MAX_TYPES {
            return Err(format!("more than {MAX_TYPES} face types"));
        }
        let mut boundary = f.boundary.clone();
        boundary.rotate_left(r);
        self.faces.push(Face {
            boundary,
            ..f.clone()
        });
        self.face_index.insert(key, self.faces.len() - 1);
        self.face_birth.push(None);
        Ok(self.faces.len() - 1)
    }

    /// Records that an edge type creates `corners` corners; every reading must agree.
    fn edge_corners(&mut self, e: usize, corners: u64) -> Result<(), String> {
        match self.edge_birth[e].1.replace(corners) {
            Some(c) if c != corners => Err(format!(
                "edge type {:?} creates {c} corners inside one face and {corners} inside another",
                self.edges[e]
            )),
            _ => Ok(()),
        }
    }

    /// Derives what face type `i` creates (see the module documentation).
    fn derive_face(&mut self, i: usize) -> Result<(), String> {
        let face = self.faces[i].clone();
        let sides = face.boundary.len() as u128;
        super::within_work(
            "the birth table of the solid's face types",
            sides * sides + 64,
        )?;
        let k = start_face(&face)?;
        let old_corners = k.corners().1;
        let n = next(&k).map_err(|e| format!("face type {:?}: {e}", face.boundary))?;
        let mut spans = Vec::with_capacity(face.boundary.len());
        let mut b = 0usize;
        for e in &face.boundary {
            let (count, _) = piece_type(e);
            spans.push((b, count));
            b += count;
        }
        if n.edges.len() < b {
            return Err("a face's subdivision has fewer edges than its sides' pieces".into());
        }
        let (corner, total) = n.corners();
        // The class of each corner: an outer end (the face's own corner), an inner end of one
        // side's pieces, or neither.
        #[derive(Clone, Copy, PartialEq)]
        enum Class {
            Born,
            Own,
            Side(usize),
        }
        let mut class = vec![Class::Born; total];
        for (s, &(b, count)) in spans.iter().enumerate() {
            for p in 0..count {
                for (end, x) in [(0, 2 * (b + p)), (1, 2 * (b + p) + 1)] {
                    let outer = (p == 0 && end == 0) || (p + 1 == count && end == 1);
                    let c = corner[x];
                    class[c] = match (class[c], outer) {
                        (_, true) | (Class::Own, _) => Class::Own,
                        (Class::Born, false) => Class::Side(s),
                        (Class::Side(t), false) if t == s => Class::Side(s),
                        (Class::Side(_), false) => {
                            return Err(format!(
                                "face type {:?}: one corner is inside two of its sides",
                                face.boundary
                            ))
                        }
                    };
                }
            }
        }
        let own = class.iter().filter(|&&c| c == Class::Own).count();
        if own != old_corners {
            return Err(format!(
                "face type {:?}: {own} corners hold an end of a side, the face has {old_corners}",
                face.boundary
            ));
        }
        let mut per_side = vec![0u64; spans.len()];
        for c in &class {
            if let Class::Side(s) = c {
                per_side[*s] += 1;
            }
        }
        for (s, &count) in per_side.iter().enumerate() {
            let e = self.edge(face.boundary[s])?;
            self.edge_corners(e, count)?;
        }
        // No set of sub-faces has its boundary on the face's sides only: the columns of ∂2
        // restricted to the edges born inside are independent over F2.
        let inside: Vec<Vec<usize>> = n
            .faces
            .iter()
            .map(|f| f.bnd.iter().map(|r| r.0).filter(|&e| e >= b).collect())
            .collect();
        if rank_f2(inside)? != n.faces.len() {
            self.sealed = true;
        }
        let born = class.iter().filter(|&&c| c == Class::Born).count() as u64;
        let faces = n
            .faces
            .iter()
            .map(|f| self.face(&f.ty))
            .collect::<Result<Vec<_>, _>>()?;
        let edges = n.edges[b..]
            .iter()
            .map(|&e| self.edge(e))
            .collect::<Result<Vec<_>, _>>()?;
        self.face_birth[i] = Some(Birth {
            faces,
            edges,
            corners: born,
        });
        Ok(())
    }
}

/// The number of classes of corners joined by the complex's edges (b0), for a complex whose
/// corners are `corner` (every edge end's class) and `n` many.
fn components(c: &Complex, corner: &[usize], n: usize) -> usize {
    let mut dsu = Parity::new(n);
    for e in 0..c.edges.len() {
        let _ = dsu.union(corner[2 * e], corner[2 * e + 1], false);
    }
    (0..n).filter(|&x| dsu.find(x).0 == x).count()
}

/// What a volume type creates inside itself, its number of sub-volumes, whether its level-1
/// complex is connected, and whether that complex relative to its subdivided surface has no
/// homology in degrees 2 and 3 over F2.
fn derive_volume(v: &Volume, table: &mut Table) -> Result<(Birth, usize, bool, bool), String> {
    let single = VolumesClaim {
        volumes: vec![v.clone()],
        levels: 0,
        shared: Vec::new(),
    };
    let k = start(&single)?;
    let s = k.surface();
    let nk = next(&k)?;
    let ns = next(&s)?;
    let prefix = ns.edges.len() <= nk.edges.len()
        && ns.faces.len() <= nk.faces.len()
        && ns.edges[..] == nk.edges[..ns.edges.len()]
        && ns.faces.iter().zip(&nk.faces).all(|(a, b)| a.ty == b.ty);
    if !prefix {
        return Err(
            "one step of the surface alone is not a prefix of one step of the volume".into(),
        );
    }
    let (corner, total) = nk.corners();
    let mut surface_class: Vec<usize> = corner[..2 * ns.edges.len()].to_vec();
    surface_class.sort_unstable();
    surface_class.dedup();
    let surface_corners = ns.corners().1;
    if surface_class.len() != surface_corners {
        return Err(format!(
            "the inside of the volume joins corners of its subdivided surface ({} classes there, \
             {surface_corners} on the surface alone)",
            surface_class.len()
        ));
    }
    let faces = nk.faces[ns.faces.len()..]
        .iter()
        .map(|f| table.face(&f.ty))
        .collect::<Result<Vec<_>, _>>()?;
    let edges = nk.edges[ns.edges.len()..]
        .iter()
        .map(|&e| table.edge(e))
        .collect::<Result<Vec<_>, _>>()?;
    let connected = components(&nk, &corner, total) == 1;
    // The complex relative to the subdivided surface: the cells past the prefix. Its H2 and H3
    // over F2 are 0 when ∂3 (sub-volumes → inner faces) is injective and every relative 2-cycle
    // of inner faces is a boundary of sub-volumes.
    let (fp, ep) = (ns.faces.len(), ns.edges.len());
    let d3: Vec<Vec<usize>> = nk
        .vols
        .iter()
        .map(|v| v.faces.iter().map(|f| f.0).filter(|&g| g >= fp).collect())
        .collect();
    let d2: Vec<Vec<usize>> = nk.faces[fp..]
        .iter()
        .map(|f| f.bnd.iter().map(|r| r.0).filter(|&e| e >= ep).collect())
        .collect();
    let (r3, r2) = (rank_f2(d3)?, rank_f2(d2)?);
    let open = r3 == nk.vols.len() && nk.faces.len() - fp == r2 + r3;
    Ok((
        Birth {
            faces,
            edges,
            corners: (total - surface_class.len()) as u64,
        },
        nk.vols.len(),
        connected,
        open,
    ))
}

/// Checks the solid-recurrence step against the proved volume closure and the claim.
pub(super) fn check_solid_recurrence(
    s: &SolidRecurrenceStep,
    closure: Option<&VolumeClosureStep>,
    claim: &VolumesClaim,
) -> Result<(String, String), String> {
    let closure = closure.ok_or("no proved volume-closure step to take the volume types from")?;
    one_per_level(s.rows.len(), claim.levels, "rows")?;
    if let Some((i, r)) = s
        .rows
        .iter()
        .enumerate()
        .find(|(i, r)| r.level != *i as u64)
    {
        return Err(format!("row {i} is for level {}", r.level));
    }
    let mut index: HashMap<TypeKey, usize> = HashMap::new();
    for (t, rule) in closure.types.iter().enumerate() {
        index.insert(
            checked_key(&rule.volume).map_err(|e| format!("type {t}: {e}"))?,
            t,
        );
    }
    // The birth table.
    let mut table = Table::default();
    let mut vol_birth = Vec::with_capacity(closure.types.len());
    let mut all_connected = true;
    let mut all_open = true;
    for (t, rule) in closure.types.iter().enumerate() {
        let (birth, subvolumes, connected, open) =
            derive_volume(&rule.volume, &mut table).map_err(|e| format!("volume type {t}: {e}"))?;
        if subvolumes != rule.children.len() {
            return Err(format!(
                "volume type {t}: its complex has {subvolumes} sub-volumes, the closure lists {}",
                rule.children.len()
            ));
        }
        all_connected &= connected;
        all_open &= open;
        vol_birth.push(birth);
    }
    // Level 0: the complex of the claim's volumes.
    let c0 = start(claim)?;
    let mut vol = vec![BigUint::zero(); closure.types.len()];
    for (i, v) in claim.volumes.iter().enumerate() {
        let key = checked_key(v).map_err(|e| format!("start volume {i}: {e}"))?;
        let t = *index
            .get(&key)
            .ok_or_else(|| format!("start volume {i} is not a listed type"))?;
        vol[t] += 1u32;
    }
    let mut fac: Vec<BigUint> = Vec::new();
    let mut edg: Vec<BigUint> = Vec::new();
    let add = |v: &mut Vec<BigUint>, i: usize, k: &BigUint| {
        if v.len() <= i {
            v.resize(i + 1, BigUint::zero());
        }
        v[i] += k;
    };
    let one = BigUint::from(1u32);
    for f in &c0.faces {
        let i = table.face(&f.ty)?;
        add(&mut fac, i, &one);
    }
    for &e in &c0.edges {
        let i = table.edge(e)?;
        add(&mut edg, i, &one);
    }
    let (corner0, n0) = c0.corners();
    let b0 = components(&c0, &corner0, n0) as u64;
    // Level 0 without cavities, over F2 (the solid-homology code refuses b2 or b3 ≠ 0).
    let level0_open = betti(&c0, 0).is_ok();
    let mut corners = BigUint::from(n0);
    // Every face type met, derived (deriving one may meet more).
    let mut i = 0;
    while i < table.faces.len() {
        table.derive_face(i)?;
        i += 1;
    }
    if let Some(e) = (0..table.edges.len()).find(|&e| table.edge_birth[e].1.is_none()) {
        return Err(format!(
            "edge type {:?} is a side of no face type: the corners born in it are not derived",
            table.edges[e]
        ));
    }
    let mut lines = Vec::new();
    for (level, row) in s.rows.iter().enumerate() {
        let sum = |v: &[BigUint]| v.iter().sum::<BigUint>();
        let (nv, nf, ne) = (sum(&vol), sum(&fac), sum(&edg));
        let euler = BigInt::from(corners.clone()) - BigInt::from(ne.clone())
            + BigInt::from(nf.clone())
            - BigInt::from(nv.clone());
        let got = [
            ("volumes", nv.to_string(), &row.volumes),
            ("faces", nf.to_string(), &row.faces),
            ("edges", ne.to_string(), &row.edges),
            ("corners", corners.to_string(), &row.corners),
            ("χ", euler.to_string(), &row.euler),
        ];
        for (what, derived, said) in &got {
            if derived != *said {
                return Err(format!(
                    "level {level}: re-derived {derived} {what}; the row says {said}"
                ));
            }
        }
        if let Some(c) = row.components {
            if !all_connected {
                return Err(format!(
                    "level {level}: components claimed, but a volume type's level-1 complex is \
                     not connected, so they are not derived"
                ));
            }
            if c != b0 {
                return Err(format!(
                    "level {level}: {c} components claimed; level 0 has {b0}, and every level \
                     keeps them"
                ));
            }
        }
        let voids_derived = match level {
            0 => level0_open,
            _ => all_open && !table.sealed,
        };
        if let Some(v) = row.voids {
            if !voids_derived || v != 0 {
                return Err(format!(
                    "level {level}: {} claimed; {}",
                    super::counted(v, "void", "voids"),
                    match voids_derived {
                        true => "the premises hold, and the level has none",
                        false => "the premises that derive voids do not hold",
                    }
                ));
            }
        }
        if let Some(t) = &row.tunnels {
            let derived = match (row.components, row.voids) {
                (Some(b0), Some(b2)) => (BigInt::from(b0) + BigInt::from(b2) - &euler).to_string(),
                _ => {
                    return Err(format!(
                        "level {level}: tunnels claimed without components and voids"
                    ))
                }
            };
            if *t != derived {
                return Err(format!(
                    "level {level}: {t} tunnels claimed; b0 + b2 − χ = {derived}"
                ));
            }
        }
        if level + 1 == s.rows.len() || level < 2 {
            lines.push(format!(
                "level {level}: {}, {}, {}, {}, χ = {}{}",
                super::counted(&nv, "volume", "volumes"),
                super::counted(&nf, "face", "faces"),
                super::counted(&ne, "edge", "edges"),
                super::counted(&corners, "corner", "corners"),
                euler,
                match row.components {
                    Some(c) => format!(", {}", super::counted(c, "component", "components")),
                    None => String::new(),
                } + &match (&row.voids, &row.tunnels) {
                    (Some(v), Some(t)) => format!(
                        ", {}, {}",
                        super::counted(v, "void", "voids"),
                        super::counted(t, "tunnel", "tunnels")
                    ),
                    (Some(v), None) => format!(", {}", super::counted(v, "void", "voids")),
                    _ => String::new(),
                }
            ));
        }
        if level + 1 == s.rows.len() {
            break;
        }
        let bits: u128 = (nf.bits() + ne.bits() + nv.bits() + 64).into();
        let size = (table.faces.len() + table.edges.len() + vol.len()) as u128;
        super::within_work("the recurrence of the solid's cells", bits * size / 32 + 1)?;
        // One level down.
        let mut nvol = vec![BigUint::zero(); vol.len()];
        let mut nfac = vec![BigUint::zero(); table.faces.len()];
        let mut nedg = vec![BigUint::zero(); table.edges.len()];
        let mut ncor = corners.clone();
        for (t, k) in vol.iter().enumerate().filter(|(_, k)| !k.is_zero()) {
            for &ch in &closure.types[t].children {
                *nvol
                    .get_mut(ch)
                    .ok_or("a child that is not a listed type")? += k;
            }
            let b = &vol_birth[t];
            b.faces.iter().for_each(|&x| nfac[x] += k);
            b.edges.iter().for_each(|&x| nedg[x] += k);
            ncor += k * b.corners;
        }
        for (f, k) in fac.iter().enumerate().filter(|(_, k)| !k.is_zero()) {
            let b = table.face_birth[f]
                .as_ref()
                .ok_or("a face type without its birth")?;
            b.faces.iter().for_each(|&x| nfac[x] += k);
            b.edges.iter().for_each(|&x| nedg[x] += k);
            ncor += k * b.corners;
        }
        for (e, k) in edg.iter().enumerate().filter(|(_, k)| !k.is_zero()) {
            let (pieces, born) = &table.edge_birth[e];
            pieces.iter().for_each(|&x| nedg[x] += k);
            ncor += k * born.unwrap_or(0);
        }
        (vol, fac, edg, corners) = (nvol, nfac, nedg, ncor);
    }
    let msg =
        format!(
        "the birth table derived from one step of the own complexes of {}, {} and {} (the code \
         of solid-homology), level 0 counted on the claim's complex, levels 0–{} by the \
         recurrence in big integers{}{}",
        super::counted(closure.types.len(), "volume type", "volume types"),
        super::counted(table.faces.len(), "face type", "face types"),
        super::counted(table.edges.len(), "edge type", "edge types"),
        s.rows.len() - 1,
        match all_connected {
            true =>
                "; every volume type's level-1 complex is connected, so every level has the \
                     components of level 0",
            false => "; a volume type's level-1 complex is not connected: no components derived",
        },
        match all_open && !table.sealed {
            true => "; no face type's sub-faces close up on its sides, and every volume type's \
                     complex relative to its subdivided surface has H2 = H3 = 0 over F2, so every \
                     level past 0 has b2 = b3 = 0 and b1 = b0 + b2 − χ",
            false => "; a face type's sub-faces close up on its sides or a volume type's relative \
                      complex has homology in degree 2 or 3: no voids derived past level 0",
        }
    );
    Ok((
        msg,
        format!("the level-n solid by the recurrence: {}", lines.join("; ")),
    ))
}

#[cfg(test)]
mod tests {
    use super::volume_tests::{b2, cube, square};
    use super::*;

    #[test]
    fn the_cube_births_what_the_worked_example_counts() {
        // docs/CERTIFICATES.md, by hand: the cube creates 8 pieces, 56 faces (24 spoke side
        // faces, 24 walls, 8 inner faces), 84 edges (36 radial, 48 inner), 36 inner corners.
        let mut table = Table::default();
        let (birth, pieces, connected, open) = derive_volume(&cube(), &mut table).unwrap();
        assert_eq!(
            (pieces, birth.faces.len(), birth.edges.len(), birth.corners),
            (8, 56, 84, 36)
        );
        assert!(connected && open);
        // A square under {joint}: 4 pentagons, 4 spokes and 4 lacuna sides, 4 lacuna corners;
        // a B2 edge: 2 pieces and the joint between them.
        let f = table.face(&square()).unwrap();
        table.derive_face(f).unwrap();
        let b = table.face_birth[f].as_ref().unwrap();
        assert_eq!((b.faces.len(), b.edges.len(), b.corners), (4, 8, 4));
        assert!(b.faces.iter().all(|&g| table.faces[g].boundary.len() == 5));
        let e = table.edge(b2()).unwrap();
        assert_eq!(table.edge_birth[e], (vec![e, e], Some(1)));
        assert!(!table.sealed);
    }

    #[test]
    fn a_delayed_face_closes_up_on_its_sides() {
        // A delayed square becomes one square without a hole: its one sub-face's boundary lies
        // on its sides only, so premise 1 fails and no voids are derived.
        let mut table = Table::default();
        let f = table
            .face(&Face {
                delay: 2,
                ..square()
            })
            .unwrap();
        table.derive_face(f).unwrap();
        assert!(table.sealed);
    }
}
