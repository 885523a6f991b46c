//! `lacuna morph A B --on INPUT --frames N`: metamorphosis between two parameter choices of one
//! structure (THEORY §13), every frame checked, an animated SVG and PNG frames.

use super::*;
use lacuna::geometry::InstantiateOptions;

/// A parameter choice: `default`, `NAME=VALUE,…`, or a template file.
fn choice(arg: &str, limits: &Limits) -> Result<InstantiateOptions, Error> {
    let mut opts = InstantiateOptions {
        limits: limits.clone(),
        ..Default::default()
    };
    let arg = arg.trim();
    if arg == "default" {
        return Ok(opts);
    }
    if arg.contains('=') {
        let items: Vec<String> = arg.split(',').map(|s| s.trim().to_string()).collect();
        opts.values = param_values(&items)?;
        return Ok(opts);
    }
    let text = lacuna::input::read_text(arg)?;
    opts.template = Some(lacuna::Source {
        name: arg.to_string(),
        text,
    });
    Ok(opts)
}

/// A and B as automata, when both are automaton files or library entries.
fn two_automata(
    args: &MorphArgs,
) -> Result<Option<(lacuna::input::AutomatonModel, lacuna::input::AutomatonModel)>, Error> {
    let load = |s: &str| -> Result<Option<lacuna::input::AutomatonModel>, Error> {
        if s.contains('=') || s == "default" || s.contains('|') {
            return Ok(None);
        }
        Ok(match lacuna::input::load_any(s)? {
            lacuna::input::Loaded::Automaton { model, .. } => Some(*model),
            lacuna::input::Loaded::Faces(_) => None,
        })
    };
    Ok(match (load(&args.a)?, load(&args.b)?) {
        (Some(a), Some(b)) => Some((a, b)),
        _ => None,
    })
}

/// `lacuna morph A.aut B.aut`: two automata of one shape.
fn automata(
    args: &MorphArgs,
    ma: lacuna::input::AutomatonModel,
    mb: lacuna::input::AutomatonModel,
    pngs: &[std::path::PathBuf],
    limits: &Limits,
) -> Result<ExitCode, Error> {
    let mut wanted: Vec<(&str, &std::path::Path)> = Vec::new();
    if let Some(s) = &args.svg {
        wanted.push(("--svg", s));
    }
    for p in pngs {
        wanted.push(("--png", p));
    }
    let inputs = [
        std::path::Path::new(args.a.as_str()),
        std::path::Path::new(args.b.as_str()),
    ];
    let mut outputs = output::Outputs::check(&inputs, &wanted)?;
    let name = format!("{} → {}", args.a, args.b);
    let (report, frames) = lacuna::export::morph_automata(
        &name,
        &ma,
        &mb,
        args.frames,
        args.level,
        limits,
        |k, ev| {
            if let Some(p) = pngs.get(k as usize) {
                outputs.write(p, |w| {
                    lacuna::export::write_morph_automaton_png(ev, args.level, args.size, w)
                })?;
            }
            Ok(())
        },
    )?;
    finish(args, &report, &frames, &mut outputs, pngs.len())
}

