//! `lacuna export` from Python: the automaton generated from the closure of faces, in lacuna's
//! automaton format or as the MODITERE Python model, as text (and written to a file).

use super::{gen_options, refuse_clobbering, run_limited, write_file};
use lacuna::export::GeneratedFormat;
use lacuna::Error;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;

/// `lacuna export INPUT --format F [-o PATH]`: the text, written to `path` too when given.
#[pyfunction]
#[pyo3(signature = (input, format="aut".to_string(), path=None, degree=2, cantor_gap="1".to_string(), limits=None))]
pub(crate) fn export(
    py: Python<'_>,
    input: String,
    format: String,
    path: Option<PathBuf>,
    degree: usize,
    cantor_gap: String,
    limits: Option<&Bound<'_, PyDict>>,
) -> PyResult<String> {
    run_limited(py, limits, move |l| {
        let format = match format.as_str() {
            "aut" => GeneratedFormat::Aut,
            "moditere" => GeneratedFormat::Moditere,
            other => {
                return Err(Error::Usage(format!(
                    "format `{other}`: the formats are 'aut' and 'moditere'"
                )))
            }
        };
        let opts = gen_options(degree, &cantor_gap)?;
        // The output is checked before the work: never the input.
        refuse_clobbering(&input, &[&path])?;
        let text =
            lacuna::export::generated_text(lacuna::input::load_any(&input)?, format, opts, &l)?;
        if let Some(p) = &path {
            write_file(p, |w| w.write_all(text.as_bytes()))?;
        }
        Ok(text)
    })
}
