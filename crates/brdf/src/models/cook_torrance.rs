//! The Cook-Torrance microfacet BRDF with a Beckmann or GGX distribution, height-correlated
//! Smith masking-shadowing and Fresnel reflectance of a real or complex index.
//!
//! R. Cook & K. Torrance, "A reflectance model for computer graphics", ACM TOG 1(1), 1982, in
//! the form of B. Walter et al., "Microfacet models for refraction through rough surfaces",
//! EGSR 2007, eq. 20: `f = F(wi·h) D(h) G2(wi, wo) / (4 cos θi cos θo)`, times an optional
//! per-channel tint. `D`, `G2` from [`crate::microfacet`], `F` from [`crate::fresnel`]. This
//! is the facet model, which the ray method reproduces on Gaussian slopes (`docs/ray-method.md`),
//! with masking. Sampled through the visible normals of `wo`: pdf
//! `D_wo(h) / (4 wo·h) = G1(wo) D(h) / (4 cos θo)` (Heitz & d'Eon 2014).

use crate::bxdf::{Brdf, BrdfSample, Rgb};
use crate::fresnel::Ior;
use crate::microfacet::Microfacet;
use crate::models::{half_vector, incident_from_half, pdf_through_half};
use glam::{DVec2, DVec3};

/// A Cook-Torrance specular lobe.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CookTorrance {
    /// Distribution of facet normals and its roughness.
    pub microfacet: Microfacet,
    /// Index of the material below the surface (air above).
    pub ior: Ior,
    /// Per-channel factor on the Fresnel reflectance (1 for a plain dielectric; a colour for
    /// metals described by one index).
    pub tint: Rgb,
}

impl CookTorrance {
    /// Approximate albedo: the tint times the Fresnel reflectance at the angle of `wo`.
    pub fn energy(&self, wo: DVec3) -> f64 {
        self.tint.element_sum() / 3.0 * self.ior.reflectance(wo.z.clamp(0.0, 1.0))
    }
}

impl CookTorrance {
    /// The value and the sampling pdf for `wo`, `wi` (both above the surface) and their half
    /// vector `h`, sharing `D(h)` and `Λ(wo)`: `pdf = D / (4 cos θo (1 + Λ(wo)))`, which is
    /// [`Microfacet::pdf_visible`]` / (4 wo·h)` simplified.
    fn eval_pdf(&self, wo: DVec3, wi: DVec3, h: DVec3) -> (Rgb, f64) {
        let mf = &self.microfacet;
        let (d, lambda_o, lambda_i) = (mf.d(h), mf.lambda(wo), mf.lambda(wi));
        let f =
            self.ior.reflectance(wi.dot(h)) * d / (4.0 * wi.z * wo.z * (1.0 + lambda_o + lambda_i));
        (self.tint * f, d / (4.0 * wo.z * (1.0 + lambda_o)))
    }
}

impl Brdf for CookTorrance {
    fn eval(&self, wo: DVec3, wi: DVec3) -> Rgb {
        match half_vector(wo, wi) {
            Some(h) => self.eval_pdf(wo, wi, h).0,
            None => Rgb::ZERO,
        }
    }

    fn sample(&self, wo: DVec3, u: DVec2) -> Option<BrdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let h = self.microfacet.sample_visible(wo, u);
        let wi = incident_from_half(wo, h)?;
        let (f, pdf) = self.eval_pdf(wo, wi, h);
        Some(BrdfSample { wi, f, pdf })
    }

    fn pdf(&self, wo: DVec3, wi: DVec3) -> f64 {
        pdf_through_half(wo, wi, |h| self.microfacet.pdf_visible(wo, h))
    }
}
