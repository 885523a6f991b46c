//! Where faces and inner faces are fanned from: a face's centre (its mean, or a point of its
//! kernel), the centre of an inner face's fan seen from the volume's centre, how far a fan may
//! shrink before it reaches its patch, and the kernel point of a surface.

use super::cells::{add, cross, dot, lerp, mean, norm, scale, sub, P3};

/// The centre of a face with corners `pts`: their mean when the face is star-shaped from it
/// about its Newell normal n (every fan triangle (c, aᵢ, aᵢ₊₁) turns counter-clockwise about n,
/// strictly), else the point of that kernel nearest to the mean (with a margin, in the plane
/// through the mean normal to n; [`kernel_point`]), else the mean.
///
/// Inner points of a face are placed towards its centre (a lacuna corner half-way from the
/// centre to its junction point), and faces are fanned around it: a centre outside the kernel
/// (the mean of an arrow-shaped sub-face at level 3, issue #31) turns fan triangles over and
/// makes sub-faces that cross.
pub(super) fn face_centre(pts: &[P3]) -> P3 {
    star_point_with(pts, false).unwrap_or_else(|| mean(pts.iter().copied()))
}

/// A point from which the polygon `pts` is star-shaped about its Newell normal n (every fan
/// triangle (c, aᵢ, aᵢ₊₁) turns counter-clockwise about n, strictly): the mean when it is one,
/// else the point of that kernel nearest to the mean with a margin of half the kernel's
/// inradius, in the plane through the mean normal to n ([`kernel_point`]); `None` when the
/// kernel is empty or thin or the polygon is flat. A triangle is star-shaped from its mean.
///
/// The mesh fans a boundary face around it when the face's own centre does not do: a point
/// well inside the kernel belongs to that face alone, where a point on a fixed list of
/// candidates (the centroid of the triangle at a corner) can be the same for two faces that
/// share the two sides at that corner (issue #31: two mirror-image cavity faces at level 3
/// fanned around one point).
pub fn star_point(pts: &[P3]) -> Option<P3> {
    star_point_with(pts, true)
}

/// [`star_point`]; a kernel point off the mean is lifted onto the face ([`lift`]) when `lifted`,
/// else left on the plane through the mean (the placement's face centres, [`face_centre`]).
fn star_point_with(pts: &[P3], lifted: bool) -> Option<P3> {
    let m = mean(pts.iter().copied());
    let k = pts.len();
    if k < 4 {
        return Some(m);
    }
    let mut n = [0.0; 3];
    for i in 0..k {
        n = add(n, cross(sub(pts[i], m), sub(pts[(i + 1) % k], m)));
    }
    let nl = norm(n);
    let size = pts.iter().map(|p| norm(sub(*p, m))).fold(0.0f64, f64::max);
    if nl <= 1e-12 * size * size {
        return None;
    }
    let n = scale(n, 1.0 / nl);
    // (c − aᵢ)·(eᵢ × n) < 0 for every side eᵢ = aᵢ₊₁ − aᵢ.
    let mut planes: Vec<(P3, P3)> = Vec::with_capacity(k + 2);
    for i in 0..k {
        let e = sub(pts[(i + 1) % k], pts[i]);
        let out = cross(e, n);
        let l = norm(out);
        if l > 0.0 {
            planes.push((scale(out, 1.0 / l), pts[i]));
        }
    }
    let inside = |c: P3| {
        planes
            .iter()
            .all(|(o, a)| dot(*o, sub(c, *a)) < -1e-9 * size)
    };
    if inside(m) {
        return Some(m);
    }
    // A slab about the mean's plane bounds the prism of such points.
    planes.push((n, add(m, scale(n, size))));
    planes.push((scale(n, -1.0), sub(m, scale(n, size))));
    let c = kernel_point(&planes, m, size)?;
    let flat = sub(c, scale(n, dot(sub(c, m), n)));
    if !lifted {
        return Some(flat);
    }
    lift(pts, n, flat)
}

