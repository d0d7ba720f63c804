//! The metameric pair: two reflectance spectra whose CIE 1931 2° tristimulus values are equal
//! under D65 and differ under illuminant A, and their reference colours.
//!
//! Construction (Wyszecki & Stiles, *Color Science*, 2nd ed., §3.8.5: a metameric black is a
//! spectrum orthogonal to the three weighting functions): the first patch is a smooth spectrum
//! `ρ1`; a wave `p(λ)` has its projection on the span of the three D65 weighting functions
//! (`gonio_color::SpectralToXyz`, CIE 1931 2°, the ASTM E308 weights the renderer's film uses)
//! removed by least squares, and `ρ2 = ρ1 + p_black`. So `Σ w_j ρ2 = Σ w_j ρ1` for j = X, Y, Z
//! under D65 to rounding, while under A the weights differ and so do the colours.

use crate::error::Result;
use gonio_color::{Illuminant, Lab, Observer, SpectralToXyz, Xyz, ciede2000};

/// The bands of both spectra: 400 to 700 nm every 10 nm.
pub fn wavelengths_nm() -> Vec<f64> {
    (0..31).map(|i| 400.0 + 10.0 * i as f64).collect()
}

/// The two spectra (reflectances in [0, 1] at [`wavelengths_nm`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Pair {
    /// The first patch: a smooth, slightly greenish grey.
    pub first: Vec<f64>,
    /// The second patch: the first plus a metameric black.
    pub second: Vec<f64>,
}

/// The pair.
pub fn pair() -> Result<Pair> {
    let wl = wavelengths_nm();
    let first: Vec<f64> = wl
        .iter()
        .map(|&w| 0.45 + 0.1 * (-((w - 530.0) / 80.0).powi(2)).exp())
        .collect();
    // The wave: two periods over the range, largest at the ends, where the D65 and A weights
    // differ most.
    let wave: Vec<f64> = wl
        .iter()
        .map(|&w| 0.3 * (2.0 * std::f64::consts::PI * (w - 400.0) / 150.0).cos())
        .collect();
    let weights = SpectralToXyz::new(&wl, Illuminant::D65, Observer::Cie1931TwoDegree)?;
    let w: Vec<[f64; 3]> = weights.xyz_weights().to_vec();
    // Least squares: p_black = p − W (WᵀW)⁻¹ Wᵀ p, W the bands × 3 matrix of weights.
    let mut gram = [[0.0; 3]; 3];
    let mut rhs = [0.0; 3];
    for (wi, &p) in w.iter().zip(&wave) {
        for a in 0..3 {
            rhs[a] += wi[a] * p;
            for b in 0..3 {
                gram[a][b] += wi[a] * wi[b];
            }
        }
    }
    let coef = solve3(gram, rhs);
    let second = first
        .iter()
        .zip(&wave)
        .zip(&w)
        .map(|((&r, &p), wi)| r + p - (0..3).map(|a| wi[a] * coef[a]).sum::<f64>())
        .collect();
    Ok(Pair { first, second })
}

/// The tristimulus values (Y of the perfect diffuser = 100, gonio_color's scale) of `reflectance` at
/// [`wavelengths_nm`] under `illuminant`, CIE 1931 2°.
pub fn xyz(reflectance: &[f64], illuminant: Illuminant) -> Result<Xyz> {
    let weights = SpectralToXyz::new(&wavelengths_nm(), illuminant, Observer::Cie1931TwoDegree)?;
    let v = weights.xyz(reflectance)?;
    let white = weights.xyz(&vec![1.0; reflectance.len()])?;
    let k = 100.0 / white.y;
    Ok(Xyz::from_array([v.x * k, v.y * k, v.z * k]))
}

/// CIELAB of `reflectance` under `illuminant`, the white the perfect diffuser under the same
/// illuminant (so the observer is taken as fully adapted to it).
pub fn lab(reflectance: &[f64], illuminant: Illuminant) -> Result<Lab> {
    let white = xyz(&vec![1.0; reflectance.len()], illuminant)?;
    Ok(xyz(reflectance, illuminant)?.to_lab(white))
}

/// CIEDE2000 between the two patches under `illuminant`.
pub fn pair_delta_e(pair: &Pair, illuminant: Illuminant) -> Result<f64> {
    Ok(ciede2000(
        lab(&pair.first, illuminant)?,
        lab(&pair.second, illuminant)?,
    ))
}

/// The solution of the 3 × 3 system `m x = r` by Cramer's rule (m is a Gram matrix of three
/// independent weighting functions: well conditioned enough for f64).
fn solve3(m: [[f64; 3]; 3], r: [f64; 3]) -> [f64; 3] {
    let det = |a: [[f64; 3]; 3]| {
        a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1])
            - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
            + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0])
    };
    let d = det(m);
    let mut x = [0.0; 3];
    for (c, xc) in x.iter_mut().enumerate() {
        let mut a = m;
        for row in 0..3 {
            a[row][c] = r[row];
        }
        *xc = det(a) / d;
    }
    x
}
