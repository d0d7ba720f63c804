//! What a match minimises ([`Objective`]): the mean CIEDE2000 over the target's geometries, or —
//! when the target gives reflectance factors — the rms difference of reflectance factors over
//! its bands and geometries ([`reflectance_differences`]), the spectral match of colour-matching
//! programs.
//!
//! Why the rms of R and not of K/S: the spectral match is least squares, which is the maximum-
//! likelihood fit when the residuals are independent with equal variance. An instrument's noise is
//! additive in the reflectance factor it measures, of about the same size at every band; K/S =
//! (1 − R)²/2R amplifies it by |d(K/S)/dR| = (1 − R²)/2R², 12 at R = 0.2 and 200 at R = 0.05, so a
//! fit in K/S is dominated by the darkest bands (the absorption bands, where the instrument is
//! least sure). K/S is what makes Kubelka–Munk linear in the concentrations for an opaque layer
//! (Duncan's mixing), which classical recipe algorithms exploit to solve for the concentrations
//! algebraically (E. Allen, "Colorant formulation and shading", ch. 7 of F. Grum & C. J. Bartleson
//! (eds.), *Optical Radiation Measurements*, vol. 2, Academic Press, 1980; R. S. Berns, *Billmeyer
//! and Saltzman's Principles of Color Technology*, 4th ed., Wiley, 2019, ch. 9); gonio's match is
//! a nonlinear search that reads the whole coating, which needs no linearity, so it fits what is
//! measured. A spectral match that succeeds is not metameric: equal spectra look alike under every
//! illuminant (Berns, ch. 9).

use crate::error::{FormulationError, Result};
use gonio_color::Spectrum;
use gonio_instrument::multiangle::MultiangleReading;
use gonio_instrument::multiangle_target::{Spectra, Target};
use std::fmt;
use std::str::FromStr;

/// What a match minimises.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Objective {
    /// Mean ΔE00 over the target's geometries (plus the weighted gloss differences).
    #[default]
    De00,
    /// rms ΔR (reflectance factor) over the target's bands and geometries.
    Spectral,
}

impl Objective {
    /// The objective's units per ΔE00, to set a stop in ΔE00 for either: 1 for `De00`, 0.01 for
    /// `Spectral`. An rms ΔR of 0.01 is about one ΔE00 at mid lightness: at Y = 0.18 (L* 50),
    /// dL*/dY = 116/(3 Y^(2/3)) = 121, so ΔR 0.01 moves L* by 1.2, and ΔE00 ≈ ΔL* there (S_L = 1
    /// at L* 50, CIE 142:2001).
    pub fn per_de00(self) -> f64 {
        match self {
            Objective::De00 => 1.0,
            Objective::Spectral => 0.01,
        }
    }
}

impl fmt::Display for Objective {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Objective::De00 => "de00",
            Objective::Spectral => "spectral",
        })
    }
}

impl FromStr for Objective {
    type Err = FormulationError;

    /// `de00` or `spectral`.
    fn from_str(s: &str) -> Result<Self> {
        match s.trim().to_ascii_lowercase().as_str() {
            "de00" => Ok(Objective::De00),
            "spectral" => Ok(Objective::Spectral),
            other => Err(FormulationError::Invalid(format!(
                "objective '{other}': de00 (mean CIEDE2000) or spectral (rms of reflectance \
                 factors)"
            ))),
        }
    }
}

/// The objective a front end asks for: `auto` (the default: spectral where the target gives
/// reflectance factors — a spectral CSV, a `.astm`, a `.gbrdf` — and no gloss readings are
/// matched, mean ΔE00 otherwise), or one of [`Objective`] given explicitly.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ObjectiveChoice {
    #[default]
    Auto,
    Given(Objective),
}

impl ObjectiveChoice {
    /// The objective for `target`, with `gloss_readings` gloss readings to match.
    pub fn resolve(self, target: &Target, gloss_readings: usize) -> Objective {
        match self {
            ObjectiveChoice::Given(o) => o,
            ObjectiveChoice::Auto if target.spectra.is_some() && gloss_readings == 0 => {
                Objective::Spectral
            }
            ObjectiveChoice::Auto => Objective::De00,
        }
    }
}

impl fmt::Display for ObjectiveChoice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ObjectiveChoice::Auto => f.write_str("auto"),
            ObjectiveChoice::Given(o) => o.fmt(f),
        }
    }
}

impl FromStr for ObjectiveChoice {
    type Err = FormulationError;

    /// `auto`, `de00` or `spectral`.
    fn from_str(s: &str) -> Result<Self> {
        if s.trim().eq_ignore_ascii_case("auto") {
            return Ok(ObjectiveChoice::Auto);
        }
        s.parse().map(ObjectiveChoice::Given).map_err(|_| {
            FormulationError::Invalid(format!(
                "objective '{}': auto (spectral where the target has spectra, else de00), \
                 de00 (mean CIEDE2000) or spectral (rms of reflectance factors)",
                s.trim()
            ))
        })
    }
}

