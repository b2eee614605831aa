//! Sparse convolution noise (Lewis 1989), as Frisvad & Wyvill compute it in
//! "Fast High-Quality Noise" (GRAPHITE 2007): impulses at random positions
//! with random values, each convolved with a compact kernel, generated on the
//! fly per grid cell by an index-addressable linear congruential generator.
//! No lattice node is special, so the noise has no grid artefacts.

use alloc::sync::Arc;
use alloc::vec::Vec;
use core::fmt;

use super::{Period, PeriodError};
use crate::hash::hash_cell;
use crate::lanes::{Elem, IntLanes, Lanes};
use crate::noise::Noise;

mod splat;
mod turbulence;

pub use splat::SplatError;
pub use turbulence::SparseTurbulence;

/// The paper's generator (its Eq. 1): `x ← (3125·x + 49) mod 2³²`, seed 1.
const LCG_A: u32 = 3125;
const LCG_C: u32 = 49;

/// `x ↦ A·x + C` after `2^b` steps of the generator, for b = 0..32: Eq. 2's
/// closed form `x_i = aⁱx₀ + (aⁱ⁻¹ + … + 1)c`, composed by squaring so any
/// index is reached in 32 steps.
const JUMPS: [(u32, u32); 32] = {
    let mut table = [(0u32, 0u32); 32];
    let (mut a, mut c) = (LCG_A, LCG_C);
    let mut b = 0;
    while b < 32 {
        table[b] = (a, c);
        // Doubling: (a, c) ∘ (a, c) = (a², a·c + c).
        c = a.wrapping_mul(c).wrapping_add(c);
        a = a.wrapping_mul(a);
        b += 1;
    }
    table
};

/// The generator's state at stream index `i` (seed x₀ = 1), per lane.
#[inline(always)]
fn lcg_at<I: IntLanes>(i: I) -> I {
    let (mut a, mut c) = (I::splat(1), I::splat(0));
    for (b, &(ja, jc)) in JUMPS.iter().enumerate() {
        // Apply the 2^b jump where bit b of the index is set.
        let (na, nc) = (a.mul(I::splat(ja as i32)), c.mul(I::splat(ja as i32)).add(I::splat(jc as i32)));
        let on = i.bit(b as u32);
        a = I::select(on, na, a);
        c = I::select(on, nc, c);
    }
    a.add(c)
}

/// One generator step.
#[inline(always)]
fn lcg_next<I: IntLanes>(x: I) -> I {
    x.mul(I::splat(LCG_A as i32)).add(I::splat(LCG_C as i32))
}

/// The top 24 bits as a float in [0, 1): exact in `f32` and `f64` (the low
/// bits of a power-of-two LCG have short periods).
#[inline(always)]
fn unit<L: Lanes>(x: L::Int) -> L {
    L::from_int(x.shr(8)) * L::cst(1.0 / 16_777_216.0)
}

/// Largest support radius a kernel may have, in cells: the search then
/// visits at most 5 cells per axis.
pub const MAX_SUPPORT: f64 = 2.0;

/// Samples in a tabulated profile.
const PROFILE_SAMPLES: usize = 4096;

/// The radial shape of the kernel around each impulse.
#[derive(Clone)]
pub enum Profile {
    /// The paper's cubic `w(d) = (1 − d²/r²)³` for `d < r`, evaluated exactly
    /// (C², compact support).
    Cubic,
    /// `w` tabulated over `t = d²/R²` ∈ [0, 1] and interpolated linearly:
    /// the Gaussian reference and user profiles.
    Table {
        /// Samples at `t = k/(len − 1)`, single precision.
        single: Arc<[f32]>,
        /// The same samples, double precision.
        double: Arc<[f64]>,
    },
}

