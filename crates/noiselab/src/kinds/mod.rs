//! The noise kinds, one module each, and the lattice machinery they share.

pub mod classic;
pub mod improved;
pub mod modified;
pub mod simplex;
pub mod simplex_n;
pub mod sparse;
pub mod value;
pub mod worley;

use crate::lanes::{lerp, Lanes};

/// Most corners a lattice cell has (4D).
pub(crate) const MAX_CORNERS: usize = 16;

/// Perlin's 2002 quintic fade 6t⁵ − 15t⁴ + 10t³, evaluated as
/// `t·t·t·(t·(t·6 − 15) + 10)` like his reference code.
#[inline(always)]
pub(crate) fn fade5<L: Lanes>(t: L) -> L {
    t * t * t * (t * (t * L::cst(6.0) - L::cst(15.0)) + L::cst(10.0))
}

/// Derivative of [`fade5`]: 30t²(t − 1)².
#[inline(always)]
pub(crate) fn fade5_deriv<L: Lanes>(t: L) -> L {
    let u = t - L::cst(1.0);
    L::cst(30.0) * t * t * u * u
}

/// Multilinear interpolation of `2^D` corner values (corner `c` has bit `d`
/// set when it is the upper corner on axis `d`), axis 0 innermost — the order
/// of every reference implementation.
#[inline(always)]
pub(crate) fn interpolate<L: Lanes, const D: usize>(mut v: [L; MAX_CORNERS], s: [L; D]) -> L {
    for (d, sd) in s.iter().enumerate() {
        for k in 0..(1 << (D - d - 1)) {
            v[k] = lerp(*sd, v[2 * k], v[2 * k + 1]);
        }
    }
    v[0]
}

/// [`interpolate`] together with its gradient, by differentiating the same
/// lerp chain: the value is bit-identical to [`interpolate`]'s.
///
/// `g[c]` is the gradient of corner `c`'s own function, `s` the fade weights
/// and `ds` their derivatives.
#[inline(always)]
pub(crate) fn interpolate_gradient<L: Lanes, const D: usize>(
    mut v: [L; MAX_CORNERS],
    mut g: [[L; D]; MAX_CORNERS],
    s: [L; D],
    ds: [L; D],
) -> (L, [L; D]) {
    for d in 0..D {
        for k in 0..(1 << (D - d - 1)) {
            let (a, b) = (v[2 * k], v[2 * k + 1]);
            let (ga, gb) = (g[2 * k], g[2 * k + 1]);
            v[k] = lerp(s[d], a, b);
            for e in 0..D {
                g[k][e] = lerp(s[d], ga[e], gb[e]);
            }
            g[k][d] = g[k][d] + ds[d] * (b - a);
        }
    }
    (v[0], g[0])
}

/// Offset of corner `c` from the cell's lower corner on axis `d` (0 or 1).
#[inline(always)]
pub(crate) const fn corner_bit(c: usize, d: usize) -> i32 {
    ((c >> d) & 1) as i32
}

/// `value` where every coordinate is finite, NaN elsewhere. Simplex kernels
/// are radial, so an infinite coordinate would otherwise give a quiet 0; the
/// library's contract is NaN for non-finite input.
#[inline(always)]
#[allow(clippy::eq_op)] // x − x is 0 for finite x and NaN for ±∞ and NaN.
pub(crate) fn finite_or_nan<L: Lanes, const D: usize>(p: [L; D], value: L) -> L {
    let mut poison = L::cst(0.0);
    for c in p {
        poison = poison + (c - c);
    }
    L::select(poison.le(L::cst(0.0)), value, poison)
}
