//! Watching a match or a sensitivity run (`watch::Watch`, what the lab's jobs use): the progress
//! counts every reading and the best objective never rises; a raised flag stops the computation
//! before its next reading with `Cancelled`; a watched run gives the unwatched one's result; and
//! the constituents a coating offers (`Varied::available`).

use crate::matching::{example, wavelengths};
use gonio_formulation::FormulationError;
use gonio_formulation::coating_sensitivity::{
    self, Method, Settings as SensitivitySettings, Varied,
};
use gonio_formulation::matching::{self, Settings};
use gonio_formulation::watch::{Progress, Watch};
use gonio_instrument::InstrumentError;
use gonio_instrument::coating_study::{self, Constituent};
use gonio_instrument::multiangle::E2194;
use gonio_instrument::multiangle_target::Target;
use gonio_io::Cancel;
use std::sync::Mutex;

fn cancelled<T>(r: Result<T, FormulationError>) -> bool {
    matches!(
        r,
        Err(FormulationError::Instrument(InstrumentError::Cancelled))
    )
}

/// The silver metallic's reading with its flakes at 20° of tilt (64 walks, seed 7).
fn target_at_20() -> Target {
    let wl = wavelengths();
    let at20 = Constituent::FlakeTilt
        .apply(&example("silver_metallic.toml"), 20.0)
        .unwrap();
    let reading =
        coating_study::multiangle_reading(&at20.evaluator(&wl).unwrap(), &wl, &E2194, 64, 7)
            .unwrap();
    Target::from_reading("tilt 20", &reading)
}

/// A match's progress: one report per reading of the search, counting 1, 2, 3 …, with a best
/// objective that never rises and ends at the best run's objective; a flag raised at the third
/// reading stops it there with `Cancelled`.
#[test]
fn a_watched_match_reports_each_reading_and_stops_when_cancelled() {
    let start = example("silver_metallic.toml");
    let target = target_at_20();
    let varied = vec![Varied::parse("tilt=2:40").unwrap()];
    let settings = Settings {
        walks: 64,
        starts: 1,
        iterations: 8,
        ..Settings::default()
    };
    let seen: Mutex<Vec<Progress>> = Mutex::new(Vec::new());
    let record = |p: Progress| seen.lock().unwrap().push(p);
    let watch = Watch {
        cancel: None,
        progress: Some(&record),
    };
    let m = matching::run_watched(&start, &target, &[], &varied, &settings, watch, &mut |_| {})
        .unwrap();
    let seen = seen.into_inner().unwrap();
    let searched: usize = m.runs.iter().map(|r| r.evaluations).sum();
    assert_eq!(seen.len(), searched);
    for (k, p) in seen.iter().enumerate() {
        assert_eq!((p.readings, p.total), (k + 1, None));
    }
    let best: Vec<f64> = seen.iter().map(|p| p.best.unwrap()).collect();
    assert!(best.windows(2).all(|w| w[1] <= w[0]), "{best:?}");
    let lowest = m
        .runs
        .iter()
        .map(|r| r.objective)
        .fold(f64::INFINITY, f64::min);
    assert_eq!(*best.last().unwrap(), lowest);

    let cancel = Cancel::new();
    let count = Mutex::new(0);
    let stop_at_3 = |p: Progress| {
        *count.lock().unwrap() = p.readings;
        if p.readings == 3 {
            cancel.cancel();
        }
    };
    let watch = Watch {
        cancel: Some(&cancel),
        progress: Some(&stop_at_3),
    };
    let r = matching::run_watched(&start, &target, &[], &varied, &settings, watch, &mut |_| {});
    assert!(cancelled(r), "the match went on");
    assert_eq!(*count.lock().unwrap(), 3);
}

/// The constituents a coating offers: the silver metallic's roughness, tilt, coverage and coat
/// thickness (aluminium flakes: no TiO2) with their default bounds; a pigmented base's
/// concentrations by name.
#[test]
fn the_constituents_a_coating_offers() {
    let silver = example("silver_metallic.toml");
    let names = |c| -> Vec<String> {
        Varied::available(c)
            .unwrap()
            .into_iter()
            .map(|v| v.name)
            .collect()
    };
    assert_eq!(
        names(&silver),
        ["roughness", "tilt", "coverage", "thickness"]
    );
    for v in Varied::available(&silver).unwrap() {
        assert_eq!(
            (v.lo, v.hi),
            Varied::default_bounds(&v.constituent, &silver).unwrap()
        );
    }
    let red = example("red_pigmented.toml");
    let offered = names(&red);
    assert!(
        offered.iter().any(|n| n == "concentration:red"),
        "{offered:?}"
    );
    assert!(!offered.iter().any(|n| n == "tilt"), "{offered:?}");
}

mod slow {
    use super::*;

    /// A watched Morris run counts its readings to its total (r (d + 1) design points, the base
    /// formulation) and gives the unwatched run's indices exactly; a raised flag stops it with
    /// `Cancelled`, and a bad sample size is refused by `check` without reading.
    #[test]
    fn a_watched_sensitivity_counts_to_its_total_and_changes_nothing() {
        let base = example("silver_metallic.toml");
        let varied = vec![Varied::parse("tilt=4:20").unwrap()];
        let outputs = gonio_formulation::appearance::Output::parse_list("gu60,L@45as15").unwrap();
        let method = Method::Morris {
            trajectories: 2,
            levels: 4,
        };
        let settings = SensitivitySettings {
            walks: 32,
            noise_repeats: 0,
            ..SensitivitySettings::default()
        };
        let furthest = Mutex::new((0, None));
        let record = |p: Progress| {
            let mut f = furthest.lock().unwrap();
            f.0 = f.0.max(p.readings);
            f.1 = p.total;
        };
        let watch = Watch {
            cancel: None,
            progress: Some(&record),
        };
        let watched =
            coating_sensitivity::run_watched(&base, &varied, &outputs, method, &settings, watch)
                .unwrap();
        assert_eq!(*furthest.lock().unwrap(), (5, Some(5)));
        let plain = coating_sensitivity::run(&base, &varied, &outputs, method, &settings).unwrap();
        assert_eq!(watched.values, plain.values);
        assert_eq!(watched.indices, plain.indices);

        let cancel = Cancel::new();
        cancel.cancel();
        let watch = Watch {
            cancel: Some(&cancel),
            progress: None,
        };
        let r =
            coating_sensitivity::run_watched(&base, &varied, &outputs, method, &settings, watch);
        assert!(cancelled(r));
        let one = Method::Morris {
            trajectories: 1,
            levels: 4,
        };
        let e = coating_sensitivity::check(&base, &varied, &outputs, one, &settings).unwrap_err();
        assert!(e.to_string().contains("1 Morris trajectories"), "{e}");
    }
}
