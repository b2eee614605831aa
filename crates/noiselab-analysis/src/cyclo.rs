//! Blind lattice detectors: lines in the spectrum of the local energy
//! (cyclostationarity) and the far autocorrelation.

use serde::Serialize;

use crate::bins::Bins;

/// Sharp lines in the spectrum of g = (v − mean)²: a stationary noise has
/// none, a lattice noise has them at its reciprocal-lattice frequencies.
#[derive(Clone, Debug, Serialize)]
pub struct Cyclostationarity {
    /// Largest bin over its ring mean, divided by `null_expected_max`.
    /// About 1 for a stationary noise.
    pub cyclo_max_over_null: f64,
    /// Expected largest of the n bins/ring-mean ratios of a stationary
    /// noise: the Gumbel location of Gamma(K, 1/K) variables plus γ·scale
    /// (≈ ln n + 0.577 for K = 1).
    pub null_expected_max: f64,
    /// Bins examined (rings within 60 dB of the strongest).
    pub bins: usize,
    /// Bins above three times `null_expected_max`.
    pub lines_above_3x_null: usize,
    /// The lowest-frequency line: its period in pixels and direction.
    pub lowest_line: Option<Line>,
    /// 1/f of the lowest line on a frequency axis (meaningful only for
    /// axis-aligned lattices).
    pub axis_period_estimate_px: Option<f64>,
    /// With a lattice period P: the largest ratio in the 3×3 bins around
    /// (1/P, 0) and around (0, 1/P); the null is about 3 (max of 18 bins).
    pub at_lattice_frequency: Option<f64>,
}

/// A spectral line.
#[derive(Clone, Debug, Serialize)]
pub struct Line {
    /// 1/f, pixels.
    pub period_px: f64,
    /// Direction of the wave vector, degrees in [0, 180): 0 = along x.
    pub angle_deg: f64,
    /// Bin over ring mean.
    pub ratio: f64,
}

/// Survival function of Gamma(K, 1/K) (mean 1), integer K.
fn gamma_survival(k: usize, x: f64) -> f64 {
    let kx = k as f64 * x;
    let (mut term, mut sum) = (1.0, 1.0);
    for i in 1..k {
        term *= kx / i as f64;
        sum += term;
    }
    (-kx).exp() * sum
}

/// Density of Gamma(K, 1/K).
fn gamma_density(k: usize, x: f64) -> f64 {
    let kf = k as f64;
    let log = kf.ln() + (kf - 1.0) * (kf * x).ln() - kf * x - (1..k).map(|i| (i as f64).ln()).sum::<f64>();
    log.exp()
}

