//! `render`, `measure` and `report` on an automaton file: resolve the operators (exact values,
//! `param` lines and `--param`), refuse a cycle that does not contract, then draw and measure the
//! attractor to the level asked.

use super::*;
use lacuna::analysis::{ContractionReport, Resolved};
use lacuna::geometry::Evaluator;
use lacuna::input::AutomatonModel;

/// A loaded automaton ready to draw.
pub(super) struct Prepared {
    name: String,
    input: String,
    model: AutomatonModel,
    resolved: Resolved,
    contraction: ContractionReport,
    ev: Evaluator,
    /// Whether the evaluator starts at another state than the model's start (`--state`).
    restarted: bool,
}

/// The automaton named by the input, when it is one (else `None`: faces).
pub(super) fn automaton_input(geo: &GeoArgs) -> Result<Option<(String, AutomatonModel)>, Error> {
    if geo.input.contains('|') || geo.input.trim().is_empty() {
        return Ok(None);
    }
    match lacuna::input::load_any(&geo.input)? {
        lacuna::input::Loaded::Automaton { name, model, .. } => Ok(Some((name, *model))),
        lacuna::input::Loaded::Faces(_) => Ok(None),
    }
}

/// Resolves, checks contraction and counts the pieces of the level before any drawing.
pub(super) fn prepare(
    geo: &GeoArgs,
    name: String,
    model: AutomatonModel,
    limits: &Limits,
    default_cells: u64,
) -> Result<Prepared, Error> {
    prepare_at(geo, name, model, None, limits, default_cells)
}

/// [`prepare`] drawing the attractor of `state` (`render --state`; `None`: the start state):
/// the evaluator starts there from its frame, and the model kept for the exact meshes is the
/// one restarted there ([`lacuna::geometry::restarted`]).
pub(super) fn prepare_at(
    geo: &GeoArgs,
    name: String,
    model: AutomatonModel,
    state: Option<&str>,
    limits: &Limits,
    default_cells: u64,
) -> Result<Prepared, Error> {
    limits.check_level(u64::from(geo.level))?;
    if geo.template.is_some() || !geo.goals.is_empty() || geo.corners.is_some() {
        return Err(Error::Usage(
            "--template, --goal and --corners apply to faces; an automaton takes its control points from its `points` line and its parameters from `param` lines and --param".into(),
        ));
    }
    let (resolved, contraction, ev) = lacuna::geometry::prepare_automaton_at(
        &model,
        state,
        &param_values(&geo.params)?,
        geo.level,
        geo.max_cells.unwrap_or(default_cells),
        limits,
    )?;
    let (model, restarted) = match lacuna::geometry::evaluated_model(&model, &resolved, &ev) {
        Some(m) => (m, true),
        None => (model, false),
    };
    Ok(Prepared {
        name,
        input: geo.input.clone(),
        model,
        resolved,
        contraction,
        ev,
        restarted,
    })
}

/// The refusal of `--state` for an input without states (`what`: faces, a volume), telling to
/// `verb` (draw, measure) without it.
pub(super) fn no_states(state: Option<&str>, what: &str, verb: &str) -> Error {
    Error::Usage(format!(
        "--state `{}` names a state of an automaton, but {what}: {verb} without --state",
        state.unwrap_or_default()
    ))
}

/// Prints the solver's warnings on standard error.
fn warn(p: &Prepared) {
    if !p.resolved.verdict.consistent {
        eprintln!(
            "warning: the constraints of {} do not hold with these values; drawn anyway",
            p.name
        );
    }
}

/// The mesh files asked of `render` on an automaton.
pub(super) struct MeshOut {
    /// The paths (STL, 3MF, OBJ).
    pub(super) targets: lacuna::mesh::Targets,
    /// The claims file of the shell (`--claims`).
    pub(super) claims: Option<std::path::PathBuf>,
    /// Width and thickness in mm.
    pub(super) size: lacuna::mesh::Size,
    /// Whether `--thickness` was given: a closed shell instead of the open surface.
    pub(super) thick: bool,
    /// The build volume (`--bed`), in mm.
    pub(super) bed: [f64; 3],
    /// The orientation (`--orient`).
    pub(super) orient: super::args::OrientArg,
    /// The printer's resolution in mm (`--resolution`) and whether a wall below it fails
    /// (`--strict`).
    pub(super) resolution: (f64, bool),
    /// The horizontal layers measured (`--layers`).
    pub(super) layers: usize,
}

