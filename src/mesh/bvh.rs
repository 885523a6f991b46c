//! A bounding-volume hierarchy over the triangles of a mesh: axis-aligned boxes, split at the
//! median centroid along the longest axis, at most [`LEAF`] triangles a leaf.
//!
//! Two queries use it: the pairs of triangles whose boxes overlap (the candidates of the
//! self-intersection test, [`crate::mesh::volume::self_intersection`]) and the pairs closer than a
//! distance (the wall-thickness bound, [`crate::mesh::wall`]). It is written here rather than
//! taken from `bvh` or `parry3d`: both queries are a few dozen lines over one flat array of nodes,
//! the boxes must be closed (touching boxes overlap, as in the sweep this replaces, so that the
//! pairs tested are exactly the same) and in `f64` on the `f32` coordinates written, and a crate
//! would add a vector library (`nalgebra`/`glam`) and its build time for no more than that.
//!
//! Boxes are computed with `min`/`max` of the coordinates themselves (no arithmetic), so a box
//! contains its triangle exactly and the overlap tests are exact.

/// Triangles a leaf holds at most.
pub const LEAF: usize = 4;

/// An axis-aligned box, closed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// Least corner.
    pub lo: [f64; 3],
    /// Greatest corner.
    pub hi: [f64; 3],
}

impl Aabb {
    /// The empty box (contains nothing; the union with any box is that box).
    pub const EMPTY: Aabb = Aabb {
        lo: [f64::INFINITY; 3],
        hi: [f64::NEG_INFINITY; 3],
    };

    /// The box of a triangle.
    pub fn of(t: &[[f64; 3]; 3]) -> Aabb {
        let mut b = Aabb::EMPTY;
        for p in t {
            b.add(*p);
        }
        b
    }

    /// Grows the box to contain `p`.
    pub fn add(&mut self, p: [f64; 3]) {
        for (k, x) in p.into_iter().enumerate() {
            self.lo[k] = self.lo[k].min(x);
            self.hi[k] = self.hi[k].max(x);
        }
    }

    /// The smallest box containing both.
    pub fn union(&self, o: &Aabb) -> Aabb {
        let mut b = *self;
        for k in 0..3 {
            b.lo[k] = b.lo[k].min(o.lo[k]);
            b.hi[k] = b.hi[k].max(o.hi[k]);
        }
        b
    }

    /// Whether the closed boxes meet (touching counts).
    pub fn overlaps(&self, o: &Aabb) -> bool {
        (0..3).all(|k| self.lo[k] <= o.hi[k] && o.lo[k] <= self.hi[k])
    }

    /// A lower bound on the distance between a point of `self` and a point of `o` (0 when they
    /// overlap). Each gap is a difference of two coordinates, rounded once; the sum of squares
    /// and the root add a few ulps, so it can exceed the true distance by a relative 1e-15 at
    /// most, which the callers' margin covers.
    pub fn distance(&self, o: &Aabb) -> f64 {
        let mut s = 0.0;
        for k in 0..3 {
            let gap = (o.lo[k] - self.hi[k]).max(self.lo[k] - o.hi[k]).max(0.0);
            s += gap * gap;
        }
        s.sqrt()
    }
}

#[derive(Clone, Debug)]
struct Node {
    bounds: Aabb,
    /// Leaf: `first..first + count` in `order`; inner node: `count == 0`, children `first` and
    /// `first + 1`.
    first: u32,
    count: u32,
}

/// The hierarchy: nodes in one array (the root first), leaves holding ranges of a permutation
/// of the triangles.
#[derive(Clone, Debug)]
pub struct Bvh {
    nodes: Vec<Node>,
    order: Vec<u32>,
    boxes: Vec<Aabb>,
}

impl Bvh {
    /// Builds the hierarchy over the boxes of the items (item `i` is `boxes[i]`).
    pub fn new(boxes: Vec<Aabb>) -> Bvh {
        let mut order: Vec<u32> = (0..boxes.len() as u32).collect();
        let mut nodes = vec![Node {
            bounds: Aabb::EMPTY,
            first: 0,
            count: 0,
        }];
        // (node, range) still to split.
        let mut todo = vec![(0usize, 0usize, order.len())];
        while let Some((n, start, end)) = todo.pop() {
            let items = &mut order[start..end];
            let mut bounds = Aabb::EMPTY;
            let mut centres = Aabb::EMPTY;
            for &i in items.iter() {
                let b = &boxes[i as usize];
                bounds = bounds.union(b);
                centres.add([0, 1, 2].map(|k| 0.5 * (b.lo[k] + b.hi[k])));
            }
            nodes[n].bounds = bounds;
            if items.len() <= LEAF {
                nodes[n].first = start as u32;
                nodes[n].count = items.len() as u32;
                continue;
            }
            let axis = (0..3)
                .max_by(|&a, &b| {
                    (centres.hi[a] - centres.lo[a]).total_cmp(&(centres.hi[b] - centres.lo[b]))
                })
                .unwrap_or(0);
            let mid = items.len() / 2;
            let key = |i: &u32| boxes[*i as usize].lo[axis] + boxes[*i as usize].hi[axis];
            items.select_nth_unstable_by(mid, |a, b| key(a).total_cmp(&key(b)));
            let left = nodes.len();
            nodes[n].first = left as u32;
            nodes[n].count = 0;
            for _ in 0..2 {
                nodes.push(Node {
                    bounds: Aabb::EMPTY,
                    first: 0,
                    count: 0,
                });
            }
            todo.push((left, start, start + mid));
            todo.push((left + 1, start + mid, end));
        }
        Bvh {
            nodes,
            order,
            boxes,
        }
    }

