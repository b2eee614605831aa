//! Frisvad & Wyvill's Figure 1 pair: sparse convolution noise at 512²,
//! 16 kernels across (32 px per cell = kernel diameter), (a) with the
//! Gaussian reference kernel and (b) with the cubic kernel, written as
//! binary PGM images (any image viewer opens them) with the render times.
//!
//! `cargo run --release -p noiselab --example sparse_figure1 [OUT_DIR]`

use std::io::Write;
use std::time::Instant;

use noiselab::{Grid, Kernel, Sparse};

fn main() -> std::io::Result<()> {
    let dir = std::path::PathBuf::from(std::env::args().nth(1).unwrap_or_else(|| ".".into()));
    std::fs::create_dir_all(&dir)?;
    let side = 512;
    let grid = Grid::new([0.0, 0.0], [1.0 / 32.0; 2], [side, side]);
    for (name, kernel) in [("figure1a-gaussian", Kernel::gaussian()), ("figure1b-cubic", Kernel::cubic())] {
        let noise = Sparse::new(0).with_impulses(30).expect("30 impulses is valid").with_kernel(kernel);
        let mut values = vec![0f32; side * side];
        let start = Instant::now();
        noise.splat_grid(&grid, &mut values).expect("the buffer matches the grid");
        let seconds = start.elapsed().as_secs_f64();
        // Standard deviation ¼: map ±4σ onto black..white.
        let pixels: Vec<u8> = values.iter().map(|v| ((v + 1.0) * 127.5).clamp(0.0, 255.0) as u8).collect();
        let path = dir.join(format!("{name}.pgm"));
        let mut file = std::io::BufWriter::new(std::fs::File::create(&path)?);
        write!(file, "P5\n{side} {side}\n255\n")?;
        file.write_all(&pixels)?;
        println!("{}: {seconds:.4} s", path.display());
    }
    Ok(())
}
