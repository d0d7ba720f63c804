//! What any spectral BRDF shows on the lab's page (`gonio lab`, issue #33), a formulation's or a
//! measured target's: the multi-angle CIELAB at a standard's geometries with each geometry's
//! sRGB swatch, Alman's flop index, the in-plane luminance BRDF at one incidence, and L* against
//! the aspecular angle at 45° illumination. `coating_readings` adds what only a coating model
//! gives (the gloss meter, the directional-hemispherical reflectance); `gonio-formulation`'s
//! `lab_target` reads a measured BRDF through the same call.
//!
//! Every reading goes through [`multiangle::read`] (D65, the CIE 1964 10° observer, point
//! apertures), so each is what `gonio multiangle` would read at that geometry; the in-plane
//! BRDF and the L* curve are multi-angle readings at many geometries. Conventions:
//! - in-plane BRDF: the light at polar angle θi on the −x side, the view at the signed
//!   scattering angle θs, positive on the specular side (the specular direction at θs = θi), as
//!   `gonio inplane` and the gloss meter count it; the luminance BRDF is `Y / (100 π)` of the
//!   reading (Y on the 0–100 scale, the perfect diffuser's 1/π giving 100), the BRDF weighted by
//!   the luminance weights of D65 and the 10° observer (ASTM E308);
//! - L* curve: 45° illumination, the aspecular angle γ from −15° to 110° every 2.5° (every
//!   geometry of ASTM E2194 and the 45° ones of E2539 among them, so that the curve passes
//!   through the standard's readings).

use crate::error::{InstrumentError, Result};
use crate::multiangle::{self, Geometry, MultiangleReading, Settings, Standard};
use glam::DVec3;
use gonio_color::{Colorimetry, Illuminant, Lab, Observer, Xyz};
use gonio_io::Cancel;

/// A spectral BRDF as [`multiangle::read`] takes it: `brdf(wo, wi, out)` writes `f(wo, wi)` in
/// 1/sr at each of the reading's wavelengths.
pub type SpectralFn<'a> = &'a (dyn Fn(DVec3, DVec3, &mut [f64]) + Sync);

/// The illumination angle of the L* curve, degrees (ASTM E2194's).
pub const CURVE_ILLUMINATION_DEG: f64 = 45.0;
/// The L* curve's aspecular angles: from −15° to 110° every 2.5°.
pub fn curve_aspecular_deg() -> Vec<f64> {
    (0..=50).map(|k| -15.0 + 2.5 * k as f64).collect()
}

/// The colour a web page shows for a reading: sRGB (IEC 61966-2-1) of its XYZ under D65 for the
/// 10° observer, white-balanced to the sRGB white ([`Colorimetry::of_xyz`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Swatch {
    /// `#rrggbb`, 8-bit encoded sRGB of the linear values clipped to [0, 1].
    pub hex: String,
    /// Linear sRGB before clipping (1 = the display's white, the perfect diffuser).
    pub linear_srgb: [f64; 3],
    /// Whether the colour lay outside the sRGB gamut (a component below 0 or above 1: too
    /// saturated, or lighter than the perfect diffuser near the specular direction) and was
    /// clipped to give `hex`.
    pub clipped: bool,
}

impl Swatch {
    /// The swatch of `xyz` (0–100 scale, D65, 10° observer).
    pub fn of_xyz(xyz: Xyz) -> Swatch {
        let c = Colorimetry::of_xyz(xyz, Illuminant::D65, Observer::Cie1964TenDegree);
        let l = c.linear_srgb;
        Swatch {
            hex: c.srgb.to_hex(),
            linear_srgb: [l.r, l.g, l.b],
            clipped: !l.in_gamut(),
        }
    }
}

/// The in-plane luminance BRDF at one incidence.
#[derive(Clone, Debug, PartialEq)]
pub struct InPlaneBrdf {
    /// The light's polar angle, degrees.
    pub incidence_deg: f64,
    /// Signed scattering angles, degrees, increasing; the specular direction at `incidence_deg`.
    pub scatter_deg: Vec<f64>,
    /// The luminance-weighted BRDF at each, 1/sr (a smooth top's mirror reflection, a delta, is
    /// not in it: [`InPlaneBrdf::mirror_reflectance`]).
    pub brdf_per_sr: Vec<f64>,
    /// The luminance-weighted reflectance of a smooth top's mirror reflection at the specular
    /// direction (Fresnel at the binder's index); 0 for a rough top or a measured BRDF, whose
    /// reflection near the specular direction is in `brdf_per_sr`.
    pub mirror_reflectance: f64,
}

