//! Benchmark (issue #4): the exact solver on the constraint systems of a series of growing
//! closures. For each face: unknowns, equations, the time to build the system from the automaton
//! (`Automaton::linearize`, best of 3), the time to solve it (best of 3, release), and whether the
//! system is consistent. Build and solve are timed apart (issue #34). With `--export DIR` it also writes each system as a sparse
//! text matrix (`lacuna::constraint::write_text`) for the FLINT comparison in `benches/compare_flint.sh`
//! and the SymPy one in `benches/compare_peers.sh`: the systems of at most 20,000 unknowns, or of
//! at most `EXPORT_MAX_UNKNOWNS` when that variable is set.
//!
//! Run: `cargo bench --bench solver [-- --export DIR]`.

use lacuna::{
    constraint::automaton_of, constraint::solve, constraint::write_text, constraint::GenOptions,
    constraint::Solution, constraint::TextLayout, topology::close_or_error, topology::Face,
    topology::Limits,
};
mod common;

/// Faces whose closures grow from a few hundred to over a million unknowns.
const SERIES: &[&str] = &[
    "C2 B2 C2 B2 C2 B2 | C2 B2 B2 | A1",
    "C2 C2 C2 | B2 B2 B2 | A1",
    "B2 C2^2 | C2 B2 B2 | A3",
    "C2 B3 C3 C3 B3 B3 | B2 C2 C2 | A1",
    "B3 C2 B2^3 C3 B2 | C2 B2 C2 | A3",
    "B4 C4 B3^3 C4 B4 C3 B2^2 | C3 B2 C3 | A3",
    "B3 C2 B2^3 C3 B2 | C2 B2 C2 | A3 | 2",
    "B4 C4 B3^3 C4 B4 C3 B2^2 | C3 B2 C3 | A3 | 2",
    "B3 C2 B2^3 C3 B2 | C2 B2 C2 | A3 | 3",
    "B4 C4 B3^3 C4 B4 C3 B2^2 | C3 B2 C3 | A3 | 3",
];

fn main() {
    let export = common::export_dir();
    let export_max: usize = std::env::var("EXPORT_MAX_UNKNOWNS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(20_000);
    println!(
        "{:>3}  {:>6}  {:>9}  {:>9}  {:>10}  {:>10}  {:>10}  face",
        "#", "types", "unknowns", "equations", "build (s)", "solve (s)", "consistent"
    );
    for (k, text) in SERIES.iter().enumerate() {
        let face = Face::parse(text).expect("valid face");
        let ts = close_or_error(&[face], &Limits::default()).expect("closes");
        let g = automaton_of(&ts, GenOptions::default());
        let (build, lin) = common::best_of(3, || g.automaton.linearize().expect("linear"));
        let (best, consistent) =
            common::best_of(3, || matches!(solve(&lin.system), Solution::Consistent(_)));
        println!(
            "{k:>3}  {:>6}  {:>9}  {:>9}  {build:>10.4}  {best:>10.4}  {consistent:>10}  {text}",
            ts.types.len(),
            lin.system.unknowns,
            lin.system.rows.len()
        );
        if let Some(dir) = &export {
            if lin.system.unknowns <= export_max {
                let path = format!("{dir}/system_{k}.txt");
                let file = std::io::BufWriter::new(std::fs::File::create(&path).expect("create"));
                write_text(&lin.system, TextLayout::Sparse, file).expect("write");
            }
        }
    }
}
