//! Value noise: a random value at each lattice node, interpolated with the
//! quintic fade.

use super::lattice::{self, Corner, Fields, Lattice};
use super::{corner_bit, fade5, fade5_deriv, Period, PeriodError, MAX_CORNERS};
use crate::grid::Span;
use crate::hash::hash_cell;
use crate::lanes::{BatchLanes, IntLanes, Lanes};
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
}

impl<const D: usize> Lattice<D> for Value {
    const HASHED: Fields = Fields { floats: 1, ints: 0 };
    const BOUND: Fields = Fields { floats: 1, ints: 0 };
    const FLAT: bool = true;

    #[inline(always)]
    fn fade<L: Lanes>(&self, t: L) -> L {
        fade5(t)
    }

    #[inline(always)]
    fn fade_deriv<L: Lanes>(&self, t: L) -> L {
        fade5_deriv(t)
    }

    /// Each node's value, in `f[0]`.
    #[inline(always)]
    fn corners<L: Lanes>(&self, cell: [L::Int; D]) -> [Corner<L>; MAX_CORNERS] {
        let mut out = [Corner::zero(); MAX_CORNERS];
        for (corner, c) in out.iter_mut().enumerate().take(1 << D) {
            let mut node = cell;
            for (d, n) in node.iter_mut().enumerate() {
                *n = n.add_c(corner_bit(corner, d));
            }
            // Top 24 bits → k ∈ [0, 2²⁴), exact in f32; k/2²³ − 1 ∈ [−1, 1).
            let k = hash_cell(self.period.wrap_cell(node), self.seed).shr(8);
            c.f[0] = L::from_int(k) * L::cst(1.0 / 8_388_608.0) - L::cst(1.0);
        }
        out
    }

    #[inline(always)]
    fn bind<L: Lanes>(&self, corner: Corner<L>, _offset: [L; D]) -> Corner<L> {
        corner
    }

    #[inline(always)]
    fn eval_from_x_term<L: Lanes>(&self, bound: &Corner<L>, _term: L) -> L {
        bound.f[0]
    }

    /// Corners are constant: the gradient comes from the fades alone.
    #[inline(always)]
    fn corner_gradient<L: Lanes>(&self, _corner: Corner<L>) -> [L; D] {
        [L::cst(0.0); D]
    }
}

macro_rules! impl_value {
    ($($d:literal),*) => {$(
        impl Noise<$d> for Value {
            crate::grid::batch_entry!($d);
            #[inline(always)]
            fn sample<L: Lanes>(&self, p: [L; $d]) -> L {
                lattice::sample(self, p)
            }
            #[inline(always)]
            fn fill_span<B: BatchLanes>(&self, span: Span<'_, $d>, out: &mut [f32]) {
                lattice::fill_span::<Self, B, $d>(self, span, out)
            }
        }
        impl NoiseGradient<$d> for Value {
            #[inline(always)]
            fn sample_gradient<L: Lanes>(&self, p: [L; $d]) -> (L, [L; $d]) {
                lattice::sample_gradient(self, p)
            }
        }
    )*};
}
impl_value!(1, 2, 3, 4);

// This module's batch drivers per instruction-set level (`grid::batch_clones!`).
crate::grid::batch_clones!();
