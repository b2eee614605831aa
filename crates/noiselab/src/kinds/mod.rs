//! The noise kinds, one module each, and the lattice machinery they share.

pub mod classic;
pub mod fast;
pub mod improved;
pub(crate) mod lattice;
pub mod modified;
pub mod simplex;
pub mod simplex_n;
pub mod sparse;
pub mod value;
pub mod worley;

use alloc::vec::Vec;

use crate::lanes::{lerp, BatchLanes, IntLanes, Lanes};

/// Most corners a lattice cell has (4D).
pub(crate) const MAX_CORNERS: usize = 16;

/// Perlin's 2002 quintic fade 6t⁵ − 15t⁴ + 10t³, evaluated as
/// `t·t·t·(t·(t·6 − 15) + 10)` like his reference code.
#[inline(always)]
pub(crate) fn fade5<L: Lanes>(t: L) -> L {
    t * t * t * (t * (t * L::cst(6.0) - L::cst(15.0)) + L::cst(10.0))
}

/// Derivative of [`fade5`]: 30t²(t − 1)².
#[inline(always)]
pub(crate) fn fade5_deriv<L: Lanes>(t: L) -> L {
    let u = t - L::cst(1.0);
    L::cst(30.0) * t * t * u * u
}

/// Multilinear interpolation of `2^D` corner values (corner `c` has bit `d`
/// set when it is the upper corner on axis `d`), axis 0 innermost — the order
/// of every reference implementation.
#[inline(always)]
pub(crate) fn interpolate<L: Lanes, const D: usize>(mut v: [L; MAX_CORNERS], s: [L; D]) -> L {
    for (d, sd) in s.iter().enumerate() {
        interpolate_axis(&mut v, D - d, *sd);
    }
    v[0]
}

/// One step of [`interpolate`]: the `2^dims` values in `v` blended in pairs
/// along their lowest axis by weight `s`, into `v[..2^(dims − 1)]`.
#[inline(always)]
pub(crate) fn interpolate_axis<L: Lanes>(v: &mut [L; MAX_CORNERS], dims: usize, s: L) {
    for k in 0..(1 << (dims - 1)) {
        v[k] = lerp(s, v[2 * k], v[2 * k + 1]);
    }
}

/// [`interpolate`] together with its gradient, by differentiating the same
/// lerp chain: the value is bit-identical to [`interpolate`]'s.
///
/// `g[c]` is the gradient of corner `c`'s own function, `s` the fade weights
/// and `ds` their derivatives.
#[inline(always)]
pub(crate) fn interpolate_gradient<L: Lanes, const D: usize>(
    mut v: [L; MAX_CORNERS],
    mut g: [[L; D]; MAX_CORNERS],
    s: [L; D],
    ds: [L; D],
) -> (L, [L; D]) {
    for d in 0..D {
        for k in 0..(1 << (D - d - 1)) {
            let (a, b) = (v[2 * k], v[2 * k + 1]);
            let (ga, gb) = (g[2 * k], g[2 * k + 1]);
            v[k] = lerp(s[d], a, b);
            for e in 0..D {
                g[k][e] = lerp(s[d], ga[e], gb[e]);
            }
            g[k][d] = g[k][d] + ds[d] * (b - a);
        }
    }
    (v[0], g[0])
}

/// Offset of corner `c` from the cell's lower corner on axis `d` (0 or 1).
#[inline(always)]
pub(crate) const fn corner_bit(c: usize, d: usize) -> i32 {
    ((c >> d) & 1) as i32
}

/// Per lane: whether `x` is finite (x − x is 0 for finite x, NaN for ±∞
/// and NaN).
#[inline(always)]
#[allow(clippy::eq_op)]
pub(crate) fn is_finite<L: Lanes>(x: L) -> L::Mask {
    (x - x).le(L::cst(0.0))
}

/// `v` resized to `len` values in the room it has, its contents
/// unspecified: what an earlier use left, or zeros; NaN in debug builds,
/// so that a result read from an entry its caller did not write is NaN
/// and fails the bit-exact tests.
pub(crate) fn unwritten(v: &mut Vec<f32>, len: usize) {
    if cfg!(debug_assertions) {
        v.clear();
        v.resize(len, f32::NAN);
    } else {
        v.resize(len, 0.0);
    }
}

/// A field-major table of records for consecutive entries (lattice points
/// or cells along axis 0): field k of entry e at `[k·stride + e]`, so
/// consecutive entries load and store as lanes. Integer fields are stored
/// as their bits. The grid fills keep their per-row records here.
pub(crate) struct Columns {
    stride: usize,
    /// How many fields: `data` holds exactly `fields · stride` values.
    fields: usize,
    data: Vec<f32>,
}

impl Columns {
    /// Room for `fields` fields of `entries` entries (zeros), in a
    /// per-thread scratch buffer ([`crate::scratch`]): hand it back with
    /// [`Columns::recycle`].
    pub(crate) fn new(fields: usize, entries: usize) -> Self {
        let mut data = crate::scratch::take(fields * entries);
        data.clear();
        data.resize(fields * entries, 0.0);
        Columns { stride: entries, fields, data }
    }

