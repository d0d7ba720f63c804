//! A renderer's picture against a scene's analytic reference: each region's mean against the
//! reference's with its standard error, CIEDE2000 per region, FLIP over the picture, and the
//! difference images.
//!
//! - Values are the luminance `Y = 0.2126 R + 0.7152 G + 0.0722 B` of linear sRGB (IEC
//!   61966-2-1).
//! - The standard error of a region's mean is `σ/√n` over its n pixels, σ² the variance of
//!   one pixel's `Y − Y_ref` estimated from the differences between horizontal neighbours (see
//!   [`regions`]): the pixels' Monte Carlo noise is independent from pixel to pixel (each
//!   renderer's samples are drawn per pixel); the reference's own variation across the region is
//!   taken out by the difference, and a smooth systematic departure by the neighbours'.
//! - CIELAB's white (for ΔE00) is the scene's white radiance (`Scene::white`) times the sRGB
//!   white (D65); in the metameric scenes each picture's own white patch is its white, so that
//!   the observer is adapted to the scene's illuminant as the reference assumes.
//! - FLIP (Andersson, Nilsson, Akenine-Möller, Oskarsson, Åström, Fairchild, "FLIP: a
//!   difference evaluator for alternating images", HPG 2020), LDR, through the `nv-flip`
//!   bindings of NVIDIA's implementation, at its default 67 pixels per degree, on both pictures
//!   divided by the scene's white, clamped to [0, 1] and sRGB-encoded.

use crate::scene::{Reference, SIZE, Scene};
use gonio_color::{Lab, LinearSrgb, Xyz, ciede2000, srgb};
use serde::Serialize;

/// Linear sRGB luminance.
pub fn luminance(c: [f64; 3]) -> f64 {
    0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]
}

/// One region's comparison.
#[derive(Debug, Clone, Serialize)]
pub struct RegionStats {
    pub name: String,
    pub pixels: usize,
    /// Mean linear sRGB of the picture and of the reference over the region.
    pub rgb: [f64; 3],
    pub reference_rgb: [f64; 3],
    /// Mean luminance of each, and the standard error of the picture's.
    pub value: f64,
    pub reference: f64,
    pub standard_error: f64,
    /// The standard error of each channel's mean.
    pub rgb_standard_error: [f64; 3],
    /// CIELAB of each mean, and their CIEDE2000.
    pub lab: [f64; 3],
    pub reference_lab: [f64; 3],
    pub delta_e00: f64,
}

fn xyz(c: [f64; 3]) -> Xyz {
    LinearSrgb {
        r: c[0],
        g: c[1],
        b: c[2],
    }
    .to_xyz()
}

fn lab(c: [f64; 3], white: [f64; 3]) -> Lab {
    xyz(c).to_lab(xyz(white))
}

/// The regions' statistics of `picture` against `reference`. In a spectral scene the white is
/// the region named "white" of each picture.
pub fn regions(scene: &Scene, reference: &Reference, picture: &[[f64; 3]]) -> Vec<RegionStats> {
    let mut out = vec![];
    let mut sums = vec![];
    for k in 0..scene.regions.len() {
        let idx: Vec<usize> = (0..SIZE * SIZE)
            .filter(|&p| reference.region[p] == Some(k))
            .collect();
        let n = idx.len().max(1) as f64;
        let mean = |img: &dyn Fn(usize) -> [f64; 3]| {
            let mut m = [0.0; 3];
            for &p in &idx {
                let v = img(p);
                for c in 0..3 {
                    m[c] += v[c] / n;
                }
            }
            m
        };
        let rgb = mean(&|p| picture[p]);
        let reference_rgb = mean(&|p| reference.rgb[p]);
        // The noise of each pixel from the differences between horizontal neighbours in the
        // region (Rice 1944's estimator, var = mean((d_p − d_q)²)/2): the picture's departure
        // from the reference, d, may vary smoothly across the region (an export's systematic
        // loss), which a plain variance of d would count as noise; the neighbours' difference
        // leaves it out to first order.
        let d = |p: usize| [0, 1, 2].map(|c| picture[p][c] - reference.rgb[p][c]);
        let (mut var, mut var_y, mut m) = ([0.0; 3], 0.0, 0.0_f64);
        for &p in &idx {
            if p % SIZE + 1 < SIZE && reference.region[p + 1] == Some(k) {
                let (a, b) = (d(p), d(p + 1));
                for c in 0..3 {
                    var[c] += 0.5 * (a[c] - b[c]).powi(2);
                }
                var_y += 0.5 * (luminance(a) - luminance(b)).powi(2);
                m += 1.0;
            }
        }
        let m = m.max(1.0);
        let (var, var_y) = (var.map(|v| v / m), var_y / m);
        sums.push((rgb, reference_rgb));
        out.push(RegionStats {
            name: scene.regions[k].name.clone(),
            pixels: idx.len(),
            rgb,
            reference_rgb,
            value: luminance(rgb),
            reference: luminance(reference_rgb),
            standard_error: (var_y / n).sqrt(),
            rgb_standard_error: var.map(|v| (v / n).sqrt()),
            lab: [0.0; 3],
            reference_lab: [0.0; 3],
            delta_e00: 0.0,
        });
    }
    let white_index = scene.regions.iter().position(|r| r.name == "white");
    let (white, white_ref) = match white_index {
        Some(w) if scene.is_spectral() => sums[w],
        _ => ([scene.white; 3], [scene.white; 3]),
    };
    for r in &mut out {
        let a = lab(r.rgb, white);
        let b = lab(r.reference_rgb, white_ref);
        r.lab = [a.l, a.a, a.b];
        r.reference_lab = [b.l, b.a, b.b];
        r.delta_e00 = ciede2000(a, b);
    }
    out
}

