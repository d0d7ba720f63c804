//! Tables from height maps (`gonio_scatter::table`): energy against the ray engine's own
//! hemisphere reflectance, a mirror's lobe against Fresnel, the Beckmann fit of a Gaussian
//! surface's table against the map's rms slope, and Kirchhoff against the ray method.

use gonio_brdf::Ior;
use gonio_brdf::fit::{FitKind, FitOptions, fit};
use gonio_brdf::table::coords::dir;
use gonio_brdf::table::{BrdfTable, Provenance, Resolution};
use gonio_scatter::kirchhoff::{Kirchhoff, KirchhoffOptions};
use gonio_scatter::ray::{RayEngine, RayOptions};
use gonio_scatter::table::{
    STR_ANISOTROPIC, TableOptions, isotropic_turns, kirchhoff_table, ray_table,
    texture_aspect_ratio,
};
use gonio_surface::HeightMap;
use gonio_surface::synth::GaussianSurface;
use std::sync::OnceLock;

fn gaussian(sq: f64, corr: f64, n: usize, seed: u64) -> HeightMap {
    GaussianSurface::square(sq, corr, n, 0.5e-6, seed)
        .generate()
        .unwrap()
}

/// The reflectance the engine's rays carry for light from `theta_i`, averaged over the source
/// azimuths `phis` (radians).
fn mean_reflectance(engine: &RayEngine, theta_i: f64, phis: &[f64]) -> f64 {
    let one = |phi: f64| -> f64 {
        let rays = engine.reflected_rays(dir(theta_i, phi)).unwrap();
        rays.iter().map(|r| r.1).sum()
    };
    phis.iter().map(|&phi| one(phi)).sum::<f64>() / phis.len() as f64
}

/// A Gaussian surface (Sq 0.3 µm, T 6 µm; 512² at 0.5 µm, the Beckmann fit's test case), its ray
/// engine and its default isotropic table, computed once for the tests that share them.
fn gaussian_table() -> &'static (RayEngine, BrdfTable) {
    static TABLE: OnceLock<(RayEngine, BrdfTable)> = OnceLock::new();
    TABLE.get_or_init(|| {
        let map = gaussian(0.3e-6, 6e-6, 512, 11);
        let engine = RayEngine::new(&map, RayOptions::default()).unwrap();
        let options = TableOptions::isotropic();
        let table = ray_table(
            &engine,
            &options,
            Provenance::default(),
            &gonio_io::Progress::silent(),
        )
        .unwrap();
        (engine, table)
    })
}

/// The table keeps the light the engine reflects: at each computed incidence its albedo (a
/// fine quadrature of the table's interpolant over the half vector) equals the sum of the rays.
/// The slices keep it exactly (lumped tents); what is left is the table's interpolation in
/// theta_d and phi_d at a fixed half vector (a cell's value depends on its own incidence, and
/// the BRDF at a fixed half vector grows as 1/cos² theta_i: with the default 1° and 2° steps
/// under 0.6% up to 76° from incidences every 1°, against 1.5% and 4% with theta_d and phi_d
/// steps twice as large, the second-order convergence of linear interpolation; the default
/// incidences every 2° add the interpolation error in theta_i, 2% at 76°), and, near normal
/// incidence, counting noise: an
/// isotropic table at normal incidence reads each ring of half vectors at one azimuth of the
/// slice of 2° incidence, about 260 000 rays over 1 000 nodes (6% per node, about 1% over the
/// lobe's 20 rings at two azimuths each).
#[test]
fn table_albedo_is_the_ray_reflectance() {
    let (engine, table) = gaussian_table();
    let turns = TableOptions::isotropic().turns();
    for ti in [0.0f64, 20.0, 40.0, 60.0, 76.0] {
        let wi = dir(ti.to_radians(), 0.0);
        // The table averages the turned sources: so does the reference.
        let rays = mean_reflectance(engine, ti.to_radians(), &turns);
        let albedo = table.albedo_with(wi, 2048, 720)[0];
        // Second-order error of linear interpolation across the 2° between incidences of a
        // BRDF growing as 1/cos² theta_i: (Δ²/8) · 2 (1 + 3 tan² theta_i).
        let step = 2f64.to_radians();
        let curvature = step * step / 8.0 * 2.0 * (1.0 + 3.0 * ti.to_radians().tan().powi(2));
        let tol = if ti == 0.0 { 0.02 } else { 0.01 + curvature };
        assert!(
            (albedo / rays - 1.0).abs() < tol,
            "{ti}°: table albedo {albedo}, rays {rays}"
        );
    }
}

