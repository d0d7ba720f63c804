//! Table evaluation (lookups per second), sampling, the .gbrdf read, on tables of the default
//! sizes, and the import of a measured paint (the scattered-data fit resampled on a table).
//! Run with `cargo bench -p gonio-bench --bench brdf_table`.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use glam::{DVec2, DVec3};
use gonio_brdf::Brdf;
use gonio_brdf::models::{Model, Ward};
use gonio_brdf::table::{BrdfTable, Provenance, Resolution, SampledTable};
use std::hint::black_box;

/// 1000 direction pairs spread over the hemisphere (a fixed low-discrepancy set).
fn pairs() -> Vec<(DVec3, DVec3)> {
    let dir = |a: f64, b: f64| {
        let z = 1.0 - 0.98 * a;
        let r = (1.0 - z * z).sqrt();
        let p = std::f64::consts::TAU * b;
        DVec3::new(r * p.cos(), r * p.sin(), z)
    };
    (0..1000)
        .map(|k| {
            let k = k as f64;
            (
                dir((k * 0.618034) % 1.0, (k * 0.414214) % 1.0),
                dir((k * 0.732051 + 0.3) % 1.0, (k * 0.236068 + 0.1) % 1.0),
            )
        })
        .collect()
}

fn bench(c: &mut Criterion) {
    let ward = Model::diffuse_specular(
        DVec3::new(0.3, 0.2, 0.1),
        Model::Ward(Ward::isotropic(DVec3::splat(0.05), 0.1)),
    );
    let table =
        BrdfTable::from_brdf(&ward, Resolution::merl_like(), false, Provenance::default()).unwrap();
    let pairs = pairs();
    let mut g = c.benchmark_group("table");
    g.throughput(Throughput::Elements(pairs.len() as u64));
    g.bench_function("eval_rgb_90x90x360", |b| {
        b.iter(|| {
            let mut s = DVec3::ZERO;
            for (wo, wi) in &pairs {
                s += table.eval(*wo, *wi);
            }
            black_box(s)
        })
    });
    let sampled = SampledTable::new(table.clone());
    g.bench_function("sample_alias_90x90x360", |b| {
        b.iter(|| {
            let mut s = 0.0;
            for (k, (wo, _)) in pairs.iter().enumerate() {
                let u = DVec2::new((k as f64 * 0.618034) % 1.0, (k as f64 * 0.414214) % 1.0);
                if let Some(x) = sampled.sample(*wo, u) {
                    s += x.pdf;
                }
            }
            black_box(s)
        })
    });
    g.finish();
    let mut g = c.benchmark_group("table_setup");
    g.sample_size(10);
    g.bench_function("alias_sampler_build_90x90x360", |b| {
        b.iter(|| black_box(SampledTable::new(table.clone())))
    });
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.gbrdf");
    gonio_brdf::gbrdf::write(&table, &path).unwrap();
    g.bench_function("gbrdf_open_mapped_35MB", |b| {
        b.iter(|| black_box(gonio_brdf::gbrdf::open_mapped(&path).unwrap()))
    });
    g.bench_function("gbrdf_read_35MB", |b| {
        b.iter(|| black_box(gonio_brdf::gbrdf::read(&path).unwrap()))
    });
    g.finish();

    // The Cornell Cayman file (1 450 geometries × 31 bands) imported at the default 90 × 90 × 48.
    let cayman =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../brdf/tests/data/cayman.astm");
    let mut g = c.benchmark_group("import");
    g.sample_size(10);
    g.bench_function("astm_cayman_90x90x48", |b| {
        b.iter(|| {
            gonio_brdf::formats::astm::import(
                &cayman,
                gonio_brdf::formats::astm::default_resolution(),
            )
            .unwrap()
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
