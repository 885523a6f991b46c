//! Reader for the input files of the AutoFrac2D command-line tool, so existing users can bring
//! their files.
//!
//! ```text
//! f
//! C_2_0 - B_2_0 - C_2_0 - B_2_0 / C_2_0 - B_2_0 - B_2_0 / 0 / 1
//! c
//! 0.3 / 1.1
//! p
//! 0 10
//! ```
//! `X_n_d` is an edge of kind X with n sub-edges and *remaining* delay d (so lacuna's delay is
//! d + 1); the third field is the face delay (again remaining, +1); the fourth the algorithm:
//! 0 = A3, 1 = AF1, 2 = A2. AutoFrac2D's algorithm 1 ("surround delay and Bézier") keeps a delayed
//! edge with its non-delayed Bézier neighbours: the spoke rule `AF1`. A face line without any delay
//! reads it as A1 (the two coincide there, and the names stay those of earlier versions). The `c` section
//! glues edges (`F1.E1 / F2.E2`); the `p` section gives coordinates (one `x y` per line), read as
//! described at [`crate::input::coords::read_point_section`]; the topology ignores them.

use crate::error::{Diagnostic, Error, Result, Source, Span};
use crate::input::assembly::vertices;
use crate::input::assembly::{Assembly, SharedEdge};
use crate::input::coords::{
    control_count, parse_coordinate, CoordKind, ExactPoint, FaceCoords, UserCoords, MAX_DEGREE,
};
use crate::topology::edge::{EdgeKind, EdgeType};
use crate::topology::face::{Face, Params};
use crate::topology::rule::Algorithm;
use num_rational::BigRational;

#[derive(Clone, Copy, PartialEq)]
enum Section {
    None,
    Faces,
    Links,
    Points,
}

/// The 1-based column of `part` (a sub-slice of `line`) in `line`.
fn col_in(line: &str, part: &str) -> usize {
    let off = (part.as_ptr() as usize)
        .saturating_sub(line.as_ptr() as usize)
        .min(line.len());
    line[..off].chars().count() + 1
}

/// True when the text looks like an AutoFrac2D file (its first meaningful line is `f`).
pub fn is_autofrac(text: &str) -> bool {
    text.lines()
        .map(str::trim)
        .find(|l| !l.is_empty() && !l.starts_with('#'))
        .is_some_and(|l| l == "f")
}

