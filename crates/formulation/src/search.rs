//! The search a match makes ([`minimise`]): Nelder–Mead (argmin's; Nelder & Mead, Comput. J. 7,
//! 308, 1965), derivative-free, on unbounded parameters mapped into the constituents' bounds by
//! MINUIT's sine transform ([`crate::bounds`]), so that every simplex vertex is a valid
//! formulation. Runs start from the start formulation and from `starts − 1` points of a
//! scrambled Sobol sequence over the bounds (deterministic; low discrepancy fills the box better
//! than random starts with so few points); the best result is run once more from a fresh
//! simplex (restarting at a claimed minimum guards against Nelder–Mead's false convergence,
//! Press et al., Numerical Recipes, 3rd ed., §10.5).
//!
//! The objective is any fallible function of the constituents' values. Its first error ends the
//! search and is returned as it is: argmin's Nelder–Mead unwraps the costs of its initial
//! simplex, so the objective it sees never fails — after an error it answers +∞ without
//! evaluating anything more, and the error is handed back once the run returns.

use crate::bounds::{from_bounds, to_bounds};
use crate::coating_sensitivity::Varied;
use crate::error::{FormulationError, Result};
use argmin::core::{CostFunction, Executor, State};
use argmin::solver::neldermead::NelderMead;
use std::cell::RefCell;
use std::time::Instant;

/// How the search runs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Search {
    /// Nelder–Mead runs before the final one: from the start and from `starts − 1` Sobol points.
    pub starts: usize,
    /// Nelder–Mead iterations per run at most.
    pub iterations: u64,
    /// A run stops when the standard deviation of the objective over the simplex's vertices is
    /// below this, in the objective's units.
    pub tolerance: f64,
}

/// One Nelder–Mead run.
#[derive(Clone, Debug, PartialEq)]
pub struct Run {
    /// Where it started and where it ended, in the constituents' units.
    pub from: Vec<f64>,
    pub to: Vec<f64>,
    /// The objective where it ended.
    pub objective: f64,
    pub evaluations: usize,
}

