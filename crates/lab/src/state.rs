//! What the lab server keeps between requests: the uploaded files (in a temporary folder of its
//! own, removed when the server stops; named by ids the lab gives, never by the client), the
//! computation running on each channel (so that a newer request stops an older one), and the
//! limits it enforces.

use crate::compute::{self, ReadingOptions};
use crate::error::ApiError;
use crate::jobs::Job;
use gonio_coating::system::Coating;
use gonio_formulation::lab_target::LabTarget;
use gonio_io::Cancel;
use gonio_render::panel::live::{LiveTable, Quality};
use std::collections::{HashMap, VecDeque};
use std::path::PathBuf;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};

/// The limits on what a client may send.
#[derive(Clone, Copy, Debug)]
pub struct Limits {
    /// Largest JSON request body, bytes.
    pub json_bytes: usize,
    /// Largest uploaded file (a topography, a target), bytes.
    pub upload_bytes: usize,
    /// Uploads kept at once; the oldest is removed beyond.
    pub uploads_kept: usize,
    /// Computations running at once; more wait for a slot (and are cancelled while they wait
    /// if a newer request replaces them).
    pub computations: usize,
}

impl Default for Limits {
    /// 1 MiB of JSON (a formulation with measured spectra is a few kB), 64 MiB per upload (an
    /// optical profiler's 2048 × 2048 map in 32-bit floats is 16 MiB), 32 uploads, 4
    /// computations at once (the page's readings and picture of B and of a pinned A; each
    /// computation uses every core, so more at once only share them).
    fn default() -> Limits {
        Limits {
            json_bytes: 1 << 20,
            upload_bytes: 64 << 20,
            uploads_kept: 32,
            computations: 4,
        }
    }
}

/// What an uploaded file is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UploadKind {
    Topography,
    Target,
}

/// One uploaded file.
#[derive(Clone, Debug)]
pub struct Upload {
    pub kind: UploadKind,
    /// The name the client gave (shown, never used as a path).
    pub name: String,
    pub path: PathBuf,
}

impl Upload {
    /// `error` as the client should read it: a reader's message names the lab's copy of the
    /// file (`/tmp/gonio-lab-…/u3.sdf`), which the client never saw; it is named by the client's
    /// name instead.
    pub fn named(&self, error: ApiError) -> ApiError {
        match error {
            ApiError::BadRequest(m) => {
                ApiError::BadRequest(m.replace(&self.path.display().to_string(), &self.name))
            }
            other => other,
        }
    }
}

/// The server's state, shared by every request.
pub struct Lab {
    pub limits: Limits,
    folder: tempfile::TempDir,
    next: AtomicU64,
    uploads: Mutex<VecDeque<(String, Upload)>>,
    channels: Mutex<HashMap<String, Cancel>>,
    /// Targets read, by upload id, standard and incidence (reading a measured BRDF imports it:
    /// seconds; a formulation's readings compare with it at every change).
    targets: Mutex<HashMap<String, Arc<LabTarget>>>,
    /// The last pictures' tables, by formulation and table level (a change of light, a refined
    /// picture after a preview of the same table, an export after the converged picture reuse
    /// them), newest last.
    tables: Mutex<VecDeque<(String, LiveTable)>>,
    /// The computations that may run at once ([`Lab::slot`]).
    slots: tokio::sync::Semaphore,
    /// The jobs (matches, sensitivity runs) by id, oldest first ([`Lab::add_job`]).
    jobs: Mutex<VecDeque<(String, Arc<Job>)>>,
}

impl Lab {
    /// A lab with its own temporary folder for uploads.
    pub fn new(limits: Limits) -> std::io::Result<Lab> {
        Ok(Lab {
            limits,
            folder: tempfile::Builder::new().prefix("gonio-lab-").tempdir()?,
            next: AtomicU64::new(1),
            uploads: Mutex::new(VecDeque::new()),
            channels: Mutex::new(HashMap::new()),
            targets: Mutex::new(HashMap::new()),
            tables: Mutex::new(VecDeque::new()),
            slots: tokio::sync::Semaphore::new(limits.computations),
            jobs: Mutex::new(VecDeque::new()),
        })
    }

