//! Value statistics, pooled over every field.

use serde::Serialize;

use crate::Field;

/// Moments and range of the values.
#[derive(Clone, Debug, Serialize)]
pub struct ValueStats {
    /// Mean.
    pub mean: f64,
    /// Standard deviation (population).
    pub std: f64,
    /// Smallest value.
    pub min: f64,
    /// Largest value.
    pub max: f64,
    /// Skewness (0 for a symmetric distribution).
    pub skewness: f64,
    /// Excess kurtosis (0 for a normal distribution).
    pub excess_kurtosis: f64,
    /// Share of values with |v| > 1.
    pub fraction_outside_unit: f64,
}

pub(crate) fn value_stats(fields: &[Field]) -> ValueStats {
    let n = fields.iter().map(|f| f.values().len()).sum::<usize>() as f64;
    let all = || fields.iter().flat_map(|f| f.values().iter().copied());
    let mean = all().sum::<f64>() / n;
    let (mut m2, mut m3, mut m4) = (0.0, 0.0, 0.0);
    let (mut min, mut max, mut outside) = (f64::INFINITY, f64::NEG_INFINITY, 0usize);
    for v in all() {
        let d = v - mean;
        let d2 = d * d;
        m2 += d2;
        m3 += d2 * d;
        m4 += d2 * d2;
        min = min.min(v);
        max = max.max(v);
        outside += (v.abs() > 1.0) as usize;
    }
    let (m2, m3, m4) = (m2 / n, m3 / n, m4 / n);
    ValueStats {
        mean,
        std: m2.sqrt(),
        min,
        max,
        skewness: m3 / m2.powf(1.5),
        excess_kurtosis: m4 / (m2 * m2) - 3.0,
        fraction_outside_unit: outside as f64 / n,
    }
}
