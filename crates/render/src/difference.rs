//! The colour difference between two renders of a scene, as a person sees it: CIEDE2000 per
//! pixel of the displayed pictures, its spread over the image, and a heat map.
//!
//! The colour compared is the colour shown: each linear sRGB pixel times the scene's exposure,
//! through its tone curve (what `gonio render -o x.png` writes, before 8-bit rounding), taken as
//! display-referred linear sRGB, turned into XYZ (IEC 61966-2-1) and CIELAB relative to the
//! display white (D65).

use crate::image::{Display, Image, ToneCurve};
use gonio_color::srgb::srgb_white;
use gonio_color::{Lab, LinearSrgb, ciede2000};

/// CIELAB of every pixel as displayed.
pub fn displayed_lab(img: &Image, display: Display) -> Vec<Lab> {
    let scale = display.exposure.exp2();
    let white = srgb_white();
    img.pixels
        .iter()
        .map(|p| {
            let [r, g, b] = p.map(|c| display.tone.apply(f64::from(c) * scale));
            LinearSrgb { r, g, b }.to_xyz().to_lab(white)
        })
        .collect()
}

/// CIEDE2000 between the displayed colours of `a` and `b`, pixel by pixel (the images have the
/// same size; a difference in size is a caller's error and yields the common prefix).
pub fn delta_e00(a: &Image, b: &Image, display: Display) -> Vec<f64> {
    displayed_lab(a, display)
        .iter()
        .zip(&displayed_lab(b, display))
        .map(|(x, y)| ciede2000(*x, *y))
        .collect()
}

/// Two renders of a scene compared when each was rendered twice, with seeds `a` and `b`, and
/// the same seed traces the same paths in both (as the colour modes do): the difference
/// `d = second − first` of one seed holds the systematic difference plus the second render's
/// own extra noise only.
pub struct SeededComparison {
    /// The mean of the two first renders.
    pub first: Image,
    /// The mean of the two second renders.
    pub second: Image,
    /// CIEDE2000 between the displayed `first` and `second`, per pixel.
    pub delta_e00: Vec<f64>,
    /// CIEDE2000 between `first` and `first + (d_a − d_b)/2`: exactly the same noise as
    /// `delta_e00` and no systematic part. Where `delta_e00` exceeds it, the renders differ
    /// beyond noise.
    pub noise_reference: Vec<f64>,
}

impl SeededComparison {
    /// Compare `[first_a, first_b]` with `[second_a, second_b]` (all the same size).
    pub fn new(first: [&Image; 2], second: [&Image; 2], display: Display) -> SeededComparison {
        let combine = |value: &dyn Fn(f32, f32, f32, f32) -> f32| {
            let mut img = Image::new(first[0].width, first[0].height);
            for (k, p) in img.pixels.iter_mut().enumerate() {
                *p = std::array::from_fn(|c| {
                    value(
                        first[0].pixels[k][c],
                        first[1].pixels[k][c],
                        second[0].pixels[k][c],
                        second[1].pixels[k][c],
                    )
                });
            }
            img
        };
        let mean_first = combine(&|fa, fb, _, _| 0.5 * (fa + fb));
        let mean_second = combine(&|_, _, sa, sb| 0.5 * (sa + sb));
        let reference = combine(&|fa, fb, sa, sb| 0.5 * (fa + fb) + 0.5 * ((sa - fa) - (sb - fb)));
        SeededComparison {
            delta_e00: delta_e00(&mean_first, &mean_second, display),
            noise_reference: delta_e00(&mean_first, &reference, display),
            first: mean_first,
            second: mean_second,
        }
    }
}

/// The relative RMSE of `image` against `reference` (same size): `sqrt(mean((I − R)²)) /
/// mean(R)` over every pixel and channel of the linear images, the measure of
/// `crates/render/benches/versus_mitsuba.py`. Against a reference rendered with k times the
/// samples, the reference's own noise adds `1/√k` of the image's noise in quadrature.
pub fn relative_rmse(image: &Image, reference: &Image) -> f64 {
    let (mut sq, mut sum) = (0.0, 0.0);
    for (a, b) in image.pixels.iter().zip(&reference.pixels) {
        for (x, y) in a.iter().zip(b) {
            sq += f64::from(x - y).powi(2);
            sum += f64::from(*y);
        }
    }
    let n = 3.0 * reference.pixels.len().max(1) as f64;
    (sq / n).sqrt() / (sum / n)
}

/// Median, 95th percentile and maximum of a set of colour differences.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Spread {
    /// The median.
    pub median: f64,
    /// The 95th percentile (nearest rank).
    pub p95: f64,
    /// The largest value.
    pub max: f64,
}

impl Spread {
    /// The spread of `values` (`None` when empty).
    pub fn of(values: &[f64]) -> Option<Spread> {
        let mut v = values.to_vec();
        v.sort_by(f64::total_cmp);
        let last = v.len().checked_sub(1)?;
        let q = |p: f64| v[((p * last as f64).round() as usize).min(last)];
        Some(Spread {
            median: q(0.5),
            p95: q(0.95),
            max: v[last],
        })
    }
}

/// A grey heat map of colour differences: ΔE00 0 black, `full_scale` or more white. Write it
/// with [`linear_display`].
pub fn heat_map(delta_e: &[f64], width: usize, height: usize, full_scale: f64) -> Image {
    let mut img = Image::new(width, height);
    for (p, d) in img.pixels.iter_mut().zip(delta_e) {
        *p = [(d / full_scale).clamp(0.0, 1.0) as f32; 3];
    }
    img
}

/// The display that writes pixel values as they are (no exposure, clamped).
pub fn linear_display() -> Display {
    Display {
        exposure: 0.0,
        tone: ToneCurve::Clamp,
    }
}
