//! Benchmarks of the colour computations the renderer and the BRDF tables call in bulk.

use criterion::{Criterion, criterion_group, criterion_main};
use gonio_color::{
    HeroSampler, Illuminant, Lab, Observer, SpectralFilm, SpectralToXyz, Spectrum, ciede2000,
    reflectance_xyz,
};
use std::hint::black_box;

fn benches(c: &mut Criterion) {
    let (d65, two) = (Illuminant::D65, Observer::Cie1931TwoDegree);
    let values: Vec<f64> = (0..81)
        .map(|i| 0.3 + 0.2 * (i as f64 / 7.0).sin())
        .collect();
    let patch = Spectrum::uniform(380.0, 5.0, values).unwrap();
    c.bench_function(
        "reflectance_xyz 5 nm spectrum (1 nm sum, 471 points)",
        |b| b.iter(|| reflectance_xyz(black_box(&patch), d65, two)),
    );

    let bands: Vec<f64> = (0..31).map(|i| 400.0 + 10.0 * i as f64).collect();
    c.bench_function("SpectralToXyz::new 31 bands", |b| {
        b.iter(|| SpectralToXyz::new(black_box(&bands), d65, two).unwrap())
    });
    let reduce = SpectralToXyz::new(&bands, d65, two).unwrap();
    // The size of a Cornell .astm table: 1439 geometries × 31 bands.
    let table: Vec<f64> = (0..1439 * 31)
        .map(|i| ((i * 7919) % 1000) as f64 * 1e-3)
        .collect();
    c.bench_function("linear_srgb_table 1439 x 31 (Cornell table)", |b| {
        b.iter(|| reduce.linear_srgb_table(black_box(&table)).unwrap())
    });

    let sampler = HeroSampler::visible();
    let film = SpectralFilm::new(sampler, d65, two);
    c.bench_function("hero sample + film rgb weights (4 wavelengths)", |b| {
        let mut u = 0.0;
        b.iter(|| {
            u = (u + 0.618_033_988_749_895) % 1.0;
            let ws = sampler.sample(black_box(u));
            film.rgb_weights(&ws)
        })
    });

    let lab1 = Lab {
        l: 50.0,
        a: 2.6772,
        b: -79.7751,
    };
    let lab2 = Lab {
        l: 50.0,
        a: 0.0,
        b: -82.7485,
    };
    c.bench_function("ciede2000 one pair", |b| {
        b.iter(|| ciede2000(black_box(lab1), black_box(lab2)))
    });
}

criterion_group!(color, benches);
criterion_main!(color);
