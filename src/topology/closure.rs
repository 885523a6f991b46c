//! The closure: every face type the recursion produces, with the type graph (THEORY §4).
//!
//! Breadth-first from the start faces, identifying types by canonical face (the closure of
//! `topology/breadth_first.rs`, shared with volumes). "Did not close" is a result
//! ([`Closure::Runaway`], with the chain of growing types), not an error. For the built-in
//! algorithms the closure is finite, and [`Bound::stated`] gives the bound in advance; the
//! closure is checked against it.

use crate::error::{Error, Result};
pub use crate::topology::breadth_first::Runaway;
use crate::topology::breadth_first::{close_types, Closable, LimitMet, Outcome};
use crate::topology::class::ClassStructure;
use crate::topology::edge::EdgeType;
use crate::topology::face::Face;
use crate::topology::limits::Limits;
use crate::topology::rule::{Algorithm, SpokeItem};
use crate::topology::subdivision::{subdivide, Subdivision};
use num_bigint::BigUint;
use petgraph::graph::DiGraph;
use serde::Serialize;
use std::collections::{BTreeSet, HashMap};

/// One face type of a closure.
#[derive(Clone, Debug)]
pub struct FaceType {
    /// The canonical face.
    pub face: Face,
    /// Its subdivision step with the incidence map.
    pub subdivision: Subdivision,
    /// The type index of each sub-face, aligned with `subdivision.subfaces`.
    pub children: Vec<usize>,
    /// The type through which it was first reached (`None` for a start type).
    pub parent: Option<usize>,
}

impl FaceType {
    /// Lacunas contributed by one subdivision step, in halves (THEORY §5).
    pub fn contribution_halves(&self) -> u64 {
        self.face.contribution_halves()
    }
}

/// The bound on a closure stated in advance (built-in algorithms only).
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Bound {
    /// Every type's boundary has at most this many edges.
    #[serde(serialize_with = "ser_display")]
    pub max_length: BigUint,
    /// The longest boundary of the start faces and their delayed chains, exact: each of those
    /// faces is a type of the closure, so a closure with a smaller `--max-boundary` cannot be
    /// built (refused before the work).
    #[serde(serialize_with = "ser_display")]
    pub chain_length: BigUint,
    /// There are at most this many types.
    #[serde(serialize_with = "ser_display")]
    pub max_types: BigUint,
    /// How the bound was derived, for the report.
    pub reason: String,
}

/// A closed set of face types.
#[derive(Clone, Debug)]
pub struct TypeSet {
    /// The types; the start types come first, in the order given.
    pub types: Vec<FaceType>,
    /// The type index of each start face (one per face of an assembly).
    pub start: Vec<usize>,
    /// The bound stated in advance, when the algorithms allow one.
    pub bound: Option<Bound>,
}

impl TypeSet {
    /// The cells forced to zero area by the combinatorics alone: a Cantor edge `Cn` (delayed or
    /// not) has two control points, and every control point of its pieces is a barycentric
    /// combination of them, so its attractor lies on the segment between its ends. A cycle of
    /// two Cantor edges between the same two points therefore encloses no area, whatever the
    /// solution: a face type of two Cantor edges, and the lacuna of a face type with two spokes
    /// when `El` is a Cantor edge (its two sides join the inner ends of the two spokes). Each is a
    /// forced collapse (THEORY §6); a two-sided cell of Bézier edges is not forced flat (its
    /// edges may bulge apart) and is not listed. Returns the types of the flat faces and of the
    /// flat lacunas.
    pub fn flat_cells(&self) -> (Vec<usize>, Vec<usize>) {
        use crate::topology::EdgeKind;
        let (mut faces, mut lacunas) = (Vec::new(), Vec::new());
        for (t, ty) in self.types.iter().enumerate() {
            let f = &ty.face;
            if f.boundary.len() == 2 && f.boundary.iter().all(|e| e.kind == EdgeKind::C) {
                faces.push(t);
            }
            if f.delay == 1 && ty.subdivision.spokes.len() == 2 && f.params.el.kind == EdgeKind::C {
                lacunas.push(t);
            }
        }
        (faces, lacunas)
    }
}

