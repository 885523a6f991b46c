//! 3MF writer (3MF Core Specification 1.x): a ZIP package (the `zip` crate, deflate) with the
//! content types, the package relationship and one model part, `unit="millimeter"`, one
//! `<object type="model">` per component and a build item for each; with [`Colours`], one base
//! material per face or volume type (`<basematerials>`, its colour as `displaycolor`) and every
//! triangle naming its type's material (`pid`, `p1`); with [`write_parts`], one object per type
//! of that type's material, put together as the components of one object. Written by hand over the zip
//! crate: the core model is a few elements, and no well-kept MIT/Apache 3MF writer crate fits
//! better than these lines.

use super::solid::{Part, Solid};
use std::io::{self, Seek, Write};
use zip::write::SimpleFileOptions;

const CONTENT_TYPES: &str = r#"<?xml version="1.0" encoding="UTF-8"?>
<Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types">
 <Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/>
 <Default Extension="model" ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/>
</Types>
"#;

const RELS: &str = r#"<?xml version="1.0" encoding="UTF-8"?>
<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">
 <Relationship Target="/3D/3dmodel.model" Id="rel0" Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/>
</Relationships>
"#;

fn xml_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

fn zip_error(e: zip::result::ZipError) -> io::Error {
    io::Error::other(e.to_string())
}

/// How a solid of cells of types is written as 3MF.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Style {
    /// One object per component, no material.
    Plain,
    /// One object per component, every triangle of its cell's type's material ([`Colours`]).
    Colours,
    /// One part per type, each of its type's material ([`write_parts`]).
    Parts,
}

/// The colour of every triangle of a solid: a base material per face or volume type.
#[derive(Clone, Debug)]
pub struct Colours {
    /// Per material (a type): its name and colour (RGB).
    pub materials: Vec<(String, [u8; 3])>,
    /// Per part, the material of each triangle.
    pub per_triangle: Vec<Vec<u32>>,
}

/// The id of the base materials resource (objects are numbered from 1).
const MATERIALS_ID: usize = 1;

/// The bytes of a 3MF package `f` builds in memory (a ZIP is written with seeks, so it is built
/// whole before the file at `path` is written): an error of `f` is the write error (E1005) of
/// `path`.
pub fn in_memory(
    path: &std::path::Path,
    f: impl FnOnce(&mut io::Cursor<Vec<u8>>) -> io::Result<()>,
) -> crate::error::Result<Vec<u8>> {
    let mut zip = io::Cursor::new(Vec::new());
    f(&mut zip).map_err(|e| crate::error::Error::Write {
        path: path.display().to_string(),
        reason: e.to_string(),
    })?;
    Ok(zip.into_inner())
}

/// Writes a solid as a 3MF package.
pub fn write<W: Write + Seek>(solid: &Solid, out: W) -> io::Result<()> {
    write_with(solid, None, out)
}

/// Writes a solid as a 3MF package, its triangles coloured by `colours` when given.
pub fn write_with<W: Write + Seek>(
    solid: &Solid,
    colours: Option<&Colours>,
    out: W,
) -> io::Result<()> {
    let objects: Vec<Object<'_>> = solid
        .parts
        .iter()
        .enumerate()
        .map(|(i, p)| Object {
            name: format!("component {i}"),
            part: p,
            material: colours.map(|c| c.per_triangle[i].first().copied().unwrap_or(0)),
            per_triangle: colours.map(|c| c.per_triangle[i].as_slice()),
        })
        .collect();
    let materials = colours.map_or(&[][..], |c| &c.materials[..]);
    write_model(
        &format!("{} level {}", solid.name, solid.level),
        materials,
        &objects,
        None,
        out,
    )
}

/// One object per type, each of its own colour, put together as the parts of one object
/// (`render --3mf-parts`): a multi-material slicer loads one object whose parts it can give
/// each an extruder. `parts` holds, per type, its name, colour and mesh.
pub fn write_parts<W: Write + Seek>(
    title: &str,
    parts: &[(String, [u8; 3], &Part)],
    out: W,
) -> io::Result<()> {
    let materials: Vec<(String, [u8; 3])> = parts.iter().map(|(n, c, _)| (n.clone(), *c)).collect();
    let objects: Vec<Object<'_>> = parts
        .iter()
        .enumerate()
        .map(|(i, (name, _, part))| Object {
            name: name.clone(),
            part,
            material: Some(i as u32),
            per_triangle: None,
        })
        .collect();
    write_model(title, &materials, &objects, Some(title), out)
}

