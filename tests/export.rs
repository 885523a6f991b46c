//! `lacuna export` (issue #23): the generated automaton written in lacuna's automaton format
//! solves to the same system (unknowns, equations, rank, degrees of freedom) for every face
//! fixture, and the MODITERE model is valid Python holding the cells and constraints the closure
//! predicts.

mod common;
use lacuna::constraint::{automaton_of, solve_automaton, solve_closure, GenOptions};
use lacuna::export::{automaton_text, moditere_text};
use lacuna::input::{load_input, parse_automaton};
use lacuna::topology::{close_or_error, Limits, Origin};
use lacuna::Source;

/// Every face fixture (the `.txt` files of `fixtures/` that are not volumes).
fn face_fixtures() -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/fixtures"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "txt"))
        // Volumes (cube-B2, …) have their own automaton, not the faces' export.
        .filter(|p| !lacuna::input::is_volume_text(&std::fs::read_to_string(p).unwrap()))
        .map(|p| p.display().to_string())
        .collect();
    v.sort();
    assert!(v.len() >= 5, "face fixtures: {v:?}");
    v
}

#[test]
fn exported_automaton_solves_like_the_input_for_every_fixture() {
    let mut cases = face_fixtures();
    cases.push("C2 B2^3 C2^2 B3 | C2 B2 B2 | AF1".into());
    for path in cases {
        let input = load_input(&path).unwrap_or_else(|e| panic!("{path}: {}", e.render()));
        let ts = close_or_error(&input.faces(), &Limits::default()).unwrap();
        let direct = solve_closure(&ts, GenOptions::default(), &Limits::default()).unwrap();
        let g = automaton_of(&ts, GenOptions::default());
        let text = automaton_text(&g.automaton, &["test".into()], &Default::default());
        let back = parse_automaton(&Source {
            name: path.clone(),
            text,
        })
        .unwrap_or_else(|e| panic!("{path}: the export does not parse: {}", e.render()));
        let (again, _, _) = solve_automaton(&back).unwrap();
        assert_eq!(
            (
                direct.unknowns,
                direct.equations,
                direct.rank,
                direct.dof,
                direct.consistent
            ),
            (
                again.unknowns,
                again.equations,
                again.rank,
                again.dof,
                again.consistent
            ),
            "fixture {path}"
        );
        assert_eq!(
            direct.particular.len(),
            again.particular.len(),
            "fixture {path}"
        );
    }
}

