//! `lacuna._lacuna`: the native half of the Python package `lacuna`.
//!
//! Every function takes an input as the command line names it (face notation, a file path or a
//! library name), calls the public API of the lacuna library, and returns what the library
//! computed: its serde reports as JSON text (exact numbers stay strings: the Python half turns them
//! into `int` and `fractions.Fraction`), polygons as flat float arrays, files written to disk. A
//! lacuna [`Error`] becomes the Python exception `lacuna.LacunaError` (or the subclass its code
//! belongs to) with the same code, message and span. The heavy work runs with the Python thread
//! detached, so other Python threads go on meanwhile.
#![forbid(unsafe_code)]
#![warn(missing_docs)]

use lacuna::input::{load_any, load_input, Loaded};
use lacuna::topology::{Closure, Limits, TypeSet};
use lacuna::{Diagnostic, Error};
use num_rational::BigRational;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::io::Write;
use std::path::{Path, PathBuf};

mod commands;
mod design;
mod export;
mod family;
mod geometry;
mod operators;
mod volume;

/// A lacuna error as the Python exception the package defines (`lacuna._errors.from_native`
/// chooses the class from the code).
fn py_err(py: Python<'_>, e: Error) -> PyErr {
    let span = e.span().map(|s| (s.line, s.col, s.len));
    let made = py
        .import("lacuna._errors")
        .and_then(|m| m.getattr("from_native"))
        .and_then(|f| {
            f.call1((
                e.code(),
                pythonic(&e.to_string()),
                span,
                pythonic(&e.render()),
            ))
        });
    match made {
        Ok(exc) => PyErr::from_value(exc),
        Err(err) => err,
    }
}

/// The limits Python takes as `limits={...}` keys, by the command line's flag.
const LIMIT_KEYS: [&str; 9] = [
    "max-boundary",
    "max-types",
    "max-level",
    "max-subedges",
    "max-delay",
    "max-digits",
    "max-unknowns",
    "max-memory",
    "max-matrix",
];

/// A message as Python users raise its limits: the command line's `--max-level` is
/// `limits={'max_level': …}` (the keyword every method takes), `--max-cells` the keyword
/// `max_cells=…`, `--corners` (in the library's message for several faces) `corners=…`; other
/// text is unchanged.
fn pythonic(message: &str) -> String {
    let message = message
        .replace("--corners", "corners=…")
        .replace("--holes-level", "holes_level=…")
        .replace("--volume-levels", "volume_levels=…")
        .replace("--level (lower it)", "level=… (lower it)");
    let mut out = String::with_capacity(message.len());
    let mut rest = message.as_str();
    while let Some(at) = rest.find("--max-") {
        out.push_str(&rest[..at]);
        let tail = &rest[at + 2..];
        let end = tail
            .find(|c: char| !(c.is_ascii_lowercase() || c == '-'))
            .unwrap_or(tail.len());
        let name = &tail[..end];
        match name {
            n if LIMIT_KEYS.contains(&n) => {
                out.push_str(&format!("limits={{'{}': …}}", n.replace('-', "_")))
            }
            "max-cells" => out.push_str("max_cells=…"),
            "max-holes-cells" => out.push_str("max_holes_cells=…"),
            n => {
                out.push_str("--");
                out.push_str(n);
            }
        }
        rest = &tail[end..];
    }
    out.push_str(rest);
    out
}

/// Runs `work` with the Python thread detached and maps its error to a Python exception.
fn run<T: Send>(py: Python<'_>, work: impl FnOnce() -> Result<T, Error> + Send) -> PyResult<T> {
    py.detach(work).map_err(|e| py_err(py, e))
}

/// Reads the `limits=` keyword, then runs `work` on the limits with the Python thread detached
/// (the body of every function that takes `limits`).
fn run_limited<T: Send>(
    py: Python<'_>,
    overrides: Option<&Bound<'_, PyDict>>,
    work: impl FnOnce(Limits) -> Result<T, Error> + Send,
) -> PyResult<T> {
    let l = limits(overrides)?;
    run(py, move || work(l))
}

/// A coded error without a source span (the library's geometry and mesh errors carry a code and a
/// message of their own).
fn coded(code: &'static str, message: String) -> Error {
    Error::Syntax(Box::new(Diagnostic {
        code,
        message,
        span: None,
        source: None,
    }))
}

/// A geometry error as a lacuna error (same code and message).
fn geo_error(e: lacuna::geometry::GeometryError) -> Error {
    match e {
        lacuna::geometry::GeometryError::Lacuna(e) => e,
        other => coded(other.code(), other.to_string()),
    }
}