/// The outcome of closing a set of faces.
#[derive(Clone, Debug)]
#[allow(clippy::large_enum_variant)]
pub enum Closure {
    /// The recursion closes: every sub-face type is in the set.
    Closed(TypeSet),
    /// The recursion grew past a limit.
    Runaway(Runaway),
}

impl Closure {
    /// Closes the given start faces under subdivision.
    pub fn of(start: &[Face], limits: &Limits) -> Result<Closure> {
        for f in start {
            limits.check_face(f)?;
        }
        let bound = Bound::stated(start);
        if let Some(b) = &bound {
            if b.chain_length > BigUint::from(limits.max_boundary) {
                return Err(b.above(limits, None));
            }
        }
        let proved = |met: LimitMet| {
            // A proved-finite closure that meets a limit is a limit error, never a runaway
            // (THEORY §4).
            let types_met = match met {
                LimitMet::Size(_) => None,
                LimitMet::Types(met) => Some(met),
            };
            bound.as_ref().map(|b| b.above(limits, types_met))
        };
        let start = start.iter().map(|f| f.canonical().0);
        Ok(match close_types(start, limits, proved)? {
            Outcome::Runaway(r) => Closure::Runaway(r),
            Outcome::Closed(types, start) => Closure::Closed(TypeSet {
                types: types
                    .into_iter()
                    .map(|n| FaceType {
                        face: n.item,
                        subdivision: n.step,
                        children: n.children,
                        parent: n.parent,
                    })
                    .collect(),
                start,
                bound,
            }),
        })
    }
}

impl Closable for Face {
    type Step = Subdivision;

    const NOUN: &'static str = "face";

    fn size(&self) -> usize {
        self.boundary.len()
    }

    fn size_reason(size: usize, limit: usize) -> String {
        format!("a sub-face boundary has {size} edges, above the limit {limit} (--max-boundary)")
    }

    fn step(&self, _: &Limits) -> Result<Subdivision> {
        subdivide(self)
    }

    fn children(step: &Subdivision) -> Vec<&Face> {
        step.subfaces.iter().map(|s| &*s.face).collect()
    }
}

