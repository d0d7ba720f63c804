//! Microfacet distributions: normalisation, Smith's projected-area identity, the free functions
//! against the distribution, the normal samplers against their pdfs, erfinv against erf.

use glam::{DVec2, DVec3};
use gonio_brdf::microfacet::*;
use std::f64::consts::PI;

/// Midpoint quadrature over the upper hemisphere in (θ, φ), `dω = sin θ dθ dφ`.
fn hemisphere_integral(n: usize, f: impl Fn(DVec3) -> f64) -> f64 {
    let (dt, dp) = (0.5 * PI / n as f64, 2.0 * PI / (2 * n) as f64);
    let mut sum = 0.0;
    for i in 0..n {
        let (s, c) = ((i as f64 + 0.5) * dt).sin_cos();
        for j in 0..2 * n {
            let p = (j as f64 + 0.5) * dp;
            sum += f(DVec3::new(s * p.cos(), s * p.sin(), c)) * s;
        }
    }
    sum * dt * dp
}

fn all_distributions() -> Vec<Microfacet> {
    vec![
        Microfacet::beckmann(0.3),
        Microfacet::ggx(0.3),
        Microfacet {
            distribution: Distribution::Beckmann,
            alpha_x: 0.2,
            alpha_y: 0.5,
        },
        Microfacet {
            distribution: Distribution::Ggx,
            alpha_x: 0.5,
            alpha_y: 0.15,
        },
    ]
}

/// Numerical quadrature of `∫ D cos th dω` over the hemisphere, which must be 1.
#[test]
fn beckmann_is_normalised() {
    for m in [0.05, 0.2, 0.5] {
        let n = 20000;
        let dth = (PI / 2.0) / n as f64;
        let sum: f64 = (0..n)
            .map(|i| {
                let th = (i as f64 + 0.5) * dth;
                beckmann_d(th.cos(), m) * th.cos() * th.sin() * 2.0 * PI * dth
            })
            .sum();
        assert!((sum - 1.0).abs() < 1e-6, "m = {m}: {sum}");
    }
}

/// Every distribution, isotropic or not, covers unit projected area.
#[test]
fn distributions_are_normalised() {
    for mf in all_distributions() {
        let sum = hemisphere_integral(600, |h| mf.d(h) * h.z);
        assert!((sum - 1.0).abs() < 1e-4, "{mf:?}: {sum}");
    }
}

/// The masking identity `∫ G1(wo) <wo·h> D(h) dh = cos to` (Heitz 2014, eq. 2) checked by
/// quadrature at several outgoing directions, for both distributions and anisotropy; this
/// ties `Λ` to `D` independently of how either is written.
#[test]
fn smith_satisfies_projected_area_identity() {
    for mf in all_distributions() {
        for (to_deg, phi_deg) in [(0.0f64, 0.0f64), (30.0, 20.0), (60.0, 90.0), (80.0, 45.0)] {
            let (to, po) = (to_deg.to_radians(), phi_deg.to_radians());
            let wo = DVec3::new(to.sin() * po.cos(), to.sin() * po.sin(), to.cos());
            let sum = hemisphere_integral(600, |h| wo.dot(h).max(0.0) * mf.d(h));
            let lhs = mf.g1(wo) * sum;
            assert!(
                (lhs - wo.z).abs() < 1e-4,
                "{mf:?} to = {to_deg}: {lhs} vs {}",
                wo.z
            );
        }
    }
}

#[test]
fn free_functions_match_the_isotropic_distribution() {
    let m = 0.4;
    let c = 0.7f64;
    let tan2 = (1.0 - c * c) / (c * c);
    let expect = (-tan2 / (m * m)).exp() / (PI * m * m * c.powi(4));
    assert!((beckmann_d(c, m) - expect).abs() < 1e-12 * expect);
    let a = 1.0 / (m * tan2.sqrt());
    let lambda = (libm::erf(a) - 1.0) / 2.0 + (-a * a).exp() / (2.0 * a * PI.sqrt());
    assert!((beckmann_lambda(c, m) - lambda).abs() < 1e-12);
    assert!((smith_g2(c, 0.5, m) - 1.0 / (1.0 + lambda + beckmann_lambda(0.5, m))).abs() < 1e-15);
    assert_eq!(smith_g1(1.0, m), 1.0);
}

/// The normal samplers as a "BRDF" whose directions are the normals themselves, with
/// `f cos = pdf` so that its albedo is the integral of the pdf: 1 for `D(h) cos θh`, and
/// 1 for the visible normals only if Smith's `G1` normalises them (Heitz 2014, eq. 2).
struct Normals {
    mf: Microfacet,
    visible: bool,
}

impl gonio_brdf::Brdf for Normals {
    fn eval(&self, wo: DVec3, h: DVec3) -> gonio_brdf::Rgb {
        gonio_brdf::Rgb::splat(if h.z > 0.0 {
            self.pdf(wo, h) / h.z
        } else {
            0.0
        })
    }
    fn sample(&self, wo: DVec3, u: DVec2) -> Option<gonio_brdf::BrdfSample> {
        let h = if self.visible {
            self.mf.sample_visible(wo, u)
        } else {
            self.mf.sample_d(u)
        };
        (h.z > 0.0).then(|| gonio_brdf::BrdfSample {
            wi: h,
            f: self.eval(wo, h),
            pdf: self.pdf(wo, h),
        })
    }
    fn pdf(&self, wo: DVec3, h: DVec3) -> f64 {
        if self.visible {
            self.mf.pdf_visible(wo, h)
        } else {
            self.mf.pdf_d(h)
        }
    }
}

