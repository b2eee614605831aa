//! The one registry of noise kinds: every command (`sample`, `render`,
//! `list`, the help text) is driven from this table, so adding a kind here
//! adds it everywhere.

use noiselab::{
    CellOutput, Classic, DynNoise, Fast, Grid, GridError, Improved, ImprovedVariant, Kernel, Metric, Modified,
    ModifiedHash, ModifiedTexture, Simplex, SimplexN, Sparse, Value, Worley,
};
use std::ops::RangeInclusive;

/// What a user chose for a kind.
#[derive(Clone, Debug)]
pub struct Params {
    pub dims: usize,
    pub seed: u32,
    pub variant: Option<String>,
    /// Sparse convolution: impulses per cell.
    pub impulses: Option<u32>,
    /// Sparse convolution: kernel name.
    pub kernel: Option<String>,
    /// Tiling periods in cells per axis (0 = unbounded).
    pub tile: Option<[u32; 4]>,
    /// Cellular: distance metric name.
    pub metric: Option<String>,
    /// Cellular: jitter in [0, 1].
    pub jitter: Option<f64>,
}

impl Params {
    /// Dimensions and seed, every option at its default.
    pub fn new(dims: usize, seed: u32) -> Params {
        Params { dims, seed, variant: None, impulses: None, kernel: None, tile: None, metric: None, jitter: None }
    }

    /// The tiling periods (all zero when not tiled).
    fn period(&self) -> [u32; 4] {
        self.tile.unwrap_or([0; 4])
    }
}

/// One registered kind.
pub struct KindSpec {
    pub name: &'static str,
    pub summary: &'static str,
    pub dims: RangeInclusive<usize>,
    pub default_dims: usize,
    /// Variant names with a description; the first is the default.
    pub variants: &'static [(&'static str, &'static str)],
    /// The documented output range per dimension, used to map values to pixels.
    pub range: fn(usize) -> (f64, f64),
    /// Kind-specific options it accepts (`impulses`, `kernel`, `metric`, `jitter`).
    pub options: &'static [&'static str],
    /// Whether `--tile` applies.
    pub tileable: bool,
    build: fn(&Params, &str) -> Result<Field, String>,
}

/// A noise of run-time dimension.
pub enum Field {
    D1(Box<dyn DynNoise<1>>),
    D2(Box<dyn DynNoise<2>>),
    D3(Box<dyn DynNoise<3>>),
    D4(Box<dyn DynNoise<4>>),
    D5(Box<dyn DynNoise<5>>),
    D6(Box<dyn DynNoise<6>>),
    D7(Box<dyn DynNoise<7>>),
    D8(Box<dyn DynNoise<8>>),
}

macro_rules! with_field {
    ($field:expr, $n:ident, $d:ident => $body:expr) => {
        #[allow(dead_code)] // `$d` is unused where the body infers the dimension
        match $field {
            Field::D1($n) => {
                const $d: usize = 1;
                $body
            }
            Field::D2($n) => {
                const $d: usize = 2;
                $body
            }
            Field::D3($n) => {
                const $d: usize = 3;
                $body
            }
            Field::D4($n) => {
                const $d: usize = 4;
                $body
            }
            Field::D5($n) => {
                const $d: usize = 5;
                $body
            }
            Field::D6($n) => {
                const $d: usize = 6;
                $body
            }
            Field::D7($n) => {
                const $d: usize = 7;
                $body
            }
            Field::D8($n) => {
                const $d: usize = 8;
                $body
            }
        }
    };
}

fn array<T: Copy + Default, const D: usize>(v: &[T]) -> [T; D] {
    let mut a = [T::default(); D];
    a.copy_from_slice(v);
    a
}

impl Field {
    /// Value at `p` (length = dims) in double precision.
    pub fn get(&self, p: &[f64]) -> f64 {
        with_field!(self, n, D => n.get(array::<f64, D>(p)))
    }

    /// Value at `p` (length = dims) in single precision.
    pub fn get_f32(&self, p: &[f32]) -> f32 {
        with_field!(self, n, D => n.get_f32(array::<f32, D>(p)))
    }

    /// Fill a grid given per-axis slices (length = dims).
    pub fn fill_grid(&self, origin: &[f64], step: &[f64], size: &[usize], out: &mut [f32]) -> Result<(), GridError> {
        with_field!(self, n, D => n.fill_grid(&Grid::new(array(origin), array(step), array(size)), out))
    }