/// Writes the STL, 3MF and (with a thickness) OBJ meshes of the level's polygon leaves: the
/// open surface, or the closed shell checked before anything is written.
fn write_meshes(p: &Prepared, level: u32, m: &MeshOut, outputs: &mut Outputs) -> Result<(), Error> {
    let t = &m.targets;
    let raw_obj = !m.thick && t.obj.is_some();
    if t.stl.is_none() && t.threemf.is_none() && (t.obj.is_none() || raw_obj) {
        return Ok(());
    }
    let built = lacuna::mesh::automaton_mesh(
        &p.ev,
        Some((&p.model, &p.resolved)),
        level,
        &p.name,
        m.size,
        m.thick,
    )
    .map_err(mesh_error)?
        .ok_or_else(|| {
            Error::Syntax(Box::new(lacuna::Diagnostic {
                code: "E0720",
                message: format!(
                    "{} has no polygon at level {level}: --stl, --3mf and a thickened --obj mesh the polygon primitives (`primitive STATE polygon`)",
                    p.name
                ),
                span: None,
                source: None,
            }))
        })?;
    let mut built = built;
    let how = if built.exact_vertices {
        "vertices identified exactly"
    } else {
        "vertices welded within 1e-9 of the size"
    };
    let part = &built.solid.parts[0];
    match built.solid.checks.first() {
        Some(c) => outputs.say(&format!(
            "mesh: {} level {level}, width {} mm, shell {} mm thick: {} vertices, {} triangles ({how}); closed oriented manifold, Euler characteristic {}\n",
            p.name, m.size.width, m.size.thickness, c.vertices, c.triangles, c.euler
        )),
        None => {
            outputs.say(&format!(
                "mesh: {} level {level}, width {} mm: the open surface, {} vertices, {} triangles ({how})\n",
                p.name,
                m.size.width,
                part.vertices.len(),
                part.triangles.len()
            ));
            eprintln!(
                "warning: the surface of {} is open, not a solid: slicers will not print it; give --thickness T (mm) for a closed shell",
                p.name
            );
        }
    }
    if !built.solid.checks.is_empty() {
        // The shell's walls: a lower bound of every wall thickness (the shell's own thickness,
        // or less where two pieces come close), against the printer's resolution.
        let (resolution, strict) = m.resolution;
        let wall = lacuna::mesh::wall::wall_bound(&built.solid.parts).map(|w| w.thickness);
        let layers = lacuna::mesh::slice::layer_features(&built.solid.parts, m.layers, resolution);
        let mm = |x: Option<(f64, f64)>| x.map_or("none".to_string(), |v| format!("{:.3} mm", v.0));
        outputs.say(&format!(
            "printability: wall thickness {} (lower bound: the least distance of two facing triangles with material between them); smallest hole {}, thinnest ligament {} (estimates from {} horizontal layers); resolution {resolution} mm\n",
            wall.map_or("none".to_string(), |w| format!("≥ {w:.3} mm")),
            mm(layers.smallest_hole),
            mm(layers.thinnest_ligament),
            layers.layers,
        ));
        let figures = lacuna::mesh::printability::SolidFigures {
            level,
            resolution,
            bed: m.bed,
            extent_mm: built.solid.extent(),
            wall_bound_mm: wall,
            layers: &layers,
        };
        let below = figures.below();
        // The overhang and the largest bridge are measured for the JSON object only.
        if outputs.json {
            outputs.printability = Some(lacuna::mesh::printability::PrintReport::of_solid(
                &built.solid.parts,
                figures,
            ));
        }
        for why in below {
            match strict {
                true => return Err(mesh_error(lacuna::mesh::MeshError::Resolution(why))),
                false => eprintln!("warning: {why}"),
            }
        }
        super::render::orient(&mut built.solid.parts, m.orient, outputs);
    }
    let solid = &built.solid;
    if let Some(w) = solid.bed_advice(m.bed, m.size.width) {
        eprintln!("{w}");
    }
    let wrote = |o: &Outputs, path: &std::path::Path| o.say(&format!("wrote {}\n", path.display()));
    if let Some(path) = &t.stl {
        outputs.write(path, |w| match t.stl_ascii {
            true => lacuna::mesh::stl::write_ascii(solid, w),
            false => lacuna::mesh::stl::write_binary(solid, w),
        })?;
        wrote(outputs, path);
    }
    if let Some(path) = &t.threemf {
        let mut zip = std::io::Cursor::new(Vec::new());
        lacuna::mesh::threemf::write(solid, &mut zip).map_err(|e| Error::Write {
            path: path.display().to_string(),
            reason: e.to_string(),
        })?;
        outputs.write(path, |w| w.write_all(zip.get_ref()))?;
        wrote(outputs, path);
    }
    if let (Some(path), true) = (&t.obj, m.thick) {
        outputs.write(path, |w| lacuna::mesh::obj::write(solid, w))?;
        wrote(outputs, path);
    }
    if let Some(path) = &m.claims {
        // An automaton has no exact topology to derive the figures from: the claims are the
        // figures of lacuna's own check of the shell it writes (a closed oriented manifold per
        // part), for a reader that shares none of lacuna's code to re-derive from the file.
        let parts: usize = solid.checks.iter().map(|c| c.components).sum();
        let euler: i64 = solid.checks.iter().map(|c| c.euler).sum();
        let per_part: Option<Vec<lacuna::meshcheck::PartClaim>> = solid
            .checks
            .iter()
            .map(|c| {
                (c.components == 1).then_some(lacuna::meshcheck::PartClaim {
                    euler: c.euler,
                    genus: (2 - c.euler) / 2,
                })
            })
            .collect();
        let claims = lacuna::export::mesh_claims(
            format!(
                "{} level {level} (shell {} mm thick; figures from lacuna's check of the written mesh, not from an exact topology)",
                p.name, m.size.thickness
            ),
            t,
            solid.triangle_count(),
            Some(parts as u64),
            Some(euler),
            Some(parts as i64 - euler / 2),
            per_part,
        );
        super::render::write_claims(outputs, path, &claims)?;
    }
    Ok(())
}

