//! Certificates: plain data that the independent checker (`checker/`) re-verifies.
//!
//! A [`Certificate`] is a versioned [`Claim`] (the input in canonical form, which `lacuna check`
//! prints first) and the list of [`Step`]s that prove every verdict about it, in the fixed order
//! the claim demands. Every number is exact: integers as JSON
//! numbers when they are small counts or indices, rationals and big integers as strings
//! (`"3"`, `"-1/2"`). Only `Vec` and ordered structures are used, so the same certificate always
//! serialises to the same bytes. The format, with the justification of every step, is documented
//! in `docs/CERTIFICATES.md`.
//!
//! This module depends on nothing else of lacuna (the checker must not trust lacuna's code), only
//! on serde.

use serde::{Deserialize, Serialize};

/// The value of [`Certificate::format`].
pub const FORMAT: &str = "lacuna-certificate";

/// The format version this code writes and checks.
pub const VERSION: u32 = 10;

/// A certificate: the claim (what was given, in canonical form) and the steps that prove every
/// verdict about it.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Certificate {
    /// Always [`FORMAT`].
    pub format: String,
    /// Always [`VERSION`] for this code.
    pub version: u32,
    /// A label for people (the library name, file or notation the user typed). Not checked and
    /// not part of the claim: what is certified is [`Certificate::claim`].
    pub input: String,
    /// What the certificate is about, in canonical form; `lacuna check` prints it first.
    pub claim: Claim,
    /// The steps, in the fixed order the claim demands (see [`Claim`]); each is tied to the
    /// claim or to the closure step.
    pub steps: Vec<Step>,
}

/// The claim of a certificate: the input, in canonical form. It fixes which steps a complete
/// certificate has, in this order:
///
/// - faces ([`Claim::Faces`]) need `closure`, then `solution-space` or `inconsistent`, may have
///   `degeneracy` (after `solution-space`), then need `limit-ratio`, and may have
///   `face-homology` after them (one start face);
/// - an automaton ([`Claim::Automaton`]) or a system ([`Claim::System`]) needs
///   `solution-space` or `inconsistent`;
/// - a substitution ([`Claim::Substitution`]) needs `limit-ratio`;
/// - volumes ([`Claim::Volumes`]) need `volume-closure`, then `limit-ratio` (lacunas in
///   quarters), and may have `solid-homology` after them.
///
/// A certificate whose steps are a proper part of that sequence (in order, the closure present
/// for faces) is *partial*: what it has is checked, but it proves less than the claim.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", deny_unknown_fields)]
pub enum Claim {
    /// Start faces and the options of THEORY §6: the closure's start types are these faces, the
    /// system is the one THEORY §6 generates with this degree and Cantor ratio.
    Faces(FacesClaim),
    /// A hand-written automaton: the checker rebuilds its linear system from the states,
    /// operators and words.
    Automaton(AutomatonClaim),
    /// A substitution given as a matrix (no faces): only its limit ratio is certified.
    Substitution(SubstitutionClaim),
    /// An explicit linear system: its solution space or inconsistency is certified.
    System(System),
    /// Start volumes (THEORY §10): their closure, exact counts and limit ratio are certified.
    Volumes(VolumesClaim),
}

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

/// The volume rule: which sub-face edges are spoke edges (THEORY §10).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
pub enum VolumeRule {
    /// Every Ea edge of every face.
    V1,
    /// V1 and every sub-edge lying on an edge of the surface.
    V2,
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

/// The closure of volume types and the counts of the start volumes.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VolumeClosureStep {
    /// The volume types (the claim's start volumes are among them, in any form).
    pub types: Vec<VolumeTypeRule>,
    /// The counts from level 0.
    pub counts: Vec<VolumeCount>,
}

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

/// The automaton is the compilation of the claim's rule text (no data: the checker compiles it).
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RuleCompilationStep {}

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

