//! Modified noise (Olano 2005). Placeholder until implemented.
use crate::lanes::Lanes;
use crate::noise::Noise;

/// Modified noise (being implemented).
#[derive(Clone, Debug)]
pub struct Modified;
/// Hash choice (being implemented).
#[derive(Clone, Debug)]
pub enum ModifiedHash {
    /// Olano's mod-61 squaring hash.
    Mod61,
}
/// Textured evaluation (being implemented).
#[derive(Clone, Debug)]
pub struct ModifiedTexture;
impl Noise<2> for Modified {
    fn sample<L: Lanes>(&self, _p: [L; 2]) -> L {
        L::cst(0.0)
    }
}
