//! The render loop: samples per pixel, tiles over threads, and the film. Each sample traces one
//! path (`crate::path`) and the pixel is their mean, in linear sRGB. In the spectral mode
//! ([`ColourMode::Spectral`]) each sample also draws its wavelengths ([`crate::spectral`]) and
//! the film turns the path's spectral values into linear sRGB.
//!
//! Samples come from Owen-scrambled Sobol sequences (Burley, "Practical hash-based Owen
//! scrambling", JCGT 9(4), 2020, the `sobol_burley` crate): sample `s` of pixel `p` uses the
//! scramble seed `hash(seed, p)` and one dimension per random decision along the path. Tiles of
//! 16 × 16 pixels are spread over the threads by rayon, and every pixel depends only on the seed
//! and its index, so the image is identical for any number of threads.

use crate::denoise::{Features, denoise};
use crate::error::{RenderError, Result};
use crate::image::Image;
use crate::path::{Sampler, Tristimulus, mix, radiance};
use crate::scene::Scene;
use crate::settings::{BrdfSampling, ColourMode, Film, Settings};
use crate::spectral::{SpectralFilmSetup, SpectralPath};
use glam::DVec2;
use gonio_brdf::Rgb;
use gonio_io::{Cancel, Progress};
use rayon::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Instant;

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
    /// How colour is carried along a path: linear sRGB (the default) or spectrally.
    pub colour: ColourMode,
    /// Denoise the picture ([`crate::denoise`]) (`None`: the scene's `[render] denoise`, else
    /// no).
    pub denoise: Option<bool>,
    /// Where to report the tiles rendered (stage `rendering`; default: nowhere).
    pub progress: Progress,
    /// Raised, the render stops: every tile looks at it before its pixels and every row of the
    /// denoiser's features before its pixels, and the render returns
    /// [`RenderError::Cancelled`] (default: never).
    pub cancel: Cancel,
}

/// What a render cost.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RenderStats {
    /// Rays traced (camera, bounce and shadow rays).
    pub rays: u64,
    /// Wall-clock time, s (denoising included).
    pub seconds: f64,
    /// Whether the picture was denoised.
    pub denoised: bool,
}

impl RenderStats {
    /// Rays per second.
    pub fn rays_per_second(&self) -> f64 {
        self.rays as f64 / self.seconds.max(1e-12)
    }
}

const TILE: usize = 16;

/// Render `scene` with `options`: the Monte Carlo estimate, denoised when the options or the
/// scene ask for it.
pub fn render(scene: &Scene, options: &RenderOptions) -> Result<(Image, RenderStats)> {
    render_picture(scene, options).map(|(image, estimate)| (image, estimate.stats))
}

/// [`render`], keeping the raw estimate beside the picture (for comparisons, whose noise must
/// be the estimate's own). The estimate's statistics are the whole render's: its time includes
/// the denoising.
pub fn render_picture(scene: &Scene, options: &RenderOptions) -> Result<(Image, Estimate)> {
    let start = Instant::now();
    let mut estimate = render_estimate(scene, options)?;
    let denoised = options.denoise.or(scene.render.denoise).unwrap_or(false);
    let image = if denoised {
        let features = Features::of_until(scene, &options.cancel)?;
        denoise(&estimate.image, &estimate.variance, &features)
    } else {
        estimate.image.clone()
    };
    estimate.stats.seconds = start.elapsed().as_secs_f64();
    estimate.stats.denoised = denoised;
    Ok((image, estimate))
}

impl RenderOptions {
    /// Samples per pixel: the option, else the scene's `[render] spp`, else 64.
    pub fn samples_per_pixel(&self, scene: &Scene) -> u32 {
        self.spp.or(scene.render.spp).unwrap_or(64)
    }
}

/// The Monte Carlo estimate of a picture, before any denoising.
#[derive(Debug, Clone)]
pub struct Estimate {
    /// The mean of each pixel's samples.
    pub image: Image,
    /// The variance of each pixel mean's luminance (the samples' variance over their number;
    /// infinite from one sample).
    pub variance: Vec<f32>,
    /// What it cost.
    pub stats: RenderStats,
}

/// The Monte Carlo estimate of `scene`'s picture with `options` (which `denoise` is ignored).
pub fn render_estimate(scene: &Scene, options: &RenderOptions) -> Result<Estimate> {
    render_estimate_on(scene, options, &Film::Display)
}

