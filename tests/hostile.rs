//! Hostile inputs to every command: a coded error and exit code 2, never a panic, a hang or a
//! silent answer (issue #8's list, as far as the formats exist today).

use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

fn run(args: &[&str]) -> (i32, String) {
    let start = Instant::now();
    let out = Command::new(env!("CARGO_BIN_EXE_lacuna"))
        .args(args)
        .stdin(Stdio::null())
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("runs");
    assert!(
        start.elapsed() < Duration::from_secs(30),
        "{args:?} took {:?}",
        start.elapsed()
    );
    let err = String::from_utf8_lossy(&out.stderr).to_string();
    assert!(!err.contains("panicked"), "{args:?} panicked: {err}");
    (out.status.code().expect("not killed by a signal"), err)
}

/// A path in this test's temporary folder, for outputs that must never be written (the
/// checkout's `target/` may not exist: issue #20 item 6).
fn out_path(name: &str) -> String {
    let dir = std::env::temp_dir().join(format!("lacuna-hostile-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name).to_string_lossy().into_owned()
}

fn temp(name: &str, bytes: &[u8]) -> String {
    let dir = std::env::temp_dir().join(format!("lacuna-hostile-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    p.to_string_lossy().into_owned()
}

#[test]
fn hostile_inputs_get_coded_errors_from_every_command() {
    let svg = out_path("hostile.svg");
    let mut huge = String::from("face 0:");
    for _ in 0..1_000_000 {
        huge.push_str(" B2");
    }
    huge.push_str(" | C2 B2 B2 | A1\n");
    let files = [
        temp("huge.txt", huge.as_bytes()),
        temp("binary.txt", &[0xff, 0xfe, 0x00, 0x41]),
        temp(
            "nan.txt",
            b"f\nC_2_0 - B_2_0 / C_2_0 - B_2_0 - B_2_0 / 0 / 1\np\nNaN 0\n",
        ),
        temp(
            "bigcoord.txt",
            b"f\nC_2_0 - B_2_0 / C_2_0 - B_2_0 - B_2_0 / 0 / 1\np\n1e400 0\n",
        ),
        temp("empty.txt", b""),
        temp(
            "selfloop.txt",
            b"face 0: B2 B2 | C2 B2 B2 | A1\nface 0 edge 0 ~ face 0 edge 0\n",
        ),
        temp(
            "nonlinear.aut",
            b"state e 2\nsub a : e <- e\nsub b : e <- e\na * b = a\n",
        ),
    ];
    let mut inputs: Vec<String> = [
        "",
        " | | ",
        "B0 B2 | C2 B2 B2 | A1",
        "C1 B2 | C2 B2 B2 | A1",
        "B2^0 B2 | C2 B2 B2 | A1",
        "B2 B2 | C2 B2 B2 | A1 | 1 | 2",
        "B2 B2 || C2 B2 B2 | A1",
        "B99999999999999999999 | C2 B2 B2 | A1",
        "B2 B2 | C2 B2 B2 | A1 | 99999999999",
        "B2 B2 | C2 B2 B2 | {joint",
        "B2^2 B2^2 | C2 B2 B2 | A1",
        "no-such-file-or-library-entry",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    inputs.extend(files);
    for input in &inputs {
        for cmd in [
            vec!["verify", input.as_str()],
            vec!["closure", input.as_str()],
            vec!["counts", input.as_str(), "--levels", "2"],
            vec!["ratio", input.as_str()],
            vec!["solve", input.as_str()],
            vec!["measure", input.as_str(), "--level", "1", "--raster", "64"],
            vec![
                "render",
                input.as_str(),
                "--level",
                "1",
                "--svg",
                svg.as_str(),
            ],
        ] {
            let (code, err) = run(&cmd);
            assert_eq!(code, 2, "{cmd:?} should be refused: {err}");
            assert!(err.contains("error[E"), "{cmd:?}: no coded error: {err}");
        }
    }
}

#[test]
fn absurd_levels_and_digits_are_refused_before_the_work() {
    let svg = out_path("hostile.svg");
    for args in [
        vec!["counts", "F0", "--levels", "18446744073709551615"],
        vec!["verify", "F0", "--levels", "1000000000"],
        vec!["ratio", "F0", "--digits", "1000000000"],
        vec!["solve", "F0", "--max-unknowns", "100"],
        vec!["verify", "F0", "--max-unknowns", "100"],
        vec!["solve", "spec-edge", "--max-unknowns", "10"],
        vec!["render", "F0", "--level", "9", "--svg", svg.as_str()],
    ] {
        let (code, err) = run(&args);
        assert_eq!(code, 2, "{args:?}: {err}");
        // A limit error (E0501), or the cell limit of the geometry (E1003), naming its flag.
        assert!(
            (err.contains("E0501") || err.contains("E1003")) && err.contains("(raise it with --"),
            "{args:?}: {err}"
        );
    }
    // Values outside a flag's fixed range (E0503, naming the flag and the range) and flags that
    // do not fit together (E0504): not limits to raise.
    let png_path = out_path("hostile.png");
    let h_png = out_path("h.png");
    let png = ["--png", png_path.as_str()];
    for (args, code, flag) in [
        (
            vec!["render", "F0", "--size", "100000"],
            "E0503",
            "--size 100000",
        ),
        (vec!["render", "F0", "--size", "0"], "E0503", "--size 0"),
        // Fixed ranges, not limits (issue #20 item 12).
        (
            vec!["solve", "F0", "--degree", "99"],
            "E0503",
            "--degree 99",
        ),
        (
            vec!["measure", "F0", "--raster", "1000000"],
            "E0503",
            "--raster 1000000",
        ),
        (
            vec!["measure", "F0", "--raster", "100"],
            "E0503",
            "--raster 100",
        ),
        (
            vec!["measure", "F0", "--raster", "1024", "--max-raster", "512"],
            "E0503",
            "--max-raster 512",
        ),
        (
            vec![
                "render",
                "F0",
                "--density-grid",
                "0",
                "--density",
                h_png.as_str(),
            ],
            "E0503",
            "--density-grid 0",
        ),
        (vec!["render", "F0"], "E0504", "nothing to write"),
    ] {
        let mut args = args;
        if args[0] == "render" && args.contains(&"--size") {
            args.extend(png);
        }
        let (status, err) = run(&args);
        assert_eq!(status, 2, "{args:?}: {err}");
        assert!(
            err.contains(&format!("error[{code}]")) && err.contains(flag),
            "{args:?}: {err}"
        );
        assert!(!err.contains("raise it with"), "{args:?}: {err}");
    }
}

#[test]
fn hostile_coordinates_templates_and_goals_get_coded_errors() {
    let h_svg = out_path("h.svg");
    let big = format!("1{}", "0".repeat(400));
    let long_line = format!("type T0\nsub 0 {}\n", "0 0; ".repeat(200_000));
    let cases: Vec<(Vec<String>, &str)> = vec![
        // Template files: empty of sub-faces is fine (nothing to project) only when it parses;
        // garbage, non-UTF-8, huge and non-finite numbers, a very long line.
        (
            vec!["--template".into(), temp("t1.tpl", b"\xff\xfe\x00")],
            "E0",
        ),
        (
            vec![
                "--template".into(),
                temp("t2.tpl", b"type T0\nsub 0 NaN 0\n"),
            ],
            "E10",
        ),
        (
            vec![
                "--template".into(),
                temp("t3.tpl", format!("type T0\nsub 0 {big} 0\n").as_bytes()),
            ],
            "E10",
        ),
        (
            vec!["--template".into(), temp("t4.tpl", long_line.as_bytes())],
            "E10",
        ),
        (
            vec!["--template".into(), temp("t5.tpl", b"delta -1\n")],
            "E10",
        ),
        // Corners on the command line.
        (vec!["--corners".into(), "NaN 0, 1 0, 1 1".into()], "E02"),
        (
            vec![
                "--corners".into(),
                format!("{big} 0, 1 0, 1 1, 0 1, 0 2, 5 5"),
            ],
            "E02",
        ),
        (
            vec!["--corners".into(), "0 0, 0 0, 0 0, 0 0, 0 0, 0 0".into()],
            "E02",
        ),
        (vec!["--corners".into(), ",,,".into()], "E02"),
        // Goals.
        (vec!["--goal".into(), format!("min-lacuna={big}")], "E10"),
        (vec!["--goal".into(), "min-lacuna=inf".into()], "E10"),
        (vec!["--goal".into(), "nonnegative=1/0".into()], "E10"),
        (vec!["--goal".into(), "".into()], "E10"),
    ];
    for (extra, code) in cases {
        let mut args: Vec<String> = ["render", "F0", "--level", "1", "--svg", &h_svg]
            .map(String::from)
            .to_vec();
        args.extend(extra);
        let argv: Vec<&str> = args.iter().map(String::as_str).collect();
        let (status, err) = run(&argv);
        assert_ne!(status, 0, "{argv:?}: {err}");
        assert!(
            err.contains(&format!("error[{code}")),
            "{:?}: {}",
            &argv[6..],
            err.chars().take(400).collect::<String>()
        );
    }
}
