//! Certificates of linear systems and limit ratios: the system and its solution (or conflict),
//! and the limit-ratio step with its witnesses (the separated ρ, left Perron vectors over Q(ρ),
//! Collatz–Wielandt vectors).

use super::CertifyError;
use crate::certificate::format::{
    Algebraic, Certificate, Claim, ClassClaim, ConflictStep, PointClaim, RadiusWitness, RatioStep,
    Recipe, Row, SolutionStep, Step, System,
};
use num_rational::BigRational;
use num_traits::{One, Zero};
use std::cmp::Ordering;

/// The certificate of an explicit linear system and lacuna's solution of it: the claim is the
/// system.
pub fn certificate_for_system(
    name: &str,
    source: &str,
    sys: &crate::constraint::LinearSystem,
    solution: &crate::constraint::Solution,
) -> Certificate {
    let mut cert = Certificate::new(name, Claim::System(system(source, sys, None)));
    cert.steps.push(solution_step(source, sys, solution));
    cert
}

/// A dense solution vector as the certificate's sparse list: the nonzero entries by index.
pub(super) fn nonzero(v: &crate::constraint::Rationals) -> Vec<(usize, String)> {
    (0..v.len())
        .filter(|&i| !v.is_zero_at(i))
        .map(|i| (i, v.text(i)))
        .collect()
}

/// A direction of a solution space as the certificate's list of `(unknown, coefficient)`.
pub(super) fn direction(d: crate::constraint::Direction<'_>) -> Vec<(usize, String)> {
    (0..d.len()).map(|j| (d.unknowns()[j], d.text(j))).collect()
}

pub(super) fn terms(v: &[(usize, BigRational)]) -> Vec<(usize, String)> {
    v.iter().map(|(i, c)| (*i, c.to_string())).collect()
}

pub(super) fn system(
    source: &str,
    sys: &crate::constraint::LinearSystem,
    recipe: Option<Recipe>,
) -> System {
    System {
        recipe,
        source: source.to_string(),
        unknowns: sys.unknowns,
        rows: sys
            .equations()
            .map(|r| Row {
                terms: terms(&r.terms),
                rhs: r.rhs.to_string(),
            })
            .collect(),
    }
}

/// The step certifying lacuna's solution of `sys` (a system as given, without recipe): its
/// solution space, or its conflict.
pub fn solution_step(
    source: &str,
    sys: &crate::constraint::LinearSystem,
    solution: &crate::constraint::Solution,
) -> Step {
    step_of_system(system(source, sys, None), solution)
}

