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
    // A file that is not a certificate at all (not JSON, or no lacuna certificate format) is
    // bad input, not a failed proof.
    // A proved certificate is one; the text is read again only when the report failed.
    let is_certificate = || {
        serde_json::from_str::<serde_json::Value>(&text)
            .ok()
            .and_then(|v| {
                v.get("format")
                    .and_then(|f| f.as_str())
                    .map(|f| f == lacuna::certificate::FORMAT)
            })
            .unwrap_or(false)
    };
    if !report.all_proved() && !is_certificate() {
        return Ok(ExitCode::from(EXIT_BAD_INPUT));
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
