//! Faces `F^d(∂, E, A)` and their notation `C2 B2 C2 B2 | C2 B2 B2 | A1 | 2` (THEORY §2).

use crate::error::{Error, Result, Source, Span};
use crate::topology::edge::EdgeType;
use crate::topology::rule::Algorithm;
use std::fmt;

/// The parameter `E = (Ea, El, Ec)`: adjacency, lacuna and gap-closing edge types.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Params {
    /// Adjacency edge, from a spoke to the central lacuna.
    pub ea: EdgeType,
    /// Lacuna edge, on the border of the central lacuna.
    pub el: EdgeType,
    /// Gap-closing edge.
    pub ec: EdgeType,
}

/// A face: boundary (counter-clockwise), parameters, algorithm and delay d ≥ 1.
///
/// Two faces are the same type when their boundaries are rotations of each other and E, A and d
/// agree; [`Face::canonical`] picks the representative (the lexicographically least rotation).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Face {
    /// The boundary edges, counter-clockwise.
    pub boundary: Vec<EdgeType>,
    /// E.
    pub params: Params,
    /// A.
    pub algorithm: Algorithm,
    /// d ≥ 1.
    pub delay: u32,
}

/// The start of the lexicographically least rotation of `s` (the two-pointer minimum-rotation
/// algorithm, O(len)); ties (periodic sequences) give the smallest start.
pub fn least_rotation<T: Ord>(s: &[T]) -> usize {
    let n = s.len();
    let (mut i, mut j, mut k) = (0usize, 1usize, 0usize);
    while i < n && j < n && k < n {
        let a = &s[(i + k) % n];
        let b = &s[(j + k) % n];
        if a == b {
            k += 1;
            continue;
        }
        if a > b {
            i += k + 1;
        } else {
            j += k + 1;
        }
        if i == j {
            j += 1;
        }
        k = 0;
    }
    i.min(j)
}

impl Face {
    /// The canonical representative and the rotation used: `canonical.boundary[k] ==
    /// self.boundary[(k + rotation) % len]`.
    pub fn canonical(&self) -> (Face, usize) {
        let r = least_rotation(&self.boundary);
        let mut boundary = self.boundary.clone();
        boundary.rotate_left(r);
        (
            Face {
                boundary,
                ..self.clone()
            },
            r,
        )
    }

    /// True when the face is its own canonical form.
    pub fn is_canonical(&self) -> bool {
        least_rotation(&self.boundary) == 0
    }

    /// Lacunas one subdivision step of this face contributes, in halves: 2 for the central lacuna
    /// (d = 1 only) plus n−1 for every non-delayed `Cn` of the boundary (THEORY §5).
    pub fn contribution_halves(&self) -> u64 {
        let centre = if self.delay == 1 { 2 } else { 0 };
        centre + self.boundary.iter().map(EdgeType::gap_halves).sum::<u64>()
    }

