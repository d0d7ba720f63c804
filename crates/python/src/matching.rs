//! Matching for Python: `gonio.coating.match`, with or without the selection of pigments from
//! gonio's library. The match and the selection are `gonio-formulation`'s ([`matching::run`],
//! [`selection`]); the selection's finalists can be searched anywhere
//! ([`selection_search`], a Dask task) and concluded here ([`SelectionPlan::conclude`]), with
//! the result of the serial selection.

use crate::coating::Coating;
use crate::error::{Result, invalid};
use gonio_coating::pigment_library;
use gonio_coating::system::{self, default_bands};
use gonio_formulation::coating_sensitivity::Varied;
use gonio_formulation::match_objective::ObjectiveChoice;
use gonio_formulation::matching::{self, Run, Settings};
use gonio_formulation::screen::Screened;
use gonio_formulation::selection::{self, Screen};
use gonio_formulation::target::{GlossTarget, at_geometries, read_target};
use gonio_instrument::multiangle_target::Target;
use gonio_io::Cancel;
use pyo3::prelude::*;
use std::path::PathBuf;

/// A run of a search as Python carries it: (from, to, objective, evaluations).
type RunTuple = (Vec<f64>, Vec<f64>, f64, usize);

/// What a match reads from its arguments.
struct Inputs {
    start: system::Coating,
    text: String,
    target: Target,
    gloss: Vec<GlossTarget>,
    varied: Vec<Varied>,
    settings: Settings,
}

/// The inputs of a match: `start`, the file `target` (.csv, .astm, .gbrdf) or the CSV text
/// `target_csv` at `standard`'s geometries, `vary` (NAME=LO:HI,...; may be empty when pigments
/// are selected), `target_gloss` (ANGLE=GU,...), `gloss_weight`, `walks`, `starts` and
/// `objective` (auto, de00, spectral).
#[allow(clippy::too_many_arguments)]
fn inputs(
    start: &Coating,
    target: Option<PathBuf>,
    target_csv: Option<String>,
    vary: &str,
    standard: &str,
    target_gloss: Option<String>,
    gloss_weight: f64,
    walks: usize,
    starts: usize,
    objective: &str,
) -> Result<Inputs> {
    let varied = Varied::resolve_list(vary, None, &start.coating, &default_bands())?;
    let geometries = gonio_instrument::multiangle::standard(standard)?;
    let gloss = match target_gloss {
        Some(list) => GlossTarget::parse_list(&list)?,
        None => Vec::new(),
    };
    let choice: ObjectiveChoice = objective.parse()?;
    let target = match (target, target_csv) {
        (Some(path), None) => read_target(&path, geometries)?,
        (None, Some(csv)) => at_geometries(Target::parse_csv(&csv, "target")?, geometries)?,
        _ => return Err(invalid("give a target file or a target's CSV text")),
    };
    let settings = Settings {
        walks,
        gloss_weight,
        starts,
        objective: choice.resolve(&target, gloss.len()),
        ..Settings::default()
    };
    Ok(Inputs {
        start: start.coating.clone(),
        text: start.toml.clone(),
        target,
        gloss,
        varied,
        settings,
    })
}

/// The fitted coating as Python's `Coating`.
fn fitted(coating: system::Coating, text: String) -> Coating {
    Coating {
        coating,
        source: "fitted".into(),
        toml: text,
    }
}

/// Match `start` to a target (the arguments as [`inputs`] reads them). Returns the result as
/// JSON text (`gonio coating match --json` without the file names), the fitted formulation's
/// TOML (the start's text with the fitted values) and the fitted Coating.
#[pyfunction]
#[pyo3(signature = (start, target, target_csv, vary, standard, target_gloss, gloss_weight, walks, starts, objective))]
#[allow(clippy::too_many_arguments)]
pub fn match_coating(
    py: Python<'_>,
    start: &Coating,
    target: Option<PathBuf>,
    target_csv: Option<String>,
    vary: &str,
    standard: &str,
    target_gloss: Option<String>,
    gloss_weight: f64,
    walks: usize,
    starts: usize,
    objective: &str,
) -> Result<(String, String, Coating)> {
    let i = inputs(
        start,
        target,
        target_csv,
        vary,
        standard,
        target_gloss,
        gloss_weight,
        walks,
        starts,
        objective,
    )?;
    let (json, text, coating) = py.detach(move || -> Result<_> {
        let m = matching::run(
            &i.start,
            &i.target,
            &i.gloss,
            &i.varied,
            &i.settings,
            &mut |_| {},
        )?;
        let text = gonio_formulation::fitted_description::with_values(
            &i.text,
            &i.varied,
            &m.fitted.values,
        )?;
        Ok((m.to_json(&i.target).to_string(), text, m.coating))
    })?;
    Ok((json, text.clone(), fitted(coating, text)))
}

/// A selection under way: the inputs and the screen; its finalists are searched by
/// [`SelectionPlan::search`] (or [`selection_search`] elsewhere) and concluded by
/// [`SelectionPlan::conclude`].
#[pyclass(module = "gonio._gonio", frozen)]
pub struct SelectionPlan {
    inputs: Inputs,
    screen: Screen,
    finalists: usize,
}

