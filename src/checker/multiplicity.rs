//! The step `multiplicity` (seed 002, eq. (18)): how many pieces of each level are one exact
//! map, re-derived by enumerating the pieces.
//!
//! A piece of level k is a state and the product `T_1·…·T_k` of its word's subdivision
//! operators. Two pieces are one map when their states are equal and their products are equal
//! in K. Grouping thousands of products needs a canonical form of the entries: the coordinates
//! on the power basis reduced modulo the field's polynomial p are canonical exactly when p is
//! irreducible (then it is α's minimal polynomial and `1, α, …` is a basis). The step proves it
//! with a prime q that does not divide p's leading coefficient and modulo which p is
//! irreducible (Rabin's test in F_q[x], written here): a factorisation over Q would reduce to
//! one modulo q of the same degrees.

use super::field::{self, P};
use super::ifs::{constraints_hold, instance, Checked, Field, KMat};
use crate::certificate::{AutomatonClaim, MultiplicityStep};
use num_bigint::BigInt;
use num_traits::{ToPrimitive, Zero};
use std::collections::{BTreeMap, HashMap};

/// The most pieces of a level the checker enumerates.
const MAX_PIECES: usize = 1 << 16;

/// The step `multiplicity`.
pub(super) fn check_multiplicity(a: &AutomatonClaim, s: &MultiplicityStep) -> Checked {
    let k = Field::of(a)?;
    let ops = instance(&k, a, &s.instance)?;
    constraints_hold(&k, a, &ops).map_err(|e| format!("the instance: {e}"))?;
    let att = a
        .attractor
        .as_ref()
        .ok_or("a multiplicity step for an automaton without an attractor")?;
    let canonical = match (&a.field, s.prime) {
        (None, _) => "Q".to_string(),
        (Some(f), Some(q)) => {
            let p: Vec<BigInt> = f
                .poly
                .iter()
                .map(|c| {
                    c.parse::<BigInt>()
                        .map_err(|_| format!("coefficient `{c}`"))
                })
                .collect::<Result<_, _>>()?;
            irreducible_mod(&p, q)?;
            format!("K (its polynomial is irreducible modulo {q}, so over Q)")
        }
        (Some(_), None) => {
            return Err(
                "no prime proves the field's polynomial irreducible: the reduced \
                        coordinates of a map need not be canonical"
                    .into(),
            )
        }
    };
    let dim = a
        .states
        .get(att.start)
        .ok_or("the start state is out of range")?
        .dim;
    let mut pieces: Vec<(usize, KMat)> = vec![(att.start, Field::identity(dim))];
    for (level, claimed) in s.levels.iter().enumerate() {
        let mut next = Vec::new();
        for (state, m) in &pieces {
            for &o in &att.subdivision {
                let op = a
                    .operators
                    .get(o)
                    .ok_or_else(|| format!("subdivision operator {o} is out of range"))?;
                if op.to != *state {
                    continue;
                }
                if next.len() == MAX_PIECES {
                    return Err(format!(
                        "level {} has more than {MAX_PIECES} pieces: the checker enumerates at most that many",
                        level + 1
                    ));
                }
                next.push((op.from, k.matmul(m, &ops[o])?));
            }
        }
        pieces = next;
        let mut maps: HashMap<(usize, Vec<P>), u64> = HashMap::new();
        for (state, m) in &pieces {
            let key: Vec<P> = m.data.iter().map(|x| field::trim(k.reduce(x))).collect();
            *maps.entry((*state, key)).or_default() += 1;
        }
        let mut histogram: BTreeMap<usize, u64> = BTreeMap::new();
        for &n in maps.values() {
            *histogram.entry(n as usize).or_default() += 1;
        }
        let derived: Vec<(usize, u64)> = histogram.into_iter().collect();
        if &derived != claimed {
            return Err(format!(
                "level {}: the pieces are {derived:?} (maps of m pieces: (m, how many)), the step lists {claimed:?}",
                level + 1
            ));
        }
    }
    let shown: Vec<String> = s
        .levels
        .iter()
        .enumerate()
        .map(|(i, h)| {
            let row: Vec<String> = h.iter().map(|(m, n)| format!("{n}×{m}")).collect();
            format!("level {}: {}", i + 1, row.join(" "))
        })
        .collect();
    Ok((
        format!(
            "every piece of levels 1 to {} enumerated, its map multiplied out and compared exactly in {canonical}; maps by pieces ({}) as listed",
            s.levels.len(),
            shown.join("; ")
        ),
        format!(
            "multiplicity: seed 002's count of the pieces that are one exact map (eq. (18)), at levels 1 to {}",
            s.levels.len()
        ),
    ))
}

