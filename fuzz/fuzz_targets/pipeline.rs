//! Invariant: the whole topology pipeline on a fuzzed face, under small limits, ends in a closed
//! closure whose identities hold, a runaway, or a coded error — never a panic or a hang.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(face) = lacuna::topology::Face::parse(text) else {
        return;
    };
    let limits = lacuna::topology::Limits {
        max_boundary: 48,
        max_types: 200,
        max_level: 20,
        max_subedges: 6,
        max_delay: 4,
        max_digits: 100,
        max_unknowns: 100_000,
        max_memory_mb: 256,
        max_matrix: 8,
    };
    if let Ok(lacuna::topology::Closure::Closed(ts)) = lacuna::topology::close(&face, &limits) {
        ts.verify().expect("closure identities");
        let _ = lacuna::topology::counts(&ts, 8);
    }
});
