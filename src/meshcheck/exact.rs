//! Exact arithmetic on the file's coordinates: every finite `f64` (and so every `f32`) is a
//! dyadic rational `m·2^e` with `|m| < 2^53`; the points of one predicate are brought to their
//! smallest common exponent, which makes them integers, and the predicate is evaluated on those
//! integers — in `i128` when their bit length leaves room for the largest product, else in
//! `BigInt`. No floating-point operation decides anything here; the only float operations are
//! the bit-level decomposition of a value and comparisons (`<`, `==`), which are exact.

use num_bigint::BigInt;
use num_traits::Zero;
use std::cmp::Ordering;
use std::ops::{Add, Mul, Sub};

/// A point as read from the file.
pub(super) type Point = [f64; 3];

/// `x = m·2^e` exactly, `m` odd (or `x = 0`, then `m = 0`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Dyadic {
    pub(super) m: i64,
    pub(super) e: i32,
}

impl Dyadic {
    /// The exact value of a finite double.
    pub(super) fn of(x: f64) -> Dyadic {
        debug_assert!(x.is_finite());
        let bits = x.to_bits();
        let exp = ((bits >> 52) & 0x7ff) as i32;
        let frac = (bits & ((1u64 << 52) - 1)) as i64;
        let (mut m, mut e) = match exp {
            0 => (frac, -1074),
            _ => (frac | (1i64 << 52), exp - 1075),
        };
        if m == 0 {
            return Dyadic { m: 0, e: 0 };
        }
        let tz = m.trailing_zeros();
        m >>= tz;
        e += tz as i32;
        if bits >> 63 == 1 {
            m = -m;
        }
        Dyadic { m, e }
    }

    /// Bits of `|m|`.
    fn bits(self) -> i32 {
        64 - self.m.unsigned_abs().leading_zeros() as i32
    }
}

/// The integers a predicate computes with: `i128` and `BigInt`, by value.
pub(super) trait Int:
    Clone + Ord + Zero + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self>
{
}
impl Int for i128 {}
impl Int for BigInt {}

/// The largest bit length of the integer coordinates evaluated in `i128`: a 3×3 determinant of
/// differences of such integers is below `2^(3·(b+1)+3) ≤ 2^126`.
const SMALL_BITS: i32 = 40;

/// Points at a common scale: `value = int · 2^exponent` for every coordinate.
pub(super) enum Scaled<const N: usize> {
    /// Every coordinate has at most [`SMALL_BITS`] bits.
    Small([[i128; 3]; N]),
    /// The general case.
    Big(Box<[[BigInt; 3]; N]>),
}

/// The points as integers at their smallest common exponent, and that exponent.
pub(super) fn scale<const N: usize>(pts: [Point; N]) -> (Scaled<N>, i32) {
    let d: [[Dyadic; 3]; N] = pts.map(|p| p.map(Dyadic::of));
    let e_min = d
        .iter()
        .flatten()
        .filter(|x| x.m != 0)
        .map(|x| x.e)
        .min()
        .unwrap_or(0);
    let bits = d
        .iter()
        .flatten()
        .filter(|x| x.m != 0)
        .map(|x| x.bits() + (x.e - e_min))
        .max()
        .unwrap_or(0);
    if bits <= SMALL_BITS {
        let s = d.map(|p| {
            p.map(|x| {
                if x.m == 0 {
                    0
                } else {
                    i128::from(x.m) << (x.e - e_min)
                }
            })
        });
        (Scaled::Small(s), e_min)
    } else {
        let s = d.map(|p| {
            p.map(|x| match x.m {
                0 => BigInt::zero(),
                m => BigInt::from(m) << ((x.e - e_min) as usize),
            })
        });
        (Scaled::Big(Box::new(s)), e_min)
    }
}

/// Runs `f` on the points at a common scale, in `i128` or `BigInt`.
macro_rules! exactly {
    ($pts:expr, |$p:ident| $body:expr) => {
        match $crate::meshcheck::exact::scale($pts).0 {
            $crate::meshcheck::exact::Scaled::Small($p) => $body,
            $crate::meshcheck::exact::Scaled::Big(b) => {
                let $p = *b;
                $body
            }
        }
    };
}
pub(super) use exactly;

fn sub<T: Int>(a: &[T; 3], b: &[T; 3]) -> [T; 3] {
    [
        a[0].clone() - b[0].clone(),
        a[1].clone() - b[1].clone(),
        a[2].clone() - b[2].clone(),
    ]
}

