//! The level-n solid of a volume or of an assembly evaluated on its placement, level by level,
//! and the least thickness of its volumes.

use super::cells::{
    add, cross, dot, norm, scale, sub, GeoVolume, InnerFan, Reading, SolidGeometry, P3,
};
use super::placement::{place_assembly, Placement};
use super::step::{check_glue, Builder};
use crate::error::Result;
use crate::topology::volume::{Volume, VolumeAssembly};
use std::collections::HashMap;

/// The start of the evaluation: the level-0 complex of the assembly on its placement, one cell
/// per cell of [`VolumeAssembly::start_map`].
fn start(b: &mut Builder, a: &VolumeAssembly, placement: &Placement) -> Result<Vec<GeoVolume>> {
    let map = a.start_map();
    let mut ids: Vec<Option<usize>> = vec![None; map.corner_count()];
    for (v, faces) in map.corner.iter().enumerate() {
        for (f, row) in faces.iter().enumerate() {
            for (i, &c) in row.iter().enumerate() {
                if ids[c].is_none() {
                    ids[c] = Some(b.point(placement[v][f][i]));
                }
            }
        }
    }
    let ids: Vec<usize> = ids
        .into_iter()
        .map(|x| x.expect("every corner placed"))
        .collect();
    let mut edge_of: Vec<Option<usize>> = vec![None; map.edge_count()];
    let mut face_of: Vec<Option<usize>> = vec![None; map.faces.len()];
    let mut out = Vec::with_capacity(a.volumes.len());
    for (v, vol) in a.volumes.iter().enumerate() {
        let mut faces = Vec::with_capacity(vol.surface.faces.len());
        for (f, face) in vol.surface.faces.iter().enumerate() {
            let len = face.boundary.len();
            let corners: Vec<usize> = (0..len).map(|i| ids[map.corner[v][f][i]]).collect();
            let mut edges = Vec::with_capacity(len);
            let mut forward = Vec::with_capacity(len);
            for i in 0..len {
                let (s, t) = (corners[i], corners[(i + 1) % len]);
                let e = match edge_of[map.side[v][f][i]] {
                    Some(e) => e,
                    None => {
                        let e = b.edge(s, t, face.boundary[i]);
                        edge_of[map.side[v][f][i]] = Some(e);
                        e
                    }
                };
                edges.push(e);
                forward.push(b.edges[e].a == s && b.edges[e].b == t);
            }
            let g = map.face[v][f];
            let id = match face_of[g] {
                Some(id) => id,
                None => {
                    let id = b.face(face.clone(), corners.clone(), None);
                    face_of[g] = Some(id);
                    id
                }
            };
            faces.push(Reading {
                face: id,
                corners,
                edges,
                forward,
            });
        }
        check_glue(vol, &faces, &b.edges)?;
        out.push(GeoVolume {
            volume: vol.clone(),
            faces,
        });
    }
    Ok(out)
}

/// Evaluates the level-`level` solid of a volume on its default placement. The caller bounds
/// the work first (the exact number of level-n cells is known from the topology).
pub fn evaluate_volume(v: &Volume, level: u32) -> Result<SolidGeometry> {
    let a = VolumeAssembly::single(v.clone());
    let placement = place_assembly(&a, &[], &[])?;
    evaluate_assembly(&a, &placement, level, InnerFan::RimMean)
}

/// Evaluates the level-`level` solid of an assembly on a placement ([`place_assembly`]): one
/// complex, a face shared by two volumes subdivided once; inner faces fanned as `fan` says. The
/// caller bounds the work first.
pub fn evaluate_assembly(
    a: &VolumeAssembly,
    placement: &Placement,
    level: u32,
    fan: InnerFan,
) -> Result<SolidGeometry> {
    let mut b = Builder {
        fan,
        points: Vec::new(),
        edges: Vec::new(),
        faces: Vec::new(),
        pieces: HashMap::new(),
        gap_point: HashMap::new(),
        spoke: HashMap::new(),
        lacuna: HashMap::new(),
        gap_side: HashMap::new(),
        subface: HashMap::new(),
        side: HashMap::new(),
        inner_edge: HashMap::new(),
        steps: HashMap::new(),
        face_steps: HashMap::new(),
        holes: Vec::new(),
    };
    let mut volumes = start(&mut b, a, placement)?;
    for _ in 0..level {
        b.holes.clear();
        let mut next = Vec::new();
        for (vid, gv) in volumes.iter().enumerate() {
            next.extend(b.step(vid, gv)?);
        }
        volumes = next;
        // Keys of one level are not needed at the next (face and volume numbers are fresh).
        b.side.clear();
    }
    Ok(SolidGeometry {
        level,
        points: b.points,
        edges: b.edges,
        faces: b.faces,
        volumes,
        holes: b.holes,
    })
}

/// The distance from `p` along the unit direction `d` to the first triangle it meets further
/// than a small tolerance (the surface's thickness there).
fn thickness(p: P3, d: P3, tris: &[[P3; 3]]) -> Option<f64> {
    let mut best: Option<f64> = None;
    let scale_of = tris
        .iter()
        .flat_map(|t| t.iter())
        .map(|q| norm(sub(*q, p)))
        .fold(0.0f64, f64::max);
    let eps = 1e-7 * scale_of.max(1e-30);
    for t in tris {
        // Möller–Trumbore.
        let e1 = sub(t[1], t[0]);
        let e2 = sub(t[2], t[0]);
        let h = cross(d, e2);
        let a = dot(e1, h);
        if a.abs() < 1e-14 * norm(e1) * norm(e2) {
            continue;
        }
        let f = 1.0 / a;
        let s = sub(p, t[0]);
        let u = f * dot(s, h);
        if !(-1e-9..=1.0 + 1e-9).contains(&u) {
            continue;
        }
        let q = cross(s, e1);
        let w = f * dot(d, q);
        if w < -1e-9 || u + w > 1.0 + 1e-9 {
            continue;
        }
        let dist = f * dot(e2, q);
        if dist > eps && best.is_none_or(|b| dist < b) {
            best = Some(dist);
        }
    }
    best
}

