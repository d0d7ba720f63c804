//! From a target appearance back to a formulation: the values of the varied constituents, within
//! their bounds, whose coating comes closest to a multi-angle target ([`run`]).
//!
//! The objective ([`Objective`]) is the mean CIEDE2000 over the target's geometries, plus
//! `gloss_weight` × |ΔGU| summed over the gloss readings the target gives; or, for a target that
//! gives reflectance factors, their rms difference over its bands and geometries (the spectral
//! match, `match_objective`; gloss readings are not combined with it). Every evaluation reads the coating with
//! the readings' seed 0 (common random numbers, as `coating_sensitivity`): the walks of two
//! nearby formulations draw the same random numbers, so the objective is a smooth function of
//! the constituents rather than one with independent noise at every point (checked in
//! `tests/it/matching.rs`, `objective_is_smooth_along_a_line`, and docs/formulation.md).
//!
//! Optimiser: Nelder–Mead (argmin's; Nelder & Mead, Comput. J. 7, 308, 1965), derivative-free,
//! on unbounded parameters `u` mapped into the bounds by MINUIT's sine transform
//! `x = lo + (hi − lo)(1 + sin u)/2` (F. James & M. Roos, "MINUIT", Comput. Phys. Commun. 10,
//! 343, 1975; James, MINUIT Reference Manual, CERN D506, §1.3.1 "parameter limits"): every
//! simplex vertex is a valid formulation, and the map is smooth with no saturation. Runs start
//! from the start formulation and from `starts − 1` points of a scrambled Sobol sequence over
//! the bounds (deterministic; low discrepancy fills the box better than random starts with so
//! few points); the best result is run once more from a fresh simplex (restarting at a claimed
//! minimum guards against Nelder–Mead's false convergence, Press et al., Numerical Recipes,
//! 3rd ed., §10.5).
//!
//! Uncertainty: Gauss–Newton at the optimum (Bates & Watts, *Nonlinear Regression Analysis and
//! Its Applications*, 1988, §2.3): `cov = s² (JᵀJ)⁻¹`, `s² = Σr²/(m − p)`, with `r` the
//! residual vector — the differences ΔL*, Δa*, Δb* at each geometry (the components of each
//! geometry's colour difference: ΔE00 itself is a norm, with a kink where a geometry is matched,
//! so its derivative is not defined there) and `gloss_weight` × ΔGU per gloss reading; for the
//! spectral objective the ΔR at each band and geometry, whose sum of squares it minimises, so
//! there the estimate is least squares proper — and `J`
//! its Jacobian in the constituents by central differences (steps of 1% of each range).

use crate::bounds::{from_bounds, rounded, to_bounds};
use crate::coating_sensitivity::Varied;
use crate::error::{FormulationError, Result};
pub use crate::match_objective::Objective;
use crate::match_objective::spectra_of;
use crate::match_reader::Reader;
use crate::target::GlossTarget;
use argmin::core::{CostFunction, Executor, State};
use argmin::solver::neldermead::NelderMead;
use gonio_coating::system::Coating;
use gonio_instrument::gloss::GlossReport;
use gonio_instrument::multiangle::{Geometry, MultiangleReading};
use gonio_instrument::multiangle_target::Target;
use std::cell::RefCell;
use std::time::Instant;

/// How a match reads each formulation and searches.
#[derive(Clone, Debug, PartialEq)]
pub struct Settings {
    /// The bands of the multi-angle colour, nm.
    pub wavelengths_nm: Vec<f64>,
    /// Walks per multi-angle geometry.
    pub walks: usize,
    /// Walks per quadrature point of the gloss meter.
    pub gloss_walks: usize,
    /// ΔE00 units per gloss unit in the objective.
    pub gloss_weight: f64,
    /// Nelder–Mead runs before the final one: from the start formulation and from
    /// `starts − 1` Sobol points.
    pub starts: usize,
    /// Nelder–Mead iterations per run at most.
    pub iterations: u64,
    /// A run stops when the standard deviation of the objective over the simplex's vertices is
    /// below this, in ΔE00 (for the spectral objective, this × [`Objective::per_de00`]).
    pub tolerance: f64,
    /// What the match minimises.
    pub objective: Objective,
}

impl Settings {
    /// Default runs before the final one.
    pub const STARTS: usize = 4;
    /// Default iterations per run.
    pub const ITERATIONS: u64 = 150;
    /// Default tolerance: a thousandth of a ΔE00, under the objective's own noise between
    /// seeds (0.02 on the silver metallic, docs/formulation.md).
    pub const TOLERANCE: f64 = 1e-3;
    /// Default ΔE00 per GU: a gloss unit counts as a tenth of a colour-difference unit.
    pub const GLOSS_WEIGHT: f64 = 0.1;
}

