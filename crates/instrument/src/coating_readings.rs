//! Every reading the lab shows of a formulation (`gonio lab`, issue #33), in one call fast
//! enough to follow a slider and that a newer request can cancel: the gloss meter (ISO 2813
//! gloss at 20/60/85°, ASTM E430 haze and DOI with DOI's Monte Carlo uncertainty, the 20° haze
//! and its log scale), the multi-angle colour at ASTM E2194 or E2539 with each geometry's sRGB
//! swatch and Alman's flop index, the directional-hemispherical reflectance at 550 nm, the
//! in-plane luminance BRDF at a chosen incidence with a smooth top's mirror given apart, and L*
//! against the aspecular angle ([`crate::brdf_readings`]). The lab, the CLI and Python call
//! [`readings`]; `Readings::to_json` is what the lab sends to its page.
//!
//! Each estimate is the one the studies make ([`coating_study::read_coating`]'s gloss meter and
//! multi-angle reading, [`crate::coating_summary::summarise`]'s albedo) with fewer walks
//! ([`ReadingsRequest::default`], docs/instruments.md, "The lab's readings", gives the walks,
//! the time and the noise they leave), and with common random numbers: every estimate's
//! streams are seeded by its geometry or quadrature point and the request's seed, never by the
//! coating, so that two nearby formulations' readings differ by their optics, not by noise.

use crate::brdf_readings::{self, BrdfReadings};
use crate::coating_study::{self, CoatingSpecimen};
use crate::coating_summary::{ALBEDO_ANGLES_DEG, SUMMARY_NM};
use crate::error::{InstrumentError, Result};
use crate::gloss::{self, GlossReport};
use crate::multiangle::Standard;
use gonio_coating::system::Coating;
use gonio_color::{Illuminant, Observer, SpectralToXyz};
use gonio_io::Cancel;

/// What to read, and with how many walks.
#[derive(Clone, Debug, PartialEq)]
pub struct ReadingsRequest {
    /// The multi-angle geometries.
    pub standard: Standard,
    /// The light's polar angle of the in-plane BRDF, degrees (0–85).
    pub incidence_deg: f64,
    /// The bands of the colour readings, nm (increasing; 550 nm among them, the albedo's).
    pub wavelengths_nm: Vec<f64>,
    /// Walks per multi-angle geometry and per point of the L* curve.
    pub walks: usize,
    /// Walks per view of the in-plane BRDF.
    pub brdf_walks: usize,
    /// Walks per quadrature point of the gloss meter (at least 2 for DOI's uncertainty).
    pub gloss_walks: usize,
    /// The gloss meter's Gauss-Legendre orders per axis over the source and over each
    /// receptor (the light from inside the coat): [`CoatingSpecimen::with_orders`]; the studies
    /// take (4, 6).
    pub gloss_orders: (usize, usize),
    /// Outgoing directions, one walk each, per incidence of the albedo.
    pub albedo_samples: usize,
    /// The streams' seed: the same seed repeats a reading bit for bit, another gives an
    /// independent one (0 is the studies' and the summary's).
    pub seed: u64,
}

impl Default for ReadingsRequest {
    /// E2194, the in-plane BRDF at 45°, 31 bands (400–700 nm), and the walks that keep a reading
    /// of every `examples/coatings` formulation well under 300 ms on two cores: 256 per
    /// multi-angle geometry, 32 per view of the in-plane BRDF, 8 per point of the gloss meter
    /// with 4 × 4 source directions and 3 × 3 receptor points, and 2048 albedo directions
    /// (docs/instruments.md, "The lab's readings": time and noise).
    fn default() -> Self {
        ReadingsRequest {
            standard: Standard::E2194,
            incidence_deg: 45.0,
            wavelengths_nm: gonio_coating::system::default_bands(),
            walks: 256,
            brdf_walks: 32,
            gloss_walks: 8,
            gloss_orders: (4, 3),
            albedo_samples: 2048,
            seed: 0,
        }
    }
}

