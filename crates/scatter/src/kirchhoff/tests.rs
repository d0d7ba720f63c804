use super::*;
use crate::analytic::GaussianModel;
use crate::geometry::spherical_direction;
use gonio_surface::synth::GaussianSurface;
use ndarray::Array2;
use num_complex::Complex64;

const N: f64 = 1.55;

fn flat(n: usize, dx: f64) -> HeightMap {
    HeightMap::new(Array2::zeros((n, n)), dx, dx).unwrap()
}

fn gaussian(sq: f64, t: f64, n: usize, dx: f64, seed: u64) -> HeightMap {
    GaussianSurface::square(sq, t, n, dx, seed)
        .generate()
        .unwrap()
}

fn engine(map: &HeightMap) -> Kirchhoff {
    Kirchhoff::new(map, KirchhoffOptions::new(Ior::Dielectric(N))).unwrap()
}

fn cone(ts: f64, alpha_deg: f64) -> Detector {
    Detector {
        direction: inplane_direction(ts),
        half_angle: alpha_deg.to_radians(),
    }
}

/// A flat patch reflects R(ti) into the specular detector (its lobe, about λ/D = 0.25° wide, lies
/// well inside the 1.4° cone) and nothing into a detector 10° away: energy is conserved to the
/// precision of the lattice sum (exact by Parseval over the whole plane); 10° away the window's
/// diffraction pattern has fallen by more than six decades.
#[test]
fn flat_patch_lobe_integrates_to_fresnel() {
    let k = engine(&flat(129, 1e-6));
    for ti_deg in [0.0f64, 20.0, 60.0] {
        let ti = ti_deg.to_radians();
        let wi = incidence_direction(ti);
        let r = Ior::Dielectric(N).reflectance(ti.cos());
        let spec = k.reflectance(550e-9, wi, &cone(ti, 1.4)).unwrap();
        assert!(
            (spec / r - 1.0).abs() < 0.01,
            "{ti_deg}°: {spec} vs R = {r}"
        );
        let off = k
            .reflectance(550e-9, wi, &cone(ti + 10f64.to_radians(), 1.4))
            .unwrap();
        assert!(off < 1e-6 * r, "{ti_deg}°: {off} off specular");
    }
}

/// The lobe of a flat patch is the diffraction pattern of the window: the pointwise BRDF at the
/// wave vectors of a 4× zero-padded FFT equals what the FFT of the sampled window predicts (times
/// the facets' sinc factor), over five decades.
#[test]
fn flat_patch_lobe_is_window_diffraction_pattern() {
    let (n, a) = (129, 1e-6);
    let k_engine = engine(&flat(n, a));
    // The window sampled independently at the cell centres of the spot's bounding square.
    let cells = 128;
    let radius = 64e-6;
    let pad = 4 * cells;
    let mut field = vec![Complex64::default(); pad * pad];
    let mut w2 = 0.0;
    for j in 0..cells {
        for i in 0..cells {
            let (x, y) = ((i as f64 - 63.5) * a, (j as f64 - 63.5) * a);
            let w = facets::schwartz((x * x + y * y).sqrt() / radius);
            field[j * pad + i] = Complex64::new(w, 0.0);
            w2 += w * w * a * a;
        }
    }
    let fft = gonio_fft::plan_inverse(pad);
    for row in field.chunks_exact_mut(pad) {
        fft.process(row);
    }
    let wavelength = 550e-9;
    let k = TAU / wavelength;
    let ti = 20f64.to_radians();
    let wi = incidence_direction(ti);
    let mirror = DVec3::new(-wi.x, 0.0, wi.z);
    let dv = TAU / (pad as f64 * a);
    let peak = k_engine.brdf(wavelength, wi, mirror).unwrap();
    for m in 0..40 {
        let vx = m as f64 * dv;
        // Column DFT at vy = 0 is the sum over rows.
        let e = (0..cells).map(|j| field[j * pad + m]).sum::<Complex64>() * a * a;
        let wo = aperture::outgoing(k, wi, vx, 0.0).unwrap();
        let sinc = kernel::sinc(0.5 * vx * a);
        let expect = aperture::brdf_factor(Ior::Dielectric(N), wi, wo)
            * k
            * k
            * wi.z
            * (e.norm_sqr() * sinc * sinc)
            / (4.0 * PI * PI * wo.z * w2);
        let got = k_engine.brdf(wavelength, wi, wo).unwrap();
        if expect > 1e-5 * peak {
            assert!(
                (got / expect - 1.0).abs() < 1e-6,
                "m = {m}: {got} vs {expect}"
            );
        }
    }
    let far = aperture::outgoing(k, wi, 60.0 * dv, 0.0).unwrap();
    assert!(k_engine.brdf(wavelength, wi, far).unwrap() < 1e-6 * peak);
}

