//! What the lab (`gonio lab`, issue #33) shows of an uploaded target, and how a formulation's
//! readings compare with it. A measured BRDF (Cornell's ASTM text, a spectral `.gbrdf` table) is
//! read as a formulation is (`instrument::brdf_readings`: the multi-angle CIELAB with swatches,
//! the flop index, the in-plane luminance BRDF and L* against the aspecular angle); a multi-angle
//! CSV (CIELAB or reflectance factors per geometry, `multiangle_target`'s layouts) gives its
//! points, with swatches and, when it holds 45as15, 45as45 and 45as110, the flop index. The
//! comparison is CIEDE2000 at each of the target's geometries ([`Target::de00`]).

use crate::error::{FormulationError, Result};
use crate::target;
use gonio_color::{Illuminant, Observer, white};
use gonio_instrument::brdf_readings::{self, BrdfReadings, Swatch, geometry_json};
use gonio_instrument::coating_readings::Readings;
use gonio_instrument::multiangle::{self, Geometry, Standard};
use gonio_instrument::multiangle_target::Target;
use gonio_io::Cancel;
use std::path::Path;

/// The width of the lobe the in-plane views of a measured BRDF resolve near the specular
/// direction, degrees ([`brdf_readings::views_deg`]: every 0.25° within 8° of it). A measured
/// table holds no delta, and its own resolution near the specular direction is about 1° in θh
/// (`gonio brdf import`'s default, 90 × 90 × 48), which the views sample four times finer.
pub const MEASURED_LOBE_DEG: f64 = 2.0;

/// What the lab shows of a target.
#[derive(Clone, Debug)]
pub struct LabTarget {
    /// The colours a formulation is compared with: the standard's geometries that the file
    /// gives (all of them for a measured BRDF), in the standard's order.
    pub target: Target,
    /// One swatch per geometry of `target`.
    pub swatches: Vec<Swatch>,
    /// Alman's flop index, when the target has 45as15, 45as45 and 45as110.
    pub flop_index: Option<f64>,
    /// A CSV's geometries that are not the standard's, left out of the comparison (shown, not
    /// dropped silently).
    pub left_out: Vec<Geometry>,
    /// A measured BRDF's readings (in-plane BRDF, L* curve); `None` for a CSV of points.
    pub brdf: Option<BrdfReadings>,
}

/// Read the target `path` for the lab at `standard`'s geometries, by its extension: `.csv`
/// (CIELAB or reflectance factors per geometry: the standard's geometries it holds, at least
/// one), `.astm` or `.gbrdf` (a measured BRDF, imported as `gonio brdf import` does and read
/// at every geometry of the standard and along the in-plane BRDF at `incidence_deg`). Errors
/// name the file.
pub fn read_lab_target(
    path: &Path,
    standard: Standard,
    incidence_deg: f64,
    cancel: &Cancel,
) -> Result<LabTarget> {
    let name = path.display().to_string();
    let invalid = |e: &dyn std::fmt::Display| FormulationError::Invalid(format!("{name}: {e}"));
    if gonio_io::extension(path) == "csv" {
        let all = Target::read_csv(path)?;
        let (kept, left_out): (Vec<Geometry>, Vec<Geometry>) = all
            .geometries()
            .into_iter()
            .partition(|g| standard.geometries().contains(g));
        if kept.is_empty() {
            return Err(invalid(&format!(
                "none of the target's geometries is one of {} (it holds {})",
                standard.name(),
                names(&left_out)
            )));
        }
        let ordered: Vec<Geometry> = standard
            .geometries()
            .iter()
            .copied()
            .filter(|g| kept.contains(g))
            .collect();
        let target = target::at_geometries(all, &ordered)?;
        let reference = white(Illuminant::D65, Observer::Cie1964TenDegree);
        let swatches = target
            .colours
            .iter()
            .map(|(_, lab)| Swatch::of_xyz(lab.to_xyz(reference)))
            .collect();
        let l = |a: f64| {
            target
                .colours
                .iter()
                .find(|(g, _)| *g == Geometry::new(45.0, a))
                .map(|(_, lab)| lab.l)
        };
        let flop_index = match (l(15.0), l(45.0), l(110.0)) {
            (Some(l15), Some(l45), Some(l110)) => Some(multiangle::flop_index(l15, l45, l110)),
            _ => None,
        };
        return Ok(LabTarget {
            target,
            swatches,
            flop_index,
            left_out,
            brdf: None,
        });
    }
    let table = target::measured_table(path)?;
    let gonio_brdf::table::Channels::Spectral { wavelengths_nm } = table.channels() else {
        return Err(invalid(&format!(
            "the lab's readings need a spectral table; this one is {}",
            table.channels().describe()
        )));
    };
    let brdf = |wo, wi, out: &mut [f64]| table.eval_channels(wo, wi, out);
    let views = brdf_readings::views_deg(incidence_deg, MEASURED_LOBE_DEG);
    let readings = brdf_readings::read(
        &brdf,
        &brdf,
        wavelengths_nm,
        standard,
        incidence_deg,
        &views,
        0.0,
        cancel,
    )
    .map_err(|e| match e {
        gonio_instrument::InstrumentError::Cancelled => e.into(),
        e => invalid(&e),
    })?;
    Ok(LabTarget {
        target: Target::from_reading(name, &readings.multiangle),
        swatches: readings.swatches.clone(),
        flop_index: readings.flop_index,
        left_out: Vec::new(),
        brdf: Some(readings),
    })
}

