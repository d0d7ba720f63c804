//! Spectral rendering ([`crate::ColourMode::Spectral`]): hero-wavelength spectral sampling
//! (A. Wilkie, S. Nawaz, M. Droske, A. Weidlich, J. Hanika, "Hero Wavelength Spectral Sampling",
//! Computer Graphics Forum 33(4), EGSR 2014, section 4). Each camera path draws a uniform number
//! u and carries four wavelengths, `λ_j = P⁻¹((u + j/4) mod 1)`: the hero and its three
//! rotations, taken in the variable of the cumulative distribution P of the wavelength pdf, so
//! that each λ_j is distributed by the pdf and the four are stratified (pbrt-v4 does the same,
//! `SampledWavelengths::SampleVisible`). The pdf is pbrt-v4's `VisibleWavelengthsPDF`,
//! `p(λ) = 0.0039398042 / cosh²(0.0072 (λ − 538 nm))` over 360–830 nm, which follows the
//! visual response and gives less colour noise than uniform wavelengths (the film weights W below
//! span the whole CIE range). The directions are sampled as in the tristimulus mode and every
//! BRDF value, weighted by `cos θ / pdf`, is taken at the four wavelengths. The film turns the
//! four values into linear sRGB as `Σ_j W(λ_j) v(λ_j) / (4 p(λ_j))`, W the weighting factors of
//! illuminant D65 and the CIE 1931 2° observer through the sRGB display matrix
//! ([`gonio_color::SpectralFilm`], whose weights for uniform wavelengths over 360–830 nm are
//! rescaled by `(1/470 nm) / p(λ)`).
//!
//! With the absolute film ([`crate::settings::Film::Absolute`], the viewing booth's) the weights
//! are instead the XYZ weighting factors of a given light's spectrum S(λ) and observer over 100,
//! and the film records CIE XYZ in cd/m²: a path's value v at λ then stands for the spectral
//! radiance `v S(λ) / (K_m ∫ S ȳ dλ)`, K_m = 683 lm/W (CIE 15:2004 eq. 7.7), so that a grey
//! light of value 1 has a luminance of 1 cd/m².
//!
//! What a path carries at λ with the display film is radiance relative to D65: the film weights contain D65's spectral
//! power, normalised so that the value 1 at every wavelength displays as linear sRGB (1, 1, 1).
//! This is the illuminant under which the tristimulus shortcut reduces spectral tables
//! ([`gonio_brdf::table::BrdfTable::to_rgb`]), so for a path that meets one surface under a white
//! light the two modes agree up to Monte Carlo noise.
//!
//! - Spectral tables (any BRDF with a [`gonio_brdf::SpectralBrdf`] view) are evaluated at
//!   the path's wavelengths, linearly between the table's bands and holding the end bands beyond
//!   them (the convention of the tristimulus band weights, [`gonio_color::SpectralToXyz`]).
//! - Everything given in linear sRGB (light and environment radiances, analytic models, RGB and
//!   monochrome tables) becomes a spectrum by [`RgbUpsampling`]: a fixed linear combination of
//!   three smooth basis spectra whose coefficients are solved so that the spectrum's colour under
//!   D65 is the given linear sRGB (the three-basis method of A. S. Glassner, "How to derive a
//!   spectrum from an RGB triplet", IEEE Computer Graphics and Applications 9(4), 1989). Grey
//!   (r = g = b) becomes exactly a flat spectrum, so a grey scene renders as in the tristimulus
//!   mode; for a light of RGB c the emitted spectral radiance is `s_c(λ) · D65(λ)` on the film's
//!   scale.

use crate::flakes::FlakeField;
use crate::material::Material;
use crate::path::{Shading, Strategy, mix, sample_brdf};
use crate::settings::{BrdfSampling, Film};
use glam::{DMat3, DVec2, DVec3, DVec4};
use gonio_brdf::sampling::{cosine_hemisphere, cosine_hemisphere_pdf};
use gonio_brdf::{Rgb, SpectralBrdf};
use gonio_color::{
    Colorimetry, HERO_COUNT, HeroSampler, Illuminant, Observer, SpectralFilm, Spectrum,
};
use std::sync::LazyLock;

/// The illuminant of the film (and of the tristimulus shortcut's reduction).
pub const ILLUMINANT: Illuminant = Illuminant::D65;
/// The observer of the film.
pub const OBSERVER: Observer = Observer::Cie1931TwoDegree;

/// Where the blue and green basis spectra cross (nm).
const BLUE_GREEN_NM: f64 = 490.0;
/// Where the green and red basis spectra cross (nm).
const GREEN_RED_NM: f64 = 585.0;
/// Width of the logistic edges of the basis spectra (nm).
const EDGE_NM: f64 = 10.0;

