//! The exact topology of the level-n solid (THEORY §10): the numbers of corners, edges, faces and
//! volumes of its cell complex, its Euler characteristic, components, voids and tunnels.
//!
//! **Every cell is born inside exactly one cell of the level before.** A step creates, inside a
//! volume, its sub-volumes, the side faces (one per spoke edge, shared by the two sub-volumes, and
//! one per wall edge), the inner faces, the radial edges (one per fan of sub-volumes around a rim
//! point), the inner edges and the inner corners ([`crate::topology::volume::VolumeSubdivision::interior`], computed with the step);
//! inside a face, its sub-faces, its spokes Ea, lacuna edges El and gap sides Ec, its lacuna
//! corners and gap points; inside an edge, its pieces and the joints or gap ends between them; a
//! corner stays a corner. A face shared by two volumes is one cell of the complex and is
//! subdivided once, so counting by birth counts every cell once. The counts are linear recurrences
//! on the vector of cell types (volume, face and edge types, and corners), in big integers.
//!
//! **Components** stay the same from level to level when the sub-volumes of every volume type are
//! connected (children of cells that share a cell still share its subdivision); otherwise they are
//! not derived. **Voids** (enclosed cavities): none at any level when no volume and no face of the
//! recursion is delayed — every face of the level before then has a hole at the next level, every
//! new cavity opens through the faces of its volume, and every group of volumes joined by shared
//! faces has a face on the boundary of the solid, so every cavity reaches the outside; at level 1
//! the start volume's cavity is a void exactly when its level-1 surface has no hole. Otherwise
//! voids are not derived. With b0 components and b2 voids, the tunnels (first Betti number, the
//! genus of a connected solid) are b1 = b0 + b2 − χ.

use crate::error::Result;
use crate::topology::edge::EdgeType;
use crate::topology::face::Face;
use crate::topology::subdivision::{subdivide, Origin};
use crate::topology::volume::assembly::StartCells;
use crate::topology::volume::closure::VolumeTypeSet;
use num_bigint::{BigInt, BigUint};
use num_traits::Zero;
use serde::Serialize;
use std::collections::{HashMap, HashSet};

/// The exact topology of the solid at one level.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct SolidLevel {
    /// The level.
    pub level: u64,
    /// Volumes (3-cells).
    #[serde(serialize_with = "crate::topology::closure::ser_display")]
    pub volumes: BigUint,
    /// Faces (2-cells).
    #[serde(serialize_with = "crate::topology::closure::ser_display")]
    pub faces: BigUint,
    /// Edges (1-cells).
    #[serde(serialize_with = "crate::topology::closure::ser_display")]
    pub edges: BigUint,
    /// Corners (0-cells).
    #[serde(serialize_with = "crate::topology::closure::ser_display")]
    pub corners: BigUint,
    /// χ = corners − edges + faces − volumes.
    #[serde(serialize_with = "crate::topology::closure::ser_display")]
    pub euler: BigInt,
    /// Connected components b0, where derived.
    pub components: Option<u64>,
    /// Enclosed cavities b2, where derived.
    pub voids: Option<u64>,
    /// Tunnels b1 = b0 + b2 − χ, where b0 and b2 are derived.
    #[serde(serialize_with = "ser_option")]
    pub tunnels: Option<BigInt>,
}

fn ser_option<S: serde::Serializer>(
    v: &Option<BigInt>,
    s: S,
) -> std::result::Result<S::Ok, S::Error> {
    match v {
        Some(x) => s.collect_str(x),
        None => s.serialize_none(),
    }
}

/// What one cell of each type creates in its relative interior.
#[derive(Default)]
struct Birth {
    volumes: Vec<usize>,
    faces: Vec<Face>,
    edges: Vec<EdgeType>,
    corners: u64,
}

/// Registry of face and edge types met so far, with what each creates.
#[derive(Default)]
struct Cells {
    faces: Vec<Face>,
    face_index: HashMap<Face, usize>,
    face_birth: Vec<(Vec<usize>, Vec<usize>, u64)>,
    edges: Vec<EdgeType>,
    edge_index: HashMap<EdgeType, usize>,
    edge_birth: Vec<(Vec<usize>, u64)>,
}

