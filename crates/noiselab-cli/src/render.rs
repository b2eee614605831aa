//! `noiselab render`: a 2D window of a noise, written atomically.

use crate::output::{Format, Image};
use crate::registry::{self, Field};
use crate::Method;
use crate::RenderArgs;
use noiselab::{Grid, Sparse};

/// Most pixels one in-memory render may have (1 GiB of f32 values).
const MAX_PIXELS: usize = 1 << 28;
/// Above this many pixels, PNG, .npy and .f32 renders stream in bands.
const STREAM_PIXELS: usize = 1 << 22;
/// Most pixels a streamed render may have (its memory does not grow with it).
const MAX_STREAM_PIXELS: usize = 1 << 32;
/// Bytes of f32 values per band: the bound on a streamed render's buffers.
const BAND_BYTES: usize = 8 << 20;

pub fn run(args: &RenderArgs) -> Result<(), String> {
    if let Some(recipe) = crate::recipes::find(&args.noise.kind) {
        return render_recipe(recipe, args);
    }
    if args.base.is_some() {
        return Err(format!("--base applies to recipes only, not {}", args.noise.kind));
    }
    let crate::Built { spec, field, dims, range, fractal } = args.noise.build(Some(1.0 / args.scale))?;
    let range = args.range.unwrap_or(range);
    if args.ramp.is_some()
        && (!args.output.extension().is_some_and(|e| e.eq_ignore_ascii_case("png")) || args.frames.is_some())
    {
        return Err("--ramp colours a still .png".into());
    }
    let format = Format::from_path(&args.output)?;
    let (width, height) = args.size;
    let limit = if matches!(format, Format::Png | Format::Npy | Format::F32)
        && spec.name != "sparse"
        && args.frames.is_none()
        && args.ramp.is_none()
    {
        MAX_STREAM_PIXELS
    } else {
        MAX_PIXELS
    };
    width
        .checked_mul(height)
        .filter(|&n| n <= limit)
        .ok_or_else(|| format!("--size {width}x{height} has more than {limit} pixels for this output"))?;
    let slice = args.slice.clone().map(|s| s.0).unwrap_or_default();
    if slice.len() > dims.saturating_sub(2) {
        return Err(format!(
            "--slice gives {} coordinate(s) but {}D noise has {} axis(es) beyond x and y",
            slice.len(),
            dims,
            dims.saturating_sub(2)
        ));
    }
    if let Some(depth) = args.depth {
        if args.frames.is_some() {
            return Err("--depth and --frames cannot be combined".into());
        }
        return volume(args, &field, dims, range, &slice, depth as usize, format);
    }
    if let Some(frames) = args.frames {
        return animate(args, field, dims, range, &slice, frames, format);
    }
    if args.r#loop {
        return Err("--loop needs --frames".into());
    }
    // Open the destination first, so a bad path fails before any work.
    let pending = crate::output::Pending::create(&args.output, args.force)?;

    let sparse = spec.name == "sparse";
    let streamable =
        matches!(format, Format::Png | Format::Npy | Format::F32) && dims >= 2 && !sparse && args.ramp.is_none();
    if streamable && width * height > STREAM_PIXELS {
        return stream(args, &field, dims, &slice, range, format, pending);
    }
    if args.method.is_some() && !sparse {
        return Err(format!("--method applies to sparse only, not {}", spec.name));
    }
    let step = 1.0 / args.scale;
    if fractal && args.method == Some(Method::Splat) {
        return Err("--method splat renders one sparse octave; fractal sums are evaluated point by point".into());
    }
    let values = if sparse && !fractal && dims >= 2 && args.method != Some(Method::Gather) {
        let noise = registry::sparse_noise(&args.noise.params(dims))?;
        splat(&noise, dims, args.origin, &slice, step, (width, height))?
    } else {
        window(&field, dims, args.origin, &slice, step, (width, height))?
    };
    if let (Some(ramp), Format::Png) = (args.ramp, format) {
        let rgb: Vec<[f32; 3]> = values.iter().map(|&v| ramp.at((v as f64 - range.0) / (range.1 - range.0))).collect();
        return pending.finish(|w| crate::output::write_rgb_png(w, width, height, &rgb));
    }
    let image = Image { width, height, values: &values, range };
    pending.finish(|w| format.write(w, &image, args.bits))
}

