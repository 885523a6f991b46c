//! The check of a triangle mesh before it is written (THEORY §11), independent of how it was built:
//! it sees only vertex positions and index triples.
//!
//! Integer checks of the combinatorics: every triangle has three distinct vertices; every directed
//! edge occurs once and its reverse once (so every edge is in exactly two triangles, with opposite
//! orientations: a closed, consistently oriented surface); the link of every vertex is one cycle
//! (no two sheets meeting at a point); the number of connected pieces and the Euler
//! characteristic `V − E + F`. Geometric checks with exact predicates on the `f32` coordinates: no
//! triangle has three collinear points (its three projections on the coordinate planes all flat);
//! the enclosed volume (a floating-point sum) is positive, so the orientation is outward.

use super::solid::Part;

/// What the check found on a part that passed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PartCheck {
    /// Vertices used by triangles.
    pub vertices: usize,
    /// Edges (each in two triangles).
    pub edges: usize,
    /// Triangles.
    pub triangles: usize,
    /// Connected pieces.
    pub components: usize,
    /// V − E + F.
    pub euler: i64,
}

fn find(p: &mut [u32], mut x: u32) -> u32 {
    while p[x as usize] != x {
        let q = p[p[x as usize] as usize];
        p[x as usize] = q;
        x = q;
    }
    x
}

/// Checks a part; `Err` says which check failed and where.
pub fn check_part(part: &Part) -> Result<PartCheck, String> {
    let nv = part.vertices.len();
    let tris = &part.triangles;
    for (i, t) in tris.iter().enumerate() {
        if t.iter().any(|&v| v as usize >= nv) {
            return Err(format!("triangle {i} names a vertex that does not exist"));
        }
        if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
            return Err(format!("triangle {i} repeats a vertex"));
        }
    }
    // Directed edges: each exactly once, each with its reverse.
    let mut directed: Vec<u64> = Vec::with_capacity(3 * tris.len());
    for t in tris {
        for k in 0..3 {
            directed.push((u64::from(t[k]) << 32) | u64::from(t[(k + 1) % 3]));
        }
    }
    directed.sort_unstable();
    if let Some(w) = directed.windows(2).find(|w| w[0] == w[1]) {
        return Err(format!(
            "edge {}–{} is traversed twice in the same direction (two triangles wound the same way, or an edge in more than two triangles)",
            w[0] >> 32,
            w[0] & 0xFFFF_FFFF
        ));
    }
    for &e in &directed {
        let rev = e.rotate_right(32);
        if directed.binary_search(&rev).is_err() {
            return Err(format!(
                "edge {}–{} is in one triangle only (the surface is open there)",
                e >> 32,
                e & 0xFFFF_FFFF
            ));
        }
    }
    let edges = directed.len() / 2;
    // Vertex links: the corners (v, a, b) of the triangles around v chain a → b into cycles.
    let mut corners: Vec<(u32, u32, u32)> = Vec::with_capacity(3 * tris.len());
    for t in tris {
        for k in 0..3 {
            corners.push((t[k], t[(k + 1) % 3], t[(k + 2) % 3]));
        }
    }
    corners.sort_unstable();
    let mut used = 0usize;
    let mut i = 0;
    while i < corners.len() {
        let v = corners[i].0;
        let mut j = i;
        while j < corners.len() && corners[j].0 == v {
            j += 1;
        }
        used += 1;
        // corners[i..j] sorted by a: follow a → b from the first.
        let fan = &corners[i..j];
        let next = |a: u32| fan.binary_search_by(|c| c.1.cmp(&a)).ok().map(|k| fan[k].2);
        let start = fan[0].1;
        let (mut a, mut steps) = (start, 0usize);
        loop {
            a = next(a).ok_or_else(|| format!("the link of vertex {v} is open"))?;
            steps += 1;
            if a == start || steps > fan.len() {
                break;
            }
        }
        if steps != fan.len() {
            return Err(format!(
                "vertex {v} joins {} triangles in more than one fan (two sheets touch at a point)",
                fan.len()
            ));
        }
        i = j;
    }
    // Connected pieces.
    let mut p: Vec<u32> = (0..nv as u32).collect();
    for t in tris {
        let (a, b, c) = (find(&mut p, t[0]), find(&mut p, t[1]), find(&mut p, t[2]));
        p[b as usize] = a;
        let c2 = find(&mut p, c);
        p[c2 as usize] = a;
    }
    let mut roots = std::collections::HashSet::new();
    for t in tris {
        roots.insert(find(&mut p, t[0]));
    }
    // Geometry: no degenerate triangle, outward orientation.
    let mut volume6 = 0.0f64;
    for (i, t) in tris.iter().enumerate() {
        let [a, b, c] = t.map(|v| part.vertices[v as usize].map(f64::from));
        let flat = [(0, 1), (1, 2), (2, 0)].iter().all(|&(x, y)| {
            let q = |p: [f64; 3]| robust::Coord { x: p[x], y: p[y] };
            robust::orient2d(q(a), q(b), q(c)) == 0.0
        });
        if flat {
            return Err(format!("triangle {i} has zero area"));
        }
        volume6 += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
            + a[2] * (b[0] * c[1] - b[1] * c[0]);
    }
    if tris.is_empty() || volume6.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return Err(format!(
            "the enclosed volume is {} mm³ (inward or empty)",
            volume6 / 6.0
        ));
    }
    Ok(PartCheck {
        vertices: used,
        edges,
        triangles: tris.len(),
        components: roots.len(),
        euler: used as i64 - edges as i64 + tris.len() as i64,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::solid::tests::tetra;

    #[test]
    fn a_tetrahedron_is_a_sphere() {
        let c = check_part(&tetra()).unwrap();
        assert_eq!((c.vertices, c.edges, c.triangles), (4, 6, 4));
        assert_eq!((c.euler, c.components), (2, 1));
    }

    #[test]
    fn open_flipped_inward_and_flat_meshes_are_refused() {
        let mut open = tetra();
        open.triangles.pop();
        assert!(check_part(&open).unwrap_err().contains("one triangle only"));
        let mut flipped = tetra();
        flipped.triangles[0] = [0, 1, 2];
        assert!(check_part(&flipped).unwrap_err().contains("same direction"));
        let mut inward = tetra();
        for t in &mut inward.triangles {
            t.swap(1, 2);
        }
        assert!(check_part(&inward).unwrap_err().contains("volume"));
        let mut flat = tetra();
        flat.vertices[3] = [0.5, 0.5, 0.0];
        assert!(check_part(&flat).unwrap_err().contains("zero area"));
    }

    #[test]
    fn two_tetrahedra_sharing_a_vertex_are_not_a_manifold() {
        let mut t = tetra();
        let shift = |p: [f32; 3]| [-p[0], -p[1], -p[2]];
        let more: Vec<[f32; 3]> = t.vertices[1..].iter().map(|&p| shift(p)).collect();
        t.vertices.extend(more);
        // The mirrored tetrahedron shares vertex 0 (mirroring reverses orientation: swap).
        let tris: Vec<[u32; 3]> = t
            .triangles
            .iter()
            .map(|tr| tr.map(|v| if v == 0 { 0 } else { v + 3 }))
            .map(|[a, b, c]| [a, c, b])
            .collect();
        t.triangles.extend(tris);
        assert!(check_part(&t).unwrap_err().contains("more than one fan"));
    }
}
