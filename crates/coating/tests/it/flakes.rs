//! Metal and interference flakes: the tabulation against its formulas, the layer's BRDF
//! against its definition, the white furnace, reciprocity, impossible flakes refused.

use glam::{DVec2, DVec3};
use gonio_brdf::fresnel::polarised;
use gonio_coating::flakes::*;
use gonio_coating::thin_film::interference_flake;
use num_complex::Complex64;
use rand::{RngExt, SeedableRng};
use std::f64::consts::PI;

fn pearl(tio2_nm: f64) -> Flakes {
    Flakes {
        pigment: FlakePigment::Interference {
            tio2_nm,
            mica_nm: 300.0,
            mica_index: 1.58,
        },
        coverage: 0.6,
        tilt_deg: 12.0,
        diameter_um: Flakes::DEFAULT_DIAMETER_UM,
        depth: None,
    }
}

/// The tabulated optics against the formulas they tabulate, between the grid points.
#[test]
fn tabulation_follows_the_formulas() {
    let (n, k) = aluminium();
    let metal = Flakes {
        pigment: FlakePigment::Metal { n, k },
        coverage: 0.5,
        tilt_deg: 10.0,
        diameter_um: Flakes::DEFAULT_DIAMETER_UM,
        depth: None,
    };
    let al = metal.optics(1.5, 550.0).unwrap();
    let index = Complex64::new(aluminium().0.value_at(550.0), aluminium().1.value_at(550.0)) / 1.5;
    let p = pearl(120.0);
    let film = p.optics(1.5, 550.0).unwrap();
    let stack = interference_flake(120.0, 300.0, 1.58, 1.5, 550.0).unwrap();
    for i in 0..200 {
        let mu = 0.05 + 0.95 * (i as f64 + 0.37) / 200.0;
        let want = polarised(mu, index).unpolarised();
        assert!((al.reflectance(mu) - want).abs() < 1e-4, "{mu}");
        let want = stack.reflectance_unpolarised(mu.acos(), 550.0);
        assert!((film.reflectance(mu) - want).abs() < 1e-4, "{mu}");
        assert!((film.reflectance(mu) + film.transmittance(mu) - 1.0).abs() < 1e-12);
    }
    // Aluminium in a binder reflects about 0.87–0.9 at normal incidence in the green.
    assert!(
        (0.85..0.93).contains(&al.reflectance(1.0)),
        "{}",
        al.reflectance(1.0)
    );
}

/// Lossless pearlescent flakes over a white base conserve energy: the layer's albedo is 1
/// less what the flakes send below the horizon (under 1% at a 12° tilt for light arriving
/// within 40° of the normal). The albedo by the layer's own sampler and, independently, by
/// uniform hemisphere sampling.
#[test]
fn white_furnace() {
    let p = pearl(80.0);
    let wl = [450.0, 550.0, 650.0];
    let optics = wl.iter().map(|&w| p.optics(1.5, w).unwrap()).collect();
    let layer = FlakeLayer::new(&p, optics, vec![1.0; 3]);
    let mut rng = rand_pcg::Pcg64::seed_from_u64(11);
    let mut f = [0.0; 3];
    for deg in [0.0f64, 20.0, 40.0] {
        let wo = DVec3::new(deg.to_radians().sin(), 0.0, deg.to_radians().cos());
        let n = 200_000;
        let (mut sampled, mut uniform) = ([0.0; 3], [0.0; 3]);
        for _ in 0..n {
            let u = DVec2::new(rng.random(), rng.random());
            if let Some((wi, pdf, _)) = layer.sample(wo, rng.random(), u, &mut f) {
                for b in 0..3 {
                    sampled[b] += f[b] * wi.z / pdf;
                }
            }
            let z: f64 = rng.random();
            let phi = 2.0 * PI * rng.random::<f64>();
            let r = (1.0 - z * z).sqrt();
            let wi = DVec3::new(r * phi.cos(), r * phi.sin(), z);
            layer.f(wo, wi, &mut f);
            for b in 0..3 {
                uniform[b] += f[b] * z * 2.0 * PI;
            }
        }
        for b in 0..3 {
            let (s, u) = (sampled[b] / n as f64, uniform[b] / n as f64);
            assert!((0.99..=1.001).contains(&s), "{deg}° band {b}: {s}");
            // Uniform sampling of a 12° lobe: relative standard error about 1%.
            assert!((u / s - 1.0).abs() < 0.04, "{deg}° band {b}: {u} vs {s}");
        }
    }
}

