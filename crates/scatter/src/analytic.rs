//! Analytic BRDFs of a Gaussian random surface (rms height `sigma`, Gaussian autocorrelation
//! `sigma² exp(-r²/T²)`), the references that the ray method and the Kirchhoff integral are held
//! against, and their detector-averaged in-plane curves.
//!
//! Models (with their sources; method and tests in `docs/kirchhoff.md`, "Analytic references"):
//! - [`AnalyticModel::Beckmann`]: the Beckmann-Spizzichino series (P. Beckmann & A. Spizzichino,
//!   *The Scattering of Electromagnetic Waves from Rough Surfaces*, 1963, ch. 5, eq. 47 with the
//!   Fresnel factor of ch. 3): the coherent specular reflectance `R e^(-g)` plus the incoherent
//!   series `R k² T² F² cos ti/(4π cos ts) · e^(-g) Σ g^m/(m! m) exp(-(vx²+vy²)T²/(4m))`,
//!   summed in log space with `ln Γ` to `m ≈ g + 10√g + 30`.
//! - [`AnalyticModel::Geometric`]: its limit for `g → ∞` (Beckmann & Spizzichino ch. 5 §3), the
//!   facet model with Beckmann normals of rms slope `m = 2 sigma/T` and no masking.
//! - [`AnalyticModel::Microfacet`]: the same facet model with height-correlated Smith masking
//!   (Heitz 2014, JCGT 3(2), eq. 99; [`gonio_brdf::microfacet`]).
//! - [`AnalyticModel::Smooth`]: the first-order (`m = 1`) term for `g → 0`, the smooth-surface halo
//!   `R k² T² F² cos ti g exp(-(vx²+vy²)T²/4)/(4π cos ts)` (Beckmann & Spizzichino ch. 5, eq. 48),
//!   plus the coherent term `R e^(-g)`.
//!
//! Fresnel reflectance is taken at the local angle of the facet that mirrors `wi` into `wo`,
//! `cos iota = sqrt((1 + wi·wo)/2)`. A detector reads `rho = ∫_cone f cos t dω`, computed by a
//! Gauss-Legendre × trapezoid quadrature over the cone ([`cone_reflectance`]); the coherent term is
//! a delta in the mirror direction and goes wholly into every detector whose cone contains it.

use crate::error::{Result, ScatterError};
use crate::geometry::{
    CurvePoint, Detector, InplaneCurve, incidence_direction, inplane_direction, label_value,
    spherical_direction,
};
use glam::DVec3;
use gonio_brdf::Ior;
use gonio_brdf::microfacet::{beckmann_d, smith_g2};
use std::f64::consts::PI;

/// Which analytic model to evaluate.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AnalyticModel {
    /// Beckmann-Spizzichino: coherent term plus the full incoherent series.
    Beckmann,
    /// The geometric-optics limit of the series (facet model without masking).
    Geometric,
    /// Facet model with height-correlated Smith masking.
    Microfacet,
    /// First-order smooth-surface limit (coherent term plus the `m = 1` halo).
    Smooth,
}

impl AnalyticModel {
    /// The name written in the `method` column of curves and CSV files.
    pub fn name(self) -> &'static str {
        match self {
            AnalyticModel::Beckmann => "beckmann",
            AnalyticModel::Geometric => "geometric",
            AnalyticModel::Microfacet => "microfacet",
            AnalyticModel::Smooth => "smooth",
        }
    }

    /// The model of a name as [`Self::name`] writes it.
    pub fn from_name(name: &str) -> Option<Self> {
        [
            Self::Beckmann,
            Self::Geometric,
            Self::Microfacet,
            Self::Smooth,
        ]
        .into_iter()
        .find(|m| m.name() == name)
    }

    /// Whether the model depends on the wavelength (wave optics).
    pub fn is_wave(self) -> bool {
        matches!(self, AnalyticModel::Beckmann | AnalyticModel::Smooth)
    }
}

/// A Gaussian random surface with a Gaussian autocorrelation, coated with a medium of index
/// `ior`: the parameters of every analytic model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GaussianModel {
    sigma: f64,
    corr_length: f64,
    ior: Ior,
}

impl GaussianModel {
    /// A model of rms height `sigma` and correlation length `corr_length` (both metres).
    pub fn new(sigma: f64, corr_length: f64, ior: Ior) -> Result<Self> {
        if !(sigma.is_finite() && sigma > 0.0) {
            return Err(ScatterError::Invalid(format!(
                "rms height {sigma} m must be positive and finite"
            )));
        }
        if !(corr_length.is_finite() && corr_length > 0.0) {
            return Err(ScatterError::Invalid(format!(
                "correlation length {corr_length} m must be positive and finite"
            )));
        }
        Ok(GaussianModel {
            sigma,
            corr_length,
            ior,
        })
    }

