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
//! **The choice** (`auto`): the candidates are the six axis directions and the outward normals
//! of the largest flat faces (up to 8, triangles grouped by normal); among those with a bed
//! contact, the least overhang (ties: the lower object); when none has a contact, the solid as
//! built (the least overhang would often stand a shell on an edge), and the advice to print with
//! supports or a raft. An axis turn is a signed permutation of the coordinates, exact in `f32`.
//! Any other turn rounds the vertices: the turned mesh is read back by the independent mesh
//! checker ([`crate::meshcheck`], exact predicates on the rounded coordinates) and kept only if
//! it passes with the same parts and χ ([`turn_checked`]); otherwise the best axis direction is
//! used and the reason said.
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

/// The most face-normal directions tried besides the six axes.
const MAX_FACE_DIRECTIONS: usize = 8;

/// The overhang and bed contact with one direction down.
#[derive(Clone, Debug, Serialize)]
pub struct Overhang {
    /// The direction that points down (`-z` is the solid as built; a face normal is written
    /// `n(x, y, z)`).
    pub down: String,
    /// The unit vector that points down.
    #[serde(skip)]
    pub vector: [f64; 3],
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
    pub chosen: String,
    /// Its unit vector.
    #[serde(skip)]
    pub vector: [f64; 3],
    /// The total surface area, mm².
    pub surface_mm2: f64,
    /// Why it was chosen (or that it was kept).
    pub reason: String,
    /// Whether the object needs supports or a raft in the chosen orientation: no area rests on
    /// the bed.
    pub needs_support: bool,
    /// The largest bridge of the parts as turned ([`largest_bridge`]), mm, once they are.
    pub largest_bridge_mm: Option<f64>,
}

