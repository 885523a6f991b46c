//! The Differential Characteristic Function (DCF) of Janbein, Gentil, Roudet and Poull,
//! "Pseudo-curvature of fractal curves" (GRAPP 2024), and the pseudo-curvature ranges it gives at
//! fixed points and dyadic points of a curve.
//!
//! Near the fixed point c of T, a point `q = c + x1·v1 + x2·v2 + …` is sent by T^n to
//! `c + x1·λ1^n·v1 + x2·λ2^n·v2 + …`, and these points lie on `D(t) = c + t·v1 + β·|t|^α·v2` with
//! `α = log|λ2| / log|λ1|` and `β = x2 / |x1|^α` (invariant along the orbit when λ1, λ2 > 0).
//! Exact here: c, λ1, λ2, v1, v2 (and the left eigenvectors), x1, x2; α when it is 2 (λ2 = ±λ1²,
//! decided exactly) or a rational p/q verified exactly (`|λ2|^q = |λ1|^p`, rational λs); β when
//! α = 2. The pseudo-curvature at c is, by α: +∞ (α < 2), 0 (α > 2), and for α = 2 the range of
//! `κ = 2|β|·|V1 × V2| / |V1|³` (V = P·v projected by the control points P) over the family of
//! DCFs, i.e. over the attractor's points. That range is computed from exact attractor points
//! (images of the fixed points under all words of a length) evaluated in floating point: an
//! inner estimate of [κinf, κsup], labelled as such; the class itself is exact.
//!
//! Sub-sequences (the paper's double DCF): λ1 < 0 sends the even and odd iterates to the two
//! sides of c along v1 (`c ± t·v1 + β·t^α·v2`), so each side collects the β of both sides;
//! λ2 < 0 alternates the sign of β. A dyadic point `p = T_w·c_k` carries the family of `T_k`
//! mapped by `T_w`: the same β, projected by the control points `P·T_w`.
//!
//! The parts: this file holds the DCF of one operator at its fixed point (the exact eigen data,
//! α, β, the class); `curvature.rs` the pseudo-curvature ranges of a curve at its fixed points
//! and dyadic points, from attractor samples; `render.rs` their text and SVG picture.

mod curvature;
mod render;

pub use curvature::{curve_curvature, CurveCurvature, DyadicPoint, SideRange};

use crate::algebra::algebraic::{FieldElement, NumberField, RealAlgebraic};
use crate::algebra::disk::root_disks;
use crate::algebra::factor::factor;
use crate::algebra::fieldpoly::{adjugate_eigenvector, AdjugateChains};
use crate::algebra::matrix::Matrix;
use crate::analysis::operators::operator::{
    char_poly, cmp_abs_with_square, eigenvector_in, f64_of, negate, render_vec,
};
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};
use serde::{Serialize, Serializer};
use std::cmp::Ordering;

/// A curvature value: a number, or +∞ (serialised as the string `"inf"`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Kappa(pub f64);

impl Serialize for Kappa {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        if self.0.is_infinite() {
            s.serialize_str("inf")
        } else {
            s.serialize_f64(self.0)
        }
    }
}

impl std::fmt::Display for Kappa {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.0.is_infinite() {
            f.write_str("+∞")
        } else {
            write!(f, "{:.6}", self.0)
        }
    }
}

/// The pseudo-curvature class at the fixed point: `oscillating` when λ1 < 0 (THEORY §8: the
/// tangent flips between v1 and −v1 and κsup is +∞ — the even and odd iterates each lie on a DCF
/// of exponent α, but the curve between them crosses the line c + ℝ·v1), else `sharp`, `finite`
/// or `flat` as α is below, equal to or above 2.
pub(crate) fn class_of(d: &DcfData) -> &'static str {
    if d.lambda1_negative {
        return "oscillating";
    }
    match d.order {
        Ordering::Greater => "sharp",
        Ordering::Equal => "finite",
        Ordering::Less => "flat",
    }
}

