//! Edge types: Bézier-like `Bn`, Cantor-like `Cn`, optionally delayed `X^d` (THEORY §2).

use crate::error::{Error, Result, Span};
use serde::Serialize;
use std::fmt;

/// Connected (`B`, Bézier-like) or disconnected (`C`, Cantor-like).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
pub enum EdgeKind {
    /// `Bn`: n sub-edges joined by n−1 joints.
    B,
    /// `Cn`: n sub-edges separated by n−1 gaps.
    C,
}

/// The largest sub-edge count or delay the notation accepts at all (the configurable limits in
/// [`crate::topology::Limits`] are usually much lower).
pub const HARD_CAP: u32 = 1_000_000;

/// An edge type `Bn`, `Cn`, `Bn^d`, `Cn^d`. The derived order (kind, then n, then delay) is the
/// fixed total order used for canonical boundaries.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct EdgeType {
    /// `B` or `C`.
    pub kind: EdgeKind,
    /// Number of sub-edges, n ≥ 2.
    pub n: u32,
    /// Delay d ≥ 1; d ≥ 2 means the edge keeps its shape for d−1 more levels.
    pub delay: u32,
}

/// What lies between two consecutive sub-edges of a subdivided boundary.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
pub enum JunctionKind {
    /// Between two sub-edges of one `Bn` edge.
    Joint,
    /// Between two sub-edges of one `Cn` edge.
    Gap,
    /// Between the last sub-edge of one boundary edge and the first of the next.
    Corner,
}

impl EdgeType {
    /// A non-delayed edge type. Panics on n < 2 (use [`EdgeType::parse`] for user input).
    pub fn new(kind: EdgeKind, n: u32) -> Self {
        assert!(n >= 2, "an edge has at least two sub-edges");
        EdgeType { kind, n, delay: 1 }
    }

    /// The same edge with delay `d` (d ≥ 1).
    pub fn delayed(self, d: u32) -> Self {
        assert!(d >= 1, "a delay is at least 1");
        EdgeType { delay: d, ..self }
    }

    /// True when d ≥ 2.
    pub fn is_delayed(&self) -> bool {
        self.delay >= 2
    }

    /// The number of sub-edges one subdivision step produces: 1 for a delayed edge, else n.
    pub fn piece_count(&self) -> u32 {
        if self.is_delayed() {
            1
        } else {
            self.n
        }
    }

    /// The type of each sub-edge: `X^(d−1)` for a delayed edge, the edge itself otherwise.
    pub fn piece(&self) -> EdgeType {
        if self.is_delayed() {
            EdgeType {
                delay: self.delay - 1,
                ..*self
            }
        } else {
            *self
        }
    }

    /// The kind of the junctions inside the subdivided edge (none for a delayed edge).
    pub fn inner_junction(&self) -> Option<JunctionKind> {
        match (self.is_delayed(), self.kind) {
            (true, _) => None,
            (false, EdgeKind::B) => Some(JunctionKind::Joint),
            (false, EdgeKind::C) => Some(JunctionKind::Gap),
        }
    }

    /// Lacunas seen from one side of this edge in one subdivision step, counted in halves:
    /// n−1 for a non-delayed `Cn` (each gap is half a lacuna), 0 otherwise.
    pub fn gap_halves(&self) -> u64 {
        match self.inner_junction() {
            Some(JunctionKind::Gap) => u64::from(self.n - 1),
            _ => 0,
        }
    }

