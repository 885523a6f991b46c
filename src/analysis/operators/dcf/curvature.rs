//! The pseudo-curvature of a curve `T_0 … T_{I−1}` with control points: the ranges on both
//! sides of every operator's fixed point and at the dyadic points (start, joints, end, asked
//! parameters), each seen through the family of DCFs of an operator mapped by a word, with β
//! sampled on exact attractor points evaluated in floating point.

use super::{dcf_data, q, Dcf, DcfData, Kappa};
use crate::algebra::matrix::Matrix;
use crate::analysis::operators::operator::{images_f64, mat_f64, mat_vec, mat_vec_f64, op_error};
use crate::error::Result;
use num_rational::BigRational;
use num_traits::{Signed, ToPrimitive, Zero};
use serde::Serialize;
use std::cmp::Ordering;

/// The pseudo-curvature range on one side of a point.
#[derive(Clone, Debug, Serialize)]
pub struct SideRange {
    /// `left`, `right`, `x1 > 0` or `x1 < 0`.
    pub side: String,
    /// How it is seen: `T0 · (family of T1 at its fixed point)`.
    pub through: String,
    /// `sharp`, `finite` or `flat` (exact).
    pub class: String,
    /// Lower end of the pseudo-curvature range.
    pub kappa_inf: Kappa,
    /// Upper end.
    pub kappa_sup: Kappa,
    /// Attractor points used (finite class); the range is an inner estimate from them.
    pub samples: usize,
    /// `[min β, max β]` over the samples on this side (finite class).
    pub beta_range: Option<[f64; 2]>,
    /// In the plane: the unit normal towards the centre of the osculating circles of positive
    /// β (the part of V2 orthogonal to V1), for drawing.
    #[serde(skip)]
    pub normal: Option<[f64; 2]>,
}

fn side_range(
    d: &DcfData,
    side: &str,
    through: String,
    betas: &[(f64, f64)],
    keep: impl Fn(f64) -> bool,
    proj: &[Vec<f64>],
) -> SideRange {
    let class = super::class_of(d);
    let mut bs: Vec<f64> = Vec::new();
    for &(x1, b) in betas {
        // λ1 < 0: the orbit visits both sides; λ2 < 0: β alternates its sign.
        if keep(x1) || d.lambda1_negative {
            bs.push(b);
            if d.lambda2_negative {
                bs.push(-b);
            }
        }
    }
    let range = bs.iter().fold(None, |acc: Option<[f64; 2]>, &b| {
        Some(acc.map_or([b, b], |[lo, hi]| [lo.min(b), hi.max(b)]))
    });
    let (kinf, ksup) = match d.order {
        Ordering::Greater => (f64::INFINITY, f64::INFINITY),
        // λ1 < 0 (THEORY §8): points of the curve on the line c + ℝ·v1 away from c come
        // arbitrarily near c, and their β is infinite.
        Ordering::Less if d.lambda1_negative => (0.0, f64::INFINITY),
        Ordering::Less => (0.0, 0.0),
        Ordering::Equal => {
            let s = 2.0 * d.shape(proj);
            match range {
                None => (f64::NAN, f64::NAN),
                Some([lo, hi]) => {
                    let min_abs = if lo <= 0.0 && hi >= 0.0 {
                        0.0
                    } else {
                        lo.abs().min(hi.abs())
                    };
                    let sup = if d.lambda1_negative {
                        f64::INFINITY
                    } else {
                        s * lo.abs().max(hi.abs())
                    };
                    (s * min_abs, sup)
                }
            }
        }
    };
    let (a, b) = d.projected(proj);
    let normal = (a.len() == 2).then(|| {
        let n2 = a[0] * a[0] + a[1] * a[1];
        let k = (b[0] * a[0] + b[1] * a[1]) / n2;
        let w = [b[0] - k * a[0], b[1] - k * a[1]];
        let l = w[0].hypot(w[1]);
        [w[0] / l, w[1] / l]
    });
    SideRange {
        normal: normal.filter(|n| n[0].is_finite() && n[1].is_finite()),
        side: side.to_string(),
        through,
        class: class.into(),
        kappa_inf: Kappa(kinf),
        kappa_sup: Kappa(ksup),
        samples: if d.order == Ordering::Equal {
            bs.len()
        } else {
            0
        },
        beta_range: if d.order == Ordering::Equal {
            range
        } else {
            None
        },
    }
}

/// A point of the curve with its left and right pseudo-curvature ranges.
#[derive(Clone, Debug, Serialize)]
pub struct DyadicPoint {
    /// The parameter t (I-adic, I the number of operators), exact.
    pub t: String,
    /// The point, barycentric, exact.
    pub point: Vec<String>,
    /// The point projected by the control points.
    pub position: Vec<f64>,
    /// The side t − 0 (none at t = 0).
    pub left: Option<SideRange>,
    /// The side t + 0 (none at t = 1).
    pub right: Option<SideRange>,
}

