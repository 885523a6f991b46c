//! What an automaton file says beyond its constraint system, for drawing and measuring its
//! attractor (documented in `docs/FORMATS.md`, "Automaton files: modelling"):
//!
//! ```text
//! field s = root of 16x^4 - 20x^2 + 5 in [1/2, 3/5]   # entries may be polynomials in s
//! space 2                                           # the modelling space: 2 or 3
//! start a                                           # the start state (default: the largest)
//! points [0 0; 1 0; 0 1]                            # its control points, one row each
//! primitive a polygon 0 1 2                         # point I | polyline I… | polygon I… | none
//! param e.T0[0][1] = 1/4                            # fixes an entry of an unknown operator
//! ```
//!
//! The lines are read here and blanked before the constraint system is parsed by
//! [`crate::input::automaton_format`], so line and column numbers stay those of the file; an
//! operator whose matrix has an entry outside Q keeps its value here ([`AutomatonModel::kvalues`]) and
//! is unknown to the rational solver (such operators may not be mixed with unknown ones).

use crate::algebra::algebraic::{FieldElement, NumberField, RealAlgebraic};
use crate::algebra::kmatrix::KMatrix;
use crate::algebra::poly::Poly;
use crate::constraint::automaton::Automaton;
use crate::error::{Error, Result, Source, Span};
use crate::input::automaton_format::{parse_automaton, parse_rational};
use num_rational::BigRational;
use num_traits::{One, Zero};

/// What a state's cells are drawn as: a subset of its control points.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Primitive {
    /// One control point.
    Point(usize),
    /// The open polyline through these control points.
    Polyline(Vec<usize>),
    /// The closed polygon on these control points.
    Polygon(Vec<usize>),
    /// Nothing (a state that only routes).
    Nothing,
}

/// An automaton with what evaluation needs: the field of its entries, the modelling space, the
/// start state and its control points, a primitive per state, and parameter values.
#[derive(Clone, Debug)]
pub struct AutomatonModel {
    /// The constraint system (operators with entries outside Q are unknown here).
    pub automaton: Automaton,
    /// The field of the entries (Q when no `field` line).
    pub field: NumberField,
    /// The generator's name and its declaration, when a field is declared.
    pub field_decl: Option<(String, String)>,
    /// The value over the field of each operator known in the file (`None`: unknown).
    pub kvalues: Vec<Option<KMatrix>>,
    /// Operators whose entries are outside Q (known here, unknown to the rational solver).
    pub field_ops: Vec<usize>,
    /// The dimension of the modelling space, 2 or 3.
    pub space: usize,
    /// The start state.
    pub start: usize,
    /// The control points of the start state (`space` coordinates each), or `None` for the
    /// default (a regular polygon).
    pub points: Option<Vec<Vec<FieldElement>>>,
    /// The primitive of each state.
    pub primitives: Vec<Primitive>,
    /// Entry values from `param` lines: (entry name, value, span).
    pub params: Vec<(String, BigRational, Span)>,
    /// The rule text the automaton was compiled from (`None`: an automaton file).
    pub rule: Option<String>,
}

fn err(
    code: &'static str,
    msg: impl Into<String>,
    ln: usize,
    col: usize,
    len: usize,
    src: &Source,
) -> Error {
    Error::at(code, msg, ln, col, len.max(1), src)
}

/// Parses an exact element of `k`: a sum of terms `c`, `c·g^e`, `c g^e` (c a rational, g the
/// generator's name, `e` a non-negative integer), e.g. `3s-4s^3`, `-1/2+2*s^2`. `None` when the
/// text is not of that form.
pub fn parse_field_element(t: &str, k: &NumberField, gen: Option<&str>) -> Option<FieldElement> {
    if t.is_empty() || t.len() > 400 {
        return None;
    }
    parse_terms(t, gen).map(|coeffs| k.element(&Poly::new(coeffs)))
}

