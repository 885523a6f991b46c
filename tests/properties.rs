//! Property tests over random boundaries, parameters and algorithms (issue #2).

use lacuna::{
    topology::close, topology::counts, topology::subdivide, topology::Algorithm, topology::Bound,
    topology::Closure, topology::EdgeKind, topology::EdgePattern, topology::EdgeType,
    topology::Face, topology::Limits, topology::Params, topology::SpokeItem, topology::TypeSet,
};
use num_bigint::BigUint;
use num_rational::BigRational;
use proptest::prelude::*;

mod common;
use common::strategies;

fn edge(max_delay: u32) -> impl Strategy<Value = EdgeType> + Clone {
    strategies::edge(2..=4, 1..=max_delay)
}

fn pattern() -> impl Strategy<Value = EdgePattern> {
    prop_oneof![
        Just(EdgePattern::Any),
        Just(EdgePattern::Kind(EdgeKind::B)),
        Just(EdgePattern::Kind(EdgeKind::C)),
        edge(2).prop_map(EdgePattern::Exact),
    ]
}

fn algorithm() -> impl Strategy<Value = Algorithm> {
    let item = prop_oneof![
        Just(SpokeItem::Joint),
        Just(SpokeItem::Gap),
        Just(SpokeItem::Corner),
        Just(SpokeItem::DelayedCorner),
        (pattern(), pattern()).prop_map(|(p, q)| SpokeItem::CornerBetween(p, q)),
    ];
    strategies::algorithm(item, 4)
}

fn face() -> impl Strategy<Value = Face> {
    strategies::face(edge(3), 1..=10, edge(2), algorithm(), 1u32..=2)
}

/// N^C and N^L of every type by the first-step recurrence, independent of `counts` (which
/// iterates the type vector forward): C(t, i+1) = Σ C(child, i), L(t, i+1) = c_t + Σ L(child, i).
fn by_recursion(ts: &TypeSet, levels: usize) -> Vec<Vec<(BigUint, BigRational)>> {
    let n = ts.types.len();
    let mut table = vec![vec![
        (
            BigUint::from(1u32),
            BigRational::from_integer(0.into())
        );
        n
    ]];
    for i in 0..levels {
        let row = (0..n)
            .map(|t| {
                let ty = &ts.types[t];
                let mut c = BigUint::from(0u32);
                let mut l = BigRational::new(ty.contribution_halves().into(), 2.into());
                for &ch in &ty.children {
                    c += &table[i][ch].0;
                    l += &table[i][ch].1;
                }
                (c, l)
            })
            .collect();
        table.push(row);
    }
    table
}

