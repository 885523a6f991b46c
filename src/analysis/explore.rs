//! Property-based exploration of a subdivision rule over a family of boundaries (THEORY §14), for
//! `lacuna explore`.
//!
//! A family is every boundary up to a length over given edge types (one per rotation class), or a
//! seeded random sample, crossed with every E over given edge types, under one algorithm. Each
//! face is checked for the requested properties — the closure closes (within the bound stated in
//! advance for the built-ins), the generated constraint system is consistent, no two distinct
//! corner points of a level-1 complex are forced to coincide, the limit ratio R exists, the
//! certificate checks, and (opt-in) the holes observed in the geometry equal the exact count. The
//! last two are supplied by the caller ([`Checks`]): the certificate layer and the geometry sit
//! above this one. A failure is shrunk greedily to a minimal counterexample — fewer edges, smaller n,
//! smaller delays, `Cn` → `Bn`, simpler E — that fails the same property, and reported with its
//! shortest witness: the runaway chain (breadth-first, so shortest), the conflicting constraints,
//! the collapsing pair, the limit points.
//!
//! Every verdict is exact. Boundary `k` of the family belongs to shard `k mod n`, and its result
//! depends on nothing else, so the lines of the shards of a family, merged by index, are the lines
//! of one run.

use crate::analysis::ratio::analyse;
use crate::constraint::{solve_closure, GenOptions};
use crate::error::{Error, Result, Source, Span};
use crate::topology::closure::{Bound, Closure, TypeSet};
use crate::topology::edge::{EdgeKind, EdgeType};
use crate::topology::face::{least_rotation, Face, Params};
use crate::topology::limits::{at_most, Limits};
use crate::topology::rule::Algorithm;
use num_rational::BigRational;
use serde::Serialize;
use std::collections::BTreeMap;

/// A property checked on every face of the family.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Property {
    /// The closure closes (and stays within the bound stated in advance, when there is one).
    Closes,
    /// The generated constraint system has a solution.
    Consistent,
    /// No two distinct corner points of a level-1 complex are forced to coincide.
    NoCollapse,
    /// The limit ratio R exists (R_i converges).
    Ratio,
    /// The certificate of every verdict is proved by the independent checker.
    Certificate,
    /// The holes observed in the instantiated geometry equal the exact count at every level up
    /// to a given one (opt-in: it needs geometry, which the caller supplies).
    Holes,
}

impl Property {
    /// Every exact property, in the order they are checked (`all`; `holes` is opt-in).
    pub const ALL: [Property; 5] = [
        Property::Closes,
        Property::Consistent,
        Property::NoCollapse,
        Property::Ratio,
        Property::Certificate,
    ];

    /// The name used on the command line and in the JSON.
    pub fn name(&self) -> &'static str {
        match self {
            Property::Closes => "closes",
            Property::Consistent => "consistent",
            Property::NoCollapse => "no-collapse",
            Property::Ratio => "ratio",
            Property::Certificate => "certificate",
            Property::Holes => "holes",
        }
    }
}

/// The shortest evidence of a failure.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Witness {
    /// `runaway chain`, `outside the stated bound`, `conflict`, `collapsing pair`, `limit points`
    /// or `certificate`.
    pub kind: String,
    /// The evidence: the chain of faces, the constraints with their multipliers, the pair, …
    pub detail: Vec<String>,
}

/// The outcome of one property on one face.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// It holds.
    Pass,
    /// It fails, with the witness.
    Fail(Witness),
    /// It could not be decided: a prerequisite failed or a limit was reached (the reason).
    Skip(String),
}

/// A property checked by a layer above this one (the certificate layer, the geometry), supplied
/// by the caller: its outcome on a face and its closed type set.
pub type Check<'a> = &'a (dyn Fn(&Face, &TypeSet) -> Outcome + Sync);

/// The checks supplied from above; a property without its check is skipped.
#[derive(Clone, Copy, Default)]
pub struct Checks<'a> {
    /// `certificate`: the certificate of the closed type set is proved by the checker.
    pub certificate: Option<Check<'a>>,
    /// `holes`: observed holes equal the exact count.
    pub holes: Option<Check<'a>>,
}

