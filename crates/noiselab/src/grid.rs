//! Batch evaluation: regular grids and point lists, eight lanes at a time.
//!
//! The drivers here are the only place that knows about instruction sets.
//! Each is compiled several times with `#[target_feature]` (AVX-512, AVX2,
//! and the baseline) and the best one the CPU supports is picked at run time
//! (with the `std` feature), so a crate built without `target-cpu=native`
//! still uses wide vectors. Every level runs the same IEEE operations, so
//! every level gives the same bits as the scalar `f32` API.

use crate::lanes::{F32x8, Lanes};
use crate::noise::Noise;
use alloc::vec::Vec;
use core::fmt;

/// A regular grid of sample points: point `(i₀, i₁, …)` lies at
/// `origin[d] + i_d · step[d]` on each axis `d`, computed in `f64` and rounded
/// to `f32`. Axis 0 varies fastest in the output buffer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Grid<const D: usize> {
    /// Coordinates of the first point.
    pub origin: [f64; D],
    /// Spacing between neighbouring points on each axis.
    pub step: [f64; D],
    /// Number of points on each axis.
    pub size: [usize; D],
}

/// Why a batch could not be filled.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum GridError {
    /// The output buffer's length is not the grid's number of points.
    LengthMismatch {
        /// Points in the grid.
        expected: usize,
        /// Length of the buffer given.
        got: usize,
    },
    /// The number of points overflows `usize`.
    TooLarge,
}

impl fmt::Display for GridError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            GridError::LengthMismatch { expected, got } => {
                write!(f, "output buffer holds {got} values but the grid has {expected} points")
            }
            GridError::TooLarge => write!(f, "grid has more points than fit in memory"),
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for GridError {}

impl<const D: usize> Grid<D> {
    /// A grid of `size` points starting at `origin`, `step` apart.
    pub fn new(origin: [f64; D], step: [f64; D], size: [usize; D]) -> Self {
        Grid { origin, step, size }
    }

    /// Total number of points, or `None` on overflow.
    pub fn checked_len(&self) -> Option<usize> {
        self.size.iter().try_fold(1usize, |a, &s| a.checked_mul(s))
    }

    /// Total number of points (saturating).
    pub fn len(&self) -> usize {
        self.checked_len().unwrap_or(usize::MAX)
    }

    /// Whether the grid has no points.
    pub fn is_empty(&self) -> bool {
        self.size.contains(&0)
    }

    /// Coordinate of index `i` along axis `d`, in `f64`.
    #[inline]
    pub fn coord(&self, d: usize, i: usize) -> f64 {
        self.origin[d] + i as f64 * self.step[d]
    }

    /// The `f32` point at flat index `index` (axis 0 fastest): exactly the
    /// point the batch evaluates there.
    pub fn point(&self, mut index: usize) -> [f32; D] {
        let mut p = [0f32; D];
        for (d, c) in p.iter_mut().enumerate() {
            let n = self.size[d].max(1);
            *c = self.coord(d, index % n) as f32;
            index /= n;
        }
        p
    }
}

/// An instruction-set level of the batch drivers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum SimdLevel {
    /// The compilation target's baseline (SSE2 on x86-64, NEON on aarch64).
    Baseline,
    /// AVX2 (x86-64). Never FMA: results stay bit-identical.
    Avx2,
    /// AVX-512F (x86-64).
    Avx512,
}

impl SimdLevel {
    /// Levels this CPU can run, lowest first.
    pub fn available() -> Vec<SimdLevel> {
        #[cfg_attr(not(all(feature = "std", target_arch = "x86_64")), allow(unused_mut))]
        let mut v = Vec::from([SimdLevel::Baseline]);
        #[cfg(all(feature = "std", target_arch = "x86_64"))]
        {
            if std::arch::is_x86_feature_detected!("avx2") {
                v.push(SimdLevel::Avx2);
            }
            if std::arch::is_x86_feature_detected!("avx512f") {
                v.push(SimdLevel::Avx512);
            }
        }
        v
    }

    /// The best level this CPU can run.
    pub fn best() -> SimdLevel {
        *Self::available().last().expect("baseline is always available")
    }
}

#[cfg(feature = "std")]
fn best_level() -> SimdLevel {
    static BEST: std::sync::OnceLock<SimdLevel> = std::sync::OnceLock::new();
    *BEST.get_or_init(SimdLevel::best)
}
#[cfg(not(feature = "std"))]
fn best_level() -> SimdLevel {
    SimdLevel::Baseline
}

/// Points per parallel task: large enough to amortise scheduling.
#[cfg(feature = "parallel")]
const PAR_CHUNK: usize = 1 << 14;

pub(crate) fn fill_grid<N: Noise<D>, const D: usize>(
    noise: &N,
    grid: &Grid<D>,
    out: &mut [f32],
) -> Result<(), GridError> {
    fill_grid_at(best_level(), noise, grid, out)
}

