//! The exact limit ratio `R = lim N^L_i / (N^L_i + N^C_i)` (THEORY §5), by eigen analysis with
//! algebraic numbers.
//!
//! # The argument
//! Augment the substitution matrix `M` with one type `L` collecting lacunas:
//! `M' = [[M, c], [0, 1]]`. With `e` the start vector, `N^C_i = (e,0)·M'^i·(1,…,1,0)` and
//! `N^L_i = (e,0)·M'^i·(0,…,0,1)`. `M'` is block triangular over its strongly connected classes;
//! by Perron–Frobenius its eigenvalues of modulus `ρ` (the largest class radius) are `ρ·ω` with
//! `ω^p = 1` for the period `p` of a class of radius `ρ`. With `P` the lcm of those periods and
//! `A = M'^P`, each subsequence `x_n = X_{Pn+r}` has generating function `N(w)/D(w)` with
//! `D(w) = det(I − wA)` (a product over the class blocks) and `deg N < dim`; its only dominant
//! pole is `w₀ = ρ^(−P)`. The coefficient of `w^n` grows like `n^(k−1) ρ^(Pn)` times a constant
//! proportional to `Ñ(w₀)`, `k` the pole order, `Ñ = N / (w − w₀)^ord`, the proportionality being
//! the same for lacunas and sub-faces. So `R_r = 1` or `0` when the pole orders differ, else
//! `Ñ_L(w₀) / (Ñ_L(w₀) + Ñ_C(w₀))`; the limit exists iff every residue `r` gives the same `R_r`.
//!
//! Computation stays over Q: the substitution `w = y^(−P)` (with `y^(P·K)` cleared) maps the root
//! `w₀` to `y = ρ`, preserving multiplicities, so the order is the multiplicity of the minimal
//! polynomial `f` of `ρ` in a rational polynomial, and `Ñ(w₀)` is, up to factors common to
//! lacunas and sub-faces, the residue of the cofactor modulo `f`, an element of Q(ρ).

use crate::algebra::algebraic::{FieldElement, NumberField, RealAlgebraic, DEFAULT_DIGITS};
use crate::algebra::factor::{charpoly, factor, FactorError};
use crate::algebra::poly::Poly;
use crate::topology::class::ClassStructure;
use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
use serde::Serialize;
use std::cmp::Ordering;

/// What made the analysis impossible.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum RatioError {
    /// A type index beyond the matrix.
    #[error("face type {face_type} is out of range (there are {types} types)")]
    TypeOutOfRange {
        /// The offending index.
        face_type: usize,
        /// The number of types.
        types: usize,
    },
    /// The contribution vector does not have one entry per type.
    #[error("{contributions} contributions for {types} face types")]
    LengthMismatch {
        /// Its length.
        contributions: usize,
        /// The number of types.
        types: usize,
    },
    /// A reached face type has no sub-face.
    #[error("face type {face_type} has no sub-face")]
    NoSubFace {
        /// The type.
        face_type: usize,
    },
    /// A negative contribution.
    #[error("face type {face_type} has a negative contribution")]
    NegativeContribution {
        /// The type.
        face_type: usize,
    },
    /// The start vector is empty.
    #[error("the start vector has no face")]
    EmptyStart,
    /// A characteristic polynomial could not be factored within budget.
    #[error(transparent)]
    Factor(#[from] FactorError),
}

/// One strongly connected class with its spectral radius.
#[derive(Clone, Debug, Serialize)]
pub struct ClassReport {
    /// Type indices, ascending.
    pub members: Vec<usize>,
    /// The gcd of the cycle lengths; `None` for a transient type.
    pub period: Option<u64>,
    /// The spectral radius, exact (same string forms as [`RatioReport::perron_root`]).
    pub spectral_radius: String,
    /// Its certified decimals.
    pub spectral_radius_decimal: String,
    /// Whether the radius equals `ρ`.
    pub dominant: bool,
    /// The spectral radius as a number.
    #[serde(skip)]
    pub radius: RealAlgebraic,
}

