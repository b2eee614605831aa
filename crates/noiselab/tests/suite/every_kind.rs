//! Properties every kind must have, run over every kind and dimension:
//! batch == scalar f32 bit for bit at every instruction-set level, the
//! documented range, and the special-input contract (NaN, ±∞, huge values).

use noiselab::grid::{fill_grid_at, fill_points_at};
use noiselab::hash::SplitMix64;
use noiselab::{
    Accuracy, Axes, CellOutput, Classic, Fast, Fractal, FractalMode, Grid, GridError, Improved, ImprovedVariant,
    Kernel, Looped, Metric, Modified, ModifiedHash, ModifiedTexture, Noise, SimdLevel, Simplex, SimplexN, Span, Sparse,
    Stores, Value, Warp, Worley,
};

/// Runs `$check!(name, noise, D, (lo, hi))` for every kind, dimension and
/// documented range (the range each type's docs promise).
macro_rules! for_every_kind {
    ($check:ident) => {
        $check!("classic", Classic::new(0), 1, (-0.5, 0.5));
        $check!("classic", Classic::new(5), 2, (-0.71, 0.71));
        $check!("classic", Classic::new(0), 3, (-0.87, 0.87));
        $check!("improved", Improved::new(0), 1, (-0.5, 0.5));
        $check!("improved", Improved::new(3), 2, (-1.0, 1.0));
        $check!("improved", Improved::new(0), 3, (-1.04, 1.04));
        $check!("improved-2002", Improved::new(0).with_variant(ImprovedVariant::Original2002), 3, (-1.04, 1.04));
        $check!("improved", Improved::new(9), 4, (-1.3, 1.3));
        $check!("simplex", Simplex::new(0), 1, (-0.64, 0.64));
        $check!("simplex", Simplex::new(0), 2, (-1.0, 1.0));
        $check!("simplex", Simplex::new(2), 3, (-1.0, 1.0));
        $check!("simplex", Simplex::new(0), 4, (-1.0, 1.0));
        $check!("modified", Modified::new(0), 1, (-0.31, 0.31));
        $check!("modified", Modified::new(0), 2, (-0.61, 0.61));
        $check!("modified", Modified::new(7), 3, (-1.0, 1.0));
        $check!("modified", Modified::new(0), 4, (-1.0, 1.0));
        $check!("modified-wide", Modified::new(3).with_hash(ModifiedHash::Wide), 3, (-1.0, 1.0));
        $check!("modified-wide", Modified::new(3).with_hash(ModifiedHash::Wide), 4, (-1.0, 1.0));
        $check!("modified-textured", ModifiedTexture::new(&Modified::new(2)), 3, (-1.0, 1.0));
        $check!("modified-textured", ModifiedTexture::new(&Modified::new(0)), 4, (-1.0, 1.0));
        $check!("simplex-n", SimplexN::new(0), 2, (-1.0, 1.0));
        $check!("simplex-n", SimplexN::new(1), 3, (-1.0, 1.0));
        $check!("simplex-n", SimplexN::new(0), 5, (-1.0, 1.0));
        $check!("simplex-n", SimplexN::new(4), 6, (-1.0, 1.0));
        $check!("value", Value::new(0), 1, (-1.0, 1.0));
        $check!("value", Value::new(1), 2, (-1.0, 1.0));
        $check!("value", Value::new(0), 3, (-1.0, 1.0));
        $check!("value", Value::new(0), 4, (-1.0, 1.0));
        $check!("looped-improved", Looped::new(Improved::new(2), 2.5).unwrap(), 3, (-1.04, 1.04));
        $check!("warped-value", Warp::new(Value::new(1), Improved::new, 7, 0.8, 0.5).unwrap(), 2, (-1.0, 1.0));
        $check!(
            "warped-improved-x3",
            Warp::new(Improved::new(1), Value::new, 7, 0.8, 0.5).unwrap().iterated(3, 0.5, 2.0).unwrap(),
            3,
            (-1.04, 1.04)
        );
        $check!(
            "fbm-improved",
            Fractal::new(|o| Improved::new(o.seed), 1, 5, FractalMode::Fbm).unwrap(),
            3,
            (-1.04, 1.04)
        );
        $check!(
            "ridged-simplex",
            Fractal::new(|o| Simplex::new(o.seed), 1, 4, FractalMode::Ridged).unwrap(),
            2,
            (0.0, 1.0)
        );
        $check!(
            "hybrid-value",
            Fractal::new(|o| Value::new(o.seed), 1, 4, FractalMode::Hybrid).unwrap(),
            4,
            (-1.5, 1.5)
        );
        $check!("fast", Fast::new(0), 2, (-1.47, 1.47));
        $check!("fast", Fast::new(3), 3, (-1.47, 1.47));
        $check!("worley", Worley::new(0), 1, (0.0, 1.0));
        $check!("worley", Worley::new(2), 2, (0.0, 2f64.sqrt()));
        $check!("worley", Worley::new(0), 3, (0.0, 3f64.sqrt()));
        $check!("worley", Worley::new(0), 4, (0.0, 2.0));
        $check!("worley-f2-f1", Worley::new(1).with_output(CellOutput::F2MinusF1), 2, (0.0, 1.5));
        $check!("worley-cells", Worley::new(1).with_output(CellOutput::CellValue), 3, (-1.0, 1.0));
        $check!(
            "worley-manhattan-f3",
            Worley::new(3).with_metric(Metric::Manhattan).unwrap().with_output(CellOutput::F3),
            2,
            (0.0, 3.0)
        );
        $check!("worley-minkowski", Worley::new(3).with_metric(Metric::Minkowski(3.0)).unwrap(), 2, (0.0, 1.5));
        // Sparse convolution is unbounded (std ¼, tails heavier for few impulses):
        // ±2.5 is ten sigma.
        $check!("sparse", Sparse::new(0), 1, (-1.2, 1.2));
        $check!("sparse", Sparse::new(4), 2, (-2.0, 2.0));
        $check!("sparse", Sparse::new(0).with_impulses(10).unwrap(), 3, (-2.5, 2.5));
        $check!("sparse", Sparse::new(1).with_impulses(6).unwrap(), 4, (-2.5, 2.5));
        $check!(
            "sparse-gaussian",
            Sparse::new(2).with_kernel(Kernel::gaussian()).with_impulses(8).unwrap(),
            2,
            (-2.0, 2.0)
        );
    };
}