    /// Rows `rows` of the 2D window of the grid (`size` beyond x and y must
    /// be 1), as the whole grid would compute them: each point is the
    /// grid's own `f32` point, so a band equals the same rows of a whole
    /// render bit for bit.
    pub fn fill_rows(
        &self,
        origin: &[f64],
        step: &[f64],
        size: &[usize],
        rows: std::ops::Range<usize>,
        out: &mut [f32],
    ) {
        with_field!(self, n, D => {
            let grid = Grid::<D>::new(array(origin), array(step), array(size));
            let width = size[0];
            let points: Vec<[f32; D]> = (rows.start * width..rows.end * width).map(|k| grid.point(k)).collect();
            // One point per output value, by construction.
            n.fill_points(&points, out).expect("a band's points match its values")
        })
    }
}

macro_rules! field {
    ($noise:expr, $dims:expr, [$($d:literal => $v:ident),*]) => {
        match $dims {
            $($d => Field::$v(Box::new($noise)),)*
            d => unreachable!("dims {d} validated against the registry"),
        }
    };
}

/// A tiling error as the command line words it.
fn tile_error(e: noiselab::PeriodError) -> String {
    format!("--tile: {e}")
}

fn improved(p: &Params, variant: &str) -> Result<Field, String> {
    let v = if variant == "2002" { ImprovedVariant::Original2002 } else { ImprovedVariant::Current };
    let n = Improved::new(p.seed).with_variant(v).with_period(p.period()).map_err(tile_error)?;
    Ok(field!(n, p.dims, [1 => D1, 2 => D2, 3 => D3, 4 => D4]))
}

fn classic(p: &Params, _: &str) -> Result<Field, String> {
    let n = Classic::new(p.seed).with_period(p.period()).map_err(tile_error)?;
    Ok(field!(n, p.dims, [1 => D1, 2 => D2, 3 => D3]))
}

fn fast(p: &Params, _: &str) -> Result<Field, String> {
    Ok(field!(Fast::new(p.seed), p.dims, [2 => D2, 3 => D3]))
}

/// Metrics `--metric` accepts for cellular noise.
pub const METRICS: &str = "euclidean, squared, manhattan, chebyshev, minkowski:P";

fn worley(p: &Params, variant: &str) -> Result<Field, String> {
    let metric = match p.metric.as_deref().unwrap_or("euclidean") {
        "euclidean" => Metric::Euclidean,
        "squared" => Metric::EuclideanSquared,
        "manhattan" => Metric::Manhattan,
        "chebyshev" => Metric::Chebyshev,
        other => match other.strip_prefix("minkowski:").map(str::parse::<f64>) {
            Some(Ok(e)) => Metric::Minkowski(e),
            _ => return Err(format!("--metric must be one of {METRICS}, got {other}")),
        },
    };
    let output = match variant {
        "f2" => CellOutput::F2,
        "f3" => CellOutput::F3,
        "f4" => CellOutput::F4,
        "f2-f1" => CellOutput::F2MinusF1,
        "mean12" => CellOutput::Mean12,
        "product12" => CellOutput::Product12,
        "cells" => CellOutput::CellValue,
        _ => CellOutput::F1,
    };
    let n = Worley::new(p.seed)
        .with_jitter(p.jitter.unwrap_or(1.0))
        .map_err(|e| format!("--jitter: {e}"))?
        .with_metric(metric)
        .map_err(|e| format!("--metric: {e}"))?
        .with_output(output)
        .with_period(p.period())
        .map_err(tile_error)?;
    Ok(field!(n, p.dims, [1 => D1, 2 => D2, 3 => D3, 4 => D4]))
}

fn simplex(p: &Params, _: &str) -> Result<Field, String> {
    Ok(field!(Simplex::new(p.seed), p.dims, [1 => D1, 2 => D2, 3 => D3, 4 => D4]))
}

fn modified(p: &Params, variant: &str) -> Result<Field, String> {
    let tiled = Modified::new(p.seed).with_period(p.period()).map_err(tile_error)?;
    let computed = |hash| tiled.with_hash(hash);
    Ok(match variant {
        "wide" => field!(computed(ModifiedHash::Wide), p.dims, [1 => D1, 2 => D2, 3 => D3, 4 => D4]),
        "textured" => {
            let t = ModifiedTexture::new(&computed(ModifiedHash::Mod61));
            field!(t, p.dims, [1 => D1, 2 => D2, 3 => D3, 4 => D4])
        }
        _ => field!(computed(ModifiedHash::Mod61), p.dims, [1 => D1, 2 => D2, 3 => D3, 4 => D4]),
    })
}

/// Kernels `--kernel` accepts for sparse convolution.
pub const SPARSE_KERNELS: &[&str] = &["cubic", "gaussian"];

