//! The closure step: re-derives every listed type's subdivision (THEORY §3) with the checker's own
//! code and checks the incidence identities and contributions (see `docs/CERTIFICATES.md`).

use crate::certificate::{
    Adjacency, ClosureStep, Edge, Face, Kind, Origin, Params, Pattern, SpokeItem, SubstitutionClaim,
};
use num_bigint::BigUint;
use num_traits::{One, Zero};
use std::collections::{BTreeMap, BTreeSet, HashMap};

/// The substitution read off a checked closure, or given by the claim: matrix rows,
/// contributions (halves), start counts. Every count is a big integer: repeated pairs add up
/// exactly, however large.
pub(super) struct Substitution {
    pub(super) matrix: Vec<BTreeMap<usize, BigUint>>,
    pub(super) contributions: Vec<BigUint>,
    pub(super) start: BTreeMap<usize, BigUint>,
    /// Contributions are in `1/unit` lacunas: 2 (halves) for faces, 4 (quarters) for volumes.
    pub(super) unit: u32,
}

/// `Σ k` of the pairs `(index, k)` with equal index, exactly (big integers), zeros dropped;
/// every index must be below `n`.
pub(super) fn merge_pairs(
    pairs: &[(usize, u64)],
    n: usize,
    what: &str,
) -> Result<BTreeMap<usize, BigUint>, String> {
    let mut out: BTreeMap<usize, BigUint> = BTreeMap::new();
    for &(s, k) in pairs {
        if s >= n {
            return Err(format!("{what}: type {s} out of range (0..{n})"));
        }
        *out.entry(s).or_insert_with(BigUint::zero) += BigUint::from(k);
    }
    out.retain(|_, k| !k.is_zero());
    Ok(out)
}

