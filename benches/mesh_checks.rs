// Benchmark of issue #30: the checks of the cube-B2 level-3 solid (91,200 triangles, as
// `render cube-B2 --level 3 --stl`) against writing its triangles as binary STL, in one run:
// wall-clock time of each phase and its ratio to the write. The phases:
// - build: evaluate, triangulate and check the solid (`volume_solid`: exact counts, manifold,
//   Euler characteristic, and the self-intersection test);
// - crossing: the self-intersection test alone (candidate pairs from the BVH of `mesh::bvh`);
// - sweep: the candidate pairs as the sweep along x before the BVH found them (pairs whose boxes
//   overlap in x, filtered on y and z; no triangle test), for comparison with the BVH;
// - wall: the wall-thickness bound (`mesh::wall`);
// - layers: the smallest hole and thinnest ligament of 20 horizontal layers (`mesh::slice`);
// - bridge: the largest bridge as built (`mesh::orient::largest_bridge`);
// - write: binary STL into memory.
// The peer named by the issue is Python writing the same triangles as binary STL (0.29 s there):
// the triangles are handed to `python3` (a raw f32 file, read before its clock starts), which
// times a plain `struct` writer — a normal per facet, 50 bytes a facet — into a file, in the same
// run. The ratios of the all-pairs tests (crossing and wall) and of every check to it are printed.
// `LEVEL=2 cargo bench --bench mesh_checks` runs a smaller level.

use lacuna::mesh::bvh::{Aabb, Bvh};
use lacuna::mesh::{self_intersection, stl, volume_solid, Part};
use lacuna::topology::volume::{parse_volume, VolumeClosure};
use lacuna::topology::Limits;
use std::time::Instant;

fn timed<T>(f: impl FnOnce() -> T) -> (T, f64) {
    let t = Instant::now();
    let r = f();
    (r, t.elapsed().as_secs_f64())
}

/// The candidate pairs of the sweep along x that the BVH replaced.
fn sweep_pairs(parts: &[Part]) -> u64 {
    let mut boxes: Vec<Aabb> = parts
        .iter()
        .flat_map(|p| {
            p.triangles
                .iter()
                .map(|t| Aabb::of(&t.map(|v| p.vertices[v as usize].map(f64::from))))
        })
        .collect();
    boxes.sort_by(|a, b| a.lo[0].total_cmp(&b.lo[0]));
    let mut n = 0u64;
    for i in 0..boxes.len() {
        for b in &boxes[i + 1..] {
            if b.lo[0] > boxes[i].hi[0] {
                break;
            }
            if b.overlaps(&boxes[i]) {
                n += 1;
            }
        }
    }
    n
}

