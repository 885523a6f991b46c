//! The plain-text format for hand-written automata (documented in `docs/FORMATS.md`).
//!
//! ```text
//! # THEORY §6 worked example
//! state v 1
//! state e 3
//! sub   v.sub0  : v <- v = [1]
//! sub   e.sub0  : e <- e              # no value: unknown
//! sub   e.sub1  : e <- e
//! embed e.bord0 : e <- v = [1; 0; 0]
//! embed e.bord1 : e <- v = [0; 0; 1]
//! barycentric                          # every column of every sub/embed operator sums to 1
//! e.bord0 * v.sub0 = e.sub0 * e.bord0
//! e.sub0 * [0; -1; 1] = e.sub1 * [-1; 1; 0]
//! ```

use crate::algebra::matrix::Matrix;
use crate::constraint::automaton::{Automaton, Constraint, ConstraintKind, Factor, OpKind};
use crate::error::{Error, Result, Source, Span};
use num_bigint::BigInt;
use num_rational::BigRational;

fn valid_name(n: &str) -> bool {
    let mut cs = n.chars();
    cs.next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && n.chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '.' || c == '\'')
}

/// Parses an exact number: an integer, a fraction `p/q`, or a decimal `0.25` (taken exactly).
pub fn parse_rational(t: &str) -> Option<BigRational> {
    if t.is_empty() || t.len() > 200 {
        return None;
    }
    if let Some((p, q)) = t.split_once('/') {
        let p: BigInt = p.parse().ok()?;
        let q: BigInt = q.parse().ok()?;
        if q == BigInt::from(0) {
            return None;
        }
        return Some(BigRational::new(p, q));
    }
    if let Some((i, f)) = t.split_once('.') {
        if f.is_empty() || !f.chars().all(|c| c.is_ascii_digit()) {
            return None;
        }
        let neg = i.starts_with('-');
        let ip: BigInt = if i.is_empty() || i == "-" || i == "+" {
            0.into()
        } else {
            i.parse().ok()?
        };
        let fp: BigInt = f.parse().ok()?;
        let scale = BigInt::from(10).pow(f.len() as u32);
        let frac = BigRational::new(fp, scale);
        let int = BigRational::from_integer(ip);
        return Some(if neg { int - frac } else { int + frac });
    }
    t.parse::<BigInt>().ok().map(BigRational::from_integer)
}

/// Parses a matrix literal `[a b; c d]` starting at byte `start` of `line`; returns the matrix and
/// the byte just after the closing bracket.
pub(crate) fn parse_matrix(
    line: &str,
    start: usize,
    ln: usize,
    src: &Source,
) -> Result<(Matrix, usize)> {
    let col = |b: usize| line[..b].chars().count() + 1;
    let Some(close) = line[start..].find(']').map(|i| start + i) else {
        return Err(Error::at(
            "E0701",
            "matrix literal is not closed by `]`",
            ln,
            col(start),
            1,
            src,
        ));
    };
    let inner = &line[start + 1..close];
    let mut rows: Vec<Vec<BigRational>> = Vec::new();
    let mut offset = start + 1;
    for row in inner.split(';') {
        let mut vals = Vec::new();
        for tok in row.split(|c: char| c.is_whitespace() || c == ',') {
            if tok.is_empty() {
                continue;
            }
            let tstart = offset + row.find(tok).unwrap_or(0);
            let v = parse_rational(tok).ok_or_else(|| {
                Error::at(
                    "E0706",
                    format!("`{tok}` is not an exact number (use 1/3, -2 or 0.25)"),
                    ln,
                    col(tstart),
                    tok.len(),
                    src,
                )
            })?;
            vals.push(v);
        }
        offset += row.len() + 1;
        rows.push(vals);
    }
    let width = rows.first().map_or(0, Vec::len);
    if width == 0 || rows.iter().any(|r| r.len() != width) {
        return Err(Error::at(
            "E0703",
            "matrix rows must be non-empty and of equal length",
            ln,
            col(start),
            close + 1 - start,
            src,
        ));
    }
    Ok((Matrix::from_rows(rows), close + 1))
}