/// A mesh error as a lacuna error (same code and message).
fn mesh_error(e: lacuna::mesh::MeshError) -> Error {
    coded(e.code(), e.to_string())
}

/// A value outside the range a keyword accepts (E0503, as the command line's flags).
fn out_of_range(
    flag: &'static str,
    value: impl ToString,
    what: &'static str,
    range: &str,
) -> Error {
    Error::OutOfRange {
        flag,
        value: value.to_string(),
        what,
        range: range.into(),
    }
}

/// The limits: the library's defaults with the entries of `overrides` (the command line's flag
/// names without `--max-` and with `_`: `boundary`, `types`, `level`, …) set.
fn limits(overrides: Option<&Bound<'_, PyDict>>) -> PyResult<Limits> {
    let mut l = Limits::default();
    let Some(d) = overrides else {
        return Ok(l);
    };
    for (k, v) in d.iter() {
        let key: String = k.extract()?;
        let value: u64 = v.extract()?;
        let small = |v: u64| -> PyResult<usize> {
            usize::try_from(v).map_err(|_| {
                py_err(
                    k.py(),
                    Error::Usage(format!("limit {key} = {v} is too large")),
                )
            })
        };
        match key.as_str() {
            "max_boundary" => l.max_boundary = small(value)?,
            "max_types" => l.max_types = small(value)?,
            "max_level" => l.max_level = value,
            "max_subedges" | "max_delay" => {
                let v = u32::try_from(value).map_err(|_| {
                    py_err(k.py(), Error::Usage(format!("limit {key} = {value} is too large")))
                })?;
                if key == "max_subedges" {
                    l.max_subedges = v
                } else {
                    l.max_delay = v
                }
            }
            "max_digits" => l.max_digits = small(value)?,
            "max_unknowns" => l.max_unknowns = small(value)?,
            "max_memory" => l.max_memory_mb = value,
            "max_matrix" => l.max_matrix = small(value)?,
            _ => {
                return Err(py_err(
                    k.py(),
                    Error::Usage(format!(
                        "unknown limit `{key}`: the limits are max_boundary, max_types, max_level, max_subedges, max_delay, max_digits, max_unknowns, max_memory, max_matrix"
                    )),
                ))
            }
        }
    }
    Ok(l)
}

/// `NAME=VALUE` pairs as exact values (E1007 for a value that is not an exact number).
fn param_values(params: &[(String, String)]) -> Result<Vec<(String, BigRational)>, Error> {
    params
        .iter()
        .map(|(n, v)| {
            lacuna::input::parse_rational(v.trim())
                .map(|q| (n.trim().to_string(), q))
                .ok_or_else(|| {
                    let text = format!("{n}={v}");
                    Error::syntax(
                        "E1007",
                        format!("parameter `{text}`: expected NAME=VALUE with an exact value (1/7, 0.25)"),
                        lacuna::Span {
                            line: 1,
                            col: 1,
                            len: text.chars().count().max(1),
                        },
                        Some(&lacuna::Source::command_line(&text)),
                    )
                })
        })
        .collect()
}

/// The Cantor gap/piece of `solve` as an exact positive value (E0113 when it is not one).
fn cantor_gap(text: &str) -> Result<BigRational, Error> {
    lacuna::input::parse_rational(text.trim())
        .filter(|g| *g > BigRational::from_integer(0.into()))
        .ok_or_else(|| {
            Error::syntax(
                "E0113",
                format!("cantor_gap `{text}` must be an exact positive number (1, 1/2, 0.25)"),
                lacuna::Span {
                    line: 1,
                    col: 1,
                    len: text.chars().count().max(1),
                },
                Some(&lacuna::Source::command_line(text)),
            )
        })
}

/// The options of THEORY §6 as Python gives them: `cantor_gap` read as an exact positive number,
/// then `degree` checked to be from 1 to 8 (in that order, so the errors come as before).
fn gen_options(degree: usize, cantor_gap: &str) -> Result<lacuna::constraint::GenOptions, Error> {
    let gap = self::cantor_gap(cantor_gap)?;
    if !(1..=8).contains(&degree) {
        return Err(out_of_range(
            "degree",
            degree,
            "the Bézier degree",
            "from 1 to 8",
        ));
    }
    Ok(lacuna::constraint::GenOptions {
        degree,
        cantor_gap: gap,
    })
}

/// Pretty JSON of a report (the layout of the command line's `--json`).
fn json(v: &impl serde::Serialize) -> String {
    serde_json::to_string_pretty(v).expect("reports serialise")
}

