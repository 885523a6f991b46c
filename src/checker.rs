//! The independent checker: re-verifies a [`Certificate`] without trusting lacuna's code.
//!
//! It may use only the `certificate` module (plain data), std, the num crates and serde_json; a test
//! (`tests/certificates.rs`) reads this file and fails on any other path into lacuna. Everything
//! it needs is re-implemented here, small: the subdivision of a face (SPEC §3), exact linear
//! checks, elimination modulo primes, strongly connected classes and periods, Sturm sequences,
//! arithmetic in Q[x]/(p) and interval evaluation. What each step proves is documented on
//! [`Step`] and in `docs/CERTIFICATES.md`.

use crate::certificate::{
    Adjacency, Certificate, ClassClaim, ClosureStep, ConflictStep, Edge, Face, Kind, LimitProof,
    Origin, Pattern, RatioClaim, RatioStep, Row, SolutionStep, SpokeItem, Step, FORMAT, VERSION,
};
use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};
use std::collections::{BTreeMap, BTreeSet, VecDeque};

/// The verdict on one step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// The step's claim is proved.
    Proved,
    /// The step is well-formed but its claim is outside what certificate v1 can prove.
    NotCovered,
    /// The step does not prove its claim.
    Failed,
}

/// What the checker concluded about one step.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StepReport {
    /// The step's name (`closure`, `solution-space`, `inconsistent`, `limit-ratio`, or `header`).
    pub step: String,
    /// The verdict.
    pub outcome: Outcome,
    /// What was proved, or why it failed, naming the step.
    pub message: String,
}

/// The checker's report: one entry per step.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CheckReport {
    /// The steps, in certificate order.
    pub steps: Vec<StepReport>,
}

impl CheckReport {
    /// True when every step is proved (the only outcome `lacuna check` accepts).
    pub fn all_proved(&self) -> bool {
        !self.steps.is_empty() && self.steps.iter().all(|s| s.outcome == Outcome::Proved)
    }

    /// True when some step failed.
    pub fn failed(&self) -> bool {
        self.steps.iter().any(|s| s.outcome == Outcome::Failed)
    }

    /// The report for one step name (the first with that name).
    pub fn step(&self, name: &str) -> Option<&StepReport> {
        self.steps.iter().find(|s| s.step == name)
    }

    /// One line per step.
    pub fn to_text(&self) -> String {
        let mut o = String::new();
        for s in &self.steps {
            let v = match s.outcome {
                Outcome::Proved => "proved",
                Outcome::NotCovered => "NOT CERTIFIED",
                Outcome::Failed => "FAILED",
            };
            o += &format!("{v:>13}  {}\n", s.message);
        }
        o
    }

    /// The report as JSON.
    pub fn to_json(&self) -> serde_json::Value {
        let steps: Vec<serde_json::Value> = self
            .steps
            .iter()
            .map(|s| {
                let outcome = match s.outcome {
                    Outcome::Proved => "proved",
                    Outcome::NotCovered => "not-covered",
                    Outcome::Failed => "failed",
                };
                serde_json::json!({"step": s.step, "outcome": outcome, "message": s.message})
            })
            .collect();
        serde_json::json!({"all_proved": self.all_proved(), "steps": steps})
    }
}

type Q = BigRational;
type Checked = Result<String, String>;
/// A parsed row: `(unknown, coefficient)` terms and the right-hand side.
type Equation = (Vec<(usize, Q)>, Q);

/// Checks a certificate given as JSON text (a parse error is a failed `header`).
pub fn check_json(text: &str) -> CheckReport {
    match Certificate::from_json(text) {
        Ok(c) => check(&c),
        Err(e) => CheckReport {
            steps: vec![StepReport {
                step: "header".into(),
                outcome: Outcome::Failed,
                message: format!("header: not a certificate: {e}"),
            }],
        },
    }
}

