//! Benchmark (issue #34): lacuna's operator kernel in process, as `lacuna operators F0` runs it on
//! every self-mapping subdivision operator (characteristic polynomial, factorisation over Q, real
//! roots, certified complex disks, eigenvectors, fixed point, contraction and the §8 class:
//! [`lacuna::analysis::analyse_matrix`]), without loading, instantiation or the report. The
//! matrices are built once, outside the clock. Prints the best of 20 runs and the sizes.
//!
//! Run: `cargo bench --bench operators [-- INPUT] [-- --matrices FILE]`. INPUT defaults to F0;
//! `--matrices FILE` reads one matrix per line (`[a b; c d]`, as `benches/compare_operators.sh`
//! exports them) instead.

use lacuna::analysis::{analyse_matrix, parse_matrix_arg};
use lacuna::constraint::OpKind;
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| a != "--bench")
        .collect();
    let file = args
        .iter()
        .position(|a| a == "--matrices")
        .and_then(|i| args.get(i + 1));
    let matrices: Vec<_> = match file {
        Some(f) => std::fs::read_to_string(f)
            .expect("matrices file")
            .lines()
            .filter(|l| !l.trim().is_empty())
            .map(|l| parse_matrix_arg(l.trim()).expect("matrix"))
            .collect(),
        None => {
            let input = args
                .iter()
                .find(|a| !a.starts_with("--"))
                .map_or("F0", String::as_str);
            let limits = lacuna::topology::Limits::default();
            let loaded = lacuna::input::load_any(input).expect("input");
            let a = lacuna::export::operators_automaton(loaded, &limits).expect("automaton");
            a.automaton
                .operators
                .iter()
                .filter(|o| o.kind == OpKind::Sub && o.to == o.from)
                .filter_map(|o| o.value.clone())
                .collect()
        }
    };
    let mut best = f64::INFINITY;
    let mut reports = Vec::new();
    for _ in 0..20 {
        let t = Instant::now();
        reports = matrices
            .iter()
            .map(|m| analyse_matrix(m).expect("analysis"))
            .collect::<Vec<_>>();
        best = best.min(t.elapsed().as_secs_f64());
    }
    let sizes: Vec<String> = matrices
        .iter()
        .map(|m| format!("{}x{}", m.rows, m.cols))
        .collect();
    println!("matrices: {} ({})", reports.len(), sizes.join(" "));
    println!("lacuna kernel (analyse_matrix, best of 20): {best:.6} s");
}
