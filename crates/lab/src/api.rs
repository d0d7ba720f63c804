//! The lab's HTTP interface: the page and its assets, and the JSON API the page uses and a script
//! can use too (docs/lab.md gives an example request for each endpoint). Handlers parse, check
//! and hand the work to [`crate::compute`] on a blocking thread; they hold no physics.
//!
//! Every computation runs under a [`gonio_io::Cancel`] flag that a newer request on the same
//! `channel` raises, and that is raised when the client leaves (the page aborts a request it no
//! longer needs), so that dragging a slider never queues work. A panic in a computation is a 500
//! with its message; the server keeps serving.

use crate::compute;
use crate::error::ApiError;
use crate::examples;
use crate::formulation;
use crate::jobs::Job;
use crate::matching::{ConstituentsRequest, MatchRequest};
use crate::sensitivity::SensitivityRequest;
use crate::state::{CancelOnDrop, Lab, Upload, UploadKind};
use axum::Router;
use axum::body::Bytes;
use axum::extract::rejection::BytesRejection;
use axum::extract::{DefaultBodyLimit, Path, Query, State};
use axum::http::{StatusCode, header};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use gonio_formulation::watch::Watch;
use gonio_io::Cancel;
use gonio_render::panel::live::Quality;
use serde::Deserialize;
use serde_json::{Value, json};
use std::sync::Arc;

type Shared = State<Arc<Lab>>;

/// The lab's routes over `lab`.
pub fn router(lab: Arc<Lab>) -> Router {
    let uploads = Router::new()
        .route("/api/upload/topography", post(upload_topography))
        .route("/api/upload/target", post(upload_target))
        .layer(DefaultBodyLimit::max(lab.limits.upload_bytes));
    Router::new()
        .route("/", get(|| async { crate::assets::page() }))
        .route("/lab.js", get(|| async { crate::assets::script() }))
        .route("/lab.css", get(|| async { crate::assets::style() }))
        .route("/api/health", get(health))
        .route(
            "/api/examples",
            get(|| async { axum::Json(examples::list()) }),
        )
        .route("/api/examples/{name}", get(example))
        .route(
            "/api/pigments",
            get(|| async { axum::Json(examples::pigments()) }),
        )
        .route(
            "/api/lightings",
            get(|| async { axum::Json(compute::lightings()) }),
        )
        .route("/api/formulation/from-toml", post(from_toml))
        .route("/api/formulation/to-toml", post(to_toml))
        .route("/api/readings", post(readings))
        .route("/api/picture", post(picture))
        .route("/api/export/{format}", post(export))
        .route("/api/constituents", post(constituents))
        .route("/api/match", post(start_match))
        .route("/api/sensitivity", post(start_sensitivity))
        .route("/api/report/demo", post(start_report))
        .route("/api/report/conformance", post(start_conformance))
        .route("/api/reports/{name}", get(report_page))
        .route("/api/jobs/{id}", get(job))
        .route("/api/jobs/{id}/cancel", post(cancel_job))
        .layer(DefaultBodyLimit::max(lab.limits.json_bytes))
        .merge(uploads)
        .fallback(|| async {
            ApiError::NotFound(
                "no such page or endpoint (the API is under /api: docs/lab.md)".into(),
            )
        })
        .with_state(lab)
}

/// What a JSON body too large for the lab is told.
const JSON_HINT: &str = "a formulation is a few kilobytes of JSON";

/// The body, or the client's error: too large (413, with the limit and `hint`, how to make it
/// fit), or unreadable.
fn body(
    body: Result<Bytes, BytesRejection>,
    limit: usize,
    what: &str,
    hint: &str,
) -> Result<Bytes, ApiError> {
    body.map_err(|e| {
        if e.status() == StatusCode::PAYLOAD_TOO_LARGE {
            ApiError::TooLarge(format!(
                "{what} is larger than the lab accepts ({:.0} MiB); {hint}",
                limit as f64 / (1 << 20) as f64,
            ))
        } else {
            ApiError::BadRequest(format!("{what}: {e}"))
        }
    })
}

