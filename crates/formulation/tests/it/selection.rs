//! Colorant selection from gonio's pigment library: the screen's model against the coating's
//! own reading, and synthetic targets made from known combinations of library pigments found
//! again — the pigments, their concentrations within their σ — with the screen's ranking of
//! the true combination measured.

use crate::matching::{quiet, wavelengths};
use gonio_coating::description;
use gonio_coating::pigment_library;
use gonio_coating::system::Coating;
use gonio_formulation::coating_sensitivity::Varied;
use gonio_formulation::matching::{Objective, Settings};
use gonio_formulation::screen::{self, Screened, StackResponse};
use gonio_formulation::selection::{self, Selection};
use gonio_instrument::coating_study;
use gonio_instrument::multiangle::{E2194, Geometry};
use gonio_instrument::multiangle_target::Target;
use gonio_io::Cancel;
use rand::SeedableRng;
use rand_distr::{Distribution, Normal};

/// The instrument's noise on a reflectance factor (spectral_matching.rs: 0.2% of the perfect
/// diffuser at every band and geometry, independent).
const REFLECTANCE_SD: f64 = 0.002;

/// A solid start: a smooth coat over a 30 µm basecoat of the library's titanium white (the
/// paint as it comes) over a 0.6 primer; the selection adds the colours.
pub(crate) const SOLID: &str = "# A white basecoat the colours are selected for\n\n[coat]\nindex = 1.5\nthickness_um = 40 # µm\n\n[base]\nkind = \"kubelka-munk\"\nthickness_um = 30\nsubstrate = 0.6\n\n[[base.pigment]]\nlibrary = \"titanium_white\"\nconcentration = 1.0 # the white\n";

fn solid() -> Coating {
    description::parse(SOLID, &wavelengths()).unwrap()
}

/// `start` with the library pigments `truth` (name, concentration) added.
fn with(start: &Coating, truth: &[(&str, f64)]) -> Coating {
    let pigments: Vec<_> = truth
        .iter()
        .map(|(n, _)| pigment_library::find(n).unwrap())
        .collect();
    let c: Vec<f64> = truth.iter().map(|t| t.1).collect();
    screen::with_pigments(start, &pigments, &c).unwrap()
}

/// The reflectance factors `coating` gives at `geometries`, read with `walks` walks from the
/// streams of seed 99 (independent of the match's seed 0), plus [`REFLECTANCE_SD`] of Gaussian
/// noise (PCG-64 seeded by `noise_seed`), as a target of spectra.
pub(crate) fn synthesised(
    coating: &Coating,
    geometries: &[Geometry],
    walks: usize,
    noise_seed: u64,
) -> Target {
    let wl = wavelengths();
    let evaluator = coating.evaluator(&wl).unwrap();
    let reading =
        coating_study::multiangle_reading(&evaluator, &wl, geometries, walks, 99).unwrap();
    let mut rng = rand_pcg::Pcg64::seed_from_u64(noise_seed);
    let noise = Normal::new(0.0, REFLECTANCE_SD).unwrap();
    let mut csv = String::from("geometry");
    for w in &wl {
        csv.push_str(&format!(",R_{w}nm"));
    }
    csv.push('\n');
    for g in &reading.geometries {
        csv.push_str(&g.geometry.to_string());
        for r in &g.reflectance_factor {
            csv.push_str(&format!(",{}", r + noise.sample(&mut rng)));
        }
        csv.push('\n');
    }
    Target::parse_csv(&csv, "synthesised.csv").unwrap()
}

/// The screen's rank (1 = first) of the combination of `names`.
fn rank(tried: &[Screened], names: &[&str]) -> usize {
    let mut want: Vec<&str> = names.to_vec();
    want.sort();
    1 + tried
        .iter()
        .position(|s| {
            let mut got: Vec<&str> = s.pigments.iter().map(String::as_str).collect();
            got.sort();
            got == want
        })
        .expect("the true combination was screened")
}

