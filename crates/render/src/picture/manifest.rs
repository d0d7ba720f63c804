//! A picture's manifest: what went in and what came out, so that anyone can reproduce the
//! picture and check that they did. JSON, written atomically, with the SHA-256 (FIPS 180-4,
//! the `sha2` crate) of every input and output file, gonio's version, the seed and the
//! settings.
//!
//! The fields (format [`MANIFEST_FORMAT`]):
//! - `format`: the manifest's format and version;
//! - `gonio_version`: the gonio crates' version (Cargo's `CARGO_PKG_VERSION`);
//! - `git_commit`: the commit gonio was built from when the build set the environment variable
//!   `GONIO_GIT_COMMIT` (read by `option_env!` at compile time: Cargo itself records no commit,
//!   and gonio has no build script), else `null`;
//! - `little_cms_version`: the Little CMS that made the display renderings (e.g. 2190 for 2.19);
//! - `seed`: the renderer's seed;
//! - `settings`: every setting, as the caller gives them (JSON);
//! - `inputs`, `outputs`: one object per file, `{ "path", "bytes", "sha256" }` (the hash in
//!   lower-case hexadecimal, as `sha256sum` prints it). A path inside the manifest's folder is
//!   written relative to that folder, others as given.

use crate::error::{RenderError, Result};
use serde_json::{Value, json};
use sha2::{Digest, Sha256};
use std::io::Read;
use std::path::Path;

/// The manifest's `format` field.
pub const MANIFEST_FORMAT: &str = "gonio picture manifest 1";

/// The SHA-256 of the file `path`, lower-case hexadecimal, and its size in bytes.
pub fn sha256_file(path: &Path) -> Result<(String, u64)> {
    let io = |e| RenderError::Io {
        path: path.to_path_buf(),
        error: e,
    };
    let mut file = std::fs::File::open(path).map_err(io)?;
    let mut hasher = Sha256::new();
    let mut buf = vec![0u8; 1 << 16];
    let mut bytes = 0u64;
    loop {
        let n = file.read(&mut buf).map_err(io)?;
        if n == 0 {
            break;
        }
        hasher.update(&buf[..n]);
        bytes += n as u64;
    }
    let hex = hasher
        .finalize()
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect();
    Ok((hex, bytes))
}

/// Write the manifest `path` (JSON, atomically) for a picture rendered with `seed` and
/// `settings` from the files `inputs` into the files `outputs`, and return it.
pub fn write_manifest(
    path: &Path,
    inputs: &[&Path],
    seed: u64,
    settings: &Value,
    outputs: &[&Path],
) -> Result<Value> {
    let folder = path.parent().unwrap_or(Path::new(""));
    let files = |paths: &[&Path]| -> Result<Vec<Value>> {
        paths
            .iter()
            .map(|p| {
                let (sha256, bytes) = sha256_file(p)?;
                let shown = match p.strip_prefix(folder) {
                    Ok(rel) if !folder.as_os_str().is_empty() => rel,
                    _ => p,
                };
                Ok(json!({
                    "path": shown.to_string_lossy(),
                    "bytes": bytes,
                    "sha256": sha256,
                }))
            })
            .collect()
    };
    let manifest = json!({
        "format": MANIFEST_FORMAT,
        "gonio_version": env!("CARGO_PKG_VERSION"),
        "git_commit": option_env!("GONIO_GIT_COMMIT"),
        "little_cms_version": lcms2::version(),
        "seed": seed,
        "settings": settings,
        "inputs": files(inputs)?,
        "outputs": files(outputs)?,
    });
    let text = serde_json::to_string_pretty(&manifest)
        .map_err(|e| RenderError::Invalid(format!("cannot write the manifest's JSON: {e}")))?;
    let io = |e| RenderError::Io {
        path: path.to_path_buf(),
        error: e,
    };
    gonio_io::write_atomic(
        path,
        |out| std::io::Write::write_all(out, format!("{text}\n").as_bytes()).map_err(io),
        io,
    )?;
    Ok(manifest)
}
