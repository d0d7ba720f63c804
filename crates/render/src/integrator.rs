//! The path tracer: unidirectional paths from the camera with next-event estimation at every
//! surface interaction and multiple importance sampling of light and BRDF samples with the power
//! heuristic (Veach, "Robust Monte Carlo methods for light transport simulation", 1997, §9.2.4,
//! β = 2), BRDF sampling through [`Brdf::sample`], and Russian roulette after three bounces
//! (pbrt-v4 §14.5.4).
//!
//! Samples come from Owen-scrambled Sobol sequences (Burley, "Practical hash-based Owen
//! scrambling", JCGT 9(4), 2020, the `sobol_burley` crate): sample `s` of pixel `p` uses the
//! scramble seed `hash(seed, p)` and one dimension per random decision along the path. Tiles of
//! 16 × 16 pixels are spread over the threads by rayon, and every pixel depends only on the seed
//! and its index, so the image is identical for any number of threads.

use crate::error::{RenderError, Result};
use crate::geometry::Ray;
use crate::image::Image;
use crate::scene::{PrimKind, Scene};
use glam::{DVec2, DVec3};
use gonio_brdf::sampling::{Frame, cosine_hemisphere, cosine_hemisphere_pdf};
use gonio_brdf::{Brdf, BrdfSample, Rgb};
use rayon::prelude::*;
use std::time::Instant;

/// How BRDF samples are drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum BrdfSampling {
    /// Each material's own importance sampler (analytic lobes, alias method for tables).
    #[default]
    Importance,
    /// Cosine-weighted directions for every material (for comparison with importance sampling).
    Cosine,
}

/// Settings of a render. Settings left `None` come from the scene's `[render]` table, then
/// from the defaults: 64 samples per pixel, seed 0, 8 bounces.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct RenderOptions {
    /// Samples per pixel (at most 65536).
    pub spp: Option<u32>,
    /// Seed of the sample sequences.
    pub seed: Option<u32>,
    /// Longest path, in surface interactions.
    pub max_bounces: Option<u32>,
    /// Number of threads (`None`: all cores).
    pub threads: Option<usize>,
    /// How BRDF samples are drawn.
    pub sampling: BrdfSampling,
    /// Show a progress bar on a terminal.
    pub progress: bool,
}

/// The settings of one render, every choice made.
struct Settings {
    spp: u32,
    seed: u32,
    max_bounces: u32,
    sampling: BrdfSampling,
}

/// What a render cost.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RenderStats {
    /// Rays traced (camera, bounce and shadow rays).
    pub rays: u64,
    /// Wall-clock time, s.
    pub seconds: f64,
}

impl RenderStats {
    /// Rays per second.
    pub fn rays_per_second(&self) -> f64 {
        self.rays as f64 / self.seconds.max(1e-12)
    }
}

const TILE: usize = 16;

/// Render `scene` with `opts`.
pub fn render(scene: &Scene, options: &RenderOptions) -> Result<(Image, RenderStats)> {
    let opts = Settings {
        spp: options.spp.or(scene.render.spp).unwrap_or(64),
        seed: options.seed.or(scene.render.seed).unwrap_or(0),
        max_bounces: options
            .max_bounces
            .or(scene.render.max_bounces)
            .unwrap_or(8),
        sampling: options.sampling,
    };
    if opts.spp == 0 || opts.spp > 1 << 16 {
        return Err(RenderError::Invalid(format!(
            "samples per pixel must be 1 to 65536, got {}",
            opts.spp
        )));
    }
    let opts = &opts;
    let start = Instant::now();
    let (w, h) = (scene.camera.width, scene.camera.height);
    let tiles: Vec<(usize, usize)> = (0..h.div_ceil(TILE))
        .flat_map(|ty| (0..w.div_ceil(TILE)).map(move |tx| (tx * TILE, ty * TILE)))
        .collect();
    let bar = if options.progress {
        indicatif::ProgressBar::new(tiles.len() as u64)
    } else {
        indicatif::ProgressBar::hidden()
    };
    bar.set_style(
        indicatif::ProgressStyle::with_template("rendering {bar:40} {pos}/{len} tiles, eta {eta}")
            .expect("valid template"),
    );
    let run = || -> Vec<(Vec<[f32; 3]>, u64)> {
        tiles
            .par_iter()
            .map(|&(x0, y0)| {
                let mut rays = 0u64;
                let mut out = Vec::with_capacity(TILE * TILE);
                for y in y0..(y0 + TILE).min(h) {
                    for x in x0..(x0 + TILE).min(w) {
                        out.push(pixel(scene, opts, x, y, &mut rays));
                    }
                }
                bar.inc(1);
                (out, rays)
            })
            .collect()
    };
    let results = match options.threads {
        Some(n) => rayon::ThreadPoolBuilder::new()
            .num_threads(n.max(1))
            .build()
            .map_err(|e| RenderError::Invalid(format!("cannot start {n} threads: {e}")))?
            .install(run),
        None => run(),
    };
    bar.finish_and_clear();
    let mut image = Image::new(w, h);
    let mut rays = 0;
    for (&(x0, y0), (vals, r)) in tiles.iter().zip(results) {
        rays += r;
        let mut it = vals.into_iter();
        for y in y0..(y0 + TILE).min(h) {
            for x in x0..(x0 + TILE).min(w) {
                image.pixels[y * w + x] = it.next().expect("one value per pixel");
            }
        }
    }
    Ok((
        image,
        RenderStats {
            rays,
            seconds: start.elapsed().as_secs_f64(),
        },
    ))
}