/// `det [u; v; w]`.
fn det3<T: Int>(u: &[T; 3], v: &[T; 3], w: &[T; 3]) -> T {
    let m0 = v[1].clone() * w[2].clone() - v[2].clone() * w[1].clone();
    let m1 = v[2].clone() * w[0].clone() - v[0].clone() * w[2].clone();
    let m2 = v[0].clone() * w[1].clone() - v[1].clone() * w[0].clone();
    u[0].clone() * m0 + u[1].clone() * m1 + u[2].clone() * m2
}

/// The sign of a value.
pub(super) fn sign<T: Int>(x: &T) -> i8 {
    match x.cmp(&T::zero()) {
        Ordering::Less => -1,
        Ordering::Equal => 0,
        Ordering::Greater => 1,
    }
}

/// The sign of `det [b − a; c − a; d − a]`: positive when `d` lies on the side of the plane
/// `a b c` where `(b − a) × (c − a)` points, zero when the four points are coplanar.
pub(super) fn orient3d<T: Int>(a: &[T; 3], b: &[T; 3], c: &[T; 3], d: &[T; 3]) -> i8 {
    sign(&det3(&sub(b, a), &sub(c, a), &sub(d, a)))
}

/// `det [a; b; c]` (six times the signed volume of the tetrahedron `0 a b c`).
pub(super) fn det<T: Int>(a: &[T; 3], b: &[T; 3], c: &[T; 3]) -> T {
    det3(a, b, c)
}

/// The sign of the orientation of `a b c` projected on the coordinate plane without axis `k`
/// (the `k` component of `(b − a) × (c − a)`).
pub(super) fn orient2d<T: Int>(k: usize, a: &[T; 3], b: &[T; 3], c: &[T; 3]) -> i8 {
    let (i, j) = ((k + 1) % 3, (k + 2) % 3);
    let l = (b[i].clone() - a[i].clone()) * (c[j].clone() - a[j].clone());
    let r = (b[j].clone() - a[j].clone()) * (c[i].clone() - a[i].clone());
    sign(&(l - r))
}

/// The first axis along which the normal `(b − a) × (c − a)` has a non-zero component (the
/// triangle projects to a non-flat triangle along it), or `None`: the three points are collinear.
pub(super) fn normal_axis<T: Int>(a: &[T; 3], b: &[T; 3], c: &[T; 3]) -> Option<usize> {
    (0..3).find(|&k| orient2d(k, a, b, c) != 0)
}

/// Whether `x`, collinear with `p q` in the projection without axis `k`, lies on the closed
/// segment `p q` there.
fn between<T: Int>(k: usize, p: &[T; 3], q: &[T; 3], x: &[T; 3]) -> bool {
    [(k + 1) % 3, (k + 2) % 3].into_iter().all(|i| {
        let (lo, hi) = match p[i] <= q[i] {
            true => (&p[i], &q[i]),
            false => (&q[i], &p[i]),
        };
        *lo <= x[i] && x[i] <= *hi
    })
}

/// Whether the closed segments `p q` and `a b` meet, in the projection without axis `k`.
fn segments_meet<T: Int>(k: usize, p: &[T; 3], q: &[T; 3], a: &[T; 3], b: &[T; 3]) -> bool {
    let (d1, d2) = (orient2d(k, p, q, a), orient2d(k, p, q, b));
    let (d3, d4) = (orient2d(k, a, b, p), orient2d(k, a, b, q));
    if d1 * d2 < 0 && d3 * d4 < 0 {
        return true;
    }
    (d1 == 0 && between(k, p, q, a))
        || (d2 == 0 && between(k, p, q, b))
        || (d3 == 0 && between(k, a, b, p))
        || (d4 == 0 && between(k, a, b, q))
}

