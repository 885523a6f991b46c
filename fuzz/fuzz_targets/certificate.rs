//! Invariant: the checker on any bytes (a mutated certificate) rejects or accepts, never panics.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let report = lacuna::checker::check_json(text);
    let _ = report.all_proved();
});
