//! Geometry from Python: the instance of faces (or an automaton) at chosen parameters, its
//! polygons and an automaton's shapes, the pictures and solids `render` writes, the measures of
//! `measure`, and the pixels of a PNG the library wrote.

use crate::{
    geo_error, json, limits, mesh_error, out_of_range, param_values, refuse_clobbering, run,
    write_file,
};
use lacuna::input::{load_any, load_input, Loaded};
use lacuna::topology::Limits;
use lacuna::Error;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;

/// Geometry options shared by `polygons`, `render`, `measure` and `report`.
pub(crate) struct Geo {
    pub(crate) input: String,
    pub(crate) level: u32,
    pub(crate) params: Vec<(String, String)>,
    pub(crate) segments: usize,
    pub(crate) max_cells: Option<u64>,
    pub(crate) limits: Limits,
    /// The corners of a single face, as the command line's `--corners` reads them.
    pub(crate) corners: Option<String>,
    /// A template file to project instead of the default fit (`--template`).
    pub(crate) template: Option<PathBuf>,
    /// Inequality goals, as the command line's `--goal` reads them.
    pub(crate) goals: Vec<String>,
    /// The state of an automaton whose attractor is drawn (`render --state`; `None`: the start).
    pub(crate) state: Option<String>,
}

impl Geo {
    /// The instance of the faces with the parameters given (the command line's `instance`).
    pub(crate) fn instance(&self, default_cells: u64) -> Result<lacuna::geometry::Instance, Error> {
        self.limits.check_level(u64::from(self.level))?;
        if !(1..=64).contains(&self.segments) {
            return Err(out_of_range(
                "segments",
                self.segments,
                "the segments per Bézier edge",
                "from 1 to 64",
            ));
        }
        let mut input = load_input(&self.input)?;
        if let Some(c) = &self.corners {
            lacuna::input::set_corners(&mut input.assembly, c)?;
        }
        let mut opts = lacuna::geometry::InstantiateOptions {
            limits: self.limits.clone(),
            ..Default::default()
        };
        opts.degree = input.assembly.coords.degree().unwrap_or(opts.degree);
        opts.values = param_values(&self.params)?;
        opts.choose(self.template.as_deref(), &self.goals, "goal")?;
        let inst = lacuna::geometry::instantiate(&input, &opts).map_err(geo_error)?;
        lacuna::measure::check_cells(&inst, self.level, self.max_cells.unwrap_or(default_cells))
            .map_err(geo_error)?;
        Ok(inst)
    }

    /// Refuses `corners`, `template` and `goal` (E0504) for an input that is not faces, saying
    /// `instead` what that input takes.
    pub(crate) fn faces_only(&self, instead: &str) -> Result<(), Error> {
        if self.corners.is_some() || self.template.is_some() || !self.goals.is_empty() {
            return Err(Error::Usage(format!(
                "corners, template and goal apply to faces; {instead}"
            )));
        }
        Ok(())
    }

    /// Refuses `state` (E0504) for faces, telling to `verb` (draw, measure) them without it.
    pub(crate) fn no_state(&self, verb: &str) -> Result<(), Error> {
        match &self.state {
            Some(state) => Err(Error::Usage(format!(
                "state `{state}` names a state of an automaton, but faces have no states: {verb} them without state"
            ))),
            None => Ok(()),
        }
    }

    /// The same geometry with the parameter choice of faces beyond `params`: `corners`,
    /// `template` and `goals`, read when the instance is built.
    pub(crate) fn choosing(
        self,
        corners: Option<String>,
        template: Option<PathBuf>,
        goals: Vec<String>,
    ) -> Self {
        Geo {
            corners,
            template,
            goals,
            ..self
        }
    }

    /// The automaton's model, resolved, contraction checked, ready to draw.
    pub(crate) fn automaton(
        &self,
        default_cells: u64,
    ) -> Result<
        (
            lacuna::input::AutomatonModel,
            lacuna::analysis::Resolved,
            lacuna::analysis::ContractionReport,
            lacuna::geometry::Evaluator,
            String,
        ),
        Error,
    > {
        self.limits.check_level(u64::from(self.level))?;
        self.faces_only(
            "an automaton takes its control points from its `points` line and its parameters from `param` lines and params",
        )?;
        let (name, model) = match load_any(&self.input)? {
            Loaded::Automaton { name, model, .. } => (name, *model),
            Loaded::Faces(_) => {
                return Err(Error::Usage(format!(
                    "`{}` is faces, not an automaton",
                    self.input
                )))
            }
        };
        let (resolved, contraction, ev) = lacuna::geometry::prepare_automaton_at(
            &model,
            self.state.as_deref(),
            &param_values(&self.params)?,
            self.level,
            self.max_cells.unwrap_or(default_cells),
            &self.limits,
        )?;
        Ok((model, resolved, contraction, ev, name))
    }
}

