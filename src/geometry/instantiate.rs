//! Instantiation of a verified structure (THEORY §7): values for the free parameters of the exact
//! solution space, control points in the plane, and the depth-first evaluation of the attractor.
//!
//! **Choosing the parameters.** Every face type gets a *template*: its control points on a regular
//! polygon (corners at the vertices, Bézier inner points evenly on the straight edges) and, for
//! each sub-face, the target position of each of its control points: pieces of the boundary where
//! the edge operators put them, the spoke points at the joints and corners, a gap point just
//! inside each gap, the lacuna vertices on a shrunken concentric polygon, and inner points of
//! `Ea`, `El`, `Ec` evenly on the straight segment between their ends. The unknowns are the
//! barycentric columns of the sub-face operators; for each column `c` (target `y`, reference
//! coordinates `r` = the mean value coordinates of `y` in the template polygon) the objective is
//! `|P·c − y|² + δ·|c − r|²`. Over the affine solution space `x = particular + B·t` this is a
//! positive definite quadratic in the free parameters `t`; its minimiser is computed in floating
//! point, **rounded to rationals** of denominator `2^bits`, and the unknowns are then formed
//! exactly as `particular + B·t` over Q. So the chosen operators satisfy every equation of the
//! system exactly whatever the rounding — [`Instance::check_exact`] re-checks every row — and
//! floating point only decides *which* exact solution is shown. Parameters given by name are fixed
//! to the given rationals before the fit. The choice itself lives in `crate::geometry::choose`: also the
//! exact projection of a user template (`--template`, `crate::geometry::template_file`) and inequality goals
//! through an LP (`--goal`, `crate::geometry::lp`).

use crate::geometry::level_one::{self, LevelOne};
use crate::geometry::options::{GeometryError, InstantiateOptions};
use crate::geometry::placement::StartFace;
use crate::geometry::point::{bezier_point, Point};
use crate::geometry::template::dim_of;
use crate::{
    constraint::automaton_of, constraint::solve, constraint::GenOptions, constraint::Generated,
    constraint::Linearized, constraint::Solution, input::Input, topology::close_or_error,
    topology::EdgeKind, topology::Face, topology::Origin, topology::TypeSet,
};
use num_rational::BigRational;
use num_traits::{ToPrimitive, Zero};

/// One boundary edge of a face state: its first control point, number of points, Bézier or not.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EdgeSlot {
    /// Index of its first control point in the face's points.
    pub offset: usize,
    /// Number of control points (q + 1 for `Bn`, 2 for `Cn`).
    pub dim: usize,
    /// Whether the edge is drawn as a Bézier curve (`Bn`) or as a segment (`Cn`).
    pub bezier: bool,
}

/// Where a sub-face edge's flag "on the boundary of the union" comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum FlagSource {
    Parent(usize),
    Shared,
    Free,
}

/// A verified structure with chosen operators and control points, ready to evaluate.
#[derive(Clone, Debug)]
pub struct Instance {
    /// The input's name.
    pub name: String,
    /// The closure.
    pub types: TypeSet,
    /// The generated automaton.
    pub generated: Generated,
    /// Its linear system.
    pub linearized: Linearized,
    /// The options the constraints were generated with (Bézier degree, Cantor gap).
    pub options: GenOptions,
    /// The exact value of every unknown.
    pub values: Vec<BigRational>,
    /// The free parameters by name with their chosen values.
    pub parameters: Vec<(String, BigRational)>,
    /// Root-mean-square distance between the chosen level-1 control points and the template.
    pub fit_residual: f64,
    /// How the parameters were chosen (method, exact residual, goals).
    pub choice: crate::geometry::choose::Choice,
    /// The exact level-1 check of the chosen point ([`Instance::level_one`]).
    pub level_one: LevelOne,
    /// The start faces in the plane.
    pub start: Vec<StartFace>,
    /// The assembly's shared edges as (start face, canonical edge index) pairs (exact components).
    pub glue: Vec<crate::topology::component::Glue>,
    /// Per type, per boundary edge.
    pub slots: Vec<Vec<EdgeSlot>>,
    /// Per type: number of control points.
    pub dims: Vec<usize>,
    /// Per type and sub-face: the operator in floating point, row-major (m_t × m_w).
    ops: Vec<Vec<Vec<f64>>>,
    flags: Vec<Vec<Vec<FlagSource>>>,
}

