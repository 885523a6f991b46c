//! Differential behaviour of subdivision operators (THEORY §8): eigenvalues, fixed point,
//! contraction on the barycentric hyperplane, and the pseudo-tangent / pseudo-curvature case.
//!
//! Every verdict is exact. The characteristic polynomial is computed and factored over Q
//! ([`crate::algebra::factor`]); real eigenvalues are [`RealAlgebraic`] numbers; eigenvectors live in the
//! field Q(λ). Moduli are compared without floats: "every root of p lies in the open disk of
//! radius r" is the Schur–Cohn test on `p(r·x)` with coefficients in Q(λ1) (signs decided by
//! [`NumberField::sign`]); "a root lies on the circle" is a gcd with the reciprocal polynomial.
//! Floats appear only in labelled approximations (complex eigenvalues, whose enclosing disks are
//! certified by exact evaluation; the numerical value of α) and in [`estimate_curvature`].

use crate::algebra::algebraic::{FieldElement, NumberField, RealAlgebraic};
use crate::algebra::disk::{approx_roots, root_disks, sqrt_up, Disk};
use crate::algebra::factor::{charpoly, factor};
use crate::algebra::fieldpoly::{
    adjugate_eigenvector, circle_position, inside_unit_disk, k_divrem, k_eval, k_scale_var,
    null_space, rationals, shifted, to_k, Position,
};
use crate::algebra::matrix::Matrix;
use crate::algebra::poly::Poly;
use crate::error::{Diagnostic, Error, Result, Source, Span};
use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{FromPrimitive, One, Signed, ToPrimitive, Zero};
use serde::Serialize;
use std::cmp::Ordering;

/// The pseudo-curvature class at a fixed point, from α = log|λ2| / log λ1.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum CurvatureClass {
    /// α < 2 (|λ2| > λ1²): pseudo-curvature +∞.
    Sharp,
    /// α = 2 (|λ2| = λ1²): a bounded range of curvatures.
    Finite,
    /// α > 2 (|λ2| < λ1², or no λ2 at all): pseudo-curvature 0.
    Flat,
    /// The exact test does not cover this configuration (several eigenvalues of modulus exactly
    /// λ1² related by inversion); never guessed.
    Undecided,
}

/// What an operator does near its fixed point.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
#[serde(tag = "case", rename_all = "snake_case")]
pub enum Behaviour {
    /// 1 = λ0 > λ1 > |λ| for every other eigenvalue λ, λ1 real and simple: a tangent along v1.
    Tangent {
        /// The class of α.
        class: CurvatureClass,
        /// What the second-order eigenvalues are (and why the class holds).
        detail: String,
    },
    /// The largest other modulus belongs to a negative eigenvalue (or to both ±λ): the curve
    /// oscillates from side to side at the fixed point.
    Oscillating {
        /// Which eigenvalues.
        detail: String,
    },
    /// A complex pair has modulus at least that of every real eigenvalue but 1: spiralling.
    Spiralling {
        /// Which eigenvalues.
        detail: String,
    },
    /// No tangent case: 1 missing or repeated, λ1 repeated or ≥ 1, every other eigenvalue 0.
    Degenerate {
        /// Why.
        detail: String,
    },
}

impl Behaviour {
    /// A short label: `sharp`, `finite`, `flat`, `undecided`, `oscillating`, `spiralling`,
    /// `degenerate`.
    pub fn label(&self) -> &'static str {
        match self {
            Behaviour::Tangent { class, .. } => match class {
                CurvatureClass::Sharp => "sharp",
                CurvatureClass::Finite => "finite",
                CurvatureClass::Flat => "flat",
                CurvatureClass::Undecided => "undecided",
            },
            Behaviour::Oscillating { .. } => "oscillating",
            Behaviour::Spiralling { .. } => "spiralling",
            Behaviour::Degenerate { .. } => "degenerate",
        }
    }

    /// The curvature class in the tangent case.
    pub fn class(&self) -> Option<CurvatureClass> {
        match self {
            Behaviour::Tangent { class, .. } => Some(*class),
            _ => None,
        }
    }
}

