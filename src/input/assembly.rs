//! Assemblies: several faces with shared edges, in lacuna's plain-text format.
//!
//! ```text
//! # comment
//! rule R = {joint gap corner(C,B)}
//! face 0: C2 B2 C2 B2 | C2 B2 B2 | A1
//! face 1: C2 B2 C2 B2 | C2 B2 B2 | R
//! face 0 edge 2 ~ face 1 edge 0
//! corners 0: 0 0, 1 0, 1 1, 0 1
//! ```
//! A shared edge must have the same type and delay on both sides; the two faces traverse it in
//! opposite directions (both boundaries are counter-clockwise). Edge indices refer to the
//! boundary as written.

use crate::error::{Error, Result, Source, Span};
use crate::input::coords::{
    double_area, interpret, offsets, parse_point_list, self_intersection, show, CoordKind,
    ExactPoint, FaceCoords, UserCoords,
};
use crate::topology::face::Face;
use crate::topology::rule::Algorithm;
use crate::topology::Glue;
use num_traits::{Signed, Zero};
use serde::Serialize;

/// Two face edges glued together.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct SharedEdge {
    /// (face index, edge index) of one side.
    pub a: (usize, usize),
    /// (face index, edge index) of the other side.
    pub b: (usize, usize),
}

/// A structure of faces with shared edges.
#[derive(Clone, Debug)]
pub struct Assembly {
    /// The faces with their names (`0`, `1`, … in files), in order of appearance.
    pub faces: Vec<(String, Face)>,
    /// The shared edges.
    pub shared: Vec<SharedEdge>,
    /// User-given coordinates (`corners NAME: …`, `points NAME: …`, AutoFrac2D's `p` section).
    pub coords: UserCoords,
}

/// A coordinates line as written: face name, its column, the points, whether corners only, and
/// the span of the point list.
type CoordLine = (String, Span, Vec<ExactPoint>, Vec<Span>, bool, Span);

/// A reference `face NAME edge I` as written: (name, edge, column).
type EdgeRef = (String, usize, usize);

impl Assembly {
    /// The shared edges, with edge indices in the canonical order of each
    /// start face (the order of [`crate::topology::FaceType::face`] and of the boundary flags).
    pub fn canonical_glue(&self) -> Vec<Glue> {
        let asm = self;
        let canon = |(f, e): (usize, usize)| {
            let face = &asm.faces[f].1;
            let (_, r) = face.canonical();
            let n = face.boundary.len();
            (f, (e + n - r % n) % n)
        };
        asm.shared
            .iter()
            .map(|s| [canon(s.a), canon(s.b)])
            .collect()
    }

