//! Output files: formats, and atomic creation (a file appears only complete).

use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// A rendered window of values, row-major (x fastest).
pub struct Image<'a> {
    pub width: usize,
    pub height: usize,
    pub values: &'a [f32],
    /// Value range mapped to black..white in PNG output.
    pub range: (f64, f64),
}

/// Output formats, chosen by file extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Grey PNG, 8 or 16 bits, mapped from the kind's range (clamped).
    Png,
    /// NumPy `.npy`, little-endian float32, shape (height, width): exact values.
    Npy,
    /// Raw little-endian float32, row-major: exact values.
    F32,
    /// OpenEXR, one 32-bit float channel "Y": exact values, for compositors.
    Exr,
}

impl Format {
    pub fn from_path(path: &Path) -> Result<Format, String> {
        let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
        match ext.as_deref() {
            Some("png") => Ok(Format::Png),
            Some("npy") => Ok(Format::Npy),
            Some("f32") => Ok(Format::F32),
            Some("exr") => Ok(Format::Exr),
            _ => Err(format!("{}: unknown output format (use .png, .npy, .f32 or .exr)", path.display())),
        }
    }

    pub fn write(self, w: &mut dyn Write, image: &Image, bits: u8) -> std::io::Result<()> {
        match self {
            Format::Png => write_png(w, image, bits),
            Format::Npy => {
                w.write_all(&npy_header(&[image.height, image.width]))?;
                write_f32_le(w, image.values)
            }
            Format::F32 => write_f32_le(w, image.values),
            Format::Exr => write_exr(w, image),
        }
    }
}

/// One float channel "Y", losslessly compressed. The exr crate writes to a
/// seekable sink, so the file is assembled in memory first.
fn write_exr(w: &mut dyn Write, image: &Image) -> std::io::Result<()> {
    use exr::prelude::*;
    let channel = AnyChannel::new("Y", FlatSamples::F32(image.values.to_vec()));
    let layer = Layer::new(
        (image.width, image.height),
        LayerAttributes::named("noise"),
        Encoding::FAST_LOSSLESS,
        AnyChannels::sort(SmallVec::from_vec(vec![channel])),
    );
    let mut bytes = std::io::Cursor::new(Vec::new());
    exr::prelude::Image::from_layer(layer).write().to_buffered(&mut bytes).map_err(std::io::Error::other)?;
    w.write_all(bytes.get_ref())
}

fn write_f32_le(w: &mut dyn Write, values: &[f32]) -> std::io::Result<()> {
    for chunk in values.chunks(4096) {
        let bytes: Vec<u8> = chunk.iter().flat_map(|v| v.to_le_bytes()).collect();
        w.write_all(&bytes)?;
    }
    Ok(())
}

/// NPY format 1.0 header for a little-endian float32 C-order array.
pub fn npy_header(shape: &[usize]) -> Vec<u8> {
    let dims: Vec<String> = shape.iter().map(|d| d.to_string()).collect();
    let shape = if dims.len() == 1 { format!("({},)", dims[0]) } else { format!("({})", dims.join(", ")) };
    let mut dict = format!("{{'descr': '<f4', 'fortran_order': False, 'shape': {shape}, }}");
    // Magic (6) + version (2) + length (2) + dict + '\n' must be a multiple of 64.
    while (10 + dict.len() + 1) % 64 != 0 {
        dict.push(' ');
    }
    dict.push('\n');
    let mut out = b"\x93NUMPY\x01\x00".to_vec();
    out.extend_from_slice(&(dict.len() as u16).to_le_bytes());
    out.extend_from_slice(dict.as_bytes());
    out
}

/// Map a value to [0, 1] over `range`, clamping; NaN maps to 0.
pub fn unit(v: f32, (lo, hi): (f64, f64)) -> f64 {
    let t = (v as f64 - lo) / (hi - lo);
    if t.is_nan() {
        0.0
    } else {
        t.clamp(0.0, 1.0)
    }
}

/// A grey PNG written band by band (rows, mapped from `range`), so only one
/// band is ever held.
pub fn write_png_bands(
    w: &mut dyn Write,
    (width, height): (usize, usize),
    bits: u8,
    range: (f64, f64),
    bands: impl Iterator<Item = Vec<f32>>,
) -> std::io::Result<()> {
    let mut enc = png::Encoder::new(w, width as u32, height as u32);
    enc.set_color(png::ColorType::Grayscale);
    enc.set_depth(if bits == 16 { png::BitDepth::Sixteen } else { png::BitDepth::Eight });
    let mut writer = enc.write_header().map_err(std::io::Error::other)?;
    let mut stream = writer.stream_writer().map_err(std::io::Error::other)?;
    for values in bands {
        let data: Vec<u8> = if bits == 16 {
            values.iter().flat_map(|&v| ((unit(v, range) * 65535.0).round() as u16).to_be_bytes()).collect()
        } else {
            values.iter().map(|&v| (unit(v, range) * 255.0).round() as u8).collect()
        };
        stream.write_all(&data)?;
    }
    stream.finish().map_err(std::io::Error::other)?;
    writer.finish().map_err(std::io::Error::other)
}

