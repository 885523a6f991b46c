//! Vertex types and the exact multiplicity of the level-k complex (THEORY §9, §13).
//!
//! A vertex's **link** is the cyclic sequence, counter-clockwise, of what surrounds it: the corners
//! of faces (a sector: face type and corner index) and holes (a lacuna, a gap or the outside). Its
//! **valence** — the number of edges meeting there, the multiplicity of the paper — is the length
//! of the link, one edge between two consecutive items. Links are read off the incidence maps:
//! turning counter-clockwise from a corner crosses the corner's incoming side into the face on the
//! other side of it (the shared edge runs the other way) or into a hole.
//!
//! One step changes a link without looking at geometry: each sector becomes the sectors of the
//! sub-faces at that corner of its face (two when the corner is a spoke, with the new edge between
//! them), holes stay holes. So vertex types close like face types, and every vertex of the level-k
//! complex is either a vertex of the level before or born inside a face (lacuna corners, gap
//! points) or inside an edge (joints, gap ends, whose link joins the fans of the faces on both
//! sides). Counts of vertex types, of edge cells (the pair of sides of an edge) and of face types
//! per level are linear recurrences in big integers: the exact valence distribution at any level,
//! V, E and F of the complex, and — where the vertex types close — the largest valence in the limit.
//!
//! The parts: `link.rs` holds the links and what one step of a face type does to them (the
//! sectors at its corners, the vertices and edges born inside it and inside its edges);
//! `limit.rs` decides the valences of the limit (bounded with their values, or unbounded with a
//! growing sector as witness); this file counts the complex level by level and, when the
//! valences are bounded, builds the linear system that steps every count.

mod limit;
mod link;

pub use limit::{GrowthWitness, LimitValence, SectorName};
pub use link::Item;

use crate::error::{Error, Result};
use crate::topology::closure::TypeSet;
use crate::topology::component::Glue;
use limit::limit_valence;
use link::{
    across, canonical, edge_births, edge_cell, evolve, fans, local, pieces_of, EdgeCell, Local,
    Other,
};
use num_bigint::BigUint;
use num_traits::Zero;
use serde::Serialize;
use std::collections::{BTreeMap, HashMap, HashSet};

/// The link items allowed per vertex type of `max_types`, summed over the vertex types of a level.
pub const LINK_ITEMS_PER_TYPE: usize = 64;

/// The valence distribution and the cells of the complex at one level.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct LevelComplex {
    /// The level.
    pub level: u64,
    /// Vertices.
    #[serde(serialize_with = "crate::topology::closure::ser_display")]
    pub vertices: BigUint,
    /// Edges.
    #[serde(serialize_with = "crate::topology::closure::ser_display")]
    pub edges: BigUint,
    /// Faces.
    #[serde(serialize_with = "crate::topology::closure::ser_display")]
    pub faces: BigUint,
    /// Number of vertices of each valence (as decimal strings).
    pub valences: BTreeMap<usize, String>,
    /// The largest valence.
    pub max_valence: usize,
    /// Gaps opened so far in edges with a face on one side only (each is half a lacuna that is
    /// not a hole of its own): N^L = holes + half_gaps / 2.
    #[serde(serialize_with = "crate::topology::closure::ser_display")]
    pub half_gaps: BigUint,
}

/// The exact complex per level and the valences of the limit.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Multiplicity {
    /// Per level from 0.
    pub levels: Vec<LevelComplex>,
    /// The number of vertex types met up to the last level.
    pub vertex_types: usize,
    /// The valences of the limit: bounded with the values, or unbounded with a witness.
    pub limit: LimitValence,
    /// When the valences are bounded: a bound on the order of the linear recurrences that every
    /// count of the complex (vertices of each valence, edges, faces, lacunas) satisfies — the
    /// closed vertex types, the edge cells, the face types and one for the lacunas. Two such
    /// sequences that agree on their first `order_a + order_b` levels agree at every level.
    pub order: Option<usize>,
    /// When the valences are bounded: the linear system that steps every count of the complex
    /// (closed vertex types, edge cells, face types), for the limit shares of the valences.
    #[serde(skip)]
    pub system: Option<VertexSystem>,
}

