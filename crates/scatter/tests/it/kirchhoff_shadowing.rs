//! Shadowing and masking in the Kirchhoff method (`docs/kirchhoff.md`, "Shadowing and masking";
//! issue 43, point 5): without them the integral lit and saw every point, and its albedo reached
//! 1.26 at 88° on the Sq 805 nm sample (512²). Held against the ray method, which traces shadowing and
//! masking over the same heights.
//!
//! The surface is that of the demo's Sq 805 nm sample (`gonio surface gen --sq-nm 805 --corr-um
//! 6 --dx-um 0.5`), cut to 256² or 512² points; 550 nm, index 1.55.
//!
//! Noise. The ray method's albedo is a sum over the map's facets, the Kirchhoff albedo a sum
//! over the spot's facets weighted by the window `W²`: two samples of one surface whose slopes
//! and heights vary from place to place. The spread of the ray albedo over the 16 blocks of a
//! 4 × 4 cut of the map (`s`, each block of area `a`) measures that variation: the ray albedo of
//! the whole map has the standard error `s/4`, and the window's, which weighs an effective area
//! `A = (Σ W²)² / Σ W⁴ · dx dy` (44% of the spot's disc), `s √(a/A)`.

use glam::DVec3;
use gonio_brdf::Ior;
use gonio_scatter::geometry::incidence_direction;
use gonio_scatter::kirchhoff::{Kirchhoff, KirchhoffOptions, Spot};
use gonio_scatter::ray::{RayEngine, RayOptions};
use gonio_surface::HeightMap;
use gonio_surface::normals::NormalMethod;
use gonio_surface::synth::GaussianSurface;

const WAVELENGTH: f64 = 550e-9;
const DX: f64 = 0.5e-6;

/// The demo's Sq 805 nm, T 6 µm sample, `n²` points at 0.5 µm.
fn sample(n: usize) -> HeightMap {
    GaussianSurface::square(0.805e-6, 6e-6, n, DX, 1)
        .generate()
        .unwrap()
}

fn kirchhoff(map: &HeightMap, options: KirchhoffOptions) -> Kirchhoff {
    Kirchhoff::new(map, options).unwrap()
}

/// The engine on `map` with shadowing and masking (the default) and without.
fn with_and_without_shadowing(map: &HeightMap) -> (Kirchhoff, Kirchhoff) {
    let without = KirchhoffOptions {
        shadowing: false,
        ..options()
    };
    (kirchhoff(map, options()), kirchhoff(map, without))
}

fn options() -> KirchhoffOptions {
    KirchhoffOptions::new(Ior::Dielectric(1.55))
}

/// Directional-hemispherical reflectance of the Kirchhoff method from `ti` degrees.
fn albedo(engine: &Kirchhoff, ti: f64) -> f64 {
    let wi = incidence_direction(ti.to_radians());
    engine
        .scattered(WAVELENGTH, wi)
        .unwrap()
        .iter()
        .map(|(_, share)| share)
        .sum()
}

/// The ray method's albedo from `ti` degrees (spline normals, as the Kirchhoff facets have;
/// shadowing and masking on, one bounce) and the standard errors of the albedo of the whole map
/// and of the Kirchhoff window on `spot` (see the module's documentation).
struct RayAlbedo {
    albedo: f64,
    sem_map: f64,
    sem_window: f64,
}

fn ray_albedo(map: &HeightMap, spot: Spot, ti: f64) -> RayAlbedo {
    let ray = RayEngine::new(
        map,
        RayOptions {
            normals: NormalMethod::Spline,
            ..RayOptions::default()
        },
    )
    .unwrap();
    let wi = incidence_direction(ti.to_radians());
    const B: usize = 4;
    let extent = (map.nx() - 1) as f64 * map.dx();
    let block = |p: DVec3| {
        let (i, j) = (p.x / extent * B as f64, p.y / extent * B as f64);
        (j as usize).min(B - 1) * B + (i as usize).min(B - 1)
    };
    let parts = ray
        .fold_rays(
            wi,
            || [0.0f64; B * B],
            |acc, rays| {
                for r in rays {
                    acc[block(ray.facet_position(r.facet))] += r.share;
                }
            },
        )
        .unwrap();
    let mut blocks = [0.0f64; B * B];
    for p in &parts {
        for (b, v) in blocks.iter_mut().zip(p) {
            *b += v;
        }
    }
    let albedo: f64 = blocks.iter().sum();
    // Each block's own albedo: its facets are a sixteenth of the map's.
    let own: Vec<f64> = blocks.iter().map(|b| b * (B * B) as f64).collect();
    let s = (own.iter().map(|b| (b - albedo).powi(2)).sum::<f64>() / (B * B - 1) as f64).sqrt();
    // The window's effective area, from its weights at the map's points.
    let radius = 0.5 * spot.diameter;
    let (mut w2, mut w4) = (0.0, 0.0);
    for iy in 0..map.ny() {
        for ix in 0..map.nx() {
            let (x, y) = (
                ix as f64 * map.dx() - spot.center.0,
                iy as f64 * map.dy() - spot.center.1,
            );
            let t2 = (x * x + y * y) / (radius * radius);
            if t2 < 1.0 {
                let w = (-1.0 / (1.0 - t2)).exp();
                w2 += w * w;
                w4 += w.powi(4);
            }
        }
    }
    let window_area = w2 * w2 / w4 * map.dx() * map.dy();
    let block_area = (extent / B as f64).powi(2);
    RayAlbedo {
        albedo,
        sem_map: s / B as f64,
        sem_window: s * (block_area / window_area).sqrt(),
    }
}

