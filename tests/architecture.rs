//! The layering of `docs/ARCHITECTURE.md`, kept honest: every `crate::` path in the library's
//! sources is mapped to the folder (layer) and file it names, and the test fails on an import that
//! goes up a layer or sideways into another layer of the same rank, on a cycle between files, and
//! on a `lacuna::` path inside the library (which would hide an import from this test). Comment
//! lines are skipped: a doc link is not an import.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The layers, bottom up. A folder may import a folder of strictly lower rank, and itself.
const LAYERS: &[(&str, u32)] = &[
    ("error", 0),
    ("progress", 0),
    ("topology", 1),
    ("algebra", 1),
    ("constraint", 2),
    ("input", 3),
    ("analysis", 4),
    ("certificate", 5),
    ("geometry", 5),
    ("checker", 6),
    ("meshcheck", 6),
    ("measure", 6),
    ("mesh", 7),
    ("family", 7),
    ("export", 8),
];

/// The names that the crate root re-exports from `error`.
const ROOT_ERROR_NAMES: &[&str] = &["Error", "Result", "Source", "Span", "Diagnostic"];

fn rank(layer: &str) -> Option<u32> {
    LAYERS.iter().find(|(l, _)| *l == layer).map(|(_, r)| *r)
}

/// Every `.rs` file of the library (the binary's `main.rs` and `cli/` may import every layer; the
/// crate root and the prelude only re-export).
fn library_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("src/ is readable") {
        let path = entry.expect("directory entry").path();
        if path.is_dir() {
            if path.file_name().is_some_and(|n| n == "cli") {
                continue;
            }
            library_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            let name = path.file_name().unwrap().to_string_lossy().to_string();
            let top = path.parent() == Some(dir);
            if top && ["main.rs", "lib.rs", "prelude.rs"].contains(&name.as_str()) {
                continue;
            }
            out.push(path);
        }
    }
}

/// The unit a source file belongs to: `layer/file` (a folder module such as `algebra/factor/`
/// counts as one file), or the root module's name.
fn unit_of(rel: &Path) -> String {
    let parts: Vec<String> = rel
        .components()
        .map(|c| {
            c.as_os_str()
                .to_string_lossy()
                .trim_end_matches(".rs")
                .to_string()
        })
        .collect();
    match parts.len() {
        1 => parts[0].clone(),
        _ => format!("{}/{}", parts[0], parts[1]),
    }
}

/// The files (units) of each layer folder, to tell `crate::layer::file::Item` from
/// `crate::layer::Item` (a re-export, which names the folder's module `layer/mod`).
fn units_by_layer(files: &[PathBuf], src: &Path) -> BTreeMap<String, BTreeSet<String>> {
    let mut m: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for f in files {
        let u = unit_of(f.strip_prefix(src).unwrap());
        if let Some((layer, file)) = u.split_once('/') {
            m.entry(layer.to_string())
                .or_default()
                .insert(file.to_string());
        }
    }
    m
}

/// The `crate::` paths of one line: `crate::a::b`, and each item of `crate::{a::b, c}`.
fn crate_paths(line: &str) -> Vec<Vec<String>> {
    let mut paths = Vec::new();
    let mut rest = line;
    while let Some(i) = rest.find("crate::") {
        let after = &rest[i + "crate::".len()..];
        let ident_before = rest[..i]
            .chars()
            .next_back()
            .is_some_and(|c| c.is_alphanumeric() || c == '_');
        if ident_before {
            // `pub(crate)` is not a path; `foo_crate::` is another name.
            rest = after;
            continue;
        }
        if let Some(group) = after.strip_prefix('{') {
            let end = group.find('}').unwrap_or(group.len());
            for item in group[..end].split(',') {
                paths.push(segments(item.trim()));
            }
            rest = &group[end..];
        } else {
            paths.push(segments(after));
            rest = after;
        }
    }
    paths.retain(|p| !p.is_empty());
    paths
}

fn segments(s: &str) -> Vec<String> {
    let mut out = Vec::new();
    for seg in s.split("::") {
        let ident: String = seg
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        if ident.is_empty() {
            break;
        }
        let whole = ident.len() == seg.len();
        out.push(ident);
        if !whole {
            break;
        }
    }
    out
}

