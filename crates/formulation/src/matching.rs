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
//! Optimiser: multi-start Nelder–Mead within the bounds ([`crate::search`], where its method and
//! sources are given).
//!
//! Uncertainty: Gauss–Newton at the optimum (Bates & Watts, *Nonlinear Regression Analysis and
//! Its Applications*, 1988, §2.3): `cov = s² (JᵀJ)⁻¹`, `s² = Σr²/(m − p)`, with `r` the
//! residual vector — the differences ΔL*, Δa*, Δb* at each geometry (the components of each
//! geometry's colour difference: ΔE00 itself is a norm, with a kink where a geometry is matched,
//! so its derivative is not defined there) and `gloss_weight` × ΔGU per gloss reading; for the
//! spectral objective the ΔR at each band and geometry, whose sum of squares it minimises, so
//! there the estimate is least squares proper — and `J`
//! its Jacobian in the constituents by central differences (steps of 1% of each range).

use crate::bounds::rounded;
use crate::coating_sensitivity::Varied;
use crate::error::{FormulationError, Result};
pub use crate::match_objective::Objective;
use crate::match_objective::spectra_of;
use crate::match_reader::Reader;
pub use crate::search::Run;
use crate::search::{Search, best_run, minimise};
use crate::target::GlossTarget;
use crate::watch::{Progress, Watch};
use gonio_coating::system::Coating;
use gonio_instrument::gloss::GlossReport;
use gonio_instrument::multiangle::{Geometry, MultiangleReading};
use gonio_instrument::multiangle_target::Target;
use std::cell::Cell;
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

/// Check a match before it reads anything: at least one constituent, none twice, each one's
/// bounds increasing and valid for `start` ([`Varied::check`]), a start and an iteration for the
/// search, a non-negative gloss weight, and for the spectral objective a target with spectra and
/// no gloss readings. [`run`] makes these checks first; a front end calls this to refuse a bad
/// request at once.
pub fn check(
    start: &Coating,
    target: &Target,
    gloss: &[GlossTarget],
    varied: &[Varied],
    settings: &Settings,
) -> Result<()> {
    if varied.is_empty() {
        return Err(FormulationError::Invalid(
            "a match needs at least one constituent to vary".into(),
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
    if settings.starts == 0 || settings.iterations == 0 || settings.walks == 0 {
        return Err(FormulationError::Invalid(format!(
            "a match needs at least one start, one iteration and one walk per geometry ({} \
             starts, {} iterations, {} walks)",
            settings.starts, settings.iterations, settings.walks
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
    Ok(())
}

/// Find the values of `varied` (within their bounds) that bring `start` closest to `target`
/// (and to the `gloss` readings), reading each formulation with `settings`. `progress` gets a
/// line per run and about every 10 s. [`search`] then [`conclude`].
pub fn run(
    start: &Coating,
    target: &Target,
    gloss: &[GlossTarget],
    varied: &[Varied],
    settings: &Settings,
    progress: &mut dyn FnMut(&str),
) -> Result<Match> {
    run_watched(
        start,
        target,
        gloss,
        varied,
        settings,
        Watch::default(),
        progress,
    )
}

/// [`run`] under `watch`: told the readings made and the lowest objective after every reading
/// of the search, and stopped (`InstrumentError::Cancelled`) before the next reading once its
/// flag is raised.
pub fn run_watched(
    start: &Coating,
    target: &Target,
    gloss: &[GlossTarget],
    varied: &[Varied],
    settings: &Settings,
    watch: Watch,
    progress: &mut dyn FnMut(&str),
) -> Result<Match> {
    let clock = Instant::now();
    let runs = search_watched(start, target, gloss, varied, settings, &watch, progress)?;
    let mut m = conclude(start, target, gloss, varied, settings, runs)?;
    m.seconds = clock.elapsed().as_secs_f64();
    Ok(m)
}

/// The start's values of `varied`, clamped into their bounds.
fn start_values(start: &Coating, varied: &[Varied]) -> Result<Vec<f64>> {
    varied
        .iter()
        .map(|v| Ok(v.constituent.value(start)?.clamp(v.lo, v.hi)))
        .collect()
}

/// The search of a match ([`run`]'s first half): the Nelder–Mead runs, the best one last but
/// one, the final run from it last. Deterministic (seed 0), so that runs made elsewhere (a
/// Dask worker) and passed to [`conclude`] give the match [`run`] gives.
pub fn search(
    start: &Coating,
    target: &Target,
    gloss: &[GlossTarget],
    varied: &[Varied],
    settings: &Settings,
    progress: &mut dyn FnMut(&str),
) -> Result<Vec<Run>> {
    search_watched(
        start,
        target,
        gloss,
        varied,
        settings,
        &Watch::default(),
        progress,
    )
}

/// [`search`] under `watch` (see [`run_watched`]).
pub fn search_watched(
    start: &Coating,
    target: &Target,
    gloss: &[GlossTarget],
    varied: &[Varied],
    settings: &Settings,
    watch: &Watch,
    progress: &mut dyn FnMut(&str),
) -> Result<Vec<Run>> {
    check(start, target, gloss, varied, settings)?;
    let reader = Reader::new(start, varied, target, gloss, settings);
    let x0 = start_values(start, varied)?;
    let search = Search {
        starts: settings.starts,
        iterations: settings.iterations,
        tolerance: settings.tolerance * settings.objective.per_de00(),
    };
    let (readings, best) = (Cell::new(0), Cell::new(f64::INFINITY));
    let watched = |x: &[f64]| {
        watch.check()?;
        let f = reader.objective(x)?;
        readings.set(readings.get() + 1);
        best.set(best.get().min(f));
        watch.report(Progress {
            readings: readings.get(),
            total: None,
            best: Some(best.get()),
        });
        Ok(f)
    };
    let runs = minimise(
        varied,
        &x0,
        &search,
        &watched,
        &|x| reader.describe(x),
        progress,
    )?;
    watch.check()?;
    Ok(runs)
}

/// A match from its search's `runs` ([`run`]'s second half): the best run's values rounded, the
/// start and the fitted formulation read in full, the Gauss–Newton uncertainty. `seconds` is
/// this half's time.
pub fn conclude(
    start: &Coating,
    target: &Target,
    gloss: &[GlossTarget],
    varied: &[Varied],
    settings: &Settings,
    runs: Vec<Run>,
) -> Result<Match> {
    let clock = Instant::now();
    check(start, target, gloss, varied, settings)?;
    if runs.is_empty() || runs.iter().any(|r| r.to.len() != varied.len()) {
        return Err(FormulationError::Invalid(format!(
            "a match concludes from at least one run, each ending at {} values",
            varied.len()
        )));
    }
    let reader = Reader::new(start, varied, target, gloss, settings);
    let x0 = start_values(start, varied)?;
    let mut evaluations: usize = runs.iter().map(|r| r.evaluations).sum();
    let best = best_run(&runs);
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
