//! Volume inputs: the one-line volume notation on the command line (`cube B2 | B2 B2 B2 | A1 |
//! B2 B2 | V1`), or a file (or library entry) whose first line that is not a comment is
//! `volume NOTATION`.

use crate::error::{Error, Result, Source};
use crate::topology::volume::{parse_volume, Solid, Volume};

/// Whether a command-line argument is volume notation: it has `|` and starts with a solid name.
pub fn is_volume_notation(arg: &str) -> bool {
    arg.contains('|')
        && arg
            .split_whitespace()
            .next()
            .is_some_and(|w| Solid::parse(w).is_some())
}

/// Whether a file's text declares a volume.
pub fn is_volume_text(text: &str) -> bool {
    text.trim_start_matches('\u{feff}')
        .lines()
        .map(str::trim)
        .find(|l| !l.is_empty() && !l.starts_with('#'))
        .is_some_and(|l| l.starts_with("volume ") || l == "volume")
}

/// Parses a volume file: comments (`#`) and blank lines, and one `volume NOTATION` line.
pub fn parse_volume_text(src: &Source) -> Result<Volume> {
    let mut found: Option<Volume> = None;
    for (i, line) in src.text.lines().enumerate() {
        let line = line.trim_start_matches('\u{feff}');
        let t = line.trim();
        if t.is_empty() || t.starts_with('#') {
            continue;
        }
        let Some(rest) = line.trim_start().strip_prefix("volume") else {
            return Err(Error::syntax(
                "E1207",
                "a volume file has one `volume NOTATION` line and comments",
                crate::error::Span {
                    line: i + 1,
                    col: 1,
                    len: line.chars().count().max(1),
                },
                Some(src),
            ));
        };
        if found.is_some() {
            return Err(Error::syntax(
                "E1207",
                "a volume file has one `volume` line (assemblies of volumes are not read yet)",
                crate::error::Span {
                    line: i + 1,
                    col: 1,
                    len: line.chars().count().max(1),
                },
                Some(src),
            ));
        }
        let offset = line.chars().count() - rest.chars().count();
        found = Some(parse_volume(rest).map_err(|e| e.within(src, i + 1, offset))?);
    }
    found.ok_or_else(|| Error::Io {
        path: src.name.clone(),
        reason: "no `volume` line".into(),
    })
}
