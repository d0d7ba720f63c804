//! Sampling building blocks shared by the analytic models, the tabulated BRDFs and the
//! renderer: cosine and power-cosine hemispheres, mirror reflection, an orthonormal frame about
//! any axis; in [`discrete`] the piecewise-constant distributions (the
//! table sampler, the environment light), in [`bilinear`] the piecewise-bilinear 2D warp of
//! Mitsuba's measured-BRDF files (the Mitsuba tensor export and reader).
//!
//! Each warp comes with its pdf per steradian so that the two cannot drift apart (pbrt-v4,
//! §A.5 "Sampling multidimensional functions").

pub mod bilinear;
pub mod discrete;

pub use bilinear::Marginal2D;
pub use discrete::{PiecewiseConstant1D, PiecewiseConstant2D};

use glam::{DVec2, DVec3};
use std::f64::consts::{FRAC_1_PI, FRAC_PI_2, FRAC_PI_4, PI};

/// Map `u` in [0, 1)² to the unit disk, preserving relative areas (Shirley & Chiu, "A
/// low-distortion map between disk and square", JGT 2(3), 1997; pbrt-v4 §A.5.1).
pub fn concentric_disk(u: DVec2) -> DVec2 {
    let o = 2.0 * u - DVec2::ONE;
    if o.x == 0.0 && o.y == 0.0 {
        return DVec2::ZERO;
    }
    let (r, theta) = if o.x.abs() > o.y.abs() {
        (o.x, FRAC_PI_4 * (o.y / o.x))
    } else {
        (o.y, FRAC_PI_2 - FRAC_PI_4 * (o.x / o.y))
    };
    let (sin, cos) = theta.sin_cos();
    r * DVec2::new(cos, sin)
}

/// The inverse of [`concentric_disk`]: the point of [0, 1]² that maps to `d` on the unit disk.
pub fn concentric_square(d: DVec2) -> DVec2 {
    let r = d.length();
    if r == 0.0 {
        return DVec2::splat(0.5);
    }
    let phi = crate::trig::atan2(d.y, d.x);
    let o = if phi.abs() <= FRAC_PI_4 {
        DVec2::new(r, r * phi / FRAC_PI_4)
    } else if phi.abs() >= 3.0 * FRAC_PI_4 {
        let theta = if phi > 0.0 { phi - PI } else { phi + PI };
        DVec2::new(-r, -r * theta / FRAC_PI_4)
    } else if phi > 0.0 {
        DVec2::new(r * (FRAC_PI_2 - phi) / FRAC_PI_4, r)
    } else {
        let theta = phi + PI;
        DVec2::new(-r * (FRAC_PI_2 - theta) / FRAC_PI_4, -r)
    };
    ((o + DVec2::ONE) * 0.5).clamp(DVec2::ZERO, DVec2::ONE)
}

/// A direction on the upper hemisphere with pdf `cos θ / π` (Malley's method: project the
/// uniform disk onto the hemisphere; pbrt-v4 §A.5.3).
pub fn cosine_hemisphere(u: DVec2) -> DVec3 {
    let d = concentric_disk(u);
    let z = (1.0 - d.length_squared()).max(0.0).sqrt();
    DVec3::new(d.x, d.y, z)
}

/// The pdf of [`cosine_hemisphere`] for a direction whose cosine to the normal is `cos_theta`.
pub fn cosine_hemisphere_pdf(cos_theta: f64) -> f64 {
    cos_theta.max(0.0) * FRAC_1_PI
}

/// A direction about +z with pdf `(n + 1)/(2π) cos^n θ` over the whole sphere's upper half
/// (the Phong lobe; E. Lafortune & Y. Willems, "Using the modified Phong reflectance model for
/// physically based rendering", KU Leuven CW 197, 1994, §4): `cos θ = u₁^(1/(n+1))`.
pub fn power_cosine(u: DVec2, exponent: f64) -> DVec3 {
    let cos_t = u.x.powf(1.0 / (exponent + 1.0));
    let sin_t = (1.0 - cos_t * cos_t).max(0.0).sqrt();
    let phi = 2.0 * PI * u.y;
    DVec3::new(sin_t * phi.cos(), sin_t * phi.sin(), cos_t)
}

/// The pdf of [`power_cosine`] for a direction at `cos_theta` from its axis.
pub fn power_cosine_pdf(cos_theta: f64, exponent: f64) -> f64 {
    if cos_theta <= 0.0 {
        return 0.0;
    }
    (exponent + 1.0) / (2.0 * PI) * cos_theta.powf(exponent)
}

/// Mirror `w` about the unit vector `n`: `2 (w·n) n - w` (both pointing away from the surface).
pub fn reflect(w: DVec3, n: DVec3) -> DVec3 {
    2.0 * w.dot(n) * n - w
}

/// An orthonormal frame whose third axis is a given unit vector.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    /// First tangent.
    pub s: DVec3,
    /// Second tangent.
    pub t: DVec3,
    /// The axis the frame was built about.
    pub n: DVec3,
}

impl Frame {
    /// The frame about the unit vector `n`, without branches on the direction (Duff et al.,
    /// "Building an orthonormal basis, revisited", JCGT 6(1), 2017, listing 3).
    pub fn from_z(n: DVec3) -> Self {
        let sign = 1.0f64.copysign(n.z);
        let a = -1.0 / (sign + n.z);
        let b = n.x * n.y * a;
        let s = DVec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
        let t = DVec3::new(b, sign + n.y * n.y * a, -n.y);
        Frame { s, t, n }
    }

    /// Components of the world vector `v` in this frame.
    pub fn to_local(&self, v: DVec3) -> DVec3 {
        DVec3::new(v.dot(self.s), v.dot(self.t), v.dot(self.n))
    }

    /// The world vector whose components in this frame are `v`.
    pub fn to_world(&self, v: DVec3) -> DVec3 {
        v.x * self.s + v.y * self.t + v.z * self.n
    }
}