/// No surface reflects more light than falls on it: the albedo stays at most 1 at every
/// incidence up to 89° (measured 0.13 / 0.21 / 0.29 / 0.40 / 0.39 at 70 / 80 / 85 / 88 / 89°).
/// Without shadowing and masking it was 0.25 at 80°, 0.44 at 85°, 1.21 at 88° and 2.05 at 89°:
/// the facets facing the source present `1 + Λ(wi)` times the footprint to it (`Λ` = 1.6 at
/// 88° for this map's rms slope of 0.27). The old method is kept behind the option, and checked
/// to break the bound, so this test would catch the option doing nothing.
#[test]
fn albedo_stays_below_one_to_grazing() {
    let map = sample(256);
    let (with, without) = with_and_without_shadowing(&map);
    for ti in [70.0, 80.0, 85.0, 88.0, 89.0] {
        let a = albedo(&with, ti);
        eprintln!("{ti}°: albedo {a:.4}");
        assert!(a > 0.0 && a <= 1.0, "{ti}°: albedo {a}");
    }
    let old = albedo(&without, 88.0);
    assert!(old > 1.0, "without shadowing the albedo at 88° was {old}");
}

mod slow {
    use super::*;

    /// In the geometric limit (the stationary-phase limit everywhere; `g → ∞`), the Kirchhoff
    /// albedo equals the ray method's at 70–88° within three standard errors of the two
    /// samples of the surface (module documentation), on a 512² map. Measured: 0.1287 / 0.2067
    /// / 0.2721 / 0.3246 against 0.1291 / 0.2063 / 0.2714 / 0.3449 at 70 / 80 / 85 / 88°
    /// (combined standard errors 0.003 / 0.007 / 0.011 / 0.029); without shadowing the method
    /// gave 0.145 / 0.27 / 0.47 / 1.26. With the default split (the integral where `g ≤ 25`)
    /// it agrees as well at 70–80° (0.1284, 0.1623, 0.2088); at 85° and 88° it is 11% and 17%
    /// above (0.3006, 0.4043), the coherent reflection of the grazing specular direction, where
    /// `g = (2 k σ cos ti)²` is 2.5 and 0.4 (`e^(-g)` = 8% and 66% of a mirror's), which geometric
    /// optics does not have.
    #[test]
    fn geometric_limit_albedo_matches_the_ray_method() {
        let map = sample(512);
        let limit = kirchhoff(
            &map,
            KirchhoffOptions {
                geometric_above: 1e-9,
                ..options()
            },
        );
        let full = kirchhoff(&map, options());
        for ti in [70.0, 75.0, 80.0, 85.0, 88.0] {
            let ray = ray_albedo(&map, limit.spot(), ti);
            let sigma = ray.sem_map.hypot(ray.sem_window);
            let mut engines = vec![("limit", &limit)];
            if ti <= 80.0 {
                engines.push(("default", &full));
            }
            for (name, engine) in engines {
                let a = albedo(engine, ti);
                eprintln!(
                    "{ti}°: kirchhoff ({name}) {a:.4}, ray {:.4} ± {sigma:.4}",
                    ray.albedo
                );
                assert!(
                    (a - ray.albedo).abs() < 3.0 * sigma,
                    "{ti}°: kirchhoff ({name}) {a}, ray {} ± {sigma}",
                    ray.albedo
                );
            }
        }
    }

    /// Below 60° shadowing and masking change little: they act on the light that leaves toward
    /// grazing directions, and little goes there. Up to 40° the albedo moves by less than three
    /// standard errors of the window (module documentation); measured on the 256² map: 0.0467
    /// → 0.0467 at 0°, 0.0476 → 0.0475 at 20°, 0.0556 → 0.0548 at 40° (2.2 standard errors).
    /// At 50° and 55° the lobe's flank reaches the grazing directions and the masking is real:
    /// 0.0684 → 0.0662 (3.2 standard errors) and 0.0800 → 0.0757 at 55°, where the ray method,
    /// which traces it, reads 0.0671 and 0.0763; there the new albedo is closer to the ray
    /// method's than the old one was.
    #[test]
    fn below_sixty_degrees_nothing_changes_beyond_the_noise() {
        let map = sample(256);
        let (with, without) = with_and_without_shadowing(&map);
        for ti in [0.0, 20.0, 40.0, 50.0, 55.0] {
            let ray = ray_albedo(&map, with.spot(), ti);
            let (new, old) = (albedo(&with, ti), albedo(&without, ti));
            eprintln!(
                "{ti}°: {old:.4} -> {new:.4} (ray {:.4}, window's standard error {:.4})",
                ray.albedo, ray.sem_window
            );
            if ti <= 40.0 {
                assert!(
                    (new - old).abs() < 3.0 * ray.sem_window,
                    "{ti}°: {old} -> {new}, noise {}",
                    ray.sem_window
                );
            } else {
                assert!(
                    (new - ray.albedo).abs() < (old - ray.albedo).abs(),
                    "{ti}°: {old} -> {new}, ray {}",
                    ray.albedo
                );
            }
        }
    }
}
