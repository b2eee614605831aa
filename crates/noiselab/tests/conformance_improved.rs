//! Improved noise against Perlin's reference code (tests/fixtures/SOURCES.md).

mod common;
use common::{assert_bit_exact, read_reference};
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
