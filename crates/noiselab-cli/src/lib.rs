//! The `noiselab` command line: sample and render procedural noise.
//!
//! `src/main.rs` only calls [`run`]. The commands live in this library so
//! that the test build compiles them once: a binary with unit tests is
//! compiled twice (as the program the integration tests run, and as its own
//! test harness), and this crate instantiates every kind's batch code.

mod analyze;
mod gallery;
mod output;
mod recipes;
mod registry;
mod render;
mod report;
mod sample;

use clap::{Args, Parser, Subcommand};
use std::process::ExitCode;

#[derive(Parser, Debug)]
#[command(name = "noiselab", version, about = "Procedural noise, reference-exact: sample values, render images")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Print a shell completion script (bash, zsh, fish, elvish, powershell) to standard output.
    Completions {
        /// The shell.
        shell: clap_complete::Shell,
    },
    /// Print the man page (roff) to standard output.
    Man,
    /// Render every kind, variant, fractal and recipe into a folder (./gallery)
    /// with an index.html giving each picture's command and render time.
    Gallery(GalleryArgs),
    /// List the noise kinds with their dimensions and variants.
    List,
    /// Read points from standard input (one per line, coordinates separated by
    /// commas or spaces) and print one value per line.
    #[command(allow_negative_numbers = true)]
    Sample(SampleArgs),
    /// Render a 2D image (or a slice of a higher-dimensional noise) to a file.
    #[command(allow_negative_numbers = true)]
    Render(RenderArgs),
    /// Measure noise images: statistics, spectrum, isotropy, lattice artefacts.
    /// Several files are several seeds of one noise (spectra averaged).
    #[command(allow_negative_numbers = true)]
    Analyze(AnalyzeArgs),
    /// Render every kind at a matched peak frequency, analyse it, and write
    /// the published comparison (docs/quality.md and its pictures).
    Report(ReportArgs),
}

/// Arguments of `noiselab gallery`.
#[derive(Args, Debug)]
pub struct GalleryArgs {
    /// Folder receiving the pictures and index.html.
    #[arg(long, default_value = "gallery")]
    pub out: std::path::PathBuf,
}

/// Arguments of `noiselab report`.
#[derive(Args, Debug)]
pub struct ReportArgs {
    /// Folder receiving quality.md and quality/*.png.
    #[arg(long, default_value = "docs")]
    pub out: std::path::PathBuf,
    /// Side of each analysed image, pixels.
    #[arg(long, default_value_t = 1024, value_parser = render::parse_count)]
    pub size: usize,
    /// Seeds per noise (their periodograms are averaged).
    #[arg(long, default_value_t = 4, value_parser = render::parse_count)]
    pub seeds: usize,
}

/// Options shared by every command that builds a noise.
#[derive(Args, Debug, Clone)]
pub struct NoiseArgs {
    /// Noise kind (see `noiselab list`).
    pub kind: String,
    /// Number of dimensions (default: the kind's usual one, 3 for most).
    #[arg(long)]
    pub dims: Option<usize>,
    /// Seed; 0 is the published reference.
    #[arg(long, default_value_t = 0)]
    pub seed: u32,
    /// Kind-specific variant (see `noiselab list`).
    #[arg(long)]
    pub variant: Option<String>,
    /// Sparse convolution: impulses per cell, the quality knob (10 decent, 30 excellent; default 20).
    #[arg(long)]
    pub impulses: Option<u32>,
    /// Sparse convolution: kernel, cubic (the paper's) or gaussian (its reference).
    #[arg(long)]
    pub kernel: Option<String>,
    /// Tile: periods in lattice cells, X[,Y[,Z[,W]]] (0 = that axis unbounded). Any positive count.
    #[arg(long, value_parser = render::parse_tile)]
    pub tile: Option<render::Tile>,
    /// Cellular: euclidean (default), squared, manhattan, chebyshev or minkowski:P.
    #[arg(long)]
    pub metric: Option<String>,
    /// Cellular: how far feature points move from cell centres, 0..=1 (default 1).
    #[arg(long)]
    pub jitter: Option<f64>,
    /// Fractal sum of N octaves (1..=30), or `auto`: as many as the pixel size allows
    /// (render only: stop before an octave varies faster than every two pixels).
    #[arg(long, value_parser = render::parse_octaves)]
    pub octaves: Option<render::Octaves>,
    /// How octaves combine (with --octaves): fbm (default), turbulence, ridged, billow, hybrid.
    #[arg(long, value_parser = render::parse_fractal)]
    pub fractal: Option<noiselab::FractalMode>,
    /// Frequency ratio between octaves (> 1, default 2).
    #[arg(long)]
    pub lacunarity: Option<f64>,
    /// Amplitude ratio between octaves (> 0, default 0.5).
    #[arg(long)]
    pub gain: Option<f64>,
}