/// The point of the polygon `pts` over `c` (a point of the kernel of its projection along the
/// unit normal `n`): Σ wᵢ·aᵢ with wᵢ the mean value coordinates of the projection of `c` in the
/// projected polygon (Floater 2003). They are positive wherever the polygon is star-shaped, and
/// they reproduce linear functions, so the point projects onto `c` and is a convex combination
/// of the corners: a bent face's centre lies among its corners rather than on the plane through
/// their mean, which can cross to the far side of a neighbour (issue #31: two mirror-image cavity
/// faces, each on its side of the mirror plane, with centres on the wrong sides). `None` when a
/// weight is not positive.
fn lift(pts: &[P3], n: P3, c: P3) -> Option<P3> {
    let k = pts.len();
    // Offsets from c in the plane normal to n.
    let d: Vec<P3> = pts
        .iter()
        .map(|p| {
            let v = sub(*p, c);
            sub(v, scale(n, dot(v, n)))
        })
        .collect();
    let r: Vec<f64> = d.iter().map(|v| norm(*v)).collect();
    // tan(αᵢ/2) for the angle αᵢ at c between corners i and i + 1.
    let mut half = Vec::with_capacity(k);
    for i in 0..k {
        let j = (i + 1) % k;
        let s = dot(cross(d[i], d[j]), n);
        let cosr = r[i] * r[j] + dot(d[i], d[j]);
        // s > 0 puts the angle in (0, π), where r·r' + d·d' = r·r'·(1 + cos α) > 0.
        if s <= 0.0 {
            return None;
        }
        half.push(s / cosr);
    }
    let mut w = Vec::with_capacity(k);
    for i in 0..k {
        if r[i] <= 0.0 {
            return None;
        }
        w.push((half[(i + k - 1) % k] + half[i]) / r[i]);
    }
    let total: f64 = w.iter().sum();
    let positive = |x: f64| x.is_finite() && x > 0.0;
    if !positive(total) || !w.iter().all(|&x| positive(x)) {
        return None;
    }
    let mut out = [0.0; 3];
    for (p, x) in pts.iter().zip(&w) {
        out = add(out, scale(*p, x / total));
    }
    Some(out)
}

/// A point `c` around which the loop `rim` is fanned with every triangle (c, rᵢ, rᵢ₊₁) seen from
/// `o` counter-clockwise from outside (strictly): the mean of the rim when it is one, else the
/// point nearest to it of the cone {c : (c − o)·((rᵢ − o) × (rᵢ₊₁ − o)) > 0 for all i} (each
/// condition is linear in c), cut off beyond the rim's mean and behind `o`, with a margin
/// ([`kernel_point`]). `None` when that cone is empty or thin.
pub(super) fn radial_centre(o: P3, rim: &[P3]) -> Option<P3> {
    let m = rim.len();
    let normals: Vec<P3> = (0..m)
        .map(|i| cross(sub(rim[i], o), sub(rim[(i + 1) % m], o)))
        .collect();
    let c = mean(rim.iter().copied());
    let sees = |c: P3| normals.iter().all(|n| dot(*n, sub(c, o)) > 0.0);
    if sees(c) {
        return Some(c);
    }
    let size = rim.iter().map(|p| norm(sub(*p, o))).fold(0.0f64, f64::max);
    let g = sub(c, o);
    let gl = norm(g);
    if gl <= 1e-12 * size {
        return None;
    }
    let g = scale(g, 1.0 / gl);
    // Outward normals: −n̂ᵢ through o, and the cap ĝ through o + 2·(c − o).
    let mut planes: Vec<(P3, P3)> = normals
        .iter()
        .filter(|n| norm(**n) > 0.0)
        .map(|n| (scale(*n, -1.0 / norm(*n)), o))
        .collect();
    planes.push((g, add(o, scale(g, 2.0 * gl))));
    // …and on the rim's side of o (behind o a clockwise rim would be seen counter-clockwise).
    planes.push((scale(g, -1.0), o));
    kernel_point(&planes, c, size).filter(|x| sees(*x) && dot(g, sub(*x, o)) > 0.0)
}

