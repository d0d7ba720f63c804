//! Which constituents drive which reading, as the page asks for it: a sensitivity run's request
//! parsed and checked by the formulation library's own checks (`coating_sensitivity::check`)
//! before its job starts, and the run under the job's watch, its result the library's
//! `Sensitivity::to_json` (the indices per output and input, and the summary in words). The
//! page draws the chart from it; the physics and the words are `gonio_formulation`'s.

use crate::compute::ReadingOptions;
use crate::error::ApiError;
use crate::matching::{VaryRequest, bad, varied};
use gonio_coating::system::Coating;
use gonio_formulation::appearance::Output;
use gonio_formulation::coating_sensitivity::{self, Method, Settings, Varied};
use gonio_formulation::watch::Watch;
use serde::Deserialize;
use serde_json::{Value, json};

/// `POST /api/sensitivity`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SensitivityRequest {
    pub formulation: Value,
    /// The constituents and their ranges.
    pub vary: Vec<VaryRequest>,
    /// The readings judged (`Output::parse` names: `gu60`, `L@45as15`, `flop`, `dE00` …);
    /// default every one of the standard (`Output::all`).
    #[serde(default)]
    pub outputs: Option<Vec<String>>,
    /// `morris` (default) or `sobol`.
    #[serde(default)]
    pub method: Option<String>,
    /// Morris trajectories or Sobol base points (defaults `Settings::MORRIS_TRAJECTORIES`,
    /// `Settings::SOBOL_BASE`).
    #[serde(default)]
    pub samples: Option<usize>,
    #[serde(default)]
    pub standard: Option<String>,
    /// Walks per geometry (default `Settings::WALKS`).
    #[serde(default)]
    pub walks: Option<usize>,
    /// Readings of the start with other seeds, whose spread is the noise (default 4).
    #[serde(default)]
    pub noise_repeats: Option<usize>,
    /// The summary's threshold (default [`THRESHOLD`]).
    #[serde(default)]
    pub threshold: Option<f64>,
    #[serde(default)]
    pub channel: Option<String>,
}

/// The summary's default threshold: an input matters for an output when its ST is at least
/// this, or its μ* this share of the largest (as `gonio coating sensitivity --threshold`).
pub const THRESHOLD: f64 = 0.1;

/// A checked sensitivity run.
pub struct SensitivityPlan {
    pub coating: Coating,
    pub varied: Vec<Varied>,
    pub outputs: Vec<Output>,
    pub method: Method,
    pub settings: Settings,
    pub threshold: f64,
}

impl SensitivityRequest {
    /// The checked plan for the formulation's `coating`; every error is the client's, with the
    /// library's message.
    pub fn plan(&self, coating: Coating) -> Result<SensitivityPlan, ApiError> {
        let options = ReadingOptions::parse(self.standard.as_deref(), None)?;
        let geometries = options.standard.geometries();
        let varied = varied(&self.vary, &coating)?;
        let outputs = match &self.outputs {
            Some(names) => names
                .iter()
                .map(|n| Output::parse(n).map_err(bad))
                .collect::<Result<Vec<_>, _>>()?,
            None => Output::all(geometries),
        };
        let method =
            Method::parse(self.method.as_deref().unwrap_or("morris"), self.samples).map_err(bad)?;
        let defaults = Settings::default();
        let settings = Settings {
            geometries: geometries.to_vec(),
            walks: self.walks.unwrap_or(defaults.walks),
            noise_repeats: self.noise_repeats.unwrap_or(defaults.noise_repeats),
            ..defaults
        };
        let threshold = self.threshold.unwrap_or(THRESHOLD);
        if !(threshold.is_finite() && threshold > 0.0 && threshold < 1.0) {
            return Err(bad(format!(
                "threshold {threshold}: a number between 0 and 1"
            )));
        }
        coating_sensitivity::check(&coating, &varied, &outputs, method, &settings).map_err(bad)?;
        Ok(SensitivityPlan {
            coating,
            varied,
            outputs,
            method,
            settings,
            threshold,
        })
    }
}

impl SensitivityPlan {
    /// Run under `watch`: `Sensitivity::to_json` (`method`, `readings`, `inputs`, `summary`,
    /// `outputs` with their indices per input) with `titles`, each output's words.
    pub fn run(&self, watch: Watch) -> Result<Value, ApiError> {
        let cancelled = || watch.cancel.is_some_and(|c| c.is_cancelled());
        let s = coating_sensitivity::run_watched(
            &self.coating,
            &self.varied,
            &self.outputs,
            self.method,
            &self.settings,
            watch,
        )
        .map_err(|e| {
            if cancelled() {
                ApiError::Cancelled
            } else {
                bad(e)
            }
        })?;
        let mut value = s.to_json(&self.varied, self.threshold);
        value["words"] = self.outputs.iter().map(|o| json!(o.words())).collect();
        Ok(value)
    }
}
