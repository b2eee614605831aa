//! The library's integration tests, one binary.
//!
//! Each file is a module here rather than a test target of its own because
//! the kinds' batch code is generic: every test binary compiled it again for
//! the kinds it named (Worley's grid path, at every instruction-set level,
//! in `every_kind`, `worley` and `grid_fast` alike). One crate compiles each
//! instantiation once. Run one file's tests with a filter, e.g.
//! `cargo test -p noiselab --test suite worley::`.

mod common;

// First: `allocations` runs its check over `every_kind`'s kinds.
#[macro_use]
mod every_kind;

mod allocations;
mod compose;
mod conformance_classic;
mod conformance_improved;
mod conformance_simplex;
mod fractal;
mod gradients;
mod grid_fast;
mod modified;
mod simplex_n;
mod sparse;
mod tiling;
mod worley;
