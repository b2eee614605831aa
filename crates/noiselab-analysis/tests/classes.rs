//! The classes of noise the literature predicts, pinned by the metrics
//! (expected values from docs/quality-metrics.md's validation table).

use noiselab::{Classic, Grid, Improved, Noise, Value};
use noiselab_analysis::{analyze, reference, AnalysisError, Field, Lattice, Options};

/// `size²` pixels of a 3D noise's z-slice at `px` pixels per cell, with a
/// node on pixel (0, 0).
fn render<N: Noise<3>>(noise: &N, size: usize, px: f64, z: f64) -> Field {
    let grid = Grid::new([0.0, 0.0, z], [1.0 / px, 1.0 / px, 1.0], [size, size, 1]);
    let mut out = vec![0f32; size * size];
    noise.fill_grid(&grid, &mut out).unwrap();
    Field::from_f32(size, size, &out).unwrap()
}

fn lattice(px: f64) -> Options {
    Options { lattice: Some(Lattice { period: px, offset: (0, 0) }), period: None }
}

#[test]
fn gradient_noise_is_zero_at_nodes_and_value_noise_is_not() {
    let improved = analyze(&[render(&Improved::new(3), 512, 16.0, 0.0)], &lattice(16.0)).unwrap();
    let l = improved.lattice.unwrap();
    assert_eq!(l.node_value_score, Some(0.0));
    assert_eq!(l.node_max_abs, Some(0.0));
    // Between lattice planes the nodes are ordinary points.
    let between = analyze(&[render(&Improved::new(3), 512, 16.0, 0.5)], &lattice(16.0)).unwrap();
    let score = between.lattice.unwrap().node_value_score.unwrap();
    assert!((0.85..1.15).contains(&score), "{score}");
    // Value noise's nodes hold its extremes: more spread than elsewhere.
    let value = analyze(&[render(&Value::new(3), 512, 16.0, 0.5)], &lattice(16.0)).unwrap();
    let score = value.lattice.unwrap().node_value_score.unwrap();
    assert!(score > 1.15, "{score}");
}

#[test]
fn cubic_fade_jumps_in_the_second_derivative_and_quintic_does_not() {
    let classic = analyze(&[render(&Classic::new(2), 512, 16.0, 0.5)], &lattice(16.0)).unwrap();
    let l = classic.lattice.unwrap();
    let (jump, reference) = (l.c2_jump_score.unwrap(), l.c2_reference_score.unwrap());
    assert!(jump > 1.5 && reference < 0.01, "cubic: {jump} (reference {reference})");
    let improved = analyze(&[render(&Improved::new(2), 512, 16.0, 0.5)], &lattice(16.0)).unwrap();
    let jump = improved.lattice.unwrap().c2_jump_score.unwrap();
    assert!(jump < 0.1, "quintic: {jump}");
}

#[test]
fn folded_variance_shows_the_lattice_and_not_a_stationary_noise() {
    let improved = analyze(&[render(&Improved::new(4), 1024, 16.0, 0.0)], &lattice(16.0)).unwrap();
    let fv = improved.lattice.unwrap().folded_variance.unwrap();
    assert!((0.35..0.47).contains(&fv.folded_variance_cv), "improved z=0: {}", fv.folded_variance_cv);
    let gauss = analyze(&[reference::gaussian_noise(1024, 1024, 3.8, 4)], &lattice(16.0)).unwrap();
    let fv = gauss.lattice.unwrap().folded_variance.unwrap();
    assert!(fv.folded_variance_cv < 1.2 * fv.null_cv, "gauss: {} (null {})", fv.folded_variance_cv, fv.null_cv);
}

