//! Fractal sums over every base kind: documented ranges, tiling that
//! composes across octaves, analytic derivatives, the footprint rule, and
//! run-time composition through `Box<dyn DynNoise>`.

use noiselab::grid::{fill_grid_at, Accuracy, SimdLevel, Span, Stores};
use noiselab::hash::SplitMix64;
use noiselab::{
    Axes, Classic, Fractal, FractalMode, Grid, Improved, Modified, Noise, NoiseGradient, Simplex, Sparse, Value, Worley,
};

fn random_points<const D: usize>(count: usize, seed: u64) -> Vec<[f64; D]> {
    let mut rng = SplitMix64(seed);
    (0..count)
        .map(|_| core::array::from_fn(|_| (rng.next() >> 11) as f64 / (1u64 << 53) as f64 * 200.0 - 100.0))
        .collect()
}

// Out of line (as every generic helper here): inlined, each test's helpers
// made one huge function that LLVM compiles on one core.
/// Every mode stays inside `mode.range(r)` for a base of range ±r (and,
/// for bases that use both signs, spans a good part of it).
#[inline(never)]
fn check_ranges<N: Noise<D>, const D: usize>(name: &str, make: impl Fn(u32) -> N, r: f64) {
    let symmetric = name != "worley";
    for mode in FractalMode::ALL {
        let f = Fractal::new(|o| make(o.seed), 9, 6, mode).unwrap();
        let (lo, hi) = mode.range(r);
        let (mut min, mut max) = (f64::MAX, f64::MIN);
        for p in random_points::<D>(20_000, 3) {
            let v = f.get(p);
            min = min.min(v);
            max = max.max(v);
        }
        assert!(min >= lo && max <= hi, "{name} {mode:?} {D}D: [{min}, {max}] outside [{lo}, {hi}]");
        assert!(
            !symmetric || max - min > 0.25 * (hi - lo),
            "{name} {mode:?}: [{min}, {max}] spans too little of [{lo}, {hi}]"
        );
    }
}

#[test]
fn every_mode_stays_in_its_documented_range_over_every_kind() {
    check_ranges::<_, 3>("improved", Improved::new, 1.04);
    check_ranges::<_, 2>("classic", Classic::new, 0.71);
    check_ranges::<_, 2>("simplex", Simplex::new, 1.0);
    check_ranges::<_, 3>("value", Value::new, 1.0);
    check_ranges::<_, 3>("modified", Modified::new, 1.0);
    check_ranges::<_, 2>("worley", Worley::new, 2f64.sqrt());
    check_ranges::<_, 2>("sparse", |s| Sparse::new(s).with_impulses(8).unwrap(), 2.0);
}

#[test]
fn tiling_composes_across_octaves() {
    // Octave i of a tile of P cells is tiled with P·2ⁱ cells.
    let period = [3, 5, 0, 0];
    let check = |name: &str, f: &dyn Fn([f64; 2]) -> f64| {
        let mut rng = SplitMix64(12);
        for _ in 0..2000 {
            let p: [f64; 2] = core::array::from_fn(|_| ((rng.next() >> 40) % 4096) as f64 / 64.0 - 32.0);
            assert_eq!(f(p).to_bits(), f([p[0] + 3.0, p[1]]).to_bits(), "{name} x at {p:?}");
            assert_eq!(f(p).to_bits(), f([p[0], p[1] + 5.0]).to_bits(), "{name} y at {p:?}");
        }
    };
    for mode in FractalMode::ALL {
        let improved =
            Fractal::new(|o| Improved::new(o.seed).with_period(o.period(period).unwrap()).unwrap(), 1, 5, mode)
                .unwrap();
        check("improved", &|p| improved.get(p));
        let value =
            Fractal::new(|o| Value::new(o.seed).with_period(o.period(period).unwrap()).unwrap(), 1, 5, mode).unwrap();
        check("value", &|p| value.get(p));
        let worley =
            Fractal::new(|o| Worley::new(o.seed).with_period(o.period(period).unwrap()).unwrap(), 1, 4, mode).unwrap();
        check("worley", &|p| worley.get(p));
        let classic =
            Fractal::new(|o| Classic::new(o.seed).with_period(o.period(period).unwrap()).unwrap(), 1, 4, mode).unwrap();
        check("classic", &|p| classic.get(p));
        let modified =
            Fractal::new(|o| Modified::new(o.seed).with_period(o.period(period).unwrap()).unwrap(), 1, 4, mode)
                .unwrap();
        check("modified", &|p| modified.get(p));
        let sparse = Fractal::new(
            |o| Sparse::new(o.seed).with_impulses(4).unwrap().with_period(o.period(period).unwrap()).unwrap(),
            1,
            3,
            mode,
        )
        .unwrap();
        check("sparse", &|p| sparse.get(p));
    }
    // A non-integer lacunarity cannot tile: a typed error, not a seam.
    let bad = Fractal::with(|o| o.period([3, 0, 0, 0]), 0, 3, FractalMode::Fbm, 2.5, 0.5).unwrap();
    assert!(bad.octaves() == 3);
}

