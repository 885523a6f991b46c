//! The combinatorial checks, on vertex indices only (the coordinates appear in messages, and in
//! the one exact test of a flat triangle): no degenerate triangle, every edge in exactly two
//! triangles running it in opposite directions, every vertex's link one cycle.

use super::exact::{exactly, normal_axis};
use super::input::Mesh;
use super::report::{Finding, Tally};

/// The undirected edge `{a, b}` as one key.
fn key(a: u32, b: u32) -> u64 {
    (u64::from(a.min(b)) << 32) | u64::from(a.max(b))
}

fn ends(k: u64) -> (u32, u32) {
    ((k >> 32) as u32, k as u32)
}

/// A finding naming triangles and vertices, with the vertices' coordinates.
pub(super) fn finding(
    mesh: &Mesh,
    kind: &'static str,
    triangles: Vec<usize>,
    vertices: Vec<u32>,
    message: String,
) -> Finding {
    Finding {
        kind,
        coordinates: vertices
            .iter()
            .map(|&v| mesh.vertices[v as usize])
            .collect(),
        triangles,
        vertices,
        message,
    }
}

/// Degenerate triangles: two corners at one place, or three on one line (every component of
/// the exact normal `(b − a) × (c − a)` is zero). Returns which triangles are degenerate.
pub(super) fn degenerate(mesh: &Mesh, tally: &mut Tally) -> Vec<bool> {
    let mut out = vec![false; mesh.triangles.len()];
    for (t, &[a, b, c]) in mesh.triangles.iter().enumerate() {
        let kind = if a == b || b == c || c == a {
            "two equal corners"
        } else {
            let p = [a, b, c].map(|v| mesh.vertices[v as usize]);
            if exactly!(p, |x| normal_axis(&x[0], &x[1], &x[2])).is_some() {
                continue;
            }
            "three collinear corners"
        };
        out[t] = true;
        tally.add("degenerate triangle", || {
            finding(
                mesh,
                "degenerate triangle",
                vec![t],
                vec![a, b, c],
                format!(
                    "{} has {kind}: {}, {}, {}",
                    mesh.triangle_name(t),
                    mesh.vertex_name(a),
                    mesh.vertex_name(b),
                    mesh.vertex_name(c)
                ),
            )
        });
    }
    out
}

/// The edges: each undirected edge with the triangles using it, sorted by edge. `uses[i]` is
/// `(edge key, triangle << 1 | forward)`, `forward` when the triangle runs it from the smaller
/// vertex index to the larger.
pub(super) struct Edges {
    pub(super) uses: Vec<(u64, u32)>,
}

impl Edges {
    pub(super) fn of(mesh: &Mesh) -> Edges {
        let mut uses = Vec::with_capacity(3 * mesh.triangles.len());
        for (t, tri) in mesh.triangles.iter().enumerate() {
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                if a != b {
                    uses.push((key(a, b), ((t as u32) << 1) | u32::from(a < b)));
                }
            }
        }
        uses.sort_unstable();
        Edges { uses }
    }

    /// The groups of uses of one edge.
    pub(super) fn groups(&self) -> impl Iterator<Item = &[(u64, u32)]> {
        self.uses.chunk_by(|x, y| x.0 == y.0)
    }

    /// Every edge in exactly two triangles, one running it each way.
    pub(super) fn check(&self, mesh: &Mesh, tally: &mut Tally) {
        for g in self.groups() {
            let forward = g.iter().filter(|u| u.1 & 1 == 1).count();
            if g.len() == 2 && forward == 1 {
                continue;
            }
            let (a, b) = ends(g[0].0);
            let kind = match g.len() {
                1 => "open edge",
                2 => "edge run one way twice",
                _ => "edge in more than two triangles",
            };
            tally.add(kind, || {
                let tris: Vec<usize> = g.iter().map(|u| (u.1 >> 1) as usize).collect();
                let names: Vec<String> = tris.iter().map(|&t| mesh.triangle_name(t)).collect();
                let edge = format!("{} – {}", mesh.vertex_name(a), mesh.vertex_name(b));
                let message = match g.len() {
                    1 => format!(
                        "edge {edge} is in one triangle only ({}): the surface is open there",
                        names[0]
                    ),
                    2 => {
                        let (from, to) = match forward {
                            2 => (a, b),
                            _ => (b, a),
                        };
                        format!(
                            "edge {} → {} is run in the same direction by {} and {}: one of them is flipped",
                            mesh.vertex_name(from),
                            mesh.vertex_name(to),
                            names[0],
                            names[1]
                        )
                    }
                    n => format!("edge {edge} is in {n} triangles: {}", names.join(", ")),
                };
                finding(mesh, kind, tris, vec![a, b], message)
            });
        }
    }
}

/// Every vertex's link is one cycle: the triangles around a vertex form one fan. Run only when
/// every edge is in exactly two triangles with opposite directions; then the link of `v` — the
/// edge `b → c` of every triangle `v b c` — enters and leaves each neighbour once, so it is a
/// union of cycles, and this counts them.
pub(super) fn links(mesh: &Mesh, tally: &mut Tally) {
    let mut link: Vec<[u32; 3]> = Vec::with_capacity(3 * mesh.triangles.len());
    for &[a, b, c] in &mesh.triangles {
        link.push([a, b, c]);
        link.push([b, c, a]);
        link.push([c, a, b]);
    }
    link.sort_unstable();
    for g in link.chunk_by(|x, y| x[0] == y[0]) {
        let v = g[0][0];
        // `g` is sorted by the link edge's start: follow the cycle through g[0].
        let next = |from: u32| g.binary_search_by(|e| e[1].cmp(&from)).ok();
        let (mut at, mut steps) = (0usize, 0usize);
        loop {
            steps += 1;
            match next(g[at][2]) {
                Some(i) if i != 0 && steps <= g.len() => at = i,
                _ => break,
            }
        }
        if steps == g.len() {
            continue;
        }
        // Count the fans.
        let mut seen = vec![false; g.len()];
        let mut fans = 0;
        for s in 0..g.len() {
            if seen[s] {
                continue;
            }
            fans += 1;
            let mut at = s;
            while !seen[at] {
                seen[at] = true;
                match next(g[at][2]) {
                    Some(i) => at = i,
                    None => break,
                }
            }
        }
        tally.add("pinched vertex", || {
            let tris: Vec<usize> = mesh
                .triangles
                .iter()
                .enumerate()
                .filter(|(_, t)| t.contains(&v))
                .map(|(i, _)| i)
                .collect();
            finding(
                mesh,
                "pinched vertex",
                tris,
                vec![v],
                format!(
                    "vertex {} joins {fans} fans of triangles ({} triangles around it): the surface is pinched there",
                    mesh.vertex_name(v),
                    g.len()
                ),
            )
        });
    }
}
