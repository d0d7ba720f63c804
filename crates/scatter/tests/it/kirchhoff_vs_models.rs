//! The Kirchhoff integral over synthetic Gaussian surfaces against the Beckmann-Spizzichino series
//! and the ray method: the acceptance test of the Kirchhoff engine (results in `docs/kirchhoff.md`,
//! "Validation against the models").
//!
//! Statistics behind the tolerances. One detector of half-angle alpha over a spot of diameter D
//! averages about π(alpha D/λ)² speckle grains, each an independent exponential variate, so its
//! reading scatters by 1/√(grains) about the ensemble mean; averaging R realisations divides that
//! by √R. The Schwartz window weights the centre of the spot: `(∫W²)²/∫W⁴` is 44% of the disc,
//! so with D = 128 µm and λ = 500 nm a 2° cone holds about 87 grains (11% per realisation, 3.8%
//! over 8) and a 3° cone about 195 (7%, 1.8% over 16). The realisation's own surface
//! statistics matter more in the tails: the spot sees only ~400 correlation areas, and a 1% error
//! in the rms slope moves the 1%-of-peak point by about 9% (relative to its peak the lobe goes as
//! `exp(-tan²θ/m²)`, which is 1% where `tan²θ/m² = ln 100`, so it changes by `2 ln 100 ≈ 9` times
//! the relative change of `m`), so the series is evaluated with each spot's own W²-weighted rms
//! height and slope along x and then averaged.
//!
//! The bound, 15%, from these figures. About 30 detectors lie above 1% of the peak; the largest
//! of 30 independent deviations exceeds four standard deviations with probability
//! 30 · 6·10⁻⁵ ≈ 2·10⁻³. Moderate case: speckle 3.8% (8 realisations, 2° cone), 4 × 3.8% = 15%.
//! Rough case: speckle 1.8% (16 realisations, 3° cone), 4 × 1.8% = 7%, plus what the spot's
//! own statistics still leave: the Kirchhoff spot sees its W²-weighted centre (~400 correlation
//! areas, so its rms slope departs from the map's by about 1/√(2 · 400) = 3.5% per realisation,
//! 0.9% over 16) while the ray method sees the whole map, and 0.9% of slope moves the 1%-of-peak
//! tail by 9 × 0.9% = 8%: 7% + 8% = 15%. (Measured: 7% for the moderate case, 10% against the
//! series and 12% against the ray method for the rough one.) A wrong normalisation, a missing
//! F factor or a wrong g (also tested by the flat and smooth cases) would miss by far more.

use gonio_brdf::Ior;
use gonio_scatter::InplaneCurve;
use gonio_scatter::analytic::{AnalyticModel, GaussianModel};
use gonio_scatter::kirchhoff::{Kirchhoff, KirchhoffOptions, Spot, average_curves};
use gonio_scatter::ray::{RayEngine, RayOptions};
use gonio_surface::HeightMap;
use gonio_surface::normals::NormalMethod;
use gonio_surface::spline::BicubicSpline;
use gonio_surface::synth::GaussianSurface;

const N: f64 = 1.55;
const WAVELENGTH: f64 = 500e-9;

fn surface(sigma: f64, t: f64, seed: u64) -> HeightMap {
    GaussianSurface::square(sigma, t, 257, 0.5e-6, seed)
        .generate()
        .unwrap()
}

fn scatter() -> Vec<f64> {
    (-70..=70)
        .step_by(5)
        .map(|d| f64::from(d).to_radians())
        .collect()
}

/// Kirchhoff curves at 20° averaged over the realisations, and the maps.
fn kirchhoff_average(
    sigma: f64,
    t: f64,
    alpha: f64,
    realisations: u64,
) -> (InplaneCurve, Vec<HeightMap>) {
    let maps: Vec<_> = (0..realisations)
        .map(|s| surface(sigma, t, 100 + s))
        .collect();
    let sets: Vec<Vec<InplaneCurve>> = maps
        .iter()
        .map(|map| {
            Kirchhoff::new(map, KirchhoffOptions::new(Ior::Dielectric(N)))
                .unwrap()
                .inplane(
                    &[WAVELENGTH],
                    &[20f64.to_radians()],
                    &scatter(),
                    alpha,
                    &gonio_io::Progress::silent(),
                )
                .unwrap()
        })
        .collect();
    (average_curves(&sets).unwrap().remove(0), maps)
}

