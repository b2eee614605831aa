//! The seed's fast volume-texture noise against improved noise through the
//! same batch API (issue 5): a 1024² slice of 3D noise and a 128³ volume.
//! Single threaded.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use noiselab::{Fast, Grid, Improved, Noise};

fn fast(c: &mut Criterion) {
    let (fast, improved) = (Fast::new(1), Improved::new(1));
    let slice = Grid::new([0.0, 0.0, 0.5], [1.0 / 32.0, 1.0 / 32.0, 0.0], [1024, 1024, 1]);
    let volume = Grid::new([0.0; 3], [1.0 / 16.0; 3], [128, 128, 128]);
    for (name, grid) in [("1024² slice", slice), ("128³ volume", volume)] {
        let mut out = vec![0f32; grid.len()];
        let mut group = c.benchmark_group(format!("fast vs improved, {name}"));
        group.sample_size(10).throughput(Throughput::Elements(grid.len() as u64));
        group.bench_function("fast", |b| b.iter(|| Noise::<3>::fill_grid(&fast, &grid, &mut out).unwrap()));
        group.bench_function("improved", |b| b.iter(|| Noise::<3>::fill_grid(&improved, &grid, &mut out).unwrap()));
        group.finish();
    }
}

criterion_group!(benches, fast);
criterion_main!(benches);