#[test]
fn export_then_solve_on_the_command_line() {
    let dir = std::env::temp_dir().join(format!("lacuna-export-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("delayed.aut");
    let f = file.to_str().unwrap();
    let (code, out, err) = common::lacuna(&[
        "export",
        "fixtures/delayed-B2-C2.txt",
        "--format",
        "aut",
        "-o",
        f,
    ]);
    assert_eq!(code, 0, "{err}");
    // Like `render`, a file written is said (issue #32).
    assert_eq!(out, format!("wrote {f}\n"));
    let json = |args: &[&str]| -> serde_json::Value {
        let (_, out, err) = common::lacuna(args);
        serde_json::from_str(&out).unwrap_or_else(|_| panic!("{err}"))
    };
    let a = json(&["solve", "fixtures/delayed-B2-C2.txt", "--json"]);
    let b = json(&["solve", f, "--json"]);
    for k in ["unknowns", "equations", "rank", "dof", "consistent"] {
        assert_eq!(a[k], b[k], "{k}");
    }
    // An automaton file is not faces: no MODITERE model of it (E0504, exit 2).
    let (code, _, err) = common::lacuna(&["export", f, "--format", "moditere"]);
    assert_eq!(code, 2);
    assert!(err.contains("E0504"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

fn python_parses(path: &std::path::Path) -> bool {
    match std::process::Command::new("python3")
        .args([
            "-c",
            "import ast, sys; ast.parse(open(sys.argv[1]).read())",
            path.to_str().unwrap(),
        ])
        .status()
    {
        Ok(s) => s.success(),
        Err(_) => {
            eprintln!("python3 is not installed: the syntax check is skipped");
            true
        }
    }
}

#[test]
fn moditere_model_is_python_with_the_predicted_cells_and_constraints() {
    let dir = std::env::temp_dir().join(format!("lacuna-moditere-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut cases = face_fixtures();
    cases.push("C2 B2^3 C2^2 B3 | C2 B2 B2 | AF1".into());
    for (k, name) in cases.iter().enumerate() {
        let input = load_input(name).unwrap();
        let ts = close_or_error(&input.faces(), &Limits::default()).unwrap();
        let g = automaton_of(&ts, GenOptions::default());
        let text = moditere_text(&input, &ts, &g, &Limits::default()).unwrap();
        let file = dir.join(format!("m{k}.py"));
        std::fs::write(&file, &text).unwrap();
        assert!(python_parses(&file), "{name}: not valid Python");
        let count = |needle: &str| text.lines().filter(|l| l.contains(needle)).count();
        // The vertex state, the edge states and one state per face type.
        assert_eq!(
            count(" = Etat('"),
            1 + ts.types.len() + edge_states(&text),
            "{name}"
        );
        let cells = text
            .lines()
            .filter(|l| l.trim_start().starts_with("Cell_") && l.contains(" = Etat("))
            .count();
        assert_eq!(cells, ts.types.len(), "{name}: cells");
        // Incidence: one per piece of a parent edge in a sub-face; adjacency: one per shared Ea;
        // edge adjacency: one per corner.
        let pieces: usize = ts
            .types
            .iter()
            .flat_map(|t| &t.subdivision.subfaces)
            .flat_map(|s| &s.origins)
            .filter(|o| matches!(o, Origin::Piece { .. }))
            .count();
        let adjacencies: usize = ts
            .types
            .iter()
            .map(|t| t.subdivision.adjacencies.len())
            .sum();
        let corners: usize = ts.types.iter().map(|t| t.face.boundary.len()).sum();
        let cell_lines = |pat: &dyn Fn(&str) -> bool| {
            text.lines()
                .filter(|l| l.trim_start().starts_with("Cell_") && l.contains('(') && pat(l))
                .count()
        };
        assert_eq!(
            cell_lines(&|l| l.contains("(Bord('")
                && l.contains(") + Sub('")
                && !l.contains("Bord('1'), Bord")),
            pieces,
            "{name}: incidence"
        );
        assert_eq!(
            cell_lines(&|l| l.contains("Permut('0'), Sub(")),
            adjacencies,
            "{name}: adjacency"
        );
        assert_eq!(
            cell_lines(&|l| l.contains("+ Bord('1'), Bord('")),
            corners,
            "{name}: edge adjacency"
        );
        // The shared edges of the start faces, and one control-point block per start face.
        assert_eq!(
            count("    init(Sub("),
            input.assembly.shared.len(),
            "{name}"
        );
        assert_eq!(
            count("init.initMat[Sub_('"),
            3 * input.faces().len(),
            "{name}"
        );
        // The solved operators: one matrix per sub-face of every type (the systems are consistent).
        let subs: usize = ts.types.iter().map(|t| t.children.len()).sum();
        assert_eq!(
            count(".setTyp('Var')") - input.faces().len(),
            subs,
            "{name}"
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// The number of edge states declared (`B2 = Etat('B2', 1)`, …).
fn edge_states(text: &str) -> usize {
    text.lines()
        .filter(|l| {
            let t = l.trim_start();
            (t.starts_with('B') || t.starts_with('C'))
                && !t.starts_with("Cell_")
                && t.contains(" = Etat('")
        })
        .count()
}

/// The shared edge of `two-quads` in MODITERE's indices, derived by hand: both faces are
/// `C2 B2 C2 B2`, whose canonical rotation `B2 C2 B2 C2` starts at written edge 1, so written edge
/// 3 of face 0 is canonical edge 2 and written edge 1 of face 1 is canonical edge 0 (both B2).
#[test]
fn moditere_shared_edges_use_the_canonical_rotation() {
    let (code, out, err) =
        common::lacuna(&["export", "fixtures/two-quads.txt", "--format", "moditere"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("    init.subs = {Sub('0'): Cell_0, Sub('1'): Cell_0}\n"));
    assert!(out.contains(
        "    Cell_0.bords = {Bord('0'): B2, Bord('1'): C2, Bord('2'): B2, Bord('3'): C2}\n"
    ));
    assert!(out.contains("    init(Sub('0') + Bord('2') + Permut('0'), Sub('1') + Bord('0'))\n"));
}

#[test]
fn bad_export_options_are_coded() {
    for (args, code) in [
        (
            // A fixed range, not a limit to raise (issue #20 item 12).
            vec!["export", "F0", "--format", "aut", "--degree", "9"],
            "E0503",
        ),
        (
            vec!["export", "F0", "--format", "aut", "--cantor-gap=-1"],
            "E0113",
        ),
        (vec!["export", "no-such-input", "--format", "aut"], "E0601"),
        (
            vec![
                "export",
                "F0",
                "--format",
                "moditere",
                "-o",
                "/nonexistent-dir/x.py",
            ],
            // A failed write (issue #20 item 6).
            "E1005",
        ),
        (
            vec!["export", "C2 B2 | C2 B2 | A1", "--format", "moditere"],
            "E0107",
        ),
    ] {
        let (exit, _, err) = common::lacuna(&args);
        assert_eq!(exit, 2, "{args:?}");
        assert!(err.contains(code), "{args:?}: {err}");
    }
    // A runaway has no automaton to export.
    let (exit, _, err) = common::lacuna(&[
        "export",
        "C2 | B2 B2 B2 | {gap}",
        "--format",
        "aut",
        "--max-boundary",
        "30",
    ]);
    assert_eq!(exit, 2);
    assert!(err.contains("E0502"), "{err}");
}
