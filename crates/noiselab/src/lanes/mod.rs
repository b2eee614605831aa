//! The numeric vocabulary every noise kernel is written in.
//!
//! A kernel is written once, generic over [`Lanes`], and instantiated for
//! `f64` (the reference-exact scalar API), `f32` (the scalar single-precision
//! API) and [`F32x8`] (eight points at a time for the batch API). The trait is
//! sealed: the set of lane types is closed, so kernels may rely on every
//! operation being an IEEE-754 operation performed lane by lane, with no fused
//! multiply-add and no reassociation. That is what makes `F32x8` lane *k*
//! equal to the `f32` result bit for bit.
//!
//! Integer lanes ([`IntLanes`]) carry lattice coordinates and hashes. They are
//! 32-bit and wrap on overflow in every build profile.

/// [`IntLanes::Bytes`] as the four vectors themselves, each lane's low byte
/// counting (every level but AVX2 and AVX-512): the additions wrap as `i32`, the lookups
/// and [`IntLanes::from_bytes`] mask.
macro_rules! bytes_as_vectors {
    () => {
        type Bytes = [Self; 4];
        #[inline(always)]
        fn to_bytes(v: [Self; 4]) -> [Self; 4] {
            v
        }
        #[inline(always)]
        fn from_bytes(b: [Self; 4]) -> [Self; 4] {
            [b[0].and_c(255), b[1].and_c(255), b[2].and_c(255), b[3].and_c(255)]
        }
        #[inline(always)]
        fn lookup_bytes(table: &Table256, b: [Self; 4]) -> [Self; 4] {
            [
                Self::lookup256(table, b[0]),
                Self::lookup256(table, b[1]),
                Self::lookup256(table, b[2]),
                Self::lookup256(table, b[3]),
            ]
        }
        #[inline(always)]
        fn add_bytes(a: [Self; 4], b: [Self; 4]) -> [Self; 4] {
            [a[0].add(b[0]), a[1].add(b[1]), a[2].add(b[2]), a[3].add(b[3])]
        }
        #[inline(always)]
        fn pick_bytes(b: [Self; 4], from: [usize; 4]) -> [Self; 4] {
            [b[from[0]], b[from[1]], b[from[2]], b[from[3]]]
        }
    };
}

// Used only by the batch drivers, which dispatch at run time with `std`.
#[cfg(all(feature = "std", target_arch = "x86_64"))]
pub(crate) mod avx2;
#[cfg(all(feature = "std", target_arch = "x86_64"))]
pub(crate) mod avx512;
mod scalar;
mod wide;

use core::fmt::Debug;
use core::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

pub use wide::{F32x16, F32x8, I32x16, I32x8, M32x16, M32x8};

pub(crate) mod sealed {
    pub trait Sealed {}
}

/// A scalar floating-point element type: `f32` or `f64`.
pub trait Elem: sealed::Sealed + Copy + Send + Sync + PartialOrd + Debug + 'static {
    /// Round an `f64` to this type (round to nearest even).
    fn from_f64(x: f64) -> Self;
    /// Widen to `f64` (exact).
    fn to_f64(self) -> f64;
    /// Of two tables holding the same data in each precision, the one of
    /// this type (for kinds whose tables are rounded per precision).
    fn pick<'a>(single: &'a [f32], double: &'a [f64]) -> &'a [Self];
}