/// `lacuna render` on an automaton.
#[allow(clippy::too_many_arguments)]
pub(super) fn render(
    geo: &GeoArgs,
    p: Prepared,
    outputs: &mut Outputs,
    svg: Option<&std::path::Path>,
    json_out: Option<&std::path::Path>,
    png: Option<&std::path::Path>,
    meshes: &MeshOut,
    picture: (usize, lacuna::export::Background, bool),
) -> Result<ExitCode, Error> {
    warn(&p);
    let level = geo.level;
    let wrote = |o: &Outputs, path: &std::path::Path| o.say(&format!("wrote {}\n", path.display()));
    if let Some(path) = svg {
        outputs.write(path, |w| {
            lacuna::export::write_automaton_svg(&p.ev, level, w)
        })?;
        wrote(outputs, path);
    }
    if let Some(path) = json_out {
        outputs.write(path, |w| {
            lacuna::export::write_automaton_json(&p.ev, level, w)
        })?;
        wrote(outputs, path);
    }
    write_meshes(&p, level, meshes, outputs)?;
    if let (Some(path), false) = (meshes.targets.obj.as_deref(), meshes.thick) {
        outputs.write(path, |w| {
            lacuna::export::write_automaton_obj(&p.ev, level, w)
        })?;
        wrote(outputs, path);
    }
    if let Some(path) = png {
        let (size, background, legend) = picture;
        outputs.write(path, |w| {
            lacuna::export::write_automaton_png(&p.ev, level, size as u32, background, legend, w)
        })?;
        wrote(outputs, path);
    }
    Ok(ExitCode::SUCCESS)
}

