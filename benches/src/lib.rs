//! Shared workloads for the benchmarks (see `benches/`). Run with
//! `cargo bench --manifest-path benches/Cargo.toml`.

use noiselab::Grid;

/// A `side²` window at 32 pixels per cell, the convention of the
/// performance note.
pub fn window(side: usize) -> Grid<2> {
    Grid::new([0.0, 0.0], [1.0 / 32.0, 1.0 / 32.0], [side, side])
}
