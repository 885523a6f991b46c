//! The steps about volumes: the closure of volume types and their counts, the volume constraint
//! system with its placements, and the homology of the level-n solid by level and by recurrence.

use super::{ClosureStep, LevelOneSide, Seat, Volume};
use serde::{Deserialize, Serialize};

/// The closure of volume types and the counts of the start volumes.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VolumeClosureStep {
    /// The volume types (the claim's start volumes are among them, in any form).
    pub types: Vec<VolumeTypeRule>,
    /// The counts from level 0.
    pub counts: Vec<VolumeCount>,
}

/// One volume type with its children.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VolumeTypeRule {
    /// A representative of the type (lacuna writes its canonical form).
    pub volume: Volume,
    /// The type index of every sub-volume of one step (with repetition, in any order).
    pub children: Vec<usize>,
    /// Lacunas added by one step, in quarters (THEORY §10).
    pub contribution_quarters: u64,
}

/// The exact counts of the start volumes at one level.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VolumeCount {
    /// The level i (the counts are listed for i = 0, 1, 2, … in order).
    pub level: u64,
    /// N^C_i: sub-volumes (a natural number).
    pub cells: String,
    /// N^L_i: lacunas (a rational, a multiple of 1/4).
    pub lacunas: String,
}

/// The solution space of the constraint system of a volume closure (THEORY §10).
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VolumeSystemStep {
    /// Bézier degree q of the `Bn` edges.
    pub degree: usize,
    /// Cantor gap/piece ratio (a rational > 0).
    pub cantor_gap: String,
    /// The face types of the surfaces, closed under subdivision (checked as a `closure` step).
    pub faces: ClosureStep,
    /// `frames[v][f] = (t, r)`: face `f` of volume type `v`, rotated left by `r`, is face type
    /// `t`.
    pub frames: Vec<Vec<(usize, usize)>>,
    /// `subvolumes[v][k]`: the sub-volume whose operator is `V<v>.T<k>`.
    pub subvolumes: Vec<Vec<SubVolumePlacement>>,
    /// The number of unknowns (the checker's column order, CERTIFICATES.md).
    pub unknowns: usize,
    /// A solution, sparse: unknowns not listed are 0.
    pub particular: Vec<(usize, String)>,
    /// The free unknowns, increasing, one per basis vector.
    pub free: Vec<usize>,
    /// Sparse basis vectors of the kernel; `basis[k]` is 1 at `free[k]`, 0 at the other free
    /// unknowns.
    pub basis: Vec<Vec<(usize, String)>>,
    /// The claimed rank (the unknowns that are not free).
    pub rank: usize,
    /// The claimed degrees of freedom.
    pub dof: usize,
}

/// Where sub-volume `k` of a volume type lies: its type, and where the faces it is built from
/// lie on that type's surface.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SubVolumePlacement {
    /// Index into the volume closure's types.
    pub type_index: usize,
    /// `((f, j), (g, r))`: sub-face `j` of face `f` (numbered as its face type subdivides) is
    /// face `g` of the type; its boundary as built, rotated left by `r`, is `g`'s face type.
    pub subfaces: Vec<((usize, usize), Seat)>,
    /// `((f, j, p), (g, r))`: the side face `X Er Ei Er` over side `p` of sub-face `j` of face
    /// `f` is face `g` of the type, rotated left by `r` as above.
    pub sides: Vec<(LevelOneSide, Seat)>,
}

/// The topology of the level-n solid of the claim's volumes at levels 0 to `rows.len() − 1`.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolidHomologyStep {
    /// One row per level, from level 0.
    pub rows: Vec<SolidRow>,
}

/// The cells, χ and components of the level-n solid of the claim's volumes at levels 0 to
/// `rows.len() − 1` (every level of the claim), by the recurrence of cells by birth.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolidRecurrenceStep {
    /// One row per level, from level 0.
    pub rows: Vec<SolidCountRow>,
}

/// The cells of the solid at one level, in decimal (they grow past any fixed width), and its
/// Betti numbers where claimed.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolidCountRow {
    /// The level.
    pub level: u64,
    /// Volumes (3-cells).
    pub volumes: String,
    /// Faces (2-cells).
    pub faces: String,
    /// Edges (1-cells).
    pub edges: String,
    /// Corners (0-cells).
    pub corners: String,
    /// χ = corners − edges + faces − volumes.
    pub euler: String,
    /// b0: connected components, when claimed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub components: Option<u64>,
    /// b2: enclosed cavities, when claimed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub voids: Option<u64>,
    /// b1 = b0 + b2 − χ: tunnels, when claimed (with b0 and b2), in decimal.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tunnels: Option<String>,
}

/// The cells and Betti numbers of the solid at one level.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolidRow {
    /// The level.
    pub level: u64,
    /// Volumes (3-cells).
    pub volumes: u64,
    /// Faces (2-cells).
    pub faces: u64,
    /// Edges (1-cells).
    pub edges: u64,
    /// Corners (0-cells).
    pub corners: u64,
    /// χ = corners − edges + faces − volumes.
    pub euler: i64,
    /// b0: connected components.
    pub components: u64,
    /// b2: enclosed cavities.
    pub voids: u64,
    /// b1: tunnels.
    pub tunnels: u64,
}
