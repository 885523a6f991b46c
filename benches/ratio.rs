//! Benchmark (issue #3): the exact limit ratio R with 50 certified digits, on the largest closure
//! of the census (17 types) and on closures of at least 20 types. Prints the best of 3 times.
//! With `--export DIR` it writes each substitution matrix, contribution vector and start vector
//! as JSON for the SymPy comparison in `benches/compare_sympy.sh`.
//!
//! Run: `cargo bench --bench ratio [-- --export DIR]`.

use lacuna::{export::ratio_of, topology::close_or_error, topology::Face, topology::Limits};
mod common;

const FACES: &[&str] = &[
    "C2 B3 C3 C3 B3 B3 | B2 C2 C2 | A1",
    "B4 C4 B3^3 C4 B4 C3 B2^2 | C3 B2 C3 | A3",
    "B4 C4 B3^3 C4 B4 C3 B2^2 | C3 B2 C3 | A3 | 3",
    "B2 B2 B2 B2 C2 | B2 C2 B2 | A1",
];

fn main() {
    let export = common::export_dir();
    println!(
        "{:>3}  {:>5}  {:>10}  {:<24}  R (50 digits)  face",
        "#", "types", "R (s)", "rho"
    );
    for (k, text) in FACES.iter().enumerate() {
        let ts = close_or_error(&[Face::parse(text).expect("valid")], &Limits::default())
            .expect("closes");
        let (best, r) = common::best_of(3, || ratio_of(&ts, 50).expect("ratio"));
        println!(
            "{k:>3}  {:>5}  {best:>10.4}  {:<24}  {}  {text}",
            ts.types.len(),
            r.perron_root,
            r.decimal.as_deref().unwrap_or("(no limit)")
        );
        if let Some(dir) = &export {
            let c: Vec<String> = ts
                .types
                .iter()
                .map(|t| format!("{}/2", t.contribution_halves()))
                .collect();
            let json = serde_json::json!({
                "face": text,
                "matrix": ts.matrix(),
                "contributions": c,
                "start": ts.start,
                "lacuna_seconds": best,
                "lacuna_decimal": r.decimal,
            });
            std::fs::write(
                format!("{dir}/ratio_{k}.json"),
                serde_json::to_string(&json).expect("json"),
            )
            .expect("write");
        }
    }
}
