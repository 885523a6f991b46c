//! Volume inputs: the one-line volume notation on the command line (`cube B2 | B2 B2 B2 | A1 |
//! B2 B2 | V1`), or a volume file (or library entry) whose first line that is not a comment
//! starts with `volume`:
//!
//! ```text
//! # a cube given by its faces, and a cube shorthand glued to it face to face
//! rule R = {joint}
//! volume A {
//!   inside: B2 B2 | B2 B2 B2 | R | V1
//!   face 0: B2 B2 B2 B2 | B2 B2 B2 | R
//!   …
//!   face 0 edge 0 ~ face 2 edge 3
//! }
//! volume B = cube B2 | B2 B2 B2 | R | B2 B2 | V1
//! volume A face 1 edge 0 ~ volume B face 0 edge 0
//! ```
//!
//! A block gives a volume by its faces (face notation), the gluing of their edges (`~`: the two
//! edges run in opposite directions, each face read counter-clockwise from outside) and the
//! `inside:` line `Er Ei | Ea El Ec | A | RULE [| d]` (G, then E and A of the faces created
//! inside, the rule and the delay). `volume NAME = NOTATION` names a shorthand, whose faces are
//! numbered as [`Solid::polygons`] lists them; a file of one volume may also be the single line
//! `volume NOTATION`. `volume A face F edge I ~ volume B face G edge J` glues face F of A to
//! face G of B, edge I lying on edge J. Errors carry the line and column.
//!
//! The parts: this file reads the text (the lines of a file, blocks, shorthands, gluings between
//! volumes and the shared faces they declare); `block.rs` builds the volume of one block and
//! checks it (every edge glued once, the surface connected and a sphere, its corner coordinates).

mod block;

use crate::error::{Error, Result, Source};
use crate::topology::edge::EdgeType;
use crate::topology::face::Face;
use crate::topology::limits::Limits;
use crate::topology::rule::Algorithm;
use crate::topology::volume::{
    mirror_consistent, parse_volume, SharedFace, Solid, Volume, VolumeAssembly, VolumeRule,
};
use block::finish;

/// Whether a command-line argument is volume notation: it has `|` and starts with a solid name.
pub fn is_volume_notation(arg: &str) -> bool {
    arg.contains('|')
        && arg
            .split_whitespace()
            .next()
            .is_some_and(|w| Solid::parse(w).is_some())
}

/// Whether a file's text declares a volume.
pub fn is_volume_text(text: &str) -> bool {
    text.trim_start_matches('\u{feff}')
        .lines()
        .map(str::trim)
        .find(|l| !l.is_empty() && !l.starts_with('#'))
        .is_some_and(|l| l.starts_with("volume ") || l == "volume")
}

/// A volume file: the volumes with their names, glued face to face.
#[derive(Clone, Debug)]
pub struct VolumeFile {
    /// The volume names, aligned with `assembly.volumes` (empty for `volume NOTATION`).
    pub names: Vec<String>,
    /// The volumes and their shared faces.
    pub assembly: VolumeAssembly,
    /// User coordinates, aligned with `assembly.volumes`: `corners[v][f][i]` is where corner `i`
    /// (the start of edge `i`) of face `f` lies; `None` for a volume given no coordinates.
    pub corners: Vec<Option<Corners>>,
}

/// The coordinates of a volume's surface: `[f][i]` for corner `i` of face `f`.
pub type Corners = Vec<Vec<[f64; 3]>>;

/// Parses a volume file of exactly one volume.
pub fn parse_volume_text(src: &Source) -> Result<Volume> {
    let file = parse_volume_file(src)?;
    match file.assembly.volumes.len() {
        1 => Ok(file.assembly.volumes[0].clone()),
        n => Err(Error::Usage(format!(
            "{}: {n} volumes glued face to face; this command reads one volume (`closure`, `counts`, `ratio` and `verify` read assemblies)",
            src.name
        ))),
    }
}

/// A line being read: number, leading column, trimmed text.
struct Line<'a> {
    ln: usize,
    col: usize,
    text: &'a str,
}

fn valid_name(name: &str) -> bool {
    !name.is_empty()
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
}

