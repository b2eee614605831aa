//! PNG pictures for the analysis report, drawn pixel by pixel (no text).
//!
//! Every function writes to a sibling `*.tmp` file and renames it into
//! place, so a report never links to a half-written picture. Odd input
//! (empty slices, NaN, zero ranges) gives a blank or partial plot, never a
//! panic; only a picture that cannot exist (zero size, a buffer of the
//! wrong length) is an `InvalidInput` error.

use std::fs::{self, File};
use std::io::{self, BufWriter};
use std::path::{Path, PathBuf};

type Rgb = [u8; 3];

const WHITE: Rgb = [255, 255, 255];
const FRAME: Rgb = [128, 128, 128];
const GRID: Rgb = [224, 224, 224];
const CURVE_BLUE: Rgb = [16, 32, 128];
const BAR_BLUE: Rgb = [176, 196, 222];
const NORMAL_RED: Rgb = [210, 20, 20];
/// Cells of the variance map with no finite value.
const MISSING: Rgb = [128, 128, 128];

/// Size of the chart pictures.
const CHART_WIDTH: usize = 640;
const CHART_HEIGHT: usize = 400;

/// Dynamic range of the spectrum picture: the brightest pixel is the
/// maximum, black is this many dB below it.
const SPECTRUM_RANGE_DB: f64 = 60.0;

/// Writes `power` (a `width × height` row-major periodogram in FFT order,
/// DC at index 0) as an 8-bit grey PNG with DC moved to the centre pixel
/// `(width / 2, height / 2)`, brightness linear in dB over the top 60 dB.
pub fn power_spectrum(path: &Path, width: usize, height: usize, power: &[f64]) -> io::Result<()> {
    if width == 0 || height == 0 || width.checked_mul(height) != Some(power.len()) {
        return Err(invalid_input(format!(
            "power spectrum of {} values cannot be drawn as {width}×{height}",
            power.len()
        )));
    }
    let db: Vec<f64> =
        power.iter().map(|&p| if p > 0.0 && p.is_finite() { 10.0 * p.log10() } else { f64::NAN }).collect();
    let top = db.iter().copied().filter(|d| d.is_finite()).fold(f64::NEG_INFINITY, f64::max);
    let mut grey = Vec::with_capacity(power.len());
    for y in 0..height {
        // fftshift: output row y shows frequency row (y - height/2) mod height.
        let ky = (y + height - height / 2) % height;
        for x in 0..width {
            let kx = (x + width - width / 2) % width;
            let level = (db[kx + ky * width] - (top - SPECTRUM_RANGE_DB)) / SPECTRUM_RANGE_DB;
            // Zero, negative and non-finite power has no level: black.
            grey.push(if level.is_nan() { 0 } else { (level.clamp(0.0, 1.0) * 255.0).round() as u8 });
        }
    }
    write_png(path, width, height, png::ColorType::Grayscale, &grey)
}

/// Draws a radial power profile — `(frequency in cycles/pixel, power)`
/// points — on log-log axes (log10 f across, 10·log10 power up) with grid
/// lines at each decade of f and every 10 dB. Non-positive and non-finite
/// points are skipped.
pub fn radial_profile(path: &Path, profile: &[(f64, f64)]) -> io::Result<()> {
    let mut points: Vec<(f64, f64)> = profile
        .iter()
        .filter(|(f, p)| f.is_finite() && p.is_finite() && *f > 0.0 && *p > 0.0)
        .map(|&(f, p)| (f.log10(), 10.0 * p.log10()))
        .collect();
    points.sort_by(|a, b| a.0.total_cmp(&b.0));

    let mut canvas = Canvas::new(CHART_WIDTH, CHART_HEIGHT, WHITE);
    let frame = Frame::chart();
    if let (Some(x), Some(y)) = (span(points.iter().map(|p| p.0)), span(points.iter().map(|p| p.1))) {
        // Half a decade / 5 dB of room when all points share a coordinate.
        let axes = Axes { frame, x: padded(x, 0.5), y: padded(y, 5.0) };
        for decade in multiples_in(axes.x, 1.0) {
            canvas.vline(axes.px(decade), frame, GRID);
        }
        for level in multiples_in(axes.y, 10.0) {
            canvas.hline(axes.py(level), frame, GRID);
        }
        let pixels: Vec<_> = points.iter().map(|&(x, y)| (axes.px(x), axes.py(y))).collect();
        canvas.polyline(&pixels, CURVE_BLUE);
    }
    canvas.outline(frame, FRAME);
    canvas.save(path)
}

