//! Geometry, only after verification: points, polygons and rasters, templates, the choice of free
//! parameters (template fit, exact projection, LP goals), placement of the start faces in the plane
//! and the streamed instantiation of the attractor.
//!
//! Architecture invariant: floats live here, but never decide a verdict; it imports the exact layers
//! (topology, algebra, constraint, input) and never measures, exports or the command line.

pub(crate) mod automaton_eval;
pub(crate) mod choose;
pub(crate) mod flatten;
pub(crate) mod instantiate;
pub(crate) mod level_one;
pub(crate) mod lp;
pub(crate) mod options;
pub(crate) mod placement;
pub(crate) mod point;
pub(crate) mod raster;
pub(crate) mod template;
pub(crate) mod template_file;
pub(crate) mod volume;
pub(crate) mod volume_valence;

pub use automaton_eval::{
    approx as field_approx, evaluated_model, exact_points, exact_polygons, prepare_automaton,
    prepare_automaton_at, restarted, Evaluator, Shape, ShapeKind,
};
pub use choose::{project_exact, Choice, ExactColumn, Projection};
pub use flatten::flatten_bezier;
pub use instantiate::{instantiate, instantiate_unchecked, Cell, EdgeSlot, Instance};
pub use level_one::LevelOne;
pub use lp::{parse_goal, Goal};
pub use options::{GeometryError, InstantiateOptions};
pub use placement::StartFace;
pub use point::{
    bezier_point, box_dimension, distance, fit_line, polyline_length, signed_area, BBox, Fit,
    Point, Raster,
};
pub use raster::{bounds, cell_count, rasterize};
pub use template::{control_points, regular_polygon};
pub use template_file::{
    format_exact, parse_template, write_template, ExactTemplate, TypeTemplate,
};
pub use volume::{
    default_placement, evaluate_assembly, evaluate_volume, least_thickness, place_assembly,
    solid_corners, star_point, GeoEdge, GeoFace, GeoVolume, InnerFan, Placement, Reading,
    SolidGeometry, P3,
};
pub use volume_valence::{assembly_valences, volume_valences, ComplexValences};
