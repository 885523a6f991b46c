//! Operators of an automaton read as curves (THEORY §8, dyadic points): every known
//! self-mapping sub-operator analysed by [`crate::analysis::operators::operator`], the end points
//! and joining points of each curve with their one-sided behaviour, and a float estimate of the
//! curvature range in the finite class (geometry: never a verdict).

use crate::algebra::algebraic::{FieldElement, NumberField};
use crate::algebra::fieldpoly::{apply, null_space, rationals};
use crate::algebra::kmatrix::KMatrix;
use crate::algebra::matrix::Matrix;
use crate::analysis::operators::operator::{
    analyse_kmatrix, analyse_matrix, images_f64, mat_f64, mat_vec, op_error, render_vec, Behaviour,
    CurvatureClass, OperatorReport, TangentData,
};
use crate::constraint::automaton::{Automaton, OpKind, Operator};
use crate::error::Result;
use num_rational::BigRational;
use num_traits::{ToPrimitive, Zero};
use serde::Serialize;
use std::cmp::Ordering;

/// One side (left or right) of a point of a curve.
#[derive(Clone, Debug, Serialize)]
pub struct Side {
    /// How the side is seen: `T1 at its fixed point`, `T0 · (T1 at its fixed point)`.
    pub through: String,
    /// The behaviour label of the operator seen (`finite`, `sharp`, …, see [`Behaviour::label`]).
    pub behaviour: String,
    /// Its curvature class in the tangent case (an affine image keeps the class).
    pub class: Option<CurvatureClass>,
    /// The tangent direction on this side (the image of v1), exact.
    pub tangent: Option<Vec<String>>,
}

/// The behaviour at an end point or joining point of a curve.
#[derive(Clone, Debug, Serialize)]
pub struct PointBehaviour {
    /// `start`, `end`, or `joint T0|T1`.
    pub label: String,
    /// The point in barycentric coordinates of the state's control points, exact.
    pub point: Vec<String>,
    /// The side before the point (none at the start).
    pub left: Option<Side>,
    /// The side after the point (none at the end).
    pub right: Option<Side>,
    /// At a joint: whether the two one-sided tangents are parallel (G1 up to orientation);
    /// `None` when not decided (tangents in different fields) or when a side has no tangent.
    pub tangent_continuous: Option<bool>,
}

/// A state read as a curve: its sub-operators `T_0 … T_{n−1}` (in file order) mapping the state
/// to itself, all known.
#[derive(Clone, Debug, Serialize)]
pub struct CurveReport {
    /// The state.
    pub state: String,
    /// The operators, in order.
    pub operators: Vec<String>,
    /// True when consecutive pieces join: `T_k · end = T_{k+1} · start` for every k, with
    /// start = fix(T_0) and end = fix(T_{n−1}); the points are reported only then.
    pub joined: bool,
    /// Why the state is not read as a curve, when it is not.
    pub note: Option<String>,
    /// Start, joints, end.
    pub points: Vec<PointBehaviour>,
}

/// The analysis of every known square subdivision operator of an automaton.
#[derive(Clone, Debug, Serialize)]
pub struct AutomatonOperators {
    /// One report per known `sub` operator mapping a state to itself.
    pub operators: Vec<OperatorReport>,
    /// Sub-operators not analysed, with the reason (unknown: solve first; between two states).
    pub skipped: Vec<String>,
    /// States with at least two self-mapping sub-operators, read as curves.
    pub curves: Vec<CurveReport>,
}

/// Analyses every known `sub` operator that maps a state to itself, and the end and joining
/// points of every state with at least two such operators (THEORY §8, dyadic points).
pub fn analyse_automaton(a: &Automaton) -> Result<AutomatonOperators> {
    analyse_automaton_only(a, None, None)
}

/// The values over a number field of an automaton's operators whose entries lie outside Q
/// (`None` for the others), with the field.
pub type FieldValues<'a> = (&'a NumberField, &'a [Option<KMatrix>]);

