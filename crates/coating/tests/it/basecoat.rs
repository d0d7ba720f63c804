//! The pigmented basecoat that holds the flakes (`gonio_coating::basecoat`, the walk of
//! `layered/basecoat.rs`) against independent answers: Beer-Lambert through the tinted binder
//! (the exact series of a smooth absorbing coat over a Lambertian base, `clear_coat`), a white
//! furnace, and (module `slow`) the adding-doubling solution of the same slab (PyPI
//! `iadpython`, S. Prahl) and Kubelka-Munk within the conversion's measured error.
//!
//! Tolerances: a walk estimate is a mean over independent samples; it must agree with its
//! reference within four of its standard errors (plus the reference's own error where it has
//! one), which a correct estimator fails about once in 16 000 comparisons.

use glam::DVec3;
use gonio_brdf::fresnel::dielectric;
use gonio_brdf::microfacet::Microfacet;
use gonio_coating::basecoat::{FlakeDepth, kubelka_munk_coefficients, transport_coefficients};
use gonio_coating::clear_coat::{Base, ClearCoatOverBase, Coat, Dispersion};
use gonio_coating::flakes::{FlakeLayer, FlakePigment, Flakes};
use gonio_coating::interface::Interface;
use gonio_coating::kubelka_munk::Coefficients;
use gonio_coating::layered::{Basecoat, EmbeddedFlakes, Scratch, Walk};
use gonio_color::Spectrum;
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64Mcg;
use std::f64::consts::PI;

pub(crate) fn dir(theta_deg: f64, phi_deg: f64) -> DVec3 {
    let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
    DVec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
}

/// A walk over `basecoat` under a top of index `n` and a clear coat of optical thickness `tau`
/// per band.
pub(crate) fn over(n: f64, roughness: Option<Microfacet>, tau: &[f64], basecoat: Basecoat) -> Walk {
    Walk {
        top: Interface::new(n, roughness),
        tau: tau.to_vec(),
        bottom: FlakeLayer::bare(basecoat.substrate.clone()),
        basecoat: Some(basecoat),
    }
}

/// A basecoat of thickness `d` (µm) without flakes.
pub(crate) fn slab(d: f64, sigma_a: &[f64], sigma_s: &[f64], rho: &[f64]) -> Basecoat {
    Basecoat {
        thickness_um: d,
        absorption: sigma_a.to_vec(),
        scattering: sigma_s.to_vec(),
        substrate: rho.to_vec(),
        flakes: None,
    }
}

/// Interference flakes (lossless: R + T = 1) in a binder of index `n`, their optics at 550 nm
/// in each of `bands` bands.
fn pearl(n: f64, coverage: f64, depth: FlakeDepth, bands: usize) -> EmbeddedFlakes {
    let flakes = Flakes {
        pigment: FlakePigment::Interference {
            tio2_nm: 120.0,
            mica_nm: 300.0,
            mica_index: 1.58,
        },
        coverage,
        tilt_deg: 15.0,
        diameter_um: Flakes::DEFAULT_DIAMETER_UM,
        depth: Some(depth),
    };
    let optics = vec![flakes.optics(n, 550.0).unwrap(); bands];
    EmbeddedFlakes {
        depth,
        coverage,
        orientation: flakes.orientation(),
        optics: FlakeLayer::new(&flakes, optics, vec![1.0; bands]),
    }
}

/// Mean and standard error per band of `f(k)` over `count` samples.
pub(crate) fn mean_se(count: usize, mut f: impl FnMut(usize) -> Vec<f64>) -> Vec<(f64, f64)> {
    let (mut sum, mut sum2) = (Vec::new(), Vec::new());
    for k in 0..count {
        let v = f(k);
        sum.resize(v.len(), 0.0);
        sum2.resize(v.len(), 0.0);
        for (b, x) in v.iter().enumerate() {
            sum[b] += x;
            sum2[b] += x * x;
        }
    }
    let m = count as f64;
    sum.iter()
        .zip(&sum2)
        .map(|(s, s2)| {
            let mean = s / m;
            let var = (s2 / m - mean * mean).max(0.0) * m / (m - 1.0);
            (mean, (var / m).sqrt())
        })
        .collect()
}

/// A cosine-distributed direction above.
pub(crate) fn cosine(rng: &mut Pcg64Mcg) -> DVec3 {
    let (u1, u2): (f64, f64) = (rng.random(), rng.random());
    let r = u1.sqrt();
    let phi = 2.0 * PI * u2;
    DVec3::new(r * phi.cos(), r * phi.sin(), (1.0 - u1).max(1e-12).sqrt())
}

