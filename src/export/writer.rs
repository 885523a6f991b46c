//! Exports of the level-n cells (THEORY §7): SVG, JSON, Wavefront OBJ prisms and PNG.
//!
//! JSON, OBJ and STL are written as text by hand, streaming: the formats are small (a JSON array,
//! OBJ `v`/`f` lines), and the output is deterministic (fixed number formatting, depth-first
//! order). The pictures are in [`crate::export::picture`] (SVG) and [`crate::export::bitmap`]
//! (colour PNG); here remain the 1-bit coverage PNG of a raster and the grayscale density PNG
//! (one pixel per block), written with stored deflate blocks.

use crate::export::picture::{write_svg_picture, PictureOptions};
use crate::geometry::instantiate::Instance;
use crate::geometry::point::{signed_area, Point, Raster};
use crate::geometry::raster::rasterize;
use crate::measure::DensityMap;
use std::io::{self, Write};

fn fmt(x: f64) -> String {
    let s = format!("{x:.6}");
    if s == "-0.000000" {
        "0.000000".into()
    } else {
        s
    }
}

/// Writes the cells of `level` as an SVG picture 512 pixels wide with its legend, on white:
/// [`write_svg_picture`] with the default [`PictureOptions`]. Edges are drawn as the curves
/// themselves (or flattened to 0.1 pixel), so `segments` is no longer used; it stays for callers.
pub fn write_svg<W: Write>(inst: &Instance, level: u32, segments: usize, out: W) -> io::Result<()> {
    let _ = segments;
    write_svg_picture(inst, level, &PictureOptions::default(), out)
}

/// Writes the cells of `level` as JSON: `{"name", "level", "cells": [{"type", "polygon": [[x, y],
/// …]}]}`, polygons counter-clockwise, coordinates with 6 decimals.
pub fn write_json<W: Write>(
    inst: &Instance,
    level: u32,
    segments: usize,
    mut out: W,
) -> io::Result<()> {
    write!(
        out,
        "{{\"name\":{},\"level\":{level},\"cells\":[",
        serde_json::to_string(&inst.name).unwrap_or_default()
    )?;
    let mut first = true;
    let mut result = Ok(());
    inst.walk(level, false, |c| {
        if result.is_err() {
            return;
        }
        let poly = inst.cell_polygon(c.ty, c.points, segments);
        let pts: Vec<String> = poly
            .iter()
            .map(|p| format!("[{},{}]", fmt(p[0]), fmt(p[1])))
            .collect();
        result = write!(
            out,
            "{}\n{{\"type\":{},\"polygon\":[{}]}}",
            if first { "" } else { "," },
            c.ty,
            pts.join(",")
        );
        first = false;
    });
    result?;
    writeln!(out, "\n]}}")
}

/// Writes the cells of `level` as a Wavefront OBJ mesh for printing: each cell extruded to a
/// prism of height `thickness` (bottom and top n-gons, one quad per side, outward normals). Each
/// prism is closed (watertight); neighbouring prisms touch along shared side walls, which slicers
/// merge.
pub fn write_obj<W: Write>(
    inst: &Instance,
    level: u32,
    segments: usize,
    thickness: f64,
    mut out: W,
) -> io::Result<()> {
    writeln!(
        out,
        "# lacuna: {} level {level}, prisms of height {}",
        inst.name,
        fmt(thickness)
    )?;
    let mut next = 1usize;
    let mut result = Ok(());
    inst.walk(level, false, |c| {
        if result.is_err() {
            return;
        }
        let mut poly: Vec<Point> = inst.cell_polygon(c.ty, c.points, segments);
        if signed_area(&poly) < 0.0 {
            poly.reverse();
        }
        let n = poly.len();
        let mut s = String::new();
        for z in [0.0, thickness] {
            for p in &poly {
                s.push_str(&format!("v {} {} {}\n", fmt(p[0]), fmt(p[1]), fmt(z)));
            }
        }
        let (b, t) = (next, next + n);
        let bottom: Vec<String> = (0..n).rev().map(|i| (b + i).to_string()).collect();
        let top: Vec<String> = (0..n).map(|i| (t + i).to_string()).collect();
        s.push_str(&format!("f {}\nf {}\n", bottom.join(" "), top.join(" ")));
        for i in 0..n {
            let j = (i + 1) % n;
            s.push_str(&format!("f {} {} {} {}\n", b + i, b + j, t + j, t + i));
        }
        next += 2 * n;
        result = out.write_all(s.as_bytes());
    });
    result
}

pub use crate::mesh::triangulate;

