use super::*;
use proptest::prelude::*;

fn q(a: i64, b: i64) -> BigRational {
    BigRational::new(a.into(), b.into())
}

/// `R_i` for `i` in `levels`, exactly, by iterating the counts with rationals.
fn ratios(
    m: &[Vec<(usize, u64)>],
    c: &[BigRational],
    start: &[(usize, u64)],
    top: usize,
) -> Vec<BigRational> {
    let mut v = vec![BigRational::zero(); m.len()];
    for &(t, k) in start {
        v[t] += BigRational::from_integer(k.into());
    }
    let mut lac = BigRational::zero();
    let mut out = Vec::new();
    for _ in 0..=top {
        let faces: BigRational = v.iter().sum();
        out.push(&lac / (&lac + &faces));
        let mut next = vec![BigRational::zero(); m.len()];
        for (t, row) in m.iter().enumerate() {
            for &(s, k) in row {
                next[s] += &v[t] * BigRational::from_integer(k.into());
            }
            lac += &v[t] * &c[t];
        }
        v = next;
    }
    out
}

/// An interval of width 2^-100 around a field element.
fn approx(rep: &RatioReport, x: &FieldElement) -> (BigRational, BigRational) {
    rep.field.enclosure(x, &q(1, 1 << 50).pow(2))
}

fn dist(rep: &RatioReport, x: &FieldElement, y: &BigRational) -> BigRational {
    let (lo, hi) = approx(rep, x);
    (lo - y).abs().max((hi - y).abs())
}

#[test]
fn f0_single_type() {
    // One type, 6 copies of itself, contribution 5/2: R = l/(l + k − 1) = (5/2)/(5/2 + 5) = 1/3.
    let rep = analyse(&[vec![(0, 6)]], &[q(5, 2)], &[(0, 1)]).unwrap();
    assert!(rep.exists);
    assert_eq!(rep.exact.as_deref(), Some("1/3"));
    assert_eq!(
        rep.decimal.as_deref(),
        Some("0.333333333333333333333333333333")
    );
    assert_eq!(rep.perron_root, "6");
    assert_eq!(rep.classes[0].spectral_radius, "6");
    assert_eq!(rep.classes[0].period, Some(1));
    // THEORY §5: R_1 = 5/17.
    assert_eq!(
        ratios(&[vec![(0, 6)]], &[q(5, 2)], &[(0, 1)], 1)[1],
        q(5, 17)
    );
    let json = serde_json::to_value(&rep).unwrap();
    assert_eq!(json["exists"], true);
    assert_eq!(json["exact"], "1/3");
    assert_eq!(json["classes"][0]["members"], serde_json::json!([0]));
}

#[test]
fn fibonacci_pair_is_quadratic() {
    // a → {a, b}, b → {a}: M = [[1,1],[1,0]], ρ = φ = (1+√5)/2, left eigenvector ℓ = (φ, 1)
    // (ℓM = (φ+1, φ) = φℓ). For one dominant primitive class e·M^j ≈ κ φ^j ℓ, so
    // N^C_i ≈ κ φ^i ℓ·1 and N^L_i ≈ κ (ℓ·c) φ^i / (φ − 1): R = ℓc / (ℓc + (φ − 1) ℓ1).
    // ℓ1 = φ + 1 = φ². With c = (1/2, 1/2): ℓc = φ²/2, R = 1/(1 + 2(φ − 1)) = 1/(2φ − 1) = 1/√5.
    let m = vec![vec![(0, 1), (1, 1)], vec![(0, 1)]];
    let rep = analyse(&m, &[q(1, 2), q(1, 2)], &[(0, 1)]).unwrap();
    assert!(rep.exists);
    assert_eq!(rep.perron_root, "(1 + sqrt(5))/2");
    assert_eq!(rep.perron_min_poly, "x^2 - x - 1");
    assert_eq!(rep.exact.as_deref(), Some("sqrt(5)/5"));
    // 1/√5 = 0.447213595499957939281834733746255247088123671922305144854179…
    assert_eq!(
        rep.decimal.as_deref(),
        Some("0.447213595499957939281834733746")
    );
    // With c = (0, 1): ℓc = 1, R = 1/(1 + (φ − 1)φ²) = 1/(1 + φ) = 1/φ² = 2 − φ = (3 − √5)/2.
    let rep = analyse(&m, &[q(0, 1), q(1, 1)], &[(0, 1)]).unwrap();
    assert_eq!(rep.exact.as_deref(), Some("(3 - sqrt(5))/2"));
    assert_eq!(
        rep.coordinates,
        Some(vec!["2".to_string(), "-1".to_string()])
    );
    // (3 − √5)/2 = 0.381966011250105151795413165634361882279690820194237137864551…
    assert_eq!(
        rep.decimal.as_deref(),
        Some("0.381966011250105151795413165634")
    );
    // certify the 30 digits independently: x ≤ R < x + 10^-30 ⇔ (3−2x−2ε)² < 5 ≤ (3−2x)².
    let x: BigRational = "381966011250105151795413165634/1000000000000000000000000000000"
        .parse()
        .unwrap();
    let eps = BigRational::new(1.into(), BigInt::from(10).pow(30));
    let three = q(3, 1);
    let two = q(2, 1);
    let hi = &three - &two * &x;
    let lo = &hi - &two * &eps;
    assert!(&lo * &lo < q(5, 1) && q(5, 1) <= &hi * &hi);
    // With c = (1, 0): ℓc = φ, R = φ/(φ + (φ−1)φ²) = 1/(1 + φ² − φ) = 1/2: rational in Q(φ).
    let rep = analyse(&m, &[q(1, 1), q(0, 1)], &[(0, 1)]).unwrap();
    assert_eq!(rep.exact.as_deref(), Some("1/2"));
}