    /// Parses the face notation. `named` resolves algorithm names defined elsewhere (assembly
    /// files). Errors carry the column on line 1 of `text`; callers re-anchor them with
    /// [`Error::within`].
    pub fn parse_with(text: &str, named: &[(String, Algorithm)]) -> Result<Face> {
        let span = |col: usize, len: usize| Span {
            line: 1,
            col,
            len: len.max(1),
        };
        let total = text.chars().count();
        if text.trim().is_empty() {
            return Err(Error::syntax(
                "E0101",
                "empty face: expected `EDGES | Ea El Ec | ALGORITHM`, e.g. `C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A1`",
                span(1, 1),
                None,
            ));
        }
        // Split into fields at '|', keeping each field's 1-based start column.
        let mut fields: Vec<(usize, &str)> = Vec::new();
        let mut start_byte = 0usize;
        for (i, ch) in text.char_indices() {
            if ch == '|' {
                fields.push((start_byte, &text[start_byte..i]));
                start_byte = i + 1;
            }
        }
        fields.push((start_byte, &text[start_byte..]));
        let col_of = |byte: usize| text[..byte].chars().count() + 1;
        if fields.len() < 3 || fields.len() > 4 {
            return Err(Error::syntax(
                "E0102",
                format!(
                    "expected 3 or 4 fields separated by `|` (EDGES | Ea El Ec | ALGORITHM [| DELAY]), found {}",
                    fields.len()
                ),
                span(1, total),
                None,
            ));
        }
        // Columns are counted incrementally (one pass per field), so long boundaries parse in
        // linear time.
        let tokens = |(off, field): (usize, &str)| -> Vec<(usize, String)> {
            let base = col_of(off);
            let mut out = Vec::new();
            let mut cur = String::new();
            let mut cur_col = 0;
            for (k, ch) in field.chars().enumerate() {
                if ch.is_whitespace() {
                    if !cur.is_empty() {
                        out.push((cur_col, std::mem::take(&mut cur)));
                    }
                } else {
                    if cur.is_empty() {
                        cur_col = base + k;
                    }
                    cur.push(ch);
                }
            }
            if !cur.is_empty() {
                out.push((cur_col, cur));
            }
            out
        };
        let trimmed_span = |(off, field): (usize, &str)| {
            let lead = field.len() - field.trim_start().len();
            span(col_of(off + lead), field.trim().chars().count())
        };
        let edge_tokens = tokens(fields[0]);
        if edge_tokens.is_empty() {
            return Err(Error::syntax(
                "E0111",
                "empty boundary: a face needs at least one edge",
                span(col_of(fields[0].0), fields[0].1.chars().count()),
                None,
            ));
        }
        let boundary = edge_tokens
            .iter()
            .map(|(c, t)| EdgeType::parse(t, *c))
            .collect::<Result<Vec<_>>>()?;
        let e_tokens = tokens(fields[1]);
        if e_tokens.len() != 3 {
            return Err(Error::syntax(
                "E0107",
                format!(
                    "E needs exactly 3 edges (Ea El Ec), found {}",
                    e_tokens.len()
                ),
                trimmed_span(fields[1]),
                None,
            ));
        }
        let e: Vec<EdgeType> = e_tokens
            .iter()
            .map(|(c, t)| EdgeType::parse(t, *c))
            .collect::<Result<_>>()?;
        let params = Params {
            ea: e[0],
            el: e[1],
            ec: e[2],
        };
        // Algorithm, with an optional `^d` (THEORY §2) ...
        let (aoff, afield) = fields[2];
        let lead = afield.len() - afield.trim_start().len();
        let atext = afield.trim();
        let acol = col_of(aoff + lead);
        if atext.is_empty() {
            return Err(Error::syntax(
                "E0108",
                "missing algorithm (A1, A2, A3 or a spoke set)",
                span(acol, 1),
                None,
            ));
        }
        let (alg_text, mut delay) = match atext.rsplit_once('^') {
            Some((a, d)) if !a.ends_with(')') && !d.contains('}') => {
                let dcol = acol + a.chars().count() + 1;
                (a, Some(parse_delay(d, dcol)?))
            }
            _ => (atext, None),
        };
        let algorithm = Algorithm::parse(alg_text, acol, named)?;
        // ... or a fourth field (issue #2).
        if let Some(&(doff, dfield)) = fields.get(3) {
            let lead = dfield.len() - dfield.trim_start().len();
            let dcol = col_of(doff + lead);
            if delay.is_some() {
                return Err(Error::syntax(
                    "E0110",
                    "face delay given twice (`^d` after the algorithm and a fourth field)",
                    span(dcol, dfield.trim().chars().count()),
                    None,
                ));
            }
            delay = Some(parse_delay(dfield.trim(), dcol)?);
        }
        Ok(Face {
            boundary,
            params,
            algorithm,
            delay: delay.unwrap_or(1),
        })
    }

