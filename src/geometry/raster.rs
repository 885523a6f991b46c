//! The raster of an instance: its level-0 bounding box, the cells of one level filled on a
//! raster fitted to it, and the exact number of cells (for progress bars). Shared by the measures
//! and the exports.

use crate::geometry::instantiate::Instance;
use crate::geometry::point::{BBox, Raster};
use crate::progress::Progress;
use crate::topology::counts;
use num_traits::ToPrimitive;

/// The exact number of cells N^C at `level` (saturating at `u64::MAX`), for progress bars.
pub fn cell_count(inst: &Instance, level: u32) -> u64 {
    counts(&inst.types, u64::from(level))[level as usize]
        .faces
        .to_u64()
        .unwrap_or(u64::MAX)
}

/// The bounding box of the level-0 faces (every cell lies inside them).
pub fn bounds(inst: &Instance, segments: usize) -> BBox {
    let mut bb = BBox::empty();
    inst.walk(0, false, |c| {
        for p in inst.cell_polygon(c.ty, c.points, segments) {
            bb.add(p);
        }
    });
    bb
}

/// Rasterises the cells of one level (with a progress bar when they are on).
pub fn rasterize(inst: &Instance, level: u32, size: usize, segments: usize) -> Raster {
    let mut r = Raster::fitting(bounds(inst, segments), size, (size / 64).max(2));
    let mut bar = Progress::new("raster", cell_count(inst, level));
    inst.walk(level, false, |c| {
        r.fill_polygon(&inst.cell_polygon(c.ty, c.points, segments));
        bar.tick();
    });
    r
}
