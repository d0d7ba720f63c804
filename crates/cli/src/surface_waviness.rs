//! `gonio surface waviness FILE`: the wave-scan bands of a map's or profile's slope or curvature
//! (`gonio_surface::waviness`, docs/surface.md "Waviness"): the rms slope (with gonio's 0–100
//! value) or curvature in each band, or why a band cannot be read.

use anyhow::Result;
use clap::{Args, ValueEnum};
use gonio_surface::waviness::{self, Direction, Quantity};
use std::path::PathBuf;

#[derive(Clone, Copy, ValueEnum)]
enum DirectionArg {
    X,
    Y,
}

#[derive(Clone, Copy, ValueEnum)]
enum QuantityArg {
    /// dz/dx, reported in mrad (JSON: rad).
    Slope,
    /// d²z/dx², reported in 1/m.
    Curvature,
}

#[derive(Args)]
pub struct WavinessArgs {
    /// Height-map or profile file (any format gonio reads).
    file: PathBuf,
    /// Direction of the scans across a map: x (each row a profile, the default) or y.
    #[arg(long, value_enum, default_value = "x")]
    direction: DirectionArg,
    /// What is band-passed: the slope (rms in mrad, with gonio's 0-100 value) or the curvature
    /// (rms in 1/m, no 0-100 value).
    #[arg(long, value_enum, default_value = "slope")]
    quantity: QuantityArg,
    /// Print one JSON object (rms slopes in rad, key rms_slope_rad; rms curvatures in 1/m, key
    /// rms_curvature_per_m; cutoffs in m).
    #[arg(long)]
    json: bool,
}

pub fn run(a: &WavinessArgs) -> Result<()> {
    let map = super::surface::read_any(&a.file)?;
    let direction = match a.direction {
        DirectionArg::X => Direction::X,
        DirectionArg::Y => Direction::Y,
    };
    let quantity = match a.quantity {
        QuantityArg::Slope => Quantity::Slope,
        QuantityArg::Curvature => Quantity::Curvature,
    };
    let bands = waviness::waviness(&map, direction, quantity)
        .map_err(|e| anyhow::anyhow!("{}: {e}", a.file.display()))?;
    if a.json {
        let key = match quantity {
            Quantity::Slope => "rms_slope_rad",
            Quantity::Curvature => "rms_curvature_per_m",
        };
        let json = serde_json::json!({
            "file": a.file.display().to_string(),
            "direction": match direction { Direction::X => "x", Direction::Y => "y" },
            "quantity": quantity.name(),
            "value_scale_rad": waviness::VALUE_SCALE_RAD,
            "bands": bands.iter().map(|r| serde_json::json!({
                "name": r.band.name, "short_m": r.band.short_m, "long_m": r.band.long_m,
                key: r.rms, "value": r.value(), "samples": r.samples,
                "unresolved": r.unresolved,
            })).collect::<Vec<_>>(),
        });
        println!("{}", serde_json::to_string_pretty(&json)?);
        return Ok(());
    }
    println!(
        "{}: wave-scan bands of the {} along {} (ISO 16610-21 Gaussian filters)",
        a.file.display(),
        quantity.name(),
        match direction {
            Direction::X => "x",
            Direction::Y => "y",
        }
    );
    match quantity {
        Quantity::Slope => println!("band  wavelengths      rms slope   value (gonio's 0-100)"),
        Quantity::Curvature => println!("band  wavelengths      rms curvature"),
    }
    for r in &bands {
        let range = format!("{}-{} mm", r.band.short_m * 1e3, r.band.long_m * 1e3);
        match (r.rms, &r.unresolved) {
            (Some(s), _) => match quantity {
                Quantity::Slope => println!(
                    "{:<5} {range:<16} {:>7.3} mrad {:>5.1}",
                    r.band.name,
                    s * 1e3,
                    waviness::value(s)
                ),
                Quantity::Curvature => {
                    println!("{:<5} {range:<16} {:>9.4} 1/m", r.band.name, s)
                }
            },
            (None, why) => println!(
                "{:<5} {range:<16} {}",
                r.band.name,
                why.as_deref().unwrap_or("not read")
            ),
        }
    }
    if quantity == Quantity::Slope {
        println!(
            "value = 100 (1 - exp(-rms slope / {} mrad)): gonio's own scale, not an instrument's",
            waviness::VALUE_SCALE_RAD * 1e3
        );
    }
    Ok(())
}
