//! Working buffers reused across grid fills on the same thread, so a
//! fill allocates (and the system zeroes and maps pages) once per thread,
//! not once per call: a fractal's octave buffers are megabytes, which
//! the allocator returns to the system on free and must map again.
//!
//! A buffer is taken out of its slot and put back when done, so a fill
//! nested inside another (a fractal of fractals) finds the slot empty and
//! allocates its own. Without `std` there are no thread-locals: each call
//! allocates.

use alloc::vec::Vec;

#[cfg(feature = "std")]
std::thread_local! {
    static SLOT: core::cell::Cell<Vec<f32>> = const { core::cell::Cell::new(Vec::new()) };
}

/// A buffer of at least `len` values (their contents unspecified: left
/// from an earlier use, or zero).
pub(crate) fn take(len: usize) -> Vec<f32> {
    #[cfg(feature = "std")]
    let mut buffer = SLOT.with(|slot| slot.take());
    #[cfg(not(feature = "std"))]
    let mut buffer = Vec::new();
    if buffer.len() < len {
        buffer.resize(len, 0.0);
    }
    buffer
}

/// Keep `buffer` for the next [`take`] on this thread.
pub(crate) fn give_back(buffer: Vec<f32>) {
    #[cfg(feature = "std")]
    SLOT.with(|slot| {
        // Keep the larger of the two (a nested fill's buffer may be smaller).
        let held = slot.take();
        slot.set(if held.capacity() > buffer.capacity() { held } else { buffer });
    });
    #[cfg(not(feature = "std"))]
    drop(buffer);
}