/// The request's JSON as `T`, or a 400 naming what is wrong.
fn parse<T: serde::de::DeserializeOwned>(
    raw: Result<Bytes, BytesRejection>,
    lab: &Lab,
) -> Result<T, ApiError> {
    let bytes = body(raw, lab.limits.json_bytes, "the request", JSON_HINT)?;
    serde_json::from_slice(&bytes)
        .map_err(|e| ApiError::BadRequest(format!("the request's JSON: {e}")))
}

/// Run `work` on a blocking thread under `cancel`, raised if this handler is dropped (the client
/// left), once one of the lab's computation slots is free ([`Lab::slot`]): a computation
/// cancelled while it waits never starts. A panic in `work` is an internal error with its
/// message.
async fn run<T: Send + 'static>(
    lab: &Lab,
    cancel: Cancel,
    work: impl FnOnce(&Cancel) -> Result<T, ApiError> + Send + 'static,
) -> Result<T, ApiError> {
    let _stop_when_dropped = CancelOnDrop(cancel.clone());
    let _slot = lab.slot().await;
    if cancel.is_cancelled() {
        return Err(ApiError::Cancelled);
    }
    match tokio::task::spawn_blocking(move || work(&cancel)).await {
        Ok(result) => result,
        Err(e) if e.is_panic() => {
            let panic = e.into_panic();
            let message = panic
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| panic.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "a computation panicked".into());
            Err(ApiError::Internal(message))
        }
        Err(e) => Err(ApiError::Internal(e.to_string())),
    }
}

async fn health() -> axum::Json<Value> {
    axum::Json(json!({ "gonio": env!("CARGO_PKG_VERSION"), "lab": true }))
}

async fn example(Path(name): Path<String>) -> Result<axum::Json<Value>, ApiError> {
    let text = examples::text(&name).ok_or_else(|| {
        ApiError::NotFound(format!(
            "no example '{name}'; the examples are {}",
            examples::EXAMPLES.map(|(n, _)| n).join(", ")
        ))
    })?;
    Ok(axum::Json(json!({
        "name": name, "toml": text, "formulation": formulation::from_toml(text)?,
    })))
}

/// A request that carries only a formulation.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FormulationOnly {
    formulation: Value,
}

/// The coating of a formulation, its topography (if any) checked to be one of this lab's uploads.
fn coating_of(lab: &Lab, f: &Value) -> Result<(gonio_coating::system::Coating, String), ApiError> {
    if let Some(id) = formulation::map_name(f) {
        lab.uploaded(UploadKind::Topography, id)?;
    }
    formulation::coating(f, lab.uploads_folder())
}

/// A TOML description (an uploaded file's text) as a formulation, checked.
async fn from_toml(
    State(lab): Shared,
    raw: Result<Bytes, BytesRejection>,
) -> Result<axum::Json<Value>, ApiError> {
    let bytes = body(raw, lab.limits.json_bytes, "the description", JSON_HINT)?;
    let text = std::str::from_utf8(&bytes)
        .map_err(|_| ApiError::BadRequest("the description is not UTF-8 text".into()))?;
    let f = formulation::from_toml(text)?;
    coating_of(&lab, &f)?;
    Ok(axum::Json(json!({ "formulation": f })))
}

