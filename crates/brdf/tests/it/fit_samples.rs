//! Fitting a model to a table: the samples a table gives the fit recover the model it was made
//! from, and their weights cover the pair space.

use gonio_brdf::fit::{FitKind, FitOptions, fit};
use gonio_brdf::models::{Index, Lambert, ModelSpec};
use gonio_brdf::table::{BrdfTable, Provenance, Resolution};
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// Fitting the table of a known Beckmann Cook-Torrance model recovers its parameters within
/// 2%. The cells hold the model's exact values, so only the f32 storage and the fit's
/// tolerance separate the result from the truth.
#[test]
fn fitting_a_model_table_recovers_the_model() {
    let spec = ModelSpec::Beckmann {
        m: 0.2,
        index: Index::Real(1.55),
        tint: None,
        diffuse: None,
    };
    let model = spec.build().unwrap();
    let res = Resolution::isotropic(24, 30, 60);
    let table = BrdfTable::from_brdf(&model, res, true, Provenance::default()).unwrap();
    let samples = table.fit_samples(80f64.to_radians());
    let got = fit(FitKind::Beckmann, &samples, FitOptions::default()).unwrap();
    let m = got.parameter("m").unwrap().value;
    let n = got.parameter("index").unwrap().value;
    assert!((m / 0.2 - 1.0).abs() < 0.02, "m {m}");
    assert!((n / 1.55 - 1.0).abs() < 0.02, "index {n}");
}

/// The weights of all cells add up to about `∫∫ cos(theta_o) dwi dwo = π · 2π` when no
/// angle is cut (the cells at the horizon, without data, hold the few percent left).
#[test]
fn weights_cover_the_pair_space() {
    let lambert = Lambert {
        albedo: gonio_brdf::Rgb::splat(0.5),
    };
    let res = Resolution::isotropic(32, 45, 90);
    let table = BrdfTable::from_brdf(&lambert, res, true, Provenance::default()).unwrap();
    let total: f64 = table.fit_samples(FRAC_PI_2).iter().map(|s| s.weight).sum();
    assert!((total / (PI * TAU) - 1.0).abs() < 0.05, "{total}");
}
