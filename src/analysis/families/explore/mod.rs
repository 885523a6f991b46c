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
//!
//! The parts: `family.rs` enumerates the family (every necklace or a seeded sample, crossed with
//! every E) and bounds its size; `face.rs` checks the properties on one face and shrinks each
//! failure; this file holds the properties, the options and the results, and runs a shard in
//! parallel, in index order.

mod face;
mod family;

pub use face::explore_face;
pub use family::MAX_FAMILY;

use crate::error::{Error, Result, Source, Span};
use crate::topology::closure::TypeSet;
use crate::topology::edge::EdgeType;
use crate::topology::face::Face;
use crate::topology::limits::Limits;
use crate::topology::rule::Algorithm;
use family::family_size;
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

#[cfg(test)]
mod tests {
    use super::*;

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
}