/// Number of histogram bins.
const BINS: usize = 100;

/// Draws a 100-bin density histogram of the finite `values` over their
/// range, with the normal density N(`mean`, `std`) over it in red.
pub fn histogram(path: &Path, values: &[f64], mean: f64, std: f64) -> io::Result<()> {
    let finite: Vec<f64> = values.iter().copied().filter(|v| v.is_finite()).collect();
    let mut canvas = Canvas::new(CHART_WIDTH, CHART_HEIGHT, WHITE);
    let frame = Frame::chart();
    if let Some(x) = span(finite.iter().copied()) {
        // All values equal: centre a unit-wide range on them.
        let x = if x.1 > x.0 { x } else { (x.0 - 0.5, x.0 + 0.5) };
        let densities = bin_densities(&finite, x);
        let columns = frame.left..=frame.right;
        let curve: Vec<(f64, f64)> = columns
            .map(|c| {
                let t = (c - frame.left) as f64 / (frame.right - frame.left) as f64;
                let v = x.0 + t * (x.1 - x.0);
                (c as f64, normal_density(v, mean, std))
            })
            .filter(|(_, d)| d.is_finite())
            .collect();
        let peak = densities.iter().chain(curve.iter().map(|(_, d)| d)).copied().fold(0.0, f64::max);
        let top = if peak > 0.0 && peak.is_finite() { peak * 1.05 } else { 1.0 };
        let axes = Axes { frame, x, y: (0.0, top) };

        let bin_width = (x.1 - x.0) / BINS as f64;
        for (k, &density) in densities.iter().enumerate() {
            let left = axes.px(x.0 + k as f64 * bin_width);
            let right = axes.px(x.0 + (k + 1) as f64 * bin_width);
            canvas.fill(left, axes.py(density), right, axes.py(0.0), BAR_BLUE);
        }
        let pixels: Vec<_> = curve.iter().map(|&(c, d)| (c, axes.py(d))).collect();
        canvas.polyline(&pixels, NORMAL_RED);
    }
    canvas.outline(frame, FRAME);
    canvas.save(path)
}

/// `count / (n · bin width)` for each of [`BINS`] equal bins over `range`.
fn bin_densities(values: &[f64], range: (f64, f64)) -> Vec<f64> {
    let bin_width = (range.1 - range.0) / BINS as f64;
    let mut counts = vec![0usize; BINS];
    for v in values {
        // `as` saturates (NaN → 0); the max value lands in the last bin.
        let k = ((v - range.0) / bin_width) as usize;
        counts[k.min(BINS - 1)] += 1;
    }
    let scale = values.len() as f64 * bin_width;
    counts.iter().map(|&c| if scale > 0.0 { c as f64 / scale } else { 0.0 }).collect()
}

/// The normal density; NaN when the distribution is degenerate, so the
/// caller drops the curve.
fn normal_density(x: f64, mean: f64, std: f64) -> f64 {
    if !(std > 0.0 && std.is_finite() && mean.is_finite()) {
        return f64::NAN;
    }
    let z = (x - mean) / std;
    (-0.5 * z * z).exp() / (std * (2.0 * std::f64::consts::PI).sqrt())
}

/// Smallest side of the variance picture.
const MIN_MAP_SIDE: usize = 256;

/// Draws a `period × period` row-major relative-variance map, each cell
/// blown up to `ceil(256 / period)` pixels square: 1.0 is white, higher
/// values go towards red and lower towards blue, saturating at ±50 %.
pub fn folded_variance(path: &Path, period: usize, map: &[f64]) -> io::Result<()> {
    if period == 0 || period.checked_mul(period) != Some(map.len()) {
        return Err(invalid_input(format!("variance map of {} values is not {period}×{period}", map.len())));
    }
    let zoom = MIN_MAP_SIDE.div_ceil(period);
    let side = period * zoom;
    let mut canvas = Canvas::new(side, side, WHITE);
    for (index, &value) in map.iter().enumerate() {
        let (x, y) = ((index % period) * zoom, (index / period) * zoom);
        let (x, y) = (x as f64, y as f64);
        let last = (zoom - 1) as f64;
        canvas.fill(x, y, x + last, y + last, diverging(value));
    }
    canvas.save(path)
}

