//! A minimal 3MF reader of its own (it shares nothing with lacuna's writer): the package is a ZIP
//! archive (`zip`); its root relationship (`_rels/.rels`) names the model part, by default
//! `3D/3dmodel.model`, which is XML (`quick-xml`, streamed, so the triangle limit holds before
//! the whole model is in memory). Read: the `unit` of the `<model>`, every `<object>` with a
//! `<mesh>` (`<vertex x y z/>`, `<triangle v1 v2 v3/>`), and the `<build>` items, in order: the
//! mesh checked is the objects the build prints. Numbers are `xs:double` in the specification and
//! are read as the nearest `f64` (Rust's correctly rounded parsing), the value they denote.
//!
//! Not supported, refused with E1503 rather than guessed: `<components>` (objects made of other
//! objects), build items or components with a `transform` other than the identity, and an
//! encrypted or otherwise unreadable part.

use super::input::{check_limit, malformed, Format, Mesh, Welder};
use crate::error::Error;
use quick_xml::events::{BytesStart, Event};
use std::collections::BTreeMap;
use std::io::{BufReader, Read};

/// An object with its mesh, as the file gives it.
#[derive(Default)]
struct Object {
    vertices: Vec<[f64; 3]>,
    triangles: Vec<[u32; 3]>,
}

fn bad(name: &str, message: String) -> Error {
    malformed("E1503", format!("`{name}`: {message}"))
}

/// The attributes of an element by local name, raw.
fn attributes(e: &BytesStart<'_>) -> Result<BTreeMap<String, String>, String> {
    let mut out = BTreeMap::new();
    for a in e.attributes() {
        let a = a.map_err(|e| e.to_string())?;
        let key = String::from_utf8_lossy(a.key.local_name().as_ref()).to_string();
        let value = String::from_utf8_lossy(&a.value).trim().to_string();
        out.insert(key, value);
    }
    Ok(out)
}

