//! The analyses of an automaton's attractor: its operators made exact
//! ([`automaton_resolve`]), whether every walk of the control graph contracts
//! ([`contraction`]), the exact similarity dimension (Mauldin–Williams, [`similarity`]) and the
//! open-set condition that makes it the Hausdorff dimension ([`open_set`], with the neighbour-map
//! criterion of Bandt–Graf in [`neighbour_maps`]), and the dimension of the boundary seen by the
//! neighbour pieces, from the graph of those maps ([`boundary`]).
//!
//! The files of this folder import each other (the contraction proof codes the resolved
//! operators, the dimension needs the control graph and the open-set witnesses) and nothing else
//! of `analysis`.

pub(crate) mod automaton_resolve;
pub(crate) mod boundary;
pub(crate) mod contraction;
pub(crate) mod neighbour_maps;
pub(crate) mod open_set;
pub(crate) mod similarity;
