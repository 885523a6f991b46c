//! The counts, the characteristic polynomial of `A^P` and the pole of the generating functions
//! at `w₀ = ρ^(−P)`: what `R_r` is for one residue (see `ratio.rs` for the argument).

use super::field::{add, scale, trim, Root, P};
use super::{within_work, Q};
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

/// The powers `y₀^k`, `k ≤ top`, of an element `y₀` of Q[x]/(p), as integer vectors over one
/// common denominator `D`: `y₀^k = vecs[k] / D`.
///
/// With them, every derivative of an integer polynomial at `y₀` is an integer combination of
/// integer vectors: no rational arithmetic, hence no gcd of the huge numbers that the counts of a
/// long period reach (measured: 71 % of the checker's time went to those gcds before).
pub(super) struct Powers {
    vecs: Vec<Vec<BigInt>>,
}

impl Powers {
    /// The powers `y₀^0 … y₀^top`, reduced modulo `p`.
    pub(super) fn of(root: &Root, y0: &[Q], top: usize) -> Powers {
        let mut rational: Vec<P> = Vec::with_capacity(top + 1);
        let mut x = root.reduce(&[Q::one()]);
        for _ in 0..=top {
            let next = root.mul(&x, y0);
            rational.push(std::mem::replace(&mut x, next));
        }
        let den = rational
            .iter()
            .flatten()
            .fold(BigInt::one(), |acc, c| acc.lcm(c.denom()));
        let vecs = rational
            .iter()
            .map(|v| v.iter().map(|c| c.numer() * (&den / c.denom())).collect())
            .collect();
        Powers { vecs }
    }

    /// Meters one product of big integers of `a` and `b` bits (its schoolbook word operations)
    /// against the work budget: the residue phase's cost depends on how the multiplicities and
    /// the sizes of the counts play out, so it is counted as it goes and stops at the budget,
    /// whatever the certificate claims.
    pub(super) fn spend(&self, a: u64, b: u64) -> Result<(), String> {
        let words = |x: u64| u128::from(x / 64 + 1);
        within_work(
            "the residues of the generating functions",
            words(a) * words(b),
        )
    }

    /// `D·f^(j)(y₀)/(j!)·j!`, i.e. `Σ_(i ≥ j) f_i·i!/(i − j)!·vecs[i − j]`: the `j`-th
    /// derivative at `y₀` times the positive constant `D`, as an integer vector.
    fn derivative_at(&self, f: &[BigInt], j: usize) -> Result<Vec<BigInt>, String> {
        let width = self.vecs.iter().map(Vec::len).max().unwrap_or(0);
        let mut out = vec![BigInt::zero(); width];
        let mut falling = BigInt::one(); // i!/(i − j)! for i = j: j!
        for k in 1..=j {
            falling *= BigInt::from(k);
        }
        for (i, c) in f.iter().enumerate().skip(j) {
            if i > j {
                // i!/(i − j)! from (i − 1)!/(i − 1 − j)!: times i/(i − j), exact.
                falling = falling * BigInt::from(i) / BigInt::from(i - j);
            }
            if c.is_zero() {
                continue;
            }
            let k = c * &falling;
            for (o, v) in out.iter_mut().zip(&self.vecs[i - j]) {
                self.spend(k.bits(), v.bits())?;
                *o += &k * v;
            }
        }
        Ok(out)
    }
}

/// An integer vector as an element of Q[x]/(p).
fn as_element(v: &[BigInt]) -> P {
    trim(v.iter().cloned().map(Q::from_integer).collect())
}

/// Whether the integer vector `v` vanishes at ρ: its content is divided out first, so that the
/// exact zero test (a gcd with `p` when `p` has degree above 1) works on the smallest numbers.
fn vanishes(root: &Root, v: &[BigInt]) -> bool {
    let content = v.iter().fold(BigInt::zero(), |g, c| g.gcd(c));
    if content.is_zero() {
        return true;
    }
    root.is_zero(&trim(
        v.iter().map(|c| Q::from_integer(c / &content)).collect(),
    ))
}

/// The multiplicity `j < cap` of `y₀` as a root of `f` and `D·f^(j)(y₀)`, the `j`-th derivative
/// at `y₀` times the positive constant `D` common to every polynomial evaluated with these
/// powers (as an integer vector), or `None` when `f^(j)(y₀) = 0` for every `j < cap`.
fn order(
    root: &Root,
    powers: &Powers,
    f: &[BigInt],
    cap: usize,
) -> Result<Option<(usize, Vec<BigInt>)>, String> {
    for j in 0..cap.min(f.len()) {
        let v = powers.derivative_at(f, j)?;
        if !vanishes(root, &v) {
            return Ok(Some((j, v)));
        }
    }
    Ok(None)
}

/// The multiplicity `m` of `y₀ = ρ^P` as a root of `q = det(y·I − A^P)`: the same for every
/// residue, so computed once.
pub(super) fn multiplicity(root: &Root, powers: &Powers, q: &[BigInt]) -> Result<usize, String> {
    Ok(order(root, powers, q, q.len())?.map_or(0, |(j, _)| j))
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

/// `R_r` from the multiplicity `m` of `y₀` in `q` and the reflected numerators of lacunas (in
/// `1/unit`: halves for faces, quarters for volumes) and cells. The leading coefficients `a_L`,
/// `a_C` are compared at the same derivative order, so the factor `D·j!` they share cancels in
/// `a_L/(a_L + unit·a_C)`.
pub(super) fn residue(
    root: &Root,
    (powers, m): (&Powers, usize),
    (nl, unit): (&[BigInt], u32),
    nc: &[BigInt],
) -> Result<Residue, String> {
    if m == 0 {
        return Err("y₀ = ρ^P is not an eigenvalue of A^P".into());
    }
    let Some((jc, ac)) = order(root, powers, nc, m)? else {
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
    Ok(match order(root, powers, nl, jc + 1)? {
        None => fixed(
            P::new(),
            format!("pole orders: lacunas < {kc} = faces: R = 0"),
        ),
        Some((jl, _)) if jl < jc => fixed(
            one.clone(),
            format!("pole orders: lacunas {} > {kc} = faces: R = 1", m - jl),
        ),
        Some((_, al)) => {
            // Both at order jc (the search above stops at jc): the same factor D, which
            // cancels in the ratio.
            let (al, ac) = (as_element(&al), as_element(&ac));
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
