//! The `lacuna` command line: one file per command, each a thin wrapper over the library that
//! formats what it computed and chooses the exit code (0 verified, 1 not verified, 2 bad input or
//! an exceeded limit). Part of the binary, not of the library; it may import every layer.

mod args;
mod automaton;
mod geo;
mod output;

mod census;
mod check;
mod check_mesh;
mod classify;
mod closure;
mod counts;
mod design;
mod explore;
mod export;
mod library;
mod measure;
mod morph;
mod operators;
mod ratio;
mod render;
mod report;
mod solve;
mod verify;
mod volume;

use args::*;
use clap::{CommandFactory, Parser};
use geo::*;
use lacuna::export::verify_report;
use lacuna::input::load_input;
use lacuna::topology::{Closure, Limits};
use lacuna::Error;
use output::Outputs;
use std::process::ExitCode;

/// Exit code: verification failed (the input was fine, the verdict is negative).
const EXIT_FAILED: u8 = 1;
/// Exit code: bad input or an exceeded limit.
const EXIT_BAD_INPUT: u8 = 2;
/// Exit code of `lacuna check`: every step present is proved, but the certificate lacks steps
/// its claim needs (a partial certificate proves part of its claim only).
const EXIT_PARTIAL: u8 = 3;

/// Parses the command line, runs the command and maps an error to its exit code (with the error
/// object on standard output under `--json`).
pub(crate) fn main() -> ExitCode {
    let cli = Cli::parse();
    let json = match &cli.command {
        Command::Verify(a) => a.args.json,
        Command::Closure(a) => a.args.json,
        Command::Counts(a) => a.args.json,
        Command::Solve(a) => a.args.json,
        Command::Ratio(a) => a.args.json,
        Command::Check(a) => a.json,
        Command::CheckMesh(a) => a.json,
        Command::Measure(a) => a.args.json,
        Command::Operators(a) => a.args.json,
        Command::Design(a) => a.json,
        Command::Census(a) => a.args.json,
        Command::Library(a) => a.json,
        Command::Explore(a) => a.args.json,
        Command::Classify(a) => a.args.json,
        Command::Morph(a) => a.args.json,
        Command::Render(_)
        | Command::Report(_)
        | Command::Export(_)
        | Command::Completions(_)
        | Command::Man(_) => false,
    };
    match run(cli) {
        Ok(code) => code,
        Err(e) => {
            if json {
                print_json(&e.to_json());
            }
            eprint!("{}", e.render());
            // Goals that no parameters meet, and a collapse that every choice has, are negative
            // answers, not bad input.
            ExitCode::from(
                if matches!(e.code(), "E1031" | "E1013") || lacuna::mesh::is_failure_code(e.code())
                {
                    EXIT_FAILED
                } else {
                    EXIT_BAD_INPUT
                },
            )
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

/// The command, with its limits.
fn run(cli: Cli) -> Result<ExitCode, Error> {
    lacuna::progress::set_progress(
        !cli.no_progress && std::io::IsTerminal::is_terminal(&std::io::stderr()),
    );
    match cli.command {
        Command::Verify(a) => verify::run(a.args, &a.limits.limits()),
        Command::Check(a) => check::run(a),
        Command::CheckMesh(a) => check_mesh::run(a),
        Command::Closure(a) => closure::run(a.args, &a.limits.limits()),
        Command::Counts(a) => counts::run(a.args, &a.limits.limits()),
        Command::Ratio(a) => ratio::run(a.args, &a.limits.limits()),
        Command::Operators(a) => operators::run(a.args, &a.limits.limits()),
        Command::Design(a) => design::run(a),
        Command::Render(a) => render::run(a.args, &a.limits.limits()),
        Command::Report(a) => report::run(a.args, &a.limits.limits()),
        Command::Measure(a) => measure::run(a.args, &a.limits.limits()),
        Command::Solve(a) => solve::run(a.args, &a.limits.limits()),
        Command::Census(a) => census::run(a.args, &a.limits.limits()),
        Command::Library(a) => library::run(a),
        Command::Export(a) => export::run(a.args, &a.limits.limits()),
        Command::Explore(a) => explore::run(a.args, &a.limits.limits()),
        Command::Classify(a) => classify::run(a.args, &a.limits.limits()),
        Command::Morph(a) => morph::run(a.args, &a.limits.limits()),
        Command::Completions(a) => {
            let mut out = Vec::new();
            clap_complete::generate(a.shell, &mut Cli::command(), "lacuna", &mut out);
            print_bytes(&out)
        }
        Command::Man(ManArgs { all: Some(dir) }) => {
            let failed = |e: std::io::Error| Error::Write {
                path: dir.display().to_string(),
                reason: e.to_string(),
            };
            std::fs::create_dir_all(&dir).map_err(failed)?;
            clap_mangen::generate_to(Cli::command(), &dir).map_err(failed)?;
            let mut pages: Vec<String> = std::fs::read_dir(&dir)
                .map_err(failed)?
                .filter_map(|e| e.ok()?.file_name().into_string().ok())
                .filter(|n| n.starts_with("lacuna") && n.ends_with(".1"))
                .collect();
            pages.sort();
            out(&format!(
                "wrote {} manual pages into {}: {}\n",
                pages.len(),
                dir.display(),
                pages.join(", ")
            ));
            Ok(ExitCode::SUCCESS)
        }
        Command::Man(ManArgs { all: None }) => {
            let mut out = Vec::new();
            clap_mangen::Man::new(Cli::command())
                .render(&mut out)
                .map_err(|e| Error::Write {
                    path: "<standard output>".into(),
                    reason: e.to_string(),
                })?;
            print_bytes(&out)
        }
    }
}

/// Writes bytes to standard output (a closed pipe is not an error), exit 0.
fn print_bytes(bytes: &[u8]) -> Result<ExitCode, Error> {
    out(&String::from_utf8_lossy(bytes));
    Ok(ExitCode::SUCCESS)
}