/// Points that exercise every branch: lattice nodes, the floats either side of
/// cell borders, negative coordinates, ordinary and large values.
fn probe_points<const D: usize>() -> Vec<[f32; D]> {
    let mut rng = SplitMix64(0x5EED + D as u64);
    let mut uniform = move |lo: f32, hi: f32| lo + (hi - lo) * ((rng.next() >> 40) as f32 / (1u64 << 24) as f32);
    let mut pts = Vec::new();
    for k in -3..=3 {
        let k = k as f32;
        for v in [k, k.next_up(), k.next_down(), k + 0.5, k - 0.25] {
            pts.push([v; D]);
        }
    }
    for _ in 0..3000 {
        let mut p = [0f32; D];
        for c in p.iter_mut() {
            *c = match (uniform(0.0, 1.0) * 4.0) as u32 {
                0 => uniform(-300.0, 300.0),
                1 => uniform(-2.0, 2.0),
                2 => {
                    // A cell border, approached from either side.
                    let k = uniform(-50.0, 50.0).round();
                    if uniform(0.0, 1.0) < 0.5 {
                        k.next_up()
                    } else {
                        k.next_down()
                    }
                }
                _ => -uniform(0.0, 1000.0),
            };
        }
        pts.push(p);
    }
    pts
}

fn same(a: f32, b: f32) -> bool {
    a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
}

