//! Energy-normalised Phong and Blinn-Phong lobes.
//!
//! - Phong (E. Lafortune & Y. Willems, "Using the modified Phong reflectance model for
//!   physically based rendering", KU Leuven CW 197, 1994, eq. 5):
//!   `f = ρs (n + 2)/(2π) cos^n α`, α the angle between `wi` and the mirror direction of `wo`;
//!   its albedo is `ρs` at normal incidence and less elsewhere. Sampled about the mirror
//!   direction with pdf `(n + 1)/(2π) cos^n α`.
//! - Blinn-Phong (J. Blinn, "Models of light reflection for computer synthesized pictures",
//!   SIGGRAPH 1977): `f = ρs c_n cos^n θh` with the exact normalisation
//!   `c_n = (n + 2)(n + 4) / (8π (2^(-n/2) + n))` that makes the albedo `ρs` at normal incidence
//!   (F. Giesen, "Phong/Blinn-Phong normalization zoo", 2009; derived in `docs/brdf-models.md`).
//!   Sampled through the half vector with pdf `(n + 1)/(2π) cos^n θh / (4 wo·h)`.

use crate::bxdf::{Brdf, BrdfSample, Rgb};
use crate::models::{half_vector, pdf_through_half, sample_through_half};
use crate::sampling::{Frame, power_cosine, power_cosine_pdf};
use glam::{DVec2, DVec3};
use std::f64::consts::PI;

/// The mirror direction of `wo` about the macroscopic normal.
fn mirror(wo: DVec3) -> DVec3 {
    DVec3::new(-wo.x, -wo.y, wo.z)
}

/// Lafortune & Willems' normalised Phong lobe.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Phong {
    /// Specular albedo at normal incidence `ρs` (per channel).
    pub specular: Rgb,
    /// Phong exponent `n` (dimensionless, ≥ 0; larger is sharper: the lobe's half width at
    /// half maximum is about `√(2 ln 2 / n)` rad).
    pub exponent: f64,
}

impl Phong {
    /// `ρs` averaged over the channels: the albedo at normal incidence.
    pub fn energy(&self) -> f64 {
        self.specular.element_sum() / 3.0
    }
}

impl Brdf for Phong {
    fn eval(&self, wo: DVec3, wi: DVec3) -> Rgb {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return Rgb::ZERO;
        }
        let c = wi.dot(mirror(wo));
        if c <= 0.0 {
            return Rgb::ZERO;
        }
        self.specular * ((self.exponent + 2.0) / (2.0 * PI) * c.powf(self.exponent))
    }

    fn sample(&self, wo: DVec3, u: DVec2) -> Option<BrdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let wi = Frame::from_z(mirror(wo)).to_world(power_cosine(u, self.exponent));
        if wi.z <= 0.0 {
            return None;
        }
        Some(BrdfSample {
            wi,
            f: self.eval(wo, wi),
            pdf: self.pdf(wo, wi),
        })
    }

    fn pdf(&self, wo: DVec3, wi: DVec3) -> f64 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        power_cosine_pdf(wi.dot(mirror(wo)), self.exponent)
    }
}

/// The exactly normalised Blinn-Phong lobe.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BlinnPhong {
    /// Specular albedo at normal incidence `ρs` (per channel).
    pub specular: Rgb,
    /// Exponent `n` on `cos θh` (dimensionless, ≥ 0; about four times the Phong exponent of
    /// the same lobe width).
    pub exponent: f64,
}

impl BlinnPhong {
    /// `ρs` averaged over the channels: the albedo at normal incidence.
    pub fn energy(&self) -> f64 {
        self.specular.element_sum() / 3.0
    }

    /// `c_n = (n + 2)(n + 4) / (8π (2^(-n/2) + n))`.
    fn normalisation(&self) -> f64 {
        let n = self.exponent;
        (n + 2.0) * (n + 4.0) / (8.0 * PI * ((-0.5 * n).exp2() + n))
    }
}

impl Brdf for BlinnPhong {
    fn eval(&self, wo: DVec3, wi: DVec3) -> Rgb {
        match half_vector(wo, wi) {
            Some(h) => self.specular * (self.normalisation() * h.z.powf(self.exponent)),
            None => Rgb::ZERO,
        }
    }

    fn sample(&self, wo: DVec3, u: DVec2) -> Option<BrdfSample> {
        sample_through_half(self, wo, power_cosine(u, self.exponent))
    }

    fn pdf(&self, wo: DVec3, wi: DVec3) -> f64 {
        pdf_through_half(wo, wi, |h| power_cosine_pdf(h.z, self.exponent))
    }
}
