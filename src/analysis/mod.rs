//! Exact analysis above the topology and the constraints: the limit ratio R by eigen analysis, the
//! operators' eigen analysis and curves (pseudo-curvature classes), inverse design, the census of
//! a family of faces, and the property-based exploration of a rule with shrinking.
//!
//! Architecture invariant: imports the layers below (topology, algebra, constraint, input) and never
//! geometry or output; floats appear only in labelled estimates, never in a verdict.

pub(crate) mod automaton_resolve;
pub(crate) mod census;
pub(crate) mod classes;
pub(crate) mod contraction;
pub(crate) mod curve;
pub(crate) mod dcf;
pub(crate) mod design;
pub(crate) mod explore;
pub(crate) mod neighbour_maps;
pub(crate) mod open_set;
pub(crate) mod operator;
pub(crate) mod ratio;
pub(crate) mod shares;
pub(crate) mod similarity;

pub use automaton_resolve::{
    analyse_attractor, constraints_failing, failures, resolve, Attractor, Failing, ResolveVerdict,
    Resolved,
};
pub use census::{census, parse_edge_list, CensusFace, CensusReport, CensusSpec};
pub use classes::{
    automaton_invariants, classify, face_invariants, levels_for, levels_needed, volume_invariants,
    AutomatonMultiplicity, Classification, Difference, Invariants, Named,
};
pub use contraction::{
    check_contraction, check_contraction_within, difference_restriction, ContractionReport,
    DEFAULT_MAX_PRODUCTS, MAX_CYCLES,
};
pub use curve::{
    analyse_automaton, analyse_automaton_only, estimate_curvature, AutomatonOperators,
    CurvatureEstimate, CurveReport, PointBehaviour, Side,
};
pub use dcf::{
    curve_curvature, operator_dcf, CurveCurvature, Dcf, DcfStart, DyadicPoint, Kappa, SideRange,
};
pub use design::{check_design, design_operator, DesignCheck, DesignError};
pub use explore::{
    explore, explore_face, parse_properties, parse_shard, BoundaryResult, Check, Checks,
    ExploreSpec, Failure, Outcome, Property, Shrunk, Summary, Witness, MAX_FAMILY,
};
pub use open_set::{OpenSetVerdict, MAX_ROUNDS};
pub use operator::{
    analyse_matrix, parse_matrix_arg, parse_rationals_arg, Behaviour, CurvatureClass, Eigenvalue,
    OperatorReport,
};
pub use ratio::{analyse, ClassReport, LimitPoint, RatioError, RatioReport};
pub use shares::{limit_shares, shares_of, LimitShare, LimitShares};
pub use similarity::{default_points, frames, similarity_dimension, SimilarityDimension};