impl Cells {
    fn edge(&mut self, e: EdgeType) -> usize {
        if let Some(&i) = self.edge_index.get(&e) {
            return i;
        }
        let i = self.edges.len();
        self.edges.push(e);
        self.edge_index.insert(e, i);
        self.edge_birth.push((Vec::new(), 0));
        // Pieces and the corners between them (a joint, or the two ends of a gap).
        let piece = self.edge(e.piece());
        let n = e.piece_count() as u64;
        let corners = match e.inner_junction() {
            None => 0,
            Some(crate::topology::edge::JunctionKind::Gap) => 2 * (n - 1),
            Some(_) => n - 1,
        };
        self.edge_birth[i] = (vec![piece; n as usize], corners);
        i
    }

    fn face(&mut self, f: &Face) -> Result<usize> {
        let (f, _) = f.canonical();
        if let Some(&i) = self.face_index.get(&f) {
            return Ok(i);
        }
        let i = self.faces.len();
        self.faces.push(f.clone());
        self.face_index.insert(f.clone(), i);
        self.face_birth.push((Vec::new(), Vec::new(), 0));
        let sub = subdivide(&f)?;
        let mut inner_edges = Vec::new();
        let mut gap_sides = HashSet::new();
        for s in &sub.subfaces {
            for (k, o) in s.origins.iter().enumerate() {
                let e = s.face.boundary[k];
                match o {
                    Origin::Lacuna { .. } => inner_edges.push(self.edge(e)),
                    Origin::GapSide { .. } => {
                        if gap_sides.insert(*o) {
                            inner_edges.push(self.edge(e));
                        }
                    }
                    Origin::Spoke { inward: true, .. } => inner_edges.push(self.edge(e)),
                    Origin::Spoke { inward: false, .. } | Origin::Piece { .. } => {}
                }
            }
        }
        let gaps = sub
            .junctions
            .iter()
            .filter(|j| j.kind == crate::topology::edge::JunctionKind::Gap)
            .count() as u64;
        // A lacuna corner per spoke, a gap point per gap.
        let corners = sub.spokes.len() as u64 + gaps;
        let subfaces = sub
            .subfaces
            .iter()
            .map(|s| self.face(&s.face))
            .collect::<Result<Vec<_>>>()?;
        self.face_birth[i] = (subfaces, inner_edges, corners);
        Ok(i)
    }
}

/// The exact topology of the solid of each start volume together (their disjoint union), from
/// level 0 to `levels`.
pub fn solid_topology(set: &VolumeTypeSet, levels: u64) -> Result<Vec<SolidLevel>> {
    let mut faces = Vec::new();
    let mut edges = Vec::new();
    let mut corners = 0u64;
    for &s in &set.start {
        let surface = &set.types[s].volume.surface;
        faces.extend(surface.faces.iter().cloned());
        for (f, row) in surface.glue.iter().enumerate() {
            for (i, &(g, j)) in row.iter().enumerate() {
                if (f, i) < (g, j) {
                    edges.push(surface.faces[f].boundary[i]);
                }
            }
        }
        corners += surface.vertices().1 as u64;
    }
    let start = StartCells {
        faces,
        edges,
        corners,
        components: set.start.len() as u64,
    };
    solid_topology_of(set, levels, &start)
}