/// The light the walk sends back from `wi` into the hemisphere (the directional-hemispherical
/// reflectance less the smooth top's mirror): `count` outgoing directions drawn with density
/// cos θo / π, one walk each, `π f` per sample.
pub(crate) fn body_albedo(walk: &Walk, wi: DVec3, count: usize, seed: u64) -> Vec<(f64, f64)> {
    let mut rng = Pcg64Mcg::seed_from_u64(seed);
    let mut scratch = Scratch::default();
    let mut out = vec![0.0; walk.bands()];
    mean_se(count, |k| {
        let wo = cosine(&mut rng);
        walk.eval_body(wo, wi, 1, seed ^ (k as u64) << 20, &mut scratch, &mut out);
        out.iter().map(|f| PI * f).collect()
    })
}

/// Without scattering the basecoat is Beer-Lambert through the tinted binder: a smooth top over
/// a pigment that only absorbs (σa d = 0.2 and 1.0) and a clear coat (τ 0.05) equals the exact
/// series of one smooth coat of optical thickness τ + σa d over the Lambertian substrate
/// (`clear_coat`, written from Fresnel's equations and the series of internal reflections, not
/// from the walk). Mutation: the walk without the pigment's absorption on its free flights fails
/// at 0/0 by 740 standard errors (0.081 against 0.054).
#[test]
fn without_scattering_it_is_beer_lambert() {
    let (d, sigma_a, rho, tau) = (10.0, [0.02, 0.1], 0.6, 0.05);
    let walk = over(
        1.5,
        None,
        &[tau; 2],
        slab(d, &sigma_a, &[0.0; 2], &[rho; 2]),
    );
    let exact = |b: usize| {
        ClearCoatOverBase {
            coat: Coat {
                index: Dispersion::Constant(1.5),
                thickness_um: 1.0,
                absorption_per_um: Spectrum::constant(vec![380.0, 780.0], tau + sigma_a[b] * d)
                    .unwrap(),
            },
            base: Base::Diffuse {
                reflectance: Spectrum::constant(vec![380.0, 780.0], rho).unwrap(),
            },
        }
        .at(550.0)
        .unwrap()
    };
    let mut scratch = Scratch::default();
    let mut out = [0.0; 2];
    for (ti, to, po) in [(0.0, 0.0, 0.0), (30.0, 50.0, 90.0), (60.0, 20.0, 180.0)] {
        let (wi, wo) = (dir(ti, 0.0), dir(to, po));
        let got = mean_se(64, |k| {
            walk.eval_body(wo, wi, 256, 7 + k as u64, &mut scratch, &mut out);
            out.to_vec()
        });
        for (b, (mean, se)) in got.iter().enumerate() {
            let want = exact(b).brdf(wi.z, wo.z);
            assert!(
                (mean - want).abs() <= 4.0 * se + 1e-12 * want,
                "{ti}/{to}, band {b}: walk {mean} ± {se}, Beer-Lambert series {want}"
            );
            assert!((mean - want).abs() < 0.01 * want, "{mean} vs {want}");
        }
    }
}

/// A white, non-absorbing basecoat (σs d = 10, isotropic) over a white substrate under a
/// lossless smooth top conserves energy: the mirror F(θi) and the light from inside add to 1
/// at 0°, 40° and 70°. With lossless interference flakes spread through it (R + T = 1, coverage
/// 0.6) or in a sheet at mid-depth (whose Smith shadowing of the way out loses light only at
/// grazing angles: under 1% here, bounded at 2%), likewise. Mutation: the isotropic phase
/// function's next-event value without its 1/cos θ (a volume vertex taken as a surface) fails
/// at 40° by 17 standard errors (0.907).
#[test]
fn white_furnace() {
    let n = 1.5;
    let cases: Vec<(&str, Basecoat, f64)> = vec![
        ("pigment", slab(10.0, &[0.0], &[1.0], &[1.0]), 0.0),
        (
            "spread pearl",
            Basecoat {
                flakes: Some(pearl(n, 0.6, FlakeDepth::Spread, 1)),
                ..slab(10.0, &[0.0], &[0.5], &[1.0])
            },
            0.0,
        ),
        (
            "sheet of pearl",
            Basecoat {
                flakes: Some(pearl(n, 0.6, FlakeDepth::Sheet(0.5), 1)),
                ..slab(10.0, &[0.0], &[0.5], &[1.0])
            },
            0.02,
        ),
    ];
    for (name, basecoat, loss) in cases {
        let walk = over(n, None, &[0.0], basecoat);
        for theta in [0.0, 40.0, 70.0] {
            let wi = dir(theta, 0.0);
            let (body, se) = body_albedo(&walk, wi, 20_000, 3)[0];
            let albedo = body + dielectric(wi.z, n);
            assert!(
                albedo <= 1.0 + 4.0 * se && albedo >= 1.0 - loss - 4.0 * se,
                "{name} at {theta}°: albedo {albedo} ± {se}"
            );
        }
    }
}

