//! The frequency bins the spectral metrics read: the unique half-plane of
//! a periodogram, so every bin is one independent sample.

/// One frequency bin.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Bin {
    /// Index into a row-major periodogram in FFT order.
    pub index: usize,
    /// Signed integer frequencies.
    pub kx: i32,
    pub ky: i32,
    /// Frequency in cycles per pixel.
    pub f: f64,
    /// Radius in bins of the shorter side (`f · L`), and its 1-bin ring.
    pub radius: f64,
    pub ring: usize,
    /// Direction in [0, π): 0 on the `ky = 0` line, π/2 on `kx = 0`.
    pub angle: f64,
}

/// The half-plane `ky > 0`, or `ky = 0, kx > 0`, without the Nyquist row
/// and column (whose bins are their own conjugates' duplicates).
pub(crate) struct Bins {
    pub width: usize,
    pub height: usize,
    /// The shorter side, `L`: rings are 1/L cycles per pixel wide.
    pub short: usize,
    pub bins: Vec<Bin>,
    /// Number of 1-bin rings (the outermost ring index + 1).
    pub rings: usize,
}

impl Bins {
    pub(crate) fn new(width: usize, height: usize) -> Bins {
        let short = width.min(height);
        let (hw, hh) = ((width / 2) as i32, (height / 2) as i32);
        let mut bins = Vec::with_capacity(width * height / 2);
        for ky in 0..hh {
            let x_start = if ky == 0 { 1 } else { 1 - hw };
            for kx in x_start..hw {
                let (fx, fy) = (kx as f64 / width as f64, ky as f64 / height as f64);
                let f = fx.hypot(fy);
                let radius = f * short as f64;
                let index = ky as usize * width + kx.rem_euclid(width as i32) as usize;
                bins.push(Bin { index, kx, ky, f, radius, ring: radius.round() as usize, angle: fy.atan2(fx) });
            }
        }
        let rings = bins.iter().map(|b| b.ring).max().unwrap_or(0) + 1;
        Bins { width, height, short, bins, rings }
    }

    /// The fundamental frequency (cycles per pixel) of the shorter side.
    pub(crate) fn f_min(&self) -> f64 {
        1.0 / self.short as f64
    }

    /// Mean of `power` per 1-bin ring over `bins` passing `keep`, with the
    /// ring counts.
    pub(crate) fn ring_means(&self, power: &[f64], keep: impl Fn(&Bin) -> bool) -> (Vec<f64>, Vec<usize>) {
        let mut sum = vec![0.0; self.rings];
        let mut count = vec![0usize; self.rings];
        for b in self.bins.iter().filter(|b| keep(b)) {
            sum[b.ring] += power[b.index];
            count[b.ring] += 1;
        }
        let mean = sum.iter().zip(&count).map(|(s, &n)| if n > 0 { s / n as f64 } else { 0.0 }).collect();
        (mean, count)
    }
}

/// Ring means linearly interpolated at a fractional radius (rings sit at
/// integer radii); empty rings are skipped by taking the nearer neighbour.
pub(crate) fn interpolate_rings(means: &[f64], counts: &[usize], radius: f64) -> f64 {
    let lo = (radius.floor() as usize).min(means.len() - 1);
    let hi = (lo + 1).min(means.len() - 1);
    let t = radius - lo as f64;
    match (counts[lo] > 0, counts[hi] > 0) {
        (true, true) => means[lo] + t * (means[hi] - means[lo]),
        (true, false) => means[lo],
        (false, true) => means[hi],
        (false, false) => 0.0,
    }
}