/// Select for the target of `truth` over [`SOLID`] and check: the true pigments chosen, each
/// concentration within 3σ of the truth (σ Gauss–Newton, least squares proper with the
/// spectral objective: the residuals are the noise), the residual sd at the noise (within 20%:
/// 155 residuals), the fitted TOML reading back to the fitted coating exactly, and the JSON's
/// tried combinations and finalists. Returns the selection and the screen's rank of the truth.
fn select_and_check(truth: &[(&str, f64)], noise_seed: u64) -> (Selection, usize) {
    let start = solid();
    let target = synthesised(&with(&start, truth), &E2194, 1, noise_seed);
    let settings = Settings {
        objective: Objective::Spectral,
        ..Settings::default()
    };
    let candidates = selection::candidates(&start, None).unwrap();
    assert_eq!(candidates.len(), 18, "the library less the start's white");
    let s = selection::run(
        &start,
        &target,
        &[],
        &[],
        &candidates,
        3,
        selection::FINALISTS,
        &settings,
        &mut quiet,
        &Cancel::default(),
    )
    .unwrap();
    let names: Vec<&str> = truth.iter().map(|t| t.0).collect();
    let r = rank(&s.screen.tried, &names);
    let chosen = s.chosen();
    eprintln!(
        "truth {truth:?}: {} combinations screened in {:.1} s, truth ranked {r}; top 5: {:?}; \
         chosen {:?} at {:?} σ {:?}, s {:.5}, mean ΔE00 {:.3}; {:.1} s in all",
        s.screen.tried.len(),
        s.screen.seconds,
        s.screen.tried[..5]
            .iter()
            .map(selection::describe)
            .collect::<Vec<_>>(),
        chosen.screened.pigments,
        chosen.result.fitted.values,
        chosen.result.sigma,
        chosen.result.residual_sd,
        chosen.result.fitted.de00.iter().sum::<f64>() / 5.0,
        s.seconds
    );
    // 18 + C(18, 2) + C(18, 3) combinations.
    assert_eq!(s.screen.tried.len(), 18 + 153 + 816);
    let mut got: Vec<&str> = chosen
        .screened
        .pigments
        .iter()
        .map(String::as_str)
        .collect();
    got.sort();
    let mut want = names.clone();
    want.sort();
    assert_eq!(got, want, "the true pigments are selected");
    let sigma = chosen.result.sigma.as_ref().unwrap();
    for (i, name) in chosen.screened.pigments.iter().enumerate() {
        let true_c = truth.iter().find(|t| t.0 == name).unwrap().1;
        let (x, sd) = (chosen.result.fitted.values[i], sigma[i]);
        assert!(
            (x - true_c).abs() < 3.0 * sd,
            "{name}: fitted {x}, true {true_c}, σ {sd}"
        );
        // The noise determines every pigment: σ a tenth of its concentration at most.
        assert!(sd < 0.1 * true_c, "{name}: σ {sd} is not a measurement");
    }
    assert!((chosen.result.residual_sd / REFLECTANCE_SD - 1.0).abs() < 0.2);
    // The fitted TOML: the chosen pigments as library entries, reading back exactly.
    let text = s.fitted_description(SOLID).unwrap();
    for name in &chosen.screened.pigments {
        assert!(text.contains(&format!("library = \"{name}\"")), "{text}");
    }
    assert!(
        text.contains("# the white") && text.contains("# µm"),
        "{text}"
    );
    assert_eq!(
        description::parse(&text, &wavelengths()).unwrap(),
        chosen.result.coating,
        "{text}"
    );
    // The JSON: the tried combinations (the best 20 and their count) and the finalists.
    let json = s.to_json(&target, 20);
    let sel = &json["selection"];
    assert_eq!(sel["combinations"], 987);
    assert_eq!(sel["tried"].as_array().unwrap().len(), 20);
    assert_eq!(
        sel["tried"][0]["score"].as_f64().unwrap(),
        s.screen.tried[0].score
    );
    let finalists = sel["finalists"].as_array().unwrap();
    assert_eq!(finalists.len(), selection::FINALISTS);
    for f in finalists {
        assert_eq!(f["de00"].as_array().unwrap().len(), 5);
        assert!(f["objective"].as_f64().unwrap() >= chosen.result.fitted.objective);
    }
    assert_eq!(sel["pigments"].as_array().unwrap().len(), truth.len());
    assert_eq!(json["objective"], "spectral");
    (s, r)
}

