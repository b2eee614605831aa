//! Sparse convolution: splatting against gathering, and against improved
//! noise through the same batch API (issue 4's measured claims). Single
//! threaded: the library is built without `parallel` here.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use noiselab::{Grid, Improved, Noise, Sparse};
use noiselab_benches::window;

fn sparse(c: &mut Criterion) {
    let grid = window(1024);
    let mut out = vec![0f32; grid.len()];
    let mut group = c.benchmark_group("sparse 1024²");
    group.sample_size(10).throughput(Throughput::Elements(grid.len() as u64));
    for n in [10u32, 20, 30] {
        let noise = Sparse::new(1).with_impulses(n).unwrap();
        group.bench_with_input(BenchmarkId::new("splat", n), &noise, |b, s| {
            b.iter(|| s.splat_grid(&grid, &mut out).unwrap())
        });
        group.bench_with_input(BenchmarkId::new("gather", n), &noise, |b, s| {
            b.iter(|| Noise::<2>::fill_grid(s, &grid, &mut out).unwrap())
        });
    }
    let improved = Improved::new(1);
    group.bench_function("improved 2D (reference)", |b| {
        b.iter(|| Noise::<2>::fill_grid(&improved, &grid, &mut out).unwrap())
    });
    // Solid noise: a slice z = 0.5 through 3D.
    let slice = Grid::new([0.0, 0.0, 0.5], [1.0 / 32.0, 1.0 / 32.0, 0.0], [1024, 1024, 1]);
    let noise = Sparse::new(1);
    group.bench_function("splat 3D slice/20", |b| b.iter(|| noise.splat_grid(&slice, &mut out).unwrap()));
    group.bench_function("gather 3D slice/20", |b| b.iter(|| Noise::<3>::fill_grid(&noise, &slice, &mut out).unwrap()));
    group.bench_function("improved 3D slice (reference)", |b| {
        b.iter(|| Noise::<3>::fill_grid(&improved, &slice, &mut out).unwrap())
    });
    group.finish();
}

criterion_group!(benches, sparse);
criterion_main!(benches);