/// [`analyse_automaton`] restricted to the operator named `only` (no curves are read then), and
/// with the operators valued in a number field analysed too (`field`: their values; see
/// [`analyse_kmatrix`] for what is decided). Error E0910 when there is no such sub-operator.
pub fn analyse_automaton_only(
    a: &Automaton,
    only: Option<&str>,
    field: Option<FieldValues<'_>>,
) -> Result<AutomatonOperators> {
    if let Some(name) = only {
        if !a
            .operators
            .iter()
            .any(|o| o.kind == OpKind::Sub && o.name == name)
        {
            return Err(op_error(
                "E0910",
                format!("no subdivision operator `{name}` in the automaton"),
            ));
        }
    }
    let mut operators = Vec::new();
    let mut skipped = Vec::new();
    for (o, op) in a
        .operators
        .iter()
        .enumerate()
        .filter(|(_, o)| o.kind == OpKind::Sub && only.is_none_or(|n| o.name == n))
    {
        let in_field = field.and_then(|(k, v)| v.get(o).cloned().flatten().map(|m| (k, m)));
        match (&op.value, op.to == op.from) {
            (_, false) => skipped.push(format!(
                "{}: maps {} to {} (not an iterated map of one state)",
                op.name, a.states[op.from].name, a.states[op.to].name
            )),
            (None, true) => match in_field {
                Some((k, m)) => match analyse_kmatrix(k, &m)? {
                    Ok(mut r) => {
                        r.name = Some(op.name.clone());
                        operators.push(r);
                    }
                    Err(why) => skipped.push(format!("{}: {why}", op.name)),
                },
                None => skipped.push(format!(
                    "{}: no value (unknown until the automaton is solved)",
                    op.name
                )),
            },
            (Some(m), true) => {
                let mut r = analyse_matrix(m)?;
                r.name = Some(op.name.clone());
                operators.push(r);
            }
        }
    }
    let mut curves = Vec::new();
    for (s, state) in a.states.iter().enumerate().filter(|_| only.is_none()) {
        let ops: Vec<&Operator> = a
            .operators
            .iter()
            .filter(|o| o.kind == OpKind::Sub && o.to == s && o.from == s)
            .collect();
        if ops.len() < 2 || state.dim < 2 {
            continue;
        }
        let names: Vec<String> = ops.iter().map(|o| o.name.clone()).collect();
        let reports: Vec<&OperatorReport> = names
            .iter()
            .filter_map(|n| operators.iter().find(|r| r.name.as_ref() == Some(n)))
            .collect();
        let mut curve = CurveReport {
            state: state.name.clone(),
            operators: names.clone(),
            joined: false,
            note: None,
            points: Vec::new(),
        };
        if reports.len() != ops.len() {
            curve.note = Some("some operators are unknown".into());
        } else if ops.iter().any(|o| o.value.is_none()) {
            curve.note = Some(
                "some operators have entries outside Q: the joints and end points are read over Q only"
                    .into(),
            );
        } else {
            let mats: Vec<&Matrix> = ops.iter().filter_map(|o| o.value.as_ref()).collect();
            match curve_points(&names, &mats, &reports) {
                Ok(points) => {
                    curve.joined = true;
                    curve.points = points;
                }
                Err(note) => curve.note = Some(note),
            }
        }
        curves.push(curve);
    }
    Ok(AutomatonOperators {
        operators,
        skipped,
        curves,
    })
}

/// The side seen through `map` (identity when `None`) of the operator `r` at its fixed point.
fn side(through: String, r: &OperatorReport, map: Option<&Matrix>) -> Side {
    let tangent = r.exact.as_ref().map(|d| match map {
        Some(m) => render_vec(&d.field, &apply(&d.field, m, &d.v1)),
        None => render_vec(&d.field, &d.v1),
    });
    Side {
        through,
        behaviour: r.behaviour.label().to_string(),
        class: r.behaviour.class(),
        tangent,
    }
}

