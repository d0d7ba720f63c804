//! Benchmarks of the ray method on a 1024 × 1024 Gaussian random surface (Sq 0.3 µm, T 6 µm,
//! 0.5 µm spacing): (a) in-plane, 4 incidences × 151 cone detectors of 1.4°, with and without
//! shadowing; (b) the full hemisphere on a 1° grid for 90 incidence angles, shadowing off.
//! Throughput is in facet reflections (facets × incidences × azimuths).

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use gonio_io::Progress;
use gonio_scatter::geometry::incidence_direction;
use gonio_scatter::ray::{HemisphereGrid, RayEngine, RayOptions};
use gonio_scatter::{Goniometer, InplaneMethod};
use gonio_surface::HeightMap;
use gonio_surface::synth::GaussianSurface;
use std::hint::black_box;
use std::time::Duration;

fn surface() -> HeightMap {
    GaussianSurface::square(0.3e-6, 6e-6, 1024, 0.5e-6, 1)
        .generate()
        .expect("synthetic surface")
}

fn inplane(c: &mut Criterion) {
    let map = surface();
    let starr = Goniometer::starr();
    let mut group = c.benchmark_group("ray_inplane_1024");
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(10));
    for shadowing in [false, true] {
        let options = RayOptions {
            shadowing,
            ..RayOptions::default()
        };
        let engine = RayEngine::new(&map, options).expect("engine");
        group.throughput(Throughput::Elements(
            (engine.facet_count() * starr.incidences.len()) as u64,
        ));
        let name = if shadowing {
            "4x151_shadowing"
        } else {
            "4x151_no_shadowing"
        };
        group.bench_function(name, |b| {
            b.iter(|| {
                black_box(
                    engine
                        .inplane_curves(&starr, &[], &Progress::silent())
                        .expect("curves"),
                )
            })
        });
    }
    group.bench_function("plan_engine", |b| {
        b.iter(|| black_box(RayEngine::new(&map, RayOptions::default()).expect("engine")))
    });
    group.finish();
}

fn hemisphere(c: &mut Criterion) {
    let map = surface();
    let options = RayOptions {
        shadowing: false,
        ..RayOptions::default()
    };
    let engine = RayEngine::new(&map, options).expect("engine");
    let grid = HemisphereGrid::with_step_deg(1.0).expect("grid");
    let mut group = c.benchmark_group("ray_hemisphere_1024");
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(30));
    group.throughput(Throughput::Elements((engine.facet_count() * 90) as u64));
    group.bench_function("90_incidences_1deg_grid", |b| {
        b.iter(|| {
            for ti in 0..90 {
                let wi = incidence_direction(f64::from(ti).to_radians());
                black_box(engine.detect_hemisphere(wi, &grid).expect("table"));
            }
        })
    });
    group.finish();
}

criterion_group!(benches, inplane, hemisphere);
criterion_main!(benches);
