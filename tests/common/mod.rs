//! Shared by the integration tests: running the `lacuna` binary, round-tripping certificates.
#![allow(dead_code)] // each test crate uses a part of it

use std::process::Command;

/// Runs the built binary in the crate's directory: (exit code, stdout, stderr).
pub fn lacuna(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_lacuna"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("the binary runs");
    (
        out.status.code().expect("exited, not killed"),
        String::from_utf8(out.stdout).expect("utf-8 stdout"),
        String::from_utf8(out.stderr).expect("utf-8 stderr"),
    )
}

/// STYLE rule 5: a pipeline test also emits the certificate of what it computed (closure,
/// solution space of the generated system, limit ratio), round-trips it through JSON and has the
/// independent checker prove every step.
pub fn assert_certified(name: &str, ts: &lacuna::TypeSet) {
    let cert = lacuna::certify::certificate_for(name, ts, lacuna::GenOptions::default())
        .unwrap_or_else(|e| panic!("{name}: no certificate: {e}"));
    let json = cert.to_json();
    let report = lacuna::checker::check_json(&json);
    assert!(
        report.all_proved(),
        "{name}: certificate not proved:\n{}",
        report.to_text()
    );
}