/// Whether `m·a.v1` and `n·b.v1` are parallel, when both live in one field.
fn parallel(a: &TangentData, m: &Matrix, b: &TangentData, n: &Matrix) -> Option<bool> {
    let same = a.field.degree() == 1 && b.field.degree() == 1
        || a.lambda1.min_poly() == b.lambda1.min_poly()
            && a.lambda1.cmp_exact(&b.lambda1) == Ordering::Equal;
    if !same {
        return None;
    }
    let k = if a.field.degree() == 1 {
        rationals()
    } else {
        a.field.clone()
    };
    // Rational fields: re-embed the coordinates as rationals of Q.
    let lift = |d: &TangentData, v: Vec<FieldElement>| -> Vec<FieldElement> {
        if d.field.degree() == 1 {
            v.iter()
                .map(|x| k.rational(x.as_rational().expect("rational")))
                .collect()
        } else {
            v
        }
    };
    let u = lift(a, apply(&a.field, m, &a.v1));
    let w = lift(b, apply(&b.field, n, &b.v1));
    Some(
        (0..u.len()).all(|i| {
            (0..u.len()).all(|j| k.sub(&k.mul(&u[i], &w[j]), &k.mul(&u[j], &w[i])).is_zero())
        }),
    )
}

/// Start, joints and end of the curve `T_0 … T_{n−1}`: the joint of T_k and T_{k+1} is
/// `T_k·fix(T_{n−1}) = T_{k+1}·fix(T_0)`; its left side is T_{n−1} at its fixed point mapped by
/// T_k, its right side T_0 at its fixed point mapped by T_{k+1}.
fn curve_points(
    names: &[String],
    mats: &[&Matrix],
    reports: &[&OperatorReport],
) -> std::result::Result<Vec<PointBehaviour>, String> {
    let n = mats.len();
    let (first, last) = (reports[0], reports[n - 1]);
    let start = first
        .fixed
        .clone()
        .ok_or_else(|| format!("{} has no unique fixed point", names[0]))?;
    let end = last
        .fixed
        .clone()
        .ok_or_else(|| format!("{} has no unique fixed point", names[n - 1]))?;
    let strs = |v: &[BigRational]| v.iter().map(ToString::to_string).collect::<Vec<_>>();
    let mut points = vec![PointBehaviour {
        label: "start".into(),
        point: strs(&start),
        left: None,
        right: Some(side(
            format!("{} at its fixed point", names[0]),
            first,
            None,
        )),
        tangent_continuous: None,
    }];
    for k in 0..n - 1 {
        let p = mat_vec(mats[k], &end);
        let p2 = mat_vec(mats[k + 1], &start);
        if p != p2 {
            return Err(format!(
                "{}·fix({}) ≠ {}·fix({}): the pieces do not join in this order",
                names[k],
                names[n - 1],
                names[k + 1],
                names[0]
            ));
        }
        let tangent_continuous = match (&last.exact, &first.exact) {
            (Some(a), Some(b)) => parallel(a, mats[k], b, mats[k + 1]),
            _ => None,
        };
        points.push(PointBehaviour {
            label: format!("joint {}|{}", names[k], names[k + 1]),
            point: strs(&p),
            left: Some(side(
                format!("{} · ({} at its fixed point)", names[k], names[n - 1]),
                last,
                Some(mats[k]),
            )),
            right: Some(side(
                format!("{} · ({} at its fixed point)", names[k + 1], names[0]),
                first,
                Some(mats[k + 1]),
            )),
            tangent_continuous,
        });
    }
    points.push(PointBehaviour {
        label: "end".into(),
        point: strs(&end),
        left: Some(side(
            format!("{} at its fixed point", names[n - 1]),
            last,
            None,
        )),
        right: None,
        tangent_continuous: None,
    });
    Ok(points)
}

/// A float estimate of the curvatures at the fixed point of an operator of the finite class.
#[derive(Clone, Debug, Serialize)]
pub struct CurvatureEstimate {
    /// Index of the operator in the list given.
    pub operator: usize,
    /// Word length of the samples.
    pub level: u32,
    /// Number of attractor points used.
    pub samples: usize,
    /// `[min, max]` of the signed curvature on the side where the v1-coordinate is positive.
    pub positive_side: Option<[f64; 2]>,
    /// The same on the side where it is negative.
    pub negative_side: Option<[f64; 2]>,
    /// What was computed (always labelled an estimate).
    pub note: String,
}

