//! The certificate producer: writes lacuna's results (closure, solution space, limit ratio) as a
//! [`Certificate`] for the independent checker ([`crate::checker`]).
//!
//! This side may use all of lacuna: the certificate claims what lacuna computed, and the checker
//! re-verifies it without lacuna's code. The only new computations here are the witnesses the
//! checker needs and lacuna does not report: the left Perron eigenvector over Q(ρ) (exact
//! elimination in lacuna's number field) and the Collatz–Wielandt vectors of the other classes.

use crate::certificate::{
    Adjacency, Algebraic, Certificate, ClassClaim, ClosureStep, ConflictStep, Edge, Face, Kind,
    LimitProof, Origin, Params, Pattern, RatioClaim, RatioStep, Row, SolutionStep, SpokeItem, Step,
    SubFace, System, TypeRule,
};
use num_rational::BigRational;
use num_traits::{One, Zero};
use std::cmp::Ordering;

/// Why a certificate could not be produced.
#[derive(Debug, thiserror::Error)]
pub enum CertifyError {
    /// Certificate v1 writes algorithms as spoke sets; a custom chooser has no data form.
    #[error("face type `{face}` uses the custom algorithm `{algorithm}`, which certificate v1 cannot express")]
    CustomAlgorithm {
        /// The face.
        face: String,
        /// The algorithm's name.
        algorithm: String,
    },
    /// lacuna itself failed (linearising the automaton).
    #[error(transparent)]
    Lacuna(#[from] lacuna::Error),
    /// The eigen analysis failed.
    #[error(transparent)]
    Ratio(#[from] lacuna::RatioError),
    /// A witness could not be built (a disagreement inside lacuna's own results).
    #[error("no witness for the limit ratio: {0}")]
    Witness(String),
}

/// The full certificate of a closed type set: the closure, the solution space (or conflict) of
/// the generated constraint system, and the limit ratio.
pub fn certificate_for(
    input: &str,
    ts: &lacuna::TypeSet,
    opts: lacuna::GenOptions,
) -> Result<Certificate, CertifyError> {
    let mut cert = Certificate::new(input);
    cert.steps.push(Step::Closure(closure_step(ts)?));
    let source = format!(
        "the constraints of the automaton generated from the closure (SPEC §6, Bézier degree {}, Cantor gap/piece ratio {})",
        opts.degree, opts.cantor_gap
    );
    let generated = lacuna::automaton_of(ts, opts);
    let (_, lin, solution) = lacuna::solve_automaton(&generated.automaton)?;
    cert.steps
        .push(solution_step(&source, &lin.system, &solution));
    let matrix = ts.matrix();
    let c: Vec<u64> = ts.types.iter().map(|t| t.contribution_halves()).collect();
    let mut start: Vec<(usize, u64)> = Vec::new();
    for &t in &ts.start {
        match start.iter_mut().find(|(s, _)| *s == t) {
            Some(e) => e.1 += 1,
            None => start.push((t, 1)),
        }
    }
    start.sort_unstable();
    cert.steps
        .push(Step::LimitRatio(ratio_step(&matrix, &c, &start)?));
    Ok(cert)
}

/// The certificate of a hand-written automaton's constraint system.
pub fn certificate_for_automaton(
    name: &str,
    automaton: &lacuna::Automaton,
) -> Result<Certificate, CertifyError> {
    let (_, lin, solution) = lacuna::solve_automaton(automaton)?;
    let source = format!("the constraints of the automaton `{name}`");
    Ok(certificate_for_system(
        name,
        &source,
        &lin.system,
        &solution,
    ))
}

/// The certificate of an explicit linear system and lacuna's solution of it.
pub fn certificate_for_system(
    name: &str,
    source: &str,
    sys: &lacuna::LinearSystem,
    solution: &lacuna::Solution,
) -> Certificate {
    let mut cert = Certificate::new(name);
    cert.steps.push(solution_step(source, sys, solution));
    cert
}

fn edge(e: &lacuna::EdgeType) -> Edge {
    let kind = match e.kind {
        lacuna::EdgeKind::B => Kind::B,
        lacuna::EdgeKind::C => Kind::C,
    };
    Edge {
        kind,
        n: e.n,
        delay: e.delay,
    }
}

fn pattern(p: &lacuna::EdgePattern) -> Pattern {
    match p {
        lacuna::EdgePattern::Any => Pattern::Any,
        lacuna::EdgePattern::Kind(k) => Pattern::Kind(match k {
            lacuna::EdgeKind::B => Kind::B,
            lacuna::EdgeKind::C => Kind::C,
        }),
        lacuna::EdgePattern::Exact(e) => Pattern::Exact(edge(e)),
    }
}

fn face(f: &lacuna::Face) -> Result<Face, CertifyError> {
    let algorithm = match &f.algorithm {
        lacuna::Algorithm::Spokes(items) => items
            .iter()
            .map(|i| match i {
                lacuna::SpokeItem::Joint => SpokeItem::Joint,
                lacuna::SpokeItem::Gap => SpokeItem::Gap,
                lacuna::SpokeItem::Corner => SpokeItem::Corner,
                lacuna::SpokeItem::DelayedCorner => SpokeItem::DelayedCorner,
                lacuna::SpokeItem::CornerBetween(p, q) => {
                    SpokeItem::CornerBetween(pattern(p), pattern(q))
                }
            })
            .collect(),
        lacuna::Algorithm::Custom(c) => {
            return Err(CertifyError::CustomAlgorithm {
                face: f.to_string(),
                algorithm: c.name(),
            })
        }
    };
    Ok(Face {
        boundary: f.boundary.iter().map(edge).collect(),
        params: Params {
            ea: edge(&f.params.ea),
            el: edge(&f.params.el),
            ec: edge(&f.params.ec),
        },
        algorithm,
        delay: f.delay,
    })
}

fn origin(o: &lacuna::Origin) -> Origin {
    match *o {
        lacuna::Origin::Piece { edge, piece } => Origin::Piece { edge, piece },
        lacuna::Origin::Spoke { spoke, inward } => Origin::Spoke { spoke, inward },
        lacuna::Origin::Lacuna { side } => Origin::Lacuna { side },
        lacuna::Origin::GapSide { edge, gap, after } => Origin::GapSide { edge, gap, after },
    }
}

/// The closure step of a closed type set.
pub fn closure_step(ts: &lacuna::TypeSet) -> Result<ClosureStep, CertifyError> {
    let types = ts
        .types
        .iter()
        .map(|t| {
            Ok(TypeRule {
                face: face(&t.face)?,
                subfaces: t
                    .subdivision
                    .subfaces
                    .iter()
                    .zip(&t.children)
                    .map(|(s, &c)| SubFace {
                        type_index: c,
                        origins: s.origins.iter().map(origin).collect(),
                    })
                    .collect(),
                adjacencies: t
                    .subdivision
                    .adjacencies
                    .iter()
                    .map(|a| Adjacency {
                        first: a.first,
                        second: a.second,
                    })
                    .collect(),
                contribution_halves: t.contribution_halves(),
            })
        })
        .collect::<Result<_, CertifyError>>()?;
    Ok(ClosureStep {
        types,
        start: ts.start.clone(),
    })
}

fn terms(v: &[(usize, BigRational)]) -> Vec<(usize, String)> {
    v.iter().map(|(i, c)| (*i, c.to_string())).collect()
}

fn system(source: &str, sys: &lacuna::LinearSystem) -> System {
    System {
        source: source.to_string(),
        unknowns: sys.unknowns,
        rows: sys
            .rows
            .iter()
            .map(|r| Row {
                terms: terms(&r.terms),
                rhs: r.rhs.to_string(),
            })
            .collect(),
    }
}

/// The step certifying lacuna's solution of `sys`: its solution space, or its conflict.
pub fn solution_step(
    source: &str,
    sys: &lacuna::LinearSystem,
    solution: &lacuna::Solution,
) -> Step {
    match solution {
        lacuna::Solution::Consistent(s) => Step::SolutionSpace(SolutionStep {
            system: system(source, sys),
            particular: s
                .particular
                .iter()
                .enumerate()
                .filter(|(_, x)| !x.is_zero())
                .map(|(i, x)| (i, x.to_string()))
                .collect(),
            free: s.free.clone(),
            basis: s.basis.iter().map(|b| terms(b)).collect(),
            pivots: s.pivots.clone(),
            rank: s.rank,
            dof: s.dof(),
        }),
        lacuna::Solution::Inconsistent(c) => Step::Inconsistent(ConflictStep {
            system: system(source, sys),
            multipliers: terms(&c.multipliers),
            constant: c.constant.to_string(),
        }),
    }
}

/// The limit-ratio step of a substitution (`matrix[t]` lists `(s, k)`), contributions in halves
/// and start `(type, multiplicity)`, with lacuna's verdict and the checker's witnesses.
pub fn ratio_step(
    matrix: &[Vec<(usize, u64)>],
    contribution_halves: &[u64],
    start: &[(usize, u64)],
) -> Result<RatioStep, CertifyError> {
    let c: Vec<BigRational> = contribution_halves
        .iter()
        .map(|&h| BigRational::new(h.into(), 2.into()))
        .collect();
    let report = lacuna::analyse(matrix, &c, start)?;
    // Classes ordered by smallest member; `order[k]` is the report's index of class k.
    let mut order: Vec<usize> = (0..report.classes.len()).collect();
    order.sort_by_key(|&i| report.classes[i].members[0]);
    let classes: Vec<ClassClaim> = order
        .iter()
        .map(|&i| ClassClaim {
            members: report.classes[i].members.clone(),
            period: report.classes[i].period,
        })
        .collect();
    let rho = report.field.generator().clone();
    let one = lacuna::RealAlgebraic::rational(BigRational::one());
    let not_covered = if report.dominant.len() > 1 {
        Some(format!(
            "{} classes share the spectral radius ρ",
            report.dominant.len()
        ))
    } else if report.classes[report.dominant[0]].period != Some(1) {
        Some(format!(
            "the dominant class has period {}",
            report.classes[report.dominant[0]].period.unwrap_or(0)
        ))
    } else if rho.cmp_exact(&one) != Ordering::Greater {
        Some(format!("ρ = {rho} is not above 1"))
    } else if report.ratio.is_none() {
        Some("lacuna's analysis gives no single limit".into())
    } else {
        None
    };
    let claim = match not_covered {
        Some(reason) => RatioClaim::NotCovered {
            reason,
            verdict: match &report.exact {
                Some(r) => format!("R = {r} (ρ = {})", report.perron_root),
                None => format!("no limit; {}", report.reasons.join("; ")),
            },
        },
        None => {
            let dominant = order
                .iter()
                .position(|&i| i == report.dominant[0])
                .expect("the dominant class is listed");
            RatioClaim::Limit(limit_proof(matrix, &report, &classes, dominant)?)
        }
    };
    Ok(RatioStep {
        matrix: matrix.to_vec(),
        contribution_halves: contribution_halves.to_vec(),
        start: start.to_vec(),
        classes,
        claim,
    })
}

fn strings(v: &[BigRational]) -> Vec<String> {
    v.iter().map(|q| q.to_string()).collect()
}

/// The witnesses of the covered case: ρ's isolating interval (refined until its lower end lies
/// above 1 and above every other class's radius), the left eigenvector, the bounds.
fn limit_proof(
    matrix: &[Vec<(usize, u64)>],
    report: &lacuna::RatioReport,
    classes: &[ClassClaim],
    dominant: usize,
) -> Result<LimitProof, CertifyError> {
    let field = &report.field;
    let mut rho = field.generator().clone();
    let others: Vec<&lacuna::RealAlgebraic> = report
        .classes
        .iter()
        .filter(|c| !c.dominant)
        .map(|c| &c.radius)
        .collect();
    let lo_above = |r: &lacuna::RealAlgebraic, x: &lacuna::RealAlgebraic| {
        lacuna::RealAlgebraic::rational(r.interval().0.clone()).cmp_exact(x) == Ordering::Greater
    };
    let one = lacuna::RealAlgebraic::rational(BigRational::one());
    let mut rounds = 0;
    while !(lo_above(&rho, &one) && others.iter().all(|x| lo_above(&rho, x))) {
        rounds += 1;
        if rounds > 10_000 {
            return Err(CertifyError::Witness(
                "ρ does not separate from a class".into(),
            ));
        }
        rho.refine();
    }
    let (lo, hi) = rho.interval();
    let poly = rho.min_poly().primitive_int();
    // Left eigenvector over the reached types: the kernel of (M − ρI)ᵀ.
    let reached: Vec<usize> = classes.iter().flat_map(|c| c.members.clone()).collect();
    let mut reached = reached;
    reached.sort_unstable();
    let at = |t: usize| reached.binary_search(&t).ok();
    let r = field.generator_element();
    let zero = field.rational(BigRational::zero());
    let mut rows = vec![vec![zero.clone(); reached.len()]; reached.len()];
    for (j, &t) in reached.iter().enumerate() {
        for &(s, k) in &matrix[t] {
            if let Some(i) = at(s) {
                let e = field.add(
                    &rows[i][j],
                    &field.rational(BigRational::from_integer(k.into())),
                );
                rows[i][j] = e;
            }
        }
        rows[j][j] = field.sub(&rows[j][j], &r);
    }
    let y = kernel_vector(field, rows, reached.len())?;
    // Normalise: 1 at the first type of the dominant class.
    let d0 = at(classes[dominant].members[0]).expect("reached");
    let scale = field
        .inv(&y[d0])
        .ok_or_else(|| CertifyError::Witness("y vanishes on the dominant class".into()))?;
    let left_vector = reached
        .iter()
        .zip(&y)
        .map(|(&t, v)| (t, field.mul(v, &scale)))
        .filter(|(_, v)| !v.is_zero())
        .map(|(t, v)| (t, strings(v.coords())))
        .collect();
    // Collatz–Wielandt vectors: x = (lo·I − B_c)⁻¹·1 > 0, so B_c·x = lo·x − 1 < lo·x.
    let q = lacuna::NumberField::new(lacuna::RealAlgebraic::rational(BigRational::zero()));
    let mut bounds = Vec::new();
    for (k, class) in classes.iter().enumerate().filter(|(k, _)| *k != dominant) {
        let size = class.members.len();
        let mut rows = vec![vec![q.rational(BigRational::zero()); size + 1]; size];
        for (i, &t) in class.members.iter().enumerate() {
            rows[i][i] = q.rational(lo.clone());
            for &(s, m) in &matrix[t] {
                if let Ok(j) = class.members.binary_search(&s) {
                    let e = field_sub_int(&q, &rows[i][j], m);
                    rows[i][j] = e;
                }
            }
            rows[i][size] = q.rational(BigRational::one());
        }
        let (red, pivots) = rref(&q, rows, size);
        if pivots.len() != size {
            return Err(CertifyError::Witness(format!(
                "class {k}: lo·I − B is singular"
            )));
        }
        let x: Vec<String> = red
            .iter()
            .map(|row| {
                row[size]
                    .as_rational()
                    .expect("a rational field")
                    .to_string()
            })
            .collect();
        bounds.push((k, x));
    }
    let ratio = report.ratio.as_ref().expect("covered case has a ratio");
    Ok(LimitProof {
        rho: Algebraic {
            poly: poly.iter().map(|c| c.to_string()).collect(),
            lo: lo.to_string(),
            hi: hi.to_string(),
        },
        dominant,
        left_vector,
        bounds,
        ratio: strings(ratio.coords()),
    })
}

fn field_sub_int(
    f: &lacuna::NumberField,
    a: &lacuna::FieldElement,
    m: u64,
) -> lacuna::FieldElement {
    f.sub(a, &f.rational(BigRational::from_integer(m.into())))
}

/// Reduced row echelon form over the field on the first `cols` columns; returns the pivot
/// columns.
fn rref(
    f: &lacuna::NumberField,
    mut a: Vec<Vec<lacuna::FieldElement>>,
    cols: usize,
) -> (Vec<Vec<lacuna::FieldElement>>, Vec<usize>) {
    let mut pivots = Vec::new();
    for col in 0..cols {
        let r = pivots.len();
        let Some(p) = (r..a.len()).find(|&i| !a[i][col].is_zero()) else {
            continue;
        };
        a.swap(r, p);
        let inv = f.inv(&a[r][col]).expect("nonzero pivot");
        a[r] = a[r].iter().map(|x| f.mul(x, &inv)).collect();
        for i in 0..a.len() {
            if i != r && !a[i][col].is_zero() {
                let k = a[i][col].clone();
                let pivot_row = a[r].clone();
                for (x, y) in a[i].iter_mut().zip(&pivot_row) {
                    *x = f.sub(x, &f.mul(&k, y));
                }
            }
        }
        pivots.push(col);
    }
    (a, pivots)
}

/// The one-dimensional kernel of a square matrix, as a vector.
fn kernel_vector(
    f: &lacuna::NumberField,
    rows: Vec<Vec<lacuna::FieldElement>>,
    n: usize,
) -> Result<Vec<lacuna::FieldElement>, CertifyError> {
    let (red, pivots) = rref(f, rows, n);
    let free: Vec<usize> = (0..n).filter(|c| !pivots.contains(c)).collect();
    if free.len() != 1 {
        return Err(CertifyError::Witness(format!(
            "the eigenspace of ρ has dimension {}, expected 1",
            free.len()
        )));
    }
    let mut y = vec![f.rational(BigRational::zero()); n];
    y[free[0]] = f.rational(BigRational::one());
    for (i, &p) in pivots.iter().enumerate() {
        y[p] = f.sub(&f.rational(BigRational::zero()), &red[i][free[0]]);
    }
    Ok(y)
}
