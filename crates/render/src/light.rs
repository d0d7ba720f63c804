//! Light sources and their sampling for next-event estimation: point lights, distant
//! (collimated) lights, spherical and planar (rectangle, disk) area lights, an equirectangular
//! environment map importance-sampled by luminance times the cosine to the lit surface's normal
//! ([`crate::env_guide`]), and a uniform sky sampled by that cosine. Every sampler returns the
//! direction, the radiance and the solid-angle pdf together, and [`Light::pdf`] gives the same
//! pdf for any direction and normal, so that multiple importance sampling can weigh light and
//! BRDF samples (Veach 1997, ch. 9).
//!
//! The environment is mapped with +y up: a direction `(sin θ cos φ, cos θ, sin θ sin φ)` reads
//! the map at `u = (φ - rotation)/2π` (column), `v = θ/π` (row, 0 at the top).

use crate::env_guide::CosineGuide;
use crate::geometry::{Shape, planar_coords};
use crate::image::Image;
use glam::{DVec2, DVec3};
use gonio_brdf::Rgb;
use gonio_brdf::sampling::{Frame, concentric_disk, cosine_hemisphere, cosine_hemisphere_pdf};
use gonio_brdf::trig::{acos, atan2};
use std::f64::consts::{PI, TAU};

/// A light sample seen from a point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LightSample {
    /// Unit direction from the point toward the light.
    pub wi: DVec3,
    /// Distance to the light (infinite for environment lights).
    pub dist: f64,
    /// Incident radiance (for a point light: intensity / distance²; for a distant light its
    /// irradiance).
    pub li: Rgb,
    /// Pdf per steradian; for a point light 1 with `delta` set.
    pub pdf: f64,
    /// A delta light (no MIS: BRDF sampling cannot find it).
    pub delta: bool,
}

/// A light.
#[derive(Debug)]
pub enum Light {
    /// Isotropic point light of intensity W/sr per channel.
    Point { position: DVec3, intensity: Rgb },
    /// A distant, collimated light (pbrt-v4 §12.4, `DistantLight`): every point receives the
    /// irradiance `irradiance` (W/m² per channel, on a plane facing the light) from the one
    /// unit direction `direction` toward the light; a delta in direction that only light
    /// samples find.
    Distant { direction: DVec3, irradiance: Rgb },
    /// An emitting primitive of the scene (sphere or planar), uniform radiance on its front.
    Area { prim: usize, radiance: Rgb },
    /// Equirectangular environment map.
    Environment(EnvMap),
    /// Uniform radiance from every direction.
    Sky { radiance: Rgb },
}

impl Light {
    /// Whether the light is at infinity (seen by rays that leave the scene).
    pub fn is_infinite(&self) -> bool {
        matches!(self, Light::Environment(_) | Light::Sky { .. })
    }

    /// Sample a direction toward the light from `p`, a point of a surface of unit shading
    /// normal `n` (which the infinite lights sample by the cosine to it).
    pub fn sample(&self, p: DVec3, n: DVec3, u: DVec2, shapes: &[Shape]) -> Option<LightSample> {
        match self {
            Light::Point {
                position,
                intensity,
            } => {
                let d = *position - p;
                let d2 = d.length_squared();
                (d2 > 0.0).then(|| LightSample {
                    wi: d / d2.sqrt(),
                    dist: d2.sqrt(),
                    li: *intensity / d2,
                    pdf: 1.0,
                    delta: true,
                })
            }
            Light::Distant {
                direction,
                irradiance,
            } => Some(LightSample {
                wi: *direction,
                dist: f64::INFINITY,
                li: *irradiance,
                pdf: 1.0,
                delta: true,
            }),
            Light::Area { prim, radiance } => {
                let (wi, dist, pdf) = sample_shape(&shapes[*prim], p, u)?;
                Some(LightSample {
                    wi,
                    dist,
                    li: *radiance,
                    pdf,
                    delta: false,
                })
            }
            Light::Environment(env) => env.sample(n, u),
            Light::Sky { radiance } => {
                // The cosine law about the normal (pbrt-v4 §A.5.3): the whole integrand of a
                // Lambertian surface under a uniform sky, so its estimate has no variance.
                let local = cosine_hemisphere(u);
                Some(LightSample {
                    wi: Frame::from_z(n).to_world(local).normalize(),
                    dist: f64::INFINITY,
                    li: *radiance,
                    pdf: cosine_hemisphere_pdf(local.z),
                    delta: false,
                })
            }
        }
    }

