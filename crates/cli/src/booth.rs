//! `gonio booth`: the virtual viewing booth (docs/standard.md): render a coating or a BRDF table
//! in the standard booth (or a booth spec) and write each view's absolute XYZ OpenEXR, sRGB and
//! Display P3 PNGs with their masks, the specimen's mask and the manifest into a folder. It
//! parses and prints; `gonio_render::booth` computes and writes.

use anyhow::{Context, Result};
use clap::Args;
use gonio_io::Progress;
use gonio_render::booth::{self, BoothJob, Resolved, Run};
use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};

#[derive(Args)]
pub struct BoothArgs {
    /// A booth spec (.toml with the booth's tables [light], [interior], [specimen] with its
    /// `material`, [camera], [render]; docs/standard.md), a coating description (.toml with
    /// [coat] and [base]; docs/coatings.md) or a spectral BRDF table (.gbrdf). A coating or a
    /// table alone is shown in the standard booth (or --booth's).
    input: PathBuf,
    /// Output folder (made if missing): per view NAME.exr (absolute CIE XYZ, cd/m²),
    /// NAME-srgb.png and NAME-p3.png (ICC profile embedded), their -mask.png (magenta out of
    /// gamut, yellow over range, cyan both), NAME-specimen.png; then manifest.json (SHA-256 of
    /// every input and output, the seed, the settings). Every file is written atomically.
    #[arg(short, long)]
    output: PathBuf,
    /// The booth spec for a coating or table INPUT (default: the standard booth, the spec of
    /// an empty file: D65 at 2000 lx, half directional at 45°, N6 interior, a flat 150 × 100 mm
    /// panel, the views near-specular, 45 and flank, CIE 1964 10° observer).
    #[arg(long, value_name = "SPEC.toml")]
    booth: Option<PathBuf>,
    /// Samples per pixel, 1 to 65536 (default: the spec's [render] spp, else 64).
    #[arg(long)]
    spp: Option<u32>,
    /// Seed of the sample sequences (default: the spec's, else 0). The pictures depend only on
    /// the spec, the material, the seed, the size and the samples, not on the threads.
    #[arg(long)]
    seed: Option<u32>,
    /// Picture size in pixels, WIDTHxHEIGHT, each 1 to 32768 (default: the spec's, else
    /// 480x320).
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    size: Option<(usize, usize)>,
    /// Worker threads (default: all cores).
    #[arg(long)]
    threads: Option<usize>,
    /// Print the summary as JSON on stdout instead of the table.
    #[arg(long)]
    json: bool,
}

/// One bar for the whole booth: the renderer reports each view's tiles (`rendering`) and then
/// the views done (`booth`); the bar counts thousandths of a view, so that it runs once from 0
/// to the last view's end.
fn whole_booth(bar: Progress, views: usize) -> Progress {
    const STEPS: u64 = 1000;
    let done_views = Arc::new(AtomicU64::new(0));
    let total = STEPS * views as u64;
    Progress::new(move |r| {
        let position = if r.stage == "booth" {
            done_views.store(r.done, Ordering::Relaxed);
            STEPS * r.done
        } else {
            let view = done_views.load(Ordering::Relaxed);
            STEPS * view + STEPS * r.done / r.total.max(1)
        };
        bar.report("booth", position.min(total), total);
    })
}

/// `WIDTHxHEIGHT`, each at least 1 pixel.
fn parse_size(text: &str) -> std::result::Result<(usize, usize), String> {
    let (w, h) = text.split_once(['x', 'X', '×']).ok_or_else(|| {
        format!("`{text}`: give the size as WIDTHxHEIGHT in pixels, e.g. 480x320")
    })?;
    let px = |s: &str| {
        s.trim()
            .parse::<usize>()
            .ok()
            .filter(|&v| (1..=1 << 15).contains(&v))
            .ok_or_else(|| {
                format!("`{text}`: width and height are whole numbers of pixels, 1 to 32768")
            })
    };
    Ok((px(w)?, px(h)?))
}

pub fn run(args: BoothArgs) -> Result<()> {
    let Resolved {
        mut spec,
        spec_file,
        material,
    } = Resolved::from_files(&args.input, args.booth.as_deref())
        .with_context(|| format!("reading the booth's input {}", args.input.display()))?;
    if let Some(spp) = args.spp {
        spec.render.spp = spp;
    }
    if let Some(seed) = args.seed {
        spec.render.seed = seed;
    }
    if let Some((w, h)) = args.size {
        spec.render.width = w;
        spec.render.height = h;
    }
    spec.check()
        .context("the booth's settings (with the flags given)")?;
    let bar = crate::progress::bar(0);
    let run = Run {
        threads: args.threads,
        progress: whole_booth(crate::progress::reporting(&bar), spec.camera.views.len()),
        ..Run::default()
    };
    let job = BoothJob {
        spec: &spec,
        spec_file: spec_file.as_deref(),
        material: material.as_deref(),
    };
    let summary = booth::write_booth(&job, &args.output, &run)
        .with_context(|| format!("rendering the booth of {}", args.input.display()))?;
    bar.finish_and_clear();
    if args.json {
        println!("{}", serde_json::to_string_pretty(&summary.to_json())?);
        return Ok(());
    }
    println!(
        "{} in the booth: {} at {} lx, white Y = {:.1} cd/m², seed {}",
        summary.material.display(),
        summary.light,
        summary.illuminance_lux,
        summary.white[1],
        summary.seed
    );
    println!(
        "{:<14} {:>9} {:>12} {:>9} | {:>9} {:>9} | {:>9} {:>9}",
        "view", "aspec_deg", "Y_cd_m2", "pixels", "srgb_oog", "srgb_over", "p3_oog", "p3_over"
    );
    for v in &summary.views {
        let mut line = format!(
            "{:<14} {:>9.1} {:>12.3} {:>9}",
            v.name, v.aspecular_deg, v.specimen_luminance, v.specimen_pixels
        );
        for d in &v.files.displays {
            line.push_str(&format!(
                " | {:>8.2}% {:>8.2}%",
                100.0 * d.out_of_gamut_fraction,
                100.0 * d.over_range_fraction
            ));
        }
        println!("{line}");
    }
    println!(
        "(Y: the specimen's mean luminance over the pixels it covers whole; oog, over: the \
         share of pixels out of the display's gamut, brighter than the white)"
    );
    println!(
        "wrote {} views into {}, manifest {}",
        summary.views.len(),
        args.output.display(),
        summary.manifest.display()
    );
    Ok(())
}
