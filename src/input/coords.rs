//! User-given control points of faces (issue #6): exact coordinates read from lacuna's assembly
//! format (`corners NAME: …`, `points NAME: …`), from the `p` section of AutoFrac2D files, or
//! from `--corners` on the command line, and their checks (the right number of points, shared
//! edges that coincide exactly on both sides, no degenerate face).
//!
//! Everything here is exact (rationals); the geometry layer (`placement.rs`) converts to floating
//! point when it places the start faces.

use crate::error::{Diagnostic, Error, Result, Source, Span};
use crate::input::automaton_format::parse_rational;
use crate::topology::edge::EdgeKind;
use crate::topology::face::Face;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Signed, Zero};
use serde::Serialize;

/// An exact point of the plane.
pub type ExactPoint = [BigRational; 2];

/// The largest Bézier degree accepted for user control points (as `lacuna solve --degree`).
pub const MAX_DEGREE: usize = 8;

/// What a face's points are.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum CoordKind {
    /// One point per corner: corner i starts edge i (as written). Inner points of `Bn` edges are
    /// evenly spaced on the straight segment (or taken from a neighbour that gives them).
    Corners,
    /// Every control point at Bézier degree `degree`: per edge as written, its first corner then
    /// (for `Bn`) its `degree − 1` inner points; the last point of an edge is the next one's first.
    Controls {
        /// The Bézier degree q (`Bn` edges have q + 1 control points).
        degree: usize,
    },
}

/// The user-given points of one face.
#[derive(Clone, Debug, PartialEq)]
pub struct FaceCoords {
    /// Index of the face in the assembly.
    pub face: usize,
    /// Corners only, or all control points.
    pub kind: CoordKind,
    /// The points, exact.
    pub points: Vec<ExactPoint>,
    /// Where each point was written (for errors).
    pub spans: Vec<Span>,
}

/// The user-given points of an assembly (faces without an entry are placed by default).
#[derive(Clone, Debug, Default)]
pub struct UserCoords {
    /// One entry per face that has coordinates, sorted by face index (at most one per face).
    pub faces: Vec<FaceCoords>,
    /// The text the spans point into.
    pub source: Option<Source>,
    /// Coordinates that were written but cannot be used (an AutoFrac2D `p` section whose count
    /// fits no reading, or that fails the checks): the topology ignores them, the placement
    /// refuses with this error.
    pub unread: Option<Diagnostic>,
}

impl UserCoords {
    /// The coordinates of face `f`, if given.
    pub fn of(&self, f: usize) -> Option<&FaceCoords> {
        self.faces
            .binary_search_by_key(&f, |c| c.face)
            .ok()
            .map(|k| &self.faces[k])
    }

    /// The Bézier degree of the faces given with all their control points (they agree; checked).
    pub fn degree(&self) -> Option<usize> {
        self.faces.iter().find_map(|c| match c.kind {
            CoordKind::Controls { degree } => Some(degree),
            CoordKind::Corners => None,
        })
    }

    /// The error of unusable coordinates, if any (see [`UserCoords::unread`]).
    pub fn usable(&self) -> Result<()> {
        match &self.unread {
            Some(d) => Err(Error::Syntax(Box::new(d.clone()))),
            None => Ok(()),
        }
    }

    /// An error at `span` of the user's text (or without source when there is none).
    pub fn error(&self, code: &'static str, message: String, span: &Span) -> Error {
        Error::syntax(code, message, span.clone(), self.source.as_ref())
    }
}

/// Number of control points of edge type `e` at degree `q`, its last point included.
pub(crate) fn dim(face: &Face, i: usize, q: usize) -> usize {
    match face.boundary[i].kind {
        EdgeKind::B => q + 1,
        EdgeKind::C => 2,
    }
}

/// Number of control points of a face at degree q: Σ (dim − 1) over its edges.
pub fn control_count(face: &Face, q: usize) -> usize {
    (0..face.boundary.len()).map(|i| dim(face, i, q) - 1).sum()
}

/// Index of the first control point of each edge at degree q.
pub(crate) fn offsets(face: &Face, q: usize) -> Vec<usize> {
    let mut off = 0;
    (0..face.boundary.len())
        .map(|i| {
            let o = off;
            off += dim(face, i, q) - 1;
            o
        })
        .collect()
}

pub(crate) fn lerp(a: &ExactPoint, b: &ExactPoint, t: &BigRational) -> ExactPoint {
    [&a[0] + (&b[0] - &a[0]) * t, &a[1] + (&b[1] - &a[1]) * t]
}

impl FaceCoords {
    /// Which of the face's points is corner i, for each corner.
    fn corner_indices(&self, face: &Face) -> Vec<usize> {
        match self.kind {
            CoordKind::Corners => (0..face.boundary.len()).collect(),
            CoordKind::Controls { degree } => offsets(face, degree),
        }
    }

    /// The corners (corner i starts edge i).
    pub fn corners(&self, face: &Face) -> Vec<ExactPoint> {
        self.corner_indices(face)
            .into_iter()
            .map(|i| self.points[i].clone())
            .collect()
    }