/// Arithmetic precision of `sample`.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum Precision {
    /// Double precision: the reference-exact path.
    F64,
    /// Single precision.
    F32,
}

/// How `render` evaluates sparse convolution noise.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// Visit each impulse once and add its kernel into the pixels it reaches.
    Splat,
    /// Evaluate every pixel on its own.
    Gather,
}

/// A noise built from the command line.
pub struct Built {
    /// The registered kind.
    pub spec: &'static registry::KindSpec,
    /// The noise (a fractal sum of the kind with --octaves).
    pub field: registry::Field,
    /// Dimensions.
    pub dims: usize,
    /// Documented output range (for mapping to pixels).
    pub range: (f64, f64),
    /// Whether --octaves made it a fractal sum.
    pub fractal: bool,
}

/// Arguments of `noiselab sample`.
#[derive(Args, Debug)]
pub struct SampleArgs {
    /// The noise to sample.
    #[command(flatten)]
    pub noise: NoiseArgs,
    /// Arithmetic precision.
    #[arg(long, value_enum, default_value_t = Precision::F64)]
    pub precision: Precision,
    /// Recipes: the 3D noise kind they are made of (default improved). A recipe samples lines of
    /// `u v t` (image coordinates in [0, 1] and time) and prints its scalar field.
    #[arg(long)]
    pub base: Option<String>,
}

/// Arguments of `noiselab render`.
#[derive(Args, Debug)]
pub struct RenderArgs {
    /// The noise to render.
    #[command(flatten)]
    pub noise: NoiseArgs,
    /// Image size in pixels, WIDTHxHEIGHT.
    #[arg(long, default_value = "512x512", value_parser = render::parse_size)]
    pub size: (usize, usize),
    /// Pixels per lattice cell (PX): pixel (row j, column i) holds noise(X + i·(1/PX), Y + j·(1/PX), …).
    #[arg(long, default_value_t = 32.0, value_parser = render::parse_scale)]
    pub scale: f64,
    /// Noise coordinates of pixel (0, 0), X,Y.
    #[arg(long, default_value = "0,0", allow_hyphen_values = true, value_parser = render::parse_pair)]
    pub origin: (f64, f64),
    /// Coordinates of the slice for 3D and 4D noise, Z[,W,…].
    #[arg(long, allow_hyphen_values = true, value_parser = render::parse_slice)]
    pub slice: Option<render::Slice>,
    /// Recipes (marble, wood, clouds, flame, planet, stucco, bump, hypertexture): the 3D noise kind
    /// they are made of (default improved); the noise options above apply to it.
    #[arg(long)]
    pub base: Option<String>,
    /// Sparse convolution: splat impulses into the image (fast, default for 2D
    /// windows and slices) or gather them per pixel (point evaluation); same image within 1e-5.
    #[arg(long, value_enum)]
    pub method: Option<Method>,
    /// Map values LO,HI (instead of the kind's documented range) to black..white or the ramp's ends.
    #[arg(long, allow_hyphen_values = true, value_parser = render::parse_range)]
    pub range: Option<(f64, f64)>,
    /// Colour PNGs through a ramp: grey, marble, wood, sky, flame.
    #[arg(long, value_parser = render::parse_ramp)]
    pub ramp: Option<noiselab::recipes::Ramp>,
    /// Render a volume of N slices along z (3D/4D noise; z spacing = pixel spacing): a (z, y, x) .npy,
    /// or numbered PNGs NAME-000.png … for an output NAME.png.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=65536))]
    pub depth: Option<u32>,
    /// Animate: render N frames along the noise's last axis (time), as an animated PNG or a 3D .npy.
    #[arg(long, value_parser = clap::value_parser!(u32).range(2..=1000))]
    pub frames: Option<u32>,
    /// With --frames: loop seamlessly (Perlin's blend over frames × time step).
    #[arg(long = "loop")]
    pub r#loop: bool,
    /// With --frames: time between frames, in cells (default 0.05).
    #[arg(long, default_value_t = 0.05)]
    pub time_step: f64,
    /// Bits per PNG sample (8 or 16).
    #[arg(long, default_value_t = 8, value_parser = render::parse_bits)]
    pub bits: u8,
    /// Output file: .png (grey, mapped from the kind's range), .npy or .f32 (exact float32 values).
    #[arg(short, long)]
    pub output: std::path::PathBuf,
    /// Overwrite an existing output file.
    #[arg(long)]
    pub force: bool,
}