/// Linear sRGB → spectrum (Glassner 1989). The basis spectra are a smooth partition of unity:
/// `red(λ) = σ((λ − 585 nm)/10 nm)`, `blue(λ) = 1 − σ((λ − 490 nm)/10 nm)`,
/// `green = 1 − red − blue`, σ the logistic function; all three lie in [0, 1] and sum to 1.
/// With `M` the 3 × 3 matrix whose column c is the linear sRGB of basis c as a reflectance under
/// D65 (CIE 1931 2°, white-balanced, [`Colorimetry::of_reflectance`]), the spectrum of `rgb` is
/// `s(λ) = basis(λ) · M⁻¹ rgb`. It is linear in `rgb`, its colour under D65 is exactly `rgb`, and
/// (1, 1, 1) gives s ≡ 1. Colours more saturated than the basis give negative coefficients and
/// may give negative values at some wavelengths (the film still integrates them to the right
/// colour).
pub struct RgbUpsampling {
    /// `M⁻¹`.
    to_coefficients: DMat3,
}

impl RgbUpsampling {
    /// The upsampling (built once).
    pub fn get() -> &'static RgbUpsampling {
        static UPSAMPLING: LazyLock<RgbUpsampling> = LazyLock::new(|| {
            let grid: Vec<f64> = (360..=830).map(f64::from).collect();
            let columns: [DVec3; 3] = std::array::from_fn(|c| {
                let values = grid.iter().map(|&w| basis(w)[c]).collect();
                let spectrum =
                    Spectrum::new(grid.clone(), values).expect("the 1 nm grid is increasing");
                let rgb = Colorimetry::of_reflectance(&spectrum, ILLUMINANT, OBSERVER).linear_srgb;
                DVec3::new(rgb.r, rgb.g, rgb.b)
            });
            RgbUpsampling {
                to_coefficients: DMat3::from_cols(columns[0], columns[1], columns[2]).inverse(),
            }
        });
        &UPSAMPLING
    }

    /// The weights `w(λ) = M⁻ᵀ basis(λ)`: the spectrum of `rgb` at λ is `rgb · w(λ)`.
    pub fn weights(&self, wavelength_nm: f64) -> DVec3 {
        self.to_coefficients.transpose() * DVec3::from_array(basis(wavelength_nm))
    }

    /// The spectrum of `rgb` at `wavelength_nm`.
    pub fn value(&self, rgb: Rgb, wavelength_nm: f64) -> f64 {
        rgb.dot(self.weights(wavelength_nm))
    }
}

/// The basis spectra [red, green, blue] at `wavelength_nm`.
fn basis(wavelength_nm: f64) -> [f64; 3] {
    let logistic = |edge: f64| 1.0 / (1.0 + (-(wavelength_nm - edge) / EDGE_NM).exp());
    let red = logistic(GREEN_RED_NM);
    let blue = 1.0 - logistic(BLUE_GREEN_NM);
    [red, 1.0 - red - blue, blue]
}

/// The wavelength pdf of pbrt-v4 (`VisibleWavelengthsPDF`), per nm, over 360–830 nm.
pub fn visible_pdf(wavelength_nm: f64) -> f64 {
    if !(360.0..=830.0).contains(&wavelength_nm) {
        return 0.0;
    }
    0.003_939_804_2 / (0.0072 * (wavelength_nm - 538.0)).cosh().powi(2)
}

/// The inverse of the cumulative distribution of [`visible_pdf`] (pbrt-v4
/// `SampleVisibleWavelengths`): `538 − 138.888889 atanh(0.85691062 − 1.82750197 u)` nm.
pub fn sample_visible(u: f64) -> f64 {
    (538.0 - 138.888_889 * (0.856_910_62 - 1.827_501_97 * u).atanh()).clamp(360.0, 830.0)
}

/// The four wavelengths of a path for the uniform number `u`: `P⁻¹((u + j/4) mod 1)`.
pub fn path_wavelengths(u: f64) -> [f64; HERO_COUNT] {
    std::array::from_fn(|j| sample_visible((u + j as f64 / HERO_COUNT as f64).fract()))
}

/// What every pixel of a render shares: the film, and what it records.
pub(crate) struct SpectralFilmSetup {
    /// The film for uniform wavelengths over 360–830 nm, whose weights are rescaled to the
    /// visible pdf.
    film: SpectralFilm,
    /// The uniform density of that film, 1/470 per nm.
    uniform_pdf: f64,
    /// Whether the film records absolute XYZ ([`Film::Absolute`]) rather than linear sRGB.
    absolute: bool,
}