/// One step of a certificate. Each variant says what the checker re-derives and why that proves
/// the claim; consumers match it exhaustively.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(tag = "step", rename_all = "kebab-case", deny_unknown_fields)]
pub enum Step {
    /// **The closure.** Justification: the checker re-derives the subdivision of every listed face
    /// type with its own implementation of THEORY §3 (sub-edges, junctions, the spoke predicate,
    /// runs between spokes, `Ec Ec` inside runs, `[Ec] Ea El Ea [Ec]`, delayed faces, canonical
    /// rotation) and compares sub-faces, origins and adjacencies with the certificate; every
    /// referenced type must be listed, so the listed set is closed under subdivision. It checks
    /// the incidence identities on the certificate's own data (each sub-edge once, each gap side
    /// once, each spoke once inward and once outward and paired by an adjacency, one lacuna side
    /// per sub-face) and the contribution of THEORY §5.
    Closure(ClosureStep),
    /// **A consistent linear system and its solution space.** The checker first rebuilds the
    /// system from the claim — THEORY §6 from the proved closure step (unknowns matched by the
    /// recipe's names), or the claimed automaton's words, or the claimed system — and requires
    /// the rows to be exactly the rebuilt ones.
    /// Justification: the particular
    /// solution satisfies every row; every basis vector satisfies the homogeneous rows and is 1 at
    /// its own free unknown and 0 at the others (so the basis is independent: nullity ≥ dof); the
    /// pivot minor is nonsingular (elimination modulo a prime; a nonzero determinant mod p is
    /// nonzero over Q: rank ≥ |pivots|); and |pivots| + dof = unknowns. Hence rank = |pivots| and
    /// the basis spans the kernel: the solution set is exactly `particular + span(basis)`.
    SolutionSpace(SolutionStep),
    /// **An inconsistent linear system** (tied to the claim, as above).
    /// Justification: `Σ m_i·row_i` has every coefficient 0
    /// and right-hand side `c ≠ 0`; any solution would satisfy `0 = c`.
    Inconsistent(ConflictStep),
    /// **The forced collapses of the level-1 complexes** (THEORY §6), after a proved
    /// `solution-space` step. Justification: the checker builds the level-1 complex of every
    /// listed face type with its own subdivision (the cells of `face-homology`), takes each
    /// corner's coordinates — the column of the sub-face operator that picks it, as unknowns of
    /// the proved system — and their affine expressions `particular + Σ t_j·basis_j` on the
    /// proved solution set. Two corners coincide on every solution exactly when their
    /// expressions are equal; the classes of such corners must be exactly the listed pairs'. The
    /// flat cells (a face of two Cantor edges, a two-sided lacuna whose sides are Cantor edges)
    /// are re-derived from the types and must be exactly the listed ones. An empty step proves
    /// that no forced collapse exists.
    Degeneracy(DegeneracyStep),
    /// **The limit ratio R** (every case: shared radii, periodic classes, ρ = 1) of the closure's
    /// substitution, the volume closure's (lacunas in quarters) or the claimed matrix. Justification: the checker recomputes the classes reached from the start and their periods, isolates ρ
    /// (Sturm), and checks per class a positive Perron eigenvector for ρ or a Collatz–Wielandt
    /// bound below ρ. By Perron–Frobenius the eigenvalues of the augmented matrix
    /// `A = [[M, c], [0, 1]]` of modulus `σ = max(ρ, 1)` are `σ·ω`, `ω^P = 1`, with `P` the lcm
    /// of the dominant periods, so for each residue `r` the generating function of
    /// `X_(P·n + r)` (faces, lacunas) has a single dominant pole, at `w₀ = σ^(−P)`. The checker
    /// computes the characteristic polynomial of `A^P` (Faddeev–LeVerrier, Newton), the
    /// numerators from the counts, the pole orders and leading coefficients in Q(ρ) with exact
    /// zero tests, and each `R_r`; the limit exists iff they agree.
    LimitRatio(RatioStep),
    /// **The closure of volumes and their counts** (THEORY §10). Justification: the checker
    /// checks that every listed type's surface is a sphere, identifies types by its own canonical
    /// code (orientation-preserving isomorphism of oriented maps with typed faces, plus G, E, A,
    /// rule and delay), re-derives one step of every listed type with its own code (the faces'
    /// subdivision of THEORY §3, the pairing of the level-1 surface, the patches cut along the
    /// rule's spoke edges, each patch a disk, the side and inner faces, caps for a delayed
    /// volume) and requires the derived sub-volumes to be exactly the listed children; the start
    /// volumes must be listed types. Then it recounts N^C and N^L level by level from the derived
    /// children and its own contributions and compares every listed count.
    VolumeClosure(VolumeClosureStep),
    /// **The topology of the level-n solid** (THEORY §10) at the listed levels. Justification:
    /// the checker builds the solid cell by cell from the claim's volumes with its own one-step
    /// subdivision: every edge cut into its pieces once, every face subdivided once in its own
    /// orientation and matched, piece by piece, with the sub-faces each volume reading it
    /// derives (from both sides of a shared face), the sub-volumes' side and inner faces and
    /// the radial and inner edges identified through the gluing of their surfaces, corners as
    /// the classes of edge ends joined around every face. It counts the cells, takes χ, b0 from
    /// the 1-skeleton, and the ranks of the boundary matrices over F2. A rank over F2 is at
    /// most the rank over Q, so the F2 Betti numbers bound the rational ones from above; with
    /// b3 = b2 = 0 over F2 and χ the same over every field, b1 over Q equals b1 over F2. Rows
    /// whose F2 b2 or b3 is not 0 are refused.
    SolidHomology(SolidHomologyStep),
    /// **The cells, χ and components of the level-n solid at every claimed level** (THEORY
    /// §10), and its voids and tunnels. Justification: every cell of level n + 1 is born inside
    /// one cell of level n, and
    /// what a cell creates depends only on its type. The checker derives the birth table itself
    /// from one step of small complexes with the code of `solid-homology`: a volume type's own
    /// complex (its sub-volumes are the proved closure's children; its interior faces, edges and
    /// corners are what its complex has beyond its subdivided surface), a face type's own
    /// complex (its sub-faces, the edges beyond its sides' pieces, the corners beyond the face's
    /// and its sides'), an edge type's pieces and the corners between them (read inside the
    /// faces that have it as a side). It counts level 0 on the complex of the claim's volumes and
    /// runs the recurrence in big integers. Components: when every volume type's level-1
    /// complex is connected, every level has the components of level 0. Voids: when no set of a
    /// face type's sub-faces has its boundary on the face's sides only, and a volume type's
    /// complex relative to its subdivided surface has no 2- or 3-dimensional homology over F2,
    /// every level past 0 has b2 = b3 = 0 (the exact sequence of the level's complex relative to
    /// its subdivided faces); then b1 = b0 − χ. See `docs/CERTIFICATES.md`.
    SolidRecurrence(SolidRecurrenceStep),
    /// **The solution space of the volume constraints** (THEORY §10). Justification: the checker checks the face closure of the surfaces as a
    /// `closure` step, checks every face frame and every sub-volume placement (an isomorphism of
    /// the sub-volume it derives onto the listed type, propagated through the gluing), rebuilds
    /// the whole system itself (faces as for `solution-space`, then the volume states, their
    /// incidences, spoke adjacencies and barycentric columns, and the faces the start volumes
    /// share read from both sides), and checks the particular
    /// solution and the basis against its own rows; the unknowns that are not free are shown
    /// independent by elimination modulo a prime. See `docs/CERTIFICATES.md`.
    VolumeSolutionSpace(VolumeSystemStep),
    /// **The topology of a face's level-n complex** (one start face). Justification: as for
    /// `solid-homology`, without volumes: the checker builds the complex from the claim's face
    /// (edges' pieces, sub-faces, spokes, lacuna and gap sides, corners), checks ∂∂ = 0 over F2,
    /// and takes b0 from the 1-skeleton and the rank of ∂2 over F2; with b2 = 0 over F2, b1 (the
    /// holes) over Q equals b1 over F2.
    FaceHomology(FaceHomologyStep),
    /// **Every cell of level 1 has area at a chosen point** (faces, after a proved
    /// `solution-space` step). Justification: the checker evaluates the point
    /// `particular + Σ t_j·basis_j` at the step's parameters (a point of the proved solution
    /// set), places every sub-face operator's columns in its parent type's frame (the sub-face's
    /// control points) and the sub-faces' lacuna sides, reversed and in side order (the central
    /// lacuna's), and computes each control polygon's signed area exactly (shoelace over Q): every
    /// one, and every frame, must be positive, and the counts and the smallest sub-face area must
    /// be the listed ones.
    LevelOne(LevelOneStep),
    /// **The automaton is its rule's compilation.** Justification: the checker reads the
    /// claim's rule text with its own parser (field line, initiator, generators, flags, age and
    /// random choices, `seed`, `depth`), compiles it with its own code (states, one per
    /// generator, age and occurrence above the depth with its own seeded SplitMix64 draws; one
    /// operator per fertile or drawn segment, the similitudes with their reflections in the
    /// frames of their states) and compares states, operators, matrices (exactly in K),
    /// barycentric operators, constraints and attractor with the claim.
    RuleCompilation(RuleCompilationStep),
    /// **Every constraint of an automaton holds** (every operator given, in Q or in the
    /// claim's field K). Justification: the checker multiplies out both words of every
    /// constraint and the column sums of every barycentric operator in K and compares them
    /// exactly (reduction modulo the field's polynomial, an exact zero test at α).
    ConstraintsHold(ConstraintsHoldStep),
    /// **A constraint of an automaton fails** (every operator given). Justification: the
    /// checker evaluates the named constraint's two words (or the named barycentric operator's
    /// column sums) exactly in K and finds them different.
    ConstraintFails(ConstraintFailsStep),
    /// **Every infinite walk of the control graph contracts** (the attractor is defined).
    /// Justification: the operators of the instance (the claim's values, the step's values for
    /// the unknown ones, which must satisfy every constraint) are barycentric, so each maps the
    /// differences of points into the differences; the listed walks form, from every reachable
    /// state, a complete prefix code of the control graph (every infinite walk from that state
    /// starts with exactly one of them); and the product of each walk, restricted to the
    /// differences, has induced norm below 1, computed exactly in K. Every infinite walk is then
    /// a concatenation of listed walks, and its products tend to 0.
    Contraction(ContractionStep),
    /// **The similarity dimension** s (Mauldin–Williams) of every cyclic strongly connected
    /// part of the control graph, and of the attractor (their largest). Justification: the
    /// checker rebuilds the frames of the states (the start points, then `F_w = F_q·T` along the
    /// first operator reaching w breadth first), checks that each operator of a part is a
    /// similitude of the claimed squared ratio `σ^k` on those frames (Gram matrices, exactly in
    /// K), builds `D(u) = det(I − M(u))` with `M(u)_(q,w) = Σ u^k`, and checks by Sturm counts
    /// that the claimed `u*` is the smallest root of D in (0, 1]; then `ρ(M(u*)) = 1` and
    /// `s = 2·ln u*/ln σ`. The decimal digits are re-derived from enclosures of logarithms.
    SimilarityDimension(SimilarityStep),
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

/// The closure: every face type with its rule, and the start types.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ClosureStep {
    /// The face types. The start types are not listed: they are the claim's faces.
    pub types: Vec<TypeRule>,
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

/// Where a face of a sub-volume lies on its type's surface: `(face, rotation)`.
pub type Seat = (usize, usize);

/// A side of the level-1 surface of a volume: `(face, sub-face, position)`.
pub type LevelOneSide = (usize, usize, usize);

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

/// An element of Q(ρ): coordinates on the power basis `1, ρ, ρ², …`.
pub type FieldCoords = Vec<String>;

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

impl Certificate {
    /// A certificate of the current format and version with no step yet.
    pub fn new(input: impl Into<String>, claim: Claim) -> Self {
        Certificate {
            format: FORMAT.to_string(),
            version: VERSION,
            input: input.into(),
            claim,
            steps: Vec::new(),
        }
    }

