//! An STL reader of its own (it shares nothing with lacuna's writer). Binary STL is an 80-byte
//! header, a little-endian `u32` triangle count and 50 bytes per triangle (normal, three corners,
//! `f32` each, and a 2-byte attribute); a file is binary when its size is exactly
//! `84 + 50·count`, whatever its header says (some writers start the header with `solid`). ASCII
//! STL is `solid NAME`, then `facet normal nx ny nz / outer loop / vertex x y z` ×3 `/ endloop /
//! endfacet` per triangle, then `endsolid NAME`; several solids may follow each other. Numbers
//! are read as `f32`, the precision of STL, so an ASCII file written with round-tripping decimals
//! describes the same mesh as its binary twin. Normals are read and not used: the order of the
//! corners decides the orientation, as for slicers.

use super::exact::Point;
use super::input::{check_limit, malformed, Format, Mesh, Welder};
use crate::error::{Error, Source};

/// Reads binary or ASCII STL.
pub(super) fn read(bytes: &[u8], name: &str, max_triangles: u64) -> Result<Mesh, Error> {
    if bytes.len() >= 84 {
        let count = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]);
        if bytes.len() as u64 == 84 + 50 * u64::from(count) {
            return binary(bytes, count, max_triangles);
        }
    }
    let text_start = bytes
        .iter()
        .position(|b| !b.is_ascii_whitespace())
        .unwrap_or(bytes.len());
    if bytes[text_start..].starts_with(b"solid") {
        return ascii(bytes, name, max_triangles);
    }
    if bytes.len() < 84 {
        return Err(malformed(
            "E1501",
            format!(
                "`{name}` is not a mesh: {} bytes, too short for binary STL (84 bytes at least), \
                 and not ASCII STL (which starts with `solid`) nor 3MF (a ZIP archive)",
                bytes.len()
            ),
        ));
    }
    let count = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]);
    Err(malformed(
        "E1501",
        format!(
            "`{name}` is not a whole binary STL: its header says {count} triangles, which take \
             {} bytes, and the file has {} (truncated, or not STL: it is neither ASCII STL nor 3MF)",
            84 + 50 * u64::from(count),
            bytes.len()
        ),
    ))
}

fn binary(bytes: &[u8], count: u32, max_triangles: u64) -> Result<Mesh, Error> {
    check_limit(u64::from(count), max_triangles)?;
    let mut w = Welder::new(Format::BinaryStl, "mm", count as usize);
    w.piece("the STL".into());
    for (t, rec) in bytes[84..].chunks_exact(50).enumerate() {
        let f = |k: usize| {
            let o = 12 + 4 * k;
            f64::from(f32::from_le_bytes([
                rec[o],
                rec[o + 1],
                rec[o + 2],
                rec[o + 3],
            ]))
        };
        let corners: [Point; 3] = [0, 1, 2].map(|c| [f(3 * c), f(3 * c + 1), f(3 * c + 2)]);
        if corners.iter().flatten().any(|x| !x.is_finite()) {
            return Err(malformed(
                "E1502",
                format!(
                    "triangle {t} (bytes {}–{}) has a coordinate that is not a finite number",
                    84 + 50 * t,
                    84 + 50 * t + 49
                ),
            ));
        }
        w.triangle(corners);
    }
    Ok(w.finish())
}

/// A word of an ASCII STL with its 1-based line and column.
struct Word<'a> {
    text: &'a str,
    line: usize,
    col: usize,
}

/// The words of a text, lazily (an ASCII STL may hold hundreds of millions). `solid NAME` and
/// `endsolid NAME`: the name is the rest of the line, skipped.
struct Words<'a> {
    lines: std::iter::Enumerate<std::str::Lines<'a>>,
    line: usize,
    rest: &'a str,
    col: usize,
}

impl<'a> Iterator for Words<'a> {
    type Item = Word<'a>;

    fn next(&mut self) -> Option<Word<'a>> {
        loop {
            if let Some(start) = self.rest.find(|c: char| !c.is_whitespace()) {
                self.col += self.rest[..start].chars().count();
                let rest = &self.rest[start..];
                let end = rest.find(char::is_whitespace).unwrap_or(rest.len());
                let word = Word {
                    text: &rest[..end],
                    line: self.line,
                    col: self.col,
                };
                self.col += word.text.chars().count();
                self.rest = match word.text {
                    "solid" | "endsolid" => "",
                    _ => &rest[end..],
                };
                return Some(word);
            }
            let (l, line) = self.lines.next()?;
            (self.line, self.rest, self.col) = (l + 1, line, 1);
        }
    }
}

