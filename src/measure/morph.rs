//! Metamorphosis (THEORY §13): frames along the segment between two parameter choices of one
//! structure, each checked.
//!
//! The solution space of the constraints is affine, so for exact parameter vectors p_A and p_B
//! every convex combination p_t = (1 − t)·p_A + t·p_B, t = k/(N − 1), is again an exact solution:
//! each frame is instantiated with p_t given by name (exact rationals, no fit). A frame is checked
//! twice: exactly, no two combinatorially distinct corner points of a level-1 complex coincide at
//! p_t ([`crate::constraint::collapses_at`]); and by measurement, the observed holes and
//! components of every level equal the exact counts ([`crate::measure::measure`]). A frame that
//! fails is reported with its index and reasons, never skipped.
//!
//! Two automata of one shape morph the same way, operator by operator: each frame's operators are
//! the exact convex combination of the two ends, checked exactly (every constraint holds, every
//! cycle of the control graph contracts); an automaton has no exact hole count to measure against.

use crate::algebra::KMatrix;
use crate::analysis::{check_contraction, constraints_failing, ResolveVerdict, Resolved};
use crate::constraint::collapses_at;
use crate::error::{Error, Result};
use crate::geometry::{
    instantiate_unchecked, Evaluator, GeometryError, Instance, InstantiateOptions,
};
use crate::input::{AutomatonModel, Input};
use crate::measure::measurement::{measure, MeasureOptions};
use num_rational::BigRational;
use num_traits::{One, Zero};
use serde::Serialize;

/// One frame of a morph.
#[derive(Clone, Debug, Serialize)]
pub struct MorphFrame {
    /// The frame's index, from 0.
    pub index: u32,
    /// Its position t on the segment, exact (`k/(N − 1)`).
    pub t: String,
    /// Whether every check passed.
    pub verified: bool,
    /// What failed (exact collapses first, then the measurement's failures).
    pub failures: Vec<String>,
    /// Observed holes at the deepest level (faces; `None` for automata, not measured).
    pub holes: Option<u64>,
    /// Observed components at the deepest level (faces; `None` for automata).
    pub components: Option<u64>,
}

/// A morph's report.
#[derive(Clone, Debug, Serialize)]
pub struct MorphReport {
    /// The structure's name.
    pub name: String,
    /// The level drawn and checked.
    pub level: u32,
    /// The free parameters (operators, for automata) that change between the two ends.
    pub changing: usize,
    /// The free parameters (operators, for automata) in all.
    pub parameters: usize,
    /// For automata whose two ends give control points: how many of the start state's control
    /// points move, and how many it has.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub moving_points: Option<(usize, usize)>,
    /// The frames.
    pub frames: Vec<MorphFrame>,
    /// Whether every frame passed.
    pub verified: bool,
    /// The first frame that failed.
    pub first_failure: Option<u32>,
}

/// The exact parameter vector of frame `k` of `n` between `a` and `b` (same names, same order).
pub fn frame_parameters(
    a: &[(String, BigRational)],
    b: &[(String, BigRational)],
    k: u32,
    n: u32,
) -> Vec<(String, BigRational)> {
    let t = BigRational::new(k.into(), (n - 1).max(1).into());
    let s = BigRational::one() - &t;
    a.iter()
        .zip(b)
        .map(|((name, x), (_, y))| (name.clone(), &s * x + &t * y))
        .collect()
}

/// Position k of n frames as exact text (`0`, `1/4`, `1`).
fn t_text(k: u32, n: u32) -> String {
    let t = BigRational::new(k.into(), (n - 1).max(1).into());
    if t.is_zero() {
        "0".into()
    } else {
        t.to_string()
    }
}

