//! ISO 16610-21's Gaussian profile filter against its analytic transmission.

use gonio_surface::gaussian_filter::*;
use std::f64::consts::PI;

/// The amplitude of the sine of wavelength `lambda` in `f` (least squares on sin and cos over
/// the filtered points, positions `(start + k) dx`).
fn amplitude(f: &Filtered, dx: f64, lambda: f64) -> f64 {
    let (mut ss, mut cc, mut sc, mut zs, mut zc) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for (k, z) in f.values.iter().enumerate() {
        let x = (f.start + k) as f64 * dx;
        let (s, c) = (2.0 * PI * x / lambda).sin_cos();
        ss += s * s;
        cc += c * c;
        sc += s * c;
        zs += z * s;
        zc += z * c;
    }
    let det = ss * cc - sc * sc;
    let a = (zs * cc - zc * sc) / det;
    let b = (zc * ss - zs * sc) / det;
    a.hypot(b)
}

/// A sine's amplitude through the mean line is `exp(−π (α λc/λ)²)`: 50% at the cutoff. The
/// discrete weights differ from the continuous function by truncation (6.6e-7 of the peak
/// beyond ±λc) and by sampling, whose error for a Gaussian of standard deviation
/// σ = α λc/√(2π) = 0.187 λc sampled at λc/64 (σ = 12 dx) is of order exp(−2π² σ²/dx²): nil;
/// the bound 1e-5 is the truncation's share with margin.
#[test]
fn a_sine_passes_as_the_transmission_says() {
    assert!((transmission(1.0, 1.0) - 0.5).abs() < 1e-15);
    let cutoff = 0.8e-3;
    let dx = cutoff / 64.0;
    for ratio in [0.25, 0.5, 1.0, 2.0, 4.0] {
        let lambda = ratio * cutoff;
        let z: Vec<f64> = (0..4096)
            .map(|i| (2.0 * PI * i as f64 * dx / lambda + 0.3).sin())
            .collect();
        let f = mean_line(&z, dx, cutoff).unwrap();
        assert_eq!(f.start, 64);
        assert_eq!(f.values.len(), 4096 - 128);
        let got = amplitude(&f, dx, lambda);
        let want = transmission(lambda, cutoff);
        assert!((got - want).abs() < 1e-5, "λ/λc {ratio}: {got} vs {want}");
    }
}

/// A straight line passes the mean line unchanged; so does a constant (the weights are
/// symmetric and sum to one).
#[test]
fn a_straight_line_is_its_own_mean_line() {
    let dx = 1e-6;
    let z: Vec<f64> = (0..500).map(|i| 3e-6 + 2e-3 * i as f64 * dx).collect();
    let f = mean_line(&z, dx, 25e-6).unwrap();
    for (k, v) in f.values.iter().enumerate() {
        assert!(
            (v - z[f.start + k]).abs() < 1e-15,
            "{k}: {v} vs {}",
            z[f.start + k]
        );
    }
}

/// A band between two cutoffs keeps a sine inside it as `H(λ; short) − H(λ; long)` and
/// suppresses the waves outside: three sines at 0.1, 1 and 10 times the band's geometric centre
/// (cutoffs 0.3 and 3 mm around 1 mm). The filtered points span 60 mm (6000 at 10 µm, after the
/// 3 mm lost at each end), a whole number of periods of each sine, so that the fit of one is
/// blind to the others (discrete orthogonality) and the bound is the filter's own (1e-5, above).
#[test]
fn a_band_keeps_the_waves_inside_it() {
    let (short, long) = (0.3e-3, 3e-3);
    let dx = 10e-6;
    let n = 6600;
    let waves = [0.1e-3, 1e-3, 10e-3];
    let z: Vec<f64> = (0..n)
        .map(|i| {
            waves
                .iter()
                .map(|l| (2.0 * PI * i as f64 * dx / l).sin())
                .sum()
        })
        .collect();
    let b = band(&z, dx, short, long).unwrap();
    for lambda in waves {
        let want = transmission(lambda, short) - transmission(lambda, long);
        let got = amplitude(&b, dx, lambda);
        assert!((got - want).abs() < 1e-5, "λ {lambda}: {got} vs {want}");
    }
    assert!(transmission(1e-3, short) - transmission(1e-3, long) > 0.8);
}

/// Profiles too short or too coarse for a cutoff are refused, saying which.
#[test]
fn too_short_or_too_coarse_is_refused() {
    let z = vec![0.0; 100];
    let e = mean_line(&z, 1e-6, 60e-6).unwrap_err().to_string();
    assert!(e.contains("too short"), "{e}");
    let e = mean_line(&z, 1e-6, 1.5e-6).unwrap_err().to_string();
    assert!(e.contains("too coarse"), "{e}");
    assert!(band(&z, 1e-6, 20e-6, 10e-6).is_err());
    assert!(mean_line(&z, 0.0, 10e-6).is_err());
}
