//! Benchmarks of `gonio brdf compute` on a 1024 × 1024 Gaussian random surface (Sq 0.3 µm,
//! T 6 µm, 0.5 µm spacing): the default isotropic ray-method table (32 × 90 × 180 nodes) from 2
//! and from 6 incidences, whose difference is the cost of one incidence (trace, deposit) and
//! whose rest is the fixed cost (planning the measures, filling the 518 400 cells), and from
//! the default 45 incidences (what `gonio brdf compute` runs, less reading the map and writing
//! the file); planning the ray engine on that map; and one Kirchhoff incidence at 550 nm on a
//! 256 × 256 crop.

use criterion::{Criterion, criterion_group, criterion_main};
use gonio_brdf::Ior;
use gonio_brdf::table::Provenance;
use gonio_scatter::kirchhoff::{Kirchhoff, KirchhoffOptions};
use gonio_scatter::ray::{RayEngine, RayOptions};
use gonio_scatter::table::{TableOptions, kirchhoff_table, ray_table};
use gonio_surface::HeightMap;
use gonio_surface::synth::GaussianSurface;
use std::hint::black_box;
use std::time::Duration;

fn surface(n: usize) -> HeightMap {
    GaussianSurface::square(0.3e-6, 6e-6, n, 0.5e-6, 1)
        .generate()
        .expect("synthetic surface")
}

fn ray(c: &mut Criterion) {
    let map = surface(1024);
    let engine = RayEngine::new(&map, RayOptions::default()).expect("engine");
    let mut group = c.benchmark_group("brdf_compute_ray_1024");
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(20));
    group.bench_function("plan_engine", |b| {
        b.iter(|| black_box(RayEngine::new(&map, RayOptions::default()).expect("engine")))
    });
    for incidences in [2usize, 6, TableOptions::isotropic().incidence_polar] {
        let options = TableOptions {
            incidence_polar: incidences,
            ..TableOptions::isotropic()
        };
        group.bench_function(format!("{incidences}_incidences"), |b| {
            b.iter(|| {
                black_box(
                    ray_table(
                        &engine,
                        &options,
                        Provenance::default(),
                        &gonio_io::Progress::silent(),
                    )
                    .expect("table"),
                )
            })
        });
    }
    group.finish();
}

fn kirchhoff(c: &mut Criterion) {
    let map = surface(256);
    let engine =
        Kirchhoff::new(&map, KirchhoffOptions::new(Ior::Dielectric(1.55))).expect("engine");
    let options = TableOptions {
        incidence_polar: 2,
        ..TableOptions::isotropic()
    };
    let mut group = c.benchmark_group("brdf_compute_kirchhoff_256");
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(20));
    group.bench_function("2_incidences_550nm", |b| {
        b.iter(|| {
            black_box(
                kirchhoff_table(
                    &engine,
                    &[550.0],
                    &options,
                    Provenance::default(),
                    &gonio_io::Progress::silent(),
                )
                .expect("table"),
            )
        })
    });
    group.finish();
}

criterion_group!(benches, ray, kirchhoff);
criterion_main!(benches);
