//! The counts, the characteristic polynomial of `A^P` and the pole of the generating functions
//! at `w₀ = ρ^(−P)`: what `R_r` is for one residue (see `ratio.rs` for the argument).

use super::field::{add, scale, Root, P};
use super::Q;
use num_bigint::{BigInt, BigUint};
use num_integer::Integer;
use num_traits::{One, Zero};
use std::collections::BTreeMap;

fn int(k: u32) -> Q {
    Q::from_integer(k.into())
}

/// `det(x·I − A)` of a sparse integer matrix, by Faddeev–LeVerrier: `M₁ = I`,
/// `c_(d−k) = −tr(A·M_k)/k`, `M_(k+1) = A·M_k + c_(d−k)·I`; the divisions are exact (the
/// coefficients are integers). Coefficients ascending.
pub(super) fn charpoly(a: &[Vec<(usize, BigInt)>]) -> Result<Vec<BigInt>, String> {
    let d = a.len();
    let mut c = vec![BigInt::zero(); d + 1];
    c[d] = BigInt::one();
    let mut mk: Vec<Vec<BigInt>> = (0..d)
        .map(|i| (0..d).map(|j| BigInt::from(u8::from(i == j))).collect())
        .collect();
    for k in 1..=d {
        let am: Vec<Vec<BigInt>> = a
            .iter()
            .map(|row| {
                let mut out = vec![BigInt::zero(); d];
                for (j, x) in row {
                    for (o, y) in out.iter_mut().zip(&mk[*j]) {
                        *o += x * y;
                    }
                }
                out
            })
            .collect();
        let tr: BigInt = (0..d).map(|i| &am[i][i]).sum();
        let (q, r) = tr.div_rem(&BigInt::from(k));
        if !r.is_zero() {
            return Err("Faddeev–LeVerrier: a trace is not divisible".into());
        }
        c[d - k] = -q;
        mk = am;
        for (i, row) in mk.iter_mut().enumerate() {
            row[i] += &c[d - k];
        }
    }
    Ok(c)
}

/// `det(y·I − A^P)` from `det(x·I − A)` (ascending coefficients): Newton's identities give the
/// power sums `s_j` of the eigenvalues of A, those of `A^P` are `s_(P·j)`, and Newton's identities
/// again give the coefficients (exact divisions).
pub(super) fn power_charpoly(chi: &[BigInt], period: usize) -> Result<Vec<BigInt>, String> {
    let d = chi.len() - 1;
    let a: Vec<&BigInt> = (0..=d).map(|i| &chi[d - i]).collect(); // x^d + a₁x^(d−1) + …
    let mut s = vec![BigInt::zero(); period * d + 1];
    for j in 1..=period * d {
        let mut t = if j <= d {
            a[j] * BigInt::from(j)
        } else {
            BigInt::zero()
        };
        for i in 1..j.min(d + 1) {
            t += a[i] * &s[j - i];
        }
        s[j] = -t;
    }
    let mut b = vec![BigInt::one()];
    for k in 1..=d {
        let mut t = s[period * k].clone();
        for i in 1..k {
            t += &b[i] * &s[period * (k - i)];
        }
        let (q, r) = t.div_rem(&BigInt::from(k));
        if !r.is_zero() {
            return Err("Newton's identities: a division is not exact".into());
        }
        b.push(-q);
    }
    Ok(b.into_iter().rev().collect())
}

fn derivative(f: &[BigInt]) -> Vec<BigInt> {
    f.iter()
        .enumerate()
        .skip(1)
        .map(|(i, c)| c * BigInt::from(i))
        .collect()
}

/// The multiplicity `j < cap` of `y₀` as a root of `f` and `f^(j)(y₀)`, or `None` when
/// `f^(j)(y₀) = 0` for every `j < cap`.
fn order(root: &Root, f: &[BigInt], y0: &[Q], cap: usize) -> Option<(usize, P)> {
    let mut f = f.to_vec();
    for j in 0..cap {
        let v = root.eval_at(&f, y0);
        if !root.is_zero(&v) {
            return Some((j, v));
        }
        f = derivative(&f);
    }
    None
}

/// What one residue gives: `R_r = num / den` in Q[x]/(p) (`den` ≠ 0 at ρ), and how it was decided.
pub(super) struct Residue {
    num: P,
    den: P,
    pub(super) why: String,
}

