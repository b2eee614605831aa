//! Sixteen lanes in AVX-512 registers: the lane type of the AVX-512 batch
//! clones.
//!
//! Written with `core::arch` intrinsics rather than as arrays so that LLVM
//! sees one vector value per operation (with arrays it sometimes vectorises
//! across corners instead, with gathers and scatters). Each operation is the
//! IEEE-754 operation the scalar `f32` path performs, lane by lane.
//!
//! The types are crate-private and only ever instantiated inside functions
//! compiled with `#[target_feature(enable = "avx512f,avx512bw,avx512dq,avx512vl,avx512vbmi")]`
//! that the batch drivers call after detecting those features (`grid.rs`):
//! that is what makes the `unsafe` intrinsic calls below sound.

use super::{sealed::Sealed, BatchLanes, F32x16, IntLanes, Lanes, Table16, Table256};
use core::arch::x86_64::*;
use core::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

/// Sixteen `f32` lanes in a `zmm` register.
#[derive(Clone, Copy, Debug)]
pub(crate) struct X16(__m512);

/// Sixteen `i32` lanes in a `zmm` register.
#[derive(Clone, Copy, Debug)]
pub(crate) struct I16(__m512i);

/// Four vectors' low bytes in one `zmm` register ([`IntLanes::Bytes`]):
/// vector `k`'s sixteen lanes in bytes `16k..16k + 16`, in order. A hash
/// chain's link is then one lookup for all four vectors, with no narrowing
/// and widening around it (random 3D points 3.64 → 3.01 ns in the probe).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Bytes64(__m512i);

/// Sixteen lane masks in a mask register.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct M16(__mmask16);

impl Sealed for X16 {}
impl Sealed for I16 {}

impl X16 {
    #[inline(always)]
    fn to_array(self) -> [f32; 16] {
        let mut a = [0f32; 16];
        // SAFETY: AVX-512F is enabled wherever X16 exists (module docs).
        unsafe { _mm512_storeu_ps(a.as_mut_ptr(), self.0) };
        a
    }
    #[inline(always)]
    fn from_array(a: [f32; 16]) -> Self {
        // SAFETY: as above.
        X16(unsafe { _mm512_loadu_ps(a.as_ptr()) })
    }
}

impl I16 {
    #[inline(always)]
    fn to_array(self) -> [i32; 16] {
        let mut a = [0i32; 16];
        // SAFETY: as above.
        unsafe { _mm512_storeu_si512(a.as_mut_ptr().cast(), self.0) };
        a
    }
    #[inline(always)]
    fn from_array(a: [i32; 16]) -> Self {
        // SAFETY: as above.
        I16(unsafe { _mm512_loadu_si512(a.as_ptr().cast()) })
    }
}

macro_rules! float_op {
    ($tr:ident, $f:ident, $intr:ident) => {
        impl $tr for X16 {
            type Output = X16;
            #[inline(always)]
            fn $f(self, o: X16) -> X16 {
                // SAFETY: AVX-512F (module docs).
                X16(unsafe { $intr(self.0, o.0) })
            }
        }
    };
}
float_op!(Add, add, _mm512_add_ps);
float_op!(Sub, sub, _mm512_sub_ps);
float_op!(Mul, mul, _mm512_mul_ps);
float_op!(Div, div, _mm512_div_ps);

impl Neg for X16 {
    type Output = X16;
    #[inline(always)]
    fn neg(self) -> X16 {
        // SAFETY: AVX-512F/DQ (module docs). Negation flips the sign bit.
        X16(unsafe { _mm512_xor_ps(self.0, _mm512_set1_ps(-0.0)) })
    }
}

impl BitAnd for M16 {
    type Output = M16;
    #[inline(always)]
    fn bitand(self, o: M16) -> M16 {
        M16(self.0 & o.0)
    }
}
impl BitOr for M16 {
    type Output = M16;
    #[inline(always)]
    fn bitor(self, o: M16) -> M16 {
        M16(self.0 | o.0)
    }
}
impl Not for M16 {
    type Output = M16;
    #[inline(always)]
    fn not(self) -> M16 {
        M16(!self.0)
    }
}

