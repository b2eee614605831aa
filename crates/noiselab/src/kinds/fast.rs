//! The volume-texture approximation of noise from the "Tileable and fast
//! noise" seed: a small periodic volume of improved noise in two channels,
//! sampled trilinearly, with the high-frequency pair rotated by an angle
//! read from a low-frequency sample, so the 8-cell repeat of the volume is
//! hidden under a pattern that repeats only every 72 cells.

use alloc::sync::Arc;
use alloc::vec::Vec;

use crate::lanes::{lerp, Elem, IntLanes, Lanes};
use crate::noise::Noise;
use crate::Improved;

/// Texels per side of the volume.
const SIDE: usize = 32;
const _: () = assert!(SIDE == 1 << 5, "texel indices use shifts by 5 and 10");
/// Lattice cells the volume spans (the improved noise inside is periodic
/// with this many cells): 4 texels per cell.
const CELLS: usize = 8;
/// The low-frequency sample is taken at p / 9.
const LOW: f64 = 1.0 / 9.0;

/// The baked volume: two channels, each SIDE³ texels, in both precisions.
#[derive(Debug)]
struct Volume {
    single: [Vec<f32>; 2],
    double: [Vec<f64>; 2],
}

/// Fast approximate noise, 2D (the z = 0 slice) and 3D.
///
/// A 32³ volume holds two independent improved noises (seeds derived from
/// this noise's seed), each periodic with 8 cells, 4 texels per cell. A
/// point p reads both channels trilinearly at p (`hi`) and the first
/// channel at p/9 (`lo`), and returns `hi.r·cos(2π·lo) + hi.g·sin(2π·lo)`.
/// The volume is built once at construction and shared by clones.
///
/// Expected artefacts (measured in docs/quality.md): trilinear
/// interpolation is only C0 across texel faces (second-derivative jumps at
/// a quarter-cell period), the texel grid shows as lattice lines at 4 px
/// per cell, and the volume itself repeats every 8 cells under the
/// rotation (which only repeats every 72).
///
/// Range: within ±1.47 = √2·1.04 (trilinear interpolation keeps each
/// channel within improved noise's ±1.04, and the rotation keeps
/// |v| ≤ √(r² + g²)); extremes found in 2·10⁶ random points: −0.98, 0.95.
///
/// On a CPU it is not faster: the 24 texel gathers per sample miss the L1
/// cache where improved noise's permutation does not (measured ratio in
/// the README). The seed's speed-up is a GPU property.
#[derive(Clone, Debug)]
pub struct Fast {
    volume: Arc<Volume>,
    seed: u32,
}

impl Fast {
    /// Bakes the volume for `seed` (two improved noises, seeds derived from
    /// it, sampled at the texel corners).
    pub fn new(seed: u32) -> Fast {
        let bases = [0u32, 1].map(|c| {
            let s = seed.wrapping_mul(2).wrapping_add(c).wrapping_add(0x5EED);
            Improved::new(s).with_period([CELLS as u32; 4]).expect("8 cells is a valid period")
        });
        let mut double = [Vec::with_capacity(SIDE.pow(3)), Vec::with_capacity(SIDE.pow(3))];
        for k in 0..SIDE.pow(3) {
            let (x, y, z) = (k % SIDE, (k / SIDE) % SIDE, k / (SIDE * SIDE));
            let p = [x, y, z].map(|c| c as f64 * CELLS as f64 / SIDE as f64);
            for (channel, base) in double.iter_mut().zip(&bases) {
                channel.push(Noise::<3>::get(base, p));
            }
        }
        let single = [0, 1].map(|c| double[c].iter().map(|&v| v as f32).collect());
        Fast { volume: Arc::new(Volume { single, double }), seed }
    }

    /// The seed.
    pub fn seed(&self) -> u32 {
        self.seed
    }

    /// The first `C` channels at `p` (in cells), trilinearly, wrapping the
    /// volume.
    #[inline(always)]
    fn texture<L: Lanes, const C: usize>(&self, p: [L; 3]) -> [L; C] {
        let scale = L::cst((SIDE / CELLS) as f64);
        let mut base = [L::Int::splat(0); 3];
        let mut frac = [L::cst(0.0); 3];
        for a in 0..3 {
            // Reduce into the volume's 8-cell period first: exact, and it
            // keeps huge coordinates finite (p·4 would overflow).
            let period = L::cst(CELLS as f64);
            let q = p[a] - (p[a] * L::cst(1.0 / CELLS as f64)).floor() * period;
            let u = q * scale;
            let fl = u.floor();
            base[a] = fl.to_int_wrapping();
            frac[a] = u - fl;
        }
        let mask = (SIDE - 1) as i32;
        // The eight texel indices, shared by the channels. (Loops, not
        // closures: a closure would not inherit the batch driver's
        // instruction set, and its lane operations would become calls.)
        let mut flat = [L::Int::splat(0); 8];
        for (k, index) in flat.iter_mut().enumerate() {
            let mut at = [L::Int::splat(0); 3];
            for a in 0..3 {
                at[a] = base[a].add_c(((k >> a) & 1) as i32).and_c(mask);
            }
            *index = at[0].add(at[1].shl(5)).add(at[2].shl(10)); // SIDE = 32 = 2⁵
        }
        let mut out = [L::cst(0.0); C];
        for (c, value) in out.iter_mut().enumerate() {
            let table = L::Elem::pick(&self.volume.single[c], &self.volume.double[c]);
            let mut corner = [L::cst(0.0); 8];
            for k in 0..8 {
                corner[k] = L::gather(table, flat[k]);
            }
            let mut x = [L::cst(0.0); 4];
            for k in 0..4 {
                x[k] = lerp(frac[0], corner[2 * k], corner[2 * k + 1]);
            }
            *value = lerp(frac[2], lerp(frac[1], x[0], x[1]), lerp(frac[1], x[2], x[3]));
        }
        out
    }

