//! Classic noise (Perlin 1985, "An Image Synthesizer"), as his original C
//! program `noise1`/`noise2`/`noise3` computes it.
//!
//! The tables are built in Rust exactly as the C `init()` builds them from
//! glibc's `random()`, so no libc and no table file are needed.

use super::lattice::{self, Corner, Fields, Lattice};
use super::{corner_bit, Period, PeriodError, MAX_CORNERS};
use crate::grid::Span;
use crate::lanes::{math::sqrt64, BatchLanes, Elem, IntLanes, Lanes};
use crate::noise::Noise;
use alloc::sync::Arc;
use alloc::vec::Vec;

/// glibc's `random()` (the TYPE_3 additive feedback generator, degree 31,
/// separation 3), reproduced exactly: `srandom(seed)` fills the state with
/// the Park–Miller recurrence (Schrage's form), drops 310 outputs, then
/// `r[i] = r[i−31] + r[i−3] (mod 2³²)` and each output is `r >> 1`.
pub(crate) struct GlibcRandom {
    r: Vec<u32>,
}

impl GlibcRandom {
    /// The state after `srandom(seed)` (glibc maps seed 0 to 1).
    pub(crate) fn new(seed: u32) -> Self {
        let mut word = if seed == 0 { 1 } else { seed as i32 } as i64;
        let mut r = Vec::with_capacity(4096);
        r.push(word as u32);
        for _ in 1..31 {
            let (hi, lo) = (word / 127_773, word % 127_773);
            word = 16_807 * lo - 2_836 * hi;
            if word < 0 {
                word += 2_147_483_647;
            }
            r.push(word as u32);
        }
        for i in 31..34 {
            r.push(r[i - 31]);
        }
        let mut g = GlibcRandom { r };
        for _ in 0..310 {
            g.next();
        }
        g
    }

    /// The next `random()` value, in 0..2³¹.
    pub(crate) fn next(&mut self) -> i32 {
        let i = self.r.len();
        let v = self.r[i - 31].wrapping_add(self.r[i - 3]);
        self.r.push(v);
        (v >> 1) as i32
    }
}

/// Table length: B + B + 2 in the C code (the tables are stored doubled).
const LEN: usize = 514;

/// The permutation and gradient tables, in both precisions.
#[derive(Debug)]
struct Tables {
    p: [i32; LEN],
    g1: ([f32; LEN], [f64; LEN]),
    g2: [([f32; LEN], [f64; LEN]); 2],
    g3: [([f32; LEN], [f64; LEN]); 3],
}

impl Tables {
    fn new(seed: u32) -> Self {
        let mut rng = GlibcRandom::new(seed.wrapping_add(1));
        // Components uniform on {−256..255}/256, as `(random() % 512 − 256) / 256`.
        let mut component = || ((rng.next() % 512) - 256) as f64 / 256.0;
        let mut p = [0i32; LEN];
        let mut g1 = ([0f32; LEN], [0f64; LEN]);
        let mut g2 = [([0f32; LEN], [0f64; LEN]); 2];
        let mut g3 = [([0f32; LEN], [0f64; LEN]); 3];
        for i in 0..256 {
            p[i] = i as i32;
            let c = component();
            (g1.0[i], g1.1[i]) = (c as f32, c);
            let v2 = [component(), component()];
            let v3 = [component(), component(), component()];
            // Float program: float products and sum, double sqrt stored to float.
            let s2 = sqrt64((v2[0] as f32 * v2[0] as f32 + v2[1] as f32 * v2[1] as f32) as f64) as f32;
            let d2 = sqrt64(v2[0] * v2[0] + v2[1] * v2[1]);
            for k in 0..2 {
                g2[k].0[i] = v2[k] as f32 / s2;
                g2[k].1[i] = v2[k] / d2;
            }
            let f3 = v3.map(|c| c as f32);
            let s3 = sqrt64((f3[0] * f3[0] + f3[1] * f3[1] + f3[2] * f3[2]) as f64) as f32;
            let d3 = sqrt64(v3[0] * v3[0] + v3[1] * v3[1] + v3[2] * v3[2]);
            for k in 0..3 {
                g3[k].0[i] = f3[k] / s3;
                g3[k].1[i] = v3[k] / d3;
            }
        }
        for i in (1..256).rev() {
            let j = (rng.next() % 256) as usize;
            p.swap(i, j);
        }
        for i in 0..258 {
            p[256 + i] = p[i];
            g1.0[256 + i] = g1.0[i];
            g1.1[256 + i] = g1.1[i];
            for g in g2.iter_mut() {
                g.0[256 + i] = g.0[i];
                g.1[256 + i] = g.1[i];
            }
            for g in g3.iter_mut() {
                g.0[256 + i] = g.0[i];
                g.1[256 + i] = g.1[i];
            }
        }
        Tables { p, g1, g2, g3 }
    }
}