/// L* against the aspecular angle at [`CURVE_ILLUMINATION_DEG`].
#[derive(Clone, Debug, PartialEq)]
pub struct LightnessCurve {
    /// Aspecular angles, degrees ([`curve_aspecular_deg`]).
    pub aspecular_deg: Vec<f64>,
    /// CIELAB L* (D65/10°) at each; above 100 near the specular direction where the coating
    /// reflects more than the perfect diffuser.
    pub lightness: Vec<f64>,
}

/// What [`read`] gives.
#[derive(Clone, Debug)]
pub struct BrdfReadings {
    pub standard: Standard,
    /// The multi-angle reading at the standard's geometries, in its order.
    pub multiangle: MultiangleReading,
    /// One swatch per geometry of `multiangle`.
    pub swatches: Vec<Swatch>,
    /// Alman's flop index ([`MultiangleReading::flop_index`]).
    pub flop_index: Option<f64>,
    pub inplane: InPlaneBrdf,
    pub lightness: LightnessCurve,
}

/// The in-plane views of [`read`]: every 1° from −85° to 85°, and every `lobe_deg / 8` (at
/// least 0.05°, at most 1°) within four `lobe_deg` of the specular direction, where a glossy
/// lobe of angular width `lobe_deg` (0: none, a smooth top's delta being given apart) must be
/// drawn.
pub fn views_deg(incidence_deg: f64, lobe_deg: f64) -> Vec<f64> {
    let mut views: Vec<f64> = (-85..=85).map(f64::from).collect();
    if lobe_deg > 0.0 {
        let step = (lobe_deg / 8.0).clamp(0.05, 1.0);
        let n = (4.0 * lobe_deg / step).ceil() as i64;
        views.extend(
            (-n..=n)
                .map(|k| incidence_deg + k as f64 * step)
                .filter(|v| v.abs() <= 85.0),
        );
    }
    views.sort_by(f64::total_cmp);
    views.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
    views
}

/// The readings of a spectral BRDF over `wavelengths_nm`: `colour` read at the standard's
/// geometries and along the L* curve (one call, so that each geometry's reading is the one a
/// reading of it alone gives), `inplane` along `views_deg` at `incidence_deg` (0 ≤ θi ≤ 85°).
/// `mirror_reflectance` is the luminance-weighted mirror reflection to report beside the
/// in-plane BRDF. Stops with [`InstrumentError::Cancelled`] when `cancel` is raised
/// (checked before each geometry and view).
#[allow(clippy::too_many_arguments)]
pub fn read(
    colour: SpectralFn,
    inplane: SpectralFn,
    wavelengths_nm: &[f64],
    standard: Standard,
    incidence_deg: f64,
    views_deg: &[f64],
    mirror_reflectance: f64,
    cancel: &Cancel,
) -> Result<BrdfReadings> {
    check_incidence(incidence_deg)?;
    let (colour, inplane) = (guarded(colour, cancel), guarded(inplane, cancel));
    let settings = Settings::default();
    let geometries = standard.geometries();
    let aspecular = curve_aspecular_deg();
    let mut asked: Vec<Geometry> = geometries.to_vec();
    asked.extend(
        aspecular
            .iter()
            .map(|&a| Geometry::new(CURVE_ILLUMINATION_DEG, a)),
    );
    let views: Vec<Geometry> = views_deg
        .iter()
        .map(|&s| Geometry::new(incidence_deg, incidence_deg - s))
        .collect();
    let (both, brdf) = rayon::join(
        || multiangle::read(&colour, wavelengths_nm, &asked, &settings),
        || multiangle::read(&inplane, wavelengths_nm, &views, &settings),
    );
    if cancel.is_cancelled() {
        return Err(InstrumentError::Cancelled);
    }
    let (mut both, brdf) = (both?, brdf?);
    let curve = both.geometries.split_off(geometries.len());
    let multiangle = both;
    Ok(BrdfReadings {
        standard,
        swatches: multiangle
            .geometries
            .iter()
            .map(|g| Swatch::of_xyz(g.xyz))
            .collect(),
        flop_index: multiangle.flop_index(),
        multiangle,
        inplane: InPlaneBrdf {
            incidence_deg,
            scatter_deg: views_deg.to_vec(),
            brdf_per_sr: brdf
                .geometries
                .iter()
                .map(|g| g.xyz.y / (100.0 * std::f64::consts::PI))
                .collect(),
            mirror_reflectance,
        },
        lightness: LightnessCurve {
            aspecular_deg: aspecular,
            lightness: curve.iter().map(|g| g.lab.l).collect(),
        },
    })
}

