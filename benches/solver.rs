//! Benchmark (issue #4): the exact solver on the constraint systems of a series of growing
//! closures. For each face: unknowns, equations, the time to build the system from the automaton
//! (`Automaton::linearize`), the time to solve it (release), and whether the system is
//! consistent. Each time is the best of at least 3 runs, repeated until half a second is spent:
//! the small systems take about 2 ms, where a best of 3 moved by half from one run to the next.
//! Last, the growth of the solve time with the unknowns (issue #34) from the systems of at least
//! 5,000 unknowns: the exponent between the smallest and the largest of them, and the
//! least-squares slope of ln(time) against ln(unknowns) over all of them. Build and solve are timed apart (issue #34). With `--export DIR` it also writes each system as a sparse
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
    let mut points: Vec<(f64, f64)> = vec![];
    for (k, text) in SERIES.iter().enumerate() {
        let face = Face::parse(text).expect("valid face");
        let ts = close_or_error(&[face], &Limits::default()).expect("closes");
        let g = automaton_of(&ts, GenOptions::default());
        let (build, lin) = common::best_within(3, 0.5, || g.automaton.linearize().expect("linear"));
        let (best, consistent) = common::best_within(3, 0.5, || {
            matches!(solve(&lin.system), Solution::Consistent(_))
        });
        points.push((lin.system.unknowns as f64, best));
        println!(
            "{k:>3}  {:>6}  {:>9}  {:>9}  {build:>10.4}  {best:>10.4}  {consistent:>10}  {text}",
            ts.types.len(),
            lin.system.unknowns,
            lin.system.len()
        );
        if let Some(dir) = &export {
            if lin.system.unknowns <= export_max {
                let path = format!("{dir}/system_{k}.txt");
                let file = std::io::BufWriter::new(std::fs::File::create(&path).expect("create"));
                write_text(&lin.system, TextLayout::Sparse, file).expect("write");
            }
        }
    }
    growth(&points);
}

/// Prints the growth exponents of the solve over the systems of at least 5,000 unknowns.
fn growth(points: &[(f64, f64)]) {
    let big: Vec<(f64, f64)> = points
        .iter()
        .filter(|(n, t)| *n >= 5000.0 && *t > 0.0)
        .map(|(n, t)| (n.ln(), t.ln()))
        .collect();
    if big.len() < 2 {
        return;
    }
    let lo = big
        .iter()
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .expect("two points");
    let hi = big
        .iter()
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .expect("two points");
    let k = big.len() as f64;
    let (mx, my) = (
        big.iter().map(|p| p.0).sum::<f64>() / k,
        big.iter().map(|p| p.1).sum::<f64>() / k,
    );
    let sxy: f64 = big.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = big.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
    println!(
        "growth of the solve over the {} systems of at least 5,000 unknowns: smallest to largest n^{:.3}, least-squares slope n^{:.3}",
        big.len(),
        (hi.1 - lo.1) / (hi.0 - lo.0),
        sxy / sxx
    );
}
