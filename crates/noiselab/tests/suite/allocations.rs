//! No allocation in a grid fill's hot path: once a thread has filled grids
//! of some shapes (which grows its kept tables and scratch buffers), filling
//! them again allocates nothing, for every kind, level and accuracy. (A
//! branch that kept one of its tables in the wrong vector allocated and
//! freed one on every call of a fractal's fine octaves.)

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

use noiselab::grid::fill_grid_at;
use noiselab::{
    Accuracy, CellOutput, Classic, Fast, Fractal, FractalMode, Grid, Improved, ImprovedVariant, Kernel, Looped, Metric,
    Modified, ModifiedHash, ModifiedTexture, Noise, SimdLevel, Simplex, SimplexN, Sparse, Value, Warp, Worley,
};

/// The system allocator, counting each thread's allocations.
struct Counting;

thread_local! {
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

fn count_one() {
    // `try_with`: a thread being torn down has no counter left.
    let _ = ALLOCATIONS.try_with(|n| n.set(n.get() + 1));
}

// SAFETY: every call passes its arguments on to the system allocator,
// whose contract is the same.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count_one();
        unsafe { System.alloc(layout) }
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        count_one();
        unsafe { System.alloc_zeroed(layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count_one();
        unsafe { System.realloc(ptr, layout, new_size) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// Allocations made on this thread so far.
fn allocations() -> usize {
    ALLOCATIONS.with(Cell::get)
}

/// The probe grids of `every_kind`, and grids of the fast fills' paths:
/// 32² tiles at 1/32 (bands of whole cells), at 1/4 (bands of cells
/// narrower than the lanes) and at 1/2 (rows of fine cells).
fn grids<const D: usize>() -> Vec<Grid<D>> {
    let mut grids = super::every_kind::probe_grids::<D>();
    let side = |x: usize| core::array::from_fn(|d| if d < 2 { x } else { 2 });
    for (origin, step) in [(0.0, 1.0 / 32.0), (1.0, 1.0 / 32.0), (0.0, 0.25), (0.5, 0.5)] {
        grids.push(Grid::new([origin; D], [step; D], side(32)));
    }
    grids
}

// Out of line, as the other suites' generic helpers (see `every_kind`).
#[inline(never)]
fn check_steady<N: Noise<D>, const D: usize>(name: &str, noise: &N) {
    let grids = grids::<D>();
    let mut outs: Vec<Vec<f32>> = grids.iter().map(|g| vec![0.0; g.len()]).collect();
    for level in SimdLevel::available() {
        for accuracy in [Accuracy::Exact, Accuracy::Fast] {
            let fill_all = |outs: &mut [Vec<f32>]| {
                for (grid, out) in grids.iter().zip(outs.iter_mut()) {
                    fill_grid_at(level, noise, grid, out, accuracy).unwrap();
                }
            };
            fill_all(&mut outs);
            let before = allocations();
            fill_all(&mut outs);
            let made = allocations() - before;
            assert_eq!(
                made,
                0,
                "{name} {D}D {level:?} {accuracy:?}: {made} allocations filling {} grids again",
                grids.len()
            );
        }
    }
}

#[test]
fn filling_again_allocates_nothing() {
    macro_rules! check {
        ($name:expr, $noise:expr, $d:literal, $range:expr) => {
            check_steady::<_, $d>($name, &$noise);
        };
    }
    for_every_kind!(check);
}

/// Splatting a window again, and a turbulence of splatted octaves,
/// allocates nothing either: the axes and the octave buffer come from the
/// thread's scratch pool. With `parallel`, inside a pool of one worker:
/// rendered from outside a pool, the job's hand-over to rayon's global
/// queue allocates now and then on the calling thread (a block of slots),
/// which is rayon's, not the fill's.
#[test]
fn splatting_again_allocates_nothing() {
    let splat_twice = || {
        let window = Grid::new([0.25, -3.0], [0.05, 0.07], [64, 40]);
        let mut out = vec![0.0; window.len()];
        let sparse = Sparse::new(4);
        let turbulence = noiselab::SparseTurbulence::new(&sparse, 0, 3);
        let splat_both = |out: &mut [f32]| {
            sparse.splat_grid(&window, out).unwrap();
            turbulence.splat_grid(&window, out).unwrap();
        };
        splat_both(&mut out);
        let before = allocations();
        splat_both(&mut out);
        allocations() - before
    };
    #[cfg(feature = "parallel")]
    let made = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap().install(splat_twice);
    #[cfg(not(feature = "parallel"))]
    let made = splat_twice();
    assert_eq!(made, 0, "splatting a window again allocated {made} times");
}
