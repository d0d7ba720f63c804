//! The texture camera ([`gonio_render::texture`]) and its readings
//! ([`gonio_render::texture_metrics`]): the metrics on images made by hand, and the camera on
//! coatings whose flakes differ in one property at a time.

use gonio_coating::description::parse;
use gonio_coating::system::{Coating, default_bands};
use gonio_render::texture::{TextureCamera, TextureReading, measure};
use gonio_render::texture_metrics::{graininess, sparkle};

/// Two spots on a flat field of 1 (20 × 20 pixels of 10 µm): their count, area, peak contrast
/// and grade, by hand; a diagonal neighbour joins a spot (8-connected); the surround is the
/// mean outside them, found though they raise the field's mean by a third.
#[test]
fn spots_are_counted_and_measured() {
    let w = 20;
    let mut y = vec![1.0; 400];
    for k in [21, 22, 41, 42] {
        y[k] = 21.0; // contrast 20
    }
    y[63] = 16.0; // diagonal to 42: the same spot, contrast 15
    y[277] = 41.0; // contrast 40, alone
    let s = sparkle(&y, w, 0.01, 0.0);
    assert_eq!(s.surround, 1.0);
    assert_eq!(s.spots, 2);
    assert!((s.density_per_mm2 - 2.0 / 0.04).abs() < 1e-9);
    assert!((s.area_percent - 100.0 * 6.0 / 400.0).abs() < 1e-12);
    assert!((s.intensity - 30.0).abs() < 1e-12);
    assert!((s.grade - 100.0 * (4.0 * 20.0 + 15.0 + 40.0) / 400.0).abs() < 1e-9);
    // Below the contrast: nothing.
    let flat: Vec<f64> = (0..400).map(|k| 1.0 + 3.0 * (k % 3) as f64).collect();
    assert_eq!(sparkle(&flat, w, 0.01, 0.0).spots, 0);
}

/// The noise is taken out: a pattern of coefficient of variation 20% seen through
/// independent noise of 30% reads 20% within the sampling error of 40 000 pixels.
#[test]
fn graininess_removes_the_pictures_noise() {
    use rand::{RngExt, SeedableRng};
    let mut rng = rand_pcg::Pcg64::seed_from_u64(3);
    let n = 40_000;
    let pattern: Vec<f64> = (0..n).map(|k| if k % 2 == 0 { 0.8 } else { 1.2 }).collect();
    let noisy = |rng: &mut rand_pcg::Pcg64| -> Vec<f64> {
        pattern
            .iter()
            .map(|p| p + 0.3 * (rng.random::<f64>() - 0.5) * 12f64.sqrt())
            .collect()
    };
    let (a, b) = (noisy(&mut rng), noisy(&mut rng));
    let g = graininess(&a, &b);
    assert!((g - 20.0).abs() < 0.5, "{g}");
    assert!(graininess(&pattern, &pattern) - 20.0 < 1e-9);
}

/// A silver metallic (aluminium, coverage 0.5, over a grey base, smooth top) with flakes
/// `diameter_um` across and `tilt_deg` rms, or none.
fn silver(flakes: Option<(f64, f64)>) -> Coating {
    let flakes = flakes.map_or(String::new(), |(d, tilt)| {
        format!(
            "[flakes]\nkind = \"aluminium\"\ncoverage = 0.5\ntilt_deg = {tilt}\ndiameter_um = {d}\n"
        )
    });
    parse(
        &format!(
            "[coat]\nindex = 1.5\nthickness_um = 30\n{flakes}[base]\nkind = \"diffuse\"\nreflectance = 0.25\n"
        ),
        &default_bands(),
    )
    .unwrap()
}

/// A 4 mm field at 20 µm per pixel (200 × 200), 8 samples per pixel.
fn camera() -> TextureCamera {
    TextureCamera {
        field_mm: 4.0,
        pixel_um: 20.0,
        spp: 8,
        ..TextureCamera::default()
    }
}

fn read(coating: &Coating) -> TextureReading {
    measure(coating, "test", &camera(), &|_, _| {}).unwrap()
}

/// The texture camera on coatings that differ in one property at a time.
mod slow {
    use super::*;

    /// Without flakes nothing sparkles and the diffuse picture is flat: the readings are the
    /// pictures' noise, taken out (graininess under 1%).
    #[test]
    fn no_flakes_no_sparkle() {
        let r = read(&silver(None));
        for s in &r.sparkle {
            assert_eq!(s.sparkle.spots, 0, "lamp at {}°", s.angle_deg);
            assert_eq!(s.sparkle.grade, 0.0);
        }
        assert!(r.graininess < 1.0, "{}", r.graininess);
    }

    /// At constant coverage, larger flakes are fewer and brighter: below the pixel's size a
    /// flake's mirror image fills a share (d/p)² of it, so the spots' contrast (sparkle
    /// intensity) grows with the diameter, and the diffuse picture's pattern of flakes and
    /// gaps is averaged less within a pixel (graininess grows). At 8, 16 and 32 µm.
    #[test]
    fn intensity_and_graininess_grow_with_flake_size() {
        let readings: Vec<TextureReading> = [8.0, 16.0, 32.0]
            .iter()
            .map(|&d| read(&silver(Some((d, 12.0)))))
            .collect();
        let intensity: Vec<f64> = readings
            .iter()
            .map(|r| r.sparkle[0].sparkle.intensity)
            .collect();
        let grain: Vec<f64> = readings.iter().map(|r| r.graininess).collect();
        assert!(
            intensity[0] < intensity[1] && intensity[1] < intensity[2],
            "{intensity:?}"
        );
        assert!(grain[0] < grain[1] && grain[1] < grain[2], "{grain:?}");
    }

    /// Under the lamp at 15° (the camera along the normal), the flakes that catch it are
    /// tilted about 5°: a wider spread of tilts puts fewer there (the Beckmann density near the
    /// normal falls as 1/tan²σ), so fewer spots and less sparkle at 6°, 12° and 24°.
    #[test]
    fn sparkle_falls_with_tilt_spread() {
        let readings: Vec<TextureReading> = [6.0, 12.0, 24.0]
            .iter()
            .map(|&t| read(&silver(Some((20.0, t)))))
            .collect();
        let spots: Vec<usize> = readings
            .iter()
            .map(|r| r.sparkle[0].sparkle.spots)
            .collect();
        let grade: Vec<f64> = readings
            .iter()
            .map(|r| r.sparkle[0].sparkle.grade)
            .collect();
        assert!(spots[0] > spots[1] && spots[1] > spots[2], "{spots:?}");
        assert!(grade[0] > grade[1] && grade[1] > grade[2], "{grade:?}");
    }

    /// The readings do not depend on the number of threads.
    #[test]
    fn readings_do_not_depend_on_threads() {
        let coating = silver(Some((20.0, 12.0)));
        let run = |threads| {
            let camera = TextureCamera {
                threads: Some(threads),
                field_mm: 2.0,
                ..camera()
            };
            measure(&coating, "test", &camera, &|_, _| {}).unwrap()
        };
        let (a, b) = (run(1), run(3));
        for (x, y) in a.sparkle.iter().zip(&b.sparkle) {
            assert_eq!(x.sparkle, y.sparkle);
        }
        assert_eq!(a.graininess, b.graininess);
    }
}
