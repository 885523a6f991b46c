//! A census: close and count every face of a family, in parallel, and tabulate the number of
//! face types. Used by `lacuna census` and by the benchmark.

use crate::error::{Error, Result, Span};
use crate::topology::closure::Closure;
use crate::topology::count::counts;
use crate::topology::edge::EdgeType;
use crate::topology::face::{least_rotation, Face, Params};
use crate::topology::limits::Limits;
use crate::topology::rule::Algorithm;
use serde::Serialize;
use std::collections::BTreeMap;
use std::sync::Mutex;
use std::time::Instant;

/// The family of faces to survey.
#[derive(Clone, Debug)]
pub struct CensusSpec {
    /// Edge types of the boundaries.
    pub edges: Vec<EdgeType>,
    /// Edge types for each of Ea, El, Ec.
    pub params: Vec<EdgeType>,
    /// Algorithms.
    pub algorithms: Vec<Algorithm>,
    /// Largest boundary length (every length from 1 up is surveyed).
    pub max_length: usize,
    /// Worker threads.
    pub threads: usize,
    /// Levels of counts computed per face.
    pub levels: u64,
    /// Also report every face (its type count, R and verdict), as `census --json` does.
    pub per_face: bool,
}

/// One face of a census, when [`CensusSpec::per_face`] asks for them.
#[derive(Clone, Debug, Serialize)]
pub struct CensusFace {
    /// The face, canonical notation.
    pub face: String,
    /// `closed`, `runaway`, `refused` or `over-limit` (a proved-finite closure above a limit).
    pub verdict: &'static str,
    /// The error code of a refused face (`E0401`: no spoke).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub code: Option<&'static str>,
    /// The number of face types of the closure, when it closed.
    pub types: Option<usize>,
    /// The limit ratio R, exact, when the closure closed and the limit exists.
    pub ratio: Option<String>,
}

/// What the census found.
#[derive(Clone, Debug, Serialize)]
pub struct CensusReport {
    /// Faces surveyed (canonical boundaries × E × algorithms).
    pub faces: usize,
    /// Faces whose closure closed.
    pub closed: usize,
    /// Faces whose closure ran away.
    pub runaway: usize,
    /// Faces refused (for instance no spoke).
    pub refused: usize,
    /// Faces whose closure is proved finite but meets a configured limit (not a verdict; absent
    /// from the JSON when zero).
    #[serde(skip_serializing_if = "is_zero")]
    pub over_limit: usize,
    /// Number of faces per number of face types in the closure.
    pub distribution: BTreeMap<usize, usize>,
    /// The face with the largest closure, and its number of types.
    pub largest: Option<(String, usize)>,
    /// Every face, in the family's order, when [`CensusSpec::per_face`] asks for them.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub per_face: Vec<CensusFace>,
    /// Worker threads used (not in the JSON, which is identical for every thread count).
    #[serde(skip)]
    pub threads: usize,
    /// Wall-clock seconds (not part of any verdict, not in the JSON).
    #[serde(skip)]
    pub elapsed_seconds: f64,
}

fn is_zero(n: &usize) -> bool {
    *n == 0
}

fn parse_list<T>(text: &str, what: &str, f: impl Fn(&str, usize) -> Result<T>) -> Result<Vec<T>> {
    let mut out = Vec::new();
    let mut col = 1;
    for item in text.split(',') {
        let t = item.trim();
        if t.is_empty() {
            return Err(Error::syntax(
                "E0112",
                format!("empty item in the list of {what}"),
                Span {
                    line: 1,
                    col,
                    len: 1,
                },
                Some(&crate::error::Source::command_line(text)),
            ));
        }
        let lead = item.len() - item.trim_start().len();
        out.push(
            f(t, col + lead)
                .map_err(|e| e.within(&crate::error::Source::command_line(text), 1, 0))?,
        );
        col += item.chars().count() + 1;
    }
    Ok(out)
}

/// A comma-separated list of edge types (`B2,C2`), each spanned in `text` for errors; `what`
/// names the list in the message of an empty item (E0112).
pub fn parse_edge_list(text: &str, what: &str) -> Result<Vec<EdgeType>> {
    parse_list(text, what, EdgeType::parse)
}