// SAFETY (every `unsafe` block below): AVX-512 F/BW/DQ/VL/VBMI are enabled
// wherever these types exist (module docs); loads and stores go through
// slices of at least sixteen elements, checked by indexing.
impl Lanes for X16 {
    type Elem = f32;
    type Int = I16;
    type Mask = M16;
    const WIDTH: usize = 16;

    #[inline(always)]
    fn splat(x: f32) -> Self {
        X16(unsafe { _mm512_set1_ps(x) })
    }
    #[inline(always)]
    fn from_slice(v: &[f32]) -> Self {
        let v = &v[..16];
        X16(unsafe { _mm512_loadu_ps(v.as_ptr()) })
    }
    #[inline(always)]
    fn lane(self, k: usize) -> f32 {
        self.to_array()[k]
    }
    #[inline(always)]
    fn floor(self) -> Self {
        // Round toward −∞, no precision exception: floorf lane by lane.
        X16(unsafe { _mm512_roundscale_ps::<0x09>(self.0) })
    }
    #[inline(always)]
    fn abs(self) -> Self {
        X16(unsafe { _mm512_andnot_ps(_mm512_set1_ps(-0.0), self.0) })
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        X16(unsafe { _mm512_sqrt_ps(self.0) })
    }
    #[inline(always)]
    fn min(self, o: Self) -> Self {
        // minps(a, b) = a < b ? a : b, the scalar `if o < self { o } else { self }`.
        X16(unsafe { _mm512_min_ps(o.0, self.0) })
    }
    #[inline(always)]
    fn max(self, o: Self) -> Self {
        X16(unsafe { _mm512_max_ps(o.0, self.0) })
    }
    #[inline(always)]
    fn min_nonnegative(self, o: Self) -> Self {
        X16(unsafe { _mm512_castsi512_ps(_mm512_min_epi32(_mm512_castps_si512(self.0), _mm512_castps_si512(o.0))) })
    }
    #[inline(always)]
    fn max_nonnegative(self, o: Self) -> Self {
        X16(unsafe { _mm512_castsi512_ps(_mm512_max_epi32(_mm512_castps_si512(self.0), _mm512_castps_si512(o.0))) })
    }
    #[inline(always)]
    fn lt(self, o: Self) -> M16 {
        M16(unsafe { _mm512_cmp_ps_mask::<_CMP_LT_OQ>(self.0, o.0) })
    }
    #[inline(always)]
    fn le(self, o: Self) -> M16 {
        M16(unsafe { _mm512_cmp_ps_mask::<_CMP_LE_OQ>(self.0, o.0) })
    }
    #[inline(always)]
    fn select(m: M16, a: Self, b: Self) -> Self {
        X16(unsafe { _mm512_mask_blend_ps(m.0, b.0, a.0) })
    }
    #[inline(always)]
    fn any(m: M16) -> bool {
        m.0 != 0
    }
    #[inline(always)]
    fn sample_dyn<const D: usize>(noise: &dyn crate::noise::DynNoise<D>, p: [Self; D]) -> Self {
        // (A loop, not `map`: see `lookup256`.)
        let mut q = [F32x16::splat(0.0); D];
        for (qk, pk) in q.iter_mut().zip(p) {
            *qk = F32x16(pk.to_array());
        }
        X16::from_array(noise.sample_x16(q).0)
    }
    #[inline(always)]
    fn powf(self, e: Self) -> Self {
        let (a, b) = (self.to_array(), e.to_array());
        let mut out = [0f32; 16];
        for k in 0..16 {
            out[k] = libm::powf(a[k], b[k]);
        }
        X16::from_array(out)
    }
    #[inline(always)]
    fn to_int_wrapping(self) -> I16 {
        // Exact for |x| < 2³¹; other lanes (rare) take `as i64 as i32`.
        let t = unsafe { _mm512_cvttps_epi32(self.0) };
        let off = unsafe { _mm512_cmpeq_epi32_mask(t, _mm512_set1_epi32(i32::MIN)) };
        if off == 0 {
            return I16(t);
        }
        let (x, mut out) = (self.to_array(), I16(t).to_array());
        for k in 0..16 {
            out[k] = x[k] as i64 as i32;
        }
        I16::from_array(out)
    }
    #[inline(always)]
    fn floor_to_int(self) -> I16 {
        I16(unsafe { _mm512_cvt_roundps_epi32::<{ _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC }>(self.0) })
    }
    #[inline(always)]
    fn from_int(i: I16) -> Self {
        X16(unsafe { _mm512_cvtepi32_ps(i.0) })
    }
    #[inline(always)]
    fn lookup16(table: &Table16, idx: I16) -> Self {
        X16(unsafe { _mm512_permutexvar_ps(idx.0, _mm512_loadu_ps(table.single().as_ptr())) })
    }
    #[inline(always)]
    fn lookup16_bytes<const T: usize>(bytes: Bytes64, floats: [&Table16; T]) -> [[Self; T]; 4] {
        // `from_bytes` without its zeroing: the permutes read only each
        // index's low four bits (LLVM makes the zeroing an AND a vector).
        let mut out = [[X16::splat(0.0); T]; 4];
        for (values, control) in out.iter_mut().zip(&UNPACK) {
            let idx = I16(unsafe { _mm512_permutexvar_epi8(_mm512_loadu_si512(control.as_ptr().cast()), bytes.0) });
            for (v, table) in values.iter_mut().zip(floats) {
                *v = X16::lookup16(table, idx);
            }
        }
        out
    }
    #[inline(always)]
    fn lookup8(table: &[f32; 8], idx: I16) -> Self {
        // The table twice over: entry `idx & 15` is entry `idx & 7`.
        X16(unsafe { _mm512_permutexvar_ps(idx.0, _mm512_broadcast_f32x8(_mm256_loadu_ps(table.as_ptr()))) })
    }
    #[inline(always)]
    fn gather(table: &[f32], idx: I16) -> Self {
        let i = idx.to_array();
        let mut out = [0f32; 16];
        for k in 0..16 {
            out[k] = table[i[k] as usize];
        }
        X16::from_array(out)
    }
}