    /// Parses lacuna's assembly format.
    pub fn parse(src: &Source) -> Result<Assembly> {
        let mut rules: Vec<(String, Algorithm)> = Vec::new();
        let mut faces: Vec<(String, Face)> = Vec::new();
        let mut links: Vec<(usize, [EdgeRef; 2])> = Vec::new();
        let mut coord_lines: Vec<CoordLine> = Vec::new();
        for (ln0, raw) in src.text.lines().enumerate() {
            let ln = ln0 + 1;
            let line = raw.split('#').next().unwrap_or("");
            let trimmed = line.trim();
            if trimmed.is_empty() {
                continue;
            }
            let lead = line.len() - line.trim_start().len();
            let col0 = line[..lead].chars().count() + 1;
            if let Some(rest) = trimmed.strip_prefix("rule ") {
                let Some((name, def)) = rest.split_once('=') else {
                    return Err(Error::at(
                        "E0201",
                        "expected `rule NAME = {…}`",
                        ln,
                        col0,
                        trimmed.len(),
                        src,
                    ));
                };
                let name = name.trim().to_string();
                let valid = !name.is_empty()
                    && name
                        .chars()
                        .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
                if !valid || ["A1", "A2", "A3"].contains(&name.as_str()) {
                    return Err(Error::at(
                        "E0201",
                        format!("invalid rule name `{name}`"),
                        ln,
                        col0 + 5,
                        name.len(),
                        src,
                    ));
                }
                let def_off = trimmed.len() - def.trim_start().len();
                let alg = Algorithm::parse(def.trim(), col0 + def_off, &rules)
                    .map_err(|e| e.within(src, ln, 0))?;
                rules.push((name, alg));
            } else if trimmed.starts_with("face ") && trimmed.contains(':') {
                let (head, notation) = trimmed.split_once(':').expect("checked");
                let name = head["face ".len()..].trim().to_string();
                if name.is_empty() || !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
                    return Err(Error::at(
                        "E0201",
                        format!("invalid face name `{name}`"),
                        ln,
                        col0 + 5,
                        name.len(),
                        src,
                    ));
                }
                if faces.iter().any(|(n, _)| *n == name) {
                    return Err(Error::at(
                        "E0202",
                        format!("face `{name}` is defined twice"),
                        ln,
                        col0 + 5,
                        name.len(),
                        src,
                    ));
                }
                let off = head.chars().count() + 1;
                let face = Face::parse_with(notation, &rules)
                    .map_err(|e| e.within(src, ln, col0 - 1 + off))?;
                faces.push((name, face));
            } else if (trimmed.starts_with("corners ") || trimmed.starts_with("points "))
                && trimmed.contains(':')
            {
                let (head, list) = trimmed.split_once(':').expect("checked");
                let corners_only = head.starts_with("corners");
                let kw = if corners_only { "corners " } else { "points " };
                let name = head[kw.len()..].trim().to_string();
                let name_col =
                    col0 + kw.len() + head[kw.len()..].len() - head[kw.len()..].trim_start().len();
                let list_col = col0 + head.chars().count() + 1;
                let (points, spans) = parse_point_list(list, ln, list_col, src)?;
                let lead = list.len() - list.trim_start().len();
                let whole = Span {
                    line: ln,
                    col: list_col + list[..lead].chars().count(),
                    len: list.trim().chars().count().max(1),
                };
                let name_span = Span {
                    line: ln,
                    col: name_col,
                    len: name.chars().count().max(1),
                };
                coord_lines.push((name, name_span, points, spans, corners_only, whole));
            } else if trimmed.contains('~') {
                let (l, r) = trimmed.split_once('~').expect("checked");
                let rcol = col0 + l.chars().count() + 1;
                let a = parse_ref(l, ln, col0, src)?;
                let b = parse_ref(r, ln, rcol, src)?;
                links.push((ln, [a, b]));
            } else {
                return Err(Error::at(
                    "E0201",
                    format!("expected `face NAME: …`, `rule NAME = …`, `face A edge I ~ face B edge J`, `corners NAME: x y, …` or `points NAME: x y, …`, found `{trimmed}`"),
                    ln,
                    col0,
                    trimmed.chars().count(),
                    src,
                ));
            }
        }
        let mut shared = Vec::new();
        for (ln, [a, b]) in links {
            let resolve = |(name, edge, col): &EdgeRef| -> Result<(usize, usize)> {
                let Some(f) = faces.iter().position(|(n, _)| n == name) else {
                    return Err(Error::at(
                        "E0203",
                        format!("no face named `{name}`"),
                        ln,
                        *col,
                        name.len() + 5,
                        src,
                    ));
                };
                Ok((f, *edge))
            };
            let ra = resolve(&a)?;
            let rb = resolve(&b)?;
            shared.push((ln, a.2, SharedEdge { a: ra, b: rb }));
        }
        if faces.is_empty() {
            return Err(Error::at(
                "E0207",
                "no face defined (expected `face 0: EDGES | Ea El Ec | A`)",
                1,
                1,
                1,
                src,
            ));
        }
        let mut coords = UserCoords {
            faces: Vec::new(),
            source: Some(src.clone()),
            unread: None,
        };
        for (name, name_span, points, spans, corners_only, whole) in coord_lines {
            let Some(f) = faces.iter().position(|(n, _)| *n == name) else {
                return Err(Error::syntax(
                    "E0203",
                    format!("no face named `{name}`"),
                    name_span,
                    Some(src),
                ));
            };
            if coords.of(f).is_some() {
                return Err(Error::syntax(
                    "E0213",
                    format!("coordinates of face `{name}` are given twice"),
                    name_span,
                    Some(src),
                ));
            }
            coords.faces.push(interpret(
                f,
                &faces[f],
                (points, spans),
                corners_only,
                &whole,
                Some(src),
            )?);
        }
        coords.faces.sort_by_key(|c| c.face);
        let asm = Assembly {
            faces,
            shared: shared.iter().map(|s| s.2).collect(),
            coords,
        };
        let lines: Vec<(usize, usize)> = shared.iter().map(|s| (s.0, s.1)).collect();
        asm.check(src, &lines)?;
        check(&asm)?;
        Ok(asm)
    }

    /// Checks the shared edges: indices in range, each face edge glued at most once, never to
    /// itself, and the same edge type and delay on both sides. `lines` gives the (line, column)
    /// of each shared edge in `src`, for errors.
    pub fn check(&self, src: &Source, lines: &[(usize, usize)]) -> Result<()> {
        let mut used: std::collections::HashMap<(usize, usize), usize> = Default::default();
        for (k, s) in self.shared.iter().enumerate() {
            let (ln, col) = lines.get(k).copied().unwrap_or((1, 1));
            let len = src
                .text
                .lines()
                .nth(ln - 1)
                .map_or(1, |l| l.trim_end().chars().count() + 1 - col);
            if s.a == s.b {
                return Err(Error::at(
                    "E0208",
                    "an edge cannot be shared with itself",
                    ln,
                    col,
                    len,
                    src,
                ));
            }
            for &(f, e) in [&s.a, &s.b] {
                let (name, face) = &self.faces[f];
                if e >= face.boundary.len() {
                    return Err(Error::at(
                        "E0204",
                        format!(
                            "face `{name}` has {} edges; edge {e} does not exist",
                            face.boundary.len()
                        ),
                        ln,
                        col,
                        len,
                        src,
                    ));
                }
                if let Some(prev) = used.insert((f, e), ln) {
                    return Err(Error::at(
                        "E0206",
                        format!("edge {e} of face `{name}` is already shared (line {prev})"),
                        ln,
                        col,
                        len,
                        src,
                    ));
                }
            }
            let ta = self.faces[s.a.0].1.boundary[s.a.1];
            let tb = self.faces[s.b.0].1.boundary[s.b.1];
            if ta != tb {
                return Err(Error::at(
                    "E0205",
                    format!(
                        "shared edge has type {ta} on face `{}` but {tb} on face `{}`: both sides must have the same type and delay",
                        self.faces[s.a.0].0, self.faces[s.b.0].0
                    ),
                    ln,
                    col,
                    len,
                    src,
                ));
            }
        }
        Ok(())
    }

    /// The faces alone, in order.
    pub fn face_list(&self) -> Vec<Face> {
        self.faces.iter().map(|(_, f)| f.clone()).collect()
    }
}

