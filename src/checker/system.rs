//! The constraint system of a closure (THEORY §6), rebuilt by the checker from the closure step
//! and the recipe (Bézier degree, Cantor gap ratio, unknown names), so that a solution-space or
//! inconsistency step is tied to the closure it claims to be about.
//!
//! The automaton, as THEORY §6 defines it:
//! - a vertex state `v` (m = 1, `v.T0 = [1]`);
//! - one state per edge type occurring (boundaries and `E`, with every lower delay): `Bn` has
//!   m = q + 1 control points and de Casteljau operators `T_k` restricting to `[k/n, (k+1)/n]`;
//!   `Cn` has m = 2 and operators onto pieces of length `p = 1/(n + (n−1)·g)` separated by gaps
//!   `g·p`; a delayed `X^d` has one operator, the identity onto `X^(d−1)`; embeddings `B0`, `B1`
//!   of the end points and the reversal `J`;
//! - one state per face type `t` with `m_t = Σ (m_edge − 1)` points (shared corners merged),
//!   embeddings `B_i` selecting edge i's points cyclically, and the unknown sub-face operators
//!   `T<t>.T<k>` (`m_t × m_w`, w the sub-face's type).
//!
//! Rows: every entry of every constraint (`lhs − rhs`, constants moved right) and every column of
//! every barycentric operator (`Σ column = 1`). Constraints: per edge type, its end points stay end
//! points and consecutive Bézier pieces meet; per face type, incidence (piece `j` of edge `i` is
//! edge `l` of sub-face `k`: `B_i · e.T_j = T_k · B_l`) and adjacency (the shared `Ea` edge:
//! `T_a · B_l · J = T_b · B_m`).

use super::automaton::rebuild_automaton;
use super::{rat, Equation, Q};
use crate::certificate::{AutomatonClaim, ClosureStep, Edge, Kind, Origin, Recipe, System};
use num_traits::{One, Zero};
use std::collections::{BTreeSet, HashMap};

/// The largest Bézier degree the checker rebuilds (lacuna accepts 1 to 8).
const MAX_DEGREE: usize = 32;

/// A dense matrix, by rows.
type Mat = Vec<Vec<Q>>;

fn zeros(r: usize, c: usize) -> Mat {
    vec![vec![Q::zero(); c]; r]
}

fn identity(n: usize) -> Mat {
    select(n, &(0..n).collect::<Vec<_>>())
}

/// The `rows × pick.len()` matrix whose column c is the unit vector `e_(pick[c])`.
fn select(rows: usize, pick: &[usize]) -> Mat {
    let mut m = zeros(rows, pick.len());
    pick.iter()
        .enumerate()
        .for_each(|(c, &r)| m[r][c] = Q::one());
    m
}

fn reversal(n: usize) -> Mat {
    select(n, &(0..n).rev().collect::<Vec<_>>())
}

fn mul(a: &Mat, b: &Mat) -> Mat {
    let cols = b.first().map_or(0, Vec::len);
    a.iter()
        .map(|row| {
            (0..cols)
                .map(|c| row.iter().zip(b).map(|(x, br)| x * &br[c]).sum())
                .collect()
        })
        .collect()
}

/// The de Casteljau restriction of a degree-q Bézier curve to `[a, b]`: column i is the blossom
/// `f(a, …, a, b, …, b)` (`q − i` times a, i times b) as weights of the q + 1 control points.
fn restriction(q: usize, a: &Q, b: &Q) -> Mat {
    let column = |i: usize| -> Vec<Q> {
        let mut pts: Mat = identity(q + 1);
        for step in 0..q {
            let u = if step < q - i { a } else { b };
            pts = pts
                .windows(2)
                .map(|w| {
                    let (p0, p1) = (&w[0], &w[1]);
                    p0.iter()
                        .zip(p1)
                        .map(|(x, y)| (Q::one() - u) * x + u * y)
                        .collect()
                })
                .collect();
        }
        pts.swap_remove(0)
    };
    let columns: Mat = (0..=q).map(column).collect();
    (0..=q)
        .map(|k| columns.iter().map(|c| c[k].clone()).collect())
        .collect()
}