    /// The span of corner i.
    pub(crate) fn corner_span(&self, face: &Face, i: usize) -> &Span {
        &self.spans[self.corner_indices(face)[i]]
    }

    /// The control points of edge i (both ends included), when they are all given.
    pub fn edge_controls(&self, face: &Face, i: usize) -> Option<Vec<ExactPoint>> {
        let CoordKind::Controls { degree } = self.kind else {
            return None;
        };
        let off = offsets(face, degree)[i];
        let m = self.points.len();
        Some(
            (0..dim(face, i, degree))
                .map(|c| self.points[(off + c) % m].clone())
                .collect(),
        )
    }

    /// All control points at degree q, in written edge order: the given ones, or, from corners,
    /// evenly spaced inner points on straight edges (exact). `None` when the points are given for
    /// another degree.
    pub fn controls(&self, face: &Face, q: usize) -> Option<Vec<ExactPoint>> {
        match self.kind {
            CoordKind::Controls { degree } if degree == q => Some(self.points.clone()),
            CoordKind::Controls { .. } => None,
            CoordKind::Corners => {
                let n = self.points.len();
                let mut out = Vec::new();
                for i in 0..n {
                    let d = dim(face, i, q) - 1;
                    for c in 0..d {
                        let t = BigRational::new(c.into(), d.into());
                        out.push(lerp(&self.points[i], &self.points[(i + 1) % n], &t));
                    }
                }
                Some(out)
            }
        }
    }
}

/// Reads the points of a face: exactly `n` corners (`corners_only`), or all its control points at
/// some degree 2 ≤ q ≤ 8 (a face without `Bn` edges: its corners). Error E0210 otherwise.
pub fn interpret(
    face_index: usize,
    (name, face): &(String, Face),
    (points, spans): (Vec<ExactPoint>, Vec<Span>),
    corners_only: bool,
    whole: &Span,
    src: Option<&Source>,
) -> Result<FaceCoords> {
    let n = face.boundary.len();
    let count = points.len();
    let kind = if count == n {
        Some(CoordKind::Corners)
    } else if corners_only {
        None
    } else {
        (2..=MAX_DEGREE)
            .find(|&q| control_count(face, q) == count)
            .map(|degree| CoordKind::Controls { degree })
    };
    let Some(kind) = kind else {
        let b = face
            .boundary
            .iter()
            .filter(|e| e.kind == EdgeKind::B)
            .count();
        let expected = if corners_only || b == 0 {
            format!("{n} (one per corner)")
        } else {
            format!(
                "{n} (one per corner) or all control points: {} at Bézier degree 2, {} at degree 3, …",
                control_count(face, 2),
                control_count(face, 3)
            )
        };
        return Err(Error::syntax(
            "E0210",
            format!("face `{name}` has {n} edges: expected {expected} points, found {count}"),
            whole.clone(),
            src,
        ));
    };
    Ok(FaceCoords {
        face: face_index,
        kind,
        points,
        spans,
    })
}

/// Parses an exact coordinate: an integer, a decimal (`0.25`) or a fraction (`-1/3`), of magnitude
/// at most 10¹⁵.
pub fn parse_coordinate(t: &str) -> Option<BigRational> {
    let v = parse_rational(t)?;
    let bound = BigRational::from_integer(BigInt::from(10u64.pow(15)));
    (v.abs() <= bound).then_some(v)
}

/// Parses `x y, x y, …` starting at column `col` (1-based, in characters) of line `ln`.
pub fn parse_point_list(
    text: &str,
    ln: usize,
    col: usize,
    src: &Source,
) -> Result<(Vec<ExactPoint>, Vec<Span>)> {
    let mut points = Vec::new();
    let mut spans = Vec::new();
    let mut byte = 0;
    for piece in text.split(',') {
        let start = byte;
        byte += piece.len() + 1;
        let lead = piece.len() - piece.trim_start().len();
        let p = piece.trim();
        let c = col + text[..start + lead].chars().count();
        let words: Vec<&str> = p.split_whitespace().collect();
        if words.len() != 2 {
            return Err(Error::at(
                "E0209",
                format!("expected a point `x y` (two exact numbers), found `{p}`"),
                ln,
                c,
                p.chars().count(),
                src,
            ));
        }
        let mut xy = Vec::new();
        for w in &words {
            let Some(v) = parse_coordinate(w) else {
                let off = (w.as_ptr() as usize).saturating_sub(p.as_ptr() as usize);
                return Err(Error::at(
                    "E0209",
                    format!("`{w}` is not an exact number of magnitude at most 10^15 (an integer, a decimal like 0.25 or a fraction like -1/3)"),
                    ln,
                    c + p[..off.min(p.len())].chars().count(),
                    w.chars().count(),
                    src,
                ));
            };
            xy.push(v);
        }
        let y = xy.pop().expect("two");
        let x = xy.pop().expect("two");
        points.push([x, y]);
        spans.push(Span {
            line: ln,
            col: c,
            len: p.chars().count().max(1),
        });
    }
    Ok((points, spans))
}

