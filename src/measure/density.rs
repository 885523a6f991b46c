//! Relative-density maps (THEORY §7): the fraction of each block of a `grid × grid` partition of the
//! window that the level-n cells cover.
//!
//! The window is the square of side `s` = the larger side of the level-0 bounding box, centred on
//! it (the same window as the pictures, without their margin). Coverage is measured on a
//! **supersampled raster**: the window is rasterised at `grid · samples` pixels per side (pixel
//! centres, as in [`crate::geometry::point::Raster::fill_polygon`]) and a block's density is the fraction
//! of its `samples²` pixel centres that lie in a cell. The error of a block is at most its boundary
//! pixels' share, about `4 / samples` for a block crossed by the boundary of the structure, and the
//! mean density equals the covered area divided by `s²` up to the same raster error.

use crate::geometry::instantiate::Instance;
use crate::geometry::point::Raster;
use crate::geometry::raster::{bounds, cell_count};
use crate::progress::Progress;
use serde::Serialize;

/// Default blocks per side.
pub const DEFAULT_GRID: usize = 64;

/// Raster pixels per block side.
pub const SAMPLES: usize = 16;

/// A relative-density map.
#[derive(Clone, Debug, PartialEq)]
pub struct DensityMap {
    /// Blocks per side.
    pub grid: usize,
    /// Raster pixels per block side.
    pub samples: usize,
    /// Densities in [0, 1], row-major, row 0 at the top.
    pub values: Vec<f64>,
}

/// The summary reported by `lacuna measure --json` as `"density"`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DensitySummary {
    /// Blocks per side.
    pub grid: usize,
    /// Raster pixels per block side (supersampling).
    pub samples: usize,
    /// Smallest block density.
    pub min: f64,
    /// Largest block density.
    pub max: f64,
    /// Mean block density (= covered fraction of the window).
    pub mean: f64,
    /// The area of the cells divided by the window's area (shoelace sums, no raster): the mean
    /// density should agree with it up to the raster error.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub area_fraction: Option<f64>,
}

impl DensityMap {
    /// The block densities of a raster whose size is a multiple of `grid`.
    pub fn of_raster(r: &Raster, grid: usize) -> DensityMap {
        let samples = r.size / grid.max(1);
        let mut values = vec![0.0; grid * grid];
        let per = (samples * samples) as f64;
        for row in 0..grid * samples {
            for col in 0..grid * samples {
                if r.covered(col, row) {
                    values[(row / samples) * grid + col / samples] += 1.0;
                }
            }
        }
        values.iter_mut().for_each(|v| *v /= per);
        DensityMap {
            grid,
            samples,
            values,
        }
    }

    /// Min, max and mean.
    pub fn summary(&self) -> DensitySummary {
        let (mut min, mut max, mut sum) = (f64::INFINITY, f64::NEG_INFINITY, 0.0);
        for &v in &self.values {
            min = min.min(v);
            max = max.max(v);
            sum += v;
        }
        DensitySummary {
            grid: self.grid,
            samples: self.samples,
            min,
            max,
            mean: sum / self.values.len().max(1) as f64,
            area_fraction: None,
        }
    }
}

/// The window of the density map: the level-0 bounding box's square, no margin.
pub fn density_raster(inst: &Instance, level: u32, grid: usize, segments: usize) -> Raster {
    let size = grid * SAMPLES;
    let mut r = Raster::fitting(bounds(inst, segments), size, 0);
    let mut bar = Progress::new("density", cell_count(inst, level));
    inst.walk(level, false, |c| {
        r.fill_polygon(&inst.cell_polygon(c.ty, c.points, segments));
        bar.tick();
    });
    r
}

/// The relative-density map of level `level` on a `grid × grid` partition of the window.
pub fn density_map(inst: &Instance, level: u32, grid: usize, segments: usize) -> DensityMap {
    DensityMap::of_raster(&density_raster(inst, level, grid, segments), grid)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::point::BBox;

    #[test]
    fn a_filled_window_is_uniformly_one_and_half_a_window_averages_one_half() {
        let bb = BBox {
            min: [0.0, 0.0],
            max: [2.0, 2.0],
        };
        let mut r = Raster::fitting(bb, 4 * SAMPLES, 0);
        r.fill_polygon(&[[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]]);
        let m = DensityMap::of_raster(&r, 4);
        assert!(m.values.iter().all(|&v| v == 1.0), "{:?}", m.values);
        let mut half = Raster::fitting(bb, 4 * SAMPLES, 0);
        half.fill_polygon(&[[0.0, 0.0], [1.0, 0.0], [1.0, 2.0], [0.0, 2.0]]);
        let s = DensityMap::of_raster(&half, 4).summary();
        // The left two columns of blocks are full, the right two empty.
        assert_eq!((s.min, s.max), (0.0, 1.0));
        assert!((s.mean - 0.5).abs() < 1.0 / 64.0, "{}", s.mean);
    }
}
