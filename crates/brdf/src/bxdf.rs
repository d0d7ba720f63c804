//! The interface every BRDF in gonio implements (analytic models and tables alike), so that the
//! instruments, the fitter and the renderer can use any of them.
//!
//! Directions are unit vectors in the local frame of the surface: +z is the normal, `wi` points
//! toward the light and `wo` toward the viewer (the convention of pbrt-v4, Pharr, Jakob &
//! Humphreys, *Physically Based Rendering*, 4th ed., 2023, and of `docs/brdf-models.md`).
//! Following pbrt-v4, sampling returns the value, the direction and the pdf together.

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
}
