//! The independent checker: re-verifies a [`Certificate`] without trusting lacuna's code.
//!
//! It may use only the `certificate` module (plain data), std, the num crates and serde_json; a test
//! (`tests/certificates.rs`) reads every file of this directory and fails on any other path into
//! lacuna. Everything it needs is re-implemented here, small, one file per concern:
//!
//! - `closure.rs`: the subdivision of a face (SPEC §3), incidence identities, contributions;
//! - `system.rs`: the constraint system of a closure (SPEC §6) rebuilt from the closure step;
//! - `linear.rs`: exact linear checks and elimination modulo primes;
//! - `field.rs`: polynomials over Q, Sturm isolation, exact zero and sign tests in Q[x]/(p);
//! - `ratio.rs`: strongly connected classes and periods, Perron–Frobenius witnesses, the verdict;
//! - `series.rs`: the counts, the characteristic polynomial of `A^P` (Faddeev–LeVerrier, Newton)
//!   and the pole of the generating functions at `ρ^(−P)`.
//!
//! What each step proves is documented on [`Step`] and in `docs/CERTIFICATES.md`.

mod closure;
mod field;
mod linear;
mod ratio;
mod series;
mod system;

use self::closure::{check_closure, Substitution};
use self::linear::{check_conflict, check_solution};
use self::ratio::check_ratio;
use crate::certificate::{Certificate, Step, FORMAT, VERSION};
use num_rational::BigRational;

/// The verdict on one step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// The step's claim is proved.
    Proved,
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

fn header_fail(m: String) -> CheckReport {
    CheckReport {
        steps: vec![StepReport {
            step: "header".into(),
            outcome: Outcome::Failed,
            message: format!("header: {m}"),
        }],
    }
}

/// The refusal of a certificate of another format or version.
fn wrong_version(format: &str, version: &str) -> Option<CheckReport> {
    if format != FORMAT {
        return Some(header_fail(format!(
            "format `{format}` is not `{FORMAT}`: not a lacuna certificate"
        )));
    }
    (version != VERSION.to_string()).then(|| {
        header_fail(format!(
            "unknown certificate version {version}: this checker reads version {VERSION} only \
             (regenerate the certificate with `lacuna verify --certificate`)"
        ))
    })
}

/// Checks a certificate given as JSON text (a parse error is a failed `header`). The format and
/// version are read first, so a certificate of another version is refused by name rather than
/// by a parse error in a step whose form changed.
pub fn check_json(text: &str) -> CheckReport {
    if let Ok(v) = serde_json::from_str::<serde_json::Value>(text) {
        let field = |k: &str| {
            v.get(k)
                .map(|x| x.to_string().trim_matches('"').to_string())
        };
        if let (Some(f), Some(ver)) = (field("format"), field("version")) {
            if let Some(report) = wrong_version(&f, &ver) {
                return report;
            }
        }
    }
    match Certificate::from_json(text) {
        Ok(c) => check(&c),
        Err(e) => header_fail(format!("not a certificate: {e}")),
    }
}

/// Checks every step of a certificate.
pub fn check(cert: &Certificate) -> CheckReport {
    if let Some(report) = wrong_version(&cert.format, &cert.version.to_string()) {
        return report;
    }
    if cert.steps.is_empty() {
        return header_fail("the certificate has no step".into());
    }
    let mut steps = Vec::new();
    let mut closure: Option<Substitution> = None;
    let mut proved_closure = None;
    for (i, step) in cert.steps.iter().enumerate() {
        let name = step.name();
        let (outcome, result) = match step {
            Step::Closure(c) => match check_closure(c) {
                Ok((msg, sub)) => {
                    closure = Some(sub);
                    proved_closure = Some(c);
                    (Outcome::Proved, Ok(msg))
                }
                Err(e) => (Outcome::Failed, Err(e)),
            },
            Step::SolutionSpace(s) => (Outcome::Proved, check_solution(s, proved_closure)),
            Step::Inconsistent(c) => (Outcome::Proved, check_conflict(c, proved_closure)),
            Step::LimitRatio(r) => (Outcome::Proved, check_ratio(r, closure.as_ref())),
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

fn rat(s: &str) -> Result<Q, String> {
    s.parse::<Q>()
        .map_err(|_| format!("`{s}` is not a rational"))
}
