//! Metrics of the mean power spectrum: peak frequency, band-limitedness,
//! the radial profile, anisotropy, angular power and axis alignment.

use serde::Serialize;

use crate::bins::{interpolate_rings, Bins};

/// Log-frequency resolution of the peak search: 1/24 octave.
const PEAK_BINS_PER_OCTAVE: f64 = 24.0;
/// Gaussian smoothing of the log-frequency energy: σ = 1/6 octave.
const PEAK_SMOOTHING_OCTAVES: f64 = 1.0 / 6.0;

/// Where the energy lies in frequency (Hann periodogram).
#[derive(Clone, Debug, Serialize)]
pub struct Spectrum {
    /// Mode of the energy per unit log-frequency, E(f) ∝ f²·S(f) in 2D,
    /// in cycles per pixel (1/24-octave bins smoothed by σ = 1/6 octave).
    pub peak_frequency: f64,
    /// The same in cycles per lattice cell, when a lattice period is given.
    pub peak_cycles_per_cell: Option<f64>,
    /// `exp(Σ P ln f / Σ P)`, cycles per pixel.
    pub log_centroid_frequency: f64,
    /// Energy fraction in [f_p/√2, f_p·√2] (one octave around the peak).
    /// Gaussian-filtered white noise: e^−½ − e^−2 = 0.471.
    pub octave_around_peak: f64,
    /// Energy fraction below f_p/4 (slicing leakage; Gaussian: 0.061).
    pub below_quarter_peak: f64,
    /// Energy fraction above 4·f_p (aliasing risk; Gaussian: 1.1e-7).
    pub above_four_peak: f64,
    /// The octave [f, 2f] holding the most energy, and that energy fraction.
    pub best_octave_low: f64,
    /// Energy fraction of the best octave.
    pub best_octave_fraction: f64,
    /// The profile in 1/3-octave bins.
    pub radial_log_binned: Vec<RadialBin>,
}

/// One 1/3-octave bin of the radial profile.
#[derive(Clone, Debug, Serialize)]
pub struct RadialBin {
    /// Geometric centre, cycles per pixel.
    pub frequency: f64,
    /// Mean periodogram value (power spectral density, P+S estimate).
    pub psd: f64,
    /// Share of the total energy (Hann estimate).
    pub energy_fraction: f64,
    /// Ulichney anisotropy of the bins in this band, dB over isotropic.
    pub anisotropy_excess_db: f64,
}

/// Sum of `power` over bins with `lo ≤ f < hi`.
fn band(bins: &Bins, power: &[f64], lo: f64, hi: f64) -> f64 {
    bins.bins.iter().filter(|b| b.f >= lo && b.f < hi).map(|b| power[b.index]).sum()
}

/// Energy per 1/24 octave from the fundamental up to the corner frequency.
fn log_energy(bins: &Bins, power: &[f64]) -> (Vec<f64>, f64) {
    let f0 = bins.f_min();
    let octaves = (core::f64::consts::FRAC_1_SQRT_2 / f0).log2();
    let n = (octaves * PEAK_BINS_PER_OCTAVE).ceil() as usize + 1;
    let mut e = vec![0.0; n];
    for b in &bins.bins {
        let x = (b.f / f0).log2() * PEAK_BINS_PER_OCTAVE;
        e[(x.max(0.0) as usize).min(n - 1)] += power[b.index];
    }
    (e, f0)
}

/// The peak frequency (cycles per pixel) from the log-frequency energy.
fn peak_frequency(e: &[f64], f0: f64) -> f64 {
    let sigma = PEAK_SMOOTHING_OCTAVES * PEAK_BINS_PER_OCTAVE;
    let reach = (3.0 * sigma).ceil() as isize;
    let smooth: Vec<f64> = (0..e.len() as isize)
        .map(|i| {
            let (mut s, mut w) = (0.0, 0.0);
            for d in -reach..=reach {
                if let Some(v) = e.get((i + d) as usize).filter(|_| i + d >= 0) {
                    let k = (-0.5 * (d as f64 / sigma).powi(2)).exp();
                    s += k * v;
                    w += k;
                }
            }
            s / w
        })
        .collect();
    let (i, _) = smooth.iter().enumerate().fold((0, f64::MIN), |best, (i, &v)| if v > best.1 { (i, v) } else { best });
    // Parabolic refinement of the maximum between its neighbours.
    let offset = if i > 0 && i + 1 < smooth.len() {
        let (a, b, c) = (smooth[i - 1], smooth[i], smooth[i + 1]);
        let d = a - 2.0 * b + c;
        if d < 0.0 {
            0.5 * (a - c) / d
        } else {
            0.0
        }
    } else {
        0.0
    };
    f0 * ((i as f64 + 0.5 + offset) / PEAK_BINS_PER_OCTAVE).exp2()
}

