//! Running a peer's Python driver (embedded in the binary, written into the work folder and run
//! with `python3`, or `$GONIO_PYTHON`): exit status 77 means the peer's module is missing, and
//! the renderer is reported unavailable, or, under `GONIO_REQUIRE_ORACLES=1` (set by
//! `.ci/run`), the run fails.

use crate::error::{Error, Result};
use std::path::Path;
use std::process::Command;

/// Whether a missing peer is a failure (`GONIO_REQUIRE_ORACLES=1`).
pub fn oracles_required() -> bool {
    std::env::var("GONIO_REQUIRE_ORACLES").as_deref() == Ok("1")
}

/// Run `script` (its text, written as `name` into `dir`: not the name of the module it imports,
/// or Python would import the script itself) with `args`. `Ok(None)` when the
/// peer is missing and not required; `Ok(Some(()))` when it ran.
pub fn run(name: &str, script: &str, dir: &Path, args: &[&Path]) -> Result<Option<()>> {
    let path = dir.join(name);
    std::fs::write(&path, script).map_err(|e| Error::io(&path.display().to_string(), e))?;
    let python = std::env::var("GONIO_PYTHON").unwrap_or_else(|_| "python3".into());
    let missing = |why: String| {
        if oracles_required() {
            Err(Error::Peer(format!("GONIO_REQUIRE_ORACLES=1 but {why}")))
        } else {
            Ok(None)
        }
    };
    let out = match Command::new(&python).arg(&path).args(args).output() {
        Ok(out) => out,
        Err(e) => return missing(format!("{python} cannot run: {e}")),
    };
    match out.status.code() {
        Some(0) => Ok(Some(())),
        Some(77) => missing(format!("{name}'s Python module is not installed")),
        _ => Err(Error::Peer(format!(
            "{name} failed ({}): {}",
            out.status,
            String::from_utf8_lossy(&out.stderr).trim()
        ))),
    }
}

/// Read `count` little-endian f32 values from `path`.
pub fn read_f32(path: &Path, count: usize) -> Result<Vec<f32>> {
    let bytes = std::fs::read(path).map_err(|e| Error::io(&path.display().to_string(), e))?;
    if bytes.len() != 4 * count {
        return Err(Error::Peer(format!(
            "{}: {} bytes, expected {}",
            path.display(),
            bytes.len(),
            4 * count
        )));
    }
    Ok(bytes
        .chunks_exact(4)
        .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        .collect())
}
