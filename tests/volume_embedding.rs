//! A level-3 solid that folded under the first two inner-face rules embeds under the third
//! (issue #31): tetrahedron C2 A1 V1 at level 3 was "NOT EMBEDDED" (an inner face shrunk half of
//! the way to its volume's centre cut through its own bent patch). `render` now writes its mesh
//! (exit 0), names the rule that drew it, and `check-mesh`, which shares no code with the
//! writer, accepts the file with the parts, Euler characteristic and genus `render` printed.

mod common;
use common::{lacuna, number_after};

#[test]
fn the_level_three_cantor_tetrahedron_embeds_and_its_mesh_checks() {
    let d = std::env::temp_dir().join(format!("lacuna-volume-embedding-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    let stl = d.join("t.stl");
    let stl_s = stl.display().to_string();
    let (code, out, err) = lacuna(&[
        "render",
        "tetrahedron C2 | B2 B2 B2 | A1 | B2 B2 | V1",
        "--level",
        "3",
        "--stl",
        &stl_s,
    ]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(!out.contains("NOT EMBEDDED"), "{out}");
    assert!(
        out.contains("inner faces fanned around a point seen from their volume's centre"),
        "{out}"
    );
    assert!(stl.exists(), "no mesh written: {out}{err}");
    let euler = number_after(&out, "surface Euler characteristic");
    let genus = number_after(&out, "surface piece, genus");
    let (code, json, err) = lacuna(&["check-mesh", &stl_s, "--json"]);
    assert_eq!(code, 0, "{json}{err}");
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert_eq!(v["euler"], euler, "{v:#}");
    assert_eq!(v["genus"], genus, "{v:#}");
    assert_eq!(v["parts"].as_array().unwrap().len(), 1, "{v:#}");
    let _ = std::fs::remove_dir_all(&d);
}
