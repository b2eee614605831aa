//! Fractal sums of any noise (Perlin 1985's 1/f noise and turbulence, and
//! Musgrave's ridged and hybrid multifractals): one octave loop for all
//! modes, written once over values and once-and-the-same over value +
//! gradient pairs, so derivatives come from the same code.

use alloc::vec::Vec;

use super::ComposeError;
use crate::grid::{store_prefix, Axes, RowPiece, SimdLevel, Span, Stores};
use crate::lanes::{BatchLanes, Lanes, StreamedRun};
use crate::noise::{Noise, NoiseGradient};

/// How octaves combine. `nᵢ` is octave i's noise at `lacunarityⁱ·p`, `aᵢ =
/// gainⁱ` its amplitude and `A = Σ aᵢ`; every sum is divided by `A`, so the
/// documented range follows from the base noise's range R.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum FractalMode {
    /// Σ aᵢ nᵢ / A (Perlin's "1/f noise"). Range ±R.
    #[default]
    Fbm,
    /// Σ aᵢ |nᵢ| / A (Perlin's turbulence). Range [0, R].
    Turbulence,
    /// Σ aᵢ (1 − |nᵢ|)²·wᵢ / A with wᵢ = clamp(2·previous term, 0, 1), w₀ = 1
    /// (Musgrave's ridged multifractal). Range [0, 1] for R ≤ 2.
    Ridged,
    /// Σ aᵢ (2|nᵢ| − 1) / A. Range [−1, 2R − 1].
    Billow,
    /// Musgrave's hybrid multifractal with offset ½: s₀ = n₀ + ½,
    /// sᵢ = (nᵢ + ½)·aᵢ weighted by the running product of earlier
    /// signals (capped at 1), over A. Range ±(R + ½).
    Hybrid,
}

impl FractalMode {
    /// Every mode, in the order the command line lists them.
    pub const ALL: [FractalMode; 5] =
        [FractalMode::Fbm, FractalMode::Turbulence, FractalMode::Ridged, FractalMode::Billow, FractalMode::Hybrid];

    /// The command-line name.
    pub fn name(self) -> &'static str {
        match self {
            FractalMode::Fbm => "fbm",
            FractalMode::Turbulence => "turbulence",
            FractalMode::Ridged => "ridged",
            FractalMode::Billow => "billow",
            FractalMode::Hybrid => "hybrid",
        }
    }

    /// The range of the sum for a base noise of range ±`r`.
    pub fn range(self, r: f64) -> (f64, f64) {
        match self {
            FractalMode::Fbm => (-r, r),
            FractalMode::Turbulence => (0.0, r),
            FractalMode::Ridged => (0.0, 1.0),
            FractalMode::Billow => (-1.0, 2.0 * r - 1.0),
            FractalMode::Hybrid => (-(r + HYBRID_OFFSET), r + HYBRID_OFFSET),
        }
    }
}

/// Musgrave's hybrid offset.
const HYBRID_OFFSET: f64 = 0.5;

/// Relative slack of [`Fractal::band_limited`]'s two-samples-a-cell test.
const BAND_SLACK: f64 = 0.01;

/// Most octaves a fractal may have.
pub const MAX_OCTAVES: u32 = 30;

/// What the octave loop needs of a number: lanes for values, and value +
/// gradient pairs for derivatives.
trait Arith: Copy {
    /// The lanes a constant factor takes.
    type Lane: Lanes;
    fn cst(c: f64) -> Self;
    fn add(self, o: Self) -> Self;
    fn mul(self, o: Self) -> Self;
    #[inline(always)]
    fn scale(self, c: f64) -> Self {
        self.scale_by(<Self::Lane as Lanes>::cst(c))
    }
    /// [`Arith::scale`] by a factor already in lanes.
    fn scale_by(self, c: Self::Lane) -> Self;
    fn abs(self) -> Self;
    /// min(self, 1).
    fn min_one(self) -> Self;
    /// clamp(self, 0, 1).
    fn clamp01(self) -> Self;
}

impl<L: Lanes> Arith for L {
    type Lane = L;
    #[inline(always)]
    fn cst(c: f64) -> Self {
        L::cst(c)
    }
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        self + o
    }
    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        self * o
    }
    #[inline(always)]
    fn scale_by(self, c: L) -> Self {
        self * c
    }
    #[inline(always)]
    fn abs(self) -> Self {
        Lanes::abs(self)
    }
    #[inline(always)]
    fn min_one(self) -> Self {
        Lanes::min(self, L::cst(1.0))
    }
    #[inline(always)]
    fn clamp01(self) -> Self {
        Lanes::max(Lanes::min(self, L::cst(1.0)), L::cst(0.0))
    }
}

/// A value and its gradient (forward-mode differentiation).
#[derive(Clone, Copy)]
struct Dual<L: Lanes, const D: usize> {
    v: L,
    d: [L; D],
}

// Gradient components by loops, not `map` or `from_fn` with closures: a
// closure would not inherit the batch driver's instruction set, and its
// lane operations would become calls.
impl<L: Lanes, const D: usize> Arith for Dual<L, D> {
    type Lane = L;
    #[inline(always)]
    fn cst(c: f64) -> Self {
        Dual { v: L::cst(c), d: [L::cst(0.0); D] }
    }
    #[inline(always)]
    fn add(mut self, o: Self) -> Self {
        for k in 0..D {
            self.d[k] = self.d[k] + o.d[k];
        }
        Dual { v: self.v + o.v, d: self.d }
    }
    #[inline(always)]
    fn mul(mut self, o: Self) -> Self {
        for k in 0..D {
            self.d[k] = self.d[k] * o.v + self.v * o.d[k];
        }
        Dual { v: self.v * o.v, d: self.d }
    }
    #[inline(always)]
    fn scale_by(mut self, c: L) -> Self {
        for g in self.d.iter_mut() {
            *g = *g * c;
        }
        Dual { v: self.v * c, d: self.d }
    }
    #[inline(always)]
    fn abs(mut self) -> Self {
        let negative = self.v.lt(L::cst(0.0));
        for g in self.d.iter_mut() {
            *g = L::select(negative, -*g, *g);
        }
        Dual { v: Lanes::abs(self.v), d: self.d }
    }
    #[inline(always)]
    fn min_one(mut self) -> Self {
        let capped = L::cst(1.0).lt(self.v);
        for g in self.d.iter_mut() {
            *g = L::select(capped, L::cst(0.0), *g);
        }
        Dual { v: L::select(capped, L::cst(1.0), self.v), d: self.d }
    }
    #[inline(always)]
    fn clamp01(mut self) -> Self {
        let out = self.v.lt(L::cst(0.0)) | L::cst(1.0).lt(self.v);
        for g in self.d.iter_mut() {
            *g = L::select(out, L::cst(0.0), *g);
        }
        Dual { v: Lanes::max(Lanes::min(self.v, L::cst(1.0)), L::cst(0.0)), d: self.d }
    }
}

