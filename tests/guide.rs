//! Keeps docs/GUIDE.md true: every `$ lacuna …` command in its console blocks is run and its
//! output (stdout, then stderr) must be exactly what the guide shows. Regenerate the guide with
//! `cargo build --release && python3 docs/make-guide.py`. The commands run in a temporary folder
//! holding a copy of `fixtures/`, so the files they write never depend on (nor land in) the
//! checkout's `target/` (issue #20 item 6).

use std::process::Command;

/// Splits a command line the way a POSIX shell would for the simple quoting the guide uses.
fn split(line: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut cur = String::new();
    let mut quote: Option<char> = None;
    let mut any = false;
    for ch in line.chars() {
        match (quote, ch) {
            (Some(q), c) if c == q => quote = None,
            (Some(_), c) => cur.push(c),
            (None, '\'' | '"') => {
                quote = Some(ch);
                any = true;
            }
            (None, c) if c.is_whitespace() => {
                if !cur.is_empty() || any {
                    out.push(std::mem::take(&mut cur));
                    any = false;
                }
            }
            (None, c) => cur.push(c),
        }
    }
    if !cur.is_empty() || any {
        out.push(cur);
    }
    out
}

/// A fresh folder with a copy of the repository's `fixtures/`.
fn work_folder() -> std::path::PathBuf {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let work = std::env::temp_dir().join(format!("lacuna-guide-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&work);
    std::fs::create_dir_all(work.join("fixtures")).unwrap();
    for entry in std::fs::read_dir(root.join("fixtures")).unwrap() {
        let entry = entry.unwrap();
        if entry.file_type().unwrap().is_file() {
            std::fs::copy(entry.path(), work.join("fixtures").join(entry.file_name())).unwrap();
        }
    }
    work
}

#[test]
fn every_command_of_the_guide_prints_what_the_guide_shows() {
    let root = env!("CARGO_MANIFEST_DIR");
    let work = work_folder();
    let guide = std::fs::read_to_string(format!("{root}/docs/GUIDE.md")).unwrap();
    let lines: Vec<&str> = guide.lines().collect();
    let mut checked = 0;
    let mut i = 0;
    while i < lines.len() {
        if let Some(cmd) = lines[i].strip_prefix("$ lacuna") {
            let mut expected = Vec::new();
            let mut j = i + 1;
            while j < lines.len() && lines[j] != "```" && !lines[j].starts_with("$ ") {
                expected.push(lines[j]);
                j += 1;
            }
            let out = Command::new(env!("CARGO_BIN_EXE_lacuna"))
                .args(split(cmd))
                .current_dir(&work)
                .output()
                .unwrap();
            let got = String::from_utf8_lossy(&out.stdout).to_string()
                + &String::from_utf8_lossy(&out.stderr);
            assert_eq!(
                got.trim_end_matches('\n'),
                expected.join("\n"),
                "docs/GUIDE.md line {}: `lacuna{cmd}` prints something else (regenerate with python3 docs/make-guide.py)",
                i + 1
            );
            checked += 1;
            i = j;
        } else {
            i += 1;
        }
    }
    let _ = std::fs::remove_dir_all(&work);
    assert!(checked >= 8, "only {checked} commands found in the guide");
}
