//! `Accuracy::Fast` grid fills: within 1e-6 (absolute) of the exact fill
//! for every lattice kind and dimension and for fractals of them, on grids
//! whose cells hold many points and few; exact for the other kinds.

use noiselab::grid::fill_grid_at;
use noiselab::{
    Accuracy, Axes, Classic, Fractal, FractalMode, Grid, Improved, ImprovedVariant, Modified, ModifiedHash,
    ModifiedTexture, Noise, SimdLevel, Simplex, Span, Stores, Value, Worley,
};

/// The documented bound.
const BOUND: f32 = 1e-6;

fn grids<const D: usize>() -> Vec<Grid<D>> {
    let size = |x: usize, rest: usize| core::array::from_fn(|d| if d == 0 { x } else { rest });
    let rest = match D {
        1 => 1,
        2 => 40,
        _ => 6,
    };
    let mut grids = vec![
        Grid::new([0.0; D], [1.0 / 32.0; D], size(300, rest)),
        Grid::new([-3.7; D], [1.0 / 7.0; D], size(200, rest)),
        Grid::new([11.3; D], [0.3; D], size(150, rest)),
        Grid::new([-250.5; D], [1.3; D], size(90, rest)),
        Grid::new([5.0; D], [-0.045; D], size(120, rest)),
        Grid::new([1000.25; D], [1.0 / 64.0; D], size(260, rest)),
        // Cells narrower than AVX2's and AVX-512's lanes along axis 0 and
        // tall enough for bands along axis 1 (in 3D and 4D as well).
        Grid::new([0.13; D], [0.25; D], core::array::from_fn(|d| [130, 40, 3, 2][d])),
        // Tiles: rows of one to four whole chunks (of 8 or 16 lanes) inside
        // one cell, whose bands are written with the chunks' coefficients
        // held; and across cells narrower than the lanes, whose lattice
        // points fit in a register: filled exactly, the points held.
        Grid::new([2.0; D], [1.0 / 32.0; D], size(32, rest)),
        Grid::new([1.0; D], [1.0 / 16.0; D], size(32, rest)),
        Grid::new([-1.0; D], [0.25; D], size(16, rest)),
        // A 2D grid inside one cell (40 rows at 1/64), which takes the
        // one-cell tile's fill on AVX2 and AVX-512 (four and two chunks).
        Grid::new([2.0; D], [1.0 / 64.0; D], size(32, rest)),
    ];
    if D == 2 {
        // Rows wider than a band's block of columns (512), ending in an
        // odd chunk and a partial one after the last pair on both AVX2
        // (139 whole chunks of 8, then 4 columns) and AVX-512 (69 of 16,
        // then 12). Fractals fill it in two strips of 560 and 556.
        grids.push(Grid::new([2.0; D], [1.0 / 32.0; D], size(1116, 8)));
        // Rows over 512 columns of cells narrower than the lanes: five rows
        // a cell (bands on AVX2, exact rows on AVX-512) and ten (bands on
        // both).
        grids.push(Grid::new([0.13; D], core::array::from_fn(|d| [0.25, 0.2][d]), size(530, 10)));
        grids.push(Grid::new([0.13; D], core::array::from_fn(|d| [0.25, 0.1][d]), size(530, 20)));
    }
    grids
}

// Out of line (as every generic helper here): inlined, each test's helpers
// made one huge function that LLVM compiles on one core.
/// The largest |fast − exact| over the grids, at every instruction-set level.
#[inline(never)]
fn worst<N: Noise<D>, const D: usize>(noise: &N) -> f32 {
    let mut worst = 0f32;
    for grid in grids::<D>() {
        for level in SimdLevel::available() {
            let mut exact = vec![0f32; grid.len()];
            let mut fast = vec![0f32; grid.len()];
            fill_grid_at(level, noise, &grid, &mut exact, Accuracy::Exact).unwrap();
            fill_grid_at(level, noise, &grid, &mut fast, Accuracy::Fast).unwrap();
            for (e, f) in exact.iter().zip(&fast) {
                assert!(e.is_finite() && f.is_finite());
                worst = worst.max((e - f).abs());
            }
        }
    }
    worst
}

macro_rules! within_bound {
    ($($name:expr => $noise:expr, $d:literal;)*) => {{
        let mut report = Vec::new();
        $(
            let w = worst::<_, $d>(&$noise);
            report.push(format!("{} {}D: {:e}", $name, $d, w));
            assert!(w <= BOUND, "{} {}D: fast differs from exact by {:e} > {:e}", $name, $d, w, BOUND);
        )*
        report
    }};
}

