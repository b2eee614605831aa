//! Modified noise, after Olano, "Modified Noise for Evaluation on Graphics
//! Hardware" (Graphics Hardware 2005): improved noise with the permutation
//! table replaced by arithmetic, so it needs no texture or table at all.
//!
//! The paper's full text and code are not public; each choice below is
//! documented with its source (see `shared/notes/modified-noise.md`):
//!
//! * Hash: squaring modulo 61, `P(v) = (v mod 61)² mod 61` — the "modified
//!   Blum Blum Shub" of Fuller's WebGL fire shader, which cites mNoise, and
//!   the 61 named by Unreal Engine's `Random.ush` for this paper.
//! * Chaining from the highest coordinate down, `h = P(x + P(y + P(z + P(w + s))))`
//!   (Fuller's shader selects a z-plane by offsetting y by a hash of z).
//!   Because `P(0) = 0`, lower dimensions are exactly the zero slices of
//!   higher ones.
//! * Gradients from hash bits, the cube-corner directions (±1, ±1, ±1, ±1):
//!   component k is +1 when bit k of the hash is set (as Unreal's
//!   Olano-derived ALU noise takes gradient signs from hash bits).
//! * Improved-noise quintic fade and interpolation order.
//!
//! Unconfirmed against the paper: the chaining order, pre-multipliers, the
//! bit-to-gradient mapping and the output scale.

use super::lattice::{self, Corner, Fields, Lattice};
use super::{corner_bit, fade5, fade5_deriv, Period, PeriodError, MAX_CORNERS};
use crate::grid::Span;
use crate::hash::fmix32;
use crate::lanes::{BatchLanes, IntLanes, Lanes};
use crate::noise::{Noise, NoiseGradient};
use alloc::sync::Arc;
use alloc::vec::Vec;

/// The hash modified noise chains over the coordinates.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum ModifiedHash {
    /// Olano's squaring modulo 61: every intermediate is an integer below
    /// 2²⁴, so even an `f32`-only GPU evaluates it exactly. The field repeats
    /// every 61 cells on every axis, and only 61 seeds differ.
    #[default]
    Mod61,
    /// The same structure with a 32-bit bijective mixer Q (MurmurHash3's
    /// finaliser, `Q(0) = 0`) instead of P: no short period, zero slices
    /// still exact, every `u32` seed distinct.
    Wide,
}

/// Output scale, one constant for every dimension so zero slices stay exact.
/// Chosen so the 4D field stays within ±1: the largest unscaled |value|
/// found by hill climbing from 2,000 starts was 1.36 (mod 61) and 1.43
/// (wide) in 4D, 1.26 in 3D, exactly 1 in 2D and 0.5 in 1D.
const SCALE: f64 = 0.6;

/// Olano-style modified noise, 1D–4D: table-free, `n2(x, y) == n3(x, y, 0)
/// == n4(x, y, 0, 0)` (as values) for every point and seed.
///
/// Ranges (tested on random points): 1D within ±0.31, 2D ±0.61, 3D and 4D
/// ±1 (largest found: 0.3, 0.6, 0.76, 0.86).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Modified {
    seed: u32,
    hash: ModifiedHash,
    period: Period,
}

impl Modified {
    /// Modified noise with the mod-61 hash; `seed` enters the innermost
    /// level of the chain (with mod 61 only `seed mod 61` matters).
    pub fn new(seed: u32) -> Self {
        Modified { seed, hash: ModifiedHash::Mod61, period: Period::NONE }
    }

    /// Tiled: periodic with `cells[k]` lattice cells along axis k (0 leaves
    /// an axis unbounded). The textured evaluation inherits the period.
    pub fn with_period(mut self, cells: [u32; 4]) -> Result<Self, PeriodError> {
        self.period = Period::new(cells)?;
        Ok(self)
    }

    /// The tiling periods.
    fn period(&self) -> Period {
        self.period
    }

    /// The same noise with another hash.
    pub fn with_hash(mut self, hash: ModifiedHash) -> Self {
        self.hash = hash;
        self
    }

    /// The seed.
    pub fn seed(&self) -> u32 {
        self.seed
    }

    /// The hash in use.
    pub fn hash(&self) -> ModifiedHash {
        self.hash
    }

    #[inline(always)]
    fn step<I: IntLanes>(&self, v: I) -> I {
        match self.hash {
            ModifiedHash::Mod61 => {
                let r = v.rem_euclid(61);
                r.mul(r).rem_euclid(61)
            }
            ModifiedHash::Wide => fmix32(v),
        }
    }

    /// The chained hash of a lattice node, padded to 4D with zeros.
    #[inline(always)]
    fn node_hash<I: IntLanes, const D: usize>(&self, node: [I; D]) -> I {
        let mut h = I::splat(self.chain_seed());
        for d in (0..4).rev() {
            let c = if d < D { node[d] } else { I::splat(0) };
            h = self.step(c.add(h));
        }
        h
    }

    /// The seed as it enters the chain.
    fn chain_seed(&self) -> i32 {
        match self.hash {
            ModifiedHash::Mod61 => (self.seed % 61) as i32,
            ModifiedHash::Wide => self.seed as i32,
        }
    }
}

/// Olano's other evaluation: the mod-61 hash of the z = w = 0 plane baked
/// into a 61×61 table ("texture"), `T[x][y] = P(x + P(y))`, and higher
/// dimensions combined from it procedurally: the plane of integer (z, w) is
/// reached by offsetting y by `P(z + P(w + s))`, as Fuller's shader selects
/// a z-plane by offsetting y by a hash of z. Values are identical to the
/// computed [`Modified`] (mod 61) with the same seed, bit for bit.
#[derive(Clone, Debug)]
pub struct ModifiedTexture {
    table: Arc<[i32]>,
    computed: Modified,
}

