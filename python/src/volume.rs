//! Volumes and volume assemblies (THEORY §10) from Python: the command line's `closure`,
//! `counts`, `ratio`, `solve`, `verify`, `render` and `measure` of a volume, each as one function
//! that takes the input as the command line names it (volume notation, a volume file or a
//! library name) and returns the same JSON as `--json`, or writes the same files.
//!
//! The volume work is the command line's (`src/cli/volume.rs`), called through the library's
//! public API with the same checks in the same order, so an input gets the same code and message
//! from Python as from the command line.

use crate::{
    json, limits, mesh_error, out_of_range, refuse_clobbering, run, run_limited, write_file,
};
use lacuna::input::VolumeFile;
use lacuna::topology::volume::{solid_topology_of, volume_counts, VolumeClosure, VolumeTypeSet};
use lacuna::topology::Limits;
use lacuna::Error;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;

/// The volume file `input` names (E0504 when it names faces or an automaton).
fn load(input: &str) -> Result<(String, VolumeFile), Error> {
    lacuna::input::load_volume_file(input)?
        .ok_or_else(|| Error::Usage(format!("`{input}` is not a volume")))
}

/// The closed set of the volumes, or the runaway as the command line's error (E0504).
fn closed(v: &VolumeFile, limits: &Limits) -> Result<VolumeTypeSet, Error> {
    match VolumeClosure::of(&v.assembly.volumes, limits)? {
        VolumeClosure::Closed(set) => Ok(set),
        VolumeClosure::Runaway(r) => Err(Error::Usage(format!(
            "the volume's closure did not close: {} (see `closure()`)",
            r.reason
        ))),
    }
}

/// The volume file `input` names and the closed set of its volumes, with `check` (a keyword's
/// range) between the two, in the command line's order.
fn load_closed(
    input: &str,
    limits: &Limits,
    check: impl FnOnce() -> Result<(), Error>,
) -> Result<(String, VolumeFile, VolumeTypeSet), Error> {
    let (name, v) = load(input)?;
    check()?;
    let set = closed(&v, limits)?;
    Ok((name, v, set))
}

/// The closure of volume types as `lacuna closure --json` prints it (closed or runaway).
#[pyfunction]
#[pyo3(signature = (input, limits=None))]
pub(crate) fn volume_closure(
    py: Python<'_>,
    input: String,
    limits: Option<&Bound<'_, PyDict>>,
) -> PyResult<String> {
    run_limited(py, limits, move |l| {
        let (name, v) = load(&input)?;
        let c = VolumeClosure::of(&v.assembly.volumes, &l)?;
        Ok(json(&lacuna::export::volume_closure_json(&name, &c)))
    })
}

/// Exact counts (cells, lacunas, R_i) and the level-n solid's topology per level, as
/// `lacuna counts --json` prints them for a volume.
#[pyfunction]
#[pyo3(signature = (input, levels, limits=None))]
pub(crate) fn volume_counts_json(
    py: Python<'_>,
    input: String,
    levels: u64,
    limits: Option<&Bound<'_, PyDict>>,
) -> PyResult<String> {
    run_limited(py, limits, move |l| {
        let (name, v, set) = load_closed(&input, &l, || l.check_level(levels))?;
        let c = volume_counts(&set, levels);
        let solid = solid_topology_of(&set, levels, &v.assembly.start_cells())?;
        Ok(json(&serde_json::json!({
            "input": name,
            "types": set.types.len(),
            "levels": c,
            "solid": solid,
        })))
    })
}

/// The limit ratio of a volume as `lacuna ratio --json` prints it.
#[pyfunction]
#[pyo3(signature = (input, digits, limits=None))]
pub(crate) fn volume_ratio(
    py: Python<'_>,
    input: String,
    digits: usize,
    limits: Option<&Bound<'_, PyDict>>,
) -> PyResult<String> {
    run_limited(py, limits, move |l| {
        let (_, _, set) = load_closed(&input, &l, || l.check_digits(digits))?;
        Ok(json(&lacuna::export::volume_ratio(&set, digits)?))
    })
}

