//! Invariant: any text read as an automaton file gives a coded error, or an automaton whose
//! linear system builds (or fails with a coded error) and solves to a result that re-checks.
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
    let Ok(a) = lacuna::input::parse_automaton(&src) else {
        return;
    };
    let Ok(lin) = a.linearize() else { return };
    if lin.system.unknowns > 2_000 || lin.system.len() > 4_000 {
        return;
    }
    match lacuna::constraint::solve(&lin.system) {
        lacuna::constraint::Solution::Consistent(s) => {
            s.check(&lin.system).expect("solution re-checks")
        }
        lacuna::constraint::Solution::Inconsistent(c) => {
            c.check(&lin.system).expect("conflict re-checks")
        }
    }
});
