//! Instruction counts of the main kernels under valgrind's callgrind
//! (through gungraun): repeatable on a shared, noisy machine where
//! wall-clock times are not. Needs valgrind and the matching runner
//! (`cargo install gungraun-runner --version 0.20.0`); run with
//! `cargo bench --manifest-path benches/Cargo.toml --bench instructions`.
//!
//! Valgrind emulates up to AVX2, so these count the AVX2 clones (eight
//! lanes), not the AVX-512 ones the criterion benchmarks time.

use std::hint::black_box;

use gungraun::prelude::*;
use noiselab::{Fractal, FractalMode, Grid, Improved, Noise, Simplex, Value, Worley};

const STEP: f64 = 1.0 / 32.0;

fn grid2() -> (Grid<2>, Vec<f32>) {
    let grid = Grid::new([0.0; 2], [STEP; 2], [256, 256]);
    (grid, vec![0f32; grid.len()])
}

/// The 256² grid of `grid2` as 64 tiles of 32², one fill call each
/// (game chunks): against `grid2`'s counts, the cost per call and per row.
fn tiles2() -> (Vec<Grid<2>>, Vec<f32>) {
    let tiles = (0..64)
        .map(|t| Grid::new([(t % 8 * 32) as f64 * STEP, (t / 8 * 32) as f64 * STEP], [STEP; 2], [32, 32]))
        .collect();
    (tiles, vec![0f32; 256 * 256])
}

/// Each of `tiles` filled by `fill` into its own 32² of `out`, in order.
#[inline(always)]
fn each_tile(tiles: &[Grid<2>], out: &mut [f32], fill: impl Fn(&Grid<2>, &mut [f32])) {
    for (grid, tile) in tiles.iter().zip(out.chunks_exact_mut(32 * 32)) {
        fill(grid, tile);
    }
}

/// The fractal of the fBm benchmarks: 6 octaves of improved noise.
fn fbm6() -> Fractal<Improved> {
    Fractal::new(|o| Improved::new(o.seed), 1337, 6, FractalMode::Fbm).unwrap()
}

fn grid3() -> (Grid<3>, Vec<f32>) {
    let grid = Grid::new([0.0; 3], [STEP; 3], [32, 32, 32]);
    (grid, vec![0f32; grid.len()])
}

fn random_points() -> (Vec<[f32; 3]>, Vec<f32>) {
    let mut rng = noiselab::hash::SplitMix64(0x9E37_79B9_7F4A_7C15);
    let mut next = move || (rng.next() >> 40) as f32 / (1u32 << 24) as f32 * 2000.0 - 1000.0;
    let points: Vec<[f32; 3]> = (0..1 << 15).map(|_| [next(), next(), next()]).collect();
    let out = vec![0f32; points.len()];
    (points, out)
}

#[library_benchmark]
#[bench::improved(setup = grid2)]
fn improved_2d_256x256((grid, mut out): (Grid<2>, Vec<f32>)) -> Vec<f32> {
    Noise::<2>::fill_grid(black_box(&Improved::new(1337)), &grid, &mut out).unwrap();
    out
}

#[library_benchmark]
#[bench::improved_fast(setup = grid2)]
fn improved_2d_fast_256x256((grid, mut out): (Grid<2>, Vec<f32>)) -> Vec<f32> {
    Noise::<2>::fill_grid_fast(black_box(&Improved::new(1337)), &grid, &mut out).unwrap();
    out
}

#[library_benchmark]
#[bench::simplex(setup = grid2)]
fn simplex_2d_256x256((grid, mut out): (Grid<2>, Vec<f32>)) -> Vec<f32> {
    Noise::<2>::fill_grid(black_box(&Simplex::new(1337)), &grid, &mut out).unwrap();
    out
}

#[library_benchmark]
#[bench::value(setup = grid2)]
fn value_2d_256x256((grid, mut out): (Grid<2>, Vec<f32>)) -> Vec<f32> {
    Noise::<2>::fill_grid(black_box(&Value::new(1337)), &grid, &mut out).unwrap();
    out
}

#[library_benchmark]
#[bench::cellular(setup = grid2)]
fn cellular_f1_2d_256x256((grid, mut out): (Grid<2>, Vec<f32>)) -> Vec<f32> {
    Noise::<2>::fill_grid(black_box(&Worley::new(1337)), &grid, &mut out).unwrap();
    out
}

