//! Families of faces from Python: one shard of `lacuna explore` (the Python package splits a
//! family into shards and hands them to any `concurrent.futures.Executor`), `lacuna census`, and
//! the independent mesh checker of `lacuna check-mesh`.

use super::{json, run, run_limited};
use lacuna::analysis::ExploreSpec;
use lacuna::Error;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Shard `shard` (0-based) of `shards` of a family, as `lacuna explore --shard i/n --json`
/// explores it: `{"results": [one per boundary], "summary": {...}}`, with the same properties
/// (`holes` measured at `holes_level` under the `max_holes_cells` estimate).
#[pyfunction]
#[pyo3(signature = (edges, max_length, params, algorithm, properties, random, seed, shard, shards, shrink_budget, threads, holes_level=lacuna::family::DEFAULT_HOLES_LEVEL, max_holes_cells=lacuna::family::DEFAULT_MAX_HOLES_CELLS, limits=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn explore_shard(
    py: Python<'_>,
    edges: String,
    max_length: usize,
    params: String,
    algorithm: String,
    properties: String,
    random: Option<u64>,
    seed: u64,
    shard: u64,
    shards: u64,
    shrink_budget: usize,
    threads: usize,
    holes_level: u32,
    max_holes_cells: u64,
    limits: Option<&Bound<'_, PyDict>>,
) -> PyResult<String> {
    run_limited(py, limits, move |l| {
        let algorithm = lacuna::topology::Algorithm::parse(algorithm.trim(), 1, &[])
            .map_err(|e| e.within(&lacuna::Source::command_line(&algorithm), 1, 0))?;
        let properties = lacuna::analysis::parse_properties(&properties)?;
        if shards == 0 || shard >= shards {
            return Err(Error::Usage(format!(
                "shard {shard} of {shards}: shards are numbered from 0 to shards − 1"
            )));
        }
        let spec = ExploreSpec {
            edges: lacuna::analysis::parse_edge_list(&edges, "edges")?,
            max_length,
            params: lacuna::analysis::parse_edge_list(&params, "parameters")?,
            algorithm,
            properties,
            random,
            seed,
            shard: (shard, shards),
            shrink_budget,
            threads: threads.clamp(1, 256),
        };
        lacuna::family::check_holes_work(&spec, holes_level, max_holes_cells, &l)?;
        let mut results = Vec::new();
        let summary = lacuna::family::with_checks(holes_level, &l, |checks| {
            lacuna::analysis::explore(&spec, &l, checks, |r| {
                results.push(serde_json::to_value(r).expect("results serialise"))
            })
        })?;
        Ok(json(
            &serde_json::json!({ "results": results, "summary": summary }),
        ))
    })
}

/// `lacuna census --json`: the family's closures, with every face.
#[pyfunction]
#[pyo3(signature = (edges, params, algorithms, max_length, threads=None, limits=None))]
pub(crate) fn census(
    py: Python<'_>,
    edges: String,
    params: String,
    algorithms: String,
    max_length: usize,
    threads: Option<usize>,
    limits: Option<&Bound<'_, PyDict>>,
) -> PyResult<String> {
    run_limited(py, limits, move |l| {
        let mut spec =
            lacuna::analysis::CensusSpec::parse(&edges, &params, &algorithms, max_length, threads)?;
        spec.per_face = true;
        Ok(json(&lacuna::analysis::census(&spec, &l)))
    })
}

/// `lacuna check-mesh --json` on the bytes of an STL or 3MF file, with the expectations and the
/// claims file's text when given (its `passed` says whether every check and expectation held).
#[pyfunction]
#[pyo3(signature = (bytes, name, expect_euler=None, expect_parts=None, claims=None, max_triangles=20_000_000))]
pub(crate) fn check_mesh(
    py: Python<'_>,
    bytes: &Bound<'_, pyo3::types::PyBytes>,
    name: String,
    expect_euler: Option<i64>,
    expect_parts: Option<u64>,
    claims: Option<(String, String)>,
    max_triangles: u64,
) -> PyResult<String> {
    // Copied before the thread detaches (a memcpy; extracting a Vec<u8> reads byte by byte).
    let bytes = bytes.as_bytes().to_vec();
    run(py, move || {
        let claims = match &claims {
            Some((text, path)) => Some(lacuna::meshcheck::Claims::parse(text, path)?),
            None => None,
        };
        let options = lacuna::meshcheck::Options {
            max_triangles,
            expect_euler,
            expect_parts,
            claims,
        };
        let report = lacuna::meshcheck::check(&bytes, &name, &options)?;
        Ok(json(&report.to_json()))
    })
}
