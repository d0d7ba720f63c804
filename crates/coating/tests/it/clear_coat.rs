//! A clear coat over a base: the lossless coat against its closed form, the white furnace, the
//! series against a photon random walk, the body table, a Kubelka-Munk base, impossible stacks.

use gonio_brdf::fresnel::dielectric;
use gonio_brdf::quadrature::gauss_legendre_on;
use gonio_brdf::table::{Provenance, Resolution};
use gonio_coating::clear_coat::*;
use gonio_coating::kubelka_munk::Coefficients;
use gonio_color::Spectrum;
use rand::{RngExt, SeedableRng};
use std::f64::consts::PI;

fn stack(n: f64, sigma_per_um: f64, thickness_um: f64, rho: f64) -> ClearCoatOverBase {
    let flat = |v: f64| Spectrum::constant(vec![380.0, 780.0], v).unwrap();
    ClearCoatOverBase {
        coat: Coat {
            index: Dispersion::Constant(n),
            thickness_um,
            absorption_per_um: flat(sigma_per_um),
        },
        base: Base::Diffuse {
            reflectance: flat(rho),
        },
    }
}

/// ∫ f(θi, θo) cos θo dω over the outgoing hemisphere (azimuth-independent: 2π ∫ f μ dμ).
fn body_albedo(o: &AtWavelength, cos_i: f64) -> f64 {
    let n_mu = 20_000;
    (0..n_mu)
        .map(|k| {
            let mu = (k as f64 + 0.5) / n_mu as f64;
            o.brdf(cos_i, mu) * mu
        })
        .sum::<f64>()
        * 2.0
        * PI
        / n_mu as f64
}

/// F̄, the hemispherical average of the internal Fresnel reflectance,
/// `∫ Fi(θ') 2 cos θ' sin θ' dθ'`, by the midpoint rule in θ' (not the module's quadrature).
fn internal_average(n: f64) -> f64 {
    let steps = 200_000;
    let h = 0.5 * PI / steps as f64;
    (0..steps)
        .map(|k| {
            let t = (k as f64 + 0.5) * h;
            dielectric(t.cos(), 1.0 / n) * 2.0 * t.cos() * t.sin() * h
        })
        .sum()
}

/// Lossless coat: the directional-hemispherical reflectance is
/// `F(θi) + (1 − F(θi)) ρ (1 − F̄)/(1 − ρ F̄)` at 0–80°. The two sides meet only through
/// `1 − F̄_external = n² (1 − F̄)` (the n² law of radiance with Fresnel reciprocity), which the
/// model does not use. The bound asked for is 1%; the quadratures (the test's midpoint rules,
/// the model's Gauss-Legendre) agree to 1e-8.
#[test]
fn lossless_coat_reflects_the_closed_form() {
    for (n, rho) in [(1.5, 0.6), (1.33, 0.2), (1.7, 0.95)] {
        let o = stack(n, 0.0, 30.0, rho).at(550.0).unwrap();
        let f_bar = internal_average(n);
        for deg in [0.0f64, 20.0, 45.0, 60.0, 80.0] {
            let c = deg.to_radians().cos();
            let got = o.specular(c) + body_albedo(&o, c);
            assert!((o.body_albedo(c) - body_albedo(&o, c)).abs() < 1e-9);
            let fi = dielectric(c, n);
            let want = fi + (1.0 - fi) * rho * (1.0 - f_bar) / (1.0 - rho * f_bar);
            assert!(
                (got - want).abs() < 1e-6,
                "n {n} ρ {rho} {deg}°: {got} vs {want}"
            );
        }
    }
}

/// A lossless coat over a white base is a white furnace: albedo 1 at every incidence.
#[test]
fn white_furnace() {
    let o = stack(1.5, 0.0, 30.0, 1.0).at(550.0).unwrap();
    for deg in [0.0f64, 30.0, 60.0, 85.0] {
        let c = deg.to_radians().cos();
        let a = o.specular(c) + body_albedo(&o, c);
        assert!((a - 1.0).abs() < 1e-8, "{deg}°: {a}");
    }
}

