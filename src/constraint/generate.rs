//! The automaton of a face closure, with the defaults of THEORY §6, and the degeneracy check.
//!
//! * a vertex state `v` (m = 1, `v.T0 = [1]`);
//! * one state per edge type: `Bn` has m = q + 1 control points (Bézier degree q, default 2) and
//!   fixed de Casteljau operators `T_k` restricting to `[k/n, (k+1)/n]`; `Cn` has m = 2 (its end
//!   points) and fixed operators leaving equal gaps (pieces and gaps all of length 1/(2n−1)); a
//!   delayed `X^d` has one operator, the identity onto `X^(d−1)`. Each edge state has its vertex
//!   embeddings `B0`, `B1` and the reversal `J`;
//! * one state per face type `T<t>`: its edges' control points with shared corners merged
//!   (m = Σ(m_edge − 1)); `B_i` selects edge i's points in order; the sub-face operators `T_k` are
//!   the unknowns, tied by incidence (pieces of the parent's edges), adjacency (shared Ea edges,
//!   with J) and barycentric equations.

use crate::algebra::matrix::{bezier_restriction, Matrix};
use crate::constraint::automaton::{Automaton, Constraint, ConstraintKind, Factor, OpKind};
use crate::constraint::linsys::SolutionSpace;
use crate::topology::closure::TypeSet;
use crate::topology::edge::{EdgeKind, EdgeType};
use crate::topology::subdivision::Origin;
use num_rational::BigRational;
use num_traits::One;
use std::collections::{BTreeMap, HashMap};

/// Options of the generated automaton.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct GenOptions {
    /// Bézier degree q of `Bn` edges (m = q + 1).
    pub degree: usize,
    /// Cantor layout: the length of a gap relative to the length of a piece (> 0). With ratio g,
    /// the n pieces of `Cn` have length 1/(n + (n−1)·g) each; 1 (the default) makes pieces and
    /// gaps equal.
    pub cantor_gap: BigRational,
}

impl Default for GenOptions {
    fn default() -> Self {
        GenOptions {
            degree: 2,
            cantor_gap: BigRational::one(),
        }
    }
}

/// The generated automaton with the indices the degeneracy check needs.
#[derive(Clone, Debug)]
pub struct Generated {
    /// The automaton.
    pub automaton: Automaton,
    /// The state of each face type.
    pub face_state: Vec<usize>,
    /// For each face type and sub-face, the operator `T_k`.
    pub sub_ops: Vec<Vec<usize>>,
    /// For each face type, the offset of each boundary edge's first control point.
    pub edge_offsets: Vec<Vec<usize>>,
}

struct Edges {
    state: BTreeMap<EdgeType, usize>,
    subs: BTreeMap<EdgeType, Vec<usize>>,
    b0: BTreeMap<EdgeType, usize>,
    b1: BTreeMap<EdgeType, usize>,
    j: BTreeMap<EdgeType, usize>,
}

fn dim(e: &EdgeType, q: usize) -> usize {
    match e.kind {
        EdgeKind::B => q + 1,
        EdgeKind::C => 2,
    }
}

fn rat(n: usize, d: usize) -> BigRational {
    BigRational::new(n.into(), d.into())
}

