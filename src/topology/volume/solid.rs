//! The common solids, and the one-line volume notation
//! `SOLID X | Ea El Ec | A | Er Ei | RULE [| d]`, e.g. `cube B2 | B2 B2 B2 | A1 | B2 B2 | V1`:
//! every edge of the solid of type `X`, every face (and every face created inside) with E and A,
//! G = (Er, Ei), the volume rule and an optional delay.

use crate::error::{Error, Result, Source, Span};
use crate::topology::edge::EdgeType;
use crate::topology::face::Face;
use crate::topology::rule::Algorithm;
use crate::topology::volume::surface::Surface;
use crate::topology::volume::{Volume, VolumeRule};
use std::collections::HashMap;

/// A solid whose faces are polygons with shared corners.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Solid {
    /// Six squares.
    Cube,
    /// Four triangles.
    Tetrahedron,
    /// Eight triangles.
    Octahedron,
    /// Two n-gons and n squares (n ≥ 3).
    Prism(usize),
    /// Four triangles and four hexagons.
    TruncatedTetrahedron,
}

impl Solid {
    /// The name in the notation.
    pub fn parse(name: &str) -> Option<Solid> {
        match name {
            "cube" => Some(Solid::Cube),
            "tetrahedron" => Some(Solid::Tetrahedron),
            "octahedron" => Some(Solid::Octahedron),
            "truncated-tetrahedron" => Some(Solid::TruncatedTetrahedron),
            _ => {
                let n: usize = name.strip_prefix("prism-")?.parse().ok()?;
                (3..=64).contains(&n).then_some(Solid::Prism(n))
            }
        }
    }

    /// The faces as corner lists, counter-clockwise seen from outside.
    pub fn polygons(self) -> Vec<Vec<usize>> {
        match self {
            // Corner x + 2y + 4z of the unit cube.
            Solid::Cube => vec![
                vec![0, 2, 3, 1],
                vec![4, 5, 7, 6],
                vec![0, 1, 5, 4],
                vec![2, 6, 7, 3],
                vec![0, 4, 6, 2],
                vec![1, 3, 7, 5],
            ],
            Solid::Tetrahedron => vec![vec![0, 2, 1], vec![0, 1, 3], vec![1, 2, 3], vec![0, 3, 2]],
            // Corners +x, −x, +y, −y, +z, −z.
            Solid::Octahedron => vec![
                vec![0, 2, 4],
                vec![2, 1, 4],
                vec![1, 3, 4],
                vec![3, 0, 4],
                vec![2, 0, 5],
                vec![1, 2, 5],
                vec![3, 1, 5],
                vec![0, 3, 5],
            ],
            Solid::Prism(n) => {
                let mut faces = vec![(0..n).rev().collect(), (n..2 * n).collect()];
                for i in 0..n {
                    let j = (i + 1) % n;
                    faces.push(vec![i, j, n + j, n + i]);
                }
                faces
            }
            Solid::TruncatedTetrahedron => {
                // Cut every corner of the tetrahedron: corner (v, w) lies on edge vw next to v.
                let tetra = Solid::Tetrahedron.polygons();
                let id = |v: usize, w: usize| 4 * v + w;
                let mut faces: Vec<Vec<usize>> = tetra
                    .iter()
                    .map(|t| {
                        (0..3)
                            .flat_map(|i| {
                                let (a, b) = (t[i], t[(i + 1) % 3]);
                                [id(a, b), id(b, a)]
                            })
                            .collect()
                    })
                    .collect();
                // The triangle at v runs against the cuts of the hexagons around v.
                for v in 0..4 {
                    let mut next: HashMap<usize, usize> = HashMap::new();
                    for t in &tetra {
                        let i = t.iter().position(|&x| x == v);
                        if let Some(i) = i {
                            let (u, w) = (t[(i + 2) % 3], t[(i + 1) % 3]);
                            // The hexagon runs (v,u) → (v,w); the triangle (v,w) → (v,u).
                            next.insert(id(v, w), id(v, u));
                        }
                    }
                    let first = *next.keys().min().expect("three neighbours");
                    let mut tri = vec![first];
                    while tri.len() < 3 {
                        tri.push(next[tri.last().expect("non-empty")]);
                    }
                    faces.push(tri);
                }
                faces
            }
        }
    }

    /// The surface of the solid with every edge of type `x` and every face with E and A of
    /// `template` (its boundary is ignored).
    pub fn surface(self, x: EdgeType, template: &Face) -> Surface {
        self.surface_with(|_| x, template)
    }

