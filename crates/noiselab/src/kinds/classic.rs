//! Classic noise (Perlin 1985). Placeholder until implemented.
use crate::lanes::Lanes;
use crate::noise::Noise;

/// Perlin's 1985 gradient noise (being implemented).
#[derive(Clone, Debug)]
pub struct Classic;
impl Noise<1> for Classic {
    fn sample<L: Lanes>(&self, _p: [L; 1]) -> L {
        L::cst(0.0)
    }
}