/// 32-bit finaliser of MurmurHash3 (Appleby), mixing the seed and the pixel index.
fn mix(mut x: u32) -> u32 {
    x ^= x >> 16;
    x = x.wrapping_mul(0x85eb_ca6b);
    x ^= x >> 13;
    x = x.wrapping_mul(0xc2b2_ae35);
    x ^ (x >> 16)
}

/// The sample stream of one path: successive dimensions of one Sobol sample.
struct Sampler {
    index: u32,
    seed: u32,
    dim: u32,
}

impl Sampler {
    fn next(&mut self) -> f64 {
        let d = self.dim;
        self.dim += 1;
        // Past the 256 dimensions of the tables, continue with freshly seeded sequences.
        let seed = if d < sobol_burley::NUM_DIMENSIONS {
            self.seed
        } else {
            mix(self.seed ^ mix(d / sobol_burley::NUM_DIMENSIONS))
        };
        f64::from(sobol_burley::sample(
            self.index,
            d % sobol_burley::NUM_DIMENSIONS,
            seed,
        ))
    }

    fn next2(&mut self) -> DVec2 {
        DVec2::new(self.next(), self.next())
    }
}

/// The mean radiance of pixel (`x`, `y`).
fn pixel(scene: &Scene, opts: &Settings, x: usize, y: usize, rays: &mut u64) -> [f32; 3] {
    let index = (y * scene.camera.width + x) as u32;
    let seed = mix(mix(opts.seed) ^ index);
    let mut sum = Rgb::ZERO;
    for s in 0..opts.spp {
        let mut sampler = Sampler {
            index: s,
            seed,
            dim: 0,
        };
        let film = DVec2::new(x as f64, y as f64) + sampler.next2();
        let l = radiance(scene, opts, scene.camera.ray(film), &mut sampler, rays);
        if l.is_finite() {
            sum += l;
        }
    }
    (sum / f64::from(opts.spp)).as_vec3().to_array()
}

/// The power heuristic with β = 2 for a sample of density `a` against a strategy of density `b`.
fn power(a: f64, b: f64) -> f64 {
    let (a2, b2) = (a * a, b * b);
    if a2 + b2 > 0.0 { a2 / (a2 + b2) } else { 0.0 }
}

/// A BRDF sample by the chosen strategy.
fn sample_brdf(brdf: &dyn Brdf, wo: DVec3, u: DVec2, how: BrdfSampling) -> Option<BrdfSample> {
    match how {
        BrdfSampling::Importance => brdf.sample(wo, u),
        BrdfSampling::Cosine => {
            let wi = cosine_hemisphere(u);
            let pdf = cosine_hemisphere_pdf(wi.z);
            (pdf > 0.0).then(|| BrdfSample {
                wi,
                f: brdf.eval(wo, wi),
                pdf,
            })
        }
    }
}

/// The density of [`sample_brdf`].
fn brdf_pdf(brdf: &dyn Brdf, wo: DVec3, wi: DVec3, how: BrdfSampling) -> f64 {
    match how {
        BrdfSampling::Importance => brdf.pdf(wo, wi),
        BrdfSampling::Cosine => cosine_hemisphere_pdf(wi.z),
    }
}

/// A point just off the surface on the side of `n`, so that a ray from it does not hit the
/// surface it leaves.
fn offset(p: DVec3, n: DVec3) -> DVec3 {
    p + n * (1e-7 * (1.0 + p.abs().max_element()))
}

