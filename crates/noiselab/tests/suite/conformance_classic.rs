//! Classic noise against Perlin's original 1985 C program (tests/fixtures/SOURCES.md).

use crate::common::{assert_bit_exact, read_reference};
use noiselab::{Classic, Noise};

#[test]
fn classic_f64_matches_the_c_program_in_double() {
    let n = Classic::new(0);
    assert_bit_exact("classic1985_double_1d", &read_reference("classic1985_double_1d.csv"), |p| n.get([p[0]]));
    assert_bit_exact("classic1985_double_2d", &read_reference("classic1985_double_2d.csv"), |p| n.get([p[0], p[1]]));
    assert_bit_exact("classic1985_double_3d", &read_reference("classic1985_double_3d.csv"), |p| {
        n.get([p[0], p[1], p[2]])
    });
}

#[test]
fn classic_f32_matches_the_verbatim_float_program() {
    let n = Classic::new(0);
    let f = |p: &[f64]| p.iter().map(|&c| c as f32).collect::<Vec<f32>>();
    assert_bit_exact("classic1985_1d", &read_reference("classic1985_1d.csv"), |p| n.get_f32([p[0] as f32]) as f64);
    assert_bit_exact("classic1985_2d", &read_reference("classic1985_2d.csv"), |p| {
        let q = f(p);
        n.get_f32([q[0], q[1]]) as f64
    });
    assert_bit_exact("classic1985_3d", &read_reference("classic1985_3d.csv"), |p| {
        let q = f(p);
        n.get_f32([q[0], q[1], q[2]]) as f64
    });
}