    #[inline(always)]
    fn eval<L: Lanes>(&self, p: [L; 3]) -> L {
        let [r, g] = self.texture::<L, 2>(p);
        let mut low = p;
        for c in low.iter_mut() {
            *c = *c * L::cst(LOW);
        }
        let [lo] = self.texture::<L, 1>(low);
        let (s, c) = sin_cos_turns(lo);
        r * c + g * s
    }
}

/// `(sin 2πx, cos 2πx)` from lane arithmetic alone, so every lane type
/// agrees bit for bit: reduce x to r ∈ [−½, ½), fold r by quarter turns to
/// |θ| ≤ π/4, evaluate Taylor polynomials of degree 11 and 12 there (error
/// below 1e-9, tested against libm), and rotate back.
#[inline(always)]
fn sin_cos_turns<L: Lanes>(x: L) -> (L, L) {
    let half = L::cst(0.5);
    let r = x - (x + half).floor(); // [−½, ½)
                                    // Fold by quarter turns: r = q/4 + s with q ∈ {−2..2}, |s| ≤ 1/8.
    let q = (r * L::cst(4.0) + half).floor();
    let s = r - q * L::cst(0.25);
    let theta = s * L::cst(core::f64::consts::TAU);
    let t2 = theta * theta;
    // Taylor series (|θ| ≤ π/4: the degree-11/12 terms bound the error by 3e-11).
    let sin = theta
        * (L::cst(1.0)
            + t2 * (L::cst(-1.0 / 6.0)
                + t2 * (L::cst(1.0 / 120.0)
                    + t2 * (L::cst(-1.0 / 5040.0)
                        + t2 * (L::cst(1.0 / 362_880.0) + t2 * L::cst(-1.0 / 39_916_800.0))))));
    let cos = L::cst(1.0)
        + t2 * (L::cst(-0.5)
            + t2 * (L::cst(1.0 / 24.0)
                + t2 * (L::cst(-1.0 / 720.0)
                    + t2 * (L::cst(1.0 / 40_320.0)
                        + t2 * (L::cst(-1.0 / 3_628_800.0) + t2 * L::cst(1.0 / 479_001_600.0))))));
    // Rotate by q quarter turns: q = ±2 → (−sin, −cos); ±1 → (±cos, ∓sin).
    let qi = q.to_int_wrapping().and_c(3);
    let (one, two, three) = (qi.eq(L::Int::splat(1)), qi.eq(L::Int::splat(2)), qi.eq(L::Int::splat(3)));
    let sin_q = L::select(one, cos, L::select(two, -sin, L::select(three, -cos, sin)));
    let cos_q = L::select(one, -sin, L::select(two, -cos, L::select(three, sin, cos)));
    (sin_q, cos_q)
}

impl Noise<3> for Fast {
    crate::grid::batch_entry!(3);
    #[inline(always)]
    fn sample<L: Lanes>(&self, p: [L; 3]) -> L {
        super::finite_or_nan(p, self.eval(p))
    }
}

impl Noise<2> for Fast {
    crate::grid::batch_entry!(2);
    #[inline(always)]
    fn sample<L: Lanes>(&self, [x, y]: [L; 2]) -> L {
        super::finite_or_nan([x, y], self.eval([x, y, L::cst(0.0)]))
    }
}

// This module's batch drivers per instruction-set level (`grid::batch_clones!`).
crate::grid::batch_clones!();

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sin_cos_from_lanes_match_libm() {
        let mut worst = 0f64;
        for k in -20_000..=20_000 {
            let x = k as f64 / 7919.0;
            let (s, c) = sin_cos_turns(x);
            let t = core::f64::consts::TAU * x;
            worst = worst.max((s - libm::sin(t)).abs()).max((c - libm::cos(t)).abs());
        }
        assert!(worst < 1e-9, "{worst}");
    }

    #[test]
    fn texture_interpolates_the_baked_noise() {
        // At texel corners the texture is the improved noise it was baked from.
        let f = Fast::new(3);
        let base = Improved::new(3u32.wrapping_mul(2).wrapping_add(0x5EED)).with_period([8; 4]).unwrap();
        for k in 0..200 {
            let p = [(k % 13) as f64 * 0.25, (k % 7) as f64 * 0.5, (k % 5) as f64 * 0.75];
            assert_eq!(f.texture::<f64, 1>(p)[0], Noise::<3>::get(&base, p));
        }
    }
}
