//! Exact templates and the template file format (docs/FORMATS.md, "Template files"): per face
//! type, optionally the corners of its template polygon, and per sub-face the target positions of
//! the sub-face's control points, all exact rationals (`1/3`, `-0.25`, `2`).
//!
//! `lacuna render INPUT --write-template FILE` writes the default template in this format (the
//! floating-point template of `crate::geometry::template` rounded to 6 decimals), so that a user edits it;
//! `--template FILE` reads it back and projects it exactly onto the solution space.

use crate::geometry::point::QPoint;
use crate::geometry::template::{mean_value, Template};
use crate::{topology::Face, topology::Origin, topology::TypeSet, Error, Source};
use num_bigint::BigInt;
use num_rational::BigRational as Q;
use num_traits::{Signed, ToPrimitive, Zero};
use std::fmt::Write as _;

/// The exact template of one face type.
#[derive(Clone, Debug, PartialEq)]
pub struct TypeTemplate {
    /// The corners of its polygon (edge i from corner i to corner i + 1).
    pub corners: Vec<QPoint>,
    /// Its control points: the corners and, on each Bézier edge, the inner points evenly spaced.
    pub points: Vec<QPoint>,
    /// Per sub-face, the target of each of its control points.
    pub targets: Vec<Vec<QPoint>>,
}

/// An exact template for every face type of a closure, with the regularisation weight δ.
#[derive(Clone, Debug, PartialEq)]
pub struct ExactTemplate {
    /// Per face type.
    pub types: Vec<TypeTemplate>,
    /// Weight of `|c − r|²` (r: the mean value coordinates of the target); 0 by default.
    pub delta: Q,
}

/// `x` rounded to 6 decimals, exactly.
fn decimal6(x: f64) -> Q {
    let scaled = (x * 1e6).round();
    let num = if scaled.is_finite() {
        BigInt::from(scaled as i128)
    } else {
        BigInt::zero()
    };
    Q::new(num, BigInt::from(1_000_000))
}

fn to_f64(q: &Q) -> f64 {
    q.to_f64().unwrap_or(f64::NAN)
}

/// The float version of an exact point.
pub(crate) fn float_point(p: &QPoint) -> [f64; 2] {
    [to_f64(&p[0]), to_f64(&p[1])]
}

/// The control points of a face with exact corners, exactly as
/// `crate::geometry::template::control_points` places them in floating point: evenly spaced on
/// straight edges, and in a digon the Bézier inner points pushed outwards by
/// `DIGON_BULGE·4s(1 − s)` times the chord (DIGON_BULGE = 1/2), so that the frame has an area.
fn exact_control_points(face: &Face, corners: &[QPoint], q: usize) -> Vec<QPoint> {
    let n = corners.len();
    let bulge = Q::new(BigInt::from(1), BigInt::from(2));
    debug_assert_eq!(bulge.to_f64(), Some(crate::geometry::template::DIGON_BULGE));
    let four = Q::from_integer(BigInt::from(4));
    let mut pts = Vec::new();
    for (i, e) in face.boundary.iter().enumerate() {
        let d = crate::geometry::template::dim_of(e, q);
        let (a, b) = (&corners[i], &corners[(i + 1) % n]);
        for c in 0..d - 1 {
            let s = Q::new(BigInt::from(c), BigInt::from(d - 1));
            let mut p = [&a[0] + (&b[0] - &a[0]) * &s, &a[1] + (&b[1] - &a[1]) * &s];
            if n == 2 && c > 0 {
                // Outward normal of a counter-clockwise face: the edge direction turned right.
                let h = &bulge * &four * &s * (Q::from_integer(BigInt::from(1)) - &s);
                p[0] += &h * (&b[1] - &a[1]);
                p[1] -= &h * (&b[0] - &a[0]);
            }
            pts.push(p);
        }
    }
    pts
}