/// [`render_estimate`] on the film `film`: linear sRGB relative to D65 ([`Film::Display`]) or
/// absolute XYZ in cd/m² ([`Film::Absolute`], spectral mode only), which the estimate's pixels
/// and variance then hold (X, Y, Z and the variance of Y).
pub fn render_estimate_on(scene: &Scene, options: &RenderOptions, film: &Film) -> Result<Estimate> {
    let opts = Settings {
        spp: options.samples_per_pixel(scene),
        seed: options.seed.or(scene.render.seed).unwrap_or(0),
        max_bounces: options
            .max_bounces
            .or(scene.render.max_bounces)
            .unwrap_or(8),
        sampling: options.sampling,
        colour: options.colour,
    };
    if opts.spp == 0 || opts.spp > 1 << 16 {
        return Err(RenderError::Invalid(format!(
            "samples per pixel must be 1 to 65536, got {}",
            opts.spp
        )));
    }
    if opts.colour == ColourMode::Tristimulus && *film != Film::Display {
        return Err(RenderError::Invalid(
            "an absolute film (XYZ in cd/m²) needs the spectral colour mode".into(),
        ));
    }
    let opts = &opts;
    let start = Instant::now();
    let spectral = SpectralFilmSetup::new(film);
    let (w, h) = (scene.camera.width, scene.camera.height);
    let tiles: Vec<(usize, usize)> = (0..h.div_ceil(TILE))
        .flat_map(|ty| (0..w.div_ceil(TILE)).map(move |tx| (tx * TILE, ty * TILE)))
        .collect();
    let done = AtomicU64::new(0);
    // Per tile: each pixel's mean and luminance variance, and the rays traced.
    type Tile = (Vec<([f32; 3], f32)>, u64);
    let run = || -> Vec<Tile> {
        tiles
            .par_iter()
            .map(|&(x0, y0)| {
                let mut rays = 0u64;
                let mut out = Vec::with_capacity(TILE * TILE);
                if options.cancel.is_cancelled() {
                    return (out, rays);
                }
                for y in y0..(y0 + TILE).min(h) {
                    for x in x0..(x0 + TILE).min(w) {
                        out.push(pixel(scene, opts, &spectral, x, y, &mut rays));
                    }
                }
                let finished = done.fetch_add(1, Ordering::Relaxed) + 1;
                options
                    .progress
                    .report("rendering", finished, tiles.len() as u64);
                (out, rays)
            })
            .collect()
    };
    let results = on_threads(options.threads, run)?;
    if options.cancel.is_cancelled() {
        return Err(RenderError::Cancelled);
    }
    let mut image = Image::new(w, h);
    let mut variance = vec![0.0; w * h];
    let mut rays = 0;
    for (&(x0, y0), (vals, r)) in tiles.iter().zip(results) {
        rays += r;
        let mut it = vals.into_iter();
        for y in y0..(y0 + TILE).min(h) {
            for x in x0..(x0 + TILE).min(w) {
                (image.pixels[y * w + x], variance[y * w + x]) =
                    it.next().expect("one value per pixel");
            }
        }
    }
    Ok(Estimate {
        image,
        variance,
        stats: RenderStats {
            rays,
            seconds: start.elapsed().as_secs_f64(),
            denoised: false,
        },
    })
}

/// `run` on `threads` threads (`None`: rayon's global pool, all of them).
pub(crate) fn on_threads<T: Send>(
    threads: Option<usize>,
    run: impl FnOnce() -> T + Send,
) -> Result<T> {
    Ok(match threads {
        Some(n) => rayon::ThreadPoolBuilder::new()
            .num_threads(n.max(1))
            .build()
            .map_err(|e| RenderError::Invalid(format!("cannot start {n} threads: {e}")))?
            .install(run),
        None => run(),
    })
}

/// The mean radiance of pixel (`x`, `y`) as the film records it (linear sRGB, or absolute XYZ),
/// and the variance of its luminance (the sample variance over the number of samples; infinite
/// from one sample).
fn pixel(
    scene: &Scene,
    opts: &Settings,
    spectral: &SpectralFilmSetup,
    x: usize,
    y: usize,
    rays: &mut u64,
) -> ([f32; 3], f32) {
    let index = (y * scene.camera.width + x) as u32;
    let seed = mix(mix(opts.seed) ^ index);
    let mut sum = Rgb::ZERO;
    let mut sum_sq = 0.0;
    for s in 0..opts.spp {
        let mut sampler = Sampler::new(s, seed);
        let film = DVec2::new(x as f64, y as f64) + sampler.next2();
        let ray = scene.camera.ray(film);
        let l = match opts.colour {
            ColourMode::Tristimulus => radiance(scene, opts, &Tristimulus, ray, &mut sampler, rays),
            ColourMode::Spectral => {
                let path = SpectralPath::new(spectral, s, seed);
                let v = radiance(scene, opts, &path, ray, &mut sampler, rays);
                path.to_film(v)
            }
        };
        if l.is_finite() {
            sum += l;
            sum_sq += spectral.luminance(l).powi(2);
        }
    }
    let n = f64::from(opts.spp);
    let mean = sum / n;
    let variance = if opts.spp > 1 {
        ((sum_sq / n - spectral.luminance(mean).powi(2)) / (n - 1.0)).max(0.0)
    } else {
        f64::INFINITY
    };
    (mean.as_vec3().to_array(), variance as f32)
}
