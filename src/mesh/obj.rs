//! Wavefront OBJ writer: one object (`o`) per part, its vertices, and triangles only (importers
//! need not triangulate anything). Coordinates in millimetres, printed as the shortest decimal
//! that reads back as the same `f32`.

use super::solid::Solid;
use std::io::{self, Write};

/// Writes a solid as OBJ (indices are global and 1-based, as the format wants).
pub fn write<W: Write>(solid: &Solid, mut out: W) -> io::Result<()> {
    writeln!(
        out,
        "# lacuna: {} level {}, millimetres, {}, closed and outward-oriented",
        solid.name,
        solid.level,
        super::counted(solid.parts.len(), "part", "parts")
    )?;
    let mut base = 1usize;
    for (i, p) in solid.parts.iter().enumerate() {
        writeln!(out, "o component_{i}")?;
        for v in &p.vertices {
            writeln!(out, "v {} {} {}", v[0], v[1], v[2])?;
        }
        for t in &p.triangles {
            writeln!(
                out,
                "f {} {} {}",
                base + t[0] as usize,
                base + t[1] as usize,
                base + t[2] as usize
            )?;
        }
        base += p.vertices.len();
    }
    out.flush()
}
