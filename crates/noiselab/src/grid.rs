//! Batch evaluation: regular grids and point lists, many lanes at a time.
//!
//! The drivers here are the only place that knows about instruction sets.
//! Each is compiled several times with `#[target_feature]` (AVX-512 with
//! sixteen lanes, AVX2 and the baseline with eight) and the best one the CPU
//! supports is picked at run time (with the `std` feature), so a crate built
//! without `target-cpu=native` still uses wide vectors. Every level runs the
//! same IEEE operations, so every level gives the same bits as the scalar
//! `f32` API.
//!
//! A grid reaches a noise as a [`Span`]: per-axis coordinates ([`Axes`]) and
//! a run of flat indices. A noise may fill it any way it likes as long as
//! each value is what [`Noise::get_f32`] gives at that point
//! ([`Accuracy::Exact`]); lattice kinds hash once per cell instead of once
//! per point (`kinds::lattice`), fractals fill octave by octave.

use crate::lanes::{BatchLanes, IntLanes, Lanes};
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
    /// A point list and its output differ in length.
    PointsMismatch {
        /// Points given.
        points: usize,
        /// Length of the output buffer given.
        out: usize,
    },
}

impl fmt::Display for GridError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            GridError::LengthMismatch { expected, got } => {
                write!(f, "output buffer holds {got} values but the grid has {expected} points")
            }
            GridError::TooLarge => write!(f, "grid has more points than fit in memory"),
            GridError::PointsMismatch { points, out } => {
                write!(f, "output buffer holds {out} values for {points} points")
            }
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

    /// The `f32` coordinates along axis `d`: [`Grid::coord`] of each index,
    /// rounded.
    pub fn axis_coords(&self, d: usize) -> Vec<f32> {
        let mut coords = alloc::vec![0.0; self.size[d]];
        self.write_axes(d..d + 1, &mut coords);
        coords
    }

    /// The coordinates of `axes`, one axis after another, into `out` (its
    /// length the sum of their sizes), compiled for the widest registers
    /// the CPU has: the same IEEE operations, so the same bits, in a
    /// quarter of the baseline's instructions on AVX-512 (at the baseline,
    /// a 32² tile's two axes were 6 % of its fast fill, perf). One
    /// dispatch for all of them: axis by axis, the two calls and level
    /// checks of a 32² tile's axes took 3 % of its fast fill (perf,
    /// AVX-512).
    fn write_axes(&self, axes: core::ops::Range<usize>, out: &mut [f32]) {
        self.write_axes_at(best_level(), axes, out)
    }

    /// [`Grid::write_axes`] at `level` (the best the CPU has up to it).
    #[cfg_attr(not(all(feature = "std", target_arch = "x86_64")), allow(unused_variables))]
    fn write_axes_at(&self, level: SimdLevel, axes: core::ops::Range<usize>, out: &mut [f32]) {
        #[cfg(all(feature = "std", target_arch = "x86_64"))]
        {
            #[target_feature(enable = "avx512f")]
            unsafe fn avx512<const D: usize>(grid: &Grid<D>, axes: core::ops::Range<usize>, out: &mut [f32]) {
                grid.write_axes_here::<crate::lanes::avx512::X16>(axes, out)
            }
            #[target_feature(enable = "avx2")]
            unsafe fn avx2<const D: usize>(grid: &Grid<D>, axes: core::ops::Range<usize>, out: &mut [f32]) {
                grid.write_axes_here::<crate::lanes::avx2::X8>(axes, out)
            }
            match runnable(level) {
                // SAFETY: `runnable` never exceeds the features the CPU reports.
                SimdLevel::Avx512 => return unsafe { avx512(self, axes, out) },
                SimdLevel::Avx2 => return unsafe { avx2(self, axes, out) },
                SimdLevel::Baseline => {}
            }
        }
        self.write_axes_here::<crate::lanes::F32x8>(axes, out)
    }

    /// [`Grid::write_axes`] at the instruction set of its caller.
    #[inline(always)]
    fn write_axes_here<B: BatchLanes>(&self, axes: core::ops::Range<usize>, out: &mut [f32]) {
        let mut rest = out;
        for d in axes {
            let (axis, after) = rest.split_at_mut(self.size[d]);
            self.write_axis_here::<B>(d, axis);
            rest = after;
        }
    }

    /// Axis `d`'s coordinates into `out` (its length the axis's size) at
    /// the instruction set of its caller ([`Grid::write_axes`]).
    #[inline(always)]
    fn write_axis_here<B: BatchLanes>(&self, d: usize, out: &mut [f32]) {
        let (origin, step) = (self.origin[d], self.step[d]);
        // Counting in `i32` where it fits (with a register to spare past the
        // end): its conversion to `f64` vectorises at the baseline
        // instruction set, `usize`'s does not. Both are exact, so the
        // coordinates are `coord`'s.
        if i32::try_from(out.len() + 2 * B::WIDTH).is_ok() {
            // A register at a time: the batch fills load an axis a register
            // at a time right after, and a load that spans two stores
            // still in flight waits for both to reach the cache. (As one
            // plain loop, a 32² tile's axes went through LLVM's 8-wide
            // remainder: its 32-byte stores under AVX-512's 64-byte loads
            // cost a 32² tile of 2D improved about 8 % of its time, perf.
            // On AVX2, LLVM stores a register joined from two halves as the
            // two halves, so there the loads still wait; on Zen 3 keeping
            // it whole measured no faster.) The last register's lanes past
            // the end are dropped.
            let w = B::WIDTH;
            let mut first = 0i32;
            let mut blocks = out.chunks_exact_mut(w);
            for block in &mut blocks {
                B::grid_coords(origin, step, first).store(block);
                first += w as i32;
            }
            let rest = blocks.into_remainder();
            if !rest.is_empty() {
                store_prefix(B::grid_coords(origin, step, first), rest);
            }
        } else {
            for (i, c) in out.iter_mut().enumerate() {
                *c = self.coord(d, i) as f32;
            }
        }
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

/// How closely a grid fill must follow the scalar API.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Accuracy {
    /// Every value equals [`Noise::get_f32`] at [`Grid::point`] bit for bit.
    #[default]
    Exact,
    /// Lattice kinds (classic, improved, value, modified) and fractals of
    /// them evaluate each grid row as a polynomial per lattice cell (or,
    /// where cells hold several rows, each column of a cell's rows): within
    /// 1e-6 of [`Accuracy::Exact`] (absolute, tested), and faster. Where a
    /// row's cells are narrower than a SIMD register's worth of points and
    /// hold few rows (fewer than four; at the AVX-512 level, fewer than
    /// eight where rows are over 512 points: a fractal's fine octaves), and
    /// for other kinds, the fill is exact. Since the register's width
    /// decides, fast values may differ between instruction-set levels,
    /// each within the bound.
    Fast,
}

