//! Configurable resource limits, checked before the work starts where they can be predicted.

use crate::error::{Error, Result};
use crate::topology::face::Face;

/// Limits on the size of the work. Every one has a command-line flag.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Limits {
    /// Maximum boundary length of any face type (`--max-boundary`).
    pub max_boundary: usize,
    /// Maximum number of face types in a closure (`--max-types`).
    pub max_types: usize,
    /// Maximum level for counts (`--max-level`).
    pub max_level: u64,
    /// Maximum sub-edge count n of an edge type (`--max-subedges`).
    pub max_subedges: u32,
    /// Maximum delay of an edge or a face (`--max-delay`).
    pub max_delay: u32,
    /// Maximum number of certified decimal digits (`--max-digits`).
    pub max_digits: usize,
    /// Maximum number of unknowns of a constraint system (`--max-unknowns`).
    pub max_unknowns: usize,
    /// Maximum estimated memory of a constraint solve, in MiB (`--max-memory`).
    pub max_memory_mb: u64,
    /// Maximum size n of an n×n matrix given to the eigen analysis (`--max-matrix`).
    pub max_matrix: usize,
    /// Maximum number of operator products formed to prove that an automaton contracts
    /// (`--max-products`).
    pub max_products: usize,
}

impl Default for Limits {
    fn default() -> Self {
        Limits {
            max_boundary: 256,
            max_types: 20_000,
            max_level: 1_000,
            max_subedges: 64,
            max_delay: 64,
            max_digits: 10_000,
            max_unknowns: 20_000_000,
            max_memory_mb: 1024,
            max_matrix: 16,
            max_products: 20_000,
        }
    }
}

impl Limits {
    /// Checks a start face against the limits.
    pub fn check_face(&self, f: &Face) -> Result<()> {
        at_most(
            "the boundary length",
            f.boundary.len(),
            self.max_boundary,
            "--max-boundary",
        )?;
        at_most("the face delay", f.delay, self.max_delay, "--max-delay")?;
        let p = f.params;
        for e in f.boundary.iter().chain([&p.ea, &p.el, &p.ec]) {
            if e.n > self.max_subedges {
                return Err(Error::limit(
                    "an edge's sub-edge count",
                    e,
                    self.max_subedges,
                    "--max-subedges",
                ));
            }
            if e.delay > self.max_delay {
                return Err(Error::limit(
                    "an edge delay",
                    e,
                    self.max_delay,
                    "--max-delay",
                ));
            }
        }
        Ok(())
    }

    /// Checks a requested number of digits.
    pub fn check_digits(&self, digits: usize) -> Result<()> {
        at_most(
            "the number of digits",
            digits,
            self.max_digits,
            "--max-digits",
        )
    }

    /// Checks the size of a constraint system before it is built and solved.
    pub fn check_unknowns(&self, unknowns: usize) -> Result<()> {
        at_most(
            "the number of unknowns",
            unknowns,
            self.max_unknowns,
            "--max-unknowns",
        )
    }

    /// Checks the estimated memory of a constraint solve (bytes) before it is built.
    pub fn check_memory(&self, bytes: u128) -> Result<()> {
        let mb = bytes.div_ceil(1 << 20);
        at_most(
            "the estimated memory of the solve in MiB",
            mb,
            u128::from(self.max_memory_mb),
            "--max-memory",
        )
    }

    /// Checks the size of a square matrix before its eigen analysis.
    pub fn check_matrix(&self, n: usize) -> Result<()> {
        at_most(
            "the size of a matrix for eigen analysis",
            n,
            self.max_matrix,
            "--max-matrix",
        )
    }

    /// Checks a requested level.
    pub fn check_level(&self, level: u64) -> Result<()> {
        at_most("the level", level, self.max_level, "--max-level")
    }
}

/// `Ok` when `value ≤ limit`, else the limit error naming `flag`.
pub fn at_most<T: PartialOrd + std::fmt::Display>(
    what: &'static str,
    value: T,
    limit: T,
    flag: &'static str,
) -> Result<()> {
    if value > limit {
        return Err(Error::limit(what, value, limit, flag));
    }
    Ok(())
}