/// What an input names, and its name: `("faces", name)`, `("automaton", name)` or
/// `("volume", name)` (one volume or several glued face to face). Parses it completely, so a bad input raises here.
#[pyfunction]
fn kind(py: Python<'_>, input: String) -> PyResult<(String, String)> {
    run(py, || {
        if let Some((name, _)) = lacuna::input::load_volume_file(&input)? {
            return Ok(("volume".to_string(), name));
        }
        Ok(match load_any(&input)? {
            Loaded::Faces(i) => ("faces".to_string(), i.name),
            Loaded::Automaton { name, .. } => ("automaton".to_string(), name),
        })
    })
}

/// The rule text an automaton was compiled from (a rule file or a library entry written as a
/// rule), `None` for a hand-written automaton; faces and volumes are refused.
#[pyfunction]
fn rule_text(py: Python<'_>, input: String) -> PyResult<Option<String>> {
    run(py, move || match load_any(&input)? {
        Loaded::Automaton { model, .. } => Ok(model.rule.clone()),
        Loaded::Faces(_) => Err(Error::Usage(format!("`{input}` is faces, not a rule"))),
    })
}

/// The start faces of faces (notation, a file or a library name): the canonical notation of
/// each, and the number of shared edges between them.
#[pyfunction]
fn start_faces(py: Python<'_>, input: String) -> PyResult<(Vec<String>, usize)> {
    run(py, move || {
        let input = load_input(&input)?;
        let faces = input
            .faces()
            .iter()
            .map(|f| f.canonical().0.to_string())
            .collect();
        Ok((faces, input.assembly.shared.len()))
    })
}

/// The canonical notation of one face (the least rotation of its boundary).
#[pyfunction]
fn canonical(py: Python<'_>, notation: String) -> PyResult<String> {
    run(py, || {
        Ok(lacuna::topology::Face::parse(&notation)?
            .canonical()
            .0
            .to_string())
    })
}

/// The library: `(name, text)` of every named structure.
#[pyfunction]
fn library() -> Vec<(String, String)> {
    lacuna::input::library()
        .iter()
        .map(|(n, t)| (n.to_string(), t.to_string()))
        .collect()
}

/// The faces `input` names and their closed set of types (E0502 when the closure runs away).
fn closed_faces(input: &str, l: &Limits) -> Result<(lacuna::input::Input, TypeSet), Error> {
    let input = load_input(input)?;
    let ts = lacuna::topology::close_or_error(&input.faces(), l)?;
    Ok((input, ts))
}

/// The closure as `lacuna closure --json` prints it (closed or runaway).
#[pyfunction]
#[pyo3(signature = (input, limits=None))]
fn closure(py: Python<'_>, input: String, limits: Option<&Bound<'_, PyDict>>) -> PyResult<String> {
    run_limited(py, limits, move |l| {
        let input = load_input(&input)?;
        let c = Closure::of(&input.faces(), &l)?;
        Ok(json(&lacuna::export::closure_json(&c)))
    })
}

/// Exact counts per level as `lacuna counts --json` prints them.
#[pyfunction]
#[pyo3(signature = (input, levels, limits=None))]
fn counts(
    py: Python<'_>,
    input: String,
    levels: u64,
    limits: Option<&Bound<'_, PyDict>>,
) -> PyResult<String> {
    run_limited(py, limits, move |l| {
        l.check_level(levels)?;
        let (input, ts) = closed_faces(&input, &l)?;
        Ok(json(&lacuna::export::counts_json(&ts, &input, levels)))
    })
}

/// The limit ratio as `lacuna ratio --json` prints it.
#[pyfunction]
#[pyo3(signature = (input, digits, limits=None))]
fn ratio(
    py: Python<'_>,
    input: String,
    digits: usize,
    limits: Option<&Bound<'_, PyDict>>,
) -> PyResult<String> {
    run_limited(py, limits, move |l| {
        l.check_digits(digits)?;
        let (_, ts) = closed_faces(&input, &l)?;
        Ok(json(&lacuna::export::ratio_of(&ts, digits)?))
    })
}

