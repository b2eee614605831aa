//! Metrics that know the lattice: node values, folded variance and the
//! second-derivative jump across cell faces; and periodicity for a period.

use serde::Serialize;

use crate::Field;

/// Where the lattice lies: `period` pixels per cell, a node at pixel
/// `offset` (column, row).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lattice {
    /// Pixels per lattice cell.
    pub period: f64,
    /// Pixel (column, row) of a lattice node.
    pub offset: (usize, usize),
}

/// Lattice metrics.
#[derive(Clone, Debug, Serialize)]
pub struct LatticeReport {
    /// Pixels per cell.
    pub period_px: f64,
    /// Node pixel (column, row).
    pub offset: (usize, usize),
    /// Whether nodes fall exactly on pixels (integer period). When false,
    /// the node, folded-variance and C2 numbers are not meaningful and
    /// are left out.
    pub exact: bool,
    /// std(values at nodes) / std(all values): 0 for gradient noise on a
    /// lattice plane, about 1 for a stationary noise, > 1 for value noise.
    pub node_value_score: Option<f64>,
    /// Root mean square of the node values.
    pub node_rms: Option<f64>,
    /// Largest |value| at a node.
    pub node_max_abs: Option<f64>,
    /// Folded variance: E[(v − mean)²] at each of the P×P cell phases,
    /// relative to the variance.
    pub folded_variance: Option<FoldedVariance>,
    /// Mean |f''(b+) − f''(b−)| at cell faces over mean |f''|, both axes
    /// (one-sided 6-point stencils): about 2 for a C1 interpolant (cubic
    /// fade), the P⁻⁴ truncation residual for C2 (quintic).
    pub c2_jump_score: Option<f64>,
    /// The same statistic at cell centres: what "no jump" gives.
    pub c2_reference_score: Option<f64>,
}

/// Variance by position inside the cell.
#[derive(Clone, Debug, Serialize)]
pub struct FoldedVariance {
    /// Coefficient of variation over the phases (flat = stationary).
    pub folded_variance_cv: f64,
    /// What independent samples give, √(2/n_phase); a correlated
    /// stationary noise stays at or below it.
    pub null_cv: f64,
    /// Smallest relative phase variance.
    pub min: f64,
    /// Largest relative phase variance.
    pub max: f64,
    /// Relative variance at the node phase.
    pub at_node: f64,
    /// Largest |phase mean − mean| over the std.
    pub folded_mean_max_over_std: f64,
    /// The P×P map (row-major, phase (0, 0) = the node), for plots.
    #[serde(skip)]
    pub map: Vec<f64>,
}

/// One-sided second derivative from six samples, exact for quintics:
/// coefficients 15/4, −77/6, 107/6, −13, 61/12, −5/6.
const ONE_SIDED_F2: [f64; 6] = [15.0 / 4.0, -77.0 / 6.0, 107.0 / 6.0, -13.0, 61.0 / 12.0, -5.0 / 6.0];

pub(crate) fn lattice(fields: &[Field], lattice: Lattice, mean: f64, std: f64) -> LatticeReport {
    let p = lattice.period;
    let exact = p >= 1.0 && (p - p.round()).abs() < 1e-9;
    let mut report = LatticeReport {
        period_px: p,
        offset: lattice.offset,
        exact,
        node_value_score: None,
        node_rms: None,
        node_max_abs: None,
        folded_variance: None,
        c2_jump_score: None,
        c2_reference_score: None,
    };
    if !exact {
        return report;
    }
    let p = p.round() as usize;
    let (ox, oy) = lattice.offset;
    let nodes: Vec<f64> = fields
        .iter()
        .flat_map(|f| {
            let xs = (ox % p..f.width()).step_by(p);
            (oy % p..f.height()).step_by(p).flat_map(move |j| xs.clone().map(move |i| f.at(i, j)))
        })
        .collect();
    if !nodes.is_empty() {
        let n = nodes.len() as f64;
        let node_mean = nodes.iter().sum::<f64>() / n;
        let node_std = (nodes.iter().map(|v| (v - node_mean).powi(2)).sum::<f64>() / n).sqrt();
        report.node_value_score = Some(node_std / std);
        report.node_rms = Some((nodes.iter().map(|v| v * v).sum::<f64>() / n).sqrt());
        report.node_max_abs = Some(nodes.iter().fold(0.0, |m: f64, v| m.max(v.abs())));
    }
    report.folded_variance = Some(folded_variance(fields, p, (ox, oy), mean, std));
    if p >= 6 {
        let jump = c2_score(fields, p, (ox, oy));
        let reference = c2_score(fields, p, (ox + p / 2, oy + p / 2));
        report.c2_jump_score = Some(jump);
        report.c2_reference_score = Some(reference);
    }
    report
}