/// One eigenvalue (a real root, or one complex pair, of an irreducible factor of the
/// characteristic polynomial).
#[derive(Clone, Debug, Serialize)]
pub struct Eigenvalue {
    /// Its minimal polynomial over Q.
    pub min_poly: String,
    /// Algebraic multiplicity.
    pub multiplicity: usize,
    /// True for a real eigenvalue; false for a complex pair `a ± b·i`.
    pub real: bool,
    /// Exact value: rational, closed form for quadratics (`a ± i*sqrt(s)` for a complex pair),
    /// or `root of P in [lo, hi]`. `None` for a complex pair of degree > 2 (see `approx`).
    pub exact: Option<String>,
    /// Real: certified decimal digits (truncated). Complex: a float approximation `a ± b i`.
    pub approx: String,
    /// Complex only: a certified radius — a root of the minimal polynomial lies within this
    /// distance of the approximation (n·|f(z)/f'(z)| evaluated exactly at the rational z).
    pub radius: Option<String>,
    /// Real only: a basis of the eigenspace, exact in Q(λ) (rendered like the eigenvalue).
    pub eigenvectors: Vec<Vec<String>>,
    #[serde(skip)]
    modulus: f64,
}

/// Everything §8 asks of one square operator.
#[derive(Clone, Debug, Serialize)]
pub struct OperatorReport {
    /// The operator's name, if it comes from an automaton.
    pub name: Option<String>,
    /// The matrix, `[a b; c d]`.
    pub matrix: String,
    /// Every column sums to 1.
    pub barycentric: bool,
    /// The characteristic polynomial `det(x·I − T)`.
    pub charpoly: String,
    /// The eigenvalues: real ones in decreasing order, then complex pairs.
    pub eigenvalues: Vec<Eigenvalue>,
    /// The fixed point in barycentric coordinates (the eigenvector of 1 scaled to sum 1).
    pub fixed_point: Option<Vec<String>>,
    /// Why there is no (unique, normalisable) fixed point, when there is none.
    pub fixed_point_note: Option<String>,
    /// 1 is a simple eigenvalue and every other eigenvalue has modulus < 1 (Schur–Cohn, exact).
    pub contractive: bool,
    /// The behaviour at the fixed point.
    pub behaviour: Behaviour,
    /// λ1 in the tangent case.
    pub lambda1: Option<String>,
    /// v1, the eigenvector of λ1 (exact in Q(λ1), last non-zero coordinate 1; up to sign).
    pub tangent: Option<Vec<String>>,
    /// α = ln|λ2| / ln λ1 in floating point — an illustration, never used for the class.
    pub alpha_approx: Option<f64>,
    #[serde(skip)]
    pub(crate) fixed: Option<Vec<BigRational>>,
    #[serde(skip)]
    pub(crate) exact: Option<TangentData>,
}

/// The exact tangent data kept for dyadic points and curvature estimates.
#[derive(Clone, Debug)]
pub(crate) struct TangentData {
    pub(crate) field: NumberField,
    pub(crate) lambda1: RealAlgebraic,
    pub(crate) v1: Vec<FieldElement>,
    /// λ2 and v2 when the second-order eigenvalue is real and equals ±λ1² (α = 2).
    pub(crate) second: Option<(FieldElement, Vec<FieldElement>)>,
}

fn q(n: i64) -> BigRational {
    BigRational::from_integer(n.into())
}

/// A lacuna error with an E09xx code and no source span.
pub(crate) fn op_error(code: &'static str, message: impl Into<String>) -> Error {
    Error::Syntax(Box::new(Diagnostic {
        code,
        message: message.into(),
        span: None,
        source: None,
    }))
}

// ---------- eigenvalues ----------

/// The characteristic polynomial `det(x·I − T)` of a square rational matrix.
pub(crate) fn char_poly(t: &Matrix) -> Poly {
    let d = t
        .data
        .iter()
        .fold(BigInt::one(), |acc, x| acc.lcm(x.denom()));
    let dr = BigRational::from_integer(d.clone());
    let ints: Vec<Vec<BigInt>> = (0..t.rows)
        .map(|i| {
            (0..t.cols)
                .map(|j| (t.get(i, j) * &dr).to_integer())
                .collect()
        })
        .collect();
    // det(x·I − d·T) = d^n · χ_T(x/d).
    let p = charpoly(&ints);
    let n = t.rows as i32;
    Poly::new(
        p.coeffs()
            .iter()
            .enumerate()
            .map(|(i, c)| c * dr.pow(i as i32 - n))
            .collect(),
    )
}

pub(crate) fn render_vec(k: &NumberField, v: &[FieldElement]) -> Vec<String> {
    v.iter().map(|x| k.render(x)).collect()
}

