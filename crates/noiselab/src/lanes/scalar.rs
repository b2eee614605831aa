//! `f32` and `f64` as one-lane [`Lanes`], with `i32` as their integer lanes.

use super::{math, sealed::Sealed, Elem, IntLanes, Lanes, Table16, Table256};

impl Sealed for f32 {}
impl Sealed for f64 {}
impl Sealed for i32 {}

impl Elem for f32 {
    #[inline(always)]
    fn from_f64(x: f64) -> Self {
        x as f32
    }
    #[inline(always)]
    fn to_f64(self) -> f64 {
        self as f64
    }
    #[inline(always)]
    fn pick<'a>(single: &'a [f32], _double: &'a [f64]) -> &'a [f32] {
        single
    }
}

impl Elem for f64 {
    #[inline(always)]
    fn from_f64(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn to_f64(self) -> f64 {
        self
    }
    #[inline(always)]
    fn pick<'a>(_single: &'a [f32], double: &'a [f64]) -> &'a [f64] {
        double
    }
}

impl IntLanes for i32 {
    type Mask = bool;
    bytes_as_vectors!();
    #[inline(always)]
    fn splat(x: i32) -> Self {
        x
    }
    #[inline(always)]
    fn lane(self, _k: usize) -> i32 {
        self
    }
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        self.wrapping_add(o)
    }
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        self.wrapping_sub(o)
    }
    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        self.wrapping_mul(o)
    }
    #[inline(always)]
    fn and(self, o: Self) -> Self {
        self & o
    }
    #[inline(always)]
    fn or(self, o: Self) -> Self {
        self | o
    }
    #[inline(always)]
    fn xor(self, o: Self) -> Self {
        self ^ o
    }
    #[inline(always)]
    fn shl(self, s: u32) -> Self {
        self.wrapping_shl(s)
    }
    #[inline(always)]
    fn shr(self, s: u32) -> Self {
        ((self as u32).wrapping_shr(s)) as i32
    }
    #[inline(always)]
    fn rem_euclid(self, m: i32) -> Self {
        i32::rem_euclid(self, m)
    }
    #[inline(always)]
    fn eq(self, o: Self) -> bool {
        self == o
    }
    #[inline(always)]
    fn lt(self, o: Self) -> bool {
        self < o
    }
    #[inline(always)]
    fn select(m: bool, a: Self, b: Self) -> Self {
        // Branch-free: noise selects on hash bits, which no predictor learns.
        core::hint::select_unpredictable(m, a, b)
    }
    #[inline(always)]
    fn gather_u8(table: &[u8], idx: Self) -> Self {
        table[idx as usize] as i32
    }
    #[inline(always)]
    fn gather_i32(table: &[i32], idx: Self) -> Self {
        table[idx as usize]
    }
    #[inline(always)]
    fn lookup256(table: &Table256, idx: Self) -> Self {
        table.0[(idx & 255) as usize] as i32
    }
    #[inline(always)]
    fn lookup16(table: &[i32; 16], idx: Self) -> Self {
        table[(idx & 15) as usize]
    }
    #[inline(always)]
    fn lookup32(table: &[i32; 32], idx: Self) -> Self {
        table[(idx & 31) as usize]
    }
}

