//! `gonio brdf compute`: the full tabulated BRDF of a height map by the ray method or the
//! Kirchhoff approximation, written as a .gbrdf table. The work is done by
//! `gonio_scatter::table`; this file parses the flags, shows progress and writes the file.

use anyhow::{Context, Result, bail};
use clap::{Args, ValueEnum};
use gonio_brdf::Ior;
use gonio_brdf::gbrdf;
use gonio_brdf::table::{BrdfTable, Provenance, Resolution};
use gonio_scatter::kirchhoff::{GEOMETRIC_ABOVE_G, Kirchhoff, KirchhoffOptions};
use gonio_scatter::ray::{RayEngine, RayOptions};
use gonio_scatter::table::{self, KirchhoffMethods, TableOptions, kirchhoff_table, ray_table};
use num_complex::Complex64;
use std::path::PathBuf;
use std::time::Instant;

/// Scattering methods `gonio brdf compute` runs.
#[derive(Clone, Copy, PartialEq, ValueEnum)]
pub enum ComputeMethod {
    /// Geometric optics on the facets of the map (one monochrome channel).
    Ray,
    /// Scalar Kirchhoff integral over the map (one channel per wavelength).
    Kirchhoff,
}

#[derive(Args)]
pub struct ComputeArgs {
    /// The height map (any format `gonio surface info` reads).
    surface: PathBuf,
    /// Output table (.gbrdf).
    #[arg(short, long)]
    output: PathBuf,
    /// Scattering method.
    #[arg(long, value_enum, default_value = "ray")]
    method: ComputeMethod,
    /// Refractive index of the material (real part).
    #[arg(long, default_value_t = 1.55)]
    index: f64,
    /// Imaginary part of the refractive index (extinction coefficient k, for metals).
    #[arg(long)]
    index_imag: Option<f64>,
    /// Kirchhoff: wavelengths in nm, comma-separated and increasing; one gives a monochrome
    /// table, several a spectral one.
    #[arg(long, value_delimiter = ',', default_value = "550")]
    wavelength_nm: Vec<f64>,
    /// Kirchhoff: the Rayleigh parameter g = (2π σ (cos θi + cos θo)/λ)² above which the
    /// stationary-phase (geometric) limit of the integral is used instead of the integral,
    /// whose cost grows with g while it tends to the limit (at g = 25 within about 9% at the
    /// lobe's peak; docs/kirchhoff.md). `inf`: the full integral everywhere.
    #[arg(long, default_value_t = GEOMETRIC_ABOVE_G)]
    geometric_above_g: f64,
    /// Table nodes theta_h,theta_d,phi_d for an isotropic table, or theta_h,theta_d,phi_d,phi_h
    /// for an anisotropic one. theta_h nodes are spaced as the square of their index (32 nodes:
    /// 0.09°, 0.35°, 0.8°, 1.4°, ... from the specular direction); theta_d nodes every
    /// 90°/theta_d, phi_d every 360°/phi_d (even), phi_h every 360°/phi_h.
    #[arg(long, value_delimiter = ',', default_value = "32,90,180")]
    resolution: Vec<usize>,
    /// Number of polar angles of incidence computed (every 90°/N from 0°); default: one per
    /// theta_d node.
    #[arg(long)]
    incidences: Option<usize>,
    /// Azimuths of incidence (every 360°/N). Isotropic tables average the surface over them,
    /// as a sample turned at random under the instrument (default from the map's texture
    /// aspect ratio Str: 1 from 0.5 up, 8 from 0.3 to 0.5, 24 below 0.3); anisotropic tables
    /// interpolate between them (default: one per phi_h node).
    #[arg(long)]
    incidence_azimuths: Option<usize>,
    /// No shadowing or masking by the height field: the ray method as the original NIST
    /// method; the Kirchhoff integral as it stands, without Smith's G2 of the spot's slopes.
    #[arg(long)]
    no_shadowing: bool,
    /// Print a JSON summary (file, resolution, time, albedo) instead of text.
    #[arg(long)]
    json: bool,
}