impl ExactTemplate {
    /// The floating-point templates rounded to 6 decimals (corners, then the control points
    /// derived from them exactly; targets rounded), δ = 0.
    pub(crate) fn rounded(types: &TypeSet, floats: &[Template], q: usize) -> ExactTemplate {
        let types = types
            .types
            .iter()
            .zip(floats)
            .map(|(ty, t)| {
                let corners: Vec<QPoint> =
                    crate::geometry::template::regular_polygon(ty.face.boundary.len())
                        .into_iter()
                        .map(|p| [decimal6(p[0]), decimal6(p[1])])
                        .collect();
                let points = exact_control_points(&ty.face, &corners, q);
                let targets = t
                    .targets
                    .iter()
                    .map(|sub| {
                        sub.iter()
                            .map(|p| [decimal6(p[0]), decimal6(p[1])])
                            .collect()
                    })
                    .collect();
                TypeTemplate {
                    corners,
                    points,
                    targets,
                }
            })
            .collect();
        ExactTemplate {
            types,
            delta: Q::zero(),
        }
    }

    /// The reference column of a target: its mean value coordinates in the template polygon,
    /// computed in floating point and rounded to multiples of `2^-bits` (any fixed rational
    /// vector would do: it only picks one minimiser among equals, or weighs δ).
    pub(crate) fn reference(&self, ty: usize, target: &QPoint, bits: u32) -> Vec<Q> {
        let poly: Vec<[f64; 2]> = self.types[ty].points.iter().map(float_point).collect();
        mean_value(&poly, float_point(target))
            .into_iter()
            .map(|w| crate::geometry::point::dyadic(w, bits))
            .collect()
    }
}

/// An exact rational as a short decimal when it is one (at most 12 digits after the point),
/// else as `p/q`.
pub fn format_exact(q: &Q) -> String {
    let mut den = q.denom().clone();
    let (mut twos, mut fives) = (0u32, 0u32);
    while (&den % 2u8).is_zero() {
        den /= 2u8;
        twos += 1;
    }
    while (&den % 5u8).is_zero() {
        den /= 5u8;
        fives += 1;
    }
    let digits = twos.max(fives);
    if den != BigInt::from(1) || digits > 12 {
        return q.to_string();
    }
    if digits == 0 {
        return q.numer().to_string();
    }
    let scaled = (q * Q::from_integer(BigInt::from(10).pow(digits))).to_integer();
    let sign = if scaled.is_negative() { "-" } else { "" };
    let s = format!("{:0>width$}", scaled.abs(), width = digits as usize + 1);
    let (int, frac) = s.split_at(s.len() - digits as usize);
    format!("{sign}{int}.{frac}")
}

fn write_points(out: &mut String, pts: &[QPoint]) {
    let text: Vec<String> = pts
        .iter()
        .map(|p| format!("{} {}", format_exact(&p[0]), format_exact(&p[1])))
        .collect();
    out.push_str(&text.join("; "));
}

fn origin_text(o: &Origin) -> String {
    match *o {
        Origin::Piece { edge, piece } => format!("piece {piece} of edge {edge}"),
        Origin::Spoke { spoke, inward } => {
            format!(
                "spoke {spoke} {}",
                if inward { "inward" } else { "outward" }
            )
        }
        Origin::Lacuna { side } => format!("lacuna side {side}"),
        Origin::GapSide { edge, gap, after } => format!(
            "{} side of gap {gap} of edge {edge}",
            if after { "after" } else { "before" }
        ),
    }
}

