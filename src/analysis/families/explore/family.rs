//! The explored family: every boundary up to the length (one per rotation class) or a seeded
//! random sample, crossed with every E, enumerated one face at a time in a fixed order, and its
//! size checked against the limits before any work.

use super::ExploreSpec;
use crate::error::{Error, Result};
use crate::topology::edge::EdgeType;
use crate::topology::face::{least_rotation, Face, Params};
use crate::topology::limits::at_most;

/// The largest family (boundaries × E) explored in one run.
pub const MAX_FAMILY: u64 = 10_000_000;

/// SplitMix64: a small deterministic generator, the same on every machine.
struct SplitMix(u64);

impl SplitMix {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

impl ExploreSpec {
    /// Checks the family's size against the limits before any work.
    pub fn check(&self) -> Result<()> {
        at_most(
            "the explored boundary length",
            self.max_length,
            12,
            "--max-length",
        )?;
        if self.max_length == 0 {
            return Err(Error::OutOfRange {
                flag: "--max-length",
                value: "0".into(),
                what: "the largest boundary length",
                range: "1 to 12".into(),
            });
        }
        if self.edges.is_empty() || self.params.is_empty() {
            return Err(Error::Usage(
                "explore needs at least one edge type in --edges and in --params".into(),
            ));
        }
        let e = (self.params.len() as u64).pow(3);
        let boundaries = match self.random {
            Some(n) => n,
            None => (1..=self.max_length as u32)
                .map(|l| (self.edges.len() as u64).saturating_pow(l))
                .fold(0u64, u64::saturating_add),
        };
        let family = boundaries.saturating_mul(e);
        if family > MAX_FAMILY {
            return Err(Error::limit(
                "the explored family (boundaries × E)",
                family,
                MAX_FAMILY,
                if self.random.is_some() {
                    "--random"
                } else {
                    "--max-length"
                },
            ));
        }
        Ok(())
    }

    /// Calls `f` with every boundary of the family, in a fixed order (before E is chosen),
    /// generating them one at a time.
    fn for_each_boundary(&self, mut f: impl FnMut(Vec<EdgeType>)) {
        let k = self.edges.len();
        if let Some(n) = self.random {
            let mut rng = SplitMix(self.seed);
            for _ in 0..n {
                let len = 1 + rng.below(self.max_length.max(1));
                f((0..len).map(|_| self.edges[rng.below(k)]).collect());
            }
            return;
        }
        for len in 1..=self.max_length {
            let mut digits = vec![0usize; len];
            loop {
                if least_rotation(&digits) == 0 {
                    f(digits.iter().map(|&d| self.edges[d]).collect());
                }
                let mut i = 0;
                while i < len && digits[i] + 1 == k {
                    digits[i] = 0;
                    i += 1;
                }
                if i == len {
                    break;
                }
                digits[i] += 1;
            }
        }
    }

    /// Calls `f` with every face of the family and its index, in order, one at a time (the
    /// family is never held in memory).
    pub fn for_each_face(&self, mut f: impl FnMut(u64, Face)) {
        let mut k = 0u64;
        self.for_each_boundary(|b| {
            for &ea in &self.params {
                for &el in &self.params {
                    for &ec in &self.params {
                        let face = Face {
                            boundary: b.clone(),
                            params: Params { ea, el, ec },
                            algorithm: self.algorithm.clone(),
                            delay: 1,
                        };
                        f(k, face.canonical().0);
                        k += 1;
                    }
                }
            }
        });
    }

    /// Every face of the family, in order (all of them, every shard).
    pub fn family(&self) -> Vec<Face> {
        let mut faces = Vec::new();
        self.for_each_face(|_, f| faces.push(f));
        faces
    }
}

impl ExploreSpec {
    /// The number of faces of the family (boundaries × E); call after [`ExploreSpec::check`],
    /// which bounds the enumeration.
    pub fn size(&self) -> u64 {
        family_size(self)
    }
}

/// The number of faces of the family (boundaries × E), for the progress bar: the necklaces are
/// counted by enumerating them (at most [`MAX_FAMILY`] cheap steps, as checked before).
pub(super) fn family_size(spec: &ExploreSpec) -> u64 {
    let e = (spec.params.len() as u64).pow(3);
    let boundaries = match spec.random {
        Some(n) => n,
        None => {
            let mut n = 0u64;
            spec.for_each_boundary(|_| n += 1);
            n
        }
    };
    boundaries * e
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::families::explore::Property;
    use crate::topology::rule::Algorithm;

    fn spec(edges: &str, params: &str, algorithm: &str, len: usize) -> ExploreSpec {
        let list = |t: &str| -> Vec<EdgeType> {
            t.split(',')
                .map(|x| EdgeType::parse(x, 1).unwrap())
                .collect()
        };
        ExploreSpec {
            edges: list(edges),
            max_length: len,
            params: list(params),
            algorithm: Algorithm::parse(algorithm, 1, &[]).unwrap(),
            properties: vec![Property::Closes],
            random: None,
            seed: 0,
            shard: (0, 1),
            shrink_budget: 100,
            threads: 1,
        }
    }

    #[test]
    fn family_is_necklaces_times_e() {
        // Necklaces over 2 letters up to length 3: 2 + 3 + 4 = 9; E over 2 types: 8.
        assert_eq!(spec("B2,C2", "B2,C2", "A1", 3).family().len(), 9 * 8);
        let mut r = spec("B2,C2", "B2", "A1", 5);
        r.random = Some(20);
        r.seed = 7;
        let a = r.family();
        assert_eq!(a.len(), 20);
        assert_eq!(a, r.family(), "the random family depends on the seed only");
    }
}
