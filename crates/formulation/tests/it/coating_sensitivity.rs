//! The coating's sensitivity: the outputs and constituents read from their names, the summary in
//! words and the CSV table, common random numbers and thread independence, and (slow) a metallic
//! whose answer physics gives, its indices also checked against SALib.

use crate::salib;
use gonio_coating::description;
use gonio_coating::system::Coating;
use gonio_formulation::appearance::Output;
use gonio_formulation::coating_sensitivity::{
    self, Indices, Method, Sensitivity, Settings, Varied,
};
use gonio_formulation::sensitivity::sobol::SobolIndices;
use gonio_formulation::sensitivity::{Input, Problem};
use gonio_instrument::coating_study::{Constituent, read_coating};
use gonio_instrument::multiangle::{E2194, Geometry};
use ndarray::{Array2, array};

fn silver(wavelengths: &[f64]) -> Coating {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/coatings/silver_metallic.toml"
    );
    description::read(std::path::Path::new(path), wavelengths).unwrap()
}

#[test]
fn outputs_and_constituents_are_read_from_their_names() {
    let outputs =
        Output::parse_list("gu20,GU60,haze,doi,L@45as15,a@45as-15,b@15as80,flop,dE00").unwrap();
    assert_eq!(outputs[4], Output::L(Geometry::new(45.0, 15.0)));
    assert_eq!(outputs[5], Output::A(Geometry::new(45.0, -15.0)));
    for o in &outputs {
        assert_eq!(Output::parse(&o.name()).unwrap(), *o);
    }
    for bad in ["gu45", "L@45", "x@45as15", "L@95as15", ""] {
        assert!(Output::parse(bad).is_err(), "{bad}");
    }
    // 5 gloss-meter readings, 3 per geometry, flop, ΔE00.
    assert_eq!(Output::all(&E2194).len(), 5 + 15 + 2);
    let v = Varied::parse_list("tilt=4:20, concentration:red=0.1:0.5").unwrap();
    assert_eq!(v[0].constituent, Constituent::FlakeTilt);
    assert_eq!(
        (v[1].name.as_str(), v[1].lo, v[1].hi),
        ("concentration:red", 0.1, 0.5)
    );
    for bad in ["tilt", "tilt=4", "tilt=a:3", "gloss=1:2"] {
        assert!(Varied::parse(bad).is_err(), "{bad}");
    }
}

/// Bounds that make no coating are refused before any reading, naming the constituent.
#[test]
fn bounds_are_checked_before_reading() {
    let wl = [450.0, 550.0, 650.0];
    let coating = silver(&wl);
    let settings = Settings {
        wavelengths_nm: wl.to_vec(),
        ..Settings::default()
    };
    for bad in ["coverage=0.5:1.5", "roughness=0.1:2", "tio2=100:200"] {
        let err = coating_sensitivity::run(
            &coating,
            &[Varied::parse(bad).unwrap()],
            &[Output::Gloss(60)],
            Method::default(),
            &settings,
        )
        .unwrap_err();
        assert!(err.to_string().contains(bad), "{bad}: {err}");
    }
}

/// `--vary` names with and without bounds: inline bounds win, then `--bounds`, then the
/// defaults (tilt 2–40°; the silver's coverage from `--bounds`); bounds for a constituent not
/// varied, and defaults that make no valid coating (tio2 on aluminium flakes), are errors.
#[test]
fn varied_constituents_take_inline_given_or_default_bounds() {
    let wl = [450.0, 550.0, 650.0];
    let coating = silver(&wl);
    let list = Varied::resolve_list(
        "roughness=0.01:0.1,tilt,coverage",
        Some("coverage=0.2:0.9"),
        &coating,
        &wl,
    )
    .unwrap();
    let bounds: Vec<(f64, f64)> = list.iter().map(|v| (v.lo, v.hi)).collect();
    assert_eq!(bounds, [(0.01, 0.1), (2.0, 40.0), (0.2, 0.9)]);
    let err = Varied::resolve_list("tilt", Some("coverage=0.2:0.9"), &coating, &wl).unwrap_err();
    assert!(err.to_string().contains("not varied"), "{err}");
    let ok = Varied::resolve_list("tilt=4:20", Some("tilt=5:6"), &coating, &wl).unwrap();
    assert_eq!((ok[0].lo, ok[0].hi), (4.0, 20.0));
    assert!(Varied::resolve_list("tio2", None, &coating, &wl).is_err());
}

