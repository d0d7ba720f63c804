//! The way back from a target to a formulation, as the page asks for it: the constituents a
//! formulation offers to vary ([`constituents`]), a match's request parsed and checked by the
//! formulation library's own checks before its job starts ([`MatchRequest::plan`]), and the
//! match run under the job's watch with its result as JSON ([`MatchPlan::run`]): the library's
//! `Match::to_json` and the fitted formulation (`fitted_description::with_values`), or, when
//! gonio selects the pigments, `selection::run_watched` with `Selection::to_json` and
//! `Selection::fitted_description`. The physics and the report are `gonio_formulation`'s; this
//! module only parses and adapts.

use crate::compute::ReadingOptions;
use crate::error::ApiError;
use crate::formulation;
use gonio_coating::pigment_library::LibraryPigment;
use gonio_coating::system::{Coating, default_bands};
use gonio_formulation::appearance::Output;
use gonio_formulation::coating_sensitivity::Varied;
use gonio_formulation::lab_target::LabTarget;
use gonio_formulation::matching::{self, Objective, Settings};
use gonio_formulation::selection::{self, Stage};
use gonio_formulation::watch::Watch;
use gonio_instrument::coating_study::Constituent;
use serde::Deserialize;
use serde_json::{Value, json};

/// A library error as the client's (400).
pub(crate) fn bad(e: impl std::fmt::Display) -> ApiError {
    ApiError::BadRequest(e.to_string())
}

/// One constituent to vary: its name (`tilt`, `concentration:NAME`, as `gonio coating match
/// --vary` reads it) and its bounds, each defaulting to `Varied::default_bounds`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VaryRequest {
    pub name: String,
    #[serde(default)]
    pub lo: Option<f64>,
    #[serde(default)]
    pub hi: Option<f64>,
}

/// The constituents of `vary` for `coating`, checked (`Varied::check`: bounds increasing, each
/// a valid coating); the errors name the constituent.
pub fn varied(vary: &[VaryRequest], coating: &Coating) -> Result<Vec<Varied>, ApiError> {
    vary.iter()
        .map(|v| {
            let constituent = Constituent::parse(&v.name).map_err(bad)?;
            let (lo, hi) = match (v.lo, v.hi) {
                (Some(lo), Some(hi)) => (lo, hi),
                (lo, hi) => {
                    let (dlo, dhi) = Varied::default_bounds(&constituent, coating)
                        .map_err(|e| bad(format!("{}: {e}", v.name)))?;
                    (lo.unwrap_or(dlo), hi.unwrap_or(dhi))
                }
            };
            let varied = Varied {
                name: v.name.clone(),
                constituent,
                lo,
                hi,
            };
            varied.check(coating, &default_bands()).map_err(bad)?;
            Ok(varied)
        })
        .collect()
}

/// Which pigments the match uses.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields, tag = "from", rename_all = "kebab-case")]
pub enum Pigments {
    /// The formulation's own (the default).
    Formulation,
    /// These pigments of gonio's library, in place of the formulation's
    /// ([`formulation::with_library_pigments`]).
    Library { names: Vec<String> },
    /// Up to `max` pigments of gonio's library selected and added to the formulation's own
    /// (`selection::run`): from `candidates` (default: the library less the formulation's
    /// own), the full match on the screen's best `finalists` (default
    /// `selection::FINALISTS`).
    Select {
        max: usize,
        #[serde(default)]
        candidates: Option<Vec<String>>,
        #[serde(default)]
        finalists: Option<usize>,
    },
}

/// `formulation` with the pigments of `pigments` (unchanged for the formulation's own).
pub fn with_pigments(formulation: &Value, pigments: Option<&Pigments>) -> Result<Value, ApiError> {
    match pigments {
        None | Some(Pigments::Formulation) | Some(Pigments::Select { .. }) => {
            Ok(formulation.clone())
        }
        Some(Pigments::Library { names }) => formulation::with_library_pigments(formulation, names),
    }
}

