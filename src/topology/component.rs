//! The exact number of connected components of the union of the level-i cells, derived from the
//! incidence data of the closure (no coordinates).
//!
//! **Which notion of connectedness.** Two cells are *adjacent* when they share an edge: a spoke
//! (`Ea`) between two sub-faces of one parent, or a piece of a parent edge shared between two
//! neighbouring parents (or, at level 0, an edge glued by the assembly). Components are the
//! classes of the transitive closure of adjacency. The topology cannot express cells that touch
//! only at a point without sharing an edge; within one class such contacts change nothing, and
//! between classes they would be a geometric accident of the placement (the default placement puts
//! faces without a shared edge apart). The raster counts components of covered pixels with
//! 8-connectivity (a diagonal step continues a component, so a cell thinner than a pixel does not
//! fall apart); the two notions agree as long as distinct classes are more than a pixel apart, and
//! when they do not, the mismatch is reported as a verification failure, not hidden.
//!
//! **Two derivations.**
//! - *Induction* ([`components_by_induction`]): if the sub-faces of every type are connected
//!   through their spokes, the number of components is the same at every level. Proof: (1) the
//!   children of a cell are connected (hypothesis); (2) if cells A and B share an edge e, e has at
//!   least one piece, and the child of A holding a piece of e shares it with the child of B holding
//!   the same piece, so the children of A and B are connected; (3) every shared edge at level i + 1
//!   is a spoke (inside one parent) or a piece of a shared parent edge (between children of
//!   adjacent parents), so children of parents in different components never become adjacent.
//!   By (1)–(3) the components of level i + 1 are in bijection with those of level i, and level 0
//!   is the assembly's graph of glued edges.
//! - *Union-find over the cells* ([`components_by_cells`]): every level-i cell carries an exact key
//!   per edge (a glued start edge, a spoke of its parent, or piece j of a keyed parent edge, with
//!   the piece index read in one fixed direction so that both sides agree); cells with a common key
//!   are joined. It needs memory proportional to the cells, so it runs under a cell limit: it is
//!   the fallback when the induction's hypothesis fails, and an independent check of it in tests.

use crate::topology::{Origin, TypeSet};
use std::collections::HashMap;

/// A shared edge of the start assembly: two (start face, canonical edge index) pairs.
pub type Glue = [(usize, usize); 2];

/// Union-find with path halving (also used by the volume step and the volume constraints).
pub(crate) struct Dsu(Vec<usize>);

impl Dsu {
    /// `n` singletons.
    pub(crate) fn new(n: usize) -> Dsu {
        Dsu((0..n).collect())
    }
    /// The root of `x`'s class.
    pub(crate) fn find(&mut self, mut x: usize) -> usize {
        while self.0[x] != x {
            self.0[x] = self.0[self.0[x]];
            x = self.0[x];
        }
        x
    }
    /// Joins the classes of `a` and `b`.
    pub(crate) fn union(&mut self, a: usize, b: usize) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            self.0[ra] = rb;
        }
    }
    /// The number of classes.
    pub(crate) fn classes(&mut self) -> usize {
        (0..self.0.len()).filter(|&x| self.find(x) == x).count()
    }
}

/// Whether the sub-faces of type `t` are connected through their shared spokes (a delayed face
/// has one sub-face: connected).
pub fn subfaces_connected(types: &TypeSet, t: usize) -> bool {
    let sub = &types.types[t].subdivision;
    let mut d = Dsu::new(sub.subfaces.len());
    for a in &sub.adjacencies {
        d.union(a.first.0, a.second.0);
    }
    d.classes() <= 1
}

/// Components of the start assembly: start faces joined by glued edges.
pub fn start_components(faces: usize, glue: &[Glue]) -> usize {
    let mut d = Dsu::new(faces);
    for [a, b] in glue {
        d.union(a.0, b.0);
    }
    d.classes()
}

