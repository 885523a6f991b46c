//! lacuna: a symbolic constraint solver and formal verifier for fractal topology (BC-IFS).
//!
//! The layering (see `docs/ARCHITECTURE.md`): combinatorial topology (edges, faces, spoke rules,
//! subdivision, closure, counts, classes) never sees a float; exact analysis sits on top of it.
#![forbid(unsafe_code)]
#![warn(missing_docs)]

// Lets modules name the public API as `lacuna::…` (the certificate producer is written that way).
extern crate self as lacuna;

mod algebraic;
mod assembly;
mod autofrac;
mod automaton;
mod automaton_format;
mod census;
mod choose;
mod class;
mod closure;
mod component;
mod coords;
mod count;
mod curve;
mod density;
mod design;
mod edge;
mod error;
mod export;
mod face;
mod factor;
mod fieldpoly;
mod generate;
mod geometry;
mod hole;
mod html;
mod instantiate;
mod library;
mod limits;
mod linsys;
mod lp;
mod matrix;
mod measure;
pub mod mesh;
mod operator;
mod placement;
mod poly;
mod presolve;
mod progress;
mod ratio;
mod report;
mod rule;
mod subdivision;
mod template;
mod template_file;

pub mod certificate;
pub mod certify;
pub mod checker;

pub use automaton::{
    solve_automaton, Automaton, Constraint, ConstraintKind, Factor, Linearized, OpKind, Operator,
    RowOrigin, SolveReport, State,
};
pub use automaton_format::{parse_automaton, parse_rational};
pub use census::{census, CensusReport, CensusSpec};
pub use choose::{project_exact, Choice, ExactColumn, Projection};
pub use class::{Class, ClassStructure};
pub use closure::{close, close_or_error, Bound, Closure, FaceType, Runaway, TypeSet};
pub use component::{canonical_glue, components_by_cells, components_by_induction, Glue};
pub use count::{counts, counts_from, LevelCount};
pub use curve::{
    analyse_automaton, estimate_curvature, AutomatonOperators, CurvatureEstimate, CurveReport,
    PointBehaviour, Side,
};
pub use density::{density_map, density_raster, DensityMap, DensitySummary};
pub use design::{check_design, design_operator, DesignCheck, DesignError};
pub use edge::{EdgeKind, EdgeType, JunctionKind};
pub use error::{Diagnostic, Error, Result, Source, Span};
pub use export::{
    render_raster, triangulate, write_json, write_obj, write_png, write_stl, write_svg,
};
pub use face::{least_rotation, Face, Params};
pub use generate::{automaton_of, degeneracies, solve_closure, GenOptions, Generated};
pub use geometry::{
    bezier_point, box_dimension, distance, fit_line, polyline_length, signed_area, BBox, Fit,
    Point, Raster, MIN_HOLE_PIXELS,
};
pub use hole::{polygon_size, smallest_holes};
pub use html::report_html;
pub use instantiate::{
    instantiate, Cell, EdgeSlot, GeometryError, Instance, InstantiateOptions, StartFace,
};
pub use measure::{
    bounds, cell_count, check_cells, exact_components, exact_topology, measure, raster_for_hole,
    rasterize, ExactTopology, LevelMeasure, MeasureOptions, MeasureReport, MIN_HOLE_WIDTH,
};
pub use operator::{
    analyse_matrix, parse_matrix_arg, parse_rationals_arg, Behaviour, CurvatureClass, Eigenvalue,
    OperatorReport,
};
pub use progress::{set_progress, Progress};
pub use template::{control_points, regular_polygon};
pub use template_file::{
    default_template, format_exact, parse_template, write_template, ExactTemplate, TypeTemplate,
};

pub use algebraic::{FieldElement, NumberField, RealAlgebraic};
pub use assembly::{Assembly, SharedEdge};
pub use coords::{
    control_count, set_corners, vertices, CoordKind, ExactPoint, FaceCoords, UserCoords,
};
pub use library::{library, load_any, load_input, parse_text, Input, Loaded};
pub use limits::Limits;
pub use linsys::{
    forced_equal, solve, write_text, Conflict, Equation, LinearSystem, Parametrization, Solution,
    SolutionSpace, TextLayout, MINIMIZE_LIMIT,
};
pub use lp::{parse_goal, Goal};
pub use matrix::{bezier_restriction, Matrix};
pub use poly::Poly;
pub use ratio::{analyse, ClassReport, LimitPoint, RatioError, RatioReport};
pub use report::{
    closure_json, closure_report, counts_json, counts_table, ratio_of, ratio_text, verify_report,
    VerifyReport,
};

pub use rule::{Algorithm, EdgePattern, Junction, SpokeChooser, SpokeItem};
pub use subdivision::{subdivide, Adjacency, Complex, Origin, SubFace, Subdivision};