#[test]
fn fast_lattice_fills_stay_within_the_bound() {
    let report = within_bound! {
        "improved" => Improved::new(3), 1;
        "improved" => Improved::new(3), 2;
        "improved" => Improved::new(0), 3;
        "improved-2002" => Improved::new(1).with_variant(ImprovedVariant::Original2002), 3;
        "improved" => Improved::new(9), 4;
        "value" => Value::new(1), 1;
        "value" => Value::new(1), 2;
        "value" => Value::new(2), 3;
        "value" => Value::new(3), 4;
        "classic" => Classic::new(0), 1;
        "classic" => Classic::new(4), 2;
        "classic" => Classic::new(0), 3;
        "modified" => Modified::new(5), 2;
        "modified" => Modified::new(5), 3;
        "modified-wide" => Modified::new(5).with_hash(ModifiedHash::Wide), 4;
        "modified-textured" => ModifiedTexture::new(&Modified::new(2)), 3;
        "tiled improved" => Improved::new(2).with_period([5, 3, 0, 0]).unwrap(), 2;
        "fbm improved" => Fractal::new(|o| Improved::new(o.seed), 1, 6, FractalMode::Fbm).unwrap(), 2;
        "fbm improved" => Fractal::new(|o| Improved::new(o.seed), 1, 4, FractalMode::Fbm).unwrap(), 3;
        "ridged value" => Fractal::new(|o| Value::new(o.seed), 1, 5, FractalMode::Ridged).unwrap(), 2;
        "turbulence classic" => Fractal::new(|o| Classic::new(o.seed), 1, 5, FractalMode::Turbulence).unwrap(), 2;
    };
    println!("largest |fast − exact|:\n{}", report.join("\n"));
}

#[test]
fn fast_fills_of_other_kinds_are_exact() {
    let grid = Grid::new([0.3, -1.2], [1.0 / 32.0, 0.07], [100, 30]);
    for level in SimdLevel::available() {
        for (name, exact, fast) in [
            (
                "simplex",
                fill(level, &Simplex::new(3), &grid, Accuracy::Exact),
                fill(level, &Simplex::new(3), &grid, Accuracy::Fast),
            ),
            (
                "worley",
                fill(level, &Worley::new(3), &grid, Accuracy::Exact),
                fill(level, &Worley::new(3), &grid, Accuracy::Fast),
            ),
        ] {
            for (e, f) in exact.iter().zip(&fast) {
                assert_eq!(e.to_bits(), f.to_bits(), "{name} at {level:?}");
            }
        }
    }
}

#[inline(never)]
fn fill<N: Noise<2>>(level: SimdLevel, noise: &N, grid: &Grid<2>, accuracy: Accuracy) -> Vec<f32> {
    let mut out = vec![0f32; grid.len()];
    fill_grid_at(level, noise, grid, &mut out, accuracy).unwrap();
    out
}

/// Fast fills of whole rows that start and end anywhere in a plane or a
/// cell (as parallel tasks cut a grid) give the whole grid's bits: the
/// fill down the columns forms a cell's coefficients the same way however
/// many of its rows a span holds.
#[test]
fn fast_spans_of_whole_rows_equal_the_whole_grid() {
    check_spans(&Improved::new(4), Grid::new([-0.4, 2.1], [1.0 / 32.0, 1.0 / 24.0], [50, 70]));
    check_spans(&Improved::new(4), Grid::new([0.3, -1.0, 0.45], [1.0 / 32.0, 1.0 / 20.0, 0.3], [43, 30, 4]));
    check_spans(&Improved::new(9), Grid::new([5.5, 0.0, -2.0, 0.1], [0.05, 0.04, 0.5, 0.7], [33, 26, 2, 2]));
    // Cells narrower than the lanes (AVX2, AVX-512), five rows each; in
    // rows over 512 columns, ten (which AVX-512 takes in bands from eight).
    check_spans(&Improved::new(4), Grid::new([0.2, -0.7], [0.25, 0.2], [61, 50]));
    check_spans(&Improved::new(4), Grid::new([0.2, -0.7], [0.25, 0.1], [530, 50]));
    check_spans(&Value::new(6), Grid::new([0.1, 0.3, -0.2], [0.25, 0.2, 0.5], [45, 33, 3]));
}