fn wide_limits(f: &Face) -> Limits {
    let bound_len = Bound::stated(std::slice::from_ref(f))
        .map_or(0, |b| usize::try_from(&b.max_length).unwrap_or(usize::MAX));
    Limits {
        max_boundary: bound_len.max(48),
        max_types: 3000,
        ..Limits::default()
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    #[test]
    fn rotating_the_boundary_gives_the_same_type(f in face(), k in 0usize..10) {
        let mut g = f.clone();
        let len = g.boundary.len();
        g.boundary.rotate_left(k % len);
        prop_assert_eq!(f.canonical().0, g.canonical().0);
    }

    #[test]
    fn one_step_keeps_every_identity(f in face()) {
        let f = f.canonical().0;
        match subdivide(&f) {
            Ok(sub) => {
                sub.verify(&f).map_err(TestCaseError::fail)?;
                if f.delay == 1 {
                    // One sub-face per spoke; each Ea shared by two sub-faces (verify checks the
                    // pairing and the opposite directions).
                    prop_assert_eq!(sub.subfaces.len(), sub.spokes.len());
                    prop_assert_eq!(sub.adjacencies.len(), sub.spokes.len());
                } else {
                    prop_assert_eq!(sub.subfaces.len(), 1);
                }
                let pieces: usize = f.boundary.iter().map(|e| e.piece_count() as usize).sum();
                let used: usize = sub.subfaces.iter().flat_map(|s| &s.origins).filter(|o| matches!(o, lacuna::topology::Origin::Piece { .. })).count();
                prop_assert_eq!(pieces, used);
            }
            Err(e) => {
                prop_assert_eq!(e.code(), "E0401");
                prop_assert_eq!(f.delay, 1);
            }
        }
    }

    #[test]
    fn closures_respect_their_bound_and_counts_their_recurrence(f in face()) {
        let limits = wide_limits(&f);
        let builtin = f.algorithm.is_builtin();
        match close(&f, &limits) {
            Err(e) => prop_assert_eq!(e.code(), "E0401"),
            Ok(Closure::Runaway(r)) => {
                prop_assert!(!builtin, "a built-in algorithm ran away: {:?}", r);
                // The witness is a chain: each face is a sub-face of the one before.
                for w in r.witness.windows(2) {
                    let parent = Face::parse(&w[0]).unwrap();
                    let child = Face::parse(&w[1]).unwrap();
                    let sub = subdivide(&parent).unwrap();
                    prop_assert!(sub.subfaces.iter().any(|s| *s.face == child));
                }
            }
            Ok(Closure::Closed(ts)) => {
                ts.verify().map_err(TestCaseError::fail)?;
                prop_assert_eq!(ts.bound.is_some(), builtin);
                let levels = 5;
                let fwd = counts(&ts, levels as u64);
                let rec = by_recursion(&ts, levels);
                for (i, l) in fwd.iter().enumerate() {
                    let (c, lac) = &rec[i][ts.start[0]];
                    prop_assert_eq!(&l.faces, c);
                    prop_assert_eq!(&l.lacunas, lac);
                }
            }
        }
    }
}

/// A decimal string as an exact rational.
fn decimal(s: &str) -> BigRational {
    let (i, f) = s.split_once('.').unwrap_or((s, ""));
    let scale = num_bigint::BigInt::from(10).pow(f.len() as u32);
    BigRational::new(format!("{i}{f}").parse().unwrap(), scale)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    /// For random closures of the built-in algorithms, the exact R lies in [0, 1] and agrees with
    /// R_i computed exactly at large levels: |R − R_i| does not grow from level 40 to level 120
    /// and is small at level 120. Where the limit does not exist, each residue class of R_i
    /// approaches its own limit point.
    #[test]
    fn exact_ratio_agrees_with_deep_counts(
        boundary in proptest::collection::vec(edge(2), 2..=6),
        ea in edge(1), el in edge(1), ec in edge(1),
        alg in prop_oneof![Just(Algorithm::a1()), Just(Algorithm::a2()), Just(Algorithm::a3())],
    ) {
        let f = Face { boundary, params: Params { ea, el, ec }, algorithm: alg, delay: 1 };
        let Ok(Closure::Closed(ts)) = close(&f, &Limits::default()) else { return Ok(()) };
        let r = lacuna::export::ratio_of(&ts, 30).unwrap();
        let c = counts(&ts, 120);
        let tol = BigRational::new(1.into(), num_bigint::BigInt::from(10).pow(25));
        let zero = BigRational::from_integer(0.into());
        let one = BigRational::from_integer(1.into());
        for p in &r.limit_points {
            let v = decimal(&p.decimal);
            prop_assert!(v >= zero && v <= &one + &tol, "limit point {} outside [0, 1]", p.decimal);
            let period = r.period as usize;
            let at = |base: usize| {
                let i = base - base % period + p.residue as usize;
                let d = &c[i].ratio - &v;
                if d < zero { -d } else { d }
            };
            prop_assert!(at(119) <= at(40) + &tol, "|R − R_i| grew: {} then {}", at(40), at(119));
            prop_assert!(at(119) < BigRational::new(1.into(), 50.into()), "R_i far from R at level ~119 for {}", f);
        }
        prop_assert_eq!(r.exists, r.limit_points.len() == 1 || r.limit_points.windows(2).all(|w| w[0].exact == w[1].exact));
    }
}
