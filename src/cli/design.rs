//! `lacuna design`.

use super::*;

/// Runs `lacuna design`.
pub(super) fn run(args: DesignArgs) -> Result<ExitCode, Error> {
    let DesignArgs {
        eigenvalues,
        eigenvectors,
        check,
        op,
        json,
    } = args;
    let mut report = lacuna::export::design_report(&eigenvalues, &eigenvectors)?;
    report.check = match (&check, &op) {
        (Some(file), Some(name)) => match lacuna::input::load_any(file)? {
            lacuna::input::Loaded::Automaton { automaton, .. } => Some(
                lacuna::analysis::check_design(&automaton, name, &report.matrix)?,
            ),
            lacuna::input::Loaded::Faces(_) => {
                return Err(Error::Usage(format!("`{file}` is not an automaton")))
            }
        },
        _ => None,
    };
    let checked = &report.check;
    if json {
        print_json(&report.to_json());
    } else {
        out(&format!("T = {}\n", report.matrix));
        out(&report.analysis.to_text());
        if let Some(c) = checked {
            out(&c.to_text());
        }
    }
    Ok(if checked.as_ref().is_some_and(|c| !c.ok()) {
        ExitCode::from(EXIT_FAILED)
    } else {
        ExitCode::SUCCESS
    })
}