#[test]
fn lattice_noises_light_the_cyclostationarity_detector_and_filtered_white_noise_does_not() {
    for (name, field) in [
        ("improved z=0", render(&Improved::new(5), 1024, 16.0, 0.0)),
        ("improved z=0.5", render(&Improved::new(5), 1024, 16.0, 0.5)),
        ("classic z=0.5", render(&Classic::new(5), 1024, 16.0, 0.5)),
        ("value z=0.5", render(&Value::new(5), 1024, 16.0, 0.5)),
    ] {
        let r = analyze(&[field], &Options::default()).unwrap();
        let c = r.cyclostationarity;
        assert!(c.cyclo_max_over_null > 5.0, "{name}: {}", c.cyclo_max_over_null);
        // The lattice's own frequency, found blind: 16 px or a harmonic.
        let period = c.lowest_line.unwrap().period_px;
        assert!(
            [16.0, 8.0, 16.0 / 2f64.sqrt(), 8.0 / 2f64.sqrt()].iter().any(|p| (period / p - 1.0).abs() < 0.03),
            "{name}: {period}"
        );
    }
    for seed in 1..=2 {
        let r = analyze(&[reference::gaussian_noise(1024, 1024, 3.8, seed)], &Options::default()).unwrap();
        let c = r.cyclostationarity;
        assert!(c.cyclo_max_over_null < 1.3, "gauss: {}", c.cyclo_max_over_null);
        assert_eq!(c.lines_above_3x_null, 0);
    }
}

#[test]
fn a_tiled_render_has_periodicity_zero() {
    // Perlin's permutation repeats every 256 cells: at 2 px per cell the
    // field repeats every 512 px, exactly; one pixel off it does not.
    let field = render(&Improved::new(0), 1024, 2.0, 0.5);
    let tiled = analyze(std::slice::from_ref(&field), &Options { lattice: None, period: Some(512) }).unwrap();
    let p = tiled.periodicity.unwrap();
    assert_eq!(p.x.unwrap().max_abs_diff, 0.0);
    assert_eq!(p.y.unwrap().max_abs_diff, 0.0);
    assert!(tiled.far_autocorrelation.max > 0.999, "{:?}", tiled.far_autocorrelation);
    let off = analyze(&[field], &Options { lattice: None, period: Some(511) }).unwrap();
    let x = off.periodicity.unwrap().x.unwrap();
    assert!(x.rms_ratio > 0.5, "{}", x.rms_ratio);
}

#[test]
fn filtered_white_noise_matches_its_closed_forms() {
    // σ = 3.8 px: f_p = 1/(2πσ) = 0.0419 cpp, one octave around the peak
    // e^−½ − e^−2 = 0.471, below f_p/4 1 − e^−1/16 = 0.061, above 4 f_p
    // e^−16 = 1.1e-7. Tolerances: twice the seed-to-seed sd of the note.
    let fields: Vec<Field> = (10..14).map(|s| reference::gaussian_noise(1024, 1024, 3.8, s)).collect();
    let r = analyze(&fields, &Options::default()).unwrap();
    let s = &r.spectrum;
    let theory = 1.0 / (2.0 * core::f64::consts::PI * 3.8);
    assert!((s.peak_frequency - theory).abs() < 2.0 * 0.0022, "peak {}", s.peak_frequency);
    assert!((s.octave_around_peak - 0.471).abs() < 2.0 * 0.009, "octave {}", s.octave_around_peak);
    assert!((s.below_quarter_peak - 0.061).abs() < 2.0 * 0.012, "below {}", s.below_quarter_peak);
    assert!(s.above_four_peak < 1e-6, "above {}", s.above_four_peak);
    // Isotropic and stationary: every detector at its null.
    assert!(r.anisotropy.excess_db.abs() < 0.5, "anisotropy {}", r.anisotropy.excess_db);
    assert!((r.axis.axis_ratio - 1.0).abs() < 3.0 * r.axis.null_sd, "axis {:?}", r.axis);
    assert!(r.angular.cv < 2.0 * r.angular.null_cv, "angular {:?}", r.angular);
    assert!(r.far_autocorrelation.max < 0.1, "{:?}", r.far_autocorrelation);
    assert!((r.values.std - 0.25).abs() < 1e-9 && r.values.excess_kurtosis.abs() < 0.1);
}