/// A flat map is a mirror: the table's lobe integrates to the Fresnel reflectance R(ti), even
/// though the lobe is a delta that the table can only hold as the tent of its innermost
/// theta_h node. (A merely smooth map spreads its rays over the first two rings, whose
/// azimuthal noise an isotropic table reads at one azimuth near normal incidence.)
#[test]
fn mirror_lobe_integrates_to_fresnel() {
    let map = HeightMap::new(ndarray::Array2::zeros((64, 64)), 0.5e-6, 0.5e-6).unwrap();
    let ior = Ior::Dielectric(1.55);
    let options = RayOptions {
        ior,
        ..RayOptions::default()
    };
    let engine = RayEngine::new(&map, options).unwrap();
    let table = ray_table(
        &engine,
        &TableOptions::isotropic(),
        Provenance::default(),
        &gonio_io::Progress::silent(),
    )
    .unwrap();
    for ti in [0.0f64, 30.0, 60.0, 80.0] {
        let albedo = table.albedo_with(dir(ti.to_radians(), 0.0), 2048, 720)[0];
        let r = ior.reflectance(ti.to_radians().cos());
        assert!((albedo / r - 1.0).abs() < 0.01, "{ti}°: {albedo} vs R {r}");
    }
}

/// Kirchhoff in its geometric-optics limit (g = (2 k Sq cos ti)² ≫ 1) agrees with the ray
/// method: the albedo of both tables at a few incidences within 5% (shadowing and masking in
/// both, Smith's statistical form in the Kirchhoff method and traced in the ray method, little
/// of either at 0° and 30° on these slopes of 0.1; Fresnel at the local angle in both). The maps are
/// small (a 64 µm spot, ten correlation lengths), so lobe shapes differ by speckle; the power
/// does not.
#[test]
fn kirchhoff_table_agrees_with_ray_table_for_a_rough_surface() {
    let map = gaussian(0.3e-6, 6e-6, 128, 7);
    let options = TableOptions {
        incidence_polar: 9,
        ..TableOptions::for_resolution(Resolution::isotropic(16, 9, 24))
    };
    let ray = RayEngine::new(&map, RayOptions::default()).unwrap();
    let ray_t = ray_table(
        &ray,
        &options,
        Provenance::default(),
        &gonio_io::Progress::silent(),
    )
    .unwrap();
    let kirchhoff = Kirchhoff::new(&map, KirchhoffOptions::new(Ior::Dielectric(1.55))).unwrap();
    let reports = std::sync::Arc::new(std::sync::Mutex::new(vec![]));
    let sink = reports.clone();
    let progress = gonio_io::Progress::new(move |r| sink.lock().unwrap().push((r.done, r.total)));
    let k_t = kirchhoff_table(
        &kirchhoff,
        &[633.0],
        &options,
        Provenance::default(),
        &progress,
    )
    .unwrap();
    // A report of no step when the work begins, then one per hemisphere map, its steps
    // weighted by the maps' expected costs: counting up to the total, which is the sum of those
    // costs (each map's deposit on the slices adds the same amount).
    let reports = reports.lock().unwrap().clone();
    assert_eq!(reports.len(), options.incidence_count() + 1);
    assert_eq!(reports[0].0, 0);
    let total = reports[0].1;
    assert!(reports.iter().all(|r| r.1 == total));
    assert!(reports.windows(2).all(|w| w[0].0 < w[1].0));
    assert_eq!(reports.last().unwrap().0, total);
    let costs: f64 = options
        .incidences()
        .iter()
        .map(|&wi| kirchhoff.hemisphere_cost(633e-9, wi).unwrap())
        .sum();
    assert!(costs > 0.0 && costs < total as f64, "{costs} vs {total}");
    for ti in [0.0f64, 30.0] {
        let (a, b) = (
            ray_t.albedo(ti.to_radians(), 0.0)[0],
            k_t.albedo(ti.to_radians(), 0.0)[0],
        );
        assert!((b / a - 1.0).abs() < 0.05, "{ti}°: ray {a}, kirchhoff {b}");
    }
}

/// The same table whatever the number of threads.
#[test]
fn tables_do_not_depend_on_the_thread_count() {
    let map = gaussian(0.3e-6, 6e-6, 96, 2);
    let engine = RayEngine::new(&map, RayOptions::default()).unwrap();
    let options = TableOptions::for_resolution(Resolution::isotropic(12, 10, 20));
    let run = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| {
                ray_table(
                    &engine,
                    &options,
                    Provenance::default(),
                    &gonio_io::Progress::silent(),
                )
                .unwrap()
                .values()
                .to_vec()
            })
    };
    let (one, two) = (run(1), run(2));
    assert!(
        one.iter()
            .zip(&two)
            .all(|(a, b)| a.to_bits() == b.to_bits())
    );
}

/// Bad options are refused with the reason.
#[test]
fn options_are_checked() {
    let mut o = TableOptions::isotropic();
    o.incidence_azimuths = 3;
    assert!(o.validate().is_ok());
    o.incidence_azimuths = 0;
    assert!(o.validate().unwrap_err().to_string().contains("isotropic"));
    let mut o = TableOptions::anisotropic();
    o.incidence_azimuths = 2;
    assert!(o.validate().is_err());
    o.incidence_azimuths = 8;
    assert!(o.validate().is_ok());
    o.incidence_polar = 1;
    assert!(o.validate().is_err());
}

/// Tests that take seconds each: `cargo test -- --skip slow::` leaves them out of a quick run.
mod slow {
    use super::*;

