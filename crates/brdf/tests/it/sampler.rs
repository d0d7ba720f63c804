//! Importance sampling of tables: the alias sampler passes the sampler checks and its estimator
//! integrates to the albedo with less variance than cosine sampling.

use glam::{DVec2, DVec3};
use gonio_brdf::bxdf::Brdf;
use gonio_brdf::table::coords::dir;
use gonio_brdf::table::*;
use rand::{RngExt, SeedableRng};
use std::f64::consts::{PI, TAU};

/// Lambert 0.2/π plus a normalised Phong lobe of exponent `n` and weight `k` about the
/// mirror direction.
fn lobe_table(n: f64, k: f64) -> BrdfTable {
    let mut b = TableBuilder::new(Resolution::isotropic(64, 32, 32), Channels::Mono).unwrap();
    b.fill(|c, out| {
        let mirror = DVec3::new(-c.wi.x, -c.wi.y, c.wi.z);
        out[0] = 0.2 / PI + k * (n + 2.0) / TAU * mirror.dot(c.wo).max(0.0).powf(n);
    });
    b.build().unwrap()
}

/// The shared sampler validation (chi-square of the sampled directions against the pdf,
/// `f cos / pdf` against the albedo by quadrature, each sample's value and pdf against
/// `eval` and `pdf`) at several viewing angles. The pdf is piecewise constant over small
/// half-vector cells, so the expected counts need a finer quadrature than the default 4 × 4
/// points per bin.
#[test]
fn alias_sampler_passes_the_sampler_checks() {
    let t = SampledTable::new(lobe_table(40.0, 0.6));
    for theta in [0.0f64, 30.0, 60.0, 80.0] {
        let wo = dir(theta.to_radians(), 0.7);
        let opts = gonio_brdf::validate::SamplerCheck {
            quadrature: 12,
            ..Default::default()
        };
        let report = gonio_brdf::validate::check_sampler(&t, wo, &opts);
        assert!(report.passed(), "theta_o {theta}: {report:?}");
    }
}

/// `f cos / pdf` averages to the albedo that quadrature gives, for a narrow lobe, and with
/// a far smaller variance than cosine-weighted sampling.
#[test]
fn estimator_integrates_to_albedo_and_pays() {
    let table = lobe_table(2000.0, 0.7);
    let sampled = SampledTable::new(table.clone());
    let n = 100_000;
    for theta in [0.0f64, 45.0, 75.0] {
        let wo = dir(theta.to_radians(), 0.2);
        let reference = table.albedo(theta.to_radians(), 0.2)[0];
        let mut rng = rand_pcg::Pcg64::seed_from_u64(3);
        let mut stats = |b: &dyn Brdf| {
            let (mut s, mut s2) = (0.0, 0.0);
            for _ in 0..n {
                let u = DVec2::new(rng.random::<f64>(), rng.random::<f64>());
                if let Some(x) = b.sample(wo, u) {
                    let v = x.f.x * x.wi.z / x.pdf;
                    s += v;
                    s2 += v * v;
                }
            }
            let mean = s / n as f64;
            (mean, ((s2 / n as f64 - mean * mean) / n as f64).sqrt())
        };
        let (mean, err) = stats(&sampled);
        let (_, err_cos) = stats(&table);
        assert!(
            (mean - reference).abs() < 5.0 * err + 0.005 * reference,
            "theta_o {theta}: {mean} ± {err} vs quadrature {reference}"
        );
        assert!(
            err_cos > 5.0 * err,
            "theta_o {theta}: alias {err} vs cosine {err_cos}"
        );
    }
}
