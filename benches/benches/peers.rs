//! noiselab against its peers on the performance note's workloads
//! (/work/shared/notes/performance.md), every peer on every workload it
//! supports, each through its fastest public API as the note describes.
//!
//! Workloads (one thread; grid sample i sits at i · 1/32 from the origin,
//! row-major, x fastest; output into a reused buffer touched before timing):
//!
//! | group | workload |
//! |---|---|
//! | `2d_perlin` `2d_simplex` `2d_value` `2d_cellular_f1` `2d_fbm6` | 2048² grid |
//! | `2d_perlin_tiles` `2d_fbm6_tiles` | the same 2048² samples as 64 × 64 tiles of 32², one call per tile, each tile's 1024 values contiguous (game chunks: per-call and per-row costs count) |
//! | `3d_perlin` `3d_simplex` | 256³ grid |
//! | `3d_perlin_points` | 4 000 000 splitmix64 points in [−1000, 1000]³ |
//! | `scalar_f64_3d_perlin_grid` / `_points` | one `f64` call per point: noiselab `Improved::get` vs noise-rs `Perlin::get` |
//!
//! Function ids are the library names (`noiselab`, `noise-rs`,
//! `fastnoise-lite`, `simdnoise`, `libnoise`, `quick-noise`,
//! `quick-noise-batch`, `noise-functions`, `noiz`), so `perf_table` can read
//! `target/criterion/<group>/<lib>/new/`. `quick-noise` is its uniform-grid
//! API where it has one (Perlin 2D/3D, value 2D, cellular 2D, fBm 2D; the 3D
//! grid is written z fastest, the crate's own order) and its batch API
//! elsewhere; `quick-noise-batch` is the batch API on those grid workloads.
//! The tile groups run only the libraries with a uniform-grid API (a
//! per-point API costs the same per point in tiles as in one grid).
//! quick-noise's fractal grid fill leaves out every octave of 1 cell per
//! sample or more (`NoiseConfig::num_grid_octaves`), keeping the full
//! normalization, so its "6 octaves" at 1/32 sum 5 (measured: its 6-octave
//! output is its 5-octave output × 0.984 = Σ₅/Σ₆, in about the same time).
//! On this grid octave 5 lies on the lattice at every sample, where gradient
//! noise is 0, so the values are the 6-octave sum all the same.
//! `noiselab-limited` is noiselab's `Fractal::band_limited()` (Perlin's
//! two-samples rule), which also sums 5, normalized over those 5.
//! simdnoise has no Perlin, so its `2d_fbm6` is fBm of simplex; its block API
//! returns a fresh `Vec` every call, which is timed (as a user pays it).
//!
//! Before a benchmark's first timed iteration, its output is computed once
//! (untimed) into a buffer pre-filled with NaN, and one line `case lib min
//! max` goes to stderr; a constant or non-finite output is flagged `BROKEN`.
//! Run a subset with criterion's filter, e.g.
//! `cargo bench --manifest-path benches/Cargo.toml --bench peers -- 2d_perlin`.

use std::hint::black_box;

use criterion::measurement::WallTime;
use criterion::{criterion_group, criterion_main, BenchmarkGroup, Criterion, Throughput};
use fastnoise_lite::{CellularDistanceFunction, CellularReturnType, FastNoiseLite, FractalType, NoiseType};
use libnoise::Generator as _;
use noise::{MultiFractal as _, NoiseFn as _};
use noise_functions::Noise as _;
use noiselab::{Fractal, FractalMode, Grid, Improved, Noise as LabNoise};
use noiz::{SampleableFor as _, SeedableNoise as _};

const SPACING: f64 = 1.0 / 32.0;
const SPACING_F32: f32 = 1.0 / 32.0;
const SEED: u32 = 1337;
const SIDE_2D: usize = 2048;
const SIDE_3D: usize = 256;
const POINTS: usize = 4_000_000;
/// Side of a tile in the tile groups (2048 / 32 = 64 tiles a side).
const TILE: usize = 32;

// ---------------------------------------------------------------- harness

/// An output element: `f32` for the batch/peer cases, `f64` for the scalar
/// `f64` groups.
trait Out: Copy {
    const NAN: Self;
    fn to_f64(self) -> f64;
}
impl Out for f32 {
    const NAN: f32 = f32::NAN;
    fn to_f64(self) -> f64 {
        self as f64
    }
}
impl Out for f64 {
    const NAN: f64 = f64::NAN;
    fn to_f64(self) -> f64 {
        self
    }
}