/// Minimise `objective` over the values of `varied` within their bounds, starting from `x0`
/// (clamped into the bounds) and from Sobol points, then again from the best. Returns every run,
/// the last one last; the first error of `objective` ends the search and is returned.
/// `describe` names a point in the progress lines, which `progress` gets once per run and about
/// every 10 s.
pub fn minimise(
    varied: &[Varied],
    x0: &[f64],
    search: &Search,
    objective: &dyn Fn(&[f64]) -> Result<f64>,
    describe: &dyn Fn(&[f64]) -> String,
    progress: &mut dyn FnMut(&str),
) -> Result<Vec<Run>> {
    if varied.is_empty() || x0.len() != varied.len() {
        return Err(FormulationError::Invalid(format!(
            "a search needs one start value per constituent and at least one constituent \
             ({} values for {} constituents)",
            x0.len(),
            varied.len()
        )));
    }
    if search.starts == 0 {
        return Err(FormulationError::Invalid(
            "a match needs at least one start".into(),
        ));
    }
    let clock = Instant::now();
    let mut starts = vec![x0.to_vec()];
    for k in 1..search.starts {
        starts.push(
            varied
                .iter()
                .enumerate()
                .map(|(i, v)| {
                    let s = sobol_burley::sample(k as u32, i as u32, 0) as f64;
                    v.lo + s * (v.hi - v.lo)
                })
                .collect(),
        );
    }
    let mut nelder_mead = |from: &[f64], step: f64, label: &str| -> Result<Run> {
        let u0: Vec<f64> = varied
            .iter()
            .zip(from)
            .map(|(v, &x)| from_bounds(v, x))
            .collect();
        // The initial simplex: u0 and u0 moved by `step` along each axis, away from the
        // nearer bound (where the sine map is flat).
        let mut simplex = vec![u0.clone()];
        for i in 0..varied.len() {
            let mut u = u0.clone();
            u[i] += if u0[i] > 0.0 { -step } else { step };
            simplex.push(u);
        }
        let state = RefCell::new(CostState {
            error: None,
            evaluations: 0,
            best: f64::INFINITY,
            last_report: Instant::now(),
            progress: &mut *progress,
        });
        let cost = Cost {
            varied,
            objective,
            state: &state,
        };
        let solver = NelderMead::new(simplex)
            .with_sd_tolerance(search.tolerance)
            .map_err(|e| FormulationError::Invalid(e.to_string()))?;
        let result = Executor::new(cost, solver)
            .configure(|s| s.max_iters(search.iterations))
            .run()
            .map(|r| {
                (
                    r.state().get_best_param().cloned(),
                    r.state().get_best_cost(),
                )
            });
        let state = state.into_inner();
        if let Some(e) = state.error {
            return Err(e);
        }
        let (best, cost) = result.map_err(|e| FormulationError::Invalid(e.to_string()))?;
        let best =
            best.ok_or_else(|| FormulationError::Invalid("Nelder-Mead found no point".into()))?;
        let run = Run {
            from: from.to_vec(),
            to: varied
                .iter()
                .zip(&best)
                .map(|(v, &u)| to_bounds(v, u))
                .collect(),
            objective: cost,
            evaluations: state.evaluations,
        };
        (state.progress)(&format!(
            "{label}: objective {:.3} at {} ({} readings, {:.0} s so far)",
            run.objective,
            describe(&run.to),
            run.evaluations,
            clock.elapsed().as_secs_f64()
        ));
        Ok(run)
    };
    let total = starts.len() + 1;
    let mut runs: Vec<Run> = Vec::with_capacity(total);
    for (k, from) in starts.iter().enumerate() {
        let label = if k == 0 {
            format!("run 1 of {total} (from the start formulation)")
        } else {
            format!("run {} of {total} (from a Sobol point)", k + 1)
        };
        runs.push(nelder_mead(from, 0.5, &label)?);
    }
    let best = best_run(&runs).to.clone();
    runs.push(nelder_mead(
        &best,
        0.1,
        &format!("run {total} of {total} (again from the best)"),
    )?);
    Ok(runs)
}

/// The run that ended lowest.
pub fn best_run(runs: &[Run]) -> &Run {
    runs.iter()
        .min_by(|a, b| a.objective.total_cmp(&b.objective))
        .expect("a search makes at least one run")
}

/// The objective as argmin sees it: the unbounded parameters mapped into the bounds, the first
/// error kept (argmin's error type carries only a message, and its Nelder–Mead unwraps the
/// initial simplex's costs), the evaluations counted, a progress line every ~10 s.
struct Cost<'a, 'b> {
    varied: &'a [Varied],
    objective: &'a dyn Fn(&[f64]) -> Result<f64>,
    state: &'a RefCell<CostState<'b>>,
}

struct CostState<'b> {
    error: Option<FormulationError>,
    evaluations: usize,
    best: f64,
    last_report: Instant,
    progress: &'b mut dyn FnMut(&str),
}

impl CostFunction for Cost<'_, '_> {
    type Param = Vec<f64>;
    type Output = f64;

    fn cost(&self, u: &Vec<f64>) -> std::result::Result<f64, argmin::core::Error> {
        if self.state.borrow().error.is_some() {
            // The search has failed: the rest of argmin's run costs nothing.
            return Ok(f64::INFINITY);
        }
        let x: Vec<f64> = self
            .varied
            .iter()
            .zip(u)
            .map(|(v, &u)| to_bounds(v, u))
            .collect();
        let result = (self.objective)(&x);
        let mut state = self.state.borrow_mut();
        state.evaluations += 1;
        match result {
            Ok(f) => {
                state.best = state.best.min(f);
                if state.last_report.elapsed().as_secs_f64() > 10.0 {
                    let line = format!(
                        "  {} readings, best objective so far {:.3}",
                        state.evaluations, state.best
                    );
                    (state.progress)(&line);
                    state.last_report = Instant::now();
                }
                Ok(f)
            }
            Err(e) => {
                state.error = Some(e);
                Ok(f64::INFINITY)
            }
        }
    }
}