/// The template file text of `template` (the format of docs/FORMATS.md).
pub fn write_template(name: &str, types: &TypeSet, q: usize, template: &ExactTemplate) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "# lacuna template for {name}: Bézier degree {q}, {}.",
        crate::error::counted(types.types.len(), "face type", "face types")
    );
    out.push_str(
        "# Exact positions: decimals (0.25), fractions (1/3), integers. Edit the targets (and\n\
         # optionally the corners), then: lacuna render INPUT --template THIS_FILE ... (docs/FORMATS.md)\n",
    );
    let _ = writeln!(out, "delta {}", format_exact(&template.delta));
    for (t, (ty, tt)) in types.types.iter().zip(&template.types).enumerate() {
        let _ = writeln!(
            out,
            "\ntype T{t}    # {}: {} control points, {} sub-faces",
            ty.face,
            tt.points.len(),
            tt.targets.len()
        );
        out.push_str("corners ");
        write_points(&mut out, &tt.corners);
        out.push('\n');
        for (k, (sf, targets)) in ty.subdivision.subfaces.iter().zip(&tt.targets).enumerate() {
            let edges: Vec<String> = sf.origins.iter().map(origin_text).collect();
            let _ = writeln!(
                out,
                "# sub-face {k}: type T{}, {} points; edges: {}",
                ty.children[k],
                targets.len(),
                edges.join(", ")
            );
            let _ = write!(out, "sub {k} ");
            write_points(&mut out, targets);
            out.push('\n');
        }
    }
    out
}

/// A token of a line: its 1-based column and text; `;` is a token of its own.
fn tokens(line: &str) -> Vec<(usize, &str)> {
    let mut out = Vec::new();
    let mut start: Option<(usize, usize)> = None; // (column, byte offset)
    for (k, (b, ch)) in line.char_indices().enumerate() {
        if ch.is_whitespace() || ch == ';' {
            if let Some((c, s)) = start.take() {
                out.push((c, &line[s..b]));
            }
            if ch == ';' {
                out.push((k + 1, ";"));
            }
        } else if start.is_none() {
            start = Some((k + 1, b));
        }
    }
    if let Some((c, s)) = start {
        out.push((c, &line[s..]));
    }
    out
}

/// A listed type being read: its index, the sub-faces seen, its corners if given, its line.
type Listed = (usize, Vec<bool>, Option<Vec<QPoint>>, usize);

