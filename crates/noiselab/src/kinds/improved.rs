//! Improved noise (Perlin, "Improving Noise", SIGGRAPH 2002).
//!
//! Value-identical to Perlin's reference `ImprovedNoise.java` in 3D and to
//! his posted `ImprovedNoise4D.java` in 4D (seed 0, `f64`). 1D and 2D are
//! defined as the zero slices of 3D: `n2(x, y) == n3(x, y, 0)` and
//! `n1(x) == n3(x, 0, 0)` as values (the sign of a zero may differ).

use super::lattice::{self, Corner, Lattice};
use super::{fade5, fade5_deriv, Period, PeriodError, MAX_CORNERS};
use crate::grid::Span;
use crate::hash::Permutation;
use crate::lanes::{BatchLanes, IntLanes, Lanes};
use crate::noise::{Noise, NoiseGradient};

/// Which 3D gradient function to use.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum ImprovedVariant {
    /// The reference as it stands today: 12 cube-edge directions padded to 16
    /// with (1,1,0), (0,−1,1), (−1,1,0), (0,−1,−1).
    #[default]
    Current,
    /// The gradient selection as first published in 2002, before Perlin's
    /// small fix (`u = h<8 || h==12 || h==13 ? x : y`,
    /// `v = h<4 || h==12 || h==13 ? y : z`).
    Original2002,
}

/// Perlin's improved gradient noise: quintic fade, edge gradients, the
/// reference permutation.
///
/// * Seed 0 is the reference permutation; other seeds shuffle it.
/// * Output is not rescaled, as in the reference. Documented ranges (tested
///   on random points; the largest |value| found by hill climbing from 2,000
///   starts on seeds 0–4 is in brackets): 1D within ±0.5 \[0.5\], 2D within
///   ±1.0 \[1.0\], 3D within ±1.04 \[1.005\], 4D within ±1.3 \[1.235\].
/// * The 4D gradient follows Perlin's posted code, quirk included: its
///   `switch` lists the triple (y, z, w) for both case 0 (commented
///   "X,Y,Z") and case 3, so half of the 32 gradients have no x component.
/// * Integer lattice points give exactly 0.
#[derive(Clone, Debug)]
pub struct Improved {
    perm: Permutation,
    variant: ImprovedVariant,
    seed: u32,
    period: Period,
}

impl Improved {
    /// Improved noise with the permutation for `seed` (0 = reference).
    pub fn new(seed: u32) -> Self {
        Improved { perm: Permutation::new(seed), variant: ImprovedVariant::Current, seed, period: Period::NONE }
    }

    /// Tiled: periodic with `cells[k]` lattice cells along axis k (0 leaves
    /// an axis unbounded; any positive count, not only powers of two).
    /// Untiled values are unchanged.
    pub fn with_period(mut self, cells: [u32; 4]) -> Result<Self, PeriodError> {
        self.period = Period::new(cells)?;
        Ok(self)
    }

    /// The same noise with another 3D gradient variant.
    pub fn with_variant(mut self, variant: ImprovedVariant) -> Self {
        self.variant = variant;
        self
    }

    /// The seed this noise was built with.
    pub fn seed(&self) -> u32 {
        self.seed
    }

    /// The 3D gradient variant.
    pub fn variant(&self) -> ImprovedVariant {
        self.variant
    }

    /// Perlin's 4D `grad(hash, x, y, z, w)` as posted (see the type docs).
    #[inline(always)]
    fn grad4<L: Lanes>(hash: L::Int, x: L, y: L, z: L, w: L) -> L {
        let h = hash.and_c(31);
        let hi = h.shr(3);
        let (case1, case2) = (hi.eq(L::Int::splat(1)), hi.eq(L::Int::splat(2)));
        // Case 0 and case 3 are both (y, z, w) in the posted code.
        let a = L::select(case1, w, L::select(case2, z, y));
        let b = L::select(case1, x, L::select(case2, w, z));
        let c = L::select(case1, y, L::select(case2, x, w));
        L::select(h.bit(2), a, -a) + L::select(h.bit(1), b, -b) + L::select(h.bit(0), c, -c)
    }

    /// Perlin's index of a corner on an axis, `(X & 255) + bit`; tiled,
    /// the corner's cell wraps first.
    #[inline(always)]
    fn index<I: IntLanes>(&self, cell: I, axis: usize, bit: i32) -> I {
        if self.period.is_none() {
            cell.and_c(255).add_c(bit)
        } else {
            self.period.wrap(axis, cell.add_c(bit)).and_c(255)
        }
    }

    /// Perlin's 3D `grad(hash, x, y, z)` picks two distinct axes u and v and
    /// returns ±u ± v. Per axis: whether it is picked, and whether negated
    /// (bit 0 negates u, bit 1 negates v).
    #[inline(always)]
    fn picks<L: Lanes>(&self, hash: L::Int) -> [(L::Mask, L::Mask); 3] {
        let h = hash.and_c(15);
        let (below4, below8) = (h.lt(L::Int::splat(4)), h.lt(L::Int::splat(8)));
        let (is12, is13, is14) = (h.eq(L::Int::splat(12)), h.eq(L::Int::splat(13)), h.eq(L::Int::splat(14)));
        let (neg_u, neg_v) = (h.bit(0), h.bit(1));
        let (u_is_x, v_is_y, v_is_x) = match self.variant {
            ImprovedVariant::Current => (below8, below4, !below4 & (is12 | is14)),
            ImprovedVariant::Original2002 => {
                let both = is12 | is13;
                // v is never x: `both & !both` is the all-false mask.
                (below8 | both, below4 | both, both & !both)
            }
        };
        // An axis picked as u or as v, negated by u's bit or v's.
        let x = (u_is_x | v_is_x, (u_is_x & neg_u) | (!u_is_x & neg_v));
        let y = (!u_is_x | v_is_y, (!u_is_x & neg_u) | (u_is_x & neg_v));
        [x, y, (!(v_is_y | v_is_x), neg_v)]
    }
}

