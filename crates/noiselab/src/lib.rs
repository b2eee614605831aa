//! # noiselab
//!
//! Procedural noise that is exactly what the papers and reference programs
//! say it is, in `f64`, `f32` and SIMD batches that agree bit for bit.
//!
//! ```
//! use noiselab::{Noise, Improved, Grid};
//!
//! // Perlin's improved noise, seed 0 = his reference permutation.
//! let noise = Improved::new(0);
//! let v = noise.get([3.14, 42.0, 7.0]);
//! assert_eq!(v, 0.13691995878400012); // Perlin's ImprovedNoise.java gives exactly this
//!
//! // A 256×256 slice at z = 0.5, 32 samples per lattice cell, 16 or 8 lanes at a time.
//! let grid = Grid::new([0.0, 0.0, 0.5], [1.0 / 32.0, 1.0 / 32.0, 0.0], [256, 256, 1]);
//! let mut image = vec![0f32; grid.len()];
//! noise.fill_grid(&grid, &mut image).unwrap();
//! assert_eq!(image[1000], noise.get_f32(grid.point(1000))); // batch == scalar f32, bit for bit
//! ```
//!
//! ## Design
//!
//! Every kind implements one trait, [`Noise`], whose single method
//! [`Noise::sample`] is generic over a sealed lane type ([`lanes::Lanes`]):
//! `f64`, `f32`, [`lanes::F32x8`] or [`lanes::F32x16`]. So each algorithm is
//! written once and serves the scalar APIs and the batch APIs
//! ([`Noise::fill_grid`], [`Noise::fill_points`]), whose instruction set
//! (AVX-512, AVX2 or portable) is picked at run time; kinds may add a grid
//! path that exploits a grid's structure, bit-identical to the point path
//! ([`Noise::fill_grid_fast`] trades the last bits for speed, within 1e-6).
//! See `ARCHITECTURE.md`.
//!
//! ## Kinds and ranges
//!
//! | kind | paper | dims | range |
//! |---|---|---|---|
//! | [`Classic`] | Perlin 1985 | 1–3 | 1D ±0.5, 2D ±0.71, 3D ±0.87 |
//! | [`Improved`] | Perlin 2002 | 1–4 | 1D ±0.5, 2D ±1, 3D ±1.04, 4D ±1.3 |
//! | [`Simplex`] | Perlin 2001 / Gustavson 2012 | 1–4 | 1D ±0.64, 2D–4D \[−1, 1\] |
//! | [`Modified`] | Olano 2005 | 1–4 | 1D ±0.31, 2D ±0.61, 3D/4D ±1 |
//! | [`Value`] | lattice value noise | 1–4 | \[−1, 1\] |
//! | [`SimplexN`] | Perlin 1999 ("Making Noise") | any | \[−1, 1\] for D ≤ 8 |
//!
//! Analytic gradients of simplex noise are planned (issue 2).
//!
//! ## Special inputs
//!
//! NaN in any coordinate gives NaN. ±∞ gives NaN (the position inside a cell
//! is undefined). Lattice cell indices are taken modulo 2³², so coordinates
//! beyond ±2³¹ cells never panic or overflow; they alias cells 2³² apart.
//! In `f32`, coordinates beyond 2²⁴ have no fractional part left, so gradient
//! kinds return 0 there.

#![cfg_attr(not(feature = "std"), no_std)]
#![deny(unsafe_op_in_unsafe_fn)]
// Lane code walks several parallel per-axis arrays at once; indices read clearer.
#![allow(clippy::needless_range_loop)]

extern crate alloc;

pub mod compose;
pub mod grid;
pub mod hash;
pub mod kinds;
pub mod lanes;
mod noise;
pub mod recipes;
mod scratch;

pub use compose::{ComposeError, Fractal, FractalMode, Looped, Octave, Warp};
pub use grid::{Accuracy, Axes, Grid, GridError, SimdLevel, Span, Stores, STREAM_MIN_VALUES};
pub use kinds::classic::Classic;
pub use kinds::fast::Fast;
pub use kinds::improved::{Improved, ImprovedVariant};
pub use kinds::modified::{Modified, ModifiedHash, ModifiedTexture};
pub use kinds::simplex::Simplex;
pub use kinds::simplex_n::{SimplexCost, SimplexN};
pub use kinds::sparse::{
    Kernel, KernelError, Normalisation, Profile, Sparse, SparseError, SparseTurbulence, SplatError, Values,
};
pub use kinds::value::Value;
pub use kinds::worley::{CellOutput, Metric, Nearest, Worley, WorleyError};
pub use kinds::{Period, PeriodError};
pub use noise::{sample_x16, sample_x8, DynNoise, Noise, NoiseGradient};

/// The README's code blocks, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../../../README.md")]
pub struct ReadmeDoctests;

/// Every kind's batch fills in an unoptimized build, on a thread's stack.
#[cfg(doctest)]
#[doc = include_str!("../tests/unoptimized_stack.md")]
pub struct UnoptimizedStackDoctests;