/// Prints `case lib min max` (stderr), flagging constant or non-finite output.
fn sanity<T: Out>(case: &str, lib: &str, values: &[T]) {
    let (mut min, mut max, mut bad) = (f64::INFINITY, f64::NEG_INFINITY, 0usize);
    for v in values {
        let v = v.to_f64();
        if v.is_finite() {
            min = min.min(v);
            max = max.max(v);
        } else {
            bad += 1;
        }
    }
    let mut verdict = String::new();
    if bad > 0 {
        verdict += &format!(" BROKEN({bad} of {} non-finite)", values.len());
    }
    if min >= max {
        verdict += " BROKEN(constant)";
    }
    eprintln!("{case} {lib} {min:.6} {max:.6}{verdict}");
}

/// One criterion group = one workload; every benchmark in it runs once
/// untimed for the sanity line, then is timed.
struct Case<'c> {
    name: &'static str,
    group: BenchmarkGroup<'c, WallTime>,
}

impl<'c> Case<'c> {
    fn new(c: &'c mut Criterion, name: &'static str, elements: usize) -> Self {
        let mut group = c.benchmark_group(name);
        group.sample_size(10).throughput(Throughput::Elements(elements as u64));
        Case { name, group }
    }

    /// A benchmark writing into the reused buffer `out`.
    fn fill<T: Out>(&mut self, lib: &str, out: &mut [T], mut f: impl FnMut(&mut [T])) {
        let name = self.name;
        let mut checked = false;
        self.group.bench_function(lib, |b| {
            if !checked {
                checked = true;
                out.fill(T::NAN);
                f(out);
                sanity(name, lib, out);
            }
            b.iter(|| {
                f(out);
                black_box(&mut *out);
            })
        });
    }

    /// A benchmark whose API returns a fresh `Vec` (allocation and drop timed).
    fn fresh(&mut self, lib: &str, mut f: impl FnMut() -> Vec<f32>) {
        let name = self.name;
        let mut checked = false;
        self.group.bench_function(lib, |b| {
            if !checked {
                checked = true;
                sanity(name, lib, &f());
            }
            b.iter(|| black_box(f()))
        });
    }

    fn finish(self) {
        self.group.finish();
    }
}

/// A buffer whose pages are touched (written) before any timing.
fn buffer<T: Out>(n: usize) -> Vec<T> {
    vec![T::NAN; n]
}

// ------------------------------------------------------- point-wise loops

#[inline(always)]
fn loop2_f64(out: &mut [f32], f: impl Fn(f64, f64) -> f64) {
    for (j, row) in out.chunks_exact_mut(SIDE_2D).enumerate() {
        let y = j as f64 * SPACING;
        for (i, o) in row.iter_mut().enumerate() {
            *o = f(i as f64 * SPACING, y) as f32;
        }
    }
}

#[inline(always)]
fn loop2_f32(out: &mut [f32], f: impl Fn(f32, f32) -> f32) {
    for (j, row) in out.chunks_exact_mut(SIDE_2D).enumerate() {
        let y = j as f32 * SPACING_F32;
        for (i, o) in row.iter_mut().enumerate() {
            *o = f(i as f32 * SPACING_F32, y);
        }
    }
}

#[inline(always)]
fn loop3_f64<T: Out>(out: &mut [T], f: impl Fn(f64, f64, f64) -> T) {
    for (k, slice) in out.chunks_exact_mut(SIDE_3D * SIDE_3D).enumerate() {
        let z = k as f64 * SPACING;
        for (j, row) in slice.chunks_exact_mut(SIDE_3D).enumerate() {
            let y = j as f64 * SPACING;
            for (i, o) in row.iter_mut().enumerate() {
                *o = f(i as f64 * SPACING, y, z);
            }
        }
    }
}

#[inline(always)]
fn loop3_f32(out: &mut [f32], f: impl Fn(f32, f32, f32) -> f32) {
    for (k, slice) in out.chunks_exact_mut(SIDE_3D * SIDE_3D).enumerate() {
        let z = k as f32 * SPACING_F32;
        for (j, row) in slice.chunks_exact_mut(SIDE_3D).enumerate() {
            let y = j as f32 * SPACING_F32;
            for (i, o) in row.iter_mut().enumerate() {
                *o = f(i as f32 * SPACING_F32, y, z);
            }
        }
    }
}

