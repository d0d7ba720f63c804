//! The Gaussian profile filter of ISO 16610-21 (geometrical product specifications, filtration:
//! linear profile filters, Gaussian filters): the mean line of a profile at a cutoff wavelength
//! λc, and band-pass profiles between two cutoffs as the wave-scan bands of a coating's long-wave
//! topography (orange peel) take them.
//!
//! The weighting function is `s(x) = exp(−π (x / (α λc))²) / (α λc)` with
//! `α = √(ln 2 / π) ≈ 0.4697` (ISO 16610-21, eq. 1), whose transmission for a sine of wavelength
//! λ is `H(λ) = exp(−π (α λc / λ)²)`: 50% at the cutoff, so that the mean line keeps the long
//! waves and the profile less its mean line (the roughness) the short ones. Discretely the
//! weights are `s` at the sample positions, truncated at ±λc (where `s` is exp(−π/α²) = 6.6e-7 of
//! its peak) and normalised to unit sum, so that a constant and a straight line pass unchanged
//! (the weights are symmetric). The mean line is given only where the weights fit inside the
//! profile: λc is lost at each end (ISO 16610-28 treats the end effects; gonio does not
//! extrapolate), so a profile must be longer than 2 λc.

use crate::error::{Result, SurfaceError};

/// α = √(ln 2 / π) of the Gaussian weighting function: 50% transmission at the cutoff.
pub fn alpha() -> f64 {
    (std::f64::consts::LN_2 / std::f64::consts::PI).sqrt()
}

/// The amplitude transmission of the mean line for a sine of wavelength `wavelength`, cutoff
/// `cutoff` (the same unit): `exp(−π (α λc / λ)²)`.
pub fn transmission(wavelength: f64, cutoff: f64) -> f64 {
    (-std::f64::consts::PI * (alpha() * cutoff / wavelength).powi(2)).exp()
}

/// A filtered profile: `values[k]` belongs to the input's point `start + k` (the points within a
/// cutoff of either end are not filtered).
#[derive(Debug, Clone, PartialEq)]
pub struct Filtered {
    pub start: usize,
    pub values: Vec<f64>,
}

/// The discrete weights for `cutoff` at spacing `dx`: `2 h + 1` values, h = ⌈λc/dx⌉.
fn weights(dx: f64, cutoff: f64) -> Vec<f64> {
    let h = (cutoff / dx).ceil() as i64;
    let width = alpha() * cutoff;
    let w: Vec<f64> = (-h..=h)
        .map(|k| {
            let x = k as f64 * dx;
            if x.abs() > cutoff {
                0.0
            } else {
                (-std::f64::consts::PI * (x / width).powi(2)).exp()
            }
        })
        .collect();
    let sum: f64 = w.iter().sum();
    w.into_iter().map(|v| v / sum).collect()
}

/// Check a profile of `n` points at `dx` against `cutoff`: finite and positive, a cutoff of at
/// least two spacings (the shortest wavelength the samples hold), and a profile longer than two
/// cutoffs.
fn check(n: usize, dx: f64, cutoff: f64) -> Result<()> {
    if !(dx > 0.0 && dx.is_finite() && cutoff.is_finite()) {
        return Err(SurfaceError::Invalid(format!(
            "Gaussian filter: the spacing {dx} and the cutoff {cutoff} must be finite and positive"
        )));
    }
    if cutoff < 2.0 * dx {
        return Err(SurfaceError::Invalid(format!(
            "Gaussian filter: a cutoff of {cutoff:e} is shorter than two sample spacings \
             ({:e}): the profile is too coarse to resolve it",
            2.0 * dx
        )));
    }
    let length = (n as f64 - 1.0) * dx;
    if length <= 2.0 * cutoff {
        return Err(SurfaceError::Invalid(format!(
            "Gaussian filter: a profile {length:e} long is too short for a cutoff of {cutoff:e}: \
             the mean line needs a cutoff on each side of every point (a profile longer than \
             {:e})",
            2.0 * cutoff
        )));
    }
    Ok(())
}

/// The mean line of the profile `z` (heights at spacing `dx`) at `cutoff` (the unit of `dx`),
/// where the weights fit inside the profile.
pub fn mean_line(z: &[f64], dx: f64, cutoff: f64) -> Result<Filtered> {
    check(z.len(), dx, cutoff)?;
    let w = weights(dx, cutoff);
    let h = w.len() / 2;
    let values = (h..z.len() - h)
        .map(|i| w.iter().zip(&z[i - h..=i + h]).map(|(a, b)| a * b).sum())
        .collect();
    Ok(Filtered { start: h, values })
}

/// The band of `z` between the cutoffs `short` and `long` (`short < long`): the mean line at
/// `short` less the mean line at `long`, over the points where both are given (those of
/// `long`). Its transmission is `H(λ; short) − H(λ; long)`.
pub fn band(z: &[f64], dx: f64, short: f64, long: f64) -> Result<Filtered> {
    if short >= long {
        return Err(SurfaceError::Invalid(format!(
            "Gaussian band: the short cutoff {short:e} must be below the long one {long:e}"
        )));
    }
    let wide = mean_line(z, dx, long)?;
    let narrow = mean_line(z, dx, short)?;
    let offset = wide.start - narrow.start;
    Ok(Filtered {
        start: wide.start,
        values: wide
            .values
            .iter()
            .enumerate()
            .map(|(k, l)| narrow.values[k + offset] - l)
            .collect(),
    })
}