/// Checks every step of a certificate.
pub fn check(cert: &Certificate) -> CheckReport {
    let header_fail = |m: String| CheckReport {
        steps: vec![StepReport {
            step: "header".into(),
            outcome: Outcome::Failed,
            message: format!("header: {m}"),
        }],
    };
    if cert.format != FORMAT || cert.version != VERSION {
        return header_fail(format!(
            "format `{}` version {} (this checker reads `{FORMAT}` version {VERSION})",
            cert.format, cert.version
        ));
    }
    if cert.steps.is_empty() {
        return header_fail("the certificate has no step".into());
    }
    let mut steps = Vec::new();
    let mut closure: Option<Substitution> = None;
    for (i, step) in cert.steps.iter().enumerate() {
        let name = step.name();
        let (outcome, result) = match step {
            Step::Closure(c) => match check_closure(c) {
                Ok((msg, sub)) => {
                    closure = Some(sub);
                    (Outcome::Proved, Ok(msg))
                }
                Err(e) => (Outcome::Failed, Err(e)),
            },
            Step::SolutionSpace(s) => (Outcome::Proved, check_solution(s)),
            Step::Inconsistent(c) => (Outcome::Proved, check_conflict(c)),
            Step::LimitRatio(r) => match check_ratio(r, closure.as_ref()) {
                Ok((covered, msg)) if !covered => (Outcome::NotCovered, Ok(msg)),
                other => (Outcome::Proved, other.map(|(_, m)| m)),
            },
        };
        let (outcome, detail) = match result {
            Ok(m) => (outcome, m),
            Err(m) => (Outcome::Failed, m),
        };
        steps.push(StepReport {
            step: name.into(),
            outcome,
            message: format!("step {i} ({name}): {detail}"),
        });
    }
    CheckReport { steps }
}

// ---------------------------------------------------------------------------------------------
// Step 1: the closure, by re-deriving every subdivision (SPEC §3).
// ---------------------------------------------------------------------------------------------

/// The substitution read off a checked closure: matrix rows, contributions, start counts.
struct Substitution {
    matrix: Vec<BTreeMap<usize, u64>>,
    contributions: Vec<u64>,
    start: BTreeMap<usize, u64>,
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
type Derived = (Vec<Edge>, Vec<Origin>, u32);

fn spoke(spoke: usize, inward: bool) -> Origin {
    Origin::Spoke { spoke, inward }
}

fn gap_side((edge, gap): (usize, usize), after: bool) -> Origin {
    Origin::GapSide { edge, gap, after }
}

/// Pieces of a subdivided edge and their type: one `X^(d−1)` when delayed, else n copies.
fn piece_type(e: &Edge) -> (usize, Edge) {
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
        (SpokeItem::CornerBetween(p, q), JKind::Corner) => {
            matches(p, &before) && matches(q, &after)
        }
        (SpokeItem::Joint | SpokeItem::Gap, _) => false,
        (SpokeItem::Corner | SpokeItem::DelayedCorner | SpokeItem::CornerBetween(..), _) => false,
    })
}

/// The start of the lexicographically least rotation (order B < C, then n, then delay); ties go
/// to the smallest start. Quadratic and plain on purpose.
fn least_rotation(b: &[Edge]) -> usize {
    let rot = |r: usize| b.iter().cycle().skip(r).take(b.len());
    (1..b.len()).fold(0, |best, r| if rot(r).lt(rot(best)) { r } else { best })
}

fn canonical(raw: Vec<(Edge, Origin)>, delay: u32) -> Derived {
    let (mut boundary, mut origins): (Vec<Edge>, Vec<Origin>) = raw.into_iter().unzip();
    let r = least_rotation(&boundary);
    boundary.rotate_left(r);
    origins.rotate_left(r);
    (boundary, origins, delay)
}