pub(crate) fn f64_of(k: &NumberField, a: &FieldElement) -> f64 {
    k.decimal(a, 17).parse().unwrap_or(f64::NAN)
}

/// A real eigenvalue with its factor's multiplicity.
struct RealRoot {
    value: RealAlgebraic,
    mult: usize,
}

/// Exact analysis of a square rational matrix: eigenvalues, fixed point, contraction and the
/// §8 behaviour. Errors: E0902 for a non-square or empty matrix, E0801 when a characteristic
/// polynomial cannot be factored within budget.
pub fn analyse_matrix(t: &Matrix) -> Result<OperatorReport> {
    if t.rows != t.cols || t.rows == 0 {
        return Err(op_error(
            "E0902",
            format!(
                "eigen analysis needs a non-empty square matrix, not {}×{}",
                t.rows, t.cols
            ),
        ));
    }
    let chi = char_poly(t);
    let factors = factor(&chi).map_err(|e| Error::Analysis(e.to_string()))?;
    let one = Poly::from_ints(&[-1, 1]);
    let mult_one = factors
        .iter()
        .find(|(f, _)| *f == one)
        .map_or(0, |(_, m)| *m);
    let mut eigen = Vec::new();
    let mut reals: Vec<RealRoot> = Vec::new();
    let mut complex_disks: Vec<ComplexFactor> = Vec::new();
    for (f, mult) in &factors {
        let roots = RealAlgebraic::real_roots(f);
        for r in &roots {
            let rendered = real_eigenvectors(t, &chi, r, *mult);
            let approx = r.decimal(12);
            eigen.push(Eigenvalue {
                min_poly: f.to_string(),
                multiplicity: *mult,
                real: true,
                exact: Some(r.to_string()),
                modulus: approx.parse::<f64>().unwrap_or(f64::NAN).abs(),
                approx,
                radius: None,
                eigenvectors: rendered,
            });
            reals.push(RealRoot {
                value: r.clone(),
                mult: *mult,
            });
        }
        if roots.len() < f.deg() {
            let disks = root_disks(f).filter(|d| {
                d.iter().filter(|x| x.above_axis()).count() * 2 == f.deg() - roots.len()
            });
            eigen.extend(complex_pairs(f, roots.len(), *mult, disks.as_deref()));
            complex_disks.push(ComplexFactor {
                poly: f.clone(),
                upper: disks.map(|d| d.into_iter().filter(Disk::above_axis).collect()),
            });
        }
    }
    // Real eigenvalues in decreasing order, complex pairs after (stable).
    let mut order: Vec<usize> = (0..eigen.len()).collect();
    let real_idx: Vec<usize> = order.iter().copied().filter(|&i| eigen[i].real).collect();
    let mut sorted_real = real_idx.clone();
    sorted_real.sort_by(|&a, &b| {
        let pos = |i: usize| real_idx.iter().position(|&x| x == i).expect("real");
        reals[pos(b)].value.cmp_exact(&reals[pos(a)].value)
    });
    order = sorted_real
        .into_iter()
        .chain(order.into_iter().filter(|&i| !eigen[i].real))
        .collect();
    let eigenvalues: Vec<Eigenvalue> = order.iter().map(|&i| eigen[i].clone()).collect();

    // Fixed point: the eigenvector of 1, scaled to coordinate sum 1.
    let qk = rationals();
    let (fixed, fixed_point_note) = if mult_one == 0 {
        (
            None,
            Some("1 is not an eigenvalue: no fixed point".to_string()),
        )
    } else {
        let one_k = qk.rational(BigRational::one());
        let ns = match (mult_one, adjugate_eigenvector(&qk, t, &chi, &one_k)) {
            (1, Some(v)) => vec![v],
            _ => null_space(&qk, shifted(&qk, t, &one_k)),
        };
        if ns.len() != 1 {
            (
                None,
                Some(format!(
                    "the eigenspace of 1 has dimension {}: the fixed point is not unique",
                    ns.len()
                )),
            )
        } else {
            let v: Vec<BigRational> = ns[0]
                .iter()
                .map(|x| x.as_rational().expect("rational"))
                .collect();
            let s: BigRational = v.iter().sum();
            if s.is_zero() {
                (
                    None,
                    Some(
                        "the eigenvector of 1 has coordinate sum 0: it is a direction, not a point"
                            .into(),
                    ),
                )
            } else {
                (Some(v.iter().map(|x| x / &s).collect::<Vec<_>>()), None)
            }
        }
    };

    // Contraction: 1 simple, every other root of χ in the open unit disk.
    let contractive = mult_one == 1 && contracts(&reals, &complex_disks);

    let (behaviour, exact) = classify(t, &chi, mult_one, &reals, &complex_disks);
    let (lambda1, tangent, alpha_approx) = match &exact {
        Some(d) => {
            let l1 = d.lambda1.decimal(17).parse::<f64>().unwrap_or(f64::NAN);
            // |λ2|: the largest modulus among the other eigenvalues (λ1 counted once less).
            let mut skipped = false;
            let m2 = eigenvalues
                .iter()
                .flat_map(|e| std::iter::repeat_n(e, e.multiplicity))
                .filter(|e| {
                    if e.exact.as_deref() == Some("1") {
                        return false;
                    }
                    if !skipped && e.real && e.exact == Some(d.lambda1.to_string()) {
                        skipped = true;
                        return false;
                    }
                    true
                })
                .map(|e| e.modulus)
                .fold(0.0f64, f64::max);
            let alpha = (m2 > 0.0).then(|| m2.ln() / l1.ln());
            (
                Some(d.lambda1.to_string()),
                Some(render_vec(&d.field, &d.v1)),
                alpha,
            )
        }
        None => (None, None, None),
    };
    Ok(OperatorReport {
        name: None,
        matrix: t.to_string(),
        barycentric: t.is_barycentric(),
        charpoly: chi.to_string(),
        eigenvalues,
        fixed_point: fixed
            .as_ref()
            .map(|v| v.iter().map(ToString::to_string).collect()),
        fixed_point_note,
        contractive,
        behaviour,
        lambda1,
        tangent,
        alpha_approx,
        fixed,
        exact,
    })
}

