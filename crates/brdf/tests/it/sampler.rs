//! Importance sampling of tables: the sampler passes the sampler checks, its estimator
//! integrates to the albedo with less variance than cosine sampling, and it keeps the
//! stratification of low-discrepancy points.

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
/// points per bin. 85° and 88° lie between bins near grazing, where the lobe is cut by the
/// horizon and the mixture of two bins is sampled.
#[test]
fn table_sampler_passes_the_sampler_checks() {
    let t = SampledTable::new(lobe_table(40.0, 0.6));
    for theta in [0.0f64, 30.0, 60.0, 80.0, 85.0, 88.0] {
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
    for theta in [0.0f64, 45.0, 75.0, 86.0] {
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
            "theta_o {theta}: table sampler {err} vs cosine {err_cos}"
        );
    }
}

/// The sampler keeps some of the stratification of low-discrepancy points: the albedo estimate
/// from 256 points of a randomly shifted Hammersley set (Cranley–Patterson rotation; each shift
/// an unbiased estimate) varies less between shifts than the estimate from 256 independent
/// points. The cell choice inverts cumulative distributions, monotone in each coordinate; the
/// alias method it replaced sends neighbouring points to unrelated cells, a ratio of 1. Between
/// two bins the mixture's distributions are inverted, not a bin chosen with part of `u.x` (which
/// gave ratios of 2.1 at 10°, 1.3 at 50°, and *below 1* near grazing: 0.28 at 80°, 0.44 at
/// 86°); measured now 4.8 at 10°, 2.0 at 50°, 1.2 at 80°, 1.04 at 86°. The gain stays modest
/// near grazing: `f cos / pdf` jumps at the edges of 11 520 cells, far more than 256 strata,
/// and the horizon cuts the lobe. Tolerance: the ratio's estimate from 256 shifts has a
/// relative standard deviation of about sqrt(2/255) = 9%, so 1.2 lies 2 of them above an alias
/// sampler's 1 and below the measured ratios at 10° and 50°; near grazing 0.75 lies 3 of them
/// below the measured ratios and above the bin choice's.
#[test]
fn sampler_keeps_the_stratification_of_low_discrepancy_points() {
    let t = SampledTable::new(lobe_table(40.0, 0.6));
    let n = 256usize;
    let shifts = 256;
    // Van der Corput's radical inverse in base 2.
    let radical_inverse = |i: u32| f64::from(i.reverse_bits()) / 4_294_967_296.0;
    let estimate = |points: &mut dyn FnMut(usize) -> DVec2, wo: DVec3| {
        let (mut s, mut s2) = (0.0, 0.0);
        for k in 0..n {
            let v = t
                .sample(wo, points(k))
                .map_or(0.0, |x| x.f.x * x.wi.z / x.pdf);
            s += v;
            s2 += v * v;
        }
        (s / n as f64, s2 / n as f64)
    };
    for (theta, min_ratio) in [(10.0f64, 1.2), (50.0, 1.2), (80.0, 0.75), (86.0, 0.75)] {
        let wo = dir(theta.to_radians(), 0.4);
        let mut rng = rand_pcg::Pcg64::seed_from_u64(11);
        // Variance of one independent sample, from many.
        let (mut m, mut m2) = (0.0, 0.0);
        for _ in 0..shifts {
            let (a, b) = estimate(&mut |_| DVec2::new(rng.random(), rng.random()), wo);
            m += a;
            m2 += b;
        }
        let (m, m2) = (m / shifts as f64, m2 / shifts as f64);
        let var_independent = (m2 - m * m) / n as f64;
        // Variance between shifted Hammersley estimates.
        let (mut h, mut h2) = (0.0, 0.0);
        for _ in 0..shifts {
            let shift = DVec2::new(rng.random(), rng.random());
            let (a, _) = estimate(
                &mut |k| {
                    let p = DVec2::new((k as f64 + 0.5) / n as f64, radical_inverse(k as u32));
                    DVec2::new((p.x + shift.x).fract(), (p.y + shift.y).fract())
                },
                wo,
            );
            h += a;
            h2 += a * a;
        }
        let h = h / shifts as f64;
        let var_hammersley = (h2 / shifts as f64 - h * h) * shifts as f64 / (shifts - 1) as f64;
        assert!(
            var_independent > min_ratio * var_hammersley,
            "theta_o {theta}: variance {var_independent:.3e} independent, \
             {var_hammersley:.3e} stratified"
        );
    }
}
