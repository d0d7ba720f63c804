//! `gonio study`: the roughness study. For a series of surfaces (the synthetic epoxy series by
//! default, or files), in-plane curves by the ray method and the Kirchhoff approximation at the
//! STARR geometry, statistics, gloss, and plots of how the specular peak changes with roughness.
//! Results go to a directory as CSV, JSON and PNG, written by [`gonio_report::study`].

use anyhow::Result;
use clap::Args;
use gonio_instrument::study::{Sample, StudyConfig};
use gonio_report::study::{execute, summary_json, synthetic_samples};
use std::path::PathBuf;

#[derive(Args)]
pub struct StudyArgs {
    /// Height-map files to study instead of synthetic surfaces.
    files: Vec<PathBuf>,
    /// Rms heights Sq of the synthetic series, nm, comma-separated (the NIST epoxy series).
    #[arg(long, value_delimiter = ',', default_value = "3,50,150,201,400,805")]
    sq_nm: Vec<f64>,
    /// Correlation length T of the synthetic surfaces (Gaussian ACF), µm.
    #[arg(long, default_value_t = 6.0)]
    corr_um: f64,
    /// Points along each side of the synthetic maps.
    #[arg(long, default_value_t = 1024)]
    size: usize,
    /// Grid spacing of the synthetic maps, µm.
    #[arg(long, default_value_t = 0.5)]
    dx_um: f64,
    /// Random seed of the synthetic maps (the same for every Sq, so they differ only in scale).
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Refractive index of the coating.
    #[arg(long, default_value_t = 1.55)]
    index: f64,
    /// Wavelengths of the Kirchhoff curves, nm, comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "500,550,600")]
    wavelength_nm: Vec<f64>,
    /// Skip the Kirchhoff curves (ray method only).
    #[arg(long)]
    no_kirchhoff: bool,
    /// Output directory (created if missing).
    #[arg(short, long)]
    output: PathBuf,
    /// Print the summary as JSON.
    #[arg(long)]
    json: bool,
}

pub fn run(args: StudyArgs) -> Result<()> {
    let samples = if args.files.is_empty() {
        synthetic_samples(
            &args.sq_nm,
            args.corr_um * 1e-6,
            args.size,
            args.dx_um * 1e-6,
            args.seed,
        )?
    } else {
        args.files
            .iter()
            .map(|p| {
                Ok(Sample {
                    label: p
                        .file_stem()
                        .map_or("sample".into(), |s| s.to_string_lossy().into_owned()),
                    map: crate::surface::read(p)?,
                })
            })
            .collect::<Result<_>>()?
    };
    let index_warnings = gonio_instrument::validity::check_index(args.index)
        .map_err(|e| anyhow::anyhow!("--index: {e}"))?;
    let config = StudyConfig {
        ior: args.index,
        wavelengths_nm: args.wavelength_nm.clone(),
        kirchhoff: !args.no_kirchhoff,
        ..StudyConfig::starr()
    };
    let bar = crate::progress::bar(0);
    let out = execute(
        &samples,
        &config,
        &args.output,
        &crate::progress::reporting(&bar),
    );
    bar.finish_and_clear();
    let out = out?;
    let mut warnings = index_warnings;
    for r in &out.results {
        warnings.extend(r.warnings.iter().map(|w| format!("{}: {w}", r.label)));
    }
    for w in &warnings {
        eprintln!("warning: {w}");
    }
    if args.json {
        let mut json = summary_json(&out);
        json["warnings"] = serde_json::json!(warnings);
        println!("{}", serde_json::to_string_pretty(&json)?);
    } else {
        for f in out.files.iter().chain(out.plots.iter().map(|p| &p.0)) {
            eprintln!("wrote {}", f.display());
        }
        for r in &out.results {
            for note in &r.notes {
                eprintln!("note: {}: {note}", r.label);
            }
        }
    }
    Ok(())
}
