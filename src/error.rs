//! Errors with stable codes and source spans, and their rendering.
//!
//! Every user-facing failure is an [`Error`] with a stable code (`E0103`, …; the table is in
//! `docs/ERRORS.md`) and, where there is a source text, the span it points at. "The recursion did
//! not close" is *not* an error: it is [`crate::topology::Closure::Runaway`].

use serde::Serialize;
use std::fmt;

/// A place in a source text: 1-based line and column (in characters), and a length.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Span {
    /// 1-based line.
    pub line: usize,
    /// 1-based column, counted in characters.
    pub col: usize,
    /// Number of characters underlined (at least 1 when rendered).
    pub len: usize,
}

/// Where a source text came from, and the text itself (for rendering the offending line).
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Source {
    /// A file path, or `<command line>`.
    pub name: String,
    /// The whole text.
    pub text: String,
}

impl Source {
    /// A source given on the command line.
    pub fn command_line(text: &str) -> Self {
        Source {
            name: "<command line>".into(),
            text: text.into(),
        }
    }
}

/// A located diagnostic: a stable code, a message, and optionally a source span.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Diagnostic {
    /// Stable code, e.g. `E0103`.
    pub code: &'static str,
    /// One-line message.
    pub message: String,
    /// Where in the source, if the error has a source.
    pub span: Option<Span>,
    /// The source name and text, if any.
    #[serde(skip)]
    pub source: Option<Source>,
}

/// Everything that can go wrong in lacuna. `Display` gives the one-line message; [`Error::render`]
/// gives the full diagnostic with the source line and a caret.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A syntax or validity error in a text (face notation, assembly file, AutoFrac2D file).
    #[error("{}", .0.message)]
    Syntax(Box<Diagnostic>),
    /// A face whose spoke rule chooses no junction: no lacuna can be placed.
    #[error("face `{face}` gets no spoke under {algorithm}: no lacuna can be placed")]
    NoSpoke {
        /// The face, in canonical notation.
        face: String,
        /// The algorithm.
        algorithm: String,
    },
    /// Flags that do not fit the input or each other (nothing to write, an option that needs an
    /// automaton, an operator that is not there, …).
    #[error("{0}")]
    Usage(String),
    /// A flag's value outside the range the command accepts (not a configurable limit).
    #[error("{flag} {value}: {what} must be {range}")]
    OutOfRange {
        /// The flag.
        flag: &'static str,
        /// The value given.
        value: String,
        /// What the flag sets.
        what: &'static str,
        /// The accepted values, in words.
        range: String,
    },
    /// A configurable limit was exceeded before the work started.
    #[error("{what} is {value}, above the limit {limit} (raise it with {flag})")]
    Limit {
        /// What was measured.
        what: &'static str,
        /// The value found.
        value: String,
        /// The limit in force.
        limit: String,
        /// The command-line flag that sets it.
        flag: &'static str,
    },
    /// The stated bound proves a closure finite, but larger than a configured limit (THEORY §4):
    /// a resource bound, not a verdict, so never reported as a runaway.
    #[error("closes: {proved} proved, above {flag} {limit} ({detail})")]
    ProvedAboveLimit {
        /// What the bound proves, in words (`boundary length ≤ 285`).
        proved: String,
        /// The limit's flag.
        flag: &'static str,
        /// The limit in force.
        limit: String,
        /// What was met and what to raise.
        detail: String,
    },
    /// A command that needs a closed closure met a runaway one.
    #[error("the closure did not close: {reason}; the witness chain has {chain} types (`lacuna closure` shows it)")]
    Runaway {
        /// The limit that was hit.
        reason: String,
        /// Length of the witness chain.
        chain: usize,
    },
    /// An exact analysis could not be completed (for instance a factoring budget ran out).
    #[error("analysis failed: {0}")]
    Analysis(String),
    /// An input file is not UTF-8 text.
    #[error("`{path}` is not UTF-8 text (invalid byte at offset {offset})")]
    NotText {
        /// The path.
        path: String,
        /// Byte offset of the first invalid byte.
        offset: usize,
    },
    /// An output file could not be written (the message says which outputs were written before).
    #[error("cannot write `{path}`: {reason}")]
    Write {
        /// The path.
        path: String,
        /// Why.
        reason: String,
    },
    /// An input file could not be read.
    #[error("cannot read `{path}`: {reason}")]
    Io {
        /// The path.
        path: String,
        /// Why.
        reason: String,
    },
}

impl Error {
    /// A syntax error at a span of a source.
    pub fn syntax(
        code: &'static str,
        message: impl Into<String>,
        span: Span,
        source: Option<&Source>,
    ) -> Self {
        Error::Syntax(Box::new(Diagnostic {
            code,
            message: message.into(),
            span: Some(span),
            source: source.cloned(),
        }))
    }

    /// A syntax error at line `line`, column `col` (1-based), `len` characters long, of `src`.
    pub fn at(
        code: &'static str,
        message: impl Into<String>,
        line: usize,
        col: usize,
        len: usize,
        src: &Source,
    ) -> Self {
        Self::syntax(
            code,
            message,
            Span {
                line,
                col,
                len: len.max(1),
            },
            Some(src),
        )
    }