/// The complex pairs of the irreducible `f` (which has `n_real` real roots): centres of the
/// certified disks when there are some (else float approximations with a radius certified one by
/// one); exact `a ± i*sqrt(s)` for quadratics.
fn complex_pairs(f: &Poly, n_real: usize, mult: usize, disks: Option<&[Disk]>) -> Vec<Eigenvalue> {
    let pairs = (f.deg() - n_real) / 2;
    let exact = (f.deg() == 2).then(|| {
        let f = f.monic();
        let re = -f.coeff(1) / q(2);
        let s = f.coeff(0) - &re * &re;
        format!("{re} ± i*sqrt({s})")
    });
    let found: Vec<((f64, f64), Option<BigRational>)> = match disks {
        Some(d) => d
            .iter()
            .filter(|x| x.above_axis())
            .map(|x| (x.approx(), Some(x.r.clone())))
            .collect(),
        None => {
            let mut z = approx_roots(f);
            z.sort_by(|a, b| b.1.partial_cmp(&a.1).unwrap_or(Ordering::Equal));
            z.into_iter().take(pairs).map(|z| (z, None)).collect()
        }
    };
    found
        .into_iter()
        .map(|((re, im), r)| Eigenvalue {
            min_poly: f.to_string(),
            multiplicity: mult,
            real: false,
            exact: exact.clone(),
            approx: format!("{re:.12} ± {:.12} i", im.abs()),
            radius: r
                .or_else(|| certified_radius(f, (re, im)))
                .map(|r| format!("{:.3e}", r.to_f64().unwrap_or(f64::NAN))),
            eigenvectors: Vec::new(),
            modulus: (re * re + im * im).sqrt(),
        })
        .collect()
}

/// A rational upper bound on `n·|f(z)/f'(z)|` at the rational point z: some root of f lies
/// within it. `None` when f'(z) = 0 or the point is not finite.
fn certified_radius(f: &Poly, z: (f64, f64)) -> Option<BigRational> {
    let (re, im) = (BigRational::from_f64(z.0)?, BigRational::from_f64(z.1)?);
    let eval = |p: &Poly| {
        p.coeffs()
            .iter()
            .rev()
            .fold((BigRational::zero(), BigRational::zero()), |(a, b), c| {
                (&a * &re - &b * &im + c, &a * &im + &b * &re)
            })
    };
    let (fa, fb) = eval(f);
    let (da, db) = eval(&f.derivative());
    let den = &da * &da + &db * &db;
    if den.is_zero() {
        return None;
    }
    let n = q(f.deg() as i64);
    Some(sqrt_up(&(&n * &n * (&fa * &fa + &fb * &fb) / den)))
}

