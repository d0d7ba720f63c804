//! The ray method's transmission against the microfacet BTDF of B. Walter, S. R. Marschner,
//! H. Li & K. E. Torrance, "Microfacet models for refraction through rough surfaces", EGSR 2007,
//! eq. 21, on Gaussian random surfaces (T 6 µm, 1024 × 1024 points at 0.5 µm; Sq 0.3 and
//! 0.9 µm, nominal per-axis rms slopes 0.07 and 0.21), index 1.5, incidence 0, 30 and 60°, on a
//! hemisphere grid of 1° × 2° cells below the surface; and the energy budget: reflected plus
//! transmitted plus shadowed and masked power is the power the facets intercept, which is
//! exactly 1 at normal incidence (results in `docs/ray-method.md`, "Transmission").
//!
//! As for the reflection (`ray_model`), a single realisation is not the ensemble: the model
//! takes each map's own measured per-axis rms slopes (anisotropic Beckmann `D`, Smith `G1` of
//! Walter eq. 23 for each direction) and is averaged over the same azimuths of incidence as the
//! ray method and over each cell (Gauss-Legendre in `sin²θ` and `φ`), so that it is what the
//! cell should read. Both sides are power-based: the table's cell holds the fraction of the
//! incident power refracted into it, which is `∫ f_t |cos θt| dω_t` over the cell with Walter's
//! `f_t` as written (its `η_o²` is the solid-angle compression of refraction; see
//! `TransmissionTable`).

use glam::DVec3;
use gonio_brdf::Ior;
use gonio_brdf::fresnel::dielectric;
use gonio_brdf::microfacet::{Distribution, Microfacet};
use gonio_brdf::quadrature::gauss_legendre_on;
use gonio_scatter::geometry::incidence_direction;
use gonio_scatter::ray::{HemisphereGrid, RayEngine, RayOptions};
use gonio_surface::synth::GaussianSurface;
use rayon::prelude::*;
use std::f64::consts::PI;

/// Relative index of the dielectric.
const N: f64 = 1.5;
const AZIMUTHS: usize = 8;
const INCIDENCE_DEG: [f64; 3] = [0.0, 30.0, 60.0];

fn mirror(v: DVec3) -> DVec3 {
    DVec3::new(v.x, v.y, -v.z)
}

fn rotate_z(v: DVec3, phi: f64) -> DVec3 {
    let (s, c) = phi.sin_cos();
    DVec3::new(c * v.x - s * v.y, s * v.x + c * v.y, v.z)
}

/// Walter et al. 2007, eq. 21, from air (`η_i = 1`, `wi` toward the source) into the material
/// (`η_o = n`, `wt` pointing down into it): with `h_t = -(wi + n wt)/|wi + n wt|` (eq. 16),
/// `f_t = |wi·h||wt·h| / (|wi·n||wt·n|) · n² (1 - F(wi·h)) G D(h) / ((wi·h) + n (wt·h))²`, zero
/// unless `wi·h > 0 > wt·h` (the χ⁺ of eq. 23), and `G = G1(wi) G1(wt)` (eq. 23, `G1` of a
/// direction below the surface taken for its mirror image above).
fn walter_btdf(wi: DVec3, wt: DVec3, mf: &Microfacet, n: f64) -> f64 {
    let h = -(wi + n * wt);
    if h.z <= 0.0 {
        return 0.0;
    }
    let h = h.normalize();
    let (ih, oh) = (wi.dot(h), wt.dot(h));
    if ih <= 0.0 || oh >= 0.0 {
        return 0.0;
    }
    let g = mf.g1(wi) * mf.g1(mirror(wt));
    let denom = ih + n * oh;
    ih * -oh / (wi.z * -wt.z) * n * n * (1.0 - dielectric(ih, n)) * g * mf.d(h) / (denom * denom)
}