/// A fixed number of floating-point lanes, operated on element-wise.
///
/// Every method is an exact IEEE-754 operation per lane (or a documented
/// exact integer conversion), so a kernel gives the same bits whatever the
/// width of the lane type it is instantiated with.
pub trait Lanes:
    sealed::Sealed
    + Copy
    + Send
    + Sync
    + Debug
    + 'static
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// The element type of one lane.
    type Elem: Elem;
    /// Signed 32-bit integer lanes of the same width.
    type Int: IntLanes<Mask = Self::Mask>;
    /// A per-lane boolean.
    type Mask: Copy + BitAnd<Output = Self::Mask> + BitOr<Output = Self::Mask> + Not<Output = Self::Mask>;
    /// Number of lanes.
    const WIDTH: usize;

    /// Every lane set to `x`.
    fn splat(x: Self::Elem) -> Self;
    /// A constant: `c` rounded to the element type, in every lane.
    #[inline(always)]
    fn cst(c: f64) -> Self {
        Self::splat(Self::Elem::from_f64(c))
    }
    /// Lanes from a slice of exactly `WIDTH` elements.
    fn from_slice(v: &[Self::Elem]) -> Self;
    /// Lane `k`.
    fn lane(self, k: usize) -> Self::Elem;

    /// Largest integer not greater than each lane.
    fn floor(self) -> Self;
    /// Absolute value.
    fn abs(self) -> Self;
    /// Correctly rounded square root.
    fn sqrt(self) -> Self;
    /// Lane-wise minimum, `if o < self { o } else { self }` in every
    /// implementation (so `self` where either is NaN): exactly
    /// `select(o.lt(self), o, self)`.
    fn min(self, o: Self) -> Self;
    /// Lane-wise maximum, `if o > self { o } else { self }` in every
    /// implementation: exactly `select(self.lt(o), o, self)`.
    fn max(self, o: Self) -> Self;
    /// [`Lanes::min`] of lanes that are neither NaN nor negative nor −0
    /// (search keys, distances). Those order as their bits do, read as
    /// signed integers, so an integer minimum gives the same bits: x86
    /// takes that one, which Zen 4 runs on all four vector pipes, where the
    /// float minimum shares the two float adders with every add and
    /// subtract (measured on this project's AVX-512 host: one float add
    /// and one float minimum a cycle together; an integer minimum beside
    /// an add, a quarter more).
    #[inline(always)]
    fn min_nonnegative(self, o: Self) -> Self {
        self.min(o)
    }
    /// [`Lanes::max`] of such lanes, as [`Lanes::min_nonnegative`].
    #[inline(always)]
    fn max_nonnegative(self, o: Self) -> Self {
        self.max(o)
    }

    /// `self < o`.
    fn lt(self, o: Self) -> Self::Mask;
    /// `self <= o`.
    fn le(self, o: Self) -> Self::Mask;
    /// `self > o`.
    #[inline(always)]
    fn gt(self, o: Self) -> Self::Mask {
        o.lt(self)
    }
    /// `self >= o`.
    #[inline(always)]
    fn ge(self, o: Self) -> Self::Mask {
        o.le(self)
    }
    /// Per lane: `a` where `m`, else `b`.
    fn select(m: Self::Mask, a: Self, b: Self) -> Self;
    /// Whether any lane of `m` is set (for loops that run until every lane
    /// is done; the result per lane must not depend on extra iterations).
    fn any(m: Self::Mask) -> bool;
    /// Evaluates a run-time-chosen noise on these lanes (the bridge that
    /// makes `Box<dyn DynNoise<D>>` a `Noise<D>`).
    #[doc(hidden)]
    fn sample_dyn<const D: usize>(noise: &dyn crate::noise::DynNoise<D>, p: [Self; D]) -> Self;
    /// Per lane: `self` raised to `e`, by libm's software `pow`/`powf`
    /// (the same function in every lane type, so lanes still agree).
    fn powf(self, e: Self) -> Self;

    /// Convert an integral value (e.g. the result of [`Lanes::floor`]) to an
    /// integer, wrapping modulo 2³² (exact for |x| < 2⁶³; NaN gives 0).
    fn to_int_wrapping(self) -> Self::Int;
    /// `⌊x⌋` as an integer, for lanes known to lie within ±2³¹ (other
    /// lanes get an unspecified value): one conversion rounding down on
    /// AVX-512, a floor and a truncation with no check for lanes out of
    /// range on AVX2 (elsewhere [`Lanes::to_int_wrapping`] of the floor).
    #[inline(always)]
    fn floor_to_int(self) -> Self::Int {
        self.floor().to_int_wrapping()
    }
    /// Convert integers to floats (rounded to nearest for |i| > 2²⁴ in f32).
    fn from_int(i: Self::Int) -> Self;
    /// Per lane: `table[idx]`. Indices must be in range (kernels mask them).
    fn gather(table: &[Self::Elem], idx: Self::Int) -> Self;
    /// Per lane: `table[idx & 15]` in the element type (one permute on
    /// AVX-512; one load, with no conversion, in one-lane `f64`).
    fn lookup16(table: &Table16, idx: Self::Int) -> Self;
    /// Per lane: `table[idx & 7]`, widened exactly to the element type
    /// (one permute on AVX2 and AVX-512, where [`Lanes::lookup16`] takes
    /// two and a blend on AVX2).
    fn lookup8(table: &[f32; 8], idx: Self::Int) -> Self;
    /// Each of `floats` at each of the four vectors of `bytes`: `[k][t]` is
    /// `lookup16(floats[t], vector k)`. AVX2 looks up the 32 bytes packed
    /// where every table has [`Table16::halves`]: two byte shuffles a table,
    /// where unpacking the bytes and [`Lanes::lookup16`] take two permutes
    /// and a blend a vector. AVX-512 spreads each vector's 16 bytes to its
    /// lanes with one byte permute, not zeroing the rest, which the
    /// table's permute ignores.
    #[inline(always)]
    fn lookup16_bytes<const T: usize>(bytes: <Self::Int as IntLanes>::Bytes, floats: [&Table16; T]) -> [[Self; T]; 4] {
        lookup16_each(Self::Int::from_bytes(bytes), floats)
    }

    /// `self * self`.
    #[inline(always)]
    fn sq(self) -> Self {
        self * self
    }
}

