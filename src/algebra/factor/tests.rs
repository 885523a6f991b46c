use super::hensel::{lift_error_big, lift_error_u64};
use super::split::{fp_pow_half, frobenius_rows};
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

proptest! {
    /// Barrett reduction is `%` for every 64-bit value and every modulus below 2^31, the
    /// largest products (near p², near 2^64) included.
    #[test]
    fn barrett_reduction_is_remainder(x in any::<u64>(), p in 2u64..(1 << 31), k in 0u64..4) {
        let m = barrett(p);
        prop_assert_eq!(reduce(x, p, m), x % p);
        let near = (p * p).saturating_sub(k);
        prop_assert_eq!(reduce(near, p, m), near % p);
        prop_assert_eq!(reduce(u64::MAX - k, p, m), (u64::MAX - k) % p);
    }
}

/// Distinct-degree factorisation as it was before the Frobenius rows: one power h^p per step.
fn ddf_by_powers(f: &[u64], p: u64) -> Vec<(Fp, usize)> {
    let mut out = Vec::new();
    let mut f = f.to_vec();
    let x: Fp = vec![0, 1];
    let mut h = x.clone();
    let pe = BigUint::from(p);
    let mut d = 0;
    while f.len() > 1 {
        d += 1;
        if f.len() - 1 < 2 * d {
            let deg = f.len() - 1;
            out.push((f, deg));
            break;
        }
        h = fp_powmod(&h, &pe, &f, p);
        let g = fp_gcd(&f, &fp_sub(&h, &x, p), p);
        if g.len() > 1 {
            f = fp_divrem(&f, &g, p).0;
            h = fp_rem(&h, &f, p);
            out.push((g, d));
        }
    }
    out
}

proptest! {
    /// The distinct-degree factorisation through the Frobenius rows is the one by powers, on
    /// random monic square-free polynomials modulo small and word-size primes.
    #[test]
    fn ddf_frobenius_is_ddf_by_powers(
        c in prop::collection::vec(any::<u64>(), 2..=12),
        which in 0usize..4,
    ) {
        let p = [3u64, 7, 101, 2_147_483_629][which];
        let mut f: Fp = c.iter().map(|x| x % p).collect();
        f.push(1);
        let df = trim((1..f.len()).map(|i| f[i] * (i as u64 % p) % p).collect());
        prop_assume!(fp_gcd(&f, &df, p).len() == 1);
        prop_assert_eq!(ddf(&f, p), ddf_by_powers(&f, p));
    }
}

proptest! {
    /// The lifting error in machine integers is the one in big integers whenever it answers,
    /// for random lifted factors below m = p^k and random f (positive and negative, small and
    /// large); with m·p ≥ 2^63 it declines.
    #[test]
    fn lift_error_u64_is_lift_error_big(
        which in 0usize..3,
        k in 1u32..3,
        gs in prop::collection::vec(prop::collection::vec(any::<u64>(), 1..=4), 1..=4),
        fs in prop::collection::vec(any::<i64>(), 1..=14),
        wide in any::<bool>(),
    ) {
        let p = [3u64, 65_521, 2_147_483_629][which];
        let m = BigInt::from(p).pow(k);
        let mp = &m * p;
        let lifted: Vec<Vec<BigInt>> = gs
            .iter()
            .map(|g| g.iter().map(|&x| BigInt::from(x) % &m).collect())
            .collect();
        let n: usize = lifted.iter().map(|g| g.len() - 1).sum::<usize>() + 1;
        let f: Vec<BigInt> = (0..n)
            .map(|i| {
                let x = BigInt::from(fs[i % fs.len()]);
                if wide { x * BigInt::from(u64::MAX) } else { x }
            })
            .collect();
        let big = lift_error_big(&f, &lifted, &m, &mp, p);
        match lift_error_u64(&f, &lifted, &m, &mp, p) {
            Some(e) => prop_assert_eq!(e, big),
            None => prop_assert!(mp >= BigInt::from(1u64 << 63)),
        }
    }
}

/// Zassenhaus recombination as it was before the constant-term pre-test: every subset's whole
/// product is formed.
fn recombine_full_products(
    f: &[BigInt],
    mut pool: Vec<Vec<BigInt>>,
    m: &BigInt,
) -> Vec<Vec<BigInt>> {
    let mut f = f.to_vec();
    let mut out = Vec::new();
    let mut size = 1;
    'search: while 2 * size <= pool.len() {
        let k = pool.len();
        let mut subset: Vec<usize> = (0..size).collect();
        loop {
            let mut h = vec![BigInt::one()];
            for &i in &subset {
                let g = &pool[i];
                let mut c = vec![BigInt::zero(); h.len() + g.len() - 1];
                for (a, x) in h.iter().enumerate() {
                    for (b, y) in g.iter().enumerate() {
                        c[a + b] += x * y;
                    }
                }
                h = c.iter().map(|x| symmetric(x, m)).collect();
            }
            if !h[0].is_zero() && (&f[0] % &h[0]).is_zero() {
                if let Some(q) = int_div_exact(&f, &h) {
                    f = q;
                    out.push(h);
                    pool = (0..k)
                        .filter(|i| !subset.contains(i))
                        .map(|i| pool[i].clone())
                        .collect();
                    continue 'search;
                }
            }
            let Some(pos) = (0..size).rev().find(|&j| subset[j] < k - size + j) else {
                break;
            };
            subset[pos] += 1;
            for j in pos + 1..size {
                subset[j] = subset[j - 1] + 1;
            }
        }
        size += 1;
    }
    if f.len() > 1 {
        out.push(f);
    }
    out
}

