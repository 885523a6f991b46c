//! Invariant: parsing any text as face notation either fails with a coded error whose span lies
//! inside the text, or succeeds and the printed face parses back to the same face.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    match lacuna::topology::Face::parse(text) {
        Ok(face) => {
            let again =
                lacuna::topology::Face::parse(&face.to_string()).expect("printed notation parses");
            assert_eq!(again, face);
        }
        Err(e) => {
            assert!(e.code().starts_with('E'));
            let _ = e.render();
        }
    }
});