/// Perlin's 1985 gradient noise, 1D–3D: 256-entry permutation, gradients
/// with components sampled from a cube and normalised (so directions are
/// cube-biased, as in the original), s-curve 3t² − 2t³.
///
/// * Seed 0 builds the tables the original C program builds under glibc's
///   never-seeded `random()`; seed `s` uses `srandom(s + 1)` (so `u32::MAX`
///   wraps to glibc's seed 0, which glibc treats as 1: it equals seed 0).
/// * `f64` equals the C program with `float` replaced by `double` bit for
///   bit; `f32` equals the verbatim float program bit for bit.
/// * As in the original, `x + 4096` is formed before splitting off the cell,
///   which quantises f32 positions to 2⁻¹²–2⁻¹¹; and, as in the original, the
///   3D z index is added to the table index rather than hashed again.
/// * Deviation: the cell is `floor(x + 4096)` where the C code truncates;
///   identical for x ≥ −4096, and correct (instead of mirrored) below.
/// * Output is not rescaled, as in the original. Ranges: 1D within ±0.5,
///   2D within ±0.71, 3D within ±0.87 (√(D/4), the bound for unit
///   gradients); the largest |value| found by hill climbing from 2,000 starts
///   on seeds 0–2 was 0.476, 0.705 and 0.729. Tested on random points.
///   Lattice points give 0.
#[derive(Clone, Debug)]
pub struct Classic {
    tables: Arc<Tables>,
    seed: u32,
    period: Period,
}

impl Classic {
    /// Classic noise with the tables for `seed` (0 = the original program's).
    pub fn new(seed: u32) -> Self {
        Classic { tables: Arc::new(Tables::new(seed)), seed, period: Period::NONE }
    }

    /// Tiled: periodic with `cells[k]` lattice cells along axis k (0 leaves
    /// an axis unbounded; any positive count). Untiled values are unchanged.
    pub fn with_period(mut self, cells: [u32; 4]) -> Result<Self, PeriodError> {
        self.period = Period::new(cells)?;
        Ok(self)
    }

    /// The seed.
    pub fn seed(&self) -> u32 {
        self.seed
    }
}

/// 3t² − 2t³ as `t·t·(3 − 2t)`.
#[inline(always)]
fn s_curve<L: Lanes>(t: L) -> L {
    t * t * (L::cst(3.0) - L::cst(2.0) * t)
}

impl Classic {
    /// The C `setup` macro's table index of a corner, `(cell + bit) & 255`;
    /// tiled, the cell (x's cell is ⌊x + 4096⌋ − 4096) wraps into the period
    /// first.
    #[inline(always)]
    fn index<I: IntLanes>(&self, cell: I, axis: usize, bit: i32) -> I {
        if self.period.is_none() {
            cell.add_c(bit).and_c(255)
        } else {
            self.period.wrap(axis, cell.add_c(bit - 4096)).and_c(255)
        }
    }

    /// Gradient component table `t` at `i`, in the lanes' precision.
    #[inline(always)]
    fn g<L: Lanes>(t: &([f32; LEN], [f64; LEN]), i: L::Int) -> L {
        L::gather(L::Elem::pick(&t.0, &t.1), i)
    }

    /// The corners' gradients (see `corners`) from each lane's `p[bx]`
    /// and `p[bx + 1]`.
    #[inline(always)]
    fn gradients_after<L: Lanes, const D: usize>(
        &self,
        first: [L::Int; 2],
        cell: [L::Int; D],
    ) -> [Corner<L>; MAX_CORNERS] {
        let t = &self.tables;
        let tables: [&([f32; LEN], [f64; LEN]); 3] = match D {
            1 => [&t.g1, &t.g1, &t.g1],
            2 => [&t.g2[0], &t.g2[1], &t.g2[1]],
            _ => [&t.g3[0], &t.g3[1], &t.g3[2]],
        };
        let mut floats = [[L::cst(0.0); 4]; MAX_CORNERS];
        for (corner, f) in floats.iter_mut().enumerate().take(1 << D) {
            let mut b = first[corner_bit(corner, 0) as usize];
            if D > 1 {
                b = self.p::<L>(b.add(self.index(cell[1], 1, corner_bit(corner, 1))));
            }
            if D > 2 {
                b = b.add(self.index(cell[2], 2, corner_bit(corner, 2)));
            }
            for d in 0..D {
                f[d] = Self::g::<L>(tables[d], b);
            }
        }
        lattice::float_records(&floats)
    }