impl Bound {
    /// The bound for the closure of `start`, when every face uses a built-in algorithm.
    ///
    /// Derivation (A1, A2 and A3 all put spokes at every joint and gap):
    /// * Only the start faces and their delayed descendants have delay ≥ 2 (sub-faces of a
    ///   non-delayed face have delay 1). That chain is computed exactly, but without building it:
    ///   a delayed step maps each edge to a fixed word (its pieces, `Ec Ec` at every gap), so the
    ///   boundary after k steps is the concatenation of the k-step words of its edges, and only
    ///   their lengths and delayed stretches are needed ([`Shape`]). The chain of a face of delay
    ///   d has d faces and its boundary lengths never decrease, so the last one is the longest.
    /// * A sub-face of a non-delayed face is a *run* of sub-edges between two spokes plus at most
    ///   five edges (`[Ec] Ea El Ea [Ec]`), and no `Ec Ec` is inserted inside a run because every gap
    ///   is a spoke. So its length is at most `r + 5`, where `r` bounds the run length:
    ///   - A2: every junction is a spoke, r = 1;
    ///   - A3: a delayed edge's single sub-edge is cut off by spokes at both its corners, so a run
    ///     is at most the last piece of one non-delayed edge and the first of the next: r = 2;
    ///   - AF1: as A3, except that a delayed edge next to a non-delayed `Bn` stays joined to it;
    ///     two delayed edges are always separated, so r = 3 (`Bn` piece, delayed edge, `Bn` piece);
    ///   - A1: a run goes from a joint/gap of a non-delayed edge through the single sub-edges of
    ///     the delayed edges that follow to the first joint/gap of the next non-delayed edge, so
    ///     r ≤ 2 + D with D the longest cyclic stretch of delayed edges of a non-delayed face. A
    ///     sub-face's delayed stretches are the parent's stretch (delays lowered by one) and the
    ///     stretch inside `Ec Ea El Ea Ec`, separated by the run's non-delayed end pieces, so
    ///     D ≤ max(D of the start faces and chain ends, D of `Ec Ea El Ea Ec`).
    /// * A sub-face type is fixed by its run (a word of length ≤ r over the edge types that can
    ///   occur: `X^k` for every `X^d` of the start faces and of E, k ≤ d) and whether it has a
    ///   leading and a trailing `Ec`: at most 4·Σ_{j≤r} |alphabet|^j types per (E, A).
    pub fn stated(start: &[Face]) -> Option<Bound> {
        if start.is_empty() || !start.iter().all(|f| f.algorithm.is_builtin()) {
            return None;
        }
        let mut chain_length = BigUint::from(0u32);
        let mut chain_types = 0usize;
        let mut alphabet: BTreeSet<EdgeType> = BTreeSet::new();
        let mut groups: BTreeSet<String> = BTreeSet::new();
        let mut max_run = 0usize;
        for f in start {
            groups.insert(format!(
                "{} {} {} {}",
                f.params.ea, f.params.el, f.params.ec, f.algorithm
            ));
            let p = f.params;
            for e in f.boundary.iter().chain([&p.ea, &p.el, &p.ec]) {
                for k in 1..=e.delay {
                    alphabet.insert(e.delayed(k));
                }
            }
            // The delayed chain, exactly, from the shapes of its edges' words.
            let mut shapes = ShapeTable::new(p.ec);
            let steps = f.delay.saturating_sub(1);
            let end = f
                .boundary
                .iter()
                .fold(Shape::empty(), |w, e| w.then(&shapes.after(*e, steps)));
            chain_types += f.delay as usize;
            // A delayed step never lengthens a delayed stretch beyond max(its old length, 2)
            // (a non-delayed edge's word starts and ends with a non-delayed piece; only its
            // `Ec Ec` can be delayed), so D ≤ max(|∂|, 2): the conversion never saturates.
            let stretch = usize::try_from(end.cyclic_stretch())
                .unwrap_or(usize::MAX)
                .min(f.boundary.len().max(2));
            if end.len > chain_length {
                chain_length = end.len.clone();
            }
            let r = match &f.algorithm {
                Algorithm::Spokes(items) if items.contains(&SpokeItem::Corner) => 1,
                Algorithm::Spokes(items) if items.contains(&SpokeItem::DelayedCorner) => 2,
                // AF1: a delayed edge is cut off at every corner except next to a non-delayed Bn,
                // and two delayed edges are always separated by a spoke, so a run is at most the
                // last piece of a Bn, one delayed edge and the first piece of the next Bn.
                Algorithm::Spokes(items) if items.contains(&SpokeItem::DelayedCornerNotB) => 3,
                _ => {
                    let pattern = [p.ec, p.ea, p.el, p.ea, p.ec];
                    let inside = pattern
                        .iter()
                        .fold(Shape::empty(), |w, e| w.then(&Shape::edge(*e)));
                    let inside = usize::try_from(inside.best).unwrap_or(pattern.len());
                    2 + stretch.max(inside)
                }
            };
            max_run = max_run.max(r);
        }
        let max_length = chain_length.clone().max(BigUint::from(max_run + 5));
        let a = BigUint::from(alphabet.len());
        let (mut words, mut power) = (BigUint::from(0u32), BigUint::from(1u32));
        for _ in 1..=max_run {
            power *= &a;
            words += &power;
        }
        let max_types = BigUint::from(chain_types) + words * 4u32 * BigUint::from(groups.len());
        Some(Bound {
            max_length,
            chain_length,
            max_types,
            reason: format!(
                "built-in algorithm: runs of at most {max_run} sub-edges, so sub-faces have at most {} edges; \
                 at most 4·Σ|alphabet|^j over {} edge types for runs, plus {chain_types} start/delayed types",
                max_run + 5,
                alphabet.len()
            ),
        })
    }

    /// The limit error for a closure this bound proves finite but that meets `limits` (THEORY §4:
    /// a limit is a resource bound, not a verdict). `types_met` is the number of types built
    /// when `--max-types` was hit, `None` for `--max-boundary`.
    fn above(&self, limits: &Limits, types_met: Option<usize>) -> Error {
        match types_met {
            None => Error::ProvedAboveLimit {
                proved: format!("boundary length ≤ {}", self.max_length),
                flag: "--max-boundary",
                limit: limits.max_boundary.to_string(),
                detail: if self.chain_length > BigUint::from(limits.max_boundary) {
                    format!(
                        "the delayed chain of a start face reaches {} edges; raise --max-boundary to at least that",
                        self.chain_length
                    )
                } else {
                    format!("raise --max-boundary to {} to build it", self.max_length)
                },
            },
            Some(met) => Error::ProvedAboveLimit {
                proved: format!("at most {} types", self.max_types),
                flag: "--max-types",
                limit: limits.max_types.to_string(),
                detail: format!("more than {met} types met; raise --max-types to build it"),
            },
        }
    }
}

