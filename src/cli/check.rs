//! `lacuna check`.

use super::*;

/// Runs `lacuna check`.
pub(super) fn run(args: CheckArgs) -> Result<ExitCode, Error> {
    let CheckArgs { certificate, json } = args;
    let text = lacuna::input::read_text(&certificate.to_string_lossy())?;
    let report = lacuna::checker::check_json(&text);
    if json {
        print_json(&report.to_json());
    } else {
        out(&report.to_text());
    }
    Ok(if report.all_proved() {
        ExitCode::SUCCESS
    } else if report.partial() {
        ExitCode::from(EXIT_PARTIAL)
    } else {
        ExitCode::from(EXIT_FAILED)
    })
}
