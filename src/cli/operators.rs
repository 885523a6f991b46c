//! `lacuna operators`.

use super::*;

/// Runs `lacuna operators`.
pub(super) fn run(args: OperatorsArgs, limits: &Limits) -> Result<ExitCode, Error> {
    let OperatorsArgs {
        input,
        matrix,
        curvature,
        points,
        level,
        op,
        at,
        exact,
        svg,
        json,
    } = args;
    let loaded = input
        .as_deref()
        .map(|input| {
            lacuna::input::load_any(input)
                .and_then(|l| lacuna::export::operators_automaton(l, limits))
        })
        .transpose()?;
    let report = lacuna::export::operators_report(
        loaded.as_ref(),
        &lacuna::export::OperatorsRequest {
            matrices: &matrix,
            curvature: curvature.as_deref(),
            points: points.as_deref(),
            at: &at,
            level,
            op: op.as_deref(),
        },
        limits,
    )?;
    let ranges = &report.curves;
    if let Some(path) = &svg {
        for (state, c) in ranges {
            let Some(text) = c.to_svg() else {
                return Err(Error::Usage(
                    "--svg draws plane curves: give 2D --points".into(),
                ));
            };
            let file = if ranges.len() == 1 {
                path.clone()
            } else {
                let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("curve");
                path.with_file_name(format!("{stem}-{state}.svg"))
            };
            std::fs::write(&file, text).map_err(|e| Error::Io {
                path: file.display().to_string(),
                reason: e.to_string(),
            })?;
        }
    }
    if json {
        print_json(&report.to_json());
    } else {
        if let Some(a) = &report.automaton {
            out(&if exact { a.to_text() } else { a.summary() });
        }
        for r in &report.matrices {
            out(&if exact { r.to_text() } else { r.summary() });
        }
        for (state, c) in ranges {
            out(&format!("curve {state}:\n{}", c.to_text(exact)));
        }
        if let Some(e) = &report.curvature {
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
