//! Reading noise fields from files (`.npy`, raw `.f32`, `.exr`) and
//! saving them as `.npy`.

use std::fmt;
use std::fs::File;
use std::io::{self, BufWriter, Cursor, Write};
use std::path::{Path, PathBuf};

use crate::{Field, FieldError};

/// Why a file could not be read as a [`Field`].
#[derive(Debug)]
pub enum ReadError {
    /// The file could not be opened or read.
    Io {
        /// The file.
        path: PathBuf,
        /// What the operating system said.
        source: io::Error,
    },
    /// The extension is none of `.npy`, `.f32`, `.exr`.
    UnsupportedExtension {
        /// The file.
        path: PathBuf,
    },
    /// The `.npy` preamble or header dictionary cannot be parsed.
    NpyHeader {
        /// The file.
        path: PathBuf,
        /// What is wrong with it.
        reason: String,
    },
    /// The `.npy` element type is not `<f4` or `<f8`.
    NpyDtype {
        /// The file.
        path: PathBuf,
        /// The `descr` found in the header.
        descr: String,
    },
    /// The `.npy` array is not 2-D.
    NpyShape {
        /// The file.
        path: PathBuf,
        /// The shape found in the header.
        shape: Vec<usize>,
    },
    /// The `.npy` array is stored column-major (`fortran_order: True`).
    NpyFortranOrder {
        /// The file.
        path: PathBuf,
    },
    /// The sample data is shorter or longer than the shape promises.
    DataLength {
        /// The file.
        path: PathBuf,
        /// Bytes of sample data the shape needs.
        expected_bytes: usize,
        /// Bytes of sample data the file holds.
        found_bytes: usize,
    },
    /// A raw `.f32` file without a given size whose value count is not a
    /// perfect square (or not a whole number of `f32`s).
    RawNotSquare {
        /// The file.
        path: PathBuf,
        /// The file's length in bytes.
        bytes: usize,
    },
    /// The size asked for differs from the size stored in the file.
    SizeMismatch {
        /// The file.
        path: PathBuf,
        /// `(width, height)` asked for.
        given: (usize, usize),
        /// `(width, height)` in the file.
        found: (usize, usize),
    },
    /// The `exr` crate could not decode the file, or it has no channel.
    Exr {
        /// The file.
        path: PathBuf,
        /// The decoder's message.
        message: String,
    },
    /// The values were read but do not make a valid [`Field`].
    Field(FieldError),
}

impl fmt::Display for ReadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ReadError::Io { path, source } => write!(f, "cannot read {}: {source}", path.display()),
            ReadError::UnsupportedExtension { path } => {
                write!(f, "{}: unsupported file type (expected .npy, .f32 or .exr)", path.display())
            }
            ReadError::NpyHeader { path, reason } => {
                write!(f, "{}: malformed .npy header: {reason}", path.display())
            }
            ReadError::NpyDtype { path, descr } => {
                write!(f, "{}: unsupported .npy dtype '{descr}' (only '<f4' and '<f8' are supported)", path.display())
            }
            ReadError::NpyShape { path, shape } => {
                write!(f, "{}: .npy array has shape {shape:?}, expected a 2-D array", path.display())
            }
            ReadError::NpyFortranOrder { path } => {
                write!(f, "{}: .npy array is in Fortran (column-major) order; save it in C order", path.display())
            }
            ReadError::DataLength { path, expected_bytes, found_bytes } => {
                write!(f, "{}: expected {expected_bytes} bytes of sample data, found {found_bytes}", path.display())
            }
            ReadError::RawNotSquare { path, bytes } => write!(
                f,
                "{}: {bytes} bytes is not a square number of f32 values; give the size explicitly",
                path.display()
            ),
            ReadError::SizeMismatch { path, given, found } => write!(
                f,
                "{}: file holds a {}×{} field but {}×{} was asked for",
                path.display(),
                found.0,
                found.1,
                given.0,
                given.1
            ),
            ReadError::Exr { path, message } => write!(f, "{}: cannot read EXR: {message}", path.display()),
            ReadError::Field(err) => write!(f, "invalid field: {err}"),
        }
    }
}