// Out of line (as every generic helper here): inlined, each test's helpers
// made one huge function that LLVM compiles on one core.
#[inline(never)]
fn check_batch<N: Noise<D>, const D: usize>(name: &str, noise: &N) {
    let pts = probe_points::<D>();
    let scalar: Vec<f32> = pts.iter().map(|&p| noise.get_f32(p)).collect();
    for level in SimdLevel::available() {
        let mut out = vec![0f32; pts.len()];
        fill_points_at(level, noise, &pts, &mut out).unwrap();
        for (i, (&s, &b)) in scalar.iter().zip(&out).enumerate() {
            assert!(same(s, b), "{name} {D}D {level:?}: point {:?}: scalar {s:e} batch {b:e}", pts[i]);
        }
        for grid in probe_grids::<D>() {
            let mut out = vec![0f32; grid.len()];
            fill_grid_at(level, noise, &grid, &mut out, Accuracy::Exact).unwrap();
            for (i, &b) in out.iter().enumerate() {
                let s = noise.get_f32(grid.point(i));
                assert!(
                    same(s, b),
                    "{name} {D}D {level:?}: grid {grid:?} point {:?}: scalar {s:e} batch {b:e}",
                    grid.point(i)
                );
            }
        }
    }
    // Spans that start and end mid-row, as parallel chunks do, at every
    // level, through the fills' own drivers (calling `fill_span` on lane
    // types here compiled every kind's batch code once more: about a third
    // of this test binary's machine code).
    let grid = Grid::new([-1.3; D], [0.03125; D], core::array::from_fn(|d| if d == 0 { 75 } else { 3 }));
    let axes = Axes::of(&grid);
    for level in SimdLevel::available() {
        for (start, len) in [(0, grid.len()), (7, 100), (74, 2), (76, 150), (grid.len() - 9, 9)] {
            if start >= grid.len() {
                continue;
            }
            let len = len.min(grid.len() - start);
            // Streamed stores too, which whole fills take only past 32 MiB.
            for stores in [Stores::Cached, Stores::Streamed] {
                let mut out = vec![0f32; len];
                noise.dispatch_span(level, Span { axes: &axes, start, accuracy: Accuracy::Exact, stores }, &mut out);
                for (k, &b) in out.iter().enumerate() {
                    let s = noise.get_f32(grid.point(start + k));
                    assert!(
                        same(s, b),
                        "{name} {D}D {level:?} {stores:?} span {start}+{len}, point {}: scalar {s:e}, batch {b:e}",
                        start + k
                    );
                }
            }
        }
    }
}

/// Streamed stores (`Stores::Streamed`, which whole fills take from 32 MiB
/// on) give the cached fill's bits on every path that streams: batches of
/// rows (few cells a row), rows of many cells, bands (fast, cells holding
/// many rows; staged, or streamed from registers where chunks start at
/// multiples of the lanes), value noise's plane blends and fast rows
/// (cells holding few), exact and fast, at every level, into outputs at
/// every offset from a register boundary, and write nothing outside the
/// output.
#[test]
fn streamed_stores_give_the_cached_bits() {
    let grids = [
        Grid::new([-1.3, 0.2], [1.0 / 32.0, 1.0 / 32.0], [75, 40]),
        Grid::new([-40.3, 0.2], [0.05, 0.09], [1300, 4]),
        Grid::new([0.3, -1.0], [1.0 / 32.0, 0.4], [43, 9]),
        // Chunk k at column k · lanes: fast bands stream from registers,
        // in one block of columns and in two.
        Grid::new([0.0, 0.3], [1.0 / 32.0, 1.0 / 32.0], [160, 40]),
        Grid::new([0.0, 0.3], [1.0 / 32.0, 1.0 / 32.0], [544, 9]),
    ];
    for grid in &grids {
        check_streamed(&Improved::new(3), grid);
        check_streamed(&Classic::new(5), grid);
        check_streamed(&Modified::new(7), grid);
        check_streamed(&Value::new(2), grid);
    }
    let grids = [
        Grid::new([-1.3, 0.2, 0.4], [1.0 / 32.0, 1.0 / 16.0, 0.3], [70, 20, 3]),
        Grid::new([-20.3, 0.2, 5.0], [0.05, 0.3, 0.5], [700, 3, 2]),
        Grid::new([0.0, 0.2, 0.4], [1.0 / 32.0, 1.0 / 16.0, 0.3], [112, 20, 2]),
    ];
    for grid in &grids {
        check_streamed(&Improved::new(3), grid);
        check_streamed(&Classic::new(0), grid);
        check_streamed(&Modified::new(1), grid);
        check_streamed(&Value::new(4), grid);
    }
    check_streamed(
        &Improved::new(3),
        &Grid::new([-1.3, 0.2, 0.4, 0.1], [1.0 / 16.0, 1.0 / 16.0, 0.3, 0.5], [40, 18, 2, 2]),
    );
}

