//! `gonio render`: render a scene file (`docs/render.md`) with the path tracer of
//! `gonio-render` and write the picture as OpenEXR, Radiance HDR or PNG.

use anyhow::{Context, Result};
use clap::{Args, ValueEnum};
use gonio_render::{BrdfSampling, ColourMode, RenderOptions, Scene};
use std::path::PathBuf;

#[derive(Args)]
pub struct RenderArgs {
    /// Scene file (TOML): camera, materials, shapes and lights; see docs/render.md.
    scene: PathBuf,
    /// Output image: .exr (linear float radiance, W m⁻² sr⁻¹), .hdr (Radiance RGBE, linear) or
    /// .png (sRGB after the scene's exposure and tone curve). Written atomically.
    #[arg(short, long)]
    output: PathBuf,
    /// Samples per pixel (1 to 65536; default: the scene's [render] spp, else 64).
    #[arg(long)]
    spp: Option<u32>,
    /// Seed of the sample sequences (default: the scene's, else 0). The image depends only on
    /// the scene, the seed and the samples per pixel, not on the number of threads.
    #[arg(long)]
    seed: Option<u32>,
    /// Worker threads (default: all cores).
    #[arg(long)]
    threads: Option<usize>,
    /// Longest path in surface interactions (default: the scene's, else 8).
    #[arg(long)]
    max_bounces: Option<u32>,
    /// BRDF sampling: each material's importance sampler, or cosine-weighted directions for
    /// every material (to compare the noise of the two).
    #[arg(long, value_enum, default_value_t = Sampling::Importance)]
    sampling: Sampling,
    /// Render spectrally: four hero wavelengths per path (360–830 nm), spectral BRDF tables
    /// evaluated at them, RGB lights and materials turned into spectra, colour formed at the film
    /// (D65, CIE 1931 2°). Default: the tristimulus shortcut (everything in linear sRGB).
    #[arg(long)]
    spectral: bool,
    /// Denoise the picture (an edge-avoiding à-trous filter steered by each pixel's variance
    /// and the first hit's normal, distance and albedo; docs/render.md), replacing the scene's
    /// `[render] denoise`. A denoised picture is smoother but biased where detail is finer than
    /// the noise; leave it off for radiometric work.
    #[arg(long, conflicts_with = "no_denoise")]
    denoise: bool,
    /// Do not denoise, whatever the scene says.
    #[arg(long)]
    no_denoise: bool,
    /// Exposure of PNG output in stops, replacing the scene's.
    #[arg(long, allow_hyphen_values = true)]
    exposure: Option<f64>,
    /// Print the render statistics as JSON (rays, seconds, rays_per_second, denoised).
    #[arg(long)]
    json: bool,
}

#[derive(Clone, Copy, ValueEnum)]
enum Sampling {
    Importance,
    Cosine,
}

pub fn run(args: RenderArgs) -> Result<()> {
    let scene = Scene::from_file(&args.scene)?;
    let opts = RenderOptions {
        spp: args.spp,
        seed: args.seed,
        max_bounces: args.max_bounces,
        threads: args.threads,
        sampling: match args.sampling {
            Sampling::Importance => BrdfSampling::Importance,
            Sampling::Cosine => BrdfSampling::Cosine,
        },
        colour: if args.spectral {
            ColourMode::Spectral
        } else {
            ColourMode::Tristimulus
        },
        denoise: match (args.denoise, args.no_denoise) {
            (true, _) => Some(true),
            (_, true) => Some(false),
            _ => None,
        },
        progress: crate::progress::reporting(&crate::progress::bar(0)),
        cancel: Default::default(),
    };
    let (image, stats) = gonio_render::render(&scene, &opts)
        .with_context(|| format!("rendering {}", args.scene.display()))?;
    let mut display = scene.display;
    if let Some(e) = args.exposure {
        display.exposure = e;
    }
    image.write(&args.output, display)?;
    if args.json {
        let out = serde_json::json!({
            "output": args.output,
            "width_px": image.width,
            "height_px": image.height,
            "rays": stats.rays,
            "seconds": stats.seconds,
            "rays_per_second": stats.rays_per_second(),
            "colour_mode": if args.spectral { "spectral" } else { "tristimulus" },
            "denoised": stats.denoised,
        });
        println!("{}", serde_json::to_string_pretty(&out)?);
    } else {
        eprintln!(
            "{}: {} × {} px, {} rays in {:.1} s ({:.2e} rays/s){}",
            args.output.display(),
            image.width,
            image.height,
            stats.rays,
            stats.seconds,
            stats.rays_per_second(),
            if stats.denoised { ", denoised" } else { "" }
        );
    }
    Ok(())
}
