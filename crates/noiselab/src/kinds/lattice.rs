//! Lattice noise, written once: what a lattice kind defines (the records of
//! a cell's corners and how a record becomes a value) and everything built
//! from that — point evaluation, analytic gradients, and the grid fill that
//! hashes once per cell instead of once per point.
//!
//! A kind splits its corner function in three so that a grid can do each
//! part where it changes:
//!
//! * [`Lattice::corners`] hashes the cell (per cell and grid plane: the
//!   expensive part, table lookups);
//! * [`Lattice::bind`] folds in the offsets along axes 1.. (per grid row);
//! * [`Lattice::eval`] adds the offset along axis 0 (per point).
//!
//! Point evaluation runs the three in a row, so `eval(bind(corner))` *is*
//! the corner function and the grid fill performs, for every point, the
//! same IEEE operations on the same operands as [`Noise::get_f32`]: the
//! results are identical bit for bit, only the work is shared.
//!
//! Flat kinds (value noise) go further without leaving the bits: their
//! corners do not depend on the row, so the blend along axis 0 is the same
//! on every row of a plane of cells. The fill forms it once per plane and
//! writes the plane's rows from it, a block of columns and up to eight rows
//! at a time.
//!
//! [`Accuracy::Fast`] goes one step further for grids: along a row inside a
//! cell, a lattice noise is `P(u) + s(u)·Q(u)` with `P`, `Q` affine in the
//! position `u` and `s` the fade, so four coefficients per cell and row
//! replace the corners (three multiplies and three adds per point). Where
//! cells also hold several rows, the same is true down the columns, and the
//! coefficients are formed once per band of rows instead of once per row.
//!
//! [`Noise::get_f32`]: crate::Noise::get_f32

use super::{
    corner_bit, interpolate, interpolate_axis, interpolate_gradient, Columns, Entries, EntriesMut, MAX_CORNERS,
};
use crate::grid::{fill_pointwise, store_prefix, Accuracy, RowPiece, Span, Stores};
use crate::lanes::{BatchLanes, IntLanes, Lanes, StreamedRun};
use alloc::vec::Vec;

/// How many float and integer fields of a [`Corner`] are in use.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Fields {
    pub floats: usize,
    pub ints: usize,
}

impl Fields {
    /// Fields in all.
    const fn total(self) -> usize {
        self.floats + self.ints
    }
}

/// What a corner contributes, in whatever form a kind needs: up to four
/// floats and two integers per lane (unused fields stay zero and cost
/// nothing after inlining).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Corner<L: Lanes> {
    pub f: [L; 4],
    pub i: [L::Int; 2],
}

impl<L: Lanes> Corner<L> {
    /// All fields zero.
    #[inline(always)]
    pub fn zero() -> Self {
        Corner { f: [L::cst(0.0); 4], i: [L::Int::splat(0); 2] }
    }

    /// [`Lattice::bind`] for a gradient record (`f`: its components) whose
    /// value is the dot product with the offset (classic and modified
    /// noise): `f[0]` kept, `f[d]` becomes the term `g_d · offset_d`.
    #[inline(always)]
    pub fn bind_gradient<const D: usize>(self, offset: [L; D]) -> Self {
        let mut b = self;
        for d in 1..D {
            b.f[d] = self.f[d] * offset[d];
        }
        b
    }

    /// The term in x of a record whose `f[0]` is axis 0's gradient
    /// component or coefficient (classic, modified and 1D–3D improved
    /// noise): `x · f[0]`.
    #[inline(always)]
    pub fn gradient_x_term(&self, x: L) -> L {
        x * self.f[0]
    }

    /// The dot product of a [`Corner::bind_gradient`] record from its term
    /// in x ([`Corner::gradient_x_term`]), summed from axis 0 up as the
    /// reference C code does.
    #[inline(always)]
    pub fn gradient_dot_from_x_term<const D: usize>(&self, term: L) -> L {
        let mut dot = term;
        for d in 1..D {
            dot = dot + self.f[d];
        }
        dot
    }
}

/// A lattice noise: values from the 2^D corners of the cell around a point,
/// blended by a fade, axis 0 innermost.
pub(crate) trait Lattice<const D: usize>: Send + Sync {
    /// The cell of coordinate `x` (wrapping to 32 bits) and the position
    /// inside it.
    #[inline(always)]
    fn split<L: Lanes>(&self, x: L) -> (L::Int, L) {
        let fl = x.floor();
        (fl.to_int_wrapping(), x - fl)
    }

    /// How many of [`Corner`]'s fields [`Lattice::corners`]' records use
    /// (the grid fill stores and moves only these).
    const HASHED: Fields;
    /// How many of [`Corner`]'s fields [`Lattice::bind`]'s records use.
    const BOUND: Fields;

    /// Whether corners contribute constants (value noise): `bind` and
    /// `eval` ignore the offsets, so [`Accuracy::Fast`]'s row polynomial is
    /// `p + s(u)·q`, and the grid fill blends along axis 0 once per plane of
    /// cells rather than once per row.
    const FLAT: bool = false;

    /// Whether the field is ±0 at every integer point, as gradient noise
    /// is: there corner 0's offsets are all 0 (its value a dot product with
    /// zeros) and every fade is 0 (`a + 0·(b − a)` keeps corner 0's zero,
    /// up to its sign). The fractal grid fill leaves out octaves whose
    /// grid lies on integer points.
    const ZERO_AT_INTEGERS: bool = false;

    /// The blend weight of a position inside a cell.
    fn fade<L: Lanes>(&self, t: L) -> L;

    /// The derivative of [`Lattice::fade`].
    fn fade_deriv<L: Lanes>(&self, t: L) -> L;

    /// The records of the corners of `cell`; corner `c` is the upper corner
    /// on axis `d` when bit `d` of `c` is set. Entries from 2^D on are unused.
    /// A record must depend only on its lattice point (`cell` plus the
    /// corner's bits, wrapping): the grid fill hashes each point once and
    /// shares it between the cells that meet there.
    fn corners<L: Lanes>(&self, cell: [L::Int; D]) -> [Corner<L>; MAX_CORNERS];

    /// The record of lattice point `at` (corner 0 of its cell; the other
    /// corners' work is dead code once inlined).
    #[inline(always)]
    fn point<L: Lanes>(&self, at: [L::Int; D]) -> Corner<L> {
        self.corners(at)[0]
    }

    /// The records of lattice points `first, first + 1, …` along axis 0,
    /// one per lane, at `rest` on axes 1.. (`rest[0]` unused): [`Lattice::point`]
    /// there, which a kind may form faster knowing the points are consecutive.
    #[inline(always)]
    fn point_row<B: BatchLanes>(&self, first: i32, rest: [i32; D]) -> Corner<B> {
        self.point::<B>(row_points::<B, D>(first, rest))
    }

    /// A corner's record with the offsets along axes 1.. folded in
    /// (`offset[0]` is not read).
    fn bind<L: Lanes>(&self, corner: Corner<L>, offset: [L; D]) -> Corner<L>;

    /// The corner's value at offset `x` along axis 0, from a bound record.
    /// Must be affine in `x` for [`Accuracy::Fast`].
    #[inline(always)]
    fn eval<L: Lanes>(&self, bound: &Corner<L>, x: L) -> L {
        self.eval_from_x_term(bound, self.x_term(bound, x))
    }

    /// Whether [`Lattice::eval`] starts from a term in `x` alone
    /// ([`Lattice::x_term`]) formed from fields [`Lattice::bind`] passes
    /// through: then the rows of a grid in one cell share each corner's
    /// term at each column, and a batch of rows forms it once.
    const X_TERM: bool = false;

    /// The corner's term in `x` (`x` itself where the kind has none), from
    /// fields [`Lattice::bind`] leaves as they are.
    #[inline(always)]
    fn x_term<L: Lanes>(&self, _bound: &Corner<L>, x: L) -> L {
        x
    }

    /// [`Lattice::eval`] from the corner's [`Lattice::x_term`].
    fn eval_from_x_term<L: Lanes>(&self, bound: &Corner<L>, term: L) -> L;

    /// [`Lattice::eval`] up to the sign of a zero result, and bit for bit
    /// where the corner's offsets on axes 1.. are not all zero.
    #[inline(always)]
    fn eval_unsigned_zero<L: Lanes>(&self, bound: &Corner<L>, x: L) -> L {
        self.eval_unsigned_zero_from_x_term(bound, self.x_term(bound, x))
    }

    /// [`Lattice::eval_unsigned_zero`] from the corner's [`Lattice::x_term`].
    /// Kinds may drop guards that only keep a zero's sign: [`interpolate`]
    /// loses it for every corner but corner 0 (the upper end of a lerp, `a +
    /// t·(b − a)` with t ≥ +0, gives the same bits for b = +0 and b = −0, so
    /// a corner upper on some axis never shows its zero's sign).
    #[inline(always)]
    fn eval_unsigned_zero_from_x_term<L: Lanes>(&self, bound: &Corner<L>, term: L) -> L {
        self.eval_from_x_term(bound, term)
    }

    /// The corner's value at `offset`, up to the sign of a zero result:
    /// point evaluation's corners, corner 0 included except where the
    /// point's value is a zero (see [`sample`] and
    /// [`Lattice::eval_unsigned_zero`]). Kinds may form it without binding.
    #[inline(always)]
    fn value_unsigned_zero<L: Lanes>(&self, corner: Corner<L>, offset: [L; D]) -> L {
        self.eval_unsigned_zero(&self.bind(corner, offset), offset[0])
    }

    /// The gradient of the corner's function (its value at each unit
    /// offset: right for gradient kinds, whose corners are linear).
    #[inline(always)]
    fn corner_gradient<L: Lanes>(&self, corner: Corner<L>) -> [L; D] {
        let mut g = [L::cst(0.0); D];
        for k in 0..D {
            let mut e = [L::cst(0.0); D];
            e[k] = L::cst(1.0);
            g[k] = self.eval(&self.bind(corner, e), e[0]);
        }
        g
    }

    /// A constant factor applied to the blended value (and its gradient).
    #[inline(always)]
    fn scale(&self) -> f64 {
        1.0
    }
}

/// Lattice points `first, first + 1, …` along axis 0 (one per lane) at
/// `rest` on axes 1...
#[inline(always)]
pub(crate) fn row_points<B: BatchLanes, const D: usize>(first: i32, rest: [i32; D]) -> [B::Int; D] {
    let mut at = [B::Int::splat(0); D];
    at[0] = B::iota().add(B::Int::splat(first));
    for d in 1..D {
        at[d] = B::Int::splat(rest[d]);
    }
    at
}

/// Corner records holding only floats (`floats[c]` for corner `c`).
///
/// Kinds fill an array of their fields and build the records from it,
/// rather than zeroing 16 whole records and filling those in: LLVM calls
/// memset for such a zeroed array on every chunk, and records are 3 KiB on
/// AVX2 against 2 KiB of floats. 3D points on AVX2 (Zen 3): classic 26.5 →
/// 23.5 ns, modified 27.2 → 23.4. (Value noise measured slower this way and
/// keeps its loop.) The closure is too small not to inline.
#[inline(always)]
pub(crate) fn float_records<L: Lanes>(floats: &[[L; 4]; MAX_CORNERS]) -> [Corner<L>; MAX_CORNERS] {
    let zero = Corner::<L>::zero();
    core::array::from_fn(|c| Corner { f: floats[c], i: zero.i })
}

/// The offsets from corner `c` to a point at position `f` in its cell.
#[inline(always)]
fn offsets<L: Lanes, const D: usize>(f: [L; D], c: usize) -> [L; D] {
    let mut off = f;
    for d in 0..D {
        if (c >> d) & 1 == 1 {
            off[d] = f[d] - L::cst(1.0);
        }
    }
    off
}

/// Cells and positions of a point's coordinates.
#[inline(always)]
fn split_point<K: Lattice<D>, L: Lanes, const D: usize>(kind: &K, p: [L; D]) -> ([L::Int; D], [L; D]) {
    let mut cell = [L::Int::splat(0); D];
    let mut f = p;
    for d in 0..D {
        (cell[d], f[d]) = kind.split(p[d]);
    }
    (cell, f)
}

/// The fades' derivatives at a point's positions.
#[inline(always)]
fn fade_derivs<K: Lattice<D>, L: Lanes, const D: usize>(kind: &K, f: [L; D]) -> [L; D] {
    let mut s = f;
    for d in 0..D {
        s[d] = kind.fade_deriv(f[d]);
    }
    s
}

/// The fades of a point's positions.
#[inline(always)]
fn fades<K: Lattice<D>, L: Lanes, const D: usize>(kind: &K, f: [L; D]) -> [L; D] {
    let mut s = f;
    for d in 0..D {
        s[d] = kind.fade(f[d]);
    }
    s
}

#[inline(always)]
fn finish<K: Lattice<D>, L: Lanes, const D: usize>(kind: &K, v: L) -> L {
    if kind.scale() == 1.0 {
        v
    } else {
        v * L::cst(kind.scale())
    }
}

/// Point evaluation.
#[inline(always)]
pub(crate) fn sample<K: Lattice<D>, L: Lanes, const D: usize>(kind: &K, p: [L; D]) -> L {
    let (cell, f) = split_point(kind, p);
    let corners = kind.corners(cell);
    let mut v = [L::cst(0.0); MAX_CORNERS];
    for (c, value) in v.iter_mut().enumerate().take(1 << D) {
        *value = kind.value_unsigned_zero(corners[c], offsets(f, c));
    }
    let weights = fades(kind, f);
    let value = interpolate(v, weights);
    // The corners' zeros may have the wrong sign (`value_unsigned_zero`).
    // A sign of zero can change the result of `+`, `−` and `×` only where
    // that result is a zero, so it reaches a lerp chain's end only where
    // the end is a zero: there corner 0 is evaluated with its sign (the
    // only corner whose sign shows, `Lattice::eval_unsigned_zero`) and the
    // chain run again; also where it is NaN, whose bits stay as they were.
    let zero = L::cst(0.0);
    if L::any(!(value.lt(zero) | value.gt(zero))) {
        let off = offsets(f, 0);
        v[0] = kind.eval(&kind.bind(corners[0], off), off[0]);
        return finish(kind, interpolate(v, weights));
    }
    finish(kind, value)
}

/// Value and analytic gradient; the value is [`sample`]'s bit for bit.
#[inline(always)]
pub(crate) fn sample_gradient<K: Lattice<D>, L: Lanes, const D: usize>(kind: &K, p: [L; D]) -> (L, [L; D]) {
    let (cell, f) = split_point(kind, p);
    let corners = kind.corners(cell);
    let mut v = [L::cst(0.0); MAX_CORNERS];
    let mut g = [[L::cst(0.0); D]; MAX_CORNERS];
    for c in 0..(1 << D) {
        let off = offsets(f, c);
        v[c] = kind.eval(&kind.bind(corners[c], off), off[0]);
        g[c] = kind.corner_gradient(corners[c]);
    }
    let (value, grad) = interpolate_gradient(v, g, fades(kind, f), fade_derivs(kind, f));
    let mut scaled = grad;
    for d in 0..D {
        scaled[d] = finish(kind, grad[d]);
    }
    (finish(kind, value), scaled)
}

/// Store a record (`fields` of them, from field `base`) for entries
/// `at..at + WIDTH`.
#[inline(always)]
fn store_record<B: BatchLanes>(columns: &mut EntriesMut<'_>, base: usize, at: usize, r: &Corner<B>, fields: Fields) {
    for m in 0..fields.floats {
        columns.store(base + m, at, r.f[m]);
    }
    for m in 0..fields.ints {
        columns.store(base + fields.floats + m, at, B::from_bits(r.i[m]));
    }
}

/// Bind every lattice point of a plane's rows (row r hashed in slot
/// `slot_of[r]` of `hashed`) to the offsets of positions `f` on axes 1..,
/// into `bound` (row r's records from field r · BOUND).
#[inline(always)]
fn bind_plane<K: Lattice<D>, B: BatchLanes, const D: usize>(
    kind: &K,
    (hashed, slot_of): (&Columns, &[usize; MAX_CORNERS / 2]),
    f: [B; D],
    bound: &mut Columns,
    points: usize,
) {
    let rows = PointRows::<D>::PER_PLANE;
    let whole_lanes = points.div_ceil(B::WIDTH) * B::WIDTH;
    // One view of every slot and one of every bound row, checked once.
    let hashed = hashed.entries(rows * K::HASHED.total(), 0, whole_lanes);
    let mut bound = bound.entries_mut(rows * K::BOUND.total(), 0, whole_lanes);
    let mut offset_of = [[B::cst(0.0); D]; MAX_CORNERS / 2];
    // Each row's slot as a view of its own, so that the reads below check
    // no runtime field, and the loop bound in the views' own terms (below):
    // as `v + WIDTH ≤ whole_lanes` over one view, which a wrapping sum does
    // not tie to their `at ≤ width − WIDTH`, every read and store kept its
    // check. A 32² tile at 1/2 on AVX2 (callgrind): 40 → 22 instructions a
    // register of both rows.
    let mut slots = [hashed; MAX_CORNERS / 2];
    for (r, (o, view)) in offset_of.iter_mut().zip(&mut slots).enumerate().take(rows) {
        *o = offsets(f, 2 * r);
        *view = hashed.fields(slot_of[r] * K::HASHED.total(), K::HASHED.total());
    }
    // (`v ≤ whole_lanes − WIDTH`, not `v < points`: the same lanes.)
    let Some(last) = whole_lanes.checked_sub(B::WIDTH) else {
        return;
    };
    let mut v = 0;
    while v <= last {
        for (r, slot) in slots.iter().enumerate().take(rows) {
            let point = At { entries: slot, at: v }.record(0, 0, K::HASHED);
            store_record(&mut bound, r * K::BOUND.total(), v, &kind.bind(point, offset_of[r]), K::BOUND);
        }
        v += B::WIDTH;
    }
}

/// Where lanes find their records' fields. (Traits, not closures: a
/// closure that LLVM declines to inline would run outside the batch
/// driver's instruction-set clone.)
trait Source<B: BatchLanes> {
    /// Field `k` of each lane's entry, or (`next` = 1) of the entry after it.
    fn field(&self, k: usize, next: usize) -> B;

    /// Corner `c`'s record, from lattice points stored as rows of records
    /// (`fields` each): corner `c` is row `c / 2`, at the lane's cell's
    /// lower point on axis 0 or (odd `c`) the next one.
    #[inline(always)]
    fn corner(&self, c: usize, fields: Fields) -> Corner<B> {
        self.record((c >> 1) * fields.total(), c & 1, fields)
    }

