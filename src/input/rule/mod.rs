//! Kaandorp's production rules: an initiator and generators, written as point lists
//! whose segments carry flags, read from a `.rule` file and compiled to an automaton
//! (documented in `docs/FORMATS.md`, "Rule files").
//!
//! ```text
//! # The Koch curve: every segment becomes four of a third.
//! field s = root of x^2 - 3 in [1, 2]
//! initiator 0,0 koch 1,0
//! generator koch 0,0 koch 1/3,0 koch 1/2,1/6s koch 2/3,0 koch 1,0
//! ```
//!
//! Between two points stands the flag of the segment joining them: a generator's name (the
//! segment is fertile and replaced by that generator), optionally followed by `/y` (mirrored
//! across the segment), `/x` (run backwards) or `/xy` (both); `-` (infertile: the segment stays
//! as drawn); `.` (no segment: the pen jumps, for generators of several parts). The `age`
//! extension chooses the generator by the age of the fractal a segment belongs to; the `random`
//! extension draws it from a seed and the segment's place (reproducible), per occurrence down to
//! a depth and once per generator segment below it.
//!
//!
//! The parts: this file holds the rule's data (segments, paths, the rule itself) and the
//! constants of its random choices; `parse.rs` reads a `.rule` text into a [`Rule`] (grammar,
//! names, error positions); `compile.rs` compiles a rule to an automaton file's text and model.

mod compile;
mod parse;

pub use compile::{compile_rule, Affine};
pub use parse::{is_rule, parse_rule};

use crate::algebra::algebraic::{FieldElement, NumberField};

/// How a generator is laid on a segment.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Flip {
    /// As drawn (Kaandorp's direction 1).
    Plain,
    /// Mirrored across the segment, `(x, y) ↦ (x, −y)` (direction 2).
    Y,
    /// Run backwards, `(x, y) ↦ (1 − x, y)` (direction 3).
    X,
    /// Both, `(x, y) ↦ (1 − x, −y)` (direction 4).
    XY,
}

/// What replaces a fertile segment.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    /// A generator, by index.
    Generator(usize),
    /// An age choice, by index: the generator is the choice's entry at the segment's age.
    Age {
        /// The choice's index.
        choice: usize,
        /// True (`NAME!`): the segment starts a new fractal, of age 0.
        restart: bool,
    },
    /// A random choice, by index: the generator is drawn from the seed and the segment's place
    /// (see [`Rule::random_pick`]).
    Random(usize),
}

/// A segment between two consecutive points of a path.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Segment {
    /// Replaced at the next step.
    Fertile {
        /// By what.
        target: Target,
        /// Laid how.
        flip: Flip,
    },
    /// Stays as drawn.
    Drawn,
    /// No segment (the pen jumps).
    Gap,
}

/// A point list with the flag of each segment (`segments.len() == points.len() − 1`).
#[derive(Clone, Debug)]
pub struct RulePath {
    /// The points, exact.
    pub points: Vec<[FieldElement; 2]>,
    /// The segments.
    pub segments: Vec<Segment>,
}

/// A production rule.
#[derive(Clone, Debug)]
pub struct Rule {
    /// The field of the coordinates (Q without a `field` line).
    pub field: NumberField,
    /// The generator's name and the declaration, when a field is declared.
    pub field_decl: Option<(String, String)>,
    /// The initiator (level 0).
    pub initiator: RulePath,
    /// The generators: name and path on the unit segment `(0,0)`–`(1,0)`.
    pub generators: Vec<(String, RulePath)>,
    /// Age choices: name and the generator of each age (the age runs modulo the length).
    pub ages: Vec<(String, Vec<usize>)>,
    /// Random choices: name and the generators drawn from.
    pub randoms: Vec<(String, Vec<usize>)>,
    /// The seed of the random choices (`seed N`, default 0).
    pub seed: u64,
    /// The depth down to which random choices are drawn per occurrence (`depth D`, default 4).
    pub depth: usize,
}

/// The most states a rule with random choices may unroll to (checked before compiling).
pub const MAX_RANDOM_STATES: u64 = 4096;

/// SplitMix64's finaliser: the hash of the random choices (documented in docs/FORMATS.md so
/// that the drawing is reproducible by any implementation).
pub fn splitmix64(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}
