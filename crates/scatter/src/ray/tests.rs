//! Tests of the ray engine against exact results: a flat and a tilted plane (closed forms, for
//! the reflected and the transmitted light), the plain O(N·D) loop (the index must find the
//! same hits), energy conservation over a hemisphere grid and in the energy budget, and
//! independence from the thread count.

use super::*;
use crate::geometry::spherical_direction;
use gonio_brdf::fresnel::dielectric;
use gonio_surface::synth::GaussianSurface;

const DX: f64 = 0.5e-6;

fn plane_map(n: usize, slope_x: f64) -> HeightMap {
    let h = Array2::from_shape_fn((n, n), |(_, ix)| slope_x * ix as f64 * DX);
    HeightMap::new(h, DX, DX).unwrap()
}

fn gaussian(n: usize, sq: f64, t: f64, seed: u64) -> HeightMap {
    GaussianSurface::square(sq, t, n, DX, seed)
        .generate()
        .unwrap()
}

/// A perfectly smooth surface gives `rho = R(ti)` in every detector whose cone holds the mirror
/// direction, whatever the aperture, and nothing anywhere else (`docs/ray-method.md`,
/// "Normalisation": all the reflected power goes into one direction). (Apertures are kept
/// off whole degrees so that no detector has the mirror direction exactly on its rim.)
#[test]
fn flat_map_reflects_fresnel_into_specular_only() {
    let map = plane_map(48, 0.0);
    let n = 1.55;
    let scatter: Vec<f64> = (-89..=89).map(|d| f64::from(d).to_radians()).collect();
    for shadowing in [true, false] {
        let options = RayOptions {
            shadowing,
            ..RayOptions::default()
        };
        let engine = RayEngine::new(&map, options).unwrap();
        assert_eq!(engine.facet_count(), 46 * 46);
        for aperture_deg in [0.2, 1.4, 4.5] {
            let alpha = f64::to_radians(aperture_deg);
            for ti_deg in [0.0, 20.0, 45.0, 60.0, 70.0, 85.0] {
                let ti: f64 = f64::to_radians(ti_deg);
                let mirror = inplane_direction(ti);
                let r = dielectric(ti.cos(), n);
                let curve = engine.inplane(ti, &scatter, alpha).unwrap();
                for p in &curve.points {
                    let d = inplane_direction(p.scatter_deg.to_radians());
                    if mirror.dot(d) > alpha.cos() {
                        assert!((p.reflectance - r).abs() < 1e-12 * r, "{ti_deg}° {p:?}");
                        let brdf = r / (cone_solid_angle(alpha) * d.z);
                        assert!((p.brdf_per_sr - brdf).abs() < 1e-9 * brdf);
                    } else {
                        assert_eq!(
                            p.reflectance, 0.0,
                            "{ti_deg}°, aperture {aperture_deg}°: {p:?}"
                        );
                    }
                }
            }
        }
    }
}

use crate::geometry::cone_solid_angle;

/// A tilted plane `h = p x` (normal tilted toward the source) taken as it is
/// (`from_normals`; `new` would level it): every facet intercepts `wi·n / n_z = cos ti + p sin ti`
/// per unit mean-plane area, so the detector on its mirror direction reads
/// `R(wi·n) (1 + p tan ti)`.
#[test]
fn tilted_plane_weights_by_intercepted_area() {
    let p = 0.1;
    let map = plane_map(40, p);
    let n = DVec3::new(-p, 0.0, 1.0).normalize();
    for shadowing in [true, false] {
        let options = RayOptions {
            shadowing,
            polarised: true,
            ..RayOptions::default()
        };
        let normals = facet_normals(&map, options.normals);
        let engine = RayEngine::from_normals(&map, normals, options).unwrap();
        for ti_deg in [10.0f64, 30.0, 50.0] {
            let wi = incidence_direction(ti_deg.to_radians());
            let c = wi.dot(n);
            let wr = 2.0 * c * n - wi;
            let det = Detector {
                direction: wr,
                half_angle: 0.5f64.to_radians(),
            };
            let reading = engine.detect(wi, &[det]).unwrap()[0];
            let expect = dielectric(c, 1.55) * (1.0 + p * ti_deg.to_radians().tan());
            assert!(
                (reading.reflectance - expect).abs() < 1e-12,
                "{ti_deg}°: {reading:?}"
            );
            let sp = reading.polarised.unwrap();
            assert!((0.5 * (sp.s + sp.p) - expect).abs() < 1e-12);
            assert_eq!(reading.hits, 38 * 38);
        }
    }
}

