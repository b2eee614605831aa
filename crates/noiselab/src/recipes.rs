//! Perlin's textures from "Making Noise" and "An Image Synthesizer" (1985),
//! each a few readable lines over *any* 3D noise, plus the tools they use:
//! fractal helpers, bias and gain, colour ramps, bump mapping and a
//! hypertexture ray marcher (Perlin & Hoffert 1989).
//!
//! Recipes work in double precision on single points; renderers call them
//! per pixel (the command line does so on every core).

use crate::lanes::math::sqrt64;
use crate::noise::{Noise, NoiseGradient};

/// Σ noise(2ⁱp)/2ⁱ over `octaves` octaves of one noise (Perlin's 1/f noise,
/// as written in the talk; [`crate::Fractal`] is the general, seeded form).
pub fn fbm<N: Noise<3>>(noise: &N, p: [f64; 3], octaves: u32) -> f64 {
    (0..octaves).map(|i| libm::ldexp(1.0, -(i as i32)) * noise.get(p.map(|c| libm::ldexp(c, i as i32)))).sum()
}

/// Σ |noise(2ⁱp)|/2ⁱ: Perlin's turbulence, whose creases make marble veins
/// and flames.
pub fn turbulence<N: Noise<3>>(noise: &N, p: [f64; 3], octaves: u32) -> f64 {
    (0..octaves).map(|i| libm::ldexp(1.0, -(i as i32)) * noise.get(p.map(|c| libm::ldexp(c, i as i32))).abs()).sum()
}

/// Perlin's bias: `t^(ln b / ln ½)`, so bias(b, ½) = b. Pushes [0, 1]
/// towards 0 (b < ½) or 1 (b > ½). Inputs are clamped to [0, 1].
///
/// ```
/// use noiselab::recipes::bias;
/// assert!((bias(0.25, 0.5) - 0.25).abs() < 1e-12);
/// assert_eq!(bias(0.8, 0.0), 0.0);
/// assert_eq!(bias(0.8, 1.0), 1.0);
/// ```
pub fn bias(b: f64, t: f64) -> f64 {
    let (b, t) = (b.clamp(1e-9, 1.0 - 1e-9), t.clamp(0.0, 1.0));
    libm::pow(t, libm::log(b) / libm::log(0.5))
}

/// Perlin's gain: an S-curve (g > ½ sharpens towards 0 and 1, g < ½
/// flattens), built from two halves of [`bias`]; gain(g, ½) = ½.
///
/// ```
/// use noiselab::recipes::gain;
/// assert!((gain(0.9, 0.5) - 0.5).abs() < 1e-12);
/// assert!(gain(0.9, 0.3) < 0.3 && gain(0.9, 0.7) > 0.7);
/// ```
pub fn gain(g: f64, t: f64) -> f64 {
    let t = t.clamp(0.0, 1.0);
    if t < 0.5 {
        bias(1.0 - g, 2.0 * t) / 2.0
    } else {
        1.0 - bias(1.0 - g, 2.0 - 2.0 * t) / 2.0
    }
}

/// A colour ramp: stops (position in [0, 1], linear RGB in [0, 1]),
/// interpolated linearly, clamped at the ends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ramp(pub &'static [(f64, [f32; 3])]);

impl Ramp {
    /// White veins in grey-green stone.
    pub const MARBLE: Ramp = Ramp(&[
        (0.0, [0.16, 0.18, 0.17]),
        (0.45, [0.55, 0.58, 0.55]),
        (0.8, [0.92, 0.93, 0.9]),
        (1.0, [1.0, 1.0, 1.0]),
    ]);
    /// Light and dark rings of wood.
    pub const WOOD: Ramp = Ramp(&[(0.0, [0.78, 0.55, 0.3]), (0.7, [0.65, 0.42, 0.2]), (1.0, [0.38, 0.2, 0.08])]);
    /// Blue sky to white cloud.
    pub const SKY: Ramp = Ramp(&[
        (0.0, [0.2, 0.4, 0.85]),
        (0.45, [0.45, 0.62, 0.92]),
        (0.75, [0.95, 0.96, 0.98]),
        (1.0, [1.0, 1.0, 1.0]),
    ]);
    /// Black through red and orange to yellow-white.
    pub const FLAME: Ramp = Ramp(&[
        (0.0, [0.0, 0.0, 0.0]),
        (0.35, [0.6, 0.05, 0.0]),
        (0.6, [1.0, 0.45, 0.0]),
        (0.85, [1.0, 0.85, 0.3]),
        (1.0, [1.0, 1.0, 0.85]),
    ]);
    /// Black to white.
    pub const GREY: Ramp = Ramp(&[(0.0, [0.0, 0.0, 0.0]), (1.0, [1.0, 1.0, 1.0])]);

