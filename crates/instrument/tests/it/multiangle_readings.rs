//! Multi-angle readings (ASTM E2194, E2539): geometry names and directions, a Lambertian sample
//! reads its reflectance, the aperture average, the flop index, colour differences.

use glam::DVec3;
use gonio_brdf::bxdf::SpectralBrdf;
use gonio_color::{Colorimetry, Illuminant, Observer, Spectrum};
use gonio_instrument::multiangle::*;
use std::f64::consts::PI;

/// A BRDF `(ρ(λ) + k (wo · x̂)) / π`: Lambertian with a term linear in the detector's
/// direction, for the aperture check.
struct Linear {
    rho: Spectrum,
    k: f64,
}

impl SpectralBrdf for Linear {
    fn eval_at(&self, wo: DVec3, wi: DVec3, wavelengths_nm: &[f64], out: &mut [f64]) {
        for (o, &w) in out.iter_mut().zip(wavelengths_nm) {
            *o = if wo.z > 0.0 && wi.z > 0.0 {
                (self.rho.value_at(w) + self.k * wo.x) / PI
            } else {
                0.0
            };
        }
    }
    fn sample_direction(&self, _: DVec3, _: glam::DVec2, _: f64) -> Option<(DVec3, f64)> {
        None
    }
}

fn bands() -> Vec<f64> {
    (0..31).map(|i| 400.0 + 10.0 * i as f64).collect()
}

/// A red-ish reflectance spectrum.
fn red() -> Spectrum {
    let wl = bands();
    let values = wl
        .iter()
        .map(|w| 0.05 + 0.6 / (1.0 + (-(w - 600.0) / 15.0).exp()))
        .collect();
    Spectrum::new(wl, values).unwrap()
}

#[test]
fn names_and_directions() {
    for (name, view) in [
        ("45as15", -30.0),
        ("45as-15", -60.0),
        ("45as45", 0.0),
        ("45as110", 65.0),
        ("15as80", 65.0),
    ] {
        let g = Geometry::parse(name).unwrap();
        assert_eq!(g.to_string(), name);
        assert_eq!(g.viewing_deg(), view);
        let (wi, wo) = g.directions();
        // The aspecular angle is the angle between the detector and the mirror direction.
        let mirror = DVec3::new(-wi.x, 0.0, wi.z);
        let angle = wo.dot(mirror).clamp(-1.0, 1.0).acos().to_degrees();
        assert!((angle - g.aspecular_deg.abs()).abs() < 1e-9, "{name}");
        // Towards the illuminator for a positive aspecular angle.
        assert_eq!(wo.x > mirror.x, g.aspecular_deg > 0.0, "{name}");
    }
    for bad in ["45", "45as", "x as 15", "45as140", "45as-50", "95as15"] {
        let e = Geometry::parse(bad).unwrap_err().to_string();
        assert!(e.contains(bad.trim()) || e.contains("below"), "{bad}: {e}");
    }
}

/// A Lambertian sample reads its own reflectance at every geometry; its CIELAB equals the
/// colorimetry of the reflectance spectrum computed independently (the 1 nm weighting of
/// `Colorimetry::of_reflectance`, interpolating the same samples linearly: equal to rounding),
/// and its flop index is 0 (L* the same at 15° and 110°).
#[test]
fn lambertian_sample_reads_its_reflectance() {
    let rho = red();
    let sample = Linear {
        rho: rho.clone(),
        k: 0.0,
    };
    let settings = Settings::default();
    let r = read_spectral(&sample, &bands(), &E2539, &settings).unwrap();
    let want = Colorimetry::of_reflectance(&rho, Illuminant::D65, Observer::Cie1964TenDegree);
    for g in &r.geometries {
        for (got, want) in g.reflectance_factor.iter().zip(rho.values()) {
            assert!((got - want).abs() < 1e-12, "{}", g.geometry);
        }
        let d = [
            g.lab.l - want.lab.l,
            g.lab.a - want.lab.a,
            g.lab.b - want.lab.b,
        ];
        assert!(d.iter().all(|d| d.abs() < 1e-9), "{}: {d:?}", g.geometry);
    }
    assert!(r.flop_index().unwrap().abs() < 1e-9);
}

/// Over a circular cone of half-angle a about the unit vector c, the mean of the direction
/// is c (1 + cos a)/2 (the mean of cos ψ over the cap, uniform in solid angle), so a BRDF
/// linear in wo averages to its value at `(1 + cos a)/2 · c`. With a = 5° the factor is
/// 0.99810; the quadrature must reproduce it to rounding.
#[test]
fn aperture_average_of_a_linear_brdf() {
    let rho = Spectrum::constant(bands(), 0.3).unwrap();
    let k = 0.2;
    let sample = Linear { rho, k };
    let a = 5.0;
    let settings = Settings {
        aperture_deg: a,
        ..Settings::default()
    };
    let g = Geometry::new(45.0, 110.0);
    let r = read_spectral(&sample, &bands(), &[g], &settings).unwrap();
    let (_, wo) = g.directions();
    let mean_x = wo.x * (1.0 + a.to_radians().cos()) / 2.0;
    let want = 0.3 + k * mean_x;
    for v in &r.geometries[0].reflectance_factor {
        assert!((v - want).abs() < 1e-12, "{v} vs {want}");
    }
}

/// Alman's formula at a hand-computed point: L*15 = 110, L*45 = 40, L*110 = 20 gives
/// 2.69 · 90^1.11 / 40^0.86 = 2.69 · 147.64 / 23.865 = 16.64.
#[test]
fn flop_index_of_a_silver_metallic() {
    let fi = flop_index(110.0, 40.0, 20.0);
    assert!((fi - 16.64).abs() < 0.01, "{fi}");
    assert!(flop_index(50.0, 50.0, 60.0) < 0.0);
}

/// Differences: a sample against itself is zero everywhere; a pure lightness change shows
/// in ΔL* only, and ΔE*ab² = ΔL*² + ΔC*² + ΔH*² for a general change.
#[test]
fn differences_decompose() {
    let settings = Settings::default();
    let a = read_spectral(&Linear { rho: red(), k: 0.0 }, &bands(), &E2194, &settings).unwrap();
    let zero = differences(&a, &a).unwrap();
    assert!(zero.iter().all(|d| d.de_ab == 0.0 && d.de00 == 0.0));
    let grey = Spectrum::constant(bands(), 0.4).unwrap();
    let b = read_spectral(&Linear { rho: grey, k: 0.0 }, &bands(), &E2194, &settings).unwrap();
    for d in differences(&a, &b).unwrap() {
        let sum = d.dl * d.dl + d.dc * d.dc + d.dh * d.dh;
        assert!((sum - d.de_ab * d.de_ab).abs() < 1e-9 * sum, "{d:?}");
    }
    let other = read_spectral(&Linear { rho: red(), k: 0.0 }, &bands(), &E2539, &settings).unwrap();
    assert!(differences(&a, &other).is_err());
}