    /// rms height, metres.
    pub fn sigma(&self) -> f64 {
        self.sigma
    }

    /// Correlation length, metres.
    pub fn corr_length(&self) -> f64 {
        self.corr_length
    }

    /// Total rms slope `m = 2 sigma / T`.
    pub fn rms_slope(&self) -> f64 {
        2.0 * self.sigma / self.corr_length
    }

    /// The roughness parameter `g = k² sigma² (cos ti + cos to)²` for the pair `(wi, wo)`.
    pub fn g(&self, wavelength: f64, wi: DVec3, wo: DVec3) -> f64 {
        let k = 2.0 * PI / wavelength;
        (k * self.sigma * (wi.z + wo.z)).powi(2)
    }

    /// Coherent specular reflectance `R(ti) e^(-g)` with `g = (2 k sigma cos ti)²`.
    pub fn coherent_reflectance(&self, wavelength: f64, theta_i: f64) -> f64 {
        let wi = incidence_direction(theta_i);
        let mirror = DVec3::new(-wi.x, -wi.y, wi.z);
        self.ior.reflectance(wi.z) * (-self.g(wavelength, wi, mirror)).exp()
    }

    /// The model's BRDF (1/sr, without the coherent delta) for the directions `wi`, `wo` (unit
    /// vectors away from the surface). `wavelength` (metres) matters only for wave models.
    pub fn brdf_dirs(&self, model: AnalyticModel, wavelength: f64, wi: DVec3, wo: DVec3) -> f64 {
        if wi.z <= 0.0 || wo.z <= 0.0 {
            return 0.0;
        }
        match model {
            AnalyticModel::Beckmann => self.series(wavelength, wi, wo, false),
            AnalyticModel::Smooth => self.series(wavelength, wi, wo, true),
            AnalyticModel::Geometric => self.facet(wi, wo, false),
            AnalyticModel::Microfacet => self.facet(wi, wo, true),
        }
    }

    /// The model's BRDF at incidence `theta_i` and outgoing `(theta_s, phi_s)` (radians,
    /// `phi_s = 0` on the specular side), 1/sr.
    pub fn brdf(
        &self,
        model: AnalyticModel,
        wavelength: f64,
        theta_i: f64,
        theta_s: f64,
        phi_s: f64,
    ) -> f64 {
        let wi = incidence_direction(theta_i);
        self.brdf_dirs(model, wavelength, wi, spherical_direction(theta_s, phi_s))
    }

    /// Reflectance a detector reads, the coherent term included for wave models.
    pub fn detector_reflectance(
        &self,
        model: AnalyticModel,
        wavelength: f64,
        theta_i: f64,
        detector: &Detector,
    ) -> f64 {
        let wi = incidence_direction(theta_i);
        let diffuse = cone_reflectance(detector, |wo| self.brdf_dirs(model, wavelength, wi, wo));
        let mirror = DVec3::new(-wi.x, -wi.y, wi.z);
        let sees_mirror = mirror.dot(detector.direction) >= detector.half_angle.cos();
        if model.is_wave() && sees_mirror {
            diffuse + self.coherent_reflectance(wavelength, theta_i)
        } else {
            diffuse
        }
    }

    /// In-plane curve at incidence `theta_i` for detectors of half-angle `half_angle` at signed
    /// scatter angles `scatter` (all radians). The BRDF column is `rho / (Omega cos ts)`.
    pub fn inplane(
        &self,
        model: AnalyticModel,
        wavelength: f64,
        theta_i: f64,
        scatter: &[f64],
        half_angle: f64,
    ) -> InplaneCurve {
        let points = scatter
            .iter()
            .map(|&ts| {
                let detector = Detector {
                    direction: inplane_direction(ts),
                    half_angle,
                };
                let rho = self.detector_reflectance(model, wavelength, theta_i, &detector);
                CurvePoint {
                    scatter_deg: label_value(ts.to_degrees()),
                    brdf_per_sr: rho / (detector.solid_angle() * ts.cos()),
                    reflectance: rho,
                    rel_uncertainty: None,
                }
            })
            .collect();
        InplaneCurve {
            method: model.name().to_string(),
            wavelength_nm: model.is_wave().then_some(label_value(wavelength * 1e9)),
            incidence_deg: label_value(theta_i.to_degrees()),
            points,
        }
    }

