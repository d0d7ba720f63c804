//! The Lambertian (ideal diffuse) BRDF `f = ρ/π`, sampled by the cosine law.

use crate::bxdf::{Brdf, BrdfSample, Rgb};
use crate::sampling::{cosine_hemisphere, cosine_hemisphere_pdf};
use glam::{DVec2, DVec3};
use std::f64::consts::FRAC_1_PI;

/// A Lambertian reflector of albedo `albedo` (per channel, in [0, 1] for a passive surface):
/// `f = albedo / π` in 1/sr (J. H. Lambert, *Photometria*, 1760).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lambert {
    /// Directional-hemispherical reflectance, the same at every incidence.
    pub albedo: Rgb,
}

impl Lambert {
    /// The albedo averaged over the channels: the exact energy of this lobe.
    pub fn energy(&self) -> f64 {
        self.albedo.element_sum() / 3.0
    }
}

impl Brdf for Lambert {
    fn eval(&self, wo: DVec3, wi: DVec3) -> Rgb {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return Rgb::ZERO;
        }
        self.albedo * FRAC_1_PI
    }

    fn sample(&self, wo: DVec3, u: DVec2) -> Option<BrdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let wi = cosine_hemisphere(u);
        if wi.z <= 0.0 {
            return None;
        }
        Some(BrdfSample {
            wi,
            f: self.albedo * FRAC_1_PI,
            pdf: cosine_hemisphere_pdf(wi.z),
        })
    }

    fn pdf(&self, wo: DVec3, wi: DVec3) -> f64 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        cosine_hemisphere_pdf(wi.z)
    }
}
