//! `lacuna library`.

use super::*;

/// Runs `lacuna library`.
pub(super) fn run(args: LibraryArgs) -> Result<ExitCode, Error> {
    let LibraryArgs { json } = args;
    let names: Vec<(&str, &str, String)> = lacuna::input::library()
        .iter()
        .map(|(n, t)| {
            (
                *n,
                lacuna::input::kind_of(t),
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
                .map(|(n, k, d)| serde_json::json!({"name": n, "kind": k, "about": d}))
                .collect::<Vec<_>>(),
        );
    } else {
        let width = names
            .iter()
            .map(|(n, _, _)| n.chars().count())
            .max()
            .unwrap_or(0);
        for (n, k, d) in names {
            out(&format!("{n:<width$}  {k:<9}  {d}\n"));
        }
    }
    Ok(ExitCode::SUCCESS)
}
