//! The errors of the conformance suite.

use thiserror::Error;

/// What can go wrong.
#[derive(Debug, Error)]
pub enum Error {
    /// A file could not be read or written.
    #[error("{path}: {source}")]
    Io {
        path: String,
        source: std::io::Error,
    },
    /// A peer renderer failed (or is missing while required).
    #[error("{0}")]
    Peer(String),
    /// Something the suite builds is invalid.
    #[error("{0}")]
    Invalid(String),
    /// gonio's renderer failed.
    #[error(transparent)]
    Render(#[from] gonio_render::RenderError),
    /// Colorimetry failed.
    #[error(transparent)]
    Color(#[from] gonio_color::ColorError),
    /// JSON encoding failed.
    #[error(transparent)]
    Json(#[from] serde_json::Error),
}

impl Error {
    /// An I/O error on `path`.
    pub fn io(path: &str, source: std::io::Error) -> Error {
        Error::Io {
            path: path.into(),
            source,
        }
    }
}

/// The suite's result type.
pub type Result<T> = std::result::Result<T, Error>;
