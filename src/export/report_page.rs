//! The self-contained HTML report of faces, of an automaton and of volumes, built from the input by one
//! function each: the command line's `lacuna report` and the Python package's `report()` write
//! the page these return.

use crate::analysis::{ContractionReport, CurveCurvature, Resolved};
use crate::error::{Error, Result};
use crate::geometry::{Evaluator, Instance};
use crate::input::{AutomatonModel, Input, VolumeFile};
use crate::topology::volume::VolumeClosure;
use crate::topology::{Closure, Limits};

/// A report page: the HTML and its verdict.
#[derive(Clone, Debug)]
pub struct ReportPage {
    /// The page, self-contained.
    pub html: String,
    /// Whether everything the page checks holds (faces: the verification and the measurement;
    /// an automaton: its constraints with the values drawn; a volume: no two triangles of its
    /// mesh cross).
    pub verified: bool,
    /// What to say beside the page when it is not verified (a volume's crossing triangles).
    pub warning: Option<String>,
}

/// The report of faces: `instance` is their instance (`None` when the closure does not close:
/// the page then says so, with the runaway witness, and has nothing to draw). The verification
/// covers levels 0 to `level` (at least 5); the pictures and measures go to `level`, with a
/// raster of `raster` pixels for box counting and `segments` per Bézier edge.
pub fn faces_report_page(
    input: &Input,
    instance: Option<&Instance>,
    level: u32,
    raster: usize,
    segments: usize,
    limits: &Limits,
) -> Result<ReportPage> {
    let levels = u64::from(level).max(5);
    let Some(inst) = instance else {
        let closure = Closure::of(&input.faces(), limits)?;
        let v = crate::export::verify_report(input, &closure, levels, limits)?;
        return Ok(ReportPage {
            html: crate::export::report_html_unverified(&v),
            verified: false,
            warning: None,
        });
    };
    // The instance's closure is the one `Closure::of` would compute again.
    let closure = Closure::Closed(inst.types.clone());
    let v = crate::export::verify_report(input, &closure, levels, limits)?;
    let opts = crate::measure::MeasureOptions {
        level,
        raster,
        segments,
        ..Default::default()
    };
    let m = crate::measure::measure(inst, &opts).map_err(|e| e.into_error())?;
    Ok(ReportPage {
        html: crate::export::report_html(&v, inst, &m, level, segments),
        verified: v.verified && m.verified,
        warning: None,
    })
}

/// The report of a volume file (one volume or several glued face to face) named `name`: its
/// closure, the exact level-n solid (levels 0 to `level`, at least 3), the level-`level` mesh
/// checked against the exact topology (at most `max_cells` faces,
/// [`MAX_REPORT_FACES`](crate::mesh::MAX_REPORT_FACES) when `None`) with its
/// sizes, a WebGL view and an SVG projection. Verified when no two triangles of the mesh cross
/// (`warning` then says which do).
pub fn volume_report_page(
    name: &str,
    v: &VolumeFile,
    level: u32,
    max_cells: Option<u64>,
    limits: &Limits,
) -> Result<ReportPage> {
    if u64::from(level) > limits.max_level {
        return Err(Error::limit(
            "the level",
            level,
            limits.max_level,
            "--max-level",
        ));
    }
    let c = VolumeClosure::of(&v.assembly.volumes, limits)?;
    let closure_text = crate::export::volume_closure_text("closure", name, &c);
    let VolumeClosure::Closed(set) = c else {
        return Err(Error::Usage(format!(
            "the closure of `{name}` did not close: there is no solid to report"
        )));
    };
    let levels = u64::from(level).max(3);
    let solid =
        crate::topology::volume::solid_topology_of(&set, levels, &v.assembly.start_cells())?;
    let vs = crate::mesh::checked_volume_solid(
        name,
        v,
        &set,
        u64::from(level),
        crate::mesh::DEFAULT_WIDTH,
        max_cells.unwrap_or(crate::mesh::MAX_REPORT_FACES),
        limits,
    )?;
    let sizes = vs.sizes(
        crate::mesh::slice::DEFAULT_LAYERS,
        crate::mesh::DEFAULT_RESOLUTION,
    );
    let mut check = vs.summary();
    check += &sizes.text(crate::mesh::DEFAULT_RESOLUTION);
    let covers = format!(
        "closed, {} volume type{}; the level-{} mesh has the exact cells, components and Euler characteristic of the topology{}",
        set.types.len(),
        if set.types.len() == 1 { "" } else { "s" },
        level,
        match &vs.crossing {
            None => " and no two of its triangles cross",
            Some(_) => ", but two of its triangles cross: see the mesh below",
        }
    );
    let html = crate::export::volume_report_html(
        name,
        (
            vs.crossing.is_none(),
            if vs.crossing.is_none() {
                "VERIFIED"
            } else {
                "NOT VERIFIED"
            },
            &covers,
        ),
        &[
            ("Closure", closure_text),
            (
                "The level-n solid (exact; – where not derived)",
                crate::export::solid_table(&solid),
            ),
            (
                &format!(
                    "The level-{} mesh, checked against the exact topology",
                    level
                ),
                check,
            ),
        ],
        &vs.solid.parts,
    );
    Ok(ReportPage {
        html,
        verified: vs.crossing.is_none(),
        warning: vs.crossing.clone(),
    })
}

/// The text of an input as given: the file's, else the library entry's, else empty (notation).
fn source_text(input: &str) -> String {
    match std::fs::read_to_string(input) {
        Ok(t) => t,
        Err(_) => crate::input::library()
            .iter()
            .find(|(n, _)| *n == input)
            .map_or(String::new(), |(_, t)| t.to_string()),
    }
}

