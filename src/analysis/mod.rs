//! Exact analysis above the topology and the constraints, one folder per subject:
//!
//! - `ratio/`: the limit ratio R by eigen analysis;
//! - `operators/`: the operators' eigen analysis, curves and pseudo-curvature classes (the DCF),
//!   inverse design;
//! - `automata/`: an automaton's operators made exact, contraction, the similarity dimension
//!   and the open-set condition;
//! - `families/`: the census of a family of faces, and the property-based exploration of a rule
//!   with shrinking;
//! - `invariants/`: the invariants of faces, volumes and automata, classes, the limit shares of
//!   the valences.
//!
//! Architecture invariant: imports the layers below (topology, algebra, constraint, input) and never
//! geometry or output; floats appear only in labelled estimates, never in a verdict.

pub(crate) mod automata;
pub(crate) mod families;
pub(crate) mod invariants;
pub(crate) mod operators;
pub(crate) mod ratio;

/// The stable paths of the analyses, as they were before the subject folders: `analysis::census`,
/// `analysis::similarity`, … name the same modules as `analysis::families::census`,
/// `analysis::automata::similarity`, …, so code written against the old paths keeps building
/// (inside the library the new paths are used, hence the `allow`). The modules are private to
/// the crate; the public API is the flat list of items re-exported below.
#[allow(unused_imports)]
pub(crate) use automata::{automaton_resolve, contraction, neighbour_maps, open_set, similarity};
/// The stable paths of the analyses of a family of faces (see above).
#[allow(unused_imports)]
pub(crate) use families::{census, explore};
/// The stable paths of the invariants and classes (see above).
#[allow(unused_imports)]
pub(crate) use invariants::{classes, shares};
/// The stable paths of the operators and curvature (see above).
#[allow(unused_imports)]
pub(crate) use operators::{curve, dcf, design, operator};

pub use ratio::{analyse, ClassReport, LimitPoint, RatioError, RatioReport};

pub use operators::curve::{
    analyse_automaton, analyse_automaton_only, estimate_curvature, AutomatonOperators,
    CurvatureEstimate, CurveReport, PointBehaviour, Side,
};
pub use operators::dcf::{
    curve_curvature, operator_dcf, CurveCurvature, Dcf, DcfStart, DyadicPoint, Kappa, SideRange,
};
pub use operators::design::{check_design, design_operator, DesignCheck, DesignError};
pub use operators::operator::{
    analyse_matrix, parse_matrix_arg, parse_rationals_arg, Behaviour, CurvatureClass, Eigenvalue,
    OperatorReport,
};

pub use automata::automaton_resolve::{
    analyse_attractor, constraints_failing, failures, resolve, Attractor, Failing, ResolveVerdict,
    Resolved,
};
pub use automata::boundary::{
    boundary_dimension, not_a_tile, BoundaryDimension, BoundaryGraph, StateBoundary, MAX_COMPONENT,
};
pub use automata::contraction::{
    check_contraction, check_contraction_within, difference_restriction, ContractionReport,
    DEFAULT_MAX_PRODUCTS, MAX_CYCLES,
};
pub use automata::open_set::{OpenSetVerdict, MAX_ROUNDS};
pub use automata::similarity::{default_points, frames, similarity_dimension, SimilarityDimension};

pub use families::census::{census, parse_edge_list, CensusFace, CensusReport, CensusSpec};
pub use families::explore::{
    explore, explore_face, parse_properties, parse_shard, BoundaryResult, Check, Checks,
    ExploreSpec, Failure, Outcome, Property, Shrunk, Summary, Witness, MAX_FAMILY,
};

pub use invariants::automaton::{automaton_invariants, AutomatonMultiplicity};
pub use invariants::classes::{
    classify, face_invariants, levels_for, levels_needed, volume_invariants, Classification,
    Difference, Invariants, Named,
};
pub use invariants::shares::{limit_shares, shares_of, LimitShare, LimitShares};