    /// Parses the face notation, with errors anchored to `source`.
    pub fn parse(text: &str) -> Result<Face> {
        Face::parse_with(text, &[]).map_err(|e| e.within(&Source::command_line(text), 1, 0))
    }
}

fn parse_delay(text: &str, col: usize) -> Result<u32> {
    let d = crate::topology::edge::parse_count(text, col, "face delay").map_err(|e| match e {
        Error::Syntax(mut d) if d.code == "E0103" => {
            d.code = "E0110";
            Error::Syntax(d)
        }
        other => other,
    })?;
    if d == 0 {
        return Err(Error::syntax(
            "E0110",
            "a face delay is at least 1",
            Span {
                line: 1,
                col,
                len: 1,
            },
            None,
        ));
    }
    Ok(d)
}

impl fmt::Display for Face {
    /// The notation, with the face delay as a fourth field when d ≥ 2.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let edges: Vec<String> = self.boundary.iter().map(|e| e.to_string()).collect();
        write!(
            f,
            "{} | {} {} {} | {}",
            edges.join(" "),
            self.params.ea,
            self.params.el,
            self.params.ec,
            self.algorithm
        )?;
        if self.delay > 1 {
            write!(f, " | {}", self.delay)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn f0_parses_and_prints() {
        let f = Face::parse("C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A1").unwrap();
        assert_eq!(f.boundary.len(), 6);
        assert_eq!(f.delay, 1);
        assert_eq!(f.to_string(), "C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A1");
        // F0: central lacuna + three C2 edges with one gap each = 1 + 3/2 = 5/2 = 5 halves.
        assert_eq!(f.contribution_halves(), 5);
    }

    #[test]
    fn delay_in_either_form() {
        let a = Face::parse("B2 C2^3 | C2 B2 B2 | A3^2").unwrap();
        let b = Face::parse("B2 C2^3 | C2 B2 B2 | A3 | 2").unwrap();
        assert_eq!(a, b);
        assert_eq!(a.delay, 2);
        assert_eq!(a.to_string(), "B2 C2^3 | C2 B2 B2 | A3 | 2");
        // A delayed face has no central lacuna, and delayed Cn edges contribute nothing.
        assert_eq!(a.contribution_halves(), 0);
    }

    #[test]
    fn canonical_is_least_rotation() {
        let f = Face::parse("C2 B2 B3 | C2 B2 B2 | A1").unwrap();
        let (c, r) = f.canonical();
        assert_eq!(c.to_string(), "B2 B3 C2 | C2 B2 B2 | A1");
        assert_eq!(r, 1);
        assert_eq!(least_rotation(&[2, 1, 2, 1]), 1);
        assert_eq!(least_rotation(&[1, 1, 1]), 0);
        assert_eq!(least_rotation(&[3, 1, 2, 1, 1]), 3);
    }

    #[test]
    fn errors_point_at_columns() {
        let e = Face::parse("C2 B2 X2 | C2 B2 B2 | A1").unwrap_err();
        assert_eq!((e.code(), e.span().unwrap().col), ("E0103", 7));
        let e = Face::parse("C2 B2 | C2 B2 | A1").unwrap_err();
        assert_eq!((e.code(), e.span().unwrap().col), ("E0107", 9));
        let e = Face::parse("C2 B2 | C2 B2 B2").unwrap_err();
        assert_eq!(e.code(), "E0102");
        let e = Face::parse("C2 B2 | C2 B2 B2 | A1 | 0").unwrap_err();
        assert_eq!((e.code(), e.span().unwrap().col), ("E0110", 25));
        let e = Face::parse("  | C2 B2 B2 | A1").unwrap_err();
        assert_eq!(e.code(), "E0111");
        assert_eq!(Face::parse("").unwrap_err().code(), "E0101");
        assert_eq!(
            Face::parse("C2 | C2 B2 B2 | A1 | x").unwrap_err().code(),
            "E0110"
        );
    }
}