    /// The record from field `base` (`fields` of them), of each lane's
    /// entry or the next.
    #[inline(always)]
    fn record(&self, base: usize, next: usize, fields: Fields) -> Corner<B> {
        let mut r = Corner::zero();
        for m in 0..fields.floats {
            r.f[m] = self.field(base + m, next);
        }
        for m in 0..fields.ints {
            r.i[m] = self.field(base + fields.floats + m, next).to_bits();
        }
        r
    }
}

/// Lanes at consecutive entries from `at` of a view checked once for a
/// whole row of them.
struct At<'a> {
    entries: &'a Entries<'a>,
    at: usize,
}

impl<B: BatchLanes> Source<B> for At<'_> {
    #[inline(always)]
    fn field(&self, k: usize, next: usize) -> B {
        self.entries.load(k, self.at + next)
    }
}

/// Every lane at one entry (and the next): its first `fields` fields,
/// bounds-checked once.
struct OneCell<'a>(Entries<'a>);

impl<'a> OneCell<'a> {
    /// Entry `cell` (and the next) of the first `fields` fields.
    #[inline(always)]
    fn new(columns: &'a Columns, cell: usize, fields: usize) -> Self {
        OneCell(columns.entries(fields, cell, 2))
    }
}

/// A source's fields from `base` on.
struct Shifted<'a, S> {
    source: &'a S,
    base: usize,
}

impl<B: BatchLanes, S: Source<B>> Source<B> for Shifted<'_, S> {
    #[inline(always)]
    fn field(&self, k: usize, next: usize) -> B {
        self.source.field(self.base + k, next)
    }
}

impl<B: BatchLanes> Source<B> for OneCell<'_> {
    #[inline(always)]
    fn field(&self, k: usize, next: usize) -> B {
        B::splat(self.0.get(k, next))
    }
}

/// Every lane at one cell's row polynomial ([`Accuracy::Fast`]): like
/// [`OneCell`], but each of the four fields checked as it is read, which
/// measured faster here than one check up front (the chunk is short, and
/// its checks merge): with `OneCell`, 3D improved fast took 0.39 instead of
/// 0.22 ns/sample.
struct OnePolynomial<'a> {
    from: &'a [f32],
    stride: usize,
}

impl<B: BatchLanes> Source<B> for OnePolynomial<'_> {
    #[inline(always)]
    fn field(&self, k: usize, next: usize) -> B {
        B::splat(self.from[k * self.stride + next])
    }
}

/// Every lane at one cell's corners, read once from another source and
/// held (in registers, once inlined) while the chunks of a run of columns
/// in that cell go by: the same operands as reading them chunk by chunk,
/// without the splats, loads and checks each chunk's reads repeat.
struct Held<B: BatchLanes> {
    corners: [Corner<B>; MAX_CORNERS],
    fields: Fields,
}

impl<B: BatchLanes> Held<B> {
    /// The `1 << D` corners of `from`, records of `fields`.
    #[inline(always)]
    fn new<const D: usize>(from: &impl Source<B>, fields: Fields) -> Self {
        let mut corners = [Corner::zero(); MAX_CORNERS];
        for (c, corner) in corners.iter_mut().enumerate().take(1 << D) {
            *corner = from.corner(c, fields);
        }
        Held { corners, fields }
    }
}

impl<B: BatchLanes> Source<B> for Held<B> {
    #[inline(always)]
    fn field(&self, k: usize, next: usize) -> B {
        let total = self.fields.total();
        let corner = &self.corners[2 * (k / total) + next];
        let m = k % total;
        if m < self.fields.floats {
            corner.f[m]
        } else {
            B::from_bits(corner.i[m - self.fields.floats])
        }
    }

    #[inline(always)]
    fn corner(&self, c: usize, _fields: Fields) -> Corner<B> {
        self.corners[c]
    }
}

/// Where [`Row::write_runs`] reads a run's corners, by the run's cell.
/// (A trait, not a closure: the closure was left out of line, a call per
/// run outside the instruction-set clone.)
trait RunCorners<B: BatchLanes> {
    fn held<const D: usize>(&self, cell: usize, fields: Fields) -> Held<B>;
}

/// Each cell's bound records in a [`Columns`] of `fields` fields
/// ([`OneCell`] at the cell).
struct CellRecords<'a> {
    columns: &'a Columns,
    fields: usize,
}

impl<B: BatchLanes> RunCorners<B> for CellRecords<'_> {
    #[inline(always)]
    fn held<const D: usize>(&self, cell: usize, fields: Fields) -> Held<B> {
        Held::new::<D>(&OneCell::new(self.columns, cell, self.fields), fields)
    }
}

/// Each lattice point's records bound for a batch of rows
/// ([`write_batch`]), at row `row` of the batch ([`BatchRow`] at the cell).
struct BatchRecords<'a> {
    table: &'a [f32],
    per_point: usize,
    row: usize,
}

impl<B: BatchLanes> RunCorners<B> for BatchRecords<'_> {
    #[inline(always)]
    fn held<const D: usize>(&self, cell: usize, fields: Fields) -> Held<B> {
        let span = self.per_point * 16;
        Held::new::<D>(
            &BatchRow { points: &self.table[cell * span..(cell + 2) * span], per_point: self.per_point, row: self.row },
            fields,
        )
    }
}

/// Lanes at up to 2·WIDTH consecutive entries from `first`: each field is
/// the two registers of those entries' values, permuted by `lane[next]`
/// (each lane's entry minus `first`, plus `next`). `NEAR`: the entries
/// and the next fit in one register, so one permute serves (on AVX2 a
/// two-register permute is two and a blend).
struct PerLane<'a, B: BatchLanes, const NEAR: bool> {
    entries: &'a Entries<'a>,
    first: usize,
    lane: [B::Int; 2],
}

impl<B: BatchLanes, const NEAR: bool> Source<B> for PerLane<'_, B, NEAR> {
    #[inline(always)]
    fn field(&self, k: usize, next: usize) -> B {
        let lo = self.entries.load(k, self.first);
        if NEAR {
            B::permute(lo, self.lane[next])
        } else {
            B::permute2(lo, self.entries.load(k, self.first + B::WIDTH), self.lane[next])
        }
    }
}

/// The cell, position and fade of each coordinate, into `cell`, `frac`
/// and `fade` (`padded` entries, whole lanes and at least the coordinates
/// rounded up to them; entries past them repeat the last coordinate's,
/// then 0).
#[inline(always)]
fn split_axis<K: Lattice<D>, B: BatchLanes, const D: usize>(
    kind: &K,
    coords: &[f32],
    (cell, frac, fade): (&mut Vec<i32>, &mut Vec<f32>, &mut Vec<f32>),
    padded: usize,
) {
    // Sized, not zeroed: the loops below write every entry, so a kept
    // vector of the same size (the next tile's) costs no memset.
    cell.resize(padded, 0);
    frac.resize(padded, 0.0);
    fade.resize(padded, 0.0);
    let (n, w) = (coords.len(), B::WIDTH);
    let mut k = 0;
    while k < n {
        let x = if k + w <= n {
            B::from_slice(&coords[k..])
        } else {
            let mut xk = [0f32; 16];
            for (j, x) in xk.iter_mut().enumerate().take(w) {
                *x = coords[(k + j).min(n - 1)];
            }
            B::from_slice(&xk)
        };
        let (c, f) = kind.split(x);
        B::store_int(c, &mut cell[k..]);
        f.store(&mut frac[k..]);
        kind.fade(f).store(&mut fade[k..]);
        k += w;
    }
    while k < padded {
        B::store_int(B::Int::splat(0), &mut cell[k..]);
        B::cst(0.0).store(&mut frac[k..]);
        B::cst(0.0).store(&mut fade[k..]);
        k += w;
    }
}

/// An axis's cells, positions and fades by index ([`split_axis`]).
type AxisRows<'a> = (&'a [i32], &'a [f32], &'a [f32]);

/// A lattice fill's vectors, kept by each thread between calls: a 32²
/// tile's fill allocated and freed ten of them (probe, 2D improved on
/// AVX2: keeping them, with the axes in one scratch buffer, 5 % fewer
/// instructions a tile). Taken whole, so a fill nested inside another
/// finds none kept and allocates its own.
#[derive(Default)]
struct Tables {
    /// The [`Columns`] of the fill: the point rows' hashed records, the
    /// rows' bound records ([`fill_bands`]: at v = 0, and `bound_upper` at
    /// v = 1), the fast rows' polynomials ([`fill_bands`]: the cells'
    /// half-blends; [`fill_row_batches`]: the chunks' terms in x) and a
    /// plane's blends.
    records: Vec<f32>,
    bound: Vec<f32>,
    bound_upper: Vec<f32>,
    coef: Vec<f32>,
    blends: Vec<f32>,
    /// Axis 0 by column: cell, position and fade.
    cell0: Vec<i32>,
    frac0: Vec<f32>,
    fade0: Vec<f32>,
    /// Runs of columns in one cell, and the chunks they are written in.
    runs: Vec<(usize, usize, usize)>,
    chunks: Vec<Chunk>,
    chunk_axis: Vec<ChunkAxis>,
    /// Short runs: each aligned chunk's cells.
    span_of: Vec<ChunkCells>,
    /// Flat kinds: the rows waiting in a [`Band`].
    plane_rows: Vec<(usize, [f32; 4])>,
    /// [`fill_bands`] and [`fill_row_batches`]: axis 1 by row (cell,
    /// position and fade); [`fill_bands`]: each chunk's band coefficients.
    cell1: Vec<i32>,
    frac1: Vec<f32>,
    fade1: Vec<f32>,
    band_coef: Vec<f32>,
    /// [`Stores::Streamed`]: the rows waiting to be copied out ([`Staging`]).
    staged: Vec<f32>,
}

crate::scratch::per_thread!(KEPT_TABLES: Tables);

impl crate::scratch::KeptVectors for Tables {
    fn held_bytes(&self) -> usize {
        use crate::scratch::bytes_of;
        let floats = [
            &self.records,
            &self.bound,
            &self.bound_upper,
            &self.coef,
            &self.blends,
            &self.frac0,
            &self.fade0,
            &self.frac1,
            &self.fade1,
            &self.band_coef,
            &self.staged,
        ];
        floats.into_iter().map(bytes_of).sum::<usize>()
            + bytes_of(&self.cell0)
            + bytes_of(&self.cell1)
            + bytes_of(&self.runs)
            + bytes_of(&self.chunks)
            + bytes_of(&self.chunk_axis)
            + bytes_of(&self.span_of)
            + bytes_of(&self.plane_rows)
    }
}

/// How many runs of equal cells the columns have.
#[inline(always)]
fn run_count(cells: &[i32]) -> usize {
    // Branch-free over pairs and inlined into the instruction set's clone,
    // so it vectorises (`windows` did not: 4 instructions a column).
    let next = cells.get(1..).unwrap_or_default();
    1 + next.iter().zip(cells).map(|(b, a)| usize::from(a != b)).sum::<usize>()
}

/// The end of the run of entries equal to `cells[start]`: whole lanes'
/// worth passed over at once, branch-free so that it vectorises (a band of
/// 32 rows in one cell, compared row by row, was 4 % of a fast 32² tile's
/// time on AVX-512), then entry by entry.
#[inline(always)]
fn run_end(cells: &[i32], start: usize, w: usize) -> usize {
    let cell = cells[start];
    let mut end = start + 1;
    while end + w <= cells.len() && cells[end..end + w].iter().fold(true, |all, &c| all & (c == cell)) {
        end += w;
    }
    while end < cells.len() && cells[end] == cell {
        end += 1;
    }
    end
}

/// Runs of equal cells among columns (`count` of them, from [`run_count`]),
/// as (start, end, cell − `min_cell`), into `runs` (replacing what it
/// held). Inlined into the instruction set's clone, where [`run_end`]'s
/// comparisons take whole registers.
#[inline(always)]
fn cell_runs(cells: &[i32], min_cell: i32, w: usize, count: usize, runs: &mut Vec<(usize, usize, usize)>) {
    runs.clear();
    runs.reserve(count);
    let mut start = 0;
    while start < cells.len() {
        let end = run_end(cells, start, w);
        runs.push((start, end, (cells[start] as i64 - min_cell as i64) as usize));
        start = end;
    }
}

/// A chunk of columns' cells: the smallest and largest, and whether they are
/// `first, first + 1, …` column by column.
#[derive(Clone, Copy)]
struct ChunkCells {
    first: usize,
    last: usize,
    consecutive: bool,
}

/// How a chunk's lanes reach their cells' records (lanes past the columns
/// are discarded, so a last, partial chunk reaches them as a whole one).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Reach {
    /// Lane j at entry `first + j`: plain loads.
    Consecutive,
    /// All within one register from `first`: one permute per field.
    Near,
    /// Within two registers: two permutes and a blend.
    Wide,
    /// Further apart (uneven or descending steps): a gather.
    Far,
}

impl ChunkCells {
    #[inline(always)]
    fn reach(&self, w: usize) -> Reach {
        let spread = self.last - self.first + 1;
        if self.consecutive {
            Reach::Consecutive
        } else if spread < w {
            Reach::Near
        } else if spread < 2 * w {
            Reach::Wide
        } else {
            Reach::Far
        }
    }
}

fn chunk_cells(cells: &[i32]) -> ChunkCells {
    let (first, last) = cell_span(cells);
    // Branch-free, so it vectorises.
    let consecutive = cells.iter().enumerate().fold(true, |all, (j, &c)| all & (c as usize == first + j));
    ChunkCells { first, last, consecutive }
}

/// The smallest and largest of some cells.
#[inline(always)]
fn cell_span(cells: &[i32]) -> (usize, usize) {
    let (lo, hi) = super::cell_range(cells);
    (lo as usize, hi as usize)
}

/// Lanes at any entries, each lane's fields gathered (`at[next]`).
struct Gathered<'a, B: BatchLanes> {
    columns: &'a Columns,
    at: [B::Int; 2],
}

impl<B: BatchLanes> Source<B> for Gathered<'_, B> {
    #[inline(always)]
    fn field(&self, k: usize, next: usize) -> B {
        B::gather(self.columns.field(k, 0), self.at[next])
    }
}

/// Lanes' worth of columns in one cell: columns `start..start + WIDTH`, of
/// which those before `end` are the cell's (the rest belong to later
/// chunks), in cell `cell`. (For [`fill_bands`] over cells narrower than
/// the lanes: aligned chunks, `cell` the first of their cells.)
#[derive(Clone, Copy)]
struct Chunk {
    start: usize,
    end: usize,
    cell: usize,
}

/// Rows of lattice points along axis 0 (point `v` of a row is cell
/// `min_cell + v`'s lower corner), hashed once and kept while the planes
/// of cells that use them go by. A row lives in the slot named by its
/// cells' parities on axes 1.., so a plane's rows take distinct slots and
/// those it shares with a neighbouring plane stay put. (Searched for in
/// twice as many slots, the slot's place changed from plane to plane and
/// the search's exits were mispredicted: a tenth of a 32² tile's time at
/// spacing 1/2, perf, AVX-512.)
struct PointRows<const D: usize> {
    records: Columns,
    /// Each slot's row: its cells on axes 1.. (`[0]` unused).
    key: [Option<[i32; D]>; MAX_CORNERS / 2],
}

impl<const D: usize> PointRows<D> {
    /// The rows of a plane of cells (`1 << (D − 1)`), and the slots.
    const PER_PLANE: usize = 1 << (D - 1);

    fn new(kept: &mut Vec<f32>, fields: Fields, points: usize) -> Self {
        PointRows {
            records: Columns::kept_in(kept, Self::PER_PLANE * fields.total(), points),
            key: [None; MAX_CORNERS / 2],
        }
    }

    /// For each row of the plane of `cell` (row r: upper on axis d + 1 when
    /// bit d of r is set), the slot holding it, hashing the rows not held.
    #[inline(always)]
    fn plane<K: Lattice<D>, B: BatchLanes>(
        &mut self,
        kind: &K,
        cell: [i32; D],
        min_cell: i32,
        points: usize,
    ) -> [usize; MAX_CORNERS / 2] {
        let mut slot_of = [0usize; MAX_CORNERS / 2];
        for (r, slot) in slot_of.iter_mut().enumerate().take(Self::PER_PLANE) {
            let mut want = [0i32; D];
            let mut s = 0;
            for d in 1..D {
                want[d] = cell[d].wrapping_add(corner_bit(r, d - 1));
                s |= ((want[d] & 1) as usize) << (d - 1);
            }
            *slot = s;
            if self.key[s] == Some(want) {
                continue;
            }
            let base = s * K::HASHED.total();
            let mut row = self.records.entries_mut(base + K::HASHED.total(), 0, points.div_ceil(B::WIDTH) * B::WIDTH);
            let mut v = 0;
            while v < points {
                let point = kind.point_row::<B>(min_cell.wrapping_add(v as i32), want);
                store_record(&mut row, base, v, &point, K::HASHED);
                v += B::WIDTH;
            }
            self.key[s] = Some(want);
        }
        slot_of
    }
}

/// The grid fill: each lattice point hashed once per row of points (kept
/// across planes of cells), bound once per grid row, evaluated per grid
/// point. Falls back to point evaluation where cells are too sparse for
/// that to pay (more cells than points).
#[inline(always)]
pub(crate) fn fill_span<K: Lattice<D> + crate::Noise<D>, B: BatchLanes, const D: usize>(
    kind: &K,
    span: Span<'_, D>,
    out: &mut [f32],
) {
    if fill_small_tile::<K, B, D>(kind, &span, out) {
        return;
    }
    let mut tables = KEPT_TABLES.take();
    fill_span_with::<K, B, D>(kind, span, out, &mut tables);
    KEPT_TABLES.keep(tables);
    if span.stores == Stores::Streamed {
        crate::lanes::stream_fence();
    }
}