#[inline(never)]
fn check_spans<N: Noise<D>, const D: usize>(noise: &N, grid: Grid<D>) {
    let axes = Axes::of(&grid);
    let nx = grid.size[0];
    let rows = grid.len() / nx;
    for level in SimdLevel::available() {
        let mut whole = vec![0f32; grid.len()];
        fill_grid_at(level, noise, &grid, &mut whole, Accuracy::Fast).unwrap();
        for (first, count) in [(0, rows), (1, 5), (3, 1), (7, rows - 7), (rows / 2 - 3, 9), (rows - 2, 2)] {
            // Streamed stores too, which whole fills take only past 32 MiB.
            for stores in [Stores::Cached, Stores::Streamed] {
                let mut out = vec![0f32; count * nx];
                noise.dispatch_span(
                    level,
                    Span { axes: &axes, start: first * nx, accuracy: Accuracy::Fast, stores },
                    &mut out,
                );
                let expected = &whole[first * nx..(first + count) * nx];
                for (k, (&e, &o)) in expected.iter().zip(&out).enumerate() {
                    assert_eq!(
                        e.to_bits(),
                        o.to_bits(),
                        "{D}D {level:?} {stores:?}, rows {first}+{count}, point {}: {e:e} vs {o:e}",
                        first * nx + k
                    );
                }
            }
        }
    }
}

/// Fast fills of 2D grids inside one cell (tiles: one to four whole chunks
/// a row, 4 to 64 rows), which form their one band in registers, give the
/// bits of the same points in the fast fill of a grid around them over
/// several cells, which takes the general bands, at every level. Some
/// grids here are not one-cell tiles at some level (too many chunks, a
/// row across a cell) and check the fallback.
#[test]
fn fast_tiles_inside_one_cell_equal_a_larger_grid() {
    let tiles = [
        // The benchmark's 32² tiles at 1/32.
        ([2.0, 5.0], [1.0 / 32.0, 1.0 / 32.0], [32, 32]),
        ([-3.0, -1.0], [1.0 / 64.0, 1.0 / 64.0], [64, 64]),
        // Rows not a multiple of the lanes; positions off the lattice lines.
        ([0.25, 7.5], [1.0 / 128.0, 1.0 / 64.0], [16, 20]),
        // The fewest rows that take bands.
        ([11.0, -6.0], [1.0 / 64.0, 1.0 / 16.0], [48, 4]),
        // Descending along axis 0, in cell −1.
        ([-0.5, 3.0], [-1.0 / 128.0, 1.0 / 64.0], [32, 40]),
        ([10000.0, 2.0], [1.0 / 64.0, 1.0 / 64.0], [32, 33]),
        // Across a cell along axis 0, and along axis 1.
        ([0.75, 0.0], [1.0 / 32.0, 1.0 / 32.0], [32, 32]),
        ([1.0, 0.5], [1.0 / 64.0, 1.0 / 32.0], [32, 32]),
    ];
    for (origin, step, size) in tiles {
        check_tile(&Improved::new(4), origin, step, size);
        check_tile(&Improved::new(1).with_variant(ImprovedVariant::Original2002), origin, step, size);
        check_tile(&Improved::new(2).with_period([5, 3, 0, 0]).unwrap(), origin, step, size);
        check_tile(&Classic::new(2), origin, step, size);
        check_tile(&Modified::new(3), origin, step, size);
        check_tile(&Value::new(6), origin, step, size);
    }
}

#[inline(never)]
fn check_tile<N: Noise<2>>(noise: &N, origin: [f64; 2], step: [f64; 2], size: [usize; 2]) {
    // The tile at (32, 32) in a grid of 32 more points on every side
    // (dyadic steps: its coordinates are the tile's exactly).
    const MARGIN: usize = 32;
    let around = Grid::new(
        core::array::from_fn(|d| origin[d] - MARGIN as f64 * step[d]),
        step,
        [size[0] + 2 * MARGIN, size[1] + 2 * MARGIN],
    );
    let tile = Grid::new(origin, step, size);
    for level in SimdLevel::available() {
        let larger = fill(level, noise, &around, Accuracy::Fast);
        let mut out = vec![f32::NAN; tile.len()];
        fill_grid_at(level, noise, &tile, &mut out, Accuracy::Fast).unwrap();
        for (j, row) in out.chunks_exact(size[0]).enumerate() {
            let from = (j + MARGIN) * around.size[0] + MARGIN;
            for (i, (&t, &e)) in row.iter().zip(&larger[from..from + size[0]]).enumerate() {
                assert_eq!(
                    t.to_bits(),
                    e.to_bits(),
                    "{level:?}, tile at {origin:?} step {step:?} size {size:?}, point ({i}, {j}): {t:e} vs {e:e}"
                );
            }
        }
    }
}