/// Parses `face NAME edge I`; returns (name, edge, column).
fn parse_ref(text: &str, ln: usize, col: usize, src: &Source) -> Result<EdgeRef> {
    let lead = text.len() - text.trim_start().len();
    let c = col + text[..lead].chars().count();
    let words: Vec<&str> = text.split_whitespace().collect();
    match words.as_slice() {
        ["face", name, "edge", idx] => match idx.parse::<usize>() {
            Ok(i) => Ok((name.to_string(), i, c)),
            Err(_) => Err(Error::at(
                "E0201",
                format!("`{idx}` is not an edge index"),
                ln,
                c,
                text.trim().len(),
                src,
            )),
        },
        _ => Err(Error::at(
            "E0201",
            format!("expected `face NAME edge INDEX`, found `{}`", text.trim()),
            ln,
            c,
            text.trim().chars().count(),
            src,
        )),
    }
}

/// The vertices of an assembly: for each face, the vertex of each corner (corner i starts edge
/// i), where a shared edge identifies its end corners with the other side's (reversed). Vertices
/// are numbered in order of first appearance, face after face, corner after corner; returns the
/// numbering and the number of vertices.
pub fn vertices(asm: &Assembly) -> (Vec<Vec<usize>>, usize) {
    let base: Vec<usize> = asm
        .faces
        .iter()
        .scan(0, |acc, (_, f)| {
            let b = *acc;
            *acc += f.boundary.len();
            Some(b)
        })
        .collect();
    let total: usize = asm.faces.iter().map(|(_, f)| f.boundary.len()).sum();
    let mut parent: Vec<usize> = (0..total).collect();
    fn find(p: &mut [usize], mut x: usize) -> usize {
        while p[x] != x {
            p[x] = p[p[x]];
            x = p[x];
        }
        x
    }
    let corner = |f: usize, i: usize| {
        let n = asm.faces[f].1.boundary.len();
        base[f] + i % n
    };
    for s in &asm.shared {
        let pairs = [
            (corner(s.a.0, s.a.1), corner(s.b.0, s.b.1 + 1)),
            (corner(s.a.0, s.a.1 + 1), corner(s.b.0, s.b.1)),
        ];
        for (x, y) in pairs {
            let (rx, ry) = (find(&mut parent, x), find(&mut parent, y));
            if rx != ry {
                parent[rx.max(ry)] = rx.min(ry);
            }
        }
    }
    let mut id = vec![usize::MAX; total];
    let mut count = 0;
    let ids = asm
        .faces
        .iter()
        .enumerate()
        .map(|(f, (_, face))| {
            (0..face.boundary.len())
                .map(|i| {
                    let r = find(&mut parent, base[f] + i);
                    if id[r] == usize::MAX {
                        id[r] = count;
                        count += 1;
                    }
                    id[r]
                })
                .collect()
        })
        .collect();
    (ids, count)
}