/// What the closure needs to know of a boundary word: its length and its stretches of delayed
/// edges (a stretch is a maximal run of consecutive edges of delay ≥ 2). Exact big integers: a
/// delayed boundary can double at every step.
#[derive(Clone, Debug, PartialEq, Eq)]
struct Shape {
    /// Number of edges.
    len: BigUint,
    /// Delayed edges at the start (`len` when every edge is delayed).
    prefix: BigUint,
    /// Delayed edges at the end.
    suffix: BigUint,
    /// The longest stretch inside the word.
    best: BigUint,
}

impl Shape {
    fn empty() -> Shape {
        let z = BigUint::from(0u32);
        Shape {
            len: z.clone(),
            prefix: z.clone(),
            suffix: z.clone(),
            best: z,
        }
    }

    fn edge(e: EdgeType) -> Shape {
        let d = BigUint::from(u32::from(e.is_delayed()));
        Shape {
            len: BigUint::from(1u32),
            prefix: d.clone(),
            suffix: d.clone(),
            best: d,
        }
    }

    /// This word followed by `next`.
    fn then(&self, next: &Shape) -> Shape {
        let prefix = if self.prefix == self.len {
            &self.len + &next.prefix
        } else {
            self.prefix.clone()
        };
        let suffix = if next.suffix == next.len {
            &next.len + &self.suffix
        } else {
            next.suffix.clone()
        };
        let across = &self.suffix + &next.prefix;
        Shape {
            len: &self.len + &next.len,
            prefix,
            suffix,
            best: self.best.clone().max(next.best.clone()).max(across),
        }
    }

    /// The longest stretch when the word is read cyclically (a boundary).
    fn cyclic_stretch(&self) -> BigUint {
        if self.prefix == self.len {
            return self.len.clone();
        }
        self.best.clone().max(&self.suffix + &self.prefix)
    }
}

/// The shapes of the words edges become after k delayed steps, memoised by (edge, k): a delayed
/// step maps `X^d` (d ≥ 2) to `X^(d−1)`, and a non-delayed edge to its n pieces with `Ec Ec` at
/// every gap (THEORY §3).
struct ShapeTable {
    ec: EdgeType,
    memo: HashMap<(EdgeType, u32), Shape>,
}

impl ShapeTable {
    fn new(ec: EdgeType) -> ShapeTable {
        ShapeTable {
            ec,
            memo: HashMap::new(),
        }
    }

    fn after(&mut self, e: EdgeType, steps: u32) -> Shape {
        if steps == 0 {
            return Shape::edge(e);
        }
        if let Some(s) = self.memo.get(&(e, steps)) {
            return s.clone();
        }
        let shape = if e.is_delayed() {
            self.after(e.piece(), steps - 1)
        } else {
            let piece = self.after(e.piece(), steps - 1);
            let gap = if e.inner_junction() == Some(crate::topology::edge::JunctionKind::Gap) {
                let ec = self.after(self.ec, steps - 1);
                Some(ec.then(&ec))
            } else {
                None
            };
            let mut w = piece.clone();
            for _ in 1..e.n {
                if let Some(g) = &gap {
                    w = w.then(g);
                }
                w = w.then(&piece);
            }
            w
        };
        self.memo.insert((e, steps), shape.clone());
        shape
    }
}

impl TypeSet {
    /// Successor lists of the type graph (one entry per sub-face).
    pub fn successors(&self) -> Vec<Vec<usize>> {
        self.types.iter().map(|t| t.children.clone()).collect()
    }

    /// The type graph as a petgraph multigraph: a node per type (its notation), an arc per
    /// sub-face (weighted by the sub-face's index).
    pub fn graph(&self) -> DiGraph<String, usize> {
        let mut g = DiGraph::new();
        let nodes: Vec<_> = self
            .types
            .iter()
            .map(|t| g.add_node(t.face.to_string()))
            .collect();
        for (t, ty) in self.types.iter().enumerate() {
            for (k, &c) in ty.children.iter().enumerate() {
                g.add_edge(nodes[t], nodes[c], k);
            }
        }
        g
    }

