//! The library of named structures (plain-text fixtures shipped with lacuna) and the loading of
//! a command-line input: face notation, a file, or a library name.

use crate::assembly::Assembly;
use crate::autofrac::{is_autofrac, parse_autofrac};
use crate::error::{Error, Result, Source};
use crate::face::Face;

/// The named structures: `(name, text)`, each a file of `fixtures/`.
pub fn library() -> &'static [(&'static str, &'static str)] {
    &[
        ("F0", include_str!("../fixtures/F0.txt")),
        ("square-B2", include_str!("../fixtures/square-B2.txt")),
        ("triangle-C2", include_str!("../fixtures/triangle-C2.txt")),
        (
            "delayed-B2-C2",
            include_str!("../fixtures/delayed-B2-C2.txt"),
        ),
        ("two-quads", include_str!("../fixtures/two-quads.txt")),
        (
            "autofrac-two-quads",
            include_str!("../fixtures/autofrac-two-quads.txt"),
        ),
    ]
}

/// What the user asked to work on.
#[derive(Clone, Debug)]
pub struct Input {
    /// A short name for reports: the notation, the file path or the library name.
    pub name: String,
    /// The faces with their shared edges (a single face is an assembly of one).
    pub assembly: Assembly,
}

impl Input {
    /// The start faces.
    pub fn faces(&self) -> Vec<Face> {
        self.assembly.face_list()
    }
}

/// Parses a text in either file format (AutoFrac2D files start with an `f` line).
pub fn parse_text(src: &Source) -> Result<Assembly> {
    if is_autofrac(&src.text) {
        parse_autofrac(src)
    } else {
        Assembly::parse(src)
    }
}

/// Resolves a command-line argument: face notation when it contains `|`, otherwise a file path,
/// otherwise a library name.
pub fn load_input(arg: &str) -> Result<Input> {
    if arg.contains('|') {
        let face = Face::parse(arg)?;
        return Ok(Input {
            name: arg.trim().to_string(),
            assembly: Assembly {
                faces: vec![("0".into(), face)],
                shared: Vec::new(),
            },
        });
    }
    let path = std::path::Path::new(arg);
    if path.is_file() {
        let bytes = std::fs::read(path).map_err(|e| Error::Io {
            path: arg.into(),
            reason: e.to_string(),
        })?;
        let text = String::from_utf8(bytes).map_err(|e| Error::Io {
            path: arg.into(),
            reason: format!(
                "not UTF-8 text (invalid byte at offset {})",
                e.utf8_error().valid_up_to()
            ),
        })?;
        let src = Source {
            name: arg.into(),
            text,
        };
        return Ok(Input {
            name: arg.into(),
            assembly: parse_text(&src)?,
        });
    }
    if let Some((name, text)) = library().iter().find(|(n, _)| *n == arg) {
        let src = Source {
            name: format!("library:{name}"),
            text: text.to_string(),
        };
        return Ok(Input {
            name: name.to_string(),
            assembly: parse_text(&src)?,
        });
    }
    let names: Vec<&str> = library().iter().map(|(n, _)| *n).collect();
    Err(Error::Io {
        path: arg.into(),
        reason: format!(
            "no such file, and not face notation (no `|`) nor a library name ({})",
            names.join(", ")
        ),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_library_entry_loads() {
        for (name, _) in library() {
            let input = load_input(name).unwrap_or_else(|e| panic!("{name}: {}", e.render()));
            assert!(!input.faces().is_empty());
        }
        assert_eq!(load_input("no-such-thing").unwrap_err().code(), "E0601");
    }
}