/// A fractal sum of `octaves` copies of a noise, each on its own seed.
#[derive(Clone, Debug)]
pub struct Fractal<N> {
    octaves: Vec<N>,
    mode: FractalMode,
    steps: Steps,
    band_limited: bool,
}

/// The octave loop's constants, formed once: octave i's frequency
/// lacunarityⁱ and amplitude gainⁱ (each by repeated multiplication), and
/// for each count k of leading octaves 1 / Σ_{i<k} gainⁱ, summed in octave
/// order (so the first k octaves of a fractal are normalized exactly as a
/// fractal of k octaves).
#[derive(Clone, Debug)]
struct Steps {
    frequency: [f64; MAX_OCTAVES as usize],
    amplitude: [f64; MAX_OCTAVES as usize],
    /// `scale[k − 1]`: the normalization of the first k octaves.
    scale: [f64; MAX_OCTAVES as usize],
}

impl Steps {
    fn new(octaves: usize, lacunarity: f64, gain: f64) -> Steps {
        let none = [0.0; MAX_OCTAVES as usize];
        let mut steps = Steps { frequency: none, amplitude: none, scale: none };
        let (mut frequency, mut amplitude, mut total) = (1.0, 1.0, 0.0);
        for i in 0..octaves {
            steps.frequency[i] = frequency;
            steps.amplitude[i] = amplitude;
            total += amplitude;
            steps.scale[i] = 1.0 / total;
            frequency *= lacunarity;
            amplitude *= gain;
        }
        steps
    }
}

/// What a fractal's constructor tells the function that makes octave i.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Octave {
    /// Octave index, 0 = the base.
    pub index: u32,
    /// The octave's seed: the fractal's seed + index, so octaves do not
    /// correlate.
    pub seed: u32,
    /// lacunarityⁱ: octave i is read at this multiple of p.
    pub frequency: f64,
}

impl Octave {
    /// A base period (in cells) scaled to this octave: tiling composes when
    /// octave i is tiled with `period · lacunarityⁱ` cells, which must be a
    /// whole number (integer lacunarity).
    pub fn period(&self, base: [u32; 4]) -> Result<[u32; 4], ComposeError> {
        let mut out = [0u32; 4];
        for (o, &b) in out.iter_mut().zip(&base) {
            let p = b as f64 * self.frequency;
            if p != libm::floor(p) || p > (1u64 << 30) as f64 {
                return Err(ComposeError::OctavePeriod(p));
            }
            *o = p as u32;
        }
        Ok(out)
    }
}

impl<N> Fractal<N> {
    /// `octaves` octaves made by `make` (seeds `seed + i`), lacunarity 2,
    /// gain ½.
    pub fn new(
        make: impl Fn(Octave) -> N,
        seed: u32,
        octaves: u32,
        mode: FractalMode,
    ) -> Result<Fractal<N>, ComposeError> {
        Fractal::with(make, seed, octaves, mode, 2.0, 0.5)
    }

    /// With explicit lacunarity (frequency ratio, > 1) and gain (amplitude
    /// ratio, > 0).
    pub fn with(
        make: impl Fn(Octave) -> N,
        seed: u32,
        octaves: u32,
        mode: FractalMode,
        lacunarity: f64,
        gain: f64,
    ) -> Result<Fractal<N>, ComposeError> {
        if !(1..=MAX_OCTAVES).contains(&octaves) {
            return Err(ComposeError::Octaves(octaves));
        }
        if !(lacunarity.is_finite() && lacunarity > 1.0) {
            return Err(ComposeError::Lacunarity(lacunarity));
        }
        if !(gain.is_finite() && gain > 0.0) {
            return Err(ComposeError::Gain(gain));
        }
        let octaves = (0..octaves)
            .map(|i| make(Octave { index: i, seed: seed.wrapping_add(i), frequency: libm::pow(lacunarity, i as f64) }))
            .collect();
        Fractal::from_octaves(octaves, mode, lacunarity, gain)
    }

    /// From octaves already made (octave i read at lacunarityⁱ·p), e.g.
    /// noises chosen at run time.
    pub fn from_octaves(
        octaves: Vec<N>,
        mode: FractalMode,
        lacunarity: f64,
        gain: f64,
    ) -> Result<Fractal<N>, ComposeError> {
        if !(1..=MAX_OCTAVES as usize).contains(&octaves.len()) {
            return Err(ComposeError::Octaves(octaves.len() as u32));
        }
        if !(lacunarity.is_finite() && lacunarity > 1.0) {
            return Err(ComposeError::Lacunarity(lacunarity));
        }
        if !(gain.is_finite() && gain > 0.0) {
            return Err(ComposeError::Gain(gain));
        }
        let steps = Steps::new(octaves.len(), lacunarity, gain);
        Ok(Fractal { octaves, mode, steps, band_limited: false })
    }

    /// Grid fills that follow Perlin's rule from the talk ("we continue
    /// this sum until … the noise would fluctuate faster than about once
    /// every two pixels"), as [`Fractal::octaves_for_footprint`] does when
    /// choosing a count: a fill leaves out the octaves whose cells are
    /// shorter than two grid steps along every axis of more than one
    /// sample (octave i is kept while lacunarityⁱ · step ≤ ½ on some axis,
    /// to within 1 % since grid coordinates are `f32`; octave 0 always is).
    /// Finer octaves add only aliasing at that resolution, and cost the
    /// most to fill.
    ///
    /// The kept octaves are normalized among themselves, so a band-limited
    /// fill equals, bit for bit, the fill of the fractal of that many
    /// octaves (same seeds, lacunarity and gain). The fill then depends on
    /// the grid's spacing: point evaluation (`get`, `fill_points`, other
    /// noises sampling this one) has no spacing and sums every octave.
    pub fn band_limited(mut self) -> Fractal<N> {
        self.band_limited = true;
        self
    }