/// One import of one unit by another, where it is written.
struct Import {
    from: String,
    to: String,
    at: String,
}

fn imports() -> (Vec<Import>, Vec<String>) {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    library_files(&src, &mut files);
    files.sort();
    let layers = units_by_layer(&files, &src);
    let mut found = Vec::new();
    let mut problems = Vec::new();
    for f in &files {
        let rel = f.strip_prefix(&src).unwrap();
        let from = unit_of(rel);
        let text = std::fs::read_to_string(f).unwrap();
        for (n, line) in text.lines().enumerate() {
            let code = line.trim_start();
            if code.starts_with("//") {
                continue;
            }
            let at = format!("src/{}:{}: {}", rel.display(), n + 1, line.trim());
            if code.contains("lacuna::") && !code.contains('"') {
                problems.push(format!(
                    "`lacuna::` path inside the library (use `crate::`): {at}"
                ));
            }
            for path in crate_paths(code) {
                let head = &path[0];
                let to = match layers.get(head) {
                    Some(units) => match path.get(1) {
                        Some(file) if units.contains(file) => format!("{head}/{file}"),
                        _ => format!("{head}/mod"),
                    },
                    // The crate root re-exports the error types.
                    None if ROOT_ERROR_NAMES.contains(&head.as_str()) => "error".to_string(),
                    None => head.clone(),
                };
                found.push(Import {
                    from: from.clone(),
                    to,
                    at: at.clone(),
                });
            }
        }
    }
    (found, problems)
}

fn layer(unit: &str) -> &str {
    unit.split('/').next().unwrap()
}

