//! `gonio demo`: the whole pipeline on embedded default data, written up as one HTML report
//! (`out/report.html`): the synthetic epoxy roughness series, a real instrument file and its
//! isotropy, the roughness study by both scattering methods, the gloss readings, coatings and
//! their colour, pictures, and texture (sparkle, graininess, orange peel).

mod coatings;
mod formulation;
mod matched;
mod pictures;
mod summary;
mod swatch_strip;
mod texture;

use crate::report::{Block, Report, Section};
use crate::study::{self, StudyOutputs};
use crate::surface::plot_height_map;
use anyhow::{Context, Result};
use clap::Args;
use gonio_instrument::isotropy::{self, IsotropyConfig};
use gonio_instrument::specimens::RaySpecimen;
use gonio_instrument::study::StudyConfig;
use gonio_io::Progress;
use gonio_scatter::ray::{RayEngine, RayOptions};
use gonio_scatter::{Goniometer, InplaneMethod};
use gonio_surface::stats::{Statistics, statistics};
use gonio_surface::{HeightMap, io};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// A real instrument file shipped in the binary: MountainsMap X3P export of a 650 × 650 map
/// (see crates/surface/tests/data/README.md for its provenance).
static REAL_FILE: &[u8] = include_bytes!("../../../surface/tests/data/x3p-2.x3p");
const REAL_FILE_NAME: &str = "x3p-2.x3p";

#[derive(Args)]
pub struct DemoArgs {
    /// Directory for the report and everything it shows (created if missing).
    #[arg(short, long, default_value = "out")]
    output: PathBuf,
    /// A small, fast run (128 × 128 maps, two samples, one wavelength), as the tests use.
    #[arg(long)]
    quick: bool,
}

/// Sizes of the demo's computations.
struct Plan {
    size: usize,
    dx: f64,
    sq_nm: Vec<f64>,
    wavelengths_nm: Vec<f64>,
}

impl Plan {
    fn new(quick: bool) -> Self {
        if quick {
            Plan {
                size: 128,
                dx: 0.5e-6,
                sq_nm: vec![50.0, 805.0],
                wavelengths_nm: vec![550.0],
            }
        } else {
            Plan {
                size: 512,
                dx: 0.5e-6,
                sq_nm: gonio_surface::synth::EPOXY_SQ_M
                    .iter()
                    .map(|s| s * 1e9)
                    .collect(),
                wavelengths_nm: vec![500.0, 550.0, 600.0],
            }
        }
    }
}

