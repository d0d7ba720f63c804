//! The report's summary: what the run computed and what it shows, in a few sentences whose
//! numbers all come from this run's results: gloss against roughness, where the ray method and
//! the Kirchhoff approximation agree, and the Rayleigh roughness that tells why they differ.

use crate::units::length;
use gonio_instrument::GlossReport;
use gonio_instrument::study::SampleResult;

/// What the summary says about the real instrument file.
pub(super) struct RealFile {
    pub name: &'static str,
    /// Sq after levelling, m.
    pub sq: f64,
    pub gloss: GlossReport,
}

/// Two 60° readings agree when they differ by at most this many gloss units ...
const AGREE_GU: f64 = 2.0;
/// ... or by at most this fraction of the larger one.
const AGREE_FRACTION: f64 = 0.1;
/// The gloss geometry the summary quotes: 60°, the one ISO 2813 uses for most surfaces.
const THETA_DEG: f64 = 60.0;

/// The summary's paragraphs. `results` are the study's samples, `wavelength_nm` the wavelength
/// of its Kirchhoff gloss readings, `pictures` whether the run rendered the pictures.
pub(super) fn paragraphs(
    results: &[SampleResult],
    wavelength_nm: f64,
    real: &RealFile,
    pictures: bool,
) -> Vec<String> {
    let mut samples: Vec<&SampleResult> = results.iter().collect();
    samples.sort_by(|a, b| a.statistics.sq.total_cmp(&b.statistics.sq));
    let (Some(&first), Some(&last)) = (samples.first(), samples.last()) else {
        return Vec::new();
    };
    let sq = |r: &SampleResult| length(r.statistics.sq);
    let kirchhoff = samples.iter().any(|r| r.gloss_kirchhoff.is_some());
    let mut out = vec![format!(
        "This run synthesised {} Gaussian random surfaces with Sq from {} to {}, computed how \
         each scatters light in the plane of incidence by the ray method (geometric optics on \
         the surface's facets){}, and read the curves with virtual gloss meters at 20°, 60° and \
         85° (ISO 2813). It did the same for a real instrument file, {} (Sq = {}, {:.1} GU at \
         60° by the ray method), and checked whether that surface is isotropic{}.",
        samples.len(),
        sq(first),
        sq(last),
        if kirchhoff {
            format!(" and by the Kirchhoff approximation at {wavelength_nm} nm (the wave solution)")
        } else {
            String::new()
        },
        real.name,
        length(real.sq),
        real.gloss.gu60,
        if pictures {
            "; the pictures at the end show two of the epoxy surfaces and measured metallic \
             paints rendered by the path tracer"
        } else {
            ""
        },
    )];
    let (r0, r1) = (first.gloss_ray.gu60, last.gloss_ray.gu60);
    let mut trend = format!(
        "Gloss against roughness: at 60° the ray method reads {r0:.1} GU on the smoothest \
         sample ({}, Sq = {}) and {r1:.1} GU on the roughest ({}, Sq = {})",
        first.label,
        sq(first),
        last.label,
        sq(last)
    );
    if let (Some(k0), Some(k1)) = (&first.gloss_kirchhoff, &last.gloss_kirchhoff) {
        trend += &format!(
            "; the Kirchhoff approximation reads {:.1} and {:.1} GU",
            k0.gu60, k1.gu60
        );
    }
    trend += ".";
    out.push(trend);
    if kirchhoff {
        out.push(agreement(&samples, wavelength_nm));
    }
    out
}

/// Where the two methods agree at 60°, where they differ most, and the Rayleigh roughness
/// there that says why.
fn agreement(samples: &[&SampleResult], wavelength_nm: f64) -> String {
    let pairs: Vec<(&SampleResult, f64, f64)> = samples
        .iter()
        .filter_map(|r| Some((*r, r.gloss_ray.gu60, r.gloss_kirchhoff.as_ref()?.gu60)))
        .collect();
    let g = |r: &SampleResult| rayleigh_roughness(r.statistics.sq, wavelength_nm);
    let name = |r: &SampleResult| format!("{} (g = {:.2})", r.label, g(r));
    let Some(&(worst, r, k)) = pairs
        .iter()
        .max_by(|a, b| (a.1 - a.2).abs().total_cmp(&(b.1 - b.2).abs()))
    else {
        return String::new();
    };
    let rayleigh = format!(
        "A surface reflects the fraction exp(−g) of the light coherently, as a mirror-like \
         beam, where g = (4π·Sq·cos θ/λ)² is its Rayleigh roughness (here at {THETA_DEG}° and \
         {wavelength_nm} nm); the ray method, which follows only the slopes of the facets, has \
         no coherent part: it is the limit of the wave solution for g well above 1."
    );
    let agrees = |r: f64, k: f64| (r - k).abs() <= AGREE_GU.max(AGREE_FRACTION * r.max(k));
    let agreeing: Vec<String> = pairs
        .iter()
        .filter(|(_, r, k)| agrees(*r, *k))
        .map(|(s, ..)| name(s))
        .collect();
    if agreeing.len() == pairs.len() {
        return format!(
            "The two methods agree at 60° on every sample, within {:.1} GU (largest difference \
             on {}). {rayleigh} Where g is small the two still agree on gloss when the 60° \
             receptor collects the coherent beam and the narrow lobe of slopes alike.",
            (r - k).abs(),
            name(worst)
        );
    }
    let mut text = if agreeing.is_empty() {
        format!("The two methods agree at 60° on no sample (within {AGREE_GU} GU or 10%). ")
    } else {
        format!(
            "The two methods agree at 60° (within {AGREE_GU} GU or 10%) on {}. ",
            agreeing.join(", ")
        )
    };
    text += &format!(
        "They differ most on {}: {r:.1} GU by the ray method, {k:.1} GU by Kirchhoff. \
         {rayleigh} ",
        name(worst)
    );
    let coherent = (-g(worst)).exp();
    text += &if g(worst) < 1.0 {
        format!(
            "On {} the surface is smooth on the scale of the wavelength: exp(−g) = \
             {coherent:.2} of the light stays in the coherent beam, which the Kirchhoff \
             approximation keeps and the ray method cannot produce.",
            worst.label
        )
    } else {
        format!(
            "On {} the coherent beam is gone (exp(−g) = {coherent:.1e}) and both methods \
             describe the same scattered lobe; what separates them is the Kirchhoff reading's \
             diffraction by the finite map, which spreads the light over angles of about \
             λ/(L cos θ) for a map L across.",
            worst.label
        )
    };
    text
}

/// The Rayleigh roughness g = (4π·Sq·cos θ/λ)² at the quoted gloss angle.
fn rayleigh_roughness(sq_m: f64, wavelength_nm: f64) -> f64 {
    (4.0 * std::f64::consts::PI * sq_m * THETA_DEG.to_radians().cos() / (wavelength_nm * 1e-9))
        .powi(2)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rayleigh_roughness_of_the_201_nm_sample() {
        // (4π · 201 nm · cos 60° / 550 nm)² = 2.29622² = 5.27263
        assert!((rayleigh_roughness(201e-9, 550.0) - 5.27263).abs() < 1e-4);
    }
}