#[inline(always)]
fn loop_points<P: Copy, T>(out: &mut [T], points: &[P], f: impl Fn(P) -> T) {
    for (o, &p) in out.iter_mut().zip(points) {
        *o = f(p);
    }
}

// ------------------------------------------------------------------ peers

fn fnl(kind: NoiseType) -> FastNoiseLite {
    let mut n = FastNoiseLite::with_seed(SEED as i32);
    n.set_noise_type(Some(kind));
    n.set_frequency(Some(1.0));
    n
}

fn fnl_cellular() -> FastNoiseLite {
    let mut n = fnl(NoiseType::Cellular);
    n.set_cellular_distance_function(Some(CellularDistanceFunction::Euclidean));
    n.set_cellular_return_type(Some(CellularReturnType::Distance));
    n
}

fn fnl_fbm() -> FastNoiseLite {
    let mut n = fnl(NoiseType::Perlin);
    n.set_fractal_type(Some(FractalType::FBm));
    n.set_fractal_octaves(Some(6));
    n.set_fractal_lacunarity(Some(2.0));
    n.set_fractal_gain(Some(0.5));
    n
}

fn rs_fbm() -> noise::Fbm<noise::Perlin> {
    noise::Fbm::<noise::Perlin>::new(SEED).set_octaves(6).set_frequency(1.0).set_lacunarity(2.0).set_persistence(0.5)
}

/// noiz: the quintic fade 6t⁵ − 15t⁴ + 10t³ of improved Perlin noise (noiz
/// ships only the cubic `Smoothstep`).
#[derive(Default, Clone, Copy, PartialEq)]
struct Quintic;

impl bevy_curve::Curve<f32> for Quintic {
    #[inline]
    fn domain(&self) -> bevy_curve::Interval {
        bevy_curve::Interval::UNIT
    }

    #[inline]
    fn sample_unchecked(&self, t: f32) -> f32 {
        t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
    }
}

mod nz {
    use noiz::prelude::*;
    pub type Perlin = MixCellGradients<OrthoGrid, super::Quintic, QuickGradients>;
    pub type Simplex = common_noise::Simplex;
    pub type Value = common_noise::Value;
    pub type Worley = common_noise::Worley;
    pub type Fbm = LayeredNoise<Normed<f32>, Persistence, FractalLayers<Octave<Perlin>>>;

    pub fn fbm() -> Fbm {
        LayeredNoise::new(
            Normed::default(),
            Persistence(0.5),
            FractalLayers { layer: Octave(Perlin::default()), lacunarity: 2.0, amount: 6 },
        )
    }
}

/// noiz `Noise<N>` at seed 1337, frequency 1.
fn noiz_seeded<N>(n: N) -> noiz::Noise<N> {
    let mut n = noiz::Noise::from(n);
    n.set_seed(SEED);
    n
}

/// quick-noise, each call inside a `#[dispatch_simd]` function so the SIMD
/// level (AVX-512 where present) is picked at run time in any build.
mod qn {
    use quick_noise::simd::{dispatch_simd, SimdSliceIterExt};
    use quick_noise::{BatchGenerator, BatchNoise, Fbm, Grid, GridGenerator};

    const FREQ: f32 = 1.0 / 32.0;

    /// Uniform-grid API, 2D, `side`², x fastest, at grid position `at`
    /// (in units of `side`: (0, 0) for a whole grid, a tile's indices for
    /// a tile).
    #[dispatch_simd(A)]
    pub fn grid2<G: GridGenerator<2>>(side: usize, at: (usize, usize), octaves: usize, out: &mut [f32]) {
        Grid::<2, A>::new(side, side)
            .grid_position(at.0 as f64, at.1 as f64)
            .seed(1337)
            .builder::<Fbm, G>()
            .octaves(octaves)
            .frequency(FREQ)
            .lacunarity(2.0)
            .persistence(0.5)
            .fill(out);
    }

    /// Uniform-grid API, 3D, `side`³ (written z fastest by the crate).
    #[dispatch_simd(A)]
    pub fn grid3<G: GridGenerator<3>>(side: usize, out: &mut [f32]) {
        Grid::<3, A>::new(side, side, side).seed(1337).builder::<Fbm, G>().frequency(FREQ).fill(out);
    }

