//! Shared by the integration tests: running the `lacuna` binary, round-tripping certificates.
#![allow(dead_code)] // each test crate uses a part of it

use std::process::Command;

pub mod mesh_files;
pub mod random_volume;
pub mod strategies;

/// The library under the name `random_volume` uses for it (the unit tests include that file
/// with `crate` under this name).
use lacuna as lib;

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

/// A fresh folder `lacuna-{name}-{pid}` in the system's temporary folder for one test's files
/// (emptied first, should an earlier run of the same process id have left it).
pub fn scratch(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("lacuna-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The instance of a named input (notation, file or library name) with the default geometry.
pub fn inst(name: &str) -> lacuna::geometry::Instance {
    let input = lacuna::input::load_input(name).unwrap_or_else(|e| panic!("{name}: {e}"));
    lacuna::geometry::instantiate(&input, &lacuna::geometry::InstantiateOptions::default())
        .unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// A path as command-line text.
pub fn s(p: &std::path::Path) -> String {
    p.to_string_lossy().into_owned()
}

/// STYLE rule 5: a pipeline test also emits the certificate of what it computed (closure,
/// solution space of the generated system, limit ratio), round-trips it through JSON and has the
/// independent checker prove every step.
pub fn assert_certified(name: &str, ts: &lacuna::topology::TypeSet) {
    let cert = certificate_for(name, ts, GenOptions::default())
        .unwrap_or_else(|e| panic!("{name}: no certificate: {e}"));
    assert_proved(name, &cert);
}

// ---- certificates ----

use lacuna::certificate::certificate_for;
use lacuna::certificate::{Certificate, Step};
use lacuna::checker::{check, check_json, Outcome};
use lacuna::{constraint::GenOptions, topology::Limits};

pub fn face_certificate(name: &str) -> Certificate {
    let input =
        lacuna::input::load_input(name).unwrap_or_else(|e| panic!("{name}: {}", e.render()));
    let ts = lacuna::topology::close_or_error(&input.faces(), &Limits::default()).expect("closes");
    lacuna::certificate::certificate_for_assembly(
        name,
        &ts,
        &input.assembly.canonical_glue(),
        GenOptions::default(),
    )
    .expect("certifiable")
}

pub fn automaton_certificate(name: &str) -> Certificate {
    match lacuna::input::load_any(name).expect("loads") {
        lacuna::input::Loaded::Automaton { model, .. } => {
            let limits = Limits::default();
            lacuna::certificate::certify_model(
                name,
                &model,
                limits.max_unknowns,
                limits.max_products,
            )
            .expect("certifiable")
        }
        lacuna::input::Loaded::Faces(_) => panic!("{name} is not an automaton"),
    }
}

/// The closed set of volume types of `volumes` within the default limits.
pub fn closed_volumes(
    volumes: &[lacuna::topology::volume::Volume],
) -> lacuna::topology::volume::VolumeTypeSet {
    match lacuna::topology::volume::VolumeClosure::of(volumes, &Limits::default()).expect("closes")
    {
        lacuna::topology::volume::VolumeClosure::Closed(set) => set,
        lacuna::topology::volume::VolumeClosure::Runaway(r) => panic!("{}", r.reason),
    }
}

/// The integer after `label` in `text` (a figure of a command's output).
pub fn number_after(text: &str, label: &str) -> i64 {
    let at = text
        .find(label)
        .unwrap_or_else(|| panic!("no `{label}` in {text}"));
    let n: String = text[at + label.len()..]
        .trim_start()
        .chars()
        .take_while(|c| *c == '-' || c.is_ascii_digit())
        .collect();
    n.parse()
        .unwrap_or_else(|_| panic!("no number after `{label}` in {text}"))
}

/// The integer before `label` in `text`.
pub fn number_before(text: &str, label: &str) -> i64 {
    let at = text
        .find(label)
        .unwrap_or_else(|| panic!("no `{label}` in {text}"));
    let n: String = text[..at]
        .trim_end()
        .chars()
        .rev()
        .take_while(|c| c.is_ascii_digit())
        .collect();
    n.chars().rev().collect::<String>().parse().unwrap()
}

/// The certificate of a volume (or an assembly of volumes) of the library, with counts to
/// level 3.
pub fn volume_certificate(name: &str) -> Certificate {
    let (_, volumes) = lacuna::input::load_volumes(name)
        .unwrap_or_else(|e| panic!("{name}: {}", e.render()))
        .unwrap_or_else(|| panic!("{name} is not a volume"));
    let set = closed_volumes(&volumes.volume_list());
    lacuna::certificate::certificate_for_volumes(name, &set, 3, &volumes).expect("certifiable")
}

/// [`volume_certificate`] with the `volume-solution-space` step, as `lacuna verify
/// --certificate` writes it.
pub fn volume_certificate_with_system(name: &str) -> Certificate {
    let mut cert = volume_certificate(name);
    let (_, volumes) = lacuna::input::load_volumes(name)
        .expect("loads")
        .expect("a volume");
    let set = closed_volumes(&volumes.volume_list());
    // The constraint system too, when it is solved within the default limits (cube-C2's is
    // refused for its memory estimate).
    match lacuna::certificate::solve_and_certify_volumes(&set, &volumes, &Limits::default()) {
        Ok(steps) => cert.steps.extend(steps),
        Err(lacuna::certificate::CertifyError::Lacuna(lacuna::Error::Limit { .. })) => {}
        Err(e) => panic!("{name}: {e}"),
    }
    cert
}

/// Emits, round-trips and checks a certificate (STYLE rule 5): every step must be proved.
pub fn assert_proved(name: &str, cert: &Certificate) {
    let json = cert.to_json();
    assert_eq!(
        json,
        cert.to_json(),
        "{name}: serialisation is not deterministic"
    );
    let back = Certificate::from_json(&json).expect("parses back");
    assert_eq!(
        &back, cert,
        "{name}: JSON round trip changed the certificate"
    );
    let report = check_json(&json);
    assert!(report.all_proved(), "{name}:\n{}", report.to_text());
}

/// Asserts that the checker rejects `cert` at the step called `step`, with a message naming it.
pub fn assert_rejected(what: &str, cert: &Certificate, step: &str) {
    let report = check(cert);
    let failed: Vec<_> = report
        .steps
        .iter()
        .filter(|s| s.outcome == Outcome::Failed)
        .collect();
    assert!(
        failed
            .iter()
            .any(|s| s.step == step && s.message.contains(step)),
        "{what}: expected step `{step}` to fail, got:\n{}",
        report.to_text()
    );
    assert!(!report.all_proved());
}

pub fn steps_named<'a>(cert: &'a mut Certificate, name: &str) -> Vec<&'a mut Step> {
    cert.steps.iter_mut().filter(|s| s.name() == name).collect()
}

/// Runs Debian's admesh (an independent STL checker) on `path` and checks that it reads one part
/// with nothing to repair: no disconnected edge, degenerate facet, fixed edge, removed, added or
/// reversed facet, backwards edge or fixed normal. Returns the number of facets it read.
pub fn admesh_finds_nothing_to_repair(path: &std::path::Path, what: &str) -> String {
    let out = Command::new("admesh")
        .arg(path)
        .output()
        .expect("admesh is installed (.ci/run installs it)");
    let text = String::from_utf8_lossy(&out.stdout);
    let field = |label: &str| -> Vec<String> {
        let line = text
            .lines()
            .find(|l| l.starts_with(label))
            .unwrap_or_else(|| panic!("{what}: no `{label}` in admesh's output:\n{text}"));
        line[line.find(':').unwrap() + 1..]
            .split_whitespace()
            .map(str::to_string)
            .collect()
    };
    assert_eq!(field("Number of parts")[0], "1", "{what}:\n{text}");
    for label in [
        "Facets with 1 disconnected edge",
        "Facets with 2 disconnected edges",
        "Facets with 3 disconnected edges",
        "Degenerate facets",
        "Edges fixed",
        "Facets removed",
        "Facets added",
        "Facets reversed",
        "Backwards edges",
        "Normals fixed",
    ] {
        assert!(
            field(label).iter().all(|v| v == "0"),
            "{what}: admesh reports {label}:\n{text}"
        );
    }
    field("Number of facets")[0].clone()
}

/// Slices `stl` into `gcode` with Debian's PrusaSlicer command line (`.ci/run` installs it),
/// with supports when asked: (whether it succeeded, its stdout and stderr).
pub fn prusa_slice(
    stl: &std::path::Path,
    gcode: &std::path::Path,
    supports: bool,
) -> (bool, String) {
    let mut slicer = Command::new("prusa-slicer");
    if supports {
        slicer.arg("--support-material");
    }
    let o = slicer
        .arg("--export-gcode")
        .arg(stl)
        .arg("-o")
        .arg(gcode)
        .output()
        .expect("prusa-slicer runs (Debian package prusa-slicer)");
    (
        o.status.success(),
        format!(
            "{}{}",
            String::from_utf8_lossy(&o.stdout),
            String::from_utf8_lossy(&o.stderr)
        ),
    )
}
