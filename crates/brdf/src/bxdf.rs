//! The interface every BRDF in gonio implements (analytic models and tables alike), so that the
//! instruments, the fitter and the renderer can use any of them.
//!
//! Directions are unit vectors in the local frame of the surface: +z is the normal, `wi` points
//! toward the light and `wo` toward the viewer (the convention of pbrt-v4, Pharr, Jakob &
//! Humphreys, *Physically Based Rendering*, 4th ed., 2023, and of `docs/brdf-models.md`).
//! Following pbrt-v4, sampling returns the value, the direction and the pdf together.
//!
//! A BRDF is given in colour (linear sRGB, [`Brdf::eval`]); one that also has a spectrum (a
//! spectral table) says so through [`Brdf::spectral`], whose [`SpectralBrdf`] evaluates it at
//! any wavelengths. A spectral renderer asks for that view and turns the colour of every other
//! BRDF into a spectrum itself.

use glam::{DVec2, DVec3};

/// Linear RGB (or any three channels); monochrome BRDFs return the same value in all three.
pub type Rgb = DVec3;

/// A sampled incident direction with the BRDF value and the pdf (per unit solid angle) of
/// having sampled it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BrdfSample {
    /// Sampled direction toward the light, unit length, local frame.
    pub wi: DVec3,
    /// `f(wi, wo)` in 1/sr.
    pub f: Rgb,
    /// Probability density of `wi` per steradian.
    pub pdf: f64,
}

/// A bidirectional reflectance distribution function.
pub trait Brdf: Send + Sync {
    /// `f(wi, wo)` in 1/sr; zero when either direction is below the surface.
    fn eval(&self, wo: DVec3, wi: DVec3) -> Rgb;

    /// Sample an incident direction for the outgoing direction `wo` from two uniform numbers in
    /// [0, 1). `None` when no direction could be sampled (e.g. `wo` below the surface).
    fn sample(&self, wo: DVec3, u: DVec2) -> Option<BrdfSample>;

    /// The pdf (per steradian) with which [`Brdf::sample`] returns `wi` given `wo`.
    fn pdf(&self, wo: DVec3, wi: DVec3) -> f64;

    /// [`Brdf::sample`] with the sampler's constant part (the largest constant under the BRDF,
    /// drawn by the cosine law) chosen `constant_weight` times as readily against the lobes,
    /// `constant_weight` in (0, 1]: the MIS compensation of a renderer whose light samples
    /// already find that part's light ([`crate::table::sampler`], "Compensation"). The
    /// default, for a BRDF whose sampling has no such part, is [`Brdf::sample`].
    fn sample_compensated(&self, wo: DVec3, u: DVec2, constant_weight: f64) -> Option<BrdfSample> {
        let _ = constant_weight;
        self.sample(wo, u)
    }

    /// The pdf with which [`Brdf::sample_compensated`] returns `wi` given `wo`.
    fn pdf_compensated(&self, wo: DVec3, wi: DVec3, constant_weight: f64) -> f64 {
        let _ = constant_weight;
        self.pdf(wo, wi)
    }

    /// The BRDF's spectrum, for one that has one; `None` (the default) for a BRDF given in
    /// colour only.
    fn spectral(&self) -> Option<&dyn SpectralBrdf> {
        None
    }
}

/// A BRDF that has a spectrum: its values at any wavelengths, and its importance sampling
/// without the colour value that [`Brdf::sample`] computes beside the direction.
pub trait SpectralBrdf: Send + Sync {
    /// `f(wi, wo)` in 1/sr at each of `wavelengths_nm`, written into `out` (same length); zero
    /// when either direction is below the surface.
    fn eval_at(&self, wo: DVec3, wi: DVec3, wavelengths_nm: &[f64], out: &mut [f64]);

    /// The direction and pdf of [`Brdf::sample_compensated`] for the same `wo`, `u` and
    /// `constant_weight`, without its value.
    fn sample_direction(&self, wo: DVec3, u: DVec2, constant_weight: f64) -> Option<(DVec3, f64)>;
}
