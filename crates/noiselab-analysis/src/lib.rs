//! The noiselab quality lab: measures 2D noise fields the way the
//! literature does, with the value an ideal (isotropic, stationary) noise
//! would give beside every figure.
//!
//! ```
//! use noiselab_analysis::{analyze, Field, Options};
//! let seeds: Vec<Field> = (1..=4).map(|s| noiselab_analysis::reference::gaussian_noise(512, 512, 3.8, s)).collect();
//! let report = analyze(&seeds, &Options::default()).unwrap();
//! // Gaussian-filtered white noise peaks at 1/(2πσ) = 0.0419 cycles per pixel,
//! // and shows no lattice.
//! assert!((report.spectrum.peak_frequency - 0.0419).abs() < 0.005);
//! assert!(report.cyclostationarity.cyclo_max_over_null < 1.5);
//! println!("{report}");
//! ```
//!
//! The metrics and their sources are documented in `docs/quality-metrics.md`
//! and on each report type.

mod bins;
mod cyclo;
mod fft;
mod field;
pub mod io;
mod lattice;
pub mod plots;
pub mod reference;
mod report;
mod spectral;
mod stats;

use std::time::Instant;

use rustfft::FftDirection;
use serde::Serialize;

pub use cyclo::{Cyclostationarity, FarAutocorrelation, Line};
pub use field::{Field, FieldError, MIN_SIDE};
pub use lattice::{FoldedVariance, Lattice, LatticeReport, Periodicity, PeriodicityAxis};
pub use spectral::{Angular, Anisotropy, Axis, RadialBin, Spectrum};
pub use stats::ValueStats;

use bins::Bins;
use fft::{Fft2, C64};

/// What the analysis may assume about the fields.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Options {
    /// The lattice (pixels per cell and a node's pixel), enabling the node,
    /// folded-variance and C2 metrics.
    pub lattice: Option<Lattice>,
    /// A period to test, in pixels.
    pub period: Option<usize>,
}

/// Why fields cannot be analysed.
#[derive(Clone, Debug, PartialEq)]
pub enum AnalysisError {
    /// No field given.
    NoFields,
    /// Fields of different sizes cannot share one averaged periodogram.
    SizeMismatch {
        /// The first field's size.
        first: (usize, usize),
        /// The differing size.
        other: (usize, usize),
    },
    /// A constant field has no spectrum or variance to analyse.
    Constant,
    /// A zero lattice period or zero period.
    BadParameter(&'static str),
}

impl core::fmt::Display for AnalysisError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            AnalysisError::NoFields => write!(f, "no field to analyse"),
            AnalysisError::SizeMismatch { first, other } => write!(
                f,
                "fields differ in size ({}×{} and {}×{}); analyse them separately",
                first.0, first.1, other.0, other.1
            ),
            AnalysisError::Constant => write!(f, "the field is constant: nothing to analyse"),
            AnalysisError::BadParameter(what) => write!(f, "{what}"),
        }
    }
}

impl std::error::Error for AnalysisError {}

/// Everything measured on one set of fields.
#[derive(Clone, Debug, Serialize)]
pub struct Report {
    /// Fields (seeds) pooled: K.
    pub fields: usize,
    /// Columns.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// Value statistics.
    pub values: ValueStats,
    /// Peak, band-limitedness and the radial profile.
    pub spectrum: Spectrum,
    /// Ulichney/Lagae anisotropy.
    pub anisotropy: Anisotropy,
    /// Angular power at the peak ring.
    pub angular: Angular,
    /// Axis-alignment score.
    pub axis: Axis,
    /// Lattice metrics, when a lattice is given.
    pub lattice: Option<LatticeReport>,
    /// Blind cyclostationarity line detector.
    pub cyclostationarity: Cyclostationarity,
    /// Far autocorrelation.
    pub far_autocorrelation: FarAutocorrelation,
    /// Periodicity, when a period is given.
    pub periodicity: Option<Periodicity>,
    /// Analysis time, seconds (single thread).
    pub seconds: f64,
    /// The averaged P+S periodogram (FFT order), for plots.
    #[serde(skip)]
    pub power: Vec<f64>,
    /// Every value, for the histogram plot.
    #[serde(skip)]
    pub pooled_values: Vec<f64>,
}

