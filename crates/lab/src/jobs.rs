//! Long computations (a match, a sensitivity run: seconds to minutes) as jobs that the page
//! follows by polling: `POST /api/match` or `/api/sensitivity` checks the request, starts the
//! job and answers its id at once; `GET /api/jobs/ID` says how far it is (readings made, of how
//! many when known, the best objective so far, the library's last progress line, and for a
//! selection the step it is at) and, once it
//! has ended, its result or its error; `POST /api/jobs/ID/cancel` stops it. A job runs under a
//! [`Cancel`] flag as the readings do: a newer job on the same channel (`match`, `sensitivity`)
//! cancels the older one, and it takes one of the lab's computation slots while it runs.

use crate::error::ApiError;
use gonio_formulation::selection::Stage;
use gonio_formulation::watch::Progress;
use gonio_io::Cancel;
use serde_json::{Value, json};
use std::sync::Mutex;
use std::time::Instant;

/// One job.
pub struct Job {
    /// What it computes: `match` or `sensitivity`.
    pub kind: &'static str,
    pub cancel: Cancel,
    started: Instant,
    status: Mutex<Status>,
}

#[derive(Default)]
struct Status {
    progress: Option<Progress>,
    line: String,
    /// A selection's step, as JSON.
    stage: Option<Value>,
    /// The result, or the error; `None` while it runs.
    outcome: Option<Result<Value, ApiError>>,
    seconds: Option<f64>,
}

impl Job {
    pub fn new(kind: &'static str, cancel: Cancel) -> Job {
        Job {
            kind,
            cancel,
            started: Instant::now(),
            status: Mutex::new(Status::default()),
        }
    }

    fn status(&self) -> std::sync::MutexGuard<'_, Status> {
        self.status.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// The computation's progress after a reading.
    pub fn progress(&self, progress: Progress) {
        let mut s = self.status();
        // Readings finish out of order on many threads: keep the furthest.
        if s.progress.is_none_or(|p| p.readings <= progress.readings) {
            s.progress = Some(progress);
        }
    }

    /// A selection's next step: its progress starts anew (a finalist's match counts its own
    /// readings).
    pub fn stage(&self, stage: Stage) {
        let mut s = self.status();
        s.progress = None;
        s.stage = Some(match stage {
            Stage::Screen { combinations } => {
                json!({"step": "screen", "combinations": combinations})
            }
            Stage::Finalist {
                index,
                count,
                pigments,
            } => {
                json!({"step": "finalist", "number": index + 1, "of": count, "pigments": pigments})
            }
        });
    }

    /// A progress line of the library's (`run 2 of 5 (from a Sobol point): objective …`).
    pub fn line(&self, line: &str) {
        self.status().line = line.trim().to_string();
    }

    /// The job has ended with `outcome`.
    pub fn end(&self, outcome: Result<Value, ApiError>) {
        let mut s = self.status();
        s.seconds = Some(self.started.elapsed().as_secs_f64());
        s.outcome = Some(outcome);
    }

    /// Whether the job has ended.
    pub fn ended(&self) -> bool {
        self.status().outcome.is_some()
    }

    /// The job as `GET /api/jobs/ID` answers it: `id`, `kind`, `state` (`running`, `done`,
    /// `failed`, `cancelled`), `readings`, `total` (null when not known), `best` (the lowest
    /// objective so far: a match's mean ΔE00; null for a sensitivity run), `line`, `stage`
    /// (a selection's step: `{step: "screen", combinations}`, whose `readings` count the
    /// combinations screened and `best` is the lowest screen score, or `{step: "finalist",
    /// number, of, pigments}`, whose `readings` are that finalist's match's; null otherwise),
    /// `seconds`
    /// (since it started, or its duration once ended), and `result` (done) or `error` and
    /// `status` (failed: the HTTP status the error would have had).
    pub fn to_json(&self, id: &str) -> Value {
        let s = self.status();
        let p = s.progress;
        let mut v = json!({
            "id": id, "kind": self.kind,
            "readings": p.map_or(0, |p| p.readings),
            "total": p.and_then(|p| p.total),
            "best": p.and_then(|p| p.best).filter(|b| b.is_finite()),
            "line": s.line,
            "stage": s.stage,
            "seconds": s.seconds.unwrap_or_else(|| self.started.elapsed().as_secs_f64()),
        });
        v["state"] = json!(match &s.outcome {
            None if self.cancel.is_cancelled() => "cancelling",
            None => "running",
            Some(Ok(_)) => "done",
            Some(Err(ApiError::Cancelled)) => "cancelled",
            Some(Err(_)) => "failed",
        });
        match &s.outcome {
            Some(Ok(result)) => v["result"] = result.clone(),
            Some(Err(ApiError::Cancelled)) => {
                v["error"] = json!("cancelled: by its Cancel or by a newer job of the same kind");
                v["status"] = json!(ApiError::Cancelled.status().as_u16());
            }
            Some(Err(e)) => {
                v["error"] = json!(e.to_string());
                v["status"] = json!(e.status().as_u16());
            }
            None => {}
        }
        v
    }
}
