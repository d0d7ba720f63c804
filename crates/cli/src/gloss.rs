//! `gonio gloss`: what a gloss meter (ISO 2813 at 20/60/85°) and an ASTM E430 appearance meter
//! (haze, distinctness of image) read on a height map (through the ray method or Kirchhoff) or
//! on a tabulated BRDF, with the ASTM D4039 haze index, and warnings where the method cannot be
//! trusted on that map (`gonio_instrument::validity`).

use anyhow::{Context, Result};
use clap::{Args, ValueEnum};
use gonio_instrument::meter::{self, MapMethod};
use std::path::PathBuf;

#[derive(Args)]
pub struct GlossArgs {
    /// A height map (any format `gonio surface` reads) or a tabulated BRDF (.gbrdf).
    input: PathBuf,
    /// Refractive index of the coating (height maps only).
    #[arg(long, default_value_t = 1.55)]
    index: f64,
    /// How a height map scatters light (height maps only).
    #[arg(long, value_enum, default_value_t = GlossMethod::Ray)]
    method: GlossMethod,
    /// Wavelength for --method kirchhoff, nm.
    #[arg(long, default_value_t = 550.0)]
    wavelength_nm: f64,
    /// Print the readings as JSON with the keys gu20, gu60, gu85, haze, haze_wide, haze_20,
    /// haze_20_log, haze_d4039, doi and warnings.
    #[arg(long)]
    json: bool,
}

/// Scattering method for height maps.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum GlossMethod {
    /// Geometric optics on the map's facets, with shadowing and masking.
    Ray,
    /// The scalar Kirchhoff approximation at --wavelength-nm over the largest spot that fits
    /// (the spot must be large enough that its diffraction, about λ/(L cos θ), stays inside the
    /// receptors: at 85° a 0.5 mm spot or more).
    Kirchhoff,
}

pub fn run(args: GlossArgs) -> Result<()> {
    anyhow::ensure!(
        args.wavelength_nm.is_finite() && args.wavelength_nm > 0.0,
        "--wavelength-nm {}: must be positive",
        args.wavelength_nm
    );
    let is_table = args
        .input
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("gbrdf"));
    let reading = if is_table {
        meter::read_table(&gonio_brdf::gbrdf::read(&args.input)?)
    } else {
        let map = crate::surface::read(&args.input)?;
        let method = match args.method {
            GlossMethod::Ray => MapMethod::Ray,
            GlossMethod::Kirchhoff => MapMethod::Kirchhoff {
                wavelength_nm: args.wavelength_nm,
            },
        };
        meter::read_height_map(&map, method, args.index)
    }
    .with_context(|| args.input.display().to_string())?;
    let (report, warnings) = (reading.report, reading.warnings);
    for w in &warnings {
        eprintln!("warning: {w}");
    }
    if args.json {
        let mut json = serde_json::to_value(report)?;
        json["warnings"] = serde_json::json!(warnings);
        println!("{}", serde_json::to_string_pretty(&json)?);
    } else {
        println!("gloss 20°: {:8.2} GU", report.gu20);
        println!("gloss 60°: {:8.2} GU", report.gu60);
        println!("gloss 85°: {:8.2} GU", report.gu85);
        println!(
            "haze:      {:8.3}  (ASTM E430 A: 100 · flux at ±2° / standard's specular flux, 30°)",
            report.haze
        );
        println!(
            "haze 5°:   {:8.3}  (ASTM E430 A wide-angle: flux at ±5°, 30°)",
            report.haze_wide
        );
        println!(
            "haze 20°:  {:8.3}  (ASTM E430 B / ISO 13803 geometry: flux at ±1.9°, 20°)",
            report.haze_20
        );
        println!(
            "log haze:  {:8.1}  (haze 20° on the haze meters' log scale: 1285.1 · log10(haze/20 + 1))",
            report.haze_20_log
        );
        println!(
            "haze D4039:{:8.2}  (ASTM D4039: 60° gloss − 20° gloss, GU)",
            report.haze_d4039
        );
        let uncertainty = if report.doi_uncertainty > 0.0 {
            format!(" ± {:.2}", report.doi_uncertainty)
        } else {
            String::new()
        };
        println!(
            "DOI:       {:8.2}{uncertainty}  (ASTM E430: 100 · (Rs − R0.3) / Rs, equal 0.1° slits, 30°)",
            report.doi
        );
    }
    Ok(())
}
