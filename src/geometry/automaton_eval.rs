//! The attractor of an automaton, drawn: the evaluation tree of the BC-IFS paper walked to level n
//! from the start state's control points, each node's points `F · T_(w1) ⋯ T_(wn)`, each leaf drawn
//! as its state's primitive. Streamed depth-first in `f64` (floats draw, they never decide);
//! [`exact_points`] gives the exact points of one word, in the field, for checks.

use crate::algebra::algebraic::FieldElement;
use crate::algebra::algebraic::NumberField;
use crate::algebra::kmatrix::KMatrix;
use crate::analysis::{default_points, Resolved};
use crate::constraint::automaton::OpKind;
use crate::input::automaton_model::{AutomatonModel, Primitive};
use serde::Serialize;

/// What a drawn piece is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum ShapeKind {
    /// A point.
    Point,
    /// An open polyline.
    Polyline,
    /// A closed polygon.
    Polygon,
}

/// One drawn piece: its state, kind and points (`[x, y, z]`, z = 0 in the plane).
#[derive(Clone, Debug, Serialize)]
pub struct Shape {
    /// The state's index.
    pub state: usize,
    /// Its kind.
    pub kind: ShapeKind,
    /// Its points.
    pub points: Vec<[f64; 3]>,
}

/// A float approximation of a field element (for drawing only: never for a verdict).
pub fn approx(k: &NumberField, v: &FieldElement) -> f64 {
    k.approx(v)
}

/// A subdivision operator out of a state: its value row-major, rows, columns, target state.
type Edge = (Vec<f64>, usize, usize, usize);

/// The automaton ready to draw: float operators, the start points, primitives.
#[derive(Clone, Debug)]
pub struct Evaluator {
    /// The modelling space's dimension (2 or 3).
    pub space: usize,
    /// State names.
    pub names: Vec<String>,
    start: usize,
    start_points: Vec<[f64; 3]>,
    /// `out[q]`: (operator value row-major, rows, cols, target state w) of each `T: q ← w`.
    out: Vec<Vec<Edge>>,
    primitives: Vec<Primitive>,
}

impl Evaluator {
    /// Prepares the drawing of a model whose operators were resolved.
    pub fn new(m: &AutomatonModel, r: &Resolved) -> Self {
        let a = &m.automaton;
        let k = &m.field;
        let pts = m
            .points
            .clone()
            .unwrap_or_else(|| default_points(a.states[m.start].dim, m.space, k));
        let start_points = pts
            .iter()
            .map(|p| {
                let mut x = [0.0; 3];
                for (d, v) in p.iter().enumerate() {
                    x[d] = approx(k, v);
                }
                x
            })
            .collect();
        let mut out = vec![Vec::new(); a.states.len()];
        for (o, op) in a.operators.iter().enumerate() {
            if op.kind == OpKind::Sub {
                out[op.to].push((
                    r.ops[o].data.iter().map(|v| approx(k, v)).collect(),
                    r.ops[o].rows,
                    r.ops[o].cols,
                    op.from,
                ));
            }
        }
        Evaluator {
            space: m.space,
            names: a.states.iter().map(|s| s.name.clone()).collect(),
            start: m.start,
            start_points,
            out,
            primitives: m.primitives.clone(),
        }
    }

    /// The same automaton drawn from another state: the attractor of `state`, from its frame.
    /// The frames are those of the exact side ([`crate::analysis::frames`]), in `f64` with the
    /// evaluator's own operators: the start state's points, then `F_w = F_q · T` along the first
    /// subdivision operator `T: q ← w` reaching w breadth first (the operators of a state in
    /// index order). The start state gives the evaluator back unchanged. A state that is not
    /// there, or that the start does not reach, is a usage error (E0504) naming the reachable
    /// states.
    pub fn with_start(self, state: &str) -> crate::error::Result<Self> {
        let frames = self.frames();
        let reachable: Vec<&str> = (0..self.names.len())
            .filter(|&q| frames[q].is_some())
            .map(|q| self.names[q].as_str())
            .collect();
        let Some(w) = self.names.iter().position(|n| n == state) else {
            return Err(crate::error::Error::Usage(format!(
                "`{state}` is not a state of this automaton: its states reachable from the start `{}` are {}",
                self.names[self.start],
                reachable.join(", ")
            )));
        };
        let Some(points) = frames[w].clone() else {
            return Err(crate::error::Error::Usage(format!(
                "the state `{state}` is not reachable from the start `{}`: it has no frame to be drawn from; the reachable states are {}",
                self.names[self.start],
                reachable.join(", ")
            )));
        };
        if w == self.start {
            return Ok(self);
        }
        Ok(Evaluator {
            start: w,
            start_points: points,
            ..self
        })
    }

    /// The index of the state drawn (the start state, or the one [`Evaluator::with_start`] chose).
    pub fn start(&self) -> usize {
        self.start
    }