    /// The solid-angle pdf with which [`Light::sample`] returns `wi` from `p` on a surface of
    /// unit shading normal `n`; for an area light `hit` is the point of the light the
    /// direction reaches.
    pub fn pdf(&self, p: DVec3, n: DVec3, wi: DVec3, hit: DVec3, shapes: &[Shape]) -> f64 {
        match self {
            Light::Point { .. } | Light::Distant { .. } => 0.0,
            Light::Area { prim, .. } => shape_pdf(&shapes[*prim], p, wi, hit),
            Light::Environment(env) => env.pdf(n, wi),
            Light::Sky { .. } => cosine_hemisphere_pdf(n.dot(wi)),
        }
    }

    /// Radiance arriving along a ray that leaves the scene in direction `dir` (infinite lights).
    pub fn le(&self, dir: DVec3) -> Rgb {
        match self {
            Light::Environment(env) => env.radiance(dir),
            Light::Sky { radiance } => *radiance,
            _ => Rgb::ZERO,
        }
    }

    /// Radiance leaving the area light's point with geometric normal `ng` toward `-dir`.
    pub fn emitted(&self, ng: DVec3, dir: DVec3) -> Rgb {
        match self {
            Light::Area { radiance, .. } if ng.dot(dir) < 0.0 => *radiance,
            _ => Rgb::ZERO,
        }
    }
}

/// Sample a point of an emitting shape seen from `p`: the direction, distance and solid-angle
/// pdf. A sphere is sampled uniformly within the cone it subtends (pbrt-v4 §6.2.4), a planar
/// shape uniformly by area, `pdf = d² / (A cos θ_light)` (pbrt-v4 §6.1).
fn sample_shape(shape: &Shape, p: DVec3, u: DVec2) -> Option<(DVec3, f64, f64)> {
    match shape {
        Shape::Sphere { centre, radius } => {
            let d = *centre - p;
            let d2 = d.length_squared();
            if d2 <= radius * radius {
                return None;
            }
            let (sin2_max, dist_c) = (radius * radius / d2, d2.sqrt());
            let cos_max = (1.0 - sin2_max).max(0.0).sqrt();
            // 1 - cos θmax computed without cancellation for small cones.
            let one_minus = sin2_max / (1.0 + cos_max);
            let cos_t = 1.0 - u.x * one_minus;
            let sin_t = (1.0 - cos_t * cos_t).max(0.0).sqrt();
            let phi = TAU * u.y;
            let frame = Frame::from_z(d / dist_c);
            let wi = frame
                .to_world(DVec3::new(sin_t * phi.cos(), sin_t * phi.sin(), cos_t))
                .normalize();
            let ray = crate::geometry::Ray { origin: p, dir: wi };
            // The grazing edge of the cone may miss by rounding: take the tangent distance.
            let dist = shape
                .intersect(&ray, 0.0, f64::INFINITY)
                .unwrap_or(dist_c * cos_t);
            Some((wi, dist, 1.0 / (TAU * one_minus)))
        }
        Shape::Planar {
            origin,
            u: a,
            v: b,
            disk,
        } => {
            let (s, t) = if *disk {
                let q = concentric_disk(u);
                (q.x, q.y)
            } else {
                (2.0 * u.x - 1.0, 2.0 * u.y - 1.0)
            };
            let q = *origin + s * *a + t * *b;
            let n = a.cross(*b).normalize();
            let d = q - p;
            let d2 = d.length_squared();
            let wi = d / d2.sqrt();
            let cos_l = -n.dot(wi);
            // Only the front (normal side) emits.
            (cos_l > 0.0 && d2 > 0.0).then(|| (wi, d2.sqrt(), d2 / (shape.area() * cos_l)))
        }
        Shape::Triangle { .. } => None,
    }
}

