//! Analyses over a family of faces: the census, every face of a family closed and counted in
//! parallel ([`census`]), and the property-based exploration of a subdivision rule with its
//! failures shrunk to minimal counterexamples ([`explore`]).
//!
//! Both stand on the limit ratio ([`crate::analysis::ratio`]) and the layers below `analysis`.

pub(crate) mod census;
pub(crate) mod explore;