/// Checks the user coordinates of an assembly: the faces given with all their control points use
/// one degree (E0214); every face is counter-clockwise with positive area and its corner polygon
/// does not cross itself (E0212); both sides of a shared edge have the same corners and, when both
/// give them, the same inner control points, exactly (E0211).
pub fn check(asm: &Assembly) -> Result<()> {
    let uc = &asm.coords;
    let mut degree: Option<(usize, &FaceCoords)> = None;
    for fc in &uc.faces {
        let (name, face) = &asm.faces[fc.face];
        if let CoordKind::Controls { degree: d } = fc.kind {
            match degree {
                Some((d0, first)) if d0 != d => {
                    return Err(uc.error(
                        "E0214",
                        format!(
                            "face `{name}` gives control points of Bézier degree {d}, but face `{}` of degree {d0}: one degree for all faces",
                            asm.faces[first.face].0
                        ),
                        &fc.spans[0],
                    ));
                }
                Some(_) => {}
                None => degree = Some((d, fc)),
            }
        }
        let corners = fc.corners(face);
        if let Some((i, j)) = self_intersection(&corners) {
            return Err(uc.error(
                "E0212",
                format!(
                    "face `{name}` is not a simple polygon: edges {i} and {j} of its corners meet"
                ),
                fc.corner_span(face, j),
            ));
        }
        // The polygon whose area is tested: all control points (a curved digon has area), else
        // the corners.
        let area = double_area(&fc.points);
        if !area.is_positive() {
            let what = if area.is_zero() {
                "has zero area"
            } else {
                "is clockwise (faces are counter-clockwise)"
            };
            return Err(uc.error(
                "E0212",
                format!("face `{name}` {what}: its points must go counter-clockwise around a region of positive area"),
                &fc.spans[0],
            ));
        }
    }
    for s in &asm.shared {
        let (Some(ca), Some(cb)) = (uc.of(s.a.0), uc.of(s.b.0)) else {
            continue;
        };
        let (fa, fb) = (&asm.faces[s.a.0], &asm.faces[s.b.0]);
        let (na, nb) = (fa.1.boundary.len(), fb.1.boundary.len());
        let (ka, kb) = (fa.1.clone(), fb.1.clone());
        let (pa, pb) = (ca.corners(&ka), cb.corners(&kb));
        let what = format!(
            "the shared edge `face {} edge {} ~ face {} edge {}`",
            fa.0, s.a.1, fb.0, s.b.1
        );
        // Edge a runs from corner a.1 to a.1 + 1; edge b the other way.
        for (ia, ib) in [(s.a.1, (s.b.1 + 1) % nb), ((s.a.1 + 1) % na, s.b.1)] {
            if pa[ia] != pb[ib] {
                return Err(uc.error(
                    "E0211",
                    format!(
                        "{what} does not match: corner {ib} of face `{}` is {}, but corner {ia} of face `{}` is {}",
                        fb.0,
                        show(&pb[ib]),
                        fa.0,
                        show(&pa[ia])
                    ),
                    cb.corner_span(&kb, ib),
                ));
            }
        }
        if let (Some(ea), Some(eb)) = (ca.edge_controls(&ka, s.a.1), cb.edge_controls(&kb, s.b.1)) {
            let m = ea.len();
            for c in 1..m.saturating_sub(1) {
                if ea[c] != eb[m - 1 - c] {
                    let off = offsets(&kb, m - 1)[s.b.1] + m - 1 - c;
                    return Err(uc.error(
                        "E0211",
                        format!(
                            "{what} does not match: inner control point {} of edge {} of face `{}` is {}, but {} on face `{}`",
                            m - 1 - c,
                            s.b.1,
                            fb.0,
                            show(&eb[m - 1 - c]),
                            show(&ea[c]),
                            fa.0
                        ),
                        &cb.spans[off],
                    ));
                }
            }
        }
    }
    Ok(())
}

