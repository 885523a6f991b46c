//! Closed surfaces of faces glued edge to edge: the boundary of a volume, as an oriented map.
//!
//! Every face is read counter-clockwise as seen from outside the volume; edge `i` of a face runs
//! from its corner `i` to its corner `i + 1`. Edge `i` of face `f` is glued to exactly one edge `j`
//! of a face `g`, traversed the other way, so corner `i + 1` of `f` is corner `j` of `g`. Going
//! around a point of the surface is the permutation `σ(f, i) = glue(f, i − 1)` of the corners, so
//! the points are the orbits of `σ` and every point's link is a cycle: the glued surface is always
//! a closed oriented surface, and it is a sphere exactly when it is connected and
//! `V − E + F = 2`.
//!
//! Two surfaces are the same type when an orientation-preserving relabelling of faces and a
//! rotation of each face's boundary turns one into the other, with equal face types. The canonical
//! form is the least code over all rooted traversals ([`Surface::canonical`]).

use crate::topology::face::Face;
use std::collections::VecDeque;

/// A closed surface of faces glued edge to edge.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Surface {
    /// The faces, each read counter-clockwise from outside.
    pub faces: Vec<Face>,
    /// `glue[f][i] = (g, j)`: edge `i` of face `f` is glued to edge `j` of face `g`.
    pub glue: Vec<Vec<(usize, usize)>>,
}

/// One item of the code of a rooted traversal; codes compare lexicographically.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Token {
    /// A face in discovery order, read from its root edge: its notation.
    Face(String),
    /// The edge glued to the next edge of the current face: (discovery index, offset from root).
    Glue(usize, usize),
}

impl Surface {
    /// Number of edges: every edge is glued to exactly one other, so half the face sides.
    pub fn edge_count(&self) -> usize {
        self.faces.iter().map(|f| f.boundary.len()).sum::<usize>() / 2
    }

    /// The points of the surface: for every corner `(f, i)`, the index of its point; and the
    /// number of points.
    pub fn vertices(&self) -> (Vec<Vec<usize>>, usize) {
        let mut id: Vec<Vec<usize>> = self
            .faces
            .iter()
            .map(|f| vec![usize::MAX; f.boundary.len()])
            .collect();
        let mut count = 0;
        for f in 0..self.faces.len() {
            for i in 0..self.faces[f].boundary.len() {
                if id[f][i] != usize::MAX {
                    continue;
                }
                let (mut g, mut j) = (f, i);
                while id[g][j] == usize::MAX {
                    id[g][j] = count;
                    (g, j) = self.sigma(g, j);
                }
                count += 1;
            }
        }
        (id, count)
    }

    /// The next corner around the same point: `glue(f, i − 1)`.
    fn sigma(&self, f: usize, i: usize) -> (usize, usize) {
        let n = self.faces[f].boundary.len();
        self.glue[f][(i + n - 1) % n]
    }

    /// V − E + F.
    pub fn euler(&self) -> i64 {
        let (_, v) = self.vertices();
        v as i64 - self.edge_count() as i64 + self.faces.len() as i64
    }

    /// Checks that the gluing is well formed and that the surface is a sphere: every edge glued to
    /// exactly one other edge of the same type and delay (a different side), the surface
    /// connected, and V − E + F = 2. The error names the first face and edge at fault.
    pub fn check(&self) -> Result<(), String> {
        if self.faces.is_empty() {
            return Err("a volume needs at least one face".into());
        }
        if self.glue.len() != self.faces.len() {
            return Err("the gluing does not list every face".into());
        }
        for (f, face) in self.faces.iter().enumerate() {
            if self.glue[f].len() != face.boundary.len() {
                return Err(format!(
                    "face {f} has {} edges but {} gluings",
                    face.boundary.len(),
                    self.glue[f].len()
                ));
            }
            for (i, &(g, j)) in self.glue[f].iter().enumerate() {
                let Some(other) = self.glue.get(g).and_then(|row| row.get(j)) else {
                    return Err(format!("face {f} edge {i} is glued to a missing edge"));
                };
                if *other != (f, i) || (g, j) == (f, i) {
                    return Err(format!(
                        "face {f} edge {i} is glued to face {g} edge {j}, which is glued elsewhere"
                    ));
                }
                let (a, b) = (face.boundary[i], self.faces[g].boundary[j]);
                if a != b {
                    return Err(format!(
                        "face {f} edge {i} ({a}) is glued to face {g} edge {j} ({b}): the types differ"
                    ));
                }
            }
        }
        let mut seen = vec![false; self.faces.len()];
        let mut queue = VecDeque::from([0usize]);
        seen[0] = true;
        while let Some(f) = queue.pop_front() {
            for &(g, _) in &self.glue[f] {
                if !seen[g] {
                    seen[g] = true;
                    queue.push_back(g);
                }
            }
        }
        if let Some(f) = seen.iter().position(|s| !s) {
            return Err(format!("face {f} is not connected to face 0"));
        }
        let chi = self.euler();
        if chi != 2 {
            return Err(format!(
                "the surface has Euler characteristic V − E + F = {chi}, not 2: it is not a sphere"
            ));
        }
        Ok(())
    }