/// The model's transmittance into each cell of the mirrored `grid`: `∫ f_t |cos θt| dω_t` over
/// the cell, averaged over the azimuths of incidence (source and cells turned together, as the
/// ray method turns them). With `u = sin²θ`, `|cos θ| sin θ dθ dφ = du dφ / 2`, integrated by a
/// 4 × 4 Gauss-Legendre rule per cell (the lobe varies over tens of cells, so the rule is exact
/// to far below the counting noise).
fn model_cells(wi: DVec3, grid: &HemisphereGrid, mf: &Microfacet) -> Vec<f64> {
    let (dt, dp) = (0.5 * PI / grid.n_theta as f64, 2.0 * PI / grid.n_phi as f64);
    (0..grid.len())
        .into_par_iter()
        .map(|k| {
            let (i, j) = (k / grid.n_phi, k % grid.n_phi);
            let (u0, u1) = (
                (i as f64 * dt).sin().powi(2),
                ((i + 1) as f64 * dt).sin().powi(2),
            );
            let mut sum = 0.0;
            for (u, wu) in gauss_legendre_on(4, u0, u1) {
                for (phi, wp) in gauss_legendre_on(4, j as f64 * dp, (j + 1) as f64 * dp) {
                    let s = u.sqrt();
                    let wt = DVec3::new(s * phi.cos(), s * phi.sin(), -(1.0 - u).sqrt());
                    let f: f64 = (0..AZIMUTHS)
                        .map(|a| {
                            let r = 2.0 * PI * a as f64 / AZIMUTHS as f64;
                            walter_btdf(rotate_z(wi, r), rotate_z(wt, r), mf, N)
                        })
                        .sum();
                    sum += 0.5 * wu * wp * f / AZIMUTHS as f64;
                }
            }
            sum
        })
        .collect()
}

/// `Σ max(wi·n, 0) / (n_z N cos ti)` over the engine's facets, computed here from their normals:
/// the power the facets facing the source intercept (exactly 1 at normal incidence, where
/// every term is `n_z / n_z`).
fn intercepted(engine: &RayEngine, wi: DVec3) -> f64 {
    let n = engine.facet_count();
    (0..n)
        .map(|i| {
            let m = engine.facet_normal(i);
            wi.dot(m).max(0.0) / m.z
        })
        .sum::<f64>()
        / (n as f64 * wi.z)
}

/// Energy conservation: every facet splits its intercepted share into `R` reflected and `1 - R`
/// transmitted, so the reflected and transmitted tables plus what the budget says was shadowed
/// or masked (or, without shadowing, dropped below the horizon) add up to the intercepted power
/// computed independently from the normals; at normal incidence without shadowing nothing is
/// lost (reflected rays rise for facets tilted under 45°, refracted ones always descend) and
/// `R + T = 1`.
///
/// Tolerance: the sides are sums of the same ~N = 254² shares in different orders; rounding
/// errors of ~N terms of size ~1/N add like a random walk, `√N ε ≈ 3e-14`; 1e-12 leaves a factor
/// of 30 (the worst case `N ε = 7e-12` needs every rounding to go the same way).
#[test]
fn reflection_and_transmission_conserve_energy() {
    let map = GaussianSurface::square(0.6e-6, 6e-6, 256, 0.5e-6, 4)
        .generate()
        .unwrap();
    let grid = HemisphereGrid::new(90, 180).unwrap();
    for shadowing in [false, true] {
        let options = RayOptions {
            ior: Ior::Dielectric(N),
            shadowing,
            ..RayOptions::default()
        };
        let engine = RayEngine::new(&map, options).unwrap();
        for ti_deg in INCIDENCE_DEG {
            let wi = incidence_direction(ti_deg.to_radians());
            let r = engine
                .detect_hemisphere(wi, &grid)
                .unwrap()
                .total_reflectance();
            let t = engine
                .transmit_hemisphere(wi, &grid)
                .unwrap()
                .total_transmittance();
            let b = engine.energy_budget(wi).unwrap();
            let lost = b.shadowed + b.reflected_lost + b.transmitted_lost;
            let i = intercepted(&engine, wi);
            eprintln!(
                "shadowing {shadowing}, {ti_deg}°: R {r:.6} T {t:.6} lost {lost:.3e} \
                 intercepted - 1 {:.3e}, residual {:.1e}",
                i - 1.0,
                r + t + lost - i
            );
            assert!(
                (r + t + lost - i).abs() < 1e-12,
                "{ti_deg}°, shadowing {shadowing}: R {r} + T {t} + lost {lost} - {i}"
            );
            if ti_deg == 0.0 {
                assert!((i - 1.0).abs() < 1e-12, "{i}");
                if !shadowing {
                    assert_eq!(lost, 0.0);
                    assert!((r + t - 1.0).abs() < 1e-12, "R {r} + T {t}");
                }
            }
        }
    }
}

/// Tests that take seconds each: `cargo test -- --skip slow::` leaves them out of a quick run.
mod slow {
    use super::*;