/// Whether the closed segment `p q` meets the closed triangle `a b c` (not degenerate): touching
/// counts. When the segment does not lie in the triangle's plane, the line `p q` meets the plane
/// in one point, on the segment when `p` and `q` are not strictly on one side; that point is in
/// the triangle when the orientations of `p q` against the three sides have no two strictly
/// opposite signs. When it lies in the plane, the test is made in the projection along an axis
/// where the triangle is not flat (one-to-one on the plane): an end point inside the triangle,
/// or the segment meeting one of its sides.
pub(super) fn segment_meets_triangle<T: Int>(
    p: &[T; 3],
    q: &[T; 3],
    a: &[T; 3],
    b: &[T; 3],
    c: &[T; 3],
) -> bool {
    let (sp, sq) = (orient3d(a, b, c, p), orient3d(a, b, c, q));
    if sp != 0 && sp == sq {
        return false;
    }
    if sp == 0 && sq == 0 {
        let Some(k) = normal_axis(a, b, c) else {
            return false;
        };
        let area = orient2d(k, a, b, c);
        let inside = |x: &[T; 3]| {
            orient2d(k, a, b, x) * area >= 0
                && orient2d(k, b, c, x) * area >= 0
                && orient2d(k, c, a, x) * area >= 0
        };
        return inside(p)
            || inside(q)
            || segments_meet(k, p, q, a, b)
            || segments_meet(k, p, q, b, c)
            || segments_meet(k, p, q, c, a);
    }
    let s = [
        orient3d(p, q, a, b),
        orient3d(p, q, b, c),
        orient3d(p, q, c, a),
    ];
    !(s.contains(&1) && s.contains(&-1))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dyadic_values_are_exact() {
        assert_eq!(Dyadic::of(0.0), Dyadic { m: 0, e: 0 });
        assert_eq!(Dyadic::of(-0.0), Dyadic { m: 0, e: 0 });
        assert_eq!(Dyadic::of(6.0), Dyadic { m: 3, e: 1 });
        assert_eq!(Dyadic::of(-0.375), Dyadic { m: -3, e: -3 });
        // 0.1f32 = 13421773 · 2^-27.
        assert_eq!(
            Dyadic::of(f64::from(0.1f32)),
            Dyadic {
                m: 13421773,
                e: -27
            }
        );
        assert_eq!(
            Dyadic::of(f64::MIN_POSITIVE / 4.0),
            Dyadic { m: 1, e: -1024 }
        );
    }

    #[test]
    fn small_and_big_scales_agree() {
        let pts = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ];
        let (s, e) = scale(pts);
        assert_eq!(e, 0);
        assert!(matches!(s, Scaled::Small(_)));
        let o = exactly!(pts, |p| orient3d(&p[0], &p[1], &p[2], &p[3]));
        assert_eq!(o, 1);
        // A tiny coordinate beside a large one needs big integers; the answer is the same.
        let tiny = [
            [0.0, 0.0, 1e-30],
            [1e6, 0.0, 0.0],
            [0.0, 1e6, 0.0],
            [0.0, 0.0, 1e6],
        ];
        assert!(matches!(scale(tiny).0, Scaled::Big(_)));
        let o = exactly!(tiny, |p| orient3d(&p[0], &p[1], &p[2], &p[3]));
        assert_eq!(o, 1);
        // Coplanar within 2^-52: exactly zero only when it is.
        let eps = f64::EPSILON;
        let flat = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.5, 0.5, eps],
        ];
        assert_eq!(exactly!(flat, |p| orient3d(&p[0], &p[1], &p[2], &p[3])), 1);
        let flat = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.5, 0.5, 0.0],
        ];
        assert_eq!(exactly!(flat, |p| orient3d(&p[0], &p[1], &p[2], &p[3])), 0);
    }

    #[test]
    fn segments_and_triangles() {
        let t = [[0.0, 0.0, 0.0], [4.0, 0.0, 0.0], [0.0, 4.0, 0.0]];
        let meets = |p: Point, q: Point| {
            exactly!([p, q, t[0], t[1], t[2]], |x| segment_meets_triangle(
                &x[0], &x[1], &x[2], &x[3], &x[4]
            ))
        };
        assert!(
            meets([1.0, 1.0, -1.0], [1.0, 1.0, 1.0]),
            "through the inside"
        );
        assert!(
            meets([1.0, 1.0, 0.0], [1.0, 1.0, 1.0]),
            "touching at an end"
        );
        assert!(
            meets([2.0, 2.0, -1.0], [2.0, 2.0, 1.0]),
            "through the hypotenuse"
        );
        assert!(!meets([3.0, 3.0, -1.0], [3.0, 3.0, 1.0]), "beside it");
        assert!(!meets([1.0, 1.0, 0.5], [1.0, 1.0, 1.0]), "above it");
        assert!(meets([-1.0, 1.0, 0.0], [5.0, 1.0, 0.0]), "coplanar, across");
        assert!(
            meets([4.0, 0.0, 0.0], [6.0, 0.0, 0.0]),
            "coplanar, at a corner"
        );
        assert!(
            !meets([5.0, 0.0, 0.0], [6.0, 0.0, 0.0]),
            "coplanar, on the line of a side"
        );
        assert!(
            !meets([3.0, 3.0, 0.0], [5.0, 1.0, 0.0]),
            "coplanar, outside"
        );
    }
}