    /// The surface of the solid with edge `k` of type `edge(k)`, numbering the solid's edges
    /// in order of first appearance (both faces of an edge get its type).
    pub fn surface_with(self, edge: impl Fn(usize) -> EdgeType, template: &Face) -> Surface {
        let polys = self.polygons();
        let mut at: HashMap<(usize, usize), (usize, usize)> = HashMap::new();
        for (f, p) in polys.iter().enumerate() {
            for i in 0..p.len() {
                at.insert((p[i], p[(i + 1) % p.len()]), (f, i));
            }
        }
        let glue = polys
            .iter()
            .map(|p| {
                (0..p.len())
                    .map(|i| at[&(p[(i + 1) % p.len()], p[i])])
                    .collect()
            })
            .collect();
        let mut number: HashMap<(usize, usize), usize> = HashMap::new();
        for p in &polys {
            for i in 0..p.len() {
                let (a, b) = (p[i], p[(i + 1) % p.len()]);
                let next = number.len();
                number.entry((a.min(b), a.max(b))).or_insert(next);
            }
        }
        let faces = polys
            .iter()
            .map(|p| Face {
                boundary: (0..p.len())
                    .map(|i| {
                        let (a, b) = (p[i], p[(i + 1) % p.len()]);
                        edge(number[&(a.min(b), a.max(b))])
                    })
                    .collect(),
                params: template.params,
                algorithm: template.algorithm.clone(),
                delay: 1,
            })
            .collect();
        Surface { faces, glue }
    }
}

/// Parses the one-line volume notation (errors carry the column on line 1 of `text`).
pub fn parse_volume(text: &str) -> Result<Volume> {
    parse_with(text, &[])
}

/// [`parse_volume`] with algorithm names defined elsewhere.
pub fn parse_with(text: &str, named: &[(String, Algorithm)]) -> Result<Volume> {
    let src = Source::command_line(text);
    let err = |col: usize, len: usize, code: &'static str, m: String| {
        Error::syntax(
            code,
            m,
            Span {
                line: 1,
                col,
                len: len.max(1),
            },
            Some(&src),
        )
    };
    // Fields with their 1-based start columns.
    let mut fields: Vec<(usize, &str)> = Vec::new();
    let mut col = 1;
    for part in text.split('|') {
        let lead = part.chars().take_while(|c| c.is_whitespace()).count();
        fields.push((col + lead, part.trim()));
        col += part.chars().count() + 1;
    }
    if !(5..=6).contains(&fields.len()) {
        return Err(err(
            1,
            text.chars().count(),
            "E1201",
            format!(
                "a volume has 5 or 6 fields separated by `|` (SOLID X | Ea El Ec | A | Er Ei | RULE [| d]), found {}",
                fields.len()
            ),
        ));
    }
    let (c0, head) = fields[0];
    let mut words = head.split_whitespace();
    let (name, edge) = (words.next().unwrap_or(""), words.next());
    let solid = Solid::parse(name).ok_or_else(|| {
        err(
            c0,
            name.chars().count(),
            "E1202",
            format!("unknown solid `{name}`: cube, tetrahedron, octahedron, prism-N (3 ≤ N ≤ 64) or truncated-tetrahedron"),
        )
    })?;
    let edge_col = c0 + name.chars().count() + 1;
    let Some(edge) = edge else {
        return Err(err(
            c0,
            head.chars().count(),
            "E1201",
            format!("`{name}` needs the type of its edges (`{name} B2`)"),
        ));
    };
    if words.next().is_some() {
        return Err(err(
            c0,
            head.chars().count(),
            "E1201",
            "the first field is a solid and one edge type (`cube B2`)".into(),
        ));
    }
    let x = EdgeType::parse(edge, edge_col).map_err(|e| e.within(&src, 1, 0))?;
    // E and A are read as a face would be, on a face of the solid's first polygon size.
    let (ce, e) = fields[1];
    let (ca, a) = fields[2];
    let sides = solid.polygons()[0].len();
    let face_text = format!("{} | {e} | {a}", vec![edge; sides].join(" "));
    let template = Face::parse_with(&face_text, named).map_err(|_| {
        err(
            ce,
            (ca + a.chars().count()).saturating_sub(ce),
            "E1203",
            format!("`{e} | {a}`: expected the face parameters Ea El Ec and an algorithm (`B2 B2 B2 | A1`)"),
        )
    })?;
    let (cg, g) = fields[3];
    let gs: Vec<&str> = g.split_whitespace().collect();
    if gs.len() != 2 {
        return Err(err(
            cg,
            g.chars().count(),
            "E1204",
            "G is two edge types: radial Er and inner Ei (`B2 B2`)".into(),
        ));
    }
    let radial = EdgeType::parse(gs[0], cg).map_err(|e| e.within(&src, 1, 0))?;
    let inner = EdgeType::parse(gs[1], cg).map_err(|e| e.within(&src, 1, 0))?;
    let (cr, r) = fields[4];
    let rule = match r {
        "V1" => VolumeRule::V1,
        "V2" => VolumeRule::V2,
        _ => {
            return Err(err(
                cr,
                r.chars().count(),
                "E1205",
                format!("unknown volume rule `{r}`: V1 or V2"),
            ))
        }
    };
    let delay = match fields.get(5) {
        None => 1,
        Some(&(cd, d)) => match d.parse::<u32>() {
            Ok(d) if (1..=64).contains(&d) => d,
            _ => {
                return Err(err(
                    cd,
                    d.chars().count(),
                    "E1206",
                    format!("the volume delay `{d}` must be an integer from 1 to 64"),
                ))
            }
        },
    };
    Ok(Volume {
        surface: solid.surface(x, &template),
        radial,
        inner,
        params: template.params,
        algorithm: template.algorithm,
        rule,
        delay,
    })
}
