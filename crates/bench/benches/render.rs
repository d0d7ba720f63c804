//! Rays per second of the path tracer on the example scenes (`docs/performance.md`,
//! "Renderer"): the rough plastic sphere on a plane (256 × 256 pixels, 64 samples per pixel) and
//! the epoxy panels (768 × 512 pixels, 16 samples per pixel as the scene asks, BRDF tables by the
//! ray method, computed once and cached beside the scene), both without denoising. Each
//! iteration renders the whole image; rays per second = rays of one render / time. The denoise
//! group times the denoiser alone on the epoxy picture (its first-hit features, then the
//! filter). The colour-mode group renders the metallic-paint scene (Cornell Cayman and Garnet
//! Red spectral tables) at 96 × 64 pixels, 16 samples per pixel, with the tristimulus shortcut
//! and spectrally (hero wavelengths).

use criterion::{Criterion, criterion_group, criterion_main};
use gonio_render::denoise::{Features, denoise};
use gonio_render::scene::SceneDesc;
use gonio_render::{ColourMode, RenderOptions, Scene, render, render_estimate};
use std::path::Path;

fn scene(name: &str) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name);
    Scene::from_file(&path).unwrap()
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("render");
    group.sample_size(10);
    for (name, spp) in [("plastic.toml", 64), ("epoxy.toml", 16)] {
        let s = scene(name);
        let opts = RenderOptions {
            spp: Some(spp),
            denoise: Some(false),
            ..RenderOptions::default()
        };
        let (_, stats) = render(&s, &opts).unwrap();
        println!(
            "{name}: {} × {} px, {spp} spp: {} rays in {:.2} s = {:.3e} rays/s",
            s.camera.width,
            s.camera.height,
            stats.rays,
            stats.seconds,
            stats.rays_per_second()
        );
        group.bench_function(name, |b| b.iter(|| render(&s, &opts).unwrap()));
    }
    group.finish();
}

/// The denoiser alone on the epoxy picture at the scene's 16 samples per pixel.
fn bench_denoise(c: &mut Criterion) {
    let s = scene("epoxy.toml");
    let estimate = render_estimate(&s, &RenderOptions::default()).unwrap();
    let mut group = c.benchmark_group("denoise");
    group.sample_size(10);
    group.bench_function("epoxy_features", |b| b.iter(|| Features::of(&s)));
    let features = Features::of(&s);
    group.bench_function("epoxy_filter", |b| {
        b.iter(|| denoise(&estimate.image, &estimate.variance, &features))
    });
    group.finish();
}

/// The metallic-paint scene at 96 × 64 pixels.
fn small_metallic() -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/metallic.toml");
    let mut desc = SceneDesc::from_toml(&std::fs::read_to_string(&path).unwrap(), &path).unwrap();
    (desc.camera.width, desc.camera.height) = (96, 64);
    Scene::build(&desc, &path).unwrap()
}

fn bench_colour_modes(c: &mut Criterion) {
    let s = small_metallic();
    let mut group = c.benchmark_group("render_colour_mode");
    group.sample_size(10);
    for (name, colour) in [
        ("metallic_96x64_tristimulus", ColourMode::Tristimulus),
        ("metallic_96x64_spectral", ColourMode::Spectral),
    ] {
        let opts = RenderOptions {
            spp: Some(16),
            colour,
            ..RenderOptions::default()
        };
        let (_, stats) = render(&s, &opts).unwrap();
        println!(
            "{name}, 16 spp: {} rays in {:.2} s = {:.3e} rays/s",
            stats.rays,
            stats.seconds,
            stats.rays_per_second()
        );
        group.bench_function(name, |b| b.iter(|| render(&s, &opts).unwrap()));
    }
    group.finish();
}

criterion_group!(benches, bench, bench_denoise, bench_colour_modes);
criterion_main!(benches);
