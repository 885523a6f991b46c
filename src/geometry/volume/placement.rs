//! The start of a volume's solid in 3D: the corners of the shorthand solids, their default
//! placement, and the placement of an assembly (given coordinates, solids glued by
//! similarities).

use super::cells::{add, cross, dot, geometry_error, lerp, mean, norm, scale, sub, P3};
use crate::error::Result;
use crate::input::Corners;
use crate::topology::volume::{Solid, Volume, VolumeAssembly};
use std::collections::HashMap;

/// The corners of a solid, indexed as [`Solid::polygons`] numbers them: regular solids with
/// their centre at the origin and edges of comparable length.
pub fn solid_corners(solid: Solid) -> Vec<P3> {
    match solid {
        Solid::Cube => (0..8)
            .map(|i| {
                let b = |k: usize| if i >> k & 1 == 1 { 1.0 } else { -1.0 };
                [b(0), b(1), b(2)]
            })
            .collect(),
        Solid::Tetrahedron => vec![
            [1.0, 1.0, 1.0],
            [1.0, -1.0, -1.0],
            [-1.0, 1.0, -1.0],
            [-1.0, -1.0, 1.0],
        ],
        Solid::Octahedron => vec![
            [1.5, 0.0, 0.0],
            [-1.5, 0.0, 0.0],
            [0.0, 1.5, 0.0],
            [0.0, -1.5, 0.0],
            [0.0, 0.0, 1.5],
            [0.0, 0.0, -1.5],
        ],
        Solid::Prism(n) => {
            let h = (std::f64::consts::PI / n as f64).sin();
            let ring = |z: f64| {
                (0..n).map(move |i| {
                    let a = 2.0 * std::f64::consts::PI * i as f64 / n as f64;
                    [a.cos(), a.sin(), z]
                })
            };
            ring(-h).chain(ring(h)).collect()
        }
        Solid::TruncatedTetrahedron => {
            let t = solid_corners(Solid::Tetrahedron);
            (0..16)
                .map(|id| {
                    let (v, w) = (id / 4, id % 4);
                    if v == w {
                        [0.0; 3]
                    } else {
                        lerp(t[v], t[w], 1.0 / 3.0)
                    }
                })
                .collect()
        }
    }
}

/// The solids whose surface a volume may have been written with.
pub(super) fn candidates() -> impl Iterator<Item = Solid> {
    [
        Solid::Cube,
        Solid::Tetrahedron,
        Solid::Octahedron,
        Solid::TruncatedTetrahedron,
    ]
    .into_iter()
    .chain((3..=64).map(Solid::Prism))
}

/// The default placement of a volume's surface: the solid it was written as (its gluing is that
/// solid's), with the solid's corners. `None` when the surface is no shorthand solid.
pub fn default_placement(v: &Volume) -> Option<(Solid, Vec<Vec<P3>>)> {
    let first = v.surface.faces.first()?;
    for s in candidates() {
        let polys = s.polygons();
        if polys.len() != v.surface.faces.len() {
            continue;
        }
        if s.surface_with(|_| first.boundary[0], first).glue != v.surface.glue {
            continue;
        }
        let mut corners = solid_corners(s);
        // Counter-clockwise from outside: the enclosed volume is positive; mirror otherwise.
        let vol: f64 = polys
            .iter()
            .map(|p| {
                (1..p.len() - 1)
                    .map(|i| dot(corners[p[0]], cross(corners[p[i]], corners[p[i + 1]])))
                    .sum::<f64>()
            })
            .sum();
        if vol < 0.0 {
            for c in &mut corners {
                c[0] = -c[0];
            }
        }
        let placed = polys
            .iter()
            .map(|p| p.iter().map(|&i| corners[i]).collect())
            .collect();
        return Some((s, placed));
    }
    None
}

/// Where the corners of the volumes of an assembly lie: `[v][f][i]` is corner `i` (the start of
/// edge `i`) of face `f` of volume `v`.
pub type Placement = Vec<Vec<Vec<P3>>>;

/// The enclosed volume of a closed surface given as polygons (fans around their means): positive
/// when the polygons run counter-clockwise seen from outside.
fn enclosed(polys: &[Vec<P3>]) -> f64 {
    polys
        .iter()
        .map(|p| {
            let c = mean(p.iter().copied());
            (0..p.len())
                .map(|i| dot(c, cross(p[i], p[(i + 1) % p.len()])))
                .sum::<f64>()
        })
        .sum::<f64>()
        / 6.0
}

/// A similarity (rotation, uniform scale, translation; no reflection) taking the polygon `q` onto
/// `p` corner by corner, if there is one (up to rounding).
fn fit(q: &[P3], p: &[P3]) -> Option<impl Fn(P3) -> P3> {
    let frame = |pts: &[P3]| -> Option<(P3, [P3; 3], f64)> {
        let c = mean(pts.iter().copied());
        let mut n = [0.0; 3];
        for i in 0..pts.len() {
            n = add(n, cross(sub(pts[i], c), sub(pts[(i + 1) % pts.len()], c)));
        }
        let nl = norm(n);
        let r = (pts.iter().map(|x| dot(sub(*x, c), sub(*x, c))).sum::<f64>() / pts.len() as f64)
            .sqrt();
        if nl <= 1e-12 * r * r || r == 0.0 {
            return None;
        }
        let n = scale(n, 1.0 / nl);
        let d = sub(pts[0], c);
        let u = sub(d, scale(n, dot(d, n)));
        let ul = norm(u);
        if ul <= 1e-12 * r {
            return None;
        }
        let u = scale(u, 1.0 / ul);
        Some((c, [u, cross(n, u), n], r))
    };
    let (cq, bq, rq) = frame(q)?;
    let (cp, bp, rp) = frame(p)?;
    let s = rp / rq;
    let map = move |x: P3| {
        let d = sub(x, cq);
        let mut out = cp;
        for k in 0..3 {
            out = add(out, scale(bp[k], s * dot(d, bq[k])));
        }
        out
    };
    let worst = q
        .iter()
        .zip(p)
        .map(|(a, b)| norm(sub(map(*a), *b)))
        .fold(0.0f64, f64::max);
    (worst <= 1e-9 * rp).then_some(map)
}