    /// The box of item `i`.
    pub fn item_box(&self, i: usize) -> &Aabb {
        &self.boxes[i]
    }

    fn leaf(&self, n: usize) -> Option<&[u32]> {
        let node = &self.nodes[n];
        (node.count > 0 || self.order.is_empty())
            .then(|| &self.order[node.first as usize..(node.first + node.count) as usize])
    }

    /// Calls `f(i, j)` once for every unordered pair of distinct items whose (closed) boxes
    /// overlap, `i < j`.
    pub fn overlapping_pairs(&self, mut f: impl FnMut(usize, usize)) {
        if self.order.is_empty() {
            return;
        }
        let mut stack = vec![(0usize, 0usize)];
        let emit = |a: u32, b: u32, f: &mut dyn FnMut(usize, usize)| {
            if self.boxes[a as usize].overlaps(&self.boxes[b as usize]) {
                f(a.min(b) as usize, a.max(b) as usize);
            }
        };
        while let Some((a, b)) = stack.pop() {
            if a != b && !self.nodes[a].bounds.overlaps(&self.nodes[b].bounds) {
                continue;
            }
            match (self.leaf(a), self.leaf(b)) {
                (Some(la), Some(lb)) if a == b => {
                    for (k, &i) in la.iter().enumerate() {
                        for &j in &lb[k + 1..] {
                            emit(i, j, &mut f);
                        }
                    }
                }
                (Some(la), Some(lb)) => {
                    for &i in la {
                        for &j in lb {
                            emit(i, j, &mut f);
                        }
                    }
                }
                _ if a == b => {
                    let c = self.nodes[a].first as usize;
                    stack.extend([(c, c), (c + 1, c + 1), (c, c + 1)]);
                }
                (None, _) => {
                    let c = self.nodes[a].first as usize;
                    stack.extend([(c, b), (c + 1, b)]);
                }
                (Some(_), None) => {
                    let c = self.nodes[b].first as usize;
                    stack.extend([(a, c), (a, c + 1)]);
                }
            }
        }
    }

    /// Calls `visit(j)` for every item whose box is at distance below `limit()` from `query`
    /// ([`Aabb::distance`]); `limit` is read again before each node, so a caller that lowers it
    /// while visiting prunes more.
    pub fn near(&self, query: &Aabb, limit: impl Fn() -> f64, mut visit: impl FnMut(usize)) {
        if self.order.is_empty() {
            return;
        }
        let mut stack = vec![0usize];
        while let Some(n) = stack.pop() {
            if self.nodes[n].bounds.distance(query) >= limit() {
                continue;
            }
            match self.leaf(n) {
                Some(items) => {
                    for &j in items {
                        if self.boxes[j as usize].distance(query) < limit() {
                            visit(j as usize);
                        }
                    }
                }
                None => {
                    let c = self.nodes[n].first as usize;
                    // The nearer child first, so that the limit drops sooner.
                    let (d0, d1) = (
                        self.nodes[c].bounds.distance(query),
                        self.nodes[c + 1].bounds.distance(query),
                    );
                    if d0 <= d1 {
                        stack.extend([c + 1, c]);
                    } else {
                        stack.extend([c, c + 1]);
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn boxes(n: usize) -> Vec<Aabb> {
        // A deterministic scatter of small boxes (a linear congruential sequence).
        let mut s = 12345u64;
        let mut next = || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        (0..n)
            .map(|_| {
                let lo = [next() * 10.0, next() * 10.0, next() * 10.0];
                let hi = [0, 1, 2].map(|k| lo[k] + next());
                Aabb { lo, hi }
            })
            .collect()
    }

    #[test]
    fn overlapping_pairs_are_exactly_the_brute_force_ones() {
        for n in [0, 1, 2, 5, 37, 400] {
            let b = boxes(n);
            let mut want = Vec::new();
            for i in 0..n {
                for j in i + 1..n {
                    if b[i].overlaps(&b[j]) {
                        want.push((i, j));
                    }
                }
            }
            let mut got = Vec::new();
            Bvh::new(b).overlapping_pairs(|i, j| got.push((i, j)));
            got.sort_unstable();
            assert_eq!(got, want, "{n} boxes");
        }
    }

    #[test]
    fn touching_boxes_overlap() {
        let a = Aabb {
            lo: [0.0; 3],
            hi: [1.0; 3],
        };
        let b = Aabb {
            lo: [1.0, 0.0, 0.0],
            hi: [2.0, 1.0, 1.0],
        };
        assert!(a.overlaps(&b));
        assert_eq!(a.distance(&b), 0.0);
        let c = Aabb {
            lo: [4.0, 5.0, 1.0],
            hi: [5.0, 6.0, 1.0],
        };
        // Gaps 3, 4 and 0: distance 5.
        assert_eq!(a.distance(&c), 5.0);
    }

    #[test]
    fn near_finds_every_box_within_the_limit() {
        let b = boxes(300);
        let q = b[7];
        let want: Vec<usize> = (0..b.len()).filter(|&j| b[j].distance(&q) < 0.8).collect();
        let mut got = Vec::new();
        Bvh::new(b).near(&q, || 0.8, |j| got.push(j));
        got.sort_unstable();
        assert_eq!(got, want);
    }
}
