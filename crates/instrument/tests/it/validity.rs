//! Where each scattering method holds: the Rayleigh parameter, indices refused or warned, the ray
//! method's warning on smooth maps, the Kirchhoff spot and speckle.

use gonio_instrument::validity::*;

/// g = (4π Sq cos θ / λ)²: for Sq = λ/(4π) at normal incidence g = 1 exactly.
#[test]
fn rayleigh_parameter() {
    let lambda = 550e-9;
    let sq = lambda / (4.0 * std::f64::consts::PI);
    assert!((rayleigh_g(sq, 0.0, lambda) - 1.0).abs() < 1e-12);
    let g60 = rayleigh_g(sq, 60f64.to_radians(), lambda);
    assert!((g60 - 0.25).abs() < 1e-12, "{g60}");
}

#[test]
fn index_refused_or_warned() {
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let e = check_index(bad).unwrap_err().to_string();
        assert!(e.contains("positive"), "{e}");
    }
    assert!(check_index(1.55).unwrap().is_empty());
    let w = check_index(0.8).unwrap();
    assert_eq!(w.len(), 1);
    assert!(w[0].contains("below 1"), "{w:?}");
}

/// A map of Sq 10 nm (g = 0.044 at 20°, 550 nm) warns for every meter reading; one of
/// Sq 805 nm (g = 331 at 20°, 2.6 at 85°) for none. At Sq 400 nm only 85° (g = 0.63)
/// is smooth.
#[test]
fn ray_method_warns_on_smooth_maps() {
    let readings = meter_readings();
    let w = ray_warnings(10e-9, 550e-9, &readings);
    assert_eq!(w.len(), 1);
    for r in &readings {
        assert!(w[0].contains(&r.name), "{} missing: {}", r.name, w[0]);
    }
    assert!(ray_warnings(805e-9, 550e-9, &readings).is_empty());
    let w = ray_warnings(400e-9, 550e-9, &readings);
    assert!(
        w[0].contains("85° gloss") && !w[0].contains("20° gloss"),
        "{w:?}"
    );
}

/// A 94 µm spot (opd-1.opd's field) at 550 nm: its spread at 85° is
/// 550e-9 / (94e-6 · cos 85°) = 0.067 rad = 3.8°, above a quarter of the 4° receptor; at 20°
/// 0.36°, under a quarter of 1.8°. DOI's slits (0.1° × 3°) hold
/// 1.75e-3 · 5.2e-2 · cos 30° · (94e-6/550e-9)² = 2.3 grains, under 10; the 60° receptor
/// (4.4° × 11.7°) 229. A 20 mm spot resolves everything.
#[test]
fn kirchhoff_spot_and_speckle() {
    let readings = meter_readings();
    let w = kirchhoff_warnings(94e-6, 550e-9, &readings);
    assert_eq!(w.len(), 2, "{w:?}");
    assert!(
        w[0].contains("85° gloss") && w[0].contains("DOI"),
        "{}",
        w[0]
    );
    assert!(
        !w[0].contains("20° gloss") && !w[0].contains("60° gloss"),
        "{}",
        w[0]
    );
    assert!(w[1].contains("DOI (2.3 grains"), "{}", w[1]);
    assert!(!w[1].contains("60° gloss"), "{}", w[1]);
    assert!(kirchhoff_warnings(20e-3, 550e-9, &readings).is_empty());
    // In-plane detectors of 1.4° half-angle at 20–70°: the spread λ/(L cos 70°) of a 94 µm
    // spot is 0.98°, above a quarter of the detector's 2.8° width; the grains
    // π (0.0244)² · cos 70° · (94e-6/550e-9)² = 18.7 are enough.
    let inplane = inplane_readings(&[20.0, 70.0], 1.4f64.to_radians());
    let w = kirchhoff_warnings(94e-6, 550e-9, &inplane);
    assert_eq!(w.len(), 1, "{w:?}");
    assert!(w[0].contains("70° incidence") && !w[0].contains("20° incidence"));
}