/// One subdivision step of `face` (SPEC §3), with lacuna's origin conventions.
fn subdivide(face: &Face) -> Result<(Vec<Derived>, Vec<Adjacency>), String> {
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

fn same_face(a: &Face, b: &Face) -> bool {
    let set =
        |f: &Face| -> BTreeSet<String> { f.algorithm.iter().map(|i| format!("{i:?}")).collect() };
    a.boundary == b.boundary && a.params == b.params && a.delay == b.delay && set(a) == set(b)
}

/// Lacunas of one step in halves (SPEC §5): 2 for the centre (d = 1), n−1 per non-delayed `Cn`.
fn contribution(f: &Face) -> u64 {
    let gaps = f
        .boundary
        .iter()
        .filter(|e| e.kind == Kind::C && e.delay == 1);
    2 * u64::from(f.delay == 1) + gaps.map(|e| u64::from(e.n) - 1).sum::<u64>()
}

fn check_closure(c: &ClosureStep) -> Result<(String, Substitution), String> {
    let nt = c.types.len();
    if c.start.is_empty() || c.start.iter().any(|&s| s >= nt) {
        return Err("the start types are missing or out of range".into());
    }
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
        if let Some(u) = (0..t).find(|&u| same_face(&c.types[u].face, f)) {
            return Err(format!("types {u} and {t} are the same face type"));
        }
    }
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
        let mut row = BTreeMap::new();
        for (k, ((boundary, origins, delay), sf)) in
            subs.into_iter().zip(&rule.subfaces).enumerate()
        {
            let want = Face {
                boundary,
                delay,
                ..rule.face.clone()
            };
            match c.types.get(sf.type_index) {
                Some(target) if same_face(&target.face, &want) => {}
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
            *row.entry(sf.type_index).or_insert(0) += 1;
        }
        if adj != rule.adjacencies {
            return Err(format!(
                "type {t}: adjacencies differ from the derived ones"
            ));
        }
        if contribution(&rule.face) != rule.contribution_halves {
            return Err(format!("type {t}: contribution is not the one of SPEC §5"));
        }
        identities(c, t).map_err(|e| format!("type {t}: {e}"))?;
        matrix.push(row);
    }
    let mut start = BTreeMap::new();
    c.start
        .iter()
        .for_each(|&s| *start.entry(s).or_insert(0) += 1);
    let subs: usize = c.types.iter().map(|r| r.subfaces.len()).sum();
    let msg = format!(
        "{nt} face type(s) closed under subdivision: {subs} sub-faces re-derived (SPEC §3), \
         every incidence identity and contribution holds"
    );
    let contributions = c.types.iter().map(|r| r.contribution_halves).collect();
    Ok((
        msg,
        Substitution {
            matrix,
            contributions,
            start,
        },
    ))
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

// ---------------------------------------------------------------------------------------------
// Steps 2 and 3: linear systems.
// ---------------------------------------------------------------------------------------------

fn rat(s: &str) -> Result<Q, String> {
    s.parse::<Q>()
        .map_err(|_| format!("`{s}` is not a rational"))
}

fn parse_rows(rows: &[Row], unknowns: usize) -> Result<Vec<Equation>, String> {
    rows.iter()
        .enumerate()
        .map(|(i, r)| {
            let terms = r
                .terms
                .iter()
                .map(|(v, c)| match *v < unknowns {
                    true => Ok((*v, rat(c)?)),
                    false => Err(format!("row {i}: unknown {v} out of range")),
                })
                .collect::<Result<Vec<_>, String>>()?;
            Ok((terms, rat(&r.rhs)?))
        })
        .collect()
}

/// A sparse vector with strictly increasing, in-range indices, as a map.
fn sparse(v: &[(usize, String)], n: usize, what: &str) -> Result<BTreeMap<usize, Q>, String> {
    if v.windows(2).any(|w| w[0].0 >= w[1].0) || v.last().is_some_and(|x| x.0 >= n) {
        return Err(format!("{what}: indices not increasing or out of range"));
    }
    v.iter().map(|(i, s)| Ok((*i, rat(s)?))).collect()
}

fn dot(terms: &[(usize, Q)], x: &BTreeMap<usize, Q>) -> Q {
    terms
        .iter()
        .filter_map(|(v, c)| x.get(v).map(|y| c * y))
        .sum()
}

fn check_solution(s: &SolutionStep) -> Checked {
    let n = s.system.unknowns;
    let rows = parse_rows(&s.system.rows, n)?;
    let part = sparse(&s.particular, n, "particular solution")?;
    if let Some(i) = rows.iter().position(|(t, rhs)| dot(t, &part) != *rhs) {
        return Err(format!("the particular solution fails row {i}"));
    }
    if s.free.windows(2).any(|w| w[0] >= w[1]) || s.free.last().is_some_and(|&f| f >= n) {
        return Err("free unknowns not increasing or out of range".into());
    }
    if s.basis.len() != s.free.len() {
        return Err(format!(
            "{} basis vectors for {} free unknowns",
            s.basis.len(),
            s.free.len()
        ));
    }
    let mut rows_of: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (i, (t, _)) in rows.iter().enumerate() {
        t.iter().for_each(|(v, _)| rows_of[*v].push(i));
    }
    for (k, b) in s.basis.iter().enumerate() {
        let b = sparse(b, n, &format!("basis vector {k}"))?;
        for (j, f) in s.free.iter().enumerate() {
            let want = if j == k { Q::one() } else { Q::zero() };
            if b.get(f).cloned().unwrap_or_else(Q::zero) != want {
                return Err(format!(
                    "basis vector {k} is not {want} at free unknown {f}"
                ));
            }
        }
        let touched: BTreeSet<usize> = b.keys().flat_map(|v| rows_of[*v].iter().copied()).collect();
        if let Some(i) = touched
            .into_iter()
            .find(|&i| !dot(&rows[i].0, &b).is_zero())
        {
            return Err(format!("basis vector {k} fails homogeneous row {i}"));
        }
    }
    let dof = s.free.len();
    if s.rank != s.pivots.len() || s.dof != dof || s.rank + dof != n {
        return Err(format!(
            "rank {} (|pivots| = {}) + dof {} (|free| = {dof}) ≠ {n} unknowns",
            s.rank,
            s.pivots.len(),
            s.dof
        ));
    }
    let p = nonsingular_minor(&rows, &s.pivots, n)?;
    Ok(format!(
        "{} rows, {n} unknowns: rank {} (pivot minor nonsingular mod {p}), {dof} degrees of \
         freedom; the solution set is exactly particular + span(basis)",
        rows.len(),
        s.rank
    ))
}

/// Shows the pivot minor nonsingular: eliminating its rows in the listed order modulo a prime
/// gives an upper-triangular matrix with nonzero diagonal. Returns the prime that worked.
fn nonsingular_minor(
    rows: &[Equation],
    pivots: &[(usize, usize)],
    n: usize,
) -> Result<u64, String> {
    let mut col_pos = vec![usize::MAX; n];
    let mut used = BTreeSet::new();
    for (k, &(r, c)) in pivots.iter().enumerate() {
        if r >= rows.len() || c >= n || !used.insert(r) || col_pos[c] != usize::MAX {
            return Err(format!("pivot {k} ({r}, {c}) is repeated or out of range"));
        }
        col_pos[c] = k;
    }
    let mut why = String::from("no prime tried");
    'prime: for p in [(1u64 << 61) - 1, 1_000_000_007, 998_244_353, 2_147_483_647] {
        let mul = |a: u64, b: u64| ((u128::from(a) * u128::from(b)) % u128::from(p)) as u64;
        let inv = |a: u64| {
            let (mut r, mut b, mut e) = (1u64, a, p - 2);
            while e > 0 {
                if e & 1 == 1 {
                    r = mul(r, b);
                }
                b = mul(b, b);
                e >>= 1;
            }
            r
        };
        let modp = |z: &BigInt| z.mod_floor(&BigInt::from(p)).to_u64().unwrap_or(0);
        let mut done: Vec<BTreeMap<usize, u64>> = Vec::with_capacity(pivots.len());
        for (k, &(r, _)) in pivots.iter().enumerate() {
            let mut row: BTreeMap<usize, u64> = BTreeMap::new();
            for (v, c) in &rows[r].0 {
                if col_pos[*v] == usize::MAX {
                    continue;
                }
                let d = modp(c.denom());
                if d == 0 {
                    why = format!("a denominator is divisible by {p}");
                    continue 'prime;
                }
                let e = row.entry(col_pos[*v]).or_insert(0);
                *e = (*e + mul(modp(c.numer()), inv(d))) % p;
            }
            row.retain(|_, x| *x != 0);
            while let Some((&j, &x)) = row.first_key_value() {
                if j >= k {
                    break;
                }
                for (&l, &y) in &done[j] {
                    let e = row.entry(l).or_insert(0);
                    *e = (*e + p - mul(x, y)) % p;
                }
                row.retain(|_, x| *x != 0);
            }
            let Some(&d) = row.get(&k) else {
                why = format!("pivot {k} vanishes after elimination mod {p}");
                continue 'prime;
            };
            let di = inv(d);
            done.push(row.into_iter().map(|(l, x)| (l, mul(x, di))).collect());
        }
        return Ok(p);
    }
    Err(format!("the pivot minor is not shown nonsingular: {why}"))
}