/// The DCFs and pseudo-curvatures of a curve `T_0 … T_{I−1}` with control points.
#[derive(Clone, Debug, Serialize)]
pub struct CurveCurvature {
    /// The DCF of each operator at its fixed point (or why there is none).
    pub dcfs: Vec<std::result::Result<Dcf, String>>,
    /// Ranges on both sides of each operator's fixed point, by the sign of x1.
    pub fixed_points: Vec<Vec<SideRange>>,
    /// Start, joints, end and the asked parameters.
    pub points: Vec<DyadicPoint>,
    /// Word length of the attractor samples.
    pub level: u32,
    /// The curve projected by the control points, in parameter order (for drawing).
    #[serde(skip)]
    pub polyline: Vec<Vec<f64>>,
    /// What the numbers are.
    pub note: String,
}

/// Parses an I-adic t in [0, 1] into its digits (`t = Σ σ_i·I^−(i+1)`). Error E0911.
fn digits(t: &BigRational, base: usize) -> Result<Vec<usize>> {
    let bad = || {
        op_error(
            "E0911",
            format!("--at {t}: not a parameter in [0, 1] with a power of {base} as denominator (at most 64 digits)"),
        )
    };
    if t.is_negative() || t > &q(1) {
        return Err(bad());
    }
    let mut x = t.clone();
    let mut out = Vec::new();
    let b = q(base as i64);
    while !x.is_zero() {
        if out.len() >= 64 {
            return Err(bad());
        }
        x *= &b;
        let d = x.floor();
        out.push(d.to_integer().to_usize().ok_or_else(bad)?);
        x -= d;
    }
    Ok(out)
}