impl std::error::Error for ReadError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            ReadError::Io { source, .. } => Some(source),
            ReadError::Field(err) => Some(err),
            _ => None,
        }
    }
}

impl From<FieldError> for ReadError {
    fn from(err: FieldError) -> Self {
        ReadError::Field(err)
    }
}

/// Reads a field from `.npy`, raw little-endian `.f32` or `.exr`, chosen by
/// the extension (case-insensitive). `size` is `(width, height)`: required
/// for a non-square `.f32`, checked against the file for the other formats.
///
/// Fails with a [`ReadError`] naming the file when it cannot be read, is
/// malformed, or holds values a [`Field`] rejects.
pub fn read_field(path: &Path, size: Option<(usize, usize)>) -> Result<Field, ReadError> {
    let extension = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    let format = match extension.as_deref() {
        Some("npy") => Format::Npy,
        Some("f32") => Format::RawF32,
        Some("exr") => Format::Exr,
        _ => return Err(ReadError::UnsupportedExtension { path: path.to_path_buf() }),
    };
    let bytes = std::fs::read(path).map_err(|source| ReadError::Io { path: path.to_path_buf(), source })?;
    let decoded = match format {
        Format::Npy => decode_npy(path, &bytes)?,
        Format::RawF32 => decode_raw(path, &bytes, size)?,
        Format::Exr => decode_exr(path, &bytes)?,
    };
    let found = (decoded.width, decoded.height);
    if let Some(given) = size.filter(|&given| given != found) {
        return Err(ReadError::SizeMismatch { path: path.to_path_buf(), given, found });
    }
    Ok(Field::new(decoded.width, decoded.height, decoded.values)?)
}

/// The file formats [`read_field`] understands.
enum Format {
    Npy,
    RawF32,
    Exr,
}

/// Samples decoded from a file, before they are checked as a [`Field`].
struct Decoded {
    width: usize,
    height: usize,
    values: Vec<f64>,
}

/// A raw file has no header: its size is given, or it is square.
fn decode_raw(path: &Path, bytes: &[u8], size: Option<(usize, usize)>) -> Result<Decoded, ReadError> {
    let (width, height) = match size {
        Some((width, height)) => {
            let expected_bytes = width.saturating_mul(height).saturating_mul(4);
            if expected_bytes != bytes.len() {
                return Err(ReadError::DataLength {
                    path: path.to_path_buf(),
                    expected_bytes,
                    found_bytes: bytes.len(),
                });
            }
            (width, height)
        }
        None => {
            let count = bytes.len() / 4;
            let side = count.isqrt();
            if !bytes.len().is_multiple_of(4) || side * side != count {
                return Err(ReadError::RawNotSquare { path: path.to_path_buf(), bytes: bytes.len() });
            }
            (side, side)
        }
    };
    Ok(Decoded { width, height, values: f32_values(bytes) })
}

/// Little-endian `f32`s.
fn f32_values(bytes: &[u8]) -> Vec<f64> {
    bytes.chunks_exact(4).map(|c| f64::from(f32::from_le_bytes([c[0], c[1], c[2], c[3]]))).collect()
}

/// Little-endian `f64`s.
fn f64_values(bytes: &[u8]) -> Vec<f64> {
    bytes.chunks_exact(8).map(|c| f64::from_le_bytes([c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]])).collect()
}

// ---------------------------------------------------------------- npy

const NPY_MAGIC: &[u8] = b"\x93NUMPY";

