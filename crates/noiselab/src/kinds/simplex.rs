//! Simplex noise (Perlin 2001), as Gustavson's reference `SimplexNoise.java`
//! (version 2012-03-09) computes it, in 2D, 3D and 4D; 1D as his
//! `simplexnoise1234.c`.

use super::finite_or_nan;
use crate::grid::{self, ChunkSampler, Span};
use crate::hash::Permutation;
use crate::lanes::{BatchLanes, IntLanes, Lanes, Table16, Table256};
use crate::noise::{Noise, NoiseGradient};
use alloc::sync::Arc;

/// Gustavson's `grad3`: the 12 edge midpoints of the cube, by column
/// (padded to 16 entries for register-wide lookups).
const GRAD3: [Table16; 3] = [
    Table16::new([1.0, -1.0, 1.0, -1.0, 1.0, -1.0, 1.0, -1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]),
    Table16::new([1.0, 1.0, -1.0, -1.0, 0.0, 0.0, 0.0, 0.0, 1.0, -1.0, 1.0, -1.0, 0.0, 0.0, 0.0, 0.0]),
    Table16::new([0.0, 0.0, 0.0, 0.0, 1.0, 1.0, -1.0, -1.0, 1.0, 1.0, -1.0, -1.0, 0.0, 0.0, 0.0, 0.0]),
];

/// Gustavson's `grad4`: the 32 permutations of (0, ±1, ±1, ±1), by column.
const GRAD4: [[i32; 32]; 4] = [
    [0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, -1, -1, -1, -1, 1, 1, 1, 1, -1, -1, -1, -1, 1, 1, 1, 1, -1, -1, -1, -1],
    [1, 1, 1, 1, -1, -1, -1, -1, 0, 0, 0, 0, 0, 0, 0, 0, 1, 1, -1, -1, 1, 1, -1, -1, 1, 1, -1, -1, 1, 1, -1, -1],
    [1, 1, -1, -1, 1, 1, -1, -1, 1, 1, -1, -1, 1, 1, -1, -1, 0, 0, 0, 0, 0, 0, 0, 0, 1, -1, 1, -1, 1, -1, 1, -1],
    [1, -1, 1, -1, 1, -1, 1, -1, 1, -1, 1, -1, 1, -1, 1, -1, 1, -1, 1, -1, 1, -1, 1, -1, 0, 0, 0, 0, 0, 0, 0, 0],
];

/// Simplex noise, value-identical in `f64` to Gustavson's 2012 Java
/// reference (seed 0 = Perlin's permutation, which that code uses; other
/// seeds shuffle it).
///
/// * 2D: kernel radius² 0.5, scale 70; 3D and 4D: radius² 0.6, scale 32 and
///   27 — with 0.6 the kernel is not zero on the simplex faces, so the
///   reference (and this) is slightly discontinuous there.
/// * Ranges: within ±1 in 2D–4D (tested on random points).
/// * 1D follows Gustavson's `simplexnoise1234.c` and equals that C code in
///   `f32` bit for bit. Range ±0.64 in 1D (largest found
///   by hill climbing: 0.6328).
/// * Not tileable, by design: the skewed simplex lattice does not line up
///   with axis-aligned periods, so there is no `with_period` (asking for one
///   is a compile-time error rather than a silent seam). Tile with a lattice
///   kind, [`Sparse`](crate::Sparse) or [`Worley`](crate::Worley).
/// * Analytic gradients ([`NoiseGradient`]) in 1D–4D, exact wherever the
///   noise is differentiable (everywhere but those 3D/4D faces).
#[derive(Clone, Debug)]
pub struct Simplex {
    perm: Permutation,
    /// Gustavson's `permMod12`: `p[i] % 12`.
    mod12: Arc<GradientIndices>,
    seed: u32,
}

/// Gustavson's `permMod12`, for lane lookups and for runs.
#[derive(Debug)]
struct GradientIndices {
    lanes: Table256,
    /// The entries twice over: a run of four from any start reads
    /// without wrapping.
    doubled: [u8; 512],
}

impl Simplex {
    /// Simplex noise with the permutation for `seed` (0 = reference).
    pub fn new(seed: u32) -> Self {
        let perm = Permutation::new(seed);
        let lanes = Table256(perm.entries().0.map(|p| p % 12));
        let doubled = core::array::from_fn(|i| lanes.0[i % 256]);
        Simplex { perm, mod12: Arc::new(GradientIndices { lanes, doubled }), seed }
    }

    /// The seed.
    pub fn seed(&self) -> u32 {
        self.seed
    }

