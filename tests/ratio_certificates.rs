//! Certificates of the limit ratio (issue #5) in every case the checker covers: irrational Perron
//! roots, equal radii in a chain, periodic dominant classes, ρ = 1; and mutations of the claims,
//! each rejected at the `limit-ratio` step. Values are derived by hand in the comments.

mod common;
use common::{assert_proved, assert_rejected, face_certificate, steps_named};
use lacuna::certificate::ratio_step;
use lacuna::certificate::{Certificate, Claim, RadiusWitness, RatioStep, Step, SubstitutionClaim};
use lacuna::checker::check;
use num_rational::BigRational;

/// The golden-ratio substitution: a transient start type 0 → 1; the class {1, 2} with
/// 1 → 1 + 2, 2 → 1 (ρ = (1 + √5)/2); a downstream class {3} (3 → 3) reached from 2.
fn golden_matrix() -> (Vec<Vec<(usize, u64)>>, Vec<u64>) {
    let m = vec![
        vec![(1, 1)],
        vec![(1, 1), (2, 1)],
        vec![(1, 1), (3, 1)],
        vec![(3, 1)],
    ];
    (m, vec![2, 1, 3, 0])
}

fn golden() -> RatioStep {
    let (m, h) = golden_matrix();
    ratio_step(&m, &h, &[(0, 1)]).expect("analyses")
}

/// The certificate claiming the substitution `(matrix, halves)` from one face of type 0, with
/// `step` as its limit ratio.
fn ratio_certificate(matrix: &[Vec<(usize, u64)>], halves: &[u64], step: RatioStep) -> Certificate {
    let claim = Claim::Substitution(SubstitutionClaim {
        matrix: matrix.to_vec(),
        contribution_halves: halves.to_vec(),
        start: vec![(0, 1)],
    });
    let mut cert = Certificate::new("matrix", claim);
    cert.steps.push(Step::LimitRatio(step));
    cert
}

fn golden_certificate(step: RatioStep) -> Certificate {
    let (m, h) = golden_matrix();
    ratio_certificate(&m, &h, step)
}

/// The ratio step of `matrix` (rows `(sub-face type, count)`), contributions in halves, one
/// start face of type 0; asserts that it checks.
fn proved_step(what: &str, matrix: &[Vec<(usize, u64)>], halves: &[u64]) -> RatioStep {
    let step = ratio_step(matrix, halves, &[(0, 1)]).expect("analyses");
    assert_proved(what, &ratio_certificate(matrix, halves, step.clone()));
    step
}

fn values(step: &RatioStep) -> Vec<String> {
    step.points.iter().map(|p| p.value.join(" ")).collect()
}

fn bump(s: &mut String) {
    *s = (s.parse::<BigRational>().unwrap() + BigRational::new(1.into(), 7.into())).to_string();
}

#[test]
fn irrational_perron_roots_are_certified() {
    let step = golden();
    assert_eq!(step.rho.poly, ["-1", "-1", "1"]);
    assert_eq!(step.points[0].value.len(), 2, "R is irrational here");
    assert_eq!(step.points[0].real.poly.len(), 3, "R is quadratic");
    let cert = golden_certificate(step.clone());
    assert_proved("golden", &cert);
    // Nudge the interval past ρ ≈ 1.618: it no longer isolates the root.
    let nudge = |lo: &str, hi: &str| {
        let mut s = step.clone();
        (s.rho.lo, s.rho.hi) = (lo.into(), hi.into());
        golden_certificate(s)
    };
    assert_rejected("interval beyond ρ", &nudge("13/8", "2"), "limit-ratio");
    assert_rejected(
        "interval holding both roots",
        &nudge("-1", "2"),
        "limit-ratio",
    );
    let mut s = step.clone();
    s.points[0].value[1] = format!(
        "{}",
        s.points[0].value[1].parse::<BigRational>().unwrap() * BigRational::from_integer(2.into())
    );
    assert_rejected("wrong limit", &golden_certificate(s), "limit-ratio");
    let mut s = step.clone();
    if let RadiusWitness::Perron(y) = &mut s.classes[1].radius {
        y[1][0] = "7".into();
    }
    assert_rejected("wrong eigenvector", &golden_certificate(s), "limit-ratio");
    // R's own interval: moved off R (it still isolates a root of nothing there).
    let mut s = step.clone();
    s.points[0].real.lo = s.points[0].real.hi.clone();
    bump(&mut s.points[0].real.hi);
    assert_rejected("interval of R moved", &golden_certificate(s), "limit-ratio");
    let mut s = step.clone();
    s.points[0].real.poly[0] = "5".into();
    assert_rejected(
        "wrong polynomial of R",
        &golden_certificate(s),
        "limit-ratio",
    );
    // A matrix entry of the claim changed: the step no longer fits it.
    let mut cert = golden_certificate(step);
    if let Claim::Substitution(sub) = &mut cert.claim {
        sub.matrix[2][0].1 = 2;
    }
    assert_rejected("flip a matrix entry", &cert, "limit-ratio");
}

