//! The analytic models (Beckmann-Spizzichino series, the geometric-optics facet model) against
//! their limits and laws: a Lambertian cone by quadrature, the geometric and smooth limits of the
//! series, energy conservation, masking, the coherent term, reciprocity.

use glam::DVec3;
use gonio_brdf::Ior;
use gonio_scatter::analytic::*;
use gonio_scatter::geometry::cone_solid_angle;
use gonio_scatter::geometry::{
    Detector, incidence_direction, inplane_direction, spherical_direction,
};
use std::f64::consts::PI;

const N: f64 = 1.55;

fn model(sigma: f64, t: f64) -> GaussianModel {
    GaussianModel::new(sigma, t, Ior::Dielectric(N)).unwrap()
}

/// Albedo `∫ f cos to dω` over the hemisphere by the midpoint rule on a (θ, φ) grid fine enough
/// for the lobes tested (0.3° × 0.6°).
fn albedo(m: &GaussianModel, model_kind: AnalyticModel, wavelength: f64, ti: f64) -> f64 {
    let (nt, np) = (300, 600);
    let (dt, dp) = (PI / 2.0 / nt as f64, 2.0 * PI / np as f64);
    let wi = incidence_direction(ti);
    let mut sum = 0.0;
    for i in 0..nt {
        let t = (i as f64 + 0.5) * dt;
        for j in 0..np {
            let wo = spherical_direction(t, (j as f64 + 0.5) * dp);
            sum += m.brdf_dirs(model_kind, wavelength, wi, wo) * t.cos() * t.sin() * dt * dp;
        }
    }
    sum
}

/// A Lambertian BRDF `1/π` seen by a cone about the normal: `rho = sin² alpha`; and by a tilted
/// cone: `(1/π) Omega cos t` up to the curvature of cos over the cone, `O(alpha²)`.
#[test]
fn cone_quadrature_of_lambertian() {
    let alpha = 5f64.to_radians();
    let normal = Detector {
        direction: DVec3::Z,
        half_angle: alpha,
    };
    let rho = cone_reflectance(&normal, |_| 1.0 / PI);
    assert!((rho - alpha.sin().powi(2)).abs() < 1e-14, "{rho}");
    let tilted = Detector {
        direction: inplane_direction(0.7),
        half_angle: alpha,
    };
    let rho = cone_reflectance(&tilted, |_| 1.0 / PI);
    let expect = cone_solid_angle(alpha) * 0.7f64.cos() * (1.0 + alpha.cos()) / 2.0 / PI;
    assert!((rho / expect - 1.0).abs() < 1e-12, "{rho} vs {expect}");
}

/// For g ≫ 1 the series tends to the geometric limit with relative corrections O(1/g): at
/// g ≈ 2500 (sigma = 2.1 µm, λ = 500 nm) they are below 1% wherever the lobe exceeds 1% of its
/// peak, and they shrink as g grows (g ≈ 400 is worse).
#[test]
fn series_tends_to_geometric_limit() {
    let wavelength = 500e-9;
    let ti = 20f64.to_radians();
    let worst = |sigma: f64| {
        let m = model(sigma, 2.0 * sigma / 0.3);
        let f = |kind, ts: f64| m.brdf(kind, wavelength, ti, ts, 0.0);
        let peak = f(AnalyticModel::Geometric, ti);
        (-75..=75)
            .map(|d| f64::from(d).to_radians())
            .filter(|&ts| f(AnalyticModel::Geometric, ts) > 0.01 * peak)
            .map(|ts| {
                (f(AnalyticModel::Beckmann, ts) / f(AnalyticModel::Geometric, ts) - 1.0).abs()
            })
            .fold(0.0, f64::max)
    };
    let big = worst(2.1e-6);
    let medium = worst(0.84e-6);
    assert!(big < 0.01, "g ≈ 2500: worst relative difference {big}");
    assert!(big < medium, "{big} should be below {medium}");
}

/// For g ≪ 1 the series is its first term: with sigma = 1 nm (g ≤ 6.3e-4) and T = 0.2 µm the
/// next term is below (g/4) e^(a/2) ≤ 4e-3 of the first (a = vxy² T²/4 ≤ k² T² = 6.3), so the
/// two agree within 1% at every angle, out of plane too.
#[test]
fn series_tends_to_smooth_limit() {
    let wavelength = 500e-9;
    let m = model(1e-9, 0.2e-6);
    for ti_deg in [0.0f64, 20.0, 60.0] {
        for ts_deg in (-80..=80).step_by(5) {
            for ps in [0.0, 1.0, 2.5] {
                let (ti, ts) = (ti_deg.to_radians(), f64::from(ts_deg).to_radians());
                let full = m.brdf(AnalyticModel::Beckmann, wavelength, ti, ts, ps);
                let first = m.brdf(AnalyticModel::Smooth, wavelength, ti, ts, ps);
                assert!(
                    (full / first - 1.0).abs() < 0.01,
                    "{ti_deg} {ts_deg} {ps}: {full} {first}"
                );
            }
        }
    }
}