    /// An isotropic table of an anisotropic surface is the average over the azimuth of incidence:
    /// its albedo equals the azimuthal mean of the anisotropic table's albedo (24 azimuths, every
    /// 15°, on the same theta_d × phi_d grid) within 1%, the required bound, at 0°, 30° and 60°, and
    /// the azimuthal mean of the rays the engine reflects (the independent reference: the table's
    /// quadrature against the sum of the rays) within 1% too; each table's interpolation error at
    /// these angles is below 1% (`table_albedo_is_the_ray_reflectance`). The surface is a Gaussian
    /// map with its y spacing stretched four times (rms slope along y a quarter of that along x,
    /// Str below 0.3). A table of one azimuth of incidence (the former default) misses by more
    /// than 5%.
    #[test]
    fn isotropic_table_of_an_anisotropic_surface_averages_the_azimuths() {
        let base = gaussian(0.4e-6, 4e-6, 128, 23);
        // The unstretched map is isotropic: one turn is enough for it.
        assert_eq!(isotropic_turns(texture_aspect_ratio(&base)), 1);
        let map = HeightMap::new(base.heights().clone(), 0.5e-6, 2e-6).unwrap();
        let str_ratio = texture_aspect_ratio(&map);
        println!("Str {str_ratio:?}");
        assert!(str_ratio.is_some_and(|s| s < STR_ANISOTROPIC));
        let engine = RayEngine::new(&map, RayOptions::default()).unwrap();
        let iso = ray_table(
            &engine,
            &TableOptions {
                incidence_azimuths: isotropic_turns(str_ratio),
                ..TableOptions::isotropic()
            },
            Provenance::default(),
            &gonio_io::Progress::silent(),
        )
        .unwrap();
        let single = ray_table(
            &engine,
            &TableOptions {
                incidence_azimuths: 1,
                ..TableOptions::isotropic()
            },
            Provenance::default(),
            &gonio_io::Progress::silent(),
        )
        .unwrap();
        // The anisotropic table on the isotropic default's theta_d × phi_d grid (1° × 2°) and
        // incidences (every 2°), so that the two differ in the azimuth of incidence only (the
        // default anisotropic table, 2° × 4° from incidences every 3.9°, is 4.5% above its rays
        // at 60° on this map: the second-order error of its coarser steps).
        let aniso = ray_table(
            &engine,
            &TableOptions {
                resolution: Resolution::anisotropic(32, 90, 180, 24),
                incidence_polar: TableOptions::isotropic().incidence_polar,
                incidence_azimuths: 24,
            },
            Provenance::default(),
            &gonio_io::Progress::silent(),
        )
        .unwrap();
        let mut single_misses = 0.0f64;
        for ti in [0.0f64, 30.0, 60.0] {
            let t = ti.to_radians();
            let mean = (0..24)
                .map(|k| aniso.albedo(t, (15.0 * k as f64).to_radians())[0])
                .sum::<f64>()
                / 24.0;
            let (a, one) = (iso.albedo(t, 0.0)[0], single.albedo(t, 0.0)[0]);
            let azimuths: Vec<f64> = (0..24).map(|k| (15.0 * k as f64).to_radians()).collect();
            let truth = mean_reflectance(&engine, t, &azimuths);
            println!(
                "{ti}°: isotropic table {a:.5}, one azimuth {one:.5}, anisotropic mean {mean:.5}, rays {truth:.5}"
            );
            assert!(
                (a / truth - 1.0).abs() < 0.01,
                "{ti}°: {a} vs the rays' {truth}"
            );
            assert!((a / mean - 1.0).abs() < 0.01, "{ti}°: {a} vs {mean}");
            single_misses = single_misses.max((one / mean - 1.0).abs());
        }
        assert!(
            single_misses > 0.05,
            "the surface is not anisotropic enough to test the average ({single_misses})"
        );
    }

    /// Fitting Beckmann's Cook-Torrance model to the ray-method table of a Gaussian surface gives a
    /// roughness m within 5% of the map's total rms slope `sqrt(sx² + sy²)`: the ray method reproduces
    /// the facet model on Gaussian slopes (`docs/ray-method.md`, "Validation"), and that model has the
    /// Beckmann D of total rms slope m (per-axis `m/√2`).
    #[test]
    fn beckmann_fit_of_a_gaussian_surface_gives_its_rms_slope() {
        let (engine, table) = gaussian_table();
        let (sx, sy) = engine.rms_slopes();
        let slope = sx.hypot(sy);
        let samples = table.fit_samples(70f64.to_radians());
        let got = fit(FitKind::Beckmann, &samples, FitOptions::default()).unwrap();
        let m = got.parameter("m").unwrap().value;
        assert!(
            (m / slope - 1.0).abs() < 0.05,
            "fitted m {m}, rms slope {slope}; {got:?}"
        );
        let n = got.parameter("index").unwrap().value;
        assert!((n - 1.55).abs() < 0.05, "fitted index {n}");
    }
}
