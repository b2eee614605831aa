//! Eight `f32` lanes: the batch API's lane type.
//!
//! Plain arrays with `#[inline(always)]` element-wise operations. LLVM turns
//! each into one vector instruction for whatever instruction set the calling
//! function is compiled for (SSE2 by default, AVX2 or AVX-512 inside the
//! batch driver's `#[target_feature]` clones), and every operation is the same
//! IEEE-754 operation as the scalar `f32` one, so results are identical.

use super::{math, sealed::Sealed, IntLanes, Lanes};
use core::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

/// Eight `f32` lanes.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(32))]
pub struct F32x8(pub [f32; 8]);

/// Eight `i32` lanes with wrapping arithmetic.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(C, align(32))]
pub struct I32x8(pub [i32; 8]);

/// Eight lane masks, each all ones (true) or all zeros (false).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(C, align(32))]
pub struct M32x8(pub [i32; 8]);

impl Sealed for F32x8 {}
impl Sealed for I32x8 {}

macro_rules! map {
    (|$i:ident| $e:expr) => {{
        let mut out = [Default::default(); 8];
        for $i in 0..8 {
            out[$i] = $e;
        }
        out
    }};
}

macro_rules! bin_op {
    ($tr:ident, $f:ident, $op:tt) => {
        impl $tr for F32x8 {
            type Output = F32x8;
            #[inline(always)]
            fn $f(self, o: F32x8) -> F32x8 {
                F32x8(map!(|i| self.0[i] $op o.0[i]))
            }
        }
    };
}
bin_op!(Add, add, +);
bin_op!(Sub, sub, -);
bin_op!(Mul, mul, *);
bin_op!(Div, div, /);

impl Neg for F32x8 {
    type Output = F32x8;
    #[inline(always)]
    fn neg(self) -> F32x8 {
        F32x8(map!(|i| -self.0[i]))
    }
}

impl BitAnd for M32x8 {
    type Output = M32x8;
    #[inline(always)]
    fn bitand(self, o: M32x8) -> M32x8 {
        M32x8(map!(|i| self.0[i] & o.0[i]))
    }
}
impl BitOr for M32x8 {
    type Output = M32x8;
    #[inline(always)]
    fn bitor(self, o: M32x8) -> M32x8 {
        M32x8(map!(|i| self.0[i] | o.0[i]))
    }
}
impl Not for M32x8 {
    type Output = M32x8;
    #[inline(always)]
    fn not(self) -> M32x8 {
        M32x8(map!(|i| !self.0[i]))
    }
}

#[inline(always)]
fn mask(b: bool) -> i32 {
    -(b as i32)
}

impl Lanes for F32x8 {
    type Elem = f32;
    type Int = I32x8;
    type Mask = M32x8;
    const WIDTH: usize = 8;