impl Substitution {
    /// The substitution a claim gives as a matrix.
    pub(super) fn of_claim(s: &SubstitutionClaim) -> Result<Substitution, String> {
        let n = s.matrix.len();
        if s.contribution_halves.len() != n {
            return Err(format!(
                "{} contributions for {n} types",
                s.contribution_halves.len()
            ));
        }
        let matrix = s
            .matrix
            .iter()
            .enumerate()
            .map(|(t, row)| merge_pairs(row, n, &format!("matrix row {t}")))
            .collect::<Result<_, _>>()?;
        let start = merge_pairs(&s.start, n, "start")?;
        if start.is_empty() {
            return Err("no start face".into());
        }
        Ok(Substitution {
            matrix,
            contributions: s.contribution_halves.iter().map(|&h| h.into()).collect(),
            start,
            unit: 2,
        })
    }
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum JKind {
    Joint,
    Gap,
    Corner,
}

/// A sub-edge: its type, (edge, piece), and the junction after it (kind, edges around it).
type SubEdge = (Edge, (usize, usize), (JKind, Edge, Edge));

/// A derived sub-face: canonical boundary, aligned origins, delay.
pub(super) type Derived = (Vec<Edge>, Vec<Origin>, u32);

fn spoke(spoke: usize, inward: bool) -> Origin {
    Origin::Spoke { spoke, inward }
}

fn gap_side((edge, gap): (usize, usize), after: bool) -> Origin {
    Origin::GapSide { edge, gap, after }
}

/// Pieces of a subdivided edge and their type: one `X^(d−1)` when delayed, else n copies.
pub(super) fn piece_type(e: &Edge) -> (usize, Edge) {
    match e.delay >= 2 {
        true => (
            1,
            Edge {
                delay: e.delay - 1,
                ..*e
            },
        ),
        false => (e.n as usize, *e),
    }
}

fn matches(p: &Pattern, e: &Edge) -> bool {
    match p {
        Pattern::Any => true,
        Pattern::Kind(k) => e.kind == *k,
        Pattern::Exact(x) => x == e,
    }
}

/// The spoke predicate on a junction `(kind, edge before, edge after)`.
fn is_spoke(items: &[SpokeItem], (kind, before, after): (JKind, Edge, Edge)) -> bool {
    items.iter().any(|item| match (item, kind) {
        (SpokeItem::Joint, JKind::Joint) | (SpokeItem::Gap, JKind::Gap) => true,
        (SpokeItem::Corner, JKind::Corner) => true,
        (SpokeItem::DelayedCorner, JKind::Corner) => before.delay >= 2 || after.delay >= 2,
        (SpokeItem::DelayedCornerNotB, JKind::Corner) => {
            let plain_b = |e: &Edge| e.kind == Kind::B && e.delay < 2;
            (before.delay >= 2 || after.delay >= 2) && !plain_b(&before) && !plain_b(&after)
        }
        (SpokeItem::CornerBetween(p, q), JKind::Corner) => {
            matches(p, &before) && matches(q, &after)
        }
        (SpokeItem::Joint | SpokeItem::Gap, _) => false,
        (
            SpokeItem::Corner
            | SpokeItem::DelayedCorner
            | SpokeItem::DelayedCornerNotB
            | SpokeItem::CornerBetween(..),
            _,
        ) => false,
    })
}

/// The start of the lexicographically least rotation (order B < C, then n, then delay); ties go
/// to the smallest start. Linear time (the two-candidate minimum-rotation scan: candidates `i`
/// and `j` are compared over `k` common elements; the loser cannot start a least rotation
/// anywhere in the `k + 1` positions it just passed, so it jumps past them; `i + j + k` grows by
/// at least 1 per step and stays below `3n`).
pub(super) fn least_rotation<T: Ord>(b: &[T]) -> usize {
    let n = b.len();
    let (mut i, mut j, mut k) = (0, 1, 0);
    while i < n && j < n && k < n {
        let (x, y) = (&b[(i + k) % n], &b[(j + k) % n]);
        match x.cmp(y) {
            std::cmp::Ordering::Equal => {
                k += 1;
                continue;
            }
            std::cmp::Ordering::Greater => i += k + 1,
            std::cmp::Ordering::Less => j += k + 1,
        }
        if i == j {
            j += 1;
        }
        k = 0;
    }
    i.min(j).min(n.saturating_sub(1))
}

fn canonical(raw: Vec<(Edge, Origin)>, delay: u32) -> Derived {
    let (mut boundary, mut origins): (Vec<Edge>, Vec<Origin>) = raw.into_iter().unzip();
    let r = least_rotation(&boundary);
    boundary.rotate_left(r);
    origins.rotate_left(r);
    (boundary, origins, delay)
}

/// One subdivision step of `face` (THEORY §3), with lacuna's origin conventions.
pub(super) fn subdivide(face: &Face) -> Result<(Vec<Derived>, Vec<Adjacency>), String> {
    let len = face.boundary.len();
    // Sub-edge m: its type, (edge, piece), and the junction after it.
    let mut pieces: Vec<SubEdge> = Vec::new();
    for (i, e) in face.boundary.iter().enumerate() {
        let (count, ty) = piece_type(e);
        for k in 0..count {
            let junction = match (k + 1 < count, e.kind) {
                (false, _) => (JKind::Corner, *e, face.boundary[(i + 1) % len]),
                (true, Kind::B) => (JKind::Joint, *e, *e),
                (true, Kind::C) => (JKind::Gap, *e, *e),
            };
            pieces.push((ty, (i, k), junction));
        }
    }
    let n = pieces.len();
    let is_gap = |m: usize| pieces[m].2 .0 == JKind::Gap;
    let piece = |m: usize| {
        let (ty, (edge, piece), _) = pieces[m];
        (ty, Origin::Piece { edge, piece })
    };
    let ec = |m: usize, after: bool| (face.params.ec, gap_side(pieces[m].1, after));
    if face.delay >= 2 {
        let mut raw = Vec::new();
        for m in 0..n {
            raw.push(piece(m));
            if is_gap(m) {
                raw.extend([ec(m, false), ec(m, true)]);
            }
        }
        return Ok((vec![canonical(raw, face.delay - 1)], Vec::new()));
    }
    let spokes: Vec<usize> = (0..n)
        .filter(|&m| is_spoke(&face.algorithm, pieces[m].2))
        .collect();
    let s = spokes.len();
    if s == 0 {
        return Err("the algorithm puts no spoke on this face".into());
    }
    let p = face.params;
    let mut subs = Vec::with_capacity(s);
    for k in 0..s {
        let (start, end) = (spokes[k], spokes[(k + 1) % s]);
        let run = if s == 1 { n } else { (end + n - start) % n };
        let mut raw = Vec::new();
        for step in 1..=run {
            let m = (start + step) % n;
            raw.push(piece(m));
            if step < run && is_gap(m) {
                raw.extend([ec(m, false), ec(m, true)]);
            }
        }
        raw.extend(is_gap(end).then(|| ec(end, false)));
        raw.push((p.ea, spoke((k + 1) % s, true)));
        raw.push((p.el, Origin::Lacuna { side: k }));
        raw.push((p.ea, spoke(k, false)));
        raw.extend(is_gap(start).then(|| ec(start, true)));
        subs.push(canonical(raw, 1));
    }
    let pos = |d: &Derived, o: Origin| d.1.iter().position(|x| *x == o).unwrap_or(0);
    let adj: Vec<Adjacency> = (0..s)
        .map(|k| (k, (k + 1) % s))
        .map(|(k, next)| Adjacency {
            first: (k, pos(&subs[k], spoke(next, true))),
            second: (next, pos(&subs[next], spoke(next, false))),
        })
        .collect();
    Ok((subs, adj))
}

/// What identifies a face type: boundary, E, delay and the algorithm as a set of items.
type FaceKey = (Vec<Edge>, Params, u32, BTreeSet<SpokeItem>);

fn key(f: &Face) -> FaceKey {
    let items = f.algorithm.iter().copied().collect();
    (f.boundary.clone(), f.params, f.delay, items)
}

/// Lacunas of one step in halves (THEORY §5): 2 for the centre (d = 1), n−1 per non-delayed `Cn`
/// (a big integer: the sum cannot wrap).
pub(super) fn contribution(f: &Face) -> BigUint {
    let gaps = f
        .boundary
        .iter()
        .filter(|e| e.kind == Kind::C && e.delay == 1);
    let centre = BigUint::from(2u32 * u32::from(f.delay == 1));
    gaps.fold(centre, |acc, e| acc + BigUint::from(e.n) - BigUint::one())
}

/// The number of sub-edges of a face (`n` per non-delayed edge, 1 per delayed edge), in u128:
/// a boundary has fewer than 2^64 edges of fewer than 2^32 pieces each, so the sum fits.
fn piece_count(f: &Face) -> u128 {
    f.boundary
        .iter()
        .map(|e| u128::try_from(piece_type(e).0).unwrap_or(u128::MAX))
        .fold(0u128, u128::saturating_add)
}

/// Checks the closure step against the claim's start faces; returns the report, the verdict
/// and the substitution read off it.
pub(super) fn check_closure(
    c: &ClosureStep,
    faces: &[Face],
) -> Result<(String, String, Substitution), String> {
    let nt = c.types.len();
    let mut index: HashMap<FaceKey, usize> = HashMap::with_capacity(nt);
    for (t, rule) in c.types.iter().enumerate() {
        let (f, p) = (&rule.face, rule.face.params);
        let edges_ok = f
            .boundary
            .iter()
            .chain([&p.ea, &p.el, &p.ec])
            .all(|e| e.n >= 2 && e.delay >= 1);
        if f.boundary.is_empty() || f.delay < 1 || f.algorithm.is_empty() || !edges_ok {
            return Err(format!(
                "type {t}: empty boundary or algorithm, n < 2 or a delay 0"
            ));
        }
        if least_rotation(&f.boundary) != 0 {
            return Err(format!(
                "type {t}: the boundary is not in canonical rotation"
            ));
        }
        // The derived sub-faces list every sub-edge once as an origin: a face with more
        // sub-edges than the certificate lists origins cannot match, and is refused before
        // anything of its size is built.
        let listed: u128 = rule.subfaces.iter().map(|s| s.origins.len() as u128).sum();
        if piece_count(f) > listed {
            return Err(format!(
                "type {t}: its edges have {} sub-edges, more than the {listed} origins listed",
                piece_count(f)
            ));
        }
        if let Some(u) = index.insert(key(f), t) {
            return Err(format!("types {u} and {t} are the same face type"));
        }
    }
    if faces.is_empty() {
        return Err("the claim has no start face".into());
    }
    let mut start: BTreeMap<usize, BigUint> = BTreeMap::new();
    let mut firsts = Vec::new();
    for (i, f) in faces.iter().enumerate() {
        match index.get(&key(f)) {
            Some(&t) if c.types[t].face == *f => {
                let count = start.entry(t).or_insert_with(BigUint::zero);
                if count.is_zero() {
                    firsts.push(t);
                }
                *count += 1u32;
            }
            _ => {
                return Err(format!(
                    "start face {i} of the claim is not a listed type (in canonical form)"
                ))
            }
        }
    }
    let children: Vec<Vec<usize>> = c
        .types
        .iter()
        .map(|r| r.subfaces.iter().map(|s| s.type_index).collect())
        .collect();
    breadth_first_order(&firsts, &children, "face")?;
    let mut matrix = Vec::with_capacity(nt);
    for (t, rule) in c.types.iter().enumerate() {
        let (subs, adj) = subdivide(&rule.face).map_err(|e| format!("type {t}: {e}"))?;
        if subs.len() != rule.subfaces.len() {
            return Err(format!(
                "type {t}: {} sub-faces listed, {} derived",
                rule.subfaces.len(),
                subs.len()
            ));
        }
        let mut row: BTreeMap<usize, BigUint> = BTreeMap::new();
        for (k, ((boundary, origins, delay), sf)) in
            subs.into_iter().zip(&rule.subfaces).enumerate()
        {
            let want = Face {
                boundary,
                delay,
                ..rule.face.clone()
            };
            match c.types.get(sf.type_index) {
                Some(target) if key(&target.face) == key(&want) => {}
                _ => {
                    return Err(format!(
                        "type {t} sub-face {k}: type {} is not the derived face",
                        sf.type_index
                    ))
                }
            }
            if sf.origins != origins {
                return Err(format!(
                    "type {t} sub-face {k}: origins differ from the derived ones"
                ));
            }
            *row.entry(sf.type_index).or_insert_with(BigUint::zero) += 1u32;
        }
        if adj != rule.adjacencies {
            return Err(format!(
                "type {t}: adjacencies differ from the derived ones"
            ));
        }
        if contribution(&rule.face) != BigUint::from(rule.contribution_halves) {
            return Err(format!(
                "type {t}: contribution is not the one of THEORY §5"
            ));
        }
        identities(c, t).map_err(|e| format!("type {t}: {e}"))?;
        matrix.push(row);
    }
    let subs: usize = c.types.iter().map(|r| r.subfaces.len()).sum();
    let msg = format!(
        "{} closed under subdivision, the claim's {} among them: {subs} sub-faces re-derived \
         (THEORY §3), every incidence identity and contribution holds",
        super::counted(nt, "face type", "face types"),
        super::counted(faces.len(), "start face", "start faces")
    );
    let verdict = format!(
        "closure: {}, closed under subdivision",
        super::counted(nt, "face type", "face types")
    );
    let contributions = c
        .types
        .iter()
        .map(|r| BigUint::from(r.contribution_halves))
        .collect();
    Ok((
        msg,
        verdict,
        Substitution {
            matrix,
            contributions,
            start,
            unit: 2,
        },
    ))
}

/// Checks that the listed types are exactly the closure of the start types, numbered in the
/// order of the canonical breadth-first closure: the distinct start types first, in the claim's
/// order, then every type the first time a listed child names it, parents in index order and
/// children in listed order. A type no start reaches, or one numbered out of that order, is
/// refused: the closure then cannot hold a family the claim never produces (whose types would
/// add constraints, counts and classes to the claim's), and two accepted certificates of one
/// claim number their types alike. Linear in the number of children.
pub(super) fn breadth_first_order(
    starts: &[usize],
    children: &[Vec<usize>],
    what: &str,
) -> Result<(), String> {
    let n = children.len();
    let mut next = 0usize;
    for &s in starts {
        if s != next {
            return Err(format!(
                "the claim's start {what}s must be types 0, 1, … in the claim's order \
                 (the canonical breadth-first closure); a start is type {s}, expected {next}"
            ));
        }
        next += 1;
    }
    let mut t = 0usize;
    while t < next {
        for &ch in &children[t] {
            match ch.cmp(&next) {
                std::cmp::Ordering::Less => {}
                std::cmp::Ordering::Equal if ch < n => next += 1,
                _ => {
                    return Err(format!(
                        "type {t} names child type {ch} where the canonical breadth-first \
                         closure numbers its next new type {next}"
                    ))
                }
            }
        }
        t += 1;
    }
    match next == n {
        true => Ok(()),
        false => Err(format!(
            "types {next} to {} are not reached from the claim's start {what}s (the canonical \
             breadth-first closure lists only what its claim produces)",
            n - 1
        )),
    }
}

/// The incidence identities of type `t`, on the certificate's own data: every edge has the type
/// its origin demands; the origins are each sub-edge, each gap side, each spoke side (inward and
/// outward) and each lacuna side exactly once; adjacencies pair the two sides of every spoke.
fn identities(c: &ClosureStep, t: usize) -> Result<(), String> {
    let (rule, f) = (&c.types[t], &c.types[t].face);
    let s = if f.delay == 1 { rule.subfaces.len() } else { 0 };
    if f.delay >= 2 && (rule.subfaces.len() != 1 || !rule.adjacencies.is_empty()) {
        return Err("a delayed face has exactly one sub-face and no adjacency".into());
    }
    let mut expected: Vec<Origin> = Vec::new();
    for (edge, e) in f.boundary.iter().enumerate() {
        let (count, _) = piece_type(e);
        expected.extend((0..count).map(|piece| Origin::Piece { edge, piece }));
        for gap in (0..count - 1).filter(|_| e.kind == Kind::C && e.delay == 1) {
            expected.extend([gap_side((edge, gap), false), gap_side((edge, gap), true)]);
        }
    }
    for j in 0..s {
        expected.extend([spoke(j, true), spoke(j, false), Origin::Lacuna { side: j }]);
    }
    let mut seen: Vec<Origin> = Vec::new();
    for (k, sf) in rule.subfaces.iter().enumerate() {
        let sub = &c.types[sf.type_index].face;
        let delay = if f.delay >= 2 { f.delay - 1 } else { 1 };
        if sub.delay != delay || sub.params != f.params || sub.boundary.len() != sf.origins.len() {
            return Err(format!("sub-face {k} has the wrong delay, E or length"));
        }
        for (pos, (o, ty)) in sf.origins.iter().zip(&sub.boundary).enumerate() {
            let want = match *o {
                Origin::Piece { edge, piece } => match f.boundary.get(edge).map(piece_type) {
                    Some((count, ty)) if piece < count => ty,
                    _ => return Err(format!("sub-face {k} position {pos}: no such piece")),
                },
                Origin::Spoke { .. } => f.params.ea,
                Origin::Lacuna { .. } => f.params.el,
                Origin::GapSide { .. } => f.params.ec,
            };
            if want != *ty {
                return Err(format!(
                    "sub-face {k} position {pos}: edge type differs from its origin"
                ));
            }
        }
        seen.extend(&sf.origins);
    }
    expected.sort();
    seen.sort();
    if seen != expected {
        return Err(
            "the origins are not each sub-edge, gap side, spoke side and lacuna side once".into(),
        );
    }
    let origin = |(f, p): (usize, usize)| rule.subfaces.get(f).and_then(|x| x.origins.get(p));
    let mut paired = BTreeSet::new();
    for a in &rule.adjacencies {
        match (origin(a.first), origin(a.second)) {
            (
                Some(&Origin::Spoke {
                    spoke: j,
                    inward: true,
                }),
                Some(&y),
            ) if y == spoke(j, false) && paired.insert(j) => {}
            _ => {
                return Err(format!(
                    "adjacency {a:?} does not pair the two sides of a spoke"
                ))
            }
        }
    }
    match paired.len() == s {
        true => Ok(()),
        false => Err(format!(
            "{} of {s} spokes paired by adjacencies",
            paired.len()
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn repeated_pairs_add_up_exactly() {
        // (0, 2^64 − 1) twice and (0, 7): 2^65 + 5, not the wrapped 5.
        let got = merge_pairs(&[(0, u64::MAX), (0, u64::MAX), (0, 7)], 1, "row").unwrap();
        let want = (BigUint::one() << 65u32) + BigUint::from(5u32);
        assert_eq!(got[&0], want);
        assert!(merge_pairs(&[(1, 1)], 1, "row").is_err());
        // A multiplicity of 2^64 + 6 written as (0, 2^64 − 1), (0, 7) is not 6.
        let got = merge_pairs(&[(0, u64::MAX), (0, 7)], 1, "start").unwrap();
        assert_eq!(got[&0], (BigUint::one() << 64u32) + BigUint::from(6u32));
    }

    #[test]
    fn least_rotation_is_the_smallest_start_of_the_least_rotation() {
        // Against the quadratic definition on every word of length ≤ 7 over {0, 1, 2}.
        let slow = |b: &[u8]| -> usize {
            let rot = |r: usize| -> Vec<u8> { b[r..].iter().chain(&b[..r]).copied().collect() };
            (0..b.len()).min_by_key(|&r| (rot(r), r)).unwrap_or(0)
        };
        for len in 1..=7u32 {
            for code in 0..3usize.pow(len) {
                let w: Vec<u8> = (0..len)
                    .map(|i| ((code / 3usize.pow(i)) % 3) as u8)
                    .collect();
                assert_eq!(least_rotation(&w), slow(&w), "{w:?}");
            }
        }
        // Linear: a million equal edges take a moment, not 10^12 comparisons.
        let long = vec![0u8; 1_000_000];
        assert_eq!(least_rotation(&long), 0);
    }
}
