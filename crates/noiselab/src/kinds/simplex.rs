//! Simplex noise. Placeholder until implemented.
use crate::lanes::Lanes;
use crate::noise::Noise;

/// Simplex noise (being implemented).
#[derive(Clone, Debug)]
pub struct Simplex;
impl Noise<2> for Simplex {
    fn sample<L: Lanes>(&self, _p: [L; 2]) -> L {
        L::cst(0.0)
    }
}