/// Why two automata are not of one shape, or `None` when they are: the same states (names and
/// dimensions), start, operators (names, kinds, source and target states), constraints and field.
pub fn shape_difference(a: &AutomatonModel, b: &AutomatonModel) -> Option<String> {
    let (x, y) = (&a.automaton, &b.automaton);
    if x.states != y.states {
        return Some("their states differ (names or numbers of control points)".into());
    }
    if a.start != b.start {
        return Some("their start states differ".into());
    }
    if x.operators.len() != y.operators.len()
        || x.operators
            .iter()
            .zip(&y.operators)
            .any(|(p, q)| (&p.name, p.kind, p.to, p.from) != (&q.name, q.kind, q.to, q.from))
    {
        return Some("their operators differ (names, kinds or states)".into());
    }
    if x.constraints.len() != y.constraints.len()
        || (0..x.constraints.len()).any(|i| x.constraint_text(i) != y.constraint_text(i))
    {
        return Some("their constraints differ".into());
    }
    if a.field_decl != b.field_decl {
        return Some("their number fields differ".into());
    }
    let count = |m: &AutomatonModel| m.points.as_ref().map(Vec::len);
    if count(a) != count(b) {
        return Some("their control points differ in number (or one has none)".into());
    }
    None
}

/// Morphs between two automata of one shape (`a`, `b` with their resolved operators): frame k
/// has every operator equal to (1 − t)·A + t·B entry by entry, exactly in the field (and the
/// start state's control points likewise, when the two give different ones), and is
/// checked exactly — every constraint holds and every cycle of the control graph contracts —
/// then handed to `draw` with its evaluator. Automata have no exact hole count, so frames are not
/// measured.
pub fn morph_automata(
    a: &AutomatonModel,
    ra: &Resolved,
    b: &AutomatonModel,
    rb: &Resolved,
    frames: u32,
    level: u32,
    mut draw: impl FnMut(u32, &Evaluator, &MorphFrame) -> Result<()>,
) -> Result<MorphReport> {
    if let Some(why) = shape_difference(a, b) {
        return Err(Error::Syntax(Box::new(crate::Diagnostic {
            code: "E1403",
            message: format!("morph: the two automata are not of one shape: {why}"),
            span: None,
            source: None,
        })));
    }
    let k = &a.field;
    let changing = ra.ops.iter().zip(&rb.ops).filter(|(x, y)| x != y).count();
    let moving_points = match (&a.points, &b.points) {
        (Some(pa), Some(pb)) => Some((pa.iter().zip(pb).filter(|(x, y)| x != y).count(), pa.len())),
        _ => None,
    };
    let mut out = Vec::new();
    for f in 0..frames {
        let t = BigRational::new(f.into(), (frames - 1).max(1).into());
        let s = BigRational::one() - &t;
        let ops: Vec<KMatrix> = ra
            .ops
            .iter()
            .zip(&rb.ops)
            .map(|(x, y)| KMatrix {
                rows: x.rows,
                cols: x.cols,
                data: x
                    .data
                    .iter()
                    .zip(&y.data)
                    .map(|(p, q)| k.add(&k.scale(p, &s), &k.scale(q, &t)))
                    .collect(),
            })
            .collect();
        let mut failures: Vec<String> = constraints_failing(a, &ops)?
            .into_iter()
            .map(|c| format!("constraint fails: {c}"))
            .collect();
        if let Err(e) = check_contraction(a, &ops) {
            failures.push(format!("{}: {e}", e.code()));
        }
        let resolved = Resolved {
            ops,
            verdict: ResolveVerdict {
                consistent: failures.is_empty(),
                ..ra.verdict.clone()
            },
        };
        // The control points move on their segments too (seed 002, eq. (21)): a projected IFS
        // whose projection changes, such as the octagonal gasket and the carpet drawn from one
        // product system (Fig. 8).
        let model = match (&a.points, &b.points) {
            (Some(pa), Some(pb)) if pa != pb => {
                let mut m = a.clone();
                m.points = Some(
                    pa.iter()
                        .zip(pb)
                        .map(|(p, q)| {
                            p.iter()
                                .zip(q)
                                .map(|(x, y)| k.add(&k.scale(x, &s), &k.scale(y, &t)))
                                .collect()
                        })
                        .collect(),
                );
                std::borrow::Cow::Owned(m)
            }
            _ => std::borrow::Cow::Borrowed(a),
        };
        let frame = MorphFrame {
            index: f,
            t: t_text(f, frames),
            verified: failures.is_empty(),
            failures,
            holes: None,
            components: None,
        };
        draw(f, &Evaluator::new(&model, &resolved), &frame)?;
        out.push(frame);
    }
    let first_failure = out.iter().find(|f| !f.verified).map(|f| f.index);
    Ok(MorphReport {
        name: "automaton".into(),
        level,
        changing,
        parameters: ra.ops.len(),
        moving_points,
        verified: first_failure.is_none(),
        first_failure,
        frames: out,
    })
}