    /// Batch API on the grid's own coordinate iterators, 2D, x fastest.
    #[dispatch_simd(A)]
    pub fn batch2<G: BatchGenerator<2>>(side: usize, octaves: usize, out: &mut [f32]) {
        let grid = Grid::<2, A>::new(side, side);
        BatchNoise::<2, Fbm, G>::builder(grid.x_iter(), grid.y_iter())
            .seed(1337)
            .octaves(octaves)
            .frequency(FREQ)
            .lacunarity(2.0)
            .persistence(0.5)
            .fill(out);
    }

    /// Batch API on the grid's own coordinate iterators, 3D, x fastest.
    #[dispatch_simd(A)]
    pub fn batch3<G: BatchGenerator<3>>(side: usize, out: &mut [f32]) {
        let grid = Grid::<3, A>::new(side, side, side);
        BatchNoise::<3, Fbm, G>::builder(grid.x_iter(), grid.y_iter(), grid.z_iter())
            .seed(1337)
            .frequency(FREQ)
            .fill(out);
    }

    /// Batch API on arbitrary points, one slice per axis, frequency 1.
    #[dispatch_simd(A)]
    pub fn points3<G: BatchGenerator<3>>(x: &[f32], y: &[f32], z: &[f32], out: &mut [f32]) {
        BatchNoise::<3, Fbm, G>::builder(x.simd_iter::<A>(), y.simd_iter::<A>(), z.simd_iter::<A>())
            .seed(1337)
            .frequency(1.0)
            .fill(out);
    }
}

/// simdnoise block settings, spacing 1/32 (it samples integer indices × freq).
fn sd_freq() -> f32 {
    SPACING_F32
}

// -------------------------------------------------------------- workloads