/// Column (1-based) of `part`, a sub-slice of `line.text`.
fn col_of(line: &Line, part: &str) -> usize {
    let off = part.as_ptr() as usize - line.text.as_ptr() as usize;
    line.col + line.text[..off].chars().count()
}

fn at(code: &'static str, m: impl Into<String>, line: &Line, part: &str, src: &Source) -> Error {
    Error::at(
        code,
        m,
        line.ln,
        col_of(line, part),
        part.chars().count().max(1),
        src,
    )
}

/// A volume block being read.
struct Block {
    name: String,
    ln: usize,
    col: usize,
    inside: Option<(EdgeType, EdgeType, Face, VolumeRule, u32)>,
    faces: Vec<(String, Face, usize, usize)>,
    links: Vec<Gluing>,
    /// `corners FACE: …` lines: (face, coordinates with the column of each, line).
    corners: Vec<(usize, Vec<Located>, usize)>,
}

/// A point of a `corners` line with the column where it is written and its width.
type Located = ([f64; 3], usize, usize);

/// A gluing inside a block: its line, column and the two (face, edge) sides.
type Gluing = (usize, usize, [(usize, usize); 2]);

/// Parses `face NAME edge I` in `part` (of `line`); names are looked up in `faces`.
fn face_edge(part: &str, line: &Line, faces: &[String], src: &Source) -> Result<(usize, usize)> {
    let words: Vec<&str> = part.split_whitespace().collect();
    let ["face", name, "edge", idx] = words.as_slice() else {
        return Err(at(
            "E1220",
            format!("expected `face NAME edge INDEX`, found `{}`", part.trim()),
            line,
            part.trim(),
            src,
        ));
    };
    let Some(f) = faces.iter().position(|n| n == name) else {
        return Err(at(
            "E1222",
            format!("no face named `{name}`"),
            line,
            name,
            src,
        ));
    };
    let Ok(i) = idx.parse::<usize>() else {
        return Err(at(
            "E1220",
            format!("`{idx}` is not an edge index"),
            line,
            idx,
            src,
        ));
    };
    Ok((f, i))
}

/// Parses the `inside:` line: `Er Ei | Ea El Ec | A | RULE [| d]`.
fn inside(
    rest: &str,
    line: &Line,
    rules: &[(String, Algorithm)],
    src: &Source,
) -> Result<(EdgeType, EdgeType, Face, VolumeRule, u32)> {
    let fields: Vec<&str> = rest.split('|').collect();
    let bad = |m: String, part: &str| at("E1232", m, line, part, src);
    if !(4..=5).contains(&fields.len()) {
        return Err(bad(
            "the inside line is `inside: Er Ei | Ea El Ec | A | RULE [| d]`".into(),
            rest.trim(),
        ));
    }
    let g: Vec<&str> = fields[0].split_whitespace().collect();
    let edge = |w: &str| EdgeType::parse(w, col_of(line, w)).map_err(|e| e.within(src, line.ln, 0));
    let [er, ei] = g.as_slice() else {
        return Err(bad(
            "G is two edge types: radial Er and inner Ei (`B2 B2`)".into(),
            fields[0].trim(),
        ));
    };
    let (er, ei) = (edge(er)?, edge(ei)?);
    let template = Face::parse_with(&format!("B2 B2 B2 | {} | {}", fields[1], fields[2]), rules)
        .map_err(|_| {
            bad(
                format!(
                    "`{} | {}`: expected the face parameters Ea El Ec and an algorithm (`B2 B2 B2 | A1`)",
                    fields[1].trim(),
                    fields[2].trim()
                ),
                fields[1].trim(),
            )
        })?;
    let rule = match fields[3].trim() {
        "V1" => VolumeRule::V1,
        "V2" => VolumeRule::V2,
        r => {
            return Err(bad(
                format!("unknown volume rule `{r}`: V1 or V2"),
                fields[3].trim(),
            ))
        }
    };
    let delay = match fields.get(4).map(|d| d.trim()) {
        None => 1,
        Some(d) => match d.parse::<u32>() {
            Ok(d) if (1..=64).contains(&d) => d,
            _ => {
                return Err(bad(
                    format!("the volume delay `{d}` must be an integer from 1 to 64"),
                    d,
                ))
            }
        },
    };
    Ok((er, ei, template, rule, delay))
}