/// The DCF of one operator at its fixed point, with its exact ingredients.
#[derive(Clone, Debug, Serialize)]
pub struct Dcf {
    /// The operator.
    pub operator: String,
    /// The fixed point c (barycentric), exact.
    pub c: Vec<String>,
    /// λ1, the real eigenvalue of largest modulus below 1, exact.
    pub lambda1: String,
    /// λ2, the next one (real), exact.
    pub lambda2: String,
    /// v1, exact (in Q(λ1)).
    pub v1: Vec<String>,
    /// v2, exact (in Q(λ1) when λ2 is rational or ±λ1², else in Q(λ2)).
    pub v2: Vec<String>,
    /// α: `2` or `p/q` when exact, else `log|λ2|/log|λ1|`.
    pub alpha: String,
    /// Whether `alpha` is an exact value.
    pub alpha_exact: bool,
    /// α in floating point.
    pub alpha_approx: f64,
    /// The paper's case: signs of λ1 and λ2 and what the iterates do.
    pub case: String,
    /// The class by α, exact: `sharp` (α < 2, κ = +∞), `finite` (α = 2), `flat` (α > 2, κ = 0).
    pub class: String,
    /// β for chosen starting points (the other fixed points of the curve), with x1 and x2.
    pub starts: Vec<DcfStart>,
}

/// `D_{T,q}` for one starting point q.
#[derive(Clone, Debug, Serialize)]
pub struct DcfStart {
    /// Where q comes from (`fix(T1)`).
    pub from: String,
    /// x1, the coordinate of q − c along v1, exact.
    pub x1: String,
    /// x2, along v2, exact.
    pub x2: String,
    /// β = x2 / |x1|^α: exact when α = 2, else `None`.
    pub beta: Option<String>,
    /// β in floating point.
    pub beta_approx: f64,
}

/// The exact eigen data behind a [`Dcf`].
#[derive(Clone, Debug)]
pub(crate) struct DcfData {
    k1: NumberField,
    k2: NumberField,
    lambda1: FieldElement,
    lambda2: FieldElement,
    v1: Vec<FieldElement>,
    v2: Vec<FieldElement>,
    /// Left eigenvectors scaled so that `u·v = 1`.
    u1: Vec<FieldElement>,
    u2: Vec<FieldElement>,
    c: Vec<BigRational>,
    lambda1_negative: bool,
    lambda2_negative: bool,
    /// Exact: −1 when |λ2| < λ1² (α > 2), 0 for α = 2, 1 for α < 2.
    order: Ordering,
    alpha: f64,
}

fn q(n: i64) -> BigRational {
    BigRational::from_integer(n.into())
}

fn transpose(t: &Matrix) -> Matrix {
    Matrix::from_rows(
        (0..t.cols)
            .map(|j| (0..t.rows).map(|i| t.get(i, j).clone()).collect())
            .collect(),
    )
}

fn dot(k: &NumberField, a: &[FieldElement], b: &[FieldElement]) -> FieldElement {
    a.iter()
        .zip(b)
        .fold(k.rational(BigRational::zero()), |acc, (x, y)| {
            k.add(&acc, &k.mul(x, y))
        })
}

fn dot_q(k: &NumberField, a: &[FieldElement], b: &[BigRational]) -> FieldElement {
    a.iter()
        .zip(b)
        .fold(k.rational(BigRational::zero()), |acc, (x, y)| {
            k.add(&acc, &k.scale(x, y))
        })
}

/// `|r|` as a real algebraic number.
fn abs(r: &RealAlgebraic) -> RealAlgebraic {
    if r.cmp_exact(&RealAlgebraic::rational(BigRational::zero())) == Ordering::Less {
        negate(r)
    } else {
        r.clone()
    }
}

/// `(p, q)` with `p/q` the best rational approximation of `x` with `q ≤ 12`.
fn small_fraction(x: f64) -> Option<(u32, u32)> {
    (1..=12u32)
        .map(|d| ((x * d as f64).round() as u32, d))
        .filter(|&(n, _)| n > 0)
        .min_by(|a, b| {
            let ea = (a.0 as f64 / a.1 as f64 - x).abs();
            let eb = (b.0 as f64 / b.1 as f64 - x).abs();
            ea.partial_cmp(&eb).unwrap_or(Ordering::Equal)
        })
}