/// The zoomed transform of a detector equals the plain O(N·D) sum at every lattice point of its
/// cone (same sinc factors and shadowing factor), to rounding.
#[test]
fn zoomed_transform_matches_direct_sum() {
    let map = gaussian(0.1e-6, 2e-6, 65, 0.5e-6, 7);
    let k_engine = engine(&map);
    let wavelength = 600e-9;
    let k = TAU / wavelength;
    let wi = incidence_direction(30f64.to_radians());
    let detector = cone(10f64.to_radians(), 4.0);
    let fast = k_engine.reflectance(wavelength, wi, &detector).unwrap();
    let v0 = -k * (wi + detector.direction);
    let grid = k_engine.detector_grid(k, wi, &detector).unwrap();
    let (dvx, dvy) = aperture::lattice_spacing(grid);
    let shadowing = k_engine.shadowing(1);
    let lambda_wi = shadowing.lambda_exact(wi);
    let mut slow = 0.0;
    for p in -20..=20 {
        for q in -20..=20 {
            let (vx, vy) = (v0.x + p as f64 * dvx, v0.y + q as f64 * dvy);
            let Some(wo) = aperture::outgoing(k, wi, vx, vy) else {
                continue;
            };
            if wo.dot(detector.direction) < detector.half_angle.cos() {
                continue;
            }
            let e = grid.field([vx, vy, v0.z], [v0.x, v0.y, v0.z]);
            slow += shadowing.g2(lambda_wi, wo)
                * aperture::brdf_factor(Ior::Dielectric(N), wi, wo)
                * e.norm_sqr()
                / wo.z;
        }
    }
    let slow = slow * dvx * dvy * wi.z / (4.0 * PI * PI * grid.w2_area);
    assert!(slow > 0.0);
    assert!((fast / slow - 1.0).abs() < 1e-9, "{fast} vs {slow}");
}

/// Sq = 3 nm: the specular detector reads the coherent reflectance R e^(-g) within 2% (the
/// diffuse light inside the cone is below 0.1% of it: the halo holds R g ≈ 0.6% of R spread over
/// about λ/T = 0.1 rad).
#[test]
fn smooth_surface_coherent_specular() {
    let (sigma, t) = (3e-9, 5e-6);
    let map = gaussian(sigma, t, 257, 1e-6, 11);
    let k_engine = engine(&map);
    let model = GaussianModel::new(sigma, t, Ior::Dielectric(N)).unwrap();
    let wavelength = 500e-9;
    for ti_deg in [0.0f64, 20.0, 60.0] {
        let ti = ti_deg.to_radians();
        let rho = k_engine
            .reflectance(wavelength, incidence_direction(ti), &cone(ti, 1.4))
            .unwrap();
        let coherent = model.coherent_reflectance(wavelength, ti);
        assert!(
            (rho / coherent - 1.0).abs() < 0.02,
            "{ti_deg}°: {rho} vs {coherent}"
        );
    }
}

