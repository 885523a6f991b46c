//! `lacuna operators` from Python: the eigen analysis of an automaton's (or an instantiated face's)
//! subdivision operators and of matrices given by hand, with the curves' DCFs and pseudo-curvature
//! ranges, as the library's report that the command line prints with `--json`.

use super::{json, run_limited};
use lacuna::input::load_any;
use lacuna::Error;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// An error of the command line's flags in the wording of the Python keywords (`--points` is
/// `points=`, `--level` the keyword `level`).
fn keywords(e: Error) -> Error {
    let rename = |m: &str| {
        [
            "--curvature",
            "--points",
            "--at",
            "--op",
            "--level",
            "--svg",
        ]
        .iter()
        .fold(m.to_string(), |m, flag| {
            m.replace(flag, &format!("{}=", &flag[2..]))
        })
        .replace("--max-matrix", "limits={'max_matrix': …}")
    };
    match e {
        Error::Usage(m) => Error::Usage(rename(&m)),
        Error::OutOfRange {
            flag: "--level",
            value,
            what,
            range,
        } => Error::OutOfRange {
            flag: "level",
            value,
            what,
            range,
        },
        other => other,
    }
}

/// `lacuna operators [INPUT] --json`: the report of the operators of `input` (an automaton, or
/// faces instantiated with the default parameters) and of `matrices` (`[a b; c d]`), with the
/// curvature estimate at the fixed point of `curvature` or, with `points`, the curves' ranges.
#[pyfunction]
#[pyo3(signature = (input=None, matrices=Vec::new(), op=None, points=None, at=Vec::new(), level=8, curvature=None, limits=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn operators(
    py: Python<'_>,
    input: Option<String>,
    matrices: Vec<String>,
    op: Option<String>,
    points: Option<String>,
    at: Vec<String>,
    level: u32,
    curvature: Option<String>,
    limits: Option<&Bound<'_, PyDict>>,
) -> PyResult<String> {
    run_limited(py, limits, move |l| {
        let automaton = input
            .as_deref()
            .map(|i| load_any(i).and_then(|x| lacuna::export::operators_automaton(x, &l)))
            .transpose()?;
        let request = lacuna::export::OperatorsRequest {
            matrices: &matrices,
            curvature: curvature.as_deref(),
            points: points.as_deref(),
            at: &at,
            level,
            op: op.as_deref(),
        };
        let report =
            lacuna::export::operators_report(automaton.as_ref(), &request, &l).map_err(keywords)?;
        Ok(json(&report.to_json()))
    })
}