/// The counts of the complex as a substitution over finitely many states, when the vertex types
/// close: vertex types (one step turns a vertex into the vertex of its stepped link), edge cells
/// (into their pieces and the vertices born inside them) and face types (into sub-faces and the
/// edges and vertices born inside). The number of states of each kind at level k is the start
/// vector stepped k times, so the number of vertices of valence v is a linear functional of it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct VertexSystem {
    /// For each state, `(s, k)`: one of it becomes `k` of state `s` in one step.
    pub step: Vec<Vec<(usize, u64)>>,
    /// The states of level 0 with their numbers.
    pub start: Vec<(usize, u64)>,
    /// For each state: its valence when it is a vertex type, `None` for edge cells and faces.
    pub valence: Vec<Option<usize>>,
}

impl VertexSystem {
    /// The number of vertices of each valence after `k` steps from the start (a check of the
    /// system against the level-by-level complex).
    pub fn valences_at(&self, k: u64) -> BTreeMap<usize, BigUint> {
        let mut x = vec![BigUint::zero(); self.step.len()];
        for &(s, n) in &self.start {
            x[s] += n;
        }
        for _ in 0..k {
            let mut y = vec![BigUint::zero(); x.len()];
            for (s, n) in x.iter().enumerate() {
                if n.is_zero() {
                    continue;
                }
                for &(t, m) in &self.step[s] {
                    y[t] += n * m;
                }
            }
            x = y;
        }
        let mut out = BTreeMap::new();
        for (s, n) in x.iter().enumerate() {
            if let (Some(v), false) = (self.valence[s], n.is_zero()) {
                *out.entry(v).or_insert_with(BigUint::zero) += n;
            }
        }
        out
    }
}

/// The substitution of [`VertexSystem`] over the closed vertex types `closed` (canonical links),
/// the edge cells `cells` and the face types of `ts`.
fn vertex_system(
    ts: &TypeSet,
    locals: &[Local],
    closed: &[Vec<Item>],
    cells: &[EdgeCell],
    start: (&[Vec<Item>], &[EdgeCell]),
) -> VertexSystem {
    let vindex: HashMap<&Vec<Item>, usize> =
        closed.iter().enumerate().map(|(i, l)| (l, i)).collect();
    let v = |link: Vec<Item>| vindex[&canonical(link)];
    let cindex: HashMap<EdgeCell, usize> = cells
        .iter()
        .enumerate()
        .map(|(i, &c)| (c, closed.len() + i))
        .collect();
    let f0 = closed.len() + cells.len();
    let tally = |items: Vec<usize>| -> Vec<(usize, u64)> {
        let mut m: BTreeMap<usize, u64> = BTreeMap::new();
        for i in items {
            *m.entry(i).or_default() += 1;
        }
        m.into_iter().collect()
    };
    let mut step = Vec::with_capacity(f0 + ts.types.len());
    for link in closed {
        step.push(vec![(v(evolve(locals, link)), 1)]);
    }
    for &((t, i), other) in cells {
        let (n, gap) = pieces_of(ts, t, i);
        let mut items: Vec<usize> = (0..n)
            .map(|m| cindex[&edge_cell(locals[t].pieces[i][m], across(locals, other, n, m))])
            .collect();
        items.extend(
            edge_births(locals, (t, i), other, n, gap)
                .into_iter()
                .map(&v),
        );
        step.push(tally(items));
    }
    let matrix = ts.matrix();
    for (t, l) in locals.iter().enumerate() {
        let mut items: Vec<usize> = l.births.iter().map(|b| v(b.clone())).collect();
        items.extend(l.edges.iter().map(|e| cindex[e]));
        let mut row = tally(items);
        row.extend(matrix[t].iter().map(|&(s, m)| (f0 + s, m)));
        step.push(row);
    }
    let mut items: Vec<usize> = start.0.iter().map(|l| v(l.clone())).collect();
    items.extend(start.1.iter().map(|c| cindex[c]));
    items.extend(ts.start.iter().map(|&t| f0 + t));
    let valence = closed
        .iter()
        .map(|l| Some(l.len()))
        .chain(std::iter::repeat_n(None, cells.len() + ts.types.len()))
        .collect();
    VertexSystem {
        step,
        start: tally(items),
        valence,
    }
}

