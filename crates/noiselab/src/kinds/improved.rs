//! Improved noise (Perlin, "Improving Noise", SIGGRAPH 2002).
//!
//! Value-identical to Perlin's reference `ImprovedNoise.java` in 3D and to
//! his posted `ImprovedNoise4D.java` in 4D (seed 0, `f64`). 1D and 2D are
//! defined as the zero slices of 3D: `n2(x, y) == n3(x, y, 0)` and
//! `n1(x) == n3(x, 0, 0)` as values (the sign of a zero may differ).

use super::lattice::{self, Corner, Fields, Lattice};
use super::{fade5, fade5_deriv, Period, PeriodError, MAX_CORNERS};
use crate::grid::Span;
use crate::hash::Permutation;
use crate::lanes::{BatchLanes, IntLanes, Lanes, Table16};
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

    /// Perlin's hash chain `p[p[p[X] + Y] + Z]` (and `+ W` in 4D) from
    /// its first links `p[X]`, `p[X + 1]`, each lookup shared by the
    /// corners it leads to; 1D and 2D continue the 3D chain with zero
    /// coordinates. Tiled, each corner's cell wraps first. Only corner 0's
    /// chain is followed unless `all`.
    ///
    /// Written level by level with constant counts, not as a loop, so that
    /// LLVM unrolls it and keeps the hashes in registers.
    #[inline(always)]
    fn chain<L: Lanes, const D: usize>(
        &self,
        first: [L::Int; 2],
        cells: [L::Int; D],
        all: bool,
    ) -> [L::Int; MAX_CORNERS] {
        let mut h = [L::Int::splat(0); MAX_CORNERS];
        h[..2].copy_from_slice(&first);
        // The link of axis 1; in 1D and 2D, followed by the zero coordinate
        // of axis 2: both in one lookup of p∘p, the same entries.
        if D > 1 {
            self.branch::<L::Int, 2>(&mut h, cells[1], 1);
        }
        let count = if D > 1 { 4 } else { 2 };
        self.perm.at_each(&mut h[..if all { count } else { 1 }], D <= 2);
        if D > 2 {
            self.branch::<L::Int, 4>(&mut h, cells[2], 2);
            self.perm.at_each(&mut h[..if all { 8 } else { 1 }], false);
        }
        if D > 3 {
            self.branch::<L::Int, 8>(&mut h, cells[3], 3);
            self.perm.at_each(&mut h[..if all { 16 } else { 1 }], false);
        }
        h
    }

    /// The next axis's indices of the `COUNT` chains in `h`: each chain
    /// branches into its lower (`h[c]`) and upper (`h[c + COUNT]`) corner.
    #[inline(always)]
    fn branch<I: IntLanes, const COUNT: usize>(&self, h: &mut [I; MAX_CORNERS], cell: I, axis: usize) {
        let (lower, upper) = (self.index(cell, axis, 0), self.index(cell, axis, 1));
        for c in 0..COUNT {
            h[c + COUNT] = h[c].add(upper);
            h[c] = h[c].add(lower);
        }
    }

    /// The records of all corners of `cells`: the hash (4D) or the
    /// gradient's coefficients (1D–3D), looked up once per lattice point
    /// rather than once per grid row in `bind` (3D points on AVX2 17.3 →
    /// 13.0 ns).
    #[inline(always)]
    fn records<L: Lanes, const D: usize>(&self, cells: [L::Int; D]) -> [Corner<L>; MAX_CORNERS] {
        if D == 4 {
            let mut first = [self.index(cells[0], 0, 0), self.index(cells[0], 0, 1)];
            self.perm.at_each(&mut first, false);
            let h = self.chain::<L, D>(first, cells, true);
            // Each record built whole from its hash, so nothing is zeroed first
            // (see `lattice::float_records`): 3D points on AVX2 20.4 → 17.5 ns.
            core::array::from_fn(|c| self.record::<L, D>(h[c]))
        } else {
            // The chain's last lookup and the gradients' coefficients at
            // once (`lookup16_bytes`), four corners at a time.
            let ([lower, upper], twice) = self.links::<L, D>(cells);
            let mut floats = [[L::cst(0.0); 4]; MAX_CORNERS];
            let gradients = L::lookup16_bytes(self.perm.at_bytes::<L::Int>(lower, twice), self.gradient_tables());
            for (f, g) in floats.iter_mut().zip(gradients).take(1 << D) {
                *f = Self::coefficients::<L, D>(g);
            }
            if D == 3 {
                let gradients = L::lookup16_bytes(self.perm.at_bytes::<L::Int>(upper, twice), self.gradient_tables());
                for (f, g) in floats[4..].iter_mut().zip(gradients) {
                    *f = Self::coefficients::<L, D>(g);
                }
            }
            lattice::float_records(&floats)
        }
    }

    /// [`Improved::chain`] of every corner of `cells` in 1D–3D up to its
    /// last lookup, carried in bytes from link to link
    /// ([`IntLanes::Bytes`]): the indices whose entries are the corners'
    /// hashes (vector `k` of the first holds corner `k`'s, of the second, in
    /// 3D, corner `k + 4`'s, as `branch` orders them), and whether those
    /// entries are read from p∘p (below 3D: the last link followed by the
    /// zero coordinates of the axes up to 2, in one lookup). Random 3D
    /// points on AVX2, callgrind: 64.8 → 59.9 instructions a point against
    /// unpacking and repacking the bytes at each link.
    #[inline(always)]
    fn links<L: Lanes, const D: usize>(&self, cells: [L::Int; D]) -> ([<L::Int as IntLanes>::Bytes; 2], bool) {
        let x = [self.index(cells[0], 0, 0), self.index(cells[0], 0, 1)];
        let y = if D > 1 { [self.index(cells[1], 1, 0), self.index(cells[1], 1, 1)] } else { x };
        let xy = L::Int::to_bytes([x[0], x[1], y[0], y[1]]);
        // p[X], p[X + 1] in vectors 0 and 1.
        let first = self.perm.at_bytes::<L::Int>(xy, false);
        if D == 1 {
            return ([first, first], true);
        }
        // p[X] + Y, p[X + 1] + Y, p[X] + Y + 1, p[X + 1] + Y + 1.
        let link = L::Int::add_bytes(L::Int::pick_bytes(first, [0, 1, 0, 1]), L::Int::pick_bytes(xy, [2, 2, 3, 3]));
        if D == 2 {
            return ([link, link], true);
        }
        let hashes = self.perm.at_bytes::<L::Int>(link, false);
        // Z and Z + 1 in vectors 0 and 1 (2 and 3 unused).
        let z = L::Int::to_bytes([self.index(cells[2], 2, 0), self.index(cells[2], 2, 1), x[0], x[0]]);
        // No closure for the two: it would not inherit the batch driver's
        // instruction set (ARCHITECTURE.md).
        let lower = L::Int::add_bytes(hashes, L::Int::pick_bytes(z, [0; 4]));
        ([lower, L::Int::add_bytes(hashes, L::Int::pick_bytes(z, [1; 4]))], false)
    }

    /// [`Improved::records`] for one lattice point, from its hash.
    #[inline(always)]
    fn record<L: Lanes, const D: usize>(&self, h: L::Int) -> Corner<L> {
        let zero = Corner::zero();
        if D == 4 {
            Corner { i: [h, zero.i[1]], f: zero.f }
        } else {
            let [cx, cy, cz] = self.gradient_tables();
            Corner {
                i: zero.i,
                f: Self::coefficients::<L, D>([L::lookup16(cx, h), L::lookup16(cy, h), L::lookup16(cz, h)]),
            }
        }
    }

    /// The 3D gradient's coefficient tables (one per axis) of the variant.
    #[inline(always)]
    fn gradient_tables(&self) -> [&Table16; 3] {
        let [x, y, z] = &GRADIENTS[self.variant as usize];
        [x, y, z]
    }

    /// A record's floats from the 3D gradient's coefficient on each axis.
    /// In 1D and 2D, `f[2]` holds instead the terms of the axes the point
    /// lies at 0 on (2D: axis 2; 1D: axes 1 and 2, summed as `bind` would):
    /// the same for every row, so formed once per lattice point rather than
    /// per row in `bind` (the same operations, so the same bits).
    #[inline(always)]
    fn coefficients<L: Lanes, const D: usize>(g: [L; 3]) -> [L; 4] {
        let mut c = [g[0], g[1], g[2], L::cst(0.0)];
        let zero = L::cst(0.0);
        if D == 2 {
            c[2] = pick(zero, c[2]);
        } else if D == 1 {
            c[2] = pick(zero, c[1]) + pick(zero, c[2]);
        }
        c
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
}