/// Why an operator has no DCF of the form `c + t·v1 + β·t^α·v2`.
pub(crate) fn dcf_data(t: &Matrix) -> std::result::Result<DcfData, String> {
    if t.rows != t.cols || t.rows < 2 {
        return Err("needs a square operator of size at least 2".into());
    }
    let chi = char_poly(t);
    let factors = factor(&chi).map_err(|e| e.to_string())?;
    let one = RealAlgebraic::rational(BigRational::one());
    let mut reals: Vec<(RealAlgebraic, usize)> = Vec::new();
    let mut disks = Vec::new();
    let mut ones = 0;
    for (f, m) in &factors {
        let roots = RealAlgebraic::real_roots(f);
        for r in &roots {
            if r.cmp_exact(&one) == Ordering::Equal {
                ones += m;
            } else if !r.as_rational().is_some_and(|x| x.is_zero()) {
                reals.push((r.clone(), *m));
            }
        }
        if roots.len() < f.deg() {
            match root_disks(f) {
                Some(d) => disks.extend(d.into_iter().filter(|x| x.above_axis())),
                None => return Err("complex eigenvalues too close to separate".into()),
            }
        }
    }
    if ones != 1 {
        return Err("1 is not a simple eigenvalue".into());
    }
    // Decreasing |λ|.
    let mut absr: Vec<(RealAlgebraic, RealAlgebraic, usize)> =
        reals.iter().map(|(r, m)| (abs(r), r.clone(), *m)).collect();
    absr.sort_by(|a, b| b.0.cmp_exact(&a.0));
    let Some((a1, l1, m1)) = absr.first().cloned() else {
        return Err("no real eigenvalue besides 1 and 0".into());
    };
    if m1 > 1 {
        return Err(format!(
            "λ1 = λ2 = {l1} (a repeated eigenvalue): the iterates converge to c along straight lines, one per starting point (no single tangent, no curvature)"
        ));
    }
    if absr
        .get(1)
        .is_some_and(|x| x.0.cmp_exact(&a1) == Ordering::Equal)
    {
        return Err(format!(
            "λ1 = −λ2, |λ1| = |λ2| = {a1}: α = 1, the even and odd iterates lie on the lines c + t·v1 + β·t·v2 and c − t·v1 + β·t·v2 (the direction oscillates between two extremes; no curvature)"
        ));
    }
    if a1.cmp_exact(&one) != Ordering::Less {
        return Err("|λ1| ≥ 1: not contractive".into());
    }
    let enclose = |r: &RealAlgebraic, x: &crate::algebra::disk::Disk| {
        let mut r = r.clone();
        for d in [40u32, 80, 160] {
            r.refine_to(&BigRational::new(BigInt::one(), BigInt::from(2).pow(d)));
            let (lo, hi) = r.interval();
            let lo = lo.max(&BigRational::zero()).clone();
            if let Some(o) = x.cmp_modulus(&lo, hi) {
                return Some(o);
            }
        }
        None
    };
    if disks
        .iter()
        .any(|x| enclose(&a1, x) != Some(Ordering::Less))
    {
        return Err("a complex pair has modulus ≥ |λ1|: spiralling".into());
    }
    let Some((a2, l2, m2)) = absr.get(1).cloned() else {
        return Err("no second real eigenvalue: the curve is straight at its fixed point".into());
    };
    if m2 > 1
        || absr
            .get(2)
            .is_some_and(|x| x.0.cmp_exact(&a2) == Ordering::Equal)
    {
        return Err(format!("|λ2| = {a2} is shared by two eigenvalues"));
    }
    if disks
        .iter()
        .any(|x| enclose(&a2, x) != Some(Ordering::Less))
    {
        return Err("a complex pair has modulus ≥ |λ2|: λ2 is complex".into());
    }
    let k1 = NumberField::new(a1.clone());
    let neg1 = l1.cmp_exact(&a1) != Ordering::Equal;
    let neg2 = l2.cmp_exact(&a2) != Ordering::Equal;
    let sign = |n: bool| if n { q(-1) } else { q(1) };
    let lambda1 = k1.scale(&k1.generator_element(), &sign(neg1));
    let order = cmp_abs_with_square(&l2, &a1, &k1);
    let (k2, lambda2) = if let Some(r) = l2.as_rational() {
        (k1.clone(), k1.rational(r.clone()))
    } else if order == Ordering::Equal {
        let g = k1.generator_element();
        (k1.clone(), k1.scale(&k1.mul(&g, &g), &sign(neg2)))
    } else {
        let k2 = NumberField::new(l2.clone());
        let g = k2.generator_element();
        (k2, g)
    };
    let tt = transpose(t);
    let (ct, ctt) = (AdjugateChains::new(t, &chi), AdjugateChains::new(&tt, &chi));
    let v1 = eigenvector_in(&k1, t, &ct, &lambda1)
        .ok_or_else(|| String::from("no eigenvector of λ1"))?;
    let v2 = eigenvector_in(&k2, t, &ct, &lambda2)
        .ok_or_else(|| String::from("no eigenvector of λ2"))?;
    let u1 = eigenvector_in(&k1, &tt, &ctt, &lambda1)
        .ok_or_else(|| String::from("no left eigenvector of λ1"))?;
    let u2 = eigenvector_in(&k2, &tt, &ctt, &lambda2)
        .ok_or_else(|| String::from("no left eigenvector of λ2"))?;
    let s1 = k1
        .inv(&dot(&k1, &u1, &v1))
        .ok_or_else(|| String::from("u1·v1 = 0"))?;
    let s2 = k2
        .inv(&dot(&k2, &u2, &v2))
        .ok_or_else(|| String::from("u2·v2 = 0"))?;
    let u1: Vec<FieldElement> = u1.iter().map(|x| k1.mul(x, &s1)).collect();
    let u2: Vec<FieldElement> = u2.iter().map(|x| k2.mul(x, &s2)).collect();
    let qk = crate::algebra::fieldpoly::rationals();
    let cv = adjugate_eigenvector(&ct, &qk, &qk.rational(BigRational::one()))
        .ok_or_else(|| String::from("no fixed point"))?;
    let cv: Vec<BigRational> = cv.iter().map(|x| x.as_rational().expect("Q")).collect();
    let sum: BigRational = cv.iter().sum();
    if sum.is_zero() {
        return Err("the eigenvector of 1 is a direction, not a point".into());
    }
    let c = cv.iter().map(|x| x / &sum).collect();
    let f1 = a1.decimal(17).parse::<f64>().unwrap_or(f64::NAN);
    let f2 = a2.decimal(17).parse::<f64>().unwrap_or(f64::NAN);
    Ok(DcfData {
        k1,
        k2,
        lambda1,
        lambda2,
        v1,
        v2,
        u1,
        u2,
        c,
        lambda1_negative: neg1,
        lambda2_negative: neg2,
        order,
        alpha: if order == Ordering::Equal {
            2.0
        } else {
            f2.ln() / f1.ln()
        },
    })
}

