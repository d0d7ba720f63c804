//! Denoising of a rendered picture, so that a few dozen samples per pixel give a picture whose
//! noise a person cannot see: the edge-avoiding à-trous wavelet filter of Dammertz, Sewtz,
//! Hanika and Lensch ("Edge-Avoiding À-Trous Wavelet Transform for fast Global Illumination
//! Filtering", HPG 2010), steered by each pixel's estimated variance as in SVGF (Schied et al.,
//! "Spatiotemporal Variance-Guided Filtering", HPG 2017, §4 and eq. 3–5; spatial part only).
//!
//! Five passes of a 5 × 5 B3-spline kernel with holes of 1, 2, 4, 8 and 16 pixels average each
//! pixel with neighbours up to 62 pixels away, but only those that show the same thing: a
//! neighbour's weight is the kernel's times
//!
//! - `exp(−|l_p − l_q| / (σ_l √Var(l_p) + ε))` for the luminance l, Var(l_p) the variance of
//!   pixel p's mean (from its samples, then filtered with the squared weights), so that
//!   differences larger than the noise — a reflected window frame, a shadow edge — stop the
//!   filter, and differences the noise explains do not (σ_l = 4, SVGF's value);
//! - `max(0, n_p · n_q)^σ_n` for the first-hit shading normals (σ_n = 128, SVGF);
//! - `exp(−|z_p − z_q| / (σ_z |∇z_p| |p − q| + ε_z))` for the first-hit distances z, so that
//!   a plane seen at a grazing angle is one surface while an object in front of another is not;
//! - `exp(−|a_p − a_q|₁ / σ_a)` for the first-hit directional albedo a (σ_a = 0.1), so that two
//!   materials side by side stay apart.
//!
//! The features (normal, distance, albedo) are the mean of four camera rays per pixel on a
//! 2 × 2 grid, so that a pixel on an edge carries the mixture it shows; they depend only on
//! the scene, not on the seed, and are computed with the image. The filter is deterministic and
//! runs over rows in parallel with the same result for any number of threads.
//!
//! What it costs: a filtered picture is biased (detail finer than the noise at the given number
//! of samples is smoothed); `docs/render.md` gives the measured error against converged
//! references. The raw estimate stays available (`denoise = false`, the default).

use crate::error::{RenderError, Result};
use crate::image::Image;
use crate::mesoscale::shading_frame;
use crate::path::{Strategy, sample_brdf};
use crate::scene::{PrimKind, Scene};
use glam::{DVec2, DVec3};
use gonio_io::Cancel;
use rayon::prelude::*;

/// The first-hit features of every pixel that steer the filter.
#[derive(Debug, Clone)]
pub struct Features {
    /// Mean shading normal (world space, toward the camera; zero where the camera sees no
    /// surface). Shorter than 1 on edges between surfaces.
    pub normal: Vec<[f32; 3]>,
    /// Mean distance from the camera to the first hit (0 where nothing is hit).
    pub depth: Vec<f32>,
    /// Mean directional albedo of the first hit's material toward the camera, per channel (1
    /// on lights and the background).
    pub albedo: Vec<[f32; 3]>,
}

/// Camera rays per pixel for the features, on a 2 × 2 grid.
const FEATURE_RAYS: [(f64, f64); 4] = [(0.25, 0.25), (0.75, 0.25), (0.25, 0.75), (0.75, 0.75)];

/// BRDF samples per feature ray for the albedo, on a 4 × 4 grid of (u₁, u₂).
const ALBEDO_SAMPLES: usize = 4;

impl Features {
    /// The features of every pixel of `scene`'s camera.
    pub fn of(scene: &Scene) -> Features {
        Features::of_until(scene, &Cancel::default()).expect("never cancelled")
    }

    /// [`Features::of`], stopping with [`RenderError::Cancelled`] when `cancel` is raised
    /// (each row of pixels looks at it first).
    pub fn of_until(scene: &Scene, cancel: &Cancel) -> Result<Features> {
        let (w, h) = (scene.camera.width, scene.camera.height);
        let rows: Vec<Vec<PixelFeatures>> = (0..h)
            .into_par_iter()
            .map(|y| {
                if cancel.is_cancelled() {
                    return Vec::new();
                }
                (0..w).map(|x| pixel_features(scene, x, y)).collect()
            })
            .collect();
        if cancel.is_cancelled() {
            return Err(RenderError::Cancelled);
        }
        let mut f = Features {
            normal: Vec::with_capacity(w * h),
            depth: Vec::with_capacity(w * h),
            albedo: Vec::with_capacity(w * h),
        };
        for (n, z, a) in rows.into_iter().flatten() {
            f.normal.push(n);
            f.depth.push(z);
            f.albedo.push(a);
        }
        Ok(f)
    }
}

