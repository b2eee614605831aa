//! Eight lanes in AVX2 registers: the lane type of the AVX2 batch clones.
//!
//! Written with `core::arch` intrinsics rather than as arrays so that LLVM
//! sees one vector value per operation (with arrays it sometimes vectorises
//! across corners instead, with gathers and scatters). Each operation is the
//! IEEE-754 operation the scalar `f32` path performs, lane by lane.
//!
//! The types are crate-private and only ever instantiated inside functions
//! compiled with `#[target_feature(enable = "avx2")]`
//! that the batch drivers call after detecting those features (`grid.rs`):
//! that is what makes the `unsafe` intrinsic calls below sound.

use super::{sealed::Sealed, BatchLanes, F32x8, IntLanes, Lanes, Table16, Table256};
use core::arch::x86_64::*;
use core::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

/// Eight `f32` lanes in a `ymm` register.
#[derive(Clone, Copy, Debug)]
pub(crate) struct X8(__m256);

/// Eight `i32` lanes in a `ymm` register.
#[derive(Clone, Copy, Debug)]
pub(crate) struct I8(__m256i);

/// Four vectors' low bytes in one `ymm` register ([`IntLanes::Bytes`]),
/// laid out as [`pack_bytes`] packs them.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Bytes32(__m256i);

/// Eight lane masks, each lane all ones (true) or all zeros (false).
#[derive(Clone, Copy, Debug)]
pub(crate) struct M8(__m256i);

impl Sealed for X8 {}
impl Sealed for I8 {}

impl X8 {
    #[inline(always)]
    fn to_array(self) -> [f32; 8] {
        let mut a = [0f32; 8];
        // SAFETY: AVX2 is enabled wherever X8 exists (module docs).
        unsafe { _mm256_storeu_ps(a.as_mut_ptr(), self.0) };
        a
    }
    #[inline(always)]
    fn from_array(a: [f32; 8]) -> Self {
        // SAFETY: as above.
        X8(unsafe { _mm256_loadu_ps(a.as_ptr()) })
    }
}

impl I8 {
    #[inline(always)]
    fn to_array(self) -> [i32; 8] {
        let mut a = [0i32; 8];
        // SAFETY: as above.
        unsafe { _mm256_storeu_si256(a.as_mut_ptr().cast(), self.0) };
        a
    }
    #[inline(always)]
    fn from_array(a: [i32; 8]) -> Self {
        // SAFETY: as above.
        I8(unsafe { _mm256_loadu_si256(a.as_ptr().cast()) })
    }
}

macro_rules! float_op {
    ($tr:ident, $f:ident, $intr:ident) => {
        impl $tr for X8 {
            type Output = X8;
            #[inline(always)]
            fn $f(self, o: X8) -> X8 {
                // SAFETY: AVX (module docs).
                X8(unsafe { $intr(self.0, o.0) })
            }
        }
    };
}
float_op!(Add, add, _mm256_add_ps);
float_op!(Sub, sub, _mm256_sub_ps);
float_op!(Mul, mul, _mm256_mul_ps);
float_op!(Div, div, _mm256_div_ps);

impl Neg for X8 {
    type Output = X8;
    #[inline(always)]
    fn neg(self) -> X8 {
        // SAFETY: AVX (module docs). Negation flips the sign bit.
        X8(unsafe { _mm256_xor_ps(self.0, _mm256_set1_ps(-0.0)) })
    }
}

impl BitAnd for M8 {
    type Output = M8;
    #[inline(always)]
    fn bitand(self, o: M8) -> M8 {
        // SAFETY: AVX2 (module docs).
        M8(unsafe { _mm256_and_si256(self.0, o.0) })
    }
}
impl BitOr for M8 {
    type Output = M8;
    #[inline(always)]
    fn bitor(self, o: M8) -> M8 {
        // SAFETY: AVX2 (module docs).
        M8(unsafe { _mm256_or_si256(self.0, o.0) })
    }
}
impl Not for M8 {
    type Output = M8;
    #[inline(always)]
    fn not(self) -> M8 {
        // SAFETY: AVX2 (module docs).
        M8(unsafe { _mm256_xor_si256(self.0, _mm256_set1_epi32(-1)) })
    }
}

