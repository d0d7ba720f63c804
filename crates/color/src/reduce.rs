//! Reduction of spectral tables to colour in one dot product per entry: precomputed weights that
//! turn the values of a spectrum sampled at fixed bands (e.g. the 400, 410, ..., 700 nm of the
//! Cornell BRDF files) into XYZ and linear sRGB, under a chosen illuminant and observer.
//!
//! The weights are exactly those of [`reflectance_xyz`](crate::reflectance_xyz) applied to the
//! band values: the spectrum between bands is linear and held beyond the first and last band, so
//! band j receives `Σ_k W_k h_j(λ_k)` where `W_k` are the 1 nm weighting factors and `h_j` the
//! linear-interpolation ("hat") function of band j — the construction of the ASTM E308-18
//! tristimulus weighting factors (section 7.3), with linear in place of Lagrange interpolation.

use crate::cie::{Illuminant, Observer};
use crate::error::{ColorError, Result};
use crate::mat3;
use crate::spectrum::Spectrum;
use crate::srgb::LinearSrgb;
use crate::tristimulus::{WeightingFactors, display_matrix};
use crate::xyz::Xyz;

/// Precomputed weights from spectral band values to XYZ (0–100 scale) and linear sRGB ([0, 1]
/// scale: a band value of 1 everywhere gives the illuminant's white, about (1, 1, 1)).
///
/// The input may be a reflectance, a reflectance factor or a BRDF in 1/sr: the output is in the
/// same units (for a BRDF, Y / 100 and the sRGB components are luminance- and colour-weighted
/// BRDFs in 1/sr).
#[derive(Clone, Debug)]
pub struct SpectralToXyz {
    wavelengths_nm: Vec<f64>,
    illuminant: Illuminant,
    observer: Observer,
    xyz_weights: Vec<[f64; 3]>,
    rgb_weights: Vec<[f64; 3]>,
}

impl SpectralToXyz {
    /// The weights for spectra sampled at `wavelengths_nm` (increasing, at least two bands), seen
    /// under `illuminant` by `observer`. Linear sRGB goes through [`display_matrix`] (Bradford
    /// white balance to the sRGB white).
    pub fn new(wavelengths_nm: &[f64], illuminant: Illuminant, observer: Observer) -> Result<Self> {
        let bands = Spectrum::constant(wavelengths_nm.to_vec(), 0.0)?;
        let factors = WeightingFactors::of(illuminant, observer);
        let mut xyz_weights = vec![[0.0; 3]; bands.len()];
        for (&w, factor) in factors.wavelengths_nm().iter().zip(factors.weights()) {
            let (i, t) = bands.segment(w);
            for c in 0..3 {
                xyz_weights[i][c] += (1.0 - t) * factor[c];
                xyz_weights[i + 1][c] += t * factor[c];
            }
        }
        let to_rgb = display_matrix(illuminant, observer);
        let rgb_weights = xyz_weights
            .iter()
            .map(|&w| mat3::mul_vec(&to_rgb, w))
            .collect();
        Ok(Self {
            wavelengths_nm: wavelengths_nm.to_vec(),
            illuminant,
            observer,
            xyz_weights,
            rgb_weights,
        })
    }

    /// The band wavelengths (nm).
    pub fn wavelengths_nm(&self) -> &[f64] {
        &self.wavelengths_nm
    }

    /// The illuminant.
    pub fn illuminant(&self) -> Illuminant {
        self.illuminant
    }

    /// The observer.
    pub fn observer(&self) -> Observer {
        self.observer
    }

    /// Number of bands.
    pub fn bands(&self) -> usize {
        self.wavelengths_nm.len()
    }

    /// `[W_X, W_Y, W_Z]` of each band: `X = Σ_j W_X[j] v[j]`.
    pub fn xyz_weights(&self) -> &[[f64; 3]] {
        &self.xyz_weights
    }

    /// [W_R, W_G, W_B] of each band for linear sRGB.
    pub fn rgb_weights(&self) -> &[[f64; 3]] {
        &self.rgb_weights
    }

    /// XYZ of one spectrum given by its band values.
    pub fn xyz(&self, values: &[f64]) -> Result<Xyz> {
        self.check_len(values.len())?;
        Ok(Xyz::from_array(dot(&self.xyz_weights, values)))
    }

    /// Linear sRGB of one spectrum given by its band values.
    pub fn linear_srgb(&self, values: &[f64]) -> Result<LinearSrgb> {
        self.check_len(values.len())?;
        let [r, g, b] = dot(&self.rgb_weights, values);
        Ok(LinearSrgb { r, g, b })
    }

    /// XYZ of each row of a row-major table with one column per band.
    pub fn xyz_table(&self, table: &[f64]) -> Result<Vec<Xyz>> {
        self.reduce_table(table, &self.xyz_weights, Xyz::from_array)
    }

    /// Linear sRGB of each row of a row-major table with one column per band.
    pub fn linear_srgb_table(&self, table: &[f64]) -> Result<Vec<LinearSrgb>> {
        self.reduce_table(table, &self.rgb_weights, |[r, g, b]| LinearSrgb { r, g, b })
    }

