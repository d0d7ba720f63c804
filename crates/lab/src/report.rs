//! The reports in the lab: `POST /api/report/demo` starts a job that runs the demo
//! ([`gonio_report::demo::run`], the call `gonio demo` makes) and `POST
//! /api/report/conformance` one that runs the conformance suite
//! ([`gonio_report::conformance::run`], the call `gonio conformance` makes), each into a folder
//! of the lab's own temporary folder, and `GET /api/reports/NAME` serves the page it wrote. The
//! demo job's `line` is the demo's step; a job's result names the page. Neither has a
//! cancellation of its own: a report job, once started, runs to its end.

use crate::error::ApiError;
use crate::jobs::Job;
use crate::state::Lab;
use gonio_conformance::{Options, Renderer};
use gonio_io::Progress;
use gonio_report::demo::{DemoPlan, DemoProgress};
use serde::Deserialize;
use serde_json::{Value, json};
use std::sync::Arc;

/// `POST /api/report/demo`'s body.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DemoRequest {
    /// The quick demo (seconds; the default) or the full one (minutes).
    #[serde(default = "quick_by_default")]
    pub quick: bool,
}

fn quick_by_default() -> bool {
    true
}

/// Run the demo for `job` into the lab's new report folder; the result names the page
/// (`{"report": "/api/reports/r7", "sections": [{"title", "seconds"}], "seconds"}`).
pub fn run(lab: &Lab, job: &Arc<Job>, request: &DemoRequest) -> Result<Value, ApiError> {
    let (name, folder) = lab.report_folder();
    let heard = job.clone();
    let progress = DemoProgress {
        steps: Progress::new(move |r| {
            heard.line(&format!("step {} of {}: {}", r.done + 1, r.total, r.stage))
        }),
        work: Progress::silent(),
    };
    let plan = DemoPlan {
        output: folder,
        quick: request.quick,
    };
    let outcome = gonio_report::demo::run(&plan, &progress)
        .map_err(|e| ApiError::Internal(format!("the demo: {e}")))?;
    Ok(json!({
        "report": format!("/api/reports/{name}"),
        "sections": outcome.sections.iter().map(|(title, seconds)| {
            json!({"title": title, "seconds": seconds})
        }).collect::<Vec<_>>(),
        "seconds": outcome.seconds,
    }))
}

/// `POST /api/report/conformance`'s body.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConformanceRequest {
    /// The renderers by name (`gonio`, `mitsuba`, `radiance`); all three when absent.
    pub renderers: Option<Vec<String>>,
    /// Samples per pixel of gonio and Mitsuba, 1 to 65536; 64 when absent.
    pub spp: Option<u32>,
}

impl ConformanceRequest {
    /// The suite's options into `folder`, or a bad request naming the unknown renderer or the
    /// samples out of range.
    pub fn options(&self, folder: std::path::PathBuf) -> Result<Options, ApiError> {
        let renderers = match &self.renderers {
            None => Renderer::ALL.to_vec(),
            Some(names) => names
                .iter()
                .map(|n| {
                    Renderer::from_name(n).ok_or_else(|| {
                        ApiError::BadRequest(format!(
                            "renderers: unknown renderer '{n}' (gonio, mitsuba or radiance)"
                        ))
                    })
                })
                .collect::<Result<_, _>>()?,
        };
        let spp = self.spp.unwrap_or(64);
        if !(1..=65536).contains(&spp) {
            return Err(ApiError::BadRequest(format!(
                "spp: {spp} samples per pixel is not between 1 and 65536"
            )));
        }
        Ok(Options {
            renderers,
            spp,
            dir: folder,
        })
    }
}

/// Run the conformance suite into the lab's report folder `(name, folder)` with `options`; the
/// result names the page and gives each scene's verdict per renderer
/// (`{"report": "/api/reports/r7", "passed": true, "scenes": [{"scene", "runs": [{"renderer",
/// "route", "verdict"}]}]}`).
pub fn run_conformance(name: &str, options: &Options) -> Result<Value, ApiError> {
    let (results, _) = gonio_report::conformance::run(options)
        .map_err(|e| ApiError::Internal(format!("the conformance suite: {e}")))?;
    Ok(json!({
        "report": format!("/api/reports/{name}"),
        "passed": results.passed(),
        "scenes": results.scenes.iter().map(|s| json!({
            "scene": s.scene.id,
            "runs": s.runs.iter().map(|r| json!({
                "renderer": r.renderer,
                "route": r.route,
                "verdict": r.verdict,
            })).collect::<Vec<_>>(),
        })).collect::<Vec<_>>(),
    }))
}

/// The page of the report `name` (a name the lab gave, `r7`), or a 404.
pub fn page(lab: &Lab, name: &str) -> Result<String, ApiError> {
    let missing = || {
        ApiError::NotFound(format!(
            "no report '{name}' in this lab (POST /api/report/demo or /api/report/conformance \
             writes one: docs/lab.md)"
        ))
    };
    let folder = lab.report(name).ok_or_else(missing)?;
    std::fs::read_to_string(folder.join("report.html")).map_err(|_| missing())
}
