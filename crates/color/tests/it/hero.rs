//! Hero-wavelength sampling: uniform and stratified wavelengths, the film's estimate converging to
//! the direct integration, a flat spectrum giving white.

use gonio_color::cie::{Illuminant, Observer};
use gonio_color::hero::*;
use gonio_color::spectrum::Spectrum;
use gonio_color::tristimulus::{WeightingFactors, reflectance_xyz};

/// With u on a stratified grid of N points (N a multiple of C), each λ_j on its own takes
/// exactly the midpoints of N equal cells of the range (it is uniform), and the C wavelengths
/// of a path fall one in each quarter of the range (they are stratified).
#[test]
fn hero_wavelengths_are_uniform_and_stratified() {
    let sampler = HeroSampler::visible();
    let n = 200;
    let paths: Vec<[f64; HERO_COUNT]> = (0..n)
        .map(|i| sampler.sample((i as f64 + 0.5) / n as f64))
        .collect();
    let cell = 400.0 / n as f64;
    for j in 0..HERO_COUNT {
        let mut marginal: Vec<f64> = paths.iter().map(|p| p[j]).collect();
        marginal.sort_by(f64::total_cmp);
        for (k, w) in marginal.iter().enumerate() {
            assert!(
                (w - (380.0 + (k as f64 + 0.5) * cell)).abs() < 1e-9,
                "{j} {k}: {w}"
            );
        }
    }
    for path in &paths {
        let mut quarters: Vec<usize> = path
            .iter()
            .map(|w| ((w - 380.0) / 100.0) as usize)
            .collect();
        quarters.sort();
        assert_eq!(quarters, [0, 1, 2, 3]);
    }
    assert!(HeroSampler::new(300.0, 700.0).is_err());
    assert!(HeroSampler::new(700.0, 500.0).is_err());
}

/// What separates the film's limit, the integral over the sampler's range of the linearly
/// interpolated weights W times the spectrum ρ, from the 1 nm sum Σ_k W_k ρ_k: the sum's terms
/// outside the range; the ends of the range, which the integral counts with half weight; and on
/// each 1 nm step the trapezoid error of a product of two linear functions, (ΔW Δρ)/6.
fn film_vs_sum_bound(factors: &WeightingFactors, rho: &Spectrum, range: (f64, f64)) -> [f64; 3] {
    let (lo, hi) = range;
    let points: Vec<(f64, [f64; 3], f64)> = factors
        .wavelengths_nm()
        .iter()
        .zip(factors.weights())
        .map(|(&w, &f)| (w, f, rho.value_at(w)))
        .collect();
    std::array::from_fn(|c| {
        let outside: f64 = points
            .iter()
            .filter(|p| p.0 < lo || p.0 > hi)
            .map(|p| p.1[c] * p.2)
            .sum();
        let ends: f64 = points
            .iter()
            .filter(|p| p.0 == lo || p.0 == hi)
            .map(|p| 0.5 * p.1[c] * p.2)
            .sum();
        let trapezoid: f64 = points
            .windows(2)
            .filter(|w| w[0].0 >= lo && w[1].0 <= hi)
            .map(|w| ((w[1].1[c] - w[0].1[c]) * (w[1].2 - w[0].2)).abs() / 6.0)
            .sum();
        outside + ends + trapezoid + 1e-6
    })
}

