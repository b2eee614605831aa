//! Two-dimensional FFTs (rustfft along rows, then along columns through a
//! transpose) and the periodograms the metrics use.

use std::sync::Arc;

use rustfft::num_complex::Complex;
use rustfft::{Fft, FftDirection, FftPlanner};

use crate::Field;

pub(crate) type C64 = Complex<f64>;

/// A planned 2D transform of a `width × height` row-major buffer, with
/// its working memory kept between calls.
pub(crate) struct Fft2 {
    width: usize,
    height: usize,
    rows: Arc<dyn Fft<f64>>,
    cols: Arc<dyn Fft<f64>>,
    transposed: Vec<C64>,
    scratch: Vec<C64>,
}

impl Fft2 {
    pub(crate) fn new(width: usize, height: usize, direction: FftDirection) -> Fft2 {
        let mut planner = FftPlanner::new();
        let rows = planner.plan_fft(width, direction);
        let cols = planner.plan_fft(height, direction);
        let scratch_len = rows.get_inplace_scratch_len().max(cols.get_inplace_scratch_len());
        Fft2 {
            width,
            height,
            rows,
            cols,
            transposed: vec![C64::default(); width * height],
            scratch: vec![C64::default(); scratch_len],
        }
    }

    /// Transforms `data` in place (unnormalised, like rustfft).
    pub(crate) fn process(&mut self, data: &mut [C64]) {
        let (w, h) = (self.width, self.height);
        debug_assert_eq!(data.len(), w * h);
        self.rows.process_with_scratch(data, &mut self.scratch);
        transpose(data, &mut self.transposed, w, h);
        self.cols.process_with_scratch(&mut self.transposed, &mut self.scratch);
        transpose(&self.transposed, data, h, w);
    }
}

/// `dst[i·h + j] = src[j·w + i]`, in cache-sized tiles.
fn transpose(src: &[C64], dst: &mut [C64], w: usize, h: usize) {
    const TILE: usize = 32;
    for j0 in (0..h).step_by(TILE) {
        for i0 in (0..w).step_by(TILE) {
            for j in j0..(j0 + TILE).min(h) {
                for i in i0..(i0 + TILE).min(w) {
                    dst[i * h + j] = src[j * w + i];
                }
            }
        }
    }
}

/// The separable Hann taper's 1D factor, `sin²(π(i + ½)/n)` (the
/// half-sample offset keeps it symmetric and non-zero at both ends).
fn hann(n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| {
            let s = (core::f64::consts::PI * (i as f64 + 0.5) / n as f64).sin();
            s * s
        })
        .collect()
}

/// `|F|²` normalised so that the bins sum to the (tapered) mean square.
fn power(data: &[C64], norm: f64) -> Vec<f64> {
    data.iter().map(|c| c.norm_sqr() * norm).collect()
}

/// Periodogram of `values − mean` under a separable Hann taper: leakage
/// below 1e-7, so spectral tails and band fractions are accurate.
pub(crate) fn hann_periodogram(fft: &mut Fft2, width: usize, height: usize, values: &[f64], mean: f64) -> Vec<f64> {
    let (wx, wy) = (hann(width), hann(height));
    let mut data = Vec::with_capacity(width * height);
    let mut weight = 0.0;
    for (j, row) in values.chunks_exact(width).enumerate() {
        for (i, v) in row.iter().enumerate() {
            let w = wx[i] * wy[j];
            weight += w * w;
            data.push(C64::new((v - mean) * w, 0.0));
        }
    }
    fft.process(&mut data);
    power(&data, 1.0 / (weight * (width * height) as f64))
}