// SAFETY (every `unsafe` block below): AVX2 is enabled
// wherever these types exist (module docs); loads and stores go through
// slices of at least sixteen elements, checked by indexing.
impl Lanes for X8 {
    type Elem = f32;
    type Int = I8;
    type Mask = M8;
    const WIDTH: usize = 8;

    #[inline(always)]
    fn splat(x: f32) -> Self {
        X8(unsafe { _mm256_set1_ps(x) })
    }
    #[inline(always)]
    fn from_slice(v: &[f32]) -> Self {
        let v = &v[..8];
        X8(unsafe { _mm256_loadu_ps(v.as_ptr()) })
    }
    #[inline(always)]
    fn lane(self, k: usize) -> f32 {
        self.to_array()[k]
    }
    #[inline(always)]
    fn floor(self) -> Self {
        // Round toward −∞, no precision exception: floorf lane by lane.
        X8(unsafe { _mm256_round_ps::<0x09>(self.0) })
    }
    #[inline(always)]
    fn abs(self) -> Self {
        X8(unsafe { _mm256_andnot_ps(_mm256_set1_ps(-0.0), self.0) })
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        X8(unsafe { _mm256_sqrt_ps(self.0) })
    }
    #[inline(always)]
    fn min(self, o: Self) -> Self {
        // minps(a, b) = a < b ? a : b, the scalar `if o < self { o } else { self }`.
        X8(unsafe { _mm256_min_ps(o.0, self.0) })
    }
    #[inline(always)]
    fn max(self, o: Self) -> Self {
        X8(unsafe { _mm256_max_ps(o.0, self.0) })
    }
    #[inline(always)]
    fn min_nonnegative(self, o: Self) -> Self {
        X8(unsafe { _mm256_castsi256_ps(_mm256_min_epi32(_mm256_castps_si256(self.0), _mm256_castps_si256(o.0))) })
    }
    #[inline(always)]
    fn max_nonnegative(self, o: Self) -> Self {
        X8(unsafe { _mm256_castsi256_ps(_mm256_max_epi32(_mm256_castps_si256(self.0), _mm256_castps_si256(o.0))) })
    }
    #[inline(always)]
    fn lt(self, o: Self) -> M8 {
        M8(unsafe { _mm256_castps_si256(_mm256_cmp_ps::<_CMP_LT_OQ>(self.0, o.0)) })
    }
    #[inline(always)]
    fn le(self, o: Self) -> M8 {
        M8(unsafe { _mm256_castps_si256(_mm256_cmp_ps::<_CMP_LE_OQ>(self.0, o.0)) })
    }
    #[inline(always)]
    fn select(m: M8, a: Self, b: Self) -> Self {
        X8(unsafe { _mm256_blendv_ps(b.0, a.0, _mm256_castsi256_ps(m.0)) })
    }
    #[inline(always)]
    fn any(m: M8) -> bool {
        unsafe { _mm256_movemask_ps(_mm256_castsi256_ps(m.0)) != 0 }
    }
    #[inline(always)]
    fn sample_dyn<const D: usize>(noise: &dyn crate::noise::DynNoise<D>, p: [Self; D]) -> Self {
        // (A loop, not `map`: a closure would not inherit the instruction
        // set, and the conversions would become calls.)
        let mut q = [F32x8::splat(0.0); D];
        for (qk, pk) in q.iter_mut().zip(p) {
            *qk = F32x8(pk.to_array());
        }
        X8::from_array(noise.sample_x8(q).0)
    }
    #[inline(always)]
    fn powf(self, e: Self) -> Self {
        let (a, b) = (self.to_array(), e.to_array());
        let mut out = [0f32; 8];
        for k in 0..8 {
            out[k] = libm::powf(a[k], b[k]);
        }
        X8::from_array(out)
    }
    #[inline(always)]
    fn to_int_wrapping(self) -> I8 {
        // Exact for |x| < 2³¹; other lanes (rare) take `as i64 as i32`.
        let t = unsafe { _mm256_cvttps_epi32(self.0) };
        let off =
            unsafe { _mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpeq_epi32(t, _mm256_set1_epi32(i32::MIN)))) };
        if off == 0 {
            return I8(t);
        }
        let (x, mut out) = (self.to_array(), I8(t).to_array());
        for k in 0..8 {
            out[k] = x[k] as i64 as i32;
        }
        I8::from_array(out)
    }
    #[inline(always)]
    fn floor_to_int(self) -> I8 {
        I8(unsafe { _mm256_cvttps_epi32(_mm256_floor_ps(self.0)) })
    }
    #[inline(always)]
    fn from_int(i: I8) -> Self {
        X8(unsafe { _mm256_cvtepi32_ps(i.0) })
    }
    #[inline(always)]
    fn lookup16(table: &Table16, idx: I8) -> Self {
        // Two eight-entry permutes, bit 3 picks.
        let table = table.single();
        unsafe {
            let lo = _mm256_permutevar8x32_ps(_mm256_loadu_ps(table.as_ptr()), idx.0);
            let hi = _mm256_permutevar8x32_ps(_mm256_loadu_ps(table[8..].as_ptr()), idx.0);
            X8(_mm256_blendv_ps(lo, hi, _mm256_castsi256_ps(_mm256_slli_epi32::<28>(idx.0))))
        }
    }
    #[inline(always)]
    fn lookup16_bytes<const T: usize>(bytes: Bytes32, floats: [&Table16; T]) -> [[Self; T]; 4] {
        if floats.iter().any(|f| f.halves().is_none()) {
            return super::lookup16_each(I8::from_bytes(bytes), floats);
        }
        let mut out = [[X8(unsafe { _mm256_setzero_ps() }); T]; 4];
        unsafe {
            let nibbles = _mm256_and_si256(bytes.0, _mm256_set1_epi8(15));
            for (t, f) in floats.iter().enumerate() {
                let Some([low, high]) = f.halves() else { continue };
                let low =
                    _mm256_shuffle_epi8(_mm256_broadcastsi128_si256(_mm_loadu_si128(low.as_ptr().cast())), nibbles);
                let high =
                    _mm256_shuffle_epi8(_mm256_broadcastsi128_si256(_mm_loadu_si128(high.as_ptr().cast())), nibbles);
                // Each entry's upper 16 bits as a word: vectors 0 and 1 in
                // the first, 2 and 3 in the second, each then moved to its
                // lanes' tops.
                let words = [_mm256_unpacklo_epi8(low, high), _mm256_unpackhi_epi8(low, high)];
                for (k, values) in out.iter_mut().enumerate() {
                    values[t] = X8(_mm256_castsi256_ps(_mm256_shuffle_epi8(words[k / 2], words_to_top(k % 2))));
                }
            }
        }
        out
    }
    #[inline(always)]
    fn lookup8(table: &[f32; 8], idx: I8) -> Self {
        // The permute reads the low three bits of each index.
        X8(unsafe { _mm256_permutevar8x32_ps(_mm256_loadu_ps(table.as_ptr()), idx.0) })
    }
    #[inline(always)]
    fn gather(table: &[f32], idx: I8) -> Self {
        let i = idx.to_array();
        let mut out = [0f32; 8];
        for k in 0..8 {
            out[k] = table[i[k] as usize];
        }
        X8::from_array(out)
    }
}

