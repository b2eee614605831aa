//! `noiselab report`: every kind rendered at a matched peak frequency,
//! analysed, and published as `docs/quality.md` with a picture of each
//! noise beside its spectrum.

use std::fmt::Write as _;
use std::path::Path;

use noiselab_analysis::{analyze, plots, reference, Field as Samples, Lattice, Options, Report};
use rayon::prelude::*;

use crate::output::{Format, Image, Pending};
use crate::registry::{self, Params};
use crate::ReportArgs;

/// Every kind's peak lands here (cycles per pixel): low enough that every
/// kind gets at least 16 pixels per cell at an integer period.
const TARGET_PEAK: f64 = 0.025;
/// Side of the pictures in the published page.
const THUMB: usize = 256;

/// One row of the comparison: a registered kind (and variant), sliced.
struct Row {
    label: String,
    kind: &'static str,
    variant: Option<&'static str>,
    z: f64,
}

/// The rows: every 3D-capable kind and variant on a lattice plane (z = 0)
/// and between planes (z = 0.5).
fn rows() -> Vec<Row> {
    let mut rows = Vec::new();
    for spec in registry::KINDS.iter().filter(|k| k.dims.contains(&3)) {
        let variants: Vec<Option<&'static str>> = if spec.variants.is_empty() {
            vec![None]
        } else {
            // Textured modified noise equals the computed one; of cellular
            // noise's outputs, F1 and the F2 − F1 borders are the ones people use.
            let shown = |v: &str| v != "textured" && (spec.name != "worley" || v == "f1" || v == "f2-f1");
            spec.variants.iter().map(|(v, _)| *v).filter(|v| shown(v)).map(Some).collect()
        };
        for (i, variant) in variants.into_iter().enumerate() {
            for z in [0.0, 0.5] {
                let name = match variant {
                    Some(v) if i > 0 => format!("{} {v}", spec.name),
                    _ => spec.name.to_string(),
                };
                rows.push(Row {
                    label: format!("{name}, z = {z}"),
                    kind: spec.name,
                    variant: if i > 0 { variant } else { None },
                    z,
                });
            }
        }
    }
    rows
}

/// Seed `s` of a row at `px` pixels per cell.
fn render(row: &Row, seed: u32, px: f64, size: usize) -> Result<Vec<f32>, String> {
    let spec = registry::find(row.kind)?;
    let params = Params { variant: row.variant.map(str::to_string), ..Params::new(3, seed) };
    let field = spec.build(&params)?;
    crate::render::window(&field, 3, (0.0, 0.0), &[row.z], 1.0 / px, (size, size))
}

fn samples(values: &[f32], size: usize) -> Result<Samples, String> {
    Samples::from_f32(size, size, values).map_err(|e| e.to_string())
}

/// One analysed row.
struct Measured {
    label: String,
    file: String,
    command: String,
    px: usize,
    report: Report,
}

/// Renders, analyses and pictures one row.
fn measure(row: Row, size: usize, seeds: usize, pictures: &Path) -> Result<Measured, String> {
    let analyse = |px: f64, lattice: Option<Lattice>| {
        let fields = (1..=seeds as u32)
            .map(|seed| samples(&render(&row, seed, px, size)?, size))
            .collect::<Result<Vec<_>, String>>()?;
        analyze(&fields, &Options { lattice, period: None }).map_err(|e| e.to_string())
    };
    // Probe the peak (all seeds) at 16 px per cell, then choose the integer
    // period that puts it at the target.
    let cycles_per_cell = analyse(16.0, None)?.spectrum.peak_frequency * 16.0;
    let px = ((cycles_per_cell / TARGET_PEAK).round() as usize).max(16);
    let report = analyse(px as f64, Some(Lattice { period: px as f64, offset: (0, 0) }))?;
    let file = row.label.replace([',', '=', ' '], "-").replace("--", "-").replace("--", "-");
    let spec = registry::find(row.kind)?;
    let thumb = THUMB.min(size);
    let first = render(&row, 1, px as f64, thumb)?;
    let image = Image { width: thumb, height: thumb, values: &first, range: (spec.range)(3) };
    Pending::create(&pictures.join(format!("{file}.png")), true)?.finish(|w| Format::Png.write(w, &image, 8))?;
    write_spectrum(&pictures.join(format!("{file}-spectrum.png")), &report)?;
    let variant = row.variant.map_or(String::new(), |v| format!(" --variant {v}"));
    let command = format!(
        "noiselab render {}{variant} --seed 1 --size {size}x{size} --scale {px} --slice {} -o {file}.npy",
        row.kind, row.z
    );
    eprintln!(
        "{:<28} {px:>3} px/cell  peak {:.4} cpp  ({:.2} s)",
        row.label, report.spectrum.peak_frequency, report.seconds
    );
    Ok(Measured { label: row.label, file, command, px, report })
}