/// A formulation as the TOML text `gonio coating` reads, checked first.
async fn to_toml(
    State(lab): Shared,
    raw: Result<Bytes, BytesRejection>,
) -> Result<Response, ApiError> {
    let request: FormulationOnly = parse(raw, &lab)?;
    let (_, text) = coating_of(&lab, &request.formulation)?;
    let text = format!(
        "# A coating formulated in gonio lab. Read it with `gonio coating info FILE`.\n{}{text}",
        formulation::map_name(&request.formulation).map_or(String::new(), |m| format!(
            "# The top's map ({m}) is the topography uploaded to the lab: put the file beside this \
             one under that name.\n"
        )),
    );
    Ok((
        [
            (header::CONTENT_TYPE, "application/toml; charset=utf-8"),
            (
                header::CONTENT_DISPOSITION,
                "attachment; filename=\"formulation.toml\"",
            ),
        ],
        text,
    )
        .into_response())
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ReadingsRequest {
    formulation: Value,
    /// "E2194" (default) or "E2539".
    #[serde(default)]
    standard: Option<String>,
    /// Incidence of the in-plane BRDF, degrees (default 45).
    #[serde(default)]
    incidence_deg: Option<f64>,
    /// A target upload's id: the readings then hold ΔE00 against it.
    #[serde(default)]
    target: Option<String>,
    #[serde(default)]
    channel: Option<String>,
}

async fn readings(
    State(lab): Shared,
    raw: Result<Bytes, BytesRejection>,
) -> Result<axum::Json<Value>, ApiError> {
    let request: ReadingsRequest = parse(raw, &lab)?;
    let (coating, _) = coating_of(&lab, &request.formulation)?;
    let options =
        compute::ReadingOptions::parse(request.standard.as_deref(), request.incidence_deg)?;
    let target = request
        .target
        .map(|id| Ok::<_, ApiError>((lab.uploaded(UploadKind::Target, &id)?.name, id)))
        .transpose()?;
    let cancel = lab.begin(request.channel.as_deref());
    let value = run(&lab.clone(), cancel, move |cancel| {
        let target = target
            .map(|(name, id)| Ok::<_, ApiError>((name, lab.target(&id, &options, cancel)?)))
            .transpose()?;
        compute::readings(
            &coating,
            &options,
            target.as_ref().map(|(n, t)| (n.as_str(), t.as_ref())),
            cancel,
        )
    })
    .await?;
    Ok(axum::Json(value))
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PictureRequest {
    formulation: Value,
    /// A light setting's name (`GET /api/lightings`; default the first).
    #[serde(default)]
    lighting: Option<String>,
    /// "preview" (default) or "converged".
    #[serde(default)]
    quality: Option<String>,
    #[serde(default)]
    channel: Option<String>,
}

async fn picture(
    State(lab): Shared,
    raw: Result<Bytes, BytesRejection>,
) -> Result<Response, ApiError> {
    let request: PictureRequest = parse(raw, &lab)?;
    let (coating, text) = coating_of(&lab, &request.formulation)?;
    let options =
        compute::PictureOptions::parse(request.lighting.as_deref(), request.quality.as_deref())?;
    let cancel = lab.begin(request.channel.as_deref());
    let picture = run(&lab.clone(), cancel, move |cancel| {
        let table = lab.table(&coating, &text, options.quality, cancel)?;
        compute::picture(&table, &options, cancel)
    })
    .await?;
    let mut response = ([(header::CONTENT_TYPE, "image/png")], picture.png).into_response();
    for (name, value) in picture.figures {
        if let Ok(v) = value.parse() {
            response.headers_mut().insert(name, v);
        }
    }
    Ok(response)
}

async fn export(
    State(lab): Shared,
    Path(format): Path<String>,
    raw: Result<Bytes, BytesRejection>,
) -> Result<Response, ApiError> {
    let format = compute::ExportFormat::parse(&format)?;
    let request: FormulationOnly = parse(raw, &lab)?;
    let (coating, text) = coating_of(&lab, &request.formulation)?;
    let cancel = lab.begin(None);
    let (bytes, filename) = run(&lab.clone(), cancel, move |cancel| {
        compute::export(
            &lab.table(&coating, &text, Quality::Converged, cancel)?,
            format,
        )
    })
    .await?;
    Ok((
        [
            (header::CONTENT_TYPE, "application/octet-stream".to_string()),
            (
                header::CONTENT_DISPOSITION,
                format!("attachment; filename=\"{filename}\""),
            ),
        ],
        bytes,
    )
        .into_response())
}

/// `?name=` of an upload: the client's file name.
#[derive(Deserialize)]
struct UploadQuery {
    name: String,
}

/// Keep an uploaded file and read it with `read` (given its id and the upload); a file its
/// reader refuses is removed and the reader's message returned (which names the client's file:
/// [`crate::state::Upload::named`]).
async fn upload(
    lab: Arc<Lab>,
    kind: UploadKind,
    name: String,
    raw: Result<Bytes, BytesRejection>,
    read: impl FnOnce(&str, &Upload, &Cancel) -> Result<Value, ApiError> + Send + 'static,
) -> Result<axum::Json<Value>, ApiError> {
    let bytes = body(
        raw,
        lab.limits.upload_bytes,
        &format!("the upload {name}"),
        "crop or resample the file (gonio surface crop) before uploading it",
    )?;
    let (id, upload) = lab.upload(kind, &name, &bytes)?;
    let read = run(&lab, Cancel::new(), {
        let (id, upload) = (id.clone(), upload.clone());
        move |cancel| read(&id, &upload, cancel)
    })
    .await;
    if read.is_err() {
        let _ = std::fs::remove_file(&upload.path);
    }
    Ok(axum::Json(
        json!({ "id": id, "name": upload.name, "read": read? }),
    ))
}

async fn upload_topography(
    State(lab): Shared,
    Query(q): Query<UploadQuery>,
    raw: Result<Bytes, BytesRejection>,
) -> Result<axum::Json<Value>, ApiError> {
    upload(lab, UploadKind::Topography, q.name, raw, |_, upload, _| {
        compute::topography(upload)
    })
    .await
}

#[derive(Deserialize)]
struct TargetQuery {
    name: String,
    #[serde(default)]
    standard: Option<String>,
    #[serde(default)]
    incidence_deg: Option<f64>,
}

async fn upload_target(
    State(lab): Shared,
    Query(q): Query<TargetQuery>,
    raw: Result<Bytes, BytesRejection>,
) -> Result<axum::Json<Value>, ApiError> {
    let options = compute::ReadingOptions::parse(q.standard.as_deref(), q.incidence_deg)?;
    let kept = lab.clone();
    upload(
        lab,
        UploadKind::Target,
        q.name,
        raw,
        move |id, _, cancel| Ok(kept.target(id, &options, cancel)?.to_json()),
    )
    .await
}

/// The constituents a formulation (with the pigments chosen) offers to vary, and the readings a
/// sensitivity run can judge it by.
async fn constituents(
    State(lab): Shared,
    raw: Result<Bytes, BytesRejection>,
) -> Result<axum::Json<Value>, ApiError> {
    let request: ConstituentsRequest = parse(raw, &lab)?;
    let options = compute::ReadingOptions::parse(request.standard.as_deref(), None)?;
    let f = crate::matching::with_pigments(&request.formulation, request.pigments.as_ref())?;
    let (coating, _) = coating_of(&lab, &f)?;
    Ok(axum::Json(crate::matching::constituents(
        &f, &coating, &options,
    )?))
}

/// Start `work` as a job of `kind` on `channel` (default: the kind; a newer job there cancels
/// this one) and answer 202 with its id at once. `work` gets the job (for its progress lines)
/// and the watch that reports its readings and carries its cancellation.
fn start_job(
    lab: Arc<Lab>,
    kind: &'static str,
    channel: Option<&str>,
    work: impl FnOnce(&Arc<Job>, Watch) -> Result<Value, ApiError> + Send + 'static,
) -> (StatusCode, axum::Json<Value>) {
    let cancel = lab.begin(Some(channel.unwrap_or(kind)));
    let job = Arc::new(Job::new(kind, cancel.clone()));
    let id = lab.add_job(job.clone());
    let answer = job.to_json(&id);
    tokio::spawn(async move {
        let working = job.clone();
        let outcome = run(&lab.clone(), cancel, move |cancel| {
            let progress = |p| working.progress(p);
            let watch = Watch {
                cancel: Some(cancel),
                progress: Some(&progress),
            };
            work(&working, watch)
        })
        .await;
        job.end(outcome);
    });
    (StatusCode::ACCEPTED, axum::Json(answer))
}

/// Check a match (its target read, its constituents and bounds, its pigments) and start it.
async fn start_match(
    State(lab): Shared,
    raw: Result<Bytes, BytesRejection>,
) -> Result<(StatusCode, axum::Json<Value>), ApiError> {
    let request: MatchRequest = parse(raw, &lab)?;
    let plan = request.plan(|f| coating_of(&lab, f))?;
    lab.uploaded(UploadKind::Target, &request.target)?;
    let target = run(&lab.clone(), Cancel::new(), {
        let (lab, id, options) = (lab.clone(), request.target.clone(), plan.options.clone());
        move |cancel| lab.target(&id, &options, cancel)
    })
    .await?;
    plan.check(&target)?;
    Ok(start_job(
        lab,
        "match",
        request.channel.as_deref(),
        move |job, watch| {
            plan.run(&target, watch, &mut |stage| job.stage(stage), &mut |line| {
                job.line(line)
            })
        },
    ))
}

/// Check a sensitivity run (its constituents and ranges, outputs, method and sample) and start
/// it.
async fn start_sensitivity(
    State(lab): Shared,
    raw: Result<Bytes, BytesRejection>,
) -> Result<(StatusCode, axum::Json<Value>), ApiError> {
    let request: SensitivityRequest = parse(raw, &lab)?;
    let (coating, _) = coating_of(&lab, &request.formulation)?;
    let plan = request.plan(coating)?;
    Ok(start_job(
        lab,
        "sensitivity",
        request.channel.as_deref(),
        move |_, watch| plan.run(watch),
    ))
}

/// Start the demo's report as a job (crate::report).
async fn start_report(
    State(lab): Shared,
    raw: Result<Bytes, BytesRejection>,
) -> Result<(StatusCode, axum::Json<Value>), ApiError> {
    let request: crate::report::DemoRequest = parse(raw, &lab)?;
    let writer = lab.clone();
    Ok(start_job(lab, "report", None, move |job, _| {
        crate::report::run(&writer, job, &request)
    }))
}

/// Start the conformance suite's report as a job (crate::report); a bad request is refused
/// before the job starts.
async fn start_conformance(
    State(lab): Shared,
    raw: Result<Bytes, BytesRejection>,
) -> Result<(StatusCode, axum::Json<Value>), ApiError> {
    let request: crate::report::ConformanceRequest = parse(raw, &lab)?;
    let (name, folder) = lab.report_folder();
    let options = request.options(folder)?;
    Ok(start_job(lab, "report", None, move |_, _| {
        crate::report::run_conformance(&name, &options)
    }))
}

/// The page of a report the lab wrote.
async fn report_page(State(lab): Shared, Path(name): Path<String>) -> Result<Response, ApiError> {
    let html = crate::report::page(&lab, &name)?;
    Ok(([(header::CONTENT_TYPE, "text/html; charset=utf-8")], html).into_response())
}

/// How far a job is, and its result or error once it has ended.
async fn job(State(lab): Shared, Path(id): Path<String>) -> Result<axum::Json<Value>, ApiError> {
    Ok(axum::Json(lab.job(&id)?.to_json(&id)))
}

/// Stop a job (it ends as `cancelled` before its next reading).
async fn cancel_job(
    State(lab): Shared,
    Path(id): Path<String>,
) -> Result<axum::Json<Value>, ApiError> {
    let job = lab.job(&id)?;
    job.cancel.cancel();
    Ok(axum::Json(job.to_json(&id)))
}