/// An irreducible factor with complex roots and, when the float approximations separate them,
/// the certified disks of its roots above the real axis (one per conjugate pair).
struct ComplexFactor {
    poly: Poly,
    upper: Option<Vec<Disk>>,
}

/// Exact eigenvectors of the real eigenvalue `r` (a root of a factor of multiplicity `mult`),
/// rendered. Simple: a column of the adjugate
/// ([`adjugate_eigenvector`]), no elimination over Q(r). Repeated: null space over Q(r).
fn real_eigenvectors(t: &Matrix, chi: &Poly, r: &RealAlgebraic, mult: usize) -> Vec<Vec<String>> {
    let k = NumberField::new(r.clone());
    let lam = k.generator_element();
    let vecs = if mult > 1 {
        null_space(&k, shifted(&k, t, &lam))
    } else {
        match adjugate_eigenvector(&k, t, chi, &lam) {
            Some(v) => vec![v],
            None => null_space(&k, shifted(&k, t, &lam)),
        }
    };
    vecs.iter().map(|v| render_vec(&k, v)).collect()
}

/// One eigenvector of the simple eigenvalue `lam` ∈ K.
pub(crate) fn eigenvector_in(
    k: &NumberField,
    t: &Matrix,
    chi: &Poly,
    lam: &FieldElement,
) -> Option<Vec<FieldElement>> {
    adjugate_eigenvector(k, t, chi, lam)
        .or_else(|| null_space(k, shifted(k, t, lam)).into_iter().next())
}

/// 1 is simple and every other eigenvalue lies in the open unit disk: real ones by exact
/// comparison, complex ones by their certified disks, Schur–Cohn over Q on the factor when a
/// disk straddles the unit circle.
fn contracts(reals: &[RealRoot], complex: &[ComplexFactor]) -> bool {
    let one = RealAlgebraic::rational(BigRational::one());
    let minus = RealAlgebraic::rational(-BigRational::one());
    let reals_ok = reals.iter().all(|r| {
        r.value.cmp_exact(&one) == Ordering::Equal && r.mult == 1
            || r.value.cmp_exact(&one) == Ordering::Less
                && r.value.cmp_exact(&minus) == Ordering::Greater
    });
    let qk = rationals();
    reals_ok
        && complex.iter().all(|c| {
            let fast = c.upper.as_ref().and_then(|d| {
                let mut all = true;
                for x in d {
                    match x.cmp_modulus(&BigRational::one(), &BigRational::one()) {
                        Some(Ordering::Less) => {}
                        Some(_) => all = false,
                        None => return None,
                    }
                }
                Some(all)
            });
            fast.unwrap_or_else(|| inside_unit_disk(&qk, &to_k(&qk, &c.poly)))
        })
}

/// An enclosure `[lo, hi]` of `|r|`, refined to width `w` (`lo ≥ 0`).
fn abs_enclosure(r: &mut RealAlgebraic, w: &BigRational) -> (BigRational, BigRational) {
    r.refine_to(w);
    let (lo, hi) = r.interval();
    let (lo, hi) = if lo.is_negative() && hi.is_positive() {
        (BigRational::zero(), lo.abs().max(hi.abs()))
    } else if hi.is_positive() || hi.is_zero() && lo.is_zero() {
        (lo.clone(), hi.clone())
    } else {
        (hi.abs(), lo.abs())
    };
    (lo.max(BigRational::zero()), hi)
}