fn check_conflict(c: &ConflictStep) -> Checked {
    let rows = parse_rows(&c.system.rows, c.system.unknowns)?;
    let mut sum: BTreeMap<usize, Q> = BTreeMap::new();
    let mut rhs = Q::zero();
    let mut used = BTreeSet::new();
    for (i, m) in &c.multipliers {
        let m = rat(m)?;
        let Some((terms, b)) = rows.get(*i).filter(|_| used.insert(*i)) else {
            return Err(format!("multiplier for row {i}: repeated or out of range"));
        };
        for (v, a) in terms {
            *sum.entry(*v).or_insert_with(Q::zero) += &m * a;
        }
        rhs += &m * b;
    }
    if let Some((v, a)) = sum.iter().find(|(_, a)| !a.is_zero()) {
        return Err(format!("the combination leaves {a}·x{v}"));
    }
    if rhs != rat(&c.constant)? || rhs.is_zero() {
        return Err(format!(
            "the combination gives 0 = {rhs}, the certificate claims {}",
            c.constant
        ));
    }
    Ok(format!(
        "{} of {} rows combine to 0 = {rhs}: no solution",
        c.multipliers.len(),
        rows.len()
    ))
}

// ---------------------------------------------------------------------------------------------
// Step 4: the limit ratio.
// ---------------------------------------------------------------------------------------------

