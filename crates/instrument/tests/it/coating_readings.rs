//! The lab's readings of a formulation (`coating_readings::readings`): the same numbers as the
//! study's and the summary's readings at the same walks and seed, the closed form of a smooth
//! coat over a Lambertian base along the in-plane BRDF, an L* curve through the standard's
//! readings, and a cancelled call that stops.

use gonio_coating::description;
use gonio_coating::system::{Coating, default_bands};
use gonio_instrument::InstrumentError;
use gonio_instrument::brdf_readings::curve_aspecular_deg;
use gonio_instrument::coating_readings::{ReadingsRequest, readings};
use gonio_instrument::coating_study::read_coating;
use gonio_instrument::coating_summary::summarise;
use gonio_instrument::multiangle::{E2194, E2539, Geometry, Standard};
use gonio_io::Cancel;
use std::f64::consts::PI;
use std::path::Path;
use std::time::{Duration, Instant};

fn example(name: &str) -> Coating {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/coatings")
        .join(name);
    description::read(&path, &default_bands()).unwrap()
}

/// A quick request: few walks, so that the tests run in seconds.
fn quick(standard: Standard, seed: u64) -> ReadingsRequest {
    ReadingsRequest {
        standard,
        walks: 64,
        brdf_walks: 4,
        gloss_walks: 2,
        albedo_samples: 16 * 64,
        seed,
        ..ReadingsRequest::default()
    }
}

/// At the study's gloss quadrature (4, 6) and the same walks and seed, the gloss meter and the
/// multi-angle colour are `read_coating`'s bit for bit (the same estimates: each geometry's
/// reading does not depend on the others read with it, and the gloss meter's groups of walks
/// sum to its walks), at E2194 and E2539; with seed 0 and `16 × walks` albedo directions the
/// albedo is `summarise`'s.
#[test]
fn readings_are_the_studys_and_the_summarys() {
    let silver = example("silver_metallic.toml");
    let wl = default_bands();
    let none = Cancel::default();
    for (standard, geometries, seed) in [
        (Standard::E2194, &E2194[..], 0),
        (Standard::E2539, &E2539[..], 3),
    ] {
        let request = ReadingsRequest {
            gloss_orders: (4, 6),
            ..quick(standard, seed)
        };
        let r = readings(&silver, &request, &none).unwrap();
        let study = read_coating(&silver, geometries, &wl, 64, 2, seed).unwrap();
        assert_eq!(r.gloss, study.gloss, "{standard:?}");
        assert_eq!(r.brdf.multiangle, study.multiangle, "{standard:?}");
        assert_eq!(r.brdf.flop_index, study.multiangle.flop_index());
        assert_eq!(r.brdf.swatches.len(), geometries.len());
        assert!(r.gloss.doi_uncertainty > 0.0, "{}", r.gloss.doi_uncertainty);
        if seed == 0 {
            let summary = summarise(&silver, &wl, 64).unwrap();
            assert_eq!(r.albedo, summary.albedo);
        }
    }
}

/// Fresnel's reflectance of unpolarised light from a medium of index `n1` into one of `n2` at
/// incidence cosine `c1` (Born & Wolf §1.5.3); 1 beyond the critical angle. Written out here, not
/// the library's.
fn fresnel(c1: f64, n1: f64, n2: f64) -> f64 {
    let s2 = n1 / n2 * (1.0 - c1 * c1).sqrt();
    if s2 >= 1.0 {
        return 1.0;
    }
    let c2 = (1.0 - s2 * s2).sqrt();
    let rs = (n1 * c1 - n2 * c2) / (n1 * c1 + n2 * c2);
    let rp = (n2 * c1 - n1 * c2) / (n2 * c1 + n1 * c2);
    0.5 * (rs * rs + rp * rp)
}

/// Composite Simpson's rule of `f` on [a, b] with `n` (even) intervals.
fn simpson(f: impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
    let h = (b - a) / n as f64;
    let inner: f64 = (1..n)
        .map(|k| f(a + k as f64 * h) * if k % 2 == 1 { 4.0 } else { 2.0 })
        .sum();
    (f(a) + f(b) + inner) * h / 3.0
}