/// The sparse convolution noise `params` describe.
pub fn sparse_noise(p: &Params) -> Result<Sparse, String> {
    let kernel = match p.kernel.as_deref().unwrap_or("cubic") {
        "cubic" => Kernel::cubic(),
        "gaussian" => Kernel::gaussian(),
        other => return Err(format!("--kernel must be one of {}, got {other}", SPARSE_KERNELS.join(", "))),
    };
    let n = p.impulses.unwrap_or(20);
    let noise = Sparse::new(p.seed)
        .with_impulses(n)
        .map_err(|_| format!("--impulses must be 1..={}, got {n}", Sparse::MAX_IMPULSES))?;
    noise.with_kernel(kernel).with_period(p.period()).map_err(tile_error)
}

fn sparse(p: &Params, _: &str) -> Result<Field, String> {
    let n = sparse_noise(p)?;
    Ok(field!(n, p.dims, [1 => D1, 2 => D2, 3 => D3, 4 => D4]))
}

fn simplex_n(p: &Params, _: &str) -> Result<Field, String> {
    let n = SimplexN::new(p.seed);
    Ok(field!(n, p.dims, [1 => D1, 2 => D2, 3 => D3, 4 => D4, 5 => D5, 6 => D6, 7 => D7, 8 => D8]))
}

fn value(p: &Params, _: &str) -> Result<Field, String> {
    let n = Value::new(p.seed).with_period(p.period()).map_err(tile_error)?;
    Ok(field!(n, p.dims, [1 => D1, 2 => D2, 3 => D3, 4 => D4]))
}

/// Every kind, in the order `list` shows them.
pub static KINDS: &[KindSpec] = &[
    KindSpec {
        name: "classic",
        summary: "Perlin 1985 gradient noise (cubic s-curve, 256-entry permutation), reference-exact",
        dims: 1..=3,
        default_dims: 3,
        tileable: true,
        options: &[],
        variants: &[],
        range: |d| {
            let b = (d as f64 / 4.0).sqrt();
            (-b, b)
        },
        build: classic,
    },
    KindSpec {
        name: "improved",
        summary: "Perlin 2002 improved noise (quintic fade, edge gradients), reference-exact",
        dims: 1..=4,
        default_dims: 3,
        tileable: true,
        options: &[],
        variants: &[
            ("current", "the reference gradient as it stands today"),
            ("2002", "the gradient as first published in 2002"),
        ],
        range: |d| match d {
            1 => (-0.5, 0.5),
            2 => (-1.0, 1.0),
            3 => (-1.04, 1.04),
            _ => (-1.3, 1.3),
        },
        build: improved,
    },
    KindSpec {
        name: "simplex",
        summary: "simplex noise, Gustavson's 2012 reference (2D-4D) and simplexnoise1234 (1D), reference-exact",
        dims: 1..=4,
        default_dims: 3,
        tileable: false,
        options: &[],
        variants: &[],
        range: |_| (-1.0, 1.0),
        build: simplex,
    },
    KindSpec {
        name: "simplex-n",
        summary: "N-dimensional simplex noise (any dimension, cost O(n^2))",
        dims: 1..=8,
        default_dims: 5,
        tileable: false,
        options: &[],
        variants: &[],
        range: |_| (-1.0, 1.0),
        build: simplex_n,
    },
    KindSpec {
        name: "value",
        summary: "lattice value noise with quintic interpolation",
        dims: 1..=4,
        default_dims: 3,
        tileable: true,
        options: &[],
        variants: &[],
        range: |_| (-1.0, 1.0),
        build: value,
    },
    KindSpec {
        name: "modified",
        summary: "Olano 2005 modified noise: table-free hash, exact zero slices",
        dims: 1..=4,
        default_dims: 3,
        tileable: true,
        options: &[],
        variants: &[
            ("mod61", "squaring modulo 61, period 61 cells (Olano)"),
            ("wide", "32-bit mixing hash with the same structure, no short period"),
            ("textured", "mod61 evaluated from a baked 61x61 plane table (same values)"),
        ],
        range: |d| match d {
            1 => (-0.31, 0.31),
            2 => (-0.61, 0.61),
            _ => (-1.0, 1.0),
        },
        build: modified,
    },
    KindSpec {
        name: "sparse",
        summary: "Sparse convolution noise (Frisvad & Wyvill 2007): random impulses, cubic kernel, no lattice artefacts; --impulses N (20), --kernel cubic|gaussian",
        dims: 1..=4,
        default_dims: 3,
        tileable: true,
        options: &["impulses", "kernel"],
        variants: &[],
        range: |_| (-1.0, 1.0),
        build: sparse,
    },
    KindSpec {
        name: "worley",
        summary: "Cellular noise (Worley 1996): distances to the nearest jittered feature points; --metric, --jitter",
        dims: 1..=4,
        default_dims: 2,
        tileable: true,
        options: &["metric", "jitter"],
        variants: &[
            ("f1", "distance to the nearest feature point"),
            ("f2", "second nearest"),
            ("f3", "third nearest"),
            ("f4", "fourth nearest"),
            ("f2-f1", "F2 − F1: cell borders"),
            ("mean12", "(F1 + F2) / 2"),
            ("product12", "F1 · F2"),
            ("cells", "a value per cell in [−1, 1): flat Voronoi cells"),
        ],
        range: |d| (0.0, (d as f64).sqrt()),
        build: worley,
    },
    KindSpec {
        name: "fast",
        summary: "Fast approximate noise: a 32³ two-channel volume of 8-periodic improved noise, trilinear, rotated by a low-frequency sample",
        dims: 2..=3,
        default_dims: 3,
        tileable: false,
        options: &[],
        variants: &[],
        range: |_| (-1.0, 1.0),
        build: fast,
    },
];

