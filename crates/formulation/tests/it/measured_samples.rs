//! The sample-by-sample comparison of a formulation with a measured BRDF
//! (`measured_samples::compare`), on samples written from the closed form of a smooth clear coat
//! over a grey base (`clear_coat::AtWavelength::brdf`, itself tested against its series): the
//! same BRDF compares at 0, and the BRDF scaled by k compares at the CIEDE2000 of two greys,
//! written out here from Sharma, Wu & Dalal (Col. Res. Appl. 30, 21, 2005): for an achromatic
//! pair a′ = b′ = 0, so ΔE00 = |ΔL*| / S_L with S_L = 1 + 0.015 (L̄ − 50)² / √(20 + (L̄ − 50)²).

use glam::DVec3;
use gonio_brdf::formats::scattered::Sample;
use gonio_coating::description;
use gonio_coating::system::default_bands;
use gonio_formulation::measured_samples::{PEAK_DEG, compare};

const GREY: &str = "[coat]\nindex = 1.5\nthickness_um = 40\nabsorption_per_um = 0\n\
                    [base]\nkind = \"diffuse\"\nreflectance = 0.4\n";

fn direction(theta_deg: f64, phi_deg: f64) -> DVec3 {
    let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
    DVec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
}

/// CIE 1976 lightness of a luminance factor `y` (0–100), written out (CIE 15:2018, eq. 8.1).
fn lightness(y: f64) -> f64 {
    let t = y / 100.0;
    if t > (6.0f64 / 29.0).powi(3) {
        116.0 * t.cbrt() - 16.0
    } else {
        116.0 * (t / (3.0 * (6.0f64 / 29.0).powi(2)) + 4.0 / 29.0) - 16.0
    }
}

#[test]
fn scaled_grey_compares_at_the_lightness_difference() {
    let bands = default_bands();
    let coating = description::parse(GREY, &bands).unwrap();
    let stack = coating.clear_coat().unwrap();
    let at = stack.at(550.0).unwrap();
    // Geometries out of plane and in plane, one of them at the mirror direction (half vector
    // on the normal: in the peak).
    let pairs = [
        (20.0, 0.0, 50.0, 180.0),
        (45.0, 0.0, 10.0, 90.0),
        (60.0, 30.0, 60.0, 210.0),
    ];
    for k in [1.0, 1.2] {
        let samples: Vec<Sample> = pairs
            .iter()
            .map(|&(ti, pi, to, po)| {
                let (wi, wo) = (direction(ti, pi), direction(to, po));
                // The base is grey and the coat's index constant: one value at every band.
                let f = k * at.brdf(wi.z, wo.z);
                Sample {
                    wi,
                    wo,
                    values: vec![f; bands.len()],
                }
            })
            .collect();
        let c = compare(&coating, &samples, &bands, 16, 0).unwrap();
        assert_eq!((c.all.count, c.peak.count, c.off_peak.count), (3, 1, 2));
        assert!(c.samples[2].theta_h_deg < PEAK_DEG);
        for (s, &(ti, _, to, _)) in c.samples.iter().zip(&pairs) {
            // Y of a flat reflectance factor R = π f is 100 R for any illuminant and observer.
            let f = at.brdf(ti.to_radians().cos(), to.to_radians().cos());
            let y = 100.0 * std::f64::consts::PI * f;
            assert!(
                (s.model_y - y).abs() < 1e-9 * y,
                "Y {} against {y}",
                s.model_y
            );
            let (l1, l2) = (lightness(k * y), lightness(y));
            let mean = 0.5 * (l1 + l2);
            let sl = 1.0 + 0.015 * (mean - 50.0).powi(2) / (20.0 + (mean - 50.0).powi(2)).sqrt();
            let expected = (l1 - l2).abs() / sl;
            assert!(
                (s.de00 - expected).abs() < 1e-6,
                "k {k}: ΔE00 {} against {expected}",
                s.de00
            );
            assert!((s.measured_y / s.model_y - k).abs() < 1e-9);
        }
        assert!((c.all.median_abs_log10_y - k.log10()).abs() < 1e-9);
        if k > 1.0 {
            assert!(c.all.mean_de00 > 1.0, "a 20% brighter grey differs visibly");
        }
    }
}

#[test]
fn mismatched_bands_are_refused() {
    let bands = default_bands();
    let coating = description::parse(GREY, &bands).unwrap();
    let s = Sample {
        wi: direction(30.0, 0.0),
        wo: direction(30.0, 180.0),
        values: vec![0.1; 3],
    };
    let e = compare(&coating, &[s], &bands, 16, 0)
        .unwrap_err()
        .to_string();
    assert!(e.contains("3 values for 31 wavelengths"), "{e}");
    assert!(compare(&coating, &[], &bands, 16, 0).is_err());
}