/// Splits a `.npy` file into its header text and sample bytes, and checks
/// the header describes a C-ordered 2-D `<f4`/`<f8` array of that length.
fn decode_npy(path: &Path, bytes: &[u8]) -> Result<Decoded, ReadError> {
    let header_err = |reason: &str| ReadError::NpyHeader { path: path.to_path_buf(), reason: reason.to_owned() };
    let (header, data) = split_npy(bytes).map_err(header_err)?;
    let header = parse_npy_header(&header).map_err(|reason| header_err(&reason))?;

    let item_size = match header.descr.as_str() {
        "<f4" => 4,
        "<f8" => 8,
        _ => return Err(ReadError::NpyDtype { path: path.to_path_buf(), descr: header.descr }),
    };
    let &[height, width] = header.shape.as_slice() else {
        return Err(ReadError::NpyShape { path: path.to_path_buf(), shape: header.shape });
    };
    if header.fortran_order {
        return Err(ReadError::NpyFortranOrder { path: path.to_path_buf() });
    }
    let expected_bytes = width
        .checked_mul(height)
        .and_then(|n| n.checked_mul(item_size))
        .ok_or_else(|| header_err("shape overflows the address space"))?;
    if data.len() != expected_bytes {
        return Err(ReadError::DataLength { path: path.to_path_buf(), expected_bytes, found_bytes: data.len() });
    }
    let values = if item_size == 4 { f32_values(data) } else { f64_values(data) };
    Ok(Decoded { width, height, values })
}

/// Magic, version, header length, header; returns the header as text and
/// the bytes after it.
fn split_npy(bytes: &[u8]) -> Result<(String, &[u8]), &'static str> {
    if !bytes.starts_with(NPY_MAGIC) {
        return Err("missing \\x93NUMPY magic");
    }
    let (major, rest) = match bytes.get(6..8) {
        Some(&[major, _minor]) => (major, &bytes[8..]),
        _ => return Err("file ends inside the preamble"),
    };
    // Version 1 has a u16 header length, versions 2 and 3 a u32.
    let (len, rest) = match major {
        1 => rest.split_first_chunk::<2>().map(|(l, r)| (usize::from(u16::from_le_bytes(*l)), r)),
        2 | 3 => rest.split_first_chunk::<4>().map(|(l, r)| (u32::from_le_bytes(*l) as usize, r)),
        _ => return Err("unsupported format version (expected 1, 2 or 3)"),
    }
    .ok_or("file ends inside the preamble")?;
    if rest.len() < len {
        return Err("file ends inside the header");
    }
    let (header, data) = rest.split_at(len);
    // Versions 1 and 2 are latin-1 (every byte is a char); version 3 is UTF-8.
    let text = if major == 3 {
        String::from_utf8(header.to_vec()).map_err(|_| "header is not valid UTF-8")?
    } else {
        header.iter().map(|&b| char::from(b)).collect()
    };
    Ok((text, data))
}

/// The three keys every `.npy` header carries.
#[derive(Debug, PartialEq)]
struct NpyHeader {
    descr: String,
    fortran_order: bool,
    shape: Vec<usize>,
}

/// The subset of Python literals that `.npy` headers use.
#[derive(Debug, PartialEq)]
enum PyValue {
    Str(String),
    Bool(bool),
    Int(usize),
    Tuple(Vec<PyValue>),
}

fn parse_npy_header(text: &str) -> Result<NpyHeader, String> {
    let mut parser = PyParser { chars: text.chars().peekable() };
    let entries = parser.dict()?;
    parser.skip_space();
    if parser.chars.peek().is_some() {
        return Err("unexpected text after the header dictionary".into());
    }
    let mut descr = None;
    let mut fortran_order = None;
    let mut shape = None;
    for (key, value) in entries {
        match (key.as_str(), value) {
            ("descr", PyValue::Str(s)) => descr = Some(s),
            ("fortran_order", PyValue::Bool(b)) => fortran_order = Some(b),
            ("shape", PyValue::Tuple(items)) => shape = Some(shape_dims(items)?),
            ("descr" | "fortran_order" | "shape", _) => return Err(format!("'{key}' has the wrong type")),
            // Unknown keys are allowed by the format; ignore them.
            _ => {}
        }
    }
    Ok(NpyHeader {
        descr: descr.ok_or("no 'descr' key")?,
        fortran_order: fortran_order.ok_or("no 'fortran_order' key")?,
        shape: shape.ok_or("no 'shape' key")?,
    })
}

