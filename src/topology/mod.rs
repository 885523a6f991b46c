//! Combinatorial topology: edge types, faces and their notation, spoke rules, one subdivision step
//! with its incidence map, the closure with its stated bound or runaway witness, strongly connected
//! classes, exact counts and components, and the resource limits that guard them.
//!
//! Architecture invariant: this layer never sees a float and imports nothing from the crate but
//! [`crate::error`]. Everything above builds on it; it knows nothing of what is built.

pub(crate) mod breadth_first;
pub(crate) mod class;
pub(crate) mod closure;
pub(crate) mod component;
pub(crate) mod count;
pub(crate) mod edge;
pub(crate) mod face;
pub(crate) mod limits;
pub(crate) mod rule;
pub(crate) mod subdivision;
pub(crate) mod vertex;
pub mod volume;

pub use class::{Class, ClassStructure};
pub use closure::{close, close_or_error, Bound, Closure, FaceType, Runaway, TypeSet};
pub use component::{components_by_cells, components_by_induction, Glue};
pub use count::{counts, counts_from, LevelCount};
pub use edge::{EdgeKind, EdgeType, JunctionKind};
pub use face::{least_rotation, Face, Params};
pub use limits::Limits;
pub use rule::{Algorithm, EdgePattern, Junction, SpokeChooser, SpokeItem};
pub use subdivision::{subdivide, Adjacency, Complex, Origin, SubFace, Subdivision};
pub use vertex::{
    multiplicity, GrowthWitness, Item, LevelComplex, LimitValence, Multiplicity, SectorName,
    VertexSystem,
};
