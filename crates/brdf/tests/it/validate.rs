//! The sampler validation (chi-squared against the pdf): p-values against tables, pooling of
//! small cells, and a wrong sampler caught.

use glam::{DVec2, DVec3};
use gonio_brdf::bxdf::{Brdf, Rgb};
use gonio_brdf::validate::*;
use std::f64::consts::PI;

/// Critical values of the chi-square distribution at upper-tail probability 0.05 and
/// 1e-4, from standard tables (e.g. NIST/SEMATECH e-Handbook, §1.3.6.7.4).
#[test]
fn p_values_match_tables() {
    for (x, dof, p) in [
        (3.841459, 1, 0.05),
        (18.307038, 10, 0.05),
        (124.342113, 100, 0.05),
        (15.136705, 1, 1e-4),
        (1.0, 2, (-0.5f64).exp()),
    ] {
        let got = chi_square_p_value(x, dof);
        assert!(
            (got - p).abs() < 1e-6 * p.max(1e-3),
            "x={x} dof={dof}: {got} vs {p}"
        );
    }
    // Large dof: the Wilson-Hilferty normal approximation is good to ~1e-3 in p here.
    let dof = 2000usize;
    let z = 1.6448536; // upper 5 % point of the normal distribution
    let k = dof as f64;
    let x = k * (1.0 - 2.0 / (9.0 * k) + z * (2.0 / (9.0 * k)).sqrt()).powi(3);
    assert!((chi_square_p_value(x, dof) - 0.05).abs() < 1e-3);
    assert_eq!(gamma_q(3.0, 0.0), 1.0);
}

#[test]
fn pooling_merges_small_cells_and_flags_impossible_samples() {
    let expected = [1.0, 2.0, 3.0, 100.0, 100.0];
    let observed = [1.0, 2.0, 3.0, 100.0, 100.0];
    let (chi2, dof) = pooled_chi_square(&observed, &expected);
    assert_eq!(chi2, 0.0);
    assert_eq!(
        dof, 2,
        "three small cells pooled into one, three cells in all"
    );
    let (chi2, _) = pooled_chi_square(&[3.0, 100.0], &[0.0, 103.0]);
    assert!(chi2.is_infinite());
}

/// A sampler that does not follow its own pdf must fail: uniform hemisphere sampling
/// labelled with the cosine pdf.
#[test]
fn a_wrong_sampler_is_caught() {
    struct Mislabelled;
    impl Brdf for Mislabelled {
        fn eval(&self, _: DVec3, wi: DVec3) -> Rgb {
            Rgb::splat(if wi.z > 0.0 { 1.0 / PI } else { 0.0 })
        }
        fn sample(&self, wo: DVec3, u: DVec2) -> Option<gonio_brdf::BrdfSample> {
            let z = u.x;
            let r = (1.0 - z * z).sqrt();
            let wi = DVec3::new(r * (2.0 * PI * u.y).cos(), r * (2.0 * PI * u.y).sin(), z);
            Some(gonio_brdf::BrdfSample {
                wi,
                f: self.eval(wo, wi),
                pdf: self.pdf(wo, wi),
            })
        }
        fn pdf(&self, _: DVec3, wi: DVec3) -> f64 {
            wi.z.max(0.0) / PI
        }
    }
    let opts = SamplerCheck {
        samples: 20_000,
        ..SamplerCheck::default()
    };
    let report = check_sampler(&Mislabelled, DVec3::Z, &opts);
    assert!(report.p_value < 1e-10, "{report:?}");
    assert!(!report.passed());
}
