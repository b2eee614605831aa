//! N-dimensional simplex noise: cost O(n²), continuity, batch agreement.

use noiselab::hash::SplitMix64;
use noiselab::{Noise, SimplexN};

fn cost<const D: usize>() -> (usize, usize) {
    let (_, c) = SimplexN::new(0).sample_counted::<f64, D>([0.3; D].map(|x| x * 1.7));
    assert_eq!(c.corners, D + 1, "{D}D: simplex has D + 1 corners");
    assert_eq!(c.comparisons, D * (D - 1) / 2);
    (c.corners, c.comparisons + c.coordinate_ops)
}

#[test]
fn cost_grows_quadratically_not_exponentially() {
    let ops = [cost::<2>(), cost::<3>(), cost::<4>(), cost::<5>(), cost::<6>(), cost::<7>(), cost::<8>()];
    for (i, (corners, total)) in ops.iter().enumerate() {
        let d = i + 2;
        // A cube lattice visits 2^D corners; the simplex D + 1.
        assert!(*corners < 1 << d || d < 3);
        // Total work within a constant times D².
        assert!(*total <= 3 * d * d + 4, "{d}D: {total} ops");
    }
    let (_, ops4) = ops[2];
    let (_, ops8) = ops[6];
    // Doubling D roughly quadruples the work (a cube lattice: ×16).
    assert!((ops8 as f64 / ops4 as f64) < 5.0, "ops(8)/ops(4) = {}", ops8 as f64 / ops4 as f64);
}

fn check_continuity<const D: usize>() {
    let n = SimplexN::new(3);
    let mut rng = SplitMix64(D as u64);
    let mut u = move || (rng.next() >> 11) as f64 / (1u64 << 53) as f64;
    for _ in 0..5000 {
        let mut p = [0.0; D];
        for c in p.iter_mut() {
            *c = u() * 100.0 - 50.0;
        }
        let mut q = p;
        q[0] += 1e-7;
        assert!((n.get(p) - n.get(q)).abs() < 1e-4, "{D}D jump at {p:?}");
    }
}

#[test]
fn continuous_in_every_dimension_tested() {
    check_continuity::<2>();
    check_continuity::<5>();
    check_continuity::<6>();
    check_continuity::<8>();
}

#[test]
fn range_in_higher_dimensions() {
    fn check<const D: usize>() {
        let n = SimplexN::new(1);
        let mut rng = SplitMix64(77 + D as u64);
        let (mut lo, mut hi) = (0f64, 0f64);
        for _ in 0..100_000 {
            let p = [0.0; D].map(|_: f64| (rng.next() >> 11) as f64 / (1u64 << 53) as f64 * 200.0 - 100.0);
            let v = n.get(p);
            lo = lo.min(v);
            hi = hi.max(v);
        }
        assert!(lo >= -1.0 && hi <= 1.0, "{D}D: [{lo}, {hi}]");
        assert!(hi - lo > 0.8, "{D}D: [{lo}, {hi}] uses too little of [-1, 1]");
    }
    check::<5>();
    check::<6>();
    check::<7>();
    check::<8>();
}