/// Classes reached from `start` (members ascending, ordered by smallest member) with periods.
fn classes(m: &[BTreeMap<usize, u64>], start: &[usize]) -> Vec<ClassClaim> {
    let n = m.len();
    let reach = |from: usize| {
        let mut seen = vec![false; n];
        let mut queue = VecDeque::from([from]);
        seen[from] = true;
        while let Some(t) = queue.pop_front() {
            for &s in m[t].keys() {
                if !std::mem::replace(&mut seen[s], true) {
                    queue.push_back(s);
                }
            }
        }
        seen
    };
    let mut reached = vec![false; n];
    start.iter().for_each(|&s| {
        reach(s)
            .iter()
            .enumerate()
            .for_each(|(t, &r)| reached[t] |= r)
    });
    let from: Vec<Vec<bool>> = (0..n)
        .map(|t| if reached[t] { reach(t) } else { vec![] })
        .collect();
    let mut out: Vec<ClassClaim> = Vec::new();
    let mut placed = vec![false; n];
    for t in (0..n).filter(|&t| reached[t]) {
        if placed[t] {
            continue;
        }
        let members: Vec<usize> = (t..n)
            .filter(|&s| reached[s] && from[t][s] && from[s][t])
            .collect();
        members.iter().for_each(|&s| placed[s] = true);
        // Period: gcd of level(u) + 1 − level(v) over arcs inside the class (BFS levels).
        let inside = |s: &usize| members.binary_search(s).is_ok();
        let mut level: BTreeMap<usize, i64> = BTreeMap::from([(t, 0)]);
        let mut queue = VecDeque::from([t]);
        let mut g: i64 = 0;
        while let Some(u) = queue.pop_front() {
            for v in m[u].keys().filter(|v| inside(v)) {
                let lu = level[&u];
                match level.get(v) {
                    Some(&lv) => g = g.gcd(&(lu + 1 - lv)),
                    None => {
                        level.insert(*v, lu + 1);
                        queue.push_back(*v);
                    }
                }
            }
        }
        let cyclic = members.len() > 1 || m[t].contains_key(&t);
        out.push(ClassClaim {
            members,
            period: cyclic.then_some(g.unsigned_abs()),
        });
    }
    out
}

/// Polynomials over Q, constant term first, without trailing zeros.
type P = Vec<Q>;

fn trim(mut p: P) -> P {
    while p.last().is_some_and(Zero::is_zero) {
        p.pop();
    }
    p
}

fn eval(p: &[Q], x: &Q) -> Q {
    p.iter().rev().fold(Q::zero(), |acc, c| acc * x + c)
}

fn rem(a: &[Q], d: &[Q]) -> P {
    let mut r = trim(a.to_vec());
    let lead = d.last().expect("divisor is nonzero");
    while r.len() >= d.len() {
        let q = r.last().expect("nonzero") / lead;
        let shift = r.len() - d.len();
        for (i, c) in d.iter().enumerate() {
            r[shift + i] -= &q * c;
        }
        r = trim(r);
    }
    r
}