    /// Room for `fields` fields of `entries` entries in `kept`, a vector
    /// its caller keeps between fills (left empty until
    /// [`Columns::keep_in`] puts it back): no trip through the scratch
    /// pool, which cost a 32² tile of 2D improved noise about 230
    /// instructions a table (callgrind, probe, AVX2). The contents are
    /// unspecified ([`unwritten`]): a caller reads only what it wrote, but
    /// for lanes whose results it never stores. (Zeroing took a tenth of a
    /// 32² tile's time: 8 KiB a tile on AVX-512, perf.)
    pub(crate) fn kept_in(kept: &mut Vec<f32>, fields: usize, entries: usize) -> Self {
        let mut data = core::mem::take(kept);
        unwritten(&mut data, fields * entries);
        Columns { stride: entries, fields, data }
    }

    /// Put the buffer back where [`Columns::kept_in`] took it from.
    pub(crate) fn keep_in(self, kept: &mut Vec<f32>) {
        *kept = self.data;
    }

    /// Give the buffer back for the next table on this thread. (A method,
    /// not `Drop`: drop glue in the grid fills' kernels measured 5 % slower
    /// on 2D fBm.)
    pub(crate) fn recycle(self) {
        crate::scratch::give_back(self.data);
    }

    /// Entries per field.
    #[inline(always)]
    pub(crate) fn stride(&self) -> usize {
        self.stride
    }

    /// Field `field` from entry `at` on.
    #[inline(always)]
    pub(crate) fn field(&self, field: usize, at: usize) -> &[f32] {
        &self.data[field * self.stride + at..]
    }

    /// [`Columns::field`], to write.
    #[inline(always)]
    fn field_mut(&mut self, field: usize, at: usize) -> &mut [f32] {
        &mut self.data[field * self.stride + at..]
    }

    /// Field `field` of entries `at..at + WIDTH`.
    #[inline(always)]
    pub(crate) fn load<B: BatchLanes>(&self, field: usize, at: usize) -> B {
        B::from_slice(self.field(field, at))
    }

    /// Store `v` as field `field` of entries `at..at + WIDTH`.
    #[inline(always)]
    pub(crate) fn store<B: BatchLanes>(&mut self, field: usize, at: usize, v: B) {
        v.store(self.field_mut(field, at));
    }

    /// Entries `first..first + width` of the first `fields` fields, checked
    /// once here so that reading them needs no check of its own (a grid
    /// chunk in one cell broadcasts dozens of them).
    #[inline(always)]
    pub(crate) fn entries(&self, fields: usize, first: usize, width: usize) -> Entries<'_> {
        // No sum or product that could overflow.
        assert!(fields <= self.fields && width <= self.stride && first <= self.stride - width);
        Entries { from: &self.data[first..], stride: self.stride, fields, width }
    }

    /// [`Columns::entries`], to write: a row of records stored a lane at a
    /// time keeps its pointer and stride in registers and checks each store
    /// once, where [`Columns::store`] reloads and checks twice.
    #[inline(always)]
    pub(crate) fn entries_mut(&mut self, fields: usize, first: usize, width: usize) -> EntriesMut<'_> {
        assert!(fields <= self.fields && width <= self.stride && first <= self.stride - width);
        EntriesMut { from: &mut self.data[first..], stride: self.stride, fields, width }
    }
}

/// Some entries of a [`Columns`], bounds-checked as a whole.
#[derive(Clone, Copy)]
pub(crate) struct Entries<'a> {
    from: &'a [f32],
    stride: usize,
    fields: usize,
    width: usize,
}

impl<'a> Entries<'a> {
    /// Fields `first..first + count` of the same entries, as a view of
    /// their own, checked here once: reads through it check their field
    /// against `count`, a constant where the caller's is, rather than
    /// against a runtime choice of fields (a plane's slot) read by read.
    #[inline(always)]
    pub(crate) fn fields(&self, first: usize, count: usize) -> Entries<'a> {
        assert!(first <= self.fields && count <= self.fields - first);
        // `from` holds `(fields − 1)·stride + width` values or more (see
        // `get`); from field `first` on, `(count − 1)·stride + width`.
        Entries { from: &self.from[first * self.stride..], stride: self.stride, fields: count, width: self.width }
    }

    /// Field `field` of the entry `at` past the first.
    #[inline(always)]
    pub(crate) fn get(&self, field: usize, at: usize) -> f32 {
        // Folds away where the caller's field and entry are constants.
        assert!(field < self.fields && at < self.width);
        // SAFETY: `from` starts `first` into data of `total · stride`
        // values, and `Columns::entries` checked fields ≤ total and first +
        // width ≤ stride. So field·stride + at ≤ (fields − 1)·stride +
        // width − 1 < total·stride − first.
        unsafe { *self.from.get_unchecked(field * self.stride + at) }
    }

    /// Field `field` of the entries `at..at + WIDTH` past the first.
    #[inline(always)]
    pub(crate) fn load<B: BatchLanes>(&self, field: usize, at: usize) -> B {
        assert!(field < self.fields && B::WIDTH <= self.width && at <= self.width - B::WIDTH);
        // SAFETY: as in `get`, with `at + WIDTH − 1 < width` the last entry.
        B::from_slice(unsafe {
            core::slice::from_raw_parts(self.from.as_ptr().add(field * self.stride + at), B::WIDTH)
        })
    }
}