/// Unit normal and area of a triangle.
pub(super) fn normal_area(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> ([f64; 3], f64) {
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

/// A triangle of the parts: its corners, unit normal and area (computed once for every
/// direction tried).
type Tri = ([[f64; 3]; 3], [f64; 3], f64);

/// The outward normals of the largest flat faces of the surface that are not along an axis
/// (triangles grouped by their normal to 1e-4: the `f32` vertices of one flat face give normals
/// that differ by rounding), largest area first, ties by the normal: resting one of them on the
/// bed needs a turn by another angle than a right one.
fn face_directions(tris: &[Tri]) -> Vec<[f64; 3]> {
    let mut area: std::collections::BTreeMap<[i64; 3], (f64, [f64; 3])> = Default::default();
    for &(_, n, ar) in tris {
        let key = n.map(|x| (x * 1e4).round() as i64);
        if ar == 0.0 || key.iter().filter(|&&x| x != 0).count() < 2 {
            continue;
        }
        let e = area.entry(key).or_insert((0.0, [0.0; 3]));
        e.0 += ar;
        for (acc, x) in e.1.iter_mut().zip(n) {
            *acc += ar * x;
        }
    }
    let mut v: Vec<([i64; 3], f64, [f64; 3])> =
        area.into_iter().map(|(k, (a, n))| (k, a, n)).collect();
    v.sort_by(|x, y| {
        y.1.partial_cmp(&x.1)
            .unwrap_or(std::cmp::Ordering::Equal)
            .then(x.0.cmp(&y.0))
    });
    // Tiny triangles of one flat face (level 3, 0.1 mm sides at 100 mm) give `f32` normals that
    // differ by more than the grid above, so one face fell into several groups and was offered
    // as several directions. Groups whose mean normals lie within 10⁻³ rad of a larger group's
    // join it (the first such group in order of area).
    //
    // A level-3 mesh has tens of thousands of groups (83,590 for tetrahedron C3 A1 V1), so the
    // groups formed so far are indexed by the cell of a 10⁻³ grid that their unit mean normal
    // lies in: 1 − u·w < 5·10⁻⁷ gives |u − w| < 10⁻³, so w lies in u's cell or a neighbouring
    // one, and only those 27 cells are searched (a linear search over all groups took 12.5 s).
    let unit = |n: [f64; 3]| {
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        n.map(|x| x / len)
    };
    let cell = |u: [f64; 3]| u.map(|x| (x * 1e3).floor() as i64);
    let mut merged: Vec<([i64; 3], f64, [f64; 3])> = Vec::new();
    let mut index: std::collections::HashMap<[i64; 3], Vec<usize>> = Default::default();
    for (k, a, n) in v {
        let u = unit(n);
        let c = cell(u);
        let mut near: Option<usize> = None;
        for d in 0..27 {
            let at = [c[0] + d % 3 - 1, c[1] + d / 3 % 3 - 1, c[2] + d / 9 - 1];
            for &i in index.get(&at).into_iter().flatten() {
                let w = unit(merged[i].2);
                if u[0] * w[0] + u[1] * w[1] + u[2] * w[2] > 1.0 - 5e-7
                    && near.is_none_or(|j| i < j)
                {
                    near = Some(i);
                }
            }
        }
        match near {
            Some(i) => {
                let before = cell(unit(merged[i].2));
                let g = &mut merged[i];
                g.1 += a;
                for (acc, x) in g.2.iter_mut().zip(n) {
                    *acc += x;
                }
                let after = cell(unit(g.2));
                if after != before {
                    if let Some(list) = index.get_mut(&before) {
                        list.retain(|&j| j != i);
                    }
                    index.entry(after).or_default().push(i);
                }
            }
            None => {
                index.entry(c).or_default().push(merged.len());
                merged.push((k, a, n));
            }
        }
    }
    let mut v = merged;
    v.sort_by(|x, y| {
        y.1.partial_cmp(&x.1)
            .unwrap_or(std::cmp::Ordering::Equal)
            .then(x.0.cmp(&y.0))
    });
    v.into_iter()
        .take(MAX_FACE_DIRECTIONS)
        .filter_map(|(_, _, n)| {
            // The area-weighted mean normal of the group, made a unit vector again.
            let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            (len > 0.0).then(|| n.map(|x| x / len))
        })
        .collect()
}

/// The figures of every candidate direction down: the six axes, as built first, then the
/// outward normals of the largest faces that are not along an axis.
pub fn overhangs(parts: &[Part]) -> (Vec<Overhang>, f64) {
    let cos = OVERHANG_DEGREES.to_radians().cos();
    let tris: Vec<Tri> = parts
        .iter()
        .flat_map(|p| {
            p.triangles.iter().map(move |t| {
                let [a, b, c] = t.map(|i| p.vertices[i as usize].map(f64::from));
                let (n, area) = normal_area(a, b, c);
                ([a, b, c], n, area)
            })
        })
        .collect();
    let surface = tris.iter().map(|t| t.2).sum();
    let mut dirs: Vec<(String, [f64; 3])> = DOWN.iter().map(|(n, d)| (n.to_string(), *d)).collect();
    dirs.extend(
        face_directions(&tris)
            .into_iter()
            .map(|n| (format!("n({:.3}, {:.3}, {:.3})", n[0], n[1], n[2]), n)),
    );
    let mut out = Vec::with_capacity(dirs.len());
    for (name, d) in &dirs {
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
        for (corners, n, area) in &tris {
            let facing = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
            if facing < cos {
                continue;
            }
            match corners.iter().all(|&v| hi - depth(v) <= BED_TOLERANCE) {
                true => contact += area,
                false => overhang += area,
            }
        }
        out.push(Overhang {
            down: name.clone(),
            vector: *d,
            overhang_mm2: overhang,
            bed_contact_mm2: contact,
            height_mm: if hi >= lo { hi - lo } else { 0.0 },
        });
    }
    (out, surface)
}

/// The least contact area that counts as resting on the bed, mm² (a square of a nozzle's width).
const MIN_CONTACT: f64 = 0.16;

/// Decides the orientation: with `auto`, the best direction (see the module documentation),
/// else the solid as built.
pub fn choose(parts: &[Part], auto: bool) -> Orientation {
    let (candidates, surface) = overhangs(parts);
    choose_among(candidates, surface, auto)
}

/// [`choose`] among the six axis directions only (exact turns).
pub fn choose_axis(parts: &[Part]) -> Orientation {
    let (mut candidates, surface) = overhangs(parts);
    candidates.truncate(DOWN.len());
    choose_among(candidates, surface, true)
}

fn choose_among(candidates: Vec<Overhang>, surface: f64, auto: bool) -> Orientation {
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
                    "the least overhang of the {} directions (of {}: the axes and the largest faces) that rest a face on the bed",
                    resting.len(),
                    candidates.len()
                ),
            ),
            // Standing a shell on an edge would overhang less and topple: keep it as built.
            None => (
                0,
                "no direction tried rests a face on the bed: kept as built".to_string(),
            ),
        },
    };
    let needs_support = !rests(&candidates[chosen]);
    Orientation {
        chosen: candidates[chosen].down.clone(),
        vector: candidates[chosen].vector,
        candidates,
        surface_mm2: surface,
        reason,
        needs_support,
        largest_bridge_mm: None,
    }
}