/// The measures of an automaton (levels, box counting, similarity dimension).
pub(super) fn measures(
    geo: &GeoArgs,
    p: &Prepared,
    digits: usize,
    limits: &Limits,
) -> Result<lacuna::measure::AutomatonMeasure, Error> {
    if digits == 0 {
        return Err(Error::OutOfRange {
            flag: "--digits",
            value: "0".into(),
            what: "the certified digits of the similarity dimension",
            range: format!("from 1 to {}", limits.max_digits),
        });
    }
    limits.check_digits(digits)?;
    Ok(lacuna::measure::automaton_measure(
        &p.name,
        &p.model,
        &p.resolved,
        &p.contraction,
        &p.ev,
        geo.level,
        digits,
    ))
}

/// `lacuna measure` on an automaton.
pub(super) fn measure(
    geo: &GeoArgs,
    p: Prepared,
    digits: usize,
    json: bool,
    limits: &Limits,
) -> Result<ExitCode, Error> {
    warn(&p);
    let mut m = measures(geo, &p, digits, limits)?;
    if p.restarted {
        m.state = Some(p.model.automaton.states[p.model.start].name.clone());
    }
    if json {
        print_json(&m);
    } else {
        out(&m.to_text());
    }
    Ok(if m.solver.consistent {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(EXIT_FAILED)
    })
}

/// `lacuna report` on an automaton.
pub(super) fn report(
    geo: &GeoArgs,
    p: Prepared,
    path: &std::path::Path,
    outputs: &mut Outputs,
    limits: &Limits,
) -> Result<ExitCode, Error> {
    warn(&p);
    let page = lacuna::export::automaton_report_page(
        &p.input,
        &p.name,
        &p.model,
        &p.resolved,
        &p.contraction,
        &p.ev,
        geo.level,
        limits,
    )?;
    outputs.write(path, |w| w.write_all(page.html.as_bytes()))?;
    outputs.say(&format!("wrote {}\n", path.display()));
    Ok(if page.verified {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(EXIT_FAILED)
    })
}

/// What `verify` says about an automaton file or a rule.
#[derive(serde::Serialize)]
struct AutomatonVerdict<'a> {
    input: &'a str,
    /// The constraints: consistent (with the free parameters left), or the failing ones.
    solver: &'a lacuna::analysis::ResolveVerdict,
    /// Whether the instance's attractor is proven defined, and how.
    contraction: Option<String>,
    /// Why contraction was not proven (a cycle that does not contract).
    contraction_fails: &'a Option<String>,
    /// The similarity dimension, when it applies.
    similarity_dimension: &'a Option<lacuna::analysis::SimilarityDimension>,
    /// Why there is no similarity dimension.
    similarity_note: &'a Option<String>,
    /// The boundary dimension of the tiles (an upper bound), when some part is a tile.
    #[serde(skip_serializing_if = "Option::is_none")]
    boundary_dimension: &'a Option<lacuna::analysis::BoundaryDimension>,
    /// The verdict.
    verified: bool,
}

