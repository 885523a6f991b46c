//! `lacuna measure`.

use super::*;

/// Runs `lacuna measure`.
pub(super) fn run(args: MeasureArgs, limits: &Limits) -> Result<ExitCode, Error> {
    let MeasureArgs {
        geo,
        raster,
        max_raster,
        density_grid,
        print,
        json,
        digits,
        certificate,
        state,
    } = args;
    check_raster("--raster", raster, lacuna::measure::LARGEST_RASTER)?;
    check_raster("--max-raster", max_raster, lacuna::measure::LARGEST_RASTER)?;
    if max_raster < raster {
        return Err(Error::OutOfRange {
            flag: "--max-raster",
            value: max_raster.to_string(),
            what: "the finest raster",
            range: format!("at least --raster ({raster})"),
        });
    }
    check_density_grid(density_grid, 0)?;
    let mut outputs = match &certificate {
        Some(path) => Outputs::check(
            &[std::path::Path::new(&geo.input)],
            &[("--certificate", path)],
        )?,
        None => Outputs::check(&[], &[])?,
    };
    if json && outputs.to_stdout {
        return Err(Error::Usage(
            "--json and --certificate - would both write to standard output".into(),
        ));
    }
    let faces_only = || {
        Error::Usage(
            "--certificate: measure certifies the chosen point of faces; for volumes and \
             automata, `lacuna verify INPUT --certificate OUT.json` certifies every exact figure \
             measure prints"
                .into(),
        )
    };
    let no_states = |what: &str| automaton::no_states(state.as_deref(), what, "measure");
    if let Some((name, v)) = lacuna::input::load_volume_file(&geo.input)? {
        if certificate.is_some() {
            return Err(faces_only());
        }
        if state.is_some() {
            return Err(no_states("a volume has no states"));
        }
        return volume::measure(&name, &v, &geo, &print, json, limits);
    }
    if let Some((name, model)) = automaton::automaton_input(&geo)? {
        if certificate.is_some() {
            return Err(faces_only());
        }
        let p = automaton::prepare_at(&geo, name, model, state.as_deref(), limits, 2_000_000)?;
        return automaton::measure(&geo, p, digits, json, limits);
    }
    if state.is_some() {
        return Err(no_states("faces have no states"));
    }
    let (_, inst) = instance(&geo, limits, 20_000_000)?;
    let opts = lacuna::measure::MeasureOptions {
        level: geo.level,
        raster,
        max_raster,
        segments: geo.segments,
        density_grid,
        ..Default::default()
    };
    let mut r = lacuna::measure::measure(&inst, &opts).map_err(geo_error)?;
    r.certification = lacuna::measure::certification(&inst);
    // Printability at the level: the smallest hole and thinnest ligament in mm (THEORY §11).
    let size = lacuna::mesh::Size {
        width: print.width,
        ..Default::default()
    };
    lacuna::mesh::check_size("--width", print.width).map_err(mesh_error)?;
    lacuna::mesh::check_size("--resolution", print.resolution).map_err(mesh_error)?;
    let p = lacuna::mesh::printability(&inst, geo.level, geo.segments, size, print.resolution)
        .map_err(mesh_error)?;
    eprint!("{}", choice_text(&geo, &inst));
    for f in &r.failures {
        eprintln!("verification failed: {f}");
    }
    let strict_failures = if print.strict { p.below() } else { Vec::new() };
    for f in &strict_failures {
        eprintln!("verification failed: {f}");
    }
    if let Some(path) = &certificate {
        let cert = lacuna::measure::placement_certificate(&inst)
            .map_err(|e| e.into_error("--certificate"))?;
        outputs.write(path, |w| w.write_all(cert.to_json().as_bytes()))?;
    }
    if json {
        print_json(&lacuna::mesh::printability::WithPrintability {
            report: &r,
            printability: &lacuna::mesh::printability::PrintReport::of_plate(&p, print.bed),
        });
    } else {
        out(&r.to_text());
        out(&p.text());
        if let Some(path) = &certificate {
            outputs.say(&format!("certificate written to {}\n", path.display()));
        }
    }
    Ok(if r.verified && strict_failures.is_empty() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(EXIT_FAILED)
    })
}
