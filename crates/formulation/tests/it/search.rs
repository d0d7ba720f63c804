//! The match's search (`search::minimise`): it finds a known minimum within the bounds and on a
//! bound, and an objective that fails on its n-th call, wherever in the search that call falls
//! (argmin's initial simplex, a run's iterations, the last run), ends it with that error: no
//! panic, and no evaluation after the failure.

use gonio_formulation::FormulationError;
use gonio_formulation::coating_sensitivity::Varied;
use gonio_formulation::search::{Search, best_run, minimise};
use std::cell::Cell;

fn varied() -> Vec<Varied> {
    vec![
        Varied::parse("tilt=4:20").unwrap(),
        Varied::parse("coverage=0.1:0.9").unwrap(),
    ]
}

const SEARCH: Search = Search {
    starts: 2,
    iterations: 200,
    tolerance: 1e-12,
};

/// A quadratic bowl (closed-form minimum 0 at (12, 0.3) inside the bounds; with its centre at
/// tilt 30, outside them, the constrained minimum is on the bound tilt = 20 at coverage 0.3).
fn bowl(centre_tilt: f64) -> impl Fn(&[f64]) -> gonio_formulation::Result<f64> {
    move |x: &[f64]| Ok(((x[0] - centre_tilt) / 16.0).powi(2) + ((x[1] - 0.3) / 0.8).powi(2))
}

#[test]
fn finds_a_known_minimum_inside_and_on_a_bound() {
    let v = varied();
    let runs = minimise(
        &v,
        &[5.0, 0.8],
        &SEARCH,
        &bowl(12.0),
        &|x| format!("{x:?}"),
        &mut |_| {},
    )
    .unwrap();
    assert_eq!(runs.len(), 3);
    let best = best_run(&runs);
    // Nelder–Mead's sd tolerance 1e-12 on a bowl of unit curvature in ranges of 16 and 0.8:
    // the vertices lie within ~1e-6 of the range of the minimum.
    assert!((best.to[0] - 12.0).abs() < 1e-4, "{:?}", best.to);
    assert!((best.to[1] - 0.3).abs() < 1e-5, "{:?}", best.to);
    let best = best_run(
        &minimise(
            &v,
            &[5.0, 0.8],
            &SEARCH,
            &bowl(30.0),
            &|_| String::new(),
            &mut |_| {},
        )
        .unwrap(),
    )
    .clone();
    assert!((best.to[0] - 20.0).abs() < 1e-4, "{:?}", best.to);
    assert!((best.to[1] - 0.3).abs() < 1e-3, "{:?}", best.to);
}

/// Calls to the bowl that succeed before the failing one, then the error. With 2 constituents
/// argmin evaluates the 3 vertices of the initial simplex first (the costs it unwraps), so n = 1
/// to 3 fail there; n = 10 and 40 fail in the first run's iterations; n past the first two runs'
/// evaluations fails in the last run.
#[test]
fn an_objective_failing_on_its_nth_call_ends_the_search_with_its_error() {
    let v = varied();
    let clean = minimise(
        &v,
        &[5.0, 0.8],
        &SEARCH,
        &bowl(12.0),
        &|_| String::new(),
        &mut |_| {},
    )
    .unwrap();
    let before_last: usize = clean[..2].iter().map(|r| r.evaluations).sum();
    for n in [1, 2, 3, 10, 40, before_last + 5] {
        let calls = Cell::new(0usize);
        let failing = |x: &[f64]| {
            calls.set(calls.get() + 1);
            if calls.get() == n {
                Err(FormulationError::Invalid(format!(
                    "the objective failed on call {n}"
                )))
            } else {
                bowl(12.0)(x)
            }
        };
        let result = minimise(
            &v,
            &[5.0, 0.8],
            &SEARCH,
            &failing,
            &|_| String::new(),
            &mut |_| {},
        );
        match result {
            Err(FormulationError::Invalid(m)) => {
                assert_eq!(m, format!("the objective failed on call {n}"))
            }
            other => panic!("call {n}: expected the objective's error, got {other:?}"),
        }
        assert_eq!(calls.get(), n, "no evaluation after the failure");
    }
}