/// `lacuna verify` on an automaton file, a library automaton or a rule (compiled): the
/// constraints, the contraction of the instance drawn (free parameters 0, `param` lines), the
/// similarity dimension and the open-set condition; `--certificate` writes the steps that
/// prove them (`constraints-hold` or `solution-space`, `contraction`, `similarity-dimension`,
/// `boundary-dimension`).
pub(super) fn verify(
    arg: &str,
    name: &str,
    model: &AutomatonModel,
    json: bool,
    certificate: Option<&std::path::Path>,
    limits: &Limits,
) -> Result<ExitCode, Error> {
    let mut outputs = match certificate {
        Some(path) => Outputs::check(&[std::path::Path::new(arg)], &[("--certificate", path)])?,
        None => Outputs::check(&[], &[])?,
    };
    if json && outputs.to_stdout {
        return Err(Error::Usage(
            "--json and --certificate - would both write to standard output".into(),
        ));
    }
    model.automaton.check_solve_limits(limits)?;
    let analysis =
        lacuna::analysis::analyse_attractor(model, limits.max_unknowns, limits.max_products, 30)?;
    let lacuna::analysis::Attractor {
        resolved,
        contraction,
        contraction_fails: fails,
        similarity,
        similarity_note: note,
        boundary,
    } = &analysis;
    let free = !resolved.verdict.free_left.is_empty();
    let consistent = resolved.verdict.consistent;
    // A cycle of the instance that does not contract is a negative verdict when the file
    // leaves no parameter free; with free parameters (set to 0) it is about that choice only.
    let verified = consistent && (contraction.is_some() || free);
    let mut o = format!(
        "lacuna verify: {name} (automaton in space {})\n\n",
        model.space
    );
    o += &format!(
        "constraints ({}): {}\n",
        resolved.verdict.field,
        match consistent {
            true => "consistent: every constraint holds".to_string(),
            false => format!("INCONSISTENT: {}", resolved.verdict.failed.join("; ")),
        }
    );
    if free {
        o += &format!(
            "  free parameters set to 0 in the instance: {}\n",
            resolved.verdict.free_left.join(", ")
        );
    }
    match (&contraction, &fails) {
        (Some(c), _) => o += &format!("{}\n", c.text()),
        (None, Some(f)) if free => {
            o += &format!("contraction: the instance with the free parameters at 0 does not contract ({f}); choose them with `lacuna render --param`\n")
        }
        (None, Some(f)) => o += &format!("contraction: FAILS — {f}\n"),
        (None, None) => {}
    }
    match (&similarity, &note) {
        (Some(s), _) if s.upper_bound => o += &format!(
            "similarity dimension = {} = {}… — an upper bound of the Hausdorff dimension only: {}\n",
            s.exact, s.decimal, s.open_set
        ),
        (Some(s), _) => o += &format!(
            "similarity dimension = {} = {}… (the Hausdorff dimension: {}{})\n",
            s.exact,
            s.decimal,
            s.open_set,
            match s.open_set_witnessed() {
                true => "",
                false => lacuna::measure::OPEN_SET_NOT_CERTIFIED,
            }
        ),
        (None, Some(n)) => o += &format!("similarity dimension: not applicable ({n})\n"),
        (None, None) => {}
    }
    if let Some(b) = boundary {
        o += &format!(
            "boundary dimension (an upper bound, tiles): {}\n",
            b.states
                .iter()
                .map(|s| format!("{} ≤ {} = {}…", s.state, s.exact, s.decimal))
                .collect::<Vec<_>>()
                .join("; ")
        );
    }
    o += &format!(
        "\nverdict: {}\n",
        match verified {
            true => "VERIFIED",
            false => "NOT VERIFIED",
        }
    );
    if !json && !outputs.to_stdout {
        out(&o);
    }
    if let Some(path) = certificate {
        let cert = lacuna::certificate::certificate_for_model(name, model, &analysis)
            .map_err(|e| e.into_error("--certificate"))?;
        outputs.write(path, |w| w.write_all(cert.to_json().as_bytes()))?;
        if !json {
            outputs.say(&format!(
                "certificate written to {}{}\n",
                path.display(),
                match &similarity {
                    Some(s) if s.open_set_refuted() => {
                        " (with the witness that the open-set condition fails: two words with one map)"
                    }
                    Some(s) if s.open_set_witnessed() => match s.open_set_by_neighbour_maps() {
                        false => " (with the open-set condition's witness: convex sets)",
                        true => " (with the open-set condition's witness: neighbour maps)",
                    },
                    Some(_) => " (the open-set condition is not certified: it is undecided, see docs/CERTIFICATES.md)",
                    None => "",
                }
            ));
        }
    }
    if json {
        print_json(&AutomatonVerdict {
            input: name,
            solver: &resolved.verdict,
            contraction: contraction.as_ref().map(|c| c.text()),
            contraction_fails: fails,
            similarity_dimension: similarity,
            similarity_note: note,
            boundary_dimension: boundary,
            verified,
        });
    } else if outputs.to_stdout {
        eprint!("{o}");
    }
    Ok(match verified {
        true => ExitCode::SUCCESS,
        false => ExitCode::from(EXIT_FAILED),
    })
}