/// Writes the cells of `level` as an ASCII STL mesh for printing: each cell extruded to a closed
/// prism of height `thickness` (bottom and top triangulated by ear clipping, two triangles per
/// side wall, outward normals), so every prism is watertight.
pub fn write_stl<W: Write>(
    inst: &Instance,
    level: u32,
    segments: usize,
    thickness: f64,
    mut out: W,
) -> io::Result<()> {
    writeln!(out, "solid lacuna")?;
    let mut result = Ok(());
    let facet = |s: &mut String, p: [[f64; 3]; 3]| {
        let u = [p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]];
        let v = [p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]];
        let mut nrm = [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ];
        let len = (nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]).sqrt();
        if len > 0.0 {
            nrm = nrm.map(|x| x / len);
        }
        s.push_str(&format!(
            "facet normal {} {} {}\n outer loop\n",
            fmt(nrm[0]),
            fmt(nrm[1]),
            fmt(nrm[2])
        ));
        for q in p {
            s.push_str(&format!(
                "  vertex {} {} {}\n",
                fmt(q[0]),
                fmt(q[1]),
                fmt(q[2])
            ));
        }
        s.push_str(" endloop\nendfacet\n");
    };
    inst.walk(level, false, |c| {
        if result.is_err() {
            return;
        }
        let mut poly: Vec<Point> = inst.cell_polygon(c.ty, c.points, segments);
        poly.dedup();
        if poly.len() > 1 && poly[0] == poly[poly.len() - 1] {
            poly.pop();
        }
        if poly.len() < 3 {
            return;
        }
        if signed_area(&poly) < 0.0 {
            poly.reverse();
        }
        let at = |p: Point, z: f64| [p[0], p[1], z];
        let mut s = String::new();
        for [a, b, c] in triangulate(&poly) {
            facet(
                &mut s,
                [
                    at(poly[a], thickness),
                    at(poly[b], thickness),
                    at(poly[c], thickness),
                ],
            );
            facet(
                &mut s,
                [at(poly[a], 0.0), at(poly[c], 0.0), at(poly[b], 0.0)],
            );
        }
        let n = poly.len();
        for i in 0..n {
            let (p, q) = (poly[i], poly[(i + 1) % n]);
            facet(&mut s, [at(p, 0.0), at(q, 0.0), at(q, thickness)]);
            facet(&mut s, [at(p, 0.0), at(q, thickness), at(p, thickness)]);
        }
        result = out.write_all(s.as_bytes());
    });
    result?;
    writeln!(out, "endsolid lacuna")
}

/// Renders the cells of `level` to a `size × size` raster (the picture window fits the level-0
/// faces).
pub fn render_raster(inst: &Instance, level: u32, size: usize, segments: usize) -> Raster {
    rasterize(inst, level, size, segments)
}

fn crc32(data: &[u8], mut crc: u32) -> u32 {
    crc = !crc;
    for &b in data {
        crc ^= b as u32;
        for _ in 0..8 {
            crc = if crc & 1 != 0 {
                (crc >> 1) ^ 0xEDB8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

fn chunk<W: Write>(out: &mut W, kind: &[u8; 4], data: &[u8]) -> io::Result<()> {
    out.write_all(&(data.len() as u32).to_be_bytes())?;
    out.write_all(kind)?;
    out.write_all(data)?;
    let crc = crc32(data, crc32(kind, 0));
    out.write_all(&crc.to_be_bytes())
}

/// Writes a raster as a 1-bit grayscale PNG (covered pixels black, the rest white). The image
/// data is zlib with stored (uncompressed) deflate blocks: about size²/8 bytes.
pub fn write_png<W: Write>(raster: &Raster, out: W) -> io::Result<()> {
    let n = raster.size;
    let stride = n.div_ceil(8);
    let mut raw = Vec::with_capacity(n * (stride + 1));
    for r in 0..n {
        raw.push(0u8);
        let mut row = vec![0xFFu8; stride];
        for c in 0..n {
            if raster.covered(c, r) {
                row[c / 8] &= !(0x80 >> (c % 8));
            }
        }
        raw.extend(row);
    }
    write_gray_png(n, n, 1, &raw, out)
}

/// Writes a density map as an 8-bit grayscale PNG, one pixel per block: density 1 black, 0 white
/// (as the 1-bit pictures, where covered pixels are black).
pub fn write_density_png<W: Write>(map: &DensityMap, out: W) -> io::Result<()> {
    let g = map.grid;
    let mut raw = Vec::with_capacity(g * (g + 1));
    for row in map.values.chunks(g) {
        raw.push(0u8);
        raw.extend(
            row.iter()
                .map(|&d| (255.0 * (1.0 - d.clamp(0.0, 1.0))).round() as u8),
        );
    }
    write_gray_png(g, g, 8, &raw, out)
}

/// Writes a grayscale PNG of `width × height` pixels at `depth` bits per pixel (1 or 8) from its
/// filtered scanlines `raw` (each row a filter byte 0 then the packed pixels). The image data is
/// zlib with stored (uncompressed) deflate blocks; no compression crate is needed for that.
pub(crate) fn write_gray_png<W: Write>(
    width: usize,
    height: usize,
    depth: u8,
    raw: &[u8],
    mut out: W,
) -> io::Result<()> {
    out.write_all(&[0x89, b'P', b'N', b'G', 0x0D, 0x0A, 0x1A, 0x0A])?;
    let mut ihdr = Vec::new();
    ihdr.extend((width as u32).to_be_bytes());
    ihdr.extend((height as u32).to_be_bytes());
    ihdr.extend([depth, 0, 0, 0, 0]);
    chunk(&mut out, b"IHDR", &ihdr)?;
    let mut z = vec![0x78, 0x01];
    let blocks: Vec<&[u8]> = raw.chunks(65_535).collect();
    for (i, b) in blocks.iter().enumerate() {
        z.push(u8::from(i + 1 == blocks.len()));
        let len = b.len() as u16;
        z.extend(len.to_le_bytes());
        z.extend((!len).to_le_bytes());
        z.extend_from_slice(b);
    }
    let (mut a, mut bsum) = (1u32, 0u32);
    for &x in raw {
        a = (a + x as u32) % 65_521;
        bsum = (bsum + a) % 65_521;
    }
    z.extend(((bsum << 16) | a).to_be_bytes());
    chunk(&mut out, b"IDAT", &z)?;
    chunk(&mut out, b"IEND", &[])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crc_of_iend_is_the_known_constant() {
        assert_eq!(crc32(b"IEND", 0), 0xAE42_6082);
    }
}
