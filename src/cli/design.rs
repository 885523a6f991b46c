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
    let values = lacuna::analysis::parse_rationals_arg(&eigenvalues)?;
    let vectors = lacuna::analysis::parse_matrix_arg(&eigenvectors)?;
    let rows: Vec<Vec<_>> = vectors
        .data
        .chunks(vectors.cols)
        .map(<[_]>::to_vec)
        .collect();
    let t = lacuna::analysis::design_operator(&values, &rows)?;
    let analysis = lacuna::analysis::analyse_matrix(&t)?;
    let checked = match (&check, &op) {
        (Some(file), Some(name)) => match lacuna::input::load_any(file)? {
            lacuna::input::Loaded::Automaton { automaton, .. } => {
                Some(lacuna::analysis::check_design(&automaton, name, &t)?)
            }
            lacuna::input::Loaded::Faces(_) => {
                return Err(Error::Usage(format!("`{file}` is not an automaton")))
            }
        },
        _ => None,
    };
    if json {
        print_json(&serde_json::json!({
            "matrix": t.to_string(),
            "analysis": analysis,
            "check": checked,
        }));
    } else {
        out(&format!("T = {t}\n"));
        out(&analysis.to_text());
        if let Some(c) = &checked {
            out(&c.to_text());
        }
    }
    Ok(if checked.as_ref().is_some_and(|c| !c.ok()) {
        ExitCode::from(EXIT_FAILED)
    } else {
        ExitCode::SUCCESS
    })
}
