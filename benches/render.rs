// Benchmark of issue #6: level 9 of F0 (6^9 ≈ 10 million cells) rendered to a 4096×4096 PNG and
// box-counted down to boxes of 1/4096. The evaluation is depth-first, so memory does not grow with
// the level (the raster dominates: 16 MB of coverage counts). `LEVEL=7 cargo bench --bench render`
// runs a smaller level.

use lacuna::{
    export::render_raster, export::write_png, geometry::box_dimension, geometry::instantiate,
    geometry::InstantiateOptions, input::load_input,
};
use std::time::Instant;

fn main() {
    let level: u32 = std::env::var("LEVEL")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(9);
    let size = 4096;
    let t0 = Instant::now();
    let input = load_input("F0").expect("F0");
    let inst = instantiate(&input, &InstantiateOptions::default()).expect("instantiate");
    let t_inst = t0.elapsed();
    let t1 = Instant::now();
    let raster = render_raster(&inst, level, size, 1);
    let t_render = t1.elapsed();
    let t2 = Instant::now();
    let fit = box_dimension(&raster, 4);
    let t_box = t2.elapsed();
    let t3 = Instant::now();
    let path = std::env::temp_dir().join(format!("lacuna-F0-{level}.png"));
    write_png(
        &raster,
        std::io::BufWriter::new(std::fs::File::create(&path).expect("create")),
    )
    .expect("png");
    let t_png = t3.elapsed();
    // Arithmetic lower bound: every node of the tree (Σ 6^i) computes its 9 control points from
    // its parent's 9 (2·9·9 multiply-adds); every leaf is a 9-gon filled on the raster.
    let nodes: u64 = (0..=level).map(|i| 6u64.pow(i)).sum();
    let cells = 6u64.pow(level);
    let flops = nodes * 2 * 9 * 9 * 2;
    let bound = flops as f64 / 1e9; // seconds at 1 Gflop/s, one core
    let total = t_render.as_secs_f64();
    println!("F0 level {level}: {cells} cells, raster {size}×{size}");
    println!(
        "  instantiate (exact solve + fit): {:.3} s",
        t_inst.as_secs_f64()
    );
    println!(
        "  evaluate + rasterise: {total:.3} s ({:.0} ns per cell)",
        total * 1e9 / cells as f64
    );
    println!(
        "  box counting k = 4..12: {:.3} s, dimension {:.4} (residual {:.4})",
        t_box.as_secs_f64(),
        fit.slope,
        fit.residual
    );
    println!(
        "  PNG (1-bit, stored): {:.3} s -> {}",
        t_png.as_secs_f64(),
        path.display()
    );
    println!(
        "  lower bound {:.0} Mflop of point arithmetic ≈ {bound:.3} s at 1 Gflop/s: ratio {:.1}",
        flops as f64 / 1e6,
        total / bound
    );
}
