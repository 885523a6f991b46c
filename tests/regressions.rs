//! Every fuzz crash becomes a named regression test: the input is kept in tests/regressions/.

use lacuna::{constraint::solve, constraint::Solution, input::parse_automaton, Source};

fn solve_file(name: &str) -> (Solution, lacuna::constraint::LinearSystem) {
    let path = format!("{}/tests/regressions/{name}", env!("CARGO_MANIFEST_DIR"));
    let text = String::from_utf8_lossy(&std::fs::read(&path).unwrap()).into_owned();
    let a = parse_automaton(&Source { name: path, text }).expect("parses");
    let lin = a.linearize().expect("linear");
    (solve(&lin.system), lin.system)
}

/// Found by the `automaton_file` fuzz target: elimination fill-in made a row longer than every
/// row of the start, and the solver indexed past its length buckets (a panic). Both inputs are
/// inconsistent systems with huge coefficients; the conflict must verify.
#[test]
fn solver_fill_in_longer_than_every_starting_row() {
    for name in [
        "solver-fill-in-longer-row-1.aut",
        "solver-fill-in-longer-row-2.aut",
    ] {
        let (sol, sys) = solve_file(name);
        match sol {
            Solution::Inconsistent(c) => c.check(&sys).unwrap_or_else(|e| panic!("{name}: {e}")),
            Solution::Consistent(s) => s.check(&sys).unwrap_or_else(|e| panic!("{name}: {e}")),
        }
    }
}

/// Found by the `automaton_file` fuzz target in CI: a word containing a non-ASCII character whose
/// UTF-8 bytes include 0xA0 was scanned byte by byte with `char::is_whitespace` (0xA0 as a char is
/// a no-break space), which cut the text inside a character (a panic). Scanning now tests ASCII
/// bytes only; the file must give a coded error or an automaton, never a panic.
#[test]
fn automaton_word_with_a_multibyte_character() {
    let path = format!(
        "{}/tests/regressions/automaton-word-multibyte.aut",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = String::from_utf8_lossy(&std::fs::read(&path).unwrap()).into_owned();
    let _ = parse_automaton(&Source { name: path, text });
}