fn grids_2d(c: &mut Criterion) {
    let n = SIDE_2D * SIDE_2D;
    let grid = Grid::new([0.0; 2], [SPACING; 2], [SIDE_2D, SIDE_2D]);
    let mut out = buffer::<f32>(n);
    let out = &mut out[..];

    // Perlin (improved, quintic fade).
    let mut g = Case::new(c, "2d_perlin", n);
    let lab = Improved::new(SEED);
    g.fill("noiselab", out, |o| lab.fill_grid(&grid, o).unwrap());
    g.fill("noiselab-fast", out, |o| lab.fill_grid_fast(&grid, o).unwrap());
    let rs = noise::Perlin::new(SEED);
    g.fill("noise-rs", out, |o| loop2_f64(o, |x, y| rs.get([x, y])));
    let lite = fnl(NoiseType::Perlin);
    g.fill("fastnoise-lite", out, |o| loop2_f32(o, |x, y| lite.get_noise_2d(x, y)));
    let lib = libnoise::Source::<2>::improved_perlin(SEED as u64);
    g.fill("libnoise", out, |o| loop2_f64(o, |x, y| lib.sample([x, y])));
    g.fill("quick-noise", out, |o| qn::grid2::<quick_noise::Perlin>(SIDE_2D, (0, 0), 1, o));
    g.fill("quick-noise-batch", out, |o| qn::batch2::<quick_noise::Perlin>(SIDE_2D, 1, o));
    let nf = noise_functions::Perlin.seed(SEED as i32);
    g.fill("noise-functions", out, |o| loop2_f32(o, |x, y| nf.sample2([x, y])));
    let nz = noiz_seeded(nz::Perlin::default());
    g.fill("noiz", out, |o| loop2_f32(o, |x, y| nz.sample(bevy_math::Vec2::new(x, y))));
    g.finish();

    // Simplex (each library's own variant).
    let mut g = Case::new(c, "2d_simplex", n);
    let lab = noiselab::Simplex::new(SEED);
    g.fill("noiselab", out, |o| lab.fill_grid(&grid, o).unwrap());
    let rs = noise::Simplex::new(SEED);
    g.fill("noise-rs", out, |o| loop2_f64(o, |x, y| rs.get([x, y])));
    let lite = fnl(NoiseType::OpenSimplex2);
    g.fill("fastnoise-lite", out, |o| loop2_f32(o, |x, y| lite.get_noise_2d(x, y)));
    let sd = *simdnoise::NoiseBuilder::gradient_2d(SIDE_2D, SIDE_2D).with_freq(sd_freq()).with_seed(SEED as i32);
    g.fresh("simdnoise", || sd.generate().0);
    let lib = libnoise::Source::<2>::simplex(SEED as u64);
    g.fill("libnoise", out, |o| loop2_f64(o, |x, y| lib.sample([x, y])));
    g.fill("quick-noise", out, |o| qn::batch2::<quick_noise::Simplex>(SIDE_2D, 1, o));
    let nf = noise_functions::Simplex.seed(SEED as i32);
    g.fill("noise-functions", out, |o| loop2_f32(o, |x, y| nf.sample2([x, y])));
    let nz = noiz_seeded(nz::Simplex::default());
    g.fill("noiz", out, |o| loop2_f32(o, |x, y| nz.sample(bevy_math::Vec2::new(x, y))));
    g.finish();

    // Value.
    let mut g = Case::new(c, "2d_value", n);
    let lab = noiselab::Value::new(SEED);
    g.fill("noiselab", out, |o| lab.fill_grid(&grid, o).unwrap());
    g.fill("noiselab-fast", out, |o| lab.fill_grid_fast(&grid, o).unwrap());
    let rs = noise::Value::new(SEED);
    g.fill("noise-rs", out, |o| loop2_f64(o, |x, y| rs.get([x, y])));
    let lite = fnl(NoiseType::Value);
    g.fill("fastnoise-lite", out, |o| loop2_f32(o, |x, y| lite.get_noise_2d(x, y)));
    let lib = libnoise::Source::<2>::value(SEED as u64);
    g.fill("libnoise", out, |o| loop2_f64(o, |x, y| lib.sample([x, y])));
    g.fill("quick-noise", out, |o| qn::grid2::<quick_noise::Value>(SIDE_2D, (0, 0), 1, o));
    g.fill("quick-noise-batch", out, |o| qn::batch2::<quick_noise::Value>(SIDE_2D, 1, o));
    let nf = noise_functions::Value.seed(SEED as i32);
    g.fill("noise-functions", out, |o| loop2_f32(o, |x, y| nf.sample2([x, y])));
    let nz = noiz_seeded(nz::Value::default());
    g.fill("noiz", out, |o| loop2_f32(o, |x, y| nz.sample(bevy_math::Vec2::new(x, y))));
    g.finish();

    // Cellular F1, Euclidean distance.
    let mut g = Case::new(c, "2d_cellular_f1", n);
    let lab = noiselab::Worley::new(SEED);
    g.fill("noiselab", out, |o| lab.fill_grid(&grid, o).unwrap());
    let rs = noise::Worley::new(SEED).set_return_type(noise::core::worley::ReturnType::Distance);
    g.fill("noise-rs", out, |o| loop2_f64(o, |x, y| rs.get([x, y])));
    let lite = fnl_cellular();
    g.fill("fastnoise-lite", out, |o| loop2_f32(o, |x, y| lite.get_noise_2d(x, y)));
    let sd = *simdnoise::NoiseBuilder::cellular_2d(SIDE_2D, SIDE_2D)
        .with_freq(sd_freq())
        .with_seed(SEED as i32)
        .with_distance_function(simdnoise::CellDistanceFunction::Euclidean)
        .with_return_type(simdnoise::CellReturnType::Distance);
    g.fresh("simdnoise", || sd.generate().0);
    let lib = libnoise::Source::<2>::worley(SEED as u64);
    g.fill("libnoise", out, |o| loop2_f64(o, |x, y| lib.sample([x, y])));
    g.fill("quick-noise", out, |o| qn::grid2::<quick_noise::Cellular>(SIDE_2D, (0, 0), 1, o));
    g.fill("quick-noise-batch", out, |o| qn::batch2::<quick_noise::Cellular>(SIDE_2D, 1, o));
    let nf = noise_functions::CellDistance::default().seed(SEED as i32);
    g.fill("noise-functions", out, |o| loop2_f32(o, |x, y| nf.sample2([x, y])));
    let nz = noiz_seeded(nz::Worley::default());
    g.fill("noiz", out, |o| loop2_f32(o, |x, y| nz.sample(bevy_math::Vec2::new(x, y))));
    g.finish();

    // fBm of Perlin, 6 octaves, lacunarity 2, gain 0.5 (simdnoise: of simplex).
    let mut g = Case::new(c, "2d_fbm6", n);
    let lab = Fractal::new(|o| Improved::new(o.seed), SEED, 6, FractalMode::Fbm).unwrap();
    g.fill("noiselab", out, |o| lab.fill_grid(&grid, o).unwrap());
    g.fill("noiselab-fast", out, |o| lab.fill_grid_fast(&grid, o).unwrap());
    // Perlin's rule keeps 5 octaves at 1/32 (octave 5 has a cell per sample,
    // where gradient noise is 0 on this grid); quick-noise drops it too.
    let limited = lab.clone().band_limited();
    g.fill("noiselab-limited", out, |o| limited.fill_grid(&grid, o).unwrap());
    let rs = rs_fbm();
    g.fill("noise-rs", out, |o| loop2_f64(o, |x, y| rs.get([x, y])));
    let lite = fnl_fbm();
    g.fill("fastnoise-lite", out, |o| loop2_f32(o, |x, y| lite.get_noise_2d(x, y)));
    let sd = *simdnoise::NoiseBuilder::fbm_2d(SIDE_2D, SIDE_2D)
        .with_freq(sd_freq())
        .with_seed(SEED as i32)
        .with_octaves(6)
        .with_lacunarity(2.0)
        .with_gain(0.5);
    g.fresh("simdnoise", || sd.generate().0);
    let lib = libnoise::Source::<2>::improved_perlin(SEED as u64).fbm(6, 1.0, 2.0, 0.5);
    g.fill("libnoise", out, |o| loop2_f64(o, |x, y| lib.sample([x, y])));
    g.fill("quick-noise", out, |o| qn::grid2::<quick_noise::Perlin>(SIDE_2D, (0, 0), 6, o));
    g.fill("quick-noise-batch", out, |o| qn::batch2::<quick_noise::Perlin>(SIDE_2D, 6, o));
    let nf = noise_functions::Perlin.fbm(6, 0.5, 2.0).seed(SEED as i32);
    g.fill("noise-functions", out, |o| loop2_f32(o, |x, y| nf.sample2([x, y])));
    let nz = noiz_seeded(nz::fbm());
    g.fill("noiz", out, |o| loop2_f32(o, |x, y| nz.sample(bevy_math::Vec2::new(x, y))));
    g.finish();
}