#[test]
fn gradients_through_every_mode_match_central_differences() {
    for mode in FractalMode::ALL {
        let f = Fractal::new(|o| Improved::new(o.seed), 4, 5, mode).unwrap();
        let h = 1e-6;
        let mut checked = 0;
        for p in random_points::<3>(1500, 8) {
            let (v, g) = f.get_gradient(p);
            assert_eq!(v, f.get(p), "{mode:?}: value from get_gradient differs");
            for k in 0..3 {
                let (mut a, mut b) = (p, p);
                a[k] += h;
                b[k] -= h;
                let numeric = (f.get(a) - f.get(b)) / (2.0 * h);
                // |n| and clamps have kinks; skip the rare stencil across one.
                let (fa, fb) = ((f.get(a) - v) / h, (v - f.get(b)) / h);
                if (fa - fb).abs() > 1e-3 * (1.0 + fa.abs()) {
                    continue;
                }
                checked += 1;
                assert!(
                    (numeric - g[k]).abs() < 1e-5 * (1.0 + g[k].abs()),
                    "{mode:?} d/dx{k} at {p:?}: {} vs {numeric}",
                    g[k]
                );
            }
        }
        assert!(checked > 4000, "{mode:?}: only {checked} smooth stencils");
    }
}

#[test]
fn octaves_follow_the_pixel_footprint() {
    // 1/32 unit per pixel: octaves up to period 2 px are 2⁰…2⁴ → 5 octaves.
    assert_eq!(Fractal::<Improved>::octaves_for_footprint(1.0 / 32.0, 2.0), 5);
    assert_eq!(Fractal::<Improved>::octaves_for_footprint(1.0 / 1024.0, 2.0), 10);
    assert_eq!(Fractal::<Improved>::octaves_for_footprint(4.0, 2.0), 1);
    assert_eq!(Fractal::<Improved>::octaves_for_footprint(1e-30, 2.0), 30);
    assert_eq!(Fractal::<Improved>::octaves_for_footprint(f64::NAN, 2.0), 1);
}