    fn reduce_table<T>(
        &self,
        table: &[f64],
        weights: &[[f64; 3]],
        wrap: impl Fn([f64; 3]) -> T,
    ) -> Result<Vec<T>> {
        if !table.len().is_multiple_of(self.bands()) {
            return Err(self.shape_error(format!("{} values do not divide into rows", table.len())));
        }
        Ok(table
            .chunks_exact(self.bands())
            .map(|row| wrap(dot(weights, row)))
            .collect())
    }

    fn check_len(&self, len: usize) -> Result<()> {
        if len == self.bands() {
            return Ok(());
        }
        Err(self.shape_error(format!("{len} values given")))
    }

    fn shape_error(&self, problem: String) -> ColorError {
        ColorError::TableShape(format!(
            "{problem}; the weights are for {} bands ({}–{} nm)",
            self.bands(),
            self.wavelengths_nm[0],
            self.wavelengths_nm[self.bands() - 1]
        ))
    }
}

fn dot(weights: &[[f64; 3]], values: &[f64]) -> [f64; 3] {
    let mut sum = [0.0; 3];
    for (w, &v) in weights.iter().zip(values) {
        for c in 0..3 {
            sum[c] += w[c] * v;
        }
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tristimulus::{Colorimetry, reflectance_xyz, white};

    fn cornell_bands() -> Vec<f64> {
        (0..31).map(|i| 400.0 + 10.0 * i as f64).collect()
    }

    /// A smooth, non-trivial test spectrum at the bands.
    fn paint(bands: &[f64]) -> Vec<f64> {
        bands
            .iter()
            .map(|w| 0.3 + 0.25 * ((w - 400.0) / 45.0).sin() + 1e-4 * (w - 550.0))
            .collect()
    }

    #[test]
    fn flat_spectrum_gives_the_illuminant_white() {
        for illuminant in Illuminant::ALL {
            for observer in Observer::ALL {
                let reduce = SpectralToXyz::new(&cornell_bands(), illuminant, observer).unwrap();
                let xyz = reduce.xyz(&[1.0; 31]).unwrap();
                let w = white(illuminant, observer);
                for (a, b) in xyz.to_array().iter().zip(w.to_array()) {
                    assert!((a - b).abs() < 1e-10, "{illuminant} {observer}");
                }
            }
        }
    }

    /// The weights reproduce the direct 1 nm integration of the interpolated spectrum (a
    /// different code path: interpolation of the values instead of distribution of the weights),
    /// for XYZ and for linear sRGB, on a uniform and on an irregular band set.
    #[test]
    fn weights_agree_with_direct_integration() {
        let irregular = vec![
            380.0, 420.0, 455.0, 500.0, 560.0, 575.0, 610.0, 700.0, 760.0,
        ];
        for bands in [cornell_bands(), irregular] {
            let values = paint(&bands);
            let spectrum = Spectrum::new(bands.clone(), values.clone()).unwrap();
            for illuminant in Illuminant::ALL {
                for observer in Observer::ALL {
                    let reduce = SpectralToXyz::new(&bands, illuminant, observer).unwrap();
                    let fast = reduce.xyz(&values).unwrap().to_array();
                    let direct = reflectance_xyz(&spectrum, illuminant, observer).to_array();
                    for c in 0..3 {
                        assert!(
                            (fast[c] - direct[c]).abs() < 1e-10,
                            "{fast:?} vs {direct:?}"
                        );
                    }
                    let rgb = reduce.linear_srgb(&values).unwrap();
                    let expected = Colorimetry::of_reflectance(&spectrum, illuminant, observer);
                    let e = expected.linear_srgb;
                    let err = (rgb.r - e.r).abs() + (rgb.g - e.g).abs() + (rgb.b - e.b).abs();
                    assert!(err < 1e-12);
                }
            }
        }
    }

    #[test]
    fn tables_reduce_row_by_row_and_reject_bad_shapes() {
        let bands = cornell_bands();
        let reduce =
            SpectralToXyz::new(&bands, Illuminant::D65, Observer::Cie1931TwoDegree).unwrap();
        let row = paint(&bands);
        let table: Vec<f64> = (0..5)
            .flat_map(|k| row.iter().map(move |v| v * k as f64))
            .collect();
        let xyz = reduce.xyz_table(&table).unwrap();
        let rgb = reduce.linear_srgb_table(&table).unwrap();
        let one = reduce.xyz(&row).unwrap();
        for (k, (x, c)) in xyz.iter().zip(&rgb).enumerate() {
            assert!((x.y - k as f64 * one.y).abs() < 1e-10);
            let expected = mat3::mul_vec(
                &display_matrix(Illuminant::D65, Observer::Cie1931TwoDegree),
                x.to_array(),
            );
            assert!((c.g - expected[1]).abs() < 1e-12);
        }
        assert!(reduce.xyz(&row[..30]).is_err());
        assert!(reduce.xyz_table(&table[..40]).is_err());
        assert!(SpectralToXyz::new(&[500.0], Illuminant::A, Observer::Cie1931TwoDegree).is_err());
    }
}
