//! The denoiser (`gonio render --denoise`): a constant picture stays constant, noise falls, edges
//! far above the noise stay.

use gonio_render::denoise::*;
use gonio_render::image::Image;
use rand::{RngExt, SeedableRng};

fn flat(w: usize, h: usize, f: impl Fn(usize, usize) -> [f32; 3]) -> Image {
    Image {
        width: w,
        height: h,
        pixels: (0..w * h).map(|p| f(p % w, p / w)).collect(),
    }
}

fn plane_features(w: usize, h: usize) -> Features {
    Features {
        normal: vec![[0.0, 0.0, 1.0]; w * h],
        depth: vec![2.0; w * h],
        albedo: vec![[0.5; 3]; w * h],
    }
}

/// A constant picture stays constant (the weights are normalised).
#[test]
fn a_constant_picture_is_unchanged() {
    let img = flat(40, 30, |_, _| [0.3, 0.2, 0.1]);
    let out = denoise(&img, &vec![0.01; 40 * 30], &plane_features(40, 30));
    for p in &out.pixels {
        for (a, b) in p.iter().zip([0.3, 0.2, 0.1]) {
            assert!((a - b).abs() < 1e-6, "{p:?}");
        }
    }
}

/// White noise of known variance on a plane falls by the filter's footprint; an edge many
/// standard deviations high survives.
#[test]
fn noise_falls_and_an_edge_far_above_it_stays() {
    let (w, h) = (96, 64);
    let sd = 0.05f32;
    let truth = |x: usize| if x < w / 2 { 0.2f32 } else { 1.0 };
    // Irwin-Hall: the sum of 12 uniform numbers less 6 has mean 0 and variance 1.
    let mut rng = rand_pcg::Pcg64::seed_from_u64(1);
    let noise: Vec<f32> = (0..w * h)
        .map(|_| (0..12).map(|_| rng.random::<f32>()).sum::<f32>() - 6.0)
        .collect();
    let img = flat(w, h, |x, y| [truth(x) + sd * noise[y * w + x]; 3]);
    let out = denoise(&img, &vec![sd * sd; w * h], &plane_features(w, h));
    let rms = |im: &Image| {
        let s: f32 = im
            .pixels
            .iter()
            .enumerate()
            .map(|(p, c)| (c[0] - truth(p % w)).powi(2))
            .sum();
        (s / (w * h) as f32).sqrt()
    };
    let (before, after) = (rms(&img), rms(&out));
    // Before: the noise itself (sd). After: the averaging over tens of neighbours cuts it
    // by far more than 3; the edge (0.8 = 16 sd) keeps its pixels apart, so no blur adds
    // error there.
    assert!((before - sd).abs() < 0.1 * sd, "input rms {before}");
    assert!(after < before / 3.0, "rms {before} -> {after}");
    for y in 0..h {
        assert!(
            out.get(w / 2 - 1, y)[0] < 0.35,
            "dark side of the edge blurred"
        );
        assert!(
            out.get(w / 2, y)[0] > 0.85,
            "bright side of the edge blurred"
        );
    }
}
