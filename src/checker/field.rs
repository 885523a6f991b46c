//! Polynomials over Q and the real algebraic number ρ: Sturm isolation, and exact zero and sign
//! tests of elements of Q[x]/(p) evaluated at ρ.
//!
//! The checker works modulo the certificate's polynomial `p` without knowing that it is
//! irreducible: evaluation at ρ is a ring homomorphism Q[x]/(p) → R, so identities proved modulo
//! `p` hold at ρ. Only *nonvanishing* needs care (a nonzero remainder may still vanish at ρ when
//! `p` is reducible): [`Root::is_zero`] decides it exactly with `gcd(p, z)`.

use super::{rat, Q};
use num_bigint::BigInt;
use num_traits::{One, Signed, Zero};

/// Polynomials over Q, constant term first, without trailing zeros.
pub(super) type P = Vec<Q>;

pub(super) fn trim(mut p: P) -> P {
    while p.last().is_some_and(Zero::is_zero) {
        p.pop();
    }
    p
}

/// The words of a rational (numerator and denominator), for the work meter.
fn words(x: &Q) -> u128 {
    u128::from((x.numer().bits() + x.denom().bits()) / 64 + 1)
}

/// The largest words of a polynomial's coefficients.
fn widest(p: &[Q]) -> u128 {
    p.iter().map(words).max().unwrap_or(1)
}

/// Meters arithmetic in Q and Q[x]/(p) (Sturm sequences, remainders, gcds, Horner): every
/// operation on numbers read from, or grown out of, a certificate is charged to the check's work
/// budget (`super::charge`); once it is spent the loops below stop early and the step is refused
/// for cost, whatever they return.
fn charge(work: u128) -> bool {
    super::charge("arithmetic over Q(ρ)", work)
}

pub(super) fn eval(p: &[Q], x: &Q) -> Q {
    let mut acc = Q::zero();
    for c in p.iter().rev() {
        if !charge(3 * words(&acc) * words(x)) {
            break;
        }
        acc = acc * x + c;
    }
    acc
}

pub(super) fn rem(a: &[Q], d: &[Q]) -> P {
    let mut r = trim(a.to_vec());
    let lead = d.last().expect("divisor is nonzero");
    let wd = widest(d);
    while r.len() >= d.len() {
        let q = r.last().expect("nonzero") / lead;
        // Only the entries this step touches are charged: a scan of all of `r` per step would
        // make the meter itself quadratic in the length (x^P reduced for P = 20 000).
        if !charge(3 * d.len() as u128 * words(&q) * wd + widest(&r[r.len() - d.len()..])) {
            r.truncate(d.len() - 1);
            return trim(r);
        }
        let shift = r.len() - d.len();
        for (i, c) in d.iter().enumerate() {
            r[shift + i] -= &q * c;
        }
        r = trim(r);
    }
    r
}

/// The quotient and remainder of `a` by a nonzero `d`.
pub(super) fn divide(a: &[Q], d: &[Q]) -> (P, P) {
    let mut r = trim(a.to_vec());
    let d = trim(d.to_vec());
    let lead = d.last().expect("divisor is nonzero").clone();
    let mut q = vec![Q::zero(); r.len().saturating_sub(d.len()) + 1];
    while r.len() >= d.len() {
        if !charge(3 * (d.len() as u128) * widest(&d) * widest(&r)) {
            break;
        }
        let c = r.last().expect("nonzero") / &lead;
        let shift = r.len() - d.len();
        for (i, x) in d.iter().enumerate() {
            r[shift + i] -= &c * x;
        }
        q[shift] = c;
        r = trim(r);
    }
    (trim(q), r)
}

pub(super) fn mul(a: &[Q], b: &[Q]) -> P {
    if !charge(3 * (a.len() * b.len()) as u128 * widest(a) * widest(b)) {
        return P::new();
    }
    let mut c = vec![Q::zero(); (a.len() + b.len()).saturating_sub(1)];
    for (i, x) in a.iter().enumerate() {
        for (j, y) in b.iter().enumerate() {
            c[i + j] += x * y;
        }
    }
    trim(c)
}

pub(super) fn add(a: &[Q], b: &[Q]) -> P {
    let mut c = vec![Q::zero(); a.len().max(b.len())];
    for (i, x) in a.iter().enumerate() {
        c[i] += x;
    }
    for (i, x) in b.iter().enumerate() {
        c[i] += x;
    }
    trim(c)
}

pub(super) fn scale(a: &[Q], k: &Q) -> P {
    trim(a.iter().map(|x| x * k).collect())
}