/// Fast fills of small 2D tiles (one to four whole chunks a row, up to 64
/// rows), which the library fills in registers whether they lie inside one
/// cell or across several, give the bits of the general fill of the same
/// grid (reached here through streamed stores, which the tiles' path does
/// not take): the same bands where the general fill takes bands, with
/// cells wider than the lanes or narrower, and the same exact rows where
/// it takes exact rows, at every level.
#[test]
fn fast_small_tiles_equal_the_general_fill() {
    let tiles = [
        // A 32² fBm-6 tile's octaves at 1/32.
        ([2.0, 5.0], [1.0 / 32.0, 1.0 / 32.0], [32, 32]),
        ([2.0, 5.0], [1.0 / 16.0, 1.0 / 16.0], [32, 32]),
        ([2.0, 5.0], [1.0 / 8.0, 1.0 / 8.0], [32, 32]),
        ([2.0, 5.0], [1.0 / 4.0, 1.0 / 4.0], [32, 32]),
        ([2.0, 5.0], [1.0 / 2.0, 1.0 / 2.0], [32, 32]),
        // Cells holding whole chunks, across cells on both axes, off the
        // lattice lines; descending along axis 0.
        ([0.75, 0.6], [1.0 / 32.0, 1.0 / 32.0], [32, 40]),
        ([1.0, 0.5], [1.0 / 64.0, 1.0 / 32.0], [64, 32]),
        ([-0.5, 3.0], [-1.0 / 16.0, 1.0 / 64.0], [48, 40]),
        // Four rows a cell: bands; five runs of rows in sixteen: row
        // polynomials (left to the general fill); three rows in one cell.
        ([5.25, -2.0], [1.0 / 16.0, 1.0 / 4.0], [64, 16]),
        ([5.25, -1.9], [1.0 / 16.0, 1.0 / 4.0], [64, 16]),
        ([0.0, 0.0], [1.0 / 32.0, 1.0 / 32.0], [48, 3]),
        // Narrow cells with many rows: within one register of points, or
        // two (AVX-512 at 32 columns, AVX2 at 16), where the general fill
        // takes bands.
        ([0.3, -1.7], [1.0 / 2.0, 1.0 / 8.0], [32, 40]),
        ([0.3, -1.7], [1.0 / 2.0, 1.0 / 8.0], [16, 24]),
        ([0.1, 0.2], [0.75, 1.0 / 8.0], [16, 32]),
        // Each column its own cell (plain loads in the general fill: exact
        // rows), and cells a chunk reaches over two registers.
        ([0.5, 0.0], [1.0, 1.0 / 8.0], [16, 32]),
        ([-0.6, 3.1], [1.5, 1.0 / 8.0], [16, 32]),
        // Far from the origin.
        ([10000.0, -7000.5], [1.0 / 8.0, 1.0 / 16.0], [32, 64]),
    ];
    for (origin, step, size) in tiles {
        let tile = Grid::new(origin, step, size);
        check_general(&Improved::new(4), &tile);
        check_general(&Improved::new(1).with_variant(ImprovedVariant::Original2002), &tile);
        check_general(&Improved::new(2).with_period([5, 3, 0, 0]).unwrap(), &tile);
        check_general(&Classic::new(2), &tile);
        check_general(&Modified::new(3), &tile);
    }
}

#[inline(never)]
fn check_general<N: Noise<2>>(noise: &N, tile: &Grid<2>) {
    let axes = Axes::of(tile);
    for level in SimdLevel::available() {
        let mut general = vec![f32::NAN; tile.len()];
        noise.dispatch_span(
            level,
            Span { axes: &axes, start: 0, accuracy: Accuracy::Fast, stores: Stores::Streamed },
            &mut general,
        );
        let mut out = vec![f32::NAN; tile.len()];
        fill_grid_at(level, noise, tile, &mut out, Accuracy::Fast).unwrap();
        for (k, (&t, &g)) in out.iter().zip(&general).enumerate() {
            let (i, j) = (k % tile.size[0], k / tile.size[0]);
            assert_eq!(t.to_bits(), g.to_bits(), "{level:?}, tile {tile:?}, point ({i}, {j}): {t:e} vs {g:e}");
        }
    }
}