/// Periodogram of the periodic component of Moisan's periodic-plus-smooth
/// decomposition (J. Math. Imaging Vis. 39:161, 2011). The smooth part `s`
/// solves `Δ_per s = v`, where `v` holds the jumps across the image's
/// borders, so `ŝ = v̂ / (2cos(2πq/W) + 2cos(2πr/H) − 4)` and the periodic
/// part is `û − ŝ`: no "+"-shaped leakage from the borders, full resolution.
pub(crate) fn periodic_periodogram(fft: &mut Fft2, field: &Field, mean: f64) -> Vec<f64> {
    let (w, h) = (field.width(), field.height());
    let mut u: Vec<C64> = field.values().iter().map(|v| C64::new(v - mean, 0.0)).collect();
    fft.process(&mut u);
    // The border image is c(j) on column 0, −c(j) on column W−1 (the jumps
    // across the left/right edge), and d(i), −d(i) on rows 0 and H−1, so
    // its transform needs only two 1D transforms:
    // v̂(q, r) = ĉ(r)·(1 − e^{2πiq/W}) + d̂(q)·(1 − e^{2πir/H}).
    let mut c: Vec<C64> = (0..h).map(|j| C64::new(field.at(w - 1, j) - field.at(0, j), 0.0)).collect();
    let mut d: Vec<C64> = (0..w).map(|i| C64::new(field.at(i, h - 1) - field.at(i, 0), 0.0)).collect();
    let mut planner = FftPlanner::new();
    planner.plan_fft_forward(h).process(&mut c);
    planner.plan_fft_forward(w).process(&mut d);
    let tau = 2.0 * core::f64::consts::PI;
    let one_minus = |k: usize, n: usize| C64::new(1.0, 0.0) - C64::from_polar(1.0, tau * k as f64 / n as f64);
    let (ex, ey): (Vec<C64>, Vec<C64>) =
        ((0..w).map(|q| one_minus(q, w)).collect(), (0..h).map(|r| one_minus(r, h)).collect());
    let cx: Vec<f64> = (0..w).map(|q| 2.0 * (tau * q as f64 / w as f64).cos()).collect();
    let cy: Vec<f64> = (0..h).map(|r| 2.0 * (tau * r as f64 / h as f64).cos()).collect();
    let norm = 1.0 / ((w * h) as f64 * (w * h) as f64);
    let mut power = vec![0.0; w * h];
    for r in 0..h {
        for q in 0..w {
            let k = r * w + q;
            if k > 0 {
                let border = c[r] * ex[q] + d[q] * ey[r];
                power[k] = (u[k] - border / (cx[q] + cy[r] - 4.0)).norm_sqr() * norm;
            }
        }
    }
    power
}

