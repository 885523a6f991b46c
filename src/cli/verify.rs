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
    if let Some((name, v)) = lacuna::input::load_volume(input.as_deref().unwrap_or("F0"))? {
        limits.check_level(levels)?;
        return volume::verify(&name, &v, levels, json, limits);
    }
    limits.check_level(levels)?;
    let input = load_input(input.as_deref().unwrap_or("F0"))?;
    let closure = Closure::of(&input.faces(), limits)?;
    let report = verify_report(&input, &closure, levels, limits)?;
    if json {
        print_json(&report);
    } else {
        out(&report.to_text());
    }
    if let Some(path) = &certificate {
        let io = |e: String| Error::Io {
            path: path.display().to_string(),
            reason: e,
        };
        match &closure {
            Closure::Closed(ts) => {
                let cert = lacuna::certificate::certificate_for(
                    &input.name,
                    ts,
                    lacuna::constraint::GenOptions::default(),
                )
                .map_err(|e| io(e.to_string()))?;
                std::fs::write(path, cert.to_json()).map_err(|e| io(e.to_string()))?;
                if !json {
                    out(&format!("certificate written to {}\n", path.display()));
                }
            }
            Closure::Runaway(_) => {
                eprintln!("no certificate written: the closure did not close (certificates have no runaway step)")
            }
        }
    }
    Ok(if report.verified {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(EXIT_FAILED)
    })
}