/// Exact comparison of `|mu|` with `lambda1²` (λ1 > 0): interval refinement separates distinct
/// numbers; equality is recognised exactly — `g(±λ1²) = 0` in Q(λ1) for the minimal polynomial
/// g of μ, and the enclosure of ±λ1² inside μ's isolating interval (g has one root there).
/// Returns the ordering and, on equality, the sign of μ.
pub(crate) fn cmp_abs_with_square(
    mu: &RealAlgebraic,
    lambda1: &RealAlgebraic,
    k: &NumberField,
) -> Ordering {
    let mu_neg = mu.cmp_exact(&RealAlgebraic::rational(BigRational::zero())) == Ordering::Less;
    if let Some(l) = lambda1.as_rational() {
        let sq = l * l;
        let target = RealAlgebraic::rational(if mu_neg { -sq } else { sq });
        let c = mu.cmp_exact(&target);
        return if mu_neg { c.reverse() } else { c };
    }
    let (mut m, mut l) = (mu.clone(), lambda1.clone());
    let mut w = BigRational::new(1.into(), (1u64 << 40).into());
    let mut equal_checked = false;
    for round in 0.. {
        let (mlo, mhi) = abs_enclosure(&mut m, &w);
        l.refine_to(&w);
        let (llo, lhi) = l.interval();
        let (slo, shi) = (llo.max(&BigRational::zero()).clone(), lhi.clone());
        let (slo, shi) = (&slo * &slo, &shi * &shi);
        if mhi < slo {
            return Ordering::Less;
        }
        if mlo > shi {
            return Ordering::Greater;
        }
        if round >= 2 && !equal_checked {
            equal_checked = true;
            let s = if mu_neg { q(-1) } else { q(1) };
            let g = k_eval(
                k,
                &to_k(k, mu.min_poly()),
                &k.scale(&k.mul(&k.generator_element(), &k.generator_element()), &s),
            );
            if g.is_zero() && mu.degree() == 1 {
                return Ordering::Equal;
            }
            if g.is_zero() {
                // ±λ1² is a root of g: it is μ iff its enclosure falls in μ's isolating interval.
                loop {
                    let (ilo, ihi) = m.interval();
                    let (ilo, ihi) = (ilo.clone(), ihi.clone());
                    l.refine_to(&w);
                    let (llo, lhi) = l.interval();
                    let (a, b) = (llo * llo * &s, lhi * lhi * &s);
                    let (a, b) = if a <= b { (a, b) } else { (b, a) };
                    if ilo < a && b < ihi {
                        return Ordering::Equal;
                    }
                    if b < ilo || ihi < a {
                        break;
                    }
                    w = &w / q(1 << 20);
                }
            }
        }
        w = &w / q(1 << 20);
    }
    unreachable!("the loop returns")
}

/// `f(−x)`.
fn reflect(f: &Poly) -> Poly {
    Poly::new(
        f.coeffs()
            .iter()
            .enumerate()
            .map(|(i, c)| if i % 2 == 1 { -c } else { c.clone() })
            .collect(),
    )
}

