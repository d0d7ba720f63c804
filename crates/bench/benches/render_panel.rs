//! The lab's panel pictures (`gonio_render::panel::live`, docs/render.md "The lab's pictures"):
//! from a coating description to a finished picture at each quality, for the silver metallic
//! (random walks) and the red solid (the exact series of a smooth coat over a diffuse base).
//! Each iteration computes the table and renders the picture (PNG included) in the studio, as
//! the lab does after a change; the table and the picture are also timed apart, so that
//! rendering a kept table under another light can be read off. The preview must take under
//! 1 s and the converged picture under 20 s on two cores.

use criterion::{Criterion, criterion_group, criterion_main};
use gonio_coating::description;
use gonio_io::Cancel;
use gonio_render::panel::Lighting;
use gonio_render::panel::live::{Quality, live_table, picture};
use std::path::Path;

fn bench(c: &mut Criterion) {
    let cancel = Cancel::new();
    let mut group = c.benchmark_group("render_panel");
    group.sample_size(10);
    for name in ["silver_metallic", "red_solid"] {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../examples/coatings")
            .join(format!("{name}.toml"));
        for quality in Quality::ALL {
            let coating = description::read(&path, &quality.bands()).unwrap();
            let q = quality.name();
            group.bench_function(format!("{name} {q}: table and picture"), |b| {
                b.iter(|| {
                    let table = live_table(&coating, quality, &cancel).unwrap();
                    picture(&table, Lighting::Studio, quality, &cancel).unwrap()
                })
            });
            group.bench_function(format!("{name} {q}: table"), |b| {
                b.iter(|| live_table(&coating, quality, &cancel).unwrap())
            });
            let table = live_table(&coating, quality, &cancel).unwrap();
            group.bench_function(format!("{name} {q}: picture of a kept table"), |b| {
                b.iter(|| picture(&table, Lighting::Booth, quality, &cancel).unwrap())
            });
        }
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