/// The monic gcd over Q (Euclid).
pub(super) fn gcd(a: &[Q], b: &[Q]) -> P {
    let (mut a, mut b) = (trim(a.to_vec()), trim(b.to_vec()));
    while !b.is_empty() {
        let r = rem(&a, &b);
        (a, b) = (b, r);
    }
    let lead = a.last().cloned().unwrap_or_else(Q::one);
    a.iter().map(|c| c / &lead).collect()
}

/// The derivative.
pub(super) fn derivative(p: &[Q]) -> P {
    trim(
        (1..p.len())
            .map(|i| &p[i] * Q::from_integer(i.into()))
            .collect(),
    )
}

/// The Sturm chain of a squarefree `p` of degree at least 1 (`p`, `p′`, then negated
/// remainders), or `None` when `p` is not squarefree (a remainder vanishes before a constant).
pub(super) fn sturm_chain(p: &[Q]) -> Option<Vec<P>> {
    let mut chain = vec![trim(p.to_vec()), derivative(p)];
    while chain.last().is_some_and(|q| q.len() > 1) {
        let r = rem(&chain[chain.len() - 2], &chain[chain.len() - 1]);
        if r.is_empty() {
            return None;
        }
        chain.push(r.into_iter().map(|c| -c).collect());
    }
    Some(chain)
}

/// The sign changes of a Sturm chain at `x` (zeros skipped).
pub(super) fn sign_changes(chain: &[P], x: &Q) -> usize {
    let signs: Vec<bool> = chain
        .iter()
        .map(|p| eval(p, x))
        .filter(|v| !v.is_zero())
        .map(|v| v.is_positive())
        .collect();
    signs.windows(2).filter(|w| w[0] != w[1]).count()
}

/// The sign of `q(x)` for every x in `[lo, hi]` when interval Horner evaluation shows it is the
/// same (the enclosure excludes 0), else `None`.
fn horner_sign(q: &[Q], lo: &Q, hi: &Q) -> Option<i32> {
    let (mut a, mut b) = (Q::zero(), Q::zero());
    for c in q.iter().rev() {
        let ps = [&a * lo, &a * hi, &b * lo, &b * hi];
        a = ps.iter().min().expect("four").clone() + c;
        b = ps.iter().max().expect("four").clone() + c;
    }
    match (a.is_positive(), b.is_negative()) {
        (true, _) => Some(1),
        (_, true) => Some(-1),
        _ => None,
    }
}

/// A real algebraic number: the only root of the squarefree `p` in `[lo, hi]`.
pub(super) struct Root {
    pub(super) p: P,
    pub(super) lo: Q,
    pub(super) hi: Q,
    /// The Sturm chain of `p` (empty for a rational root, `lo = hi`).
    chain: Vec<P>,
    /// A narrower interval around the root, `2^−64` wide, made on the first sign asked for:
    /// most signs are decided on it by one interval evaluation, without the exact zero test.
    narrow: std::cell::OnceCell<(Q, Q)>,
}

impl Root {
    /// Confirms that `[lo, hi]` isolates exactly one root of `poly` (Sturm, `poly` squarefree);
    /// `what` names the number in messages.
    pub(super) fn isolate(poly: &[String], lo: &str, hi: &str, what: &str) -> Result<Root, String> {
        let p = trim(
            poly.iter()
                .map(|c| rat(c).ok().filter(Q::is_integer))
                .collect::<Option<_>>()
                .ok_or_else(|| format!("{what}'s polynomial has a non-integer coefficient"))?,
        );
        let (lo, hi) = (rat(lo)?, rat(hi)?);
        if p.len() < 2 {
            return Err(format!("{what}'s polynomial is constant"));
        }
        if p.len() == 2 {
            let root = -&p[0] / &p[1];
            return match lo == root && hi == root {
                true => Ok(Root {
                    p,
                    lo,
                    hi,
                    chain: Vec::new(),
                    narrow: std::cell::OnceCell::new(),
                }),
                false => Err(format!(
                    "{what}: the interval [{lo}, {hi}] is not the rational root {root}"
                )),
            };
        }
        if lo >= hi || eval(&p, &lo).is_zero() || eval(&p, &hi).is_zero() {
            return Err(format!("{what}: [{lo}, {hi}] is empty or ends at a root"));
        }
        let chain =
            sturm_chain(&p).ok_or_else(|| format!("{what}'s polynomial is not squarefree"))?;
        match sign_changes(&chain, &lo).checked_sub(sign_changes(&chain, &hi)) {
            Some(1) => Ok(Root {
                p,
                lo,
                hi,
                chain,
                narrow: std::cell::OnceCell::new(),
            }),
            _ => Err(format!(
                "{what}: [{lo}, {hi}] does not hold exactly one root of its polynomial"
            )),
        }
    }

