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