/// The limit of `R_{Pn+r}` for one residue `r`.
#[derive(Clone, Debug, Serialize)]
pub struct LimitPoint {
    /// The residue `r` modulo [`RatioReport::period`].
    pub residue: u64,
    /// Exact value (same string forms as [`RatioReport::exact`]).
    pub exact: String,
    /// Certified decimals.
    pub decimal: String,
    /// The value in Q(ρ).
    #[serde(skip)]
    pub value: FieldElement,
}

/// The outcome of the eigen analysis.
#[derive(Clone, Debug, Serialize)]
pub struct RatioReport {
    /// Whether `R_i` converges.
    pub exists: bool,
    /// The limit, exact, when it exists: `1/3` when rational; `(a + b*sqrt(d))/c` when `ρ` is
    /// quadratic; otherwise `<polynomial in rho> where rho = root of <min poly> in [lo, hi]`.
    /// `None` (JSON `null`) when the limit does not exist: see `limit_points`.
    pub exact: Option<String>,
    /// Certified decimals of the limit (truncated), when it exists.
    pub decimal: Option<String>,
    /// The limit on the power basis `1, ρ, …, ρ^(deg−1)` of Q(ρ), when it exists.
    pub coordinates: Option<Vec<String>>,
    /// `ρ`, the largest spectral radius: `6`, `(1 + sqrt(5))/2`, or `root of <min poly> in
    /// [lo, hi]`.
    pub perron_root: String,
    /// Certified decimals of `ρ`.
    pub perron_decimal: String,
    /// The minimal polynomial of `ρ` over Q (irreducible), in `x`.
    pub perron_min_poly: String,
    /// `P`: the lcm of the periods of the dominant classes.
    pub period: u64,
    /// The classes reached from the start, sources first.
    pub classes: Vec<ClassReport>,
    /// Indices into `classes` of the classes of radius `ρ`.
    pub dominant: Vec<usize>,
    /// `lim R_{Pn+r}` for `r = 0..P` (one entry when `P = 1`).
    pub limit_points: Vec<LimitPoint>,
    /// How the decision was reached, for people.
    pub reasons: Vec<String>,
    /// Q(ρ).
    #[serde(skip)]
    pub field: NumberField,
    /// The limit in Q(ρ), when it exists.
    #[serde(skip)]
    pub ratio: Option<FieldElement>,
}

impl RatioReport {
    /// At least `digits` certified digits of the limit after the point, when it exists.
    pub fn decimal(&self, digits: usize) -> Option<String> {
        self.ratio.as_ref().map(|r| self.field.decimal(r, digits))
    }

    /// Recomputes every decimal string with `digits` digits.
    pub fn with_digits(mut self, digits: usize) -> Self {
        self.decimal = self.decimal(digits);
        self.perron_decimal = self.field.generator().decimal(digits);
        for p in &mut self.limit_points {
            p.decimal = self.field.decimal(&p.value, digits);
        }
        for c in &mut self.classes {
            c.spectral_radius_decimal = c.radius.decimal(digits);
        }
        self
    }
}

/// The spectral radius of a class block with characteristic polynomial `chi`: its largest real
/// root. Every eigenvalue has modulus at most the largest row sum `row_max` (Perron–Frobenius),
/// so integer roots are split off by testing `−row_max..=row_max`; the rest is factored and the
/// largest real root of each irreducible factor compared exactly.
fn spectral_radius(chi: &Poly, row_max: u64) -> Result<RealAlgebraic, FactorError> {
    let mut rest = chi.clone();
    while !rest.is_zero() && rest.coeff(0).is_zero() {
        rest = rest.exact_div(&Poly::x()).expect("x divides");
    }
    let mut best: Option<RealAlgebraic> = None;
    let bound = i64::try_from(row_max).unwrap_or(i64::MAX);
    for k in (-bound..=bound).rev().filter(|&k| k != 0) {
        let lin = Poly::from_ints(&[-k, 1]);
        let mut found = false;
        while rest.deg() > 0 {
            match rest.exact_div(&lin) {
                Some(q) => {
                    rest = q;
                    found = true;
                }
                None => break,
            }
        }
        if found && best.is_none() {
            best = Some(RealAlgebraic::rational(BigRational::from_integer(k.into())));
        }
    }
    if best.is_none() {
        best = Some(RealAlgebraic::rational(BigRational::zero()));
    }
    let mut best = best.expect("set above");
    if rest.deg() > 0 {
        for (g, _) in factor(&rest)? {
            if let Some(r) = RealAlgebraic::largest_root(&g) {
                if r.cmp_exact(&best) == Ordering::Greater {
                    best = r;
                }
            }
        }
    }
    Ok(best)
}

