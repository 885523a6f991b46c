//! The mesh as the file gives it: the format (decided from the content, not the name), the
//! triangles in file order, and their corners welded by exact coordinate equality — STL repeats
//! the coordinates of a corner in every triangle; 3MF indexes them, and its indices are replaced
//! by coordinates too, so that two indices at one place are one vertex, as a slicer sees them.

use super::exact::Point;
use crate::error::{Diagnostic, Error};
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hash, Hasher};

/// The mesh formats read.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Binary STL: 80-byte header, triangle count, 50 bytes per triangle.
    BinaryStl,
    /// ASCII STL: `solid … facet normal … outer loop vertex … endloop endfacet … endsolid`.
    AsciiStl,
    /// 3MF: a ZIP package whose model part holds objects with meshes and build items.
    ThreeMf,
}

impl Format {
    /// How the format is named in reports.
    pub fn name(self) -> &'static str {
        match self {
            Format::BinaryStl => "binary STL",
            Format::AsciiStl => "ASCII STL",
            Format::ThreeMf => "3MF",
        }
    }

    /// The tag of the format in JSON.
    pub fn tag(self) -> &'static str {
        match self {
            Format::BinaryStl => "stl-binary",
            Format::AsciiStl => "stl-ascii",
            Format::ThreeMf => "3mf",
        }
    }
}

/// A run of triangles that came from one 3MF build item (STL has one run).
#[derive(Clone, Debug)]
pub(super) struct Piece {
    /// The index of its first triangle in the whole mesh.
    pub(super) first: usize,
    /// What the file calls it (`object 2`).
    pub(super) label: String,
}

/// A welded mesh: vertices by exact coordinates, triangles as vertex triples in file order.
#[derive(Clone, Debug)]
pub(super) struct Mesh {
    pub(super) format: Format,
    /// The unit of the coordinates (`mm` for STL, which has none: millimetres by custom).
    pub(super) unit: String,
    pub(super) vertices: Vec<Point>,
    pub(super) triangles: Vec<[u32; 3]>,
    pub(super) pieces: Vec<Piece>,
    /// Things worth saying that are not failures (3MF indices welded, objects not built).
    pub(super) notes: Vec<String>,
}

impl Mesh {
    /// How a triangle is named in messages: its index, and for 3MF its object and index there.
    pub(super) fn triangle_name(&self, t: usize) -> String {
        if self.format != Format::ThreeMf {
            return format!("triangle {t}");
        }
        let i = self
            .pieces
            .partition_point(|p| p.first <= t)
            .saturating_sub(1);
        match self.pieces.get(i) {
            Some(p) => format!("triangle {t} ({} triangle {})", p.label, t - p.first),
            None => format!("triangle {t}"),
        }
    }

    /// A vertex with its coordinates, for messages.
    pub(super) fn vertex_name(&self, v: u32) -> String {
        let p = self.vertices[v as usize];
        format!("v{v} ({}, {}, {})", p[0], p[1], p[2])
    }
}

/// FNV-1a over the coordinate bits: the welding map hashes tens of millions of keys, and SipHash
/// would double the time of reading a large STL.
#[derive(Default)]
pub(super) struct Fnv(u64);

impl Hasher for Fnv {
    fn finish(&self) -> u64 {
        self.0 ^ (self.0 >> 32)
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0 ^ u64::from(b)).wrapping_mul(0x100_0000_01b3);
        }
    }
    fn write_u64(&mut self, x: u64) {
        // One multiply per word, then a fold of the high bits into the low ones.
        let h = (self.0 ^ x).wrapping_mul(0x9e37_79b9_7f4a_7c15);
        self.0 = h ^ (h >> 29);
    }
}

/// The exact coordinates of a vertex, as bits, hashed word by word.
#[derive(PartialEq, Eq)]
struct Key([u64; 3]);

impl Hash for Key {
    fn hash<H: Hasher>(&self, h: &mut H) {
        for x in self.0 {
            h.write_u64(x);
        }
    }
}

/// Builds a [`Mesh`] from triangles given by their corner coordinates.
pub(super) struct Welder {
    map: HashMap<Key, u32, BuildHasherDefault<Fnv>>,
    mesh: Mesh,
}

impl Welder {
    pub(super) fn new(format: Format, unit: &str, triangles: usize) -> Welder {
        Welder {
            map: HashMap::with_capacity_and_hasher(triangles / 2 + 4, Default::default()),
            mesh: Mesh {
                format,
                unit: unit.to_string(),
                vertices: Vec::with_capacity(triangles / 2 + 4),
                triangles: Vec::with_capacity(triangles),
                pieces: Vec::new(),
                notes: Vec::new(),
            },
        }
    }

    /// The vertex at `p` (finite coordinates; `-0` is `0`).
    pub(super) fn vertex(&mut self, p: Point) -> u32 {
        let p = p.map(|x| x + 0.0);
        let key = Key(p.map(f64::to_bits));
        let next = self.mesh.vertices.len() as u32;
        let v = *self.map.entry(key).or_insert(next);
        if v == next {
            self.mesh.vertices.push(p);
        }
        v
    }

    pub(super) fn triangle(&mut self, corners: [Point; 3]) {
        let t = corners.map(|p| self.vertex(p));
        self.mesh.triangles.push(t);
    }

    pub(super) fn triangle_of(&mut self, t: [u32; 3]) {
        self.mesh.triangles.push(t);
    }

    pub(super) fn piece(&mut self, label: String) {
        let first = self.mesh.triangles.len();
        self.mesh.pieces.push(Piece { first, label });
    }

    pub(super) fn note(&mut self, note: String) {
        self.mesh.notes.push(note);
    }

    pub(super) fn finish(self) -> Mesh {
        self.mesh
    }
}

/// A malformed file: `code` with a message and no span.
pub(super) fn malformed(code: &'static str, message: String) -> Error {
    Error::Syntax(Box::new(Diagnostic {
        code,
        message,
        span: None,
        source: None,
    }))
}

/// The triangle limit, checked before the work (E0501: a limit, not a verdict).
pub(super) fn check_limit(triangles: u64, max: u64) -> Result<(), Error> {
    if triangles > max {
        return Err(Error::limit(
            "the number of triangles (a limit, not a verdict on the mesh)",
            triangles,
            max,
            "--max-triangles",
        ));
    }
    Ok(())
}

/// Reads a mesh file's bytes: 3MF when it is a ZIP archive, else STL (binary when its size is
/// exactly what its triangle count says, ASCII when it starts with `solid`).
pub(super) fn read(bytes: &[u8], name: &str, max_triangles: u64) -> Result<Mesh, Error> {
    if bytes.starts_with(b"PK\x03\x04") {
        return super::threemf::read(bytes, name, max_triangles);
    }
    super::stl::read(bytes, name, max_triangles)
}
