//! Working buffers reused across grid fills on the same thread, so a
//! fill allocates (and the system zeroes and maps pages) once per thread,
//! not once per call: a fractal's octave buffers are megabytes, and a
//! fill's records hundreds of kilobytes at one cell per point,
//! which the allocator returns to the system on free and must map again
//! (2D improved noise, one 2048-point row at one cell per point: 70 µs a
//! call with fresh allocations, 26 µs with the allocator told never to
//! give memory back).
//!
//! Buffers are taken out of a per-thread pool and put back when done, so
//! fills nested inside others (a fractal's octaves) take buffers of their
//! own. Without `std` there are no thread-locals: each call allocates.

use alloc::vec::Vec;

/// Most buffers a thread keeps: a cellular fill holds four tables at once
/// (a lattice fill keeps its own tables, and a grid fill its axes); a
/// fractal adds its octave values and, over rows of several strips, each
/// octave's strip axes (six octaves: seven; its whole axes it keeps
/// itself). Deeper nesting allocates past these.
#[cfg(feature = "std")]
const KEPT: usize = 16;

/// Most values a thread's pool holds in all (32 MiB), so memory stays
/// bounded however large a fill once was: a fill whose buffers exceed it
/// (rows of millions of points, fractals of dozens of octaves over long
/// rows) allocates per call, a small cost beside that much work. The
/// performance workloads stay well inside it (6-octave fBm of 2048² rows:
/// 0.8 M values).
#[cfg(feature = "std")]
const KEPT_VALUES: usize = 8 << 20;

#[cfg(feature = "std")]
std::thread_local! {
    static POOL: core::cell::Cell<Vec<Vec<f32>>> = const { core::cell::Cell::new(Vec::new()) };
}

/// Working vectors that a kind's grid fill keeps per thread between calls
/// (its tables of cells, runs and chunk plans), so a warm fill allocates
/// nothing: declared with [`per_thread!`], taken whole at the start of a
/// fill and kept again at its end. Taken whole, a fill nested inside
/// another of the same kind finds none kept and allocates its own.
pub(crate) trait KeptVectors: Default + 'static {
    /// Bytes the vectors hold (their capacities).
    fn held_bytes(&self) -> usize;
}

/// The bytes a vector holds.
pub(crate) fn bytes_of<T>(v: &Vec<T>) -> usize {
    v.capacity() * core::mem::size_of::<T>()
}

/// One [`KeptVectors`] per thread (none without `std`: each fill then
/// allocates). Declared with [`per_thread!`].
pub(crate) struct PerThread<T: 'static> {
    #[cfg(feature = "std")]
    pub(crate) slot: &'static std::thread::LocalKey<core::cell::Cell<Option<alloc::boxed::Box<T>>>>,
    #[cfg(not(feature = "std"))]
    pub(crate) kind: core::marker::PhantomData<fn() -> T>,
}

impl<T: KeptVectors> PerThread<T> {
    /// Most bytes a thread keeps in one slot (about 35,000 columns of a
    /// lattice fill's tables): a fill of longer rows allocates per call, a
    /// small cost beside its work.
    const KEPT_BYTES: usize = 1 << 20;

    /// This thread's kept vectors, or new empty ones. Boxed, so taking and
    /// keeping them moves a pointer, not the vectors' headers. Not
    /// borrowed in place: the fill would then run in `with`'s closure,
    /// which is compiled without the instruction set of its caller (5× the
    /// instructions, lattice 2D tiles).
    #[inline(always)]
    pub(crate) fn take(&self) -> alloc::boxed::Box<T> {
        #[cfg(feature = "std")]
        return self.slot.with(core::cell::Cell::take).unwrap_or_default();
        #[cfg(not(feature = "std"))]
        alloc::boxed::Box::default()
    }

    /// Keep `kept` for this thread's next fill, unless it holds more
    /// than the bound (then it is freed).
    #[inline(always)]
    pub(crate) fn keep(&self, kept: alloc::boxed::Box<T>) {
        if kept.held_bytes() > Self::KEPT_BYTES {
            return;
        }
        #[cfg(feature = "std")]
        self.slot.with(|slot| slot.set(Some(kept)));
        #[cfg(not(feature = "std"))]
        drop(kept);
    }
}