/// [`fill_span`] with the thread's kept vectors.
#[inline(always)]
fn fill_span_with<K: Lattice<D> + crate::Noise<D>, B: BatchLanes, const D: usize>(
    kind: &K,
    span: Span<'_, D>,
    out: &mut [f32],
    tables: &mut Tables,
) {
    // The tables' vectors as `kept_*`: the names without go to the tables.
    let Tables {
        records: kept_records,
        bound: kept_bound,
        bound_upper: kept_bound_upper,
        coef: kept_coef,
        blends: kept_blends,
        cell0,
        frac0,
        fade0,
        runs,
        chunks,
        chunk_axis,
        span_of,
        plane_rows,
        cell1,
        frac1,
        fade1,
        band_coef,
        staged,
    } = tables;
    let w = B::WIDTH;
    let xs = span.axes.axis(0);
    let nx = xs.len();
    if out.is_empty() || nx == 0 {
        return;
    }
    // Columns this span touches.
    let (lo, hi) = span.columns(out.len());

    // Axis 0 once per span: cell, position and fade of each column.
    let cols = hi - lo;
    let padded = cols.div_ceil(w) * w + w;
    split_axis::<K, B, D>(kind, &xs[lo..hi], (cell0, frac0, fade0), padded);
    // Runs of equal cells; cells numbered from the smallest.
    let (min_cell, max_cell) = super::cell_range(&cell0[..cols]);
    let ncell = (max_cell as i64 - min_cell as i64 + 1) as usize;
    if ncell > 2 * cols + 64 {
        return fill_pointwise::<K, B, D>(kind, span, out);
    }
    // Splat a cell's record over whole lanes when runs of columns in one
    // cell fill them; permute per lane when they are short.
    let run_total = run_count(&cell0[..cols]);
    let long_runs = cols >= run_total * w;
    // Flat kinds blend along axis 0 once per plane of cells where planes
    // hold several rows: each row then only finishes the blend (in 2D, one
    // multiply and one add per point). Exact, so fast fills take it too.
    let by_plane = K::FLAT && D >= 2 && long_runs && {
        let ys = span.axes.axis(1);
        let planes = 1 + ys.windows(2).filter(|y| kind.split::<f32>(y[0]).0 != kind.split::<f32>(y[1]).0).count();
        ys.len() >= 2 * planes
    };
    // Fast: a polynomial per cell and row pays where cells hold whole lanes
    // of points; where they are narrower, building it costs more than the
    // exact evaluation it saves, so the fill is exact there.
    let fast = span.accuracy == Accuracy::Fast && long_runs && !by_plane;
    let whole_rows = lo == 0 && hi == nx && span.start.is_multiple_of(nx) && out.len().is_multiple_of(nx);
    // Fast, whole rows, and cells that hold several rows along axis 1:
    // down the columns, a band of rows at a time ([`fill_bands`]).
    // (Axis 1 by row, as axis 0 by column, kept for the bands.)
    let bands = fast && D >= 2 && whole_rows && tall_cells::<K, B, D>(kind, &span, (cell1, frac1, fade1), BAND_ROWS);
    // Whole rows of long runs, exact, with few enough lattice points that a
    // batch's bound records stay in L1 beside the rows: rows in batches,
    // each point's records bound for a batch at once ([`fill_row_batches`]).
    // (Past that, 2D improved over 2048² rows measured 0.32 → 0.40 ns/point
    // with batches: 17 KiB of records per batch.)
    let batches = D >= 2
        && long_runs
        && !fast
        && !by_plane
        && (ncell + 1) * PointRows::<D>::PER_PLANE * K::BOUND.total() <= BATCH_POINT_FIELDS
        && whole_rows;
    // Streamed: the bands, the batches and whole rows of long runs are
    // staged and copied out (the rest, plane blends included, store
    // plainly).
    let stage = span.stores == Stores::Streamed && whole_rows && long_runs && !by_plane && nx <= STAGE_VALUES;
    let mut staging = Staging::new(staged, stage, (nx, w));
    // Runs of columns in one cell, as (start, end, cell), where they are used.
    if long_runs {
        cell_runs(&cell0[..cols], min_cell, w, run_total, runs);
    } else {
        runs.clear();
    }
    // Lattice points along axis 0: the cells' lower corners and one more.
    let points = ncell + 1;
    let room = points + 3 * w;
    let rows = PointRows::<D>::PER_PLANE;
    let mut point_rows = PointRows::<D>::new(kept_records, K::HASHED, room);
    // Sized up front, as `runs` is, so that a thread's first fill grows
    // each kept vector once rather than push by push.
    let chunk_total = cols.div_ceil(w) + runs.len();
    chunks.clear();
    chunks.reserve(if long_runs { chunk_total } else { 0 });
    if long_runs {
        // Written in place over the kept entries (only lanes below `w` are
        // read, and long runs read no `lane`): built whole and pushed, each
        // cost a zeroed 200-byte record and its copy (callgrind, a 32² tile
        // of 2D improved on AVX2: 1.7 % of the exact fill's instructions,
        // 2.0 % of the fast one's).
        chunk_axis.resize(chunk_total, ChunkAxis::ZERO);
        let mut axes = chunk_axis.iter_mut();
        for &(start, end, cell) in runs.iter() {
            for (s, a) in (start..end).step_by(w).zip(&mut axes) {
                chunks.push(Chunk { start: s, end, cell });
                a.first = cell;
                a.x[..w].copy_from_slice(&frac0[s..s + w]);
                a.fade[..w].copy_from_slice(&fade0[s..s + w]);
            }
        }
        chunk_axis.truncate(chunks.len());
    } else {
        chunk_axis.clear();
        chunk_axis.reserve(chunk_total);
    }
    if batches || bands {
        if bands {
            let axis1 = (&cell1[..], &frac1[..], &fade1[..]);
            let kept = [kept_bound, kept_bound_upper, kept_coef, band_coef];
            fill_bands::<K, B, D>(
                kind,
                span,
                (out, &mut staging),
                (chunks, chunk_axis),
                &mut point_rows,
                (min_cell, points, false),
                (axis1, kept),
            );
        } else {
            // Axis 1 by row, for the batches' lanes.
            let ny = span.axes.size(1);
            split_axis::<K, B, D>(kind, span.axes.axis(1), (cell1, frac1, fade1), ny.div_ceil(w) * w + w);
            let axis1 = (&cell1[..], &frac1[..], &fade1[..]);
            let kept = (kept_bound, kept_coef);
            fill_row_batches::<K, B, D>(
                kind,
                span,
                (out, &mut staging),
                (chunks, chunk_axis),
                (&mut point_rows, kept),
                (min_cell, points),
                axis1,
            );
        }
        point_rows.records.keep_in(kept_records);
        return;
    }
    // Each row's bound records, field-major: the fields a cell's corners read.
    let bound_fields = rows * K::BOUND.total();
    let mut bound = Columns::kept_in(kept_bound, bound_fields, room);
    // For the per-lane path: cells counted from the smallest.
    for (j, c) in cell0[..padded].iter_mut().enumerate() {
        *c = if j < cols { (*c).wrapping_sub(min_cell) } else { 0 };
    }
    // Each aligned chunk of columns' cells, for the per-lane path.
    span_of.clear();
    if !long_runs {
        span_of.extend(cell0[..cols].chunks(w).map(chunk_cells));
    }
    // Whole rows whose chunks all reach their cells one way (a regular
    // grid finer than its lanes: one cell per column, or a few) run a loop
    // that knows it ([`fill_fine_rows`]), with each chunk's positions,
    // fades and lanes' cells stored with it.
    let reach = span_of.iter().map(|c| Some(c.reach(w))).reduce(|a, b| if a == b { a } else { None }).flatten();
    let fine = !long_runs && whole_rows && matches!(reach, Some(Reach::Consecutive | Reach::Near));
    let near = reach == Some(Reach::Near);
    let axis0 = (&cell0[..cols], &frac0[..], &fade0[..]);
    // Fast, with cells narrower than the lanes but holding several rows
    // (2D at 1/4; on AVX-512, at 1/8 where rows are wide): down the
    // columns too, each lane reading its own cell's coefficients. Not
    // where the row's lattice points fit in one register: there the exact
    // held fill beat the bands (32² tiles on AVX-512, probe, ns/sample: at
    // 1/8 0.76 against 1.00, at 1/4 0.78 against 1.12).
    let held = !long_runs && whole_rows && D >= 2 && points <= 2 * w;
    // (Asking splits axis 1, which the exact fine rows then keep: a 32²
    // tile at 1/2 split it twice, 2 % of the fast fill's instructions.)
    let ask_bands = fine && near && span.accuracy == Accuracy::Fast && D >= 2 && !(held && points <= w);
    if ask_bands && tall_cells::<K, B, D>(kind, &span, (cell1, frac1, fade1), narrow_band_rows::<B>(nx)) {
        fine_chunks::<B>(axis0, span_of, true, chunk_axis);
        chunks.extend(chunk_axis.iter().enumerate().map(|(k, a)| Chunk {
            start: k * w,
            end: (k * w + w).min(cols),
            cell: a.first,
        }));
        let axis1 = (&cell1[..], &frac1[..], &fade1[..]);
        // Back to the kept vector, which the bands take: held here, it
        // left them an empty one, so every call allocated their table
        // and freed this one (a malloc and a free per fBm tile, perf).
        bound.keep_in(kept_bound);
        let kept = [kept_bound, kept_bound_upper, kept_coef, band_coef];
        fill_bands::<K, B, D>(
            kind,
            span,
            (out, &mut staging),
            (chunks, chunk_axis),
            &mut point_rows,
            (min_cell, points, true),
            (axis1, kept),
        );
        point_rows.records.keep_in(kept_records);
        return;
    }
    // Whole rows of cells narrower than the lanes whose lattice points
    // fit in two registers (a 32² tile at 1/2 to 1/8 on AVX-512): the
    // points held in registers ([`fill_held_fine_rows`]), whatever the
    // chunks' reach.
    if held {
        fine_chunks::<B>(axis0, span_of, false, chunk_axis);
        let ny = span.axes.size(1);
        split_axis::<K, B, D>(kind, span.axes.axis(1), (cell1, frac1, fade1), ny.div_ceil(w) * w + w);
        let axis1 = (&cell1[..], &frac1[..], &fade1[..]);
        if points <= w {
            fill_held_fine_rows::<K, B, D, false>(
                kind,
                span,
                out,
                chunk_axis,
                &mut point_rows,
                (min_cell, points),
                axis1,
            );
        } else {
            fill_held_fine_rows::<K, B, D, true>(
                kind,
                span,
                out,
                chunk_axis,
                &mut point_rows,
                (min_cell, points),
                axis1,
            );
        }
        point_rows.records.keep_in(kept_records);
        bound.keep_in(kept_bound);
        return;
    }
    if fine {
        fine_chunks::<B>(axis0, span_of, true, chunk_axis);
        if D >= 2 && !ask_bands {
            let ny = span.axes.size(1);
            split_axis::<K, B, D>(kind, span.axes.axis(1), (cell1, frac1, fade1), ny.div_ceil(w) * w);
        }
        let axis1 = (&cell1[..], &frac1[..], &fade1[..]);
        fill_fine_rows::<K, B, D>(
            kind,
            span,
            out,
            chunk_axis,
            (&mut point_rows, &mut bound),
            (min_cell, points, near),
            axis1,
        );
        point_rows.records.keep_in(kept_records);
        bound.keep_in(kept_bound);
        return;
    }
    // Fast: each cell's row polynomial.
    let mut coef = Columns::kept_in(kept_coef, if fast { 4 } else { 0 }, room);
    // By plane: the plane's blends along axis 0, by column.
    let mut blends = Columns::kept_in(kept_blends, if by_plane { rows } else { 0 }, padded);
    // Slices from here on: reached through the kept vectors' headers, their
    // pointers and lengths were loaded again after stores (probe, 2D
    // 6-octave fBm: 2.6 % more instructions than with fresh vectors).
    let (chunks, chunk_axis, span_of) = (&chunks[..], &chunk_axis[..], &span_of[..]);
    let (cell0, frac0, fade0) = (&cell0[..], &frac0[..], &fade0[..]);
    let mut plane: Option<[i32; D]> = None;
    let mut slot_of = [0usize; MAX_CORNERS / 2];
    let mut band = Band { columns: (0, 0), rows: core::mem::take(plane_rows) };
    // Grids well past L2 (the whole grid's, not this span's: threads cut
    // a grid into smaller spans): ask for each chunk's line ahead of its
    // store.
    let mut grid_points = 1usize;
    for d in 0..D {
        grid_points = grid_points.saturating_mul(span.axes.size(d));
    }
    // (Staged rows store to L1.)
    let prefetch = grid_points >= PREFETCH_MIN_VALUES && !staging.on();

    for RowPiece { idx, first: i0, offset: o0, len: n } in span.rows(out.len()) {
        // Axes 1..: the same for the whole row.
        let (cell, f) = row_cells(kind, &span, idx);
        let new_plane = plane != Some(cell);
        if new_plane {
            slot_of = point_rows.plane::<K, B>(kind, cell, min_cell, points);
            plane = Some(cell);
        }
        // Bind the row's offsets to every point of the plane's rows.
        let (weights, fs) = row_lanes::<K, B, D>(kind, f);
        if new_plane || !by_plane {
            bind_plane::<K, B, D>(kind, (&point_rows.records, &slot_of), fs, &mut bound, points);
        }
        if by_plane {
            let columns = (i0 - lo, i0 - lo + n);
            if new_plane || band.columns != columns || band.rows.len() == Band::ROWS {
                band.write::<K, B, D>(kind, &blends, out, span.stores);
                band.columns = columns;
            }
            if new_plane {
                for (ch, axis) in chunks.iter().zip(chunk_axis) {
                    let rec = OneCell::new(&bound, ch.cell, bound_fields);
                    plane_blends(kind, axis.lanes::<B>(), &rec, &mut blends, ch.start);
                }
            }
            let mut row_weights = [0.0; 4];
            for d in 1..D {
                row_weights[d] = kind.fade(f[d]);
            }
            band.rows.push((o0, row_weights));
            continue;
        }
        if fast {
            // Fast: the weight of each pair of corners along axis 0 in the
            // blend over axes 1.. (pair k is upper on axis d + 1 when bit d
            // of k is set), and each cell's row polynomial.
            let mut pair_weights = [B::cst(1.0); MAX_CORNERS / 2];
            for (k, pw) in pair_weights.iter_mut().enumerate().take(rows) {
                for d in 1..D {
                    let s = weights[d];
                    *pw = *pw * if corner_bit(k, d - 1) == 1 { s } else { B::cst(1.0) - s };
                }
            }
            // Cells k.. read their entries and the next, within the table.
            let view = bound.entries(bound_fields, 0, bound.stride());
            let mut k = 0;
            while k < ncell {
                let cells = At { entries: &view, at: k };
                for (m, v) in polynomial(kind, &cells, &pair_weights, (0, 1)).into_iter().enumerate() {
                    coef.store(m, k, v);
                }
                k += w;
            }
        }
        // Exact points read their cells' corners, fast ones their cells'
        // polynomials.
        let records = if fast { &coef } else { &bound };

        // The points: for each run of columns in one cell, whole lanes.
        // Column s (from lo) is out[o0 + lo + s − i0]; lanes past the row's
        // end are overwritten by the next run or row, or not stored.
        let row = Row { frac: frac0, fade: fade0, weights, off_line: off_line(f) };
        let row_end = i0 + n - lo;
        let (a0, a1) = (i0 - lo, row_end);
        let whole = a0 == 0 && a1 == cols;
        match (long_runs, fast) {
            // Whole rows: every chunk, written where it starts.
            (true, false) if whole => {
                let records = CellRecords { columns: records, fields: bound_fields };
                let to = staging.target(&mut out[o0..]);
                row.write_runs(kind, (chunks, chunk_axis, None), &records, (to, prefetch));
                staging.flush::<B>(&mut out[o0..o0 + n]);
            }
            (true, true) if whole => {
                let to = staging.target(&mut out[o0..]);
                for (ch, axis) in chunks.iter().zip(chunk_axis) {
                    let (x, fade) = axis.lanes::<B>();
                    emit(
                        poly_at::<K, B, D>(
                            x,
                            fade,
                            &OnePolynomial { from: records.field(0, ch.cell), stride: records.stride() },
                        ),
                        &mut to[ch.start..],
                    );
                }
                staging.flush::<B>(&mut out[o0..o0 + n]);
            }
            // Part of a row: chunks clipped to it.
            (true, false) => {
                for ch in chunks {
                    let s = ch.start.max(a0);
                    if s < ch.end.min(a1) {
                        let rec = OneCell::new(records, ch.cell, bound_fields);
                        emit(row.exact(kind, s, &rec), &mut out[o0 + s - a0..]);
                    }
                }
            }
            (true, true) => {
                for ch in chunks {
                    let s = ch.start.max(a0);
                    if s < ch.end.min(a1) {
                        let coef = OnePolynomial { from: records.field(0, ch.cell), stride: records.stride() };
                        emit(row.poly::<K>(s, &coef), &mut out[o0 + s - a0..]);
                    }
                }
            }
            // Short runs (fast fills are exact here): lanes read their own cells.
            (false, _) => {
                // Corners read a cell's entry and the next one.
                let view = records.entries(bound_fields, 0, records.stride());
                let mut s = a0;
                while s < a1 {
                    // The chunk's cells (lanes past the columns are discarded).
                    let cells = if s % w == 0 { span_of[s / w] } else { chunk_cells(&cell0[s..(s + w).min(cols)]) };
                    let first = cells.first;
                    let at = B::load_int(&cell0[s..]);
                    let lane = at.sub(B::Int::splat(first as i32));
                    let lane = [lane, lane.add_c(1)];
                    let v = match cells.reach(w) {
                        Reach::Consecutive => row.exact(kind, s, &At { entries: &view, at: first }),
                        Reach::Near => row.exact(kind, s, &PerLane::<B, true> { entries: &view, first, lane }),
                        Reach::Wide => row.exact(kind, s, &PerLane::<B, false> { entries: &view, first, lane }),
                        Reach::Far => row.exact(kind, s, &Gathered { columns: records, at: [at, at.add_c(1)] }),
                    };
                    emit(v, &mut out[o0 + s - a0..]);
                    s += w;
                }
            }
        }
    }
    // Guarded so that kinds which are not flat do not compile the band.
    if by_plane {
        band.write::<K, B, D>(kind, &blends, out, span.stores);
    }
    *plane_rows = band.rows;
    point_rows.records.keep_in(kept_records);
    bound.keep_in(kept_bound);
    coef.keep_in(kept_coef);
    blends.keep_in(kept_blends);
}

/// Most values a [`Stores::Streamed`] band stages at a time, and the
/// widest rows a streamed fill stages (wider ones store plainly): 4 KiB.
/// Larger pieces drain less of their copy while the next is computed (see
/// [`StreamedRun`]).
const STAGE_VALUES: usize = 1024;

/// A [`Stores::Streamed`] fill's rows where they are not whole registers
/// in order ([`stream_band`]): written first to a buffer the caches hold,
/// then copied out past them ([`stream_copy`]). The row writers keep their
/// stores as they are (whole registers at any column, lanes past a row's
/// end that the next chunk overwrites), and the output's lines are never
/// read from memory.
///
/// [`stream_copy`]: crate::lanes::stream_copy
struct Staging<'a> {
    /// The buffer, or `None` where the fill stores plainly.
    buf: Option<&'a mut Vec<f32>>,
}