    /// The permutation `p[i]`.
    #[inline(always)]
    fn p<L: Lanes>(&self, i: L::Int) -> L::Int {
        L::Int::gather_i32(&self.tables.p, i)
    }
}

impl<const D: usize> Lattice<D> for Classic {
    const HASHED: Fields = Fields { floats: D, ints: 0 };
    const BOUND: Fields = Fields { floats: D, ints: 0 };
    /// (`x + 4096` is an integer where `x` is.)
    const ZERO_AT_INTEGERS: bool = true;

    /// As the C `setup`: `t = x + 4096` is formed first (quantising f32
    /// positions), the cell is `⌊t⌋` and the position `t − ⌊t⌋`.
    #[inline(always)]
    fn split<L: Lanes>(&self, x: L) -> (L::Int, L) {
        let t = x + L::cst(4096.0);
        let fl = t.floor();
        (fl.to_int_wrapping(), t - fl)
    }

    #[inline(always)]
    fn fade<L: Lanes>(&self, t: L) -> L {
        s_curve(t)
    }

    #[inline(always)]
    fn fade_deriv<L: Lanes>(&self, t: L) -> L {
        L::cst(6.0) * t * (L::cst(1.0) - t)
    }

    /// The corners' gradients. 1D: `g1[p[bx]]`; 2D: `g2[p[p[bx] + by]]`;
    /// 3D: `g3[p[p[bx] + by] + bz]` — the z index is added to the table
    /// index, not hashed, as in 1985.
    #[inline(always)]
    fn corners<L: Lanes>(&self, cell: [L::Int; D]) -> [Corner<L>; MAX_CORNERS] {
        self.gradients_after([self.p::<L>(self.index(cell[0], 0, 0)), self.p::<L>(self.index(cell[0], 0, 1))], cell)
    }

    /// Untiled, a row's `p[bx]` are consecutive table entries (the table
    /// repeats past 256): one load instead of a lookup per lane.
    #[inline(always)]
    fn point_row<B: BatchLanes>(&self, first: i32, rest: [i32; D]) -> Corner<B> {
        let cells = lattice::row_points::<B, D>(first, rest);
        let lower = if self.period.is_none() {
            B::load_int(&self.tables.p[(first & 255) as usize..])
        } else {
            self.p::<B>(self.index(cells[0], 0, 0))
        };
        // Corner 0 only: the upper corners' work is dead code.
        self.gradients_after([lower, lower], cells)[0]
    }

    /// `f[0]` keeps axis 0's gradient component; `f[d]` becomes `r_d · g_d`.
    #[inline(always)]
    fn bind<L: Lanes>(&self, corner: Corner<L>, offset: [L; D]) -> Corner<L> {
        corner.bind_gradient(offset)
    }

    /// `rx·gx`: the gradient's x passes through `bind`.
    const X_TERM: bool = true;

    #[inline(always)]
    fn x_term<L: Lanes>(&self, b: &Corner<L>, x: L) -> L {
        b.gradient_x_term(x)
    }

    /// `rx·gx + ry·gy + rz·gz`, summed from x, as the C code.
    #[inline(always)]
    fn eval_from_x_term<L: Lanes>(&self, b: &Corner<L>, term: L) -> L {
        b.gradient_dot_from_x_term::<D>(term)
    }
}

macro_rules! impl_classic {
    ($($d:literal),*) => {$(
        impl Noise<$d> for Classic {
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
    )*};
}
impl_classic!(1, 2, 3);

// This module's batch drivers per instruction-set level (`grid::batch_clones!`).
crate::grid::batch_clones!();

#[cfg(test)]
mod tests {
    use super::GlibcRandom;

    #[test]
    fn glibc_random_default_stream() {
        let mut r = GlibcRandom::new(1);
        assert_eq!([r.next(), r.next(), r.next()], [1804289383, 846930886, 1681692777]);
    }
}