    /// The gradient indices of corners `i0`, `i0 + 1`, `i0 + 2` (and
    /// `i0 + 3`) of a row whose hash so far is `row` (`perm[j + …]`): the
    /// reference's `permMod12[i + row]` at consecutive `i` is a run of the
    /// table, one read where the lanes would hash each corner.
    #[inline(always)]
    fn run(&self, i0: i32, row: i32) -> &[u8] {
        let from = (i0 + row) as usize & 255;
        &self.mod12.doubled[from..from + 4]
    }

    /// 2D: the gradient indices of corners `(i0 + a, j0 + b)`, `a` from 0
    /// to 3 and `b` from 0 to 2, at entry `4b + a` (12 to 15 unused).
    #[inline(always)]
    fn corner_runs(&self, i0: i32, j0: i32) -> [u8; 16] {
        let mut runs = [0u8; 16];
        for (b, run) in runs.chunks_exact_mut(4).take(3).enumerate() {
            run.copy_from_slice(self.run(i0, self.perm.at(j0 + b as i32)));
        }
        runs
    }

    /// `permMod12[i]`, for `0 ≤ i < 512`.
    #[inline(always)]
    fn gradient_index<I: IntLanes>(&self, i: I) -> I {
        I::lookup256(&self.mod12.lanes, i)
    }

    /// `grad3[gi]`.
    #[inline(always)]
    fn grad3<L: Lanes, const D: usize>(gi: L::Int) -> [L; D] {
        let mut g = [L::cst(0.0); D];
        for (d, gd) in g.iter_mut().enumerate() {
            *gd = L::lookup16(&GRAD3[d], gi);
        }
        g
    }

    /// `grad4[gi]`.
    #[inline(always)]
    fn grad4<L: Lanes>(gi: L::Int) -> [L; 4] {
        let mut g = [L::cst(0.0); 4];
        for (d, gd) in g.iter_mut().enumerate() {
            *gd = L::from_int(L::Int::lookup32(&GRAD4[d], gi));
        }
        g
    }

    /// Gustavson's 3D hash of a corner `(i + a, j + b, k + c)`:
    /// `permMod12[ii + a + perm[jj + b + perm[kk + c]]]`, given `perm[kk + c]`.
    #[inline(always)]
    fn hash3<I: IntLanes>(&self, [ii, jj]: [I; 2], [a, b]: [I; 2], perm_kc: I) -> I {
        self.gradient_index(ii.add(a).add(self.perm.at(jj.add(b).add(perm_kc))))
    }

    /// The 4D hash of corner `c + o`, `perm[c0 + o0 + perm[c1 + o1 + …]] & 31`,
    /// given the innermost `perm[c3 + o3]`.
    #[inline(always)]
    fn hash4<I: IntLanes>(&self, c: [I; 4], o: [I; 4], perm_c3: I) -> I {
        let h = self.perm.at(c[2].add(o[2]).add(perm_c3));
        let h = self.perm.at(c[1].add(o[1]).add(h));
        self.perm.at(c[0].add(o[0]).add(h)).and_c(31)
    }
}

/// A point's `C` simplex corners, ready to sum: corner `c` contributes
/// `(r² − |d|²)⁴ · (g · d)` where positive, with `d` its offset and `g` its
/// gradient. The corner search is shared; `value` and `value_gradient` do
/// only the arithmetic each needs, so `sample` pays nothing for gradients.
struct Corners<L: Lanes, const D: usize, const C: usize> {
    p: [L; D],
    r2: f64,
    scale: f64,
    g: [[L; D]; C],
    d: [[L; D]; C],
}

impl<L: Lanes, const D: usize, const C: usize> Corners<L, D, C> {
    /// `(r² − |d|², g · d)` for corner `c`.
    #[inline(always)]
    fn falloff_and_dot(&self, c: usize) -> (L, L) {
        let (g, d) = (self.g[c], self.d[c]);
        let mut t = L::cst(self.r2);
        for k in 0..D {
            t = t - d[k] * d[k];
        }
        let mut dot = g[0] * d[0];
        for k in 1..D {
            dot = dot + g[k] * d[k];
        }
        (t, dot)
    }

    /// The noise: `scale ×` the corners summed in the reference's order;
    /// NaN for non-finite input.
    #[inline(always)]
    fn value(&self) -> L {
        finite_or_nan(self.p, self.value_at_finite())
    }