impl SpectralFilmSetup {
    /// The film `film` describes: for [`Film::Display`] D65 and the CIE 1931 2° observer
    /// through the sRGB display matrix; for [`Film::Absolute`] the XYZ weights of its light
    /// and observer divided by 100, so that v ≡ 1 records the light's white with Y = 1 cd/m²
    /// (the weighting factors make the perfect diffuser's Y 100, [`SpectralFilm`]).
    pub(crate) fn new(film: &Film) -> SpectralFilmSetup {
        let sampler = HeroSampler::new(360.0, 830.0).expect("the CIE range is valid");
        let (film, absolute) = match film {
            Film::Display => (SpectralFilm::new(sampler, ILLUMINANT, OBSERVER), false),
            Film::Absolute { light, observer } => {
                (SpectralFilm::of_spectrum(sampler, light, *observer), true)
            }
        };
        SpectralFilmSetup {
            film,
            uniform_pdf: sampler.pdf_per_nm(),
            absolute,
        }
    }

    /// Per wavelength, the film's weights `W(λ_j) / (4 p(λ_j))` of the visible pdf: linear
    /// sRGB, or absolute XYZ.
    fn weights(&self, wavelengths_nm: &[f64; HERO_COUNT]) -> [[f64; 3]; HERO_COUNT] {
        let (mut weights, scale) = if self.absolute {
            (self.film.xyz_weights(wavelengths_nm), 0.01)
        } else {
            (self.film.rgb_weights(wavelengths_nm), 1.0)
        };
        for (w, &l) in weights.iter_mut().zip(wavelengths_nm) {
            let ratio = scale * self.uniform_pdf / visible_pdf(l);
            w.iter_mut().for_each(|c| *c *= ratio);
        }
        weights
    }

    /// The luminance of a value the film recorded: Y of XYZ, or of linear sRGB by its Y row.
    pub(crate) fn luminance(&self, c: Rgb) -> f64 {
        if self.absolute {
            c.y
        } else {
            crate::light::luminance(c.as_vec3().to_array())
        }
    }
}

/// Scrambles the wavelength stream apart from the path's own dimensions.
const WAVELENGTH_STREAM: u32 = 0x6c8e_9cf5;

/// One spectral path: its wavelengths, the upsampling weights at them and the film weights.
pub(crate) struct SpectralPath {
    wavelengths_nm: [f64; HERO_COUNT],
    /// Per wavelength, `w(λ)` of [`RgbUpsampling::weights`].
    upsample: [DVec3; HERO_COUNT],
    /// Per wavelength, the film's weights (linear sRGB, or absolute XYZ).
    film: [[f64; 3]; HERO_COUNT],
}

impl SpectralPath {
    /// The wavelengths of sample `index` of the pixel with scramble seed `seed`: the hero comes
    /// from its own Owen-scrambled Sobol stream (stratified over the pixel's samples), so the
    /// path's other random decisions use the same dimensions as in the tristimulus mode.
    pub(crate) fn new(setup: &SpectralFilmSetup, index: u32, seed: u32) -> SpectralPath {
        let u = f64::from(sobol_burley::sample(
            index,
            0,
            mix(seed ^ WAVELENGTH_STREAM),
        ));
        let wavelengths_nm = path_wavelengths(u);
        let up = RgbUpsampling::get();
        SpectralPath {
            wavelengths_nm,
            upsample: wavelengths_nm.map(|w| up.weights(w)),
            film: setup.weights(&wavelengths_nm),
        }
    }

    /// What the film records of the path (linear sRGB, or absolute XYZ) from its values at the
    /// four wavelengths.
    pub(crate) fn to_film(&self, values: DVec4) -> Rgb {
        self.film
            .iter()
            .zip(values.to_array())
            .map(|(w, v)| Rgb::from_array(*w) * v)
            .sum()
    }
}

impl Shading for SpectralPath {
    type C = DVec4;

    fn carry_rgb(&self, rgb: Rgb) -> DVec4 {
        DVec4::from_array(self.upsample.map(|w| rgb.dot(w)))
    }

    fn carry_bands(&self, flakes: &FlakeField, values: &[f64]) -> DVec4 {
        let bands = flakes.glint().wavelengths_nm();
        DVec4::from_array(
            self.wavelengths_nm
                .map(|w| gonio_brdf::table::band_value(bands, values, w)),
        )
    }

    fn eval(&self, material: &Material, wo: DVec3, wi: DVec3) -> DVec4 {
        match material.brdf.spectral() {
            Some(spectral) => self.eval_spectral(spectral, wo, wi),
            None => self.carry_rgb(material.brdf.eval(wo, wi)),
        }
    }

