//! The `lacuna` command line: a thin wrapper over the library.
#![forbid(unsafe_code)]

use clap::Parser;
use lacuna::{load_input, verify_report, Closure, Error, Limits};
use std::process::ExitCode;

/// Exit code: verification failed (the input was fine, the verdict is negative).
const EXIT_FAILED: u8 = 1;
/// Exit code: bad input or an exceeded limit.
const EXIT_BAD_INPUT: u8 = 2;
/// Exit code of `lacuna check`: every step present is proved, but the certificate lacks steps
/// its claim needs (a partial certificate proves part of its claim only).
const EXIT_PARTIAL: u8 = 3;

mod args;
use args::{Cli, Command, GeoArgs};

fn main() -> ExitCode {
    let cli = Cli::parse();
    let json = matches!(
        &cli.command,
        Command::Verify { json: true, .. }
            | Command::Closure { json: true, .. }
            | Command::Counts { json: true, .. }
            | Command::Solve { json: true, .. }
            | Command::Ratio { json: true, .. }
            | Command::Check { json: true, .. }
            | Command::Measure { json: true, .. }
            | Command::Operators { json: true, .. }
            | Command::Design { json: true, .. }
            | Command::Census { json: true, .. }
            | Command::Library { json: true }
    );
    match run(cli) {
        Ok(code) => code,
        Err(e) => {
            if json {
                print_json(&e.to_json());
            }
            eprint!("{}", e.render());
            // Goals that no parameters meet are a negative answer, not bad input.
            ExitCode::from(if e.code() == "E1031" {
                EXIT_FAILED
            } else {
                EXIT_BAD_INPUT
            })
        }
    }
}

/// Writes to standard output; a closed pipe (`lacuna … | head`) is not an error.
fn out(text: &str) {
    use std::io::Write;
    let mut stdout = std::io::stdout().lock();
    let _ = stdout
        .write_all(text.as_bytes())
        .and_then(|_| stdout.flush());
}

fn print_json(v: &impl serde::Serialize) {
    out(&(serde_json::to_string_pretty(v).expect("reports serialise") + "\n"));
}

/// The curvature estimate of `--curvature OP --points …`: the curve is the known `sub`
/// operators from OP's state to itself, in file order.
fn curvature_estimate(
    a: &lacuna::Automaton,
    name: &str,
    points: &str,
    level: u32,
) -> Result<lacuna::CurvatureEstimate, Error> {
    use num_traits::ToPrimitive;
    let Some(op) = a.operators.iter().find(|o| o.name == name) else {
        return Err(Error::Usage(format!(
            "no operator `{name}` in the automaton"
        )));
    };
    let curve: Vec<&lacuna::Operator> = a
        .operators
        .iter()
        .filter(|o| {
            o.kind == lacuna::OpKind::Sub && o.to == op.to && o.from == op.to && o.value.is_some()
        })
        .collect();
    let Some(index) = curve.iter().position(|o| o.name == name) else {
        return Err(Error::Usage(format!(
            "`{name}` is not a known subdivision operator of its state onto itself"
        )));
    };
    let ops: Vec<lacuna::Matrix> = curve.iter().filter_map(|o| o.value.clone()).collect();
    let m = lacuna::parse_matrix_arg(points)?;
    if m.cols != 2 {
        return Err(Error::Usage(format!(
            "--points needs rows `x y`, found {} columns",
            m.cols
        )));
    }
    let pts: Vec<[f64; 2]> = (0..m.rows)
        .map(|r| {
            [
                m.get(r, 0).to_f64().unwrap_or(f64::NAN),
                m.get(r, 1).to_f64().unwrap_or(f64::NAN),
            ]
        })
        .collect();
    if pts.iter().flatten().any(|v| !v.is_finite()) {
        return Err(Error::Usage("--points must be finite numbers".into()));
    }
    lacuna::estimate_curvature(&ops, index, &pts, level.min(16))
}

