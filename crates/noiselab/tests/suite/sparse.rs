//! Sparse convolution noise: the splatting renderers against point
//! evaluation, statistics, kernels, turbulence and bad input.

use noiselab::hash::SplitMix64;
use noiselab::{Grid, Kernel, KernelError, Noise, Sparse, SparseError, SparseTurbulence, SplatError, Values};

fn assert_close(name: &str, a: &[f32], b: &[f32], tol: f32) {
    assert_eq!(a.len(), b.len());
    let worst = a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0f32, f32::max);
    assert!(worst <= tol, "{name}: splat and point evaluation differ by {worst}");
    eprintln!("{name}: max |splat − point| = {worst:e}");
}

/// Splat vs point evaluation on a window of a D-dim noise.
fn compare<const D: usize>(name: &str, noise: &Sparse, grid: Grid<D>)
where
    Sparse: Noise<D>,
{
    let mut splat = vec![0f32; grid.len()];
    let mut point = vec![0f32; grid.len()];
    noise.splat_grid(&grid, &mut splat).unwrap();
    noise.fill_grid(&grid, &mut point).unwrap();
    assert_close(name, &splat, &point, 1e-5);
}

#[test]
fn splatting_equals_point_evaluation() {
    let n = Sparse::new(3);
    // Straddling negative coordinates and cell borders, odd steps.
    compare("2D", &n, Grid::new([-2.3, -1.7], [0.037, 0.041], [150, 130]));
    compare("2D, descending x", &n, Grid::new([3.0, -0.5], [-0.05, 0.05], [90, 70]));
    compare("2D, exact borders", &n, Grid::new([-1.0, -1.0], [0.125, 0.25], [40, 33]));
    compare("3D slice z = 0", &n, Grid::new([-1.5, -1.5, 0.0], [0.04, 0.04, 0.0], [100, 100, 1]));
    compare("3D slice z = −0.73", &n, Grid::new([0.2, -3.1, -0.73], [0.03, 0.05, 0.0], [120, 80, 1]));
    compare("4D slice", &n, Grid::new([-0.4, 0.9, 0.5, -2.25], [0.06, 0.06, 0.0, 0.0], [60, 60, 1, 1]));
    compare(
        "gaussian 2D",
        &Sparse::new(1).with_kernel(Kernel::gaussian()),
        Grid::new([-1.2, 0.3], [0.05, 0.05], [80, 80]),
    );
    compare(
        "halves 3D",
        &Sparse::new(2).with_values(Values::Halves),
        Grid::new([5.5, -7.5, 1.5], [0.05, 0.05, 0.0], [64, 64, 1]),
    );
    let stretched = Kernel::cubic()
        .anisotropic([[0.5, 0.2, 0.0, 0.0], [0.0, 1.5, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]])
        .unwrap();
    compare(
        "anisotropic 2D",
        &Sparse::new(4).with_kernel(stretched.clone()),
        Grid::new([-1.0, -1.0], [0.04, 0.04], [90, 90]),
    );
    compare(
        "anisotropic 3D slice",
        &Sparse::new(4).with_kernel(stretched),
        Grid::new([-1.0, -1.0, 0.3], [0.04, 0.04, 0.0], [70, 70, 1]),
    );
    let ring = Kernel::radial_profile(0.6, |d| (d * 12.0).cos() * (1.0 - d / 0.6)).unwrap();
    compare("custom ring kernel", &Sparse::new(5).with_kernel(ring), Grid::new([0.1, 0.1], [0.03, 0.03], [100, 100]));
    // Far away (beyond the f32 pixel-resolution limit) it falls back to point evaluation.
    compare("far window", &n, Grid::new([1e7, 3e7], [0.5, 0.5], [20, 20]));
    // Pixels sparser than cells: also point evaluation.
    compare("coarse window", &n, Grid::new([0.0, 0.0], [7.3, 5.1], [20, 20]));
}