fn mul(a: &[Q], b: &[Q]) -> P {
    let mut c = vec![Q::zero(); (a.len() + b.len()).saturating_sub(1)];
    for (i, x) in a.iter().enumerate() {
        for (j, y) in b.iter().enumerate() {
            c[i + j] += x * y;
        }
    }
    trim(c)
}

fn add(a: &[Q], b: &[Q]) -> P {
    let mut c = vec![Q::zero(); a.len().max(b.len())];
    for (i, x) in a.iter().enumerate() {
        c[i] += x;
    }
    for (i, x) in b.iter().enumerate() {
        c[i] += x;
    }
    trim(c)
}

fn sign_changes(chain: &[P], x: &Q) -> usize {
    let signs: Vec<bool> = chain
        .iter()
        .map(|p| eval(p, x))
        .filter(|v| !v.is_zero())
        .map(|v| v.is_positive())
        .collect();
    signs.windows(2).filter(|w| w[0] != w[1]).count()
}

/// ρ: the only root of `p` in `[lo, hi]`, with bisection for sign decisions.
struct Root {
    p: P,
    lo: Q,
    hi: Q,
}

impl Root {
    /// Confirms that `[lo, hi]` isolates exactly one root of `p` (Sturm, `p` squarefree).
    fn isolate(poly: &[String], lo: &str, hi: &str) -> Result<Root, String> {
        let p = trim(
            poly.iter()
                .map(|c| c.parse::<BigInt>().map(Q::from_integer))
                .collect::<Result<_, _>>()
                .map_err(|_| "ρ's polynomial has a non-integer coefficient".to_string())?,
        );
        let (lo, hi) = (rat(lo)?, rat(hi)?);
        if p.len() < 2 {
            return Err("ρ's polynomial is constant".into());
        }
        if p.len() == 2 {
            let root = -&p[0] / &p[1];
            return match lo == root && hi == root {
                true => Ok(Root { p, lo, hi }),
                false => Err(format!(
                    "the interval [{lo}, {hi}] is not the rational root {root}"
                )),
            };
        }
        if lo >= hi || eval(&p, &lo).is_zero() || eval(&p, &hi).is_zero() {
            return Err(format!("[{lo}, {hi}] is empty or ends at a root"));
        }
        let mut chain = vec![
            p.clone(),
            trim(
                (1..p.len())
                    .map(|i| &p[i] * Q::from_integer(i.into()))
                    .collect(),
            ),
        ];
        while chain.last().is_some_and(|q| q.len() > 1) {
            let r = rem(&chain[chain.len() - 2], &chain[chain.len() - 1]);
            if r.is_empty() {
                return Err("ρ's polynomial is not squarefree".into());
            }
            chain.push(r.into_iter().map(|c| -c).collect());
        }
        match sign_changes(&chain, &lo) - sign_changes(&chain, &hi) {
            1 => Ok(Root { p, lo, hi }),
            k => Err(format!(
                "[{lo}, {hi}] holds {k} roots of ρ's polynomial, not 1"
            )),
        }
    }