/// [`Noise::fill_grid`] at a chosen instruction-set level (for tests and
/// benchmarks; a level the CPU lacks falls back to the baseline).
pub fn fill_grid_at<N: Noise<D>, const D: usize>(
    level: SimdLevel,
    noise: &N,
    grid: &Grid<D>,
    out: &mut [f32],
) -> Result<(), GridError> {
    let expected = grid.checked_len().ok_or(GridError::TooLarge)?;
    if out.len() != expected {
        return Err(GridError::LengthMismatch { expected, got: out.len() });
    }
    if expected == 0 {
        return Ok(());
    }
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        if expected >= 4 * PAR_CHUNK {
            out.par_chunks_mut(PAR_CHUNK)
                .enumerate()
                .for_each(|(k, chunk)| dispatch_grid(level, noise, grid, k * PAR_CHUNK, chunk));
            return Ok(());
        }
    }
    dispatch_grid(level, noise, grid, 0, out);
    Ok(())
}

pub(crate) fn fill_points<N: Noise<D>, const D: usize>(noise: &N, points: &[[f32; D]], out: &mut [f32]) {
    fill_points_at(best_level(), noise, points, out)
}

/// [`Noise::fill_points`] at a chosen instruction-set level.
pub fn fill_points_at<N: Noise<D>, const D: usize>(
    level: SimdLevel,
    noise: &N,
    points: &[[f32; D]],
    out: &mut [f32],
) {
    assert_eq!(points.len(), out.len(), "fill_points: points and output differ in length");
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        if points.len() >= 4 * PAR_CHUNK {
            out.par_chunks_mut(PAR_CHUNK)
                .zip(points.par_chunks(PAR_CHUNK))
                .for_each(|(o, p)| dispatch_points(level, noise, p, o));
            return;
        }
    }
    dispatch_points(level, noise, points, out)
}

macro_rules! dispatcher {
    ($name:ident, $body:ident, ($($arg:ident : $ty:ty),*)) => {
        fn $name<N: Noise<D>, const D: usize>(level: SimdLevel, noise: &N, $($arg: $ty),*) {
            #[cfg(all(feature = "std", target_arch = "x86_64"))]
            {
                #[target_feature(enable = "avx512f")]
                unsafe fn avx512<N: Noise<D>, const D: usize>(noise: &N, $($arg: $ty),*) {
                    $body(noise, $($arg),*)
                }
                #[target_feature(enable = "avx2")]
                unsafe fn avx2<N: Noise<D>, const D: usize>(noise: &N, $($arg: $ty),*) {
                    $body(noise, $($arg),*)
                }
                let best = best_level();
                // SAFETY: each clone runs only when the CPU reports its feature.
                match level.min(best) {
                    SimdLevel::Avx512 => return unsafe { avx512(noise, $($arg),*) },
                    SimdLevel::Avx2 => return unsafe { avx2(noise, $($arg),*) },
                    SimdLevel::Baseline => {}
                }
            }
            let _ = level;
            $body(noise, $($arg),*)
        }
    };
}

dispatcher!(dispatch_grid, grid_span, (grid: &Grid<D>, start: usize, out: &mut [f32]));
dispatcher!(dispatch_points, points_span, (points: &[[f32; D]], out: &mut [f32]));

/// Fill `out` with grid points `start..start + out.len()`, row by row.
#[inline(always)]
fn grid_span<N: Noise<D>, const D: usize>(noise: &N, grid: &Grid<D>, start: usize, out: &mut [f32]) {
    let nx = grid.size[0];
    let mut index = start;
    let end = start + out.len();
    while index < end {
        let i0 = index % nx;
        let row_end = (index - i0 + nx).min(end);
        // Coordinates of axes 1.. are constant along the row.
        let mut rest = index / nx;
        let mut p = [F32x8::splat(0.0); D];
        for (d, pd) in p.iter_mut().enumerate().skip(1) {
            let n = grid.size[d];
            *pd = F32x8::splat(grid.coord(d, rest % n) as f32);
            rest /= n;
        }
        let mut i = i0;
        while i < i0 + (row_end - index) {
            let count = (i0 + (row_end - index) - i).min(8);
            let mut xs = [0f32; 8];
            for (k, x) in xs.iter_mut().enumerate() {
                // Pad the tail with the last point; its lanes are discarded.
                *x = grid.coord(0, i + k.min(count - 1)) as f32;
            }
            p[0] = F32x8(xs);
            let v = noise.sample(p);
            let o = index - start + (i - i0);
            out[o..o + count].copy_from_slice(&v.0[..count]);
            i += count;
        }
        index = row_end;
    }
}

#[inline(always)]
fn points_span<N: Noise<D>, const D: usize>(noise: &N, points: &[[f32; D]], out: &mut [f32]) {
    for (pc, oc) in points.chunks(8).zip(out.chunks_mut(8)) {
        let mut p = [F32x8::splat(0.0); D];
        for (d, pd) in p.iter_mut().enumerate() {
            let mut xs = [0f32; 8];
            for (k, x) in xs.iter_mut().enumerate() {
                *x = pc[k.min(pc.len() - 1)][d];
            }
            *pd = F32x8(xs);
        }
        let v = noise.sample(p);
        oc.copy_from_slice(&v.0[..oc.len()]);
    }
}