/// The exact constraint system's solution as `lacuna solve --json` prints it: of the closure of
/// faces, or of an automaton file (for an automaton whose entries lie in a number field, the
/// field verdict, with a `field` key).
#[pyfunction]
#[pyo3(signature = (input, degree=2, cantor_gap="1".to_string(), limits=None))]
fn solve(
    py: Python<'_>,
    input: String,
    degree: usize,
    cantor_gap: String,
    limits: Option<&Bound<'_, PyDict>>,
) -> PyResult<String> {
    run_limited(py, limits, move |l| {
        let opts = gen_options(degree, &cantor_gap)?;
        let report = match load_any(&input)? {
            Loaded::Automaton { model, .. } if !model.field_ops.is_empty() => {
                let r = lacuna::analysis::resolve(&model, &[], l.max_unknowns)?;
                return Ok(json(&r.verdict));
            }
            Loaded::Automaton { automaton, .. } => {
                automaton.check_solve_limits(&l)?;
                lacuna::constraint::solve_automaton(&automaton)?.0
            }
            Loaded::Faces(input) => {
                let ts = lacuna::topology::close_or_error(&input.faces(), &l)?;
                lacuna::constraint::solve_closure(&ts, opts, &l)?
            }
        };
        Ok(json(&report))
    })
}

/// The whole verification as `lacuna verify --json` prints it.
#[pyfunction]
#[pyo3(signature = (input, levels=5, limits=None))]
fn verify(
    py: Python<'_>,
    input: String,
    levels: u64,
    limits: Option<&Bound<'_, PyDict>>,
) -> PyResult<String> {
    run_limited(py, limits, move |l| {
        l.check_level(levels)?;
        let input = load_input(&input)?;
        let c = Closure::of(&input.faces(), &l)?;
        Ok(json(&lacuna::export::verify_report(
            &input, &c, levels, &l,
        )?))
    })
}

/// The certificate of every verdict (closure, solution space, limit ratio) as JSON text, the file
/// `lacuna verify --certificate` writes.
#[pyfunction]
#[pyo3(signature = (input, limits=None))]
fn certificate(
    py: Python<'_>,
    input: String,
    limits: Option<&Bound<'_, PyDict>>,
) -> PyResult<String> {
    run_limited(py, limits, move |l| {
        let (input, ts) = closed_faces(&input, &l)?;
        let cert = lacuna::certificate::certificate_for_assembly(
            &input.name,
            &ts,
            &input.assembly.canonical_glue(),
            lacuna::constraint::GenOptions::default(),
        )
        .map_err(|e| e.into_error("certificate"))?;
        Ok(cert.to_json())
    })
}

/// The certificate of an automaton or a rule as JSON text, the file `lacuna verify NAME
/// --certificate` writes: its constraints, the contraction of every walk and the similarity
/// dimension (with the open-set witness where convex sets or neighbour maps decide it).
#[pyfunction]
#[pyo3(signature = (input, limits=None))]
fn automaton_certificate(
    py: Python<'_>,
    input: String,
    limits: Option<&Bound<'_, PyDict>>,
) -> PyResult<String> {
    run_limited(py, limits, move |l| {
        let (name, model) = match load_any(&input)? {
            Loaded::Automaton { name, model, .. } => (name, model),
            Loaded::Faces(_) => {
                return Err(Error::Usage(format!("`{input}` is not an automaton")));
            }
        };
        l.check_unknowns(model.automaton.unknown_count())?;
        let cert =
            lacuna::certificate::certify_model(&name, &model, l.max_unknowns, l.max_products)
                .map_err(|e| e.into_error("certificate"))?;
        Ok(cert.to_json())
    })
}

/// The independent checker on a certificate's text: `(report JSON, all proved, partial)`.
#[pyfunction]
fn check_text(py: Python<'_>, text: String) -> (String, bool, bool) {
    py.detach(move || {
        let r = lacuna::checker::check_json(&text);
        (json(&r.to_json()), r.all_proved(), r.partial())
    })
}