/// `LO,HI` with LO < HI, both finite.
pub fn parse_range(s: &str) -> Result<(f64, f64), String> {
    match parse_list(s)?.as_slice() {
        [lo, hi] if lo < hi => Ok((*lo, *hi)),
        _ => Err(format!("expected LO,HI with LO < HI, got '{s}'")),
    }
}

/// A colour ramp by name.
pub fn parse_ramp(s: &str) -> Result<noiselab::recipes::Ramp, String> {
    use noiselab::recipes::Ramp;
    match s.trim() {
        "grey" | "gray" => Ok(Ramp::GREY),
        "marble" => Ok(Ramp::MARBLE),
        "wood" => Ok(Ramp::WOOD),
        "sky" => Ok(Ramp::SKY),
        "flame" => Ok(Ramp::FLAME),
        _ => Err(format!("--ramp must be one of grey, marble, wood, sky, flame, got {s}")),
    }
}

/// A volume: `depth` slices along z, z spacing equal to the pixel spacing,
/// as one (z, y, x) `.npy` or numbered slice PNGs. Every file is checked
/// before any is written, and each appears atomically.
fn volume(
    args: &RenderArgs,
    field: &Field,
    dims: usize,
    range: (f64, f64),
    slice: &[f64],
    depth: usize,
    format: Format,
) -> Result<(), String> {
    if dims < 3 {
        return Err(format!("--depth renders volumes of 3D or 4D noise; this is {dims}D (use --dims 3)"));
    }
    let (width, height) = args.size;
    let total = width.checked_mul(height).and_then(|n| n.checked_mul(depth)).filter(|&n| n <= MAX_PIXELS);
    total.ok_or_else(|| format!("a {width}x{height}x{depth} volume has more than {MAX_PIXELS} voxels"))?;
    let step = 1.0 / args.scale;
    let mut origin = vec![args.origin.0, args.origin.1];
    origin.extend(slice.iter().copied());
    origin.resize(dims, 0.0);
    let mut steps = vec![step, step, step];
    steps.resize(dims, 0.0);
    let mut size = vec![width, height, depth];
    size.resize(dims, 1);
    let mut values = vec![0f32; width * height * depth];
    let targets: Vec<std::path::PathBuf> = match format {
        Format::Npy => vec![args.output.clone()],
        Format::Png => {
            let stem = args.output.file_stem().and_then(|s| s.to_str()).unwrap_or("slice");
            (0..depth).map(|k| args.output.with_file_name(format!("{stem}-{k:03}.png"))).collect()
        }
        _ => return Err("--depth writes a (z, y, x) .npy or numbered .png slices".into()),
    };
    let pending =
        targets.iter().map(|t| crate::output::Pending::create(t, args.force)).collect::<Result<Vec<_>, _>>()?;
    field.fill_grid(&origin, &steps, &size, &mut values).map_err(|e| e.to_string())?;
    if format == Format::Npy {
        let file = pending.into_iter().next().expect("one target");
        return file.finish(|w| {
            w.write_all(&crate::output::npy_header(&[depth, height, width]))?;
            let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
            w.write_all(&bytes)
        });
    }
    for (file, layer) in pending.into_iter().zip(values.chunks(width * height)) {
        let image = Image { width, height, values: layer, range };
        file.finish(|w| Format::Png.write(w, &image, args.bits))?;
    }
    Ok(())
}

