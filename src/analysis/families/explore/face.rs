//! One face of the family explored: the requested properties checked in order (and what they
//! need first), each failure shrunk greedily to a minimal counterexample with its witness.

use super::{BoundaryResult, Checks, ExploreSpec, Failure, Outcome, Property, Shrunk, Witness};
use crate::analysis::ratio::analyse;
use crate::constraint::{solve_closure, GenOptions};
use crate::topology::closure::{Bound, Closure};
use crate::topology::edge::{EdgeKind, EdgeType};
use crate::topology::face::{Face, Params};
use crate::topology::limits::Limits;
use num_rational::BigRational;
use std::collections::BTreeMap;

/// The evaluation of one face.
struct Evaluation {
    refused: Option<(&'static str, String)>,
    types: Option<usize>,
    ratio: Option<String>,
    outcomes: Vec<(Property, Outcome)>,
}

/// Checks `props` on one face (and what they need first).
fn evaluate(face: &Face, props: &[Property], limits: &Limits, checks: &Checks) -> Evaluation {
    let mut ev = Evaluation {
        refused: None,
        types: None,
        ratio: None,
        outcomes: Vec::new(),
    };
    let skip_all = |ev: &mut Evaluation, why: &str| {
        for &p in props {
            if !ev.outcomes.iter().any(|(q, _)| *q == p) {
                ev.outcomes.push((p, Outcome::Skip(why.into())));
            }
        }
    };
    if let Err(e) = limits.check_face(face) {
        ev.refused = Some((e.code(), e.to_string()));
        return ev;
    }
    let ts = match Closure::of(std::slice::from_ref(face), limits) {
        Err(e) => {
            ev.refused = Some((e.code(), e.to_string()));
            return ev;
        }
        Ok(Closure::Runaway(r)) => {
            if let Some(bound) = Bound::stated(std::slice::from_ref(face)) {
                // A built-in closes; the limit was reached first.
                ev.refused = Some((
                    "E0501",
                    format!(
                        "closes (boundary length ≤ {} proved) but {}",
                        bound.max_length, r.reason
                    ),
                ));
                return ev;
            }
            let mut detail = vec![r.reason.clone()];
            detail.extend(r.witness.iter().cloned());
            if props.contains(&Property::Closes) {
                ev.outcomes.push((
                    Property::Closes,
                    Outcome::Fail(Witness {
                        kind: "runaway chain".into(),
                        detail,
                    }),
                ));
            }
            skip_all(&mut ev, "the closure did not close");
            return ev;
        }
        Ok(Closure::Closed(ts)) => ts,
    };
    ev.types = Some(ts.types.len());
    if props.contains(&Property::Closes) {
        let outcome = match &ts.bound {
            Some(b) => {
                let long = ts
                    .types
                    .iter()
                    .find(|t| num_bigint::BigUint::from(t.face.boundary.len()) > b.max_length);
                if let Some(t) = long {
                    Outcome::Fail(Witness {
                        kind: "outside the stated bound".into(),
                        detail: vec![format!(
                            "{} has {} edges, above the stated bound {}",
                            t.face,
                            t.face.boundary.len(),
                            b.max_length
                        )],
                    })
                } else if num_bigint::BigUint::from(ts.types.len()) > b.max_types {
                    Outcome::Fail(Witness {
                        kind: "outside the stated bound".into(),
                        detail: vec![format!(
                            "{} types, above the stated bound {}",
                            ts.types.len(),
                            b.max_types
                        )],
                    })
                } else {
                    Outcome::Pass
                }
            }
            None => Outcome::Pass,
        };
        ev.outcomes.push((Property::Closes, outcome));
    }
    if props.contains(&Property::Consistent) || props.contains(&Property::NoCollapse) {
        match solve_closure(&ts, GenOptions::default(), limits) {
            Err(e) => {
                for p in [Property::Consistent, Property::NoCollapse] {
                    if props.contains(&p) {
                        ev.outcomes
                            .push((p, Outcome::Skip(format!("{}: {e}", e.code()))));
                    }
                }
            }
            Ok(report) => {
                if props.contains(&Property::Consistent) {
                    let outcome = if report.consistent {
                        Outcome::Pass
                    } else {
                        let mut detail = vec![format!(
                            "these constraints with these multipliers sum to 0 = {}",
                            report.conflict_constant.clone().unwrap_or_default()
                        )];
                        detail.extend(
                            report
                                .conflict
                                .iter()
                                .flatten()
                                .map(|c| format!("× {}  {}", c.multiplier, c.constraint)),
                        );
                        Outcome::Fail(Witness {
                            kind: "conflict".into(),
                            detail,
                        })
                    };
                    ev.outcomes.push((Property::Consistent, outcome));
                }
                if props.contains(&Property::NoCollapse) {
                    let outcome = if !report.consistent {
                        Outcome::Skip("the constraint system is inconsistent".into())
                    } else if report.degenerate.is_empty() {
                        Outcome::Pass
                    } else {
                        Outcome::Fail(Witness {
                            kind: "collapsing pair".into(),
                            detail: vec![
                                report.degenerate[0].clone(),
                                format!(
                                    "{} in all",
                                    crate::error::counted(
                                        report.degenerate.len(),
                                        "forced collapse",
                                        "forced collapses"
                                    )
                                ),
                            ],
                        })
                    };
                    ev.outcomes.push((Property::NoCollapse, outcome));
                }
            }
        }
    }
    if props.contains(&Property::Ratio) {
        let c: Vec<BigRational> = ts
            .types
            .iter()
            .map(|t| BigRational::new(t.contribution_halves().into(), 2.into()))
            .collect();
        let outcome = match analyse(&ts.matrix(), &c, &[(ts.start[0], 1)]) {
            Err(e) => Outcome::Skip(e.to_string()),
            Ok(r) if r.exists => {
                ev.ratio = r.exact.clone();
                Outcome::Pass
            }
            Ok(r) => {
                let mut detail = vec![format!(
                    "R_i does not converge: period {} of the dominant classes",
                    r.period
                )];
                detail.extend(
                    r.limit_points
                        .iter()
                        .map(|p| format!("lim R_({}n+{}) = {}", r.period, p.residue, p.exact)),
                );
                Outcome::Fail(Witness {
                    kind: "limit points".into(),
                    detail,
                })
            }
        };
        ev.outcomes.push((Property::Ratio, outcome));
    }
    for (p, check) in [
        (Property::Certificate, checks.certificate),
        (Property::Holes, checks.holes),
    ] {
        if props.contains(&p) {
            let outcome = match check {
                None => Outcome::Skip(format!("no {} check supplied", p.name())),
                Some(check) => check(face, &ts),
            };
            ev.outcomes.push((p, outcome));
        }
    }
    ev
}

/// The faces one shrinking step away, simplest changes first: remove an edge; lower an edge's n
/// or delay or make it a `Bn`; the same on Ea, El, Ec; lower the face delay. Every candidate is
/// smaller in (length, Σn, Σdelay, number of `Cn`), so shrinking ends.
fn candidates(f: &Face) -> Vec<Face> {
    let mut out: Vec<Face> = Vec::new();
    let mut push = |g: Face| {
        let g = g.canonical().0;
        if g != *f && !out.contains(&g) {
            out.push(g);
        }
    };
    let simpler = |e: &EdgeType| -> Vec<EdgeType> {
        let mut v = Vec::new();
        if e.n > 2 {
            v.push(EdgeType { n: e.n - 1, ..*e });
        }
        if e.delay > 1 {
            v.push(EdgeType {
                delay: e.delay - 1,
                ..*e
            });
        }
        if e.kind == EdgeKind::C {
            v.push(EdgeType {
                kind: EdgeKind::B,
                ..*e
            });
        }
        v
    };
    if f.boundary.len() > 1 {
        for i in 0..f.boundary.len() {
            let mut g = f.clone();
            g.boundary.remove(i);
            push(g);
        }
    }
    for i in 0..f.boundary.len() {
        for e in simpler(&f.boundary[i]) {
            let mut g = f.clone();
            g.boundary[i] = e;
            push(g);
        }
    }
    for k in 0..3 {
        let get = |p: &Params| [p.ea, p.el, p.ec][k];
        for e in simpler(&get(&f.params)) {
            let mut g = f.clone();
            match k {
                0 => g.params.ea = e,
                1 => g.params.el = e,
                _ => g.params.ec = e,
            }
            push(g);
        }
    }
    if f.delay > 1 {
        push(Face {
            delay: f.delay - 1,
            ..f.clone()
        });
    }
    out
}

/// The witness of `p` on `f` when it fails `p`.
fn fails(f: &Face, p: Property, limits: &Limits, checks: &Checks) -> Option<Witness> {
    let ev = evaluate(f, &[p], limits, checks);
    ev.outcomes.into_iter().find_map(|(q, o)| match o {
        Outcome::Fail(w) if q == p => Some(w),
        _ => None,
    })
}

/// Shrinks a failure of `p` on `f` (witness `w`) greedily within `budget` evaluations.
fn shrink(
    f: &Face,
    w: Witness,
    p: Property,
    limits: &Limits,
    budget: usize,
    checks: &Checks,
) -> Shrunk {
    let (mut cur, mut witness, mut steps, mut spent) = (f.clone(), w, 0usize, 0usize);
    'outer: loop {
        for g in candidates(&cur) {
            if spent >= budget {
                return Shrunk {
                    face: cur.to_string(),
                    witness,
                    steps,
                    minimal: false,
                };
            }
            spent += 1;
            if let Some(w) = fails(&g, p, limits, checks) {
                cur = g;
                witness = w;
                steps += 1;
                continue 'outer;
            }
        }
        return Shrunk {
            face: cur.to_string(),
            witness,
            steps,
            minimal: true,
        };
    }
}