/// Parses `X Y Z, X Y Z, …`: exactly `n` points of three finite numbers.
fn coordinates(
    list: &str,
    n: usize,
    what: &str,
    line: &Line,
    src: &Source,
) -> Result<Vec<Located>> {
    let list_t = list.trim();
    let items: Vec<&str> = list_t.split(',').collect();
    if items.len() != n {
        return Err(at(
            "E1214",
            format!(
                "{what} has {n} corners; {} given (`X Y Z`, separated by commas)",
                crate::error::counted(items.len(), "point", "points")
            ),
            line,
            list_t,
            src,
        ));
    }
    let mut out = Vec::with_capacity(n);
    for item in items {
        let words: Vec<&str> = item.split_whitespace().collect();
        let nums: Vec<f64> = words
            .iter()
            .filter_map(|w| w.parse::<f64>().ok().filter(|x| x.is_finite()))
            .collect();
        if words.len() != 3 || nums.len() != 3 {
            let part = if item.trim().is_empty() {
                list_t
            } else {
                item.trim()
            };
            return Err(at(
                "E1214",
                format!(
                    "`{}` is not a point `X Y Z` of three finite numbers",
                    item.trim()
                ),
                line,
                part,
                src,
            ));
        }
        let item = item.trim();
        out.push((
            [nums[0], nums[1], nums[2]],
            col_of(line, item),
            item.chars().count(),
        ));
    }
    Ok(out)
}