    /// [`Self::value`] where every coordinate is known to be finite (a grid
    /// whose axes are): the same bits there, without the per-chunk guard.
    #[inline(always)]
    fn value_at_finite(&self) -> L {
        let mut sum = L::cst(0.0);
        for c in 0..C {
            let (t, dot) = self.falloff_and_dot(c);
            let t2 = t * t;
            // `t` is never NaN (the offsets are not), so `t ≥ 0` is
            // `!(t < 0)`: the same select, without negating the mask.
            let n = L::select(t.ge(L::cst(0.0)), t2 * t2 * dot, L::cst(0.0));
            sum = if c == 0 { n } else { sum + n };
        }
        L::cst(self.scale) * sum
    }

    /// The noise and its gradient. Inside a simplex `d` moves with the
    /// point, so `∂n/∂x_j = t⁴ g_j − 8 t³ d_j (g · d)` with `t = r² − |d|²`.
    #[inline(always)]
    fn value_gradient(&self) -> (L, [L; D]) {
        let zero = L::cst(0.0);
        let mut grad = [zero; D];
        for c in 0..C {
            let (t, dot) = self.falloff_and_dot(c);
            let t2 = t * t;
            let slope = L::cst(8.0) * t2 * t * dot;
            let outside = t.lt(zero);
            for k in 0..D {
                let term = L::select(outside, zero, t2 * t2 * self.g[c][k] - slope * self.d[c][k]);
                grad[k] = if c == 0 { term } else { grad[k] + term };
            }
        }
        let s = L::cst(self.scale);
        // (A loop, not `map`: a closure would not inherit the batch
        // driver's instruction set.)
        for gk in grad.iter_mut() {
            *gk = finite_or_nan(self.p, s * *gk);
        }
        (self.value(), grad)
    }
}

/// For a chunk table: lane 0's cells and each lane's cells less those, or
/// `None` where some lane is not in lane 0's cell or the next on an axis.
#[inline(always)]
fn chunk_cells<L: Lanes, const D: usize>(cells: [L::Int; D]) -> Option<([i32; D], [L::Int; D])> {
    let mut first = [0i32; D];
    for a in 0..D {
        first[a] = cells[a].lane(0);
    }
    Some((first, cells_from::<L, D>(cells, first, [1; D])?))
}

/// Each lane's cells less `origin`, or `None` where some lane's are not
/// within `reach` of it (0 to `reach[a]` on axis `a`).
#[inline(always)]
fn cells_from<L: Lanes, const D: usize>(cells: [L::Int; D], origin: [i32; D], reach: [i32; D]) -> Option<[L::Int; D]> {
    let zero = L::Int::splat(0);
    let mut d = [zero; D];
    let mut far = zero.lt(zero);
    for a in 0..D {
        d[a] = cells[a].sub(L::Int::splat(origin[a]));
        far = far | d[a].lt(zero) | L::Int::splat(reach[a]).lt(d[a]);
    }
    if L::any(far) {
        return None;
    }
    Some(d)
}

/// Offsets `o` (each 0 to 2) as an entry of a 3 × 3 × 3 chunk table,
/// `a + 3b + 9c`.
#[inline(always)]
fn table_entry3<I: IntLanes>(o: [I; 3]) -> I {
    let (b, c) = (o[1], o[2]);
    o[0].add(b.shl(1).add(b)).add(c.shl(3).add(c))
}

/// A bound on coordinates below which a cell's integer and float corners
/// come from one conversion each and sums of up to three of them are
/// exact (so equal the reference's integer sums converted): skewed, they
/// stay within ±2²², and three of those sum below 2²⁴.
const SMALL: f32 = (1 << 21) as f32;

/// With eight lanes, a 2D chunk table's entry `e` holds the gradient of corner
/// `(i0 + TABLE2_A[e], j0 + TABLE2_B[e])`, `(i0, j0)` lane 0's cell. Entries
/// 0 to 7 serve corners 0 and 2, by the lane's cell offset `2·di + dj`
/// (corner 2 from entry 4); entries 8 to 15 serve corner 1 (from entry 12
/// below the diagonal). So each lane's lookup is into eight entries: one
/// permute.
const TABLE2_A: [i32; 16] = [0, 0, 1, 1, 1, 1, 2, 2, 1, 1, 2, 2, 0, 0, 1, 1];
const TABLE2_B: [i32; 16] = [0, 1, 0, 1, 1, 2, 1, 2, 0, 1, 0, 1, 1, 2, 1, 2];

