//! The `lacuna` command line: one file per command, each a thin wrapper over the library that
//! formats what it computed and chooses the exit code (0 verified, 1 not verified, 2 bad input or
//! an exceeded limit). Part of the binary, not of the library; it may import every layer.

mod args;
mod automaton;
mod geo;

mod census;
mod check;
mod closure;
mod counts;
mod design;
mod library;
mod measure;
mod operators;
mod ratio;
mod render;
mod report;
mod solve;
mod verify;

use args::*;
use clap::Parser;
use geo::*;
use lacuna::export::verify_report;
use lacuna::input::load_input;
use lacuna::topology::{Closure, Limits};
use lacuna::Error;
use std::process::ExitCode;

/// Exit code: verification failed (the input was fine, the verdict is negative).
const EXIT_FAILED: u8 = 1;
/// Exit code: bad input or an exceeded limit.
const EXIT_BAD_INPUT: u8 = 2;

/// Parses the command line, runs the command and maps an error to its exit code (with the error
/// object on standard output under `--json`).
pub(crate) fn main() -> ExitCode {
    let cli = Cli::parse();
    let json = match &cli.command {
        Command::Verify(a) => a.json,
        Command::Closure(a) => a.json,
        Command::Counts(a) => a.json,
        Command::Solve(a) => a.json,
        Command::Ratio(a) => a.json,
        Command::Check(a) => a.json,
        Command::Measure(a) => a.json,
        Command::Operators(a) => a.json,
        Command::Design(a) => a.json,
        Command::Census(a) => a.json,
        Command::Library(a) => a.json,
        Command::Render(_) | Command::Report(_) => false,
    };
    match run(cli) {
        Ok(code) => code,
        Err(e) => {
            if json {
                print_json(&e.to_json());
            }
            eprint!("{}", e.render());
            // Goals that no parameters meet are a negative answer, not bad input.
            ExitCode::from(if e.code() == "E1031" {
                EXIT_FAILED
            } else {
                EXIT_BAD_INPUT
            })
        }
    }
}

/// Writes to standard output; a closed pipe (`lacuna … | head`) is not an error.
pub(crate) fn out(text: &str) {
    use std::io::Write;
    let mut stdout = std::io::stdout().lock();
    let _ = stdout
        .write_all(text.as_bytes())
        .and_then(|_| stdout.flush());
}

/// Prints a value as pretty JSON on standard output.
pub(crate) fn print_json(v: &impl serde::Serialize) {
    out(&(serde_json::to_string_pretty(v).expect("reports serialise") + "\n"));
}

/// Creates an output file for writing.
pub(crate) fn create(path: &std::path::Path) -> Result<std::io::BufWriter<std::fs::File>, Error> {
    std::fs::File::create(path)
        .map(std::io::BufWriter::new)
        .map_err(|e| Error::Io {
            path: path.display().to_string(),
            reason: e.to_string(),
        })
}

/// The limits of the command line, then the command.
fn run(cli: Cli) -> Result<ExitCode, Error> {
    let l = cli.limits;
    lacuna::progress::set_progress(
        !cli.no_progress && std::io::IsTerminal::is_terminal(&std::io::stderr()),
    );
    let limits = Limits {
        max_boundary: l.max_boundary,
        max_types: l.max_types,
        max_level: l.max_level,
        max_subedges: l.max_subedges,
        max_delay: l.max_delay,
        max_digits: l.max_digits,
        max_unknowns: l.max_unknowns,
    };
    match cli.command {
        Command::Verify(a) => verify::run(a, &limits),
        Command::Check(a) => check::run(a),
        Command::Closure(a) => closure::run(a, &limits),
        Command::Counts(a) => counts::run(a, &limits),
        Command::Ratio(a) => ratio::run(a, &limits),
        Command::Operators(a) => operators::run(a, &limits),
        Command::Design(a) => design::run(a),
        Command::Render(a) => render::run(a, &limits),
        Command::Report(a) => report::run(a, &limits),
        Command::Measure(a) => measure::run(a, &limits),
        Command::Solve(a) => solve::run(a, &limits),
        Command::Census(a) => census::run(a, &limits),
        Command::Library(a) => library::run(a),
    }
}