#[test]
fn periodic_class_oscillates() {
    // a → 2 b, b → 8 a: ρ = 4, period 2. Level 2j: 16^j a; level 2j+1: 2·16^j b.
    // N^L_2j = (16^j − 1)/15 · S with S = c_a + 2 c_b; N^L_{2j+1} = N^L_2j + 16^j c_a.
    // R_2j → S/(S + 15); R_{2j+1} → (S/15 + c_a)/(S/15 + c_a + 2) = T/(T + 30), T = 16c_a + 2c_b.
    let m = vec![vec![(1, 2)], vec![(0, 8)]];
    // c = (1, 0): S = 1, T = 16: limit points 1/16 and 16/46 = 8/23.
    let rep = analyse(&m, &[q(1, 1), q(0, 1)], &[(0, 1)]).unwrap();
    assert!(!rep.exists);
    assert_eq!(rep.exact, None);
    assert_eq!(rep.period, 2);
    assert_eq!(rep.perron_root, "4");
    let pts: Vec<&str> = rep.limit_points.iter().map(|p| p.exact.as_str()).collect();
    assert_eq!(pts, vec!["1/16", "8/23"]);
    // Coincidence: T = 2S ⇔ c_b = 7 c_a; c = (1/2, 7/2): S = 15/2, R = (15/2)/(45/2) = 1/3.
    let rep = analyse(&m, &[q(1, 2), q(7, 2)], &[(0, 1)]).unwrap();
    assert!(rep.exists);
    assert_eq!(rep.exact.as_deref(), Some("1/3"));
    assert_eq!(rep.limit_points.len(), 2);
}

#[test]
fn chain_with_equal_radii() {
    // a → {a, a, b}, b → {b, b}: M = [[2,1],[0,2]], both classes of radius 2. From one a:
    // a_i = 2^i, b_i = i·2^(i−1), N^C_i = 2^(i−1)(i + 2);
    // N^L_i = c_a(2^i − 1) + c_b((i − 2)2^(i−1) + 1). If c_b > 0, R = c_b/(c_b + 1); else R = 0.
    let m = vec![vec![(0, 2), (1, 1)], vec![(1, 2)]];
    let rep = analyse(&m, &[q(1, 2), q(1, 1)], &[(0, 1)]).unwrap();
    assert_eq!(rep.exact.as_deref(), Some("1/2"));
    assert_eq!(rep.dominant, vec![0, 1]);
    assert!(rep
        .reasons
        .iter()
        .any(|r| r.contains("pole orders: lacunas 2, sub-faces 2")));
    let rep = analyse(&m, &[q(3, 1), q(0, 1)], &[(0, 1)]).unwrap();
    assert_eq!(rep.exact.as_deref(), Some("0"));
    assert!(rep.reasons.iter().any(|r| r.contains("sub-faces dominate")));
    // check the closed forms for N^L, N^C against the iteration at i = 7 (c = (1/2, 1)).
    let i = 7i64;
    let nc = (1 << (i - 1)) * (i + 2);
    let nl2 = (1 << i) - 1 + 2 * ((i - 2) * (1 << (i - 1)) + 1); // 2·N^L
    assert_eq!(
        ratios(&m, &[q(1, 2), q(1, 1)], &[(0, 1)], 7)[7],
        q(nl2, nl2 + 2 * nc)
    );
}