/// Gives corners to the only face of an assembly (`--corners "x y, x y, …"` on the command line).
pub fn set_corners(asm: &mut Assembly, text: &str) -> Result<()> {
    let src = Source::command_line(text);
    if asm.faces.len() != 1 {
        return Err(Error::at(
            "E0215",
            format!(
                "--corners gives the corners of a single face, but the input has {} faces: write `corners NAME: …` lines in the assembly file",
                asm.faces.len()
            ),
            1,
            1,
            text.chars().count(),
            &src,
        ));
    }
    let parsed = parse_point_list(text, 1, 1, &src)?;
    let whole = Span {
        line: 1,
        col: 1,
        len: text.chars().count().max(1),
    };
    let fc = interpret(0, &asm.faces[0], parsed, true, &whole, Some(&src))?;
    asm.coords = UserCoords {
        faces: vec![fc],
        source: Some(src),
        unread: None,
    };
    check(asm)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::input::coords::control_count;

    #[test]
    fn vertices_merge_the_corners_of_shared_edges() {
        let src = Source {
            name: "t".into(),
            text: "face 0: B2 B2 B2 | C2 B2 B2 | A1\nface 1: B2 B2 B2 B2 | C2 B2 B2 | A1\nface 0 edge 2 ~ face 1 edge 0\n".into(),
        };
        let a = Assembly::parse(&src).unwrap();
        // Face 0 edge 2 runs corner 2 → corner 0; face 1 edge 0 runs corner 0 → corner 1, so face
        // 1's corner 0 is face 0's corner 0 and its corner 1 is face 0's corner 2.
        let (ids, v) = vertices(&a);
        assert_eq!(ids, vec![vec![0, 1, 2], vec![0, 2, 3, 4]]);
        assert_eq!(v, 5);
        assert_eq!(control_count(&a.faces[1].1, 3), 12);
    }

    fn src(t: &str) -> Source {
        Source {
            name: "test.txt".into(),
            text: t.into(),
        }
    }

    #[test]
    fn parses_rules_faces_and_links() {
        let a = Assembly::parse(&src(
            "# two quads\nrule R = {joint gap corner(C,B)}\nface 0: C2 B2 C2 B2 | C2 B2 B2 | A1\nface 1: C2 B2 C2 B2 | C2 B2 B2 | R\nface 0 edge 1 ~ face 1 edge 3\n",
        ))
        .unwrap();
        assert_eq!(a.faces.len(), 2);
        assert_eq!(
            a.faces[1].1.algorithm.to_string(),
            "{joint gap corner(C,B)}"
        );
        assert_eq!(
            a.shared,
            vec![SharedEdge {
                a: (0, 1),
                b: (1, 3)
            }]
        );
    }

    #[test]
    fn bad_assemblies_have_codes_and_lines() {
        let cases = [
            ("face 0: C2 B2 | C2 B2 B2 | A1\nface 0: B2 B2 | C2 B2 B2 | A1", "E0202", 2),
            ("face 0: C2 B2 | C2 B2 B2 | A1\nface 0 edge 0 ~ face 9 edge 0", "E0203", 2),
            ("face 0: C2 B2 | C2 B2 B2 | A1\nface 1: C2 B2 | C2 B2 B2 | A1\nface 0 edge 5 ~ face 1 edge 0", "E0204", 3),
            ("face 0: C2 B2 | C2 B2 B2 | A1\nface 1: C2 B2 | C2 B2 B2 | A1\nface 0 edge 0 ~ face 1 edge 1", "E0205", 3),
            (
                "face 0: C2 B2 | C2 B2 B2 | A1\nface 1: C2 B2 | C2 B2 B2 | A1\nface 0 edge 0 ~ face 1 edge 0\nface 0 edge 0 ~ face 1 edge 0",
                "E0206",
                4,
            ),
            ("face 0: C2 B2 | C2 B2 B2 | A1\nface 0 edge 0 ~ face 0 edge 0", "E0208", 2),
            ("# nothing\n", "E0207", 1),
            ("face 0: C2 Q2 | C2 B2 B2 | A1", "E0103", 1),
            ("hello", "E0201", 1),
        ];
        for (text, code, line) in cases {
            let e = Assembly::parse(&src(text)).unwrap_err();
            assert_eq!(
                (e.code(), e.span().map(|s| s.line)),
                (code, Some(line)),
                "{text}"
            );
        }
        // The column of an error inside a face line is the column in the file.
        let e = Assembly::parse(&src("face 0: C2 Q2 | C2 B2 B2 | A1")).unwrap_err();
        assert_eq!(e.span().unwrap().col, 12);
    }
}