/// How a grid fill stores its values. Either way they are the same values.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Stores {
    /// Plain stores, through the caches: for outputs the caches hold, or
    /// that are read again soon (a fractal's octaves).
    #[default]
    Cached,
    /// Past the caches (non-temporal stores), for a caller's output larger
    /// than the last-level cache ([`STREAM_MIN_VALUES`] or more), where a
    /// plain store first reads its line from memory. The lattice kinds'
    /// fills of whole rows of long runs of one cell, up to 1024 values wide
    /// (classic, improved, modified: exact rows and fast bands), take it,
    /// as do value noise's plane blends where the rows start at one offset
    /// from a register boundary (rows of a multiple of the register's
    /// lanes); wider rows, finer cells and other kinds store plainly.
    /// A fractal's combine of up to eight octaves where every coordinate is
    /// finite streams where asked to, and on grids of 2²⁰ points (4 MiB) or
    /// more whether asked or not.
    Streamed,
}

/// Fewest values for which a grid fill streams its stores
/// ([`Stores::Streamed`]): 32 MiB. (In C on this project's AVX-512 host,
/// plain stores filled 32 MiB at 0.18 ns a value, as streamed ones did,
/// 40 MiB at 0.35 and 64 MiB at 0.49, against 0.16–0.18 streamed.)
pub const STREAM_MIN_VALUES: usize = 1 << 23;

/// The coordinates of a grid, axis by axis, rounded to `f32`: exactly the
/// coordinates the batch evaluates (point `(i₀, i₁, …)` is
/// `(axes[0][i₀], axes[1][i₁], …)`).
#[derive(Clone, Debug, PartialEq)]
pub struct Axes<const D: usize> {
    /// Every axis's coordinates, axis after axis: one buffer, taken from
    /// the thread's scratch pool by the grid fills (a 32² tile's fill
    /// allocated one vector per axis, and a fractal's one per axis and
    /// octave).
    coords: Vec<f32>,
    /// Where each axis ends in `coords`.
    ends: [usize; D],
}

impl<const D: usize> Axes<D> {
    /// No points on any axis, holding no buffer.
    pub(crate) const EMPTY: Self = Axes { coords: Vec::new(), ends: [0; D] };

    /// The axes of `grid`.
    pub fn of(grid: &Grid<D>) -> Self {
        let mut axes = Self::room(grid.size);
        grid.write_axes(0..D, &mut axes.coords);
        axes
    }

    /// The axes of `grid` in `coords` (resized to them).
    fn of_in(grid: &Grid<D>, mut coords: Vec<f32>) -> Self {
        let (ends, total) = Self::ends_of(grid.size);
        coords.resize(total, 0.0);
        grid.write_axes(0..D, &mut coords);
        Axes { coords, ends }
    }

    /// Axes given coordinate by coordinate.
    pub fn new(coords: [Vec<f32>; D]) -> Self {
        let mut axes = Self::room(core::array::from_fn(|d| coords[d].len()));
        for (d, c) in coords.iter().enumerate() {
            let (start, end) = axes.bounds(d);
            axes.coords[start..end].copy_from_slice(c);
        }
        axes
    }

    /// Axes of `sizes` points (contents unspecified), in a scratch buffer.
    fn room(sizes: [usize; D]) -> Self {
        let (ends, total) = Self::ends_of(sizes);
        let mut coords = crate::scratch::take(total);
        coords.truncate(total);
        Axes { coords, ends }
    }

    /// Where each axis of `sizes` points ends in one buffer, and its length.
    fn ends_of(sizes: [usize; D]) -> ([usize; D], usize) {
        let mut ends = [0; D];
        let mut total = 0usize;
        for (end, size) in ends.iter_mut().zip(sizes) {
            total = total.checked_add(size).expect("axes too long to hold");
            *end = total;
        }
        (ends, total)
    }

    /// Where axis `d` starts and ends in the buffer.
    #[inline(always)]
    fn bounds(&self, d: usize) -> (usize, usize) {
        (if d == 0 { 0 } else { self.ends[d - 1] }, self.ends[d])
    }

    /// Give the buffer back to the thread's scratch pool.
    pub(crate) fn recycle(self) {
        crate::scratch::give_back(self.coords);
    }