fn f64s(v: &[BigRational]) -> Vec<f64> {
    v.iter().map(|x| x.to_f64().unwrap_or(f64::NAN)).collect()
}

/// Estimates the range of curvatures at the fixed point of `ops[index]` when its class is finite
/// (α = 2) with a real λ2 = ±λ1²: near the fixed point c, an attractor point p is
/// `c + a1·v1 + a2·v2 + …` (a_i from the left eigenvectors), its images under T^j follow
/// `c + t·v1 + β·t²·v2` with `β = a2/a1²` (invariant, since λ2 = ±λ1²), and the curvature of that
/// parabola projected by the control points `points` is `2β·(V1 × V2)/|V1|³`. The points p are the
/// images of the operators' fixed points under every word of length `level` (at most 2^16
/// samples). Floats throughout: an estimate, never a verdict. Errors: E0903 when the operator is
/// not in the finite class with a real λ2, E0905 for a wrong number of points or too many samples.
pub fn estimate_curvature(
    ops: &[Matrix],
    index: usize,
    points: &[[f64; 2]],
    level: u32,
) -> Result<CurvatureEstimate> {
    let t = ops
        .get(index)
        .ok_or_else(|| op_error("E0905", format!("no operator {index}")))?;
    let r = analyse_matrix(t)?;
    let data = match (&r.behaviour, &r.exact) {
        (
            Behaviour::Tangent {
                class: CurvatureClass::Finite,
                ..
            },
            Some(d),
        ) if d.second.is_some() => d,
        _ => {
            return Err(op_error(
                "E0903",
                format!(
                    "the curvature range is estimated only for the finite class with λ2 = ±λ1² real; this operator is {}",
                    r.behaviour.label()
                ),
            ))
        }
    };
    let n = t.rows;
    if points.len() != n {
        return Err(op_error(
            "E0905",
            format!(
                "{} control points given for a {n}-point operator",
                points.len()
            ),
        ));
    }
    let count = (ops.len() as u64).checked_pow(level).unwrap_or(u64::MAX);
    if count > 1 << 16 {
        return Err(op_error(
            "E0905",
            format!("{count} words of length {level}: more than 65536 samples"),
        ));
    }
    let k = &data.field;
    let (l2, v2) = data.second.as_ref().expect("checked");
    // Left eigenvectors u_i (null space of Tᵀ − λ_i I), scaled so that u_i · v_i = 1.
    let left = |lam: &FieldElement, v: &[FieldElement]| -> Vec<f64> {
        let tt = Matrix::from_rows(
            (0..n)
                .map(|j| (0..n).map(|i| t.get(i, j).clone()).collect())
                .collect(),
        );
        let u = null_space(k, crate::algebra::fieldpoly::shifted(k, &tt, lam)).remove(0);
        let dot = u
            .iter()
            .zip(v)
            .fold(k.rational(BigRational::zero()), |acc, (a, b)| {
                k.add(&acc, &k.mul(a, b))
            });
        let inv = k.inv(&dot).expect("simple eigenvalue: u·v ≠ 0");
        u.iter()
            .map(|x| crate::analysis::operators::operator::f64_of(k, &k.mul(x, &inv)))
            .collect()
    };
    let u1 = left(&k.generator_element(), &data.v1);
    let u2 = left(l2, v2);
    let proj = |v: &[FieldElement]| -> [f64; 2] {
        let w: Vec<f64> = v
            .iter()
            .map(|x| crate::analysis::operators::operator::f64_of(k, x))
            .collect();
        let mut s = [0.0, 0.0];
        for (wi, p) in w.iter().zip(points) {
            s[0] += wi * p[0];
            s[1] += wi * p[1];
        }
        s
    };
    let (big_v1, big_v2) = (proj(&data.v1), proj(v2));
    let cross = big_v1[0] * big_v2[1] - big_v1[1] * big_v2[0];
    let norm3 = (big_v1[0] * big_v1[0] + big_v1[1] * big_v1[1]).powf(1.5);
    let c = f64s(
        r.fixed
            .as_ref()
            .expect("contractive tangent case has a fixed point"),
    );
    let seeds: Vec<Vec<f64>> = ops
        .iter()
        .filter_map(|m| {
            analyse_matrix(m)
                .ok()
                .and_then(|r| r.fixed)
                .map(|f| f64s(&f))
        })
        .collect();
    let fm: Vec<Vec<Vec<f64>>> = ops.iter().map(mat_f64).collect();
    let pts = images_f64(&fm, seeds, level);
    let mut pos: Option<[f64; 2]> = None;
    let mut neg: Option<[f64; 2]> = None;
    let mut used = 0;
    for p in &pts {
        let d: Vec<f64> = p.iter().zip(&c).map(|(a, b)| a - b).collect();
        let a1: f64 = u1.iter().zip(&d).map(|(a, b)| a * b).sum();
        let a2: f64 = u2.iter().zip(&d).map(|(a, b)| a * b).sum();
        if a1.abs() < 1e-9 {
            continue;
        }
        used += 1;
        let kappa = 2.0 * a2 / (a1 * a1) * cross / norm3;
        let slot = if a1 > 0.0 { &mut pos } else { &mut neg };
        *slot = Some(match *slot {
            None => [kappa, kappa],
            Some([lo, hi]) => [lo.min(kappa), hi.max(kappa)],
        });
    }
    Ok(CurvatureEstimate {
        operator: index,
        level,
        samples: used,
        positive_side: pos,
        negative_side: neg,
        note: "estimate (floating point): curvature of c + t·v1 + β·t²·v2 over sampled attractor points; not a verdict".into(),
    })
}

