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
        json,
    } = args;
    let loaded = match &input {
        None => None,
        Some(input) => match lacuna::input::load_any(input)? {
            lacuna::input::Loaded::Automaton { automaton, .. } => Some(automaton),
            // Faces: instantiate (default parameters, an exact point of the solution space)
            // and analyse the instantiated operators.
            lacuna::input::Loaded::Faces(faces) => {
                let mut opts = lacuna::geometry::InstantiateOptions {
                    limits: limits.clone(),
                    ..Default::default()
                };
                opts.degree = faces.assembly.coords.degree().unwrap_or(opts.degree);
                let inst = lacuna::geometry::instantiate(&faces, &opts).map_err(geo_error)?;
                Some(inst.instantiated_automaton())
            }
        },
    };
    // The eigen analysis of a dense n×n matrix grows steeply with n (a 10×10 of random digits
    // takes about 14 s): every matrix is checked against --max-matrix before any is analysed.
    if let Some(a) = &loaded {
        for op in &a.operators {
            if op.kind == lacuna::constraint::OpKind::Sub && op.value.is_some() && op.to == op.from
            {
                limits.check_matrix(a.states[op.to].dim)?;
            }
        }
    }
    let parsed = matrix
        .iter()
        .map(|m| lacuna::analysis::parse_matrix_arg(m))
        .collect::<Result<Vec<_>, Error>>()?;
    for m in &parsed {
        limits.check_matrix(m.rows.max(m.cols))?;
    }
    let automaton = loaded
        .as_ref()
        .map(lacuna::analysis::analyse_automaton)
        .transpose()?;
    let matrices = parsed
        .iter()
        .map(lacuna::analysis::analyse_matrix)
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

/// The curvature estimate of `--curvature OP --points …`: the curve is the known `sub`
/// operators from OP's state to itself, in file order.
fn curvature_estimate(
    a: &lacuna::constraint::Automaton,
    name: &str,
    points: &str,
    level: u32,
) -> Result<lacuna::analysis::CurvatureEstimate, Error> {
    use num_traits::ToPrimitive;
    // Issue #20 item 14: refused, not silently lowered to 16.
    if level > 16 {
        return Err(Error::OutOfRange {
            flag: "--level",
            value: level.to_string(),
            what: "the word length of the curvature samples",
            range: "from 0 to 16".into(),
        });
    }
    let Some(op) = a.operators.iter().find(|o| o.name == name) else {
        return Err(Error::Usage(format!(
            "no operator `{name}` in the automaton"
        )));
    };
    let curve: Vec<&lacuna::constraint::Operator> = a
        .operators
        .iter()
        .filter(|o| {
            o.kind == lacuna::constraint::OpKind::Sub
                && o.to == op.to
                && o.from == op.to
                && o.value.is_some()
        })
        .collect();
    let Some(index) = curve.iter().position(|o| o.name == name) else {
        return Err(Error::Usage(format!(
            "`{name}` is not a known subdivision operator of its state onto itself"
        )));
    };
    let ops: Vec<lacuna::algebra::Matrix> = curve.iter().filter_map(|o| o.value.clone()).collect();
    let m = lacuna::analysis::parse_matrix_arg(points)?;
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
    lacuna::analysis::estimate_curvature(&ops, index, &pts, level)
}
