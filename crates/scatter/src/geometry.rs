//! Measurement geometry shared by the scattering methods: incidence and in-plane scattering
//! directions, detectors with a circular aperture, and the in-plane curve that every method
//! returns. Conventions (those of in-plane goniometers such as NIST's STARR; `docs/physics.md`,
//! "Frames, angles, units"): +z is the mean surface normal, `wi` points toward the source and `wo`
//! toward the detector, the source lies in the x-z plane at negative x, and the in-plane scattering
//! angle is signed, with the specular peak at `+ti` and negative angles on the source's side.

use glam::DVec3;
use std::f64::consts::PI;

/// Direction toward a source at incidence `theta_i` (radians) in the x-z plane, at negative x:
/// `wi = (-sin ti, 0, cos ti)`.
pub fn incidence_direction(theta_i: f64) -> DVec3 {
    DVec3::new(-theta_i.sin(), 0.0, theta_i.cos())
}

/// Direction toward an in-plane detector at the signed scattering angle `theta_s` (radians):
/// `wo = (sin ts, 0, cos ts)`; the specular peak of incidence ti is at `ts = +ti`.
pub fn inplane_direction(theta_s: f64) -> DVec3 {
    DVec3::new(theta_s.sin(), 0.0, theta_s.cos())
}

/// Direction `(ts, ps)` with `ps = 0` on the specular side:
/// `wo = (sin ts cos ps, sin ts sin ps, cos ts)`.
pub fn spherical_direction(theta: f64, phi: f64) -> DVec3 {
    DVec3::new(
        theta.sin() * phi.cos(),
        theta.sin() * phi.sin(),
        theta.cos(),
    )
}

/// Solid angle of a cone of half-angle `alpha` (radians): `2π(1 - cos alpha)` steradians.
pub fn cone_solid_angle(alpha: f64) -> f64 {
    2.0 * PI * (1.0 - alpha.cos())
}

/// A detector: a cone of half-angle `half_angle` (radians) about a unit `direction`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Detector {
    pub direction: DVec3,
    pub half_angle: f64,
}

impl Detector {
    /// The solid angle the detector subtends, in steradians.
    pub fn solid_angle(&self) -> f64 {
        cone_solid_angle(self.half_angle)
    }
}

/// An in-plane goniometer: sources at the incidences, detectors of one cone half-angle at the
/// signed scattering angles, all in the plane of incidence and in radians (the conventions of
/// this module's directions). Built from degrees at the edges ([`Goniometer::from_degrees`]);
/// [`Goniometer::starr`] is the NIST STARR set-up the project's measurements use.
#[derive(Debug, Clone, PartialEq)]
pub struct Goniometer {
    /// Incidence angles, radians.
    pub incidences: Vec<f64>,
    /// Signed scattering angles, radians (specular at `+incidence`).
    pub scatter: Vec<f64>,
    /// Detector cone half-angle, radians.
    pub half_angle: f64,
}

impl Goniometer {
    /// A goniometer from angles in degrees: incidences, signed scattering angles and the
    /// detector's half-angle (the aperture).
    pub fn from_degrees(incidences_deg: &[f64], scatter_deg: &[f64], aperture_deg: f64) -> Self {
        Goniometer {
            incidences: incidences_deg.iter().map(|d| d.to_radians()).collect(),
            scatter: scatter_deg.iter().map(|d| d.to_radians()).collect(),
            half_angle: aperture_deg.to_radians(),
        }
    }

    /// The NIST STARR in-plane set-up of the epoxy roughness series: incidence 20°, 45°, 60° and
    /// 70°, scattering angles −75° to 75° in 1° steps, detectors of 1.4° half-angle.
    pub fn starr() -> Self {
        let scatter: Vec<f64> = (-75..=75).map(f64::from).collect();
        Goniometer::from_degrees(&STARR_INCIDENCES_DEG, &scatter, STARR_APERTURE_DEG)
    }

    /// The incidences in degrees (as the curves label them).
    pub fn incidences_deg(&self) -> Vec<f64> {
        self.incidences
            .iter()
            .map(|t| label_value(t.to_degrees()))
            .collect()
    }

    /// The scattering angles in degrees (as the curves label them).
    pub fn scatter_deg(&self) -> Vec<f64> {
        self.scatter
            .iter()
            .map(|t| label_value(t.to_degrees()))
            .collect()
    }

    /// The detector at the scattering angle `theta_s` (radians).
    pub fn detector(&self, theta_s: f64) -> Detector {
        Detector {
            direction: inplane_direction(theta_s),
            half_angle: self.half_angle,
        }
    }
}

/// Incidence angles of the NIST STARR set-up, degrees.
pub const STARR_INCIDENCES_DEG: [f64; 4] = [20.0, 45.0, 60.0, 70.0];

/// Detector half-angle of the NIST STARR set-up, degrees.
pub const STARR_APERTURE_DEG: f64 = 1.4;

/// A value for a curve's label (degrees, nm) rounded to 10⁻⁹, so that a quantity converted from
/// the user's unit to SI and back reads as given (60° → rad → deg is 59.99999999999999).
pub fn label_value(x: f64) -> f64 {
    (x * 1e9).round() / 1e9
}

/// One point of an in-plane curve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurvePoint {
    /// Signed scattering angle in degrees (specular at +incidence).
    pub scatter_deg: f64,
    /// BRDF averaged over the detector, 1/sr.
    pub brdf_per_sr: f64,
    /// Reflectance collected by the detector, `rho ≈ f Omega cos ts`.
    pub reflectance: f64,
    /// Relative standard uncertainty of `reflectance` (Poisson, from hit counts) where the method
    /// counts hits; `None` otherwise.
    pub rel_uncertainty: Option<f64>,
}

/// An in-plane curve at one incidence (and wavelength, for wave methods).
#[derive(Debug, Clone, PartialEq)]
pub struct InplaneCurve {
    /// Method or model name as written in the `method` column ("ray", "kirchhoff", "beckmann", ...).
    pub method: String,
    /// Wavelength in nm, when the result depends on it.
    pub wavelength_nm: Option<f64>,
    /// Incidence angle in degrees.
    pub incidence_deg: f64,
    /// Points in increasing scatter angle.
    pub points: Vec<CurvePoint>,
}
