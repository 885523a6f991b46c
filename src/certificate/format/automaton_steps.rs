//! The steps about hand-written automata: a rule's compilation, constraints that hold or fail,
//! contraction, the similarity dimension and its open-set witnesses (neighbour maps), the
//! boundary dimension of tiles, seed 002's multiplicity level by level.

use super::{Algebraic, FieldCoords};
use serde::{Deserialize, Serialize};

/// The automaton is the compilation of the claim's rule text (no data: the checker compiles it).
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RuleCompilationStep {}

/// The step `constraints-hold`: no data, the claim has everything.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConstraintsHoldStep {
    /// How many constraints the claim has (a cross-check for people).
    pub constraints: usize,
}

/// The step `constraint-fails`: exactly one of the two fields is given.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConstraintFailsStep {
    /// The index of a constraint whose two words differ.
    pub constraint: Option<usize>,
    /// The index of an operator listed barycentric whose columns do not all sum to 1.
    pub barycentric: Option<usize>,
}

/// The step `contraction`.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContractionStep {
    /// The values of the claim's unknown operators in the instance that is drawn (by operator
    /// index, coordinates in K); an operator the claim gives is not repeated here.
    pub instance: Vec<(usize, Vec<Vec<FieldCoords>>)>,
    /// The induced norm: `inf` (max row sum) or `1` (max column sum).
    pub norm: String,
    /// The walks, each a non-empty list of subdivision operators `T1, T2, …` with
    /// `T_(i+1)`'s row state the column state of `T_i`; the walks from one state are a
    /// complete prefix code.
    pub walks: Vec<Vec<usize>>,
}

/// One cyclic strongly connected part of the control graph and its similarity dimension.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SimilarityPart {
    /// The part's states, increasing.
    pub states: Vec<usize>,
    /// σ ∈ (0, 1) in K: every squared ratio of the part is a power of it.
    pub sigma: FieldCoords,
    /// Each operator inside the part (row and column state in the part) with the exponent k
    /// of its squared ratio `σ^k`, by operator index, increasing (0 for ratio 1: the operator
    /// that first reaches a state fixes that state's frame; those must form no cycle).
    pub exponents: Vec<(usize, u32)>,
    /// `u*`, the smallest root of `det(I − M(u))` in (0, 1].
    pub u: Algebraic,
    /// `s` when it is rational (`u*^(2b) = σ^a` for `s = a/b`), else `None`.
    pub rational: Option<String>,
    /// u* as an element of K, when it is one and irrational (`s = 2j` with `u* = σ^j`): the
    /// checker then compares `u*^(2b)` with `σ^a` in K.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub u_field: Option<FieldCoords>,
    /// A witness of the open-set condition: for every state of the part, in order, a convex
    /// polygon in the state's chart (the barycentric coordinates `x ↦ (1 − Σx, x)` of its
    /// control points: 2 coordinates for 3 points, 1 for 2 points), its vertices
    /// counter-clockwise (in one dimension: the two ends, increasing).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub open_set: Option<Vec<Vec<Vec<FieldCoords>>>>,
    /// The other witness of the open-set condition (never given with `open_set`): the
    /// neighbour maps of the part (Bandt–Graf), a finite set closed under refinement without
    /// the identity; or two words with the same map, a witness that the condition fails.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub neighbour_maps: Option<NeighbourMaps>,
}

/// The open-set condition of a part decided by its neighbour maps `h = g_u⁻¹ ∘ g_v` (words u,
/// v of the part's operators from one state with different first operators; `g_e` the map of
/// the operator `e: q ← w` from w's coordinates to q's).
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", deny_unknown_fields)]
pub enum NeighbourMaps {
    /// The condition holds: a finite set of neighbour maps, closed under refinement, without the
    /// identity.
    Holds(NeighbourHolds),
    /// The condition fails: two words whose maps are equal.
    Fails(NeighbourFails),
}