    #[inline(always)]
    fn splat(x: f32) -> Self {
        F32x8([x; 8])
    }
    #[inline(always)]
    fn from_slice(v: &[f32]) -> Self {
        F32x8(map!(|i| v[i]))
    }
    #[inline(always)]
    fn lane(self, k: usize) -> f32 {
        self.0[k]
    }
    #[inline(always)]
    fn floor(self) -> Self {
        F32x8(map!(|i| math::floor32(self.0[i])))
    }
    #[inline(always)]
    fn abs(self) -> Self {
        F32x8(map!(|i| self.0[i].abs()))
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        F32x8(map!(|i| math::sqrt32(self.0[i])))
    }
    #[inline(always)]
    fn min(self, o: Self) -> Self {
        F32x8(map!(|i| if o.0[i] < self.0[i] { o.0[i] } else { self.0[i] }))
    }
    #[inline(always)]
    fn max(self, o: Self) -> Self {
        F32x8(map!(|i| if o.0[i] > self.0[i] { o.0[i] } else { self.0[i] }))
    }
    #[inline(always)]
    fn lt(self, o: Self) -> M32x8 {
        M32x8(map!(|i| mask(self.0[i] < o.0[i])))
    }
    #[inline(always)]
    fn le(self, o: Self) -> M32x8 {
        M32x8(map!(|i| mask(self.0[i] <= o.0[i])))
    }
    #[inline(always)]
    fn any(m: M32x8) -> bool {
        m.0.iter().any(|&v| v != 0)
    }
    #[inline(always)]
    fn powf(self, e: Self) -> Self {
        F32x8(map!(|i| libm::powf(self.0[i], e.0[i])))
    }
    #[inline(always)]
    fn sample_dyn<const D: usize>(noise: &dyn crate::noise::DynNoise<D>, p: [Self; D]) -> Self {
        noise.sample_x8(p)
    }
    #[inline(always)]
    fn select(m: M32x8, a: Self, b: Self) -> Self {
        // Bitwise blend: the form LLVM maps to one blend instruction.
        F32x8(map!(|i| f32::from_bits(
            (a.0[i].to_bits() & m.0[i] as u32) | (b.0[i].to_bits() & !m.0[i] as u32)
        )))
    }
    #[inline(always)]
    fn to_int_wrapping(self) -> I32x8 {
        I32x8(map!(|i| self.0[i] as i64 as i32))
    }
    #[inline(always)]
    fn from_int(v: I32x8) -> Self {
        F32x8(map!(|i| v.0[i] as f32))
    }
    #[inline(always)]
    fn gather(table: &[f32], idx: I32x8) -> Self {
        F32x8(map!(|i| table[idx.0[i] as usize]))
    }
}

impl IntLanes for I32x8 {
    type Mask = M32x8;
    #[inline(always)]
    fn splat(x: i32) -> Self {
        I32x8([x; 8])
    }
    #[inline(always)]
    fn lane(self, k: usize) -> i32 {
        self.0[k]
    }
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        I32x8(map!(|i| self.0[i].wrapping_add(o.0[i])))
    }
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        I32x8(map!(|i| self.0[i].wrapping_sub(o.0[i])))
    }
    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        I32x8(map!(|i| self.0[i].wrapping_mul(o.0[i])))
    }
    #[inline(always)]
    fn and(self, o: Self) -> Self {
        I32x8(map!(|i| self.0[i] & o.0[i]))
    }
    #[inline(always)]
    fn or(self, o: Self) -> Self {
        I32x8(map!(|i| self.0[i] | o.0[i]))
    }
    #[inline(always)]
    fn xor(self, o: Self) -> Self {
        I32x8(map!(|i| self.0[i] ^ o.0[i]))
    }
    #[inline(always)]
    fn shl(self, s: u32) -> Self {
        I32x8(map!(|i| self.0[i].wrapping_shl(s)))
    }
    #[inline(always)]
    fn shr(self, s: u32) -> Self {
        I32x8(map!(|i| (self.0[i] as u32).wrapping_shr(s) as i32))
    }
    #[inline(always)]
    fn rem_euclid(self, m: i32) -> Self {
        I32x8(map!(|i| self.0[i].rem_euclid(m)))
    }
    #[inline(always)]
    fn eq(self, o: Self) -> M32x8 {
        M32x8(map!(|i| mask(self.0[i] == o.0[i])))
    }
    #[inline(always)]
    fn lt(self, o: Self) -> M32x8 {
        M32x8(map!(|i| mask(self.0[i] < o.0[i])))
    }
    #[inline(always)]
    fn select(m: M32x8, a: Self, b: Self) -> Self {
        I32x8(map!(|i| (a.0[i] & m.0[i]) | (b.0[i] & !m.0[i])))
    }
    #[inline(always)]
    fn gather_u8(table: &[u8], idx: Self) -> Self {
        I32x8(map!(|i| table[idx.0[i] as usize] as i32))
    }
    #[inline(always)]
    fn gather_i32(table: &[i32], idx: Self) -> Self {
        I32x8(map!(|i| table[idx.0[i] as usize]))
    }
}
