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
