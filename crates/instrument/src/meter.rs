//! A gloss and appearance meter's readings of a height map or a tabulated BRDF, with the
//! warnings of the validity checks: what `gonio gloss` and the Python package's `gonio.gloss`
//! report, computed once here so that both give the same numbers. A height map scatters light
//! by the ray method (with shadowing and masking) or by the scalar Kirchhoff approximation over
//! the largest spot that fits; a table is read photometrically, as the luminance of its channels.

use crate::error::Result;
use crate::gloss::{BrdfSpecimen, GlossReport, measure};
use crate::specimens::{KirchhoffSpecimen, RaySpecimen};
use crate::validity;
use gonio_brdf::table::BrdfTable;
use gonio_brdf::{Brdf, Ior};
use gonio_scatter::kirchhoff::{Kirchhoff, KirchhoffOptions};
use gonio_scatter::ray::{RayEngine, RayOptions};
use gonio_surface::HeightMap;

/// How a height map scatters light for the meters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MapMethod {
    /// Geometric optics on the map's facets, with shadowing and masking.
    Ray,
    /// The scalar Kirchhoff approximation at this wavelength (nm) over the largest spot that
    /// fits the map (its diffraction, about λ/(L cos θ), must stay inside the receptors: at 85°
    /// a 0.5 mm spot or more).
    Kirchhoff {
        /// Wavelength, nm.
        wavelength_nm: f64,
    },
}

/// The readings and the warnings of a reading.
#[derive(Debug, Clone)]
pub struct MeterReading {
    /// Gloss, haze and DOI.
    pub report: GlossReport,
    /// Where the reading cannot be trusted (`validity`).
    pub warnings: Vec<String>,
}

/// The meters on a coating of refractive index `index` whose top surface is `map`.
pub fn read_height_map(map: &HeightMap, method: MapMethod, index: f64) -> Result<MeterReading> {
    let mut warnings = validity::check_index(index)?;
    let meter = validity::meter_readings();
    let report = match method {
        MapMethod::Ray => {
            let levelled = gonio_surface::ops::level(map)?;
            let sq = gonio_surface::stats::height_parameters(&levelled).0;
            warnings.extend(validity::ray_warnings(
                sq,
                validity::PHOTOMETRIC_WAVELENGTH,
                &meter,
            ));
            let options = RayOptions {
                ior: Ior::Dielectric(index),
                ..RayOptions::default()
            };
            let engine = RayEngine::new(map, options)?;
            measure(&RaySpecimen { engine: &engine })?
        }
        MapMethod::Kirchhoff { wavelength_nm } => {
            if !(wavelength_nm.is_finite() && wavelength_nm > 0.0) {
                return Err(crate::InstrumentError::Invalid(format!(
                    "wavelength {wavelength_nm} nm: must be positive"
                )));
            }
            let wavelength = wavelength_nm * 1e-9;
            let engine = Kirchhoff::new(map, KirchhoffOptions::new(Ior::Dielectric(index)))?;
            warnings.extend(validity::kirchhoff_warnings(
                engine.spot().diameter,
                wavelength,
                &meter,
            ));
            measure(&KirchhoffSpecimen {
                engine: &engine,
                wavelength,
            })?
        }
    };
    warnings.extend(validity::doi_warning(&report));
    Ok(MeterReading { report, warnings })
}

/// The meters on a tabulated BRDF. Gloss is a photometric reading: the luminance (Rec. 709 /
/// sRGB Y) of the table's linear sRGB.
pub fn read_table(table: &BrdfTable) -> Result<MeterReading> {
    let specimen = BrdfSpecimen::new(|wi, wo| {
        let f = table.eval(wo, wi);
        0.2126 * f.x + 0.7152 * f.y + 0.0722 * f.z
    });
    let report = measure(&specimen)?;
    let warnings = validity::doi_warning(&report).into_iter().collect();
    Ok(MeterReading { report, warnings })
}
