//! The input of every metric: a rectangular grid of samples.

use core::fmt;

/// A 2D field of noise samples, row-major: `value(i, j)` is column `i`
/// (x, fastest) of row `j` (y). Values are kept in `f64` so sums over a
/// megapixel stay accurate; non-finite values are rejected on construction.
#[derive(Clone, Debug, PartialEq)]
pub struct Field {
    width: usize,
    height: usize,
    data: Vec<f64>,
}

/// Why a buffer cannot be a [`Field`].
#[derive(Clone, Debug, PartialEq)]
pub enum FieldError {
    /// `width × height` differs from the number of values given.
    SizeMismatch {
        /// Width × height asked for.
        expected: usize,
        /// Values given.
        got: usize,
    },
    /// Width or height below the minimum the metrics need.
    TooSmall {
        /// The width given.
        width: usize,
        /// The height given.
        height: usize,
    },
    /// A NaN or infinite value at this index.
    NonFinite {
        /// Index into the row-major data.
        index: usize,
    },
}

impl fmt::Display for FieldError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FieldError::SizeMismatch { expected, got } => {
                write!(f, "field size mismatch: width × height = {expected} but {got} values given")
            }
            FieldError::TooSmall { width, height } => {
                write!(f, "field {width}×{height} is too small to analyse (need at least {MIN_SIDE}×{MIN_SIDE})")
            }
            FieldError::NonFinite { index } => write!(f, "non-finite value at index {index} (row-major)"),
        }
    }
}

impl std::error::Error for FieldError {}

/// The smallest side the spectral metrics accept: a few rings beyond the
/// three innermost ones the axis metric skips.
pub const MIN_SIDE: usize = 16;

impl Field {
    /// A field from row-major values.
    pub fn new(width: usize, height: usize, data: Vec<f64>) -> Result<Field, FieldError> {
        if width.checked_mul(height) != Some(data.len()) {
            return Err(FieldError::SizeMismatch { expected: width.saturating_mul(height), got: data.len() });
        }
        if width < MIN_SIDE || height < MIN_SIDE {
            return Err(FieldError::TooSmall { width, height });
        }
        if let Some(index) = data.iter().position(|v| !v.is_finite()) {
            return Err(FieldError::NonFinite { index });
        }
        Ok(Field { width, height, data })
    }

    /// A field from `f32` values (what the noise library renders).
    pub fn from_f32(width: usize, height: usize, data: &[f32]) -> Result<Field, FieldError> {
        Field::new(width, height, data.iter().map(|&v| v as f64).collect())
    }

    /// A field of `f(i, j)` for every column `i` and row `j`.
    pub fn from_fn(width: usize, height: usize, mut f: impl FnMut(usize, usize) -> f64) -> Result<Field, FieldError> {
        let mut data = Vec::with_capacity(width * height);
        for j in 0..height {
            for i in 0..width {
                data.push(f(i, j));
            }
        }
        Field::new(width, height, data)
    }

    /// Columns.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Rows.
    pub fn height(&self) -> usize {
        self.height
    }

    /// All values, row-major.
    pub fn values(&self) -> &[f64] {
        &self.data
    }

    /// The value at column `i`, row `j`.
    #[inline]
    pub fn at(&self, i: usize, j: usize) -> f64 {
        self.data[j * self.width + i]
    }

    /// Row `j`.
    pub fn row(&self, j: usize) -> &[f64] {
        &self.data[j * self.width..(j + 1) * self.width]
    }
}