/// Proves that the integer polynomial `p` (constant term first) is irreducible over Q: `q` is a
/// prime not dividing its leading coefficient and p modulo q passes Rabin's test (f of degree d
/// is irreducible over F_q iff `x^(q^d) ≡ x mod f` and `gcd(x^(q^(d/r)) − x, f) = 1` for every
/// prime r dividing d).
fn irreducible_mod(p: &[BigInt], q: u64) -> Result<(), String> {
    if !(3..1 << 31).contains(&q) || !is_prime(q) {
        return Err(format!("{q} is not an odd prime below 2^31"));
    }
    let big_q = BigInt::from(q);
    let f: Vec<u64> = p
        .iter()
        .map(|c| {
            let r = c % &big_q;
            let r = if r < BigInt::zero() { r + &big_q } else { r };
            r.to_u64().expect("a residue below q")
        })
        .collect();
    let d = p.len().saturating_sub(1);
    let lead = *f.last().ok_or("the field's polynomial is empty")?;
    if d == 0 || lead == 0 {
        return Err(format!(
            "{q} divides the leading coefficient of the field's polynomial"
        ));
    }
    super::within_work("Rabin's test modulo q", (d * d * d) as u128 * 64)?;
    let inv = pow_mod(lead, q - 2, q);
    let f: Vec<u64> = f.iter().map(|&c| c * inv % q).collect();
    let x = vec![0, 1];
    // x^(q^j) mod f for j = 0..=d, by repeated q-th powers.
    let mut frob = vec![x.clone()];
    for j in 1..=d {
        let next = pow_poly(&frob[j - 1], q, &f, q);
        frob.push(next);
    }
    if trim(frob[d].clone()) != trim(rem(&x, &f, q)) {
        return Err(format!(
            "the field's polynomial is not irreducible modulo {q}: x^(q^{d}) ≢ x"
        ));
    }
    for r in (2..=d).filter(|r| d % r == 0 && is_prime(*r as u64)) {
        let h = sub(&frob[d / r], &x, q);
        let g = gcd(&h, &f, q);
        if g.len() > 1 {
            return Err(format!(
                "the field's polynomial is not irreducible modulo {q}: it has a factor of degree dividing {}",
                d / r
            ));
        }
    }
    Ok(())
}

fn is_prime(n: u64) -> bool {
    n >= 2 && (2..).take_while(|i| i * i <= n).all(|i| n % i != 0)
}

fn pow_mod(mut a: u64, mut e: u64, q: u64) -> u64 {
    let mut r = 1;
    a %= q;
    while e > 0 {
        if e & 1 == 1 {
            r = r * a % q;
        }
        a = a * a % q;
        e >>= 1;
    }
    r
}

fn trim(mut a: Vec<u64>) -> Vec<u64> {
    while a.last() == Some(&0) {
        a.pop();
    }
    a
}

fn sub(a: &[u64], b: &[u64], q: u64) -> Vec<u64> {
    let n = a.len().max(b.len());
    let at = |v: &[u64], i: usize| v.get(i).copied().unwrap_or(0);
    trim((0..n).map(|i| (at(a, i) + q - at(b, i)) % q).collect())
}