/// `det(I − w·B^P)` from `χ_B = det(x·I − B)`, through power sums (Newton's identities): the
/// power sums of the eigenvalues of `B^P` are those of `B` at multiples of `P`.
fn reversed_power_charpoly(chi: &Poly, period: u64) -> Vec<BigInt> {
    let n = chi.deg();
    // c_k: coefficient of x^(n−k); integers as chi is monic integral.
    let c: Vec<BigInt> = (0..=n).map(|k| chi.coeff(n - k).to_integer()).collect();
    let big_p = usize::try_from(period).expect("period fits usize");
    let top = big_p * n;
    let mut ps = vec![BigInt::zero(); top + 1];
    for m in 1..=top {
        let mut s = if m <= n {
            &c[m] * BigInt::from(m)
        } else {
            BigInt::zero()
        };
        for i in 1..=n.min(m - 1) {
            s += &c[i] * &ps[m - i];
        }
        ps[m] = -s;
    }
    let q: Vec<&BigInt> = (0..=n).map(|k| &ps[k * big_p]).collect();
    let mut d = vec![BigInt::one()];
    for k in 1..=n {
        let mut s = q[k].clone();
        for i in 1..k {
            s += &d[i] * q[k - i];
        }
        d.push(-s / BigInt::from(k));
    }
    d
}

/// The multiplicity of the monic integral `f` in the integral `p` (nonzero) and the cofactor.
/// Division by a monic integer polynomial stays in Z, so this runs on integers.
pub(crate) fn split_off(p: &[BigInt], f: &Poly) -> (usize, Poly) {
    let f: Vec<BigInt> = f.coeffs().iter().map(BigRational::to_integer).collect();
    let df = f.len() - 1;
    let mut h: Vec<BigInt> = p.to_vec();
    while h.last().is_some_and(Zero::is_zero) {
        h.pop();
    }
    let mut e = 0;
    while h.len() > df {
        let mut r = h.clone();
        let mut q = vec![BigInt::zero(); r.len() - df];
        for i in (0..q.len()).rev() {
            let t = std::mem::take(&mut r[i + df]);
            if t.is_zero() {
                continue;
            }
            for (j, fj) in f.iter().enumerate().take(df) {
                if !fj.is_zero() {
                    r[i + j] -= &t * fj;
                }
            }
            q[i] = t;
        }
        if !r.iter().all(Zero::is_zero) {
            break;
        }
        e += 1;
        h = q;
    }
    (e, Poly::from_bigints(&h))
}

/// `y^(P·K) · N(y^(−P))` for the coefficients `n` of `N(w)`, `deg N ≤ K`.
pub(crate) fn reflect(n: &[BigInt], period: usize, k: usize) -> Vec<BigInt> {
    let mut c = vec![BigInt::zero(); period * k + 1];
    for (j, a) in n.iter().enumerate() {
        c[period * (k - j)] = a.clone();
    }
    c
}

/// The part of a substitution's spectrum that decides its limits (module doc).
pub(crate) struct Spectrum {
    /// The states reached from the start, ascending.
    pub(crate) reached: Vec<usize>,
    /// The classes reached from the start, sources first.
    pub(crate) classes: Vec<ClassReport>,
    /// `ρ`, the largest spectral radius.
    pub(crate) rho: RealAlgebraic,
    /// Indices into `classes` of the classes of radius `ρ`.
    pub(crate) dominant: Vec<usize>,
    /// `P`, the lcm of the periods of the dominant classes.
    pub(crate) period: u64,
    /// `Π det(I − w·B^P)` over the non-transient class blocks `B`, lowest degree first.
    pub(crate) det: Vec<BigInt>,
}

