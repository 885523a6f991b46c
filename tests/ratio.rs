//! The limit ratio R on fixtures, against hand derivations written here.

mod common;
use lacuna::{
    export::ratio_of, input::load_input, topology::close_or_error, topology::counts,
    topology::Limits, topology::TypeSet,
};
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::Signed;

fn closed(name: &str) -> TypeSet {
    let input = load_input(name).unwrap_or_else(|e| panic!("fixture {name}: {}", e.render()));
    let ts = close_or_error(&input.faces(), &Limits::default()).unwrap();
    common::assert_certified(name, &ts);
    ts
}

/// A decimal string as an exact rational.
fn dec(s: &str) -> BigRational {
    let (i, f) = s.split_once('.').unwrap_or((s, ""));
    let scale = BigInt::from(10).pow(f.len() as u32);
    let n: BigInt = format!("{i}{f}").parse().unwrap();
    BigRational::new(n, scale)
}

#[test]
fn f0_is_one_third() {
    // THEORY §5: R = l/(l + k − 1) = (5/2)/(5/2 + 5) = 1/3.
    let r = ratio_of(&closed("F0"), 30).unwrap();
    assert!(r.exists);
    assert_eq!(r.exact.as_deref(), Some("1/3"), "fixture F0");
    assert_eq!(r.perron_root, "6");
    assert_eq!(
        r.decimal.as_deref(),
        Some("0.333333333333333333333333333333")
    );
}

#[test]
fn triangle_is_one_fifth() {
    // The pentagon P5 class (5 copies, contribution 1) dominates: R = 1/(1 + 5 − 1) = 1/5.
    let r = ratio_of(&closed("triangle-C2"), 10).unwrap();
    assert_eq!(r.exact.as_deref(), Some("1/5"), "fixture triangle-C2");
    assert_eq!(r.classes.len(), 4);
}

#[test]
fn two_type_cycle_with_an_irrational_perron_root() {
    // fixtures/cycle-sqrt17.txt: M = [[3, 2], [2, 4]] (checked here), contributions 3/2 and 2.
    // ρ² − 7ρ + 8 = 0, ρ = (7 + √17)/2. Independently of lacuna's generating functions: for a
    // simple dominant eigenvalue, e·M^i/ρ^i → α·y with y the left eigenvector (y·M = ρ·y), so
    // N^C_i ~ α·y·1·ρ^i, N^L_i ~ α·y·c·ρ^i/(ρ − 1) and R = y·c / (y·c + (ρ − 1)·y·1).
    // y = (2, ρ − 3): y·c = 3 + 2(ρ − 3) = 2ρ − 3 = 4 + √17, y·1 = ρ − 1 = (5 + √17)/2,
    // (ρ − 1)² = (21 + 5√17)/2, so R = 2(4 + √17)/(29 + 7√17) = 2(√17 − 3)/8 = (√17 − 3)/4.
    let ts = closed("cycle-sqrt17");
    assert_eq!(
        ts.matrix(),
        vec![vec![(0, 3), (1, 2)], vec![(0, 2), (1, 4)]]
    );
    let halves: Vec<u64> = ts.types.iter().map(|t| t.contribution_halves()).collect();
    assert_eq!(halves, [3, 4]);
    let r = ratio_of(&ts, 50).unwrap();
    assert!(r.exists);
    assert_eq!(r.exact.as_deref(), Some("(-3 + sqrt(17))/4"));
    assert_eq!(r.perron_root, "(7 + sqrt(17))/2");
    assert_eq!(r.perron_min_poly, "x^2 - 7*x + 8");
    // 50 digits of (√17 − 3)/4, computed independently (Python's decimal module, 80 digits:
    // 0.28077640640441513745535246399351925628679980634340510859965839327373858658...).
    assert_eq!(
        r.decimal.as_deref(),
        Some("0.28077640640441513745535246399351925628679980634340")
    );
    // R_i converges to it: |R − R_i| shrinks geometrically (second eigenvalue / ρ ≈ 0.26).
    let c = counts(&ts, 60);
    let exact = dec(r.decimal.as_deref().unwrap());
    let gap = |i: usize| (&c[i].ratio - &exact).abs();
    assert!(gap(60) < gap(30) && gap(30) < gap(10));
    assert!(gap(60) < BigRational::new(1.into(), BigInt::from(10).pow(12)));
}

#[test]
fn delayed_fixture_is_dominated_by_g6() {
    // G6 = B2 C2 B2 C2 B2 C2 (6 copies, contribution 5/2) dominates: 1/3, like F0.
    let r = ratio_of(&closed("delayed-B2-C2"), 10).unwrap();
    assert_eq!(r.exact.as_deref(), Some("1/3"));
}

mod self_similar {
    use super::*;
    use lacuna::{analysis::CensusSpec, topology::close, topology::Closure, topology::Face};
    use proptest::prelude::*;

    /// R of a closure that is a single self-similar type must be l/(l + k − 1) (THEORY §5), with
    /// k its number of sub-faces and l its contribution.
    fn check_single_type(ts: &TypeSet) {
        let k = ts.types[0].children.len() as i64;
        let l = BigRational::new(ts.types[0].contribution_halves().into(), 2.into());
        let want = &l / (&l + BigRational::from_integer((k - 1).into()));
        let r = ratio_of(ts, 30).unwrap();
        assert!(r.exists);
        assert_eq!(
            r.exact.as_deref(),
            Some(want.to_string().as_str()),
            "{}",
            ts.types[0].face
        );
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 32, ..ProptestConfig::default() })]

        /// `Bn Bn Bn Bn | Bn Bn Bn | A2`: every junction is a spoke, every run is one piece, and
        /// piece + `Ea El Ea` is the same square: a face with 4n copies of itself and l = 1, so
        /// R = 1/(4n).
        #[test]
        fn squares_of_bezier_edges_are_self_similar(n in 2u32..=8) {
            let e = format!("B{n}");
            let face = Face::parse(&format!("{e} {e} {e} {e} | {e} {e} {e} | A2")).unwrap();
            let Closure::Closed(ts) = close(&face, &Limits::default()).unwrap() else { panic!() };
            prop_assert_eq!(ts.types.len(), 1);
            prop_assert_eq!(ts.types[0].children.len(), 4 * n as usize);
            check_single_type(&ts);
            let r = ratio_of(&ts, 10).unwrap();
            prop_assert_eq!(r.exact.unwrap(), format!("1/{}", 4 * n));
        }
    }

    /// Every single-type closure of the census family (boundaries of length ≤ 5 over B2, C2,
    /// B3, C3, E over {B2, C2}³, A1 and A2) obeys l/(l + k − 1).
    #[test]
    fn every_single_type_closure_of_the_census_family() {
        let spec = CensusSpec::parse("B2,C2,B3,C3", "B2,C2", "A1,A2", 5, Some(1)).unwrap();
        let mut found = 0;
        for f in spec.faces() {
            if let Ok(Closure::Closed(ts)) = close(&f, &Limits::default()) {
                if ts.types.len() == 1 {
                    check_single_type(&ts);
                    found += 1;
                }
            }
        }
        assert!(found >= 2, "only {found} single-type closures");
    }
}