/// CIEDE2000 between two CIELAB triples.
pub fn delta_e(a: [f64; 3], b: [f64; 3]) -> f64 {
    let lab = |v: [f64; 3]| Lab {
        l: v[0],
        a: v[1],
        b: v[2],
    };
    ciede2000(lab(a), lab(b))
}

/// The ΔE00 that 4 standard errors of a region's mean make: each channel's standard error
/// turned into a ΔE00 by moving the mean by it, the three (independent) combined in
/// quadrature, times 4 (linear propagation of the noise; 4 σ as for the luminances).
pub fn delta_e_noise(r: &RegionStats, white: [f64; 3]) -> f64 {
    let base = lab(r.rgb, white);
    let sum: f64 = (0..3)
        .map(|c| {
            let mut moved = r.rgb;
            moved[c] += r.rgb_standard_error[c];
            ciede2000(base, lab(moved, white)).powi(2)
        })
        .sum();
    4.0 * sum.sqrt()
}

/// The 8-bit sRGB of `picture` divided by `white`, clamped.
pub fn srgb8(picture: &[[f64; 3]], white: f64) -> Vec<u8> {
    picture
        .iter()
        .flat_map(|c| c.map(|v| (srgb::encode((v / white).clamp(0.0, 1.0)) * 255.0).round() as u8))
        .collect()
}

/// Pixels of a strip's gap between two pictures.
const STRIP_GAP: usize = 4;

/// Several pictures ([`SIZE`]² 8-bit RGB each) side by side, each enlarged `scale` times with
/// square pixels and separated by white gaps, as one 8-bit RGB image of `(width, height)`: a
/// run's reference, picture, difference and FLIP map seen together in the report.
pub fn strip(pictures: &[&[u8]], scale: usize) -> (Vec<u8>, usize, usize) {
    let side = SIZE * scale;
    let n = pictures.len();
    let width = n * side + n.saturating_sub(1) * STRIP_GAP;
    let mut out = vec![255u8; width * side * 3];
    for (k, p) in pictures.iter().enumerate() {
        let x0 = k * (side + STRIP_GAP);
        for y in 0..side {
            for x in 0..side {
                let s = ((y / scale) * SIZE + x / scale) * 3;
                let d = (y * width + x0 + x) * 3;
                out[d..d + 3].copy_from_slice(&p[s..s + 3]);
            }
        }
    }
    (out, width, side)
}

/// FLIP's error map of `picture` against `reference` (both linear, divided by `white`) and its
/// mean.
pub fn flip(reference: &[[f64; 3]], picture: &[[f64; 3]], white: f64) -> (Vec<u8>, f64) {
    let n = SIZE as u32;
    let r = nv_flip::FlipImageRgb8::with_data(n, n, &srgb8(reference, white));
    let t = nv_flip::FlipImageRgb8::with_data(n, n, &srgb8(picture, white));
    let map = nv_flip::flip(r, t, nv_flip::DEFAULT_PIXELS_PER_DEGREE);
    let mean = nv_flip::FlipPool::from_image(&map).mean();
    let coloured = map.apply_color_lut(&nv_flip::magma_lut()).to_vec();
    (coloured, f64::from(mean))
}

/// The signed difference `picture − reference` as an 8-bit picture: red where the picture is
/// brighter, blue where darker, full at `full` (radiance units) of luminance.
pub fn difference(reference: &[[f64; 3]], picture: &[[f64; 3]], full: f64) -> Vec<u8> {
    picture
        .iter()
        .zip(reference)
        .flat_map(|(p, r)| {
            let d = ((luminance(*p) - luminance(*r)) / full).clamp(-1.0, 1.0);
            let v = (d.abs() * 255.0).round() as u8;
            if d >= 0.0 { [v, 0, 0] } else { [0, 0, v] }
        })
        .collect()
}

/// Encode an 8-bit RGB picture of [`SIZE`]² pixels as PNG.
pub fn png(rgb: Vec<u8>) -> crate::Result<Vec<u8>> {
    png_sized(rgb, SIZE, SIZE)
}

/// The PNG of an 8-bit RGB image of `width` × `height` pixels.
pub fn png_sized(rgb: Vec<u8>, width: usize, height: usize) -> crate::Result<Vec<u8>> {
    let image = image::RgbImage::from_raw(width as u32, height as u32, rgb)
        .ok_or_else(|| crate::Error::Invalid("picture of the wrong size".into()))?;
    let mut bytes = std::io::Cursor::new(Vec::new());
    image
        .write_to(&mut bytes, image::ImageFormat::Png)
        .map_err(|e| crate::Error::Invalid(format!("cannot encode the PNG: {e}")))?;
    Ok(bytes.into_inner())
}