/// Radiance along `ray`.
fn radiance(
    scene: &Scene,
    opts: &Settings,
    mut ray: Ray,
    sampler: &mut Sampler,
    rays: &mut u64,
) -> Rgb {
    let shapes = scene.accel.shapes();
    let n_lights = scene.lights.len();
    let p_select = 1.0 / n_lights.max(1) as f64;
    let mut l = Rgb::ZERO;
    let mut beta = Rgb::ONE;
    // Density of the BRDF sample that produced `ray` (None: a camera ray).
    let mut prev_pdf: Option<f64> = None;
    let mut prev_p = ray.origin;
    for bounce in 0..=opts.max_bounces {
        *rays += 1;
        let Some(hit) = scene.accel.intersect(&ray, 0.0, f64::INFINITY) else {
            for light in scene.lights.iter().filter(|l| l.is_infinite()) {
                let le = light.le(ray.dir);
                let w = prev_pdf.map_or(1.0, |pdf| {
                    power(
                        pdf,
                        p_select * light.pdf(prev_p, ray.dir, DVec3::ZERO, shapes),
                    )
                });
                l += beta * le * w;
            }
            break;
        };
        let material = match scene.prims[hit.prim] {
            PrimKind::Emitter(k) => {
                let light = &scene.lights[k];
                let le = light.emitted(hit.ng, ray.dir);
                let w = prev_pdf.map_or(1.0, |pdf| {
                    power(pdf, p_select * light.pdf(prev_p, ray.dir, hit.p, shapes))
                });
                l += beta * le * w;
                break;
            }
            PrimKind::Surface(m) => &scene.materials[m],
        };
        let brdf: &dyn Brdf = material.brdf.as_ref();
        // Two-sided surfaces: shade the side the ray arrives from.
        let (ng, ns) = if hit.ng.dot(ray.dir) > 0.0 {
            (-hit.ng, -hit.ns)
        } else {
            (hit.ng, hit.ns)
        };
        let frame = Frame {
            s: hit.tangent,
            t: ns.cross(hit.tangent),
            n: ns,
        };
        let wo = frame.to_local(-ray.dir);
        if wo.z <= 0.0 {
            break;
        }
        let origin = offset(hit.p, ng);

        // Next-event estimation: one light chosen uniformly.
        if n_lights > 0 {
            let k = ((sampler.next() * n_lights as f64) as usize).min(n_lights - 1);
            let u = sampler.next2();
            if let Some(ls) = scene.lights[k].sample(hit.p, u, shapes) {
                let wi = frame.to_local(ls.wi);
                if wi.z > 0.0 && ls.wi.dot(ng) > 0.0 && ls.li != Rgb::ZERO && ls.pdf > 0.0 {
                    let f = brdf.eval(wo, wi);
                    if f != Rgb::ZERO {
                        *rays += 1;
                        let shadow = Ray { origin, dir: ls.wi };
                        // Stop short of the light itself (the origin is offset too).
                        let t_max = if ls.dist.is_finite() {
                            ls.dist * (1.0 - 1e-5)
                        } else {
                            f64::INFINITY
                        };
                        if !scene.accel.occluded(&shadow, 0.0, t_max) {
                            let pdf_l = p_select * ls.pdf;
                            let w = if ls.delta {
                                1.0
                            } else {
                                power(pdf_l, brdf_pdf(brdf, wo, wi, opts.sampling))
                            };
                            l += beta * f * ls.li * (wi.z * w / pdf_l);
                        }
                    }
                }
            }
        } else {
            sampler.next();
            sampler.next2();
        }
        if bounce == opts.max_bounces {
            break;
        }

        // Continue the path by sampling the BRDF.
        let u = sampler.next2();
        let Some(s) = sample_brdf(brdf, wo, u, opts.sampling) else {
            break;
        };
        let wi_world = frame.to_world(s.wi);
        if s.pdf <= 0.0 || s.wi.z <= 0.0 || wi_world.dot(ng) <= 0.0 {
            break;
        }
        beta *= s.f * (s.wi.z / s.pdf);
        prev_pdf = Some(s.pdf);
        prev_p = hit.p;
        ray = Ray {
            origin,
            dir: wi_world.normalize(),
        };
        let u_rr = sampler.next();
        if bounce >= 3 {
            let q = beta.max_element().min(0.95);
            if u_rr >= q || q.is_nan() {
                break;
            }
            beta /= q;
        }
    }
    l
}
