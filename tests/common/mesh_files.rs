//! Written meshes read back with readers that are not the writers (issue #35: one copy instead of
//! one per test file): STL with the `stl_io` crate, 3MF with the `zip` crate and a minimal XML
//! scan written here.

use std::io::{Cursor, Read};

/// A triangle mesh as read back: positions and index triples (vertices merged by identical
/// coordinates, which is what a slicer does with STL).
pub struct Read3 {
    /// The positions.
    pub vertices: Vec<[f32; 3]>,
    /// The triangles, as indices into `vertices`.
    pub triangles: Vec<[usize; 3]>,
}

/// `(b − a) × (c − a)`: the normal of the triangle `abc` along its winding, of length twice its
/// area.
pub fn cross([a, b, c]: [[f64; 3]; 3]) -> [f64; 3] {
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let w = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    [
        u[1] * w[2] - u[2] * w[1],
        u[2] * w[0] - u[0] * w[2],
        u[0] * w[1] - u[1] * w[0],
    ]
}

/// Reads an STL with `stl_io`; checks every facet's normal agrees with its winding.
pub fn read_stl(bytes: &[u8], what: &str) -> Read3 {
    read(bytes, what, false)
}

/// [`read_stl`] for a closed surface, with `stl_io`'s validation too: no zero-area facet, and
/// every edge of a facet met the other way round by another.
pub fn read_closed_stl(bytes: &[u8], what: &str) -> Read3 {
    read(bytes, what, true)
}

fn read(bytes: &[u8], what: &str, closed: bool) -> Read3 {
    let mesh = stl_io::read_stl(&mut Cursor::new(bytes)).unwrap_or_else(|e| panic!("{what}: {e}"));
    if closed {
        mesh.validate()
            .unwrap_or_else(|e| panic!("{what}: stl_io's validation: {e}"));
    }
    let vertices: Vec<[f32; 3]> = mesh.vertices.iter().map(|v| v.0).collect();
    for (i, f) in mesh.faces.iter().enumerate() {
        let n = cross(f.vertices.map(|v| vertices[v].map(f64::from)));
        let dot: f64 = (0..3).map(|k| n[k] * f64::from(f.normal.0[k])).sum();
        assert!(dot > 0.0, "{what}: facet {i} is wound against its normal");
    }
    Read3 {
        vertices,
        triangles: mesh.faces.iter().map(|f| f.vertices).collect(),
    }
}

/// The number of triangles a binary STL's header states.
pub fn binary_stl_triangles(bytes: &[u8]) -> usize {
    u32::from_le_bytes(bytes[80..84].try_into().unwrap()) as usize
}

/// The model part `3D/3dmodel.model` of a 3MF package; checks the package also holds its
/// content types and relationships.
pub fn model_xml(bytes: &[u8]) -> String {
    let mut z = zip::ZipArchive::new(Cursor::new(bytes)).expect("a zip archive");
    for name in ["[Content_Types].xml", "_rels/.rels"] {
        assert!(z.by_name(name).is_ok(), "3MF without {name}");
    }
    let mut xml = String::new();
    z.by_name("3D/3dmodel.model")
        .expect("the model part")
        .read_to_string(&mut xml)
        .unwrap();
    xml
}

/// The value of attribute `name` in an XML element's text.
pub fn attribute<'a>(el: &'a str, name: &str) -> Option<&'a str> {
    let key = format!(" {name}=\"");
    let at = el.find(&key)? + key.len();
    Some(&el[at..at + el[at..].find('"')?])
}

/// [`attribute`], which must be there.
pub fn attr<'a>(el: &'a str, name: &str) -> &'a str {
    attribute(el, name).unwrap_or_else(|| panic!("no {name} in {el}"))
}