/// The exact constraint system of the volume states (faces shared between volumes read from both
/// sides) as `lacuna solve --json` prints it.
#[pyfunction]
#[pyo3(signature = (input, degree=2, cantor_gap="1".to_string(), limits=None))]
pub(crate) fn volume_solve(
    py: Python<'_>,
    input: String,
    degree: usize,
    cantor_gap: String,
    limits: Option<&Bound<'_, PyDict>>,
) -> PyResult<String> {
    run_limited(py, limits, move |l| {
        let opts = crate::gen_options(degree, &cantor_gap)?;
        let (_, v, set) = load_closed(&input, &l, || Ok(()))?;
        let shared = lacuna::constraint::shared_readings(&v.assembly);
        Ok(json(&lacuna::constraint::solve_volumes(
            &set, &shared, opts, &l,
        )?))
    })
}

/// The whole verification of a volume as `lacuna verify --json` prints it: the closure, every
/// sub-volume's surface a sphere, counts, the level-n solid, R and the constraints.
#[pyfunction]
#[pyo3(signature = (input, levels=5, limits=None))]
pub(crate) fn volume_verify(
    py: Python<'_>,
    input: String,
    levels: u64,
    limits: Option<&Bound<'_, PyDict>>,
) -> PyResult<String> {
    run_limited(py, limits, move |l| {
        let (name, v) = load(&input)?;
        l.check_level(levels)?;
        let set = match VolumeClosure::of(&v.assembly.volumes, &l)? {
            VolumeClosure::Closed(set) => set,
            // Not closed: the closure's report, as the command line prints it (exit 1).
            c => {
                let mut r = lacuna::export::volume_closure_json(&name, &c);
                r["verified"] = serde_json::Value::Bool(false);
                return Ok(json(&r));
            }
        };
        let report = lacuna::export::volume_verify(&set, &v.assembly, levels, &l)?;
        Ok(json(&report.json(&name, &set)))
    })
}

/// The certificate of a volume's closure, counts and level-n solid (levels 0 to `levels`) as JSON
/// text, the file `lacuna verify NAME --levels N --certificate` writes.
#[pyfunction]
#[pyo3(signature = (input, levels=5, limits=None))]
pub(crate) fn volume_certificate(
    py: Python<'_>,
    input: String,
    levels: u64,
    limits: Option<&Bound<'_, PyDict>>,
) -> PyResult<String> {
    run_limited(py, limits, move |l| {
        let (name, v, set) = load_closed(&input, &l, || l.check_level(levels))?;
        let lacuna_error = |e| match e {
            lacuna::certificate::CertifyError::Lacuna(e) => e,
            e => Error::Usage(format!("certificate: {e}")),
        };
        let mut cert =
            lacuna::certificate::certificate_for_volumes(&name, &set, levels, &v.assembly)
                .map_err(lacuna_error)?;
        // The solution space of the constraints too, as `verify --certificate` writes it (a
        // system above the limits is left out, not an error).
        match lacuna::certificate::solve_and_certify_volumes(&set, &v.assembly, &l) {
            Ok(steps) => cert.steps.extend(steps),
            Err(lacuna::certificate::CertifyError::Lacuna(
                Error::Limit { .. } | Error::ProvedAboveLimit { .. },
            )) => {}
            Err(e) => return Err(lacuna_error(e)),
        }
        Ok(cert.to_json())
    })
}

/// Printing sizes shared by `volume_render` and `volume_measure` (the command line's
/// `PrintArgs`).
pub(crate) struct Print {
    /// Width in mm of the level-0 solid (x extent).
    pub(crate) width: f64,
    /// The printer's smallest feature in mm.
    pub(crate) resolution: f64,
    /// A feature below the resolution fails instead of warning.
    pub(crate) strict: bool,
    /// The build volume in mm.
    pub(crate) bed: [f64; 3],
    /// Horizontal layers measured.
    pub(crate) layers: usize,
}

impl Print {
    /// Checks the sizes as the command line's flags do.
    fn check(&self) -> Result<(), Error> {
        lacuna::mesh::check_size("--resolution", self.resolution).map_err(mesh_error)?;
        let max = lacuna::mesh::slice::MAX_LAYERS;
        if !(1..=max).contains(&self.layers) {
            return Err(out_of_range(
                "layers",
                self.layers,
                "the horizontal layers measured",
                &format!("from 1 to {max}"),
            ));
        }
        if !self.bed.iter().all(|x| x.is_finite() && *x > 0.0) {
            return Err(Error::Usage(format!(
                "bed {:?} is not a build volume: give three positive sizes in mm, such as (200, 200, 200)",
                self.bed
            )));
        }
        Ok(())
    }
}