/// A large window, rendered and written band by band: memory stays about
/// [`BAND_BYTES`] of values (plus their points, 3×, and one band of encoded
/// rows), whatever the image size. Measured: a 32768² 16-bit PNG peaks at
/// 39 MB resident (50 s on 2 cores), where the whole image would be 4 GB of
/// values. Bands equal the same rows of an in-memory render bit for bit. A
/// progress bar shows on a terminal.
fn stream(
    args: &RenderArgs,
    field: &Field,
    dims: usize,
    slice: &[f64],
    range: (f64, f64),
    format: Format,
    pending: crate::output::Pending,
) -> Result<(), String> {
    let (width, height) = args.size;
    let step = 1.0 / args.scale;
    let mut origin = vec![args.origin.0, args.origin.1];
    origin.extend(slice.iter().copied());
    origin.resize(dims, 0.0);
    let mut steps = vec![step, step];
    steps.resize(dims, 0.0);
    let mut size = vec![width, height];
    size.resize(dims, 1);
    let band_rows = (BAND_BYTES / (4 * width)).clamp(1, height);
    let bar = indicatif::ProgressBar::new(height as u64);
    let bands = (0..height).step_by(band_rows).map(|start| {
        let rows = start..(start + band_rows).min(height);
        let mut values = vec![0f32; rows.len() * width];
        field.fill_rows(&origin, &steps, &size, rows.clone(), &mut values);
        bar.inc(rows.len() as u64);
        values
    });
    let result = pending.finish(|w| match format {
        Format::Png => crate::output::write_png_bands(w, (width, height), args.bits, range, bands),
        _ => {
            if format == Format::Npy {
                w.write_all(&crate::output::npy_header(&[height, width]))?;
            }
            for values in bands {
                let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
                w.write_all(&bytes)?;
            }
            Ok(())
        }
    });
    bar.finish_and_clear();
    result
}

/// An animation along the noise's last axis (time): `frames` frames
/// `--time-step` apart, as an animated PNG (looping forever) or a
/// (frames, height, width) `.npy`. With `--loop` the noise is Perlin's
/// blend loop over frames × step, so the last frame leads seamlessly back
/// to the first.
fn animate(
    args: &RenderArgs,
    field: Field,
    dims: usize,
    range: (f64, f64),
    slice: &[f64],
    frames: u32,
    format: Format,
) -> Result<(), String> {
    if dims < 3 {
        return Err(format!("--frames animates the last axis of 3D or 4D noise; this is {dims}D (use --dims 3)"));
    }
    if !matches!(format, Format::Png | Format::Npy) {
        return Err("--frames writes an animated .png or a (frames, height, width) .npy".into());
    }
    let dt = args.time_step;
    if !(dt.is_finite() && dt > 0.0) {
        return Err(format!("--time-step must be positive, got {dt}"));
    }
    let field = if args.r#loop {
        let length = frames as f64 * dt;
        macro_rules! looped {
            ($($v:ident),*) => {
                match field {
                    $(Field::$v(n) => Field::$v(Box::new(noiselab::Looped::new(n, length).map_err(|e| e.to_string())?)),)*
                    other => other,
                }
            };
        }
        looped!(D3, D4)
    } else {
        field
    };
    let pending = crate::output::Pending::create(&args.output, args.force)?;
    let (width, height) = args.size;
    let mut slice = slice.to_vec();
    slice.resize(dims - 2, 0.0);
    let t0 = slice[dims - 3];
    let mut all = Vec::with_capacity(frames as usize * width * height);
    for k in 0..frames {
        slice[dims - 3] = t0 + k as f64 * dt;
        all.extend(window(&field, dims, args.origin, &slice, 1.0 / args.scale, (width, height))?);
    }
    let frame_len = width * height;
    pending.finish(|w| match format {
        Format::Npy => {
            w.write_all(&crate::output::npy_header(&[frames as usize, height, width]))?;
            let bytes: Vec<u8> = all.iter().flat_map(|v| v.to_le_bytes()).collect();
            w.write_all(&bytes)
        }
        _ => crate::output::write_apng(w, width, height, all.chunks(frame_len), range),
    })
}

