//! How noisy a picture is: render a scene with N samples per pixel and with 4N, raw and
//! denoised, and a raw reference with 16N, and print the relative RMSE of each picture
//! ([`gonio_render::difference::relative_rmse`]) against the others.
//!
//! ```text
//! cargo run --release -p gonio-render --features studies --example noise -- examples/epoxy.toml [--spp N] [--json]
//! ```
//!
//! What the figures mean (σ the raw N-sample picture's noise, relative to the mean):
//! - `raw_vs_raw4x`: σ √(1 + 1/4), the Monte Carlo noise at N samples;
//! - `denoised_vs_denoised4x`: the denoiser's acceptance criterion (the shown picture against the
//!   same pipeline with four times the samples): the filter's residual noise, plus the change of
//!   its bias between N and 4N;
//! - `denoised_vs_raw16x`: the shown picture against a raw reference with 16 times the samples:
//!   the filter's bias and residual noise, with the reference's own noise σ/4 in quadrature.
//!
//! It also prints the time of each render (the machine's load changes them).

use gonio_render::denoise::{Features, denoise};
use gonio_render::difference::relative_rmse;
use gonio_render::{Image, RenderOptions, Scene, render_estimate};
use std::path::PathBuf;

fn main() {
    if let Err(e) = run() {
        eprintln!("error: {e}");
        std::process::exit(2);
    }
}

fn run() -> Result<(), String> {
    let mut args = std::env::args().skip(1);
    let mut scene_path: Option<PathBuf> = None;
    let (mut spp, mut json) = (None, false);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--spp" => {
                let v = args.next().ok_or("--spp needs a number")?;
                spp = Some(v.parse::<u32>().map_err(|e| format!("--spp {v}: {e}"))?);
            }
            "--json" => json = true,
            _ if scene_path.is_none() => scene_path = Some(a.into()),
            _ => {
                return Err(format!(
                    "unexpected argument {a}; usage: noise SCENE [--spp N] [--json]"
                ));
            }
        }
    }
    let path = scene_path.ok_or("usage: noise SCENE.toml [--spp N] [--json]")?;
    let scene = Scene::from_file(&path).map_err(|e| e.to_string())?;
    let n = spp.or(scene.render.spp).unwrap_or(64);
    let features = Features::of(&scene);
    let estimate = |spp: u32| -> Result<(Image, Image, f64, f64), String> {
        let opts = RenderOptions {
            spp: Some(spp),
            ..Default::default()
        };
        let e = render_estimate(&scene, &opts).map_err(|e| e.to_string())?;
        let start = std::time::Instant::now();
        let d = denoise(&e.image, &e.variance, &features);
        Ok((e.image, d, e.stats.seconds, start.elapsed().as_secs_f64()))
    };
    let (raw, shown, seconds, denoise_seconds) = estimate(n)?;
    let (raw4, shown4, seconds4, _) = estimate(4 * n)?;
    let (raw16, _, seconds16, _) = estimate(16 * n)?;
    let figures = [
        ("raw_vs_raw4x", relative_rmse(&raw, &raw4)),
        ("denoised_vs_denoised4x", relative_rmse(&shown, &shown4)),
        ("denoised_vs_raw16x", relative_rmse(&shown, &raw16)),
        ("denoised4x_vs_raw16x", relative_rmse(&shown4, &raw16)),
        ("raw4x_vs_raw16x", relative_rmse(&raw4, &raw16)),
    ];
    if json {
        let mut out = serde_json::Map::new();
        out.insert("scene".into(), path.display().to_string().into());
        out.insert("spp".into(), n.into());
        out.insert(
            "size_px".into(),
            serde_json::json!([scene.camera.width, scene.camera.height]),
        );
        for (k, v) in figures {
            out.insert(k.into(), v.into());
        }
        out.insert(
            "seconds".into(),
            serde_json::json!({"spp": seconds, "spp4x": seconds4, "spp16x": seconds16,
                               "denoise": denoise_seconds}),
        );
        println!("{}", serde_json::Value::Object(out));
    } else {
        println!(
            "{}: {} × {} px, {n} spp ({seconds:.1} s; denoising {denoise_seconds:.2} s; \
             4x {seconds4:.1} s, 16x {seconds16:.1} s)",
            path.display(),
            scene.camera.width,
            scene.camera.height
        );
        for (k, v) in figures {
            println!("  {k:<24} {:.2}%", 100.0 * v);
        }
    }
    Ok(())
}