/// Parses an automaton file.
pub fn parse_automaton(src: &Source) -> Result<Automaton> {
    let mut a = Automaton::default();
    let mut bary_all = false;
    for (ln0, raw) in src.text.lines().enumerate() {
        let ln = ln0 + 1;
        let line = raw.split('#').next().unwrap_or("");
        let t = line.trim();
        if t.is_empty() {
            continue;
        }
        let col = |s: &str| {
            line[..(s.as_ptr() as usize - line.as_ptr() as usize)]
                .chars()
                .count()
                + 1
        };
        let words: Vec<&str> = t.split_whitespace().collect();
        match words[0] {
            "state" => {
                let [_, name, dim] = words.as_slice() else {
                    return Err(Error::at(
                        "E0701",
                        "expected `state NAME DIM`",
                        ln,
                        col(t),
                        t.len(),
                        src,
                    ));
                };
                if !valid_name(name) || a.states.iter().any(|s| s.name == *name) {
                    return Err(Error::at(
                        "E0705",
                        format!("invalid or duplicate state name `{name}`"),
                        ln,
                        col(name),
                        name.len(),
                        src,
                    ));
                }
                let dim: usize = match dim.parse() {
                    Ok(d) if (1..=4096).contains(&d) => d,
                    _ => {
                        return Err(Error::at(
                            "E0706",
                            format!("state dimension `{dim}` must be an integer in 1..=4096"),
                            ln,
                            col(dim),
                            dim.len(),
                            src,
                        ))
                    }
                };
                a.add_state(*name, dim);
            }
            "sub" | "embed" | "perm" | "op" => {
                let kind = match words[0] {
                    "sub" => OpKind::Sub,
                    "embed" => OpKind::Embed,
                    "perm" => OpKind::Perm,
                    _ => OpKind::Other,
                };
                // KIND NAME : Q <- W [= MATRIX]
                let (head, value) = match t.split_once('=') {
                    Some((h, v)) => (h, Some(v)),
                    None => (t, None),
                };
                let hw: Vec<&str> = head.split_whitespace().collect();
                let [_, name, ":", q, "<-", w] = hw.as_slice() else {
                    return Err(Error::at(
                        "E0701",
                        "expected `KIND NAME : TO <- FROM [= MATRIX]`",
                        ln,
                        col(t),
                        t.len(),
                        src,
                    ));
                };
                if !valid_name(name) || a.operators.iter().any(|o| o.name == *name) {
                    return Err(Error::at(
                        "E0705",
                        format!("invalid or duplicate operator name `{name}`"),
                        ln,
                        col(name),
                        name.len(),
                        src,
                    ));
                }
                let find = |s: &&str| a.states.iter().position(|x| x.name == **s);
                let Some(to) = find(q) else {
                    return Err(Error::at(
                        "E0702",
                        format!("unknown state `{q}`"),
                        ln,
                        col(q),
                        q.len(),
                        src,
                    ));
                };
                let Some(from) = find(w) else {
                    return Err(Error::at(
                        "E0702",
                        format!("unknown state `{w}`"),
                        ln,
                        col(w),
                        w.len(),
                        src,
                    ));
                };
                let value = match value {
                    None => None,
                    Some(v) => {
                        let vs = v.trim_start();
                        let start = line.len()
                            - (line.len() - (vs.as_ptr() as usize - line.as_ptr() as usize));
                        if !vs.starts_with('[') {
                            return Err(Error::at(
                                "E0701",
                                "expected a matrix literal `[…]` after `=`",
                                ln,
                                col(vs),
                                vs.trim().len(),
                                src,
                            ));
                        }
                        let (m, end) = parse_matrix(line, start, ln, src)?;
                        if !line[end..].trim().is_empty() {
                            return Err(Error::at(
                                "E0701",
                                "unexpected text after the matrix",
                                ln,
                                col(&line[end..]),
                                line[end..].trim_end().len(),
                                src,
                            ));
                        }
                        let want = (a.states[to].dim, a.states[from].dim);
                        if (m.rows, m.cols) != want {
                            return Err(Error::at(
                                "E0703",
                                format!("`{name}` maps {w} into {q} so it is {}×{}, but the matrix is {}×{}", want.0, want.1, m.rows, m.cols),
                                ln,
                                col(vs),
                                vs.trim().len(),
                                src,
                            ));
                        }
                        Some(m)
                    }
                };
                a.add_op(*name, kind, to, from, value);
            }
            "barycentric" => {
                if words.len() == 1 {
                    bary_all = true;
                }
                for w in &words[1..] {
                    let Some(o) = a.operators.iter().position(|x| x.name == *w) else {
                        return Err(Error::at(
                            "E0702",
                            format!("unknown operator `{w}`"),
                            ln,
                            col(w),
                            w.len(),
                            src,
                        ));
                    };
                    if !a.barycentric.contains(&o) {
                        a.barycentric.push(o);
                    }
                }
            }
            _ => {
                let Some((l, r)) = t.split_once('=') else {
                    return Err(Error::at(
                        "E0701",
                        format!("expected `state`, an operator declaration, `barycentric`, or a constraint `WORD = WORD`, found `{t}`"),
                        ln,
                        col(t),
                        t.len(),
                        src,
                    ));
                };
                let lhs = parse_word(line, l, &a, ln, src)?;
                let rhs = parse_word(line, r, &a, ln, src)?;
                a.constraints.push(Constraint {
                    label: format!("line {ln}"),
                    span: Some(Span {
                        line: ln,
                        col: col(t),
                        len: t.chars().count(),
                    }),
                    kind: ConstraintKind::Word,
                    lhs,
                    rhs,
                });
            }
        }
    }
    if a.states.is_empty() {
        return Err(Error::at("E0707", "no state declared", 1, 1, 1, src));
    }
    if bary_all {
        for (o, op) in a.operators.iter().enumerate() {
            if matches!(op.kind, OpKind::Sub | OpKind::Embed) && !a.barycentric.contains(&o) {
                a.barycentric.push(o);
            }
        }
    }
    // Constraint errors found later (shapes, nonlinear words) carry spans into this source.
    Ok(a)
}

