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
        out(&lacuna::export::volume_closure_text("closure", name, &c));
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
        // `levels` and `types` as faces have them (issue #32); `counts` and `volume_types` are
        // the old names, kept for one release.
        print_json(&serde_json::json!({
            "input": name,
            "types": set.types.len(),
            "levels": c,
            "solid": solid,
            "volume_types": set.types.len(),
            "counts": c,
        }));
    } else {
        let n = set.types.len();
        out(&format!(
            "{name} ({n} volume type{})\n",
            if n == 1 { "" } else { "s" }
        ));
        out(&lacuna::export::volume_counts_table(&c));
        out("\nthe level-n solid (exact cell counts, derived by lacuna, not in the certificate; – where not derived)\n");
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
    // The constraints of THEORY §10, with the faces shared between volumes read from both sides.
    // A limit on the solve leaves the constraints undecided; the rest is still reported (and
    // certified: the constraints are the volume-solution-space step, with the faces an assembly's
    // volumes share).
    let report = lacuna::export::volume_verify(&set, v, levels, limits)?;
    let opts = lacuna::constraint::GenOptions::default();
    let verified = report.verified();
    let decided = report.solved.is_ok();
    let system_step = match &report.solved {
        Ok(s) => lacuna::certificate::volume_system_step(&set, s, &opts).map_err(|e| match e {
            lacuna::certificate::CertifyError::Lacuna(e) => e,
            e => Error::Usage(format!("--certificate: {e}")),
        })?,
        Err(_) => Vec::new(),
    };
    let system_certified = !system_step.is_empty();
    let certified = lacuna::certificate::solid_rows(&report.solid).len();
    let has_voids = lacuna::certificate::recurrence_has_voids(&set);
    let cert = match certificate {
        Some(_) => {
            let mut c = lacuna::certificate::certificate_for_volumes(name, &set, levels, v)
                .map_err(|e| match e {
                    lacuna::certificate::CertifyError::Lacuna(e) => e,
                    e => Error::Usage(format!("--certificate: {e}")),
                })?;
            c.steps.extend(system_step);
            Some(c)
        }
        None => None,
    };
    if json {
        print_json(&report.json(name, &set));
    } else {
        let mut t =
            lacuna::export::volume_closure_text("verify", name, &VolumeClosure::Closed(set));
        t += &format!(
            "\nstructure: every sub-volume's boundary is a sphere{}\n\ncounts\n",
            if verified { "" } else { ": FAILED" }
        );
        for f in &report.failures {
            t += &format!("  {f}\n");
        }
        t += &lacuna::export::volume_counts_table(&report.counts);
        // Voids and tunnels that neither step certifies: past the levels built cell by cell,
        // when the recurrence claims none (a delayed volume).
        let loose: Vec<String> = report
            .solid
            .iter()
            .filter(|l| l.level as usize >= certified && l.level > 0)
            .filter(|l| l.voids.is_some() && !has_voids)
            .map(|l| l.level.to_string())
            .collect();
        t += &format!(
            "\nthe level-n solid (exact; {}cells, χ{} of every level by the recurrence of cells by birth (solid-recurrence){}; – where not derived)\n",
            match certified {
                0 => String::new(),
                n => format!("levels 0–{} certified cell by cell with ranks over F2 (solid-homology); ", n - 1),
            },
            match has_voids {
                true => ", components, voids and tunnels",
                false => " and components",
            },
            match loose.len() {
                0 => String::new(),
                _ => format!(
                    "; voids and tunnels of level {} derived by lacuna's argument (THEORY §10), not in the certificate",
                    loose.join(", ")
                ),
            }
        );
        t += &lacuna::export::solid_table(&report.solid);
        t += "\n";
        t += &lacuna::export::ratio_text(&report.ratio);
        match &report.solved {
            Ok(solved) => {
                let solver = &solved.report;
                t += &format!(
                    "\nconstraints (faces and volumes, Bézier degree 2; exact, {}): {} unknowns, {} equations, {}\n",
                    match system_certified {
                        true => "certified by the solution space (volume-solution-space)",
                        false => "not in the certificate",
                    },
                    solver.unknowns,
                    solver.equations,
                    if solver.consistent {
                        format!("consistent, {} degrees of freedom", solver.dof)
                    } else {
                        "INCONSISTENT (see `lacuna solve`)".into()
                    }
                );
                t += &format!(
                    "degeneracy (exact, {}): {}\n",
                    match system_certified {
                        true => "certified (degeneracy)",
                        false => "not in the certificate",
                    },
                    if solver.degenerate.is_empty() {
                        "no two distinct corner points of a face's level-1 complex are forced to coincide"
                            .to_string()
                    } else {
                        solver.degenerate.join("; ")
                    }
                );
            }
            Err(e) => {
                t += &format!("\nconstraints: NOT DECIDED (a limit, not a verdict): {e}\n");
            }
        }
        t += &format!(
            "\nverdict: {}\n",
            match (verified, decided) {
                (true, _) => "VERIFIED",
                (false, true) => "NOT VERIFIED",
                (false, false) => "NOT DECIDED (the constraints were not solved within the limits)",
            }
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
    // A failure found or a solve that decided against is a verdict; a limit alone is not.
    Ok(if verified {
        ExitCode::SUCCESS
    } else if decided || !report.failures.is_empty() {
        ExitCode::from(EXIT_FAILED)
    } else {
        ExitCode::from(EXIT_BAD_INPUT)
    })
}

/// The checked solid of a volume at `level` (THEORY §10, §11): the level and the exact number of
/// faces are bounded before any geometry is built.
fn checked_solid(
    name: &str,
    v: &lacuna::input::VolumeFile,
    geo: &GeoArgs,
    width: f64,
    limits: &Limits,
) -> Result<
    (
        lacuna::mesh::VolumeSolid,
        lacuna::topology::volume::VolumeTypeSet,
    ),
    Error,
> {
    if u64::from(geo.level) > limits.max_level {
        return Err(Error::limit(
            "the level",
            geo.level,
            limits.max_level,
            "--max-level",
        ));
    }
    only_volume_flags(geo)?;
    let set = closed(&v.assembly.volumes, limits)?;
    let cap = geo.max_cells.unwrap_or(lacuna::mesh::MAX_SOLID_FACES);
    let vs = lacuna::mesh::checked_volume_solid(
        name,
        v,
        &set,
        u64::from(geo.level),
        width,
        cap,
        limits,
    )?;
    Ok((vs, set))
}

/// Refuses the flags that apply to faces only.
fn only_volume_flags(geo: &GeoArgs) -> Result<(), Error> {
    if !geo.params.is_empty()
        || geo.corners.is_some()
        || geo.template.is_some()
        || !geo.goals.is_empty()
    {
        return Err(Error::Usage(
            "--param, --corners, --template and --goal apply to faces; a volume is placed on its solid or on the corners its file gives (see docs/VOLUMES.md)".into(),
        ));
    }
    Ok(())
}

/// What `render` writes for a volume.
pub(super) struct VolumeTargets<'a> {
    pub(super) svg: Option<&'a std::path::Path>,
    pub(super) png: Option<&'a std::path::Path>,
    pub(super) claims: Option<&'a std::path::Path>,
    pub(super) mesh: &'a lacuna::mesh::Targets,
    pub(super) size: usize,
    pub(super) transparent: bool,
    pub(super) style: lacuna::mesh::threemf::Style,
}

/// `lacuna render` of a volume: the mesh files only when the solid is embedded (no two triangles
/// cross); the pictures in any case, with a warning when it folds.
pub(super) fn render(
    name: &str,
    v: &lacuna::input::VolumeFile,
    geo: &GeoArgs,
    print: &PrintArgs,
    t: VolumeTargets<'_>,
    outputs: &mut Outputs,
    limits: &Limits,
) -> Result<ExitCode, Error> {
    lacuna::mesh::check_size("--resolution", print.resolution).map_err(mesh_error)?;
    let (mut vs, set) = checked_solid(name, v, geo, print.width, limits)?;
    outputs.say(&vs.summary());
    let sizes = vs.sizes(print.layers, print.resolution);
    outputs.say(&sizes.text(print.resolution));
    let mut failed = false;
    if t.mesh.any() {
        vs.embedded()?;
        // The overhang and the largest bridge are measured for the JSON object only.
        if outputs.json {
            outputs.printability =
                Some(sizes.report(&vs.solid.parts, geo.level, print.resolution, print.bed));
        }
        if print.strict {
            if let Some(b) = sizes.below(print.resolution).first() {
                return Err(mesh_error(lacuna::mesh::MeshError::Resolution(b.clone())));
            }
        }
    } else if let Some(m) = &vs.crossing {
        eprintln!("warning: {m}");
        failed = true;
    }
    let wrote = |o: &Outputs, p: &std::path::Path| o.say(&format!("wrote {}\n", p.display()));
    let orientation = match t.mesh.any() {
        true => Some(super::render::orient(
            &mut vs.solid.parts,
            print.orient,
            outputs,
        )),
        false => None,
    };
    let solid = &vs.solid;
    if t.mesh.any() {
        if let Some(w) = solid.bed_advice(print.bed, print.width) {
            eprintln!("{w}");
        }
    }
    if let Some(p) = &t.mesh.stl {
        outputs.write(p, |w| match t.mesh.stl_ascii {
            true => lacuna::mesh::stl::write_ascii(solid, w),
            false => lacuna::mesh::stl::write_binary(solid, w),
        })?;
        wrote(outputs, p);
    }
    if let (Some(p), Some(o)) = (&t.mesh.threemf, &orientation) {
        use lacuna::mesh::threemf::Style;
        let type_name = |k: usize| format!("V{k}");
        match t.style {
            Style::Plain => super::render::write_threemf(outputs, p, |zip| {
                lacuna::mesh::threemf::write(solid, zip)
            })?,
            Style::Colours => {
                let colours = lacuna::export::volume_type_colours(&vs, &set)?;
                super::render::write_threemf(outputs, p, |zip| {
                    lacuna::mesh::threemf::write_with(solid, Some(&colours), zip)
                })?;
            }
            Style::Parts => {
                let mut parts = vs.type_parts(&set)?;
                let title = format!("{} level {}", solid.name, solid.level);
                super::render::write_type_parts(outputs, p, &title, &mut parts, o, type_name)?;
            }
        }
        wrote(outputs, p);
    }
    if let Some(p) = &t.mesh.obj {
        outputs.write(p, |w| lacuna::mesh::obj::write(solid, w))?;
        wrote(outputs, p);
    }
    if let Some(p) = t.claims {
        let c = lacuna::export::volume_solid_claims(
            format!("{} level {}", geo.input, geo.level),
            t.mesh,
            &vs,
        );
        super::render::write_claims(outputs, p, &c)?;
    }
    if let Some(p) = t.svg {
        outputs.write(p, |w| {
            lacuna::export::write_volume_svg(&solid.parts, 512, w)
        })?;
        wrote(outputs, p);
    }
    if let Some(p) = t.png {
        outputs.write(p, |w| {
            lacuna::export::write_volume_png(&solid.parts, t.size as u32, t.transparent, w)
        })?;
        wrote(outputs, p);
    }
    Ok(if failed {
        ExitCode::from(EXIT_FAILED)
    } else {
        ExitCode::SUCCESS
    })
}

/// Which step of a volume's certificate proves the exact figures of `level`, when the
/// `solid-homology` step builds levels `0..certified` cell by cell and `has_voids` says whether
/// the `solid-recurrence` step claims voids and tunnels past level 0.
fn solid_provenance(
    level: &lacuna::topology::volume::SolidLevel,
    certified: usize,
    has_voids: bool,
) -> String {
    if (level.level as usize) < certified {
        return "certified cell by cell with ranks over F2 (solid-homology)".into();
    }
    let loose = level.level > 0 && level.voids.is_some() && !has_voids;
    format!(
        "cells, χ{} certified by the recurrence of cells by birth (solid-recurrence){}",
        match has_voids {
            true => ", components, voids and tunnels",
            false => " and components",
        },
        match loose {
            true => "; voids and tunnels derived by lacuna's argument (THEORY §10), not in the certificate",
            false => "",
        }
    )
}

/// `lacuna measure` of a volume: the exact topology of the level, the checked mesh, its sizes in
/// mm and the printability against `--resolution`.
pub(super) fn measure(
    name: &str,
    v: &lacuna::input::VolumeFile,
    geo: &GeoArgs,
    print: &PrintArgs,
    json: bool,
    limits: &Limits,
) -> Result<ExitCode, Error> {
    lacuna::mesh::check_size("--resolution", print.resolution).map_err(mesh_error)?;
    let (vs, set) = checked_solid(name, v, geo, print.width, limits)?;
    let sizes = vs.sizes(print.layers, print.resolution);
    let verified =
        vs.crossing.is_none() && (!print.strict || sizes.below(print.resolution).is_empty());
    if json {
        print_json(&lacuna::export::volume_measure_json(
            name,
            &vs,
            &sizes,
            print.resolution,
            print.bed,
            verified,
        ));
    } else {
        let levels = lacuna::topology::volume::solid_topology_of(
            &set,
            u64::from(geo.level),
            &v.assembly.start_cells(),
        )?;
        out(&format!(
            "{name}, level {} (exact; {}: `lacuna verify {name} --levels {} --certificate OUT.json` writes it)\n",
            geo.level,
            solid_provenance(&vs.exact, lacuna::certificate::solid_rows(&levels).len(), lacuna::certificate::recurrence_has_voids(&set)),
            geo.level.max(1),
        ));
        out(&lacuna::export::solid_table(std::slice::from_ref(
            &vs.exact,
        )));
        out(&vs.summary());
        out(&format!(
            "  (lacuna's own check of the mesh it built, not a certificate step: `lacuna render {name} --level {} --stl F.stl --claims C.json` writes it, `lacuna check-mesh F.stl --claims C.json` re-checks the file independently)\n",
            geo.level
        ));
        out(&sizes.text(print.resolution));
        out(&format!(
            "verdict: {}\n",
            if verified { "VERIFIED" } else { "NOT VERIFIED" }
        ));
    }
    Ok(if verified {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(EXIT_FAILED)
    })
}

/// `lacuna report` of a volume: an HTML page with the closure, the exact solid, the checked mesh
/// and its sizes, a WebGL view and an SVG projection.
pub(super) fn report(
    name: &str,
    v: &lacuna::input::VolumeFile,
    geo: &GeoArgs,
    path: &std::path::Path,
    outputs: &mut Outputs,
    limits: &Limits,
) -> Result<ExitCode, Error> {
    only_volume_flags(geo)?;
    let page = lacuna::export::volume_report_page(name, v, geo.level, geo.max_cells, limits)?;
    outputs.write(path, |w| w.write_all(page.html.as_bytes()))?;
    outputs.say(&format!("wrote {}\n", path.display()));
    Ok(if page.verified {
        ExitCode::SUCCESS
    } else {
        if let Some(w) = &page.warning {
            eprintln!("warning: {w}");
        }
        ExitCode::from(EXIT_FAILED)
    })
}