/// The checked solid of the volumes at `level` (the command line's `checked_solid`): the level
/// and the exact number of faces are bounded before any geometry is built.
fn checked_solid(
    name: &str,
    v: &VolumeFile,
    level: u64,
    width: f64,
    max_cells: Option<u64>,
    limits: &Limits,
) -> Result<(lacuna::mesh::VolumeSolid, VolumeTypeSet), Error> {
    let set = closed(v, limits)?;
    let cap = max_cells.unwrap_or(lacuna::mesh::MAX_SOLID_FACES);
    let vs = lacuna::mesh::checked_volume_solid(name, v, &set, level, width, cap, limits)?;
    Ok((vs, set))
}

/// What `volume_render` writes.
pub(crate) struct Targets {
    pub(crate) svg: Option<PathBuf>,
    pub(crate) png: Option<PathBuf>,
    pub(crate) stl: Option<PathBuf>,
    pub(crate) stl_ascii: bool,
    pub(crate) threemf: Option<PathBuf>,
    /// `plain`, `colours` or `parts`.
    pub(crate) threemf_style: String,
    pub(crate) obj: Option<PathBuf>,
    pub(crate) claims: Option<PathBuf>,
    pub(crate) size: usize,
    pub(crate) transparent: bool,
    /// `keep` or `auto`.
    pub(crate) orient: String,
    /// Return the HTML fragment of the WebGL view (`viewer` in the JSON).
    pub(crate) viewer: bool,
}

/// Writes a 3MF package built in memory (a ZIP is written with seeks) to `p`.
fn write_threemf(
    p: &std::path::Path,
    f: impl FnOnce(&mut std::io::Cursor<Vec<u8>>) -> std::io::Result<()>,
) -> Result<(), Error> {
    let zip = lacuna::mesh::threemf::in_memory(p, f)?;
    write_file(p, |w| w.write_all(&zip))
}

/// The level-n solid of a volume as `lacuna render` builds it, with the files asked for written:
/// the mesh files only when the solid is embedded (E1041 when two triangles cross), the pictures
/// in any case. Returns JSON: `written`, `notes` (what the command line says on its way),
/// `embedded`, `crossing`, `printability` (when a mesh is written) and `parts` (per component,
/// its vertices x y z interleaved and its triangles as vertex indices, as built, in mm).
#[pyfunction]
#[pyo3(signature = (input, level, targets, width=lacuna::mesh::DEFAULT_WIDTH, resolution=lacuna::mesh::DEFAULT_RESOLUTION, strict=false, bed=lacuna::mesh::DEFAULT_BED, layers=lacuna::mesh::slice::DEFAULT_LAYERS, max_cells=None, limits=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn volume_render(
    py: Python<'_>,
    input: String,
    level: u64,
    targets: &Bound<'_, PyDict>,
    width: f64,
    resolution: f64,
    strict: bool,
    bed: [f64; 3],
    layers: usize,
    max_cells: Option<u64>,
    limits: Option<&Bound<'_, PyDict>>,
) -> PyResult<String> {
    let l = self::limits(limits)?;
    let get_path = |k: &str| -> PyResult<Option<PathBuf>> {
        Ok(match targets.get_item(k)? {
            Some(v) if !v.is_none() => Some(v.extract()?),
            _ => None,
        })
    };
    let get_flag = |k: &str| -> PyResult<bool> {
        Ok(match targets.get_item(k)? {
            Some(v) => v.is_truthy()?,
            None => false,
        })
    };
    let get_text = |k: &str, default: &str| -> PyResult<String> {
        Ok(match targets.get_item(k)? {
            Some(v) if !v.is_none() => v.extract()?,
            _ => default.to_string(),
        })
    };
    let t = Targets {
        svg: get_path("svg")?,
        png: get_path("png")?,
        stl: get_path("stl")?,
        stl_ascii: get_flag("stl_ascii")?,
        threemf: get_path("threemf")?,
        threemf_style: get_text("threemf_style", "plain")?,
        obj: get_path("obj")?,
        claims: get_path("claims")?,
        size: match targets.get_item("size")? {
            Some(v) if !v.is_none() => v.extract()?,
            _ => 1024,
        },
        transparent: get_flag("transparent")?,
        orient: get_text("orient", "keep")?,
        viewer: get_flag("viewer")?,
    };
    let print = Print {
        width,
        resolution,
        strict,
        bed,
        layers,
    };
    run(py, move || render(&input, level, &t, &print, max_cells, &l))
}