/// Perlin's 3D `grad(hash, x, y, z)` as coefficients: for hash h (low four
/// bits) it picks two distinct axes u and v and returns ±u ± v, bit 0
/// negating u and bit 1 v. Entry `[axis][h]` is that axis's coefficient:
/// +1, −1, or 0 where the axis is not picked.
const fn gradient_table(variant: ImprovedVariant) -> [[f32; 16]; 3] {
    let mut table = [[0.0; 16]; 3];
    let mut h = 0;
    while h < 16 {
        let (u, v) = match variant {
            ImprovedVariant::Current => (
                if h < 8 { 0 } else { 1 },
                if h < 4 {
                    1
                } else if h == 12 || h == 14 {
                    0
                } else {
                    2
                },
            ),
            ImprovedVariant::Original2002 => {
                (if h < 8 || h == 12 || h == 13 { 0 } else { 1 }, if h < 4 || h == 12 || h == 13 { 1 } else { 2 })
            }
        };
        table[u][h] = if h & 1 == 0 { 1.0 } else { -1.0 };
        table[v][h] = if h & 2 == 0 { 1.0 } else { -1.0 };
        h += 1;
    }
    table
}

/// [`gradient_table`] for each variant.
const GRADIENTS: [[Table16; 3]; 2] =
    [tables(gradient_table(ImprovedVariant::Current)), tables(gradient_table(ImprovedVariant::Original2002))];

