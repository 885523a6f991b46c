//! STL writers: binary (the default; 50 bytes a triangle, `f32` coordinates) and ASCII. STL has
//! no unit and no parts: coordinates are millimetres (the unit slicers assume), and the parts of
//! a solid are its connected pieces. Each facet's normal is computed from its vertices as written,
//! so it always agrees with their winding.

use super::solid::Solid;
use std::io::{self, Write};

/// The unit normal of a triangle from its `f32` vertices (0 when degenerate, which the check
/// refuses before any writer runs).
pub fn normal(p: [[f32; 3]; 3]) -> [f32; 3] {
    let d = |i: usize, k: usize| f64::from(p[i][k]) - f64::from(p[0][k]);
    let (u, v) = ([d(1, 0), d(1, 1), d(1, 2)], [d(2, 0), d(2, 1), d(2, 2)]);
    let n = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    if len > 0.0 {
        n.map(|x| (x / len) as f32)
    } else {
        [0.0; 3]
    }
}

/// The triangles of a solid with their corner positions, part after part.
fn facets(solid: &Solid) -> impl Iterator<Item = [[f32; 3]; 3]> + '_ {
    solid.parts.iter().flat_map(|p| {
        p.triangles
            .iter()
            .map(move |t| t.map(|v| p.vertices[v as usize]))
    })
}

/// Writes a solid as binary STL: an 80-byte header naming it, the triangle count, then per
/// triangle its normal, its three vertices (little-endian `f32`) and a zero attribute.
pub fn write_binary<W: Write>(solid: &Solid, mut out: W) -> io::Result<()> {
    let mut header = [b' '; 80];
    let title = format!(
        "lacuna {} level {} mm ({} parts)",
        solid.name,
        solid.level,
        solid.parts.len()
    );
    // A binary STL header must not start with "solid" (readers would take it for ASCII).
    let bytes = title.as_bytes();
    let n = bytes.len().min(80);
    header[..n].copy_from_slice(&bytes[..n]);
    out.write_all(&header)?;
    let count = u32::try_from(solid.triangle_count())
        .map_err(|_| io::Error::other("more than 2^32 triangles"))?;
    out.write_all(&count.to_le_bytes())?;
    let mut rec = [0u8; 50];
    for f in facets(solid) {
        let n = normal(f);
        for (k, x) in n.iter().chain(f.iter().flatten()).enumerate() {
            rec[4 * k..4 * k + 4].copy_from_slice(&x.to_le_bytes());
        }
        out.write_all(&rec)?;
    }
    out.flush()
}

/// Writes a solid as ASCII STL. Coordinates are printed as the shortest decimal that reads back
/// as the same `f32`, so the ASCII and binary files describe the same mesh.
pub fn write_ascii<W: Write>(solid: &Solid, mut out: W) -> io::Result<()> {
    let name = solid.name.replace(|c: char| c.is_whitespace(), "_");
    writeln!(out, "solid {name}")?;
    for f in facets(solid) {
        let n = normal(f);
        writeln!(out, "facet normal {} {} {}", n[0], n[1], n[2])?;
        writeln!(out, " outer loop")?;
        for p in f {
            writeln!(out, "  vertex {} {} {}", p[0], p[1], p[2])?;
        }
        writeln!(out, " endloop\nendfacet")?;
    }
    writeln!(out, "endsolid {name}")?;
    out.flush()
}