/// The kernel convolved with every impulse: a radial profile of radius
/// `radius` (cells), optionally seen through a linear map for anisotropy.
#[derive(Clone)]
pub struct Kernel {
    name: &'static str,
    profile: Profile,
    /// Radius where the profile reaches zero, in cells (before the map).
    radius: f64,
    /// `d ↦ A·d` before the profile (row-major 4×4; the top-left D×D block
    /// is used in D dimensions). Identity for isotropic kernels.
    map: Option<[[f64; 4]; 4]>,
    /// Reach of the kernel in input space, per dimension 1..=4 (index D−1).
    support: [f64; 4],
    /// ∫ w(|A·d|)² dd per dimension, for the variance normalisation.
    energy: [f64; 4],
}

impl fmt::Debug for Kernel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Kernel")
            .field("name", &self.name)
            .field("radius", &self.radius)
            .field("map", &self.map)
            .finish()
    }
}

/// Why a kernel cannot be used.
#[derive(Clone, Debug, PartialEq)]
pub enum KernelError {
    /// Radius not finite and positive, or the support exceeds [`MAX_SUPPORT`].
    BadRadius(f64),
    /// The profile gave a non-finite value at this `t`.
    NonFiniteProfile(f64),
    /// The anisotropy map is not finite or not invertible (in some D).
    BadMap,
}

impl fmt::Display for KernelError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            KernelError::BadRadius(r) => {
                write!(f, "kernel reach {r} cells is not in (0, {MAX_SUPPORT}]")
            }
            KernelError::NonFiniteProfile(t) => write!(f, "kernel profile is not finite at d²/R² = {t}"),
            KernelError::BadMap => write!(f, "anisotropy map must be finite and invertible"),
        }
    }
}

impl Kernel {
    /// The paper's cubic kernel with radius ½ cell: the cell width equals
    /// the kernel diameter, so 2^D cells reach any point.
    pub fn cubic() -> Kernel {
        Kernel::build("cubic", Profile::Cubic, 0.5, None).expect("the cubic kernel is valid")
    }

    /// The Gaussian of the paper's reference noise (§2): σ = r/3 for the
    /// cubic's r = ½ cell, truncated where it falls below f32 resolution
    /// (e^{−d²/2σ²} < 2⁻²⁴, i.e. d > 5.77σ ≈ 0.96 cells), so 3^D cells
    /// are visited. Tabulated (4096 samples of d²; interpolation error below
    /// 3e-6 of the peak).
    pub fn gaussian() -> Kernel {
        let sigma = 0.5 / 3.0;
        let reach = sigma * libm::sqrt(2.0 * 24.0 * core::f64::consts::LN_2);
        let profile = move |d: f64| libm::exp(-d * d / (2.0 * sigma * sigma));
        let mut k = Kernel::radial_profile(reach, profile).expect("the Gaussian kernel is valid");
        k.name = "gaussian";
        k
    }

    /// A user kernel: any radial profile `w(d)` on `0 ≤ d ≤ radius` (cells;
    /// zero beyond), tabulated at construction. Art direction, as the paper
    /// suggests: rings, soft spots, bumps.
    pub fn radial_profile(radius: f64, w: impl Fn(f64) -> f64) -> Result<Kernel, KernelError> {
        if !(radius.is_finite() && radius > 0.0 && radius <= MAX_SUPPORT) {
            return Err(KernelError::BadRadius(radius));
        }
        let mut double = Vec::with_capacity(PROFILE_SAMPLES + 1);
        for k in 0..=PROFILE_SAMPLES {
            let t = k as f64 / PROFILE_SAMPLES as f64;
            let v = w(radius * libm::sqrt(t));
            if !v.is_finite() {
                return Err(KernelError::NonFiniteProfile(t));
            }
            double.push(v);
        }
        // One extra sample so interpolation at t → 1 never reads past the end.
        double.push(*double.last().unwrap_or(&0.0));
        let single: Vec<f32> = double.iter().map(|&v| v as f32).collect();
        let profile = Profile::Table { single: single.into(), double: double.into() };
        Kernel::build("custom", profile, radius, None)
    }

    /// This kernel seen through a linear map: `w(|A·d|)`. Stretching by `A`
    /// = diag(½, 1) doubles the kernel along x. The reach grows by the
    /// map's inverse norm and must stay within [`MAX_SUPPORT`].
    pub fn anisotropic(self, a: [[f64; 4]; 4]) -> Result<Kernel, KernelError> {
        Kernel::build(self.name, self.profile, self.radius, Some(a))
    }