/// `POST /api/constituents`: the formulation (with the pigments chosen), and what it offers to
/// vary and to read.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConstituentsRequest {
    pub formulation: Value,
    #[serde(default)]
    pub pigments: Option<Pigments>,
    #[serde(default)]
    pub standard: Option<String>,
}

/// `{formulation, constituents: [{name, label, value, lo, hi}], outputs: [{name, words}]}`: the
/// formulation with the pigments chosen, every constituent it has with its value and default
/// bounds (`Varied::available`), and the readings a sensitivity run can judge it by at the
/// standard (`Output::all`).
pub fn constituents(
    formulation: &Value,
    coating: &Coating,
    options: &ReadingOptions,
) -> Result<Value, ApiError> {
    let available = Varied::available(coating).map_err(bad)?;
    let list = available
        .iter()
        .map(|v| {
            Ok(json!({
                "name": v.name, "label": v.constituent.label(),
                "value": v.constituent.value(coating).map_err(bad)?, "lo": v.lo, "hi": v.hi,
            }))
        })
        .collect::<Result<Vec<_>, ApiError>>()?;
    let outputs: Vec<Value> = Output::all(options.standard.geometries())
        .iter()
        .map(|o| json!({ "name": o.name(), "words": o.words() }))
        .collect();
    Ok(json!({ "formulation": formulation, "constituents": list, "outputs": outputs }))
}

/// `POST /api/match`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MatchRequest {
    /// The start formulation.
    pub formulation: Value,
    /// The target: an upload's id (`POST /api/upload/target`).
    pub target: String,
    /// The geometries matched: `E2194` (default) or `E2539`; the target's that the standard has.
    #[serde(default)]
    pub standard: Option<String>,
    /// The constituents to vary.
    pub vary: Vec<VaryRequest>,
    /// The pigments: `{"from": "formulation"}` (default), `{"from": "library", "names": […]}`
    /// or `{"from": "select", "max": N, "candidates": […], "finalists": K}`.
    #[serde(default)]
    pub pigments: Option<Pigments>,
    /// `de00` (default) or `spectral` (a target with reflectance factors).
    #[serde(default)]
    pub objective: Option<String>,
    /// Walks per geometry (default `matching::Settings`' ).
    #[serde(default)]
    pub walks: Option<usize>,
    /// Nelder–Mead runs before the final one (default `Settings::STARTS`).
    #[serde(default)]
    pub starts: Option<usize>,
    /// Iterations per run at most (default `Settings::ITERATIONS`).
    #[serde(default)]
    pub iterations: Option<u64>,
    #[serde(default)]
    pub channel: Option<String>,
}

/// A checked match, ready to run once its target is read.
pub struct MatchPlan {
    pub coating: Coating,
    /// The start formulation's TOML (the fitted one is this with the fitted values).
    pub text: String,
    pub varied: Vec<Varied>,
    pub settings: Settings,
    pub options: ReadingOptions,
    /// When gonio selects the pigments: what from.
    pub selection: Option<SelectPlan>,
}

/// A selection's candidates (checked: `selection::candidates`), pigments at most and finalists.
pub struct SelectPlan {
    pub candidates: Vec<&'static LibraryPigment>,
    pub max: usize,
    pub finalists: usize,
}

/// How many of the screen's best combinations a selection's JSON lists.
const SHOWN: usize = 10;