/// What was explored.
#[derive(Clone, Debug)]
pub struct ExploreSpec {
    /// Edge types of the boundaries.
    pub edges: Vec<EdgeType>,
    /// Largest boundary length.
    pub max_length: usize,
    /// Edge types for each of Ea, El, Ec.
    pub params: Vec<EdgeType>,
    /// The algorithm.
    pub algorithm: Algorithm,
    /// The properties, in check order.
    pub properties: Vec<Property>,
    /// A random sample of this many boundaries instead of every one.
    pub random: Option<u64>,
    /// The seed of the random sample.
    pub seed: u64,
    /// This run explores shard `.0` (0-based) of `.1`.
    pub shard: (u64, u64),
    /// Most property evaluations spent shrinking one failure.
    pub shrink_budget: usize,
    /// Worker threads (the output does not depend on their number).
    pub threads: usize,
}

/// The largest family (boundaries × E) explored in one run.
pub const MAX_FAMILY: u64 = 10_000_000;

fn bad_option(text: &str, msg: String) -> Error {
    Error::syntax(
        "E0114",
        msg,
        Span {
            line: 1,
            col: 1,
            len: text.chars().count().max(1),
        },
        Some(&Source::command_line(text)),
    )
}

/// Parses `closes,consistent,…` (or `all`).
pub fn parse_properties(text: &str) -> Result<Vec<Property>> {
    let mut out = Vec::new();
    for item in text.split(',').map(str::trim) {
        if item == "all" {
            return Ok(Property::ALL.to_vec());
        }
        let Some(p) = Property::ALL
            .iter()
            .chain(&[Property::Holes])
            .find(|p| p.name() == item)
        else {
            return Err(bad_option(
                text,
                format!("unknown property `{item}` (closes, consistent, no-collapse, ratio, certificate, holes or all)"),
            ));
        };
        if !out.contains(p) {
            out.push(*p);
        }
    }
    out.sort();
    Ok(out)
}

/// Parses `--shard i/n` (1 ≤ i ≤ n) into the 0-based shard and the count.
pub fn parse_shard(text: &str) -> Result<(u64, u64)> {
    let parsed = text
        .split_once('/')
        .and_then(|(i, n)| Some((i.trim().parse::<u64>().ok()?, n.trim().parse::<u64>().ok()?)));
    match parsed {
        Some((i, n)) if n >= 1 && (1..=n).contains(&i) => Ok((i - 1, n)),
        _ => Err(bad_option(
            text,
            format!("--shard `{text}` must be i/n with 1 ≤ i ≤ n (for instance 2/8)"),
        )),
    }
}

/// SplitMix64: a small deterministic generator, the same on every machine.
struct SplitMix(u64);

impl SplitMix {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

impl ExploreSpec {
    /// Checks the family's size against the limits before any work.
    pub fn check(&self) -> Result<()> {
        at_most(
            "the explored boundary length",
            self.max_length,
            12,
            "--max-length",
        )?;
        if self.max_length == 0 {
            return Err(Error::OutOfRange {
                flag: "--max-length",
                value: "0".into(),
                what: "the largest boundary length",
                range: "1 to 12".into(),
            });
        }
        if self.edges.is_empty() || self.params.is_empty() {
            return Err(Error::Usage(
                "explore needs at least one edge type in --edges and in --params".into(),
            ));
        }
        let e = (self.params.len() as u64).pow(3);
        let boundaries = match self.random {
            Some(n) => n,
            None => (1..=self.max_length as u32)
                .map(|l| (self.edges.len() as u64).saturating_pow(l))
                .fold(0u64, u64::saturating_add),
        };
        let family = boundaries.saturating_mul(e);
        if family > MAX_FAMILY {
            return Err(Error::limit(
                "the explored family (boundaries × E)",
                family,
                MAX_FAMILY,
                if self.random.is_some() {
                    "--random"
                } else {
                    "--max-length"
                },
            ));
        }
        Ok(())
    }