    /// The strongly connected classes reached from the start faces, with their periods.
    pub fn classes(&self) -> ClassStructure {
        ClassStructure::new(&self.successors(), &self.start)
    }

    /// The substitution matrix, sparse: `matrix()[t]` lists (s, number of sub-faces of type s).
    pub fn matrix(&self) -> Vec<Vec<(usize, u64)>> {
        self.types
            .iter()
            .map(|t| {
                let mut m: std::collections::BTreeMap<usize, u64> = Default::default();
                for &c in &t.children {
                    *m.entry(c).or_default() += 1;
                }
                m.into_iter().collect()
            })
            .collect()
    }

    /// Checks the closure: every step's structural identities, every sub-face listed with the
    /// right type, and the stated bound (when there is one).
    pub fn verify(&self) -> std::result::Result<(), String> {
        for (t, ty) in self.types.iter().enumerate() {
            ty.subdivision
                .verify(&ty.face)
                .map_err(|e| format!("type T{t}: {e}"))?;
            if ty.children.len() != ty.subdivision.subfaces.len() {
                return Err(format!(
                    "type T{t}: children and sub-faces differ in number"
                ));
            }
            for (s, &c) in ty.subdivision.subfaces.iter().zip(&ty.children) {
                match self.types.get(c) {
                    Some(ct) if ct.face == *s.face => {}
                    _ => return Err(format!("type T{t}: sub-face `{}` is not type T{c}", s.face)),
                }
            }
        }
        if let Some(b) = &self.bound {
            let longest = self
                .types
                .iter()
                .map(|t| t.face.boundary.len())
                .max()
                .unwrap_or(0);
            if BigUint::from(longest) > b.max_length {
                return Err(format!(
                    "a boundary of {longest} edges breaks the stated bound {}",
                    b.max_length
                ));
            }
            if BigUint::from(self.types.len()) > b.max_types {
                return Err(format!(
                    "{} types break the stated bound {}",
                    self.types.len(),
                    b.max_types
                ));
            }
        }
        Ok(())
    }

    /// Asserts [`TypeSet::verify`] (tests and fuzzing).
    #[cfg(any(test, fuzzing))]
    pub fn sanity_check(&self) {
        if let Err(e) = self.verify() {
            panic!("closure broke an identity: {e}");
        }
    }
}

/// Closes a single face; convenience for the common case.
pub fn close(face: &Face, limits: &Limits) -> Result<Closure> {
    Closure::of(std::slice::from_ref(face), limits)
}

/// The closed type set, or a limit error naming the runaway (for callers that need a closed set).
pub fn close_or_error(start: &[Face], limits: &Limits) -> Result<TypeSet> {
    match Closure::of(start, limits)? {
        Closure::Closed(ts) => Ok(ts),
        Closure::Runaway(r) => Err(Error::Runaway {
            reason: r.reason,
            chain: r.witness.len(),
        }),
    }
}

