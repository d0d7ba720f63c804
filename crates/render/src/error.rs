//! The one error type of the render crate: every failure names the file (scene, mesh, map,
//! table, output image) and says what was wrong and how to fix it.

use std::path::PathBuf;

/// Errors of the render crate.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// Reading or writing a file failed at the operating-system level.
    #[error("{path}: {error}")]
    Io {
        path: PathBuf,
        error: std::io::Error,
    },
    /// A scene file (or a file it refers to) is malformed or asks for something impossible.
    #[error("{path}: {problem}")]
    Scene { path: PathBuf, problem: String },
    /// A BRDF could not be built or loaded (the error names the file).
    #[error(transparent)]
    Brdf(#[from] gonio_brdf::BrdfError),
    /// A coating's table could not be computed.
    #[error(transparent)]
    Coating(gonio_coating::CoatingError),
    /// An image could not be read or written.
    #[error("{path}: {problem}")]
    Image { path: PathBuf, problem: String },
    /// A render option is out of range.
    #[error("{0}")]
    Invalid(String),
    /// The caller raised its [`gonio_io::Cancel`] flag: the render (or the table it needed)
    /// stopped, and no partial picture is returned.
    #[error("cancelled")]
    Cancelled,
}

impl RenderError {
    /// A problem in the scene file `path`.
    pub fn scene(path: impl Into<PathBuf>, problem: impl Into<String>) -> Self {
        RenderError::Scene {
            path: path.into(),
            problem: problem.into(),
        }
    }

    /// A problem with the image file `path`.
    pub fn image(path: impl Into<PathBuf>, problem: impl std::fmt::Display) -> Self {
        RenderError::Image {
            path: path.into(),
            problem: problem.to_string(),
        }
    }
}

/// A coating's error, its cancellation the render's own ([`RenderError::Cancelled`]), so that a
/// caller looks for one variant whichever step was stopped.
impl From<gonio_coating::CoatingError> for RenderError {
    fn from(e: gonio_coating::CoatingError) -> Self {
        match e {
            gonio_coating::CoatingError::Cancelled => RenderError::Cancelled,
            e => RenderError::Coating(e),
        }
    }
}

/// Result with [`RenderError`].
pub type Result<T> = std::result::Result<T, RenderError>;