#[test]
fn splatting_does_not_depend_on_how_the_window_is_cut() {
    // Bands are the unit of (parallel) work; a window rendered whole equals
    // its halves rendered alone, bit for bit, so thread count cannot matter.
    let n = Sparse::new(9).with_impulses(30).unwrap();
    let whole = Grid::new([-0.5, -0.25], [0.02, 0.02], [100, 100]);
    let mut all = vec![0f32; 100 * 100];
    n.splat_grid(&whole, &mut all).unwrap();
    let top = Grid::new([-0.5, -0.25], [0.02, 0.02], [100, 37]);
    let bottom = Grid::new([-0.5, -0.25 + 37.0 * 0.02], [0.02, 0.02], [100, 63]);
    let (mut a, mut b) = (vec![0f32; 3700], vec![0f32; 6300]);
    n.splat_grid(&top, &mut a).unwrap();
    n.splat_grid(&bottom, &mut b).unwrap();
    assert_eq!(&all[..3700], &a[..]);
    // The bottom window's y coordinates are computed from its own origin, so
    // compare it with point evaluation rather than bits.
    let mut point = vec![0f32; 6300];
    n.fill_grid(&bottom, &mut point).unwrap();
    assert_close("bottom", &b, &point, 1e-5);
}

#[test]
fn positions_renderer_equals_point_evaluation() {
    let n = Sparse::new(7);
    let mut rng = SplitMix64(5);
    let mut unit = move || (rng.next() >> 40) as f32 / (1u32 << 24) as f32;
    // A sphere of radius 2.5 seen from +z (the paper's surface case), plus
    // scattered points, a NaN and an infinity.
    let mut positions = Vec::new();
    for j in 0..64 {
        for i in 0..64 {
            let (x, y) = (i as f32 / 12.0 - 2.6, j as f32 / 12.0 - 2.6);
            let z2 = 6.25 - x * x - y * y;
            positions.push([x, y, if z2 > 0.0 { z2.sqrt() } else { -1.0 }]);
        }
    }
    for _ in 0..500 {
        positions.push([unit() * 20.0 - 10.0, unit() * 20.0 - 10.0, unit() * 20.0 - 10.0]);
    }
    positions.push([f32::NAN, 0.0, 0.0]);
    positions.push([0.0, f32::INFINITY, 0.0]);
    let mut splat = vec![0f32; positions.len()];
    n.splat_positions(&positions, &mut splat).unwrap();
    let point: Vec<f32> = positions.iter().map(|p| Noise::<3>::get_f32(&n, *p)).collect();
    let k = positions.len();
    assert!(splat[k - 2].is_nan() && splat[k - 1].is_nan());
    assert_close("positions", &splat[..k - 2], &point[..k - 2], 1e-5);
}

#[test]
fn turbulence_splat_equals_point_evaluation() {
    let t = SparseTurbulence::new(&Sparse::new(2).with_impulses(12).unwrap(), 0, 3);
    assert_eq!(t.octaves(), 4);
    let grid = Grid::new([-0.7, 0.4, 0.25], [0.02, 0.02, 0.0], [96, 96, 1]);
    let mut splat = vec![0f32; grid.len()];
    let mut point = vec![0f32; grid.len()];
    t.splat_grid(&grid, &mut splat).unwrap();
    t.fill_grid(&grid, &mut point).unwrap();
    assert_close("turbulence", &splat, &point, 4e-5);
    assert!(point.iter().all(|&v| v >= 0.0));
}

#[test]
fn statistics_match_the_normalisation() {
    // Variance normalisation: standard deviation ¼ in every dimension.
    fn std_and_tail<const D: usize>(n: &Sparse, count: usize) -> (f64, f64)
    where
        Sparse: Noise<D>,
    {
        let mut rng = SplitMix64(D as u64);
        let (mut s2, mut out) = (0.0, 0usize);
        for _ in 0..count {
            let mut p = [0f64; D];
            for c in p.iter_mut() {
                *c = (rng.next() >> 11) as f64 / (1u64 << 53) as f64 * 1000.0 - 500.0;
            }
            let v = n.get(p);
            s2 += v * v;
            out += (v.abs() > 1.0) as usize;
        }
        ((s2 / count as f64).sqrt(), out as f64 / count as f64)
    }
    let n = Sparse::new(0);
    for (d, (std, tail)) in
        [(1, std_and_tail::<1>(&n, 200_000)), (2, std_and_tail::<2>(&n, 200_000)), (3, std_and_tail::<3>(&n, 50_000))]
    {
        assert!((std - 0.25).abs() < 0.01, "{d}D std {std}");
        assert!(tail < 2e-3, "{d}D share beyond ±1: {tail}");
    }
    let (std, _) = std_and_tail::<2>(&Sparse::new(0).with_kernel(Kernel::gaussian()), 100_000);
    assert!((std - 0.25).abs() < 0.01, "gaussian std {std}");
    // The paper's mapping centres the noise on ½.
    let paper = Sparse::new(0).with_normalisation(noiselab::Normalisation::Paper);
    let mean: f64 = (0..20_000).map(|i| paper.get([i as f64 * 0.173, i as f64 * 0.071])).sum::<f64>() / 20_000.0;
    assert!((mean - 0.5).abs() < 0.02, "{mean}");
    // Seeds change the stream.
    assert_ne!(Sparse::new(1).get([0.3, 0.4]), Sparse::new(2).get([0.3, 0.4]));
}

