//! The `lacuna` command line: a thin wrapper over the library (the commands are in `cli/`).
#![forbid(unsafe_code)]

mod cli;

fn main() -> std::process::ExitCode {
    cli::main()
}
