//! The choices of a render, in a leaf module that the integrator, the path tracer, the
//! spectral mode and the denoiser all read: how BRDF samples are drawn, how colour is carried,
//! and the settings of one render with every choice made.

/// How BRDF samples are drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum BrdfSampling {
    /// Each material's own importance sampler (analytic lobes, alias method for tables).
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

/// The settings of one render, every choice made.
pub(crate) struct Settings {
    pub spp: u32,
    pub seed: u32,
    pub max_bounces: u32,
    pub sampling: BrdfSampling,
    pub colour: ColourMode,
}