/// Blue–white–red around 1.0, saturating where |v − 1| ≥ 0.5.
fn diverging(value: f64) -> Rgb {
    if !value.is_finite() {
        return MISSING;
    }
    let d = ((value - 1.0) / 0.5).clamp(-1.0, 1.0);
    let fade = (255.0 * (1.0 - d.abs())).round() as u8;
    if d >= 0.0 {
        [255, fade, fade]
    } else {
        [fade, fade, 255]
    }
}

fn invalid_input(message: String) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidInput, message)
}

/// `(min, max)` of the values, or `None` when there are none.
fn span(values: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    values.fold(None, |acc, v| match acc {
        None => Some((v, v)),
        Some((lo, hi)) => Some((lo.min(v), hi.max(v))),
    })
}

/// The range widened by 5 % each side, or to `± half` around a single value.
fn padded((lo, hi): (f64, f64), half: f64) -> (f64, f64) {
    if hi > lo {
        let pad = 0.05 * (hi - lo);
        (lo - pad, hi + pad)
    } else {
        (lo - half, lo + half)
    }
}

/// Multiples of `step` inside `[lo, hi]`.
fn multiples_in((lo, hi): (f64, f64), step: f64) -> impl Iterator<Item = f64> {
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    (first..=last).map(move |k| k as f64 * step)
}

/// The pixel rectangle (inclusive) that holds the data of a chart.
#[derive(Clone, Copy)]
struct Frame {
    left: usize,
    top: usize,
    right: usize,
    bottom: usize,
}

impl Frame {
    /// The chart pictures leave a margin round the frame, wider at the
    /// left and bottom where axis labels would go.
    fn chart() -> Frame {
        Frame { left: 50, top: 20, right: CHART_WIDTH - 21, bottom: CHART_HEIGHT - 41 }
    }
}

/// Maps data coordinates to pixel coordinates inside a frame.
struct Axes {
    frame: Frame,
    x: (f64, f64),
    y: (f64, f64),
}

impl Axes {
    fn px(&self, x: f64) -> f64 {
        let (left, right) = (self.frame.left as f64, self.frame.right as f64);
        left + (x - self.x.0) / (self.x.1 - self.x.0) * (right - left)
    }

    /// Pixel rows grow downwards, data upwards.
    fn py(&self, y: f64) -> f64 {
        let (top, bottom) = (self.frame.top as f64, self.frame.bottom as f64);
        bottom - (y - self.y.0) / (self.y.1 - self.y.0) * (bottom - top)
    }
}

/// Rounds a coordinate to a pixel, pulled in to just outside `0..limit`
/// so wild values cannot make the drawing loops run for ages.
fn to_pixel(v: f64, limit: usize) -> i64 {
    if v.is_nan() {
        return -1;
    }
    v.round().clamp(-2.0, limit as f64 + 1.0) as i64
}

/// An RGB picture being drawn. Drawing outside it is clipped silently.
struct Canvas {
    width: usize,
    height: usize,
    pixels: Vec<u8>,
}

impl Canvas {
    fn new(width: usize, height: usize, background: Rgb) -> Canvas {
        Canvas { width, height, pixels: background.repeat(width * height) }
    }

    fn set(&mut self, x: i64, y: i64, colour: Rgb) {
        if let (Ok(x), Ok(y)) = (usize::try_from(x), usize::try_from(y)) {
            if x < self.width && y < self.height {
                let at = 3 * (y * self.width + x);
                self.pixels[at..at + 3].copy_from_slice(&colour);
            }
        }
    }

    /// Fills the rectangle between two corners (inclusive, any order).
    fn fill(&mut self, x0: f64, y0: f64, x1: f64, y1: f64, colour: Rgb) {
        let (x0, x1) = (to_pixel(x0, self.width), to_pixel(x1, self.width));
        let (y0, y1) = (to_pixel(y0, self.height), to_pixel(y1, self.height));
        for y in y0.min(y1)..=y0.max(y1) {
            for x in x0.min(x1)..=x0.max(x1) {
                self.set(x, y, colour);
            }
        }
    }