#[test]
fn flipped_matrix_entries_are_rejected_against_the_closure() {
    // The ratio step carries no matrix: it is about the closure's substitution. A class witness
    // of another substitution is rejected.
    let mut cert = face_certificate("triangle-C2");
    if let [Step::LimitRatio(r)] = &mut steps_named(&mut cert, "limit-ratio")[..] {
        r.classes[0].members.push(99);
    }
    assert_rejected("a class of another matrix", &cert, "limit-ratio");
}

#[test]
fn equal_radii_in_a_chain_are_certified() {
    // a → {a, a, b}, b → {b, b}: M = [[2, 1], [0, 2]], two classes of radius 2 in a chain. From
    // one a: a_i = 2^i, b_i = i·2^(i−1), N^C_i = 2^(i−1)(i + 2),
    // N^L_i = c_a(2^i − 1) + c_b((i − 2)·2^(i−1) + 1). Both grow like i·2^i when c_b > 0 (pole
    // orders 2 and 2) and R = c_b/(c_b + 1); with c = (1/2, 1): R = 1/2.
    let m = vec![vec![(0, 2), (1, 1)], vec![(1, 2)]];
    let step = proved_step("chain, c_b = 1", &m, &[1, 2]);
    assert!(step.exists && step.period == 1);
    assert!(step
        .classes
        .iter()
        .all(|c| matches!(c.radius, RadiusWitness::Perron(_))));
    assert_eq!(values(&step), ["1/2"]);
    // c = (3, 0): N^L_i = 3(2^i − 1) is of lower order than N^C_i: R = 0.
    assert_eq!(values(&proved_step("chain, c_b = 0", &m, &[6, 0])), ["0"]);
    // Three classes of radius 2 in a chain a → b → c (pole order 3): N^C_i ~ i²·2^i/8,
    // lacunas only at c: N^L_i ~ c_c·Σ_(j<i) j²·2^j/8 ~ c_c·i²·2^i/8: R = c_c/(c_c + 1) = 1/3
    // with c_c = 1/2.
    let m = vec![vec![(0, 2), (1, 1)], vec![(1, 2), (2, 1)], vec![(2, 2)]];
    assert_eq!(
        values(&proved_step("chain of three", &m, &[0, 0, 1])),
        ["1/3"]
    );
}

#[test]
fn shared_radius_fixture_is_certified() {
    // fixtures/shared-radius-pentagons.txt: two one-type classes P → 5P, P' → 5P', contribution 1
    // each, one start face of each: N^C_i = 2·5^i, N^L_i = 2(5^i − 1)/4, R = (1/2)/(1/2 + 2) = 1/5.
    let cert = face_certificate("shared-radius-pentagons");
    let Some(Step::LimitRatio(r)) = cert.steps.iter().find(|s| s.name() == "limit-ratio") else {
        panic!("no ratio step")
    };
    assert_eq!(r.classes.len(), 2);
    assert!(r
        .classes
        .iter()
        .all(|c| matches!(c.radius, RadiusWitness::Perron(_))));
    assert_eq!(values(r), ["1/5"]);
    assert!(check(&cert).all_proved());
}

#[test]
fn periodic_dominant_classes_are_certified() {
    // a → 2b, b → 8a: ρ = 4, period 2. Level 2j: 16^j faces a; level 2j+1: 2·16^j faces b.
    // N^L_(2j) = (16^j − 1)/15·S, S = c_a + 2c_b: R_(2j) → S/(S + 15);
    // N^L_(2j+1) = N^L_(2j) + 16^j·c_a: R_(2j+1) → T/(T + 30), T = 16c_a + 2c_b.
    let m = vec![vec![(1, 2)], vec![(0, 8)]];
    // c = (1, 0): S = 1, T = 16: no limit, limit points 1/16 and 16/46 = 8/23.
    let step = proved_step("periodic, oscillating", &m, &[2, 0]);
    assert!(!step.exists);
    assert_eq!(step.period, 2);
    assert_eq!(values(&step), ["1/16", "8/23"]);
    assert_eq!(step.points[0].decimal, "0.062500000000000000000000000000");
    // c = (1/2, 7/2): S = 15/2, T = 15: both residues give 1/3, the limit exists.
    let step = proved_step("periodic, converging", &m, &[1, 7]);
    assert!(step.exists);
    assert_eq!(values(&step), ["1/3", "1/3"]);
}