/// The width of the widest overhang with −z down, mm: the span a bridge (or a support) must
/// cross. The overhang triangles (facing down beyond [`OVERHANG_DEGREES`], not on the bed) are
/// grouped into regions by the edges they share; each region is seen from below (its triangles
/// projected on the bed and united by `i_overlay`), and its width is twice the radius of the
/// largest disc inside it ([`super::feature::largest_disc`], within 10⁻³ mm): a strip of width `w`
/// and any length needs a bridge of span `w`, whichever way the slicer lays it. None when nothing
/// overhangs. An estimate on the `f32` coordinates, for advice.
pub fn largest_bridge(parts: &[Part]) -> Option<f64> {
    use i_overlay::core::fill_rule::FillRule;
    use i_overlay::float::simplify::SimplifyShape;
    let cos = OVERHANG_DEGREES.to_radians().cos();
    let bottom = parts
        .iter()
        .flat_map(|p| p.vertices.iter().map(|v| f64::from(v[2])))
        .fold(f64::INFINITY, f64::min);
    let mut widest: Option<f64> = None;
    for p in parts {
        let corners = |t: &[u32; 3]| t.map(|i| p.vertices[i as usize].map(f64::from));
        let over: Vec<usize> = (0..p.triangles.len())
            .filter(|&k| {
                let [a, b, c] = corners(&p.triangles[k]);
                let (n, area) = normal_area(a, b, c);
                area > 0.0
                    && -n[2] >= cos
                    && !(a[2] - bottom <= BED_TOLERANCE
                        && b[2] - bottom <= BED_TOLERANCE
                        && c[2] - bottom <= BED_TOLERANCE)
            })
            .collect();
        let mut dsu = super::below::Dsu::new(over.len());
        let mut by_edge: std::collections::HashMap<(u32, u32), usize> = Default::default();
        for (k, &t) in over.iter().enumerate() {
            let v = p.triangles[t];
            for e in 0..3 {
                let (a, b) = (v[e], v[(e + 1) % 3]);
                match by_edge.entry((a.min(b), a.max(b))) {
                    std::collections::hash_map::Entry::Occupied(o) => dsu.union(k, *o.get()),
                    std::collections::hash_map::Entry::Vacant(slot) => {
                        slot.insert(k);
                    }
                }
            }
        }
        let mut regions: std::collections::BTreeMap<usize, Vec<Vec<[f64; 2]>>> = Default::default();
        for (k, &t) in over.iter().enumerate() {
            // Facing down, the triangle turns clockwise seen from above: reversed, it is
            // counter-clockwise as `i_overlay`'s non-zero rule wants.
            let [a, b, c] = corners(&p.triangles[t]);
            regions.entry(dsu.find(k)).or_default().push(vec![
                [a[0], a[1]],
                [c[0], c[1]],
                [b[0], b[1]],
            ]);
        }
        for tris in regions.into_values() {
            for shape in tris.simplify_shape(FillRule::NonZero) {
                let Some((outer, holes)) = shape.split_first() else {
                    continue;
                };
                let islands: Vec<&[[f64; 2]]> = holes.iter().map(Vec::as_slice).collect();
                let (lo, _) = super::feature::largest_disc(outer, &islands, 1e-3);
                widest = Some(widest.map_or(2.0 * lo, |w| w.max(2.0 * lo)));
            }
        }
    }
    widest
}