    /// Calls `f` with every boundary of the family, in a fixed order (before E is chosen),
    /// generating them one at a time.
    fn for_each_boundary(&self, mut f: impl FnMut(Vec<EdgeType>)) {
        let k = self.edges.len();
        if let Some(n) = self.random {
            let mut rng = SplitMix(self.seed);
            for _ in 0..n {
                let len = 1 + rng.below(self.max_length.max(1));
                f((0..len).map(|_| self.edges[rng.below(k)]).collect());
            }
            return;
        }
        for len in 1..=self.max_length {
            let mut digits = vec![0usize; len];
            loop {
                if least_rotation(&digits) == 0 {
                    f(digits.iter().map(|&d| self.edges[d]).collect());
                }
                let mut i = 0;
                while i < len && digits[i] + 1 == k {
                    digits[i] = 0;
                    i += 1;
                }
                if i == len {
                    break;
                }
                digits[i] += 1;
            }
        }
    }

    /// Calls `f` with every face of the family and its index, in order, one at a time (the
    /// family is never held in memory).
    pub fn for_each_face(&self, mut f: impl FnMut(u64, Face)) {
        let mut k = 0u64;
        self.for_each_boundary(|b| {
            for &ea in &self.params {
                for &el in &self.params {
                    for &ec in &self.params {
                        let face = Face {
                            boundary: b.clone(),
                            params: Params { ea, el, ec },
                            algorithm: self.algorithm.clone(),
                            delay: 1,
                        };
                        f(k, face.canonical().0);
                        k += 1;
                    }
                }
            }
        });
    }

    /// Every face of the family, in order (all of them, every shard).
    pub fn family(&self) -> Vec<Face> {
        let mut faces = Vec::new();
        self.for_each_face(|_, f| faces.push(f));
        faces
    }
}

/// A shrunk counterexample.
#[derive(Clone, Debug, Serialize)]
pub struct Shrunk {
    /// The minimal face found (canonical notation).
    pub face: String,
    /// Its witness.
    pub witness: Witness,
    /// Shrinking steps taken.
    pub steps: usize,
    /// True when no simpler face fails the property (false when the budget ran out first).
    pub minimal: bool,
}

/// One failed property of one face.
#[derive(Clone, Debug, Serialize)]
pub struct Failure {
    /// The property.
    pub property: Property,
    /// Its witness on the face itself.
    pub witness: Witness,
    /// The minimal counterexample it shrinks to.
    pub shrunk: Shrunk,
}

/// The result on one face of the family: one JSON line.
#[derive(Clone, Debug, Serialize)]
pub struct BoundaryResult {
    /// Index in the family (the same in every shard).
    pub index: u64,
    /// The face, canonical notation.
    pub face: String,
    /// `pass`, `fail`, `refused` (bad face for this rule, e.g. no spoke; not a failure) or
    /// `limit` (a limit was reached before a verdict; not a failure).
    pub status: &'static str,
    /// The error code of a refused face or a reached limit.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub code: Option<&'static str>,
    /// Number of face types of the closure, when it closed.
    pub types: Option<usize>,
    /// The limit ratio R, exact, when computed and existing.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ratio: Option<String>,
    /// Each checked property: `pass`, `fail` or `skip: <reason>`.
    pub properties: BTreeMap<&'static str, String>,
    /// The failures, shrunk.
    pub failures: Vec<Failure>,
}

/// What one shard found, for the summary line.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Summary {
    /// The shard, `i/n`.
    pub shard: String,
    /// Faces explored by this shard.
    pub boundaries: u64,
    /// Faces where every property held.
    pub passed: u64,
    /// Faces where a property failed.
    pub failed: u64,
    /// Faces refused by the rule (no spoke).
    pub refused: u64,
    /// Faces where a limit was reached first.
    pub limit: u64,
    /// Failures per property.
    pub failures: BTreeMap<&'static str, u64>,
    /// The distinct minimal counterexamples, with the property they break.
    pub counterexamples: Vec<(String, Property)>,
}