/// One side of a constraint: a known matrix, or `X · right` with X the unknown operator whose
/// entry `(r, j)` is unknown `base + r·cols + j`.
enum Side {
    Known(Mat),
    Unknown {
        base: usize,
        rows: usize,
        right: Mat,
    },
}

impl Side {
    /// Entry `(r, c)` as `(terms, constant)`.
    fn entry(&self, r: usize, c: usize) -> (Vec<(usize, Q)>, Q) {
        match self {
            Side::Known(m) => (Vec::new(), m[r][c].clone()),
            Side::Unknown { base, right, .. } => {
                let cols = right.len();
                let terms = (0..cols)
                    .filter(|&j| !right[j][c].is_zero())
                    .map(|j| (base + r * cols + j, right[j][c].clone()))
                    .collect();
                (terms, Q::zero())
            }
        }
    }

    fn shape(&self) -> (usize, usize) {
        match self {
            Side::Known(m) => (m.len(), m.first().map_or(0, Vec::len)),
            Side::Unknown { rows, right, .. } => (*rows, right.first().map_or(0, Vec::len)),
        }
    }
}

/// The rebuilt system, unknowns in the checker's own order, with their names.
struct Builder {
    q: usize,
    gap: Q,
    rows: Vec<Equation>,
}

/// The number of control points of an edge: q + 1 for `Bn`, 2 for `Cn`.
fn dim(q: usize, e: &Edge) -> usize {
    match e.kind {
        Kind::B => q + 1,
        Kind::C => 2,
    }
}

impl Builder {
    fn dim(&self, e: &Edge) -> usize {
        dim(self.q, e)
    }

    /// `lhs = rhs`, entry by entry.
    fn equal(&mut self, lhs: Side, rhs: Side) -> Result<(), String> {
        let (r, c) = lhs.shape();
        if rhs.shape() != (r, c) {
            return Err("a rebuilt constraint has sides of different shapes".into());
        }
        for (i, j) in (0..r).flat_map(|i| (0..c).map(move |j| (i, j))) {
            let ((mut terms, lk), (rt, rk)) = (lhs.entry(i, j), rhs.entry(i, j));
            terms.extend(rt.into_iter().map(|(v, a)| (v, -a)));
            self.rows.push((terms, rk - lk));
        }
        Ok(())
    }

    /// Each column of a known barycentric operator sums to 1.
    fn barycentric(&mut self, m: &Mat) {
        for c in 0..m.first().map_or(0, Vec::len) {
            let sum: Q = m.iter().map(|row| &row[c]).sum();
            self.rows.push((Vec::new(), Q::one() - sum));
        }
    }

    /// The fixed operators `T_k` of an edge type onto its pieces.
    fn subs(&self, e: &Edge) -> Vec<Mat> {
        if e.delay >= 2 {
            return vec![identity(self.dim(e))];
        }
        let n = e.n as usize;
        let frac = |a: usize, b: usize| Q::new(a.into(), b.into());
        (0..n)
            .map(|k| match e.kind {
                Kind::B => restriction(self.q, &frac(k, n), &frac(k + 1, n)),
                Kind::C => {
                    let p = Q::one() / (frac(n, 1) + frac(n - 1, 1) * &self.gap);
                    let lo = frac(k, 1) * (&p + &self.gap * &p);
                    let hi = &lo + &p;
                    vec![vec![Q::one() - &lo, Q::one() - &hi], vec![lo, hi]]
                }
            })
            .collect()
    }

    /// The rows of one edge type: its operators are barycentric and consistent with the vertices.
    fn edge(&mut self, e: &Edge) -> Result<(), String> {
        let piece = match e.delay >= 2 {
            true => Edge {
                delay: e.delay - 1,
                ..*e
            },
            false => *e,
        };
        let (m, mp) = (self.dim(e), self.dim(&piece));
        let (b0, b1) = (select(m, &[0]), select(m, &[m - 1]));
        let (p0, p1) = (select(mp, &[0]), select(mp, &[mp - 1]));
        let subs = self.subs(e);
        let n = subs.len();
        self.equal(Side::Known(b0.clone()), Side::Known(mul(&subs[0], &p0)))?;
        self.equal(Side::Known(b1.clone()), Side::Known(mul(&subs[n - 1], &p1)))?;
        if e.kind == Kind::B && e.delay == 1 {
            for k in 0..n - 1 {
                let (l, r) = (mul(&subs[k], &p1), mul(&subs[k + 1], &p0));
                self.equal(Side::Known(l), Side::Known(r))?;
            }
        }
        Ok(())
    }
}