/// The lane types batches are evaluated in ([`F32x8`], [`F32x16`]): `f32`
/// lanes that can also be stored and loaded in bulk.
pub trait BatchLanes: Lanes<Elem = f32> {
    /// The batch drivers' level whose clones use these lanes.
    const LEVEL: crate::grid::SimdLevel;
    /// Write the lanes to `out[..WIDTH]`.
    fn store(self, out: &mut [f32]);
    /// [`BatchLanes::store`] past the caches (a non-temporal store: the
    /// line is not read in first, and no other line is evicted for it)
    /// where `out` starts on a register-wide boundary; a plain store
    /// elsewhere. Other threads may not see the values before a store
    /// fence (the grid fills end each span that streamed with one).
    fn store_streamed(self, out: &mut [f32]);
    /// Integer lanes 0, 1, …, WIDTH − 1.
    fn iota() -> Self::Int;
    /// A regular axis's coordinates at indices `first, first + 1, …`:
    /// `(origin + i · step) as f32`, the same IEEE operations as the
    /// scalar expression in `f64`, so the same bits (see `Grid::write_axes`,
    /// which stores them a register at a time).
    #[inline(always)]
    fn grid_coords(origin: f64, step: f64, first: i32) -> Self {
        let mut values = [0f32; 16];
        for (i, c) in (first..).zip(values.iter_mut().take(Self::WIDTH)) {
            *c = (origin + f64::from(i) * step) as f32;
        }
        Self::from_slice(&values)
    }
    /// Write integer lanes to `out[..WIDTH]`.
    fn store_int(v: Self::Int, out: &mut [i32]);
    /// Integer lanes from `v[..WIDTH]`.
    fn load_int(v: &[i32]) -> Self::Int;
    /// Integer lanes from the bytes `v[..WIDTH]`, zero-extended (one load
    /// and widen, where a table lookup would load lane by lane).
    fn load_u8(v: &[u8]) -> Self::Int;
    /// The lanes' bit patterns.
    fn to_bits(self) -> Self::Int;
    /// Lanes with the given bit patterns.
    fn from_bits(i: Self::Int) -> Self;
    /// Per lane: entry `idx` of the `2·WIDTH` entries `lo` then `hi`
    /// (`idx & (2·WIDTH − 1)`): one two-register permute on AVX-512.
    fn permute2(lo: Self, hi: Self, idx: Self::Int) -> Self;
    /// Per lane: entry `idx & (WIDTH − 1)` of `v` (one permute).
    fn permute(v: Self, idx: Self::Int) -> Self;
}

