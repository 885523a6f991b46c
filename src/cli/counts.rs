//! `lacuna counts`.

use super::*;

/// Runs `lacuna counts`.
pub(super) fn run(args: CountsArgs, limits: &Limits) -> Result<ExitCode, Error> {
    let CountsArgs {
        input,
        levels,
        json,
    } = args;
    if let Some((name, v)) = lacuna::input::load_volumes(&input)? {
        limits.check_level(levels)?;
        return volume::counts(&name, &v, levels, json, limits);
    }
    limits.check_level(levels)?;
    let input = load_input(&input)?;
    let ts = lacuna::topology::close_or_error(&input.faces(), limits)?;
    if json {
        let mut v = lacuna::export::counts_json(&ts, &input, levels);
        v["input"] = serde_json::Value::from(input.name.clone());
        print_json(&v);
    } else {
        out(&format!(
            "{} ({} face type{})\n",
            input.name,
            ts.types.len(),
            if ts.types.len() == 1 { "" } else { "s" }
        ));
        out(&lacuna::export::counts_table(&lacuna::topology::counts(
            &ts, levels,
        )));
    }
    Ok(ExitCode::SUCCESS)
}
