//! When a virtual reading cannot be trusted: plain-words warnings about the scattering method
//! and the map it reads, and the check of the refractive index.
//!
//! Three limits, each an estimate from the physics rather than an exact bound (and, after a
//! reading, a fourth: a DOI whose patch-to-patch spread on the map is large, [`doi_warning`]):
//!
//! - **Ray method on a smooth map.** A Gaussian surface of rms height Sq reflects the fraction
//!   `e^−g` of its light coherently (a specular spike as narrow as the spot's diffraction), with
//!   the Rayleigh roughness parameter `g = (4π Sq cos θ / λ)²` at incidence θ (Beckmann &
//!   Spizzichino 1963, ch. 5; `docs/kirchhoff.md`, "Analytic references"). Geometric optics has
//!   no coherent part: it spreads all the light over the facet-slope lobe. Where `g < 1` the
//!   coherent part (more than 1/e = 37% of the reflected light) dominates and the ray method
//!   misses it: `opd-1.opd` reads 53 GU at 20° by the ray method and 93 GU by Kirchhoff.
//! - **Kirchhoff spot too small for an aperture.** A spot of diameter L resolves directions
//!   about `λ / (L cos θ)` apart in the plane of incidence (its diffraction spreads a mirror's
//!   image that wide). A reading is trusted where that spread is at most a quarter of its
//!   angular scale: the receptor's in-plane width for a specular reading (gloss), the offset
//!   from specular for an off-specular one (DOI's 0.3°, haze's 1.9–5°), the detector's full
//!   width for an in-plane curve. A quarter keeps the diffraction tail a mirror spills past
//!   the scale to a few per cent (for a sinc² pattern the fraction beyond `U` widths is about
//!   `1/(π² U)`): a flat 0.5 mm patch at 85° (spread 0.72°, receptor 4°) reads the smooth
//!   surface's gloss within 1%, a 0.13 mm patch (2.8°) reads 68 GU instead of 99.8.
//! - **Too few speckle grains.** A speckle grain of that spot subtends about `(λ/L)² / cos θ`
//!   steradians, so a receptor of solid angle Ω averages `N = Ω cos θ (L/λ)²` grains, and the
//!   diffusely scattered part of its reading fluctuates from spot to spot by about `1/√N`
//!   (Goodman, *Speckle Phenomena in Optics*, 2007, §4.6). Below 10 grains that is over 30%.

use crate::error::{InstrumentError, Result};
use crate::gloss::{Aperture, GlossReport, e430};

/// Rayleigh roughness parameter below which the coherent specular part dominates.
pub const RAYLEIGH_G_MIN: f64 = 1.0;
/// Fewest speckle grains a receptor should average.
pub const SPECKLE_GRAINS_MIN: f64 = 10.0;
/// Largest ratio of the spot's diffraction spread to a reading's angular scale.
pub const SPREAD_RATIO_MAX: f64 = 0.25;
/// Wavelength at which photometric readings (gloss, haze, DOI) are judged: 550 nm, near the peak
/// of the photopic response.
pub const PHOTOMETRIC_WAVELENGTH: f64 = 550e-9;

/// The Rayleigh roughness parameter `g = (4π Sq cos θ / λ)²` of specular reflection at
/// incidence `theta` (radians) for rms height `sq` and wavelength `wavelength` (metres)
/// (Beckmann & Spizzichino 1963, ch. 5: `g = k² σ² (cos θi + cos θs)²` with `k = 2π/λ`, at
/// `θs = θi`; `docs/kirchhoff.md`, "Analytic references").
pub fn rayleigh_g(sq: f64, theta: f64, wavelength: f64) -> f64 {
    (4.0 * std::f64::consts::PI * sq * theta.cos() / wavelength).powi(2)
}

/// DOI uncertainty (one standard deviation, DOI units) above which a reading is flagged.
pub const DOI_UNCERTAINTY_MAX: f64 = 5.0;

/// A warning when the DOI of `report` is uncertain by more than [`DOI_UNCERTAINTY_MAX`] units
/// from the finite map: the 0.1° slits of DOI catch few of the ray method's reflected rays on a
/// rough or small map, so the reading changes from one map of the surface to the next.
pub fn doi_warning(report: &GlossReport) -> Option<String> {
    (report.doi_uncertainty > DOI_UNCERTAINTY_MAX).then(|| {
        format!(
            "DOI {:.1} is uncertain by ±{:.1} (one standard deviation over 16 patches of the \
             map): its 0.1° slits catch few reflected rays from this map; read a larger map, \
             or several, and average",
            report.doi, report.doi_uncertainty
        )
    })
}

/// Check the coating's refractive index: not finite or not positive is refused (the Fresnel
/// reflectance of such an index is meaningless); an index below 1 is accepted with a warning.
pub fn check_index(n: f64) -> Result<Vec<String>> {
    if !n.is_finite() || n <= 0.0 {
        return Err(InstrumentError::Invalid(format!(
            "refractive index {n}: it must be a positive number (coatings are about 1.4-1.7)"
        )));
    }
    Ok(if n < 1.0 {
        vec![format!(
            "refractive index {n} is below 1: a coating denser than air has n > 1 \
             (about 1.4-1.7); the reflectance is computed as for an interface seen from \
             the denser side"
        )]
    } else {
        Vec::new()
    })
}

/// One reading a virtual instrument takes, as the validity checks see it.
#[derive(Debug, Clone, PartialEq)]
pub struct ReadingGeometry {
    /// Name in plain words ("20° gloss", "DOI").
    pub name: String,
    /// Incidence angle, radians (the reading's specular direction is at the same angle).
    pub theta: f64,
    /// The receptor.
    pub aperture: Aperture,
    /// The angular scale the reading resolves, radians: the receptor's in-plane width for a
    /// specular reading, the offset from specular for an off-specular one.
    pub scale: f64,
}