/// The rebuilt rows with unknowns renumbered to the certificate's columns (matched by name).
/// `given_rows` is the number of rows the certificate lists: every edge state yields at least
/// one row per piece, so edges with more pieces (or delays) than that cannot match and are
/// refused before anything of their size is built; likewise the unknowns are counted (checked
/// arithmetic) and compared with the recipe before a name is built.
pub(super) fn rebuild(
    c: &ClosureStep,
    (degree, cantor_gap): (usize, &str),
    recipe: &Recipe,
    given_rows: usize,
) -> Result<Vec<Equation>, String> {
    let (layout, rows) = rebuild_ordered(
        c,
        (degree, cantor_gap),
        Some(recipe.unknowns.len()),
        given_rows as u128,
    )?;
    let column = columns(&layout.names, &recipe.unknowns)?;
    let renumber = |(terms, rhs): Equation| -> Equation {
        (
            terms.into_iter().map(|(v, a)| (column[v], a)).collect(),
            rhs,
        )
    };
    Ok(rows.into_iter().map(renumber).collect())
}

/// The rebuilt system with the unknowns in the checker's own order (the layout's names), for
/// Bézier degree and Cantor ratio as written. `expected`, when given, is the number of unknowns
/// the certificate names (compared before a name is built); the edge states must need at most
/// `max_states` rows.
pub(super) fn rebuild_ordered(
    c: &ClosureStep,
    (degree, cantor_gap): (usize, &str),
    expected: Option<usize>,
    max_states: u128,
) -> Result<(Layout, Vec<Equation>), String> {
    if !(1..=MAX_DEGREE).contains(&degree) {
        return Err(format!("Bézier degree {degree} is not in 1..={MAX_DEGREE}"));
    }
    let gap = rat(cantor_gap)?;
    if gap <= Q::zero() {
        return Err(format!("Cantor gap ratio {gap} is not positive"));
    }
    let q = degree;
    let mut b = Builder {
        q,
        gap,
        rows: Vec::new(),
    };
    // The edge states: every edge occurring, with all lower delays; bounded by the rows first.
    // Per base edge (kind, n), the largest delay: its states X^1 … X^D give at least n rows
    // (the pieces of X^1) and one per state.
    let mut deepest: std::collections::BTreeMap<(Kind, u32), u32> = Default::default();
    for rule in &c.types {
        let p = rule.face.params;
        for e in rule.face.boundary.iter().chain([&p.ea, &p.el, &p.ec]) {
            let d = deepest.entry((e.kind, e.n)).or_insert(0);
            *d = (*d).max(e.delay);
        }
    }
    let states = deepest.iter().fold(0u128, |acc, ((_, n), d)| {
        acc.saturating_add(u128::from(*n))
            .saturating_add(u128::from(*d))
    });
    if states > max_states {
        return Err(format!(
            "the edge types need more than the {max_states} rows the certificate lists"
        ));
    }
    let edges: BTreeSet<Edge> = deepest
        .iter()
        .flat_map(|(&(kind, n), &d)| (1..=d).map(move |delay| Edge { kind, n, delay }))
        .collect();
    let lay = layout(c, q, expected)?;
    let (dims, offsets, base) = (&lay.dims, &lay.offsets, &lay.base);
    let embed = |t: usize, i: usize| -> Option<Mat> {
        let e = c.types.get(t)?.face.boundary.get(i)?;
        let o: usize = *offsets.get(t).and_then(|o: &Vec<usize>| o.get(i))?;
        let pick: Vec<usize> = (0..dim(q, e)).map(|x| (o + x) % dims[t]).collect();
        Some(select(dims[t], &pick))
    };
    // The vertex and every edge type, with all lower delays.
    b.barycentric(&identity(1));
    for e in &edges {
        let m = b.dim(e);
        b.barycentric(&select(m, &[0]));
        b.barycentric(&select(m, &[m - 1]));
        b.subs(e).iter().for_each(|s| b.barycentric(s));
        b.edge(e)?;
    }
    let missing = || "the closure's indices are out of range".to_string();
    for (t, rule) in c.types.iter().enumerate() {
        let unknown = |k: usize, right: Mat| Side::Unknown {
            base: base[t][k],
            rows: dims[t],
            right,
        };
        for (k, sf) in rule.subfaces.iter().enumerate() {
            let w = sf.type_index;
            for col in 0..dims[w] {
                let terms = (0..dims[t])
                    .map(|r| (base[t][k] + r * dims[w] + col, Q::one()))
                    .collect();
                b.rows.push((terms, Q::one()));
            }
            for (l, o) in sf.origins.iter().enumerate() {
                let Origin::Piece { edge, piece } = *o else {
                    continue;
                };
                let e = rule.face.boundary.get(edge).ok_or_else(missing)?;
                let sub = b.subs(e).into_iter().nth(piece).ok_or_else(missing)?;
                let lhs = mul(&embed(t, edge).ok_or_else(missing)?, &sub);
                let rhs = unknown(k, embed(w, l).ok_or_else(missing)?);
                b.equal(Side::Known(lhs), rhs)?;
            }
        }
        for a in &rule.adjacencies {
            let ((sa, la), (sb, lb)) = (a.first, a.second);
            let ty = |s: usize| rule.subfaces.get(s).map(|x| x.type_index);
            let (wa, wb) = (ty(sa).ok_or_else(missing)?, ty(sb).ok_or_else(missing)?);
            let ea = c.types[wa].face.boundary.get(la).ok_or_else(missing)?;
            let left = mul(&embed(wa, la).ok_or_else(missing)?, &reversal(b.dim(ea)));
            let right = embed(wb, lb).ok_or_else(missing)?;
            b.equal(unknown(sa, left), unknown(sb, right))?;
        }
    }
    Ok((lay, b.rows))
}