    /// The coordinates along `axis`.
    #[inline(always)]
    pub fn axis(&self, axis: usize) -> &[f32] {
        let (start, end) = self.bounds(axis);
        &self.coords[start..end]
    }

    /// Whether every coordinate of every axis is finite.
    pub(crate) fn all_finite(&self) -> bool {
        self.coords[..self.ends[D - 1]].iter().all(|c| c.is_finite())
    }

    /// Whether every coordinate of every axis lies within `±limit` (so is
    /// finite).
    pub(crate) fn all_within(&self, limit: f32) -> bool {
        self.coords[..self.ends[D - 1]].iter().all(|c| c.abs() <= limit)
    }

    /// Whether every coordinate of every axis is an integer (finite).
    /// Branch-free, so that it vectorises: a fractal tile asks it of every
    /// octave, and an octave on integers went through its coordinates one
    /// by one (3 % of a 32² tile of fBm-6, perf).
    pub(crate) fn all_integers(&self) -> bool {
        self.coords[..self.ends[D - 1]]
            .iter()
            .fold(true, |all, &c| all & (c.is_finite() & (c == crate::lanes::math::floor32(c))))
    }

    /// Points of the grid: every axis's size multiplied.
    pub(crate) fn points(&self) -> usize {
        (0..D).fold(1usize, |n, d| n.saturating_mul(self.size(d)))
    }

    /// Points along `axis`.
    #[inline(always)]
    pub fn size(&self, axis: usize) -> usize {
        let (start, end) = self.bounds(axis);
        end - start
    }

    /// Every coordinate multiplied by `factor` in `f32` (`c * factor` per
    /// coordinate, as a point evaluation of `p * factor` rounds it).
    pub fn scaled(&self, factor: f32) -> Self {
        self.scaled_in(factor, crate::scratch::take(self.coords.len()))
    }

    /// [`Axes::scaled`] into `coords`, a buffer its caller keeps (see
    /// [`Axes::into_coords`]).
    pub(crate) fn scaled_in(&self, factor: f32, mut coords: Vec<f32>) -> Self {
        coords.clear();
        coords.extend(self.coords.iter().map(|&c| c * factor));
        Axes { coords, ends: self.ends }
    }

    /// The buffer, for its owner to keep (where [`Axes::recycle`] gives
    /// it to the scratch pool).
    pub(crate) fn into_coords(self) -> Vec<f32> {
        self.coords
    }

    /// The axes of columns `columns` (of axis 0) in every row, in a
    /// scratch buffer.
    pub(crate) fn columns(&self, columns: core::ops::Range<usize>) -> Self {
        let mut sizes = [columns.len(); D];
        for (d, size) in sizes.iter_mut().enumerate().skip(1) {
            *size = self.size(d);
        }
        let mut axes = Self::room(sizes);
        let width = columns.len();
        axes.coords[..width].copy_from_slice(&self.axis(0)[columns]);
        axes.coords[width..].copy_from_slice(&self.coords[self.ends[0]..self.ends[D - 1]]);
        axes
    }

    /// The indices along axes 1.. of row `row` (axis 0 varies within a row).
    #[inline(always)]
    pub fn row_indices(&self, mut row: usize) -> [usize; D] {
        let mut idx = [0usize; D];
        for d in 1..D {
            let n = self.size(d);
            idx[d] = row % n;
            row /= n;
        }
        idx
    }
}

/// A run of a grid's points, in flat order (axis 0 fastest), for a noise to
/// fill: the unit of work of the batch drivers.
#[derive(Clone, Copy, Debug)]
pub struct Span<'a, const D: usize> {
    /// The grid's coordinates.
    pub axes: &'a Axes<D>,
    /// Flat index of the first point.
    pub start: usize,
    /// How closely values must follow the scalar API.
    pub accuracy: Accuracy,
    /// How the values are stored.
    pub stores: Stores,
}

impl<const D: usize> Span<'_, D> {
    /// The columns (axis-0 indices) that `len` points from the span's
    /// start touch, as a range `lo..hi`: the span's own columns when it
    /// stays in one row, else every column.
    #[inline(always)]
    pub fn columns(&self, len: usize) -> (usize, usize) {
        let nx = self.axes.size(0);
        if nx == 0 {
            return (0, 0);
        }
        let first = self.start % nx;
        if first + len <= nx {
            (first, first + len)
        } else {
            (0, nx)
        }
    }

    /// The (partial) grid rows that `len` points from the span's start
    /// cover, in order.
    #[inline(always)]
    pub fn rows(&self, len: usize) -> RowIter<'_, D> {
        RowIter { axes: self.axes, index: self.start, end: self.start + len, start: self.start, next: None }
    }
}

/// A piece of one grid row: [`Span::rows`]'s items.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RowPiece<const D: usize> {
    /// The row's indices along axes 1.. (`[0]` is 0; see [`Axes::row_indices`]).
    pub idx: [usize; D],
    /// The first column.
    pub first: usize,
    /// Where the piece starts in the span's output.
    pub offset: usize,
    /// Number of columns.
    pub len: usize,
}

/// Iterator over the row pieces of a span.
#[derive(Clone, Debug)]
pub struct RowIter<'a, const D: usize> {
    axes: &'a Axes<D>,
    index: usize,
    end: usize,
    start: usize,
    /// The next row's indices, once the first piece is out (rows then
    /// follow one another: the indices count up, no divisions).
    next: Option<[usize; D]>,
}