/// The exact series against a Monte Carlo random walk of photons through the same stack (an
/// independent method: every pass simulated, absorption by survival probability, internal
/// reflections and total internal reflection by Fresnel's probability, the base by
/// cosine-distributed directions). 400 000 photons at 40° into a coat with absorption
/// (σd = 0.3) over ρ = 0.7; outgoing light tallied in 10 bins of equal projected solid angle
/// (equal steps of cos² θo). Each bin agrees with the integral of f cos θ over it within four
/// standard deviations of its binomial count (about 2% of the bin's value); the escaped
/// total within 1%.
#[test]
fn series_matches_a_photon_random_walk() {
    let (n, tau, rho) = (1.5, 0.3, 0.7);
    let o = stack(n, 0.01, 30.0, rho).at(550.0).unwrap();
    assert!((o.tau - tau).abs() < 1e-12);
    let cos_i = 40f64.to_radians().cos();
    let mut rng = rand_pcg::Pcg64::seed_from_u64(7);
    let (photons, bins) = (400_000usize, 10usize);
    let mut tally = vec![0usize; bins];
    let mut specular = 0usize;
    for _ in 0..photons {
        if rng.random::<f64>() < dielectric(cos_i, n) {
            specular += 1;
            continue;
        }
        // Downwards at the refracted angle.
        let mut mu = (1.0 - (1.0 - cos_i * cos_i) / (n * n)).sqrt();
        loop {
            if rng.random::<f64>() >= (-tau / mu).exp() || rng.random::<f64>() >= rho {
                break; // absorbed in the coat or by the base
            }
            mu = rng.random::<f64>().sqrt(); // Lambertian: cos θ with density 2μ
            if rng.random::<f64>() >= (-tau / mu).exp() {
                break;
            }
            if rng.random::<f64>() < dielectric(mu, 1.0 / n) {
                continue; // reflected back down at the same angle
            }
            let mu_o2 = 1.0 - n * n * (1.0 - mu * mu);
            tally[((mu_o2 * bins as f64) as usize).min(bins - 1)] += 1;
            break;
        }
    }
    let spec = specular as f64 / photons as f64;
    assert!((spec - o.specular(cos_i)).abs() < 4.0 * (o.specular(cos_i) / photons as f64).sqrt());
    let mut total_mc = 0.0;
    let mut total_model = 0.0;
    for (b, &count) in tally.iter().enumerate() {
        // ∫ f μ 2π dμ over μ² in [b/bins, (b + 1)/bins].
        let (lo, hi) = (
            (b as f64 / bins as f64).sqrt(),
            ((b + 1) as f64 / bins as f64).sqrt(),
        );
        let model: f64 = gauss_legendre_on(32, lo, hi)
            .into_iter()
            .map(|(mu, w)| w * o.brdf(cos_i, mu) * mu * 2.0 * PI)
            .sum();
        let p = count as f64 / photons as f64;
        let sd = (model * (1.0 - model) / photons as f64).sqrt();
        assert!(
            (p - model).abs() < 4.0 * sd,
            "bin {b}: {p} vs {model} (σ {sd})"
        );
        total_mc += p;
        total_model += model;
    }
    assert!(
        (total_mc / total_model - 1.0).abs() < 0.01,
        "{total_mc} vs {total_model}"
    );
}

/// The table holds the body BRDF at its cells, reciprocal, one channel per wavelength.
#[test]
fn body_table_holds_the_brdf() {
    let s = stack(1.5, 0.002, 40.0, 0.6);
    let wl = [450.0, 550.0, 650.0];
    let t = s
        .body_table(Resolution::isotropic(16, 16, 8), &wl, Provenance::default())
        .unwrap();
    let o = s.at(550.0).unwrap();
    let (wi, wo) = (
        glam::DVec3::new(0.5, 0.0, 0.75f64.sqrt()),
        glam::DVec3::new(-0.3, 0.2, (1.0f64 - 0.13).sqrt()),
    );
    let mut v = [0.0; 3];
    t.eval_channels(wo, wi, &mut v);
    let want = o.brdf(wi.z, wo.z);
    // The body BRDF depends on θi and θo only; the table interpolates it in half/difference
    // angles, with an error of a few per mille at 16 × 16 × 8.
    assert!((v[1] / want - 1.0).abs() < 0.01, "{} vs {want}", v[1]);
    let mut back = [0.0; 3];
    t.eval_channels(wi, wo, &mut back);
    assert!((back[1] / v[1] - 1.0).abs() < 0.01);
}

/// A Kubelka-Munk base reads as the diffuse base of its layer's reflectance.
#[test]
fn kubelka_munk_base() {
    let flat = |v: f64| Spectrum::constant(vec![380.0, 780.0], v).unwrap();
    let base = Base::KubelkaMunk {
        pigments: vec![Pigment {
            name: "red".into(),
            concentration: 0.5,
            k_per_um: flat(0.4),
            s_per_um: flat(0.6),
        }],
        thickness_um: 20.0,
        substrate: flat(0.9),
    };
    let want = Coefficients::new(0.2, 0.3).unwrap().reflectance(20.0, 0.9);
    assert!((base.reflectance(550.0).unwrap() - want).abs() < 1e-15);
}