    /// Whether grid fills are [band-limited](Fractal::band_limited).
    pub fn is_band_limited(&self) -> bool {
        self.band_limited
    }

    /// How many leading octaves a grid fill over `axes` sums: all, or
    /// those [band limiting](Fractal::band_limited) keeps at the axes'
    /// smallest mean step (all of them where no axis has two samples).
    fn octaves_for<const D: usize>(&self, axes: &Axes<D>) -> usize {
        let all = self.octaves.len();
        if !self.band_limited {
            return all;
        }
        let step = (0..D)
            .map(|d| axes.axis(d))
            .filter(|a| a.len() >= 2)
            .map(|a| libm::fabs((a[a.len() - 1] as f64 - a[0] as f64) / (a.len() - 1) as f64))
            .filter(|s| s.is_finite() && *s > 0.0)
            .fold(f64::INFINITY, f64::min);
        if step == f64::INFINITY {
            return all;
        }
        // The slack absorbs f32 rounding of the coordinates: a step of
        // exactly 1/32 far from the origin may measure a little above it.
        1 + (1..all).take_while(|&i| self.steps.frequency[i] * step <= 0.5 * (1.0 + BAND_SLACK)).count()
    }

    /// Perlin's rule from the talk: stop before an octave would vary faster
    /// than about once every two pixels. With `footprint` input units per
    /// pixel (a base of about one feature per unit), that is
    /// `⌊log_lacunarity(1 / (2·footprint))⌋ + 1` octaves, within 1..=30.
    pub fn octaves_for_footprint(footprint: f64, lacunarity: f64) -> u32 {
        if !(footprint.is_finite() && footprint > 0.0 && lacunarity.is_finite() && lacunarity > 1.0) {
            return 1;
        }
        let n = libm::floor(libm::log(1.0 / (2.0 * footprint)) / libm::log(lacunarity)) + 1.0;
        n.clamp(1.0, MAX_OCTAVES as f64) as u32
    }

    /// Number of octaves.
    pub fn octaves(&self) -> usize {
        self.octaves.len()
    }

    /// The mode.
    pub fn mode(&self) -> FractalMode {
        self.mode
    }

    /// The octave loop, over any [`Arith`]: `octaves.octave(i, frequency)`
    /// gives octave i's noise (value or value + gradient).
    #[inline(always)]
    fn combine<T: Arith>(&self, octaves: &impl Octaves<T>) -> T {
        self.steps.combine(self.mode, self.octaves.len(), octaves)
    }
}

/// The octave loop's running state at a point: the sum so far and the
/// weight that ridged and hybrid carry from octave to octave.
#[derive(Clone, Copy)]
struct OctaveSum<T> {
    sum: T,
    weight: T,
}

impl<T: Arith> OctaveSum<T> {
    #[inline(always)]
    fn start() -> Self {
        OctaveSum { sum: T::cst(0.0), weight: T::cst(1.0) }
    }

    /// One octave of the loop: octave i's noise `n` at `amplitude`.
    #[inline(always)]
    fn add_octave(&mut self, mode: FractalMode, i: usize, n: T, amplitude: T::Lane) {
        let term = match mode {
            FractalMode::Fbm => n,
            FractalMode::Turbulence => n.abs(),
            FractalMode::Billow => n.abs().scale(2.0).add(T::cst(-1.0)),
            FractalMode::Ridged => {
                let s = T::cst(1.0).add(n.abs().scale(-1.0));
                let s = s.mul(s).mul(self.weight);
                self.weight = s.scale(2.0).clamp01();
                s
            }
            FractalMode::Hybrid => {
                let signal = n.add(T::cst(HYBRID_OFFSET));
                if i == 0 {
                    self.weight = signal;
                    signal
                } else {
                    // Hybrid applies its own amplitude inside the weight.
                    let w = self.weight.min_one();
                    let s = signal.scale_by(amplitude);
                    self.weight = w.mul(s);
                    self.sum = self.sum.add(w.mul(s));
                    return;
                }
            }
        };
        self.sum = self.sum.add(term.scale_by(amplitude));
    }
}

/// Where the octave loop finds octave i's noise. (A trait, not a closure:
/// a closure LLVM declines to inline would run outside the batch driver's
/// instruction-set clone.)
trait Octaves<T: Arith> {
    fn octave(&self, i: usize, frequency: f64) -> T;
    /// Octave i's amplitude (`amplitude`) in lanes.
    #[inline(always)]
    fn amplitude(&self, _i: usize, amplitude: f64) -> T::Lane {
        <T::Lane as Lanes>::cst(amplitude)
    }
    /// The sum's normalization (`scale`) in lanes.
    #[inline(always)]
    fn normalization(&self, scale: f64) -> T::Lane {
        <T::Lane as Lanes>::cst(scale)
    }
}

/// An octave whose scaled point overflows (|p| near the float limit) is
/// NaN; it contributes 0 instead, so finite input stays finite. NaN input
/// gives NaN (checked on the result).
#[inline(always)]
fn finite_or_zero<L: Lanes>(v: L) -> L {
    L::select(crate::kinds::is_finite(v), v, L::cst(0.0))
}

/// Each octave evaluated at the point.
struct AtPoint<'a, N, L, const D: usize> {
    noises: &'a [N],
    p: [L; D],
}

impl<N: Noise<D>, L: Lanes, const D: usize> Octaves<L> for AtPoint<'_, N, L, D> {
    #[inline(always)]
    fn octave(&self, i: usize, frequency: f64) -> L {
        let mut q = self.p;
        for c in q.iter_mut() {
            *c = *c * L::cst(frequency);
        }
        finite_or_zero(self.noises[i].sample(q))
    }
}

/// Each octave's value and gradient at the point.
struct GradientAtPoint<'a, N, L, const D: usize> {
    noises: &'a [N],
    p: [L; D],
}

impl<N: NoiseGradient<D>, L: Lanes, const D: usize> Octaves<Dual<L, D>> for GradientAtPoint<'_, N, L, D> {
    #[inline(always)]
    fn octave(&self, i: usize, frequency: f64) -> Dual<L, D> {
        let mut q = self.p;
        for c in q.iter_mut() {
            *c = *c * L::cst(frequency);
        }
        let (v, g) = self.noises[i].sample_gradient(q);
        let mut d = g;
        for k in 0..D {
            d[k] = finite_or_zero(g[k] * L::cst(frequency));
        }
        Dual { v: finite_or_zero(v), d }
    }
}