/// Reads the geometry keywords.
#[allow(clippy::too_many_arguments)]
pub(crate) fn geo(
    input: String,
    level: u32,
    params: Vec<(String, String)>,
    segments: usize,
    max_cells: Option<u64>,
    limits: Option<&Bound<'_, PyDict>>,
) -> PyResult<Geo> {
    Ok(Geo {
        input,
        level,
        params,
        segments,
        max_cells,
        limits: self::limits(limits)?,
        corners: None,
        template: None,
        goals: Vec::new(),
        state: None,
    })
}

/// Polygons of the level: `(types, offsets, coordinates)`: cell `i` has type `types[i]` and the
/// points `offsets[i]..offsets[i+1]` of `coordinates` (x, y interleaved), full `f64` precision.
#[pyfunction]
#[pyo3(signature = (input, level, params=Vec::new(), segments=4, max_cells=None, limits=None, corners=None, template=None, goals=Vec::new()))]
#[allow(clippy::type_complexity, clippy::too_many_arguments)]
pub(crate) fn polygons(
    py: Python<'_>,
    input: String,
    level: u32,
    params: Vec<(String, String)>,
    segments: usize,
    max_cells: Option<u64>,
    limits: Option<&Bound<'_, PyDict>>,
    corners: Option<String>,
    template: Option<PathBuf>,
    goals: Vec<String>,
) -> PyResult<(Vec<usize>, Vec<usize>, Vec<f64>)> {
    let g =
        geo(input, level, params, segments, max_cells, limits)?.choosing(corners, template, goals);
    run(py, move || {
        let inst = g.instance(2_000_000)?;
        let (mut types, mut offsets, mut xy) = (Vec::new(), vec![0usize], Vec::new());
        inst.walk(g.level, false, |c| {
            let poly = inst.cell_polygon(c.ty, c.points, g.segments);
            types.push(c.ty);
            for p in &poly {
                xy.push(p[0]);
                xy.push(p[1]);
            }
            offsets.push(offsets.last().copied().unwrap_or(0) + poly.len());
        });
        Ok((types, offsets, xy))
    })
}

/// The shapes of an automaton's attractor at the level, as JSON (the `--json-out` file of
/// `lacuna render` on an automaton), with the state names and whether the constraints hold.
#[pyfunction]
#[pyo3(signature = (input, level, params=Vec::new(), max_cells=None, limits=None, state=None))]
pub(crate) fn automaton_shapes(
    py: Python<'_>,
    input: String,
    level: u32,
    params: Vec<(String, String)>,
    max_cells: Option<u64>,
    limits: Option<&Bound<'_, PyDict>>,
    state: Option<String>,
) -> PyResult<(String, Vec<String>, bool)> {
    let g = Geo {
        state,
        ..geo(input, level, params, 4, max_cells, limits)?
    };
    run(py, move || {
        let (_, resolved, _, ev, _) = g.automaton(2_000_000)?;
        let mut buf = Vec::new();
        lacuna::export::write_automaton_json(&ev, g.level, &mut buf).map_err(|e| Error::Write {
            path: "<memory>".into(),
            reason: e.to_string(),
        })?;
        Ok((
            String::from_utf8_lossy(&buf).into_owned(),
            ev.names.clone(),
            resolved.verdict.consistent,
        ))
    })
}