/// The last chunk table ([`ChunkTables::gradients2`],
/// [`ChunkTables::gradient_indices3`]) and the cell it was made from (lane
/// 0's; 2D: third coordinate 0), which later chunks along a grid row share
/// while their lanes lie within its reach.
struct ChunkTable {
    cell: Option<[i32; 3]>,
    /// Whether the grid's coordinates all lie within ±[`SMALL`].
    small: bool,
    /// 3D: the gradient indices.
    entries: [i32; 32],
    /// 2D: by axis, the gradients' components: sixteen lanes, at entry
    /// `4b + a` for corner `(i0 + a, j0 + b)`; narrower, at the entries of
    /// [`TABLE2_A`], in two halves of eight.
    gradients: [[[f32; 8]; 2]; 2],
}

impl ChunkTable {
    #[inline(always)]
    fn empty(small: bool) -> Self {
        ChunkTable { cell: None, small, entries: [0; 32], gradients: [[[0.0; 8]; 2]; 2] }
    }
}

/// Where a chunk's corner gradients may come from other than per-lane
/// lookups: a grid's chunk table (batch lanes), or nowhere ([`NoTables`],
/// a point evaluation, whose lanes need not be near each other).
trait ChunkTables<L: Lanes> {
    /// 2D: the three corners' gradients for lanes in cells `cell`, corner
    /// 1 by `upper`.
    fn gradients2(&mut self, noise: &Simplex, cell: [L::Int; 2], upper: L::Mask) -> Option<[[L; 2]; 3]>;
    /// Whether every coordinate is known to lie within ±[`SMALL`].
    fn small(&self) -> bool;
    /// 3D: the four corners' gradient indices for lanes in cells `cell`.
    /// Corner 1 steps along `i` or `j` where `steps[0]` says so, else along
    /// `k`; corner 2 along `i` and `j` where `steps[1]` say so, and along
    /// `k` unless both do.
    fn gradient_indices3(
        &mut self,
        noise: &Simplex,
        cell: [L::Int; 3],
        steps: [[L::Mask; 2]; 2],
    ) -> Option<[L::Int; 4]>;
}

/// No chunk tables: every lane hashes its own corners.
struct NoTables;

impl<L: Lanes> ChunkTables<L> for NoTables {
    #[inline(always)]
    fn gradients2(&mut self, _: &Simplex, _: [L::Int; 2], _: L::Mask) -> Option<[[L; 2]; 3]> {
        None
    }
    #[inline(always)]
    fn small(&self) -> bool {
        false
    }
    #[inline(always)]
    fn gradient_indices3(&mut self, _: &Simplex, _: [L::Int; 3], _: [[L::Mask; 2]; 2]) -> Option<[L::Int; 4]> {
        None
    }
}

/// A grid's chunk tables: where a chunk's lanes lie in lane 0's cell or the
/// next on each axis, the corners those cells reach are hashed once into a
/// small table each lane indexes, instead of hashed per lane. The same
/// entries, so the same bits (at every level: a lookup costs a load per
/// lane on AVX2 and the baseline, a chain of byte permutes on AVX-512).
/// `None` where the lanes spread further.
impl<B: BatchLanes> ChunkTables<B> for ChunkTable {
    #[inline(always)]
    fn small(&self) -> bool {
        self.small
    }

