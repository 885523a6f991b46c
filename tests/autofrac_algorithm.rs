//! AutoFrac2D's algorithm 1 as the built-in spoke rule `AF1` (issue #23): on random faces with
//! delays, the spokes of one subdivision step are exactly the junctions the issue names — every
//! joint and gap, and every corner between edges P and Q where at least one is delayed and
//! neither is a non-delayed `Bn` — and the closure stays within the bound stated in advance.

use lacuna::topology::{
    close, subdivide, Algorithm, Closure, EdgeKind, EdgeType, Face, JunctionKind, Limits, Params,
};
use proptest::prelude::*;

mod common;

/// An AutoFrac2D file with algorithm 1 and delays is read as AF1, closes, and its certificate
/// (with the new spoke item) is proved by the independent checker.
#[test]
fn autofrac_algorithm_1_with_delays_closes_and_is_certified() {
    let dir = std::env::temp_dir().join(format!("lacuna-af1-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("af1.txt");
    std::fs::write(
        &file,
        "f\nB_2_0 - C_2_1 - B_2_0 - C_2_0 / C_2_0 - B_2_0 - B_2_0 / 0 / 1\n",
    )
    .unwrap();
    let input = lacuna::input::load_input(file.to_str().unwrap()).unwrap();
    assert_eq!(
        input.faces()[0].to_string(),
        "B2 C2^2 B2 C2 | C2 B2 B2 | AF1"
    );
    let ts = lacuna::topology::close_or_error(&input.faces(), &Limits::default()).unwrap();
    ts.verify().unwrap();
    common::assert_certified("af1.txt", &ts);
    std::fs::remove_dir_all(&dir).ok();
}

fn edge() -> impl Strategy<Value = EdgeType> + Clone {
    common::strategies::edge(2..=3, 1u32..=3)
}

/// The face, with at least one delayed boundary edge.
fn face() -> impl Strategy<Value = Face> {
    (
        prop::collection::vec(edge(), 1..=6),
        0usize..6,
        edge(),
        edge(),
        edge(),
    )
        .prop_map(|(mut boundary, k, ea, el, ec)| {
            let i = k % boundary.len();
            if !boundary.iter().any(EdgeType::is_delayed) {
                boundary[i] = boundary[i].delayed(2);
            }
            Face {
                boundary,
                params: Params { ea, el, ec },
                algorithm: Algorithm::af1(),
                delay: 1,
            }
        })
}

/// The issue's description of the spoke set, written independently of `SpokeItem`.
fn expected_spoke(kind: JunctionKind, p: &EdgeType, q: &EdgeType) -> bool {
    let plain_b = |e: &EdgeType| e.kind == EdgeKind::B && e.delay == 1;
    match kind {
        JunctionKind::Joint | JunctionKind::Gap => true,
        JunctionKind::Corner => (p.delay > 1 || q.delay > 1) && !plain_b(p) && !plain_b(q),
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn af1_spokes_are_the_issue_spoke_set(f in face()) {
        let (f, _) = f.canonical();
        match subdivide(&f) {
            Ok(sub) => {
                let want: Vec<usize> = sub
                    .junctions
                    .iter()
                    .enumerate()
                    .filter(|(_, j)| expected_spoke(j.kind, &j.before, &j.after))
                    .map(|(m, _)| m)
                    .collect();
                prop_assert_eq!(&sub.spokes, &want, "{}", f);
                sub.verify(&f).map_err(TestCaseError::fail)?;
            }
            // Every non-delayed edge has inner joints or gaps, and two delayed edges meet at a
            // spoke, so AF1 always finds a spoke.
            Err(e) => prop_assert!(false, "{} refused: {}", f, e.render()),
        }
    }

    #[test]
    fn af1_closes_within_the_stated_bound(f in face()) {
        let limits = Limits { max_boundary: 64, max_types: 5_000, ..Limits::default() };
        if let Ok(Closure::Closed(ts)) = close(&f, &limits) {
            let bound = ts.bound.clone().expect("AF1 is built in: a bound is stated");
            for t in &ts.types {
                prop_assert!(num_bigint::BigUint::from(t.face.boundary.len()) <= bound.max_length, "{} in the closure of {}", t.face, f);
            }
            prop_assert!(num_bigint::BigUint::from(ts.types.len()) <= bound.max_types);
        } else if let Ok(Closure::Runaway(r)) = close(&f, &limits) {
            prop_assert!(false, "AF1 ran away from {}: {:?}", f, r);
        }
    }
}