/// `a` negated where `neg`, or −0 (the additive identity) where the axis is
/// not picked: summing these over the axes in any order gives Perlin's
/// `±u ± v` bit for bit.
#[inline(always)]
fn pick<L: Lanes>(a: L, (picked, neg): (L::Mask, L::Mask)) -> L {
    L::select(picked, L::select(neg, -a, a), L::cst(-0.0))
}

impl<const D: usize> Lattice<D> for Improved {
    const FLOATS: usize = if D == 4 { 3 } else { 2 };
    const INTS: usize = 1;

    #[inline(always)]
    fn fade<L: Lanes>(&self, t: L) -> L {
        fade5(t)
    }

    #[inline(always)]
    fn fade_deriv<L: Lanes>(&self, t: L) -> L {
        fade5_deriv(t)
    }

    /// Perlin's hash chain `p[p[p[X] + Y] + Z]` (and `+ W` in 4D), each
    /// lookup shared by the corners it leads to; 1D and 2D continue the 3D
    /// chain with zero coordinates. Tiled, each corner's cell wraps first.
    #[inline(always)]
    fn corners<L: Lanes>(&self, cells: [L::Int; D]) -> [Corner<L>; MAX_CORNERS] {
        let depth = if D == 4 { 4 } else { 3 };
        let mut h = [L::Int::splat(0); MAX_CORNERS];
        h[0] = self.perm.at(self.index(cells[0], 0, 0));
        h[1] = self.perm.at(self.index(cells[0], 0, 1));
        let mut count = 2;
        for d in 1..depth {
            if d < D {
                let (lower, upper) = (self.index(cells[d], d, 0), self.index(cells[d], d, 1));
                for c in (0..count).rev() {
                    h[c + count] = self.perm.at(h[c].add(upper));
                    h[c] = self.perm.at(h[c].add(lower));
                }
                count *= 2;
            } else {
                for hc in h.iter_mut().take(count) {
                    *hc = self.perm.at(*hc);
                }
            }
        }
        let mut out = [Corner::zero(); MAX_CORNERS];
        for c in 0..MAX_CORNERS {
            out[c].i[0] = h[c];
        }
        out
    }

    /// 1D–3D: the terms of axes 1.. summed (`f[1]`), axis 0's sign as ±1
    /// (`f[0]`) and whether it is picked (`i[0]`). 4D (whose three terms are
    /// summed in a hash-dependent order): the hash and the offsets.
    #[inline(always)]
    fn bind<L: Lanes>(&self, corner: Corner<L>, offset: [L; D]) -> Corner<L> {
        let mut at = [L::cst(0.0); 4];
        at[..D].copy_from_slice(&offset);
        let mut b = Corner::zero();
        if D == 4 {
            b.i[0] = corner.i[0];
            b.f[..3].copy_from_slice(&at[1..]);
        } else {
            let [x, y, z] = self.picks::<L>(corner.i[0]);
            b.f[0] = L::select(x.1, L::cst(-1.0), L::cst(1.0));
            b.f[1] = pick(at[1], y) + pick(at[2], z);
            b.i[0] = L::Int::select(x.0, L::Int::splat(-1), L::Int::splat(0));
        }
        b
    }

    #[inline(always)]
    fn eval<L: Lanes>(&self, b: &Corner<L>, x: L) -> L {
        if D == 4 {
            Self::grad4(b.i[0], x, b.f[0], b.f[1], b.f[2])
        } else {
            let picked = b.i[0].lt(L::Int::splat(0));
            L::select(picked, x * b.f[0] + b.f[1], b.f[1])
        }
    }
}

macro_rules! impl_improved {
    ($($d:literal),*) => {$(
        impl Noise<$d> for Improved {
            #[inline(always)]
            fn sample<L: Lanes>(&self, p: [L; $d]) -> L {
                lattice::sample(self, p)
            }
            #[inline(always)]
            fn fill_span<B: BatchLanes>(&self, span: Span<'_, $d>, out: &mut [f32]) {
                lattice::fill_span::<Self, B, $d>(self, span, out)
            }
        }
        impl NoiseGradient<$d> for Improved {
            #[inline(always)]
            fn sample_gradient<L: Lanes>(&self, p: [L; $d]) -> (L, [L; $d]) {
                lattice::sample_gradient(self, p)
            }
        }
    )*};
}
impl_improved!(1, 2, 3, 4);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    #[allow(clippy::approx_constant)] // 3.14 is the input Perlin printed, not π.
    fn perlin_reference_point() {
        // Printed by Perlin's ImprovedNoise.java for noise(3.14, 42, 7).
        assert_eq!(Improved::new(0).get([3.14, 42.0, 7.0]), 0.13691995878400012);
    }

    #[test]
    fn lower_dimensions_are_zero_slices() {
        let n = Improved::new(7);
        for i in 0..2000 {
            let x = (i as f64) * 0.731 - 700.0;
            let y = (i as f64) * -0.377 + 91.3;
            assert_eq!(Noise::<2>::get(&n, [x, y]), Noise::<3>::get(&n, [x, y, 0.0]));
            assert_eq!(Noise::<1>::get(&n, [x]), Noise::<3>::get(&n, [x, 0.0, 0.0]));
        }
    }
}