/// A band-limited grid fill is, bit for bit, the fill of the fractal of the
/// octaves Perlin's rule keeps at the grid's step (the count
/// `octaves_for_footprint` gives), in every mode; points keep every octave.
#[test]
fn band_limited_fills_are_the_fractal_of_the_octaves_a_grid_resolves() {
    // (lacunarity, gain, origin, steps, sizes, octaves kept of 6)
    let cases = [
        (2.0, 0.5, [0.0, 0.0], [1.0 / 32.0; 2], [256, 64], 5),
        (2.0, 0.5, [-3.3, 1.7], [0.1; 2], [90, 70], 3),
        (2.5, 0.4, [0.25, -8.0], [0.05; 2], [120, 33], 3),
        // The finer axis decides; an axis of one sample has no step.
        (2.0, 0.5, [1.0, 2.0], [0.3, 0.01], [40, 50], 6),
        (2.0, 0.5, [1.0, 2.0], [0.2, 7.0], [300, 1], 2),
        // Past the 512² threshold, so the parallel fill splits it.
        (2.0, 0.5, [5.5, -0.5], [1.0 / 16.0; 2], [600, 600], 4),
        // Far from the origin, f32 coordinates blur a step of exactly
        // 1/32 (2 samples a cell at octave 4): still kept.
        (2.0, 0.5, [1000.37, -0.1], [1.0 / 32.0; 2], [3, 2], 5),
    ];
    for (lacunarity, gain, origin, step, size, kept) in cases {
        let grid = Grid::new(origin, step, size);
        let footprint = step.iter().zip(size).filter(|&(_, n)| n >= 2).map(|(s, _)| *s).fold(f64::INFINITY, f64::min);
        assert_eq!(Fractal::<Improved>::octaves_for_footprint(footprint, lacunarity).min(6), kept, "{step:?}");
        for mode in FractalMode::ALL {
            let make = |octaves| Fractal::with(|o| Improved::new(o.seed), 11, octaves, mode, lacunarity, gain).unwrap();
            let limited = make(6).band_limited();
            assert!(limited.is_band_limited() && !make(6).is_band_limited());
            let (mut got, mut want) = (vec![f32::NAN; grid.len()], vec![f32::NAN; grid.len()]);
            limited.fill_grid(&grid, &mut got).unwrap();
            make(kept).fill_grid(&grid, &mut want).unwrap();
            let same = got.iter().zip(&want).all(|(a, b)| a.to_bits() == b.to_bits());
            assert!(same, "{mode:?} {step:?}: not the {kept}-octave fractal's fill");
            // Fast fills keep the same octaves.
            limited.fill_grid_fast(&grid, &mut got).unwrap();
            make(kept).fill_grid_fast(&grid, &mut want).unwrap();
            let same = got.iter().zip(&want).all(|(a, b)| a.to_bits() == b.to_bits());
            assert!(same, "{mode:?} {step:?}: not the {kept}-octave fractal's fast fill");
            let p = grid.point(size[0] / 2);
            assert_eq!(
                limited.get_f32(p).to_bits(),
                make(6).get_f32(p).to_bits(),
                "{mode:?}: points keep every octave"
            );
        }
    }
    // One sample: no step to judge by, so every octave is summed.
    let point = Grid::new([0.3, 0.4], [0.5; 2], [1, 1]);
    let fbm = Fractal::new(|o| Improved::new(o.seed), 3, 6, FractalMode::Fbm).unwrap();
    let (mut a, mut b) = ([0f32], [0f32]);
    fbm.clone().band_limited().fill_grid(&point, &mut a).unwrap();
    fbm.fill_grid(&point, &mut b).unwrap();
    assert_eq!(a[0].to_bits(), b[0].to_bits());
}

#[test]
fn fractals_over_run_time_noises_equal_the_static_ones() {
    let boxed =
        Fractal::new(|o| Box::new(Improved::new(o.seed)) as Box<dyn noiselab::DynNoise<3>>, 2, 4, FractalMode::Ridged)
            .unwrap();
    let fixed = Fractal::new(|o| Improved::new(o.seed), 2, 4, FractalMode::Ridged).unwrap();
    let grid = noiselab::Grid::new([0.1, -0.2, 0.3], [0.07, 0.05, 0.0], [37, 11, 1]);
    let (mut a, mut b) = (vec![0f32; grid.len()], vec![0f32; grid.len()]);
    Noise::fill_grid(&boxed, &grid, &mut a).unwrap();
    Noise::fill_grid(&fixed, &grid, &mut b).unwrap();
    assert_eq!(a, b);
    assert_eq!(Noise::get(&boxed, [0.3, 0.4, 0.5]), Noise::get(&fixed, [0.3, 0.4, 0.5]));
}

/// In every mode, a fractal of fractals fills its grid (the inner fills
/// nested inside the outer, each needing its own octave buffers) with the
/// point values; repeated fills of different sizes on one thread give the
/// same bits.
#[test]
fn nested_fractal_grids_equal_their_points_in_every_mode() {
    let inner = |seed| Fractal::new(|o| Improved::new(o.seed), seed, 3, FractalMode::Turbulence).unwrap();
    for mode in FractalMode::ALL {
        let outer = Fractal::new(|o| inner(o.seed), 5, 3, mode).unwrap();
        for (size, step) in [([300, 200], 0.07), ([70_000, 2], 0.01), ([40, 30], 0.3)] {
            let grid = Grid::new([-3.3, 1.7], [step; 2], size);
            let mut out = vec![f32::NAN; grid.len()];
            outer.fill_grid(&grid, &mut out).unwrap();
            for (i, &v) in out.iter().enumerate().step_by(97) {
                assert_eq!(v.to_bits(), outer.get_f32(grid.point(i)).to_bits(), "{mode:?} {size:?}: point {i}");
            }
            let mut again = vec![0f32; grid.len()];
            outer.fill_grid(&grid, &mut again).unwrap();
            assert!(
                out.iter().zip(&again).all(|(a, b)| a.to_bits() == b.to_bits()),
                "{mode:?} {size:?}: second fill differs"
            );
        }
    }
}