#[test]
fn radius_one_is_certified() {
    // a → a: N^C_i = 1, N^L_i = i·c: R = 1 if c > 0, else 0.
    assert_eq!(
        values(&proved_step("a → a, c = 1", &[vec![(0, 1)]], &[2])),
        ["1"]
    );
    assert_eq!(
        values(&proved_step("a → a, c = 0", &[vec![(0, 1)]], &[0])),
        ["0"]
    );
    // a → b → a, c = (1, 0): period 2 at radius 1; N^C = 1, N^L_i = ⌈i/2⌉: R = 1 on both residues.
    let step = proved_step("a ⇄ b", &[vec![(1, 1)], vec![(0, 1)]], &[2, 0]);
    assert!(step.exists && step.period == 2);
    assert_eq!(values(&step), ["1", "1"]);
    // a → {a, b}, b → b, c = (1, 0): N^C_i = i + 1, N^L_i = i: R = 1/2 (two radius-1 classes
    // in a chain and the lacuna type: pole orders 2 and 2).
    let m = vec![vec![(0, 1), (1, 1)], vec![(1, 1)]];
    assert_eq!(values(&proved_step("radius-1 chain", &m, &[2, 0])), ["1/2"]);
    // a → {a, b}, b → 2b, c = (7, 1/2): a (radius 1) feeds b (radius 2); only b matters:
    // R = (1/2)/(1/2 + 2 − 1) = 1/3, a's linear lacunas are negligible.
    let m = vec![vec![(0, 1), (1, 1)], vec![(1, 2)]];
    let step = proved_step("radius 1 feeding 2", &m, &[14, 1]);
    assert_eq!(values(&step), ["1/3"]);
    assert!(matches!(step.classes[0].radius, RadiusWitness::Below(_)));
}

#[test]
fn mutated_limit_claims_are_rejected() {
    let m = vec![vec![(1, 2)], vec![(0, 8)]];
    let oscillating = (
        m.clone(),
        vec![2, 0],
        ratio_step(&m, &[2, 0], &[(0, 1)]).expect("analyses"),
    );
    let converging = (
        m.clone(),
        vec![1, 7],
        ratio_step(&m, &[1, 7], &[(0, 1)]).expect("analyses"),
    );
    type Case = (Vec<Vec<(usize, u64)>>, Vec<u64>, RatioStep);
    let rejected = |what: &str, (m, h, step): &Case, edit: &dyn Fn(&mut RatioStep)| {
        let mut s = step.clone();
        edit(&mut s);
        assert_ne!(&s, step, "{what}: the mutation changed nothing");
        assert_rejected(what, &ratio_certificate(m, h, s), "limit-ratio");
    };
    rejected("claim a limit that does not exist", &oscillating, &|s| {
        s.exists = true
    });
    rejected("deny a limit that exists", &converging, &|s| {
        s.exists = false
    });
    rejected("nudge a limit point", &oscillating, &|s| {
        bump(&mut s.points[1].value[0])
    });
    rejected("swap the limit points", &oscillating, &|s| {
        s.points.swap(0, 1)
    });
    rejected("claim period 1", &oscillating, &|s| {
        s.period = 1;
        s.points.truncate(1);
    });
    rejected("claim period 4", &converging, &|s| {
        s.period = 4;
        s.points.extend(s.points.clone());
    });
    rejected("claim a class period", &oscillating, &|s| {
        s.classes[0].period = Some(1)
    });
    rejected("nudge the interval of R", &oscillating, &|s| {
        bump(&mut s.points[0].real.lo);
        s.points[0].real.hi = s.points[0].real.lo.clone();
    });
    rejected("wrong decimals", &oscillating, &|s| {
        s.points[0].decimal = "0.062600000000000000000000000000".into()
    });
    rejected("nudge ρ", &oscillating, &|s| {
        s.rho.poly = vec!["-5".into(), "1".into()];
        (s.rho.lo, s.rho.hi) = ("5".into(), "5".into());
    });
    rejected(
        "a dominant class passed off as smaller",
        &converging,
        &|s| s.classes[0].radius = RadiusWitness::Below(vec!["1".into(), "1".into()]),
    );
    // A smaller class's bound is not a Perron vector, nor the other way round.
    let fm = vec![vec![(0, 1), (1, 1)], vec![(1, 2)]];
    let feeding = (
        fm.clone(),
        vec![14, 1],
        ratio_step(&fm, &[14, 1], &[(0, 1)]).expect("analyses"),
    );
    rejected("a smaller class passed off as dominant", &feeding, &|s| {
        s.classes[0].radius = RadiusWitness::Perron(vec![vec!["1".into()]])
    });
    rejected(
        "a Collatz–Wielandt vector that is not positive",
        &feeding,
        &|s| s.classes[0].radius = RadiusWitness::Below(vec!["0".into()]),
    );
    rejected(
        "the dominant class's witness moved to the other class",
        &feeding,
        &|s| s.classes.swap(0, 1),
    );
}