/// A cell met by [`Instance::walk`].
#[derive(Clone, Copy, Debug)]
pub struct Cell<'a> {
    /// Face type.
    pub ty: usize,
    /// Level of the cell.
    pub depth: u32,
    /// Control points.
    pub points: &'a [Point],
    /// For each boundary edge: whether it lies on the boundary of the union of the cells of its
    /// level (derived from the topology, not from coordinates).
    pub free: &'a [bool],
}

fn slots_of(face: &Face, q: usize) -> Vec<EdgeSlot> {
    let mut off = 0;
    face.boundary
        .iter()
        .map(|e| {
            let d = dim_of(e, q);
            let s = EdgeSlot {
                offset: off,
                dim: d,
                bezier: e.kind == EdgeKind::B,
            };
            off += d - 1;
            s
        })
        .collect()
}

fn to_f64(r: &BigRational) -> f64 {
    r.to_f64().unwrap_or(f64::NAN)
}

/// Instantiates an input: closes it, solves its constraint system exactly, chooses the free
/// parameters (see the module documentation) and places the start faces.
/// When the fitted point makes a level-1 cell degenerate that the constraints do not force to
/// be, the automatic area goal moves it (`crate::geometry::level_one`); the exact level-1 check
/// then runs on the point chosen.
pub fn instantiate(input: &Input, opt: &InstantiateOptions) -> Result<Instance, GeometryError> {
    let (inst, checked) = build(input, opt, true)?;
    let level_one = checked.expect("the level-1 check runs when the fit may be moved")?;
    Ok(Instance { level_one, ..inst })
}

/// [`instantiate`] without the exact level-1 check of the chosen point ([`Instance::level_one`])
/// and without moving a degenerate fit: for a caller that reports a degenerate choice as a
/// finding of its own (a frame of a morph that passes through a collapse), not as an error.
pub fn instantiate_unchecked(
    input: &Input,
    opt: &InstantiateOptions,
) -> Result<Instance, GeometryError> {
    build(input, opt, false).map(|(inst, _)| inst)
}

/// The instance, and with `lift` the exact level-1 check of its chosen point (done by the
/// choice, which moves a degenerate fit first).
type Built = (Instance, Option<Result<LevelOne, GeometryError>>);

fn build(input: &Input, opt: &InstantiateOptions, lift: bool) -> Result<Built, GeometryError> {
    let q = opt.degree.max(1);
    let faces = input.faces();
    // A one-edge face has no placement with area (issue #20 item 3): refused before the work.
    if let Some(f) = faces.iter().find(|f| f.boundary.len() == 1) {
        return Err(GeometryError::OneEdge {
            face: f.to_string(),
        });
    }
    let types = close_or_error(&faces, &opt.limits)?;
    if let Some(t) = types.types.iter().find(|t| t.face.boundary.len() == 1) {
        return Err(GeometryError::OneEdge {
            face: t.face.to_string(),
        });
    }
    let options = GenOptions {
        degree: q,
        cantor_gap: opt.cantor_gap.clone(),
    };
    let generated = automaton_of(&types, options.clone());
    let a = &generated.automaton;
    // The solve's size is known from the automaton's shapes: refuse it before the work.
    a.check_solve_limits(&opt.limits)?;
    let lin = a.linearize()?;
    let Solution::Consistent(space) = solve(&lin.system) else {
        return Err(GeometryError::Inconsistent);
    };
    let param = space.parametrize();
    let dof = space.free.len();
    let names: Vec<String> = space
        .free
        .iter()
        .map(|&f| a.entry_name(lin.unknown_entries[f]))
        .collect();
    // Fixed parameters (given by name).
    let mut fixed: Vec<Option<BigRational>> = vec![None; dof];
    for (name, v) in &opt.values {
        let k = names
            .iter()
            .position(|n| n == name)
            .ok_or_else(|| GeometryError::UnknownParameter { name: name.clone() })?;
        fixed[k] = Some(v.clone());
    }
    let cx = crate::geometry::choose::Context {
        types: &types,
        generated: &generated,
        lin: &lin,
        param: &param,
        fixed: &fixed,
        q,
        lift,
    };
    let (tq, choice, checked) = crate::geometry::choose::choose(&cx, opt)?;
    let values = crate::geometry::choose::unknowns_at(&param, lin.system.unknowns, &tq);
    let fit_residual = choice.rms;
    let parameters = names.into_iter().zip(tq).collect();
    let slots: Vec<Vec<EdgeSlot>> = types.types.iter().map(|t| slots_of(&t.face, q)).collect();
    let dims: Vec<usize> = generated
        .face_state
        .iter()
        .map(|&s| a.states[s].dim)
        .collect();
    let mut ops = Vec::new();
    let mut flags = Vec::new();
    for (t, ty) in types.types.iter().enumerate() {
        let mut tops = Vec::new();
        let mut tflags = Vec::new();
        for (k, &w) in ty.children.iter().enumerate() {
            let base = lin.offsets[generated.sub_ops[t][k]].expect("unknown");
            let len = dims[t] * dims[w];
            tops.push(values[base..base + len].iter().map(to_f64).collect());
            tflags.push(
                ty.subdivision.subfaces[k]
                    .origins
                    .iter()
                    .map(|o| match *o {
                        Origin::Piece { edge, .. } => FlagSource::Parent(edge),
                        Origin::Spoke { .. } => FlagSource::Shared,
                        Origin::Lacuna { .. } | Origin::GapSide { .. } => FlagSource::Free,
                    })
                    .collect(),
            );
        }
        ops.push(tops);
        flags.push(tflags);
    }
    let start = crate::geometry::placement::place(input, &types, q)?;
    let inst = Instance {
        name: input.name.clone(),
        types,
        generated,
        linearized: lin,
        options,
        values,
        parameters,
        fit_residual,
        choice,
        level_one: LevelOne::default(),
        start,
        glue: input.assembly.canonical_glue(),
        slots,
        dims,
        ops,
        flags,
    };
    inst.check_exact()?;
    Ok((inst, checked))
}

