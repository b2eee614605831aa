//! Cellular noise against brute force: the ring search finds the true k
//! nearest feature points at full jitter, for every metric and output.

use noiselab::hash::SplitMix64;
use noiselab::{CellOutput, Metric, Noise, Worley, WorleyError};

fn metric_distance(metric: Metric, d: &[f64]) -> f64 {
    match metric {
        Metric::Euclidean => d.iter().map(|c| c * c).sum::<f64>().sqrt(),
        Metric::EuclideanSquared => d.iter().map(|c| c * c).sum(),
        Metric::Manhattan => d.iter().map(|c| c.abs()).sum(),
        Metric::Chebyshev => d.iter().fold(0.0, |m, c| m.max(c.abs())),
        Metric::Minkowski(p) => d.iter().map(|c| c.abs().powf(p)).sum::<f64>().powf(1.0 / p),
    }
}

/// The four nearest feature points among every cell within ±`reach` cells.
fn brute_force<const D: usize>(w: &Worley, metric: Metric, p: [f64; D], reach: i64) -> ([f64; 4], [f64; D]) {
    let base = p.map(|c| c.floor() as i64);
    let side = (2 * reach + 1) as usize;
    let mut all = Vec::new();
    for flat in 0..side.pow(D as u32) {
        let mut rest = flat;
        let cell: [i64; D] = core::array::from_fn(|a| {
            let o = (rest % side) as i64 - reach;
            rest /= side;
            base[a] + o
        });
        let q = w.feature_point(cell);
        let d: Vec<f64> = (0..D).map(|a| q[a] - p[a]).collect();
        all.push((metric_distance(metric, &d), q));
    }
    all.sort_by(|a, b| a.0.total_cmp(&b.0));
    ([all[0].0, all[1].0, all[2].0, all[3].0], all[0].1)
}

fn check<const D: usize>(metric: Metric, jitter: f64, points: usize)
where
    Worley: Noise<D>,
{
    let w = Worley::new(17).with_metric(metric).unwrap().with_jitter(jitter).unwrap();
    let mut rng = SplitMix64(D as u64 * 31 + 7);
    let mut unit = move || (rng.next() >> 11) as f64 / (1u64 << 53) as f64;
    for i in 0..points {
        let mut p = [0f64; D];
        for c in p.iter_mut() {
            *c = unit() * 40.0 - 20.0;
        }
        if i % 4 == 0 {
            // Right at a cell face or corner, where fixed 3×3 searches fail.
            let a = i % D;
            p[a] = p[a].round() + (unit() - 0.5) * 1e-9;
        }
        let nearest = w.nearest(p);
        let (want, f1_point) = brute_force(&w, metric, p, 4);
        for (k, (got, want)) in nearest.distance.iter().zip(want).enumerate() {
            let err = (got - want).abs();
            assert!(err <= 1e-12 * (1.0 + want), "{metric:?} {D}D F{} at {p:?}: {got} vs brute force {want}", k + 1);
        }
        assert_eq!(nearest.point[0].map(|c| (c * 1e9).round()), f1_point.map(|c| (c * 1e9).round()));
        // The noise's outputs are these distances.
        for (out, k) in [(CellOutput::F1, 0), (CellOutput::F2, 1), (CellOutput::F3, 2), (CellOutput::F4, 3)] {
            let v = w.with_output(out).get(p);
            assert!((v - want[k]).abs() <= 1e-12 * (1.0 + want[k]));
        }
    }
}

#[test]
fn ring_search_equals_brute_force() {
    for metric in
        [Metric::Euclidean, Metric::EuclideanSquared, Metric::Manhattan, Metric::Chebyshev, Metric::Minkowski(3.0)]
    {
        check::<1>(metric, 1.0, 2000);
        check::<2>(metric, 1.0, 2000);
        check::<3>(metric, 1.0, 600);
        check::<4>(metric, 1.0, 150);
    }
    check::<2>(Metric::Euclidean, 0.5, 1000);
    check::<3>(Metric::Euclidean, 0.0, 200);
}

#[test]
fn combinations_and_cell_ids() {
    let w = Worley::new(5);
    let p = [0.3, -7.9, 2.2];
    let n = w.nearest(p);
    let [f1, f2, ..] = n.distance;
    assert_eq!(w.with_output(CellOutput::F2MinusF1).get(p), f2 - f1);
    assert_eq!(w.with_output(CellOutput::Mean12).get(p), (f1 + f2) * 0.5);
    assert_eq!(w.with_output(CellOutput::Product12).get(p), f1 * f2);
    // The cell value is constant inside a Voronoi cell: moving towards the
    // nearest feature point keeps it.
    let cell_value = w.with_output(CellOutput::CellValue);
    let q = core::array::from_fn::<f64, 3, _>(|a| p[a] + 0.5 * (n.point[0][a] - p[a]));
    assert_eq!(cell_value.get(p), cell_value.get(q));
    assert_eq!(w.nearest(q).id[0], n.id[0]);
    assert_ne!(n.id[0], n.id[1]);
    // No jitter: the feature points form the regular grid of cell centres.
    let grid = Worley::new(5).with_jitter(0.0).unwrap();
    assert_eq!(grid.feature_point([3i64, -2]), [3.5, -1.5]);
    assert_eq!(grid.get([3.5, -1.5]), 0.0);
}