impl BatchLanes for X8 {
    const LEVEL: crate::grid::SimdLevel = crate::grid::SimdLevel::Avx2;
    #[inline(always)]
    fn store(self, out: &mut [f32]) {
        let out = &mut out[..8];
        unsafe { _mm256_storeu_ps(out.as_mut_ptr(), self.0) }
    }
    #[inline(always)]
    fn store_streamed(self, out: &mut [f32]) {
        let out = &mut out[..8];
        if out.as_ptr().addr().is_multiple_of(32) {
            // SAFETY: 8 entries in bounds, on a 32-byte boundary as the store requires.
            unsafe { _mm256_stream_ps(out.as_mut_ptr(), self.0) }
        } else {
            self.store(out);
        }
    }
    #[inline(always)]
    fn iota() -> I8 {
        I8(unsafe { _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7) })
    }
    #[inline(always)]
    fn store_int(v: I8, out: &mut [i32]) {
        let out = &mut out[..8];
        unsafe { _mm256_storeu_si256(out.as_mut_ptr().cast(), v.0) }
    }
    #[inline(always)]
    fn to_bits(self) -> I8 {
        I8(unsafe { _mm256_castps_si256(self.0) })
    }
    #[inline(always)]
    fn from_bits(i: I8) -> Self {
        X8(unsafe { _mm256_castsi256_ps(i.0) })
    }
    #[inline(always)]
    fn permute2(lo: Self, hi: Self, idx: I8) -> Self {
        // Two eight-entry permutes, bit 3 picks.
        unsafe {
            let a = _mm256_permutevar8x32_ps(lo.0, idx.0);
            let b = _mm256_permutevar8x32_ps(hi.0, idx.0);
            X8(_mm256_blendv_ps(a, b, _mm256_castsi256_ps(_mm256_slli_epi32::<28>(idx.0))))
        }
    }
    #[inline(always)]
    fn permute(v: Self, idx: I8) -> Self {
        X8(unsafe { _mm256_permutevar8x32_ps(v.0, idx.0) })
    }
    #[inline(always)]
    fn load_int(v: &[i32]) -> I8 {
        let v = &v[..8];
        I8(unsafe { _mm256_loadu_si256(v.as_ptr().cast()) })
    }
    #[inline(always)]
    fn load_u8(v: &[u8]) -> I8 {
        let v = &v[..8];
        I8(unsafe { _mm256_cvtepu8_epi32(_mm_loadl_epi64(v.as_ptr().cast())) })
    }
}

