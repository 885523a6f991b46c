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
        Err(Error::Runaway { .. }) => {
            let input = load_input(&geo.input)?;
            let closure = Closure::of(&input.faces(), limits)?;
            let v = verify_report(&input, &closure, u64::from(geo.level).max(5), limits)?;
            let html = lacuna::export::report_html_unverified(&v);
            outputs.write(&path, |w| w.write_all(html.as_bytes()))?;
            outputs.say(&format!("wrote {}\n", path.display()));
            return Ok(ExitCode::from(EXIT_FAILED));
        }
        other => other?,
    };
    // The instance's closure is the one `Closure::of` would compute again.
    let closure = Closure::Closed(inst.types.clone());
    let v = verify_report(&input, &closure, u64::from(geo.level).max(5), limits)?;
    let opts = lacuna::measure::MeasureOptions {
        level: geo.level,
        raster,
        segments: geo.segments,
        ..Default::default()
    };
    let m = lacuna::measure::measure(&inst, &opts).map_err(geo_error)?;
    eprint!("{}", choice_text(&geo, &inst));
    let html = lacuna::export::report_html(&v, &inst, &m, geo.level, geo.segments);
    outputs.write(&path, |w| w.write_all(html.as_bytes()))?;
    outputs.say(&format!("wrote {}\n", path.display()));
    Ok(if v.verified && m.verified {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(EXIT_FAILED)
    })
}
