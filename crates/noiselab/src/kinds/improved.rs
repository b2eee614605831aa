//! Improved noise (Perlin, "Improving Noise", SIGGRAPH 2002).
//!
//! Value-identical to Perlin's reference `ImprovedNoise.java` in 3D and to
//! his posted `ImprovedNoise4D.java` in 4D (seed 0, `f64`). 1D and 2D are
//! defined as the zero slices of 3D: `n2(x, y) == n3(x, y, 0)` and
//! `n1(x) == n3(x, 0, 0)` as values (the sign of a zero may differ).

use super::{corner_bit, fade5, fade5_deriv, interpolate, interpolate_gradient, Period, PeriodError, MAX_CORNERS};
use crate::hash::Permutation;
use crate::lanes::{cell, IntLanes, Lanes};
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

    /// Perlin's `grad(hash, x, y, z)`: the dot product of the hashed gradient
    /// with `(x, y, z)`, written as his selects so the rounding is his.
    #[inline(always)]
    fn grad3<L: Lanes>(&self, hash: L::Int, x: L, y: L, z: L) -> L {
        let h = hash.and_c(15);
        let lt = |k: i32| h.lt(L::Int::splat(k));
        let is = |k: i32| h.eq(L::Int::splat(k));
        let (u_is_x, v_is_y) = match self.variant {
            ImprovedVariant::Current => (lt(8), lt(4)),
            ImprovedVariant::Original2002 => (lt(8) | is(12) | is(13), lt(4) | is(12) | is(13)),
        };
        let u = L::select(u_is_x, x, y);
        let v_alt = match self.variant {
            ImprovedVariant::Current => L::select(is(12) | is(14), x, z),
            ImprovedVariant::Original2002 => z,
        };
        let v = L::select(v_is_y, y, v_alt);
        L::select(h.bit(0), -u, u) + L::select(h.bit(1), -v, v)
    }

    /// Perlin's 4D `grad(hash, x, y, z, w)` as posted (see the type docs).
    #[inline(always)]
    fn grad4<L: Lanes>(hash: L::Int, x: L, y: L, z: L, w: L) -> L {
        let h = hash.and_c(31);
        let hi = h.shr(3);
        let case = |k: i32| hi.eq(L::Int::splat(k));
        // Case 0 and case 3 are both (y, z, w) in the posted code.
        let a = L::select(case(1), w, L::select(case(2), z, y));
        let b = L::select(case(1), x, L::select(case(2), w, z));
        let c = L::select(case(1), y, L::select(case(2), x, w));
        L::select(h.bit(2), a, -a) + L::select(h.bit(1), b, -b) + L::select(h.bit(0), c, -c)
    }

    /// The dot product of corner hash `h` with offset `d` (padded with zeros).
    #[inline(always)]
    fn dot<L: Lanes, const D: usize>(&self, h: L::Int, d: [L; D]) -> L {
        let z = L::cst(0.0);
        let at = |k: usize| if k < D { d[k] } else { z };
        if D == 4 {
            Self::grad4(h, at(0), at(1), at(2), at(3))
        } else {
            self.grad3(h, at(0), at(1), at(2))
        }
    }

    /// Per-corner hashes and offsets, shared by value and gradient.
    #[inline(always)]
    fn corners<L: Lanes, const D: usize>(
        &self,
        p: [L; D],
    ) -> ([L::Int; MAX_CORNERS], [[L; D]; MAX_CORNERS], [L; D]) {
        let (cells, f) = cell(p);
        let c = cells.map(|ci| ci.and_c(255));
        // Perlin's index of a corner on an axis: (X & 255) + bit, read from
        // the doubled table; tiled, the corner's cell wraps first.
        let tiled = !self.period.is_none();
        let index = |d: usize, bit: i32| {
            if tiled { self.period.wrap(d, cells[d].add_c(bit)).and_c(255) } else { c[d].add_c(bit) }
        };
        // 1D and 2D continue Perlin's 3D hash chain with zero coordinates.
        let depth = if D == 4 { 4 } else { 3 };
        let mut hashes = [L::Int::splat(0); MAX_CORNERS];
        let mut offsets = [[L::cst(0.0); D]; MAX_CORNERS];
        for corner in 0..(1 << D) {
            let mut h = self.perm.at(index(0, corner_bit(corner, 0)));
            for d in 1..depth {
                let step = if d < D { index(d, corner_bit(corner, d)) } else { L::Int::splat(0) };
                h = self.perm.at(h.add(step));
            }
            hashes[corner] = h;
            for d in 0..D {
                offsets[corner][d] = if corner_bit(corner, d) == 1 { f[d] - L::cst(1.0) } else { f[d] };
            }
        }
        (hashes, offsets, f)
    }

    #[inline(always)]
    fn eval<L: Lanes, const D: usize>(&self, p: [L; D]) -> L {
        let (hashes, offsets, f) = self.corners(p);
        let mut v = [L::cst(0.0); MAX_CORNERS];
        for corner in 0..(1 << D) {
            v[corner] = self.dot(hashes[corner], offsets[corner]);
        }
        interpolate(v, f.map(fade5))
    }

    #[inline(always)]
    fn eval_gradient<L: Lanes, const D: usize>(&self, p: [L; D]) -> (L, [L; D]) {
        let (hashes, offsets, f) = self.corners(p);
        let mut v = [L::cst(0.0); MAX_CORNERS];
        let mut g = [[L::cst(0.0); D]; MAX_CORNERS];
        for corner in 0..(1 << D) {
            v[corner] = self.dot(hashes[corner], offsets[corner]);
            for k in 0..D {
                // The gradient vector's k-th component is its dot with e_k.
                let mut e = [L::cst(0.0); D];
                e[k] = L::cst(1.0);
                g[corner][k] = self.dot(hashes[corner], e);
            }
        }
        interpolate_gradient(v, g, f.map(fade5), f.map(fade5_deriv))
    }
}

macro_rules! impl_improved {
    ($($d:literal),*) => {$(
        impl Noise<$d> for Improved {
            #[inline(always)]
            fn sample<L: Lanes>(&self, p: [L; $d]) -> L {
                self.eval(p)
            }
        }
        impl NoiseGradient<$d> for Improved {
            #[inline(always)]
            fn sample_gradient<L: Lanes>(&self, p: [L; $d]) -> (L, [L; $d]) {
                self.eval_gradient(p)
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