/// The readings of [`crate::gloss::measure`]: the ISO 2813 gloss receptors, DOI's 0.1° slits at
/// 0.3° from specular, and the haze receptors of E430 Test Methods A and B.
pub fn meter_readings() -> Vec<ReadingGeometry> {
    let mut out: Vec<ReadingGeometry> = [20u32, 60, 85]
        .into_iter()
        .map(|deg| {
            let g = crate::gloss::Geometry::iso2813(deg).expect("ISO 2813 angle");
            ReadingGeometry {
                name: format!("{deg}° gloss"),
                theta: g.theta,
                aperture: g.receptor.aperture,
                scale: g.receptor.aperture.in_plane,
            }
        })
        .collect();
    let off = |name: &str, theta_deg: f64, aperture: Aperture, offset_deg: f64| ReadingGeometry {
        name: name.to_string(),
        theta: theta_deg.to_radians(),
        aperture,
        scale: offset_deg.to_radians(),
    };
    out.push(off(
        "DOI",
        e430::THETA_DEG,
        e430::doi_receptor(),
        e430::DOI_OFFSET_DEG,
    ));
    out.push(off(
        "haze (E430 A, 2°)",
        e430::THETA_DEG,
        e430::receptor(),
        e430::HAZE_OFFSET_DEG,
    ));
    out.push(off(
        "haze (E430 A, 5°)",
        e430::THETA_DEG,
        e430::receptor(),
        e430::WIDE_HAZE_OFFSET_DEG,
    ));
    out.push(off(
        "haze (20°)",
        e430::B_THETA_DEG,
        e430::b_receptor(),
        e430::B_HAZE_OFFSET_DEG,
    ));
    out
}

/// The detectors of in-plane curves at `incidences_deg`: a cone of half-angle `half_angle`
/// (radians) on the specular direction of each incidence, resolving its own full width.
pub fn inplane_readings(incidences_deg: &[f64], half_angle: f64) -> Vec<ReadingGeometry> {
    incidences_deg
        .iter()
        .map(|&deg| ReadingGeometry {
            name: format!("the in-plane curve at {deg}° incidence"),
            theta: deg.to_radians(),
            // The square of equal solid angle stands in for the cone: side √π · half-angle.
            aperture: Aperture {
                in_plane: std::f64::consts::PI.sqrt() * half_angle,
                perpendicular: std::f64::consts::PI.sqrt() * half_angle,
            },
            scale: 2.0 * half_angle,
        })
        .collect()
}

/// Warnings for the ray method on a map of rms height `sq` (metres) at `wavelength` (metres):
/// one, naming the readings where `g < 1`, or none.
pub fn ray_warnings(sq: f64, wavelength: f64, readings: &[ReadingGeometry]) -> Vec<String> {
    let smooth: Vec<String> = readings
        .iter()
        .filter_map(|r| {
            let g = rayleigh_g(sq, r.theta, wavelength);
            (g < RAYLEIGH_G_MIN).then(|| format!("{} (g = {g:.2})", r.name))
        })
        .collect();
    if smooth.is_empty() {
        return Vec::new();
    }
    vec![format!(
        "the map is smooth for light of {:.0} nm (Sq = {:.1} nm): its Rayleigh roughness \
         g = (4π Sq cos θ / λ)² is below 1 for {}, so most of the light there is reflected \
         coherently, as a sharp specular spike the ray method cannot produce; these readings \
         are unreliable by the ray method, use --method kirchhoff",
        wavelength * 1e9,
        sq * 1e9,
        smooth.join(", ")
    )]
}

/// Warnings for the Kirchhoff approximation over a spot of diameter `spot` (metres) at
/// `wavelength` (metres): readings whose angular scale the spot cannot resolve, and readings
/// that average too few speckle grains.
pub fn kirchhoff_warnings(spot: f64, wavelength: f64, readings: &[ReadingGeometry]) -> Vec<String> {
    let mut out = Vec::new();
    let spread_deg = |r: &ReadingGeometry| (wavelength / (spot * r.theta.cos())).to_degrees();
    let blurred: Vec<String> = readings
        .iter()
        .filter(|r| spread_deg(r) > SPREAD_RATIO_MAX * r.scale.to_degrees())
        .map(|r| {
            format!(
                "{} (spread {:.2}° against {:.2}°)",
                r.name,
                spread_deg(r),
                r.scale.to_degrees()
            )
        })
        .collect();
    if !blurred.is_empty() {
        out.push(format!(
            "the illuminated spot ({:.0} µm across) is too small for {}: its diffraction \
             spreads a mirror's image over about λ/(L cos θ), more than a quarter of the angle \
             the reading must resolve, so light spills across the receptor's edge; these \
             readings need a larger map",
            spot * 1e6,
            blurred.join(", ")
        ));
    }
    let grains = |r: &ReadingGeometry| {
        let omega = r.aperture.in_plane * 2.0 * (0.5 * r.aperture.perpendicular).sin();
        omega * r.theta.cos() * (spot / wavelength).powi(2)
    };
    let speckled: Vec<String> = readings
        .iter()
        .filter(|r| grains(r) < SPECKLE_GRAINS_MIN)
        .map(|r| {
            let n = grains(r);
            format!("{} ({n:.1} grains, ±{:.0}%)", r.name, 100.0 / n.sqrt())
        })
        .collect();
    if !speckled.is_empty() {
        out.push(format!(
            "too few speckle grains in the receptor for {}: the diffusely scattered light \
             these readings collect would change by about 1/√grains from one spot of the \
             surface to another; a larger map (or averaging several spots) steadies them",
            speckled.join(", ")
        ));
    }
    out
}
