//! Benchmarks of the coating optics: the spectral body table of the example red coating at
//! the default resolution (90 × 90 × 48, 31 bands), a layered table by random walks (the
//! silver metallic, with a fixed number of walks and with walks added to the L* target), the thin-film reflectance of an interference flake, and a finite
//! Kubelka-Munk layer.

use criterion::{Criterion, criterion_group, criterion_main};
use gonio_brdf::formats::astm;
use gonio_brdf::table::{Provenance, Resolution};
use gonio_coating::cell::CellWalks;
use gonio_coating::description;
use gonio_coating::kubelka_munk::Coefficients;
use gonio_coating::system::TARGET_DL;
use gonio_coating::thin_film::{Polarisation, interference_flake};
use std::hint::black_box;
use std::path::Path;

fn benches(c: &mut Criterion) {
    let bands: Vec<f64> = (0..31).map(|i| 400.0 + 10.0 * i as f64).collect();
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/coatings/red_solid.toml");
    let stack = description::read(&path, &bands)
        .unwrap()
        .clear_coat()
        .unwrap();
    let mut group = c.benchmark_group("coating");
    group.sample_size(10);
    group.bench_function("body table 90x90x48, 31 bands (red_solid.toml)", |b| {
        b.iter(|| {
            stack
                .body_table(
                    astm::default_resolution(),
                    black_box(&bands),
                    Provenance::default(),
                )
                .unwrap()
        })
    });
    // A layered system through the random walks: an eighth of the default table's cells
    // (criterion's ten samples of the default table would take five minutes; the whole table
    // is timed through `gonio coating compute` in docs/performance.md).
    let silver_path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/coatings/silver_metallic.toml");
    let silver = description::read(&silver_path, &bands).unwrap();
    // The same eighth of the default table with 32 walks in every cell, and with walks added
    // where a cell's L* is noisier than the default target (what `gonio coating compute` does).
    for (label, walks) in [
        ("32 walks", CellWalks::fixed(32)),
        (
            "32 walks and more to 1/3 L*",
            CellWalks::adaptive(32, TARGET_DL),
        ),
    ] {
        group.bench_function(
            format!("layered table 45x45x24, 31 bands, {label} (silver_metallic.toml)"),
            |b| {
                b.iter(|| {
                    silver
                        .table(
                            Resolution::isotropic(45, 45, 24),
                            black_box(&bands),
                            walks,
                            Provenance::default(),
                        )
                        .unwrap()
                })
            },
        );
    }
    group.finish();
    let flake = interference_flake(120.0, 400.0, 1.58, 1.5, 550.0).unwrap();
    c.bench_function("interference flake reflectance, s and p (3 films)", |b| {
        b.iter(|| {
            flake.reflectance(Polarisation::S, black_box(0.7), 550.0)
                + flake.reflectance(Polarisation::P, black_box(0.7), 550.0)
        })
    });
    let km = Coefficients::new(0.2, 0.3).unwrap();
    c.bench_function("Kubelka-Munk finite layer reflectance", |b| {
        b.iter(|| km.reflectance(black_box(20.0), black_box(0.6)))
    });
}

criterion_group!(group, benches);
criterion_main!(group);