/// `params`' noise as a fractal sum: octave i is the kind built with seed
/// `seed + i`, combined by `mode`.
pub fn fractal(
    spec: &KindSpec,
    params: &Params,
    octaves: u32,
    mode: noiselab::FractalMode,
    lacunarity: f64,
    gain: f64,
) -> Result<Field, String> {
    // A tiled octave i keeps the whole tile as its period: tile·lacunarityⁱ cells.
    let tile = |i: u32| -> Result<Option<[u32; 4]>, String> {
        let Some(t) = params.tile else { return Ok(None) };
        let octave = noiselab::Octave { index: i, seed: 0, frequency: lacunarity.powi(i as i32) };
        octave.period(t).map(Some).map_err(|e| format!("--tile with --octaves: {e}"))
    };
    let fields = (0..octaves)
        .map(|i| spec.build(&Params { seed: params.seed.wrapping_add(i), tile: tile(i)?, ..params.clone() }))
        .collect::<Result<Vec<Field>, String>>()?;
    macro_rules! sum {
        ($($v:ident),*) => {
            match fields.first() {
                $(Some(Field::$v(_)) => {
                    let boxes = fields.into_iter().map(|f| match f { Field::$v(b) => b, _ => unreachable!("octaves share a dimension") }).collect();
                    Field::$v(Box::new(noiselab::Fractal::from_octaves(boxes, mode, lacunarity, gain).map_err(|e| e.to_string())?))
                })*
                None => unreachable!("at least one octave"),
            }
        };
    }
    Ok(sum!(D1, D2, D3, D4, D5, D6, D7, D8))
}

/// Look a kind up by name.
pub fn find(name: &str) -> Result<&'static KindSpec, String> {
    KINDS.iter().find(|k| k.name == name).ok_or_else(|| {
        let names: Vec<&str> = KINDS.iter().map(|k| k.name).collect();
        format!("unknown kind '{name}' (known: {})", names.join(", "))
    })
}

impl KindSpec {
    /// Validate `params` and build the noise.
    pub fn build(&self, params: &Params) -> Result<Field, String> {
        if !self.dims.contains(&params.dims) {
            return Err(format!(
                "--dims for {} must be {}..={}, got {}",
                self.name,
                self.dims.start(),
                self.dims.end(),
                params.dims
            ));
        }
        let variant = match (&params.variant, self.variants) {
            (None, []) => "",
            (None, v) => v[0].0,
            (Some(name), []) => return Err(format!("{} has no variants, got --variant {name}", self.name)),
            (Some(name), v) => match v.iter().find(|(n, _)| n == name) {
                Some((n, _)) => n,
                None => {
                    let names: Vec<&str> = v.iter().map(|(n, _)| *n).collect();
                    return Err(format!("--variant for {} must be one of {}, got {name}", self.name, names.join(", ")));
                }
            },
        };
        let options = [
            (params.impulses.is_some(), "impulses"),
            (params.kernel.is_some(), "kernel"),
            (params.metric.is_some(), "metric"),
            (params.jitter.is_some(), "jitter"),
        ];
        for (given, option) in options {
            if given && !self.options.contains(&option) {
                return Err(format!("--{option} does not apply to {}", self.name));
            }
        }
        if params.tile.is_some() && !self.tileable {
            return Err(format!(
                "--tile: {} is not tileable (its lattice is skewed or baked); tileable kinds: {}",
                self.name,
                KINDS.iter().filter(|k| k.tileable).map(|k| k.name).collect::<Vec<_>>().join(", ")
            ));
        }
        (self.build)(params, variant)
    }
}