/// Builds the automaton of a closed type set.
pub fn automaton_of(ts: &TypeSet, opts: GenOptions) -> Generated {
    let q = opts.degree.max(1);
    let mut a = Automaton::default();
    let v = a.add_state("v", 1);
    let vt = a.add_op("v.T0", OpKind::Sub, v, v, Some(Matrix::identity(1)));
    a.barycentric.push(vt);
    // Every edge type that occurs, with all the lower delays of delayed ones.
    let mut types: std::collections::BTreeSet<EdgeType> = Default::default();
    for t in &ts.types {
        let p = t.face.params;
        for e in t.face.boundary.iter().chain([&p.ea, &p.el, &p.ec]) {
            for d in 1..=e.delay {
                types.insert(e.delayed(d));
            }
        }
    }
    let mut edges = Edges {
        state: BTreeMap::new(),
        subs: BTreeMap::new(),
        b0: BTreeMap::new(),
        b1: BTreeMap::new(),
        j: BTreeMap::new(),
    };
    for e in &types {
        let m = dim(e, q);
        let s = a.add_state(e.to_string(), m);
        edges.state.insert(*e, s);
        let b0 = a.add_op(
            format!("{e}.B0"),
            OpKind::Embed,
            s,
            v,
            Some(Matrix::selection(m, &[0])),
        );
        let b1 = a.add_op(
            format!("{e}.B1"),
            OpKind::Embed,
            s,
            v,
            Some(Matrix::selection(m, &[m - 1])),
        );
        let j = a.add_op(
            format!("{e}.J"),
            OpKind::Perm,
            s,
            s,
            Some(Matrix::reversal(m)),
        );
        a.barycentric.extend([b0, b1]);
        edges.b0.insert(*e, b0);
        edges.b1.insert(*e, b1);
        edges.j.insert(*e, j);
    }
    // Sub-operators need the piece states, so a second pass.
    for e in &types {
        let s = edges.state[e];
        let piece = e.piece();
        let ps = edges.state[&piece];
        let n = e.piece_count() as usize;
        let mut subs = Vec::new();
        for k in 0..n {
            let m = if e.is_delayed() {
                Matrix::identity(dim(e, q))
            } else {
                match e.kind {
                    EdgeKind::B => bezier_restriction(q, &rat(k, n), &rat(k + 1, n)),
                    EdgeKind::C => {
                        // Piece k covers [k·(p + g·p), k·(p + g·p) + p] with p = 1/(n + (n−1)·g).
                        let g = &opts.cantor_gap;
                        let p = BigRational::one() / (rat(n, 1) + rat(n - 1, 1) * g);
                        let lo = rat(k, 1) * (&p + g * &p);
                        let hi = &lo + &p;
                        Matrix::from_rows(vec![
                            vec![BigRational::one() - &lo, BigRational::one() - &hi],
                            vec![lo, hi],
                        ])
                    }
                }
            };
            let op = a.add_op(format!("{e}.T{k}"), OpKind::Sub, s, ps, Some(m));
            a.barycentric.push(op);
            subs.push(op);
        }
        // The fixed operators must be consistent with the vertices: end points stay end points,
        // and consecutive Bézier pieces meet (Cantor pieces are separated by gaps).
        let label = format!("edge {e}");
        let con = |lhs: Vec<Factor>, rhs: Vec<Factor>, kind| Constraint {
            label: label.clone(),
            span: None,
            kind,
            lhs,
            rhs,
        };
        a.constraints.push(con(
            vec![Factor::Op(edges.b0[e]), Factor::Op(vt)],
            vec![Factor::Op(subs[0]), Factor::Op(edges.b0[&piece])],
            ConstraintKind::Incidence,
        ));
        a.constraints.push(con(
            vec![Factor::Op(edges.b1[e]), Factor::Op(vt)],
            vec![Factor::Op(subs[n - 1]), Factor::Op(edges.b1[&piece])],
            ConstraintKind::Incidence,
        ));
        if e.kind == EdgeKind::B && !e.is_delayed() {
            for k in 0..n - 1 {
                a.constraints.push(con(
                    vec![Factor::Op(subs[k]), Factor::Op(edges.b1[&piece])],
                    vec![Factor::Op(subs[k + 1]), Factor::Op(edges.b0[&piece])],
                    ConstraintKind::Adjacency,
                ));
            }
        }
        edges.subs.insert(*e, subs);
    }
    // Face states.
    let mut face_state = Vec::new();
    let mut edge_offsets = Vec::new();
    let mut embeds: Vec<Vec<usize>> = Vec::new();
    for (t, ty) in ts.types.iter().enumerate() {
        let dims: Vec<usize> = ty.face.boundary.iter().map(|e| dim(e, q)).collect();
        let m: usize = dims.iter().map(|d| d - 1).sum::<usize>().max(1);
        let s = a.add_state(format!("T{t}"), m);
        let mut offsets = Vec::new();
        let mut off = 0;
        let mut bs = Vec::new();
        for (i, e) in ty.face.boundary.iter().enumerate() {
            offsets.push(off);
            let pick: Vec<usize> = (0..dims[i]).map(|c| (off + c) % m).collect();
            bs.push(a.add_op(
                format!("T{t}.B{i}"),
                OpKind::Embed,
                s,
                edges.state[e],
                Some(Matrix::selection(m, &pick)),
            ));
            off += dims[i] - 1;
        }
        face_state.push(s);
        edge_offsets.push(offsets);
        embeds.push(bs);
    }
    let mut sub_ops = Vec::new();
    for (t, ty) in ts.types.iter().enumerate() {
        let mut ops = Vec::new();
        for (k, &w) in ty.children.iter().enumerate() {
            let op = a.add_op(
                format!("T{t}.T{k}"),
                OpKind::Sub,
                face_state[t],
                face_state[w],
                None,
            );
            a.barycentric.push(op);
            ops.push(op);
        }
        for (k, sub) in ty.subdivision.subfaces.iter().enumerate() {
            let w = ty.children[k];
            for (l, origin) in sub.origins.iter().enumerate() {
                if let Origin::Piece { edge, piece } = *origin {
                    let e = ty.face.boundary[edge];
                    a.constraints.push(Constraint {
                        label: format!("T{t} incidence: piece {piece} of edge {edge} is edge {l} of sub-face {k}"),
                        span: None,
                        kind: ConstraintKind::Incidence,
                        lhs: vec![Factor::Op(embeds[t][edge]), Factor::Op(edges.subs[&e][piece])],
                        rhs: vec![Factor::Op(ops[k]), Factor::Op(embeds[w][l])],
                    });
                }
            }
        }
        for adj in &ty.subdivision.adjacencies {
            let ((sa, la), (sb, lb)) = (adj.first, adj.second);
            let (wa, wb) = (ty.children[sa], ty.children[sb]);
            let ea = ts.types[wa].face.boundary[la];
            a.constraints.push(Constraint {
                label: format!("T{t} adjacency: edge {la} of sub-face {sa} = edge {lb} of sub-face {sb} reversed"),
                span: None,
                kind: ConstraintKind::Adjacency,
                lhs: vec![Factor::Op(ops[sa]), Factor::Op(embeds[wa][la]), Factor::Op(edges.j[&ea])],
                rhs: vec![Factor::Op(ops[sb]), Factor::Op(embeds[wb][lb])],
            });
        }
        sub_ops.push(ops);
    }
    Generated {
        automaton: a,
        face_state,
        sub_ops,
        edge_offsets,
    }
}