/// Octave values already filled for a chunk of a grid: octave i from
/// `i · stride` in `buffers`, the chunk starting `at` there; the octaves'
/// amplitudes in lanes, formed once per block rather than converted and
/// broadcast per octave and chunk (2D fBm-6 over 2048²: 458 → 443 M
/// instructions; 4.32 → 4.21 ns/point on Zen 4).
#[derive(Clone, Copy)]
struct Filled<'a, B> {
    buffers: &'a [f32],
    stride: usize,
    at: usize,
    /// Octaves filled (the leading ones).
    count: usize,
    amplitudes: &'a [B],
    /// The normalization of the grid's octaves (`count` or more).
    normalization: B,
}

impl<B: BatchLanes> Filled<'_, B> {
    /// Octave i's values at the chunk, as filled. Read unchecked but for
    /// tests that fold or leave the octave loop (checked, the loop took 18
    /// instructions an octave, and the combine pass 296 M instead of 208 M).
    #[inline(always)]
    fn lanes(&self, i: usize) -> B {
        assert!(i < self.count && self.at <= self.stride && B::WIDTH <= self.stride - self.at);
        // SAFETY: `new` checked count · stride ≤ buffers.len(), and i <
        // count, at + WIDTH ≤ stride, so the lanes end within octave i's
        // stride, at most (i + 1) · stride ≤ buffers.len().
        let lanes =
            unsafe { core::slice::from_raw_parts(self.buffers.as_ptr().add(i * self.stride + self.at), B::WIDTH) };
        B::from_slice(lanes)
    }

    /// Octave i's `len` values from point `at` of the block (checked: they
    /// lie within octave i's stride).
    #[inline(always)]
    fn values(&self, i: usize, at: usize, len: usize) -> &[f32] {
        assert!(i < self.count && at <= self.stride && len <= self.stride - at);
        &self.buffers[i * self.stride + at..i * self.stride + at + len]
    }
}

impl<'a, B> Filled<'a, B> {
    /// `count` octaves from `buffers`, `stride` apart, at chunk 0.
    #[inline(always)]
    fn new(buffers: &'a [f32], stride: usize, count: usize, (amplitudes, normalization): (&'a [B], B)) -> Self {
        // What `octave`'s unchecked reads rest on.
        assert!(count.checked_mul(stride).is_some_and(|len| len <= buffers.len()));
        Filled { buffers, stride, at: 0, count, amplitudes, normalization }
    }
}

impl<B: BatchLanes> Octaves<B> for Filled<'_, B> {
    #[inline(always)]
    fn octave(&self, i: usize, _frequency: f64) -> B {
        finite_or_zero(self.lanes(i))
    }
    #[inline(always)]
    fn amplitude(&self, i: usize, _amplitude: f64) -> B {
        self.amplitudes[i]
    }
    #[inline(always)]
    fn normalization(&self, _scale: f64) -> B {
        self.normalization
    }
}

/// Points per block of the grid fill: the octaves of a block are filled
/// one after another, then combined (the buffers stay in cache). Each
/// octave's fill has a setup cost per call, so blocks are not made to fit
/// the 1 MiB L2: on 2048² 6-octave fBm, 2^14 points took 4.2 ns/point,
/// 2^16 3.63, 2^17 3.50 and 2^19 3.65 (L3 then thrashes). Measured again
/// once the octaves' record tables came from the scratch pool: 2^15 11.1,
/// 2^16 10.2 and 2^17 9.8 ns/point on a slower day.
const BLOCK: usize = 1 << 17;

/// About how many columns each strip of a grid fill takes, where rows are
/// at least two strips wide: octaves are filled strip by strip, down all
/// the span's rows, since the fine octaves fill faster along shorter rows
/// (2D improved over 2²² points at 1/2, AVX-512, Emerald Rapids: rows of
/// 512 0.61–0.84 ns/point, of 2048 0.96–0.98; at 1/4 0.51–0.54 against
/// 0.58–0.68). 6-octave fBm over 2048² at 1/32 (probe, ns/point, three runs
/// each): whole rows 3.6–4.0, strips of 256 3.06–3.11, 512 2.91–3.01, 1024
/// 2.87–3.43.
const STRIP: usize = 512;

/// Fewest points of a grid whose combine stores its values past the caches
/// ([`Stores::Streamed`]): 4 MiB, where the kinds' own fills stream from
/// [`crate::STREAM_MIN_VALUES`] (32 MiB) on.
/// 6-octave fBm at 1/32 (probe, AVX-512, Emerald Rapids, ns/point, two runs
/// each, plain → streamed): 4096² 3.08–3.17 → 2.70; 2048² (5 octaves)
/// 2.94–3.06 → 2.65–2.68; 1024² 2.79–2.91 → 2.68–2.72; 512² 2.67–2.73 →
/// 2.58–2.94.
const COMBINE_STREAM_MIN_VALUES: usize = 1 << 20;

impl<N: Noise<D>, const D: usize> Noise<D> for Fractal<N> {
    crate::grid::batch_entry!(D);
    #[inline(always)]
    fn sample<L: Lanes>(&self, p: [L; D]) -> L {
        let v = self.combine(&AtPoint { noises: &self.octaves, p });
        crate::kinds::finite_or_nan(p, v)
    }