/// Parses an AutoFrac2D input file into an assembly.
pub fn parse_autofrac(src: &Source) -> Result<Assembly> {
    let mut section = Section::None;
    let mut faces: Vec<(String, Face)> = Vec::new();
    let mut shared = Vec::new();
    let mut lines = Vec::new();
    let mut points: Vec<ExactPoint> = Vec::new();
    let mut spans: Vec<Span> = Vec::new();
    let mut p_span: Option<Span> = None;
    // The line of each section header seen (`f`, `c`, `p`): each comes once (issue #20 item 17).
    let mut headers: Vec<(&str, usize)> = Vec::new();
    for (ln0, line) in src.text.lines().enumerate() {
        let ln = ln0 + 1;
        let t = line.trim();
        if t.is_empty() || t.starts_with('#') {
            continue;
        }
        if matches!(t, "f" | "c" | "p") {
            if let Some((_, first)) = headers.iter().find(|(h, _)| *h == t) {
                return Err(Error::at(
                    "E0301",
                    format!("the `{t}` section is given twice (first at line {first})"),
                    ln,
                    col_in(line, t),
                    1,
                    src,
                ));
            }
            headers.push((t, ln));
        }
        match t {
            "f" => section = Section::Faces,
            "c" => section = Section::Links,
            "p" => {
                section = Section::Points;
                p_span.get_or_insert(Span {
                    line: ln,
                    col: col_in(line, t),
                    len: 1,
                });
            }
            _ => match section {
                Section::None => {
                    return Err(Error::at(
                        "E0301",
                        "expected the `f` section first",
                        ln,
                        col_in(line, t),
                        t.len(),
                        src,
                    ));
                }
                Section::Faces => {
                    let face = parse_face(line, t, ln, src)?;
                    faces.push((faces.len().to_string(), face));
                }
                Section::Links => {
                    let parts: Vec<&str> = t.split('/').collect();
                    if parts.len() != 2 {
                        return Err(Error::at(
                            "E0301",
                            format!("expected `F1.E1 / F2.E2`, found `{t}`"),
                            ln,
                            col_in(line, t),
                            t.len(),
                            src,
                        ));
                    }
                    let mut ends = [(0usize, 0usize); 2];
                    for (k, p) in parts.iter().enumerate() {
                        let p = p.trim();
                        let parsed = p.split_once('.').and_then(|(f, e)| {
                            Some((f.parse::<usize>().ok()?, e.parse::<usize>().ok()?))
                        });
                        let Some((f, e)) = parsed else {
                            return Err(Error::at(
                                "E0301",
                                format!("expected `FACE.EDGE`, found `{p}`"),
                                ln,
                                col_in(line, p),
                                p.len(),
                                src,
                            ));
                        };
                        if f >= faces.len() {
                            return Err(Error::at(
                                "E0203",
                                format!("no face {f} (the file defines {})", faces.len()),
                                ln,
                                col_in(line, p),
                                p.len(),
                                src,
                            ));
                        }
                        ends[k] = (f, e);
                    }
                    shared.push(SharedEdge {
                        a: ends[0],
                        b: ends[1],
                    });
                    lines.push((ln, col_in(line, t)));
                }
                Section::Points => {
                    let words: Vec<&str> = t.split_whitespace().collect();
                    let xy: Vec<BigRational> = words.iter().filter_map(|w| number(w)).collect();
                    let [x, y] = <[BigRational; 2]>::try_from(xy)
                        .ok()
                        .filter(|_| words.len() == 2)
                        .ok_or_else(|| {
                            Error::at(
                                "E0303",
                                format!("expected a point `x y` with two finite numbers of magnitude at most 10^15 (a non-zero one not below 2.2e-308, where a float would round it to 0), found `{t}`"),
                                ln,
                                col_in(line, t),
                                t.len(),
                                src,
                            )
                        })?;
                    points.push([x, y]);
                    spans.push(Span {
                        line: ln,
                        col: col_in(line, t),
                        len: t.chars().count(),
                    });
                }
            },
        }
    }
    if faces.is_empty() {
        return Err(Error::at(
            "E0207",
            "no face defined in the `f` section",
            1,
            1,
            1,
            src,
        ));
    }
    let mut asm = Assembly {
        faces,
        shared,
        coords: Default::default(),
    };
    asm.check(src, &lines)?;
    // The topology ignores the coordinates: a `p` section that cannot be used is kept as an
    // error for the placement (render, measure, report), so files that verified before still do.
    if let Some(p) = p_span {
        match read_point_section(&asm, points, spans, p, src) {
            Ok(coords) => asm.coords = coords,
            Err(e) => asm.coords.unread = Some(diagnostic(e)),
        }
        if let Err(e) = crate::input::assembly::check(&asm) {
            asm.coords.faces.clear();
            asm.coords.unread = Some(diagnostic(e));
        }
    }
    Ok(asm)
}

fn diagnostic(e: Error) -> Diagnostic {
    match e {
        Error::Syntax(d) => *d,
        other => Diagnostic {
            code: other.code(),
            message: other.to_string(),
            span: None,
            source: None,
        },
    }
}

/// A coordinate of the `p` section: exact when written as an integer, decimal or fraction, else
/// the exact value of the floating-point number (`1e3`, as the AutoFrac2D tool reads it); finite,
/// of magnitude at most 10¹⁵, and not a non-zero number that the float reading would turn into
/// 0 or a subnormal (`1e-400`, `1e-310`: refused rather than read silently as 0).
fn number(w: &str) -> Option<BigRational> {
    if w.len() >= 64 {
        return None;
    }
    parse_coordinate(w).or_else(|| {
        let f = w
            .parse::<f64>()
            .ok()
            .filter(|f| f.is_finite() && f.abs() <= 1e15)?;
        let mantissa = w.split(['e', 'E']).next().unwrap_or("");
        let nonzero = mantissa.bytes().any(|b| (b'1'..=b'9').contains(&b));
        if nonzero && f.abs() < f64::MIN_POSITIVE {
            return None;
        }
        BigRational::from_float(f)
    })
}