#[test]
fn tiled_cells_repeat_exactly() {
    let w = Worley::new(2).with_period([5, 3, 7, 4]).unwrap().with_output(CellOutput::F2MinusF1);
    let mut rng = SplitMix64(99);
    for _ in 0..3000 {
        let p: [f64; 3] = core::array::from_fn(|_| ((rng.next() >> 40) % 4096) as f64 / 64.0 - 32.0);
        for (k, period) in [5.0, 3.0, 7.0].into_iter().enumerate() {
            let mut q = p;
            q[k] += period;
            assert_eq!(w.get(p).to_bits(), w.get(q).to_bits(), "axis {k} at {p:?}");
        }
    }
}

#[test]
fn bad_parameters_are_typed_errors() {
    assert_eq!(Worley::new(0).with_jitter(1.5).unwrap_err(), WorleyError::Jitter(1.5));
    assert!(Worley::new(0).with_jitter(f64::NAN).is_err());
    assert!(Worley::new(0).with_metric(Metric::Minkowski(0.5)).is_err());
    assert!(Worley::new(0).with_metric(Metric::Minkowski(f64::INFINITY)).is_err());
    assert!(Worley::new(0).with_period([0, 1 << 31, 0, 0]).is_err());
    // Special inputs: NaN in, NaN out; huge coordinates stay finite.
    assert!(Worley::new(0).get([f64::NAN, 1.0]).is_nan());
    assert!(Worley::new(0).get([1e30, -1e30]).is_finite());
}

// Out of line (as every generic helper here): inlined, each test's helpers
// made one huge function that LLVM compiles on one core.
/// The grid fill (feature points per row of cells, permuted into lanes)
/// against the point path, bit for bit, at every instruction-set level:
/// fine and coarse spacing (chunks within one cell, across many, and the
/// fallbacks), reversed axes, tiling, every output and metric, 1D–4D.
#[inline(never)]
fn grid_equals_points<const D: usize>(w: &Worley, grid: &noiselab::Grid<D>)
where
    Worley: Noise<D>,
{
    for level in noiselab::SimdLevel::available() {
        let mut out = vec![0f32; grid.len()];
        noiselab::grid::fill_grid_at(level, w, grid, &mut out, noiselab::Accuracy::Exact).unwrap();
        for (i, &v) in out.iter().enumerate() {
            let want = w.get_f32(grid.point(i));
            assert_eq!(v.to_bits(), want.to_bits(), "{w:?} {level:?} {grid:?} point {i}: {v} vs {want}");
        }
    }
}

#[test]
fn grid_fill_equals_the_point_path() {
    use noiselab::Grid;
    let outputs = [CellOutput::F1, CellOutput::F2, CellOutput::F4, CellOutput::F2MinusF1, CellOutput::CellValue];
    let metrics =
        [Metric::Euclidean, Metric::EuclideanSquared, Metric::Manhattan, Metric::Chebyshev, Metric::Minkowski(3.0)];
    for (i, (&output, &metric)) in outputs.iter().cycle().zip(metrics.iter()).enumerate().take(8) {
        let w = Worley::new(i as u32).with_metric(metric).unwrap().with_output(output);
        for step in [1.0 / 32.0, 0.13, 0.9, 2.5, -0.07] {
            grid_equals_points(&w, &Grid::new([-3.3], [step], [300]));
            grid_equals_points(&w, &Grid::new([-3.3, 5.1], [step, 0.11], [67, 9]));
            grid_equals_points(&w, &Grid::new([0.2, -1.0, 2.0], [step, 0.3, 0.45], [37, 4, 3]));
            grid_equals_points(&w, &Grid::new([0.2, -1.0, 2.0, 0.7], [step, 0.3, 0.45, 0.6], [21, 3, 2, 2]));
        }
    }
    // 2D F1 fills rows of one row of cells in bands of up to eight: full
    // bands, bands cut by a new row of cells or the end.
    for metric in [Metric::Euclidean, Metric::Manhattan] {
        let w = Worley::new(11).with_metric(metric).unwrap();
        grid_equals_points(&w, &Grid::new([-0.4, 3.01], [1.0 / 32.0, 1.0 / 64.0], [100, 70]));
        grid_equals_points(&w, &Grid::new([2.6, -1.3], [1.0 / 20.0, 0.03], [130, 41]));
    }
    let tiled = Worley::new(5).with_period([3, 4, 0, 0]).unwrap().with_jitter(0.8).unwrap();
    grid_equals_points(&tiled, &Grid::new([-5.0, -5.0], [1.0 / 16.0; 2], [200, 40]));
    grid_equals_points(&Worley::new(9), &Grid::new([1e8, -2e9], [1.0, 1.0], [40, 3]));
    // Rows whose coordinates along axes 1.. are not finite (NaN, as the
    // point path gives) beside finite ones.
    grid_equals_points(&Worley::new(4), &Grid::new([0.3, f64::NAN], [1.0 / 32.0, 0.1], [40, 3]));
    grid_equals_points(&Worley::new(4), &Grid::new([0.3, 1.0, -2.0], [1.0 / 32.0, f64::MAX, 0.5], [40, 3, 2]));
}