/// The work of [`volume_render`], with the Python thread detached.
fn render(
    input: &str,
    level: u64,
    t: &Targets,
    print: &Print,
    max_cells: Option<u64>,
    l: &Limits,
) -> Result<String, Error> {
    use lacuna::mesh::threemf::Style;
    let style = match t.threemf_style.as_str() {
        "plain" => Style::Plain,
        "colours" => Style::Colours,
        "parts" => Style::Parts,
        other => {
            return Err(Error::Usage(format!(
                "threemf_style `{other}`: give \"plain\", \"colours\" or \"parts\""
            )))
        }
    };
    let auto = match t.orient.as_str() {
        "keep" => false,
        "auto" => true,
        other => {
            return Err(Error::Usage(format!(
                "orient `{other}`: give \"keep\" or \"auto\""
            )))
        }
    };
    if t.claims.is_some() && t.stl.is_none() && t.threemf.is_none() {
        return Err(Error::Usage(
            "claims describes the mesh written with stl or threemf: give one of them".into(),
        ));
    }
    if t.claims.is_some() && style == Style::Parts {
        return Err(Error::Usage(
            "claims describes one solid; threemf_style=\"parts\" writes one part per type".into(),
        ));
    }
    if style != Style::Plain && t.threemf.is_none() {
        return Err(Error::Usage(format!(
            "threemf_style=\"{}\" needs threemf",
            t.threemf_style
        )));
    }
    if !(1..=8192).contains(&t.size) {
        return Err(out_of_range(
            "size",
            t.size,
            "the PNG size in pixels",
            "from 1 to 8192",
        ));
    }
    print.check()?;
    refuse_clobbering(
        input,
        &[&t.svg, &t.png, &t.stl, &t.threemf, &t.obj, &t.claims],
    )?;
    let mesh = lacuna::mesh::Targets {
        stl: t.stl.clone(),
        stl_ascii: t.stl_ascii,
        threemf: t.threemf.clone(),
        obj: t.obj.clone(),
    };
    let (name, v) = load(input)?;
    let (mut vs, set) = checked_solid(&name, &v, level, print.width, max_cells, l)?;
    let mut notes = vec![vs.summary()];
    let sizes = vs.sizes(print.layers, print.resolution);
    notes.push(sizes.text(print.resolution));
    let mut printability = None;
    if mesh.any() {
        vs.embedded()?;
        printability =
            Some(sizes.report(&vs.solid.parts, vs.solid.level, print.resolution, print.bed));
        if print.strict {
            if let Some(b) = sizes.below(print.resolution).first() {
                return Err(mesh_error(lacuna::mesh::MeshError::Resolution(b.clone())));
            }
        }
    }
    // The parts as built, before any turn for the bed.
    let parts: Vec<serde_json::Value> = vs
        .solid
        .parts
        .iter()
        .map(|p| {
            serde_json::json!({
                "vertices": p.vertices.iter().flatten().collect::<Vec<_>>(),
                "triangles": p.triangles.iter().flatten().collect::<Vec<_>>(),
            })
        })
        .collect();
    // The rotating view of the volume report, as built (it centres the solid itself).
    let viewer = t.viewer.then(|| {
        // One canvas id per view: a notebook holds many on one page.
        static VIEWS: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
        let n = VIEWS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let id = format!("lacuna-solid-{}-{n}", std::process::id());
        lacuna::export::volume_viewer_with_id(&vs.solid.parts, &id)
    });
    let orientation = match mesh.any() {
        true => {
            let parts = &mut vs.solid.parts;
            let mut o = lacuna::mesh::orient::choose(parts, auto);
            if let Err(why) = lacuna::mesh::orient::turn_checked(parts, &o) {
                notes.push(format!("note: {why}; the best axis direction instead\n"));
                o = lacuna::mesh::orient::choose_axis(parts);
                let _ = lacuna::mesh::orient::turn_checked(parts, &o);
            }
            o.largest_bridge_mm = lacuna::mesh::orient::largest_bridge(parts);
            notes.push(o.text());
            Some(o)
        }
        false => None,
    };
    let solid = &vs.solid;
    if mesh.any() {
        if let Some(w) = solid.bed_advice(print.bed, print.width) {
            notes.push(format!("{w}\n"));
        }
    }
    let mut written: Vec<PathBuf> = Vec::new();
    if let Some(p) = &t.stl {
        write_file(p, |w| match t.stl_ascii {
            true => lacuna::mesh::stl::write_ascii(solid, w),
            false => lacuna::mesh::stl::write_binary(solid, w),
        })?;
        written.push(p.clone());
    }
    if let (Some(p), Some(o)) = (&t.threemf, &orientation) {
        let type_name = |k: usize| format!("V{k}");
        match style {
            Style::Plain => write_threemf(p, |zip| lacuna::mesh::threemf::write(solid, zip))?,
            Style::Colours => {
                let colours = lacuna::export::volume_type_colours(&vs, &set)?;
                write_threemf(p, |zip| {
                    lacuna::mesh::threemf::write_with(solid, Some(&colours), zip)
                })?;
            }
            Style::Parts => {
                let mut typed = vs.type_parts(&set)?;
                let mut meshes: Vec<lacuna::mesh::Part> =
                    typed.iter().map(|t| t.part.clone()).collect();
                lacuna::mesh::orient::apply(&mut meshes, o);
                for (t, m) in typed.iter_mut().zip(meshes) {
                    t.part = m;
                }
                let named: Vec<(String, [u8; 3], &lacuna::mesh::Part)> = typed
                    .iter()
                    .map(|t| (type_name(t.ty), lacuna::export::type_colour(t.ty), &t.part))
                    .collect();
                let title = format!("{} level {}", solid.name, solid.level);
                write_threemf(p, |zip| {
                    lacuna::mesh::threemf::write_parts(&title, &named, zip)
                })?;
            }
        }
        written.push(p.clone());
    }
    if let Some(p) = &t.obj {
        write_file(p, |w| lacuna::mesh::obj::write(solid, w))?;
        written.push(p.clone());
    }
    if let Some(p) = &t.claims {
        let claims =
            lacuna::export::volume_solid_claims(format!("{input} level {level}"), &mesh, &vs);
        write_file(p, |w| w.write_all(claims.to_json().as_bytes()))?;
        written.push(p.clone());
    }
    if let Some(p) = &t.svg {
        write_file(p, |w| {
            lacuna::export::write_volume_svg(&solid.parts, 512, w)
        })?;
        written.push(p.clone());
    }
    if let Some(p) = &t.png {
        write_file(p, |w| {
            lacuna::export::write_volume_png(&solid.parts, t.size as u32, t.transparent, w)
        })?;
        written.push(p.clone());
    }
    Ok(json(&serde_json::json!({
        "input": name,
        "level": level,
        "written": written,
        "notes": notes,
        "embedded": vs.crossing.is_none(),
        "crossing": vs.crossing,
        "solid": vs.exact,
        "printability": printability,
        "parts": parts,
        "viewer": viewer,
    })))
}

