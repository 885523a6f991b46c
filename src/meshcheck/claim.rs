//! The claims file: what the writer of a mesh says the mesh is, as plain data (`render --claims`
//! writes it; `check-mesh --claims` compares it with what the mesh is). Nothing in it is trusted:
//! every figure is recomputed from the mesh and compared.
//!
//! ```json
//! {
//!   "format": "lacuna-mesh-claims",
//!   "version": 1,
//!   "source": "F0 level 2",
//!   "meshes": ["f0.stl"],
//!   "triangles": 1032,
//!   "parts": 1,
//!   "euler": -24,
//!   "genus": 13,
//!   "per_part": [{ "euler": -24, "genus": 13 }]
//! }
//! ```
//!
//! `parts`, `euler` (the sum over parts), `genus` (the sum over parts) and `per_part` are left
//! out (`null`) when the writer does not know them exactly; `source` is a label for people.

use super::input::malformed;
use crate::error::Error;
use serde::{Deserialize, Serialize};

/// The format tag of a claims file.
pub const CLAIMS_FORMAT: &str = "lacuna-mesh-claims";
/// The version of the claims format.
pub const CLAIMS_VERSION: u32 = 1;

/// The figures one part of a mesh is claimed to have.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PartClaim {
    /// Its Euler characteristic χ = V − E + F.
    pub euler: i64,
    /// Its genus (2 − χ)/2.
    pub genus: i64,
}

/// What a mesh file is claimed to be.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Claims {
    /// Always [`CLAIMS_FORMAT`].
    pub format: String,
    /// Always [`CLAIMS_VERSION`].
    pub version: u32,
    /// What the mesh is of, for people (not compared).
    pub source: String,
    /// The names of the mesh files written with these claims (compared with the checked file's
    /// name: a difference is a note, not a failure, since files get renamed).
    pub meshes: Vec<String>,
    /// The number of triangles.
    pub triangles: u64,
    /// The number of parts (connected surfaces), when known.
    pub parts: Option<u64>,
    /// The sum of the parts' Euler characteristics, when known.
    pub euler: Option<i64>,
    /// The sum of the parts' genera, when known.
    pub genus: Option<i64>,
    /// Each part's figures (compared as a multiset: the order of parts is not topology), when
    /// known.
    pub per_part: Option<Vec<PartClaim>>,
}

impl Claims {
    /// Reads a claims file's text (E1504 when it is not one).
    pub fn parse(text: &str, name: &str) -> Result<Claims, Error> {
        let c: Claims = serde_json::from_str(text).map_err(|e| {
            malformed(
                "E1504",
                format!("`{name}` is not a claims file of lacuna: {e}"),
            )
        })?;
        if c.format != CLAIMS_FORMAT || c.version != CLAIMS_VERSION {
            return Err(malformed(
                "E1504",
                format!(
                    "`{name}` is format `{}` version {}; check-mesh reads `{CLAIMS_FORMAT}` version {CLAIMS_VERSION}",
                    c.format, c.version
                ),
            ));
        }
        Ok(c)
    }

    /// The claims as pretty JSON.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).expect("claims serialise") + "\n"
    }
}