/// Reads a sum of terms `c`, `c*v`, `c v^e` (c rational, optional; e at most 64; `v` the
/// variable, absent for rationals only), without spaces, into coefficients by degree. `None` when
/// the text is not of that form.
fn parse_terms(t: &str, var: Option<&str>) -> Option<Vec<BigRational>> {
    let mut coeffs: Vec<BigRational> = Vec::new();
    let bytes = t.as_bytes();
    let mut i = 0;
    let mut first = true;
    while i < bytes.len() {
        let mut sign = BigRational::one();
        if bytes[i] == b'+' || bytes[i] == b'-' {
            if bytes[i] == b'-' {
                sign = -sign;
            }
            i += 1;
        } else if !first {
            return None;
        }
        first = false;
        let start = i;
        while i < bytes.len() && (bytes[i].is_ascii_digit() || bytes[i] == b'/' || bytes[i] == b'.')
        {
            i += 1;
        }
        let coef = if i > start {
            parse_rational(&t[start..i])?
        } else {
            BigRational::one()
        };
        if i < bytes.len() && bytes[i] == b'*' {
            i += 1;
        }
        let mut exp = 0usize;
        if let Some(v) = var.filter(|v| t[i..].starts_with(v)) {
            i += v.len();
            exp = 1;
            if i < bytes.len() && bytes[i] == b'^' {
                i += 1;
                let s = i;
                while i < bytes.len() && bytes[i].is_ascii_digit() {
                    i += 1;
                }
                exp = t[s..i].parse().ok().filter(|e| *e <= 64)?;
            }
        } else if i == start {
            return None;
        }
        if coeffs.len() <= exp {
            coeffs.resize(exp + 1, BigRational::zero());
        }
        coeffs[exp] += sign * coef;
    }
    Some(coeffs)
}

/// Parses a polynomial in `x` (or `var`) over Q: `16x^4 - 20x^2 + 5`.
fn parse_poly(t: &str, var: &str) -> Option<Poly> {
    let compact: String = t.chars().filter(|c| !c.is_whitespace()).collect();
    parse_terms(&compact, Some(var)).map(Poly::new)
}