/// Where the unknowns of a closure's system sit: per face type its number of control points
/// (`dims`), the position of each boundary edge's first point (`offsets`), the first unknown of
/// each sub-face operator (`base`) and every unknown's name, in the checker's own order.
pub(super) struct Layout {
    /// `m_t`, the control points of face type t.
    pub dims: Vec<usize>,
    /// `offsets[t][i]`: the first point of boundary edge i of type t.
    pub offsets: Vec<Vec<usize>>,
    /// `base[t][k]`: the unknown of entry `[0][0]` of sub-face operator k of type t.
    pub base: Vec<Vec<usize>>,
    /// `T<t>.T<k>[r][c]`, row-major per operator.
    pub names: Vec<String>,
}

/// The layout of the unknowns of a closure's system for Bézier degree `q`; the number of
/// unknowns is counted (checked arithmetic) and compared with `expected` before a name is
/// built.
pub(super) fn layout(c: &ClosureStep, q: usize, expected: Option<usize>) -> Result<Layout, String> {
    // Face states: dimension, and the offset of each boundary edge's first point.
    let mut dims = Vec::new();
    let mut offsets = Vec::new();
    for rule in &c.types {
        let ds: Vec<usize> = rule.face.boundary.iter().map(|e| dim(q, e) - 1).collect();
        offsets.push(
            ds.iter()
                .scan(0, |s, d| Some(std::mem::replace(s, *s + d)))
                .collect(),
        );
        dims.push(ds.iter().sum::<usize>().max(1));
    }
    // The unknowns: sub-face operator k of type t, entries in row-major order. Counted first.
    let mut count: usize = 0;
    for (t, rule) in c.types.iter().enumerate() {
        for sf in &rule.subfaces {
            let w = *dims
                .get(sf.type_index)
                .ok_or("a sub-face type is out of range")?;
            count = dims[t]
                .checked_mul(w)
                .and_then(|x| count.checked_add(x))
                .ok_or("the number of unknowns overflows")?;
        }
    }
    if let Some(expected) = expected.filter(|&e| e != count) {
        return Err(format!(
            "the recipe names {expected} unknowns, the closure has {count}"
        ));
    }
    super::within_work("the unknowns of the face system", count as u128)?;
    let mut names = Vec::with_capacity(count);
    let mut base = Vec::new();
    for (t, rule) in c.types.iter().enumerate() {
        let mut bs = Vec::new();
        for (k, sf) in rule.subfaces.iter().enumerate() {
            let w = dims[sf.type_index];
            bs.push(names.len());
            for (r, col) in (0..dims[t]).flat_map(|r| (0..w).map(move |col| (r, col))) {
                names.push(format!("T{t}.T{k}[{r}][{col}]"));
            }
        }
        base.push(bs);
    }
    Ok(Layout {
        dims,
        offsets,
        base,
        names,
    })
}

