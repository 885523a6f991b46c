//! Benchmark (issue #2): a census of closure + counts (to level 10) over every face with boundary
//! length ≤ 6 over {B2, C2, B3, C3}, E over {B2, C2}³ and A1/A2. Reports faces per second and
//! per core, single-threaded and on all cores. Run with `cargo bench --bench census`.

use lacuna::{analysis::census, analysis::CensusSpec, topology::Limits};

fn main() {
    let cores = std::thread::available_parallelism()
        .map(|n| n.get())
        .unwrap_or(1);
    println!("census benchmark: boundaries ≤ 6 over B2,C2,B3,C3; E over {{B2,C2}}³; A1, A2; counts to level 10");
    for threads in [1, cores] {
        let spec = CensusSpec::parse("B2,C2,B3,C3", "B2,C2", "A1,A2", 6, Some(threads))
            .expect("valid spec");
        // Best of three runs.
        let mut best = f64::INFINITY;
        let mut last = None;
        for _ in 0..3 {
            let r = census(&spec, &Limits::default());
            best = best.min(r.elapsed_seconds);
            last = Some(r);
        }
        let r = last.expect("ran");
        let rate = r.faces as f64 / best;
        println!(
            "threads {threads}: {} faces ({} closed, {} refused), largest closure {} types, best {:.3} s: {:.0} faces/s, {:.0} faces/s per core",
            r.faces,
            r.closed,
            r.refused,
            r.largest.as_ref().map_or(0, |l| l.1),
            best,
            rate,
            rate / threads as f64
        );
    }
}
