//! Reference fields with known spectra: the nulls every metric is read
//! against.

use rustfft::FftDirection;

use crate::fft::{Fft2, C64};
use crate::Field;

/// SplitMix64 (Steele, Lea & Flood 2014): a small, well-mixed generator.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in (0, 1].
    fn unit(&mut self) -> f64 {
        ((self.next() >> 11) + 1) as f64 / (1u64 << 53) as f64
    }
}

/// White N(0, 1) noise filtered by a Gaussian of `sigma` pixels (applied
/// in the frequency domain, so the field is periodic), scaled to std 0.25.
/// The isotropic, stationary reference: its energy per log-frequency
/// peaks at 1/(2πσ) cycles per pixel, one octave around the peak holds
/// e^−½ − e^−2 = 0.471 of the energy, below a quarter of the peak
/// 1 − e^−1/16 = 0.061.
pub fn gaussian_noise(width: usize, height: usize, sigma: f64, seed: u64) -> Field {
    let mut rng = SplitMix64(seed);
    // Box–Muller: two uniforms give one normal (the other is discarded for
    // simplicity; speed is not a concern here).
    let mut data: Vec<C64> = (0..width * height)
        .map(|_| {
            let (u, v) = (rng.unit(), rng.unit());
            C64::new((-2.0 * u.ln()).sqrt() * (2.0 * core::f64::consts::PI * v).cos(), 0.0)
        })
        .collect();
    Fft2::new(width, height, FftDirection::Forward).process(&mut data);
    let two_pi_sigma2 = 2.0 * (core::f64::consts::PI * sigma).powi(2);
    for r in 0..height {
        let fy = signed(r, height) / height as f64;
        for q in 0..width {
            let fx = signed(q, width) / width as f64;
            // Fourier transform of a unit-sum Gaussian: exp(−2π²σ²f²).
            data[r * width + q] *= (-two_pi_sigma2 * (fx * fx + fy * fy)).exp();
        }
    }
    data[0] = C64::default();
    Fft2::new(width, height, FftDirection::Inverse).process(&mut data);
    let values: Vec<f64> = data.iter().map(|c| c.re).collect();
    let sd = (values.iter().map(|v| v * v).sum::<f64>() / values.len() as f64).sqrt();
    Field::new(width, height, values.iter().map(|v| 0.25 * v / sd).collect())
        .expect("finite, non-empty reference field")
}

fn signed(k: usize, n: usize) -> f64 {
    if k <= n / 2 {
        k as f64
    } else {
        k as f64 - n as f64
    }
}
