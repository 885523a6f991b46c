//! The cells of a volume's solid in 3D (points, edges, faces as read, volumes), the solid
//! itself, the ways an inner face is fanned, the constants of the placement rules, and the vector
//! arithmetic on points.

use crate::error::{Diagnostic, Error};
use crate::topology::edge::EdgeType;
use crate::topology::face::Face;
use crate::topology::volume::Volume;
use std::collections::HashMap;

/// A point in space.
pub type P3 = [f64; 3];

/// λ: where a lacuna corner lies between the face centre and its spoke's junction point.
pub const LACUNA: f64 = 0.5;

/// μ: how far a gap's point lies from the gap towards the face centre.
pub const NOTCH: f64 = 0.25;

/// κ: how far the centre of a cap of a delayed volume is pushed towards the volume's centre.
pub const PUSH: f64 = 0.2;

/// σ: the fraction of the way from a rim point to its volume's centre at which its inner corner
/// (the end of its radial edge) is placed.
pub const SHRINK: f64 = 0.5;

/// An edge: a straight segment from point `a` to point `b`.
#[derive(Clone, Debug)]
pub struct GeoEdge {
    /// Start point.
    pub a: usize,
    /// End point.
    pub b: usize,
    /// Its type.
    pub ty: EdgeType,
}

/// A face: a loop of edges as its first reader reads it.
#[derive(Clone, Debug)]
pub struct GeoFace {
    /// Its type as read by its first reader.
    pub face: Face,
    /// Corner `i` is where side `i` starts.
    pub corners: Vec<usize>,
    /// The centre: inner points are placed towards it, and the face is triangulated as a fan
    /// around it.
    pub center: P3,
    /// Whether the step chose the centre so that every triangle of the fan around it is seen
    /// from the centre of its volume's parent (the inner faces of [`InnerFan::Radial`]): the
    /// mesh then fans the face around this point and no other, which the rule's argument
    /// covers, even where the face is bent too much to look star-shaped along its mean normal.
    pub fan_fixed: bool,
}

/// One face of a volume's surface as the volume reads it (counter-clockwise from outside).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Reading {
    /// The global face.
    pub face: usize,
    /// Corner `i`: the start of side `i`.
    pub corners: Vec<usize>,
    /// The edge of side `i`.
    pub edges: Vec<usize>,
    /// Whether side `i` runs along its edge (from `a` to `b`).
    pub forward: Vec<bool>,
}

/// A volume of the evaluated solid.
#[derive(Clone, Debug)]
pub struct GeoVolume {
    /// The volume (its surface in the form the step gives it).
    pub volume: Volume,
    /// `faces[k]` reads face `k` of `volume.surface`.
    pub faces: Vec<Reading>,
}

/// The solid of one level: every cell with its geometry.
#[derive(Clone, Debug)]
pub struct SolidGeometry {
    /// The level.
    pub level: u32,
    /// Every point made so far (cells of this level and of the levels before).
    pub points: Vec<P3>,
    /// Every edge made so far.
    pub edges: Vec<GeoEdge>,
    /// Every face made so far.
    pub faces: Vec<GeoFace>,
    /// The volumes of this level.
    pub volumes: Vec<GeoVolume>,
    /// The holes the last step opened, as loops of points: the lacuna of every face it
    /// subdivided (its lacuna corners) and every gap of a `Cn` edge (its two ends).
    pub holes: Vec<Vec<usize>>,
}

impl SolidGeometry {
    /// The cells of this level: (volumes, faces, edges, corners), each counted once.
    pub fn cell_counts(&self) -> (usize, usize, usize, usize) {
        let mut faces = std::collections::HashSet::new();
        let mut edges = std::collections::HashSet::new();
        let mut corners = std::collections::HashSet::new();
        for v in &self.volumes {
            for r in &v.faces {
                faces.insert(r.face);
                edges.extend(r.edges.iter().copied());
                corners.extend(r.corners.iter().copied());
            }
        }
        (self.volumes.len(), faces.len(), edges.len(), corners.len())
    }

    /// For every face of this level, the volumes that hold it, with the reading of each.
    pub fn face_readers(&self) -> HashMap<usize, Vec<(usize, usize)>> {
        let mut out: HashMap<usize, Vec<(usize, usize)>> = HashMap::new();
        for (vi, v) in self.volumes.iter().enumerate() {
            for (k, r) in v.faces.iter().enumerate() {
                out.entry(r.face).or_default().push((vi, k));
            }
        }
        out
    }
}

pub(super) fn geometry_error(code: &'static str, message: String) -> Error {
    Error::Syntax(Box::new(Diagnostic {
        code,
        message,
        span: None,
        source: None,
    }))
}

pub(super) fn add(a: P3, b: P3) -> P3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

pub(super) fn sub(a: P3, b: P3) -> P3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

pub(super) fn scale(a: P3, s: f64) -> P3 {
    [a[0] * s, a[1] * s, a[2] * s]
}

pub(super) fn lerp(a: P3, b: P3, t: f64) -> P3 {
    add(a, scale(sub(b, a), t))
}

pub(super) fn dot(a: P3, b: P3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub(super) fn cross(a: P3, b: P3) -> P3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

pub(super) fn norm(a: P3) -> f64 {
    dot(a, a).sqrt()
}

pub(super) fn mean(points: impl Iterator<Item = P3>) -> P3 {
    let (mut s, mut n) = ([0.0; 3], 0.0f64);
    for p in points {
        s = add(s, p);
        n += 1.0;
    }
    scale(s, 1.0 / n.max(1.0))
}

/// How the inner face of a sub-volume (its rim shrunk towards the volume's centre, see
/// [`SHRINK`]) is drawn: a fan of triangles around one centre point. Two rules, because each
/// folds where the other does not (`docs/volume-sweep.sh`); the mesh layer tries them in order
/// and keeps the first whose solid embeds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InnerFan {
    /// Around the mean of the inner face's corners.
    RimMean,
    /// Around the same shrink of a point M of the patch (a corner of the patch inside it, the
    /// middle of an edge between two of its sub-faces, or a sub-face's centre: the one with the
    /// least sum of squared distances to the rim's corners), so that the fan is the shrunk image
    /// of a fan on the patch. Around the rim's mean, the fan of a strongly bent rim (two faces
    /// meeting in a valley seen from the centre) can cut through the patch.
    PatchPoint,
    /// Around the same shrink of a point from which every triangle of the rim's fan is seen from
    /// the volume's centre (counter-clockwise from outside), with the step's shrink lowered below
    /// [`SHRINK`] where an inner face would otherwise reach its patch; the volume's centre is
    /// then chosen to see the sub-faces of its level-1 surface, on which the sub-volumes stand
    /// (issue #31: at level 3, the inner face of a sub-volume over a patch bent around a corner of
    /// the cavity cut through that patch under both rules above).
    Radial,
}

impl InnerFan {
    /// Every rule, in the order the mesh layer tries them.
    pub const ALL: [InnerFan; 3] = [InnerFan::RimMean, InnerFan::PatchPoint, InnerFan::Radial];

    /// A few words for reports.
    pub fn describe(self) -> &'static str {
        match self {
            InnerFan::RimMean => "inner faces fanned around their mean",
            InnerFan::PatchPoint => {
                "inner faces fanned around the shrink of a point of their patch"
            }
            InnerFan::Radial => {
                "inner faces fanned around a point seen from their volume's centre, and shrunk to stay inside their patch's cone"
            }
        }
    }
}