#[test]
fn bad_parameters_are_typed_errors() {
    assert_eq!(Sparse::new(0).with_impulses(0).unwrap_err(), SparseError::Impulses(0));
    assert!(Sparse::new(0).with_impulses(Sparse::MAX_IMPULSES + 1).is_err());
    for r in [0.0, -1.0, f64::NAN, f64::INFINITY, 2.5] {
        assert!(matches!(Kernel::radial_profile(r, |_| 1.0), Err(KernelError::BadRadius(_))), "{r}");
    }
    assert!(matches!(Kernel::radial_profile(0.5, |d| 1.0 / d), Err(KernelError::NonFiniteProfile(_))));
    let singular = [[1.0, 0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0], [0.0; 4], [0.0; 4]];
    assert_eq!(Kernel::cubic().anisotropic(singular).unwrap_err(), KernelError::BadMap);
    let too_wide = [[0.1, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]];
    assert!(matches!(Kernel::cubic().anisotropic(too_wide), Err(KernelError::BadRadius(_))));
    let n = Sparse::new(0);
    let mut out = vec![0f32; 8];
    assert_eq!(n.splat_grid(&Grid::new([0.0; 3], [0.1; 3], [2, 2, 2]), &mut out), Err(SplatError::NotAWindow));
    assert!(matches!(n.splat_grid(&Grid::new([0.0; 2], [0.1; 2], [3, 3]), &mut out), Err(SplatError::Grid(_))));
    assert!(matches!(n.splat_positions(&[[0.0; 3]; 3], &mut out), Err(SplatError::PositionsMismatch { .. })));
    // NaN and infinite windows evaluate point by point: NaN, not a panic.
    let mut out = vec![0f32; 4];
    n.splat_grid(&Grid::new([f64::NAN, 0.0], [0.1, 0.1], [2, 2]), &mut out).unwrap();
    assert!(out.iter().all(|v| v.is_nan()));
}

#[test]
fn tiled_noise_repeats_exactly() {
    fn check<const D: usize>(n: &Sparse, period: [u32; 4])
    where
        Sparse: Noise<D>,
    {
        let mut rng = SplitMix64(D as u64 + 40);
        for _ in 0..2000 {
            // Multiples of 1/64 keep p and p + period exact in f32 and f64.
            let mut p = [0f64; D];
            for c in p.iter_mut() {
                *c = ((rng.next() >> 40) % 4096) as f64 / 64.0 - 32.0;
            }
            for k in 0..D {
                let mut q = p;
                q[k] += period[k] as f64;
                assert_eq!(n.get(p).to_bits(), n.get(q).to_bits(), "{D}D axis {k} at {p:?}");
                let (pf, qf) = (p.map(|c| c as f32), q.map(|c| c as f32));
                assert_eq!(n.get_f32(pf).to_bits(), n.get_f32(qf).to_bits());
            }
        }
    }
    for period in [[3, 5, 7, 2], [1, 1, 1, 1], [300, 257, 11, 4]] {
        let n = Sparse::new(6).with_impulses(8).unwrap().with_period(period).unwrap();
        check::<1>(&n, period);
        check::<2>(&n, period);
        check::<3>(&n, period);
        check::<4>(&n, period);
    }
    // A tile rendered twice side by side is seamless: the splatted window
    // repeats with the period in pixels.
    let n = Sparse::new(1).with_period([4, 3, 0, 0]).unwrap();
    let px = 16;
    let (w, h) = (8 * px, 6 * px);
    let grid = Grid::new([0.0, 0.0], [1.0 / px as f64; 2], [w, h]);
    let mut out = vec![0f32; w * h];
    n.splat_grid(&grid, &mut out).unwrap();
    for j in 0..h {
        for i in 0..w {
            assert_eq!(out[j * w + i], out[(j % (3 * px)) * w + i % (4 * px)], "pixel ({i}, {j})");
        }
    }
    assert_eq!(Sparse::new(0).with_period([1 << 31, 0, 0, 0]).unwrap_err(), noiselab::PeriodError(1 << 31));
}