/// Run `gonio brdf compute`.
pub fn run(a: ComputeArgs) -> Result<()> {
    let mut options = table_options(&a)?;
    let ior = match a.index_imag {
        Some(k) if k > 0.0 => Ior::Conductor(Complex64::new(a.index, k)),
        _ => Ior::Dielectric(a.index),
    };
    if !(a.index.is_finite() && a.index > 0.0) {
        bail!("--index {}: the refractive index must be positive", a.index);
    }
    if a.geometric_above_g.is_nan() || a.geometric_above_g <= 0.0 {
        bail!(
            "--geometric-above-g {}: the Rayleigh parameter must be positive (inf: the full \
             integral everywhere)",
            a.geometric_above_g
        );
    }
    let map = crate::surface::read(&a.surface)
        .with_context(|| format!("cannot read the height map {}", a.surface.display()))?;
    let str_ratio = table::texture_aspect_ratio(&map);
    if options.resolution.is_isotropic() && a.incidence_azimuths.is_none() {
        options.incidence_azimuths = table::isotropic_turns(str_ratio);
    }
    let warnings: Vec<String> = table::anisotropy_warning(str_ratio, &options)
        .into_iter()
        .collect();
    for w in &warnings {
        eprintln!("warning: {}: {w}", a.surface.display());
    }
    let method = match a.method {
        ComputeMethod::Ray => "ray",
        ComputeMethod::Kirchhoff => "kirchhoff",
    };
    let mut provenance = Provenance::new(a.surface.display().to_string(), method);
    provenance.refractive_index = Some([a.index, a.index_imag.unwrap_or(0.0)]);
    provenance.extra.insert(
        "incidences".into(),
        serde_json::json!({
            "polar": options.incidence_polar,
            "azimuths": options.incidence_azimuths,
        }),
    );
    let runs = options.incidence_count()
        * match a.method {
            ComputeMethod::Ray => 1,
            ComputeMethod::Kirchhoff => a.wavelength_nm.len(),
        };
    let bar = crate::progress::bar(runs as u64);
    bar.set_message(format!("brdf compute ({method})"));
    let progress = crate::progress::reporting(&bar);
    let start = Instant::now();
    let mut methods = Vec::new();
    let table = match a.method {
        ComputeMethod::Ray => {
            if a.wavelength_nm != [550.0] {
                bail!(
                    "--wavelength-nm applies to --method kirchhoff; the ray method does not \
                     depend on the wavelength"
                );
            }
            let ray_options = RayOptions {
                ior,
                shadowing: !a.no_shadowing,
                ..RayOptions::default()
            };
            provenance.extra.insert(
                "ray".into(),
                serde_json::json!({"shadowing": !a.no_shadowing}),
            );
            let engine = RayEngine::new(&map, ray_options)
                .with_context(|| format!("{}", a.surface.display()))?;
            ray_table(&engine, &options, provenance, &progress)?
        }
        ComputeMethod::Kirchhoff => {
            let engine = Kirchhoff::new(
                &map,
                KirchhoffOptions {
                    geometric_above: a.geometric_above_g,
                    shadowing: !a.no_shadowing,
                    ..KirchhoffOptions::new(ior)
                },
            )
            .with_context(|| format!("{}", a.surface.display()))?;
            methods = table::kirchhoff_methods(&engine, &a.wavelength_nm, &options)
                .with_context(|| format!("{}", a.surface.display()))?;
            kirchhoff_table(&engine, &a.wavelength_nm, &options, provenance, &progress)
                .with_context(|| format!("{}", a.surface.display()))?
        }
    };
    bar.finish_and_clear();
    let seconds = start.elapsed().as_secs_f64();
    gbrdf::write(&table, &a.output)
        .with_context(|| format!("cannot write {}", a.output.display()))?;
    report(&a, &table, seconds, ior, &warnings, &methods)
}

/// The table and incidence options from the flags.
fn table_options(a: &ComputeArgs) -> Result<TableOptions> {
    let resolution = match a.resolution[..] {
        [th, td, pd] => Resolution::isotropic(th, td, pd),
        [th, td, pd, ph] if ph > 1 => Resolution::anisotropic(th, td, pd, ph),
        _ => bail!(
            "--resolution takes theta_h,theta_d,phi_d (isotropic) or theta_h,theta_d,phi_d,phi_h \
             with phi_h > 1 (anisotropic), e.g. 32,90,180"
        ),
    };
    let mut options = if resolution.is_isotropic() {
        TableOptions::for_resolution(resolution)
    } else {
        TableOptions {
            resolution,
            ..TableOptions::anisotropic()
        }
    };
    if let Some(n) = a.incidences {
        options.incidence_polar = n;
    }
    if let Some(m) = a.incidence_azimuths {
        options.incidence_azimuths = m;
    }
    options
        .validate()
        .map_err(|e| anyhow::anyhow!("--resolution/--incidences: {e}"))?;
    Ok(options)
}

/// Print what was written: text, or JSON with `--json`.
fn report(
    a: &ComputeArgs,
    table: &BrdfTable,
    seconds: f64,
    ior: Ior,
    warnings: &[String],
    methods: &[KirchhoffMethods],
) -> Result<()> {
    let angles = [0.0, 30.0, 60.0];
    let albedo = table.albedo_curve(&angles);
    let fresnel_r: Vec<f64> = angles
        .iter()
        .map(|t: &f64| ior.reflectance(t.to_radians().cos()))
        .collect();
    if a.json {
        let rows: Vec<_> = angles
            .iter()
            .zip(&albedo.albedo)
            .zip(&fresnel_r)
            .map(|((t, al), r)| {
                serde_json::json!({"theta_i_deg": t, "albedo": al, "fresnel_reflectance": r})
            })
            .collect();
        let out = serde_json::json!({
            "file": a.output.display().to_string(),
            "surface": a.surface.display().to_string(),
            "resolution": table.resolution(),
            "channels": table.channels(),
            "seconds": seconds,
            "albedo": rows,
            "warnings": warnings,
            "kirchhoff_methods": methods.iter().map(KirchhoffMethods::to_json).collect::<Vec<_>>(),
        });
        println!("{}", serde_json::to_string_pretty(&out)?);
        return Ok(());
    }
    println!(
        "wrote {} ({}, {}) in {seconds:.1} s",
        a.output.display(),
        table.resolution().describe(),
        table.channels().describe()
    );
    for m in methods {
        println!("kirchhoff at {}", m.describe());
    }
    for ((t, al), r) in angles.iter().zip(&albedo.albedo).zip(&fresnel_r) {
        let shown: Vec<String> = al.iter().map(|v| format!("{v:.4}")).collect();
        println!(
            "albedo at {t:>2}°: {} (flat surface: {r:.4})",
            shown.join(" ")
        );
    }
    Ok(())
}
