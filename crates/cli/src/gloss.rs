//! `gonio gloss`: what a gloss meter (ISO 2813 at 20/60/85°) and an ASTM E430-style appearance
//! meter (haze, distinctness of image) read on a height map (through the ray method) or on a
//! tabulated BRDF.

use anyhow::{Context, Result};
use clap::{Args, ValueEnum};
use gonio_brdf::{Brdf, Ior};
use gonio_instrument::gloss::{BrdfSpecimen, GlossReport, measure};
use gonio_instrument::specimens::{KirchhoffSpecimen, RaySpecimen};
use gonio_scatter::kirchhoff::{Kirchhoff, KirchhoffOptions};
use gonio_scatter::ray::{RayEngine, RayOptions};
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
    /// Print the readings as JSON with the keys gu20, gu60, gu85, haze, doi.
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
    let is_table = args
        .input
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("gbrdf"));
    let report: GlossReport = if is_table {
        let table = gonio_brdf::gbrdf::read(&args.input)?;
        // Gloss is a photometric reading: the luminance (Rec. 709 / sRGB Y) of the BRDF's channels.
        let specimen = BrdfSpecimen::new(|wi, wo| {
            let f = table.eval(wo, wi);
            0.2126 * f.x + 0.7152 * f.y + 0.0722 * f.z
        });
        measure(&specimen)?
    } else {
        let map = crate::surface::read(&args.input)?;
        match args.method {
            GlossMethod::Ray => {
                let options = RayOptions {
                    ior: Ior::Dielectric(args.index),
                    ..RayOptions::default()
                };
                let engine = RayEngine::new(&map, options)
                    .with_context(|| format!("{}: ray method", args.input.display()))?;
                measure(&RaySpecimen { engine: &engine })?
            }
            GlossMethod::Kirchhoff => {
                let options = KirchhoffOptions::new(Ior::Dielectric(args.index));
                let engine = Kirchhoff::new(&map, options)
                    .with_context(|| format!("{}: Kirchhoff", args.input.display()))?;
                measure(&KirchhoffSpecimen {
                    engine: &engine,
                    wavelength: args.wavelength_nm * 1e-9,
                })?
            }
        }
    };
    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        println!("gloss 20°: {:8.2} GU", report.gu20);
        println!("gloss 60°: {:8.2} GU", report.gu60);
        println!("gloss 85°: {:8.2} GU", report.gu85);
        println!(
            "haze:      {:8.3}  (100 · flux at ±2° / standard's specular flux, 30°)",
            report.haze
        );
        println!(
            "DOI:       {:8.2}  (100 · (specular − flux at ±0.3°) / specular, 30°)",
            report.doi
        );
    }
    Ok(())
}