/// The 2048² grid as tiles of `TILE`², one fill call each (tile-major
/// output), for the libraries with a uniform-grid API.
fn tiles_2d(c: &mut Criterion) {
    let n = SIDE_2D * SIDE_2D;
    let per_side = SIDE_2D / TILE;
    // Tile t is (t mod per_side, t div per_side); its samples are the big grid's.
    let tiles: Vec<(usize, usize)> = (0..per_side * per_side).map(|t| (t % per_side, t / per_side)).collect();
    let grids: Vec<Grid<2>> = tiles
        .iter()
        .map(|&(i, j)| {
            Grid::new([(i * TILE) as f64 * SPACING, (j * TILE) as f64 * SPACING], [SPACING; 2], [TILE, TILE])
        })
        .collect();
    let mut out = buffer::<f32>(n);
    let out = &mut out[..];

    let mut g = Case::new(c, "2d_perlin_tiles", n);
    let lab = Improved::new(SEED);
    g.fill("noiselab", out, |o| each_tile(o, |t, tile| lab.fill_grid(&grids[t], tile).unwrap()));
    g.fill("noiselab-fast", out, |o| each_tile(o, |t, tile| lab.fill_grid_fast(&grids[t], tile).unwrap()));
    g.fill("quick-noise", out, |o| each_tile(o, |t, tile| qn::grid2::<quick_noise::Perlin>(TILE, tiles[t], 1, tile)));
    g.finish();

    let mut g = Case::new(c, "2d_fbm6_tiles", n);
    let lab = Fractal::new(|o| Improved::new(o.seed), SEED, 6, FractalMode::Fbm).unwrap();
    g.fill("noiselab", out, |o| each_tile(o, |t, tile| lab.fill_grid(&grids[t], tile).unwrap()));
    g.fill("noiselab-fast", out, |o| each_tile(o, |t, tile| lab.fill_grid_fast(&grids[t], tile).unwrap()));
    let limited = lab.clone().band_limited();
    g.fill("noiselab-limited", out, |o| each_tile(o, |t, tile| limited.fill_grid(&grids[t], tile).unwrap()));
    g.fill("quick-noise", out, |o| each_tile(o, |t, tile| qn::grid2::<quick_noise::Perlin>(TILE, tiles[t], 6, tile)));
    g.finish();
}

