//! Wave-scan bands of a profile's slope against the filter's analytic transmission, and on a
//! measured file.

use gonio_surface::HeightMap;
use gonio_surface::gaussian_filter::transmission;
use gonio_surface::waviness::*;
use ndarray::Array2;
use std::f64::consts::PI;

/// A map of `rows` identical profiles `z = a sin(2π x / λ)` along x, `n` points at `dx`.
fn sine_map(a: f64, lambda: f64, n: usize, dx: f64, rows: usize) -> HeightMap {
    let z = Array2::from_shape_fn((rows, n), |(_, i)| {
        a * (2.0 * PI * i as f64 * dx / lambda).sin()
    });
    HeightMap::new(z, dx, dx).unwrap()
}

/// A sine of 2 mm, amplitude 0.5 µm (a visible orange peel), along a 100 mm scan at 10 µm: its
/// slope has amplitude `2π a / λ` (1.571 mrad), shrunk by the forward difference's
/// `sin(k dx/2)/(k dx/2)` (1 − 4e-5), and each band keeps `H(λ; short) − H(λ; long)` of it, so its
/// rms is that over √2. The bound: the rms over a whole number of periods is exact; over the
/// band's filtered length L (at least 76 mm) the partial period adds at most λ/(4πL) = 0.2%.
#[test]
fn a_sine_reads_as_the_bands_transmission_says() {
    let (a, lambda, dx) = (0.5e-6, 2e-3, 10e-6);
    let map = sine_map(a, lambda, 10_001, dx, 2);
    let k = 2.0 * PI / lambda;
    let slope = a * k * (k * dx / 2.0).sin() / (k * dx / 2.0);
    for r in waviness(&map, Direction::X, Quantity::Slope).unwrap() {
        let b = r.band;
        let want = slope * (transmission(lambda, b.short_m) - transmission(lambda, b.long_m))
            / 2f64.sqrt();
        match r.rms {
            Some(got) => assert!(
                (got - want).abs() <= 0.002 * slope / 2f64.sqrt() + 1e-12,
                "{}: {got:e} vs {want:e}",
                b.name
            ),
            None => panic!("{}: {:?}", b.name, r.unresolved),
        }
    }
    let r = waviness(&map, Direction::X, Quantity::Slope).unwrap();
    // The 2 mm wave lies in Wc (1–3 mm): the largest of Wa–We, though a Gaussian band passes
    // only H(2; 1) − H(2; 3) = 0.63 of it.
    let largest = r[..5]
        .iter()
        .max_by(|p, q| p.rms.partial_cmp(&q.rms).unwrap())
        .unwrap();
    assert_eq!(largest.band.name, "Wc");
    assert!((value(1e-3) - 28.35).abs() < 0.01);
}

/// Curvature of the same 2 mm sine of 0.5 µm: amplitude `a k²` (4.935 1/m), shrunk by the
/// second difference's `sinc²(k dx/2)` (1 − 8e-5), so its rms is `(2π/λ)² a / √2` (3.490 1/m)
/// times each band's transmission; the bound is the slope test's 0.2% (a partial period).
/// Curvature bands carry no 0–100 value.
#[test]
fn a_sines_curvature_reads_as_the_bands_transmission_says() {
    let (a, lambda, dx) = (0.5e-6, 2e-3, 10e-6);
    let map = sine_map(a, lambda, 10_001, dx, 2);
    let k = 2.0 * PI / lambda;
    let sinc = (k * dx / 2.0).sin() / (k * dx / 2.0);
    let rms = a * k * k * sinc * sinc / 2f64.sqrt();
    assert!((rms - 3.490).abs() < 1e-3, "{rms}");
    for r in waviness(&map, Direction::X, Quantity::Curvature).unwrap() {
        let b = r.band;
        let want = rms * (transmission(lambda, b.short_m) - transmission(lambda, b.long_m));
        let got = r
            .rms
            .unwrap_or_else(|| panic!("{}: {:?}", b.name, r.unresolved));
        assert!(
            (got - want).abs() <= 0.002 * rms + 1e-9,
            "{}: {got} vs {want} 1/m",
            b.name
        );
        assert_eq!(r.quantity, Quantity::Curvature);
        assert_eq!(r.value(), None);
    }
}

/// The same profiles along y read the same; invalid points split a profile into runs, each
/// filtered alone; bands too fine for the spacing or too long for the runs say so.
#[test]
fn directions_gaps_and_unresolved_bands() {
    let (a, lambda, dx) = (0.5e-6, 2e-3, 10e-6);
    let map = sine_map(a, lambda, 3001, dx, 3);
    let along_x = waviness(&map, Direction::X, Quantity::Slope).unwrap();
    let turned = HeightMap::new(map.heights().t().to_owned(), dx, dx).unwrap();
    let along_y = waviness(&turned, Direction::Y, Quantity::Slope).unwrap();
    assert_eq!(along_x, along_y);
    // 30 mm of profile: Wd (3–10 mm) needs more than 20 mm and LW (1.2–12) more than 24: both
    // read; We (10–30) does not.
    let names = |f: &dyn Fn(&BandReading) -> bool| {
        along_x
            .iter()
            .filter(|r| f(r))
            .map(|r| r.band.name)
            .collect::<Vec<_>>()
    };
    assert_eq!(names(&|r| r.rms.is_none()), ["We"]);
    assert!(
        along_x.iter().filter(|r| r.rms.is_none()).all(|r| r
            .unresolved
            .as_ref()
            .unwrap()
            .contains("too short"))
    );
    // A gap in the middle of every row leaves two runs of 15 mm: Wd then needs more.
    let mut with_gap = map.heights().to_owned();
    with_gap.column_mut(1500).fill(f64::NAN);
    let gapped = HeightMap::with_invalid(with_gap, dx, dx).unwrap();
    let r = waviness(&gapped, Direction::X, Quantity::Slope).unwrap();
    assert!(
        r.iter()
            .find(|r| r.band.name == "Wd")
            .unwrap()
            .rms
            .is_none()
    );
    let wc = |v: &[BandReading]| v.iter().find(|r| r.band.name == "Wc").unwrap().rms.unwrap();
    assert!((wc(&r) - wc(&along_x)).abs() < 0.01 * wc(&along_x));
    // 60 µm spacing: Wa (from 0.1 mm) is too fine.
    let coarse = waviness(
        &sine_map(a, lambda, 1001, 60e-6, 1),
        Direction::X,
        Quantity::Slope,
    )
    .unwrap();
    assert!(
        coarse[0]
            .unresolved
            .as_ref()
            .unwrap()
            .contains("too coarse"),
        "{:?}",
        coarse[0]
    );
}

/// The FRT profilometer's 12 mm map at 24 µm (crates/surface/tests/data/frt-1.frt, 31% of its
/// points invalid): the bands up to Wc read, Wd and beyond need longer runs than it has.
#[test]
fn a_measured_map_reads_where_it_can() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/frt-1.frt");
    let map = gonio_surface::io::read(&path).unwrap();
    let r = waviness(&map, Direction::X, Quantity::Slope).unwrap();
    for b in &r {
        match b.band.name {
            "Wa" | "Wb" | "SW" => assert!(b.rms.is_some_and(|s| s > 0.0 && s.is_finite()), "{b:?}"),
            "Wd" | "We" | "LW" => assert!(
                b.unresolved
                    .as_ref()
                    .is_some_and(|u| u.contains("too short")),
                "{b:?}"
            ),
            _ => {}
        }
    }
}