/// A sensitivity made by hand (two inputs, Sobol figures chosen), for the summary and the CSV.
fn made_by_hand() -> Sensitivity {
    let indices = |st: [f64; 2], variance| SobolIndices {
        s1: st.to_vec(),
        s1_conf: vec![0.01, 0.01],
        st: st.to_vec(),
        st_conf: vec![0.05, 0.004],
        variance,
    };
    Sensitivity {
        problem: Problem::new(vec![
            Input::new("roughness", 0.01, 0.1),
            Input::new("tilt", 6.0, 20.0),
        ])
        .unwrap(),
        outputs: vec![Output::Gloss(60), Output::Flop, Output::Haze],
        points: Array2::zeros((4, 2)),
        values: array![
            [10.0, 5.0, 1.0],
            [20.0, 6.0, 1.0],
            [30.0, 5.0, 1.0],
            [40.0, 6.0, 1.0]
        ],
        indices: Indices::Sobol(vec![
            indices([0.93, 0.012], 125.0),
            indices([0.05, 0.6], 0.25),
            indices([0.0, 0.0], 0.0),
        ]),
        base: vec![25.0, 5.5, 1.0],
        noise: vec![0.1, 0.3, 0.0],
    }
}

#[test]
fn summary_says_which_inputs_drive_which_output() {
    let text = made_by_hand().summary(0.1);
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(
        lines,
        [
            "60° gloss is driven by roughness (ST 0.93 ± 0.050); tilt does not matter (ST ≤ 0.012).",
            "The flop index is driven by tilt (ST 0.60 ± 0.0040); roughness does not matter \
             (ST ≤ 0.050) (its noise, sd 0.30, is 36% of its variance over the design: read \
             with more walks).",
            "Haze does not vary over these ranges.",
        ],
        "{text}"
    );
}

#[test]
fn csv_table_has_a_row_per_output_and_input() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("indices.csv");
    made_by_hand().write_csv(&path).unwrap();
    let mut reader = csv::Reader::from_path(&path).unwrap();
    assert_eq!(
        reader.headers().unwrap().iter().collect::<Vec<_>>(),
        [
            "output", "input", "variance", "base", "noise", "s1", "s1_conf", "st", "st_conf"
        ]
    );
    let rows: Vec<csv::StringRecord> = reader.records().map(|r| r.unwrap()).collect();
    assert_eq!(rows.len(), 6);
    assert_eq!(&rows[1][0], "gu60");
    assert_eq!(&rows[1][1], "tilt");
    assert_eq!(rows[1][7].parse::<f64>().unwrap(), 0.012);
    assert_eq!(rows[2][2].parse::<f64>().unwrap(), 0.25);
    let missing = dir.path().join("no/such/dir/indices.csv");
    let err = made_by_hand().write_csv(&missing).unwrap_err();
    assert!(err.to_string().contains("no/such/dir"), "{err}");
}

/// The same design read on one thread and on two gives the same readings bit for bit (each
/// point is read alone, from its own streams).
#[test]
fn readings_do_not_depend_on_the_thread_count() {
    let wl = [450.0, 550.0, 650.0];
    let coating = silver(&wl);
    let settings = Settings {
        wavelengths_nm: wl.to_vec(),
        walks: 64,
        gloss_walks: 1,
        noise_repeats: 1,
        ..Settings::default()
    };
    let run = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| {
                coating_sensitivity::run(
                    &coating,
                    &[Varied::parse("tilt=8:16").unwrap()],
                    &[
                        Output::L(Geometry::new(45.0, 25.0)),
                        Output::Gloss(20),
                        Output::De00,
                    ],
                    Method::Morris {
                        trajectories: 2,
                        levels: 4,
                    },
                    &settings,
                )
                .unwrap()
            })
    };
    let (one, two) = (run(1), run(2));
    assert_eq!(one.values, two.values);
    assert_eq!(one.noise, two.noise);
    assert!(one.noise.iter().all(|&n| n > 0.0), "{:?}", one.noise);
}

mod slow {
    use super::*;

    /// Common random numbers: read with the same seed, two formulations 1% apart in flake tilt
    /// (12° and 12.12°, the silver metallic) differ by much less noise than two independent
    /// readings would. Over seeds 0–5, the standard deviation of the difference
    /// `f(12.12°, s) − f(12°, s)` against that of `f(12°, s)`: an independent pair's difference
    /// would have √2 times it; measured 0.02 (gu60) to 0.52 (b* at 45as110), median 0.20 over the
    /// 21 outputs. Bounds: below 1 for each output (with 6 seeds a ratio of standard deviations
    /// is uncertain by a factor of about 2 either way, so no tighter bound per output is
    /// meaningful) and a median below 0.3 (without common random numbers the median of 21 would
    /// be near √2).
    #[test]
    fn crn_differences_are_smooth() {
        let wl: Vec<f64> = (0..7).map(|k| 400.0 + 50.0 * k as f64).collect();
        let coating = silver(&wl);
        let tilted = Constituent::FlakeTilt.apply(&coating, 12.12).unwrap();
        let outputs = Output::all(&E2194);
        let read = |c: &Coating, s| {
            let r = read_coating(c, &E2194, &wl, 1024, 8, s).unwrap();
            let reference = r.multiangle.clone();
            outputs
                .iter()
                .map(|o| o.value(&r, &reference, &E2194).unwrap())
                .collect::<Vec<f64>>()
        };
        let seeds = 0..6u64;
        let base: Vec<Vec<f64>> = seeds.clone().map(|s| read(&coating, s)).collect();
        let other: Vec<Vec<f64>> = seeds.map(|s| read(&tilted, s)).collect();
        let sd = |v: &[f64]| {
            let m = v.iter().sum::<f64>() / v.len() as f64;
            (v.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / (v.len() - 1) as f64).sqrt()
        };
        let mut ratios = Vec::new();
        for (k, o) in outputs.iter().enumerate() {
            if *o == Output::De00 {
                continue; // against the reading itself: 0
            }
            let noise = sd(&base.iter().map(|r| r[k]).collect::<Vec<_>>());
            let diff = sd(&base
                .iter()
                .zip(&other)
                .map(|(a, b)| b[k] - a[k])
                .collect::<Vec<_>>());
            assert!(diff < noise, "{}: {diff} against {noise}", o.name());
            ratios.push(diff / noise);
        }
        ratios.sort_by(f64::total_cmp);
        let median = ratios[ratios.len() / 2];
        assert!(median < 0.3, "{ratios:?}");
    }

