//! Maps whose two spacings differ by many orders of magnitude, as a damaged header makes them:
//! every statistic returns after a number of steps bounded by the map's points, whatever the
//! spacings, and still measures the decay along the axis it can resolve.

use crate::fixture_tools::fixture;
use gonio_surface::stats::{self, Autocorrelation, Statistics};
use gonio_surface::{HeightMap, io};
use std::path::Path;
use std::sync::mpsc;
use std::time::Duration;

/// `statistics(map)` on another thread, or `None` when it has not returned within `limit`.
///
/// A hang detector, not a speed test: the 300 × 300 maps below take milliseconds (the issue asks
/// for under a second each); before the fix a 3 pm spacing against 63 µm took minutes and a
/// 1e-15 m one would have taken days. The limit leaves a loaded CI machine a factor of hundreds.
fn statistics_within(map: HeightMap, limit: Duration) -> Option<Statistics> {
    let (send, receive) = mpsc::channel();
    std::thread::spawn(move || send.send(stats::statistics(&map).unwrap()));
    receive.recv_timeout(limit).ok()
}

const LIMIT: Duration = Duration::from_secs(20);

/// The shared TrueMap file with byte 67 (the last of the x field length, an f32 in mm) changed
/// from 0x41 to 0x04: the field becomes about 4e-36 mm, x spacing 1.3e-41 m against 63 µm.
fn damaged_tmd() -> HeightMap {
    let mut bytes = std::fs::read(fixture("tmd-1.tmd")).unwrap();
    assert_eq!(bytes[67], 0x41, "the fixture is the shared tmd-1.tmd");
    bytes[67] = 0x04;
    io::read_bytes(Path::new("damaged.tmd"), &bytes).unwrap()
}

#[test]
fn a_damaged_truemap_header_reads_with_a_warning_and_its_statistics_return() {
    let map = damaged_tmd();
    assert!(map.dx() < 1e-40 && (map.dy() / 63.19e-6 - 1.0).abs() < 1e-3);
    let warnings: Vec<&str> = map.meta.warnings().collect();
    assert!(
        warnings
            .iter()
            .any(|w| w.contains("spacings differ") && w.contains("header may be damaged")),
        "{warnings:?}"
    );
    let st = statistics_within(map, LIMIT).expect("the statistics return");
    assert!(st.sq > 0.0 && st.sal.is_some(), "{st:?}");
    // The undamaged file reads without that warning.
    let good = io::read(&fixture("tmd-1.tmd")).unwrap();
    assert_eq!(good.meta.warnings().count(), 0);
}

/// First lag (fractional, linear between whole lags) at which the ACF along +x (`along_x`) or
/// +y drops to 0.2: the decay length in lags along that axis, computed on the lag grid's nodes.
fn decay_lags(acf: &Autocorrelation, along_x: bool) -> f64 {
    let at = |k: f64| {
        if along_x {
            acf.at(k * acf.dx, 0.0)
        } else {
            acf.at(0.0, k * acf.dy)
        }
    };
    let mut prev = at(0.0);
    for k in 1.. {
        let a = at(k as f64);
        assert!(!a.is_nan(), "the ACF decays within the lag grid");
        if a <= stats::ACF_THRESHOLD {
            return k as f64 - 1.0 + (prev - stats::ACF_THRESHOLD) / (prev - a);
        }
        prev = a;
    }
    unreachable!()
}

#[test]
fn sal_returns_for_x_spacings_from_a_femtometre_to_a_petametre_against_63_um() {
    let map = io::read(&fixture("tmd-1.tmd")).unwrap();
    let dy = map.dy();
    // At an aspect beyond 10⁴ every direction but those within 10⁻⁴ rad of the slow axis runs
    // along the fast one in lag space: Sal is the fast axis's decay length, the same number of
    // lags whatever the spacing. It is the minimum over 720 directions that cross the lag grid
    // at angles within (10⁻⁴ … π/2) of the axis, so it lies at or just below the axis's own
    // (linear interpolation along a slightly slanted line, a relative difference below 10⁻⁶).
    let acf = Autocorrelation::of(&map).unwrap();
    let (lags_x, lags_y) = (decay_lags(&acf, true), decay_lags(&acf, false));
    for exponent in -15..=15 {
        let dx = 10f64.powi(exponent);
        let st = statistics_within(map.clone().with_spacing(dx, dy).unwrap(), LIMIT)
            .unwrap_or_else(|| panic!("statistics did not return for dx = {dx:e} m"));
        let sal = st.sal.expect("the map's ACF decays");
        let expected = if dx < dy * 1e-4 {
            Some(lags_x * dx)
        } else if dx > dy * 1e4 {
            Some(lags_y * dy)
        } else {
            None
        };
        if let Some(expected) = expected {
            assert!(
                sal <= expected * (1.0 + 1e-9) && sal > expected * (1.0 - 1e-6),
                "dx {dx:e}: Sal {sal:e} against the fast axis's {expected:e}"
            );
        }
    }
}