impl BatchLanes for X16 {
    const LEVEL: crate::grid::SimdLevel = crate::grid::SimdLevel::Avx512;
    #[inline(always)]
    fn store(self, out: &mut [f32]) {
        let out = &mut out[..16];
        unsafe { _mm512_storeu_ps(out.as_mut_ptr(), self.0) }
    }
    #[inline(always)]
    fn store_streamed(self, out: &mut [f32]) {
        let out = &mut out[..16];
        if out.as_ptr().addr().is_multiple_of(64) {
            // SAFETY: 16 entries in bounds, on a 64-byte boundary as the store requires.
            unsafe { _mm512_stream_ps(out.as_mut_ptr(), self.0) }
        } else {
            self.store(out);
        }
    }
    #[inline(always)]
    fn iota() -> I16 {
        I16(unsafe { _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15) })
    }
    #[inline(always)]
    fn grid_coords(origin: f64, step: f64, first: i32) -> Self {
        // Two halves of eight in f64 (exact conversions, then the scalar's
        // multiply, add and rounding), joined into one register.
        unsafe {
            let i = _mm512_add_epi32(_mm512_set1_epi32(first), Self::iota().0);
            let (o, s) = (_mm512_set1_pd(origin), _mm512_set1_pd(step));
            let lo = _mm512_cvtpd_ps(_mm512_add_pd(o, _mm512_mul_pd(_mm512_cvtepi32_pd(_mm512_castsi512_si256(i)), s)));
            let hi = _mm512_cvtpd_ps(_mm512_add_pd(
                o,
                _mm512_mul_pd(_mm512_cvtepi32_pd(_mm512_extracti64x4_epi64::<1>(i)), s),
            ));
            X16(_mm512_castpd_ps(_mm512_insertf64x4::<1>(
                _mm512_castpd256_pd512(_mm256_castps_pd(lo)),
                _mm256_castps_pd(hi),
            )))
        }
    }
    #[inline(always)]
    fn store_int(v: I16, out: &mut [i32]) {
        let out = &mut out[..16];
        unsafe { _mm512_storeu_si512(out.as_mut_ptr().cast(), v.0) }
    }
    #[inline(always)]
    fn to_bits(self) -> I16 {
        I16(unsafe { _mm512_castps_si512(self.0) })
    }
    #[inline(always)]
    fn from_bits(i: I16) -> Self {
        X16(unsafe { _mm512_castsi512_ps(i.0) })
    }
    #[inline(always)]
    fn permute2(lo: Self, hi: Self, idx: I16) -> Self {
        X16(unsafe { _mm512_permutex2var_ps(lo.0, idx.0, hi.0) })
    }
    #[inline(always)]
    fn permute(v: Self, idx: I16) -> Self {
        X16(unsafe { _mm512_permutexvar_ps(idx.0, v.0) })
    }
    #[inline(always)]
    fn load_int(v: &[i32]) -> I16 {
        let v = &v[..16];
        I16(unsafe { _mm512_loadu_si512(v.as_ptr().cast()) })
    }
    #[inline(always)]
    fn load_u8(v: &[u8]) -> I16 {
        let v = &v[..16];
        I16(unsafe { _mm512_cvtepu8_epi32(_mm_loadu_si128(v.as_ptr().cast())) })
    }
}

