//! The level-n solid of a volume in 3D (THEORY §10), for pictures and printable meshes.
//!
//! **What this is.** A default placement, not a solution of the BC-IFS constraint system: the
//! start volume is a regular solid (its corners on known coordinates), and every step places
//! the new points by simple rules on the points already placed. Floats live here only; every
//! cell, incidence and count comes from the exact step ([`subdivide_volume`] and
//! [`crate::topology::subdivision::subdivide`]), so the geometry cannot have other cells than the
//! topology: the cells built here are counted and compared with
//! [`crate::topology::volume::solid_topology`] by the mesh layer.
//!
//! **Cells.** Points, edges (straight segments between two points), faces (a loop of edges, with
//! a centre point used to place their inner points and to triangulate them) and volumes (a
//! canonical [`Volume`] with, for every face of its surface, the global face it reads and how).
//! A face shared by two volumes is one global face, subdivided once: the points and edges born
//! inside a face are keyed by what identifies them on either side (the junction point of a
//! spoke, the boundary pieces of a sub-face, the end point of a gap), so the second reader finds
//! what the first made. A reader that would make a different cell is refused.
//!
//! **Placement rules.**
//! - An edge's pieces split its segment evenly; a `Cn` edge has n pieces and n − 1 gaps of equal
//!   length.
//! - Inside a face with centre `c`: the lacuna corner of the spoke at junction point `j` is
//!   `c + λ(j − c)` (λ = [`LACUNA`]), the point of a gap with ends `a`, `b` is
//!   `m + μ(c − m)` with `m = (a + b)/2` (μ = [`NOTCH`]).
//! - Inside a volume with centre `o` (the mean of the corners of its faces, a corner counted once
//!   for every face that holds it): the inner corner at the end of the radial edge from a rim
//!   point `p` is `p + σ(o − p)` (σ = [`SHRINK`]). The side face over a rim edge then lies in the
//!   cone from `o` over that edge, and the inner face is the rim loop shrunk towards `o`. (An
//!   earlier rule pushed `p` along the summed outward normals of its faces by one depth per
//!   volume; on the non-convex pieces of level 2 and beyond the pushed copies crossed.) Side faces
//!   join a rim edge to its inner copy; the inner face is the loop of inner corners.
//! - A face's centre is the mean of its corners; a cap of a delayed volume is pushed into its
//!   volume by [`PUSH`] of the way to the volume's centre, so that two caps over one hole part.
//! - [`InnerFan::Radial`], the third way the mesh layer tries when the first two fold (issue
//!   #31), changes four of these rules: the volume's centre sees its level-1 surface, an inner
//!   face is fanned around a point from which the centre sees every fan triangle, the shrink is
//!   lowered where the inner face would reach its patch (`reach`), and a face whose mean lies
//!   outside its kernel is centred at a kernel point.
//!
//! **Files.** `cells.rs` (points, edges, faces, volumes, the solid, the vector arithmetic),
//! `centres.rs` (face centres, fan centres, kernels and reach), `step.rs` (the builder: one step
//! of faces and volumes, the inner-face rules), `placement.rs` (the start volumes placed in 3D),
//! `evaluate.rs` (the level-n solid of a volume or an assembly, thickness).
//!
//! [`subdivide_volume`]: crate::topology::volume::subdivide_volume
//! [`Volume`]: crate::topology::volume::Volume

mod cells;
mod centres;
mod evaluate;
mod placement;
mod step;

pub use cells::{GeoEdge, GeoFace, GeoVolume, InnerFan, Reading, SolidGeometry, P3};
pub use centres::star_point;
pub use evaluate::{evaluate_assembly, evaluate_volume, least_thickness};
pub use placement::{default_placement, place_assembly, solid_corners, Placement};
