//! Invariant: any text read as a production-rule file or a volume file gives a coded error, or a
//! rule whose compiled automaton parses and a volume file whose volumes are all spheres (with
//! coordinates, if any, for every corner, and a placement or a coded error) — never a panic or a
//! hang.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let src = lacuna::Source {
        name: "fuzz".into(),
        text: text.into(),
    };
    // The text picks the reader as lacuna does (a rule has an `initiator` line), so one corpus
    // feeds both.
    if !lacuna::input::is_rule(text) {
        match lacuna::input::parse_volume_file(&src) {
            Ok(f) => {
                for v in &f.assembly.volumes {
                    if let Err(why) = v.surface.check() {
                        panic!("an accepted volume is not a sphere: {why}");
                    }
                }
                // Coordinates, when given, are one point per corner of every face.
                assert_eq!(f.corners.len(), f.assembly.volumes.len());
                for (v, c) in f.assembly.volumes.iter().zip(&f.corners) {
                    if let Some(c) = c {
                        assert_eq!(c.len(), v.surface.faces.len());
                        for (face, pts) in v.surface.faces.iter().zip(c) {
                            assert_eq!(face.boundary.len(), pts.len());
                        }
                    }
                }
                // Placing the start volumes is a coded error or a placement, never a panic.
                if let Err(e) = lacuna::geometry::place_assembly(&f.assembly, &f.corners, &f.names)
                {
                    let _ = e.render();
                }
            }
            Err(e) => {
                let _ = e.render();
            }
        }
    } else {
        match lacuna::input::compile_rule(&src) {
            Ok((_, model)) => assert!(!model.automaton.states.is_empty()),
            Err(e) => {
                let _ = e.render();
            }
        }
    }
});
