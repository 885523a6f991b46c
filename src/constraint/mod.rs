//! The BC-IFS constraint system: automata (states, operators, words), their generation from a
//! closure, the exact sparse solver over Q with presolve and conflict certificates, and the
//! degeneracy check.
//!
//! Architecture invariant: imports only [`crate::topology`], [`crate::algebra`] and the root
//! utilities; exact throughout.

pub(crate) mod automaton;
pub(crate) mod generate;
pub(crate) mod linsys;
pub(crate) mod presolve;
pub(crate) mod volume;

pub use automaton::{
    solve_automaton, solve_system, Automaton, Constraint, ConstraintKind, Factor, Linearized,
    OpKind, Operator, RowOrigin, SolveReport, State,
};
pub use generate::{
    automaton_of, collapses, collapses_at, degeneracies, solve_closure, Collapses, GenOptions,
    Generated,
};
pub use linsys::{
    forced_equal, solve, write_text, Conflict, Direction, Directions, Equation, LinearSystem,
    Parametrization, Rationals, Solution, SolutionSpace, TextLayout, MINIMIZE_LIMIT,
};
pub use volume::{
    shared_readings, solve_volumes, solve_volumes_with_system, volume_automaton, GeneratedVolumes,
    SharedReading, SolvedVolumes,
};
