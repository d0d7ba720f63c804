//! The error type of the `scatter` crate: bad inputs to a scattering method (a map too small to
//! hold a facet, an impossible detector, an option out of range) and failures of the surface
//! crate it calls, each saying what was wrong and how to fix it.

use gonio_surface::SurfaceError;

/// Everything that can go wrong while computing scattering from a surface.
#[derive(Debug, thiserror::Error)]
pub enum ScatterError {
    /// An input or option is out of its valid range; the message says which and why.
    #[error("{0}")]
    Invalid(String),
    /// The surface crate failed (reading, normals, synthesis).
    #[error(transparent)]
    Surface(#[from] SurfaceError),
}

/// Result with [`ScatterError`].
pub type Result<T, E = ScatterError> = std::result::Result<T, E>;