impl Residue {
    /// Whether `v = R_r`: `v·den − num = 0` at ρ.
    pub(super) fn is(&self, root: &Root, v: &[Q]) -> bool {
        root.is_zero(&add(&root.mul(v, &self.den), &scale(&self.num, &-Q::one())))
    }
}

/// `R_r` from `q` and the reflected numerators of lacunas (in `1/unit`: halves for faces,
/// quarters for volumes) and cells.
pub(super) fn residue(
    root: &Root,
    q: &[BigInt],
    (nl, unit): (&[BigInt], u32),
    nc: &[BigInt],
    y0: &[Q],
) -> Result<Residue, String> {
    let m = order(root, q, y0, q.len()).map_or(0, |(j, _)| j);
    if m == 0 {
        return Err("y₀ = ρ^P is not an eigenvalue of A^P".into());
    }
    let Some((jc, ac)) = order(root, nc, y0, m) else {
        return Err("the face counts have no pole at w₀ = ρ^(−P)".into());
    };
    let one = vec![Q::one()];
    let fixed = |v: P, why: String| Residue {
        num: v,
        den: one.clone(),
        why,
    };
    if nl.iter().all(Zero::is_zero) {
        return Ok(fixed(P::new(), "no lacuna ever: R = 0".into()));
    }
    let kc = m - jc;
    Ok(match order(root, nl, y0, jc + 1) {
        None => fixed(
            P::new(),
            format!("pole orders: lacunas < {kc} = faces: R = 0"),
        ),
        Some((jl, _)) if jl < jc => fixed(
            one.clone(),
            format!("pole orders: lacunas {} > {kc} = faces: R = 1", m - jl),
        ),
        Some((_, al)) => {
            let den = add(&al, &scale(&ac, &int(unit)));
            if root.is_zero(&den) {
                return Err("the leading coefficients cancel".into());
            }
            let cells = if unit == 2 { "faces" } else { "cells" };
            let why = format!("pole orders {kc} (lacunas and {cells}): R = a_L/(a_L + {unit}·a_C)");
            Residue { num: al, den, why }
        }
    })
}

/// The counts `X_i` for `i < len` on the reached types: faces, and lacunas in halves (big
/// integers throughout).
pub(super) fn counts(
    m: &[BTreeMap<usize, BigUint>],
    c: &[BigUint],
    start: &BTreeMap<usize, BigUint>,
    len: usize,
) -> (Vec<BigInt>, Vec<BigInt>) {
    let mut v: BTreeMap<usize, BigUint> = start.clone();
    let mut lac = BigUint::zero();
    let (mut faces, mut lacunas) = (Vec::with_capacity(len), Vec::with_capacity(len));
    for _ in 0..len {
        faces.push(BigInt::from(v.values().sum::<BigUint>()));
        lacunas.push(BigInt::from(lac.clone()));
        let mut next: BTreeMap<usize, BigUint> = BTreeMap::new();
        for (t, x) in &v {
            for (s, k) in &m[*t] {
                *next.entry(*s).or_default() += x * k;
            }
            lac += x * &c[*t];
        }
        v = next;
    }
    (faces, lacunas)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn charpoly_of_a_power() {
        // A = [[0, 2], [8, 0]]: det(xI − A) = x² − 16; A² = 16·I: det(yI − A²) = (y − 16)².
        let a = vec![vec![(1, BigInt::from(2))], vec![(0, BigInt::from(8))]];
        let chi = charpoly(&a).unwrap();
        assert_eq!(chi, [-16, 0, 1].map(BigInt::from));
        assert_eq!(
            power_charpoly(&chi, 2).unwrap(),
            [256, -32, 1].map(BigInt::from)
        );
        // [[1, 1], [1, 0]]: x² − x − 1; squared: eigenvalues φ², φ'² with sum 3, product 1.
        let a = vec![
            vec![(0, BigInt::one()), (1, BigInt::one())],
            vec![(0, BigInt::one())],
        ];
        let chi = charpoly(&a).unwrap();
        assert_eq!(chi, [-1, -1, 1].map(BigInt::from));
        assert_eq!(
            power_charpoly(&chi, 2).unwrap(),
            [1, -3, 1].map(BigInt::from)
        );
    }
}
