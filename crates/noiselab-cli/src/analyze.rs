//! `noiselab analyze`: the quality report of one or more noise images.

use std::path::Path;

use noiselab_analysis::{analyze, io, plots, Lattice, Options, Report};

use crate::AnalyzeArgs;

pub fn run(args: &AnalyzeArgs) -> Result<(), String> {
    let fields = args
        .files
        .iter()
        .map(|path| io::read_field(path, args.size).map_err(|e| e.to_string()))
        .collect::<Result<Vec<_>, _>>()?;
    let options = Options {
        lattice: args.lattice.map(|period| Lattice { period, offset: args.lattice_offset }),
        period: args.period,
    };
    let report = analyze(&fields, &options).map_err(|e| e.to_string())?;
    if let Some(dir) = &args.plots {
        write_plots(dir, &report)?;
    }
    if args.json {
        let text =
            serde_json::to_string_pretty(&report).map_err(|e| format!("cannot encode the report as JSON: {e}"))?;
        println!("{text}");
    } else {
        print!("{report}");
    }
    Ok(())
}

/// The four pictures of a report, into `dir` (created if missing).
pub fn write_plots(dir: &Path, report: &Report) -> Result<(), String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: cannot create the plot folder: {e}", dir.display()))?;
    let fail = |name: &str, e: std::io::Error| format!("{}: {e}", dir.join(name).display());
    plots::power_spectrum(&dir.join("spectrum.png"), report.width, report.height, &report.power)
        .map_err(|e| fail("spectrum.png", e))?;
    let profile: Vec<(f64, f64)> = report.spectrum.radial_log_binned.iter().map(|b| (b.frequency, b.psd)).collect();
    plots::radial_profile(&dir.join("radial.png"), &profile).map_err(|e| fail("radial.png", e))?;
    plots::histogram(&dir.join("histogram.png"), &report.pooled_values, report.values.mean, report.values.std)
        .map_err(|e| fail("histogram.png", e))?;
    if let Some(fv) = report.lattice.as_ref().and_then(|l| l.folded_variance.as_ref()) {
        let period = (fv.map.len() as f64).sqrt().round() as usize;
        plots::folded_variance(&dir.join("folded-variance.png"), period, &fv.map)
            .map_err(|e| fail("folded-variance.png", e))?;
    }
    Ok(())
}
