//! The independent checker: re-verifies a [`Certificate`] without trusting lacuna's code.
//!
//! It may use only the `certificate` module (plain data), std, the num crates and serde_json; a test
//! (`tests/certificates.rs`) reads every file of this directory and fails on any other path into
//! lacuna. Everything it needs is re-implemented here, small, one file per concern:
//!
//! - `claim.rs`: the claim printed first, the fixed structure of the steps, strict numbers;
//! - `closure.rs`: the subdivision of a face (THEORY §3), incidence identities, contributions;
//! - `automaton.rs`: the linear system of a hand-written automaton, rebuilt from its words;
//! - `system.rs`: the constraint system of a closure (THEORY §6) rebuilt from the closure step;
//! - `linear.rs`: exact linear checks and elimination modulo primes;
//! - `degeneracy.rs`: the corners of every type's level-1 complex that the proved solution set
//!   forces to coincide, and the cells forced flat;
//! - `level_one.rs`: a chosen point of the proved solution set at which every level-1 control
//!   polygon has positive area in the given frames;
//! - `ifs.rs`: an automaton's field K, its matrices, its operators' values and its constraints
//!   evaluated in K;
//! - `control_graph.rs`: the control graph of an automaton's attractor, its cyclic parts;
//! - `contraction.rs`: the contraction of every walk of the control graph (a complete prefix code
//!   of walks of norm below 1);
//! - `similarity.rs`: the similarity dimension of the attractor (Mauldin–Williams) and what the
//!   parts' open-set witnesses make of it;
//! - `convex_open_set.rs`: the open-set condition of a part witnessed by convex sets in the
//!   states' charts;
//! - `enclosure.rs`: rational enclosures of numbers of K, of roots and of logarithms;
//! - `neighbour.rs`: the open-set condition of a part decided by neighbour maps (a closed set
//!   without the identity, or two words with one map), exactly in the automaton's field;
//! - `field.rs`: polynomials over Q, Sturm isolation, exact zero and sign tests in Q[x]/(p);
//! - `ratio.rs`: strongly connected classes and periods, Perron–Frobenius witnesses, the verdict;
//! - `series.rs`: the counts, the characteristic polynomial of `A^P` (Faddeev–LeVerrier, Newton)
//!   and the pole of the generating functions at `ρ^(−P)`;
//! - `volume.rs`: oriented maps (sphere check, canonical code) and one subdivision step of a
//!   volume (THEORY §10), the volume types and their counts.
//! - `rule.rs`: a rule text read and compiled again, compared with the claim's automaton.
//! - `choice.rs`: a rule's age and random choices (ages, seeded SplitMix64 draws, the states
//!   of occurrences above the depth and their bound);
//! - `volume_system.rs`: the volume constraint system rebuilt from the step's own derivation;
//!   `volume_points.rs`: its volume points in frames, level 1, placements proved as isomorphisms;
//! - `solid.rs`: the level-n solid built cell by cell, its cells, χ and Betti numbers (ranks
//!   of boundary matrices over F2);
//! - `solid_recurrence.rs`: the solid's cells, χ and components at every level, by the
//!   recurrence of cells by birth whose table it derives from one step of each type's complex.
//!
//! What each step proves is documented on [`Step`] and in `docs/CERTIFICATES.md`. No value read
//! from a certificate, or derived from one, is held in a fixed-width integer that could wrap:
//! counts, multiplicities, periods and their lcm are big integers, indices are compared with the
//! length they index before use, and sizes are multiplied with checked arithmetic.
//!
//! [`Step`]: crate::certificate::Step

mod automaton;
mod boundary;
mod choice;
mod claim;
mod closure;
mod contraction;
mod control_graph;
mod convex_open_set;
mod degeneracy;
mod enclosure;
mod face_homology;
mod field;
mod ifs;
mod level_one;
mod linear;
mod multiplicity;
mod neighbour;
mod ranks;
mod ratio;
mod rule;
mod series;
mod similarity;
mod solid;
mod solid_recurrence;
mod system;
mod volume;
mod volume_points;
mod volume_system;