    /// The nine corners cells `(i0, j0)` to `(i0 + 1, j0 + 1)` reach; each
    /// lane's gradient component is then one permute, where five table
    /// lookups and six permutes were.
    #[inline(always)]
    fn gradients2(&mut self, noise: &Simplex, cell: [B::Int; 2], upper: B::Mask) -> Option<[[B; 2]; 3]> {
        if B::WIDTH == 16 {
            // One register per axis, corner (i0 + a, j0 + b) at entry 4b + a
            // for `a` up to 3: the table serves lanes up to two cells past
            // its origin along a row, so along a row of 2048 at 1/32 the
            // chunks make one every third or fourth, where they made one
            // each.
            let reach = [2, 1];
            let held = match self.cell {
                Some([i0, j0, _]) => cells_from::<B, 2>(cell, [i0, j0], reach),
                None => None,
            };
            let [di, dj] = match held {
                Some(d) => d,
                None => {
                    let origin = [cell[0].lane(0), cell[1].lane(0)];
                    let d = cells_from::<B, 2>(cell, origin, reach)?;
                    let gi = B::load_u8(&noise.corner_runs(origin[0] & 255, origin[1] & 255));
                    B::lookup16(&GRAD3[0], gi).store(self.gradients[0].as_flattened_mut());
                    B::lookup16(&GRAD3[1], gi).store(self.gradients[1].as_flattened_mut());
                    self.cell = Some([origin[0], origin[1], 0]);
                    d
                }
            };
            let [x, y] = &self.gradients;
            let (x, y) = (B::from_slice(x.as_flattened()), B::from_slice(y.as_flattened()));
            let e0 = dj.shl(2).add(di);
            // Corner 1 is (1, 0) above the diagonal, else (0, 1).
            let e1 = e0.add(B::Int::select(upper, B::Int::splat(1), B::Int::splat(4)));
            let e2 = e0.add_c(5);
            return Some([
                [B::permute(x, e0), B::permute(y, e0)],
                [B::permute(x, e1), B::permute(y, e1)],
                [B::permute(x, e2), B::permute(y, e2)],
            ]);
        }
        let ([i0, j0], [di, dj]) = chunk_cells::<B, 2>(cell)?;
        let (i0, j0) = (i0 & 255, j0 & 255);
        let renew = self.cell != Some([i0, j0, 0]);
        self.cell = Some([i0, j0, 0]);
        let [x, y] = &mut self.gradients;
        // Narrower registers: two halves of eight per axis, at the entries
        // of [`TABLE2_A`], so that each lookup is one permute of eight.
        if renew {
            let runs = noise.corner_runs(i0, j0);
            let mut entries = [0u8; 16];
            for (e, entry) in entries.iter_mut().enumerate() {
                *entry = runs[(4 * TABLE2_B[e] + TABLE2_A[e]) as usize];
            }
            for (half, indices) in entries.chunks_exact(8).enumerate() {
                let gi = B::load_u8(indices);
                B::lookup16(&GRAD3[0], gi).store(&mut x[half]);
                B::lookup16(&GRAD3[1], gi).store(&mut y[half]);
            }
        }
        let e0 = di.shl(1).add(dj);
        // Corner 1 is (1, 0) above the diagonal, else (0, 1).
        let e1 = e0.add(B::Int::select(upper, B::Int::splat(0), B::Int::splat(4)));
        let e2 = e0.add_c(4);
        Some([
            [B::lookup8(&x[0], e0), B::lookup8(&y[0], e0)],
            [B::lookup8(&x[1], e1), B::lookup8(&y[1], e1)],
            [B::lookup8(&x[0], e2), B::lookup8(&y[0], e2)],
        ])
    }

    /// The 27 corners cells `c0` to `c0 + (1, 1, 1)` reach, entry
    /// `a + 3b + 9c` for corner `c0 + (a, b, c)` (twelve lookups and nine
    /// runs per table, where each lane would take ten lookups); each lane's
    /// four corners read from it.
    #[inline(always)]
    fn gradient_indices3(
        &mut self,
        noise: &Simplex,
        cell: [B::Int; 3],
        steps: [[B::Mask; 2]; 2],
    ) -> Option<[B::Int; 4]> {
        let (c0, d) = chunk_cells::<B, 3>(cell)?;
        let c0 = [c0[0] & 255, c0[1] & 255, c0[2] & 255];
        if self.cell != Some(c0) {
            // Nine runs of three (written four at a time, each over the
            // last one's spare entry).
            let mut runs = [0u8; 32];
            for c in 0..3 {
                let pk = noise.perm.at(c0[2] + c);
                for b in 0..3 {
                    let at = (9 * c + 3 * b) as usize;
                    runs[at..at + 4].copy_from_slice(noise.run(c0[0], noise.perm.at(c0[1] + b + pk)));
                }
            }
            for (indices, entries) in runs.chunks_exact(B::WIDTH).zip(self.entries.chunks_exact_mut(B::WIDTH)) {
                B::store_int(B::load_u8(indices), entries);
            }
            self.cell = Some(c0);
        }
        let e0 = table_entry3(d);
        let splat = B::Int::splat;
        // Corner 1 steps along one axis: entry 1, 3 or 9 further; corner 2
        // along all but one: 13 less that one's.
        let [[i1, j1], [i2, j2]] = steps;
        let e1 = e0.add(B::Int::select(i1, splat(1), B::Int::select(j1, splat(3), splat(9))));
        let e2 = e0.add(B::Int::select(i2, B::Int::select(j2, splat(4), splat(10)), splat(12)));
        let mut gi = [splat(0); 4];
        for (g, e) in gi.iter_mut().zip([e0, e1, e2, e0.add_c(13)]) {
            *g = B::Int::lookup32(&self.entries, e);
        }
        Some(gi)
    }
}

