//! `lacuna design` from Python: the exact operator T = V·D·V⁻¹ of chosen eigenvalues and
//! eigenvectors, its eigen analysis and, against an automaton, the check of plugging it in.

use super::run;
use lacuna::input::{load_any, Loaded};
use lacuna::Error;
use pyo3::prelude::*;

/// `lacuna design --eigenvalues V --eigenvectors M [--check FILE --op NAME] --json`.
#[pyfunction]
#[pyo3(signature = (eigenvalues, eigenvectors, check=None, op=None))]
pub(crate) fn design(
    py: Python<'_>,
    eigenvalues: String,
    eigenvectors: String,
    check: Option<String>,
    op: Option<String>,
) -> PyResult<String> {
    run(py, move || {
        let mut report = lacuna::export::design_report(&eigenvalues, &eigenvectors)?;
        if let (Some(file), Some(name)) = (&check, &op) {
            report.check = Some(match load_any(file)? {
                Loaded::Automaton { automaton, .. } => {
                    lacuna::analysis::check_design(&automaton, name, &report.matrix)?
                }
                Loaded::Faces(_) => {
                    return Err(Error::Usage(format!("`{file}` is not an automaton")))
                }
            });
        }
        Ok(super::json(&report.to_json()))
    })
}