/// 400–700 nm every 10 nm, the sensitivity's walks (`coating_sensitivity::Settings::WALKS`,
/// `GLOSS_WALKS`), the defaults above and the ΔE00 objective.
impl Default for Settings {
    fn default() -> Self {
        let s = crate::coating_sensitivity::Settings::default();
        Settings {
            wavelengths_nm: s.wavelengths_nm,
            walks: s.walks,
            gloss_walks: s.gloss_walks,
            gloss_weight: Settings::GLOSS_WEIGHT,
            starts: Settings::STARTS,
            iterations: Settings::ITERATIONS,
            tolerance: Settings::TOLERANCE,
            objective: Objective::default(),
        }
    }
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

/// What one formulation reads against the target.
#[derive(Clone, Debug)]
pub struct Comparison {
    /// The constituents' values.
    pub values: Vec<f64>,
    /// ΔE00 at each of the target's geometries, in its order.
    pub de00: Vec<f64>,
    /// The gloss meter's reading (20°, 60°, 85° gloss, haze, DOI).
    pub gloss: GlossReport,
    /// The multi-angle reading at the target's geometries.
    pub multiangle: MultiangleReading,
    /// rms ΔR over the target's bands and geometries, when the target gives reflectance
    /// factors.
    pub rms_reflectance: Option<f64>,
    /// The objective: mean ΔE00 plus the weighted gloss differences, or the rms ΔR.
    pub objective: f64,
}

/// A match's result.
#[derive(Clone, Debug)]
pub struct Match {
    /// What was minimised.
    pub objective: Objective,
    pub varied: Vec<Varied>,
    /// The target's geometries.
    pub geometries: Vec<Geometry>,
    pub gloss_targets: Vec<GlossTarget>,
    /// The start formulation against the target (its values clamped into the bounds).
    pub start: Comparison,
    /// The fitted formulation against the target.
    pub fitted: Comparison,
    /// One standard deviation of each fitted value (Gauss–Newton); `None` when the residuals
    /// cannot determine them (no more residuals than constituents, or JᵀJ singular: a
    /// constituent that changes nothing).
    pub sigma: Option<Vec<f64>>,
    /// The residuals' standard deviation `s` (CIELAB units; reflectance factor for the spectral
    /// objective).
    pub residual_sd: f64,
    /// The fitted coating.
    pub coating: Coating,
    pub runs: Vec<Run>,
    /// Readings made in all (runs, the Jacobian, the start and the fitted formulation).
    pub evaluations: usize,
    /// Wall-clock seconds.
    pub seconds: f64,
}

impl Match {
    /// Whether constituent `i` ended within 0.1% of the range of a bound (its σ then
    /// describes a constrained value).
    pub fn at_bound(&self, i: usize) -> bool {
        let v = &self.varied[i];
        let x = self.fitted.values[i];
        let margin = 1e-3 * (v.hi - v.lo);
        x <= v.lo + margin || x >= v.hi - margin
    }
}

/// The objective as argmin sees it: the unbounded parameters, the first error kept (argmin's
/// error type carries only a message), the evaluations counted, a progress line every ~10 s.
struct Cost<'a, 'b> {
    reader: &'a Reader<'a>,
    state: &'a RefCell<ObjectiveState<'b>>,
}

struct ObjectiveState<'b> {
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
        let x: Vec<f64> = self
            .reader
            .varied
            .iter()
            .zip(u)
            .map(|(v, &u)| to_bounds(v, u))
            .collect();
        let result = self.reader.objective(&x);
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
                let message = e.to_string();
                state.error.get_or_insert(e);
                Err(argmin::core::Error::msg(message))
            }
        }
    }
}

/// The objective a match minimises, at the values `x` of `varied` (in their units): mean ΔE00
/// from `target` over its geometries plus the weighted gloss differences, the formulation read
/// with seed 0 as every evaluation of [`run`] is.
pub fn objective(
    start: &Coating,
    target: &Target,
    gloss: &[GlossTarget],
    varied: &[Varied],
    settings: &Settings,
    x: &[f64],
) -> Result<f64> {
    if x.len() != varied.len() {
        return Err(FormulationError::Invalid(format!(
            "{} values for {} constituents",
            x.len(),
            varied.len()
        )));
    }
    Reader::new(start, varied, target, gloss, settings).objective(x)
}