impl Instance {
    /// The default template of the instance in the template file format (what
    /// `lacuna render INPUT --write-template FILE` writes).
    pub fn default_template(&self, opt: &InstantiateOptions) -> String {
        use crate::geometry::template_file::{write_template, ExactTemplate};
        let q = opt.degree.max(1);
        let floats: Vec<crate::geometry::template::Template> = self
            .types
            .types
            .iter()
            .map(|ty| crate::geometry::template::template(ty, &self.types, q, opt))
            .collect();
        let exact = ExactTemplate::rounded(&self.types, &floats, q);
        write_template(&self.name, &self.types, q, &exact)
    }

    /// The exact level-1 check of the chosen point in each type's default template under `opt`
    /// (its control points rounded to dyadic rationals): every sub-face's and every central
    /// lacuna's control polygon has positive signed area (`crate::geometry::level_one`). A cell of
    /// zero or negative area is a degenerate choice (E1012) or a forced collapse (E1013),
    /// refused before any drawing.
    pub fn level_one(&self, opt: &InstantiateOptions) -> Result<LevelOne, GeometryError> {
        let q = opt.degree.max(1);
        let frames = level_one::frames(&self.types, q, opt);
        let cells = level_one::cells(&self.types, &self.generated, &self.linearized);
        level_one::check(&cells, &frames, &self.values)
    }

    /// Re-checks every equation of the constraint system on the chosen values, exactly over Q.
    pub fn check_exact(&self) -> Result<(), GeometryError> {
        for (row, eq) in self.linearized.system.equations().enumerate() {
            let mut s = -eq.rhs.clone();
            for (x, c) in &eq.terms {
                s += c * &self.values[*x];
            }
            if !s.is_zero() {
                return Err(GeometryError::NotExact { row });
            }
        }
        Ok(())
    }

    /// The exact matrix of sub-face operator `k` of type `t` (m_t × m_w, row-major).
    /// The automaton with every unknown operator replaced by its chosen exact value (the
    /// instantiated automaton analysed by `lacuna operators`).
    pub fn instantiated_automaton(&self) -> crate::constraint::Automaton {
        let mut a = self.generated.automaton.clone();
        for (o, op) in a.operators.iter_mut().enumerate() {
            if let Some(base) = self.linearized.offsets[o] {
                let (r, c) = (
                    self.generated.automaton.states[op.to].dim,
                    self.generated.automaton.states[op.from].dim,
                );
                op.value = Some(crate::algebra::Matrix {
                    rows: r,
                    cols: c,
                    data: self.values[base..base + r * c].to_vec(),
                });
            }
        }
        a
    }

