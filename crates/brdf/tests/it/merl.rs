//! The MERL binary format: an exact round trip on its grid, out-of-gamut colours kept in
//! luminance and hue, truncated and foreign files refused.

use glam::DVec3;
use gonio_brdf::formats::merl::*;
use gonio_brdf::table::{Channels, Resolution, TableBuilder};

/// A reciprocal, colourful, glossy test BRDF.
fn glossy(wi: DVec3, wo: DVec3) -> [f64; 3] {
    let h = (wi + wo).normalize();
    let spec = 0.5 * (-(1.0 - h.z * h.z) / (h.z * h.z) / 0.01).exp() / (wi.z * wo.z).sqrt();
    [0.1 + spec, 0.2 + 0.8 * spec, 0.05 + 1.2 * spec]
}

#[test]
fn round_trip_on_the_merl_grid_is_exact_to_f32() {
    let res = Resolution::isotropic(90, 90, 360);
    let mut b = TableBuilder::new(res, Channels::Rgb).unwrap();
    b.fill(|c, out| out.copy_from_slice(&glossy(c.wi, c.wo)));
    let t = b.build().unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("g.binary");
    write(&t, &path).unwrap();
    assert_eq!(
        std::fs::metadata(&path).unwrap().len(),
        12 + 24 * 90 * 90 * 180
    );
    let back = read(&path).unwrap();
    assert_eq!(back.resolution(), res);
    let mut worst = 0.0f64;
    for (a, b) in t.values().iter().zip(back.values()) {
        assert_eq!(a.is_nan(), b.is_nan());
        if !a.is_nan() {
            worst = worst.max(((a - b) / a).abs() as f64);
        }
    }
    // The only loss is f32 → f64 → f32 through the scale factors.
    assert!(worst < 1e-6, "worst relative difference {worst}");
}

/// The mapping keeps the luminance and the hue direction, lands on the gamut's boundary
/// (smallest component 0) and leaves in-gamut colours alone.
#[test]
fn out_of_gamut_colours_keep_luminance_and_hue() {
    let lum = |c: DVec3| c.dot(DVec3::new(0.2126, 0.7152, 0.0722));
    for rgb in [
        DVec3::new(-0.02, 0.05, 0.3),
        DVec3::new(0.4, -0.1, 0.05),
        DVec3::new(0.01, 0.2, -0.03),
    ] {
        let m = into_gamut(rgb);
        assert!((lum(m) - lum(rgb)).abs() < 1e-15, "{rgb} -> {m}");
        assert!(m.min_element().abs() < 1e-15, "{m}");
        let (d0, d1) = (rgb - lum(rgb), m - lum(m));
        assert!(d0.cross(d1).length() < 1e-12 * d0.length(), "{d0} vs {d1}");
        assert!(d1.length() < d0.length());
    }
    assert_eq!(
        into_gamut(DVec3::new(0.1, 0.2, 0.3)),
        DVec3::new(0.1, 0.2, 0.3)
    );
    assert_eq!(into_gamut(DVec3::new(-0.5, 0.01, 0.0)), DVec3::ZERO);
}

#[test]
fn truncated_and_foreign_files_are_rejected() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("x.binary");
    std::fs::write(&path, [90u8, 0, 0, 0, 90, 0, 0, 0, 180, 0, 0, 0, 1, 2, 3]).unwrap();
    let msg = read(&path).unwrap_err().to_string();
    assert!(msg.contains("x.binary") && msg.contains("bytes"), "{msg}");
    std::fs::write(&path, b"GBRDF\0\r\n and more").unwrap();
    assert!(read(&path).unwrap_err().to_string().contains("dimensions"));
}