/// Pseudo-curvatures of the curve `ops` (in order, the operators of one state onto itself) with
/// control points `points` (n rows of 2 or 3 coordinates): the DCF of every operator at its
/// fixed point, ranges on both sides of every fixed point, and left and right ranges at t = 0,
/// every joint k/I, t = 1 and each t of `at`. Errors: E0905 (control points), E0911 (a t that is
/// not I-adic in [0, 1]), E0912 (the pieces do not join: not a curve).
pub fn curve_curvature(
    names: &[String],
    ops: &[Matrix],
    points: &[Vec<f64>],
    at: &[BigRational],
    level: u32,
) -> Result<CurveCurvature> {
    let n = ops.first().map_or(0, |m| m.rows);
    if ops.len() < 2 {
        return Err(op_error("E0912", "a curve needs at least two operators"));
    }
    if points.len() != n || points.iter().any(|p| p.len() != points[0].len()) {
        return Err(op_error(
            "E0905",
            format!(
                "{} control points given for {n}-point operators",
                points.len()
            ),
        ));
    }
    let dim = points[0].len();
    if !(2..=3).contains(&dim) {
        return Err(op_error("E0905", "control points need 2 or 3 coordinates"));
    }
    let proj0: Vec<Vec<f64>> = (0..dim)
        .map(|r| points.iter().map(|p| p[r]).collect())
        .collect();
    let data: Vec<std::result::Result<DcfData, String>> = ops.iter().map(dcf_data).collect();
    let fixed: Vec<Option<Vec<BigRational>>> = data
        .iter()
        .map(|d| d.as_ref().ok().map(|d| d.c.clone()))
        .collect();
    let starts: Vec<(String, Vec<BigRational>)> = names
        .iter()
        .zip(&fixed)
        .filter_map(|(nm, f)| f.clone().map(|f| (format!("fix({nm})"), f)))
        .collect();
    let dcfs = data
        .iter()
        .zip(names)
        .map(|(d, nm)| match d {
            Ok(d) => Ok(d.report(
                nm,
                &starts
                    .iter()
                    .filter(|(from, _)| *from != format!("fix({nm})"))
                    .cloned()
                    .collect::<Vec<_>>(),
            )),
            Err(e) => Err(format!("{nm}: {e}")),
        })
        .collect();
    // Attractor samples: the fixed points under every word of length `level` (≤ 2^14 points).
    let mut level = level;
    while (ops.len() as u64).saturating_pow(level) * (starts.len() as u64) > 1 << 14 && level > 0 {
        level -= 1;
    }
    let fm: Vec<Vec<Vec<f64>>> = ops.iter().map(mat_f64).collect();
    let samples = images_f64(
        &fm,
        starts
            .iter()
            .map(|(_, p)| p.iter().map(|x| x.to_f64().unwrap_or(f64::NAN)).collect())
            .collect(),
        level,
    );
    let betas: Vec<Vec<(f64, f64)>> = data
        .iter()
        .map(|d| {
            d.as_ref()
                .map_or_else(|_| Vec::new(), |d| d.betas(&samples))
        })
        .collect();
    let fixed_points: Vec<Vec<SideRange>> = data
        .iter()
        .zip(names)
        .zip(&betas)
        .map(|((d, nm), b)| match d {
            Ok(d) => vec![
                side_range(
                    d,
                    "x1 > 0",
                    format!("{nm} at its fixed point"),
                    b,
                    |x| x > 0.0,
                    &proj0,
                ),
                side_range(
                    d,
                    "x1 < 0",
                    format!("{nm} at its fixed point"),
                    b,
                    |x| x < 0.0,
                    &proj0,
                ),
            ],
            Err(_) => Vec::new(),
        })
        .collect();
    let last = ops.len() - 1;
    let (Some(c0), Some(cl)) = (fixed[0].clone(), fixed[last].clone()) else {
        return Err(op_error(
            "E0912",
            "the first or last operator has no DCF (see its reason)",
        ));
    };
    for k in 0..last {
        if mat_vec(&ops[k], &cl) != mat_vec(&ops[k + 1], &c0) {
            return Err(op_error(
                "E0912",
                format!(
                    "{}·fix({}) ≠ {}·fix({}): the pieces do not join",
                    names[k],
                    names[last],
                    names[k + 1],
                    names[0]
                ),
            ));
        }
    }
    let base = ops.len();
    let mut ts: Vec<BigRational> = (0..=base)
        .map(|k| BigRational::new(k.into(), base.into()))
        .collect();
    for t in at {
        if !ts.contains(t) {
            ts.push(t.clone());
        }
    }
    let word = |ds: &[usize]| -> Matrix {
        ds.iter().fold(Matrix::identity(n), |acc, &d| {
            acc.mul(&ops[d]).expect("square")
        })
    };
    let project = |w: &Matrix| -> Vec<Vec<f64>> {
        let wf = mat_f64(w);
        proj0
            .iter()
            .map(|row| {
                (0..n)
                    .map(|j| (0..n).map(|i| row[i] * wf[i][j]).sum())
                    .collect()
            })
            .collect()
    };
    let wname = |ds: &[usize]| -> String {
        if ds.is_empty() {
            String::new()
        } else {
            ds.iter()
                .map(|&d| names[d].as_str())
                .collect::<Vec<_>>()
                .join("·")
                + " · "
        }
    };
    let mut out = Vec::new();
    for t in &ts {
        let ds = digits(t, base)?;
        let right = (t < &q(1)).then(|| ds.clone());
        let left = (t.is_positive()).then(|| {
            if t == &q(1) {
                Vec::new()
            } else {
                let mut l = ds.clone();
                *l.last_mut().expect("t > 0 has a digit") -= 1;
                l
            }
        });
        let point = match &right {
            Some(ds) => mat_vec(&word(ds), &c0),
            None => cl.clone(),
        };
        let sr = |ds: &Vec<usize>, op: usize, side: &str| -> Option<SideRange> {
            let d = data[op].as_ref().ok()?;
            Some(side_range(
                d,
                side,
                format!("{}(family of {} at its fixed point)", wname(ds), names[op]),
                &betas[op],
                |_| true,
                &project(&word(ds)),
            ))
        };
        out.push(DyadicPoint {
            t: t.to_string(),
            position: proj0
                .iter()
                .map(|row| {
                    row.iter()
                        .zip(&point)
                        .map(|(a, b)| a * b.to_f64().unwrap_or(f64::NAN))
                        .sum()
                })
                .collect(),
            point: point.iter().map(ToString::to_string).collect(),
            left: left.as_ref().and_then(|ds| sr(ds, last, "left")),
            right: right.as_ref().and_then(|ds| sr(ds, 0, "right")),
        });
    }
    // The curve in parameter order: words in lexicographic order applied to c0, then c_last.
    let mut line: Vec<Vec<f64>> = vec![c0.iter().map(|x| x.to_f64().unwrap_or(f64::NAN)).collect()];
    while line.len() * base <= 1 << 12 {
        line = fm
            .iter()
            .flat_map(|m| line.iter().map(move |p| mat_vec_f64(m, p)))
            .collect();
    }
    line.push(cl.iter().map(|x| x.to_f64().unwrap_or(f64::NAN)).collect());
    let polyline = line.iter().map(|p| mat_vec_f64(&proj0, p)).collect();
    let mut note = String::from("classes and DCF coefficients exact; κ ranges of the finite class from the β of exact attractor points evaluated in floating point (an inner estimate of [κinf, κsup])");
    if fixed_points
        .iter()
        .flatten()
        .any(|s| s.class == "oscillating")
    {
        note += "; κsup of the oscillating class (λ1 < 0) is +∞ by the argument of THEORY §8";
    }
    Ok(CurveCurvature {
        polyline,
        dcfs,
        fixed_points,
        points: out,
        level,
        note,
    })
}
