//! Writing output files: every file the `gonio` command writes goes through [`write_atomic`], so
//! that a failure never leaves half a file and outputs have ordinary permissions.

use anyhow::{Context, Result};
use std::fs::File;
use std::io::BufWriter;
use std::path::Path;

/// Write a file atomically ([`gonio_io::write_atomic`]: the old file or the complete new one,
/// never half a file); errors name the file.
pub fn write_atomic(
    path: &Path,
    body: impl FnOnce(&mut BufWriter<&mut File>) -> Result<()>,
) -> Result<()> {
    gonio_io::write_atomic(path, body, anyhow::Error::new)
        .with_context(|| format!("{}: cannot write", path.display()))
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
            anyhow::bail!("the encoder failed")
        })
        .unwrap_err();
        let text = format!("{err:#}");
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
        let err = write_atomic(&path, |w| Ok(w.write_all(b"x")?)).unwrap_err();
        assert!(format!("{err:#}").contains("out.png"), "{err:#}");
    }
}