#[test]
fn bad_parameters_are_typed_errors() {
    use noiselab::ComposeError;
    assert_eq!(Fractal::new(|o| Improved::new(o.seed), 0, 0, FractalMode::Fbm).unwrap_err(), ComposeError::Octaves(0));
    assert_eq!(
        Fractal::new(|o| Improved::new(o.seed), 0, 31, FractalMode::Fbm).unwrap_err(),
        ComposeError::Octaves(31)
    );
    assert!(Fractal::with(|o| Improved::new(o.seed), 0, 3, FractalMode::Fbm, 1.0, 0.5).is_err());
    assert!(Fractal::with(|o| Improved::new(o.seed), 0, 3, FractalMode::Fbm, 2.0, -0.5).is_err());
    let octave = noiselab::Octave { index: 1, seed: 0, frequency: 2.5 };
    assert!(octave.period([3, 0, 0, 0]).is_err());
}

/// Where a grid's coordinates leave f32's range, its fractal fill gives NaN
/// there and the point values everywhere else, in every mode (the combine
/// pass keeps point evaluation's guard only for such grids).
#[test]
fn fractal_grids_past_the_float_range_equal_their_points() {
    // Axis 0 runs 3.0e38, 3.2e38, 3.4e38, then past f32::MAX (∞).
    let grid = Grid::new([3.0e38, 0.2], [2.0e37, 0.1], [8, 3]);
    for mode in FractalMode::ALL {
        let fractal = Fractal::new(|o| Improved::new(o.seed), 4, 5, mode).unwrap();
        let mut out = vec![0f32; grid.len()];
        fractal.fill_grid(&grid, &mut out).unwrap();
        for (i, &v) in out.iter().enumerate() {
            let p = grid.point(i);
            assert_eq!(v.is_nan(), !p[0].is_finite(), "{mode:?}: point {i} at {p:?} gave {v}");
            assert_eq!(v.to_bits(), fractal.get_f32(p).to_bits(), "{mode:?}: point {i} at {p:?}");
        }
    }
}

/// Octaves of gradient noise whose grid lies on integer points are ±0 at
/// every point, and the fractal fill leaves them out; its values are still
/// the point values bit for bit, zero signs included, in every mode and at
/// every instruction-set level.
#[inline(never)]
fn check_on_integers<N: Noise<D>, const D: usize>(name: &str, make: impl Fn(u32) -> N, grids: &[Grid<D>]) {
    for mode in FractalMode::ALL {
        let fractal = Fractal::new(|o| make(o.seed), 4, 6, mode).unwrap();
        for grid in grids {
            grid_equals_points(&fractal, grid, &format!("{name} {mode:?}"));
        }
    }
}

/// `noise`'s exact fill of `grid` at every instruction-set level gives its
/// point values bit for bit; returns them.
fn grid_equals_points<N: Noise<D>, const D: usize>(noise: &N, grid: &Grid<D>, what: &str) -> Vec<f32> {
    let points: Vec<f32> = (0..grid.len()).map(|i| noise.get_f32(grid.point(i))).collect();
    for level in SimdLevel::available() {
        let mut out = vec![f32::NAN; grid.len()];
        fill_grid_at(level, noise, grid, &mut out, Accuracy::Exact).unwrap();
        for (i, (&v, &p)) in out.iter().zip(&points).enumerate() {
            assert_eq!(v.to_bits(), p.to_bits(), "{what} {level:?} {grid:?}: point {i} at {:?}", grid.point(i));
        }
    }
    points
}