/// `per_thread!(NAME: Type)` declares `static NAME: PerThread<Type>`.
macro_rules! per_thread {
    ($name:ident: $ty:ty) => {
        static $name: crate::scratch::PerThread<$ty> = {
            #[cfg(feature = "std")]
            {
                std::thread_local! {
                    static SLOT: core::cell::Cell<Option<alloc::boxed::Box<$ty>>> = const { core::cell::Cell::new(None) };
                }
                crate::scratch::PerThread { slot: &SLOT }
            }
            #[cfg(not(feature = "std"))]
            crate::scratch::PerThread { kind: core::marker::PhantomData }
        };
    };
}
pub(crate) use per_thread;

/// A buffer of at least `len` values (their contents unspecified: left
/// from an earlier use, or zero).
pub(crate) fn take(len: usize) -> Vec<f32> {
    // Nothing to hold (a table with no fields): no pool round trip, which
    // was 5 % of a 32² tile of 2D improved noise (1.42 → 1.35 ns/point).
    if len == 0 {
        return Vec::new();
    }
    #[cfg(feature = "std")]
    let mut buffer = POOL.with(|slot| {
        let mut pool = slot.take();
        // The smallest that fits, else the largest (to grow): a fill's
        // small tables must not take the fractal's megabytes, which would
        // then be allocated again.
        let fits = pool.iter().enumerate().filter(|(_, b)| b.capacity() >= len).min_by_key(|(_, b)| b.capacity());
        let pick = fits.or_else(|| pool.iter().enumerate().max_by_key(|(_, b)| b.capacity())).map(|(k, _)| k);
        let buffer = pick.map(|k| pool.swap_remove(k)).unwrap_or_default();
        slot.set(pool);
        buffer
    });
    #[cfg(not(feature = "std"))]
    let mut buffer = Vec::new();
    if buffer.len() < len {
        buffer.resize(len, 0.0);
    }
    buffer
}

/// Keep `buffer` for a later [`take`] on this thread.
pub(crate) fn give_back(buffer: Vec<f32>) {
    if buffer.capacity() == 0 {
        return;
    }
    #[cfg(feature = "std")]
    POOL.with(|slot| {
        let mut pool = slot.take();
        let held: usize = pool.iter().map(Vec::capacity).sum();
        if pool.len() < KEPT {
            if held + buffer.capacity() <= KEPT_VALUES {
                pool.push(buffer);
            }
        } else if let Some(smallest) = pool.iter_mut().min_by_key(|b| b.capacity()) {
            // Full: keep the larger, within the bound.
            if smallest.capacity() < buffer.capacity() && held - smallest.capacity() + buffer.capacity() <= KEPT_VALUES
            {
                *smallest = buffer;
            }
        }
        slot.set(pool);
    });
    #[cfg(not(feature = "std"))]
    drop(buffer);
}

#[cfg(all(test, feature = "std"))]
mod tests {
    use super::*;

    /// The capacities of the buffers this thread's pool holds.
    fn held() -> Vec<usize> {
        POOL.with(|slot| {
            let pool = slot.take();
            let held = pool.iter().map(Vec::capacity).collect();
            slot.set(pool);
            held
        })
    }

    /// A buffer past the bound is freed, one within it kept, and however
    /// many large buffers come back the pool stays within the bound.
    #[test]
    fn keeps_at_most_the_bound() {
        give_back(take(KEPT_VALUES + 1));
        assert!(held().iter().all(|&c| c <= KEPT_VALUES));
        let kept = take(1 << 20);
        let capacity = kept.capacity();
        give_back(kept);
        assert!(held().contains(&capacity));
        let many: Vec<_> = (0..KEPT).map(|_| take(3 << 20)).collect();
        for b in many {
            give_back(b);
        }
        let total: usize = held().iter().sum();
        assert!((2 * (3 << 20)..=KEPT_VALUES).contains(&total), "{total} values held");
    }

    /// A small request takes the smallest buffer that fits, leaving the
    /// large one for the large request (a fractal's octaves beside its
    /// octaves' own tables), and a buffer given back is used again.
    #[test]
    fn takes_the_smallest_buffer_that_fits() {
        let (large, small) = (take(1 << 20), take(1000));
        let (large_at, small_at) = (large.as_ptr(), small.as_ptr());
        give_back(large);
        give_back(small);
        let again_small = take(900);
        let again_large = take(1 << 19);
        assert_eq!(again_small.as_ptr(), small_at);
        assert_eq!(again_large.as_ptr(), large_at);
        assert!(again_small.len() >= 900 && again_large.len() >= 1 << 19);
    }
}