/// The forced collapses of a closure's level-1 complexes (THEORY §6), as data: what the
/// certificate's `degeneracy` step lists.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Collapses {
    /// `[type, sub-face, corner, sub-face, corner]`: two combinatorially distinct corners that
    /// coincide on every solution (each later corner paired with the first of its class).
    pub coincide: Vec<[usize; 5]>,
    /// Face types of two Cantor edges (area 0).
    pub flat_faces: Vec<usize>,
    /// Face types whose two-sided lacuna has Cantor sides (area 0).
    pub flat_lacunas: Vec<usize>,
}

impl Collapses {
    /// True when nothing collapses.
    pub fn is_empty(&self) -> bool {
        self.coincide.is_empty() && self.flat_faces.is_empty() && self.flat_lacunas.is_empty()
    }

    /// One message per forced collapse, in the words `verify` prints.
    pub fn messages(&self, verb: &str) -> Vec<String> {
        let mut out: Vec<String> = self
            .coincide
            .iter()
            .map(|[t, k1, p1, k2, p2]| {
                format!(
                    "T{t}: corner {p1} of sub-face {k1} and corner {p2} of sub-face {k2} {verb}"
                )
            })
            .collect();
        out.extend(self.flat_faces.iter().map(|t| {
            format!("T{t}: its two edges are Cantor edges between the same two corners: the face has area 0")
        }));
        out.extend(self.flat_lacunas.iter().map(|t| {
            format!(
                "T{t}: its lacuna has two sides, both Cantor edges between the inner ends of its \
                 two spokes: the lacuna has area 0"
            )
        }));
        out
    }
}

