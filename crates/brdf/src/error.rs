//! The one error type of the brdf crate: every failure names the file (when there is one) and
//! says what was wrong and, where it can, how to fix it.

use std::path::PathBuf;

/// Errors of the brdf crate.
#[derive(Debug, thiserror::Error)]
pub enum BrdfError {
    /// Reading or writing a file failed at the operating-system level.
    #[error("{path}: {cause}")]
    Io {
        path: PathBuf,
        /// The operating system's error (in the message, not repeated as a source).
        cause: std::io::Error,
    },
    /// A file was read but its content is not what its format requires.
    #[error("{path}: {problem}")]
    Format { path: PathBuf, problem: String },
    /// An argument (resolution, channel list, model parameter, ...) is out of range.
    #[error("{0}")]
    Invalid(String),
}

impl BrdfError {
    /// An I/O error on `path`.
    pub fn io(path: impl Into<PathBuf>, cause: std::io::Error) -> Self {
        BrdfError::Io {
            path: path.into(),
            cause,
        }
    }

    /// A format error in `path`.
    pub fn format(path: impl Into<PathBuf>, problem: impl Into<String>) -> Self {
        BrdfError::Format {
            path: path.into(),
            problem: problem.into(),
        }
    }
}

/// Result with [`BrdfError`].
pub type Result<T> = std::result::Result<T, BrdfError>;