/// For each rebuilt unknown, the certificate's column with the same name; the names must be a
/// permutation of the rebuilt ones.
pub(super) fn columns(rebuilt: &[String], given: &[String]) -> Result<Vec<usize>, String> {
    if rebuilt.len() != given.len() {
        return Err(format!(
            "the recipe names {} unknowns, the closure has {}",
            given.len(),
            rebuilt.len()
        ));
    }
    let mut at: HashMap<&str, usize> = HashMap::with_capacity(given.len());
    for (j, name) in given.iter().enumerate() {
        if at.insert(name, j).is_some() {
            return Err(format!("the recipe names unknown `{name}` twice"));
        }
    }
    rebuilt
        .iter()
        .map(|n| {
            at.get(n.as_str())
                .copied()
                .ok_or_else(|| format!("the recipe does not name unknown `{n}`"))
        })
        .collect()
}

/// The layout of a closure's unknowns (degree `q`) and, for each, its column in the proved
/// solution space `s`, matched by the recipe's names: what the steps that read operator entries
/// on the solution set (`degeneracy`, `level-one`) stand on.
pub(super) fn solution_layout(
    c: &ClosureStep,
    q: usize,
    s: &crate::certificate::SolutionStep,
) -> Result<(Layout, Vec<usize>), String> {
    let recipe = s
        .system
        .recipe
        .as_ref()
        .ok_or("the solution space has no recipe naming its unknowns")?;
    let lay = layout(c, q, Some(s.system.unknowns))?;
    let column = columns(&lay.names, &recipe.unknowns)?;
    Ok((lay, column))
}

/// A row in canonical form: terms merged by unknown, zeros dropped, sorted.
fn canonical((terms, rhs): &Equation) -> (Vec<(usize, Q)>, Q) {
    let mut merged: Vec<(usize, Q)> = terms.clone();
    merged.sort_unstable_by_key(|(v, _)| *v);
    let mut out: Vec<(usize, Q)> = Vec::with_capacity(merged.len());
    for (v, a) in merged {
        match out.last_mut() {
            Some((w, b)) if *w == v => *b += a,
            _ => out.push((v, a)),
        }
    }
    out.retain(|(_, a)| !a.is_zero());
    (out, rhs.clone())
}

/// Checks that the certificate's rows are exactly the rebuilt rows (as a multiset, each in
/// canonical form), with a hash map: linear in the rows' total size. Returns a description of
/// the first difference.
pub(super) fn same_rows(given: &[Equation], rebuilt: &[Equation]) -> Result<(), String> {
    if given.len() != rebuilt.len() {
        return Err(format!(
            "the certificate lists {} rows, the rebuilt system has {}",
            given.len(),
            rebuilt.len()
        ));
    }
    let mut count: HashMap<(Vec<(usize, Q)>, Q), usize> = HashMap::with_capacity(rebuilt.len());
    rebuilt
        .iter()
        .for_each(|r| *count.entry(canonical(r)).or_insert(0) += 1);
    for (i, r) in given.iter().enumerate() {
        match count.get_mut(&canonical(r)) {
            Some(k) if *k > 0 => *k -= 1,
            _ => return Err(format!("row {i} of the certificate is not a rebuilt row")),
        }
    }
    Ok(())
}