    /// The exact entries of the sub-face operator `T_k` of type `t`, row-major.
    pub fn operator_exact(&self, t: usize, k: usize) -> &[BigRational] {
        let w = self.types.types[t].children[k];
        let base = self.linearized.offsets[self.generated.sub_ops[t][k]].expect("unknown");
        &self.values[base..base + self.dims[t] * self.dims[w]]
    }

    /// Visits the cells depth-first down to `level` (every depth when `all_depths`, else only the
    /// cells of `level`), in a deterministic order. Memory grows with the level and the number of
    /// sub-faces per type, not with the number of cells.
    pub fn walk(&self, level: u32, all_depths: bool, mut visit: impl FnMut(&Cell)) {
        let mut stack: Vec<(usize, u32, Vec<Point>, Vec<bool>)> = Vec::new();
        let mut spare_pts: Vec<Vec<Point>> = Vec::new();
        let mut spare_flags: Vec<Vec<bool>> = Vec::new();
        for s in self.start.iter().rev() {
            stack.push((s.ty, 0, s.points.clone(), s.free.clone()));
        }
        while let Some((t, depth, pts, free)) = stack.pop() {
            if all_depths || depth == level {
                visit(&Cell {
                    ty: t,
                    depth,
                    points: &pts,
                    free: &free,
                });
            }
            if depth < level {
                let m_t = self.dims[t];
                let ty = &self.types.types[t];
                for k in (0..ty.children.len()).rev() {
                    let w = ty.children[k];
                    let m_w = self.dims[w];
                    let op = &self.ops[t][k];
                    let mut child = spare_pts.pop().unwrap_or_default();
                    child.clear();
                    for i in 0..m_w {
                        let (mut x, mut y) = (0.0, 0.0);
                        for (j, p) in pts.iter().enumerate().take(m_t) {
                            let v = op[j * m_w + i];
                            x += v * p[0];
                            y += v * p[1];
                        }
                        child.push([x, y]);
                    }
                    let mut cf = spare_flags.pop().unwrap_or_default();
                    cf.clear();
                    cf.extend(self.flags[t][k].iter().map(|f| match *f {
                        FlagSource::Parent(e) => free[e],
                        FlagSource::Shared => false,
                        FlagSource::Free => true,
                    }));
                    stack.push((w, depth + 1, child, cf));
                }
            }
            spare_pts.push(pts);
            spare_flags.push(free);
        }
    }

    /// The boundary flags of sub-face `k` of a cell of type `t` whose edges have flags `free`
    /// (pieces inherit their parent edge's flag, spokes are shared, lacuna and gap sides free).
    pub fn child_free(&self, t: usize, k: usize, free: &[bool]) -> Vec<bool> {
        self.flags[t][k]
            .iter()
            .map(|f| match *f {
                FlagSource::Parent(e) => free[e],
                FlagSource::Shared => false,
                FlagSource::Free => true,
            })
            .collect()
    }

    /// The control points of boundary edge `e` of a cell of type `t`.
    pub fn edge_controls(&self, t: usize, e: usize, points: &[Point]) -> Vec<Point> {
        let s = self.slots[t][e];
        let m = points.len();
        (0..s.dim).map(|c| points[(s.offset + c) % m]).collect()
    }

    /// The polyline of boundary edge `e` of a cell (both ends included): a Bézier edge flattened to
    /// `segments` segments, a Cantor edge as the segment between its end points.
    pub fn edge_polyline(
        &self,
        t: usize,
        e: usize,
        points: &[Point],
        segments: usize,
    ) -> Vec<Point> {
        let ctrl = self.edge_controls(t, e, points);
        if self.slots[t][e].bezier && segments > 1 {
            (0..=segments)
                .map(|i| bezier_point(&ctrl, i as f64 / segments as f64))
                .collect()
        } else {
            vec![ctrl[0], ctrl[ctrl.len() - 1]]
        }
    }

    /// The closed polygon of a cell (its edges' polylines, each end point once).
    pub fn cell_polygon(&self, t: usize, points: &[Point], segments: usize) -> Vec<Point> {
        let mut poly = Vec::new();
        for e in 0..self.slots[t].len() {
            let mut pl = self.edge_polyline(t, e, points, segments);
            pl.pop();
            poly.extend(pl);
        }
        poly
    }
}
