//! The certificate of a measured instance: the certificate of its faces (closure, solution space,
//! degeneracy, limit ratio, face topology) and a `level-one` step that proves the exact level-1
//! line `measure` prints — every level-1 control polygon has positive area at the chosen point,
//! in each type's frame.
//!
//! It lives here, not in `certificate/produce/`, because the chosen point and its frames are
//! geometry's (a layer of the same rank as `certificate`); this layer sees both.

use crate::certificate::{certificate_for_assembly, Certificate, CertifyError, LevelOneStep, Step};
use crate::geometry::Instance;
use num_rational::BigRational as Q;
use std::collections::HashMap;

/// The certificate of `inst`'s faces with the `level-one` step of its chosen point.
pub fn placement_certificate(inst: &Instance) -> Result<Certificate, CertifyError> {
    let mut cert =
        certificate_for_assembly(&inst.name, &inst.types, &inst.glue, inst.options.clone())?;
    let step = level_one_step(inst, &cert).map_err(CertifyError::Witness)?;
    cert.steps.push(Step::LevelOne(step));
    Ok(cert)
}

/// The `level-one` step of `inst` for the faces' certificate `cert`: the chosen point as the
/// values of `cert`'s free unknowns (its basis vector `j` is 1 at free unknown `j` and 0 at the
/// others, so `t_j` is the point's value there), the frames of the instance's level-1 check,
/// and that check's counts.
fn level_one_step(inst: &Instance, cert: &Certificate) -> Result<LevelOneStep, String> {
    let space = cert
        .steps
        .iter()
        .find_map(|s| match s {
            Step::SolutionSpace(s) => Some(s),
            _ => None,
        })
        .ok_or("the constraints are inconsistent: there is no point to certify")?;
    let recipe = space
        .system
        .recipe
        .as_ref()
        .ok_or("the solution space names no unknowns")?;
    let a = &inst.generated.automaton;
    let by_name: HashMap<String, &Q> = inst
        .linearized
        .unknown_entries
        .iter()
        .zip(&inst.values)
        .map(|(&e, v)| (a.entry_name(e), v))
        .collect();
    let value = |u: usize| -> Result<Q, String> {
        let name = recipe.unknowns.get(u).ok_or("an unknown out of range")?;
        by_name
            .get(name)
            .map(|v| (*v).clone())
            .ok_or_else(|| format!("the instance has no unknown `{name}`"))
    };
    let parameters: Vec<Q> = space
        .free
        .iter()
        .map(|&u| value(u))
        .collect::<Result<_, _>>()?;
    // The point the checker will form must be the instance's: particular + Σ t_j·basis_j at
    // every unknown.
    let parse = |s: &str| s.parse::<Q>().map_err(|e| format!("`{s}`: {e}"));
    let mut formed: Vec<Q> = vec![Q::default(); recipe.unknowns.len()];
    for (u, v) in &space.particular {
        formed[*u] += parse(v)?;
    }
    for (b, t) in space.basis.iter().zip(&parameters) {
        for (u, v) in b {
            formed[*u] += parse(v)? * t;
        }
    }
    for (u, f) in formed.iter().enumerate() {
        if *f != value(u)? {
            return Err(format!(
                "the chosen point is not on the certified solution set at `{}`",
                recipe.unknowns[u]
            ));
        }
    }
    let l = &inst.level_one;
    if l.frames.len() != inst.types.types.len() {
        return Err("the instance's level-1 check did not run".into());
    }
    Ok(LevelOneStep {
        frames: l
            .frames
            .iter()
            .map(|f| {
                f.iter()
                    .map(|p| [p[0].to_string(), p[1].to_string()])
                    .collect()
            })
            .collect(),
        parameters: parameters.iter().map(Q::to_string).collect(),
        sub_faces: l.cells as u64,
        lacunas: l.lacunas as u64,
        smallest_area: l
            .smallest_area
            .as_ref()
            .ok_or("the instance has no sub-face")?
            .to_string(),
    })
}
