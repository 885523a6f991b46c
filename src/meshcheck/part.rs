//! The parts of the mesh — its connected components through shared edges — and their figures:
//! vertices V, edges E, triangles F, the Euler characteristic χ = V − E + F, and the enclosed
//! volume by the divergence theorem, `Σ det(a, b, c) / 6` over the part's triangles `a b c`,
//! summed exactly (positive when the triangles are counter-clockwise seen from outside).

use super::exact::{det, scale, Scaled};
use super::incidence::Edges;
use super::input::Mesh;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};

/// One part's figures.
#[derive(Clone, Debug)]
pub struct Part {
    /// Its first triangle in the file.
    pub first_triangle: usize,
    /// Vertices.
    pub vertices: u64,
    /// Undirected edges.
    pub edges: u64,
    /// Triangles.
    pub triangles: u64,
    /// χ = V − E + F.
    pub euler: i64,
    /// Genus `(2 − χ)/2`, when the whole mesh is a closed oriented manifold.
    pub genus: Option<i64>,
    /// The exact enclosed volume (in the file's unit, cubed), when every edge is closed.
    pub volume: Option<BigRational>,
}

fn find(parent: &mut [u32], mut x: u32) -> u32 {
    while parent[x as usize] != x {
        let p = parent[parent[x as usize] as usize];
        parent[x as usize] = p;
        x = p;
    }
    x
}

/// The part of every triangle (numbered by first triangle) and each part's V, E, F, χ.
pub(super) fn parts(mesh: &Mesh, edges: &Edges) -> (Vec<u32>, Vec<Part>) {
    let n = mesh.triangles.len();
    let mut parent: Vec<u32> = (0..n as u32).collect();
    for g in edges.groups() {
        let r = find(&mut parent, g[0].1 >> 1);
        for u in &g[1..] {
            let s = find(&mut parent, u.1 >> 1);
            if s != r {
                parent[s as usize] = r;
            }
        }
    }
    let mut number = vec![u32::MAX; n];
    let mut of = vec![0u32; n];
    let mut out: Vec<Part> = Vec::new();
    for t in 0..n {
        let r = find(&mut parent, t as u32) as usize;
        if number[r] == u32::MAX {
            number[r] = out.len() as u32;
            out.push(Part {
                first_triangle: t,
                vertices: 0,
                edges: 0,
                triangles: 0,
                euler: 0,
                genus: None,
                volume: None,
            });
        }
        of[t] = number[r];
        out[of[t] as usize].triangles += 1;
    }
    for g in edges.groups() {
        out[of[(g[0].1 >> 1) as usize] as usize].edges += 1;
    }
    let mut corners: Vec<u64> = Vec::with_capacity(3 * n);
    for (t, tri) in mesh.triangles.iter().enumerate() {
        for &v in tri {
            corners.push((u64::from(of[t]) << 32) | u64::from(v));
        }
    }
    corners.sort_unstable();
    corners.dedup();
    for c in corners {
        out[(c >> 32) as usize].vertices += 1;
    }
    for p in &mut out {
        p.euler = p.vertices as i64 - p.edges as i64 + p.triangles as i64;
    }
    (of, out)
}

/// A sum of `det · 2^(3e)` terms, kept per exponent `e` in `i128` until it would overflow.
#[derive(Default)]
struct Sum {
    terms: Vec<(i32, i128, BigInt)>,
}

impl Sum {
    fn slot(&mut self, e: i32) -> &mut (i32, i128, BigInt) {
        let i = match self.terms.iter().position(|t| t.0 == e) {
            Some(i) => i,
            None => {
                self.terms.push((e, 0, BigInt::zero()));
                self.terms.len() - 1
            }
        };
        &mut self.terms[i]
    }

    fn add_small(&mut self, e: i32, x: i128) {
        let s = self.slot(e);
        match s.1.checked_add(x) {
            Some(y) => s.1 = y,
            None => {
                s.2 += BigInt::from(s.1) + BigInt::from(x);
                s.1 = 0;
            }
        }
    }

    fn add_big(&mut self, e: i32, x: BigInt) {
        self.slot(e).2 += x;
    }

    fn value(&self) -> BigRational {
        let mut total = BigRational::zero();
        for (e, small, big) in &self.terms {
            let n = BigInt::from(*small) + big;
            let p = BigInt::one() << (3 * e.unsigned_abs() as usize);
            total += match *e >= 0 {
                true => BigRational::from_integer(n * p),
                false => BigRational::new(n, p),
            };
        }
        total / BigRational::from_integer(BigInt::from(6))
    }
}

/// The exact volume of every part.
pub(super) fn volumes(mesh: &Mesh, of: &[u32], parts: &mut [Part]) {
    let mut sums: Vec<Sum> = (0..parts.len()).map(|_| Sum::default()).collect();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        let p = tri.map(|v| mesh.vertices[v as usize]);
        let sum = &mut sums[of[t] as usize];
        match scale(p) {
            (Scaled::Small(x), e) => sum.add_small(e, det(&x[0], &x[1], &x[2])),
            (Scaled::Big(x), e) => sum.add_big(e, det(&x[0], &x[1], &x[2])),
        }
    }
    for (p, s) in parts.iter_mut().zip(sums) {
        p.volume = Some(s.value());
    }
}

/// A rational as a decimal with `digits` decimals (half away from zero), and whether that is
/// exact.
pub(super) fn decimal(r: &BigRational, digits: usize) -> (String, bool) {
    let scale = BigInt::from(10).pow(digits as u32);
    let scaled = r * BigRational::from_integer(scale.clone());
    let exact = scaled.is_integer();
    let half = BigRational::new(BigInt::one(), BigInt::from(2));
    let n = (scaled.abs() + half).floor().to_integer();
    let (int, frac) = (&n / &scale, &n % &scale);
    let sign = if r.is_negative() && !n.is_zero() {
        "-"
    } else {
        ""
    };
    let mut frac = format!("{:0>width$}", frac.to_string(), width = digits);
    while exact && frac.ends_with('0') {
        frac.pop();
    }
    let text = match frac.is_empty() {
        true => format!("{sign}{int}"),
        false => format!("{sign}{int}.{frac}"),
    };
    (text, exact)
}

/// A rational as the nearest `f64` (for JSON readers that want a number).
pub(super) fn approx(r: &BigRational) -> f64 {
    r.to_f64().unwrap_or(f64::NAN)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decimals() {
        let r = |n: i64, d: i64| BigRational::new(BigInt::from(n), BigInt::from(d));
        assert_eq!(decimal(&r(1000, 1), 3), ("1000".into(), true));
        assert_eq!(decimal(&r(1, 8), 3), ("0.125".into(), true));
        assert_eq!(decimal(&r(1, 4), 3), ("0.25".into(), true));
        assert_eq!(decimal(&r(1, 6), 3), ("0.167".into(), false));
        assert_eq!(decimal(&r(-1, 6), 3), ("-0.167".into(), false));
        assert_eq!(decimal(&r(-1, 1_000_000), 3), ("0.000".into(), false));
    }
}