    /// The frame (control points) of every state reachable from the start, in `f64`: the start
    /// state's points, then `F_w = F_q · T` along the first operator reaching w breadth first.
    fn frames(&self) -> Vec<Option<Vec<[f64; 3]>>> {
        let mut frames: Vec<Option<Vec<[f64; 3]>>> = vec![None; self.out.len()];
        frames[self.start] = Some(self.start_points.clone());
        let mut queue = std::collections::VecDeque::from([self.start]);
        while let Some(q) = queue.pop_front() {
            for edge in &self.out[q] {
                let w = edge.3;
                if frames[w].is_none() {
                    let f = child_points(frames[q].as_ref().expect("visited"), edge);
                    frames[w] = Some(f);
                    queue.push_back(w);
                }
            }
        }
        frames
    }

    /// The number of leaves at level n (a state without subdivision operators is a leaf where it
    /// is reached), saturating; computed before any walk.
    pub fn count(&self, level: u32) -> u128 {
        let n = self.out.len();
        let mut v = vec![0u128; n];
        v[self.start] = 1;
        let mut leaves = 0u128;
        for _ in 0..level {
            let mut next = vec![0u128; n];
            for (q, &c) in v.iter().enumerate() {
                if c == 0 {
                    continue;
                }
                if self.out[q].is_empty() {
                    leaves = leaves.saturating_add(c);
                }
                for (_, _, _, w) in &self.out[q] {
                    next[*w] = next[*w].saturating_add(c);
                }
            }
            v = next;
        }
        v.iter().fold(leaves, |acc, x| acc.saturating_add(*x))
    }

    /// Calls `f(state, depth, points)` for every leaf of the evaluation tree at level n.
    pub fn walk<F: FnMut(usize, u32, &[[f64; 3]])>(&self, level: u32, f: &mut F) {
        let mut stack: Vec<(usize, u32, Vec<[f64; 3]>)> =
            vec![(self.start, 0, self.start_points.clone())];
        while let Some((q, d, pts)) = stack.pop() {
            if d == level || self.out[q].is_empty() {
                f(q, d, &pts);
                continue;
            }
            for edge in self.out[q].iter().rev() {
                stack.push((edge.3, d + 1, child_points(&pts, edge)));
            }
        }
    }

    /// True when a state has no subdivision operator: its shape is drawn as it is at every level
    /// (a rule's infertile segment), not an approximation still to be refined.
    pub fn is_terminal(&self, state: usize) -> bool {
        self.out[state].is_empty()
    }

    /// The primitive of a leaf as a shape (`None` for `none`).
    pub fn shape(&self, state: usize, pts: &[[f64; 3]]) -> Option<Shape> {
        let pick = |idx: &[usize]| idx.iter().map(|&i| pts[i]).collect::<Vec<_>>();
        let (kind, points) = match &self.primitives[state] {
            Primitive::Point(i) => (ShapeKind::Point, vec![pts[*i]]),
            Primitive::Polyline(v) => (ShapeKind::Polyline, pick(v)),
            Primitive::Polygon(v) => (ShapeKind::Polygon, pick(v)),
            Primitive::Nothing => return None,
        };
        Some(Shape {
            state,
            kind,
            points,
        })
    }

    /// Every shape at level n, in the order of the walk.
    pub fn shapes(&self, level: u32) -> Vec<Shape> {
        let mut v = Vec::new();
        self.walk(level, &mut |q, _, pts| {
            if let Some(s) = self.shape(q, pts) {
                v.push(s);
            }
        });
        v
    }
}

/// The points `F · T` of the node an operator leads to, from the points `F` of its parent (the
/// columns of F; T's entry (i, j) weighs the parent's point i in the child's point j).
fn child_points(pts: &[[f64; 3]], (t, rows, cols, _): &Edge) -> Vec<[f64; 3]> {
    let mut child = vec![[0.0; 3]; *cols];
    for (j, c) in child.iter_mut().enumerate() {
        for i in 0..*rows {
            let a = t[i * cols + j];
            if a != 0.0 {
                for x in 0..3 {
                    c[x] += a * pts[i][x];
                }
            }
        }
    }
    child
}

/// An automaton made ready to draw at `level`: its unknowns resolved with the parameter
/// `values`, its contraction proved within `limits.max_products`, and the pieces of the level
/// counted against `max_cells` before any drawing (E0501). The command line's `render`,
/// `measure` and `report` and the Python package all prepare an automaton here.
pub fn prepare_automaton(
    m: &AutomatonModel,
    values: &[(String, num_rational::BigRational)],
    level: u32,
    max_cells: u64,
    limits: &crate::topology::Limits,
) -> crate::error::Result<(Resolved, crate::analysis::ContractionReport, Evaluator)> {
    prepare_automaton_at(m, None, values, level, max_cells, limits)
}

