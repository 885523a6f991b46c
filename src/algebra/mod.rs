//! Exact algebra: polynomials over Q with root isolation, characteristic polynomials and factoring
//! over Q, real algebraic numbers and the number fields Q(ρ), polynomials over Q(λ), and small dense
//! exact matrices.
//!
//! Architecture invariant: pure mathematics, no floats in a decision; it imports nothing from the
//! crate but [`crate::error`] and knows nothing of faces, automata or geometry.

pub(crate) mod algebraic;
pub(crate) mod disk;
pub(crate) mod factor;
pub(crate) mod fieldpoly;
pub(crate) mod intgcd;
pub(crate) mod kmatrix;
pub(crate) mod matrix;
pub(crate) mod poly;
pub(crate) mod reallog;
pub(crate) mod square_part;

pub use algebraic::{FieldElement, NumberField, RealAlgebraic};
pub use kmatrix::KMatrix;
pub use matrix::{bezier_restriction, Matrix};
pub use poly::Poly;
