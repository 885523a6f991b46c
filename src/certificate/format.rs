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
//!
//! The certificate and its claim and steps are here; the types they hold, one file per part of
//! the format: `format/claims.rs` (what a claim states: faces, substitutions, automata,
//! volumes), `format/face_steps.rs` (the closure of faces, degeneracy, level one, face homology),
//! `format/system_steps.rs` (linear systems, solutions and conflicts, the limit ratio),
//! `format/volume_steps.rs` (volume closure, volume system, the solid's homology) and
//! `format/automaton_steps.rs` (rules, constraints, contraction, similarity dimension, open-set
//! witnesses).

mod automaton_steps;
mod claims;
mod face_steps;
mod system_steps;
mod volume_steps;

pub use automaton_steps::{
    BoundaryComponent, BoundaryPart, BoundaryState, BoundaryStep, ConstraintFailsStep,
    ConstraintsHoldStep, ContractionStep, MultiplicityStep, NeighbourFails, NeighbourHolds,
    NeighbourMap, NeighbourMaps, RuleCompilationStep, SimilarityPart, SimilarityStep,
};
pub use claims::{
    AttractorClaim, AutomatonClaim, AutomatonOperator, AutomatonState, Edge, Face, FacesClaim,
    FieldCoords, GluedSides, Kind, Params, Pattern, SharedFaceClaim, SpokeItem, SubstitutionClaim,
    Volume, VolumeRule, VolumesClaim, WordEquation, WordFactor,
};
pub use face_steps::{
    Adjacency, ClosureStep, DegeneracyStep, FaceHomologyStep, FaceRow, LevelOneSide, LevelOneStep,
    Origin, Seat, SubFace, TypeRule,
};
pub use system_steps::{
    Algebraic, ClassClaim, ConflictStep, PointClaim, RadiusWitness, RatioStep, Recipe, Row,
    SolutionStep, System,
};
pub use volume_steps::{
    SolidCountRow, SolidHomologyStep, SolidRecurrenceStep, SolidRow, SubVolumePlacement,
    VolumeClosureStep, VolumeCount, VolumeSystemStep, VolumeTypeRule,
};

use serde::{Deserialize, Serialize};

/// The value of [`Certificate::format`].
pub const FORMAT: &str = "lacuna-certificate";

/// The format version this code writes and checks.
pub const VERSION: u32 = 13;

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
///   `face-homology` after them (the start faces glued as the claim says);
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
    /// **The topology of the start faces' level-n complex** (one face, or an assembly glued along
    /// the claim's sides). Justification: as for `solid-homology`, without volumes: the checker
    /// builds the complex from the claim's faces, each glued side one edge with its partner
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
    /// **An upper bound of the boundary dimension** of every state of a tile part (a part of
    /// similarity dimension exactly 2 in the plane): the dimension of the set where the pieces
    /// of the state's attractor touch other pieces. Justification: the checker re-derives the
    /// part's σ, exponents and `s = 2` as the similarity-dimension step does, proves the
    /// open-set condition with the neighbour maps (a finite set closed under refinement,
    /// without the identity, so the attractors are tiles) and rebuilds the graph of their
    /// refinements that pass the ball test; each kept map's set `B_h` is covered by the sets of
    /// its children, mapped back with the refining operator's ratio (left) or 1 (right), so the
    /// Mauldin–Williams value of the strongly connected components reachable from a state's
    /// maps bounds the dimension. It checks the components, an equitable partition of each
    /// (whose quotient has the same spectral radius), `u*` the smallest root of
    /// `det(I − Q(u))` in (0, 1], that the claimed component's `u*` is the smallest over the
    /// components reachable from the state (Sturm counts on their product), and the digits.
    BoundaryDimension(BoundaryStep),
    /// **Seed 002's multiplicity at levels 1 to n** (eq. (18)): how many pieces of a level are
    /// one exact map. Justification: the checker completes the instance (every constraint
    /// holding), enumerates the pieces of the start state level by level with its own code — a
    /// piece is a state and the product `T_1·T_2·…·T_k` of the subdivision operators of its
    /// word, each `T_(i+1)` into the state `T_i` comes from — groups the pieces whose state and
    /// product are equal (exactly in K, entries reduced modulo the field's polynomial), and
    /// compares each level's histogram with the listed one.
    Multiplicity(MultiplicityStep),
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
            Step::BoundaryDimension(_) => "boundary-dimension",
            Step::Multiplicity(_) => "multiplicity",
        }
    }
}