/// Reads the `p` section of an AutoFrac2D file (lacuna's reading; see docs/FORMATS.md): with C
/// the total number of corners (Σ n_f), V the number of distinct vertices (shared edges identify
/// corners) and K_q the total number of control points at Bézier degree q, a section of
/// - C points gives the corners face after face, each face's corners in its edge order (corner i
///   starts edge i) — the AutoFrac2D tool's own layout when it places inner points itself (`-a`);
/// - K_q points (2 ≤ q ≤ 8; the tool writes q = 2, or 3 with `-c`) gives every control point,
///   face after face: each edge's first corner then its inner Bézier points;
/// - V points gives the distinct vertices in order of first appearance.
///
/// Any other count is error E0304 (at the `p` line), which lists the accepted counts; an empty
/// section gives no coordinates.
pub fn read_point_section(
    asm: &Assembly,
    points: Vec<ExactPoint>,
    spans: Vec<Span>,
    p_span: Span,
    src: &Source,
) -> Result<UserCoords> {
    let mut out = UserCoords {
        faces: Vec::new(),
        source: Some(src.clone()),
        unread: None,
    };
    let count = points.len();
    if count == 0 {
        return Ok(out);
    }
    let corners: usize = asm.faces.iter().map(|(_, f)| f.boundary.len()).sum();
    let (ids, v) = vertices(asm);
    let per_face = |q: Option<usize>| -> Vec<FaceCoords> {
        let mut at = 0;
        asm.faces
            .iter()
            .enumerate()
            .map(|(f, (_, face))| {
                let (k, kind) = match q {
                    None => (face.boundary.len(), CoordKind::Corners),
                    Some(degree) => (control_count(face, degree), CoordKind::Controls { degree }),
                };
                let fc = FaceCoords {
                    face: f,
                    kind,
                    points: points[at..at + k].to_vec(),
                    spans: spans[at..at + k].to_vec(),
                };
                at += k;
                fc
            })
            .collect()
    };
    let degree = (2..=MAX_DEGREE).find(|&q| {
        asm.faces
            .iter()
            .map(|(_, f)| control_count(f, q))
            .sum::<usize>()
            == count
    });
    out.faces = if count == corners {
        per_face(None)
    } else if let Some(q) = degree {
        per_face(Some(q))
    } else if count == v {
        ids.iter()
            .enumerate()
            .map(|(f, vs)| FaceCoords {
                face: f,
                kind: CoordKind::Corners,
                points: vs.iter().map(|&i| points[i].clone()).collect(),
                spans: vs.iter().map(|&i| spans[i].clone()).collect(),
            })
            .collect()
    } else {
        let k2: usize = asm.faces.iter().map(|(_, f)| control_count(f, 2)).sum();
        let k3: usize = asm.faces.iter().map(|(_, f)| control_count(f, 3)).sum();
        let mut accepted = vec![format!("{corners} (the corners, face after face)")];
        if k2 != corners {
            accepted.push(format!(
                "{k2} or {k3} (all control points at Bézier degree 2 or 3, face after face)"
            ));
        }
        if v != corners {
            accepted.push(format!("{v} (the distinct vertices)"));
        }
        return Err(Error::syntax(
            "E0304",
            format!(
                "the `p` section has {count} points; lacuna reads {}",
                accepted.join(", or ")
            ),
            p_span,
            Some(src),
        ));
    };
    Ok(out)
}

fn parse_edge(text: &str, line: &str, ln: usize, src: &Source) -> Result<EdgeType> {
    let col = col_in(line, text);
    let bad = |m: String| Error::at("E0301", m, ln, col, text.chars().count(), src);
    let parts: Vec<&str> = text.split('_').collect();
    let [k, n, d] = parts.as_slice() else {
        return Err(bad(format!(
            "`{text}` is not an AutoFrac2D edge (expected X_n_d, e.g. C_2_0)"
        )));
    };
    let kind = match *k {
        "B" => EdgeKind::B,
        "C" => EdgeKind::C,
        _ => return Err(bad(format!("`{text}`: edge kind must be B or C"))),
    };
    let n: u32 = crate::topology::edge::parse_count(n, col + 2, "sub-edge count")
        .map_err(|e| e.within(src, ln, 0))?;
    if n < 2 {
        return Err(Error::at(
            "E0104",
            format!("`{text}`: an edge needs at least 2 sub-edges"),
            ln,
            col,
            text.len(),
            src,
        ));
    }
    let d: u32 =
        crate::topology::edge::parse_count(d, col, "delay").map_err(|e| e.within(src, ln, 0))?;
    if d >= crate::topology::edge::HARD_CAP {
        return Err(bad(format!("`{text}`: delay too large")));
    }
    Ok(EdgeType {
        kind,
        n,
        delay: d + 1,
    })
}