fn shape_dims(items: Vec<PyValue>) -> Result<Vec<usize>, String> {
    items
        .into_iter()
        .map(|item| match item {
            PyValue::Int(n) => Ok(n),
            other => Err(format!("shape entry {other:?} is not an integer")),
        })
        .collect()
}

/// A small recursive-descent parser: tolerant of whitespace, trailing
/// commas and either quote style, since writers other than NumPy differ.
struct PyParser<'a> {
    chars: std::iter::Peekable<std::str::Chars<'a>>,
}

impl PyParser<'_> {
    fn skip_space(&mut self) {
        while self.chars.next_if(|c| c.is_whitespace()).is_some() {}
    }

    fn expect(&mut self, want: char) -> Result<(), String> {
        self.skip_space();
        match self.chars.next() {
            Some(c) if c == want => Ok(()),
            Some(c) => Err(format!("expected '{want}', found '{c}'")),
            None => Err(format!("expected '{want}', found end of header")),
        }
    }

    /// True (and consumed) if the next non-space char is `c`.
    fn eat(&mut self, c: char) -> bool {
        self.skip_space();
        self.chars.next_if_eq(&c).is_some()
    }

    fn dict(&mut self) -> Result<Vec<(String, PyValue)>, String> {
        self.expect('{')?;
        let mut entries = Vec::new();
        while !self.eat('}') {
            let key = match self.value()? {
                PyValue::Str(key) => key,
                other => return Err(format!("dictionary key {other:?} is not a string")),
            };
            self.expect(':')?;
            entries.push((key, self.value()?));
            if !self.eat(',') {
                self.expect('}')?;
                break;
            }
        }
        Ok(entries)
    }

    fn tuple(&mut self) -> Result<Vec<PyValue>, String> {
        let mut items = Vec::new();
        while !self.eat(')') {
            items.push(self.value()?);
            if !self.eat(',') {
                self.expect(')')?;
                break;
            }
        }
        Ok(items)
    }

    fn value(&mut self) -> Result<PyValue, String> {
        self.skip_space();
        match self.chars.peek().copied() {
            Some(q @ ('\'' | '"')) => {
                self.chars.next();
                self.string(q).map(PyValue::Str)
            }
            Some('(') => {
                self.chars.next();
                self.tuple().map(PyValue::Tuple)
            }
            Some(c) if c.is_ascii_digit() => self.int().map(PyValue::Int),
            Some(c) if c.is_alphabetic() => match self.word().as_str() {
                "True" => Ok(PyValue::Bool(true)),
                "False" => Ok(PyValue::Bool(false)),
                word => Err(format!("unexpected word '{word}'")),
            },
            Some(c) => Err(format!("unexpected '{c}'")),
            None => Err("header ends early".into()),
        }
    }

    /// The rest of a string literal whose opening quote `q` was consumed.
    fn string(&mut self, q: char) -> Result<String, String> {
        let mut s = String::new();
        loop {
            match self.chars.next() {
                Some(c) if c == q => return Ok(s),
                Some('\\') => s.extend(self.chars.next()),
                Some(c) => s.push(c),
                None => return Err("unterminated string".into()),
            }
        }
    }

    fn int(&mut self) -> Result<usize, String> {
        let mut digits = String::new();
        while let Some(d) = self.chars.next_if(char::is_ascii_digit) {
            digits.push(d);
        }
        // Python 2 era NumPy wrote longs as `512L`.
        self.chars.next_if(|&c| c == 'L' || c == 'l');
        digits.parse().map_err(|_| format!("integer {digits} is too large"))
    }

    fn word(&mut self) -> String {
        let mut word = String::new();
        while let Some(c) = self.chars.next_if(|c| c.is_alphanumeric() || *c == '_') {
            word.push(c);
        }
        word
    }
}