/// The conversion between Kubelka-Munk's constants and the transport coefficients is an
/// inverse pair.
#[test]
fn conversion_round_trips() {
    let km = Coefficients::new(0.3, 1.7).unwrap();
    let (sa, ss) = transport_coefficients(km);
    assert_eq!((sa, ss), (0.15, 1.7 * 4.0 / 3.0));
    let back = kubelka_munk_coefficients(sa, ss);
    assert!((back.k - km.k).abs() < 1e-15 && (back.s - km.s).abs() < 1e-15);
}

mod slow {
    use super::*;
    use crate::oracle;

    /// iadpython: total reflectance (UR1, specular included) and transmittance (UT1) for
    /// normal collimated incidence, and the same for diffuse incidence (URU, UTU), at 16 and 32
    /// quadrature points. `n` is the slab's index with air above; below, the slab meets air
    /// (n = 1) or, for n ≠ 1, a thick absorbing slide of the slab's own index (an index-matched
    /// black substrate, as gonio's basecoat over a black substrate).
    const SCRIPT: &str = r#"
import json, sys
import iadpython as iad
out = []
for c in json.load(sys.stdin):
    row = []
    for q in (16, 32):
        s = iad.Sample(a=c["a"], b=c["b"], g=0.0, n=c["n"], quad_pts=q)
        if c["n"] != 1.0:
            s.n_below = c["n"]
            s.b_below = 60.0
        row.append([float(x) for x in s.rt()])
    out.append(row)
json.dump(out, sys.stdout)
"#;

    /// The slab without flakes equals adding-doubling (iadpython, an independent solution of
    /// the same radiative-transfer equation): single-scattering albedo 0.5, 0.9 and 0.99,
    /// optical thickness 1 and 4, isotropic scattering, normal incidence, the directional-
    /// hemispherical reflectance (a) index-matched (n = 1) over black, (b) index-matched over
    /// a Lambertian substrate of 0.5, added to iadpython's slab exactly (the substrate forgets
    /// directions: `R = UR1 + UT1 ρ UTU / (1 − ρ URU)`), (c) under a smooth top of n = 1.5 over
    /// an index-matched black substrate (iadpython's specular 0.04 included, gonio's mirror
    /// F(0) added). Tolerance: four standard errors of the walks (20 000 outgoing directions,
    /// one walk each) plus iadpython's own quadrature error, taken as twice the change from 16
    /// to 32 points (its results converge faster than that; the largest change is printed).
    /// Mutation: a walk that leaves at the top's underside instead of being reflected back
    /// (no internal reflection) fails (c) at albedo 0.5, τ 1 (0.0717 ± 0.0003 against 0.0756).
    #[test]
    fn slab_equals_adding_doubling() {
        let mut cases = Vec::new();
        for n in [1.0, 1.5] {
            for a in [0.5, 0.9, 0.99] {
                for tau in [1.0, 4.0] {
                    cases.push((n, a, tau));
                }
            }
        }
        let input = serde_json::Value::Array(
            cases
                .iter()
                .map(|&(n, a, b)| serde_json::json!({"n": n, "a": a, "b": b}))
                .collect(),
        );
        let Some(iad): Option<Vec<[[f64; 4]; 2]>> =
            oracle::run(SCRIPT, "iadpython", "iadpython", &input)
        else {
            return;
        };
        let d = 10.0;
        let mut worst_quadrature: f64 = 0.0;
        for (&(n, a, tau), [r16, r32]) in cases.iter().zip(&iad) {
            let quadrature = 2.0 * (0..4).map(|i| (r32[i] - r16[i]).abs()).fold(0.0, f64::max);
            worst_quadrature = worst_quadrature.max(quadrature);
            let [ur1, ut1, uru, utu] = *r32;
            let sigma = tau / d;
            let substrates: &[f64] = if n == 1.0 { &[0.0, 0.5] } else { &[0.0] };
            for &rho in substrates {
                let walk = over(
                    n,
                    None,
                    &[0.0],
                    slab(d, &[(1.0 - a) * sigma], &[a * sigma], &[rho]),
                );
                let (body, se) = body_albedo(&walk, DVec3::Z, 20_000, 11)[0];
                let got = body + dielectric(1.0, n);
                let want = ur1 + ut1 * rho * utu / (1.0 - rho * uru);
                assert!(
                    (got - want).abs() <= 4.0 * se + quadrature,
                    "n {n}, albedo {a}, τ {tau}, ρ {rho}: walk {got} ± {se}, iadpython {want} \
                     (quadrature {quadrature})"
                );
            }
        }
        eprintln!("iadpython's largest change from 16 to 32 points (×2): {worst_quadrature:.2e}");
    }