    /// A limit error: `what` is `value`, above `limit` (raise it with `flag`).
    pub fn limit(
        what: &'static str,
        value: impl std::fmt::Display,
        limit: impl std::fmt::Display,
        flag: &'static str,
    ) -> Self {
        Error::Limit {
            what,
            value: value.to_string(),
            limit: limit.to_string(),
            flag,
        }
    }

    /// The stable error code.
    pub fn code(&self) -> &'static str {
        match self {
            Error::Syntax(d) => d.code,
            Error::NoSpoke { .. } => "E0401",
            Error::Limit { .. } | Error::ProvedAboveLimit { .. } => "E0501",
            Error::OutOfRange { .. } => "E0503",
            Error::Usage(_) => "E0504",
            Error::Io { .. } => "E0601",
            Error::Write { .. } => "E1005",
            Error::NotText { .. } => "E0602",
            Error::Analysis(_) => "E0801",
            Error::Runaway { .. } => "E0502",
        }
    }

    /// The span, when the error points into a source text.
    pub fn span(&self) -> Option<&Span> {
        match self {
            Error::Syntax(d) => d.span.as_ref(),
            Error::NoSpoke { .. }
            | Error::Limit { .. }
            | Error::ProvedAboveLimit { .. }
            | Error::OutOfRange { .. }
            | Error::Usage(_)
            | Error::Io { .. }
            | Error::Write { .. }
            | Error::NotText { .. }
            | Error::Analysis(_)
            | Error::Runaway { .. } => None,
        }
    }

    /// Attaches a source to a syntax error that has none yet (parsers of sub-texts leave it to
    /// their caller, or name the sub-text as the command line), shifting the span by
    /// `line_offset` lines and `col_offset` columns.
    pub fn within(self, source: &Source, line: usize, col_offset: usize) -> Self {
        match self {
            Error::Syntax(mut d) => {
                if let Some(span) = d.span.as_mut() {
                    if span.line == 1 {
                        span.col += col_offset;
                    }
                    span.line += line - 1;
                }
                let sub_text = d
                    .source
                    .as_ref()
                    .is_some_and(|s| s.name == Source::command_line("").name);
                if d.source.is_none() || sub_text {
                    d.source = Some(source.clone());
                }
                Error::Syntax(d)
            }
            other => other,
        }
    }

    /// The full diagnostic as shown to a user: code, message, and the source line with a caret.
    pub fn render(&self) -> String {
        let mut out = format!("error[{}]: {}\n", self.code(), self);
        if let Error::Syntax(d) = self {
            if let (Some(span), Some(source)) = (&d.span, &d.source) {
                let line_text = source.text.lines().nth(span.line - 1).unwrap_or("");
                let gutter = span.line.to_string().len();
                let pad = " ".repeat(gutter);
                out += &format!("{pad}--> {}:{}:{}\n", source.name, span.line, span.col);
                out += &format!("{pad} |\n{} | {}\n", span.line, line_text);
                out += &format!(
                    "{pad} | {}{}\n",
                    " ".repeat(span.col.saturating_sub(1)),
                    "^".repeat(span.len.max(1))
                );
            }
        }
        out
    }

    /// The diagnostic as JSON-ready data.
    pub fn to_json(&self) -> serde_json::Value {
        serde_json::json!({
            "error": {
                "code": self.code(),
                "message": self.to_string(),
                "span": self.span(),
            }
        })
    }
}

impl fmt::Display for Span {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}", self.line, self.col)
    }
}

/// Shorthand for results in lacuna.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// `n` with its noun, singular or plural: `1 part`, `2 parts` (for every message that counts).
pub fn counted(n: impl std::fmt::Display, one: &str, many: &str) -> String {
    let text = n.to_string();
    match text.as_str() {
        "1" => format!("1 {one}"),
        _ => format!("{text} {many}"),
    }
}

#[cfg(test)]
mod counted_tests {
    #[test]
    fn one_is_singular_and_every_other_number_plural() {
        assert_eq!(super::counted(1, "part", "parts"), "1 part");
        assert_eq!(super::counted(0, "part", "parts"), "0 parts");
        assert_eq!(super::counted(13u64, "hole", "holes"), "13 holes");
        let big = num_bigint::BigUint::from(1u32);
        assert_eq!(super::counted(&big, "hole", "holes"), "1 hole");
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn render_points_at_the_column() {
        let src = Source::command_line("C2 X2 | B2 B2 B2 | A1");
        let e = Error::syntax(
            "E0103",
            "unknown edge type `X2`",
            Span {
                line: 1,
                col: 4,
                len: 2,
            },
            Some(&src),
        );
        let text = e.render();
        assert!(text.starts_with("error[E0103]: unknown edge type `X2`\n"));
        assert!(text.contains(" --> <command line>:1:4\n"));
        assert!(text.ends_with("  |    ^^\n"), "{text}");
    }
}
