//! N-dimensional simplex noise. Placeholder until implemented.
use crate::lanes::Lanes;
use crate::noise::Noise;

/// N-dimensional simplex noise (being implemented).
#[derive(Clone, Debug)]
pub struct SimplexN;
impl Noise<5> for SimplexN {
    fn sample<L: Lanes>(&self, _p: [L; 5]) -> L {
        L::cst(0.0)
    }
}