/// The DCF of one operator at its fixed point, for the starting points `starts` (name, point
/// in barycentric coordinates), or the reason why it has none (the paper's cases λ1 = λ2,
/// λ1 = −λ2, complex λ2, …).
pub fn operator_dcf(
    name: &str,
    t: &Matrix,
    starts: &[(String, Vec<BigRational>)],
) -> std::result::Result<Dcf, String> {
    dcf_data(t).map(|d| d.report(name, starts))
}

impl DcfData {
    /// `(x1, x2)` of the point q, exact.
    fn coords(&self, p: &[BigRational]) -> (FieldElement, FieldElement) {
        let d: Vec<BigRational> = p.iter().zip(&self.c).map(|(a, b)| a - b).collect();
        (dot_q(&self.k1, &self.u1, &d), dot_q(&self.k2, &self.u2, &d))
    }

    /// The report, with β for each named starting point.
    pub(crate) fn report(&self, name: &str, starts: &[(String, Vec<BigRational>)]) -> Dcf {
        let (k1, k2) = (&self.k1, &self.k2);
        let l1 = k1.render(&self.lambda1);
        let l2 = k2.render(&self.lambda2);
        let (alpha, alpha_exact) = match self.order {
            Ordering::Equal => ("2".to_string(), true),
            _ => self.exact_alpha().map_or_else(
                || (format!("log|λ2|/log|λ1| ≈ {:.9}", self.alpha), false),
                |(p, q)| (format!("{p}/{q}"), true),
            ),
        };
        let case = match (self.lambda1_negative, self.lambda2_negative) {
            (false, false) => "λ1 > 0, λ2 > 0: one DCF per starting point",
            (true, false) => "λ1 < 0: even iterates on c + t·v1 + β·t^α·v2, odd ones on c − t·v1 + β·t^α·v2 (two sub-sequences, on both sides of c, with one β: x1 → λ1·x1 and x2 → λ2·x2 leave x2/|x1|^α unchanged, so each side's κ range serves both parities)",
            (false, true) => "λ2 < 0: even iterates on c + t·v1 + β·t^α·v2, odd ones on c + t·v1 − β·t^α·v2 (two sub-sequences, β of both signs)",
            (true, true) => "λ1 < 0 and λ2 < 0: even iterates on c + t·v1 + β·t^α·v2, odd ones on c − t·v1 − β·t^α·v2 (one |β| for both: each side's κ range serves both parities)",
        };
        let class = class_of(self);
        let starts = starts
            .iter()
            .filter_map(|(from, p)| {
                let (x1, x2) = self.coords(p);
                if x1.is_zero() {
                    return None;
                }
                let (f1, f2) = (f64_of(k1, &x1), f64_of(k2, &x2));
                let beta = (self.order == Ordering::Equal).then(|| {
                    let sq = k1.mul(&x1, &x1);
                    k1.render(&k1.mul(&x2, &k1.inv(&sq).expect("x1 ≠ 0")))
                });
                Some(DcfStart {
                    from: from.clone(),
                    x1: k1.render(&x1),
                    x2: k2.render(&x2),
                    beta,
                    beta_approx: f2 / f1.abs().powf(self.alpha),
                })
            })
            .collect();
        Dcf {
            operator: name.to_string(),
            c: self.c.iter().map(ToString::to_string).collect(),
            lambda1: l1,
            lambda2: l2,
            v1: render_vec(k1, &self.v1),
            v2: render_vec(k2, &self.v2),
            alpha,
            alpha_exact,
            alpha_approx: self.alpha,
            case: case.to_string(),
            class: class.to_string(),
            starts,
        }
    }