    /// Parses one edge token such as `B2`, `C3^2`. `col` is the token's 1-based column, used in
    /// errors.
    pub fn parse(token: &str, col: usize) -> Result<EdgeType> {
        let span = |c: usize, l: usize| Span {
            line: 1,
            col: c,
            len: l.max(1),
        };
        let whole = span(col, token.chars().count());
        let mut chars = token.chars();
        let kind = match chars.next() {
            Some('B') => EdgeKind::B,
            Some('C') => EdgeKind::C,
            _ => {
                return Err(Error::syntax(
                    "E0103",
                    format!("`{token}` is not an edge type (expected Bn or Cn, e.g. B2, C3^2)"),
                    whole,
                    None,
                ))
            }
        };
        let rest = &token[1..];
        let (n_text, delay_text) = match rest.split_once('^') {
            Some((a, b)) => (a, Some(b)),
            None => (rest, None),
        };
        let n = parse_count(n_text, col + 1, "sub-edge count")?;
        if n < 2 {
            return Err(Error::syntax(
                "E0104",
                format!("`{token}`: an edge needs at least 2 sub-edges (n ≥ 2)"),
                span(col + 1, n_text.len()),
                None,
            ));
        }
        let delay = match delay_text {
            None => 1,
            Some(t) => {
                let dcol = col + 2 + n_text.len();
                let d = parse_count(t, dcol, "delay")?;
                if d < 1 {
                    return Err(Error::syntax(
                        "E0105",
                        format!("`{token}`: a delay is at least 1 (`X^1` is `X`)"),
                        span(dcol, t.len()),
                        None,
                    ));
                }
                d
            }
        };
        Ok(EdgeType { kind, n, delay })
    }
}

/// Parses a decimal count for the notation, with errors for missing digits and overflow.
pub(crate) fn parse_count(text: &str, col: usize, what: &str) -> Result<u32> {
    let span = Span {
        line: 1,
        col,
        len: text.chars().count().max(1),
    };
    if text.is_empty() || !text.chars().all(|c| c.is_ascii_digit()) {
        return Err(Error::syntax(
            "E0103",
            format!("expected a {what} (digits), found `{text}`"),
            span,
            None,
        ));
    }
    match text.parse::<u32>() {
        Ok(v) if v <= HARD_CAP => Ok(v),
        _ => Err(Error::syntax(
            "E0106",
            format!("{what} `{text}` is too large (at most {HARD_CAP})"),
            span,
            None,
        )),
    }
}

impl fmt::Display for EdgeType {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let k = match self.kind {
            EdgeKind::B => 'B',
            EdgeKind::C => 'C',
        };
        write!(f, "{k}{}", self.n)?;
        if self.delay > 1 {
            write!(f, "^{}", self.delay)?;
        }
        Ok(())
    }
}

impl Serialize for EdgeType {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

impl fmt::Display for EdgeKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            EdgeKind::B => "B",
            EdgeKind::C => "C",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parse_and_print_round_trip() {
        for t in ["B2", "C3", "C2^3", "B4^2"] {
            assert_eq!(EdgeType::parse(t, 1).unwrap().to_string(), t);
        }
        assert_eq!(EdgeType::parse("B2^1", 1).unwrap().to_string(), "B2");
    }

    #[test]
    fn subdivision_of_edges_follows_the_spec() {
        let c2 = EdgeType::new(EdgeKind::C, 2);
        assert_eq!(c2.piece_count(), 2);
        assert_eq!(c2.inner_junction(), Some(JunctionKind::Gap));
        assert_eq!(c2.gap_halves(), 1);
        let c3d = c2.delayed(3);
        assert_eq!(c3d.piece_count(), 1);
        assert_eq!(c3d.piece(), c2.delayed(2));
        assert_eq!(c3d.inner_junction(), None);
        assert_eq!(c3d.gap_halves(), 0);
        let b4 = EdgeType::new(EdgeKind::B, 4);
        assert_eq!(b4.inner_junction(), Some(JunctionKind::Joint));
        assert_eq!(b4.gap_halves(), 0);
    }

    #[test]
    fn bad_tokens_have_codes() {
        assert_eq!(EdgeType::parse("B0", 1).unwrap_err().code(), "E0104");
        assert_eq!(EdgeType::parse("C1", 1).unwrap_err().code(), "E0104");
        assert_eq!(EdgeType::parse("B2^0", 1).unwrap_err().code(), "E0105");
        assert_eq!(EdgeType::parse("X2", 1).unwrap_err().code(), "E0103");
        assert_eq!(EdgeType::parse("B", 1).unwrap_err().code(), "E0103");
        assert_eq!(
            EdgeType::parse("B99999999999", 1).unwrap_err().code(),
            "E0106"
        );
        assert_eq!(EdgeType::parse("B2^", 1).unwrap_err().code(), "E0103");
    }
}
