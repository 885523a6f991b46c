//! Placement of the start faces in the plane (THEORY §7, issue #6): the user's coordinates where
//! given, regular polygons elsewhere, with every shared edge drawn once.
//!
//! 1. Corners are identified into *vertices* through the shared edges ([`crate::input::vertices`]). A
//!    face two of whose corners are one vertex cannot be drawn as a plane polygon (E1008).
//! 2. Faces with user coordinates are fixed (their shared edges coincide exactly: checked when
//!    the file was read).
//! 3. The other faces are placed breadth-first over the shared-edge graph, from the user faces of
//!    their component or, in a component without any, from its first face on a regular polygon
//!    (face 0 at the origin, circumradius 1; further components to the right): a face reached
//!    through a shared edge is the regular polygon on the other side of that edge.
//! 4. Every vertex must then have one position: all the corners it identifies agree within
//!    10⁻⁹ of the drawing's size. Where they do not (a cycle of faces that does not close with
//!    regular polygons, such as three quads around a vertex), the default faces of that
//!    component are placed by least squares instead: unknown vertex positions and one similarity
//!    per face, minimising Σ |vertex − similarity(regular polygon corner)|² (as-similar-as-possible),
//!    with the user's vertices fixed (or, without any, the first two corners of the first face).
//!    Every shared edge then holds by construction; a face that comes out clockwise, flat or
//!    self-crossing is error E1008 naming it — never a silent gap.
//! 5. Control points: the user's (exact, converted once to floating point), or evenly spaced on
//!    straight edges; then every shared edge's control points are copied from one side to the
//!    other (reversed), so both sides hold bit-identical points.

use crate::geometry::point::Point;
use crate::geometry::template::{control_points, regular_polygon};
use crate::{
    input::vertices, input::CoordKind, input::Input, topology::EdgeKind, topology::TypeSet,
    Diagnostic, Error, Result,
};
use num_traits::ToPrimitive;
use std::collections::VecDeque;
use std::f64::consts::PI;

fn placement_error(message: String) -> Error {
    Error::Syntax(Box::new(Diagnostic {
        code: "E1008",
        message,
        span: None,
        source: None,
    }))
}

fn to_point(p: &crate::input::ExactPoint) -> Point {
    [
        p[0].to_f64().unwrap_or(f64::NAN),
        p[1].to_f64().unwrap_or(f64::NAN),
    ]
}

/// A start face placed in the plane.
#[derive(Clone, Debug)]
pub struct StartFace {
    /// Its face type.
    pub ty: usize,
    /// Its control points, in the order of the type's state.
    pub points: Vec<Point>,
    /// For each boundary edge (canonical order): on the boundary of the assembly (not shared).
    pub free: Vec<bool>,
}

/// The regular polygon with corners `ef` → `ef + 1` at `pb` → `pa` (the far side of a neighbour's
/// edge `pa` → `pb`), sides of equal length, counter-clockwise.
fn polygon_on_edge(n: usize, ef: usize, pa: Point, pb: Point) -> Vec<Point> {
    let mut w = vec![[0.0; 2]; n];
    w[ef] = pb;
    w[(ef + 1) % n] = pa;
    let turn = 2.0 * PI / n as f64;
    let (cs, sn) = (turn.cos(), turn.sin());
    for step in 1..n.saturating_sub(1) {
        let i = (ef + step) % n;
        let (prev, cur) = (w[(i + n - 1) % n], w[i]);
        let d = [cur[0] - prev[0], cur[1] - prev[1]];
        w[(i + 1) % n] = [
            cur[0] + cs * d[0] - sn * d[1],
            cur[1] + sn * d[0] + cs * d[1],
        ];
    }
    w
}