    /// The colour at `t` (NaN gives the first stop).
    ///
    /// ```
    /// use noiselab::recipes::Ramp;
    /// assert_eq!(Ramp::GREY.at(0.5), [0.5, 0.5, 0.5]);
    /// assert_eq!(Ramp::GREY.at(7.0), [1.0, 1.0, 1.0]);
    /// ```
    pub fn at(&self, t: f64) -> [f32; 3] {
        let stops = self.0;
        let t = if t.is_nan() { stops[0].0 } else { t };
        let k = stops.iter().position(|s| s.0 >= t).unwrap_or(stops.len() - 1);
        if k == 0 {
            return stops[0].1;
        }
        let ((a, ca), (b, cb)) = (stops[k - 1], stops[k]);
        let f = (((t - a) / (b - a)).clamp(0.0, 1.0)) as f32;
        core::array::from_fn(|c| ca[c] + f * (cb[c] - ca[c]))
    }
}

/// Marble (Perlin 1985): `sin(x + turbulence)`, veins where the sine
/// crests are pushed around by turbulence. In [−1, 1]; colour with
/// [`Ramp::MARBLE`] at (v + 1)/2.
///
/// ```
/// use noiselab::{recipes::marble, Improved};
/// let v = marble(&Improved::new(0), [0.3, 0.4, 0.5]);
/// assert!((-1.0..=1.0).contains(&v));
/// ```
pub fn marble<N: Noise<3>>(noise: &N, p: [f64; 3]) -> f64 {
    libm::sin(p[0] * 6.0 + 10.0 * turbulence(noise, p, 6))
}

/// Wood: concentric rings around the y axis, their radius wobbled by
/// low-frequency noise. The fraction of the ring count, in [0, 1).
///
/// ```
/// use noiselab::{recipes::wood, Improved};
/// let v = wood(&Improved::new(0), [0.3, 0.4, 0.5]);
/// assert!((0.0..1.0).contains(&v));
/// ```
pub fn wood<N: Noise<3>>(noise: &N, p: [f64; 3]) -> f64 {
    let r = sqrt64(p[0] * p[0] + p[2] * p[2]) * 10.0 + 2.0 * noise.get([p[0] * 0.8, p[1] * 0.2, p[2] * 0.8]);
    r - libm::floor(r)
}

/// Clouds (the talk's sky): a colour map of `y + F(x, y, z)` with F a
/// fractal sum, so clouds thin out with height. Animate by moving z.
///
/// ```
/// use noiselab::{recipes::clouds, Improved};
/// assert!(clouds(&Improved::new(0), [0.3, 0.4, 0.5]).is_finite());
/// ```
pub fn clouds<N: Noise<3>>(noise: &N, p: [f64; 3]) -> f64 {
    p[1] + fbm(noise, [p[0] * 3.0, p[1] * 3.0, p[2]], 7)
}

/// The flame corona: a radial gradient from the centre whose phase is
/// shifted by turbulence, the noise stretched in x, y and moved in z over
/// time `t`, so the flame flickers outwards. In about [−1, 1.5];
/// colour with [`Ramp::FLAME`].
///
/// ```
/// use noiselab::{recipes::flame, Improved};
/// let (inside, outside) = (flame(&Improved::new(0), [0.0, 0.05], 0.0), flame(&Improved::new(0), [0.9, 0.9], 0.0));
/// assert!(inside > outside);
/// ```
pub fn flame<N: Noise<3>>(noise: &N, [x, y]: [f64; 2], t: f64) -> f64 {
    let r = sqrt64(x * x + y * y);
    1.2 - 2.0 * r + 0.9 * turbulence(noise, [x * 3.0, y * 3.0, -t * 1.5], 6)
}

/// Stucco: a bumpy height field, fractal noise sharpened by [`gain`] so
/// flat plaster meets sudden lumps. In [0, 1].
///
/// ```
/// use noiselab::{recipes::stucco, Improved};
/// let v = stucco(&Improved::new(0), [0.3, 0.4, 0.5]);
/// assert!((0.0..=1.0).contains(&v));
/// ```
pub fn stucco<N: Noise<3>>(noise: &N, p: [f64; 3]) -> f64 {
    gain(0.8, 0.5 + 0.6 * fbm(noise, p.map(|c| c * 8.0), 5))
}