    /// Octave by octave: each octave fills the block through its own grid
    /// path at the scaled coordinates (the same `f32` products a point
    /// evaluation forms), then the octave loop combines the values, point
    /// by point in the same order: the bits of [`Noise::get_f32`] (of the
    /// kept octaves' fractal where [band-limited](Fractal::band_limited)).
    #[inline(always)]
    fn fill_span<B: BatchLanes>(&self, span: Span<'_, D>, out: &mut [f32]) {
        let w = B::WIDTH;
        let nx = span.axes.size(0).max(1);
        // From the whole grid's axes, so every span (and thread) agrees.
        let count = self.octaves_for(span.axes);
        // Each kept octave's axes (in buffers this thread keeps, put back
        // below), in an array: collected into a `Vec`, they were a malloc
        // and a free per call (2 % of a 32² tile of fBm-6, perf).
        let mut kept = KEPT_OCTAVE_AXES.take();
        let mut scaled = [const { Axes::EMPTY }; MAX_OCTAVES as usize];
        for (axes, &f) in scaled.iter_mut().zip(&self.steps.frequency[..count]) {
            *axes = span.axes.scaled_in(f as f32, kept.0.pop().unwrap_or_default());
        }
        // Kept again at once, with what is left: an octave that is itself a
        // fractal takes its buffers from below these (last in, first out),
        // so nested fractals allocate nothing once warm either.
        KEPT_OCTAVE_AXES.keep(kept);
        // An octave of gradient noise whose grid lies on integer points is
        // ±0 at every point (on a grid of spacing 2⁻ᵏ from integers, every
        // octave from the k-th on): it is not filled, and reads as +0. The
        // same bits in every mode: the others take |n| or add a constant to
        // n, and fBm's sum starts at +0 and is never −0 (a sum is −0 only
        // if both addends are), so adding −0 or +0 to it gives the same.
        let mut on_integers = [false; MAX_OCTAVES as usize];
        for ((skip, noise), axes) in on_integers.iter_mut().zip(&self.octaves).zip(&scaled[..count]) {
            *skip = noise.zero_at_integers() && axes.all_integers();
        }
        // fBm adds each octave's term, and +0 at a finite amplitude is a
        // term of +0, which leaves the sum as it was: trailing octaves on
        // integers are then neither filled nor summed (a 32² tile of fBm-6
        // at 1/32 zeroed its sixth octave's 4 KiB every call). The first
        // octave always is, so the combine has an octave to loop over.
        let mut summed = count;
        while self.mode == FractalMode::Fbm
            && summed > 1
            && on_integers[summed - 1]
            && (self.steps.amplitude[summed - 1] as f32).is_finite()
        {
            summed -= 1;
        }
        // Where every coordinate is finite, point evaluation's NaN guard
        // passes every value: the combine needs no positions.
        let finite = span.axes.all_finite();
        // The whole grid's size, not the span's: threads cut it into smaller ones.
        let stores = if span.axes.points() >= COMBINE_STREAM_MIN_VALUES { Stores::Streamed } else { span.stores };
        let fills =
            OctaveFills { scaled: &scaled[..count], on_integers: &on_integers[..count], summed, finite, stores };
        match strip_width(nx, w) {
            // Whole rows of every coordinate, finite: strip by strip.
            Some(width) if D >= 2 && finite && span.start.is_multiple_of(nx) && out.len().is_multiple_of(nx) => {
                let (first_row, rows) = (span.start / nx, out.len() / nx);
                let mut first = 0;
                while first < nx {
                    let width = width.min(nx - first);
                    let mut narrow = [const { Axes::EMPTY }; MAX_OCTAVES as usize];
                    for (narrow, axes) in narrow.iter_mut().zip(fills.scaled) {
                        *narrow = axes.columns(first..first + width);
                    }
                    let strip = Span { axes: &narrow[0], start: first_row * width, ..span };
                    let strip_fills = OctaveFills { scaled: &narrow[..count], ..fills };
                    self.fill_blocks::<B, D>(
                        &strip_fills,
                        strip,
                        rows * width,
                        Some(Strip { first, width, stride: nx }),
                        out,
                    );
                    for axes in &mut narrow[..count] {
                        core::mem::replace(axes, Axes::EMPTY).recycle();
                    }
                    first += width;
                }
            }
            _ => self.fill_blocks::<B, D>(&fills, span, out.len(), None, out),
        }
        if stores == Stores::Streamed {
            crate::lanes::stream_fence();
        }
        let mut kept = KEPT_OCTAVE_AXES.take();
        for axes in &mut scaled[..count] {
            kept.0.push(core::mem::replace(axes, Axes::EMPTY).into_coords());
        }
        KEPT_OCTAVE_AXES.keep(kept);
    }
}

/// The buffers of a grid fill's octave axes, kept by each thread between
/// fills rather than taken from the scratch pool one by one and given
/// back (12 trips a tile of fBm-6: 1,210 instructions of a fast 32²
/// tile's 51,800, callgrind, AVX2).
#[derive(Default)]
struct KeptOctaveAxes(Vec<Vec<f32>>);

impl crate::scratch::KeptVectors for KeptOctaveAxes {
    fn held_bytes(&self) -> usize {
        self.0.iter().map(crate::scratch::bytes_of).sum::<usize>() + crate::scratch::bytes_of(&self.0)
    }
}

crate::scratch::per_thread!(KEPT_OCTAVE_AXES: KeptOctaveAxes);

/// What a grid fill's octaves read: each kept octave's scaled axes,
/// whether they lie on integers (such octaves are not filled), how many
/// leading octaves are filled, and whether every coordinate is finite; and
/// how the combine stores.
#[derive(Clone, Copy)]
struct OctaveFills<'a, const D: usize> {
    scaled: &'a [Axes<D>],
    on_integers: &'a [bool],
    summed: usize,
    finite: bool,
    stores: Stores,
}

/// Columns `first..first + width` of a span's rows of `stride` points:
/// where a strip's values go in the span's output.
#[derive(Clone, Copy)]
struct Strip {
    first: usize,
    width: usize,
    stride: usize,
}

/// The columns of each strip a fill splits rows of `nx` points into (about
/// [`STRIP`], whole registers of `w` lanes but for the last), or `None`
/// where rows are narrower than two strips.
fn strip_width(nx: usize, w: usize) -> Option<usize> {
    let strips = nx / STRIP;
    (strips >= 2).then(|| nx.div_ceil(strips).next_multiple_of(w))
}