/// Turns the parts so that the chosen direction points to −z. An axis direction is a signed
/// permutation of the coordinates, exact in `f32`. Another direction is a rotation rounded to
/// `f32`: the turned mesh is then written as STL and read back by the independent mesh checker
/// ([`crate::meshcheck`], exact predicates on the rounded coordinates), and kept only when it is
/// still a closed oriented manifold without crossing or degenerate triangles, with the same
/// parts and χ; otherwise the parts are left as they were and the reason is returned.
pub fn turn_checked(parts: &mut [Part], o: &Orientation) -> Result<(), String> {
    if DOWN.iter().any(|(n, _)| *n == o.chosen) {
        turn(parts, &o.chosen);
        return Ok(());
    }
    let before = check_parts(parts)?;
    let kept: Vec<Part> = parts.to_vec();
    rotate(parts, o.vector);
    match check_parts(parts) {
        Ok(after) if after == before => Ok(()),
        Ok(_) | Err(_) => {
            parts.clone_from_slice(&kept);
            Err(format!(
                "turned to {} down, the rounded mesh did not pass the independent mesh check",
                o.chosen
            ))
        }
    }
}

/// The parts as a binary STL read by the independent checker: (parts, χ) when every check
/// passes.
fn check_parts(parts: &[Part]) -> Result<(usize, i64), String> {
    let n: usize = parts.iter().map(|p| p.triangles.len()).sum();
    let mut bytes = vec![b' '; 80];
    bytes.extend_from_slice(&(n as u32).to_le_bytes());
    for p in parts {
        for t in &p.triangles {
            bytes.extend_from_slice(&[0u8; 12]);
            for &i in t {
                for x in p.vertices[i as usize] {
                    bytes.extend_from_slice(&x.to_le_bytes());
                }
            }
            bytes.extend_from_slice(&[0u8; 2]);
        }
    }
    let r = crate::meshcheck::check(&bytes, "turned mesh", &Default::default())
        .map_err(|e| e.to_string())?;
    match r.checks_pass() {
        true => Ok((r.parts.len(), r.euler())),
        false => Err("the turned mesh fails the mesh check".into()),
    }
}

/// Turns more parts as `o` turned the solid ([`turn_checked`] kept it): an axis direction as a
/// permutation ([`turn`]), another as the same rounded rotation.
pub fn apply(parts: &mut [Part], o: &Orientation) {
    match DOWN.iter().any(|(n, _)| *n == o.chosen) {
        true => turn(parts, &o.chosen),
        false => rotate(parts, o.vector),
    }
}

/// Rotates the parts so that the unit vector `d` points to −z (Rodrigues), rounded to `f32`.
fn rotate(parts: &mut [Part], d: [f64; 3]) {
    let t = [0.0, 0.0, -1.0];
    let v = [
        d[1] * t[2] - d[2] * t[1],
        d[2] * t[0] - d[0] * t[2],
        d[0] * t[1] - d[1] * t[0],
    ];
    let c = d[0] * t[0] + d[1] * t[1] + d[2] * t[2];
    // R = I + [v]× + [v]×² / (1 + c); d is no axis here, so c > −1.
    let k = [[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]];
    let mut r = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            let k2: f64 = (0..3).map(|m| k[i][m] * k[m][j]).sum();
            r[i][j] = f64::from(u8::from(i == j)) + k[i][j] + k2 / (1.0 + c);
        }
    }
    for p in parts.iter_mut() {
        for x in &mut p.vertices {
            let y = x.map(f64::from);
            *x = [0, 1, 2].map(|i| (r[i][0] * y[0] + r[i][1] * y[1] + r[i][2] * y[2]) as f32);
        }
    }
}