/// Arguments of `noiselab analyze`.
#[derive(Args, Debug)]
pub struct AnalyzeArgs {
    /// Images to analyse: .npy (2-D float32/float64), .f32 (raw float32, square
    /// unless --size) or .exr; all the same size.
    #[arg(required = true)]
    pub files: Vec<std::path::PathBuf>,
    /// Pixels per lattice cell (a node on pixel 0,0 unless --lattice-offset):
    /// enables the node, folded-variance and second-derivative metrics.
    #[arg(long, value_parser = render::parse_scale)]
    pub lattice: Option<f64>,
    /// Pixel COLUMN,ROW of a lattice node.
    #[arg(long, default_value = "0,0", value_parser = render::parse_offset)]
    pub lattice_offset: (usize, usize),
    /// A period to test, in pixels (tiling check).
    #[arg(long, value_parser = render::parse_count)]
    pub period: Option<usize>,
    /// Size of raw .f32 input, WIDTHxHEIGHT.
    #[arg(long, value_parser = render::parse_size)]
    pub size: Option<(usize, usize)>,
    /// Print the report as JSON.
    #[arg(long)]
    pub json: bool,
    /// Write PNG plots (spectrum, radial profile, histogram, folded variance) into this folder.
    #[arg(long)]
    pub plots: Option<std::path::PathBuf>,
}

/// The command line with the registries' contents in the help of the
/// commands that take a noise, so `--help`, completions and the man page
/// list exactly what `list` lists.
fn command() -> clap::Command {
    use clap::CommandFactory;
    let kinds: Vec<String> = registry::KINDS.iter().map(|k| format!("  {:<12} {}", k.name, k.summary)).collect();
    let recipes: Vec<String> = recipes::RECIPES.iter().map(|r| format!("  {:<12} {}", r.name, r.summary)).collect();
    let text = format!(
        "Kinds:\n{}\n\nRecipes:\n{}\n\nSee `noiselab list` for dimensions and variants.",
        kinds.join("\n"),
        recipes.join("\n")
    );
    Cli::command()
        .mut_subcommand("render", |c| c.after_help(text.clone()))
        .mut_subcommand("sample", |c| c.after_help(text.clone()))
}

/// Parse the process's arguments and run the command; the exit code is 0 on
/// success, 1 when the command fails and 2 for bad arguments.
pub fn run() -> ExitCode {
    use clap::FromArgMatches;
    let cli = match command().try_get_matches().and_then(|m| Cli::from_arg_matches(&m)) {
        Ok(cli) => cli,
        Err(e) => {
            use clap::error::ErrorKind;
            if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion) {
                let _ = e.print();
                return ExitCode::SUCCESS;
            }
            if e.kind() == ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand {
                let _ = e.print();
                return ExitCode::from(2);
            }
            // One line, as for every other error.
            let text = e.render().to_string();
            // The message may continue on indented lines (e.g. the missing
            // arguments) before the usage block; keep them, on one line.
            let message: Vec<&str> = text.lines().take_while(|l| !l.trim().is_empty()).map(str::trim).collect();
            let message = message.join(" ");
            let message = message.trim_start_matches("error: ");
            let message = if message.is_empty() { "invalid arguments" } else { message };
            eprintln!("noiselab: {message} (see --help)");
            return ExitCode::from(2);
        }
    };
    let result = match cli.command {
        Command::Gallery(args) => gallery::run(&args),
        Command::Completions { shell } => {
            clap_complete::generate(shell, &mut command(), "noiselab", &mut std::io::stdout());
            Ok(())
        }
        Command::Man => clap_mangen::Man::new(command())
            .render(&mut std::io::stdout())
            .map_err(|e| format!("cannot write the man page: {e}")),
        Command::List => {
            list();
            Ok(())
        }
        Command::Sample(args) => sample::run(&args),
        Command::Render(args) => render::run(&args),
        Command::Analyze(args) => analyze::run(&args),
        Command::Report(args) => report::run(&args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(msg) => {
            eprintln!("noiselab: {msg}");
            ExitCode::FAILURE
        }
    }
}