impl<N> Fractal<N> {
    /// The octaves of `len` points of `span` filled block by block, each
    /// block then combined into `out`: in order, or, for a `strip`, row by
    /// row into its columns (`span` then runs over the strip's own axes).
    #[inline(always)]
    fn fill_blocks<B: BatchLanes, const D: usize>(
        &self,
        fills: &OctaveFills<'_, D>,
        span: Span<'_, D>,
        len: usize,
        strip: Option<Strip>,
        out: &mut [f32],
    ) where
        N: Noise<D>,
    {
        let nx = span.axes.size(0).max(1);
        let (summed, count) = (fills.summed, fills.scaled.len());
        // Whole rows per block where rows are short, so octaves see whole rows.
        let block = if nx < BLOCK { BLOCK / nx * nx } else { BLOCK };
        // Octave i's values from i · stride (a buffer kept by the thread),
        // no longer than the span needs: a 32² tile took 6 × 2¹⁷ values,
        // which the thread's first tile zeroed. A strip's rows are combined
        // from `r · width` on, so the last octave has a block's room past
        // its stride.
        let stride = block.min(len) + B::WIDTH;
        let room = if strip.is_some() { block.min(len) } else { 0 };
        let mut buffers = crate::scratch::take(summed * stride + room);
        let mut done = 0;
        while done < len {
            let n = block.min(len - done);
            let start = span.start + done;
            for (i, noise) in self.octaves[..summed].iter().enumerate() {
                let octave = &mut buffers[i * stride..i * stride + n];
                if fills.on_integers[i] {
                    // Once: nothing else writes this octave's buffer, and
                    // later blocks are no longer than the first (a 2048²
                    // fBm zeroed 512 KiB 32 times).
                    if done == 0 {
                        octave.fill(0.0);
                    }
                } else {
                    // Through the octave's own clones, not inlined here: the
                    // kind's grid path is then compiled once per kind and
                    // level, not again in every fractal over it (one call per
                    // block).
                    noise.dispatch_span(
                        B::LEVEL,
                        Span { axes: &fills.scaled[i], start, accuracy: span.accuracy, stores: Stores::Cached },
                        octave,
                    );
                }
            }
            match strip {
                // Blocks of a strip are whole rows of it (`len` and `block`
                // are multiples of its width).
                Some(Strip { first, width, stride: row_stride }) => {
                    for r in 0..n / width {
                        let at = (done / width + r) * row_stride + first;
                        let octaves =
                            OctaveBuffers { values: &buffers[r * width..], stride, count: summed, total: count };
                        combine_finite(
                            B::LEVEL,
                            &self.steps,
                            self.mode,
                            octaves,
                            &mut out[at..at + width],
                            fills.stores,
                        );
                    }
                }
                None => {
                    let block_out = &mut out[done..done + n];
                    let octaves = OctaveBuffers { values: &buffers[..], stride, count: summed, total: count };
                    if fills.finite {
                        combine_finite(B::LEVEL, &self.steps, self.mode, octaves, block_out, fills.stores);
                    } else {
                        let part = Span { start, ..span };
                        let amplitudes = self.steps.lane_amplitudes::<B>(summed);
                        self.combine_with_positions::<B, D>(part, self.steps.filled(octaves, &amplitudes), block_out);
                    }
                }
            }
            done += n;
        }
        crate::scratch::give_back(buffers);
    }

    /// The grid fill's second pass over a block of `part` where some
    /// coordinate is not finite: the octave loop over the filled octaves
    /// (`filled`, from `at` 0), point by point with positions, NaN where a
    /// coordinate is not finite (as point evaluation). Where every
    /// coordinate is finite, [`combine_finite`] needs no positions.
    #[inline(always)]
    fn combine_with_positions<B: BatchLanes, const D: usize>(
        &self,
        part: Span<'_, D>,
        filled: Filled<'_, B>,
        out: &mut [f32],
    ) {
        // The mode dispatched once per block.
        match self.mode {
            FractalMode::Fbm => self.combine_with_positions_as::<B, D>(FractalMode::Fbm, part, filled, out),
            FractalMode::Turbulence => {
                self.combine_with_positions_as::<B, D>(FractalMode::Turbulence, part, filled, out)
            }
            FractalMode::Ridged => self.combine_with_positions_as::<B, D>(FractalMode::Ridged, part, filled, out),
            FractalMode::Billow => self.combine_with_positions_as::<B, D>(FractalMode::Billow, part, filled, out),
            FractalMode::Hybrid => self.combine_with_positions_as::<B, D>(FractalMode::Hybrid, part, filled, out),
        }
    }

    /// [`Fractal::combine_with_positions`] in `mode`.
    #[inline(always)]
    fn combine_with_positions_as<B: BatchLanes, const D: usize>(
        &self,
        mode: FractalMode,
        part: Span<'_, D>,
        filled: Filled<'_, B>,
        out: &mut [f32],
    ) {
        let w = B::WIDTH;
        let xs = part.axes.axis(0);
        for RowPiece { idx, first, offset, len: n } in part.rows(out.len()) {
            let mut p = [B::cst(0.0); D];
            for d in 1..D {
                p[d] = B::splat(part.axes.axis(d)[idx[d]]);
            }
            let mut k = 0;
            while k < n {
                let at = offset + k;
                p[0] = if n - k >= w { B::from_slice(&xs[first + k..]) } else { pad(&xs[first + k..first + n]) };
                // NaN where any coordinate is not finite, as point evaluation.
                let v =
                    crate::kinds::finite_or_nan(p, self.steps.combine(mode, filled.count, &Filled { at, ..filled }));
                let count = (n - k).min(w);
                store_prefix(v, &mut out[at..at + count]);
                k += w;
            }
        }
    }
}

/// A block's octaves as filled: octave i's values from `i · stride` in
/// `values`, the first `count` octaves, of the `total` the grid reads
/// (the rest add nothing: see [`Fractal::fill_span`]).
#[derive(Clone, Copy)]
struct OctaveBuffers<'a> {
    values: &'a [f32],
    stride: usize,
    count: usize,
    total: usize,
}

/// [`Steps::combine_finite`] at `level` (the best the CPU has up to it).
/// One clone per level for every fractal: the combine needs neither the
/// noise nor the dimension, and inlined into each fractal's fill it was
/// compiled again for every noise type, dimension and level (with its
/// loops unrolled per octave count, the test suite's build then ran past
/// 40 minutes).
fn combine_finite(
    level: SimdLevel,
    steps: &Steps,
    mode: FractalMode,
    octaves: OctaveBuffers<'_>,
    out: &mut [f32],
    stores: Stores,
) {
    // SAFETY: `runnable` never exceeds the features the CPU reports, and
    // the baseline clone needs none.
    unsafe {
        match crate::grid::runnable(level) {
            #[cfg(all(feature = "std", target_arch = "x86_64"))]
            SimdLevel::Avx512 => combine_clones::avx512(steps, mode, octaves, out, stores),
            #[cfg(all(feature = "std", target_arch = "x86_64"))]
            SimdLevel::Avx2 => combine_clones::avx2(steps, mode, octaves, out, stores),
            _ => combine_clones::baseline(steps, mode, octaves, out, stores),
        }
    }
}