/// Serialises any `Display` value as a JSON string (exact numbers stay exact).
pub fn ser_display<T: std::fmt::Display, S: serde::Serializer>(
    v: &T,
    s: S,
) -> Result<S::Ok, S::Error> {
    s.collect_str(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn closed(s: &str) -> TypeSet {
        match close(&Face::parse(s).unwrap(), &Limits::default()).unwrap() {
            Closure::Closed(ts) => {
                ts.sanity_check();
                ts
            }
            Closure::Runaway(r) => panic!("runaway: {r:?}"),
        }
    }

    #[test]
    fn f0_closes_on_itself() {
        let ts = closed("C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A1");
        assert_eq!(ts.types.len(), 1);
        assert_eq!(ts.types[0].children, vec![0; 6]);
        assert_eq!(ts.matrix(), vec![vec![(0, 6)]]);
        let cl = ts.classes();
        assert_eq!(cl.classes.len(), 1);
        assert_eq!(cl.classes[0].period, Some(1));
        assert_eq!(ts.graph().edge_count(), 6);
    }

    #[test]
    fn square_of_b2_closes_with_a_hand_checked_type() {
        // `B2 B2 B2 B2 | B2 B2 B2 | A1`: 4 joints are the spokes; each run is the second half of
        // one B2 and the first half of the next, closed by Ea El Ea: 5 × B2. The pentagon of B2
        // subdivides into 5 runs of the same shape, so the closure is {square, pentagon} with
        // square → 4 pentagons, pentagon → 5 pentagons.
        let ts = closed("B2 B2 B2 B2 | B2 B2 B2 | A1");
        assert_eq!(ts.types.len(), 2);
        assert_eq!(ts.types[1].face.boundary.len(), 5);
        assert_eq!(ts.matrix(), vec![vec![(1, 4)], vec![(1, 5)]]);
        let cl = ts.classes();
        assert_eq!(cl.classes.len(), 2);
        assert_eq!(cl.classes[0].period, None);
    }

    #[test]
    fn runaway_is_a_result_with_a_witness() {
        // Spokes only at joints: every gap stays inside a run and adds `Ec Ec`, so C3 boundaries
        // grow without end.
        let f = Face::parse("B2 C3 | B2 B2 C3 | {joint}").unwrap();
        let limits = Limits {
            max_boundary: 40,
            ..Limits::default()
        };
        match close(&f, &limits).unwrap() {
            Closure::Runaway(r) => {
                assert!(r.witness.len() >= 2);
                assert!(r.reason.contains("--max-boundary"));
                let lens: Vec<usize> = r
                    .witness
                    .iter()
                    .map(|w| w.split('|').next().unwrap().split_whitespace().count())
                    .collect();
                assert!(
                    lens.windows(2).all(|w| w[0] < w[1]),
                    "chain grows: {lens:?}"
                );
            }
            Closure::Closed(ts) => panic!("expected runaway, got {} types", ts.types.len()),
        }
    }

    #[test]
    fn delayed_chain_stays_within_the_stated_bound() {
        let ts = closed("B3 C2 B2^3 C3 B2 | C2 B2 C2 | A3");
        let b = ts.bound.clone().unwrap();
        assert!(ts
            .types
            .iter()
            .all(|t| BigUint::from(t.face.boundary.len()) <= b.max_length));
        let ts = closed("B2 C2^3 | C2 B2 B2 | A1 | 3");
        assert_eq!(ts.types[0].face.delay, 3);
        assert_eq!(ts.types[1].face.delay, 2);
    }

    /// The shapes agree with the delayed chain built step by step (the old way), on faces with
    /// delayed edges, delayed E and every kind of edge.
    #[test]
    fn chain_shapes_match_the_built_chain() {
        for s in [
            "B2 C2 | B2 B2 B2 | A1 | 6",
            "B3 C2^3 B2^2 C3 | C2 B2 C2^2 | A1 | 5",
            "C2^4 C2^4 B2 | B2^2 C3 C2^3 | A3 | 4",
            "B2^5 B2^5 | C2 B2 B2 | A1 | 3",
            "C3 B2^2 B2^2 B2^2 C2 | B2 B2 C2^2 | A1 | 4",
        ] {
            let f = Face::parse(s).unwrap();
            let p = f.params;
            let mut cur = f.boundary.clone();
            for _ in 1..f.delay {
                let mut next = Vec::new();
                for e in &cur {
                    for k in 0..e.piece_count() {
                        next.push(e.piece());
                        if k + 1 < e.piece_count()
                            && e.inner_junction() == Some(crate::topology::edge::JunctionKind::Gap)
                        {
                            next.extend([p.ec, p.ec]);
                        }
                    }
                }
                cur = next;
            }
            let mut table = ShapeTable::new(p.ec);
            let shape = f
                .boundary
                .iter()
                .fold(Shape::empty(), |w, e| w.then(&table.after(*e, f.delay - 1)));
            assert_eq!(shape.len, BigUint::from(cur.len()), "{s}");
            // The longest cyclic stretch of delayed edges, by a direct scan of two turns.
            let n = cur.len();
            let (mut best, mut run) = (0usize, 0usize);
            for i in 0..2 * n {
                run = if cur[i % n].is_delayed() { run + 1 } else { 0 };
                best = best.max(run.min(n));
            }
            assert_eq!(shape.cyclic_stretch(), BigUint::from(best), "{s}");
            let b = Bound::stated(std::slice::from_ref(&f)).unwrap();
            assert_eq!(b.chain_length, BigUint::from(n), "{s}");
        }
    }
}