/// The evaluation of one face.
struct Evaluation {
    refused: Option<(&'static str, String)>,
    types: Option<usize>,
    ratio: Option<String>,
    outcomes: Vec<(Property, Outcome)>,
}

/// Checks `props` on one face (and what they need first).
fn evaluate(face: &Face, props: &[Property], limits: &Limits, checks: &Checks) -> Evaluation {
    let mut ev = Evaluation {
        refused: None,
        types: None,
        ratio: None,
        outcomes: Vec::new(),
    };
    let skip_all = |ev: &mut Evaluation, why: &str| {
        for &p in props {
            if !ev.outcomes.iter().any(|(q, _)| *q == p) {
                ev.outcomes.push((p, Outcome::Skip(why.into())));
            }
        }
    };
    if let Err(e) = limits.check_face(face) {
        ev.refused = Some((e.code(), e.to_string()));
        return ev;
    }
    let ts = match Closure::of(std::slice::from_ref(face), limits) {
        Err(e) => {
            ev.refused = Some((e.code(), e.to_string()));
            return ev;
        }
        Ok(Closure::Runaway(r)) => {
            if let Some(bound) = Bound::stated(std::slice::from_ref(face)) {
                // A built-in closes; the limit was reached first.
                ev.refused = Some((
                    "E0501",
                    format!(
                        "closes (boundary length ≤ {} proved) but {}",
                        bound.max_length, r.reason
                    ),
                ));
                return ev;
            }
            let mut detail = vec![r.reason.clone()];
            detail.extend(r.witness.iter().cloned());
            if props.contains(&Property::Closes) {
                ev.outcomes.push((
                    Property::Closes,
                    Outcome::Fail(Witness {
                        kind: "runaway chain".into(),
                        detail,
                    }),
                ));
            }
            skip_all(&mut ev, "the closure did not close");
            return ev;
        }
        Ok(Closure::Closed(ts)) => ts,
    };
    ev.types = Some(ts.types.len());
    if props.contains(&Property::Closes) {
        let outcome = match &ts.bound {
            Some(b) => {
                let long = ts
                    .types
                    .iter()
                    .find(|t| num_bigint::BigUint::from(t.face.boundary.len()) > b.max_length);
                if let Some(t) = long {
                    Outcome::Fail(Witness {
                        kind: "outside the stated bound".into(),
                        detail: vec![format!(
                            "{} has {} edges, above the stated bound {}",
                            t.face,
                            t.face.boundary.len(),
                            b.max_length
                        )],
                    })
                } else if num_bigint::BigUint::from(ts.types.len()) > b.max_types {
                    Outcome::Fail(Witness {
                        kind: "outside the stated bound".into(),
                        detail: vec![format!(
                            "{} types, above the stated bound {}",
                            ts.types.len(),
                            b.max_types
                        )],
                    })
                } else {
                    Outcome::Pass
                }
            }
            None => Outcome::Pass,
        };
        ev.outcomes.push((Property::Closes, outcome));
    }
    if props.contains(&Property::Consistent) || props.contains(&Property::NoCollapse) {
        match solve_closure(&ts, GenOptions::default(), limits) {
            Err(e) => {
                for p in [Property::Consistent, Property::NoCollapse] {
                    if props.contains(&p) {
                        ev.outcomes
                            .push((p, Outcome::Skip(format!("{}: {e}", e.code()))));
                    }
                }
            }
            Ok(report) => {
                if props.contains(&Property::Consistent) {
                    let outcome = if report.consistent {
                        Outcome::Pass
                    } else {
                        let mut detail = vec![format!(
                            "these constraints with these multipliers sum to 0 = {}",
                            report.conflict_constant.clone().unwrap_or_default()
                        )];
                        detail.extend(
                            report
                                .conflict
                                .iter()
                                .flatten()
                                .map(|c| format!("× {}  {}", c.multiplier, c.constraint)),
                        );
                        Outcome::Fail(Witness {
                            kind: "conflict".into(),
                            detail,
                        })
                    };
                    ev.outcomes.push((Property::Consistent, outcome));
                }
                if props.contains(&Property::NoCollapse) {
                    let outcome = if !report.consistent {
                        Outcome::Skip("the constraint system is inconsistent".into())
                    } else if report.degenerate.is_empty() {
                        Outcome::Pass
                    } else {
                        Outcome::Fail(Witness {
                            kind: "collapsing pair".into(),
                            detail: vec![
                                report.degenerate[0].clone(),
                                format!(
                                    "{} in all",
                                    crate::error::counted(
                                        report.degenerate.len(),
                                        "forced collapse",
                                        "forced collapses"
                                    )
                                ),
                            ],
                        })
                    };
                    ev.outcomes.push((Property::NoCollapse, outcome));
                }
            }
        }
    }
    if props.contains(&Property::Ratio) {
        let c: Vec<BigRational> = ts
            .types
            .iter()
            .map(|t| BigRational::new(t.contribution_halves().into(), 2.into()))
            .collect();
        let outcome = match analyse(&ts.matrix(), &c, &[(ts.start[0], 1)]) {
            Err(e) => Outcome::Skip(e.to_string()),
            Ok(r) if r.exists => {
                ev.ratio = r.exact.clone();
                Outcome::Pass
            }
            Ok(r) => {
                let mut detail = vec![format!(
                    "R_i does not converge: period {} of the dominant classes",
                    r.period
                )];
                detail.extend(
                    r.limit_points
                        .iter()
                        .map(|p| format!("lim R_({}n+{}) = {}", r.period, p.residue, p.exact)),
                );
                Outcome::Fail(Witness {
                    kind: "limit points".into(),
                    detail,
                })
            }
        };
        ev.outcomes.push((Property::Ratio, outcome));
    }
    for (p, check) in [
        (Property::Certificate, checks.certificate),
        (Property::Holes, checks.holes),
    ] {
        if props.contains(&p) {
            let outcome = match check {
                None => Outcome::Skip(format!("no {} check supplied", p.name())),
                Some(check) => check(face, &ts),
            };
            ev.outcomes.push((p, outcome));
        }
    }
    ev
}

/// The faces one shrinking step away, simplest changes first: remove an edge; lower an edge's n
/// or delay or make it a `Bn`; the same on Ea, El, Ec; lower the face delay. Every candidate is
/// smaller in (length, Σn, Σdelay, number of `Cn`), so shrinking ends.
fn candidates(f: &Face) -> Vec<Face> {
    let mut out: Vec<Face> = Vec::new();
    let mut push = |g: Face| {
        let g = g.canonical().0;
        if g != *f && !out.contains(&g) {
            out.push(g);
        }
    };
    let simpler = |e: &EdgeType| -> Vec<EdgeType> {
        let mut v = Vec::new();
        if e.n > 2 {
            v.push(EdgeType { n: e.n - 1, ..*e });
        }
        if e.delay > 1 {
            v.push(EdgeType {
                delay: e.delay - 1,
                ..*e
            });
        }
        if e.kind == EdgeKind::C {
            v.push(EdgeType {
                kind: EdgeKind::B,
                ..*e
            });
        }
        v
    };
    if f.boundary.len() > 1 {
        for i in 0..f.boundary.len() {
            let mut g = f.clone();
            g.boundary.remove(i);
            push(g);
        }
    }
    for i in 0..f.boundary.len() {
        for e in simpler(&f.boundary[i]) {
            let mut g = f.clone();
            g.boundary[i] = e;
            push(g);
        }
    }
    for k in 0..3 {
        let get = |p: &Params| [p.ea, p.el, p.ec][k];
        for e in simpler(&get(&f.params)) {
            let mut g = f.clone();
            match k {
                0 => g.params.ea = e,
                1 => g.params.el = e,
                _ => g.params.ec = e,
            }
            push(g);
        }
    }
    if f.delay > 1 {
        push(Face {
            delay: f.delay - 1,
            ..f.clone()
        });
    }
    out
}

/// The witness of `p` on `f` when it fails `p`.
fn fails(f: &Face, p: Property, limits: &Limits, checks: &Checks) -> Option<Witness> {
    let ev = evaluate(f, &[p], limits, checks);
    ev.outcomes.into_iter().find_map(|(q, o)| match o {
        Outcome::Fail(w) if q == p => Some(w),
        _ => None,
    })
}

/// Shrinks a failure of `p` on `f` (witness `w`) greedily within `budget` evaluations.
fn shrink(
    f: &Face,
    w: Witness,
    p: Property,
    limits: &Limits,
    budget: usize,
    checks: &Checks,
) -> Shrunk {
    let (mut cur, mut witness, mut steps, mut spent) = (f.clone(), w, 0usize, 0usize);
    'outer: loop {
        for g in candidates(&cur) {
            if spent >= budget {
                return Shrunk {
                    face: cur.to_string(),
                    witness,
                    steps,
                    minimal: false,
                };
            }
            spent += 1;
            if let Some(w) = fails(&g, p, limits, checks) {
                cur = g;
                witness = w;
                steps += 1;
                continue 'outer;
            }
        }
        return Shrunk {
            face: cur.to_string(),
            witness,
            steps,
            minimal: true,
        };
    }
}