/// A grid's chunks in row order, each chunk table kept for the next.
struct TableReuse<'a, const D: usize> {
    noise: &'a Simplex,
    memo: ChunkTable,
    /// Whether every coordinate of the grid is finite, so no chunk needs
    /// the NaN guard.
    finite: bool,
}

/// 1 where the mask is set, else 0.
#[inline(always)]
fn one_if<L: Lanes>(m: L::Mask) -> L::Int {
    L::Int::select(m, L::Int::splat(1), L::Int::splat(0))
}

/// `x − i` for an offset `i` ∈ {0, 1}, exact like the reference's `x0 - i1`.
#[inline(always)]
fn minus<L: Lanes>(x: L, i: L::Int) -> L {
    x - L::from_int(i)
}

/// `x − 1` where `m`, else `x` (`x − 0` is `x`, signed zeros included):
/// the reference's `x0 - i1` for `i1 = m ? 1 : 0`, without the conversion.
#[inline(always)]
fn minus_one_if<L: Lanes>(x: L, m: L::Mask) -> L {
    L::select(m, x - L::cst(1.0), x)
}

impl Simplex {
    #[inline(always)]
    fn corners2<L: Lanes>(&self, [xin, yin]: [L; 2], tables: &mut impl ChunkTables<L>) -> Corners<L, 2, 3> {
        let f2 = L::cst(0.5 * (3f64.sqrt() - 1.0));
        let g2 = L::cst((3.0 - 3f64.sqrt()) / 6.0);
        let s = (xin + yin) * f2;
        let (xs, ys) = (xin + s, yin + s);
        // The cell, its corner and that corner's skew, `(i + j)·G2`.
        let (i, j, fi, fj, t) = if tables.small() {
            // Within ±SMALL the cell is one conversion (rounding down) per
            // axis, and the float sum i + j is exact, as its conversion is.
            let (i, j) = (xs.floor_to_int(), ys.floor_to_int());
            let (fi, fj) = (L::from_int(i), L::from_int(j));
            (i, j, fi, fj, (fi + fj) * g2)
        } else {
            let (i, j) = (xs.floor().to_int_wrapping(), ys.floor().to_int_wrapping());
            (i, j, L::from_int(i), L::from_int(j), L::from_int(i.add(j)) * g2)
        };
        let x0 = xin - (fi - t);
        let y0 = yin - (fj - t);
        let upper = x0.gt(y0);
        let i1 = one_if::<L>(upper);
        let x1 = minus_one_if(x0, upper) + g2;
        let y1 = minus_one_if(y0, !upper) + g2;
        let x2 = x0 - L::cst(1.0) + L::cst(2.0) * g2;
        let y2 = y0 - L::cst(1.0) + L::cst(2.0) * g2;
        // The reference's `i & 255` and `j & 255` are left to the lookups,
        // which read an index's low byte.
        let g = match tables.gradients2(self, [i, j], upper) {
            Some(g) => g,
            None => {
                // perm[j + j1] is perm[j] or perm[j + 1], which corners 0
                // and 2 look up anyway: a select instead of a third lookup.
                let (p0, p1) = (self.perm.at(j), self.perm.at(j.add_c(1)));
                let gi0 = self.gradient_index(i.add(p0));
                let gi1 = self.gradient_index(i.add(i1).add(L::Int::select(upper, p0, p1)));
                let gi2 = self.gradient_index(i.add_c(1).add(p1));
                [Self::grad3(gi0), Self::grad3(gi1), Self::grad3(gi2)]
            }
        };
        Corners { p: [xin, yin], r2: 0.5, scale: 70.0, g, d: [[x0, y0], [x1, y1], [x2, y2]] }
    }