/// The solid-angle density of [`sample_shape`] for the direction `wi` that meets the shape at
/// `hit`.
fn shape_pdf(shape: &Shape, p: DVec3, wi: DVec3, hit: DVec3) -> f64 {
    match shape {
        Shape::Sphere { centre, radius } => {
            let d2 = (*centre - p).length_squared();
            if d2 <= radius * radius {
                return 0.0;
            }
            let sin2_max = radius * radius / d2;
            let cos_max = (1.0 - sin2_max).max(0.0).sqrt();
            1.0 / (TAU * sin2_max / (1.0 + cos_max))
        }
        Shape::Planar { origin, u, v, disk } => {
            let (a, b) = planar_coords(*origin, *u, *v, hit);
            let inside = if *disk {
                a * a + b * b <= 1.0 + 1e-9
            } else {
                a.abs() <= 1.0 + 1e-9 && b.abs() <= 1.0 + 1e-9
            };
            let n = u.cross(*v).normalize();
            let cos_l = -n.dot(wi);
            if !inside || cos_l <= 0.0 {
                return 0.0;
            }
            (hit - p).length_squared() / (shape.area() * cos_l)
        }
        Shape::Triangle { .. } => 0.0,
    }
}

/// The direction of an equirectangular map's coordinates `(u, v)` in [0, 1]²: θ = πv from +y
/// (the map's top), φ = 2πu + `rotation` from +x toward +z; [`EnvMap`]'s `dir_to_uv` inverts it.
pub(crate) fn map_direction(u: f64, v: f64, rotation: f64) -> DVec3 {
    map_direction_at(u, (PI * v).sin_cos(), rotation)
}

/// [`map_direction`] from the sine and cosine of θ = πv, for a caller that has them.
fn map_direction_at(u: f64, (sin_t, cos_t): (f64, f64), rotation: f64) -> DVec3 {
    let (sin_p, cos_p) = (TAU * u + rotation).sin_cos();
    DVec3::new(sin_t * cos_p, cos_t, sin_t * sin_p)
}

/// An equirectangular environment map, importance-sampled in proportion to luminance times
/// `sin θ` times the cosine to the lit surface's normal ([`CosineGuide`]).
#[derive(Debug)]
pub struct EnvMap {
    image: Image,
    scale: f64,
    rotation: f64,
    /// Pixels in proportion to luminance times `sin θ` times the cosine, per normal.
    guide: CosineGuide,
}

impl EnvMap {
    /// The map `image` scaled by `scale`, turned by `rotation_rad` about +y.
    pub fn new(image: Image, scale: f64, rotation_rad: f64) -> EnvMap {
        let (w, h) = (image.width, image.height);
        let weights: Vec<f64> = (0..h)
            .flat_map(|j| {
                let sin_t = (PI * (j as f64 + 0.5) / h as f64).sin();
                let image = &image;
                (0..w).map(move |i| luminance(image.get(i, j)) * sin_t)
            })
            .collect();
        let guide = CosineGuide::new(&weights, w, h, rotation_rad);
        EnvMap {
            image,
            scale,
            rotation: rotation_rad,
            guide,
        }
    }

    fn dir_to_uv(&self, d: DVec3) -> (f64, f64) {
        let theta = acos(d.y.clamp(-1.0, 1.0));
        let phi = (atan2(d.z, d.x) - self.rotation).rem_euclid(TAU);
        (phi / TAU, theta / PI)
    }

    fn pixel(&self, u: f64, v: f64) -> (usize, usize) {
        let (w, h) = (self.image.width, self.image.height);
        (
            ((u * w as f64) as usize).min(w - 1),
            ((v * h as f64) as usize).min(h - 1),
        )
    }

    /// Radiance from direction `d`.
    pub fn radiance(&self, d: DVec3) -> Rgb {
        let (u, v) = self.dir_to_uv(d);
        let (i, j) = self.pixel(u, v);
        Rgb::from_array(self.image.get(i, j).map(f64::from)) * self.scale
    }