/// Morphs `input` from the parameter choice `a` to `b` in `frames` frames (at least 2), checking
/// each; `draw(k, instance, frame)` is called for every frame after its checks.
pub fn morph(
    input: &Input,
    a: &InstantiateOptions,
    b: &InstantiateOptions,
    frames: u32,
    mopts: &MeasureOptions,
    mut draw: impl FnMut(u32, &Instance, &MorphFrame) -> std::result::Result<(), GeometryError>,
) -> std::result::Result<MorphReport, GeometryError> {
    // The end points and the frames are instantiated without the level-1 check: a frame whose
    // chosen point flattens a cell is a failure of that frame, reported with the others.
    let ia = instantiate_unchecked(input, a)?;
    let ib = instantiate_unchecked(input, b)?;
    let pa = ia.parameters.clone();
    let pb = ib.parameters.clone();
    debug_assert!(pa.iter().zip(&pb).all(|(x, y)| x.0 == y.0));
    let changing = pa.iter().zip(&pb).filter(|(x, y)| x.1 != y.1).count();
    let mut out = Vec::new();
    for k in 0..frames {
        let mut opts = a.clone();
        opts.template = None;
        opts.goals.clear();
        opts.values = frame_parameters(&pa, &pb, k, frames);
        let mut inst = instantiate_unchecked(input, &opts)?;
        let level_one = inst.level_one(&opts);
        let mut failures: Vec<String> = collapses_at(
            &inst.types,
            &inst.generated,
            &inst.linearized.offsets,
            &inst.values,
        )
        .into_iter()
        .map(|c| format!("collapse: {c}"))
        .collect();
        match level_one {
            Ok(l) => inst.level_one = l,
            Err(e) => failures.push(format!("{}: {e}", e.code())),
        }
        let (holes, components) = match measure(&inst, mopts) {
            Ok(r) => {
                failures.extend(r.failures);
                (Some(r.holes as u64), Some(r.components as u64))
            }
            Err(e) => {
                failures.push(format!("{}: {e}", e.code()));
                (None, None)
            }
        };
        let frame = MorphFrame {
            index: k,
            t: t_text(k, frames),
            verified: failures.is_empty(),
            failures,
            holes,
            components,
        };
        draw(k, &inst, &frame)?;
        out.push(frame);
    }
    let first_failure = out.iter().find(|f| !f.verified).map(|f| f.index);
    Ok(MorphReport {
        name: input.name.clone(),
        level: mopts.level,
        changing,
        parameters: pa.len(),
        moving_points: None,
        verified: first_failure.is_none(),
        first_failure,
        frames: out,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(n: i64, d: i64) -> BigRational {
        BigRational::new(n.into(), d.into())
    }

    #[test]
    fn frames_are_exact_convex_combinations() {
        // Between (x: 0, y: 1) and (x: 1, y: −1) in 5 frames: t = 0, 1/4, 1/2, 3/4, 1, so
        // x = t and y = 1 − 2t: frame 1 is (1/4, 1/2), frame 2 (1/2, 0), frame 4 (1, −1).
        let a = vec![("x".to_string(), q(0, 1)), ("y".to_string(), q(1, 1))];
        let b = vec![("x".to_string(), q(1, 1)), ("y".to_string(), q(-1, 1))];
        let f1 = frame_parameters(&a, &b, 1, 5);
        assert_eq!((f1[0].1.clone(), f1[1].1.clone()), (q(1, 4), q(1, 2)));
        let f2 = frame_parameters(&a, &b, 2, 5);
        assert_eq!((f2[0].1.clone(), f2[1].1.clone()), (q(1, 2), q(0, 1)));
        assert_eq!(frame_parameters(&a, &b, 0, 5), a);
        assert_eq!(frame_parameters(&a, &b, 4, 5), b);
    }
}