/// A mesh object of the model: its name, mesh, material (index into the base materials) and,
/// optionally, a material per triangle.
struct Object<'a> {
    name: String,
    part: &'a Part,
    material: Option<u32>,
    per_triangle: Option<&'a [u32]>,
}

/// The package: materials (none: no `<basematerials>`), the mesh objects, and either one build
/// item per object or, with `group`, one object of that name made of them all as components.
fn write_model<W: Write + Seek>(
    title: &str,
    materials: &[(String, [u8; 3])],
    objects: &[Object<'_>],
    group: Option<&str>,
    out: W,
) -> io::Result<()> {
    let mut z = zip::ZipWriter::new(out);
    // Fast deflate: level 1 makes the model about as small as level 6 in a fraction of the time
    // (the XML is repetitive).
    let opts = SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Deflated)
        .compression_level(Some(1));
    z.start_file("[Content_Types].xml", opts)
        .map_err(zip_error)?;
    z.write_all(CONTENT_TYPES.as_bytes())?;
    z.start_file("_rels/.rels", opts).map_err(zip_error)?;
    z.write_all(RELS.as_bytes())?;
    z.start_file("3D/3dmodel.model", opts).map_err(zip_error)?;
    {
        let mut w = io::BufWriter::with_capacity(1 << 16, &mut z);
        writeln!(w, r#"<?xml version="1.0" encoding="UTF-8"?>"#)?;
        writeln!(
            w,
            r#"<model unit="millimeter" xml:lang="en-US" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">"#
        )?;
        writeln!(
            w,
            r#" <metadata name="Title">{}</metadata>"#,
            xml_escape(title)
        )?;
        writeln!(w, r#" <metadata name="Application">lacuna</metadata>"#)?;
        writeln!(w, " <resources>")?;
        // With materials they take id 1 and the objects follow.
        let first = usize::from(!materials.is_empty()) + 1;
        if !materials.is_empty() {
            writeln!(w, r#"  <basematerials id="{MATERIALS_ID}">"#)?;
            for (name, [r, g, b]) in materials {
                writeln!(
                    w,
                    r##"   <base name="{}" displaycolor="#{r:02X}{g:02X}{b:02X}FF"/>"##,
                    xml_escape(name)
                )?;
            }
            writeln!(w, "  </basematerials>")?;
        }
        for (i, o) in objects.iter().enumerate() {
            let material = o.material.map_or(String::new(), |m| {
                format!(r#" pid="{MATERIALS_ID}" pindex="{m}""#)
            });
            writeln!(
                w,
                r#"  <object id="{}" type="model" name="{}"{material}><mesh><vertices>"#,
                i + first,
                xml_escape(&o.name)
            )?;
            for v in &o.part.vertices {
                writeln!(w, r#"<vertex x="{}" y="{}" z="{}"/>"#, v[0], v[1], v[2])?;
            }
            writeln!(w, "</vertices><triangles>")?;
            for (k, t) in o.part.triangles.iter().enumerate() {
                match o.per_triangle {
                    Some(c) => writeln!(
                        w,
                        r#"<triangle v1="{}" v2="{}" v3="{}" pid="{MATERIALS_ID}" p1="{}"/>"#,
                        t[0], t[1], t[2], c[k]
                    )?,
                    None => writeln!(
                        w,
                        r#"<triangle v1="{}" v2="{}" v3="{}"/>"#,
                        t[0], t[1], t[2]
                    )?,
                }
            }
            writeln!(w, "</triangles></mesh></object>")?;
        }
        let items: Vec<usize> = match group {
            None => (first..first + objects.len()).collect(),
            Some(name) => {
                let id = first + objects.len();
                writeln!(
                    w,
                    r#"  <object id="{id}" type="model" name="{}"><components>"#,
                    xml_escape(name)
                )?;
                for i in 0..objects.len() {
                    writeln!(w, r#"   <component objectid="{}"/>"#, i + first)?;
                }
                writeln!(w, "  </components></object>")?;
                vec![id]
            }
        };
        writeln!(w, " </resources>\n <build>")?;
        for id in items {
            writeln!(w, r#"  <item objectid="{id}"/>"#)?;
        }
        writeln!(w, " </build>\n</model>")?;
        w.flush()?;
    }
    let mut inner = z.finish().map_err(zip_error)?;
    inner.flush()
}