/// One pixel's mean normal, distance and albedo.
type PixelFeatures = ([f32; 3], f32, [f32; 3]);

/// The mean features of pixel (`x`, `y`).
fn pixel_features(scene: &Scene, x: usize, y: usize) -> PixelFeatures {
    let (mut n, mut z, mut a) = (DVec3::ZERO, 0.0, DVec3::ZERO);
    for (dx, dy) in FEATURE_RAYS {
        let ray = scene.camera.ray(DVec2::new(x as f64 + dx, y as f64 + dy));
        let Some(hit) = scene.accel.intersect(&ray, 0.0, f64::INFINITY) else {
            a += DVec3::ONE;
            continue;
        };
        z += hit.t;
        let PrimKind::Surface(m) = scene.prims[hit.prim] else {
            a += DVec3::ONE;
            continue;
        };
        let (_, frame) = shading_frame(scene, &scene.materials[m], &hit, ray.dir);
        n += frame.n;
        let wo = frame.to_local(-ray.dir);
        if wo.z <= 0.0 {
            continue;
        }
        // The directional albedo toward the camera by stratified importance samples.
        let brdf = scene.materials[m].brdf.as_ref();
        let mut sum = DVec3::ZERO;
        for i in 0..ALBEDO_SAMPLES * ALBEDO_SAMPLES {
            let u = DVec2::new(
                ((i % ALBEDO_SAMPLES) as f64 + 0.5) / ALBEDO_SAMPLES as f64,
                ((i / ALBEDO_SAMPLES) as f64 + 0.5) / ALBEDO_SAMPLES as f64,
            );
            if let Some(s) = sample_brdf(brdf, wo, u, Strategy::IMPORTANCE)
                && s.pdf > 0.0
                && s.wi.z > 0.0
            {
                sum += s.f * (s.wi.z / s.pdf);
            }
        }
        let mirror = DVec3::splat(scene.materials[m].mirror(wo.z));
        a += (sum / (ALBEDO_SAMPLES * ALBEDO_SAMPLES) as f64 + mirror)
            .clamp(DVec3::ZERO, DVec3::splat(4.0));
    }
    let k = FEATURE_RAYS.len() as f64;
    (
        (n / k).as_vec3().to_array(),
        (z / k) as f32,
        (a / k).as_vec3().to_array(),
    )
}

/// σ_l: how many standard deviations of a pixel's noise a luminance difference may span and
/// still be averaged (SVGF, Schied et al. 2017, §4.4).
const SIGMA_LUMINANCE: f32 = 4.0;
/// σ_n: the exponent of the normals' cosine (SVGF).
const SIGMA_NORMAL: i32 = 128;
/// σ_z: how many times the distance the local gradient predicts two pixels may differ by.
const SIGMA_DEPTH: f32 = 1.0;
/// σ_a: the albedo difference (sum over channels) at which a neighbour's weight falls by e.
const SIGMA_ALBEDO: f32 = 0.1;
/// Passes of the filter (holes of 1, 2, 4, 8, 16 pixels).
const PASSES: u32 = 5;
/// The B3-spline kernel (Dammertz et al. 2010).
const KERNEL: [f32; 5] = [1.0 / 16.0, 1.0 / 4.0, 3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0];

/// Luminance of linear sRGB in single precision, as the filter works.
fn luminance(c: [f32; 3]) -> f32 {
    crate::light::luminance(c) as f32
}

