//! The roughness study: for a series of surfaces, in-plane curves by the ray method and the
//! Kirchhoff approximation at the STARR geometry, ISO 25178 statistics, and the peak height and
//! width of every curve, so that appearance can be followed across the series.

use crate::compare::{Peak, peak};
use crate::error::{InstrumentError, Result};
use crate::gloss::{GlossReport, measure};
use crate::specimens::{KirchhoffSpecimen, RaySpecimen};
use crate::validity;
use gonio_brdf::Ior;
use gonio_io::Progress;
use gonio_scatter::kirchhoff::{Kirchhoff, KirchhoffOptions};
use gonio_scatter::ray::{RayEngine, RayOptions};
use gonio_scatter::{Goniometer, InplaneCurve, InplaneMethod};
use gonio_surface::HeightMap;
use gonio_surface::stats::{Statistics, statistics};

/// Wavelength of the Kirchhoff gloss readings: 550 nm, near the peak of the photopic response.
pub const GLOSS_WAVELENGTH: f64 = 550e-9;

/// What to compute for every sample.
#[derive(Debug, Clone, PartialEq)]
pub struct StudyConfig {
    /// Refractive index of the coating.
    pub ior: f64,
    /// The in-plane goniometer the curves are read at.
    pub goniometer: Goniometer,
    /// Wavelengths of the Kirchhoff curves, nm.
    pub wavelengths_nm: Vec<f64>,
    /// Whether to compute Kirchhoff curves (the ray method is always computed).
    pub kirchhoff: bool,
}

impl StudyConfig {
    /// The NIST STARR geometry: incidence 20/45/60/70°, scatter -75..75° in 1° steps, a 1.4°
    /// detector; wavelengths 500, 550, 600 nm; index 1.55.
    pub fn starr() -> Self {
        StudyConfig {
            ior: 1.55,
            goniometer: Goniometer::starr(),
            wavelengths_nm: vec![500.0, 550.0, 600.0],
            kirchhoff: true,
        }
    }
}

/// One sample of the study.
pub struct Sample {
    pub label: String,
    pub map: HeightMap,
}

/// What the study found for one sample.
#[derive(Debug, Clone)]
pub struct SampleResult {
    pub label: String,
    pub statistics: Statistics,
    /// Gloss, haze and DOI by the ray method.
    pub gloss_ray: GlossReport,
    /// Gloss, haze and DOI by the Kirchhoff approximation at 550 nm (when computed).
    pub gloss_kirchhoff: Option<GlossReport>,
    /// What could not be computed for this sample, and why.
    pub notes: Vec<String>,
    /// Readings that were computed but should not be trusted, and why (see [`crate::validity`]).
    pub warnings: Vec<String>,
    /// Ray curves (one per incidence), then Kirchhoff curves (per wavelength and incidence).
    pub curves: Vec<InplaneCurve>,
}

/// The peak of one curve of one sample.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct PeakRow {
    pub label: String,
    pub sq_m: f64,
    pub method: String,
    pub wavelength_nm: Option<f64>,
    pub incidence_deg: f64,
    pub peak: Peak,
}

impl SampleResult {
    /// The peak (position, height, FWHM) of each curve with a positive maximum.
    pub fn peaks(&self) -> Vec<PeakRow> {
        self.curves
            .iter()
            .filter_map(|c| {
                Some(PeakRow {
                    label: self.label.clone(),
                    sq_m: self.statistics.sq,
                    method: c.method.clone(),
                    wavelength_nm: c.wavelength_nm,
                    incidence_deg: c.incidence_deg,
                    peak: peak(c)?,
                })
            })
            .collect()
    }
}

