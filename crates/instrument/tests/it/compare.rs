//! Comparing curves: a Gaussian peak's height and FWHM, a self-comparison is zero, a scaling shows.

use gonio_instrument::compare::*;
use gonio_scatter::{CurvePoint, InplaneCurve};

fn gaussian_curve(centre: f64, sigma: f64, height: f64) -> InplaneCurve {
    InplaneCurve {
        method: "test".into(),
        wavelength_nm: None,
        incidence_deg: centre,
        points: (-75..=75)
            .map(|d| {
                let x = d as f64;
                let r = height * (-(x - centre).powi(2) / (2.0 * sigma * sigma)).exp() + 1e-6;
                CurvePoint {
                    scatter_deg: x,
                    brdf_per_sr: r,
                    reflectance: r,
                    rel_uncertainty: None,
                }
            })
            .collect(),
    }
}

/// A Gaussian's FWHM is 2√(2 ln 2) σ; linear interpolation on a 1° grid of a σ = 5° peak is
/// accurate to well under 0.1°.
#[test]
fn gaussian_peak_and_fwhm() {
    let c = gaussian_curve(20.0, 5.0, 0.3);
    let p = peak(&c).unwrap();
    assert_eq!(p.position_deg, 20.0);
    let fwhm = 2.0 * (2.0 * 2f64.ln()).sqrt() * 5.0;
    assert!((p.fwhm_deg.unwrap() - fwhm).abs() < 0.1, "{:?}", p.fwhm_deg);
}

#[test]
fn self_comparison_is_zero_and_scaling_shows() {
    let a = gaussian_curve(45.0, 3.0, 0.5);
    let c = compare(&a, &a).unwrap();
    assert_eq!(c.rms_log10, 0.0);
    assert_eq!(c.common_points, 151);
    assert_eq!(c.peak_a, c.peak_b);
    let mut b = a.clone();
    b.points.iter_mut().for_each(|p| p.reflectance *= 10.0);
    assert!((compare(&a, &b).unwrap().rms_log10 - 1.0).abs() < 1e-12);
}