/// Parses a volume file (see the module documentation).
pub fn parse_volume_file(src: &Source) -> Result<VolumeFile> {
    let mut rules: Vec<(String, Algorithm)> = Vec::new();
    let mut names: Vec<String> = Vec::new();
    let mut volumes: Vec<Volume> = Vec::new();
    let mut corners: Vec<Option<Corners>> = Vec::new();
    // The solid of every volume given as a shorthand.
    let mut solids: Vec<Option<Solid>> = Vec::new();
    // The face names of every volume (a shorthand's faces are `0`, `1`, …).
    let mut face_names: Vec<Vec<String>> = Vec::new();
    let mut unnamed = false;
    let mut block: Option<Block> = None;
    // (line, column, side a, side b) of each gluing between volumes.
    let mut links: Vec<(usize, usize, SharedFace)> = Vec::new();
    for (ln0, raw) in src.text.lines().enumerate() {
        let raw = raw.trim_start_matches('\u{feff}');
        let code = raw.split('#').next().unwrap_or("");
        let text = code.trim();
        if text.is_empty() {
            continue;
        }
        let lead = code.len() - code.trim_start().len();
        let line = Line {
            ln: ln0 + 1,
            col: code[..lead].chars().count() + 1,
            text,
        };
        if let Some(b) = block.as_mut() {
            if text == "}" {
                let b = block.take().expect("inside a block");
                face_names.push(b.faces.iter().map(|f| f.0.clone()).collect());
                let (v, c) = finish(b, src)?;
                volumes.push(v);
                corners.push(c);
                solids.push(None);
                continue;
            }
            if let Some(rest) = text.strip_prefix("inside:") {
                if b.inside.is_some() {
                    return Err(at("E1220", "a second `inside:` line", &line, text, src));
                }
                b.inside = Some(inside(rest, &line, &rules, src)?);
            } else if let Some(rest) = text.strip_prefix("corners ") {
                let Some((name, list)) = rest.split_once(':') else {
                    return Err(at(
                        "E1214",
                        "expected `corners FACE: X Y Z, X Y Z, …`",
                        &line,
                        text,
                        src,
                    ));
                };
                let name = name.trim();
                let Some(f) = b.faces.iter().position(|x| x.0 == name) else {
                    return Err(at(
                        "E1222",
                        format!("no face named `{name}` above (give a face before its corners)"),
                        &line,
                        name,
                        src,
                    ));
                };
                if b.corners.iter().any(|c| c.0 == f) {
                    return Err(at(
                        "E1221",
                        format!("the corners of face `{name}` are given twice"),
                        &line,
                        name,
                        src,
                    ));
                }
                let n = b.faces[f].1.boundary.len();
                let pts = coordinates(list, n, &format!("face `{name}`"), &line, src)?;
                b.corners.push((f, pts, line.ln));
            } else if text.starts_with("face ") && text.contains('~') {
                let (l, r) = text.split_once('~').expect("checked");
                let names: Vec<String> = b.faces.iter().map(|f| f.0.clone()).collect();
                let x = face_edge(l, &line, &names, src)?;
                let y = face_edge(r, &line, &names, src)?;
                b.links.push((line.ln, line.col, [x, y]));
            } else if text.starts_with("face ") && text.contains(':') {
                let (head, notation) = text.split_once(':').expect("checked");
                let name = head["face ".len()..].trim();
                if !valid_name(name) {
                    return Err(at(
                        "E1220",
                        format!("invalid face name `{name}`"),
                        &line,
                        head,
                        src,
                    ));
                }
                if b.faces.iter().any(|f| f.0 == name) {
                    return Err(at(
                        "E1221",
                        format!("face `{name}` is defined twice in volume `{}`", b.name),
                        &line,
                        name,
                        src,
                    ));
                }
                let offset = col_of(&line, notation) - 1;
                let face = Face::parse_with(notation, &rules)
                    .map_err(|e| e.within(src, line.ln, offset))?;
                b.faces
                    .push((name.to_string(), face, line.ln, col_of(&line, name)));
            } else {
                return Err(at(
                    "E1220",
                    format!("inside a volume block: expected `inside: …`, `face NAME: …`, `corners NAME: …`, `face A edge I ~ face B edge J` or `}}`, found `{text}`"),
                    &line,
                    text,
                    src,
                ));
            }
            continue;
        }
        if let Some(rest) = text.strip_prefix("rule ") {
            let Some((name, def)) = rest.split_once('=') else {
                return Err(at("E1220", "expected `rule NAME = {…}`", &line, text, src));
            };
            let name = name.trim();
            if !valid_name(name) || ["A1", "A2", "A3"].contains(&name) {
                return Err(at(
                    "E1220",
                    format!("invalid rule name `{name}`"),
                    &line,
                    name,
                    src,
                ));
            }
            let def = def.trim();
            let alg = Algorithm::parse(def, col_of(&line, def), &rules)
                .map_err(|e| e.within(src, line.ln, 0))?;
            rules.push((name.to_string(), alg));
            continue;
        }
        let Some(rest) = text.strip_prefix("volume") else {
            return Err(at(
                "E1207",
                format!("expected `volume …`, `rule NAME = …` or a comment, found `{text}`"),
                &line,
                text,
                src,
            ));
        };
        if unnamed {
            return Err(at(
                "E1207",
                "a file with an unnamed `volume NOTATION` line has no other volume (name them: `volume A = NOTATION`)",
                &line,
                text,
                src,
            ));
        }
        let rest_t = rest.trim();
        if let Some((name, list)) = rest_t
            .split_once(" corners:")
            .filter(|(n, _)| valid_name(n.trim()))
        {
            let name = name.trim();
            let Some(v) = names.iter().position(|n| n == name) else {
                return Err(at(
                    "E1222",
                    format!("no volume named `{name}` defined above"),
                    &line,
                    name,
                    src,
                ));
            };
            let Some(solid) = solids[v] else {
                return Err(at(
                    "E1214",
                    format!("volume `{name}` is a block: give its corners face by face inside it (`corners FACE: …`)"),
                    &line,
                    name,
                    src,
                ));
            };
            if corners[v].is_some() {
                return Err(at(
                    "E1221",
                    format!("the corners of volume `{name}` are given twice"),
                    &line,
                    name,
                    src,
                ));
            }
            let polys = solid.polygons();
            let mut ids: Vec<usize> = polys.iter().flatten().copied().collect();
            ids.sort_unstable();
            ids.dedup();
            let pts = coordinates(list, ids.len(), &format!("volume `{name}`"), &line, src)?;
            let of = |id: usize| pts[ids.binary_search(&id).expect("a corner of the solid")].0;
            corners[v] = Some(
                polys
                    .iter()
                    .map(|p| p.iter().map(|&id| of(id)).collect())
                    .collect(),
            );
        } else if text.contains('~') {
            let (l, r) = text.split_once('~').expect("checked");
            let a = volume_face_edge(l, &line, &names, &face_names, &volumes, src)?;
            let b = volume_face_edge(r, &line, &names, &face_names, &volumes, src)?;
            links.push((line.ln, line.col, SharedFace { a, b }));
        } else if let Some(name) = rest_t.strip_suffix('{') {
            let name = name.trim();
            check_new_name(name, &line, &names, src)?;
            names.push(name.to_string());
            block = Some(Block {
                name: name.to_string(),
                ln: line.ln,
                col: col_of(&line, name),
                inside: None,
                faces: Vec::new(),
                links: Vec::new(),
                corners: Vec::new(),
            });
        } else if let Some((name, notation)) = rest_t.split_once('=') {
            let name = name.trim();
            check_new_name(name, &line, &names, src)?;
            let offset = col_of(&line, notation) - 1;
            let v = crate::topology::volume::solid::parse_with(notation, &rules)
                .map_err(|e| e.within(src, line.ln, offset))?;
            names.push(name.to_string());
            face_names.push((0..v.surface.faces.len()).map(|i| i.to_string()).collect());
            volumes.push(v);
            corners.push(None);
            solids.push(notation.split_whitespace().next().and_then(Solid::parse));
        } else if volumes.is_empty() && !rest_t.is_empty() {
            let offset = col_of(&line, rest_t) - 1;
            let v = crate::topology::volume::solid::parse_with(rest_t, &rules)
                .map_err(|e| e.within(src, line.ln, offset))?;
            volumes.push(v);
            corners.push(None);
            solids.push(None);
            unnamed = true;
        } else {
            return Err(at(
                "E1220",
                "expected `volume NAME {`, `volume NAME = NOTATION` or `volume A face F edge I ~ volume B face G edge J`",
                &line,
                text,
                src,
            ));
        }
    }
    if let Some(b) = block {
        return Err(Error::at(
            "E1220",
            format!("volume `{}` is not closed by a `}}` line", b.name),
            b.ln,
            b.col,
            b.name.chars().count().max(1),
            src,
        ));
    }
    if volumes.is_empty() {
        return Err(Error::Io {
            path: src.name.clone(),
            reason: "no `volume` line".into(),
        });
    }
    let mut assembly = VolumeAssembly {
        volumes,
        shared: Vec::new(),
    };
    let mut used: std::collections::HashMap<(usize, usize), usize> = Default::default();
    for (ln, col, s) in links {
        let len = link_len(src, ln, col);
        let err = |code: &'static str, m: String| Error::at(code, m, ln, col, len, src);
        if s.a.0 == s.b.0 {
            return Err(err(
                "E1230",
                "a volume cannot share a face with itself".into(),
            ));
        }
        for side in [s.a, s.b] {
            if let Some(prev) = used.insert((side.0, side.1), ln) {
                return Err(err(
                    "E1230",
                    format!(
                        "face {} of volume `{}` is already shared (line {prev}): a face lies between two volumes at most",
                        side.1, names[side.0]
                    ),
                ));
            }
        }
        assembly.same_face(&s).map_err(|m| {
            err(
                "E1230",
                format!("the shared face is not the same face from both sides: {m}"),
            )
        })?;
        let face = &assembly.volumes[s.a.0].surface.faces[s.a.1];
        if let Err(m) = mirror_consistent(face, &Limits::default())? {
            return Err(err(
                "E1231",
                format!("the two volumes subdivide the shared face differently: {m}"),
            ));
        }
        assembly.shared.push(s);
    }
    Ok(VolumeFile {
        names,
        assembly,
        corners,
    })
}