#[cfg(test)]
mod component_tests {
    //! The exact components (`crate::topology::component`) of assemblies read from files.
    use crate::input::load_input;
    use crate::topology::component::start_components;
    use crate::topology::{
        close_or_error, components_by_cells, components_by_induction, Glue, Limits, TypeSet,
    };

    fn setup(name: &str) -> (TypeSet, Vec<Glue>) {
        let input = load_input(name).unwrap();
        let ts = close_or_error(&input.faces(), &Limits::default()).unwrap();
        (ts, input.assembly.canonical_glue())
    }

    #[test]
    fn two_quads_form_one_component_and_two_apart_form_two() {
        let (ts, glue) = setup("two-quads");
        assert_eq!(glue.len(), 1);
        assert_eq!(start_components(2, &glue), 1);
        assert_eq!(start_components(2, &[]), 2);
        assert_eq!(components_by_induction(&ts, &glue), Ok(1));
        assert_eq!(
            components_by_cells(&ts, &glue, 3, 1_000_000),
            Some(Ok(vec![1; 4]))
        );
        // Without the glue the two quads and all their descendants stay apart.
        assert_eq!(
            components_by_cells(&ts, &[], 3, 1_000_000),
            Some(Ok(vec![2; 4]))
        );
    }

    #[test]
    fn cell_limit_turns_the_union_find_off() {
        let (ts, glue) = setup("F0");
        // 6^3 = 216 cells at level 3.
        assert!(components_by_cells(&ts, &glue, 3, 215).is_none());
        assert!(components_by_cells(&ts, &glue, 3, 216).is_some());
    }
}
