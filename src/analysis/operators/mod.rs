//! Operators and curvature (THEORY §8): the exact eigen analysis of one subdivision operator and
//! its curvature class ([`operator`]), an automaton's operators read as curves with their dyadic
//! points ([`curve`]), the differential characteristic functions and the pseudo-curvature ranges
//! they give ([`dcf`]), and inverse design, `T = V·D·V⁻¹` from chosen eigenvalues ([`design`]).
//!
//! [`operator`] is the base of the folder; the other files import it, and nothing else of
//! `analysis`.

pub(crate) mod curve;
pub(crate) mod dcf;
pub(crate) mod design;
pub(crate) mod operator;