fn check_new_name(name: &str, line: &Line, names: &[String], src: &Source) -> Result<()> {
    if !valid_name(name) {
        return Err(at(
            "E1220",
            format!("invalid volume name `{name}`"),
            line,
            name,
            src,
        ));
    }
    if names.iter().any(|n| n == name) {
        return Err(at(
            "E1221",
            format!("volume `{name}` is defined twice"),
            line,
            name,
            src,
        ));
    }
    Ok(())
}

/// Parses `volume NAME face F edge I` (face names of a block, or indices of a shorthand).
fn volume_face_edge(
    part: &str,
    line: &Line,
    names: &[String],
    face_names: &[Vec<String>],
    volumes: &[Volume],
    src: &Source,
) -> Result<(usize, usize, usize)> {
    let words: Vec<&str> = part.split_whitespace().collect();
    let ["volume", name, "face", face, "edge", idx] = words.as_slice() else {
        return Err(at(
            "E1220",
            format!(
                "expected `volume NAME face F edge I`, found `{}`",
                part.trim()
            ),
            line,
            part.trim(),
            src,
        ));
    };
    let Some(v) = names
        .iter()
        .position(|n| n == name)
        .filter(|&v| v < volumes.len())
    else {
        return Err(at(
            "E1222",
            format!("no volume named `{name}` defined above"),
            line,
            name,
            src,
        ));
    };
    let faces = &volumes[v].surface.faces;
    let Some(f) = face_names[v].iter().position(|n| n == face) else {
        return Err(at(
            "E1222",
            format!(
                "volume `{name}` has no face `{face}` (a shorthand's faces are 0 to {})",
                faces.len() - 1
            ),
            line,
            face,
            src,
        ));
    };
    let i = idx
        .parse::<usize>()
        .ok()
        .filter(|&i| i < faces[f].boundary.len());
    let Some(i) = i else {
        return Err(at(
            "E1223",
            format!(
                "face {f} of volume `{name}` has {} edges; edge `{idx}` does not exist",
                faces[f].boundary.len()
            ),
            line,
            idx,
            src,
        ));
    };
    Ok((v, f, i))
}