/// [`combine_finite`]'s clones, one per instruction-set level.
mod combine_clones {
    use super::{FractalMode, OctaveBuffers, Steps, Stores};

    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    #[target_feature(enable = "avx512f,avx512bw,avx512dq,avx512vl,avx512vbmi")]
    pub(super) unsafe fn avx512(
        steps: &Steps,
        mode: FractalMode,
        octaves: OctaveBuffers<'_>,
        out: &mut [f32],
        stores: Stores,
    ) {
        steps.combine_finite::<crate::lanes::avx512::X16>(mode, octaves, out, stores)
    }

    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    #[target_feature(enable = "avx2")]
    pub(super) unsafe fn avx2(
        steps: &Steps,
        mode: FractalMode,
        octaves: OctaveBuffers<'_>,
        out: &mut [f32],
        stores: Stores,
    ) {
        steps.combine_finite::<crate::lanes::avx2::X8>(mode, octaves, out, stores)
    }

    pub(super) unsafe fn baseline(
        steps: &Steps,
        mode: FractalMode,
        octaves: OctaveBuffers<'_>,
        out: &mut [f32],
        stores: Stores,
    ) {
        steps.combine_finite::<crate::lanes::F32x8>(mode, octaves, out, stores)
    }
}

impl Steps {
    /// The octave loop over the first `count` octaves, in `mode` (a
    /// constant where the caller dispatches on the mode once, so the loop
    /// has no branch on it).
    #[inline(always)]
    fn combine<T: Arith>(&self, mode: FractalMode, count: usize, octaves: &impl Octaves<T>) -> T {
        let mut state = OctaveSum::start();
        for i in 0..count {
            let amplitude = octaves.amplitude(i, self.amplitude[i]);
            state.add_octave(mode, i, octaves.octave(i, self.frequency[i]), amplitude);
        }
        state.sum.scale_by(octaves.normalization(self.scale[count - 1]))
    }

    /// The first `count` amplitudes in lanes, formed once per block rather
    /// than per octave and chunk.
    #[inline(always)]
    fn lane_amplitudes<B: BatchLanes>(&self, count: usize) -> [B; MAX_OCTAVES as usize] {
        let mut lanes = [B::cst(0.0); MAX_OCTAVES as usize];
        for (lanes, &a) in lanes.iter_mut().zip(&self.amplitude).take(count) {
            *lanes = B::cst(a);
        }
        lanes
    }

    /// A block's `octaves` for the octave loop, with their amplitudes in
    /// lanes ([`Steps::lane_amplitudes`]) and the normalization of their
    /// `total`.
    #[inline(always)]
    fn filled<'a, B: BatchLanes>(&self, octaves: OctaveBuffers<'a>, amplitudes: &'a [B]) -> Filled<'a, B> {
        let normalization = B::cst(self.scale[octaves.total - 1]);
        Filled::new(octaves.values, octaves.stride, octaves.count, (amplitudes, normalization))
    }

    /// The grid fill's second pass over a block where every coordinate is
    /// finite (point evaluation's NaN guard then passes every value, so no
    /// positions are needed): the octave loop over the filled octaves in
    /// output order, the mode dispatched once per block.
    #[inline(always)]
    fn combine_finite<B: BatchLanes>(
        &self,
        mode: FractalMode,
        octaves: OctaveBuffers<'_>,
        out: &mut [f32],
        stores: Stores,
    ) {
        let amplitudes = self.lane_amplitudes::<B>(octaves.count);
        let filled = self.filled(octaves, &amplitudes);
        match mode {
            FractalMode::Fbm => self.combine_finite_as::<B>(FractalMode::Fbm, filled, out, stores),
            FractalMode::Turbulence => self.combine_finite_as::<B>(FractalMode::Turbulence, filled, out, stores),
            FractalMode::Ridged => self.combine_finite_as::<B>(FractalMode::Ridged, filled, out, stores),
            FractalMode::Billow => self.combine_finite_as::<B>(FractalMode::Billow, filled, out, stores),
            FractalMode::Hybrid => self.combine_finite_as::<B>(FractalMode::Hybrid, filled, out, stores),
        }
    }

    /// [`Steps::combine_finite`] in `mode`: up to 8 octaves (fBm's usual 4–8)
    /// in registers, chunk by chunk, stored as `stores` says; more, octave
    /// by octave through a run of sums, stored plainly.
    #[inline(always)]
    fn combine_finite_as<B: BatchLanes>(
        &self,
        mode: FractalMode,
        filled: Filled<'_, B>,
        out: &mut [f32],
        stores: Stores,
    ) {
        match filled.count {
            1 => self.combine_by_chunk::<B, 1>(mode, filled, out, stores),
            2 => self.combine_by_chunk::<B, 2>(mode, filled, out, stores),
            3 => self.combine_by_chunk::<B, 3>(mode, filled, out, stores),
            4 => self.combine_by_chunk::<B, 4>(mode, filled, out, stores),
            5 => self.combine_by_chunk::<B, 5>(mode, filled, out, stores),
            6 => self.combine_by_chunk::<B, 6>(mode, filled, out, stores),
            7 => self.combine_by_chunk::<B, 7>(mode, filled, out, stores),
            8 => self.combine_by_chunk::<B, 8>(mode, filled, out, stores),
            _ => self.combine_in_order::<B>(mode, filled, out),
        }
    }

    /// [`Steps::combine_finite`] for any count of octaves: in output order,
    /// [`COMBINE_RUN`] chunks of lanes at a time, octave by octave across
    /// the run. Each point still takes its octaves in order,
    /// so the bits are the octave loop's; but the loop's bookkeeping and the
    /// octave's amplitude are paid once per octave and run, not per chunk,
    /// and the run's sums stay in L1.
    ///
    /// The octaves are summed without their guard: in every mode a
    /// non-finite octave value makes its term non-finite, and a sum that
    /// was non-finite stays so, so a finite result means every octave was
    /// finite and the guard would have changed nothing. Only a chunk whose
    /// result is not finite (an octave that overflowed) is combined again
    /// with the guard.
    #[inline(always)]
    fn combine_in_order<B: BatchLanes>(&self, mode: FractalMode, filled: Filled<'_, B>, out: &mut [f32]) {
        let w = B::WIDTH;
        let mut start = 0;
        while start < out.len() {
            let len = (out.len() - start).min(COMBINE_RUN * w);
            let chunks = len.div_ceil(w);
            let mut sums = [OctaveSum::<B>::start(); COMBINE_RUN];
            for i in 0..filled.count {
                let amplitude = filled.amplitudes[i];
                for (sum, v) in sums[..chunks].iter_mut().zip(filled.values(i, start, chunks * w).chunks_exact(w)) {
                    sum.add_octave(mode, i, B::from_slice(v), amplitude);
                }
            }
            // Whole chunks apart from the last, partial one: their stores
            // need no length.
            let (whole, tail) = out[start..start + len].split_at_mut(len / w * w);
            for (k, (sum, out)) in sums.iter().zip(whole.chunks_exact_mut(w)).enumerate() {
                store_prefix(self.finish_chunk(mode, sum, Filled { at: start + k * w, ..filled }), out);
            }
            if !tail.is_empty() {
                store_prefix(
                    self.finish_chunk(mode, &sums[chunks - 1], Filled { at: start + len / w * w, ..filled }),
                    tail,
                );
            }
            start += len;
        }
    }