#[test]
fn radius_one_gives_one() {
    // a → {a}, contribution 1: N^C = 1, N^L_i = i, R → 1.
    let rep = analyse(&[vec![(0, 1)]], &[q(1, 1)], &[(0, 1)]).unwrap();
    assert_eq!(rep.exact.as_deref(), Some("1"));
    assert_eq!(rep.perron_root, "1");
    // No lacuna at all: R = 0.
    let rep = analyse(&[vec![(0, 1)]], &[q(0, 1)], &[(0, 1)]).unwrap();
    assert_eq!(rep.exact.as_deref(), Some("0"));
    // a → {a, b}, b → 2 b: a (radius 1) feeds b (radius 2); only b matters: 1-type formula
    // with k = 2, l = 1/2: R = (1/2)/(1/2 + 1) = 1/3 (a's linear lacunas are negligible).
    let rep = analyse(
        &[vec![(0, 1), (1, 1)], vec![(1, 2)]],
        &[q(7, 1), q(1, 2)],
        &[(0, 1)],
    )
    .unwrap();
    assert_eq!(rep.exact.as_deref(), Some("1/3"));
    assert_eq!(rep.classes[0].spectral_radius, "1");
}

#[test]
fn cubic_perron_root() {
    // a → b, b → c, c → {a, b}: characteristic polynomial x^3 − x − 1 (plastic number).
    let m = vec![vec![(1, 1)], vec![(2, 1)], vec![(0, 1), (1, 1)]];
    let rep = analyse(&m, &[q(1, 1), q(0, 1), q(0, 1)], &[(0, 1)]).unwrap();
    assert_eq!(rep.perron_min_poly, "x^3 - x - 1");
    assert!(rep.perron_root.starts_with("root of x^3 - x - 1 in ["));
    assert!(rep
        .exact
        .as_deref()
        .unwrap()
        .contains("where rho = root of x^3 - x - 1"));
    assert_eq!(rep.perron_decimal, "1.324717957244746025960908854478");
    let r = ratios(&m, &[q(1, 1), q(0, 1), q(0, 1)], &[(0, 1)], 300);
    assert!(dist(&rep, rep.ratio.as_ref().unwrap(), &r[300]) < q(1, 1_000_000_000));
}

#[test]
fn errors_are_reported() {
    assert_eq!(
        analyse(&[vec![(1, 1)]], &[q(0, 1)], &[(0, 1)]).unwrap_err(),
        RatioError::TypeOutOfRange {
            face_type: 1,
            types: 1
        }
    );
    assert_eq!(
        analyse(&[vec![], vec![(1, 2)]], &[q(0, 1), q(0, 1)], &[(0, 1)]).unwrap_err(),
        RatioError::NoSubFace { face_type: 0 }
    );
    assert_eq!(
        analyse(&[vec![(0, 2)]], &[q(0, 1)], &[]).unwrap_err(),
        RatioError::EmptyStart
    );
}

fn arb_system() -> impl Strategy<Value = (Vec<Vec<(usize, u64)>>, Vec<BigRational>)> {
    (2usize..=5).prop_flat_map(|n| {
        (
            prop::collection::vec(prop::collection::vec(0u64..=3, n), n),
            prop::collection::vec(0i64..=6, n),
        )
            .prop_map(move |(rows, cs)| {
                let m = rows
                    .into_iter()
                    .enumerate()
                    .map(|(t, row)| {
                        let mut r: Vec<(usize, u64)> = row
                            .into_iter()
                            .enumerate()
                            .filter(|&(_, k)| k > 0)
                            .collect();
                        if r.is_empty() {
                            r.push(((t + 1) % n, 1));
                        }
                        r
                    })
                    .collect();
                (m, cs.into_iter().map(|x| q(x, 2)).collect())
            })
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    #[test]
    fn single_type_formula(k in 1u64..20, l2 in 0i64..40) {
        let l = q(l2, 2);
        let rep = analyse(&[vec![(0, k)]], std::slice::from_ref(&l), &[(0, 3)]).unwrap();
        let want = if l2 == 0 { q(0, 1) } else { &l / (&l + BigRational::from_integer((k - 1).into())) };
        prop_assert_eq!(rep.ratio.unwrap().as_rational(), Some(want));
    }

    #[test]
    fn agrees_with_iteration((m, c) in arb_system()) {
        let rep = analyse(&m, &c, &[(0, 1)]).unwrap();
        let period = rep.period as usize;
        let top = 150 - 150 % period;
        let r = ratios(&m, &c, &[(0, 1)], top + period);
        for (res, p) in rep.limit_points.iter().enumerate() {
            let (lo, hi) = approx(&rep, &p.value);
            prop_assert!(lo >= q(-1, 1 << 40) && hi <= q(1, 1) + q(1, 1 << 40));
            let early = dist(&rep, &p.value, &r[60 - 60 % period + res]);
            let late = dist(&rep, &p.value, &r[top + res]);
            prop_assert!(late < q(1, 20), "{:?} residue {}: |R - R_i| = {}", rep.reasons, res, late);
            prop_assert!(late <= &early + q(1, 1 << 40), "not shrinking: {} then {}", early, late);
        }
        if !rep.exists {
            prop_assert!(rep.limit_points.iter().any(|p| p.value != rep.limit_points[0].value));
        }
    }
}