/// The classes of the substitution `m` reached from `start_types`, their spectral radii, `ρ`,
/// `P` and the denominator `det(I − w·M^P)` of the generating functions of every subsequence
/// `x_{Pn+r}` of a count (`M` block triangular over its classes).
pub(crate) fn spectrum(
    m: &[Vec<(usize, u64)>],
    start_types: &[usize],
) -> Result<Spectrum, FactorError> {
    spectrum_of(m, &ClassStructure::new(&successors(m), start_types))
}

/// The states each state of `m` has a positive count of.
fn successors(m: &[Vec<(usize, u64)>]) -> Vec<Vec<usize>> {
    m.iter()
        .map(|row| {
            row.iter()
                .filter(|&&(_, k)| k > 0)
                .map(|&(s, _)| s)
                .collect()
        })
        .collect()
}

/// [`spectrum`] over the class structure of `m` already built from its start.
fn spectrum_of(
    m: &[Vec<(usize, u64)>],
    structure: &ClassStructure,
) -> Result<Spectrum, FactorError> {
    let n = m.len();
    let reached: Vec<usize> = (0..n)
        .filter(|&t| structure.class_of[t].is_some())
        .collect();
    // Per class: characteristic polynomial of its block and spectral radius.
    let mut chis: Vec<Option<Poly>> = Vec::new();
    let mut classes: Vec<ClassReport> = Vec::new();
    for class in &structure.classes {
        let idx = |t: usize| class.members.binary_search(&t).ok();
        let block: Vec<Vec<BigInt>> = class
            .members
            .iter()
            .map(|&t| {
                let mut row = vec![BigInt::zero(); class.members.len()];
                for &(s, k) in &m[t] {
                    if let Some(j) = idx(s) {
                        row[j] += k;
                    }
                }
                row
            })
            .collect();
        let row_sums: Vec<BigInt> = block.iter().map(|r| r.iter().sum()).collect();
        let (chi, radius) = if class.period.is_none() {
            (None, RealAlgebraic::rational(BigRational::zero()))
        } else if row_sums.iter().all(|s| *s == row_sums[0]) {
            // Equal row sums k: the all-ones vector is a positive eigenvector, so ρ = k.
            let k = BigRational::from_integer(row_sums[0].clone());
            (Some(charpoly(&block)), RealAlgebraic::rational(k))
        } else {
            let chi = charpoly(&block);
            let row_max = row_sums.iter().max().expect("nonempty").clone();
            let row_max = u64::try_from(row_max).unwrap_or(u64::MAX);
            let r = spectral_radius(&chi, row_max)?;
            (Some(chi), r)
        };
        chis.push(chi);
        classes.push(ClassReport {
            members: class.members.clone(),
            period: class.period,
            spectral_radius: radius.to_string(),
            spectral_radius_decimal: radius.decimal(DEFAULT_DIGITS),
            dominant: false,
            radius,
        });
    }
    let mut rho = RealAlgebraic::rational(BigRational::zero());
    for cl in &classes {
        if cl.radius.cmp_exact(&rho) == Ordering::Greater {
            rho = cl.radius.clone();
        }
    }
    let mut dominant = Vec::new();
    let mut big_p = 1u64;
    for (i, cl) in classes.iter_mut().enumerate() {
        if cl.radius.cmp_exact(&rho) == Ordering::Equal {
            cl.dominant = true;
            dominant.push(i);
            big_p = big_p.lcm(&cl.period.expect("a dominant class has a cycle (ρ ≥ 1)"));
        }
    }
    let mut det = vec![BigInt::one()];
    for chi in chis.iter().flatten() {
        det = poly_mul(&det, &reversed_power_charpoly(chi, big_p));
    }
    Ok(Spectrum {
        reached,
        classes,
        rho,
        dominant,
        period: big_p,
        det,
    })
}