    /// [`Steps::combine_in_order`] for exactly `COUNT` octaves: a chunk at a
    /// time, its octaves summed in a register with their amplitudes
    /// held in registers, so nothing but the octave values is loaded and
    /// only the result is stored (6 octaves on AVX2: 32 instructions a
    /// chunk, against 48 through a run of sums in memory). The same octaves
    /// in the same order: the same bits.
    #[inline(always)]
    fn combine_by_chunk<B: BatchLanes, const COUNT: usize>(
        &self,
        mode: FractalMode,
        filled: Filled<'_, B>,
        out: &mut [f32],
        stores: Stores,
    ) {
        let w = B::WIDTH;
        // Loops, not `array::from_fn`, whose closures LLVM may leave out of
        // line, outside the instruction-set clone.
        let mut amplitudes = [B::cst(0.0); COUNT];
        let mut octaves = [core::ptr::null::<f32>(); COUNT];
        // The chunks, the last one padded, end at `padded`: checked here
        // for every octave, rather than per octave and chunk.
        let padded = out.len().div_ceil(w) * w;
        for i in 0..COUNT {
            amplitudes[i] = filled.amplitudes[i];
            octaves[i] = filled.values(i, 0, padded).as_ptr();
        }
        let (whole, tail) = out.split_at_mut(out.len() / w * w);
        let chunks = whole.len() / w;
        match stores {
            Stores::Streamed => {
                let mut run = StreamedRun::<B>::new(whole);
                for k in 0..chunks {
                    // SAFETY: k · w + w ≤ whole.len() ≤ padded.
                    run.push(unsafe { self.combined_chunk(mode, &octaves, &amplitudes, filled, k * w) });
                }
                run.finish();
            }
            Stores::Cached => {
                for (k, out) in whole.chunks_exact_mut(w).enumerate() {
                    // SAFETY: k · w + w ≤ whole.len() ≤ padded.
                    store_prefix(unsafe { self.combined_chunk(mode, &octaves, &amplitudes, filled, k * w) }, out);
                }
            }
        }
        if !tail.is_empty() {
            // SAFETY: whole.len() + w = padded.
            store_prefix(unsafe { self.combined_chunk(mode, &octaves, &amplitudes, filled, whole.len()) }, tail);
        }
    }

    /// [`Steps::combine_by_chunk`]'s value of the chunk at `at`.
    ///
    /// # Safety
    /// Each `octaves[i]` points to at least `at + B::WIDTH` readable values.
    #[inline(always)]
    unsafe fn combined_chunk<B: BatchLanes, const COUNT: usize>(
        &self,
        mode: FractalMode,
        octaves: &[*const f32; COUNT],
        amplitudes: &[B; COUNT],
        filled: Filled<'_, B>,
        at: usize,
    ) -> B {
        // SAFETY: the caller's promise.
        let sum = unsafe { sum_chunk(mode, octaves, amplitudes, at) };
        self.finish_chunk(mode, &sum, Filled { at, ..filled })
    }

    /// A chunk of [`Steps::combine_in_order`] from its unguarded sum,
    /// combined again with the guard where that is not finite.
    #[inline(always)]
    fn finish_chunk<B: BatchLanes>(&self, mode: FractalMode, sum: &OctaveSum<B>, filled: Filled<'_, B>) -> B {
        let v = sum.sum.scale_by(filled.normalization);
        if B::any(!crate::kinds::is_finite(v)) {
            self.combine(mode, filled.count, &filled)
        } else {
            v
        }
    }
}

/// Chunks of lanes per run of [`Steps::combine_in_order`]: 64 keeps a
/// run's sums in 4 KiB (AVX2) to 8 KiB (AVX-512).
const COMBINE_RUN: usize = 64;

/// A chunk's octaves summed in order: octave i's lanes at `at` from
/// `octaves[i]`, at `amplitudes[i]`.
///
/// # Safety
/// Each `octaves[i]` points to at least `at + B::WIDTH` readable values.
#[inline(always)]
unsafe fn sum_chunk<B: BatchLanes, const COUNT: usize>(
    mode: FractalMode,
    octaves: &[*const f32; COUNT],
    amplitudes: &[B; COUNT],
    at: usize,
) -> OctaveSum<B> {
    let mut sum = OctaveSum::start();
    for i in 0..COUNT {
        // SAFETY: the caller's promise.
        let lanes = unsafe { core::slice::from_raw_parts(octaves[i].add(at), B::WIDTH) };
        sum.add_octave(mode, i, B::from_slice(lanes), amplitudes[i]);
    }
    sum
}

/// Lanes from up to WIDTH values, the last repeated.
#[inline(always)]
fn pad<B: BatchLanes>(v: &[f32]) -> B {
    let mut lanes = [0f32; 16];
    for (j, x) in lanes.iter_mut().enumerate().take(B::WIDTH) {
        *x = v[j.min(v.len() - 1)];
    }
    B::from_slice(&lanes)
}

/// Analytic derivatives through every mode, where the base has them.
impl<N: NoiseGradient<D>, const D: usize> NoiseGradient<D> for Fractal<N> {
    #[inline(always)]
    fn sample_gradient<L: Lanes>(&self, p: [L; D]) -> (L, [L; D]) {
        let d = self.combine(&GradientAtPoint { noises: &self.octaves, p });
        let mut g = d.d;
        for c in g.iter_mut() {
            *c = crate::kinds::finite_or_nan(p, *c);
        }
        (crate::kinds::finite_or_nan(p, d.v), g)
    }
}

// This module's batch drivers per instruction-set level (`grid::batch_clones!`).
crate::grid::batch_clones!();