use self::claim::{claim_lines, structure};
use self::closure::{check_closure, Substitution};
use self::linear::{check_conflict, check_solution};
use self::ratio::check_ratio;
use self::system::Tie;
use self::volume::check_volume_closure;
use crate::certificate::{Certificate, Claim, Step, FORMAT, VERSION};
use num_rational::BigRational;

pub use self::claim::{escape, parse_decimal, parse_rational};

/// The verdict on one step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// The step's claim is proved.
    Proved,
    /// The step does not prove its claim.
    Failed,
    /// The step was not checked: its estimated cost exceeds a [`Budget`] (E0501, naming the
    /// figure and the flag that raises it), or an earlier step was refused so. Not a verdict:
    /// the certificate may be right or wrong.
    Refused,
}

/// What the checker may spend on one certificate. Before each phase it estimates the work from
/// the sizes it has already read (matrix dimension, degree, period, number of residues, boundary
/// lengths, pivots) and refuses the step for cost when an estimate exceeds its budget; phases
/// whose cost cannot be foreseen (elimination with fill-in, products of operators) count their
/// work as they go and stop at the budget. The default work budget is two to four seconds
/// of a release build (`docs/CERTIFICATES.md` gives what was measured); `lacuna check
/// --max-work`, `--max-levels`, `--max-sides` raise the budgets.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Budget {
    /// The most big-integer word operations of the whole check, estimated or metered
    /// (`--max-work`).
    pub work: u128,
    /// The most levels of counts: `P·d` for a limit ratio, the claimed levels of a volume
    /// closure (`--max-levels`).
    pub levels: u64,
    /// The most sides of the level-1 surfaces of all listed volume types together, the work of
    /// re-deriving them (`--max-sides`).
    pub sides: u128,
}

impl Default for Budget {
    fn default() -> Self {
        Budget {
            work: 10_000_000_000,
            levels: 20_000,
            sides: 400_000,
        }
    }
}

thread_local! {
    /// The budget of the check running on this thread (set by [`check_with`]).
    static BUDGET: std::cell::Cell<Budget> = std::cell::Cell::new(Budget::default());
    /// Set when the current step was refused for cost: kept out of the messages, so that no
    /// text read from a certificate can make a rejection look like a refusal or the reverse.
    static OVER: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
    /// The first refusal for cost of the current step.
    static REFUSAL: std::cell::RefCell<String> = const { std::cell::RefCell::new(String::new()) };
    /// The word operations charged to the check running on this thread.
    static SPENT: std::cell::Cell<u128> = const { std::cell::Cell::new(0) };
}

/// `1 cell`, `2 cells`: a count with its noun in the right number. The checker's own copy of
/// the producer's helper (`crate::error::counted`): it imports nothing outside `certificate`.
pub(super) fn counted(n: impl std::fmt::Display, one: &str, many: &str) -> String {
    match n.to_string() {
        t if t == "1" => format!("1 {one}"),
        t => format!("{t} {many}"),
    }
}

/// The budget in force.
pub(super) fn budget() -> Budget {
    BUDGET.with(std::cell::Cell::get)
}

/// Refuses the current step for cost: `what` needs about `figure` (of the unit the flag
/// counts), above `limit`. Returns the message (E0501, the figure, the flag).
pub(super) fn over(what: &str, figure: u128, limit: u128, flag: &str) -> String {
    let m = format!(
        "E0501 refused for cost, not a verdict: {what} needs about {figure}, above the budget of \
         {limit} (raise it with `lacuna check --{flag} N`)"
    );
    if !OVER.with(|o| o.replace(true)) {
        REFUSAL.with(|r| *r.borrow_mut() = m.clone());
    }
    m
}

/// Charges `work` word operations where a phase cannot stop with an error (arithmetic in
/// Q[x]/(p)): false once the budget is exceeded, and the loop that asked stops early. Whatever
/// the step then returns, it is refused for cost (the checker reads the mark, not the result).
pub(super) fn charge(what: &str, work: u128) -> bool {
    within_work(what, work).is_ok()
}

