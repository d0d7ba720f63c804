//! The demo: the whole pipeline on embedded default data, written up as one HTML report
//! (`report.html`): the synthetic epoxy roughness series, a real instrument file and its
//! isotropy, the roughness study by both scattering methods, the gloss readings, coatings and
//! their colour, formulation, pictures, texture (sparkle, graininess, orange peel), and the
//! standard of appearance (the viewing booth's pictures and their closure against the
//! instrument). `gonio
//! demo`, `gonio.report.demo` in Python and the lab's report job call [`run`].

mod coatings;
mod formulation;
mod isotropy;
mod matched;
mod pictures;
mod standard;
mod study;
mod summary;
mod surfaces;
mod swatch_strip;
mod texture;

use crate::Result;
use crate::html::{Report, Section};
use crate::output::create_dir;
use gonio_instrument::study::StudyConfig;
use gonio_io::Progress;
use std::path::PathBuf;
use std::time::Instant;

/// A real instrument file shipped in the binary: MountainsMap X3P export of a 650 × 650 map
/// (see crates/surface/tests/data/README.md for its provenance).
static REAL_FILE: &[u8] = include_bytes!("../../../surface/tests/data/x3p-2.x3p");
const REAL_FILE_NAME: &str = "x3p-2.x3p";

/// What to run: where, and how large.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DemoPlan {
    /// The folder of the report and of everything it shows (created if missing).
    pub output: PathBuf,
    /// A small, fast run (128 × 128 maps, two samples, one wavelength, no path-traced
    /// pictures), as the tests use: seconds instead of minutes.
    pub quick: bool,
}

/// Where the demo tells how far it has come.
#[derive(Debug, Clone, Default)]
pub struct DemoProgress {
    /// One report as each step begins: its title as the stage, the steps finished and all the
    /// steps (`"coatings: ...", 4, 7`).
    pub steps: Progress,
    /// The reports of the computations inside a step (the study's samples, each render's
    /// tiles, the texture camera's pictures), one computation after another: each counts its
    /// own steps from the start.
    pub work: Progress,
}

/// What a run wrote and how long it took.
#[derive(Debug, Clone, PartialEq)]
pub struct DemoOutcome {
    /// The report, `report.html` in the plan's folder.
    pub report: PathBuf,
    /// Each section's title and the seconds its computation took, in the report's order.
    pub sections: Vec<(String, f64)>,
    /// The whole run, seconds.
    pub seconds: f64,
}

/// Sizes of the demo's computations.
struct Sizes {
    size: usize,
    dx: f64,
    sq_nm: Vec<f64>,
    wavelengths_nm: Vec<f64>,
}

impl Sizes {
    fn new(quick: bool) -> Self {
        if quick {
            Sizes {
                size: 128,
                dx: 0.5e-6,
                sq_nm: vec![50.0, 805.0],
                wavelengths_nm: vec![550.0],
            }
        } else {
            Sizes {
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

/// Run the demo as `plan` says and write its report; `progress` hears each step and the work
/// inside it. Every file the report shows, and those its commands read, are written beside it.
pub fn run(plan: &DemoPlan, progress: &DemoProgress) -> Result<DemoOutcome> {
    let sizes = Sizes::new(plan.quick);
    let dir = plan.output.as_path();
    create_dir(dir)?;
    let work = &progress.work;
    let started = Instant::now();
    let mut sections = Vec::new();
    let steps: u64 = if plan.quick { 8 } else { 9 };
    let mut step = 0;
    let mut announce = |what: &str| {
        progress.steps.report(what, step, steps);
        step += 1;
    };

    announce("synthesising the epoxy roughness series");
    let (samples, seconds) = timed(|| {
        crate::study::synthetic_samples(
            &sizes.sq_nm,
            gonio_surface::synth::EPOXY_CORR_LENGTH_M,
            sizes.size,
            sizes.dx,
            1,
        )
    });
    let samples = samples?;
    sections.push(surfaces::series_section(&samples, &sizes, dir, seconds)?);

    announce("a real instrument file: statistics and in-plane curves");
    let (section, seconds) = timed(|| surfaces::real_file_section(dir));
    let (section, real) = section?;
    sections.push(with_time(section, seconds));

    announce("is the real surface isotropic? its curves turned by 90° and 45°");
    let (section, seconds) = timed(|| isotropy::isotropy_section(dir));
    sections.push(with_time(section?, seconds));

    announce("the roughness study: ray method and Kirchhoff approximation");
    let config = StudyConfig {
        wavelengths_nm: sizes.wavelengths_nm.clone(),
        ..StudyConfig::starr()
    };
    let (out, seconds) =
        timed(|| crate::study::execute(&samples, &config, &dir.join("study"), work));
    let out = out?;
    sections.push(study::study_section(&out, &config, &sizes, seconds));

    announce("coatings: multi-angle colour of a clear-coated red and of the measured paints");
    let (section, seconds) = timed(|| coatings::coatings_section(dir, !plan.quick));
    sections.push(with_time(section?, seconds));

    announce("formulation: three Cornell paints against their matches, and the silver metallic");
    let (section, seconds) = timed(|| formulation::formulation_section(dir, plan.quick, work));
    sections.push(with_time(section?, seconds));

    if !plan.quick {
        announce("pictures: the NIST figure 6 panels and the metallic paints");
        let (section, seconds) = timed(|| pictures::render_section(dir, work));
        sections.push(with_time(section?, seconds));
    }

    announce("texture: the sparkle of a silver metallic and the orange peel of a clear coat");
    let (section, seconds) = timed(|| texture::texture_section(dir, plan.quick, work));
    sections.push(with_time(section?, seconds));

    announce(
        "standard of appearance: a metallic and a solid in the viewing booth, and its closure",
    );
    let (section, seconds) = timed(|| standard::standard_section(dir, plan.quick, work));
    sections.push(with_time(section?, seconds));

    let report = Report {
        title: "gonio demo report".into(),
        intro: format!(
            "What gonio computes from surface topography, end to end, on the data built into the \
             binary: synthetic Gaussian surfaces of the NIST epoxy roughness series ({} × {} points \
             at {} µm, correlation length {} µm) and a real instrument file. Every figure below was \
             computed by this run (gonio {}).",
            sizes.size,
            sizes.size,
            sizes.dx * 1e6,
            gonio_surface::synth::EPOXY_CORR_LENGTH_M * 1e6,
            env!("CARGO_PKG_VERSION")
        ),
        summary: summary::paragraphs(&out.results, KIRCHHOFF_GLOSS_NM, &real, !plan.quick),
        sections,
    };
    let path = dir.join("report.html");
    report.write(&path)?;
    Ok(DemoOutcome {
        report: path,
        sections: report
            .sections
            .iter()
            .map(|s| (s.title.clone(), s.seconds))
            .collect(),
        seconds: started.elapsed().as_secs_f64(),
    })
}

/// The wavelength of the study's Kirchhoff gloss readings, nm.
const KIRCHHOFF_GLOSS_NM: f64 = 550.0;

fn timed<T>(work: impl FnOnce() -> T) -> (T, f64) {
    let t = Instant::now();
    let out = work();
    (out, t.elapsed().as_secs_f64())
}

/// `section` with the seconds its computation took.
fn with_time(section: Section, seconds: f64) -> Section {
    Section { seconds, ..section }
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