/// Analyses `fields` (several seeds of one noise, all the same size; their
/// periodograms are averaged and their values pooled).
pub fn analyze(fields: &[Field], options: &Options) -> Result<Report, AnalysisError> {
    let start = Instant::now();
    let first = fields.first().ok_or(AnalysisError::NoFields)?;
    let (w, h) = (first.width(), first.height());
    if let Some(other) = fields.iter().find(|f| (f.width(), f.height()) != (w, h)) {
        return Err(AnalysisError::SizeMismatch { first: (w, h), other: (other.width(), other.height()) });
    }
    if let Some(l) = options.lattice {
        if !(l.period.is_finite() && l.period > 0.0) {
            return Err(AnalysisError::BadParameter("the lattice period must be a positive number of pixels"));
        }
    }
    if options.period == Some(0) {
        return Err(AnalysisError::BadParameter("the period must be a positive number of pixels"));
    }
    let k = fields.len();
    let values = stats::value_stats(fields);
    if values.std == 0.0 {
        return Err(AnalysisError::Constant);
    }
    let bins = Bins::new(w, h);
    let mut forward = Fft2::new(w, h, FftDirection::Forward);
    // Padded to 1.5× so the circular correlation does not wrap for lags up
    // to half the size.
    let (pw, ph) = ((3 * w).div_ceil(2), (3 * h).div_ceil(2));
    let mut padded = Fft2::new(pw, ph, FftDirection::Forward);
    let mut hann = vec![0.0; w * h];
    let mut periodic = vec![0.0; w * h];
    let mut energy = vec![0.0; w * h];
    let mut padded_power = vec![0.0; pw * ph];
    for field in fields {
        // Each field around its own mean: seeds may differ in offset.
        let mean = field.values().iter().sum::<f64>() / field.values().len() as f64;
        add(&mut hann, &fft::hann_periodogram(&mut forward, w, h, field.values(), mean));
        add(&mut periodic, &fft::periodic_periodogram(&mut forward, field, mean));
        let local: Vec<f64> = field.values().iter().map(|v| (v - mean) * (v - mean)).collect();
        let local_mean = local.iter().sum::<f64>() / local.len() as f64;
        add(&mut energy, &fft::hann_periodogram(&mut forward, w, h, &local, local_mean));
        fft::padded_power(&mut padded, pw, ph, field, mean, &mut padded_power);
    }
    for p in [&mut hann, &mut periodic, &mut energy] {
        p.iter_mut().for_each(|v| *v /= k as f64);
    }

    let cell = options.lattice.map(|l| l.period);
    let spectrum = spectral::spectrum(&bins, &hann, &periodic, k, cell);
    let fp = spectrum.peak_frequency;
    let lattice_px =
        options.lattice.filter(|l| (l.period - l.period.round()).abs() < 1e-9).map(|l| l.period.round() as usize);

    let mut autocorr: Vec<C64> = padded_power.iter().map(|&p| C64::new(p, 0.0)).collect();
    Fft2::new(pw, ph, FftDirection::Inverse).process(&mut autocorr);
    let autocorr: Vec<f64> = autocorr.iter().map(|c| c.re / (pw * ph) as f64).collect();

    Ok(Report {
        fields: k,
        width: w,
        height: h,
        anisotropy: spectral::anisotropy(&bins, &periodic, k, fp),
        angular: spectral::angular(&bins, &periodic, k, fp),
        axis: spectral::axis(&bins, &periodic, k),
        lattice: options.lattice.map(|l| lattice::lattice(fields, l, values.mean, values.std)),
        cyclostationarity: cyclo::cyclostationarity(&bins, &energy, k, lattice_px),
        far_autocorrelation: cyclo::far_autocorrelation(&autocorr, (pw, ph), (w, h), k, values.std * values.std, fp),
        periodicity: options.period.map(|t| lattice::periodicity(fields, t, values.std)),
        spectrum,
        power: periodic,
        pooled_values: fields.iter().flat_map(|f| f.values().iter().copied()).collect(),
        values,
        seconds: start.elapsed().as_secs_f64(),
    })
}

fn add(acc: &mut [f64], p: &[f64]) {
    acc.iter_mut().zip(p).for_each(|(a, b)| *a += b);
}