impl CensusSpec {
    /// Builds a spec from comma-separated lists.
    pub fn parse(
        edges: &str,
        params: &str,
        algorithms: &str,
        max_length: usize,
        threads: Option<usize>,
    ) -> Result<Self> {
        let edges = parse_list(edges, "edges", EdgeType::parse)?;
        let params = parse_list(params, "parameters", EdgeType::parse)?;
        let algorithms = parse_list(algorithms, "algorithms", |t, c| Algorithm::parse(t, c, &[]))?;
        crate::topology::limits::at_most(
            "the census boundary length",
            max_length,
            12,
            "--max-length",
        )?;
        let threads = threads
            .unwrap_or_else(|| {
                std::thread::available_parallelism()
                    .map(|n| n.get())
                    .unwrap_or(1)
            })
            .clamp(1, 256);
        Ok(CensusSpec {
            edges,
            params,
            algorithms,
            max_length,
            threads,
            levels: 10,
            per_face: false,
        })
    }

    /// Every face of the family — canonical boundaries (one per rotation class) × E × A — one at
    /// a time, in a fixed order: the family is never held in memory (at `--max-length 12` it has
    /// tens of millions of faces).
    pub fn faces(&self) -> impl Iterator<Item = Face> + '_ {
        let combos: Vec<(EdgeType, EdgeType, EdgeType, &Algorithm)> = self
            .params
            .iter()
            .flat_map(|&ea| {
                self.params.iter().flat_map(move |&el| {
                    self.params
                        .iter()
                        .flat_map(move |&ec| self.algorithms.iter().map(move |a| (ea, el, ec, a)))
                })
            })
            .collect();
        Necklaces::new(self.edges.len(), self.max_length).flat_map(move |digits| {
            let boundary: Vec<EdgeType> = digits.iter().map(|&d| self.edges[d]).collect();
            combos.clone().into_iter().map(move |(ea, el, ec, a)| Face {
                boundary: boundary.clone(),
                params: Params { ea, el, ec },
                algorithm: a.clone(),
                delay: 1,
            })
        })
    }

    /// The number of faces of the family, from the necklace count
    /// `N(k, n) = (1/n)·Σ_{d | n} φ(d)·k^(n/d)` (rotation classes of words of length n over k
    /// letters) summed over the lengths, times |E choices|³ × |algorithms|; saturates at
    /// `u64::MAX`.
    pub fn family_size(&self) -> u64 {
        let k = self.edges.len() as u128;
        let mut boundaries: u128 = 0;
        for n in 1..=self.max_length as u32 {
            let mut sum: u128 = 0;
            for d in (1..=n).filter(|d| n % d == 0) {
                let term = k
                    .checked_pow(n / d)
                    .and_then(|p| p.checked_mul(u128::from(totient(d))));
                match term.and_then(|t| sum.checked_add(t)) {
                    Some(x) => sum = x,
                    None => return u64::MAX,
                }
            }
            boundaries = boundaries.saturating_add(sum / u128::from(n));
        }
        let per = (self.params.len() as u128).pow(3) * self.algorithms.len() as u128;
        u64::try_from(boundaries.saturating_mul(per)).unwrap_or(u64::MAX)
    }
}

/// Euler's totient.
fn totient(n: u32) -> u32 {
    (1..=n).filter(|&k| num_integer::gcd(k, n) == 1).count() as u32
}

/// The least rotations of all words of length 1 to `max_len` over `k` letters (as digit
/// vectors), shortest first, each length in base-k counting order; one word in memory at a time.
struct Necklaces {
    k: usize,
    max_len: usize,
    digits: Vec<usize>,
    done: bool,
}

impl Necklaces {
    fn new(k: usize, max_len: usize) -> Necklaces {
        Necklaces {
            k,
            max_len,
            digits: vec![0],
            done: k == 0 || max_len == 0,
        }
    }

    /// Steps to the next word (base-k counting, then one letter longer).
    fn advance(&mut self) {
        let len = self.digits.len();
        let mut i = 0;
        while i < len && self.digits[i] + 1 == self.k {
            self.digits[i] = 0;
            i += 1;
        }
        if i < len {
            self.digits[i] += 1;
        } else if len < self.max_len {
            self.digits = vec![0; len + 1];
        } else {
            self.done = true;
        }
    }
}

impl Iterator for Necklaces {
    type Item = Vec<usize>;

    fn next(&mut self) -> Option<Vec<usize>> {
        while !self.done {
            let canonical = least_rotation(&self.digits) == 0;
            let word = canonical.then(|| self.digits.clone());
            self.advance();
            if word.is_some() {
                return word;
            }
        }
        None
    }
}

