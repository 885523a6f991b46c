//! `lacuna report`, `lacuna classify` and `lacuna morph` from Python: the library functions the
//! command line calls, their pages, comparisons and frames returned to the Python half.

use crate::geometry::geo;
use crate::{json, out_of_range, param_values, refuse_clobbering, run, run_limited, write_file};
use lacuna::input::{load_any, load_input, Loaded};
use lacuna::Error;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;

/// `lacuna report INPUT --out PATH`: the HTML page of faces, an automaton or volumes and its
/// verdict, the page written to `path` too when given (never over the input). A closure that does
/// not close is a page that says so (not verified), as on the command line.
#[pyfunction]
#[pyo3(signature = (input, level=3, path=None, params=Vec::new(), raster=2048, segments=4, max_cells=None, limits=None, corners=None, template=None, goals=Vec::new()))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn report(
    py: Python<'_>,
    input: String,
    level: u32,
    path: Option<PathBuf>,
    params: Vec<(String, String)>,
    raster: usize,
    segments: usize,
    max_cells: Option<u64>,
    limits: Option<&Bound<'_, PyDict>>,
    corners: Option<String>,
    template: Option<PathBuf>,
    goals: Vec<String>,
) -> PyResult<(String, bool)> {
    let g =
        geo(input, level, params, segments, max_cells, limits)?.choosing(corners, template, goals);
    run(py, move || {
        if !(16..=8192).contains(&raster) || !raster.is_power_of_two() {
            return Err(out_of_range(
                "raster",
                raster,
                "the raster size",
                "a power of two from 16 to 8192",
            ));
        }
        refuse_clobbering(&g.input, &[&path])?;
        if let Some(t) = g.template.as_ref().and_then(|t| t.to_str()) {
            refuse_clobbering(t, &[&path])?;
        }
        let page = if let Some((name, v)) = lacuna::input::load_volume_file(&g.input)? {
            g.faces_only("a volume is placed on its solid or on the corners its file gives")?;
            if !g.params.is_empty() {
                return Err(Error::Usage(
                    "params apply to faces and automata; a volume is placed on its solid or on the corners its file gives".into(),
                ));
            }
            lacuna::export::volume_report_page(&name, &v, g.level, g.max_cells, &g.limits)?
        } else if let Loaded::Automaton { .. } = load_any(&g.input)? {
            let (model, resolved, contraction, ev, name) = g.automaton(100_000)?;
            lacuna::export::automaton_report_page(
                &g.input,
                &name,
                &model,
                &resolved,
                &contraction,
                &ev,
                g.level,
                &g.limits,
            )?
        } else {
            // The pictures embed every cell of every level as SVG: keep them small.
            let (input, inst) = match g.instance(200_000) {
                Err(Error::Runaway { .. }) => (load_input(&g.input)?, None),
                other => (load_input(&g.input)?, Some(other?)),
            };
            lacuna::export::faces_report_page(
                &input,
                inst.as_ref(),
                g.level,
                raster,
                g.segments,
                &g.limits,
            )?
        };
        if let Some(p) = &path {
            write_file(p, |w| w.write_all(page.html.as_bytes()))?;
        }
        Ok((page.html, page.verified))
    })
}

/// `lacuna classify A B --json`: the comparison of the invariants of two inputs, as the command
/// line prints it, with its text under `text`.
#[pyfunction]
#[pyo3(signature = (a, b, levels=4, volume_levels=2, max_cells=200_000, multiplicity="coincidences".to_string(), limits=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn classify(
    py: Python<'_>,
    a: String,
    b: String,
    levels: u64,
    volume_levels: u64,
    max_cells: u64,
    multiplicity: String,
    limits: Option<&Bound<'_, PyDict>>,
) -> PyResult<String> {
    run_limited(py, limits, move |l| {
        let multiplicity = match multiplicity.as_str() {
            "contacts" => lacuna::analysis::AutomatonMultiplicity::Contacts,
            "coincidences" => lacuna::analysis::AutomatonMultiplicity::Coincidences,
            other => {
                return Err(Error::Usage(format!(
                    "multiplicity `{other}`: the multiplicities are 'contacts' and 'coincidences'"
                )))
            }
        };
        let opts = lacuna::export::ClassifyOptions {
            levels,
            volume_levels,
            max_cells,
            multiplicity,
        };
        let outcome = lacuna::export::classify_inputs(&a, &b, &opts, &l)?;
        let mut v = outcome.to_json();
        v["kinds"] = serde_json::json!({"a": outcome.a.kind, "b": outcome.b.kind});
        v["text"] = outcome.to_text().into();
        Ok(json(&v))
    })
}

/// One frame as the Python half reads it: the type (or state) of every cell, the offsets of
/// its points in the flat coordinates (x, y interleaved) and whether it is a closed polygon.
type Frame = (Vec<usize>, Vec<usize>, Vec<f64>, Vec<bool>);