/// The exact topology of the solid whose level-0 complex has the cells `start` (an assembly of
/// the start volumes of `set`, glued face to face), from level 0 to `levels`. Every cell of
/// `start` is subdivided once, whichever volumes share it.
pub fn solid_topology_of(
    set: &VolumeTypeSet,
    levels: u64,
    start: &StartCells,
) -> Result<Vec<SolidLevel>> {
    let mut cells = Cells::default();
    let mut births: Vec<Birth> = Vec::with_capacity(set.types.len());
    let mut all_connected = true;
    let mut any_delayed = false;
    // Whether each type's level-1 surface has a hole (its cavity opens).
    let mut opens = Vec::with_capacity(set.types.len());
    for t in &set.types {
        let int = &t.subdivision.interior;
        all_connected &= int.children_connected;
        opens.push(int.opens);
        any_delayed |= t.volume.delay >= 2;
        let mut edges = vec![t.volume.radial; int.radial_edges];
        edges.extend(vec![t.volume.inner; int.inner_edges]);
        births.push(Birth {
            volumes: t.children.clone(),
            faces: int.faces.clone(),
            edges,
            corners: int.radial_edges as u64,
        });
    }
    // Register every face and edge type reachable, so that the vectors have fixed length.
    let mut vol_faces: Vec<(Vec<usize>, Vec<usize>)> = Vec::new();
    for b in &births {
        let f = b
            .faces
            .iter()
            .map(|f| cells.face(f))
            .collect::<Result<Vec<_>>>()?;
        let e = b.edges.iter().map(|&e| cells.edge(e)).collect();
        vol_faces.push((f, e));
    }
    // Level 0: the start volumes with the cells of their assembly.
    let nv = set.types.len();
    let mut vol = vec![BigUint::zero(); nv];
    let mut fac: Vec<BigUint> = Vec::new();
    let mut edg: Vec<BigUint> = Vec::new();
    let mut corners = BigUint::from(start.corners);
    for &s in &set.start {
        vol[s] += 1u32;
    }
    let start_faces = start
        .faces
        .iter()
        .map(|f| cells.face(f))
        .collect::<Result<Vec<_>>>()?;
    let start_edges: Vec<usize> = start.edges.iter().map(|&e| cells.edge(e)).collect();
    let any_delayed_face = cells.faces.iter().any(|f| f.delay >= 2);
    fac.resize(cells.faces.len(), BigUint::zero());
    edg.resize(cells.edges.len(), BigUint::zero());
    for f in start_faces {
        fac[f] += 1u32;
    }
    for e in start_edges {
        edg[e] += 1u32;
    }
    let starts = start.components;
    // Cavities of volumes glued face to face may open into each other: level-1 voids are derived
    // for volumes apart only.
    let apart = start.components == set.start.len() as u64;
    let level1_voids: Option<u64> = apart.then(|| {
        set.start
            .iter()
            .map(|&s| u64::from(set.types[s].volume.delay == 1 && !opens[s]))
            .sum()
    });
    let mut out = Vec::new();
    for level in 0..=levels {
        let sum = |v: &[BigUint]| v.iter().sum::<BigUint>();
        let (c, f, e) = (sum(&vol), sum(&fac), sum(&edg));
        let euler = BigInt::from(corners.clone()) - BigInt::from(e.clone())
            + BigInt::from(f.clone())
            - BigInt::from(c.clone());
        let components = (level == 0 || all_connected).then_some(starts);
        let voids = match level {
            0 => Some(0),
            _ if !any_delayed && !any_delayed_face => Some(0),
            1 => level1_voids,
            _ => None,
        };
        let tunnels = match (components, voids) {
            (Some(b0), Some(b2)) => Some(BigInt::from(b0) + BigInt::from(b2) - &euler),
            _ => None,
        };
        out.push(SolidLevel {
            level,
            volumes: c,
            faces: f,
            edges: e,
            corners: corners.clone(),
            euler,
            components,
            voids,
            tunnels,
        });
        if level == levels {
            break;
        }
        let mut nvol = vec![BigUint::zero(); nv];
        let mut nfac = vec![BigUint::zero(); cells.faces.len()];
        let mut nedg = vec![BigUint::zero(); cells.edges.len()];
        let mut ncor = corners.clone();
        for (t, k) in vol.iter().enumerate() {
            if k.is_zero() {
                continue;
            }
            for &ch in &births[t].volumes {
                nvol[ch] += k;
            }
            for &x in &vol_faces[t].0 {
                nfac[x] += k;
            }
            for &x in &vol_faces[t].1 {
                nedg[x] += k;
            }
            ncor += k * births[t].corners;
        }
        for (t, k) in fac.iter().enumerate() {
            if k.is_zero() {
                continue;
            }
            let (subs, inner, born) = &cells.face_birth[t];
            for &x in subs {
                nfac[x] += k;
            }
            for &x in inner {
                nedg[x] += k;
            }
            ncor += k * born;
        }
        for (t, k) in edg.iter().enumerate() {
            if k.is_zero() {
                continue;
            }
            let (pieces, born) = &cells.edge_birth[t];
            for &x in pieces {
                nedg[x] += k;
            }
            ncor += k * born;
        }
        vol = nvol;
        fac = nfac;
        edg = nedg;
        corners = ncor;
    }
    Ok(out)
}