/// A smooth coat (n 1.5, σd = 0.08) over a grey Lambertian base (ρ 0.5): the in-plane luminance
/// BRDF equals the closed form of docs/coatings.md (`clear_coat`),
/// `(1 − F(θi)) (1 − F(θo)) A(θi') A(θo') ρ / (π n² (1 − ρ r̄))`, `A(θ') = exp(−σd / cos θ')`,
/// `r̄ = ∫ Fi(μ) e^{−2σd/μ} 2μ dμ` (here by Simpson's rule, 2 × 20 000 intervals split at the
/// critical angle, with μ = μc + (1 − μc) s² above it: error under 1e-10), at views on both
/// sides, at the specular direction too (the body only: no spike), and the mirror's delta is
/// given apart as Fresnel's F(θi). Grey, so the luminance weighting (weights summing to 1)
/// leaves the value unchanged: bound 1e-8 relative, the rounding of 31 weighted bands and of
/// the library's own quadrature of r̄ (1e-9).
#[test]
fn smooth_coat_inplane_brdf_is_the_closed_form() {
    let (n, tau, rho): (f64, f64, f64) = (1.5, 0.08, 0.5);
    let coating = description::parse(
        "[coat]\nindex = 1.5\nthickness_um = 40\nabsorption_per_um = 0.002\n\
         [base]\nkind = \"diffuse\"\nreflectance = 0.5\n",
        &default_bands(),
    )
    .unwrap();
    let incidence = 30.0_f64;
    let request = ReadingsRequest {
        incidence_deg: incidence,
        ..quick(Standard::E2194, 0)
    };
    let r = readings(&coating, &request, &Cancel::default()).unwrap();
    let mu_c = (1.0 - 1.0 / (n * n)).sqrt();
    let below = simpson(
        |m| (-2.0 * tau / m.max(1e-300)).exp() * 2.0 * m,
        0.0,
        mu_c,
        20_000,
    );
    let above = simpson(
        |s| {
            let m = mu_c + (1.0 - mu_c) * s * s;
            fresnel(m, n, 1.0) * (-2.0 * tau / m).exp() * 2.0 * m * 2.0 * (1.0 - mu_c) * s
        },
        0.0,
        1.0,
        20_000,
    );
    let r_bar = below + above;
    let inside = |theta_deg: f64| {
        let s = theta_deg.to_radians().sin() / n;
        (1.0 - s * s).sqrt()
    };
    let closed = |theta_o: f64| {
        let (ci, co) = (
            incidence.to_radians().cos(),
            theta_o.abs().to_radians().cos(),
        );
        (1.0 - fresnel(ci, 1.0, n))
            * (1.0 - fresnel(co, 1.0, n))
            * (-tau / inside(incidence)).exp()
            * (-tau / inside(theta_o)).exp()
            * rho
            / (PI * n * n * (1.0 - rho * r_bar))
    };
    let inplane = &r.brdf.inplane;
    for view in [-80.0, -45.0, -10.0, 0.0, 12.0, 30.0, 55.0, 85.0] {
        let k = inplane
            .scatter_deg
            .iter()
            .position(|&s| s == view)
            .unwrap_or_else(|| panic!("no view at {view}°"));
        let (got, want) = (inplane.brdf_per_sr[k], closed(view));
        assert!(
            ((got - want) / want).abs() < 1e-8,
            "{view}°: {got} vs {want}"
        );
    }
    let f = fresnel(incidence.to_radians().cos(), 1.0, n);
    assert!(
        (inplane.mirror_reflectance - f).abs() < 1e-10,
        "{} vs {f}",
        inplane.mirror_reflectance
    );
}

/// The L* curve passes through the standard's readings: at each 45° geometry of E2194 and
/// E2539 the curve's L* is the reading's, bit for bit (the same estimate: the same walks from
/// the same streams). A rough glossy top (the silver) makes the walks matter.
#[test]
fn lightness_curve_passes_through_the_standards_readings() {
    let silver = example("silver_metallic.toml");
    let r = readings(&silver, &quick(Standard::E2539, 5), &Cancel::default()).unwrap();
    let curve = &r.brdf.lightness;
    assert_eq!(curve.aspecular_deg, curve_aspecular_deg());
    let mut met = 0;
    for g in r.brdf.multiangle.geometries.iter() {
        if g.geometry.illumination_deg != 45.0 {
            continue;
        }
        let k = curve
            .aspecular_deg
            .iter()
            .position(|&a| a == g.geometry.aspecular_deg)
            .unwrap_or_else(|| panic!("{} not on the curve", g.geometry));
        assert_eq!(curve.lightness[k], g.lab.l, "{}", g.geometry);
        met += 1;
    }
    assert_eq!(met, 6);
    // A metallic: the curve falls from near specular to the flank.
    let at = |a: f64| curve.lightness[curve.aspecular_deg.iter().position(|&x| x == a).unwrap()];
    assert!(at(15.0) > at(45.0) && at(45.0) > at(110.0));
}