/// For a solid (a smooth coat over the Kubelka-Munk base: a closed form), the screen's model —
/// the stack's response `a + b ρ/(1 − c ρ)` read over three greys — is the coating's own
/// reading: every reflectance factor of three combinations, within 1e-9 (the closed form's
/// interreflection series has exactly this form; the difference is rounding).
#[test]
fn the_screen_is_the_closed_form_for_a_solid() {
    let start = solid();
    let wl = wavelengths();
    let response = StackResponse::measure(&start, &E2194, &wl, 1).unwrap();
    for truth in [
        &[("phthalo_blue_green_shade", 0.05)][..],
        &[("pyrrole_red", 0.3), ("bone_black", 0.01)][..],
        &[
            ("hansa_yellow_opaque", 0.2),
            ("phthalo_green_blue_shade", 0.02),
            ("quinacridone_magenta", 0.005),
        ][..],
    ] {
        let coating = with(&start, truth);
        let rho: Vec<f64> = wl
            .iter()
            .map(|&w| coating.base.reflectance(w).unwrap())
            .collect();
        let screened = response.reading(&rho).unwrap();
        let evaluator = coating.evaluator(&wl).unwrap();
        let read = coating_study::multiangle_reading(&evaluator, &wl, &E2194, 1, 0).unwrap();
        for (a, b) in screened.geometries.iter().zip(&read.geometries) {
            for (x, y) in a.reflectance_factor.iter().zip(&b.reflectance_factor) {
                assert!((x - y).abs() < 1e-9, "{truth:?} {}: {x} {y}", a.geometry);
            }
        }
    }
}

/// Bad selections are refused with what is wrong: no pigment to select, more than the
/// candidates, no finalist, an unknown candidate (with the closest name), one given twice or
/// already in the base, a diffuse base, a raised cancel flag.
#[test]
fn bad_selections_are_refused() {
    let start = solid();
    let target = synthesised(&with(&start, &[("pyrrole_red", 0.2)]), &E2194, 1, 1);
    let settings = Settings::default();
    let candidates = selection::candidates(&start, None).unwrap();
    let run = |max: usize, finalists: usize, cancel: &Cancel| {
        selection::run(
            &start,
            &target,
            &[],
            &[],
            &candidates,
            max,
            finalists,
            &settings,
            &mut quiet,
            cancel,
        )
        .unwrap_err()
        .to_string()
    };
    assert!(run(0, 3, &Cancel::default()).contains("at least 1 pigment"));
    assert!(run(1, 0, &Cancel::default()).contains("at least 1 finalist"));
    // 18 candidates (the library less the white).
    assert!(run(19, 3, &Cancel::default()).contains("at most 18"));
    let cancel = Cancel::new();
    cancel.cancel();
    assert_eq!(run(1, 1, &cancel), "cancelled");
    let names = |s: &str| -> Vec<String> { s.split(',').map(String::from).collect() };
    let e = selection::candidates(&start, Some(&names("pyrrole_red,phthalo_blu")))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("'phthalo_blu'") && e.contains("did you mean"),
        "{e}"
    );
    let e = selection::candidates(&start, Some(&names("pyrrole_red,pyrrole_red")))
        .unwrap_err()
        .to_string();
    assert!(e.contains("twice"), "{e}");
    let e = selection::candidates(&start, Some(&names("titanium_white")))
        .unwrap_err()
        .to_string();
    assert!(e.contains("already in the start's base"), "{e}");
    let diffuse = description::parse(
        "[coat]\nindex = 1.5\nthickness_um = 40\n[base]\nkind = \"diffuse\"\nreflectance = 0.5\n",
        &wavelengths(),
    )
    .unwrap();
    let e = selection::candidates(&diffuse, None)
        .unwrap_err()
        .to_string();
    assert!(e.contains("kind = \"kubelka-munk\""), "{e}");
    let only = selection::candidates(&start, Some(&names("pyrrole_red, bone_black"))).unwrap();
    assert_eq!(
        only.iter().map(|p| p.name.as_str()).collect::<Vec<_>>(),
        ["pyrrole_red", "bone_black"]
    );
    let _ = Varied::parse("tilt=1:2").unwrap();
}

/// A metallic start: aluminium flakes (coverage 0.6, tilt 12°) under a glossy rough top, over
/// a 20 µm basecoat with a little of the library's white (0.05) over a dark primer.
const METALLIC: &str = "[top]\nroughness = { distribution = \"ggx\", alpha = 0.03 }\n\n[coat]\nindex = 1.5\nthickness_um = 40\n\n[flakes]\nkind = \"aluminium\"\ncoverage = 0.6\ntilt_deg = 12\n\n[base]\nkind = \"kubelka-munk\"\nthickness_um = 20\nsubstrate = 0.05\n\n[[base.pigment]]\nlibrary = \"titanium_white\"\nconcentration = 0.05\n";

pub(crate) mod slow {
    use super::*;