/// Saves `field` as a NumPy v1.0 `<f8` array of shape `(height, width)`.
pub fn write_npy(path: &Path, field: &Field) -> io::Result<()> {
    let header = npy_header(field.height(), field.width());
    let mut out = BufWriter::new(File::create(path)?);
    out.write_all(NPY_MAGIC)?;
    out.write_all(&[1, 0])?;
    // The header is well under 64 KiB: three short keys and two integers.
    out.write_all(&(header.len() as u16).to_le_bytes())?;
    out.write_all(header.as_bytes())?;
    for v in field.values() {
        out.write_all(&v.to_le_bytes())?;
    }
    out.into_inner().map_err(io::IntoInnerError::into_error)?.sync_all()
}

/// The header dictionary, space-padded so the data starts on a 64-byte
/// boundary (what NumPy does, so the file can be memory-mapped aligned).
fn npy_header(rows: usize, cols: usize) -> String {
    let mut header = format!("{{'descr': '<f8', 'fortran_order': False, 'shape': ({rows}, {cols}), }}");
    // Preamble: 6 magic + 2 version + 2 length bytes; the header ends in '\n'.
    let unpadded = 10 + header.len() + 1;
    header.extend(std::iter::repeat_n(' ', unpadded.next_multiple_of(64) - unpadded));
    header.push('\n');
    header
}

// ---------------------------------------------------------------- exr

