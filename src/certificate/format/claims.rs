//! What a claim states: start faces and their edges, substitutions, hand-written automata
//! (states, operators, words, attractor), volumes and the faces they share.

use super::Algebraic;
use serde::{Deserialize, Serialize};

/// The claim about faces: the start faces (canonical form, one per start face, repeated for
/// equal faces) and how the constraint system is generated (THEORY §6).
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FacesClaim {
    /// The start faces, each in canonical rotation.
    pub faces: Vec<Face>,
    /// Bézier degree q of the `Bn` edges (m = q + 1 control points).
    pub degree: usize,
    /// Cantor layout: the length of a gap relative to the length of a piece (a rational > 0).
    pub cantor_gap: String,
    /// The sides glued together in an assembly of start faces (none for one face; omitted from
    /// the JSON when empty). Only `face-homology` reads them: the closure, the system and the
    /// ratio are those of the start faces whatever their gluing.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub glue: Vec<GluedSides>,
}

/// Two sides of start faces glued together: `[face, side]` each, the face an index into
/// [`FacesClaim::faces`] and the side an index into its boundary (canonical rotation). The two
/// sides are one edge read in opposite directions, as the sides two faces of the same orientation
/// share.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GluedSides {
    /// The first side, `[face, side]`.
    pub a: [usize; 2],
    /// The second side, `[face, side]`, read against the first.
    pub b: [usize; 2],
}

/// `B` (connected) or `C` (Cantor-like).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
pub enum Kind {
    /// Bézier-like, `Bn`.
    B,
    /// Cantor-like, `Cn`.
    C,
}

/// An edge type `Kn^delay`. The derived order (kind, n, delay) is the canonical order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Edge {
    /// `B` or `C`.
    pub kind: Kind,
    /// Number of sub-edges (≥ 2).
    pub n: u32,
    /// Delay (≥ 1).
    pub delay: u32,
}

/// `E = (Ea, El, Ec)`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Params {
    /// Adjacency edge.
    pub ea: Edge,
    /// Lacuna edge.
    pub el: Edge,
    /// Gap-closing edge.
    pub ec: Edge,
}

/// A pattern on an edge in a `corner(P,Q)` item.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", deny_unknown_fields)]
pub enum Pattern {
    /// `*`.
    Any,
    /// Every edge of this kind.
    Kind(Kind),
    /// Exactly this edge type.
    Exact(Edge),
}

/// One item of a spoke set (the algorithm).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SpokeItem {
    /// Every joint.
    Joint,
    /// Every gap.
    Gap,
    /// Every corner.
    Corner,
    /// Every corner next to a delayed edge.
    DelayedCorner,
    /// Every corner next to a delayed edge where neither edge is a non-delayed `Bn` (AutoFrac2D's
    /// algorithm 1).
    DelayedCornerNotB,
    /// Corners from an edge matching the first pattern to one matching the second.
    CornerBetween(Pattern, Pattern),
}

/// A face `F^d(∂, E, A)` with the algorithm as its spoke items.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Face {
    /// Boundary, counter-clockwise.
    pub boundary: Vec<Edge>,
    /// E.
    pub params: Params,
    /// A: a junction is a spoke when one item holds.
    pub algorithm: Vec<SpokeItem>,
    /// d ≥ 1.
    pub delay: u32,
}

/// A substitution: `matrix[t]` lists `(s, k)`, a face of type `t` has `k` sub-faces of type
/// `s` (repeated pairs add up); lacunas of one step of each type in halves; start faces
/// `(type, multiplicity)` (repeated types add up).
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SubstitutionClaim {
    /// The rows of the substitution matrix.
    pub matrix: Vec<Vec<(usize, u64)>>,
    /// Lacunas contributed by one step of each type, in halves.
    pub contribution_halves: Vec<u64>,
    /// Start faces `(type, multiplicity)`.
    pub start: Vec<(usize, u64)>,
}

/// A hand-written automaton (THEORY §6): states, operators (known matrices or unknown),
/// constraints (equalities of words) and the operators whose columns sum to 1.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AutomatonClaim {
    /// The states: name and dimension (number of control points).
    pub states: Vec<AutomatonState>,
    /// The operators, in order; the unknown entries are numbered operator by operator, row by
    /// row.
    pub operators: Vec<AutomatonOperator>,
    /// The constraints `lhs = rhs`.
    pub constraints: Vec<WordEquation>,
    /// Operators whose every column sums to 1.
    pub barycentric: Vec<usize>,
    /// The real number field K = Q(α) of the entries given outside Q (`None`: every given entry
    /// is rational). Coordinates of elements of K are on the power basis `1, α, α², …`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub field: Option<Algebraic>,
    /// The modelling of the attractor (`None` for an automaton that is only a constraint
    /// system): the start state, its control points and the subdivision operators.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub attractor: Option<AttractorClaim>,
    /// The rule text the automaton was compiled from (`None`: written by hand); the
    /// `rule-compilation` step compiles it again.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rule: Option<String>,
}