/// `new` takes angles from the map's mean plane: a tilted plane reflects as a flat one.
#[test]
fn new_levels_the_map() {
    let engine = RayEngine::new(&plane_map(40, 0.1), RayOptions::default()).unwrap();
    let flat = RayEngine::new(&plane_map(40, 0.0), RayOptions::default()).unwrap();
    let wi = incidence_direction(30f64.to_radians());
    let det = Detector {
        direction: DVec3::new(-wi.x, -wi.y, wi.z),
        half_angle: 0.5f64.to_radians(),
    };
    let (a, b) = (
        engine.detect(wi, &[det]).unwrap()[0],
        flat.detect(wi, &[det]).unwrap()[0],
    );
    assert!((a.reflectance - b.reflectance).abs() < 1e-12, "{a:?} {b:?}");
    assert_eq!(a.hits, b.hits);
}

/// The direction index finds exactly the hits of a plain loop over every ray, for detectors
/// anywhere on the hemisphere (pole, horizon, both sides) and of any aperture.
#[test]
fn index_agrees_with_plain_loop() {
    let map = gaussian(256, 0.3e-6, 2.0e-6, 7);
    let engine = RayEngine::new(&map, RayOptions::default()).unwrap();
    let wi = incidence_direction(40f64.to_radians());
    let rays = engine.rays(wi, 0, None);
    let mut detectors = Vec::new();
    for (k, alpha_deg) in [0.2, 1.4, 4.0, 12.0].into_iter().enumerate() {
        for i in 0..18 {
            for j in 0..24 {
                let theta = (i as f64 * 5.0 + k as f64).to_radians();
                let phi = (j as f64 * 15.0 + 2.0 * k as f64).to_radians();
                detectors.push(Detector {
                    direction: spherical_direction(theta, phi),
                    half_angle: f64::to_radians(alpha_deg),
                });
            }
        }
    }
    let readings = engine.detect(wi, &detectors).unwrap();
    let mut hit_any = 0;
    for (det, reading) in detectors.iter().zip(&readings) {
        let plain = index::collect_exhaustive(&rays, det);
        assert_eq!(reading.hits, plain.hits, "{det:?}");
        assert!(
            (reading.reflectance - plain.w).abs() <= 1e-12 * plain.w,
            "{det:?}"
        );
        hit_any += (plain.hits > 0) as usize;
    }
    assert!(
        hit_any > detectors.len() / 4,
        "only {hit_any} detectors saw light"
    );
}

/// With shadowing off, every ray leaves upward, so a hemisphere grid collects
/// `Σ R(wi·n) (wi·n)/(n_z N cos ti)`. For slopes with zero mean the intercepted-area factor
/// `(wi·n)/(n_z cos ti) = 1 + p tan ti` averages to one, so the total equals the mean facet
/// Fresnel reflectance (to the small correlation of R with the slope).
#[test]
fn hemisphere_conserves_energy() {
    let map = gaussian(512, 0.05e-6, 6.0e-6, 3);
    let options = RayOptions {
        shadowing: false,
        ..RayOptions::default()
    };
    let engine = RayEngine::new(&map, options).unwrap();
    let grid = HemisphereGrid::with_step_deg(2.0).unwrap();
    for ti_deg in [0.0f64, 30.0, 60.0, 80.0] {
        let wi = incidence_direction(ti_deg.to_radians());
        let table = engine.detect_hemisphere(wi, &grid).unwrap();
        let total = table.total_reflectance();
        let mean_r = engine.mean_facet_reflectance(wi).unwrap();
        assert!(
            (total / mean_r - 1.0).abs() < 0.01,
            "{ti_deg}°: {total} vs {mean_r}"
        );
    }
}

/// The same numbers, bit for bit, on 1 and 2 threads: cone detectors with shadowing, masking, a
/// second bounce and azimuthal averaging, a hemisphere grid, the transmitted light on a
/// hemisphere grid and the energy budget.
#[test]
fn identical_for_one_and_two_threads() {
    let map = gaussian(192, 0.5e-6, 2.0e-6, 11);
    let options = RayOptions {
        second_bounce: true,
        azimuths: 3,
        polarised: true,
        ..RayOptions::default()
    };
    let wi = incidence_direction(60f64.to_radians());
    let detectors: Vec<Detector> = (-80..=80)
        .map(|d| Detector {
            direction: inplane_direction(f64::from(d).to_radians()),
            half_angle: 2f64.to_radians(),
        })
        .collect();
    let grid = HemisphereGrid::with_step_deg(3.0).unwrap();
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let engine = RayEngine::new(&map, options).unwrap();
            (
                engine.detect(wi, &detectors).unwrap(),
                engine.detect_hemisphere(wi, &grid).unwrap(),
                engine.transmit_hemisphere(wi, &grid).unwrap(),
                engine.energy_budget(wi).unwrap(),
            )
        })
    };
    let (one, two) = (run(1), run(2));
    assert_eq!(one, two);
    assert!(one.0.iter().any(|r| r.hits > 0));
}

