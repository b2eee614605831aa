//! Seamless loops and domain warps over any noise.

use noiselab::hash::SplitMix64;
use noiselab::{ComposeError, Improved, Looped, Noise, Sparse, Value, Warp};

#[test]
fn loops_repeat_exactly_and_continuously() {
    for length in [1.0, 2.5, 7.0] {
        let looped = Looped::new(Improved::new(3), length).unwrap();
        let mut rng = SplitMix64(length as u64);
        for _ in 0..2000 {
            let x = (rng.next() >> 11) as f64 / (1u64 << 53) as f64 * 20.0 - 10.0;
            let y = (rng.next() >> 11) as f64 / (1u64 << 53) as f64 * 20.0 - 10.0;
            // Frame 0 and frame N (t = T, 2T, −T) are the same frame.
            let first = looped.get([x, y, 0.0]);
            for k in [1.0, 2.0, -1.0] {
                assert_eq!(first.to_bits(), looped.get([x, y, k * length]).to_bits(), "T = {length}");
            }
            // Approaching the end of the loop approaches the first frame.
            let end = looped.get([x, y, length * (1.0 - 1e-9)]);
            assert!((end - first).abs() < 1e-6, "jump at the loop point: {end} vs {first}");
        }
    }
    // Sparse convolution loops too (any noise).
    let sparse = Looped::new(Sparse::new(1), 3.0).unwrap();
    assert_eq!(sparse.get([0.3, 0.7, 0.0]), sparse.get([0.3, 0.7, 3.0]));
    assert_eq!(Looped::new(Improved::new(0), 0.0).unwrap_err(), ComposeError::LoopLength(0.0));
    assert!(Looped::new(Improved::new(0), f64::NAN).is_err());
}

#[test]
fn warp_reads_the_noise_at_the_displaced_point() {
    let base = Value::new(1);
    let warp = Warp::new(base, Improved::new, 10, 0.7, 0.5).unwrap();
    for p in [[0.3, -1.2], [5.5, 2.25], [-3.0, 0.125]] {
        let at = p.map(|c| c * 0.5);
        let q = [
            p[0] + 0.7 * Noise::<2>::get(&Improved::new(11), at),
            p[1] + 0.7 * Noise::<2>::get(&Improved::new(12), at),
        ];
        assert_eq!(warp.get(p), base.get(q));
    }
    // Zero amplitude is the identity.
    let still = Warp::new(base, Improved::new, 10, 0.0, 1.0).unwrap();
    assert_eq!(still.get([0.3, 0.4]), base.get([0.3, 0.4]));
    // Iterating warps the warped point again.
    let twice = Warp::new(base, Improved::new, 10, 0.7, 0.5).unwrap().iterated(2, 0.5, 2.0).unwrap();
    assert_ne!(twice.get([0.3, 0.4]), warp.get([0.3, 0.4]));
    assert!(Warp::new(base, Improved::new, 0, f64::NAN, 1.0).is_err());
    assert!(Warp::new(base, Improved::new, 0, 1.0, 0.0).is_err());
    assert!(warp.clone().iterated(0, 0.5, 2.0).is_err());
    assert!(warp.iterated(2, -1.0, 2.0).is_err());
}

#[test]
fn warps_compose_with_tiling() {
    // Base tiled every 4 cells; the field read at 2p is tiled every 8.
    let base = Improved::new(2).with_period([4, 4, 0, 0]).unwrap();
    let warp = Warp::new(base, |s| Value::new(s).with_period([8, 8, 0, 0]).unwrap(), 3, 0.5, 2.0).unwrap();
    let mut worst = 0f64;
    for i in 0..2000 {
        let p = [(i % 64) as f64 / 16.0, (i / 64) as f64 / 16.0];
        for k in 0..2 {
            let mut q = p;
            q[k] += 4.0;
            worst = worst.max((warp.get(p) - warp.get(q)).abs());
        }
    }
    assert!(worst < 1e-9, "warped tile differs across its period by {worst}");
}

#[test]
fn time_varying_solids_loop_in_4d_and_by_tiling_time() {
    // 4D noise with time as the fourth axis: Perlin's blend loop and, the
    // exact alternative, a period on the time axis.
    let blend = Looped::new(Improved::new(5), 4.0).unwrap();
    let tiled = Improved::new(5).with_period([0, 0, 0, 4]).unwrap();
    let mut rng = SplitMix64(44);
    for _ in 0..1000 {
        let p: [f64; 3] = core::array::from_fn(|_| (rng.next() >> 11) as f64 / (1u64 << 53) as f64 * 10.0 - 5.0);
        let at = |t: f64| [p[0], p[1], p[2], t];
        assert_eq!(blend.get(at(0.0)).to_bits(), blend.get(at(4.0)).to_bits());
        assert_eq!(tiled.get(at(0.0)).to_bits(), tiled.get(at(4.0)).to_bits());
        assert_eq!(tiled.get(at(1.25)).to_bits(), tiled.get(at(5.25)).to_bits());
    }
}