/// An animated PNG (APNG) of grey frames mapped from `range`, 25 frames
/// per second, looping forever.
pub fn write_apng<'a>(
    w: &mut dyn Write,
    width: usize,
    height: usize,
    frames: impl ExactSizeIterator<Item = &'a [f32]>,
    range: (f64, f64),
) -> std::io::Result<()> {
    let mut enc = png::Encoder::new(w, width as u32, height as u32);
    enc.set_color(png::ColorType::Grayscale);
    enc.set_depth(png::BitDepth::Eight);
    enc.set_animated(frames.len() as u32, 0).map_err(std::io::Error::other)?;
    enc.set_frame_delay(1, 25).map_err(std::io::Error::other)?;
    let mut writer = enc.write_header().map_err(std::io::Error::other)?;
    for frame in frames {
        let data: Vec<u8> = frame.iter().map(|&v| (unit(v, range) * 255.0).round() as u8).collect();
        writer.write_image_data(&data).map_err(std::io::Error::other)?;
    }
    writer.finish().map_err(std::io::Error::other)
}

/// An 8-bit RGB PNG of linear colours in [0, 1] (sRGB-encoded on the way
/// out, so ramps interpolate in linear light).
pub fn write_rgb_png(w: &mut dyn Write, width: usize, height: usize, rgb: &[[f32; 3]]) -> std::io::Result<()> {
    let mut enc = png::Encoder::new(w, width as u32, height as u32);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    let encode = |c: f32| {
        let c = if c.is_nan() { 0.0 } else { c.clamp(0.0, 1.0) };
        let s = if c <= 0.003_130_8 { 12.92 * c } else { 1.055 * c.powf(1.0 / 2.4) - 0.055 };
        (s * 255.0).round() as u8
    };
    let data: Vec<u8> = rgb.iter().flat_map(|p| p.map(encode)).collect();
    let mut writer = enc.write_header().map_err(std::io::Error::other)?;
    writer.write_image_data(&data).map_err(std::io::Error::other)?;
    writer.finish().map_err(std::io::Error::other)
}

fn write_png(w: &mut dyn Write, image: &Image, bits: u8) -> std::io::Result<()> {
    let mut enc = png::Encoder::new(w, image.width as u32, image.height as u32);
    enc.set_color(png::ColorType::Grayscale);
    let data: Vec<u8> = if bits == 16 {
        enc.set_depth(png::BitDepth::Sixteen);
        image.values.iter().flat_map(|&v| ((unit(v, image.range) * 65535.0).round() as u16).to_be_bytes()).collect()
    } else {
        enc.set_depth(png::BitDepth::Eight);
        image.values.iter().map(|&v| (unit(v, image.range) * 255.0).round() as u8).collect()
    };
    let mut writer = enc.write_header().map_err(std::io::Error::other)?;
    writer.write_image_data(&data).map_err(std::io::Error::other)?;
    writer.finish().map_err(std::io::Error::other)
}

/// An output being written: a temporary file beside the destination, renamed
/// onto it only when complete. Dropped unfinished, the temporary is removed.
pub struct Pending {
    temp: tempfile::NamedTempFile,
    dest: PathBuf,
    force: bool,
}

impl Pending {
    /// Check the destination and open the temporary file.
    pub fn create(dest: &Path, force: bool) -> Result<Pending, String> {
        if dest.exists() && !force {
            return Err(format!("{}: already exists (use --force to overwrite)", dest.display()));
        }
        let dir = match dest.parent() {
            Some(d) if !d.as_os_str().is_empty() => d,
            _ => Path::new("."),
        };
        let temp = tempfile::Builder::new()
            .prefix(".noiselab-")
            .suffix(".partial")
            .tempfile_in(dir)
            .map_err(|e| format!("{}: cannot write: {e}", dest.display()))?;
        Ok(Pending { temp, dest: dest.to_path_buf(), force })
    }

    /// Write the content, then move it into place atomically.
    pub fn finish(self, write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>) -> Result<(), String> {
        let name = self.dest.display().to_string();
        let err = |e: std::io::Error| format!("{name}: {e}");
        {
            let mut w = BufWriter::new(self.temp.as_file());
            write(&mut w).map_err(err)?;
            w.flush().map_err(err)?;
        }
        // Temporary files are created owner-only; the result should have the
        // permissions of an ordinary new file.
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            self.temp.as_file().set_permissions(std::fs::Permissions::from_mode(0o644)).map_err(err)?;
        }
        self.temp.as_file().sync_all().map_err(err)?;
        let persisted =
            if self.force { self.temp.persist(&self.dest) } else { self.temp.persist_noclobber(&self.dest) };
        persisted.map(|_| ()).map_err(|e| err(e.error))
    }
}
