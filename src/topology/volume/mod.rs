//! Lacunar volumes in 3D (THEORY §10): a volume is a closed surface of lacunar faces; one step
//! subdivides every face, cuts the level-1 surface along the spoke edges chosen by the volume rule
//! into patches, and raises one sub-volume over each patch.
//!
//! - [`surface`]: closed surfaces as oriented maps (gluing, sphere check, canonical form);
//! - [`solid`]: the common solids and the one-line volume notation;
//! - [`step`]: one subdivision step of a volume, with its patches and sub-volumes;
//! - [`closure`]: the closure of volume types, exact counts of sub-volumes and lacunas;
//! - [`assembly`]: several volumes glued face to face, the level-0 complex of an assembly;
//! - [`complex`]: the exact topology of the level-n solid (cells, χ, components, voids, tunnels).
//!
//! Like the rest of the topology layer this never sees a float.

pub(crate) mod assembly;
pub(crate) mod closure;
pub(crate) mod complex;
pub(crate) mod solid;
pub(crate) mod step;
pub(crate) mod surface;

pub use assembly::{mirror_consistent, reversed, SharedFace, StartCells, StartMap, VolumeAssembly};
pub use closure::{
    volume_counts, volumes_by_type, VolumeClosure, VolumeLevelCount, VolumeType, VolumeTypeSet,
};
pub use complex::{face_cells, faces_cells, solid_topology, solid_topology_of, SolidLevel};
pub use solid::{parse_volume, Solid};
pub use step::{subdivide_volume, Interior, Patch, Placed, SubVolume, VolumeSubdivision};
pub use surface::Surface;

use crate::topology::edge::EdgeType;
use crate::topology::face::{Face, Params};
use crate::topology::rule::Algorithm;
use crate::topology::subdivision::Origin;
use std::fmt;

/// Which sub-face edges of the level-1 surface are spoke edges, along which the surface is cut
/// into patches. A new rule is a new variant with its predicate in [`VolumeRule::is_spoke`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum VolumeRule {
    /// Every adjacency edge Ea of every face.
    V1,
    /// V1 and every sub-edge lying on an edge of the surface.
    V2,
}

impl VolumeRule {
    /// Whether a sub-face edge with this origin (in its face's subdivision) is a spoke edge.
    pub fn is_spoke(self, origin: &Origin) -> bool {
        match (self, origin) {
            (_, Origin::Spoke { .. }) => true,
            (VolumeRule::V2, Origin::Piece { .. }) => true,
            (VolumeRule::V1, Origin::Piece { .. }) => false,
            (_, Origin::Lacuna { .. } | Origin::GapSide { .. }) => false,
        }
    }
}

impl fmt::Display for VolumeRule {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            VolumeRule::V1 => "V1",
            VolumeRule::V2 => "V2",
        })
    }
}

/// A volume `V(S, G, E, A, rule, d)`.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Volume {
    /// The boundary surface S (a sphere).
    pub surface: Surface,
    /// G = (Er, Ei): the radial and inner edge types created inside the volume.
    pub radial: EdgeType,
    /// Ei.
    pub inner: EdgeType,
    /// E of the faces created inside the volume (side, inner and cap faces).
    pub params: Params,
    /// A of the faces created inside the volume.
    pub algorithm: Algorithm,
    /// The volume rule.
    pub rule: VolumeRule,
    /// d ≥ 1.
    pub delay: u32,
}

impl Volume {
    /// The volume with its surface in canonical form: two volumes are the same type exactly when
    /// their canonical forms are equal.
    pub fn canonical(&self) -> Volume {
        Volume {
            surface: self.surface.canonical(),
            ..self.clone()
        }
    }

    /// A face created inside this volume with the given boundary.
    pub(crate) fn inner_face(&self, boundary: Vec<EdgeType>) -> Face {
        Face {
            boundary,
            params: self.params,
            algorithm: self.algorithm.clone(),
            delay: 1,
        }
    }

    /// Lacunas one step of this volume contributes, in quarters: 4 for its central cavity plus
    /// the face contribution in halves of every face of S (each face hole and gap is shared with
    /// the cell on the other side, so it counts half), when the volume is not delayed; 0 for a
    /// delayed volume, whose holes are capped.
    pub fn contribution_quarters(&self) -> u64 {
        if self.delay >= 2 {
            return 0;
        }
        4 + self
            .surface
            .faces
            .iter()
            .map(Face::contribution_halves)
            .sum::<u64>()
    }
}

impl fmt::Display for Volume {
    /// A short description: faces, corners and edges of S, G, E, A, rule and delay.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (_, v) = self.surface.vertices();
        write!(
            f,
            "volume of {} faces, {} corners, {} edges | G {} {} | {} {} {} | {} | {}",
            self.surface.faces.len(),
            v,
            self.surface.edge_count(),
            self.radial,
            self.inner,
            self.params.ea,
            self.params.el,
            self.params.ec,
            self.algorithm,
            self.rule
        )?;
        if self.delay > 1 {
            write!(f, " | {}", self.delay)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests;
