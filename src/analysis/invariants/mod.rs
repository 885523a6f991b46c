//! Invariants and topological classes (THEORY §13): the exact invariants of faces, volumes and
//! automata and the comparison of two structures ([`classes`]), and the exact limit shares of
//! the valences ([`shares`]) that the invariants of a face end with.
//!
//! The shares stand on the limit ratio's spectral tools ([`crate::analysis::ratio`]); the
//! invariants of an automaton on its resolved operators ([`crate::analysis::automata`]).

pub(crate) mod automaton;
pub(crate) mod classes;
pub(crate) mod shares;