    /// The root compared with a rational `x`, exactly: outside `[lo, hi]` by the interval; inside,
    /// `p(x) = 0` means `x` is the root (the only one there), otherwise the Sturm count on
    /// `(lo, x]` says whether the root lies below `x`.
    pub(super) fn cmp_rational(&self, x: &Q) -> std::cmp::Ordering {
        use std::cmp::Ordering::{Equal, Greater, Less};
        if self.chain.is_empty() {
            return self.lo.cmp(x);
        }
        if x < &self.lo {
            return Greater;
        }
        if x > &self.hi {
            return Less;
        }
        if eval(&self.p, x).is_zero() {
            return Equal;
        }
        match sign_changes(&self.chain, &self.lo) > sign_changes(&self.chain, x) {
            true => Less,
            false => Greater,
        }
    }

    /// `z` reduced modulo `p`.
    pub(super) fn reduce(&self, z: &[Q]) -> P {
        rem(z, &self.p)
    }

    /// `a·b` in Q[x]/(p).
    pub(super) fn mul(&self, a: &[Q], b: &[Q]) -> P {
        rem(&mul(a, b), &self.p)
    }

    /// The integer polynomial `f` evaluated at the element `y` (Horner in Q[x]/(p)).
    pub(super) fn eval_at(&self, f: &[BigInt], y: &[Q]) -> P {
        f.iter().rev().fold(P::new(), |acc, c| {
            add(&self.mul(&acc, y), &trim(vec![Q::from_integer(c.clone())]))
        })
    }

    /// Whether `z(ρ) = 0`, exactly. With `g = gcd(p, z)`: `z(ρ) = 0` iff `g(ρ) = 0`; `g` divides
    /// the squarefree `p`, whose only root in `[lo, hi]` is ρ (simple) and which does not vanish
    /// at `lo`, `hi`; so `g` has ρ as a root iff it changes sign on `[lo, hi]`.
    pub(super) fn is_zero(&self, z: &[Q]) -> bool {
        let z = self.reduce(z);
        if z.is_empty() {
            return true;
        }
        if self.p.len() == 2 {
            return false; // a nonzero constant
        }
        let g = gcd(&self.p, &z);
        g.len() > 1 && (eval(&g, &self.lo) * eval(&g, &self.hi)).is_negative()
    }

