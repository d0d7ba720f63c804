//! `gonio coating compute | info`: a coating described in TOML (a smooth clear coat over a
//! diffuse or Kubelka-Munk base; `docs/coatings.md`) turned into a spectral BRDF table of its
//! body reflection, and a summary of its optics and multi-angle colour
//! (`gonio_coating::clear_coat`, `gonio_instrument::multiangle`).

use anyhow::{Context, Result};
use clap::{Args, Subcommand};
use gonio_coating::clear_coat::{self, AtWavelength, ClearCoatOverBase};
use gonio_coating::description;
use gonio_instrument::multiangle::{self, E2194, MultiangleReading, Settings};
use std::path::{Path, PathBuf};

#[derive(Subcommand)]
pub enum CoatingCommand {
    /// Tabulate the coating's body reflection (everything but the coat's mirror reflection) as a
    /// spectral .gbrdf: `gonio coating compute COATING.toml -o T.gbrdf`.
    Compute(ComputeArgs),
    /// The coating's optics: coat index, base reflectance, the coat's mirror reflectance at the
    /// gloss angles, the directional-hemispherical reflectance, and its multi-angle colour
    /// (ASTM E2194, D65/10°).
    Info(InfoArgs),
}

#[derive(Args)]
pub struct ComputeArgs {
    /// The coating's description (TOML; examples/coatings/).
    coating: PathBuf,
    /// Output table (.gbrdf).
    #[arg(short, long)]
    output: PathBuf,
    /// Nodes theta_h,theta_d,phi_d of the table.
    #[arg(long, value_delimiter = ',', default_values_t = crate::brdf::import_resolution())]
    resolution: Vec<usize>,
    /// Wavelengths of the table's channels, nm: first:last:step.
    #[arg(long, default_value = "400:700:10")]
    bands: String,
}

#[derive(Args)]
pub struct InfoArgs {
    /// The coating's description (TOML).
    coating: PathBuf,
    /// Print JSON: coat_index, base_reflectance, specular (20/60/85°), albedo (0/45/75°, at
    /// 550 nm) and multiangle (as `gonio multiangle --json`'s geometries).
    #[arg(long)]
    json: bool,
}

pub fn run(cmd: CoatingCommand) -> Result<()> {
    match cmd {
        CoatingCommand::Compute(a) => compute(a),
        CoatingCommand::Info(a) => info(a),
    }
}

/// The 31 bands 400, 410, ..., 700 nm, or those of `--bands first:last:step`.
fn bands(spec: &str) -> Result<Vec<f64>> {
    let parts: Vec<f64> = spec
        .split(':')
        .map(|p| p.trim().parse::<f64>())
        .collect::<std::result::Result<_, _>>()
        .with_context(|| format!("--bands {spec}: write first:last:step in nm, e.g. 400:700:10"))?;
    let [first, last, step] = parts[..] else {
        anyhow::bail!("--bands {spec}: write first:last:step in nm, e.g. 400:700:10");
    };
    anyhow::ensure!(
        first > 0.0 && last > first && step > 0.0 && ((last - first) / step) < 1000.0,
        "--bands {spec}: needs 0 < first < last and a positive step (at most 1000 bands)"
    );
    let n = ((last - first) / step + 1e-9).floor() as usize + 1;
    anyhow::ensure!(n >= 2, "--bands {spec}: needs at least two bands");
    Ok((0..n).map(|i| first + step * i as f64).collect())
}

fn read(path: &Path, wavelengths: &[f64]) -> Result<ClearCoatOverBase> {
    Ok(description::read(path, wavelengths)?)
}

fn compute(a: ComputeArgs) -> Result<()> {
    let wavelengths = bands(&a.bands)?;
    let res = crate::brdf::resolution(&a.resolution)?;
    let stack = read(&a.coating, &wavelengths)?;
    let provenance = clear_coat::body_provenance(a.coating.display().to_string());
    let table = stack
        .body_table(res, &wavelengths, provenance)
        .with_context(|| a.coating.display().to_string())?;
    gonio_brdf::gbrdf::write(&table, &a.output)?;
    eprintln!(
        "{}: {} × {} × {} nodes, {} bands {}–{} nm (body reflection; the mirror reflection \
         is not in the table)",
        a.output.display(),
        res.theta_h,
        res.theta_d,
        res.phi_d,
        wavelengths.len(),
        wavelengths[0],
        wavelengths[wavelengths.len() - 1]
    );
    Ok(())
}

