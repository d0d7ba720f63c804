//! Benchmarks of the surface crate on a 4096 × 4096 map: reading it from X3P and GSF files,
//! plane levelling, the ISO 25178-2 statistics, facet normals and synthesis; and the time to read
//! each instrument file of the test fixtures (one per format, from the file to a `HeightMap`).
//! Run with `cargo bench -p gonio-bench --bench surface`; figures go into docs/performance.md.

use criterion::{Criterion, criterion_group, criterion_main};
use gonio_surface::normals::{NormalMethod, facet_normals};
use gonio_surface::synth::GaussianSurface;
use gonio_surface::{io, ops, stats};
use std::hint::black_box;
use std::time::Duration;

const N: usize = 4096;

fn request() -> GaussianSurface {
    GaussianSurface::square(201e-9, 6e-6, N, 0.5e-6, 1)
}

fn bench(c: &mut Criterion) {
    let map = request().generate().expect("synthesis");
    let dir = tempfile::tempdir().expect("temporary directory");
    let mut g = c.benchmark_group("surface 4096x4096");
    g.sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(20));
    for ext in ["x3p", "gsf"] {
        let path = dir.path().join(format!("map.{ext}"));
        io::write(&map, &path).expect("write");
        g.bench_function(format!("read {ext}"), |b| {
            b.iter(|| io::read(black_box(&path)).expect("read"))
        });
    }
    g.bench_function("level", |b| {
        b.iter(|| ops::level(black_box(&map)).expect("level"))
    });
    g.bench_function("statistics (levelling included)", |b| {
        b.iter(|| stats::statistics(black_box(&map)).expect("statistics"))
    });
    let levelled = ops::level(&map).expect("level");
    g.bench_function("height parameters and Sdq", |b| {
        b.iter(|| {
            (
                stats::height_parameters(black_box(&levelled)),
                stats::rms_gradient(&levelled),
            )
        })
    });
    g.bench_function("autocorrelation, Sal and Str", |b| {
        b.iter(|| stats::Autocorrelation::of_levelled(black_box(&levelled)).sal_str(0.2))
    });
    g.bench_function("radial PSD", |b| {
        b.iter(|| stats::radial_psd(black_box(&map), stats::Window::Hann).expect("psd"))
    });
    for method in [NormalMethod::Plane, NormalMethod::Spline] {
        g.bench_function(format!("facet normals {method:?}"), |b| {
            b.iter(|| facet_normals(black_box(&map), method))
        });
    }
    g.bench_function("synthesis", |b| {
        b.iter(|| request().generate().expect("synthesis"))
    });
    g.finish();
}

/// One real file of each format read from disk (the test fixtures, tests/data).
fn fixtures(c: &mut Criterion) {
    let data = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../surface/tests/data");
    let mut g = c.benchmark_group("read fixture");
    g.sample_size(20)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3));
    for name in [
        "x3p-2.x3p",
        "sdf-1.sdf",
        "matrix-3.txt",
        "metropro-1.dat",
        "opd-1.opd",
        "plu-1.plu",
        "sur-2.sur",
        "al3d-1.al3d",
        "di-1.di",
        "nid-1.nid",
        "spot_1-1000nm.ibw",
        "mi-1.mi",
        "top-1.top",
        "stp-1.stp",
        "frt-1.frt",
        "mnt-1.mnt",
        "nms-1.nms",
        "tmd-1.tmd",
        "matrix-4.txt",
        "xyz-1.txt",
        "opdx-3.opdx",
    ] {
        let path = data.join(name);
        g.bench_function(name, |b| {
            b.iter(|| io::read(black_box(&path)).expect("read"))
        });
    }
    g.finish();
}

criterion_group!(benches, bench, fixtures);
criterion_main!(benches);