macro_rules! int_op {
    ($f:ident, $intr:ident) => {
        #[inline(always)]
        fn $f(self, o: Self) -> Self {
            I16(unsafe { $intr(self.0, o.0) })
        }
    };
}

impl IntLanes for I16 {
    type Mask = M16;
    type Bytes = Bytes64;
    #[inline(always)]
    fn to_bytes(v: [Self; 4]) -> Bytes64 {
        // Two two-register byte permutes gather the low bytes of a and b,
        // c and d; the second pair's 32 go above the first's.
        let [a, b, c, d] = v;
        unsafe {
            let control = _mm512_loadu_si512(PACK_TWO.as_ptr().cast());
            let ab = _mm512_permutex2var_epi8(a.0, control, b.0);
            let cd = _mm512_permutex2var_epi8(c.0, control, d.0);
            Bytes64(_mm512_inserti64x4::<1>(ab, _mm512_castsi512_si256(cd)))
        }
    }
    #[inline(always)]
    fn from_bytes(b: Bytes64) -> [Self; 4] {
        // Byte 4i of vector k is byte 16k + i; the other three are zeroed.
        let mut out = [Self::splat(0); 4];
        for (v, control) in out.iter_mut().zip(&UNPACK) {
            *v = I16(unsafe {
                _mm512_maskz_permutexvar_epi8(0x1111_1111_1111_1111, _mm512_loadu_si512(control.as_ptr().cast()), b.0)
            });
        }
        out
    }
    #[inline(always)]
    fn lookup_bytes(table: &Table256, b: Bytes64) -> Bytes64 {
        Bytes64(lookup_packed(table, b.0))
    }
    #[inline(always)]
    fn add_bytes(a: Bytes64, b: Bytes64) -> Bytes64 {
        Bytes64(unsafe { _mm512_add_epi8(a.0, b.0) })
    }
    #[inline(always)]
    fn pick_bytes(b: Bytes64, from: [usize; 4]) -> Bytes64 {
        // Whole 128-bit quarters: dword 4k + i is dword 4·from[k] + i.
        let mut control = [0i32; 16];
        for (at, c) in control.iter_mut().enumerate() {
            *c = (4 * from[at / 4] + at % 4) as i32;
        }
        Bytes64(unsafe { _mm512_permutexvar_epi32(_mm512_loadu_si512(control.as_ptr().cast()), b.0) })
    }
    #[inline(always)]
    fn splat(x: i32) -> Self {
        I16(unsafe { _mm512_set1_epi32(x) })
    }
    #[inline(always)]
    fn lane(self, k: usize) -> i32 {
        self.to_array()[k]
    }
    int_op!(add, _mm512_add_epi32);
    int_op!(sub, _mm512_sub_epi32);
    int_op!(mul, _mm512_mullo_epi32);
    int_op!(and, _mm512_and_si512);
    int_op!(or, _mm512_or_si512);
    int_op!(xor, _mm512_xor_si512);
    #[inline(always)]
    fn shl(self, s: u32) -> Self {
        if s >= 32 {
            return Self::splat(0);
        }
        I16(unsafe { _mm512_sll_epi32(self.0, _mm_cvtsi32_si128(s as i32)) })
    }
    #[inline(always)]
    fn shr(self, s: u32) -> Self {
        if s >= 32 {
            return Self::splat(0);
        }
        I16(unsafe { _mm512_srl_epi32(self.0, _mm_cvtsi32_si128(s as i32)) })
    }
    #[inline(always)]
    fn rem_euclid(self, m: i32) -> Self {
        let mut a = self.to_array();
        for v in a.iter_mut() {
            *v = v.rem_euclid(m);
        }
        I16::from_array(a)
    }
    #[inline(always)]
    fn eq(self, o: Self) -> M16 {
        M16(unsafe { _mm512_cmpeq_epi32_mask(self.0, o.0) })
    }
    #[inline(always)]
    fn lt(self, o: Self) -> M16 {
        M16(unsafe { _mm512_cmplt_epi32_mask(self.0, o.0) })
    }
    #[inline(always)]
    fn select(m: M16, a: Self, b: Self) -> Self {
        I16(unsafe { _mm512_mask_blend_epi32(m.0, b.0, a.0) })
    }
    #[inline(always)]
    fn gather_u8(table: &[u8], idx: Self) -> Self {
        let i = idx.to_array();
        let mut out = [0i32; 16];
        for k in 0..16 {
            out[k] = table[i[k] as usize] as i32;
        }
        I16::from_array(out)
    }
    #[inline(always)]
    fn lookup256(table: &Table256, idx: Self) -> Self {
        let bytes = unsafe { _mm512_castsi128_si512(_mm512_cvtepi32_epi8(idx.0)) };
        I16(unsafe { _mm512_cvtepu8_epi32(_mm512_castsi512_si128(lookup_packed(table, bytes))) })
    }
    #[inline(always)]
    fn lookup16(table: &[i32; 16], idx: Self) -> Self {
        I16(unsafe { _mm512_permutexvar_epi32(idx.0, _mm512_loadu_si512(table.as_ptr().cast())) })
    }
    #[inline(always)]
    fn lookup32(table: &[i32; 32], idx: Self) -> Self {
        unsafe {
            let (lo, hi) = (_mm512_loadu_si512(table.as_ptr().cast()), _mm512_loadu_si512(table[16..].as_ptr().cast()));
            I16(_mm512_permutex2var_epi32(lo, idx.0, hi))
        }
    }
    #[inline(always)]
    fn gather_i32(table: &[i32], idx: Self) -> Self {
        let i = idx.to_array();
        let mut out = [0i32; 16];
        for k in 0..16 {
            out[k] = table[i[k] as usize];
        }
        I16::from_array(out)
    }
}