    /// The folder holding the uploads (a formulation's `top.roughness.map` is read from here).
    pub fn uploads_folder(&self) -> &std::path::Path {
        self.folder.path()
    }

    /// Keep `bytes` as an upload of `kind` named `name` by the client: written into the lab's
    /// folder under a new id (`u7.sdf`: a number and the client's extension, letters and digits
    /// only, which the readers use to tell the format), returned with the upload.
    pub fn upload(
        &self,
        kind: UploadKind,
        name: &str,
        bytes: &[u8],
    ) -> Result<(String, Upload), ApiError> {
        let ext: String = std::path::Path::new(name)
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase())
            .unwrap_or_default()
            .chars()
            .filter(|c| c.is_ascii_alphanumeric())
            .take(8)
            .collect();
        if ext.is_empty() {
            return Err(ApiError::BadRequest(format!(
                "{name}: the file's name needs its extension (.sdf, .x3p, .astm, .csv ...): the \
                 readers tell the format by it"
            )));
        }
        let id = format!("u{}.{ext}", self.next.fetch_add(1, Ordering::Relaxed));
        let path = self.folder.path().join(&id);
        std::fs::write(&path, bytes)
            .map_err(|e| ApiError::Internal(format!("cannot keep the upload {name}: {e}")))?;
        let upload = Upload {
            kind,
            name: name.chars().take(200).collect(),
            path,
        };
        let mut uploads = self.uploads.lock().unwrap_or_else(|p| p.into_inner());
        uploads.push_back((id.clone(), upload.clone()));
        while uploads.len() > self.limits.uploads_kept {
            if let Some((_, old)) = uploads.pop_front() {
                let _ = std::fs::remove_file(old.path);
            }
        }
        Ok((id, upload))
    }

    /// The upload `id` of `kind`, or a 404 saying what the lab has.
    pub fn uploaded(&self, kind: UploadKind, id: &str) -> Result<Upload, ApiError> {
        let uploads = self.uploads.lock().unwrap_or_else(|p| p.into_inner());
        uploads
            .iter()
            .find(|(i, u)| i == id && u.kind == kind)
            .map(|(_, u)| u.clone())
            .ok_or_else(|| {
                ApiError::NotFound(format!(
                    "no {} upload '{id}' in this lab (upload the file first; the lab keeps the \
                     last {} uploads while it runs)",
                    match kind {
                        UploadKind::Topography => "topography",
                        UploadKind::Target => "target",
                    },
                    self.limits.uploads_kept
                ))
            })
    }

    /// The target upload `id` read at `options`' standard and incidence: kept from an earlier
    /// request, or read now (under `cancel`) and kept.
    pub fn target(
        &self,
        id: &str,
        options: &ReadingOptions,
        cancel: &Cancel,
    ) -> Result<Arc<LabTarget>, ApiError> {
        let key = format!("{id} {} {}", options.standard.name(), options.incidence_deg);
        if let Some(t) = self
            .targets
            .lock()
            .unwrap_or_else(|p| p.into_inner())
            .get(&key)
        {
            return Ok(t.clone());
        }
        let upload = self.uploaded(UploadKind::Target, id)?;
        let target = Arc::new(compute::target(&upload, options, cancel)?);
        let mut targets = self.targets.lock().unwrap_or_else(|p| p.into_inner());
        if targets.len() >= 64 {
            targets.clear();
        }
        targets.insert(key, target.clone());
        Ok(target)
    }

    /// The pictures' table of `coating` (described by `text`) at `quality`: kept from an earlier
    /// request, or computed now (under `cancel`) and kept (the last 8).
    pub fn table(
        &self,
        coating: &Coating,
        text: &str,
        quality: Quality,
        cancel: &Cancel,
    ) -> Result<LiveTable, ApiError> {
        let key = format!(
            "{:?} {} {}\n{text}",
            quality.resolution(coating),
            quality.walks(),
            quality.bands().len()
        );
        let mut tables = self.tables.lock().unwrap_or_else(|p| p.into_inner());
        if let Some(k) = tables.iter().position(|(t, _)| *t == key) {
            let kept = tables.remove(k).expect("the position found");
            tables.push_back(kept.clone());
            return Ok(kept.1);
        }
        drop(tables);
        let table = compute::table(coating, quality, cancel)?;
        let mut tables = self.tables.lock().unwrap_or_else(|p| p.into_inner());
        tables.push_back((key, table.clone()));
        while tables.len() > 8 {
            tables.pop_front();
        }
        Ok(table)
    }

    /// Wait for a computation slot (see [`Limits::computations`]); the slot is free again when the
    /// permit is dropped.
    pub async fn slot(&self) -> tokio::sync::SemaphorePermit<'_> {
        self.slots
            .acquire()
            .await
            .expect("the lab never closes its semaphore")
    }

    /// Start a computation on `channel`: the one running there is cancelled. Without a channel
    /// the computation stops only when its client leaves.
    pub fn begin(&self, channel: Option<&str>) -> Cancel {
        let cancel = Cancel::new();
        if let Some(channel) = channel {
            let mut channels = self.channels.lock().unwrap_or_else(|p| p.into_inner());
            // Finished computations leave cancelled flags behind (see [`CancelOnDrop`]): keep
            // the map to the ones running, however many channel names clients invent.
            if channels.len() > 256 {
                channels.retain(|_, c| !c.is_cancelled());
            }
            if let Some(old) = channels.insert(channel.chars().take(64).collect(), cancel.clone()) {
                old.cancel();
            }
        }
        cancel
    }
}