/// A smooth dielectric transmits `1 - R(ti)` (Fresnel, Born & Wolf §1.5.2) into the one cell
/// holding Snell's direction, `sin θt = sin ti / n` forward (azimuth 0), and nothing elsewhere;
/// its budget is `R + T = 1`: every facet intercepts `cos ti / cos ti = 1` of its share. (The
/// refraction angles, 0, 13.18, 28.13, 35.26 and 41.65°, lie off the 1° cell boundaries but
/// for 0°, which the first ring holds.)
#[test]
fn flat_map_transmits_fresnel_into_snell_direction() {
    let map = plane_map(48, 0.0);
    let n = 1.5;
    let grid = HemisphereGrid::with_step_deg(1.0).unwrap();
    for shadowing in [true, false] {
        let options = RayOptions {
            ior: Ior::Dielectric(n),
            shadowing,
            polarised: true,
            ..RayOptions::default()
        };
        let engine = RayEngine::new(&map, options).unwrap();
        for ti_deg in [0.0f64, 20.0, 45.0, 60.0, 85.0] {
            let ti = ti_deg.to_radians();
            let wi = incidence_direction(ti);
            let r = dielectric(ti.cos(), n);
            let table = engine.transmit_hemisphere(wi, &grid).unwrap();
            let theta_t = (ti.sin() / n).asin();
            let cell = grid.cell(DVec3::new(theta_t.sin(), 0.0, theta_t.cos()));
            for (k, &t) in table.transmittance.iter().enumerate() {
                if k == cell {
                    assert!(
                        (t - (1.0 - r)).abs() < 1e-12,
                        "{ti_deg}°: {t} vs {}",
                        1.0 - r
                    );
                    assert_eq!(table.hits[k], 46 * 46);
                } else {
                    assert_eq!(t, 0.0, "{ti_deg}°: cell {k}");
                }
            }
            let (ts, tp) = table.transmittance_sp.as_ref().unwrap();
            let sp = gonio_brdf::fresnel::polarised(ti.cos(), n.into());
            assert!((ts[cell] - (1.0 - sp.s)).abs() < 1e-12);
            assert!((tp[cell] - (1.0 - sp.p)).abs() < 1e-12);
            let budget = engine.energy_budget(wi).unwrap();
            assert!((budget.intercepted - 1.0).abs() < 1e-12, "{budget:?}");
            assert!((budget.reflected - r).abs() < 1e-12, "{budget:?}");
            assert!((budget.transmitted - (1.0 - r)).abs() < 1e-12, "{budget:?}");
            // Each lost part is a sum of 46² differences `R p - R p` of zero, to rounding.
            for lost in [
                budget.shadowed,
                budget.reflected_lost,
                budget.transmitted_lost,
            ] {
                assert!(lost.abs() < 1e-14, "{budget:?}");
            }
        }
    }
}

/// A tilted plane `h = p x` taken as it is transmits `(1 - R(wi·n)) (1 + p tan ti)` (the
/// intercepted area of `tilted_plane_weights_by_intercepted_area`) along Snell's law about its
/// normal, `wt = (η c - √(1 - η²(1 - c²))) n - η wi` with `η = 1/n`, `c = wi·n`: the refracted
/// ray makes `sin θ = sin(ι)/n` with `-n`, in the plane of `wi` and `n`.
#[test]
fn tilted_plane_transmits_along_snell() {
    let p = 0.1;
    let map = plane_map(40, p);
    let normal = DVec3::new(-p, 0.0, 1.0).normalize();
    let n = 1.5;
    let grid = HemisphereGrid::with_step_deg(0.5).unwrap();
    let options = RayOptions {
        ior: Ior::Dielectric(n),
        ..RayOptions::default()
    };
    let normals = facet_normals(&map, options.normals);
    let engine = RayEngine::from_normals(&map, normals, options).unwrap();
    for ti_deg in [10.0f64, 30.0, 50.0] {
        let wi = incidence_direction(ti_deg.to_radians());
        let c = wi.dot(normal);
        let table = engine.transmit_hemisphere(wi, &grid).unwrap();
        let expect = (1.0 - dielectric(c, n)) * (1.0 + p * ti_deg.to_radians().tan());
        assert!(
            (table.total_transmittance() - expect).abs() < 1e-12,
            "{ti_deg}°: {} vs {expect}",
            table.total_transmittance()
        );
        // Snell's law checked on its own terms: angle to -n, and coplanarity.
        let sin_t = (1.0 - c * c).sqrt() / n;
        let wt = (-normal * (1.0 - sin_t * sin_t).sqrt() + (wi - c * normal).normalize() * -sin_t)
            .normalize();
        let cell = grid.cell(DVec3::new(wt.x, wt.y, -wt.z));
        assert_eq!(table.hits[cell], 38 * 38, "{ti_deg}°");
        assert!((table.transmittance[cell] - expect).abs() < 1e-12);
    }
}

