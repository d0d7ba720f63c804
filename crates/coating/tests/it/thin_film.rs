//! Thin films: a bare interface is Fresnel's, quarter- and half-wave films, total internal
//! reflection, rutile's index at the sodium line, impossible media refused.

use gonio_coating::thin_film::*;
use num_complex::Complex64;

fn real(n: f64) -> Complex64 {
    Complex64::new(n, 0.0)
}

/// Without films the stack is one interface: Fresnel's equations (written here with the
/// angles, Born & Wolf §1.5.2: `rs = −sin(θ0−θ1)/sin(θ0+θ1)`, `rp = tan(θ0−θ1)/tan(θ0+θ1)`).
#[test]
fn bare_interface_is_fresnel() {
    let (n0, n1) = (1.0, 1.5);
    let stack = Stack::new(n0, vec![], real(n1)).unwrap();
    for deg in [5.0f64, 30.0, 56.0, 80.0] {
        let t0 = deg.to_radians();
        let t1 = (n0 * t0.sin() / n1).asin();
        let rs = (t0 - t1).sin() / (t0 + t1).sin();
        let rp = (t0 - t1).tan() / (t0 + t1).tan();
        let got_s = stack.reflectance(Polarisation::S, t0, 550.0);
        let got_p = stack.reflectance(Polarisation::P, t0, 550.0);
        assert!(
            (got_s - rs * rs).abs() < 1e-14,
            "{deg}: {got_s} vs {}",
            rs * rs
        );
        assert!(
            (got_p - rp * rp).abs() < 1e-14,
            "{deg}: {got_p} vs {}",
            rp * rp
        );
    }
}

/// A quarter-wave film (n1 d = λ/4) at normal incidence reflects
/// `((n0 ns − n1²)/(n0 ns + n1²))²` (Born & Wolf §1.6.4, eq. 61); a half-wave film is absent.
#[test]
fn quarter_and_half_wave_films() {
    let (n0, n1, ns, lambda) = (1.0, 2.3, 1.52, 600.0);
    let quarter = Stack::new(
        n0,
        vec![Film {
            index: real(n1),
            thickness_nm: lambda / (4.0 * n1),
        }],
        real(ns),
    )
    .unwrap();
    let want = ((n0 * ns - n1 * n1) / (n0 * ns + n1 * n1)).powi(2);
    for pol in [Polarisation::S, Polarisation::P] {
        let got = quarter.reflectance(pol, 0.0, lambda);
        assert!((got - want).abs() < 1e-14, "{got} vs {want}");
    }
    let half = Stack::new(
        n0,
        vec![Film {
            index: real(n1),
            thickness_nm: lambda / (2.0 * n1),
        }],
        real(ns),
    )
    .unwrap();
    let bare = ((n0 - ns) / (n0 + ns)).powi(2);
    assert!((half.reflectance(Polarisation::S, 0.0, lambda) - bare).abs() < 1e-14);
}

/// Beyond the critical angle of a dense ambient over a rarer substrate the reflection is
/// total whatever the (lossless) films between.
#[test]
fn total_internal_reflection() {
    let stack = Stack::new(
        1.5,
        vec![Film {
            index: real(1.38),
            thickness_nm: 100.0,
        }],
        real(1.0),
    )
    .unwrap();
    for pol in [Polarisation::S, Polarisation::P] {
        let r = stack.reflectance(pol, 60f64.to_radians(), 550.0);
        assert!((r - 1.0).abs() < 1e-12, "{r}");
    }
}

/// The handbooks' ordinary index of rutile at the sodium D line (589.3 nm) is 2.613; the
/// fit's residual there is a few units in the fourth decimal.
#[test]
fn rutile_index_at_the_sodium_line() {
    let n = rutile_ordinary(589.3);
    assert!((n - 2.613).abs() < 0.002, "{n}");
}

#[test]
fn impossible_media_are_refused() {
    assert!(Stack::new(0.0, vec![], real(1.5)).is_err());
    assert!(Stack::new(1.0, vec![], Complex64::new(1.5, -0.1)).is_err());
    let e = Stack::new(
        1.0,
        vec![Film {
            index: real(2.0),
            thickness_nm: -5.0,
        }],
        real(1.5),
    )
    .unwrap_err();
    assert!(e.to_string().contains("film 1"), "{e}");
}