pub fn run(args: &ReportArgs) -> Result<(), String> {
    let size = args.size;
    let seeds = args.seeds;
    let pictures = args.out.join("quality");
    std::fs::create_dir_all(&pictures).map_err(|e| format!("{}: {e}", pictures.display()))?;
    // Rows are independent: analyse them on every core (the analysis of one
    // image is single-threaded).
    let mut measured =
        rows().into_par_iter().map(|row| measure(row, size, seeds, &pictures)).collect::<Result<Vec<_>, String>>()?;
    // The isotropic, stationary reference at the same peak: σ = 1/(2π f).
    let sigma = 1.0 / (2.0 * core::f64::consts::PI * TARGET_PEAK);
    let fields: Vec<Samples> = (1..=seeds as u64).map(|s| reference::gaussian_noise(size, size, sigma, s)).collect();
    let options = Options { lattice: Some(Lattice { period: 16.0, offset: (0, 0) }), period: None };
    let report = analyze(&fields, &options).map_err(|e| e.to_string())?;
    let side = THUMB.min(size);
    let thumb: Vec<f32> = (0..side * side).map(|k| fields[0].at(k % side, k / side) as f32).collect();
    let image = Image { width: side, height: side, values: &thumb, range: (-1.0, 1.0) };
    Pending::create(&pictures.join("gaussian-reference.png"), true)?.finish(|w| Format::Png.write(w, &image, 8))?;
    write_spectrum(&pictures.join("gaussian-reference-spectrum.png"), &report)?;
    measured.push(Measured {
        label: format!("reference: Gaussian-filtered white noise, σ = {sigma:.2} px"),
        file: "gaussian-reference".into(),
        command: "noiselab_analysis::reference::gaussian_noise".into(),
        px: 16,
        report,
    });

    let tradeoff = sparse_tradeoff(size, seeds, &pictures)?;
    let page = page(&measured, size, seeds) + &tradeoff;
    Pending::create(&args.out.join("quality.md"), true)?.finish(|w| w.write_all(page.as_bytes()))
}