/// Some entries of a [`Columns`] to write, bounds-checked as a whole.
pub(crate) struct EntriesMut<'a> {
    from: &'a mut [f32],
    stride: usize,
    fields: usize,
    width: usize,
}

impl EntriesMut<'_> {
    /// Store `v` as field `field` of the entries `at..at + WIDTH` past the first.
    #[inline(always)]
    pub(crate) fn store<B: BatchLanes>(&mut self, field: usize, at: usize, v: B) {
        assert!(field < self.fields && B::WIDTH <= self.width && at <= self.width - B::WIDTH);
        // SAFETY: as in `Entries::load`.
        v.store(unsafe {
            core::slice::from_raw_parts_mut(self.from.as_mut_ptr().add(field * self.stride + at), B::WIDTH)
        });
    }
}

/// The smallest and largest of some cells (of a grid row's columns).
#[inline(always)]
pub(crate) fn cell_range(cells: &[i32]) -> (i32, i32) {
    cells.iter().fold((i32::MAX, i32::MIN), |(a, b), &c| (a.min(c), b.max(c)))
}

/// `value` where every coordinate is finite, NaN elsewhere. Simplex kernels
/// are radial, so an infinite coordinate would otherwise give a quiet 0; the
/// library's contract is NaN for non-finite input.
#[inline(always)]
#[allow(clippy::eq_op)] // x − x is 0 for finite x and NaN for ±∞ and NaN.
pub(crate) fn finite_or_nan<L: Lanes, const D: usize>(p: [L; D], value: L) -> L {
    let mut poison = L::cst(0.0);
    for c in p {
        poison = poison + (c - c);
    }
    L::select(poison.le(L::cst(0.0)), value, poison)
}

/// Per-axis tiling periods in lattice cells (0 = that axis is unbounded).
/// Cell indices are wrapped before they are hashed, so a tiled noise repeats
/// exactly, has the statistics of the untiled one and costs one remainder
/// per corner. Axes beyond a noise's dimension are ignored.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Period([i32; 4]);

/// A period longer than 2³⁰ cells (the limit keeps wrapped indices exact).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PeriodError(pub u32);

impl core::fmt::Display for PeriodError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(f, "a period must be at most 2^30 cells, got {}", self.0)
    }
}

#[cfg(feature = "std")]
impl std::error::Error for PeriodError {}

impl Period {
    /// No axis tiled.
    pub const NONE: Period = Period([0; 4]);

    /// `cells[k]` cells along axis k (0 = unbounded).
    pub fn new(cells: [u32; 4]) -> Result<Period, PeriodError> {
        match cells.iter().find(|&&c| c > 1 << 30) {
            Some(&c) => Err(PeriodError(c)),
            None => Ok(Period(cells.map(|c| c as i32))),
        }
    }

    /// The periods, in cells.
    pub fn cells(&self) -> [u32; 4] {
        self.0.map(|c| c as u32)
    }

    /// Whether no axis is tiled.
    pub fn is_none(&self) -> bool {
        self.0 == [0; 4]
    }

    /// Cell index `c` on `axis`, wrapped into the period.
    #[inline(always)]
    pub(crate) fn wrap<I: IntLanes>(&self, axis: usize, c: I) -> I {
        match self.0.get(axis) {
            Some(&p) if p > 0 => c.rem_euclid(p),
            _ => c,
        }
    }

    /// A whole cell, wrapped.
    #[inline(always)]
    pub(crate) fn wrap_cell<I: IntLanes, const D: usize>(&self, mut cell: [I; D]) -> [I; D] {
        for (axis, c) in cell.iter_mut().enumerate() {
            *c = self.wrap(axis, *c);
        }
        cell
    }
}

#[cfg(all(test, feature = "std"))]
mod tests {
    use super::Columns;

    #[test]
    fn entries_read_every_field_and_refuse_what_lies_outside() {
        let mut t = Columns::new(3, 10);
        for (k, v) in t.data.iter_mut().enumerate() {
            *v = k as f32;
        }
        let e = t.entries(3, 7, 3);
        assert_eq!((e.get(0, 0), e.get(2, 2)), (7.0, 29.0));
        let refused = |fields: usize, first: usize, width: usize| {
            std::panic::catch_unwind(|| {
                t.entries(fields, first, width);
            })
            .is_err()
        };
        assert!(refused(4, 0, 1));
        assert!(refused(3, 8, 3));
        assert!(refused(1, 0, 11));
        assert!(refused(1, usize::MAX, 2));
        assert!(!refused(3, 10, 0));
        assert!(std::panic::catch_unwind(|| e.get(3, 0)).is_err());
        assert!(std::panic::catch_unwind(|| e.get(0, 3)).is_err());
    }
}