/// The measures of a volume's level-n solid as `lacuna measure --json` prints them: the exact
/// topology of the level, the checked mesh, its sizes in mm and the printability.
#[pyfunction]
#[pyo3(signature = (input, level, width=lacuna::mesh::DEFAULT_WIDTH, resolution=lacuna::mesh::DEFAULT_RESOLUTION, strict=false, bed=lacuna::mesh::DEFAULT_BED, layers=lacuna::mesh::slice::DEFAULT_LAYERS, max_cells=None, limits=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn volume_measure(
    py: Python<'_>,
    input: String,
    level: u64,
    width: f64,
    resolution: f64,
    strict: bool,
    bed: [f64; 3],
    layers: usize,
    max_cells: Option<u64>,
    limits: Option<&Bound<'_, PyDict>>,
) -> PyResult<String> {
    let l = self::limits(limits)?;
    let print = Print {
        width,
        resolution,
        strict,
        bed,
        layers,
    };
    run(py, move || {
        print.check()?;
        let (name, v) = load(&input)?;
        let (vs, _) = checked_solid(&name, &v, level, print.width, max_cells, &l)?;
        let sizes = vs.sizes(print.layers, print.resolution);
        let verified =
            vs.crossing.is_none() && (!print.strict || sizes.below(print.resolution).is_empty());
        Ok(json(&lacuna::export::volume_measure_json(
            &name,
            &vs,
            &sizes,
            print.resolution,
            print.bed,
            verified,
        )))
    })
}
