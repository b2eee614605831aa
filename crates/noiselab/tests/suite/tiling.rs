//! Tiling for every tileable kind: with a period per axis (any positive
//! number of cells, beyond 256 too), the value — and the analytic gradient
//! where there is one — at p and at p + period·e_k are identical bit for
//! bit, in f64 and f32. Untiled values are untouched (the conformance tests
//! still pass).

use noiselab::grid::fill_grid_at;
use noiselab::hash::SplitMix64;
use noiselab::{
    Accuracy, Classic, Grid, Improved, ImprovedVariant, Modified, ModifiedHash, ModifiedTexture, Noise, NoiseGradient,
    SimdLevel, Sparse, Value, Worley,
};

const PERIODS: [[u32; 4]; 3] = [[3, 5, 7, 2], [1, 1, 1, 1], [300, 257, 11, 4]];

/// Points on a 1/64 grid in ±32, so p + period stays exact in f32.
fn points<const D: usize>(seed: u64) -> Vec<[f64; D]> {
    let mut rng = SplitMix64(seed);
    (0..1500).map(|_| core::array::from_fn(|_| ((rng.next() >> 40) % 4096) as f64 / 64.0 - 32.0)).collect()
}

fn check_values<N: Noise<D>, const D: usize>(name: &str, noise: &N, period: [u32; 4]) {
    for p in points::<D>(D as u64) {
        for k in 0..D {
            let mut q = p;
            q[k] += period[k] as f64;
            assert_eq!(
                noise.get(p).to_bits(),
                noise.get(q).to_bits(),
                "{name} {D}D period {period:?} axis {k} at {p:?}"
            );
            let (pf, qf) = (p.map(|c| c as f32), q.map(|c| c as f32));
            assert_eq!(noise.get_f32(pf).to_bits(), noise.get_f32(qf).to_bits(), "{name} {D}D f32 axis {k} at {p:?}");
        }
    }
}

fn check_gradients<N: NoiseGradient<D>, const D: usize>(name: &str, noise: &N, period: [u32; 4]) {
    for p in points::<D>(D as u64 + 10) {
        for k in 0..D {
            let mut q = p;
            q[k] += period[k] as f64;
            let (a, b) = (noise.get_gradient(p), noise.get_gradient(q));
            assert_eq!(a.0.to_bits(), b.0.to_bits(), "{name} {D}D gradient value at {p:?}");
            assert_eq!(a.1.map(f64::to_bits), b.1.map(f64::to_bits), "{name} {D}D gradient at {p:?}");
        }
    }
}

macro_rules! every_dim {
    ($check:ident, $name:expr, $noise:expr, $period:expr, [$($d:literal),*]) => {
        $( $check::<_, $d>($name, &$noise, $period); )*
    };
}

#[test]
fn every_lattice_kind_tiles_exactly() {
    for period in PERIODS {
        every_dim!(check_values, "classic", Classic::new(3).with_period(period).unwrap(), period, [1, 2, 3]);
        let improved = Improved::new(4).with_period(period).unwrap();
        every_dim!(check_values, "improved", improved, period, [1, 2, 3, 4]);
        every_dim!(check_gradients, "improved", improved, period, [1, 2, 3, 4]);
        let original = Improved::new(0).with_variant(ImprovedVariant::Original2002).with_period(period).unwrap();
        every_dim!(check_values, "improved-2002", original, period, [3]);
        let value = Value::new(5).with_period(period).unwrap();
        every_dim!(check_values, "value", value, period, [1, 2, 3, 4]);
        every_dim!(check_gradients, "value", value, period, [1, 2, 3, 4]);
        let modified = Modified::new(6).with_period(period).unwrap();
        every_dim!(check_values, "modified", modified, period, [1, 2, 3, 4]);
        every_dim!(check_gradients, "modified", modified, period, [1, 2, 3, 4]);
        let wide = Modified::new(6).with_hash(ModifiedHash::Wide).with_period(period).unwrap();
        every_dim!(check_values, "modified-wide", wide, period, [2, 3]);
        every_dim!(check_values, "modified-textured", ModifiedTexture::new(&modified), period, [2, 3, 4]);
        every_dim!(check_values, "worley", Worley::new(7).with_period(period).unwrap(), period, [1, 2, 3, 4]);
        let sparse = Sparse::new(8).with_impulses(4).unwrap().with_period(period).unwrap();
        every_dim!(check_values, "sparse", sparse, period, [1, 2, 3]);
    }
}

/// Grid fills of tiled kinds give point evaluation's values bit for bit,
/// at every instruction-set level: 2D tiles of whole
/// chunks across cells (each plane's lattice points held in registers),
/// starting below 0 and crossing the period, and larger grids.
#[test]
fn tiled_grid_fills_equal_point_evaluation() {
    for period in PERIODS {
        check_fills("improved", &Improved::new(4).with_period(period).unwrap());
        check_fills("classic", &Classic::new(3).with_period(period).unwrap());
        check_fills("modified", &Modified::new(6).with_period(period).unwrap());
        check_fills("value", &Value::new(5).with_period(period).unwrap());
    }
}

#[inline(never)]
fn check_fills<N: Noise<2>>(name: &str, noise: &N) {
    let grids = [
        Grid::new([-2.0, -1.5], [0.125, 0.25], [32, 32]),
        Grid::new([-3.0, 1.0], [0.5, -0.5], [16, 40]),
        Grid::new([0.5, -4.0], [1.0 / 16.0, 0.3], [48, 20]),
        Grid::new([-1.25, 0.0], [0.07, 0.11], [150, 9]),
    ];
    for grid in grids {
        for level in SimdLevel::available() {
            let mut out = vec![0f32; grid.len()];
            fill_grid_at(level, noise, &grid, &mut out, Accuracy::Exact).unwrap();
            for (i, &v) in out.iter().enumerate() {
                let p = grid.point(i);
                assert_eq!(v.to_bits(), noise.get_f32(p).to_bits(), "{name} {grid:?} {level:?} point {p:?}");
            }
        }
    }
}

#[test]
fn untiled_axes_and_untiled_noises_are_unchanged() {
    // Period 0 on an axis leaves it unbounded: the same values as untiled.
    let plain = Improved::new(0);
    let tiled_x = Improved::new(0).with_period([5, 0, 0, 0]).unwrap();
    let mut repeats = 0;
    for p in points::<3>(77) {
        if p[0] >= 0.0 && p[0] < 4.0 {
            // Inside the first tile (away from its upper border) the cells are the same.
            assert_eq!(plain.get(p), tiled_x.get(p));
        }
        let mut q = p;
        q[1] += 5.0;
        repeats += (tiled_x.get(p) == tiled_x.get(q)) as usize;
    }
    // y is not tiled: values 5 cells apart agree only where both are 0 (on lattice planes).
    assert!(repeats < 150, "{repeats} of 1500 points repeat along the untiled axis");
    assert_eq!(Improved::new(0).with_period([1 << 31, 0, 0, 0]).unwrap_err(), noiselab::PeriodError(1 << 31));
}