/// The number of components at every level by induction, or `Err(t)` with the first type whose
/// sub-faces are not connected (the hypothesis fails).
pub fn components_by_induction(types: &TypeSet, glue: &[Glue]) -> Result<usize, usize> {
    if let Some(t) = (0..types.types.len()).find(|&t| !subfaces_connected(types, t)) {
        return Err(t);
    }
    Ok(start_components(types.start.len(), glue))
}

/// An edge key: an exact identity shared by the two cells that have the edge, and the direction
/// in which this cell traverses it relative to the key's reference direction.
#[derive(Clone, Copy)]
struct Key {
    id: u64,
    reversed: bool,
}

/// The number of components of the union of the level-i cells for i = 0..=level, by union-find
/// over the cells, or `None` when a level has more than `max_cells` cells. Also checks that no
/// edge key is held by more than two cells (`Err` with the level otherwise).
pub fn components_by_cells(
    types: &TypeSet,
    glue: &[Glue],
    level: u32,
    max_cells: usize,
) -> Option<Result<Vec<usize>, u32>> {
    let mut next_id = 0u64;
    let mut fresh = || {
        next_id += 1;
        next_id - 1
    };
    // Level 0: one key per start edge, glued edges share theirs (the second side reversed).
    let mut glued: HashMap<(usize, usize), Key> = HashMap::new();
    for [a, b] in glue {
        let id = fresh();
        glued.insert(
            *a,
            Key {
                id,
                reversed: false,
            },
        );
        glued.insert(*b, Key { id, reversed: true });
    }
    let mut cells: Vec<(usize, Vec<Key>)> = types
        .start
        .iter()
        .enumerate()
        .map(|(f, &t)| {
            let n = types.types[t].face.boundary.len();
            let keys = (0..n)
                .map(|e| {
                    glued.get(&(f, e)).copied().unwrap_or(Key {
                        id: fresh(),
                        reversed: false,
                    })
                })
                .collect();
            (t, keys)
        })
        .collect();
    let mut out = Vec::new();
    for l in 0..=level {
        if cells.len() > max_cells {
            return None;
        }
        let mut d = Dsu::new(cells.len());
        let mut holder: HashMap<u64, (usize, u8)> = HashMap::new();
        for (c, (_, keys)) in cells.iter().enumerate() {
            for k in keys {
                let h = holder.entry(k.id).or_insert((c, 0));
                h.1 += 1;
                if h.1 > 2 {
                    return Some(Err(l));
                }
                let first = h.0;
                d.union(first, c);
            }
        }
        out.push(d.classes());
        if l == level {
            break;
        }
        // Children: pieces of keyed parent edges keep a derived key, spokes get one per parent.
        let mut pieces: HashMap<(u64, u32), u64> = HashMap::new();
        let mut next: Vec<(usize, Vec<Key>)> = Vec::new();
        for (t, keys) in &cells {
            let ty = &types.types[*t];
            let mut spokes: HashMap<usize, u64> = HashMap::new();
            for (k, sf) in ty.subdivision.subfaces.iter().enumerate() {
                let child_keys = sf
                    .origins
                    .iter()
                    .map(|o| match *o {
                        Origin::Piece { edge, piece } => {
                            let pk = keys[edge];
                            let np = ty.face.boundary[edge].piece_count();
                            let j = if pk.reversed {
                                np - 1 - piece as u32
                            } else {
                                piece as u32
                            };
                            let id = *pieces.entry((pk.id, j)).or_insert_with(&mut fresh);
                            Key {
                                id,
                                reversed: pk.reversed,
                            }
                        }
                        Origin::Spoke { spoke, inward } => Key {
                            id: *spokes.entry(spoke).or_insert_with(&mut fresh),
                            reversed: inward,
                        },
                        Origin::Lacuna { .. } | Origin::GapSide { .. } => Key {
                            id: fresh(),
                            reversed: false,
                        },
                    })
                    .collect();
                next.push((ty.children[k], child_keys));
            }
        }
        cells = next;
    }
    Some(Ok(out))
}