/// `f(t, tile)` for each tile of `out`, in order.
#[inline(always)]
fn each_tile(out: &mut [f32], mut f: impl FnMut(usize, &mut [f32])) {
    for (t, tile) in out.chunks_exact_mut(TILE * TILE).enumerate() {
        f(t, tile);
    }
}

fn grids_3d(c: &mut Criterion) {
    let n = SIDE_3D * SIDE_3D * SIDE_3D;
    let grid = Grid::new([0.0; 3], [SPACING; 3], [SIDE_3D; 3]);
    let mut out = buffer::<f32>(n);
    let out = &mut out[..];

    let mut g = Case::new(c, "3d_perlin", n);
    let lab = Improved::new(SEED);
    g.fill("noiselab", out, |o| lab.fill_grid(&grid, o).unwrap());
    g.fill("noiselab-fast", out, |o| lab.fill_grid_fast(&grid, o).unwrap());
    let rs = noise::Perlin::new(SEED);
    g.fill("noise-rs", out, |o| loop3_f64(o, |x, y, z| rs.get([x, y, z]) as f32));
    let lite = fnl(NoiseType::Perlin);
    g.fill("fastnoise-lite", out, |o| loop3_f32(o, |x, y, z| lite.get_noise_3d(x, y, z)));
    let lib = libnoise::Source::<3>::improved_perlin(SEED as u64);
    g.fill("libnoise", out, |o| loop3_f64(o, |x, y, z| lib.sample([x, y, z]) as f32));
    g.fill("quick-noise", out, |o| qn::grid3::<quick_noise::Perlin>(SIDE_3D, o));
    g.fill("quick-noise-batch", out, |o| qn::batch3::<quick_noise::Perlin>(SIDE_3D, o));
    let nf = noise_functions::Perlin.seed(SEED as i32);
    g.fill("noise-functions", out, |o| loop3_f32(o, |x, y, z| nf.sample3([x, y, z])));
    let nz = noiz_seeded(nz::Perlin::default());
    g.fill("noiz", out, |o| loop3_f32(o, |x, y, z| nz.sample(bevy_math::Vec3::new(x, y, z))));
    g.finish();

    let mut g = Case::new(c, "3d_simplex", n);
    let lab = noiselab::Simplex::new(SEED);
    g.fill("noiselab", out, |o| lab.fill_grid(&grid, o).unwrap());
    let rs = noise::Simplex::new(SEED);
    g.fill("noise-rs", out, |o| loop3_f64(o, |x, y, z| rs.get([x, y, z]) as f32));
    let lite = fnl(NoiseType::OpenSimplex2);
    g.fill("fastnoise-lite", out, |o| loop3_f32(o, |x, y, z| lite.get_noise_3d(x, y, z)));
    let sd =
        *simdnoise::NoiseBuilder::gradient_3d(SIDE_3D, SIDE_3D, SIDE_3D).with_freq(sd_freq()).with_seed(SEED as i32);
    g.fresh("simdnoise", || sd.generate().0);
    let lib = libnoise::Source::<3>::simplex(SEED as u64);
    g.fill("libnoise", out, |o| loop3_f64(o, |x, y, z| lib.sample([x, y, z]) as f32));
    g.fill("quick-noise", out, |o| qn::batch3::<quick_noise::Simplex>(SIDE_3D, o));
    let nf = noise_functions::Simplex.seed(SEED as i32);
    g.fill("noise-functions", out, |o| loop3_f32(o, |x, y, z| nf.sample3([x, y, z])));
    let nz = noiz_seeded(nz::Simplex::default());
    g.fill("noiz", out, |o| loop3_f32(o, |x, y, z| nz.sample(bevy_math::Vec3::new(x, y, z))));
    g.finish();
}

/// 4 M splitmix64 points in [−1000, 1000)³, in f64 and rounded to f32.
fn random_points() -> Vec<[f64; 3]> {
    let mut rng = noiselab::hash::SplitMix64(0x9E37_79B9_7F4A_7C15);
    let mut next = move || (rng.next() >> 11) as f64 / (1u64 << 53) as f64 * 2000.0 - 1000.0;
    (0..POINTS).map(|_| [next(), next(), next()]).collect()
}