/// Parses `F * F * …` where F is an operator name or a matrix literal; `part` is a sub-slice of
/// `line`.
fn parse_word(
    line: &str,
    part: &str,
    a: &Automaton,
    ln: usize,
    src: &Source,
) -> Result<Vec<Factor>> {
    let base = part.as_ptr() as usize - line.as_ptr() as usize;
    let col = |b: usize| line[..b].chars().count() + 1;
    let mut factors = Vec::new();
    let mut i = 0usize;
    let bytes = part.as_bytes();
    let mut expect_factor = true;
    while i < bytes.len() {
        // Byte-wise scanning stays on character boundaries because only ASCII bytes are tested
        // (a byte of a multi-byte character is never ASCII).
        let c = bytes[i] as char;
        if bytes[i].is_ascii_whitespace() {
            i += 1;
            continue;
        }
        if !expect_factor {
            if c == '*' {
                expect_factor = true;
                i += 1;
                continue;
            }
            return Err(Error::at(
                "E0701",
                "expected `*` between factors",
                ln,
                col(base + i),
                1,
                src,
            ));
        }
        if c == '[' {
            let (m, end) = parse_matrix(line, base + i, ln, src)?;
            factors.push(Factor::Literal(m));
            i = end - base;
        } else {
            let start = i;
            while i < bytes.len() && !bytes[i].is_ascii_whitespace() && bytes[i] != b'*' {
                i += 1;
            }
            let name = &part[start..i];
            let Some(o) = a.operators.iter().position(|x| x.name == name) else {
                return Err(Error::at(
                    "E0702",
                    format!("unknown operator `{name}`"),
                    ln,
                    col(base + start),
                    name.chars().count(),
                    src,
                ));
            };
            factors.push(Factor::Op(o));
        }
        expect_factor = false;
    }
    if factors.is_empty() || expect_factor {
        return Err(Error::at(
            "E0701",
            "a word needs at least one factor (and no trailing `*`)",
            ln,
            col(base),
            part.len(),
            src,
        ));
    }
    Ok(factors)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn src(t: &str) -> Source {
        Source {
            name: "a.txt".into(),
            text: t.into(),
        }
    }

    #[test]
    fn numbers_are_exact() {
        assert_eq!(parse_rational("1/3").unwrap().to_string(), "1/3");
        assert_eq!(parse_rational("-0.25").unwrap().to_string(), "-1/4");
        assert_eq!(parse_rational("2").unwrap().to_string(), "2");
        assert!(parse_rational("1/0").is_none());
        assert!(parse_rational("NaN").is_none());
        assert!(parse_rational("1e5").is_none());
    }

    #[test]
    fn parses_declarations_and_words() {
        let a = parse_automaton(&src(
            "state v 1\nstate e 3\nsub v.sub0 : v <- v = [1]\nsub e.sub0 : e <- e\nembed e.bord0 : e <- v = [1; 0; 0]\nbarycentric\ne.bord0 * v.sub0 = e.sub0 * e.bord0\ne.sub0 * [0; -1; 1] = e.sub0 * [1;0;0]\n",
        ))
        .unwrap();
        assert_eq!(a.states.len(), 2);
        assert_eq!(a.operators.len(), 3);
        assert_eq!(a.barycentric.len(), 3);
        assert_eq!(a.constraints.len(), 2);
        assert!(
            matches!(&a.constraints[1].lhs[1], Factor::Literal(m) if m.rows == 3 && m.cols == 1)
        );
    }

    #[test]
    fn errors_have_codes_and_columns() {
        let cases = [
            ("state e 3\nsub e.t : e <- f\n", "E0702", 2, 16),
            ("state e 3\nsub e.t : e <- e = [1 2; 3]\n", "E0703", 2, 20),
            ("state e 3\nstate e 2\n", "E0705", 2, 7),
            ("state e 0\n", "E0706", 1, 9),
            ("state e 1\nsub t : e <- e = [x]\n", "E0706", 2, 19),
            ("state e 1\nsub t : e <- e\nt * q = t\n", "E0702", 3, 5),
            ("state e 1\nsub t : e <- e\nt * = t\n", "E0701", 3, 1),
            ("hello\n", "E0701", 1, 1),
        ];
        for (text, code, line, c) in cases {
            let e = parse_automaton(&src(text)).unwrap_err();
            let s = e.span().unwrap();
            assert_eq!((e.code(), s.line, s.col), (code, line, c), "{text}");
        }
    }
}