/// [`prepare_automaton`] drawing the attractor of `state` (by name; `None`: the start state)
/// from its frame ([`Evaluator::with_start`]): the pieces counted are that state's, and a state
/// the start does not reach is refused (E0504) before anything is counted.
pub fn prepare_automaton_at(
    m: &AutomatonModel,
    state: Option<&str>,
    values: &[(String, num_rational::BigRational)],
    level: u32,
    max_cells: u64,
    limits: &crate::topology::Limits,
) -> crate::error::Result<(Resolved, crate::analysis::ContractionReport, Evaluator)> {
    limits.check_level(u64::from(level))?;
    let resolved = crate::analysis::resolve(m, values, limits.max_unknowns)?;
    let contraction =
        crate::analysis::check_contraction_within(m, &resolved.ops, limits.max_products)?;
    let ev = Evaluator::new(m, &resolved);
    let ev = match state {
        Some(name) => ev.with_start(name)?,
        None => ev,
    };
    let count = ev.count(level);
    if count > u128::from(max_cells) {
        return Err(crate::error::Error::limit(
            "the pieces of the level",
            count,
            max_cells,
            "--max-cells",
        ));
    }
    Ok((resolved, contraction, ev))
}

/// The model drawn from another state: `state` becomes the start and its exact frame
/// ([`crate::analysis::frames`], `F_w = F_q · T` breadth first from the start's points) its
/// control points, so that [`exact_points`] and [`exact_polygons`] walk that state's attractor
/// as [`Evaluator::with_start`] draws it. `None` when the start does not reach `state`.
pub fn restarted(m: &AutomatonModel, r: &Resolved, state: usize) -> Option<AutomatonModel> {
    if state == m.start {
        return Some(m.clone());
    }
    let f = crate::analysis::frames(m, &r.ops).get(state)?.clone()?;
    let points = (0..f.cols)
        .map(|c| (0..f.rows).map(|d| f.get(d, c).clone()).collect())
        .collect();
    Some(AutomatonModel {
        start: state,
        points: Some(points),
        ..m.clone()
    })
}

/// The model `ev` draws when it starts at another state than `m`'s start (`render --state`,
/// `measure --state`): `m` [`restarted`] there; `None` when it starts at `m`'s start.
pub fn evaluated_model(m: &AutomatonModel, r: &Resolved, ev: &Evaluator) -> Option<AutomatonModel> {
    (ev.start() != m.start).then(|| {
        // `Evaluator::with_start` refuses a state the start does not reach.
        restarted(m, r, ev.start()).expect("the evaluator's start is reachable")
    })
}

/// The exact control points (columns of `space × m`) of the node reached from the start by the
/// operators `word` (each `T: q ← w` continuing from state q); `None` when the word does not
/// follow the control graph.
pub fn exact_points(
    m: &AutomatonModel,
    r: &Resolved,
    word: &[usize],
) -> Option<Vec<Vec<FieldElement>>> {
    let a = &m.automaton;
    let k = &m.field;
    let pts = m
        .points
        .clone()
        .unwrap_or_else(|| default_points(a.states[m.start].dim, m.space, k));
    let mut f = KMatrix {
        rows: m.space,
        cols: pts.len(),
        data: (0..m.space)
            .flat_map(|d| pts.iter().map(move |p| p[d].clone()))
            .collect(),
    };
    let mut state = m.start;
    for &o in word {
        let op = a.operators.get(o)?;
        if op.to != state || op.kind != OpKind::Sub {
            return None;
        }
        f = f.mul(k, &r.ops[o])?;
        state = op.from;
    }
    Some(
        (0..f.cols)
            .map(|c| (0..f.rows).map(|d| f.get(d, c).clone()).collect())
            .collect(),
    )
}

/// The exact polygon leaves of level n (the walk of [`Evaluator::walk`], in the field): for every
/// leaf whose primitive is a polygon, its corners as exact points (`space` coordinates each).
/// `None` when the level has more than `max_leaves` leaves (checked before the walk).
pub fn exact_polygons(
    m: &AutomatonModel,
    r: &Resolved,
    level: u32,
    max_leaves: u128,
) -> Option<Vec<Vec<Vec<FieldElement>>>> {
    let a = &m.automaton;
    let k = &m.field;
    if Evaluator::new(m, r).count(level) > max_leaves {
        return None;
    }
    let pts = m
        .points
        .clone()
        .unwrap_or_else(|| default_points(a.states[m.start].dim, m.space, k));
    let start = KMatrix {
        rows: m.space,
        cols: pts.len(),
        data: (0..m.space)
            .flat_map(|d| pts.iter().map(move |p| p[d].clone()))
            .collect(),
    };
    let mut out_ops: Vec<Vec<usize>> = vec![Vec::new(); a.states.len()];
    for (o, op) in a.operators.iter().enumerate() {
        if op.kind == OpKind::Sub {
            out_ops[op.to].push(o);
        }
    }
    let mut polys = Vec::new();
    let mut stack: Vec<(usize, u32, KMatrix)> = vec![(m.start, 0, start)];
    while let Some((q, d, f)) = stack.pop() {
        if d == level || out_ops[q].is_empty() {
            if let Primitive::Polygon(idx) = &m.primitives[q] {
                polys.push(
                    idx.iter()
                        .map(|&c| (0..f.rows).map(|x| f.get(x, c).clone()).collect())
                        .collect(),
                );
            }
            continue;
        }
        for &o in out_ops[q].iter().rev() {
            let child = f.mul(k, &r.ops[o])?;
            stack.push((a.operators[o].from, d + 1, child));
        }
    }
    Some(polys)
}