/// The report of an automaton (`input` as given: its file or library text is shown on the
/// page) drawn by `ev` at `level`, its model resolved as `resolved` and its cycles checked as
/// `contraction`: the measures (similarity dimension to 30 digits), the operators' eigen analysis
/// and the pseudo-curvature of its curves.
#[allow(clippy::too_many_arguments)]
pub fn automaton_report_page(
    input: &str,
    name: &str,
    model: &AutomatonModel,
    resolved: &Resolved,
    contraction: &ContractionReport,
    ev: &Evaluator,
    level: u32,
    limits: &Limits,
) -> Result<ReportPage> {
    limits.check_digits(30)?;
    let m = crate::measure::automaton_measure(name, model, resolved, contraction, ev, level, 30);
    let classes = classes_text(model, resolved);
    let curves = report_curves(model, resolved);
    let html = crate::export::automaton_report_html(ev, &m, &classes, &curves, &source_text(input));
    Ok(ReportPage {
        html,
        verified: m.solver.consistent,
        warning: None,
    })
}

/// The operators' eigen analysis (as `lacuna operators` prints it): rational operators over Q,
/// the others over the automaton's field.
fn classes_text(model: &AutomatonModel, resolved: &Resolved) -> String {
    let mut a = model.automaton.clone();
    let mut in_field = vec![None; a.operators.len()];
    for (o, op) in a.operators.iter_mut().enumerate() {
        let k = &resolved.ops[o];
        let data: Option<Vec<_>> = k.data.iter().map(|v| v.as_rational()).collect();
        match data {
            Some(d) => {
                op.value = Some(crate::algebra::Matrix {
                    rows: k.rows,
                    cols: k.cols,
                    data: d,
                })
            }
            None => {
                op.value = None;
                in_field[o] = Some(k.clone());
            }
        }
    }
    match crate::analysis::analyse_automaton_only(&a, None, Some((&model.field, &in_field))) {
        Ok(r) => r.to_text(),
        Err(e) => format!("not analysed: {e}"),
    }
}

/// The pseudo-curvature ranges of the automaton's curves for the report: every reachable state
/// drawn as a polyline with two or more rational subdivision operators onto itself, its control
/// points those of its first node (reached from the start by the shortest word), at the start,
/// the joints, the end and the parameters k/I³ (I operators); samples of level 6.
fn report_curves(
    model: &AutomatonModel,
    resolved: &Resolved,
) -> Vec<(String, std::result::Result<CurveCurvature, String>)> {
    use num_traits::ToPrimitive;
    let m = &model;
    let a = &m.automaton;
    let k = &m.field;
    // Shortest words from the start (breadth first over the control graph).
    let mut word: Vec<Option<Vec<usize>>> = vec![None; a.states.len()];
    word[m.start] = Some(Vec::new());
    let mut queue = std::collections::VecDeque::from([m.start]);
    while let Some(q) = queue.pop_front() {
        for (o, op) in a.operators.iter().enumerate() {
            if op.kind == crate::constraint::OpKind::Sub && op.to == q && word[op.from].is_none() {
                let mut w = word[q].clone().unwrap_or_default();
                w.push(o);
                word[op.from] = Some(w);
                queue.push_back(op.from);
            }
        }
    }
    let approx = |v: &crate::algebra::FieldElement| -> f64 {
        match v.as_rational() {
            Some(q) => q.to_f64().unwrap_or(f64::NAN),
            None => {
                let w =
                    num_rational::BigRational::new(1.into(), num_bigint::BigInt::from(1u64 << 60));
                let (lo, hi) = k.enclosure(v, &w);
                ((lo + hi) / num_rational::BigRational::from_integer(2.into()))
                    .to_f64()
                    .unwrap_or(f64::NAN)
            }
        }
    };
    let mut out = Vec::new();
    for (s, state) in a.states.iter().enumerate() {
        let Some(w) = &word[s] else { continue };
        if !matches!(m.primitives[s], crate::input::Primitive::Polyline(_)) {
            continue;
        }
        let ops: Vec<usize> = (0..a.operators.len())
            .filter(|&o| {
                let op = &a.operators[o];
                op.kind == crate::constraint::OpKind::Sub && op.to == s && op.from == s
            })
            .collect();
        if ops.len() < 2 {
            continue;
        }
        let mats: Option<Vec<crate::algebra::Matrix>> = ops
            .iter()
            .map(|&o| {
                let km = &resolved.ops[o];
                let data: Option<Vec<_>> = km.data.iter().map(|v| v.as_rational()).collect();
                data.map(|d| crate::algebra::Matrix {
                    rows: km.rows,
                    cols: km.cols,
                    data: d,
                })
            })
            .collect();
        let Some(mats) = mats else {
            out.push((
                state.name.clone(),
                Err("operators outside Q: the differential characteristic functions are computed over Q".to_string()),
            ));
            continue;
        };
        let Some(pts) = crate::geometry::exact_points(m, resolved, w) else {
            continue;
        };
        let pts: Vec<Vec<f64>> = pts.iter().map(|q| q.iter().map(approx).collect()).collect();
        let names: Vec<String> = ops.iter().map(|&o| a.operators[o].name.clone()).collect();
        let i = ops.len() as i64;
        let at: Vec<num_rational::BigRational> = (1..i * i * i)
            .filter(|j| j % (i * i) != 0)
            .map(|j| num_rational::BigRational::new(j.into(), (i * i * i).into()))
            .collect();
        out.push((
            state.name.clone(),
            crate::analysis::curve_curvature(&names, &mats, &pts, &at, 6)
                .map_err(|e| e.to_string()),
        ));
    }
    out
}