/// The stack's multi-angle reading at the E2194 geometries (the mirror reflection is 15° or
/// more away from every one of them).
fn multiangle_reading(optics: &[AtWavelength], wavelengths: &[f64]) -> Result<MultiangleReading> {
    let body = |wo: glam::DVec3, wi: glam::DVec3, out: &mut [f64]| {
        for (o, at) in out.iter_mut().zip(optics) {
            *o = at.brdf(wi.z, wo.z);
        }
    };
    Ok(multiangle::read(
        &body,
        wavelengths,
        &E2194,
        &Settings::default(),
    )?)
}

fn info(a: InfoArgs) -> Result<()> {
    let wavelengths = bands("400:700:10")?;
    let stack = read(&a.coating, &wavelengths)?;
    let optics = wavelengths
        .iter()
        .map(|&w| stack.at(w))
        .collect::<gonio_coating::Result<Vec<_>>>()?;
    // The optics at one of the 31 bands, computed once above.
    let at = |nm: f64| {
        let band = wavelengths
            .iter()
            .position(|&w| w == nm)
            .expect("400, 450, ..., 700 nm are among the 10 nm bands");
        &optics[band]
    };
    let at550 = at(550.0);
    let gloss_angles = [20.0f64, 60.0, 85.0];
    let specular: Vec<f64> = gloss_angles
        .iter()
        .map(|d| at550.specular(d.to_radians().cos()))
        .collect();
    let albedo_angles = [0.0f64, 45.0, 75.0];
    let albedo: Vec<f64> = albedo_angles
        .iter()
        .map(|d| {
            let c = d.to_radians().cos();
            at550.specular(c) + at550.body_albedo(c)
        })
        .collect();
    let reading = multiangle_reading(&optics, &wavelengths)?;
    if a.json {
        let json = serde_json::json!({
            "file": a.coating.display().to_string(),
            "coat_index": { "400": at(400.0).n, "550": at550.n, "700": at(700.0).n },
            "base_reflectance": wavelengths.iter().zip(&optics).map(|(w, o)| serde_json::json!({"nm": w, "reflectance": o.rho})).collect::<Vec<_>>(),
            "specular": gloss_angles.iter().zip(&specular).map(|(d, r)| serde_json::json!({"theta_deg": d, "reflectance": r})).collect::<Vec<_>>(),
            "albedo": albedo_angles.iter().zip(&albedo).map(|(d, r)| serde_json::json!({"theta_i_deg": d, "albedo": r})).collect::<Vec<_>>(),
            "multiangle": reading.geometries.iter().map(|g| serde_json::json!({
                "name": g.geometry.to_string(), "L": g.lab.l, "a": g.lab.a, "b": g.lab.b,
                "C": g.lab.chroma(), "h_deg": g.lab.hue_deg(),
            })).collect::<Vec<_>>(),
            "flop_index": reading.flop_index(),
        });
        println!("{}", serde_json::to_string_pretty(&json)?);
        return Ok(());
    }
    println!("{}", a.coating.display());
    println!(
        "coat: n {:.4} / {:.4} / {:.4} at 400 / 550 / 700 nm, {} µm",
        at(400.0).n,
        at550.n,
        at(700.0).n,
        stack.coat.thickness_um
    );
    let rho: Vec<String> = [400.0, 450.0, 500.0, 550.0, 600.0, 650.0, 700.0]
        .iter()
        .map(|&w| format!("{:.3}", at(w).rho))
        .collect();
    println!(
        "base reflectance at 400, 450, ..., 700 nm: {}",
        rho.join(" ")
    );
    println!(
        "mirror reflectance of the coat (550 nm) at 20 / 60 / 85°: {:.4} / {:.4} / {:.4}",
        specular[0], specular[1], specular[2]
    );
    println!(
        "directional-hemispherical reflectance (550 nm) at 0 / 45 / 75°: {:.4} / {:.4} / {:.4}",
        albedo[0], albedo[1], albedo[2]
    );
    println!("multi-angle colour (ASTM E2194, D65/10°):");
    println!(
        "{:>9} {:>8} {:>8} {:>8} {:>8}",
        "geometry", "L*", "a*", "b*", "C*ab"
    );
    for g in &reading.geometries {
        println!(
            "{:>9} {:>8.2} {:>8.2} {:>8.2} {:>8.2}",
            g.geometry.to_string(),
            g.lab.l,
            g.lab.a,
            g.lab.b,
            g.lab.chroma()
        );
    }
    if let Some(fi) = reading.flop_index() {
        println!("flop index: {fi:.2}");
    }
    Ok(())
}