/// Refining the facets further (a four times smaller phase tolerance about doubles the refinement)
/// changes no reading above 1% of the peak by more than 1%, for a rough surface (g ≈ 20).
#[test]
fn refinement_converges() {
    let map = gaussian(0.25e-6, 2.5e-6, 129, 0.5e-6, 3);
    let coarse = engine(&map);
    let mut options = KirchhoffOptions::new(Ior::Dielectric(N));
    options.phase_tolerance = 0.3 / 4.0;
    let fine = Kirchhoff::new(&map, options).unwrap();
    let wavelength = 500e-9;
    let ti = 20f64.to_radians();
    let wi = incidence_direction(ti);
    let k = TAU / wavelength;
    let vz = -k * 2.0 * ti.cos();
    let (rc, rf) = (coarse.refinement(vz).unwrap(), fine.refinement(vz).unwrap());
    assert!(rf > rc, "{rf} vs {rc}");
    let scatter: Vec<f64> = (-60..=70)
        .step_by(10)
        .map(|d| f64::from(d).to_radians())
        .collect();
    let read = |e: &Kirchhoff| -> Vec<f64> {
        scatter
            .iter()
            .map(|&ts| e.reflectance(wavelength, wi, &cone(ts, 3.0)).unwrap())
            .collect()
    };
    let (a, b) = (read(&coarse), read(&fine));
    let peak = a.iter().cloned().fold(0.0, f64::max);
    for ((x, y), ts) in a.iter().zip(&b).zip(&scatter) {
        if *x > 0.01 * peak {
            assert!(
                (x / y - 1.0).abs() < 0.01,
                "{}°: {x} vs {y}",
                ts.to_degrees()
            );
        }
    }
}

/// Out-of-plane pointwise BRDFs are reciprocal for a rough surface, as the Kirchhoff integral is
/// symmetric in (wi, wo) (v and F are).
#[test]
fn pointwise_reciprocity() {
    let map = gaussian(0.05e-6, 1e-6, 65, 0.25e-6, 5);
    let k_engine = engine(&map);
    let (a, b) = (
        spherical_direction(0.4, 2.0),
        spherical_direction(0.9, -0.5),
    );
    let ab = k_engine.brdf(500e-9, a, b).unwrap();
    let ba = k_engine.brdf(500e-9, b, a).unwrap();
    assert!((ab / ba - 1.0).abs() < 1e-9, "{ab} vs {ba}");
}

#[test]
fn rejects_bad_spots() {
    let map = flat(65, 1e-6);
    let mut options = KirchhoffOptions::new(Ior::Dielectric(N));
    options.spot = Some(Spot {
        center: (10e-6, 32e-6),
        diameter: 40e-6,
    });
    assert!(Kirchhoff::new(&map, options).is_err());
    options.spot = Some(Spot {
        center: (32e-6, 32e-6),
        diameter: 4e-6,
    });
    assert!(Kirchhoff::new(&map, options).is_err());
    assert!(Spot::tiled(&map, 30e-6, 4).unwrap().len() == 4);
    assert!(Spot::tiled(&map, 30e-6, 5).is_err());
}

/// The hemisphere table of a flat patch holds R(ti): Parseval makes the lattice sum exact.
#[test]
fn flat_patch_hemisphere_holds_fresnel() {
    let k_engine = engine(&flat(129, 1e-6));
    let grid = crate::ray::HemisphereGrid::with_step_deg(2.0).unwrap();
    for ti_deg in [0.0f64, 45.0] {
        let ti = ti_deg.to_radians();
        let table = k_engine
            .hemisphere(550e-9, incidence_direction(ti), &grid)
            .unwrap();
        let r = Ior::Dielectric(N).reflectance(ti.cos());
        let total = table.total_reflectance();
        assert!((total / r - 1.0).abs() < 1e-4, "{ti_deg}°: {total} vs {r}");
    }
}

