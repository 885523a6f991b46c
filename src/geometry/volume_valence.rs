//! The valences of a volume's level-k complex (THEORY §13): the number of edges at every corner
//! of the level-k solid, read off the cells [`evaluate_assembly`] builds from the exact step.
//!
//! The cells are identified by the step's incidences (a point or edge born inside a face or an
//! edge is keyed by what names it from either side), never by coordinates: the placement only
//! gives them positions. So the counts here are combinatorial, and the caller compares them with
//! the exact counts of [`crate::topology::volume::solid_topology`] (corners, and edges through the
//! degree sum). The caller also bounds the work before it starts, from those exact counts.

use crate::error::{Diagnostic, Error, Result};
use crate::geometry::volume::{evaluate_assembly, place_assembly, InnerFan, Placement};
use crate::topology::volume::{Volume, VolumeAssembly};
use std::collections::{BTreeMap, HashMap, HashSet};

/// The corners of one level of a volume's solid by valence.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ComplexValences {
    /// The level.
    pub level: u32,
    /// The corners of the level's cells.
    pub corners: usize,
    /// The edges of the level's cells.
    pub edges: usize,
    /// For each valence, how many corners have it.
    pub valences: BTreeMap<usize, u64>,
}

/// The valences of the corners of the level-`level` complex of `v` (one volume, on a shorthand
/// solid: E1210 otherwise). E1440 when the complex is not one: an edge from a corner to itself,
/// or an edge whose ends are not corners of the level's faces.
pub fn volume_valences(v: &Volume, level: u32) -> Result<ComplexValences> {
    let a = VolumeAssembly::single(v.clone());
    let placement = place_assembly(&a, &[], &[])?;
    assembly_valences(&a, &placement, level)
}

/// [`volume_valences`] of an assembly (volumes glued face to face, a shared face one face of the
/// complex) on a placement ([`place_assembly`]); the placement only positions the cells.
pub fn assembly_valences(
    a: &VolumeAssembly,
    placement: &Placement,
    level: u32,
) -> Result<ComplexValences> {
    let g = evaluate_assembly(a, placement, level, InnerFan::RimMean)?;
    let mut edges: HashSet<usize> = HashSet::new();
    let mut corners: HashSet<usize> = HashSet::new();
    for gv in &g.volumes {
        for r in &gv.faces {
            edges.extend(r.edges.iter().copied());
            corners.extend(r.corners.iter().copied());
        }
    }
    let mut degree: HashMap<usize, usize> = HashMap::new();
    for &e in &edges {
        let (a, b) = (g.edges[e].a, g.edges[e].b);
        if a == b || !corners.contains(&a) || !corners.contains(&b) {
            return Err(mismatch(format!(
                "edge {e} of the level-{level} complex runs from point {a} to point {b}, which is not an edge between two of its corners"
            )));
        }
        *degree.entry(a).or_default() += 1;
        *degree.entry(b).or_default() += 1;
    }
    if let Some(c) = corners.iter().find(|c| !degree.contains_key(c)) {
        return Err(mismatch(format!(
            "corner {c} of the level-{level} complex has no edge"
        )));
    }
    let mut valences: BTreeMap<usize, u64> = BTreeMap::new();
    for d in degree.values() {
        *valences.entry(*d).or_default() += 1;
    }
    Ok(ComplexValences {
        level,
        corners: corners.len(),
        edges: edges.len(),
        valences,
    })
}

/// E1440: the level-k complex of a volume disagrees with itself or with the exact counts.
pub fn mismatch(message: String) -> Error {
    Error::Syntax(Box::new(Diagnostic {
        code: "E1440",
        message: format!("{message} (a bug: please report it with the input)"),
        span: None,
        source: None,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::topology::volume::parse_volume;

    #[test]
    fn cube_b2_levels_0_and_1_by_hand() {
        let v = parse_volume("cube B2 | B2 B2 B2 | A1 | B2 B2 | V1").unwrap();
        // Level 0: the cube, 8 corners with 3 edges each.
        let c = volume_valences(&v, 0).unwrap();
        assert_eq!((c.corners, c.edges), (8, 12));
        assert_eq!(c.valences, BTreeMap::from([(3, 8)]));
        // Level 1 (THEORY §10: 8 sub-volumes, one per cube corner, over a patch of the three
        // pentagons `piece piece Ea El Ea` at that corner; 13 faces, 19 corners, 30 edges each).
        // Each square face has 4 joints (the cube's edge midpoints, shared by two faces), a spoke
        // from each to a corner of the face's square lacuna. The rule V1 cuts along the spokes,
        // so a patch's rim is 6 spokes (shared with the neighbouring sub-volume) and 3 lacuna
        // sides (walls); its rim points are its 3 joints and 6 lacuna corners, and every rim
        // point has one radial edge to an inner corner (the sub-volumes around it share the side
        // face over the spoke there, hence the radial edge).
        // - 8 cube corners: the 3 pieces of the cube's edges: valence 3;
        // - 12 joints: 2 pieces, 2 spokes (one per face at the cube edge), 1 radial: 5;
        // - 24 lacuna corners: 1 spoke, 2 lacuna sides, 1 radial: 4;
        // - 12 inner corners of joints: the radial and the 2 inner edges of the side faces over
        //   the 2 spokes (each shared by the two sub-volumes): 3;
        // - 24 inner corners of lacuna corners: the radial, the inner edge over the spoke, and
        //   one inner edge of the wall of each of the two sub-volumes that meet there: 4.
        // Corners 8 + 12 + 24 + 12 + 24 = 80, edges (8·3 + 12·5 + 48·4 + 12·3)/2 = 156: the
        // exact counts of the level-1 solid (topology::volume::solid_topology).
        let c = volume_valences(&v, 1).unwrap();
        assert_eq!((c.corners, c.edges), (80, 156));
        assert_eq!(c.valences, BTreeMap::from([(3, 20), (4, 48), (5, 12)]));
    }

    #[test]
    fn simple_polyhedra_at_level_1() {
        // The count of the cube generalizes to every solid with 3 faces at each corner (V
        // corners, E edges), B2 edges, A1 and V1: the V old corners 3, the E joints 5, the 2E
        // lacuna corners (one per spoke, two spokes per edge) 4, the E inner corners of joints 3
        // and the 2E inner corners of lacuna corners 4: {3: V + E, 4: 4E, 5: E}. The hexagonal
        // prism and the truncated tetrahedron (V = 12, E = 18) are different solids with equal
        // valences; the tetrahedron has V = 4, E = 6.
        for (solid, v, e) in [
            ("tetrahedron", 4, 6),
            ("truncated-tetrahedron", 12, 18),
            ("prism-6", 12, 18),
        ] {
            let vol = parse_volume(&format!("{solid} B2 | B2 B2 B2 | A1 | B2 B2 | V1")).unwrap();
            let c = volume_valences(&vol, 1).unwrap();
            assert_eq!(
                c.valences,
                BTreeMap::from([(3, v + e), (4, 4 * e), (5, e)]),
                "{solid}"
            );
            assert_eq!(c.corners as u64, v + 6 * e, "{solid}");
        }
    }
}