    fn sample(&self, n: DVec3, u: DVec2) -> Option<LightSample> {
        if self.guide.total() <= 0.0 {
            return None;
        }
        let ((i, j), p, pdf_uv) = self.guide.sample(n, u)?;
        let (uu, v) = (p.x, p.y);
        // Keep off the poles, where the density per steradian is singular.
        let v = v.clamp(1e-9, 1.0 - 1e-9);
        let (sin_t, cos_t) = (PI * v).sin_cos();
        if sin_t <= 0.0 {
            return None;
        }
        let wi = map_direction_at(uu, (sin_t, cos_t), self.rotation);
        // The radiance of the sampled pixel itself (recomputing it from `wi` could round into a
        // neighbour at a pixel edge).
        Some(LightSample {
            wi,
            dist: f64::INFINITY,
            li: Rgb::from_array(self.image.get(i, j).map(f64::from)) * self.scale,
            pdf: pdf_uv / (2.0 * PI * PI * sin_t),
            delta: false,
        })
    }

    fn pdf(&self, n: DVec3, d: DVec3) -> f64 {
        if self.guide.total() <= 0.0 {
            return 0.0;
        }
        let (u, v) = self.dir_to_uv(d);
        let (i, j) = self.pixel(u, v);
        let sin_t = (PI * v).sin();
        if sin_t <= 0.0 {
            return 0.0;
        }
        self.guide.density(n, i, j) / (2.0 * PI * PI * sin_t)
    }
}