proptest! {
    /// Recombination with the constant-term pre-test gives the factors of the one forming
    /// every product, in the same order, on products of distinct irreducibles (up to nine
    /// modular factors) lifted modulo the first few square-free primes.
    #[test]
    fn recombine_is_recombine_full_products(
        picks in prop::collection::btree_set(0usize..9, 1..5),
        which in 0usize..3,
    ) {
        let irr = irreducibles();
        let mut prod = Poly::from_ints(&[1]);
        for &i in &picks {
            prod = &prod * &irr[i];
        }
        let f = prod.primitive_int();
        let p = primes()
            .filter(|&p| {
                let fp = trim(f.iter().map(|a| residue(a, p)).collect());
                let dfp = trim((1..fp.len()).map(|i| fp[i] * (i as u64 % p) % p).collect());
                fp_gcd(&fp, &dfp, p).len() == 1
            })
            .nth(which)
            .unwrap();
        let fp: Fp = f.iter().map(|a| residue(a, p)).collect();
        let mut seed = 0x9E37_79B9_7F4A_7C15u64;
        let mut gs = Vec::new();
        for (g, d) in &ddf(&fp, p) {
            edf(g, *d, p, &mut seed, &mut gs);
        }
        let norm1: BigInt = f.iter().map(Signed::abs).sum();
        let bound = (BigInt::one() << (f.len() - 1)) * norm1;
        let (lifted, m) = hensel::hensel(&f, &gs, p, &bound);
        let fast = recombine(&f, lifted.clone(), &m, p).unwrap();
        prop_assert_eq!(fast, recombine_full_products(&f, lifted, &m));
    }
}

proptest! {
    /// Factoring each square-free part at the small scale gives the factors of the lcm scale in
    /// the same order (the replayed recombination included): products of distinct linear and
    /// quadratic factors with denominators that are powers of 2 and 3 (so that the two scales
    /// differ), several of the same degree, with and without a zero root and repeated factors.
    #[test]
    fn small_scale_factors_as_lcm_scale(
        lin in prop::collection::btree_set((-9i64..10, 0u32..5, 0u32..3), 0..5),
        quad in prop::collection::vec((-9i64..10, -9i64..10, 0u32..4), 0..3),
        zero_root in any::<bool>(),
        square in any::<bool>(),
    ) {
        let q = |n: i64, d: u32, t: u32| {
            num_rational::BigRational::new(
                n.into(),
                BigInt::from(2).pow(d) * BigInt::from(3).pow(t),
            )
        };
        let mut f = Poly::from_ints(&[1]);
        for &(n, d, t) in &lin {
            f = &f * &Poly::new(vec![q(n, d, t), q(1, 0, 0)]);
        }
        for &(b, c, d) in &quad {
            f = &f * &Poly::new(vec![q(c, 2 * d, 0), q(b, d, 0), q(1, 0, 0)]);
        }
        if zero_root {
            f = &f * &Poly::x();
        }
        if square && f.deg() > 0 {
            f = &f * &Poly::new(vec![q(1, 3, 0), q(1, 0, 0)]).pow(2);
        }
        prop_assume!(f.deg() > 0);
        let small = factor_with(&f, true).map(|v| format!("{v:?}"));
        let lcm = factor_with(&f, false).map(|v| format!("{v:?}"));
        prop_assert_eq!(small.map_err(|e| e.to_string()), lcm.map_err(|e| e.to_string()));
    }

    /// The replayed recombination finds every factor whose modular factors are listed, each
    /// once, and a factor made of one modular factor before any made of more.
    #[test]
    fn replay_finds_every_factor(owner in prop::collection::vec(0usize..5, 1..9)) {
        let mut ids: Vec<usize> = owner.clone();
        ids.sort_unstable();
        ids.dedup();
        let order = scaled::replay_recombination(owner.clone()).unwrap().unwrap();
        let mut sorted = order.clone();
        sorted.sort_unstable();
        prop_assert_eq!(sorted, ids);
        let size = |j: usize| owner.iter().filter(|&&o| o == j).count();
        let sizes: Vec<usize> = order.iter().map(|&j| size(j)).collect();
        let last = sizes.len() - 1;
        prop_assert!(sizes[..last].windows(2).all(|w| w[0] <= w[1]));
    }
}

#[test]
fn small_scale_is_smaller() {
    // x^2 + x/4 + 1/64: lcm scale 64, small scale 8.
    let q = |n: i64, d: i64| num_rational::BigRational::new(n.into(), d.into());
    let g = Poly::new(vec![q(1, 64), q(1, 4), q(1, 1)]);
    assert_eq!(scaled::lcm_scale(&g), BigInt::from(64));
    assert_eq!(scaled::small_scale(&g), BigInt::from(8));
}

