//! The paper's point-rendering idea on the CPU: instead of gathering the
//! 2^D·n impulses around every pixel, visit each impulse once and add
//! `v·w(d)` into the pixels inside its kernel, row span by row span.
//!
//! Every pixel receives exactly the impulses point evaluation would sum (the
//! same distance test decides), in a different order, so the two agree to
//! rounding (tested: 1e-5). Rows are processed in fixed bands, so the result
//! does not depend on the number of threads.

use alloc::vec::Vec;
use core::fmt;

use super::Sparse;
use crate::grid::{Grid, GridError};
use crate::noise::Noise;

/// Rows per band: the unit of work (and of parallelism).
const BAND: usize = 32;

/// Coordinates beyond this (in cells) lose pixel resolution in `f32`;
/// such windows are evaluated point by point instead.
const SPLAT_LIMIT: f64 = (1u32 << 22) as f64;

/// Why a window cannot be splatted.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum SplatError {
    /// The grid is not a 2D window: it has more than one point on an axis
    /// beyond x and y (splatting renders planes; use `fill_grid` for volumes).
    NotAWindow,
    /// The output buffer does not match the grid.
    Grid(GridError),
    /// One position per output pixel is needed.
    PositionsMismatch {
        /// Positions given.
        positions: usize,
        /// Output length.
        out: usize,
    },
}

impl fmt::Display for SplatError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SplatError::NotAWindow => write!(f, "splatting renders 2D windows: axes beyond x and y must have size 1"),
            SplatError::Grid(e) => e.fmt(f),
            SplatError::PositionsMismatch { positions, out } => {
                write!(f, "{positions} positions for {out} output values")
            }
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for SplatError {}

/// `floor(x)` as a cell index (callers keep |x| below [`SPLAT_LIMIT`]).
fn cell_of(x: f64) -> i64 {
    libm::floor(x) as i64
}

impl Sparse {
    /// Renders a 2D window — a `D`-dimensional grid whose axes beyond x
    /// and y have size 1, i.e. a plane of 2D noise or an axis-aligned slice
    /// of 3D/4D noise — by splatting each impulse into the pixels it
    /// reaches. Same points as [`Noise::fill_grid`] (pixel `(i, j)` at
    /// `grid.point`), equal to it within 1e-5.
    ///
    /// Windows whose coordinates exceed ±2²² cells, or whose pixels are
    /// sparser than the impulses (more cells than pixels to visit), are
    /// evaluated point by point, which is exact and then cheaper.
    pub fn splat_grid<const D: usize>(&self, grid: &Grid<D>, out: &mut [f32]) -> Result<(), SplatError>
    where
        Sparse: Noise<D>,
    {
        if D < 2 || grid.size[2.min(D)..].iter().any(|&s| s > 1) {
            return Err(SplatError::NotAWindow);
        }
        let expected = grid.checked_len().ok_or(SplatError::Grid(GridError::TooLarge))?;
        if out.len() != expected {
            return Err(SplatError::Grid(GridError::LengthMismatch { expected, got: out.len() }));
        }
        let (w, h) = (grid.size[0], grid.size[1]);
        if w == 0 || h == 0 {
            return Ok(());
        }
        let reach = self.support(D);
        let span = |d: usize, n: usize| {
            let (a, b) = (grid.coord(d, 0), grid.coord(d, n.saturating_sub(1)));
            (a.min(b) - reach, a.max(b) + reach)
        };
        let (x_span, y_span) = (span(0, w), span(1, h));
        // NaN fails `near` too, so NaN windows are evaluated point by point.
        let near = |c: f64| c.abs() < SPLAT_LIMIT;
        let far =
            ![x_span.0, x_span.1, y_span.0, y_span.1].into_iter().all(near) || !(2..D).all(|d| near(grid.origin[d]));
        let cells = (x_span.1 - x_span.0 + 2.0) * (y_span.1 - y_span.0 + 2.0);
        if far || cells > (w * h) as f64 {
            return Noise::<D>::fill_grid(self, grid, out).map_err(SplatError::Grid);
        }

        // The axes in the thread's scratch pool, as the grid fills take them.
        let axes = crate::grid::Axes::of(grid);
        let (xs, ys) = (axes.axis(0), axes.axis(1));
        let mut slice = [0f32; D];
        for (d, s) in slice.iter_mut().enumerate().skip(2) {
            *s = grid.coord(d, 0) as f32;
        }
        let (scale, offset) = self.output_scale(D);
        let render_band = |j0: usize, rows: &mut [f32]| {
            rows.fill(0.0);
            self.splat_band::<D>(xs, &ys[j0..j0 + rows.len() / w], &slice, rows);
            for v in rows.iter_mut() {
                *v = (*v as f64 * scale + offset) as f32;
            }
        };
        #[cfg(feature = "parallel")]
        {
            use rayon::prelude::*;
            out.par_chunks_mut(BAND * w).enumerate().for_each(|(b, rows)| render_band(b * BAND, rows));
        }
        #[cfg(not(feature = "parallel"))]
        for (b, rows) in out.chunks_mut(BAND * w).enumerate() {
            render_band(b * BAND, rows);
        }
        axes.recycle();
        Ok(())
    }