/// Charges `work` word operations to the certificate's account (an estimate before a phase, or
/// one metered product) and refuses when the account exceeds the work budget: the budget bounds
/// the whole check, not each phase, so a certificate of many classes or residues cannot buy
/// unbounded work a phase at a time.
pub(super) fn within_work(what: &str, work: u128) -> Result<(), String> {
    let limit = budget().work;
    let total = SPENT.with(|s| {
        let t = s.get().saturating_add(work);
        s.set(t);
        t
    });
    match total <= limit {
        true => Ok(()),
        false => Err(over(
            &format!("the check, at {what}, (word operations)"),
            total,
            limit,
            "max-work",
        )),
    }
}

/// What the checker concluded about one step.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StepReport {
    /// The step's name (`closure`, `solution-space`, `inconsistent`, `limit-ratio`, or `header`
    /// and `structure` for a certificate refused as a whole).
    pub step: String,
    /// The verdict.
    pub outcome: Outcome,
    /// What was proved, or why it failed, naming the step.
    pub message: String,
    /// The short statement the step proves about the claim (`None` when it failed).
    pub verdict: Option<String>,
}

/// The checker's report: the claim, then one entry per step.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CheckReport {
    /// The claim, as printed first (one line per item); empty when the header was refused.
    pub claim: Vec<String>,
    /// The steps, in certificate order.
    pub steps: Vec<StepReport>,
    /// The steps the claim needs that the certificate does not have (a *partial* certificate).
    pub missing: Vec<String>,
}

impl CheckReport {
    /// True when every step is proved and none is missing: the only outcome `lacuna check`
    /// accepts (exit 0).
    pub fn all_proved(&self) -> bool {
        !self.steps.is_empty()
            && self.steps.iter().all(|s| s.outcome == Outcome::Proved)
            && self.missing.is_empty()
    }

    /// True when some step failed (exit 1).
    pub fn failed(&self) -> bool {
        self.steps.iter().any(|s| s.outcome == Outcome::Failed)
    }

    /// True when nothing failed but a step was refused for cost (exit 2): no verdict.
    pub fn refused(&self) -> bool {
        !self.failed() && self.steps.iter().any(|s| s.outcome == Outcome::Refused)
    }

    /// True when nothing failed or was refused but steps the claim needs are missing: the
    /// certificate proves part of its claim only (`lacuna check` exits 3).
    pub fn partial(&self) -> bool {
        !self.failed() && !self.refused() && !self.missing.is_empty()
    }

    /// The report for one step name (the first with that name).
    pub fn step(&self, name: &str) -> Option<&StepReport> {
        self.steps.iter().find(|s| s.step == name)
    }

    /// What `check` states about the input: the claim lines and the verdict of every proved
    /// step. Two certificates that both check state the same thing iff these are equal.
    pub fn claims(&self) -> Vec<String> {
        let verdicts = self.steps.iter().filter_map(|s| s.verdict.clone());
        self.claim.iter().cloned().chain(verdicts).collect()
    }

    /// The claim, then one line per step, then the partial notice if any.
    pub fn to_text(&self) -> String {
        let mut o = String::new();
        for c in &self.claim {
            o += &format!("{:>13}  {c}\n", "claim");
        }
        for s in &self.steps {
            let v = match s.outcome {
                Outcome::Proved => "proved",
                Outcome::Failed => "FAILED",
                Outcome::Refused => "REFUSED",
            };
            o += &format!("{v:>13}  {}\n", s.message);
        }
        // What is proved, in one line each, once every step is.
        if !self.failed() && !self.refused() {
            for v in self.steps.iter().filter_map(|s| s.verdict.as_deref()) {
                o += &format!("{:>13}  {v}\n", "verdict");
            }
        }
        if self.partial() {
            o += &format!(
                "{:>13}  the certificate proves only part of its claim: no {} step\n",
                "PARTIAL",
                self.missing.join(", no ")
            );
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
                    Outcome::Refused => "refused",
                };
                serde_json::json!({"step": s.step, "outcome": outcome, "message": s.message,
                                   "verdict": s.verdict})
            })
            .collect();
        serde_json::json!({"all_proved": self.all_proved(), "partial": self.partial(),
                           "refused": self.refused(),
                           "claim": self.claim, "missing": self.missing, "steps": steps})
    }
}