    /// The canonical JSON text (compact, one trailing newline): the same certificate always
    /// gives the same bytes.
    pub fn to_json(&self) -> String {
        serde_json::to_string(self).expect("a certificate serialises") + "\n"
    }

    /// Parses a certificate from JSON.
    pub fn from_json(text: &str) -> Result<Self, serde_json::Error> {
        serde_json::from_str(text)
    }
}

impl Step {
    /// The step's name as used in messages and in the JSON `step` tag.
    pub fn name(&self) -> &'static str {
        match self {
            Step::Closure(_) => "closure",
            Step::SolutionSpace(_) => "solution-space",
            Step::Inconsistent(_) => "inconsistent",
            Step::Degeneracy(_) => "degeneracy",
            Step::LimitRatio(_) => "limit-ratio",
            Step::VolumeClosure(_) => "volume-closure",
            Step::SolidHomology(_) => "solid-homology",
            Step::SolidRecurrence(_) => "solid-recurrence",
            Step::VolumeSolutionSpace(_) => "volume-solution-space",
            Step::FaceHomology(_) => "face-homology",
            Step::LevelOne(_) => "level-one",
            Step::RuleCompilation(_) => "rule-compilation",
            Step::ConstraintsHold(_) => "constraints-hold",
            Step::ConstraintFails(_) => "constraint-fails",
            Step::Contraction(_) => "contraction",
            Step::SimilarityDimension(_) => "similarity-dimension",
        }
    }
}