/// How far the fan `fan` may be shrunk towards `o` and stay strictly between `o` and the
/// surface `patch`: the least, over the rays from `o` through both, of the patch's distance
/// from `o` over the fan's (ρ_P/ρ_F). The fan shrunk by any factor below it lies strictly
/// closer to `o` than the patch on every ray. `None` when a triangle of either is not seen
/// from `o` counter-clockwise from outside (strictly): the bound means nothing then.
///
/// On the cone over one fan triangle and one patch triangle, 1/ρ is linear in the direction
/// (1/ρ(ω) = n·ω / n·a for the plane through a with normal n), so ρ_P/ρ_F is a ratio of two
/// linear functions, positive on the cone, and its least value is at an edge ray of the
/// intersection of the two cones: the fan triangle's corners clipped by the three planes through
/// `o` and the patch triangle's edges.
pub(super) fn reach(o: P3, fan: &[[P3; 3]], patch: &[[P3; 3]]) -> Option<f64> {
    let rel = |t: &[P3; 3]| t.map(|p| sub(p, o));
    let det = |t: &[P3; 3]| dot(t[0], cross(t[1], t[2]));
    let plane = |t: &[P3; 3]| {
        let n = cross(sub(t[1], t[0]), sub(t[2], t[0]));
        (n, dot(n, t[0]))
    };
    let patch: Vec<[P3; 3]> = patch.iter().map(rel).collect();
    if patch.iter().any(|t| det(t) <= 0.0) {
        return None;
    }
    let mut least = f64::INFINITY;
    for f in fan.iter().map(rel) {
        if det(&f) <= 0.0 {
            return None;
        }
        let (nf, df) = plane(&f);
        for p in &patch {
            let mut poly: Vec<P3> = f.to_vec();
            for k in 0..3 {
                let h = cross(p[k], p[(k + 1) % 3]);
                poly = clip(&poly, h);
                if poly.is_empty() {
                    break;
                }
            }
            let (np, dp) = plane(p);
            for w in poly {
                let (a, b) = (dot(nf, w) / df, dot(np, w) / dp);
                if b > 0.0 {
                    least = least.min(a / b);
                }
            }
        }
    }
    Some(least)
}

/// The polygon `poly` (corners as directions) clipped to the half-space `h·x ≥ 0`
/// (Sutherland–Hodgman).
fn clip(poly: &[P3], h: P3) -> Vec<P3> {
    let mut out = Vec::with_capacity(poly.len() + 1);
    for i in 0..poly.len() {
        let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
        let (sa, sb) = (dot(h, a), dot(h, b));
        if sa >= 0.0 {
            out.push(a);
        }
        if (sa >= 0.0) != (sb >= 0.0) {
            out.push(lerp(a, b, sa / (sa - sb)));
        }
    }
    out
}