/// Reads a text file as lacuna reads its inputs (UTF-8, a byte-order mark skipped; E0601, E0602).
#[pyfunction]
fn read_text(py: Python<'_>, path: String) -> PyResult<String> {
    run(py, move || lacuna::input::read_text(&path))
}
/// Writes a file whole: to a temporary file beside it, renamed over the target when complete
/// (E1005 when it cannot be written; nothing partial is left).
fn write_file(
    path: &Path,
    body: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> Result<(), Error> {
    let failed = |e: std::io::Error| Error::Write {
        path: path.display().to_string(),
        reason: e.to_string(),
    };
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let name = path
        .file_name()
        .map_or_else(|| "out".into(), |n| n.to_string_lossy().into_owned());
    let tmp = dir.join(format!(".{name}.{}.tmp", std::process::id()));
    let result = (|| {
        let mut f = std::io::BufWriter::new(std::fs::File::create(&tmp)?);
        body(&mut f)?;
        f.flush()?;
        f.into_inner().map_err(|e| e.into_error())?.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result.map_err(failed)
}

/// Refuses (E0504, as the command line) an output that is the input file, or two outputs to one
/// file.
fn refuse_clobbering(input: &str, outputs: &[&Option<PathBuf>]) -> Result<(), Error> {
    // A path names the same file as another when both resolve to it (an output that does not
    // exist yet resolves through its folder).
    let resolve = |p: &Path| -> PathBuf {
        if let Ok(c) = p.canonicalize() {
            return c;
        }
        match (p.parent(), p.file_name()) {
            (Some(d), Some(n)) if !d.as_os_str().is_empty() => d
                .canonicalize()
                .map_or_else(|_| p.to_path_buf(), |d| d.join(n)),
            (_, Some(n)) => std::env::current_dir().map_or_else(|_| p.to_path_buf(), |d| d.join(n)),
            _ => p.to_path_buf(),
        }
    };
    let input = Path::new(input);
    let input = input.is_file().then(|| resolve(input));
    let mut seen: Vec<PathBuf> = Vec::new();
    for p in outputs.iter().filter_map(|p| p.as_deref()) {
        let r = resolve(p);
        if input.as_ref() == Some(&r) {
            return Err(Error::Usage(format!(
                "`{}` is the input: an output never overwrites it",
                p.display()
            )));
        }
        if seen.contains(&r) {
            return Err(Error::Usage(format!(
                "two outputs would write `{}`",
                p.display()
            )));
        }
        seen.push(r);
    }
    Ok(())
}
/// The native module.
#[pymodule]
fn _lacuna(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_function(wrap_pyfunction!(kind, m)?)?;
    m.add_function(wrap_pyfunction!(rule_text, m)?)?;
    m.add_function(wrap_pyfunction!(canonical, m)?)?;
    m.add_function(wrap_pyfunction!(start_faces, m)?)?;
    m.add_function(wrap_pyfunction!(library, m)?)?;
    m.add_function(wrap_pyfunction!(closure, m)?)?;
    m.add_function(wrap_pyfunction!(counts, m)?)?;
    m.add_function(wrap_pyfunction!(ratio, m)?)?;
    m.add_function(wrap_pyfunction!(solve, m)?)?;
    m.add_function(wrap_pyfunction!(verify, m)?)?;
    m.add_function(wrap_pyfunction!(certificate, m)?)?;
    m.add_function(wrap_pyfunction!(automaton_certificate, m)?)?;
    m.add_function(wrap_pyfunction!(check_text, m)?)?;
    m.add_function(wrap_pyfunction!(read_text, m)?)?;
    m.add_function(wrap_pyfunction!(geometry::polygons, m)?)?;
    m.add_function(wrap_pyfunction!(geometry::automaton_shapes, m)?)?;
    m.add_function(wrap_pyfunction!(geometry::render, m)?)?;
    m.add_function(wrap_pyfunction!(geometry::measure, m)?)?;
    m.add_function(wrap_pyfunction!(geometry::decode_png, m)?)?;
    m.add_function(wrap_pyfunction!(operators::operators, m)?)?;
    m.add_function(wrap_pyfunction!(design::design, m)?)?;
    m.add_function(wrap_pyfunction!(commands::report, m)?)?;
    m.add_function(wrap_pyfunction!(commands::classify, m)?)?;
    m.add_function(wrap_pyfunction!(commands::morph, m)?)?;
    m.add_function(wrap_pyfunction!(export::export, m)?)?;
    m.add_function(wrap_pyfunction!(family::explore_shard, m)?)?;
    m.add_function(wrap_pyfunction!(family::census, m)?)?;
    m.add_function(wrap_pyfunction!(family::check_mesh, m)?)?;
    m.add_function(wrap_pyfunction!(volume::volume_closure, m)?)?;
    m.add_function(wrap_pyfunction!(volume::volume_counts_json, m)?)?;
    m.add_function(wrap_pyfunction!(volume::volume_ratio, m)?)?;
    m.add_function(wrap_pyfunction!(volume::volume_solve, m)?)?;
    m.add_function(wrap_pyfunction!(volume::volume_verify, m)?)?;
    m.add_function(wrap_pyfunction!(volume::volume_certificate, m)?)?;
    m.add_function(wrap_pyfunction!(volume::volume_render, m)?)?;
    m.add_function(wrap_pyfunction!(volume::volume_measure, m)?)?;
    Ok(())
}
