//! The one trait every noise implements, and its derivative companion.

use crate::grid::{self, Accuracy, Grid, GridError, SimdLevel, Span};
use crate::lanes::{BatchLanes, F32x16, F32x8, Lanes};

/// A coherent-noise field over `D`-dimensional space.
///
/// Implementations are immutable plain data (every noise is `Send + Sync`,
/// cheap to clone or share by reference), and one unit of input space is one
/// lattice cell for every kind. The single required method is written once,
/// generic over the lane type, and serves every API:
///
/// * [`Noise::get`]: one point in `f64` (the reference-exact path);
/// * [`Noise::get_f32`]: one point in `f32`;
/// * [`Noise::fill_grid`] and [`Noise::fill_points`]: batches in `f32`,
///   evaluated sixteen ([`F32x16`], AVX-512) or eight ([`F32x8`]) points at
///   a time, equal to `get_f32` bit for bit.
pub trait Noise<const D: usize>: Send + Sync {
    /// The field at `p`, one point per lane.
    fn sample<L: Lanes>(&self, p: [L; D]) -> L;

    /// The field at one point, in double precision.
    #[inline]
    fn get(&self, p: [f64; D]) -> f64
    where
        Self: Sized,
    {
        grid::point(self, p)
    }

    /// The field at one point, in single precision.
    #[inline]
    fn get_f32(&self, p: [f32; D]) -> f32
    where
        Self: Sized,
    {
        grid::point(self, p)
    }

    /// Fill `out` with the field on a regular grid, axis 0 fastest.
    ///
    /// `out.len()` must equal `grid.len()`. Values equal [`Noise::get_f32`] at
    /// each point ([`Grid::point`]) bit for bit.
    fn fill_grid(&self, grid: &Grid<D>, out: &mut [f32]) -> Result<(), GridError>
    where
        Self: Sized,
    {
        grid::fill_grid(self, grid, out, Accuracy::Exact)
    }

    /// [`Noise::fill_grid`], trading the last bits for speed where a kind
    /// can ([`Accuracy::Fast`]: lattice kinds and their fractals, within
    /// 1e-6 of the exact fill; other kinds fill exactly).
    fn fill_grid_fast(&self, grid: &Grid<D>, out: &mut [f32]) -> Result<(), GridError>
    where
        Self: Sized,
    {
        grid::fill_grid(self, grid, out, Accuracy::Fast)
    }

    /// Fill `out[i]` with the field at `points[i]`; an error, with
    /// nothing written, where the slices differ in length.
    fn fill_points(&self, points: &[[f32; D]], out: &mut [f32]) -> Result<(), GridError>
    where
        Self: Sized,
    {
        grid::fill_points(self, points, out)
    }

