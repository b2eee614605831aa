//! The readable form of a [`Report`]: every figure with what an ideal
//! (isotropic, stationary) noise would give beside it.

use core::fmt::{self, Display, Formatter};

use crate::Report;

/// Writes `name  value  (null: ...)` rows.
fn row(f: &mut Formatter<'_>, name: &str, value: String, null: &str) -> fmt::Result {
    if null.is_empty() {
        writeln!(f, "  {name:<44} {value}")
    } else {
        writeln!(f, "  {name:<44} {value:<14} null: {null}")
    }
}

fn opt(v: Option<f64>, digits: usize) -> String {
    v.map_or_else(|| "–".to_string(), |v| format!("{v:.digits$}"))
}

impl Display for Report {
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        let k = self.fields;
        writeln!(
            f,
            "{}×{} pixels, {} field{} (periodograms averaged), analysed in {:.2} s",
            self.width,
            self.height,
            k,
            if k == 1 { "" } else { "s" },
            self.seconds
        )?;
        let v = &self.values;
        writeln!(f, "values")?;
        row(f, "mean / std", format!("{:.4} / {:.4}", v.mean, v.std), "")?;
        row(f, "min / max", format!("{:.4} / {:.4}", v.min, v.max), "")?;
        row(f, "skewness", format!("{:.3}", v.skewness), "0 (symmetric)")?;
        row(f, "excess kurtosis", format!("{:.3}", v.excess_kurtosis), "0 (normal)")?;
        row(f, "share with |v| > 1", format!("{:.2e}", v.fraction_outside_unit), "0 (documented range)")?;

        let s = &self.spectrum;
        writeln!(f, "spectrum")?;
        let cells = s.peak_cycles_per_cell.map_or(String::new(), |c| format!(" ({c:.3} cycles/cell)"));
        row(f, "peak frequency (cycles/pixel)", format!("{:.4}{cells}", s.peak_frequency), "")?;
        row(f, "log-frequency centroid", format!("{:.4}", s.log_centroid_frequency), "")?;
        row(
            f,
            "energy in the octave around the peak",
            format!("{:.3}", s.octave_around_peak),
            "0.471 (Gaussian-filtered white noise)",
        )?;
        row(f, "energy below peak/4", format!("{:.4}", s.below_quarter_peak), "0.061 (Gaussian)")?;
        row(f, "energy above 4×peak", format!("{:.1e}", s.above_four_peak), "1.1e-7 (Gaussian)")?;
        row(
            f,
            "best octave",
            format!("[{:.4}, {:.4}] holds {:.3}", s.best_octave_low, 2.0 * s.best_octave_low, s.best_octave_fraction),
            "",
        )?;

        writeln!(f, "isotropy")?;
        let a = &self.anisotropy;
        row(
            f,
            "anisotropy, peak octave (dB over isotropic)",
            format!("{:+.2}", a.excess_db),
            &format!("0 ± {:.2} dB", 10.0 / core::f64::consts::LN_10 * a.peak_octave_linear_null_std * k as f64),
        )?;
        let g = &self.angular;
        row(f, "angular power max/min (16 sectors)", format!("{:.3}", g.max_over_min), "")?;
        row(f, "angular CV", format!("{:.4}", g.cv), &format!("{:.4}", g.null_cv))?;
        row(
            f,
            "axis / diagonal sectors",
            format!("{:.3} / {:.3}", g.axis_sector_ratio, g.diagonal_sector_ratio),
            "1 / 1",
        )?;
        let x = &self.axis;
        row(
            f,
            "axis-line ratio (kx=0 and ky=0 lines)",
            format!("{:.3} (z {:+.1})", x.axis_ratio, x.z),
            &format!("1 ± {:.3}", x.null_sd),
        )?;
        row(
            f,
            "kx=0 / ky=0 / diagonal lines",
            format!("{:.3} / {:.3} / {:.3}", x.kx0_ratio, x.ky0_ratio, x.diagonal_ratio),
            "1 / 1 / 1",
        )?;

        if let Some(l) = &self.lattice {
            writeln!(
                f,
                "lattice ({} px per cell, node at {:?}{})",
                l.period_px,
                l.offset,
                if l.exact { "" } else { ", not exact: node metrics skipped" }
            )?;
            row(
                f,
                "node value score (std at nodes / std)",
                opt(l.node_value_score, 4),
                "1 (stationary); gradient noise 0 on lattice planes",
            )?;
            row(f, "node rms / max |v|", format!("{} / {}", opt(l.node_rms, 4), opt(l.node_max_abs, 4)), "")?;
            if let Some(fv) = &l.folded_variance {
                row(
                    f,
                    "folded variance CV",
                    format!("{:.4}", fv.folded_variance_cv),
                    &format!("≤ {:.4} (iid)", fv.null_cv),
                )?;
                row(
                    f,
                    "folded variance min / max / at node",
                    format!("{:.3} / {:.3} / {:.3}", fv.min, fv.max, fv.at_node),
                    "1 / 1 / 1",
                )?;
            }
            let reference = l.c2_reference_score.map_or("–".into(), |r| format!("{r:.4} (same at cell centres)"));
            row(f, "second-derivative jump at cell faces", opt(l.c2_jump_score, 4), &reference)?;
        }
        let c = &self.cyclostationarity;
        writeln!(f, "lattice detectors (blind)")?;
        row(
            f,
            "cyclostationarity: max line / null",
            format!("{:.2}", c.cyclo_max_over_null),
            &format!("1 (null max {:.1} over {} bins)", c.null_expected_max, c.bins),
        )?;
        row(f, "lines above 3× null", c.lines_above_3x_null.to_string(), "0")?;
        if let Some(line) = &c.lowest_line {
            row(f, "lowest line", format!("period {:.2} px at {:.0}°", line.period_px, line.angle_deg), "")?;
        }
        if let Some(p) = c.axis_period_estimate_px {
            row(f, "axis period estimate (px)", format!("{p:.2}"), "")?;
        }
        if let Some(r) = c.at_lattice_frequency {
            row(f, "line at the lattice frequency (bin / ring mean)", format!("{r:.1}"), "≈ 3")?;
        }
        let fa = &self.far_autocorrelation;
        row(
            f,
            "far autocorrelation (lag ≥ 4/peak)",
            format!("{:.3} at {:?}", fa.max, fa.lag),
            "0.03–0.1; 1 if it repeats",
        )?;
        if let Some(p) = &self.periodicity {
            writeln!(f, "periodicity ({} px)", p.period_px)?;
            for (axis, a) in [("x", &p.x), ("y", &p.y)] {
                if let Some(a) = a {
                    row(
                        f,
                        &format!("{axis}: max |v(p + T) − v(p)|, rms ratio"),
                        format!("{:.2e}, {:.3}", a.max_abs_diff, a.rms_ratio),
                        "0 periodic; ≈ 1 unrelated",
                    )?;
                }
            }
        }
        Ok(())
    }
}
