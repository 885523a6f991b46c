//! The library of named structures (plain-text fixtures shipped with lacuna) and the loading of
//! a command-line input: face notation, a file, or a library name.

use crate::constraint::automaton::Automaton;
use crate::error::{Error, Result, Source};
use crate::input::assembly::Assembly;
use crate::input::autofrac::{is_autofrac, parse_autofrac};
use crate::input::automaton_model::{is_automaton_model, parse_model, AutomatonModel};
use crate::input::suggest::did_you_mean;
use crate::topology::face::Face;

/// The named structures: `(name, text)`, each a file of `fixtures/`.
pub fn library() -> &'static [(&'static str, &'static str)] {
    &[
        ("F0", include_str!("../../fixtures/F0.txt")),
        ("square-B2", include_str!("../../fixtures/square-B2.txt")),
        (
            "triangle-C2",
            include_str!("../../fixtures/triangle-C2.txt"),
        ),
        (
            "delayed-B2-C2",
            include_str!("../../fixtures/delayed-B2-C2.txt"),
        ),
        ("two-quads", include_str!("../../fixtures/two-quads.txt")),
        (
            "autofrac-two-quads",
            include_str!("../../fixtures/autofrac-two-quads.txt"),
        ),
        (
            "cycle-sqrt17",
            include_str!("../../fixtures/cycle-sqrt17.txt"),
        ),
        (
            "shared-radius-pentagons",
            include_str!("../../fixtures/shared-radius-pentagons.txt"),
        ),
        ("spec-edge", include_str!("../../fixtures/spec-edge.aut")),
        (
            "spec-edge-incidence",
            include_str!("../../fixtures/spec-edge-incidence.aut"),
        ),
        (
            "half-tangent-edge",
            include_str!("../../fixtures/half-tangent-edge.aut"),
        ),
        (
            "bspline-quadratic",
            include_str!("../../fixtures/bspline-quadratic.aut"),
        ),
        ("quad-patch", include_str!("../../fixtures/quad-patch.aut")),
        (
            "de-casteljau-edge",
            include_str!("../../fixtures/de-casteljau-edge.aut"),
        ),
        (
            "chaikin-known",
            include_str!("../../fixtures/chaikin-known.aut"),
        ),
        ("cube-B2", include_str!("../../fixtures/cube-B2.txt")),
        (
            "tetrahedron-B2",
            include_str!("../../fixtures/tetrahedron-B2.txt"),
        ),
        (
            "de-casteljau-cubic",
            include_str!("../../fixtures/de-casteljau-cubic.aut"),
        ),
        (
            "bspline-quadratic-4",
            include_str!("../../fixtures/bspline-quadratic-4.aut"),
        ),
        (
            "bspline-cubic",
            include_str!("../../fixtures/bspline-cubic.aut"),
        ),
        (
            "quad-patch-3d",
            include_str!("../../fixtures/quad-patch-3d.aut"),
        ),
        (
            "sierpinski-triangle",
            include_str!("../../fixtures/sierpinski-triangle.aut"),
        ),
        ("cantor-set", include_str!("../../fixtures/cantor-set.aut")),
        ("cube-C2", include_str!("../../fixtures/cube-C2.txt")),
        (
            "truncated-tetrahedron",
            include_str!("../../fixtures/truncated-tetrahedron.txt"),
        ),
        ("two-cubes", include_str!("../../fixtures/two-cubes.txt")),
        ("kite-dart", include_str!("../../fixtures/kite-dart.aut")),
        (
            "penrose-robinson",
            include_str!("../../fixtures/penrose-robinson.aut"),
        ),
        (
            "sierpinski-carpet",
            include_str!("../../fixtures/sierpinski-carpet.aut"),
        ),
        (
            "lemniscate-fractal",
            include_str!("../../fixtures/lemniscate-fractal.aut"),
        ),
        (
            "rose-fractal",
            include_str!("../../fixtures/rose-fractal.aut"),
        ),
        ("gasket-3", include_str!("../../fixtures/gasket-3.aut")),
        ("gasket-4", include_str!("../../fixtures/gasket-4.aut")),
        ("gasket-5", include_str!("../../fixtures/gasket-5.aut")),
        ("gasket-6", include_str!("../../fixtures/gasket-6.aut")),
        ("gasket-7", include_str!("../../fixtures/gasket-7.aut")),
        ("gasket-8", include_str!("../../fixtures/gasket-8.aut")),
        (
            "quadric-koch",
            include_str!("../../fixtures/quadric-koch.rule"),
        ),
        ("koch", include_str!("../../fixtures/koch.rule")),
        (
            "sierpinski-arrowhead",
            include_str!("../../fixtures/sierpinski-arrowhead.rule"),
        ),
        (
            "heighway-dragon",
            include_str!("../../fixtures/heighway-dragon.rule"),
        ),
        (
            "pythagoras-tree",
            include_str!("../../fixtures/pythagoras-tree.rule"),
        ),
        (
            "self-seeding-square",
            include_str!("../../fixtures/self-seeding-square.rule"),
        ),
        ("vegetation", include_str!("../../fixtures/vegetation.rule")),
        (
            "random-tree",
            include_str!("../../fixtures/random-tree.rule"),
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

/// What a library entry (or any input text) is: `volume`, `rule`, `automaton`, `assembly` (faces
/// with shared edges, or several faces) or `face` (one face).
pub fn kind_of(text: &str) -> &'static str {
    if crate::input::volume_file::is_volume_text(text) {
        "volume"
    } else if crate::input::rule::is_rule(text) {
        "rule"
    } else if is_automaton_model(text) {
        "automaton"
    } else {
        let src = Source {
            name: String::new(),
            text: text.to_string(),
        };
        match parse_text(&src) {
            Ok(a) if a.faces.len() == 1 && a.shared.is_empty() => "face",
            _ => "assembly",
        }
    }
}

/// What a command-line argument names: faces (a face, an assembly) or a hand-written automaton.
#[derive(Clone, Debug)]
#[allow(clippy::large_enum_variant)]
pub enum Loaded {
    /// Faces with their shared edges.
    Faces(Input),
    /// A hand-written automaton.
    Automaton {
        /// The file path or library name.
        name: String,
        /// The automaton.
        automaton: Automaton,
        /// The automaton with its modelling lines (field, space, points, primitives).
        model: Box<AutomatonModel>,
    },
}

/// Resolves a command-line argument: face notation when it contains `|`, otherwise a file path,
/// otherwise a library name. Files and library entries are automata when their first line
/// declares a state.
pub fn load_any(arg: &str) -> Result<Loaded> {
    // An empty argument is an empty face notation (E0101), not a file name.
    if arg.contains('|') || arg.trim().is_empty() {
        let face = Face::parse(arg)?;
        return Ok(Loaded::Faces(Input {
            name: arg.trim().to_string(),
            assembly: Assembly {
                faces: vec![("0".into(), face)],
                shared: Vec::new(),
                coords: Default::default(),
            },
        }));
    }
    let (name, src) = read_source(arg)?;
    // Face notation piped in: one line with `|` (comments and blank lines aside) that is no
    // line of a file format (those name a face with `face NAME:`).
    if arg == "-" {
        let lines: Vec<&str> = src
            .text
            .lines()
            .map(|l| l.split('#').next().unwrap_or("").trim())
            .filter(|l| !l.is_empty())
            .collect();
        if let [line] = lines[..] {
            if line.contains('|') && !line.contains(':') {
                let face = Face::parse(line)?;
                return Ok(Loaded::Faces(Input {
                    name: line.to_string(),
                    assembly: Assembly {
                        faces: vec![("0".into(), face)],
                        shared: Vec::new(),
                        coords: Default::default(),
                    },
                }));
            }
        }
    }
    if crate::input::volume_file::is_volume_text(&src.text) {
        return Err(Error::Io {
            path: name,
            reason: "this is a volume: `closure`, `counts`, `ratio`, `verify`, `solve`, `render`, `measure` and `report` read volumes"
                .into(),
        });
    }
    // A `.rule` file is read by the rule grammar even when its `initiator` line is misspelt, so
    // that its errors are the rule grammar's.
    if src.name.ends_with(".rule") || crate::input::rule::is_rule(&src.text) {
        let (_, model) = crate::input::rule::compile_rule(&src)?;
        return Ok(Loaded::Automaton {
            name,
            automaton: model.automaton.clone(),
            model: Box::new(model),
        });
    }
    if is_automaton_model(&src.text) {
        let model = parse_model(&src)?;
        return Ok(Loaded::Automaton {
            name,
            automaton: model.automaton.clone(),
            model: Box::new(model),
        });
    }
    Ok(Loaded::Faces(Input {
        name,
        assembly: parse_text(&src)?,
    }))
}

/// Like [`load_any`], for commands that work on faces only.
pub fn load_input(arg: &str) -> Result<Input> {
    match load_any(arg)? {
        Loaded::Faces(input) => Ok(input),
        Loaded::Automaton { name, .. } => Err(Error::Io {
            path: name,
            reason: "this is an automaton, not faces: `verify`, `solve`, `operators`, `render`, `measure` and `report` read automata; this command reads faces only".into(),
        }),
    }
}

/// The volume a command-line argument names, if it names one: notation, a file or a library
/// entry. `None` when the argument is something else (faces, an automaton, nothing readable).
pub fn load_volume(arg: &str) -> Result<Option<(String, crate::topology::volume::Volume)>> {
    // Standard input is read once, by the loader of faces and automata.
    if arg == "-" {
        return Ok(None);
    }
    if arg.contains('|') {
        return match crate::input::volume_file::is_volume_notation(arg) {
            true => Ok(Some((
                arg.trim().to_string(),
                crate::topology::volume::parse_volume(arg)?,
            ))),
            false => Ok(None),
        };
    }
    match read_source(arg) {
        Ok((name, src)) if crate::input::volume_file::is_volume_text(&src.text) => Ok(Some((
            name,
            crate::input::volume_file::parse_volume_text(&src)?,
        ))),
        _ => Ok(None),
    }
}

/// The volumes a command-line argument names, if it names volumes: notation, or a volume file
/// or library entry (one volume or several glued face to face). `None` when the argument is
/// something else.
pub fn load_volumes(
    arg: &str,
) -> Result<Option<(String, crate::topology::volume::VolumeAssembly)>> {
    Ok(load_volume_file(arg)?.map(|(name, f)| (name, f.assembly)))
}

/// The volume file a command-line argument names (notation, a file or a library entry), with
/// the volumes' user coordinates; `None` when the argument is something else.
pub fn load_volume_file(arg: &str) -> Result<Option<(String, crate::input::VolumeFile)>> {
    if arg == "-" {
        return Ok(None);
    }
    if arg.contains('|') {
        return match crate::input::volume_file::is_volume_notation(arg) {
            true => Ok(Some((
                arg.trim().to_string(),
                crate::input::volume_file::notation_file(arg)?,
            ))),
            false => Ok(None),
        };
    }
    match read_source(arg) {
        Ok((name, src)) if crate::input::volume_file::is_volume_text(&src.text) => Ok(Some((
            name,
            crate::input::volume_file::parse_volume_file(&src)?,
        ))),
        _ => Ok(None),
    }
}

/// Reads a text file, or standard input for `-`: UTF-8 (else E0602, naming the offset of the
/// first invalid byte), without a leading byte-order mark (editors on some systems write one; it
/// is not part of the text). A file that cannot be read is E0601.
pub fn read_text(path: &str) -> Result<String> {
    let bytes = if path == "-" {
        // Standard input is read once and kept: a command may look at its input more than once
        // (its kind, then its content).
        static STDIN: std::sync::OnceLock<Result<Vec<u8>, String>> = std::sync::OnceLock::new();
        STDIN
            .get_or_init(|| {
                let mut b = Vec::new();
                std::io::Read::read_to_end(&mut std::io::stdin(), &mut b)
                    .map(|_| b)
                    .map_err(|e| e.to_string())
            })
            .clone()
            .map_err(|reason| Error::Io {
                path: "<standard input>".into(),
                reason,
            })?
    } else {
        std::fs::read(path).map_err(|e| Error::Io {
            path: path.into(),
            reason: e.to_string(),
        })?
    };
    let bom = if bytes.starts_with(b"\xEF\xBB\xBF") {
        3
    } else {
        0
    };
    String::from_utf8(bytes[bom..].to_vec()).map_err(|e| Error::NotText {
        path: if path == "-" {
            "<standard input>".into()
        } else {
            path.into()
        },
        offset: bom + e.utf8_error().valid_up_to(),
    })
}

/// Reads a file, standard input (`-`) or a library entry as text.
fn read_source(arg: &str) -> Result<(String, Source)> {
    let path = std::path::Path::new(arg);
    if arg == "-" || path.is_file() {
        let name = if arg == "-" { "<standard input>" } else { arg };
        let text = read_text(arg)?;
        return Ok((
            name.into(),
            Source {
                name: name.into(),
                text,
            },
        ));
    }
    if let Some((name, text)) = library().iter().find(|(n, _)| *n == arg) {
        return Ok((
            name.to_string(),
            Source {
                name: format!("library:{name}"),
                text: text.to_string(),
            },
        ));
    }
    let names: Vec<&str> = library().iter().map(|(n, _)| *n).collect();
    let reason = match did_you_mean(arg, &names) {
        Some(best) => format!(
            "no such file, and not face notation (no `|`) nor a library name: did you mean \
             `{best}`? (`lacuna library` lists the {} entries)",
            names.len()
        ),
        None => format!(
            "no such file, and not face notation (no `|`) nor a library name ({})",
            names.join(", ")
        ),
    };
    Err(Error::Io {
        path: arg.into(),
        reason,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn misspelt_names_are_matched_to_the_closest_entry() {
        let names = ["F0", "sierpinski-triangle", "koch", "cube-B2"];
        // One letter swapped (y for i), case only, one letter missing.
        assert_eq!(
            did_you_mean("sierpinsky-triangle", &names),
            Some("sierpinski-triangle")
        );
        assert_eq!(did_you_mean("f0", &names), Some("F0"));
        assert_eq!(did_you_mean("cube-b", &names), Some("cube-B2"));
        // Nothing near: no guess.
        assert_eq!(did_you_mean("dragon", &names), None);
    }

    #[test]
    fn kinds_by_content() {
        assert_eq!(kind_of("face 0: B2 B2 B2 B2 | B2 B2 B2 | A1\n"), "face");
        assert_eq!(kind_of("state e 2\n"), "automaton");
        assert_eq!(
            kind_of("# x\ninitiator 0,0 g 1,0\ngenerator g 0,0 g 1,0\n"),
            "rule"
        );
        assert_eq!(
            kind_of(include_str!("../../fixtures/two-quads.txt")),
            "assembly"
        );
        assert_eq!(
            kind_of(include_str!("../../fixtures/cube-B2.txt")),
            "volume"
        );
    }

    #[test]
    fn every_library_entry_loads() {
        for (name, text) in library() {
            if crate::input::volume_file::is_volume_text(text) {
                let (_, a) = load_volumes(name)
                    .unwrap_or_else(|e| panic!("{name}: {}", e.render()))
                    .unwrap_or_else(|| panic!("{name}: not read as a volume"));
                for v in &a.volumes {
                    assert_eq!(v.surface.check(), Ok(()), "{name}");
                }
                continue;
            }
            match load_any(name).unwrap_or_else(|e| panic!("{name}: {}", e.render())) {
                Loaded::Faces(input) => assert!(!input.faces().is_empty()),
                Loaded::Automaton { automaton, .. } => assert!(!automaton.states.is_empty()),
            }
        }
        assert_eq!(load_input("no-such-thing").unwrap_err().code(), "E0601");
    }
}