#[test]
fn fractal_grids_on_integer_points_equal_their_points() {
    let grids = [
        // From octave 2 on, every octave lies on integer points.
        Grid::new([3.0, -2.0], [0.25; 2], [13, 9]),
        // A tile: its fBm is 0 only at its origin.
        Grid::new([5.0, 7.0], [1.0 / 32.0; 2], [32, 32]),
        // A quarter of the points are 0.
        Grid::new([-4.0, 1.0], [0.5; 2], [11, 6]),
        // Every octave on integer points: every value is ±0.
        Grid::new([-4.0, 1.0], [1.0; 2], [7, 5]),
    ];
    check_on_integers::<_, 2>("improved", Improved::new, &grids);
    check_on_integers::<_, 2>("classic", Classic::new, &grids);
    check_on_integers::<_, 2>("modified", Modified::new, &grids);
    // Chosen at run time, as the command line's noises are.
    check_on_integers::<_, 2>(
        "boxed improved",
        |s| Box::new(Improved::new(s)) as Box<dyn noiselab::DynNoise<2>>,
        &grids[..2],
    );
    check_on_integers::<_, 3>("improved", Improved::new, &[Grid::new([1.0, 2.0, -3.0], [0.125; 3], [9, 5, 4])]);
    // Two blocks of the fill (the second starts mid-grid).
    check_on_integers::<_, 2>("improved", Improved::new, &[Grid::new([0.0; 2], [1.0 / 32.0; 2], [600, 300])]);
    // fBm's sum starts at +0, and with every octave ±0 stays +0.
    let fbm = Fractal::new(|o| Improved::new(o.seed), 4, 6, FractalMode::Fbm).unwrap();
    let grid = Grid::new([-4.0, 1.0], [1.0; 2], [7, 5]);
    let mut out = vec![f32::NAN; grid.len()];
    fbm.fill_grid(&grid, &mut out).unwrap();
    assert!(out.iter().all(|v| v.to_bits() == 0), "{out:?}");
    // fBm leaves trailing octaves on integer points out of its sum, but
    // only where their amplitude is finite in f32: here it overflows from
    // octave 2 on, and +0 · ∞ is NaN.
    let loud = Fractal::with(|o| Improved::new(o.seed), 4, 6, FractalMode::Fbm, 2.0, 1e30).unwrap();
    let values = grid_equals_points(&loud, &grids[0], "fBm at gain 1e30");
    assert!(values.iter().all(|v| v.is_nan()), "{values:?}");
}

/// Grid fills of 1 to 10 octaves equal their points bit for bit, in every
/// mode, at every instruction-set level.
#[test]
fn fractal_grids_of_every_octave_count_equal_their_points() {
    let grid = Grid::new([-1.3, 2.2], [0.07, 0.05], [37, 9]);
    for octaves in 1..=10 {
        for mode in FractalMode::ALL {
            let fractal = Fractal::new(|o| Improved::new(o.seed), 6, octaves, mode).unwrap();
            grid_equals_points(&fractal, &grid, &format!("{octaves} octaves, {mode:?}"));
        }
    }
}

/// Finite coordinates whose higher octaves overflow (scaled past the float
/// range, those octaves are NaN and count as 0): the grid fill's combine,
/// which sums without that guard and sums again with it where a result is
/// not finite, gives the point values, at every instruction-set level.
#[test]
fn fractal_grids_whose_octaves_overflow_equal_their_points() {
    let grid = Grid::new([1.0e38, 0.2], [1.0e36, 0.1], [21, 3]);
    for octaves in [3, 6, 9] {
        for mode in FractalMode::ALL {
            let fractal = Fractal::new(|o| Improved::new(o.seed), 2, octaves, mode).unwrap();
            let points = grid_equals_points(&fractal, &grid, &format!("{octaves} octaves, {mode:?}"));
            assert!(points.iter().all(|v| v.is_finite()), "{mode:?}: finite input, finite values");
        }
    }
}