/// A point of the kernel of a surface given by the outward unit normals and points of its fan
/// triangles (`n·(x − c) < 0` for all): the one nearest (in L1) to `near` among the points at
/// least half the kernel's inradius inside every plane. `None` when the kernel is empty or thin
/// (inradius ≤ 10⁻⁹·`size`) or the solver fails. Two linear programs with `good_lp`'s pure-Rust
/// simplex (`microlp`, f64): this is geometry, no verdict rests on it.
pub(super) fn kernel_point(planes: &[(P3, P3)], near: P3, size: f64) -> Option<P3> {
    use good_lp::{microlp, variable, variables, Expression, Solution, SolverModel};
    let side = |x: &[good_lp::Variable; 3], n: P3, c: P3| -> Expression {
        // −n·(x − c): the distance inside the plane.
        let mut e = Expression::from(dot(n, c));
        for k in 0..3 {
            e.add_mul(-n[k], x[k]);
        }
        e
    };
    let bound = |k: usize| (near[k] - 2.0 * size, near[k] + 2.0 * size);
    // 1. The inradius: maximise t with every plane at least t away.
    let mut vars = variables!();
    let x: [good_lp::Variable; 3] = std::array::from_fn(|k| {
        let (lo, hi) = bound(k);
        vars.add(variable().min(lo).max(hi))
    });
    let t = vars.add(variable().min(0.0).max(size));
    let mut model = vars.maximise(t).using(microlp);
    for &(n, c) in planes {
        model.add_constraint(side(&x, n, c).geq(t));
    }
    let sol = model.solve().ok()?;
    let r = sol.value(t);
    if r <= 1e-9 * size {
        return None;
    }
    // 2. Nearest to `near` (L1) among the points at least r/2 inside.
    let mut vars = variables!();
    let x: [good_lp::Variable; 3] = std::array::from_fn(|k| {
        let (lo, hi) = bound(k);
        vars.add(variable().min(lo).max(hi))
    });
    let d: [good_lp::Variable; 3] = std::array::from_fn(|_| vars.add(variable().min(0.0)));
    let total: Expression = d.iter().copied().sum();
    let mut model = vars.minimise(total).using(microlp);
    for k in 0..3 {
        model.add_constraint((Expression::from(x[k]) - near[k]).leq(d[k]));
        model.add_constraint((Expression::from(near[k]) - x[k]).leq(d[k]));
    }
    for &(n, c) in planes {
        model.add_constraint(side(&x, n, c).geq(r / 2.0));
    }
    let sol = model.solve().ok()?;
    Some(std::array::from_fn(|k| sol.value(x[k])))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_kernel_point_of_a_cube_nearest_to_a_far_point() {
        // The unit cube [0, 1]³ by its six planes (outward normal, a point). Its kernel is the
        // cube, whose inradius is 1/2 (the centre). The points at least 1/4 inside every plane
        // form [1/4, 3/4]³, and the one nearest to (5, 5, 5) in L1 is its corner (3/4, 3/4, 3/4).
        // (`size` bounds the search to a box of ±2·size around the given point.)
        let planes: Vec<(P3, P3)> = (0..3)
            .flat_map(|k| {
                let mut n = [0.0; 3];
                n[k] = 1.0;
                [(n, [1.0; 3]), (scale(n, -1.0), [0.0; 3])]
            })
            .collect();
        let p = kernel_point(&planes, [5.0; 3], 10.0).unwrap();
        for x in p {
            assert!((x - 0.75).abs() < 1e-7, "{p:?}");
        }
        // Two parallel planes facing away from each other leave an empty kernel.
        let empty = [
            ([1.0, 0.0, 0.0], [0.0; 3]),
            ([-1.0, 0.0, 0.0], [1.0, 0.0, 0.0]),
        ];
        assert_eq!(kernel_point(&empty, [0.5; 3], 1.0), None);
    }

    #[test]
    fn the_reach_of_a_fan_is_the_least_ratio_of_distances_on_the_shared_cone() {
        // Seen from the origin, the patch is the triangle a = (1, 0, 1), b = (0, 1, 1),
        // c = (−½, −½, 1) in the plane z = 1 (det(a, b, c) = 2 > 0: counter-clockwise from
        // outside). A copy twice as far (the plane z = 2) is at twice the distance on every ray:
        // reach ½.
        let patch = [[[1.0, 0.0, 1.0], [0.0, 1.0, 1.0], [-0.5, -0.5, 1.0]]];
        let twice = [patch[0].map(|p| scale(p, 2.0))];
        let r = reach([0.0; 3], &twice, &patch).unwrap();
        assert!((r - 0.5).abs() < 1e-12, "{r}");
        // A fan triangle in the plane z − x/4 = 1 whose cone holds the patch's: its corners are
        // the rays (3, 0, 1), (−1, ±2, 1) met at t = 4 and t = 4/5. On a ray ω the patch is at
        // 1/ω_z and the fan at 1/(ω_z − ω_x/4), so ρ_P/ρ_F = 1 − ω_x/(4ω_z): least where x/z is
        // greatest inside the patch's cone, 1 at a, so 3/4. Over the fan's whole cone (x/z up to
        // 3) it would be 1/4: only the shared cone counts.
        let fan = [[[12.0, 0.0, 4.0], [-0.8, 1.6, 0.8], [-0.8, -1.6, 0.8]]];
        let r = reach([0.0; 3], &fan, &patch).unwrap();
        assert!((r - 0.75).abs() < 1e-12, "{r}");
        // Moving everything by the same vector changes nothing.
        let d = [0.3, -2.0, 5.0];
        let moved =
            |t: &[[P3; 3]]| -> Vec<[P3; 3]> { t.iter().map(|x| x.map(|p| add(p, d))).collect() };
        let r = reach(d, &moved(&fan), &moved(&patch)).unwrap();
        assert!((r - 0.75).abs() < 1e-12, "{r}");
        // A fan triangle seen from behind (clockwise) bounds nothing.
        let turned = [[fan[0][0], fan[0][2], fan[0][1]]];
        assert_eq!(reach([0.0; 3], &turned, &patch), None);
        // Nor does a patch seen from behind.
        let behind = [[patch[0][0], patch[0][2], patch[0][1]]];
        assert_eq!(reach([0.0; 3], &fan, &behind), None);
    }

    #[test]
    fn corners_pulled_in_unevenly_keep_a_fan_below_its_evenly_pulled_copy() {
        // The radial rule's per-sub-volume shrink (issue #31): a sub-volume's inner face is its
        // rim fan with every point p moved to o + αₚ(p − o), where αₚ is at most the sub-volume's
        // own α (a corner shared with a neighbour takes the neighbour's smaller α). On the ray
        // through a point Σλᵢvᵢ of a fan triangle, the moved triangle lies at 1/Σ(λᵢ/αᵢ) ≤ α of
        // it, so its reach over any patch the fan reaches with ρ is at least ρ/α. Checked on
        // the patch of the test above with the slanted fan (ρ = 3/4) and α = 1/2, with corner
        // fractions drawn from [1/50, 1/2] by a fixed linear congruential sequence.
        let patch = [[[1.0, 0.0, 1.0], [0.0, 1.0, 1.0], [-0.5, -0.5, 1.0]]];
        let fan = [[12.0, 0.0, 4.0], [-0.8, 1.6, 0.8], [-0.8, -1.6, 0.8]];
        let rho = reach([0.0; 3], &[fan], &patch).unwrap();
        let mut x: u64 = 12345;
        let mut next = || {
            x = x
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            0.02 + 0.48 * ((x >> 11) as f64 / (1u64 << 53) as f64)
        };
        for _ in 0..200 {
            let a = [next(), next(), next()];
            let moved = [0, 1, 2].map(|i| scale(fan[i], a[i]));
            let r = reach([0.0; 3], &[moved], &patch).unwrap();
            assert!(r >= rho / 0.5 * (1.0 - 1e-12), "{a:?}: {r} < {}", rho / 0.5);
        }
        // All at ½ gives exactly ρ/½.
        let even = [0, 1, 2].map(|i| scale(fan[i], 0.5));
        let r = reach([0.0; 3], &[even], &patch).unwrap();
        assert!((r - rho / 0.5).abs() < 1e-12, "{r}");
        // One corner further out than ½ breaks the bound on some ray.
        let out = [scale(fan[0], 0.9), scale(fan[1], 0.5), scale(fan[2], 0.5)];
        assert!(reach([0.0; 3], &[out], &patch).unwrap() < rho / 0.5);
    }

    /// Whether every fan triangle (c, rᵢ, rᵢ₊₁) turns counter-clockwise seen from `o`.
    fn sees_all(o: P3, c: P3, rim: &[P3]) -> bool {
        let m = rim.len();
        (0..m).all(|i| dot(sub(c, o), cross(sub(rim[i], o), sub(rim[(i + 1) % m], o))) > 0.0)
    }

    /// A chevron, counter-clockwise in its plane: (0, 0), (4, 0), (4, 1), (1, 1), (1, 4),
    /// (0, 4), with the reflex corner at (1, 1). The mean of its six corners, (5/3, 5/3), lies
    /// beyond the reflex corner; its kernel is the open square (0, 1)².
    const CHEVRON: [[f64; 2]; 6] = [
        [0.0, 0.0],
        [4.0, 0.0],
        [4.0, 1.0],
        [1.0, 1.0],
        [1.0, 4.0],
        [0.0, 4.0],
    ];

    #[test]
    fn a_radial_centre_sees_every_fan_triangle_from_the_volume_centre() {
        // A square rim in the plane z = 1 around the z axis: its mean (0, 0, 1) sees it.
        let square: Vec<P3> = vec![
            [1.0, -1.0, 1.0],
            [1.0, 1.0, 1.0],
            [-1.0, 1.0, 1.0],
            [-1.0, -1.0, 1.0],
        ];
        assert_eq!(radial_centre([0.0; 3], &square), Some([0.0, 0.0, 1.0]));
        // A chevron in the plane z = 1, counter-clockwise seen from above: (0, 0), (4, 0),
        // (4, 1), (1, 1), (1, 4), (0, 4)… with the reflex corner at (1, 1), the mean of its six
        // corners is (5/3, 5/3), beyond the reflex corner: the triangle (mean, (4, 1), (1, 1))
        // turns clockwise. Its kernel is the open square (0, 1)².
        let chevron: Vec<P3> = CHEVRON.iter().map(|p| [p[0], p[1], 1.0]).collect();
        let o = [0.5, 0.5, -1.0];
        assert!(!sees_all(o, mean(chevron.iter().copied()), &chevron));
        let c = radial_centre(o, &chevron).unwrap();
        assert!(sees_all(o, c, &chevron), "{c:?}");
        // Clockwise, no point on its side of o sees it (behind o, the points over the kernel
        // would).
        let mut turned = chevron.clone();
        turned.reverse();
        assert_eq!(radial_centre(o, &turned), None);
    }

    /// The chevron tilted out of its plane by a rotation about the x axis (cos 0.6, sin 0.8),
    /// lifted to z ≥ 3, and its unit normal.
    fn tilted_chevron() -> (Vec<P3>, P3) {
        let (cs, sn) = (0.6, 0.8);
        let chevron = CHEVRON
            .iter()
            .map(|p| [p[0], cs * p[1], sn * p[1] + 3.0])
            .collect();
        (chevron, [0.0, -sn, cs])
    }

    #[test]
    fn a_face_centre_is_its_mean_unless_the_mean_is_outside_its_kernel() {
        // A square: its mean.
        let square: Vec<P3> = vec![
            [0.0, 0.0, 2.0],
            [2.0, 0.0, 2.0],
            [2.0, 2.0, 2.0],
            [0.0, 2.0, 2.0],
        ];
        assert_eq!(face_centre(&square), [1.0, 1.0, 2.0]);
        // The chevron above, tilted out of its plane by a rotation about the x axis: the mean
        // lies beyond the reflex corner, and the centre chosen instead lies in the face's plane
        // and sees every side counter-clockwise about the face's normal.
        let (chevron, n) = tilted_chevron();
        let sees = |c: P3| {
            (0..6).all(|i| {
                let (a, b) = (chevron[i], chevron[(i + 1) % 6]);
                dot(n, cross(sub(a, c), sub(b, c))) > 0.0
            })
        };
        let m = mean(chevron.iter().copied());
        assert!(!sees(m));
        let c = face_centre(&chevron);
        assert!(sees(c), "{c:?}");
        assert!(
            dot(n, sub(c, chevron[0])).abs() < 1e-9,
            "{c:?} off the plane"
        );
    }

    #[test]
    fn a_lifted_kernel_point_lies_on_a_flat_face_and_among_the_corners_of_a_bent_one() {
        // The tilted chevron of the test above is flat: mean value coordinates reproduce linear
        // functions, so the lifted point is the kernel point itself, in the face's plane, and it
        // sees every side.
        let (chevron, n) = tilted_chevron();
        let c = star_point(&chevron).unwrap();
        assert!(dot(n, sub(c, chevron[0])).abs() < 1e-9, "{c:?}");
        assert!((0..6).all(|i| {
            let (a, b) = (chevron[i], chevron[(i + 1) % 6]);
            dot(n, cross(sub(a, c), sub(b, c))) > 0.0
        }));
        // Bend the chevron: corners with x < 1 are raised by (1 − x)², a function the mean value
        // coordinates do not reproduce. Every corner has z ≥ 0 and one has z > 0, so a convex
        // combination with positive weights lies strictly above z = 0, where a point on the plane
        // through the mean need not (the mean plane of a bent face passes below its high corners
        // and above its low ones).
        let bent: Vec<P3> = CHEVRON
            .iter()
            .map(|p| {
                [
                    p[0],
                    p[1],
                    if p[0] < 1.0 {
                        (1.0 - p[0]).powi(2)
                    } else {
                        0.0
                    },
                ]
            })
            .collect();
        let c = star_point(&bent).expect("the bent chevron's projection has a kernel");
        assert!(
            c[2] > 0.0 && c[2] < 1.0,
            "{c:?} not among the corners' heights"
        );
    }
}
