//! `lacuna ratio`.

use super::*;

/// Runs `lacuna ratio`.
pub(super) fn run(args: RatioArgs, limits: &Limits) -> Result<ExitCode, Error> {
    let RatioArgs {
        input,
        digits,
        json,
    } = args;
    if let Some((name, v)) = lacuna::input::load_volumes(&input)? {
        limits.check_digits(digits)?;
        return volume::ratio(&name, &v, digits, json, limits);
    }
    limits.check_digits(digits)?;
    let input = load_input(&input)?;
    let ts = lacuna::topology::close_or_error(&input.faces(), limits)?;
    let r = lacuna::export::ratio_of(&ts, digits)?;
    if json {
        print_json(&r);
    } else {
        out(&format!(
            "{} ({} face type{})\n",
            input.name,
            ts.types.len(),
            if ts.types.len() == 1 { "" } else { "s" }
        ));
        out(&lacuna::export::ratio_text(&r));
    }
    Ok(ExitCode::SUCCESS)
}