/// Parses a template file for the closure `types` (Bézier degree `q`), starting from `default`:
/// the types the file lists replace theirs. Errors carry the line and column (codes E1020–E1025).
pub fn parse_template(
    text: &str,
    source_name: &str,
    types: &TypeSet,
    q: usize,
    default: &ExactTemplate,
) -> Result<ExactTemplate, Error> {
    let src = Source {
        name: source_name.to_string(),
        text: text.to_string(),
    };
    let err = |code: &'static str, msg: String, line: usize, col: usize, len: usize| {
        Error::at(code, msg, line, col, len, &src)
    };
    let mut out = default.clone();
    // Per listed type: the line of its `type`, whether corners were given, sub-faces seen.
    let mut seen_types: Vec<Option<usize>> = vec![None; types.types.len()];
    let mut current: Option<Listed> = None;
    let finish = |cur: Option<Listed>, out: &mut ExactTemplate| -> Result<(), Error> {
        if let Some((t, subs, corners, line)) = cur {
            if let Some(k) = subs.iter().position(|s| !s) {
                return Err(err(
                    "E1024",
                    format!("type T{t}: sub-face {k} has no `sub {k}` line (every sub-face of a listed type needs its targets)"),
                    line,
                    1,
                    4,
                ));
            }
            if let Some(c) = corners {
                out.types[t].points = exact_control_points(&types.types[t].face, &c, q);
                out.types[t].corners = c;
            }
        }
        Ok(())
    };
    let mut delta_seen = false;
    for (i, raw) in text.lines().enumerate() {
        let line_no = i + 1;
        let line = raw.split('#').next().unwrap_or("");
        let toks = tokens(line);
        let Some(&(col0, word)) = toks.first() else {
            continue;
        };
        let rest = &toks[1..];
        match word {
            "delta" => {
                if delta_seen || rest.len() != 1 {
                    return Err(err(
                        "E1020",
                        "`delta` takes one exact number, once per file".into(),
                        line_no,
                        col0,
                        5,
                    ));
                }
                let (c, s) = rest[0];
                let v = crate::input::parse_rational(s)
                    .filter(|v| !v.is_negative())
                    .ok_or_else(|| {
                        err(
                            "E1021",
                            format!("`{s}` is not an exact number ≥ 0 (0, 1/20, 0.05)"),
                            line_no,
                            c,
                            s.chars().count(),
                        )
                    })?;
                out.delta = v;
                delta_seen = true;
            }
            "type" => {
                finish(current.take(), &mut out)?;
                let Some(&(c, first)) = rest.first() else {
                    return Err(err(
                        "E1020",
                        "`type` needs a face type: T3, 3 or its canonical notation".into(),
                        line_no,
                        col0,
                        4,
                    ));
                };
                let tail = line[line.char_indices().nth(c - 1).map_or(0, |x| x.0)..].trim();
                let index = first
                    .strip_prefix('T')
                    .unwrap_or(first)
                    .parse::<usize>()
                    .ok()
                    .filter(|_| rest.len() == 1);
                let t = match index {
                    Some(t) => Some(t).filter(|&t| t < types.types.len()),
                    None => Face::parse(tail).ok().and_then(|f| {
                        let canon = f.canonical().0;
                        types.types.iter().position(|ty| ty.face == canon)
                    }),
                }
                .ok_or_else(|| {
                    err(
                        "E1022",
                        format!(
                            "no face type `{tail}` in the closure (T0 … T{}, or a type's canonical notation as `lacuna closure` prints it)",
                            types.types.len() - 1
                        ),
                        line_no,
                        c,
                        tail.chars().count(),
                    )
                })?;
                if let Some(l) = seen_types[t] {
                    return Err(err(
                        "E1024",
                        format!("type T{t} is already given on line {l}"),
                        line_no,
                        col0,
                        4,
                    ));
                }
                seen_types[t] = Some(line_no);
                let subs = vec![false; types.types[t].children.len()];
                current = Some((t, subs, None, line_no));
            }
            "corners" | "sub" => {
                let Some((t, subs, corners, _)) = current.as_mut() else {
                    return Err(err(
                        "E1020",
                        format!("`{word}` before any `type` line"),
                        line_no,
                        col0,
                        word.len(),
                    ));
                };
                let t = *t;
                let (pts_toks, k) = if word == "sub" {
                    let Some(&(c, s)) = rest.first() else {
                        return Err(err(
                            "E1020",
                            "`sub` needs the sub-face index".into(),
                            line_no,
                            col0,
                            3,
                        ));
                    };
                    let nsub = subs.len();
                    let k = s
                        .parse::<usize>()
                        .ok()
                        .filter(|&k| k < nsub)
                        .ok_or_else(|| {
                            err(
                                "E1023",
                                format!(
                                    "type T{t} has sub-faces 0 … {}; `{s}` is none of them",
                                    nsub - 1
                                ),
                                line_no,
                                c,
                                s.chars().count(),
                            )
                        })?;
                    if subs[k] {
                        return Err(err(
                            "E1024",
                            format!("sub-face {k} of type T{t} is given twice"),
                            line_no,
                            c,
                            s.chars().count(),
                        ));
                    }
                    (&rest[1..], Some(k))
                } else {
                    if corners.is_some() {
                        return Err(err(
                            "E1024",
                            format!("the corners of type T{t} are given twice"),
                            line_no,
                            col0,
                            7,
                        ));
                    }
                    (rest, None)
                };
                let pts = parse_points(pts_toks, &err, line_no)?;
                let expected = match k {
                    Some(k) => out.types[t].targets[k].len(),
                    None => types.types[t].face.boundary.len(),
                };
                if pts.len() != expected {
                    let what = match k {
                        Some(k) => {
                            format!("sub-face {k} of type T{t} has {expected} control points")
                        }
                        None => format!("type T{t} has {expected} corners"),
                    };
                    return Err(err(
                        "E1023",
                        format!("{what}; this line gives {}", pts.len()),
                        line_no,
                        col0,
                        line.trim_end().chars().count() + 1 - col0,
                    ));
                }
                match k {
                    Some(k) => {
                        subs[k] = true;
                        out.types[t].targets[k] = pts;
                    }
                    None => *corners = Some(pts),
                }
            }
            other => {
                return Err(err(
                    "E1020",
                    format!("unknown keyword `{other}` (expected delta, type, corners or sub)"),
                    line_no,
                    col0,
                    other.chars().count(),
                ))
            }
        }
    }
    finish(current.take(), &mut out)?;
    Ok(out)
}