impl CurvatureEstimate {
    /// A human-readable rendering.
    pub fn to_text(&self) -> String {
        let side = |s: &Option<[f64; 2]>| {
            s.map_or("no sample".to_string(), |[a, b]| {
                format!("[{a:.6}, {b:.6}]")
            })
        };
        format!(
            "curvature estimate at the fixed point of operator {} (level {}, {} samples)\n  side v1 > 0: {}\n  side v1 < 0: {}\n  {}\n",
            self.operator,
            self.level,
            self.samples,
            side(&self.positive_side),
            side(&self.negative_side),
            self.note
        )
    }
}

impl AutomatonOperators {
    /// The full rendering: every operator with its exact forms, then every curve's points.
    pub fn to_text(&self) -> String {
        self.render(true)
    }

    /// The summary: a few lines per operator (see [`OperatorReport::summary`]), then every
    /// curve's points with exact forms only when short.
    pub fn summary(&self) -> String {
        self.render(false)
    }

    fn render(&self, exact: bool) -> String {
        let cut = |v: &[String]| -> String {
            let s = v.join(", ");
            if exact || s.chars().count() <= 120 {
                s
            } else {
                format!("{} coordinates; exact form in --exact", v.len())
            }
        };
        let mut out = String::new();
        for r in &self.operators {
            out += &if exact { r.to_text() } else { r.summary() };
            out += "\n";
        }
        for s in &self.skipped {
            out += &format!("not analysed: {s}\n");
        }
        for c in &self.curves {
            out += &format!("curve {} ({}):\n", c.state, c.operators.join(", "));
            if let Some(n) = &c.note {
                out += &format!("  not read as a curve: {n}\n");
            }
            for p in &c.points {
                out += &format!("  {} at ({})\n", p.label, cut(&p.point));
                for (name, s) in [("left", &p.left), ("right", &p.right)] {
                    if let Some(s) = s {
                        out += &format!("    {name}: {} via {}", s.behaviour, s.through);
                        if let Some(t) = &s.tangent {
                            out += &format!(", tangent ({})", cut(t));
                        }
                        out += "\n";
                    }
                }
                if let Some(g) = p.tangent_continuous {
                    out += &format!(
                        "    tangents {}\n",
                        if g {
                            "parallel (G1)"
                        } else {
                            "not parallel (corner)"
                        }
                    );
                }
            }
        }
        out
    }
}
