//! `lacuna verify`.

use super::*;

/// Runs `lacuna verify`.
pub(super) fn run(args: VerifyArgs, limits: &Limits) -> Result<ExitCode, Error> {
    let VerifyArgs {
        input,
        levels,
        json,
        certificate,
    } = args;
    if let Some((name, v)) = lacuna::input::load_volumes(input.as_deref().unwrap_or("F0"))? {
        limits.check_level(levels)?;
        return volume::verify(&name, &v, levels, json, certificate.as_deref(), limits);
    }
    limits.check_level(levels)?;
    let arg = input.as_deref().unwrap_or("F0");
    if !arg.contains('|') && !arg.trim().is_empty() {
        if let lacuna::input::Loaded::Automaton { name, model, .. } = lacuna::input::load_any(arg)?
        {
            return automaton::verify(arg, &name, &model, json, certificate.as_deref(), limits);
        }
    }
    let mut outputs = match &certificate {
        Some(path) => Outputs::check(&[std::path::Path::new(arg)], &[("--certificate", path)])?,
        None => Outputs::check(&[], &[])?,
    };
    if json && outputs.to_stdout {
        return Err(Error::Usage(
            "--json and --certificate - would both write to standard output".into(),
        ));
    }
    let input = load_input(arg)?;
    let closure = Closure::of(&input.faces(), limits)?;
    let report = verify_report(&input, &closure, levels, limits)?;
    // The text report comes first; under --json the report is printed only once everything
    // succeeded, so that standard output holds one JSON document (the report or the error).
    if !json && !outputs.to_stdout {
        out(&report.to_text());
    }
    if let Some(path) = &certificate {
        match &closure {
            Closure::Closed(ts) => {
                let cert = lacuna::certificate::certificate_for_assembly(
                    &input.name,
                    ts,
                    &input.assembly.canonical_glue(),
                    lacuna::constraint::GenOptions::default(),
                )
                .map_err(|e| e.into_error("--certificate"))?;
                outputs.write(path, |w| w.write_all(cert.to_json().as_bytes()))?;
                if !json {
                    outputs.say(&format!("certificate written to {}\n", path.display()));
                }
            }
            Closure::Runaway(_) => {
                eprintln!("no certificate written: the closure did not close (certificates have no runaway step)")
            }
        }
    }
    if json {
        print_json(&report);
    } else if outputs.to_stdout {
        eprint!("{}", report.to_text());
    }
    Ok(if report.verified {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(EXIT_FAILED)
    })
}
