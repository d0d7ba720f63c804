//! `gonio coating predict FORMULATION.toml --target MEASURED`: a formulation against a
//! measurement, at every geometry of a standard and, for a measured BRDF (.astm), at every
//! measured sample (`gonio_formulation::prediction`, which composes the text and the JSON).

use anyhow::{Context, Result};
use clap::Args;
use gonio_coating::system::default_bands;
use gonio_instrument::multiangle;
use std::path::PathBuf;

#[derive(Args)]
pub struct PredictArgs {
    /// The formulation (TOML), e.g. the output of `gonio coating match`.
    coating: PathBuf,
    /// The measurement: a measured BRDF (.astm, Cornell's text: read at the standard's
    /// geometries as `gonio coating match` reads it, and compared sample by sample), a spectral
    /// table (.gbrdf) or a multi-angle CSV holding the standard's geometries.
    #[arg(long)]
    target: PathBuf,
    /// The geometries: e2539 (45° illumination at aspecular −15, 15, 25, 45, 75, 110°, and 15°
    /// illumination at −15, 15, 45, 80°) or e2194 (45° only).
    #[arg(long, default_value = "e2539")]
    standard: String,
    /// Random walks per geometry and per measured sample (a rough top or flakes); the noise of
    /// L* falls as 1/sqrt(walks).
    #[arg(long, default_value_t = 4096)]
    walks: usize,
    /// Print the result as JSON (every sample's summary, the means per illumination angle).
    #[arg(long)]
    json: bool,
}

pub fn predict(a: PredictArgs) -> Result<()> {
    let coating = crate::coating::read(&a.coating, &default_bands())?;
    let geometries = multiangle::standard(&a.standard).context("--standard")?;
    anyhow::ensure!(a.walks > 0, "--walks must be at least 1");
    let p = gonio_formulation::prediction::predict(&coating, &a.target, geometries, a.walks)
        .with_context(|| format!("{} against {}", a.coating.display(), a.target.display()))?;
    if a.json {
        let mut json = p.to_json();
        json["file"] = a.coating.display().to_string().into();
        println!("{}", serde_json::to_string_pretty(&json)?);
    } else {
        println!("{} against {}", a.coating.display(), a.target.display());
        print!("{}", p.report());
    }
    Ok(())
}