    fn build(
        name: &'static str,
        profile: Profile,
        radius: f64,
        map: Option<[[f64; 4]; 4]>,
    ) -> Result<Kernel, KernelError> {
        let mut support = [radius; 4];
        let mut scale = [1.0; 4];
        if let Some(a) = map {
            if a.iter().flatten().any(|v| !v.is_finite()) {
                return Err(KernelError::BadMap);
            }
            for d in 1..=4 {
                let (inverse_norm, det) = inverse_frobenius_and_det(&a, d).ok_or(KernelError::BadMap)?;
                support[d - 1] = radius * inverse_norm;
                scale[d - 1] = 1.0 / det.abs();
            }
        }
        if let Some(&s) = support.iter().find(|&&s| !(s > 0.0 && s <= MAX_SUPPORT)) {
            return Err(KernelError::BadRadius(s));
        }
        let mut kernel = Kernel { name, profile, radius, map, support, energy: [0.0; 4] };
        for d in 1..=4 {
            kernel.energy[d - 1] = scale[d - 1] * radial_energy(&kernel, d);
        }
        Ok(kernel)
    }

    /// The kernel's name (`cubic`, `gaussian`, `custom`).
    pub fn name(&self) -> &'static str {
        self.name
    }

    /// `w` at squared distance `d2` (after the map), in lanes.
    #[inline(always)]
    fn weight<L: Lanes>(&self, d2: L) -> L {
        let t = d2 * L::cst(1.0 / (self.radius * self.radius));
        let inside = t.lt(L::cst(1.0));
        let w = match &self.profile {
            Profile::Cubic => {
                let s = L::cst(1.0) - t;
                s * s * s
            }
            Profile::Table { single, double } => {
                let table = L::Elem::pick(single, double);
                let x = t.min(L::cst(1.0)) * L::cst(PROFILE_SAMPLES as f64);
                let i = x.floor();
                let k = i.to_int_wrapping();
                let (a, b) = (L::gather(table, k), L::gather(table, k.add_c(1)));
                a + (x - i) * (b - a)
            }
        };
        L::select(inside, w, L::cst(0.0))
    }

    /// `w` at distance `d` (f64, isotropic), for integrals.
    fn weight_at(&self, d: f64) -> f64 {
        self.weight::<f64>(d * d)
    }
}

/// ∫ w(|y|)² dy over D-space, by Simpson's rule on the radius.
fn radial_energy(kernel: &Kernel, d: usize) -> f64 {
    let sphere = [
        2.0,
        2.0 * core::f64::consts::PI,
        4.0 * core::f64::consts::PI,
        2.0 * core::f64::consts::PI * core::f64::consts::PI,
    ][d - 1];
    let steps = 4000;
    let h = kernel.radius / steps as f64;
    let f = |k: usize| {
        let rho = k as f64 * h;
        let w = kernel.weight_at(rho);
        w * w * libm::pow(rho, (d - 1) as f64)
    };
    let mut sum = f(0) + f(steps);
    for k in 1..steps {
        sum += f(k) * if k % 2 == 1 { 4.0 } else { 2.0 };
    }
    sphere * sum * h / 3.0
}

/// Frobenius norm of the inverse of the top-left d×d block, and its
/// determinant (None when singular).
fn inverse_frobenius_and_det(a: &[[f64; 4]; 4], d: usize) -> Option<(f64, f64)> {
    // Gauss–Jordan on [A | I] with partial pivoting.
    let mut m = [[0.0; 8]; 4];
    for r in 0..d {
        for c in 0..d {
            m[r][c] = a[r][c];
        }
        m[r][4 + r] = 1.0;
    }
    let mut det = 1.0;
    for col in 0..d {
        let pivot = (col..d).max_by(|&x, &y| m[x][col].abs().total_cmp(&m[y][col].abs()))?;
        if m[pivot][col].abs() < 1e-12 {
            return None;
        }
        if pivot != col {
            m.swap(pivot, col);
            det = -det;
        }
        let p = m[col][col];
        det *= p;
        for c in 0..8 {
            m[col][c] /= p;
        }
        for r in 0..d {
            if r != col {
                let f = m[r][col];
                for c in 0..8 {
                    m[r][c] -= f * m[col][c];
                }
            }
        }
    }
    let mut norm = 0.0;
    for row in m.iter().take(d) {
        for v in &row[4..4 + d] {
            norm += v * v;
        }
    }
    Some((libm::sqrt(norm), det))
}