macro_rules! int_op {
    ($f:ident, $intr:ident) => {
        #[inline(always)]
        fn $f(self, o: Self) -> Self {
            I8(unsafe { $intr(self.0, o.0) })
        }
    };
}

impl IntLanes for I8 {
    type Mask = M8;
    #[inline(always)]
    fn splat(x: i32) -> Self {
        I8(unsafe { _mm256_set1_epi32(x) })
    }
    #[inline(always)]
    fn lane(self, k: usize) -> i32 {
        self.to_array()[k]
    }
    int_op!(add, _mm256_add_epi32);
    int_op!(sub, _mm256_sub_epi32);
    int_op!(mul, _mm256_mullo_epi32);
    int_op!(and, _mm256_and_si256);
    int_op!(or, _mm256_or_si256);
    int_op!(xor, _mm256_xor_si256);
    #[inline(always)]
    fn shl(self, s: u32) -> Self {
        if s >= 32 {
            return Self::splat(0);
        }
        I8(unsafe { _mm256_sll_epi32(self.0, _mm_cvtsi32_si128(s as i32)) })
    }
    #[inline(always)]
    fn shr(self, s: u32) -> Self {
        if s >= 32 {
            return Self::splat(0);
        }
        I8(unsafe { _mm256_srl_epi32(self.0, _mm_cvtsi32_si128(s as i32)) })
    }
    #[inline(always)]
    fn rem_euclid(self, m: i32) -> Self {
        let mut a = self.to_array();
        for v in a.iter_mut() {
            *v = v.rem_euclid(m);
        }
        I8::from_array(a)
    }
    #[inline(always)]
    fn eq(self, o: Self) -> M8 {
        M8(unsafe { _mm256_cmpeq_epi32(self.0, o.0) })
    }
    #[inline(always)]
    fn lt(self, o: Self) -> M8 {
        M8(unsafe { _mm256_cmpgt_epi32(o.0, self.0) })
    }
    #[inline(always)]
    fn select(m: M8, a: Self, b: Self) -> Self {
        I8(unsafe { _mm256_blendv_epi8(b.0, a.0, m.0) })
    }
    #[inline(always)]
    fn gather_u8(table: &[u8], idx: Self) -> Self {
        let i = idx.to_array();
        let mut out = [0i32; 8];
        for k in 0..8 {
            out[k] = table[i[k] as usize] as i32;
        }
        I8::from_array(out)
    }
    #[inline(always)]
    fn lookup256(table: &Table256, idx: Self) -> Self {
        let i = idx.to_array();
        let mut out = [0i32; 8];
        for k in 0..8 {
            out[k] = table.0[(i[k] & 255) as usize] as i32;
        }
        I8::from_array(out)
    }
    type Bytes = Bytes32;
    #[inline(always)]
    fn to_bytes(v: [Self; 4]) -> Bytes32 {
        Bytes32(pack_bytes(v))
    }
    #[inline(always)]
    fn from_bytes(b: Bytes32) -> [Self; 4] {
        unpack_bytes(b.0)
    }
    #[inline(always)]
    fn lookup_bytes(table: &Table256, b: Bytes32) -> Bytes32 {
        Bytes32(lookup_packed(table, b.0))
    }
    #[inline(always)]
    fn add_bytes(a: Bytes32, b: Bytes32) -> Bytes32 {
        Bytes32(unsafe { _mm256_add_epi8(a.0, b.0) })
    }
    #[inline(always)]
    fn pick_bytes(b: Bytes32, from: [usize; 4]) -> Bytes32 {
        // Byte i of vector k in each half is byte 4·from[k] + i there.
        let mut control = [0u8; 32];
        for (at, c) in control.iter_mut().enumerate() {
            let (k, i) = (at % 16 / 4, at % 4);
            *c = (4 * from[k] + i) as u8;
        }
        Bytes32(unsafe { _mm256_shuffle_epi8(b.0, _mm256_loadu_si256(control.as_ptr().cast())) })
    }
    #[inline(always)]
    fn lookup16(table: &[i32; 16], idx: Self) -> Self {
        // Two eight-entry permutes, bit 3 picks.
        unsafe {
            let lo = _mm256_permutevar8x32_epi32(_mm256_loadu_si256(table.as_ptr().cast()), idx.0);
            let hi = _mm256_permutevar8x32_epi32(_mm256_loadu_si256(table[8..].as_ptr().cast()), idx.0);
            let upper = _mm256_slli_epi32::<28>(idx.0);
            I8(_mm256_castps_si256(_mm256_blendv_ps(
                _mm256_castsi256_ps(lo),
                _mm256_castsi256_ps(hi),
                _mm256_castsi256_ps(upper),
            )))
        }
    }
    #[inline(always)]
    fn lookup32(table: &[i32; 32], idx: Self) -> Self {
        let (lo, hi) = (
            Self::lookup16(table[..16].try_into().unwrap(), idx),
            Self::lookup16(table[16..].try_into().unwrap(), idx),
        );
        // Bit 4 picks.
        let upper = unsafe { _mm256_slli_epi32::<27>(idx.0) };
        I8(unsafe {
            _mm256_castps_si256(_mm256_blendv_ps(
                _mm256_castsi256_ps(lo.0),
                _mm256_castsi256_ps(hi.0),
                _mm256_castsi256_ps(upper),
            ))
        })
    }
    #[inline(always)]
    fn gather_i32(table: &[i32], idx: Self) -> Self {
        let i = idx.to_array();
        let mut out = [0i32; 8];
        for k in 0..8 {
            out[k] = table[i[k] as usize];
        }
        I8::from_array(out)
    }
}