/// The degeneracy check (THEORY §6): for every face type, the corner points of its level-1
/// complex that are combinatorially distinct must not be forced to coincide by the constraints
/// (each coordinate has the same affine expression in the free parameters, see
/// `Parametrization::expression`), and no cell may be forced to zero area by two Cantor sides
/// on one segment ([`TypeSet::flat_cells`]).
pub fn collapses(
    ts: &TypeSet,
    g: &Generated,
    offsets: &[Option<usize>],
    space: &SolutionSpace,
) -> Collapses {
    let param = space.parametrize();
    let (flat_faces, flat_lacunas) = ts.flat_cells();
    Collapses {
        coincide: coinciding(ts, g, offsets, |x| param.expression(x)),
        flat_faces,
        flat_lacunas,
    }
}

/// [`collapses`] as messages, one per forced collapse.
pub fn degeneracies(
    ts: &TypeSet,
    g: &Generated,
    offsets: &[Option<usize>],
    space: &SolutionSpace,
) -> Vec<String> {
    collapses(ts, g, offsets, space).messages("are forced to coincide")
}

/// The same check at one point of the solution space (THEORY §13, a frame of a morph): with the
/// exact value of every unknown, two combinatorially distinct corner points of a level-1 complex
/// coincide when their barycentric coordinates in the parent are equal — then they coincide in
/// every placement. Returns one message per collapse.
pub fn collapses_at(
    ts: &TypeSet,
    g: &Generated,
    offsets: &[Option<usize>],
    values: &[BigRational],
) -> Vec<String> {
    Collapses {
        coincide: coinciding(ts, g, offsets, |x| values[x].clone()),
        ..Collapses::default()
    }
    .messages("coincide")
}

/// For every face type, the pairs of distinct level-1 corner points whose coordinates (unknown
/// indices, mapped by `key`) are equal: `[type, sub-face, corner, sub-face, corner]`, the first
/// corner of the class first.
fn coinciding<K: std::hash::Hash + Eq>(
    ts: &TypeSet,
    g: &Generated,
    offsets: &[Option<usize>],
    key: impl Fn(usize) -> K,
) -> Vec<[usize; 5]> {
    let a = &g.automaton;
    let mut out = Vec::new();
    for (t, ty) in ts.types.iter().enumerate() {
        let class = ty.subdivision.corner_classes(&ty.face);
        // One representative per point of the level-1 complex, with its coordinates as variables.
        let mut reps: BTreeMap<usize, (usize, usize)> = BTreeMap::new();
        for (k, points) in class.iter().enumerate() {
            for (p, &point) in points.iter().enumerate() {
                reps.entry(point).or_insert((k, p));
            }
        }
        let reps: Vec<(usize, usize)> = reps.into_values().collect();
        let m_t = a.states[g.face_state[t]].dim;
        let coords = |(k, p): (usize, usize)| -> Option<Vec<usize>> {
            let op = g.sub_ops[t][k];
            let base = offsets[op]?;
            let w = ty.children[k];
            let m_w = a.states[g.face_state[w]].dim;
            let col = g.edge_offsets[w][p] % m_w;
            Some((0..m_t).map(|r| base + r * m_w + col).collect())
        };
        let mut seen: HashMap<Vec<K>, (usize, usize)> = HashMap::new();
        for &rep in &reps {
            let Some(xs) = coords(rep) else { continue };
            let k: Vec<K> = xs.iter().map(|&x| key(x)).collect();
            match seen.get(&k) {
                Some(&first) => out.push([t, first.0, first.1, rep.0, rep.1]),
                None => {
                    seen.insert(k, rep);
                }
            }
        }
    }
    out
}

/// Generates, solves and checks degeneracy for a closed type set.
pub fn solve_closure(
    ts: &TypeSet,
    opts: GenOptions,
    limits: &crate::topology::limits::Limits,
) -> crate::error::Result<crate::constraint::automaton::SolveReport> {
    let g = automaton_of(ts, opts);
    g.automaton.check_solve_limits(limits)?;
    let (mut report, lin, solution) = crate::constraint::automaton::solve_automaton(&g.automaton)?;
    if let crate::constraint::linsys::Solution::Consistent(space) = &solution {
        report.degenerate = degeneracies(ts, &g, &lin.offsets, space);
        report.degeneracy_checked = true;
    }
    Ok(report)
}
