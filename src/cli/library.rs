//! `lacuna library`.

use super::*;

/// Runs `lacuna library`.
pub(super) fn run(args: LibraryArgs) -> Result<ExitCode, Error> {
    let LibraryArgs { json } = args;
    let names: Vec<(&str, String)> = lacuna::input::library()
        .iter()
        .map(|(n, t)| {
            (
                *n,
                t.lines()
                    .next()
                    .unwrap_or("")
                    .trim_start_matches('#')
                    .trim()
                    .to_string(),
            )
        })
        .collect();
    if json {
        print_json(
            &names
                .iter()
                .map(|(n, d)| serde_json::json!({"name": n, "about": d}))
                .collect::<Vec<_>>(),
        );
    } else {
        let width = names
            .iter()
            .map(|(n, _)| n.chars().count())
            .max()
            .unwrap_or(0);
        for (n, d) in names {
            out(&format!("{n:<width$}  {d}\n"));
        }
    }
    Ok(ExitCode::SUCCESS)
}