/// Everything about where the energy lies. `hann` drives the peak and the
/// band fractions (accurate tails); `periodic` the radial PSD (full
/// resolution, no border cross).
pub(crate) fn spectrum(bins: &Bins, hann: &[f64], periodic: &[f64], fields: usize, cell: Option<f64>) -> Spectrum {
    let (log, f0) = log_energy(bins, hann);
    let fp = peak_frequency(&log, f0);
    let total: f64 = bins.bins.iter().map(|b| hann[b.index]).sum();
    let frac = |lo: f64, hi: f64| band(bins, hann, lo, hi) / total;
    let sqrt2 = core::f64::consts::SQRT_2;
    let (weighted, sum) =
        bins.bins.iter().fold((0.0, 0.0), |(w, s), b| (w + hann[b.index] * b.f.ln(), s + hann[b.index]));

    // Best octave: slide a 24-bin window over the log energy.
    let per = PEAK_BINS_PER_OCTAVE as usize;
    let (mut best_start, mut best) = (0, 0.0);
    for start in 0..log.len().saturating_sub(per) {
        let s: f64 = log[start..start + per].iter().sum();
        if s > best {
            (best_start, best) = (start, s);
        }
    }

    // 1/3-octave radial bins from the fundamental, in one pass.
    let bands = ((sqrt2 * 0.5 / f0).log2() * 3.0).ceil() as usize;
    let (mut psd, mut count, mut energy) = (vec![0.0; bands], vec![0usize; bands], vec![0.0; bands]);
    for b in &bins.bins {
        let band = (((b.f / f0).log2() * 3.0).max(0.0) as usize).min(bands - 1);
        psd[band] += periodic[b.index];
        count[band] += 1;
        energy[band] += hann[b.index];
    }
    let per_ring = ring_anisotropies(bins, periodic);
    let radial = (0..bands)
        .filter(|&i| count[i] > 0)
        .map(|i| {
            let (lo, hi) = (f0 * (i as f64 / 3.0).exp2(), f0 * ((i + 1) as f64 / 3.0).exp2());
            let (a, rings) = mean_anisotropy(bins, &per_ring, lo, hi);
            RadialBin {
                frequency: (lo * hi).sqrt(),
                psd: psd[i] / count[i] as f64,
                energy_fraction: energy[i] / total,
                anisotropy_excess_db: if rings.is_empty() {
                    f64::NAN
                } else {
                    10.0 * a.log10() + 10.0 * (fields as f64).log10()
                },
            }
        })
        .collect();

    Spectrum {
        peak_frequency: fp,
        peak_cycles_per_cell: cell.map(|p| fp * p),
        log_centroid_frequency: (weighted / sum).exp(),
        octave_around_peak: frac(fp / sqrt2, fp * sqrt2),
        below_quarter_peak: frac(0.0, fp / 4.0),
        above_four_peak: frac(4.0 * fp, f64::INFINITY),
        best_octave_low: f0 * (best_start as f64 / PEAK_BINS_PER_OCTAVE).exp2(),
        best_octave_fraction: best / total,
        radial_log_binned: radial,
    }
}

