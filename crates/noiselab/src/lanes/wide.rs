//! Eight and sixteen `f32` lanes: the batch API's lane types.
//!
//! Plain arrays with `#[inline(always)]` element-wise operations. LLVM turns
//! each into vector instructions for whatever instruction set the calling
//! function is compiled for (SSE2 by default, AVX2 or AVX-512 inside the
//! batch driver's `#[target_feature]` clones), and every operation is the same
//! IEEE-754 operation as the scalar `f32` one, so results are identical.
//! [`F32x16`] fills one AVX-512 register; [`F32x8`] one AVX2 register.

use super::{math, sealed::Sealed, BatchLanes, IntLanes, Lanes, Table16, Table256};
use core::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

#[inline(always)]
fn mask(b: bool) -> i32 {
    -(b as i32)
}

macro_rules! wide_lanes {
    ($n:literal, $f:ident, $i:ident, $m:ident, $align:literal, $dyn:ident, $doc:literal) => {
        #[doc = concat!($doc, " `f32` lanes.")]
        #[derive(Clone, Copy, Debug, PartialEq)]
        #[repr(C, align($align))]
        pub struct $f(pub [f32; $n]);

        #[doc = concat!($doc, " `i32` lanes with wrapping arithmetic.")]
        #[derive(Clone, Copy, Debug, PartialEq, Eq)]
        #[repr(C, align($align))]
        pub struct $i(pub [i32; $n]);

        #[doc = concat!($doc, " lane masks, each all ones (true) or all zeros (false).")]
        #[derive(Clone, Copy, Debug, PartialEq, Eq)]
        #[repr(C, align($align))]
        pub struct $m(pub [i32; $n]);

        impl Sealed for $f {}
        impl Sealed for $i {}

        // Plain loops rather than `array::from_fn`, which LLVM does not
        // always inline.
        impl $f {
            #[inline(always)]
            fn map(self, f: impl Fn(f32) -> f32) -> Self {
                let mut out = [0f32; $n];
                for k in 0..$n {
                    out[k] = f(self.0[k]);
                }
                $f(out)
            }
            #[inline(always)]
            fn zip(self, o: Self, f: impl Fn(f32, f32) -> f32) -> Self {
                let mut out = [0f32; $n];
                for k in 0..$n {
                    out[k] = f(self.0[k], o.0[k]);
                }
                $f(out)
            }
            #[inline(always)]
            fn test(self, o: Self, f: impl Fn(f32, f32) -> bool) -> $m {
                let mut out = [0i32; $n];
                for k in 0..$n {
                    out[k] = mask(f(self.0[k], o.0[k]));
                }
                $m(out)
            }
        }

        impl $i {
            #[inline(always)]
            fn zip(self, o: Self, f: impl Fn(i32, i32) -> i32) -> Self {
                let mut out = [0i32; $n];
                for k in 0..$n {
                    out[k] = f(self.0[k], o.0[k]);
                }
                $i(out)
            }
            #[inline(always)]
            fn map(self, f: impl Fn(i32) -> i32) -> Self {
                let mut out = [0i32; $n];
                for k in 0..$n {
                    out[k] = f(self.0[k]);
                }
                $i(out)
            }
        }

        impl $m {
            #[inline(always)]
            fn zip(self, o: Self, f: impl Fn(i32, i32) -> i32) -> Self {
                let mut out = [0i32; $n];
                for k in 0..$n {
                    out[k] = f(self.0[k], o.0[k]);
                }
                $m(out)
            }
        }

        impl Add for $f {
            type Output = $f;
            #[inline(always)]
            fn add(self, o: $f) -> $f {
                self.zip(o, |a, b| a + b)
            }
        }
        impl Sub for $f {
            type Output = $f;
            #[inline(always)]
            fn sub(self, o: $f) -> $f {
                self.zip(o, |a, b| a - b)
            }
        }
        impl Mul for $f {
            type Output = $f;
            #[inline(always)]
            fn mul(self, o: $f) -> $f {
                self.zip(o, |a, b| a * b)
            }
        }
        impl Div for $f {
            type Output = $f;
            #[inline(always)]
            fn div(self, o: $f) -> $f {
                self.zip(o, |a, b| a / b)
            }
        }
        impl Neg for $f {
            type Output = $f;
            #[inline(always)]
            fn neg(self) -> $f {
                self.map(|a| -a)
            }
        }

        impl BitAnd for $m {
            type Output = $m;
            #[inline(always)]
            fn bitand(self, o: $m) -> $m {
                self.zip(o, |a, b| a & b)
            }
        }
        impl BitOr for $m {
            type Output = $m;
            #[inline(always)]
            fn bitor(self, o: $m) -> $m {
                self.zip(o, |a, b| a | b)
            }
        }
        impl Not for $m {
            type Output = $m;
            #[inline(always)]
            fn not(self) -> $m {
                self.zip(self, |a, _| !a)
            }
        }

        impl Lanes for $f {
            type Elem = f32;
            type Int = $i;
            type Mask = $m;
            const WIDTH: usize = $n;

            #[inline(always)]
            fn splat(x: f32) -> Self {
                $f([x; $n])
            }
            #[inline(always)]
            fn from_slice(v: &[f32]) -> Self {
                let mut out = [0f32; $n];
                out.copy_from_slice(&v[..$n]);
                $f(out)
            }
            #[inline(always)]
            fn lane(self, k: usize) -> f32 {
                self.0[k]
            }
            #[inline(always)]
            fn floor(self) -> Self {
                self.map(math::floor32)
            }
            #[inline(always)]
            fn abs(self) -> Self {
                self.map(f32::abs)
            }
            #[inline(always)]
            fn sqrt(self) -> Self {
                self.map(math::sqrt32)
            }
            #[inline(always)]
            fn min(self, o: Self) -> Self {
                self.zip(o, |a, b| if b < a { b } else { a })
            }
            #[inline(always)]
            fn max(self, o: Self) -> Self {
                self.zip(o, |a, b| if b > a { b } else { a })
            }
            #[inline(always)]
            fn lt(self, o: Self) -> $m {
                self.test(o, |a, b| a < b)
            }
            #[inline(always)]
            fn le(self, o: Self) -> $m {
                self.test(o, |a, b| a <= b)
            }
            #[inline(always)]
            fn any(m: $m) -> bool {
                m.0.iter().any(|&v| v != 0)
            }
            #[inline(always)]
            fn powf(self, e: Self) -> Self {
                self.zip(e, libm::powf)
            }
            #[inline(always)]
            fn sample_dyn<const D: usize>(noise: &dyn crate::noise::DynNoise<D>, p: [Self; D]) -> Self {
                noise.$dyn(p)
            }
            #[inline(always)]
            fn select(m: $m, a: Self, b: Self) -> Self {
                // Bitwise blend: the form LLVM maps to one blend instruction.
                let mut out = [0f32; $n];
                for k in 0..$n {
                    out[k] = f32::from_bits((a.0[k].to_bits() & m.0[k] as u32) | (b.0[k].to_bits() & !m.0[k] as u32));
                }
                $f(out)
            }
            #[inline(always)]
            fn to_int_wrapping(self) -> $i {
                let mut out = [0i32; $n];
                for k in 0..$n {
                    out[k] = self.0[k] as i64 as i32;
                }
                $i(out)
            }
            #[inline(always)]
            fn from_int(v: $i) -> Self {
                let mut out = [0f32; $n];
                for k in 0..$n {
                    out[k] = v.0[k] as f32;
                }
                $f(out)
            }
            #[inline(always)]
            fn lookup16(table: &Table16, idx: $i) -> Self {
                Self::gather(table.single(), idx.and_c(15))
            }
            #[inline(always)]
            fn lookup8(table: &[f32; 8], idx: $i) -> Self {
                Self::gather(table, idx.and_c(7))
            }
            #[inline(always)]
            fn gather(table: &[f32], idx: $i) -> Self {
                let mut out = [0f32; $n];
                for k in 0..$n {
                    out[k] = table[idx.0[k] as usize];
                }
                $f(out)
            }
        }

        impl BatchLanes for $f {
            const LEVEL: crate::grid::SimdLevel = crate::grid::SimdLevel::Baseline;
            #[inline(always)]
            fn store(self, out: &mut [f32]) {
                out[..$n].copy_from_slice(&self.0);
            }
            #[inline(always)]
            fn store_streamed(self, out: &mut [f32]) {
                let out = &mut out[..$n];
                // SSE2's four-lane streaming store, which every x86_64 CPU has.
                #[cfg(target_arch = "x86_64")]
                if out.as_ptr().addr().is_multiple_of(16) {
                    use core::arch::x86_64::{_mm_loadu_ps, _mm_stream_ps};
                    for k in (0..$n).step_by(4) {
                        // SAFETY: entries k..k + 4 are in bounds of both, and
                        // `out`'s on a 16-byte boundary as the store requires.
                        unsafe { _mm_stream_ps(out.as_mut_ptr().add(k), _mm_loadu_ps(self.0.as_ptr().add(k))) }
                    }
                    return;
                }
                out.copy_from_slice(&self.0);
            }
            #[inline(always)]
            fn iota() -> $i {
                let mut out = [0i32; $n];
                for k in 0..$n {
                    out[k] = k as i32;
                }
                $i(out)
            }
            #[inline(always)]
            fn store_int(v: $i, out: &mut [i32]) {
                out[..$n].copy_from_slice(&v.0);
            }
            #[inline(always)]
            fn to_bits(self) -> $i {
                let mut out = [0i32; $n];
                for k in 0..$n {
                    out[k] = self.0[k].to_bits() as i32;
                }
                $i(out)
            }
            #[inline(always)]
            fn from_bits(v: $i) -> Self {
                let mut out = [0f32; $n];
                for k in 0..$n {
                    out[k] = f32::from_bits(v.0[k] as u32);
                }
                $f(out)
            }
            #[inline(always)]
            fn permute2(lo: Self, hi: Self, idx: $i) -> Self {
                let mut out = [0f32; $n];
                for k in 0..$n {
                    let j = (idx.0[k] as usize) & (2 * $n - 1);
                    out[k] = if j < $n { lo.0[j] } else { hi.0[j - $n] };
                }
                $f(out)
            }
            #[inline(always)]
            fn permute(v: Self, idx: $i) -> Self {
                let mut out = [0f32; $n];
                for k in 0..$n {
                    out[k] = v.0[(idx.0[k] as usize) & ($n - 1)];
                }
                $f(out)
            }
            #[inline(always)]
            fn load_int(v: &[i32]) -> $i {
                let mut out = [0i32; $n];
                out.copy_from_slice(&v[..$n]);
                $i(out)
            }
            #[inline(always)]
            fn load_u8(v: &[u8]) -> $i {
                let mut out = [0i32; $n];
                for (o, &b) in out.iter_mut().zip(&v[..$n]) {
                    *o = b as i32;
                }
                $i(out)
            }
        }

        impl IntLanes for $i {
            type Mask = $m;
            bytes_as_vectors!();
            #[inline(always)]
            fn splat(x: i32) -> Self {
                $i([x; $n])
            }
            #[inline(always)]
            fn lane(self, k: usize) -> i32 {
                self.0[k]
            }
            #[inline(always)]
            fn add(self, o: Self) -> Self {
                self.zip(o, i32::wrapping_add)
            }
            #[inline(always)]
            fn sub(self, o: Self) -> Self {
                self.zip(o, i32::wrapping_sub)
            }
            #[inline(always)]
            fn mul(self, o: Self) -> Self {
                self.zip(o, i32::wrapping_mul)
            }
            #[inline(always)]
            fn and(self, o: Self) -> Self {
                self.zip(o, |a, b| a & b)
            }
            #[inline(always)]
            fn or(self, o: Self) -> Self {
                self.zip(o, |a, b| a | b)
            }
            #[inline(always)]
            fn xor(self, o: Self) -> Self {
                self.zip(o, |a, b| a ^ b)
            }
            #[inline(always)]
            fn shl(self, s: u32) -> Self {
                self.map(|a| a.wrapping_shl(s))
            }
            #[inline(always)]
            fn shr(self, s: u32) -> Self {
                self.map(|a| (a as u32).wrapping_shr(s) as i32)
            }
            #[inline(always)]
            fn rem_euclid(self, m: i32) -> Self {
                self.map(|a| a.rem_euclid(m))
            }
            #[inline(always)]
            fn eq(self, o: Self) -> $m {
                $m(self.zip(o, |a, b| mask(a == b)).0)
            }
            #[inline(always)]
            fn lt(self, o: Self) -> $m {
                $m(self.zip(o, |a, b| mask(a < b)).0)
            }
            #[inline(always)]
            fn select(m: $m, a: Self, b: Self) -> Self {
                let mut out = [0i32; $n];
                for k in 0..$n {
                    out[k] = (a.0[k] & m.0[k]) | (b.0[k] & !m.0[k]);
                }
                $i(out)
            }
            #[inline(always)]
            fn gather_u8(table: &[u8], idx: Self) -> Self {
                idx.map(|i| table[i as usize] as i32)
            }
            #[inline(always)]
            fn gather_i32(table: &[i32], idx: Self) -> Self {
                idx.map(|i| table[i as usize])
            }
            #[inline(always)]
            fn lookup256(table: &Table256, idx: Self) -> Self {
                idx.map(|i| table.0[(i & 255) as usize] as i32)
            }
            #[inline(always)]
            fn lookup16(table: &[i32; 16], idx: Self) -> Self {
                idx.map(|i| table[(i & 15) as usize])
            }
            #[inline(always)]
            fn lookup32(table: &[i32; 32], idx: Self) -> Self {
                idx.map(|i| table[(i & 31) as usize])
            }
        }
    };
}

wide_lanes!(8, F32x8, I32x8, M32x8, 32, sample_x8, "Eight");
wide_lanes!(16, F32x16, I32x16, M32x16, 64, sample_x16, "Sixteen");