impl ModifiedTexture {
    /// Bake the table for `noise`'s seed (the mod-61 hash is always used:
    /// the wide hash has no small period to bake).
    pub fn new(noise: &Modified) -> Self {
        let computed = noise.with_hash(ModifiedHash::Mod61);
        // The plane itself is seed-free: the seed enters through the offset.
        let plane = Modified::new(0);
        let table: Vec<i32> = (0..61 * 61).map(|k| plane.node_hash::<i32, 2>([k / 61, k % 61])).collect();
        ModifiedTexture { table: table.into(), computed }
    }

    /// The source noise's tiling periods.
    fn period(&self) -> Period {
        self.computed.period
    }

    #[inline(always)]
    fn node_hash<I: IntLanes, const D: usize>(&self, node: [I; D]) -> I {
        // Procedural part: the plane offset from the axes beyond y.
        let mut inner = I::splat(self.computed.chain_seed());
        for d in (2..4).rev() {
            let c = if d < D { node[d] } else { I::splat(0) };
            inner = self.computed.step(c.add(inner));
        }
        let y = if D > 1 { node[1] } else { I::splat(0) };
        let row = node[0].rem_euclid(61).mul(I::splat(61));
        I::gather_i32(&self.table, row.add(y.add(inner).rem_euclid(61)))
    }
}

/// Both evaluations share everything but the node hash.
macro_rules! modified_lattice {
    ($t:ty) => {
        impl<const D: usize> Lattice<D> for $t {
            const HASHED: Fields = Fields { floats: D, ints: 0 };
            const BOUND: Fields = Fields { floats: D, ints: 0 };
            const ZERO_AT_INTEGERS: bool = true;

            #[inline(always)]
            fn fade<L: Lanes>(&self, t: L) -> L {
                fade5(t)
            }

            #[inline(always)]
            fn fade_deriv<L: Lanes>(&self, t: L) -> L {
                fade5_deriv(t)
            }

            /// The corners' gradient vectors, ±1 per axis from the hash's low bits.
            #[inline(always)]
            fn corners<L: Lanes>(&self, cell: [L::Int; D]) -> [Corner<L>; MAX_CORNERS] {
                let mut floats = [[L::cst(0.0); 4]; MAX_CORNERS];
                for (corner, f) in floats.iter_mut().enumerate().take(1 << D) {
                    let mut node = cell;
                    for (d, n) in node.iter_mut().enumerate() {
                        *n = n.add_c(corner_bit(corner, d));
                    }
                    let h = self.node_hash(self.period().wrap_cell(node));
                    for d in 0..D {
                        f[d] = L::select(h.bit(d as u32), L::cst(1.0), L::cst(-1.0));
                    }
                }
                lattice::float_records(&floats)
            }

            /// `f[0]` keeps axis 0's gradient component; `f[d]` becomes the
            /// term `g_d · offset_d`.
            #[inline(always)]
            fn bind<L: Lanes>(&self, corner: Corner<L>, offset: [L; D]) -> Corner<L> {
                corner.bind_gradient(offset)
            }

            /// Axis 0's product: its gradient component passes through `bind`.
            const X_TERM: bool = true;

            #[inline(always)]
            fn x_term<L: Lanes>(&self, b: &Corner<L>, x: L) -> L {
                b.gradient_x_term(x)
            }

            /// The dot product, summed from axis 0 up.
            #[inline(always)]
            fn eval_from_x_term<L: Lanes>(&self, b: &Corner<L>, term: L) -> L {
                b.gradient_dot_from_x_term::<D>(term)
            }

            #[inline(always)]
            fn scale(&self) -> f64 {
                SCALE
            }
        }
    };
}
modified_lattice!(Modified);
modified_lattice!(ModifiedTexture);

macro_rules! impl_modified {
    ($($d:literal),*) => {$(
        impl Noise<$d> for Modified {
            crate::grid::batch_entry!($d);
            #[inline(always)]
            fn sample<L: Lanes>(&self, p: [L; $d]) -> L {
                lattice::sample(self, p)
            }
            #[inline(always)]
            fn fill_span<B: BatchLanes>(&self, span: Span<'_, $d>, out: &mut [f32]) {
                lattice::fill_span::<Self, B, $d>(self, span, out)
            }
            #[inline]
            fn zero_at_integers(&self) -> bool {
                <Self as Lattice<$d>>::ZERO_AT_INTEGERS
            }
        }
        impl Noise<$d> for ModifiedTexture {
            crate::grid::batch_entry!($d);
            #[inline(always)]
            fn sample<L: Lanes>(&self, p: [L; $d]) -> L {
                lattice::sample(self, p)
            }
            #[inline(always)]
            fn fill_span<B: BatchLanes>(&self, span: Span<'_, $d>, out: &mut [f32]) {
                lattice::fill_span::<Self, B, $d>(self, span, out)
            }
            #[inline]
            fn zero_at_integers(&self) -> bool {
                <Self as Lattice<$d>>::ZERO_AT_INTEGERS
            }
        }
        impl NoiseGradient<$d> for Modified {
            #[inline(always)]
            fn sample_gradient<L: Lanes>(&self, p: [L; $d]) -> (L, [L; $d]) {
                lattice::sample_gradient(self, p)
            }
        }
    )*};
}
impl_modified!(1, 2, 3, 4);

// This module's batch drivers per instruction-set level (`grid::batch_clones!`).
crate::grid::batch_clones!();
