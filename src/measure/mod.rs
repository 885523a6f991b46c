//! Measures of an instance: area, perimeter, their factors, box-counting dimension, density maps,
//! the smallest holes, and observed holes and components compared with the exact counts.
//!
//! Architecture invariant: imports geometry and the exact layers; the one verdict it gives compares
//! integers. It never imports exports or the command line.

pub(crate) mod automaton_measure;
pub(crate) mod certify;
pub(crate) mod density;
pub(crate) mod hole;
pub(crate) mod measurement;
pub(crate) mod morph;

pub use automaton_measure::{
    automaton_measure, box_dimension, level_measures, shape_measure, AutomatonLevel,
    AutomatonMeasure, BoundaryReport, BoxDimension, OPEN_SET_NOT_CERTIFIED,
};
pub use certify::placement_certificate;
pub use density::{density_map, density_raster, DensityMap, DensitySummary};
pub use hole::{polygon_size, smallest_holes};
pub use measurement::{
    certification, check_cells, exact_components, exact_topology, measure, raster_for_hole,
    Certification, ExactTopology, LevelMeasure, MeasureOptions, MeasureReport, LARGEST_RASTER,
    MIN_HOLE_WIDTH,
};
pub use morph::{
    frame_parameters, morph, morph_automata, shape_difference, MorphFrame, MorphReport,
};