fn list() {
    println!("kinds:");
    for k in registry::KINDS {
        println!(
            "{:<10} dims {}..={} (default {})  {}",
            k.name,
            k.dims.start(),
            k.dims.end(),
            k.default_dims,
            k.summary
        );
        for (i, (name, what)) in k.variants.iter().enumerate() {
            let default = if i == 0 { " (default)" } else { "" };
            println!("{:<12}--variant {name}{default}: {what}", "");
        }
    }
    println!("recipes (render only; --base KIND picks the 3D noise, improved by default; --slice T is time):");
    for r in recipes::RECIPES {
        println!("{:<12} {}", r.name, r.summary);
    }
    println!("fractal sums of any kind: --octaves N|auto --fractal fbm|turbulence|ridged|billow|hybrid");
}

/// The pure helpers `tests/helpers.rs` checks directly; not an API.
#[doc(hidden)]
pub mod internals {
    pub use crate::output::{npy_header, unit};
    pub use crate::render::{parse_list, parse_pair, parse_scale, parse_size};
    pub use crate::sample::{parse_point, split};
}

impl NoiseArgs {
    /// Every noise option, for `dims` dimensions.
    pub fn params(&self, dims: usize) -> registry::Params {
        registry::Params {
            variant: self.variant.clone(),
            impulses: self.impulses,
            kernel: self.kernel.clone(),
            tile: self.tile.map(|t| t.0),
            metric: self.metric.clone(),
            jitter: self.jitter,
            ..registry::Params::new(dims, self.seed)
        }
    }

    /// Resolve the kind and build the noise, validating every parameter.
    /// Resolve the kind and build the noise (a fractal sum with
    /// `--octaves`), validating every parameter. `footprint` is the input
    /// distance per pixel, for `--octaves auto`. Returns the kind, the
    /// noise, its dimension and its documented range.
    pub fn build(&self, footprint: Option<f64>) -> Result<Built, String> {
        let spec = registry::find(&self.kind)?;
        let dims = self.dims.unwrap_or(spec.default_dims);
        let params = self.params(dims);
        let base_range = (spec.range)(dims);
        let lacunarity = self.lacunarity.unwrap_or(2.0);
        let gain = self.gain.unwrap_or(0.5);
        let octaves = match (self.octaves, footprint) {
            (None, _) => {
                if self.fractal.is_some() || self.lacunarity.is_some() || self.gain.is_some() {
                    return Err("--fractal, --lacunarity and --gain need --octaves".into());
                }
                let field = spec.build(&params)?;
                return Ok(Built { spec, field, dims, range: base_range, fractal: false });
            }
            (Some(render::Octaves::Count(n)), _) => n,
            (Some(render::Octaves::Auto), Some(f)) => noiselab::Fractal::<()>::octaves_for_footprint(f, lacunarity),
            (Some(render::Octaves::Auto), None) => {
                return Err("--octaves auto needs a pixel size: use it with render".into())
            }
        };
        let mode = self.fractal.unwrap_or_default();
        let field = registry::fractal(spec, &params, octaves, mode, lacunarity, gain)?;
        let r = base_range.0.abs().max(base_range.1.abs());
        Ok(Built { spec, field, dims, range: mode.range(r), fractal: true })
    }
}