/// The FFTs interpolated in vz equal the plain sum over points at every lattice direction (with
/// the same shadowing factor): the total matches the O(N·D) loop to 10⁻⁴ (5·10⁻⁶ measured), the
/// interpolation error.
#[test]
fn hemisphere_fft_matches_direct_sum() {
    let map = gaussian(0.15e-6, 1.5e-6, 33, 0.5e-6, 9);
    let k_engine = engine(&map);
    let wavelength = 600e-9;
    let k = TAU / wavelength;
    let wi = incidence_direction(30f64.to_radians());
    let grid = crate::ray::HemisphereGrid::with_step_deg(5.0).unwrap();
    let table = k_engine.hemisphere(wavelength, wi, &grid).unwrap();
    let r = k_engine.sampling_refinement(k * (wi.z + 1.0));
    let facets = k_engine.grid(r);
    let (dvx, dvy) = aperture::lattice_spacing(facets);
    let (nx, ny) = (facets.nx as isize, facets.ny as isize);
    let shadowing = k_engine.shadowing(r);
    let lambda_wi = shadowing.lambda_exact(wi);
    let mut direct = 0.0;
    for p in -(nx / 2)..(nx + 1) / 2 {
        for q in -(ny / 2)..(ny + 1) / 2 {
            let (vx, vy) = (p as f64 * dvx, q as f64 * dvy);
            let Some(wo) = aperture::outgoing(k, wi, vx, vy) else {
                continue;
            };
            let e = facets.field([vx, vy, -k * (wi.z + wo.z)], [0.0; 3]);
            direct += shadowing.g2(lambda_wi, wo)
                * aperture::brdf_factor(Ior::Dielectric(N), wi, wo)
                * e.norm_sqr()
                / wo.z;
        }
    }
    let direct = direct * dvx * dvy * wi.z / (4.0 * PI * PI * facets.w2_area);
    let total = table.total_reflectance();
    assert!((total / direct - 1.0).abs() < 1e-4, "{total} vs {direct}");
}

/// Energy over the hemisphere for a moderately rough surface (g ≈ 8): the table's total equals
/// the Beckmann-Spizzichino albedo (series over the hemisphere plus the coherent part) within 1%;
/// thousands of speckle grains make the total nearly noise-free, and the series itself conserves
/// energy to 1% here (see the analytic tests).
#[test]
fn rough_hemisphere_albedo_matches_series() {
    let (sigma, t) = (0.12e-6, 2e-6);
    let map = gaussian(sigma, t, 129, 0.5e-6, 21);
    let k_engine = engine(&map);
    let wavelength = 500e-9;
    let ti = 20f64.to_radians();
    let wi = incidence_direction(ti);
    let grid = crate::ray::HemisphereGrid::with_step_deg(1.0).unwrap();
    let total = k_engine
        .hemisphere(wavelength, wi, &grid)
        .unwrap()
        .total_reflectance();
    let model = GaussianModel::new(sigma, t, Ior::Dielectric(N)).unwrap();
    let (nt, np) = (300, 600);
    let (dt, dp) = (PI / 2.0 / nt as f64, TAU / np as f64);
    let mut albedo = model.coherent_reflectance(wavelength, ti);
    for i in 0..nt {
        let th = (i as f64 + 0.5) * dt;
        for j in 0..np {
            let wo = spherical_direction(th, (j as f64 + 0.5) * dp);
            albedo += model.brdf_dirs(crate::analytic::AnalyticModel::Beckmann, wavelength, wi, wo)
                * th.cos()
                * th.sin()
                * dt
                * dp;
        }
    }
    assert!((total / albedo - 1.0).abs() < 0.01, "{total} vs {albedo}");
}

/// Curves are labelled with the angles and wavelengths as a person writes them, not with the
/// rounding noise of the conversion to SI and back.
#[test]
fn curve_labels_read_as_given() {
    let k_engine = engine(&flat(33, 1e-6));
    let curves = k_engine
        .inplane(
            &[550e-9],
            &[60f64.to_radians()],
            &[60f64.to_radians()],
            0.05,
            &gonio_io::Progress::silent(),
        )
        .unwrap();
    assert_eq!(curves[0].wavelength_nm, Some(550.0));
    assert_eq!(curves[0].incidence_deg, 60.0);
    assert_eq!(curves[0].points[0].scatter_deg, 60.0);
}