/// Signed 32-bit integer lanes with wrapping arithmetic.
pub trait IntLanes: sealed::Sealed + Copy + Send + Sync + Debug + 'static {
    /// A per-lane boolean, shared with the float lanes of the same width.
    type Mask: Copy;
    /// Every lane set to `x`.
    fn splat(x: i32) -> Self;
    /// Lane `k`.
    fn lane(self, k: usize) -> i32;
    /// Wrapping addition.
    fn add(self, o: Self) -> Self;
    /// Wrapping subtraction.
    fn sub(self, o: Self) -> Self;
    /// Wrapping multiplication.
    fn mul(self, o: Self) -> Self;
    /// Bitwise and.
    fn and(self, o: Self) -> Self;
    /// Bitwise or.
    fn or(self, o: Self) -> Self;
    /// Bitwise exclusive or.
    fn xor(self, o: Self) -> Self;
    /// Shift left by `s` bits.
    fn shl(self, s: u32) -> Self;
    /// Logical (unsigned) shift right by `s` bits.
    fn shr(self, s: u32) -> Self;
    /// Euclidean remainder by a positive constant: the result is in `0..m`.
    fn rem_euclid(self, m: i32) -> Self;
    /// Signed `self == o`.
    fn eq(self, o: Self) -> Self::Mask;
    /// Signed `self < o`.
    fn lt(self, o: Self) -> Self::Mask;
    /// Per lane: `a` where `m`, else `b`.
    fn select(m: Self::Mask, a: Self, b: Self) -> Self;
    /// Per lane: `table[idx]` widened to i32. Indices must be in range.
    fn gather_u8(table: &[u8], idx: Self) -> Self;
    /// Per lane: `table[idx & 255]`, a byte table of 256 entries (four
    /// register-wide byte permutes on AVX-512 VBMI instead of sixteen loads).
    fn lookup256(table: &Table256, idx: Self) -> Self;
    /// [`IntLanes::lookup256`] of four index vectors at once: on AVX2 their
    /// 32 low bytes go through one set of byte shuffles instead of 32
    /// scalar loads; on AVX-512 their 64 through one pair of permutes
    /// instead of four.
    #[inline(always)]
    fn lookup256x4(table: &Table256, idx: [Self; 4]) -> [Self; 4] {
        Self::from_bytes(Self::lookup_bytes(table, Self::to_bytes(idx)))
    }
    /// Four vectors' lanes where only each lane's low byte counts: what a
    /// chain of lookups in 256-entry byte tables carries from link to link.
    /// AVX2 and AVX-512 pack the 32 or 64 bytes into one register, so such
    /// a chain neither unpacks nor repacks between its links; other levels
    /// keep the vectors.
    type Bytes: Copy;
    /// The four vectors' low bytes.
    fn to_bytes(v: [Self; 4]) -> Self::Bytes;
    /// The four vectors of the bytes, zero-extended.
    fn from_bytes(b: Self::Bytes) -> [Self; 4];
    /// Per byte: `table[b]`.
    fn lookup_bytes(table: &Table256, b: Self::Bytes) -> Self::Bytes;
    /// Per byte: `a + b`, wrapping at 256.
    fn add_bytes(a: Self::Bytes, b: Self::Bytes) -> Self::Bytes;
    /// The bytes whose vector `k` is vector `from[k]` of `b` (`from[k] < 4`).
    fn pick_bytes(b: Self::Bytes, from: [usize; 4]) -> Self::Bytes;
    /// Per lane: `table[idx & 15]` (one permute on AVX-512).
    fn lookup16(table: &[i32; 16], idx: Self) -> Self;
    /// Per lane: `table[idx & 31]` (one two-table permute on AVX-512).
    fn lookup32(table: &[i32; 32], idx: Self) -> Self;
    /// Per lane: `table[idx]`. Indices must be in range.
    fn gather_i32(table: &[i32], idx: Self) -> Self;

    /// `self & m` for a constant.
    #[inline(always)]
    fn and_c(self, m: i32) -> Self {
        self.and(Self::splat(m))
    }
    /// `self + c` for a constant.
    #[inline(always)]
    fn add_c(self, c: i32) -> Self {
        self.add(Self::splat(c))
    }
    /// Lanes where bit `b` is set.
    #[inline(always)]
    fn bit(self, b: u32) -> Self::Mask {
        self.and_c(1 << b).eq(Self::splat(1 << b))
    }
}

/// A 256-entry byte table, aligned for whole-register loads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(C, align(64))]
pub struct Table256(pub [u8; 256]);

