//! Benchmarks of the isotropy check on a 1024 × 1024 map (the epoxy sample's grid, Sq 201 nm):
//! the exact quarter turn, the turn by 45° with its crop, and the whole check (ray method, STARR
//! geometry) at 90° and at 45°.
//! Run with `cargo bench -p gonio-bench --bench instrument_isotropy`; figures go into
//! docs/performance.md.

use criterion::{Criterion, criterion_group, criterion_main};
use gonio_instrument::isotropy::{IsotropyConfig, Method, check};
use gonio_surface::ops::{quarter_turns, turned_pair};
use gonio_surface::synth::epoxy_surface;
use std::hint::black_box;
use std::time::Duration;

fn bench(c: &mut Criterion) {
    let map = epoxy_surface(201e-9, 1).generate().expect("synthesis");
    let mut g = c.benchmark_group("isotropy 1024x1024");
    g.sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(10));
    g.bench_function("quarter turn", |b| {
        b.iter(|| quarter_turns(black_box(&map), 1).expect("turn"))
    });
    g.bench_function("turn 45° and crop", |b| {
        b.iter(|| turned_pair(black_box(&map), 45.0).expect("turn"))
    });
    for angle in [90.0, 45.0] {
        let config = IsotropyConfig {
            angles_deg: vec![angle],
            ..IsotropyConfig::starr(Method::Ray)
        };
        g.bench_function(format!("check {angle}° (ray, 4 incidences)"), |b| {
            b.iter(|| {
                check(black_box(&map), &config, &gonio_io::Progress::silent()).expect("check")
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
