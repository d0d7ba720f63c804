//! `compare` of the ray-method and Kirchhoff curves of the rough epoxy sample (Sq 805 nm,
//! T 6 µm) at the STARR geometry: the two methods' differences must stay within what the
//! validation of the Kirchhoff integral established.
//!
//! What that validation established (docs/kirchhoff.md, "Analytic references"; Beckmann &
//! Spizzichino 1963, ch. 5): for g ≫ 1 the Kirchhoff integral tends to the geometric (facet)
//! limit, which the ray method computes, with corrections O(1/g); here
//! g = k²σ²(2 cos 20°)² ≈ 300 at 550 nm, so the methods must agree up to the noise of
//! each and two small systematic differences. The noise, per detector and realisation, in the
//! log of the ratio of the two readings:
//!
//! - speckle: a Kirchhoff detector averages `N = π alpha² A cos ts/λ²` grains, with
//!   `A = 0.44 π D²/4` for the Schwartz window over a spot of diameter D (docs/kirchhoff.md,
//!   "Speckle"), the `cos ts` because the cone's in-plane extent in wave-vector space shrinks with
//!   it; each reading scatters by `1/√N` (17% at ts = 0 for D = 127.5 µm, 1.4°, 550 nm);
//! - the slope histogram: the Kirchhoff spot weights the middle of the map (`A` is 2.9 times
//!   smaller than the map), the ray method the whole map uniformly; the spot's histogram departs
//!   from the map's by `var_map (A_map/A − 1)`, where `var_map`, the map's own departure from the
//!   ensemble, is measured by the ray curves' spread over the realisations less their counting
//!   noise;
//! - counting: `1/hits` of the ray method.
//!
//! Averaging R realisations divides the sum by R. Systematic differences: plane-fit normals (the
//! ray method's default, as the study uses) see the slopes `ε` ≈ 1.2% lower than the bicubic
//! spline the Kirchhoff integral follows, which changes a Gaussian lobe's `ln rho` at the level
//! `q` of its peak by `2ε(1 − ln(1/q))`, at most `2.6ε` above a tenth of the peak; shadowing and
//! masking (Smith `Λ` for rms slope 0.27) removes at most 3% below 75° at these incidences; both
//! methods now apply it (the ray method by tracing the map, the Kirchhoff integral by Smith's
//! `Λ` of the spot's slopes), so their difference in it is at most that whole 3%, kept as the
//! bound. Their sum `b` is added to every tolerance.
//!
//! Tolerances (3σ): the RMS over the `m` lobe points (ray reading above a tenth of its peak) of
//! `log10` ratios with variances `s_j²` has `E[rms²] = mean s²`, with a relative spread
//! `√(2/m)`; the peak height differs by at most `3 s + b` at the peak; a half-maximum crossing moves
//! by `s σ/1.18` for a lobe of standard deviation σ (from its FWHM), and both move by the peak's
//! error, so the FWHMs differ by `3 (σ/1.18) √(s_l² + s_r² + 4 s_p²)` plus `ε` FWHM, with σ ≈ 22°
//! from the facet tilt `2 atan s` along the plane of incidence; near its top a lobe drops by
//! `δ²/2σ²`, so noise `s` can move a maximum by up to `σ √(6 s)` (3σ), plus half a scatter step.

use gonio_brdf::Ior;
use gonio_instrument::compare::compare;
use gonio_scatter::InplaneCurve;
use gonio_scatter::kirchhoff::{Kirchhoff, KirchhoffOptions, Spot, average_curves};
use gonio_scatter::ray::{RayEngine, RayOptions};
use gonio_surface::HeightMap;
use gonio_surface::normals::NormalMethod;
use gonio_surface::synth::{EPOXY_CORR_LENGTH_M, GaussianSurface};

const SQ: f64 = 805e-9;
const N: usize = 256;
const DX: f64 = 0.5e-6;
const REALISATIONS: u64 = 8;
const WAVELENGTH: f64 = 550e-9;
const INCIDENCES_DEG: [f64; 4] = [20.0, 45.0, 60.0, 70.0];
const STEP_DEG: f64 = 5.0;