/// Expected maximum of `n` iid Gamma(K, 1/K): Gumbel approximation with
/// location a (survival 1/n) and scale 1/(n·density(a)).
pub(crate) fn null_expected_max(n: usize, k: usize) -> f64 {
    let target = 1.0 / n.max(2) as f64;
    let (mut lo, mut hi) = (0.0, 200.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if gamma_survival(k, mid) > target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let a = 0.5 * (lo + hi);
    const EULER_GAMMA: f64 = 0.577_215_664_901_532_9;
    a + EULER_GAMMA / (n as f64 * gamma_density(k, a))
}

/// Lines in `power` (the K-averaged Hann periodogram of the local energy).
pub(crate) fn cyclostationarity(
    bins: &Bins,
    power: &[f64],
    fields: usize,
    lattice: Option<usize>,
) -> Cyclostationarity {
    let (means, _) = bins.ring_means(power, |_| true);
    let strongest = means.iter().skip(1).cloned().fold(0.0, f64::max);
    let valid = |ring: usize| ring >= 1 && means[ring] > 0.0 && means[ring] >= strongest * 1e-6;
    let mut n = 0usize;
    let mut best = 0.0f64;
    let mut lines: Vec<(f64, &crate::bins::Bin)> = Vec::new();
    for b in bins.bins.iter().filter(|b| valid(b.ring)) {
        n += 1;
        let ratio = power[b.index] / means[b.ring];
        best = best.max(ratio);
        lines.push((ratio, b));
    }
    let null = null_expected_max(n, fields);
    lines.retain(|(ratio, _)| *ratio > 3.0 * null);
    let as_line = |(ratio, b): &(f64, &crate::bins::Bin)| Line {
        period_px: 1.0 / b.f,
        angle_deg: b.angle.to_degrees(),
        ratio: *ratio,
    };
    let lowest = lines.iter().min_by(|a, b| a.1.f.total_cmp(&b.1.f)).map(as_line);
    let axis_lowest = lines.iter().filter(|(_, b)| b.kx == 0 || b.ky == 0).min_by(|a, b| a.1.f.total_cmp(&b.1.f));
    let at_lattice = lattice.map(|p| {
        let (w, h) = (bins.width as i64, bins.height as i64);
        let mut m = 0.0f64;
        for (cx, cy) in [((w as f64 / p as f64).round() as i64, 0), (0, (h as f64 / p as f64).round() as i64)] {
            for dy in -1..=1 {
                for dx in -1..=1 {
                    let (kx, ky) = (cx + dx, cy + dy);
                    let f = ((kx as f64 / w as f64).powi(2) + (ky as f64 / h as f64).powi(2)).sqrt();
                    let ring = (f * bins.short as f64).round() as usize;
                    if ring < means.len() && means[ring] > 0.0 {
                        let index = ky.rem_euclid(h) as usize * w as usize + kx.rem_euclid(w) as usize;
                        m = m.max(power[index] / means[ring]);
                    }
                }
            }
        }
        m
    });
    Cyclostationarity {
        cyclo_max_over_null: best / null,
        null_expected_max: null,
        bins: n,
        lines_above_3x_null: lines.len(),
        lowest_line: lowest,
        axis_period_estimate_px: axis_lowest.map(|(_, b)| 1.0 / b.f),
        at_lattice_frequency: at_lattice,
    }
}

/// The largest normalised linear autocorrelation far from the origin.
#[derive(Clone, Debug, Serialize)]
pub struct FarAutocorrelation {
    /// max over lags with max(|dx|, |dy|) ≥ `min_lag_px`, |dx| ≤ W/2,
    /// |dy| ≤ H/2: 1 when the field repeats within half its size, about
    /// 0.03–0.1 otherwise.
    pub max: f64,
    /// The lag (dx, dy) where it occurs.
    pub lag: (i64, i64),
    /// 4/f_p, rounded up.
    pub min_lag_px: usize,
}

/// From the inverse transform of the K-summed padded power (`autocorr`,
/// `pad_w × pad_h`, unnormalised): divide by the overlap and the variance.
pub(crate) fn far_autocorrelation(
    autocorr: &[f64],
    (pad_w, pad_h): (usize, usize),
    (w, h): (usize, usize),
    fields: usize,
    variance: f64,
    fp: f64,
) -> FarAutocorrelation {
    let min_lag = (4.0 / fp).ceil() as usize;
    let (mut best, mut lag) = (f64::NEG_INFINITY, (0, 0));
    let (hw, hh) = ((w / 2) as i64, (h / 2) as i64);
    for dy in -hh..=hh {
        for dx in -hw..=hw {
            if (dx.unsigned_abs().max(dy.unsigned_abs()) as usize) < min_lag {
                continue;
            }
            let overlap = (w as i64 - dx.abs()) * (h as i64 - dy.abs()) * fields as i64;
            let index = dy.rem_euclid(pad_h as i64) as usize * pad_w + dx.rem_euclid(pad_w as i64) as usize;
            let r = autocorr[index] / overlap as f64 / variance;
            if r > best {
                (best, lag) = (r, (dx, dy));
            }
        }
    }
    FarAutocorrelation { max: best, lag, min_lag_px: min_lag }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn null_max_for_one_field_is_ln_n_plus_gamma() {
        for n in [100usize, 10_000, 500_000] {
            let expected = (n as f64).ln() + 0.5772156649;
            assert!((null_expected_max(n, 1) - expected).abs() < 1e-6, "{n}");
        }
        // Averaging K periodograms concentrates the ratios near 1.
        assert!(null_expected_max(500_000, 4) < null_expected_max(500_000, 1));
        assert!(null_expected_max(500_000, 4) > 3.0);
    }
}
