//! How far a formulation's BRDF is from a measured one, sample by sample: at every geometry a
//! gonioreflectometer measured (Cornell's ASTM files: 1439 pairs of directions, out of plane
//! included), the formulation's spectral BRDF and the measured one are each read as a colour and
//! compared. This is how a match is judged on what it did not see: the match fits a handful of
//! multi-angle geometries, the measurement holds the whole hemisphere.
//!
//! Each sample's spectrum `f(λ)` (1/sr) becomes the reflectance factor `R(λ) = π f(λ)` (the
//! ratio to a perfect diffuser lit and seen the same way, ASTM E284), then CIE XYZ and CIELAB
//! under D65 for the 1964 10° observer, as the multi-angle readings are
//! (`instrument::multiangle::read`): the colour the sample would show in a multi-angle
//! instrument with point apertures at that geometry. Near the mirror direction of a glossy paint
//! `R` exceeds 1 by orders of magnitude (Y up to 2·10⁵ on the Cayman), L* exceeds 100 and a
//! colour difference there says more about the instrument's aperture than about the paint: the
//! samples whose half vector lies within [`PEAK_DEG`] of the normal are summarised apart.
//!
//! Per sample: CIEDE2000 between the two CIELAB colours (Sharma, Wu & Dalal, Col. Res. Appl. 30,
//! 21, 2005, as every ΔE00 of gonio) and the ratio of the luminance factors `Y_model/Y_measured`.
//! Summaries: mean, median and 90th percentile of ΔE00, and the median of |log10 ratio| over
//! the samples where both Y are positive (a measured 0 is below the instrument's floor).

use crate::error::{FormulationError, Result};
use gonio_brdf::formats::scattered::Sample;
use gonio_coating::system::Coating;
use gonio_color::{Illuminant, Lab, Observer, SpectralToXyz, ciede2000, white};
use gonio_instrument::coating_study::walked_brdf;
use rayon::prelude::*;

/// Samples whose half vector lies within this angle of the surface's normal, degrees, are the
/// gloss peak's: there the measured value depends on the instrument's aperture and alignment
/// (the clear coat's mirror lobe is about 1° wide, the Cornell gonioreflectometer's aperture is
/// of the same order), and they are summarised apart. 5° keeps 8 to 30 of the 1439 Cornell
/// samples in the peak.
pub const PEAK_DEG: f64 = 5.0;

/// One sample: where it was measured, and the two colours.
#[derive(Clone, Debug)]
pub struct SampleDifference {
    /// Polar angles of the light and the view and their azimuths, degrees.
    pub theta_i_deg: f64,
    pub phi_i_deg: f64,
    pub theta_o_deg: f64,
    pub phi_o_deg: f64,
    /// The half vector's angle from the normal, degrees.
    pub theta_h_deg: f64,
    pub measured: Lab,
    pub model: Lab,
    /// Luminance factors Y (0–100 for a white diffuser), measured and model.
    pub measured_y: f64,
    pub model_y: f64,
    pub de00: f64,
}

/// A summary over a set of samples.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Summary {
    pub count: usize,
    pub mean_de00: f64,
    pub median_de00: f64,
    pub p90_de00: f64,
    /// Median of |log10(Y_model/Y_measured)| over the samples where both are positive.
    pub median_abs_log10_y: f64,
}

/// Every sample compared, and the summaries.
#[derive(Clone, Debug)]
pub struct SampleComparison {
    pub samples: Vec<SampleDifference>,
    /// Samples whose half vector is at least [`PEAK_DEG`] from the normal.
    pub off_peak: Summary,
    /// The others.
    pub peak: Summary,
    pub all: Summary,
}

