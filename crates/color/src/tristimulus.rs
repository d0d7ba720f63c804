//! Spectrum → CIE XYZ: the colour of a reflecting surface under an illuminant, or of a light
//! source itself; and the display transform from such XYZ to sRGB.
//!
//! Method: CIE 15:2004, section 7.1 (eqs. 7.1–7.2), summed at the 1 nm spacing of the embedded
//! tables over 360–830 nm. The sample's spectrum is interpolated linearly to the table's
//! wavelengths and held constant beyond its ends (CIE 15:2004, 7.2.2.1).

use crate::adaptation::bradford_matrix;
use crate::cie::{Illuminant, Observer};
use crate::mat3::{self, Mat3};
use crate::spectrum::Spectrum;
use crate::srgb::{LinearSrgb, Srgb, srgb_white, xyz_to_linear_srgb_matrix};
use crate::xyz::{Lab, XyY, Xyz};
use std::sync::LazyLock;

/// The maximum luminous efficacy of photopic vision, K_m = 683 lm/W (CIE 15:2004, eq. 7.7; the SI
/// definition of the candela fixes 683 lm/W at 540 THz).
pub const K_M_LM_PER_W: f64 = 683.0;

/// The weighting factors of an illuminant and observer at 1 nm: `W_k = 100 S(λ_k) (x̄, ȳ, z̄)(λ_k)
/// / Σ S ȳ`, so that the XYZ of a reflectance ρ is `Σ_k W_k ρ(λ_k)` and the perfect reflecting
/// diffuser has Y = 100 exactly (CIE 15:2004 eq. 7.1 with k = 100 / Σ S ȳ Δλ).
#[derive(Debug)]
pub struct WeightingFactors {
    wavelengths_nm: Vec<f64>,
    weights: Vec<[f64; 3]>,
}

impl WeightingFactors {
    fn compute(illuminant: Illuminant, observer: Observer) -> Self {
        Self::of_spectrum(illuminant.spd(), observer)
    }

    /// The weighting factors of a light of relative spectral power `spd` (a CIE illuminant's
    /// table or a measured source, interpolated linearly to the 1 nm grid and held at its end
    /// values beyond its range) seen by `observer`.
    pub fn of_spectrum(spd: &Spectrum, observer: Observer) -> Self {
        let cmfs = observer.cmfs();
        let wavelengths_nm = cmfs.wavelengths_nm().to_vec();
        let raw: Vec<[f64; 3]> = wavelengths_nm
            .iter()
            .map(|&w| cmfs.at(w).map(|c| c * spd.value_at(w)))
            .collect();
        let k = 100.0 / raw.iter().map(|w| w[1]).sum::<f64>();
        let weights = raw.into_iter().map(|w| w.map(|c| c * k)).collect();
        Self {
            wavelengths_nm,
            weights,
        }
    }

    /// The weighting factors of `illuminant` and `observer` (computed once, then shared).
    pub fn of(illuminant: Illuminant, observer: Observer) -> &'static WeightingFactors {
        static TABLES: [LazyLock<WeightingFactors>; 4] = [
            LazyLock::new(|| {
                WeightingFactors::compute(Illuminant::D65, Observer::Cie1931TwoDegree)
            }),
            LazyLock::new(|| {
                WeightingFactors::compute(Illuminant::D65, Observer::Cie1964TenDegree)
            }),
            LazyLock::new(|| WeightingFactors::compute(Illuminant::A, Observer::Cie1931TwoDegree)),
            LazyLock::new(|| WeightingFactors::compute(Illuminant::A, Observer::Cie1964TenDegree)),
        ];
        let index = match (illuminant, observer) {
            (Illuminant::D65, Observer::Cie1931TwoDegree) => 0,
            (Illuminant::D65, Observer::Cie1964TenDegree) => 1,
            (Illuminant::A, Observer::Cie1931TwoDegree) => 2,
            (Illuminant::A, Observer::Cie1964TenDegree) => 3,
        };
        &TABLES[index]
    }

    /// The wavelengths of the factors (nm): 360–830 at 1 nm.
    pub fn wavelengths_nm(&self) -> &[f64] {
        &self.wavelengths_nm
    }

    /// The factors [W_X, W_Y, W_Z] at each wavelength.
    pub fn weights(&self) -> &[[f64; 3]] {
        &self.weights
    }

    /// Their sums: the XYZ of the perfect reflecting diffuser, Y = 100.
    pub fn white(&self) -> Xyz {
        Xyz::from_array(std::array::from_fn(|c| {
            self.weights.iter().map(|w| w[c]).sum()
        }))
    }
}

/// XYZ (0–100 scale) of a surface of spectral reflectance (or transmittance, or reflectance
/// factor) `reflectance` lit by `illuminant`: the perfect reflecting diffuser (ρ = 1) has Y = 100.
pub fn reflectance_xyz(reflectance: &Spectrum, illuminant: Illuminant, observer: Observer) -> Xyz {
    let table = WeightingFactors::of(illuminant, observer);
    let mut xyz = [0.0; 3];
    for (&w, weight) in table.wavelengths_nm.iter().zip(&table.weights) {
        let rho = reflectance.value_at(w);
        for c in 0..3 {
            xyz[c] += weight[c] * rho;
        }
    }
    Xyz::from_array(xyz)
}