/// A 16-entry float table for [`Lanes::lookup16`], held in `f32` and, widened
/// exactly, in `f64` repeated to 256 entries: one-lane `f64` reads its entry
/// as it is (a conversion per entry was 24 of the 300 instructions of a
/// scalar 3D point), at a byte index (a hash read from a byte table) with no
/// mask to apply.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Table16 {
    single: [f32; 16],
    double: [f64; 256],
    halves: Option<[[u8; 16]; 2]>,
}

impl Table16 {
    /// The table of `entries`.
    pub const fn new(entries: [f32; 16]) -> Self {
        let mut double = [0.0; 256];
        let mut k = 0;
        while k < 256 {
            double[k] = entries[k % 16] as f64;
            k += 1;
        }
        let (mut low, mut high, mut two_bytes) = ([0; 16], [0; 16], true);
        let mut k = 0;
        while k < 16 {
            let bits = entries[k].to_bits();
            two_bytes &= bits & 0xFFFF == 0;
            (low[k], high[k]) = ((bits >> 16) as u8, (bits >> 24) as u8);
            k += 1;
        }
        Table16 { single: entries, double, halves: if two_bytes { Some([low, high]) } else { None } }
    }

    /// Bits 16–23 and 24–31 of each entry in `f32`, where every entry's
    /// lower sixteen bits are zero (±1, ±0, ±0.5 …): the entries are then
    /// two bytes each, which byte shuffles can look up.
    #[inline(always)]
    pub fn halves(&self) -> Option<&[[u8; 16]; 2]> {
        self.halves.as_ref()
    }

    /// The entries in `f32`.
    #[inline(always)]
    pub fn single(&self) -> &[f32; 16] {
        &self.single
    }

    /// Entry `i & 15` in `f64`.
    #[inline(always)]
    pub fn double(&self, i: i32) -> f64 {
        self.double[(i & 255) as usize]
    }
}

/// `[k][t] = L::lookup16(floats[t], bytes[k])`: [`Lanes::lookup16_bytes`]
/// on unpacked bytes.
#[inline(always)]
pub(crate) fn lookup16_each<L: Lanes, const T: usize>(bytes: [L::Int; 4], floats: [&Table16; T]) -> [[L; T]; 4] {
    let mut out = [[L::cst(0.0); T]; 4];
    for (values, b) in out.iter_mut().zip(bytes) {
        for (v, table) in values.iter_mut().zip(floats) {
            *v = L::lookup16(table, b);
        }
    }
    out
}

/// Linear interpolation `a + t·(b − a)`, the form every reference uses
/// (Perlin 1985/2002, Gustavson). Not `a·(1−t) + b·t`, which rounds differently.
#[inline(always)]
pub fn lerp<L: Lanes>(t: L, a: L, b: L) -> L {
    a + t * (b - a)
}

/// Split coordinates into the integer cell (wrapped to 32 bits) and the
/// fractional position inside it, `x − floor(x)`.
#[inline(always)]
pub fn cell<L: Lanes, const D: usize>(p: [L; D]) -> ([L::Int; D], [L; D]) {
    let mut c = [L::Int::splat(0); D];
    let mut f = p;
    for d in 0..D {
        let fl = p[d].floor();
        c[d] = fl.to_int_wrapping();
        f[d] = p[d] - fl;
    }
    (c, f)
}

/// Mathematical helpers that need `std` or `libm`.
pub(crate) mod math {
    #[cfg(feature = "std")]
    #[inline(always)]
    pub fn floor32(x: f32) -> f32 {
        x.floor()
    }
    #[cfg(feature = "std")]
    #[inline(always)]
    pub fn floor64(x: f64) -> f64 {
        x.floor()
    }
    #[cfg(feature = "std")]
    #[inline(always)]
    pub fn sqrt32(x: f32) -> f32 {
        x.sqrt()
    }
    #[cfg(feature = "std")]
    #[inline(always)]
    pub fn sqrt64(x: f64) -> f64 {
        x.sqrt()
    }
    #[cfg(not(feature = "std"))]
    pub use libm::{floor as floor64, floorf as floor32, sqrt as sqrt64, sqrtf as sqrt32};
}

