//! `lacuna solve`.

use super::*;

/// Runs `lacuna solve`.
pub(super) fn run(args: SolveArgs, limits: &Limits) -> Result<ExitCode, Error> {
    let SolveArgs {
        input,
        params,
        degree,
        cantor_gap,
        json,
    } = args;
    let gap = lacuna::input::parse_rational(cantor_gap.trim())
        .filter(|g| *g > num_rational::BigRational::from_integer(0.into()))
        .ok_or_else(|| {
            Error::syntax(
                "E0113",
                format!(
                    "--cantor-gap `{cantor_gap}` must be an exact positive number (1, 1/2, 0.25)"
                ),
                lacuna::Span {
                    line: 1,
                    col: 1,
                    len: cantor_gap.chars().count().max(1),
                },
                Some(&lacuna::Source::command_line(&cantor_gap)),
            )
        })?;
    if !(1..=8).contains(&degree) {
        // A fixed range, not a limit to raise (issue #20 item 12).
        return Err(Error::OutOfRange {
            flag: "--degree",
            value: degree.to_string(),
            what: "the Bézier degree",
            range: "from 1 to 8".into(),
        });
    }
    let opts = lacuna::constraint::GenOptions {
        degree,
        cantor_gap: gap.clone(),
    };
    let report = if let Some((_, v)) = lacuna::input::load_volumes(&input)? {
        let set = volume::closed(&v.volumes, limits)?;
        let shared = lacuna::constraint::shared_readings(&v);
        lacuna::constraint::solve_volumes(&set, &shared, opts, limits)?
    } else {
        match lacuna::input::load_any(&input)? {
            lacuna::input::Loaded::Automaton { model, .. } if !model.field_ops.is_empty() => {
                // Entries outside Q: every operator is given; check the constraints in the field.
                let r = lacuna::analysis::resolve(&model, &[], limits.max_unknowns)?;
                let v = r.verdict;
                if json {
                    print_json(&v);
                } else {
                    let mut o = format!(
                        "field {}: every operator is given; {} and the barycentric conditions checked exactly in the field\n",
                        v.field,
                        lacuna::mesh::counted(model.automaton.constraints.len(), "constraint", "constraints")
                    );
                    if v.consistent {
                        o += "consistent: every constraint holds\n";
                    } else {
                        o += "INCONSISTENT: these fail:\n";
                        for f in &v.failed {
                            o += &format!("  {f}\n");
                        }
                    }
                    out(&o);
                }
                return Ok(if v.consistent {
                    ExitCode::SUCCESS
                } else {
                    ExitCode::from(EXIT_FAILED)
                });
            }
            lacuna::input::Loaded::Automaton { automaton, .. } => {
                automaton.check_solve_limits(limits)?;
                lacuna::constraint::solve_automaton(&automaton)?.0
            }
            lacuna::input::Loaded::Faces(input) => {
                let ts = lacuna::topology::close_or_error(&input.faces(), limits)?;
                lacuna::constraint::solve_closure(
                    &ts,
                    lacuna::constraint::GenOptions {
                        degree,
                        cantor_gap: gap,
                    },
                    limits,
                )?
            }
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
