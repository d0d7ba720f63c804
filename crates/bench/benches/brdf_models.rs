//! Evaluations and samples per second of every analytic model: 4096 direction pairs (or
//! random numbers) per iteration, so that criterion's throughput reads in elements/s.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use glam::{DVec2, DVec3};
use gonio_brdf::Brdf;
use gonio_brdf::models::{Model, ModelSpec};
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64;
use std::hint::black_box;

const N: usize = 4096;

fn models() -> Vec<(&'static str, Model)> {
    [
        ("lambert", r#"{"model": "lambert", "albedo": 0.5}"#),
        (
            "phong",
            r#"{"model": "phong", "specular": 0.5, "exponent": 50}"#,
        ),
        (
            "blinn-phong",
            r#"{"model": "blinn-phong", "specular": 0.5, "exponent": 200}"#,
        ),
        (
            "ward",
            r#"{"model": "ward", "specular": 0.1, "alpha": 0.1, "alpha_y": 0.2}"#,
        ),
        (
            "beckmann",
            r#"{"model": "beckmann", "m": 0.2, "index": 1.5}"#,
        ),
        ("ggx", r#"{"model": "ggx", "alpha": 0.2, "index": 1.5}"#),
        (
            "ggx+diffuse",
            r#"{"model": "ggx", "alpha": 0.2, "index": 1.5, "diffuse": 0.5}"#,
        ),
    ]
    .into_iter()
    .map(|(name, json)| {
        (
            name,
            ModelSpec::from_json(json)
                .expect("valid spec")
                .build()
                .expect("valid model"),
        )
    })
    .collect()
}

/// A random direction on the upper hemisphere, uniform in solid angle.
fn hemisphere(rng: &mut Pcg64) -> DVec3 {
    let z: f64 = rng.random();
    let phi = 2.0 * std::f64::consts::PI * rng.random::<f64>();
    let r = (1.0 - z * z).sqrt();
    DVec3::new(r * phi.cos(), r * phi.sin(), z.max(1e-3))
}

fn bench(c: &mut Criterion) {
    let mut rng = Pcg64::seed_from_u64(3);
    let pairs: Vec<(DVec3, DVec3)> = (0..N)
        .map(|_| (hemisphere(&mut rng), hemisphere(&mut rng)))
        .collect();
    let us: Vec<DVec2> = (0..N)
        .map(|_| DVec2::new(rng.random(), rng.random()))
        .collect();
    let mut group = c.benchmark_group("brdf");
    group.throughput(Throughput::Elements(N as u64));
    for (name, model) in models() {
        group.bench_function(format!("eval/{name}"), |b| {
            b.iter(|| {
                pairs
                    .iter()
                    .map(|&(wo, wi)| model.eval(wo, wi).x)
                    .sum::<f64>()
            })
        });
        group.bench_function(format!("sample/{name}"), |b| {
            b.iter(|| {
                let mut sum = 0.0;
                for (&(wo, _), &u) in pairs.iter().zip(&us) {
                    if let Some(s) = model.sample(black_box(wo), u) {
                        sum += s.pdf;
                    }
                }
                sum
            })
        });
    }
    group.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20).warm_up_time(std::time::Duration::from_millis(500))
        .measurement_time(std::time::Duration::from_secs(2));
    targets = bench
}
criterion_main!(benches);