/// The reference white: XYZ of the perfect reflecting diffuser under `illuminant`, Y = 100.
pub fn white(illuminant: Illuminant, observer: Observer) -> Xyz {
    WeightingFactors::of(illuminant, observer).white()
}

/// How to scale the XYZ of a light source.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EmissionScale {
    /// `X = K_m Σ L(λ) x̄(λ) Δλ` with K_m = 683 lm/W: for a spectral radiance in
    /// W sr⁻¹ m⁻² nm⁻¹, Y is the luminance in cd/m² (CIE 15:2004, eq. 7.7).
    Absolute,
    /// Scaled so that the source itself has Y = 100.
    Relative,
}

/// XYZ of a light source of spectral power (radiance) `emission`. Outside its sampled range the
/// source is taken to emit nothing (unlike a reflectance, which is held at its end values).
pub fn emission_xyz(emission: &Spectrum, observer: Observer, scale: EmissionScale) -> Xyz {
    let cmfs = observer.cmfs();
    let (lo, hi) = emission.range_nm();
    let mut xyz = [0.0; 3];
    // The tables are at 1 nm, so the sum is the integral with Δλ = 1 nm.
    for &w in cmfs
        .wavelengths_nm()
        .iter()
        .filter(|&&w| w >= lo && w <= hi)
    {
        let power = emission.value_at(w);
        let cmf = cmfs.at(w);
        for c in 0..3 {
            xyz[c] += cmf[c] * power;
        }
    }
    let factor = match scale {
        EmissionScale::Absolute => K_M_LM_PER_W,
        EmissionScale::Relative if xyz[1] != 0.0 => 100.0 / xyz[1],
        EmissionScale::Relative => 0.0,
    };
    Xyz::from_array(xyz.map(|v| v * factor))
}

/// The matrix from XYZ (0–100 scale) seen under `illuminant` to linear sRGB in [0, 1]: a
/// Bradford adaptation from the illuminant's white (for this observer) to the sRGB white, then the
/// sRGB matrix, so that the perfect reflecting diffuser displays as (1, 1, 1) exactly. Under A
/// this is a real chromatic adaptation; under D65 it only reconciles the white computed from the
/// tables with sRGB's rounded x, y = 0.3127, 0.3290 (a correction of 3e-4 for the 2° observer,
/// 2% in blue for the 10° observer, whose D65 white has another chromaticity).
pub fn display_matrix(illuminant: Illuminant, observer: Observer) -> Mat3 {
    display_matrix_for_white(white(illuminant, observer))
}

/// [`display_matrix`] for a light whose white (the perfect diffuser's XYZ, 0–100 scale) is
/// `white`: a measured source's.
pub fn display_matrix_for_white(white: Xyz) -> Mat3 {
    let to_rgb = xyz_to_linear_srgb_matrix().map(|row| row.map(|v| v / 100.0));
    mat3::mul(&to_rgb, &bradford_matrix(white, srgb_white()))
}

/// Everything `gonio color xyz` reports about one reflectance spectrum.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Colorimetry {
    /// The illuminant.
    pub illuminant: Illuminant,
    /// The observer.
    pub observer: Observer,
    /// XYZ under the illuminant, 0–100 scale.
    pub xyz: Xyz,
    /// Chromaticity and Y; `None` for black.
    pub xyy: Option<XyY>,
    /// The reference white (perfect reflecting diffuser under the illuminant).
    pub white: Xyz,
    /// CIELAB relative to `white`.
    pub lab: Lab,
    /// Linear sRGB through [`display_matrix`] (white-balanced to the illuminant's white); may lie
    /// outside [0, 1] for colours outside the sRGB gamut.
    pub linear_srgb: LinearSrgb,
    /// Encoded sRGB of the linear values clipped to [0, 1].
    pub srgb: Srgb,
}

impl Colorimetry {
    /// The colorimetry of a surface of spectral reflectance `reflectance`.
    pub fn of_reflectance(
        reflectance: &Spectrum,
        illuminant: Illuminant,
        observer: Observer,
    ) -> Self {
        Colorimetry::of_xyz(
            reflectance_xyz(reflectance, illuminant, observer),
            illuminant,
            observer,
        )
    }

    /// The colorimetry of the tristimulus values `xyz` (0–100 scale) under `illuminant` for
    /// `observer`: a colour known by its XYZ or, through [`Lab::to_xyz`], its CIELAB (a
    /// multi-angle reading, a target).
    pub fn of_xyz(xyz: Xyz, illuminant: Illuminant, observer: Observer) -> Self {
        let white = white(illuminant, observer);
        let [r, g, b] = mat3::mul_vec(&display_matrix(illuminant, observer), xyz.to_array());
        let linear_srgb = LinearSrgb { r, g, b };
        Colorimetry {
            illuminant,
            observer,
            xyz,
            xyy: xyz.to_xyy(),
            white,
            lab: xyz.to_lab(white),
            linear_srgb,
            srgb: linear_srgb.encode(),
        }
    }
}
