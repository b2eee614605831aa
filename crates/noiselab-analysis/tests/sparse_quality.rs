//! Sparse convolution noise is free of lattice artefacts where improved
//! noise is not (Frisvad & Wyvill 2007), measured as the quality note says:
//! 1024² slices at 32 px per cell, 4 seeds.

use noiselab::{Grid, Improved, Kernel, Noise, Sparse};
use noiselab_analysis::{analyze, Field, Lattice, Options, Report};

const SIDE: usize = 1024;
const PX: f64 = 32.0;

fn slice(z: f64) -> Grid<3> {
    Grid::new([0.0, 0.0, z], [1.0 / PX, 1.0 / PX, 0.0], [SIDE, SIDE, 1])
}

fn measure(render: impl Fn(u32, &mut [f32])) -> Report {
    let fields: Vec<Field> = (1..=4)
        .map(|seed| {
            let mut out = vec![0f32; SIDE * SIDE];
            render(seed, &mut out);
            Field::from_f32(SIDE, SIDE, &out).unwrap()
        })
        .collect();
    analyze(&fields, &Options { lattice: Some(Lattice { period: PX, offset: (0, 0) }), period: None }).unwrap()
}

fn sparse(kernel: Kernel, z: f64) -> Report {
    measure(|seed, out| Sparse::new(seed).with_kernel(kernel.clone()).splat_grid(&slice(z), out).unwrap())
}

#[test]
fn sparse_convolution_shows_no_lattice_and_improved_noise_does() {
    for z in [0.0, 0.5] {
        let s = sparse(Kernel::cubic(), z);
        let i = measure(|seed, out| Improved::new(seed).fill_grid(&slice(z), out).unwrap());
        let (sl, il) = (s.lattice.as_ref().unwrap(), i.lattice.as_ref().unwrap());
        let (sf, jf) = (sl.folded_variance.as_ref().unwrap(), il.folded_variance.as_ref().unwrap());
        eprintln!(
            "z = {z}: sparse cyclo {:.2} folded CV {:.4} (null {:.4}) node {:.3}; improved cyclo {:.1} folded CV {:.3}",
            s.cyclostationarity.cyclo_max_over_null,
            sf.folded_variance_cv,
            sf.null_cv,
            sl.node_value_score.unwrap(),
            i.cyclostationarity.cyclo_max_over_null,
            jf.folded_variance_cv
        );
        assert!(
            s.cyclostationarity.cyclo_max_over_null <= 1.3,
            "sparse cyclo {}",
            s.cyclostationarity.cyclo_max_over_null
        );
        assert!(sf.folded_variance_cv <= 0.03, "sparse folded CV {}", sf.folded_variance_cv);
        assert!((sl.node_value_score.unwrap() - 1.0).abs() < 0.1, "sparse node score {:?}", sl.node_value_score);
        assert!(
            i.cyclostationarity.cyclo_max_over_null >= 8.0,
            "improved cyclo {}",
            i.cyclostationarity.cyclo_max_over_null
        );
        assert!(jf.folded_variance_cv >= 0.08, "improved folded CV {}", jf.folded_variance_cv);
    }
}

#[test]
fn cubic_kernel_spectrum_is_close_to_the_gaussian_reference() {
    let cubic = sparse(Kernel::cubic(), 0.25);
    let gauss = sparse(Kernel::gaussian(), 0.25);
    // The 1/3-octave bands holding the central 95 % of the cubic's energy.
    let bands = &cubic.spectrum.radial_log_binned;
    let mut cumulative = 0.0;
    let mut worst: f64 = 0.0;
    for (c, g) in bands.iter().zip(&gauss.spectrum.radial_log_binned) {
        let before = cumulative;
        cumulative += c.energy_fraction;
        if before >= 0.025 && cumulative <= 0.975 {
            let ratio = c.psd / g.psd;
            eprintln!("f = {:.4}: cubic/gaussian = {ratio:.3}", c.frequency);
            worst = worst.max((ratio - 1.0).abs());
        }
    }
    eprintln!("worst deviation {worst:.3}");
    assert!(worst <= 0.10, "cubic and Gaussian spectra differ by {worst}");
}
