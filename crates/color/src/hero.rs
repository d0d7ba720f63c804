//! Hero-wavelength spectral sampling for the renderer: each path carries a few wavelengths spread
//! evenly over the visible range, and the film turns their spectral values into XYZ or linear
//! sRGB with per-wavelength weights.
//!
//! Source: A. Wilkie, S. Nawaz, M. Droske, A. Weidlich, J. Hanika, "Hero Wavelength Spectral
//! Sampling", Computer Graphics Forum 33(4) (EGSR 2014), section 4: a hero wavelength λ_h is drawn
//! uniformly over [λ_min, λ_max) and the others are its rotations
//! `λ_j = λ_min + (λ_h − λ_min + j Δ / C) mod Δ`, j = 0..C, Δ = λ_max − λ_min, so every λ_j is
//! uniform on its own (pdf 1/Δ) and the C samples stratify the range. The film estimate of a
//! tristimulus value is the Monte Carlo average `X ≈ (1/C) Σ_j W_X(λ_j) v(λ_j) / p(λ_j)`, with
//! W the CIE weighting factors of the illuminant and observer (pbrt-v4, section 4.6.6, does the
//! same with C = 4).

use crate::cie::{Illuminant, Observer};
use crate::error::{ColorError, Result};
use crate::mat3::{self, Mat3};
use crate::spectrum::Spectrum;
use crate::srgb::LinearSrgb;
use crate::tristimulus::{WeightingFactors, display_matrix, display_matrix_for_white};
use crate::xyz::Xyz;

/// Number of wavelengths carried per path (C in Wilkie et al. 2014).
pub const HERO_COUNT: usize = 4;

/// Draws the wavelengths of a path over a range (nm).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HeroSampler {
    min_nm: f64,
    max_nm: f64,
}

impl HeroSampler {
    /// Sample over [min_nm, max_nm), which must lie inside the 360–830 nm of the CIE tables.
    pub fn new(min_nm: f64, max_nm: f64) -> Result<Self> {
        let valid = (360.0..830.0).contains(&min_nm) && min_nm < max_nm && max_nm <= 830.0;
        if !valid {
            return Err(ColorError::InvalidSpectrum(format!(
                "hero-wavelength range {min_nm}–{max_nm} nm: it must be increasing and within \
                 360–830 nm, the range of the CIE tables"
            )));
        }
        Ok(Self { min_nm, max_nm })
    }

    /// The usual visible range, 380–780 nm.
    pub fn visible() -> Self {
        Self {
            min_nm: 380.0,
            max_nm: 780.0,
        }
    }

    /// The range (nm).
    pub fn range_nm(&self) -> (f64, f64) {
        (self.min_nm, self.max_nm)
    }

    /// The path's wavelengths (nm) for a uniform random number `u` in [0, 1): the hero
    /// `λ_min + u Δ` first, then its rotations by Δ/C.
    pub fn sample(&self, u: f64) -> [f64; HERO_COUNT] {
        let span = self.max_nm - self.min_nm;
        let hero = u.clamp(0.0, 1.0) * span;
        std::array::from_fn(|j| {
            let offset = (hero + j as f64 * span / HERO_COUNT as f64) % span;
            self.min_nm + offset
        })
    }

    /// The density of each wavelength (1/nm): 1/Δ.
    pub fn pdf_per_nm(&self) -> f64 {
        1.0 / (self.max_nm - self.min_nm)
    }
}

/// Film weights for hero-wavelength rendering under `illuminant`, seen by `observer`.
///
/// A path's spectral values v(λ_j) are throughputs relative to a light of the illuminant's
/// spectrum (a reflectance-like quantity: v = 1 for a path that reaches a light of unit strength
/// over a perfect white reflector): the weights include the illuminant's power and normalise so
/// that v ≡ 1 averages to the illuminant's white (Y = 100, linear sRGB ≈ 1).
#[derive(Clone, Debug)]
pub struct SpectralFilm {
    sampler: HeroSampler,
    /// The wavelengths of the weighting factors (1 nm), for the segment lookup.
    grid: Spectrum,
    /// `W(λ_k) / (C p)` on the grid: XYZ weights.
    xyz: Vec<[f64; 3]>,
    /// The same through the display matrix: linear sRGB weights.
    rgb: Vec<[f64; 3]>,
    /// The XYZ that v ≡ 1 averages to: the light's white, Y = 100.
    white: Xyz,
}