fn ascii(bytes: &[u8], name: &str, max_triangles: u64) -> Result<Mesh, Error> {
    let text = String::from_utf8_lossy(bytes);
    let source = || Source {
        name: name.to_string(),
        text: text.to_string(),
    };
    let words = Words {
        lines: text.lines().enumerate(),
        line: 0,
        rest: "",
        col: 1,
    };
    let fail = |w: Option<&Word>, message: String| -> Error {
        match w {
            Some(w) => Error::at(
                "E1502",
                message,
                w.line,
                w.col,
                w.text.chars().count(),
                &source(),
            ),
            None => malformed(
                "E1502",
                format!("`{name}`: {message} at the end of the file"),
            ),
        }
    };
    let mut it = words.peekable();
    let expect = |want: &str, it: &mut std::iter::Peekable<Words<'_>>| {
        let w = it.next();
        match &w {
            Some(x) if x.text == want => Ok(()),
            Some(x) => Err(fail(
                w.as_ref(),
                format!("expected `{want}`, found `{}`", x.text),
            )),
            None => Err(fail(None, format!("expected `{want}`"))),
        }
    };
    let number = |it: &mut std::iter::Peekable<Words<'_>>| {
        let w = it.next();
        match w.as_ref().map(|w| w.text.parse::<f32>()) {
            Some(Ok(x)) if x.is_finite() => Ok(f64::from(x)),
            Some(_) => Err(fail(
                w.as_ref(),
                format!(
                    "`{}` is not a finite number",
                    w.as_ref().map_or("", |w| w.text)
                ),
            )),
            None => Err(fail(None, "expected a number".into())),
        }
    };
    let mut w = Welder::new(Format::AsciiStl, "mm", 0);
    w.piece("the STL".into());
    let mut count = 0u64;
    let mut solids = 0;
    while it.peek().is_some() {
        expect("solid", &mut it)?;
        solids += 1;
        loop {
            match it.peek().map(|w| w.text) {
                Some("endsolid") => {
                    it.next();
                    break;
                }
                Some("facet") => {}
                _ => {
                    let x = it.next();
                    return Err(fail(
                        x.as_ref(),
                        match &x {
                            Some(x) => {
                                format!("expected `facet` or `endsolid`, found `{}`", x.text)
                            }
                            None => "expected `facet` or `endsolid`".into(),
                        },
                    ));
                }
            }
            count += 1;
            check_limit(count, max_triangles)?;
            expect("facet", &mut it)?;
            expect("normal", &mut it)?;
            for _ in 0..3 {
                number(&mut it)?;
            }
            expect("outer", &mut it)?;
            expect("loop", &mut it)?;
            let mut corners = [[0.0; 3]; 3];
            for c in &mut corners {
                expect("vertex", &mut it)?;
                for x in c.iter_mut() {
                    *x = number(&mut it)?;
                }
            }
            expect("endloop", &mut it)?;
            expect("endfacet", &mut it)?;
            w.triangle(corners);
        }
    }
    if solids > 1 {
        w.note(format!(
            "{solids} solids in one ASCII STL, checked as one mesh"
        ));
    }
    Ok(w.finish())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ascii_and_binary_read_the_same_triangle() {
        let text = "solid t\nfacet normal 0 0 1\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n  \
                    vertex 0 0.1 0\n endloop\nendfacet\nendsolid t\n";
        let a = read(text.as_bytes(), "t.stl", 10).unwrap();
        assert_eq!(a.format, Format::AsciiStl);
        let mut b = vec![0u8; 84];
        b[80] = 1;
        let mut rec = vec![0u8; 50];
        for (k, x) in [0f32, 0., 1., 0., 0., 0., 1., 0., 0., 0., 0.1, 0.]
            .iter()
            .enumerate()
        {
            rec[4 * k..4 * k + 4].copy_from_slice(&x.to_le_bytes());
        }
        b.extend(rec);
        let m = read(&b, "t.stl", 10).unwrap();
        assert_eq!(m.format, Format::BinaryStl);
        assert_eq!(m.vertices, a.vertices);
        assert_eq!(m.vertices[2][1], f64::from(0.1f32));
        // Truncated: exit 2 material, E1501.
        let e = read(&b[..b.len() - 1], "t.stl", 10).unwrap_err();
        assert_eq!(e.code(), "E1501");
        // A limit, not a verdict.
        assert_eq!(read(&b, "t.stl", 0).unwrap_err().code(), "E0501");
    }

    #[test]
    fn ascii_errors_point_at_the_word() {
        let text = "solid t\nfacet normal 0 0 1\n outer loop\n  vertex 0 x 0\n";
        let e = read(text.as_bytes(), "t.stl", 10).unwrap_err();
        assert_eq!(e.code(), "E1502");
        assert!(e.render().contains("t.stl:4:12"), "{}", e.render());
        let e = read(b"solid t\nfacet normal 0 0 1\n", "t.stl", 10).unwrap_err();
        assert!(e.to_string().contains("end of the file"), "{e}");
    }
}