/// `table[i]` for each of 64 bytes `i`: the bytes select from four 64-byte
/// registers, two two-register byte permutes covering entries 0..128 and
/// 128..256, bit 7 picking between them (four operations for 64 lookups).
#[inline(always)]
fn lookup_packed(table: &Table256, bytes: __m512i) -> __m512i {
    let t = &table.0;
    unsafe {
        // Four loads, not a `map`: a closure would not inherit the
        // instruction set (see `kinds::fast`, where one cost 9x).
        let t0 = _mm512_loadu_si512(t[0..64].as_ptr().cast());
        let t1 = _mm512_loadu_si512(t[64..128].as_ptr().cast());
        let t2 = _mm512_loadu_si512(t[128..192].as_ptr().cast());
        let t3 = _mm512_loadu_si512(t[192..256].as_ptr().cast());
        let low = _mm512_permutex2var_epi8(t0, bytes, t1);
        let high = _mm512_permutex2var_epi8(t2, bytes, t3);
        _mm512_mask_blend_epi8(_mm512_movepi8_mask(bytes), low, high)
    }
}

/// [`IntLanes::to_bytes`]' control: bytes 0..16 read the low byte of each
/// dword of the first register, 16..32 of the second (index bit 6).
const PACK_TWO: [u8; 64] = {
    let mut c = [0u8; 64];
    let mut at = 0;
    while at < 32 {
        c[at] = (4 * (at % 16) + 64 * (at / 16)) as u8;
        at += 1;
    }
    c
};

/// [`IntLanes::from_bytes`]' controls: byte 4i of vector k reads byte
/// 16k + i (the others are masked to zero).
const UNPACK: [[u8; 64]; 4] = {
    let mut c = [[0u8; 64]; 4];
    let mut k = 0;
    while k < 4 {
        let mut at = 0;
        while at < 64 {
            c[k][at] = (16 * k + at / 4) as u8;
            at += 1;
        }
        k += 1;
    }
    c
};
