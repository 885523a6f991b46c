//! Volumes (THEORY §10) in `closure`, `counts`, `ratio` and `verify`: the commands try
//! [`lacuna::input::load_volume`] first and hand a volume to these functions.

use super::*;
use lacuna::topology::volume::{volume_counts, VolumeAssembly, VolumeClosure};

/// `lacuna closure` of a volume.
pub(super) fn closure(
    name: &str,
    v: &VolumeAssembly,
    json: bool,
    limits: &Limits,
) -> Result<ExitCode, Error> {
    let c = VolumeClosure::of(&v.volumes, limits)?;
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
    v: &[lacuna::topology::volume::Volume],
    limits: &Limits,
) -> Result<lacuna::topology::volume::VolumeTypeSet, Error> {
    match VolumeClosure::of(v, limits)? {
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
    v: &VolumeAssembly,
    levels: u64,
    json: bool,
    limits: &Limits,
) -> Result<ExitCode, Error> {
    let set = closed(&v.volumes, limits)?;
    let c = volume_counts(&set, levels);
    let solid = lacuna::topology::volume::solid_topology_of(&set, levels, &v.start_cells())?;
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
    v: &VolumeAssembly,
    digits: usize,
    json: bool,
    limits: &Limits,
) -> Result<ExitCode, Error> {
    let set = closed(&v.volumes, limits)?;
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

/// `lacuna verify` of a volume: the closure, every sub-volume's surface a sphere, counts and R;
/// with `--certificate`, the certificate of the closure and counts (THEORY §10).
pub(super) fn verify(
    name: &str,
    v: &VolumeAssembly,
    levels: u64,
    json: bool,
    certificate: Option<&std::path::Path>,
    limits: &Limits,
) -> Result<ExitCode, Error> {
    let mut outputs = match certificate {
        Some(path) => Outputs::check(&[std::path::Path::new(name)], &[("--certificate", path)])?,
        None => Outputs::check(&[], &[])?,
    };
    if json && outputs.to_stdout {
        return Err(Error::Usage(
            "--json and --certificate - would both write to standard output".into(),
        ));
    }
    let c = VolumeClosure::of(&v.volumes, limits)?;
    let VolumeClosure::Closed(set) = c else {
        if certificate.is_some() {
            eprintln!("no certificate written: the closure did not close (certificates have no runaway step)");
        }
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
    let solid = lacuna::topology::volume::solid_topology_of(&set, levels, &v.start_cells())?;
    let r = lacuna::export::volume_ratio(&set, 30)?;
    // The constraints of THEORY §10 are generated for one volume: the incidence along faces
    // shared between volumes is not built.
    let solver = match v.volumes.len() {
        1 => Some(lacuna::constraint::solve_volumes(
            &set,
            Default::default(),
            limits,
        )?),
        _ => None,
    };
    let verified = failures.is_empty() && solver.as_ref().is_none_or(|s| s.ok());
    let cert = match certificate {
        Some(_) => Some(
            lacuna::certificate::certificate_for_volumes(name, &set, levels).map_err(
                |e| match e {
                    lacuna::certificate::CertifyError::Lacuna(e) => e,
                    e => Error::Usage(format!("--certificate: {e}")),
                },
            )?,
        ),
        None => None,
    };
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
        let mut t = lacuna::export::volume_closure_text(name, &VolumeClosure::Closed(set));
        t += &format!(
            "\nstructure: every sub-volume's boundary is a sphere{}\n\ncounts\n",
            if verified { "" } else { ": FAILED" }
        );
        for f in &failures {
            t += &format!("  {f}\n");
        }
        t += &lacuna::export::volume_counts_table(&counts);
        t += "\nthe level-n solid (exact cell counts; – where not derived)\n";
        t += &lacuna::export::solid_table(&solid);
        t += "\n";
        t += &lacuna::export::ratio_text(&r);
        match &solver {
            Some(solver) => {
                t += &format!(
                    "\nconstraints (faces and volumes, Bézier degree 2): {} unknowns, {} equations, {}\n",
                    solver.unknowns,
                    solver.equations,
                    if solver.consistent {
                        format!("consistent, {} degrees of freedom", solver.dof)
                    } else {
                        "INCONSISTENT (see `lacuna solve`)".into()
                    }
                );
                t += &format!(
                    "degeneracy: {}\n",
                    if solver.degenerate.is_empty() {
                        "no two distinct corner points of a face's level-1 complex are forced to coincide"
                            .to_string()
                    } else {
                        solver.degenerate.join("; ")
                    }
                );
            }
            None => {
                t += "\nconstraints: not generated for an assembly of several volumes (the incidence along shared faces is not built); the verdict covers the closure, the spheres, the counts and R\n";
            }
        }
        t += &format!(
            "\nverdict: {}\n",
            if verified { "VERIFIED" } else { "NOT VERIFIED" }
        );
        match outputs.to_stdout {
            true => eprint!("{t}"),
            false => out(&t),
        }
    }
    if let (Some(path), Some(cert)) = (certificate, cert) {
        outputs.write(path, |w| w.write_all(cert.to_json().as_bytes()))?;
        if !json {
            outputs.say(&format!("certificate written to {}\n", path.display()));
        }
    }
    Ok(if verified {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(EXIT_FAILED)
    })
}
