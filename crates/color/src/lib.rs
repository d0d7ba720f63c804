//! Colour science for gonio: sampled spectra, the CIE standard observers and illuminants,
//! spectrum → CIE XYZ, xyY, CIELAB, sRGB, Bradford chromatic adaptation, CIEDE2000, and the
//! spectral reductions the BRDF tables and the renderer use (precomputed XYZ/RGB weights for a
//! set of wavelength bands; hero-wavelength sampling with film weights).
//!
//! Conventions: wavelengths in nm; XYZ on the 0–100 scale with Y = 100 for the perfect
//! reflecting diffuser; linear and encoded sRGB on [0, 1].
//!
//! ```
//! use gonio_color::{Colorimetry, Illuminant, Observer, Spectrum};
//! let grey = Spectrum::constant(vec![380.0, 780.0], 0.18)?;
//! let c = Colorimetry::of_reflectance(&grey, Illuminant::D65, Observer::Cie1931TwoDegree);
//! assert!((c.xyz.y - 18.0).abs() < 1e-9);
//! assert!((c.lab.l - 49.496).abs() < 1e-3);
//! # Ok::<(), gonio_color::ColorError>(())
//! ```

pub mod adaptation;
pub mod cie;
pub mod ciede2000;
pub mod error;
pub mod hero;
mod mat3;
pub mod reduce;
pub mod spectrum;
pub mod srgb;
pub mod tristimulus;
pub mod xyz;

pub use cie::{ColorMatchingFunctions, Illuminant, Observer};
pub use ciede2000::{ciede2000, ciede2000_weighted};
pub use error::{ColorError, Result};
pub use hero::{HERO_COUNT, HeroSampler, SpectralFilm};
pub use mat3::Mat3;
pub use reduce::SpectralToXyz;
pub use spectrum::Spectrum;
pub use srgb::{LinearSrgb, Srgb};
pub use tristimulus::{
    Colorimetry, EmissionScale, WeightingFactors, display_matrix, display_matrix_for_white,
    emission_xyz, reflectance_xyz, white,
};
pub use xyz::{Lab, XyY, Xyz, lightness_slope};