/// Find the values of `varied` (within their bounds) that bring `start` closest to `target`
/// (and to the `gloss` readings), reading each formulation with `settings`. `progress` gets a
/// line per run and about every 10 s.
pub fn run(
    start: &Coating,
    target: &Target,
    gloss: &[GlossTarget],
    varied: &[Varied],
    settings: &Settings,
    progress: &mut dyn FnMut(&str),
) -> Result<Match> {
    let clock = Instant::now();
    if varied.is_empty() {
        return Err(FormulationError::Invalid(
            "a match needs at least one constituent to vary".into(),
        ));
    }
    if settings.starts == 0 {
        return Err(FormulationError::Invalid(
            "a match needs at least one start".into(),
        ));
    }
    if settings.objective == Objective::Spectral {
        spectra_of(target)?;
    }
    if settings.objective == Objective::Spectral && !gloss.is_empty() {
        return Err(FormulationError::Invalid(
            "the spectral objective fits reflectance factors only: give gloss readings with \
             the de00 objective"
                .into(),
        ));
    }
    if !(settings.gloss_weight.is_finite() && settings.gloss_weight >= 0.0) {
        return Err(FormulationError::Invalid(format!(
            "gloss weight {}: a non-negative number of ΔE00 per GU",
            settings.gloss_weight
        )));
    }
    for (i, v) in varied.iter().enumerate() {
        if varied[..i].iter().any(|w| w.constituent == v.constituent) {
            return Err(FormulationError::Invalid(format!(
                "{}: varied twice",
                v.name
            )));
        }
        v.check(start, &settings.wavelengths_nm)?;
    }
    let reader = Reader::new(start, varied, target, gloss, settings);
    let x0: Vec<f64> = varied
        .iter()
        .map(|v| Ok(v.constituent.value(start)?.clamp(v.lo, v.hi)))
        .collect::<Result<_>>()?;
    let d = varied.len();
    let mut starts = vec![x0.clone()];
    for k in 1..settings.starts {
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
    let mut evaluations = 0;
    let mut runs: Vec<Run> = Vec::new();
    let mut nelder_mead = |from: &[f64], step: f64, label: &str| -> Result<Run> {
        let u0: Vec<f64> = varied
            .iter()
            .zip(from)
            .map(|(v, &x)| from_bounds(v, x))
            .collect();
        // The initial simplex: u0 and u0 moved by `step` along each axis, away from the
        // nearer bound (where the sine map is flat).
        let mut simplex = vec![u0.clone()];
        for i in 0..d {
            let mut u = u0.clone();
            u[i] += if u0[i] > 0.0 { -step } else { step };
            simplex.push(u);
        }
        let state = RefCell::new(ObjectiveState {
            error: None,
            evaluations: 0,
            best: f64::INFINITY,
            last_report: Instant::now(),
            progress: &mut *progress,
        });
        let objective = Cost {
            reader: &reader,
            state: &state,
        };
        let solver = NelderMead::new(simplex)
            .with_sd_tolerance(settings.tolerance * settings.objective.per_de00())
            .map_err(|e| FormulationError::Invalid(e.to_string()))?;
        let result = Executor::new(objective, solver)
            .configure(|s| s.max_iters(settings.iterations))
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
        let to: Vec<f64> = varied
            .iter()
            .zip(&best)
            .map(|(v, &u)| to_bounds(v, u))
            .collect();
        let run = Run {
            from: from.to_vec(),
            to,
            objective: cost,
            evaluations: state.evaluations,
        };
        (state.progress)(&format!(
            "{label}: objective {:.3} at {} ({} readings, {:.0} s so far)",
            run.objective,
            reader.describe(&run.to),
            run.evaluations,
            clock.elapsed().as_secs_f64()
        ));
        Ok(run)
    };
    for (k, from) in starts.iter().enumerate() {
        let label = if k == 0 {
            format!("run 1 of {} (from the start formulation)", starts.len() + 1)
        } else {
            format!("run {} of {} (from a Sobol point)", k + 1, starts.len() + 1)
        };
        let r = nelder_mead(from, 0.5, &label)?;
        evaluations += r.evaluations;
        runs.push(r);
    }
    let best = runs
        .iter()
        .min_by(|a, b| a.objective.total_cmp(&b.objective))
        .expect("at least one run")
        .to
        .clone();
    let last = nelder_mead(
        &best,
        0.1,
        &format!(
            "run {} of {} (again from the best)",
            runs.len() + 1,
            runs.len() + 1
        ),
    )?;
    evaluations += last.evaluations;
    runs.push(last);
    let best = runs
        .iter()
        .min_by(|a, b| a.objective.total_cmp(&b.objective))
        .expect("at least one run");
    let fitted_x: Vec<f64> = varied
        .iter()
        .zip(&best.to)
        .map(|(v, &x)| rounded(v, x))
        .collect();
    let (start_cmp, fitted) = rayon::join(|| reader.compare(&x0), || reader.compare(&fitted_x));
    let (sigma, residual_sd, readings) = reader.uncertainty(&fitted_x)?;
    evaluations += 2 + readings;
    Ok(Match {
        objective: settings.objective,
        varied: varied.to_vec(),
        geometries: reader.geometries.clone(),
        gloss_targets: gloss.to_vec(),
        start: start_cmp?,
        fitted: fitted?,
        sigma,
        residual_sd,
        coating: reader.coating(&fitted_x)?,
        runs,
        evaluations,
        seconds: clock.elapsed().as_secs_f64(),
    })
}