/// Explores one face (index `index` of the family).
pub fn explore_face(
    index: u64,
    face: &Face,
    spec: &ExploreSpec,
    limits: &Limits,
    checks: &Checks,
) -> BoundaryResult {
    let ev = evaluate(face, &spec.properties, limits, checks);
    let mut r = BoundaryResult {
        index,
        face: face.to_string(),
        status: "pass",
        code: None,
        types: ev.types,
        ratio: ev.ratio,
        properties: BTreeMap::new(),
        failures: Vec::new(),
    };
    if let Some((code, msg)) = ev.refused {
        r.status = if code == "E0501" { "limit" } else { "refused" };
        r.code = Some(code);
        for p in &spec.properties {
            r.properties.insert(p.name(), format!("skip: {msg}"));
        }
        return r;
    }
    for (p, o) in ev.outcomes {
        let text = match &o {
            Outcome::Pass => "pass".to_string(),
            Outcome::Fail(_) => "fail".to_string(),
            Outcome::Skip(why) => format!("skip: {why}"),
        };
        r.properties.insert(p.name(), text);
        if let Outcome::Fail(w) = o {
            let shrunk = shrink(face, w.clone(), p, limits, spec.shrink_budget, checks);
            r.failures.push(Failure {
                property: p,
                witness: w,
                shrunk,
            });
        }
    }
    if !r.failures.is_empty() {
        r.status = "fail";
    }
    r
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shrink_candidates_are_smaller() {
        let f = Face::parse("C3^2 B2 | C2 B2 B2 | {gap}").unwrap();
        let size = |g: &Face| {
            let p = g.params;
            let all: Vec<&EdgeType> = g.boundary.iter().chain([&p.ea, &p.el, &p.ec]).collect();
            (
                g.boundary.len(),
                all.iter().map(|e| e.n).sum::<u32>()
                    + all.iter().map(|e| e.delay).sum::<u32>()
                    + all.iter().filter(|e| e.kind == EdgeKind::C).count() as u32
                    + g.delay,
            )
        };
        for g in candidates(&f) {
            assert!(size(&g) < size(&f), "{g} is not smaller than {f}");
        }
    }
}
