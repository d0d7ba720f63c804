//! Spectral matching of a solid colour: three Kubelka-Munk pigments recovered from a target's
//! reflectance factors, where the CIELAB match of the same target settles on a metamer.

use crate::matching::{assert_recovered, example, quiet, wavelengths};
use gonio_color::{Illuminant, Observer, SpectralToXyz, ciede2000, white};
use gonio_formulation::coating_sensitivity::Varied;
use gonio_formulation::matching::{self, Match, Objective, Settings};
use gonio_instrument::coating_study;
use gonio_instrument::multiangle::{E2194, Geometry, MultiangleReading};
use gonio_instrument::multiangle_target::Target;
use rand::SeedableRng;
use rand_distr::{Distribution, Normal};

/// The instrument's noise on a reflectance factor: a standard deviation of 0.002 at every band
/// and geometry, independent (0.2% of the perfect diffuser: the order of a spectrophotometer's
/// short-term repeatability; an assumption, as the 0.15 in CIELAB of `matching.rs` is).
const REFLECTANCE_SD: f64 = 0.002;

/// CIELAB of the reading at `g` under `illuminant` (10° observer).
fn lab_under(reading: &MultiangleReading, g: Geometry, illuminant: Illuminant) -> gonio_color::Lab {
    let o = Observer::Cie1964TenDegree;
    let to_xyz = SpectralToXyz::new(&reading.wavelengths_nm, illuminant, o).unwrap();
    let r = &reading.at(g).unwrap().reflectance_factor;
    to_xyz.xyz(r).unwrap().to_lab(white(illuminant, o))
}

pub(crate) mod slow {
    use super::*;

    /// examples/coatings/solid_three_pigments.toml (red, white and the ColorChecker "light skin"
    /// inverted as pigments, in a 10 µm basecoat over a 0.6 primer, under a smooth coat: read
    /// exactly, no walks) at concentrations 0.1, 0.05, 0.5: its reflectance factors at E2194,
    /// 400–700 nm every 10 nm, plus [`REFLECTANCE_SD`] of noise, written as the CSV a target
    /// takes. Matched from the example's 0.3, 0.1, 1.0 within 0.02–1, 0.01–0.5, 0.1–3:
    /// - spectral: each concentration within 3σ of the truth (σ, Gauss–Newton, is least squares
    ///   proper here: the residuals are the noise), σ under 2% of each range, and the rms ΔR at
    ///   the noise (s within 20% of 0.002: with 155 residuals less 3 the sample s is within
    ///   ±1/√(2·152) = 6% of σ at one standard deviation);
    /// - CIELAB (mean ΔE00, the same target's colours): ends at a mean ΔE00 no worse than the
    ///   truth's own (the noise's) — as good a match as the truth by its objective — at
    ///   concentrations more than 10 of the spectral σ from the truth, its own σ (Gauss–Newton
    ///   on ΔL*, Δa*, Δb*) wider than a range for one of them at least — CIELAB leaves the
    ///   formulation undetermined — and an rms ΔR over 1.3 times the spectral fit's (a fit that
    ///   left only the noise would have an rms within ±1/√(2·155) = 6% of it at one standard
    ///   deviation: 1.3 is five of them): a metamer, whose spectrum departs from the truth's
    ///   where the observer is nearly blind (printed by band; docs/formulation.md).
    #[test]
    fn spectral_match_recovers_three_pigments_where_cielab_finds_a_metamer() {
        let start = example("solid_three_pigments.toml");
        let varied = Varied::parse_list(
            "concentration:red=0.02:1,concentration:white=0.01:0.5,\
             concentration:light_skin=0.1:3",
        )
        .unwrap();
        let truth = [0.1, 0.05, 0.5];
        let mut true_coating = start.clone();
        for (v, &x) in varied.iter().zip(&truth) {
            true_coating = v.constituent.apply(&true_coating, x).unwrap();
        }
        let wl = wavelengths();
        let evaluator = true_coating.evaluator(&wl).unwrap();
        let truth_reading =
            coating_study::multiangle_reading(&evaluator, &wl, &E2194, 1, 99).unwrap();
        let mut rng = rand_pcg::Pcg64::seed_from_u64(3);
        let noise = Normal::new(0.0, REFLECTANCE_SD).unwrap();
        let mut csv = String::from("geometry");
        for w in &wl {
            csv.push_str(&format!(",R_{w}nm"));
        }
        csv.push('\n');
        for g in &truth_reading.geometries {
            csv.push_str(&g.geometry.to_string());
            for r in &g.reflectance_factor {
                csv.push_str(&format!(",{}", r + noise.sample(&mut rng)));
            }
            csv.push('\n');
        }
        let target = Target::parse_csv(&csv, "three_pigments.csv").unwrap();
        let mean = |d: &[f64]| d.iter().sum::<f64>() / d.len() as f64;
        let truth_de00 = mean(&target.de00(&truth_reading).unwrap());
        let run = |objective| -> Match {
            let settings = Settings {
                objective,
                ..Settings::default()
            };
            matching::run(&start, &target, &[], &varied, &settings, &mut quiet).unwrap()
        };
        let (spectral, cielab) = (run(Objective::Spectral), run(Objective::De00));
        let a45 = Geometry::new(45.0, 45.0);
        let under_a = |m: &Match| {
            ciede2000(
                lab_under(&m.fitted.multiangle, a45, Illuminant::A),
                lab_under(&truth_reading, a45, Illuminant::A),
            )
        };
        for (name, m) in [("spectral", &spectral), ("CIELAB", &cielab)] {
            eprintln!(
                "{name}: fitted {:?} σ {:?}; mean ΔE00 {:.3} -> {:.3} (truth {truth_de00:.3}); \
                 rms ΔR {:.5} -> {:.5}; s {:.5}; ΔE00 from the truth at 45as45 under A {:.3}; \
                 {} readings, {:.1} s",
                m.fitted.values,
                m.sigma,
                mean(&m.start.de00),
                mean(&m.fitted.de00),
                m.start.rms_reflectance.unwrap(),
                m.fitted.rms_reflectance.unwrap(),
                m.residual_sd,
                under_a(m),
                m.evaluations,
                m.seconds
            );
        }
        // Where the metamer's spectrum departs from the truth's (45as45, noiseless).
        let departs: Vec<String> = wl
            .iter()
            .zip(&cielab.fitted.multiangle.at(a45).unwrap().reflectance_factor)
            .zip(&truth_reading.at(a45).unwrap().reflectance_factor)
            .step_by(3)
            .map(|((w, x), y)| format!("{w}: {:+.4}", x - y))
            .collect();
        eprintln!(
            "CIELAB fit − truth at 45as45, ΔR by band: {}",
            departs.join(", ")
        );
        assert_recovered(&spectral, &truth, 0.02);
        assert!((spectral.residual_sd / REFLECTANCE_SD - 1.0).abs() < 0.2);
        let sigma = spectral.sigma.as_ref().unwrap();
        assert!(mean(&cielab.fitted.de00) <= truth_de00);
        assert!(
            (0..3).any(|i| (cielab.fitted.values[i] - truth[i]).abs() > 10.0 * sigma[i]),
            "{:?}",
            cielab.fitted.values
        );
        let rms = |m: &Match| m.fitted.rms_reflectance.unwrap();
        assert!(rms(&cielab) > 1.3 * rms(&spectral));
        let cielab_sigma = cielab.sigma.as_ref().unwrap();
        assert!(
            (0..3).any(|i| cielab_sigma[i] > varied[i].hi - varied[i].lo),
            "{cielab_sigma:?}"
        );
    }
}