/// The rms height of the part of `map` the spot sees and its total rms slope `√2 sx` from the
/// rms slope along x, the plane of incidence, which sets the in-plane lobe; both weighted as the
/// field is, by the squared window (`W²` over the default spot, slopes of the bicubic spline).
fn spot_statistics(map: &HeightMap) -> (f64, f64) {
    let spot = Spot::largest(map);
    let spline = BicubicSpline::from_map(map).unwrap();
    let radius = 0.5 * spot.diameter;
    let (mut sw, mut sh, mut sh2, mut ss2) = (0.0, 0.0, 0.0, 0.0);
    for iy in 0..map.ny() {
        for ix in 0..map.nx() {
            let x = ix as f64 * map.dx() - spot.center.0;
            let y = iy as f64 * map.dy() - spot.center.1;
            let t2 = (x * x + y * y) / (radius * radius);
            if t2 >= 1.0 {
                continue;
            }
            let w2 = (-2.0 / (1.0 - t2)).exp();
            let h = map.heights()[[iy, ix]];
            let g = spline.node_gradient(ix, iy);
            sw += w2;
            sh += w2 * h;
            sh2 += w2 * h * h;
            ss2 += w2 * g.x * g.x;
        }
    }
    let mean = sh / sw;
    ((sh2 / sw - mean * mean).sqrt(), (2.0 * ss2 / sw).sqrt())
}

/// The Beckmann-Spizzichino curve averaged over the realisations, each evaluated with the rms
/// height and slope its spot actually has (a single realisation's statistics depart from the
/// ensemble's, and a 1% error in the rms slope moves the 1%-of-peak point by about 9%: see the
/// module comment).
fn series_average(maps: &[HeightMap], alpha: f64) -> InplaneCurve {
    let sets: Vec<Vec<InplaneCurve>> = maps
        .iter()
        .map(|map| {
            let (sigma, slope) = spot_statistics(map);
            let model = GaussianModel::new(sigma, 2.0 * sigma / slope, Ior::Dielectric(N)).unwrap();
            let ti = 20f64.to_radians();
            vec![model.inplane(AnalyticModel::Beckmann, WAVELENGTH, ti, &scatter(), alpha)]
        })
        .collect();
    average_curves(&sets).unwrap().remove(0)
}

/// Largest relative difference of `a` from the reference `b` where `b` exceeds 1% of its peak.
fn worst(a: &InplaneCurve, b: &InplaneCurve) -> f64 {
    let peak = b.points.iter().map(|p| p.brdf_per_sr).fold(0.0, f64::max);
    a.points
        .iter()
        .zip(&b.points)
        .filter(|(_, q)| q.brdf_per_sr > 0.01 * peak)
        .map(|(p, q)| (p.brdf_per_sr / q.brdf_per_sr - 1.0).abs())
        .fold(0.0, f64::max)
}

