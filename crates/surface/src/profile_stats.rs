//! Statistics of a line profile per ISO 21920-2:2021 (profile surface texture: terms,
//! definitions and parameters), computed over the valid points after removing the
//! least-squares line: root-mean-square height Rq, arithmetic mean height Ra, skewness Rsk,
//! kurtosis Rku and root-mean-square slope Rdq.
//!
//! ISO 21920-2 defines these on the evaluation length of a profile that has been filtered with
//! the λs and λc filters of ISO 16610-21; no filter is applied here, so on an unfiltered
//! profile the values are, strictly, the primary-profile parameters (Pq, Pa, ...) of the same
//! definitions. The standard leaves the discrete derivative to the implementation: Rdq uses
//! forward differences between neighbouring valid points, like Sdq in [`crate::stats`], so for
//! a sine of wavenumber k sampled at spacing dx it is `sinc`-low by a factor
//! `sin(k dx/2)/(k dx/2)`.

use crate::error::{Result, SurfaceError};
use crate::heightmap::HeightMap;

/// ISO 21920-2 parameters of a line profile (lengths in metres).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProfileStatistics {
    /// Root-mean-square height, m.
    pub rq: f64,
    /// Arithmetic mean height, m.
    pub ra: f64,
    /// Skewness; NaN for a straight profile.
    pub rsk: f64,
    /// Kurtosis; NaN for a straight profile.
    pub rku: f64,
    /// Root-mean-square slope, dimensionless.
    pub rdq: f64,
}

/// The [`ProfileStatistics`] of `profile` after removing its least-squares line. An error when
/// the map is not a line profile or has fewer than two valid points.
pub fn profile_statistics(profile: &HeightMap) -> Result<ProfileStatistics> {
    if !profile.is_profile() {
        return Err(SurfaceError::Invalid(format!(
            "a {} × {} areal map is not a line profile",
            profile.nx(),
            profile.ny()
        )));
    }
    let dx = profile.dx();
    let points: Vec<(f64, f64)> = profile
        .heights()
        .iter()
        .enumerate()
        .filter(|(_, z)| !z.is_nan())
        .map(|(i, &z)| (i as f64 * dx, z))
        .collect();
    if points.len() < 2 {
        return Err(SurfaceError::Invalid(format!(
            "a line profile needs two valid points, this one has {}",
            points.len()
        )));
    }
    let (slope, intercept) = least_squares_line(&points);
    let residual: Vec<Option<f64>> = profile
        .heights()
        .iter()
        .enumerate()
        .map(|(i, &z)| (!z.is_nan()).then_some(z - (intercept + slope * i as f64 * dx)))
        .collect();

    let n = points.len() as f64;
    let valid = residual.iter().flatten();
    let moment = |p: i32| valid.clone().map(|z| z.powi(p)).sum::<f64>() / n;
    let rq = moment(2).sqrt();
    let ra = valid.clone().map(|z| z.abs()).sum::<f64>() / n;
    let slopes: Vec<f64> = residual
        .windows(2)
        .filter_map(|w| Some((w[1]? - w[0]?) / dx))
        .collect();
    let rdq = if slopes.is_empty() {
        0.0
    } else {
        (slopes.iter().map(|s| s * s).sum::<f64>() / slopes.len() as f64).sqrt()
    };
    Ok(ProfileStatistics {
        rq,
        ra,
        rsk: moment(3) / rq.powi(3),
        rku: moment(4) / rq.powi(4),
        rdq,
    })
}

/// Slope and intercept of the least-squares line through `points` (at least two distinct x).
fn least_squares_line(points: &[(f64, f64)]) -> (f64, f64) {
    let n = points.len() as f64;
    let mean_x = points.iter().map(|p| p.0).sum::<f64>() / n;
    let mean_z = points.iter().map(|p| p.1).sum::<f64>() / n;
    let (sxz, sxx) = points.iter().fold((0.0, 0.0), |(sxz, sxx), &(x, z)| {
        let u = x - mean_x;
        (sxz + u * (z - mean_z), sxx + u * u)
    });
    let slope = sxz / sxx;
    (slope, mean_z - slope * mean_x)
}

#[cfg(test)]
mod tests {
    use super::*;
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
        let (sq, ..) = crate::stats::height_parameters(&crate::ops::level(&p).unwrap());
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
}
