use noiselab::{Classic, Grid, Improved, Noise, Simplex, Value};
use noiselab_analysis::*;
fn render<N: Noise<3>>(n: &N, p: f64, z: f64) -> Field {
    let g = Grid::new([0.0, 0.0, z], [1.0 / p, 1.0 / p, 1.0], [1024, 1024, 1]);
    let mut out = vec![0f32; 1024 * 1024];
    n.fill_grid(&g, &mut out).unwrap();
    Field::from_f32(1024, 1024, &out).unwrap()
}
fn show(name: &str, fields: &[Field], opts: Options) {
    let r = analyze(fields, &opts).unwrap();
    let l = r.lattice.as_ref();
    println!("{name:>14}: std {:.3} kurt {:.3} fp {:.4} oct {:.3} below {:.4} above {:.1e} anis {:.2}dB angCV {:.3} (null {:.3}) axis {:.3}±{:.3} kx0 {:.3} ky0 {:.3} node {:?} fvcv {:?} c2 {:?}/{:?} cyclo {:.2} lowest {:?} far {:.3} t {:.2}s",
        r.values.std, r.values.excess_kurtosis, r.spectrum.peak_frequency, r.spectrum.octave_around_peak, r.spectrum.below_quarter_peak, r.spectrum.above_four_peak,
        r.anisotropy.excess_db, r.angular.cv, r.angular.null_cv, r.axis.axis_ratio, r.axis.null_sd, r.axis.kx0_ratio, r.axis.ky0_ratio,
        l.and_then(|l| l.node_value_score), l.and_then(|l| l.folded_variance.as_ref().map(|f| f.folded_variance_cv)), l.and_then(|l| l.c2_jump_score), l.and_then(|l| l.c2_reference_score),
        r.cyclostationarity.cyclo_max_over_null, r.cyclostationarity.lowest_line.as_ref().map(|l| (l.period_px, l.angle_deg)), r.far_autocorrelation.max, r.seconds);
}
fn main() {
    let lat = Options { lattice: Some(Lattice { period: 16.0, offset: (0, 0) }), period: None };
    let g: Vec<Field> = (1..=4).map(|s| reference::gaussian_noise(1024, 1024, 3.8, s)).collect();
    show("gauss K1", &g[..1], lat);

    show("gauss K4", &g, lat);
    show("improved z0", &[render(&Improved::new(1), 16.0, 0.0)], lat);
    show("improved z.5", &[render(&Improved::new(1), 16.0, 0.5)], lat);
    show("classic z.5", &[render(&Classic::new(1), 16.0, 0.5)], lat);
    show("value z.5", &[render(&Value::new(1), 16.0, 0.5)], lat);
    show("simplex", &[render(&Simplex::new(1), 24.0, 0.0)], lat);
}