/// Writes the pictures and solids of the level of faces or of an automaton: SVG, PNG (`size`
/// pixels wide), binary or ASCII STL (faces only; the solid is built and checked against the
/// exact topology first). Returns the paths written. `state` draws that state of an automaton
/// instead of its start state (`render --state`).
#[pyfunction]
#[pyo3(signature = (input, level, params=Vec::new(), svg=None, png=None, stl=None, stl_ascii=false, size=1024, legend=true, transparent=false, width=None, thickness=None, segments=4, max_cells=None, limits=None, corners=None, template=None, goals=Vec::new(), state=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn render(
    py: Python<'_>,
    input: String,
    level: u32,
    params: Vec<(String, String)>,
    svg: Option<PathBuf>,
    png: Option<PathBuf>,
    stl: Option<PathBuf>,
    stl_ascii: bool,
    size: usize,
    legend: bool,
    transparent: bool,
    width: Option<f64>,
    thickness: Option<f64>,
    segments: usize,
    max_cells: Option<u64>,
    limits: Option<&Bound<'_, PyDict>>,
    corners: Option<String>,
    template: Option<PathBuf>,
    goals: Vec<String>,
    state: Option<String>,
) -> PyResult<Vec<PathBuf>> {
    let g = Geo {
        state,
        ..geo(input, level, params, segments, max_cells, limits)?.choosing(corners, template, goals)
    };
    run(py, move || {
        if svg.is_none() && png.is_none() && stl.is_none() {
            return Err(Error::Usage(
                "nothing to write: give svg, png or stl".into(),
            ));
        }
        if !(1..=8192).contains(&size) {
            return Err(out_of_range(
                "size",
                size,
                "the PNG size in pixels",
                "from 1 to 8192",
            ));
        }
        refuse_clobbering(&g.input, &[&svg, &png, &stl])?;
        if let Some(t) = g.template.as_ref().and_then(|t| t.to_str()) {
            refuse_clobbering(t, &[&svg, &png, &stl])?;
        }
        let mut wrote = Vec::new();
        if let Loaded::Automaton { .. } = load_any(&g.input)? {
            if stl.is_some() {
                return Err(Error::Usage(
                    "stl applies to faces; an automaton is written as svg or png".into(),
                ));
            }
            let vector = svg.is_some();
            let (_, _, _, ev, _) = g.automaton(if vector { 2_000_000 } else { 20_000_000 })?;
            if let Some(p) = &svg {
                write_file(p, |w| lacuna::export::write_automaton_svg(&ev, g.level, w))?;
                wrote.push(p.clone());
            }
            if let Some(p) = &png {
                let background = match transparent {
                    true => lacuna::export::Background::Transparent,
                    false => lacuna::export::Background::White,
                };
                write_file(p, |w| {
                    lacuna::export::write_automaton_png(
                        &ev,
                        g.level,
                        size as u32,
                        background,
                        legend,
                        w,
                    )
                })?;
                wrote.push(p.clone());
            }
            return Ok(wrote);
        }
        g.no_state("draw")?;
        let vector = svg.is_some() || stl.is_some();
        let inst = g.instance(if vector { 2_000_000 } else { 100_000_000 })?;
        let picture = lacuna::export::PictureOptions {
            width: size as u32,
            background: if transparent {
                lacuna::export::Background::Transparent
            } else {
                lacuna::export::Background::White
            },
            legend,
            ..Default::default()
        };
        if let Some(p) = &svg {
            let opts = lacuna::export::PictureOptions {
                width: 512,
                ..picture.clone()
            };
            write_file(p, |w| {
                lacuna::export::write_svg_picture(&inst, g.level, &opts, w)
            })?;
            wrote.push(p.clone());
        }
        if let Some(p) = &stl {
            let size = lacuna::mesh::Size {
                width: width.unwrap_or(lacuna::mesh::DEFAULT_WIDTH),
                thickness: thickness.unwrap_or(2.0),
            };
            lacuna::mesh::check_size("--width", size.width).map_err(mesh_error)?;
            lacuna::mesh::check_size("--thickness", size.thickness).map_err(mesh_error)?;
            let solid =
                lacuna::mesh::build(&inst, g.level, g.segments, size).map_err(mesh_error)?;
            write_file(p, |w| match stl_ascii {
                true => lacuna::mesh::stl::write_ascii(&solid, w),
                false => lacuna::mesh::stl::write_binary(&solid, w),
            })?;
            wrote.push(p.clone());
        }
        if let Some(p) = &png {
            write_file(p, |w| {
                lacuna::export::write_png_picture(&inst, g.level, &picture, w)
            })?;
            wrote.push(p.clone());
        }
        Ok(wrote)
    })
}