impl MatchRequest {
    /// The start coating (`coating_of` of the formulation with its pigments) and the checked
    /// plan; every error is the client's, with the library's message.
    pub fn plan(
        &self,
        coating_of: impl Fn(&Value) -> Result<(Coating, String), ApiError>,
    ) -> Result<MatchPlan, ApiError> {
        let options = ReadingOptions::parse(self.standard.as_deref(), None)?;
        let f = with_pigments(&self.formulation, self.pigments.as_ref())?;
        let (coating, text) = coating_of(&f)?;
        let varied = varied(&self.vary, &coating)?;
        let defaults = Settings::default();
        let settings = Settings {
            walks: self.walks.unwrap_or(defaults.walks),
            starts: self.starts.unwrap_or(defaults.starts),
            iterations: self.iterations.unwrap_or(defaults.iterations),
            objective: match self.objective.as_deref() {
                None => Objective::default(),
                Some(name) => name.parse().map_err(bad)?,
            },
            ..defaults
        };
        let selection = match &self.pigments {
            Some(Pigments::Select {
                max,
                candidates,
                finalists,
            }) => {
                let candidates =
                    selection::candidates(&coating, candidates.as_deref()).map_err(bad)?;
                let finalists = finalists.unwrap_or(selection::FINALISTS);
                selection::check(candidates.len(), *max, finalists).map_err(bad)?;
                Some(SelectPlan {
                    candidates,
                    max: *max,
                    finalists,
                })
            }
            _ => None,
        };
        Ok(MatchPlan {
            coating,
            text,
            varied,
            settings,
            options,
            selection,
        })
    }
}

impl MatchPlan {
    /// Check the plan against the read `target` (`matching::check`: e.g. a spectral objective
    /// needs a target with reflectance factors).
    /// A selection's: `selection::check_run`.
    pub fn check(&self, target: &LabTarget) -> Result<(), ApiError> {
        match &self.selection {
            None => matching::check(
                &self.coating,
                &target.target,
                &[],
                &self.varied,
                &self.settings,
            ),
            Some(s) => selection::check_run(
                &self.coating,
                &target.target,
                &[],
                &self.varied,
                &s.candidates,
                s.max,
                s.finalists,
                &self.settings,
            ),
        }
        .map_err(bad)
    }

    /// Run the match against `target` under `watch`, with the library's progress lines to
    /// `line` (and a selection's steps to `stage`): `Match::to_json` (docs/formulation.md:
    /// `constituents` with `sigma`, `geometries` with `de00_start` and `de00_fitted`, the
    /// means …), for a selection `Selection::to_json` (the chosen finalist's match and
    /// `selection`: the pigments chosen, the combinations screened, the best `SHOWN` tried,
    /// the finalists), with `formulation` and `toml`, the fitted formulation.
    pub fn run(
        &self,
        target: &LabTarget,
        watch: Watch,
        stage: &mut dyn FnMut(Stage),
        line: &mut dyn FnMut(&str),
    ) -> Result<Value, ApiError> {
        let cancelled = || watch.cancel.is_some_and(|c| c.is_cancelled());
        let failed = |e| {
            if cancelled() {
                ApiError::Cancelled
            } else {
                bad(e)
            }
        };
        if let Some(s) = &self.selection {
            let selected = selection::run_watched(
                &self.coating,
                &target.target,
                &[],
                &self.varied,
                &s.candidates,
                s.max,
                s.finalists,
                &self.settings,
                watch,
                stage,
                line,
            )
            .map_err(failed)?;
            let toml = selected.fitted_description(&self.text).map_err(bad)?;
            let value = selected.to_json(&target.target, SHOWN);
            return self.with_formulation(value, &toml);
        }
        let m = matching::run_watched(
            &self.coating,
            &target.target,
            &[],
            &self.varied,
            &self.settings,
            watch,
            line,
        )
        .map_err(failed)?;
        let toml = gonio_formulation::fitted_description::with_values(
            &self.text,
            &self.varied,
            &m.fitted.values,
        )
        .map_err(bad)?;
        self.with_formulation(m.to_json(&target.target), &toml)
    }

    /// A result's JSON with the fitted formulation (`formulation`, `toml`) and `standard`.
    fn with_formulation(&self, mut value: Value, toml: &str) -> Result<Value, ApiError> {
        value["formulation"] = formulation::from_toml(toml)?;
        value["toml"] = json!(toml);
        value["standard"] = json!(self.options.standard.name());
        Ok(value)
    }
}