    /// Fill `out` with the points `span.start..span.start + out.len()` of
    /// a grid, on lanes `B`. The batch drivers call this inside their
    /// instruction-set clones; kinds override it to exploit a grid's
    /// structure (hash once per cell, not per point). Every override must
    /// give [`Noise::get_f32`]'s bits under [`Accuracy::Exact`].
    #[doc(hidden)]
    #[inline(always)]
    fn fill_span<B: BatchLanes>(&self, span: Span<'_, D>, out: &mut [f32])
    where
        Self: Sized,
    {
        grid::fill_pointwise::<Self, B, D>(self, span, out)
    }

    /// Whether [`Noise::get_f32`] is ±0 at every point with integer
    /// coordinates (gradient noise; `false` when not known). The fractal
    /// grid fill leaves out an octave whose grid lies on such points.
    #[doc(hidden)]
    #[inline]
    fn zero_at_integers(&self) -> bool {
        false
    }

    /// The batch drivers' entry for a span: [`Noise::fill_span`] compiled
    /// for `level` (the best the CPU has up to it). Kinds override it to
    /// enter clones compiled in their own module (`grid::batch_clones!`);
    /// the values are the same either way.
    #[doc(hidden)]
    fn dispatch_span(&self, level: SimdLevel, span: Span<'_, D>, out: &mut [f32])
    where
        Self: Sized,
    {
        grid::batch::span(level, self, span, out)
    }

    /// The batch drivers' entry for a list of points, as
    /// [`Noise::dispatch_span`] for spans.
    #[doc(hidden)]
    fn dispatch_points(&self, level: SimdLevel, points: &[[f32; D]], out: &mut [f32])
    where
        Self: Sized,
    {
        grid::batch::points(level, self, points, out)
    }
}

/// A noise with an analytic gradient.
pub trait NoiseGradient<const D: usize>: Noise<D> {
    /// The value and the gradient `(∂/∂x₀, …, ∂/∂x_{D−1})` at `p`.
    ///
    /// The value equals [`Noise::sample`] at the same point up to rounding
    /// (it may be computed along a different path).
    fn sample_gradient<L: Lanes>(&self, p: [L; D]) -> (L, [L; D]);

    /// Value and gradient at one point, in double precision.
    #[inline]
    fn get_gradient(&self, p: [f64; D]) -> (f64, [f64; D]) {
        self.sample_gradient::<f64>(p)
    }
}

impl<N: Noise<D>, const D: usize> Noise<D> for &N {
    #[inline(always)]
    fn sample<L: Lanes>(&self, p: [L; D]) -> L {
        (**self).sample(p)
    }
    #[inline(always)]
    fn fill_span<B: BatchLanes>(&self, span: Span<'_, D>, out: &mut [f32]) {
        (**self).fill_span::<B>(span, out)
    }
    #[inline]
    fn zero_at_integers(&self) -> bool {
        (**self).zero_at_integers()
    }
    #[inline]
    fn dispatch_span(&self, level: SimdLevel, span: Span<'_, D>, out: &mut [f32]) {
        (**self).dispatch_span(level, span, out)
    }
    #[inline]
    fn dispatch_points(&self, level: SimdLevel, points: &[[f32; D]], out: &mut [f32]) {
        (**self).dispatch_points(level, points, out)
    }
}

impl<N: NoiseGradient<D>, const D: usize> NoiseGradient<D> for &N {
    #[inline(always)]
    fn sample_gradient<L: Lanes>(&self, p: [L; D]) -> (L, [L; D]) {
        (**self).sample_gradient(p)
    }
}

/// The object-safe face of [`Noise`], for pipelines chosen at run time
/// (the command line): one virtual call per point or per batch.
pub trait DynNoise<const D: usize>: Send + Sync {
    /// [`Noise::get`].
    fn get(&self, p: [f64; D]) -> f64;
    /// [`Noise::get_f32`].
    fn get_f32(&self, p: [f32; D]) -> f32;
    /// [`Noise::fill_grid`].
    fn fill_grid(&self, grid: &Grid<D>, out: &mut [f32]) -> Result<(), GridError>;
    /// [`Noise::fill_points`].
    fn fill_points(&self, points: &[[f32; D]], out: &mut [f32]) -> Result<(), GridError>;
    /// Eight lanes at once ([`Noise::sample`] on [`F32x8`]).
    fn sample_x8(&self, p: [F32x8; D]) -> F32x8;
    /// Sixteen lanes at once ([`Noise::sample`] on [`F32x16`]).
    fn sample_x16(&self, p: [F32x16; D]) -> F32x16;
    /// A grid span, through the concrete noise's own batch path (at the
    /// best instruction-set level).
    #[doc(hidden)]
    fn fill_span_dyn(&self, span: Span<'_, D>, out: &mut [f32]);
    /// [`Noise::zero_at_integers`].
    #[doc(hidden)]
    fn zero_at_integers_dyn(&self) -> bool;
}

/// A noise chosen at run time is a [`Noise`] again (one virtual call per
/// point, or per eight points in batches), so fractals, warps and loops
/// compose over it.
impl<const D: usize> Noise<D> for alloc::boxed::Box<dyn DynNoise<D>> {
    #[inline(always)]
    fn sample<L: Lanes>(&self, p: [L; D]) -> L {
        L::sample_dyn(&**self, p)
    }
    #[inline(always)]
    fn fill_span<B: BatchLanes>(&self, span: Span<'_, D>, out: &mut [f32]) {
        // The boxed noise's own path (`**self`: not the box's blanket
        // DynNoise impl, which would come back here).
        (**self).fill_span_dyn(span, out)
    }
    #[inline]
    fn zero_at_integers(&self) -> bool {
        (**self).zero_at_integers_dyn()
    }
}

impl<N: Noise<D>, const D: usize> DynNoise<D> for N {
    fn get(&self, p: [f64; D]) -> f64 {
        Noise::get(self, p)
    }
    fn get_f32(&self, p: [f32; D]) -> f32 {
        Noise::get_f32(self, p)
    }
    fn fill_grid(&self, grid: &Grid<D>, out: &mut [f32]) -> Result<(), GridError> {
        Noise::fill_grid(self, grid, out)
    }
    fn fill_points(&self, points: &[[f32; D]], out: &mut [f32]) -> Result<(), GridError> {
        Noise::fill_points(self, points, out)
    }
    fn sample_x8(&self, p: [F32x8; D]) -> F32x8 {
        Noise::sample(self, p)
    }
    fn sample_x16(&self, p: [F32x16; D]) -> F32x16 {
        Noise::sample(self, p)
    }
    fn fill_span_dyn(&self, span: Span<'_, D>, out: &mut [f32]) {
        grid::fill_span_best(self, span, out)
    }
    fn zero_at_integers_dyn(&self) -> bool {
        Noise::zero_at_integers(self)
    }
}

/// Evaluate eight points at once (a building block for custom batch loops).
#[inline]
pub fn sample_x8<N: Noise<D>, const D: usize>(noise: &N, p: [F32x8; D]) -> F32x8 {
    noise.sample(p)
}

/// Evaluate sixteen points at once (fastest inside code compiled for AVX-512).
#[inline]
pub fn sample_x16<N: Noise<D>, const D: usize>(noise: &N, p: [F32x16; D]) -> F32x16 {
    noise.sample(p)
}