/// Points `x y; x y; …` (a trailing `;` allowed).
fn parse_points(
    toks: &[(usize, &str)],
    err: &dyn Fn(&'static str, String, usize, usize, usize) -> Error,
    line: usize,
) -> Result<Vec<QPoint>, Error> {
    let mut pts = Vec::new();
    for group in toks.split(|t| t.1 == ";") {
        if group.is_empty() {
            continue;
        }
        if group.len() != 2 {
            let (c, s) = group[0];
            return Err(err(
                "E1021",
                format!(
                    "a point is two exact numbers `x y`; found {} number(s) here",
                    group.len()
                ),
                line,
                c,
                s.chars().count(),
            ));
        }
        let mut xy = Vec::with_capacity(2);
        for &(c, s) in group {
            xy.push(crate::input::parse_rational(s).ok_or_else(|| {
                err(
                    "E1021",
                    format!("`{s}` is not an exact number (1/3, -0.25, 2)"),
                    line,
                    c,
                    s.chars().count(),
                )
            })?);
        }
        let y = xy.pop().expect("two");
        let x = xy.pop().expect("two");
        pts.push([x, y]);
    }
    Ok(pts)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_digon_frame_bulges_exactly_as_the_float_one() {
        // Corners (−1, 1/4), (1, 1/4); each Bézier inner point at the chord's middle (0, 1/4),
        // pushed right of its edge by ½·4·½·½ = ½ of the chord (2, 0) or (−2, 0): (0, −3/4)
        // and (0, 5/4). Flat, the frame had area 0 and an exact template of a digon projected
        // onto a collapsed lacuna.
        let q = |a: i64, b: i64| Q::new(a.into(), b.into());
        let face: Face = crate::input::load_input("B2 B2 | B2 B2 B2 | A1")
            .unwrap()
            .faces()[0]
            .clone();
        let corners = [[q(-1, 1), q(1, 4)], [q(1, 1), q(1, 4)]];
        let exact = exact_control_points(&face, &corners, 2);
        let by_hand = [
            [q(-1, 1), q(1, 4)],
            [q(0, 1), q(-3, 4)],
            [q(1, 1), q(1, 4)],
            [q(0, 1), q(5, 4)],
        ];
        assert_eq!(exact, by_hand);
        let float =
            crate::geometry::template::control_points(&face, &[[-1.0, 0.25], [1.0, 0.25]], 2);
        for (e, f) in exact.iter().zip(&float) {
            assert_eq!(float_point(e), *f);
        }
    }

    #[test]
    fn exact_decimals_are_written_as_decimals() {
        let q = |a: i64, b: i64| Q::new(a.into(), b.into());
        assert_eq!(format_exact(&q(1, 4)), "0.25");
        assert_eq!(format_exact(&q(-1, 4)), "-0.25");
        assert_eq!(format_exact(&q(-866025, 1_000_000)), "-0.866025");
        assert_eq!(format_exact(&q(3, 1)), "3");
        assert_eq!(format_exact(&q(1, 3)), "1/3");
        assert_eq!(format_exact(&q(1, 1 << 20)), "1/1048576");
        assert_eq!(format_exact(&q(0, 1)), "0");
    }

    #[test]
    fn tokens_have_columns() {
        assert_eq!(
            tokens("sub 0  1 2;3/4 -5"),
            vec![
                (1, "sub"),
                (5, "0"),
                (8, "1"),
                (10, "2"),
                (11, ";"),
                (12, "3/4"),
                (16, "-5")
            ]
        );
    }
}