macro_rules! scalar_lanes {
    ($t:ty, $floor:path, $sqrt:path, $pow:path, $truncate:path, $lookup16:path, $dyn:ident) => {
        impl Lanes for $t {
            type Elem = $t;
            type Int = i32;
            type Mask = bool;
            const WIDTH: usize = 1;

            #[inline(always)]
            fn splat(x: $t) -> Self {
                x
            }
            #[inline(always)]
            fn from_slice(v: &[$t]) -> Self {
                v[0]
            }
            #[inline(always)]
            fn lane(self, _k: usize) -> $t {
                self
            }
            #[inline(always)]
            fn floor(self) -> Self {
                $floor(self)
            }
            #[inline(always)]
            fn abs(self) -> Self {
                <$t>::abs(self)
            }
            #[inline(always)]
            fn sqrt(self) -> Self {
                $sqrt(self)
            }
            #[inline(always)]
            fn min(self, o: Self) -> Self {
                if o < self {
                    o
                } else {
                    self
                }
            }
            #[inline(always)]
            fn max(self, o: Self) -> Self {
                if o > self {
                    o
                } else {
                    self
                }
            }
            #[inline(always)]
            fn lt(self, o: Self) -> bool {
                self < o
            }
            #[inline(always)]
            fn le(self, o: Self) -> bool {
                self <= o
            }
            #[inline(always)]
            fn any(m: bool) -> bool {
                m
            }
            #[inline(always)]
            fn powf(self, e: Self) -> Self {
                $pow(self, e)
            }
            #[inline(always)]
            fn sample_dyn<const D: usize>(noise: &dyn crate::noise::DynNoise<D>, p: [Self; D]) -> Self {
                $dyn(noise, p)
            }
            #[inline(always)]
            fn select(m: bool, a: Self, b: Self) -> Self {
                // Branch-free: noise selects on hash bits, which no predictor learns.
                core::hint::select_unpredictable(m, a, b)
            }
            #[inline(always)]
            fn to_int_wrapping(self) -> i32 {
                // One truncating conversion where the value fits (as the
                // vector lanes do); the rest go to `wrap_far`. (Saturating at
                // once took five more instructions an axis, on a scalar
                // point's critical path.)
                let t = $truncate(self);
                if t != i32::MIN {
                    t
                } else {
                    wrap_far(f64::from(self))
                }
            }
            #[inline(always)]
            fn from_int(i: i32) -> Self {
                i as $t
            }
            #[inline(always)]
            fn gather(table: &[$t], idx: i32) -> Self {
                table[idx as usize]
            }
            #[inline(always)]
            fn lookup16(table: &Table16, idx: i32) -> Self {
                $lookup16(table, idx)
            }
            #[inline(always)]
            fn lookup8(table: &[f32; 8], idx: i32) -> Self {
                table[(idx & 7) as usize] as $t
            }
        }
    };
}

scalar_lanes!(f32, math::floor32, math::sqrt32, libm::powf, truncate32, lookup16_f32, get_f32);
scalar_lanes!(f64, math::floor64, math::sqrt64, libm::pow, truncate64, Table16::double, get);

/// [`Lanes::to_int_wrapping`] of a value that a plain conversion does not
/// take (|x| ≥ 2³¹, or NaN): `as i64` saturates (NaN → 0), the second cast
/// wraps. Out of line and cold, so the common path stays a conversion and
/// a branch: inlined, LLVM formed both results and picked one (3D improved
/// in `f64`, AVX2 clone, callgrind: 218 → 206 instructions a point).
#[cold]
#[inline(never)]
fn wrap_far(x: f64) -> i32 {
    x as i64 as i32
}

/// [`Lanes::lookup16`] in `f32`.
#[inline(always)]
fn lookup16_f32(table: &Table16, idx: i32) -> f32 {
    table.single()[(idx & 15) as usize]
}

/// `x` truncated to `i32`, or `i32::MIN` where it does not fit (NaN too):
/// x86-64's conversion, which has no saturation to fix up.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn truncate32(x: f32) -> i32 {
    use core::arch::x86_64::{_mm_cvttss_si32, _mm_set_ss};
    // SAFETY: SSE, part of x86-64.
    unsafe { _mm_cvttss_si32(_mm_set_ss(x)) }
}

/// [`truncate32`] for `f64`.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn truncate64(x: f64) -> i32 {
    use core::arch::x86_64::{_mm_cvttsd_si32, _mm_set_sd};
    // SAFETY: SSE2, part of x86-64.
    unsafe { _mm_cvttsd_si32(_mm_set_sd(x)) }
}

/// [`truncate32`] elsewhere: `i32::MIN` stands for every value out of
/// range, which then takes the wrapping path.
#[cfg(not(target_arch = "x86_64"))]
#[inline(always)]
fn truncate32(x: f32) -> i32 {
    if (-2147483648.0..2147483648.0).contains(&x) {
        x as i32
    } else {
        i32::MIN
    }
}

/// [`truncate64`] elsewhere.
#[cfg(not(target_arch = "x86_64"))]
#[inline(always)]
fn truncate64(x: f64) -> i32 {
    if (-2147483648.0..2147483648.0).contains(&x) {
        x as i32
    } else {
        i32::MIN
    }
}

/// `DynNoise::get`, by name for the macro.
#[inline(always)]
fn get<const D: usize>(noise: &dyn crate::noise::DynNoise<D>, p: [f64; D]) -> f64 {
    noise.get(p)
}

/// `DynNoise::get_f32`, by name for the macro.
#[inline(always)]
fn get_f32<const D: usize>(noise: &dyn crate::noise::DynNoise<D>, p: [f32; D]) -> f32 {
    noise.get_f32(p)
}
