//! `lacuna closure`.

use super::*;

/// Runs `lacuna closure`.
pub(super) fn run(args: ClosureArgs, limits: &Limits) -> Result<ExitCode, Error> {
    let ClosureArgs { input, json } = args;
    if let Some((name, v)) = lacuna::input::load_volumes(&input)? {
        return volume::closure(&name, &v, json, limits);
    }
    let input = load_input(&input)?;
    let closure = Closure::of(&input.faces(), limits)?;
    if json {
        print_json(&lacuna::export::closure_json(&closure));
    } else {
        let report = lacuna::export::closure_report(&input, &closure);
        out(&report.closure_text());
    }
    Ok(match closure {
        Closure::Closed(_) => ExitCode::SUCCESS,
        Closure::Runaway(_) => ExitCode::from(EXIT_FAILED),
    })
}