    #[inline(always)]
    fn corners3<L: Lanes>(&self, [xin, yin, zin]: [L; 3], tables: &mut impl ChunkTables<L>) -> Corners<L, 3, 4> {
        let f3 = L::cst(1.0 / 3.0);
        let g3 = L::cst(1.0 / 6.0);
        let s = (xin + yin + zin) * f3;
        let (xs, ys, zs) = (xin + s, yin + s, zin + s);
        // The cell, its corner and that corner's skew, `(i + j + k)·G3`,
        // as in 2D (`corners2`).
        let ([i, j, k], [fi, fj, fk], t) = if tables.small() {
            let (i, j, k) = (xs.floor_to_int(), ys.floor_to_int(), zs.floor_to_int());
            let (fi, fj, fk) = (L::from_int(i), L::from_int(j), L::from_int(k));
            ([i, j, k], [fi, fj, fk], (fi + fj + fk) * g3)
        } else {
            let (i, j, k) = (xs.floor().to_int_wrapping(), ys.floor().to_int_wrapping(), zs.floor().to_int_wrapping());
            ([i, j, k], [L::from_int(i), L::from_int(j), L::from_int(k)], L::from_int(i.add(j).add(k)) * g3)
        };
        let x0 = xin - (fi - t);
        let y0 = yin - (fj - t);
        let z0 = zin - (fk - t);
        // The reference's if/else ladder (with its `>=` tie rules) as masks.
        // The reference's if/else ladder (with its `>=` tie rules) as masks:
        // corner 1 steps along the largest axis, corner 2 along all but the
        // smallest (the ladder's six cases, ties included, since `>=` is
        // transitive where nothing is NaN; a NaN point's value is NaN).
        let (xy, yz, xz) = (x0.ge(y0), y0.ge(z0), x0.ge(z0));
        let (mi1, mj1) = (xy & xz, !xy & yz);
        let mk1 = !(mi1 | mj1);
        let (mi2, mj2) = (xy | (yz & xz), !xy | yz);
        let mk2 = !(mi2 & mj2);
        let (g3x2, g3x3) = (L::cst(2.0) * g3, L::cst(3.0) * g3);
        let d1 = [minus_one_if(x0, mi1) + g3, minus_one_if(y0, mj1) + g3, minus_one_if(z0, mk1) + g3];
        let d2 = [minus_one_if(x0, mi2) + g3x2, minus_one_if(y0, mj2) + g3x2, minus_one_if(z0, mk2) + g3x2];
        let one = L::cst(1.0);
        let d3 = [x0 - one + g3x3, y0 - one + g3x3, z0 - one + g3x3];
        // The reference's `& 255` on each axis is left to the lookups.
        let cell = [i, j];
        let (zero, unit) = (L::Int::splat(0), L::Int::splat(1));
        let gi = match tables.gradient_indices3(self, [i, j, k], [[mi1, mj1], [mi2, mj2]]) {
            Some(gi) => gi,
            None => {
                let (i1, j1) = (one_if::<L>(mi1), one_if::<L>(mj1));
                let (i2, j2) = (one_if::<L>(mi2), one_if::<L>(mj2));
                // perm[k + c] for c ∈ {0, 1}: looked up once each, then
                // selected per corner (two table lookups fewer per point).
                let (pk0, pk1) = (self.perm.at(k), self.perm.at(k.add_c(1)));
                [
                    self.hash3(cell, [zero; 2], pk0),
                    self.hash3(cell, [i1, j1], L::Int::select(mk1, pk1, pk0)),
                    self.hash3(cell, [i2, j2], L::Int::select(mk2, pk1, pk0)),
                    self.hash3(cell, [unit; 2], pk1),
                ]
            }
        };
        let g = [Self::grad3(gi[0]), Self::grad3(gi[1]), Self::grad3(gi[2]), Self::grad3(gi[3])];
        Corners { p: [xin, yin, zin], r2: 0.6, scale: 32.0, g, d: [[x0, y0, z0], d1, d2, d3] }
    }

    #[inline(always)]
    fn corners4<L: Lanes>(&self, p: [L; 4]) -> Corners<L, 4, 5> {
        let f4 = L::cst((5f64.sqrt() - 1.0) / 4.0);
        let g4 = L::cst((5.0 - 5f64.sqrt()) / 20.0);
        let s = (p[0] + p[1] + p[2] + p[3]) * f4;
        let mut c = [L::Int::splat(0); 4];
        for a in 0..4 {
            c[a] = (p[a] + s).floor().to_int_wrapping();
        }
        let t = L::from_int(c[0].add(c[1]).add(c[2]).add(c[3])) * g4;
        let mut x0 = p;
        for a in 0..4 {
            x0[a] = p[a] - (L::from_int(c[a]) - t);
        }
        // Rank each axis as the reference does: for every pair, the larger
        // (strictly) scores a point; on a tie the second axis scores.
        let mut rank = [L::Int::splat(0); 4];
        for a in 0..4 {
            for b in a + 1..4 {
                let a_wins = one_if::<L>(x0[a].gt(x0[b]));
                rank[a] = rank[a].add(a_wins);
                rank[b] = rank[b].add(L::Int::splat(1).sub(a_wins));
            }
        }
        // Corner k (1..=3) steps along the axes ranked at least 4 − k, and
        // sits at x0 − offset + k·G4.
        let mut o = [[L::Int::splat(0); 4]; 5];
        let mut d = [x0; 5];
        for k in 1..5 {
            let kg4 = if k == 1 { g4 } else { L::cst(k as f64) * g4 };
            for a in 0..4 {
                o[k][a] = if k == 4 { L::Int::splat(1) } else { one_if::<L>(L::Int::splat(3 - k as i32).lt(rank[a])) };
                d[k][a] = if k == 4 { x0[a] - L::cst(1.0) + kg4 } else { minus(x0[a], o[k][a]) + kg4 };
            }
        }
        let mut cell = c;
        for a in 0..4 {
            cell[a] = c[a].and_c(255);
        }
        // perm[c3 + o3] for o3 ∈ {0, 1}: looked up once each, then selected
        // per corner (three table lookups fewer per point).
        let (p0, p1) = (self.perm.at(cell[3]), self.perm.at(cell[3].add_c(1)));
        let mut g = [[L::cst(0.0); 4]; 5];
        for k in 0..5 {
            let inner = L::Int::select(o[k][3].eq(L::Int::splat(1)), p1, p0);
            g[k] = Self::grad4(self.hash4(cell, o[k], inner));
        }
        Corners { p, r2: 0.6, scale: 27.0, g, d }
    }

