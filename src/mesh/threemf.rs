//! 3MF writer (3MF Core Specification 1.x): a ZIP package (the `zip` crate, deflate) with the
//! content types, the package relationship and one model part, `unit="millimeter"`, one
//! `<object type="model">` per component and a build item for each; with [`Colours`], one base
//! material per face type (`<basematerials>`, its colour as `displaycolor`) and every triangle
//! naming its type's material (`pid`, `p1`). Written by hand over the zip
//! crate: the core model is a few elements, and no well-kept MIT/Apache 3MF writer crate fits
//! better than these lines.

use super::solid::Solid;
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

/// The colour of every triangle of a solid: a base material per face type.
#[derive(Clone, Debug)]
pub struct Colours {
    /// Per material (face type): its name and colour (RGB).
    pub materials: Vec<(String, [u8; 3])>,
    /// Per part, the material of each triangle.
    pub per_triangle: Vec<Vec<u32>>,
}

/// The id of the base materials resource (objects are numbered from 1).
const MATERIALS_ID: usize = 1;

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
            r#" <metadata name="Title">{} level {}</metadata>"#,
            xml_escape(&solid.name),
            solid.level
        )?;
        writeln!(w, r#" <metadata name="Application">lacuna</metadata>"#)?;
        writeln!(w, " <resources>")?;
        // With colours the materials take id 1 and the objects follow.
        let first = usize::from(colours.is_some()) + 1;
        if let Some(c) = colours {
            writeln!(w, r#"  <basematerials id="{MATERIALS_ID}">"#)?;
            for (name, [r, g, b]) in &c.materials {
                writeln!(
                    w,
                    r##"   <base name="{}" displaycolor="#{r:02X}{g:02X}{b:02X}FF"/>"##,
                    xml_escape(name)
                )?;
            }
            writeln!(w, "  </basematerials>")?;
        }
        for (i, p) in solid.parts.iter().enumerate() {
            let material = colours.map_or(String::new(), |c| {
                let m = c.per_triangle[i].first().copied().unwrap_or(0);
                format!(r#" pid="{MATERIALS_ID}" pindex="{m}""#)
            });
            writeln!(
                w,
                r#"  <object id="{}" type="model" name="component {i}"{material}><mesh><vertices>"#,
                i + first
            )?;
            for v in &p.vertices {
                writeln!(w, r#"<vertex x="{}" y="{}" z="{}"/>"#, v[0], v[1], v[2])?;
            }
            writeln!(w, "</vertices><triangles>")?;
            for (k, t) in p.triangles.iter().enumerate() {
                match colours {
                    Some(c) => writeln!(
                        w,
                        r#"<triangle v1="{}" v2="{}" v3="{}" pid="{MATERIALS_ID}" p1="{}"/>"#,
                        t[0], t[1], t[2], c.per_triangle[i][k]
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
        writeln!(w, " </resources>\n <build>")?;
        for i in 0..solid.parts.len() {
            writeln!(w, r#"  <item objectid="{}"/>"#, i + first)?;
        }
        writeln!(w, " </build>\n</model>")?;
        w.flush()?;
    }
    let mut inner = z.finish().map_err(zip_error)?;
    inner.flush()
}