type Q = BigRational;
/// A step's result: `(report message, verdict)` or why it failed.
type Checked = Result<(String, String), String>;
/// A parsed row: `(unknown, coefficient)` terms and the right-hand side.
type Equation = (Vec<(usize, Q)>, Q);

fn refused(step: &str, claim: Vec<String>, m: String) -> CheckReport {
    CheckReport {
        claim,
        steps: vec![StepReport {
            step: step.into(),
            outcome: Outcome::Failed,
            message: format!("{step}: {m}"),
            verdict: None,
        }],
        missing: Vec::new(),
    }
}

/// The refusal of a certificate of another format or version.
fn wrong_version(format: &str, version: &str) -> Option<CheckReport> {
    if format != FORMAT {
        return Some(refused(
            "header",
            Vec::new(),
            format!("format `{format}` is not `{FORMAT}`: not a lacuna certificate"),
        ));
    }
    (version != VERSION.to_string()).then(|| {
        refused(
            "header",
            Vec::new(),
            format!(
                "unknown certificate version {version}: this checker reads version {VERSION} \
                 only (regenerate the certificate with `lacuna verify --certificate`)"
            ),
        )
    })
}

/// Checks a certificate given as JSON text (a parse error, an unknown field included, is a
/// failed `header`). The format and version are read first, so a certificate of another version
/// is refused by name rather than by a parse error in a step whose form changed.
pub fn check_json(text: &str) -> CheckReport {
    check_json_with(text, Budget::default())
}

/// [`check_json`] within the given budget.
pub fn check_json_with(text: &str, budget: Budget) -> CheckReport {
    if let Ok(v) = serde_json::from_str::<serde_json::Value>(text) {
        let field = |k: &str| {
            v.get(k)
                .map(|x| x.to_string().trim_matches('"').to_string())
        };
        if let (Some(f), Some(ver)) = (field("format"), field("version")) {
            if let Some(report) = wrong_version(&f, &ver) {
                return escaped(report);
            }
        }
    }
    match Certificate::from_json(text) {
        Ok(c) => check_with(&c, budget),
        Err(e) => escaped(refused(
            "header",
            Vec::new(),
            format!("not a certificate: {e}"),
        )),
    }
}

/// Checks a certificate: prints its claim, checks that its steps have the structure the claim
/// demands (else it is refused as a whole), then checks every step, each tied to the claim or
/// to the closure step.
pub fn check(cert: &Certificate) -> CheckReport {
    check_with(cert, Budget::default())
}

/// [`check`] within the given budget: a step whose estimated cost exceeds it is refused for
/// cost (E0501), and the steps after it are not checked.
pub fn check_with(cert: &Certificate, budget: Budget) -> CheckReport {
    let before = BUDGET.with(|b| b.replace(budget));
    let spent = SPENT.with(|s| s.replace(0));
    let report = escaped(check_unescaped(cert));
    BUDGET.with(|b| b.set(before));
    SPENT.with(|s| s.set(spent));
    report
}

/// The report with every line [`escape`]d: the claim, the messages and the verdicts all carry
/// text read from the file.
fn escaped(r: CheckReport) -> CheckReport {
    CheckReport {
        claim: r.claim.iter().map(|c| escape(c)).collect(),
        steps: r
            .steps
            .into_iter()
            .map(|s| StepReport {
                message: escape(&s.message),
                verdict: s.verdict.as_deref().map(escape),
                ..s
            })
            .collect(),
        missing: r.missing,
    }
}

