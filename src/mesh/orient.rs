//! Orientation for printing (GEOMETRY §5): for each of the six axis directions taken as "down",
//! the overhang a printer must support and the area resting on the bed; `--orient auto` turns the
//! solid so that the best of them is down.
//!
//! **Overhang**: the area of the triangles whose outward normal points down within
//! [`OVERHANG_DEGREES`] of straight down (a surface more than 45° from vertical, facing down:
//! the usual limit of a fused-filament printer without supports), except those lying on the bed.
//! **Bed contact**: the area of the triangles lying in the bed plane (every vertex within
//! [`BED_TOLERANCE`] of the lowest point) and facing down. A solid with no bed contact touches
//! the bed at points or edges only: a slicer finds nothing to extrude in the first layer
//! without supports or a raft.
//!
//! **The choice** (`auto`): among the directions with a bed contact, the least overhang (ties:
//! the lower object); when none has a contact, the solid as built (the least overhang would
//! often stand a shell on an edge), and the advice to print with supports or a raft. Only the six axis directions are tried: the turn is then a permutation of the
//! coordinates with signs, exact in `f32`, so the mesh checked before is the mesh written (a
//! rotation by another angle would round the vertices and would have to be checked again).
//! These are floating-point figures that advise; they decide no verdict.

use super::solid::Part;
use serde::Serialize;

/// A downward surface steeper than this from vertical needs support, in degrees.
pub const OVERHANG_DEGREES: f64 = 45.0;

/// How close to the lowest point a vertex must be to lie on the bed, in mm.
pub const BED_TOLERANCE: f64 = 1e-3;

/// The six directions, as the names and unit vectors of "down".
const DOWN: [(&str, [f64; 3]); 6] = [
    ("-z", [0.0, 0.0, -1.0]),
    ("+z", [0.0, 0.0, 1.0]),
    ("-y", [0.0, -1.0, 0.0]),
    ("+y", [0.0, 1.0, 0.0]),
    ("-x", [-1.0, 0.0, 0.0]),
    ("+x", [1.0, 0.0, 0.0]),
];

/// The overhang and bed contact with one axis direction down.
#[derive(Clone, Debug, Serialize)]
pub struct Overhang {
    /// The direction that points down (`-z` is the solid as built).
    pub down: &'static str,
    /// The area of the downward surfaces steeper than [`OVERHANG_DEGREES`], mm².
    pub overhang_mm2: f64,
    /// The area resting on the bed, mm².
    pub bed_contact_mm2: f64,
    /// The object's height with this direction down, mm.
    pub height_mm: f64,
}

/// The report: every direction, the one in force and why.
#[derive(Clone, Debug, Serialize)]
pub struct Orientation {
    /// Each direction's figures, as built (`-z`) first.
    pub candidates: Vec<Overhang>,
    /// The direction down in the file written.
    pub chosen: &'static str,
    /// The total surface area, mm².
    pub surface_mm2: f64,
    /// Why it was chosen (or that it was kept).
    pub reason: String,
    /// Whether the object needs supports or a raft in the chosen orientation: no area rests on
    /// the bed.
    pub needs_support: bool,
}

