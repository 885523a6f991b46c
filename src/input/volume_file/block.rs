//! A volume block built and checked: its edges glued exactly once to edges of the same type and
//! delay, its faces one connected surface that is a sphere, and the coordinates of its `corners`
//! lines placing every point of the surface once.

use super::{link_len, Block, Corners};
use crate::error::{Error, Result, Source};
use crate::topology::volume::surface::Surface;
use crate::topology::volume::Volume;

/// Builds and checks the volume of a block: every edge glued exactly once, to an edge of the
/// same type and delay, the surface connected and a sphere.
pub(super) fn finish(b: Block, src: &Source) -> Result<(Volume, Option<Corners>)> {
    let head = |code: &'static str, m: String| {
        Error::at(code, m, b.ln, b.col, b.name.chars().count().max(1), src)
    };
    let Some((radial, inner, template, rule, delay)) = b.inside.clone() else {
        return Err(head(
            "E1220",
            format!(
                "volume `{}` has no `inside: Er Ei | Ea El Ec | A | RULE` line",
                b.name
            ),
        ));
    };
    if b.faces.is_empty() {
        return Err(head("E1220", format!("volume `{}` has no face", b.name)));
    }
    let mut glue: Vec<Vec<Option<(usize, usize)>>> = b
        .faces
        .iter()
        .map(|(_, f, _, _)| vec![None; f.boundary.len()])
        .collect();
    for &(ln, col, [x, y]) in &b.links {
        let len = link_len(src, ln, col);
        let err = |code: &'static str, m: String| Error::at(code, m, ln, col, len, src);
        for &(f, i) in &[x, y] {
            let (name, face, _, _) = &b.faces[f];
            if i >= face.boundary.len() {
                return Err(err(
                    "E1223",
                    format!(
                        "face `{name}` has {} edges; edge {i} does not exist",
                        face.boundary.len()
                    ),
                ));
            }
        }
        if x == y {
            return Err(err("E1224", "an edge cannot be glued to itself".into()));
        }
        for &(f, i) in &[x, y] {
            if glue[f][i].is_some() {
                return Err(err(
                    "E1224",
                    format!(
                        "edge {i} of face `{}` is already glued: every edge is glued exactly once",
                        b.faces[f].0
                    ),
                ));
            }
        }
        let (tx, ty) = (b.faces[x.0].1.boundary[x.1], b.faces[y.0].1.boundary[y.1]);
        if tx != ty {
            return Err(err(
                "E1226",
                format!(
                    "edge {} of face `{}` is {tx} but edge {} of face `{}` is {ty}: glued edges have the same type and delay",
                    x.1, b.faces[x.0].0, y.1, b.faces[y.0].0
                ),
            ));
        }
        glue[x.0][x.1] = Some(y);
        glue[y.0][y.1] = Some(x);
    }
    for (f, row) in glue.iter().enumerate() {
        if let Some(i) = row.iter().position(Option::is_none) {
            let (name, _, ln, col) = &b.faces[f];
            return Err(Error::at(
                "E1225",
                format!("edge {i} of face `{name}` is not glued: every edge is glued exactly once"),
                *ln,
                *col,
                name.chars().count().max(1),
                src,
            ));
        }
    }
    let surface = Surface {
        faces: b.faces.iter().map(|(_, f, _, _)| f.clone()).collect(),
        glue: glue
            .into_iter()
            .map(|r| r.into_iter().map(|x| x.expect("checked")).collect())
            .collect(),
    };
    let (_, points) = surface.vertices();
    if !connected(&surface) {
        return Err(head(
            "E1228",
            format!(
                "the faces of volume `{}` do not form one connected surface",
                b.name
            ),
        ));
    }
    let chi = surface.euler();
    if chi != 2 {
        return Err(head(
            "E1229",
            format!(
                "the surface of volume `{}` is not a sphere: {points} corners − {} edges + {} faces = {chi}, not 2",
                b.name,
                surface.edge_count(),
                surface.faces.len()
            ),
        ));
    }
    let corners = block_corners(&b, &surface, src)?;
    Ok((
        Volume {
            surface,
            radial,
            inner,
            params: template.params,
            algorithm: template.algorithm,
            rule,
            delay,
        },
        corners,
    ))
}

/// The coordinates of a block's surface from its `corners FACE:` lines: `None` without such
/// lines; every point of the surface placed once (a point given by several faces must be given
/// the same coordinates).
fn block_corners(b: &Block, surface: &Surface, src: &Source) -> Result<Option<Corners>> {
    if b.corners.is_empty() {
        return Ok(None);
    }
    let (vid, count) = surface.vertices();
    let mut at_point: Vec<Option<([f64; 3], usize, String)>> = vec![None; count];
    for (f, pts, ln) in &b.corners {
        for (i, (p, col, width)) in pts.iter().enumerate() {
            let here = format!("corner {i} of face `{}`", b.faces[*f].0);
            match &at_point[vid[*f][i]] {
                Some((q, _, there)) if q != p => {
                    return Err(Error::at(
                        "E1212",
                        format!(
                            "{here} is at {} but it is the same point as {there}, given at {}",
                            show(*p),
                            show(*q)
                        ),
                        *ln,
                        *col,
                        *width,
                        src,
                    ))
                }
                Some(_) => {}
                None => at_point[vid[*f][i]] = Some((*p, *ln, here)),
            }
        }
    }
    let mut out = Vec::with_capacity(surface.faces.len());
    for (f, row) in vid.iter().enumerate() {
        let mut face = Vec::with_capacity(row.len());
        for (i, &p) in row.iter().enumerate() {
            let Some((q, _, _)) = &at_point[p] else {
                let (name, _, ln, col) = &b.faces[f];
                return Err(Error::at(
                    "E1213",
                    format!("corner {i} of face `{name}` has no coordinates: with `corners` lines, every corner of the surface is placed (a corner shared by several faces needs to be given once)"),
                    *ln,
                    *col,
                    name.chars().count().max(1),
                    src,
                ));
            };
            face.push(*q);
        }
        out.push(face);
    }
    Ok(Some(out))
}

fn show(p: [f64; 3]) -> String {
    format!("({} {} {})", p[0], p[1], p[2])
}

fn connected(s: &Surface) -> bool {
    let mut seen = vec![false; s.faces.len()];
    let mut stack = vec![0usize];
    seen[0] = true;
    while let Some(f) = stack.pop() {
        for &(g, _) in &s.glue[f] {
            if !std::mem::replace(&mut seen[g], true) {
                stack.push(g);
            }
        }
    }
    seen.iter().all(|&x| x)
}
