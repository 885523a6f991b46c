//! lacuna: a symbolic constraint solver and formal verifier for fractal topology (BC-IFS).
//!
//! The layering (see `docs/ARCHITECTURE.md`): combinatorial topology (edges, faces, spoke rules,
//! subdivision, closure, counts, classes) never sees a float; exact analysis sits on top of it.
#![forbid(unsafe_code)]
#![warn(missing_docs)]

mod assembly;
mod autofrac;
mod census;
mod class;
mod closure;
mod count;
mod edge;
mod error;
mod face;
mod library;
mod limits;
mod report;
mod rule;
mod subdivision;

pub use census::{census, CensusReport, CensusSpec};
pub use class::{Class, ClassStructure};
pub use closure::{close, close_or_error, Bound, Closure, FaceType, Runaway, TypeSet};
pub use count::{counts, counts_from, LevelCount};
pub use edge::{EdgeKind, EdgeType, JunctionKind};
pub use error::{Diagnostic, Error, Result, Source, Span};
pub use face::{least_rotation, Face, Params};

pub use assembly::{Assembly, SharedEdge};
pub use library::{library, load_input, parse_text, Input};
pub use limits::Limits;
pub use report::{closure_json, counts_json, counts_table, verify_report, VerifyReport};

pub use rule::{Algorithm, EdgePattern, Junction, SpokeChooser, SpokeItem};
pub use subdivision::{subdivide, Adjacency, Origin, SubFace, Subdivision};