    fn vline(&mut self, x: f64, frame: Frame, colour: Rgb) {
        self.fill(x, frame.top as f64, x, frame.bottom as f64, colour);
    }

    fn hline(&mut self, y: f64, frame: Frame, colour: Rgb) {
        self.fill(frame.left as f64, y, frame.right as f64, y, colour);
    }

    fn outline(&mut self, frame: Frame, colour: Rgb) {
        self.vline(frame.left as f64, frame, colour);
        self.vline(frame.right as f64, frame, colour);
        self.hline(frame.top as f64, frame, colour);
        self.hline(frame.bottom as f64, frame, colour);
    }

    /// A 2-pixel-thick line by Bresenham's algorithm: each step stamps a
    /// 2×2 block, which keeps diagonal segments as heavy as straight ones.
    fn line(&mut self, from: (f64, f64), to: (f64, f64), colour: Rgb) {
        let (mut x, mut y) = (to_pixel(from.0, self.width), to_pixel(from.1, self.height));
        let (x1, y1) = (to_pixel(to.0, self.width), to_pixel(to.1, self.height));
        let (dx, dy) = ((x1 - x).abs(), -(y1 - y).abs());
        let (sx, sy) = ((x1 - x).signum(), (y1 - y).signum());
        let mut err = dx + dy;
        loop {
            for (ox, oy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                self.set(x + ox, y + oy, colour);
            }
            if x == x1 && y == y1 {
                return;
            }
            let e2 = 2 * err;
            if e2 >= dy {
                err += dy;
                x += sx;
            }
            if e2 <= dx {
                err += dx;
                y += sy;
            }
        }
    }

    /// Joins consecutive points; a single point is drawn as a dot.
    fn polyline(&mut self, points: &[(f64, f64)], colour: Rgb) {
        match points {
            [only] => self.line(*only, *only, colour),
            _ => {
                for pair in points.windows(2) {
                    self.line(pair[0], pair[1], colour);
                }
            }
        }
    }

    fn save(&self, path: &Path) -> io::Result<()> {
        write_png(path, self.width, self.height, png::ColorType::Rgb, &self.pixels)
    }
}

/// Encodes 8-bit pixels to `path` via a sibling temporary file, renamed
/// into place only once complete.
fn write_png(path: &Path, width: usize, height: usize, colour: png::ColorType, data: &[u8]) -> io::Result<()> {
    let too_big = |_| invalid_input(format!("a {width}×{height} picture is too large for PNG"));
    let (width, height) = (u32::try_from(width).map_err(too_big)?, u32::try_from(height).map_err(too_big)?);
    let tmp = temp_path(path)?;
    let result = encode(&tmp, width, height, colour, data).and_then(|()| fs::rename(&tmp, path));
    if result.is_err() {
        // Best effort: the original error is the one worth reporting.
        let _ = fs::remove_file(&tmp);
    }
    result
}

/// `picture.png` → `picture.png.tmp`, in the same directory so the
/// rename cannot cross file systems.
fn temp_path(path: &Path) -> io::Result<PathBuf> {
    let mut name =
        path.file_name().ok_or_else(|| invalid_input(format!("{} is not a file path", path.display())))?.to_os_string();
    name.push(".tmp");
    Ok(path.with_file_name(name))
}