fn rough_sample(seed: u64) -> HeightMap {
    GaussianSurface::square(SQ, EPOXY_CORR_LENGTH_M, N, DX, seed)
        .generate()
        .unwrap()
}

/// Mean and sample variance.
fn mean_var(v: &[f64]) -> (f64, f64) {
    let n = v.len() as f64;
    let mean = v.iter().sum::<f64>() / n;
    (
        mean,
        v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0),
    )
}

/// Tests that take seconds each: `cargo test -- --skip slow::` leaves them out of a quick run.
mod slow {
    use super::*;

    #[test]
    fn ray_and_kirchhoff_curves_of_the_rough_sample_agree() {
        let half_angle = 1.4f64.to_radians();
        let scatter_deg: Vec<f64> = (0..=30).map(|i| -75.0 + STEP_DEG * i as f64).collect();
        let scatter: Vec<f64> = scatter_deg.iter().map(|t| t.to_radians()).collect();
        let incidences: Vec<f64> = INCIDENCES_DEG.iter().map(|t| t.to_radians()).collect();
        let ior = Ior::Dielectric(1.55);
        let (mut rays, mut waves, mut slope_ratio, mut slope_x) =
            (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        let mut spot = None;
        for seed in 0..REALISATIONS {
            let map = rough_sample(100 + seed);
            let ray = RayEngine::new(
                &map,
                RayOptions {
                    ior,
                    ..RayOptions::default()
                },
            )
            .unwrap();
            let spline = RayEngine::new(
                &map,
                RayOptions {
                    ior,
                    normals: NormalMethod::Spline,
                    ..RayOptions::default()
                },
            )
            .unwrap();
            let ((px, py), (sx, sy)) = (ray.rms_slopes(), spline.rms_slopes());
            slope_ratio.push(0.5 * (px / sx + py / sy));
            slope_x.push(px);
            rays.push(
                incidences
                    .iter()
                    .map(|&ti| ray.inplane(ti, &scatter, half_angle).unwrap())
                    .collect::<Vec<_>>(),
            );
            let k = Kirchhoff::new(&map, KirchhoffOptions::new(ior)).unwrap();
            spot = Some(Spot::largest(&map));
            waves.push(
                k.inplane(
                    &[WAVELENGTH],
                    &incidences,
                    &scatter,
                    half_angle,
                    &gonio_io::Progress::silent(),
                )
                .unwrap(),
            );
        }
        let r = REALISATIONS as f64;
        let ray_mean = average_curves(&rays).unwrap();
        let wave_mean = average_curves(&waves).unwrap();

        // Speckle grains at normal detection, and the spot's effective area against the map's.
        let d = spot.unwrap().diameter;
        let area = 0.44 * std::f64::consts::PI * d * d / 4.0;
        let grains =
            std::f64::consts::PI * half_angle * half_angle * area / (WAVELENGTH * WAVELENGTH);
        assert!((grains - 35.0).abs() < 1.0, "{grains} grains");
        let map_area = ((N - 1) as f64 * DX).powi(2);
        // Systematic: plane-fit slopes and shadowing.
        let eps = 1.0 - slope_ratio.iter().sum::<f64>() / r;
        assert!(
            (0.0..0.03).contains(&eps),
            "plane-fit slopes {eps} below the spline's"
        );
        let b = 2.6 * eps + 0.03;
        let log10e = std::f64::consts::LOG10_E;
        // The lobe's standard deviation in scatter angle: twice the facet tilt along the plane of
        // incidence (facet model: a facet tilted by `a` turns the reflected ray by `2a`), about 22°.
        let sigma = (2.0 * (slope_x.iter().sum::<f64>() / r).atan()).to_degrees();
        let position_tol = |s_peak: f64| sigma * (6.0 * s_peak).sqrt() + 0.5 * STEP_DEG;

        for (c, ti) in INCIDENCES_DEG.iter().enumerate() {
            let (ray, wave) = (&ray_mean[c], &wave_mean[c]);
            let peak = ray.points.iter().map(|p| p.reflectance).fold(0.0, f64::max);
            // Variance of ln(kirchhoff/ray) of the averaged curves at each scatter angle.
            let s2: Vec<f64> = (0..scatter.len())
                .map(|j| {
                    let ln_ray: Vec<f64> = rays
                        .iter()
                        .map(|s| s[c].points[j].reflectance.ln())
                        .collect();
                    let counting = rays
                        .iter()
                        .map(|s| s[c].points[j].rel_uncertainty.unwrap().powi(2))
                        .sum::<f64>()
                        / r;
                    let histogram = (mean_var(&ln_ray).1 - counting).max(0.0);
                    let speckle = 1.0 / (grains * scatter[j].cos());
                    (speckle + histogram * (map_area / area - 1.0) + counting) / r
                })
                .collect();
            let lobe: Vec<usize> = (0..scatter.len())
                .filter(|&j| ray.points[j].reflectance > 0.1 * peak)
                .collect();
            let lobe_curve = InplaneCurve {
                points: lobe.iter().map(|&j| ray.points[j]).collect(),
                ..ray.clone()
            };
            let cmp = compare(&lobe_curve, wave).unwrap();
            let m = cmp.common_points as f64;
            assert_eq!(cmp.common_points, lobe.len());
            let mean_s2 = lobe.iter().map(|&j| s2[j]).sum::<f64>() / m;
            let rms_tol = log10e * ((mean_s2 * (1.0 + 3.0 * (2.0 / m).sqrt())).sqrt() + b);
            let j_peak = scatter_deg
                .iter()
                .position(|&t| t == cmp.peak_a.position_deg)
                .unwrap();
            let s_peak = s2[j_peak].sqrt();
            let height = (cmp.peak_b.reflectance / cmp.peak_a.reflectance).ln();
            eprintln!(
                "{ti}°: {} lobe points, rms_log10 {:.4} (tolerance {rms_tol:.4}), peak at {} / {}, \
                 height ratio {:.3} (tolerance ±{:.3}), FWHM {:?} / {:?}",
                lobe.len(),
                cmp.rms_log10,
                cmp.peak_a.position_deg,
                cmp.peak_b.position_deg,
                height.exp(),
                3.0 * s_peak + b,
                cmp.peak_a.fwhm_deg,
                cmp.peak_b.fwhm_deg
            );
            assert!(
                cmp.rms_log10 < rms_tol,
                "{ti}°: rms_log10 {}",
                cmp.rms_log10
            );
            assert!(
                height.abs() < 3.0 * s_peak + b,
                "{ti}°: peak ratio {}",
                height.exp()
            );
            match (cmp.peak_a.fwhm_deg, cmp.peak_b.fwhm_deg) {
                (Some(wa), Some(wb)) => {
                    let at = |deg: f64| {
                        let j = ((deg + 75.0) / STEP_DEG).round().clamp(0.0, 30.0) as usize;
                        s2[j]
                    };
                    let (left, right) = (
                        cmp.peak_a.position_deg - 0.5 * wa,
                        cmp.peak_a.position_deg + 0.5 * wa,
                    );
                    let spread = (at(left) + at(right) + 4.0 * s_peak * s_peak).sqrt();
                    let tol = 3.0 * sigma / 1.18 * spread + eps * wa;
                    assert!((wa - wb).abs() < tol, "{ti}°: FWHM {wa} vs {wb} (±{tol})");
                }
                // Both lobes run past the last detector (75°) before falling to half maximum.
                (None, None) => {}
                (a, b) => panic!("{ti}°: only one lobe falls to half maximum: {a:?} {b:?}"),
            }
            let moved = (cmp.peak_a.position_deg - cmp.peak_b.position_deg).abs();
            let tol = position_tol(s_peak);
            assert!(moved <= tol, "{ti}°: peaks {moved}° apart (±{tol})");
        }
    }
}
