//! Comparison of two in-plane curves (measured against computed, or one method against another):
//! the RMS difference of log10 reflectance over the common angles, and each curve's peak
//! position, peak height and full width at half maximum.

use gonio_scatter::InplaneCurve;

/// Peak of a curve: position and height of the maximum reflectance, and its FWHM (degrees),
/// found by linear interpolation of the half-maximum crossings on either side.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Peak {
    pub position_deg: f64,
    pub reflectance: f64,
    /// `None` when the curve does not fall to half maximum on both sides within its range.
    pub fwhm_deg: Option<f64>,
}

/// The comparison of two curves at one incidence.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Comparison {
    pub incidence_deg: f64,
    pub wavelength_nm: Option<f64>,
    /// RMS over the common angles (both reflectances > 0) of `log10(rho_b) - log10(rho_a)`.
    pub rms_log10: f64,
    /// Number of angles the RMS was taken over.
    pub common_points: usize,
    pub peak_a: Peak,
    pub peak_b: Peak,
}

/// The peak of a curve, or `None` for an empty curve or one without positive values.
pub fn peak(curve: &InplaneCurve) -> Option<Peak> {
    let pts = &curve.points;
    let (imax, max) = pts
        .iter()
        .enumerate()
        .filter(|(_, p)| p.reflectance.is_finite())
        .max_by(|a, b| a.1.reflectance.total_cmp(&b.1.reflectance))?;
    if max.reflectance <= 0.0 {
        return None;
    }
    let half = 0.5 * max.reflectance;
    let crossing = |range: &mut dyn Iterator<Item = usize>| -> Option<f64> {
        let mut prev = imax;
        for i in range {
            if pts[i].reflectance < half {
                let (a, b) = (&pts[prev], &pts[i]);
                let t = (a.reflectance - half) / (a.reflectance - b.reflectance);
                return Some(a.scatter_deg + t * (b.scatter_deg - a.scatter_deg));
            }
            prev = i;
        }
        None
    };
    let left = crossing(&mut (0..imax).rev());
    let right = crossing(&mut (imax + 1..pts.len()));
    Some(Peak {
        position_deg: max.scatter_deg,
        reflectance: max.reflectance,
        fwhm_deg: left.zip(right).map(|(l, r)| r - l),
    })
}

/// Compare curve `b` against curve `a` at the angles they share (to 1e-6 degree).
pub fn compare(a: &InplaneCurve, b: &InplaneCurve) -> Option<Comparison> {
    let mut sum = 0.0;
    let mut n = 0usize;
    for pa in &a.points {
        if let Some(pb) = b
            .points
            .iter()
            .find(|p| (p.scatter_deg - pa.scatter_deg).abs() < 1e-6)
            && pa.reflectance > 0.0
            && pb.reflectance > 0.0
        {
            let d = pb.reflectance.log10() - pa.reflectance.log10();
            sum += d * d;
            n += 1;
        }
    }
    Some(Comparison {
        incidence_deg: a.incidence_deg,
        wavelength_nm: a.wavelength_nm.or(b.wavelength_nm),
        rms_log10: if n > 0 {
            (sum / n as f64).sqrt()
        } else {
            f64::NAN
        },
        common_points: n,
        peak_a: peak(a)?,
        peak_b: peak(b)?,
    })
}