/// The light a gloss receptor collects from a map too rough for one sampled grid is the mean over
/// smaller spots. A rough map (Sq 0.3 µm, T 3 µm, rms slope 0.2) at 550 nm and 20° needs
/// its phase sampled 3 times finer than the map for a cone about specular (590 thousand facets
/// over the 128 µm spot; the whole hemisphere would need 10 times); with the facet limit set to
/// 2¹⁸ the engine cuts the spot's square into 2 × 2 spots of 64 µm. The comparison with the ray
/// method also checks the cone's sampling rule (no image of the field reaches the cone). The
/// reflectance into a 5° cone about specular (a gloss receptor) must match, on the same map, the
/// ray method (spline normals, without its shadowing: at 20° on slopes of 0.2 Smith's `Λ` is
/// below 10⁻⁸ for the source and the cone, so the Kirchhoff method's `G2` is 1 there too) and
/// the single-spot result.
///
/// Tolerance. Speckle: the four spots together hold as much window area as the single spot,
/// `A = 0.44 π D²/4` with D = 128 µm, so the cone averages `N = π alpha² A/λ² ≈ 450` grains and
/// a reading scatters by `1/√N = 4.7%`; three standard deviations are 14%. The ray method sees
/// the whole map and the spots their windowed centres, whose rms slopes differ by a few per cent
/// (the specular reading of a facet model goes as `1/m²`): 6% more. So 20% against the ray
/// method; between split and single spot (the same surface, overlapping windows) the speckle of
/// both, `√2 · 3 · 4.7% = 20%`. A missing division by the number of spots would be 300% off.
#[test]
fn spot_averaged_receptor_matches_ray_method() {
    use gonio_scatter::Detector;
    use gonio_scatter::geometry::{incidence_direction, inplane_direction};
    let (sigma, t) = (0.3e-6, 3e-6);
    let wavelength = 550e-9;
    let map = surface(sigma, t, 300);
    let ti = 20f64.to_radians();
    let wi = incidence_direction(ti);
    let receptor = Detector {
        direction: inplane_direction(ti),
        half_angle: 5f64.to_radians(),
    };
    let whole = Kirchhoff::new(&map, KirchhoffOptions::new(Ior::Dielectric(N))).unwrap();
    let split = Kirchhoff::new(
        &map,
        KirchhoffOptions {
            max_facets: 1 << 18,
            ..KirchhoffOptions::new(Ior::Dielectric(N))
        },
    )
    .unwrap();
    assert_eq!(
        whole
            .sampling_spots_for(wavelength, wi, Some(&receptor))
            .unwrap()
            .len(),
        1
    );
    let spots = split
        .sampling_spots_for(wavelength, wi, Some(&receptor))
        .unwrap();
    assert_eq!(spots.len(), 4, "{spots:?}");
    let read = |e: &Kirchhoff| -> f64 {
        e.scattered_in_cone(wavelength, wi, &receptor)
            .unwrap()
            .iter()
            .map(|s| s.1)
            .sum()
    };
    let (k_whole, k_split) = (read(&whole), read(&split));
    let options = RayOptions {
        ior: Ior::Dielectric(N),
        normals: NormalMethod::Spline,
        shadowing: false,
        ..RayOptions::default()
    };
    let cos_alpha = receptor.half_angle.cos();
    let ray: f64 = RayEngine::new(&map, options)
        .unwrap()
        .reflected_rays(wi)
        .unwrap()
        .iter()
        .filter(|(wo, _)| wo.dot(receptor.direction) >= cos_alpha)
        .map(|s| s.1)
        .sum();
    eprintln!("split {k_split:.4e}, whole {k_whole:.4e}, ray {ray:.4e}");
    assert!(
        (k_split / ray - 1.0).abs() < 0.2,
        "split {k_split} vs ray {ray}"
    );
    assert!(
        (k_split / k_whole - 1.0).abs() < 0.2,
        "split {k_split} vs whole {k_whole}"
    );
}

/// Tests that take seconds each: `cargo test -- --skip slow::` leaves them out of a quick run.
mod slow {
    use super::*;

    /// Rough: sigma = 0.3 µm, T = 3 µm (rms slope 0.2), g = 50 at 20° and 500 nm; against the series
    /// and against the ray method on the same maps (spline normals, without its shadowing; the
    /// Kirchhoff method's `G2`, Smith's function of the slopes, is above 0.99 wherever the
    /// detectors read, out to 75°, where `Λ` = 0.006 for this rms slope).
    #[test]
    fn rough_matches_beckmann_series_and_ray_method() {
        let (sigma, t) = (0.3e-6, 3e-6);
        let alpha = 3f64.to_radians();
        let ti = 20f64.to_radians();
        let g = (4.0 * std::f64::consts::PI * sigma * ti.cos() / WAVELENGTH).powi(2);
        assert!(g > 40.0, "g = {g}");
        let (kirchhoff, maps) = kirchhoff_average(sigma, t, alpha, 16);
        let series = series_average(&maps, alpha);
        let ws = worst(&kirchhoff, &series);
        let options = RayOptions {
            ior: Ior::Dielectric(N),
            normals: NormalMethod::Spline,
            shadowing: false,
            ..RayOptions::default()
        };
        let rays: Vec<Vec<InplaneCurve>> = maps
            .iter()
            .map(|m| {
                vec![
                    RayEngine::new(m, options)
                        .unwrap()
                        .inplane(ti, &scatter(), alpha)
                        .unwrap(),
                ]
            })
            .collect();
        let ray = average_curves(&rays).unwrap().remove(0);
        let w = worst(&kirchhoff, &ray);
        assert!(
            ws < 0.15,
            "against the series: worst relative difference {ws}"
        );
        assert!(
            w < 0.15,
            "against the ray method: worst relative difference {w}"
        );
    }