/// A flag raised before the call returns `Cancelled` at once; raised during a reading (1024
/// walks per geometry, about a second of work on this machine's test build), the call returns
/// `Cancelled` within one estimate (a geometry's or a view's walks, a source direction of the
/// gloss meter, an albedo incidence: a few milliseconds each). Bound 150 ms, for a loaded
/// machine; the time it took is printed. The rough top's multiple-scattering table, built once
/// per index and roughness (0.1–0.2 s), is not interruptible: a quick reading builds it first.
#[test]
fn a_cancelled_reading_stops() {
    let silver = example("silver_metallic.toml");
    let request = ReadingsRequest {
        walks: 1024,
        ..ReadingsRequest::default()
    };
    let raised = Cancel::new();
    raised.cancel();
    assert!(matches!(
        readings(&silver, &request, &raised),
        Err(InstrumentError::Cancelled)
    ));
    readings(&silver, &quick(Standard::E2194, 0), &Cancel::default()).unwrap();
    let cancel = Cancel::new();
    let flag = cancel.clone();
    let started = Instant::now();
    let stopper = std::thread::spawn(move || {
        std::thread::sleep(Duration::from_millis(30));
        flag.cancel();
        Instant::now()
    });
    let result = readings(&silver, &request, &cancel);
    let returned = Instant::now();
    let cancelled_at = stopper.join().unwrap();
    let latency = returned.saturating_duration_since(cancelled_at);
    eprintln!(
        "cancelled after {:?}, returned {latency:?} later",
        cancelled_at - started
    );
    assert!(matches!(result, Err(InstrumentError::Cancelled)));
    assert!(latency < Duration::from_millis(150), "{latency:?}");
}

/// The JSON the lab receives holds every reading with its unit in its name.
#[test]
fn json_names_every_reading() {
    let red = example("red_solid.toml");
    let r = readings(&red, &quick(Standard::E2194, 0), &Cancel::default()).unwrap();
    let json = r.to_json();
    for key in [
        "standard",
        "multiangle",
        "flop_index",
        "inplane_brdf",
        "lightness_curve",
        "gloss",
        "albedo",
        "albedo_nm",
        "walks",
    ] {
        assert!(json.get(key).is_some(), "{key}");
    }
    assert_eq!(json["standard"], "E2194");
    assert_eq!(json["multiangle"][0]["geometry"], "45as15");
    let hex = json["multiangle"][0]["srgb_hex"].as_str().unwrap();
    assert!(hex.starts_with('#') && hex.len() == 7, "{hex}");
    assert_eq!(json["gloss"]["doi"], r.gloss.doi);
    assert_eq!(
        json["inplane_brdf"]["brdf_per_sr"]
            .as_array()
            .unwrap()
            .len(),
        r.brdf.inplane.scatter_deg.len()
    );
    // The red's swatch at 45as45 is a red, in gamut; the geometry is a standard's.
    let g = &r.brdf.multiangle.geometries[2];
    assert_eq!(g.geometry, Geometry::new(45.0, 45.0));
    let [red_, green, blue] = r.brdf.swatches[2].linear_srgb;
    assert!(
        red_ > 2.0 * green && red_ > 2.0 * blue,
        "{red_} {green} {blue}"
    );
    assert!(!r.brdf.swatches[2].clipped);
}

mod slow {
    use super::*;
    use gonio_instrument::coating_study::CoatingSpecimen;
    use gonio_instrument::gloss;

    /// DOI's uncertainty from the jackknife over groups of walks is the walks' real error: on the
    /// silver metallic at the lab's gloss settings (8 walks per point, orders 4 and 3), the root
    /// mean square of the reported uncertainty over 16 seeds against the standard deviation of
    /// DOI over the same seeds. Their ratio's statistical error: the standard deviation from 16
    /// seeds has a relative standard error of 1/√(2·15) = 18%, the mean of 16 jackknifes of 7
    /// degrees of freedom 1/√(2·7·16) = 7%: together about 20%, so a ratio outside [0.5, 2]
    /// (ln 2 = 3.5 standard errors) says the estimate is wrong, not unlucky. Measured: 0.9 on
    /// the flake coatings, up to 5 times pessimistic on the rough red, whose walks' Sobol
    /// stratification the jackknife does not see (docs/instruments.md).
    #[test]
    fn doi_uncertainty_is_the_spread_over_seeds() {
        let silver = example("silver_metallic.toml");
        let reports: Vec<_> = (1..=16)
            .map(|seed| {
                let specimen = CoatingSpecimen::new(&silver, 555.0, 8)
                    .unwrap()
                    .with_orders(4, 3)
                    .unwrap()
                    .with_seed(seed);
                gloss::measure(&specimen).unwrap()
            })
            .collect();
        let n = reports.len() as f64;
        let mean = reports.iter().map(|r| r.doi).sum::<f64>() / n;
        let sd = (reports.iter().map(|r| (r.doi - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
        let rms = (reports
            .iter()
            .map(|r| r.doi_uncertainty.powi(2))
            .sum::<f64>()
            / n)
            .sqrt();
        eprintln!("DOI {mean:.3}: spread over seeds {sd:.4}, jackknife rms {rms:.4}");
        assert!((0.5..2.0).contains(&(rms / sd)), "{rms} vs {sd}");
    }
}