/// Writes the SVG, prints the report and chooses the exit code.
fn finish(
    args: &MorphArgs,
    report: &lacuna::measure::MorphReport,
    frames: &lacuna::export::MorphFrames,
    outputs: &mut output::Outputs,
    pngs: usize,
) -> Result<ExitCode, Error> {
    if let Some(p) = &args.svg {
        outputs.write(p, |w| {
            lacuna::export::write_morph_svg(&report.name, frames, args.size, args.seconds, w)
        })?;
    }
    if args.json {
        print_json(report);
    } else {
        let mut s = match report.moving_points {
            Some((k, n)) => format!(
                "{}: {} frames at level {}, {} of {} operators change, {k} of {n} control points move\n",
                report.name,
                report.frames.len(),
                report.level,
                report.changing,
                report.parameters
            ),
            None => format!(
                "{}: {} frames at level {}, {} of {} free parameters change\n",
                report.name,
                report.frames.len(),
                report.level,
                report.changing,
                report.parameters
            ),
        };
        for f in &report.frames {
            if f.verified {
                s += &match (f.holes, f.components) {
                    (Some(h), Some(c)) => format!(
                        "frame {:>3}  t = {:<8} verified: {h} holes, {c} components as the exact counts\n",
                        f.index, f.t
                    ),
                    _ => format!(
                        "frame {:>3}  t = {:<8} verified: constraints hold, cycles contract\n",
                        f.index, f.t
                    ),
                };
            } else {
                s += &format!("frame {:>3}  t = {:<8} FAILED\n", f.index, f.t);
                for r in &f.failures {
                    s += &format!("             {r}\n");
                }
            }
        }
        s += &match report.first_failure {
            None => "VERIFIED: every frame\n".to_string(),
            Some(k) => format!("NOT VERIFIED: frame {k} is the first that fails\n"),
        };
        outputs.say(&s);
        if let Some(p) = &args.svg {
            outputs.say(&format!("wrote {}\n", p.display()));
        }
        if pngs > 0 {
            outputs.say(&format!("wrote {pngs} PNG frames\n"));
        }
    }
    Ok(if report.verified {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(EXIT_FAILED)
    })
}

/// Runs `lacuna morph`.
pub(super) fn run(args: MorphArgs, limits: &Limits) -> Result<ExitCode, Error> {
    if !(2..=1000).contains(&args.frames) {
        return Err(Error::OutOfRange {
            flag: "--frames",
            value: args.frames.to_string(),
            what: "the number of frames",
            range: "from 2 to 1000".into(),
        });
    }
    if !(16..=8192).contains(&args.size) {
        return Err(Error::OutOfRange {
            flag: "--size",
            value: args.size.to_string(),
            what: "the frame size in pixels",
            range: "from 16 to 8192".into(),
        });
    }
    if !(args.seconds.is_finite() && args.seconds > 0.0 && args.seconds <= 60.0) {
        return Err(Error::OutOfRange {
            flag: "--seconds",
            value: args.seconds.to_string(),
            what: "the seconds per frame",
            range: "above 0 and at most 60".into(),
        });
    }
    limits.check_level(u64::from(args.level))?;
    let pngs = match &args.png {
        Some(p) => lacuna::export::morph_png_paths(p, args.frames, "--png")?,
        None => Vec::new(),
    };
    let Some(on) = &args.on else {
        if let Some((ma, mb)) = two_automata(&args)? {
            return automata(&args, ma, mb, &pngs, limits);
        }
        return Err(Error::syntax(
            "E1402",
            "morph: give the structure with --on INPUT (A and B are parameter choices of it: template files, NAME=VALUE,… or `default`)",
            lacuna::Span {
                line: 1,
                col: 1,
                len: args.a.chars().count().max(1),
            },
            Some(&lacuna::Source::command_line(&args.a)),
        ));
    };
    let mut wanted: Vec<(&str, &std::path::Path)> = Vec::new();
    if let Some(s) = &args.svg {
        wanted.push(("--svg", s));
    }
    for p in &pngs {
        wanted.push(("--png", p));
    }
    let mut inputs = vec![std::path::Path::new(on.as_str())];
    for c in [&args.a, &args.b] {
        if !c.contains('=') && c != "default" {
            inputs.push(std::path::Path::new(c.as_str()));
        }
    }
    let mut outputs = output::Outputs::check(&inputs, &wanted)?;
    let input = load_input(on)?;
    let a = choice(&args.a, limits)?;
    let b = choice(&args.b, limits)?;
    let (report, frames) = lacuna::export::morph_faces(
        &input,
        &a,
        &b,
        args.frames,
        args.level,
        args.size,
        args.max_cells,
        limits,
        |k, inst| {
            if let Some(p) = pngs.get(k as usize) {
                outputs
                    .write(p, |w| {
                        lacuna::export::write_morph_png(inst, args.level, args.size, w)
                    })
                    .map_err(lacuna::geometry::GeometryError::Lacuna)?;
            }
            Ok(())
        },
    )
    .map_err(geo_error)?;
    finish(&args, &report, &frames, &mut outputs, pngs.len())
}