    /// A blue-green metallic: the start's flakes at coverage 0.45 (the start says 0.6) with
    /// phthalo green (blue shade) 0.3 and phthalo blue (green shade) 0.2 in the basecoat, read
    /// with 1024 walks from seed 99's streams plus [`REFLECTANCE_SD`] of noise. Selecting up to
    /// 2 of 6 candidates (the two, their red-shade and yellow-shade neighbours, ultramarine and
    /// cerulean) with the coverage varied (0.2–0.9): the screen (at the start's coverage, the
    /// stack's response read with the match's walks) ranks the truth within the finalists, the
    /// full match chooses it, and the coverage comes back within 3σ.
    #[test]
    fn a_metallics_pigments_are_selected_with_its_coverage() {
        let wl = wavelengths();
        let start = description::parse(METALLIC, &wl).unwrap();
        let truth = [
            ("phthalo_green_blue_shade", 0.3),
            ("phthalo_blue_green_shade", 0.2),
        ];
        let coverage = Varied::parse("coverage=0.2:0.9").unwrap();
        let true_coating = coverage
            .constituent
            .apply(&with(&start, &truth), 0.45)
            .unwrap();
        let target = synthesised(&true_coating, &E2194, 1024, 7);
        let names: Vec<String> = [
            "phthalo_green_blue_shade",
            "phthalo_green_yellow_shade",
            "phthalo_blue_green_shade",
            "phthalo_blue_red_shade",
            "ultramarine_blue",
            "cerulean_blue_chromium",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect();
        let candidates = selection::candidates(&start, Some(&names)).unwrap();
        let settings = Settings {
            objective: Objective::Spectral,
            ..Settings::default()
        };
        let s = selection::run(
            &start,
            &target,
            &[],
            std::slice::from_ref(&coverage),
            &candidates,
            2,
            selection::FINALISTS,
            &settings,
            &mut quiet,
            &Cancel::default(),
        )
        .unwrap();
        let r = rank(&s.screen.tried, &[truth[0].0, truth[1].0]);
        let chosen = s.chosen();
        eprintln!(
            "metallic: {} combinations screened in {:.1} s, truth ranked {r}; top 5: {:?}; \
             chosen {:?} at {:?} σ {:?}, s {:.5}, mean ΔE00 {:.3}; finalists' objectives {:?}; \
             {:.1} s in all",
            s.screen.tried.len(),
            s.screen.seconds,
            s.screen.tried[..5]
                .iter()
                .map(selection::describe)
                .collect::<Vec<_>>(),
            chosen.screened.pigments,
            chosen.result.fitted.values,
            chosen.result.sigma,
            chosen.result.residual_sd,
            chosen.result.fitted.de00.iter().sum::<f64>() / 5.0,
            s.finalists
                .iter()
                .map(|f| f.result.fitted.objective)
                .collect::<Vec<_>>(),
            s.seconds
        );
        assert_eq!(s.screen.tried.len(), 6 + 15);
        assert!(r <= selection::FINALISTS, "the truth is a finalist");
        let mut got: Vec<&str> = chosen
            .screened
            .pigments
            .iter()
            .map(String::as_str)
            .collect();
        got.sort();
        assert_eq!(
            got,
            ["phthalo_blue_green_shade", "phthalo_green_blue_shade"]
        );
        let sigma = chosen.result.sigma.as_ref().unwrap();
        let x = chosen.result.fitted.values[0];
        assert!(
            (x - 0.45).abs() < 3.0 * sigma[0],
            "coverage {x} σ {}",
            sigma[0]
        );
    }

    /// Two colours in the white: phthalo blue (green shade) 0.04 and hansa yellow 0.15, a green.
    #[test]
    fn two_pigments_are_selected_and_recovered() {
        let (_, r) = select_and_check(
            &[
                ("phthalo_blue_green_shade", 0.04),
                ("hansa_yellow_opaque", 0.15),
            ],
            5,
        );
        assert_eq!(r, 1, "the screen ranks the truth first");
    }

    /// Three colours in the white: pyrrole red 0.1, ultramarine blue 0.2 and bone black 0.01,
    /// a dull violet-red.
    #[test]
    fn three_pigments_are_selected_and_recovered() {
        let (_, r) = select_and_check(
            &[
                ("pyrrole_red", 0.1),
                ("ultramarine_blue", 0.2),
                ("bone_black", 0.01),
            ],
            6,
        );
        assert_eq!(r, 1, "the screen ranks the truth first");
    }
}
