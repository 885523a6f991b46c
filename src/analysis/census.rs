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
use std::sync::atomic::{AtomicUsize, Ordering};
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
    /// `closed`, `runaway` or `refused`.
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
        out.push(f(t, col).map_err(|e| e.within(&crate::error::Source::command_line(text), 1, 0))?);
        col += item.chars().count() + 1;
    }
    Ok(out)
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

    /// Every face of the family: canonical boundaries (one per rotation class) × E × A.
    pub fn faces(&self) -> Vec<Face> {
        let mut boundaries: Vec<Vec<EdgeType>> = Vec::new();
        let k = self.edges.len();
        for len in 1..=self.max_length {
            let mut digits = vec![0usize; len];
            loop {
                if least_rotation(&digits) == 0 {
                    boundaries.push(digits.iter().map(|&d| self.edges[d]).collect());
                }
                // Next word in base k.
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
        let mut faces = Vec::new();
        for b in &boundaries {
            for &ea in &self.params {
                for &el in &self.params {
                    for &ec in &self.params {
                        for a in &self.algorithms {
                            faces.push(Face {
                                boundary: b.clone(),
                                params: Params { ea, el, ec },
                                algorithm: a.clone(),
                                delay: 1,
                            });
                        }
                    }
                }
            }
        }
        faces
    }
}

enum Outcome {
    Closed(usize, Option<String>),
    Runaway,
    Refused(&'static str),
}

/// Runs the census.
pub fn census(spec: &CensusSpec, limits: &Limits) -> CensusReport {
    let faces = spec.faces();
    let start = Instant::now();
    let next = AtomicUsize::new(0);
    let results: Mutex<Vec<Option<Outcome>>> = Mutex::new((0..faces.len()).map(|_| None).collect());
    let bar = Mutex::new(crate::progress::Progress::with_step(
        "census",
        faces.len() as u64,
        16,
    ));
    std::thread::scope(|s| {
        for _ in 0..spec.threads {
            s.spawn(|| loop {
                let i = next.fetch_add(1, Ordering::Relaxed);
                if i >= faces.len() {
                    break;
                }
                let outcome = match Closure::of(std::slice::from_ref(&faces[i]), limits) {
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
                    Err(e) => Outcome::Refused(e.code()),
                };
                results.lock().expect("no worker panics")[i] = Some(outcome);
                bar.lock().expect("no worker panics").tick();
            });
        }
    });
    let elapsed = start.elapsed().as_secs_f64();
    let results = results.into_inner().expect("no worker panics");
    let mut report = CensusReport {
        faces: faces.len(),
        closed: 0,
        runaway: 0,
        refused: 0,
        distribution: BTreeMap::new(),
        largest: None,
        per_face: Vec::new(),
        threads: spec.threads,
        elapsed_seconds: elapsed,
    };
    for (face, r) in faces.iter().zip(results) {
        let r = r.expect("every face was surveyed");
        if spec.per_face {
            let (verdict, code, types, ratio) = match &r {
                Outcome::Closed(n, ratio) => ("closed", None, Some(*n), ratio.clone()),
                Outcome::Runaway => ("runaway", None, None, None),
                Outcome::Refused(code) => ("refused", Some(*code), None, None),
            };
            report.per_face.push(CensusFace {
                face: face.to_string(),
                verdict,
                code,
                types,
                ratio,
            });
        }
        match r {
            Outcome::Closed(n, _) => {
                report.closed += 1;
                *report.distribution.entry(n).or_default() += 1;
                if report.largest.as_ref().is_none_or(|(_, m)| n > *m) {
                    report.largest = Some((face.to_string(), n));
                }
            }
            Outcome::Runaway => report.runaway += 1,
            Outcome::Refused(_) => report.refused += 1,
        }
    }
    report
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
            "census: {} faces — {} closed, {} runaway, {} refused (no spoke)\n",
            self.faces, self.closed, self.runaway, self.refused
        );
        o += "types  faces\n";
        for (t, n) in &self.distribution {
            o += &format!("{t:>5}  {n}\n");
        }
        if let Some((f, n)) = &self.largest {
            o += &format!("largest closure: {n} types, from `{f}`\n");
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
        assert_eq!(spec.faces().len(), 15);
        // Over 4 letters up to length 3: 4 + 10 + 24 = 38; × 2³ E × 2 algorithms.
        let spec = CensusSpec::parse("B2,C2,B3,C3", "B2,C2", "A1,A2", 3, Some(2)).unwrap();
        assert_eq!(spec.faces().len(), 38 * 8 * 2);
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