/// `45as15, 45as45`.
fn names(geometries: &[Geometry]) -> String {
    geometries
        .iter()
        .map(Geometry::to_string)
        .collect::<Vec<_>>()
        .join(", ")
}

impl LabTarget {
    /// CIEDE2000 of a formulation's `readings` from the target at each of the target's
    /// geometries, in order ([`Target::de00`]); the readings must be at the same standard.
    pub fn de00(&self, readings: &Readings) -> Result<Vec<(Geometry, f64)>> {
        let de = self.target.de00(&readings.brdf.multiangle)?;
        Ok(self.target.geometries().into_iter().zip(de).collect())
    }

    /// The target as JSON: `source` (the file), `multiangle` (one entry per geometry, as
    /// `BrdfReadings::to_json`'s: `geometry`, `illumination_deg`, `aspecular_deg`, `L`, `a`,
    /// `b`, `C`, `h_deg`, `srgb_hex`, `srgb_clipped`), `flop_index` (or null), `left_out` (a
    /// CSV's geometries not in the standard) and, for a measured BRDF, `standard`,
    /// `inplane_brdf` and `lightness_curve` as a formulation's readings give them.
    pub fn to_json(&self) -> serde_json::Value {
        let mut json = match &self.brdf {
            Some(b) => b.to_json(),
            None => serde_json::json!({
                "multiangle": self.target.colours.iter().zip(&self.swatches)
                    .map(|((g, lab), s)| geometry_json(*g, *lab, s))
                    .collect::<Vec<_>>(),
                "flop_index": self.flop_index,
            }),
        };
        if let Some(map) = json.as_object_mut() {
            map.insert("source".into(), self.target.source.clone().into());
            map.insert(
                "left_out".into(),
                self.left_out
                    .iter()
                    .map(Geometry::to_string)
                    .collect::<Vec<_>>()
                    .into(),
            );
        }
        json
    }
}

/// The comparison as JSON: `de00` [{`geometry`, `de00`}], `mean_de00` and `max_de00`.
pub fn comparison_json(de00: &[(Geometry, f64)]) -> serde_json::Value {
    let values: Vec<f64> = de00.iter().map(|(_, d)| *d).collect();
    serde_json::json!({
        "de00": de00.iter().map(|(g, d)| serde_json::json!({
            "geometry": g.to_string(), "de00": d,
        })).collect::<Vec<_>>(),
        "mean_de00": values.iter().sum::<f64>() / values.len().max(1) as f64,
        "max_de00": values.iter().copied().fold(0.0, f64::max),
    })
}