/// The energy budget splits the intercepted power without remainder and its reflected and
/// transmitted parts are the totals of the hemisphere tables (summed in another order, so to
/// rounding), with and without shadowing, on a rough surface that shadows and masks (rms slope
/// 1, so that refracted rays, steeper than 48° below the horizon, meet the surface again).
#[test]
fn budget_matches_tables() {
    let map = gaussian(192, 1.0e-6, 2.0e-6, 5);
    let grid = HemisphereGrid::with_step_deg(3.0).unwrap();
    for shadowing in [true, false] {
        let options = RayOptions {
            ior: Ior::Dielectric(1.5),
            shadowing,
            ..RayOptions::default()
        };
        let engine = RayEngine::new(&map, options).unwrap();
        for ti_deg in [0.0f64, 40.0, 70.0] {
            let wi = incidence_direction(ti_deg.to_radians());
            let b = engine.energy_budget(wi).unwrap();
            let parts =
                b.shadowed + b.reflected + b.reflected_lost + b.transmitted + b.transmitted_lost;
            assert!((parts - b.intercepted).abs() < 1e-12, "{b:?}");
            let r = engine.detect_hemisphere(wi, &grid).unwrap();
            let t = engine.transmit_hemisphere(wi, &grid).unwrap();
            assert!((r.total_reflectance() - b.reflected).abs() < 1e-12, "{b:?}");
            assert!(
                (t.total_transmittance() - b.transmitted).abs() < 1e-12,
                "{b:?}"
            );
            // The surface (rms slope 2 Sq/T = 1) shadows, and masks refracted rays, at 70°
            // (measured: 35% of the incident power shadowed, 8% refracted and masked).
            if shadowing && ti_deg == 70.0 {
                assert!(b.shadowed > 0.0 && b.transmitted_lost > 0.0, "{b:?}");
            }
        }
    }
}

/// Bad inputs are errors, not panics.
#[test]
fn rejects_bad_input() {
    let map = plane_map(8, 0.0);
    let bad = RayOptions {
        azimuths: 0,
        ..RayOptions::default()
    };
    assert!(RayEngine::new(&map, bad).is_err());
    let bounce_without_masking = RayOptions {
        shadowing: false,
        second_bounce: true,
        ..RayOptions::default()
    };
    assert!(RayEngine::new(&map, bounce_without_masking).is_err());
    assert!(RayEngine::new(&plane_map(2, 0.0), RayOptions::default()).is_err());
    let engine = RayEngine::new(&map, RayOptions::default()).unwrap();
    let down = DVec3::new(0.0, 0.0, -1.0);
    assert!(engine.detect(down, &[]).is_err());
    let det = Detector {
        direction: DVec3::Z,
        half_angle: 0.0,
    };
    assert!(engine.detect(DVec3::Z, &[det]).is_err());
    assert!(engine.inplane(95f64.to_radians(), &[0.0], 0.01).is_err());
    let grid = HemisphereGrid::with_step_deg(5.0).unwrap();
    let metal = RayOptions {
        ior: Ior::Conductor(num_complex::Complex64::new(0.2, 3.0)),
        ..RayOptions::default()
    };
    let metal = RayEngine::new(&map, metal).unwrap();
    assert!(metal.transmit_hemisphere(DVec3::Z, &grid).is_err());
    assert!(metal.energy_budget(DVec3::Z).is_err());
    for n in [0.0, -1.5, f64::NAN] {
        let bad = RayOptions {
            ior: Ior::Dielectric(n),
            ..RayOptions::default()
        };
        let bad = RayEngine::new(&map, bad).unwrap();
        assert!(bad.transmit_hemisphere(DVec3::Z, &grid).is_err());
    }
    assert!(engine.transmit_hemisphere(down, &grid).is_err());
}
