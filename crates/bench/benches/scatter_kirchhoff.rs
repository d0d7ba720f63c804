//! Kirchhoff benchmarks on a 1024 × 1024 synthetic coating (Sq = 20 nm, T = 5 µm, 0.5 µm
//! spacing, Gaussian autocorrelation; refinement 1 for every direction): one in-plane curve of
//! 151 detectors (1.4° half-angle) at one incidence and wavelength (the full set of 4 incidences ×
//! 3 wavelengths is 12 such curves; the detectors are independent jobs, so it takes 12 times as
//! long), one detector alone, and a full-hemisphere table at 20° and 550 nm.
//! Figures: docs/performance.md, "Kirchhoff".

use criterion::{Criterion, criterion_group, criterion_main};
use gonio_brdf::Ior;
use gonio_scatter::Detector;
use gonio_scatter::geometry::{incidence_direction, inplane_direction};
use gonio_scatter::kirchhoff::{Kirchhoff, KirchhoffOptions};
use gonio_scatter::ray::HemisphereGrid;
use gonio_surface::synth::GaussianSurface;
use std::hint::black_box;

fn coating() -> Kirchhoff {
    let map = GaussianSurface::square(20e-9, 5e-6, 1024, 0.5e-6, 1)
        .generate()
        .unwrap();
    Kirchhoff::new(&map, KirchhoffOptions::new(Ior::Dielectric(1.55))).unwrap()
}

fn bench(c: &mut Criterion) {
    let engine = coating();
    let scatter: Vec<f64> = (-75..=75).map(|d| f64::from(d).to_radians()).collect();
    let alpha = 1.4f64.to_radians();
    let mut group = c.benchmark_group("kirchhoff_1024");
    group.sample_size(10);
    group.bench_function("one_detector", |b| {
        let detector = Detector {
            direction: inplane_direction(0.5),
            half_angle: alpha,
        };
        let wi = incidence_direction(20f64.to_radians());
        b.iter(|| black_box(engine.reflectance(550e-9, wi, &detector).unwrap()))
    });
    group.bench_function("inplane_151_angles", |b| {
        b.iter(|| {
            black_box(
                engine
                    .inplane(
                        &[550e-9],
                        &[20f64.to_radians()],
                        &scatter,
                        alpha,
                        &gonio_io::Progress::silent(),
                    )
                    .unwrap(),
            )
        })
    });
    group.bench_function("hemisphere_1deg", |b| {
        let grid = HemisphereGrid::with_step_deg(1.0).unwrap();
        let wi = incidence_direction(20f64.to_radians());
        b.iter(|| black_box(engine.hemisphere(550e-9, wi, &grid).unwrap()))
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