/// Energy: the geometric limit at small slopes (m = 0.05) reflects R(ti) up to O(m²); the
/// Beckmann series with its coherent part never exceeds 1 and, for a moderately rough surface
/// (g ≈ 10, m = 0.1, T ≈ 5 λ), stays within 1% of R as Kirchhoff theory without
/// shadowing should (its error is O(m²) and O((λ/T)²)).
#[test]
fn energy_conservation() {
    let wavelength = 550e-9;
    let ti = 20f64.to_radians();
    let r = Ior::Dielectric(N).reflectance(ti.cos());
    let geo = model(0.1e-6, 4e-6);
    let a = albedo(&geo, AnalyticModel::Geometric, wavelength, ti);
    assert!(
        (a / r - 1.0).abs() < 0.01,
        "geometric albedo {a} vs R = {r}"
    );

    let rough = model(147e-9, 2.94e-6);
    let g = rough.g(wavelength, incidence_direction(ti), inplane_direction(ti));
    assert!((9.0..11.0).contains(&g), "g = {g}");
    let total = albedo(&rough, AnalyticModel::Beckmann, wavelength, ti)
        + rough.coherent_reflectance(wavelength, ti);
    assert!(total <= 1.0);
    assert!(
        (total / r - 1.0).abs() < 0.03,
        "Beckmann albedo {total} vs R = {r}"
    );
}

/// Masking only removes light: the microfacet model is below the geometric one everywhere and
/// equal to it at normal incidence and exitance to first order.
#[test]
fn masking_removes_light() {
    let m = model(0.3e-6, 2e-6);
    for ts_deg in (-85..=85).step_by(5) {
        let ts = f64::from(ts_deg).to_radians();
        let ti = 40f64.to_radians();
        let geo = m.brdf(AnalyticModel::Geometric, 0.0, ti, ts, 0.0);
        let mf = m.brdf(AnalyticModel::Microfacet, 0.0, ti, ts, 0.0);
        assert!(mf <= geo && mf > 0.0, "{ts_deg}: {mf} vs {geo}");
    }
}

/// The coherent spike goes into the detector that sees the mirror direction only, and the curve
/// reports `rho / (Omega cos ts)`.
#[test]
fn coherent_term_in_specular_detector() {
    let wavelength = 550e-9;
    let m = model(3e-9, 5e-6);
    let ti = 20f64.to_radians();
    let alpha = 1.4f64.to_radians();
    let curve = m.inplane(
        AnalyticModel::Beckmann,
        wavelength,
        ti,
        &[18f64.to_radians(), ti, 22f64.to_radians()],
        alpha,
    );
    let coherent = m.coherent_reflectance(wavelength, ti);
    let g = (4.0 * PI * 3e-9 * ti.cos() / wavelength).powi(2);
    let r = Ior::Dielectric(N).reflectance(ti.cos());
    assert!((coherent - r * (-g).exp()).abs() < 1e-15);
    let [off_low, spec, off_high] = curve.points[..] else {
        panic!("three points expected")
    };
    assert!(off_low.reflectance < 1e-3 * coherent);
    assert!(off_high.reflectance < 1e-3 * coherent);
    assert!(spec.reflectance > coherent && spec.reflectance < 1.01 * coherent);
    let omega = cone_solid_angle(alpha);
    assert!((spec.brdf_per_sr - spec.reflectance / (omega * ti.cos())).abs() < 1e-9);
    assert_eq!(curve.method, "beckmann");
    assert_eq!(curve.wavelength_nm, Some(550.0));
}

/// Reciprocity `f(wi, wo) = f(wo, wi)` for every model, out of plane too.
#[test]
fn reciprocity() {
    let m = model(0.2e-6, 3e-6);
    let a = spherical_direction(0.3, 2.0);
    let b = spherical_direction(1.1, -0.4);
    for kind in [
        AnalyticModel::Beckmann,
        AnalyticModel::Geometric,
        AnalyticModel::Microfacet,
        AnalyticModel::Smooth,
    ] {
        let ab = m.brdf_dirs(kind, 600e-9, a, b);
        let ba = m.brdf_dirs(kind, 600e-9, b, a);
        assert!((ab / ba - 1.0).abs() < 1e-12, "{kind:?}: {ab} vs {ba}");
        assert_eq!(AnalyticModel::from_name(kind.name()), Some(kind));
    }
}
