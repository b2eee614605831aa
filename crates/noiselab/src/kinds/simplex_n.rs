//! Simplex noise in any dimension (Perlin, "Making Noise", 1999: "simplex
//! noise … for higher dimensions", cost O(n²) instead of the cube
//! lattice's O(2ⁿ)).

use super::finite_or_nan;
use crate::hash::hash_cell;
use crate::lanes::{IntLanes, Lanes};
use crate::noise::Noise;

/// Work done by one evaluation, counted by the same loops that do it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SimplexCost {
    /// Simplex corners evaluated (D + 1).
    pub corners: usize,
    /// Coordinate comparisons made to rank the axes.
    pub comparisons: usize,
    /// Per-coordinate operations over all corners (offsets, distance, dot).
    pub coordinate_ops: usize,
}

/// N-dimensional simplex noise for any `D ≥ 1` (`Noise<D>` for every D).
///
/// Skew `F = (√(D+1) − 1)/D`, unskew `G = (1 − 1/√(D+1))/D`; the simplex
/// is found by ranking the axes (ties broken by axis index); each of the
/// D + 1 corners contributes `max(0, ½ − |d|²)⁴ · (g · d)` with a gradient of
/// ±1 components from a table-free hash of the corner and the seed. The
/// radius² ½ keeps the field continuous (unlike the 0.6 of Gustavson's
/// 3D/4D). Output is multiplied by a per-dimension constant so it lies in
/// \[−1, 1\] (measured for D ≤ 8 by hill climbing, with a 10 % margin;
/// extrapolated, untested, above 8). Not value-compatible
/// with [`crate::Simplex`], which is Gustavson-exact in 2D–4D. Dimensions
/// above 32 reuse gradient bits.
///
/// Not tileable (no `with_period`): its skewed lattice does not line up
/// with axis-aligned periods.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct SimplexN {
    seed: u32,
}

/// Output scale per dimension (index D): 0.9 / (largest unscaled |value|
/// found by hill climbing from 2,000 starts), rounded down. Those maxima were
/// 0.0140, 0.0143, 0.0161, 0.0184, 0.0206, 0.0225, 0.0243, 0.0260 for D = 1..8.
const SCALE: [f64; 9] = [0.0, 64.0, 63.0, 55.0, 48.0, 43.0, 39.0, 36.0, 34.0];

/// Scale for any D: the table, then an extrapolation of its trend (the
/// maximum grows by about 0.002 per dimension), untested beyond 8.
fn scale(d: usize) -> f64 {
    if d < SCALE.len() {
        SCALE[d]
    } else {
        0.9 / (0.026 + 0.002 * (d - 8) as f64)
    }
}

impl SimplexN {
    /// N-dimensional simplex noise for `seed`.
    pub fn new(seed: u32) -> Self {
        SimplexN { seed }
    }

    /// The seed.
    pub fn seed(&self) -> u32 {
        self.seed
    }

    /// Evaluate and count the work (for cost tests).
    pub fn sample_counted<L: Lanes, const D: usize>(&self, p: [L; D]) -> (L, SimplexCost) {
        let mut cost = SimplexCost::default();
        let v = self.eval(p, &mut cost);
        (v, cost)
    }

    #[inline(always)]
    fn eval<L: Lanes, const D: usize>(&self, p: [L; D], cost: &mut SimplexCost) -> L {
        let n = D as f64;
        let f = L::cst(((n + 1.0).sqrt() - 1.0) / n);
        let g = L::cst((1.0 - 1.0 / (n + 1.0).sqrt()) / n);
        let mut sum = L::cst(0.0);
        for x in p {
            sum = sum + x;
        }
        let s = sum * f;
        // (A loop, not `map`: a closure would not inherit the batch
        // driver's instruction set.)
        let mut cell = [L::Int::splat(0); D];
        for d in 0..D {
            cell[d] = (p[d] + s).floor().to_int_wrapping();
        }
        let mut csum = L::Int::splat(0);
        for c in cell {
            csum = csum.add(c);
        }
        let t = L::from_int(csum) * g;
        let mut x0 = p;
        for d in 0..D {
            x0[d] = p[d] - (L::from_int(cell[d]) - t);
        }
        // rank[i] = axes that come before i in decreasing order: O(D²).
        let mut rank = [L::Int::splat(0); D];
        for i in 0..D {
            for j in i + 1..D {
                cost.comparisons += 1;
                let j_first = L::Int::select(x0[j].gt(x0[i]), L::Int::splat(1), L::Int::splat(0));
                rank[i] = rank[i].add(j_first);
                rank[j] = rank[j].add(L::Int::splat(1).sub(j_first));
            }
        }
        let mut total = L::cst(0.0);
        for k in 0..=D {
            cost.corners += 1;
            let kg = L::cst(k as f64) * g;
            let mut node = cell;
            let mut d = x0;
            for i in 0..D {
                cost.coordinate_ops += 1;
                let step = L::Int::select(rank[i].lt(L::Int::splat(k as i32)), L::Int::splat(1), L::Int::splat(0));
                node[i] = cell[i].add(step);
                d[i] = x0[i] - L::from_int(step) + kg;
            }
            let h = hash_cell(node, self.seed);
            let mut r = L::cst(0.5);
            let mut dot = L::cst(0.0);
            for i in 0..D {
                cost.coordinate_ops += 1;
                r = r - d[i] * d[i];
                dot = dot + L::select(h.bit((i % 32) as u32), d[i], -d[i]);
            }
            let r2 = r * r;
            total = total + L::select(r.lt(L::cst(0.0)), L::cst(0.0), r2 * r2 * dot);
        }
        finite_or_nan(p, total * L::cst(scale(D)))
    }
}

impl<const D: usize> Noise<D> for SimplexN {
    crate::grid::batch_entry!(D);
    #[inline(always)]
    fn sample<L: Lanes>(&self, p: [L; D]) -> L {
        const { assert!(D >= 1, "SimplexN needs at least one dimension") };
        self.eval(p, &mut SimplexCost::default())
    }
}

// This module's batch drivers per instruction-set level (`grid::batch_clones!`).
crate::grid::batch_clones!();
