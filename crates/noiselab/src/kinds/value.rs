//! Value noise: a random value at each lattice node, interpolated with the
//! quintic fade.

use super::{corner_bit, fade5, fade5_deriv, interpolate, interpolate_gradient, Period, PeriodError, MAX_CORNERS};
use crate::hash::hash_cell;
use crate::lanes::{cell, IntLanes, Lanes};
use crate::noise::{Noise, NoiseGradient};

/// Lattice value noise, 1D–4D.
///
/// Each node gets a value uniform on the 2²⁴ points `k/2²³ − 1` of
/// \[−1, 1), from a table-free hash of the node and the seed, so every value
/// is exact in `f32`. Values between nodes are interpolated with Perlin's
/// quintic fade, which keeps the result inside \[−1, 1\] (a convex
/// combination of node values). Unlike gradient noise it is not zero at the
/// nodes: it equals the node's value there.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Value {
    seed: u32,
    period: Period,
}

impl Value {
    /// Value noise for `seed`.
    pub fn new(seed: u32) -> Self {
        Value { seed, period: Period::NONE }
    }

    /// Tiled: periodic with `cells[k]` lattice cells along axis k (0 leaves
    /// an axis unbounded; any positive count, not only powers of two).
    /// Untiled values are unchanged.
    pub fn with_period(mut self, cells: [u32; 4]) -> Result<Self, PeriodError> {
        self.period = Period::new(cells)?;
        Ok(self)
    }

    /// The seed.
    pub fn seed(&self) -> u32 {
        self.seed
    }

    #[inline(always)]
    fn corners<L: Lanes, const D: usize>(&self, p: [L; D]) -> ([L; MAX_CORNERS], [L; D]) {
        let (c, f) = cell(p);
        let mut v = [L::cst(0.0); MAX_CORNERS];
        for (corner, vc) in v.iter_mut().enumerate().take(1 << D) {
            let mut node = c;
            for (d, n) in node.iter_mut().enumerate() {
                *n = n.add_c(corner_bit(corner, d));
            }
            // Top 24 bits → k ∈ [0, 2²⁴), exact in f32; k/2²³ − 1 ∈ [−1, 1).
            let k = hash_cell(self.period.wrap_cell(node), self.seed).shr(8);
            *vc = L::from_int(k) * L::cst(1.0 / 8_388_608.0) - L::cst(1.0);
        }
        (v, f)
    }
}

macro_rules! impl_value {
    ($($d:literal),*) => {$(
        impl Noise<$d> for Value {
            #[inline(always)]
            fn sample<L: Lanes>(&self, p: [L; $d]) -> L {
                let (v, f) = self.corners(p);
                interpolate(v, f.map(fade5))
            }
        }
        impl NoiseGradient<$d> for Value {
            #[inline(always)]
            fn sample_gradient<L: Lanes>(&self, p: [L; $d]) -> (L, [L; $d]) {
                let (v, f) = self.corners(p);
                let g = [[L::cst(0.0); $d]; MAX_CORNERS];
                interpolate_gradient(v, g, f.map(fade5), f.map(fade5_deriv))
            }
        }
    )*};
}
impl_value!(1, 2, 3, 4);
