//! `lacuna export`.

use super::*;

/// Reads `--cantor-gap` as an exact positive number (E0113 otherwise).
pub(super) fn cantor_gap(text: &str) -> Result<num_rational::BigRational, Error> {
    lacuna::input::parse_rational(text.trim())
        .filter(|g| *g > num_rational::BigRational::from_integer(0.into()))
        .ok_or_else(|| {
            Error::syntax(
                "E0113",
                format!("--cantor-gap `{text}` must be an exact positive number (1, 1/2, 0.25)"),
                lacuna::Span {
                    line: 1,
                    col: 1,
                    len: text.chars().count().max(1),
                },
                Some(&lacuna::Source::command_line(text)),
            )
        })
}

/// Runs `lacuna export`.
pub(super) fn run(args: ExportArgs, limits: &Limits) -> Result<ExitCode, Error> {
    let ExportArgs {
        input,
        format,
        output,
        degree,
        cantor_gap: gap,
    } = args;
    let gap = cantor_gap(&gap)?;
    if !(1..=8).contains(&degree) {
        return Err(Error::OutOfRange {
            flag: "--degree",
            value: degree.to_string(),
            what: "the Bézier degree",
            range: "from 1 to 8".into(),
        });
    }
    // The output is checked before the work: never the input, in an existing folder.
    let mut outputs = match &output {
        Some(p) => Some(Outputs::check(
            &[std::path::Path::new(&input)],
            &[("--output", p)],
        )?),
        None => None,
    };
    let opts = lacuna::constraint::GenOptions {
        degree,
        cantor_gap: gap.clone(),
    };
    let text = match lacuna::input::load_any(&input)? {
        lacuna::input::Loaded::Automaton {
            name, automaton, ..
        } => {
            if format == ExportFormat::Moditere {
                return Err(Error::Usage(format!(
                    "`{name}` is an automaton file: the MODITERE export needs faces (a face, an assembly or an AutoFrac2D file)"
                )));
            }
            lacuna::export::automaton_text(
                &automaton,
                &[format!("lacuna export of the automaton `{name}`")],
                &Default::default(),
            )
        }
        lacuna::input::Loaded::Faces(input) => {
            let ts = lacuna::topology::close_or_error(&input.faces(), limits)?;
            match format {
                ExportFormat::Aut => {
                    let g = lacuna::constraint::automaton_of(&ts, opts);
                    limits.check_unknowns(g.automaton.unknown_count())?;
                    let notes = g
                        .face_state
                        .iter()
                        .zip(&ts.types)
                        .map(|(&s, t)| (s, t.face.to_string()))
                        .collect();
                    lacuna::export::automaton_text(
                        &g.automaton,
                        &[
                            format!(
                                "lacuna export of `{}`: the automaton generated from its closure ({} face types),",
                                input.name.replace('\n', " "),
                                ts.types.len()
                            ),
                            format!("Bézier degree {degree}, Cantor gap/piece ratio {gap} (THEORY §6)."),
                            "`lacuna solve` of this file gives the unknowns, equations, rank and degrees of freedom".into(),
                            "of `lacuna solve` on the input; the degeneracy check needs the faces, so only the input has it.".into(),
                        ],
                        &notes,
                    )
                }
                ExportFormat::Moditere => {
                    let g = lacuna::constraint::automaton_of(&ts, opts.clone());
                    limits.check_unknowns(g.automaton.unknown_count())?;
                    lacuna::export::moditere_text(&input, &ts, opts)?
                }
            }
        }
    };
    match (output, outputs.as_mut()) {
        (Some(path), Some(o)) => o.write(&path, |w| w.write_all(text.as_bytes()))?,
        _ => out(&text),
    }
    Ok(ExitCode::SUCCESS)
}
