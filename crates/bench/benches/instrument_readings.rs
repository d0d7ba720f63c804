//! Benchmark of the lab's readings (`coating_readings::readings`, issue #33): one formulation's
//! every reading at the lab's defaults (E2194, 256 walks per geometry, 32 per in-plane view,
//! the gloss meter at 8 walks per point), for each `examples/coatings/*.toml`. The aim is 300 ms
//! per reading on two cores; the rough tops' multiple-scattering table is built once, before
//! the timing, as the lab builds it once per roughness (its cost is docs/performance.md's).

use criterion::{Criterion, criterion_group, criterion_main};
use gonio_coating::description;
use gonio_instrument::coating_readings::{ReadingsRequest, readings};
use gonio_io::Cancel;
use std::hint::black_box;
use std::path::Path;

fn benches(c: &mut Criterion) {
    let request = ReadingsRequest::default();
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/coatings");
    let mut paths: Vec<_> = std::fs::read_dir(&folder)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    paths.sort();
    let mut group = c.benchmark_group("lab readings");
    group.sample_size(20);
    let cancel = Cancel::new();
    for path in paths {
        let coating = description::read(&path, &request.wavelengths_nm).unwrap();
        readings(&coating, &request, &cancel).unwrap();
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        group.bench_function(name, |b| {
            b.iter(|| readings(black_box(&coating), &request, &cancel).unwrap())
        });
    }
    group.finish();
}

criterion_group!(instrument_readings, benches);
criterion_main!(instrument_readings);