/// Sum over fields of `|X|²` for `values − mean` zero-padded to
/// `pad_w × pad_h`: its inverse transform is the linear autocorrelation.
pub(crate) fn padded_power(fft: &mut Fft2, pad_w: usize, pad_h: usize, field: &Field, mean: f64, acc: &mut [f64]) {
    let mut data = vec![C64::default(); pad_w * pad_h];
    for j in 0..field.height() {
        for (i, v) in field.row(j).iter().enumerate() {
            data[j * pad_w + i].re = v - mean;
        }
    }
    fft.process(&mut data);
    for (a, c) in acc.iter_mut().zip(&data) {
        *a += c.norm_sqr();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn border_transform_matches_the_full_one() {
        // The two-1D-transform shortcut against a direct P+S with the
        // border image transformed in full.
        let (w, h) = (20, 18);
        let field = Field::from_fn(w, h, |i, j| ((i * 7 + j * 3) as f64 * 0.77).sin() + 0.1 * i as f64).unwrap();
        let mut fft = Fft2::new(w, h, FftDirection::Forward);
        let fast = periodic_periodogram(&mut fft, &field, 0.0);
        let mut u: Vec<C64> = field.values().iter().map(|&v| C64::new(v, 0.0)).collect();
        let mut b = vec![C64::default(); w * h];
        for i in 0..w {
            let jump = field.at(i, h - 1) - field.at(i, 0);
            b[i].re += jump;
            b[(h - 1) * w + i].re -= jump;
        }
        for j in 0..h {
            let jump = field.at(w - 1, j) - field.at(0, j);
            b[j * w].re += jump;
            b[j * w + w - 1].re -= jump;
        }
        fft.process(&mut u);
        fft.process(&mut b);
        let tau = 2.0 * core::f64::consts::PI;
        for r in 0..h {
            for q in 0..w {
                let k = r * w + q;
                if k == 0 {
                    continue;
                }
                let denom = 2.0 * (tau * q as f64 / w as f64).cos() + 2.0 * (tau * r as f64 / h as f64).cos() - 4.0;
                let slow = (u[k] - b[k] / denom).norm_sqr() / ((w * h * w * h) as f64);
                assert!((slow - fast[k]).abs() < 1e-12, "bin ({q}, {r}): {slow} vs {}", fast[k]);
            }
        }
    }

    #[test]
    fn fft2_matches_a_direct_dft() {
        let (w, h) = (6, 4);
        let x: Vec<C64> = (0..w * h).map(|k| C64::new((k as f64 * 0.37).sin(), (k as f64 * 0.11).cos())).collect();
        let mut y = x.clone();
        Fft2::new(w, h, FftDirection::Forward).process(&mut y);
        // Reused working memory does not leak into the next transform.
        let mut fft = Fft2::new(w, h, FftDirection::Forward);
        fft.process(&mut vec![C64::new(9.0, -3.0); w * h]);
        let mut z = x.clone();
        fft.process(&mut z);
        assert_eq!(z, y);
        for r in 0..h {
            for q in 0..w {
                let mut sum = C64::default();
                for j in 0..h {
                    for i in 0..w {
                        let phase = -2.0 * core::f64::consts::PI * (q * i) as f64 / w as f64
                            - 2.0 * core::f64::consts::PI * (r * j) as f64 / h as f64;
                        sum += x[j * w + i] * C64::from_polar(1.0, phase);
                    }
                }
                assert!((sum - y[r * w + q]).norm() < 1e-9, "bin ({q}, {r})");
            }
        }
    }

    #[test]
    fn periodic_plus_smooth_removes_border_leakage() {
        // A linear ramp is harmonic: its periodic part is almost nothing,
        // while its raw periodogram is dominated by the wrap-around jump.
        let (w, h) = (64, 48);
        let field = Field::from_fn(w, h, |i, j| i as f64 * 0.5 + j as f64 * 0.25).unwrap();
        let mean = field.values().iter().sum::<f64>() / (w * h) as f64;
        let mut fft = Fft2::new(w, h, FftDirection::Forward);
        let ps: f64 = periodic_periodogram(&mut fft, &field, mean).iter().sum();
        let raw_var = field.values().iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (w * h) as f64;
        assert!(ps < 1e-3 * raw_var, "P+S energy {ps} vs variance {raw_var}");
    }

    #[test]
    fn periodic_plus_smooth_ignores_an_added_ramp() {
        // A ramp is harmonic, so P+S assigns it to the smooth part: the
        // periodic spectrum of texture + ramp is that of the texture alone.
        let (w, h) = (64, 64);
        let tau = 2.0 * core::f64::consts::PI;
        let texture =
            |i: usize, j: usize| (tau * 3.0 * i as f64 / w as f64).sin() * (tau * 5.0 * j as f64 / h as f64).cos();
        let plain = Field::from_fn(w, h, texture).unwrap();
        let ramped = Field::from_fn(w, h, |i, j| texture(i, j) + 0.05 * i as f64 - 0.03 * j as f64).unwrap();
        let mut fft = Fft2::new(w, h, FftDirection::Forward);
        let mean = |f: &Field| f.values().iter().sum::<f64>() / (w * h) as f64;
        let a = periodic_periodogram(&mut fft, &plain, mean(&plain));
        let b = periodic_periodogram(&mut fft, &ramped, mean(&ramped));
        let diff: f64 = a.iter().zip(&b).map(|(x, y)| (x - y).abs()).sum();
        let total: f64 = a.iter().sum();
        assert!(diff < 2e-3 * total, "P+S moved {diff} of {total}");
    }
}
