//! Perlin's textures on the command line: `noiselab render marble -o
//! marble.png` (the coloured picture) or `-o marble.npy` (the scalar field
//! before colouring), over any 3D noise (`--base`, improved by default).
//! Each entry frames one recipe of `noiselab::recipes` in the unit square.

use noiselab::recipes::{self, Hypertexture, Ramp};
use noiselab::DynNoise;
use rayon::prelude::*;

/// The base noise every recipe reads.
pub type Base = Box<dyn DynNoise<3>>;

/// A recipe's pixel: scalar field and linear RGB colour at image
/// coordinates (u, v) ∈ [0, 1]² (v down) and time t.
pub type Pixel = fn(&Base, f64, f64, f64) -> (f64, [f32; 3]);

/// One registered recipe.
pub struct RecipeSpec {
    pub name: &'static str,
    pub summary: &'static str,
    pub pixel: Pixel,
}

fn grey(v: f64) -> [f32; 3] {
    [v as f32; 3]
}

/// Every recipe, in the order `list` shows them.
pub static RECIPES: &[RecipeSpec] = &[
    RecipeSpec {
        name: "marble",
        summary: "sin(x + turbulence) through a stone colour ramp (Perlin 1985)",
        pixel: |n, u, v, t| {
            let m = recipes::marble(n, [u * 3.0, v * 3.0, t]);
            (m, Ramp::MARBLE.at(0.5 + 0.5 * m))
        },
    },
    RecipeSpec {
        name: "wood",
        summary: "rings around an axis, wobbled by low-frequency noise",
        pixel: |n, u, v, t| {
            let w = recipes::wood(n, [(u - 0.5) * 1.6, t, (v - 0.5) * 1.6]);
            (w, Ramp::WOOD.at(recipes::bias(0.7, w)))
        },
    },
    RecipeSpec {
        name: "clouds",
        summary: "colour map of y + F(x, y, z): clouds thinning with height; animate with --slice T",
        pixel: |n, u, v, t| {
            let c = recipes::clouds(n, [u * 2.0, 0.6 - v, t]);
            (c, Ramp::SKY.at(recipes::gain(0.7, 0.35 - c)))
        },
    },
    RecipeSpec {
        name: "flame",
        summary: "flame corona: radial gradient phase-shifted by turbulence moving in z over time (--slice T)",
        pixel: |n, u, v, t| {
            let f = recipes::flame(n, [(u - 0.5) * 2.0, (0.5 - v) * 2.0], t);
            (f, Ramp::FLAME.at(f * 0.7))
        },
    },
    RecipeSpec {
        name: "planet",
        summary: "the cloudy planet of slide 21: continents, oceans, drifting cloud bands (--slice T)",
        pixel: |n, u, v, t| {
            let (rgb, height) = recipes::planet(n, u, v, t);
            (height, rgb)
        },
    },
    RecipeSpec {
        name: "stucco",
        summary: "fractal bumps sharpened by Perlin's gain, lit by their own slope",
        pixel: |n, u, v, t| {
            let h = |u: f64, v: f64| recipes::stucco(n, [u, v, t]);
            let (e, s) = (1.0 / 512.0, h(u, v));
            let normal = [-(h(u + e, v) - s) / e * 0.004, (h(u, v + e) - s) / e * 0.004, 1.0];
            let l = (normal[0] * normal[0] + normal[1] * normal[1] + 1.0).sqrt();
            (s, grey(recipes::shade(normal.map(|c| c / l)) * (0.6 + 0.4 * s)))
        },
    },
    RecipeSpec {
        name: "bump",
        summary: "a sphere bump-mapped by the noise gradient (central differences), lit",
        pixel: |n, u, v, _| match recipes::bumpy_sphere(u, v, |p, normal| {
            recipes::bump_normal_numeric(n, p, normal, 0.25)
        }) {
            Some(b) => (b, [0.9 * b as f32, 0.75 * b as f32, 0.55 * b as f32]),
            None => (0.0, [0.0; 3]),
        },
    },
    RecipeSpec {
        name: "hypertexture",
        summary: "a noisy sphere of density, sharpened by gain and ray-marched (Perlin & Hoffert 1989)",
        pixel: |n, u, v, _| {
            let (light, alpha) = Hypertexture::new(n).march(u, v);
            (alpha, [(0.95 * light) as f32, (0.85 * light) as f32, (0.7 * light) as f32])
        },
    },
];

/// Looks a recipe up by name.
pub fn find(name: &str) -> Option<&'static RecipeSpec> {
    RECIPES.iter().find(|r| r.name == name)
}

/// Every pixel of a `width × height` image, rows in parallel.
pub fn render(spec: &RecipeSpec, base: &Base, (width, height): (usize, usize), t: f64) -> (Vec<f32>, Vec<[f32; 3]>) {
    let pixels: Vec<(f64, [f32; 3])> = (0..height)
        .into_par_iter()
        .flat_map_iter(|j| {
            (0..width)
                .map(move |i| (spec.pixel)(base, (i as f64 + 0.5) / width as f64, (j as f64 + 0.5) / height as f64, t))
        })
        .collect();
    (pixels.iter().map(|p| p.0 as f32).collect(), pixels.iter().map(|p| p.1).collect())
}