/// What [`readings`] gives.
#[derive(Clone, Debug)]
pub struct Readings {
    /// The request the readings answer.
    pub request: ReadingsRequest,
    /// Gloss, haze and DOI at 555 nm ([`gloss::measure`] on a [`CoatingSpecimen`]); DOI's
    /// uncertainty is the walks' (the jackknife over groups of them).
    pub gloss: GlossReport,
    /// The directional-hemispherical reflectance at [`SUMMARY_NM`], the mirror reflection
    /// included, at each of [`ALBEDO_ANGLES_DEG`]: (incidence °, reflectance).
    pub albedo: Vec<(f64, f64)>,
    /// The multi-angle colour, swatches, flop index, in-plane BRDF and L* curve.
    pub brdf: BrdfReadings,
}

/// Read `coating` as `request` asks, stopping with [`InstrumentError::Cancelled`] within one
/// estimate (a geometry, a view, a source direction of the gloss meter, an albedo incidence)
/// of `cancel` being raised.
///
/// At the same walks and seed the gloss and multi-angle readings are
/// [`coating_study::read_coating`]'s and the albedo [`crate::coating_summary::summarise`]'s (its
/// `16 × walks` directions), to rounding.
pub fn readings(coating: &Coating, request: &ReadingsRequest, cancel: &Cancel) -> Result<Readings> {
    if cancel.is_cancelled() {
        return Err(InstrumentError::Cancelled);
    }
    let r = request;
    if r.walks == 0 || r.brdf_walks == 0 || r.gloss_walks == 0 || r.albedo_samples == 0 {
        return Err(InstrumentError::Invalid(
            "readings: at least one walk per estimate (walks, brdf_walks, gloss_walks, \
             albedo_samples)"
                .into(),
        ));
    }
    let at = r
        .wavelengths_nm
        .iter()
        .position(|&w| w == SUMMARY_NM)
        .ok_or_else(|| {
            InstrumentError::Invalid(format!(
                "readings: the bands must include {SUMMARY_NM} nm (the albedo's)"
            ))
        })?;
    brdf_readings::check_incidence(r.incidence_deg)?;
    coating.check(&r.wavelengths_nm)?;
    let evaluator = coating.evaluator(&r.wavelengths_nm)?;
    let specimen = CoatingSpecimen::new(coating, 555.0, r.gloss_walks)?
        .with_orders(r.gloss_orders.0, r.gloss_orders.1)?
        .with_seed(r.seed)
        .with_cancel(cancel.clone());
    // The smooth top's mirror at the in-plane incidence, weighted as the BRDF is (Y of D65 and
    // the 10° observer; the reflectance factor's Y over 100).
    let to_xyz = SpectralToXyz::new(
        &r.wavelengths_nm,
        Illuminant::D65,
        Observer::Cie1964TenDegree,
    )
    .map_err(|e| InstrumentError::Invalid(format!("readings: bands: {e}")))?;
    let mirror = to_xyz
        .xyz(&evaluator.mirror(r.incidence_deg.to_radians().cos()))
        .map_err(|e| InstrumentError::Invalid(e.to_string()))?
        .y
        / 100.0;
    let lobe_deg = coating
        .roughness
        .map_or(0.0, |m| 2.0 * m.alpha_x.max(m.alpha_y).atan().to_degrees());
    let views = brdf_readings::views_deg(r.incidence_deg, lobe_deg);
    let colour = coating_study::walked_brdf(&evaluator, r.walks, r.seed);
    let inplane = coating_study::walked_brdf(&evaluator, r.brdf_walks, r.seed);
    let (gloss, (brdf, albedo)) = rayon::join(
        || gloss::measure(&specimen),
        || {
            rayon::join(
                || {
                    brdf_readings::read(
                        &colour,
                        &inplane,
                        &r.wavelengths_nm,
                        r.standard,
                        r.incidence_deg,
                        &views,
                        mirror,
                        cancel,
                    )
                },
                || {
                    ALBEDO_ANGLES_DEG
                        .iter()
                        .map(|&d| {
                            if cancel.is_cancelled() {
                                return Err(InstrumentError::Cancelled);
                            }
                            let cos = d.to_radians().cos();
                            Ok((d, evaluator.albedo(cos, r.albedo_samples)[at]))
                        })
                        .collect::<Result<Vec<_>>>()
                },
            )
        },
    );
    if cancel.is_cancelled() {
        return Err(InstrumentError::Cancelled);
    }
    Ok(Readings {
        request: r.clone(),
        gloss: gloss?,
        albedo: albedo?,
        brdf: brdf?,
    })
}

