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
//!
//! The parts: this file computes the spectrum (eigenvalues with their certified disks,
//! eigenvectors, the fixed point, contraction); `classify.rs` makes the §8 case analysis at the
//! fixed point (tangent, oscillating, spiralling, degenerate; the class of α); `text.rs` reads
//! matrices from the command line and writes the report.

use crate::algebra::algebraic::{FieldElement, NumberField, RealAlgebraic};
use crate::algebra::disk::{approx_roots, root_disks, sqrt_up, Disk};
use crate::algebra::factor::{charpoly, factor};
use crate::algebra::fieldpoly::{
    adjugate_eigenvector, inside_unit_disk, null_space, rationals, shifted, to_k, AdjugateChains,
};
use crate::algebra::matrix::Matrix;
use crate::algebra::poly::Poly;
use crate::error::{Diagnostic, Error, Result, Source, Span};
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{FromPrimitive, One, ToPrimitive, Zero};
use serde::Serialize;
use std::cmp::Ordering;

mod classify;
mod field;

use classify::classify;
pub(crate) use classify::{cmp_abs_with_square, negate};
pub use field::analyse_kmatrix;

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
    let d = t.data.iter().fold(BigInt::one(), |acc, x| {
        crate::algebra::intgcd::lcm(&acc, x.denom())
    });
    let ints: Vec<Vec<BigInt>> = (0..t.rows)
        .map(|i| {
            (0..t.cols)
                .map(|j| {
                    let x = t.get(i, j);
                    x.numer() * (&d / x.denom())
                })
                .collect()
        })
        .collect();
    // det(x·I − d·T) = d^n · χ_T(x/d).
    let p = charpoly(&ints);
    let n = t.rows;
    // c_i / d^(n−i): one gcd per coefficient, no rational power or product.
    let mut dpow = BigInt::one();
    let mut c: Vec<BigRational> = p
        .coeffs()
        .iter()
        .rev()
        .map(|c| {
            let x = crate::algebra::intgcd::ratio(c.numer().clone(), c.denom() * &dpow);
            dpow *= &d;
            x
        })
        .collect();
    c.reverse();
    debug_assert_eq!(c.len(), n + 1);
    Poly::new(c)
}

pub(crate) fn render_vec(k: &NumberField, v: &[FieldElement]) -> Vec<String> {
    k.render_many(v)
}

pub(crate) fn f64_of(k: &NumberField, a: &FieldElement) -> f64 {
    k.decimal(a, 17).parse().unwrap_or(f64::NAN)
}

/// `t·v` over Q (the point `v` mapped by the operator `t`).
pub(crate) fn mat_vec(t: &Matrix, v: &[BigRational]) -> Vec<BigRational> {
    (0..t.rows)
        .map(|i| v.iter().enumerate().map(|(j, x)| t.get(i, j) * x).sum())
        .collect()
}

/// The entries of `m` as floats, row by row (NaN where one does not fit).
pub(crate) fn mat_f64(m: &Matrix) -> Vec<Vec<f64>> {
    (0..m.rows)
        .map(|i| {
            (0..m.cols)
                .map(|j| m.get(i, j).to_f64().unwrap_or(f64::NAN))
                .collect()
        })
        .collect()
}

/// `m·p` in floating point.
pub(crate) fn mat_vec_f64(m: &[Vec<f64>], p: &[f64]) -> Vec<f64> {
    m.iter()
        .map(|row| row.iter().zip(p).map(|(a, b)| a * b).sum())
        .collect()
}

/// The images of `points` under every word of length `level` of the float operators `ms`, in
/// floating point: each point in turn mapped by each operator, `level` times (attractor samples).
pub(crate) fn images_f64(ms: &[Vec<Vec<f64>>], points: Vec<Vec<f64>>, level: u32) -> Vec<Vec<f64>> {
    let mut pts = points;
    for _ in 0..level {
        pts = pts
            .iter()
            .flat_map(|p| ms.iter().map(move |m| mat_vec_f64(m, p)))
            .collect();
    }
    pts
}

/// A real eigenvalue with its factor's multiplicity. `value` is exactly as
/// [`RealAlgebraic::real_roots`] isolated it, never refined (`classify` mirrors it).
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
    let chains = AdjugateChains::new(t, &chi);
    let mut eigen = Vec::new();
    let mut reals: Vec<RealRoot> = Vec::new();
    let mut complex_disks: Vec<ComplexFactor> = Vec::new();
    for (f, mult) in &factors {
        let roots = RealAlgebraic::real_roots(f);
        for r in &roots {
            let rendered = real_eigenvectors(t, &chains, r, *mult);
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
        let ns = match (mult_one, adjugate_eigenvector(&chains, &qk, &one_k)) {
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
            let s = v.iter().fold(BigRational::zero(), |acc, x| {
                crate::algebra::intgcd::add(&acc, x)
            });
            if s.is_zero() {
                (
                    None,
                    Some(
                        "the eigenvector of 1 has coordinate sum 0: it is a direction, not a point"
                            .into(),
                    ),
                )
            } else {
                let inv = s.recip();
                (
                    Some(
                        v.iter()
                            .map(|x| crate::algebra::intgcd::mul(x, &inv))
                            .collect::<Vec<_>>(),
                    ),
                    None,
                )
            }
        }
    };

    // Contraction: 1 simple, every other root of χ in the open unit disk.
    let contractive = mult_one == 1 && contracts(&reals, &complex_disks);

    let (behaviour, exact) = classify(t, &chi, &chains, mult_one, &reals, &complex_disks);
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
/// ([`adjugate_eigenvector`] on the matrix's `chains`), no elimination over Q(r).
/// Repeated: null space over Q(r).
fn real_eigenvectors(
    t: &Matrix,
    chains: &AdjugateChains,
    r: &RealAlgebraic,
    mult: usize,
) -> Vec<Vec<String>> {
    let k = NumberField::new(r.clone());
    let lam = k.generator_element();
    let vecs = if mult > 1 {
        null_space(&k, shifted(&k, t, &lam))
    } else {
        match adjugate_eigenvector(chains, &k, &lam) {
            Some(v) => vec![v],
            None => null_space(&k, shifted(&k, t, &lam)),
        }
    };
    vecs.iter().map(|v| render_vec(&k, v)).collect()
}

/// One eigenvector of the simple eigenvalue `lam` ∈ K of `t` (whose [`AdjugateChains`] are
/// `chains`).
pub(crate) fn eigenvector_in(
    k: &NumberField,
    t: &Matrix,
    chains: &AdjugateChains,
    lam: &FieldElement,
) -> Option<Vec<FieldElement>> {
    adjugate_eigenvector(chains, k, lam)
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
mod text;
pub use text::{parse_matrix_arg, parse_rationals_arg};
