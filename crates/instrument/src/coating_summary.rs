//! A coating's optics at a glance, as `gonio coating info` prints them and the Python package
//! returns them: the coat's index, the base's reflectance spectrum, the coat's mirror
//! reflectance at the gloss angles, the directional-hemispherical reflectance, and the
//! multi-angle colour (ASTM E2194, D65/10°) with Alman's flop index. One call, so that every
//! front end reports the same numbers.

use crate::coating_study::multiangle_reading;
use crate::error::Result;
use crate::multiangle::{E2194, MultiangleReading};
use gonio_coating::system::Coating;

/// The gloss meter's angles at which the summary gives the coat's mirror reflectance, degrees.
pub const GLOSS_ANGLES_DEG: [f64; 3] = [20.0, 60.0, 85.0];
/// The incidences at which the summary gives the directional-hemispherical reflectance, degrees.
pub const ALBEDO_ANGLES_DEG: [f64; 3] = [0.0, 45.0, 75.0];
/// The wavelength of the mirror and directional-hemispherical reflectances, nm (near the
/// photopic peak; the coat's reflection is nearly grey).
pub const SUMMARY_NM: f64 = 550.0;

/// [`summarise`]'s figures.
#[derive(Clone, Debug)]
pub struct CoatingSummary {
    /// The coat's refractive index at 400, 550 and 700 nm: (nm, n).
    pub coat_index: Vec<(f64, f64)>,
    /// The base's reflectance under the coat at each wavelength: (nm, reflectance factor).
    pub base_reflectance: Vec<(f64, f64)>,
    /// The coat's mirror reflectance at [`SUMMARY_NM`] and each of [`GLOSS_ANGLES_DEG`]:
    /// (incidence °, reflectance); 0 for a rough top, whose reflection is spread.
    pub specular: Vec<(f64, f64)>,
    /// The directional-hemispherical reflectance at [`SUMMARY_NM`] and each of
    /// [`ALBEDO_ANGLES_DEG`]: (incidence °, reflectance).
    pub albedo: Vec<(f64, f64)>,
    /// The multi-angle colour at the ASTM E2194 geometries.
    pub multiangle: MultiangleReading,
}

impl CoatingSummary {
    /// The summary as JSON, as `gonio coating info --json` prints it (without the file's name):
    /// `coat_index` {"400", "550", "700"}, `base_reflectance` [{nm, reflectance}], `specular`
    /// [{theta_deg, reflectance}], `albedo` [{theta_i_deg, albedo}], `multiangle` [{name, L, a,
    /// b, C, h_deg}] and `flop_index`.
    pub fn to_json(&self) -> serde_json::Value {
        let pairs = |v: &[(f64, f64)], x: &str, y: &str| {
            v.iter()
                .map(|(a, b)| serde_json::json!({ x: a, y: b }))
                .collect::<Vec<_>>()
        };
        let index: serde_json::Map<String, serde_json::Value> = self
            .coat_index
            .iter()
            .map(|(w, n)| (format!("{w}"), serde_json::json!(n)))
            .collect();
        serde_json::json!({
            "coat_index": index,
            "base_reflectance": pairs(&self.base_reflectance, "nm", "reflectance"),
            "specular": pairs(&self.specular, "theta_deg", "reflectance"),
            "albedo": pairs(&self.albedo, "theta_i_deg", "albedo"),
            "multiangle": self.multiangle.geometries.iter().map(|g| serde_json::json!({
                "name": g.geometry.to_string(), "L": g.lab.l, "a": g.lab.a, "b": g.lab.b,
                "C": g.lab.chroma(), "h_deg": g.lab.hue_deg(),
            })).collect::<Vec<_>>(),
            "flop_index": self.multiangle.flop_index(),
        })
    }
}

/// The summary of `coating` over `wavelengths_nm` (which must hold [`SUMMARY_NM`]), with `walks`
/// random walks per multi-angle geometry and 16 × `walks` outgoing directions per albedo (a
/// rough top or flakes; a smooth coat over a diffuse base is exact).
pub fn summarise(
    coating: &Coating,
    wavelengths_nm: &[f64],
    walks: usize,
) -> Result<CoatingSummary> {
    let at = wavelengths_nm
        .iter()
        .position(|&w| w == SUMMARY_NM)
        .ok_or_else(|| {
            crate::InstrumentError::Invalid(format!(
                "the summary's wavelengths must include {SUMMARY_NM} nm"
            ))
        })?;
    let evaluator = coating.evaluator(wavelengths_nm)?;
    let base_reflectance = wavelengths_nm
        .iter()
        .map(|&w| Ok((w, coating.base.reflectance(w)?)))
        .collect::<Result<Vec<_>>>()?;
    let cos = |deg: f64| deg.to_radians().cos();
    Ok(CoatingSummary {
        coat_index: [400.0, SUMMARY_NM, 700.0]
            .iter()
            .map(|&w| (w, coating.coat.index.at(w)))
            .collect(),
        base_reflectance,
        specular: GLOSS_ANGLES_DEG
            .iter()
            .map(|&d| (d, evaluator.mirror(cos(d))[at]))
            .collect(),
        albedo: ALBEDO_ANGLES_DEG
            .iter()
            .map(|&d| (d, evaluator.albedo(cos(d), 16 * walks)[at]))
            .collect(),
        multiangle: multiangle_reading(&evaluator, wavelengths_nm, &E2194, walks, 0)?,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A smooth coat of index 1.5 over a grey diffuse base: the mirror reflectance is
    /// Fresnel's (0.04 at normal incidence, rising toward grazing), the base reflectance is the
    /// description's, and the albedo lies between the coat's reflection and that plus the base.
    #[test]
    fn summary_of_a_smooth_coat_over_grey() {
        let wl: Vec<f64> = (0..31).map(|i| 400.0 + 10.0 * i as f64).collect();
        let coating = gonio_coating::description::parse(
            "[coat]\nindex = 1.5\nthickness_um = 40\n[base]\nkind = \"diffuse\"\nreflectance = 0.3\n",
            &wl,
        )
        .unwrap();
        let s = summarise(&coating, &wl, 64).unwrap();
        assert_eq!(s.coat_index[1], (550.0, 1.5));
        assert!(s.base_reflectance.iter().all(|&(_, r)| r == 0.3));
        let fresnel = |deg: f64| gonio_brdf::fresnel::dielectric(deg.to_radians().cos(), 1.5);
        for &(d, r) in &s.specular {
            assert!(
                (r - fresnel(d)).abs() < 1e-12,
                "{d}°: {r} vs {}",
                fresnel(d)
            );
        }
        for &(d, a) in &s.albedo {
            let mirror = fresnel(d);
            assert!(a > mirror && a < mirror + 0.3, "{d}°: albedo {a}");
        }
        assert_eq!(s.multiangle.geometries.len(), E2194.len());
        assert!(summarise(&coating, &[500.0, 600.0], 64).is_err());
    }
}