/// The denoised picture of `image`, whose pixel means have the luminance variances `variance`
/// (same size), steered by the first-hit `features` of the same camera.
pub fn denoise(image: &Image, variance: &[f32], features: &Features) -> Image {
    let (w, h) = (image.width, image.height);
    let gradient = depth_gradient(&features.depth, w, h);
    let unit: Vec<Option<[f32; 3]>> = features
        .normal
        .iter()
        .map(|n| {
            let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            (len > 1e-3).then(|| n.map(|c| c / len))
        })
        .collect();
    let mut colour = image.pixels.clone();
    let mut var = variance.to_vec();
    for pass in 0..PASSES {
        let step = 1isize << pass;
        let var_blur = blur3(&var, w, h);
        let rows: Vec<Vec<([f32; 3], f32)>> = (0..h)
            .into_par_iter()
            .map(|y| {
                (0..w)
                    .map(|x| {
                        let p = y * w + x;
                        let lp = luminance(colour[p]);
                        let sigma_l = SIGMA_LUMINANCE * var_blur[p].max(0.0).sqrt()
                            + 1e-6 * lp.abs().max(1e-6);
                        let (zp, gp) = (features.depth[p], gradient[p]);
                        let ap = features.albedo[p];
                        let mut sum_w = 0.0f32;
                        let mut sum_c = [0.0f32; 3];
                        let mut sum_v = 0.0f32;
                        for (j, kj) in KERNEL.iter().enumerate() {
                            let qy = y as isize + (j as isize - 2) * step;
                            if qy < 0 || qy >= h as isize {
                                continue;
                            }
                            for (i, ki) in KERNEL.iter().enumerate() {
                                let qx = x as isize + (i as isize - 2) * step;
                                if qx < 0 || qx >= w as isize {
                                    continue;
                                }
                                let q = qy as usize * w + qx as usize;
                                let weight = if q == p {
                                    kj * ki
                                } else {
                                    let dist = step as f32
                                        * (((i as f32 - 2.0).powi(2) + (j as f32 - 2.0).powi(2))
                                            .sqrt());
                                    let wl = (-(luminance(colour[q]) - lp).abs() / sigma_l).exp();
                                    let wn = match (unit[p], unit[q]) {
                                        (Some(a), Some(b)) => {
                                            (a[0] * b[0] + a[1] * b[1] + a[2] * b[2])
                                                .max(0.0)
                                                .powi(SIGMA_NORMAL)
                                        }
                                        (None, None) => 1.0,
                                        _ => 0.0,
                                    };
                                    let wz = (-(features.depth[q] - zp).abs()
                                        / (SIGMA_DEPTH * gp * dist + 1e-3 * zp.max(1e-6)))
                                    .exp();
                                    let aq = features.albedo[q];
                                    let da = (aq[0] - ap[0]).abs()
                                        + (aq[1] - ap[1]).abs()
                                        + (aq[2] - ap[2]).abs();
                                    let wa = (-da / SIGMA_ALBEDO).exp();
                                    kj * ki * wl * wn * wz * wa
                                };
                                for (s, c) in sum_c.iter_mut().zip(colour[q]) {
                                    *s += weight * c;
                                }
                                sum_w += weight;
                                sum_v += weight * weight * var[q];
                            }
                        }
                        // The pixel itself always has a positive weight.
                        (sum_c.map(|s| s / sum_w), sum_v / (sum_w * sum_w))
                    })
                    .collect()
            })
            .collect();
        for (p, (c, v)) in rows.into_iter().flatten().enumerate() {
            colour[p] = c;
            var[p] = v;
        }
    }
    Image {
        width: w,
        height: h,
        pixels: colour,
    }
}

/// The magnitude of the screen-space gradient of the distances `depth` (per pixel), by central
/// differences (one-sided at the border and next to pixels where nothing is hit).
fn depth_gradient(depth: &[f32], w: usize, h: usize) -> Vec<f32> {
    let at = |x: isize, y: isize| -> Option<f32> {
        (x >= 0 && y >= 0 && (x as usize) < w && (y as usize) < h)
            .then(|| depth[y as usize * w + x as usize])
            .filter(|&z| z > 0.0)
    };
    let derivative = |minus: Option<f32>, here: f32, plus: Option<f32>| match (minus, plus) {
        (Some(a), Some(b)) => 0.5 * (b - a),
        (Some(a), None) => here - a,
        (None, Some(b)) => b - here,
        (None, None) => 0.0,
    };
    (0..h * w)
        .map(|p| {
            let (x, y) = ((p % w) as isize, (p / w) as isize);
            let z = depth[p];
            let gx = derivative(at(x - 1, y), z, at(x + 1, y));
            let gy = derivative(at(x, y - 1), z, at(x, y + 1));
            (gx * gx + gy * gy).sqrt()
        })
        .collect()
}

/// `values` blurred by a 3 × 3 Gaussian (1 2 1 / 2 4 2 / 1 2 1, renormalised at the border).
fn blur3(values: &[f32], w: usize, h: usize) -> Vec<f32> {
    const K: [f32; 3] = [0.25, 0.5, 0.25];
    (0..h * w)
        .map(|p| {
            let (x, y) = (p % w, p / w);
            let (mut sum, mut norm) = (0.0, 0.0);
            for (j, kj) in K.iter().enumerate() {
                for (i, ki) in K.iter().enumerate() {
                    let (qx, qy) = ((x + i).wrapping_sub(1), (y + j).wrapping_sub(1));
                    if qx < w && qy < h {
                        sum += kj * ki * values[qy * w + qx];
                        norm += kj * ki;
                    }
                }
            }
            sum / norm
        })
        .collect()
}