    /// The code of the traversal rooted at edge `i0` of face `f0`, with the discovery order and
    /// the root edge of every face.
    fn code(&self, f0: usize, i0: usize) -> (Vec<Token>, Vec<usize>, Vec<usize>) {
        let n = self.faces.len();
        let mut order = vec![usize::MAX; n];
        let mut root = vec![0usize; n];
        let mut seq = vec![f0];
        order[f0] = 0;
        root[f0] = i0;
        let mut code = Vec::new();
        let mut head = 0;
        while head < seq.len() {
            let f = seq[head];
            head += 1;
            let face = &self.faces[f];
            let len = face.boundary.len();
            let mut rotated = face.clone();
            rotated.boundary.rotate_left(root[f]);
            code.push(Token::Face(rotated.to_string()));
            for k in 0..len {
                let (g, j) = self.glue[f][(root[f] + k) % len];
                if order[g] == usize::MAX {
                    order[g] = seq.len();
                    root[g] = j;
                    seq.push(g);
                }
                let lg = self.faces[g].boundary.len();
                code.push(Token::Glue(order[g], (j + lg - root[g]) % lg));
            }
        }
        (code, seq, root)
    }

    /// The canonical form: faces relabelled in the order of the least rooted traversal, each
    /// rotated to start at its root edge. Two surfaces are of the same type exactly when their
    /// canonical forms are equal. (The surface must be connected.)
    pub fn canonical(&self) -> Surface {
        self.canonical_map().0
    }

    /// [`Surface::canonical`] with where each face went: face `f` becomes face `index[f]`, its
    /// boundary rotated left by `root[f]`.
    pub fn canonical_map(&self) -> (Surface, Vec<usize>, Vec<usize>) {
        // The code starts with the root face read from its root edge: only the least such
        // reading can start the least code.
        let rotation = |f: usize, i: usize| {
            let mut rotated = self.faces[f].clone();
            rotated.boundary.rotate_left(i);
            rotated.to_string()
        };
        let roots: Vec<(usize, usize, String)> = (0..self.faces.len())
            .flat_map(|f| (0..self.faces[f].boundary.len()).map(move |i| (f, i)))
            .map(|(f, i)| (f, i, rotation(f, i)))
            .collect();
        let least = roots.iter().map(|r| &r.2).min().cloned();
        let mut best: Option<(Vec<Token>, Vec<usize>, Vec<usize>)> = None;
        for (f, i, s) in &roots {
            if Some(s) != least.as_ref() {
                continue;
            }
            let c = self.code(*f, *i);
            if best.as_ref().is_none_or(|b| c.0 < b.0) {
                best = Some(c);
            }
        }
        let (_, seq, root) = best.expect("a surface has a face");
        let mut new_index = vec![0usize; self.faces.len()];
        for (k, &f) in seq.iter().enumerate() {
            new_index[f] = k;
        }
        let mut faces = Vec::with_capacity(seq.len());
        let mut glue: Vec<Vec<(usize, usize)>> = Vec::with_capacity(seq.len());
        for &f in &seq {
            let len = self.faces[f].boundary.len();
            let mut face = self.faces[f].clone();
            face.boundary.rotate_left(root[f]);
            faces.push(face);
            glue.push(
                (0..len)
                    .map(|k| {
                        let (g, j) = self.glue[f][(root[f] + k) % len];
                        let lg = self.faces[g].boundary.len();
                        (new_index[g], (j + lg - root[g]) % lg)
                    })
                    .collect(),
            );
        }
        (Surface { faces, glue }, new_index, root)
    }
}