/// The exact complex of the start faces of `ts` (glued by `glue`) from level 0 to `levels`.
///
/// `max_types` bounds the number of vertex types met level by level (a limit error beyond it,
/// `--max-types`): under a rule with unbounded valence they never stop growing.
pub fn multiplicity(
    ts: &TypeSet,
    glue: &[Glue],
    levels: u64,
    max_types: usize,
) -> Result<Multiplicity> {
    let locals: Vec<Local> = (0..ts.types.len()).map(|t| local(ts, t)).collect();
    let mut vtypes: Vec<Vec<Item>> = Vec::new();
    let mut vindex: HashMap<Vec<Item>, usize> = HashMap::new();
    let mut intern = |link: Vec<Item>, vtypes: &mut Vec<Vec<Item>>| -> usize {
        let link = canonical(link);
        if let Some(&i) = vindex.get(&link) {
            return i;
        }
        vtypes.push(link.clone());
        vindex.insert(link, vtypes.len() - 1);
        vtypes.len() - 1
    };
    // Level 0: the start faces as polygons glued along the assembly's shared edges.
    let lens: Vec<usize> = ts
        .start
        .iter()
        .map(|&t| ts.types[t].face.boundary.len())
        .collect();
    let mut partner = HashMap::new();
    for g in glue {
        partner.insert(g[0], g[1]);
        partner.insert(g[1], g[0]);
    }
    let mut vcount: HashMap<usize, BigUint> = HashMap::new();
    let mut start_links = Vec::new();
    for (fan, cyclic) in fans(&lens, &partner) {
        let mut link: Vec<Item> = fan
            .iter()
            .map(|&(f, c)| Item::Sector {
                ty: ts.start[f],
                corner: c,
            })
            .collect();
        if !cyclic {
            link.push(Item::Hole);
        }
        start_links.push(link.clone());
        let v = intern(link, &mut vtypes);
        *vcount.entry(v).or_default() += 1u32;
    }
    let mut ecount: HashMap<EdgeCell, BigUint> = HashMap::new();
    let mut start_cells = Vec::new();
    for (f, &t) in ts.start.iter().enumerate() {
        for i in 0..lens[f] {
            let other = match partner.get(&(f, i)) {
                Some(&(g, j)) => {
                    if (g, j) < (f, i) {
                        continue;
                    }
                    Other::Face(ts.start[g], j)
                }
                None => Other::Outside,
            };
            start_cells.push(edge_cell((t, i), other));
            *ecount.entry(edge_cell((t, i), other)).or_default() += 1u32;
        }
    }
    let mut fcount = vec![BigUint::zero(); ts.types.len()];
    for &t in &ts.start {
        fcount[t] += 1u32;
    }
    let matrix = ts.matrix();
    let mut half_gaps = BigUint::zero();
    let mut out = Vec::new();
    for level in 0..=levels {
        let mut valences: BTreeMap<usize, BigUint> = BTreeMap::new();
        for (&v, k) in &vcount {
            *valences.entry(vtypes[v].len()).or_default() += k;
        }
        out.push(LevelComplex {
            level,
            vertices: vcount.values().sum(),
            edges: ecount.values().sum(),
            faces: fcount.iter().sum(),
            max_valence: valences.keys().next_back().copied().unwrap_or(0),
            valences: valences
                .into_iter()
                .map(|(v, k)| (v, k.to_string()))
                .collect(),
            half_gaps: half_gaps.clone(),
        });
        if vtypes.len() > max_types {
            return Err(Error::limit(
                "the number of vertex types",
                vtypes.len(),
                max_types,
                "--max-types",
            ));
        }
        // Under an unbounded valence links grow with the level (doubling under A2): their total
        // length is bounded too, before the next step is built.
        let total: usize = vcount.keys().map(|&v| vtypes[v].len()).sum();
        let budget = max_types.saturating_mul(LINK_ITEMS_PER_TYPE);
        if level < levels && total > budget {
            return Err(Error::limit(
                "the total length of the vertex links of a level",
                total,
                budget,
                "--max-types (64 link items per type)",
            ));
        }
        if level == levels {
            break;
        }
        let mut nv: HashMap<usize, BigUint> = HashMap::new();
        let mut ne: HashMap<EdgeCell, BigUint> = HashMap::new();
        let mut nf = vec![BigUint::zero(); ts.types.len()];
        for (&v, k) in &vcount {
            let link = evolve(&locals, &vtypes[v]);
            let w = intern(link, &mut vtypes);
            *nv.entry(w).or_default() += k;
        }
        for (t, k) in fcount.iter().enumerate() {
            if k.is_zero() {
                continue;
            }
            for b in &locals[t].births {
                let w = intern(b.clone(), &mut vtypes);
                *nv.entry(w).or_default() += k;
            }
            for e in &locals[t].edges {
                *ne.entry(*e).or_default() += k;
            }
            for &(s, m) in &matrix[t] {
                nf[s] += k * m;
            }
        }
        for (&((t, i), other), k) in &ecount {
            let (n, gap) = pieces_of(ts, t, i);
            if gap && !matches!(other, Other::Face(..)) {
                half_gaps += k * (n as u64 - 1);
            }
            for m in 0..n {
                let c = edge_cell(locals[t].pieces[i][m], across(&locals, other, n, m));
                *ne.entry(c).or_default() += k;
            }
            for w in edge_births(&locals, (t, i), other, n, gap) {
                let w = intern(w, &mut vtypes);
                *nv.entry(w).or_default() += k;
            }
        }
        vcount = nv;
        ecount = ne;
        fcount = nf;
    }
    // The limit: every vertex type that is ever born — the start vertices, the births of every
    // face type and of every edge cell reached — and the sector substitution that steps them.
    let mut born: Vec<Vec<Item>> = start_links.clone();
    let mut cells: Vec<EdgeCell> = Vec::new();
    let mut seen_cells: HashSet<EdgeCell> = HashSet::new();
    for c in start_cells
        .iter()
        .copied()
        .chain(locals.iter().flat_map(|l| l.edges.iter().copied()))
    {
        if seen_cells.insert(c) {
            cells.push(c);
        }
    }
    let mut i = 0;
    while i < cells.len() {
        let ((t, s), other) = cells[i];
        let (n, gap) = pieces_of(ts, t, s);
        for m in 0..n {
            let c = edge_cell(locals[t].pieces[s][m], across(&locals, other, n, m));
            if seen_cells.insert(c) {
                cells.push(c);
            }
        }
        born.extend(edge_births(&locals, (t, s), other, n, gap));
        i += 1;
    }
    for l in &locals {
        born.extend(l.births.iter().cloned());
    }
    let limit = limit_valence(ts, &locals, &born)?;
    // With bounded valences the vertex types close (finitely many links of bounded length over
    // finitely many sectors): the state of a level — vertex types, edge cells, face types and the
    // lacunas so far — then steps linearly, so every count of the complex is a linear recurrence
    // of order at most its dimension.
    let (order, system) = match limit {
        LimitValence::Unbounded { .. } => (None, None),
        LimitValence::Bounded { .. } => {
            let mut closed: Vec<Vec<Item>> = Vec::new();
            let mut seen: HashSet<Vec<Item>> = HashSet::new();
            for l in born.iter().chain(vtypes.iter()) {
                let l = canonical(l.clone());
                if seen.insert(l.clone()) {
                    closed.push(l);
                }
            }
            let mut i = 0;
            while i < closed.len() {
                if closed.len() > max_types {
                    return Err(Error::limit(
                        "the number of vertex types",
                        closed.len(),
                        max_types,
                        "--max-types",
                    ));
                }
                let l = canonical(evolve(&locals, &closed[i]));
                if seen.insert(l.clone()) {
                    closed.push(l);
                }
                i += 1;
            }
            let system = vertex_system(ts, &locals, &closed, &cells, (&start_links, &start_cells));
            (
                Some(closed.len() + cells.len() + ts.types.len() + 1),
                Some(system),
            )
        }
    };
    Ok(Multiplicity {
        levels: out,
        vertex_types: vtypes.len(),
        limit,
        order,
        system,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::topology::closure::close_or_error;
    use crate::topology::count::counts;
    use crate::topology::face::Face;
    use crate::topology::limits::Limits;
    use num_bigint::BigInt;
    use num_rational::BigRational;

    fn of(text: &str, levels: u64) -> (TypeSet, Multiplicity) {
        let f = Face::parse(text).unwrap();
        let ts = close_or_error(&[f], &Limits::default()).unwrap();
        let m = multiplicity(&ts, &[], levels, 400).unwrap();
        (ts, m)
    }

    fn valences(l: &LevelComplex) -> Vec<(usize, String)> {
        l.valences.iter().map(|(v, k)| (*v, k.clone())).collect()
    }

    #[test]
    fn f0_by_hand() {
        // Level 0: a hexagon, 6 corners of valence 2 (two boundary edges each).
        // Level 1: 6 sub-faces; the 6 old corners (valence 2: A1 puts no spoke at a corner), the
        // 3 joints (two pieces and a spoke: 3), the 6 ends of the 3 boundary gaps (a piece and a
        // gap side: 2), the 3 gap points (two gap sides and a spoke: 3), the 6 lacuna corners
        // (two lacuna edges and a spoke: 3): 24 vertices, {2: 12, 3: 12}; edges: 12 pieces, 6
        // spokes, 6 lacuna edges, 6 gap sides = 30; valences sum to 2·30 = 60 = 12·2 + 12·3.
        let (_, m) = of("C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A1", 3);
        let l0 = &m.levels[0];
        assert_eq!(
            (l0.vertices.to_string(), l0.edges.to_string()),
            ("6".into(), "6".into())
        );
        assert_eq!(valences(l0), vec![(2, "6".into())]);
        let l1 = &m.levels[1];
        assert_eq!(
            (
                l1.vertices.to_string(),
                l1.edges.to_string(),
                l1.faces.to_string()
            ),
            ("24".into(), "30".into(), "6".into())
        );
        assert_eq!(valences(l1), vec![(2, "12".into()), (3, "12".into())]);
        // No valence ever exceeds 3. Under A1 no corner is a spoke, so a sector stays one sector
        // and a vertex keeps its valence once born. Births: a lacuna corner (two sub-faces and
        // the lacuna) and a gap point (two sub-faces and the gap) have 3; a joint lies on a B2
        // edge, and F0's B2 edges (its boundary, El and Ec) all border a hole or the outside, so
        // a joint has two sub-faces and that hole: 3; the only edges with faces on both sides are
        // the spokes Ea = C2 and their pieces, whose gap ends have a sub-face, the gap and a
        // sub-face: 3 (on the outer C2 edges, a sub-face and the outside: 2).
        assert_eq!(m.levels[2].max_valence, 3);
        assert_eq!(m.levels[3].max_valence, 3);
        assert_eq!(
            m.limit,
            LimitValence::Bounded {
                max_valence: 3,
                valences: vec![2, 3]
            }
        );
    }

    #[test]
    fn f0_closed_forms_at_every_level() {
        // Hand derivation for F0 = `C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A1`. A sub-face is
        // `C2 B2 | C2 B2 C2 | B2`: a piece of the parent's C2 side, a piece of its B2 side, a spoke
        // Ea = C2 (shared with the neighbour), El = B2 (lacuna), a spoke, Ec = B2 (gap). So a B2
        // side always borders a hole or the outside, a C2 side is outer (a piece of F0's C2 sides)
        // or shared (a spoke or a piece of one). A1 puts no spoke at a corner, so a vertex keeps
        // its valence once born. Edge cells at level k, with F_k = 6^k faces:
        //   outer C2: 3·2^k, outer B2: 3·2^k,
        //   shared C2: S_{k+1} = 2 S_k + 6 F_k, S_0 = 0, so S_k = 3(6^k − 2^k)/2,
        //   B2 at holes: H_{k+1} = 2 H_k + 12 F_k (6 El and 6 Ec per face), so H_k = 2 S_k.
        // Births of a step: per face 6 lacuna corners and 3 gap points (valence 3); a joint per B2
        // cell (two sub-faces and the hole across: 3); two gap ends per shared C2 cell (two
        // sub-faces and the gap: 3) and per outer C2 cell (one sub-face and the outside: 2).
        //   n2_k = 6 + Σ_{j<k} 6·2^j = 6·2^k,
        //   n3_{k+1} = n3_k + 9·6^k + 3·2^k + H_k + 2 S_k = n3_k + 15·6^k − 3·2^k,
        //   so n3_k = 3·6^k − 3·2^k; V_k = 3·6^k + 3·2^k; E_k = 6·2^k + (9/2)(6^k − 2^k).
        // Degree check: 2 n2 + 3 n3 = 9·6^k + 3·2^k = 2 E_k.
        let (_, m) = of("C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A1", 6);
        for (k, l) in m.levels.iter().enumerate() {
            let six = BigUint::from(6u32).pow(k as u32);
            let two = BigUint::from(2u32).pow(k as u32);
            let n2 = &two * 6u32;
            let n3 = &six * 3u32 - &two * 3u32;
            let mut want = vec![(2, n2.to_string())];
            if !n3.is_zero() {
                want.push((3, n3.to_string()));
            }
            assert_eq!(valences(l), want, "level {k}");
            assert_eq!(l.vertices, &six * 3u32 + &two * 3u32, "level {k}");
            assert_eq!(
                l.edges,
                &two * 6u32 + (&six - &two) * 9u32 / 2u32,
                "level {k}"
            );
            assert_eq!(l.faces, six, "level {k}");
            assert_eq!(l.max_valence, if k == 0 { 2 } else { 3 }, "level {k}");
        }
    }

    /// Stepping the counting system of `m` from its start gives, at every level, the valences
    /// built level by level.
    fn steps_like_levels(m: &Multiplicity, what: &str) {
        let sys = m.system.as_ref().expect("bounded valences");
        for l in &m.levels {
            let got: Vec<(usize, String)> = sys
                .valences_at(l.level)
                .into_iter()
                .map(|(v, k)| (v, k.to_string()))
                .collect();
            assert_eq!(got, valences(l), "{what} level {}", l.level);
        }
    }

    #[test]
    fn the_linear_system_steps_like_the_complex() {
        // The substitution over closed vertex types, edge cells and face types is an independent
        // way to the valence counts: stepping its start vector k times must give the valences of
        // level k built level by level (vertex links evolved and interned one level at a time).
        for text in [
            "C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A1",
            "B2 C2 | B2 B2 B2 | A1 | 3",
            "C3 B2 B2 | C2 C2 B2 | A1",
            "B2 B2 B2 C2 | B2 B2 B2 | {joint}",
        ] {
            let (_, m) = of(text, 4);
            steps_like_levels(&m, text);
        }
        // Two quads glued along a B2 side (fixtures/two-quads.txt in canonical rotation): the
        // shared edge is one edge cell of the start, its two end vertices have two sectors.
        let f = Face::parse("B2 C2 B2 C2 | C2 B2 B2 | A1").unwrap();
        let ts = close_or_error(&[f.clone(), f], &Limits::default()).unwrap();
        assert_eq!(ts.start.len(), 2);
        let m = multiplicity(&ts, &[[(0, 2), (1, 0)]], 4, 400).unwrap();
        assert_eq!(m.levels[0].edges.to_string(), "7");
        steps_like_levels(&m, "two quads");
        let (_, m) = of("B2 B2 B2 B2 | B2 B2 B2 | A2", 2);
        assert!(
            m.system.is_none(),
            "unbounded valences have no finite system"
        );
    }

    #[test]
    fn growing_links_meet_a_limit_not_a_hang() {
        // Under A2 a corner's link doubles every level: level 40 would need links of 2^40 items.
        let f = Face::parse("B2 B2 B2 B2 | B2 B2 B2 | A2").unwrap();
        let ts = close_or_error(&[f], &Limits::default()).unwrap();
        let e = multiplicity(&ts, &[], 40, 100).unwrap_err();
        assert!(e.to_string().contains("--max-types"), "{e}");
    }

    #[test]
    fn a2_corners_grow_without_bound() {
        // Under A2 every corner is a spoke: a corner of valence v gains one spoke per face around
        // it at every step, so the vertex types never close.
        let (_, m) = of("B2 B2 B2 B2 | B2 B2 B2 | A2", 3);
        assert!(m.levels[3].max_valence > m.levels[2].max_valence);
        match &m.limit {
            LimitValence::Unbounded { witness } => {
                assert!(witness.period >= 1);
                assert_ne!(witness.gained, "0");
                assert_eq!(witness.cycle.first(), Some(&witness.sector));
                assert_eq!(witness.cycle.last(), Some(&witness.sector));
            }
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn euler_characteristic_matches_the_lacuna_count_at_every_level() {
        // V − E + F = 1 − holes for a connected face, and the holes are the lacunas N^L less the
        // half lacunas of gaps opened on the border of a hole or of the outside.
        for text in [
            "C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A1",
            "C2 C2 C2 C2 C2 | C2 C2 C2 | A2",
            "B2^2 C2 B3 | C2 B2 B2 | A3",
            "B2 C2 | B2 B2 B2 | A1 | 3",
            "C3 B2 B2 | C2 C2 B2 | A1",
        ] {
            let (ts, m) = of(text, 4);
            let c = counts(&ts, 4);
            for (l, lc) in m.levels.iter().zip(&c) {
                let chi = BigInt::from(l.vertices.clone()) - BigInt::from(l.edges.clone())
                    + BigInt::from(l.faces.clone());
                let holes = &lc.lacunas
                    - BigRational::new(BigInt::from(l.half_gaps.clone()), BigInt::from(2));
                assert_eq!(
                    BigRational::from_integer(chi),
                    BigRational::from_integer(1.into()) - holes,
                    "{text} level {}",
                    l.level
                );
                // Every edge has two ends.
                let degree_sum: BigUint = l
                    .valences
                    .iter()
                    .map(|(v, k)| k.parse::<BigUint>().unwrap() * *v)
                    .sum();
                assert_eq!(degree_sum, &l.edges * 2u32, "{text} level {}", l.level);
            }
        }
    }
}