/// Reads a 3MF package.
pub(super) fn read(bytes: &[u8], name: &str, max_triangles: u64) -> Result<Mesh, Error> {
    let mut zip = zip::ZipArchive::new(std::io::Cursor::new(bytes))
        .map_err(|e| bad(name, format!("not a readable ZIP archive ({e})")))?;
    let model_path = model_part(&mut zip, name)?;
    let entry = zip.by_name(&model_path).map_err(|e| {
        bad(
            name,
            format!("no model part `{model_path}` in the package ({e})"),
        )
    })?;
    let mut reader = quick_xml::Reader::from_reader(BufReader::new(entry));
    let at = |r: &quick_xml::Reader<_>| format!("{model_path}, byte {}", r.buffer_position());
    let mut buf = Vec::new();
    let mut objects: BTreeMap<String, Object> = BTreeMap::new();
    let mut order: Vec<String> = Vec::new();
    let mut current: Option<String> = None;
    let mut items: Vec<String> = Vec::new();
    let mut unit = "millimeter".to_string();
    let (mut triangles, mut vertices) = (0u64, 0u64);
    loop {
        let ev = reader
            .read_event_into(&mut buf)
            .map_err(|e| bad(name, format!("XML error at {}: {e}", at(&reader))))?;
        let (e, empty) = match &ev {
            Event::Start(e) => (e, false),
            Event::Empty(e) => (e, true),
            Event::End(e) => {
                if e.local_name().as_ref() == b"object" {
                    current = None;
                }
                buf.clear();
                continue;
            }
            Event::Eof => break,
            _ => {
                buf.clear();
                continue;
            }
        };
        let local = e.local_name();
        let tag = local.as_ref();
        let attrs = || {
            attributes(e).map_err(|m| bad(name, format!("bad attribute at {}: {m}", at(&reader))))
        };
        let number = |a: &BTreeMap<String, String>, key: &str| -> Result<f64, Error> {
            let v = a.get(key).ok_or_else(|| {
                bad(
                    name,
                    format!("a <vertex> without `{key}` at {}", at(&reader)),
                )
            })?;
            match v.parse::<f64>() {
                Ok(x) if x.is_finite() => Ok(x),
                _ => Err(bad(
                    name,
                    format!("`{key}=\"{v}\"` is not a finite number at {}", at(&reader)),
                )),
            }
        };
        match tag {
            b"model" => {
                if let Some(u) = attrs()?.get("unit") {
                    unit = u.clone();
                }
            }
            b"object" => {
                let a = attrs()?;
                let id = a.get("id").cloned().ok_or_else(|| {
                    bad(
                        name,
                        format!("an <object> without an id at {}", at(&reader)),
                    )
                })?;
                if objects.contains_key(&id) {
                    return Err(bad(
                        name,
                        format!("object id {id} given twice at {}", at(&reader)),
                    ));
                }
                objects.insert(id.clone(), Object::default());
                order.push(id.clone());
                current = (!empty).then_some(id);
            }
            b"vertex" => {
                let a = attrs()?;
                let p = [number(&a, "x")?, number(&a, "y")?, number(&a, "z")?];
                vertices += 1;
                if vertices > max_triangles.saturating_mul(3) {
                    return Err(Error::limit(
                        "the number of vertices (a limit, not a verdict on the mesh)",
                        vertices,
                        max_triangles.saturating_mul(3),
                        "--max-triangles (3 vertices per triangle)",
                    ));
                }
                match current.as_ref().and_then(|id| objects.get_mut(id)) {
                    Some(o) => o.vertices.push(p),
                    None => {
                        return Err(bad(
                            name,
                            format!("a <vertex> outside an <object> at {}", at(&reader)),
                        ))
                    }
                }
            }
            b"triangle" => {
                let a = attrs()?;
                let mut t = [0u32; 3];
                for (k, key) in ["v1", "v2", "v3"].iter().enumerate() {
                    t[k] = a.get(*key).and_then(|v| v.parse().ok()).ok_or_else(|| {
                        bad(
                            name,
                            format!(
                                "a <triangle> whose `{key}` is missing or not an index at {}",
                                at(&reader)
                            ),
                        )
                    })?;
                }
                triangles += 1;
                check_limit(triangles, max_triangles)?;
                match current.as_ref().and_then(|id| objects.get_mut(id)) {
                    Some(o) => o.triangles.push(t),
                    None => {
                        return Err(bad(
                            name,
                            format!("a <triangle> outside an <object> at {}", at(&reader)),
                        ))
                    }
                }
            }
            b"component" | b"components" => {
                return Err(bad(
                    name,
                    format!(
                        "objects made of components are not supported by check-mesh (at {}); \
                         give each object its own <mesh>",
                        at(&reader)
                    ),
                ))
            }
            b"item" => {
                let a = attrs()?;
                if let Some(tr) = a.get("transform") {
                    if !is_identity(tr) {
                        return Err(bad(
                            name,
                            format!(
                                "a build item with transform \"{tr}\" at {}: transforms are not \
                                 supported by check-mesh (the check runs on the file's own \
                                 coordinates)",
                                at(&reader)
                            ),
                        ));
                    }
                }
                let id = a.get("objectid").cloned().ok_or_else(|| {
                    bad(
                        name,
                        format!("a build <item> without objectid at {}", at(&reader)),
                    )
                })?;
                items.push(id);
            }
            _ => {}
        }
        buf.clear();
    }
    if items.is_empty() {
        return Err(bad(
            name,
            "the <build> has no item: the package prints nothing".into(),
        ));
    }
    let mut w = Welder::new(Format::ThreeMf, &unit, triangles as usize);
    let mut welded = 0usize;
    for id in &items {
        let o = objects.get(id).ok_or_else(|| {
            bad(
                name,
                format!("a build item names object {id}, which is not defined"),
            )
        })?;
        w.piece(format!("object {id}"));
        let index: Vec<u32> = o.vertices.iter().map(|p| w.vertex(*p)).collect();
        let mut seen = index.clone();
        seen.sort_unstable();
        seen.dedup();
        welded += index.len() - seen.len();
        for (k, t) in o.triangles.iter().enumerate() {
            let mut v = [0u32; 3];
            for c in 0..3 {
                v[c] = *index.get(t[c] as usize).ok_or_else(|| {
                    bad(
                        name,
                        format!(
                            "object {id} triangle {k} names vertex {}, and the object has {}",
                            t[c],
                            index.len()
                        ),
                    )
                })?;
            }
            w.triangle_of(v);
        }
    }
    let unused = order.iter().filter(|id| !items.contains(id)).count();
    if unused > 0 {
        w.note(format!(
            "{} not in the build, not checked (they are not printed)",
            match unused {
                1 => "1 object".to_string(),
                n => format!("{n} objects"),
            }
        ));
    }
    if welded > 0 {
        w.note(format!(
            "{welded} vertex index(es) at the same coordinates as another of its object: one vertex each"
        ));
    }
    Ok(w.finish())
}

/// The model part named by the package's root relationships, or `3D/3dmodel.model`.
fn model_part<R: Read + std::io::Seek>(
    zip: &mut zip::ZipArchive<R>,
    name: &str,
) -> Result<String, Error> {
    let mut rels = String::new();
    match zip.by_name("_rels/.rels") {
        Ok(f) => {
            f.take(1 << 20)
                .read_to_string(&mut rels)
                .map_err(|e| bad(name, format!("`_rels/.rels` cannot be read ({e})")))?;
        }
        Err(_) => return Ok("3D/3dmodel.model".into()),
    }
    let mut reader = quick_xml::Reader::from_str(&rels);
    loop {
        match reader.read_event() {
            Ok(Event::Start(e)) | Ok(Event::Empty(e))
                if e.local_name().as_ref() == b"Relationship" =>
            {
                let a = attributes(&e).map_err(|m| bad(name, format!("`_rels/.rels`: {m}")))?;
                if a.get("Type").is_some_and(|t| t.ends_with("/3dmodel")) {
                    if let Some(t) = a.get("Target") {
                        return Ok(t.trim_start_matches('/').to_string());
                    }
                }
            }
            Ok(Event::Eof) => return Ok("3D/3dmodel.model".into()),
            Err(e) => return Err(bad(name, format!("`_rels/.rels` is not XML ({e})"))),
            _ => {}
        }
    }
}

/// Whether a 3MF transform (`m00 m01 m02 m10 … m32`, twelve numbers) is the identity.
fn is_identity(tr: &str) -> bool {
    let v: Vec<Option<f64>> = tr.split_whitespace().map(|x| x.parse().ok()).collect();
    let id = [1., 0., 0., 0., 1., 0., 0., 0., 1., 0., 0., 0.];
    v.len() == 12 && v.iter().zip(id).all(|(x, y)| *x == Some(y))
}