    /// Per cell where Walter's BTDF exceeds 3% of its peak, the ray method's transmittance `T`
    /// and the model's `M` differ by `e = T/M - 1`. The cell's rays come from at least
    /// `n = hits/K` distinct facets (each facet is traced once per azimuth, K = 8), so its
    /// counting error is `σ = √(κ/n)`, with `κ` the facets one correlation area puts into one
    /// cell (more than 1 where neighbouring facets share a normal; less where the K turned
    /// copies of a facet fall in different cells and so count partly independently). With
    /// `z = e/√(K/hits)`, measured mean `z²` (that is `κ`) is 0.24–1.20 over the six cases,
    /// and the largest `|z|` 4.5 among ~4000 cells. Asserted: mean `z²` below 2 (a systematic
    /// 2% error in the peak cells, about 50 000 hits, would alone give 2.5), and every `|z|`
    /// below 6, six standard deviations for `κ = 1` (4.9 for `κ = 1.5`: over 4000 cells of a
    /// normal `z`, a false alarm once in ~10⁴ runs).
    ///
    /// Totals: the model and the map have the same zeroth, first (mean slope 0, levelled map)
    /// and second (the map's rms slopes) slope moments, so the transmittances differ through the
    /// third and fourth moments of one realisation (about 7000 correlation areas: standard
    /// errors `0.05 σ³` and `0.12 σ⁴` for a Gaussian, `σ ≤ 0.21` per axis) times derivatives of
    /// order one of the share `(1 - R)(1 + p tan ti)`, about 1e-4; and through shadowing, which
    /// Smith's `G1` only approximates (30% of `1 - G1(wi)`). Bound: `5e-4 + 0.3 (1 - G1(wi))`;
    /// measured at most 1.3e-5.
    #[test]
    fn gaussian_surfaces_match_walter_btdf() {
        let grid = HemisphereGrid::new(90, 180).unwrap();
        for (sq, seed) in [(0.3e-6, 1u64), (0.9e-6, 2)] {
            let map = GaussianSurface::square(sq, 6e-6, 1024, 0.5e-6, seed)
                .generate()
                .unwrap();
            let options = RayOptions {
                ior: Ior::Dielectric(N),
                azimuths: AZIMUTHS,
                ..RayOptions::default()
            };
            let engine = RayEngine::new(&map, options).unwrap();
            let (sx, sy) = engine.rms_slopes();
            // Beckmann α along an axis is √2 × the rms slope along it.
            let mf = Microfacet {
                distribution: Distribution::Beckmann,
                alpha_x: 2f64.sqrt() * sx,
                alpha_y: 2f64.sqrt() * sy,
            };
            for ti_deg in INCIDENCE_DEG {
                let wi = incidence_direction(ti_deg.to_radians());
                let table = engine.transmit_hemisphere(wi, &grid).unwrap();
                let model = model_cells(wi, &grid, &mf);
                let btdf = |k: usize| model[k] / grid.projected_solid_angle(k / grid.n_phi);
                let peak = (0..grid.len()).map(btdf).fold(0.0, f64::max);
                let (mut cells, mut z2, mut worst) = (0, 0.0, 0.0f64);
                for k in (0..grid.len()).filter(|&k| btdf(k) > 0.03 * peak) {
                    let e = table.transmittance[k] / model[k] - 1.0;
                    let z = e / (AZIMUTHS as f64 / table.hits[k] as f64).sqrt();
                    assert!(
                        z.abs() < 6.0,
                        "Sq {sq}, {ti_deg}°, cell {:?}: ray/model - 1 = {e:.4}, {} hits, z {z:.2}",
                        grid.centre(k / grid.n_phi, k % grid.n_phi),
                        table.hits[k]
                    );
                    cells += 1;
                    z2 += z * z;
                    worst = worst.max(e.abs());
                }
                let (t_ray, t_model) = (table.total_transmittance(), model.iter().sum::<f64>());
                eprintln!(
                    "Sq {} µm (slopes {sx:.4} {sy:.4}), {ti_deg}°: {cells} cells, worst {worst:.4}, \
                     mean z² {:.3}, T ray {t_ray:.7} model {t_model:.7}",
                    sq * 1e6,
                    z2 / cells as f64
                );
                assert!(
                    cells >= 50,
                    "{ti_deg}°: only {cells} cells above 3% of the peak"
                );
                assert!(
                    z2 / cells as f64 <= 2.0,
                    "{ti_deg}°: mean z² {}",
                    z2 / cells as f64
                );
                let bound = 5e-4 + 0.3 * (1.0 - mf.g1(wi));
                assert!(
                    (t_ray - t_model).abs() < bound,
                    "{ti_deg}°: T {t_ray} vs model {t_model}"
                );
            }
        }
    }
}