impl<const D: usize> Iterator for RowIter<'_, D> {
    type Item = RowPiece<D>;
    #[inline(always)]
    fn next(&mut self) -> Option<RowPiece<D>> {
        let nx = self.axes.size(0);
        if self.index >= self.end || nx == 0 {
            return None;
        }
        let (idx, first) = match self.next {
            Some(idx) => (idx, 0),
            None => (self.axes.row_indices(self.index / nx), self.index % nx),
        };
        let len = (nx - first).min(self.end - self.index);
        let piece = RowPiece { idx, first, offset: self.index - self.start, len };
        self.index += len;
        // The following row: axis 1 counts up, carrying into the next axes.
        let mut following = idx;
        for d in 1..D {
            following[d] += 1;
            if following[d] < self.axes.size(d) {
                break;
            }
            following[d] = 0;
        }
        self.next = Some(following);
        Some(piece)
    }
}

/// The default way to fill a span: evaluate [`Noise::sample`] on `B`'s
/// lanes, chunk by chunk along each row.
#[inline(always)]
pub fn fill_pointwise<N: Noise<D>, B: BatchLanes, const D: usize>(noise: &N, span: Span<'_, D>, out: &mut [f32]) {
    fill_chunks::<_, B, D>(&mut Pointwise(noise), span, out)
}

/// A grid's points evaluated a chunk of lanes at a time, in order along
/// each row, with whatever the evaluator carries from one chunk to the
/// next (a kind's per-chunk tables). A trait, not a closure: a closure's
/// body would not inherit the batch driver's instruction set.
pub(crate) trait ChunkSampler<B: BatchLanes, const D: usize> {
    /// The values at the chunk's points.
    fn sample(&mut self, p: [B; D]) -> B;
}

/// [`Noise::sample`] chunk by chunk, nothing carried.
struct Pointwise<'a, N>(&'a N);

impl<N: Noise<D>, B: BatchLanes, const D: usize> ChunkSampler<B, D> for Pointwise<'_, N> {
    #[inline(always)]
    fn sample(&mut self, p: [B; D]) -> B {
        self.0.sample(p)
    }
}

/// [`fill_pointwise`] through a [`ChunkSampler`].
#[inline(always)]
pub(crate) fn fill_chunks<S: ChunkSampler<B, D>, B: BatchLanes, const D: usize>(
    noise: &mut S,
    span: Span<'_, D>,
    out: &mut [f32],
) {
    let w = B::WIDTH;
    let xs = span.axes.axis(0);
    for RowPiece { idx, first: i0, offset: o0, len: n } in span.rows(out.len()) {
        let mut p = [B::splat(0.0); D];
        for d in 1..D {
            p[d] = B::splat(span.axes.axis(d)[idx[d]]);
        }
        let mut k = 0;
        // Two chunks at a time: independent work the CPU can overlap.
        while k + 2 * w <= n {
            let i = i0 + k;
            let mut q = p;
            p[0] = B::from_slice(&xs[i..i + w]);
            q[0] = B::from_slice(&xs[i + w..i + 2 * w]);
            let (a, b) = (noise.sample(p), noise.sample(q));
            a.store(&mut out[o0 + k..]);
            b.store(&mut out[o0 + k + w..]);
            k += 2 * w;
        }
        while k < n {
            let count = (n - k).min(w);
            let i = i0 + k;
            p[0] = row_lanes(xs, i, count);
            let v = noise.sample(p);
            store_prefix(v, &mut out[o0 + k..o0 + k + count]);
            k += count;
        }
    }
}

/// Coordinates `xs[i..i + count]` (`count` ≤ WIDTH) as lanes, a short
/// tail padded with its last point (whose extra lanes are discarded).
#[inline(always)]
pub(crate) fn row_lanes<B: BatchLanes>(xs: &[f32], i: usize, count: usize) -> B {
    if count == B::WIDTH {
        return B::from_slice(&xs[i..i + count]);
    }
    let mut pad = [0f32; 16];
    for (j, x) in pad.iter_mut().enumerate().take(B::WIDTH) {
        *x = xs[i + j.min(count - 1)];
    }
    B::from_slice(&pad)
}

/// Store the first `out.len()` (≤ WIDTH) lanes of `v`.
#[inline(always)]
pub(crate) fn store_prefix<B: BatchLanes>(v: B, out: &mut [f32]) {
    if out.len() == B::WIDTH {
        v.store(out);
    } else {
        let mut tmp = [0f32; 16];
        v.store(&mut tmp);
        out.copy_from_slice(&tmp[..out.len()]);
    }
}

/// An instruction-set level of the batch drivers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum SimdLevel {
    /// The compilation target's baseline (SSE2 on x86-64, NEON on aarch64),
    /// eight lanes.
    Baseline,
    /// AVX2 (x86-64), eight lanes. Never FMA: results stay bit-identical.
    Avx2,
    /// AVX-512 F, BW, DQ, VL and VBMI (x86-64: Ice Lake, Zen 4 and later),
    /// sixteen lanes. (Earlier AVX-512 CPUs, without VBMI's byte permutes
    /// for table lookups, run the AVX2 level.)
    Avx512,
}