/// Compare `coating` with the measured `samples` (spectra at `wavelengths_nm`, 1/sr), the
/// coating read with `walks` walks per sample (a rough top or flakes) from the streams of `seed`
/// (`instrument::coating_study::walked_brdf`, as the multi-angle readings). A smooth top's
/// mirror reflection (a delta) is not in the coating's BRDF: it shows only in the peak's samples.
pub fn compare(
    coating: &Coating,
    samples: &[Sample],
    wavelengths_nm: &[f64],
    walks: usize,
    seed: u64,
) -> Result<SampleComparison> {
    if samples.is_empty() {
        return Err(FormulationError::Invalid(
            "no measured samples to compare with".into(),
        ));
    }
    if let Some(s) = samples
        .iter()
        .find(|s| s.values.len() != wavelengths_nm.len())
    {
        return Err(FormulationError::Invalid(format!(
            "a measured sample has {} values for {} wavelengths",
            s.values.len(),
            wavelengths_nm.len()
        )));
    }
    coating.check(wavelengths_nm)?;
    let evaluator = coating.evaluator(wavelengths_nm)?;
    let brdf = walked_brdf(&evaluator, walks, seed);
    let (illuminant, observer) = (Illuminant::D65, Observer::Cie1964TenDegree);
    let to_xyz = SpectralToXyz::new(wavelengths_nm, illuminant, observer)
        .map_err(|e| FormulationError::Invalid(format!("wavelengths of the samples: {e}")))?;
    let white = white(illuminant, observer);
    let colour = |f: &[f64]| -> Result<(Lab, f64)> {
        let r: Vec<f64> = f.iter().map(|v| std::f64::consts::PI * v).collect();
        let xyz = to_xyz
            .xyz(&r)
            .map_err(|e| FormulationError::Invalid(e.to_string()))?;
        Ok((xyz.to_lab(white), xyz.y))
    };
    let rows = samples
        .par_iter()
        .map(|s| {
            let mut f = vec![0.0; wavelengths_nm.len()];
            brdf(s.wo, s.wi, &mut f);
            let (model, model_y) = colour(&f)?;
            let (measured, measured_y) = colour(&s.values)?;
            let h = (s.wi + s.wo).normalize();
            let angles = |w: glam::DVec3| {
                (
                    w.z.clamp(-1.0, 1.0).acos().to_degrees(),
                    w.y.atan2(w.x).to_degrees(),
                )
            };
            let ((theta_i_deg, phi_i_deg), (theta_o_deg, phi_o_deg)) = (angles(s.wi), angles(s.wo));
            Ok(SampleDifference {
                theta_i_deg,
                phi_i_deg,
                theta_o_deg,
                phi_o_deg,
                theta_h_deg: h.z.clamp(-1.0, 1.0).acos().to_degrees(),
                measured,
                model,
                measured_y,
                model_y,
                de00: ciede2000(measured, model),
            })
        })
        .collect::<Result<Vec<_>>>()?;
    let off: Vec<&SampleDifference> = rows.iter().filter(|r| r.theta_h_deg >= PEAK_DEG).collect();
    let peak: Vec<&SampleDifference> = rows.iter().filter(|r| r.theta_h_deg < PEAK_DEG).collect();
    let all: Vec<&SampleDifference> = rows.iter().collect();
    Ok(SampleComparison {
        off_peak: summary(&off),
        peak: summary(&peak),
        all: summary(&all),
        samples: rows,
    })
}

/// The summary of `rows` (NaN statistics for an empty set).
pub fn summary(rows: &[&SampleDifference]) -> Summary {
    let mut de: Vec<f64> = rows.iter().map(|r| r.de00).collect();
    de.sort_by(f64::total_cmp);
    let mut log_ratio: Vec<f64> = rows
        .iter()
        .filter(|r| r.model_y > 0.0 && r.measured_y > 0.0)
        .map(|r| (r.model_y / r.measured_y).log10().abs())
        .collect();
    log_ratio.sort_by(f64::total_cmp);
    Summary {
        count: rows.len(),
        mean_de00: de.iter().sum::<f64>() / de.len() as f64,
        median_de00: quantile(&de, 0.5),
        p90_de00: quantile(&de, 0.9),
        median_abs_log10_y: quantile(&log_ratio, 0.5),
    }
}

/// The `q` quantile of sorted `v` by linear interpolation between order statistics (Hyndman &
/// Fan's definition 7, numpy's default); NaN for an empty `v`.
fn quantile(v: &[f64], q: f64) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    let pos = q * (v.len() - 1) as f64;
    let (i, t) = (pos.floor() as usize, pos.fract());
    let j = (i + 1).min(v.len() - 1);
    v[i] + t * (v[j] - v[i])
}
