//! Feature sizes of a planar structure as a printer sees them (GEOMETRY §5, "Printability"):
//! the material is the union of the level-n cells (its [`Outline`], in millimetres), its holes the
//! bounded components of the complement.
//!
//! **Smallest hole.** The least `2r` such that dilating the material by `r` closes a hole: twice
//! the least, over the holes, of the radius of the largest disc inside the hole (its pole of
//! inaccessibility). [`largest_disc`] finds it by subdividing square cells (as `polylabel` does):
//! the signed distance `s` to the hole's boundary is 1-Lipschitz, so no point of a cell of
//! half-side `h` and centre `c` has `s` above `s(c) + h√2`; cells that cannot beat the best centre
//! found by more than the tolerance are dropped. The result is a bracket `[lo, lo + tol]` that
//! contains the radius, on the polygons (Bézier edges flattened to `--segments` pieces, corners
//! rounded to `f32` millimetres), with `tol` = [`HOLE_TOLERANCE`].
//!
//! **Thinnest ligament.** The least `2r` such that eroding the material by `r` changes its
//! topology: a component splits or vanishes, a hole opens, or two holes (or a hole and the
//! outside) merge because the wall between them is cut. The erosion is `i_overlay`'s polygon
//! offset by `−r` with round joins (arcs cut in chords of at most 0.01π rad: the eroded outline
//! is within `1.3e-4·r` of the true one, and `i_overlay` snaps to an integer grid of about
//! `extent / 2³⁰`); `r` doubles from [`LIGAMENT_TOLERANCE`] until the numbers
//! of components or holes differ from the material's, then is bisected to
//! [`LIGAMENT_TOLERANCE`]. An estimate, not a bound: a change that reverses within one step of
//! the scan is not seen, and the offset is approximate.
//!
//! Both are floating point and decide a warning, or with `--strict` a failure (E1042), never a
//! topological verdict.

use super::outline::Outline;
use i_overlay::core::fill_rule::FillRule;
use i_overlay::float::simplify::SimplifyShape;
use i_overlay::mesh::outline::offset::OutlineOffset;
use i_overlay::mesh::style::{LineJoin, OutlineStyle};
use std::cmp::Ordering;
use std::collections::{BinaryHeap, HashMap};

/// Width of the bracket of a hole's inscribed radius, mm.
pub const HOLE_TOLERANCE: f64 = 1e-4;

/// Bisection tolerance of the erosion radius, mm (the ligament, `2r`, is within twice this).
pub const LIGAMENT_TOLERANCE: f64 = 5e-4;

/// A point of the plane, mm.
pub type P2 = [f64; 2];

/// Shapes as `i_overlay` gives them: each an outer contour (counter-clockwise) and its holes
/// (clockwise).
pub type Shapes = Vec<Vec<Vec<P2>>>;

/// The union of the cells: the outline's directed segments chained into closed loops (every
/// point has as many segments in as out) and normalised by `i_overlay` (non-zero winding: the
/// material is on the left of every segment, winding 1 inside).
pub fn material(o: &Outline) -> Shapes {
    let mut out_of: HashMap<u32, Vec<u32>> = HashMap::new();
    for (k, s) in o.segments.iter().enumerate() {
        out_of.entry(s[0]).or_default().push(k as u32);
    }
    let mut used = vec![false; o.segments.len()];
    let mut loops: Vec<Vec<P2>> = Vec::new();
    for start in 0..o.segments.len() {
        if used[start] {
            continue;
        }
        let mut ring = Vec::new();
        let mut k = start;
        loop {
            used[k] = true;
            let s = o.segments[k];
            ring.push(o.points[s[0] as usize]);
            let next = out_of
                .get(&s[1])
                .and_then(|v| v.iter().copied().find(|&n| !used[n as usize]));
            match next {
                Some(n) => k = n as usize,
                None => break,
            }
        }
        if ring.len() >= 3 {
            loops.push(ring);
        }
    }
    loops.simplify_shape(FillRule::NonZero)
}

/// Components and holes of shapes.
pub fn betti(shapes: &Shapes) -> (usize, usize) {
    (
        shapes.len(),
        shapes.iter().map(|s| s.len().saturating_sub(1)).sum(),
    )
}