fn parse_face(line: &str, t: &str, ln: usize, src: &Source) -> Result<Face> {
    let parts: Vec<&str> = t.split('/').collect();
    if parts.len() != 4 {
        return Err(Error::at(
            "E0301",
            format!(
                "a face has 4 parts separated by `/` (edges / E / delay / algorithm), found {}",
                parts.len()
            ),
            ln,
            col_in(line, t),
            t.len(),
            src,
        ));
    }
    let edges = |p: &str| -> Result<Vec<EdgeType>> {
        p.split('-')
            .map(|e| parse_edge(e.trim(), line, ln, src))
            .collect()
    };
    let boundary = edges(parts[0])?;
    let e = edges(parts[1])?;
    if e.len() != 3 {
        let p = parts[1].trim();
        return Err(Error::at(
            "E0107",
            format!("E needs exactly 3 edges, found {}", e.len()),
            ln,
            col_in(line, p),
            p.len(),
            src,
        ));
    }
    let dtext = parts[2].trim();
    let delay = crate::topology::edge::parse_count(dtext, col_in(line, dtext), "face delay")
        .map_err(|e| e.within(src, ln, 0))?;
    if delay >= crate::topology::edge::HARD_CAP {
        return Err(Error::at(
            "E0110",
            "face delay too large",
            ln,
            col_in(line, dtext),
            dtext.len(),
            src,
        ));
    }
    let atext = parts[3].trim();
    let any_delay = delay > 0 || boundary.iter().chain(&e).any(EdgeType::is_delayed);
    let algorithm = match atext {
        "0" => Algorithm::a3(),
        "2" => Algorithm::a2(),
        "1" if !any_delay => Algorithm::a1(),
        "1" => Algorithm::af1(),
        _ => {
            return Err(Error::at(
                "E0302",
                format!("unknown AutoFrac2D algorithm `{atext}` (0, 1 or 2)"),
                ln,
                col_in(line, atext),
                atext.len(),
                src,
            ));
        }
    };
    Ok(Face {
        boundary,
        params: Params {
            ea: e[0],
            el: e[1],
            ec: e[2],
        },
        algorithm,
        delay: delay + 1,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn src(t: &str) -> Source {
        Source {
            name: "af.txt".into(),
            text: t.into(),
        }
    }

    #[test]
    fn reads_the_readme_example() {
        let text = "f\nC_2_0 - B_2_0 - C_2_0 - B_2_0 / C_2_0 - B_2_0 - B_2_0 / 0 / 1\nC_2_0 - B_2_0 - C_2_0 - B_2_0 / C_2_0 - B_2_0 - B_2_0 / 0 / 1\nc\n0.3 / 1.1\np\n0 10\n-10 10\n";
        assert!(is_autofrac(text));
        let a = parse_autofrac(&src(text)).unwrap();
        assert_eq!(a.faces.len(), 2);
        assert_eq!(a.faces[0].1.to_string(), "C2 B2 C2 B2 | C2 B2 B2 | A1");
        // Two points fit no reading of the `p` section (8 corners, 12 or 16 control points, 6
        // vertices): the topology reads the file, the placement will refuse it.
        assert_eq!(a.coords.unread.as_ref().map(|d| d.code), Some("E0304"));
        assert!(a.coords.faces.is_empty());
        assert_eq!(
            a.shared,
            vec![SharedEdge {
                a: (0, 3),
                b: (1, 1)
            }]
        );
    }

    #[test]
    fn delays_are_shifted_by_one() {
        let a = parse_autofrac(&src("f\nC_2_2 - B_3_0 / C_2_0 - B_2_0 - B_2_0 / 1 / 0\n")).unwrap();
        assert_eq!(a.faces[0].1.to_string(), "C2^3 B3 | C2 B2 B2 | A3 | 2");
    }

    #[test]
    fn algorithm_1_with_delays_is_af1() {
        let a = parse_autofrac(&src("f\nC_2_0 - B_2_1 / C_2_0 - B_2_0 - B_2_0 / 0 / 1\n")).unwrap();
        assert_eq!(a.faces[0].1.to_string(), "C2 B2^2 | C2 B2 B2 | AF1");
        let a = parse_autofrac(&src("f\nC_2_0 - B_2_0 / C_2_0 - B_2_0 - B_2_0 / 1 / 1\n")).unwrap();
        assert_eq!(a.faces[0].1.to_string(), "C2 B2 | C2 B2 B2 | AF1 | 2");
    }

    #[test]
    fn errors_have_codes() {
        let cases = [
            ("f\nC_2_0 - B_2_0 / C_2_0 - B_2_0 / 0 / 1\n", "E0107"),
            (
                "f\nC_2_0 - B_2_0 / C_2_0 - B_2_0 - B_2_0 / 0 / 7\n",
                "E0302",
            ),
            (
                "f\nC_2_0 - X_2_0 / C_2_0 - B_2_0 - B_2_0 / 0 / 1\n",
                "E0301",
            ),
            (
                "f\nC_1_0 - B_2_0 / C_2_0 - B_2_0 - B_2_0 / 0 / 1\n",
                "E0104",
            ),
            (
                "f\nC_2_0 - B_2_0 / C_2_0 - B_2_0 - B_2_0 / 0 / 1\nc\n0.0 / 3.1\n",
                "E0203",
            ),
            (
                "f\nC_2_0 - B_2_0 / C_2_0 - B_2_0 - B_2_0 / 0 / 1\np\nNaN 1\n",
                "E0303",
            ),
            (
                "f\nC_2_0 - B_2_0 / C_2_0 - B_2_0 - B_2_0 / 0 / 1\np\n1e999 1\n",
                "E0303",
            ),
            ("f\nc\n", "E0207"),
        ];
        for (text, code) in cases {
            assert_eq!(
                parse_autofrac(&src(text)).unwrap_err().code(),
                code,
                "{text}"
            );
        }
    }
}