/// Ask for the cache line at `p` ahead of a store to it (a hint: never
/// faults, whatever `p` is).
#[inline(always)]
pub(crate) fn prefetch_store(p: *const f32) {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: a prefetch reads nothing and cannot fault.
    unsafe {
        core::arch::x86_64::_mm_prefetch::<{ core::arch::x86_64::_MM_HINT_T0 }>(p.cast());
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = p;
}

/// Copy `from` into `to` (of the same length) past the caches: the
/// entries from `to`'s first register-wide boundary on, a register at a
/// time through [`BatchLanes::store_streamed`]; the few before it and after
/// the last whole register, plainly. For outputs larger than the last-level
/// cache, where a plain store first reads its line from memory: in C on
/// this project's AVX-512 host, 64 MiB filled at 0.49 ns a value with
/// plain stores and 0.18 streamed (32 MiB, which the cache holds: 0.18
/// both).
#[inline(always)]
pub(crate) fn stream_copy<B: BatchLanes>(from: &[f32], to: &mut [f32]) {
    let w = B::WIDTH;
    let n = from.len().min(to.len());
    let head = to.as_ptr().align_offset(4 * w).min(n);
    let body_end = head + (n - head) / w * w;
    to[..head].copy_from_slice(&from[..head]);
    let mut i = head;
    while i < body_end {
        B::from_slice(&from[i..]).store_streamed(&mut to[i..i + w]);
        i += w;
    }
    to[body_end..n].copy_from_slice(&from[body_end..n]);
}

/// Registers written one after another over a run of values, stored past
/// the caches on register-wide boundaries: each streamed store is the two
/// registers that straddle a boundary, permuted into one, and the values
/// before the first boundary and after the last are stored plainly. Unlike
/// [`stream_copy`] from a staged buffer, the stores drain while the next
/// registers are computed (in C on this project's AVX-512 host, a compute
/// loop filling 64 MiB: 0.49 ns a value with plain stores, 0.40 staged in
/// 16 KiB pieces, 0.31 in 4 KiB pieces, 0.26 streamed as it went; 0.19
/// computing alone).
pub(crate) struct StreamedRun<'a, B: BatchLanes> {
    out: &'a mut [f32],
    /// Values before `out`'s first register-wide boundary (0..WIDTH).
    lead: usize,
    /// Values pushed so far.
    at: usize,
    /// The register pushed last.
    carry: B,
    /// Lane j takes entry `j + lead` of the last register and the next.
    idx: B::Int,
}

impl<'a, B: BatchLanes> StreamedRun<'a, B> {
    /// A run over `out`, whose length the registers pushed must make up.
    #[inline(always)]
    pub(crate) fn new(out: &'a mut [f32]) -> Self {
        let w = B::WIDTH;
        let lead = out.as_ptr().align_offset(4 * w).min(w) % w;
        StreamedRun { out, lead, at: 0, carry: B::cst(0.0), idx: B::iota().add(B::Int::splat(lead as i32)) }
    }

    /// The next `WIDTH` values.
    #[inline(always)]
    pub(crate) fn push(&mut self, v: B) {
        let w = B::WIDTH;
        if self.lead == 0 {
            v.store_streamed(&mut self.out[self.at..self.at + w]);
        } else if self.at == 0 {
            crate::grid::store_prefix(v, &mut self.out[..self.lead]);
        } else {
            let s = self.at - w + self.lead;
            B::permute2(self.carry, v, self.idx).store_streamed(&mut self.out[s..s + w]);
        }
        self.carry = v;
        self.at += w;
    }

    /// Store what the last register left past the last boundary.
    #[inline(always)]
    pub(crate) fn finish(self) {
        if self.lead != 0 && self.at != 0 {
            let s = self.at - B::WIDTH + self.lead;
            crate::grid::store_prefix(B::permute(self.carry, self.idx), &mut self.out[s..self.at]);
        }
    }
}

/// Order this thread's streamed stores ([`BatchLanes::store_streamed`])
/// before its later stores, so that a thread which sees those (a join, a
/// release) sees the streamed values too.
#[inline(always)]
pub(crate) fn stream_fence() {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: SSE, which every x86_64 CPU has; a fence reads and writes nothing.
    unsafe {
        core::arch::x86_64::_mm_sfence();
    }
}

#[cfg(all(test, feature = "std", target_arch = "x86_64"))]
mod tests {
    use super::*;

