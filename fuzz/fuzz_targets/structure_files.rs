//! Invariant: any text read as a production-rule file or a volume file gives a coded error, or a
//! rule whose compiled automaton parses and a volume file whose volumes are all spheres — never a
//! panic or a hang.
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
