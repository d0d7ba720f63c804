//! The demo report's roughness study section: the study's curves, gloss and peaks across the
//! epoxy series by the ray method and the Kirchhoff approximation ([`crate::study`]), as
//! `gonio study` writes them.

use super::{Sizes, doi_text};
use crate::html::{Block, Section};
use crate::study::{self, StudyOutputs};
use crate::units::comma_list;
use gonio_instrument::study::StudyConfig;

pub(super) fn study_section(
    out: &StudyOutputs,
    config: &StudyConfig,
    plan: &Sizes,
    seconds: f64,
) -> Section {
    let mut blocks = vec![Block::Text(format!(
        "For every sample, in-plane curves at the NIST STARR geometry (incidence {} degrees, \
         scatter -75..75° in 1° steps, 1.4° detectors) by the ray method and by the Kirchhoff \
         approximation at {} nm. The ray method cannot produce the coherent specular spike of the \
         smooth samples; the two methods meet for the rough ones.",
        config
            .goniometer
            .incidences_deg()
            .iter()
            .map(|v| v.to_string())
            .collect::<Vec<_>>()
            .join(", "),
        config
            .wavelengths_nm
            .iter()
            .map(|v| v.to_string())
            .collect::<Vec<_>>()
            .join(", "),
    ))];
    let rows = out
        .peaks
        .iter()
        .filter(|p| p.method == "ray" || study::same_wavelength(p.wavelength_nm, Some(550.0)))
        .map(|p| {
            vec![
                p.label.clone(),
                p.method.clone(),
                p.wavelength_nm.map_or("-".into(), |w| format!("{w}")),
                format!("{}", p.incidence_deg),
                format!("{}", p.peak.position_deg),
                format!("{:.4e}", p.peak.reflectance),
                p.peak.fwhm_deg.map_or("-".into(), |w| format!("{w:.2}")),
            ]
        })
        .collect();
    blocks.push(Block::Text(
        "Gloss, haze and distinctness of image that the virtual meters read on each sample, \
         from the rays the ray method reflects and from the Kirchhoff field at 550 nm (ISO 2813 \
         apertures; haze and DOI after ASTM E430 at 30°, see docs/instruments.md). The Kirchhoff \
         readings of these small maps are limited by the spot's diffraction (about λ/(L cos θ)), \
         most at 85° and in the 0.1° DOI slit."
            .into(),
    ));
    blocks.push(Block::Table {
        headers: [
            "sample", "method", "Sq (nm)", "GU 20°", "GU 60°", "GU 85°", "haze", "DOI",
        ]
        .map(String::from)
        .to_vec(),
        rows: out
            .results
            .iter()
            .flat_map(|r| {
                [
                    ("ray", Some(&r.gloss_ray)),
                    ("Kirchhoff 550 nm", r.gloss_kirchhoff.as_ref()),
                ]
                .into_iter()
                .filter_map(|(method, g)| {
                    let g = g?;
                    Some(vec![
                        r.label.clone(),
                        method.to_string(),
                        format!("{:.1}", r.statistics.sq * 1e9),
                        format!("{:.1}", g.gu20),
                        format!("{:.1}", g.gu60),
                        format!("{:.1}", g.gu85),
                        format!("{:.2}", g.haze),
                        doi_text(g),
                    ])
                })
                .collect::<Vec<_>>()
            })
            .collect(),
    });
    for r in &out.results {
        for note in &r.notes {
            blocks.push(Block::Text(format!("{}: {note}", r.label)));
        }
    }
    blocks.push(Block::Table {
        headers: [
            "sample",
            "method",
            "λ (nm)",
            "incidence (°)",
            "peak at (°)",
            "peak reflectance",
            "FWHM (°)",
        ]
        .map(String::from)
        .to_vec(),
        rows,
    });
    blocks.push(Block::Code(format!(
        "gonio study --sq-nm {} --corr-um {} --size {} --dx-um {} --wavelength-nm {} -o study",
        comma_list(&plan.sq_nm),
        gonio_surface::synth::EPOXY_CORR_LENGTH_M * 1e6,
        plan.size,
        plan.dx * 1e6,
        comma_list(&config.wavelengths_nm),
    )));
    for (path, caption) in &out.plots {
        blocks.push(Block::Image {
            path: path.clone(),
            caption: caption.clone(),
        });
    }
    Section {
        title: "The roughness study".into(),
        blocks,
        seconds,
    }
}