    /// Lanes that are neither NaN nor negative nor −0: zero, subnormals,
    /// ordinary values, ties, the largest finite and infinity.
    fn nonnegative() -> Vec<f32> {
        let mut v = vec![0.0, f32::from_bits(1), f32::MIN_POSITIVE, 0.5, 1.0, 1.0, 2.25, f32::MAX, f32::INFINITY];
        let mut state = 0x9E37_79B9u32;
        while v.len() < 64 {
            state = state.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
            v.push(f32::from_bits((state >> 1) % 0x7F80_0000));
        }
        v
    }

    /// `min_nonnegative` and `max_nonnegative` give `min`'s and `max`'s
    /// bits on every pair of windows.
    #[inline(always)]
    fn check<L: Lanes<Elem = f32>>() {
        let v = nonnegative();
        let w = L::WIDTH;
        for i in 0..=v.len() - w {
            for j in 0..=v.len() - w {
                let (a, b) = (L::from_slice(&v[i..i + w]), L::from_slice(&v[j..j + w]));
                for (want, got) in [(a.min(b), a.min_nonnegative(b)), (a.max(b), a.max_nonnegative(b))] {
                    for k in 0..w {
                        assert_eq!(got.lane(k).to_bits(), want.lane(k).to_bits(), "{} vs {}", v[i + k], v[j + k]);
                    }
                }
            }
        }
    }

    /// On indices of every sign and size: `lookup256x4` gives each lane
    /// `table[idx & 255]`; in bytes, additions wrap at 256 and picks move
    /// whole vectors; `lookup16_bytes` gives each float table's entry at a
    /// byte's low nibble, bit for bit, with tables of two-byte entries (±0,
    /// ±1, ±0.5, ±2, ±3: [`Table16::halves`]) and with one that has none
    /// (so the lookup takes the lane-wise way), alone or beside the others.
    #[inline(always)]
    fn check_lookup<B: BatchLanes>() {
        let two_bytes =
            Table16::new([1.0, -1.0, 0.0, -0.0, 0.5, -0.5, 2.0, -2.0, 3.0, -3.0, 1.0, 0.0, -1.0, 0.0, 0.5, 1.0]);
        let reversed = Table16::new(core::array::from_fn(|k| two_bytes.single()[15 - k]));
        let wide = Table16::new(core::array::from_fn(|k| 0.1 * k as f32 - 0.7));
        assert!(two_bytes.halves().is_some() && reversed.halves().is_some() && wide.halves().is_none());
        let table = Table256(core::array::from_fn(|i| (i as u8).wrapping_mul(167).wrapping_add(13)));
        let mut state = 0x2545_F491u32;
        let mut idx = vec![0i32; 64 * B::WIDTH];
        for (k, i) in idx.iter_mut().enumerate() {
            state = state.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
            *i = if k % 5 == 0 { (state % 256) as i32 } else { state as i32 };
        }
        for four in idx.chunks_exact(4 * B::WIDTH) {
            let w = B::WIDTH;
            let vectors =
                [B::load_int(four), B::load_int(&four[w..]), B::load_int(&four[2 * w..]), B::load_int(&four[3 * w..])];
            for (v, got) in B::Int::lookup256x4(&table, vectors).into_iter().enumerate() {
                for k in 0..B::WIDTH {
                    let i = four[v * B::WIDTH + k];
                    assert_eq!(got.lane(k), table.0[(i & 255) as usize] as i32, "index {i}");
                }
            }
            let shifted = [vectors[1], vectors[3], vectors[0], vectors[2]];
            for from in [[0, 1, 2, 3], [3, 3, 0, 1], [2, 0, 1, 2]] {
                let sums = B::Int::add_bytes(B::Int::to_bytes(vectors), B::Int::to_bytes(shifted));
                for (v, got) in B::Int::from_bytes(B::Int::pick_bytes(sums, from)).into_iter().enumerate() {
                    for k in 0..B::WIDTH {
                        let (a, b) = (vectors[from[v]].lane(k), shifted[from[v]].lane(k));
                        assert_eq!(got.lane(k), a.wrapping_add(b) & 255, "{a} + {b}, picked {from:?}");
                    }
                }
            }
            let looked = B::Int::lookup_bytes(&table, B::Int::to_bytes(vectors));
            for floats in [[&two_bytes, &reversed], [&two_bytes, &wide], [&wide, &wide]] {
                for (v, values) in B::lookup16_bytes(looked, floats).iter().enumerate() {
                    for (t, value) in values.iter().enumerate() {
                        for k in 0..B::WIDTH {
                            let i = four[v * B::WIDTH + k];
                            let want = floats[t].single()[(table.0[(i & 255) as usize] & 15) as usize];
                            assert_eq!(value.lane(k).to_bits(), want.to_bits(), "index {i}, table {t}");
                        }
                    }
                }
            }
        }
    }