/// Ulichney's anisotropy per 1-bin ring: the unbiased variance of the
/// periodogram detrended by the interpolated radial mean, over its squared
/// mean (None for rings with fewer than two bins).
fn ring_anisotropies(bins: &Bins, power: &[f64]) -> Vec<Option<f64>> {
    let (means, counts) = bins.ring_means(power, |_| true);
    let mut sum = vec![0.0; bins.rings];
    let mut sum2 = vec![0.0; bins.rings];
    let mut n = vec![0usize; bins.rings];
    for b in bins.bins.iter().filter(|b| b.ring > 0) {
        let trend = interpolate_rings(&means, &counts, b.radius);
        if trend > 0.0 {
            let q = power[b.index] / trend;
            sum[b.ring] += q;
            sum2[b.ring] += q * q;
            n[b.ring] += 1;
        }
    }
    (0..bins.rings)
        .map(|r| {
            let k = n[r] as f64;
            (n[r] > 1).then(|| {
                let mean = sum[r] / k;
                ((sum2[r] - k * mean * mean) / (k - 1.0)) / (mean * mean)
            })
        })
        .collect()
}

/// Mean anisotropy over the rings with `lo ≤ r/L ≤ hi`, and those rings.
fn mean_anisotropy(bins: &Bins, per_ring: &[Option<f64>], lo: f64, hi: f64) -> (f64, Vec<usize>) {
    let rings: Vec<usize> = (1..bins.rings)
        .filter(|&r| per_ring[r].is_some() && (lo..=hi).contains(&(r as f64 / bins.short as f64)))
        .collect();
    let mean = rings.iter().filter_map(|&r| per_ring[r]).sum::<f64>() / rings.len() as f64;
    (mean, rings)
}

/// Ulichney/Lagae anisotropy over the rings of the peak octave.
#[derive(Clone, Debug, Serialize)]
pub struct Anisotropy {
    /// 10·log10 of the mean ring anisotropy A(r) in the peak octave.
    pub peak_octave_db: f64,
    /// The isotropic reference, −10·log10 K dB for K averaged fields.
    pub isotropic_db: f64,
    /// `peak_octave_db − isotropic_db`: 0 for an isotropic noise.
    pub excess_db: f64,
    /// Mean A(r) (linear) and the null sd of that mean under isotropy,
    /// (1/K)·√((2 + 6/K)/n_ring) per ring, averaged over the rings.
    pub peak_octave_linear: f64,
    /// Null sd of `peak_octave_linear`.
    pub peak_octave_linear_null_std: f64,
    /// Rings averaged.
    pub rings: usize,
}

/// Anisotropy in the octave around `fp`, on the P+S periodogram.
pub(crate) fn anisotropy(bins: &Bins, periodic: &[f64], fields: usize, fp: f64) -> Anisotropy {
    let sqrt2 = core::f64::consts::SQRT_2;
    let k = fields as f64;
    let (_, counts) = bins.ring_means(periodic, |_| true);
    let (mean_a, rings) = mean_anisotropy(bins, &ring_anisotropies(bins, periodic), fp / sqrt2, fp * sqrt2);
    let var_sum: f64 = rings.iter().map(|&r| (1.0 / k).powi(2) * (2.0 + 6.0 / k) / counts[r] as f64).sum();
    let null_std = var_sum.sqrt() / rings.len().max(1) as f64;
    let db = 10.0 * mean_a.log10();
    let iso = -10.0 * k.log10();
    Anisotropy {
        peak_octave_db: db,
        isotropic_db: iso,
        excess_db: db - iso,
        peak_octave_linear: mean_a,
        peak_octave_linear_null_std: null_std,
        rings: rings.len(),
    }
}

/// Power by direction in the peak octave (own variant, documented): bins
/// normalised by the radial mean, averaged in 16 sectors of 11.25° over
/// 0–180°; sector 0 is centred on the `ky = 0` line, sector 8 on `kx = 0`.
#[derive(Clone, Debug, Serialize)]
pub struct Angular {
    /// Mean normalised power per sector (1 = the radial mean).
    pub sectors: Vec<f64>,
    /// Largest over smallest sector.
    pub max_over_min: f64,
    /// Coefficient of variation across sectors.
    pub cv: f64,
    /// CV an isotropic noise gives, √(mean(1/(K·n_sector))).
    pub null_cv: f64,
    /// Mean of the two axis sectors (0 and 8) over the mean sector.
    pub axis_sector_ratio: f64,
    /// Mean of the two diagonal sectors (4 and 12) over the mean sector.
    pub diagonal_sector_ratio: f64,
}