/// Unit normal and area of a triangle.
fn normal_area(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> ([f64; 3], f64) {
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let w = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    let n = [
        u[1] * w[2] - u[2] * w[1],
        u[2] * w[0] - u[0] * w[2],
        u[0] * w[1] - u[1] * w[0],
    ];
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    match len > 0.0 {
        true => (n.map(|x| x / len), len / 2.0),
        false => ([0.0; 3], 0.0),
    }
}

/// The figures of every axis direction, as built first.
pub fn overhangs(parts: &[Part]) -> (Vec<Overhang>, f64) {
    let cos = OVERHANG_DEGREES.to_radians().cos();
    let mut out = Vec::with_capacity(DOWN.len());
    let mut surface = 0.0;
    for (k, (name, d)) in DOWN.iter().enumerate() {
        let depth = |p: [f64; 3]| p[0] * d[0] + p[1] * d[1] + p[2] * d[2];
        // The bed is at the greatest depth along d (the lowest point).
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for p in parts {
            for v in &p.vertices {
                let x = depth(v.map(f64::from));
                lo = lo.min(x);
                hi = hi.max(x);
            }
        }
        let (mut overhang, mut contact) = (0.0, 0.0);
        for p in parts {
            for t in &p.triangles {
                let [a, b, c] = t.map(|i| p.vertices[i as usize].map(f64::from));
                let (n, area) = normal_area(a, b, c);
                if k == 0 {
                    surface += area;
                }
                let facing = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
                if facing < cos {
                    continue;
                }
                let on_bed = [a, b, c].iter().all(|&v| hi - depth(v) <= BED_TOLERANCE);
                match on_bed {
                    true => contact += area,
                    false => overhang += area,
                }
            }
        }
        out.push(Overhang {
            down: name,
            overhang_mm2: overhang,
            bed_contact_mm2: contact,
            height_mm: if hi >= lo { hi - lo } else { 0.0 },
        });
    }
    (out, surface)
}

/// The least contact area that counts as resting on the bed, mm² (a square of a nozzle's width).
const MIN_CONTACT: f64 = 0.16;

/// Decides the orientation: with `auto`, the best axis direction (see the module documentation),
/// else the solid as built.
pub fn choose(parts: &[Part], auto: bool) -> Orientation {
    let (candidates, surface) = overhangs(parts);
    let rests = |o: &Overhang| o.bed_contact_mm2 >= MIN_CONTACT;
    let key = |o: &Overhang| (o.overhang_mm2, o.height_mm);
    let best = |pool: Vec<usize>| {
        pool.into_iter().min_by(|&a, &b| {
            let (x, y) = (key(&candidates[a]), key(&candidates[b]));
            x.partial_cmp(&y).unwrap_or(std::cmp::Ordering::Equal)
        })
    };
    let resting: Vec<usize> = (0..candidates.len())
        .filter(|&i| rests(&candidates[i]))
        .collect();
    let (chosen, reason) = match auto {
        false => (0, "as built (--orient keep)".to_string()),
        true => match best(resting.clone()) {
            Some(i) => (
                i,
                format!(
                    "the least overhang of the {} axis directions that rest a face on the bed",
                    resting.len()
                ),
            ),
            // Standing a shell on an edge would overhang less and topple: keep it as built.
            None => (
                0,
                "no axis direction rests a face on the bed: kept as built".to_string(),
            ),
        },
    };
    let needs_support = !rests(&candidates[chosen]);
    Orientation {
        chosen: candidates[chosen].down,
        candidates,
        surface_mm2: surface,
        reason,
        needs_support,
    }
}

/// Turns the solid so that the direction `down` (one of the six names) points to −z: a
/// permutation of the coordinates with signs (a proper rotation, so triangles keep their
/// orientation), exact in `f32`.
pub fn turn(parts: &mut [Part], down: &str) {
    let map: fn([f32; 3]) -> [f32; 3] = match down {
        "+z" => |[x, y, z]| [x, -y, -z],
        "-y" => |[x, y, z]| [x, -z, y],
        "+y" => |[x, y, z]| [x, z, -y],
        "-x" => |[x, y, z]| [-z, y, x],
        "+x" => |[x, y, z]| [z, y, -x],
        _ => |v| v,
    };
    for p in parts.iter_mut() {
        for v in &mut p.vertices {
            *v = map(*v);
        }
    }
}

impl Orientation {
    /// A few lines for the terminal.
    pub fn text(&self) -> String {
        let c = self
            .candidates
            .iter()
            .find(|o| o.down == self.chosen)
            .unwrap_or(&self.candidates[0]);
        let share = match self.surface_mm2 > 0.0 {
            true => 100.0 * c.overhang_mm2 / self.surface_mm2,
            false => 0.0,
        };
        let mut s = format!(
            "orientation: {} down ({}): overhang beyond {OVERHANG_DEGREES}° {:.1} mm² ({share:.1} % of the surface), {:.1} mm² on the bed, height {:.1} mm\n",
            self.chosen, self.reason, c.overhang_mm2, c.bed_contact_mm2, c.height_mm
        );
        let others: Vec<String> = self
            .candidates
            .iter()
            .map(|o| format!("{} {:.1}", o.down, o.overhang_mm2))
            .collect();
        s += &format!(
            "  overhang (mm²) by the direction down: {}\n",
            others.join(", ")
        );
        if self.needs_support {
            s += "warning: no face rests on the bed in this orientation: print with supports or a raft (PrusaSlicer: --support-material)\n";
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::solid::Part;

    /// A box from the origin to (a, b, c), triangles counter-clockwise from outside.
    fn cuboid(a: f32, b: f32, c: f32) -> Vec<Part> {
        let v: Vec<[f32; 3]> = (0..8)
            .map(|i| {
                [
                    if i & 1 == 1 { a } else { 0.0 },
                    if i & 2 == 2 { b } else { 0.0 },
                    if i & 4 == 4 { c } else { 0.0 },
                ]
            })
            .collect();
        let quads = [
            [0, 2, 3, 1],
            [4, 5, 7, 6],
            [0, 1, 5, 4],
            [2, 6, 7, 3],
            [0, 4, 6, 2],
            [1, 3, 7, 5],
        ];
        let triangles = quads
            .iter()
            .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
            .collect();
        vec![Part {
            vertices: v,
            triangles,
            holes: None,
        }]
    }

    #[test]
    fn a_box_rests_on_a_face_and_has_no_overhang() {
        // A 10 × 20 × 30 box as built: its bottom (200 mm²) rests on the bed, nothing overhangs;
        // the same with any axis down (each bottom face on the bed), heights 30, 30, 20, 20, 10, 10.
        let s = cuboid(10.0, 20.0, 30.0);
        let (c, surface) = overhangs(&s);
        assert!((surface - 2.0 * (200.0 + 300.0 + 600.0)).abs() < 1e-6);
        let contact: Vec<f64> = c.iter().map(|o| o.bed_contact_mm2).collect();
        for (got, want) in contact
            .iter()
            .zip([200.0, 200.0, 300.0, 300.0, 600.0, 600.0])
        {
            assert!((got - want).abs() < 1e-6, "{contact:?}");
        }
        assert!(c.iter().all(|o| o.overhang_mm2 == 0.0));
        let o = choose(&s, true);
        // Every direction rests and none overhangs: the lowest, ±x down (height 10).
        assert_eq!(o.chosen, "-x");
        assert!(!o.needs_support);
    }

    #[test]
    fn turning_moves_the_direction_down_exactly() {
        // Turning the 10×20×30 box so that +x points down gives, as built (-z), the figures +x
        // had, and keeps the orientation of the triangles.
        let mut s = cuboid(10.0, 20.0, 30.0);
        let before = overhangs(&s).0;
        turn(&mut s, "+x");
        let after = overhangs(&s).0;
        // +x down became -z down: the same figures.
        let find = |v: &[Overhang], n: &str| v.iter().find(|o| o.down == n).unwrap().clone();
        assert!((find(&after, "-z").height_mm - find(&before, "+x").height_mm).abs() < 1e-9);
        assert!(
            (find(&after, "-z").bed_contact_mm2 - find(&before, "+x").bed_contact_mm2).abs() < 1e-9
        );
        // A proper rotation: the enclosed volume keeps its sign (6000 mm³, positive).
        let p = &s[0];
        let six: f64 = p
            .triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| p.vertices[i as usize].map(f64::from));
                a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                    + a[2] * (b[0] * c[1] - b[1] * c[0])
            })
            .sum();
        assert!((six / 6.0 - 6000.0).abs() < 1e-6, "{six}");
    }

    #[test]
    fn a_wider_box_on_a_box_overhangs_unless_laid_on_its_side() {
        // Box A 10×10×10 at the origin and box B 20×10×10 on top of it, 5 mm wider on each side
        // in x. As built (-z down): B's bottom (200 mm²) faces down above the bed: overhang 200,
        // A's bottom rests (100). +z down: B's top rests (200), A's top overhangs (100). ±x down:
        // one x-face of B rests (100), A's faces down there overhang (100). ±y down: A's and B's
        // y-faces at y = 0 (or 10) all rest (300), nothing overhangs: the choice, -y first.
        let mut parts = cuboid(10.0, 10.0, 10.0);
        let mut b = cuboid(20.0, 10.0, 10.0).remove(0);
        for v in &mut b.vertices {
            v[0] -= 5.0;
            v[2] += 10.0;
        }
        parts.push(b);
        let (c, _) = overhangs(&parts);
        let got: Vec<(f64, f64)> = c
            .iter()
            .map(|o| (o.overhang_mm2, o.bed_contact_mm2))
            .collect();
        let want = [
            (200.0, 100.0),
            (100.0, 200.0),
            (0.0, 300.0),
            (0.0, 300.0),
            (100.0, 100.0),
            (100.0, 100.0),
        ];
        for (g, w) in got.iter().zip(want) {
            assert!(
                (g.0 - w.0).abs() < 1e-6 && (g.1 - w.1).abs() < 1e-6,
                "{got:?}"
            );
        }
        let o = choose(&parts, true);
        assert_eq!(o.chosen, "-y", "{}", o.text());
        assert_eq!(choose(&parts, false).chosen, "-z");
    }

    #[test]
    fn a_tilted_sheet_touching_the_bed_on_an_edge_needs_support() {
        // One triangle pair, a square sheet tilted 60° from the bed, its lower edge on the bed
        // (no area on the bed): every direction of the six sees no face resting.
        let h = 3f32.sqrt() / 2.0;
        let part = Part {
            vertices: vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 0.5, h],
                [0.0, 0.5, h],
            ],
            triangles: vec![[0, 1, 2], [0, 2, 3], [0, 2, 1], [0, 3, 2]],
            holes: None,
        };
        let o = choose(&[part], true);
        assert!(o.needs_support, "{}", o.text());
    }
}
