//! Writing, copying and reading the report's files: every file goes through [`write_atomic`]
//! (gonio_io's: the old file or the complete new one, never half a file, ordinary
//! permissions), and every I/O error names its file.

use crate::{ReportError, Result};
use std::fs::File;
use std::io::BufWriter;
use std::path::Path;

/// The error of `path` failing with `error`.
pub fn io_error(path: &Path, error: std::io::Error) -> ReportError {
    ReportError::Io {
        path: path.display().to_string(),
        error,
    }
}

/// Write `path` atomically ([`gonio_io::write_atomic`]); `body` writes the contents. Errors
/// name the file.
pub fn write_atomic(
    path: &Path,
    body: impl FnOnce(&mut BufWriter<&mut File>) -> std::io::Result<()>,
) -> Result<()> {
    gonio_io::write_atomic(path, body, |e| e).map_err(|e| io_error(path, e))
}

/// Write `bytes` to `path` atomically.
pub fn write_bytes(path: &Path, bytes: &[u8]) -> Result<()> {
    write_atomic(path, |w| std::io::Write::write_all(w, bytes))
}

/// Copy the file `from` to `to` (beside a report, so that the commands it shows run there).
pub fn copy(from: &Path, to: &Path) -> Result<()> {
    std::fs::copy(from, to).map_err(|e| io_error(from, e))?;
    Ok(())
}

/// The text of the file `path`.
pub fn read_text(path: &Path) -> Result<String> {
    std::fs::read_to_string(path).map_err(|e| io_error(path, e))
}

/// Create the folder `dir` and its parents, if missing.
pub fn create_dir(dir: &Path) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| io_error(dir, e))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Write;

    #[test]
    fn failed_write_keeps_the_old_file_and_leaves_no_temporary_file() {
        let dir = tempfile::tempdir().unwrap();
        let csv = dir.path().join("peaks.csv");
        std::fs::write(&csv, "old,file\n").unwrap();
        let err = write_atomic(&csv, |w| {
            w.write_all(&[b'x'; 200_000])?;
            Err(std::io::Error::other("the encoder failed"))
        })
        .unwrap_err();
        let text = err.to_string();
        assert!(
            text.contains("peaks.csv") && text.contains("the encoder failed"),
            "{text}"
        );
        assert_eq!(std::fs::read_to_string(&csv).unwrap(), "old,file\n");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[test]
    fn a_missing_directory_is_an_error_naming_the_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("no/such/out.png");
        let err = write_bytes(&path, b"x").unwrap_err();
        assert!(err.to_string().contains("out.png"), "{err}");
    }
}
