//! The report of `lacuna operators` (THEORY §8): the eigen analysis of an automaton's
//! subdivision operators and of matrices given by hand, the curvature estimate at one operator's
//! fixed point and the DCFs and pseudo-curvature ranges of the curves, computed in the order the
//! command line checks them, and its JSON. The command line and the Python package print the same
//! object.

use crate::algebra::matrix::Matrix;
use crate::analysis::{
    analyse_automaton_only, analyse_matrix, curve_curvature, estimate_curvature, parse_matrix_arg,
    AutomatonOperators, CurvatureEstimate, CurveCurvature, OperatorReport,
};
use crate::constraint::{Automaton, OpKind, Operator};
use crate::input::Loaded;
use crate::topology::Limits;
use crate::{Diagnostic, Error};
use num_traits::ToPrimitive;

/// What `lacuna operators` analyses and how.
#[derive(Clone, Debug, Default)]
pub struct OperatorsRequest<'a> {
    /// Matrices given by hand, `[a b; c d]`.
    pub matrices: &'a [String],
    /// The operator whose fixed point's pseudo-curvature range is estimated (needs `points`).
    pub curvature: Option<&'a str>,
    /// Control points of a curve's state, `x y; x y; …`.
    pub points: Option<&'a str>,
    /// Dyadic parameters where the left and right pseudo-curvature ranges are also given.
    pub at: &'a [String],
    /// Word length of the attractor samples.
    pub level: u32,
    /// Only this operator of the automaton.
    pub op: Option<&'a str>,
}

/// What `lacuna operators` found.
#[derive(Debug)]
pub struct OperatorsReport {
    /// The analysis of the automaton's operators, when an input was given.
    pub automaton: Option<AutomatonOperators>,
    /// The analysis of every matrix given by hand, in order.
    pub matrices: Vec<OperatorReport>,
    /// The curvature estimate at the fixed point of the chosen operator.
    pub curvature: Option<CurvatureEstimate>,
    /// The DCFs and pseudo-curvature ranges of every curve, by its state's name.
    pub curves: Vec<(String, CurveCurvature)>,
}

impl OperatorsReport {
    /// The object `lacuna operators --json` prints.
    pub fn to_json(&self) -> serde_json::Value {
        let curves: Vec<serde_json::Value> = self
            .curves
            .iter()
            .map(|(state, c)| serde_json::json!({ "state": state, "curvature": c }))
            .collect();
        serde_json::json!({
            "automaton": self.automaton,
            "matrices": self.matrices,
            "curvature": self.curvature,
            "curves": curves,
        })
    }
}

/// The automaton whose operators `lacuna operators` analyses, with the values over its number
/// field of the operators whose entries lie outside Q (automaton files with a `field` line).
#[derive(Clone, Debug)]
pub struct OperatorsInput {
    /// The automaton (operators over Q have their value).
    pub automaton: Automaton,
    /// The field and every operator's value over it, when the file declares a field.
    pub field: Option<(
        crate::algebra::NumberField,
        Vec<Option<crate::algebra::KMatrix>>,
    )>,
}

/// The automaton whose operators `lacuna operators` analyses: an automaton file's own (with its
/// number field's values), or the instantiated automaton of faces (default parameters, an exact
/// point of the solution space).
pub fn operators_automaton(loaded: Loaded, limits: &Limits) -> Result<OperatorsInput, Error> {
    match loaded {
        Loaded::Automaton {
            automaton, model, ..
        } => Ok(OperatorsInput {
            field: model
                .field_decl
                .is_some()
                .then(|| (model.field.clone(), model.kvalues.clone())),
            automaton,
        }),
        Loaded::Faces(faces) => {
            let mut opts = crate::geometry::InstantiateOptions {
                limits: limits.clone(),
                ..Default::default()
            };
            opts.degree = faces.assembly.coords.degree().unwrap_or(opts.degree);
            let inst = crate::geometry::instantiate(&faces, &opts).map_err(|e| match e {
                crate::geometry::GeometryError::Lacuna(e) => e,
                other => Error::Syntax(Box::new(Diagnostic {
                    code: other.code(),
                    message: other.to_string(),
                    span: None,
                    source: None,
                })),
            })?;
            Ok(OperatorsInput {
                automaton: inst.instantiated_automaton(),
                field: None,
            })
        }
    }
}

