//! What users write: the library of named structures, assembly files, AutoFrac2D files, hand-written
//! automaton files and exact user coordinates, with diagnostics that point at line and column.
//!
//! Architecture invariant: parses into the types of [`crate::topology`] and [`crate::constraint`];
//! never imports analysis, geometry or output.

pub(crate) mod assembly;
pub(crate) mod autofrac;
pub(crate) mod automaton_format;
pub(crate) mod automaton_model;
pub(crate) mod coords;
pub(crate) mod library;
pub(crate) mod rule;
pub(crate) mod suggest;
pub(crate) mod volume_file;

pub use assembly::{set_corners, vertices, Assembly, SharedEdge};
pub use automaton_format::{parse_automaton, parse_rational};
pub use automaton_model::{parse_field_element, parse_model, AutomatonModel, Primitive};
pub use coords::{control_count, CoordKind, ExactPoint, FaceCoords, UserCoords};
pub use library::{
    kind_of, library, load_any, load_input, load_volume, load_volume_file, load_volumes,
    parse_text, read_text, Input, Loaded,
};
pub use rule::{compile_rule, is_rule, parse_rule, Affine, Flip, Rule, RulePath, Segment, Target};
pub use volume_file::{
    is_volume_notation, is_volume_text, parse_volume_file, parse_volume_text, Corners, VolumeFile,
};