/// Equal-degree splitting as it was before the Frobenius rows: `a^((p^d − 1)/2)` as one power.
fn edf_by_powers(f: &[u64], d: usize, p: u64, seed: &mut u64, out: &mut Vec<Fp>) {
    let n = f.len() - 1;
    if n == d {
        out.push(f.to_vec());
        return;
    }
    let e = (BigUint::from(p).pow(d as u32) - 1u32) / 2u32;
    loop {
        let a: Fp = trim(
            (0..n)
                .map(|_| {
                    *seed ^= *seed << 13;
                    *seed ^= *seed >> 7;
                    *seed ^= *seed << 17;
                    *seed % p
                })
                .collect(),
        );
        if a.len() < 2 {
            continue;
        }
        let b = fp_sub(&fp_powmod(&a, &e, f, p), &[1], p);
        let g = fp_gcd(f, &b, p);
        if g.len() > 1 && g.len() < f.len() {
            let other = fp_divrem(f, &g, p).0;
            edf_by_powers(&g, d, p, seed, out);
            edf_by_powers(&other, d, p, seed, out);
            return;
        }
    }
}

proptest! {
    /// The power through the Frobenius rows is the plain power `a^((p^d − 1)/2) mod f`, for
    /// random `a` and random monic `f` (square-free or not) modulo small and word-size primes.
    #[test]
    fn pow_half_is_powmod(
        c in prop::collection::vec(any::<u64>(), 1..=10),
        a in prop::collection::vec(any::<u64>(), 0..=14),
        d in 1usize..5,
        which in 0usize..4,
    ) {
        let p = [3u64, 7, 101, 2_147_483_629][which];
        let mut f: Fp = c.iter().map(|x| x % p).collect();
        f.push(1);
        let a = trim(a.iter().map(|x| x % p).collect());
        let rows = frobenius_rows(&f, p);
        let e = (BigUint::from(p).pow(d as u32) - 1u32) / 2u32;
        prop_assert_eq!(fp_pow_half(&a, d, &f, p, &rows), fp_powmod(&a, &e, &f, p));
    }

    /// Equal-degree splitting with the Frobenius rows gives the factors of the one by powers,
    /// in the same order (the same random elements split the same way), on the equal-degree
    /// parts of random square-free polynomials.
    #[test]
    fn edf_is_edf_by_powers(
        c in prop::collection::vec(any::<u64>(), 2..=12),
        which in 0usize..4,
    ) {
        let p = [3u64, 7, 101, 2_147_483_629][which];
        let mut f: Fp = c.iter().map(|x| x % p).collect();
        f.push(1);
        let df = trim((1..f.len()).map(|i| f[i] * (i as u64 % p) % p).collect());
        prop_assume!(fp_gcd(&f, &df, p).len() == 1);
        for (g, d) in ddf(&f, p) {
            let (mut s1, mut s2) = (0x9E37_79B9_7F4A_7C15u64, 0x9E37_79B9_7F4A_7C15u64);
            let (mut o1, mut o2) = (Vec::new(), Vec::new());
            edf(&g, d, p, &mut s1, &mut o1);
            edf_by_powers(&g, d, p, &mut s2, &mut o2);
            prop_assert_eq!(o1, o2);
        }
    }
}

/// Powers modulo `f` as they were before [`Reducer`]: every remainder by [`fp_rem`].
fn powmod_by_rem(a: &[u64], e: &BigUint, f: &[u64], p: u64) -> Fp {
    let mut r: Fp = vec![1];
    let base = fp_rem(a, f, p);
    for i in (0..e.bits()).rev() {
        r = fp_rem(&fp_mul(&r, &r, p), f, p);
        if e.bit(i) {
            r = fp_rem(&fp_mul(&r, &base, p), f, p);
        }
    }
    r
}

proptest! {
    /// Powers through the reducer are those through `fp_rem`, for monic and non-monic `f` of
    /// every degree from 0, random bases and exponents, small and word-size primes.
    #[test]
    fn reducer_powmod_is_powmod_by_rem(
        c in prop::collection::vec(any::<u64>(), 0..=10),
        lead in 1u64..1000,
        a in prop::collection::vec(any::<u64>(), 0..=14),
        e in any::<u64>(),
        which in 0usize..4,
    ) {
        let p = [3u64, 7, 101, 2_147_483_629][which];
        let mut f: Fp = c.iter().map(|x| x % p).collect();
        f.push(lead % (p - 1) + 1);
        let a = trim(a.iter().map(|x| x % p).collect());
        let e = BigUint::from(e);
        prop_assert_eq!(fp_powmod(&a, &e, &f, p), powmod_by_rem(&a, &e, &f, p));
        let r = Reducer::new(&f, p);
        let prod = fp_mul(&a, &a, p);
        prop_assert_eq!(r.rem(prod.clone()), fp_rem(&prod, &f, p));
    }
}