/// The single volume of notation on the command line, as a file of one volume.
pub fn notation_file(arg: &str) -> Result<VolumeFile> {
    Ok(VolumeFile {
        names: Vec::new(),
        assembly: VolumeAssembly::single(parse_volume(arg)?),
        corners: vec![None],
    })
}

/// The length of a link line's span from column `col` of line `ln` to the end of its text (the
/// comment and trailing blanks left out), at least 1: what an error about that link underlines.
fn link_len(src: &Source, ln: usize, col: usize) -> usize {
    let text = src.text.lines().nth(ln - 1).unwrap_or("");
    let end = text
        .split('#')
        .next()
        .unwrap_or("")
        .trim_end()
        .chars()
        .count()
        + 1;
    end.saturating_sub(col).max(1)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::topology::volume::{volume_counts, VolumeClosure};

    fn src(t: &str) -> Source {
        Source {
            name: "test.txt".into(),
            text: t.into(),
        }
    }

    /// The cube written out by hand: corner x + 2y + 4z, each face counter-clockwise seen from
    /// outside, and every edge a → b glued to the edge b → a of the face next to it.
    const CUBE_BLOCK: &str = "\
# the cube, face by face
volume cube {
  inside: B2 B2 | B2 B2 B2 | A1 | V1
  face bottom: B2 B2 B2 B2 | B2 B2 B2 | A1   # 0 2 3 1
  face top:    B2 B2 B2 B2 | B2 B2 B2 | A1   # 4 5 7 6
  face front:  B2 B2 B2 B2 | B2 B2 B2 | A1   # 0 1 5 4
  face back:   B2 B2 B2 B2 | B2 B2 B2 | A1   # 2 6 7 3
  face left:   B2 B2 B2 B2 | B2 B2 B2 | A1   # 0 4 6 2
  face right:  B2 B2 B2 B2 | B2 B2 B2 | A1   # 1 3 7 5
  face bottom edge 0 ~ face left edge 3      # 0→2 | 2→0
  face bottom edge 1 ~ face back edge 3      # 2→3 | 3→2
  face bottom edge 2 ~ face right edge 0     # 3→1 | 1→3
  face bottom edge 3 ~ face front edge 0     # 1→0 | 0→1
  face top edge 0 ~ face front edge 2        # 4→5 | 5→4
  face top edge 1 ~ face right edge 2        # 5→7 | 7→5
  face top edge 2 ~ face back edge 1         # 7→6 | 6→7
  face top edge 3 ~ face left edge 1         # 6→4 | 4→6
  face front edge 1 ~ face right edge 3      # 1→5 | 5→1
  face front edge 3 ~ face left edge 0       # 4→0 | 0→4
  face back edge 0 ~ face left edge 2        # 2→6 | 6→2
  face back edge 2 ~ face right edge 1       # 7→3 | 3→7
}
";

    #[test]
    fn the_cube_block_is_the_cube_shorthand() {
        let block = parse_volume_text(&src(CUBE_BLOCK)).unwrap();
        let short = parse_volume("cube B2 | B2 B2 B2 | A1 | B2 B2 | V1").unwrap();
        assert_eq!(block.canonical(), short.canonical());
        let counts = |v: &Volume| {
            let VolumeClosure::Closed(set) =
                VolumeClosure::of(std::slice::from_ref(v), &Limits::default()).unwrap()
            else {
                panic!("closes")
            };
            (set.types.len(), volume_counts(&set, 3))
        };
        let (types, c) = counts(&block);
        assert_eq!((types, c.clone()), counts(&short));
        // THEORY §10: 1, 8, 152, 3032 cells.
        let cells: Vec<String> = c.iter().map(|l| l.cells.to_string()).collect();
        assert_eq!(cells, ["1", "8", "152", "3032"]);
        // The named shorthand is the same volume as the unnamed one.
        let named =
            parse_volume_file(&src("volume A = cube B2 | B2 B2 B2 | A1 | B2 B2 | V1")).unwrap();
        assert_eq!(named.names, ["A"]);
        assert_eq!(named.assembly.volumes[0], short);
    }

    /// The tetrahedron with one C2 edge (corners 0 1 2 3; edge {0,1} is C2), every face with
    /// `R`, which puts a spoke at the corner from a C edge to a B edge.
    fn tetra(name: &str) -> String {
        format!(
            "volume {name} {{
  inside: B2 B2 | B2 B2 B2 | R | V1
  face f0: B2 B2 C2 | B2 B2 B2 | R   # 0 2 1
  face f1: C2 B2 B2 | B2 B2 B2 | R   # 0 1 3
  face f2: B2 B2 B2 | B2 B2 B2 | R   # 1 2 3
  face f3: B2 B2 B2 | B2 B2 B2 | R   # 0 3 2
  face f0 edge 0 ~ face f3 edge 2
  face f0 edge 1 ~ face f2 edge 0
  face f0 edge 2 ~ face f1 edge 0
  face f1 edge 1 ~ face f2 edge 2
  face f1 edge 2 ~ face f3 edge 0
  face f2 edge 1 ~ face f3 edge 1
}}
"
        )
    }

    #[test]
    fn shared_faces_are_checked() {
        let rule = "rule R = {joint gap corner(C,B)}\n";
        let two = format!("{rule}{}{}", tetra("A"), tetra("B"));
        assert!(parse_volume_file(&src(&two)).is_ok());
        // A face shared with a face of another type.
        let t = format!("{two}volume A face f2 edge 0 ~ volume B face f1 edge 0\n");
        let e = parse_volume_file(&src(&t)).unwrap_err();
        assert_eq!((e.code(), e.span().unwrap().line), ("E1230", 28));
        // A's f1 (C2 B2 B2) read from B is B's f0 (B2 B2 C2) with A's edge 0 on B's edge 2: the
        // same face, but R puts a spoke at the corner C2 → B2 of A's reading, which B reads as
        // B2 → C2: the two volumes would subdivide it differently.
        let t = format!("{two}volume A face f1 edge 0 ~ volume B face f0 edge 2\n");
        let e = parse_volume_file(&src(&t)).unwrap_err();
        assert_eq!(e.code(), "E1231", "{}", e.render());
        // With the symmetric A1 the same gluing is accepted.
        let sym = two.replace("corner(C,B)", "");
        let t = format!("{sym}volume A face f1 edge 0 ~ volume B face f0 edge 2\n");
        let file = parse_volume_file(&src(&t)).unwrap();
        assert_eq!(file.assembly.shared.len(), 1);
    }

    #[test]
    fn bad_volume_files_have_codes_lines_and_columns() {
        let face = "B2 B2 B2 B2 | B2 B2 B2 | A1";
        let inside = "  inside: B2 B2 | B2 B2 B2 | A1 | V1\n";
        // A torus: one square with opposite edges glued (V − E + F = 1 − 2 + 1 = 0).
        let torus = format!(
            "volume T {{\n{inside}  face s: {face}\n  face s edge 0 ~ face s edge 2\n  face s edge 1 ~ face s edge 3\n}}\n"
        );
        // Two spheres of two digons each: not connected.
        let digon = "B2 B2 | B2 B2 B2 | A1";
        let apart = format!(
            "volume D {{\n{inside}  face a: {digon}\n  face b: {digon}\n  face c: {digon}\n  face d: {digon}\n  face a edge 0 ~ face b edge 0\n  face a edge 1 ~ face b edge 1\n  face c edge 0 ~ face d edge 0\n  face c edge 1 ~ face d edge 1\n}}\n"
        );
        let cube = "volume A = cube B2 | B2 B2 B2 | A1 | B2 B2 | V1\n";
        let cases: Vec<(String, &str, usize, usize)> = vec![
            (format!("volume X {{\n{inside}  face a: {face}\n"), "E1220", 1, 8),
            (format!("volume X {{\n  face a: {face}\n}}\n"), "E1220", 1, 8),
            (format!("volume X {{\n{inside}  hello\n}}\n"), "E1220", 3, 3),
            (format!("volume X {{\n{inside}  face a: {face}\n  face a: {face}\n}}\n"), "E1221", 4, 8),
            (format!("{cube}{cube}"), "E1221", 2, 8),
            ("# x\nvolume A = sphere B2 | B2 B2 B2 | A1 | B2 B2 | V1\n".to_string(), "E1202", 2, 12),
            (format!("volume X {{\n{inside}  face a: {face}\n  face a edge 0 ~ face b edge 1\n}}\n"), "E1222", 4, 24),
            (format!("{cube}volume A face 0 edge 0 ~ volume Z face 0 edge 0\n"), "E1222", 2, 33),
            (format!("volume X {{\n{inside}  face a: {face}\n  face a edge 7 ~ face a edge 1\n}}\n"), "E1223", 4, 3),
            (format!("{cube}volume A face 0 edge 9 ~ volume A face 1 edge 0\n"), "E1223", 2, 22),
            (format!("volume X {{\n{inside}  face a: {face}\n  face a edge 0 ~ face a edge 2\n  face a edge 2 ~ face a edge 1\n}}\n"), "E1224", 5, 3),
            (format!("volume X {{\n{inside}  face a: {face}\n  face a edge 0 ~ face a edge 0\n}}\n"), "E1224", 4, 3),
            (format!("volume X {{\n{inside}  face a: {face}\n  face a edge 0 ~ face a edge 2\n}}\n"), "E1225", 3, 8),
            (format!("volume X {{\n{inside}  face a: C2 B2 | B2 B2 B2 | A1\n  face a edge 0 ~ face a edge 1\n}}\n"), "E1226", 4, 3),
            (apart, "E1228", 1, 8),
            (torus, "E1229", 1, 8),
            (format!("{cube}volume A face 0 edge 0 ~ volume A face 1 edge 0\n"), "E1230", 2, 1),
            ("volume X {\n  inside: B2 | B2 B2 B2 | A1 | V1\n}\n".to_string(), "E1232", 2, 11),
            ("volume X {\n  inside: B2 B2 | B2 B2 B2 | A1 | V7\n}\n".to_string(), "E1232", 2, 35),
            (format!("volume X {{\n{inside}  face a: B2 Q2 | B2 B2 B2 | A1\n}}\n"), "E0103", 3, 14),
        ];
        for (text, code, line, col) in cases {
            let e = parse_volume_file(&src(&text)).unwrap_err();
            let span = e.span().unwrap_or_else(|| panic!("{text}: no span"));
            // The error shows the file's line, not a sub-text's.
            assert!(
                e.render()
                    .contains(&format!("test.txt:{}:{}", span.line, span.col)),
                "{}",
                e.render()
            );
            assert_eq!(
                (e.code(), span.line, span.col),
                (code, line, col),
                "{text}\n{}",
                e.render()
            );
        }
    }
}