#[inline(never)]
fn check_streamed<N: Noise<D>, const D: usize>(noise: &N, grid: &Grid<D>) {
    let axes = Axes::of(grid);
    let n = grid.len();
    for level in SimdLevel::available() {
        for accuracy in [Accuracy::Exact, Accuracy::Fast] {
            let mut cached = vec![0f32; n];
            noise.dispatch_span(level, Span { axes: &axes, start: 0, accuracy, stores: Stores::Cached }, &mut cached);
            for offset in [0, 1, 3, 4, 7, 8, 15] {
                let mut buf = vec![f32::NAN; n + 16];
                noise.dispatch_span(
                    level,
                    Span { axes: &axes, start: 0, accuracy, stores: Stores::Streamed },
                    &mut buf[offset..offset + n],
                );
                for (k, (&c, &s)) in cached.iter().zip(&buf[offset..]).enumerate() {
                    assert_eq!(
                        c.to_bits(),
                        s.to_bits(),
                        "{D}D {grid:?} {level:?} {accuracy:?} offset {offset}, point {k}: {c:e} vs {s:e}"
                    );
                }
                assert!(
                    buf[..offset].iter().chain(&buf[offset + n..]).all(|v| v.is_nan()),
                    "{D}D {grid:?} {level:?} {accuracy:?} offset {offset}: a store outside the output"
                );
            }
        }
    }
}

/// Value noise's plane blends store whole registers of memory from the
/// first column on a register boundary (one chunk before it), so each
/// offset of the output from a boundary splits its rows differently:
/// every offset, at every level, gives `get_f32`'s bits and writes nothing
/// outside the output. Rows of a multiple of the lanes share their offset;
/// the others fall back to chunks from the first column.
#[test]
fn plane_blends_at_every_output_offset_give_the_point_bits() {
    check_offsets(&Value::new(2), &Grid::new([0.0, 0.3], [1.0 / 32.0, 1.0 / 16.0], [96, 33]));
    check_offsets(&Value::new(2), &Grid::new([-1.3, 0.2], [1.0 / 32.0, 1.0 / 32.0], [75, 40]));
    check_offsets(&Value::new(5), &Grid::new([-7.1, 0.2], [1.0 / 20.0, 1.0 / 8.0], [48, 20]));
    check_offsets(&Value::new(7), &Grid::new([0.4, 0.2, -0.3], [1.0 / 32.0, 1.0 / 16.0, 0.25], [64, 20, 3]));
    check_offsets(&Value::new(7), &Grid::new([0.4, 0.2, -0.3], [1.0 / 32.0, 1.0 / 16.0, 0.25], [37, 20, 2]));
}

#[inline(never)]
fn check_offsets<N: Noise<D>, const D: usize>(noise: &N, grid: &Grid<D>) {
    let n = grid.len();
    let want: Vec<f32> = (0..n).map(|i| noise.get_f32(grid.point(i))).collect();
    for level in SimdLevel::available() {
        for offset in 0..16 {
            let mut buf = vec![f32::NAN; n + 32];
            let start = buf.as_ptr().align_offset(64) + offset;
            fill_grid_at(level, noise, grid, &mut buf[start..start + n], Accuracy::Exact).unwrap();
            for (k, (&w, &v)) in want.iter().zip(&buf[start..]).enumerate() {
                assert_eq!(
                    w.to_bits(),
                    v.to_bits(),
                    "{D}D {grid:?} {level:?} offset {offset}, point {k}: {w:e} vs {v:e}"
                );
            }
            assert!(
                buf[..start].iter().chain(&buf[start + n..]).all(|v| v.is_nan()),
                "{D}D {grid:?} {level:?} offset {offset}: a store outside the output"
            );
        }
    }
}

