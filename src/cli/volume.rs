//! Volumes (THEORY §10) in `closure`, `counts`, `ratio` and `verify`: the commands try
//! [`lacuna::input::load_volume`] first and hand a volume to these functions.

use super::*;
use lacuna::topology::volume::{volume_counts, Volume, VolumeClosure};

/// `lacuna closure` of a volume.
pub(super) fn closure(
    name: &str,
    v: &Volume,
    json: bool,
    limits: &Limits,
) -> Result<ExitCode, Error> {
    let c = VolumeClosure::of(std::slice::from_ref(v), limits)?;
    if json {
        print_json(&lacuna::export::volume_closure_json(name, &c));
    } else {
        out(&lacuna::export::volume_closure_text(name, &c));
    }
    Ok(match c {
        VolumeClosure::Closed(_) => ExitCode::SUCCESS,
        VolumeClosure::Runaway(_) => ExitCode::from(EXIT_FAILED),
    })
}

/// The closed set of a volume, or the runaway as a coded error (for the commands that need it).
pub(super) fn closed(
    v: &Volume,
    limits: &Limits,
) -> Result<lacuna::topology::volume::VolumeTypeSet, Error> {
    match VolumeClosure::of(std::slice::from_ref(v), limits)? {
        VolumeClosure::Closed(set) => Ok(set),
        VolumeClosure::Runaway(r) => Err(Error::Usage(format!(
            "the volume's closure did not close: {} (see `lacuna closure`)",
            r.reason
        ))),
    }
}

/// `lacuna counts` of a volume.
pub(super) fn counts(
    name: &str,
    v: &Volume,
    levels: u64,
    json: bool,
    limits: &Limits,
) -> Result<ExitCode, Error> {
    let set = closed(v, limits)?;
    let c = volume_counts(&set, levels);
    let solid = lacuna::topology::volume::solid_topology(&set, levels)?;
    if json {
        print_json(&serde_json::json!({
            "input": name,
            "volume_types": set.types.len(),
            "counts": c,
            "solid": solid,
        }));
    } else {
        let n = set.types.len();
        out(&format!(
            "{name} ({n} volume type{})\n",
            if n == 1 { "" } else { "s" }
        ));
        out(&lacuna::export::volume_counts_table(&c));
        out("\nthe level-n solid (exact cell counts; – where not derived)\n");
        out(&lacuna::export::solid_table(&solid));
    }
    Ok(ExitCode::SUCCESS)
}

/// `lacuna ratio` of a volume.
pub(super) fn ratio(
    name: &str,
    v: &Volume,
    digits: usize,
    json: bool,
    limits: &Limits,
) -> Result<ExitCode, Error> {
    let set = closed(v, limits)?;
    let r = lacuna::export::volume_ratio(&set, digits)?;
    if json {
        print_json(&r);
    } else {
        let n = set.types.len();
        out(&format!(
            "{name} ({n} volume type{})\n",
            if n == 1 { "" } else { "s" }
        ));
        out(&lacuna::export::ratio_text(&r));
    }
    Ok(ExitCode::SUCCESS)
}

/// `lacuna verify` of a volume: the closure, every sub-volume's surface a sphere, counts and R.
pub(super) fn verify(
    name: &str,
    v: &Volume,
    levels: u64,
    json: bool,
    limits: &Limits,
) -> Result<ExitCode, Error> {
    let c = VolumeClosure::of(std::slice::from_ref(v), limits)?;
    let VolumeClosure::Closed(set) = c else {
        return closure(name, v, json, limits).map(|_| ExitCode::from(EXIT_FAILED));
    };
    let mut failures = Vec::new();
    for (i, t) in set.types.iter().enumerate() {
        for (k, s) in t.subdivision.subvolumes.iter().enumerate() {
            if let Err(e) = s.volume.surface.check() {
                failures.push(format!("V{i} sub-volume {k}: {e}"));
            }
        }
    }
    let counts = volume_counts(&set, levels);
    let solid = lacuna::topology::volume::solid_topology(&set, levels)?;
    let r = lacuna::export::volume_ratio(&set, 30)?;
    let solver = lacuna::constraint::solve_volumes(&set, Default::default(), limits)?;
    let verified = failures.is_empty() && solver.ok();
    if json {
        print_json(&serde_json::json!({
            "input": name,
            "verified": verified,
            "volume_types": set.types.len(),
            "failures": failures,
            "counts": counts,
            "solid": solid,
            "ratio": r,
            "solver": solver,
        }));
    } else {
        out(&lacuna::export::volume_closure_text(
            name,
            &VolumeClosure::Closed(set),
        ));
        out(&format!(
            "\nstructure: every sub-volume's boundary is a sphere{}\n\ncounts\n",
            if verified { "" } else { ": FAILED" }
        ));
        for f in &failures {
            out(&format!("  {f}\n"));
        }
        out(&lacuna::export::volume_counts_table(&counts));
        out("\nthe level-n solid (exact cell counts; – where not derived)\n");
        out(&lacuna::export::solid_table(&solid));
        out("\n");
        out(&lacuna::export::ratio_text(&r));
        out(&format!(
            "\nconstraints (faces and volumes, Bézier degree 2): {} unknowns, {} equations, {}\n",
            solver.unknowns,
            solver.equations,
            if solver.consistent {
                format!("consistent, {} degrees of freedom", solver.dof)
            } else {
                "INCONSISTENT (see `lacuna solve`)".into()
            }
        ));
        out(&format!(
            "degeneracy: {}\n",
            if solver.degenerate.is_empty() {
                "no two distinct corner points of a face's level-1 complex are forced to coincide"
                    .to_string()
            } else {
                solver.degenerate.join("; ")
            }
        ));
        out(&format!(
            "\nverdict: {}\n",
            if verified { "VERIFIED" } else { "NOT VERIFIED" }
        ));
    }
    Ok(if verified {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(EXIT_FAILED)
    })
}