/// Run the study over `samples`; `progress` is told what each step (statistics, ray method,
/// Kirchhoff, per sample) is about to do and how many are done. Each sample's
/// `warnings` name the readings its methods cannot be trusted for ([`crate::validity`]): the ray
/// method where the map is smooth for the wavelength, Kirchhoff where the map is too small.
pub fn run(
    samples: &[Sample],
    config: &StudyConfig,
    progress: &Progress,
) -> Result<Vec<SampleResult>> {
    let gonio = &config.goniometer;
    if gonio.incidences.is_empty() || gonio.scatter.is_empty() {
        return Err(InstrumentError::Invalid(
            "the study needs incidence and scatter angles".into(),
        ));
    }
    // An index that is not positive is refused; the warning for one below 1 is the caller's to
    // give once (`validity::check_index`), not once per sample.
    validity::check_index(config.ior)?;
    let ior = Ior::Dielectric(config.ior);
    // The ray curves are judged at the longest wavelength the study compares them with (the
    // smallest Rayleigh roughness), the meter readings at 550 nm.
    let longest = config
        .wavelengths_nm
        .iter()
        .map(|w| w * 1e-9)
        .fold(validity::PHOTOMETRIC_WAVELENGTH, f64::max);
    let meter = validity::meter_readings();
    let detectors = validity::inplane_readings(&gonio.incidences_deg(), gonio.half_angle);
    let kirchhoff = config.kirchhoff && !config.wavelengths_nm.is_empty();
    let steps = if kirchhoff { 3 } else { 2 };
    let total = (samples.len() * steps) as u64;
    samples
        .iter()
        .enumerate()
        .map(|(i, s)| {
            let step = |k: usize, what: &str| {
                progress.report(
                    &format!("{}: {what}", s.label),
                    (i * steps + k) as u64,
                    total,
                )
            };
            step(0, "statistics");
            let stats = statistics(&s.map)?;
            let mut warnings = Vec::new();
            warnings.extend(
                validity::ray_warnings(stats.sq, GLOSS_WAVELENGTH, &meter)
                    .into_iter()
                    .map(|w| format!("ray gloss: {w}")),
            );
            warnings.extend(
                validity::ray_warnings(stats.sq, longest, &detectors)
                    .into_iter()
                    .map(|w| format!("ray curves: {w}")),
            );
            step(1, "ray method");
            let engine = RayEngine::new(
                &s.map,
                RayOptions {
                    ior,
                    ..RayOptions::default()
                },
            )?;
            let gloss_ray = measure(&RaySpecimen { engine: &engine })?;
            warnings.extend(validity::doi_warning(&gloss_ray).map(|w| format!("ray gloss: {w}")));
            let silent = Progress::silent();
            let mut curves = engine.inplane_curves(gonio, &[], &silent)?;
            let mut gloss_kirchhoff = None;
            let mut notes = Vec::new();
            if kirchhoff {
                step(2, "Kirchhoff");
                let k = Kirchhoff::new(&s.map, KirchhoffOptions::new(ior))?;
                let spot = k.spot().diameter;
                warnings.extend(
                    validity::kirchhoff_warnings(spot, GLOSS_WAVELENGTH, &meter)
                        .into_iter()
                        .map(|w| format!("Kirchhoff gloss: {w}")),
                );
                warnings.extend(
                    validity::kirchhoff_warnings(spot, longest, &detectors)
                        .into_iter()
                        .map(|w| format!("Kirchhoff curves: {w}")),
                );
                curves.extend(k.inplane_curves(gonio, &config.wavelengths_nm, &silent)?);
                // Gloss needs the whole receptor cones at 20–85°: a rough map may be too coarse
                // for the Kirchhoff sampling there even where the in-plane curves could be
                // computed; the sample then has no Kirchhoff gloss, and a note says why.
                match measure(&KirchhoffSpecimen {
                    engine: &k,
                    wavelength: GLOSS_WAVELENGTH,
                }) {
                    Ok(g) => gloss_kirchhoff = Some(g),
                    Err(e) => notes.push(format!("no Kirchhoff gloss: {e}")),
                }
            }
            Ok(SampleResult {
                label: s.label.clone(),
                statistics: stats,
                gloss_ray,
                gloss_kirchhoff,
                notes,
                warnings,
                curves,
            })
        })
        .collect()
}
