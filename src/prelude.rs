//! The common path in one import: `use lacuna::prelude::*;` brings what it takes to read an input,
//! close it, count it, compute its limit ratio and solve its constraints.
//!
//! ```
//! use lacuna::prelude::*;
//! let face = Face::parse("C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A1").unwrap();
//! let closure = close_or_error(&[face], &Limits::default()).unwrap();
//! assert_eq!(closure.types.len(), 1);
//! ```

pub use crate::analysis::{analyse, RatioReport};
pub use crate::constraint::{automaton_of, solve, solve_closure, Automaton, GenOptions, Solution};
pub use crate::error::{Error, Result};
pub use crate::input::{load_input, Input};
pub use crate::topology::{close, close_or_error, counts, Closure, Face, Limits, TypeSet};