#[test]
fn improved_noise_at_z0_is_band_limited_and_its_slice_is_not() {
    // Cook & DeRose: a 2D slice of 3D noise gains low-frequency energy.
    let z0 = analyze(&[render(&Improved::new(6), 1024, 16.0, 0.0)], &lattice(16.0)).unwrap();
    let half = analyze(&[render(&Improved::new(6), 1024, 16.0, 0.5)], &lattice(16.0)).unwrap();
    assert!(z0.spectrum.octave_around_peak > 0.6 && z0.spectrum.below_quarter_peak < 0.012, "{:?}", z0.spectrum);
    assert!(half.spectrum.octave_around_peak < 0.56 && half.spectrum.below_quarter_peak > 0.02, "{:?}", half.spectrum);
    let cells = z0.spectrum.peak_cycles_per_cell.unwrap();
    assert!((cells - 0.671).abs() < 0.06, "{cells}");
}

#[test]
fn bad_input_is_a_typed_error() {
    let a = reference::gaussian_noise(64, 64, 2.0, 1);
    let b = reference::gaussian_noise(64, 32, 2.0, 1);
    assert_eq!(analyze(&[], &Options::default()).unwrap_err(), AnalysisError::NoFields);
    assert!(matches!(analyze(&[a.clone(), b], &Options::default()), Err(AnalysisError::SizeMismatch { .. })));
    let flat = Field::new(32, 32, vec![0.5; 1024]).unwrap();
    assert_eq!(analyze(&[flat], &Options::default()).unwrap_err(), AnalysisError::Constant);
    for period in [0.0, -3.0, f64::NAN, f64::INFINITY] {
        let opts = Options { lattice: Some(Lattice { period, offset: (0, 0) }), period: None };
        assert!(matches!(analyze(std::slice::from_ref(&a), &opts), Err(AnalysisError::BadParameter(_))), "{period}");
    }
    let opts = Options { lattice: None, period: Some(0) };
    assert!(matches!(analyze(std::slice::from_ref(&a), &opts), Err(AnalysisError::BadParameter(_))));
    // A non-integer lattice is analysed but marked inexact, without node numbers.
    let opts = Options { lattice: Some(Lattice { period: 10.5, offset: (0, 0) }), period: Some(1000) };
    let r = analyze(&[a], &opts).unwrap();
    let l = r.lattice.unwrap();
    assert!(!l.exact && l.node_value_score.is_none() && l.c2_jump_score.is_none());
    let p = r.periodicity.unwrap();
    assert!(p.x.is_none() && p.y.is_none());
}

#[test]
fn json_report_has_the_documented_fields() {
    let r = analyze(&[render(&Improved::new(1), 256, 16.0, 0.0)], &lattice(16.0)).unwrap();
    let json: serde_json::Value = serde_json::to_value(&r).unwrap();
    let mut names = Vec::new();
    collect_keys(&json, &mut names);
    for key in ["mean", "std", "peak_frequency", "folded_variance_cv", "node_value_score", "cyclo_max_over_null"] {
        assert!(names.iter().any(|n| n == key), "{key} missing");
    }
    let text = r.to_string();
    assert!(text.contains("peak frequency") && text.contains("null"), "{text}");
}

fn collect_keys(v: &serde_json::Value, out: &mut Vec<String>) {
    match v {
        serde_json::Value::Object(map) => {
            for (k, v) in map {
                out.push(k.clone());
                collect_keys(v, out);
            }
        }
        serde_json::Value::Array(items) => items.iter().for_each(|v| collect_keys(v, out)),
        _ => {}
    }
}

#[test]
fn analysing_a_megapixel_takes_well_under_a_second() {
    // Not a timing assertion (those live in benches): the report carries
    // its own time, and this prints it for the log.
    let r = analyze(&[reference::gaussian_noise(1024, 1024, 3.8, 1)], &lattice(16.0)).unwrap();
    eprintln!("1024² analysed in {:.3} s", r.seconds);
    assert!(r.seconds > 0.0);
}
