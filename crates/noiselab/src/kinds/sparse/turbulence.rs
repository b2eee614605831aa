//! The paper's turbulence (its Eq. 4–5): octave f of scale 2^f·s₀ with the
//! same impulses per kernel, its value scaled by 1/2^f, absolute value per
//! octave.

use alloc::vec::Vec;

use super::Sparse;
use crate::grid::Grid;
use crate::lanes::Lanes;
use crate::noise::Noise;

/// `Σ_{f = lo}^{hi} |noise_f(2^f·p)| / 2^f` over sparse convolution noise.
///
/// Octave f evaluated at 2^f·p sees cells 2^f times smaller in the base
/// domain, each holding n impulses: n·(2^D)^f impulses per base cell, as the
/// paper's Eq. 5 counts, so every octave has the base octave's quality.
/// Each octave draws from its own stream (seed + f), so octaves do not
/// correlate. Values are ≥ 0; with the variance normalisation each octave
/// has standard deviation ¼, so the mean is about 0.2·Σ 2^−f.
#[derive(Clone, Debug)]
pub struct SparseTurbulence {
    octaves: Vec<(Sparse, f64)>,
}

impl SparseTurbulence {
    /// Octaves `lo..=hi` (frequency 2^f) of `base`.
    pub fn new(base: &Sparse, lo: u32, hi: u32) -> SparseTurbulence {
        let octaves = (lo..=hi.max(lo))
            .map(|f| {
                let mut o = base.clone();
                o.seed = base.seed.wrapping_add(f);
                (o, libm::ldexp(1.0, f as i32))
            })
            .collect();
        SparseTurbulence { octaves }
    }

    /// Number of octaves.
    pub fn octaves(&self) -> usize {
        self.octaves.len()
    }

    /// The same sum rendered by splatting each octave (see
    /// [`Sparse::splat_grid`]); equal to `fill_grid` within 1e-5 per octave.
    pub fn splat_grid<const D: usize>(&self, grid: &Grid<D>, out: &mut [f32]) -> Result<(), super::SplatError>
    where
        Sparse: Noise<D>,
    {
        // The octave's buffer from the thread's scratch pool: a window's
        // worth, which a fresh allocation would zero and map on every call.
        let mut octave = crate::scratch::take(out.len());
        let sum = self.sum_octaves(grid, out, &mut octave[..out.len()]);
        crate::scratch::give_back(octave);
        sum
    }

    /// [`SparseTurbulence::splat_grid`], each octave splatted into `octave`.
    fn sum_octaves<const D: usize>(
        &self,
        grid: &Grid<D>,
        out: &mut [f32],
        octave: &mut [f32],
    ) -> Result<(), super::SplatError>
    where
        Sparse: Noise<D>,
    {
        out.fill(0.0);
        for (noise, freq) in &self.octaves {
            let scaled = Grid::new(grid.origin.map(|o| o * freq), grid.step.map(|s| s * freq), grid.size);
            noise.splat_grid(&scaled, octave)?;
            let amp = (1.0 / freq) as f32;
            for (o, v) in out.iter_mut().zip(octave.iter()) {
                *o += amp * v.abs();
            }
        }
        Ok(())
    }
}

macro_rules! impl_turbulence {
    ($($d:literal),*) => {$(
        impl Noise<$d> for SparseTurbulence {
            crate::grid::batch_entry!($d);
            #[inline(always)]
            fn sample<L: Lanes>(&self, p: [L; $d]) -> L {
                let mut sum = L::cst(0.0);
                for (noise, freq) in &self.octaves {
                    let q = p.map(|c| c * L::cst(*freq));
                    sum = sum + L::cst(1.0 / freq) * Noise::<$d>::sample(noise, q).abs();
                }
                sum
            }
        }
    )*};
}
impl_turbulence!(1, 2, 3, 4);

// This module's batch drivers per instruction-set level (`grid::batch_clones!`).
crate::grid::batch_clones!();