fn segment_distance(p: P2, a: P2, b: P2) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let l = dx * dx + dy * dy;
    let t = if l > 0.0 {
        (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / l).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let (x, y) = (a[0] + t * dx - p[0], a[1] + t * dy - p[1]);
    (x * x + y * y).sqrt()
}

/// Whether `p` is inside the closed polygon `ring` (even–odd crossing count).
fn inside(p: P2, ring: &[P2]) -> bool {
    let mut c = false;
    let n = ring.len();
    for i in 0..n {
        let (a, b) = (ring[i], ring[(i + n - 1) % n]);
        if (a[1] > p[1]) != (b[1] > p[1])
            && p[0] < (b[0] - a[0]) * (p[1] - a[1]) / (b[1] - a[1]) + a[0]
        {
            c = !c;
        }
    }
    c
}

struct Cell {
    c: P2,
    h: f64,
    d: f64,
    max: f64,
}

impl PartialEq for Cell {
    fn eq(&self, o: &Self) -> bool {
        self.max.total_cmp(&o.max) == Ordering::Equal
    }
}
impl Eq for Cell {}
impl PartialOrd for Cell {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Cell {
    fn cmp(&self, o: &Self) -> Ordering {
        self.max.total_cmp(&o.max)
    }
}

/// The radius of the largest disc inside the region bounded by `ring` and outside every polygon
/// of `islands`, as a bracket `(lo, hi)` with `hi − lo ≤ tol` (or the bracket reached after
/// 10⁶ cells, never narrower than the truth allows). See the module doc.
pub fn largest_disc(ring: &[P2], islands: &[&[P2]], tol: f64) -> (f64, f64) {
    let mut lo_c = [f64::INFINITY; 2];
    let mut hi_c = [f64::NEG_INFINITY; 2];
    for p in ring {
        for k in 0..2 {
            lo_c[k] = lo_c[k].min(p[k]);
            hi_c[k] = hi_c[k].max(p[k]);
        }
    }
    let size = (hi_c[0] - lo_c[0]).min(hi_c[1] - lo_c[1]);
    if ring.len() < 3 || size.partial_cmp(&0.0) != Some(Ordering::Greater) {
        return (0.0, 0.0);
    }
    let edges = |poly: &[P2], p: P2, best: &mut f64| {
        for i in 0..poly.len() {
            *best = best.min(segment_distance(p, poly[i], poly[(i + 1) % poly.len()]));
        }
    };
    let signed = |p: P2| {
        let mut d = f64::INFINITY;
        edges(ring, p, &mut d);
        for isl in islands {
            edges(isl, p, &mut d);
        }
        let within = inside(p, ring) && !islands.iter().any(|isl| inside(p, isl));
        if within {
            d
        } else {
            -d
        }
    };
    let cell = |c: P2, h: f64| {
        let d = signed(c);
        Cell {
            c,
            h,
            d,
            max: d + h * std::f64::consts::SQRT_2,
        }
    };
    // Cells of the thinner side's size, but at most 1024 along the longer side: a long thin
    // hole must not seed billions of cells (any size is sound: a cell's bound holds for every
    // point in it).
    let longest = (hi_c[0] - lo_c[0]).max(hi_c[1] - lo_c[1]);
    let size = size.max(longest / 1024.0);
    let mut heap = BinaryHeap::new();
    let h = size / 2.0;
    let mut x = lo_c[0];
    while x < hi_c[0] {
        let mut y = lo_c[1];
        while y < hi_c[1] {
            heap.push(cell([x + h, y + h], h));
            y += size;
        }
        x += size;
    }
    let mut best = f64::NEG_INFINITY;
    let mut visited = 0usize;
    while let Some(c) = heap.pop() {
        best = best.max(c.d);
        if c.max - best <= tol {
            return (best.max(0.0), c.max.max(best).max(0.0));
        }
        visited += 1;
        if visited > 1_000_000 {
            return (best.max(0.0), c.max.max(0.0));
        }
        let h = c.h / 2.0;
        for (dx, dy) in [(-h, -h), (h, -h), (-h, h), (h, h)] {
            let n = cell([c.c[0] + dx, c.c[1] + dy], h);
            best = best.max(n.d);
            if n.max > best + tol {
                heap.push(n);
            }
        }
    }
    (best.max(0.0), (best + tol).max(0.0))
}

fn bbox(ring: &[P2]) -> [f64; 4] {
    let mut b = [
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    ];
    for p in ring {
        b[0] = b[0].min(p[0]);
        b[1] = b[1].min(p[1]);
        b[2] = b[2].max(p[0]);
        b[3] = b[3].max(p[1]);
    }
    b
}

/// The smallest hole's width (twice its largest inscribed radius) as a bracket `(lo, hi)`, mm;
/// none when the material has no hole.
pub fn smallest_hole(shapes: &Shapes) -> Option<(f64, f64)> {
    let outers: Vec<(&[P2], [f64; 4])> = shapes
        .iter()
        .filter_map(|s| s.first())
        .map(|r| (r.as_slice(), bbox(r)))
        .collect();
    let mut least: Option<(f64, f64)> = None;
    for s in shapes {
        for hole in s.iter().skip(1) {
            let b = bbox(hole);
            // Other components lying in this hole bound it too (their own holes are other holes).
            let islands: Vec<&[P2]> = outers
                .iter()
                .filter(|(r, ob)| {
                    ob[0] >= b[0]
                        && ob[1] >= b[1]
                        && ob[2] <= b[2]
                        && ob[3] <= b[3]
                        && !std::ptr::eq(*r, hole.as_slice())
                        && r.first().is_some_and(|&p| inside(p, hole))
                })
                .map(|(r, _)| *r)
                .collect();
            let (lo, hi) = largest_disc(hole, &islands, HOLE_TOLERANCE);
            least = Some(match least {
                None => (2.0 * lo, 2.0 * hi),
                Some((a, b)) => (a.min(2.0 * lo), b.min(2.0 * hi)),
            });
        }
    }
    least
}

/// The material eroded by `r`, mm.
pub fn erode(shapes: &Shapes, r: f64) -> Shapes {
    let style = OutlineStyle::new(-r).line_join(LineJoin::Round(0.01 * std::f64::consts::PI));
    shapes.outline(&style)
}

/// The thinnest ligament (the least `2r` at which erosion by `r` changes the material's numbers
/// of components or holes) as a bracket `(lo, hi)` of the scan and bisection, mm; none for no
/// material. An estimate (see the module doc).
pub fn thinnest_ligament(shapes: &Shapes) -> Option<(f64, f64)> {
    thinnest_ligament_below(shapes, f64::INFINITY)
}

/// [`thinnest_ligament`] when it is below `cap` (mm): none when eroding by `cap / 2` leaves the
/// numbers of components and holes as they are. One erosion decides a material whose ligaments
/// are all wider, so the least over many layers ([`super::slice`]) bisects only the layers that
/// beat the least so far.
pub fn thinnest_ligament_below(shapes: &Shapes, cap: f64) -> Option<(f64, f64)> {
    let base = betti(shapes);
    if base.0 == 0 {
        return None;
    }
    let b = shapes
        .iter()
        .filter_map(|s| s.first())
        .map(|r| bbox(r))
        .fold(
            [
                f64::INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::NEG_INFINITY,
            ],
            |a, b| {
                [
                    a[0].min(b[0]),
                    a[1].min(b[1]),
                    a[2].max(b[2]),
                    a[3].max(b[3]),
                ]
            },
        );
    let reach = (b[2] - b[0]).max(b[3] - b[1]);
    let changed = |r: f64| betti(&erode(shapes, r)) != base;
    if cap.is_finite() && !changed(cap / 2.0) {
        return None;
    }
    // Doubling, then bisection: each erosion of a large level costs a polygon offset of the
    // whole union, and doubling takes about half the erosions a finer growth would (measured:
    // F0 level 5, 7 776 cells, 23 erosions with steps of ×1.25 against 13).
    let (mut lo, mut hi) = (0.0, LIGAMENT_TOLERANCE);
    while !changed(hi) {
        if hi >= cap / 2.0 {
            // Changed at cap / 2 (checked above), not at hi: the change is in (lo, cap / 2].
            hi = cap / 2.0;
            break;
        }
        if hi > reach {
            // Nothing is left of any material eroded past its extent: not reached for real
            // shapes; say "at least".
            return Some((2.0 * hi, f64::INFINITY));
        }
        lo = hi;
        hi *= 2.0;
    }
    while hi - lo > LIGAMENT_TOLERANCE {
        let mid = 0.5 * (lo + hi);
        if changed(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    Some((2.0 * lo, 2.0 * hi))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Vec<P2> {
        vec![[x0, y0], [x1, y0], [x1, y1], [x0, y1]]
    }

    #[test]
    fn a_square_with_a_centred_square_hole() {
        // The unit square (scaled to 10 mm) with a centred square hole of side a.
        //
        // Hole: the largest disc in a square of side a has radius a/2, so the smallest hole is a.
        //
        // Ligament: the ring between the two squares has width w = (10 − a)/2. Eroded by r it is
        // the points at distance ≥ r from both the outside and the hole. While 2r < w it is still
        // a ring (one component, one hole). Past 2r = w the four sides are gone (their width is
        // w − 2r) but the corners are not: at (t, t) from an outer corner the distance to the
        // outside is t and to the hole's corner √2(w − t), both ≥ r for t in [r, w − r/√2],
        // which is not empty while r ≤ w/(1 + 1/√2) ≈ 0.59w. So at 2r = w one ring becomes four
        // pieces and the hole opens to the outside: (1, 1) → (4, 0). The ligament is w.
        for a in [5.0, 8.0] {
            let outer = rect(0.0, 0.0, 10.0, 10.0);
            let mut hole = rect(5.0 - a / 2.0, 5.0 - a / 2.0, 5.0 + a / 2.0, 5.0 + a / 2.0);
            hole.reverse();
            let shapes = vec![vec![outer, hole]];
            assert_eq!(betti(&shapes), (1, 1));
            let (lo, hi) = smallest_hole(&shapes).unwrap();
            assert!(
                lo <= a && a <= hi && hi - lo <= 2.0 * HOLE_TOLERANCE + 1e-12,
                "a = {a}: hole in [{lo}, {hi}]"
            );
            let w = (10.0 - a) / 2.0;
            let (lo, hi) = thinnest_ligament(&shapes).unwrap();
            // Bracket of the bisection, widened by the offset's error (chords of round joins,
            // integer snapping): 1e-3 mm.
            assert!(
                lo - 1e-3 <= w && w <= hi + 1e-3 && hi - lo <= 2.0 * LIGAMENT_TOLERANCE,
                "a = {a}: ligament in [{lo}, {hi}], w = {w}"
            );
        }
    }

    #[test]
    fn two_squares_joined_by_a_bar_split_at_the_bar_width() {
        // Squares [0,10]² and [20,30]×[0,10] joined by a bar 1 mm wide: erosion splits the bar
        // at 2r = 1 (the squares would vanish at 2r = 10). No hole.
        let shapes = vec![
            rect(0.0, 0.0, 10.0, 10.0),
            rect(10.0, 4.5, 20.0, 5.5),
            rect(20.0, 0.0, 30.0, 10.0),
        ]
        .simplify_shape(FillRule::NonZero);
        assert_eq!(betti(&shapes), (1, 0));
        assert_eq!(smallest_hole(&shapes), None);
        let (lo, hi) = thinnest_ligament(&shapes).unwrap();
        assert!(lo - 1e-3 <= 1.0 && 1.0 <= hi + 1e-3, "[{lo}, {hi}]");
    }

    #[test]
    fn an_island_in_a_hole_bounds_the_disc() {
        // A 10 mm square hole with a 2 mm square island at its centre: the largest disc sits in
        // a corner between the island and the hole's sides. On the diagonal, a disc centred at
        // (t, t) from the hole's corner touches the sides at radius t and the island's corner
        // (at 4 from the hole's corner along both axes) at √2(4 − t); equal when
        // t = 4√2/(1 + √2) ≈ 2.343. Off the diagonal it only gets closer to one side.
        let ring = rect(0.0, 0.0, 10.0, 10.0);
        let island = rect(4.0, 4.0, 6.0, 6.0);
        let (lo, hi) = largest_disc(&ring, &[&island], 1e-6);
        let t = 4.0 * 2f64.sqrt() / (1.0 + 2f64.sqrt());
        assert!(lo <= t + 1e-12 && t <= hi + 1e-12, "[{lo}, {hi}] vs {t}");
    }
}