impl<'a> Staging<'a> {
    /// Staging in `buf` where `on`, for rows of `nx` values: room for a
    /// band's piece ([`STAGE_VALUES`], or a row), a batch of `w` rows and
    /// a register past either.
    #[inline(always)]
    fn new(buf: &'a mut Vec<f32>, on: bool, (nx, w): (usize, usize)) -> Self {
        if !on {
            return Staging { buf: None };
        }
        super::unwritten(buf, STAGE_VALUES.max(w * nx) + w);
        Staging { buf: Some(buf) }
    }

    /// Whether the fill stages its rows.
    #[inline(always)]
    fn on(&self) -> bool {
        self.buf.is_some()
    }

    /// Where to write values bound for the start of `out`: `out` itself,
    /// or the whole buffer (a register longer than what it stages).
    #[inline(always)]
    fn target<'b>(&'b mut self, out: &'b mut [f32]) -> &'b mut [f32] {
        match &mut self.buf {
            Some(buf) => buf,
            None => out,
        }
    }

    /// Copy the first `out.len()` staged values to `out` past the caches;
    /// nothing where the fill stores plainly.
    #[inline(always)]
    fn flush<B: BatchLanes>(&self, out: &mut [f32]) {
        if let Some(buf) = &self.buf {
            crate::lanes::stream_copy::<B>(&buf[..out.len()], out);
        }
    }
}

/// Up to WIDTH rows of one plane of cells, in one cell along axis 1 and at
/// one position on axes 2.., written together ([`write_batch`]).
struct RowBatch<'a, const D: usize> {
    /// How many rows.
    rows: usize,
    /// The rows' positions and fades along axis 1, from the first row on
    /// (whole lanes of entries: those past the batch are read, not used).
    frac: &'a [f32],
    fade: &'a [f32],
    /// The batch's positions on axes 2.. (`[0]` and `[1]` at 0).
    f: [f32; D],
}

/// Most fields of bound records (over all lattice points of a row) for
/// which [`fill_row_batches`] pays: 16 rows each, 8 KiB.
const BATCH_POINT_FIELDS: usize = 128;

/// Every lane at one row of a batch's bound points ([`fill_row_batches`]):
/// `points` holds a cell's two points, each as `per_point` fields (record
/// `r`'s field `m` at `r · BOUND + m`) of 16 rows.
struct BatchRow<'a> {
    points: &'a [f32],
    per_point: usize,
    row: usize,
}

impl<B: BatchLanes> Source<B> for BatchRow<'_> {
    #[inline(always)]
    fn field(&self, k: usize, next: usize) -> B {
        B::splat(self.points[(next * self.per_point + k) * 16 + self.row % 16])
    }
}

/// The exact fill of whole rows whose columns run in long runs of one
/// cell, up to WIDTH rows of one plane of cells at a time: each lattice
/// point's records are bound for all the batch's rows at once (one row per
/// lane: the same operations on the same operands as binding row by row),
/// then each row of the batch is written chunk by chunk from them. Row by row,
/// a short row (a 32² tile) paid a vector bind for two points, the round
/// trip through the bound table and the row's bookkeeping for two chunks.
/// Batches are cut from runs of rows in one cell along axis 1, whose
/// positions and fades come split in lanes (`cell1, frac1, fade1`), so a
/// row costs no split of its own and no step of a row iterator (a 32²
/// tile: 10 693 → 9 981 instructions on AVX2, callgrind; 0.464 → 0.423
/// ns/sample on AVX-512, medians of five alternating probe runs).
#[inline(always)]
fn fill_row_batches<K: Lattice<D>, B: BatchLanes, const D: usize>(
    kind: &K,
    span: Span<'_, D>,
    (out, staging): (&mut [f32], &mut Staging<'_>),
    (chunks, chunk_axis): (&[Chunk], &[ChunkAxis]),
    (point_rows, (kept_bound, terms)): (&mut PointRows<D>, (&mut Vec<f32>, &mut Vec<f32>)),
    (min_cell, points): (i32, usize),
    (cell1, frac1, fade1): AxisRows<'_>,
) {
    let nx = span.axes.size(0);
    let w = B::WIDTH;
    // Each point's bound records, 16 rows per field.
    let mut bound = Columns::kept_in(kept_bound, 1, points * PointRows::<D>::PER_PLANE * K::BOUND.total() * 16);
    let mut plane: Option<[i32; D]> = None;
    let mut slot_of = [0usize; MAX_CORNERS / 2];
    // Rows of a few whole chunks, each inside one cell (a tile inside a
    // cell, or across a few), are written by `write_held_rows`: how many
    // chunks, or 0.
    let aligned = chunks_aligned(chunks, w);
    let held = if aligned && nx == chunks.len() * w && matches!(chunks.len(), 1 | 2 | 4) { chunks.len() } else { 0 };
    for AxisRun { row, y0, y1, cell, f } in axis1_runs::<K, D>(kind, &span, cell1, out.len(), w) {
        if plane != Some(cell) {
            slot_of = point_rows.plane::<K, B>(kind, cell, min_cell, points);
            plane = Some(cell);
        }
        let mut y = y0;
        while y < y1 {
            let rows = (y1 - y).min(w);
            let at = (row + (y - y0)) * nx;
            let batch = RowBatch { rows, frac: &frac1[y..], fade: &fade1[y..], f };
            let to = &mut staging.target(&mut out[at..])[..rows * nx];
            write_batch::<K, B, D>(
                kind,
                &batch,
                (chunks, chunk_axis, held),
                (&point_rows.records, &slot_of, points),
                (&mut bound, terms),
                (to, nx),
            );
            staging.flush::<B>(&mut out[at..at + rows * nx]);
            y += rows;
        }
    }
    bound.keep_in(kept_bound);
}

/// Whether chunk k starts at column k · `w` for every k (runs of whole
/// registers: 2D at 1/32, 32² tiles; every narrow band), so that rows are
/// written a register at a time with no start to read per chunk.
#[inline(always)]
fn chunks_aligned(chunks: &[Chunk], w: usize) -> bool {
    chunks.iter().enumerate().fold(true, |all, (k, ch)| all & (ch.start == k * w))
}

/// A span's whole rows (`len` points of it), run by run of rows in one
/// cell along axis 1 and at one position on axes 2.. (`cell1`: each row's
/// cell along axis 1, from [`split_axis`]): the walk [`fill_row_batches`],
/// [`fill_fine_rows`], [`fill_held_fine_rows`] and [`fill_bands`] share.
/// In 1D (no axis 1, `cell1` unread) a run of one row.
#[inline(always)]
fn axis1_runs<'a, K: Lattice<D>, const D: usize>(
    kind: &'a K,
    span: &'a Span<'a, D>,
    cell1: &'a [i32],
    len: usize,
    w: usize,
) -> AxisRuns<'a, K, D> {
    let first_row = span.start / span.axes.size(0);
    AxisRuns { kind, span, cell1, w, first_row, next: first_row, end_row: first_row + len / span.axes.size(0) }
}

/// The runs of [`axis1_runs`]: grid rows `next..end_row` still to walk.
struct AxisRuns<'a, K, const D: usize> {
    kind: &'a K,
    span: &'a Span<'a, D>,
    cell1: &'a [i32],
    w: usize,
    first_row: usize,
    next: usize,
    end_row: usize,
}

/// A run of [`axis1_runs`]: rows `y0..y1` along axis 1, the first of them
/// `row` rows into the span, their cell on axes 1.. and their positions
/// on axes 2.. (axes 0 and 1 left at 0).
struct AxisRun<const D: usize> {
    row: usize,
    y0: usize,
    y1: usize,
    cell: [i32; D],
    f: [f32; D],
}

impl<K: Lattice<D>, const D: usize> Iterator for AxisRuns<'_, K, D> {
    type Item = AxisRun<D>;

    #[inline(always)]
    fn next(&mut self) -> Option<AxisRun<D>> {
        let r = self.next;
        if r >= self.end_row {
            return None;
        }
        if D == 1 {
            // One row, at 0 on every axis past the first.
            self.next = r + 1;
            return Some(AxisRun { row: r - self.first_row, y0: 0, y1: 1, cell: [0; D], f: [0.0; D] });
        }
        let idx = self.span.axes.row_indices(r);
        let y0 = idx[1];
        let y1 = run_end(&self.cell1[..self.span.axes.size(1).min(y0 + (self.end_row - r))], y0, self.w);
        let (mut cell, mut f) = ([0i32; D], [0f32; D]);
        cell[1] = self.cell1[y0];
        for d in 2..D {
            (cell[d], f[d]) = self.kind.split(self.span.axes.axis(d)[idx[d]]);
        }
        self.next = r + (y1 - y0);
        Some(AxisRun { row: r - self.first_row, y0, y1, cell, f })
    }
}

/// [`fill_row_batches`]' batch: every point's records bound for the
/// batch's rows, then the rows (`out`: the batch's, `nx` values each;
/// `held`: the rows are that many whole chunks of one cell, or 0).
#[inline(always)]
fn write_batch<K: Lattice<D>, B: BatchLanes, const D: usize>(
    kind: &K,
    batch: &RowBatch<'_, D>,
    (chunks, chunk_axis, held): (&[Chunk], &[ChunkAxis], usize),
    (hashed, slot_of, points): (&Columns, &[usize; MAX_CORNERS / 2], usize),
    (bound, terms): (&mut Columns, &mut Vec<f32>),
    (out, nx): (&mut [f32], usize),
) {
    let per_point = PointRows::<D>::PER_PLANE * K::BOUND.total();
    // The rows in lanes: positions on axis 1, one row a lane; on axes 2..
    // the batch's own in every lane, with their fades and whether they are
    // off the lattice lines there (axis 1 of `batch.f` is at 0).
    let (mut weights, mut fs) = row_lanes::<K, B, D>(kind, batch.f);
    fs[1] = B::from_slice(batch.frac);
    let off_rest = off_line(batch.f);
    // A loop, not `array::from_fn`: LLVM left that call out of line, outside
    // the batch driver's instruction-set clone (a tenth of a 32² tile's
    // instructions on AVX2, with a memcpy of the array).
    let mut offsets_of = [[B::cst(0.0); D]; MAX_CORNERS / 2];
    for (r, o) in offsets_of.iter_mut().enumerate().take(PointRows::<D>::PER_PLANE) {
        *o = offsets(fs, 2 * r);
    }
    let hashed_fields = PointRows::<D>::PER_PLANE * K::HASHED.total();
    let table = bound.field_mut(0, 0);
    for v in 0..points {
        let point = OneCell::new(hashed, v, hashed_fields);
        let slots = &mut table[v * per_point * 16..(v + 1) * per_point * 16];
        for (r, &slot) in slot_of.iter().enumerate().take(PointRows::<D>::PER_PLANE) {
            let b = kind.bind::<B>(point.record(slot * K::HASHED.total(), 0, K::HASHED), offsets_of[r]);
            for m in 0..K::BOUND.floats {
                b.f[m].store(&mut slots[(r * K::BOUND.total() + m) * 16..]);
            }
            for m in 0..K::BOUND.ints {
                B::from_bits(b.i[m]).store(&mut slots[(r * K::BOUND.total() + K::BOUND.floats + m) * 16..]);
            }
        }
    }
    let table = bound.field(0, 0);
    let records = BatchRecords { table, per_point, row: 0 };
    // The chunks' cells read where used: copied into an array, they became
    // a masked gather and a masked store that the first read of the array
    // waited on (about a tenth of a 32² tile's time on AVX-512, perf).
    let chunks_held = (chunk_axis, chunks);
    // Rows inside one cell read its corners once a row; across cells (a
    // chunk a cell on AVX-512 at 1/16) once a chunk.
    let one_cell = chunks[..held].iter().all(|ch| ch.cell == chunks[0].cell);
    let rest = (weights, off_rest);
    match (held, one_cell) {
        (1, _) => return write_held_rows::<K, B, D, 1, true>(kind, batch, chunks_held, &records, rest, out),
        (2, true) => return write_held_rows::<K, B, D, 2, true>(kind, batch, chunks_held, &records, rest, out),
        (2, false) => return write_held_rows::<K, B, D, 2, false>(kind, batch, chunks_held, &records, rest, out),
        (4, true) => return write_held_rows::<K, B, D, 4, true>(kind, batch, chunks_held, &records, rest, out),
        (4, false) => return write_held_rows::<K, B, D, 4, false>(kind, batch, chunks_held, &records, rest, out),
        _ => {}
    }
    // Each chunk's corners' terms in x, the same for every row of the
    // batch ([`Lattice::X_TERM`]): formed once, from its first row's.
    let corners = 1 << D;
    if K::X_TERM {
        // Every entry is written below: grown, never cleared.
        if terms.len() < chunks.len() * corners * B::WIDTH {
            terms.resize(chunks.len() * corners * B::WIDTH, 0.0);
        }
        for ((ch, axis), at) in chunks.iter().zip(chunk_axis).zip(terms.chunks_exact_mut(corners * B::WIDTH)) {
            let held = records.held::<D>(ch.cell, K::BOUND);
            for (t, to) in
                x_terms::<K, B, D>(kind, axis.lanes::<B>().0, &held).iter().zip(at.chunks_exact_mut(B::WIDTH))
            {
                t.store(to);
            }
        }
    }
    let formed = if K::X_TERM { Some(&terms[..]) } else { None };
    // Indices, not zipped iterators: see `write_aligned_band`.
    for j in 0..batch.rows {
        weights[1] = B::splat(batch.fade[j]);
        let row = Row { frac: &[], fade: &[], weights, off_line: off_rest || batch.frac[j] != 0.0 };
        let records = BatchRecords { table, per_point, row: j };
        let out = (&mut out[j * nx..(j + 1) * nx], false);
        row.write_runs(kind, (chunks, chunk_axis, formed), &records, out);
    }
}

/// [`write_batch`]'s rows where each is `N` (1, 2 or 4) whole chunks, each
/// inside one cell (`chunks`; `ONE_CELL`: all in the same), such as
/// a tile inside a cell or across a few: the chunks' positions and fades
/// held in registers down the batch, so a row costs its corners' splats
/// (once, or once a chunk), its points and its stores. (Through [`Row::write_runs`],
/// each row also paid the chunk loop's checks for a new cell and a partial
/// store, and kept its corners' addresses on the stack: a 32² tile inside a
/// cell took 9 980 instructions instead of 7 097 on AVX2, callgrind. On
/// AVX-512 the probe's medians gave 0.423 against 0.363 ns/sample in one
/// stop and 0.415 against 0.395 in the next, within a build's spread.)
#[inline(always)]
fn write_held_rows<K: Lattice<D>, B: BatchLanes, const D: usize, const N: usize, const ONE_CELL: bool>(
    kind: &K,
    batch: &RowBatch<'_, D>,
    (chunk_axis, chunks): (&[ChunkAxis], &[Chunk]),
    records: &BatchRecords<'_>,
    (mut weights, off_rest): ([B; D], bool),
    out: &mut [f32],
) {
    let w = B::WIDTH;
    // `held` is `chunks.len()`: this always takes the chunks.
    let Some(chunks) = chunks.first_chunk::<N>() else {
        debug_assert!(false, "write_batch holds {N} chunks a row, not {}", chunks.len());
        return;
    };
    // Each chunk's fades, and its corners' terms in x ([`Lattice::x_term`]),
    // the same for every row of the batch: formed from its first row's.
    let mut fades = [B::cst(0.0); N];
    let mut terms = [[B::cst(0.0); MAX_CORNERS]; N];
    let first = BatchRecords { row: 0, ..*records };
    for (k, (ch, axis)) in chunks.iter().zip(chunk_axis).enumerate() {
        let x;
        (x, fades[k]) = axis.lanes::<B>();
        terms[k] = x_terms::<K, B, D>(kind, x, &first.held::<D>(ch.cell, K::BOUND));
    }
    let axis = (&terms, &fades);
    for j in 0..batch.rows.min(out.len() / (N * w)) {
        weights[1] = B::splat(batch.fade[j]);
        let row = Row { frac: &[], fade: &[], weights, off_line: off_rest || batch.frac[j] != 0.0 };
        let records = BatchRecords { row: j, ..*records };
        let out = &mut out[j * N * w..(j + 1) * N * w];
        // `off_line` once a row, not once a chunk.
        if row.off_line {
            row.write_held::<K, N, true, ONE_CELL>(kind, axis, (&records, chunks), out);
        } else {
            row.write_held::<K, N, false, ONE_CELL>(kind, axis, (&records, chunks), out);
        }
    }
}

/// Each aligned chunk of a span's columns, for the fine rows: positions
/// and fades (`axis0`: cells counted from the smallest, by column;
/// positions and fades padded to whole lanes) and each lane's cell,
/// counted from the chunk's first (`relative`) or from the smallest.
#[inline(always)]
fn fine_chunks<B: BatchLanes>(
    (cell0, frac0, fade0): AxisRows<'_>,
    span_of: &[ChunkCells],
    relative: bool,
    chunk_axis: &mut Vec<ChunkAxis>,
) {
    let w = B::WIDTH;
    for (s, cells) in (0..cell0.len()).step_by(w).zip(span_of) {
        let first = if relative { cells.first } else { 0 };
        let mut a = ChunkAxis { first, ..ChunkAxis::ZERO };
        a.x[..w].copy_from_slice(&frac0[s..s + w]);
        a.fade[..w].copy_from_slice(&fade0[s..s + w]);
        let lanes = &cell0[s..(s + w).min(cell0.len())];
        for (l, &c) in a.lane.iter_mut().zip(lanes) {
            *l = c - first as i32;
        }
        chunk_axis.push(a);
    }
}

