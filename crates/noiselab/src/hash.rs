//! Lattice hashing shared by the kinds: Perlin's permutation tables and a
//! table-free integer hash.

use crate::lanes::{BatchLanes, IntLanes, Table256};
use alloc::sync::Arc;

/// Perlin's reference permutation of 0..=255 (Improving Noise, 2002; also used
/// by Gustavson's simplex reference code).
pub const PERLIN_PERMUTATION: [u8; 256] = [
    151, 160, 137, 91, 90, 15, 131, 13, 201, 95, 96, 53, 194, 233, 7, 225, 140, 36, 103, 30, 69, 142, 8, 99, 37, 240,
    21, 10, 23, 190, 6, 148, 247, 120, 234, 75, 0, 26, 197, 62, 94, 252, 219, 203, 117, 35, 11, 32, 57, 177, 33, 88,
    237, 149, 56, 87, 174, 20, 125, 136, 171, 168, 68, 175, 74, 165, 71, 134, 139, 48, 27, 166, 77, 146, 158, 231, 83,
    111, 229, 122, 60, 211, 133, 230, 220, 105, 92, 41, 55, 46, 245, 40, 244, 102, 143, 54, 65, 25, 63, 161, 1, 216,
    80, 73, 209, 76, 132, 187, 208, 89, 18, 169, 200, 196, 135, 130, 116, 188, 159, 86, 164, 100, 109, 198, 173, 186,
    3, 64, 52, 217, 226, 250, 124, 123, 5, 202, 38, 147, 118, 126, 255, 82, 85, 212, 207, 206, 59, 227, 47, 16, 58, 17,
    182, 189, 28, 42, 223, 183, 170, 213, 119, 248, 152, 2, 44, 154, 163, 70, 221, 153, 101, 155, 167, 43, 172, 9, 129,
    22, 39, 253, 19, 98, 108, 110, 79, 113, 224, 232, 178, 185, 112, 104, 218, 246, 97, 228, 251, 34, 242, 193, 238,
    210, 144, 12, 191, 179, 162, 241, 81, 51, 145, 235, 249, 14, 239, 107, 49, 192, 214, 31, 181, 199, 106, 157, 184,
    84, 204, 176, 115, 121, 50, 45, 127, 4, 150, 254, 138, 236, 205, 93, 222, 114, 67, 29, 24, 72, 243, 141, 128, 195,
    78, 66, 215, 61, 156, 180,
];

/// A permutation of 0..=255 stored twice (512 entries), so that
/// `p[p[x] + y]` needs no wrap for `x, y ≤ 256`.
///
/// Seed 0 is Perlin's reference permutation; other seeds are shuffles of it
/// drawn from a SplitMix64 stream seeded by the seed. Cheap to clone (shared).
#[derive(Clone, Debug)]
pub struct Permutation {
    tables: Arc<Tables>,
}

#[derive(Debug)]
struct Tables {
    doubled: [u8; 512],
    lookup: Table256,
    /// `p[p[i]]`: two links of a chain whose second adds 0.
    twice: Table256,
}

impl Permutation {
    /// The permutation for `seed`.
    pub fn new(seed: u32) -> Self {
        let mut p = PERLIN_PERMUTATION;
        if seed != 0 {
            let mut rng = SplitMix64(seed as u64);
            for i in (1..256).rev() {
                let j = (rng.next() % (i as u64 + 1)) as usize;
                p.swap(i, j);
            }
        }
        Self::from_table(&p)
    }

    /// A permutation from an explicit table (must be a permutation of 0..=255).
    pub fn from_table(p: &[u8; 256]) -> Self {
        let mut doubled = [0u8; 512];
        doubled[..256].copy_from_slice(p);
        doubled[256..].copy_from_slice(p);
        let twice = Table256(core::array::from_fn(|i| p[p[i] as usize]));
        Permutation { tables: Arc::new(Tables { doubled, lookup: Table256(*p), twice }) }
    }

    /// The doubled table.
    #[inline(always)]
    pub fn table(&self) -> &[u8; 512] {
        &self.tables.doubled
    }

    /// The 256 entries, for table lookups in lanes.
    #[inline(always)]
    pub fn entries(&self) -> &Table256 {
        &self.tables.lookup
    }