/// Screen the selection of up to `select` of `candidates` (library names; None: the whole
/// library less the start's pigments) for `start` (the other arguments as [`match_coating`]'s),
/// keeping `finalists` for the full match (seconds; the GIL released).
#[pyfunction]
#[pyo3(signature = (start, target, target_csv, vary, standard, target_gloss, gloss_weight, walks, starts, objective, select, candidates, finalists))]
#[allow(clippy::too_many_arguments)]
pub fn selection_plan(
    py: Python<'_>,
    start: &Coating,
    target: Option<PathBuf>,
    target_csv: Option<String>,
    vary: &str,
    standard: &str,
    target_gloss: Option<String>,
    gloss_weight: f64,
    walks: usize,
    starts: usize,
    objective: &str,
    select: usize,
    candidates: Option<Vec<String>>,
    finalists: usize,
) -> Result<SelectionPlan> {
    let i = inputs(
        start,
        target,
        target_csv,
        vary,
        standard,
        target_gloss,
        gloss_weight,
        walks,
        starts,
        objective,
    )?;
    if finalists == 0 {
        return Err(invalid("a selection needs at least 1 finalist (0 given)"));
    }
    let screen = py.detach(|| -> Result<Screen> {
        let list = selection::candidates(&i.start, candidates.as_deref())?;
        Ok(selection::screen(
            &i.start,
            &i.target,
            &list,
            select,
            &i.settings,
            &Cancel::default(),
        )?)
    })?;
    Ok(SelectionPlan {
        inputs: i,
        screen,
        finalists,
    })
}

/// The runs of a finalist's search ([`selection::finalist_start`], then
/// [`matching::search`]), as Python carries them.
fn finalist_runs(i: &Inputs, screened: &Screened) -> Result<Vec<RunTuple>> {
    let (coating, varied) = selection::finalist_start(&i.start, &i.varied, screened)?;
    let runs = matching::search(
        &coating,
        &i.target,
        &i.gloss,
        &varied,
        &i.settings,
        &mut |_| {},
    )?;
    Ok(runs
        .into_iter()
        .map(|r| (r.from, r.to, r.objective, r.evaluations))
        .collect())
}

#[pymethods]
impl SelectionPlan {
    /// The finalists: (pigments, screened concentrations, screen score), best first.
    fn finalists(&self) -> Vec<(Vec<String>, Vec<f64>, f64)> {
        self.screen
            .tried
            .iter()
            .take(self.finalists)
            .map(|s| (s.pigments.clone(), s.concentrations.clone(), s.score))
            .collect()
    }

    /// The search runs of finalist `k` (the GIL released).
    fn search(&self, py: Python<'_>, k: usize) -> Result<Vec<RunTuple>> {
        let screened = self
            .screen
            .tried
            .get(k)
            .filter(|_| k < self.finalists)
            .ok_or_else(|| invalid(format!("no finalist {k}")))?;
        py.detach(|| finalist_runs(&self.inputs, screened))
    }

    /// The selection from every finalist's `runs` (in the finalists' order): its JSON text
    /// (`gonio coating match --select --json` without the file names, the best `shown` of the
    /// tried combinations), the fitted TOML and the fitted Coating.
    fn conclude(
        &self,
        py: Python<'_>,
        runs: Vec<Vec<RunTuple>>,
        shown: usize,
    ) -> Result<(String, String, Coating)> {
        let count = self.finalists.min(self.screen.tried.len());
        if runs.len() != count {
            return Err(invalid(format!(
                "{} finalists' runs for {count} finalists",
                runs.len()
            )));
        }
        let i = &self.inputs;
        let (json, text, coating) = py.detach(|| -> Result<_> {
            let done = self.screen.tried[..count]
                .iter()
                .zip(runs)
                .map(|(screened, runs)| {
                    let runs = runs
                        .into_iter()
                        .map(|(from, to, objective, evaluations)| Run {
                            from,
                            to,
                            objective,
                            evaluations,
                        })
                        .collect();
                    Ok(selection::conclude_finalist(
                        &i.start,
                        &i.target,
                        &i.gloss,
                        &i.varied,
                        screened,
                        &i.settings,
                        runs,
                    )?)
                })
                .collect::<Result<Vec<_>>>()?;
            let s = selection::conclude(self.screen.clone(), done, 0.0)?;
            let text = s.fitted_description(&i.text)?;
            Ok((
                s.to_json(&i.target, shown).to_string(),
                text,
                s.chosen().result.coating.clone(),
            ))
        })?;
        Ok((json, text.clone(), fitted(coating, text)))
    }
}

/// The search runs of the finalist `pigments` at `concentrations` (as [`SelectionPlan::finalists`]
/// gives them) for the match the other arguments describe (as [`match_coating`]'s): a Dask task,
/// equal to [`SelectionPlan::search`] of that finalist.
#[pyfunction]
#[pyo3(signature = (start, target, target_csv, vary, standard, target_gloss, gloss_weight, walks, starts, objective, pigments, concentrations))]
#[allow(clippy::too_many_arguments)]
pub fn selection_search(
    py: Python<'_>,
    start: &Coating,
    target: Option<PathBuf>,
    target_csv: Option<String>,
    vary: &str,
    standard: &str,
    target_gloss: Option<String>,
    gloss_weight: f64,
    walks: usize,
    starts: usize,
    objective: &str,
    pigments: Vec<String>,
    concentrations: Vec<f64>,
) -> Result<Vec<RunTuple>> {
    let i = inputs(
        start,
        target,
        target_csv,
        vary,
        standard,
        target_gloss,
        gloss_weight,
        walks,
        starts,
        objective,
    )?;
    for p in &pigments {
        pigment_library::find(p)?;
    }
    let screened = Screened {
        pigments,
        concentrations,
        score: f64::NAN,
    };
    py.detach(|| finalist_runs(&i, &screened))
}