/// The paper's Figure 7 as numbers: quality against impulses per cell,
/// with the cost of each measured now (both renderers, this machine).
fn sparse_tradeoff(size: usize, seeds: usize, pictures: &Path) -> Result<String, String> {
    use std::time::Instant;
    let px = 32.0;
    let grid = noiselab::Grid::new([0.0, 0.0, 0.5], [1.0 / px, 1.0 / px, 0.0], [size, size, 1]);
    let mut s = String::new();
    let _ = writeln!(s, "\n## Sparse convolution: quality against quantity (Frisvad & Wyvill's Figure 7)\n");
    let _ = writeln!(
        s,
        "Slices z = 0.5 of 3D sparse convolution noise (cubic kernel), {size}², {px} px per cell, {seeds} seeds. \
         Times are one render of one seed on this machine, all cores, measured when this page was generated \
         (criterion benchmarks: `cargo bench --manifest-path benches/Cargo.toml`).\n"
    );
    let _ = writeln!(s, "| impulses per cell | picture | excess kurtosis | anisotropy (dB) | axis-line ratio | folded-variance CV (null) | cyclo max/null | splat (ms) | gather (ms) | gather/splat |");
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|---|");
    for n in [10u32, 20, 30] {
        let params = |seed| Params { impulses: Some(n), ..Params::new(3, seed) };
        let mut fields = Vec::new();
        let mut first = Vec::new();
        for seed in 1..=seeds as u32 {
            let noise = registry::sparse_noise(&params(seed))?;
            let mut out = vec![0f32; size * size];
            noise.splat_grid(&grid, &mut out).map_err(|e| e.to_string())?;
            if seed == 1 {
                first = out.clone();
            }
            fields.push(samples(&out, size)?);
        }
        let r = analyze(&fields, &Options { lattice: Some(Lattice { period: px, offset: (0, 0) }), period: None })
            .map_err(|e| e.to_string())?;
        let noise = registry::sparse_noise(&params(1))?;
        let mut out = vec![0f32; size * size];
        let t = Instant::now();
        noise.splat_grid(&grid, &mut out).map_err(|e| e.to_string())?;
        let splat = t.elapsed().as_secs_f64();
        let t = Instant::now();
        noiselab::Noise::<3>::fill_grid(&noise, &grid, &mut out).map_err(|e| e.to_string())?;
        let gather = t.elapsed().as_secs_f64();
        let thumb = THUMB.min(size);
        let crop: Vec<f32> = (0..thumb * thumb).map(|k| first[(k / thumb) * size + k % thumb]).collect();
        let file = format!("sparse-n{n}");
        let image = Image { width: thumb, height: thumb, values: &crop, range: (-1.0, 1.0) };
        Pending::create(&pictures.join(format!("{file}.png")), true)?.finish(|w| Format::Png.write(w, &image, 8))?;
        let fv = r.lattice.as_ref().and_then(|l| l.folded_variance.as_ref());
        let _ = writeln!(
            s,
            "| {n} | ![n = {n}](quality/{file}.png) | {:.3} | {:+.2} | {:.2} | {} | {:.2} | {:.1} | {:.1} | {:.1} |",
            r.values.excess_kurtosis,
            r.anisotropy.excess_db,
            r.axis.axis_ratio,
            fv.map_or("–".into(), |f| format!("{:.4} ({:.4})", f.folded_variance_cv, f.null_cv)),
            r.cyclostationarity.cyclo_max_over_null,
            splat * 1e3,
            gather * 1e3,
            gather / splat
        );
    }
    let _ = writeln!(
        s,
        "\nMore impulses make the noise more Gaussian (excess kurtosis towards 0) at proportional cost; \
         no setting shows a lattice (cyclostationarity ≈ 1, no lines). The folded-variance null assumes \
         Gaussian values; with excess kurtosis κ its sampling CV grows by √(1 + κ/2) (1.35× at n = 10), \
         which is what the n = 10 row shows."
    );
    Ok(s)
}

/// What a row's numbers say, by the quality note's suggested thresholds.
fn flags(r: &Report, seeds: usize) -> Vec<&'static str> {
    let mut f = Vec::new();
    if r.cyclostationarity.cyclo_max_over_null > 2.0 {
        f.push("lattice lines");
    }
    let anisotropy_sd_db = 10.0 / core::f64::consts::LN_10 * r.anisotropy.peak_octave_linear_null_std * seeds as f64;
    if r.anisotropy.excess_db > 3.0 * anisotropy_sd_db {
        f.push("anisotropic");
    }
    if r.axis.z < -3.0 {
        f.push("axes depleted");
    } else if r.axis.z > 3.0 {
        f.push("axis-aligned");
    }
    if let Some(l) = &r.lattice {
        // A jump only counts where it stands out from the same statistic
        // at cell centres (cellular noise is C0 everywhere, not at faces).
        if let (Some(jump), Some(centres)) = (l.c2_jump_score, l.c2_reference_score) {
            if jump > 1.0 && jump > 2.0 * centres {
                f.push("C2 jump");
            }
        }
        if l.node_value_score.is_some_and(|n| n < 0.01) {
            f.push("zero at nodes");
        }
        if l.folded_variance.as_ref().is_some_and(|v| v.folded_variance_cv > 2.0 * v.null_cv) {
            f.push("cell-dependent variance");
        }
    }
    f
}

/// The central `THUMB²` frequencies of the averaged spectrum (out to
/// ±THUMB/2 bins), still in FFT order for the plot to centre.
fn write_spectrum(path: &Path, report: &Report) -> Result<(), String> {
    let (w, h) = (report.width, report.height);
    let side = THUMB.min(w).min(h);
    let half = (side / 2) as i64;
    let mut crop = vec![0.0; side * side];
    for ky in -half..half {
        for kx in -half..half {
            let src = ky.rem_euclid(h as i64) as usize * w + kx.rem_euclid(w as i64) as usize;
            let dst = ky.rem_euclid(side as i64) as usize * side + kx.rem_euclid(side as i64) as usize;
            crop[dst] = report.power[src];
        }
    }
    plots::power_spectrum(path, side, side, &crop).map_err(|e| format!("{}: {e}", path.display()))
}