/// A recipe over its base noise: the coloured picture (PNG) or the scalar
/// field (.npy, .f32). Time is `--slice`'s first value.
fn render_recipe(recipe: &crate::recipes::RecipeSpec, args: &RenderArgs) -> Result<(), String> {
    let format = Format::from_path(&args.output)?;
    let (width, height) = args.size;
    width
        .checked_mul(height)
        .filter(|&n| n <= MAX_PIXELS)
        .ok_or_else(|| format!("--size {width}x{height} has more than {MAX_PIXELS} pixels"))?;
    if args.method.is_some() {
        return Err("--method applies to sparse only".into());
    }
    let mut noise = args.noise.clone();
    noise.kind = args.base.clone().unwrap_or_else(|| "improved".into());
    if noise.dims.is_some_and(|d| d != 3) {
        return Err(format!("recipes read 3D noise; --dims {} does not apply", noise.dims.unwrap_or(3)));
    }
    noise.dims = Some(3);
    let crate::Built { field, .. } = noise.build(Some(1.0 / width.max(height) as f64))?;
    let registry::Field::D3(base) = field else { unreachable!("dims fixed to 3") };
    let t = args.slice.as_ref().and_then(|s| s.0.first().copied()).unwrap_or(0.0);
    let pending = crate::output::Pending::create(&args.output, args.force)?;
    let (values, rgb) = crate::recipes::render(recipe, &base, (width, height), t);
    match format {
        Format::Png => pending.finish(|w| crate::output::write_rgb_png(w, width, height, &rgb)),
        _ => {
            let image = Image { width, height, values: &values, range: (0.0, 1.0) };
            pending.finish(|w| format.write(w, &image, args.bits))
        }
    }
}

/// The same window as [`window`], rendered by splatting sparse convolution
/// impulses.
pub fn splat(
    noise: &Sparse,
    dims: usize,
    (x, y): (f64, f64),
    slice: &[f64],
    step: f64,
    (width, height): (usize, usize),
) -> Result<Vec<f32>, String> {
    fn go<const D: usize>(n: &Sparse, origin: &[f64], step: f64, (w, h): (usize, usize)) -> Result<Vec<f32>, String>
    where
        Sparse: noiselab::Noise<D>,
    {
        let mut o = [0.0; D];
        o.copy_from_slice(&origin[..D]);
        let mut s = [0.0; D];
        (s[0], s[1]) = (step, step);
        let mut size = [1; D];
        (size[0], size[1]) = (w, h);
        let mut out = vec![0f32; w * h];
        n.splat_grid(&Grid::new(o, s, size), &mut out).map_err(|e| e.to_string())?;
        Ok(out)
    }
    let mut origin = vec![x, y];
    origin.extend(slice.iter().copied());
    origin.resize(dims.max(2), 0.0);
    match dims {
        2 => go::<2>(noise, &origin, step, (width, height)),
        3 => go::<3>(noise, &origin, step, (width, height)),
        4 => go::<4>(noise, &origin, step, (width, height)),
        d => Err(format!("splatting renders 2D to 4D sparse noise, not {d}D")),
    }
}

/// Pixel (row j, column i) = noise(X + i·step, Y + j·step, slice…): the
/// window every picture is made of. A 1D noise varies along x only.
pub fn window(
    field: &Field,
    dims: usize,
    (x, y): (f64, f64),
    slice: &[f64],
    step: f64,
    (width, height): (usize, usize),
) -> Result<Vec<f32>, String> {
    let mut values = vec![0f32; width * height];
    if dims == 1 {
        let mut row = vec![0f32; width];
        field.fill_grid(&[x], &[step], &[width], &mut row).map_err(|e| e.to_string())?;
        for r in values.chunks_mut(width) {
            r.copy_from_slice(&row);
        }
    } else {
        let mut origin = vec![x, y];
        origin.extend(slice.iter().copied());
        origin.resize(dims, 0.0);
        let mut steps = vec![step, step];
        steps.resize(dims, 0.0);
        let mut size = vec![width, height];
        size.resize(dims, 1);
        field.fill_grid(&origin, &steps, &size, &mut values).map_err(|e| e.to_string())?;
    }
    Ok(values)
}

/// `WIDTHxHEIGHT`, both at least 1.
pub fn parse_size(s: &str) -> Result<(usize, usize), String> {
    let bad = || format!("'{s}' is not a size like 512x512");
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
    let w: usize = w.trim().parse().map_err(|_| bad())?;
    let h: usize = h.trim().parse().map_err(|_| bad())?;
    if w == 0 || h == 0 {
        return Err(format!("size must be at least 1x1, got {s}"));
    }
    Ok((w, h))
}

