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
pub fn best_of<T>(runs: usize, mut f: impl FnMut() -> T) -> (f64, T) {
    let mut best = f64::INFINITY;
    let mut last = None;
    for _ in 0..runs.max(1) {
        let t = Instant::now();
        let r = f();
        best = best.min(t.elapsed().as_secs_f64());
        last = Some(r);
    }
    (best, last.expect("ran at least once"))
}
