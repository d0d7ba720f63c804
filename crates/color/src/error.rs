//! The error type of gonio-color: every failure names the file (when there is one), the line and
//! what was wrong.

use std::path::PathBuf;

/// Result with [`ColorError`].
pub type Result<T, E = ColorError> = std::result::Result<T, E>;

/// What went wrong in gonio-color.
#[derive(Debug, thiserror::Error)]
pub enum ColorError {
    /// A spectrum file could not be opened or read.
    #[error("{}: cannot read the file: {cause}", file.display())]
    Io {
        /// The file.
        file: PathBuf,
        /// The operating system's error (in the message, so not repeated as a source).
        cause: std::io::Error,
    },
    /// A line of a spectrum file is malformed.
    #[error("{}, line {line}: {problem}", file.display())]
    Parse {
        /// The file.
        file: PathBuf,
        /// 1-based line number.
        line: usize,
        /// What is wrong and how to fix it.
        problem: String,
    },
    /// Samples that do not form a spectrum (lengths differ, wavelengths not increasing, ...).
    #[error("invalid spectrum: {0}")]
    InvalidSpectrum(String),
    /// A spectral table whose row length does not match the number of wavelengths.
    #[error("spectral table: {0}")]
    TableShape(String),
}
