//! Benchmarks of the formulation studies: the readings a sensitivity run makes of the silver
//! metallic (gloss, haze, DOI and the E2194 colour of one formulation at the defaults, 1024
//! walks per geometry and 8 per gloss quadrature point), one at a time and a batch of eight in
//! parallel (the rate a run reaches on this machine's cores, from which docs/performance.md
//! projects a Dask cluster's).

use criterion::{Criterion, criterion_group, criterion_main};
use gonio_coating::description;
use gonio_formulation::appearance::Output;
use gonio_formulation::coating_sensitivity::{Method, Plan, Settings, Varied};
use gonio_formulation::sensitivity;
use gonio_instrument::multiangle::E2194;
use ndarray::Array2;
use std::hint::black_box;
use std::path::Path;

fn benches(c: &mut Criterion) {
    let settings = Settings::default();
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/coatings/silver_metallic.toml");
    let silver = description::read(&path, &settings.wavelengths_nm).unwrap();
    let varied = Varied::parse_list("roughness=0.01:0.1,tilt=4:20,coverage=0.3:0.8").unwrap();
    let plan = Plan::new(
        &silver,
        &varied,
        &Output::all(&E2194),
        Method::default(),
        &settings,
    )
    .unwrap();
    let mut group = c.benchmark_group("formulation");
    group.sample_size(10);
    group.bench_function(
        "sensitivity reading, silver metallic (22 outputs, E2194, 1024 walks)",
        |b| b.iter(|| plan.read_point(black_box(&[0.05, 12.0, 0.6])).unwrap()),
    );
    let points = Array2::from_shape_fn((8, 3), |(i, j)| {
        [
            0.02 + 0.01 * i as f64,
            6.0 + 2.0 * i as f64,
            0.4 + 0.05 * i as f64,
        ][j]
    });
    group.bench_function("8 sensitivity readings in parallel, silver metallic", |b| {
        b.iter(|| {
            sensitivity::evaluate(black_box(&points), plan.outputs().len(), |x| {
                plan.read_point(x)
            })
            .unwrap()
        })
    });
    group.finish();
}

criterion_group!(formulation, benches);
criterion_main!(formulation);