#[test]
fn normal_samplers_follow_their_pdfs() {
    use gonio_brdf::validate::{SamplerCheck, check_sampler};
    let opts = SamplerCheck {
        samples: 100_000,
        ..SamplerCheck::default()
    };
    for mf in all_distributions() {
        for visible in [false, true] {
            for (t, p) in [(0.0f64, 0.0f64), (50.0, 30.0), (80.0, 200.0)] {
                let (t, p) = (t.to_radians(), p.to_radians());
                let wo = DVec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos());
                let report = check_sampler(&Normals { mf, visible }, wo, &opts);
                assert!(
                    report.passed(),
                    "{mf:?} visible={visible} {wo}: {report:#?}"
                );
                assert!(
                    (report.albedo_quadrature.x - 1.0).abs() < 2e-3,
                    "{report:?}"
                );
            }
        }
    }
}

/// erfinv inverts libm's erf to near double precision across the range.
#[test]
fn erfinv_inverts_erf() {
    for x in [-5.0, -3.2, -1.0, -0.3, 0.0, 1e-8, 0.5, 2.0, 4.5] {
        let y = libm::erf(x);
        let back = erfinv(y);
        let tol = if x.abs() > 3.0 { 1e-4 } else { 1e-13 };
        assert!((back - x).abs() < tol * x.abs().max(1.0), "{x}: {back}");
    }
}

/// The stratified visible normals are the sampler's own at each stratum, to the bit, for every
/// distribution and for directions from normal incidence (where Beckmann's slopes are not
/// separable) to grazing; and `g2_with` is `g2`.
#[test]
fn stratified_visible_normals_are_the_samplers() {
    let n = 7;
    for m in all_distributions() {
        for (theta, phi) in [
            (0.0f64, 0.0f64),
            (1e-7, 0.3),
            (0.4, 0.0),
            (1.1, 2.0),
            (1.55, 4.0),
        ] {
            let w = DVec3::new(
                theta.sin() * phi.cos(),
                theta.sin() * phi.sin(),
                theta.cos(),
            );
            let grid = m.sample_visible_stratified(w, n);
            assert_eq!(grid.len(), n * n);
            for (k, h) in grid.iter().enumerate() {
                let u = DVec2::new(
                    ((k / n) as f64 + 0.5) / n as f64,
                    ((k % n) as f64 + 0.5) / n as f64,
                );
                let one = m.sample_visible(w, u);
                assert_eq!(
                    h.to_array().map(f64::to_bits),
                    one.to_array().map(f64::to_bits)
                );
                assert_eq!(
                    m.g2_with(m.lambda(w), *h).to_bits(),
                    m.g2(w, *h).to_bits(),
                    "{m:?} {w} {h}"
                );
            }
        }
    }
}

/// `visible_disk_point` inverts `visible_normal_on_disk`, and the latter at the polar point
/// `(√u.x cos 2πu.y, √u.x sin 2πu.y)` is `sample_visible(u)`, for views from normal incidence to
/// 89° and stretched anisotropic roughness. Tolerance: each step (stretch, projection on the
/// frame, the half-disk warp divided by `s ≥ ½`, normalisation) loses a few ulps, amplified
/// near the disk's rim (`|p|` up to 0.99, where `dp2/dnh ≈ 1/√(1 - |p|²) < 8`): far below 1e-9.
#[test]
fn visible_disk_point_inverts_the_ggx_visible_normal() {
    let mut aniso = Microfacet::ggx(0.1);
    aniso.alpha_y = 0.3;
    for m in [Microfacet::ggx(0.05), Microfacet::ggx(0.4), aniso] {
        for theta in [0.0f64, 30.0, 75.0, 89.0] {
            let (st, ct) = theta.to_radians().sin_cos();
            let w = DVec3::new(0.6 * st, 0.8 * st, ct);
            for i in 1..20 {
                for j in 0..20 {
                    let u = DVec2::new(i as f64 / 20.0 * 0.98, (j as f64 + 0.5) / 20.0);
                    let (r, phi) = (u.x.sqrt(), 2.0 * PI * u.y);
                    let p = DVec2::new(r * phi.cos(), r * phi.sin());
                    let h = m.visible_normal_on_disk(w, p);
                    assert!(
                        (h - m.sample_visible(w, u)).length() < 1e-9,
                        "{m:?} {theta} {u}"
                    );
                    let back = m.visible_disk_point(w, h).expect("the normal is visible");
                    assert!(
                        (back - p).length() < 1e-9,
                        "{m:?} theta {theta}: {p} -> {h} -> {back}"
                    );
                }
            }
        }
    }
    let beckmann = Microfacet::beckmann(0.2);
    assert!(beckmann.visible_disk_point(DVec3::Z, DVec3::Z).is_none());
    let ggx = Microfacet::ggx(0.2);
    let w = DVec3::new(0.8, 0.0, 0.6);
    assert!(
        ggx.visible_disk_point(w, DVec3::new(-0.8, 0.0, -0.6))
            .is_none()
    );
}