/// The exact fill of whole rows whose cells are narrower than a chunk (a
/// regular grid with fewer than WIDTH columns per cell: the finer octaves
/// of a fractal), every chunk reaching its cells one way (`near`: through
/// one permute per field; otherwise lane j at entry `first + j`). The
/// generic row loop's work and order, with its per-row and per-chunk
/// bookkeeping taken out: each chunk's lanes are found once per span, the
/// rows are walked by runs along axis 1 (`axis1`, split once per span; in
/// 1D, one run of one row), not split one by one (a 32² tile at 1/2 on
/// AVX2, callgrind: 22.6 → 22.1 instructions a sample), and a row on the
/// lattice lines picks its corner-0 evaluation once, not per chunk.
#[inline(always)]
fn fill_fine_rows<K: Lattice<D>, B: BatchLanes, const D: usize>(
    kind: &K,
    span: Span<'_, D>,
    out: &mut [f32],
    chunk_axis: &[ChunkAxis],
    (point_rows, bound): (&mut PointRows<D>, &mut Columns),
    (min_cell, points, near): (i32, usize, bool),
    (cell1, frac1, fade1): AxisRows<'_>,
) {
    let nx = span.axes.size(0);
    let bound_fields = PointRows::<D>::PER_PLANE * K::BOUND.total();
    // Consecutive chunks that start at whole registers (one cell a column:
    // every chunk but those after a skipped cell).
    let aligned = !near && chunk_axis.iter().all(|a| a.first % B::WIDTH == 0);
    for AxisRun { row, y0, y1, cell, f } in axis1_runs::<K, D>(kind, &span, cell1, out.len(), B::WIDTH) {
        let slot_of = point_rows.plane::<K, B>(kind, cell, min_cell, points);
        // Axes 2.. for the whole run; axis 1 row by row.
        let (mut weights, mut fs) = row_lanes::<K, B, D>(kind, f);
        let off_rest = off_line(f);
        for y in y0..y1 {
            let mut off = off_rest;
            if D >= 2 {
                fs[1] = B::splat(frac1[y]);
                weights[1] = B::splat(fade1[y]);
                off |= frac1[y] != 0.0;
            }
            bind_plane::<K, B, D>(kind, (&point_rows.records, &slot_of), fs, bound, points);
            let view = bound.entries(bound_fields, 0, bound.stride());
            let at = (row + (y - y0)) * nx;
            let out = &mut out[at..at + nx];
            if near {
                FineRow { points: NearPoints(&view), chunk_axis, weights }.write::<K>(kind, off, out);
            } else if aligned {
                FineRow { points: AlignedPointsAt(&view), chunk_axis, weights }.write::<K>(kind, off, out);
            } else {
                FineRow { points: PointsAt(&view), chunk_axis, weights }.write::<K>(kind, off, out);
            }
        }
    }
}

/// The exact fill of whole rows whose cells are narrower than a chunk and
/// whose lattice points along axis 0 fit in one register, or two (`TWO`):
/// the finer octaves of a fractal over a small tile (a 32² tile at 1/8,
/// 1/4 and 1/2 on AVX-512, at 1/4 on AVX2). Each plane's hashed point rows
/// are loaded into registers once; each row binds them there and every
/// chunk permutes its lanes' corners out of them, whatever its reach.
/// [`fill_fine_rows`] stores each row's bound records and loads them back
/// chunk by chunk: on a row of two chunks that traffic (and, before it
/// walked rows by runs, a split per row) outweighed the chunks.
#[inline(always)]
fn fill_held_fine_rows<K: Lattice<D>, B: BatchLanes, const D: usize, const TWO: bool>(
    kind: &K,
    span: Span<'_, D>,
    out: &mut [f32],
    chunk_axis: &[ChunkAxis],
    point_rows: &mut PointRows<D>,
    (min_cell, points): (i32, usize),
    (cell1, frac1, fade1): AxisRows<'_>,
) {
    let (nx, w) = (span.axes.size(0), B::WIDTH);
    let rows = PointRows::<D>::PER_PLANE;
    for AxisRun { row, y0, y1, cell, f } in axis1_runs::<K, D>(kind, &span, cell1, out.len(), w) {
        let slot_of = point_rows.plane::<K, B>(kind, cell, min_cell, points);
        // The plane's rows of points: row r's first register, and second.
        let view = point_rows.records.entries(rows * K::HASHED.total(), 0, 2 * w);
        let mut hashed = [[Corner::<B>::zero(); 2]; MAX_CORNERS / 2];
        for (held, &slot) in hashed.iter_mut().zip(&slot_of).take(rows) {
            for (j, h) in held.iter_mut().enumerate().take(if TWO { 2 } else { 1 }) {
                *h = At { entries: &view, at: j * w }.record(slot * K::HASHED.total(), 0, K::HASHED);
            }
        }
        let out = &mut out[row * nx..(row + y1 - y0) * nx];
        write_held_run::<K, B, D, TWO>(kind, &hashed, chunk_axis, (&frac1[y0..y1], &fade1[y0..y1], f), out);
    }
}

/// The rows of a run along axis 1 (`out`: whole rows, one for each of
/// `frac1` and `fade1`; `f`: the run's positions on axes 2..) from its
/// plane's hashed point rows held in registers (`hashed[r]`: plane row r's
/// first register, and its second where `TWO`): each row binds them there
/// and every chunk permutes its lanes' corners out of them. The rows of
/// [`fill_held_fine_rows`] and [`fill_small_tile`].
#[inline(always)]
fn write_held_run<K: Lattice<D>, B: BatchLanes, const D: usize, const TWO: bool>(
    kind: &K,
    hashed: &[[Corner<B>; 2]; MAX_CORNERS / 2],
    chunk_axis: &[ChunkAxis],
    (frac1, fade1, f): (&[f32], &[f32], [f32; D]),
    out: &mut [f32],
) {
    let Some(nx) = out.len().checked_div(frac1.len()) else {
        return;
    };
    // Axes 2.. for the whole run; axis 1 row by row.
    let (mut weights, mut fs) = row_lanes::<K, B, D>(kind, f);
    let off_rest = off_line(f);
    for ((&frac, &fade), out) in frac1.iter().zip(fade1).zip(out.chunks_exact_mut(nx)) {
        fs[1] = B::splat(frac);
        weights[1] = B::splat(fade);
        let points = bound_held::<K, B, D, TWO>(kind, hashed, fs);
        FineRow { points, chunk_axis, weights }.write::<K>(kind, off_rest || frac != 0.0, out);
    }
}

/// Where a fine row's chunks find their corners' bound records.
trait FinePoints<B: BatchLanes> {
    /// The records of a chunk's lanes' corners.
    fn chunk(&self, axis: &ChunkAxis) -> impl Source<B>;
}

/// Bound records in a row's table, each chunk's lanes within one register
/// from the chunk's first cell: one permute per field.
struct NearPoints<'a>(&'a Entries<'a>);

impl<B: BatchLanes> FinePoints<B> for NearPoints<'_> {
    #[inline(always)]
    fn chunk(&self, axis: &ChunkAxis) -> impl Source<B> {
        let lane = B::load_int(&axis.lane);
        PerLane::<B, true> { entries: self.0, first: axis.first, lane: [lane, lane.add_c(1)] }
    }
}

/// Bound records in a row's table, lane j of a chunk at its first cell
/// plus j: plain loads.
struct PointsAt<'a>(&'a Entries<'a>);

impl<B: BatchLanes> FinePoints<B> for PointsAt<'_> {
    #[inline(always)]
    fn chunk(&self, axis: &ChunkAxis) -> impl Source<B> {
        At { entries: self.0, at: axis.first }
    }
}

/// Bound records in a row's table, lane j of a chunk at its first cell
/// plus j, the first at a whole register: each next entry permuted out of
/// two aligned loads. (Loaded from `first + 1`, it straddles two of the
/// row's bind's stores, which a load cannot take forwarded while they are
/// in flight, as they are in rows as short as a 32² tile's.)
struct AlignedPointsAt<'a>(&'a Entries<'a>);

impl<B: BatchLanes> FinePoints<B> for AlignedPointsAt<'_> {
    #[inline(always)]
    fn chunk(&self, axis: &ChunkAxis) -> impl Source<B> {
        AlignedAt { entries: self.0, at: axis.first, next: B::iota().add_c(1) }
    }
}

/// [`AlignedPointsAt`]'s lanes: entries `at..at + WIDTH`, `at` a multiple
/// of the width, and the entries after them (`next`: each lane's plus one,
/// of the two registers from `at`).
struct AlignedAt<'a, B: BatchLanes> {
    entries: &'a Entries<'a>,
    at: usize,
    next: B::Int,
}

impl<B: BatchLanes> Source<B> for AlignedAt<'_, B> {
    #[inline(always)]
    fn field(&self, k: usize, next: usize) -> B {
        let lo = self.entries.load(k, self.at);
        if next == 0 {
            lo
        } else {
            B::permute2(lo, self.entries.load(k, self.at + B::WIDTH), self.next)
        }
    }
}

/// A row's bound records of one or two (`TWO`) registers of lattice
/// points per plane row, held ([`fill_held_fine_rows`]): each lane's corner
/// permuted out by its cell, counted from the span's smallest.
#[derive(Clone, Copy)]
struct HeldPoints<B: BatchLanes, const TWO: bool> {
    rows: [[Corner<B>; 2]; MAX_CORNERS / 2],
    fields: Fields,
}

/// One chunk's lanes over [`HeldPoints`].
struct HeldLanes<'a, B: BatchLanes, const TWO: bool> {
    points: &'a HeldPoints<B, TWO>,
    lane: [B::Int; 2],
}

impl<B: BatchLanes, const TWO: bool> FinePoints<B> for HeldPoints<B, TWO> {
    #[inline(always)]
    fn chunk(&self, axis: &ChunkAxis) -> impl Source<B> {
        let lane = B::load_int(&axis.lane);
        HeldLanes { points: self, lane: [lane, lane.add_c(1)] }
    }
}

impl<B: BatchLanes, const TWO: bool> Source<B> for HeldLanes<'_, B, TWO> {
    #[inline(always)]
    fn field(&self, k: usize, next: usize) -> B {
        let fields = self.points.fields;
        let [lo, hi] = self.points.rows[k / fields.total()].map(|r| {
            let m = k % fields.total();
            if m < fields.floats {
                r.f[m]
            } else {
                B::from_bits(r.i[m - fields.floats])
            }
        });
        if TWO {
            B::permute2(lo, hi, self.lane[next])
        } else {
            B::permute(lo, self.lane[next])
        }
    }
}

/// One row of the fine fills: where its chunks' corners come from, the
/// span's chunks and the row's fades on axes 1...
struct FineRow<'a, P, B: BatchLanes, const D: usize> {
    points: P,
    chunk_axis: &'a [ChunkAxis],
    weights: [B; D],
}

impl<P: FinePoints<B>, B: BatchLanes, const D: usize> FineRow<'_, P, B, D> {
    /// Every chunk of the row into `out` (the whole row); `off_line`: the
    /// row is off the lattice lines along axis 0 ([`corner_values`]),
    /// decided once a row, not once a chunk.
    #[inline(always)]
    fn write<K: Lattice<D>>(&self, kind: &K, off_line: bool, out: &mut [f32]) {
        if off_line {
            self.write_as::<K, true>(kind, out);
        } else {
            self.write_as::<K, false>(kind, out);
        }
    }

    #[inline(always)]
    fn write_as<K: Lattice<D>, const OFF_LINE: bool>(&self, kind: &K, out: &mut [f32]) {
        let w = B::WIDTH;
        let full = out.len() / w;
        let mut whole = out.chunks_exact_mut(w);
        for (axis, out) in self.chunk_axis.iter().zip(&mut whole) {
            store_prefix(self.chunk::<K, OFF_LINE>(kind, axis), out);
        }
        let tail = whole.into_remainder();
        if !tail.is_empty() {
            store_prefix(self.chunk::<K, OFF_LINE>(kind, &self.chunk_axis[full]), tail);
        }
    }

    #[inline(always)]
    fn chunk<K: Lattice<D>, const OFF_LINE: bool>(&self, kind: &K, axis: &ChunkAxis) -> B {
        let (x, fade) = axis.lanes::<B>();
        let values = corner_values::<K, B, D, OFF_LINE>(kind, x, &self.points.chunk(axis));
        let mut weights = self.weights;
        weights[0] = fade;
        finish(kind, interpolate(values, weights))
    }
}

/// Fewest rows of one cell along axis 1, on average, for which
/// [`fill_bands`] pays (its per-band work costs about what a few rows of
/// points do).
const BAND_ROWS: usize = 4;

/// Fewest rows of one cell along axis 1, on average, for which
/// [`fill_bands`] pays where cells are narrower than a register (each lane
/// reading its own cell's coefficients) in rows of `nx` columns:
/// [`BAND_ROWS`], but half a register's lanes (8 on AVX-512) where rows
/// are wider than a block of columns. Against sixteen lanes, which read a
/// chunk's cells for the exact rows with one permute a field, a wide
/// band's per-cell work (half-blends, then each chunk's coefficients,
/// across the whole row) no longer pays at four rows. 2D improved fast at
/// 1/4 (cells 4 × 4 points), 32 rows, AVX-512, ns/point, three alternating
/// probe runs each (medians), bands against exact rows: 32 columns
/// 1.00 against 1.24–1.26, 64: 0.63–0.64 against 0.88, 256: 0.47–0.49
/// against 0.54, 512: 0.51 against 0.49–0.50, 1024: 0.84–0.88 against
/// 0.50, 2048: 0.89–0.92 against 0.57–0.70. Over 2048 columns with 8
/// rows a cell the two were level (cells 4 × 8), or the bands ahead
/// (8 × 8); on AVX2 the bands were not behind at four rows (2048
/// columns, minima 0.85–0.90 against 0.89–1.11). 6-octave fBm fast over
/// 2048² at 1/32, whose fourth octave is at 1/4, medians of five
/// alternating runs: 3.94–4.57 → 3.48–4.24 (32² tiles of it: no change).
#[inline(always)]
fn narrow_band_rows<B: BatchLanes>(nx: usize) -> usize {
    if nx > BAND_BLOCK_COLUMNS {
        BAND_ROWS.max(B::WIDTH / 2)
    } else {
        BAND_ROWS
    }
}

/// Whether cells along axis 1 hold `min_rows` rows or more on average,
/// for [`fill_bands`]; axis 1 split into `cell1, frac1, fade1` by the way.
#[inline(always)]
fn tall_cells<K: Lattice<D>, B: BatchLanes, const D: usize>(
    kind: &K,
    span: &Span<'_, D>,
    (cell1, frac1, fade1): (&mut Vec<i32>, &mut Vec<f32>, &mut Vec<f32>),
    min_rows: usize,
) -> bool {
    let ny = span.axes.size(1);
    split_axis::<K, B, D>(kind, span.axes.axis(1), (cell1, frac1, fade1), ny.div_ceil(B::WIDTH) * B::WIDTH);
    ny >= min_rows * run_count(&cell1[..ny])
}

/// Most rows [`fill_small_tile`] takes: its rows' positions and fades
/// live on the stack.
const ONE_CELL_ROWS: usize = 64;

/// The fill of a small whole 2D grid of a non-flat kind (a game's 16² to
/// 64² tile), with no kept tables: what the general fill does for it, with
/// the lattice points held in registers and the axes on the stack. A 32²
/// tile spent about three quarters of its time around its rows in the
/// general fill (perf, AVX-512: splitting and scanning its axes, building
/// its chunks and runs, hashing and binding through the tables), and the
/// octaves of a fractal tile walked four of its paths, more machine code
/// than the instruction cache holds (performance-history, stop 73).
///
/// Rows of one to [`HELD_BAND_CHUNKS`] whole chunks, up to
/// [`ONE_CELL_ROWS`] of them, whose lattice points along axis 0 fit in two
/// registers. Exact inside one cell, rows of one, two or four chunks:
/// [`write_batch`]'s held rows, batch by batch. Otherwise, run by run of
/// rows in one cell along axis 1 ([`small_tile_runs`]): exact,
/// [`fill_held_fine_rows`]' rows ([`write_held_run`]), one walk for every
/// spacing, so that a fractal's octaves run one compact path rather than
/// the general fill's several (a 32² fBm-6 tile on AVX-512, probe, ns/sample:
/// 4.06–4.25 → 3.08–3.19; callgrind on AVX2, 4096 tiles: 292 → 260
/// million instructions, L1 instruction misses 2.12 → 1.46 million).
/// [`Accuracy::Fast`] takes that walk too, with what the general fill
/// chooses for the same grid ([`fast_small_tile`]), so that a fast tile
/// equals the same points of a larger grid: [`fill_bands`]' bands
/// ([`write_held_bands`]: the same operations on the same operands) or
/// the exact held rows; where the general fill would take its row
/// polynomials instead, the tile is left to it.
/// Returns false, having written nothing, where the span is not such a
/// grid.
#[inline(always)]
fn fill_small_tile<K: Lattice<D>, B: BatchLanes, const D: usize>(
    kind: &K,
    span: &Span<'_, D>,
    out: &mut [f32],
) -> bool {
    let w = B::WIDTH;
    if D != 2 || K::FLAT || span.stores != Stores::Cached {
        return false;
    }
    let (xs, ys) = (span.axes.axis(0), span.axes.axis(1));
    let (nx, ny) = (xs.len(), ys.len());
    let chunks = nx / w;
    let fast = span.accuracy == Accuracy::Fast;
    if !(1..=HELD_BAND_CHUNKS).contains(&chunks)
        || nx != chunks * w
        || !(1..=ONE_CELL_ROWS).contains(&ny)
        || span.start != 0
        || out.len() != nx * ny
    {
        return false;
    }
    // Most grids this does not take leave here, before any split (split
    // first, each of a 32² fBm-6 tile's five octaves across cells paid
    // about 390 instructions more: callgrind, AVX2). An axis runs one way,
    // so its ends' cells bound its span of cells from below.
    let (Some(&x0), Some(&x1)) = (xs.first(), xs.last()) else {
        return false;
    };
    let ends = (i64::from(kind.split::<f32>(x0).0) - i64::from(kind.split::<f32>(x1).0)).unsigned_abs();
    if ends + 2 > 2 * w as u64 {
        return false;
    }
    // Axis 0 by chunk and axis 1 by row, as [`split_axis`] splits them.
    let mut axis0 = [ChunkAxis::ZERO; HELD_BAND_CHUNKS];
    let mut cells = [0i32; 16 * HELD_BAND_CHUNKS];
    for (k, a) in axis0.iter_mut().enumerate().take(chunks) {
        let (c, f) = kind.split(B::from_slice(&xs[k * w..]));
        B::store_int(c, &mut cells[k * w..]);
        f.store(&mut a.x);
        kind.fade(f).store(&mut a.fade);
    }
    let (mut frac1, mut fade1, mut cells1) = ([0f32; ONE_CELL_ROWS], [0f32; ONE_CELL_ROWS], [0i32; ONE_CELL_ROWS]);
    // (`r + w ≤ ONE_CELL_ROWS`: r < ny ≤ ONE_CELL_ROWS, both multiples of w.)
    for r in (0..ny).step_by(w) {
        let mut yr = [0f32; 16];
        for (j, y) in yr.iter_mut().enumerate().take(w) {
            *y = ys[(r + j).min(ny - 1)];
        }
        let (c, f) = kind.split(B::from_slice(&yr));
        B::store_int(c, &mut cells1[r..]);
        f.store(&mut frac1[r..]);
        kind.fade(f).store(&mut fade1[r..]);
    }
    // The span of cells along axis 0 (not from its ends alone: past ±2³¹
    // the cells wrap).
    let (min_cell, max_cell) = super::cell_range(&cells[..nx]);
    let cell1 = cells1[0];
    let one_cell = min_cell == max_cell && cells1[..ny].iter().fold(true, |all, &c| all & (c == cell1));
    let axis0 = &mut axis0[..chunks];
    if one_cell && !fast && chunks != 3 {
        // The cell's lattice points as [`PointRows::plane`] hashes them:
        // row r along axis 0 from the cell's lower point, its lanes 0 and
        // 1 the cell's corners 2r and 2r + 1.
        let mut hashed = [Corner::<B>::zero(); 2];
        for (r, h) in hashed.iter_mut().enumerate() {
            let mut row = [0i32; D];
            row[1] = cell1.wrapping_add(r as i32);
            *h = fields_of(kind.point_row::<B>(min_cell, row), K::HASHED);
        }
        one_cell_rows::<K, B, D>(kind, &hashed, axis0, (&frac1, &fade1, ny), out);
        return true;
    }
    // Lattice points along axis 0: the cells' lower points and one more.
    let points = (i64::from(max_cell) - i64::from(min_cell) + 2) as u64;
    if points > 2 * w as u64 {
        return false;
    }
    // Each lane's cell, counted from the smallest ([`HeldLanes`]).
    for (k, a) in axis0.iter_mut().enumerate() {
        for (l, &c) in a.lane.iter_mut().zip(&cells[k * w..(k + 1) * w]) {
            *l = c.wrapping_sub(min_cell);
        }
    }
    // (A `match` on `fast`, not `bool::then`: its closure was left out of
    // line, outside the batch driver's instruction-set clone.)
    let bands = match fast {
        true => match fast_small_tile::<B>(axis0, (&cells[..nx], &cells1[..ny]), points as usize) {
            Some(bands) => bands,
            None => return false,
        },
        false => false,
    };
    let rows = (&cells1[..ny], &frac1[..ny], &fade1[..ny]);
    match (points <= w as u64, bands) {
        (true, false) => small_tile_runs::<K, B, D, false, false>(kind, axis0, min_cell, rows, out),
        (false, false) => small_tile_runs::<K, B, D, true, false>(kind, axis0, min_cell, rows, out),
        (true, true) => small_tile_runs::<K, B, D, false, true>(kind, axis0, min_cell, rows, out),
        (false, true) => small_tile_runs::<K, B, D, true, true>(kind, axis0, min_cell, rows, out),
    }
    true
}