/// What a system step is tied to.
pub(super) enum Tie<'a> {
    /// The proved closure step of a faces claim, with the claim's degree and Cantor ratio.
    Closure {
        /// The closure step.
        closure: &'a ClosureStep,
        /// Bézier degree.
        degree: usize,
        /// Cantor gap/piece ratio (a rational, as written).
        gap: &'a str,
    },
    /// The claim's automaton.
    Automaton(&'a AutomatonClaim),
    /// The claim's system, as given.
    Given(&'a System),
    /// Nothing: a faces claim whose closure step failed, or a claim without systems.
    Missing,
}

/// Ties a system to the claim: its rows must be exactly the ones rebuilt from the proved
/// closure step, from the claim's automaton, or the claim's system. Returns the first words of
/// the step's report.
pub(super) fn tie(system: &System, rows: &[Equation], tie: Tie) -> Result<String, String> {
    let n = system.unknowns;
    let mismatch = |e: String| format!("the system does not match the claim: {e}");
    match (tie, &system.recipe) {
        (Tie::Missing, _) => Err("no proved closure step to tie the system to".into()),
        (Tie::Closure { .. }, None) => {
            Err("the system has no recipe, so it is not tied to the closure step".into())
        }
        (Tie::Automaton(_) | Tie::Given(_), Some(_)) => Err(mismatch(
            "a recipe, but the claim is not about faces".into(),
        )),
        (
            Tie::Closure {
                closure,
                degree,
                gap,
            },
            Some(recipe),
        ) => {
            if recipe.unknowns.len() != n {
                return Err(mismatch(format!(
                    "{} unknown names for {n} unknowns",
                    recipe.unknowns.len()
                )));
            }
            let rebuilt = rebuild(closure, (degree, gap), recipe, rows.len())
                .map_err(|e| format!("the system does not match the closure: {e}"))?;
            same_rows(rows, &rebuilt)
                .map_err(|e| format!("the system does not match the closure: {e}"))?;
            Ok(format!(
                "system rebuilt from the closure: {} rows over {n} unknowns (THEORY §6, Bézier \
                 degree {degree}, Cantor gap/piece {gap}), the certificate's rows exactly",
                rebuilt.len(),
            ))
        }
        (Tie::Automaton(a), None) => {
            let rebuilt = rebuild_automaton(a, n, rows).map_err(mismatch)?;
            same_rows(rows, &rebuilt).map_err(mismatch)?;
            Ok(format!(
                "system rebuilt from the claim's automaton: {} rows over {n} unknowns, the \
                 certificate's rows exactly",
                rebuilt.len()
            ))
        }
        (Tie::Given(s), None) => {
            if s.unknowns != n {
                return Err(mismatch(format!(
                    "{n} unknowns, the claim has {}",
                    s.unknowns
                )));
            }
            let claimed = super::linear::parse_rows(&s.rows, s.unknowns)?;
            same_rows(rows, &claimed).map_err(mismatch)?;
            Ok(format!(
                "the claim's system: {} rows over {n} unknowns",
                rows.len()
            ))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(n: i64, d: i64) -> Q {
        Q::new(n.into(), d.into())
    }

    #[test]
    fn restriction_and_cantor_pieces_by_hand() {
        // [0, 1/2] of a quadratic: P0, (P0 + P1)/2, (P0 + 2·P1 + P2)/4 as columns.
        let want = [[q(1, 1), q(1, 2), q(1, 4)], [q(0, 1), q(1, 2), q(1, 2)]];
        let got = restriction(2, &q(0, 1), &q(1, 2));
        assert_eq!(got[..2], want.map(|r| r.to_vec()));
        assert_eq!(got[2], vec![q(0, 1), q(0, 1), q(1, 4)]);
        // C2 with equal gaps: pieces [0, 1/3] and [2/3, 1]; the second has end points
        // (1/3·A + 2/3·B) and B.
        let e = Edge {
            kind: Kind::C,
            n: 2,
            delay: 1,
        };
        let b = Builder {
            q: 2,
            gap: q(1, 1),
            rows: Vec::new(),
        };
        let one = vec![vec![q(1, 3), q(0, 1)], vec![q(2, 3), q(1, 1)]];
        assert_eq!(b.subs(&e)[1], one);
    }
}