enum Outcome {
    Closed(usize, Option<String>),
    Runaway,
    Refused(&'static str),
    OverLimit,
}

/// What one worker saw; merged at the end (the merge does not depend on the thread count).
#[derive(Default)]
struct Tally {
    faces: usize,
    closed: usize,
    runaway: usize,
    refused: usize,
    over_limit: usize,
    distribution: BTreeMap<usize, usize>,
    /// Largest closure: (types, index in the family order, face).
    largest: Option<(usize, usize, Face)>,
    /// Every face with its index in the family order, when the spec asks for them.
    per_face: Vec<(usize, CensusFace)>,
}

impl Tally {
    fn add(&mut self, index: usize, face: Face, outcome: Outcome, per_face: bool) {
        self.faces += 1;
        if per_face {
            let (verdict, code, types, ratio) = match &outcome {
                Outcome::Closed(n, ratio) => ("closed", None, Some(*n), ratio.clone()),
                Outcome::Runaway => ("runaway", None, None, None),
                Outcome::Refused(code) => ("refused", Some(*code), None, None),
                Outcome::OverLimit => ("over-limit", Some("E0501"), None, None),
            };
            self.per_face.push((
                index,
                CensusFace {
                    face: face.to_string(),
                    verdict,
                    code,
                    types,
                    ratio,
                },
            ));
        }
        match outcome {
            Outcome::Closed(n, _) => {
                self.closed += 1;
                *self.distribution.entry(n).or_default() += 1;
                self.offer_largest(n, index, face);
            }
            Outcome::Runaway => self.runaway += 1,
            Outcome::Refused(_) => self.refused += 1,
            Outcome::OverLimit => self.over_limit += 1,
        }
    }

    /// Keeps the largest closure; ties go to the face first in the family order.
    fn offer_largest(&mut self, n: usize, index: usize, face: Face) {
        let better = match &self.largest {
            None => true,
            Some((m, i, _)) => n > *m || (n == *m && index < *i),
        };
        if better {
            self.largest = Some((n, index, face));
        }
    }

