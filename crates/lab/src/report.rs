//! The demo's report in the lab: `POST /api/report/demo` starts a job that runs the demo
//! ([`gonio_report::demo::run`], the call `gonio demo` makes) into a folder of the lab's own
//! temporary folder, and `GET /api/reports/NAME` serves the page it wrote. The job's `line` is
//! the demo's step; its result names the page. The demo has no cancellation of its own: a
//! report job, once started, runs to its end.

use crate::error::ApiError;
use crate::jobs::Job;
use crate::state::Lab;
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

/// The page of the report `name` (a name the lab gave, `r7`), or a 404.
pub fn page(lab: &Lab, name: &str) -> Result<String, ApiError> {
    let missing = || {
        ApiError::NotFound(format!(
            "no report '{name}' in this lab (POST /api/report/demo writes one: docs/lab.md)"
        ))
    };
    let folder = lab.report(name).ok_or_else(missing)?;
    std::fs::read_to_string(folder.join("report.html")).map_err(|_| missing())
}