/// Rows of two strips (512 columns each) or more are filled strip by strip,
/// each strip's rows combined into its columns: the point values bit for
/// bit, in every mode, at every instruction-set level, in 2D and 3D, for
/// strips that are not whole registers wide, for spans of whole rows from
/// mid-grid (as threads take them) and spans that start or end mid-row
/// (filled in whole rows), and where octaves overflow.
#[test]
fn fractal_grids_in_strips_equal_their_points() {
    // Strips of 560 and 540 columns; of 528, 528 and 523.
    let grids = [Grid::new([-3.3, 0.7], [1.0 / 40.0, 0.3], [1100, 5]), Grid::new([0.1, 0.2], [0.5, 0.25], [1579, 3])];
    for mode in FractalMode::ALL {
        let fractal = Fractal::new(|o| Improved::new(o.seed), 6, 5, mode).unwrap();
        for grid in &grids {
            grid_equals_points(&fractal, grid, &format!("{mode:?}"));
        }
        let solid = Fractal::new(|o| Value::new(o.seed), 2, 4, mode).unwrap();
        grid_equals_points(
            &solid,
            &Grid::new([0.3, -1.0, 2.0], [0.05, 0.4, 0.5], [1030, 3, 2]),
            &format!("3D {mode:?}"),
        );
        // Octaves 5 to 8 past the float range (counted as 0).
        let loud = Fractal::new(|o| Improved::new(o.seed), 2, 9, mode).unwrap();
        let points = grid_equals_points(
            &loud,
            &Grid::new([1.0e37, 0.2], [1.0e34, 0.1], [1100, 2]),
            &format!("overflowing {mode:?}"),
        );
        assert!(points.iter().all(|v| v.is_finite()), "{mode:?}: finite input, finite values");
        // Spans: rows 2 and 3; from mid-row 0 to mid-row 3.
        let grid = &grids[0];
        let axes = Axes::of(grid);
        for level in SimdLevel::available() {
            for (start, len) in [(2 * 1100, 2 * 1100), (7, 3 * 1100)] {
                let mut out = vec![f32::NAN; len];
                fractal.dispatch_span(
                    level,
                    Span { axes: &axes, start, accuracy: Accuracy::Exact, stores: Stores::Cached },
                    &mut out,
                );
                for (k, &v) in out.iter().enumerate() {
                    let p = grid.point(start + k);
                    assert_eq!(
                        v.to_bits(),
                        fractal.get_f32(p).to_bits(),
                        "{mode:?} {level:?} span {start}+{len}: point {}",
                        start + k
                    );
                }
            }
        }
    }
}

/// The combine stores past the caches on grids of 2²⁰ points or more, and
/// on spans asked to: the point values bit for bit, at every
/// instruction-set level, in strips (rows starting at every offset from a
/// register boundary) and in whole rows, into outputs at every offset from
/// one, writing nothing outside them.
#[test]
fn streamed_fractal_combines_equal_their_points() {
    let fbm = Fractal::new(|o| Improved::new(o.seed), 8, 4, FractalMode::Fbm).unwrap();
    // Strips of 560 and 547 columns; whole rows of 300.
    grid_equals_points(&fbm, &Grid::new([0.3, -2.0], [1.0 / 32.0, 1.0 / 48.0], [1107, 950]), "streamed strips");
    grid_equals_points(&fbm, &Grid::new([0.3, -2.0], [1.0 / 32.0, 1.0 / 48.0], [300, 3500]), "streamed rows");
    for grid in [Grid::new([-1.3, 0.2], [0.07, 0.05], [1100, 3]), Grid::new([-1.3, 0.2], [0.07, 0.05], [75, 4])] {
        let axes = Axes::of(&grid);
        let n = grid.len();
        for mode in FractalMode::ALL {
            let fractal = Fractal::new(|o| Improved::new(o.seed), 8, 5, mode).unwrap();
            let points: Vec<f32> = (0..n).map(|i| fractal.get_f32(grid.point(i))).collect();
            for level in SimdLevel::available() {
                for offset in [0, 1, 3, 4, 7, 8, 15] {
                    let mut buf = vec![f32::NAN; n + 16];
                    let span = Span { axes: &axes, start: 0, accuracy: Accuracy::Exact, stores: Stores::Streamed };
                    fractal.dispatch_span(level, span, &mut buf[offset..offset + n]);
                    for (k, (&v, &p)) in buf[offset..offset + n].iter().zip(&points).enumerate() {
                        assert_eq!(v.to_bits(), p.to_bits(), "{mode:?} {level:?} {grid:?} offset {offset}: point {k}");
                    }
                    let outside = buf[..offset].iter().chain(&buf[offset + n..]);
                    assert!(
                        outside.into_iter().all(|v| v.is_nan()),
                        "{mode:?} {level:?} offset {offset}: wrote outside the output"
                    );
                }
            }
        }
    }
}