    /// α = p/q exactly, for rational λ1 and λ2 with `|λ2|^q = |λ1|^p` (q ≤ 12).
    fn exact_alpha(&self) -> Option<(u32, u32)> {
        let a = self.lambda1.as_rational()?.abs();
        let b = self.lambda2.as_rational()?.abs();
        let (p, d) = small_fraction(self.alpha)?;
        (b.pow(d as i32) == a.pow(p as i32)).then_some((p, d))
    }

    /// `V1, V2` projected by `proj` (dim × n, floats).
    fn projected(&self, proj: &[Vec<f64>]) -> (Vec<f64>, Vec<f64>) {
        let f = |k: &NumberField, v: &[FieldElement]| -> Vec<f64> {
            let w: Vec<f64> = v.iter().map(|x| f64_of(k, x)).collect();
            proj.iter()
                .map(|row| row.iter().zip(&w).map(|(a, b)| a * b).sum())
                .collect()
        };
        (f(&self.k1, &self.v1), f(&self.k2, &self.v2))
    }

    /// `|V1 × V2| / |V1|³` for the projection.
    fn shape(&self, proj: &[Vec<f64>]) -> f64 {
        let (a, b) = self.projected(proj);
        let cross2 = if a.len() == 2 {
            (a[0] * b[1] - a[1] * b[0]).powi(2)
        } else {
            (a[1] * b[2] - a[2] * b[1]).powi(2)
                + (a[2] * b[0] - a[0] * b[2]).powi(2)
                + (a[0] * b[1] - a[1] * b[0]).powi(2)
        };
        let n2: f64 = a.iter().map(|x| x * x).sum();
        cross2.sqrt() / n2.powf(1.5)
    }

    /// `(x1, β)` of the attractor samples, floats (points with x1 ≈ 0 skipped).
    fn betas(&self, samples: &[Vec<f64>]) -> Vec<(f64, f64)> {
        let u1: Vec<f64> = self.u1.iter().map(|x| f64_of(&self.k1, x)).collect();
        let u2: Vec<f64> = self.u2.iter().map(|x| f64_of(&self.k2, x)).collect();
        let c: Vec<f64> = self
            .c
            .iter()
            .map(|x| x.to_f64().unwrap_or(f64::NAN))
            .collect();
        samples
            .iter()
            .filter_map(|p| {
                let d: Vec<f64> = p.iter().zip(&c).map(|(a, b)| a - b).collect();
                let x1: f64 = u1.iter().zip(&d).map(|(a, b)| a * b).sum();
                let x2: f64 = u2.iter().zip(&d).map(|(a, b)| a * b).sum();
                (x1.abs() > 1e-12).then(|| (x1, x2 / x1.abs().powf(self.alpha)))
            })
            .collect()
    }
}