    /// The sign of `z(ρ)` (−1, 0, 1): the exact zero test, then interval Horner evaluation on
    /// bisections of `[lo, hi]` until the enclosure excludes 0 (it does, `z(ρ)` being nonzero);
    /// `None` if that takes more than 4000 bisections.
    pub(super) fn sign(&self, z: &[Q]) -> Option<i32> {
        let q = self.reduce(z);
        if q.is_empty() {
            return Some(0);
        }
        // An enclosure that excludes 0 decides a sign without the zero test (a gcd).
        let (nlo, nhi) = self.narrow.get_or_init(|| self.bisect(64));
        if let Some(s) = horner_sign(&q, nlo, nhi) {
            return Some(s);
        }
        if self.is_zero(&q) {
            return Some(0);
        }
        let (mut lo, mut hi) = (nlo.clone(), nhi.clone());
        let s_lo = eval(&self.p, &self.lo).is_positive();
        for _ in 0..4000 {
            if lo == hi || eval(&self.p, &lo).is_zero() {
                return Some(if eval(&q, &lo).is_positive() { 1 } else { -1 });
            }
            if let Some(s) = horner_sign(&q, &lo, &hi) {
                return Some(s);
            }
            let mid = (&lo + &hi) / Q::from_integer(2.into());
            let pm = eval(&self.p, &mid);
            if pm.is_zero() {
                (lo, hi) = (mid.clone(), mid);
            } else if pm.is_positive() == s_lo {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        None
    }

    /// `[lo, hi]` bisected (by the sign of p, which changes at the root only) to at most
    /// `2^−bits` wide; a rational root gives `[root, root]`.
    fn bisect(&self, bits: u64) -> (Q, Q) {
        let (mut lo, mut hi) = (self.lo.clone(), self.hi.clone());
        let width = Q::new(BigInt::one(), BigInt::one() << bits);
        let s_lo = eval(&self.p, &lo).is_positive();
        while &hi - &lo > width {
            if eval(&self.p, &lo).is_zero() {
                return (lo.clone(), lo);
            }
            let mid = (&lo + &hi) / Q::from_integer(2.into());
            let pm = eval(&self.p, &mid);
            if pm.is_zero() {
                return (mid.clone(), mid);
            } else if pm.is_positive() == s_lo {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        (lo, hi)
    }

    /// The inverse of `z` in `Q[x]/(p)` by the extended Euclidean algorithm, confirmed: `y·z − 1`
    /// vanishes at ρ. `None` when z shares a factor with p (then z may vanish at ρ, or p is
    /// reducible and z a unit of the real field but not of `Q[x]/(p)`).
    pub(super) fn inverse(&self, z: &[Q]) -> Option<P> {
        let z = self.reduce(z);
        if z.is_empty() {
            return None;
        }
        // s_i·z ≡ r_i (mod p): the remainders' degrees fall at every round, so p's degree
        // bounds the rounds (an exhausted work budget stops `divide` early; the bound stops
        // the loop).
        let (mut r0, mut r1) = (self.p.clone(), z.clone());
        let (mut s0, mut s1) = (P::new(), vec![Q::one()]);
        for _ in 0..self.p.len() {
            if r1.len() <= 1 {
                break;
            }
            let (q, r) = divide(&r0, &r1);
            let s = add(&s0, &scale(&mul(&q, &s1), &-Q::one()));
            r0 = std::mem::replace(&mut r1, r);
            s0 = std::mem::replace(&mut s1, s);
        }
        if r1.len() != 1 {
            return None;
        }
        let y = self.reduce(&scale(&s1, &(Q::one() / &r1[0])));
        let one = add(&self.mul(&y, &z), &[-Q::one()]);
        self.is_zero(&one).then_some(y)
    }

    /// An element of Q[x]/(p) from certificate coordinates.
    pub(super) fn element(&self, coords: &[String]) -> Result<P, String> {
        let p = trim(coords.iter().map(|s| rat(s)).collect::<Result<_, _>>()?);
        Ok(self.reduce(&p))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(n: i64) -> Q {
        Q::from_integer(n.into())
    }

    #[test]
    fn zero_test_works_modulo_a_reducible_polynomial() {
        // p = (x − 2)(x² − 2) = x³ − 2x² − 2x + 4, ρ = 2 isolated in [3/2, 5/2]
        // (√2 ≈ 1.414 lies outside). z = x² − 2 is a nonzero remainder vanishing at √2 only,
        // z = x − 2 vanishes at ρ although x − 2 ∤ … is not a multiple of p.
        let root = Root::isolate(&["4", "-2", "-2", "1"].map(String::from), "3/2", "5/2", "ρ")
            .expect("isolates");
        assert!(!root.is_zero(&[q(-2), q(0), q(1)]));
        assert!(root.is_zero(&[q(-2), q(1)]));
        assert_eq!(root.sign(&[q(-2), q(0), q(1)]), Some(1)); // ρ² − 2 = 2
        assert_eq!(root.sign(&[q(1), q(-1)]), Some(-1)); // 1 − ρ
        assert!(Root::isolate(&["4", "-2", "-2", "1"].map(String::from), "1", "3", "ρ").is_err());
    }

    #[test]
    fn inverses_in_a_quadratic_field_and_in_q() {
        // ρ = √2 (x² − 2 on [1, 2]): 1/(1 + √2) = √2 − 1, since (1 + √2)(√2 − 1) = 2 − 1.
        let root = Root::isolate(&["-2", "0", "1"].map(String::from), "1", "2", "ρ").unwrap();
        assert_eq!(root.inverse(&[q(1), q(1)]), Some(vec![q(-1), q(1)]));
        assert_eq!(root.inverse(&[]), None);
        // In Q (ρ = 0, the root of x): 1/(−4) = −1/4.
        let zero = Root::isolate(&["0", "1"].map(String::from), "0", "0", "ρ").unwrap();
        assert_eq!(
            zero.inverse(&[q(-4)]),
            Some(vec![Q::new((-1).into(), 4.into())])
        );
        // Modulo (x − 2)(x² − 2) with ρ = 2, x² − 2 is 2 at ρ but no unit of Q[x]/(p).
        let red =
            Root::isolate(&["4", "-2", "-2", "1"].map(String::from), "3/2", "5/2", "ρ").unwrap();
        assert_eq!(red.inverse(&[q(-2), q(0), q(1)]), None);
    }
}
