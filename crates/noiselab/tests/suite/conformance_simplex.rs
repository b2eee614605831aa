//! Simplex noise against Gustavson's SimplexNoise.java, 2012-03-09 (tests/fixtures/SOURCES.md).

use crate::common::{assert_bit_exact, read_reference};
use noiselab::{Noise, Simplex};

#[test]
fn simplex_2d_matches_gustavson_2012() {
    let n = Simplex::new(0);
    assert_bit_exact("simplex2d", &read_reference("simplex2d.csv"), |p| n.get([p[0], p[1]]));
}

#[test]
fn simplex_3d_matches_gustavson_2012() {
    let n = Simplex::new(0);
    assert_bit_exact("simplex3d", &read_reference("simplex3d.csv"), |p| n.get([p[0], p[1], p[2]]));
}

#[test]
fn simplex_4d_matches_gustavson_2012() {
    let n = Simplex::new(0);
    assert_bit_exact("simplex4d", &read_reference("simplex4d.csv"), |p| n.get([p[0], p[1], p[2], p[3]]));
}

#[test]
fn simplex_1d_f32_matches_simplexnoise1234_c() {
    let n = Simplex::new(0);
    assert_bit_exact("gustavson_simplexnoise1234_1d", &read_reference("gustavson_simplexnoise1234_1d.csv"), |p| {
        n.get_f32([p[0] as f32]) as f64
    });
}
