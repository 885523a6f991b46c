//! What `render`, `measure`, `report` and `operators` share: the instance of the input with the
//! parameters given on the command line, and the checks of raster and grid sizes.

use super::*;

/// A geometry error as a lacuna error (same code and message).
pub(super) fn geo_error(e: lacuna::geometry::GeometryError) -> Error {
    e.into_error()
}

impl GeoArgs {
    /// The files this command reads (the input, the template), which no output may overwrite.
    pub(super) fn inputs(&self) -> Vec<&std::path::Path> {
        let mut v = vec![std::path::Path::new(&self.input)];
        v.extend(self.template.as_deref());
        v
    }
}

/// The input (with `--corners` applied) and its instance with the parameters given, after
/// checking the limits on the level and on the number of output cells.
pub(super) fn instance(
    geo: &GeoArgs,
    limits: &Limits,
    default_cells: u64,
) -> Result<(lacuna::input::Input, lacuna::geometry::Instance), Error> {
    limits.check_level(u64::from(geo.level))?;
    if !(1..=64).contains(&geo.segments) {
        // A fixed range, not a limit to raise (issue #20 item 12).
        return Err(Error::OutOfRange {
            flag: "--segments",
            value: geo.segments.to_string(),
            what: "the segments per Bézier edge",
            range: "from 1 to 64".into(),
        });
    }
    let mut input = load_input(&geo.input)?;
    if let Some(c) = &geo.corners {
        lacuna::input::set_corners(&mut input.assembly, c)?;
    }
    let mut opts = lacuna::geometry::InstantiateOptions {
        limits: limits.clone(),
        ..Default::default()
    };
    // User control points fix the Bézier degree.
    opts.degree = input.assembly.coords.degree().unwrap_or(opts.degree);
    opts.values = param_values(&geo.params)?;
    opts.choose(geo.template.as_deref(), &geo.goals, "--goal")?;
    let inst = lacuna::geometry::instantiate(&input, &opts).map_err(geo_error)?;
    lacuna::measure::check_cells(&inst, geo.level, geo.max_cells.unwrap_or(default_cells))
        .map_err(geo_error)?;
    Ok((input, inst))
}

/// How the parameters were chosen, when a template or goals were given or the automatic area
/// goal moved a degenerate fit (else nothing).
pub(super) fn choice_text(geo: &GeoArgs, inst: &lacuna::geometry::Instance) -> String {
    let c = &inst.choice;
    if geo.template.is_none() && geo.goals.is_empty() && c.lifted.is_none() {
        return String::new();
    }
    let mut s = format!("parameters: {}\n", c.method);
    if let Some(cell) = &c.lifted {
        s += &format!(
            "the fit made {cell} degenerate; the automatic area goal moved it (every level-1 cell \
             at least 1/64 of its type's template area shared among the type's cells, met by \
             linearisation and an LP, checked exactly)\n"
        );
    }
    if let (Some(r), Some(a)) = (&c.residual, c.residual_approx) {
        s += &format!("template residual Σ|P·c − y|² = {r} (≈ {a:.6e})\n");
        for (t, m) in c.per_type_max.iter().enumerate() {
            s += &format!("  T{t}: largest squared distance {m}\n");
        }
    }
    let how = if c.moved_by_goals {
        "by the LP"
    } else {
        "by the fit as it was"
    };
    match &c.min_slack {
        Some(m) => {
            s += &format!(
                "goals {} met exactly {how}; smallest slack {m}\n",
                c.goals.join(", ")
            )
        }
        None if !c.goals.is_empty() => {
            s += &format!("goals {}: no inequality applies\n", c.goals.join(", "))
        }
        None => {}
    }
    s
}

/// A raster size must be a power of two from 16 up to `max`.
pub(super) fn check_raster(flag: &'static str, raster: usize, max: usize) -> Result<(), Error> {
    if !(16..=max).contains(&raster) || !raster.is_power_of_two() {
        return Err(Error::OutOfRange {
            flag,
            value: raster.to_string(),
            what: "the raster size",
            range: format!("a power of two from 16 to {max}"),
        });
    }
    Ok(())
}

/// The density grid: from `min` to 1024 blocks per side (the map is rasterised at 16 pixels per
/// block).
pub(super) fn check_density_grid(grid: usize, min: usize) -> Result<(), Error> {
    if !(min..=1024).contains(&grid) {
        return Err(Error::OutOfRange {
            flag: "--density-grid",
            value: grid.to_string(),
            what: "the number of blocks per side",
            range: format!(
                "from {min} to 1024{}",
                if min == 0 { " (0: no map)" } else { "" }
            ),
        });
    }
    Ok(())
}

/// A mesh-layer error as a lacuna error (same code and message).
pub(super) fn mesh_error(e: lacuna::mesh::MeshError) -> Error {
    Error::Syntax(Box::new(lacuna::Diagnostic {
        code: e.code(),
        message: e.to_string(),
        span: None,
        source: None,
    }))
}

/// The `--param NAME=VALUE` flags as exact values (E1007 for one that is not NAME=VALUE with an
/// exact value); faces and automata read them alike.
pub(super) fn param_values(
    params: &[String],
) -> Result<Vec<(String, num_rational::BigRational)>, Error> {
    params
        .iter()
        .map(|p| {
            p.split_once('=')
                .and_then(|(n, v)| {
                    Some((
                        n.trim().to_string(),
                        lacuna::input::parse_rational(v.trim())?,
                    ))
                })
                .ok_or_else(|| {
                    Error::syntax(
                        "E1007",
                        format!(
                            "--param `{p}`: expected NAME=VALUE with an exact value (1/7, 0.25)"
                        ),
                        lacuna::Span {
                            line: 1,
                            col: 1,
                            len: p.chars().count().max(1),
                        },
                        Some(&lacuna::Source::command_line(p)),
                    )
                })
        })
        .collect()
}