    /// Integral values of every size: small, at and past ±2³¹ and ±2⁶³,
    /// the largest finite, infinities and NaN.
    fn integral() -> Vec<f64> {
        let two31 = 2147483648.0;
        let two63 = 9223372036854775808.0;
        let mut v = vec![0.0, -0.0, 1.0, -1.0, 255.0, -256.0, 16777216.0, -16777217.0];
        v.extend([two31 - 128.0, two31, -two31, -two31 - 256.0, 2.0 * two31, 3e9, -3e9, 5e9 + 7.0]);
        v.extend([1e18, -1e18, two63, -two63, 2.0 * two63, 1e30, -1e30, f64::from(f32::MAX)]);
        v.extend([f64::MAX, f64::INFINITY, f64::NEG_INFINITY, f64::NAN]);
        v
    }

    /// `to_int_wrapping` gives `x as i64 as i32` (saturating, then wrapping)
    /// in every lane, whether a lane's value fits the plain conversion or
    /// takes the path past it.
    #[inline(always)]
    fn check_wrapping<B: BatchLanes>() {
        let v: Vec<f32> = integral().iter().map(|&x| x as f32).collect();
        let w = B::WIDTH;
        // Every window, the last one (NaN in its last lane) included.
        for i in 0..=v.len() - w {
            let got = B::from_slice(&v[i..i + w]).to_int_wrapping();
            for k in 0..w {
                assert_eq!(got.lane(k), v[i + k] as i64 as i32, "{}", v[i + k]);
            }
        }
    }

    /// The properties the tests below check, each on any lanes.
    #[derive(Clone, Copy)]
    enum Property {
        NonnegativeMinMax,
        LookupsOfFour,
        Wrapping,
    }

    #[inline(always)]
    fn check_property<B: BatchLanes>(property: Property) {
        match property {
            Property::NonnegativeMinMax => check::<B>(),
            Property::LookupsOfFour => check_lookup::<B>(),
            Property::Wrapping => check_wrapping::<B>(),
        }
    }

    #[target_feature(enable = "avx2")]
    fn at_avx2(property: Property) {
        check_property::<avx2::X8>(property);
    }

    /// The features of the AVX-512 level.
    #[target_feature(enable = "avx512f,avx512bw,avx512dq,avx512vl,avx512vbmi")]
    fn at_avx512(property: Property) {
        check_property::<avx512::X16>(property);
    }

    /// `property` on the baseline's lanes and on every level the CPU has.
    fn at_every_level(property: Property) {
        check_property::<F32x8>(property);
        check_property::<F32x16>(property);
        let best = crate::grid::SimdLevel::best();
        if best >= crate::grid::SimdLevel::Avx2 {
            // SAFETY: the CPU reports the level's features.
            unsafe { at_avx2(property) };
        }
        if best == crate::grid::SimdLevel::Avx512 {
            // SAFETY: as above.
            unsafe { at_avx512(property) };
        }
    }

    /// Four vectors looked up at once are each looked up alone.
    #[test]
    fn lookups_of_four_are_lookups_of_one() {
        at_every_level(Property::LookupsOfFour);
    }

    /// Conversions to integers wrap alike in scalar `f32` and `f64` and in
    /// every level's lanes.
    #[test]
    fn conversions_wrap_alike() {
        for x in integral() {
            assert_eq!(Lanes::to_int_wrapping(x), x as i64 as i32, "{x}");
            assert_eq!(Lanes::to_int_wrapping(x as f32), x as f32 as i64 as i32, "{x}");
        }
        at_every_level(Property::Wrapping);
    }

    /// The integer minimum and maximum that x86 takes for them are the
    /// float ones.
    #[test]
    fn nonnegative_min_and_max_are_min_and_max() {
        check::<f32>();
        at_every_level(Property::NonnegativeMinMax);
    }
}
