//! Exact counts per level: faces N^C_i, lacunas N^L_i and R_i (THEORY §5).
//!
//! Iterates on the vector of type multiplicities (never on individual faces), with big integers;
//! lacunas are kept in halves so every operation is an integer one.

use crate::topology::closure::TypeSet;
use num_bigint::BigUint;
use num_rational::BigRational;
use num_traits::Zero;
use serde::Serialize;

/// The counts at one level.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct LevelCount {
    /// The level i.
    pub level: u64,
    /// N^C_i.
    #[serde(serialize_with = "crate::topology::closure::ser_display")]
    pub faces: BigUint,
    /// N^L_i (a half-integer).
    #[serde(serialize_with = "crate::topology::closure::ser_display")]
    pub lacunas: BigRational,
    /// R_i = N^L_i / (N^L_i + N^C_i).
    #[serde(serialize_with = "crate::topology::closure::ser_display")]
    pub ratio: BigRational,
}

/// Counts from levels 0 to `levels` starting from the given multiplicities of types.
pub fn counts_from(ts: &TypeSet, start: &[(usize, u64)], levels: u64) -> Vec<LevelCount> {
    let matrix = ts.matrix();
    let halves: Vec<u64> = ts.types.iter().map(|t| t.contribution_halves()).collect();
    let mut v = vec![BigUint::zero(); ts.types.len()];
    for &(t, k) in start {
        v[t] += k;
    }
    let mut lacuna_halves = BigUint::zero();
    let mut out = Vec::with_capacity(levels as usize + 1);
    for level in 0..=levels {
        let faces: BigUint = v.iter().sum();
        let lacunas = BigRational::new(lacuna_halves.clone().into(), 2.into());
        // R_i = (h/2) / (h/2 + f) = h / (h + 2f) with h the lacunas in halves: one gcd,
        // gcd(h, h + 2f) = gcd(h, 2f), instead of the three of rational arithmetic.
        let ratio = if lacuna_halves.is_zero() {
            BigRational::zero()
        } else {
            let twice = &faces << 1u32;
            let g = num_integer::Integer::gcd(&lacuna_halves, &twice);
            BigRational::new_raw(
                (&lacuna_halves / &g).into(),
                ((&lacuna_halves + &twice) / &g).into(),
            )
        };
        out.push(LevelCount {
            level,
            faces,
            lacunas,
            ratio,
        });
        if level == levels {
            break;
        }
        for (vt, h) in v.iter().zip(&halves) {
            lacuna_halves += vt * h;
        }
        v = next_level(&matrix, &v);
    }
    out
}

/// One level down: the faces of each type that the faces counted in `v` give (`matrix` as
/// [`TypeSet::matrix`] returns it).
fn next_level(matrix: &[Vec<(usize, u64)>], v: &[BigUint]) -> Vec<BigUint> {
    let mut next = vec![BigUint::zero(); v.len()];
    for (t, vt) in v.iter().enumerate().filter(|(_, x)| !x.is_zero()) {
        for &(s, k) in &matrix[t] {
            next[s] += vt * k;
        }
    }
    next
}

/// The level-`level` faces of each type, the start faces of the type set taken together: the
/// start vector times the substitution matrix `level` times.
pub fn population(ts: &TypeSet, level: u64) -> Vec<BigUint> {
    let matrix = ts.matrix();
    let mut v = vec![BigUint::zero(); ts.types.len()];
    for &t in &ts.start {
        v[t] += 1u32;
    }
    (0..level).fold(v, |v, _| next_level(&matrix, &v))
}

/// Counts for the start faces of the type set taken together (an assembly: the total).
pub fn counts(ts: &TypeSet, levels: u64) -> Vec<LevelCount> {
    let start: Vec<(usize, u64)> = ts.start.iter().map(|&t| (t, 1)).collect();
    counts_from(ts, &start, levels)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::topology::closure::{close, Closure};
    use crate::topology::face::Face;
    use crate::topology::limits::Limits;

    fn ts(s: &str) -> TypeSet {
        match close(&Face::parse(s).unwrap(), &Limits::default()).unwrap() {
            Closure::Closed(ts) => ts,
            Closure::Runaway(r) => panic!("{r:?}"),
        }
    }

    #[test]
    fn f0_counts_match_the_spec() {
        // THEORY §5: N^L = 0, 5/2, 35/2, 215/2, 1295/2, 7775/2; N^C = 6^i; R_1 = 5/17.
        let c = counts(&ts("C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A1"), 5);
        let lac: Vec<String> = c.iter().map(|l| l.lacunas.to_string()).collect();
        assert_eq!(lac, ["0", "5/2", "35/2", "215/2", "1295/2", "7775/2"]);
        let faces: Vec<String> = c.iter().map(|l| l.faces.to_string()).collect();
        assert_eq!(faces, ["1", "6", "36", "216", "1296", "7776"]);
        assert_eq!(c[1].ratio.to_string(), "5/17");
    }

    #[test]
    fn square_counts_by_hand() {
        // Square of B2 → 4 pentagons (contribution 1 each step: central lacuna only),
        // pentagon → 5 pentagons. N^C: 1, 4, 20, 100; N^L: 0, 1, 1+4, 5+20 = 25.
        let c = counts(&ts("B2 B2 B2 B2 | B2 B2 B2 | A1"), 3);
        let got: Vec<(String, String)> = c
            .iter()
            .map(|l| (l.faces.to_string(), l.lacunas.to_string()))
            .collect();
        let want = [("1", "0"), ("4", "1"), ("20", "5"), ("100", "25")];
        assert_eq!(got, want.map(|(a, b)| (a.to_string(), b.to_string())));
    }

    #[test]
    fn level_200_is_exact() {
        // F0: N^C_i = 6^i and N^L_i = (6^i − 1)/2 (sum of 5/2·6^j, j < i).
        let c = counts(&ts("C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A1"), 200);
        let six = BigUint::from(6u32).pow(200);
        assert_eq!(c[200].faces, six);
        let want = BigRational::new((six - 1u32).into(), 2.into());
        assert_eq!(c[200].lacunas, want);
    }
}