#[library_benchmark]
#[bench::fbm6(setup = grid2)]
fn fbm6_2d_256x256((grid, mut out): (Grid<2>, Vec<f32>)) -> Vec<f32> {
    let fbm = fbm6();
    Noise::<2>::fill_grid(black_box(&fbm), &grid, &mut out).unwrap();
    out
}

#[library_benchmark]
#[bench::fbm6_fast(setup = grid2)]
fn fbm6_2d_fast_256x256((grid, mut out): (Grid<2>, Vec<f32>)) -> Vec<f32> {
    let fbm = fbm6();
    Noise::<2>::fill_grid_fast(black_box(&fbm), &grid, &mut out).unwrap();
    out
}

#[library_benchmark]
#[bench::improved(setup = tiles2)]
fn improved_2d_64_tiles_of_32x32((tiles, mut out): (Vec<Grid<2>>, Vec<f32>)) -> Vec<f32> {
    let noise = Improved::new(1337);
    each_tile(&tiles, &mut out, |grid, tile| Noise::<2>::fill_grid(black_box(&noise), grid, tile).unwrap());
    out
}

#[library_benchmark]
#[bench::fbm6(setup = tiles2)]
fn fbm6_2d_64_tiles_of_32x32((tiles, mut out): (Vec<Grid<2>>, Vec<f32>)) -> Vec<f32> {
    let fbm = fbm6();
    each_tile(&tiles, &mut out, |grid, tile| Noise::<2>::fill_grid(black_box(&fbm), grid, tile).unwrap());
    out
}

#[library_benchmark]
#[bench::improved_fast(setup = tiles2)]
fn improved_2d_fast_64_tiles_of_32x32((tiles, mut out): (Vec<Grid<2>>, Vec<f32>)) -> Vec<f32> {
    let noise = Improved::new(1337);
    each_tile(&tiles, &mut out, |grid, tile| Noise::<2>::fill_grid_fast(black_box(&noise), grid, tile).unwrap());
    out
}

#[library_benchmark]
#[bench::fbm6_fast(setup = tiles2)]
fn fbm6_2d_fast_64_tiles_of_32x32((tiles, mut out): (Vec<Grid<2>>, Vec<f32>)) -> Vec<f32> {
    let fbm = fbm6();
    each_tile(&tiles, &mut out, |grid, tile| Noise::<2>::fill_grid_fast(black_box(&fbm), grid, tile).unwrap());
    out
}

#[library_benchmark]
#[bench::improved(setup = grid3)]
fn improved_3d_32x32x32((grid, mut out): (Grid<3>, Vec<f32>)) -> Vec<f32> {
    Noise::<3>::fill_grid(black_box(&Improved::new(1337)), &grid, &mut out).unwrap();
    out
}

#[library_benchmark]
#[bench::simplex(setup = grid3)]
fn simplex_3d_32x32x32((grid, mut out): (Grid<3>, Vec<f32>)) -> Vec<f32> {
    Noise::<3>::fill_grid(black_box(&Simplex::new(1337)), &grid, &mut out).unwrap();
    out
}

#[library_benchmark]
#[bench::improved(setup = random_points)]
fn improved_3d_32k_random_points((points, mut out): (Vec<[f32; 3]>, Vec<f32>)) -> Vec<f32> {
    Noise::<3>::fill_points(black_box(&Improved::new(1337)), &points, &mut out).unwrap();
    out
}

#[library_benchmark]
#[bench::improved(setup = random_points)]
fn improved_3d_f64_scalar_4k_points((points, _out): (Vec<[f32; 3]>, Vec<f32>)) -> f64 {
    let noise = Improved::new(1337);
    points[..4096].iter().map(|p| Noise::<3>::get(black_box(&noise), p.map(f64::from))).sum()
}

library_benchmark_group!(
    name = kernels,
    benchmarks = [
        improved_2d_256x256,
        improved_2d_fast_256x256,
        simplex_2d_256x256,
        value_2d_256x256,
        cellular_f1_2d_256x256,
        fbm6_2d_256x256,
        fbm6_2d_fast_256x256,
        improved_2d_64_tiles_of_32x32,
        fbm6_2d_64_tiles_of_32x32,
        improved_2d_fast_64_tiles_of_32x32,
        fbm6_2d_fast_64_tiles_of_32x32,
        improved_3d_32x32x32,
        simplex_3d_32x32x32,
        improved_3d_32k_random_points,
        improved_3d_f64_scalar_4k_points
    ]
);

main!(library_benchmark_groups = kernels);