/// Angular power at the peak ring, on the P+S periodogram.
pub(crate) fn angular(bins: &Bins, periodic: &[f64], fields: usize, fp: f64) -> Angular {
    const SECTORS: usize = 16;
    let sqrt2 = core::f64::consts::SQRT_2;
    let (means, counts) = bins.ring_means(periodic, |_| true);
    let width = core::f64::consts::PI / SECTORS as f64;
    let mut sum = [0.0; SECTORS];
    let mut n = [0usize; SECTORS];
    for b in bins.bins.iter().filter(|b| b.f >= fp / sqrt2 && b.f <= fp * sqrt2) {
        let trend = interpolate_rings(&means, &counts, b.radius);
        if trend > 0.0 {
            let s = ((b.angle / width + 0.5).floor() as usize) % SECTORS;
            sum[s] += periodic[b.index] / trend;
            n[s] += 1;
        }
    }
    let sectors: Vec<f64> = (0..SECTORS).map(|s| if n[s] > 0 { sum[s] / n[s] as f64 } else { f64::NAN }).collect();
    let mean = sectors.iter().sum::<f64>() / SECTORS as f64;
    let sd = (sectors.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / SECTORS as f64).sqrt();
    let max = sectors.iter().cloned().fold(f64::MIN, f64::max);
    let min = sectors.iter().cloned().fold(f64::MAX, f64::min);
    let null = (n.iter().map(|&c| 1.0 / (fields as f64 * c.max(1) as f64)).sum::<f64>() / SECTORS as f64).sqrt();
    Angular {
        max_over_min: max / min,
        cv: sd / mean,
        null_cv: null,
        axis_sector_ratio: 0.5 * (sectors[0] + sectors[8]) / mean,
        diagonal_sector_ratio: 0.5 * (sectors[4] + sectors[12]) / mean,
        sectors,
    }
}

/// Energy on the frequency axes against what the off-axis spectrum
/// predicts there (rings 3..L/2, P+S periodogram). 1 is isotropic; above 1,
/// straight axis-aligned features; below 1, axes depleted (a hash artefact).
#[derive(Clone, Debug, Serialize)]
pub struct Axis {
    /// Σ P / Σ S̄ over the bins with `kx = 0` or `ky = 0`.
    pub axis_ratio: f64,
    /// Null sd of `axis_ratio`, √(Σ S̄²/K) / Σ S̄.
    pub null_sd: f64,
    /// `(axis_ratio − 1) / null_sd`.
    pub z: f64,
    /// The `kx = 0` line alone (variation along y).
    pub kx0_ratio: f64,
    /// The `ky = 0` line alone (variation along x, i.e. column sums).
    pub ky0_ratio: f64,
    /// The diagonal lines `|kx| = |ky|`.
    pub diagonal_ratio: f64,
}

/// Axis-alignment score on the P+S periodogram.
pub(crate) fn axis(bins: &Bins, periodic: &[f64], fields: usize) -> Axis {
    let (means, counts) = bins.ring_means(periodic, |b| b.kx != 0 && b.ky != 0);
    let max_ring = bins.short / 2;
    let line = |keep: &dyn Fn(i32, i32) -> bool| {
        let (mut p, mut s, mut s2) = (0.0, 0.0, 0.0);
        for b in bins.bins.iter().filter(|b| b.ring >= 3 && b.ring <= max_ring && keep(b.kx, b.ky)) {
            let expected = interpolate_rings(&means, &counts, b.radius);
            p += periodic[b.index];
            s += expected;
            s2 += expected * expected;
        }
        (p / s, (s2 / fields as f64).sqrt() / s)
    };
    let (axis_ratio, null_sd) = line(&|kx, ky| kx == 0 || ky == 0);
    let (kx0_ratio, _) = line(&|kx, _| kx == 0);
    let (ky0_ratio, _) = line(&|_, ky| ky == 0);
    let (diagonal_ratio, _) = line(&|kx, ky| kx.abs() == ky.abs());
    Axis { axis_ratio, null_sd, z: (axis_ratio - 1.0) / null_sd, kx0_ratio, ky0_ratio, diagonal_ratio }
}