fn finite(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err(format!("'{}' is not a finite number", s.trim())),
    }
}

/// PNG bits per sample: 8 or 16.
pub fn parse_bits(s: &str) -> Result<u8, String> {
    match s.trim() {
        "8" => Ok(8),
        "16" => Ok(16),
        _ => Err(format!("bits must be 8 or 16, got {s}")),
    }
}

/// Pixels per cell: finite and positive.
pub fn parse_scale(s: &str) -> Result<f64, String> {
    let v = finite(s)?;
    if v > 0.0 {
        Ok(v)
    } else {
        Err(format!("expected a positive number of pixels, got {s}"))
    }
}

/// `X,Y`.
pub fn parse_pair(s: &str) -> Result<(f64, f64), String> {
    match parse_list(s)?.as_slice() {
        [x, y] => Ok((*x, *y)),
        _ => Err(format!("'{s}' is not a pair like 0,0")),
    }
}

/// Tiling periods in cells (a newtype: clap treats a bare array as values).
#[derive(Clone, Copy, Debug)]
pub struct Tile(pub [u32; 4]);

/// `X[,Y[,Z[,W]]]`: whole numbers of cells, at least one positive.
pub fn parse_tile(s: &str) -> Result<Tile, String> {
    let parts: Vec<&str> = s.split(',').collect();
    if parts.len() > 4 {
        return Err(format!("at most 4 periods, got '{s}'"));
    }
    let mut cells = [0u32; 4];
    for (c, part) in cells.iter_mut().zip(&parts) {
        *c = part.trim().parse().map_err(|_| format!("'{}' is not a whole number of cells", part.trim()))?;
    }
    if cells.iter().all(|&c| c == 0) {
        return Err(format!("at least one period must be positive, got '{s}'"));
    }
    Ok(Tile(cells))
}

/// `--octaves`: a count or `auto`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Octaves {
    /// This many octaves.
    Count(u32),
    /// From the pixel footprint.
    Auto,
}

/// `N` (1..=30) or `auto`.
pub fn parse_octaves(s: &str) -> Result<Octaves, String> {
    if s.trim() == "auto" {
        return Ok(Octaves::Auto);
    }
    match s.trim().parse::<u32>() {
        Ok(n) if (1..=noiselab::compose::MAX_OCTAVES).contains(&n) => Ok(Octaves::Count(n)),
        _ => Err(format!("--octaves must be 1..={} or auto, got {s}", noiselab::compose::MAX_OCTAVES)),
    }
}

/// A fractal mode by name.
pub fn parse_fractal(s: &str) -> Result<noiselab::FractalMode, String> {
    noiselab::FractalMode::ALL.into_iter().find(|m| m.name() == s.trim()).ok_or_else(|| {
        let names: Vec<&str> = noiselab::FractalMode::ALL.iter().map(|m| m.name()).collect();
        format!("--fractal must be one of {}, got {s}", names.join(", "))
    })
}

/// A positive whole number.
pub fn parse_count(s: &str) -> Result<usize, String> {
    match s.trim().parse::<usize>() {
        Ok(n) if n > 0 => Ok(n),
        _ => Err(format!("expected a positive whole number, got '{s}'")),
    }
}

/// `COLUMN,ROW`: two whole numbers.
pub fn parse_offset(s: &str) -> Result<(usize, usize), String> {
    let bad = || format!("'{s}' is not a pixel like 0,0");
    let (a, b) = s.split_once(',').ok_or_else(bad)?;
    Ok((a.trim().parse().map_err(|_| bad())?, b.trim().parse().map_err(|_| bad())?))
}

/// Slice coordinates beyond x and y (a newtype: clap treats a bare `Vec` as
/// a multi-valued option).
#[derive(Clone, Debug)]
pub struct Slice(pub Vec<f64>);

/// `Z[,W,…]`.
pub fn parse_slice(s: &str) -> Result<Slice, String> {
    parse_list(s).map(Slice)
}

/// Comma-separated finite numbers.
pub fn parse_list(s: &str) -> Result<Vec<f64>, String> {
    s.split(',').map(finite).collect()
}