/// Refuse an in-plane incidence outside 0–85°.
pub fn check_incidence(incidence_deg: f64) -> Result<()> {
    if !(incidence_deg.is_finite() && (0.0..=85.0).contains(&incidence_deg)) {
        return Err(InstrumentError::Invalid(format!(
            "incidence {incidence_deg}°: the in-plane BRDF's light must be between 0° and 85°"
        )));
    }
    Ok(())
}

/// `brdf`, skipped (zeros) once `cancel` is raised: the reading it feeds is then thrown away.
fn guarded<'a>(
    brdf: SpectralFn<'a>,
    cancel: &'a Cancel,
) -> impl Fn(DVec3, DVec3, &mut [f64]) + Sync + 'a {
    move |wo, wi, out: &mut [f64]| {
        if cancel.is_cancelled() {
            out.fill(0.0);
        } else {
            brdf(wo, wi, out);
        }
    }
}

impl BrdfReadings {
    /// The readings as JSON (see docs/instruments.md, "The lab's readings"):
    /// - `standard`: `"E2194"` or `"E2539"`;
    /// - `multiangle`: one object per geometry, `geometry` (`45as15`), `illumination_deg`,
    ///   `aspecular_deg`, CIELAB D65/10° `L`, `a`, `b`, `C`, `h_deg`, and the swatch
    ///   `srgb_hex` (`#rrggbb`) with `srgb_clipped` (out of the sRGB gamut, clipped);
    /// - `flop_index`: Alman's, or null without 45as15, 45as45 and 45as110;
    /// - `inplane_brdf`: `incidence_deg`, `scatter_deg` (signed, the specular direction at
    ///   +incidence), `brdf_per_sr` (luminance-weighted, D65/10°), `mirror_reflectance` (a
    ///   smooth top's delta at the specular direction, luminance-weighted; 0 otherwise);
    /// - `lightness_curve`: `illumination_deg` (45), `aspecular_deg`, `L`.
    pub fn to_json(&self) -> serde_json::Value {
        serde_json::json!({
            "standard": self.standard.name(),
            "multiangle": self.multiangle.geometries.iter().zip(&self.swatches).map(|(g, s)| {
                geometry_json(g.geometry, g.lab, s)
            }).collect::<Vec<_>>(),
            "flop_index": self.flop_index,
            "inplane_brdf": {
                "incidence_deg": self.inplane.incidence_deg,
                "scatter_deg": self.inplane.scatter_deg,
                "brdf_per_sr": self.inplane.brdf_per_sr,
                "mirror_reflectance": self.inplane.mirror_reflectance,
            },
            "lightness_curve": {
                "illumination_deg": CURVE_ILLUMINATION_DEG,
                "aspecular_deg": self.lightness.aspecular_deg,
                "L": self.lightness.lightness,
            },
        })
    }
}

/// One geometry's entry of `multiangle` in [`BrdfReadings::to_json`]: `geometry`,
/// `illumination_deg`, `aspecular_deg`, `L`, `a`, `b`, `C`, `h_deg`, `srgb_hex`, `srgb_clipped`.
pub fn geometry_json(geometry: Geometry, lab: Lab, swatch: &Swatch) -> serde_json::Value {
    serde_json::json!({
        "geometry": geometry.to_string(),
        "illumination_deg": geometry.illumination_deg,
        "aspecular_deg": geometry.aspecular_deg,
        "L": lab.l, "a": lab.a, "b": lab.b,
        "C": lab.chroma(), "h_deg": lab.hue_deg(),
        "srgb_hex": swatch.hex, "srgb_clipped": swatch.clipped,
    })
}
