//! The mesh layer (THEORY §11): printable solids of verified structures.
//!
//! **What it is for.** A planar structure at level n is turned into one closed, oriented,
//! triangulated 2-manifold per connected component: the union of the level-n cells extruded to a
//! thickness, with every shared edge shared (no internal walls, no duplicated vertices), side
//! walls only on the outer boundary and around the holes, top and bottom triangulated as polygons
//! with holes. The mesh is checked before anything is written, and written as binary or ASCII
//! STL, 3MF (core specification, millimetres) or Wavefront OBJ.
//!
//! **Architecture invariant.** This layer sits on top of the geometry layer: it may import
//! `crate::geometry`, `crate::instantiate`, `crate::measure` and `crate::hole` (and the
//! exact types of the layers below), never the command line. The 3D volumes of THEORY §10 will use
//! the same [`Part`], [`check`] and writers.
//!
//! **What is exact and what is not.** Which points of the level-n complex are one vertex is decided
//! from the topology, not from coordinates ([`outline`]): every cell edge carries an exact key
//! shared with the cell across it, and corners are identified through those keys. Coordinates are
//! floating point (millimetres rounded once to `f32`, the precision of binary STL, so that every
//! geometric test runs on the coordinates that are written). The verdict on the mesh is an integer
//! check of its combinatorics ([`check`]): every edge in exactly two triangles with opposite
//! orientations, every vertex's link one cycle, and the Euler characteristic of each component
//! equal to `2 − 2·holes` with `holes` from the exact counts. The geometric tests (no cell crossing
//! another, no zero-area triangle) use exact predicates (`robust`) on those `f32` coordinates.

pub mod bvh;
pub mod check;
pub mod expect;
pub mod feature;
pub mod obj;
pub mod orient;
pub mod outline;
pub mod polygon;
pub mod printability;
pub mod slice;
pub mod solid;
pub mod stl;
pub mod surface;
pub mod threemf;
pub mod volume;
pub mod wall;

pub use check::{check_part, PartCheck};

/// The layers below as the mesh layer uses them, named once here: when a module of those layers
/// moves, these lines are the only ones to change.
mod below {
    pub(crate) use crate::analysis::Resolved;
    pub(crate) use crate::geometry::automaton_eval::{
        approx, exact_polygons, Evaluator, ShapeKind,
    };
    pub(crate) use crate::geometry::instantiate::{Cell, Instance};
    pub(crate) use crate::geometry::point::{bezier_point, distance, Point};
    pub(crate) use crate::geometry::raster::bounds;
    pub(crate) use crate::input::automaton_model::AutomatonModel;
    pub(crate) use crate::measure::measurement::exact_topology;
    pub(crate) use crate::topology::component::{components_by_induction, start_components, Dsu};
    pub(crate) use crate::topology::count::population;
}
pub use polygon::triangulate;
pub use printability::{printability, Printability};
pub use solid::{
    build, build_typed, check_type_part, embedded, face_parts, Part, Solid, TypePart, TypedSolid,
};
pub use surface::{
    automaton_mesh, automaton_surface, exact_automaton_surface, thicken, AutomatonSolid, Surface,
    EXACT_LEAVES,
};
pub use volume::{assembly_solid, self_intersection, volume_solid, VolumeSolid};

/// Sizes of a printed solid, in millimetres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Size {
    /// The width (x extent) of the level-0 faces: the structure is scaled to it.
    pub width: f64,
    /// The thickness of the extrusion.
    pub thickness: f64,
}

impl Default for Size {
    fn default() -> Self {
        Size {
            width: DEFAULT_WIDTH,
            thickness: DEFAULT_THICKNESS,
        }
    }
}

/// Default width in mm (`--width`).
pub const DEFAULT_WIDTH: f64 = 100.0;
/// Default thickness in mm (`--thickness`).
pub const DEFAULT_THICKNESS: f64 = 2.0;
/// Default printer resolution in mm (`--resolution`): a common nozzle width.
pub const DEFAULT_RESOLUTION: f64 = 0.4;

/// The default build volume (`--bed`), mm: a common 200 mm cube.
pub const DEFAULT_BED: [f64; 3] = [200.0; 3];

/// Errors of the mesh layer, each with a stable code (`E104x`). [`MeshError::is_failure`] tells a
/// verification failure (exit 1: the mesh would not be the verified structure) from bad input
/// (exit 2).
#[derive(Debug, thiserror::Error)]
pub enum MeshError {
    /// A size is not a positive finite number of millimetres (E1043).
    #[error("{flag} {value} must be a positive number of millimetres")]
    Size {
        /// The option.
        flag: &'static str,
        /// The value given.
        value: f64,
    },
    /// Cells overlap or cross, or the boundary of the union touches itself (E1041): the geometry
    /// does not realise the verified topology.
    #[error("the level-{level} cells do not form the verified structure: {reason}")]
    Overlap {
        /// The level.
        level: u32,
        /// What was found, and where.
        reason: String,
    },
    /// The mesh is not a closed oriented manifold, or its Euler characteristic differs from the
    /// exact topology (E1040).
    #[error("the level-{level} mesh fails its check: {reason}")]
    Check {
        /// The level.
        level: u32,
        /// Which check, and where.
        reason: String,
    },
    /// A feature is below the printer resolution and `--strict` was given (E1042).
    #[error("{0}")]
    Resolution(String),
    /// The exact topology could not be derived (E1006, as in `measure`).
    #[error("exact topology: {0}")]
    Topology(String),
    /// An output file could not be written (E1005).
    #[error("cannot write `{path}`: {reason}")]
    Write {
        /// The path.
        path: String,
        /// Why.
        reason: String,
    },
}