/// Luminance of linear sRGB (ITU-R BT.709 weights, the Y row of the sRGB matrix).
pub fn luminance(c: [f32; 3]) -> f64 {
    0.2126 * f64::from(c[0]) + 0.7152 * f64::from(c[1]) + 0.0722 * f64::from(c[2])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Integrate a light's pdf over the sphere by the midpoint rule.
    fn pdf_integral(pdf: impl Fn(DVec3) -> f64, n: usize) -> f64 {
        let mut sum = 0.0;
        for i in 0..n {
            let theta = PI * (i as f64 + 0.5) / n as f64;
            for k in 0..2 * n {
                let d = map_direction((k as f64 + 0.5) / (2 * n) as f64, theta / PI, 0.0);
                sum += pdf(d) * theta.sin();
            }
        }
        sum * (PI / n as f64) * (PI / n as f64)
    }

    fn test_map() -> EnvMap {
        let mut img = Image::new(16, 8);
        for (k, p) in img.pixels.iter_mut().enumerate() {
            let v = 0.1 + ((k * 7919) % 13) as f32;
            *p = [v, 0.5 * v, 0.2];
        }
        EnvMap::new(img, 2.0, 0.3)
    }

    /// Normals to light from: the poles, the map's seam, and directions between.
    fn normals() -> Vec<DVec3> {
        let mut n = vec![DVec3::Y, -DVec3::Y, DVec3::X, DVec3::Z, -DVec3::Z];
        n.extend((0..12).map(|k| {
            let (t, p) = (0.3 + 0.21 * k as f64, 1.7 * k as f64);
            map_direction(p / TAU, t / PI, 0.0)
        }));
        n
    }

    #[test]
    fn environment_pdf_integrates_to_one_covers_the_hemisphere_and_matches_samples() {
        let env = test_map();
        for n in normals() {
            let total = pdf_integral(|d| env.pdf(n, d), 400);
            assert!((total - 1.0).abs() < 2e-3, "{n}: {total}");
            // Every direction above the horizon (the map has no black pixel) can be sampled:
            // a light sample alone is unbiased.
            let uncovered =
                pdf_integral(|d| f64::from(d.dot(n) > 1e-9 && env.pdf(n, d) <= 0.0), 200);
            assert_eq!(uncovered, 0.0, "{n}");
            for k in 1..500 {
                let u = DVec2::new((k as f64 * 0.618034).fract(), (k as f64 * 0.7548).fract());
                let s = env.sample(n, u).unwrap();
                assert!((env.pdf(n, s.wi) / s.pdf - 1.0).abs() < 1e-6);
                assert_eq!(s.li, env.radiance(s.wi));
            }
        }
    }

    #[test]
    fn few_environment_samples_fall_below_the_horizon() {
        // A 256 × 128 map has 64 × 32 cells of 5.6°, each within about 4° of its centre, and
        // the normal cells reach about 4° from theirs: the cosine bound lets the density
        // spill into a band about 8° deep below the horizon, where the bound is at most
        // sin 8° = 0.14; the band holds about 2π ∫₀^0.14 (0.14 − x) dx / π ≈ 2% of the
        // density of a uniform map (the test map's pixels vary 130-fold, hence 4%).
        let mut img = Image::new(256, 128);
        for (k, p) in img.pixels.iter_mut().enumerate() {
            *p = [0.1 + ((k * 7919) % 13) as f32; 3];
        }
        let env = EnvMap::new(img, 1.0, 0.3);
        for n in normals() {
            let below = pdf_integral(|d| if d.dot(n) < 0.0 { env.pdf(n, d) } else { 0.0 }, 400);
            assert!(below < 0.04, "{n}: {below}");
        }
    }

    #[test]
    fn sky_pdf_is_the_cosine_law_about_the_normal() {
        let sky = Light::Sky { radiance: Rgb::ONE };
        for n in normals() {
            let total = pdf_integral(|d| sky.pdf(DVec3::ZERO, n, d, DVec3::ZERO, &[]), 400);
            assert!((total - 1.0).abs() < 2e-3, "{n}: {total}");
            for k in 1..200 {
                let u = DVec2::new((k as f64 * 0.618034).fract(), (k as f64 * 0.7548).fract());
                let s = sky.sample(DVec3::ZERO, n, u, &[]).unwrap();
                assert!(s.wi.dot(n) >= 0.0);
                let pdf = sky.pdf(DVec3::ZERO, n, s.wi, DVec3::ZERO, &[]);
                assert!((pdf / s.pdf - 1.0).abs() < 1e-9, "{pdf} {}", s.pdf);
            }
        }
    }

    #[test]
    fn area_light_pdfs_integrate_to_one_and_match_samples() {
        let p = DVec3::new(0.2, -0.1, 0.0);
        let shapes = [
            Shape::Sphere {
                centre: DVec3::new(0.5, 3.0, 0.2),
                radius: 0.8,
            },
            Shape::Planar {
                origin: DVec3::new(0.0, 2.0, 0.5),
                u: DVec3::new(0.7, 0.0, 0.2),
                v: DVec3::new(0.0, 0.3, 0.5),
                disk: false,
            },
            Shape::Planar {
                origin: DVec3::new(0.0, 2.0, 0.5),
                u: DVec3::new(0.7, 0.0, 0.2),
                v: DVec3::new(0.0, 0.3, 0.5),
                disk: true,
            },
        ];
        for shape in &shapes {
            // Point the planar lights' fronts toward p.
            let shape = match shape {
                Shape::Planar { origin, u, v, disk } if u.cross(*v).dot(p - *origin) < 0.0 => {
                    Shape::Planar {
                        origin: *origin,
                        u: *v,
                        v: *u,
                        disk: *disk,
                    }
                }
                s => s.clone(),
            };
            let pdf = |d: DVec3| {
                let r = crate::geometry::Ray { origin: p, dir: d };
                match shape.intersect(&r, 0.0, f64::INFINITY) {
                    Some(t) => shape_pdf(&shape, p, d, p + t * d),
                    None => 0.0,
                }
            };
            let total = pdf_integral(pdf, 800);
            assert!((total - 1.0).abs() < 0.01, "{shape:?}: {total}");
            for k in 0..200 {
                let u = DVec2::new((k as f64 * 0.618034).fract(), (k as f64 * 0.7548).fract());
                let (wi, dist, pdf_s) = sample_shape(&shape, p, u).unwrap();
                let q = p + dist * wi;
                assert!((shape_pdf(&shape, p, wi, q) / pdf_s - 1.0).abs() < 1e-6);
            }
        }
    }
}
