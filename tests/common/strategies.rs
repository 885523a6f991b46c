//! Random faces for the property tests (issue #35: one copy instead of one per test file). Each
//! test keeps its own distribution — sizes tuned to what its property costs — by passing the
//! pieces: an edge strategy for the boundary and one for the parameters, an algorithm strategy
//! and a face delay. The tuple is generated in the order boundary, Ea, El, Ec, algorithm, delay,
//! as every copy did, so a recorded failure replays the same face.

use lacuna::topology::{Algorithm, EdgeKind, EdgeType, Face, Params, SpokeItem};
use proptest::prelude::*;
use std::ops::RangeInclusive;

/// An edge `Bn` or `Cn` with n in `sub_edges` and the delay `delay` draws.
pub fn edge(
    sub_edges: RangeInclusive<u32>,
    delay: impl Strategy<Value = u32> + Clone,
) -> impl Strategy<Value = EdgeType> + Clone {
    (
        prop_oneof![Just(EdgeKind::B), Just(EdgeKind::C)],
        sub_edges,
        delay,
    )
        .prop_map(|(k, n, d)| EdgeType::new(k, n).delayed(d))
}

/// A1, A2 or A3, uniformly.
pub fn builtin_algorithm() -> impl Strategy<Value = Algorithm> {
    prop_oneof![
        Just(Algorithm::a1()),
        Just(Algorithm::a2()),
        Just(Algorithm::a3())
    ]
}

/// A1, A2, A3 (weights 3, 2, 2) or a spoke set of 1 to `most − 1` items drawn from `items`
/// (weight 2).
pub fn algorithm(
    items: impl Strategy<Value = SpokeItem> + Clone + 'static,
    most: usize,
) -> impl Strategy<Value = Algorithm> {
    prop_oneof![
        3 => Just(Algorithm::a1()),
        2 => Just(Algorithm::a2()),
        2 => Just(Algorithm::a3()),
        2 => proptest::collection::btree_set(items, 1..most).prop_map(Algorithm::spoke_set),
    ]
}

/// The four spoke items that need no edge pattern.
pub fn plain_spoke_item() -> impl Strategy<Value = SpokeItem> + Clone {
    prop_oneof![
        Just(SpokeItem::Joint),
        Just(SpokeItem::Gap),
        Just(SpokeItem::Corner),
        Just(SpokeItem::DelayedCorner),
    ]
}

/// A face of `lengths` boundary edges drawn by `boundary`, parameters drawn by `param`, the
/// algorithm by `algorithm` and the face delay by `delay`.
pub fn face<E, P>(
    boundary: E,
    lengths: RangeInclusive<usize>,
    param: P,
    algorithm: impl Strategy<Value = Algorithm>,
    delay: impl Strategy<Value = u32>,
) -> impl Strategy<Value = Face>
where
    E: Strategy<Value = EdgeType>,
    P: Strategy<Value = EdgeType> + Clone,
{
    (
        proptest::collection::vec(boundary, lengths),
        param.clone(),
        param.clone(),
        param,
        algorithm,
        delay,
    )
        .prop_map(|(boundary, ea, el, ec, algorithm, delay)| Face {
            boundary,
            params: Params { ea, el, ec },
            algorithm,
            delay,
        })
}