/// How impulse values are drawn.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Values {
    /// Uniform in [−1, 1).
    #[default]
    Uniform,
    /// The paper's split (Listing 2): the first half of each cell's impulses
    /// in [0, 1), the second half in (−1, 0].
    Halves,
}

/// How the sum of kernels is scaled.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Normalisation {
    /// Divided by its theoretical standard deviation √(n/3 · ∫w²) and
    /// multiplied by ¼: standard deviation ¼ (exact for uniform values;
    /// slightly less for `Halves`), so |v| > 1 is a 4σ event (about 6e-5
    /// of samples). Not clamped.
    #[default]
    Variance,
    /// The paper's mapping of [−n^{1/D}, n^{1/D}] onto [0, 1]:
    /// `0.5 + sum / (2 n^{1/D})` (not clamped; the paper's colour buffer is).
    Paper,
    /// The raw sum Σ vᵢ·w(dᵢ).
    Raw,
}

/// Sparse convolution noise, 1D–4D.
///
/// The domain is divided into unit cells (one unit = one cell, as for every
/// kind); the cubic kernel's diameter equals the cell width, so the 2^D cells
/// around a point hold every impulse that reaches it. Each cell holds `n`
/// impulses (the paper's quality knob: 10 decent, 30 excellent), drawn from
/// the paper's LCG `x ← 3125x + 49 mod 2³²` started at stream index
/// `hash(cell, seed) · n · (D + 1)` and reached in 32 steps by Eq. 2's
/// closed form: no tables, any window in any order. Per impulse the stream
/// gives D position coordinates (uniform in the cell) and a value.
///
/// Where the paper indexes cells linearly (which would repeat impulses along
/// a lattice direction), the cell index here is a mixed hash of the cell
/// coordinates, so no two nearby cells share a stream.
///
/// Range: with the default [`Normalisation::Variance`], standard deviation
/// ¼ and unbounded tails (tested: |v| > 1 in < 0.05 % of samples).
#[derive(Clone, Debug)]
pub struct Sparse {
    seed: u32,
    impulses: u32,
    kernel: Kernel,
    values: Values,
    normalisation: Normalisation,
    period: Period,
}

/// Why a sparse noise cannot be built.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum SparseError {
    /// Impulses per cell must be at least 1 (and at most 10 000).
    Impulses(u32),
}

impl fmt::Display for SparseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SparseError::Impulses(n) => write!(f, "impulses per cell must be 1..=10000, got {n}"),
        }
    }
}

impl Sparse {
    /// Most impulses per cell.
    pub const MAX_IMPULSES: u32 = 10_000;

    /// The paper's noise with `n = 20` impulses per cell and the cubic kernel.
    pub fn new(seed: u32) -> Sparse {
        Sparse {
            seed,
            impulses: 20,
            kernel: Kernel::cubic(),
            values: Values::Uniform,
            normalisation: Normalisation::Variance,
            period: Period::NONE,
        }
    }

    /// With `n` impulses per cell.
    pub fn with_impulses(mut self, n: u32) -> Result<Sparse, SparseError> {
        if n == 0 || n > Self::MAX_IMPULSES {
            return Err(SparseError::Impulses(n));
        }
        self.impulses = n;
        Ok(self)
    }

