//! Invariant: any text read as an assembly or AutoFrac2D file gives a coded error or an assembly
//! whose shared edges all pass their checks.
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
    match lacuna::input::parse_text(&src) {
        Ok(a) => {
            for s in &a.shared {
                assert_eq!(
                    a.faces[s.a.0].1.boundary[s.a.1],
                    a.faces[s.b.0].1.boundary[s.b.1]
                );
            }
        }
        Err(e) => {
            let _ = e.render();
        }
    }
});
