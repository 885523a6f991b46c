// Benchmark of issue #13: F0 at level 6 (46,656 cells) as one checked solid in binary STL and in
// 3MF, against the per-cell ASCII prisms of `lacuna::export::write_stl` (the writer `render --stl` used
// before the mesh layer), in one run: wall-clock time, peak resident memory of each phase and
// file size, and the ratios. `LEVEL=5 cargo bench --bench mesh` runs a smaller level.
//
// Peak memory per phase: the kernel's high-water mark (VmHWM) is reset before each phase by
// writing 5 to /proc/self/clear_refs (Linux); where that is refused the column says so.

use lacuna::mesh::{build, stl, threemf, Size};
use lacuna::{
    export::write_stl, geometry::instantiate, geometry::InstantiateOptions, input::load_input,
};
use std::io::BufWriter;
use std::time::Instant;

/// Resets the peak resident memory; false when the kernel refuses.
fn reset_peak() -> bool {
    std::fs::write("/proc/self/clear_refs", "5").is_ok()
}

/// The peak resident memory in MB since the last reset.
fn peak_mb() -> Option<f64> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = s.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb / 1024.0)
}

struct Phase {
    name: &'static str,
    seconds: f64,
    peak: Option<f64>,
    bytes: u64,
}

fn phase(name: &'static str, path: &std::path::Path, f: impl FnOnce()) -> Phase {
    let reset = reset_peak();
    let t = Instant::now();
    f();
    let seconds = t.elapsed().as_secs_f64();
    Phase {
        name,
        seconds,
        peak: if reset { peak_mb() } else { None },
        bytes: std::fs::metadata(path).map(|m| m.len()).unwrap_or(0),
    }
}

fn main() {
    let level: u32 = std::env::var("LEVEL")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(6);
    let segments = 4;
    let input = load_input("F0").expect("F0");
    let inst = instantiate(&input, &InstantiateOptions::default()).expect("instantiate");
    let dir = std::env::temp_dir();
    let create = |p: &std::path::Path| BufWriter::new(std::fs::File::create(p).expect("create"));
    let (old, bin, mf) = (
        dir.join(format!("lacuna-F0-{level}-prisms.stl")),
        dir.join(format!("lacuna-F0-{level}.stl")),
        dir.join(format!("lacuna-F0-{level}.3mf")),
    );
    let phases = [
        phase("old: ASCII prisms (write_stl)", &old, || {
            write_stl(&inst, level, segments, 0.04, create(&old)).expect("prisms");
        }),
        phase("build + check + binary STL", &bin, || {
            let s = build(&inst, level, segments, Size::default()).expect("solid");
            stl::write_binary(&s, create(&bin)).expect("stl");
        }),
        phase("build + check + 3MF", &mf, || {
            let s = build(&inst, level, segments, Size::default()).expect("solid");
            threemf::write(&s, create(&mf)).expect("3mf");
        }),
    ];
    println!(
        "F0 level {level}: {} cells, --segments {segments}",
        6u64.pow(level)
    );
    for p in &phases {
        println!(
            "  {:<32} {:>7.3} s  peak {:>9}  file {:>8.1} MB",
            p.name,
            p.seconds,
            p.peak.map_or("n/a".to_string(), |m| format!("{m:.1} MB")),
            p.bytes as f64 / 1e6
        );
    }
    for p in &phases[1..] {
        println!(
            "  {} against the old writer: time ×{:.2}, file ×{:.3}{}",
            p.name,
            p.seconds / phases[0].seconds,
            p.bytes as f64 / phases[0].bytes as f64,
            match (p.peak, phases[0].peak) {
                (Some(a), Some(b)) => format!(", peak memory ×{:.2}", a / b),
                _ => String::new(),
            }
        );
    }
    for p in [&old, &bin, &mf] {
        let _ = std::fs::remove_file(p);
    }
}