/// The cells of the level-n complex of one face (its sub-faces, edges and corners; the
/// lacunas are holes, not cells), from level 0 to `levels`, by birth as for solids: `(faces,
/// edges, corners)` per level.
pub fn face_cells(face: &Face, levels: u64) -> Result<Vec<[BigUint; 3]>> {
    faces_cells(std::slice::from_ref(face), &[], levels)
}

/// The cells of the level-n complex of start faces glued along `glue` (pairs of (face, side),
/// the two sides one edge read in opposite directions, each side glued at most once), as
/// [`face_cells`]: a glued edge is one edge whose pieces and inner corners are counted once,
/// and the corners at level 0 are the classes of the faces' corners under the gluing (they stay
/// corners at every level, the ends of their edges' end pieces).
pub fn faces_cells(
    faces: &[Face],
    glue: &[crate::topology::component::Glue],
    levels: u64,
) -> Result<Vec<[BigUint; 3]>> {
    let mut cells = Cells::default();
    let mut starts = Vec::new();
    let mut base = Vec::with_capacity(faces.len());
    let mut slots = 0usize;
    for f in faces {
        starts.push(cells.face(f)?);
        base.push(slots);
        slots += f.boundary.len();
    }
    // Corner i of a face starts its side i; gluing side a to side b (opposite directions) joins
    // the start of a to the end of b and the end of a to the start of b.
    let corner = |f: usize, i: usize| base[f] + i % faces[f].boundary.len();
    let mut dsu = crate::topology::component::Dsu::new(slots);
    let mut second = vec![false; slots];
    for &[(fa, a), (fb, b)] in glue {
        dsu.union(corner(fa, a), corner(fb, b + 1));
        dsu.union(corner(fa, a + 1), corner(fb, b));
        second[corner(fb, b)] = true;
    }
    let mut start_edges = Vec::new();
    for (f, face) in faces.iter().enumerate() {
        for (i, &e) in face.boundary.iter().enumerate() {
            if !second[corner(f, i)] {
                start_edges.push(cells.edge(e));
            }
        }
    }
    let mut fac = vec![BigUint::zero(); cells.faces.len()];
    let mut edg = vec![BigUint::zero(); cells.edges.len()];
    for t in starts {
        fac[t] += 1u32;
    }
    for e in start_edges {
        edg[e] += 1u32;
    }
    let mut corners = BigUint::from(dsu.classes());
    let mut out = Vec::new();
    for level in 0..=levels {
        let sum = |v: &[BigUint]| v.iter().sum::<BigUint>();
        out.push([sum(&fac), sum(&edg), corners.clone()]);
        if level == levels {
            break;
        }
        let mut nfac = vec![BigUint::zero(); cells.faces.len()];
        let mut nedg = vec![BigUint::zero(); cells.edges.len()];
        for (t, k) in fac.iter().enumerate().filter(|(_, k)| !k.is_zero()) {
            let (subs, inner, born) = &cells.face_birth[t];
            for &x in subs {
                nfac[x] += k;
            }
            for &x in inner {
                nedg[x] += k;
            }
            corners += k * born;
        }
        for (t, k) in edg.iter().enumerate().filter(|(_, k)| !k.is_zero()) {
            let (pieces, born) = &cells.edge_birth[t];
            for &x in pieces {
                nedg[x] += k;
            }
            corners += k * born;
        }
        fac = nfac;
        edg = nedg;
    }
    Ok(out)
}