/// The measures of the level as `lacuna measure --json` prints them: of faces (with the
/// printability at the level), or of an automaton's attractor.
#[pyfunction]
#[pyo3(signature = (input, level, params=Vec::new(), raster=2048, max_raster=8192, digits=30, width=None, resolution=None, segments=4, max_cells=None, limits=None, corners=None, template=None, goals=Vec::new(), state=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn measure(
    py: Python<'_>,
    input: String,
    level: u32,
    params: Vec<(String, String)>,
    raster: usize,
    max_raster: usize,
    digits: usize,
    width: Option<f64>,
    resolution: Option<f64>,
    segments: usize,
    max_cells: Option<u64>,
    limits: Option<&Bound<'_, PyDict>>,
    corners: Option<String>,
    template: Option<PathBuf>,
    goals: Vec<String>,
    state: Option<String>,
) -> PyResult<String> {
    let g = Geo {
        state,
        ..geo(input, level, params, segments, max_cells, limits)?.choosing(corners, template, goals)
    };
    run(py, move || {
        let largest = lacuna::measure::LARGEST_RASTER;
        for (flag, r) in [("raster", raster), ("max_raster", max_raster)] {
            if !(16..=largest).contains(&r) || !r.is_power_of_two() {
                return Err(out_of_range(
                    flag,
                    r,
                    "the raster size",
                    &format!("a power of two from 16 to {largest}"),
                ));
            }
        }
        if max_raster < raster {
            return Err(out_of_range(
                "max_raster",
                max_raster,
                "the finest raster",
                &format!("at least raster ({raster})"),
            ));
        }
        if let Loaded::Automaton { .. } = load_any(&g.input)? {
            if digits == 0 {
                return Err(out_of_range(
                    "digits",
                    0,
                    "the certified digits of the similarity dimension",
                    &format!("from 1 to {}", g.limits.max_digits),
                ));
            }
            g.limits.check_digits(digits)?;
            let (model, resolved, contraction, ev, name) = g.automaton(2_000_000)?;
            // Another state: measured as the automaton restarted there (`measure --state`).
            let restarted = lacuna::geometry::evaluated_model(&model, &resolved, &ev);
            let mut m = lacuna::measure::automaton_measure(
                &name,
                restarted.as_ref().unwrap_or(&model),
                &resolved,
                &contraction,
                &ev,
                g.level,
                digits,
            );
            m.state = restarted.map(|r| r.automaton.states[r.start].name.clone());
            return Ok(json(&m));
        }
        g.no_state("measure")?;
        let inst = g.instance(20_000_000)?;
        let opts = lacuna::measure::MeasureOptions {
            level: g.level,
            raster,
            max_raster,
            segments: g.segments,
            ..Default::default()
        };
        let mut r = lacuna::measure::measure(&inst, &opts).map_err(geo_error)?;
        // As `lacuna measure --json`: which certificate step proves the exact counts.
        r.certification = lacuna::measure::certification(&inst);
        let size = lacuna::mesh::Size {
            width: width.unwrap_or(lacuna::mesh::DEFAULT_WIDTH),
            ..Default::default()
        };
        let resolution = resolution.unwrap_or(lacuna::mesh::DEFAULT_RESOLUTION);
        lacuna::mesh::check_size("--width", size.width).map_err(mesh_error)?;
        lacuna::mesh::check_size("--resolution", resolution).map_err(mesh_error)?;
        let p = lacuna::mesh::printability(&inst, g.level, g.segments, size, resolution)
            .map_err(mesh_error)?;
        Ok(json(&lacuna::mesh::printability::WithPrintability {
            report: &r,
            printability: &lacuna::mesh::printability::PrintReport::of_plate(
                &p,
                lacuna::mesh::DEFAULT_BED,
            ),
        }))
    })
}

/// The pixels of a PNG (8-bit RGB or RGBA, as the library writes them): `(height, width, RGBA
/// bytes row by row)`, RGB widened with an opaque alpha.
#[pyfunction]
pub(crate) fn decode_png(
    py: Python<'_>,
    data: &Bound<'_, pyo3::types::PyBytes>,
) -> PyResult<(u32, u32, std::borrow::Cow<'static, [u8]>)> {
    // Copied before the thread detaches (a memcpy; extracting a Vec<u8> reads byte by byte).
    let data = data.as_bytes().to_vec();
    run(py, move || {
        let bad = |e: String| Error::Usage(format!("not a PNG lacuna reads: {e}"));
        let mut reader = png::Decoder::new(std::io::Cursor::new(data))
            .read_info()
            .map_err(|e| bad(e.to_string()))?;
        let size = reader
            .output_buffer_size()
            .ok_or_else(|| bad("too large".into()))?;
        let mut buf = vec![0; size];
        let info = reader
            .next_frame(&mut buf)
            .map_err(|e| bad(e.to_string()))?;
        buf.truncate(info.buffer_size());
        let rgba = match (info.color_type, info.bit_depth) {
            (png::ColorType::Rgba, png::BitDepth::Eight) => buf,
            (png::ColorType::Rgb, png::BitDepth::Eight) => buf
                .chunks(3)
                .flat_map(|p| [p[0], p[1], p[2], 255])
                .collect(),
            (c, d) => return Err(bad(format!("{c:?} at {d:?}"))),
        };
        Ok((info.height, info.width, std::borrow::Cow::Owned(rgba)))
    })
}