/// What [`fill_span_with`] does with a fast small tile of whole chunks
/// (`axis0`, each lane's cell counted from the smallest; `cells`, `cells1`:
/// each column's and row's cell) whose `points` lattice points along axis
/// 0 fit in two registers, decided as it decides: `Some(true)` for its
/// bands (cells holding whole chunks, or narrower cells that every chunk
/// reaches within one register, with points past one register; either
/// with enough rows a cell), `Some(false)` for its exact held rows, `None`
/// for its row polynomials (cells holding whole chunks but few rows).
#[inline(always)]
fn fast_small_tile<B: BatchLanes>(
    axis0: &[ChunkAxis],
    (cells, cells1): (&[i32], &[i32]),
    points: usize,
) -> Option<bool> {
    let w = B::WIDTH;
    let long_runs = cells.len() >= run_count(cells) * w;
    let min_rows = if long_runs { BAND_ROWS } else { narrow_band_rows::<B>(cells.len()) };
    let tall = cells1.len() >= min_rows * run_count(cells1);
    if long_runs {
        return tall.then_some(true);
    }
    // A loop, not `Iterator::all`: LLVM left `all` out of line, outside
    // the instruction-set clone (482 instructions of a fast fBm-6 32² tile,
    // callgrind).
    let mut near = true;
    for a in axis0 {
        near &= chunk_cells(&a.lane[..w]).reach(w) == Reach::Near;
    }
    Some(tall && near && points > w)
}

/// [`fill_small_tile`]'s rows across cells, run by run of rows in one cell
/// along axis 1: the plane's two rows of lattice points hashed as
/// [`PointRows::plane`] hashes them (from the smallest cell along axis 0;
/// one register each, or two where `TWO`), then its rows: exact
/// ([`write_held_run`]), or, where `BANDS`, as one band ([`write_held_bands`]).
#[inline(always)]
fn small_tile_runs<K: Lattice<D>, B: BatchLanes, const D: usize, const TWO: bool, const BANDS: bool>(
    kind: &K,
    axis0: &[ChunkAxis],
    min_cell: i32,
    (cells1, frac1, fade1): (&[i32], &[f32], &[f32]),
    out: &mut [f32],
) {
    let (nx, w) = (axis0.len() * B::WIDTH, B::WIDTH);
    let mut y0 = 0;
    // The last plane's upper row of points, and its cell: the next plane
    // up's lower row. (Kept apart from `hashed`, which lives in registers
    // within a run; held across runs, all of it was zeroed on the stack.)
    let mut upper: Option<(i32, [Corner<B>; 2])> = None;
    while let Some(&cell) = cells1.get(y0) {
        let y1 = run_end(cells1, y0, w);
        let mut hashed = [[Corner::<B>::zero(); 2]; MAX_CORNERS / 2];
        for (r, held) in hashed.iter_mut().enumerate().take(PointRows::<D>::PER_PLANE) {
            let mut row = [0i32; D];
            row[1] = cell.wrapping_add(r as i32);
            match upper {
                Some((c, points)) if r == 0 && c == row[1] => *held = points,
                _ => {
                    for (j, h) in held.iter_mut().enumerate().take(if TWO { 2 } else { 1 }) {
                        *h = fields_of(kind.point_row::<B>(min_cell.wrapping_add((j * w) as i32), row), K::HASHED);
                    }
                }
            }
        }
        upper = Some((cell.wrapping_add(1), hashed[1]));
        let (frac, fade) = (&frac1[y0..y1], &fade1[y0..y1]);
        let to = &mut out[y0 * nx..y1 * nx];
        if BANDS {
            write_held_bands::<K, B, D, TWO>(kind, &hashed, axis0, (frac, fade), to);
        } else {
            write_held_run::<K, B, D, TWO>(kind, &hashed, axis0, (frac, fade, [0.0; D]), to);
        }
        y0 = y1;
    }
}

/// One band of [`small_tile_runs`] ([`Accuracy::Fast`]): [`fill_bands`]'
/// band of a 2D plane with every table held in registers. The plane's
/// point rows (`hashed`) bound at v = 0 and v = 1 as [`bind_plane`] binds
/// them; each cell's four half-blend polynomials, the cells in lanes
/// (register j: cells j · WIDTH on), from its corners permuted out of the
/// points; each chunk's band coefficients from its lanes' cells'
/// half-blends, permuted out by [`ChunkAxis::lane`] (all lanes the same
/// cell where cells hold whole chunks, as [`fill_bands`]' splat reads it).
/// The same operations on the same operands, lane by lane, as
/// [`fill_bands`], so the same bits.
#[inline(always)]
fn write_held_bands<K: Lattice<D>, B: BatchLanes, const D: usize, const TWO: bool>(
    kind: &K,
    hashed: &[[Corner<B>; 2]; MAX_CORNERS / 2],
    axis0: &[ChunkAxis],
    rows: (&[f32], &[f32]),
    out: &mut [f32],
) {
    let w = B::WIDTH;
    // Two plain locals, not an array of them: held in an array, the
    // points were zeroed and read through the stack (a fast 32² tile took
    // twice its time, 15 % of it in memset: perf, AVX-512).
    let at_row = |v: f64| {
        let mut fs = [B::cst(0.0); D];
        fs[1] = B::cst(v);
        fs
    };
    let lower = bound_held::<K, B, D, TWO>(kind, hashed, at_row(0.0));
    let upper = bound_held::<K, B, D, TWO>(kind, hashed, at_row(1.0));
    let weights = half_blend_weights::<K, B, D>(kind, [0.0; D]);
    let mut halves = [[B::cst(0.0); 16]; 2];
    for (j, to) in halves.iter_mut().enumerate().take(if TWO { 2 } else { 1 }) {
        let lane = B::iota().add_c((j * w) as i32);
        for (h, weights) in weights.iter().enumerate() {
            let cells = HeldLanes { points: if h & 1 == 0 { &lower } else { &upper }, lane: [lane, lane.add_c(1)] };
            to[4 * h..4 * h + 4].copy_from_slice(&polynomial(kind, &cells, weights, (h >> 1, 2)));
        }
    }
    let mut band = [[B::cst(0.0); 4]; HELD_BAND_CHUNKS];
    for (c, axis) in band.iter_mut().zip(axis0) {
        let lanes = HeldHalves::<B, TWO> { halves: &halves, lane: B::load_int(&axis.lane) };
        *c = band_coefficients(half_blends::<K, B, D>(axis.lanes(), &lanes));
    }
    match axis0.len() {
        1 => write_band_rows::<B, 1>(out, rows, &[band[0]]),
        2 => write_band_rows::<B, 2>(out, rows, &[band[0], band[1]]),
        3 => write_band_rows::<B, 3>(out, rows, &[band[0], band[1], band[2]]),
        _ => write_band_rows::<B, 4>(out, rows, &band),
    }
}

/// A plane's point rows held in registers (`hashed`) bound at the
/// positions `fs` within their cells, as [`bind_plane`] binds them: a row
/// of [`write_held_run`], a band edge of [`write_held_bands`].
#[inline(always)]
fn bound_held<K: Lattice<D>, B: BatchLanes, const D: usize, const TWO: bool>(
    kind: &K,
    hashed: &[[Corner<B>; 2]; MAX_CORNERS / 2],
    fs: [B; D],
) -> HeldPoints<B, TWO> {
    let mut bound = HeldPoints::<B, TWO> { rows: [[Corner::zero(); 2]; MAX_CORNERS / 2], fields: K::BOUND };
    for (row, (held, b)) in hashed.iter().zip(&mut bound.rows).enumerate().take(PointRows::<D>::PER_PLANE) {
        let offsets = offsets(fs, 2 * row);
        for (h, b) in held.iter().zip(b).take(if TWO { 2 } else { 1 }) {
            *b = kind.bind(*h, offsets);
        }
    }
    bound
}

/// Each cell's half-blend polynomials in registers ([`write_held_bands`]:
/// register j's lane l for cell j · WIDTH + l), read at each lane's cell.
struct HeldHalves<'a, B: BatchLanes, const TWO: bool> {
    halves: &'a [[B; 16]; 2],
    lane: B::Int,
}

impl<B: BatchLanes, const TWO: bool> Source<B> for HeldHalves<'_, B, TWO> {
    #[inline(always)]
    fn field(&self, k: usize, _next: usize) -> B {
        if TWO {
            B::permute2(self.halves[0][k], self.halves[1][k], self.lane)
        } else {
            B::permute(self.halves[0][k], self.lane)
        }
    }
}

/// Most fields of a lattice point's records bound for a batch of a 2D
/// grid's rows: two rows of records of up to six fields.
const ONE_CELL_POINT_FIELDS: usize = 2 * 6;

/// [`fill_small_tile`]'s exact rows: batches of up to WIDTH rows, each
/// with the cell's two points bound for its rows as [`write_batch`] binds
/// them (in a table on the stack), then written by [`write_held_rows`].
#[inline(always)]
fn one_cell_rows<K: Lattice<D>, B: BatchLanes, const D: usize>(
    kind: &K,
    hashed: &[Corner<B>; 2],
    axis0: &[ChunkAxis],
    (frac1, fade1, ny): (&[f32; ONE_CELL_ROWS], &[f32; ONE_CELL_ROWS], usize),
    out: &mut [f32],
) {
    let (w, nx) = (B::WIDTH, axis0.len() * B::WIDTH);
    let per_point = PointRows::<D>::PER_PLANE * K::BOUND.total();
    debug_assert!(per_point <= ONE_CELL_POINT_FIELDS);
    let mut chunks = [Chunk { start: 0, end: nx, cell: 0 }; 4];
    for (k, ch) in chunks.iter_mut().enumerate() {
        ch.start = k * w;
    }
    let mut table = [0f32; 2 * ONE_CELL_POINT_FIELDS * 16];
    let (weights, mut fs) = row_lanes::<K, B, D>(kind, [0.0; D]);
    for y in (0..ny).step_by(w) {
        // (`y + w ≤ ONE_CELL_ROWS`, as in [`fill_small_tile`].)
        fs[1] = B::from_slice(&frac1[y..]);
        for (v, slots) in table.chunks_exact_mut(per_point * 16).take(2).enumerate() {
            for (r, &point) in hashed.iter().enumerate() {
                let b = kind.bind::<B>(lane_of(point, v), offsets(fs, 2 * r));
                for m in 0..K::BOUND.floats {
                    b.f[m].store(&mut slots[(r * K::BOUND.total() + m) * 16..]);
                }
                for m in 0..K::BOUND.ints {
                    B::from_bits(b.i[m]).store(&mut slots[(r * K::BOUND.total() + K::BOUND.floats + m) * 16..]);
                }
            }
        }
        let rows = (ny - y).min(w);
        let batch = RowBatch { rows, frac: &frac1[y..], fade: &fade1[y..], f: [0.0; D] };
        let records = BatchRecords { table: &table, per_point, row: 0 };
        let to = &mut out[y * nx..(y + rows) * nx];
        let rest = (weights, false);
        match axis0.len() {
            1 => write_held_rows::<K, B, D, 1, true>(kind, &batch, (axis0, &chunks[..1]), &records, rest, to),
            2 => write_held_rows::<K, B, D, 2, true>(kind, &batch, (axis0, &chunks[..2]), &records, rest, to),
            _ => write_held_rows::<K, B, D, 4, true>(kind, &batch, (axis0, &chunks[..4]), &records, rest, to),
        }
    }
}

/// A record's first `fields` fields, the rest zero: what the grid fill's
/// tables hold of it ([`store_record`], read back by [`Source::record`]).
#[inline(always)]
fn fields_of<B: BatchLanes>(r: Corner<B>, fields: Fields) -> Corner<B> {
    let mut kept = Corner::zero();
    kept.f[..fields.floats].copy_from_slice(&r.f[..fields.floats]);
    kept.i[..fields.ints].copy_from_slice(&r.i[..fields.ints]);
    kept
}

/// Lane `j` of a record, in every lane. (Permutes in loops: `map` over
/// the fields, and `lane`, were left out of line, calls outside the batch
/// driver's instruction-set clone.)
#[inline(always)]
fn lane_of<B: BatchLanes>(r: Corner<B>, j: usize) -> Corner<B> {
    let at = B::Int::splat(j as i32);
    let mut spread = r;
    for v in spread.f.iter_mut() {
        *v = B::permute(*v, at);
    }
    for v in spread.i.iter_mut() {
        *v = B::permute(B::from_bits(*v), at).to_bits();
    }
    spread
}