    /// A metallic whose answer physics gives: the silver metallic with its top's roughness
    /// (GGX α 0.02–0.1) and its flakes' tilt spread (6–20°) varied. Gloss is the top's mirror-like
    /// reflection into the receptor, which the roughness spreads and the flakes under the coat
    /// hardly reach (their light is a broad lobe, a few GU at 20° of the silver's 13): 20° and
    /// 60° gloss depend on the roughness, the tilt's total index within its interval of 0. Far
    /// from the specular direction (45as110) the light comes from the flakes tilted furthest, and
    /// the roughness of a top that the light crosses twice there changes it little: L* at 45as110
    /// depends mostly on the tilt, and so do L* at 45as15 (the flakes' lobe) and the flop. The
    /// same design's indices equal SALib's (oracle).
    ///
    /// Measured (N = 16 base points, 64 readings, 512 walks; ± the 95% half-widths): ST of
    /// [roughness, tilt] for 20° gloss [0.91 ± 0.53, 0.074 ± 0.078], 60° gloss [0.91 ± 0.51,
    /// 0.063 ± 0.053], L* at 45as110 [0.031 ± 0.029, 1.24 ± 0.38], L* at 45as15 [0.013 ± 0.014,
    /// 1.13 ± 0.54], flop [0.004 ± 0.007, 1.15 ± 0.48] (ST above 1 is the estimator's scatter at
    /// this N). The tilt's share of the gloss is not exactly 0: the flakes' light inside the
    /// receptor (1.5 GU of the 13 at 20° at 12°, the meter read without its walks) grows as the
    /// spread narrows. Bounds: the tilt's ST under 0.15 for gloss, the roughness's under 0.1
    /// for the rest, and the driving input's interval clear of the other's.
    #[test]
    fn metallic_gloss_follows_roughness_and_flank_follows_tilt() {
        let wl: Vec<f64> = (0..7).map(|k| 400.0 + 50.0 * k as f64).collect();
        let varied = Varied::parse_list("roughness=0.02:0.1,tilt=6:20").unwrap();
        let outputs = Output::parse_list("gu20,gu60,L@45as110,L@45as15,flop").unwrap();
        let settings = Settings {
            wavelengths_nm: wl.clone(),
            walks: 512,
            gloss_walks: 2,
            noise_repeats: 2,
            ..Settings::default()
        };
        let s = coating_sensitivity::run(
            &silver(&wl),
            &varied,
            &outputs,
            Method::Sobol { base: 16 },
            &settings,
        )
        .unwrap();
        let Indices::Sobol(indices) = &s.indices else {
            panic!("Sobol asked")
        };
        // [roughness, tilt] per output: gu20, gu60, L@45as110, L@45as15, flop.
        for k in [0, 1] {
            let (st, conf) = (indices[k].st.clone(), indices[k].st_conf.clone());
            assert!(
                st[1] < 0.15,
                "{}: tilt's ST {} ± {}",
                outputs[k].name(),
                st[1],
                conf[1]
            );
            assert!(
                st[0] - conf[0] > st[1] + conf[1],
                "{}: {st:?} ± {conf:?}",
                outputs[k].name()
            );
        }
        for k in [2, 3, 4] {
            let (st, conf) = (indices[k].st.clone(), indices[k].st_conf.clone());
            assert!(
                st[0] < 0.1,
                "{}: roughness's ST {} ± {}",
                outputs[k].name(),
                st[0],
                conf[0]
            );
            assert!(
                st[1] - conf[1] > st[0] + conf[0],
                "{}: {st:?} ± {conf:?}",
                outputs[k].name()
            );
        }
        assert!(
            s.summary(0.1)
                .starts_with("20° gloss is driven by roughness")
        );
        let problem = s.problem.clone();
        let Some(theirs) = salib::salib(&salib::case(&problem, "sobol", 0, &s.points, &s.values))
        else {
            return;
        };
        for (o, t) in indices.iter().zip(&theirs) {
            salib::assert_same("S1", &o.s1, &t["s1"], 1.0);
            salib::assert_same("ST", &o.st, &t["st"], 1.0);
        }
    }
}
