//! The steps about faces: the closure of face types and their rules, the corners forced to
//! coincide, the level-one point, and the homology of a face's complex.

use super::Face;
use serde::{Deserialize, Serialize};

/// The closure: every face type with its rule, and the start types.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ClosureStep {
    /// The face types. The start types are not listed: they are the claim's faces.
    pub types: Vec<TypeRule>,
}

/// One face type with its subdivision rule.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TypeRule {
    /// The face, in canonical form.
    pub face: Face,
    /// Sub-face `k` runs from spoke `k` to spoke `k + 1` (one sub-face for a delayed face).
    pub subfaces: Vec<SubFace>,
    /// Adjacency `k` pairs the two sides of spoke `k + 1` (none for a delayed face).
    pub adjacencies: Vec<Adjacency>,
    /// Lacunas added by one subdivision step, in halves (THEORY §5).
    pub contribution_halves: u64,
}

/// Where an edge of a sub-face comes from (lacuna's `Origin`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Origin {
    /// Piece `piece` of the parent's boundary edge `edge`.
    Piece {
        /// Parent edge.
        edge: usize,
        /// Piece within it.
        piece: usize,
    },
    /// The Ea edge on spoke `spoke`, inward = from the boundary to the lacuna.
    Spoke {
        /// Spoke index (in the order of the spoke junctions).
        spoke: usize,
        /// Direction.
        inward: bool,
    },
    /// Side `side` of the central lacuna (El).
    Lacuna {
        /// Equal to the sub-face index.
        side: usize,
    },
    /// One side (Ec) of gap `gap` of the parent's edge `edge`; `after` for the later piece.
    GapSide {
        /// Parent edge.
        edge: usize,
        /// Gap within it.
        gap: usize,
        /// Which side.
        after: bool,
    },
}

/// A sub-face: its type and, aligned with that type's boundary, the origin of each edge.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SubFace {
    /// Index into [`ClosureStep::types`].
    pub type_index: usize,
    /// `origins[k]` is the origin of edge `k` of the type's (canonical) boundary.
    pub origins: Vec<Origin>,
}

/// Two sub-faces sharing an Ea edge: `(sub-face, boundary position)` of each side.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Adjacency {
    /// The side traversed inward.
    pub first: (usize, usize),
    /// The side traversed outward.
    pub second: (usize, usize),
}

/// The step `degeneracy`: what the constraints force to collapse (empty lists: nothing).
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DegeneracyStep {
    /// Two combinatorially distinct corners of a face type's level-1 complex that coincide on
    /// every solution: `[type, sub-face, corner, sub-face, corner]` (corner `i` of a sub-face is
    /// the start of its boundary edge `i`). A class of more than two such corners is listed as
    /// pairs that join it.
    pub coincide: Vec<[usize; 5]>,
    /// Face types of two Cantor edges: the face has area 0 on every solution.
    pub flat_faces: Vec<usize>,
    /// Face types whose lacuna has two sides, both Cantor edges: the lacuna has area 0.
    pub flat_lacunas: Vec<usize>,
}

/// The step `level-one`: a chosen point of the proved solution space at which every cell of
/// level 1 has a control polygon of positive signed area, in frames the step gives.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LevelOneStep {
    /// Per face type (closure order), its frame: one point `[x, y]` (rationals) per control
    /// point of the type, in boundary order. The type's own control polygon in its frame must
    /// have positive signed area.
    pub frames: Vec<Vec<[String; 2]>>,
    /// The chosen point: the value of each free parameter, in the order of the proved
    /// `solution-space` step's `free` list (the point is `particular + Σ t_j·basis_j`).
    pub parameters: Vec<String>,
    /// The sub-faces checked, over all types.
    pub sub_faces: u64,
    /// The central lacunas checked, over all types.
    pub lacunas: u64,
    /// The smallest signed area of a sub-face's control polygon in its parent's frame.
    pub smallest_area: String,
}

/// Where a face of a sub-volume lies on its type's surface: `(face, rotation)`.
pub type Seat = (usize, usize);

/// A side of the level-1 surface of a volume: `(face, sub-face, position)`.
pub type LevelOneSide = (usize, usize, usize);

/// The topology of the level-n complex of one start face at levels 0 to `rows.len() − 1`.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FaceHomologyStep {
    /// One row per level, from level 0.
    pub rows: Vec<FaceRow>,
}

/// The cells, components and holes of a face's complex at one level.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FaceRow {
    /// The level.
    pub level: u64,
    /// Cells (2-cells: the level-n sub-faces).
    pub faces: u64,
    /// Edges (1-cells).
    pub edges: u64,
    /// Corners (0-cells).
    pub corners: u64,
    /// χ = corners − edges + faces.
    pub euler: i64,
    /// b0: connected components.
    pub components: u64,
    /// b1: holes (lacunas and closed gaps).
    pub holes: u64,
}