pub fn run(args: DemoArgs) -> Result<()> {
    let plan = Plan::new(args.quick);
    let dir = &args.output;
    std::fs::create_dir_all(dir)
        .with_context(|| format!("{}: cannot create directory", dir.display()))?;
    let started = Instant::now();
    let mut sections = Vec::new();
    let steps = if args.quick { 7 } else { 8 };
    let mut step = 0;
    let mut announce = |what: &str| {
        step += 1;
        eprintln!("[{step}/{steps}] {what}");
    };

    announce("synthesising the epoxy roughness series");
    let (samples, seconds) = timed(|| {
        study::synthetic_samples(
            &plan.sq_nm,
            gonio_surface::synth::EPOXY_CORR_LENGTH_M,
            plan.size,
            plan.dx,
            1,
        )
    });
    let samples = samples?;
    sections.push(series_section(&samples, &plan, dir, seconds)?);

    announce("a real instrument file: statistics and in-plane curves");
    let (section, seconds) = timed(|| real_file_section(dir));
    let (mut section, real) = section?;
    section.seconds = seconds;
    sections.push(section);

    announce("is the real surface isotropic? its curves turned by 90° and 45°");
    let (section, seconds) = timed(|| isotropy_section(dir));
    let mut section = section?;
    section.seconds = seconds;
    sections.push(section);

    announce("the roughness study: ray method and Kirchhoff approximation");
    let config = StudyConfig {
        wavelengths_nm: plan.wavelengths_nm.clone(),
        ..StudyConfig::starr()
    };
    let (out, seconds) = timed(|| study::execute(&samples, &config, &dir.join("study")));
    let out = out?;
    sections.push(study_section(&out, &config, &plan, seconds));

    announce("coatings: multi-angle colour of a clear-coated red and of the measured paints");
    let (section, seconds) = timed(|| coatings::coatings_section(dir, !args.quick));
    let mut section = section?;
    section.seconds = seconds;
    sections.push(section);

    announce("formulation: three Cornell paints against their matches, and the silver metallic");
    let (section, seconds) = timed(|| formulation::formulation_section(dir, args.quick));
    let mut section = section?;
    section.seconds = seconds;
    sections.push(section);

    if !args.quick {
        announce("pictures: the NIST figure 6 panels and the metallic paints");
        let (section, seconds) = timed(|| pictures::render_section(dir));
        let mut section = section?;
        section.seconds = seconds;
        sections.push(section);
    }

    announce("texture: the sparkle of a silver metallic and the orange peel of a clear coat");
    let (section, seconds) = timed(|| texture::texture_section(dir, args.quick));
    let mut section = section?;
    section.seconds = seconds;
    sections.push(section);

    let report = Report {
        title: "gonio demo report".into(),
        intro: format!(
            "What gonio computes from surface topography, end to end, on the data built into the \
             binary: synthetic Gaussian surfaces of the NIST epoxy roughness series ({} × {} points \
             at {} µm, correlation length {} µm) and a real instrument file. Every figure below was \
             computed by this run (gonio {}).",
            plan.size,
            plan.size,
            plan.dx * 1e6,
            gonio_surface::synth::EPOXY_CORR_LENGTH_M * 1e6,
            env!("CARGO_PKG_VERSION")
        ),
        summary: summary::paragraphs(&out.results, KIRCHHOFF_GLOSS_NM, &real, !args.quick),
        sections,
    };
    let path = dir.join("report.html");
    report.write(&path)?;
    eprintln!(
        "done in {:.0} s: the report is {}",
        started.elapsed().as_secs_f64(),
        path.display()
    );
    Ok(())
}

fn timed<T>(work: impl FnOnce() -> T) -> (T, f64) {
    let t = Instant::now();
    let out = work();
    (out, t.elapsed().as_secs_f64())
}

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

