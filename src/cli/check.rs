//! `lacuna check`.

use super::*;

/// Runs `lacuna check`.
pub(super) fn run(args: CheckArgs) -> Result<ExitCode, Error> {
    let CheckArgs {
        certificate,
        json,
        max_work,
        max_levels,
        max_sides,
    } = args;
    let text = lacuna::input::read_text(&certificate.to_string_lossy())?;
    let budget = lacuna::checker::Budget {
        work: max_work,
        levels: max_levels,
        sides: max_sides,
    };
    let report = lacuna::checker::check_json_with(&text, budget);
    if json {
        print_json(&report.to_json());
    } else {
        out(&report.to_text());
    }
    Ok(if report.all_proved() {
        ExitCode::SUCCESS
    } else if report.refused() {
        ExitCode::from(EXIT_BAD_INPUT)
    } else if report.partial() {
        ExitCode::from(EXIT_PARTIAL)
    } else {
        ExitCode::from(EXIT_FAILED)
    })
}