/// Grids that exercise the batch drivers' cases: runs of one cell longer and
/// shorter than the lanes, rows not a multiple of the lane width, negative
/// and zero steps, cell borders, negative and far coordinates.
pub(crate) fn probe_grids<const D: usize>() -> Vec<Grid<D>> {
    let size = |x: usize, rest: usize| core::array::from_fn(|d| if d == 0 { x } else { rest });
    let rest = if D > 2 { 3 } else { 5 };
    // Axes 0 and 1, then the same for every axis past them.
    fn axes<T: Copy, const D: usize>(v: [T; 3]) -> [T; D] {
        core::array::from_fn(|d| v[d.min(2)])
    }
    vec![
        Grid::new([-2.125; D], [0.0625; D], size(37, rest)),
        Grid::new([0.0; D], [1.0 / 32.0; D], size(70, rest)),
        Grid::new([3.3; D], [0.7; D], size(41, rest)),
        // One cell per column: each lane in the next cell.
        Grid::new([-3.37; D], [1.0; D], size(45, rest)),
        Grid::new([1.0; D], [-0.015625; D], size(130, 2)),
        Grid::new([0.5; D], [0.0; D], size(19, 2)),
        Grid::new([-70000.37; D], [0.11; D], size(40, 2)),
        Grid::new([123456.0; D], [1.0 / 48.0; D], size(100, 2)),
        // Across ±2²¹, where simplex grids stop taking their cells from one
        // rounding conversion, and just inside it.
        Grid::new([2097150.0; D], [0.125; D], size(40, 2)),
        Grid::new([-2097151.0; D], [0.0625; D], size(16, 2)),
        // Columns on and between lattice lines; rows on them, or just below
        // one (−1e-9 splits to the fraction 1.0 in f32): the corners whose
        // offsets are all zero give signed zeros.
        Grid::new(core::array::from_fn(|d| if d == 0 { 0.0 } else { -1e-9 }), [0.5; D], size(45, rest)),
        // Whole rows in long runs, many of them: batches of rows, full and
        // partial, cut where rows cross into the next plane of cells (and
        // one row on the lattice line y = 0).
        Grid::new(
            [-0.5; D],
            [1.0 / 32.0; D],
            core::array::from_fn(|d| match d {
                0 => 48,
                1 => 37,
                _ => 2,
            }),
        ),
        // Tiles inside one cell along axis 0: rows of one to four whole
        // chunks of 8 or 16 lanes, in batches cut from axis 1's runs and
        // written with the chunks' positions held, on and off the lattice
        // lines of axes 1.. (axis 2 from 0).
        Grid::new(axes([2.0, -0.5, 0.0]), [1.0 / 32.0; D], axes([32, 40, 2])),
        Grid::new(axes([-3.5, 1.25, 0.0]), [1.0 / 32.0; D], axes([16, 20, 2])),
        // Inside one cell on axes 0 and 1 as well: a 2D grid of one, two
        // or four whole chunks a row takes a fill of its own, the cell's
        // records in registers and on the stack (64 columns: eight chunks
        // of 8 lanes, so the general fill on AVX2).
        Grid::new(axes([2.0, 0.25, 0.0]), [1.0 / 64.0; D], axes([32, 40, 2])),
        Grid::new(axes([-3.5, 1.25, 0.5]), [1.0 / 64.0; D], axes([16, 20, 2])),
        Grid::new(axes([7.0, -2.0, 0.0]), [1.0 / 128.0; D], axes([64, 3, 2])),
        // And across two cells: a chunk each (16 lanes) or two (8).
        Grid::new(axes([1.0, -0.25, 0.5]), [1.0 / 16.0; D], axes([32, 24, 2])),
        // Tiles of cells narrower than the lanes whose lattice points fit
        // in one register or two (a fractal tile's fine octaves), each
        // plane's points held in registers: 32 columns at 1/8, 33 at 1/4,
        // 32 and 12 at 1/2, on and off the lattice lines, and an axis 0
        // that descends by uneven steps of cells.
        Grid::new(axes([4.0, -0.5, 0.0]), [0.125; D], axes([32, 20, 2])),
        Grid::new(axes([-2.0, 0.25, 0.5]), [0.25; D], axes([33, 12, 2])),
        Grid::new(axes([6.0, 0.0, -1.0]), [0.5; D], axes([32, 8, 2])),
        Grid::new(axes([1.3, -7.0, 0.0]), [0.5; D], axes([12, 6, 2])),
        Grid::new(axes([3.1, 0.6, 0.2]), axes([-0.3, 0.2, 0.7]), axes([20, 9, 2])),
        // 2D tiles of whole chunks across cells, each plane's points held
        // in registers (one walk for any spacing): three chunks at 1/8 with
        // axis 1 descending; three at 1/4 (AVX2) with rows that skip
        // cells; one chunk of 16 or two of 8 down 64 rows at 1/2, on the
        // lattice lines; and three chunks inside one cell (48 columns at
        // 1/128, the rows of 24 at 1/64 across two cells).
        Grid::new(axes([5.0, 2.0, 0.0]), axes([0.125, -0.25, 0.5]), axes([48, 24, 2])),
        Grid::new(axes([-1.0, 0.4, 0.0]), axes([0.25, 1.7, 0.5]), axes([24, 10, 2])),
        Grid::new(axes([0.0, -9.0, 0.0]), [0.5; D], axes([16, 64, 2])),
        Grid::new(axes([2.0, 0.25, 0.0]), axes([1.0 / 128.0, 1.0 / 64.0, 0.5]), axes([48, 16, 2])),
        Grid::new(axes([2.5, 0.25, 0.0]), [1.0 / 64.0; D], axes([24, 40, 2])),
        // Non-finite coordinates (NaN where the scalar API gives NaN): the
        // last axis at 0.3 + i·∞ (NaN, then +∞), and axis 0 from 3.0e38 by
        // 1e37, past f32::MAX (≈ 3.4e38) from column 5 of each row.
        Grid::new([0.3; D], core::array::from_fn(|d| if d == D - 1 { f64::INFINITY } else { 0.0625 }), size(37, 2)),
        Grid::new(
            core::array::from_fn(|d| if d == 0 { 3.0e38 } else { 0.3 }),
            core::array::from_fn(|d| if d == 0 { 1.0e37 } else { 0.25 }),
            size(37, 2),
        ),
    ]
}