/// Places the volumes of an assembly in 3D: a volume with user coordinates (`given`) where they
/// say; a shorthand solid glued to a placed volume by the similarity that lays its shared face on
/// the placed one (so the solid lands on the far side); the first shorthand of a group that
/// nothing places yet on its default placement ([`default_placement`]). Refused: a volume left
/// without a place (E1210), coordinates that wind a surface inside out (E1215), and two volumes
/// that put one corner of the level-0 complex at two places (E1216).
pub fn place_assembly(
    a: &VolumeAssembly,
    given: &[Option<Corners>],
    names: &[String],
) -> Result<Placement> {
    let n = a.volumes.len();
    let name = |v: usize| match names.get(v) {
        Some(x) => format!("volume `{x}`"),
        None if n == 1 => "the volume".to_string(),
        None => format!("volume {v}"),
    };
    let mut placed: Vec<Option<Corners>> =
        (0..n).map(|v| given.get(v).cloned().flatten()).collect();
    let default: Vec<Option<Corners>> = a
        .volumes
        .iter()
        .map(|v| default_placement(v).map(|(_, p)| p))
        .collect();
    let mut group = crate::topology::component::Dsu::new(n);
    for s in &a.shared {
        group.union(s.a.0, s.b.0);
    }
    loop {
        let mut progress = false;
        for s in &a.shared {
            for (here, there) in [(s.a, s.b), (s.b, s.a)] {
                let (vh, fh, eh) = here;
                let (vt, ft, et) = there;
                if placed[vh].is_none() || placed[vt].is_some() {
                    continue;
                }
                let Some(own) = &default[vt] else { continue };
                let len = own[ft].len();
                // Corner `eh + k` of the placed face is corner `et + 1 − k` of the other.
                let target: Vec<P3> = (0..len)
                    .map(|j| {
                        placed[vh].as_ref().expect("placed")[fh]
                            [(eh + et + 1 + len - j % len) % len]
                    })
                    .collect();
                let Some(map) = fit(&own[ft], &target) else {
                    return Err(geometry_error(
                        "E1216",
                        format!(
                            "{} cannot be laid on face {fh} of {}: its face {ft} has another shape (give its corners)",
                            name(vt),
                            name(vh)
                        ),
                    ));
                };
                placed[vt] = Some(
                    own.iter()
                        .map(|f| f.iter().map(|&x| map(x)).collect())
                        .collect(),
                );
                progress = true;
            }
        }
        if !progress {
            let next = (0..n).find(|&v| {
                placed[v].is_none()
                    && default[v].is_some()
                    && (0..n).all(|w| placed[w].is_none() || group.find(w) != group.find(v))
            });
            match next {
                Some(v) => placed[v] = default[v].clone(),
                None => break,
            }
        }
    }
    let mut out = Vec::with_capacity(n);
    for (v, p) in placed.into_iter().enumerate() {
        let Some(p) = p else {
            return Err(geometry_error(
                "E1210",
                format!("the surface of {} is none of the shorthand solids (cube, tetrahedron, octahedron, prism-N, truncated-tetrahedron) and nothing places it: give its corners (`corners FACE: X Y Z, …` lines in its block, docs/FORMATS.md)", name(v)),
            ));
        };
        if enclosed(&p).partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            return Err(geometry_error(
                "E1215",
                format!("the corners of {} do not enclose a positive volume with its faces counter-clockwise seen from outside (mirror them, or list every face's corners counter-clockwise from outside)", name(v)),
            ));
        }
        out.push(p);
    }
    // One corner of the level-0 complex, one place.
    let map = a.start_map();
    let size = out
        .iter()
        .flatten()
        .flatten()
        .map(|x| norm(*x))
        .fold(0.0f64, f64::max)
        .max(1e-300);
    let mut seen: HashMap<usize, (P3, usize)> = HashMap::new();
    for (v, faces) in out.iter().enumerate() {
        for (f, face) in faces.iter().enumerate() {
            for (i, &x) in face.iter().enumerate() {
                let c = map.corner[v][f][i];
                match seen.get(&c) {
                    Some(&(y, w)) if norm(sub(x, y)) > 1e-9 * size => {
                        return Err(geometry_error(
                            "E1216",
                            format!(
                                "corner {i} of face {f} of {} is at ({:.6} {:.6} {:.6}) but {} puts the same corner at ({:.6} {:.6} {:.6}): volumes sharing a face must agree on its corners",
                                name(v), x[0], x[1], x[2], name(w), y[0], y[1], y[2]
                            ),
                        ))
                    }
                    Some(_) => {}
                    None => {
                        seen.insert(c, (x, v));
                    }
                }
            }
        }
    }
    Ok(out)
}
