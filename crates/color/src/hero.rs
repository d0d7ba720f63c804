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
use crate::mat3;
use crate::spectrum::Spectrum;
use crate::srgb::LinearSrgb;
use crate::tristimulus::{WeightingFactors, display_matrix};
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
}

impl SpectralFilm {
    /// The film for wavelengths drawn by `sampler`.
    pub fn new(sampler: HeroSampler, illuminant: Illuminant, observer: Observer) -> Self {
        let factors = WeightingFactors::of(illuminant, observer);
        let grid = Spectrum::constant(factors.wavelengths_nm().to_vec(), 0.0)
            .expect("the weighting factors share the valid grid of the CIE tables");
        let scale = 1.0 / (HERO_COUNT as f64 * sampler.pdf_per_nm());
        let xyz: Vec<[f64; 3]> = factors
            .weights()
            .iter()
            .map(|w| w.map(|v| v * scale))
            .collect();
        let to_rgb = display_matrix(illuminant, observer);
        let rgb = xyz.iter().map(|&w| mat3::mul_vec(&to_rgb, w)).collect();
        Self {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tristimulus::reflectance_xyz;

    /// With u on a stratified grid of N points (N a multiple of C), each λ_j on its own takes
    /// exactly the midpoints of N equal cells of the range (it is uniform), and the C wavelengths
    /// of a path fall one in each quarter of the range (they are stratified).
    #[test]
    fn hero_wavelengths_are_uniform_and_stratified() {
        let sampler = HeroSampler::visible();
        let n = 200;
        let paths: Vec<[f64; HERO_COUNT]> = (0..n)
            .map(|i| sampler.sample((i as f64 + 0.5) / n as f64))
            .collect();
        let cell = 400.0 / n as f64;
        for j in 0..HERO_COUNT {
            let mut marginal: Vec<f64> = paths.iter().map(|p| p[j]).collect();
            marginal.sort_by(f64::total_cmp);
            for (k, w) in marginal.iter().enumerate() {
                assert!(
                    (w - (380.0 + (k as f64 + 0.5) * cell)).abs() < 1e-9,
                    "{j} {k}: {w}"
                );
            }
        }
        for path in &paths {
            let mut quarters: Vec<usize> = path
                .iter()
                .map(|w| ((w - 380.0) / 100.0) as usize)
                .collect();
            quarters.sort();
            assert_eq!(quarters, [0, 1, 2, 3]);
        }
        assert!(HeroSampler::new(300.0, 700.0).is_err());
        assert!(HeroSampler::new(700.0, 500.0).is_err());
    }

    /// What separates the film's limit, the integral over the sampler's range of the linearly
    /// interpolated weights W times the spectrum ρ, from the 1 nm sum Σ_k W_k ρ_k: the sum's terms
    /// outside the range; the ends of the range, which the integral counts with half weight; and on
    /// each 1 nm step the trapezoid error of a product of two linear functions, (ΔW Δρ)/6.
    fn film_vs_sum_bound(
        factors: &WeightingFactors,
        rho: &Spectrum,
        range: (f64, f64),
    ) -> [f64; 3] {
        let (lo, hi) = range;
        let points: Vec<(f64, [f64; 3], f64)> = factors
            .wavelengths_nm()
            .iter()
            .zip(factors.weights())
            .map(|(&w, &f)| (w, f, rho.value_at(w)))
            .collect();
        std::array::from_fn(|c| {
            let outside: f64 = points
                .iter()
                .filter(|p| p.0 < lo || p.0 > hi)
                .map(|p| p.1[c] * p.2)
                .sum();
            let ends: f64 = points
                .iter()
                .filter(|p| p.0 == lo || p.0 == hi)
                .map(|p| 0.5 * p.1[c] * p.2)
                .sum();
            let trapezoid: f64 = points
                .windows(2)
                .filter(|w| w[0].0 >= lo && w[1].0 <= hi)
                .map(|w| ((w[1].1[c] - w[0].1[c]) * (w[1].2 - w[0].2)).abs() / 6.0)
                .sum();
            outside + ends + trapezoid + 1e-6
        })
    }

    /// A flat spectrum reduces to the illuminant's white, and a smooth one to its direct 1 nm
    /// integration, within the bound above (at most 0.03 on the 0–100 scale here; the Monte Carlo
    /// error of 20 000 stratified paths is far below it).
    #[test]
    fn film_estimate_converges_to_the_direct_integration() {
        let values = (0..81)
            .map(|i| 0.4 + 0.3 * (i as f64 / 9.0).sin())
            .collect();
        let smooth = Spectrum::uniform(380.0, 5.0, values).unwrap();
        let flat = Spectrum::constant(vec![360.0, 830.0], 1.0).unwrap();
        let samplers = [
            HeroSampler::new(360.0, 830.0).unwrap(),
            HeroSampler::visible(),
        ];
        for illuminant in Illuminant::ALL {
            for observer in Observer::ALL {
                let factors = WeightingFactors::of(illuminant, observer);
                for sampler in samplers {
                    let film = SpectralFilm::new(sampler, illuminant, observer);
                    for spectrum in [&flat, &smooth] {
                        let n = 20_000;
                        let mut sum = [0.0; 3];
                        for i in 0..n {
                            let ws = sampler.sample((i as f64 + 0.5) / n as f64);
                            let values = ws.map(|w| spectrum.value_at(w));
                            let xyz = film.xyz(&ws, &values).to_array();
                            (0..3).for_each(|c| sum[c] += xyz[c] / n as f64);
                        }
                        let direct = reflectance_xyz(spectrum, illuminant, observer).to_array();
                        let bound = film_vs_sum_bound(factors, spectrum, sampler.range_nm());
                        for c in 0..3 {
                            assert!(bound[c] < 0.03, "{bound:?}");
                            assert!(
                                (sum[c] - direct[c]).abs() <= bound[c],
                                "{illuminant} {observer} {:?}: {sum:?} vs {direct:?}, {bound:?}",
                                sampler.range_nm()
                            );
                        }
                    }
                }
            }
        }
    }

    /// The sRGB weights are the XYZ weights through the display matrix: a flat spectrum averages
    /// to sRGB white under A (after Bradford adaptation).
    #[test]
    fn rgb_weights_give_white_for_a_flat_spectrum() {
        let sampler = HeroSampler::new(360.0, 830.0).unwrap();
        let film = SpectralFilm::new(sampler, Illuminant::A, Observer::Cie1931TwoDegree);
        let n = 20_000;
        let mut rgb = [0.0; 3];
        for i in 0..n {
            let ws = sampler.sample((i as f64 + 0.5) / n as f64);
            let c = film.linear_srgb(&ws, &[1.0; HERO_COUNT]);
            for (s, v) in rgb.iter_mut().zip([c.r, c.g, c.b]) {
                *s += v / n as f64;
            }
        }
        for v in rgb {
            assert!((v - 1.0).abs() < 1e-5, "{rgb:?}");
        }
    }
}
