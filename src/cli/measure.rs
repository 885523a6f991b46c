//! `lacuna measure`.

use super::*;

/// Runs `lacuna measure`.
pub(super) fn run(args: MeasureArgs, limits: &Limits) -> Result<ExitCode, Error> {
    let MeasureArgs {
        geo,
        raster,
        max_raster,
        density_grid,
        json,
        digits,
    } = args;
    check_raster("--raster", raster, lacuna::measure::LARGEST_RASTER)?;
    check_raster("--max-raster", max_raster, lacuna::measure::LARGEST_RASTER)?;
    if max_raster < raster {
        return Err(Error::OutOfRange {
            flag: "--max-raster",
            value: max_raster.to_string(),
            what: "the finest raster",
            range: format!("at least --raster ({raster})"),
        });
    }
    check_density_grid(density_grid, 0)?;
    if let Some((name, model)) = automaton::automaton_input(&geo)? {
        let p = automaton::prepare(&geo, name, model, limits, 2_000_000)?;
        return automaton::measure(&geo, p, digits, json, limits);
    }
    let (_, inst) = instance(&geo, limits, 20_000_000)?;
    let opts = lacuna::measure::MeasureOptions {
        level: geo.level,
        raster,
        max_raster,
        segments: geo.segments,
        density_grid,
        ..Default::default()
    };
    let r = lacuna::measure::measure(&inst, &opts).map_err(geo_error)?;
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