/// What an automaton's attractor is built from: the control graph has one edge `q → w` per
/// subdivision operator `T: q ← w`; the attractor of the start state is drawn from its control
/// points.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AttractorClaim {
    /// The start state.
    pub start: usize,
    /// The control points of the start state: one row of coordinates (in K) per point, each
    /// of the modelling space's dimension (2 or 3).
    pub points: Vec<Vec<FieldCoords>>,
    /// The subdivision operators, by index, increasing.
    pub subdivision: Vec<usize>,
}

/// A state of an automaton.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AutomatonState {
    /// Name.
    pub name: String,
    /// Dimension m.
    pub dim: usize,
}

/// An operator from state `from` (columns) into state `to` (rows).
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AutomatonOperator {
    /// Name.
    pub name: String,
    /// Row state.
    pub to: usize,
    /// Column state.
    pub from: usize,
    /// The matrix (rows of rationals), or `None` when unknown or given in the field.
    pub value: Option<Vec<Vec<String>>>,
    /// The matrix given in the claim's field K (rows of coordinates), when its entries are not
    /// all rational; `value` is then `None`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub field_value: Option<Vec<Vec<FieldCoords>>>,
}

/// A factor of a word.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", deny_unknown_fields)]
pub enum WordFactor {
    /// An operator, by index.
    Op(usize),
    /// A literal matrix (rows of rationals).
    Literal(Vec<Vec<String>>),
}

/// A constraint `lhs = rhs` between two words (products of factors, left to right).
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WordEquation {
    /// Left word.
    pub lhs: Vec<WordFactor>,
    /// Right word.
    pub rhs: Vec<WordFactor>,
}

/// An element of Q(ρ): coordinates on the power basis `1, ρ, ρ², …`.
pub type FieldCoords = Vec<String>;

/// The claim about volumes: the start volumes, each as its boundary surface (faces glued edge
/// to edge) with G, E, A, rule and delay.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VolumesClaim {
    /// The start volumes.
    pub volumes: Vec<Volume>,
    /// The counts are certified at levels 0 to `levels`.
    pub levels: u64,
    /// The faces two start volumes share (a 3D assembly); none for volumes apart. They matter
    /// to the level-n solid (`solid-homology`) and to the constraints (`volume-solution-space`);
    /// counts and the limit ratio are those of the volumes apart.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub shared: Vec<SharedFaceClaim>,
}

/// Two start volumes sharing a face: edge `a[2]` of face `a[1]` of volume `a[0]` lies on edge
/// `b[2]` of face `b[1]` of volume `b[0]`, traversed the other way; then edge `a[2] + k` lies on
/// edge `b[2] − k`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SharedFaceClaim {
    /// (volume, face, edge) on one side.
    pub a: [usize; 3],
    /// (volume, face, edge) on the other side.
    pub b: [usize; 3],
}

/// A volume `V(S, G, E, A, rule, d)`: its boundary surface S as faces read counter-clockwise
/// from outside, edge `i` of face `f` glued to edge `j` of face `g` when `glue[f][i] = (g, j)`.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Volume {
    /// The faces of S.
    pub faces: Vec<Face>,
    /// `glue[f][i] = (g, j)`.
    pub glue: Vec<Vec<(usize, usize)>>,
    /// Er: the radial edge type created inside.
    pub radial: Edge,
    /// Ei: the inner edge type created inside.
    pub inner: Edge,
    /// E of the faces created inside.
    pub params: Params,
    /// A of the faces created inside (spoke items).
    pub algorithm: Vec<SpokeItem>,
    /// The volume rule.
    pub rule: VolumeRule,
    /// d ≥ 1.
    pub delay: u32,
}

/// The volume rule: which sub-face edges are spoke edges (THEORY §10).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
pub enum VolumeRule {
    /// Every Ea edge of every face.
    V1,
    /// V1 and every sub-edge lying on an edge of the surface.
    V2,
}
