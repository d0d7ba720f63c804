//! The choices of a render, in a leaf module that the integrator, the path tracer, the
//! spectral mode and the denoiser all read: how BRDF samples are drawn, how colour is carried,
//! what the film records, and the settings of one render with every choice made.

use gonio_color::{Observer, Spectrum};
use std::sync::Arc;

/// How BRDF samples are drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum BrdfSampling {
    /// Each material's own importance sampler (analytic lobes; tables through the visible
    /// normals of a fitted GGX, `gonio_brdf::table::sampler`).
    #[default]
    Importance,
    /// Cosine-weighted directions for every material (for comparison with importance sampling).
    Cosine,
}

/// How colour is carried along a path.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ColourMode {
    /// The tristimulus shortcut: every BRDF and light in linear sRGB (spectral tables reduced
    /// under D65 by their band weights), multiplied channel by channel along the path.
    #[default]
    Tristimulus,
    /// Hero-wavelength spectral rendering (Wilkie et al. 2014): four wavelengths per path,
    /// spectral tables evaluated at them, RGB materials and lights turned into spectra, and the
    /// spectral values turned into colour at the film (D65, CIE 1931 2°). See
    /// [`crate::spectral`].
    Spectral,
}

/// What the film records of the spectral mode ([`crate::spectral`]; [`crate::render_estimate_on`]).
#[derive(Debug, Clone, PartialEq, Default)]
pub enum Film {
    /// Linear sRGB, radiance relative to D65 seen by the CIE 1931 2° observer: a grey light of
    /// value 1 on a perfect white diffuser displays as (1, 1, 1).
    #[default]
    Display,
    /// Absolute CIE XYZ in cd/m² (Y is the luminance) under a light of relative spectral power
    /// `light` seen by `observer`: a grey light of value v emits the spectral radiance
    /// `v S(λ) / (K_m ∫ S ȳ dλ)` (K_m = 683 lm/W), whose luminance is v cd/m², so a sky of value
    /// v gives an illuminance of π v lx on a plane and a distant light of irradiance value E
    /// gives E lx on a plane facing it. Needs [`ColourMode::Spectral`].
    Absolute {
        /// The light's relative spectral power (a CIE illuminant's table or a measured source).
        light: Arc<Spectrum>,
        /// The observer whose colour-matching functions give X, Y, Z.
        observer: Observer,
    },
}

/// The settings of one render, every choice made.
pub(crate) struct Settings {
    pub spp: u32,
    pub seed: u32,
    pub max_bounces: u32,
    pub sampling: BrdfSampling,
    pub colour: ColourMode,
}