fn double_area(poly: &[Point]) -> f64 {
    let m = poly.len();
    (0..m)
        .map(|i| {
            let (a, b) = (poly[i], poly[(i + 1) % m]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum()
}

fn cross(a: Point, b: Point, c: Point) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// Whether a counter-clockwise polygon is simple: no two non-adjacent edges cross or touch.
fn is_simple(poly: &[Point]) -> bool {
    let m = poly.len();
    for i in 0..m {
        let (a, b) = (poly[i], poly[(i + 1) % m]);
        for j in i + 2..m {
            if i == 0 && j == m - 1 {
                continue;
            }
            let (c, d) = (poly[j], poly[(j + 1) % m]);
            let (o1, o2) = (cross(a, b, c), cross(a, b, d));
            let (o3, o4) = (cross(c, d, a), cross(c, d, b));
            if o1 * o2 <= 0.0 && o3 * o4 <= 0.0 {
                return false;
            }
        }
    }
    true
}

/// Places the start faces (see the module documentation). `q` is the Bézier degree.
pub(crate) fn place(input: &Input, types: &TypeSet, q: usize) -> Result<Vec<StartFace>> {
    let asm = &input.assembly;
    let uc = &asm.coords;
    uc.usable()?;
    let nf = asm.faces.len();
    let (vid, nv) = vertices(asm);
    let shared_name = |s: &crate::input::SharedEdge| {
        format!(
            "face {} edge {} ~ face {} edge {}",
            asm.faces[s.a.0].0, s.a.1, asm.faces[s.b.0].0, s.b.1
        )
    };
    for (f, ids) in vid.iter().enumerate() {
        for i in 0..ids.len() {
            if let Some(j) = (i + 1..ids.len()).find(|&j| ids[j] == ids[i]) {
                let edges: Vec<String> = asm
                    .shared
                    .iter()
                    .filter(|s| s.a.0 == f || s.b.0 == f)
                    .map(shared_name)
                    .collect();
                return Err(placement_error(format!(
                    "the shared edges ({}) make corners {i} and {j} of face `{}` one point: it cannot be drawn as a polygon in the plane",
                    edges.join(", "),
                    asm.faces[f].0
                )));
            }
        }
    }
    // The user's control points at degree q, and their corners.
    let mut user: Vec<Option<Vec<Point>>> = vec![None; nf];
    let mut corners: Vec<Option<Vec<Point>>> = vec![None; nf];
    for fc in &uc.faces {
        let (name, face) = &asm.faces[fc.face];
        let Some(pts) = fc.controls(face, q) else {
            let d = match fc.kind {
                CoordKind::Controls { degree } => degree,
                CoordKind::Corners => q,
            };
            return Err(uc.error(
                "E0214",
                format!("face `{name}` gives control points of Bézier degree {d}, but the instantiation uses degree {q}"),
                &fc.spans[0],
            ));
        };
        user[fc.face] = Some(pts.iter().map(to_point).collect());
        corners[fc.face] = Some(fc.corners(face).iter().map(to_point).collect());
    }
    // Components of the shared-edge graph, and neighbours.
    let mut adj: Vec<Vec<(usize, usize, usize)>> = vec![Vec::new(); nf];
    for s in &asm.shared {
        if s.a.0 != s.b.0 {
            adj[s.a.0].push((s.a.1, s.b.0, s.b.1));
            adj[s.b.0].push((s.b.1, s.a.0, s.a.1));
        }
    }
    let mut comp = vec![usize::MAX; nf];
    let mut comps: Vec<Vec<usize>> = Vec::new();
    for f0 in 0..nf {
        if comp[f0] != usize::MAX {
            continue;
        }
        let c = comps.len();
        let mut members = vec![f0];
        comp[f0] = c;
        let mut k = 0;
        while k < members.len() {
            for &(_, g, _) in &adj[members[k]] {
                if comp[g] == usize::MAX {
                    comp[g] = c;
                    members.push(g);
                }
            }
            k += 1;
        }
        comps.push(members);
    }
    // Default size: the mean edge length of the user's faces, else circumradius 1.
    let user_edges: Vec<f64> = corners
        .iter()
        .flatten()
        .flat_map(|c| {
            (0..c.len()).map(move |i| crate::geometry::point::distance(c[i], c[(i + 1) % c.len()]))
        })
        .collect();
    let unit_edge =
        (!user_edges.is_empty()).then(|| user_edges.iter().sum::<f64>() / user_edges.len() as f64);
    // Breadth-first placement, component by component.
    let mut gauge: Vec<Option<usize>> = vec![None; comps.len()];
    for (c, members) in comps.iter().enumerate() {
        let mut queue: VecDeque<usize> = members
            .iter()
            .copied()
            .filter(|&f| corners[f].is_some())
            .collect();
        if queue.is_empty() {
            let root = members[0];
            let n = asm.faces[root].1.boundary.len();
            let scale = unit_edge.map_or(1.0, |e| e / (2.0 * (PI / n as f64).sin()));
            let mut poly: Vec<Point> = regular_polygon(n)
                .into_iter()
                .map(|p| [p[0] * scale, p[1] * scale])
                .collect();
            let placed: Vec<&Point> = corners.iter().flatten().flatten().collect();
            if !placed.is_empty() {
                let max_x = placed.iter().map(|p| p[0]).fold(f64::MIN, f64::max);
                let min_x = poly.iter().map(|p| p[0]).fold(f64::MAX, f64::min);
                let shift = max_x - min_x + scale;
                poly.iter_mut().for_each(|p| p[0] += shift);
            }
            corners[root] = Some(poly);
            gauge[c] = Some(vid[root][0]);
            queue.push_back(root);
        }
        while let Some(f) = queue.pop_front() {
            for &(e, g, eg) in &adj[f] {
                if corners[g].is_some() {
                    continue;
                }
                let cf = corners[f].as_ref().expect("placed");
                let (pa, pb) = (cf[e], cf[(e + 1) % cf.len()]);
                corners[g] = Some(polygon_on_edge(asm.faces[g].1.boundary.len(), eg, pa, pb));
                queue.push_back(g);
            }
        }
    }
    // One position per vertex: user vertices first, then the others; conflicts mark components.
    let corners: Vec<Vec<Point>> = corners.into_iter().map(|c| c.expect("placed")).collect();
    let size = corners
        .iter()
        .flatten()
        .fold(1.0f64, |m, p| m.max(p[0].abs()).max(p[1].abs()));
    let tol = 1e-9 * size;
    let mut pos: Vec<Option<Point>> = vec![None; nv];
    let mut fixed = vec![false; nv];
    let mut conflict: Vec<Option<(usize, usize)>> = vec![None; comps.len()];
    let order = (0..nf)
        .filter(|&f| user[f].is_some())
        .chain((0..nf).filter(|&f| user[f].is_none()));
    for f in order {
        for (i, &v) in vid[f].iter().enumerate() {
            let p = corners[f][i];
            match pos[v] {
                None => pos[v] = Some(p),
                Some(old) => {
                    if crate::geometry::point::distance(old, p) > tol && conflict[comp[f]].is_none()
                    {
                        conflict[comp[f]] = Some((f, i));
                    }
                }
            }
            if user[f].is_some() {
                fixed[v] = true;
            }
        }
    }
    for (c, members) in comps.iter().enumerate() {
        let Some((g, i)) = conflict[c] else {
            continue;
        };
        let relax: Vec<usize> = members
            .iter()
            .copied()
            .filter(|&f| user[f].is_none())
            .collect();
        relax_component(&relax, gauge[c], &vid, &corners, &fixed, &mut pos);
        for &f in &relax {
            let poly: Vec<Point> = vid[f].iter().map(|&v| pos[v].expect("placed")).collect();
            let area = double_area(&poly);
            if !(area.is_finite() && area > 1e-12 * size * size && is_simple(&poly)) {
                return Err(placement_error(format!(
                    "the default placement cannot honour every shared edge: the regular polygons do not close around corner {i} of face `{}`, and the least-squares placement makes face `{}` flat, clockwise or self-crossing; give the faces' corners (`corners NAME: x y, …` lines)",
                    asm.faces[g].0, asm.faces[f].0
                )));
            }
        }
    }
    // Control points in written order; shared edges copied so both sides are identical.
    let q_of = |f: usize, e: usize| match asm.faces[f].1.boundary[e].kind {
        EdgeKind::B => q + 1,
        EdgeKind::C => 2,
    };
    let offsets: Vec<Vec<usize>> = (0..nf)
        .map(|f| {
            let mut off = 0;
            (0..asm.faces[f].1.boundary.len())
                .map(|e| {
                    let o = off;
                    off += q_of(f, e) - 1;
                    o
                })
                .collect()
        })
        .collect();
    let mut points: Vec<Vec<Point>> = (0..nf)
        .map(|f| match &user[f] {
            Some(p) => p.clone(),
            None => {
                let c: Vec<Point> = vid[f].iter().map(|&v| pos[v].expect("placed")).collect();
                control_points(&asm.faces[f].1, &c, q)
            }
        })
        .collect();
    let rank: Vec<u8> = (0..nf)
        .map(|f| match uc.of(f).map(|c| c.kind) {
            Some(CoordKind::Controls { .. }) => 2,
            Some(CoordKind::Corners) => 1,
            None => 0,
        })
        .collect();
    for s in &asm.shared {
        let (from, to) = if rank[s.b.0] > rank[s.a.0] {
            (s.b, s.a)
        } else {
            (s.a, s.b)
        };
        let d = q_of(from.0, from.1);
        let (mf, mt) = (points[from.0].len(), points[to.0].len());
        let src: Vec<Point> = (0..d)
            .map(|c| points[from.0][(offsets[from.0][from.1] + c) % mf])
            .collect();
        for (c, p) in src.iter().rev().enumerate() {
            points[to.0][(offsets[to.0][to.1] + c) % mt] = *p;
        }
    }
    Ok(asm
        .faces
        .iter()
        .enumerate()
        .map(|(f, (_, face))| {
            let (_, r) = face.canonical();
            let n = face.boundary.len();
            let mut pts = points[f].clone();
            pts.rotate_left(offsets[f][r]);
            let free = (0..n)
                .map(|i| {
                    let e = (i + r) % n;
                    !asm.shared.iter().any(|s| s.a == (f, e) || s.b == (f, e))
                })
                .collect();
            StartFace {
                ty: types.start[f],
                points: pts,
                free,
            }
        })
        .collect())
}

/// Least-squares (as-similar-as-possible) placement of the default faces `faces` of one
/// component whose breadth-first placement `corners` does not close. The unknowns are the
/// positions of their vertices that are not `fixed` and one similarity `z ↦ c·z + t` (c = a + ib)
/// per face; the energy E is Σ over their corners of |vertex − similarity(regular polygon
/// corner)|², quadratic in the unknowns.
///
/// - With user vertices in the component (they are `fixed`), E is minimised: a linear
///   least-squares problem.
/// - Without (`gauge` is the component's first vertex), E alone would shrink everything to a
///   point, and fixing two vertices would favour their edge. The gauge vertex is fixed (at the
///   origin, for the computation) and E is minimised under Σ |c_f|² = 1: the smallest generalised
///   eigenvector, by inverse iteration. E/Σ|c_f|² is invariant under similarities and under
///   relabelling the faces, so a symmetric assembly gets a symmetric placement. The result is
///   scaled, rotated and translated back to the breadth-first placement's size, the first face's
///   orientation and the gauge vertex's position.
///
/// Linear solves by conjugate gradients on the normal equations. Written by hand: a few dozen
/// lines, no sparse solver crate needed.
fn relax_component(
    faces: &[usize],
    gauge: Option<usize>,
    vid: &[Vec<usize>],
    corners: &[Vec<Point>],
    fixed: &[bool],
    pos: &mut [Option<Point>],
) {
    let origin = gauge.and_then(|g| pos[g]).unwrap_or([0.0, 0.0]);
    let is_fixed = |v: usize| fixed[v] || Some(v) == gauge;
    let mut vmap = vec![usize::MAX; pos.len()];
    let mut free = Vec::new();
    for &f in faces {
        for &v in &vid[f] {
            if !is_fixed(v) && vmap[v] == usize::MAX {
                vmap[v] = free.len();
                free.push(v);
            }
        }
    }
    let nfree = free.len();
    let unknowns = 2 * nfree + 4 * faces.len();
    let mut z = vec![0.0; unknowns];
    // Start: the breadth-first placement (relative to `origin`): vertices at the mean of their
    // positions, similarities fitted (Procrustes).
    let mut count = vec![0.0; nfree];
    for &f in faces {
        for (i, &v) in vid[f].iter().enumerate() {
            if vmap[v] != usize::MAX {
                let k = vmap[v];
                z[2 * k] += corners[f][i][0] - origin[0];
                z[2 * k + 1] += corners[f][i][1] - origin[1];
                count[k] += 1.0;
            }
        }
    }
    for k in 0..nfree {
        z[2 * k] /= count[k];
        z[2 * k + 1] /= count[k];
    }
    // Residual rows: Σ coef·z[idx] + constant.
    let mut rows: Vec<(Vec<(usize, f64)>, f64)> = Vec::new();
    for (j, &f) in faces.iter().enumerate() {
        let n = vid[f].len();
        let r = regular_polygon(n);
        let base = 2 * nfree + 4 * j;
        let c = &corners[f];
        let mean = c.iter().fold([0.0, 0.0], |m, p| {
            [m[0] + p[0] / n as f64, m[1] + p[1] / n as f64]
        });
        let (mut sa, mut sb, mut ss) = (0.0, 0.0, 0.0);
        for i in 0..n {
            let p = [c[i][0] - mean[0], c[i][1] - mean[1]];
            sa += r[i][0] * p[0] + r[i][1] * p[1];
            sb += r[i][0] * p[1] - r[i][1] * p[0];
            ss += r[i][0] * r[i][0] + r[i][1] * r[i][1];
        }
        z[base] = sa / ss;
        z[base + 1] = sb / ss;
        z[base + 2] = mean[0] - origin[0];
        z[base + 3] = mean[1] - origin[1];
        for (i, &v) in vid[f].iter().enumerate() {
            let (rx, ry) = (r[i][0], r[i][1]);
            let mut x = vec![(base, -rx), (base + 1, ry), (base + 2, -1.0)];
            let mut y = vec![(base + 1, -rx), (base, -ry), (base + 3, -1.0)];
            let (mut kx, mut ky) = (0.0, 0.0);
            if vmap[v] == usize::MAX {
                let p = pos[v].expect("fixed vertices are placed");
                kx = p[0] - origin[0];
                ky = p[1] - origin[1];
            } else {
                x.push((2 * vmap[v], 1.0));
                y.push((2 * vmap[v] + 1, 1.0));
            }
            rows.push((x, kx));
            rows.push((y, ky));
        }
    }
    let apply = |z: &[f64]| -> Vec<f64> {
        let mut out = vec![0.0; unknowns];
        for (terms, _) in &rows {
            let s: f64 = terms.iter().map(|&(i, c)| c * z[i]).sum();
            for &(i, c) in terms {
                out[i] += c * s;
            }
        }
        out
    };
    let scale_of = |z: &[f64]| -> f64 {
        (0..faces.len())
            .map(|j| z[2 * nfree + 4 * j].powi(2) + z[2 * nfree + 4 * j + 1].powi(2))
            .sum()
    };
    if gauge.is_none() {
        let mut b = vec![0.0; unknowns];
        for (terms, k) in &rows {
            for &(i, c) in terms {
                b[i] -= c * k;
            }
        }
        conjugate_gradients(&apply, &b, &mut z);
    } else {
        // Inverse iteration on A z = λ B z, B selecting the c entries.
        let c0 = [z[2 * nfree], z[2 * nfree + 1]];
        let size0 = scale_of(&z);
        let mut y = z.clone();
        for _ in 0..100 {
            let mut b = vec![0.0; unknowns];
            for j in 0..faces.len() {
                b[2 * nfree + 4 * j] = z[2 * nfree + 4 * j];
                b[2 * nfree + 4 * j + 1] = z[2 * nfree + 4 * j + 1];
            }
            conjugate_gradients(&apply, &b, &mut y);
            let norm = (scale_of(&y) / size0).sqrt();
            if !(norm.is_finite() && norm > 0.0) {
                break;
            }
            let next: Vec<f64> = y.iter().map(|v| v / norm).collect();
            let change: f64 = next.iter().zip(&z).map(|(a, b)| (a - b).powi(2)).sum();
            z = next;
            y.clone_from(&z);
            if change <= 1e-24 * size0 {
                break;
            }
        }
        // Rotate so that the first face keeps its breadth-first orientation (this also fixes the
        // sign of the eigenvector).
        let c = [z[2 * nfree], z[2 * nfree + 1]];
        let phi = c0[1].atan2(c0[0]) - c[1].atan2(c[0]);
        let (cs, sn) = (phi.cos(), phi.sin());
        for pair in 0..(unknowns / 2) {
            let (x, y) = (z[2 * pair], z[2 * pair + 1]);
            z[2 * pair] = cs * x - sn * y;
            z[2 * pair + 1] = sn * x + cs * y;
        }
    }
    for (k, &v) in free.iter().enumerate() {
        pos[v] = Some([z[2 * k] + origin[0], z[2 * k + 1] + origin[1]]);
    }
}

/// Solves `apply(z) = b` for a symmetric positive definite operator by conjugate gradients,
/// starting from `z`.
fn conjugate_gradients(apply: &dyn Fn(&[f64]) -> Vec<f64>, b: &[f64], z: &mut [f64]) {
    let n = b.len();
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    let az = apply(z);
    let mut r: Vec<f64> = b.iter().zip(&az).map(|(x, y)| x - y).collect();
    let mut p = r.clone();
    let mut rr = dot(&r, &r);
    let stop = 1e-28 * dot(b, b).max(1e-300);
    for _ in 0..(10 * n + 100) {
        if rr <= stop {
            break;
        }
        let ap = apply(&p);
        let pap = dot(&p, &ap);
        if pap.is_nan() || pap <= 0.0 {
            break;
        }
        let alpha = rr / pap;
        for i in 0..n {
            z[i] += alpha * p[i];
            r[i] -= alpha * ap[i];
        }
        let rr_new = dot(&r, &r);
        let beta = rr_new / rr;
        rr = rr_new;
        for i in 0..n {
            p[i] = r[i] + beta * p[i];
        }
    }
}
