//! What the geometry layer is asked and how it fails: the options of an instantiation (degree,
//! Cantor gap, parameter values, template, goals, limits) and the coded errors of the layer.

use crate::constraint::GenOptions;
use crate::topology::Limits;
use num_rational::BigRational;

/// Errors of the geometry layer, each with a stable code (`E10xx`).
#[derive(Debug, thiserror::Error)]
pub enum GeometryError {
    /// An error of the layers below (input, closure, limits).
    #[error(transparent)]
    Lacuna(#[from] crate::Error),
    /// The constraint system has no solution: there is nothing to instantiate.
    #[error("the constraint system has no solution (`lacuna solve` shows the conflict): nothing to instantiate")]
    Inconsistent,
    /// A parameter value was given for a name that is not a free parameter.
    #[error("`{name}` is not a free parameter (`lacuna solve INPUT --params` lists them)")]
    UnknownParameter {
        /// The name given.
        name: String,
    },
    /// The requested level has more cells than the limit allows.
    #[error(
        "level {level} has {cells} cells, above the limit {limit} (raise it with --max-cells)"
    )]
    TooManyCells {
        /// The level asked for.
        level: u32,
        /// The exact number of cells N^C_level.
        cells: String,
        /// The limit in force.
        limit: u64,
    },
    /// The chosen operators break an equation (an internal error: it cannot happen when the
    /// solution space is right).
    #[error("the chosen operators break equation {row} of the constraint system")]
    NotExact {
        /// The row of the linear system.
        row: usize,
    },
    /// The exact hole count disagrees with N^L (an internal error).
    #[error("exact topology: {0}")]
    Topology(String),
    /// The goals of the parameter choice cannot be met (E1031), the LP answer cannot be
    /// rounded to meet them exactly (E1032), or the LP solver failed (E1033).
    #[error("{message}")]
    Goal {
        /// The code.
        code: &'static str,
        /// What went wrong, naming the goal.
        message: String,
    },
    /// A face of one edge: its edge starts and ends at its only corner, so every placement makes
    /// it a loop without area (its Bézier control points at the default degree lie on one segment),
    /// and its cells could not be drawn or measured.
    #[error("face `{face}` has a single edge, which starts and ends at its only corner: it has no area in the plane, so it cannot be placed (give the face at least two edges)")]
    OneEdge {
        /// The face, in notation.
        face: String,
    },
    /// The chosen point of the solution space gives a level-1 cell a control polygon of zero
    /// or negative area in its type's template: a degenerate choice (E1012), or a collapse that
    /// every choice has (E1013); nothing is drawn.
    #[error("the chosen parameters make {cell} degenerate: its control polygon has signed area {area} in the type's template ({advice})")]
    Degenerate {
        /// The cell.
        cell: String,
        /// Its signed area, exactly.
        area: String,
        /// What to do: other parameters, or nothing when the collapse is forced.
        advice: String,
        /// The constraints force the collapse (E1013, a negative verdict: exit 1); else the
        /// choice is at fault (E1012, exit 2).
        forced: bool,
    },
    /// An output file could not be written.
    #[error("cannot write `{path}`: {reason}")]
    Write {
        /// The path.
        path: String,
        /// Why.
        reason: String,
    },
}

impl GeometryError {
    /// As a lacuna error with the same code and message (a lacuna error stays itself).
    pub fn into_error(self) -> crate::Error {
        match self {
            GeometryError::Lacuna(e) => e,
            other => crate::Error::Syntax(Box::new(crate::Diagnostic {
                code: other.code(),
                message: other.to_string(),
                span: None,
                source: None,
            })),
        }
    }

    /// The stable diagnostic code.
    pub fn code(&self) -> &'static str {
        match self {
            GeometryError::Lacuna(e) => e.code(),
            GeometryError::Inconsistent => "E1001",
            GeometryError::UnknownParameter { .. } => "E1002",
            GeometryError::TooManyCells { .. } => "E1003",
            GeometryError::NotExact { .. } => "E1004",
            GeometryError::Write { .. } => "E1005",
            GeometryError::OneEdge { .. } => "E1009",
            GeometryError::Degenerate { forced: false, .. } => "E1012",
            GeometryError::Degenerate { forced: true, .. } => "E1013",
            GeometryError::Topology(_) => "E1006",
            GeometryError::Goal { code, .. } => code,
        }
    }
}

/// How the free parameters and the template are chosen.
#[derive(Clone, Debug)]
pub struct InstantiateOptions {
    /// Bézier degree q of `Bn` edges (as in `lacuna solve --degree`).
    pub degree: usize,
    /// Cantor layout: gap length relative to piece length (as in [`GenOptions`]).
    pub cantor_gap: BigRational,
    /// Parameter values given by name (`T0.T3[2][5]`), fixed before the fit.
    pub values: Vec<(String, BigRational)>,
    /// Weight δ of the reference coordinates against the target positions.
    pub regularization: f64,
    /// Lacuna vertices at this fraction of the distance from the centre to their spoke point.
    pub lacuna_scale: f64,
    /// Gap points at this fraction of the distance from the centre to the gap's middle.
    pub gap_depth: f64,
    /// The fitted parameters are rounded to multiples of `2^-bits`.
    pub bits: u32,
    /// The limits the closure is computed under.
    pub limits: Limits,
    /// A template file (name and text) to project exactly instead of the default fit.
    pub template: Option<crate::Source>,
    /// Inequality goals met through an LP (`crate::geometry::lp`).
    pub goals: Vec<crate::geometry::lp::Goal>,
}

impl InstantiateOptions {
    /// Sets the parameter choice the command line takes as `--template` and `--goal` (Python as
    /// `template` and `goal`): the template file at `template`, read as a source named by its
    /// path, and each goal as [`parse_goal`](crate::geometry::parse_goal) reads it (E1030,
    /// naming `goal_flag`, for one it does not).
    pub fn choose(
        &mut self,
        template: Option<&std::path::Path>,
        goals: &[String],
        goal_flag: &str,
    ) -> Result<(), crate::Error> {
        if let Some(path) = template {
            let text = crate::input::read_text(&path.to_string_lossy())?;
            self.template = Some(crate::Source {
                name: path.display().to_string(),
                text,
            });
        }
        for g in goals {
            let goal = crate::geometry::lp::parse_goal(g).ok_or_else(|| {
                crate::Error::syntax(
                    "E1030",
                    format!("{goal_flag} `{g}`: expected nonnegative, nonnegative=M or min-lacuna=S with exact M, S ≥ 0"),
                    crate::Span {
                        line: 1,
                        col: 1,
                        len: g.chars().count().max(1),
                    },
                    Some(&crate::Source::command_line(g)),
                )
            })?;
            self.goals.push(goal);
        }
        Ok(())
    }
}

impl Default for InstantiateOptions {
    fn default() -> Self {
        InstantiateOptions {
            degree: 2,
            cantor_gap: GenOptions::default().cantor_gap,
            values: Vec::new(),
            regularization: 0.05,
            lacuna_scale: 0.45,
            gap_depth: 0.85,
            bits: 20,
            limits: Limits::default(),
            template: None,
            goals: Vec::new(),
        }
    }
}