/// First valid layer, channel "Y", else "R", else the first one.
fn decode_exr(path: &Path, bytes: &[u8]) -> Result<Decoded, ReadError> {
    use exr::prelude::*;

    let exr_err = |message: String| ReadError::Exr { path: path.to_path_buf(), message };
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .first_valid_layer()
        .all_attributes()
        .from_buffered(Cursor::new(bytes))
        .map_err(|e| exr_err(e.to_string()))?;
    let layer = image.layer_data;
    let channels = &layer.channel_data.list;
    let channel = ["Y", "R"]
        .iter()
        .find_map(|name| channels.iter().find(|c| c.name.eq(name)))
        .or(channels.first())
        .ok_or_else(|| exr_err("the layer has no channels".into()))?;
    Ok(Decoded {
        width: layer.size.width(),
        height: layer.size.height(),
        values: channel.sample_data.values_as_f32().map(f64::from).collect(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::fs;

    /// A `.npy` file from a header dictionary and raw sample bytes.
    fn npy_bytes(version: u8, dict: &str, data: &[u8]) -> Vec<u8> {
        let mut bytes = NPY_MAGIC.to_vec();
        bytes.extend([version, 0]);
        let header = format!("{dict}\n");
        if version == 1 {
            bytes.extend((header.len() as u16).to_le_bytes());
        } else {
            bytes.extend((header.len() as u32).to_le_bytes());
        }
        bytes.extend(header.as_bytes());
        bytes.extend(data);
        bytes
    }

    fn f4_dict(shape: &str) -> String {
        format!("{{'descr': '<f4', 'fortran_order': False, 'shape': {shape}, }}")
    }

    fn f32_bytes(values: impl IntoIterator<Item = f32>) -> Vec<u8> {
        values.into_iter().flat_map(f32::to_le_bytes).collect()
    }

    /// Writes `bytes` to `name` in a fresh directory and reads it back.
    fn read_bytes(name: &str, bytes: &[u8], size: Option<(usize, usize)>) -> Result<Field, ReadError> {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join(name);
        fs::write(&path, bytes).unwrap();
        read_field(&path, size)
    }

    #[test]
    fn npy_round_trip() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("field.npy");
        let field = Field::from_fn(17, 19, |i, j| (i as f64).sin() * 1e-3 + j as f64 / 7.0).unwrap();
        write_npy(&path, &field).unwrap();

        let bytes = fs::read(&path).unwrap();
        let header_len = usize::from(u16::from_le_bytes([bytes[8], bytes[9]]));
        assert_eq!((10 + header_len) % 64, 0, "data must start 64-byte aligned");
        assert_eq!(bytes[9 + header_len], b'\n');
        assert_eq!(read_field(&path, None).unwrap(), field);
        assert_eq!(read_field(&path, Some((17, 19))).unwrap(), field);
    }

    #[test]
    fn npy_f4_hand_built() {
        let values = (0..20).flat_map(|j| (0..16).map(move |i| i as f32 + 100.0 * j as f32));
        let bytes = npy_bytes(1, &f4_dict("(20, 16)"), &f32_bytes(values));
        let field = read_bytes("a.npy", &bytes, None).unwrap();
        assert_eq!((field.width(), field.height()), (16, 20));
        assert_eq!(field.at(3, 0), 3.0);
        assert_eq!(field.at(15, 19), 1915.0);
        assert_eq!(field.row(2)[5], 205.0);
    }

    #[test]
    fn npy_header_is_parsed_tolerantly() {
        let dict = "{ \"shape\":(16 ,16L),\n\"fortran_order\" : False , \"descr\":\"<f4\" }";
        for version in [1, 2, 3] {
            let bytes = npy_bytes(version, dict, &f32_bytes(vec![0.5; 256]));
            let field = read_bytes("B.NPY", &bytes, None).unwrap();
            assert_eq!((field.width(), field.height()), (16, 16));
        }
    }

    #[test]
    fn raw_f32_square_and_explicit_size() {
        let field = read_bytes("sq.f32", &f32_bytes((0..256).map(|v| v as f32)), None).unwrap();
        assert_eq!((field.width(), field.height()), (16, 16));
        assert_eq!(field.at(1, 2), 33.0);

        let bytes = f32_bytes((0..320).map(|v| v as f32));
        let field = read_bytes("rect.F32", &bytes, Some((16, 20))).unwrap();
        assert_eq!((field.width(), field.height()), (16, 20));
        assert_eq!(field.at(15, 19), 319.0);
    }

    #[test]
    fn npy_errors() {
        let data = f32_bytes(vec![0.0; 256]);
        let mut bad_magic = npy_bytes(1, &f4_dict("(16, 16)"), &data);
        bad_magic[1] = b'X';
        assert!(matches!(read_bytes("m.npy", &bad_magic, None), Err(ReadError::NpyHeader { .. })));

        let truncated = npy_bytes(1, &f4_dict("(16, 16)"), &data[..1000]);
        assert!(matches!(
            read_bytes("t.npy", &truncated, None),
            Err(ReadError::DataLength { expected_bytes: 1024, found_bytes: 1000, .. })
        ));

        let int_dict = "{'descr': '<i4', 'fortran_order': False, 'shape': (16, 16), }";
        match read_bytes("i.npy", &npy_bytes(1, int_dict, &data), None) {
            Err(err @ ReadError::NpyDtype { .. }) => assert!(err.to_string().contains("<i4"), "{err}"),
            other => panic!("{other:?}"),
        }

        match read_bytes("s.npy", &npy_bytes(1, &f4_dict("(1, 16, 16)"), &data), None) {
            Err(ReadError::NpyShape { shape, .. }) => assert_eq!(shape, [1, 16, 16]),
            other => panic!("{other:?}"),
        }

        let fortran = "{'descr': '<f4', 'fortran_order': True, 'shape': (16, 16), }";
        assert!(matches!(
            read_bytes("f.npy", &npy_bytes(1, fortran, &data), None),
            Err(ReadError::NpyFortranOrder { .. })
        ));

        let broken = npy_bytes(1, "{'descr': '<f4', 'shape': (16, 16", &data);
        assert!(matches!(read_bytes("h.npy", &broken, None), Err(ReadError::NpyHeader { .. })));

        let ok = npy_bytes(1, &f4_dict("(16, 16)"), &data);
        assert!(matches!(
            read_bytes("z.npy", &ok, Some((16, 32))),
            Err(ReadError::SizeMismatch { given: (16, 32), found: (16, 16), .. })
        ));
    }

    #[test]
    fn raw_and_file_errors() {
        let bytes = f32_bytes(vec![0.0; 300]);
        assert!(matches!(read_bytes("r.f32", &bytes, None), Err(ReadError::RawNotSquare { bytes: 1200, .. })));
        assert!(matches!(read_bytes("r.f32", &bytes, Some((16, 16))), Err(ReadError::DataLength { .. })));

        let dir = tempfile::tempdir().unwrap();
        let missing = dir.path().join("missing.npy");
        let err = read_field(&missing, None).unwrap_err();
        assert!(matches!(err, ReadError::Io { .. }));
        assert!(err.to_string().contains("missing.npy"), "{err}");

        assert!(matches!(read_bytes("x.png", &bytes, None), Err(ReadError::UnsupportedExtension { .. })));
        assert!(matches!(read_bytes("noext", &bytes, None), Err(ReadError::UnsupportedExtension { .. })));
    }

    #[test]
    fn field_errors() {
        let mut values = vec![0.0f32; 256];
        values[17] = f32::NAN;
        let nan = npy_bytes(1, &f4_dict("(16, 16)"), &f32_bytes(values));
        assert!(matches!(read_bytes("n.npy", &nan, None), Err(ReadError::Field(FieldError::NonFinite { index: 17 }))));
        assert!(matches!(
            read_bytes("small.f32", &f32_bytes(vec![0.0; 64]), None),
            Err(ReadError::Field(FieldError::TooSmall { .. }))
        ));
    }

    /// Writes an uncompressed-free (RLE) EXR with the given `f32` channels.
    fn write_exr(path: &Path, size: (usize, usize), channels: Vec<(&str, Vec<f32>)>) {
        use exr::prelude::*;
        let list = channels
            .into_iter()
            .map(|(name, values)| AnyChannel::new(name, FlatSamples::F32(values)))
            .collect::<Vec<_>>();
        let layer = Layer::new(
            size,
            LayerAttributes::named("noise"),
            Encoding::FAST_LOSSLESS,
            AnyChannels::sort(SmallVec::from_vec(list)),
        );
        Image::from_layer(layer).write().to_file(path).unwrap();
    }

    #[test]
    fn exr_single_y_channel() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("y.exr");
        let values: Vec<f32> = (0..32 * 16).map(|k| k as f32 * 0.25 - 7.0).collect();
        write_exr(&path, (32, 16), vec![("Y", values.clone())]);

        let field = read_field(&path, None).unwrap();
        assert_eq!((field.width(), field.height()), (32, 16));
        assert_eq!(field.at(5, 3), f64::from(values[3 * 32 + 5]));
        assert!(matches!(read_field(&path, Some((16, 32))), Err(ReadError::SizeMismatch { .. })));
    }

    #[test]
    fn exr_prefers_y_over_other_channels() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("ry.EXR");
        write_exr(&path, (16, 16), vec![("R", vec![1.0; 256]), ("A", vec![3.0; 256]), ("Y", vec![2.0; 256])]);
        assert!(read_field(&path, None).unwrap().values().iter().all(|&v| v == 2.0));
    }

    #[test]
    fn corrupt_exr_is_an_error() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("good.exr");
        write_exr(&path, (32, 16), vec![("Y", vec![0.5; 512])]);
        let good = fs::read(&path).unwrap();

        let mut corrupt = vec![good[..good.len() / 2].to_vec(), b"not an exr file at all".to_vec()];
        let mut scrambled = good.clone();
        for b in scrambled.iter_mut().skip(8).step_by(3) {
            *b ^= 0x5a;
        }
        corrupt.push(scrambled);
        for bytes in corrupt {
            assert!(matches!(read_bytes("bad.exr", &bytes, None), Err(ReadError::Exr { .. })));
        }
    }
}