/// Explores one face (index `index` of the family).
pub fn explore_face(
    index: u64,
    face: &Face,
    spec: &ExploreSpec,
    limits: &Limits,
    checks: &Checks,
) -> BoundaryResult {
    let ev = evaluate(face, &spec.properties, limits, checks);
    let mut r = BoundaryResult {
        index,
        face: face.to_string(),
        status: "pass",
        code: None,
        types: ev.types,
        ratio: ev.ratio,
        properties: BTreeMap::new(),
        failures: Vec::new(),
    };
    if let Some((code, msg)) = ev.refused {
        r.status = if code == "E0501" { "limit" } else { "refused" };
        r.code = Some(code);
        for p in &spec.properties {
            r.properties.insert(p.name(), format!("skip: {msg}"));
        }
        return r;
    }
    for (p, o) in ev.outcomes {
        let text = match &o {
            Outcome::Pass => "pass".to_string(),
            Outcome::Fail(_) => "fail".to_string(),
            Outcome::Skip(why) => format!("skip: {why}"),
        };
        r.properties.insert(p.name(), text);
        if let Outcome::Fail(w) = o {
            let shrunk = shrink(face, w.clone(), p, limits, spec.shrink_budget, checks);
            r.failures.push(Failure {
                property: p,
                witness: w,
                shrunk,
            });
        }
    }
    if !r.failures.is_empty() {
        r.status = "fail";
    }
    r
}