/// Each axis's coefficients as a lookup table.
const fn tables([x, y, z]: [[f32; 16]; 3]) -> [Table16; 3] {
    [Table16::new(x), Table16::new(y), Table16::new(z)]
}

/// Offset `a` times its coefficient `c`, or −0 (the additive identity)
/// where the axis is not picked (`c` = 0): summing these over the axes in
/// any order gives Perlin's `±u ± v` bit for bit (`a·±1` is exactly `±a`).
#[inline(always)]
fn pick<L: Lanes>(a: L, c: L) -> L {
    L::select(L::cst(0.0).lt(c.abs()), a * c, L::cst(-0.0))
}

impl<const D: usize> Lattice<D> for Improved {
    /// 1D–3D: the gradient's coefficient on each axis (below 3D, `f[2]`
    /// holds the axes at 0's terms: see `coefficients`); 4D: the hash.
    const HASHED: Fields = if D == 4 { Fields { floats: 0, ints: 1 } } else { Fields { floats: 3, ints: 0 } };
    /// 1D–3D: axis 0's coefficient and the other axes' terms; 4D: the
    /// offsets of axes 1..3 and the hash.
    const BOUND: Fields = if D == 4 { Fields { floats: 3, ints: 1 } } else { Fields { floats: 2, ints: 0 } };
    const ZERO_AT_INTEGERS: bool = true;

    #[inline(always)]
    fn fade<L: Lanes>(&self, t: L) -> L {
        fade5(t)
    }

    #[inline(always)]
    fn fade_deriv<L: Lanes>(&self, t: L) -> L {
        fade5_deriv(t)
    }

    /// [`Improved::records`].
    #[inline(always)]
    fn corners<L: Lanes>(&self, cells: [L::Int; D]) -> [Corner<L>; MAX_CORNERS] {
        self.records::<L, D>(cells)
    }