/// Turns the solid so that the direction `down` (one of the six axis names) points to −z: a
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
        if let Some(b) = self.largest_bridge_mm {
            s += &format!(
                "  largest bridge {b:.2} mm (the widest overhang region seen from below, an estimate)\n"
            );
        }
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

    /// A regular tetrahedron of edge `a` with corners (1,1,1), (1,−1,−1), (−1,1,−1), (−1,−1,1)
    /// scaled, triangles counter-clockwise from outside.
    fn tetrahedron(a: f32) -> Vec<Part> {
        let s = a / (2.0 * 2f32.sqrt());
        let v = vec![[s, s, s], [s, -s, -s], [-s, s, -s], [-s, -s, s]];
        vec![Part {
            vertices: v,
            triangles: vec![[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]],
            holes: None,
        }]
    }

    #[test]
    fn a_tetrahedron_is_turned_onto_a_face_and_checked() {
        // No axis direction rests a face of the tetrahedron (every face normal has three
        // non-zero coordinates ±1/√3); its faces' normals do. Edge 10 mm: a face has area
        // (√3/4)·100 = 43.30 mm², and after the turn (checked by the independent mesh checker) it
        // lies on the bed, nothing overhanging (the other faces lean outwards at 19.5° from
        // vertical).
        let mut parts = tetrahedron(10.0);
        let o = choose(&parts, true);
        assert!(o.chosen.starts_with("n("), "{}", o.text());
        assert!(!o.needs_support);
        turn_checked(&mut parts, &o).unwrap();
        let (after, _) = overhangs(&parts);
        let face = 3f64.sqrt() / 4.0 * 100.0;
        assert!(
            (after[0].bed_contact_mm2 - face).abs() < 1e-3,
            "{}",
            after[0].bed_contact_mm2
        );
        assert!(after[0].overhang_mm2 < 1e-9);
        // A tetrahedron of edge 0.3 mm: every face (0.039 mm²) is below the contact that
        // counts (0.16 mm²): kept as built, supports advised.
        let tiny = tetrahedron(0.3);
        let o = choose(&tiny, true);
        assert_eq!(o.chosen, "-z");
        assert!(o.needs_support, "{}", o.text());
    }

    /// By hand, two boxes: a 10 × 4 × 1 bar at height 5 over nothing, and a 1 × 1 × 1 cube on
    /// the bed. The bar's underside is an overhang of 10 × 4: a bridge of
    /// span 4 (the largest disc of a 10 × 4 rectangle has diameter 4); the cube's underside is
    /// on the bed and its top faces up: no overhang.
    #[test]
    fn one_flat_face_of_tiny_triangles_is_one_direction() {
        // Two triangles of the plane x + y + z = 0 whose normals, as `f32` rounding of tiny
        // triangles makes them, differ by 3·10⁻⁴ in one coordinate (more than the 10⁻⁴ grid, so
        // they were two groups) but by far less than 10⁻³ rad: one direction, not two. A third
        // triangle of another plane stays apart.
        let s = 1.0 / 3f64.sqrt();
        let tri = |n: [f64; 3], a: f64| -> Tri { ([[0.0; 3]; 3], n, a) };
        let tilt = {
            let m = [s + 3e-4, s, s];
            let l = (m[0] * m[0] + m[1] * m[1] + m[2] * m[2]).sqrt();
            m.map(|x| x / l)
        };
        let d = face_directions(&[tri([s, s, s], 2.0), tri(tilt, 1.0), tri([s, -s, s], 0.5)]);
        assert_eq!(d.len(), 2, "{d:?}");
        assert!(
            (d[0][0] - s).abs() < 2e-4 && (d[0][1] - s).abs() < 2e-4,
            "{d:?}"
        );
        assert!(d[1][1] < 0.0, "{d:?}");
    }

    #[test]
    fn the_largest_bridge_is_the_widest_overhang_seen_from_below() {
        let mut bar = cuboid(10.0, 4.0, 1.0);
        for v in &mut bar[0].vertices {
            v[2] += 5.0;
        }
        let parts = [bar[0].clone(), cuboid(1.0, 1.0, 1.0)[0].clone()];
        let b = largest_bridge(&parts).expect("the bar overhangs");
        assert!((b - 4.0).abs() < 2e-3, "{b}");
        // On the bed alone, nothing overhangs.
        assert_eq!(largest_bridge(&cuboid(10.0, 4.0, 1.0)), None);
    }
}