/// Explores this shard of the family, calling `emit` with each result in index order; returns
/// the summary.
pub fn explore(
    spec: &ExploreSpec,
    limits: &Limits,
    checks: &Checks,
    mut emit: impl FnMut(&BoundaryResult),
) -> Result<Summary> {
    spec.check()?;
    let (shard, of) = spec.shard;
    let mut s = Summary {
        shard: format!("{}/{}", shard + 1, of),
        ..Summary::default()
    };
    let total = family_size(spec);
    let bar = std::sync::Mutex::new(crate::progress::Progress::with_step(
        "explore",
        total / of + 1,
        1,
    ));
    let threads = spec.threads.max(1);
    // Faces are explored in blocks, in parallel, and emitted in index order: the output does not
    // depend on the thread count, and memory stays bounded by the block.
    let mut block: Vec<(u64, Face)> = Vec::new();
    let mut flush = |block: &mut Vec<(u64, Face)>, s: &mut Summary| {
        let results: Vec<BoundaryResult> = if threads == 1 || block.len() == 1 {
            block
                .iter()
                .map(|(k, f)| {
                    let r = explore_face(*k, f, spec, limits, checks);
                    bar.lock().expect("no worker panics").tick();
                    r
                })
                .collect()
        } else {
            let next = std::sync::atomic::AtomicUsize::new(0);
            let slots: std::sync::Mutex<Vec<Option<BoundaryResult>>> =
                std::sync::Mutex::new((0..block.len()).map(|_| None).collect());
            std::thread::scope(|sc| {
                for _ in 0..threads.min(block.len()) {
                    sc.spawn(|| loop {
                        let i = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                        let Some((k, f)) = block.get(i) else { break };
                        let r = explore_face(*k, f, spec, limits, checks);
                        slots.lock().expect("no worker panics")[i] = Some(r);
                        bar.lock().expect("no worker panics").tick();
                    });
                }
            });
            slots
                .into_inner()
                .expect("no worker panics")
                .into_iter()
                .map(|r| r.expect("every face explored"))
                .collect()
        };
        for r in &results {
            s.boundaries += 1;
            match r.status {
                "pass" => s.passed += 1,
                "fail" => s.failed += 1,
                "limit" => s.limit += 1,
                _ => s.refused += 1,
            }
            for f in &r.failures {
                *s.failures.entry(f.property.name()).or_default() += 1;
                let c = (f.shrunk.face.clone(), f.property);
                if !s.counterexamples.contains(&c) {
                    s.counterexamples.push(c);
                }
            }
            emit(r);
        }
        block.clear();
    };
    spec.for_each_face(|k, face| {
        if k % of != shard {
            return;
        }
        block.push((k, face));
        if block.len() >= 16 * threads {
            flush(&mut block, &mut s);
        }
    });
    flush(&mut block, &mut s);
    Ok(s)
}

