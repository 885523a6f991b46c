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
    // The eigen analysis of a dense n×n matrix grows with n (a 20×20 of random digits takes a
    // fraction of a second, repeated eigenvalues cost more): every matrix is checked against
    // --max-matrix before any is analysed.
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
        .map(|a| lacuna::analysis::analyse_automaton_only(a, op.as_deref()))
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
    let ranges = match (&points, &loaded, &curvature) {
        (Some(pts), Some(a), None) => curve_ranges(a, pts, &at, level, op.as_deref())?,
        (Some(_), None, None) => {
            return Err(Error::Usage(
                "--points needs an automaton file or a face".into(),
            ));
        }
        _ => Vec::new(),
    };
    if let Some(path) = &svg {
        for (state, c) in &ranges {
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
        let curves: Vec<serde_json::Value> = ranges
            .iter()
            .map(|(state, c)| serde_json::json!({ "state": state, "curvature": c }))
            .collect();
        print_json(&serde_json::json!({
            "automaton": automaton,
            "matrices": matrices,
            "curvature": estimate,
            "curves": curves,
        }));
    } else {
        if let Some(a) = &automaton {
            out(&if exact { a.to_text() } else { a.summary() });
        }
        for r in &matrices {
            out(&if exact { r.to_text() } else { r.summary() });
        }
        for (state, c) in &ranges {
            out(&format!("curve {state}:\n{}", c.to_text(exact)));
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

/// The DCFs and pseudo-curvature ranges of every curve (a state with at least two known
/// sub-operators onto itself, in file order) whose state has as many points as `points` gives;
/// with `--op`, only the curve holding that operator.
fn curve_ranges(
    a: &lacuna::constraint::Automaton,
    points: &str,
    at: &[String],
    level: u32,
    only: Option<&str>,
) -> Result<Vec<(String, lacuna::analysis::CurveCurvature)>, Error> {
    use num_traits::ToPrimitive;
    let m = lacuna::analysis::parse_matrix_arg(points)?;
    let pts: Vec<Vec<f64>> = (0..m.rows)
        .map(|r| {
            (0..m.cols)
                .map(|c| m.get(r, c).to_f64().unwrap_or(f64::NAN))
                .collect()
        })
        .collect();
    if pts.iter().flatten().any(|v| !v.is_finite()) {
        return Err(Error::Usage("--points must be finite numbers".into()));
    }
    let ts = at
        .iter()
        .map(|t| {
            lacuna::input::parse_rational(t.trim()).ok_or_else(|| {
                Error::Usage(format!("--at {t}: expected an exact number such as 3/8"))
            })
        })
        .collect::<Result<Vec<_>, Error>>()?;
    let mut out = Vec::new();
    for (s, state) in a.states.iter().enumerate() {
        let ops: Vec<&lacuna::constraint::Operator> = a
            .operators
            .iter()
            .filter(|o| o.kind == lacuna::constraint::OpKind::Sub && o.to == s && o.from == s)
            .collect();
        if ops.len() < 2
            || state.dim != m.rows
            || ops.iter().any(|o| o.value.is_none())
            || only.is_some_and(|n| ops.iter().all(|o| o.name != n))
        {
            continue;
        }
        let names: Vec<String> = ops.iter().map(|o| o.name.clone()).collect();
        let mats: Vec<lacuna::algebra::Matrix> =
            ops.iter().filter_map(|o| o.value.clone()).collect();
        out.push((
            state.name.clone(),
            lacuna::analysis::curve_curvature(&names, &mats, &pts, &ts, level.min(16))?,
        ));
    }
    if out.is_empty() {
        return Err(Error::Usage(format!(
            "--points: no curve (a state with two or more known sub-operators onto itself) has {} control points",
            m.rows
        )));
    }
    Ok(out)
}