/// The least thickness of a volume of the solid: from every corner of its surface, along the
/// inward normal of every face there, the distance to its surface (an estimate: corners only).
pub fn least_thickness(g: &SolidGeometry, v: &GeoVolume) -> Option<f64> {
    let mut tris: Vec<[P3; 3]> = Vec::new();
    let mut rays: Vec<(usize, P3)> = Vec::new();
    for r in &v.faces {
        let c = g.faces[r.face].center;
        let mut n = [0.0; 3];
        for i in 0..r.corners.len() {
            let a = g.points[r.corners[i]];
            let b = g.points[r.corners[(i + 1) % r.corners.len()]];
            n = add(n, cross(sub(a, c), sub(b, c)));
            tris.push([c, a, b]);
        }
        let len = norm(n);
        if len > 0.0 {
            for &p in &r.corners {
                rays.push((p, scale(n, -1.0 / len)));
            }
        }
    }
    let mut least: Option<f64> = None;
    for (p, d) in rays {
        if let Some(h) = thickness(g.points[p], d, &tris) {
            least = Some(least.map_or(h, |l: f64| l.min(h)));
        }
    }
    least
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::volume::cells::{mean, SHRINK};
    use crate::geometry::volume::placement::default_placement;
    use crate::topology::volume::parse_volume;

    #[test]
    fn a_surface_that_is_no_shorthand_solid_has_no_default_placement() {
        // The tetrahedron with its faces listed in another order is the same sphere, but its
        // gluing is not the one `Solid::Tetrahedron` writes: no placement is guessed (E1210).
        let mut v = parse_volume("tetrahedron B2 | B2 B2 B2 | A1 | B2 B2 | V1").unwrap();
        assert!(default_placement(&v).is_some());
        let order = [1usize, 0, 2, 3];
        let new_index = |f: usize| order.iter().position(|&o| o == f).unwrap();
        let faces = order.iter().map(|&f| v.surface.faces[f].clone()).collect();
        let glue = order
            .iter()
            .map(|&f| {
                v.surface.glue[f]
                    .iter()
                    .map(|&(g, j)| (new_index(g), j))
                    .collect()
            })
            .collect();
        v.surface = crate::topology::volume::Surface { faces, glue };
        assert_eq!(v.surface.check(), Ok(()));
        assert!(default_placement(&v).is_none());
        assert_eq!(evaluate_volume(&v, 1).unwrap_err().code(), "E1210");
    }

    #[test]
    fn the_solids_are_placed_counter_clockwise_from_outside() {
        for name in [
            "cube",
            "tetrahedron",
            "octahedron",
            "prism-5",
            "truncated-tetrahedron",
        ] {
            let v = parse_volume(&format!("{name} B2 | B2 B2 B2 | A1 | B2 B2 | V1")).unwrap();
            let (_, polys) = default_placement(&v).unwrap();
            // Every face is planar with its normal pointing away from the origin (the centre).
            for p in &polys {
                let c = mean(p.iter().copied());
                let mut n = [0.0; 3];
                for i in 0..p.len() {
                    n = add(n, cross(p[i], p[(i + 1) % p.len()]));
                }
                assert!(dot(n, c) > 0.0, "{name}: a face is wound inwards");
                for q in p {
                    assert!(
                        dot(sub(*q, c), n).abs() < 1e-9,
                        "{name}: a face is not flat"
                    );
                }
            }
        }
    }

    #[test]
    fn inner_corners_of_the_cube_are_its_rim_points_shrunk_towards_its_centre() {
        // By hand: the cube on [−1, 1]³ has its centre o at the origin (every corner is counted
        // three times, once per face, and the corners are symmetric). At level 1 its rim points
        // are the 12 edge midpoints and the 24 lacuna corners (c + ½(j − c) on each face), all
        // on the surface (max |coordinate| = 1); with the 8 cube corners that is 44 surface
        // points. Each rim point has one radial edge (its two sub-volumes share it through their
        // spoke face), ending at p + σ(o − p) = 0.65 p: 36 inner corners, max |coordinate| =
        // 0.65, each 0.65 times a rim point. 44 + 36 = 80 corners (docs/VOLUMES.md).
        let v = parse_volume("cube B2 | B2 B2 B2 | A1 | B2 B2 | V1").unwrap();
        let g = evaluate_volume(&v, 1).unwrap();
        let mut corners = std::collections::BTreeSet::new();
        for gv in &g.volumes {
            for r in &gv.faces {
                corners.extend(r.corners.iter().copied());
            }
        }
        let size = |p: P3| p.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let (outer, inner): (Vec<P3>, Vec<P3>) = corners
            .iter()
            .map(|&c| g.points[c])
            .partition(|&p| (size(p) - 1.0).abs() < 1e-12);
        assert_eq!((outer.len(), inner.len()), (44, 36));
        for q in &inner {
            assert!((size(*q) - (1.0 - SHRINK)).abs() < 1e-12, "{q:?}");
            assert!(
                outer
                    .iter()
                    .any(|p| norm(sub(scale(*p, 1.0 - SHRINK), *q)) < 1e-12),
                "{q:?} is no rim point shrunk towards the centre"
            );
        }
    }
}