impl Readings {
    /// The readings as JSON, [`BrdfReadings::to_json`]'s fields and:
    /// - `gloss`: `gloss_20_gu`, `gloss_60_gu`, `gloss_85_gu` (ISO 2813, GU), `haze_hu` and
    ///   `haze_wide_hu` (ASTM E430 Method A at 30°, ±2° and ±5°, HU), `haze_20_hu` and
    ///   `haze_20_log_hu` (Method B at 20°, linear and the log scale of haze meters),
    ///   `haze_d4039_gu` (60° − 20° gloss), `doi` and `doi_uncertainty` (ASTM E430, 0–100; the
    ///   walks' standard error), all at 555 nm;
    /// - `albedo_nm` (550) and `albedo`: [{`theta_i_deg`, `albedo`}], the
    ///   directional-hemispherical reflectance;
    /// - `walks`: {`per_geometry`, `per_brdf_view`, `per_gloss_point`, `albedo_samples`,
    ///   `seed`}, what the estimates took.
    pub fn to_json(&self) -> serde_json::Value {
        let g = &self.gloss;
        let r = &self.request;
        let mut json = self.brdf.to_json();
        let extra = serde_json::json!({
            "gloss": {
                "gloss_20_gu": g.gu20, "gloss_60_gu": g.gu60, "gloss_85_gu": g.gu85,
                "haze_hu": g.haze, "haze_wide_hu": g.haze_wide,
                "haze_20_hu": g.haze_20, "haze_20_log_hu": g.haze_20_log,
                "haze_d4039_gu": g.haze_d4039,
                "doi": g.doi, "doi_uncertainty": g.doi_uncertainty,
            },
            "albedo_nm": SUMMARY_NM,
            "albedo": self.albedo.iter().map(|(d, a)| serde_json::json!({
                "theta_i_deg": d, "albedo": a,
            })).collect::<Vec<_>>(),
            "walks": {
                "per_geometry": r.walks, "per_brdf_view": r.brdf_walks,
                "per_gloss_point": r.gloss_walks, "albedo_samples": r.albedo_samples,
                "seed": r.seed,
            },
        });
        if let (Some(map), serde_json::Value::Object(extra)) = (json.as_object_mut(), extra) {
            map.extend(extra);
        }
        json
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A request without walks or without the albedo's band is refused, saying why.
    #[test]
    fn bad_requests_are_refused() {
        let wl = gonio_coating::system::default_bands();
        let coating = gonio_coating::description::parse(
            "[coat]\nindex = 1.5\nthickness_um = 40\n[base]\nkind = \"diffuse\"\nreflectance = 0.3\n",
            &wl,
        )
        .unwrap();
        let none = Cancel::default();
        let e = readings(
            &coating,
            &ReadingsRequest {
                gloss_walks: 0,
                ..Default::default()
            },
            &none,
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("gloss_walks"), "{e}");
        let e = readings(
            &coating,
            &ReadingsRequest {
                wavelengths_nm: vec![400.0, 500.0, 600.0, 700.0],
                ..Default::default()
            },
            &none,
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("550"), "{e}");
        let e = readings(
            &coating,
            &ReadingsRequest {
                incidence_deg: 88.0,
                ..Default::default()
            },
            &none,
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("85"), "{e}");
    }
}