#[test]
fn batch_equals_scalar_f32_bit_for_bit() {
    macro_rules! check {
        ($name:expr, $noise:expr, $d:literal, $range:expr) => {
            check_batch::<_, $d>($name, &$noise)
        };
    }
    for_every_kind!(check);
}

#[inline(never)]
fn check_range<N: Noise<D>, const D: usize>(name: &str, noise: &N, (lo, hi): (f64, f64)) {
    let mut rng = SplitMix64(D as u64 * 7919);
    let (mut min, mut max) = (f64::INFINITY, f64::NEG_INFINITY);
    for _ in 0..200_000 {
        let mut p = [0f64; D];
        for c in p.iter_mut() {
            *c = (rng.next() >> 11) as f64 / (1u64 << 53) as f64 * 512.0 - 256.0;
        }
        let v = noise.get(p);
        min = min.min(v);
        max = max.max(v);
    }
    assert!(min >= lo && max <= hi, "{name} {D}D: values [{min}, {max}] outside documented [{lo}, {hi}]");
    // The range is not vacuous: the noise uses a good part of it.
    assert!(max - min > 0.5 * (hi - lo), "{name} {D}D: values [{min}, {max}] span too little of [{lo}, {hi}]");
}

#[test]
fn values_stay_in_documented_range() {
    macro_rules! check {
        ($name:expr, $noise:expr, $d:literal, $range:expr) => {
            check_range::<_, $d>($name, &$noise, $range)
        };
    }
    for_every_kind!(check);
}

#[inline(never)]
fn check_special<N: Noise<D>, const D: usize>(name: &str, noise: &N) {
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        for axis in 0..D {
            let mut p = [0.3; D];
            p[axis] = bad;
            let v = noise.get(p);
            assert!(v.is_nan(), "{name} {D}D: {p:?} gave {v}, want NaN");
            let v = noise.get_f32(p.map(|c| c as f32));
            assert!(v.is_nan(), "{name} {D}D f32: {p:?} gave {v}, want NaN");
        }
    }
    // Far beyond ±2³¹ cells: finite, no panic (debug builds check overflow).
    for huge in
        [3.0e9, -3.0e9, 1.0e15, -1.0e15, 1.0e300, -1.0e300, f64::MAX, f64::MIN, 2.0f64.powi(31), -(2.0f64.powi(31))]
    {
        let mut p = [0.5; D];
        p[0] = huge;
        assert!(noise.get(p).is_finite(), "{name} {D}D: {p:?} not finite");
        // In f32 the same magnitudes, clamped to the largest finite float.
        let pf = p.map(|c| (c as f32).clamp(f32::MIN, f32::MAX));
        assert!(noise.get_f32(pf).is_finite(), "{name} {D}D f32: {pf:?} not finite");
    }
    // Batches whose output does not fit: a typed error, nothing written.
    let mut out = [7.0f32; 3];
    assert_eq!(
        noise.fill_points(&[[0.5; D]; 2], &mut out),
        Err(GridError::PointsMismatch { points: 2, out: 3 }),
        "{name} {D}D"
    );
    let grid = Grid::new([0.0; D], [0.5; D], [2; D]);
    for accuracy in [Accuracy::Exact, Accuracy::Fast] {
        let filled = fill_grid_at(SimdLevel::best(), noise, &grid, &mut out, accuracy);
        assert_eq!(filled, Err(GridError::LengthMismatch { expected: grid.len(), got: 3 }), "{name} {D}D");
    }
    assert_eq!(out, [7.0; 3], "{name} {D}D: a refused batch wrote");
}