#[test]
fn reciprocal() {
    let p = pearl(140.0);
    let layer = FlakeLayer::new(&p, vec![p.optics(1.5, 500.0).unwrap()], vec![0.4]);
    let (a, b) = (
        DVec3::new(0.3, 0.1, 0.9).normalize(),
        DVec3::new(-0.2, 0.05, 0.95).normalize(),
    );
    let (mut x, mut y) = ([0.0], [0.0]);
    layer.f(a, b, &mut x);
    layer.f(b, a, &mut y);
    assert!((x[0] / y[0] - 1.0).abs() < 1e-12 && x[0] > 0.0);
}

/// The layer's BRDF is its definition from the flakes' optics, band by band (the layer keeps
/// the bands' tables side by side for speed): `c R(wo·h) D(h) / (4 N(wo) N(wi))` with
/// `N(w) = cos θ` within 40° of the normal for a 12° spread (every flake faces w), plus
/// `a(wi) a(wo) ρ / (π (1 − ρ c R̄))`, `a(w) = 1 − c + c T̃(w)`; and the pdfs the walk takes
/// with it are the layer's own pdf either way, the sampler's second pdf that of the way back.
#[test]
fn layer_brdf_is_its_definition() {
    let p = pearl(120.0);
    let wl = [420.0, 550.0, 680.0];
    let rho = [0.3, 0.5, 0.7];
    let optics: Vec<FlakeOptics> = wl.iter().map(|&w| p.optics(1.5, w).unwrap()).collect();
    let layer = FlakeLayer::new(&p, optics.clone(), rho.to_vec());
    let m = p.orientation();
    let c = p.coverage;
    let mut rng = rand_pcg::Pcg64::seed_from_u64(5);
    let dir = |rng: &mut rand_pcg::Pcg64| {
        let t = rng.random::<f64>() * 40f64.to_radians();
        let f = rng.random::<f64>() * 2.0 * PI;
        DVec3::new(t.sin() * f.cos(), t.sin() * f.sin(), t.cos())
    };
    let mut out = [0.0; 3];
    for _ in 0..200 {
        let (wo, wi) = (dir(&mut rng), dir(&mut rng));
        let (to, back) = layer.f_and_pdfs(wo, wi, &mut out);
        let h = (wo + wi).normalize();
        for b in 0..3 {
            let o = &optics[b];
            let through = |w: DVec3| 1.0 - c + c * o.tilted_transmittance(w.z);
            let want = c * o.reflectance(wo.dot(h)) * m.d(h) / (4.0 * wo.z * wi.z)
                + through(wi) * through(wo) * rho[b]
                    / (PI * (1.0 - rho[b] * c * o.diffuse_reflectance()));
            assert!((out[b] / want - 1.0).abs() < 1e-4, "{} vs {want}", out[b]);
        }
        assert!((to / layer.pdf(wo, wi) - 1.0).abs() < 1e-12);
        assert!((back / layer.pdf(wi, wo) - 1.0).abs() < 1e-12);
        let u = DVec2::new(rng.random(), rng.random());
        if let Some((w, pdf, back)) = layer.sample(wo, rng.random(), u, &mut out) {
            assert!((pdf / layer.pdf(wo, w) - 1.0).abs() < 1e-12);
            assert!((back / layer.pdf(w, wo) - 1.0).abs() < 1e-12);
        }
    }
}

#[test]
fn impossible_flakes_are_refused() {
    let mut p = pearl(100.0);
    p.coverage = 1.2;
    assert!(p.check().is_err());
    let mut p = pearl(100.0);
    p.tilt_deg = 0.0;
    assert!(p.check().is_err());
    assert!(pearl(100.0).check().is_ok());
}
