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
        cantor_gap: gap,
    };
    let format = match format {
        ExportFormat::Aut => lacuna::export::GeneratedFormat::Aut,
        ExportFormat::Moditere => lacuna::export::GeneratedFormat::Moditere,
    };
    let text =
        lacuna::export::generated_text(lacuna::input::load_any(&input)?, format, opts, limits)?;
    match (output, outputs.as_mut()) {
        (Some(path), Some(o)) => {
            o.write(&path, |w| w.write_all(text.as_bytes()))?;
            o.say(&format!("wrote {}\n", path.display()));
        }
        _ => out(&text),
    }
    Ok(ExitCode::SUCCESS)
}
