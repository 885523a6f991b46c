//! Determinism: the same input gives byte-identical JSON and certificates across runs and thread
//! counts (issue #8).

mod common;

fn stdout(args: &[&str]) -> String {
    let (code, out, err) = common::lacuna(args);
    assert_eq!(code, 0, "{args:?}: {err}");
    out
}

#[test]
fn census_json_does_not_depend_on_the_thread_count() {
    let base = [
        "census",
        "--max-length",
        "3",
        "--edges",
        "B2,C2,C3",
        "--params",
        "B2,C2",
        "--json",
    ];
    let one = stdout(&[&base[..], &["--threads", "1"]].concat());
    let two = stdout(&[&base[..], &["--threads", "2"]].concat());
    let four = stdout(&[&base[..], &["--threads", "4"]].concat());
    assert_eq!(one, two);
    assert_eq!(one, four);
}

#[test]
fn reports_and_certificates_are_byte_identical_across_runs() {
    for args in [
        vec!["verify", "delayed-B2-C2", "--json"],
        vec!["closure", "triangle-C2", "--json"],
        vec!["ratio", "cycle-sqrt17", "--json", "--digits", "60"],
        vec!["solve", "quad-patch", "--json"],
    ] {
        assert_eq!(stdout(&args), stdout(&args), "{args:?}");
    }
    let dir = std::env::temp_dir().join(format!("lacuna-det-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (a, b) = (dir.join("a.json"), dir.join("b.json"));
    stdout(&[
        "verify",
        "triangle-C2",
        "--certificate",
        a.to_str().unwrap(),
    ]);
    stdout(&[
        "verify",
        "triangle-C2",
        "--certificate",
        b.to_str().unwrap(),
    ]);
    assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
}