impl SpectralFilm {
    /// The film for wavelengths drawn by `sampler`.
    pub fn new(sampler: HeroSampler, illuminant: Illuminant, observer: Observer) -> Self {
        Self::of_factors(
            sampler,
            WeightingFactors::of(illuminant, observer),
            display_matrix(illuminant, observer),
        )
    }

    /// The film of a light of relative spectral power `spd` (a CIE illuminant's table or a
    /// measured source; see [`WeightingFactors::of_spectrum`]), its linear sRGB white-balanced to
    /// that light's white ([`display_matrix_for_white`]).
    pub fn of_spectrum(sampler: HeroSampler, spd: &Spectrum, observer: Observer) -> Self {
        let factors = WeightingFactors::of_spectrum(spd, observer);
        Self::of_factors(sampler, &factors, display_matrix_for_white(factors.white()))
    }

    /// The film of the weighting factors `factors`, with `to_rgb` from their XYZ to linear sRGB.
    fn of_factors(sampler: HeroSampler, factors: &WeightingFactors, to_rgb: Mat3) -> Self {
        let grid = Spectrum::constant(factors.wavelengths_nm().to_vec(), 0.0)
            .expect("the weighting factors share the valid grid of the CIE tables");
        let scale = 1.0 / (HERO_COUNT as f64 * sampler.pdf_per_nm());
        let xyz: Vec<[f64; 3]> = factors
            .weights()
            .iter()
            .map(|w| w.map(|v| v * scale))
            .collect();
        let rgb = xyz.iter().map(|&w| mat3::mul_vec(&to_rgb, w)).collect();
        Self {
            white: factors.white(),
            sampler,
            grid,
            xyz,
            rgb,
        }
    }

    /// The table entry at `wavelength_nm`, linear between the 1 nm grid points.
    fn lookup(&self, table: &[[f64; 3]], wavelength_nm: f64) -> [f64; 3] {
        let (i, t) = self.grid.segment(wavelength_nm);
        std::array::from_fn(|c| table[i][c] + t * (table[i + 1][c] - table[i][c]))
    }

    /// The XYZ that v ≡ 1 averages to (0–100 scale): the perfect diffuser under the light.
    pub fn white(&self) -> Xyz {
        self.white
    }

    /// The sampler this film expects the wavelengths from.
    pub fn sampler(&self) -> &HeroSampler {
        &self.sampler
    }

    /// [w_X, w_Y, w_Z] for each wavelength: the path's XYZ (0–100 scale) is `Σ_j w_j v(λ_j)`.
    /// Each is `W(λ_j) / (C p(λ_j))`, W the 1 nm weighting factors interpolated linearly.
    pub fn xyz_weights(&self, wavelengths_nm: &[f64; HERO_COUNT]) -> [[f64; 3]; HERO_COUNT] {
        wavelengths_nm.map(|w| self.lookup(&self.xyz, w))
    }

    /// [w_R, w_G, w_B] for each wavelength: the path's linear sRGB is `Σ_j w_j v(λ_j)`
    /// (white-balanced to the illuminant, see [`display_matrix`]).
    pub fn rgb_weights(&self, wavelengths_nm: &[f64; HERO_COUNT]) -> [[f64; 3]; HERO_COUNT] {
        wavelengths_nm.map(|w| self.lookup(&self.rgb, w))
    }

    /// The XYZ estimate of one path.
    pub fn xyz(&self, wavelengths_nm: &[f64; HERO_COUNT], values: &[f64; HERO_COUNT]) -> Xyz {
        Xyz::from_array(weighted_sum(&self.xyz_weights(wavelengths_nm), values))
    }

    /// The linear sRGB estimate of one path.
    pub fn linear_srgb(
        &self,
        wavelengths_nm: &[f64; HERO_COUNT],
        values: &[f64; HERO_COUNT],
    ) -> LinearSrgb {
        let [r, g, b] = weighted_sum(&self.rgb_weights(wavelengths_nm), values);
        LinearSrgb { r, g, b }
    }
}

fn weighted_sum(weights: &[[f64; 3]; HERO_COUNT], values: &[f64; HERO_COUNT]) -> [f64; 3] {
    std::array::from_fn(|c| weights.iter().zip(values).map(|(w, v)| w[c] * v).sum())
}
