//! Differences between two pictures (`gonio render --compare`): CIEDE2000 per pixel, its spread,
//! and a seeded comparison that separates a systematic difference from the noise.

use gonio_render::difference::*;
use gonio_render::image::Image;

#[test]
fn identical_images_differ_by_zero_and_spread_is_by_rank() {
    let mut img = Image::new(3, 2);
    for (k, p) in img.pixels.iter_mut().enumerate() {
        *p = [0.1 * k as f32, 0.2, 0.05 * k as f32];
    }
    let display = linear_display();
    assert!(delta_e00(&img, &img, display).iter().all(|d| *d == 0.0));
    let s = Spread::of(&[3.0, 1.0, 2.0, 5.0, 4.0]).unwrap();
    assert_eq!((s.median, s.p95, s.max), (3.0, 5.0, 5.0));
    assert!(Spread::of(&[]).is_none());
}

#[test]
fn a_seeded_comparison_separates_the_systematic_part_from_the_noise() {
    // The second render is the first scaled by 1.1 (a systematic difference) with its own
    // noise +e for seed a and -e for seed b: the means differ only by the scaling, and the
    // noise reference is the mean first render plus e (less the scaling's share of the
    // first render's own noise, 0.1 (fa - fb) / 2).
    let grey = |v: f32| {
        let mut img = Image::new(1, 1);
        img.pixels[0] = [v; 3];
        img
    };
    let (fa, fb) = (grey(0.20), grey(0.22));
    let (sa, sb) = (grey(0.20 * 1.1 + 0.01), grey(0.22 * 1.1 - 0.01));
    let d = linear_display();
    let c = SeededComparison::new([&fa, &fb], [&sa, &sb], d);
    let scaled = delta_e00(&grey(0.21), &grey(0.21 * 1.1), d)[0];
    let noise = delta_e00(&grey(0.21), &grey(0.21 + 0.01 - 0.001), d)[0];
    assert!(
        (c.delta_e00[0] - scaled).abs() < 1e-4,
        "{} {scaled}",
        c.delta_e00[0]
    );
    assert!(
        (c.noise_reference[0] - noise).abs() < 1e-4,
        "{} {noise}",
        c.noise_reference[0]
    );
}

#[test]
fn a_white_and_a_black_pixel_differ_by_100() {
    // CIEDE2000 between L* = 100 and L* = 0 with a* = b* = 0 is the lightness difference
    // itself, 100: the weight S_L is 1 at the mean lightness 50 (Sharma et al. 2005, eq. 8).
    let (mut white, mut black) = (Image::new(1, 1), Image::new(1, 1));
    white.pixels[0] = [1.0; 3];
    black.pixels[0] = [0.0; 3];
    let d = delta_e00(&white, &black, linear_display())[0];
    assert!((d - 100.0).abs() < 1e-6, "{d}");
    let map = heat_map(&[0.0, 1.0, 4.0], 3, 1, 2.0);
    assert_eq!(map.pixels[1], [0.5; 3]);
    assert_eq!(map.pixels[2], [1.0; 3]);
}
