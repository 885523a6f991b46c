//! The steps about linear systems and limit ratios: a system and its solution space or conflict,
//! and the limit ratio with its class claims and witnesses.

use super::FieldCoords;
use serde::{Deserialize, Serialize};

/// An explicit linear system over Q.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct System {
    /// Where the system comes from, for people (not checked).
    pub source: String,
    /// Number of unknowns.
    pub unknowns: usize,
    /// The equations.
    pub rows: Vec<Row>,
    /// How the system is generated from the closure step (THEORY §6), for systems of face
    /// closures; the checker rebuilds the system from the closure and requires the rows above to
    /// be exactly the rebuilt ones. `None` for a hand-written automaton: the system as given.
    pub recipe: Option<Recipe>,
}

/// A sparse linear equation `Σ coef·x[var] = rhs`, rationals as strings.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Row {
    /// `(unknown, coefficient)`; an unknown may repeat (coefficients add up).
    pub terms: Vec<(usize, String)>,
    /// Right-hand side.
    pub rhs: String,
}

/// The recipe of a system generated from a closure (THEORY §6): the degree and Cantor ratio are
/// the claim's, the recipe names the columns.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Recipe {
    /// The name of every unknown, in column order: entry `[r][c]` of the sub-face operator `k`
    /// of face type `t` is `T<t>.T<k>[r][c]`.
    pub unknowns: Vec<String>,
}

/// The solution space of a consistent system.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolutionStep {
    /// The system.
    pub system: System,
    /// A solution, sparse: unknowns not listed are 0.
    pub particular: Vec<(usize, String)>,
    /// The free unknowns, one per basis vector.
    pub free: Vec<usize>,
    /// Sparse basis vectors of the kernel; `basis[k]` is 1 at `free[k]`, 0 at the other free
    /// unknowns.
    pub basis: Vec<Vec<(usize, String)>>,
    /// Rank witness: `(row, unknown)` pairs, in elimination order.
    pub pivots: Vec<(usize, usize)>,
    /// The claimed rank.
    pub rank: usize,
    /// The claimed degrees of freedom (dimension of the solution space).
    pub dof: usize,
}

/// The proof that a system has no solution.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConflictStep {
    /// The system.
    pub system: System,
    /// `(row, multiplier)`.
    pub multipliers: Vec<(usize, String)>,
    /// `Σ m_i·rhs_i`, claimed nonzero.
    pub constant: String,
}

/// The limit ratio of the substitution: the closure's (faces) or the claim's (a matrix).
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RatioStep {
    /// The classes reached from the start, ordered by smallest member, with radius witnesses.
    pub classes: Vec<ClassClaim>,
    /// ρ, the largest class radius (at least 1).
    pub rho: Algebraic,
    /// `P`: the lcm of the periods of the classes of radius ρ.
    pub period: u64,
    /// Whether `R_i` converges (all points equal).
    pub exists: bool,
    /// The number of decimals of every point (each `decimal` has exactly this many).
    pub digits: usize,
    /// `lim R_(P·n + r)` for `r = 0 … P − 1`.
    pub points: Vec<PointClaim>,
}

/// A strongly connected class of the types reached from the start, with the witness of its
/// spectral radius.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ClassClaim {
    /// Members, ascending.
    pub members: Vec<usize>,
    /// Gcd of the cycle lengths; `None` for a transient type (no cycle).
    pub period: Option<u64>,
    /// Why its spectral radius is ρ, below ρ, or 0.
    pub radius: RadiusWitness,
}

/// The witness of a class's spectral radius against ρ.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum RadiusWitness {
    /// A transient type (no cycle): its block is `[0]`.
    Transient,
    /// A dominant class: a left eigenvector `y > 0` of its block `B` for ρ (`y·B = ρ·y`), aligned
    /// with the members, coordinates in Q(ρ). By Perron–Frobenius the radius of `B` is ρ.
    Perron(Vec<FieldCoords>),
    /// A smaller class: a rational `x > 0` aligned with the members with `B·x < lo·x`
    /// componentwise (Collatz–Wielandt: the radius of `B` is below `lo ≤ ρ`).
    Below(Vec<String>),
}

/// A real algebraic number: the only root of `poly` in `[lo, hi]`.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Algebraic {
    /// Integer coefficients, constant term first.
    pub poly: Vec<String>,
    /// Lower end (rational).
    pub lo: String,
    /// Upper end (rational); equal to `lo` for a rational number.
    pub hi: String,
}

/// The claimed limit of `R_(P·n + r)` for one residue `r`.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PointClaim {
    /// The value in Q(ρ).
    pub value: FieldCoords,
    /// The same number as a root of its minimal polynomial, isolated (for people and other
    /// tools; the checker verifies that the polynomial vanishes there and isolates it).
    pub real: Algebraic,
    /// Decimal digits, truncated: `decimal ≤ value < decimal + 10^(−digits)`.
    pub decimal: String,
}