/// The witness that the open-set condition holds.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NeighbourHolds {
    /// The coordinates of every state: `charts` (the barycentric coordinates of its control
    /// points) or `drawing` (the plane, through the state's frame
    /// `E_q(y) = P_0 + (P_1 − P_0, P_2 − P_0)·y`).
    pub coordinates: String,
    /// The centre `c_q` of every state of the part, in order, in its coordinates.
    pub centres: Vec<Vec<FieldCoords>>,
    /// The common radius R > 0 (rational): every attractor `A_q` lies in `B(c_q, R)`.
    pub radius: String,
    /// The margin μ > 0 (rational) of the ball test `|h(c_r) − c_q| ≤ R + ρ(h)·R + μ`.
    pub margin: String,
    /// The maps of the set.
    pub maps: Vec<NeighbourMap>,
    /// Positive rational scales `c_q`, one per state of the part in order, when the coordinates
    /// are rescaled: state q's coordinates are multiplied by `c_q`, so an operator `q ← w`
    /// becomes `x ↦ c_q·g(x/c_w)` (ratio `ρ·c_q/c_w`). Chosen so that every operator contracts
    /// when one alone does not (an identity between two states, THEORY §6); absent: all 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scales: Option<Vec<String>>,
}

/// One neighbour map `h: x ↦ A·x + b` from state r's coordinates to state q's.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NeighbourMap {
    /// The state (index) h maps into: the end of the word u.
    pub q: usize,
    /// The state (index) h maps from: the end of the word v.
    pub r: usize,
    /// The linear part, `d × d` row-major.
    pub a: Vec<FieldCoords>,
    /// The translation.
    pub b: Vec<FieldCoords>,
}

/// The witness that the open-set condition fails.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NeighbourFails {
    /// The first word (operator indices, each starting where the previous one ends).
    pub u: Vec<usize>,
    /// The second word, from the same state, with another first operator, to the same end.
    pub v: Vec<usize>,
}

/// The step `similarity-dimension`.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SimilarityStep {
    /// The instance, as in [`ContractionStep::instance`].
    pub instance: Vec<(usize, Vec<Vec<FieldCoords>>)>,
    /// Every cyclic strongly connected part reachable from the start, ordered by smallest state.
    pub parts: Vec<SimilarityPart>,
    /// The number of decimal digits of `decimal`.
    pub digits: usize,
    /// The largest part's s, truncated: `decimal ≤ s < decimal + 10^(−digits)`.
    pub decimal: String,
}

/// The step `boundary-dimension`: an upper bound of the dimension of the set where the pieces
/// of each state's attractor touch, for the states of the tile parts.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoundaryStep {
    /// One entry per tile part, by increasing part index.
    pub parts: Vec<BoundaryPart>,
    /// The number of decimal digits of every state's `decimal`.
    pub digits: usize,
}

/// The boundary graph of one tile part.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoundaryPart {
    /// The part's index in the `similarity-dimension` step (its s must be exactly 2).
    pub part: usize,
    /// The neighbour maps whose refinements form the graph, when that part's open-set witness
    /// is not neighbour maps; absent: the part's own neighbour maps. Either way the checker
    /// proves them closed under refinement, without the identity.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub maps: Option<NeighbourHolds>,
    /// Every cyclic strongly connected component of the graph of refinements (nodes are the
    /// maps, in their order), ordered by smallest node.
    pub components: Vec<BoundaryComponent>,
    /// Every state of the part, in order.
    pub states: Vec<BoundaryState>,
}

/// One cyclic strongly connected component of the boundary graph and its value.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoundaryComponent {
    /// Its nodes (map indices), increasing.
    pub nodes: Vec<usize>,
    /// The class of every node in an equitable partition: nodes of one class have, class by
    /// class, the same exponents on their edges inside the component.
    pub classes: Vec<usize>,
    /// `u*`, the smallest root in (0, 1] of `det(I − Q(u))`, `Q` the quotient matrix.
    pub u: Algebraic,
    /// The value `2·ln u*/ln σ` when it is rational, else `None`.
    pub rational: Option<String>,
}

/// One state's claimed bound.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoundaryState {
    /// The component of largest value reachable from the maps with the state on either side;
    /// `None` when no cyclic component is reachable (the value is 0).
    pub component: Option<usize>,
    /// The value, truncated to the step's digits.
    pub decimal: String,
}

/// The step `multiplicity` (seed 002, eq. (18)): the pieces of the start state's levels 1 to n,
/// grouped by their exact map.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MultiplicityStep {
    /// The values of the claim's unknown operators in the instance (as in `contraction`).
    pub instance: Vec<(usize, Vec<Vec<FieldCoords>>)>,
    /// For a claim with a field: an odd prime q, not dividing the leading coefficient of the
    /// field's polynomial, modulo which that polynomial is irreducible — so it is irreducible
    /// over Q and the reduced coordinates of an element of K are canonical.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub prime: Option<u64>,
    /// Level by level from 1: for each m (increasing), how many distinct maps — a state and
    /// the product of the word's operators — are exactly m pieces of the level.
    pub levels: Vec<Vec<(usize, u64)>>,
}
