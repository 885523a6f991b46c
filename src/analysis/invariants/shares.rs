//! The limit shares of the valences (THEORY §13): the share of the vertices of the level-k
//! complex that have valence v, as k grows, exactly.
//!
//! When the valences are bounded the counts of the complex step linearly over finitely many
//! states ([`VertexSystem`]: closed vertex types, edge cells, face types), so the number of
//! vertices of valence v at level k is `a_v · M^k c_0` and the share is `a_v·c_k / 1·c_k`. The
//! limit is decided like the limit ratio R (`analysis/ratio`): with `ρ` the largest spectral
//! radius and `P` the lcm of the periods of the classes of radius `ρ`, each subsequence
//! `x_{Pn+r}` has the generating function `N(w)/det(I − w·M^P)` whose only dominant pole is
//! `w₀ = ρ^(−P)`; its coefficients grow like `n^(k−1)·ρ^(Pn)` times `Ñ(w₀)` (`k` the pole order)
//! up to a factor common to every count with the same pole order. So the valences of the highest
//! pole order share the limit in proportion to their `Ñ(w₀)` (elements of Q(ρ)), the others have
//! share 0; the limit exists iff every residue `r` gives the same shares. With an unbounded valence
//! there is no finite system and nothing is claimed.

use crate::algebra::algebraic::{FieldElement, NumberField, DEFAULT_DIGITS};
use crate::analysis::ratio::{numerator, reflect, spectrum, split_off, Spectrum};
use crate::error::{Error, Result};
use crate::topology::{Multiplicity, VertexSystem};
use num_bigint::BigInt;
use num_traits::Zero;
use serde::Serialize;
use std::collections::BTreeSet;

/// The limit share of one valence.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct LimitShare {
    /// The valence.
    pub valence: usize,
    /// The share, exact (`1/3`, `(a + b*sqrt(d))/c`, or a polynomial in ρ with ρ's minimal
    /// polynomial and isolating interval).
    pub share: String,
    /// Certified decimals of the share (truncated).
    pub decimal: String,
    /// Whether `share` is a canonical form (rational or quadratic), so that two equal shares
    /// read the same string whatever field they were computed in.
    #[serde(skip)]
    pub canonical: bool,
}

/// The limit shares of the valences of a structure.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
#[serde(tag = "status", rename_all = "snake_case")]
pub enum LimitShares {
    /// The shares converge; one entry per valence met at any level, ascending.
    Exact {
        /// The shares.
        shares: Vec<LimitShare>,
    },
    /// The shares oscillate: level `Pn + r` tends to `residues[r]`, not all equal.
    NoLimit {
        /// `P`.
        period: u64,
        /// The limit points, one list per residue `r = 0..P`.
        residues: Vec<Vec<LimitShare>>,
    },
    /// Not decided, and why.
    NotDecided {
        /// Why, in words.
        reason: String,
    },
}

impl std::fmt::Display for LimitShares {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let list = |s: &[LimitShare]| {
            s.iter()
                .map(|x| {
                    // Eight decimals for people (truncated, like the certified ones); the exact
                    // value when it is short.
                    let short = match x.decimal.find('.') {
                        Some(p) if x.decimal.len() > p + 9 => format!("{}…", &x.decimal[..p + 9]),
                        _ => x.decimal.clone(),
                    };
                    if x.share.len() > 40 {
                        format!("{}: {short}", x.valence)
                    } else if x.share.parse::<i64>().is_ok() {
                        format!("{}: {}", x.valence, x.share)
                    } else {
                        format!("{}: {} ≈ {short}", x.valence, x.share)
                    }
                })
                .collect::<Vec<_>>()
                .join("; ")
        };
        match self {
            LimitShares::Exact { shares } => write!(f, "{}", list(shares)),
            LimitShares::NoLimit { period, residues } => {
                write!(f, "no limit: levels k mod {period} tend to")?;
                for (r, s) in residues.iter().enumerate() {
                    write!(f, " [{r}: {}]", list(s))?;
                }
                Ok(())
            }
            LimitShares::NotDecided { reason } => write!(f, "not decided: {reason}"),
        }
    }
}

