//! Simplex noise against Gustavson's SimplexNoise.java, 2012-03-09 (tests/fixtures/SOURCES.md).

mod common;
use common::{assert_bit_exact, read_reference};
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
