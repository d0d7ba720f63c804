//! Synthetic Gaussian surfaces: Sq exact and mean zero, the same map for a seed whatever the
//! thread count, the autocorrelation at the correlation length, the epoxy series.

use gonio_surface::heightmap::HeightMap;
use gonio_surface::ops;
use gonio_surface::synth::*;

fn request(acf: Acf, n: usize, seed: u64) -> GaussianSurface {
    GaussianSurface {
        sq: 201e-9,
        corr_length: 4e-6,
        acf,
        nx: n,
        ny: n / 2,
        dx: 0.4e-6,
        dy: 0.5e-6,
        seed,
    }
}

fn levelled_rms(map: &HeightMap) -> f64 {
    let lev = ops::level(map).unwrap();
    (lev.heights().iter().map(|z| z * z).sum::<f64>() / lev.valid_count() as f64).sqrt()
}

#[test]
fn sq_is_exact_and_mean_is_zero() {
    for acf in [Acf::Gaussian, Acf::Exponential] {
        let req = request(acf, 128, 7);
        let map = req.generate().unwrap();
        assert_eq!((map.nx(), map.ny()), (128, 64));
        assert!((levelled_rms(&map) / req.sq - 1.0).abs() < 1e-9, "{acf:?}");
        let mean = map.heights().mean().unwrap();
        assert!(mean.abs() < 1e-12 * req.sq, "{acf:?} mean {mean}");
    }
}

#[test]
fn same_seed_same_map_whatever_the_thread_count() {
    let req = request(Acf::Gaussian, 64, 42);
    let run = |threads| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| req.generate().unwrap())
    };
    let one = run(1);
    assert_eq!(one.heights(), run(3).heights());
    let other = GaussianSurface {
        seed: 43,
        ..req.clone()
    }
    .generate()
    .unwrap();
    assert_ne!(one.heights(), other.heights());
}

/// The realised autocorrelation along x at lag T is C(T)/C(0) = 1/e for both shapes (both
/// equal e^-1 at r = T). The estimate from a map of area A has a standard deviation of about
/// sqrt(∫ (ρ² + ρ(r+τ)ρ(r-τ)) d²r / A) <= sqrt(π T² / A) (Bartlett's formula; ∫ ρ² d²r = π T²/2
/// for both shapes), so the mean over 8 maps is held to 4 of those standard deviations.
#[test]
fn autocorrelation_at_the_correlation_length() {
    for acf in [Acf::Gaussian, Acf::Exponential] {
        let req = GaussianSurface {
            ny: 256,
            ..request(acf, 256, 0)
        };
        let lag = (req.corr_length / req.dx).round() as usize; // 10 points
        let realisations = 8;
        let mut mean = 0.0;
        for seed in 0..realisations {
            let map = GaussianSurface {
                seed,
                ..req.clone()
            }
            .generate()
            .unwrap();
            let (mut c0, mut c) = (0.0, 0.0);
            for row in map.heights().rows() {
                for ix in 0..req.nx {
                    c0 += row[ix] * row[ix];
                    c += row[ix] * row[(ix + lag) % req.nx];
                }
            }
            mean += c / c0 / realisations as f64;
        }
        let area = req.nx as f64 * req.dx * req.ny as f64 * req.dy;
        let sigma = (std::f64::consts::PI * req.corr_length.powi(2) / area).sqrt()
            / (realisations as f64).sqrt();
        let expect = acf.normalised(lag as f64 * req.dx, req.corr_length);
        assert!(
            (mean - expect).abs() < 4.0 * sigma,
            "{acf:?}: {mean} vs {expect} ± {sigma}"
        );
    }
}

#[test]
fn bad_requests_are_errors() {
    let ok = request(Acf::Gaussian, 16, 0);
    for bad in [
        GaussianSurface {
            sq: 0.0,
            ..ok.clone()
        },
        GaussianSurface {
            corr_length: f64::NAN,
            ..ok.clone()
        },
        GaussianSurface {
            dx: -1.0,
            ..ok.clone()
        },
        GaussianSurface {
            nx: 1,
            ..ok.clone()
        },
    ] {
        assert!(bad.generate().is_err(), "{bad:?}");
    }
}

#[test]
fn epoxy_series_spans_3_to_805_nm() {
    assert_eq!(EPOXY_SQ_M.first(), Some(&3e-9));
    assert_eq!(EPOXY_SQ_M.last(), Some(&805e-9));
    for sq in [150e-9, 201e-9] {
        assert!(EPOXY_SQ_M.contains(&sq));
    }
    let small = GaussianSurface {
        nx: 64,
        ny: 64,
        ..epoxy_surface(805e-9, 1)
    };
    assert!((levelled_rms(&small.generate().unwrap()) / 805e-9 - 1.0).abs() < 1e-9);
}
