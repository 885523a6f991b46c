//! lacuna: a symbolic constraint solver and formal verifier for fractal topology (BC-IFS).
//!
//! The crate is cut into layers, one folder each, and imports only go downward (see
//! `docs/ARCHITECTURE.md`; `tests/architecture.rs` enforces it):
//!
//! | layer | what it holds |
//! | --- | --- |
//! | [`topology`] | edges, faces, spoke rules, subdivision, closure, classes, counts (never a float) |
//! | [`algebra`] | polynomials, factoring, real algebraic numbers, number fields, exact matrices |
//! | [`constraint`] | automata, their generation from closures, the exact sparse solver |
//! | [`input`] | the library, assembly, AutoFrac2D and automaton files, user coordinates |
//! | [`analysis`] | the limit ratio R, operators and curves, inverse design, census |
//! | [`certificate`] | the certificate format and its producer; [`checker`] re-verifies it alone |
//! | [`geometry`] | templates, parameter choice, placement, instantiation (floats from here on) |
//! | [`measure`] | areas, perimeters, dimensions, holes and components against the exact counts |
//! | [`mesh`] | printable solids: one checked watertight mesh per component, STL, 3MF, OBJ |
//! | [`export`] | SVG, PNG, OBJ, STL, JSON, the text reports and the HTML report |
//! | [`meshcheck`] | the independent mesh checker: reads STL and 3MF alone, shares nothing with [`mesh`] |
//!
//! [`error`] and [`progress`] sit under every layer. The [`prelude`] holds the common path: parse a
//! face, close it, count, compute R, solve.
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod error;
pub mod progress;

pub mod topology;

pub mod algebra;

pub mod constraint;

pub mod input;

pub mod analysis;

pub mod certificate;
pub mod checker;

pub mod geometry;

pub mod measure;

pub mod mesh;

pub mod family;

pub mod export;

pub mod meshcheck;

pub mod prelude;

pub use error::{Diagnostic, Error, Result, Source, Span};