/// A geometry error as a lacuna error (same code and message).
fn geo_error(e: lacuna::GeometryError) -> Error {
    match e {
        lacuna::GeometryError::Lacuna(e) => e,
        other => Error::Syntax(Box::new(lacuna::Diagnostic {
            code: other.code(),
            message: other.to_string(),
            span: None,
            source: None,
        })),
    }
}

/// The input (with `--corners` applied) and its instance with the parameters given, after
/// checking the limits on the level and on the number of output cells.
fn instance(
    geo: &GeoArgs,
    limits: &Limits,
    default_cells: u64,
) -> Result<(lacuna::Input, lacuna::Instance), Error> {
    limits.check_level(u64::from(geo.level))?;
    if !(1..=64).contains(&geo.segments) {
        return Err(Error::limit(
            "the segments per Bézier edge",
            geo.segments,
            64,
            "--segments",
        ));
    }
    let mut input = load_input(&geo.input)?;
    if let Some(c) = &geo.corners {
        lacuna::set_corners(&mut input.assembly, c)?;
    }
    let mut opts = lacuna::InstantiateOptions {
        limits: limits.clone(),
        ..Default::default()
    };
    // User control points fix the Bézier degree.
    opts.degree = input.assembly.coords.degree().unwrap_or(opts.degree);
    for p in &geo.params {
        let parsed = p
            .split_once('=')
            .and_then(|(n, v)| Some((n.trim().to_string(), lacuna::parse_rational(v.trim())?)));
        let Some(pair) = parsed else {
            return Err(Error::syntax(
                "E1007",
                format!("--param `{p}`: expected NAME=VALUE with an exact value (1/7, 0.25)"),
                lacuna::Span {
                    line: 1,
                    col: 1,
                    len: p.chars().count().max(1),
                },
                Some(&lacuna::Source::command_line(p)),
            ));
        };
        opts.values.push(pair);
    }
    parameter_choice(geo, &mut opts)?;
    let inst = lacuna::instantiate(&input, &opts).map_err(geo_error)?;
    lacuna::check_cells(&inst, geo.level, geo.max_cells.unwrap_or(default_cells))
        .map_err(geo_error)?;
    Ok((input, inst))
}

/// `--template` and `--goal` into the instantiation options.
fn parameter_choice(geo: &GeoArgs, opts: &mut lacuna::InstantiateOptions) -> Result<(), Error> {
    if let Some(path) = &geo.template {
        let text = std::fs::read_to_string(path).map_err(|e| Error::Io {
            path: path.display().to_string(),
            reason: e.to_string(),
        })?;
        opts.template = Some(lacuna::Source {
            name: path.display().to_string(),
            text,
        });
    }
    for g in &geo.goals {
        let goal = lacuna::parse_goal(g).ok_or_else(|| {
            Error::syntax(
                "E1030",
                format!("--goal `{g}`: expected nonnegative, nonnegative=M or min-lacuna=S with exact M, S ≥ 0"),
                lacuna::Span {
                    line: 1,
                    col: 1,
                    len: g.chars().count().max(1),
                },
                Some(&lacuna::Source::command_line(g)),
            )
        })?;
        opts.goals.push(goal);
    }
    Ok(())
}