    /// Beckmann's geometric factor and Fresnel reflectance at the local angle:
    /// `(R(iota), F²)` with `F = (1 + wi·wo)/(cos ti (cos ti + cos to))`.
    fn fresnel_and_f2(&self, wi: DVec3, wo: DVec3) -> (f64, f64) {
        let c = wi.dot(wo);
        let cos_iota = ((1.0 + c) / 2.0).max(0.0).sqrt();
        let f = (1.0 + c) / (wi.z * (wi.z + wo.z));
        (self.ior.reflectance(cos_iota), f * f)
    }

    /// The incoherent Beckmann-Spizzichino series, or its first term without `e^(-g)` when
    /// `first_order`.
    fn series(&self, wavelength: f64, wi: DVec3, wo: DVec3, first_order: bool) -> f64 {
        let k = 2.0 * PI / wavelength;
        let t2 = self.corr_length * self.corr_length;
        let s = wi + wo;
        let vxy2 = k * k * (s.x * s.x + s.y * s.y);
        let g = self.g(wavelength, wi, wo);
        let (r, f2) = self.fresnel_and_f2(wi, wo);
        let prefactor = r * k * k * t2 * f2 * wi.z / (4.0 * PI * wo.z);
        let sum = if first_order {
            g * (-vxy2 * t2 / 4.0).exp()
        } else {
            beckmann_sum(g, vxy2 * t2 / 4.0)
        };
        prefactor * sum
    }

    /// The facet model `R(iota) D(h) G / (4 cos ti cos to)`, with Smith masking when `masked`.
    fn facet(&self, wi: DVec3, wo: DVec3, masked: bool) -> f64 {
        let m = self.rms_slope();
        let h = (wi + wo).normalize();
        let (r, _) = self.fresnel_and_f2(wi, wo);
        let g = if masked { smith_g2(wi.z, wo.z, m) } else { 1.0 };
        r * beckmann_d(h.z, m) * g / (4.0 * wi.z * wo.z)
    }
}

/// `e^(-g) Σ_{m≥1} g^m/(m! m) exp(-a/m)`, each term formed in log space. Terms below
/// `m = g - 10√g - 30` are skipped (their Poisson weight is below e^(-50) of the peak) and the sum
/// ends at `m = g + 10√g + 30`, as far above the peak (`docs/kirchhoff.md`, "Analytic references").
pub fn beckmann_sum(g: f64, a: f64) -> f64 {
    if g <= 0.0 {
        return 0.0;
    }
    let spread = 10.0 * g.sqrt() + 30.0;
    let first = ((g - spread).floor() as i64).max(1);
    let last = (g + spread).ceil() as i64;
    let ln_g = g.ln();
    (first..=last)
        .map(|m| {
            let mf = m as f64;
            (mf * ln_g - libm::lgamma(mf + 1.0) - mf.ln() - g - a / mf).exp()
        })
        .sum()
}

/// `rho = ∫_cone f(wo) cos(to) dω` over a detector cone, by Gauss-Legendre quadrature in
/// `u = (1 - cos θ')/(1 - cos alpha)` (θ' from the cone axis; uniform in solid angle) and the
/// trapezoid rule in azimuth about the axis (exact for trigonometric polynomials), with 24 × 48
/// nodes: enough for lobes down to about a tenth of the cone's width.
pub fn cone_reflectance(detector: &Detector, f: impl Fn(DVec3) -> f64) -> f64 {
    const N_U: usize = 24;
    const N_PHI: usize = 48;
    let axis = detector.direction.normalize();
    let (e1, e2) = axis.any_orthonormal_pair();
    let one_minus_cos = 1.0 - detector.half_angle.cos();
    let mut sum = 0.0;
    for (x, w) in gonio_brdf::quadrature::gauss_legendre(N_U) {
        let u = 0.5 * (x + 1.0);
        let cos_t = 1.0 - u * one_minus_cos;
        let sin_t = (1.0 - cos_t * cos_t).max(0.0).sqrt();
        let mut ring = 0.0;
        for j in 0..N_PHI {
            let phi = 2.0 * PI * j as f64 / N_PHI as f64;
            let wo = cos_t * axis + sin_t * (phi.cos() * e1 + phi.sin() * e2);
            if wo.z > 0.0 {
                ring += f(wo) * wo.z;
            }
        }
        sum += 0.5 * w * ring / N_PHI as f64;
    }
    sum * detector.solid_angle()
}