fn points_3d(c: &mut Criterion) {
    let p64 = random_points();
    let p32: Vec<[f32; 3]> = p64.iter().map(|p| p.map(|v| v as f32)).collect();
    let axis = |d: usize| -> Vec<f32> { p32.iter().map(|p| p[d]).collect() };
    let (xs, ys, zs) = (axis(0), axis(1), axis(2));
    let mut out = buffer::<f32>(POINTS);
    let out = &mut out[..];

    let mut g = Case::new(c, "3d_perlin_points", POINTS);
    let lab = Improved::new(SEED);
    g.fill("noiselab", out, |o| LabNoise::<3>::fill_points(&lab, &p32, o).unwrap());
    let rs = noise::Perlin::new(SEED);
    g.fill("noise-rs", out, |o| loop_points(o, &p64, |p| rs.get(p) as f32));
    let lite = fnl(NoiseType::Perlin);
    g.fill("fastnoise-lite", out, |o| loop_points(o, &p32, |p| lite.get_noise_3d(p[0], p[1], p[2])));
    let lib = libnoise::Source::<3>::improved_perlin(SEED as u64);
    g.fill("libnoise", out, |o| loop_points(o, &p64, |p| lib.sample(p) as f32));
    g.fill("quick-noise", out, |o| qn::points3::<quick_noise::Perlin>(&xs, &ys, &zs, o));
    let nf = noise_functions::Perlin.seed(SEED as i32);
    g.fill("noise-functions", out, |o| loop_points(o, &p32, |p| nf.sample3(p)));
    let nz = noiz_seeded(nz::Perlin::default());
    g.fill("noiz", out, |o| loop_points(o, &p32, |p| nz.sample(bevy_math::Vec3::from_array(p))));
    g.finish();

    // Scalar f64 single-point calls on the same points.
    let mut out64 = buffer::<f64>(POINTS);
    let mut g = Case::new(c, "scalar_f64_3d_perlin_points", POINTS);
    g.fill("noiselab", &mut out64[..], |o| loop_points(o, &p64, |p| LabNoise::<3>::get(&lab, p)));
    g.fill("noise-rs", &mut out64[..], |o| loop_points(o, &p64, |p| rs.get(p)));
    g.finish();
}

fn scalar_grid(c: &mut Criterion) {
    let n = SIDE_3D * SIDE_3D * SIDE_3D;
    let mut out = buffer::<f64>(n);
    let out = &mut out[..];
    let mut g = Case::new(c, "scalar_f64_3d_perlin_grid", n);
    let lab = Improved::new(SEED);
    g.fill("noiselab", out, |o| loop3_f64(o, |x, y, z| LabNoise::<3>::get(&lab, [x, y, z])));
    let rs = noise::Perlin::new(SEED);
    g.fill("noise-rs", out, |o| loop3_f64(o, |x, y, z| rs.get([x, y, z])));
    g.finish();
}

/// The kinds no peer has, on the same grids: sparse convolution noise
/// (splatted and gathered, 20 impulses per cell) and the fast volume-texture
/// approximation.
fn ours_only(c: &mut Criterion) {
    let n = SIDE_2D * SIDE_2D;
    let grid = Grid::new([0.0; 2], [SPACING; 2], [SIDE_2D, SIDE_2D]);
    let mut out = buffer::<f32>(n);
    let out = &mut out[..];
    let mut g = Case::new(c, "2d_sparse", n);
    let sparse = noiselab::Sparse::new(SEED);
    g.fill("noiselab", out, |o| sparse.splat_grid(&grid, o).unwrap());
    g.fill("noiselab-gather", out, |o| LabNoise::<2>::fill_grid(&sparse, &grid, o).unwrap());
    g.finish();

    let n = SIDE_3D * SIDE_3D * SIDE_3D;
    let grid = Grid::new([0.0; 3], [SPACING; 3], [SIDE_3D; 3]);
    let mut out = buffer::<f32>(n);
    let out = &mut out[..];
    let mut g = Case::new(c, "3d_fast_texture", n);
    let fast = noiselab::Fast::new(SEED);
    g.fill("noiselab", out, |o| LabNoise::<3>::fill_grid(&fast, &grid, o).unwrap());
    g.finish();
}

criterion_group!(benches, grids_2d, tiles_2d, grids_3d, points_3d, scalar_grid, ours_only);
criterion_main!(benches);