    /// The sign of `q(ρ)`, decided by interval evaluation and bisection (−1, 0, 1); `None` when
    /// undecided after many bisections.
    fn sign(&self, q: &[Q]) -> Option<i32> {
        let q = rem(q, &self.p);
        if q.is_empty() {
            return Some(0);
        }
        let (mut lo, mut hi) = (self.lo.clone(), self.hi.clone());
        let s_lo = eval(&self.p, &lo).is_positive();
        for _ in 0..4000 {
            if lo == hi || eval(&self.p, &lo).is_zero() {
                let v = eval(&q, &lo);
                return Some(if v.is_zero() {
                    0
                } else if v.is_positive() {
                    1
                } else {
                    -1
                });
            }
            // Interval Horner: [a, b] ∋ q(x) for every x in [lo, hi].
            let (mut a, mut b) = (Q::zero(), Q::zero());
            for c in q.iter().rev() {
                let ps = [&a * &lo, &a * &hi, &b * &lo, &b * &hi];
                a = ps.iter().min().expect("four").clone() + c;
                b = ps.iter().max().expect("four").clone() + c;
            }
            if a.is_positive() {
                return Some(1);
            }
            if b.is_negative() {
                return Some(-1);
            }
            let mid = (&lo + &hi) / Q::from_integer(2.into());
            let pm = eval(&self.p, &mid);
            if pm.is_zero() {
                (lo, hi) = (mid.clone(), mid);
            } else if pm.is_positive() == s_lo {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        None
    }
}

fn check_ratio(r: &RatioStep, closure: Option<&Substitution>) -> Result<(bool, String), String> {
    let n = r.matrix.len();
    if r.contribution_halves.len() != n {
        return Err(format!(
            "{} contributions for {n} types",
            r.contribution_halves.len()
        ));
    }
    let mut m: Vec<BTreeMap<usize, u64>> = vec![BTreeMap::new(); n];
    for (t, row) in r.matrix.iter().enumerate() {
        for &(s, k) in row {
            if s >= n {
                return Err(format!("matrix row {t}: type {s} out of range"));
            }
            if k > 0 {
                *m[t].entry(s).or_insert(0) += k;
            }
        }
    }
    let mut start: BTreeMap<usize, u64> = BTreeMap::new();
    for &(t, k) in &r.start {
        if t >= n || k == 0 {
            return Err(format!("start ({t}, {k}) is out of range or empty"));
        }
        *start.entry(t).or_insert(0) += k;
    }
    if start.is_empty() {
        return Err("no start type".into());
    }
    let tied = match closure {
        Some(c)
            if c.matrix == m && c.contributions == r.contribution_halves && c.start == start =>
        {
            "the closure's substitution"
        }
        Some(_) => {
            return Err("matrix, contributions or start differ from the closure step".into())
        }
        None => "the given substitution (no closure step to tie it to)",
    };
    let start_types: Vec<usize> = start.keys().copied().collect();
    let cls = classes(&m, &start_types);
    if cls != r.classes {
        return Err(
            "the classes or periods differ from the checker's own (BFS, gcd of levels)".into(),
        );
    }
    let proof = match &r.claim {
        RatioClaim::NotCovered { reason, verdict } => {
            return Ok((
                false,
                format!(
                "{} class(es) and their periods re-derived for {tied}; the limit is NOT certified \
                 (outside certificate v1: {reason}); lacuna's uncertified verdict: {verdict}",
                cls.len()
            ),
            ))
        }
        RatioClaim::Limit(p) => p,
    };
    let verdict = check_limit(&m, &r.contribution_halves, &cls, proof)?;
    Ok((
        true,
        format!("{} class(es) re-derived for {tied}; {verdict}", cls.len()),
    ))
}

fn check_limit(
    m: &[BTreeMap<usize, u64>],
    c: &[u64],
    cls: &[ClassClaim],
    proof: &LimitProof,
) -> Result<String, String> {
    let root = Root::isolate(&proof.rho.poly, &proof.rho.lo, &proof.rho.hi)?;
    let dom = cls
        .get(proof.dominant)
        .ok_or("the dominant class index is out of range")?;
    if dom.period != Some(1) {
        return Err("the dominant class is not primitive (period ≠ 1)".into());
    }
    if root.lo <= Q::one() {
        return Err("ρ > 1 is not shown (lo ≤ 1)".into());
    }
    let field = |v: &[String]| -> Result<P, String> {
        let p = trim(v.iter().map(|s| rat(s)).collect::<Result<_, _>>()?);
        Ok(rem(&p, &root.p))
    };
    let reached: BTreeSet<usize> = cls.iter().flat_map(|k| k.members.iter().copied()).collect();
    let mut y: BTreeMap<usize, P> = BTreeMap::new();
    for (t, v) in &proof.left_vector {
        if !reached.contains(t) || y.insert(*t, field(v)?).is_some() {
            return Err(format!("left vector: type {t} repeated or not reached"));
        }
    }
    let x = vec![Q::zero(), Q::one()];
    let times_rho = |v: &[Q]| rem(&mul(v, &x), &root.p);
    let zero = P::new();
    let get = |t: &usize| y.get(t).unwrap_or(&zero);
    // y·M = ρ·y on every reached type, and y_D·B_D = ρ·y_D on the dominant class.
    let mut ym: BTreeMap<usize, P> = BTreeMap::new();
    let mut yb: BTreeMap<usize, P> = BTreeMap::new();
    for (t, yt) in &y {
        for (s, k) in &m[*t] {
            let term: P = yt
                .iter()
                .map(|a| a * Q::from_integer((*k).into()))
                .collect();
            let e = ym.entry(*s).or_default();
            *e = add(e, &term);
            if dom.members.contains(t) && dom.members.contains(s) {
                let e = yb.entry(*s).or_default();
                *e = add(e, &term);
            }
        }
    }
    for s in &reached {
        if rem(ym.get(s).unwrap_or(&zero), &root.p) != times_rho(get(s)) {
            return Err(format!("y·M ≠ ρ·y at type {s}"));
        }
    }
    for s in &dom.members {
        if rem(yb.get(s).unwrap_or(&zero), &root.p) != times_rho(get(s)) {
            return Err(format!("y·B ≠ ρ·y on the dominant class at type {s}"));
        }
    }
    for (t, yt) in &y {
        let want = if dom.members.contains(t) { 1 } else { 0 };
        match root.sign(yt) {
            Some(s) if s >= want => {}
            _ => {
                return Err(format!(
                    "y at type {t} is not shown {}",
                    ["≥ 0", "> 0"][want as usize]
                ))
            }
        }
    }
    if let Some(t) = dom.members.iter().find(|t| !y.contains_key(t)) {
        return Err(format!("y is 0 at type {t} of the dominant class"));
    }
    // Collatz–Wielandt: B_c·x < lo·x with x > 0 gives ρ(B_c) < lo ≤ ρ.
    let mut bounded = BTreeSet::new();
    for (k, xs) in &proof.bounds {
        let class = cls
            .get(*k)
            .filter(|_| *k != proof.dominant && bounded.insert(*k));
        let class = class.ok_or(format!(
            "bound for class {k}: repeated, dominant or out of range"
        ))?;
        let xs: Vec<Q> = xs.iter().map(|s| rat(s)).collect::<Result<_, _>>()?;
        if xs.len() != class.members.len() || xs.iter().any(|v| !v.is_positive()) {
            return Err(format!(
                "bound for class {k}: not a positive vector on its members"
            ));
        }
        for (i, t) in class.members.iter().enumerate() {
            let bx: Q = class
                .members
                .iter()
                .zip(&xs)
                .map(|(s, v)| v * Q::from_integer(m[*t].get(s).copied().unwrap_or(0).into()))
                .sum();
            if bx >= &root.lo * &xs[i] {
                return Err(format!("bound for class {k}: (B·x)_{t} ≥ lo·x_{t}"));
            }
        }
    }
    if bounded.len() + 1 != cls.len() {
        return Err("a non-dominant class has no Collatz–Wielandt bound".into());
    }
    // R·(y·c + (ρ−1)·y·1) = y·c in Q[x]/(p).
    let half = Q::new(BigInt::one(), BigInt::from(2));
    let yc = y.iter().fold(P::new(), |acc, (t, v)| {
        add(
            &acc,
            &v.iter()
                .map(|a| a * &half * Q::from_integer(c[*t].into()))
                .collect::<P>(),
        )
    });
    let y1 = y.values().fold(P::new(), |acc, v| add(&acc, v));
    let den = add(&yc, &rem(&mul(&y1, &[-Q::one(), Q::one()]), &root.p));
    let ratio = field(&proof.ratio)?;
    if rem(&mul(&ratio, &den), &root.p) != yc {
        return Err("R·(y·c + (ρ−1)·y·1) ≠ y·c: the claimed limit is wrong".into());
    }
    let shown = |v: &[Q]| {
        v.iter()
            .map(|q| q.to_string())
            .collect::<Vec<_>>()
            .join(", ")
    };
    let rho = match root.p.len() {
        2 => format!("ρ = {} (rational root of its polynomial)", root.lo),
        _ => format!(
            "ρ isolated in ({}, {}) by Sturm's theorem",
            root.lo, root.hi
        ),
    };
    Ok(format!(
        "{rho}, a simple, strictly dominant eigenvalue (Perron–Frobenius eigenvector, \
         Collatz–Wielandt bounds), dominant class primitive: R exists and equals ({}) on the \
         power basis 1, ρ, …",
        shown(&ratio)
    ))
}