/// Parses a bracketed matrix of field elements starting at byte `start` of `line`.
fn parse_kmatrix(
    line: &str,
    start: usize,
    k: &NumberField,
    gen: Option<&str>,
    ln: usize,
    src: &Source,
) -> Result<(Vec<Vec<FieldElement>>, usize)> {
    let col = |b: usize| line[..b].chars().count() + 1;
    let Some(close) = line[start..].find(']').map(|i| start + i) else {
        return Err(err(
            "E0701",
            "matrix literal is not closed by `]`",
            ln,
            col(start),
            1,
            src,
        ));
    };
    let inner = &line[start + 1..close];
    let mut rows = Vec::new();
    let mut offset = start + 1;
    for row in inner.split(';') {
        let mut vals = Vec::new();
        let mut pos = 0;
        for tok in row.split(|c: char| c.is_whitespace() || c == ',') {
            if tok.is_empty() {
                pos += 1;
                continue;
            }
            let tstart = offset + row[pos..].find(tok).map_or(pos, |i| i + pos);
            pos = tstart - offset + tok.len();
            let v = parse_field_element(tok, k, gen).ok_or_else(|| {
                err(
                    "E0706",
                    match gen {
                        Some(g) => format!("`{tok}` is not an exact number nor a polynomial in `{g}` (use 1/3, 0.25, 2{g}^2-1)"),
                        None => format!("`{tok}` is not an exact number (use 1/3, -2 or 0.25)"),
                    },
                    ln,
                    col(tstart),
                    tok.chars().count(),
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
        return Err(err(
            "E0703",
            "matrix rows must be non-empty and of equal length",
            ln,
            col(start),
            close + 1 - start,
            src,
        ));
    }
    Ok((rows, close + 1))
}

/// Parses a `field NAME = root of POLYNOMIAL in [LO, HI]` declaration (`t`, a trimmed slice of
/// `line`): the field and (generator name, normalised declaration). Shared by automaton and rule
/// files.
pub(crate) fn parse_field_decl(
    line: &str,
    t: &str,
    ln: usize,
    src: &Source,
) -> Result<(NumberField, (String, String))> {
    let col = |s: &str| {
        line[..(s.as_ptr() as usize - line.as_ptr() as usize)]
            .chars()
            .count()
            + 1
    };
    let bad = || {
        err(
            "E0711",
            "expected `field NAME = root of POLYNOMIAL in [LO, HI]`",
            ln,
            col(t),
            t.chars().count(),
            src,
        )
    };
    let rest = t["field".len()..].trim();
    let (name, rhs) = rest.split_once('=').ok_or_else(bad)?;
    let name = name.trim();
    if name.is_empty() || !name.chars().all(|c| c.is_ascii_alphabetic()) {
        return Err(bad());
    }
    let rhs = rhs.trim();
    let body = rhs.strip_prefix("root of").ok_or_else(bad)?;
    let (poly_text, interval) = body.rsplit_once(" in ").ok_or_else(bad)?;
    let interval = interval.trim();
    let inner = interval
        .strip_prefix('[')
        .and_then(|s| s.strip_suffix(']'))
        .ok_or_else(bad)?;
    let (lo, hi) = inner.split_once(',').ok_or_else(bad)?;
    let (lo, hi) = (parse_rational(lo.trim()), parse_rational(hi.trim()));
    let (Some(lo), Some(hi)) = (lo, hi) else {
        return Err(err(
            "E0711",
            "the interval's ends must be exact numbers",
            ln,
            col(interval),
            interval.len(),
            src,
        ));
    };
    let f = parse_poly(poly_text.trim(), "x")
        .or_else(|| parse_poly(poly_text.trim(), name))
        .filter(|p| p.deg() >= 1 && p.deg() <= 16)
        .ok_or_else(|| {
            err(
                "E0711",
                format!(
                    "`{}` is not a polynomial in x of degree 1 to 16 with exact coefficients",
                    poly_text.trim()
                ),
                ln,
                col(poly_text.trim()),
                poly_text.trim().len(),
                src,
            )
        })?;
    let gen = RealAlgebraic::root_in(&f, &lo, &hi).ok_or_else(|| {
            err("E0711", format!("{} has no root or more than one root in [{lo}, {hi}]: give an interval isolating one root", f.render("x")), ln, col(interval), interval.len(), src)
        })?;
    Ok((
        NumberField::new(gen),
        (
            name.to_string(),
            format!("{name} = root of {} in [{lo}, {hi}]", f.render("x")),
        ),
    ))
}

/// A `primitive` line: state name, primitive, line, column, and the span of each index.
type PrimitiveLine = (String, Primitive, usize, usize, Vec<(usize, usize)>);

/// True when the first meaningful line of a text starts an automaton file (`state`, `field` or
/// `space`).
pub fn is_automaton_model(text: &str) -> bool {
    text.lines()
        .map(|l| l.split('#').next().unwrap_or("").trim())
        .find(|l| !l.is_empty())
        .is_some_and(|l| {
            l.starts_with("state ") || l.starts_with("field ") || l.starts_with("space ")
        })
}

/// Parses an automaton file with its modelling lines.
pub fn parse_model(src: &Source) -> Result<AutomatonModel> {
    let mut filtered: Vec<String> = Vec::new();
    let mut field = NumberField::new(RealAlgebraic::rational(BigRational::zero()));
    let mut field_decl: Option<(String, String)> = None;
    let mut space: Option<(usize, usize)> = None;
    let mut start: Option<(String, usize, usize)> = None;
    let mut points: Option<(Vec<Vec<FieldElement>>, usize, usize)> = None;
    let mut prims: Vec<PrimitiveLine> = Vec::new();
    let mut params: Vec<(String, BigRational, Span)> = Vec::new();
    let mut kops: Vec<(String, Vec<Vec<FieldElement>>, usize, usize)> = Vec::new();
    for (ln0, raw) in src.text.lines().enumerate() {
        let ln = ln0 + 1;
        let line = raw.split('#').next().unwrap_or("");
        let t = line.trim();
        let col = |s: &str| {
            line[..(s.as_ptr() as usize - line.as_ptr() as usize)]
                .chars()
                .count()
                + 1
        };
        let first = t.split_whitespace().next().unwrap_or("");
        match first {
            "field" => {
                if field_decl.is_some() {
                    return Err(err(
                        "E0711",
                        "a second `field` line (one field per file)",
                        ln,
                        col(t),
                        t.len(),
                        src,
                    ));
                }
                let (k, decl) = parse_field_decl(line, t, ln, src)?;
                field = k;
                field_decl = Some(decl);
                filtered.push(String::new());
            }
            "space" => {
                let d = t.split_whitespace().nth(1).unwrap_or("");
                match (d.parse::<usize>(), t.split_whitespace().count()) {
                    (Ok(v @ (2 | 3)), 2) if space.is_none() => space = Some((v, ln)),
                    _ => {
                        return Err(err(
                            "E0712",
                            "expected `space 2` or `space 3`, once",
                            ln,
                            col(t),
                            t.len(),
                            src,
                        ))
                    }
                }
                filtered.push(String::new());
            }
            "start" => {
                let ws: Vec<&str> = t.split_whitespace().collect();
                if ws.len() != 2 || start.is_some() {
                    return Err(err(
                        "E0712",
                        "expected `start STATE`, once",
                        ln,
                        col(t),
                        t.len(),
                        src,
                    ));
                }
                start = Some((ws[1].to_string(), ln, col(ws[1])));
                filtered.push(String::new());
            }
            "points" => {
                if points.is_some() {
                    return Err(err(
                        "E0712",
                        "a second `points` line",
                        ln,
                        col(t),
                        t.len(),
                        src,
                    ));
                }
                let rest = &t["points".len()..];
                let Some(b) = rest.find('[') else {
                    return Err(err(
                        "E0712",
                        "expected `points [X Y; X Y; …]`",
                        ln,
                        col(t),
                        t.len(),
                        src,
                    ));
                };
                let bstart = (rest.as_ptr() as usize - line.as_ptr() as usize) + b;
                let gen = field_decl.as_ref().map(|(n, _)| n.as_str());
                let (rows, end) = parse_kmatrix(line, bstart, &field, gen, ln, src)?;
                if !line[end..].trim().is_empty() {
                    return Err(err(
                        "E0701",
                        "unexpected text after the matrix",
                        ln,
                        col(&line[end..]),
                        line[end..].trim_end().len(),
                        src,
                    ));
                }
                points = Some((rows, ln, col(t)));
                filtered.push(String::new());
            }
            "primitive" => {
                let ws: Vec<&str> = t.split_whitespace().collect();
                if ws.len() < 3 {
                    return Err(err(
                        "E0712",
                        "expected `primitive STATE point|polyline|polygon|none [INDEX …]`",
                        ln,
                        col(t),
                        t.len(),
                        src,
                    ));
                }
                let mut idx = Vec::new();
                let mut spans = Vec::new();
                for w in &ws[3..] {
                    let Ok(v) = w.parse::<usize>() else {
                        return Err(err(
                            "E0712",
                            format!("`{w}` is not a control-point index (0, 1, …)"),
                            ln,
                            col(w),
                            w.len(),
                            src,
                        ));
                    };
                    idx.push(v);
                    spans.push((col(w), w.len()));
                }
                let p = match ws[2] {
                    "point" if idx.len() <= 1 => Primitive::Point(idx.first().copied().unwrap_or(0)),
                    "polyline" => Primitive::Polyline(idx),
                    "polygon" => Primitive::Polygon(idx),
                    "none" if idx.is_empty() => Primitive::Nothing,
                    other => return Err(err("E0712", format!("`{other}`: a primitive is `point [I]`, `polyline [I …]`, `polygon [I …]` or `none`"), ln, col(ws[2]), ws[2].len(), src)),
                };
                prims.push((ws[1].to_string(), p, ln, col(ws[1]), spans));
                filtered.push(String::new());
            }
            "param" => {
                let rest = t["param".len()..].trim();
                let parsed = rest
                    .split_once('=')
                    .and_then(|(n, v)| Some((n.trim().to_string(), parse_rational(v.trim())?)));
                let Some((name, value)) = parsed else {
                    return Err(err(
                        "E0712",
                        "expected `param OPERATOR[ROW][COL] = VALUE` with an exact value",
                        ln,
                        col(t),
                        t.len(),
                        src,
                    ));
                };
                params.push((
                    name,
                    value,
                    Span {
                        line: ln,
                        col: col(t),
                        len: t.chars().count(),
                    },
                ));
                filtered.push(String::new());
            }
            "sub" | "embed" | "perm" | "op" if field_decl.is_some() && t.contains('=') => {
                // Operator values may hold field elements: read them here.
                let (head, value) = t.split_once('=').expect("contains =");
                let vs = value.trim_start();
                let name = head.split_whitespace().nth(1).unwrap_or("").to_string();
                if vs.starts_with('[') {
                    let bstart = vs.as_ptr() as usize - line.as_ptr() as usize;
                    let gen = field_decl.as_ref().map(|(n, _)| n.as_str());
                    let (rows, _) = parse_kmatrix(line, bstart, &field, gen, ln, src)?;
                    if rows.iter().flatten().any(|v| v.as_rational().is_none()) {
                        kops.push((name, rows, ln, col(vs)));
                        // The rational parser sees the operator as unknown.
                        filtered.push(line[..bstart].trim_end().trim_end_matches('=').to_string());
                        continue;
                    }
                }
                filtered.push(raw.to_string());
            }
            _ => filtered.push(raw.to_string()),
        }
    }
    let text = filtered.join("\n");
    let automaton = parse_automaton(&Source {
        name: src.name.clone(),
        text,
    })
    .map_err(|e| relocate(e, src))?;
    let n_ops = automaton.operators.len();
    let mut kvalues: Vec<Option<KMatrix>> = automaton
        .operators
        .iter()
        .map(|o| o.value.as_ref().map(|m| KMatrix::from_rational(&field, m)))
        .collect();
    let mut field_ops = Vec::new();
    for (name, rows, ln, c) in kops {
        let o = automaton
            .operators
            .iter()
            .position(|x| x.name == name)
            .expect("declared by the parser");
        let op = &automaton.operators[o];
        let want = (automaton.states[op.to].dim, automaton.states[op.from].dim);
        if (rows.len(), rows[0].len()) != want {
            return Err(err(
                "E0703",
                format!(
                    "`{name}` is {}×{}, but the matrix is {}×{}",
                    want.0,
                    want.1,
                    rows.len(),
                    rows[0].len()
                ),
                ln,
                c,
                1,
                src,
            ));
        }
        kvalues[o] = Some(KMatrix {
            rows: want.0,
            cols: want.1,
            data: rows.into_iter().flatten().collect(),
        });
        field_ops.push(o);
    }
    debug_assert_eq!(kvalues.len(), n_ops);
    let find = |s: &str| automaton.states.iter().position(|x| x.name == s);
    let start = match start {
        Some((name, ln, c)) => find(&name).ok_or_else(|| {
            err(
                "E0702",
                format!("unknown state `{name}`"),
                ln,
                c,
                name.len(),
                src,
            )
        })?,
        None => {
            // The first state of largest dimension.
            let mut best = 0;
            for (i, s) in automaton.states.iter().enumerate() {
                if s.dim > automaton.states[best].dim {
                    best = i;
                }
            }
            best
        }
    };
    let space_dim = space.map_or(2, |s| s.0);
    let points = match points {
        None => None,
        Some((rows, ln, c)) => {
            let m = automaton.states[start].dim;
            if rows.len() != m || rows[0].len() != space_dim {
                return Err(err("E0712", format!("the start state `{}` has {m} control points in space {space_dim}: `points` needs {m} rows of {space_dim} numbers, found {} of {}", automaton.states[start].name, rows.len(), rows[0].len()), ln, c, 6, src));
            }
            Some(rows)
        }
    };
    let mut primitives: Vec<Primitive> = automaton
        .states
        .iter()
        .map(|s| Primitive::Polyline((0..s.dim).collect()))
        .collect();
    for (name, p, ln, c, spans) in prims {
        let s = find(&name).ok_or_else(|| {
            err(
                "E0702",
                format!("unknown state `{name}`"),
                ln,
                c,
                name.len(),
                src,
            )
        })?;
        let m = automaton.states[s].dim;
        let p = match p {
            Primitive::Polyline(v) if v.is_empty() => Primitive::Polyline((0..m).collect()),
            Primitive::Polygon(v) if v.is_empty() => Primitive::Polygon((0..m).collect()),
            p => p,
        };
        let idx: Vec<usize> = match &p {
            Primitive::Point(i) => vec![*i],
            Primitive::Polyline(v) | Primitive::Polygon(v) => v.clone(),
            Primitive::Nothing => Vec::new(),
        };
        if let Some(pos) = idx.iter().position(|&i| i >= m) {
            let (cc, l) = spans.get(pos).copied().unwrap_or((c, name.len()));
            return Err(err(
                "E0712",
                format!(
                    "state `{name}` has {m} control points (0 to {}): no point {}",
                    m - 1,
                    idx[pos]
                ),
                ln,
                cc,
                l,
                src,
            ));
        }
        primitives[s] = p;
    }
    Ok(AutomatonModel {
        automaton,
        field,
        field_decl,
        kvalues,
        field_ops,
        space: space_dim,
        start,
        points,
        primitives,
        params,
        rule: None,
    })
}

/// Errors of the filtered text point into the original file.
fn relocate(e: Error, src: &Source) -> Error {
    match e {
        Error::Syntax(mut d) => {
            if d.source.is_some() {
                d.source = Some(src.clone());
            }
            Error::Syntax(d)
        }
        other => other,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn src(t: &str) -> Source {
        Source {
            name: "a.aut".into(),
            text: t.into(),
        }
    }

    #[test]
    fn field_entries_are_exact() {
        let m = parse_model(&src("field s = root of 16x^4 - 20x^2 + 5 in [1/2, 3/5]\nstate a 2\nsub a.T : a <- a = [1-2s^2 0; 2s^2 1]\n")).unwrap();
        assert_eq!(m.field.degree(), 4);
        let t = m.kvalues[0].as_ref().unwrap();
        assert!(t.is_barycentric(&m.field));
        assert_eq!(m.field_ops, vec![0]);
        assert!(m.automaton.operators[0].value.is_none());
    }

    #[test]
    fn model_errors_have_codes_and_columns() {
        let cases = [
            ("state e 2\nspace 4\n", "E0712", 2, 1),
            (
                "field s = root of x^2 - 2 in [-2, 2]\nstate e 1\n",
                "E0711",
                1,
                30,
            ),
            ("state e 2\npoints [0 0; 1]\n", "E0703", 2, 8),
            ("state e 2\npoints [0 0 0; 1 1 1]\n", "E0712", 2, 1),
            ("state e 2\nprimitive e polygon 0 2\n", "E0712", 2, 23),
            ("state e 2\nprimitive f point\n", "E0702", 2, 11),
            ("state e 2\nstart q\n", "E0702", 2, 7),
            (
                "field s = root of x^2 - 2 in [1, 2]\nstate e 1\nsub t : e <- e = [2q]\n",
                "E0706",
                3,
                19,
            ),
        ];
        for (text, code, line, c) in cases {
            let e = parse_model(&src(text)).unwrap_err();
            let s = e.span().unwrap();
            assert_eq!((e.code(), s.line, s.col), (code, line, c), "{text}");
        }
    }
}
