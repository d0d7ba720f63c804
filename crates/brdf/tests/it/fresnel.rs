//! Fresnel reflectance against check values, normal incidence and Brewster's angle; the complex
//! index reduces to the real one.

use gonio_brdf::fresnel::*;
use num_complex::Complex64;

fn cos_deg(d: f64) -> f64 {
    d.to_radians().cos()
}

/// Check values at the gloss geometries (20, 60, 85°) for the n = 1.567 black-glass gloss
/// standard and an n = 1.55 coating, from the formulas of the module comment to 5 digits.
#[test]
fn dielectric_check_values() {
    for (n, deg, r) in [
        (1.567, 20.0, 0.04908),
        (1.567, 60.0, 0.10006),
        (1.567, 85.0, 0.61915),
        (1.55, 20.0, 0.04681),
        (1.55, 60.0, 0.09734),
        (1.55, 85.0, 0.61773),
    ] {
        let got = dielectric(cos_deg(deg), n);
        assert!((got - r).abs() < 5e-6, "n={n} {deg}°: {got} vs {r}");
    }
}

/// Normal incidence: ((n-1)/(n+1))², and for a metal ((n-1)² + κ²)/((n+1)² + κ²).
#[test]
fn normal_incidence() {
    let n = 1.5;
    assert!((dielectric(1.0, n) - 0.04).abs() < 1e-12);
    let m = Complex64::new(0.27, 2.78); // gold-like at 600 nm
    let expect = ((m.re - 1.0).powi(2) + m.im * m.im) / ((m.re + 1.0).powi(2) + m.im * m.im);
    assert!((Ior::Conductor(m).reflectance(1.0) - expect).abs() < 1e-12);
}

/// The complex formula reduces to the real one, Rp vanishes at Brewster's angle, and grazing
/// incidence reflects everything.
#[test]
fn complex_matches_real_and_brewster() {
    let n = 1.55;
    for deg in [0.0, 10.0, 45.0, 70.0, 89.0] {
        let c = cos_deg(deg);
        let p = polarised(c, Complex64::new(n, 0.0));
        assert!((p.unpolarised() - dielectric(c, n)).abs() < 1e-12);
        assert!(p.s >= p.p);
    }
    let brewster = n.atan();
    assert!(Ior::Dielectric(n).polarised(brewster.cos()).p < 1e-20);
    assert!((dielectric(0.0, n) - 1.0).abs() < 1e-12);
    assert_eq!(dielectric(0.1, 0.6), 1.0);
}
