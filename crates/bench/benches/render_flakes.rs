//! The discrete flakes' cost (`docs/performance.md`, "Discrete flakes"): finding the flake
//! under a point (a search of 27 cells), the sparkle close-up (`examples/sparkle.toml` at
//! 256 × 170 pixels, 16 samples per pixel) with the flakes discrete and smooth (the table
//! alone, the glint in it), and the texture camera's five pictures on the silver metallic (a
//! 3 mm field at 15 µm per pixel, 8 samples per pixel, the table included).

use criterion::{Criterion, criterion_group, criterion_main};
use glam::DVec3;
use gonio_coating::glint::Glint;
use gonio_coating::system::default_bands;
use gonio_render::coating_material::{FlakeMode, from_coating};
use gonio_render::flakes::FlakeField;
use gonio_render::texture::{TextureCamera, measure};
use gonio_render::{ColourMode, RenderOptions, Scene, render};
use std::hint::black_box;
use std::path::{Path, PathBuf};

fn examples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

fn silver() -> gonio_coating::system::Coating {
    gonio_coating::description::read(
        &examples().join("coatings/silver_metallic.toml"),
        &default_bands(),
    )
    .unwrap()
}

fn bench_lookup(c: &mut Criterion) {
    let coating = silver();
    let glint = Glint::new(&coating, &default_bands()).unwrap().unwrap();
    let field = FlakeField::new(glint, 1).unwrap();
    let points: Vec<DVec3> = (0..4096)
        .map(|k| DVec3::new(k as f64 * 3.7e-6, (k * 7 % 4096) as f64 * 2.3e-6, -4e-5))
        .collect();
    c.bench_function("flakes/flake_at x4096", |b| {
        b.iter(|| {
            points
                .iter()
                .filter(|p| field.flake_at(black_box(**p)).is_some())
                .count()
        })
    });
}

fn bench_sparkle(c: &mut Criterion) {
    let mut group = c.benchmark_group("flakes");
    group.sample_size(10);
    let path = examples().join("sparkle.toml");
    let mut desc =
        gonio_render::scene::SceneDesc::from_toml(&std::fs::read_to_string(&path).unwrap(), &path)
            .unwrap();
    desc.camera.width = 256;
    desc.camera.height = 170;
    let discrete = Scene::build(&desc, &path).unwrap();
    let mut smooth = Scene::build(&desc, &path).unwrap();
    smooth.materials[0] = from_coating("s", &silver(), "bench", FlakeMode::Smooth, 1).unwrap();
    let opts = RenderOptions {
        spp: Some(16),
        colour: ColourMode::Tristimulus,
        ..RenderOptions::default()
    };
    for (name, scene) in [("sparkle discrete", &discrete), ("sparkle smooth", &smooth)] {
        let (_, stats) = render(scene, &opts).unwrap();
        println!(
            "{name}: 256 × 170 px, 16 spp: {} rays in {:.2} s = {:.3e} rays/s",
            stats.rays,
            stats.seconds,
            stats.rays_per_second()
        );
        group.bench_function(name, |b| b.iter(|| render(scene, &opts).unwrap()));
    }
    let camera = TextureCamera {
        field_mm: 3.0,
        spp: 8,
        ..TextureCamera::default()
    };
    let coating = silver();
    group.bench_function("texture camera 3 mm", |b| {
        b.iter(|| measure(&coating, "bench", &camera, &|_, _| {}).unwrap())
    });
    group.finish();
}

criterion_group!(benches, bench_lookup, bench_sparkle);
criterion_main!(benches);