    fn sample(
        &self,
        material: &Material,
        wo: DVec3,
        u: DVec2,
        strategy: Strategy,
    ) -> Option<(DVec3, DVec4, f64)> {
        let Some(spectral) = material.brdf.spectral() else {
            return sample_brdf(material.brdf.as_ref(), wo, u, strategy)
                .map(|s| (s.wi, self.carry_rgb(s.f), s.pdf));
        };
        // The directions of the tristimulus mode (Brdf::sample), spectral values.
        let (wi, pdf) = match strategy.how {
            BrdfSampling::Importance => {
                spectral.sample_direction(wo, u, strategy.constant_weight)?
            }
            BrdfSampling::Cosine => {
                let wi = cosine_hemisphere(u);
                (wi, cosine_hemisphere_pdf(wi.z))
            }
        };
        (pdf > 0.0).then(|| (wi, self.eval_spectral(spectral, wo, wi), pdf))
    }
}

impl SpectralPath {
    /// A spectral BRDF at the path's four wavelengths.
    fn eval_spectral(&self, spectral: &dyn SpectralBrdf, wo: DVec3, wi: DVec3) -> DVec4 {
        let mut values = [0.0; HERO_COUNT];
        spectral.eval_at(wo, wi, &self.wavelengths_nm, &mut values);
        DVec4::from_array(values)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The upsampled spectrum's colour under D65, integrated independently by the colour crate,
    /// is the input; grey gives a flat spectrum; the basis is a partition of unity.
    #[test]
    fn upsampling_round_trips_and_keeps_grey_flat() {
        let up = RgbUpsampling::get();
        let grid: Vec<f64> = (360..=830).map(f64::from).collect();
        for rgb in [
            Rgb::new(0.8, 0.3, 0.1),
            Rgb::new(0.1, 0.5, 0.9),
            Rgb::new(0.25, 0.6, 0.2),
            Rgb::splat(0.4),
        ] {
            let values = grid.iter().map(|&w| up.value(rgb, w)).collect();
            let s = Spectrum::new(grid.clone(), values).unwrap();
            let back = Colorimetry::of_reflectance(&s, ILLUMINANT, OBSERVER).linear_srgb;
            let err = (DVec3::new(back.r, back.g, back.b) - rgb)
                .abs()
                .max_element();
            assert!(err < 1e-9, "{rgb}: {back:?}");
        }
        for w in [380.0, 452.5, 490.0, 585.0, 700.0, 780.0] {
            assert!((up.value(Rgb::splat(0.7), w) - 0.7).abs() < 1e-9);
            let b = basis(w);
            assert!(b.iter().all(|v| (0.0..=1.0).contains(v)));
            assert!((b.iter().sum::<f64>() - 1.0).abs() < 1e-12);
        }
    }

    /// The pdf integrates to 1 over 360–830 nm (midpoint rule), the sampler inverts its
    /// cumulative distribution (the fraction of stratified samples below λ is ∫ p up to λ), and
    /// the film of a flat spectrum averages to white over stratified paths.
    #[test]
    fn visible_wavelengths_follow_their_pdf_and_the_film_is_unbiased() {
        let n = 47_000;
        let total: f64 = (0..n)
            .map(|i| visible_pdf(360.0 + 470.0 * (i as f64 + 0.5) / n as f64) * 470.0 / n as f64)
            .sum();
        assert!((total - 1.0).abs() < 1e-6, "{total}");
        let paths = 4000;
        let lambdas: Vec<f64> = (0..paths)
            .flat_map(|i| path_wavelengths((i as f64 + 0.5) / paths as f64))
            .collect();
        for edge in [400.0, 480.0, 538.0, 600.0, 700.0] {
            let below = lambdas.iter().filter(|&&l| l < edge).count() as f64;
            let steps = 10_000;
            let cdf: f64 = (0..steps)
                .map(|i| {
                    let l = 360.0 + (edge - 360.0) * (i as f64 + 0.5) / steps as f64;
                    visible_pdf(l) * (edge - 360.0) / steps as f64
                })
                .sum();
            assert!((below / lambdas.len() as f64 - cdf).abs() < 1e-3, "{edge}");
        }
        let setup = SpectralFilmSetup::new(&Film::Display);
        let mut rgb = [0.0; 3];
        for i in 0..paths {
            let ws = path_wavelengths((i as f64 + 0.5) / paths as f64);
            for w in setup.weights(&ws) {
                (0..3).for_each(|c| rgb[c] += w[c] / paths as f64);
            }
        }
        for v in rgb {
            assert!((v - 1.0).abs() < 1e-3, "{rgb:?}");
        }
    }
}
