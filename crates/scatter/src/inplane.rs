//! One interface for in-plane curves: the ray method, the Kirchhoff approximation and the
//! analytic models all answer "what does this [`Goniometer`] read, at these wavelengths?" with
//! the same call, so that the instruments, the study, the command line and the Python package
//! call one thing whatever the method. Each method keeps its own engine underneath
//! ([`RayEngine::inplane`], [`Kirchhoff::inplane`], [`GaussianModel::inplane`]).
//!
//! Curves come incidence by incidence for a wavelength-independent method (the ray method, the
//! geometric analytic models: one curve per incidence, no wavelength), and wavelength-major then
//! incidence for the wave methods (Kirchhoff, Beckmann-Spizzichino).

use crate::Result;
use crate::analytic::{AnalyticModel, GaussianModel};
use crate::error::ScatterError;
use crate::geometry::{Goniometer, InplaneCurve, label_value};
use crate::kirchhoff::Kirchhoff;
use crate::ray::RayEngine;
use gonio_io::Progress;

/// A scattering method that computes in-plane curves.
pub trait InplaneMethod {
    /// The curves `goniometer` reads at the wavelengths `wavelengths_nm` (ignored by methods
    /// that do not depend on the wavelength; a wave method needs at least one), reporting the
    /// curves (or detectors) done to `progress`.
    fn inplane_curves(
        &self,
        goniometer: &Goniometer,
        wavelengths_nm: &[f64],
        progress: &Progress,
    ) -> Result<Vec<InplaneCurve>>;
}

impl InplaneMethod for RayEngine {
    fn inplane_curves(
        &self,
        goniometer: &Goniometer,
        _wavelengths_nm: &[f64],
        progress: &Progress,
    ) -> Result<Vec<InplaneCurve>> {
        let total = goniometer.incidences.len() as u64;
        goniometer
            .incidences
            .iter()
            .enumerate()
            .map(|(k, &ti)| {
                let curve = self.inplane(ti, &goniometer.scatter, goniometer.half_angle);
                progress.report("ray method", k as u64 + 1, total);
                curve
            })
            .collect()
    }
}

impl InplaneMethod for Kirchhoff {
    fn inplane_curves(
        &self,
        goniometer: &Goniometer,
        wavelengths_nm: &[f64],
        progress: &Progress,
    ) -> Result<Vec<InplaneCurve>> {
        let wavelengths = wavelengths_of(wavelengths_nm, "the Kirchhoff approximation")?;
        self.inplane(
            &wavelengths,
            &goniometer.incidences,
            &goniometer.scatter,
            goniometer.half_angle,
            progress,
        )
    }
}

/// An analytic model of a surface's statistics, as an in-plane method.
#[derive(Debug, Clone, Copy)]
pub struct AnalyticMethod<'a> {
    /// The surface's statistics.
    pub surface: &'a GaussianModel,
    /// The model evaluated.
    pub model: AnalyticModel,
}

impl InplaneMethod for AnalyticMethod<'_> {
    fn inplane_curves(
        &self,
        goniometer: &Goniometer,
        wavelengths_nm: &[f64],
        progress: &Progress,
    ) -> Result<Vec<InplaneCurve>> {
        // A geometric model is the same at every wavelength: one curve per incidence, computed
        // at any wavelength (it is not used).
        let wavelengths = if self.model.is_wave() {
            wavelengths_of(wavelengths_nm, self.model.name())?
        } else {
            vec![550e-9]
        };
        let total = (wavelengths.len() * goniometer.incidences.len()) as u64;
        let mut curves = Vec::with_capacity(total as usize);
        for &l in &wavelengths {
            for &ti in &goniometer.incidences {
                curves.push(self.surface.inplane(
                    self.model,
                    l,
                    ti,
                    &goniometer.scatter,
                    goniometer.half_angle,
                ));
                progress.report(self.model.name(), curves.len() as u64, total);
            }
        }
        Ok(curves)
    }
}

/// Wavelengths in metres from nanometres; a wave method needs at least one, each positive.
fn wavelengths_of(wavelengths_nm: &[f64], method: &str) -> Result<Vec<f64>> {
    if wavelengths_nm.is_empty() {
        return Err(ScatterError::Invalid(format!(
            "{method} needs at least one wavelength"
        )));
    }
    if let Some(bad) = wavelengths_nm
        .iter()
        .find(|l| !(**l > 0.0 && l.is_finite()))
    {
        return Err(ScatterError::Invalid(format!(
            "wavelength {} nm must be positive and finite",
            label_value(*bad)
        )));
    }
    Ok(wavelengths_nm.iter().map(|l| l * 1e-9).collect())
}