    /// Kubelka-Munk's reflectance of the same layer, for diffuse illumination (what
    /// Kubelka-Munk assumes), index-matched: the walk's hemispherical-hemispherical reflectance
    /// (directions in and out both cosine-distributed, `π f`) against
    /// `R(K = 2σa, S = 3σs/4, X, Rg)` over single-scattering albedos 0.3–0.99, optical thickness
    /// 1–10 and substrates 0 and 0.5. The conversion's error, measured against adding-doubling
    /// (module documentation of `basecoat`): at most 0.018 in R over black; the walks, with
    /// the substrates, find at most 0.020 (printed). The bound is 0.025 plus four standard
    /// errors. Mutation: Star et al.'s form (`S = 3σs/4 − σa/4`, its inverse in the walk) fails
    /// at albedo 0.3, τ 1 over black (0.115 against Kubelka-Munk's 0.067).
    #[test]
    fn slab_equals_kubelka_munk_within_the_conversion() {
        let d = 10.0;
        let mut worst: f64 = 0.0;
        for a in [0.3, 0.6, 0.9, 0.99] {
            for tau in [1.0, 3.0, 10.0] {
                for rho in [0.0, 0.5] {
                    let sigma = tau / d;
                    let km = kubelka_munk_coefficients((1.0 - a) * sigma, a * sigma);
                    let (sa, ss) = transport_coefficients(km);
                    let walk = over(1.0, None, &[0.0], slab(d, &[sa], &[ss], &[rho]));
                    let mut rng = Pcg64Mcg::seed_from_u64(5);
                    let mut scratch = Scratch::default();
                    let mut out = [0.0];
                    let (got, se) = mean_se(20_000, |k| {
                        let (wi, wo) = (cosine(&mut rng), cosine(&mut rng));
                        walk.eval_body(wo, wi, 1, k as u64, &mut scratch, &mut out);
                        vec![PI * out[0]]
                    })[0];
                    let want = km.reflectance(d, rho);
                    worst = worst.max((got - want).abs());
                    assert!(
                        (got - want).abs() <= 0.025 + 4.0 * se,
                        "albedo {a}, τ {tau}, ρ {rho}: walk {got} ± {se}, Kubelka-Munk {want}"
                    );
                }
            }
        }
        eprintln!("largest |walk − Kubelka-Munk|: {worst:.4}");
    }
}

/// `[flakes] depth` reads a fraction (a sheet) or "spread"; a depth out of 0–1, another word,
/// a spread coverage of 1, a depth over a diffuse base and discrete flakes (the renderer's
/// glint) inside the basecoat are refused with errors naming what is wrong. The example's
/// coating goes through the basecoat's walk.
#[test]
fn depth_in_the_description() {
    use gonio_coating::description::parse;
    let wl = [450.0, 550.0, 650.0];
    let text = |depth: &str, coverage: f64, base: &str| {
        format!(
            "[coat]\nindex = 1.5\nthickness_um = 40\n[flakes]\nkind = \"aluminium\"\n\
             coverage = {coverage}\ntilt_deg = 12\n{depth}\n{base}"
        )
    };
    let km = "[base]\nkind = \"kubelka-munk\"\nthickness_um = 15\nsubstrate = 0.3\n\
              [[base.pigment]]\nlibrary = \"phthalo_blue_green_shade\"\nconcentration = 0.05\n";
    let diffuse = "[base]\nkind = \"diffuse\"\nreflectance = 0.3\n";
    let depth_of = |t: String| parse(&t, &wl).map(|c| c.flakes.unwrap().depth);
    assert_eq!(
        depth_of(text("depth = \"spread\"", 0.6, km)).unwrap(),
        Some(FlakeDepth::Spread)
    );
    assert_eq!(
        depth_of(text("depth = 0.25", 0.6, km)).unwrap(),
        Some(FlakeDepth::Sheet(0.25))
    );
    assert_eq!(depth_of(text("", 0.6, km)).unwrap(), None);
    for (depth, coverage, base, says) in [
        ("depth = 1.5", 0.6, km, "from 0"),
        ("depth = \"deep\"", 0.6, km, "'deep'"),
        ("depth = \"spread\"", 1.0, km, "below 1"),
        ("depth = 0.5", 0.6, diffuse, "kubelka-munk"),
    ] {
        let e = depth_of(text(depth, coverage, base))
            .unwrap_err()
            .to_string();
        assert!(e.contains("depth") || e.contains("coverage"), "{e}");
        assert!(e.contains(says), "{depth}: {e}");
    }
    let coating = parse(&text("depth = \"spread\"", 0.6, km), &wl).unwrap();
    let e = coating
        .table_without_glint(
            gonio_brdf::table::Resolution::isotropic(4, 4, 4),
            &wl,
            4,
            gonio_brdf::table::Provenance::default(),
            &gonio_io::Cancel::default(),
        )
        .unwrap_err()
        .to_string();
    assert!(e.contains("inside the basecoat"), "{e}");
    let e = gonio_coating::glint::Glint::new(&coating, &wl)
        .unwrap_err()
        .to_string();
    assert!(e.contains("inside the basecoat"), "{e}");
    let gonio_coating::system::Evaluator::Walks(groups) = coating.evaluator(&wl).unwrap() else {
        panic!("flakes are walked");
    };
    let basecoat = groups[0].1.basecoat.as_ref().expect("the basecoat's walk");
    // The library's K and S per µm (0.5 × concentration × relative) converted: σa = K/2.
    let km_at = gonio_coating::basecoat::mixture_at(
        match &coating.base {
            Base::KubelkaMunk { pigments, .. } => pigments,
            Base::Diffuse { .. } => unreachable!(),
        },
        550.0,
    )
    .unwrap();
    assert_eq!(basecoat.absorption[1], km_at.k / 2.0);
    assert_eq!(basecoat.scattering[1], km_at.s * 4.0 / 3.0);
}