impl ExploreSpec {
    /// The number of faces of the family (boundaries × E); call after [`ExploreSpec::check`],
    /// which bounds the enumeration.
    pub fn size(&self) -> u64 {
        family_size(self)
    }
}

/// The number of faces of the family (boundaries × E), for the progress bar: the necklaces are
/// counted by enumerating them (at most [`MAX_FAMILY`] cheap steps, as checked before).
fn family_size(spec: &ExploreSpec) -> u64 {
    let e = (spec.params.len() as u64).pow(3);
    let boundaries = match spec.random {
        Some(n) => n,
        None => {
            let mut n = 0u64;
            spec.for_each_boundary(|_| n += 1);
            n
        }
    };
    boundaries * e
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(edges: &str, params: &str, algorithm: &str, len: usize) -> ExploreSpec {
        let list = |t: &str| -> Vec<EdgeType> {
            t.split(',')
                .map(|x| EdgeType::parse(x, 1).unwrap())
                .collect()
        };
        ExploreSpec {
            edges: list(edges),
            max_length: len,
            params: list(params),
            algorithm: Algorithm::parse(algorithm, 1, &[]).unwrap(),
            properties: vec![Property::Closes],
            random: None,
            seed: 0,
            shard: (0, 1),
            shrink_budget: 100,
            threads: 1,
        }
    }

    #[test]
    fn family_is_necklaces_times_e() {
        // Necklaces over 2 letters up to length 3: 2 + 3 + 4 = 9; E over 2 types: 8.
        assert_eq!(spec("B2,C2", "B2,C2", "A1", 3).family().len(), 9 * 8);
        let mut r = spec("B2,C2", "B2", "A1", 5);
        r.random = Some(20);
        r.seed = 7;
        let a = r.family();
        assert_eq!(a.len(), 20);
        assert_eq!(a, r.family(), "the random family depends on the seed only");
    }

    #[test]
    fn options_parse() {
        assert_eq!(parse_shard("2/8").unwrap(), (1, 8));
        for bad in ["0/3", "4/3", "x", "1/0"] {
            assert_eq!(parse_shard(bad).unwrap_err().code(), "E0114", "{bad}");
        }
        assert_eq!(parse_properties("all").unwrap().len(), 5);
        assert_eq!(
            parse_properties("ratio,closes").unwrap(),
            vec![Property::Closes, Property::Ratio]
        );
        assert_eq!(parse_properties("nice").unwrap_err().code(), "E0114");
    }

    #[test]
    fn shrink_candidates_are_smaller() {
        let f = Face::parse("C3^2 B2 | C2 B2 B2 | {gap}").unwrap();
        let size = |g: &Face| {
            let p = g.params;
            let all: Vec<&EdgeType> = g.boundary.iter().chain([&p.ea, &p.el, &p.ec]).collect();
            (
                g.boundary.len(),
                all.iter().map(|e| e.n).sum::<u32>()
                    + all.iter().map(|e| e.delay).sum::<u32>()
                    + all.iter().filter(|e| e.kind == EdgeKind::C).count() as u32
                    + g.delay,
            )
        };
        for g in candidates(&f) {
            assert!(size(&g) < size(&f), "{g} is not smaller than {f}");
        }
    }
}