impl MeshError {
    /// The stable diagnostic code.
    pub fn code(&self) -> &'static str {
        match self {
            MeshError::Check { .. } => "E1040",
            MeshError::Overlap { .. } => "E1041",
            MeshError::Resolution(_) => "E1042",
            MeshError::Size { .. } => "E1043",
            MeshError::Topology(_) => "E1006",
            MeshError::Write { .. } => "E1005",
        }
    }

    /// Whether this is a negative verdict (exit 1) rather than bad input or an I/O error (exit 2).
    pub fn is_failure(&self) -> bool {
        matches!(
            self,
            MeshError::Check { .. } | MeshError::Overlap { .. } | MeshError::Resolution(_)
        )
    }
}

/// Whether a diagnostic code is a verification failure of the mesh layer (exit 1).
pub fn is_failure_code(code: &str) -> bool {
    matches!(code, "E1040" | "E1041" | "E1042" | "E1211")
}

/// Checks that a size option is a positive finite number.
pub fn check_size(flag: &'static str, value: f64) -> Result<(), MeshError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(MeshError::Size { flag, value })
    }
}

/// The mesh formats to write, with their paths.
#[derive(Clone, Debug, Default)]
pub struct Targets {
    /// STL (binary unless `stl_ascii`).
    pub stl: Option<std::path::PathBuf>,
    /// Write the STL as ASCII.
    pub stl_ascii: bool,
    /// 3MF (core specification, millimetres).
    pub threemf: Option<std::path::PathBuf>,
    /// Wavefront OBJ with triangles.
    pub obj: Option<std::path::PathBuf>,
}

impl Targets {
    /// Whether any mesh is asked for.
    pub fn any(&self) -> bool {
        self.stl.is_some() || self.threemf.is_some() || self.obj.is_some()
    }
}

/// Builds and checks the solid of `level`, then writes every target. Returns one line per file
/// written and a summary of the check; nothing is written when the check fails.
pub fn write_targets(
    inst: &below::Instance,
    level: u32,
    segments: usize,
    size: Size,
    targets: &Targets,
) -> Result<String, MeshError> {
    check_size("--width", size.width)?;
    check_size("--thickness", size.thickness)?;
    let solid = build(inst, level, segments, size)?;
    let mut text = solid.summary();
    let io = |p: &std::path::Path, e: std::io::Error| MeshError::Write {
        path: p.display().to_string(),
        reason: e.to_string(),
    };
    let create = |p: &std::path::Path| {
        std::fs::File::create(p)
            .map(std::io::BufWriter::new)
            .map_err(|e| io(p, e))
    };
    if let Some(p) = &targets.stl {
        let out = create(p)?;
        if targets.stl_ascii {
            stl::write_ascii(&solid, out)
        } else {
            stl::write_binary(&solid, out)
        }
        .map_err(|e| io(p, e))?;
        text += &format!("wrote {}\n", p.display());
    }
    if let Some(p) = &targets.threemf {
        threemf::write(&solid, create(p)?).map_err(|e| io(p, e))?;
        text += &format!("wrote {}\n", p.display());
    }
    if let Some(p) = &targets.obj {
        obj::write(&solid, create(p)?).map_err(|e| io(p, e))?;
        text += &format!("wrote {}\n", p.display());
    }
    Ok(text)
}

pub use crate::error::counted;

/// The most faces of a volume's level-n solid built when the caller gives no bound
/// (`--max-cells`). Measured on the level-3 sweep of docs/VOLUMES.md: about 3 KB of memory and
/// 40 µs of CPU per face, all told (the largest case, 1,500,066 faces, peaked at 4.6 GB and took
/// 57 s), so the default admits every case of that sweep on a machine with 8 GB.
pub const MAX_SOLID_FACES: u64 = 1_600_000;

/// The most faces of the level-n solid of a volume's HTML report when the caller gives no bound:
/// the page carries every triangle for its WebGL view, about 100 bytes each, so this keeps a
/// page under about 100 MB.
pub const MAX_REPORT_FACES: u64 = 400_000;

/// The checked level-`level` solid of a volume file (`set` the closure of its volumes), `width`
/// millimetres wide: the level (at most `limits.max_level`) and the exact number of faces of the
/// level (at most `max_faces`) are bounded before any geometry is built; then the volumes are
/// placed and the solid built and checked by [`assembly_solid`].
pub fn checked_volume_solid(
    name: &str,
    v: &crate::input::VolumeFile,
    set: &crate::topology::volume::VolumeTypeSet,
    level: u64,
    width: f64,
    max_faces: u64,
    limits: &crate::topology::Limits,
) -> crate::error::Result<VolumeSolid> {
    let too_deep = || crate::Error::limit("the level", level, limits.max_level, "--max-level");
    if level > limits.max_level {
        return Err(too_deep());
    }
    let level = u32::try_from(level).map_err(|_| too_deep())?;
    let exact = crate::topology::volume::solid_topology_of(
        set,
        u64::from(level),
        &v.assembly.start_cells(),
    )?;
    let faces = &exact.last().expect("one row per level").faces;
    if *faces > max_faces.into() {
        return Err(crate::Error::limit(
            "the number of faces of the level-n solid",
            faces,
            max_faces,
            "--max-cells",
        ));
    }
    check_size("--width", width).map_err(|e| {
        crate::Error::Syntax(Box::new(crate::Diagnostic {
            code: e.code(),
            message: e.to_string(),
            span: None,
            source: None,
        }))
    })?;
    let placement = crate::geometry::place_assembly(&v.assembly, &v.corners, &v.names)?;
    assembly_solid(name, &v.assembly, &placement, set, level, width)
}
