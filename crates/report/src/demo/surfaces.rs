//! The demo report's first sections: the synthetic epoxy roughness series (statistics and a
//! height map) and a real instrument file (statistics, height map, in-plane curves by the ray
//! method and gloss), with the table of ISO 25178-2 statistics both share.

use super::summary;
use super::{REAL_FILE, REAL_FILE_NAME, Sizes, doi_text};
use crate::Result;
use crate::html::{Block, Section};
use crate::output::write_bytes;
use crate::plots::{plot_curves, plot_height_map};
use gonio_instrument::specimens::RaySpecimen;
use gonio_io::Progress;
use gonio_scatter::ray::{RayEngine, RayOptions};
use gonio_scatter::{Goniometer, InplaneMethod};
use gonio_surface::stats::{Statistics, statistics};
use gonio_surface::{HeightMap, io};
use std::path::Path;

fn stats_row(label: &str, map: &HeightMap, st: &Statistics) -> Vec<String> {
    let opt_um = |v: Option<f64>| v.map_or("-".into(), |v| format!("{:.2}", v * 1e6));
    vec![
        label.to_string(),
        format!("{} × {}", map.nx(), map.ny()),
        format!("{:.3} × {:.3}", map.dx() * 1e6, map.dy() * 1e6),
        format!("{:.2}", st.sq * 1e9),
        format!("{:.2}", st.sa * 1e9),
        format!("{:.3}", st.ssk),
        format!("{:.3}", st.sku),
        format!("{:.4}", st.sdq),
        opt_um(st.sal),
        st.str.map_or("-".into(), |v| format!("{v:.3}")),
    ]
}

fn stats_headers() -> Vec<String> {
    [
        "sample",
        "grid",
        "dx × dy (µm)",
        "Sq (nm)",
        "Sa (nm)",
        "Ssk",
        "Sku",
        "Sdq",
        "Sal (µm)",
        "Str",
    ]
    .map(String::from)
    .to_vec()
}

pub(super) fn series_section(
    samples: &[gonio_instrument::study::Sample],
    plan: &Sizes,
    dir: &Path,
    seconds: f64,
) -> Result<Section> {
    let mut rows = Vec::new();
    for s in samples {
        let st = statistics(&s.map)?;
        rows.push(stats_row(&s.label, &s.map, &st));
    }
    let mut blocks = vec![
        Block::Text(format!(
            "Gaussian random surfaces synthesised by spectral filtering with the FFT (Gaussian \
             autocorrelation), one per requested Sq ({} nm), all from the same seed so that they \
             differ only in scale. ISO 25178-2 parameters after levelling; for a Gaussian \
             surface Sdq should be close to 2·Sq/T.",
            plan.sq_nm
                .iter()
                .map(|v| v.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        )),
        Block::Table {
            headers: stats_headers(),
            rows,
        },
    ];
    if let Some(s) = samples
        .iter()
        .find(|s| s.label == "sq201nm")
        .or(samples.first())
    {
        let png = dir.join(format!("surface_{}.png", s.label));
        plot_height_map(&s.map, &s.label, &png)?;
        blocks.push(Block::Image {
            path: png,
            caption: format!("Height map of {}", s.label),
        });
    }
    Ok(Section {
        title: "Surfaces: the epoxy roughness series".into(),
        blocks,
        seconds,
    })
}

/// The real file's section, and what the summary quotes of it. The file is written beside the
/// report, so that the commands the section shows run as written in the output folder.
pub(super) fn real_file_section(dir: &Path) -> Result<(Section, summary::RealFile)> {
    let copy = dir.join(REAL_FILE_NAME);
    write_bytes(&copy, REAL_FILE)?;
    let map = io::read_bytes(Path::new(REAL_FILE_NAME), REAL_FILE)?;
    let st = statistics(&map)?;
    let png = dir.join("real_surface.png");
    plot_height_map(&map, REAL_FILE_NAME, &png)?;
    let engine = RayEngine::new(&map, RayOptions::default())?;
    let curves = engine.inplane_curves(&Goniometer::starr(), &[], &Progress::silent())?;
    let gloss = gonio_instrument::measure(&RaySpecimen { engine: &engine })?;
    let csv = dir.join("real_inplane.csv");
    gonio_instrument::curves::write_csv(&csv, &curves)?;
    let curves_png = dir.join("real_inplane.png");
    plot_curves(&curves_png, &curves)?;
    let meta = &map.meta;
    let section = Section {
        title: format!("A real instrument file: {REAL_FILE_NAME}"),
        blocks: vec![
            Block::Text(format!(
                "A height map written by {} ({}), read by gonio's X3P reader. Statistics after \
                 least-squares levelling, then the in-plane BRDF by the ray method (index 1.55, \
                 shadowing and masking on, 1.4° detectors) at the STARR incidences.",
                meta.instrument
                    .as_deref()
                    .unwrap_or("an unnamed instrument"),
                meta.format.as_deref().unwrap_or("X3P"),
            )),
            Block::Table {
                headers: stats_headers(),
                rows: vec![stats_row(REAL_FILE_NAME, &map, &st)],
            },
            Block::Image {
                path: png,
                caption: format!("Levelled heights of {REAL_FILE_NAME}"),
            },
            Block::Image {
                path: curves_png,
                caption: format!(
                    "In-plane BRDF of {REAL_FILE_NAME} by the ray method (also in {})",
                    csv.display()
                ),
            },
            Block::Table {
                headers: ["GU 20°", "GU 60°", "GU 85°", "haze", "DOI"]
                    .map(String::from)
                    .to_vec(),
                rows: vec![vec![
                    format!("{:.1}", gloss.gu20),
                    format!("{:.1}", gloss.gu60),
                    format!("{:.1}", gloss.gu85),
                    format!("{:.2}", gloss.haze),
                    doi_text(&gloss),
                ]],
            },
            Block::Code(format!(
                "gonio surface info {REAL_FILE_NAME}\n\
                 gonio inplane {REAL_FILE_NAME} --method ray --incidence-deg 20,45,60,70 \
                 --scatter-deg=-75:75:1 --aperture-deg 1.4 --index 1.55 -o real_inplane.csv --plot real_inplane.png\n\
                 gonio gloss {REAL_FILE_NAME} --index 1.55"
            )),
        ],
        seconds: 0.0,
    };
    let real = summary::RealFile {
        name: REAL_FILE_NAME,
        sq: st.sq,
        gloss,
    };
    Ok((section, real))
}
