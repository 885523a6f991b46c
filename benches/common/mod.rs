//! Shared by the benchmark harnesses: the `--export DIR` argument and best-of-n timing.

use std::time::Instant;

/// The directory after `--export`, created, when given.
pub fn export_dir() -> Option<String> {
    let args: Vec<String> = std::env::args().collect();
    let dir = args
        .iter()
        .position(|a| a == "--export")
        .and_then(|i| args.get(i + 1))
        .cloned();
    if let Some(dir) = &dir {
        std::fs::create_dir_all(dir).expect("export directory");
    }
    dir
}

/// Runs `f` `runs` times; the best wall-clock time in seconds and the last result.
#[allow(dead_code)] // each bench includes this module; the ratio bench calls this one
pub fn best_of<T>(runs: usize, f: impl FnMut() -> T) -> (f64, T) {
    best_within(runs, 0.0, f)
}

/// Like [`best_of`], but keeps running past `min_runs` until `budget` seconds have been spent
/// (at most 1,000 runs): a best of three is noise for a 2 ms figure, a few hundred are not.
pub fn best_within<T>(min_runs: usize, budget: f64, mut f: impl FnMut() -> T) -> (f64, T) {
    let start = Instant::now();
    let mut best = f64::INFINITY;
    let mut last = None;
    let mut runs = 0;
    while runs < min_runs.max(1) || (start.elapsed().as_secs_f64() < budget && runs < 1000) {
        let t = Instant::now();
        let r = f();
        best = best.min(t.elapsed().as_secs_f64());
        last = Some(r);
        runs += 1;
    }
    (best, last.expect("ran at least once"))
}
