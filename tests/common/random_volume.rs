//! Random volumes for the property tests (issue #35: one copy for the unit tests of
//! `topology::volume` and the integration tests). The unit tests include this file with
//! `#[path]`, so it names the library as `super::lib` (`crate` there, `lacuna` here), never by
//! its name. Each test picks its own distribution by the lists it passes; the tuple is drawn in
//! the order solid, eighteen edges, E, algorithm, rule, delay, so a recorded failure replays
//! the same volume.

use super::lib::topology::volume::{Solid, Volume, VolumeRule};
use super::lib::topology::{EdgeType, Face};
use proptest::prelude::*;

/// A small solid (cube, tetrahedron, octahedron, 3- to 5-prism, truncated tetrahedron) whose
/// edges are drawn from `edges`, with a B2 triangle's parameters E drawn from `es` and its
/// algorithm from `algorithms` (both written as in a face's notation), rule V1 or V2, delay 1 or
/// 2. Radial and inner edges are B2.
pub fn volume(
    edges: Vec<&'static str>,
    es: Vec<&'static str>,
    algorithms: Vec<&'static str>,
) -> impl Strategy<Value = Volume> {
    let solid = prop_oneof![
        Just(Solid::Cube),
        Just(Solid::Tetrahedron),
        Just(Solid::Octahedron),
        (3usize..6).prop_map(Solid::Prism),
        Just(Solid::TruncatedTetrahedron)
    ];
    (
        solid,
        proptest::collection::vec(proptest::sample::select(edges), 18),
        proptest::sample::select(es),
        proptest::sample::select(algorithms),
        proptest::sample::select(vec![VolumeRule::V1, VolumeRule::V2]),
        1u32..3,
    )
        .prop_map(|(solid, edges, e, a, rule, delay)| {
            let template = Face::parse(&format!("B2 B2 B2 | {e} | {a}")).unwrap();
            let edges: Vec<EdgeType> = edges
                .iter()
                .map(|t| EdgeType::parse(t, 1).unwrap())
                .collect();
            Volume {
                surface: solid.surface_with(|k| edges[k % edges.len()], &template),
                radial: EdgeType::parse("B2", 1).unwrap(),
                inner: EdgeType::parse("B2", 1).unwrap(),
                params: template.params,
                algorithm: template.algorithm,
                rule,
                delay,
            }
        })
}