pub(super) fn step_of_system(system: System, solution: &crate::constraint::Solution) -> Step {
    match solution {
        crate::constraint::Solution::Consistent(s) => Step::SolutionSpace(SolutionStep {
            system,
            particular: nonzero(&s.particular),
            free: s.free.clone(),
            basis: s.basis.iter().map(direction).collect(),
            pivots: s.pivots.clone(),
            rank: s.rank,
            dof: s.dof(),
        }),
        crate::constraint::Solution::Inconsistent(c) => Step::Inconsistent(ConflictStep {
            system,
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
    ratio_step_in(matrix, contribution_halves, start, 2)
}

/// [`ratio_step`] with contributions in `1/unit` lacunas (2 for faces, 4 for volumes).
pub(super) fn ratio_step_in(
    matrix: &[Vec<(usize, u64)>],
    contributions: &[u64],
    start: &[(usize, u64)],
    unit: u32,
) -> Result<RatioStep, CertifyError> {
    let c: Vec<BigRational> = contributions
        .iter()
        .map(|&h| BigRational::new(h.into(), unit.into()))
        .collect();
    let report = crate::analysis::analyse(matrix, &c, start)?;
    let field = &report.field;
    let rho = separated_rho(&report)?;
    let lo = rho.interval().0.clone();
    // Classes ordered by smallest member.
    let mut order: Vec<usize> = (0..report.classes.len()).collect();
    order.sort_by_key(|&i| report.classes[i].members[0]);
    let classes = order
        .iter()
        .map(|&i| {
            let class = &report.classes[i];
            let radius = match (class.period, class.dominant) {
                (None, _) => RadiusWitness::Transient,
                (Some(_), true) => {
                    RadiusWitness::Perron(perron_vector(field, matrix, &class.members)?)
                }
                (Some(_), false) => {
                    RadiusWitness::Below(collatz_wielandt(&lo, matrix, &class.members)?)
                }
            };
            Ok(ClassClaim {
                members: class.members.clone(),
                period: class.period,
                radius,
            })
        })
        .collect::<Result<_, CertifyError>>()?;
    let points: Vec<PointClaim> = report
        .limit_points
        .iter()
        .map(|p| {
            Ok(PointClaim {
                value: match p.value.coords() {
                    [] => vec!["0".to_string()],
                    c => strings(c),
                },
                real: algebraic(&real_of(field, &p.value)?),
                decimal: p.decimal.clone(),
            })
        })
        .collect::<Result<_, CertifyError>>()?;
    let digits = points
        .first()
        .map_or(0, |p| p.decimal.split_once('.').map_or(0, |(_, f)| f.len()));
    Ok(RatioStep {
        classes,
        rho: algebraic(&rho),
        period: report.period,
        exists: report.exists,
        digits,
        points,
    })
}

pub(super) fn strings(v: &[BigRational]) -> Vec<String> {
    v.iter().map(|q| q.to_string()).collect()
}

pub(super) fn algebraic(x: &crate::algebra::RealAlgebraic) -> Algebraic {
    let (lo, hi) = x.interval();
    Algebraic {
        poly: x
            .min_poly()
            .primitive_int()
            .iter()
            .map(|c| c.to_string())
            .collect(),
        lo: lo.to_string(),
        hi: hi.to_string(),
    }
}

/// ρ with an isolating interval whose lower end lies above 1 (when ρ is irrational) and above
/// every smaller class radius, as the Collatz–Wielandt bounds need.
fn separated_rho(
    report: &crate::analysis::RatioReport,
) -> Result<crate::algebra::RealAlgebraic, CertifyError> {
    let mut rho = report.field.generator().clone();
    let others: Vec<&crate::algebra::RealAlgebraic> = report
        .classes
        .iter()
        .filter(|c| !c.dominant)
        .map(|c| &c.radius)
        .collect();
    let one = crate::algebra::RealAlgebraic::rational(BigRational::one());
    let lo_above = |r: &crate::algebra::RealAlgebraic, x: &crate::algebra::RealAlgebraic| {
        r.degree() == 1
            || crate::algebra::RealAlgebraic::rational(r.interval().0.clone()).cmp_exact(x)
                == Ordering::Greater
    };
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
    Ok(rho)
}

/// The left eigenvector `y` of the block of `members` for ρ (`y·B = ρ·y`), 1 at the first
/// member; positive by Perron–Frobenius.
fn perron_vector(
    field: &crate::algebra::NumberField,
    matrix: &[Vec<(usize, u64)>],
    members: &[usize],
) -> Result<Vec<Vec<String>>, CertifyError> {
    let r = field.generator_element();
    let zero = field.rational(BigRational::zero());
    let size = members.len();
    // Row i of (B − ρI)ᵀ: Σ_j y_j (B[j][i] − ρ δ_ij) = 0.
    let mut rows = vec![vec![zero; size]; size];
    for (j, &t) in members.iter().enumerate() {
        for &(s, k) in &matrix[t] {
            if let Ok(i) = members.binary_search(&s) {
                rows[i][j] = field.add(
                    &rows[i][j],
                    &field.rational(BigRational::from_integer(k.into())),
                );
            }
        }
        rows[j][j] = field.sub(&rows[j][j], &r);
    }
    let y = kernel_vector(field, rows, size)?;
    let scale = field
        .inv(&y[0])
        .ok_or_else(|| CertifyError::Witness("the Perron vector vanishes".into()))?;
    Ok(y.iter()
        .map(|v| strings(field.mul(v, &scale).coords()))
        .collect())
}

/// `x = (lo·I − B)⁻¹·1 > 0` on the block of `members`, so `B·x = lo·x − 1 < lo·x`.
fn collatz_wielandt(
    lo: &BigRational,
    matrix: &[Vec<(usize, u64)>],
    members: &[usize],
) -> Result<Vec<String>, CertifyError> {
    let q = crate::algebra::NumberField::new(crate::algebra::RealAlgebraic::rational(
        BigRational::zero(),
    ));
    let size = members.len();
    let mut rows = vec![vec![q.rational(BigRational::zero()); size + 1]; size];
    for (i, &t) in members.iter().enumerate() {
        rows[i][i] = q.rational(lo.clone());
        for &(s, m) in &matrix[t] {
            if let Ok(j) = members.binary_search(&s) {
                let e = field_sub_int(&q, &rows[i][j], m);
                rows[i][j] = e;
            }
        }
        rows[i][size] = q.rational(BigRational::one());
    }
    let (red, pivots) = rref(&q, rows, size);
    if pivots.len() != size {
        return Err(CertifyError::Witness("lo·I − B is singular".into()));
    }
    Ok(red
        .iter()
        .map(|row| {
            row[size]
                .as_rational()
                .expect("a rational field")
                .to_string()
        })
        .collect())
}

/// `v` as a real algebraic number: its minimal polynomial over Q (the first linear dependence
/// among `1, v, v², …` in Q(ρ), a field) and the isolating interval of its root equal to `v`.
fn real_of(
    field: &crate::algebra::NumberField,
    v: &crate::algebra::FieldElement,
) -> Result<crate::algebra::RealAlgebraic, CertifyError> {
    if let Some(q) = v.as_rational() {
        return Ok(crate::algebra::RealAlgebraic::rational(q));
    }
    let q = crate::algebra::NumberField::new(crate::algebra::RealAlgebraic::rational(
        BigRational::zero(),
    ));
    let deg = field.degree();
    let coord = |x: &crate::algebra::FieldElement, i: usize| q.rational(x.poly().coeff(i));
    let mut powers = vec![field.rational(BigRational::one())];
    for k in 1..=deg {
        powers.push(field.mul(&powers[k - 1], v));
        // Solve Σ_(i<k) a_i·v^i = v^k on the coordinates.
        let rows = (0..deg)
            .map(|i| (0..=k).map(|j| coord(&powers[j], i)).collect())
            .collect();
        let (red, pivots) = rref(&q, rows, k + 1);
        if pivots.contains(&k) {
            continue; // v^k is independent of the lower powers
        }
        let mut coeffs: Vec<BigRational> = vec![BigRational::zero(); k + 1];
        for (row, &p) in red.iter().zip(&pivots) {
            coeffs[p] = -row[k].as_rational().expect("rational");
        }
        coeffs[k] = BigRational::one();
        let f = crate::algebra::Poly::new(coeffs);
        let sign = |x: &BigRational| field.sign(&field.sub(v, &field.rational(x.clone())));
        return crate::algebra::RealAlgebraic::real_roots(&f)
            .into_iter()
            .find(|r| {
                let (lo, hi) = r.interval();
                sign(lo) == Ordering::Greater && sign(hi) == Ordering::Less
            })
            .ok_or_else(|| CertifyError::Witness("no root of the minimal polynomial is R".into()));
    }
    Err(CertifyError::Witness("no minimal polynomial found".into()))
}

fn field_sub_int(
    f: &crate::algebra::NumberField,
    a: &crate::algebra::FieldElement,
    m: u64,
) -> crate::algebra::FieldElement {
    f.sub(a, &f.rational(BigRational::from_integer(m.into())))
}

/// Reduced row echelon form over the field on the first `cols` columns; returns the pivot
/// columns.
fn rref(
    f: &crate::algebra::NumberField,
    mut a: Vec<Vec<crate::algebra::FieldElement>>,
    cols: usize,
) -> (Vec<Vec<crate::algebra::FieldElement>>, Vec<usize>) {
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
    f: &crate::algebra::NumberField,
    rows: Vec<Vec<crate::algebra::FieldElement>>,
    n: usize,
) -> Result<Vec<crate::algebra::FieldElement>, CertifyError> {
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

pub(super) fn rational(s: &str) -> Result<BigRational, CertifyError> {
    s.parse()
        .map_err(|_| CertifyError::Witness(format!("`{s}` is not a rational")))
}