fn normalize(v: [f64; 3]) -> [f64; 3] {
    let l = sqrt64(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if l > 0.0 {
        v.map(|c| c / l)
    } else {
        v
    }
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The light of every lit recipe: from the upper left, in front.
pub const LIGHT: [f64; 3] = [-0.48, 0.6, 0.64];

/// Bump mapping (Perlin 1985; the sparse-convolution paper's Figure 6):
/// the normal `n` tilted by the part of the noise gradient tangent to the
/// surface, `n' = normalize(n − k·(∇f − (∇f·n)·n))`, with the analytic
/// gradient.
///
/// ```
/// use noiselab::{recipes::{bump_normal, bump_normal_numeric}, Improved};
/// let (noise, p, n) = (Improved::new(0), [0.3, 0.4, 0.5], [0.0, 0.0, 1.0]);
/// let (a, b) = (bump_normal(&noise, p, n, 0.3), bump_normal_numeric(&noise, p, n, 0.3));
/// assert!((0..3).all(|k| (a[k] - b[k]).abs() < 1e-6));
/// ```
pub fn bump_normal<N: NoiseGradient<3>>(noise: &N, p: [f64; 3], n: [f64; 3], strength: f64) -> [f64; 3] {
    tilt(n, noise.get_gradient(p).1, strength)
}

/// [`bump_normal`] for any noise, with the gradient from central
/// differences (h = 1e-4), as the sparse-convolution paper does.
pub fn bump_normal_numeric<N: Noise<3>>(noise: &N, p: [f64; 3], n: [f64; 3], strength: f64) -> [f64; 3] {
    let h = 1e-4;
    let g = core::array::from_fn(|k| {
        let (mut a, mut b) = (p, p);
        a[k] += h;
        b[k] -= h;
        (noise.get(a) - noise.get(b)) / (2.0 * h)
    });
    tilt(n, g, strength)
}

fn tilt(n: [f64; 3], g: [f64; 3], strength: f64) -> [f64; 3] {
    let along = dot(g, n);
    normalize(core::array::from_fn(|k| n[k] - strength * (g[k] - along * n[k])))
}

/// Diffuse + specular light for a normal seen from +z.
pub fn shade(n: [f64; 3]) -> f64 {
    let diffuse = dot(n, LIGHT).max(0.0);
    let half = normalize([LIGHT[0], LIGHT[1], LIGHT[2] + 1.0]);
    let specular = libm::pow(dot(n, half).max(0.0), 40.0);
    (0.08 + 0.85 * diffuse + 0.35 * specular).min(1.0)
}

/// A unit sphere seen from +z filling the image: the surface point and
/// normal under image coordinates (u, v) ∈ [0, 1]² (v down), or None off
/// the sphere.
pub fn sphere_at(u: f64, v: f64) -> Option<[f64; 3]> {
    let (x, y) = (u * 2.2 - 1.1, 1.1 - v * 2.2);
    let z2 = 1.0 - x * x - y * y;
    (z2 >= 0.0).then(|| [x, y, sqrt64(z2)])
}

/// The bump-mapped sphere: brightness at image coordinates (u, v), with
/// the surface normal tilted by noise at 6× the sphere's scale; None off
/// the sphere. `normal` chooses the analytic or numeric tilt.
///
/// ```
/// use noiselab::{recipes::{bump_normal, bumpy_sphere}, Improved};
/// let noise = Improved::new(0);
/// let lit = bumpy_sphere(0.5, 0.5, |p, n| bump_normal(&noise, p, n, 0.3)).unwrap();
/// assert!((0.0..=1.0).contains(&lit));
/// assert!(bumpy_sphere(0.0, 0.0, |_, n| n).is_none());
/// ```
pub fn bumpy_sphere(u: f64, v: f64, normal: impl Fn([f64; 3], [f64; 3]) -> [f64; 3]) -> Option<f64> {
    let p = sphere_at(u, v)?;
    Some(shade(normal(p.map(|c| c * 6.0), p)))
}

/// The cloudy planet of the talk's slide 21: oceans and continents from
/// fractal noise on the sphere, white cloud bands from turbulence drifting
/// with time `t`, lit from the upper left. Returns the colour (black off
/// the planet) and the land height.
///
/// ```
/// use noiselab::{recipes::planet, Improved};
/// let noise = Improved::new(0);
/// assert_eq!(planet(&noise, 0.0, 0.0, 0.0), ([0.0; 3], 0.0)); // a corner: space
/// let (rgb, _) = planet(&noise, 0.5, 0.5, 0.0);
/// assert!(rgb.iter().all(|c| (0.0..=1.0).contains(c)) && rgb.iter().any(|&c| c > 0.05));
/// ```
pub fn planet<N: Noise<3>>(noise: &N, u: f64, v: f64, t: f64) -> ([f32; 3], f64) {
    let Some(p) = sphere_at(u, v) else { return ([0.0; 3], 0.0) };
    let height = fbm(noise, p.map(|c| c * 2.5), 7);
    let ground: [f32; 3] = if height < 0.02 {
        let depth = ((0.02 - height) * 3.0).clamp(0.0, 1.0) as f32;
        [0.05, 0.2 - 0.1 * depth, 0.55 - 0.25 * depth]
    } else if height < 0.25 {
        [0.2, 0.45, 0.15]
    } else {
        [0.55, 0.45, 0.35]
    };
    let swirl = [p[0] * 3.0 + t, p[1] * 9.0, p[2] * 3.0];
    let cloud = gain(0.75, (turbulence(noise, swirl, 5) * 2.2 - 0.75).clamp(0.0, 1.0)) as f32;
    let light = shade(p) as f32;
    let rgb = core::array::from_fn(|c| (ground[c] * (1.0 - cloud) + cloud) * light);
    (rgb, height)
}

/// A hypertexture (Perlin & Hoffert 1989): a soft sphere's density
/// disturbed by fractal noise, sharpened by [`gain`] so the transition from
/// empty to solid is a couple of ray samples thick.
///
/// ```
/// use noiselab::{recipes::Hypertexture, Improved};
/// let h = Hypertexture::new(Improved::new(0));
/// assert!(h.density([0.0; 3]) > 0.9 && h.density([2.0, 0.0, 0.0]) < 0.1);
/// let (centre, corner) = (h.march(0.5, 0.5), h.march(0.02, 0.02));
/// assert!(centre.1 > 0.99 && corner.1 < 0.01); // opaque at the centre, empty in the corner
/// ```
#[derive(Clone, Debug)]
pub struct Hypertexture<N> {
    noise: N,
    /// How far noise moves the surface (in sphere radii).
    pub roughness: f64,
    /// Noise frequency (features per radius).
    pub frequency: f64,
    /// The gain applied to the density (higher = harder surface).
    pub sharpness: f64,
}

impl<N: Noise<3>> Hypertexture<N> {
    /// A rough sphere of radius 1 made of `noise`.
    pub fn new(noise: N) -> Hypertexture<N> {
        Hypertexture { noise, roughness: 0.45, frequency: 2.5, sharpness: 0.9 }
    }

    /// Density in [0, 1] at `p`: 1 − |p| + roughness·fBm, centred on ½ at
    /// the surface and sharpened by `gain`.
    pub fn density(&self, p: [f64; 3]) -> f64 {
        let r = sqrt64(dot(p, p));
        let d = 1.0 - r + self.roughness * fbm(&self.noise, p.map(|c| c * self.frequency), 5);
        gain(self.sharpness, (0.5 + 2.0 * d).clamp(0.0, 1.0))
    }

    /// Marches the ray through image coordinates (u, v) along −z, front to
    /// back, accumulating opacity from the density and shading each step
    /// by the density gradient (central differences) as a normal. Returns
    /// brightness and the accumulated opacity (the scalar field).
    pub fn march(&self, u: f64, v: f64) -> (f64, f64) {
        let (x, y) = (u * 3.0 - 1.5, 1.5 - v * 3.0);
        let steps = 160;
        let dz = 3.0 / steps as f64;
        let (mut light, mut alpha) = (0.0, 0.0);
        for k in 0..steps {
            let p = [x, y, 1.5 - (k as f64 + 0.5) * dz];
            let density = self.density(p);
            if density <= 1e-4 {
                continue;
            }
            let a = (1.0 - libm::exp(-density * dz * 25.0)) * (1.0 - alpha);
            let h = 0.02;
            let g: [f64; 3] = core::array::from_fn(|k| {
                let (mut q, mut r) = (p, p);
                q[k] += h;
                r[k] -= h;
                self.density(r) - self.density(q)
            });
            light += a * shade(normalize(g));
            alpha += a;
            if alpha > 0.995 {
                break;
            }
        }
        (light, alpha)
    }
}
