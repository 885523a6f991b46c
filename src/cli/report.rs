//! `lacuna report`.

use super::*;

/// Runs `lacuna report`.
pub(super) fn run(args: ReportArgs, limits: &Limits) -> Result<ExitCode, Error> {
    let ReportArgs {
        geo,
        out: path,
        raster,
    } = args;
    check_raster("--raster", raster, 8192)?;
    let mut outputs = Outputs::check(&geo.inputs(), &[("--out", &path)])?;
    if let Some((name, v)) = lacuna::input::load_volume_file(&geo.input)? {
        return volume::report(&name, &v, &geo, &path, &mut outputs, limits);
    }
    if let Some((name, model)) = automaton::automaton_input(&geo)? {
        let p = automaton::prepare(&geo, name, model, limits, 100_000)?;
        return automaton::report(&geo, p, &path, &mut outputs, limits);
    }
    // The pictures embed every cell of every level as SVG: keep them small.
    let (input, inst) = match instance(&geo, limits, 200_000) {
        // A closure that does not close is a negative verdict, as in `lacuna verify` (exit 1):
        // the page says so, with the runaway witness, and has nothing to draw.
        Err(Error::Runaway { .. }) => (load_input(&geo.input)?, None),
        other => {
            let (input, inst) = other?;
            (input, Some(inst))
        }
    };
    if let Some(inst) = &inst {
        eprint!("{}", choice_text(&geo, inst));
    }
    let page = lacuna::export::faces_report_page(
        &input,
        inst.as_ref(),
        geo.level,
        raster,
        geo.segments,
        limits,
    )?;
    outputs.write(&path, |w| w.write_all(page.html.as_bytes()))?;
    outputs.say(&format!("wrote {}\n", path.display()));
    Ok(if page.verified {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(EXIT_FAILED)
    })
}