fn series_section(
    samples: &[gonio_instrument::study::Sample],
    plan: &Plan,
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

/// The wavelength of the study's Kirchhoff gloss readings, nm.
const KIRCHHOFF_GLOSS_NM: f64 = 550.0;

/// The real file's section, and what the summary quotes of it. The file is written beside the
/// report, so that the commands the section shows run as written in the output folder.
fn real_file_section(dir: &Path) -> Result<(Section, summary::RealFile)> {
    let copy = dir.join(REAL_FILE_NAME);
    crate::output::write_atomic(&copy, |w| Ok(std::io::Write::write_all(w, REAL_FILE)?))?;
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
    crate::inplane::plot_curves(&curves_png, &curves)?;
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

/// The isotropy check on the real file: its in-plane curves (ray method) and those of the map
/// turned by 90° (exact) and 45° (spline, both cropped to the inscribed square), compared.
fn isotropy_section(dir: &Path) -> Result<Section> {
    let map = io::read_bytes(Path::new(REAL_FILE_NAME), REAL_FILE)?;
    let config = IsotropyConfig {
        angles_deg: vec![90.0, 45.0],
        ..IsotropyConfig::starr(isotropy::Method::Ray)
    };
    let checks = isotropy::check(&map, &config, &Progress::silent())?;
    let mut blocks = vec![Block::Text(format!(
        "An isotropic surface scatters the same whatever its azimuth. The in-plane curves of \
         {REAL_FILE_NAME} (ray method, STARR geometry, the plane of incidence along x) against \
         those of the same map turned about its normal: by 90° exactly (the grid transposed, no \
         interpolation) and by 45° (bicubic spline, both maps cropped to the largest square \
         inside the turned one, so that both are read over the same area). The lobe's width \
         follows the rms slope along the plane of incidence; Str is the ISO 25178 texture \
         aspect ratio (1 for an isotropic surface). For isotropic synthetic maps (256 × 256 \
         points, 40 correlation lengths across) the RMS difference of log10 reflectance is about \
         0.15, mostly from the few rays in the tails (docs/instruments.md)."
    ))];
    let slope_rows = checks
        .iter()
        .flat_map(|c| {
            [("original", &c.original), ("turned", &c.rotated)].map(|(name, o)| {
                vec![
                    format!("{}°", c.angle_deg),
                    name.to_string(),
                    format!("{} × {}", o.nx, o.ny),
                    format!("{:.4}", o.rms_slope_x),
                    format!("{:.4}", o.rms_slope_y),
                    o.str.map_or("-".into(), |v| format!("{v:.3}")),
                ]
            })
        })
        .collect();
    blocks.push(Block::Table {
        headers: [
            "turn",
            "map",
            "points",
            "rms slope along x (plane of incidence)",
            "rms slope along y",
            "Str",
        ]
        .map(String::from)
        .to_vec(),
        rows: slope_rows,
    });
    let fwhm = |v: Option<f64>| v.map_or("-".into(), |w| format!("{w:.2}"));
    let rows = checks
        .iter()
        .flat_map(|c| {
            c.comparisons.iter().map(|x| {
                vec![
                    format!("{}°", c.angle_deg),
                    format!("{}", x.incidence_deg),
                    format!("{:.3}", x.rms_log10),
                    format!("{} / {}", x.peak_a.position_deg, x.peak_b.position_deg),
                    format!(
                        "{:.3e} / {:.3e}",
                        x.peak_a.reflectance, x.peak_b.reflectance
                    ),
                    format!("{} / {}", fwhm(x.peak_a.fwhm_deg), fwhm(x.peak_b.fwhm_deg)),
                ]
            })
        })
        .collect();
    blocks.push(Block::Table {
        headers: [
            "turn",
            "incidence (°)",
            "RMS Δlog10 ρ",
            "peak at (°) original / turned",
            "peak reflectance original / turned",
            "FWHM (°) original / turned",
        ]
        .map(String::from)
        .to_vec(),
        rows,
    });
    crate::isotropy::write_csv(&dir.join("isotropy.csv"), &checks)?;
    for c in &checks {
        let png = dir.join(format!("isotropy_rot{}.png", c.angle_deg));
        crate::isotropy::plot_check(&png, c)?;
        blocks.push(Block::Image {
            path: png,
            caption: format!(
                "{REAL_FILE_NAME}: in-plane reflectance of the original (lines) and of the map \
                 turned by {}° (dots)",
                c.angle_deg
            ),
        });
    }
    blocks.push(Block::Code(format!(
        "gonio isotropy {REAL_FILE_NAME} --angle-deg 90,45 -o isotropy.png --csv isotropy.csv"
    )));
    Ok(Section {
        title: format!("Isotropy of {REAL_FILE_NAME}"),
        blocks,
        seconds: 0.0,
    })
}

fn study_section(out: &StudyOutputs, config: &StudyConfig, plan: &Plan, seconds: f64) -> Section {
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
        crate::comma_list(&plan.sq_nm),
        gonio_surface::synth::EPOXY_CORR_LENGTH_M * 1e6,
        plan.size,
        plan.dx * 1e6,
        crate::comma_list(&config.wavelengths_nm),
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
/// DOI as the report shows it: with its uncertainty from the finite map where it has one
/// (the ray method's, `GlossReport::doi_uncertainty`).
fn doi_text(g: &gonio_instrument::gloss::GlossReport) -> String {
    if g.doi_uncertainty > 0.0 {
        format!("{:.1} ± {:.1}", g.doi, g.doi_uncertainty)
    } else {
        format!("{:.1}", g.doi)
    }
}
