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
    if let Some((name, model)) = automaton::automaton_input(&geo)? {
        let p = automaton::prepare(&geo, name, model, limits, 100_000)?;
        return automaton::report(&geo, p, &path, limits);
    }
    // The pictures embed every cell of every level as SVG: keep them small.
    let (input, inst) = instance(&geo, limits, 200_000)?;
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