fn main() {
    let level: u32 = std::env::var("LEVEL")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(3);
    let v = parse_volume("cube B2 | B2 B2 B2 | A1 | B2 B2 | V1").expect("cube-B2 parses");
    let VolumeClosure::Closed(set) =
        VolumeClosure::of(std::slice::from_ref(&v), &Limits::default()).expect("closure")
    else {
        panic!("cube-B2 closes")
    };
    let (vs, build) = timed(|| volume_solid("cube-B2", &v, &set, level, 100.0).expect("builds"));
    let parts = &vs.solid.parts;
    let ((crossing, tested), crossing_s) = timed(|| self_intersection(parts));
    assert!(crossing.is_none());
    let (swept, sweep_s) = timed(|| sweep_pairs(parts));
    let (bvh_pairs, bvh_s) = timed(|| {
        let boxes: Vec<Aabb> = parts
            .iter()
            .flat_map(|p| {
                p.triangles
                    .iter()
                    .map(|t| Aabb::of(&t.map(|v| p.vertices[v as usize].map(f64::from))))
            })
            .collect();
        let mut n = 0u64;
        Bvh::new(boxes).overlapping_pairs(|_, _| n += 1);
        n
    });
    assert_eq!(swept, bvh_pairs, "the BVH finds the sweep's pairs");
    let (wall, wall_s) = timed(|| lacuna::mesh::wall::wall_bound(parts));
    let (layers, layers_s) = timed(|| lacuna::mesh::slice::layer_features(parts, 20, 0.4));
    let (bridge, bridge_s) = timed(|| lacuna::mesh::orient::largest_bridge(parts));
    println!(
        "layers: {} sliced, smallest hole {:?}, thinnest ligament {:?}; largest bridge {:?} mm",
        layers.layers, layers.smallest_hole, layers.thinnest_ligament, bridge
    );
    let (bytes, write_s) = timed(|| {
        let mut out = Vec::new();
        stl::write_binary(&vs.solid, &mut out).expect("writes");
        out.len()
    });
    println!(
        "cube-B2 level {level}: {} triangles, {tested} pairs tested, {bytes} bytes of STL, wall ≥ {:.3} mm",
        vs.solid.triangle_count(),
        wall.map_or(f64::NAN, |w| w.thickness)
    );
    let python = python_write(parts);
    println!("{:<34} {:>10} {:>12}", "phase", "seconds", "÷ write");
    for (name, s) in [
        ("build and check (volume_solid)", build),
        ("crossing test (BVH)", crossing_s),
        ("candidate pairs, BVH", bvh_s),
        ("candidate pairs, x sweep (before)", sweep_s),
        ("wall bound (BVH)", wall_s),
        ("layers (20 slices)", layers_s),
        ("largest bridge", bridge_s),
        ("write binary STL", write_s),
    ] {
        println!("{name:<34} {s:>10.4} {:>12.1}", s / write_s);
    }
    match python {
        Some(py) => {
            let pairs = crossing_s + wall_s;
            let all = build + wall_s + layers_s + bridge_s;
            println!("peer: python3 writes the same triangles as binary STL in {py:.4} s");
            println!(
                "all-pairs tests (crossing + wall) {pairs:.4} s = {:.2} × the peer's write",
                pairs / py
            );
            println!(
                "every check (build and check, wall, layers, bridge) {all:.4} s = {:.2} × the peer's write",
                all / py
            );
        }
        None => println!("peer: python3 did not run; no ratio to it"),
    }
}

/// The peer: `python3` writing the triangles of `parts` as binary STL with `struct`, timed in
/// Python (seconds), or none when python3 is missing or fails.
fn python_write(parts: &[Part]) -> Option<f64> {
    let dir = std::env::temp_dir().join(format!("lacuna-bench-stl-{}", std::process::id()));
    std::fs::create_dir_all(&dir).ok()?;
    let raw = dir.join("triangles.f32");
    let mut bytes = Vec::new();
    for p in parts {
        for t in &p.triangles {
            for v in t {
                for x in p.vertices[*v as usize] {
                    bytes.extend_from_slice(&x.to_le_bytes());
                }
            }
        }
    }
    std::fs::write(&raw, &bytes).ok()?;
    let script = r#"
import array, struct, sys, time
raw = array.array('f'); raw.frombytes(open(sys.argv[1], 'rb').read())
n = len(raw) // 9
t0 = time.perf_counter()
with open(sys.argv[2], 'wb') as f:
    f.write(b'python peer'.ljust(80, b' ')); f.write(struct.pack('<I', n))
    pack = struct.Struct('<12fH').pack
    for i in range(n):
        ax, ay, az, bx, by, bz, cx, cy, cz = raw[9 * i: 9 * i + 9]
        ux, uy, uz, wx, wy, wz = bx - ax, by - ay, bz - az, cx - ax, cy - ay, cz - az
        nx, ny, nz = uy * wz - uz * wy, uz * wx - ux * wz, ux * wy - uy * wx
        l = (nx * nx + ny * ny + nz * nz) ** 0.5 or 1.0
        f.write(pack(nx / l, ny / l, nz / l, ax, ay, az, bx, by, bz, cx, cy, cz, 0))
print(time.perf_counter() - t0)
"#;
    let out = std::process::Command::new("python3")
        .arg("-c")
        .arg(script)
        .arg(&raw)
        .arg(dir.join("peer.stl"))
        .output()
        .ok()?;
    let _ = std::fs::remove_dir_all(&dir);
    String::from_utf8(out.stdout).ok()?.trim().parse().ok()
}
