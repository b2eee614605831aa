//! Modified noise: exact zero slices, the 61-cell period, gradients.

use noiselab::hash::SplitMix64;
use noiselab::{Modified, ModifiedHash, ModifiedTexture, Noise, NoiseGradient};

fn points(n: usize, seed: u64) -> Vec<[f64; 4]> {
    let mut rng = SplitMix64(seed);
    let mut u = move || (rng.next() >> 11) as f64 / (1u64 << 53) as f64;
    (0..n)
        .map(|i| {
            let mut p = [0.0; 4];
            for c in p.iter_mut() {
                *c = if i % 4 == 0 { (u() * 200.0 - 100.0).round() } else { u() * 400.0 - 200.0 };
            }
            p
        })
        .collect()
}

#[test]
fn lower_dimensions_are_exact_zero_slices() {
    for noise in [Modified::new(0), Modified::new(17), Modified::new(5).with_hash(ModifiedHash::Wide)] {
        for [x, y, z, _] in points(20_000, 1) {
            let n4 = Noise::<4>::get(&noise, [x, y, z, 0.0]);
            assert_eq!(Noise::<3>::get(&noise, [x, y, z]), n4);
            assert_eq!(Noise::<2>::get(&noise, [x, y]), Noise::<3>::get(&noise, [x, y, 0.0]));
            assert_eq!(Noise::<1>::get(&noise, [x]), Noise::<2>::get(&noise, [x, 0.0]));
            let f = [x as f32, y as f32, z as f32];
            assert_eq!(Noise::<3>::get_f32(&noise, f), Noise::<4>::get_f32(&noise, [f[0], f[1], f[2], 0.0]));
        }
    }
}

#[test]
fn mod61_repeats_every_61_cells_and_wide_does_not() {
    let m = Modified::new(9);
    let w = Modified::new(9).with_hash(ModifiedHash::Wide);
    let mut wide_differs = 0;
    for p in points(5_000, 2) {
        for axis in 0..4 {
            let mut q = p;
            q[axis] += 61.0;
            assert_eq!(m.get(p), m.get(q), "{p:?} axis {axis}");
            wide_differs += (w.get(p) != w.get(q)) as usize;
        }
    }
    // A quarter of the probes are lattice nodes, where gradient noise is 0
    // in both places; every other probe must differ.
    assert!(wide_differs >= 14_990, "wide hash repeated at 61 cells: only {wide_differs} of 15000 differ");
}

#[test]
fn gradients_match_central_differences() {
    let n = Modified::new(3);
    let h = 1e-6;
    for p in points(3_000, 3) {
        // Shift a third of the points near a cell border.
        let p = [p[0] + 0.3, p[1], p[2] - 0.7, p[3] + 1e-4];
        let (v, g) = NoiseGradient::<4>::get_gradient(&n, p);
        assert_eq!(v, Noise::<4>::get(&n, p));
        for k in 0..4 {
            let (mut a, mut b) = (p, p);
            a[k] += h;
            b[k] -= h;
            let numeric = (n.get(a) - n.get(b)) / (2.0 * h);
            assert!((numeric - g[k]).abs() < 1e-6 * (1.0 + g[k].abs()), "{p:?} d/dx{k}: {} vs {numeric}", g[k]);
        }
    }
}

#[test]
fn textured_evaluation_equals_computed() {
    for seed in [0, 1, 44] {
        let computed = Modified::new(seed);
        let textured = ModifiedTexture::new(&computed);
        for [x, y, z, w] in points(100_000, 4 + seed as u64) {
            assert_eq!(Noise::<2>::get(&textured, [x, y]), Noise::<2>::get(&computed, [x, y]));
            assert_eq!(Noise::<3>::get(&textured, [x, y, z]), Noise::<3>::get(&computed, [x, y, z]));
            assert_eq!(Noise::<4>::get(&textured, [x, y, z, w]), Noise::<4>::get(&computed, [x, y, z, w]));
        }
    }
}
