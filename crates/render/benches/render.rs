//! Rays per second of the path tracer on the example scenes (`docs/performance.md`,
//! "Renderer"): the rough plastic sphere on a plane (256 × 256 pixels) and the epoxy panels
//! (384 × 256 pixels, BRDF tables by the ray method, computed once and cached beside the scene),
//! both at 64 samples per pixel. Each iteration renders the whole image; rays per second = rays
//! of one render / time.

use criterion::{Criterion, criterion_group, criterion_main};
use gonio_render::{RenderOptions, Scene, render};
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
    for name in ["plastic.toml", "epoxy.toml"] {
        let s = scene(name);
        let opts = RenderOptions {
            spp: Some(64),
            ..RenderOptions::default()
        };
        let (_, stats) = render(&s, &opts).unwrap();
        println!(
            "{name}: {} × {} px, 64 spp: {} rays in {:.2} s = {:.3e} rays/s",
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

criterion_group!(benches, bench);
criterion_main!(benches);
