//! Property tests of the contraction proof (brief autofin): random one-state automata with two
//! barycentric operators on three points, whose actions on the differences of points are random
//! 2 × 2 matrices A0, A1 of small dyadic entries (T[i][j] = A[i][j] for i, j < 2, third column
//! (0, 0, 1), last row completing the columns to 1 — so T's restriction is exactly A).
//!
//! Checked independently of the library, in floating point with a margin:
//! - "proven" ⇒ every product of up to 6 operators has spectral radius < 1 (a necessary condition
//!   of a joint spectral radius < 1);
//! - E0715 naming a cycle ⇒ that cycle's product has spectral radius ≥ 1;
//! - E0721 only when no product of up to 2 operators has spectral radius ≥ 1 (otherwise the search
//!   would have refused it on the way).

use lacuna::analysis::{check_contraction_within, resolve};
use lacuna::input::parse_model;
use lacuna::Source;
use proptest::prelude::*;

type M2 = [[f64; 2]; 2];

fn mul(a: &M2, b: &M2) -> M2 {
    let mut c = [[0.0; 2]; 2];
    for i in 0..2 {
        for j in 0..2 {
            c[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j];
        }
    }
    c
}

/// Spectral radius of a real 2 × 2 matrix.
fn rho(a: &M2) -> f64 {
    let (t, d) = (a[0][0] + a[1][1], a[0][0] * a[1][1] - a[0][1] * a[1][0]);
    let disc = t * t / 4.0 - d;
    if disc >= 0.0 {
        (t / 2.0).abs() + disc.sqrt()
    } else {
        d.abs().sqrt()
    }
}

fn product(word: &[usize], ops: &[M2; 2]) -> M2 {
    word.iter()
        .fold([[1.0, 0.0], [0.0, 1.0]], |p, &o| mul(&p, &ops[o]))
}

fn entry() -> impl Strategy<Value = i32> {
    -8i32..=8
}

fn text(a: &[[[i32; 2]; 2]; 2]) -> String {
    // Entries k/8; T = [a00 a01 0; a10 a11 0; 1−a00−a10 1−a01−a11 1].
    let q = |k: i32| format!("{k}/8");
    let mut s = String::from("state e 3\n");
    for (o, m) in a.iter().enumerate() {
        let last = |j: usize| format!("{}/8", 8 - m[0][j] - m[1][j]);
        s += &format!(
            "sub e.T{o} : e <- e = [{} {} 0; {} {} 0; {} {} 1]\n",
            q(m[0][0]),
            q(m[0][1]),
            q(m[1][0]),
            q(m[1][1]),
            last(0),
            last(1)
        );
    }
    s + "barycentric\nspace 2\n"
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    #[test]
    fn the_proof_and_the_refusals_agree_with_the_spectra(
        e in proptest::array::uniform2(proptest::array::uniform2(proptest::array::uniform2(entry())))
    ) {
        let ops: [M2; 2] = e.map(|m| m.map(|r| r.map(|k| f64::from(k) / 8.0)));
        let src = text(&e);
        let m = parse_model(&Source::command_line(&src)).expect("a model");
        let r = resolve(&m, &[], 10_000).expect("resolved");
        match check_contraction_within(&m, &r.ops, 300) {
            Ok(_) => {
                let mut words: Vec<Vec<usize>> = vec![Vec::new()];
                for _ in 0..6 {
                    words = words
                        .into_iter()
                        .flat_map(|w| (0..2).map(move |o| [w.clone(), vec![o]].concat()))
                        .collect();
                    for w in &words {
                        let p = rho(&product(w, &ops));
                        prop_assert!(p < 1.0 + 1e-9, "proven, but {w:?} has spectral radius {p}\n{src}");
                    }
                }
            }
            Err(err) => {
                let msg = err.render();
                if msg.contains("E0715") {
                    // "the cycle e.T0 · e.T1 does not contract": its operators in order.
                    let cycle = msg.split("the cycle ").nth(1).unwrap().split(" does not").next().unwrap();
                    let word: Vec<usize> = cycle
                        .split(" · ")
                        .map(|n| n.trim().trim_start_matches("e.T").parse().unwrap())
                        .collect();
                    let p = rho(&product(&word, &ops));
                    prop_assert!(p > 1.0 - 1e-9, "refused {cycle}, spectral radius {p}\n{src}");
                } else {
                    prop_assert!(msg.contains("E0721"), "{msg}");
                    for w in [vec![0], vec![1], vec![0, 1]] {
                        let p = rho(&product(&w, &ops));
                        prop_assert!(p < 1.0 + 1e-9, "undecided, but {w:?} has spectral radius {p}\n{src}");
                    }
                }
            }
        }
    }
}
