//! What a match says, for every front end alike: its result as JSON (`gonio coating match
//! --json`, the Python package's `gonio.coating.match`).

use crate::matching::Match;
use gonio_instrument::GlossReport;
use gonio_instrument::multiangle_target::Target;

impl Match {
    /// The match against `target` as JSON: `objective` (`de00` or `spectral`), `constituents`
    /// [{name, lo, hi, start, fitted, sigma, at_bound}], `geometries` [{name, de00_start,
    /// de00_fitted, target {L, a, b}, start {L, a, b}, fitted {L, a, b}}] (CIELAB D65/10°),
    /// `mean_de00_start`, `mean_de00_fitted`, `objective_start`, `objective_fitted` (the
    /// objective's value), `rms_reflectance_start`, `rms_reflectance_fitted` (rms ΔR over the
    /// target's bands and geometries; null for a CIELAB target), `residual_sd`, `target_gloss`
    /// [{angle, gu}], `gloss_start`, `gloss_fitted` {gu20, gu60, gu85, haze, doi},
    /// `evaluations`, `seconds`.
    pub fn to_json(&self, target: &Target) -> serde_json::Value {
        let sigma = |i: usize| self.sigma.as_ref().map(|s| s[i]);
        let mean = |d: &[f64]| d.iter().sum::<f64>() / d.len() as f64;
        let lab = |l: gonio_color::Lab| serde_json::json!({"L": l.l, "a": l.a, "b": l.b});
        let reading_lab =
            |m: &gonio_instrument::multiangle::MultiangleReading, g| m.at(g).map(|r| lab(r.lab));
        let constituents: Vec<_> = self
            .varied
            .iter()
            .enumerate()
            .map(|(i, v)| {
                serde_json::json!({
                    "name": v.name, "lo": v.lo, "hi": v.hi,
                    "start": self.start.values[i], "fitted": self.fitted.values[i],
                    "sigma": sigma(i), "at_bound": self.at_bound(i),
                })
            })
            .collect();
        let geometries: Vec<_> = self
            .geometries
            .iter()
            .enumerate()
            .map(|(k, &g)| {
                serde_json::json!({
                    "name": g.to_string(),
                    "de00_start": self.start.de00[k], "de00_fitted": self.fitted.de00[k],
                    "target": target.colours.iter().find(|(h, _)| *h == g).map(|(_, l)| lab(*l)),
                    "start": reading_lab(&self.start.multiangle, g),
                    "fitted": reading_lab(&self.fitted.multiangle, g),
                })
            })
            .collect();
        let gloss = |g: &GlossReport| {
            serde_json::json!({"gu20": g.gu20, "gu60": g.gu60, "gu85": g.gu85, "haze": g.haze,
                               "doi": g.doi})
        };
        serde_json::json!({
            "objective": self.objective.to_string(),
            "constituents": constituents,
            "geometries": geometries,
            "mean_de00_start": mean(&self.start.de00),
            "mean_de00_fitted": mean(&self.fitted.de00),
            "objective_start": self.start.objective,
            "objective_fitted": self.fitted.objective,
            "rms_reflectance_start": self.start.rms_reflectance,
            "rms_reflectance_fitted": self.fitted.rms_reflectance,
            "residual_sd": self.residual_sd,
            "target_gloss": self
                .gloss_targets
                .iter()
                .map(|t| serde_json::json!({"angle": t.angle, "gu": t.gu}))
                .collect::<Vec<_>>(),
            "gloss_start": gloss(&self.start.gloss),
            "gloss_fitted": gloss(&self.fitted.gloss),
            "evaluations": self.evaluations,
            "seconds": self.seconds,
        })
    }
}