    /// `p[p[i & 255]]` per lane: one lookup for two links when the second
    /// adds a zero coordinate (lower dimensions continuing a longer chain).
    #[inline(always)]
    pub fn twice<I: IntLanes>(&self, i: I) -> I {
        I::lookup256(&self.tables.twice, i)
    }

    /// `p[(first + k) & 255]` in lane k: consecutive entries, read from the
    /// doubled table with one load (a run of at most 16 never wraps it).
    #[inline(always)]
    pub fn run<B: BatchLanes>(&self, first: i32) -> B::Int {
        B::load_u8(&self.tables.doubled[(first & 255) as usize..])
    }

    /// [`Permutation::at`] (or, `twice`, [`Permutation::twice`]) of each
    /// of `idx`, in place: up to four vectors to one
    /// [`IntLanes::lookup256x4`], a lone one by itself.
    #[inline(always)]
    pub fn at_each<I: IntLanes>(&self, idx: &mut [I], twice: bool) {
        let table = if twice { &self.tables.twice } else { &self.tables.lookup };
        // Element by element, not `copy_from_slice`: slices of vectors
        // would be copied with `memmove` calls.
        let n = idx.len();
        for group in 0..n.div_ceil(4) {
            let first = 4 * group;
            if first + 1 == n {
                idx[first] = I::lookup256(table, idx[first]);
            } else {
                // No `array::from_fn`: its closure would not inherit the
                // batch driver's instruction set (ARCHITECTURE.md).
                let last = n - 1;
                let four = [idx[first], idx[first + 1], idx[(first + 2).min(last)], idx[(first + 3).min(last)]];
                let looked = I::lookup256x4(table, four);
                for (k, v) in looked.into_iter().enumerate().take(n - first) {
                    idx[first + k] = v;
                }
            }
        }
    }

    /// [`Permutation::at`] (or, `twice`, [`Permutation::twice`]) of bytes
    /// ([`IntLanes::lookup_bytes`]).
    #[inline(always)]
    pub fn at_bytes<I: IntLanes>(&self, b: I::Bytes, twice: bool) -> I::Bytes {
        I::lookup_bytes(if twice { &self.tables.twice } else { &self.tables.lookup }, b)
    }

    /// `p[i]` per lane, for `0 ≤ i < 512` (the doubled table's range: the
    /// lookup reads `p[i & 255]`, the same entry).
    #[inline(always)]
    pub fn at<I: IntLanes>(&self, i: I) -> I {
        I::lookup256(&self.tables.lookup, i)
    }
}

/// SplitMix64 (Steele, Lea & Flood 2014): a tiny, well-mixed stream used only
/// to derive tables from seeds.
#[derive(Clone, Debug)]
pub struct SplitMix64(pub u64);

impl SplitMix64 {
    /// Next 64 random bits.
    #[allow(clippy::should_implement_trait)]
    pub fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
}

/// Per-axis multipliers for [`hash_cell`] (odd, well-spread constants).
const AXIS_PRIMES: [i32; 4] = [0x9E37_79B1_u32 as i32, 0x85EB_CA77_u32 as i32, 0xC2B2_AE3D_u32 as i32, 0x27D4_EB2F];

/// The MurmurHash3 32-bit finaliser (Appleby): a bijection of u32 with good
/// avalanche and `fmix32(0) == 0`.
#[inline(always)]
pub fn fmix32<I: IntLanes>(mut h: I) -> I {
    h = h.xor(h.shr(16));
    h = h.mul(I::splat(0x85EB_CA6B_u32 as i32));
    h = h.xor(h.shr(13));
    h = h.mul(I::splat(0xC2B2_AE35_u32 as i32));
    h.xor(h.shr(16))
}

/// A table-free hash of a lattice cell and a seed: 32 well-mixed bits.
#[inline(always)]
pub fn hash_cell<I: IntLanes, const D: usize>(cell: [I; D], seed: u32) -> I {
    let mut h = I::splat(seed.wrapping_mul(0x2545_F491) as i32);
    for d in 0..D {
        h = h.xor(cell[d].mul(I::splat(AXIS_PRIMES[d % 4])));
    }
    fmix32(h)
}