/// gonio's smooth coat over an opaque Kubelka-Munk layer against Saunderson's correction
/// (`kubelka_munk::saunderson`, J. L. Saunderson, JOSA 32, 727 (1942)) at 45/0 (45as45), the
/// geometry of colour-matching instruments, specular excluded (so the leading k1 term, the
/// mirror reflection, is not read): `R = (1 − k1)(1 − k2) R∞ / (1 − k2 R∞)`, with k1 = F(45°) and
/// k2 the coat's internal diffuse reflectance (here by the midpoint rule, `internal_average`;
/// 0.596 for n = 1.5, the "about 0.6" colour-matching programs use).
///
/// gonio's body reflection is `π f = (1 − F(θi)) (1 − F(θo)) R∞ / (n² (1 − r̄ R∞))` for a lossless
/// coat, with r̄ = k2: the same series of internal reflections, term for term, and the same
/// entry factor (1 − k1). They differ in the exit factor only: Saunderson's (1 − k2) is the
/// share of the diffuse light inside that leaves into the whole hemisphere (an integrating
/// sphere's reading), gonio's (1 − F(θo))/n² the radiance leaving towards the receiver (its
/// hemispherical mean, cosine-weighted, is (1 − k2): `1 − r_e = n² (1 − r_i)`). So
/// gonio / Saunderson = (1 − F(0°)) / (n² (1 − k2)) at 45/0 for every R∞ — 1.057 for n = 1.5:
/// gonio reads 5.7% more, since Fresnel transmittance at normal exit (0.96) exceeds its
/// hemispherical mean (1 − r_e = 0.908). Checked: the ratio is that constant to 1e-6 over R∞
/// from 0.03 to 0.95 (the quadratures agree to 1e-8 on k2, the opaque layer's residual
/// substrate term is e^(−2bSX) < 1e-30), and the hemispherical body albedo equals Saunderson's
/// formula itself to 1e-6.
#[test]
fn smooth_coat_over_an_opaque_layer_is_saundersons_correction() {
    use gonio_coating::kubelka_munk::saunderson;
    let flat = |v: f64| Spectrum::constant(vec![380.0, 780.0], v).unwrap();
    let n = 1.5;
    let (c45, k2) = (45f64.to_radians().cos(), internal_average(n));
    let k1 = dielectric(c45, n);
    let exit = (1.0 - dielectric(1.0, n)) / (n * n * (1.0 - k2));
    eprintln!("k1 {k1:.4}, k2 {k2:.4}, gonio/Saunderson at 45/0 {exit:.4}");
    assert!((k2 - 0.596).abs() < 5e-4 && (exit - 1.057).abs() < 1e-3);
    for k_over_s in [0.0013, 0.01, 0.1, 0.5, 2.0, 15.0] {
        let stack = ClearCoatOverBase {
            coat: Coat {
                index: Dispersion::Constant(n),
                thickness_um: 40.0,
                absorption_per_um: flat(0.0),
            },
            base: Base::KubelkaMunk {
                pigments: vec![Pigment {
                    name: "p".into(),
                    concentration: 1.0,
                    k_per_um: flat(k_over_s),
                    s_per_um: flat(1.0),
                }],
                thickness_um: 1e4,
                substrate: flat(0.5),
            },
        };
        let o = stack.at(550.0).unwrap();
        let r_inf = Coefficients::new(k_over_s, 1.0).unwrap().r_infinity();
        assert!((o.rho - r_inf).abs() < 1e-12, "opaque: {} {r_inf}", o.rho);
        let saunderson_45_0 = saunderson(r_inf, k1, k2) - k1;
        let gonio_45_0 = PI * o.brdf(c45, 1.0);
        assert!(
            (gonio_45_0 / saunderson_45_0 / exit - 1.0).abs() < 1e-6,
            "R∞ {r_inf}: gonio {gonio_45_0}, Saunderson {saunderson_45_0}"
        );
        assert!((o.body_albedo(c45) - saunderson_45_0).abs() < 1e-6);
    }
}

#[test]
fn impossible_stacks_are_refused() {
    assert!(stack(0.9, 0.0, 30.0, 0.5).check(&[550.0]).is_err());
    assert!(stack(1.5, -0.1, 30.0, 0.5).check(&[550.0]).is_err());
    assert!(stack(1.5, 0.0, 30.0, 1.2).check(&[550.0]).is_err());
    assert!(stack(1.5, 0.0, f64::NAN, 0.5).check(&[550.0]).is_err());
    assert!(stack(1.5, 0.0, 30.0, 0.5).check(&[400.0, 700.0]).is_ok());
}
