//! Analytic gradients against central differences, across cell borders.

use noiselab::hash::SplitMix64;
use noiselab::{Improved, Noise, NoiseGradient, Simplex, Value};

/// Check `sample_gradient` against central differences at `count` points,
/// a third of them within 1e-3 of a cell border on some axis.
///
/// `jumps` allows for noises that are discontinuous on some surfaces
/// (simplex 3D/4D with Gustavson's radius² 0.6): where the central stencil
/// straddles such a surface, the analytic gradient must instead match the
/// one-sided difference on the smooth side, and such points must be rare.
fn check_gradient<N: NoiseGradient<D>, const D: usize>(name: &str, noise: &N, count: usize, jumps: bool) {
    let mut rng = SplitMix64(0xD1FF + D as u64);
    let mut unit = move || (rng.next() >> 11) as f64 / (1u64 << 53) as f64;
    let h = 1e-6;
    let mut worst = 0f64;
    let mut straddles = 0;
    for i in 0..count {
        let mut p = [0f64; D];
        for c in p.iter_mut() {
            *c = unit() * 200.0 - 100.0;
        }
        if i % 3 == 0 {
            let axis = i % D;
            p[axis] = p[axis].round() + (unit() - 0.5) * 2e-3;
        }
        let (v, g) = noise.get_gradient(p);
        assert_eq!(v, noise.get(p), "{name} {D}D: value from get_gradient differs from get at {p:?}");
        for k in 0..D {
            let (mut a, mut b) = (p, p);
            a[k] += h;
            b[k] -= h;
            let (fa, fb) = (noise.get(a), noise.get(b));
            let numeric = (fa - fb) / (2.0 * h);
            let err = (numeric - g[k]).abs();
            if err < 1e-6 * (1.0 + g[k].abs()) {
                worst = worst.max(err);
                continue;
            }
            let one_sided = [(fa - v) / h, (v - fb) / h];
            let smooth_side = one_sided.iter().any(|d| (d - g[k]).abs() < 1e-4 * (1.0 + g[k].abs()));
            assert!(
                jumps && smooth_side,
                "{name} {D}D: d/dx{k} at {p:?}: analytic {} central {numeric} one-sided {one_sided:?}",
                g[k]
            );
            straddles += 1;
        }
    }
    assert!(straddles * 1000 <= count * D, "{name} {D}D: {straddles} stencils straddle a jump");
    eprintln!(
        "{name} {D}D: worst |analytic − central difference| over {count} points: {worst:e}; {straddles} straddles"
    );
}

#[test]
fn improved_gradients() {
    let n = Improved::new(0);
    check_gradient::<_, 1>("improved", &n, 3000, false);
    check_gradient::<_, 2>("improved", &n, 3000, false);
    check_gradient::<_, 3>("improved", &n, 3000, false);
    check_gradient::<_, 4>("improved", &n, 3000, false);
}

#[test]
fn value_gradients() {
    let n = Value::new(11);
    check_gradient::<_, 1>("value", &n, 3000, false);
    check_gradient::<_, 2>("value", &n, 3000, false);
    check_gradient::<_, 3>("value", &n, 3000, false);
    check_gradient::<_, 4>("value", &n, 3000, false);
}

#[test]
fn simplex_gradients() {
    let n = Simplex::new(0);
    check_gradient::<_, 1>("simplex", &n, 3000, false);
    check_gradient::<_, 2>("simplex", &n, 3000, false);
    check_gradient::<_, 3>("simplex", &n, 3000, true);
    check_gradient::<_, 4>("simplex", &n, 3000, true);
    check_gradient::<_, 3>("simplex", &Simplex::new(5), 3000, true);
}

#[test]
fn improved_gradient_is_the_lattice_gradient_at_nodes() {
    // At a node the fade weights are 0/1 and flat, so the gradient is the
    // node's own gradient vector: one of Perlin's 12 edge directions.
    let n = Improved::new(0);
    for x in -5..5 {
        for y in -5..5 {
            let (v, g) = NoiseGradient::<3>::get_gradient(&n, [x as f64, y as f64, 2.0]);
            assert_eq!(v, 0.0);
            let nonzero = g.iter().filter(|c| **c != 0.0).count();
            assert_eq!(nonzero, 2, "{g:?}");
            assert!(g.iter().all(|c| c.abs() == 1.0 || *c == 0.0), "{g:?}");
        }
    }
    let _ = Noise::<3>::get(&n, [0.0; 3]);
}
