//! The film image: binning, the display transform (exposure, tone curves, sRGB) and the EXR, HDR
//! and PNG files it writes and reads.

use gonio_render::image::*;

#[test]
fn binning_averages_blocks_and_drops_the_ragged_edge() {
    let mut img = Image::new(5, 3);
    for (i, p) in img.pixels.iter_mut().enumerate() {
        *p = [i as f32, 1.0, 0.0];
    }
    let b = img.binned(2);
    assert_eq!((b.width, b.height), (2, 1));
    // Block (0, 0): pixels 0, 1, 5, 6; block (1, 0): 2, 3, 7, 8.
    assert_eq!(b.pixels, vec![[3.0, 1.0, 0.0], [5.0, 1.0, 0.0]]);
}

#[test]
fn exr_and_hdr_round_trip_linear_values() {
    let dir = tempfile::tempdir().unwrap();
    let mut img = Image::new(3, 2);
    img.pixels[1] = [0.25, 2.0, 100.0];
    img.pixels[5] = [1e-3, 0.5, 7.0];
    let exr = dir.path().join("a.exr");
    img.write(&exr, Display::default()).unwrap();
    assert_eq!(Image::read(&exr).unwrap(), img);
    let hdr = dir.path().join("a.hdr");
    img.write(&hdr, Display::default()).unwrap();
    let back = Image::read(&hdr).unwrap();
    // RGBE keeps 8 mantissa bits per channel relative to the largest: 1% of the maximum.
    for (a, b) in back.pixels.iter().zip(&img.pixels) {
        let m = b.iter().fold(0.0f32, |m, &v| m.max(v));
        for k in 0..3 {
            assert!((a[k] - b[k]).abs() <= 0.01 * m + 1e-6, "{a:?} {b:?}");
        }
    }
}

#[test]
fn png_applies_exposure_and_tone_and_bad_extension_is_refused() {
    let mut img = Image::new(2, 1);
    img.pixels[0] = [0.5, 0.5, 0.5];
    img.pixels[1] = [8.0, 8.0, 8.0];
    let d = Display {
        exposure: 1.0,
        tone: ToneCurve::Clamp,
    };
    let bytes = img.to_srgb8(d);
    assert_eq!(&bytes, &[255, 255, 255, 255, 255, 255]);
    let d = Display {
        exposure: -1.0,
        tone: ToneCurve::Clamp,
    };
    // 0.25 encodes to 0.5371 in sRGB.
    assert_eq!(img.to_srgb8(d)[0], 137);
    assert!((ToneCurve::Filmic.apply(1e6) - 1.0).abs() < 0.04);
    assert!((ToneCurve::Reinhard.apply(1.0) - 0.5).abs() < 1e-12);
    let dir = tempfile::tempdir().unwrap();
    let err = img.write(&dir.path().join("a.jpg"), d).unwrap_err();
    assert!(err.to_string().contains("a.jpg"), "{err}");
    assert!(std::fs::read_dir(dir.path()).unwrap().next().is_none());
}