/// A table of the basecoat's walks is the same, bit for bit, on one thread and on two (each
/// cell's walks seeded by the pair, `layered/stream.rs`).
#[test]
fn table_does_not_depend_on_the_thread_count() {
    use gonio_brdf::table::{Provenance, Resolution};
    let wl = [450.0, 550.0, 650.0];
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/coatings/blue_metallic_embedded.toml");
    let coating = gonio_coating::description::read(&path, &wl).unwrap();
    let on = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| {
                coating
                    .table(
                        Resolution::isotropic(8, 8, 6),
                        &wl,
                        4,
                        Provenance::default(),
                    )
                    .unwrap()
            })
    };
    let bits = |t: &gonio_brdf::table::BrdfTable| {
        t.values().iter().map(|v| v.to_bits()).collect::<Vec<_>>()
    };
    assert!(bits(&on(1)) == bits(&on(2)), "the tables differ");
}

/// The bands share the walk's directions but not its free flights' coefficients: each band of
/// a walk over four bands whose pigment absorbs and scatters very differently (single-scattering
/// albedo 0.02 to 0.99, optical thickness 0.5 to 8), with spread lossless flakes, equals the
/// same band walked alone (where the hero is always that band and the spectral MIS weights are
/// 1), within four joint standard errors: the hero's choice and the balance heuristic over it
/// are unbiased. Mutation: the density of the path left without the scattering coefficient at
/// a scattering event (`p_c *= σs_c` dropped) fails by 9 standard errors.
#[test]
fn each_band_equals_the_band_walked_alone() {
    let d = 10.0;
    let sigma_a = [0.01, 0.2, 0.05, 0.79];
    let sigma_s = [0.79, 0.05, 0.2, 0.01];
    let basecoat = |bands: &[usize]| Basecoat {
        flakes: Some(pearl(1.5, 0.5, FlakeDepth::Spread, bands.len())),
        ..slab(
            d,
            &bands.iter().map(|&b| sigma_a[b]).collect::<Vec<_>>(),
            &bands.iter().map(|&b| sigma_s[b]).collect::<Vec<_>>(),
            &vec![0.5; bands.len()],
        )
    };
    let wi = dir(30.0, 0.0);
    let together = body_albedo(
        &over(1.5, None, &[0.0; 4], basecoat(&[0, 1, 2, 3])),
        wi,
        40_000,
        9,
    );
    for (b, &(mean, se_t)) in together.iter().enumerate() {
        let (alone, se) = body_albedo(&over(1.5, None, &[0.0], basecoat(&[b])), wi, 40_000, 19)[0];
        let joint = (se * se + se_t * se_t).sqrt();
        assert!(
            (mean - alone).abs() <= 4.0 * joint,
            "band {b}: with the others {mean} ± {se_t}, alone {alone} ± {se}"
        );
    }
}