impl Lab {
    /// Jobs kept: the oldest that have ended are forgotten beyond this many.
    pub const JOBS_KEPT: usize = 16;

    /// Keep `job` under a new id (`j3`), which is returned. Beyond [`Lab::JOBS_KEPT`] jobs the
    /// oldest that have ended are forgotten (running ones are kept: their channels cancel them).
    pub fn add_job(&self, job: Arc<Job>) -> String {
        let id = format!("j{}", self.next.fetch_add(1, Ordering::Relaxed));
        let mut jobs = self.jobs.lock().unwrap_or_else(|p| p.into_inner());
        jobs.push_back((id.clone(), job));
        while jobs.len() > Lab::JOBS_KEPT {
            match jobs.iter().position(|(_, j)| j.ended()) {
                Some(k) => {
                    jobs.remove(k);
                }
                None => break,
            }
        }
        id
    }

    /// A new folder for a report, inside the lab's temporary folder, and its name (`r7`: the
    /// lab's, never the client's).
    pub fn report_folder(&self) -> (String, PathBuf) {
        let name = format!("r{}", self.next.fetch_add(1, Ordering::Relaxed));
        let folder = self.folder.path().join(&name);
        (name, folder)
    }

    /// The folder of the report `name`, if `name` is one the lab gives (`r` and digits).
    pub fn report(&self, name: &str) -> Option<PathBuf> {
        let digits = name.strip_prefix('r')?;
        (!digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()))
            .then(|| self.folder.path().join(name))
    }

    /// The job `id`, or a 404.
    pub fn job(&self, id: &str) -> Result<Arc<Job>, ApiError> {
        let jobs = self.jobs.lock().unwrap_or_else(|p| p.into_inner());
        jobs.iter()
            .find(|(i, _)| i == id)
            .map(|(_, j)| j.clone())
            .ok_or_else(|| {
                ApiError::NotFound(format!(
                    "no job '{id}' in this lab (the lab keeps the last {} jobs while it runs)",
                    Lab::JOBS_KEPT
                ))
            })
    }
}

/// Cancels its flag when dropped: a handler holds one while its computation runs, so that a
/// client closing the connection (the page aborting a stale request) stops the computation.
pub struct CancelOnDrop(pub Cancel);

impl Drop for CancelOnDrop {
    fn drop(&mut self) {
        self.0.cancel();
    }
}