    /// Moderately rough: sigma = 0.12 µm, T = 2 µm (rms slope 0.12), g = 8 at 20° and 500 nm.
    #[test]
    fn moderately_rough_matches_beckmann_series() {
        let (sigma, t) = (0.12e-6, 2e-6);
        let alpha = 2f64.to_radians();
        let ti = 20f64.to_radians();
        let g = (4.0 * std::f64::consts::PI * sigma * ti.cos() / WAVELENGTH).powi(2);
        assert!((5.0..20.0).contains(&g), "g = {g}");
        let (kirchhoff, maps) = kirchhoff_average(sigma, t, alpha, 8);
        let series = series_average(&maps, alpha);
        let w = worst(&kirchhoff, &series);
        assert!(w < 0.15, "worst relative difference {w}");
    }

    /// No grating ghosts. Facets of pitch `a` act as a grating: before the facet grid was
    /// refined to keep its grating orders off the detectors, smooth maps showed the diffuse lobe
    /// imaged at `sin ts = sin ti - λ/a` (-48° at 20°, 550 nm, 0.5 µm facets) at up to 7·10⁻³ 1/sr
    /// where the true scatter is below 10⁻⁹. On the demo's smooth samples (Sq 3 and 50 nm, T = 6 µm)
    /// every detector more than 10° from specular must now read below three times the
    /// Beckmann-Spizzichino series (cone-averaged: the 3× covers the speckle of one realisation, a
    /// 1.4° cone over the 128 µm spot holds about 35 grains, 17% rms, and the realisation's own
    /// statistics in the tails) or below 10⁻⁵ of the specular detector, whichever is larger. The
    /// second bound is the floor of what the method claims: ten degrees from specular the window's
    /// diffraction pattern alone is six decades down (`flat_patch_lobe_integrates_to_fresnel`), and a
    /// ghost is the lobe's image attenuated only by `(a δ/2π)²`, about 10⁻⁴ of the lobe.
    #[test]
    fn smooth_maps_show_no_grating_ghosts() {
        let wavelength = 550e-9;
        let alpha = 1.4f64.to_radians();
        let scatter: Vec<f64> = (-75..=75).map(|d| f64::from(d).to_radians()).collect();
        let mut worst_ratio: f64 = 0.0;
        for (sigma, seed) in [(3e-9, 21), (50e-9, 22)] {
            let map = GaussianSurface::square(sigma, 6e-6, 257, 0.5e-6, seed)
                .generate()
                .unwrap();
            let engine = Kirchhoff::new(&map, KirchhoffOptions::new(Ior::Dielectric(N))).unwrap();
            let model = GaussianModel::new(sigma, 6e-6, Ior::Dielectric(N)).unwrap();
            for ti_deg in [20.0f64, 60.0] {
                let ti = ti_deg.to_radians();
                let curve = engine
                    .inplane(
                        &[wavelength],
                        &[ti],
                        &scatter,
                        alpha,
                        &gonio_io::Progress::silent(),
                    )
                    .unwrap()
                    .remove(0);
                let series =
                    model.inplane(AnalyticModel::Beckmann, wavelength, ti, &scatter, alpha);
                let specular = engine
                    .inplane(
                        &[wavelength],
                        &[ti],
                        &[ti],
                        alpha,
                        &gonio_io::Progress::silent(),
                    )
                    .unwrap()[0]
                    .points[0]
                    .brdf_per_sr;
                for (p, q) in curve.points.iter().zip(&series.points) {
                    if (p.scatter_deg - ti_deg).abs() <= 10.0 {
                        continue;
                    }
                    let bound = (3.0 * q.brdf_per_sr).max(1e-5 * specular);
                    let ratio = p.brdf_per_sr / bound;
                    worst_ratio = worst_ratio.max(ratio);
                    assert!(
                        ratio < 1.0,
                        "Sq {} nm, {ti_deg}°, {}°: {:.3e} 1/sr against the bound {bound:.3e} \
                         (series {:.3e}, specular {specular:.3e})",
                        sigma * 1e9,
                        p.scatter_deg,
                        p.brdf_per_sr,
                        q.brdf_per_sr
                    );
                }
            }
        }
        eprintln!("worst ratio to the bound: {worst_ratio:.3e}");
    }
}