/// The limit shares of the valences of a complex ([`Multiplicity`] of faces or an assembly).
pub fn limit_shares(m: &Multiplicity) -> Result<LimitShares> {
    let Some(sys) = &m.system else {
        return Ok(LimitShares::NotDecided {
            reason:
                "a valence grows without bound, so the vertex types do not close into a finite \
                     linear system"
                    .into(),
        });
    };
    shares_of(sys)
}

/// The limit shares of the valences of a vertex system (module doc).
pub fn shares_of(sys: &VertexSystem) -> Result<LimitShares> {
    let start_types: Vec<usize> = sys
        .start
        .iter()
        .filter(|&&(_, k)| k > 0)
        .map(|&(s, _)| s)
        .collect();
    let Spectrum {
        reached,
        rho,
        period,
        det,
        ..
    } = spectrum(&sys.step, &start_types).map_err(|e| Error::Analysis(e.to_string()))?;
    let valences: Vec<usize> = reached
        .iter()
        .filter_map(|&s| sys.valence[s])
        .collect::<BTreeSet<_>>()
        .into_iter()
        .collect();
    if valences.is_empty() {
        return Ok(LimitShares::NotDecided {
            reason: "the complex has no vertex".into(),
        });
    }
    let field = NumberField::new(rho.clone());
    let f = rho.min_poly().clone();
    let p = usize::try_from(period).map_err(|_| Error::Analysis("period above usize".into()))?;
    let dim = reached.len();
    // The first P·dim terms of the count of each valence.
    let mut x = vec![BigInt::zero(); sys.step.len()];
    for &(s, k) in &sys.start {
        x[s] += k;
    }
    let mut seqs: Vec<Vec<BigInt>> = vec![Vec::with_capacity(p * dim); valences.len()];
    for _ in 0..p * dim {
        for (i, &v) in valences.iter().enumerate() {
            seqs[i].push(
                reached
                    .iter()
                    .filter(|&&s| sys.valence[s] == Some(v))
                    .map(|&s| &x[s])
                    .sum(),
            );
        }
        let mut y = vec![BigInt::zero(); x.len()];
        for &s in &reached {
            if x[s].is_zero() {
                continue;
            }
            for &(t, k) in &sys.step[s] {
                y[t] += &x[s] * k;
            }
        }
        x = y;
    }
    let (ord_d, _) = split_off(&reflect(&det, p, dim), &f);
    let mut residues = Vec::with_capacity(p);
    for r in 0..p {
        // Pole order at w₀ and Ñ(w₀) (up to the common factor) of each valence's count.
        let lead: Vec<(usize, Option<FieldElement>)> = seqs
            .iter()
            .map(|seq| {
                let n = numerator(&det, seq, p, dim, r);
                if n.iter().all(Zero::is_zero) {
                    return (0, None);
                }
                let (e, h) = split_off(&reflect(&n, p, dim - 1), &f);
                (ord_d.saturating_sub(e), Some(field.element(&h)))
            })
            .collect();
        let top = lead.iter().map(|(k, _)| *k).max().unwrap_or(0);
        if top == 0 {
            return Ok(LimitShares::NotDecided {
                reason: format!(
                    "the vertices of the levels k = {r} mod {period} grow more slowly than rho^k"
                ),
            });
        }
        let mut total = field.rational(Zero::zero());
        for (k, a) in &lead {
            if let (true, Some(a)) = (*k == top, a) {
                total = field.add(&total, a);
            }
        }
        let mut shares = Vec::with_capacity(valences.len());
        for (i, (k, a)) in lead.iter().enumerate() {
            let value = match (a, *k == top) {
                (Some(a), true) => field
                    .div(a, &total)
                    .ok_or_else(|| Error::Analysis("leading terms cancel".into()))?,
                _ => field.rational(Zero::zero()),
            };
            shares.push((valences[i], value));
        }
        residues.push(shares);
    }
    let named = |s: &[(usize, FieldElement)]| -> Vec<LimitShare> {
        s.iter()
            .map(|(v, x)| LimitShare {
                valence: *v,
                share: field.render(x),
                decimal: field.decimal(x, DEFAULT_DIGITS),
                canonical: x.as_rational().is_some() || field.degree() == 2,
            })
            .collect()
    };
    if residues.iter().all(|s| *s == residues[0]) {
        Ok(LimitShares::Exact {
            shares: named(&residues[0]),
        })
    } else {
        Ok(LimitShares::NoLimit {
            period,
            residues: residues.iter().map(|s| named(s)).collect(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::topology::{close_or_error, multiplicity, Face, Limits};

    fn shares(text: &str) -> LimitShares {
        let ts = close_or_error(&[Face::parse(text).unwrap()], &Limits::default()).unwrap();
        limit_shares(&multiplicity(&ts, &[], 0, 400).unwrap()).unwrap()
    }

    fn exact(s: &LimitShares) -> Vec<(usize, &str)> {
        match s {
            LimitShares::Exact { shares } => shares
                .iter()
                .map(|x| (x.valence, x.share.as_str()))
                .collect(),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn f0_tends_to_valence_3() {
        // THEORY §13 (and topology::vertex's closed forms): level k of F0 has 6·2^k vertices of
        // valence 2 and 3·6^k − 3·2^k of valence 3, so the share of 2 is
        // 6·2^k / (3·6^k + 3·2^k) → 0 and that of 3 tends to 1.
        assert_eq!(
            exact(&shares("C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A1")),
            vec![(2, "0"), (3, "1")]
        );
    }

    #[test]
    fn b2_square_shares_four_fifths_and_one_fifth() {
        // The square `B2 B2 B2 B2 | B2 B2 B2 | A1`: spokes at the 4 joints, none at a corner, so
        // a vertex keeps its valence once born. Its sub-faces are B2 pentagons (a piece of each
        // of two sides, a spoke Ea, the lacuna side El, a spoke), which split into 5 pentagons:
        // F_0 = 1, F_k = 4·5^(k−1). Edge cells: outer O_k = 4·2^k; shared (spokes and their
        // pieces) S_{k+1} = 2 S_k + (spokes of level k) with S_0 = 0, S_1 = 4, so
        // S_k = (4/3)(5^k − 2^k); at holes H_k = S_k (one El per spoke).
        // Births of a step: a lacuna corner per spoke (two sub-faces and the lacuna: 3); a joint
        // per edge cell: on an outer or hole edge two sub-faces and the hole (3), on a shared
        // edge two sub-faces on each side (4).
        //   n2_k = 4 (the square's corners),
        //   n4_k = Σ_{j<k} S_j = (5^k − 1)/3 − (4/3)(2^k − 1),
        //   n3_k = Σ_{j<k} (4·5^j + O_j + H_j) = (4/3)(5^k − 1) + (8/3)(2^k − 1).
        // Shares: n3/V → (4/3)/(4/3 + 1/3) = 4/5, n4/V → 1/5, n2/V → 0.
        let s = shares("B2 B2 B2 B2 | B2 B2 B2 | A1");
        assert_eq!(exact(&s), vec![(2, "0"), (3, "4/5"), (4, "1/5")]);
        // The closed forms themselves, level by level (a check of the derivation).
        let ts = close_or_error(
            &[Face::parse("B2 B2 B2 B2 | B2 B2 B2 | A1").unwrap()],
            &Limits::default(),
        )
        .unwrap();
        let m = multiplicity(&ts, &[], 6, 400).unwrap();
        for l in &m.levels {
            let (five, two) = (5i64.pow(l.level as u32), 2i64.pow(l.level as u32));
            let n3 = (4 * (five - 1) + 8 * (two - 1)) / 3;
            let n4 = (five - 1 - 4 * (two - 1)) / 3;
            let want: Vec<(usize, String)> = [(2, 4), (3, n3), (4, n4)]
                .into_iter()
                .filter(|&(_, n)| n > 0)
                .map(|(v, n)| (v, n.to_string()))
                .collect();
            let got: Vec<(usize, String)> =
                l.valences.iter().map(|(v, n)| (*v, n.clone())).collect();
            assert_eq!(got, want, "level {}", l.level);
        }
    }

    #[test]
    fn shares_agree_with_the_counts_of_a_deep_level() {
        // An independent way to the limit: the valence counts of level 14, built level by level
        // (no eigenvalue), divided by the vertex count. Floats only compare the two here; the
        // gap is the decay of the subdominant terms, far below 0.01 at level 14 for these faces.
        for text in [
            "C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A1",
            "B2 B2 B2 B2 | B2 B2 B2 | A1",
            "B2 B2 B2 B2 | B2 C2 B2 | A1",
            "B2 B2 B2 B2 | C2 C2 B2 | A1",
            "C3 B2 B2 | C2 C2 B2 | A1",
        ] {
            let ts = close_or_error(&[Face::parse(text).unwrap()], &Limits::default()).unwrap();
            let m = multiplicity(&ts, &[], 14, 400).unwrap();
            let LimitShares::Exact { shares } = limit_shares(&m).unwrap() else {
                panic!("{text}: no limit");
            };
            let last = m.levels.last().unwrap();
            let total: f64 = last.vertices.to_string().parse().unwrap();
            let mut sum = 0.0;
            for x in &shares {
                let n: f64 = last
                    .valences
                    .get(&x.valence)
                    .map_or(0.0, |n| n.parse().unwrap());
                let exact: f64 = x.decimal.parse().unwrap();
                sum += exact;
                assert!(
                    (n / total - exact).abs() < 0.01,
                    "{text}: valence {} has {} at level 14, the limit is {}",
                    x.valence,
                    n / total,
                    x.share
                );
            }
            assert!((sum - 1.0).abs() < 1e-9, "{text}: shares sum to {sum}");
        }
    }

    #[test]
    fn periodic_births_have_no_limit() {
        // A system made by hand: face types A (state 0) and B (1) with A → 2 B and a vertex of
        // valence 3 (state 2), B → 2 A and a vertex of valence 4 (3); vertices stay. From one A,
        // level k has 2^k faces, of type A for even k; the births of the step from level j are
        // 2^j vertices of valence 3 (j even) or 4 (j odd). At k = 2n: n3 = (4^n − 1)/3,
        // n4 = 2(4^n − 1)/3, shares 1/3 and 2/3; at k = 2n + 1: n3 = (4^(n+1) − 1)/3,
        // n4 = 2(4^n − 1)/3, shares tending to 4/6 = 2/3 and 1/3. No limit, period 2.
        let sys = VertexSystem {
            step: vec![
                vec![(1, 2), (2, 1)],
                vec![(0, 2), (3, 1)],
                vec![(2, 1)],
                vec![(3, 1)],
            ],
            start: vec![(0, 1)],
            valence: vec![None, None, Some(3), Some(4)],
        };
        let LimitShares::NoLimit { period, residues } = shares_of(&sys).unwrap() else {
            panic!("a limit")
        };
        assert_eq!(period, 2);
        let at = |r: usize| -> Vec<(usize, String)> {
            residues[r]
                .iter()
                .map(|x| (x.valence, x.share.clone()))
                .collect()
        };
        assert_eq!(at(0), vec![(3, "1/3".to_string()), (4, "2/3".to_string())]);
        assert_eq!(at(1), vec![(3, "2/3".to_string()), (4, "1/3".to_string())]);
    }

    #[test]
    fn unbounded_valences_are_not_decided() {
        // A2 puts a spoke at every corner: valences grow, there is no finite system.
        assert!(matches!(
            shares("B2 B2 B2 B2 | B2 B2 B2 | A2"),
            LimitShares::NotDecided { .. }
        ));
    }
}