fn folded_variance(fields: &[Field], p: usize, (ox, oy): (usize, usize), mean: f64, std: f64) -> FoldedVariance {
    let mut sum = vec![0.0; p * p];
    let mut sq = vec![0.0; p * p];
    let mut count = vec![0usize; p * p];
    for f in fields {
        for j in 0..f.height() {
            let py = (j + p - oy % p) % p;
            for (i, v) in f.row(j).iter().enumerate() {
                let k = py * p + (i + p - ox % p) % p;
                let d = v - mean;
                sum[k] += d;
                sq[k] += d * d;
                count[k] += 1;
            }
        }
    }
    let var = std * std;
    let map: Vec<f64> = sq.iter().zip(&count).map(|(s, &n)| s / n.max(1) as f64 / var).collect();
    let m = map.iter().sum::<f64>() / map.len() as f64;
    let sd = (map.iter().map(|v| (v - m).powi(2)).sum::<f64>() / map.len() as f64).sqrt();
    let n_phase = count.iter().sum::<usize>() as f64 / count.len() as f64;
    let folded_mean_max = sum.iter().zip(&count).map(|(s, &n)| (s / n.max(1) as f64).abs()).fold(0.0, f64::max);
    FoldedVariance {
        folded_variance_cv: sd / m,
        null_cv: (2.0 / n_phase).sqrt(),
        min: map.iter().cloned().fold(f64::MAX, f64::min),
        max: map.iter().cloned().fold(f64::MIN, f64::max),
        at_node: map[0],
        folded_mean_max_over_std: folded_mean_max / std,
        map,
    }
}

/// Mean |f''(b+) − f''(b−)| over the faces `b ≡ origin (mod p)` on both
/// axes, over mean |central second difference|.
fn c2_score(fields: &[Field], p: usize, (ox, oy): (usize, usize)) -> f64 {
    let (mut jump, mut jumps, mut curv, mut curvs) = (0.0, 0usize, 0.0, 0usize);
    // `line(k)` reads sample k of one row or column of length n.
    let mut scan = |n: usize, origin: usize, line: &dyn Fn(usize) -> f64| {
        for k in 1..n - 1 {
            curv += (line(k + 1) - 2.0 * line(k) + line(k - 1)).abs();
            curvs += 1;
        }
        for b in (origin % p..n).step_by(p).filter(|&b| b >= 5 && b + 5 < n) {
            let (mut ahead, mut behind) = (0.0, 0.0);
            for (s, c) in ONE_SIDED_F2.iter().enumerate() {
                ahead += c * line(b + s);
                behind += c * line(b - s);
            }
            jump += (ahead - behind).abs();
            jumps += 1;
        }
    };
    for f in fields {
        for j in 0..f.height() {
            scan(f.width(), ox, &|i| f.at(i, j));
        }
        for i in 0..f.width() {
            scan(f.height(), oy, &|j| f.at(i, j));
        }
    }
    (jump / jumps.max(1) as f64) / (curv / curvs.max(1) as f64)
}

/// How far the field is from repeating with a period.
#[derive(Clone, Debug, Serialize)]
pub struct Periodicity {
    /// The period tested, pixels.
    pub period_px: usize,
    /// Along x (None when the field is not wider than the period).
    pub x: Option<PeriodicityAxis>,
    /// Along y.
    pub y: Option<PeriodicityAxis>,
}

/// `v(p + T·e) − v(p)` along one axis.
#[derive(Clone, Debug, Serialize)]
pub struct PeriodicityAxis {
    /// Largest |difference|: 0 for a periodic field.
    pub max_abs_diff: f64,
    /// rms(difference) / (√2·std): 0 periodic, about 1 unrelated.
    pub rms_ratio: f64,
}

pub(crate) fn periodicity(fields: &[Field], t: usize, std: f64) -> Periodicity {
    let axis = |dx: usize, dy: usize| {
        let (mut max, mut sq, mut n) = (0.0f64, 0.0, 0usize);
        for f in fields {
            if f.width() <= dx || f.height() <= dy {
                return None;
            }
            for j in 0..f.height() - dy {
                for i in 0..f.width() - dx {
                    let d = f.at(i + dx, j + dy) - f.at(i, j);
                    max = max.max(d.abs());
                    sq += d * d;
                    n += 1;
                }
            }
        }
        Some(PeriodicityAxis {
            max_abs_diff: max,
            rms_ratio: (sq / n as f64).sqrt() / (core::f64::consts::SQRT_2 * std),
        })
    };
    Periodicity { period_px: t, x: axis(t, 0), y: axis(0, t) }
}