/// The §8 case analysis, exact. Returns the behaviour and, in the tangent case, λ1 and v1.
///
/// Moduli are compared first by enclosures — isolating intervals of the real eigenvalues and the
/// certified disks of the complex ones — which decide every strict inequality; equalities of
/// real eigenvalues (λ2 = ±λ1²) are recognised exactly in Q(λ1). Only when a complex disk cannot
/// be separated from the circle in question does the analysis fall back to the exact tests over
/// Q(ρ) (Schur–Cohn, gcd with the reciprocal polynomial).
fn classify(
    t: &Matrix,
    chi: &Poly,
    mult_one: usize,
    reals: &[RealRoot],
    complex: &[ComplexFactor],
) -> (Behaviour, Option<TangentData>) {
    let degenerate = |detail: String| (Behaviour::Degenerate { detail }, None);
    if mult_one == 0 {
        return degenerate("1 is not an eigenvalue".into());
    }
    if mult_one > 1 {
        return degenerate(format!("1 is an eigenvalue of multiplicity {mult_one}"));
    }
    if t.rows == 1 {
        return degenerate("a 1×1 operator: its attractor is a point".into());
    }
    let zero = RealAlgebraic::rational(BigRational::zero());
    let one = RealAlgebraic::rational(BigRational::one());
    // Largest positive root, and the largest |r| over negative roots, with multiplicities.
    let mut pos: Option<(RealAlgebraic, usize)> = None;
    let mut neg: Option<(RealAlgebraic, usize)> = None;
    for r in reals {
        if r.value.cmp_exact(&one) == Ordering::Equal {
            continue;
        }
        match r.value.cmp_exact(&zero) {
            Ordering::Greater => {
                if pos
                    .as_ref()
                    .is_none_or(|(p, _)| r.value.cmp_exact(p) == Ordering::Greater)
                {
                    pos = Some((r.value.clone(), r.mult));
                }
            }
            Ordering::Less => {
                let a = negate(&r.value);
                if neg
                    .as_ref()
                    .is_none_or(|(p, _)| a.cmp_exact(p) == Ordering::Greater)
                {
                    neg = Some((a, r.mult));
                }
            }
            Ordering::Equal => {}
        }
    }
    let (rho, rho_pos, rho_neg) = match (&pos, &neg) {
        (None, None) => {
            return if complex.is_empty() {
                degenerate(
                    "every eigenvalue but 1 is 0: the operator collapses onto its fixed point"
                        .into(),
                )
            } else {
                (
                    Behaviour::Spiralling {
                        detail: "every eigenvalue but 1 and 0 is complex".into(),
                    },
                    None,
                )
            };
        }
        (Some((p, _)), None) => (p.clone(), true, false),
        (None, Some((n, _))) => (n.clone(), false, true),
        (Some((p, _)), Some((n, _))) => match p.cmp_exact(n) {
            Ordering::Greater => (p.clone(), true, false),
            Ordering::Less => (n.clone(), false, true),
            Ordering::Equal => (p.clone(), true, true),
        },
    };
    let k = NumberField::new(rho.clone());
    let rho_k = k.generator_element();
    // Does a complex pair reach modulus ρ? Disks first; else Schur–Cohn on f(ρ·x) over Q(ρ)
    // with its roots ±1 removed.
    for c in complex {
        let fast = c.upper.as_ref().and_then(|d| {
            let mut r = rho.clone();
            let mut reach = false;
            for x in d {
                let mut decided = None;
                for digits in [40u32, 80, 160] {
                    r.refine_to(&BigRational::new(1.into(), BigInt::from(2).pow(digits)));
                    let (lo, hi) = r.interval();
                    if let Some(o) = x.cmp_modulus(lo, hi) {
                        decided = Some(o);
                        break;
                    }
                }
                match decided? {
                    Ordering::Less => {}
                    _ => reach = true,
                }
            }
            Some(reach)
        });
        let reach = fast.unwrap_or_else(|| {
            let mut g = k_scale_var(&k, &to_k(&k, &c.poly), &rho_k);
            for s in [1i64, -1] {
                if k_eval(&k, &g, &k.rational(q(s))).is_zero() {
                    g = k_divrem(&k, &g, &[k.rational(q(-s)), k.rational(q(1))]).0;
                }
            }
            !inside_unit_disk(&k, &g)
        });
        if reach {
            return (
                Behaviour::Spiralling {
                    detail: format!(
                        "a complex pair (roots of {}) has modulus at least {}, the largest real modulus",
                        short_poly(&c.poly),
                        short_number(&rho)
                    ),
                },
                None,
            );
        }
    }
    if rho_neg {
        let rho = short_number(&rho);
        let detail = if rho_pos {
            format!("both {rho} and -({rho}) are eigenvalues of largest modulus")
        } else {
            format!("the largest other modulus belongs to the negative eigenvalue -({rho})")
        };
        return (Behaviour::Oscillating { detail }, None);
    }
    let mult = pos.as_ref().map_or(1, |(_, m)| *m);
    if mult > 1 {
        return degenerate(format!("λ1 = {rho} is repeated (multiplicity {mult})"));
    }
    if rho.cmp_exact(&one) != Ordering::Less {
        return degenerate(format!("λ1 = {rho} is not below 1: not contractive"));
    }
    // Tangent case: λ1 = ρ simple and strictly dominant. v1 over Q(λ1).
    let v1 = eigenvector_in(&k, t, chi, &rho_k).expect("a simple eigenvalue has an eigenvector");
    let r2 = k.mul(&rho_k, &rho_k);
    // The other eigenvalues against the circle of radius λ1².
    let mut outside = false;
    let mut on_circle = false;
    let mut which: Vec<&str> = Vec::new();
    let mut others = 0usize;
    for r in reals {
        if r.value.cmp_exact(&one) == Ordering::Equal || r.value.cmp_exact(&rho) == Ordering::Equal
        {
            continue;
        }
        others += 1;
        match cmp_abs_with_square(&r.value, &rho, &k) {
            Ordering::Greater => outside = true,
            Ordering::Equal => {
                on_circle = true;
                let neg = r.value.cmp_exact(&zero) == Ordering::Less;
                let w = if neg { "-λ1²" } else { "λ1²" };
                if !which.contains(&w) {
                    which.push(w);
                }
            }
            Ordering::Less => {}
        }
    }
    let mut fallback = false;
    let mut complex_on_circle = false;
    if !complex.is_empty() {
        others += 1;
        let mut sq = rho.clone();
        for c in complex {
            let Some(d) = &c.upper else {
                fallback = true;
                break;
            };
            for x in d {
                let mut decided = None;
                for digits in [40u32, 80, 160] {
                    sq.refine_to(&BigRational::new(1.into(), BigInt::from(2).pow(digits)));
                    let (lo, hi) = sq.interval();
                    let lo = lo.max(&BigRational::zero()).clone();
                    let (lo, hi) = (&lo * &lo, hi * hi);
                    if let Some(o) = x.cmp_modulus(&lo, &hi) {
                        decided = Some(o);
                        break;
                    }
                }
                match decided {
                    Some(Ordering::Greater) => outside = true,
                    Some(_) => {}
                    None => fallback = true,
                }
            }
        }
    }
    let class = if outside {
        CurvatureClass::Sharp
    } else if fallback {
        // A complex pair too close to the circle |z| = λ1² for the disks: the exact test on
        // g(x) = h2(λ1²·x), h2 = χ / ((x − 1)(x − λ1)), over Q(λ1).
        let h = chi
            .exact_div(&Poly::from_ints(&[-1, 1]))
            .expect("1 is a root");
        let (h2, _) = k_divrem(
            &k,
            &to_k(&k, &h),
            &[
                k.sub(&k.rational(BigRational::zero()), &rho_k),
                k.rational(q(1)),
            ],
        );
        let g = k_scale_var(&k, &h2, &r2);
        match circle_position(&k, &g) {
            Position::Inside => CurvatureClass::Flat,
            Position::OnCircle => {
                complex_on_circle = !on_circle;
                CurvatureClass::Finite
            }
            Position::Outside => CurvatureClass::Sharp,
            Position::Undecided => CurvatureClass::Undecided,
        }
    } else if on_circle {
        CurvatureClass::Finite
    } else {
        CurvatureClass::Flat
    };
    // λ2 = ±λ1² real: keep it and its eigenvector for dyadic points and curvature.
    let mut second = None;
    for w in &which {
        let s = if *w == "λ1²" { q(1) } else { q(-1) };
        let l2 = k.scale(&r2, &s);
        let multiple = reals
            .iter()
            .any(|r| r.mult > 1 && cmp_abs_with_square(&r.value, &rho, &k) == Ordering::Equal);
        if second.is_none() && !multiple {
            if let Some(v) = eigenvector_in(&k, t, chi, &l2) {
                second = Some((l2, v));
            }
        }
    }
    let detail = if others == 0 {
        "no eigenvalue besides 1 and λ1: the curve is straight at its fixed point".to_string()
    } else {
        match class {
            CurvatureClass::Flat => "every other eigenvalue has modulus < λ1² (α > 2)".to_string(),
            CurvatureClass::Sharp => "an eigenvalue has modulus > λ1² (α < 2)".to_string(),
            CurvatureClass::Finite if which.is_empty() || complex_on_circle && which.is_empty() => {
                "a complex pair has modulus exactly λ1² and none exceeds it (α = 2)".to_string()
            }
            CurvatureClass::Finite => format!(
                "λ2 = {} and no eigenvalue exceeds λ1² in modulus (α = 2)",
                which.join(" and ")
            ),
            CurvatureClass::Undecided => {
                "several eigenvalues of modulus λ1² related by inversion: not decided".to_string()
            }
        }
    };
    (
        Behaviour::Tangent { class, detail },
        Some(TangentData {
            field: k,
            lambda1: rho,
            v1,
            second,
        }),
    )
}

/// The polynomial, or `a factor of degree d` when it is long.
fn short_poly(p: &Poly) -> String {
    let s = p.to_string();
    if s.chars().count() <= 60 {
        s
    } else {
        format!("an irreducible factor of degree {}", p.deg())
    }
}

/// The exact form, or `≈ decimal (degree d)` when it is long.
fn short_number(r: &RealAlgebraic) -> String {
    let s = r.to_string();
    if s.chars().count() <= 60 {
        s
    } else {
        format!("≈ {} (degree {})", r.decimal(12), r.degree())
    }
}

/// `−r`: the root of `f(−x)` (f the minimal polynomial of r) mirroring r — real roots come in
/// opposite order.
pub(crate) fn negate(r: &RealAlgebraic) -> RealAlgebraic {
    let f = r.min_poly();
    let roots = RealAlgebraic::real_roots(f);
    let i = roots
        .iter()
        .position(|x| x.cmp_exact(r) == Ordering::Equal)
        .expect("r is a root of its minimal polynomial");
    let mut mirrored = RealAlgebraic::real_roots(&reflect(f));
    mirrored.swap_remove(roots.len() - 1 - i)
}

mod text;
pub use text::{parse_matrix_arg, parse_rationals_arg};