/// The target's reflectance factors; an error naming it when it gives CIELAB only.
pub fn spectra_of(target: &Target) -> Result<&Spectra> {
    target.spectra.as_ref().ok_or_else(|| {
        FormulationError::Invalid(format!(
            "{}: the target gives CIELAB only; a spectral match needs its reflectance factors \
             (a CSV of R_400nm ... R_700nm per geometry, or a measured table)",
            target.source
        ))
    })
}

/// `reading` − `target` in reflectance factor at each of the target's bands within the reading's
/// wavelengths (the reading linearly interpolated to them) and each of the target's geometries,
/// geometry by geometry. An error names the target when it holds no spectra, when none of its
/// bands lies within the reading's, or when the reading lacks one of its geometries.
pub fn reflectance_differences(target: &Target, reading: &MultiangleReading) -> Result<Vec<f64>> {
    let spectra = spectra_of(target)?;
    let (first, last) = match reading.wavelengths_nm.as_slice() {
        [first, .., last] => (*first, *last),
        _ => {
            return Err(FormulationError::Invalid(
                "a spectral match reads the coating at two wavelengths at least".into(),
            ));
        }
    };
    let bands: Vec<f64> = spectra
        .wavelengths_nm
        .iter()
        .copied()
        .filter(|w| (first..=last).contains(w))
        .collect();
    if bands.is_empty() {
        return Err(FormulationError::Invalid(format!(
            "{}: no band of the target lies within the match's {first}–{last} nm",
            target.source
        )));
    }
    let mut d = Vec::with_capacity(bands.len() * target.colours.len());
    for ((g, _), factors) in target.colours.iter().zip(&spectra.reflectance_factors) {
        let read = reading
            .at(*g)
            .ok_or_else(|| FormulationError::Invalid(format!("{g} was not read")))?;
        let model = Spectrum::new(
            reading.wavelengths_nm.clone(),
            read.reflectance_factor.clone(),
        )
        .map_err(|e| FormulationError::Invalid(format!("the reading at {g}: {e}")))?;
        for (w, r) in spectra.wavelengths_nm.iter().zip(factors) {
            if (first..=last).contains(w) {
                d.push(model.value_at(*w) - r);
            }
        }
    }
    Ok(d)
}

/// The root mean square of `d`.
pub fn rms(d: &[f64]) -> f64 {
    (d.iter().map(|x| x * x).sum::<f64>() / d.len() as f64).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use gonio_instrument::multiangle::{E2194, Settings, read_lambertian};

    /// A grey 0.3 read against itself differs by 0; against a target of 0.25 by 0.05 at every
    /// band within the reading (the target's 5 nm bands, the reading's 10 nm ones: interpolated);
    /// a CIELAB target is refused naming it; the names parse.
    #[test]
    fn reflectance_differences_of_greys() {
        let wl: Vec<f64> = (0..31).map(|i| 400.0 + 10.0 * i as f64).collect();
        let reading = read_lambertian(&[0.3; 31], &wl, &E2194, &Settings::default()).unwrap();
        let fine: Vec<f64> = (0..81).map(|i| 380.0 + 5.0 * i as f64).collect();
        let grey = read_lambertian(&vec![0.25; 81], &fine, &E2194, &Settings::default()).unwrap();
        let target = Target::from_reading("grey", &grey);
        let d = reflectance_differences(&target, &reading).unwrap();
        assert_eq!(d.len(), 61 * 5, "400–700 nm every 5 nm, 5 geometries");
        assert!(d.iter().all(|x| (x - 0.05).abs() < 1e-12));
        assert!((rms(&d) - 0.05).abs() < 1e-12);
        let own = Target::from_reading("own", &reading);
        assert_eq!(rms(&reflectance_differences(&own, &reading).unwrap()), 0.0);
        let lab = Target {
            spectra: None,
            ..own.clone()
        };
        let e = reflectance_differences(&lab, &reading)
            .unwrap_err()
            .to_string();
        assert!(e.contains("own: the target gives CIELAB only"), "{e}");
        assert_eq!(
            "Spectral".parse::<Objective>().unwrap(),
            Objective::Spectral
        );
        assert_eq!(Objective::default().to_string(), "de00");
        assert!("rms".parse::<Objective>().is_err());
        // auto: spectral for a target of spectra without gloss readings, de00 otherwise.
        let auto: ObjectiveChoice = "auto".parse().unwrap();
        assert_eq!(auto, ObjectiveChoice::default());
        assert_eq!(auto.resolve(&own, 0), Objective::Spectral);
        assert_eq!(auto.resolve(&own, 1), Objective::De00);
        assert_eq!(auto.resolve(&lab, 0), Objective::De00);
        let de00: ObjectiveChoice = "de00".parse().unwrap();
        assert_eq!(de00.resolve(&own, 0), Objective::De00);
        let e = "rms".parse::<ObjectiveChoice>().unwrap_err().to_string();
        assert!(e.contains("auto"), "{e}");
    }
}