/// Smith's `Λ` of the map's own slopes (`shadowing`) against Smith's integral for Gaussian
/// slopes, `Λ = E[(1 - q/μ)₊] - 1` over the normal density of `q` (Smith 1967; for zero mean
/// the closed form of Heitz 2014, eq. 72), with the spot's own `W²`-weighted mean and rms slope
/// along the direction's azimuth, on a Gaussian map (Sq 0.8 µm, T 6 µm, 256²: rms slope 0.27).
/// The spot's mean slope matters: it is a sample of about 450 correlation areas, tilted by a
/// few thousandths, and `q̄/μ` reaches 0.02 at 75° and 0.35 at 89°. `1 + Λ` (the facets' area
/// projected toward `w` over the footprint's, what `G1` divides by) agrees within 3% from 75°
/// to 89° (measured at most 1.3%): with the spot's own mean and rms slope, what remains is the
/// shape of a histogram of about 450 independent slopes. The table (used for outgoing directions)
/// equals the exact sum over the facets (used for the source) to 10⁻³ of `1 + Λ`, and a flat
/// map has `Λ = 0`, so nothing changes there.
#[test]
fn smith_lambda_of_the_map_matches_the_gaussian_form() {
    let map = gaussian(0.8e-6, 6e-6, 256, 0.5e-6, 4);
    let k = engine(&map);
    let grid = k.grid(1);
    let shadowing = k.shadowing(1);
    // W²-weighted mean and rms of the slope along (c, s).
    let moments = |c: f64, s: f64| {
        let (mut s0, mut s1, mut s2) = (0.0, 0.0, 0.0);
        for i in 0..grid.w.len() {
            let w2 = grid.w[i] * grid.w[i];
            let q = grid.hx[i] * c + grid.hy[i] * s;
            s0 += w2;
            s1 += w2 * q;
            s2 += w2 * q * q;
        }
        let mean = s1 / s0;
        (mean, (s2 / s0 - mean * mean).sqrt())
    };
    // Smith's integral over a normal density (trapezoid, 10⁵ steps from 12 sd below the mean).
    let gaussian_lambda = |mu: f64, mean: f64, sd: f64| {
        let (lo, steps) = (mean - 12.0 * sd, 100_000);
        let h = (mu - lo) / steps as f64;
        let f = |q: f64| {
            (1.0 - q / mu) * (-0.5 * ((q - mean) / sd).powi(2)).exp() / (sd * (2.0 * PI).sqrt())
        };
        let inner: f64 = (1..steps).map(|i| f(lo + i as f64 * h)).sum();
        (inner + 0.5 * (f(lo) + f(mu))) * h - 1.0
    };
    for phi_deg in [0.0f64, 45.0, 90.0, 200.0] {
        let (s, c) = phi_deg.to_radians().sin_cos();
        let (mean, sd) = moments(c, s);
        for theta_deg in [75.0f64, 80.0, 85.0, 88.0, 89.0] {
            let w = spherical_direction(theta_deg.to_radians(), phi_deg.to_radians());
            let exact = shadowing.lambda_exact(w);
            let table = shadowing.lambda(w);
            let reference = gaussian_lambda(1.0 / theta_deg.to_radians().tan(), mean, sd);
            assert!(
                ((1.0 + exact) / (1.0 + reference) - 1.0).abs() < 0.03,
                "{theta_deg}° at {phi_deg}°: {exact} vs Gaussian {reference} (slope {mean} ± {sd})"
            );
            assert!(
                (table - exact).abs() < 1e-3 * (1.0 + exact),
                "{theta_deg}° at {phi_deg}°: table {table} vs {exact}"
            );
        }
    }
    let flat = engine(&flat(65, 1e-6));
    let none = flat.shadowing(1);
    let w = spherical_direction(89f64.to_radians(), 0.3);
    assert_eq!((none.lambda_exact(w), none.lambda(w)), (0.0, 0.0));
}