pub(crate) fn show(p: &ExactPoint) -> String {
    format!("({}, {})", p[0], p[1])
}

/// Twice the signed area of a polygon, exactly.
pub(crate) fn double_area(poly: &[ExactPoint]) -> BigRational {
    let m = poly.len();
    let mut s = BigRational::zero();
    for i in 0..m {
        let (a, b) = (&poly[i], &poly[(i + 1) % m]);
        s += &a[0] * &b[1] - &b[0] * &a[1];
    }
    s
}

/// The sign of the orientation of (a, b, c).
pub(crate) fn orient(a: &ExactPoint, b: &ExactPoint, c: &ExactPoint) -> i32 {
    let v = (&b[0] - &a[0]) * (&c[1] - &a[1]) - (&b[1] - &a[1]) * (&c[0] - &a[0]);
    if v.is_zero() {
        0
    } else if v.is_positive() {
        1
    } else {
        -1
    }
}

/// Whether c lies on the closed segment ab, given that a, b, c are collinear.
pub(crate) fn on_segment(a: &ExactPoint, b: &ExactPoint, c: &ExactPoint) -> bool {
    (0..2).all(|k| c[k] >= a[k].clone().min(b[k].clone()) && c[k] <= a[k].clone().max(b[k].clone()))
}

/// Whether the closed segments ab and cd meet.
pub(crate) fn segments_meet(
    a: &ExactPoint,
    b: &ExactPoint,
    c: &ExactPoint,
    d: &ExactPoint,
) -> bool {
    let (o1, o2, o3, o4) = (
        orient(a, b, c),
        orient(a, b, d),
        orient(c, d, a),
        orient(c, d, b),
    );
    if o1 * o2 < 0 && o3 * o4 < 0 {
        return true;
    }
    (o1 == 0 && on_segment(a, b, c))
        || (o2 == 0 && on_segment(a, b, d))
        || (o3 == 0 && on_segment(c, d, a))
        || (o4 == 0 && on_segment(c, d, b))
}

/// The first pair of edges of a closed polygon that meet other than at their common corner
/// (adjacent edges that fold back onto each other included). Faces above this size are not
/// tested (they are above every boundary limit; the test is quadratic).
pub(crate) fn self_intersection(poly: &[ExactPoint]) -> Option<(usize, usize)> {
    let m = poly.len();
    if !(3..=1024).contains(&m) {
        return None;
    }
    for i in 0..m {
        let (a, b) = (&poly[i], &poly[(i + 1) % m]);
        // Adjacent edge i + 1: it folds back when its end lies on edge i beyond the corner.
        let c = &poly[(i + 2) % m];
        if orient(a, b, c) == 0 && (on_segment(a, b, c) || on_segment(b, c, a)) {
            return Some((i, (i + 1) % m));
        }
        for j in i + 2..m {
            if i == 0 && j == m - 1 {
                continue;
            }
            if segments_meet(a, b, &poly[j], &poly[(j + 1) % m]) {
                return Some((i, j));
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pts(p: &[(i64, i64)]) -> Vec<ExactPoint> {
        p.iter()
            .map(|&(x, y)| {
                [
                    BigRational::from_integer(x.into()),
                    BigRational::from_integer(y.into()),
                ]
            })
            .collect()
    }

    #[test]
    fn simple_polygons_by_hand() {
        assert_eq!(
            self_intersection(&pts(&[(0, 0), (1, 0), (1, 1), (0, 1)])),
            None
        );
        // Non-convex but simple (an L).
        let l = pts(&[(0, 0), (2, 0), (2, 1), (1, 1), (1, 2), (0, 2)]);
        assert_eq!(self_intersection(&l), None);
        // Bow tie: edge 0 (0,0)-(2,0)... edges 1 (2,0)-(0,1) and 3 (3,1)-(0,0) cross at (1.2, 0.4).
        assert_eq!(
            self_intersection(&pts(&[(0, 0), (2, 0), (0, 1), (3, 1)])),
            Some((1, 3))
        );
        // A corner repeated: edge 1 has length 0 and folds onto edge 0.
        assert_eq!(
            self_intersection(&pts(&[(0, 0), (1, 0), (1, 0), (0, 1)])),
            Some((0, 1))
        );
        // Edge 2 runs back along edge 1: (0,0) (2,0) (2,2) (2,1) ...
        assert!(self_intersection(&pts(&[(0, 0), (2, 0), (2, 2), (2, 1), (0, 1)])).is_some());
        // Two non-adjacent corners at one point (a figure eight touching itself).
        assert!(
            self_intersection(&pts(&[(0, 0), (2, 0), (1, 1), (2, 2), (0, 2), (1, 1)])).is_some()
        );
        assert_eq!(
            double_area(&pts(&[(0, 0), (2, 0), (2, 1), (0, 1)])),
            BigRational::from_integer(4.into())
        );
    }
}
