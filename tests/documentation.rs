//! Issue #20 items 18 and 19: the documentation says what is true, and the mathematics it cites is
//! in the repository.

use std::path::Path;

fn read(rel: &str) -> String {
    std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join(rel)).unwrap()
}

/// Every text file under `dir` with one of the extensions, as (path, text).
fn files(dir: &str, exts: &[&str]) -> Vec<(String, String)> {
    let mut out = Vec::new();
    let mut stack = vec![Path::new(env!("CARGO_MANIFEST_DIR")).join(dir)];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|x| exts.iter().any(|e| x == *e)) {
                let text = std::fs::read_to_string(&p).unwrap_or_default();
                out.push((p.display().to_string(), text));
            }
        }
    }
    out
}

#[test]
fn hardening_19_the_mathematics_cited_is_in_the_repository() {
    // No reference points at a SPEC that users cannot read; every "THEORY §n" names a section
    // that docs/THEORY.md has.
    let theory = read("docs/THEORY.md");
    let mut checked = 0;
    for dir in ["src", "docs", "fixtures", "tests"] {
        for (path, text) in files(dir, &["rs", "md", "txt", "aut"]) {
            if path.ends_with("tests/documentation.rs") {
                continue;
            }
            for (n, line) in text.lines().enumerate() {
                assert!(
                    !line.contains("SPEC §") && !line.contains("SPEC.md"),
                    "{path}:{}: cites the SPEC: {line}",
                    n + 1
                );
                let mut rest = line;
                while let Some(i) = rest.find("THEORY §") {
                    let digits: String = rest[i + "THEORY §".len()..]
                        .chars()
                        .take_while(char::is_ascii_digit)
                        .collect();
                    // `THEORY §n` written as a pattern (THEORY.md's own introduction).
                    if digits.is_empty() {
                        rest = &rest[i + 1..];
                        continue;
                    }
                    assert!(
                        theory.contains(&format!("\n## §{digits} ")),
                        "{path}:{}: THEORY §{digits} is not a section of docs/THEORY.md",
                        n + 1
                    );
                    checked += 1;
                    rest = &rest[i + 1..];
                }
            }
        }
    }
    assert!(
        checked > 50,
        "only {checked} references found: the scan is broken"
    );
    // The terms the issue found undefined are defined there.
    for term in ["contribution", "R_i", "Ea", "El", "Ec", "half"] {
        assert!(theory.contains(term), "THEORY.md does not define {term}");
    }
}

#[test]
fn hardening_18_the_docs_name_flags_that_exist_and_built_things_as_built() {
    // ARCHITECTURE.md no longer says geometry is not built; the README's "Not yet" list names
    // none of what exists.
    let arch = read("docs/ARCHITECTURE.md");
    assert!(!arch.contains("not built yet"), "ARCHITECTURE.md");
    let readme = read("README.md");
    let not_yet = readme
        .split("Not yet")
        .nth(1)
        .expect("the README has a Not yet list");
    let not_yet = &not_yet[..not_yet.find("\n\n").unwrap_or(not_yet.len())];
    for built in [
        "LP goals",
        "density maps",
        "progress bars",
        "several dominant classes",
        "certificates and geometry of volumes",
        "topological classes",
        "morphing",
    ] {
        assert!(
            !not_yet.contains(built),
            "README lists {built} as not yet built"
        );
    }
    // Every `--json-out`-style flag of the render table in GEOMETRY.md is a flag of render.
    let geometry = read("docs/GEOMETRY.md");
    assert!(
        !geometry.contains("`--json OUT`"),
        "GEOMETRY.md names --json OUT"
    );
    let (code, help, _) = {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_lacuna"))
            .args(["render", "--help"])
            .output()
            .unwrap();
        (
            out.status.code(),
            String::from_utf8(out.stdout).unwrap(),
            (),
        )
    };
    assert_eq!(code, Some(0));
    for flag in [
        "--json-out",
        "--stl",
        "--3mf",
        "--obj",
        "--png",
        "--density",
    ] {
        assert!(help.contains(flag), "render --help lacks {flag}");
    }
}

#[test]
fn hardening_18_an_empty_face_is_e0101_as_errors_md_says() {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_lacuna"))
        .args(["verify", ""])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(err.contains("E0101"), "{err}");
    assert!(read("docs/ERRORS.md").contains("| E0101 | empty face notation"));
}