fn encode(path: &Path, width: u32, height: u32, colour: png::ColorType, data: &[u8]) -> io::Result<()> {
    let mut encoder = png::Encoder::new(BufWriter::new(File::create(path)?), width, height);
    encoder.set_color(colour);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header()?;
    writer.write_image_data(data)?;
    writer.finish()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::BufReader;

    struct Decoded {
        width: u32,
        height: u32,
        colour: png::ColorType,
        pixels: Vec<u8>,
    }

    impl Decoded {
        fn rgb(&self, x: u32, y: u32) -> Rgb {
            let at = 3 * (y * self.width + x) as usize;
            [self.pixels[at], self.pixels[at + 1], self.pixels[at + 2]]
        }

        fn has_non_white(&self) -> bool {
            self.pixels.chunks(3).any(|p| p != WHITE)
        }

        /// True if any pixel has this exact colour.
        fn has(&self, colour: Rgb) -> bool {
            self.pixels.chunks(3).any(|p| p == colour)
        }
    }

    fn decode(path: &Path) -> Decoded {
        let decoder = png::Decoder::new(BufReader::new(File::open(path).unwrap()));
        let mut reader = decoder.read_info().unwrap();
        let mut pixels = vec![0; reader.output_buffer_size().unwrap()];
        let info = reader.next_frame(&mut pixels).unwrap();
        assert_eq!(info.bit_depth, png::BitDepth::Eight);
        pixels.truncate(info.buffer_size());
        Decoded { width: info.width, height: info.height, colour: info.color_type, pixels }
    }

    /// Asserts the directory holds exactly the named files (no `.tmp`).
    fn assert_only(dir: &Path, names: &[&str]) {
        let mut found: Vec<String> =
            fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).collect();
        found.sort();
        let mut names: Vec<String> = names.iter().map(|n| n.to_string()).collect();
        names.sort();
        assert_eq!(found, names);
    }

    #[test]
    fn power_spectrum_centres_dc() {
        let dir = tempfile::tempdir().unwrap();
        for (width, height) in [(32, 16), (17, 21)] {
            let path = dir.path().join(format!("spectrum-{width}x{height}.png"));
            let mut power = vec![1e-9; width * height];
            power[0] = 1.0;
            power[1] = f64::NAN;
            power[2] = -1.0;
            power_spectrum(&path, width, height, &power).unwrap();

            let image = decode(&path);
            assert_eq!((image.width, image.height), (width as u32, height as u32));
            assert_eq!(image.colour, png::ColorType::Grayscale);
            let grey = |x: usize, y: usize| image.pixels[y * width + x];
            assert_eq!(grey(width / 2, height / 2), 255);
            assert_eq!(grey(0, 0), 0);
            assert_eq!(image.pixels.iter().filter(|&&g| g != 0).count(), 1);
        }
        assert_only(dir.path(), &["spectrum-17x21.png", "spectrum-32x16.png"]);
    }

    #[test]
    fn power_spectrum_scales_60_db() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("s.png");
        let mut power = vec![0.0; 16 * 16];
        power[0] = 1e6;
        power[1] = 1e3; // 30 dB below the maximum: mid grey
        power_spectrum(&path, 16, 16, &power).unwrap();
        assert_eq!(decode(&path).pixels[8 * 16 + 9], 128);
    }

    #[test]
    fn power_spectrum_rejects_wrong_length() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("s.png");
        let err = power_spectrum(&path, 16, 16, &[1.0; 10]).unwrap_err();
        assert_eq!(err.kind(), io::ErrorKind::InvalidInput);
        assert!(power_spectrum(&path, 0, 0, &[]).is_err());
        assert_only(dir.path(), &[]);
    }

    #[test]
    fn radial_profile_draws_curve() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("radial.png");
        let profile: Vec<(f64, f64)> = (1..200).map(|k| (k as f64 / 400.0, 1.0 / (k * k) as f64)).collect();
        radial_profile(&path, &profile).unwrap();
        let image = decode(&path);
        assert_eq!((image.width, image.height, image.colour), (640, 400, png::ColorType::Rgb));
        assert!(image.has(CURVE_BLUE) && image.has(GRID) && image.has(FRAME));
        assert_eq!(image.rgb(0, 0), WHITE);
        assert_only(dir.path(), &["radial.png"]);
    }

    #[test]
    fn radial_profile_survives_odd_input() {
        let dir = tempfile::tempdir().unwrap();
        let odd: [&[(f64, f64)]; 4] = [
            &[],
            &[(f64::NAN, 1.0), (0.0, 1.0), (0.1, -1.0), (0.2, f64::INFINITY)],
            &[(0.1, 1.0)],
            &[(0.1, 1.0), (0.1, 1.0), (1e-300, 1e300)],
        ];
        for (k, profile) in odd.iter().enumerate() {
            let path = dir.path().join(format!("r{k}.png"));
            radial_profile(&path, profile).unwrap();
            let image = decode(&path);
            assert_eq!((image.width, image.height), (640, 400));
            assert!(image.has_non_white(), "the frame is always drawn");
        }
        assert!(decode(&dir.path().join("r2.png")).has(CURVE_BLUE), "a single point is a dot");
    }

    #[test]
    fn histogram_draws_bars_and_normal() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("hist.png");
        // A deterministic bell-ish sample: sums of three uniform-ish values.
        let values: Vec<f64> = (0..5000u64)
            .map(|k| (0..3).map(|s| ((k * 7919 + s * 104729) % 1000) as f64 / 1000.0).sum::<f64>())
            .collect();
        histogram(&path, &values, 1.5, 0.5).unwrap();
        let image = decode(&path);
        assert_eq!((image.width, image.height, image.colour), (640, 400, png::ColorType::Rgb));
        assert!(image.has(BAR_BLUE) && image.has(NORMAL_RED) && image.has(FRAME));
        assert_only(dir.path(), &["hist.png"]);
    }

    #[test]
    fn histogram_survives_odd_input() {
        let dir = tempfile::tempdir().unwrap();
        let cases: [(&[f64], f64, f64); 5] = [
            (&[], 0.0, 1.0),
            (&[f64::NAN, f64::INFINITY], f64::NAN, f64::NAN),
            (&[2.0; 10], 2.0, 0.0),
            (&[-f64::MAX, f64::MAX], 0.0, 1e-320),
            (&[0.0, 1.0, f64::NAN], 0.5, 0.5),
        ];
        for (k, (values, mean, std)) in cases.into_iter().enumerate() {
            let path = dir.path().join(format!("h{k}.png"));
            histogram(&path, values, mean, std).unwrap();
            let image = decode(&path);
            assert_eq!((image.width, image.height), (640, 400));
            assert!(image.has_non_white());
        }
        assert!(decode(&dir.path().join("h2.png")).has(BAR_BLUE), "equal values make one bar");
    }

    #[test]
    fn folded_variance_colours() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("folded.png");
        // period 3 → zoom 86 → 258 px; cells: 1.0, 1.5, 0.5, 1.25, 9, NaN, ...
        let map = [1.0, 1.5, 0.5, 1.25, 9.0, f64::NAN, 0.75, -3.0, 1.0];
        folded_variance(&path, 3, &map).unwrap();
        let image = decode(&path);
        assert_eq!((image.width, image.height, image.colour), (258, 258, png::ColorType::Rgb));
        let cell = |i: u32, j: u32| image.rgb(i * 86 + 40, j * 86 + 40);
        assert_eq!(cell(0, 0), WHITE);
        assert_eq!(cell(1, 0), [255, 0, 0]);
        assert_eq!(cell(2, 0), [0, 0, 255]);
        assert_eq!(cell(0, 1), [255, 128, 128]);
        assert_eq!(cell(1, 1), [255, 0, 0]);
        assert_eq!(cell(2, 1), MISSING);
        assert_eq!(cell(0, 2), [128, 128, 255]);
        assert_eq!(cell(1, 2), [0, 0, 255]);
        assert_eq!(image.rgb(257, 257), WHITE);
        assert_only(dir.path(), &["folded.png"]);
    }

    #[test]
    fn folded_variance_sizes() {
        let dir = tempfile::tempdir().unwrap();
        for (period, side) in [(1, 256), (16, 256), (100, 300), (300, 300)] {
            let path = dir.path().join(format!("v{period}.png"));
            folded_variance(&path, period, &vec![1.0; period * period]).unwrap();
            assert_eq!(decode(&path).width, side);
        }
        let path = dir.path().join("bad.png");
        assert!(folded_variance(&path, 0, &[]).is_err());
        assert!(folded_variance(&path, 4, &[1.0; 15]).is_err());
        assert!(!path.exists());
    }

    #[test]
    fn write_replaces_existing_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("p.png");
        fs::write(&path, b"old").unwrap();
        folded_variance(&path, 16, &[1.0; 256]).unwrap();
        assert_eq!(decode(&path).width, 256);
        assert_only(dir.path(), &["p.png"]);
    }
}