#[test]
fn special_inputs_follow_the_contract() {
    macro_rules! check {
        ($name:expr, $noise:expr, $d:literal, $range:expr) => {
            check_special::<_, $d>($name, &$noise)
        };
    }
    for_every_kind!(check);
}

#[test]
fn noises_are_send_sync_and_cheap_to_share() {
    fn assert_traits<T: Send + Sync + Clone + 'static>() {}
    assert_traits::<Classic>();
    assert_traits::<Improved>();
    assert_traits::<Simplex>();
    assert_traits::<SimplexN>();
    assert_traits::<Modified>();
    assert_traits::<ModifiedTexture>();
    assert_traits::<Value>();
}

/// The contract on arbitrary inputs: non-finite in, NaN out; finite in,
/// finite out; every API agrees.
#[inline(never)]
fn check_any<N: Noise<D>, const D: usize>(name: &str, noise: &N, coords: &[f64]) {
    let mut p = [0f64; D];
    p.copy_from_slice(&coords[..D]);
    let v = noise.get(p);
    if p.iter().all(|c| c.is_finite()) {
        assert!(v.is_finite(), "{name} {D}D: {p:?} gave {v}");
    } else {
        assert!(v.is_nan(), "{name} {D}D: {p:?} gave {v}, want NaN");
    }
    let pf = p.map(|c| c as f32);
    let vf = noise.get_f32(pf);
    assert_eq!(vf.is_nan(), pf.iter().any(|c| !c.is_finite()), "{name} {D}D f32: {pf:?} gave {vf}");
    let mut out = [0f32; 1];
    noise.fill_points(&[pf], &mut out).unwrap();
    assert!(same(out[0], vf), "{name} {D}D: batch {} != scalar {vf} at {pf:?}", out[0]);
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(64))]
    #[test]
    fn arbitrary_inputs_follow_the_contract(
        coords in proptest::collection::vec(proptest::num::f64::ANY, 8),
        small in proptest::collection::vec(-1.0e4f64..1.0e4, 8),
    ) {
        macro_rules! check {
            ($name:expr, $noise:expr, $d:literal, $range:expr) => {{
                let noise = $noise;
                check_any::<_, $d>($name, &noise, &coords);
                check_any::<_, $d>($name, &noise, &small);
            }};
        }
        for_every_kind!(check);
    }
}

/// Grids large enough to be split into parallel tasks (with the `parallel`
/// feature, which the workspace's command line turns on) give every point
/// the bits of the scalar API, wherever the tasks cut the rows.
#[test]
fn large_grids_equal_the_scalar_api() {
    #[inline(never)]
    fn check<N: Noise<D>, const D: usize>(name: &str, noise: &N, grid: Grid<D>) {
        let mut out = vec![0f32; grid.len()];
        noise.fill_grid(&grid, &mut out).unwrap();
        for (i, &b) in out.iter().enumerate().step_by(7) {
            let s = noise.get_f32(grid.point(i));
            assert!(same(s, b), "{name} {D}D point {i}: scalar {s:e} batch {b:e}");
        }
    }
    // Past 2^20 points: the exact rows prefetch their stores.
    check("improved", &Improved::new(1), Grid::new([0.1, -3.0], [1.0 / 32.0, 1.0 / 40.0], [1031, 1100]));
    check("simplex", &Simplex::new(1), Grid::new([0.1, -3.0], [0.01, 0.02], [700, 1031]));
    check("value", &Value::new(1), Grid::new([0.0; 3], [0.05; 3], [90, 80, 70]));
    check("value", &Value::new(1), Grid::new([0.3, -2.0], [1.0 / 32.0, 1.0 / 24.0], [1000, 300]));
    // Rows longer than the fractal's block: octaves fill pieces of rows.
    let value_fbm = Fractal::new(|o| Value::new(o.seed), 1, 2, FractalMode::Fbm).unwrap();
    check("fbm value", &value_fbm, Grid::new([0.3, -2.0], [1.0 / 32.0, 1.0 / 64.0], [70_000, 5]));
    check(
        "fbm improved",
        &Fractal::new(|o| Improved::new(o.seed), 1, 5, FractalMode::Fbm).unwrap(),
        Grid::new([0.0; 2], [1.0 / 64.0; 2], [1500, 400]),
    );
    check("worley", &Worley::new(3), Grid::new([-7.0; 2], [1.0 / 16.0; 2], [600, 600]));
}