    fn merge(&mut self, other: Tally) {
        self.faces += other.faces;
        self.closed += other.closed;
        self.runaway += other.runaway;
        self.refused += other.refused;
        self.over_limit += other.over_limit;
        for (n, c) in other.distribution {
            *self.distribution.entry(n).or_default() += c;
        }
        if let Some((n, i, f)) = other.largest {
            self.offer_largest(n, i, f);
        }
        self.per_face.extend(other.per_face);
    }
}

/// Faces handed to a worker at a time.
const BATCH: usize = 256;

/// Runs the census. The family is streamed: workers take batches of faces from one shared
/// enumeration and keep only their tallies, so memory does not grow with the family.
pub fn census(spec: &CensusSpec, limits: &Limits) -> CensusReport {
    let start = Instant::now();
    let family = Mutex::new(spec.faces().enumerate());
    let total = Mutex::new(Tally::default());
    let bar = Mutex::new(crate::progress::Progress::with_step(
        "census",
        spec.family_size(),
        16,
    ));
    std::thread::scope(|s| {
        for _ in 0..spec.threads {
            s.spawn(|| {
                let mut tally = Tally::default();
                loop {
                    let batch: Vec<(usize, Face)> = family
                        .lock()
                        .expect("no worker panics")
                        .by_ref()
                        .take(BATCH)
                        .collect();
                    if batch.is_empty() {
                        break;
                    }
                    let n = batch.len() as u64;
                    for (i, face) in batch {
                        let outcome = match Closure::of(std::slice::from_ref(&face), limits) {
                            Ok(Closure::Closed(ts)) => {
                                let c = counts(&ts, spec.levels);
                                debug_assert_eq!(c.len() as u64, spec.levels + 1);
                                let ratio = if spec.per_face {
                                    exact_ratio(&ts)
                                } else {
                                    None
                                };
                                Outcome::Closed(ts.types.len(), ratio)
                            }
                            Ok(Closure::Runaway(_)) => Outcome::Runaway,
                            Err(e) if e.code() == "E0501" => Outcome::OverLimit,
                            Err(e) => Outcome::Refused(e.code()),
                        };
                        tally.add(i, face, outcome, spec.per_face);
                    }
                    bar.lock().expect("no worker panics").add(n);
                }
                total.lock().expect("no worker panics").merge(tally);
            });
        }
    });
    let elapsed = start.elapsed().as_secs_f64();
    let mut t = total.into_inner().expect("no worker panics");
    // Every face in the family's order, whatever the thread count.
    t.per_face.sort_by_key(|(i, _)| *i);
    CensusReport {
        faces: t.faces,
        closed: t.closed,
        runaway: t.runaway,
        refused: t.refused,
        over_limit: t.over_limit,
        distribution: t.distribution,
        largest: t.largest.map(|(n, _, f)| (f.to_string(), n)),
        per_face: t.per_face.into_iter().map(|(_, f)| f).collect(),
        threads: spec.threads,
        elapsed_seconds: elapsed,
    }
}

/// The exact limit ratio of a one-face closure, when it exists (and the analysis succeeds).
fn exact_ratio(ts: &crate::topology::closure::TypeSet) -> Option<String> {
    let c: Vec<num_rational::BigRational> = ts
        .types
        .iter()
        .map(|t| num_rational::BigRational::new(t.contribution_halves().into(), 2.into()))
        .collect();
    crate::analysis::ratio::analyse(&ts.matrix(), &c, &[(ts.start[0], 1)])
        .ok()
        .and_then(|r| r.exact)
}

impl CensusReport {
    /// The human-readable table.
    pub fn to_text(&self) -> String {
        let mut o = format!(
            "census: {} face{} — {} closed, {} runaway, {} refused (no spoke){}\n",
            self.faces,
            if self.faces == 1 { "" } else { "s" },
            self.closed,
            self.runaway,
            self.refused,
            if self.over_limit > 0 {
                format!(
                    ", {} over a limit (raise it to survey them)",
                    self.over_limit
                )
            } else {
                String::new()
            }
        );
        o += "types  faces\n";
        for (t, n) in &self.distribution {
            o += &format!("{t:>5}  {n}\n");
        }
        if let Some((f, n)) = &self.largest {
            o += &format!(
                "largest closure: {n} type{}, from `{f}`\n",
                if *n == 1 { "" } else { "s" }
            );
        }
        let rate = self.faces as f64 / self.elapsed_seconds.max(1e-9);
        o += &format!(
            "{:.2} s on {} thread{}: {:.0} faces/s, {:.0} faces/s per thread\n",
            self.elapsed_seconds,
            self.threads,
            if self.threads == 1 { "" } else { "s" },
            rate,
            rate / self.threads as f64
        );
        o
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn family_size_is_the_necklace_count() {
        // Necklaces (rotation classes) over 2 letters: lengths 1..4 give 2, 3, 4, 6 = 15.
        let spec = CensusSpec::parse("B2,C2", "B2", "A1", 4, Some(1)).unwrap();
        assert_eq!(spec.faces().count(), 15);
        assert_eq!(spec.family_size(), 15);
        // Over 4 letters up to length 3: 4 + 10 + 24 = 38; × 2³ E × 2 algorithms.
        let spec = CensusSpec::parse("B2,C2,B3,C3", "B2,C2", "A1,A2", 3, Some(2)).unwrap();
        assert_eq!(spec.faces().count(), 38 * 8 * 2);
        assert_eq!(spec.family_size(), 38 * 8 * 2);
        let r = census(&spec, &Limits::default());
        assert_eq!(r.closed + r.runaway + r.refused, r.faces);
        assert_eq!(r.runaway, 0, "built-in algorithms always close");
        assert!(r.per_face.is_empty());
    }

    #[test]
    fn per_face_gives_types_ratio_and_verdict() {
        let mut spec = CensusSpec::parse("B2,C2", "C2,B2", "A1,{joint}", 2, Some(1)).unwrap();
        spec.per_face = true;
        let r = census(&spec, &Limits::default());
        assert_eq!(r.per_face.len(), r.faces);
        let f0_like = r
            .per_face
            .iter()
            .find(|f| f.face == "B2 C2 | C2 B2 B2 | A1")
            .unwrap();
        assert_eq!(f0_like.verdict, "closed");
        assert!(f0_like.ratio.is_some() && f0_like.types.is_some());
        // {joint} on a boundary of Cantor edges only: no spoke.
        let c = r
            .per_face
            .iter()
            .find(|f| f.face == "C2 | C2 B2 B2 | {joint}")
            .unwrap();
        assert_eq!((c.verdict, c.code), ("refused", Some("E0401")));
        let closed = r.per_face.iter().filter(|f| f.verdict == "closed").count();
        assert_eq!(closed, r.closed);
    }
}