/// How the parameters were chosen, when a template or goals were given (else nothing).
fn choice_text(geo: &GeoArgs, inst: &lacuna::Instance) -> String {
    if geo.template.is_none() && geo.goals.is_empty() {
        return String::new();
    }
    let c = &inst.choice;
    let mut s = format!("parameters: {}\n", c.method);
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
fn check_raster(flag: &'static str, raster: usize, max: usize) -> Result<(), Error> {
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
fn check_density_grid(grid: usize, min: usize) -> Result<(), Error> {
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

/// Creates an output file for writing.
fn create(path: &std::path::Path) -> Result<std::io::BufWriter<std::fs::File>, Error> {
    std::fs::File::create(path)
        .map(std::io::BufWriter::new)
        .map_err(|e| Error::Io {
            path: path.display().to_string(),
            reason: e.to_string(),
        })
}

fn run(cli: Cli) -> Result<ExitCode, Error> {
    let l = cli.limits;
    lacuna::set_progress(!cli.no_progress && std::io::IsTerminal::is_terminal(&std::io::stderr()));
    let limits = Limits {
        max_boundary: l.max_boundary,
        max_types: l.max_types,
        max_level: l.max_level,
        max_subedges: l.max_subedges,
        max_delay: l.max_delay,
        max_digits: l.max_digits,
        max_unknowns: l.max_unknowns,
    };
    match cli.command {
        Command::Verify {
            input,
            levels,
            json,
            certificate,
        } => {
            limits.check_level(levels)?;
            let input = load_input(input.as_deref().unwrap_or("F0"))?;
            let closure = Closure::of(&input.faces(), &limits)?;
            let report = verify_report(&input, &closure, levels, &limits)?;
            if json {
                print_json(&report);
            } else {
                out(&report.to_text());
            }
            if let Some(path) = &certificate {
                let io = |e: String| Error::Io {
                    path: path.display().to_string(),
                    reason: e,
                };
                match &closure {
                    Closure::Closed(ts) => {
                        let cert = lacuna::certify::certificate_for(
                            &input.name,
                            ts,
                            lacuna::GenOptions::default(),
                        )
                        .map_err(|e| io(e.to_string()))?;
                        std::fs::write(path, cert.to_json()).map_err(|e| io(e.to_string()))?;
                        if !json {
                            out(&format!("certificate written to {}\n", path.display()));
                        }
                    }
                    Closure::Runaway(_) => {
                        eprintln!("no certificate written: the closure did not close (certificates have no runaway step)")
                    }
                }
            }
            Ok(if report.verified {
                ExitCode::SUCCESS
            } else {
                ExitCode::from(EXIT_FAILED)
            })
        }
        Command::Check { certificate, json } => {
            let text = std::fs::read_to_string(&certificate).map_err(|e| Error::Io {
                path: certificate.display().to_string(),
                reason: e.to_string(),
            })?;
            let report = lacuna::checker::check_json(&text);
            if json {
                print_json(&report.to_json());
            } else {
                out(&report.to_text());
            }
            Ok(if report.all_proved() {
                ExitCode::SUCCESS
            } else if report.partial() {
                ExitCode::from(EXIT_PARTIAL)
            } else {
                ExitCode::from(EXIT_FAILED)
            })
        }
        Command::Closure { input, json } => {
            let input = load_input(&input)?;
            let closure = Closure::of(&input.faces(), &limits)?;
            if json {
                print_json(&lacuna::closure_json(&closure));
            } else {
                let report = lacuna::closure_report(&input, &closure);
                out(&report.closure_text());
            }
            Ok(match closure {
                Closure::Closed(_) => ExitCode::SUCCESS,
                Closure::Runaway(_) => ExitCode::from(EXIT_FAILED),
            })
        }
        Command::Counts {
            input,
            levels,
            json,
        } => {
            limits.check_level(levels)?;
            let input = load_input(&input)?;
            let ts = lacuna::close_or_error(&input.faces(), &limits)?;
            if json {
                print_json(&lacuna::counts_json(&ts, &input, levels));
            } else {
                out(&format!(
                    "{} ({} face type{})\n",
                    input.name,
                    ts.types.len(),
                    if ts.types.len() == 1 { "" } else { "s" }
                ));
                out(&lacuna::counts_table(&lacuna::counts(&ts, levels)));
            }
            Ok(ExitCode::SUCCESS)
        }
        Command::Ratio {
            input,
            digits,
            json,
        } => {
            limits.check_digits(digits)?;
            let input = load_input(&input)?;
            let ts = lacuna::close_or_error(&input.faces(), &limits)?;
            let r = lacuna::ratio_of(&ts, digits)?;
            if json {
                print_json(&r);
            } else {
                out(&format!("{} ({} face types)\n", input.name, ts.types.len()));
                out(&lacuna::ratio_text(&r));
            }
            Ok(ExitCode::SUCCESS)
        }
        Command::Operators {
            input,
            matrix,
            curvature,
            points,
            level,
            json,
        } => {
            let loaded = match &input {
                None => None,
                Some(input) => match lacuna::load_any(input)? {
                    lacuna::Loaded::Automaton { automaton, .. } => Some(automaton),
                    // Faces: instantiate (default parameters, an exact point of the solution space)
                    // and analyse the instantiated operators.
                    lacuna::Loaded::Faces(faces) => {
                        let mut opts = lacuna::InstantiateOptions {
                            limits: limits.clone(),
                            ..Default::default()
                        };
                        opts.degree = faces.assembly.coords.degree().unwrap_or(opts.degree);
                        let inst = lacuna::instantiate(&faces, &opts).map_err(geo_error)?;
                        Some(inst.instantiated_automaton())
                    }
                },
            };
            let automaton = loaded.as_ref().map(lacuna::analyse_automaton).transpose()?;
            let matrices = matrix
                .iter()
                .map(|m| lacuna::analyse_matrix(&lacuna::parse_matrix_arg(m)?))
                .collect::<Result<Vec<_>, Error>>()?;
            let estimate = match (&curvature, &points, &loaded) {
                (Some(name), Some(pts), Some(a)) => Some(curvature_estimate(a, name, pts, level)?),
                (Some(_), _, None) => {
                    return Err(Error::Usage("--curvature needs an automaton file".into()));
                }
                _ => None,
            };
            if json {
                print_json(&serde_json::json!({
                    "automaton": automaton,
                    "matrices": matrices,
                    "curvature": estimate,
                }));
            } else {
                if let Some(a) = &automaton {
                    out(&a.to_text());
                }
                for r in &matrices {
                    out(&r.to_text());
                }
                if let Some(e) = &estimate {
                    let side = |s: &Option<[f64; 2]>| {
                        s.map_or("no sample".to_string(), |[lo, hi]| {
                            format!("[{lo:.6}, {hi:.6}]")
                        })
                    };
                    out(&format!(
                        "curvature estimate at the fixed point of {} (level {}, {} samples, floating point):\n  positive side {}, negative side {}\n  {}\n",
                        curvature.as_deref().unwrap_or(""),
                        e.level,
                        e.samples,
                        side(&e.positive_side),
                        side(&e.negative_side),
                        e.note
                    ));
                }
            }
            Ok(ExitCode::SUCCESS)
        }
        Command::Design {
            eigenvalues,
            eigenvectors,
            check,
            op,
            json,
        } => {
            let values = lacuna::parse_rationals_arg(&eigenvalues)?;
            let vectors = lacuna::parse_matrix_arg(&eigenvectors)?;
            let rows: Vec<Vec<_>> = vectors
                .data
                .chunks(vectors.cols)
                .map(<[_]>::to_vec)
                .collect();
            let t = lacuna::design_operator(&values, &rows)?;
            let analysis = lacuna::analyse_matrix(&t)?;
            let checked = match (&check, &op) {
                (Some(file), Some(name)) => match lacuna::load_any(file)? {
                    lacuna::Loaded::Automaton { automaton, .. } => {
                        Some(lacuna::check_design(&automaton, name, &t)?)
                    }
                    lacuna::Loaded::Faces(_) => {
                        return Err(Error::Usage(format!("`{file}` is not an automaton")))
                    }
                },
                _ => None,
            };
            if json {
                print_json(&serde_json::json!({
                    "matrix": t.to_string(),
                    "analysis": analysis,
                    "check": checked,
                }));
            } else {
                out(&format!("T = {t}\n"));
                out(&analysis.to_text());
                if let Some(c) = &checked {
                    out(&c.to_text());
                }
            }
            Ok(if checked.as_ref().is_some_and(|c| !c.ok()) {
                ExitCode::from(EXIT_FAILED)
            } else {
                ExitCode::SUCCESS
            })
        }
        Command::Render {
            geo,
            svg,
            json_out,
            obj,
            stl,
            thickness,
            png,
            size,
            density,
            density_grid,
            write_template,
        } => {
            if svg.is_none()
                && json_out.is_none()
                && obj.is_none()
                && stl.is_none()
                && png.is_none()
                && density.is_none()
                && write_template.is_none()
            {
                return Err(Error::Usage(
                    "nothing to write: give --svg, --json-out, --obj, --stl, --png, --density or --write-template"
                        .into(),
                ));
            }
            check_density_grid(density_grid, 1)?;
            if !(1..=16_384).contains(&size) {
                return Err(Error::OutOfRange {
                    flag: "--size",
                    value: size.to_string(),
                    what: "the PNG size in pixels",
                    range: "from 1 to 16384".into(),
                });
            }
            if !(thickness.is_finite() && thickness > 0.0) {
                return Err(Error::Usage(format!(
                    "--thickness {thickness} must be a positive number"
                )));
            }
            let vector = svg.is_some() || json_out.is_some() || obj.is_some() || stl.is_some();
            let (_, inst) = instance(&geo, &limits, if vector { 2_000_000 } else { 100_000_000 })?;
            let io = |path: &std::path::Path, e: std::io::Error| Error::Io {
                path: path.display().to_string(),
                reason: e.to_string(),
            };
            let (level, segs) = (geo.level, geo.segments);
            out(&choice_text(&geo, &inst));
            if let Some(p) = &write_template {
                let text = lacuna::default_template(&inst, &lacuna::InstantiateOptions::default());
                std::fs::write(p, text).map_err(|e| io(p, e))?;
                out(&format!("wrote {}\n", p.display()));
            }
            if let Some(p) = &svg {
                lacuna::write_svg(&inst, level, segs, create(p)?).map_err(|e| io(p, e))?;
                out(&format!("wrote {}\n", p.display()));
            }
            if let Some(p) = &json_out {
                lacuna::write_json(&inst, level, segs, create(p)?).map_err(|e| io(p, e))?;
                out(&format!("wrote {}\n", p.display()));
            }
            if let Some(p) = &obj {
                lacuna::write_obj(&inst, level, segs, thickness, create(p)?)
                    .map_err(|e| io(p, e))?;
                out(&format!("wrote {}\n", p.display()));
            }
            if let Some(p) = &stl {
                lacuna::write_stl(&inst, level, segs, thickness, create(p)?)
                    .map_err(|e| io(p, e))?;
                out(&format!("wrote {}\n", p.display()));
            }
            if let Some(p) = &png {
                let raster = lacuna::render_raster(&inst, level, size, segs);
                lacuna::write_png(&raster, create(p)?).map_err(|e| io(p, e))?;
                out(&format!("wrote {}\n", p.display()));
            }
            if let Some(p) = &density {
                let map = lacuna::density_map(&inst, level, density_grid, segs);
                map.write_png(create(p)?).map_err(|e| io(p, e))?;
                out(&format!("wrote {}\n", p.display()));
            }
            Ok(ExitCode::SUCCESS)
        }
        Command::Report {
            geo,
            out: path,
            raster,
        } => {
            check_raster("--raster", raster, 8192)?;
            // The pictures embed every cell of every level as SVG: keep them small.
            let (input, inst) = instance(&geo, &limits, 200_000)?;
            // The instance's closure is the one `Closure::of` would compute again.
            let closure = Closure::Closed(inst.types.clone());
            let v = verify_report(&input, &closure, u64::from(geo.level).max(5), &limits)?;
            let opts = lacuna::MeasureOptions {
                level: geo.level,
                raster,
                segments: geo.segments,
                ..Default::default()
            };
            let m = lacuna::measure(&inst, &opts).map_err(geo_error)?;
            eprint!("{}", choice_text(&geo, &inst));
            let html = lacuna::report_html(&v, &inst, &m, geo.level, geo.segments);
            std::fs::write(&path, html).map_err(|e| Error::Io {
                path: path.display().to_string(),
                reason: e.to_string(),
            })?;
            out(&format!("wrote {}\n", path.display()));
            Ok(if v.verified && m.verified {
                ExitCode::SUCCESS
            } else {
                ExitCode::from(EXIT_FAILED)
            })
        }
        Command::Measure {
            geo,
            raster,
            max_raster,
            density_grid,
            json,
        } => {
            check_raster("--raster", raster, 16_384)?;
            check_raster("--max-raster", max_raster, 16_384)?;
            if max_raster < raster {
                return Err(Error::OutOfRange {
                    flag: "--max-raster",
                    value: max_raster.to_string(),
                    what: "the finest raster",
                    range: format!("at least --raster ({raster})"),
                });
            }
            check_density_grid(density_grid, 0)?;
            let (_, inst) = instance(&geo, &limits, 20_000_000)?;
            let opts = lacuna::MeasureOptions {
                level: geo.level,
                raster,
                max_raster,
                segments: geo.segments,
                density_grid,
                ..Default::default()
            };
            let r = lacuna::measure(&inst, &opts).map_err(geo_error)?;
            eprint!("{}", choice_text(&geo, &inst));
            for f in &r.failures {
                eprintln!("verification failed: {f}");
            }
            if json {
                print_json(&r);
            } else {
                out(&r.to_text());
            }
            Ok(if r.verified {
                ExitCode::SUCCESS
            } else {
                ExitCode::from(EXIT_FAILED)
            })
        }
        Command::Solve {
            input,
            params,
            degree,
            cantor_gap,
            json,
        } => {
            let gap = lacuna::parse_rational(cantor_gap.trim())
                .filter(|g| *g > num_rational::BigRational::from_integer(0.into()))
                .ok_or_else(|| {
                    Error::syntax(
                        "E0113",
                        format!("--cantor-gap `{cantor_gap}` must be an exact positive number (1, 1/2, 0.25)"),
                        lacuna::Span { line: 1, col: 1, len: cantor_gap.chars().count().max(1) },
                        Some(&lacuna::Source::command_line(&cantor_gap)),
                    )
                })?;
            if !(1..=8).contains(&degree) {
                return Err(Error::limit("the Bézier degree", degree, 8, "--degree"));
            }
            let report = match lacuna::load_any(&input)? {
                lacuna::Loaded::Automaton { automaton, .. } => {
                    limits.check_unknowns(automaton.unknown_count())?;
                    lacuna::solve_automaton(&automaton)?.0
                }
                lacuna::Loaded::Faces(input) => {
                    let ts = lacuna::close_or_error(&input.faces(), &limits)?;
                    lacuna::solve_closure(
                        &ts,
                        lacuna::GenOptions {
                            degree,
                            cantor_gap: gap,
                        },
                        &limits,
                    )?
                }
            };
            if json {
                print_json(&report);
            } else {
                out(&report.to_text(params));
            }
            Ok(if report.ok() {
                ExitCode::SUCCESS
            } else {
                ExitCode::from(EXIT_FAILED)
            })
        }
        Command::Census { spec, json } => {
            let spec = lacuna::CensusSpec::parse(
                &spec.edges,
                &spec.params,
                &spec.algorithms,
                spec.max_length,
                spec.threads,
            )?;
            let report = lacuna::census(&spec, &limits);
            if json {
                print_json(&report);
            } else {
                out(&report.to_text());
            }
            Ok(ExitCode::SUCCESS)
        }
        Command::Library { json } => {
            let names: Vec<(&str, String)> = lacuna::library()
                .iter()
                .map(|(n, t)| {
                    (
                        *n,
                        t.lines()
                            .next()
                            .unwrap_or("")
                            .trim_start_matches('#')
                            .trim()
                            .to_string(),
                    )
                })
                .collect();
            if json {
                print_json(
                    &names
                        .iter()
                        .map(|(n, d)| serde_json::json!({"name": n, "about": d}))
                        .collect::<Vec<_>>(),
                );
            } else {
                let width = names
                    .iter()
                    .map(|(n, _)| n.chars().count())
                    .max()
                    .unwrap_or(0);
                for (n, d) in names {
                    out(&format!("{n:<width$}  {d}\n"));
                }
            }
            Ok(ExitCode::SUCCESS)
        }
    }
}