/// A parameter choice of faces: the template file when given, else the exact values (none: the
/// default fit).
fn choice(
    template: Option<&str>,
    values: &[(String, String)],
    limits: &lacuna::topology::Limits,
) -> Result<lacuna::geometry::InstantiateOptions, Error> {
    let mut opts = lacuna::geometry::InstantiateOptions {
        limits: limits.clone(),
        ..Default::default()
    };
    match template {
        Some(path) => {
            opts.template = Some(lacuna::Source {
                name: path.to_string(),
                text: lacuna::input::read_text(path)?,
            })
        }
        None => opts.values = param_values(values)?,
    }
    Ok(opts)
}

/// `lacuna morph A B [--on INPUT]`: with `on`, A and B are parameter choices of those faces (a
/// template file, else the exact values, none for the default fit); without, A and B are two
/// automata of one shape. Returns the report (JSON), every frame's cells and the files written:
/// the animated SVG to `svg` and one PNG per frame to `png` (a pattern whose `{}` becomes the
/// frame number), when given.
#[pyfunction]
#[pyo3(signature = (a=None, b=None, a_params=Vec::new(), b_params=Vec::new(), on=None, frames=9, level=2, size=512, seconds=0.5, svg=None, png=None, max_cells=200_000, limits=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn morph(
    py: Python<'_>,
    a: Option<String>,
    b: Option<String>,
    a_params: Vec<(String, String)>,
    b_params: Vec<(String, String)>,
    on: Option<String>,
    frames: u32,
    level: u32,
    size: u32,
    seconds: f64,
    svg: Option<PathBuf>,
    png: Option<String>,
    max_cells: u64,
    limits: Option<&Bound<'_, PyDict>>,
) -> PyResult<(String, Vec<Frame>, Vec<PathBuf>)> {
    run_limited(py, limits, move |l| {
        if !(2..=1000).contains(&frames) {
            return Err(out_of_range(
                "frames",
                frames,
                "the number of frames",
                "from 2 to 1000",
            ));
        }
        if !(16..=8192).contains(&size) {
            return Err(out_of_range(
                "size",
                size,
                "the frame size in pixels",
                "from 16 to 8192",
            ));
        }
        if !(seconds.is_finite() && seconds > 0.0 && seconds <= 60.0) {
            return Err(out_of_range(
                "seconds",
                seconds,
                "the seconds per frame",
                "above 0 and at most 60",
            ));
        }
        l.check_level(u64::from(level))?;
        let pngs = match &png {
            Some(p) => lacuna::export::morph_png_paths(p, frames, "png")?,
            None => Vec::new(),
        };
        let outputs: Vec<Option<PathBuf>> = std::iter::once(svg.clone())
            .chain(pngs.iter().cloned().map(Some))
            .collect();
        let outputs: Vec<&Option<PathBuf>> = outputs.iter().collect();
        for i in on.iter().chain(&a).chain(&b) {
            refuse_clobbering(i, &outputs)?;
        }
        let (report, drawn) = match &on {
            Some(on) => {
                let input = load_input(on)?;
                let ca = choice(a.as_deref(), &a_params, &l)?;
                let cb = choice(b.as_deref(), &b_params, &l)?;
                lacuna::export::morph_faces(
                    &input,
                    &ca,
                    &cb,
                    frames,
                    level,
                    size,
                    max_cells,
                    &l,
                    |k, inst| {
                        if let Some(p) = pngs.get(k as usize) {
                            write_file(p, |w| {
                                lacuna::export::write_morph_png(inst, level, size, w)
                            })?;
                        }
                        Ok(())
                    },
                )
                .map_err(|e| e.into_error())?
            }
            None => {
                let automaton = |s: &Option<String>| -> Result<_, Error> {
                    let s = s.as_deref().unwrap_or_default();
                    match load_any(s)? {
                        Loaded::Automaton { model, .. } => Ok(*model),
                        Loaded::Faces(_) => Err(Error::Usage(format!(
                            "`{s}` is faces: morph faces between two parameter choices with on=…"
                        ))),
                    }
                };
                let (ma, mb) = (automaton(&a)?, automaton(&b)?);
                let name = format!(
                    "{} → {}",
                    a.as_deref().unwrap_or_default(),
                    b.as_deref().unwrap_or_default()
                );
                lacuna::export::morph_automata(&name, &ma, &mb, frames, level, &l, |k, ev| {
                    if let Some(p) = pngs.get(k as usize) {
                        write_file(p, |w| {
                            lacuna::export::write_morph_automaton_png(ev, level, size, w)
                        })?;
                    }
                    Ok(())
                })?
            }
        };
        if let Some(p) = &svg {
            write_file(p, |w| {
                lacuna::export::write_morph_svg(&report.name, &drawn, size, seconds, w)
            })?;
        }
        let written = svg.into_iter().chain(pngs).collect();
        let cells = drawn
            .iter()
            .map(|(cells, _)| {
                let (mut types, mut offsets, mut xy, mut closed) =
                    (Vec::new(), vec![0usize], Vec::new(), Vec::new());
                for (ty, poly, c) in cells {
                    types.push(*ty);
                    xy.extend(poly.iter().flat_map(|p| [p[0], p[1]]));
                    offsets.push(offsets.last().copied().unwrap_or(0) + poly.len());
                    closed.push(*c);
                }
                (types, offsets, xy, closed)
            })
            .collect();
        Ok((json(&report), cells, written))
    })
}