/// The low bytes of four vectors a, b, c, d in one register, in each
/// 128-bit half `a b c d` four lanes each: lanes 0–3 in the lower half,
/// 4–7 in the upper (the interleaving of the packs).
#[inline(always)]
fn pack_bytes(idx: [I8; 4]) -> __m256i {
    unsafe {
        let byte = _mm256_set1_epi32(255);
        // No `map`: its closure would not inherit AVX2.
        let [a, b, c, d] = idx;
        let (a, b) = (_mm256_and_si256(a.0, byte), _mm256_and_si256(b.0, byte));
        let (c, d) = (_mm256_and_si256(c.0, byte), _mm256_and_si256(d.0, byte));
        _mm256_packus_epi16(_mm256_packus_epi32(a, b), _mm256_packus_epi32(c, d))
    }
}

/// The four vectors of [`pack_bytes`]' layout, zero-extended.
#[inline(always)]
fn unpack_bytes(bytes: __m256i) -> [I8; 4] {
    unsafe {
        // Unpacking with zeros undoes the packs' interleaving.
        let zero = _mm256_setzero_si256();
        let (ab, cd) = (_mm256_unpacklo_epi8(bytes, zero), _mm256_unpackhi_epi8(bytes, zero));
        [
            I8(_mm256_unpacklo_epi16(ab, zero)),
            I8(_mm256_unpackhi_epi16(ab, zero)),
            I8(_mm256_unpacklo_epi16(cd, zero)),
            I8(_mm256_unpackhi_epi16(cd, zero)),
        ]
    }
}

