//! The flakes' glint in the texture camera's pictures ([`crate::texture`]), each pixel's value
//! the exact mean over its footprint: what a camera's pixel, which integrates its area,
//! records, and the same for any number of samples per pixel.
//!
//! Why not the path tracer's samples: a flake about a pixel's size or smaller is found by the
//! share of a pixel's samples that land on it (and the path follows its mirror on half of
//! them), so the pixel's glint fluctuates with the samples, and whether it passes a spot's
//! threshold too: at 16 samples per pixel a flake that covers a share f of a pixel is missed
//! with probability `(1 − f/2)^16` (12% for a quarter), a sliver of a flake much more often,
//! so the sparkle readings depended on the samples (issue 43: 523 spots at 16 samples, 648 at 64, field 12 mm at
//! 30 µm). Here the picture is rendered with the flakes' glint left out
//! ([`crate::flakes::FlakeField::without_glint`]: the rest of the coating, whose noise is a
//! small share of the surround's level, far under a spot's threshold) and the glint added
//! exactly: for each pixel, the pieces of every flake in its footprint
//! ([`crate::flakes::FlakeField::sections`], clipped exactly), each mirroring the light it
//! sees along its one mirror direction ([`gonio_coating::glint::Glint::flake`]), weighted by
//! its area over the pixel's. This is the expectation of the path tracer's glint over the
//! pixel's samples (its delta lobe followed with probability `p` and weighted by `1/p`): the
//! same light, without the noise.
//!
//! Approximations, both far below a pixel's change: the viewing direction and the
//! refraction's parallax are taken at the pixel's centre (across a pixel of 30 µm seen from
//! 1 m the direction turns by 3·10⁻⁵ rad, against the lamp's radius of 0.035 rad; the parallax
//! under 40 µm of coat moves by 10⁻⁹ m), and a flake mirrors what it sees directly (the
//! specimen is a plane under the lights: nothing else sends light back to it).

use crate::error::{RenderError, Result};
use crate::flakes::{Flake, MAX_BANDS};
use crate::geometry::Ray;
use crate::image::Image;
use crate::integrator::on_threads;
use crate::mesoscale::shading_frame;
use crate::path::offset;
use crate::scene::{PrimKind, Scene};
use glam::{DVec2, DVec3};
use gonio_brdf::Rgb;
use rayon::prelude::*;

/// The glint of the discrete flakes that `scene`'s camera sees, each pixel's value the mean
/// over its footprint (linear sRGB), on `threads` threads (`None`: all); the pixels where the
/// camera sees no discrete flakes are 0. The surface with flakes must be a plane facing the
/// camera, its normal along z and the pixels' footprints along x and y (the texture
/// camera's), so that a footprint is a rectangle of the flakes' plane.
pub fn glint_picture(scene: &Scene, threads: Option<usize>) -> Result<Image> {
    let (w, h) = (scene.camera.width, scene.camera.height);
    let rows = on_threads(threads, || {
        (0..h)
            .into_par_iter()
            .map(|y| {
                (0..w)
                    .map(|x| pixel(scene, x, y))
                    .collect::<Result<Vec<_>>>()
            })
            .collect::<Result<Vec<_>>>()
    })??;
    let mut image = Image::new(w, h);
    for (out, value) in image.pixels.iter_mut().zip(rows.into_iter().flatten()) {
        *out = value.as_vec3().to_array();
    }
    Ok(image)
}

/// Pixel (`x`, `y`)'s glint.
fn pixel(scene: &Scene, x: usize, y: usize) -> Result<Rgb> {
    let camera = &scene.camera;
    let (fx, fy) = (x as f64, y as f64);
    let centre = camera.ray(DVec2::new(fx + 0.5, fy + 0.5));
    let Some(hit) = scene.accel.intersect(&centre, 0.0, f64::INFINITY) else {
        return Ok(Rgb::ZERO);
    };
    let PrimKind::Surface(m) = scene.prims[hit.prim] else {
        return Ok(Rgb::ZERO);
    };
    let material = &scene.materials[m];
    let Some(flakes) = &material.flakes else {
        return Ok(Rgb::ZERO);
    };
    let (ng, frame) = shading_frame(scene, material, &hit, centre.dir);
    let wo = frame.to_local(-centre.dir);
    if wo.z <= 0.0 {
        return Ok(Rgb::ZERO);
    }
    // The footprint: where the rays through the pixel's corners meet the surface's plane.
    let corner = |u: f64, v: f64| {
        let ray = camera.ray(DVec2::new(u, v));
        ray.origin + ray.dir * ((hit.p - ray.origin).dot(ng) / ray.dir.dot(ng))
    };
    let (a, b, c) = (
        corner(fx, fy),
        corner(fx + 1.0, fy + 1.0),
        corner(fx + 1.0, fy),
    );
    let size = (a - b).abs().max_element();
    let aligned = |d: DVec3| d.x.abs().min(d.y.abs()) <= 1e-9 * size;
    if ng.z.abs() < 1.0 - 1e-12 || !aligned(c - a) || !aligned(c - b) {
        return Err(RenderError::Invalid(
            "texture camera: the flakes' plane must face the camera along z with the pixels \
             along x and y"
                .into(),
        ));
    }
    // On the flakes' plane, the footprint moves by the refraction's parallax.
    let shift = flakes.under(hit.p, &frame, wo) - hit.p;
    let (lo, hi) = (a.min(b) + shift, a.max(b) + shift);
    let area = (hi.x - lo.x) * (hi.y - lo.y);
    let origin = offset(hit.p, ng);
    let glint = flakes.glint();
    let mut bands = [0.0; MAX_BANDS];
    let bands = &mut bands[..glint.wavelengths_nm().len()];
    let mut sum = Rgb::ZERO;
    let corners = (DVec2::new(lo.x, lo.y), DVec2::new(hi.x, hi.y));
    // The light a flake of normal `h` mirrors, its weight per band into `out`.
    let mirrored = |h: DVec3, out: &mut [f64]| {
        glint.flake(wo, h, out).map_or(Rgb::ZERO, |wi| {
            let dir = frame.to_world(wi).normalize();
            arriving(scene, &Ray { origin, dir })
        })
    };
    let nb = bands.len();
    // Only the flakes that mirror some light are clipped.
    let lit = |f: Option<&Flake>| {
        f.is_some_and(|f| mirrored(f.normal, &mut [0.0; MAX_BANDS][..nb]) != Rgb::ZERO)
    };
    flakes.sections(lo.z, corners.0, corners.1, lit, |flake, piece| {
        if let Some(f) = flake {
            let light = mirrored(f.normal, bands);
            sum += flakes.to_rgb(bands) * light * piece;
        }
    });
    Ok(sum / area)
}

/// The lights' radiance arriving along `ray`: an area light it meets first, else the lights
/// at infinity where it leaves the scene (0 when a surface is in the way).
fn arriving(scene: &Scene, ray: &Ray) -> Rgb {
    match scene.accel.intersect(ray, 0.0, f64::INFINITY) {
        None => scene
            .lights
            .iter()
            .filter(|l| l.is_infinite())
            .map(|l| l.le(ray.dir))
            .sum(),
        Some(hit) => match scene.prims[hit.prim] {
            PrimKind::Emitter(k) => scene.lights[k].emitted(hit.ng, ray.dir),
            PrimKind::Surface(_) => Rgb::ZERO,
        },
    }
}