    /// Adds every impulse reaching the band's pixels into `rows` (raw sum).
    fn splat_band<const D: usize>(&self, xs: &[f32], ys: &[f32], slice: &[f32; D], rows: &mut [f32]) {
        let w = xs.len();
        let reach = self.support(D);
        let bounds = |c: &[f32]| {
            let (lo, hi) = c.iter().fold((f64::MAX, f64::MIN), |(lo, hi), &v| (lo.min(v as f64), hi.max(v as f64)));
            (cell_of(lo - reach), cell_of(hi + reach))
        };
        let (cx, cy) = (bounds(xs), bounds(ys));
        let mut lo = [0i64; D];
        let mut hi = [0i64; D];
        (lo[0], hi[0]) = cx;
        (lo[1], hi[1]) = cy;
        for d in 2..D {
            (lo[d], hi[d]) = (cell_of(slice[d] as f64 - reach), cell_of(slice[d] as f64 + reach));
        }
        // Pixel k sits at first + k·step (then rounded to f32), so a
        // coordinate maps to a fractional pixel index by arithmetic; ranges
        // are padded by a pixel each side for that rounding (the distance
        // test decides each pixel anyway). Casts of non-negative values
        // truncate, i.e. floor, without a libm call.
        let axis = |c: &[f32]| {
            let n = c.len();
            let step = if n > 1 { (c[n - 1] as f64 - c[0] as f64) / (n - 1) as f64 } else { 1.0 };
            (c[0] as f64, if step == 0.0 { 1.0 } else { step }, n as f64)
        };
        let (x_axis, y_axis) = (axis(xs), axis(ys));
        let pixel = |(first, step, _): (f64, f64, f64), x: f64| (x - first) / step;
        let range = |(_, step, n): (f64, f64, f64), centre: f64, half: f64| -> (usize, usize) {
            let half = half / step.abs();
            ((centre - half - 1.0).clamp(0.0, n) as usize, (centre + half + 2.0).clamp(0.0, n) as usize)
        };
        let mut cell = [0i64; D];
        let count: i64 = (0..D).map(|d| hi[d] - lo[d] + 1).product();
        for flat in 0..count {
            let mut rest = flat;
            for d in 0..D {
                let n = hi[d] - lo[d] + 1;
                cell[d] = lo[d] + rest % n;
                rest /= n;
            }
            let cell_i32 = cell.map(|c| c as i32);
            let cell_f = cell.map(|c| c as f32);
            self.impulses_of::<f32, D>(cell_i32, |pos, value| {
                let mut d = [0f32; D];
                let mut plane = 0f64;
                for k in 2..D {
                    d[k] = (slice[k] - cell_f[k]) - pos[k];
                    plane += d[k] as f64 * d[k] as f64;
                }
                // An isotropic kernel dz from the slice covers a disk of
                // radius √(r² − dz²): skip impulses with dz ≥ r and shrink
                // the box to the disk. (Per-row spans were measured slower
                // than testing the box's corners.) Padded for rounding; the
                // distance test decides every pixel.
                let half = if self.is_isotropic() {
                    let left = reach * reach * (1.0 + 1e-6) - plane;
                    if left <= 0.0 {
                        return;
                    }
                    crate::lanes::math::sqrt64(left) + 1e-6
                } else {
                    reach + 1e-6
                };
                let px = pixel(x_axis, cell[0] as f64 + pos[0] as f64);
                let py = pixel(y_axis, cell[1] as f64 + pos[1] as f64);
                let (i0, i1) = range(x_axis, px, half);
                let (j0, j1) = range(y_axis, py, half);
                for j in j0..j1 {
                    d[1] = (ys[j] - cell_f[1]) - pos[1];
                    let row = &mut rows[j * w..(j + 1) * w];
                    for i in i0..i1 {
                        d[0] = (xs[i] - cell_f[0]) - pos[0];
                        row[i] += value * self.weight::<f32>(self.distance2::<f32, D>(d));
                    }
                }
            });
        }
    }