/// `a mod f` for monic f.
fn rem(a: &[u64], f: &[u64], q: u64) -> Vec<u64> {
    let mut r = trim(a.to_vec());
    let d = f.len() - 1;
    while r.len() > d {
        let c = *r.last().expect("longer than f");
        let shift = r.len() - 1 - d;
        for (i, &fi) in f.iter().enumerate() {
            r[shift + i] = (r[shift + i] + q - c * fi % q) % q;
        }
        r = trim(r);
    }
    r
}

fn mul_mod(a: &[u64], b: &[u64], f: &[u64], q: u64) -> Vec<u64> {
    if a.is_empty() || b.is_empty() {
        return Vec::new();
    }
    let mut out = vec![0u64; a.len() + b.len() - 1];
    for (i, &x) in a.iter().enumerate() {
        for (j, &y) in b.iter().enumerate() {
            out[i + j] = (out[i + j] + x * y % q) % q;
        }
    }
    rem(&out, f, q)
}

/// `a^e mod f`.
fn pow_poly(a: &[u64], mut e: u64, f: &[u64], q: u64) -> Vec<u64> {
    let mut base = rem(a, f, q);
    let mut r = vec![1u64];
    while e > 0 {
        if e & 1 == 1 {
            r = mul_mod(&r, &base, f, q);
        }
        base = mul_mod(&base, &base, f, q);
        e >>= 1;
    }
    r
}

/// The monic gcd of a and b (empty for two zeros).
fn gcd(a: &[u64], b: &[u64], q: u64) -> Vec<u64> {
    let (mut a, mut b) = (trim(a.to_vec()), trim(b.to_vec()));
    while !b.is_empty() {
        let inv = pow_mod(*b.last().expect("nonzero"), q - 2, q);
        let monic: Vec<u64> = b.iter().map(|&c| c * inv % q).collect();
        let r = rem(&a, &monic, q);
        a = monic;
        b = r;
    }
    a
}

#[cfg(test)]
mod tests {
    use super::*;

    fn poly(c: &[i64]) -> Vec<BigInt> {
        c.iter().map(|&x| BigInt::from(x)).collect()
    }

    #[test]
    fn rabin_by_hand() {
        // x² − 2 is irreducible modulo 3 (2 is not a square mod 3: squares 0, 1) and splits
        // modulo 7 (3² = 9 ≡ 2).
        assert!(irreducible_mod(&poly(&[-2, 0, 1]), 3).is_ok());
        assert!(irreducible_mod(&poly(&[-2, 0, 1]), 7).is_err());
        // (x² + 1)² has no root mod 3 but is not irreducible: Rabin's gcd test finds it.
        assert!(irreducible_mod(&poly(&[1, 0, 2, 0, 1]), 3).is_err());
        // x⁴ + x + 1 over F_3: x = 1 gives 3 ≡ 0, a root.
        assert!(irreducible_mod(&poly(&[1, 1, 0, 0, 1]), 3).is_err());
        // x⁴ + x + 1 over F_2 is irreducible (no root; not (x² + x + 1)² = x⁴ + x² + 1), but 2 is
        // not an odd prime; modulo 5, 16x⁴ − 20x² + 5 (the pentagonal gasket's field) is x⁴.
        assert!(irreducible_mod(&poly(&[1, 1, 0, 0, 1]), 2).is_err());
        assert!(irreducible_mod(&poly(&[5, 0, -20, 0, 16]), 5).is_err());
        // x³ − 2 modulo 7: the cubes mod 7 are 0, 1, 6, so 2 is no cube and the cubic has no
        // root: irreducible; modulo 5 every residue is a cube (3³ = 27 ≡ 2): a root.
        assert!(irreducible_mod(&poly(&[-2, 0, 0, 1]), 7).is_ok());
        assert!(irreducible_mod(&poly(&[-2, 0, 0, 1]), 5).is_err());
        // Not a prime.
        assert!(irreducible_mod(&poly(&[-2, 0, 1]), 9).is_err());
    }
}
