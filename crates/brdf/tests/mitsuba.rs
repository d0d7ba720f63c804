//! An analytic Ward BRDF, tabulated and exported to the Mitsuba 3 / pbrt-v4 tensor format, read
//! back with our evaluator of that format (which follows Mitsuba's `measured` plugin), agrees
//! with the analytic value within 5% at 100 direction pairs wherever the value is above 1% of
//! the largest value among them.

use glam::{DVec2, DVec3};
use gonio_brdf::Brdf;
use gonio_brdf::formats::mitsuba::{self, MitsubaOptions, TensorBrdf};
use gonio_brdf::models::Ward;
use gonio_brdf::table::{BrdfTable, Provenance, Resolution};
use gonio_brdf::validate::{SamplerCheck, check_sampler};
use rand::{RngExt, SeedableRng};

#[test]
fn ward_table_through_the_tensor_file_matches_the_model() {
    let ward = Ward::isotropic(DVec3::new(0.6, 0.4, 0.2), 0.2);
    let table = BrdfTable::from_brdf(
        &ward,
        Resolution::isotropic(90, 64, 64),
        false,
        Provenance::new("ward alpha 0.2", "model"),
    )
    .unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("ward.bsdf");
    mitsuba::write(&table, &path, MitsubaOptions::default()).unwrap();
    let tensor = TensorBrdf::read(&path).unwrap();
    assert_eq!(tensor.channel_count(), 3);

    // Viewers uniform in solid angle up to 80°, lights drawn from the lobe (the model's own
    // sampler), so that most pairs lie where the BRDF matters.
    let mut rng = rand_pcg::Pcg64::seed_from_u64(5);
    let mut pairs = vec![];
    while pairs.len() < 100 {
        let z = 1.0 - rng.random::<f64>() * (1.0 - 80f64.to_radians().cos());
        let phi = rng.random::<f64>() * std::f64::consts::TAU;
        let r = (1.0 - z * z).sqrt();
        let wo = DVec3::new(r * phi.cos(), r * phi.sin(), z);
        if let Some(s) = ward.sample(wo, DVec2::new(rng.random(), rng.random()))
            && s.wi.z > 0.05
        {
            pairs.push((wo, s.wi));
        }
    }
    let peak = pairs
        .iter()
        .map(|(wo, wi)| ward.eval(*wo, *wi).x)
        .fold(0.0, f64::max);
    let mut checked = 0;
    let mut worst = 0.0f64;
    for (wo, wi) in &pairs {
        let want = ward.eval(*wo, *wi);
        if want.x < 0.01 * peak {
            continue;
        }
        checked += 1;
        let got = tensor.eval(*wo, *wi);
        for c in 0..3 {
            let rel = (got[c] - want[c]).abs() / want[c];
            worst = worst.max(rel);
            assert!(
                rel < 0.05,
                "wo {wo} wi {wi}: tensor {got} vs model {want} ({rel:.3})"
            );
        }
    }
    println!("{checked} pairs checked, worst relative error {worst:.4}");
    assert!(checked >= 80, "only {checked} pairs above 1% of the peak");

    // Mitsuba's sampling routine, as reproduced by the reader, samples what its pdf says.
    for theta in [10.0f64, 50.0] {
        let wo = DVec3::new(theta.to_radians().sin(), 0.0, theta.to_radians().cos());
        let report = check_sampler(&tensor, wo, &SamplerCheck::default());
        assert!(report.passed(), "theta_o {theta}: {report:?}");
    }
}