/// The product of two integer polynomials (coefficients lowest first).
pub(crate) fn poly_mul(a: &[BigInt], b: &[BigInt]) -> Vec<BigInt> {
    let mut prod = vec![BigInt::zero(); a.len() + b.len() - 1];
    for (i, x) in a.iter().enumerate() {
        for (j, y) in b.iter().enumerate() {
            prod[i + j] += x * y;
        }
    }
    prod
}

/// The numerator `N(w) = D(w)·X(w) mod w^dim` of the generating function of `x_{Pn+r}`, from
/// the first `P·dim` terms of `x` (`deg N < dim`).
pub(crate) fn numerator(
    d: &[BigInt],
    seq: &[BigInt],
    period: usize,
    dim: usize,
    r: usize,
) -> Vec<BigInt> {
    (0..dim)
        .map(|j| {
            (0..=j.min(d.len() - 1))
                .map(|i| &d[i] * &seq[period * (j - i) + r])
                .sum()
        })
        .collect()
}

/// Analyses the limit ratio of the substitution `m` (`m[t]` lists `(s, k)`: a face of type `t`
/// has `k` sub-faces of type `s`), contributions `c` (lacunas added by subdividing one face of
/// each type) and start faces `start` (`(type, multiplicity)`). Decimals have
/// [`DEFAULT_DIGITS`] digits; see [`RatioReport::with_digits`].
pub fn analyse(
    m: &[Vec<(usize, u64)>],
    c: &[BigRational],
    start: &[(usize, u64)],
) -> Result<RatioReport, RatioError> {
    let n = m.len();
    if c.len() != n {
        return Err(RatioError::LengthMismatch {
            contributions: c.len(),
            types: n,
        });
    }
    for &(t, _) in start.iter().chain(m.iter().flatten()) {
        if t >= n {
            return Err(RatioError::TypeOutOfRange {
                face_type: t,
                types: n,
            });
        }
    }
    let start: Vec<(usize, u64)> = start.iter().copied().filter(|&(_, k)| k > 0).collect();
    if start.is_empty() {
        return Err(RatioError::EmptyStart);
    }
    let succ = successors(m);
    let start_types: Vec<usize> = start.iter().map(|&(t, _)| t).collect();
    // Checked before the spectrum: a reached type without sub-face would leave no cycle.
    let structure = ClassStructure::new(&succ, &start_types);
    for t in (0..n).filter(|&t| structure.class_of[t].is_some()) {
        if succ[t].is_empty() {
            return Err(RatioError::NoSubFace { face_type: t });
        }
        if c[t].is_negative() {
            return Err(RatioError::NegativeContribution { face_type: t });
        }
    }
    let Spectrum {
        reached,
        classes,
        rho,
        dominant,
        period: big_p,
        det,
    } = spectrum_of(m, &structure)?;
    let field = NumberField::new(rho.clone());
    let f = rho.min_poly().clone();
    let period = usize::try_from(big_p).expect("period fits usize");

    // D(w) = (1 − w) · Π det(I − w B^P) over the non-transient blocks.
    let d = poly_mul(&[BigInt::one(), -BigInt::one()], &det);
    let dim = reached.len() + 1;

    // The counts X_i for i < P·dim, lacunas scaled by `den` to stay integral.
    let den = reached
        .iter()
        .fold(BigInt::one(), |acc, &t| acc.lcm(c[t].denom()));
    let cint: Vec<BigInt> = c
        .iter()
        .map(|x| (x * BigRational::from_integer(den.clone())).to_integer())
        .collect();
    let mut v = vec![BigInt::zero(); n];
    for &(t, k) in &start {
        v[t] += k;
    }
    let mut lac = BigInt::zero();
    let (mut seq_c, mut seq_l) = (Vec::new(), Vec::new());
    for _ in 0..period * dim {
        seq_c.push(reached.iter().map(|&t| &v[t]).sum::<BigInt>());
        seq_l.push(lac.clone());
        let mut next = vec![BigInt::zero(); n];
        for &t in &reached {
            if v[t].is_zero() {
                continue;
            }
            for &(s, k) in &m[t] {
                next[s] += &v[t] * k;
            }
            lac += &v[t] * &cint[t];
        }
        v = next;
    }

    let (ord_d, _) = split_off(&reflect(&d, period, dim), &f);
    let numerator = |seq: &[BigInt], r: usize| numerator(&d, seq, period, dim, r);
    let mut reasons = vec![format!(
        "{} face type{} reached in {} class{}; rho = {} from the dominant class{} {}",
        reached.len(),
        if reached.len() == 1 { "" } else { "s" },
        classes.len(),
        if classes.len() == 1 { "" } else { "es" },
        rho,
        if dominant.len() == 1 { "" } else { "es" },
        dominant
            .iter()
            .map(|&i| format!(
                "{:?} (period {})",
                classes[i].members,
                classes[i].period.unwrap_or(0)
            ))
            .collect::<Vec<_>>()
            .join(", ")
    )];
    reasons.push(format!(
        "P = lcm of the dominant periods = {big_p}; the pole w0 = rho^-{big_p} of det(I - w M'^{big_p}) has order {ord_d}"
    ));
    let inv_den = field.rational(BigRational::new(BigInt::one(), den.clone()));
    let mut limit_points = Vec::new();
    for r in 0..period {
        let n_c = numerator(&seq_c, r);
        let n_l = numerator(&seq_l, r);
        let (e_c, h_c) = split_off(&reflect(&n_c, period, dim - 1), &f);
        let pole_c = ord_d - e_c;
        debug_assert!(pole_c >= 1, "the face counts grow like rho^i");
        let (value, why) = if n_l.iter().all(Zero::is_zero) {
            (
                field.rational(BigRational::zero()),
                "no lacuna ever: R = 0".to_string(),
            )
        } else {
            let (e_l, h_l) = split_off(&reflect(&n_l, period, dim - 1), &f);
            let pole_l = ord_d - e_l;
            let orders = format!("pole orders: lacunas {pole_l}, sub-faces {pole_c}");
            match pole_l.cmp(&pole_c) {
                Ordering::Greater => (
                    field.rational(BigRational::one()),
                    format!("{orders}: lacunas dominate, R = 1"),
                ),
                Ordering::Less => (
                    field.rational(BigRational::zero()),
                    format!("{orders}: sub-faces dominate, R = 0"),
                ),
                Ordering::Equal => {
                    let a_l = field.mul(&field.element(&h_l), &inv_den);
                    let a_c = field.element(&h_c);
                    let value = field
                        .div(&a_l, &field.add(&a_l, &a_c))
                        .expect("leading terms of the same sign are nonzero");
                    (
                        value,
                        format!("{orders}: R = ratio of the leading coefficients at w0"),
                    )
                }
            }
        };
        let residue = if period > 1 {
            format!("i = {r} mod {big_p}: ")
        } else {
            String::new()
        };
        reasons.push(format!("{residue}{why} = {}", field.render(&value)));
        limit_points.push(LimitPoint {
            residue: r as u64,
            exact: field.render(&value),
            decimal: field.decimal(&value, DEFAULT_DIGITS),
            value,
        });
    }
    let exists = limit_points
        .iter()
        .all(|p| p.value == limit_points[0].value);
    let ratio = exists.then(|| limit_points[0].value.clone());
    reasons.push(if exists {
        if period > 1 {
            "the limit exists: every residue class has the same limit".to_string()
        } else {
            "the limit exists".to_string()
        }
    } else {
        format!(
            "the limit does not exist: R_i oscillates between {} limit points",
            period
        )
    });
    Ok(RatioReport {
        exists,
        exact: ratio.as_ref().map(|x| field.render(x)),
        decimal: ratio.as_ref().map(|x| field.decimal(x, DEFAULT_DIGITS)),
        coordinates: ratio.as_ref().map(|x| {
            (0..field.degree())
                .map(|i| x.poly().coeff(i).to_string())
                .collect()
        }),
        perron_root: rho.to_string(),
        perron_decimal: rho.decimal(DEFAULT_DIGITS),
        perron_min_poly: rho.min_poly().to_string(),
        period: big_p,
        classes,
        dominant,
        limit_points,
        reasons,
        field,
        ratio,
    })
}

#[cfg(test)]
mod tests;
