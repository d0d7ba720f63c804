//! The default orange peel: what `gonio surface gen` synthesises from a power law when given no
//! spectrum of its own, and what the demo's texture section shows. `C(q) ∝ q^-4` (equal mean
//! square slope in every octave) between 0.3 mm and 10 mm, rms slope along x 1 mrad
//! (docs/surface.md, "Synthesis", gives the sources of the scales).

/// The exponent of the power spectral density, `C(q) ∝ q^-DEFAULT_EXPONENT`.
pub const DEFAULT_EXPONENT: f64 = 4.0;
/// The longest wavelength of the spectrum, mm.
pub const DEFAULT_LONG_MM: f64 = 10.0;
/// The shortest wavelength of the spectrum, mm.
pub const DEFAULT_SHORT_MM: f64 = 0.3;
/// The rms slope along x, mrad: a good automotive finish.
pub const DEFAULT_SLOPE_MRAD: f64 = 1.0;