    /// 1D: Gustavson's `simplexnoise1234` definition (Perlin's permutation;
    /// kernel (1 − x²)⁴, gradients ±1…±8 from the hash, scale 0.25). With
    /// r² = 1 the kernel reaches zero exactly at the neighbouring node.
    #[inline(always)]
    fn corners1<L: Lanes>(&self, [x]: [L; 1]) -> Corners<L, 1, 2> {
        let fl = x.floor();
        let i0 = fl.to_int_wrapping();
        let x0 = x - fl;
        let mut g = [[L::cst(0.0)]; 2];
        for (k, gk) in g.iter_mut().enumerate() {
            let h = self.perm.at(i0.add_c(k as i32).and_c(255)).and_c(15);
            let m = L::from_int(h.and_c(7).add_c(1));
            *gk = [L::select(h.bit(3), -m, m)];
        }
        Corners { p: [x], r2: 1.0, scale: 0.25, g, d: [[x0], [x0 - L::cst(1.0)]] }
    }
}

macro_rules! impl_simplex {
    ($($d:literal => $corners:ident),*) => {$(
        impl Noise<$d> for Simplex {
            crate::grid::batch_entry!($d);
            #[inline(always)]
            fn sample<L: Lanes>(&self, p: [L; $d]) -> L {
                self.$corners(p).value()
            }
        }
        impl NoiseGradient<$d> for Simplex {
            #[inline(always)]
            fn sample_gradient<L: Lanes>(&self, p: [L; $d]) -> (L, [L; $d]) {
                self.$corners(p).value_gradient()
            }
        }
    )*};
}
impl_simplex!(1 => corners1, 4 => corners4);

/// 2D and 3D, whose chunks look their hashes up in a chunk table: grid
/// rows keep the last table for the next chunk ([`TableReuse`]).
macro_rules! impl_simplex_tabled {
    ($($d:literal => $corners:ident),*) => {$(
        impl Noise<$d> for Simplex {
            crate::grid::batch_entry!($d);
            #[inline(always)]
            fn sample<L: Lanes>(&self, p: [L; $d]) -> L {
                self.$corners(p, &mut NoTables).value()
            }
            #[inline(always)]
            fn fill_span<B: BatchLanes>(&self, span: Span<'_, $d>, out: &mut [f32]) {
                let finite = span.axes.all_finite();
                let memo = ChunkTable::empty(span.axes.all_within(SMALL));
                grid::fill_chunks::<_, B, $d>(&mut TableReuse { noise: self, memo, finite }, span, out)
            }
        }
        impl<B: BatchLanes> ChunkSampler<B, $d> for TableReuse<'_, $d> {
            #[inline(always)]
            fn sample(&mut self, p: [B; $d]) -> B {
                let corners = self.noise.$corners(p, &mut self.memo);
                if self.finite { corners.value_at_finite() } else { corners.value() }
            }
        }
        impl NoiseGradient<$d> for Simplex {
            #[inline(always)]
            fn sample_gradient<L: Lanes>(&self, p: [L; $d]) -> (L, [L; $d]) {
                self.$corners(p, &mut NoTables).value_gradient()
            }
        }
    )*};
}
impl_simplex_tabled!(2 => corners2, 3 => corners3);

// This module's batch drivers per instruction-set level (`grid::batch_clones!`).
crate::grid::batch_clones!();
