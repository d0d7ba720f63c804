//! `gonio surface waviness FILE`: the wave-scan bands of a map's or profile's slope
//! (`gonio_surface::waviness`, docs/surface.md "Waviness"): the rms slope in each band, gonio's
//! 0–100 value, or why a band cannot be read.

use anyhow::Result;
use clap::{Args, ValueEnum};
use gonio_surface::waviness::{self, Direction};
use std::path::PathBuf;

#[derive(Clone, Copy, ValueEnum)]
enum DirectionArg {
    X,
    Y,
}

#[derive(Args)]
pub struct WavinessArgs {
    /// Height-map or profile file (any format gonio reads).
    file: PathBuf,
    /// Direction of the scans across a map: x (each row a profile, the default) or y.
    #[arg(long, value_enum, default_value = "x")]
    direction: DirectionArg,
    /// Print one JSON object (rms slopes in rad: keys ending in _rad; cutoffs in m).
    #[arg(long)]
    json: bool,
}

pub fn run(a: &WavinessArgs) -> Result<()> {
    let map = super::surface::read_any(&a.file)?;
    let direction = match a.direction {
        DirectionArg::X => Direction::X,
        DirectionArg::Y => Direction::Y,
    };
    let bands = waviness::waviness(&map, direction)
        .map_err(|e| anyhow::anyhow!("{}: {e}", a.file.display()))?;
    if a.json {
        let json = serde_json::json!({
            "file": a.file.display().to_string(),
            "direction": match direction { Direction::X => "x", Direction::Y => "y" },
            "value_scale_rad": waviness::VALUE_SCALE_RAD,
            "bands": bands.iter().map(|r| serde_json::json!({
                "name": r.band.name, "short_m": r.band.short_m, "long_m": r.band.long_m,
                "rms_slope_rad": r.rms_slope, "value": r.value(), "samples": r.samples,
                "unresolved": r.unresolved,
            })).collect::<Vec<_>>(),
        });
        println!("{}", serde_json::to_string_pretty(&json)?);
        return Ok(());
    }
    println!(
        "{}: wave-scan bands of the slope along {} (ISO 16610-21 Gaussian filters)",
        a.file.display(),
        match direction {
            Direction::X => "x",
            Direction::Y => "y",
        }
    );
    println!("band  wavelengths      rms slope   value (gonio's 0-100)");
    for r in &bands {
        let range = format!("{}-{} mm", r.band.short_m * 1e3, r.band.long_m * 1e3);
        match (r.rms_slope, &r.unresolved) {
            (Some(s), _) => println!(
                "{:<5} {range:<16} {:>7.3} mrad {:>5.1}",
                r.band.name,
                s * 1e3,
                waviness::value(s)
            ),
            (None, why) => println!(
                "{:<5} {range:<16} {}",
                r.band.name,
                why.as_deref().unwrap_or("not read")
            ),
        }
    }
    println!(
        "value = 100 (1 - exp(-rms slope / {} mrad)): gonio's own scale, not an instrument's",
        waviness::VALUE_SCALE_RAD * 1e3
    );
    Ok(())
}