/// The analyses of `lacuna operators` on `automaton` (when given) and `request`, every matrix
/// checked against `--max-matrix` before any is analysed.
pub fn operators_report(
    input: Option<&OperatorsInput>,
    request: &OperatorsRequest<'_>,
    limits: &Limits,
) -> Result<OperatorsReport, Error> {
    let automaton = input.map(|i| &i.automaton);
    let field = input.and_then(|i| i.field.as_ref().map(|(k, v)| (k, v.as_slice())));
    // The eigen analysis of a dense n×n matrix grows with n (a 20×20 of random digits takes a
    // fraction of a second, repeated eigenvalues cost more): every matrix is checked against
    // --max-matrix before any is analysed.
    if let Some(a) = automaton {
        for (o, op) in a.operators.iter().enumerate() {
            let known = op.value.is_some()
                || field.is_some_and(|(_, v)| v.get(o).is_some_and(Option::is_some));
            if op.kind == OpKind::Sub && known && op.to == op.from {
                limits.check_matrix(a.states[op.to].dim)?;
            }
        }
    }
    let parsed = request
        .matrices
        .iter()
        .map(|m| parse_matrix_arg(m))
        .collect::<Result<Vec<_>, Error>>()?;
    for m in &parsed {
        limits.check_matrix(m.rows.max(m.cols))?;
    }
    let analysed = automaton
        .map(|a| analyse_automaton_only(a, request.op, field))
        .transpose()?;
    let matrices = parsed
        .iter()
        .map(analyse_matrix)
        .collect::<Result<Vec<_>, Error>>()?;
    let level = request.level;
    let curvature = match (request.curvature, request.points, automaton) {
        (Some(name), Some(pts), Some(a)) => Some(curvature_estimate(a, name, pts, level)?),
        (Some(_), _, None) => {
            return Err(Error::Usage("--curvature needs an automaton file".into()));
        }
        _ => None,
    };
    let curves = match (request.points, automaton, request.curvature) {
        (Some(pts), Some(a), None) => curve_ranges(a, pts, request.at, level, request.op)?,
        (Some(_), None, None) => {
            return Err(Error::Usage(
                "--points needs an automaton file or a face".into(),
            ));
        }
        _ => Vec::new(),
    };
    Ok(OperatorsReport {
        automaton: analysed,
        matrices,
        curvature,
        curves,
    })
}

/// The curvature estimate of `--curvature OP --points …`: the curve is the known `sub`
/// operators from OP's state to itself, in file order.
fn curvature_estimate(
    a: &Automaton,
    name: &str,
    points: &str,
    level: u32,
) -> Result<CurvatureEstimate, Error> {
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
    let curve: Vec<&Operator> = a
        .operators
        .iter()
        .filter(|o| o.kind == OpKind::Sub && o.to == op.to && o.from == op.to && o.value.is_some())
        .collect();
    let Some(index) = curve.iter().position(|o| o.name == name) else {
        return Err(Error::Usage(format!(
            "`{name}` is not a known subdivision operator of its state onto itself"
        )));
    };
    let ops: Vec<Matrix> = curve.iter().filter_map(|o| o.value.clone()).collect();
    let m = parse_matrix_arg(points)?;
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
    estimate_curvature(&ops, index, &pts, level)
}

/// The DCFs and pseudo-curvature ranges of every curve (a state with at least two known
/// sub-operators onto itself, in file order) whose state has as many points as `points` gives;
/// with `--op`, only the curve holding that operator.
fn curve_ranges(
    a: &Automaton,
    points: &str,
    at: &[String],
    level: u32,
    only: Option<&str>,
) -> Result<Vec<(String, CurveCurvature)>, Error> {
    let m = parse_matrix_arg(points)?;
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
            crate::input::parse_rational(t.trim()).ok_or_else(|| {
                Error::Usage(format!("--at {t}: expected an exact number such as 3/8"))
            })
        })
        .collect::<Result<Vec<_>, Error>>()?;
    let mut out = Vec::new();
    for (s, state) in a.states.iter().enumerate() {
        let ops: Vec<&Operator> = a
            .operators
            .iter()
            .filter(|o| o.kind == OpKind::Sub && o.to == s && o.from == s)
            .collect();
        if ops.len() < 2
            || state.dim != m.rows
            || ops.iter().any(|o| o.value.is_none())
            || only.is_some_and(|n| ops.iter().all(|o| o.name != n))
        {
            continue;
        }
        let names: Vec<String> = ops.iter().map(|o| o.name.clone()).collect();
        let mats: Vec<Matrix> = ops.iter().filter_map(|o| o.value.clone()).collect();
        out.push((
            state.name.clone(),
            curve_curvature(&names, &mats, &pts, &ts, level.min(16))?,
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

/// What `lacuna design` found: the operator of the chosen eigenvalues and eigenvectors, its eigen
/// analysis and, when asked, the check of plugging it into an automaton.
#[derive(Debug)]
pub struct DesignReport {
    /// T = V·D·V⁻¹, exact.
    pub matrix: Matrix,
    /// Its eigen analysis.
    pub analysis: OperatorReport,
    /// The check against an automaton's operator (`--check FILE --op NAME`).
    pub check: Option<crate::analysis::DesignCheck>,
}

impl DesignReport {
    /// The object `lacuna design --json` prints.
    pub fn to_json(&self) -> serde_json::Value {
        serde_json::json!({
            "matrix": self.matrix.to_string(),
            "analysis": self.analysis,
            "check": self.check,
        })
    }
}

/// The operator of `lacuna design --eigenvalues V --eigenvectors M` (one eigenvector per row, in
/// the order of the eigenvalues) and its eigen analysis; no check yet.
pub fn design_report(eigenvalues: &str, eigenvectors: &str) -> Result<DesignReport, Error> {
    let values = crate::analysis::parse_rationals_arg(eigenvalues)?;
    let vectors = parse_matrix_arg(eigenvectors)?;
    let rows: Vec<Vec<_>> = vectors
        .data
        .chunks(vectors.cols)
        .map(<[_]>::to_vec)
        .collect();
    let matrix = crate::analysis::design_operator(&values, &rows)?;
    let analysis = analyse_matrix(&matrix)?;
    Ok(DesignReport {
        matrix,
        analysis,
        check: None,
    })
}