/// [`Accuracy::Fast`]'s fill of whole rows where cells hold several rows
/// along axis 1. A band is the rows of one cell along axis 1 at one
/// position on axes 2..; inside it every column's value is `P(v) +
/// s(v)·Q(v)`, with `P`, `Q` affine in the position `v` along axis 1 and
/// `s` its fade. So a band costs, per point, three multiplies, three adds
/// and the loads of its column's four coefficients (which stay in cache
/// across the band's rows), and the coefficients are formed once per band
/// rather than once per row. They come from the row polynomials along
/// axis 0 ([`polynomial`]) of the cell's lower and upper corners on axis 1,
/// bound at `v` = 0 and 1: since every corner is linear in its offsets,
/// those four half-blends fix the band. `narrow`: cells narrower than the
/// lanes (the fine rows' chunks), each lane reading its own cell's
/// half-blends.
#[inline(always)]
fn fill_bands<K: Lattice<D>, B: BatchLanes, const D: usize>(
    kind: &K,
    span: Span<'_, D>,
    (out, staging): (&mut [f32], &mut Staging<'_>),
    (chunks, chunk_axis): (&[Chunk], &[ChunkAxis]),
    point_rows: &mut PointRows<D>,
    (min_cell, points, narrow): (i32, usize, bool),
    ((cell1, frac1, fade1), [kept_lower, kept_upper, kept_halves, coef]): (AxisRows<'_>, [&mut Vec<f32>; 4]),
) {
    let nx = span.axes.size(0);
    let w = B::WIDTH;
    let rows = PointRows::<D>::PER_PLANE;
    let ncell = points - 1;
    let room = point_rows.records.stride();
    // The plane's rows' records bound at v = 0 and at v = 1.
    let mut bound = [
        Columns::kept_in(kept_lower, rows * K::BOUND.total(), room),
        Columns::kept_in(kept_upper, rows * K::BOUND.total(), room),
    ];
    // Each cell's four half-blends, four coefficients each.
    let mut halves = Columns::kept_in(kept_halves, 16, room);
    // Each chunk's band coefficients, chunk by chunk.
    super::unwritten(coef, chunks.len() * 4 * w);
    // Chunks before `whole` store all their lanes inside the row; the
    // rest, at its end, store as many as fit.
    let whole = chunks.partition_point(|ch| ch.start + w <= nx);
    // Each row stored a register at a time, where it can be.
    let aligned = chunks_aligned(chunks, w);
    // Rows wider than a block are written as many short streams at once
    // (one per row of the band), which the hardware prefetchers do not
    // follow: ask for the lines a few rows ahead. (At 512 columns or
    // fewer a band is one stream; prefetching there measured slower: 512²
    // at 1/32, 0.113 → 0.122 ns/point.)
    // (Streamed, no line is read before its store.)
    let prefetch = nx > BAND_BLOCK_COLUMNS && !staging.on();
    let held_band = aligned && nx == whole * w && whole <= HELD_BAND_CHUNKS;
    // Streamed, a band of rows of whole registers within one block is one
    // run of registers, streamed as they are computed ([`stream_band`]);
    // other bands are staged, a piece of up to STAGE_VALUES values (or a
    // row) at a time.
    let direct = staging.on() && aligned && nx == whole * w && !held_band && nx <= BAND_BLOCK_COLUMNS;
    let staged = staging.on() && !direct;
    let piece_rows = if staged { (STAGE_VALUES / nx).max(1) } else { usize::MAX };
    // The band: rows y0..y1 of one plane, in one cell along axis 1.
    for AxisRun { row, y0, y1, cell, f } in axis1_runs::<K, D>(kind, &span, cell1, out.len(), w) {
        let slot_of = point_rows.plane::<K, B>(kind, cell, min_cell, points);
        // Bind the plane's rows at the band's offsets on axes 2.., with
        // v = 0 and v = 1 on axis 1.
        let mut fs = [B::cst(0.0); D];
        for d in 2..D {
            fs[d] = B::splat(f[d]);
        }
        for (v, table) in bound.iter_mut().enumerate() {
            fs[1] = B::cst(v as f64);
            bind_plane::<K, B, D>(kind, (&point_rows.records, &slot_of), fs, table, points);
        }
        let pair_weights = half_blend_weights::<K, B, D>(kind, f);
        let views =
            [bound[0].entries(rows * K::BOUND.total(), 0, room), bound[1].entries(rows * K::BOUND.total(), 0, room)];
        // Checked once for every cell (each store through `Columns::store`
        // checked its own bounds: 18 instructions a store).
        let mut to = halves.entries_mut(16, 0, ncell.div_ceil(w) * w);
        let mut k = 0;
        while k < ncell {
            for (h, weights) in pair_weights.iter().enumerate() {
                let cells = At { entries: &views[h & 1], at: k };
                // Only the pairs on h's side of axis 1 weigh anything.
                for (m, v) in polynomial(kind, &cells, weights, (h >> 1, 2)).into_iter().enumerate() {
                    to.store(4 * h + m, k, v);
                }
            }
            k += w;
        }
        // Each chunk's coefficients from its cell's half-blends (a chunk of
        // narrow cells: each lane's from its own cell, within one register
        // from the chunk's first).
        let narrow_view = halves.entries(16, 0, ncell.div_ceil(w) * w + w);
        for ((ch, axis), to) in chunks.iter().zip(chunk_axis).zip(coef.chunks_exact_mut(4 * w)) {
            let half = if narrow {
                let lane = B::load_int(&axis.lane);
                half_blends::<K, B, D>(
                    axis.lanes(),
                    &PerLane::<B, true> { entries: &narrow_view, first: axis.first, lane: [lane, lane] },
                )
            } else {
                half_blends::<K, B, D>(axis.lanes(), &OneCell::new(&halves, ch.cell, 16))
            };
            for (m, v) in band_coefficients(half).into_iter().enumerate() {
                v.store(&mut to[m * w..]);
            }
        }
        let mut ya = y0;
        while ya < y1 {
            let yb = y1.min(ya.saturating_add(piece_rows));
            let at = (row + (ya - y0)) * nx;
            let n = (yb - ya) * nx;
            let band_out = if staged { &mut staging.target(&mut out[at..])[..n] } else { &mut out[at..at + n] };
            let band_rows = (&frac1[ya..yb], &fade1[ya..yb]);
            if held_band {
                match whole {
                    1 => write_held_band::<B, 1>(band_out, band_rows, coef),
                    2 => write_held_band::<B, 2>(band_out, band_rows, coef),
                    3 => write_held_band::<B, 3>(band_out, band_rows, coef),
                    _ => write_held_band::<B, 4>(band_out, band_rows, coef),
                }
            } else if direct {
                stream_band::<B>(band_out, band_rows, &coef[..whole * 4 * w]);
            } else if aligned && prefetch {
                write_aligned_band::<B, true>(band_out, nx, band_rows, (coef, whole));
            } else if aligned {
                write_aligned_band::<B, false>(band_out, nx, band_rows, (coef, whole));
            } else {
                // Row by row; lanes past a chunk's cell are written again by
                // the next chunk.
                let (coef_whole, coef_end) = coef.split_at(whole * 4 * w);
                for ((row, &v), &s) in band_out.chunks_exact_mut(nx).zip(band_rows.0).zip(band_rows.1) {
                    let (v, s) = (B::splat(v), B::splat(s));
                    for (ch, c) in chunks[..whole].iter().zip(coef_whole.chunks_exact(4 * w)) {
                        band_value::<B>(c, v, s).store(&mut row[ch.start..ch.start + w]);
                    }
                    for (ch, c) in chunks[whole..].iter().zip(coef_end.chunks_exact(4 * w)) {
                        emit(band_value::<B>(c, v, s), &mut row[ch.start..]);
                    }
                }
            }
            if staged {
                staging.flush::<B>(&mut out[at..at + n]);
            }
            ya = yb;
        }
    }
    let [lower, upper] = bound;
    lower.keep_in(kept_lower);
    upper.keep_in(kept_upper);
    halves.keep_in(kept_halves);
}

/// Columns of a band written together, down its rows, before the next
/// ones: their coefficients (16 bytes a column) stay in L1 while the rows
/// go by, and each row's piece is still stored in order. Whole rows at a
/// time across 2048 columns, each chunk's four loads came from L2 (perf,
/// 2D improved fast at 1/32, AVX-512: most of the loop's time on those
/// loads); a single chunk at a time down the columns, each store missed
/// the cache (0.93 ns/point against 0.65).
const BAND_BLOCK_COLUMNS: usize = 512;

/// How many rows ahead [`write_aligned_band`] asks for the lines it will
/// store (2D improved fast over 2048² at 1/32, AVX-512, alternating probe
/// runs: 0.20–0.29 ns/point without, 0.16–0.18 two rows ahead, 0.14–0.17
/// four; rows are 8 KiB apart there).
const PREFETCH_AHEAD: usize = 4;

/// How far ahead of a store (in values) the exact rows ask for its line,
/// where the grid has [`PREFETCH_MIN_VALUES`] points or more: two rows of
/// 2048 ahead. (The hardware prefetchers should follow a row's stores, but 2D
/// improved exact over 2048² at 1/32, AVX-512, five alternating probe runs
/// each, measured 0.30–0.34 ns/point, median 0.31, without and 0.28–0.30,
/// median 0.28, with; in a noisier stretch, medians 0.35 without, 0.32 at
/// 1024 values ahead, 0.28 at 4096. 3D over 256³, whose output is past L3,
/// did not change: 0.53.)
const ROW_PREFETCH_AHEAD: usize = 4096;

/// Fewest grid points for which the exact rows prefetch ([`ROW_PREFETCH_AHEAD`]):
/// 4 MiB of output, past L2. (Over 512², whose output L2 holds,
/// prefetching measured 2 % slower.)
const PREFETCH_MIN_VALUES: usize = 1 << 20;

/// [`fill_bands`]' rows where chunk k starts at column k · w (`whole`
/// chunks inside the row, then at most one at its end): a block of
/// columns at a time down the band, two chunks a turn (a turn's own
/// instructions were half of a chunk's: 7 of 14 on AVX2). `frac`,
/// `fade`: the band's rows' positions and fades along axis 1. (Iterators
/// zipped by value here were built out of line, a call per row outside
/// the instruction-set clone: 1/8-wide cells' 32² tiles 0.8 → 1.4
/// ns/sample, perf, AVX-512; iterators zipped by reference, and slices,
/// stay inline.) `PREFETCH`: each pair's lines [`PREFETCH_AHEAD`] rows
/// below are requested as it is stored (past the band's last rows, the
/// next band's).
#[inline(always)]
fn write_aligned_band<B: BatchLanes, const PREFETCH: bool>(
    band_out: &mut [f32],
    nx: usize,
    (frac, fade): (&[f32], &[f32]),
    (coef, whole): (&[f32], usize),
) {
    let w = B::WIDTH;
    let (coef_whole, coef_end) = coef.split_at(whole * 4 * w);
    let pairs = whole / 2;
    let block = BAND_BLOCK_COLUMNS / (2 * w);
    let mut p0 = 0;
    while p0 < pairs {
        let p1 = (p0 + block).min(pairs);
        let c = &coef_whole[p0 * 8 * w..p1 * 8 * w];
        for ((row, &v), &s) in band_out.chunks_exact_mut(nx).zip(frac).zip(fade) {
            let (v, s) = (B::splat(v), B::splat(s));
            let mut pairs = row[p0 * 2 * w..p1 * 2 * w].chunks_exact_mut(2 * w);
            for (out, c) in (&mut pairs).zip(c.chunks_exact(8 * w)) {
                if PREFETCH {
                    let ahead = out.as_ptr().wrapping_add(PREFETCH_AHEAD * nx);
                    crate::lanes::prefetch_store(ahead);
                    crate::lanes::prefetch_store(ahead.wrapping_add(w));
                }
                let (lo, hi) = out.split_at_mut(w);
                band_value::<B>(c, v, s).store(lo);
                band_value::<B>(&c[4 * w..], v, s).store(hi);
            }
        }
        p0 = p1;
    }
    let odd = whole % 2 == 1;
    let tail = coef_end.get(..4 * w);
    if !odd && tail.is_none() {
        return;
    }
    for ((row, &v), &s) in band_out.chunks_exact_mut(nx).zip(frac).zip(fade) {
        let (v, s) = (B::splat(v), B::splat(s));
        if odd {
            let k = whole - 1;
            band_value::<B>(&coef_whole[4 * w * k..], v, s).store(&mut row[w * k..w * k + w]);
        }
        if let Some(c) = tail {
            emit(band_value::<B>(c, v, s), &mut row[w * whole..]);
        }
    }
}

/// [`fill_bands`]' rows where they are whole registers from chunk k at
/// column k · w and the band is streamed ([`Stores::Streamed`]): the
/// band's rows, in order, are one run of registers ([`StreamedRun`]), so
/// only its first and last values are stored plainly. (A run per row, with
/// plain stores at both ends of every row, read 0.86 ns/sample against 0.57
/// for plain stores throughout, 3D improved fast over 256³ with a build
/// running beside both.)
#[inline(always)]
fn stream_band<B: BatchLanes>(band_out: &mut [f32], (frac, fade): (&[f32], &[f32]), coef: &[f32]) {
    let w = B::WIDTH;
    let mut run = StreamedRun::<B>::new(band_out);
    for (&v, &s) in frac.iter().zip(fade) {
        let (v, s) = (B::splat(v), B::splat(s));
        for c in coef.chunks_exact(4 * w) {
            run.push(band_value::<B>(c, v, s));
        }
    }
    run.finish();
}

/// Most chunks a row of [`write_held_band`] holds: their coefficients take
/// four registers each, 16 in all.
const HELD_BAND_CHUNKS: usize = 4;

/// [`fill_bands`]' rows of `N` whole chunks (a 32² tile on AVX-512: two):
/// the chunks' coefficients held in registers down the band, so a row
/// costs its two splats, the arithmetic and the stores. (Through
/// [`write_aligned_band`], a row of one pair of chunks paid a turn of its
/// block and pair loops and reloaded the coefficients: a fast 32² tile
/// took 5 097 instructions instead of 4 693 on AVX2, callgrind, and 0.341
/// instead of 0.300 ns/sample on AVX-512, medians of five probe runs.)
#[inline(always)]
fn write_held_band<B: BatchLanes, const N: usize>(band_out: &mut [f32], rows: (&[f32], &[f32]), coef: &[f32]) {
    let w = B::WIDTH;
    let mut held = [[B::cst(0.0); 4]; N];
    for (k, c) in held.iter_mut().enumerate() {
        for (m, v) in c.iter_mut().enumerate() {
            *v = B::from_slice(&coef[(4 * k + m) * w..]);
        }
    }
    write_band_rows::<B, N>(band_out, rows, &held);
}

/// A band's rows of `N` whole chunks from their coefficients in registers
/// (`held[k]`: chunk k's `p₀, p₁, q₀, q₁`).
#[inline(always)]
fn write_band_rows<B: BatchLanes, const N: usize>(
    band_out: &mut [f32],
    (frac, fade): (&[f32], &[f32]),
    held: &[[B; 4]; N],
) {
    let w = B::WIDTH;
    // Indices, not zipped iterators (see `write_aligned_band`).
    let rows = frac.len().min(fade.len()).min(band_out.len() / (N * w));
    for r in 0..rows {
        let (v, s) = (B::splat(frac[r]), B::splat(fade[r]));
        let row = &mut band_out[r * N * w..(r + 1) * N * w];
        for (k, &c) in held.iter().enumerate() {
            band_point(c, v, s).store(&mut row[k * w..(k + 1) * w]);
        }
    }
}

/// Each half-blend's weights on the pairs of corners along axis 0, for a
/// band at positions `f` on axes 2.. ([`fill_bands`]): half-blend h (bit 0:
/// at v = 1; bit 1: the upper corners on axis 1) weighs pair k (bit 0:
/// upper on axis 1; bit d − 1: on axis d) by the band's fades on axes 2..
/// where its side on axis 1 is h's, and the other pairs by 0.
#[inline(always)]
fn half_blend_weights<K: Lattice<D>, B: BatchLanes, const D: usize>(
    kind: &K,
    f: [f32; D],
) -> [[B; MAX_CORNERS / 2]; 4] {
    let mut pair_weights = [[B::cst(0.0); MAX_CORNERS / 2]; 4];
    for (h, weights) in pair_weights.iter_mut().enumerate() {
        for (k, pw) in weights.iter_mut().enumerate().take(PointRows::<D>::PER_PLANE) {
            if k & 1 != h >> 1 {
                continue;
            }
            *pw = B::cst(1.0);
            for d in 2..D {
                let s = B::splat(kind.fade(f[d]));
                *pw = *pw * if corner_bit(k, d - 1) == 1 { s } else { B::cst(1.0) - s };
            }
        }
    }
    pair_weights
}

/// A band's coefficients `p₀, p₁, q₀, q₁` ([`band_point`]) from a chunk's
/// four half-blends ([`half_blends`]).
#[inline(always)]
fn band_coefficients<B: BatchLanes>(half: [B; 4]) -> [B; 4] {
    let p1 = half[1] - half[0];
    [half[0], p1, half[2] - half[0], (half[3] - half[2]) - p1]
}

/// A chunk's four half-blends ([`fill_bands`]) at its positions `x` along
/// axis 0 (fades `fade`), from its cells' coefficients (16 fields: four
/// per half-blend).
#[inline(always)]
fn half_blends<K: Lattice<D>, B: BatchLanes, const D: usize>((x, fade): (B, B), cells: &impl Source<B>) -> [B; 4] {
    let mut half = [B::cst(0.0); 4];
    for (h, v) in half.iter_mut().enumerate() {
        *v = poly_at::<K, B, D>(x, fade, &Shifted { source: cells, base: 4 * h });
    }
    half
}

/// A band's point from its chunk's coefficients `c` (`p₀, p₁, q₀, q₁`, a
/// register each) at position `v` (fade `s`) along axis 1.
#[inline(always)]
fn band_value<B: BatchLanes>(c: &[f32], v: B, s: B) -> B {
    let w = B::WIDTH;
    band_point([B::from_slice(c), B::from_slice(&c[w..]), B::from_slice(&c[2 * w..]), B::from_slice(&c[3 * w..])], v, s)
}

/// [`band_value`] from coefficients in registers.
#[inline(always)]
fn band_point<B: BatchLanes>([p0, p1, q0, q1]: [B; 4], v: B, s: B) -> B {
    (p0 + p1 * v) + s * (q0 + q1 * v)
}

/// Flat kinds: rows of one plane whose points are the same columns
/// (`columns`, from `lo`), waiting to be written a block of columns at a
/// time: the block's blends ([`plane_blends`]) stay in registers down the
/// rows, so each point costs its arithmetic and one store.
struct Band {
    columns: (usize, usize),
    /// Each row's start in the output and fades on axes 1...
    rows: Vec<(usize, [f32; 4])>,
}

impl Band {
    /// Columns per block, in vectors. Eight measured faster than four (2D
    /// value 0.09 against 0.18 ns/point), and in 3D too (0.19 against 0.23),
    /// though there the blends spill.
    const BLOCK: usize = 8;

    /// The most rows written together: each is a stream of stores, and a
    /// plane's every row (32 at spacing 1/32) cost more than reloading the
    /// blends every eight rows (2D value over 2048² at 1/32, AVX-512,
    /// probe, six alternating runs: 0.099–0.128 ns/point against
    /// 0.124–0.244 for whole planes, 0.103–0.170 with six rows).
    const ROWS: usize = 8;

    /// Write the waiting rows and forget them, streaming the stores
    /// ([`Stores::Streamed`]) where they are whole registers of memory.
    #[inline(always)]
    fn write<K: Lattice<D>, B: BatchLanes, const D: usize>(
        &mut self,
        kind: &K,
        blends: &Columns,
        out: &mut [f32],
        stores: Stores,
    ) {
        if self.rows.is_empty() {
            return;
        }
        let w = B::WIDTH;
        let (a0, a1) = self.columns;
        let fields = (1 << D) / 2;
        // Where every row starts at the same offset from a register of
        // memory, the chunks run from the first column on its boundary (one
        // chunk before it), so that no store crosses a cache line (a 512-bit
        // store across two cost 0.20 ns a value over 16 MiB against 0.16, in
        // C on the Emerald Rapids host) and streamed stores can stream.
        let aligned = self.aligned_from::<B>(out, blends.stride() - a0);
        let lead = aligned.unwrap_or(0);
        let stream = aligned.is_some() && stores == Stores::Streamed;
        let n = a1 - a0;
        let view = blends.entries(fields, a0, lead + (n - lead).div_ceil(w) * w);
        let mut c = 0;
        if lead > 0 {
            let mut b = [B::cst(0.0); MAX_CORNERS / 2];
            for (m, v) in b.iter_mut().enumerate().take(fields) {
                *v = view.load(m, 0);
            }
            for &(at, weights) in &self.rows {
                from_blends(kind, &b, &splat_all(weights)).store(&mut out[at..at + w]);
            }
            c = lead;
        }
        // Whole chunks in blocks, the last block shorter. (The same call
        // twice, so that the full blocks' count is a constant there: rows
        // of 256 from column 12 ended in single chunks at first, 3D value
        // over 256³ 0.74 → 1.0 ns/sample.)
        while n - c >= w {
            let chunks = ((n - c) / w).min(Self::BLOCK);
            if chunks == Self::BLOCK {
                self.write_block::<K, B, D>(kind, &view, (c, Self::BLOCK), out, stream);
            } else {
                self.write_block::<K, B, D>(kind, &view, (c, chunks), out, stream);
            }
            c += chunks * w;
        }
        if c < n {
            // A part chunk: one ending at the rows' end, over the chunk
            // before it, where the rows are a chunk wide or wider and their
            // stores are plain (a part store is a copy through memory: 8 %
            // of 3D value's fill over 256³, rows of 256 from column 12, perf).
            let from = if n >= w && !stream { n - w } else { c };
            let mut b = [B::cst(0.0); MAX_CORNERS / 2];
            for (m, v) in b.iter_mut().enumerate().take(fields) {
                *v = view.load(m, from);
            }
            for &(at, weights) in &self.rows {
                store_prefix(from_blends(kind, &b, &splat_all(weights)), &mut out[at + from..at + n]);
            }
        }
        self.rows.clear();
    }

    /// `chunks` (up to [`Band::BLOCK`]) whole chunks from column `c` of
    /// every waiting row, the block's blends loaded once for all rows.
    #[inline(always)]
    fn write_block<K: Lattice<D>, B: BatchLanes, const D: usize>(
        &self,
        kind: &K,
        view: &Entries<'_>,
        (c, chunks): (usize, usize),
        out: &mut [f32],
        stream: bool,
    ) {
        let w = B::WIDTH;
        let mut block = [[B::cst(0.0); MAX_CORNERS / 2]; Self::BLOCK];
        for (k, b) in block.iter_mut().enumerate().take(chunks) {
            for (m, v) in b.iter_mut().enumerate().take((1 << D) / 2) {
                *v = view.load(m, c + k * w);
            }
        }
        for &(at, weights) in &self.rows {
            let weights = splat_all(weights);
            // The block's row sliced once, not each store (3 of the 7
            // instructions a chunk were its bounds checks).
            let row = &mut out[at + c..at + c + chunks * w];
            for (b, to) in block.iter().zip(row.chunks_exact_mut(w)) {
                let v = from_blends(kind, b, &weights);
                if stream {
                    v.store_streamed(to);
                } else {
                    v.store(to);
                }
            }
        }
    }

    /// The first column whose output lies on a register boundary in every
    /// waiting row; `None` where the rows' offsets from one differ, where
    /// they are shorter than two registers, or where the blends (`room`
    /// entries from the first column) would not reach a whole register
    /// past the last column from there.
    #[inline(always)]
    fn aligned_from<B: BatchLanes>(&self, out: &[f32], room: usize) -> Option<usize> {
        let w = B::WIDTH;
        let n = self.columns.1 - self.columns.0;
        let &(first, _) = self.rows.first()?;
        let lead = out[first..].as_ptr().align_offset(4 * w).min(w) % w;
        // (WIDTH is a power of two, so a wrapped difference's remainder is the true one's.)
        let same = self.rows.iter().all(|&(at, _)| at.wrapping_sub(first) % w == 0);
        (same && n >= 2 * w && lead + (n - lead).div_ceil(w) * w <= room).then_some(lead)
    }
}

/// Each value on all lanes.
#[inline(always)]
fn splat_all<B: BatchLanes>(values: [f32; 4]) -> [B; 4] {
    let mut lanes = [B::cst(0.0); 4];
    for (l, v) in lanes.iter_mut().zip(values) {
        *l = B::splat(v);
    }
    lanes
}

/// Flat kinds: a point from its column's blends along axis 0 (`blends`,
/// pairs along axis 1 as `a, b − a`) and its row's fades on axes 1...
#[inline(always)]
fn from_blends<K: Lattice<D>, B: BatchLanes, const D: usize>(
    kind: &K,
    blends: &[B; MAX_CORNERS / 2],
    weights: &[B; 4],
) -> B {
    let mut v = [B::cst(0.0); MAX_CORNERS];
    // Axis 1's lerp, a + w·(b − a).
    for (j, vj) in v.iter_mut().enumerate().take((1 << D) / 4) {
        *vj = blends[2 * j] + weights[1] * blends[2 * j + 1];
    }
    for d in 2..D {
        interpolate_axis(&mut v, D - d, weights[d]);
    }
    finish(kind, v[0])
}

/// What a grid row's points share: axis 0's positions and fades by column,
/// and the fades of axes 1...
struct Row<'a, B: BatchLanes, const D: usize> {
    frac: &'a [f32],
    fade: &'a [f32],
    weights: [B; D],
    /// Whether the row is off the lattice lines along axis 0 (some offset
    /// on axes 1.. is not zero), where corner 0 too takes
    /// [`Lattice::eval_unsigned_zero`].
    off_line: bool,
}

impl<B: BatchLanes, const D: usize> Row<'_, B, D> {
    /// The points at columns `s..s + WIDTH`, from their cells' bound corners.
    #[inline(always)]
    fn exact<K: Lattice<D>>(&self, kind: &K, s: usize, rec: &impl Source<B>) -> B {
        self.exact_at(kind, B::from_slice(&self.frac[s..]), B::from_slice(&self.fade[s..]), rec)
    }

    /// The points at positions `x` (fades `fade`) along axis 0.
    #[inline(always)]
    fn exact_at<K: Lattice<D>>(&self, kind: &K, x: B, fade: B, rec: &impl Source<B>) -> B {
        if self.off_line {
            self.exact_with::<K, true>(kind, x, fade, rec)
        } else {
            self.exact_with::<K, false>(kind, x, fade, rec)
        }
    }

    /// [`Row::exact_at`] with its `off_line` known ([`corner_values`]).
    #[inline(always)]
    fn exact_with<K: Lattice<D>, const OFF_LINE: bool>(&self, kind: &K, x: B, fade: B, rec: &impl Source<B>) -> B {
        self.exact_from_terms::<K, OFF_LINE>(kind, &x_terms::<K, B, D>(kind, x, rec), fade, rec)
    }

    /// [`Row::exact_with`] from the corners' terms in `x` ([`x_terms`]).
    #[inline(always)]
    fn exact_from_terms<K: Lattice<D>, const OFF_LINE: bool>(
        &self,
        kind: &K,
        terms: &[B; MAX_CORNERS],
        fade: B,
        rec: &impl Source<B>,
    ) -> B {
        let mut weights = self.weights;
        weights[0] = fade;
        finish(kind, interpolate(corner_values_from_terms::<K, B, D, OFF_LINE>(kind, terms, rec), weights))
    }

    /// A whole row of long runs (`chunks`, `chunk_axis`) into `out` (the
    /// row): a run's corners read once from `corners` at its cell, when its
    /// first chunk comes, and held while its chunks go by. (Chunk by chunk,
    /// 2D improved re-read eight fields for every 8 points; slicing the
    /// chunks run by run cost as much in bookkeeping for runs of 4.)
    /// `terms`: each chunk's corners' terms in x formed already, `1 << D`
    /// registers a chunk ([`write_batch`]); `None`: formed here.
    #[inline(always)]
    fn write_runs<K: Lattice<D>>(
        &self,
        kind: &K,
        (chunks, chunk_axis, terms): (&[Chunk], &[ChunkAxis], Option<&[f32]>),
        corners: &impl RunCorners<B>,
        out: (&mut [f32], bool),
    ) {
        let runs = (chunks, chunk_axis, terms.unwrap_or(&[]));
        // (The batches, which form the terms, never prefetch.)
        match (self.off_line, terms.is_some(), out.1) {
            (true, true, _) => self.write_runs_with::<K, true, true, false>(kind, runs, corners, out.0),
            (false, true, _) => self.write_runs_with::<K, false, true, false>(kind, runs, corners, out.0),
            (true, false, true) => self.write_runs_with::<K, true, false, true>(kind, runs, corners, out.0),
            (true, false, false) => self.write_runs_with::<K, true, false, false>(kind, runs, corners, out.0),
            (false, false, true) => self.write_runs_with::<K, false, false, true>(kind, runs, corners, out.0),
            (false, false, false) => self.write_runs_with::<K, false, false, false>(kind, runs, corners, out.0),
        }
    }

    /// `TERMS`: the chunks' terms in x come from `terms`; `PREFETCH`: each
    /// chunk asks for its line [`ROW_PREFETCH_AHEAD`] values ahead. (A
    /// constant, and one check for a whole register's store: 2D improved
    /// over 2048² at 1/32, AVX2, callgrind: 5.93 → 5.53 instructions a
    /// sample; 3D over 128³ 8.99 → 8.72.)
    #[inline(always)]
    fn write_runs_with<K: Lattice<D>, const OFF_LINE: bool, const TERMS: bool, const PREFETCH: bool>(
        &self,
        kind: &K,
        (chunks, chunk_axis, terms): (&[Chunk], &[ChunkAxis], &[f32]),
        corners: &impl RunCorners<B>,
        out: &mut [f32],
    ) {
        let Some(first) = chunks.first() else { return };
        let (mut at, mut held) = (first.cell, corners.held::<D>(first.cell, K::BOUND));
        let per_chunk = (1 << D) * B::WIDTH;
        // The last start of a whole register in `out`.
        let last_whole = out.len().checked_sub(B::WIDTH);
        for (i, (ch, axis)) in chunks.iter().zip(chunk_axis).enumerate() {
            if ch.cell != at {
                (at, held) = (ch.cell, corners.held::<D>(ch.cell, K::BOUND));
            }
            let (x, fade) = axis.lanes::<B>();
            if PREFETCH {
                crate::lanes::prefetch_store(out.as_ptr().wrapping_add(ch.start + ROW_PREFETCH_AHEAD));
            }
            let chunk_terms = if TERMS {
                let mut t = [B::cst(0.0); MAX_CORNERS];
                for (term, from) in t.iter_mut().zip(terms[i * per_chunk..(i + 1) * per_chunk].chunks_exact(B::WIDTH)) {
                    *term = B::from_slice(from);
                }
                t
            } else {
                x_terms::<K, B, D>(kind, x, &held)
            };
            let v = self.exact_from_terms::<K, OFF_LINE>(kind, &chunk_terms, fade, &held);
            // A whole register where it fits (one check, no overflow to
            // test), else a part at the end of `out`.
            match last_whole {
                Some(last) if ch.start <= last => v.store(&mut out[ch.start..ch.start + B::WIDTH]),
                _ => emit(v, &mut out[ch.start..]),
            }
        }
    }

    /// [`write_held_rows`]' row: `N` whole chunks with their corners' terms
    /// in x and their fades (`axis`), chunk k in cell `chunks[k].cell` of
    /// `records` (`ONE_CELL`: all in the first's). (Reading the corners again
    /// only where the cell changes cost a 32² tile inside a cell 9 % more
    /// instructions on AVX2.)
    #[inline(always)]
    fn write_held<K: Lattice<D>, const N: usize, const OFF_LINE: bool, const ONE_CELL: bool>(
        &self,
        kind: &K,
        (terms, fades): (&[[B; MAX_CORNERS]; N], &[B; N]),
        (records, chunks): (&BatchRecords<'_>, &[Chunk; N]),
        out: &mut [f32],
    ) {
        let w = B::WIDTH;
        let mut held = records.held::<D>(chunks[0].cell, K::BOUND);
        for k in 0..N {
            if !ONE_CELL && k > 0 {
                held = records.held::<D>(chunks[k].cell, K::BOUND);
            }
            self.exact_from_terms::<K, OFF_LINE>(kind, &terms[k], fades[k], &held).store(&mut out[k * w..(k + 1) * w]);
        }
    }

    /// The same points from their cells' row polynomials ([`Accuracy::Fast`]).
    #[inline(always)]
    fn poly<K: Lattice<D>>(&self, s: usize, coef: &impl Source<B>) -> B {
        poly_at::<K, B, D>(B::from_slice(&self.frac[s..]), B::from_slice(&self.fade[s..]), coef)
    }
}

/// A grid row's cells and positions on axes 1.. (`[0]` unused), from its
/// indices along them.
#[inline(always)]
fn row_cells<K: Lattice<D>, const D: usize>(kind: &K, span: &Span<'_, D>, idx: [usize; D]) -> ([i32; D], [f32; D]) {
    let mut cell = [0i32; D];
    let mut f = [0f32; D];
    for d in 1..D {
        (cell[d], f[d]) = kind.split(span.axes.axis(d)[idx[d]]);
    }
    (cell, f)
}

/// A row's fades (`weights`) and positions (`fs`) on axes 1.. in lanes.
#[inline(always)]
fn row_lanes<K: Lattice<D>, B: BatchLanes, const D: usize>(kind: &K, f: [f32; D]) -> ([B; D], [B; D]) {
    let mut weights = [B::splat(0.0); D];
    let mut fs = [B::splat(0.0); D];
    for d in 1..D {
        weights[d] = B::splat(kind.fade(f[d]));
        fs[d] = B::splat(f[d]);
    }
    (weights, fs)
}

/// Whether a row at positions `f` on axes 1.. (`f[0]` unused) is off the
/// lattice lines along axis 0. (A loop: `(1..D).any(..)` was left out of
/// line, a call per row outside the instruction-set clone.)
#[inline(always)]
fn off_line<const D: usize>(f: [f32; D]) -> bool {
    let mut off = false;
    for &fd in &f[1..] {
        off |= fd != 0.0;
    }
    off
}

/// The values of a chunk's corners at positions `x` along axis 0, from
/// their bound records; `OFF_LINE` for a row off the lattice lines.
#[inline(always)]
fn corner_values<K: Lattice<D>, B: BatchLanes, const D: usize, const OFF_LINE: bool>(
    kind: &K,
    x: B,
    rec: &impl Source<B>,
) -> [B; MAX_CORNERS] {
    corner_values_from_terms::<K, B, D, OFF_LINE>(kind, &x_terms::<K, B, D>(kind, x, rec), rec)
}

/// Each corner's [`Lattice::x_term`] at positions `x` along axis 0.
#[inline(always)]
fn x_terms<K: Lattice<D>, B: BatchLanes, const D: usize>(kind: &K, x: B, rec: &impl Source<B>) -> [B; MAX_CORNERS] {
    let xm1 = x - B::cst(1.0);
    let mut terms = [B::cst(0.0); MAX_CORNERS];
    for (c, term) in terms.iter_mut().enumerate().take(1 << D) {
        *term = kind.x_term(&rec.corner(c, K::BOUND), if c & 1 == 1 { xm1 } else { x });
    }
    terms
}

/// [`corner_values`] from the corners' terms in `x` ([`x_terms`]). Only
/// corner 0's zero can reach the result ([`Lattice::eval_unsigned_zero`]).
#[inline(always)]
fn corner_values_from_terms<K: Lattice<D>, B: BatchLanes, const D: usize, const OFF_LINE: bool>(
    kind: &K,
    terms: &[B; MAX_CORNERS],
    rec: &impl Source<B>,
) -> [B; MAX_CORNERS] {
    let mut v = [B::cst(0.0); MAX_CORNERS];
    for c in 0..(1 << D) {
        let bound = rec.corner(c, K::BOUND);
        v[c] = if OFF_LINE || c != 0 {
            kind.eval_unsigned_zero_from_x_term(&bound, terms[c])
        } else {
            kind.eval_from_x_term(&bound, terms[c])
        };
    }
    v
}

/// Flat kinds: a chunk's blends along axis 0, which every row of the
/// plane shares, as [`interpolate`] forms them, stored by pairs along axis
/// 1 as `a, b − a` (the lerp's own difference) at column `at`.
#[inline(always)]
fn plane_blends<K: Lattice<D>, B: BatchLanes, const D: usize>(
    kind: &K,
    (x, fade): (B, B),
    rec: &impl Source<B>,
    blends: &mut Columns,
    at: usize,
) {
    // Every row of the plane shares these: corner 0 keeps its zero's sign.
    let mut v = corner_values::<K, B, D, false>(kind, x, rec);
    interpolate_axis(&mut v, D, fade);
    for j in 0..(1 << D) / 4 {
        blends.store(2 * j, at, v[2 * j]);
        blends.store(2 * j + 1, at, v[2 * j + 1] - v[2 * j]);
    }
}

/// The row polynomial at positions `x` (fades `fade`).
#[inline(always)]
fn poly_at<K: Lattice<D>, B: BatchLanes, const D: usize>(x: B, fade: B, coef: &impl Source<B>) -> B {
    if K::FLAT {
        // Flat corners: the affine parts are constants.
        coef.field(0, 0) + fade * coef.field(2, 0)
    } else {
        (coef.field(0, 0) + coef.field(1, 0) * x) + fade * (coef.field(2, 0) + coef.field(3, 0) * x)
    }
}

/// A chunk's positions and fades, stored with it so whole rows read them
/// without index arithmetic; for chunks whose lanes lie in several cells
/// (short runs), also each lane's cell as an entry past `first`, the
/// chunk's first cell.
#[derive(Clone, Copy)]
struct ChunkAxis {
    x: [f32; 16],
    fade: [f32; 16],
    lane: [i32; 16],
    first: usize,
}

impl ChunkAxis {
    const ZERO: Self = ChunkAxis { x: [0.0; 16], fade: [0.0; 16], lane: [0; 16], first: 0 };

    #[inline(always)]
    fn lanes<B: BatchLanes>(&self) -> (B, B) {
        (B::from_slice(&self.x), B::from_slice(&self.fade))
    }
}

/// Store up to WIDTH lanes at the start of `out`.
#[inline(always)]
fn emit<B: BatchLanes>(v: B, out: &mut [f32]) {
    let count = out.len().min(B::WIDTH);
    store_prefix(v, &mut out[..count]);
}

/// [`Accuracy::Fast`]'s coefficients for a block of cells: the row inside
/// each cell is `(p₀ + p₁·u) + s(u)·(q₀ + q₁·u)`, from the cells' bound
/// corners (`eval` is affine in u) weighted by the row's fixed blend over
/// axes 1... Pairs `first, first + step, …` only: the others weigh 0.
#[inline(always)]
fn polynomial<K: Lattice<D>, B: BatchLanes, const D: usize>(
    kind: &K,
    bound: &impl Source<B>,
    pair_weights: &[B; MAX_CORNERS / 2],
    (first, step): (usize, usize),
) -> [B; 4] {
    let mut sum = [B::cst(0.0); 4];
    for k in (first..1 << (D - 1)).step_by(step) {
        // Corners 2k and 2k + 1 differ on axis 0: A(u) = a + b·u (lower
        // corner, offset u) and B(u) − A(u) = c + d·u (upper, offset u − 1).
        let lo = bound.corner(2 * k, K::BOUND);
        let up = bound.corner(2 * k + 1, K::BOUND);
        let a = kind.eval(&lo, B::cst(0.0));
        let b = kind.eval(&lo, B::cst(1.0)) - a;
        let up0 = kind.eval(&up, B::cst(0.0));
        let e = kind.eval(&up, B::cst(1.0)) - up0;
        let wk = pair_weights[k];
        let terms = [a, b, (up0 - e) - a, e - b];
        for m in 0..4 {
            sum[m] = sum[m] + wk * terms[m];
        }
    }
    for v in sum.iter_mut() {
        *v = finish(kind, *v);
    }
    sum
}