    /// Tiled: periodic with `period[k]` cells along axis k (0 leaves an axis
    /// unbounded; axes beyond the noise's dimension are ignored). Cell
    /// indices wrap before they are hashed, so the tile repeats exactly and
    /// has the statistics of the untiled noise.
    pub fn with_period(mut self, cells: [u32; 4]) -> Result<Sparse, PeriodError> {
        self.period = Period::new(cells)?;
        Ok(self)
    }

    /// With another kernel.
    pub fn with_kernel(mut self, kernel: Kernel) -> Sparse {
        self.kernel = kernel;
        self
    }

    /// With another way of drawing values.
    pub fn with_values(mut self, values: Values) -> Sparse {
        self.values = values;
        self
    }

    /// With another output scaling.
    pub fn with_normalisation(mut self, normalisation: Normalisation) -> Sparse {
        self.normalisation = normalisation;
        self
    }

    /// The seed.
    pub fn seed(&self) -> u32 {
        self.seed
    }

    /// Impulses per cell.
    pub fn impulses(&self) -> u32 {
        self.impulses
    }

    /// The kernel.
    pub fn kernel(&self) -> &Kernel {
        &self.kernel
    }

    /// How far (in cells) an impulse reaches in `D` dimensions.
    pub fn support(&self, dims: usize) -> f64 {
        self.kernel.support[dims.clamp(1, 4) - 1]
    }

    /// The factor applied to the raw sum in `D` dimensions, and the offset
    /// added after it.
    pub fn output_scale(&self, dims: usize) -> (f64, f64) {
        let d = dims.clamp(1, 4);
        let n = self.impulses as f64;
        match self.normalisation {
            Normalisation::Variance => (0.25 / libm::sqrt(n / 3.0 * self.kernel.energy[d - 1]), 0.0),
            Normalisation::Paper => (1.0 / (2.0 * libm::pow(n, 1.0 / d as f64)), 0.5),
            Normalisation::Raw => (1.0, 0.0),
        }
    }

    /// Cells visited per axis for a reach of `support` cells.
    pub(crate) fn cells_per_axis(support: f64) -> usize {
        // An interval of length 2R meets ⌈2R⌉ + 1 unit cells at most (2R + 1
        // when 2R is a whole number, as for the cubic kernel).
        let span = 2.0 * support;
        let whole = libm::floor(span);
        if span == whole {
            whole as usize + 1
        } else {
            whole as usize + 2
        }
    }

    /// The impulses of one cell in `D` dimensions: calls `f(offset, value)`
    /// with each impulse's position inside the cell (in [0, 1)^D, as lanes)
    /// and its value in [−1, 1).
    #[inline(always)]
    pub(crate) fn impulses_of<L: Lanes, const D: usize>(&self, cell: [L::Int; D], mut f: impl FnMut([L; D], L)) {
        let per_cell = self.impulses as i32 * (D as i32 + 1);
        let cell = self.period.wrap_cell(cell);
        let mut x = lcg_at(hash_cell(cell, self.seed).mul(L::Int::splat(per_cell)));
        let half = self.impulses / 2;
        for k in 0..self.impulses {
            let mut pos = [L::cst(0.0); D];
            for c in pos.iter_mut() {
                x = lcg_next(x);
                *c = unit::<L>(x);
            }
            x = lcg_next(x);
            let u = unit::<L>(x);
            let value = match self.values {
                Values::Uniform => u * L::cst(2.0) - L::cst(1.0),
                Values::Halves if k < half => u,
                Values::Halves => -u,
            };
            f(pos, value);
        }
    }

    /// Squared kernel distance from offset `d` (point − impulse), through
    /// the anisotropy map if any.
    #[inline(always)]
    pub(crate) fn distance2<L: Lanes, const D: usize>(&self, d: [L; D]) -> L {
        let mut s = L::cst(0.0);
        match &self.kernel.map {
            None => {
                for c in d {
                    s = s + c * c;
                }
            }
            Some(a) => {
                for row in a.iter().take(D) {
                    let mut y = L::cst(0.0);
                    for k in 0..D {
                        y = y + L::cst(row[k]) * d[k];
                    }
                    s = s + y * y;
                }
            }
        }
        s
    }