fn check_unescaped(cert: &Certificate) -> CheckReport {
    if let Some(report) = wrong_version(&cert.format, &cert.version.to_string()) {
        return report;
    }
    let claim = claim_lines(&cert.claim);
    let missing = match structure(&cert.claim, &cert.steps) {
        Ok(m) => m,
        Err(e) => return refused("structure", claim, e),
    };
    // An automaton's field, values in it and attractor must be well formed whatever steps
    // follow: no step may be accepted about a claim that names nothing.
    if let Claim::Automaton(a) = &cert.claim {
        if let Err(e) = self::ifs::well_formed(a) {
            return refused("structure", claim, format!("the claimed automaton: {e}"));
        }
    }
    let mut steps = Vec::new();
    let mut closure: Option<(Substitution, &crate::certificate::ClosureStep)> = None;
    let mut volumes: Option<Substitution> = None;
    let mut volume_closure: Option<&crate::certificate::VolumeClosureStep> = None;
    let mut volume_system: Option<&crate::certificate::VolumeSystemStep> = None;
    let mut solution: Option<&crate::certificate::SolutionStep> = None;
    // The proved similarity step and its parts' graphs of neighbour maps.
    let mut similarity: Option<(
        &crate::certificate::SimilarityStep,
        Vec<Option<self::neighbour::Refinements>>,
    )> = None;
    let given = match &cert.claim {
        Claim::Substitution(s) => Some(Substitution::of_claim(s)),
        Claim::Faces(_) | Claim::Automaton(_) | Claim::System(_) | Claim::Volumes(_) => None,
    };
    let mut refused_at: Option<usize> = None;
    for (i, step) in cert.steps.iter().enumerate() {
        let name = step.name();
        if let Some(j) = refused_at {
            steps.push(StepReport {
                step: name.into(),
                outcome: Outcome::Refused,
                message: format!("step {i} ({name}): not checked, step {j} was refused for cost"),
                verdict: None,
            });
            continue;
        }
        OVER.with(|o| o.set(false));
        let tie = match (&cert.claim, &closure) {
            (Claim::Faces(f), Some((_, c))) => Tie::Closure {
                closure: c,
                degree: f.degree,
                gap: &f.cantor_gap,
            },
            (Claim::Faces(_), None) => Tie::Missing,
            (Claim::Automaton(a), _) => Tie::Automaton(a),
            (Claim::System(s), _) => Tie::Given(s),
            (Claim::Substitution(_) | Claim::Volumes(_), _) => Tie::Missing,
        };
        let result = match step {
            Step::Closure(c) => match &cert.claim {
                Claim::Faces(f) => check_closure(c, &f.faces).map(|(msg, verdict, sub)| {
                    closure = Some((sub, c));
                    (msg, verdict)
                }),
                _ => Err("a closure step in a certificate whose claim has no faces".into()),
            },
            Step::VolumeClosure(c) => match &cert.claim {
                Claim::Volumes(v) => check_volume_closure(c, v).map(|(msg, verdict, sub)| {
                    volumes = Some(sub);
                    volume_closure = Some(c);
                    (msg, verdict)
                }),
                _ => {
                    Err("a volume-closure step in a certificate whose claim has no volumes".into())
                }
            },
            Step::RuleCompilation(_) => match &cert.claim {
                Claim::Automaton(a) => self::rule::check_rule_compilation(a),
                _ => Err(
                    "a rule-compilation step in a certificate whose claim is no automaton".into(),
                ),
            },
            Step::FaceHomology(s) => match &cert.claim {
                Claim::Faces(f) => self::face_homology::check_face(s, f),
                _ => Err("a face-homology step in a certificate whose claim has no faces".into()),
            },
            Step::SolidHomology(s) => match &cert.claim {
                Claim::Volumes(v) => self::solid::check_solid(s, v),
                _ => {
                    Err("a solid-homology step in a certificate whose claim has no volumes".into())
                }
            },
            Step::SolidRecurrence(s) => match &cert.claim {
                Claim::Volumes(v) => {
                    self::solid_recurrence::check_solid_recurrence(s, volume_closure, v)
                }
                _ => Err(
                    "a solid-recurrence step in a certificate whose claim has no volumes".into(),
                ),
            },
            Step::VolumeSolutionSpace(s) => match &cert.claim {
                Claim::Volumes(v) => self::volume_system::check_volume_system(s, volume_closure, v)
                    .inspect(|_| volume_system = Some(s)),
                _ => Err(
                    "a volume-solution-space step in a certificate whose claim has no volumes"
                        .into(),
                ),
            },
            Step::ConstraintsHold(s) => match &cert.claim {
                Claim::Automaton(a) => self::ifs::check_constraints_hold(a, s.constraints),
                _ => Err(
                    "a constraints-hold step in a certificate whose claim is no automaton".into(),
                ),
            },
            Step::ConstraintFails(s) => match &cert.claim {
                Claim::Automaton(a) => self::ifs::check_constraint_fails(a, s),
                _ => Err(
                    "a constraint-fails step in a certificate whose claim is no automaton".into(),
                ),
            },
            Step::Contraction(s) => match &cert.claim {
                Claim::Automaton(a) => self::contraction::check_contraction(a, s),
                _ => Err("a contraction step in a certificate whose claim is no automaton".into()),
            },
            Step::SimilarityDimension(s) => match &cert.claim {
                Claim::Automaton(a) => {
                    self::similarity::check_similarity(a, s).map(|(m, v, graphs)| {
                        similarity = Some((s, graphs));
                        (m, v)
                    })
                }
                _ => Err(
                    "a similarity-dimension step in a certificate whose claim is no automaton"
                        .into(),
                ),
            },
            Step::BoundaryDimension(b) => match &cert.claim {
                Claim::Automaton(a) => self::boundary::check_boundary(a, similarity.as_ref(), b),
                _ => Err(
                    "a boundary-dimension step in a certificate whose claim is no automaton".into(),
                ),
            },
            Step::Multiplicity(m) => match &cert.claim {
                Claim::Automaton(a) => self::multiplicity::check_multiplicity(a, m),
                _ => Err("a multiplicity step in a certificate whose claim is no automaton".into()),
            },
            Step::SolutionSpace(s) => check_solution(s, tie).inspect(|_| solution = Some(s)),
            Step::Degeneracy(d) => match (&cert.claim, &closure, solution) {
                (Claim::Faces(f), Some((_, c)), Some(s)) => {
                    self::degeneracy::check_degeneracy(d, c, f.degree, s)
                }
                (Claim::Faces(_), _, _) => Err(
                    "no proved closure and solution-space steps to take the corners from".into(),
                ),
                (Claim::Volumes(_), _, _) => match volume_system {
                    Some(s) => self::degeneracy::check_volume_degeneracy(d, s),
                    None => {
                        Err("no proved volume-solution-space step to take the corners from".into())
                    }
                },
                _ => Err("a degeneracy step in a certificate whose claim has no faces".into()),
            },
            Step::LevelOne(l) => match (&cert.claim, &closure, solution) {
                (Claim::Faces(f), Some((_, c)), Some(s)) => {
                    self::level_one::check_level_one(l, c, f.degree, s)
                }
                (Claim::Faces(_), _, _) => {
                    Err("no proved closure and solution-space steps to take the cells from".into())
                }
                _ => Err("a level-one step in a certificate whose claim has no faces".into()),
            },
            Step::Inconsistent(c) => check_conflict(c, tie),
            Step::LimitRatio(r) => match (&given, &closure, &volumes) {
                (Some(Ok(sub)), _, _) => check_ratio(r, sub, "the claim's substitution"),
                (Some(Err(e)), _, _) => Err(format!("the claim's substitution: {e}")),
                (None, Some((sub, _)), _) => check_ratio(r, sub, "the closure's substitution"),
                (None, None, Some(sub)) => check_ratio(r, sub, "the volume closure's substitution"),
                (None, None, None) => {
                    Err("no proved closure step to take the substitution from".into())
                }
            },
        };
        let (outcome, message, verdict) = match result {
            _ if OVER.with(|o| o.replace(false)) => {
                refused_at = Some(i);
                let m = REFUSAL.with(|r| std::mem::take(&mut *r.borrow_mut()));
                (Outcome::Refused, m, None)
            }
            Ok((m, v)) => (Outcome::Proved, m, Some(v)),
            Err(m) => (Outcome::Failed, m, None),
        };
        steps.push(StepReport {
            step: name.into(),
            outcome,
            message: format!("step {i} ({name}): {message}"),
            verdict,
        });
    }
    CheckReport {
        claim,
        steps,
        missing,
    }
}

/// A rational in the certificate's strict form (see [`parse_rational`]).
fn rat(s: &str) -> Result<Q, String> {
    parse_rational(s)
}
