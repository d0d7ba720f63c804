//! `gonio texture COATING.toml`: the virtual texture camera ([`gonio_render::texture`]) on a
//! coating description: sparkle under a lamp at 15°, 45° and 75°, graininess under diffuse
//! light, read from pictures of the coating's flakes drawn one by one.

use crate::progress::spinner;
use anyhow::Result;
use clap::Args;
use gonio_coating::system::default_bands;
use gonio_render::texture::{TextureCamera, TextureReading, measure};
use gonio_report::texture_pictures::write_pictures;
use serde_json::{Value, json};
use std::path::{Path, PathBuf};

#[derive(Args, Debug)]
pub struct TextureArgs {
    /// The coating description (TOML, docs/coatings.md); its `[flakes] diameter_um` sets the
    /// flakes' size (default 20 µm).
    coating: PathBuf,
    /// Side of the square field seen by the camera, mm.
    #[arg(long, default_value_t = 6.0)]
    field_mm: f64,
    /// Pixel footprint on the specimen, µm (the field is field_mm·1000/pixel_um pixels a
    /// side, 16 to 4096).
    #[arg(long, default_value_t = 15.0)]
    pixel_um: f64,
    /// Samples per pixel of each picture.
    #[arg(long, default_value_t = 16)]
    spp: u32,
    /// Seed that places the flakes (another seed: another patch of the same coating).
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Write the pictures (PNG: sparkle_15.png, sparkle_45.png, sparkle_75.png, diffuse.png)
    /// into this folder.
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// Print the readings as JSON.
    #[arg(long)]
    json: bool,
}

pub fn run(a: TextureArgs) -> Result<()> {
    let coating = gonio_coating::description::read(&a.coating, &default_bands())?;
    let camera = TextureCamera {
        field_mm: a.field_mm,
        pixel_um: a.pixel_um,
        spp: a.spp,
        flake_seed: a.seed,
        threads: None,
    };
    let bar = spinner("texture camera");
    let source = a.coating.display().to_string();
    let reading = measure(&coating, &source, &camera, &|k, what| {
        bar.set_message(format!("texture camera: picture {k} of 5, {what}"));
    });
    bar.finish_and_clear();
    let reading = reading?;
    if let Some(dir) = &a.output {
        write_pictures(&reading, dir)?;
    }
    if a.json {
        println!(
            "{}",
            serde_json::to_string_pretty(&to_json(&reading, &camera))?
        );
    } else {
        print!("{}", text(&reading, &camera, &a.coating));
    }
    Ok(())
}

/// The readings as JSON.
fn to_json(r: &TextureReading, camera: &TextureCamera) -> Value {
    json!({
        "camera": {
            "field_mm": camera.field_mm,
            "pixel_um": camera.pixel_um,
            "pixels": camera.pixels(),
            "spp": camera.spp,
            "flake_seed": camera.flake_seed,
            "lamp_radius_deg": gonio_render::texture::LAMP_RADIUS_DEG,
        },
        "sparkle": r.sparkle.iter().map(|s| json!({
            "lamp_deg": s.angle_deg,
            "spots": s.sparkle.spots,
            "density_per_mm2": s.sparkle.density_per_mm2,
            "area_percent": s.sparkle.area_percent,
            "intensity": s.sparkle.intensity,
            "grade": s.sparkle.grade,
        })).collect::<Vec<_>>(),
        "graininess_percent": r.graininess,
        "graininess_uncertainty_percent": r.graininess_uncertainty,
    })
}

/// The readings as a table.
fn text(r: &TextureReading, camera: &TextureCamera, coating: &Path) -> String {
    let mut out = format!(
        "{}: texture camera, {} mm field at {} µm per pixel ({} px), {} samples per pixel\n\n\
         lamp   spots  density   area   intensity   grade\n\
         deg           1/mm²     %      contrast    %\n",
        coating.display(),
        camera.field_mm,
        camera.pixel_um,
        camera.pixels(),
        camera.spp
    );
    for s in &r.sparkle {
        let p = &s.sparkle;
        out.push_str(&format!(
            "{:>4}  {:>6}  {:>7.2}  {:>6.3}  {:>9.1}  {:>7.3}\n",
            s.angle_deg, p.spots, p.density_per_mm2, p.area_percent, p.intensity, p.grade
        ));
    }
    out.push_str(&format!(
        "\ngraininess (diffuse light): {:.2} ± {:.3} %\n\
         (gonio's own scales, docs/instruments.md \"Texture\": not a commercial instrument's)\n",
        r.graininess, r.graininess_uncertainty
    ));
    out
}