fn page(rows: &[Measured], size: usize, seeds: usize) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "# Noise quality, measured\n");
    let _ = writeln!(
        s,
        "Generated by `cargo run --release -p noiselab-cli -- report` (do not edit by hand). Every kind is rendered at \
         {size}×{size} pixels, {seeds} seeds (periodograms averaged), on a lattice plane (z = 0) and between planes \
         (z = 0.5), with its pixels per cell chosen so that its spectral peak lands near {TARGET_PEAK} cycles per \
         pixel. The metrics are defined in [quality-metrics.md](quality-metrics.md); the last row is the isotropic, \
         stationary reference, and the second row gives what an ideal noise scores.\n"
    );
    let _ = writeln!(
        s,
        "| noise | px/cell | std | excess kurtosis | peak (cpp) | peak (cycles/cell) | octave around peak | below peak/4 | anisotropy (dB) | axis-line ratio | node value score | folded-variance CV | C2 jump (centres) | cyclo max/null | flags |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    let null_fv = rows
        .first()
        .and_then(|r| r.report.lattice.as_ref()?.folded_variance.as_ref().map(|f| f.null_cv))
        .unwrap_or(f64::NAN);
    let _ = writeln!(
        s,
        "| *ideal (null)* | | | 0 | | | 0.471 | 0.061 | 0 ± {:.2} | 1 ± {:.3} | 1 | ≤ {null_fv:.3} | = centres | 1 | |",
        rows.first().map_or(f64::NAN, |r| 10.0 / core::f64::consts::LN_10
            * r.report.anisotropy.peak_octave_linear_null_std
            * seeds as f64),
        rows.first().map_or(f64::NAN, |r| r.report.axis.null_sd),
    );
    for m in rows {
        let r = &m.report;
        let l = r.lattice.as_ref();
        let num = |v: Option<f64>, d: usize| v.map_or("–".to_string(), |v| format!("{v:.d$}"));
        let c2 =
            l.map_or("–".to_string(), |l| format!("{} ({})", num(l.c2_jump_score, 3), num(l.c2_reference_score, 3)));
        let _ = writeln!(
            s,
            "| {} | {} | {:.3} | {:.2} | {:.4} | {:.3} | {:.3} | {:.4} | {:+.2} | {:.2} | {} | {} | {} | {:.1} | {} |",
            m.label,
            m.px,
            r.values.std,
            r.values.excess_kurtosis,
            r.spectrum.peak_frequency,
            r.spectrum.peak_frequency * m.px as f64,
            r.spectrum.octave_around_peak,
            r.spectrum.below_quarter_peak,
            r.anisotropy.excess_db,
            r.axis.axis_ratio,
            num(l.and_then(|l| l.node_value_score), 3),
            num(l.and_then(|l| l.folded_variance.as_ref().map(|f| f.folded_variance_cv)), 3),
            c2,
            r.cyclostationarity.cyclo_max_over_null,
            flags(r, seeds).join(", "),
        );
    }
    let _ = writeln!(
        s,
        "\nFlags (thresholds from the quality note, in units of each metric's null sd where it has one): \
         *lattice lines* — cyclostationarity max/null > 2; *anisotropic* — anisotropy more than 3 null sd above \
         isotropic; *axes depleted* / *axis-aligned* — axis-line ratio more than 3 null sd below / above 1; \
         *C2 jump* — second-derivative jump score > 1 and above twice its value at cell centres; *zero at nodes* — node value score < 0.01; \
         *cell-dependent variance* — folded-variance CV > 2× its iid null."
    );
    let _ = writeln!(
        s,
        "\nThe reference's lattice columns use an arbitrary 16 px grid: it has none, so they show the null.\n"
    );
    let _ = writeln!(s, "## Pictures\n");
    let _ = writeln!(s, "Each noise ({THUMB}×{THUMB} pixels of seed 1) beside the central {THUMB}×{THUMB} bins of its averaged spectrum (log scale, 60 dB).\n");
    let _ = writeln!(s, "| noise | picture | spectrum | reproduce |");
    let _ = writeln!(s, "|---|---|---|---|");
    for m in rows {
        let _ = writeln!(
            s,
            "| {} | ![{0}](quality/{1}.png) | ![spectrum](quality/{1}-spectrum.png) | `{2}` |",
            m.label, m.file, m.command
        );
    }
    s
}