    /// Whether the kernel is radial in input space (no anisotropy map).
    pub(crate) fn is_isotropic(&self) -> bool {
        self.kernel.map.is_none()
    }

    /// `w` at squared kernel distance `d2`.
    #[inline(always)]
    pub(crate) fn weight<L: Lanes>(&self, d2: L) -> L {
        self.kernel.weight(d2)
    }

    /// The raw sum at `p`, gathering every impulse of the cells in reach.
    #[inline(always)]
    fn raw<L: Lanes, const D: usize>(&self, p: [L; D]) -> L {
        let reach = self.support(D);
        let m = Self::cells_per_axis(reach);
        let mut base = [L::Int::splat(0); D];
        let mut frac = p;
        for k in 0..D {
            let b = (p[k] - L::cst(reach)).floor();
            base[k] = b.to_int_wrapping();
            frac[k] = p[k] - b;
        }
        let mut sum = L::cst(0.0);
        let cells = m.pow(D as u32);
        for c in 0..cells {
            let mut cell = base;
            let mut local = frac;
            let mut rest = c;
            for k in 0..D {
                let step = (rest % m) as i32;
                rest /= m;
                cell[k] = base[k].add_c(step);
                local[k] = frac[k] - L::cst(step as f64);
            }
            self.impulses_of::<L, D>(cell, |pos, value| {
                let mut d = local;
                for k in 0..D {
                    d[k] = local[k] - pos[k];
                }
                sum = sum + value * self.weight(self.distance2(d));
            });
        }
        sum
    }
}

macro_rules! impl_sparse {
    ($($d:literal),*) => {$(
        impl Noise<$d> for Sparse {
            crate::grid::batch_entry!($d);
            #[inline(always)]
            fn sample<L: Lanes>(&self, p: [L; $d]) -> L {
                let (scale, offset) = self.output_scale($d);
                let v = self.raw(p) * L::cst(scale) + L::cst(offset);
                super::finite_or_nan(p, v)
            }
        }
    )*};
}
impl_sparse!(1, 2, 3, 4);

// This module's batch drivers per instruction-set level (`grid::batch_clones!`).
crate::grid::batch_clones!();

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn jump_equals_stepping() {
        let mut x = 1u32;
        for i in 0..5000u32 {
            assert_eq!(lcg_at::<i32>(i as i32) as u32, x, "index {i}");
            x = x.wrapping_mul(LCG_A).wrapping_add(LCG_C);
        }
        // Far indices: the jump composes like stepping.
        let far = 0x8765_4321u32;
        let stepped = (0..10).fold(lcg_at::<i32>(far as i32), |x, _| lcg_next(x));
        assert_eq!(stepped, lcg_at::<i32>(far.wrapping_add(10) as i32));
    }

    #[test]
    fn cells_per_axis_covers_the_reach() {
        assert_eq!(Sparse::cells_per_axis(0.5), 2);
        assert_eq!(Sparse::cells_per_axis(0.962), 3);
        assert_eq!(Sparse::cells_per_axis(1.0), 3);
        assert_eq!(Sparse::cells_per_axis(1.2), 4);
    }

    #[test]
    fn cubic_energy_matches_the_closed_form() {
        // ∫ (1 − ρ²/r²)⁶ over D-space = (S_D r^D / 2)·B(D/2, 7).
        let k = Kernel::cubic();
        let r: f64 = 0.5;
        let beta = |a: f64, b: f64| libm::exp(libm::lgamma(a) + libm::lgamma(b) - libm::lgamma(a + b));
        let sphere =
            [2.0, 2.0 * core::f64::consts::PI, 4.0 * core::f64::consts::PI, 2.0 * core::f64::consts::PI.powi(2)];
        for d in 1..=4 {
            let exact = sphere[d - 1] * r.powi(d as i32) / 2.0 * beta(d as f64 / 2.0, 7.0);
            assert!((k.energy[d - 1] / exact - 1.0).abs() < 1e-6, "D = {d}: {} vs {exact}", k.energy[d - 1]);
        }
    }
}
