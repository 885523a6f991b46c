use super::*;
use proptest::prelude::*;

fn ints(rows: &[&[i64]]) -> Vec<Vec<BigInt>> {
    rows.iter()
        .map(|r| r.iter().map(|&x| x.into()).collect())
        .collect()
}

#[test]
fn charpoly_of_small_matrices() {
    // [[1,1],[1,0]]: x^2 - x - 1.
    assert_eq!(
        charpoly(&ints(&[&[1, 1], &[1, 0]])),
        Poly::from_ints(&[-1, -1, 1])
    );
    // Companion-like 3-cycle with weight 2: x^3 - 2.
    assert_eq!(
        charpoly(&ints(&[&[0, 2, 0], &[0, 0, 1], &[1, 0, 0]])),
        Poly::from_ints(&[-2, 0, 0, 1])
    );
    // Upper triangular: (x-3)(x-5)(x+1).
    let p = charpoly(&ints(&[&[3, 7, 9], &[0, 5, 4], &[0, 0, -1]]));
    assert_eq!(
        p,
        &(&Poly::from_ints(&[-3, 1]) * &Poly::from_ints(&[-5, 1])) * &Poly::from_ints(&[1, 1])
    );
}

#[test]
fn factors_of_known_products() {
    // (x^2 - 2)(x^2 + 1)(x^3 - x - 1)^2 (x - 4) x
    let a = Poly::from_ints(&[-2, 0, 1]);
    let b = Poly::from_ints(&[1, 0, 1]);
    let c = Poly::from_ints(&[-1, -1, 0, 1]);
    let d = Poly::from_ints(&[-4, 1]);
    let p = &(&(&(&a * &b) * &c.pow(2)) * &d) * &Poly::x();
    let got = factor(&p).unwrap();
    let mut want = vec![(Poly::x(), 1), (d, 1), (a, 1), (b, 1), (c, 2)];
    let mut got_sorted = got.clone();
    got_sorted.sort_by_key(|(g, m)| (g.deg(), *m, g.to_string()));
    want.sort_by_key(|(g, m)| (g.deg(), *m, g.to_string()));
    assert_eq!(got_sorted, want);
    // x^4 + 1 is irreducible over Q but splits modulo every prime.
    assert_eq!(factor(&Poly::from_ints(&[1, 0, 0, 0, 1])).unwrap().len(), 1);
    // Swinnerton-Dyer x^4 - 10x^2 + 1: irreducible, splits into linear/quadratic mod p.
    assert_eq!(
        factor(&Poly::from_ints(&[1, 0, -10, 0, 1])).unwrap().len(),
        1
    );
    // Rational coefficients: (x/2 - 1/3)(x^2 + 1/4).
    let qq = |a: i64, b: i64| num_rational::BigRational::new(a.into(), b.into());
    let r = &Poly::new(vec![qq(-1, 3), qq(1, 2)]) * &Poly::new(vec![qq(1, 4), qq(0, 1), qq(1, 1)]);
    assert_eq!(factor(&r).unwrap().len(), 2);
}

fn irreducibles() -> Vec<Poly> {
    vec![
        Poly::from_ints(&[-1, -1, 1]),
        Poly::from_ints(&[-2, 0, 0, 1]),
        Poly::from_ints(&[1, 1, 1]),
        Poly::from_ints(&[3, 1]),
        Poly::from_ints(&[-1, -1, 0, 1]),
        Poly::from_ints(&[1, 0, 0, 0, 1]),
        Poly::from_ints(&[-3, 0, 0, 0, 0, 1]),
        Poly::from_ints(&[1, 0, -10, 0, 1]),
        Poly::from_ints(&[-7, 2, 1]),
    ]
}

proptest! {
    #[test]
    fn factor_recovers_products(picks in prop::collection::vec((0usize..9, 1usize..3), 1..4)) {
        let irr = irreducibles();
        let mut want: std::collections::BTreeMap<String, usize> = Default::default();
        let mut p = Poly::from_ints(&[1]);
        for (i, m) in picks {
            p = &p * &irr[i].pow(m);
            *want.entry(irr[i].monic().to_string()).or_default() += m;
        }
        let got: std::collections::BTreeMap<String, usize> =
            factor(&p).unwrap().into_iter().map(|(g, m)| (g.to_string(), m)).collect();
        prop_assert_eq!(got, want);
    }

    #[test]
    fn charpoly_matches_trace_and_det(m in prop::collection::vec(prop::collection::vec(0i64..4, 3), 3)) {
        let a: Vec<Vec<BigInt>> = m.iter().map(|r| r.iter().map(|&x| x.into()).collect()).collect();
        let p = charpoly(&a);
        let tr: i64 = (0..3).map(|i| m[i][i]).sum();
        let det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
        prop_assert_eq!(p.coeff(2), num_rational::BigRational::from_integer((-tr).into()));
        prop_assert_eq!(p.coeff(0), num_rational::BigRational::from_integer((-det).into()));
        prop_assert_eq!(p.coeff(3), num_rational::BigRational::one());
    }
}