    /// Noise at arbitrary 3D positions, one per output value (the paper's
    /// §5: a buffer of surface positions per pixel). Cells are culled from
    /// the positions as the paper's ID buffer does (§6): positions are
    /// grouped by the lowest cell that can reach them, and each group sums
    /// only the impulses of its neighbouring cells. Equal to point evaluation
    /// within 1e-5.
    pub fn splat_positions(&self, positions: &[[f32; 3]], out: &mut [f32]) -> Result<(), SplatError> {
        if positions.len() != out.len() {
            return Err(SplatError::PositionsMismatch { positions: positions.len(), out: out.len() });
        }
        let reach = self.support(3);
        let m = Self::cells_per_axis(reach) as i32;
        // The ID buffer: (lowest cell in reach, pixel), sorted so each cell's
        // pixels are contiguous. Non-finite or far positions go point by point.
        let mut ids: Vec<([i32; 3], usize)> = Vec::with_capacity(positions.len());
        for (k, p) in positions.iter().enumerate() {
            if p.iter().all(|c| (c.abs() as f64) < SPLAT_LIMIT) {
                ids.push((p.map(|c| cell_of(c as f64 - reach) as i32), k));
            } else {
                out[k] = Noise::<3>::get_f32(self, *p);
            }
        }
        ids.sort_unstable();
        let (scale, offset) = self.output_scale(3);
        let groups: Vec<&[([i32; 3], usize)]> = ids.chunk_by(|a, b| a.0 == b.0).collect();
        let mut sums = vec_zeroed(ids.len());
        let mut start = 0;
        let mut ranges = Vec::with_capacity(groups.len());
        for g in &groups {
            ranges.push((start, g.len()));
            start += g.len();
        }
        let sum_group = |group: &[([i32; 3], usize)], acc: &mut [f32]| {
            let base = group[0].0;
            for c in 0..m * m * m {
                let step = [c % m, (c / m) % m, c / (m * m)];
                let cell = [base[0] + step[0], base[1] + step[1], base[2] + step[2]];
                let cell_f = cell.map(|v| v as f32);
                self.impulses_of::<f32, 3>(cell, |pos, value| {
                    for (slot, &(_, k)) in acc.iter_mut().zip(group) {
                        let p = positions[k];
                        let d = [(p[0] - cell_f[0]) - pos[0], (p[1] - cell_f[1]) - pos[1], (p[2] - cell_f[2]) - pos[2]];
                        // The paper's interval depth test, then the kernel.
                        if d[2] * d[2] < (reach * reach) as f32 {
                            *slot += value * self.weight::<f32>(self.distance2::<f32, 3>(d));
                        }
                    }
                });
            }
        };
        let mut slices: Vec<&mut [f32]> = Vec::with_capacity(groups.len());
        let mut rest: &mut [f32] = &mut sums;
        for &(_, len) in &ranges {
            let (head, tail) = rest.split_at_mut(len);
            slices.push(head);
            rest = tail;
        }
        #[cfg(feature = "parallel")]
        {
            use rayon::prelude::*;
            groups.par_iter().zip(slices.par_iter_mut()).for_each(|(g, acc)| sum_group(g, acc));
        }
        #[cfg(not(feature = "parallel"))]
        for (g, acc) in groups.iter().zip(slices.iter_mut()) {
            sum_group(g, acc);
        }
        for (&(_, k), s) in ids.iter().zip(&sums) {
            out[k] = (*s as f64 * scale + offset) as f32;
        }
        Ok(())
    }
}

fn vec_zeroed(n: usize) -> Vec<f32> {
    let mut v = Vec::with_capacity(n);
    v.resize(n, 0.0);
    v
}
