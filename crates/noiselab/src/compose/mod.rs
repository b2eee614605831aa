//! Noises built from other noises: fractal sums, seamless time loops and
//! domain warps.
//! Each wraps any [`Noise`] and is itself a `Noise`, so they nest and
//! batch like the kinds they wrap.

use crate::lanes::Lanes;
use crate::noise::Noise;

mod fractal;

pub use fractal::{Fractal, FractalMode, Octave, MAX_OCTAVES};

/// Perlin's looping animation ("Making Noise"): with time as the last axis
/// and a loop length `T`,
/// `F₂(x, t) = ((T − t)·F(x, t) + t·F(x, t − T)) / T` for t ∈ [0, T),
/// and t taken modulo T elsewhere, so frame 0 and frame T are identical.
///
/// The blend halves the variance contribution of each term mid-loop (the
/// standard deviation dips to about 0.71× at t = T/2); tiling the time axis
/// of a lattice kind (`with_period`) is the exact alternative without the
/// dip, when T is a whole number of cells.
#[derive(Clone, Debug)]
pub struct Looped<N> {
    noise: N,
    length: f64,
}

/// Why a combinator cannot be built.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ComposeError {
    /// A loop length must be finite and positive.
    LoopLength(f64),
    /// Warp amplitude and frequency must be finite (frequency positive).
    Warp(f64),
    /// At most 16 warp iterations.
    Iterations(u32),
    /// Octaves must be 1..=30.
    Octaves(u32),
    /// Lacunarity must be finite and above 1.
    Lacunarity(f64),
    /// Gain must be finite and positive.
    Gain(f64),
    /// A tiled octave's period (base period × lacunarityⁱ) must be a whole
    /// number of cells.
    OctavePeriod(f64),
}

impl core::fmt::Display for ComposeError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            ComposeError::LoopLength(t) => write!(f, "loop length must be finite and positive, got {t}"),
            ComposeError::Warp(v) => {
                write!(f, "warp amplitude and frequency must be finite (frequency positive), got {v}")
            }
            ComposeError::Iterations(n) => write!(f, "warp iterations must be 1..=16, got {n}"),
            ComposeError::Octaves(n) => write!(f, "octaves must be 1..=30, got {n}"),
            ComposeError::Lacunarity(l) => write!(f, "lacunarity must be finite and above 1, got {l}"),
            ComposeError::Gain(g) => write!(f, "gain must be finite and positive, got {g}"),
            ComposeError::OctavePeriod(p) => write!(
                f,
                "a tiled octave needs a whole number of cells per period, got {p} (use an integer lacunarity)"
            ),
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for ComposeError {}

impl<N> Looped<N> {
    /// `noise` looping in its last coordinate with period `length`.
    pub fn new(noise: N, length: f64) -> Result<Looped<N>, ComposeError> {
        if !(length.is_finite() && length > 0.0) {
            return Err(ComposeError::LoopLength(length));
        }
        Ok(Looped { noise, length })
    }
}

impl<N: Noise<D>, const D: usize> Noise<D> for Looped<N> {
    crate::grid::batch_entry!(D);
    #[inline(always)]
    fn sample<L: Lanes>(&self, mut p: [L; D]) -> L {
        let period = L::cst(self.length);
        let t = p[D - 1];
        let t = t - (t / period).floor() * period; // [0, T]
        p[D - 1] = t;
        let now = self.noise.sample(p);
        p[D - 1] = t - period;
        let before = self.noise.sample(p);
        ((period - t) * now + t * before) / period
    }
}

/// Domain warping: the wrapped noise read at `p + a·w(f·p)`, where `w` is a
/// vector field whose D components are independent noises (seeds
/// `seed + 1 … seed + D`), and, iterated, the warp applied again to the
/// warped point with the amplitude scaled by `gain` and the frequency by
/// `lacunarity` each time (the "fractal" warp FastNoise offers).
///
/// Tiling composes when the warp field is tiled with period × frequency
/// cells: the warped noise then repeats to rounding (points p and p + T
/// are displaced by the same vector, but `p + T + d` and `p + d + T` may
/// differ in the last bit).
#[derive(Clone, Debug)]
pub struct Warp<N, W> {
    noise: N,
    field: [W; 4],
    amplitude: f64,
    frequency: f64,
    iterations: u32,
    gain: f64,
    lacunarity: f64,
}

impl<N, W> Warp<N, W> {
    /// `noise` warped by the field `make(seed + k)` for each axis k, moved
    /// by up to about `amplitude` (in `noise`'s units), the field read at
    /// `frequency · p`.
    pub fn new(
        noise: N,
        make: impl Fn(u32) -> W,
        seed: u32,
        amplitude: f64,
        frequency: f64,
    ) -> Result<Warp<N, W>, ComposeError> {
        if !amplitude.is_finite() {
            return Err(ComposeError::Warp(amplitude));
        }
        if !(frequency.is_finite() && frequency > 0.0) {
            return Err(ComposeError::Warp(frequency));
        }
        let field = core::array::from_fn(|k| make(seed.wrapping_add(k as u32 + 1)));
        Ok(Warp { noise, field, amplitude, frequency, iterations: 1, gain: 0.5, lacunarity: 2.0 })
    }

    /// Iterated: `iterations` warps, each with the amplitude × `gain` and
    /// the frequency × `lacunarity` of the one before.
    pub fn iterated(mut self, iterations: u32, gain: f64, lacunarity: f64) -> Result<Warp<N, W>, ComposeError> {
        if !(1..=16).contains(&iterations) {
            return Err(ComposeError::Iterations(iterations));
        }
        for v in [gain, lacunarity] {
            if !(v.is_finite() && v > 0.0) {
                return Err(ComposeError::Warp(v));
            }
        }
        (self.iterations, self.gain, self.lacunarity) = (iterations, gain, lacunarity);
        Ok(self)
    }
}

impl<N: Noise<D>, W: Noise<D>, const D: usize> Noise<D> for Warp<N, W> {
    crate::grid::batch_entry!(D);
    #[inline(always)]
    fn sample<L: Lanes>(&self, p: [L; D]) -> L {
        const { assert!(D <= 4, "domain warps are defined for 1 to 4 dimensions") };
        let mut q = p;
        let (mut amplitude, mut frequency) = (self.amplitude, self.frequency);
        for _ in 0..self.iterations {
            // (A loop, not `map`: a closure would not inherit the batch
            // driver's instruction set.)
            let mut at = q;
            for c in at.iter_mut() {
                *c = *c * L::cst(frequency);
            }
            let mut moved = q;
            for (k, m) in moved.iter_mut().enumerate() {
                let w = self.field[k].sample(at);
                // Where `frequency · p` overflows (|p| near the float limit)
                // the field is NaN: leave such points unwarped rather than
                // turn a finite input into NaN. NaN input stays NaN below.
                let w = L::select(crate::kinds::is_finite(w), w, L::cst(0.0));
                *m = *m + L::cst(amplitude) * w;
            }
            q = moved;
            amplitude *= self.gain;
            frequency *= self.lacunarity;
        }
        self.noise.sample(q)
    }
}

// This module's batch drivers per instruction-set level (`grid::batch_clones!`).
crate::grid::batch_clones!();
