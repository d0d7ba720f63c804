//! ISO 21920 profile statistics: a sine against its analytic values, Rq equal to the areal Sq of
//! the same row, a straight line removed entirely, invalid points skipped.

use gonio_surface::heightmap::HeightMap;
use gonio_surface::profile_stats::*;
use std::f64::consts::{PI, SQRT_2};

/// `periods` whole periods of a sine of amplitude `a` over `n` points, on a tilted line.
/// The sine is centred on the profile (a cosine about its middle), so that it is orthogonal
/// to the least-squares line and the analytic values hold to within the sampling.
fn tilted_sine(a: f64, periods: f64, n: usize, dx: f64) -> (HeightMap, f64) {
    let length = (n - 1) as f64 * dx;
    let k = 2.0 * PI * periods / length;
    let z = (0..n)
        .map(|i| {
            let x = i as f64 * dx;
            a * (k * (x - length / 2.0) + PI / 2.0).sin() + 3e-3 * x + 1e-7
        })
        .collect();
    (HeightMap::profile(z, dx).unwrap(), k)
}

#[test]
fn sine_matches_the_analytic_values() {
    let (a, dx) = (50e-9, 0.1e-6);
    let (p, k) = tilted_sine(a, 10.0, 20_001, dx);
    let s = profile_statistics(&p).unwrap();
    // Rq = A/√2, Ra = 2A/π, Rsk = 0, Rku = 3/2 and Rdq = Ak/√2; the forward difference
    // lowers Rdq by sin(k dx/2)/(k dx/2) ≈ 1 − 2e-6 here.
    assert!((s.rq / (a / SQRT_2) - 1.0).abs() < 1e-4, "Rq {}", s.rq);
    assert!((s.ra / (2.0 * a / PI) - 1.0).abs() < 1e-4, "Ra {}", s.ra);
    assert!(s.rsk.abs() < 1e-4, "Rsk {}", s.rsk);
    assert!((s.rku - 1.5).abs() < 1e-4, "Rku {}", s.rku);
    assert!(
        (s.rdq / (a * k / SQRT_2) - 1.0).abs() < 1e-4,
        "Rdq {}",
        s.rdq
    );
}

#[test]
fn rq_equals_the_areal_sq_of_the_one_row_map() {
    // The areal statistics level a one-row map with its least-squares line too.
    let (p, _) = tilted_sine(2e-8, 3.5, 999, 1e-7);
    let rq = profile_statistics(&p).unwrap().rq;
    let (sq, ..) = gonio_surface::stats::height_parameters(&gonio_surface::ops::level(&p).unwrap());
    assert!((rq / sq - 1.0).abs() < 1e-12, "Rq {rq}, Sq {sq}");
}

#[test]
fn a_straight_line_is_removed_entirely() {
    let z = (0..100).map(|i| 2e-9 * i as f64 - 5e-8).collect();
    let s = profile_statistics(&HeightMap::profile(z, 1e-6).unwrap()).unwrap();
    assert!(s.rq < 1e-20 && s.ra < 1e-20 && s.rdq < 1e-14, "{s:?}");
}

#[test]
fn invalid_points_are_skipped() {
    let (a, dx) = (1e-8, 1e-7);
    let (p, _) = tilted_sine(a, 4.0, 4001, dx);
    let mut z = p.heights().clone();
    z[[0, 17]] = f64::NAN;
    z[[0, 2500]] = f64::NAN;
    let s = profile_statistics(&p.with_heights(z).unwrap()).unwrap();
    assert!((s.rq / (a / SQRT_2) - 1.0).abs() < 1e-3, "Rq {}", s.rq);
}

#[test]
fn areal_maps_and_single_points_are_errors() {
    let areal = HeightMap::new(ndarray::Array2::zeros((2, 2)), 1.0, 1.0).unwrap();
    assert!(profile_statistics(&areal).is_err());
    let one = HeightMap::profile(vec![1.0, f64::NAN], 1.0).unwrap();
    assert!(profile_statistics(&one).is_err());
}