    /// Untiled, a row's `p[X]` are consecutive entries of the table: one
    /// load for the lanes' first link instead of a lookup per lane.
    #[inline(always)]
    fn point_row<B: BatchLanes>(&self, first: i32, rest: [i32; D]) -> Corner<B> {
        let cells = lattice::row_points::<B, D>(first, rest);
        let lower =
            if self.period.is_none() { self.perm.run::<B>(first) } else { self.perm.at(self.index(cells[0], 0, 0)) };
        self.record::<B, D>(self.chain::<B, D>([lower, lower], cells, false)[0])
    }

    /// 1D–3D: axis 0's coefficient (`f[0]`) and the terms of axes 1..
    /// summed (`f[1]`). 4D (whose three terms are summed in a
    /// hash-dependent order): the hash and the offsets.
    #[inline(always)]
    fn bind<L: Lanes>(&self, corner: Corner<L>, offset: [L; D]) -> Corner<L> {
        let mut at = [L::cst(0.0); 4];
        at[..D].copy_from_slice(&offset);
        let mut b = Corner::zero();
        if D == 4 {
            b.i[0] = corner.i[0];
            b.f[..3].copy_from_slice(&at[1..]);
        } else {
            b.f[0] = corner.f[0];
            // Below 3D the terms of the axes at 0 come ready (`coefficients`).
            b.f[1] = match D {
                1 => corner.f[2],
                2 => pick(at[1], corner.f[1]) + corner.f[2],
                _ => pick(at[1], corner.f[1]) + pick(at[2], corner.f[2]),
            };
        }
        b
    }

    /// 1D–3D: `x·c₀`, axis 0's coefficient passing through `bind`; 4D: `x`.
    const X_TERM: bool = D < 4;

    #[inline(always)]
    fn x_term<L: Lanes>(&self, b: &Corner<L>, x: L) -> L {
        if D == 4 {
            x
        } else {
            b.gradient_x_term(x)
        }
    }

    #[inline(always)]
    fn eval_from_x_term<L: Lanes>(&self, b: &Corner<L>, term: L) -> L {
        if D == 4 {
            Self::grad4(b.i[0], term, b.f[0], b.f[1], b.f[2])
        } else {
            L::select(L::cst(0.0).lt(b.f[0].abs()), term + b.f[1], b.f[1])
        }
    }

    /// `x·c₀ + c` without the select: where axis 0 is not picked it adds
    /// ±0 to `c`, which changes `c` only if it is a zero. Where the
    /// offsets on axes 1.. are not all zero the gradient's two picked
    /// offsets are not both zero, their sum is never −0, and the result is
    /// `eval`'s bit for bit. (A quarter of a 3D grid point's time.)
    #[inline(always)]
    fn eval_unsigned_zero_from_x_term<L: Lanes>(&self, b: &Corner<L>, term: L) -> L {
        if D == 4 {
            <Self as Lattice<D>>::eval_from_x_term(self, b, term)
        } else {
            term + b.f[1]
        }
    }

    /// 1D–3D: the offsets' dot product with the coefficients, without
    /// [`pick`]'s guards: the two picked axes give ±u ± v exactly and the
    /// third adds a zero, which can change only a zero's sign. (Random 3D
    /// points on AVX2: 8.84 → 8.24 ns.)
    #[inline(always)]
    fn value_unsigned_zero<L: Lanes>(&self, corner: Corner<L>, offset: [L; D]) -> L {
        if D == 4 {
            <Self as Lattice<D>>::eval_unsigned_zero(self, &<Self as Lattice<D>>::bind(self, corner, offset), offset[0])
        } else {
            let mut v = offset[0] * corner.f[0];
            for d in 1..D {
                v = v + offset[d] * corner.f[d];
            }
            v
        }
    }
}

macro_rules! impl_improved {
    ($($d:literal),*) => {$(
        impl Noise<$d> for Improved {
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
        impl NoiseGradient<$d> for Improved {
            #[inline(always)]
            fn sample_gradient<L: Lanes>(&self, p: [L; $d]) -> (L, [L; $d]) {
                lattice::sample_gradient(self, p)
            }
        }
    )*};
}
impl_improved!(1, 2, 3, 4);

// This module's batch drivers per instruction-set level (`grid::batch_clones!`).
crate::grid::batch_clones!();

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