#[test]
fn imports_only_go_down_a_layer() {
    let (found, mut problems) = imports();
    assert!(
        found.len() > 100,
        "too few imports found: the scan is broken"
    );
    for i in &found {
        let (a, b) = (layer(&i.from), layer(&i.to));
        if a == b {
            continue;
        }
        match (rank(a), rank(b)) {
            (Some(ra), Some(rb)) if rb < ra => {}
            (Some(_), Some(_)) => problems.push(format!("{a} may not import {b}: {}", i.at)),
            _ => problems.push(format!("unknown layer in `{a}` → `{b}`: {}", i.at)),
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

#[test]
fn the_checker_and_the_certificate_format_stand_alone() {
    let (found, _) = imports();
    let bad: Vec<&Import> = found
        .iter()
        .filter(|i| {
            (layer(&i.from) == "checker"
                && !matches!(i.to.as_str(), "certificate/format" | "certificate/mod")
                && layer(&i.to) != "checker")
                || (i.from == "certificate/format" && i.to != "certificate/format")
        })
        .collect();
    let lines: Vec<&str> = bad.iter().map(|i| i.at.as_str()).collect();
    assert!(bad.is_empty(), "{}", lines.join("\n"));
}

/// The mesh checker shares no code with the mesh writer (`mesh`, `export`) nor anything else of
/// lacuna: its `crate::` paths name only `error` and itself, and its `use` lines only std, the
/// crates it reads with, `crate::error` and its own files (`super::`, `self::` in `mod.rs`).
#[test]
fn the_mesh_checker_imports_nothing_of_the_producer() {
    let (found, _) = imports();
    let bad: Vec<&str> = found
        .iter()
        .filter(|i| layer(&i.from) == "meshcheck" && !matches!(layer(&i.to), "error" | "meshcheck"))
        .map(|i| i.at.as_str())
        .collect();
    assert!(bad.is_empty(), "{}", bad.join("\n"));
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/meshcheck");
    let roots = [
        "std::",
        "crate::error",
        "num_bigint",
        "num_rational",
        "num_traits",
        "serde",
        "serde_json",
        "zip",
        "quick_xml",
        "super::",
        "self::",
    ];
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("src/meshcheck/ exists")
        .map(|e| e.expect("entry").path())
        .collect();
    files.sort();
    assert!(files.len() >= 5, "the scan is broken: {files:?}");
    let mut seen_use = 0;
    for f in &files {
        assert!(
            f.extension().is_some_and(|e| e == "rs"),
            "{}: meshcheck is one folder of .rs files",
            f.display()
        );
        let name = f.file_name().unwrap().to_string_lossy().to_string();
        let text = std::fs::read_to_string(f).unwrap();
        for (n, line) in text.lines().enumerate() {
            let code = line.split("//").next().unwrap_or("").trim();
            let at = format!("src/meshcheck/{name}:{}: {}", n + 1, line.trim());
            for banned in [
                "lacuna::",
                "extern crate",
                "#[path",
                "super::super",
                "include!",
            ] {
                assert!(!code.contains(banned), "`{banned}` in {at}");
            }
            for producer in [
                "crate::mesh",
                "crate::export",
                "crate::geometry",
                "crate::measure",
            ] {
                // `crate::mesh` but not `crate::meshcheck`.
                let named = code.match_indices(producer).any(|(i, _)| {
                    !code[i + producer.len()..]
                        .starts_with(|c: char| c.is_alphanumeric() || c == '_')
                });
                assert!(!named, "the producer `{producer}` in {at}");
            }
            if name == "mod.rs" {
                assert!(
                    !code.contains("super::"),
                    "the module root reaches outside: {at}"
                );
            }
            if let Some(path) = code.strip_prefix("use ").or(code.strip_prefix("pub use ")) {
                seen_use += 1;
                assert!(
                    roots.iter().any(|r| path.starts_with(r)),
                    "`use {path}` is not allowed in the mesh checker: {at}"
                );
            }
        }
    }
    assert!(
        seen_use > 10,
        "too few `use` lines found: the scan is broken"
    );
}

#[test]
fn no_cycle_between_files() {
    let (found, _) = imports();
    let mut graph: BTreeMap<&str, BTreeMap<&str, &str>> = BTreeMap::new();
    for i in &found {
        if i.from != i.to && !i.to.ends_with("/mod") {
            graph
                .entry(&i.from)
                .or_default()
                .entry(&i.to)
                .or_insert(&i.at);
        }
    }
    // Depth-first search for a back edge; the cycle is printed with the line of every import.
    fn visit<'a>(
        u: &'a str,
        graph: &BTreeMap<&'a str, BTreeMap<&'a str, &'a str>>,
        state: &mut BTreeMap<&'a str, u8>,
        stack: &mut Vec<&'a str>,
    ) -> Option<Vec<&'a str>> {
        state.insert(u, 1);
        stack.push(u);
        for (&v, _) in graph.get(u).into_iter().flatten() {
            match state.get(v).copied().unwrap_or(0) {
                0 => {
                    if let Some(c) = visit(v, graph, state, stack) {
                        return Some(c);
                    }
                }
                1 => {
                    let start = stack.iter().position(|&s| s == v).unwrap();
                    let mut cycle = stack[start..].to_vec();
                    cycle.push(v);
                    return Some(cycle);
                }
                _ => {}
            }
        }
        stack.pop();
        state.insert(u, 2);
        None
    }
    let mut state = BTreeMap::new();
    let nodes: Vec<&str> = graph.keys().copied().collect();
    for u in nodes {
        if state.get(u).copied().unwrap_or(0) == 0 {
            if let Some(cycle) = visit(u, &graph, &mut state, &mut Vec::new()) {
                let lines: Vec<String> = cycle
                    .windows(2)
                    .map(|w| graph[w[0]][w[1]].to_string())
                    .collect();
                panic!("import cycle {}:\n{}", cycle.join(" → "), lines.join("\n"));
            }
        }
    }
}

#[test]
fn the_scan_sees_paths_in_groups_and_skips_pub_crate() {
    assert_eq!(
        crate_paths("use crate::{topology::face::Face, error::Error};"),
        vec![
            vec!["topology".to_string(), "face".into(), "Face".into()],
            vec!["error".to_string(), "Error".into()]
        ]
    );
    assert!(crate_paths("pub(crate) fn f() {}").is_empty());
    assert_eq!(
        crate_paths("let x = crate::measure::hole::smallest_holes(a);"),
        vec![vec![
            "measure".to_string(),
            "hole".into(),
            "smallest_holes".into()
        ]]
    );
}