/// A flat spectrum reduces to the illuminant's white, and a smooth one to its direct 1 nm
/// integration, within the bound above (at most 0.03 on the 0–100 scale here; the Monte Carlo
/// error of 20 000 stratified paths is far below it).
#[test]
fn film_estimate_converges_to_the_direct_integration() {
    let values = (0..81)
        .map(|i| 0.4 + 0.3 * (i as f64 / 9.0).sin())
        .collect();
    let smooth = Spectrum::uniform(380.0, 5.0, values).unwrap();
    let flat = Spectrum::constant(vec![360.0, 830.0], 1.0).unwrap();
    let samplers = [
        HeroSampler::new(360.0, 830.0).unwrap(),
        HeroSampler::visible(),
    ];
    for illuminant in Illuminant::ALL {
        for observer in Observer::ALL {
            let factors = WeightingFactors::of(illuminant, observer);
            for sampler in samplers {
                let film = SpectralFilm::new(sampler, illuminant, observer);
                for spectrum in [&flat, &smooth] {
                    let n = 20_000;
                    let mut sum = [0.0; 3];
                    for i in 0..n {
                        let ws = sampler.sample((i as f64 + 0.5) / n as f64);
                        let values = ws.map(|w| spectrum.value_at(w));
                        let xyz = film.xyz(&ws, &values).to_array();
                        (0..3).for_each(|c| sum[c] += xyz[c] / n as f64);
                    }
                    let direct = reflectance_xyz(spectrum, illuminant, observer).to_array();
                    let bound = film_vs_sum_bound(factors, spectrum, sampler.range_nm());
                    for c in 0..3 {
                        assert!(bound[c] < 0.03, "{bound:?}");
                        assert!(
                            (sum[c] - direct[c]).abs() <= bound[c],
                            "{illuminant} {observer} {:?}: {sum:?} vs {direct:?}, {bound:?}",
                            sampler.range_nm()
                        );
                    }
                }
            }
        }
    }
}

/// The sRGB weights are the XYZ weights through the display matrix: a flat spectrum averages
/// to sRGB white under A (after Bradford adaptation).
#[test]
fn rgb_weights_give_white_for_a_flat_spectrum() {
    let sampler = HeroSampler::new(360.0, 830.0).unwrap();
    let film = SpectralFilm::new(sampler, Illuminant::A, Observer::Cie1931TwoDegree);
    let n = 20_000;
    let mut rgb = [0.0; 3];
    for i in 0..n {
        let ws = sampler.sample((i as f64 + 0.5) / n as f64);
        let c = film.linear_srgb(&ws, &[1.0; HERO_COUNT]);
        for (s, v) in rgb.iter_mut().zip([c.r, c.g, c.b]) {
            *s += v / n as f64;
        }
    }
    for v in rgb {
        assert!((v - 1.0).abs() < 1e-5, "{rgb:?}");
    }
}

/// A film of a CIE illuminant's own table given as a spectrum is that illuminant's film
/// (weights and white), and a measured spectrum scaled by any factor gives the same film (the
/// weights are relative to the light's luminance).
#[test]
fn film_of_a_spectrum_is_the_illuminants_film() {
    let sampler = HeroSampler::new(360.0, 830.0).unwrap();
    let waves = [402.5, 517.0, 633.3, 780.0];
    for observer in Observer::ALL {
        let named = SpectralFilm::new(sampler, Illuminant::A, observer);
        let spd = Illuminant::A.spd();
        let scaled = Spectrum::new(
            spd.wavelengths_nm().to_vec(),
            spd.values().iter().map(|v| 7.0 * v).collect(),
        )
        .unwrap();
        for film in [
            SpectralFilm::of_spectrum(sampler, spd, observer),
            SpectralFilm::of_spectrum(sampler, &scaled, observer),
        ] {
            for (a, b) in [
                (film.xyz_weights(&waves), named.xyz_weights(&waves)),
                (film.rgb_weights(&waves), named.rgb_weights(&waves)),
            ] {
                for (x, y) in a.iter().flatten().zip(b.iter().flatten()) {
                    assert!((x - y).abs() <= 1e-12 * y.abs().max(1.0), "{x} {y}");
                }
            }
            let (w, n) = (film.white().to_array(), named.white().to_array());
            assert!((0..3).all(|c| (w[c] - n[c]).abs() < 1e-9), "{w:?} {n:?}");
            assert!((w[1] - 100.0).abs() < 1e-9);
        }
    }
}