/// `table[i]` for each of 32 bytes `i`. Sixteen byte shuffles, one per
/// sixteen-entry row of the table, each look up the low nibbles; a tree of
/// blends then picks the row by bits 4, 5, 6 and 7. About 50 operations
/// for 32 lookups (the rows' loads included; 60 with packing the indices
/// and unpacking the result), against four instructions and a
/// store-forwarding stall per lane with scalar loads (Zen 3's gathers
/// measured slower still: 3.6 ns for eight lanes).
#[inline(always)]
fn lookup_packed(table: &Table256, bytes: __m256i) -> __m256i {
    unsafe {
        let low = _mm256_and_si256(bytes, _mm256_set1_epi8(15));
        // `blendv` reads bit 7 of each byte: shift bit 4 (5, 6) there.
        let (bit4, bit5, bit6) =
            (_mm256_slli_epi16::<3>(bytes), _mm256_slli_epi16::<2>(bytes), _mm256_slli_epi16::<1>(bytes));
        let mut pairs = [_mm256_setzero_si256(); 8];
        // No closure for a row's shuffle: it would not inherit AVX2.
        for (rows, p) in table.0.chunks_exact(32).zip(pairs.iter_mut()) {
            let even = _mm256_shuffle_epi8(_mm256_broadcastsi128_si256(_mm_load_si128(rows.as_ptr().cast())), low);
            let odd = _mm256_shuffle_epi8(_mm256_broadcastsi128_si256(_mm_load_si128(rows[16..].as_ptr().cast())), low);
            *p = _mm256_blendv_epi8(even, odd, bit4);
        }
        let mut quads = [_mm256_setzero_si256(); 4];
        for (j, q) in quads.iter_mut().enumerate() {
            *q = _mm256_blendv_epi8(pairs[2 * j], pairs[2 * j + 1], bit5);
        }
        let lower = _mm256_blendv_epi8(quads[0], quads[1], bit6);
        let upper = _mm256_blendv_epi8(quads[2], quads[3], bit6);
        _mm256_blendv_epi8(lower, upper, bytes)
    }
}

/// Shuffle controls that move 16-bit word `4·j + i` of each 128-bit half
/// to the top of 32-bit lane `i` (zeros below): lanes of vector `j` of a
/// pair unpacked from [`pack_bytes`]' layout.
#[inline(always)]
fn words_to_top(j: usize) -> __m256i {
    const fn lane(j: usize, i: usize) -> i32 {
        let byte = (8 * j + 2 * i) as i32;
        0x8080 | byte << 16 | (byte + 1) << 24
    }
    let c = [lane(j, 0), lane(j, 1), lane(j, 2), lane(j, 3)];
    unsafe { _mm256_setr_epi32(c[0], c[1], c[2], c[3], c[0], c[1], c[2], c[3]) }
}