impl SimdLevel {
    /// Levels this CPU can run, lowest first.
    pub fn available() -> Vec<SimdLevel> {
        #[cfg_attr(not(all(feature = "std", target_arch = "x86_64")), allow(unused_mut))]
        let mut v = Vec::from([SimdLevel::Baseline]);
        #[cfg(all(feature = "std", target_arch = "x86_64"))]
        {
            use std::arch::is_x86_feature_detected as has;
            if has!("avx2") {
                v.push(SimdLevel::Avx2);
            }
            if has!("avx512f") && has!("avx512bw") && has!("avx512dq") && has!("avx512vl") && has!("avx512vbmi") {
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

/// Fewest points per parallel task: enough to amortise scheduling.
#[cfg(feature = "parallel")]
const PAR_CHUNK: usize = 1 << 15;

pub(crate) fn fill_grid<N: Noise<D>, const D: usize>(
    noise: &N,
    grid: &Grid<D>,
    out: &mut [f32],
    accuracy: Accuracy,
) -> Result<(), GridError> {
    fill_grid_at(best_level(), noise, grid, out, accuracy)
}

/// [`Noise::fill_grid`] (or, with [`Accuracy::Fast`], [`Noise::fill_grid_fast`])
/// at a chosen instruction-set level (for tests and benchmarks; a level the
/// CPU lacks falls back to the best it has).
pub fn fill_grid_at<N: Noise<D>, const D: usize>(
    level: SimdLevel,
    noise: &N,
    grid: &Grid<D>,
    out: &mut [f32],
    accuracy: Accuracy,
) -> Result<(), GridError> {
    let expected = grid.checked_len().ok_or(GridError::TooLarge)?;
    if out.len() != expected {
        return Err(GridError::LengthMismatch { expected, got: out.len() });
    }
    if expected == 0 {
        return Ok(());
    }
    let mut kept = KEPT_AXES.take();
    let axes = Axes::of_in(grid, core::mem::take(&mut kept.0));
    fill_axes_at(level, noise, &axes, out, accuracy);
    kept.0 = axes.coords;
    KEPT_AXES.keep(kept);
    Ok(())
}

/// [`fill_grid_at`]'s axes buffer, kept by each thread between fills
/// rather than taken from the scratch pool and given back, which was 4 %
/// of a fast 32² tile's time (perf, AVX-512).
#[derive(Default)]
struct KeptAxes(Vec<f32>);

impl crate::scratch::KeptVectors for KeptAxes {
    fn held_bytes(&self) -> usize {
        crate::scratch::bytes_of(&self.0)
    }
}

crate::scratch::per_thread!(KEPT_AXES: KeptAxes);

/// Fill `out` (flat, axis 0 fastest; its length must be the product of the
/// axes' sizes) at the points of `axes`, in parallel under the `parallel`
/// feature. Chunks follow rows, and no value depends on how the work is cut.
pub(crate) fn fill_axes_at<N: Noise<D>, const D: usize>(
    level: SimdLevel,
    noise: &N,
    axes: &Axes<D>,
    out: &mut [f32],
    accuracy: Accuracy,
) {
    // The whole output's size, not a span's: threads cut it into smaller ones.
    let stores = if out.len() >= STREAM_MIN_VALUES { Stores::Streamed } else { Stores::Cached };
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        if out.len() >= 4 * PAR_CHUNK {
            // About four tasks per thread, whole rows where rows are short.
            let nx = axes.size(0).max(1);
            let per_task = (out.len() / (4 * rayon::current_num_threads())).max(PAR_CHUNK);
            let chunk = if nx <= per_task { per_task / nx * nx } else { per_task };
            out.par_chunks_mut(chunk).enumerate().for_each(|(k, part)| {
                noise.dispatch_span(level, Span { axes, start: k * chunk, accuracy, stores }, part)
            });
            return;
        }
    }
    noise.dispatch_span(level, Span { axes, start: 0, accuracy, stores }, out)
}

/// One point in `f64` or `f32` ([`Noise::get`], [`Noise::get_f32`]),
/// compiled for AVX2 where the CPU has it: the same IEEE operations (no
/// FMA), with branch-free blends and rounding instructions instead of
/// library calls.
#[inline(always)]
pub(crate) fn point<N: Noise<D>, L: Lanes, const D: usize>(noise: &N, p: [L; D]) -> L {
    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    {
        #[target_feature(enable = "avx2")]
        unsafe fn avx2<N: Noise<D>, L: Lanes, const D: usize>(noise: &N, p: [L; D]) -> L {
            // Each coordinate read by itself. The caller stores them one by
            // one, and LLVM's SLP vectoriser loaded two at once where a kind
            // floors them together, a load the CPU cannot forward from two
            // stores: a stall before the first floor (3D improved in f64,
            // Zen 4: 33 → 22 ns a point; the `1.8×` that once kept scalar
            // lanes off `value_unsigned_zero`).
            let mut q = p;
            for (to, from) in q.iter_mut().zip(&p) {
                // SAFETY: `from` is a valid reference.
                *to = unsafe { core::ptr::read_volatile(from) };
            }
            noise.sample(q)
        }
        if best_level() >= SimdLevel::Avx2 {
            // SAFETY: the CPU reports AVX2.
            return unsafe { avx2(noise, p) };
        }
    }
    noise.sample(p)
}

/// One span at the best level (the bridge for noises chosen at run time).
pub(crate) fn fill_span_best<N: Noise<D>, const D: usize>(noise: &N, span: Span<'_, D>, out: &mut [f32]) {
    noise.dispatch_span(best_level(), span, out)
}

pub(crate) fn fill_points<N: Noise<D>, const D: usize>(
    noise: &N,
    points: &[[f32; D]],
    out: &mut [f32],
) -> Result<(), GridError> {
    fill_points_at(best_level(), noise, points, out)
}

/// [`Noise::fill_points`] at a chosen instruction-set level.
pub fn fill_points_at<N: Noise<D>, const D: usize>(
    level: SimdLevel,
    noise: &N,
    points: &[[f32; D]],
    out: &mut [f32],
) -> Result<(), GridError> {
    if points.len() != out.len() {
        return Err(GridError::PointsMismatch { points: points.len(), out: out.len() });
    }
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        if points.len() >= 4 * PAR_CHUNK {
            out.par_chunks_mut(PAR_CHUNK)
                .zip(points.par_chunks(PAR_CHUNK))
                .for_each(|(o, p)| noise.dispatch_points(level, p, o));
            return Ok(());
        }
    }
    noise.dispatch_points(level, points, out);
    Ok(())
}

/// The level to run for a request of `level`: the best the CPU has up to it.
#[inline]
pub(crate) fn runnable(level: SimdLevel) -> SimdLevel {
    level.min(best_level())
}

/// Defines `mod batch` in the calling module: the batch drivers
/// (a span through [`Noise::fill_span`], a list of points through
/// [`Noise::sample`]) compiled once per instruction-set level, each level
/// in a submodule of its own, and `span` / `points` to pick one at run time.
///
/// Why every kind's module has its own: rustc compiles a generic function's
/// instances in the codegen unit of the module that defines it, and LLVM
/// optimises one codegen unit on one core. With one set of clones here, all
/// kinds' batch code at all levels formed one codegen unit: the test binary
/// that names every kind spent over 13 minutes optimising it on one core
/// while the other idled. A kind's `Noise` impl enters its own module's
/// clones through [`batch_entry!`], so kinds and levels compile in
/// parallel. The code is the same wherever it is compiled.
macro_rules! batch_clones {
    ($($vis:tt)*) => {
        /// This module's batch drivers, one clone per instruction-set level
        /// (`crate::grid::batch_clones!` says why they live here).
        $($vis)* mod batch {
            use crate::grid::{SimdLevel, Span};
            use crate::noise::Noise;

            /// `span` at `level` (the best the CPU has up to it).
            pub(crate) fn span<N: Noise<D>, const D: usize>(level: SimdLevel, noise: &N, span: Span<'_, D>, out: &mut [f32]) {
                // SAFETY: `runnable` never exceeds the features the CPU
                // reports, and the baseline clone needs none.
                crate::grid::with_driver_stack(|| unsafe {
                    match crate::grid::runnable(level) {
                        #[cfg(all(feature = "std", target_arch = "x86_64"))]
                        SimdLevel::Avx512 => avx512::span(noise, span, out),
                        #[cfg(all(feature = "std", target_arch = "x86_64"))]
                        SimdLevel::Avx2 => avx2::span(noise, span, out),
                        _ => baseline::span(noise, span, out),
                    }
                })
            }

            /// `points` at `level` (the best the CPU has up to it).
            pub(crate) fn points<N: Noise<D>, const D: usize>(level: SimdLevel, noise: &N, points: &[[f32; D]], out: &mut [f32]) {
                // SAFETY: as for `span`.
                crate::grid::with_driver_stack(|| unsafe {
                    match crate::grid::runnable(level) {
                        #[cfg(all(feature = "std", target_arch = "x86_64"))]
                        SimdLevel::Avx512 => avx512::points(noise, points, out),
                        #[cfg(all(feature = "std", target_arch = "x86_64"))]
                        SimdLevel::Avx2 => avx2::points(noise, points, out),
                        _ => baseline::points(noise, points, out),
                    }
                })
            }

            #[cfg(all(feature = "std", target_arch = "x86_64"))]
            crate::grid::level_clones!(avx512, crate::lanes::avx512::X16, #[target_feature(enable = "avx512f,avx512bw,avx512dq,avx512vl,avx512vbmi")]);
            #[cfg(all(feature = "std", target_arch = "x86_64"))]
            crate::grid::level_clones!(avx2, crate::lanes::avx2::X8, #[target_feature(enable = "avx2")]);
            crate::grid::level_clones!(baseline, crate::lanes::F32x8,);
        }
    };
}
pub(crate) use batch_clones;

/// Runs `driver` (a batch driver) where the stack has room for it.
///
/// Unoptimized code keeps its own stack slot for every temporary of every
/// inlined body, and a driver inlines its kind's whole batch code: at
/// opt-level 0 a driver's frame measured up to 5.3 MiB (2D to 4D Worley on
/// AVX-512; 4D improved 3.1 MiB), beyond the 2 MiB a spawned thread or a
/// rayon worker gets, so a user's debug build overflowed there. Where less
/// than [`UNOPTIMIZED_RED_ZONE`] is left, the driver runs on a fresh stack of
/// [`UNOPTIMIZED_STACK`] (stacker), once per driver call, so once per span or
/// point list. Cargo's `debug_assertions` is the sign of such a build (its
/// dev profile sets both); elsewhere a driver's frame is a few KiB and this
/// is a plain call.
#[inline(always)]
pub(crate) fn with_driver_stack<R>(driver: impl FnOnce() -> R) -> R {
    #[cfg(all(feature = "std", debug_assertions))]
    {
        stacker::maybe_grow(UNOPTIMIZED_RED_ZONE, UNOPTIMIZED_STACK, driver)
    }
    #[cfg(not(all(feature = "std", debug_assertions)))]
    {
        driver()
    }
}

/// The stack a batch driver needs in an unoptimized build: the largest
/// frame measured (5.3 MiB) with room to spare.
#[cfg(all(feature = "std", debug_assertions))]
const UNOPTIMIZED_RED_ZONE: usize = 8 << 20;

/// The stack [`with_driver_stack`] gives a driver where the red zone is not
/// left: address space, its pages taken only as the frame touches them.
#[cfg(all(feature = "std", debug_assertions))]
const UNOPTIMIZED_STACK: usize = 16 << 20;

/// One level's module of [`batch_clones!`]: the span and point drivers on
/// lanes `$lanes`, compiled with `$feature`.
macro_rules! level_clones {
    ($module:ident, $lanes:ty, $(#[$feature:meta])?) => {
        mod $module {
            use crate::grid::Span;
            use crate::noise::Noise;

            // Never inlined: the baseline clone (the only one that could
            // be) made the dispatcher's frame its own, over 4 KiB with a
            // stack probe, for every call at every level.
            $(#[$feature])?
            #[inline(never)]
            pub(super) unsafe fn span<N: Noise<D>, const D: usize>(noise: &N, span: Span<'_, D>, out: &mut [f32]) {
                noise.fill_span::<$lanes>(span, out)
            }

            $(#[$feature])?
            #[inline(never)]
            pub(super) unsafe fn points<N: Noise<D>, const D: usize>(noise: &N, points: &[[f32; D]], out: &mut [f32]) {
                crate::grid::points_body::<N, $lanes, D>(noise, points, out)
            }
        }
    };
}
pub(crate) use level_clones;

/// The `Noise` methods that enter the calling module's [`batch_clones!`]
/// (`$d`: the impl's dimension, a literal or its const parameter).
macro_rules! batch_entry {
    ($d:tt) => {
        #[inline]
        fn dispatch_span(&self, level: crate::grid::SimdLevel, span: crate::grid::Span<'_, $d>, out: &mut [f32]) {
            batch::span(level, self, span, out)
        }
        #[inline]
        fn dispatch_points(&self, level: crate::grid::SimdLevel, points: &[[f32; $d]], out: &mut [f32]) {
            batch::points(level, self, points, out)
        }
    };
}
pub(crate) use batch_entry;

// The clones of noises that do not name their own (yours, and noises chosen
// at run time).
batch_clones!(pub(crate));

/// The point-list driver on lanes `B`: whole chunks of lanes through
/// [`Noise::sample`], the last chunk padded.
#[inline(always)]
pub(crate) fn points_body<N: Noise<D>, B: BatchLanes, const D: usize>(noise: &N, points: &[[f32; D]], out: &mut [f32]) {
    let w = B::WIDTH;
    // Two chunks at a time where possible: independent work the CPU can overlap.
    let pairs = points.len() / (2 * w) * (2 * w);
    for (pc, oc) in points[..pairs].chunks_exact(2 * w).zip(out[..pairs].chunks_exact_mut(2 * w)) {
        let (a, b) = (noise.sample(lanes_of::<B, D>(&pc[..w])), noise.sample(lanes_of::<B, D>(&pc[w..])));
        a.store(&mut oc[..w]);
        b.store(&mut oc[w..]);
    }
    for (pc, oc) in points[pairs..].chunks(w).zip(out[pairs..].chunks_mut(w)) {
        store_prefix(noise.sample(lanes_of::<B, D>(pc)), oc);
    }
}

/// Up to WIDTH points as lanes per axis (the last point repeated).
#[inline(always)]
fn lanes_of<B: BatchLanes, const D: usize>(pc: &[[f32; D]]) -> [B; D] {
    if B::LEVEL == SimdLevel::Avx512 && D > 1 && pc.len() == B::WIDTH {
        return deinterleave::<B, D>(pc.as_flattened());
    }
    if B::LEVEL == SimdLevel::Avx2 && D == 3 && pc.len() == B::WIDTH {
        return deinterleave_coprime::<B, D>(pc.as_flattened());
    }
    let mut p = [B::splat(0.0); D];
    for (d, pd) in p.iter_mut().enumerate() {
        let mut xs = [0f32; 16];
        for (k, x) in xs.iter_mut().enumerate().take(B::WIDTH) {
            *x = pc[k.min(pc.len() - 1)][d];
        }
        *pd = B::from_slice(&xs);
    }
    p
}

/// WIDTH points stored point by point (`flat`, D·WIDTH coordinates) as
/// lanes per axis: the D registers of coordinates permuted two at a time,
/// where loading them a coordinate per lane took 48 inserts per 16 3D
/// points (AVX-512, 4 M random 3D points of improved noise in the probe:
/// 2.72 → 2.55 ns/point). Only on AVX-512, whose two-register permute is
/// one instruction.
#[inline(always)]
fn deinterleave<B: BatchLanes, const D: usize>(flat: &[f32]) -> [B; D] {
    let w = B::WIDTH;
    let mut regs = [B::splat(0.0); D];
    for (q, r) in regs.iter_mut().enumerate() {
        *r = B::from_slice(&flat[q * w..]);
    }
    let mut p = [B::splat(0.0); D];
    for (d, pd) in p.iter_mut().enumerate() {
        // Lane k of axis d is coordinate k·D + d, in register (k·D + d) / w.
        // The first permute takes the lanes found in registers 0 and 1,
        // each later one those in its register, keeping the rest.
        let mut idx = [0i32; 16];
        for (k, i) in idx.iter_mut().enumerate().take(w) {
            *i = (k * D + d).min(2 * w - 1) as i32;
        }
        let mut lanes = B::permute2(regs[0], regs[1], B::load_int(&idx));
        for (q, &r) in regs.iter().enumerate().skip(2) {
            for (k, i) in idx.iter_mut().enumerate().take(w) {
                let at = k * D + d;
                *i = if at / w == q { (w + at % w) as i32 } else { k as i32 };
            }
            lanes = B::permute2(lanes, r, B::load_int(&idx));
        }
        *pd = lanes;
    }
    p
}

/// [`deinterleave`] where D and WIDTH have no common factor (3D on AVX2,
/// which has no two-register permute): coordinate k·D + d lies in lane
/// (k·D + d) mod WIDTH of its register, a different lane for each k, so
/// selects with constant masks (immediate blends) gather an axis's lanes
/// from the D registers into one, and one permute puts them in order.
/// Three operations an axis in 3D, where inserting a coordinate per lane
/// took nine (random 3D points of improved noise on AVX2, 64 Ki of them
/// under callgrind: 66.2 → 64.8 instructions a point).
#[inline(always)]
fn deinterleave_coprime<B: BatchLanes, const D: usize>(flat: &[f32]) -> [B; D] {
    let w = B::WIDTH;
    debug_assert!(D % 2 == 1, "D must be odd: WIDTH is a power of two");
    let mut regs = [B::splat(0.0); D];
    for (q, r) in regs.iter_mut().enumerate() {
        *r = B::from_slice(&flat[q * w..]);
    }
    let mut p = [B::splat(0.0); D];
    for (d, pd) in p.iter_mut().enumerate() {
        // Lane `at % w` of the gathered register comes from register `at / w`.
        let (mut from, mut order) = ([0i32; 16], [0i32; 16]);
        for k in 0..w {
            let at = k * D + d;
            from[at % w] = (at / w) as i32;
            order[k] = (at % w) as i32;
        }
        let from = B::load_int(&from);
        let mut gathered = regs[0];
        for (q, &r) in regs.iter().enumerate().skip(1) {
            gathered = B::select(from.eq(B::Int::splat(q as i32)), r, gathered);
        }
        *pd = B::permute(gathered, B::load_int(&order));
    }
    p
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Lane k of axis d is point k's coordinate d, for every dimension
    /// that permutes and both lane widths.
    #[test]
    fn deinterleave_puts_each_axis_in_its_lanes() {
        fn check<B: BatchLanes, const D: usize>() {
            let w = B::WIDTH;
            let pts: Vec<[f32; D]> = (0..w).map(|k| core::array::from_fn(|d| (k * 10 + d) as f32)).collect();
            let mut ways = vec![deinterleave::<B, D>(pts.as_flattened())];
            if D % 2 == 1 {
                ways.push(deinterleave_coprime::<B, D>(pts.as_flattened()));
            }
            for (way, lanes) in ways.iter().enumerate() {
                for (d, l) in lanes.iter().enumerate() {
                    let mut got = [0f32; 16];
                    l.store(&mut got);
                    let want: Vec<f32> = (0..w).map(|k| (k * 10 + d) as f32).collect();
                    assert_eq!(&got[..w], &want[..], "{D}D axis {d}, {w} lanes, way {way}");
                }
            }
        }
        check::<crate::lanes::F32x16, 2>();
        check::<crate::lanes::F32x16, 3>();
        check::<crate::lanes::F32x16, 4>();
        check::<crate::lanes::F32x8, 3>();
        check::<crate::lanes::F32x8, 4>();
    }

    /// The axes a grid fill reads are [`Grid::coord`] rounded to `f32`, bit
    /// for bit, at the CPU's best level and at the portable lanes: whole
    /// registers and the remainder, far and huge coordinates (past
    /// `f32::MAX`: infinite), negative steps.
    #[test]
    fn written_axes_are_the_rounded_coordinates() {
        let grids = [
            Grid::new([0.1, -3.0], [1.0 / 32.0, -0.7], [70, 33]),
            Grid::new([123456.789, -70000.37], [1.0 / 48.0, 1e-7], [16, 5]),
            Grid::new([3.0e38, 1.0], [1.0e37, f64::INFINITY], [40, 3]),
        ];
        for grid in &grids {
            let want: Vec<f32> = (0..2).flat_map(|d| (0..grid.size[d]).map(move |i| grid.coord(d, i) as f32)).collect();
            let mut got = vec![0f32; want.len()];
            let same = |got: &[f32]| {
                got.iter().zip(&want).all(|(a, b)| a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan()))
            };
            for level in SimdLevel::available() {
                got.fill(0.0);
                grid.write_axes_at(level, 0..2, &mut got);
                assert!(same(&got), "{level:?}: {got:?}");
            }
            got.fill(0.0);
            grid.write_axes_here::<crate::lanes::F32x8>(0..2, &mut got);
            assert!(same(&got), "8 portable lanes: {got:?}");
            got.fill(0.0);
            grid.write_axes_here::<crate::lanes::F32x16>(0..2, &mut got);
            assert!(same(&got), "16 portable lanes: {got:?}");
        }
    }

    /// Row pieces from any start cover the span in order, each with the
    /// indices `row_indices` gives its row (the iterator counts them up).
    #[test]
    fn row_pieces_carry_their_rows_indices() {
        let axes = Axes::of(&Grid::new([0.0; 3], [1.0; 3], [5, 3, 4]));
        for start in [0, 1, 4, 5, 14, 15, 16, 59] {
            for len in [1, 4, 6, 17, 60 - start] {
                let len = len.min(60 - start);
                let span = Span { axes: &axes, start, accuracy: Accuracy::Exact, stores: Stores::Cached };
                let mut at = start;
                for piece in span.rows(len) {
                    assert_eq!(piece.offset, at - start);
                    assert_eq!(piece.first, at % 5);
                    assert_eq!(piece.idx, axes.row_indices(at / 5), "start {start}, len {len}, at {at}");
                    at += piece.len;
                }
                assert_eq!(at, start + len);
            }
        }
    }
}
