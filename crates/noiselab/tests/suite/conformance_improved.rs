//! Improved noise against Perlin's reference code (tests/fixtures/SOURCES.md).

use crate::common::{assert_bit_exact, read_reference};
use noiselab::hash::PERLIN_PERMUTATION;
use noiselab::{Improved, ImprovedVariant, Noise};

#[test]
fn improved_3d_matches_improvednoise_java() {
    let n = Improved::new(0);
    let rows = read_reference("improved3d.csv");
    assert_bit_exact("improved3d", &rows, |p| n.get([p[0], p[1], p[2]]));
}

#[test]
fn improved_3d_original_2002_gradient() {
    let n = Improved::new(0).with_variant(ImprovedVariant::Original2002);
    let rows = read_reference("improved3d_2002grad.csv");
    assert_bit_exact("improved3d_2002grad", &rows, |p| n.get([p[0], p[1], p[2]]));
}

#[test]
fn improved_4d_matches_improvednoise4d_java() {
    let n = Improved::new(0);
    let rows = read_reference("improved4d.csv");
    assert_bit_exact("improved4d", &rows, |p| n.get([p[0], p[1], p[2], p[3]]));
}

/// Perlin's 2002 improved noise in 3D written out plainly in `f64` (the
/// algorithm of ImprovedNoise.java: quintic fade, `a + t·(b − a)` lerps,
/// `grad` as ±u ± v), as an oracle for the sign of zero results, which the
/// reference CSVs do not keep.
fn improved_oracle(p: [f64; 3]) -> f64 {
    let perm = |i: usize| PERLIN_PERMUTATION[i & 255] as usize;
    let fade = |t: f64| t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
    let lerp = |t: f64, a: f64, b: f64| a + t * (b - a);
    let grad = |h: usize, x: f64, y: f64, z: f64| {
        let h = h & 15;
        let u = if h < 8 { x } else { y };
        let v = if h < 4 {
            y
        } else if h == 12 || h == 14 {
            x
        } else {
            z
        };
        (if h & 1 == 0 { u } else { -u }) + (if h & 2 == 0 { v } else { -v })
    };
    let floor = p.map(f64::floor);
    let [i, j, k] = floor.map(|c| (c as i64 & 255) as usize);
    let [x, y, z] = [p[0] - floor[0], p[1] - floor[1], p[2] - floor[2]];
    let (a, b) = (perm(i) + j, perm(i + 1) + j);
    let (aa, ab, ba, bb) = (perm(a) + k, perm(a + 1) + k, perm(b) + k, perm(b + 1) + k);
    let corner = |h: usize, dx: f64, dy: f64, dz: f64| grad(perm(h), x - dx, y - dy, z - dz);
    let (u, v, w) = (fade(x), fade(y), fade(z));
    let lower_z = lerp(
        v,
        lerp(u, corner(aa, 0.0, 0.0, 0.0), corner(ba, 1.0, 0.0, 0.0)),
        lerp(u, corner(ab, 0.0, 1.0, 0.0), corner(bb, 1.0, 1.0, 0.0)),
    );
    let upper_z = lerp(
        v,
        lerp(u, corner(aa + 1, 0.0, 0.0, 1.0), corner(ba + 1, 1.0, 0.0, 1.0)),
        lerp(u, corner(ab + 1, 0.0, 1.0, 1.0), corner(bb + 1, 1.0, 1.0, 1.0)),
    );
    lerp(w, lower_z, upper_z)
}

/// On and near lattice lines many corners are ±0; the result's sign of
/// zero must still be the reference program's (bit-for-bit, unlike the
/// CSV comparison, which takes −0 = +0).
#[test]
fn improved_3d_keeps_the_reference_zero_signs() {
    let n = Improved::new(0);
    // Integers, halves, a quarter, and points just below a line (−1e-17,
    // whose fraction rounds to 1.0; 5 − 1e-15, whose does not).
    let mut coords: Vec<f64> = (-10..=10).map(f64::from).collect();
    coords.extend([0.5, -0.5, 0.25, -1e-17, 5.0 - 1e-15]);
    let (mut zeros, mut negative_zeros) = (0, 0);
    for &x in &coords {
        for &y in &coords {
            for &z in &coords {
                let (want, got) = (improved_oracle([x, y, z]), n.get([x, y, z]));
                assert_eq!(got.to_bits(), want.to_bits(), "({x}, {y}, {z}): got {got:e}, want {want:e}");
                zeros += (want == 0.0) as usize;
                negative_zeros += (want.to_bits() == (-0.0f64).to_bits()) as usize;
            }
        }
    }
    // The points do test signs: both zeros occur.
    assert!(negative_zeros > 20 && zeros - negative_zeros > 20, "{zeros} zeros, {negative_zeros} of them −0");
}
